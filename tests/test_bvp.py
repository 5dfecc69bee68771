"""General boundary value problems (IPS = 4): AUTO-07p's demos bvp, pvl, non, ext and
lin (their constants unchanged, the scripts' overrides only) against AUTO's own
b-files, and the 1-D Bratu problem against its closed form.

Located points (BP, LP, UZ) are compared with AUTO's to the location tolerance both
engines promise, EPSS (1 + sqrt(|DS DSMAX|)) on the arclength (the tangent is unit,
so a parameter moves by at most that much). End points depend on the step history and
are compared by type only.
"""
import math
from pathlib import Path

import mpmath
import numpy as np
import pytest

from b_rows import branch_rows
from demo_files import autoref, copy_demo
from tolerances import location_tolerance
from washer.auto.constants_file import read_constants
from washer.auto.files import read_s, type_name
from washer.run import run

#: the Python transcriptions of the demos' equations (NAME/NAME.py), which the tests run
#: in place of AUTO's NAME.f90
PYTHON = Path(__file__).parent / "data" / "bvp"


def demo(tmp_path: Path, name: str) -> Path:
    return copy_demo(name, tmp_path, PYTHON / name)


def auto_rows(name: str, bfile: str) -> list:
    """(type, branch, PAR(ICP(1))) of AUTO's labelled rows."""
    return [(type_name(r.ty), r.br, r.values[0])
            for r in branch_rows(autoref(name) / bfile) if r.lab]


def ours(*runs) -> list:
    return [(s.ty, s.br, s.par[s_icp - 1]) for r, s_icp in runs for s in r.specials]


def compare(got, ref, tol, uz_targets=()):
    """Types and branches in order; located values within `tol` of AUTO's. A UZ on a
    UZR/UZSTOP value of PAR(ICP(1)) itself (`uz_targets`) is judged by that exact
    value: ours on it to 1e-9, AUTO's within twice the tolerance (AUTO stops locating
    on EPSS: bvp's UZSTOP p1 = 0 is -2.8e-5 in its b-file)."""
    assert [(t, b) for t, b, _ in got] == [(t, b) for t, b, _ in ref]
    for (t, b, o), (_, _, a) in zip(got, ref):
        if t == "UZ" and any(abs(o - v) <= 1e-9 for v in uz_targets):
            v = min(uz_targets, key=lambda v: abs(o - v))
            assert abs(a - v) <= 2 * tol, (t, b, o, a)
        elif t != "EP":
            assert abs(o - a) <= tol, (t, b, o, a)


def test_bvp_demo_trivial_branch(tmp_path):
    """bvp.auto's first run: on u = 0 the linearisation u'' = -(p1 pi)^2 u has
    nontrivial solutions at p1 = 1, 2, ...: five BPs, then UZSTOP 5.5. The BPs are the
    collocation's discrete eigenvalues (NTST = 20, NCOL = 4), within 1e-7 of the
    integers (3e-8 at p1 = 5), and the steps of 0.2 end on them to within the location
    tolerance: each located BP is the step's end itself (AUTO's LCSPBV takes it when
    its first secant correction is below the tolerance), at 1.0000001 .. 5.0000005 as
    in AUTO's b-file."""
    d = demo(tmp_path, "bvp")
    c = read_constants(d / "c.bvp")
    r = run(d / "c.bvp", e="bvp", sv="bvp", verbose=False)
    assert r.status == "ok"
    ref = auto_rows("bvp", "b.bvp")
    compare(ours((r, 1)), [x for x in ref if x[1] == 1], location_tolerance(c))
    auto_bps = [a for t, b, a in ref if t == "BP" and b == 1]
    bps = [s.par[0] for s in r.specials if s.ty == "BP"]
    assert len(bps) == len(auto_bps) == 5
    for k, (bp, a) in enumerate(zip(bps, auto_bps)):
        assert bp == pytest.approx(k + 1, abs=location_tolerance(c))
        assert bp == pytest.approx(a, abs=1e-9)           # AUTO's step end, 10 digits


@pytest.mark.slow
def test_bvp_demo_switched_branches(tmp_path):
    """bvp.auto: ISW = -1 at each BP, both directions, DSMAX = 10, UZR on p2 = int u1:
    every UZ (and the two folds) of AUTO's b.bvp, in order, on branch 2."""
    d = demo(tmp_path, "bvp")
    c = read_constants(d / "c.bvp")
    r = run(d / "c.bvp", e="bvp", sv="bvp", verbose=False)
    runs = [(r, 1)]
    for bp in [s for s in r.specials if s.ty == "BP"]:
        for ds in (c["DS"], -c["DS"]):
            q = run(d / "c.bvp", e="bvp", s="bvp", IRS=bp.lab, ISW=-1, DSMAX=10, DS=ds,
                    UZR={2: [-6.0, -3.0, 3.0, 6.0]}, UZSTOP={1: [0.0, 5.5], 2: [-9.0, 9.0]},
                    sv="sw", verbose=False)
            assert q.status == "ok"
            runs.append((q, 1))
    compare(ours(*runs), auto_rows("bvp", "b.bvp"), location_tolerance(c, DSMAX=10), uz_targets=(0.0,))


def bratu_theta(lam: float, branch: int) -> float:
    """theta of the 1-D Bratu solution u = -2 ln(cosh(theta (t - 1/2) / 2) / cosh(theta/4))
    of u'' + lam e^u = 0, u(0) = u(1) = 0: lam = theta^2 / (2 cosh^2(theta / 4)); the
    lower branch has theta below the fold's theta_c (theta tanh(theta/4) = 4)."""
    mpmath.mp.dps = 30
    g = lambda th: th ** 2 / (2 * mpmath.cosh(th / 4) ** 2) - lam
    return float(mpmath.findroot(g, 1.0 if branch == 0 else 8.0))


def test_pvl_demo_and_bratu_closed_form(tmp_path):
    """pvl (the 1-D Bratu problem, with a PVLS writing GETP measures into PAR(2..5)):
    AUTO's UZ, LP, UZ, UZ, UZ in order within the location tolerance; the fold at the
    closed form's lam_c = theta_c^2 / (2 cosh^2(theta_c/4)) (theta_c tanh(theta_c/4) = 4)
    to the discretisation's accuracy (NTST = 5: AUTO 3.7e-8 off, ours the same); the
    PVLS values u2(0) = theta tanh(theta/4) at the UZ points lam = 2 of both branches."""
    d = demo(tmp_path, "pvl")
    c = read_constants(d / "c.pvl")
    r = run(d / "c.pvl", e="pvl", sv="pvl", verbose=False)
    assert r.status == "ok"
    compare(ours((r, 1)), auto_rows("pvl", "b.pvl"), location_tolerance(c))
    mpmath.mp.dps = 30
    th_c = float(mpmath.findroot(lambda th: th * mpmath.tanh(th / 4) - 4, 4.8))
    lam_c = th_c ** 2 / (2 * math.cosh(th_c / 4) ** 2)
    assert r("LP1").par[0] == pytest.approx(lam_c, abs=1e-7)
    uz = [s for s in r.specials if s.ty == "UZ" and abs(s.par[0] - 2.0) < 1e-6]
    assert len(uz) == 2
    for branch, s in enumerate(uz):
        th = bratu_theta(2.0, branch)
        assert s.par[3] == pytest.approx(th * math.tanh(th / 4), rel=1e-5)   # GETP('BV0', 2)
        assert s.par[2] == pytest.approx(-s.par[3], rel=1e-5)                # GETP('MIN', 2)


def test_non_demo(tmp_path):
    d = demo(tmp_path, "non")
    c = read_constants(d / "c.non")
    r = run(d / "c.non", e="non", sv="non", verbose=False)
    assert r.status == "ok"
    compare(ours((r, 1)), auto_rows("non", "b.non"), location_tolerance(c))


def test_ext_demo(tmp_path):
    """ext: BPs of the trivial branch on a coarse mesh (NTST = 8, NCOL = 2: the discrete
    BPs lie off the integers), then the branch from BP3 with NCOL = 3 to UZSTOP 6."""
    d = demo(tmp_path, "ext")
    c = read_constants(d / "c.ext")
    r1 = run(d / "c.ext", e="ext", sv="ext", verbose=False)
    r2 = run(d / "c.ext", e="ext", s="ext", IRS=r1("BP3").lab, ISW=-1, NCOL=3, sv="ext2",
             verbose=False)
    assert r1.status == r2.status == "ok"
    compare(ours((r1, 1), (r2, 1)), auto_rows("ext", "b.ext"), location_tolerance(c))


def test_lin_demo(tmp_path):
    """lin: the linear eigenvalue problem; BPs at the discrete eigenvalues, the
    eigenfunction branch from BP1 (NTST = 6, UZ at int u1^2 = 1), then a continuation
    in (p1, p2) from that UZ to the A1 = 5 end point."""
    d = demo(tmp_path, "lin")
    c = read_constants(d / "c.lin")
    r1 = run(d / "c.lin", e="lin", sv="lin", verbose=False)
    r2 = run(d / "c.lin", e="lin", s="lin", IRS=r1("BP1").lab, NTST=6, ISW=-1, DSMAX=0.5,
             A1=5.0, sv="lin2", verbose=False)
    r3 = run(d / "c.lin", e="lin", s="lin2", IRS=r2("UZ1").lab, ICP=[1, 2], NTST=5, ISW=1,
             DSMAX=0.5, A1=5.0, UZR={3: 1.0}, sv="lin3", verbose=False)
    assert r1.status == r2.status == r3.status == "ok"
    compare(ours((r1, 1), (r2, 1)), auto_rows("lin", "b.lin"), location_tolerance(c, DSMAX=0.5))
    compare(ours((r3, 1)), auto_rows("lin", "b.2p"), location_tolerance(c, DSMAX=0.5))
    # On the eigenfunction branch p1 stays the first eigenvalue.
    assert r2("UZ1").par[0] == pytest.approx(1.0, abs=1e-6)


def test_bvp_needs_its_conditions(tmp_path):
    """NBC conditions without bcnd: a clear error naming what is missing."""
    d = demo(tmp_path, "non")
    text = (d / "non.py").read_text().replace("def bcnd", "def _no_bcnd")
    (d / "non.py").write_text(text)
    r = run(d / "c.non", e="non", sv="non", verbose=False)
    assert "NBC = 3 boundary conditions but no bcnd(u0, u1, par)" in r.status


def test_nep_demo(tmp_path):
    """nep: the BP of the nonlinear eigenvalue problem at p1 = p2 = pi^2 / 2 (ours to
    1e-8, AUTO's 4.9348023388), UZ on p1 = 2, 4, ... on both branches."""
    d = demo(tmp_path, "nep")
    c = read_constants(d / "c.nep.1")
    r = run(d / "c.nep.1", e="nep", sv="nep", verbose=False)
    runs = [(r, 1)]
    for bp in [s for s in r.specials if s.ty == "BP"]:
        runs.append((run(d / "c.nep.2", e="nep", s="nep", IRS=bp.lab, sv="nep2",
                         verbose=False), 1))
    assert all(q.status == "ok" for q, _ in runs)
    compare(ours(*runs), auto_rows("nep", "b.nep"), location_tolerance(c))
    assert r("BP1").par[0] == pytest.approx(math.pi ** 2 / 2, abs=1e-8)


@pytest.mark.slow
def test_obv_demo(tmp_path):
    """obv: continuation of an optimality system (NBC = 6, NINT = 5: eight free
    parameters), three BPs; the switched branch; restarts with other free parameters
    (ICP changed, the stored direction then not reused) and fewer integral conditions
    taken from the same icnd (the first NINT). The multipliers that stay at 0 on the
    first branch give no UZ (AUTO: none either)."""
    d = demo(tmp_path, "obv")
    c = read_constants(d / "c.obv")
    r1 = run(d / "c.obv", e="obv", sv="obv", verbose=False)
    r2 = run(d / "c.obv", e="obv", s="obv", IRS=r1("BP1").lab, ISW=-1, NMX=5, sv="o1",
             verbose=False)
    r3 = run(d / "c.obv", e="obv", s="o1", IRS=r2.specials[-1].lab,
             ICP=[10, 1, 2, 17, 18, 13, 14, 15], ISW=1, NMX=100, sv="o2", verbose=False)
    r4 = run(d / "c.obv", e="obv", s="o2", IRS=r3("UZ2").lab,
             ICP=[10, 1, 2, 3, 18, 13, 14, 15], ISW=1, NMX=25, sv="o3", verbose=False)
    for r, bfile in ((r1, "b.obv"), (r2, "b.1"), (r3, "b.2"), (r4, "b.3")):
        assert r.status == "ok"
        compare(ours((r, 10)), auto_rows("obv", bfile), location_tolerance(c))


def test_tim_demo(tmp_path):
    """tim: NDIM = 10, NTST = 100, fixed steps (IADS = 0) to NMX = 10: the end point is
    then determined by the steps alone, and agrees with AUTO's to the Newton tolerance."""
    d = demo(tmp_path, "tim")
    c = read_constants(d / "c.tim")
    r = run(d / "c.tim", e="tim", sv="tim", verbose=False)
    assert r.status == "ok"
    ref = auto_rows("tim", "b.tim")
    assert [(s.ty, s.br) for s in r.specials] == [(t, b) for t, b, _ in ref]
    assert r.specials[-1].par[0] == pytest.approx(ref[-1][2], abs=10 * c["EPSL"])


@pytest.mark.slow
def test_fsh_demo(tmp_path):
    """fsh: a travelling wave of Fisher's equation as a connecting orbit (the saddle's
    eigenvector in PAR(12..14), stpnt setting PAR at t = 0 and reading it at later t);
    continued in the period to 200, then in the wave speed with an integral phase
    condition added at the restart (NINT = 1)."""
    d = demo(tmp_path, "fsh")
    c = read_constants(d / "c.fsh")
    r1 = run(d / "c.fsh", e="fsh", sv="f0", verbose=False)
    r2 = run(d / "c.fsh", e="fsh", s="f0", IRS=r1("UZ4").lab, ICP=[2, 11, 12, 13, 14], NINT=1,
             DS=-c["DS"], UZR={2: [1.0, 2.0, 3.0, 5.0, 10.0]}, UZSTOP={2: 0.0}, A0=-0.1,
             sv="fsh", verbose=False)
    assert r1.status == r2.status == "ok"
    compare(ours((r1, 11)), auto_rows("fsh", "b.0"), location_tolerance(c), uz_targets=(200.0,))
    compare(ours((r2, 2)), auto_rows("fsh", "b.fsh"), location_tolerance(c))


def test_spb_demo_first_runs(tmp_path):
    """spb: a singularly perturbed BVP continued in rl to 1, then in eps down to 1e-5
    (UZ at each decade, AUTO's within EPSS of ours)."""
    d = demo(tmp_path, "spb")
    c = read_constants(d / "c.spb.1")
    r0 = run(d / "c.spb.0", e="spb", sv="s0", verbose=False)
    r1 = run(d / "c.spb.1", e="spb", s="s0", IRS=r0.specials[-1].lab, sv="s1", verbose=False)
    assert r0.status == r1.status == "ok"
    compare(ours((r0, 3)), auto_rows("spb", "b.0"), location_tolerance(c))
    compare(ours((r1, 2)), auto_rows("spb", "b.1"), location_tolerance(c))


@pytest.mark.slow
def test_spb_demo_continuation_in_gamma(tmp_path):
    """spb, runs 3 and 4: NTST = 200, NPR = 1 (every point labelled, the restart's first
    one too, as AUTO), then 700 steps in gamma with DSMAX = 1000 to the UZSTOP -2.2."""
    d = demo(tmp_path, "spb")
    c3 = read_constants(d / "c.spb.3")
    r0 = run(d / "c.spb.0", e="spb", sv="s0", verbose=False)
    run(d / "c.spb.1", e="spb", s="s0", IRS=r0.specials[-1].lab, sv="s1", verbose=False)
    r2 = run(d / "c.spb.2", e="spb", s="s1", IRS="UZ2", sv="s2", verbose=False)
    r3 = run(d / "c.spb.3", e="spb", s="s2", IRS=r2.specials[-1].lab, sv="s3", verbose=False)
    assert r2.status == r3.status == "ok"
    ref = [r for r in branch_rows(autoref("spb") / "b.2.gz") if r.lab]
    # Run 3: NPR = 1 labels every one of its 15 points, the first (the restart) included.
    assert [s.ty for s in r2.specials] == [type_name(r.ty) for r in ref[:15]]
    assert r3.specials[-1].ty == "UZ" and type_name(ref[-1].ty) == "UZ"
    assert abs(r3.specials[-1].par[0] - ref[-1].values[0]) <= location_tolerance(c3)


def test_um2_demo(tmp_path):
    """um2: orbits between two circles (NBC = 3, the period free): the outer radius to
    0.6, eps down to 0.1, then the start angle theta from 0.25 round to the UZSTOP 1.25
    with NPR = 1."""
    d = demo(tmp_path, "um2")
    c = read_constants(d / "c.um2")
    r1 = run(d / "c.um2", e="um2", sv="u1", verbose=False)
    r2 = run(d / "c.um2", e="um2", s="u1", IRS=r1.specials[-1].lab, ICP=["eps", "Period"],
             DS=-c["DS"], DSMAX=1.0, UZSTOP={"eps": 0.1}, sv="u2", verbose=False)
    r3 = run(d / "c.um2", e="um2", s="u2", IRS=r2.specials[-1].lab, ICP=["theta", "Period"],
             NPR=1, DS=c["DS"], DSMIN=1e-5, DSMAX=1.0, UZSTOP={"theta": [1.25, -0.75]},
             sv="u3", verbose=False)
    assert r1.status == r2.status == r3.status == "ok"
    compare(ours((r1, 11)), auto_rows("um2", "b.1"), location_tolerance(c, DSMAX=10.0))
    compare(ours((r2, 2)), auto_rows("um2", "b.2"), location_tolerance(c, DSMAX=1.0))
    # Every point of the last run is labelled (NPR = 1); the run ends at theta = 1.25.
    last = [r for r in ours((r3, 1)) if r[0] != ""]
    ref = [r for r in auto_rows("um2", "b.3") if r[0] != ""]
    compare(last, ref, location_tolerance(c, DSMAX=1.0), uz_targets=(1.25,))


def test_int_demo_fold_locus(tmp_path):
    """int: the LP of a BVP with a boundary and an integral condition, then its locus in
    (p1, p2) as AUTO's script runs it: a generating run from the LP (five points, the
    null vector's norm free, ending at an EP of the locus, code 59, on a new branch),
    restarted to follow the locus: AUTO's UZ p1 = 3 (code -54) at p2 = 7.90922 is ours
    within the tolerance. The generating run starts, as AUTO's STPNBL, from v = 0 and the
    norm int |v|^2 = 0 and leaves the LP's branch along v (STDRBV at the crossing), so the
    null vector's norm grows with the arclength as AUTO's (6.6e-3 after five points) and
    weighs v in the locus's arclength as AUTO's does: every row of the locus is AUTO's,
    the EP at NMX = 40 too (p1 = 1.36979; with v scaled to int |v|^2 = 1 it lay at
    p1 = 2.09, a UZ later)."""
    d = demo(tmp_path, "int")
    c = read_constants(d / "c.int")
    tol = location_tolerance(c)
    r1 = run(d / "c.int", e="int", sv="int", verbose=False)
    compare(ours((r1, 1)), auto_rows("int", "b.int"), tol, uz_targets=(1.0, 3.0))
    gen = run(d / "c.int", e="int", s="int", IRS=r1("LP1").lab, ICP=[1, 2], ISW=2, sv="gen",
              verbose=False)
    assert [(s.code, s.br, s.lab) for s in gen.specials] == [(59, 2, 8)]
    assert gen.specials[0].par[0] == pytest.approx(r1("LP1").par[0], abs=tol)
    lp = run(d / "c.int", e="int", s="gen", IRS=8, ICP=[1, 2], ISW=2, sv="lp", verbose=False)
    assert lp.status == "ok"
    ref = [r for r in branch_rows(autoref("int") / "b.lp") if r.lab]
    got = [s for s in lp.specials]
    assert (got[0].code, got[0].br) == (ref[0].ty, ref[0].br) == (-54, 2)
    assert abs(got[0].par[1] - ref[0].values[-1]) <= tol       # p2 at the UZ p1 = 3
    assert (got[-1].code, got[-1].br) == (ref[-1].ty, ref[-1].br) == (59, 2)
    # Each step of both engines is its own point's correction to EPSL = EPSU (relative:
    # EPSU (1 + max |U|) absolute on the state, max |U| from 9.15 at the LP to 16.4 at
    # the EP), from the row before: the rows' difference grows by at most twice that (two
    # engines) a step, row k within 2 k EPSU (1 + max |U|).
    eps = c["EPSU"]
    assert c["EPSL"] == eps
    # int |v|^2 at the generating run's end (AUTO's PAR(4) there, kept in every record of
    # its locus run: autoref s.lp) is the square of the arclength s its four steps went
    # (v grows as s times the unit null vector: 1e-4 after a step of DS = 0.01), so it
    # moves by 2 s times the steps' error: within 2 s 8 EPSU (1 + max |U|) of AUTO's,
    # 2.0e-3 relative (measured 1.7e-5).
    auto_norm = read_s(autoref("int") / "s.lp")[0].par[3]
    s_gen = math.sqrt(auto_norm)
    u_gen = max(np.max(np.abs(r.u)) for r in gen.rows)
    assert abs(gen.specials[0].par[3] - auto_norm) <= 2 * s_gen * 8 * eps * (1 + u_gen)
    # Row by row (PAR(1), PAR(2)) from the restart (measured: 4.9e-5 at row 10 against
    # 2.0e-4, 2.1e-6 at row 40 against 1.4e-3; 0.72 at the EP with v of unit norm). The
    # bound must grow with k: one step's 2 EPSU (1 + max |U|) = 2.0e-5, not summed, is
    # exceeded at rows 10-12 (4.8e-5: the difference jumps there, then shrinks again).
    rows = [r for r in lp.rows if r.br == 2]
    auto = branch_rows(autoref("int") / "b.lp")
    assert len(rows) == len(auto) == 40
    for k, (r, a) in enumerate(zip(rows, auto), start=1):
        bound = 2 * k * eps * (1 + np.max(np.abs(r.u)))
        assert abs(r.par[0] - a.values[0]) <= bound and abs(r.par[1] - a.values[-1]) <= bound


BRATU_A = '''
import numpy as np
def func(u, par):
    return np.array([u[1], -par[0] * np.exp(u[0])])
def stpnt(u, par, t=0.0):
    par[:2] = 0.0
    u[:] = 0.0
def bcnd(u0, u1, par):
    return np.array([u0[0] - par[1], u1[0] - par[1]])
'''


def test_fold_locus_closed_form(tmp_path):
    """u'' + lam e^u = 0, u(0) = u(1) = a: with w = u - a this is Bratu's problem in
    lam e^a, so its folds lie on lam e^a = lam_c, exactly in the discretised problem
    too (the collocation commutes with the shift); lam_c the LP of the a = 0 branch,
    within the discretisation of Bratu's 3.5138307191. Every point of the locus, both
    ways from the LP to the UZSTOPs a = -1 and 1, satisfies it to 1e-9."""
    (tmp_path / "bra.py").write_text(BRATU_A)
    (tmp_path / "c.bra").write_text("NDIM=2, IPS=4, ICP=[1], NBC=2, NINT=0, NTST=10, NCOL=4, "
                                    "ILP=1, ISP=2, NMX=100, DS=0.1, DSMAX=0.5, EPSS=1e-6, "
                                    "UZSTOP={1: -1.0}, NPAR=2\n")
    r1 = run(tmp_path / "c.bra", e="bra", sv="bra", verbose=False)
    lam_c = r1("LP1").par[0]
    assert lam_c == pytest.approx(3.5138307191, abs=1e-7)
    gen = run(tmp_path / "c.bra", e="bra", s="bra", IRS="LP1", ICP=[1, 2], ISW=2, sv="gen",
              verbose=False)
    ends = set()
    for ds in (0.1, -0.1):
        r = run(tmp_path / "c.bra", e="bra", s="gen", IRS=gen.specials[-1].lab, ICP=[1, 2],
                ISW=2, DS=ds, UZSTOP={2: [-1.0, 1.0]}, NMX=200, sv="lp", verbose=False)
        assert r.status == "ok" and r.specials[-1].ty == "UZ"
        ends.add(round(r.specials[-1].par[1]))
        for row in r.rows:
            assert row.par[0] * math.exp(row.par[1]) == pytest.approx(lam_c, abs=1e-9)
    assert ends == {-1, 1}


@pytest.mark.slow
def test_um3_demo(tmp_path):
    """um3: orbits from a circle in z = 0 to a sphere: the outer radius to 1, eps down to
    0.01, then the start angle both ways (NPR = 1) until the period reaches 1e4, where the
    orbits approach the stable manifold: theta -> 0.4998523 and -0.5001477, AUTO's two
    UZ of b.3 (its merged, relabelled result of both runs)."""
    d = demo(tmp_path, "um3")
    c = read_constants(d / "c.um3")
    r1 = run(d / "c.um3", e="um3", sv="u1", verbose=False)
    r2 = run(d / "c.um3", e="um3", s="u1", IRS=r1.specials[-1].lab, ICP=["eps", "Period"],
             DS=-c["DS"], DSMAX=1.0, UZSTOP={"eps": 0.01}, sv="u2", verbose=False)
    assert r1.status == r2.status == "ok"
    compare(ours((r1, 11)), auto_rows("um3", "b.1"), location_tolerance(c, DSMAX=10.0))
    compare(ours((r2, 2)), auto_rows("um3", "b.2"), location_tolerance(c, DSMAX=1.0))
    ends = []
    for ds in (c["DS"], -c["DS"]):
        p = run(d / "c.um3", e="um3", s="u2", IRS=r2.specials[-1].lab, ICP=["theta", "Period"],
                NPR=1, DS=ds, DSMIN=1e-5, DSMAX=1.0,
                UZSTOP={"theta": [1.25, -0.75], "Period": 1e4}, sv="u3", verbose=False)
        assert p.status == "ok" and p.specials[-1].ty == "UZ"
        # AUTO's own two UZ are 0.56 and 0.043 above 1e4 (the period grows fast along
        # the arclength, THL(11) = 0, and AUTO stops locating on EPSS): ours closer.
        assert abs(p.specials[-1].par[10] - 1e4) < 0.043
        ends.append(p.specials[-1].par[0])
    ref = [r.values[0] for r in branch_rows(autoref("um3") / "b.3")
           if type_name(r.ty) == "UZ"]
    assert len(ref) == 2
    np.testing.assert_allclose(sorted(ends), sorted(ref), atol=location_tolerance(c, DSMAX=1.0))


def test_stw_demo(tmp_path):
    """stw: a travelling wave from an approximate start (stpnt's profile does not satisfy
    the eigenvector conditions: AUTO corrects it on the first step, as we do): NBC = 10,
    NINT = 1, ten free parameters; UZ at PAR(1) = 1 and EP at NMX = 20 as AUTO's (its
    first point PAR(1) = 0.0071658 is ours to 1e-5)."""
    d = demo(tmp_path, "stw")
    c = read_constants(d / "c.stw")
    r = run(d / "c.stw", e="stw", sv="stw", verbose=False)
    assert r.status == "ok"
    compare(ours((r, 1)), auto_rows("stw", "b.stw"), location_tolerance(c), uz_targets=(1.0,))
    ref = branch_rows(autoref("stw") / "b.stw")
    assert r.rows[1].values[0] == pytest.approx(ref[1].values[0], abs=1e-5)


def test_ezp_demo(tmp_path):
    """ezp: Bratu's problem in complex variables (NDIM = 4 reals); the real fold is a BP
    (3.5138307, AUTO's 3.5138307570) into complex solutions, followed both ways (ISW = -1)
    to UZ at lam = 5 and 6. The second switch restarts from the records of both earlier
    runs, as the script's `ezp + run(...)` hands AUTO: branch 3, labels 8 and 9."""
    d = demo(tmp_path, "ezp")
    c = read_constants(d / "c.ezp")
    r = run(d / "c.ezp", e="ezp", sv="ezp", verbose=False)
    q1 = run(d / "c.ezp", e="ezp", s="ezp", IRS=r("BP1").lab, ISW=-1, sv="q1", verbose=False)
    (d / "s.both").write_text((d / "s.ezp").read_text() + (d / "s.q1").read_text())
    q2 = run(d / "c.ezp", e="ezp", s="both", IRS=r("BP1").lab, ISW=-1, DS=-c["DS"], sv="q2",
             verbose=False)
    assert r.status == q1.status == q2.status == "ok"
    compare(ours((r, 1), (q1, 1), (q2, 1)), auto_rows("ezp", "b.ezp"), location_tolerance(c),
            uz_targets=(2.0, 5.0, 6.0))
    assert [s.lab for s in q2.specials] == [8, 9]
    # The complex branch: Im u1 is nonzero on it (the real branch has none).
    assert np.max(np.abs(q2.specials[0].U[:, 1])) > 0.1


BRATU_2 = '''
import numpy as np
def func(u, par):
    return np.array([u[1], -par[0] * np.exp(u[0])])
def stpnt(u, par, t=0.0):
    par[0] = 0.0
    u[:] = 0.0
def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0]])
'''

BRATU_3 = '''
import numpy as np
def func(u, par):
    return np.array([u[1], -par[0] * np.exp(u[0]), u[0]])
def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0], u0[2]])
def pvls(u, par):
    par[1] = u.bv1(3)
'''


def test_restart_with_more_components(tmp_path):
    """A BVP restarted from a solution with fewer components (AUTO's READBV fills the
    others with 0, as pcl's connecting orbits start from a periodic orbit): Bratu's
    problem with u3' = u1, u3(0) = 0 appended, restarted at lam = 1 from the plain
    problem's solution; at the UZ lam = 2 u3(1) = int_0^1 u1 dt, against the closed form
    u1 = -2 ln(cosh(theta (t - 1/2) / 2) / cosh(theta / 4)) (theta on the lower branch)."""
    (tmp_path / "b2.py").write_text(BRATU_2)
    (tmp_path / "b3.py").write_text(BRATU_3)
    (tmp_path / "c.b2").write_text("NDIM=2, IPS=4, ICP=[1], NBC=2, NINT=0, NTST=10, NCOL=4, "
                                   "ILP=0, ISP=0, NMX=100, DS=0.1, DSMAX=0.5, NPAR=2, "
                                   "UZSTOP={1: 1.0}\n")
    (tmp_path / "c.b3").write_text("NDIM=3, IPS=4, ICP=[1, 2], NBC=3, NINT=0, NTST=10, NCOL=4, "
                                   "ILP=0, ISP=0, NMX=100, DS=0.1, DSMAX=0.5, NPAR=2, "
                                   "UZSTOP={1: 2.0}\n")
    r2 = run(tmp_path / "c.b2", e="b2", sv="b2", verbose=False)
    r3 = run(tmp_path / "c.b3", e="b3", s="b2", IRS=r2.specials[-1].lab, sv="b3", verbose=False)
    assert r2.status == r3.status == "ok" and r3.specials[-1].ty == "UZ"
    uz = r3.specials[-1]
    th = bratu_theta(2.0, 0)
    mpmath.mp.dps = 20
    exact = float(mpmath.quad(lambda t: -2 * mpmath.log(mpmath.cosh(th * (t - 0.5) / 2)
                                                       / mpmath.cosh(th / 4)), [0, 1]))
    assert uz.par[1] == pytest.approx(exact, rel=1e-6)
    assert uz.U.shape[1] == 3


BRATU_TWICE = '''
import numpy as np
def func(u, par):
    return np.array([u[1], -par[0] * np.exp(u[0]), u[3], -par[0] * np.exp(u[2])])
def stpnt(u, par, t=0.0):
    u[2:4] = u[0:2]              # the restart's new components: a copy of the stored ones
def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0], u0[2], u1[2]])
'''


def test_restart_extends_the_system_through_stpnt(tmp_path):
    """A BVP restarted with more components than the stored solution calls stpnt at each
    stored point with the stored values in place and keeps what it puts in the new
    components (AUTO's READBV: c2c's stpnt copies the cycle and its eigenfunction into
    U(7:12) when NDIM grows from 6 to 12). Bratu's problem, restarted as two copies of
    itself: the restart's first point is the stored solution twice, its L2-norm sqrt(2)
    times the stored one (with zeros in the new components the start would not be a
    solution and its norm the stored one)."""
    (tmp_path / "b2.py").write_text(BRATU_2)
    (tmp_path / "b4.py").write_text(BRATU_TWICE)
    (tmp_path / "c.b2").write_text("NDIM=2, IPS=4, ICP=[1], NBC=2, NINT=0, NTST=10, NCOL=4, "
                                   "ILP=0, ISP=0, NMX=100, DS=0.1, DSMAX=0.5, NPAR=2, "
                                   "UZSTOP={1: 1.0}\n")
    (tmp_path / "c.b4").write_text("NDIM=4, IPS=4, ICP=[1], NBC=4, NINT=0, NTST=10, NCOL=4, "
                                   "ILP=0, ISP=0, NMX=3, DS=0.1, DSMAX=0.5, NPAR=2\n")
    r2 = run(tmp_path / "c.b2", e="b2", sv="b2", verbose=False)
    r4 = run(tmp_path / "c.b4", e="b4", s="b2", IRS=r2.specials[-1].lab, sv="b4", verbose=False)
    assert r4.status == "ok"
    stored, first = r2.rows[-1], r4.rows[0]
    assert first.par[0] == pytest.approx(1.0, abs=1e-12)
    assert first.values[1] == pytest.approx(math.sqrt(2) * stored.values[1], rel=1e-9)  # L2


GROWTH = '''
import numpy as np
def func(u, par):
    return np.array([par[1] * u[0]])
def stpnt(u, par, t=0.0):
    par[0], par[1] = 0.0, -1.0
    u[:] = 0.0
def bcnd(u0, u1, par):
    return np.array([u0[0] - u1[0]])
def icnd(u, uold, udot, upold, par):
    return np.array([u[0] - par[0]])
'''


def test_start_direction_without_the_first_parameter(tmp_path):
    """u' = p2 u, u(0) = u(1), int u dt = p1: the trivial branch u = 0, p1 = 0 moves in
    p2 alone, so the start direction has no PAR(ICP(1)) component (as the eigenfunction
    branch of AUTO's c2c demo, ICP = [11, 12, 10], moves PAR(12) alone) and must be the
    Jacobian's null vector, not a solve bordered by PAR(ICP(1)). The constants u = c,
    p1 = c cross it at p2 = 0: a BP."""
    (tmp_path / "gro.py").write_text(GROWTH)
    (tmp_path / "c.gro").write_text("NDIM=1, IPS=4, ICP=[1, 2], NBC=1, NINT=1, NTST=5, NCOL=3, "
                                    "ILP=0, ISP=2, NMX=50, DS=0.1, DSMAX=0.2, NPAR=2, "
                                    "UZSTOP={2: 1.0}\n")
    r = run(tmp_path / "c.gro", e="gro", sv="gro", verbose=False)
    tol = 2e-4 * (1 + math.sqrt(0.1 * 0.2))
    assert r.status == "ok" and [s.ty for s in r.specials] == ["EP", "BP", "UZ"]
    assert abs(r("BP1").par[1]) <= tol and r("UZ1").par[1] == pytest.approx(1.0)
    assert all(abs(row.par[0]) <= 1e-9 for row in r.rows)


def test_isw_minus_one_at_a_regular_point_continues_the_branch(tmp_path):
    """A general BVP restarted with ISW = -1 at a label that is not a BP (AUTO's CNRLBV
    takes IPERP = 1 whenever IRS != 0 and ISW < 0: STDRBV's null vector of the Jacobian,
    PAR(ICP(1))-dot > 0 or else the next free parameter's) continues the one branch through
    the point; AUTO's p2c demo restarts its eigenfunction problem so from a UZ of cycles
    with the ISW = -1 of an earlier run. u' = p2 u, u(0) = u(1), int u dt = p1 from its UZ
    at p2 = 1: the trivial branch u = 0, p1 = 0, p2 increasing (p1-dot is 0) to the UZSTOP
    at p2 = 2, with no BP (the one at p2 = 0 lies behind)."""
    (tmp_path / "gro.py").write_text(GROWTH)
    (tmp_path / "c.gro").write_text("NDIM=1, IPS=4, ICP=[1, 2], NBC=1, NINT=1, NTST=5, NCOL=3, "
                                    "ILP=0, ISP=2, NMX=50, DS=0.1, DSMAX=0.2, NPAR=2, "
                                    "UZSTOP={2: 1.0}\n")
    r = run(tmp_path / "c.gro", e="gro", sv="gro", verbose=False)
    r2 = run(tmp_path / "c.gro", e="gro", s="gro", IRS=r("UZ1").lab, ISW=-1,
             UZSTOP={2: 2.0}, sv="gro2", verbose=False)
    assert r2.status == "ok" and [s.ty for s in r2.specials] == ["UZ"]
    assert r2("UZ1").par[1] == pytest.approx(2.0)
    p2 = [row.par[1] for row in r2.rows]
    assert all(b > a for a, b in zip(p2, p2[1:]))
    assert all(abs(row.par[0]) <= 1e-9 for row in r2.rows)


STIFF = '''
import numpy as np
def func(u, par):
    return np.array([par[1] * u[0], -par[1] * u[1]])
def stpnt(u, par, t=0.0):
    par[0], par[1] = 0.5, 40.0
    u[:] = 0.0
def bcnd(u0, u1, par):
    return np.array([u1[0] - par[0] * np.exp(par[1]) * u0[0], u0[1]])
'''


def test_branch_point_test_of_a_stiff_bvp():
    """u1' = T u1, u2' = -T u2 with T = 40, u1(1) = c e^T u1(0), u2(0) = 0: the trivial
    branch u = 0 in c has one BP, at c = 1 (where u1 = e^(T t) u1(0) solves it), up to the
    collocation's growth factor over the 40 intervals (the (4, 4) Pade approximant of
    e^(hT) at hT = 1, 2e-8 relative per interval). Eliminating the interior onto u(0) is
    single shooting over growth e^40 (and decay e^-40): the reduced matrix's rounding,
    eps |M_RI| |X| ~ 1e2, exceeds its smallest singular value, so the test's sign comes
    from the sparse factorisations of the bordered Jacobian and its interior block."""
    import tempfile
    from washer.cont.systems import general_bvp
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "stiff.py").write_text(STIFF)
        (tmp / "c.stiff").write_text("NDIM=2, IPS=4, ICP=[1], NBC=2, NINT=0, NTST=40, NCOL=4, "
                                     "ILP=0, ISP=2, NMX=50, DS=0.1, DSMAX=0.1, NPAR=2, "
                                     "UZSTOP={1: 1.5}\n")
        seen = []
        orig = general_bvp.BoundaryValueProblem._schur_unreliable

        def spy(self, *a):
            seen.append(orig(self, *a))
            return seen[-1]
        general_bvp.BoundaryValueProblem._schur_unreliable = spy
        try:
            r = run(tmp / "c.stiff", e="stiff", sv="stiff", verbose=False)
        finally:
            general_bvp.BoundaryValueProblem._schur_unreliable = orig
    assert r.status == "ok" and [s.ty for s in r.specials] == ["EP", "BP", "UZ"]
    assert r("BP1").par[0] == pytest.approx(1.0, abs=1e-5)
    assert seen and all(seen)


def test_permutation_sign():
    """The sign of a permutation (the factorisations' row and column orders) is the
    determinant of its matrix."""
    from washer.cont.linalg import permutation_sign
    rng = np.random.default_rng(3)
    for n in (1, 2, 5, 12):
        for _ in range(5):
            p = rng.permutation(n)
            assert permutation_sign(p) == round(np.linalg.det(np.eye(n)[p]))


@pytest.mark.slow
def test_man_demo(tmp_path):
    """man: the Lorenz stable manifold grown as orbits from a circle around the origin
    (NBC = 7, NINT = 1: int |f| dt = PAR(12)): AUTO's five UZ on PAR(12) = 10 .. 150,
    PAR(11) within the tolerance (AUTO's own to ~1e-9), then the circle's angle PAR(5)
    from the UZ 25 orbit to the UZSTOP 1.1 with NPR = 2 outputs (~3 min)."""
    d = demo(tmp_path, "man")
    c0 = read_constants(d / "c.man.0")
    r0 = run(d / "c.man.0", e="man", sv="m0", verbose=False)
    assert r0.status == "ok"
    compare(ours((r0, 11)), auto_rows("man", "b.0"), location_tolerance(c0))
    r1 = run(d / "c.man.1", e="man", s="m0", IRS=r0("UZ2").lab, sv="m1", verbose=False)
    assert r1.status == "ok"
    ref = [r for r in branch_rows(autoref("man") / "b.1") if r.lab]
    assert r1.specials[-1].ty == type_name(ref[-1].ty) == "UZ"
    assert r1.specials[-1].par[4] == pytest.approx(1.1, abs=1e-9)


def test_the_a1_window_and_the_row_share_one_solution_per_point(tmp_path, monkeypatch):
    """With an A0..A1 window the runner measures each point's Solution for the window
    (STPLBV) and writes the same Solution to the b-row: one evaluation per regular
    point, and the rows the same as those of a run without the window."""
    from washer.cont.systems.general_bvp import BoundaryValueProblem
    d = demo(tmp_path, "lin")
    r1 = run(d / "c.lin", e="lin", sv="lin", verbose=False)
    kw = dict(e="lin", s="lin", IRS=r1("BP1").lab, NTST=6, ISW=-1, DSMAX=0.5, verbose=False)
    plain = run(d / "c.lin", sv="lin2", **kw)
    calls = []
    real = BoundaryValueProblem.solution

    def counted(self, x, tangent):
        calls.append(1)
        return real(self, x, tangent)
    monkeypatch.setattr(BoundaryValueProblem, "solution", counted)
    windowed = run(d / "c.lin", A1=1e6, sv="lin3", **kw)      # a window that never ends it
    assert windowed.status == plain.status == "ok"

    def data_rows(name):
        return [ln for ln in (tmp_path / name).read_text().splitlines()
                if ln.split() and ln.split()[0].lstrip("-").isdigit() and ln.split()[0] != "0"]
    rows = data_rows("b.lin3")
    # regular points (TY 0, RG 4, EP 9, MX -9) once; a located special point twice (its
    # info is evaluated between the window's check and the row, which drops the kept one)
    special = sum(1 for r in rows if int(r.split()[2]) not in (0, 4, 9, -9))
    assert len(rows) > 5 and len(calls) == len(rows) + special
    assert rows == data_rows("b.lin2")


def test_nag_leaves_its_located_uz_along_the_branch(tmp_path):
    """nag's heteroclinic orbits of u'' = c u' - u (1 - u)(u - a) from 0 to 1 are the one
    front u = 1 / (1 + exp(-t / sqrt 2)) for every a, with c = (1 - 2 a) / sqrt 2: the
    eigenvalues 1 / sqrt 2 at u = 0 and -1 / sqrt 2 at u = 1 and their eigenvectors
    (PAR(5)..PAR(10)) are the same for all a. The branch is the straight line (a, c(a)),
    PAR(1) moving 1 / sqrt 3 per unit of arclength (THL = 1, |(1, -sqrt 2)| = sqrt 3).
    From the UZ located at PAR(1) = 1 = RL1 the next step (DS = DSMAX = 0.05) ends the run
    EP at PAR(1) = 1 + 0.05 / sqrt 3, as AUTO-07p's (1.02887): the located point leaves
    along the secant of the location's last trial step (AUTO's CONTBV after LCSPBV). Its
    tangent, the null vector of the Jacobian bordered by the previous trial's, had cosine
    0.91 with the branch (PAR(3), PAR(4), the orbit's distances from the equilibria, are
    nearly free: 1e-9 to 4e-7 along the run) and the step landed at 1.03168; a direction
    at cosine 0.73 made every step fail down to DSMIN (MX). Tolerance: the secant of a
    trial step of 0.017 to 0.033 between points converged to EPSU = 1e-7 is within
    ~1e-5 of the branch's direction, 0.05 times that in PAR(1)."""
    copy_demo("nag", tmp_path)
    r = run(tmp_path / "c.nag", e="nag", sv="nag", verbose=False)
    assert [s.ty for s in r.specials] == ["EP", "UZ", "UZ", "EP"]
    uz, ep = r.specials[2], r.specials[3]
    assert uz.par[0] == pytest.approx(1.0, abs=1e-9)
    assert ep.par[0] == pytest.approx(1 + 0.05 / math.sqrt(3), abs=1e-6)
    assert ep.par[1] == pytest.approx((1 - 2 * ep.par[0]) / math.sqrt(2), abs=1e-6)
