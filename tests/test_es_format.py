"""The compiled ES formatter (csrc/cont/es_format.cpp) against the Python one
(washer.auto.es_format.python_es_one, Python's correctly rounded float formatting) on
random doubles: every bit pattern (subnormals, NaN with either sign, the infinities,
3-digit exponents), magnitudes spread over the exponents AUTO's files see, integers and
half-integers (exact ties at the last digit: both round them to even), and the doubles
next to the decimal halves of each format's last digit (where a rounding shortcut would
go wrong)."""
from __future__ import annotations

import numpy as np
import pytest

from washer.auto import es_format
from washer.auto.es_format import es_text, python_es_one, python_es_text

pytestmark = pytest.mark.skipif(not es_format.COMPILED, reason="washer._cont not built")

#: AUTO's formats: b- and s-file values ES19.10E3, d-file values ES14.5, the b-file
#: header's ES11.4 and ES12.4; and a few others the formatter takes.
FORMATS = [(19, 10, True), (14, 5, False), (11, 4, False), (12, 4, False), (9, 0, False),
           (24, 15, True), (26, 17, False)]


def _doubles(n: int, seed: int) -> np.ndarray:
    """n doubles of the kinds in the module's docstring, shuffled."""
    rng = np.random.default_rng(seed)
    q = n // 5
    bits = rng.integers(0, 2**64, size=q, dtype=np.uint64, endpoint=False).view(np.float64)
    spread = rng.standard_normal(q) * 10.0 ** rng.integers(-40, 40, q)
    ints = rng.integers(-10**16, 10**16, q).astype(float) / rng.choice([1.0, 2.0, 4.0], q)
    # the decimal halves of the 11th and the 6th significant digit and their neighbours
    mant = rng.integers(10**11, 10**12, q) * 10 + 5
    exps = rng.integers(-30, 30, q)
    halves = np.array([float(f"{m}e{e}") for m, e in zip(mant.tolist(), exps.tolist())])
    halves[::2] = [float(f"{m // 10**5}e{e}") for m, e in zip(mant[::2].tolist(), exps[::2].tolist())]
    near = halves * rng.choice([-1.0, 1.0], q)
    step = rng.integers(-2, 3, q)
    near = np.nextafter(near, np.where(step > 0, np.inf, -np.inf))
    near = np.where(step == 0, halves, near)
    rest = n - 4 * q
    tiny = rng.integers(1, 2**52, rest).view(np.float64) * rng.choice([-1.0, 1.0], rest)
    edge = np.array([0.0, -0.0, np.nan, -np.nan, np.inf, -np.inf, 5e-324, -5e-324,
                     2.2250738585072014e-308, 2.225073858507201e-308, 1.7976931348623157e308,
                     1e22, 1e23, 1e-22, 1e-23, 9.99999999995, 9.999999999949999, 0.5, 2.5,
                     1e100, 1e-100, 9.9999999999e99, 9.99999999995e99, 9.99995e-100])
    out = np.concatenate([bits, spread, ints, near, tiny, edge])
    rng.shuffle(out)
    return out


def _check(values: np.ndarray, width: int, digits: int, exp3: bool) -> None:
    """The compiled text of the values equals the Python formatter's, value by value
    (the first difference named)."""
    ours = es_text(values, width, digits, exp3)
    ref = "".join(python_es_one(x, width, digits, exp3) for x in values.tolist())
    if ours != ref:
        for x in values.tolist():
            a, b = es_text([x], width, digits, exp3), python_es_one(x, width, digits, exp3)
            assert a == b, f"{x!r} ES{width}.{digits}{'E3' if exp3 else ''}: {a!r} != {b!r}"
        assert ours == ref


@pytest.mark.parametrize("width,digits,exp3", FORMATS)
def test_compiled_formatter_is_the_python_one(width, digits, exp3):
    _check(_doubles(50_000, seed=width * 100 + digits), width, digits, exp3)


@pytest.mark.slow
@pytest.mark.parametrize("width,digits,exp3", FORMATS[:2])
def test_compiled_formatter_is_the_python_one_on_millions(width, digits, exp3):
    for seed in range(4):
        _check(_doubles(1_000_000, seed=1000 + seed), width, digits, exp3)


def test_lines_and_rows():
    """per_line and indent lay rows out as the s-file's blocks (each row on lines of its
    own, 7 values a line after 4 blanks); a flat sequence is one row; nested lists and
    numpy rows give the same text; no values give no text."""
    rng = np.random.default_rng(5)
    for k, m in [(1, 1), (3, 7), (2, 8), (4, 15), (1, 0), (0, 3)]:
        M = rng.standard_normal((k, m))
        for args in ((19, 10, True, 7, 4), (14, 5, False, 2, 0), (19, 10, True, None, 0)):
            ref = python_es_text(M, *args)
            assert es_text(M, *args) == ref
            assert es_text(M.tolist(), *args) == ref
    assert es_text([], 19, 10, True, 7, 4) == ""
    assert es_text([1.0, 2.0, 3.0], 14, 5, per_line=2, indent=1) == \
        "    1.00000E+00   2.00000E+00\n    3.00000E+00"
    assert es_text(np.arange(3.0).reshape(1, 3), 11, 4) == es_text([0.0, 1.0, 2.0], 11, 4)
    # a value wider than its field is never cut
    assert es_text([-1.5e-300], 6, 2) == "-1.50-300"
    assert es_text([np.float32(0.5), 3], 11, 4) == " 5.0000E-01 3.0000E+00"


def test_gfortran_texts():
    """gfortran's texts: the sign of -0.0, NaN of either sign, the infinities, 3-digit
    exponents with and without Ee, rounding up into the next decade."""
    assert es_text([-0.0], 19, 10, True) == " -0.0000000000E+000"
    assert es_text([-np.nan, np.inf, -np.inf], 11, 4) == "        NaN   Infinity  -Infinity"
    assert es_text([1e-100], 19, 10, True) == "  1.0000000000E-100"
    assert es_text([-1.7976931348623157e308], 12, 4) == " -1.7977+308"
    assert es_text([9.99999999999], 19, 10, True) == "  1.0000000000E+001"
    assert es_text([9.999999e99], 14, 5) == "   1.00000+100"
    assert es_text([5e-324], 14, 5) == "   4.94066-324"


def test_point_text_is_the_python_one():
    """A point's b-line, screen line and eigenvalue or Floquet block in one compiled call
    equal the Python layout (python_point_text): rows of 0..12 values, real and complex
    spectra and multipliers (their moduli by libm's hypot as Python's complex abs),
    NaN and 3-digit exponents, negative and wide integers, names of 1..4 characters and a
    heading with non-ASCII column titles."""
    from washer.auto.es_format import point_text, python_point_text
    rng = np.random.default_rng(11)
    pool = _doubles(5_000, seed=17)
    heads = ["", "\n  BR    PT  TY  LAB  ω    \n", "=" * 47 + "\n\n  BR    PT  TY  LAB \n"]
    for trial in range(400):
        n = int(rng.integers(0, 13))
        values = rng.choice(pool, n)
        ints = [int(x) for x in rng.integers(-10**5, 10**6, 4)]
        if trial % 3 == 0:
            ints = [1, -int(rng.integers(1, 9999)), 0, 0]
        name = ["", "EP", "HB", "UZ4"][trial % 4]
        k = int(rng.integers(0, 6))
        if trial % 5 == 0:
            eigen = None
        elif trial % 2:
            eigen = (ints[0], abs(ints[1]), rng.choice(pool, k))
        else:
            z = np.empty(k, dtype=complex)
            z.real, z.imag = rng.choice(pool, k), rng.choice(pool, k)
            eigen = (ints[0], abs(ints[1]), z)
        if eigen is not None and trial % 7 < 3:
            # PVSPBV's Floquet block instead (cycles): the stable count given
            eigen = eigen + (int(rng.integers(0, 13)),)
        head = heads[trial % 3]
        for vals in (values, values.tolist(), None):
            got = point_text(*ints, name, vals, head, eigen)
            assert got == python_point_text(*ints, name, vals, head, eigen), (ints, name, vals)
    d = point_text(1, 2, 0, 0, "", None, "", (1, 2, np.array([1.0, -0.6 + 0.8j, 3e-5]), 2))[1]
    assert d.splitlines() == [
        "   1     2         Multipliers:     Stable:   2",
        "   1     2         Multiplier  1    1.00000E+00   0.00000E+00  Abs. Val.   1.00000E+00",
        "   1     2         Multiplier  2   -6.00000E-01   8.00000E-01  Abs. Val.   1.00000E+00",
        "   1     2         Multiplier  3    3.00000E-05   0.00000E+00  Abs. Val.   3.00000E-05"]
    b, d = point_text(1, -2, 0, 0, "", [0.5], "", (1, 2, [-1.0 + 2j, -1.0 - 2j]))
    assert b == "   1    -2   0    0  5.0000000000E-001\n"
    assert d.splitlines() == ["   1    -2        0   5.00000E-01", "",
                              "   1     2         Eigenvalues  :   Stable:   2",
                              "   1     2         Eigenvalue  1:  -1.00000E+00   2.00000E+00",
                              "   1     2         Eigenvalue  2:  -1.00000E+00  -2.00000E+00"]


def test_floquet_block_modulus_of_nan_and_inf_parts():
    """A multiplier with a NaN part has modulus NaN, one with an infinite part inf, in the
    compiled block (hypot) and in the Python layout alike; CPython's complex abs leaves
    errno as it found it on the NaN path, so the layout decides NaN before calling it."""
    from washer.auto.es_format import _modulus, point_text, python_point_text
    nan, inf = float("nan"), float("inf")
    mults = np.array([complex(nan, 5.04545e15), complex(inf, nan), complex(1.5e308, 1.5e308)])
    eigen = (1, 2, mults, 0)
    assert point_text(1, 2, 0, 0, "", None, "", eigen) == \
        python_point_text(1, 2, 0, 0, "", None, "", eigen)
    assert np.isnan(_modulus(complex(nan, 5.04545e15)))
    assert _modulus(complex(inf, nan)) == inf
    assert _modulus(complex(1.5e308, 1.5e308)) == inf
