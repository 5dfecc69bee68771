"""Loci of period doublings and torus bifurcations of cycles (IPS = 2, ISW = 2 from PD /
TR labels) against closed forms, and the washer's torus locus in (Omega, C_p) against
the one-parameter locations of washer.forced.

tests/data/mobius/mobius.py is a cycle (the unit circle, period 1) whose transverse
Floquet multipliers are -exp((a +- sqrt(b)) T) exactly (its docstring derives them);
scipy's integration of the variational equation confirms them in
test_mobius_multipliers_closed_form. Hence, with T = 1:
* PD where a + sqrt(b) = 0 or a - sqrt(b) = 0: the PD locus is b = a^2, and its 1:2
  resonance (both transverse multipliers at -1) is (a, b) = (0, 0);
* TR where a = 0 (b < 0), with torus angle theta = pi - sqrt(-b): the TR locus is a = 0,
  its 1:3 resonance at sqrt(-b) = pi/3 (b = -pi^2/9), 1:4 at sqrt(-b) = pi/2 (b = -pi^2/4).
The cycle does not depend on (a, b), so the located values are exact up to the location
tolerance EPSS (1 + sqrt|DS DSMAX|) in arclength (the tangent is unit in the weighted
norm, so each coordinate moves by at most that) and the collocation error of the
variational equation, h^(2 NCOL) superconvergent at the mesh points (measured 2e-12 at
NTST = 20, NCOL = 4; 1e-9 allowed).
"""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from tolerances import location_tolerance
from washer.run import run

DATA = Path(__file__).parent / "data"
COLLOCATION = 1e-9


@pytest.fixture(scope="module")
def mobius(tmp_path_factory):
    d = tmp_path_factory.mktemp("mobius")
    for f in (DATA / "mobius").iterdir():
        shutil.copy(f, d)
    return d


def labelled(res, name):
    return [r for r in res.rows if r.lab and r.ty == name]


def test_mobius_multipliers_closed_form():
    """The test problem itself: the monodromy matrix by scipy's integration of the
    variational equation against 1, exp(-2 T), -exp((a +- sqrt(b)) T)."""
    import importlib.util
    spec = importlib.util.spec_from_file_location("mobius", DATA / "mobius" / "mobius.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    for a, b in ((-0.5, -1.0), (-0.1, 0.02), (-0.3, 0.09)):
        par, u = np.zeros(12), np.zeros(4)
        mod.stpnt(u, par, 0.0)
        par[0], par[1] = a, b
        T = 2 * math.pi / par[2]

        def rhs(t, Y):
            x, P = Y[:4], Y[4:].reshape(4, 4)
            h = 1e-6
            A = np.column_stack([(mod.func(x + h * e, par) - mod.func(x - h * e, par)) / (2 * h)
                                 for e in np.eye(4)])
            return np.r_[mod.func(x, par), (A @ P).ravel()]
        sol = solve_ivp(rhs, (0, T), np.r_[u, np.eye(4).ravel()], rtol=1e-11, atol=1e-12)
        mu = np.sort_complex(np.linalg.eigvals(sol.y[4:, -1].reshape(4, 4)))
        lam = a + np.array([1, -1]) * np.sqrt(complex(b))
        want = np.sort_complex(np.r_[1, math.exp(-2 * T), -np.exp(lam * T)])
        assert mu == pytest.approx(want, abs=1e-7)


def generated(res):
    """The label of the EP a generating run ends with (AUTO: "Restart at EP label")."""
    assert res.status == "ok"
    lab = [r for r in res.rows if r.lab]
    assert [r.ty for r in lab] == ["EP"] and len(res.rows) == 5         # NMX = 5
    return lab[-1].lab


@pytest.fixture(scope="module")
def tr_locus(mobius):
    """TR1, then the locus as AUTO computes it: the generating run from TR1 (5 steps that
    scale the eigenfunction) and the locus restarted at its EP. The generating run moves
    the first parameter with the second fixed: with b first, the whole locus a = 0 would
    solve it (the cycle does not depend on b), so it runs with ICP = [a, b]."""
    one = run(mobius / "c.mobius.tr", verbose=False, sv="tr")
    assert one.status == "ok"
    gen = run(mobius / "c.mobius.trloc", verbose=False, sv="trgen", s="tr", ICP=[1, 2])
    loc = run(mobius / "c.mobius.trloc", verbose=False, sv="trloc", s="trgen",
              IRS=generated(gen))
    assert loc.status == "ok"
    return one, loc


def test_mobius_tr_point(tr_locus, mobius):
    one, _ = tr_locus
    (tr,) = labelled(one, "TR")
    assert tr.values[0] == pytest.approx(0.0, abs=location_tolerance(mobius / "c.mobius.tr"))
    # PAR(12), the torus angle the TR record carries: pi - sqrt(-b) T = pi - 1
    assert tr.par[11] == pytest.approx(math.pi - 1, abs=1e-6)


def test_mobius_tr_locus_resonances(tr_locus, mobius):
    """ICP = [b, a] from TR1 towards smaller b: a stays 0; R3 (-87) at b = -pi^2/9, R4
    (-88) at b = -pi^2/4, then the UZSTOP b = -3 (-84); PAR(12) = pi - sqrt(-b) all along."""
    _, loc = tr_locus
    tol = location_tolerance(mobius / "c.mobius.trloc")
    lab = [r for r in loc.rows if r.lab]
    assert [r.code for r in lab] == [-87, -88, -84]
    assert lab[0].values[0] == pytest.approx(-math.pi ** 2 / 9, abs=tol)
    assert lab[1].values[0] == pytest.approx(-math.pi ** 2 / 4, abs=tol)
    for r in loc.rows:
        b, a = r.values[0], r.values[-1]
        assert a == pytest.approx(0.0, abs=COLLOCATION)
        assert r.par[11] == pytest.approx(math.pi - math.sqrt(-b), abs=COLLOCATION)


def test_mobius_pd_locus(mobius):
    """PD at a = -sqrt(0.25); its locus in (a, b) passes the 1:2 resonance R2 (-76) at
    (0, 0) and follows b = a^2 on both sides, up to the UZSTOP a = 0.3 (-74)."""
    one = run(mobius / "c.mobius.pd", verbose=False, sv="pd")
    assert one.status == "ok"
    (pd,) = labelled(one, "PD")
    assert pd.values[0] == pytest.approx(-0.5, abs=location_tolerance(mobius / "c.mobius.pd"))
    gen = run(mobius / "c.mobius.pdloc", verbose=False, sv="pdgen", s="pd")
    loc = run(mobius / "c.mobius.pdloc", verbose=False, sv="pdloc", s="pdgen",
              IRS=generated(gen))
    assert loc.status == "ok"
    lab = [r for r in loc.rows if r.lab]
    assert [r.code for r in lab] == [-76, -74]
    tol = location_tolerance(mobius / "c.mobius.pdloc")
    assert lab[0].values[0] == pytest.approx(0.0, abs=tol)
    assert lab[0].values[-1] == pytest.approx(0.0, abs=tol)
    for r in loc.rows:
        a, b = r.values[0], r.values[-1]
        assert b == pytest.approx(a * a, abs=COLLOCATION)


@pytest.mark.slow
def test_washer_torus_locus_matches_one_parameter_locations(tmp_path):
    """The washer's exact stability boundary continued as a TR locus in (Omega, C_p)
    (auto_constants/c.washer.forced.tr: its generating run from the TR of
    c.washer.forced, then the locus from the generating run's EP)
    against washer.problems.forced.critical_cp, an independent route (shooting of the
    forced response with an adaptive integrator at 1e-10, its TR located in C_p alone)
    at the locus's UZ points Omega = 11 and 12 Hz: the same C_p to 1e-8 (collocation at
    NTST = 20 is superconvergent, ~1e-11 here; the shooting's own integration error is of
    that size too)."""
    from washer.problems import forced
    from washer.problems.washer import _reference_params
    root = Path(__file__).parent.parent / "auto_constants"
    for name in ("c.washer.forced", "c.washer.forced.tr"):
        shutil.copy(root / name, tmp_path)
    one = run(tmp_path / "c.washer.forced", verbose=False, sv="forced",
              UZSTOP={"C_p": [0.0, 0.12]})
    assert one.status == "ok"
    gen = run(tmp_path / "c.washer.forced.tr", verbose=False, sv="trgen", s="forced", PAR={})
    loc = run(tmp_path / "c.washer.forced.tr", verbose=False, sv="trloc", s="trgen",
              PAR={}, UZR={"Omega": [11.0]}, IRS=generated(gen))
    assert loc.status == "ok"
    uz = [r for r in loc.rows if r.lab]
    assert [r.ty for r in uz] == ["UZ", "UZ"]
    params = _reference_params()
    for r in uz:
        omega, cp = r.values[0], r.values[-1]
        want = forced.critical_cp(params.replace(Omega=omega))["C_p_exact"]
        assert cp == pytest.approx(want, abs=1e-8)


def test_mobius_tr_locus_restarts_from_its_own_point(tr_locus, mobius):
    """A restart at a point of the torus locus (its UZ at b = -3, IRS there, ISW = 2)
    continues the locus from the stored (u, v, w) and angle PAR(12): a = 0 and
    theta = pi - sqrt(-b) on to the UZSTOP b = -9. (Beyond, theta reaches 0 at
    b = -pi^2, the 1:1 resonance, where the pair meets the trivial multiplier: a triple
    multiplier 1, at which the extended system is singular; its location fails there and
    the d-file says so.)"""
    res = run(mobius / "c.mobius.trloc", verbose=False, sv="trloc2", s="trloc",
              IRS="UZ1", UZSTOP={2: -9.0})
    assert res.status == "ok"
    lab = [r for r in res.rows if r.lab]
    assert [r.code for r in lab] == [-84]
    assert res.rows[0].values[0] == pytest.approx(-3.0)
    assert lab[0].values[0] == pytest.approx(-9.0)
    for r in res.rows:
        b, a = r.values[0], r.values[-1]
        assert a == pytest.approx(0.0, abs=COLLOCATION)
        assert r.par[11] == pytest.approx(math.pi - math.sqrt(-b), abs=COLLOCATION)


def test_mobius_tr_locus_with_a_third_parameter_keeps_the_angle(tr_locus, mobius):
    """ICP = [b, a, w, PERIOD] at a restart on the torus locus (four entries: AUTO's
    INITPS frees ICP(1..4) as given): the frequency w = PAR(3) takes the angle's place,
    so theta = PAR(12) stays at its value pi - sqrt(3) from the UZ at b = -3, and the
    locus a = 0 continues with sqrt(-b) T = pi - theta and T w = 2 pi (the cycle's
    period), down to the UZSTOP b = -6. (With the angle free, as before, T would stay 1.)"""
    res = run(mobius / "c.mobius.trloc", verbose=False, sv="trloc3", s="trloc",
              IRS="UZ1", ICP=[2, 1, 3, 11], UZSTOP={2: -6.0})
    assert res.status == "ok"
    assert [r.code for r in res.rows if r.lab] == [-84]
    assert res.rows[-1].values[0] == pytest.approx(-6.0)
    # the angle as the s-file stores it (10 digits) at the UZ, located to within tol
    theta = res.rows[0].par[11]
    assert theta == pytest.approx(math.pi - math.sqrt(3.0),
                                  abs=location_tolerance(mobius / "c.mobius.trloc") + 1e-9)
    for r in res.rows:
        b, a = r.values[0], r.par[0]
        assert a == pytest.approx(0.0, abs=COLLOCATION)
        assert r.par[11] == theta
        assert math.sqrt(-b) * r.par[10] == pytest.approx(math.pi - theta, abs=1e-8)
        assert r.par[10] * r.par[2] == pytest.approx(2 * math.pi, abs=1e-8)


# ---------------------------------------------------------------- folds and recurring
# resonances: tests/data/mobius/mobius_fold.py (its docstring derives the loci), with
# AUTO-07p's runs of the same problem in tests/data/mobius_fold_auto.
AUTO_FOLD = DATA / "mobius_fold_auto"


def auto_labelled(name):
    from tests.b_rows import branch_rows
    return [(r.ty, r.values[0], r.values[-1]) for r in branch_rows(AUTO_FOLD / name) if r.lab]


@pytest.fixture(scope="module")
def fold_tr(mobius):
    """TR1 at p1 = 0.25, its generating run, and the torus locus both ways from its EP
    (DS = +0.05 first towards p2 = -1, the 1:2 resonance, as AUTO's)."""
    one = run(mobius / "c.mobius_fold.tr", verbose=False, sv="ftr")
    gen = run(mobius / "c.mobius_fold.trloc", verbose=False, sv="ftrgen", s="ftr")
    up = run(mobius / "c.mobius_fold.trloc", verbose=False, sv="ftrup", s="ftrgen",
             IRS=generated(gen))
    down = run(mobius / "c.mobius_fold.trloc", verbose=False, sv="ftrdown", s="ftrgen",
               IRS=generated(gen), DS=-0.05)
    assert one.status == up.status == down.status == "ok"
    return up, down


def check_on_torus_locus(res):
    """Every row: p1 = p2^2 and cos(theta) = cos(pi - sqrt(1 + p2)) (theta continued past
    pi is the same torus as 2 pi - theta). At the R2 point the extended system is
    singular (the PD locus, theta = pi, crosses it there: AUTO's BP): Newton converges
    only linearly, at ratio 1/2 at a simple singular point, and stops on its increment
    test, |dp| <= EPSL (1 + |p|) = 2e-7 (EPSL = 1e-7, |p| = 1): each parameter's error is
    then up to its last increment (the rest of the geometric series), and p1 - p2^2 moves
    by dp1 - 2 p2 dp2, up to 3 times that (measured: 5.4e-8 and 2.6e-7 on two step
    sequences into the point)."""
    for r in res.rows:
        p1, p2, theta = r.par[0], r.par[1], r.par[11]
        tol = 6e-7 if r.code == -86 else COLLOCATION
        assert p1 == pytest.approx(p2 * p2, abs=tol)
        assert math.cos(theta) == pytest.approx(math.cos(math.pi - math.sqrt(1 + p2)),
                                                abs=tol)


def test_mobius_fold_tr_locus_folds_and_resonances(fold_tr, mobius):
    """From TR1 away from the 1:2 resonance: the fold of the locus in p1 at (0, 0) (LP,
    85), R3 (-87) at p2 = pi^2/9 - 1, R4 (-88) at pi^2/4 - 1, the UZSTOP p2 = 2 (-84): the
    closed form to the location tolerance, AUTO-07p's labels (its LP 1.1e-7 off in p2,
    within its looser location)."""
    _, down = fold_tr
    tol = location_tolerance(mobius / "c.mobius_fold.trloc")
    lab = [r for r in down.rows if r.lab]
    assert [r.code for r in lab] == [85, -87, -88, -84]
    want = [(0.0, 0.0), (None, math.pi ** 2 / 9 - 1), (None, math.pi ** 2 / 4 - 1), (4.0, 2.0)]
    for r, (p1, p2) in zip(lab, want):
        assert r.par[1] == pytest.approx(p2, abs=tol)
        if p1 is not None:
            assert r.par[0] == pytest.approx(p1, abs=tol)
    assert lab[1].par[11] == pytest.approx(2 * math.pi / 3, abs=tol)
    assert lab[2].par[11] == pytest.approx(math.pi / 2, abs=tol)
    check_on_torus_locus(down)
    auto = auto_labelled("b.trloc_down")
    assert [t for t, *_ in auto] == [r.code for r in lab]
    for (_, a1, a2), r in zip(auto, lab):
        assert (r.par[0], r.par[1]) == pytest.approx((a1, a2), abs=2e-7)


def test_mobius_fold_tr_locus_through_the_12_resonance(fold_tr, mobius):
    """Towards p2 = -1 the angle reaches pi (R2, -86: both multipliers of the pair at -1)
    and goes on to 2 pi - theta_0: the locus turns back in the parameters there (the fold
    of the locus is the R2 point itself: one label, R2) and retraces p1 = p2^2 through
    the fold at (0, 0) (LP) and the resonances again, now at theta = 4 pi/3 (R3) and
    3 pi/2 (R4), to the UZSTOP p2 = 2. AUTO-07p labels the R2 point BP (86) and the LP,
    and none of the two resonances past pi: its test theta (theta - pi/2) (theta - 2 pi/3)
    (theta - pi) vanishes only at those angles, while the multipliers there are
    exp(+-2 pi i/3) and +-i (the closed form, p2 = pi^2/9 - 1 and pi^2/4 - 1)."""
    up, _ = fold_tr
    tol = location_tolerance(mobius / "c.mobius_fold.trloc")
    lab = [r for r in up.rows if r.lab]
    assert [r.code for r in lab] == [-86, 85, -87, -88, -84]
    r2, lp, r3, r4, uz = lab
    assert (r2.par[0], r2.par[1], r2.par[11]) == pytest.approx((1.0, -1.0, math.pi), abs=tol)
    assert (lp.par[0], lp.par[1]) == pytest.approx((0.0, 0.0), abs=tol)
    assert lp.par[11] == pytest.approx(math.pi + 1, abs=tol)
    assert r3.par[1] == pytest.approx(math.pi ** 2 / 9 - 1, abs=tol)
    assert r3.par[11] == pytest.approx(4 * math.pi / 3, abs=tol)
    assert r4.par[1] == pytest.approx(math.pi ** 2 / 4 - 1, abs=tol)
    assert r4.par[11] == pytest.approx(3 * math.pi / 2, abs=tol)
    assert uz.par[1] == pytest.approx(2.0)
    check_on_torus_locus(up)
    auto = auto_labelled("b.trloc_up")
    assert [t for t, *_ in auto] == [86, 85, -84]
    for (_, a1, a2), r in zip(auto, (r2, lp, uz)):
        assert (r.par[0], r.par[1]) == pytest.approx((a1, a2), abs=2e-7)


def test_mobius_fold_pd_locus_fold(mobius):
    """The PD locus p1 = p2^2 - 1/2 folds in p1 at (-1/2, 0): LP (75) there, then the
    UZSTOP p2 = -0.6 (-74), as AUTO-07p's b.pdloc (its LP 7.7e-7 off in p2)."""
    one = run(mobius / "c.mobius_fold.pd", verbose=False, sv="fpd")
    (pd,) = labelled(one, "PD")
    assert pd.par[0] == pytest.approx(-0.25, abs=location_tolerance(mobius / "c.mobius_fold.pd"))
    gen = run(mobius / "c.mobius_fold.pdloc", verbose=False, sv="fpdgen", s="fpd")
    loc = run(mobius / "c.mobius_fold.pdloc", verbose=False, sv="fpdloc", s="fpdgen",
              IRS=generated(gen))
    assert loc.status == "ok"
    tol = location_tolerance(mobius / "c.mobius_fold.pdloc")
    lab = [r for r in loc.rows if r.lab]
    assert [r.code for r in lab] == [75, -74]
    assert (lab[0].par[0], lab[0].par[1]) == pytest.approx((-0.5, 0.0), abs=tol)
    for r in loc.rows:
        assert r.par[0] == pytest.approx(r.par[1] ** 2 - 0.5, abs=COLLOCATION)
    auto = auto_labelled("b.pdloc")
    assert [t for t, *_ in auto] == [75, -74]
    for (_, a1, a2), r in zip(auto, lab):
        assert (r.par[0], r.par[1]) == pytest.approx((a1, a2), abs=1e-6)


def test_mobius_fold_restarts_at_resonance_labels(fold_tr, mobius):
    """Labels of the resonances name their points as AUTO's ('R31': the first R3, the type
    name being two characters): ISW = 2 there goes on along the torus locus, ISW = 1
    continues the cycles in p1 alone from the locus point (p2 held)."""
    from washer.auto.diagram import SolutionList, read_solutions
    sols = SolutionList(read_solutions(mobius / "s.ftrdown"))
    assert sols("R31").rec.code == -87
    assert [s.rec.code for s in sols("R4")] == [-88]
    loc = run(mobius / "c.mobius_fold.trloc", verbose=False, files=False, s="ftrdown",
              IRS="R31", NMX=20, UZSTOP={})
    assert loc.status == "ok"
    assert loc.rows[0].par[1] == pytest.approx(math.pi ** 2 / 9 - 1, abs=1e-6)
    check_on_torus_locus(loc)
    cyc = run(mobius / "c.mobius_fold.trloc", verbose=False, files=False, s="ftrdown",
              IRS="R41", ISW=1, ICP=[1, 11], NMX=10, UZSTOP={})
    assert cyc.status == "ok"
    p2 = math.pi ** 2 / 4 - 1
    for r in cyc.rows:
        assert r.par[1] == pytest.approx(p2, abs=1e-6)      # the record's p2, held
        assert r.par[10] == pytest.approx(1.0, abs=1e-9)    # the cycle's period T = 1


def test_mobius_fold_tr_locus_past_the_12_resonance_from_autos_record(mobius):
    """AUTO-07p's own R3 record (s.trloc_down, label 6) restarted here towards p2 = -1:
    the fold (0, 0), R2 at (1, -1), where the PD locus (theta = pi) crosses; the way on
    is the torus locus's own (theta moving, the orbit and the parameters stationary), not
    the secant, whose steps went onto the crossing locus (theta = pi, p1 - p2^2 growing
    to 3.2, R2 'located' on it again and again): LP at theta = pi + 1, R3 and R4 at
    4 pi/3 and 3 pi/2, the UZSTOP p2 = 2. AUTO's record is located more loosely (its R3
    7e-9 off in p2), so the R2 point here carries the start's error through a singular
    Newton (p1 - p2^2 = 5.6e-7, EPSL = 1e-7 relative increments over linear
    convergence): 1e-6 allowed there."""
    shutil.copy(AUTO_FOLD / "s.trloc_down.gz", mobius / "s.autotrloc.gz")
    res = run(mobius / "c.mobius_fold.trloc", verbose=False, files=False, s="autotrloc",
              IRS=6, NMX=100)
    assert res.status == "ok"
    assert [r.code for r in res.rows if r.lab] == [85, -86, 85, -87, -88, -84]
    tol = location_tolerance(mobius / "c.mobius_fold.trloc")
    r3, r4 = [r for r in res.rows if r.code in (-87, -88)]
    assert (r3.par[1], r3.par[11]) == pytest.approx((math.pi ** 2 / 9 - 1, 4 * math.pi / 3),
                                                    abs=tol)
    assert (r4.par[1], r4.par[11]) == pytest.approx((math.pi ** 2 / 4 - 1, 3 * math.pi / 2),
                                                    abs=tol)
    for r in res.rows:
        assert r.par[0] == pytest.approx(r.par[1] ** 2, abs=1e-6)
