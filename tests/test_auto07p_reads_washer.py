"""AUTO-07p itself reading what washer writes: the headers and records of extended systems
as AUTO's, and AUTO-07p continuing a locus from washer's s-records of it. (AUTO's Python
parsers read every file of every demo folder's run in tests/test_auto_demo_folders.py.)

The s-record header's NPARI (field 13) is what AUTO-07p needs of an extended system's
record: it reads the user's NPAR as NPAR - NPARI and finds the locus' internal
parameters after it. Skipped with a message where AUTO-07p is not installed.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from b_rows import branch_rows, header_blocks
from washer.auto.constants_file import read_constants
from washer.auto.diagram import read_solutions
from washer.auto.files import read_s

ROOT = Path(__file__).resolve().parents[1]
DEMOS = Path(__file__).parent / "data" / "auto_demos"
HAVE_AUTO = shutil.which("auto-07p") is not None and shutil.which("gfortran") is not None

pytestmark = pytest.mark.slow


def _washer_demo(tmp_path_factory, demo: str) -> Path:
    """The demo folder run by washer's CLUI (`python -m washer.auto DEMO.auto`)."""
    work = tmp_path_factory.mktemp("w") / demo
    shutil.copytree(DEMOS / demo, work, ignore=shutil.ignore_patterns("autoref"))
    env = dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1")
    subprocess.run([sys.executable, "-m", "washer.auto", f"{demo}.auto"], cwd=work, env=env,
                   check=True, capture_output=True, timeout=900)
    return work


@pytest.fixture(scope="module")
def plp(tmp_path_factory):
    return _washer_demo(tmp_path_factory, "plp")


@pytest.fixture(scope="module")
def integral(tmp_path_factory):
    return _washer_demo(tmp_path_factory, "int")


@pytest.fixture(scope="module")
def dd2(tmp_path_factory):
    return _washer_demo(tmp_path_factory, "dd2")


@pytest.mark.skipif(not HAVE_AUTO, reason="AUTO-07p (auto-07p and gfortran) is not installed")
def test_auto07p_continues_washers_fold_of_cycles_locus(plp, tmp_path):
    """AUTO-07p restarts plp's fold locus of cycles (c.plp.plp: PAR(4), PAR(1), period)
    from washer's record of it (s.loci, its UZ at PAR(1) = 111, label 4) and follows the
    same curve: it passes PAR(1) = 111 again where washer's own run did (UZ5), within
    twice the location tolerance EPSS (1 + sqrt(DS DSMAX)) (each engine within it, PAR(4)
    having weight 1 in the arclength), and the period to 1e-6 relative. The records
    carry NPARI = 2 (beta and the norm constant after the user's NPAR), without which
    AUTO-07p's restart takes washer's beta for a user parameter and stops (MX) at once."""
    recs = {r.lab: r for r in read_s(plp / "s.loci")}
    start = recs[4]
    assert start.ty == "UZ" and start.curve_type == 5 and start.par[0] == pytest.approx(111)
    head = (plp / "s.loci").read_text().splitlines()
    fold_heads = [h.split() for h in head if len(h.split()) == 16 and h.split()[2] == "-54"]
    assert fold_heads and all(h[12] == "2" for h in fold_heads)
    auto = tmp_path / "auto"
    auto.mkdir()
    for name in ("plp.f90", "c.plp.plp"):
        shutil.copy(DEMOS / "plp" / name, auto / name)
    shutil.copy(plp / "s.loci", auto / "s.ours")
    (auto / "r.auto").write_text("run(e='plp', c='plp.plp', s='ours', IRS=4, NMX=30, sv='x')\n")
    subprocess.run(["auto-07p", "r.auto"], cwd=auto, env=dict(os.environ, OMP_NUM_THREADS="1"),
                   capture_output=True, timeout=600, check=True)
    rows = branch_rows(auto / "b.x")
    uz = [r for r in rows if r.lab and r.ty == -54]
    assert len(rows) == 30 and len(uz) == 1
    ours = [r for r in branch_rows(plp / "b.loci") if r.lab == 5][0]
    assert ours.ty == -54
    tol = 1e-6 * (1 + (0.1 * 3.0) ** 0.5)          # c.plp.plp: EPSS, DS, DSMAX
    assert uz[0].values[0] == pytest.approx(ours.values[0], abs=2 * tol)      # PAR(4)
    assert uz[0].values[-1] == pytest.approx(ours.values[-1], rel=1e-6)       # period


@pytest.mark.parametrize("demo, name", [("integral", "b.lp"), ("dd2", "b.pd")])
def test_extended_systems_headers_are_autos(demo, name, request):
    """The header of an extended system's run as AUTO-07p writes it, byte for byte
    (AUTO's own file of the same run, autoref): the fold locus of int's BVP (NDIM 4,
    NBC 2, NINT 3, NPAR 4: the system's own, the user's NDIM 2, NPAR 3, NBC 1, NINT 1
    under 'User-specified constants', Branch type 5 'LP') and the period-doubling locus
    of dd2's map (NDIM 5, Branch type 7 'PD')."""
    folder = request.getfixturevalue(demo)
    ref = DEMOS / folder.name / "autoref" / name
    assert header_blocks(folder / name)[0] == header_blocks(ref)[0]


def test_fold_of_cycles_header_is_autos(plp):
    """plp's fold locus of cycles: its header block is AUTO's b.loci block byte for byte:
    NDIM 4, NBC 4, NINT 3 (2 NDIM periodicity conditions; the phase, v's orthogonality
    and the normalisation), NPAR 13 (PAR(1..11), beta, c: no PAR(12) torus angle where
    TR is not detected, ISP = 1), the user's NDIM 2, NPAR 5, NBC 0, NINT 0 listed under
    them, Branch type 5 'LP', the active parameters PAR(4), the period, PAR(1) and beta
    (PAR(12))."""
    ours = [b for b in header_blocks(plp / "b.loci") if any("Branch type:  5" in x for x in b)]
    ref = [b for b in header_blocks(DEMOS / "plp" / "autoref" / "b.loci")
           if any("Branch type:  5" in x for x in b)]
    assert len(ours) == len(ref) == 1
    assert ours[0] == ref[0]


@pytest.mark.skipif(not HAVE_AUTO, reason="AUTO-07p (auto-07p and gfortran) is not installed")
def test_auto07p_continues_washers_fold_locus_of_a_bvp(integral, tmp_path):
    """AUTO-07p restarts int's fold locus (c.int, ICP = [1, 2], ISW = 2) from washer's
    record of it (s.lp, the UZ at PAR(1) = 3, label 9; NPARI = 1: the norm after the
    user's NPAR) and meets PAR(1) = 1 where washer, restarted from the same record by the
    same script line, does: PAR(2) within twice the location tolerance
    EPSS (1 + sqrt(DS DSMAX)) of c.int (the demo's own run ends at NMX before PAR(1) = 1,
    in both programs)."""
    recs = {r.lab: r for r in read_s(integral / "s.lp")}
    assert recs[9].ty == "UZ" and recs[9].par[0] == pytest.approx(3) and recs[9].npari == 1
    line = "run(e='int', c='int', s='ours', IRS=9, ICP=[1, 2], ISW=2, sv='x')\n"
    uz = {}
    for who, cmd in (("auto", ["auto-07p", "r.auto"]),
                     ("washer", [sys.executable, "-m", "washer.auto", "r.auto"])):
        folder = tmp_path / who
        folder.mkdir()
        for name in ("int.f90", "c.int"):
            shutil.copy(DEMOS / "int" / name, folder / name)
        shutil.copy(integral / "s.lp", folder / "s.ours")
        (folder / "r.auto").write_text(line)
        subprocess.run(cmd, cwd=folder, env=dict(os.environ, OMP_NUM_THREADS="1"),
                       capture_output=True, timeout=600, check=True)
        uz[who] = [r for r in branch_rows(folder / "b.x") if r.lab and r.ty == -54]
    assert len(uz["auto"]) == 1 and uz["auto"][0].values[0] == pytest.approx(1.0, abs=1e-5)
    assert len(uz["washer"]) == 1 and uz["washer"][0].values[0] == pytest.approx(1.0, abs=1e-5)
    tol = 1e-4 * (1 + (0.01 * 2.0) ** 0.5)          # c.int: EPSS, DS, DSMAX
    assert uz["auto"][0].values[-1] == pytest.approx(uz["washer"][0].values[-1], abs=2 * tol)


def _record_heads(path: Path) -> list[tuple[list[int], list[int]]]:
    """Each s-record's 16 header integers and the ICP line of its stored direction (the
    records' own lines, as read_solutions keeps them: s.NAME.gz read where s.NAME is not)."""
    out = []
    for s in read_solutions(path):
        h = [int(x) for x in s.raw[0].split()]
        ntpl, nar = h[6], h[7]
        out.append((h, [int(x) for x in s.raw[1 + ((nar - 1) // 7 + 1) * ntpl].split()]))
    return out


#: The s-record header fields compared with AUTO's: all but IBR, NTOT, ITP, LAB (where
#: the point lies on the curve) and IPRIV.
_SAME = {4: "NFPR", 5: "ISW", 6: "NTPL", 7: "NAR", 8: "NROWPR", 9: "NTST", 10: "NCOL",
         11: "NPAR", 12: "NPARI", 13: "NDIM", 14: "IPS"}


def _assert_records_like_autos(ours: Path, ref: Path, code: int) -> None:
    mine = [(h, icp) for h, icp in _record_heads(ours) if h[2] == code]
    auto = [(h, icp) for h, icp in _record_heads(ref) if h[2] == code]
    assert mine and auto
    for h, icp in mine:
        assert {_SAME[k]: h[k] for k in _SAME} == {_SAME[k]: auto[0][0][k] for k in _SAME}
        assert icp == auto[0][1]


def test_fold_of_cycles_records_are_autos(plp):
    """plp's fold locus of cycles (UZ, code -54) as AUTO's records of it (autoref s.loci):
    NFPR = 4 (periodic.f90 INITPS: NDIM = 2 NDIM, NBC = NDIM, NINT = 3, so NFPR = NBC +
    NINT - NDIM + 1 = 4) with ICP = PAR(4), the period, PAR(1) and beta (PAR(12)) and
    their four RLDOT, NPAR 13, NPARI 2, the sizes of the stored profile."""
    _assert_records_like_autos(plp / "s.loci", DEMOS / "plp" / "autoref" / "s.loci", -54)


def test_fold_of_cycles_beta_is_autos(plp):
    """beta (PAR(12) of plp's fold-locus records) is AUTO-07p 0.9.2's: the factor of f in
    v' = T f_u v + beta f. (v, beta) is the locus's null vector, fixed up to its scale
    int |v|^2 + beta^2 = c (PAR(13)), so beta / sqrt(c) is one number for both engines
    up to sign (measured 0.0612121 both at UZ3; with beta / T in place of beta ours was
    0.6459, T = 10.54 times AUTO's, and a record of either engine read by the other
    started off its locus).

    How closely: each record is a UZ of PAR(1) (c.plp.plp's UZR, UZSTOP), located by each
    engine to EPSS (1 + sqrt(|DS DSMAX|)) in arclength, along which beta, a free parameter
    of weight 1 (THL = {}), moves at most as fast; and corrected with beta's last change
    below EPSL (1 + |beta|). beta / sqrt(c) of each engine is within those two over
    sqrt(c) (c fixed on the run) of the point's own: their sum over both engines bounds
    the difference (4.7e-6 .. 4.8e-6; measured 6e-10 .. 9.7e-8)."""
    c = read_constants(DEMOS / "plp" / "c.plp.plp")
    located = c["EPSS"] * (1 + abs(c["DS"] * c["DSMAX"]) ** 0.5)
    mine = [r for r in read_s(plp / "s.loci") if abs(r.br) == 4]
    ref = [r for r in read_s(DEMOS / "plp" / "autoref" / "s.loci") if abs(r.br) == 4]
    assert len(mine) == len(ref) >= 2
    for r, a in zip(mine, ref):
        assert r.ty == a.ty == "UZ"
        bound = sum((located + c["EPSL"] * (1 + abs(x.par[-2]))) / x.par[-1] ** 0.5
                    for x in (r, a))
        assert abs(abs(r.par[-2]) / r.par[-1] ** 0.5 - abs(a.par[-2]) / a.par[-1] ** 0.5) \
            <= bound, (r.lab, a.lab)


@pytest.fixture(scope="module")
def lcbp(tmp_path_factory):
    return _washer_demo(tmp_path_factory, "lcbp")


@pytest.mark.parametrize("name", ["b.lcbp.1", "b.lcbp.2.fw", "b.lcbp.2.bw", "b.lcbp.3.fw",
                                  "b.lcbp.3.bw"])
def test_branch_point_of_cycles_headers_are_autos(lcbp, name):
    """lcbp's b-file headers are AUTO's byte for byte (autoref): the cycles' run (e =
    'lcbp' s = '/' sv = 'lcbp.1': the CLUI's fresh start) and the restarted BP loci of
    cycles, non-generic (ISW = 2: NDIM 4, NBC 4, NINT 4, NPAR 15 = PAR(1..12), phi3, a,
    b) and generic (ISW = 3: NPAR 14, no b). (The generating runs, lcbp.2.sw and
    lcbp.3.sw, differ: AUTO's is a system of 4 NDIM components with 9 internal
    parameters, ours starts from the adjoint computed at the BP: 2 NDIM, 3.)"""
    assert header_blocks(lcbp / name)[0] == header_blocks(DEMOS / "lcbp" / "autoref" / name)[0]


@pytest.mark.skipif(not HAVE_AUTO, reason="AUTO-07p (auto-07p and gfortran) is not installed")
def test_branch_point_of_cycles_records_are_autos(lcbp, tmp_path):
    """The s-records of lcbp's restarted BP loci of cycles (code 64) as AUTO-07p's own of
    the same script, run here: NFPR 5 with the same ICP (PAR(1), the period, PAR(2) or
    PAR(3), b (PAR(15), ISW = 2 only), phi3 (PAR(13))), NPAR 15 and NPARI 3 (ISW = 2),
    NPAR 14 and NPARI 2 (ISW = 3), the profile's sizes."""
    auto = tmp_path / "lcbp"
    shutil.copytree(DEMOS / "lcbp", auto, ignore=shutil.ignore_patterns("autoref"))
    subprocess.run(["auto-07p", "lcbp.auto"], cwd=auto, env=dict(os.environ, OMP_NUM_THREADS="1"),
                   capture_output=True, timeout=600, check=True)
    for name in ("s.lcbp.2.fw", "s.lcbp.2.bw", "s.lcbp.3.fw", "s.lcbp.3.bw"):
        _assert_records_like_autos(lcbp / name, auto / name, 64)
