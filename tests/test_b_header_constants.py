"""The constants a b-file header states (washer.auto.diagram.header_constants), read as
AUTO-07p's parseB reads them, and a run from a loaded diagram taking them as AUTO's CLUI
does (bifDiag: the solutions carry the header's constants without IRS, PAR, U, s, sv,
dat, TY, LAB, IBR; a c= file and keywords come after them)."""
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from auto07p_parsers import auto_python
from washer.auto import clui
from washer.auto.diagram import has_constants, header_constants, read_branches

DEMOS = Path(__file__).parent / "data" / "auto_demos"
AUTO_B_FILES = sorted(p for p in DEMOS.glob("*/autoref/b.*") if p.suffix != ".gz")


def _headers(path):
    return [b.header for b in read_branches(path) if has_constants(b.header)]


def test_homconts_header_with_user_specified_values_on_autos_own_file():
    # fhh's first run (IPS = 9, ISTART = 3): STHD states the run's own NBC = 7, NPAR = 17
    # and the NUNSTAB, NSTAB it computed (1, 2), then the user's below them (0, 14, -1, -1)
    h = header_constants(_headers(DEMOS / "fhh" / "autoref" / "b.1")[0])
    assert (h["IPS"], h["NDIM"], h["NTST"], h["NMX"], h["ICP"]) == (9, 3, 35, 50, [11, 17])
    assert (h["NBC"], h["NPAR"], h["NUNSTAB"], h["NSTAB"]) == (0, 14, -1, -1)
    assert (h["IEQUIB"], h["ITWIST"], h["ISTART"]) == (1, 0, 3)
    assert (h["DS"], h["DSMIN"], h["DSMAX"], h["EPSS"]) == (0.1, 1e-3, 2.0, 1e-5)
    assert h["UZR"] == {17: 0} and h["THL"] == {} and h["e"] == "fhn"
    assert h["RL0"] == -1.7976e308 and h["A1"] == 1.7976e308     # ES12.4 '1.7976+308'
    assert "NUZR" not in h                                       # a count, not a constant


def test_every_statement_of_autos_headers_is_read():
    """Each KEY = of every header line of AUTO-07p's b-files in tests/data is a constant
    read (NUZR, a count, and the branch type's TY excepted)."""
    n = 0
    for path in AUTO_B_FILES:
        for header in _headers(path):
            h = header_constants(header)
            n += 1
            for line in header[1:]:
                for key in re.findall(r"([A-Za-z]+)\s*=", line):
                    assert key in h or key in ("NUZR", "TY"), (path, key, line)
    assert n > 200


_AUTO_PARSEB = """
import json, sys
sys.modules['numpy'] = None     # AUTO's pure-Python arrays (tests/auto07p_parsers.py)
sys.path.insert(0, sys.argv[1])
from auto import parseB
out = {}
for f in sys.argv[2:]:
    out[f] = [{k: v for k, v in b.c.items() if v is not None and k[:7] != 'Active '
               and k not in ('homcont', 'new')} for b in parseB.parseBR(f) if b.c is not None]
print(json.dumps(out))
"""


def _as_autos(key, value):
    """washer's dict of an indexed constant as parseC's list of [index, value] pairs."""
    if isinstance(value, dict):
        return [[k, v] for k, v in value.items()]
    return value


@pytest.mark.skipif(auto_python() is None, reason="AUTO-07p's Python tools not installed")
def test_header_constants_are_autos_parseb_s():
    """Every value AUTO-07p's own parseB reads from the headers of its b-files in
    tests/data is washer's, and washer reads no constant it does not. (parseB also starts
    a branch at each PT = 1 without a header, with the constants before it: the
    headers are compared in order, one per header block.)"""
    out = subprocess.run([sys.executable, "-c", _AUTO_PARSEB, str(auto_python())] +
                         [str(p) for p in AUTO_B_FILES], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-2000:]
    autos = json.loads(out.stdout)
    compared = 0
    for path in AUTO_B_FILES:
        ours = [header_constants(h) for h in _headers(path)]
        theirs = autos[str(path)]
        # parseB's extra branches (a PT = 1 without a header) repeat the constants before
        firsts = [c for i, c in enumerate(theirs) if i == 0 or c is not theirs[i - 1]]
        for c in ours:
            assert c and any(json.loads(json.dumps({k: _as_autos(k, v) for k, v in c.items()}))
                             == t for t in firsts), path
            compared += 1
    assert compared > 200


@pytest.fixture
def ab_folder(tmp_path, monkeypatch):
    for f in ("ab.f90", "c.ab.1"):
        shutil.copy(DEMOS / "ab" / f, tmp_path)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(clui, "_runner", clui.Runner())
    return tmp_path


def _fresh_runner(monkeypatch):
    monkeypatch.setattr(clui, "_runner", clui.Runner())


def test_a_run_from_a_loaded_diagram_takes_its_headers_constants(ab_folder, monkeypatch):
    """ab's first run saved (sv='1'); then, with nothing remembered, r = loadbd('1') and
    run(r('UZ1')): the solution carries the header's constants (c.ab.1's, IRS, s, sv
    None), and the run is the run from the same solution as the first run returned it."""
    first = clui.run(e="ab", c="ab.1", sv="1")
    _fresh_runner(monkeypatch)
    bd = clui.loadbd("1")
    c = bd("UZ1").c
    assert (c["NDIM"], c["IPS"], c["ICP"], c["NPAR"], c["NMX"], c["DS"]) == (2, 1, [2], 3, 200, 0.1)
    assert c["THL"] == {11: 0.0} and c["UZSTOP"] == {2: 18.0} and c["e"] == "ab"
    assert c["IRS"] is None and c["sv"] is None and c["s"] is None
    clui.run(bd("UZ1"), NMX=15, sv="loaded")
    _fresh_runner(monkeypatch)
    clui.run(first("UZ1"), NMX=15, sv="returned")
    b_loaded, b_returned = Path("b.loaded").read_text(), Path("b.returned").read_text()
    assert b_loaded.replace("sv = 'loaded'", "sv = 'returned'") == b_returned
    assert Path("s.loaded").read_text() == Path("s.returned").read_text()
    # a keyword comes after the header: 15 steps, the header's NMX = 200 replaced
    assert len([ln for ln in b_loaded.splitlines() if not ln.split()[0] == "0"]) == 15
    assert "NMX=   15" in b_loaded


def test_a_constants_file_comes_after_the_header(ab_folder, monkeypatch):
    """run(r, c='x'): c.x replaces every constant it does not set by its default (AUTO's
    parseC update), the header's included; e stays the header's."""
    clui.run(e="ab", c="ab.1", sv="1")
    _fresh_runner(monkeypatch)
    Path("c.x").write_text("NDIM = 2, IPS = 1, ICP = [2], NMX = 4, DS = 0.05\n")
    sol = clui.load(clui.loadbd("1")("UZ1"), c="x")
    assert (sol.c["NMX"], sol.c["DS"], sol.c["NPAR"], sol.c["UZSTOP"]) == (4, 0.05, None, None)
    assert sol.c["e"] == "ab" and sol.c["IRS"] == sol.rec.lab


def _homcont_lines(block):
    return [ln for ln in block if re.match(r"   0 +(NUNSTAB=| IREV=| IFIXED=| IPSI=)", ln)]


@pytest.mark.slow
def test_homcont_header_lines_are_autos_on_fhh(tmp_path, monkeypatch):
    """fhh's 8 runs (homotopy start ISTART = 3, ITWIST = 1, IPSI and IFIXED lists): the
    HomCont lines of every header block are AUTO-07p's byte for byte (the NUNSTAB, NSTAB,
    ISTART the run uses, IEQUIB, ITWIST; IREV, IFIXED, IPSI; the user's below)."""
    from b_rows import header_blocks
    from washer.auto.script import run_script
    work = tmp_path / "fhh"
    shutil.copytree(DEMOS / "fhh", work, ignore=shutil.ignore_patterns("autoref"))
    monkeypatch.chdir(work)
    monkeypatch.setattr(clui, "_runner", clui.Runner())
    run_script("fhn.auto")
    n = 0
    for ref in sorted((DEMOS / "fhh" / "autoref").glob("b.*")):
        theirs, ours = header_blocks(ref), header_blocks(work / ref.name)
        assert len(ours) == len(theirs), ref.name
        for a, b in zip(theirs, ours):
            assert _homcont_lines(b) == _homcont_lines(a), ref.name
            n += bool(_homcont_lines(a))
    assert n >= 8
