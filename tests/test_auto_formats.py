"""washer's b-, s- and d-files are AUTO-07p's: byte-identical headers, and readable by
AUTO's own Python tools (parseB, parseD).

AUTO-07p's python package is not on PyPI, so the properties its parsers rely on are
restated here in our own code (from reading python/auto/parseB.py and parseD.py of
auto-07p/auto-07p) and checked first on AUTO's own files, then on ours.
"""
import re
from pathlib import Path

import pytest

from auto_reference import AB2P_LOCUS
from washer.auto.constants_file import Constants, read_constants
from washer.auto.files import D_BAR, OutputFiles, Row, column_title, fmt_es

DATA = Path(__file__).parent / "data"
REF = DATA / "auto_reference"
TITLES = ["PAR(1)", "L2-NORM", "U(1)", "U(2)"]


# ------------------------------------------------------------------ the rules
def check_parseB_rules(text: str) -> int:
    """What parseB needs of a b-file; returns the number of data lines.

    * Lines whose first field is '0' form header blocks; every block must be
      followed by at least one data line (parseB reads the column count from the
      first data line after a header and fails on a header without one).
    * The column-title line ('   0    PT  TY  LAB ...') is cut into slots of
      (data line length incl. newline - 19) // ncolumns characters starting at
      character 20; each slot's stripped text is a column name.
    * Data lines: 4 integers, then reals, 19 characters each.
    * The first header line holds RL0, RL1, A0, A1 after the '0'.
    """
    lines = text.splitlines(keepends=True)
    n_data, i = 0, 0
    while i < len(lines):
        if lines[i].split()[0] == "0":
            block = []
            while i < len(lines) and lines[i].split()[0] == "0":
                block.append(lines[i])
                i += 1
            assert i < len(lines), "a header block without data lines: parseB cannot read it"
            data = lines[i]
            ncol = len(data.split()) - 4
            titles = [l for l in block if " PT " in l]
            if titles:
                width = (len(data) - 19) // ncol
                assert width == 19, f"column slot width {width}"
                slots = [titles[-1][20 + k * width:20 + (k + 1) * width] for k in range(ncol)]
                assert all(s.strip() and " " not in s.strip() for s in slots), slots
        f = lines[i].split()
        [int(x) for x in f[:4]]
        assert len(lines[i].rstrip("\n")) == 19 + 19 * (len(f) - 4)
        n_data += 1
        i += 1
    first = [l for l in lines if l.split()[0] == "0"][:1]
    if first:
        words = first[0].split()
        assert len(words) == 5
        [float(re.sub(r"(\d)([+-]\d{3})$", r"\1E\2", w)) for w in words[1:]]
    return n_data


def check_parseD_rules(text: str) -> list[tuple[int, int, int]]:
    """What parseD needs of a d-file; returns (branch, point, eigenvalue count) per point.

    parseD splits the file at lines of 47 '=' ; in each part it takes the line after
    the first line whose first word is 'BR' and reads its first two fields as the
    branch and point numbers (integers); eigenvalues are the matches of
    'Eigenvalue' + whitespace, whose 3rd and 4th fields are the real and
    imaginary parts. A part with fewer than 3 lines or no 'BR' line is skipped,
    with its eigenvalues.
    """
    found = []
    for part in text.split(D_BAR + "\n"):
        lines = part.splitlines()
        heads = [k for k, l in enumerate(lines) if l.split()[:1] == ["BR"]]
        eig = re.findall(r"Eigenvalue\s.*", part)
        if len(lines) < 3 or not heads or heads[0] + 1 >= len(lines):
            assert not eig, "eigenvalues parseD would skip (no 'BR' line in their part)"
            continue
        sp = lines[heads[0] + 1].split()
        br, pt = int(sp[0]), int(sp[1])
        for e in eig:
            w = e.split()
            float(w[2]), float(w[3])
        found.append((br, pt, len(eig)))
    return found


def test_rules_hold_on_auto_files():
    """The restated rules accept AUTO-07p's own files (else they test nothing real)."""
    assert check_parseB_rules((REF / "ab_fortran" / "b.run1").read_text()) > 10
    assert check_parseB_rules((REF / "ab2p" / "b.hb_fwd").read_text()) > 10
    points = check_parseD_rules((REF / "ab2p" / "d.eq.head").read_text())
    assert len(points) >= 5 and all(n == 2 for _, _, n in points[:5])


def test_rules_reject_what_parse_b_and_d_cannot_read():
    header_only = (REF / "ab_fortran" / "b.run1").read_text().split("   1    -1")[0]
    with pytest.raises(AssertionError, match="header block without data"):
        check_parseB_rules(header_only)
    no_bars = "   1     1         Eigenvalues  :   Stable:   2\n" \
              "   1     1         Eigenvalue  1: -1.00000E+00  0.00000E+00\n" * 3
    with pytest.raises(AssertionError, match="eigenvalues parseD would skip"):
        check_parseD_rules(no_bars)


# ------------------------------------------------------------ exact headers
def _ab2p(sv: str, ds: float, irs: int) -> Constants:
    """The constants of ab2p's codim-1 runs (ab2p.auto): c.ab, then ICP, ISW, UZSTOP, and
    IRS = the label of eq('HB1') or eq('LP1') (AUTO's CLUI passes the label number)."""
    c = read_constants(DATA / "ab" / "c.ab")
    dict.__setitem__(c, "PAR", {})          # those runs restart from eq's s-file, no PAR
    for k, v in dict(AB2P_LOCUS, DS=ds, sv=sv, IRS=irs).items():
        c.set(k, v)
    return c


def _run2() -> Constants:
    c = read_constants(DATA / "auto_demos" / "ab" / "c.ab.2")
    c.set("IRS", 2)                          # run(c='ab.2', IRS=2) in the ab demo
    return c


CASES = {
    # file: (constants, internal NDIM, IRS used, curve type, titles, first data row)
    "ab_fortran/b.run1": (lambda: read_constants(DATA / "auto_demos" / "ab" / "c.ab.1"), 2, None, 0,
                          ["PAR(2)"] + TITLES[1:], Row(1, -1, 9, 1, [8.0, 0.0, 0.0, 0.0])),
    "ab_fortran/b.run2": (_run2, 2, None, 0, TITLES, Row(1, -1, 0, 0, [0.0, 0.0, 0.0, 0.0])),
    "ab2p/b.hb_fwd": (lambda: _ab2p("hb_fwd", 0.01, 2), 6, 2, 3, TITLES + ["PAR(2)"], None),
    "ab2p/b.hb_bwd": (lambda: _ab2p("hb_bwd", -0.01, 2), 6, 2, 3, TITLES + ["PAR(2)"], None),
    "ab2p/b.lp_fwd": (lambda: _ab2p("lp_fwd", 0.01, 3), 5, 3, 2, TITLES + ["PAR(2)"], None),
    "ab2p/b.lp_bwd": (lambda: _ab2p("lp_bwd", -0.01, 3), 5, 3, 2, TITLES + ["PAR(2)"], None),
}


@pytest.mark.parametrize("name", CASES)
def test_b_header_is_autos_byte_for_byte(tmp_path, name):
    make, ndim, irs, curve, titles, first = CASES[name]
    ref = (REF / name).read_text().splitlines(keepends=True)
    ref_first = next(l for l in ref if not l.startswith("   0"))
    out = OutputFiles(tmp_path, "x")
    out.header(make(), ndim, 11, titles, curve, {2: "LP", 3: "HB"}.get(curve, ""), irs=irs)
    out.branch_start()
    if first is None:           # take AUTO's first point: only the layout is under test
        f = ref_first.split()
        first = Row(int(f[0]), int(f[1]), int(f[2]), int(f[3]), [float(x) for x in f[4:]])
    out.row(first)
    ours = (tmp_path / "b.x").read_text().splitlines(keepends=True)
    n = ref.index(ref_first) + 1
    assert ours == ref[:n]


def test_column_titles_follow_headng():
    assert column_title("PAR(12)") == "   PAR(12)         "
    assert column_title("U(3)") == "     U(3)          "
    assert column_title("m_u") == "     m_u           "              # centred: 7 - (3-1)//2
    assert column_title("a_rather_long_parameter_name") == " a_rather_long     "   # 13 chars
    # HEADNG's IPLT column of a named component: 'INTEGRAL ' // name (AUTO's exp demo:
    # 'INTEGRAL u'), 'L2-NORM ' // name (ffn: 'L2-NORM x'), 'MAX ' // name, centred as a
    # whole, the name cut to its 13 characters (a CHARACTER(13)) and not the prefix
    assert column_title("INTEGRAL u") == "  INTEGRAL u       "             # 7 - (10-1)//2 = 3
    assert column_title("L2-NORM x") == "  L2-NORM x        "              # 7 - 8//2 = 3
    assert column_title("MAX a_rather_long_name") == " MAX a_rather_long "
    assert fmt_es(-1.7976e308, 12, 4) == " -1.7976+308" and fmt_es(1e-7, 11, 4) == " 1.0000E-07"


# --------------------------------------------------------- writer behaviour
def _write_points(out: OutputFiles, n: int) -> None:
    c = read_constants(DATA / "ab" / "c.ab")
    out.header(c, 2, 11, TITLES)
    out.branch_start()
    for k in range(1, n + 1):
        out.row(Row(1, -k, 9 if k == 1 else 0, int(k == 1), [0.1 * k, 1.0, 0.5, 0.5]))
        out.eigenvalues(1, k, [-1.0 + 0.5j, -1.0 - 0.5j])


def test_our_b_and_d_files_satisfy_auto_parsers(tmp_path):
    out = OutputFiles(tmp_path, "x")
    _write_points(out, 4)
    out.diag(f"\n{D_BAR}\n\n Total Time    0.100E-01")
    assert check_parseB_rules((tmp_path / "b.x").read_text()) == 4
    points = check_parseD_rules((tmp_path / "d.x").read_text())
    assert [(br, abs(pt), n) for br, pt, n in points] == [(1, k, 2) for k in range(1, 5)]
    assert "   1     1         Eigenvalue  1:  -1.00000E+00   5.00000E-01" in \
        (tmp_path / "d.x").read_text()                                # AUTO's ES14.5


def test_a_run_without_points_leaves_no_header_only_b_file(tmp_path):
    out = OutputFiles(tmp_path, "x")
    out.header(read_constants(DATA / "ab" / "c.ab"), 2, 11, TITLES)
    out.branch_start()
    assert (tmp_path / "b.x").read_text() == ""        # parseB reads an empty file as no data
    check_parseB_rules("")


def test_d_file_lines_are_autos(tmp_path):
    """Point, eigenvalue and multiplier lines as AUTO-07p writes them (ab2p/d.eq, and
    ab_po_raw/d.raw3 quoted in docs/auto.md 2.3)."""
    ref = (REF / "ab2p" / "d.eq.head").read_text().splitlines()
    out = OutputFiles(tmp_path, "x")
    out.column_titles = TITLES
    out.row(Row(1, -2, 0, 0, [4.40397e-03, 1.95091e-02, 4.46835e-03, 1.89905e-02]))
    out.eigenvalues(1, 1, [-1.0, -4.0])
    out.multipliers(7, 2, [1.0, 1.00168], 1)
    ours = (tmp_path / "d.x").read_text().splitlines()
    assert ours[1] in ref and ours[2] in ref                   # heading and point line
    assert ours[4:7] == ref[2:5]                               # the eigenvalue block
    assert ours[7:] == [
        "   7     2         Multipliers:     Stable:   1",
        "   7     2         Multiplier  1    1.00000E+00   0.00000E+00  Abs. Val.   1.00000E+00",
        "   7     2         Multiplier  2    1.00168E+00   0.00000E+00  Abs. Val.   1.00168E+00"]


def test_our_s_records_are_what_parseS_counts(tmp_path):
    """parseS takes a record as a header of 12 or 16 integers and NROWPR lines whose
    numbers it counts; our records read back to the same values."""
    import numpy as np
    from washer.auto.files import read_s
    from washer.cont.branch import Record
    rec = Record(2, 140, -32, 7, 2, 2, 2, 1, np.array([0.57, 1.59, 0.7, 0.7, 3.1, 11.0]),
                 np.linspace(0.1, 1.1, 11), [1, 2], [0.039, -0.48], np.arange(6) / 7)
    out = OutputFiles(tmp_path, "x")
    out.record(rec)
    out.record(rec)
    lines = (tmp_path / "s.x").read_text().splitlines()
    h = [int(x) for x in lines[0].split()]
    assert len(h) == 16 and len(lines) == 2 * (1 + h[8])            # NROWPR lines each
    ntpl, nar, nfpr, npar = h[6], h[7], h[4], h[11]
    body = " ".join(lines[1:1 + h[8]]).split()
    assert len(body) == ntpl * nar + nfpr + nfpr + ntpl * (nar - 1) + npar
    back = read_s(tmp_path / "s.x")[1]
    np.testing.assert_allclose(back.u, rec.u, rtol=1e-10)         # the whole stored state
    np.testing.assert_allclose(back.udot, rec.udot, atol=1e-11)
    assert back.icp == [1, 2] and back.code == -32 and back.ty == "GH" and back.lab == 7


def test_a_step_number_past_9999_is_written_as_auto_writes_it(tmp_path):
    """A record at step 100000 (a long time integration): AUTO's s-file header holds
    MTOT = MOD(NTOT-1, 9999) + 1 = 10 (WRTSP8) in its I6 field; the raw number fills the
    field and runs into the branch number before it ('     1100000'), which neither
    AUTO's parseS nor our reader takes for two integers."""
    import numpy as np
    from washer.auto.files import read_s
    from washer.cont.branch import Record
    for pt, mtot in ((100000, 10), (9999, 9999), (10000, 1), (-20000, -2)):
        rec = Record(1, pt, 9, 201, 1, 1, 1, 1, np.array([0.5, 0.25]), np.arange(4.0))
        out = OutputFiles(tmp_path, f"p{abs(pt)}")
        out.record(rec)
        out.close()
        path = tmp_path / f"s.p{abs(pt)}"
        head = [int(x) for x in path.read_text().splitlines()[0].split()]
        assert head[:4] == [1, mtot, 9, 201]
        back = read_s(path)[0]
        assert back.lab == 201 and back.pt == mtot
        np.testing.assert_allclose(back.u, rec.u, rtol=1e-10)


def test_row_formatting_is_the_python_formatter_value_by_value():
    """The formatting of whole rows (fmt_e_many, fmt_es_many) gives the text of the
    Python formatter (washer.auto.es_format.python_es_one) value by value: 3-digit
    exponents, zeros, signs, rounding at the last digit, NaN, infinities."""
    import numpy as np
    from washer.auto.es_format import python_es_one
    from washer.auto.files import fmt_e, fmt_e_many, fmt_es_many
    rng = np.random.default_rng(7)
    plain = np.r_[0.0, -0.0, 1.0, -1.0, 9.99999999995, 9.999999999949999, 1e-99, -1e-99,
                  9.9e98, 0.5e-7, 123456.789, rng.standard_normal(50) * 10.0 ** rng.integers(
                      -98, 98, 50)]
    odd = np.r_[plain[:5], 1e-100, -3.2e150, 1.7976931348623157e308, np.nan, np.inf, -np.inf]
    for vals in (plain, odd):
        assert fmt_e_many(vals) == "".join(python_es_one(v, 19, 10, True) for v in vals)
        assert fmt_e_many(list(vals)) == "".join(fmt_e(v) for v in vals)
        assert fmt_es_many(vals, 14, 5) == "".join(python_es_one(v, 14, 5, False) for v in vals)
        assert fmt_es_many(vals, 11, 4) == "".join(python_es_one(v, 11, 4, False) for v in vals)


def _rows_by_value(M) -> list:
    """The s-file lines of M's rows from the Python formatter value by value: 7 values a
    line after 4 blanks, every row on lines of its own."""
    from washer.auto.es_format import python_es_one
    out = []
    for row in M.tolist():
        out += ["    " + "".join(python_es_one(v, 19, 10, True) for v in row[i:i + 7])
                for i in range(0, len(row), 7)]
    return out


def test_block_formatting_is_rows_of_fmt_e():
    """A BVP record's blocks in one call (files._block_lines) give the lines of the Python
    formatter value by value (7 a line after 4 blanks, each row of the block on lines of
    its own), for rows of 1..15 values and with 3-digit exponents, NaN, infinities."""
    import numpy as np
    from washer.auto.files import _block_lines, _rows, fmt_e
    rng = np.random.default_rng(3)
    for k, m in [(1, 1), (5, 4), (801, 4), (3, 7), (3, 8), (4, 15), (2, 14)]:
        M = rng.standard_normal((k, m)) * 10.0 ** rng.integers(-98, 98, (k, m))
        M.flat[::5] = 0.0
        M.flat[1::7] = -0.0
        lines = "\n".join(_block_lines(M)).split("\n")
        assert lines == _rows_by_value(M)
        assert len(lines) == k * ((m + 6) // 7)
        assert lines[0] == "    " + "".join(fmt_e(v) for v in M[0, :7])
        assert "\n".join(_rows(list(M[0]))).split("\n") == _rows_by_value(M[:1])
    odd = np.array([[1e-100, 2.0, np.nan], [np.inf, -3.2e150, 0.5]])
    assert "\n".join(_block_lines(odd)).split("\n") == _rows_by_value(odd)
    assert _rows([]) == []
    assert _block_lines(np.zeros((0, 3))) == [] and _block_lines(np.zeros((2, 0))) == []
