"""Event handling of the engine on AUTO's `ab` demo: several zeros in one step,
weighted arclength (THU), and equations failing at a trial point. (A zero hidden
before a located one, which linear estimates misorder, is exercised by the
washer's C_a Hopf curve in test_paper.py.)"""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from b_rows import branch_rows
from washer.run import run

DATA = Path(__file__).parent / "data"


@pytest.fixture
def ab(tmp_path):
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    return tmp_path / "c.ab"


#: AUTO-07p 0.9.2's b-files of the three runs below (tests/data/uz_stop/README.md)
NEAR = DATA / "uz_stop"


def _labelled(rows):
    return [(abs(r.pt), r.ty, r.lab) for r in rows if r.ty != 0]


@pytest.mark.parametrize("name, uzr, uzstop, labelled", [
    # 1e-5 apart in PAR(1), 1.6e-4 in arclength: two zeros in one step, both labelled in
    # arclength order (a linear estimate could take them in either order)
    ("two4", [0.1, 0.10001], None, [0.1, 0.10001]),
    # 5e-7 apart, 8e-6 in arclength, within the location tolerance 1.05e-5: AUTO's
    # LCSPAE stores the second user value as 0 once the first is located: one UZ
    ("two", [0.1, 0.1000005], None, [0.1]),
    # the same with the second a UZSTOP: one UZ, and the run goes on to NMX
    ("stop", [0.1], [0.1000005], [0.1])])
def test_user_values_in_one_step_as_auto(ab, name, uzr, uzstop, labelled):
    kw = {} if uzstop is None else {"UZSTOP": {1: uzstop}}
    res = run(ab, verbose=False, UZR={1: uzr}, DS=0.05, DSMAX=0.05, NMX=20, ISP=0, ILP=0,
              sv="w", **kw)
    ours = branch_rows(ab.parent / "b.w")
    autos = branch_rows(NEAR / f"b.near_{name}")
    assert _labelled(ours) == _labelled(autos)
    uz = [s.par[0] for s in res.specials if s.ty == "UZ"]
    # each located to within EPSS (1 + sqrt(DS DSMAX)) = 1.05e-5 of arclength, along
    # which PAR(1) moves 0.06 per unit here: 1e-9 is far inside that
    assert uz == [pytest.approx(v, abs=1e-9) for v in labelled]
    assert res.specials[-1].ty == "EP"


def test_a_located_point_at_nmx_or_outside_the_window_is_the_end_point(ab):
    """AUTO's STPLAE / STPLBV: a point at PT = NMX, or with PAR(ICP(1)) outside RL0..RL1,
    ends the branch as its EP, a located one too (its type is overridden). The UZ at
    PAR(1) = 0.1 is located at some PT k; with NMX = k the same point is the EP, and with
    RL1 just below its value (the located point lies beyond it) as well."""
    res = run(ab, verbose=False, UZR={1: 0.1}, DS=0.05, DSMAX=0.05, NMX=20, ISP=0, ILP=0)
    (uz,) = [r for r in res.rows if r.lab and r.ty == "UZ"]
    k = abs(uz.pt)
    at_nmx = run(ab, verbose=False, UZR={1: 0.1}, DS=0.05, DSMAX=0.05, NMX=k, ISP=0, ILP=0)
    last = at_nmx.rows[-1]
    assert abs(last.pt) == k and last.ty == "EP" and last.values[0] == pytest.approx(0.1)
    assert [r.ty for r in at_nmx.rows if r.lab].count("UZ") == 0
    beyond = run(ab, verbose=False, UZR={1: 0.1}, RL1=0.1 - 1e-9, DS=0.05, DSMAX=0.05,
                 NMX=20, ISP=0, ILP=0)
    assert beyond.rows[-1].ty == "EP" and abs(beyond.rows[-1].pt) == k
    assert beyond.rows[-1].values[0] == pytest.approx(0.1)


def test_a_uz_at_the_window_edge_located_by_trials_is_inside(ab):
    """A UZ on PAR(ICP(1)) at RL1 itself that the location's trials aimed at lies at its
    value, inside the closed window: the UZ keeps its type and the branch ends at the
    next point (AUTO's nag demo: UZR 1.0 with RL1 = 1.0, written UZ and the next point EP;
    AUTO writes its last trial's own PAR, on whichever side of the value its location
    error left it: nag's 1.1e-9 inside, this run's 1.7e-9 beyond, an EP at PT 17)."""
    res = run(ab, verbose=False, UZR={1: 0.105}, RL1=0.105, EPSS=1e-4, DS=0.05,
              DSMAX=0.05, NMX=40, ISP=0, ILP=0)
    labelled = [r for r in res.rows if r.lab]
    assert [r.ty for r in labelled][-2:] == ["UZ", "EP"]
    uz, ep = labelled[-2:]
    assert uz.values[0] == pytest.approx(0.105, abs=1e-12)
    assert abs(ep.pt) == abs(uz.pt) + 1


def test_a_uz_at_the_window_edge_located_at_the_step_end_is_the_end_point(ab):
    """AUTO's LCSPAE takes the step's end itself as the special point when its first
    secant correction is below the location tolerance EPSS (1 + sqrt|DS DSMAX|), without a
    trial: with EPSS = 1e-2 the step that passes PAR(1) = 0.105 ends 2.9e-4 beyond it,
    within 1.05e-2, and that point, outside RL1 = 0.105, is the branch's EP (STPLAE), not a
    UZ. AUTO-07p on ab.f90 with these constants writes the same: EP at PT 17,
    PAR(1) = 0.10529294861. Without RL1 the same point is the UZ."""
    kw = dict(verbose=False, UZR={1: 0.105}, EPSS=1e-2, DS=0.05, DSMAX=0.05, NMX=40,
              ISP=0, ILP=0)
    free = run(ab, **kw)
    (uz,) = [r for r in free.rows if r.lab and r.ty == "UZ"]
    tol = 1e-2 * (1 + 0.05)
    assert 0.105 + 1e-4 < uz.values[0] < 0.105 + tol       # the step's end, beyond it
    # the step's end: the row before it is the previous regular point
    before = [r for r in free.rows if abs(r.pt) == abs(uz.pt) - 1]
    assert before and before[0].values[0] < 0.105
    edge = run(ab, RL1=0.105, **kw)
    labelled = [r for r in edge.rows if r.lab]
    assert [r.ty for r in labelled] == ["EP", "EP"]
    assert abs(labelled[-1].pt) == abs(uz.pt)
    assert labelled[-1].values[0] == uz.values[0]


def test_the_step_end_rule_is_autos_first_secant_test():
    """events.at_step_end: (1 + HMACH) |q_cur s| < tol |q_prev - q_cur|, tol = EPSS (1 +
    sqrt|DS DSMAX|): a test linear in s, q(s) = s - z over a step of s = 1 from 0, has its
    zero at the step's end exactly when z > 1 - tol."""
    from types import SimpleNamespace
    from washer.cont.events import at_step_end
    st = SimpleNamespace(EPSS=1e-4, DS=0.01, DSMAX=0.04)
    tol = 1e-4 * (1 + 0.02)
    for z, inside in ((1 - 0.9 * tol, True), (1 - 1.1 * tol, False), (0.5, False)):
        assert at_step_end(0.0 - z, 1.0 - z, 1.0, st) is inside


def test_thu_reweights_the_step(ab):
    # U(2) dominates ab's arclength at the start; weighted down, the same
    # number of steps of the same DS covers more of the parameter.
    plain = run(ab, verbose=False, NMX=5, DSMAX=0.01, ISP=0, ILP=0)
    weighted = run(ab, verbose=False, NMX=5, DSMAX=0.01, ISP=0, ILP=0, THU={2: 1e-4})
    span = lambda r: abs(r.rows[-1].values[0] - r.rows[0].values[0])
    assert span(weighted) > 2 * span(plain)


def test_equations_failing_at_a_trial_point_shrink_the_step(ab, tmp_path):
    # The equations raise beyond p1 = 0.12: the run must stop cleanly with MX
    # (after halving the step down to DSMIN), keeping the points before it.
    src = (tmp_path / "ab.py").read_text()
    (tmp_path / "ab.py").write_text(src.replace("def func(u, par):", "def func(u, par):\n"
                                                "    if par[0] > 0.12:\n"
                                                "        raise ValueError('outside the domain')",
                                                1))
    res = run(ab, verbose=False, NMX=200, ISP=0, ILP=0)
    assert res.specials[-1].ty == "MX" and "minimum step" in res.status
    p1 = np.array([r.values[0] for r in res.rows])
    assert p1.max() <= 0.12 and p1.max() > 0.11


def test_a_failing_location_step_is_retried_halved():
    """A trial step of the location that does not converge is retried at s halved back
    towards the last converged trial (AUTO's STEPBV inside LCSPBV), and the zero is still
    located: q(s) = s^2 - 1/4 from q(0) < 0 to q(1) > 0, whose secant estimate s = 1/4
    lies where steps fail (s < 0.3); the retry at 0.625 converges and Muller finds 1/2."""
    from types import SimpleNamespace
    from washer.cont.events import LocationFailed, locate
    settings = SimpleNamespace(EPSS=1e-8, DS=0.01, DSMAX=0.1, ITMX=9, DSMIN=1e-3)
    tried = []

    def trial(s):
        tried.append(s)
        if s < 0.3:
            raise RuntimeError("no convergence")
        return None, s * s - 0.25
    _, s = locate(trial, "LP", -0.25, 0.75, 1.0, settings)
    assert s == pytest.approx(0.5, abs=1e-8)
    assert tried[:2] == [pytest.approx(0.25), pytest.approx(0.625)]
    # still failing below DSMIN: LocationFailed with what happened, for the d-file
    with pytest.raises(LocationFailed, match="halving"):
        locate(lambda s: (_ for _ in ()).throw(RuntimeError("diverges")), "LP", -0.25, 0.75,
               1.0, settings)


def test_when_itmx_runs_out_autos_rule_decides():
    """AUTO's LCSPBV stops at the first trial whose next correction is below the
    tolerance EPSS (1 + sqrt|DS DSMAX|); washer goes on narrowing the sign bracket, and
    where ITMX runs out first, AUTO's rule decides. q(s) = tanh(3 (s - z) / S) over a
    step S = 1e-3, zero z = 0.37 S: with ITMX = 3 (four trials) the last trial lies
    2.7e-8 from z after a step of 2.5e-6, its next correction below the tolerance 1e-7:
    the zero is there, within the tolerance of z (it failed before: 'no convergence in
    ITMX = 3 iterations'). With ITMX = 2 the last trial is 2.5e-6 off and its next
    correction above the tolerance: no convergence, as in AUTO."""
    from types import SimpleNamespace
    from washer.cont.events import LocationFailed, locate
    S, z = 1e-3, 0.37e-3

    def trial(s):
        return ("point", s), math.tanh(3 * (s - z) / S)
    q0, q1 = trial(0.0)[1], trial(S)[1]
    settings = SimpleNamespace(EPSS=1e-7, DS=0.01, DSMAX=0.1, ITMX=3, DSMIN=1e-12)
    tol = settings.EPSS * (1 + (settings.DS * settings.DSMAX) ** 0.5)
    pt, s = locate(trial, "PD", q0, q1, S, settings)
    assert pt == ("point", s) and abs(s - z) < tol
    with pytest.raises(LocationFailed, match="ITMX = 2"):
        locate(trial, "PD", q0, q1, S, SimpleNamespace(**{**vars(settings), "ITMX": 2}))


def test_a_location_ends_at_the_last_trial_when_the_failing_correction_is_below_tolerance():
    """Next to a branch point of cycles the last, tiny trial step may not converge (the
    Newton matrix is nearly singular): AUTO's LCSPBV tests the correction before it
    steps and returns the point it has. Here the trial steps converge everywhere but
    within 1e-7 of the zero of q(s) = e + e^2 / 3 + e^3 (e = s - 1/2), and the location
    ends at the last converged trial, within the tolerance EPSS (1 + sqrt|DS DSMAX|) of
    the zero (it failed before: 'trial step failed')."""
    from types import SimpleNamespace
    from washer.cont.events import locate
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=9, DSMIN=1e-3)
    tol = settings.EPSS * (1 + (settings.DS * settings.DSMAX) ** 0.5)

    def trial(s):
        e = s - 0.5
        if abs(e) < 1e-7:
            raise RuntimeError("no convergence next to the branch point")
        return ("point", s), e + e * e / 3 + e ** 3
    pt, s = locate(trial, "BP", trial(0.0)[1], trial(1.0)[1], 1.0, settings)
    assert pt == ("point", s)
    assert abs(s - 0.5) < tol


@pytest.mark.parametrize("steep", [1.0, 30.0])
def test_a_jump_of_the_test_is_not_located_as_a_zero(steep):
    """A test that jumps across 0 (q = -0.5 + s for s < 0.3, 0.2 + s beyond) is bracketed
    down to the jump, but the bracket's ends then differ by 0.4 over less than 10
    tolerances while the whole step changes q by 1.7: not a zero (AUTO's Muller creeps
    towards such a point and stops at ITMX with 'Possible special point'; tfc's test of
    BPs of cycles after its Hopf start). A genuine zero, even a steep one (q = tanh of
    steep (s - 0.3), 30 times the step's mean slope there), is located to tolerance."""
    from types import SimpleNamespace
    from washer.cont.events import LocationFailed, locate
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=60, DSMIN=1e-12)
    tol = settings.EPSS * (1 + (settings.DS * settings.DSMAX) ** 0.5)

    def jump(s):
        return ("point", s), (-0.5 + s) if s < 0.3 else (0.2 + s)
    with pytest.raises(LocationFailed, match="jump"):
        locate(jump, "BP", jump(0.0)[1], jump(1.0)[1], 1.0, settings)

    def smooth(s):
        return ("point", s), math.tanh(steep * (s - 0.3))
    _, s = locate(smooth, "BP", smooth(0.0)[1], smooth(1.0)[1], 1.0, settings)
    assert abs(s - 0.3) < tol


def test_a_user_value_whose_change_newton_does_not_resolve_is_located_not_a_jump():
    """A user value's test PAR(i) - v changes across a location's bracket by Newton's
    noise where the parameter itself stays within Newton's tolerance of v along the step
    (kdv's run 6: the gap PAR(24) goes from 1.8e-10 to -1.7e-9 over the step, 4.6e-10
    across a bracket of 2.2e-8, EPSL = 1e-7; AUTO labels its zero). Here q = -2e-10 + 1e-10 s
    up to s = 0.3 and 2e-10 + 1e-10 s beyond: it changes sign at s = 0.3 by a step of
    4e-10, 800 times its change over the whole step per unit of arclength. With the
    resolution of a parameter converged to EPSL = 1e-7 the bracket closes on s = 0.3 and
    that is the zero; a test with no resolution (0) is a jump there, as before."""
    from types import SimpleNamespace
    from washer.cont.events import LocationFailed, locate, location_tolerance
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=60, DSMIN=1e-12)
    tol = location_tolerance(settings)

    def gap(s):
        return ("point", s), (-2e-10 + 1e-10 * s) if s < 0.3 else (2e-10 + 1e-10 * s)
    q0, q1 = gap(0.0)[1], gap(1.0)[1]
    pt, s = locate(gap, ("UZ", 0), q0, q1, 1.0, settings, resolution=1e-7)
    assert abs(s - 0.3) < 10 * tol and pt == ("point", s)
    with pytest.raises(LocationFailed, match="jump"):
        locate(gap, ("UZ", 0), q0, q1, 1.0, settings)


def test_a_user_value_has_no_pole():
    """A test whose located trial exceeds its values at both ends of the step is refused
    as a pole (the first Lyapunov coefficient through a zero eigenvalue), but a user
    value PAR(i) - v has no pole: its trials' values are the parameter's own, and Newton's
    noise on it (fnb's run 6 starts where Lin's gap PAR(22) is 0 by construction: the gap
    changes sign at 1e-10 between two points at one PAR(21), and AUTO labels UZ30 there)
    is no reason to refuse its zero. Here q = -1e-9 (1 - |s - 0.3|) up to s = 0.3,
    +1e-9 (1 - |s - 0.3|) beyond, below the resolution 1e-7 of a parameter converged to
    EPSL: located at 0.3 as a user value, refused as a pole for a bifurcation test."""
    from types import SimpleNamespace
    from washer.cont.events import LocationFailed, locate, location_tolerance
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=60, DSMIN=1e-12)

    def noise(s):
        return ("point", s), math.copysign(1e-9 * (1 - abs(s - 0.3)), s - 0.3)
    q0, q1 = noise(0.0)[1], noise(1.0)[1]
    _, s = locate(noise, ("UZ", 0), q0, q1, 1.0, settings, resolution=1e-7, crossing=True)
    assert abs(s - 0.3) < 10 * location_tolerance(settings)
    with pytest.raises(LocationFailed, match="pole"):
        locate(noise, "BP", q0, q1, 1.0, settings, resolution=1e-7)


def test_a_zero_with_newton_noise_on_one_side_is_located():
    """A test whose values at converged points carry an error of the Newton tolerance's
    size (r3b's circle of L5 at mu = 1: 0.47 and -0.18 at the step's ends, -3.6e-10 at a
    trial and +4.4e-6 at the next, 5.3e-11 beyond it): q = z - s + 1e-4 for s < z,
    z - s - 1e-9 beyond (z = 1/pi). The bracket closes on the zero with its ends 1e-4
    apart over 1.5e-8, which reads as a jump, but its right end is 1e-9, below ZERO_FACTOR
    of the step's values: the zero, located (AUTO's BP there). Without that rule
    (ZERO_FACTOR = 0) it is refused as a jump."""
    from types import SimpleNamespace

    import washer.cont.events as events
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=8, DSMIN=1e-12)
    tol = settings.EPSS * (1 + (settings.DS * settings.DSMAX) ** 0.5)
    z = 1 / math.pi

    def noisy(s):
        return ("point", s), (z - s) + (1e-4 if s < z else -1e-9)
    q0, q1 = noisy(0.0)[1], noisy(1.0)[1]
    _, s = events.locate(noisy, "BP", q0, q1, 1.0, settings)
    assert abs(s - z) < tol
    saved = events.ZERO_FACTOR
    try:
        events.ZERO_FACTOR = 0.0
        with pytest.raises(events.LocationFailed, match="jump"):
            events.locate(noisy, "BP", q0, q1, 1.0, settings)
    finally:
        events.ZERO_FACTOR = saved


def test_the_fold_is_located_before_a_branch_point_in_the_same_step():
    """AUTO's LCSPAE / LCSPBV take the fold test before the branch-point test: where both
    change sign over a step, the fold is located first, even if the BP test's linear
    estimate puts its zero earlier (next to a BP of cycles its determinant may creep
    from -1e-18 to 1e-15: tor's symmetric cycles); the BP is then looked for only
    between the previous point and the fold. Here the BP's zero (s = 0.3) lies beyond
    the fold's (s = 0.1): the step's special point is the fold, the first trial is the
    fold's."""
    from types import SimpleNamespace
    from washer.cont.codes import Code
    from washer.cont.branch import Point
    from washer.cont.events import first_zero
    settings = SimpleNamespace(EPSS=1e-8, DS=0.01, DSMAX=0.1, ITMX=9, DSMIN=1e-6)
    tests = {Code.LPC: lambda s: 0.01 - 0.1 * s, Code.BPC: lambda s: 1e-15 * (s - 0.3)}

    def point(s, values=None):
        return Point(np.array([s]), np.array([1.0]), None,
                     values or {k: f(s) for k, f in tests.items()})
    prev = point(0.0, {Code.LPC: 0.01, Code.BPC: -1e-18})
    cur = point(1.0, {Code.LPC: -0.09, Code.BPC: 1e-15})
    tried = []

    def trial(s, key, base=None, chord=None, span=None):
        tried.append(key)
        return point(s), tests[key](s)

    def refresh(p):
        p.tests = {k: f(p.x[0]) for k, f in tests.items()}
    sp, key, same = first_zero(prev, cur, 1.0, settings, trial=trial,
                               accepted=lambda k, a, b: True, refresh=refresh,
                               inner=lambda a, b: float(a @ b), note=lambda text: None,
                               curve_type=0)
    assert tried[0] == Code.LPC and key == Code.LPC and same == []
    assert sp.x[0] == pytest.approx(0.1, abs=1e-8)


@pytest.mark.parametrize("order", [3, 5, 1.5])
def test_a_zero_of_high_order_is_located_to_tolerance(order):
    """At a zero of high order Muller's iteration only creeps (tfc's iso-periodic family:
    a branch point of cycles at the tip of a fold, its BP test ~ the cube of the
    distance): q(s) = (s - 0.3)^m (odd in s - 0.3, m = 3, 5 and 1.5). Its trials on one
    side are fitted by the power law through the last three, which converges: located to
    the tolerance EPSS (1 + sqrt|DS DSMAX|) within ITMX = 14 without any zero threshold
    (ZERO_FACTOR off); with the fit off (ONE_SIDED out of reach) the location runs out of
    ITMX, and the d-file's note says what was tried and where it got to."""
    from types import SimpleNamespace

    import washer.cont.events as events
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=14, DSMIN=1e-12)
    tol = settings.EPSS * (1 + (settings.DS * settings.DSMAX) ** 0.5)

    def power(s):
        return ("point", s), math.copysign(abs(s - 0.3) ** order, s - 0.3)
    q0, q1 = power(0.0)[1], power(1.0)[1]
    saved = events.ZERO_FACTOR, events.ONE_SIDED
    try:
        events.ZERO_FACTOR = 0.0
        pt, s = events.locate(power, "BP", q0, q1, 1.0, settings)
        assert abs(s - 0.3) < tol and pt == ("point", s)
        if order == 1.5:
            return                    # Muller alone gets there too (order < 2)
        events.ONE_SIDED = 10 ** 6
        with pytest.raises(events.LocationFailed,
                           match=r"ITMX = 14 .*15 trials, the last at s = 0\.2"):
            events.locate(power, "BP", q0, q1, 1.0, settings)
    finally:
        events.ZERO_FACTOR, events.ONE_SIDED = saved


def test_a_zero_far_inside_a_flat_test_is_bisected_to():
    """r3b's vertical family: the BP test of cycles goes from -4e-22 to +6e-20 over the
    step, flat near the previous point; here q = -1 + 140 (exp(14 s) - 1) / (exp(14) - 1)
    (the same ratio of its end values), zero at s* = ln(1 + (exp(14) - 1) / 140) / 14.
    Muller's parabola and the Illinois step creep from the flat end, their steps growing;
    after three growing steps on one side the bracket is bisected (Brent's safeguard), and
    the zero is located within ITMX = 10 (AUTO's LCSPBV takes up to ITMX + 1 trials); it
    is not without the bisection."""
    from types import SimpleNamespace

    import washer.cont.events as events
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=10, DSMIN=1e-12)
    tol = settings.EPSS * (1 + (settings.DS * settings.DSMAX) ** 0.5)

    def flat(s):
        return ("point", s), -1 + 140 * math.expm1(14 * s) / math.expm1(14)
    q0, q1 = flat(0.0)[1], flat(1.0)[1]
    _, s = events.locate(flat, "BP", q0, q1, 1.0, settings)
    assert abs(s - math.log1p(math.expm1(14) / 140) / 14) < tol
    saved = events._widening
    try:
        events._widening = lambda streak: False
        with pytest.raises(events.LocationFailed, match="ITMX"):
            events.locate(flat, "BP", q0, q1, 1.0, settings)
    finally:
        events._widening = saved


def _points_of(tests):
    """(point(s), refresh(point)) for a one-dimensional branch x = s whose test values
    are tests[key](s)."""
    from washer.cont.branch import Point

    def point(s):
        return Point(np.array([s]), np.array([1.0]), None,
                     {k: f(s) for k, f in tests.items()})

    def refresh(p):
        p.tests = {k: f(p.x[0]) for k, f in tests.items()}
    return point, refresh


def test_a_located_zero_is_not_counted_again_whatever_the_noise_beyond_it():
    """AUTO's LCSPAE / LCSPBV store 0 as the value of the test they located and of every
    test whose zero lies within the location tolerance of the point; a stored 0 makes no
    sign change with the next point. Here a fold test 0.3 - s (simple zero) and a
    branch-point test (s - 0.3)^3 (a zero of order three, vanishing with it) change sign
    over one step: the fold, AUTO's ITEST 1, is located first and the branch point,
    ITEST 2, vanishing there, is absorbed (first come, first served: LP); both are
    stored as 0 at the point located, so that on the next step the branch-point test's
    rounding noise, of either sign, is no new sign change (with the sign beyond the zero
    stored instead, noise of the other sign was one: a second label for the one
    point)."""
    from types import SimpleNamespace
    from washer.cont.codes import Code
    from washer.cont.events import first_zero, sign_changes
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=9, DSMIN=1e-6)
    tests = {Code.LP: lambda s: 0.3 - s, Code.BP: lambda s: (s - 0.3) ** 3}

    point, refresh = _points_of(tests)
    prev, cur = point(0.0), point(1.0)
    sp, key, same = first_zero(prev, cur, 1.0, settings,
                               trial=lambda s, k, base=None, chord=None, span=None: (point(s),
                                                                         tests[k](s)),
                               accepted=lambda k, a, b: True, refresh=refresh,
                               inner=lambda a, b: float(a @ b), note=lambda text: None)
    assert key == Code.LP and Code.BP in same          # one point, the fold's (AUTO's order)
    assert sp.x[0] == pytest.approx(0.3, abs=1e-6)
    assert sp.tests[Code.LP] == 0.0 and sp.tests[Code.BP] == 0.0
    for noise in (1e-17, -1e-17):
        nxt = point(sp.x[0] + 1e-3)
        nxt.tests[Code.BP] = noise
        assert sign_changes(sp.tests, nxt.tests) == []


def test_a_branch_point_located_short_of_a_located_fold_is_the_point_and_the_fold_counts_again():
    """AUTO's CNRLAE / CNRLBV visit each test once after a step, the fold (ITEST 1) before
    the branch point (ITEST 2), each at the point the tests before it left. The fold test
    0.3 - s is located first, at s = 0.3; the branch-point test 0.299995 - s there is
    -5e-6, of the sign opposite its value at the previous point, and its secant zero
    5e-6 away, beyond the location tolerance EPSS (1 + sqrt(DS DSMAX)) = 1.03e-6 (though
    within ten of it): it is located between the previous point and the fold and the
    point is its, a BP (last located). The fold test is evaluated afresh there (5e-6, the
    sign before its zero, not stored as 0), so the next step, across s = 0.3, labels the
    fold: BP, then LP, on consecutive points."""
    from types import SimpleNamespace
    from washer.cont.codes import Code
    from washer.cont.events import first_zero, sign_changes
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=9, DSMIN=1e-6)
    tests = {Code.LP: lambda s: 0.3 - s, Code.BP: lambda s: 0.299995 - s}

    point, refresh = _points_of(tests)

    def kwargs(s0):
        """first_zero's hooks for a step from the point at s0 (trials land at s0 + s)."""
        return dict(trial=lambda s, k, base=None, chord=None, span=None:
                    (point(s0 + s), tests[k](s0 + s)),
                    accepted=lambda k, a, b: True, refresh=refresh,
                    inner=lambda a, b: float(a @ b), note=lambda text: None)
    prev, cur = point(0.0), point(1.0)
    sp, key, same = first_zero(prev, cur, 1.0, settings, **kwargs(0.0))
    assert key == Code.BP and same == []
    assert sp.x[0] == pytest.approx(0.299995, abs=1e-7)
    assert sp.tests[Code.BP] == 0.0
    assert sp.tests[Code.LP] == pytest.approx(5e-6, abs=1e-7)
    nxt = point(0.5)
    assert sign_changes(sp.tests, nxt.tests) == [Code.LP]
    sp2, key2, _ = first_zero(sp, nxt, 0.5 - sp.x[0], settings, **kwargs(sp.x[0]))
    assert key2 == Code.LP and sp2.x[0] == pytest.approx(0.3, abs=1e-7)


@pytest.mark.parametrize("key, state_jumps, bvp", [(("UZ", 0), True, True),
                                                   (("UZ", 0), True, False),
                                                   (("UZ", 0), False, True),
                                                   ("BP", True, False)],
                         ids=["UZ-branch-jumps", "UZ-branch-jumps-algebraic",
                              "UZ-value-jumps", "BP"])
def test_a_user_value_crossed_by_a_jump_of_the_branch_is_labelled_past_it(
        key, state_jumps, bvp):
    """A branch that jumps within one step (Newton leaving for another sheet of solutions:
    kdv's run 3, from PAR(1) = 3.0488 to 2.7364 across UZR = 3) crosses the user value
    there. Here the state is (s, q) with q = s + 0.05 up to s = 0.2 and s - 0.3 beyond, and
    the test is q: it changes sign only across the jump, where the location's bracket
    closes. AUTO's LCSPBV steps on from the step's end and labels its last trial (its UZ4
    of kdv's run 3, at PAR(1) = 2.7295): here the trials (secant, then Muller on the s
    asked for) end on the far sheet's own zero, q = 0 at s = 0.3, to the location
    tolerance EPSS (1 + sqrt|DS DSMAX|) = 1.03e-6 in s (q = s - 0.3 there). On an
    algebraic branch (no BVP secants) the step's end is labelled, with a note.
    A user value that jumps while the state does not (a PVLS's step function of a
    continuous branch, the state here (s, 0)) is no crossing of the branch, and a
    bifurcation test jumping is no zero (tfc's BP test): both stay unlabelled, 'Possible
    special point'."""
    from types import SimpleNamespace
    from washer.cont.branch import Point
    from washer.cont.codes import Code
    from washer.cont.events import first_zero
    key = Code.BP if key == "BP" else key
    settings = SimpleNamespace(EPSS=1e-6, DS=0.01, DSMAX=0.1, ITMX=60, DSMIN=1e-12)

    def q_of(s):
        return s + 0.05 if s < 0.2 else s - 0.3

    def point(s):
        return Point(np.array([s, q_of(s) if state_jumps else 0.0]), np.array([1.0, 0.0]),
                     None, {key: q_of(s)})

    def refresh(p):
        p.tests = {key: q_of(p.x[0])}
    prev, cur = point(0.0), point(0.25)
    notes = []
    hit = first_zero(prev, cur, 0.25, settings,
                     trial=lambda s, k, base=None, chord=None, span=None: (point(s), q_of(s)),
                     accepted=lambda k, a, b: True, refresh=refresh,
                     inner=lambda a, b: float(a @ b), note=notes.append, secant=bvp)
    assert len(notes) == 1
    if key == Code.BP or not state_jumps:
        # (the BP refused as a pole here: its trials beyond the jump exceed the step's
        # values; a user value has no pole, and its bracket closes on the jump)
        assert hit is None and notes[0].startswith("NOTE:Possible special point")
        return
    sp, k, same = hit
    assert k == key and same == []
    if not bvp:
        assert sp is cur and not sp.across_jump
        assert "UZ1 crossed by a jump of the branch, labelled where the step landed" \
            in notes[0]
        return
    assert sp is not cur and sp.across_jump
    assert sp.x[0] == pytest.approx(0.3, abs=1.03e-6) and sp.x[1] == sp.x[0] - 0.3
    assert "UZ1 crossed by a jump of the branch, labelled at the location's last trial" \
        in notes[0]


def test_past_a_jump_the_trials_go_on_from_the_step_end_as_autos_lcspbv():
    """kdv's run 3: past the jump the trials land on the far sheet, where the user value's
    test hardly changes (AUTO's -0.2703, -0.2705, -0.27049): they converge because they
    stop moving, not on a zero. Here the far sheet's test is q = -0.27 - 0.1 s and prev's
    0.05 (the step from 0 to -0.002, as kdv's DS). The labelled point is the last trial,
    the first steps back from the step's end by the secant correction, every later one from
    the trial before, and the corrections, recomputed with AUTO's MUELLER as it is written
    (the parabola's coefficients A, B about the last trial, its root -C -+ R), fall below
    EPSS (1 + sqrt|DS DSMAX|) at the last trial only."""
    import math
    from types import SimpleNamespace
    from washer.cont.branch import Point
    from washer.cont.events import first_zero, location_tolerance
    from washer.cont.settings import HMACH
    key = ("UZ", 0)
    settings = SimpleNamespace(EPSS=1e-5, DS=-0.001, DSMAX=2.0, ITMX=10, DSMIN=1e-8)
    tol = location_tolerance(settings)

    def far(s):
        return -0.27 - 0.1 * s

    def point(s, q):
        # the state (s, q): s along the branch, the test q
        return Point(np.array([s, q]), np.array([1.0, 0.0]), None, {key: q})
    prev, cur = point(0.0, 0.05), point(-0.002, far(-0.002))
    asked = []

    def trial(s, k, base=None, chord=None, span=None):
        # a trial from the step's end (chord) or from a trial (base, stepping as it
        # stands) lands on the far sheet
        asked.append((s, base))
        p = point(s, far(s))
        return p, p.x[1]
    notes = []
    sp, k, same = first_zero(prev, cur, -0.002, settings, trial=trial,
                             accepted=lambda k_, a, b: True,
                             refresh=lambda p: None, inner=lambda a, b: float(a @ b),
                             note=notes.append, secant=True)
    assert k == key and sp.across_jump and "last trial past it" in notes[0]
    trials = asked[-len([a for a in asked if a[1] is not None and len(a[1]) > 2]) - 1:]
    assert trials[0][1] is None and all(b is not None and b[2] for _, b in trials[1:])
    q0, q1 = 0.05, far(-0.002)
    assert trials[0][0] == pytest.approx(-0.002 + (1 + HMACH) * q1 / (q0 - q1) * -0.002,
                                         rel=1e-12)
    s0, s1 = 0.0, -0.002
    corrections = []
    for s, _ in trials:
        q = far(s)
        h0, h1 = s0 - s, s1 - s
        d = h0 * h1 * (h1 - h0)
        a = (h1 ** 2 * (q0 - q) - h0 ** 2 * (q1 - q)) / d
        b = (-h1 * (q0 - q) + h0 * (q1 - q)) / d
        c = a / (2 * b)
        r = math.sqrt(c * c - q / b)
        corrections.append((1 + HMACH) * (-c - r if c < 0 else -c + r))
        if q1 * q < 0:
            q0, s0 = q1, s1
        q1, s1 = q, s
    assert len(trials) > 1 and all(abs(c) >= tol for c in corrections[:-1])
    assert abs(corrections[-1]) < tol
    assert sp.x[1] == far(trials[-1][0])


def test_a_second_zero_within_the_tolerance_of_a_located_fold_is_not_searched():
    """AUTO's LCSPBV, once a point is located (AP%ITP /= 0), sets a later test's Q1 = 0
    where its zero lies within the location tolerance EPSS (1 + sqrt|DS DSMAX|) of that
    point: it is neither located nor allowed to move the point. snh's h1b has a BP test
    at rounding level (-1.5e-13 before its fold, 1e-16 at it): searched between the
    previous point and the located fold, its noise zero 2.5e-6 of arclength short of the
    fold became the point, typed LP, where the fold test was 1.5e-3, not 0, and the next
    step labelled the fold again. Here the fold test 0.5 - s vanishes at s = 0.5 and
    the BP test 1e-13 (0.5 - d - s) at d = 1e-4 short of it, inside the tolerance 2e-4
    (EPSS 1e-4, DS = DSMAX = 1) but not within the fraction SIMULTANEOUS of the step: the
    point is the fold itself, both tests are stored as 0 there, so the next step (fold
    test -0.1 beyond) sees no sign change."""
    from types import SimpleNamespace
    from washer.cont.codes import Code
    from washer.cont.events import SIMULTANEOUS, first_zero, linear_fraction, sign_changes
    settings = SimpleNamespace(EPSS=1e-4, DS=1.0, DSMAX=1.0, ITMX=9, DSMIN=1e-6)
    d = 1e-4
    tests = {Code.LPC: lambda s: 0.5 - s, Code.BPC: lambda s: 1e-13 * (0.5 - d - s)}

    point, refresh = _points_of(tests)
    prev, cur = point(0.0), point(1.0)
    at_fold = tests[Code.BPC](0.5)
    # the old rule would search it: its zero is 2e-4 of the way short of the fold
    assert linear_fraction(prev.tests[Code.BPC], at_fold) < 1 - SIMULTANEOUS
    tried = []

    def trial(s, key, base=None, chord=None, span=None):
        tried.append(key)
        return point(s), tests[key](s)
    sp, key, same = first_zero(prev, cur, 1.0, settings, trial=trial,
                               accepted=lambda k, a, b: True, refresh=refresh,
                               inner=lambda a, b: float(a @ b), note=lambda text: None)
    assert Code.BPC not in tried                       # never searched
    assert key == Code.LPC
    # the fold test is linear: the secant's first trial lands on its zero (to HMACH)
    assert sp.x[0] == pytest.approx(0.5, abs=1e-6)
    assert sp.tests[Code.LPC] == 0.0 and sp.tests[Code.BPC] == 0.0
    assert sign_changes(sp.tests, point(0.6).tests) == []


@pytest.mark.parametrize("keys, curve_type, want", [
    (["BP", "LP"], 0, "LP"),          # ITEST 1 before 2: the fold first, the BP absorbed
    (["BT", "LP"], 3, "LP"),          # the fold (1) before BT (4) on a Hopf locus
    (["CP", "LP"], 2, "CP"),          # the cusp overrides the fold on a fold locus (ITP 22)
    (["CP", "LP"], 3, "LP"),          # GH does not override the fold on a Hopf locus (32)
    ([("UZ", 0), "HB"], 0, "HB"),     # a bifurcation overrides a user value
    ([("UZ", 1), ("UZ", 0)], 0, ("UZ", 0)),   # user values in IUZ's order
    (["PD", "BPC", "LPC"], 0, "LPC"),  # LCSPBV's order: the fold of cycles first
])
def test_tests_vanishing_at_one_point_are_typed_as_autos_lcspae(keys, curve_type, want):
    """AUTO's CNRLAE / CNRLBV visit the tests in ITEST order (user values first), each at
    the point the ones before left, and LCSPAE / LCSPBV set Q1 = 0 for a test whose zero
    lies within the tolerance of a point already located: the first located types the
    point, but for the two overrides LCSPAE writes out (a bifurcation over UZ, and CP
    over LP where ITP = 22, a fold on a fold locus)."""
    from washer.cont.codes import Code
    from washer.cont.events import autos_type
    code = lambda k: k if isinstance(k, tuple) else Code[k]        # noqa: E731
    assert autos_type([code(k) for k in keys], curve_type) == code(want)
