"""Fortran's ESw.d and ESw.dE3 edit descriptors as gfortran writes them: the numbers of
AUTO-07p's b-, s- and d-files. One formatter: the compiled one of the engine's module
(csrc/cont/es_format.cpp, `cont_format_es`), with `python_es_text` below as its reference
and the fallback where that module cannot be imported (the tests hold the two to the
same text on millions of doubles).

    es_text([1.5, -0.0], 19, 10, exp3=True)   '   1.5000000000E+000  -0.0000000000E+000'
    es_text([1e-120], 12, 4)                  ' 1.0000-120'   (ES12.4: no 'E' beyond 99)

Text only, no numerics: the digits are the correctly rounded ones (ties to even), as C's
printf and Python's float formatting give them.
"""
from __future__ import annotations

import math
import threading

import numpy as np

try:
    from washer import build_stamp
    from washer._cont import ffi as _ffi, lib as _lib
    build_stamp.check("washer._cont", _ffi, _lib)
    if not hasattr(_lib, "cont_format_es"):
        raise ImportError("washer._cont has no cont_format_es")
except ImportError:              # no compiled engine (or a stale one): the Python formatter
    _ffi = _lib = None

#: Whether the compiled formatter is in use.
COMPILED = _lib is not None


def _special(x: float, width: int) -> str | None:
    """gfortran's text for NaN (either sign) and the infinities, right-justified; None
    for finite x."""
    if math.isnan(x):
        return "NaN".rjust(width)
    if math.isinf(x):
        return ("Infinity" if x > 0 else "-Infinity").rjust(width)
    return None


def python_es_one(x: float, width: int, digits: int, exp3: bool) -> str:
    """One value as ESw.d (exp3 False: 'E' and a 2-digit exponent; beyond 99 three digits
    without the 'E', '-1.7976+308') or ESw.dE3 (exp3 True: 'E' and 3 digits),
    right-justified in `width` (never cut)."""
    x = float(x)
    special = _special(x, width)
    if special:
        return special
    mant, exp = f"{x:.{digits}e}".split("e")     # Python rounds once, correctly
    exp = int(exp)
    sign = "+" if exp >= 0 else "-"
    if exp3:
        text = f"{mant}E{sign}{abs(exp):03d}"
    elif abs(exp) <= 99:
        text = f"{mant}E{sign}{abs(exp):02d}"
    else:
        text = f"{mant}{sign}{abs(exp):03d}"
    return text.rjust(width)


def python_es_text(values, width: int, digits: int, exp3: bool = False,
                   per_line: int | None = None, indent: int = 0) -> str:
    """`es_text` in Python, value by value."""
    M = np.asarray(values, dtype=float)
    if per_line is None or M.ndim < 2:
        rows = M.reshape(1, -1)
    else:
        rows = M.reshape(M.shape[0], M.size // M.shape[0] if M.shape[0] else 0)
    lines = []
    for row in rows.tolist():
        per = per_line or max(len(row), 1)
        for i in range(0, len(row), per):
            lines.append(" " * indent + "".join(python_es_one(x, width, digits, exp3)
                                                 for x in row[i:i + per]))
    return "\n".join(lines)


_buffers = threading.local()       # the C text's buffer, grown as needed, one a thread


def _buffer(size: int):
    buf = getattr(_buffers, "buf", None)
    if buf is None or len(buf) < size:
        buf = _buffers.buf = _ffi.new("char[]", max(size, 4096))
    return buf


def es_text(values, width: int, digits: int, exp3: bool = False,
            per_line: int | None = None, indent: int = 0) -> str:
    """The values in ESw.d (exp3 False) or ESw.dE3 (exp3 True), concatenated.

    values: numbers, a sequence or an array. per_line None: all of them (flattened) on
    one line; else a 2-D array's rows (a flat sequence: one row) each start a line of at
    most `per_line` values. Every line starts with `indent` blanks; lines are joined by
    newlines, none at the end. Each value is right-justified in `width` characters and
    never cut; NaN prints as 'NaN', the infinities as 'Infinity' / '-Infinity'
    (gfortran's text)."""
    if _lib is None:
        return python_es_text(values, width, digits, exp3, per_line, indent)
    if type(values) is list or type(values) is tuple:
        k, m, v = 1, len(values), values
    else:
        a = np.ascontiguousarray(values, dtype=float)
        if a.ndim >= 2 and per_line is not None:
            k = a.shape[0]
            m = a.size // k if k else 0
        else:
            k, m = 1, a.size
        v = _ffi.from_buffer("double[]", a)
    per = per_line or max(m, 1)
    size = k * m * max(width, digits + 8) + k * (m // per + 1) * (indent + 1) + 1
    buf = _buffers.__dict__.get("buf")
    if buf is None or len(buf) < size:
        buf = _buffer(size)
    try:
        n = _lib.cont_format_es(v, k, m, per, indent, width, digits, int(exp3), buf)
    except TypeError:             # nested rows, or items a double cannot take: numpy's view
        return es_text(np.asarray(values, dtype=float), width, digits, exp3, per_line, indent)
    if n < 0:
        raise ValueError(f"cannot format {k} x {m} values as ES{width}.{digits}")
    return _ffi.unpack(buf, n).decode("ascii")


def python_point_text(br: int, pt: int, ty: int, lab: int, name: str, values, dhead: str,
                      eigen=None) -> tuple[str, str]:
    """`point_text` in Python."""
    b = d = ""
    if values is not None:
        v = [float(x) for x in values]
        b = f"{br:4d}{pt:6d}{ty:4d}{lab:5d}{python_es_text(v, 19, 10, True)}\n"
        d = f"{dhead}{br:4d}{pt:6d} {name:>3}{lab:5d}{python_es_text(v[:8], 14, 5)}\n"
    if eigen is not None and len(eigen) == 4:
        ebr, ept, mults, n_stable = eigen
        z = np.asarray(mults, dtype=complex).tolist()
        lines = [f"{ebr:4d}{ept:6d}         Multipliers:     Stable:{n_stable:4d}"]
        lines += [f"{ebr:4d}{ept:6d}         Multiplier{k:3d} "
                  f"{python_es_text([x.real, x.imag], 14, 5)}"
                  f"  Abs. Val.{python_es_text([_modulus(x)], 14, 5)}" for k, x in enumerate(z, 1)]
        d += "\n".join(lines) + "\n"
    elif eigen is not None:
        ebr, ept, eig = eigen
        z = np.asarray(eig, dtype=complex).tolist()
        stable = sum(1 for x in z if x.real < 0)
        head = f"{ebr:4d}{ept:6d}         Eigenvalue"
        lines = [f"\n{head}s  :   Stable:{stable:4d}"]
        lines += [f"{head}{k:3d}:{python_es_text([x.real, x.imag], 14, 5)}"
                  for k, x in enumerate(z, 1)]
        d += "\n".join(lines) + "\n"
    return b, d


def _modulus(z: complex) -> float:
    """|z| as Python's abs of a complex takes it (libm's hypot, as cont_auto_point), inf
    where that overflows (abs raises there, hypot returns inf).

    A part NaN and none infinite is NaN, as hypot gives, decided before abs: CPython's
    complex abs returns NaN there without clearing errno, so an ERANGE left by earlier C
    code made it raise OverflowError and the modulus read inf."""
    if (math.isnan(z.real) or math.isnan(z.imag)) and not (
            math.isinf(z.real) or math.isinf(z.imag)):
        return math.nan
    try:
        return abs(z)
    except OverflowError:
        return math.inf


_UTF8: dict = {}           # `_utf8`'s bytes by text


def point_text(br: int, pt: int, ty: int, lab: int, name: str, values, dhead: str,
               eigen=None) -> tuple[str, str]:
    """A continuation point's text in AUTO's b- and d-files (io.f90 WRLINE, ae.f90
    PRINTEIG): (b, d), in one compiled call (csrc/cont/auto_point.cpp, cont_auto_point).

    values None: no b-line and no screen line; else b is the b-file line (I4 br, I6 pt,
    I4 ty, I5 lab, the values in ES19.10E3) and d starts with `dhead` (the d-file's bar
    and screen heading, as given) and the screen line (I4 br, I6 pt, a blank, `name`
    right-justified in 3, I5 lab, the first 8 values in ES14.5). eigen: (br, pt,
    eigenvalues) of PRINTEIG's block (the count of real parts below 0, then each
    eigenvalue's real and imaginary part in ES14.5) that follows in d, or (br, pt,
    multipliers, stable count) of PVSPBV's Floquet block (the count, then each
    multiplier's real and imaginary part and modulus in ES14.5), or None. Every line ends
    with a newline; integers are right-justified, never cut."""
    if _lib is None:
        return python_point_text(br, pt, ty, lab, name, values, dhead, eigen)
    data, nb = point_bytes(br, pt, ty, lab, name, values, dhead, eigen)
    return data[:nb].decode("ascii"), data[nb:].decode("utf-8")


def point_bytes(br: int, pt: int, ty: int, lab: int, name: str, values, dhead: str,
                eigen=None) -> tuple[bytes, int]:
    """`point_text`'s b and d text as one run of UTF-8 bytes and the length of b in it
    (the output files take the bytes as they are: no text made and encoded again)."""
    if _lib is None:
        b, d = python_point_text(br, pt, ty, lab, name, values, dhead, eigen)
        b = b.encode("ascii")
        return b + d.encode("utf-8"), len(b)
    if type(values) is list or type(values) is tuple:
        n, v = len(values), values
    elif values is None:
        n, v = -1, _ffi.NULL
    else:
        a = np.ascontiguousarray(values, dtype=float).ravel()
        n, v = a.size, _ffi.from_buffer("double[]", a)
    if eigen is None:
        ebr = ept = 0
        neig, e, cplx, nstable = -1, _ffi.NULL, 0, -1
    else:
        ebr, ept, eig = eigen[0], eigen[1], eigen[2]
        nstable = eigen[3] if len(eigen) == 4 else -1
        e, neig, cplx = _eigen_cdata(eig)
    nm, dh = _UTF8.get(name), _UTF8.get(dhead)
    if nm is None or dh is None:
        nm, dh = _utf8(name), _utf8(dhead)
    # (the b-line, heading and screen line, the eigenvalues' lines; n, neig >= -1)
    size = 343 + 20 * n + len(nm) + len(dh) + 90 * neig
    scratch = _buffers.__dict__
    buf, blen = scratch.get("buf"), scratch.get("lengths")
    if buf is None or len(buf) < size or blen is None:
        buf, blen = _buffer(size), _lengths()
    try:
        total = _lib.cont_auto_point(br, pt, ty, lab, nm, v, n, dh, ebr, ept, e, neig, cplx,
                                     nstable, buf, blen)
    except TypeError:           # items a double cannot take: numpy's view
        return point_bytes(br, pt, ty, lab, name, np.asarray(values, dtype=float), dhead, eigen)
    return _ffi.unpack(buf, total), blen[0]


_COMPLEX, _REAL = np.dtype(np.complex128), np.dtype(np.float64)


def _eigen_cdata(eig) -> tuple:
    """(pointer, count, 1 for complex values / 0 for real ones) of eigenvalues or
    multipliers as cont_auto_point reads them: a contiguous complex or real array as it
    lies in memory (no copy), anything else as a complex array's (re, im) pairs."""
    if type(eig) is np.ndarray:
        dt = eig.dtype
        if dt == _COMPLEX or dt == _REAL:
            a = eig if eig.flags.c_contiguous else np.ascontiguousarray(eig)
            return _ffi.from_buffer("double[]", a), a.size, int(dt == _COMPLEX)
    a = np.ascontiguousarray(eig, dtype=complex)
    return _ffi.from_buffer("double[]", a.view(np.float64)), a.size, 1


def _utf8(text: str) -> bytes:
    """text's UTF-8 bytes, remembered (a run passes the same few names and headings)."""
    b = _UTF8.get(text)
    if b is None:
        if len(_UTF8) > 256:
            _UTF8.clear()
        b = _UTF8[text] = text.encode("utf-8")
    return b


def _lengths():
    out = getattr(_buffers, "lengths", None)
    if out is None:
        out = _buffers.lengths = _ffi.new("int *")
    return out
