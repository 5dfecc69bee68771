"""The periodic-orbit runs (IPS = 2) of AUTO-07p's demo scripts ab, lrz, chu, plp and
frc against AUTO-07p's own output.

Constants files are used unchanged (tests/data/auto_demos/<demo>/c.*),
with only the overrides each .auto script passes; restarts read our own equilibrium
runs, as the scripts read theirs. Compared with AUTO's b-files: the labelled rows'
types in order, and PAR(ICP(1)) and PERIOD of *located* points (UZ, LP, PD) at 1e-5
relative: the same collocation (NTST, NCOL, mesh adaption) solves the same discrete
problem, so the remaining difference is the location tolerance EPSS. Regular NPR
outputs and end points depend on the step-size history and are compared by type only;
MAX U columns by neither (AUTO's own builds differ there in the 4th-5th digit, docs/auto.md
section 0). Branch numbers follow AUTO's rule for IPS = 2 restarts at an HB: the
label of the HB (docs/auto.md 1.4); the script relabels its files between runs, so AUTO's
numbers are compared only where no relabelling intervened (lrz, chu, plp's first
periodic runs). Exact: frc's period stays 2 pi / beta on both its branches (the
appended oscillator fixes it).
"""
import functools
import math
import shutil
from pathlib import Path

import pytest

from auto_reference import autoref, demo_dir
from b_rows import branch_rows, segments
from washer.auto.files import type_name
from washer.run import run

LOCATED = ("UZ", "LP", "PD", "BP", "TR")

def run_periodic(cfile: Path, sv: str, **overrides):
    """run(), which must end its branch normally."""
    res = run(cfile, verbose=False, sv=sv, **overrides)
    assert res.status == "ok", f"{cfile.name} {overrides}: {res.status}"
    return res


#: Rows of the periodic branches of a b-file.
rows = functools.partial(branch_rows, periodic=True)


def compare(ours: list, ref: list, branch=True, uz_values=None) -> None:
    lab_o = [r for r in ours if r.lab]
    lab_r = [r for r in ref if r.lab]
    key = (lambda r: (r.br, r.ty)) if branch else (lambda r: r.ty)
    assert [key(r) for r in lab_o] == [key(r) for r in lab_r]
    for o, r in zip(lab_o, lab_r):
        if type_name(r.ty) in LOCATED:
            for k in (0, len(r.values) - 1):      # PAR(ICP(1)); PERIOD (or last ICP)
                if type_name(r.ty) == "UZ" and uz_values is not None and \
                        any(math.isclose(o.values[k], v, rel_tol=1e-9) for v in uz_values):
                    # Where AUTO's own UZ is loose (it stops on EPSS: PERIOD 999.88 for
                    # UZSTOP 1000 in ab), the exact UZR/UZSTOP value judges: ours is on it.
                    assert o.values[k] == pytest.approx(r.values[k], rel=1e-3)
                    continue
                assert o.values[k] == pytest.approx(r.values[k], rel=1e-5), (type_name(r.ty), k)


# ---------------------------------------------------------------------------
# ab: for solution in ab("HB"): run(solution, c='ab.3')

@pytest.mark.slow
def test_ab_periodic_families(tmp_path_factory):
    """One family from each of the 7 HBs of the six p1-branches; each ends at the UZSTOP
    p1 = 0.25 or PERIOD = 1000, as in b.ab's periodic branches (in the same order)."""
    d = demo_dir(tmp_path_factory, "ab")
    start = run(d / "c.ab.1", verbose=False, e="ab", sv="start")
    ref = segments(rows(autoref("ab") / "b.ab.gz"))
    k = 0
    for s in start.specials:
        eq = run(d / "c.ab.2", verbose=False, e="ab", s="start", IRS=s.lab, sv=f"eq{s.lab}")
        for hb in [h for h in eq.specials if h.ty == "HB"]:
            sv = f"po{s.lab}_{hb.lab}"
            run_periodic(d / "c.ab.3", sv, e="ab", s=f"eq{s.lab}", IRS=hb.lab)
            ours = rows(d / f"b.{sv}")
            assert {-r.br for r in ours} == {hb.lab}       # IPS=2 from an HB: BR = its label
            compare(ours, ref[k], branch=False, uz_values=(0.25, 1000.0))
            k += 1
    assert k == len(ref) == 7


# ---------------------------------------------------------------------------
# lrz: run(lrz('HB1'), IPS=2, ICP=['rho','PERIOD'], NMX=35, NPR=2, DS=0.5), same for HB2

@pytest.mark.parametrize("hb", ["HB1", "HB2"])
def test_lrz_periodic_families(tmp_path_factory, hb):
    """The two symmetric families from HB1 (label 4) and HB2 (label 6): NPR = 2 regular
    outputs then EP at NMX = 35; the period grows towards the homoclinic orbit at
    rho = 13.9266 (AUTO: 585.4 at the end)."""
    d = demo_dir(tmp_path_factory, "lrz")
    run(d / "c.lrz", verbose=False, e="lrz", sv="lrz")
    sv = f"po_{hb}"
    run_periodic(d / "c.lrz", sv, e="lrz", s="lrz", IRS=hb, IPS=2, ICP=["rho", "PERIOD"],
                 NMX=35, NPR=2, DS=0.5)
    ours = rows(d / f"b.{sv}")
    ref = segments(rows(autoref("lrz") / "b.lrz"))[0 if hb == "HB1" else 1]
    compare(ours, ref)
    last = ours[-1]
    assert last.values[0] == pytest.approx(13.9266, rel=1e-4)
    assert last.values[-1] > 300


# ---------------------------------------------------------------------------
# chu: run(r1("HB1"), IPS=2, ICP=[1,11])

def test_chu_periodic_family_period_doubling(tmp_path_factory):
    """From HB1 (label 6, branch 6): PD at alpha = 8.19600, then EP at NMX = 100."""
    d = demo_dir(tmp_path_factory, "chu")
    run(d / "c.chu", verbose=False, e="chu", sv="r1")
    run_periodic(d / "c.chu", "r2", e="chu", s="r1", IRS="HB1", IPS=2, ICP=[1, 11])
    compare(rows(d / "b.r2"), rows(autoref("chu") / "b.chu"))


# ---------------------------------------------------------------------------
# plp: ps = run(hb, c='plp.ps') for each HB; the cycle-fold locus; the isola

@pytest.fixture(scope="module")
def plp(tmp_path_factory):
    d = demo_dir(tmp_path_factory, "plp")
    run(d / "c.plp.ss", verbose=False, e="plp", sv="ss")
    return d


@pytest.mark.parametrize("k, hb", [(0, "HB1"), (1, "HB2")])
def test_plp_periodic_families(plp, k, hb):
    """From HB1 (branch 2): LP of cycles (code 5) at PAR(4) = 2.75969, UZSTOP 4; from HB2
    (branch 3): LP at 5.00784, UZSTOP 4 (b.plp's periodic branches)."""
    run_periodic(plp / "c.plp.ps", f"ps{k + 1}", e="plp", s="ss", IRS=hb)
    compare(rows(plp / f"b.ps{k + 1}"), segments(rows(autoref("plp") / "b.plp"))[k])


@pytest.mark.slow
def test_plp_cycle_fold_locus(plp):
    """lpstart = run(plp('LP1'), c='plp.plp') generates starting data (ISW = 2 on IPS = 2:
    AUTO ends it with an EP to restart from); then run(lpstart) and DS='-': UZ at
    PAR(1) = 111 twice and 109 forward, 109 backward (b.loci's cycle-fold branch, merged
    there, so compared as sets of (PAR(4), PAR(1)) at 1e-5)."""
    run_periodic(plp / "c.plp.ps", "ps1", e="plp", s="ss", IRS="HB1")
    gen = run_periodic(plp / "c.plp.plp", "lpstart", e="plp", s="ps1", IRS="LP1")
    eps = [s for s in gen.specials if s.ty == "EP"]
    pts = []
    if eps and not any(s.ty == "UZ" for s in gen.specials):
        # AUTO's two stages: a generation run ending at an EP, restarted both ways
        for ds, sv in ((None, "lpf"), ("-", "lpb")):
            extra = {} if ds is None else {"DS": ds}
            run_periodic(plp / "c.plp.plp", sv, e="plp", s="lpstart", IRS=eps[-1].lab, **extra)
            pts += [(r.values[0], r.values[-2]) for r in rows(plp / f"b.{sv}") if r.lab
                    and type_name(r.ty) == "UZ"]
    else:
        # washer starts the locus at the LP itself (systems/cycle_fold.py): the run from
        # LP1 is the forward branch; DS='-' from LP1 the backward one
        run_periodic(plp / "c.plp.plp", "lpb", e="plp", s="ps1", IRS="LP1", DS="-")
        for sv in ("lpstart", "lpb"):
            pts += [(r.values[0], r.values[-2]) for r in rows(plp / f"b.{sv}") if r.lab
                    and type_name(r.ty) == "UZ"]
    ref = rows(autoref("plp") / "b.loci")                 # periodic rows: the cycle-fold locus
    want = [(r.values[0], r.values[-2]) for r in ref if r.lab and type_name(r.ty) == "UZ"]
    assert len(pts) == len(want) == 4
    for p4, p1 in want:
        assert any(abs(a - p4) <= 1e-5 * p4 and abs(b - p1) <= 1e-5 * p1 for a, b in pts), (p4, p1)


# ---------------------------------------------------------------------------
# frc: r1 = run(e='frc', c='frc'); r2 = run(r1("UZ1"), ICP=[5,11], NMX=20, DS=-0.5, DSMAX=5.0)

def test_frc_forced_response(tmp_path_factory):
    """The homotopy in the forcing amplitude r from the exact orbit at r = 0 (IRS = 0,
    STPNT at every mesh time): UZ at r = 0.2, EP at NMX = 10 (b.0); then in the forcing
    frequency beta from UZ1: EP at NMX = 20 (b.frc). On both branches the period is
    exactly 2 pi / beta (the appended oscillator sets it): 1e-7 relative (Newton)."""
    d = demo_dir(tmp_path_factory, "frc")
    run_periodic(d / "c.frc", "r1", e="frc")
    compare(rows(d / "b.r1"), rows(autoref("frc") / "b.0"))
    run_periodic(d / "c.frc", "r2", e="frc", s="r1", IRS="UZ1", ICP=[5, 11], NMX=20, DS=-0.5,
                 DSMAX=5.0)
    r1 = branch_rows(d / "b.r1")
    r2 = branch_rows(d / "b.r2")
    for r in r1:
        assert r.values[-1] == pytest.approx(2 * math.pi / 100, rel=1e-7)
    for r in r2:
        assert r.values[-1] == pytest.approx(2 * math.pi / r.values[0], rel=1e-7)
    ref2 = branch_rows(autoref("frc") / "b.frc")
    assert [type_name(r.ty) for r in r2 if r.lab] == [type_name(r.ty) for r in ref2 if r.lab]


def test_plp_isola_from_a_fold_locus_point(tmp_path_factory):
    """iso = run(loci('UZ4'), c='plp.iso') both ways: an orbit (ISW = 1) restarted from a
    point of the fold locus of cycles (AUTO's own s.loci, label 4: PAR(4) = 2.98629,
    PAR(1) = 111). The record's free parameters (PAR(4), PERIOD, PAR(1), PAR(NPAR+1)) are
    not the run's (PAR(4), PERIOD), so its stored direction (the locus's tangent, which
    moves PAR(1)) is not reused (AUTO's STPNBV1: NODIR = 1): the run starts along its
    own null vector at the fold and goes round the isola at PAR(1) = 111 to the UZ at
    PAR(4) = 4 and the fold at 4.72213 (STOP LP1) each way, as in AUTO's b.iso (1e-5:
    the location tolerance EPSS = 1e-6 with DS, DSMAX of c.plp.iso)."""
    d = demo_dir(tmp_path_factory, "plp")
    shutil.copy(autoref("plp") / "s.loci.gz", d / "s.aloci.gz")      # s='aloci' reads it
    ref = [r for r in rows(autoref("plp") / "b.iso") if r.lab]
    got = []
    for ds, sv in ((None, "isof"), ("-", "isob")):
        extra = {} if ds is None else {"DS": ds}
        run_periodic(d / "c.plp.iso", sv, e="plp", s="aloci", IRS=4, **extra)
        out = [r for r in rows(d / f"b.{sv}") if r.lab and type_name(r.ty) in LOCATED]
        assert [type_name(r.ty) for r in out] == ["UZ", "LP"]
        got += [(type_name(r.ty), r.values[0]) for r in out]
    assert sorted(t for t, _ in got) == sorted(type_name(r.ty) for r in ref) == \
        ["LP", "LP", "UZ", "UZ"]
    for t, w in got:
        exact = [r.values[0] for r in ref if type_name(r.ty) == t]
        assert min(abs(w - v) for v in exact) <= 1e-5 * w, (t, w, exact)
