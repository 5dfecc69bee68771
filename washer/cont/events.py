"""Special points on a branch: sign changes of test functions, their location
and AUTO's rules for them (LCSPAE / LCSPBV).

A test value changes sign between two consecutive points when the two values
have strictly opposite signs (AUTO tests Q0 * Q1 < 0 by signs, so a value
that is exactly 0 or undefined on either side never counts). The system's
`accept` rule must then agree (an HB needs the stable count to change by 2).
When several tests change sign in one step, the earliest zero along the
branch is located first, by a linear estimate, then re-checked: the interval
up to the located point is searched again, so no zero is stepped over.

Location (LCSPAE): where the secant estimate of the zero already lies within the
tolerance below of the step's end, the step's end itself is the special point, with
no trial (`at_step_end`). Otherwise trial points are continuation steps of arclength s from
the previous point; the first trial is the secant estimate, then Muller's
method (a parabola through the last three (s, q) pairs) kept inside the
bracket, up to ITMX + 1 trials as AUTO's LCSPAE / LCSPBV (DO NITSP1 = 0, ITMX).
Two safeguards where Muller only creeps from one side of the zero: a zero of
high order (a branch point at a fold's tip: q ~ (s - s*)^3) is approached by
the power law fitted to the last three one-sided trials (`_power_secant`), and
a zero far inside a bracket over which the test is flat at one end by a
bisection once the one-sided steps grow (`_widening`). A trial step that does
not converge is retried at s halved back towards the last converged trial, down
to DSMIN, as AUTO's STEPBV halves the step of its location (the bracket is
kept). Converged when the last change of s satisfies
|delta s| / (1 + sqrt(|DS DSMAX|)) < EPSS (and the bracket is within 10 times
that, or the change before was below it too): that is the location tolerance in
arclength (parameters are located to about that times the parameter's rate
along the branch; in practice much better, since Muller converges with order
~1.84 and the last step is below the tolerance). A location that does not
converge, or whose trial step fails, is not an error: the point is kept
unlabelled and the d-file says "NOTE:Possible special point" (AUTO). A user value
crossed by a jump of a BVP branch within the step (Newton leaving for another sheet)
is labelled where AUTO's LCSPBV stops, at the last of its trials past the jump
(`locate_past_jump`).

When several zeros lie in one step (`first_zero`), the earliest is located first and
the interval up to it searched again; zeros of several tests at one point are one
special point typed as AUTO types it (`autos_type`); at a BP the
branch's direction is the secant from the previous point.

Where a change goes: the rules (which zero, when a location has converged, what counts as
a jump) are here; the trial points themselves, continuation steps from the previous point
at a given arclength, are made by the iterator (washer.cont.iterator.Continuation:
`_first_zero` hands this module `_trial`; `_radial` is a trial's direction on a sphere
of arclength), and which tests a system has and what accepts their zeros by the systems
(`active_tests`, `test_functions`, `accept` in washer.cont.system).
"""
from __future__ import annotations

import math

import numpy as np

from washer.cont.codes import Code, curve_code, type_name
from washer.cont.settings import HMACH

#: A zero estimated within this fraction of a step from a located special
#: point lies on it: a second test vanishes there too (a transcritical BP is
#: also a zero eigenvalue). AUTO takes simultaneous zeros first come, first
#: served: the second is not located again.
SIMULTANEOUS = 1e-6


#: AUTO's test order (ITEST) after its user values: LCSPAE's FNCSAE / FNCSEQ check the
#: fold (1), the branch point (2), the cusp (3), BT (4), GH (5) and the Hopf test (6);
#: LCSPBV's FNCSBV the fold of cycles (1), their branch point (2), PD / TR (3). After a
#: step each test is visited once in this order, at the point the tests before it left
#: (the step's end or the point one of them located): first come, first served
#: (`autos_type`). GH shares the cusp's code (Code.CP), and with it the cusp's rank.
ORDER = (Code.LP, Code.BP, Code.CP, Code.BT, Code.HB, Code.ZH, Code.LPC, Code.BPC,
         Code.PD, Code.TR)


def _order(key) -> int:
    """Rank of a test key in AUTO's visiting order: user values (tuples) first, in IUZ's
    order, then ORDER."""
    if isinstance(key, tuple):
        return key[1] - 10 ** 6
    return ORDER.index(key) if key in ORDER else len(ORDER)


def autos_type(keys, curve_type: int = 0):
    """The type AUTO gives one point at which the tests `keys` vanish together (each
    absorbed by the first located: LCSPAE / LCSPBV set a later test's Q1 = 0 where its
    zero lies within the location tolerance of the located point): the first in AUTO's
    order, except that a bifurcation overrides a user value and, on a fold locus
    (curve_type 2: AUTO's ITP 22), the cusp a fold (the two overrides LCSPAE writes
    out). So a fold and a branch point at one point are an LP (tfc's BP locus meeting a
    fold at PAR(6) = 0.0173913, AUTO's restart: LP), a fold and a BT an LP (a Hopf curve
    touching a fold line of constant PAR(ICP(1)): AUTO goes on along it), a fold and GH
    on a Hopf locus an LP."""
    ranked = sorted(keys, key=_order)
    t = ranked[0]
    for k in ranked[1:]:
        if (isinstance(t, tuple) and not isinstance(k, tuple)) \
                or (t == Code.LP and k == Code.CP and curve_type == 2):
            t = k
    return t


#: Resonances at which a torus locus (curve type 8: the TR locus of cycles, the
#: Neimark-Sacker locus of maps) folds in every parameter: the angles theta and
#: 2 pi - theta (and -theta) state the same torus condition, so the parameters are even
#: functions of theta about 0 and pi, and the locus passes R1 and R2 turning back along
#: itself. LP and the resonance are one point there, typed by the resonance; its test,
#: a function of theta alone, is located, not the tangent's component (the extended
#: system meets the PD locus there, where the tangent is ill-determined).
TORUS_FOLDS = {8: (Code.R1, Code.R2)}


def _key_name(key, curve_type: int = 0) -> str:
    """'HB', 'GH', 'UZ2', ... for a test key (notes)."""
    if isinstance(key, tuple):
        return f"UZ{key[1] + 1}"
    return type_name(curve_code(key, curve_type))


#: A located zero whose bracket's ends differ, per unit of arclength, by more than this
#: many times the test's change over the whole step is a jump of the test, not a zero.
JUMP_FACTOR = 1e3

#: A location that runs out of ITMX iterations with its last trial's test this far below
#: its values at the ends of the step (or whose bracket has an end this far below them)
#: has found the zero: at a zero of high order the
#: test's rounding (~1e-12 of its values over the step) limits the location to its m-th
#: root, and the trials may wander there without meeting the tolerance in arclength.
ZERO_FACTOR = 1e-6

#: A located "zero" whose test value exceeds both bracketing values in
#: magnitude is a sign change through a pole or a jump (e.g. the first
#: Lyapunov coefficient through a zero eigenvalue), not a zero: rejected.
POLE_FACTOR = 1.0


def _no_nearer_zero(q: float, q_prev: float, q_cur: float) -> bool:
    """Whether a located point's test value q is no nearer zero than the step's end of its
    own sign, and not small against the step's values (ZERO_FACTOR). Towards a zero a test
    falls in magnitude; towards a pole it grows from both sides, and a trial on the side of
    the step's smaller end (-1.2e5 at the step's start, +1.7e8 at its end: n-body's
    collinear branch passing the massless primary in one step) stays above that end
    whatever the iteration does and below the other, so POLE_FACTOR's comparison with the
    larger end passes it."""
    same = q_prev if (q < 0) == (q_prev < 0) else q_cur
    return abs(q) >= abs(same) and abs(q) > ZERO_FACTOR * max(abs(q_prev), abs(q_cur))


def _left_behind(s_best: float, lo: float, hi: float, tol: float) -> bool:
    """Whether the location's point lies more than tol outside its last sign bracket [lo,
    hi]: a trial that converged (two corrections below tol) where the secant put the zero,
    after which the trials went on and the bracket closed elsewhere (on n-body's pole,
    5.8e-5 from the step's start against a bracket [9.47e-3, 1.0e-2])."""
    return s_best < min(lo, hi) - tol or s_best > max(lo, hi) + tol


class LocationFailed(RuntimeError):
    """The location did not converge (ITMX) or a trial step failed."""


class CrossedByJump(LocationFailed):
    """The location's bracket closed on a jump of the test, not on a zero: ends, the
    converged trial points at the bracket's two ends, on the previous point's side and on
    the step end's (None where no trial has moved that end), width, the bracket's
    arclength."""

    def __init__(self, text: str, ends=(None, None), width: float = 0.0):
        super().__init__(text)
        self.ends, self.width = ends, width


def location_tolerance(settings) -> float:
    """A location's stopping tolerance on the arclength, EPSS (1 + sqrt|DS DSMAX|), as
    AUTO's LCSPAE / LCSPBV scale it; settings has EPSS, DS, DSMAX."""
    return settings.EPSS * (1 + math.sqrt(abs(settings.DS * settings.DSMAX)))


def sign_changes(prev_tests: dict, cur_tests: dict) -> list:
    """Keys of tests whose values have strictly opposite signs."""
    out = []
    for key, b in cur_tests.items():
        a = prev_tests.get(key)
        if a is None or b is None:
            continue
        if (a < 0 < b) or (b < 0 < a):
            out.append(key)
    return out


def linear_fraction(a: float, b: float) -> float:
    """Where a linear interpolation of a -> b crosses zero, in [0, 1]."""
    return a / (a - b)


def _muller(s: list, q: list) -> float | None:
    """Root of the parabola through three (s, q) pairs closest to the last s."""
    (s0, s1, s2), (q0, q1, q2) = s[-3:], q[-3:]
    h1, h2 = s1 - s0, s2 - s1
    if h1 == 0 or h2 == 0 or h1 + h2 == 0:
        return None
    d1, d2 = (q1 - q0) / h1, (q2 - q1) / h2
    a = (d2 - d1) / (h2 + h1)
    b = a * h2 + d2
    disc = b * b - 4 * a * q2
    if disc < 0:
        return None
    den = b + math.copysign(math.sqrt(disc), b)
    if den == 0:
        return None
    return s2 - 2 * q2 / den


#: Trials (with the step's end on their side) in a row on one side of the zero after
#: which the location fits a power law to the last three (`_power_secant`): Muller's
#: parabola has then had three tries and is creeping.
ONE_SIDED = 4

#: The highest order of a zero `_power_secant` fits.
MAX_ORDER = 16.0


def _widening(streak: list) -> bool:
    """Whether the last three trials on one side of the zero moved by growing steps
    (each at least the one before): Muller's parabola then creeps towards a zero far
    inside a bracket over which the test is far from quadratic (r3b's vertical family:
    the BP test of cycles goes from -4e-22 to +6e-20 over the step and is flat near the
    previous point, the trials double their distance from it six times). A bisection of
    the bracket then halves it at once (the safeguard of Brent's method)."""
    if len(streak) < 4:
        return False
    d = [streak[i + 1][0] - streak[i][0] for i in (-4, -3, -2)]
    return d[0] * d[1] > 0 and d[1] * d[2] > 0 and abs(d[1]) >= abs(d[0]) and \
        abs(d[2]) >= abs(d[1])


def _power_secant(s: list, q: list) -> float | None:
    """The zero s* of the power law q = c |s - s*|^m (sign of s - s*) through three trials
    on one side of it, or None where there is none with 1 <= m <= MAX_ORDER.

    At a zero of order m > 1 (a branch point at the tip of a fold: tfc's iso-periodic
    cycles, whose BP test goes as the cube of the distance) the secant and Muller
    iterations lose their superlinear convergence: the trials creep towards s* from one
    side, their steps shrinking by a steady ratio (about 0.71 for a cube; from a step of
    1e-2 down to EPSS = 1e-7 would take some 35 trials, more than ITMX). q^(1/m) has a
    simple zero there: m is such that the three points (s_i, q_i^(1/m)) lie on one line
    (bisection on m), s* is that line's zero. Exact for a pure power law, so that the
    iteration converges superlinearly at a zero of any order; at a simple zero m -> 1
    and this is the secant."""
    def g(v, m):
        return math.copysign(abs(v) ** (1 / m), v)

    q0, q1, q2 = q
    h1, h2 = s[1] - s[0], s[2] - s[1]

    def bend(m):
        g1 = g(q1, m)
        return (g(q2, m) - g1) / h2 - (g1 - g(q0, m)) / h1
    if len(set(s)) < 3 or 0 in q:
        return None
    a, b = 1.0, MAX_ORDER
    fa, fb = bend(a), bend(b)
    if not (np.isfinite(fa) and np.isfinite(fb)) or fa * fb > 0:
        return None
    for _ in range(60):
        mid = (a + b) / 2
        fm = bend(mid)
        if fm == 0:
            a = b = mid
            break
        a, fa, b, fb = (a, fa, mid, fm) if fa * fm < 0 else (mid, fm, b, fb)
    m = (a + b) / 2
    g1, g2 = g(q[1], m), g(q[2], m)
    if g1 == g2:
        return None
    return s[2] - g2 * (s[2] - s[1]) / (g2 - g1)


def _converged_trial(trial, s_new: float, s_last: float, settings, base=None):
    """trial(s_new), or, where its step does not converge, trial at s halved back towards
    the last converged trial s_last (AUTO's LCSPBV steps from its last trial point with
    STEPBV, which halves a failing step down to DSMIN): (point, q, s). LocationFailed when
    the retried step is below DSMIN and still fails."""
    first = None
    while True:
        try:
            pt, q = trial(s_new) if base is None else trial(s_new, base)
            return pt, q, s_new
        except (RuntimeError, ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:
            # A trial step that does not converge (ConvergenceError, ProblemError are
            # RuntimeErrors); programming errors are not turned into notes.
            first = first or exc
            half = s_last + (s_new - s_last) / 2
            if abs(half - s_last) < settings.DSMIN or half == s_new:
                raise LocationFailed(f"trial step failed at s = {s_new:.6g} after halving "
                                     f"towards s = {s_last:.6g} down to DSMIN ({first})") from exc
            s_new = half


def locate(trial, key, q_prev: float, q_cur: float, s_cur: float, settings,
           from_last: bool = False, position=None, resolution: float = 0.0,
           trace: list | None = None, crossing: bool = False):
    """Zero of test `key` between the previous point (s = 0, value q_prev) and
    the current one (s = s_cur, value q_cur).

    trial(s) -> (point, q): the continuation step of arclength s from the
    previous point and the test's value there (raises on failure).
    from_last: call trial(s, (point, s_point)) with the last converged trial instead,
    once there is one, so that the step is taken from it (AUTO's LCSPBV continues from
    its last trial point: the final step is tiny and converges in the fewest Newton
    iterations, which is what ADPTDS then sees).
    position(point) -> s: where a trial point lies on the previous point's arclength
    coordinate; with from_last no trial ends exactly at the s asked for (the first steps
    back from the step's end along the chord to it by s - s_cur, on the plane across it,
    as AUTO's first trial; the later ones step from the trial points), so
    every trial is placed by position: q must stay a function of one coordinate for the
    secant, Muller and the bracket to make sense.
    resolution: the smallest change of the test Newton's tolerance resolves between two
    points (a user value's, `first_zero`); a bracket whose ends differ by no more is no
    jump of the test, whatever its width.
    trace: a list to which every converged trial (point, s) is appended, in order.
    crossing: the test is a coordinate of the solution (a user value PAR(i) - v), which
    has no pole: a trial beyond the step's values is no reason to refuse the bracket.
    Returns (point, s) or raises LocationFailed (CrossedByJump where the bracket closed
    on a jump of the test).

    AUTO stops as soon as a correction of s is below the tolerance; a
    one-sided iteration can then stop with the zero still far inside its
    bracket. Here the sign bracket is kept and iterations go on (within ITMX)
    until it is below 10 tolerances too; if ITMX runs out first, AUTO's own
    rule decides.

    A trial that does not converge even halved (`_converged_trial`) ends the location
    at the last converged trial when the correction it was asked for is below the
    tolerance: AUTO's LCSPBV tests the next correction before it steps and returns the
    point it has (next to a branch point of cycles, where the Newton matrix is nearly
    singular, that last tiny step is the one that fails: brc's BP).
    """
    tol = location_tolerance(settings)
    lo, qlo, hi, qhi = 0.0, q_prev, s_cur, q_cur          # the bracket (as s values)
    raw = {"lo": q_prev, "hi": q_cur}                      # its ends' values, unscaled
    end_pts = {"lo": None, "hi": None}                     # its ends' trial points
    ss, qs = [0.0, s_cur], [q_prev, q_cur]
    s_new = s_cur - q_cur * s_cur / (q_cur - q_prev)       # secant (AUTO's first step)
    s_last = s_cur
    best = last = auto_nit = auto_stop = None
    zero = False
    side = 0                  # which end moved last (Illinois: halve the stale end)
    streak = [(s_cur, q_cur)]  # consecutive trials (s, q) on one side of the zero
    converged = fitted = False  # fitted: a trial's s came from `_power_secant`
    # AUTO's LCSPAE and LCSPBV take up to ITMX + 1 trials (DO NITSP1 = 0, ITMX).
    for _ in range(max(settings.ITMX, 0) + 1):
        try:
            if not from_last and last is not None and position is not None:
                try:
                    got = trial(s_new)
                except (RuntimeError, ArithmeticError, ValueError, np.linalg.LinAlgError):
                    # A trial from the previous point that fails next to a branch point
                    # (the predictor's error over the whole step against a nearly
                    # singular Newton matrix) is taken, from then on, from the last
                    # converged trial, as AUTO's LCSPAE always steps (STEPAE from its
                    # current point): short steps whose predictor is nearly exact.
                    from_last = True
                else:
                    got = (*got, s_new)
            else:
                got = None
            base = (last[0], last[1]) if (from_last and last is not None) else None
            if got is not None and not from_last:
                pt, q, s_new = got
            else:
                pt, q, s_new = _converged_trial(trial, s_new, s_last, settings, base)
            # Trials from the last trial, and the chord's first trial (a step back from
            # the step's end, `iterator.Continuation._trial`), land off the s asked: each
            # is placed by its projection. The first trial of a BP of a BVP, a step from
            # prev along its tangent on its plane, stays at the s asked, as before the
            # chord's trial: placed by its projection, ppp's BP of cycles at the tip of its
            # fold moved 5.7e-10 in arclength and the step after it then failed down to
            # DSMIN (its EP at NMX lost, an MX).
            if position is not None and (base is not None
                                         or (from_last and key != Code.BPC)):
                s_new = position(pt)
        except LocationFailed:
            if last is not None and abs(s_new - last[1]) < 2 * tol:
                best = last
                break
            raise
        if q is None or not np.isfinite(q):
            raise LocationFailed("test function undefined at a trial point")
        if trace is not None:
            trace.append((pt, s_new))
        if q == 0:
            best = (pt, s_new, q)
            break
        streak = streak + [(s_new, q)] if (q < 0) == (streak[0][1] < 0) else [(s_new, q)]
        if (q < 0) == (qlo < 0):
            lo, qlo = s_new, q
            raw["lo"] = q
            end_pts["lo"] = pt
            if side == -1:
                qhi /= 2
            side = -1
        else:
            hi, qhi = s_new, q
            raw["hi"] = q
            end_pts["hi"] = pt
            if side == 1:
                qlo /= 2
            side = 1
        last = (pt, s_new, q)
        converged, was_converged = abs(s_new - s_last) < tol, converged
        if converged:
            best = (pt, s_new, q)
            if abs(hi - lo) < 10 * tol or (was_converged and fitted):
                # the bracket is closed, or, at a zero of high order approached from one
                # side (the power law fitted once), two corrections in a row were below
                # the tolerance: the bracket's far end stays where it was
                break
        ss.append(s_new)
        qs.append(q)
        s_last = s_new
        cand, fit = _muller(ss, qs), None
        if len(streak) >= ONE_SIDED:
            # trials creeping from one side: the zero of the power law through the last
            # three (`_power_secant`)
            s3, q3 = zip(*streak[-3:])
            fit = _power_secant(list(s3), list(q3))
            cand = cand if fit is None else fit
        a, b = min(lo, hi), max(lo, hi)
        if _widening(streak):
            cand = (lo + hi) / 2                          # bisection (`_widening`)
        elif cand is None or not (a < cand < b):
            cand = hi - qhi * (hi - lo) / (qhi - qlo)     # Illinois regula falsi
        fitted = fitted or (fit is not None and cand == fit)
        if auto_nit is None and abs(cand - s_new) < tol:
            # AUTO's LCSPBV would stop here (the next correction is below the
            # tolerance): ADPTDS then sees this trial's Newton count.
            auto_nit = getattr(pt, "iterations", None)
            auto_stop = (pt, s_new, q)
        s_new = cand
    if best is None and last is not None and \
            abs(last[2]) <= ZERO_FACTOR * max(abs(q_prev), abs(q_cur)):
        best, zero = last, True        # crept onto a zero of high order: it is there
    if best is None and auto_stop is not None:
        # ITMX ran out before the bracket closed: AUTO's rule decides, which stops at
        # the first trial whose next correction is below the tolerance (the iteration
        # converging just as ITMX runs out: the base hepatocyte model's PD of cycles in
        # docs/auto_compatibility.md's problems of AUTO users, its next correction 5.7e-10
        # after a step of
        # 9.3e-8, ITMX = 4).
        best = auto_stop
    if best is None:
        tried = f"; {len(ss) - 2} trials, the last at s = {last[1]:.6g} with test " \
            f"{last[2]:.3g}" if last is not None else ""
        raise LocationFailed(f"no convergence in ITMX = {settings.ITMX} iterations (the "
                             f"step: s = 0 to {s_cur:.6g}, test {q_prev:.3g} to {q_cur:.3g}"
                             f"{tried}; bracket [{min(lo, hi):.6g}, {max(lo, hi):.6g}])")
    pt, s_best, q = best
    if not crossing and abs(q) > POLE_FACTOR * max(abs(q_prev), abs(q_cur)):
        raise LocationFailed("sign change through a pole, not a zero")
    if _left_behind(s_best, lo, hi, tol) and _no_nearer_zero(q, q_prev, q_cur):
        raise LocationFailed(f"sign change through a pole, not a zero (the test is {q:.3g} "
                             f"at s = {s_best:.3g}, {q_prev:.3g} and {q_cur:.3g} at the "
                             f"step's ends, the last bracket [{min(lo, hi):.3g}, "
                             f"{max(lo, hi):.3g}])")
    width = abs(hi - lo)
    # An end of the bracket this far below the step's values is the zero itself: across a
    # bracket narrower than the trials' Newton tolerance the test's change is their noise
    # (r3b's circle of L5 at mu = 1: -3.6e-10 and +4.4e-6 across 5.3e-11 in arclength,
    # the test 0.47 and -0.18 at the step's ends).
    zero = zero or min(abs(raw["lo"]), abs(raw["hi"])) <= \
        ZERO_FACTOR * max(abs(q_prev), abs(q_cur))
    if not zero and 0 < width < 10 * tol and q_cur != q_prev and \
            abs(raw["lo"] - raw["hi"]) > resolution and \
            abs(raw["lo"] - raw["hi"]) / width > \
            JUMP_FACTOR * abs(q_cur - q_prev) / abs(s_cur):
        # The bracket closed on a jump, not a zero: the test changes across it as over
        # a step JUMP_FACTOR times longer (AUTO's Muller iteration, without a bracket,
        # creeps towards such a point and stops at ITMX: "Possible special point";
        # tfc's test of BPs of cycles just after its Hopf start, -6.8e-7 at 2e-9 from
        # the previous point, +5e-7 there).
        raise CrossedByJump(f"sign change through a jump, not a zero (the test changes by "
                            f"{abs(raw['lo'] - raw['hi']):.3g} across the last bracket of "
                            f"{width:.3g})", (end_pts["lo"], end_pts["hi"]), width)
    if auto_nit is not None and hasattr(pt, "iterations"):
        # The step control after a located point counts the Newton iterations of the
        # trial AUTO ends its location with (the further trials that narrow the
        # bracket here are tiny steps of one iteration).
        pt.iterations = auto_nit
    return pt, s_best


# AUTO's HMACH (settings.HMACH): LCSPAE / LCSPBV lengthen every secant and Muller
# correction by this fraction, so that a trial lands just beyond the estimated zero.


def at_step_end(q_prev: float, q_cur: float, s_cur: float, settings) -> bool:
    """Whether the zero of a test that changed sign from q_prev to q_cur over a step of
    arclength s_cur is located at the step's end itself: AUTO's LCSPAE / LCSPBV return
    the current point, without a trial step, when the first secant correction back to
    the zero, (1 + HMACH) q_cur s_cur / (q_prev - q_cur), is below the location tolerance
    EPSS (1 + sqrt|DS DSMAX|). The point is then where the continuation step put it, on
    the far side of the zero (phs's UZ at PAR(1) = 1 = RL1: the step lands 1e-7 beyond
    it, which AUTO writes as the end point EP)."""
    tol = location_tolerance(settings)
    return abs((1 + HMACH) * q_cur * s_cur) < tol * abs(q_prev - q_cur)


def _solution_jumped(exc: Exception, prev, target, inner) -> bool:
    """Whether a location that failed on a jump of its test (CrossedByJump) had the
    solution itself jump across its last bracket: the bracket's end points (an end no
    trial has moved is still the interval's own, prev or target) lie JUMP_FACTOR times
    further apart, in the system's inner product, than the bracket's arclength."""
    if not isinstance(exc, CrossedByJump):
        return False
    lo_pt, hi_pt = exc.ends
    d = (target if hi_pt is None else hi_pt).x - (prev if lo_pt is None else lo_pt).x
    return math.sqrt(inner(d, d)) > JUMP_FACTOR * exc.width


def locate_past_jump(trial, q_prev: float, q_cur: float, s_cur: float, settings):
    """AUTO's LCSPBV as it runs where the branch jumped across a user value within the
    step (`_solution_jumped`): (point, s) of its last trial, or LocationFailed.

    The first trial steps back from the step's end by the secant correction
    (1 + HMACH) q_cur s_cur / (q_prev - q_cur) (trial(s)); every later one steps from the
    last trial by Muller's correction as it stands (trial(s, (last, s_last, True))). The
    s of each trial is the one asked for, not where Newton put it: on the far sheet
    the trials land where it lies, whatever s says, and their test hardly changes.
    Muller's parabola (`_muller`) runs through the bracket's end q0 (at s0, prev's
    until a trial changes sign), the trial before (q1, s1) and the last (AUTO's MUELLER:
    q0, s0 move to q1, s1 where the last trial's sign differs from q1's), and the
    location stops when its correction is below the tolerance EPSS (1 + sqrt|DS DSMAX|),
    at most ITMX + 1 trials: it converges as the trials stop moving, not on a zero of
    the test. kdv's run 3 (PAR(1) from 3.0488 to 2.7364 across UZR = 3): AUTO's trials
    land at PAR(1) - 3 = -0.2703, -0.2705, -0.27049 and it labels the last, UZ4 at
    2.7295; mtn's run 2, where the step lands 0.0066 past AUTO's UZ6 at 5.98510."""
    tol = location_tolerance(settings)
    s0, q0, s1, q1 = 0.0, q_prev, s_cur, q_cur
    rds = (1 + HMACH) * q1 / (q0 - q1) * (s1 - s0)
    last = None
    for _ in range(max(settings.ITMX, 0) + 1):
        s = s1 + rds
        pt, q = trial(s) if last is None else trial(s, (last, s1, True))
        if q is None or not np.isfinite(q):
            raise LocationFailed("test function undefined at a trial point")
        root = _muller([s0, s1, s], [q0, q1, q])
        if root is None:
            raise LocationFailed(f"Muller's parabola has no real zero (trial at s = {s:.6g}, "
                                 f"test {q:.3g})")
        if (q1 < 0) != (q < 0):
            s0, q0 = s1, q1
        s1, q1, last = s, q, pt
        rds = (1 + HMACH) * (root - s)
        if abs(rds) < tol:
            return pt, s
    raise LocationFailed(f"no convergence in ITMX = {settings.ITMX} iterations past the jump "
                         f"(the last trial at s = {s1:.6g} with test {q1:.3g})")


def first_zero(prev, cur, ds: float, settings, *, trial, accepted, refresh, inner, note,
               curve_type: int = 0, secant: bool = False, sphere: bool = False,
               resolution=None):
    """The earliest accepted zero between the points prev and cur (a step of arclength
    ds): (point, key, keys of other tests vanishing at the same point) or None. A zero
    that cannot be located is left (`note` says so, AUTO's "Possible special point")
    and the next one is tried.

    trial(s, key, base, chord, span) -> (point, value of test key): the continuation
        step of arclength s from prev, evaluating that test only; chord: the secant from
        prev to the far end of the interval being searched per unit of its arclength span
        (prev.x + span chord is that end: the predictor's line); base: (an earlier trial
        point, its s) to step from it instead, with a third item True to step along that
        point's own direction by s - its s as it stands (`locate_past_jump`).
    accepted(key, prev, cur) -> bool: the system's acceptance rule (UZ keys always).
    refresh(point) -> None: all test values at a located point, at its tangent.
    inner(a, b): the system's inner product (the BP's secant is made unit in it).
    note(text): a d-file note.
    secant: leave every located point along the secant from prev (AUTO's CONTBV on
        BVPs: UDOTPS = (UPS - UOLDPS) / DSOLD after every point), not only branch points.
    sphere: the arclength is the sphere about prev (`System.arclength`): a trial's s is
        its distance from prev (signed as the step), else its projection on prev's step
        direction (the plane). The location's bracket holds trials from prev and trials
        from the last trial (`locate`'s position): both must be measured in the
        coordinate in which a step from prev of arclength s lands at s.
    resolution(key) -> float: the smallest change of test key Newton's tolerance resolves
        (`locate`); 0 where None.

    Zeros of several tests at one point (a transcritical BP is also a zero eigenvalue;
    two Hopf loci crossing) are one special point: its type is the first in AUTO's
    order (`autos_type`), whichever zero was located. A zero whose first secant estimate lies
    within the location tolerance of cur is cur itself (`at_step_end`): the point returned
    is then the object cur."""
    target, span, found = cur, ds, None
    failed: set = set()
    tol = 10 * location_tolerance(settings)
    # Zeros located in this step: key -> s. One located within the tolerance of the
    # interval's far end lies there (a fold located first, then a branch point between
    # prev and it, at a symmetric pitchfork where both vanish at one point): its test is
    # not searched again short of it, where its value at the branch point (next to a
    # crossing branch, whatever tangent the trial took) says nothing of this branch.
    located: dict = {}
    # Once a point is located, a test whose zero lies within the location tolerance of
    # it (`at_step_end` from prev to it) is not searched: AUTO's LCSPAE / LCSPBV set its
    # Q1 = 0 there (AP%ITP /= 0), so it neither changes sign nor moves the point. A
    # fraction of the step (SIMULTANEOUS) is no such rule: snh's h1b (BP test at
    # rounding level, -1.5e-13 before its fold and 1e-16 at it) had its BP searched
    # 2.5e-6 of arclength short of the located fold, a noise zero the location
    # converged on; the point, typed LP, then lay short of the fold (fold test 1.5e-3,
    # not 0) and the next step labelled the fold again, 3.4e-10 further in nu1.
    for _ in range(2 * len(cur.tests) + 1):
        keys = [k for k in sign_changes(prev.tests, target.tests)
                if (found is None or k != found[1]) and k not in failed
                and not (k in located and abs(located[k] - span) < tol)
                and not (found is not None and _same_user_point(found[1], k, prev, target,
                                                                span, settings))
                and not (found is not None and k in (Code.LP, Code.LPC)
                         and found[1] in TORUS_FOLDS.get(curve_type, ()))
                and not (found is not None
                         and at_step_end(prev.tests[k], target.tests[k], span, settings))
                and accepted(k, prev, target)
                and SIMULTANEOUS < linear_fraction(prev.tests[k], target.tests[k])
                < (1 - SIMULTANEOUS if found is not None else 2)]
        if not keys:
            break
        keys.sort(key=lambda k: linear_fraction(prev.tests[k], target.tests[k]))
        key = keys[0]
        if found is None and key in (Code.BP, Code.BPC):
            # AUTO's LCSPAE / LCSPBV take the fold test before the branch-point test:
            # where both change sign over a step the fold is located first (the BP only
            # if it lies between the previous point and the fold): next to a BP the
            # linear estimate of its determinant's zero is no guide to the order.
            folds = [k for k in keys if k in (Code.LP, Code.LPC)]
            if folds:
                key = folds[0]
        if found is None and key in (Code.LP, Code.LPC):
            turns = [k for k in keys if k in TORUS_FOLDS.get(curve_type, ())]
            if turns:
                key = turns[0]
        # The trial points' predictor runs along the chord from prev to the interval's far
        # end (AUTO's LCSPAE steps back from the far point along its secant, the same
        # line): an interpolation between two points of the branch. Prev's tangent
        # extrapolates instead, and where another branch crosses within the step (a
        # pitchfork met at its fold, u^3 - p u = 0 followed along p = u^2) it leaves
        # the branch's side and Newton converges onto the crossing branch.
        chord = (target.x - prev.x) / span
        if found is None and at_step_end(prev.tests[key], target.tests[key], span, settings):
            # AUTO's LCSPAE / LCSPBV: the step's end is the special point itself.
            refresh(target)
            found = (target, key)
            located[key] = span
            near_sp = [(prev, 0.0)]
            continue
        trace: list = []
        try:
            sp, s_sp = locate(lambda s_, base=None: trial(s_, key, base, chord, span), key,
                              prev.tests[key], target.tests[key], span, settings,
                              from_last=secant,
                              position=(lambda p: signed_distance(p.x - prev.x, span, inner))
                              if sphere else
                              (lambda p: inner(p.x - prev.x, prev.step_direction)),
                              resolution=0.0 if resolution is None else resolution(key),
                              trace=trace, crossing=isinstance(key, tuple))
        except RuntimeError as exc:
            if isinstance(key, tuple) and _solution_jumped(exc, prev, target, inner):
                # The solution itself jumps across the bracket (its ends' states lie
                # JUMP_FACTOR times further apart than its arclength: Newton leaving for
                # another sheet of solutions within the step), and a user value's test, the
                # parameter PAR(i) - v, crosses the value with it. AUTO's LCSPBV, whose trials
                # step on from the step's end, labels it on that side, at its last trial
                # (`locate_past_jump`); its scripts count that label (kdv.auto's r3('UZ2')
                # is the UZ at 3 reached later). Where those trials fail, and on algebraic
                # branches (LCSPAE's trials, from prev on the sphere, are not these), the
                # step's end is labelled. A value that jumps while the solution does not (a
                # PVLS's step function of the state) is no crossing of the branch: left
                # unlocated.
                name, past = _key_name(key, curve_type), None
                if secant:
                    try:
                        sp, s_sp = locate_past_jump(
                            lambda s_, base=None: trial(s_, key, base, chord, span),
                            prev.tests[key], target.tests[key], span, settings)
                    except RuntimeError as failed_past:
                        past = failed_past
                if secant and past is None:
                    note(f"NOTE:{name} crossed by a jump of the branch, labelled at the "
                         f"location's last trial past it ({exc})")
                    sp.across_jump = True
                else:
                    why = "" if past is None else f"; past the jump: {past}"
                    note(f"NOTE:{name} crossed by a jump of the branch, labelled where the "
                         f"step landed ({exc}{why})")
                    sp, s_sp = target, span
                refresh(sp)
                found = (sp, key)
                located[key] = s_sp
                near_sp = [(prev, 0.0)]
                target, span = sp, s_sp
                continue
            # LocationFailed, or a failed evaluation (ConvergenceError, ProblemError):
            # that zero stays unlocated (AUTO: "Possible special point"); the other
            # tests of the interval are still looked at (a UZSTOP next to a noisy GH
            # test must still stop the run).
            failed.add(key)
            note(f"NOTE:Possible special point ({_key_name(key, curve_type)}: {exc})")
            continue
        refresh(sp)
        near_sp = [(prev, 0.0), (target, span)] + trace
        found = (sp, key)
        located[key] = s_sp
        target, span = sp, s_sp
    if found is None:
        return None
    sp, key = found
    # User values vanishing at a located one: the point's key is the first in AUTO's
    # order (`_same_user_point`); the others are stored as 0 with it, not labelled.
    users = [k for k in sign_changes(prev.tests, cur.tests)
             if k == key or _same_user_point(key, k, prev, sp, span, settings)] \
        if isinstance(key, tuple) else []
    if users:
        key = min(users, key=lambda k: k[1])
    # Other tests that change sign over the step and vanish at sp, to within the
    # location tolerance, by their linear zero estimate from sp's value. A test located
    # earlier in this step, before this one moved the point short of it, is not among
    # them: AUTO visits each test once (LCSPAE / LCSPBV in CNRLAE's / CNRLBV's loop), and
    # a test it located is evaluated afresh where a later one's location leaves the point
    # (DO ITEST = 1, ISTEPPED - 1), its zero then labelled on the next step if it lies
    # beyond: a fold located first, then a branch point between the previous point and
    # the fold, is a BP here.
    earlier = [k for k in located if k != key]
    same = []
    for k in sign_changes(prev.tests, cur.tests):
        # User values are not merged with each other here: one vanishing at a located
        # user value is that point's (`_same_user_point`, above). A bifurcation test
        # vanishing at a located UZ overrides it (LCSPAE: the point is typed by the
        # bifurcation, and a UZSTOP there does not stop); a UZ vanishing at a located
        # bifurcation is that point.
        if k == key or (isinstance(k, tuple) and isinstance(key, tuple)):
            continue
        if k in earlier:
            continue
        if k not in sp.tests or sp.tests[k] is None:
            continue
        slope = abs(cur.tests[k] - prev.tests[k]) / abs(ds)
        if slope > 0 and abs(sp.tests[k]) / slope < tol and accepted(k, prev, cur):
            same.append(k)
    folds = [k for k in sign_changes(prev.tests, cur.tests) if k in (Code.LP, Code.LPC)]
    if key in TORUS_FOLDS.get(curve_type, ()) and folds:
        same = [k for k in same if k not in folds] + folds
        best = key
    else:
        best = autos_type([key] + same, curve_type)
    if best != key:
        same = [k for k in same if k != best] + [key]
    tangent = branch_point_tangent(sp, span, near_sp, tol / 10, inner) \
        if sphere and best in (Code.BP, Code.BPC) else None
    if tangent is not None:
        # AUTO's direction there (`branch_point_tangent`): the point's tangent (its
        # tests' border, the direction written, the one a branch switch starts from:
        # AUTO's STBIF stores this UDOT) and the next step's predictor.
        sp.tangent = tangent
        refresh(sp)
    elif best in (Code.BP, Code.BPC) or secant:
        # At a branch point G_x has a two-dimensional null space: the bordered
        # tangent solve is singular there, and its solution may point along the other
        # branch (cosine 4e-4 with the branch's direction was measured at a BP of
        # cycles). The branch's direction is the secant from the previous point (AUTO
        # stores it too, and on BVPs takes it at every point). Divided by the signed
        # arclength of the located step (x_sp = x_prev + s t), so that the tangent keeps
        # the branch's orientation for negative DS too.
        sec = (sp.x - prev.x) / span
        sp.tangent = sec / math.sqrt(inner(sec, sec))
        refresh(sp)
    # best is stored as 0 too: the label's test (a fold typed over a branch point found
    # within the tolerance of it) would otherwise change sign again on the next step
    # where sp lies short of its zero, and label the same point twice.
    clear_located(prev, sp, span, [best, key] + same + users, settings, fresh=earlier)
    return sp, best, same


def branch_point_tangent(sp, s_sp: float, points: list, tol: float, inner):
    """The followed branch's unit tangent at a branch point sp, at s_sp on the previous
    point's arclength coordinate s, or None: the derivative at s_sp of the quadratic
    through sp and, on either side of it, the point of `points` ((point, s): the step's
    ends and the location's trials) nearest to it at least tol away; dx/ds, oriented as
    s (as every step direction is: x_next = x + ds d), unit in the inner product. With
    those points at distances h_a, h_b its error is at most h_a h_b max|x'''| / 6 plus
    2 eps / min(h_a, h_b) for points off the branch by eps (Newton's tolerance).

    At a branch point G_x's null space is two-dimensional: no tangent solve defines the
    branch's direction there. AUTO's SOLVAE leaves every converged step along its secant,
    UDOT = (U - UOLD) / RDS, the steps of LCSPAE's location included, which step on from
    each other: AUTO leaves a located point along the secant of its last location step,
    a correction of at least the location tolerance tol (the location stops once the
    next one is below it), the followed branch's tangent at the point to within that
    step's length times the curvature plus Newton's error over it. Our trials are steps
    from the previous point, each converged to Newton's tolerance on its own: the chord
    from the previous point was off by half the branch's turn over the whole step (the
    restricted three-body problem's circle of equilibria, tests/data/auto_demos/nbody:
    the step after each BP then took 3 Newton iterations where AUTO's takes 2, and ADPTDS
    kept its steps at 2/3 of AUTO's); the secant from the last trial before sp was
    Newton's noise over their distance where they lie closer than tol (on that circle,
    EPSU = 1e-9, a BP's last trial 1.2e-6 from the one before lay 2.3e-9 off the circle
    in PAR(1), and that secant's PAR(1) component was 1.9e-3, the circle's 0)."""
    near = []
    for side in (-1, 1):
        # the nearest point at least tol away on each side of sp (along s's sign)
        cands = [p for p in points if p[0] is not sp and abs(p[1] - s_sp) >= tol
                 and (p[1] - s_sp) * side > 0]
        if not cands:
            return None
        near.append(min(cands, key=lambda p: abs(p[1] - s_sp)))
    (pa, sa), (pb, sb) = near
    d = pa.x * ((s_sp - sb) / ((sa - sb) * (sa - s_sp))) \
        + pb.x * ((s_sp - sa) / ((sb - sa) * (sb - s_sp))) \
        + sp.x * (1 / (s_sp - sa) + 1 / (s_sp - sb))
    n = math.sqrt(inner(d, d))
    return d / n if n > 0 and math.isfinite(n) else None


def _same_user_point(found, k, prev, sp, span: float, settings) -> bool:
    """Whether user value k (a UZ key) vanishes at sp, where user value `found` was
    located, a step of arclength span from prev: AUTO's LCSPAE / LCSPBV, once a point is
    located, store 0 for a later test whose zero lies within the location tolerance of it
    (`at_step_end`), and its UZ tests come first, in IUZ's order (UZR's values as listed,
    then UZSTOP's: `Settings.UZR`'s). So a UZR value and a UZSTOP value at one parameter
    value are one point, typed by the UZR: labelled once, and the run does not stop
    there (AUTO-07p 0.9.2 on ab's equilibria, ab's cycles and exp's BVP,
    tests/test_uz_stop.py)."""
    return isinstance(found, tuple) and isinstance(k, tuple) and k != found \
        and k in prev.tests and sp.tests.get(k) is not None \
        and at_step_end(prev.tests[k], sp.tests[k], span, settings)


def signed_distance(d: np.ndarray, s: float, inner) -> float:
    """The distance |d| in the system's inner product, signed as s: where a step of
    arclength s from a point lands on the sphere arclength (AUTO's SOLVAE)."""
    return math.copysign(math.sqrt(inner(d, d)), s)


def clear_located(prev, sp, s_sp: float, located, settings, fresh=()) -> None:
    """The stored values of the tests at a located special point sp, reached by a step of
    arclength s_sp from prev: AUTO's LCSPAE (ae.f90) and LCSPBV (bvp.f90) return Q = 0
    for the test they located, and, once a point is located (AP%ITP /= 0), set Q1 = 0
    for every test whose zero lies within the location tolerance of it
    (|(1 + HMACH) Q1 DSTEST| < EPSS (1 + sqrt|DS DSMAX|) |Q0 - Q1|, `at_step_end` with
    DSTEST = s_sp). A stored 0 never makes a sign change with the next point's value
    (`sign_changes`), so the zero just located is not counted again on the next step,
    whatever sign noise gives the test there: next to a double zero (a fold and a
    branch point together at a symmetric pitchfork) the test's value at the located
    point and at the next one are both rounding noise.

    located: the tests labelled at sp (the one located and those merged with it).
    User values (UZ tests) are kept apart as in the merge (`first_zero`): two UZR values
    within the tolerance of each other are two points, so only a located UZ is cleared.
    fresh: tests located earlier in the step, short of which a later location moved the
    point: they keep their values at sp (AUTO evaluates them afresh there)."""
    for k, q in sp.tests.items():
        if q is None or k in fresh:
            continue
        q0 = prev.tests.get(k)
        if k in located or (not isinstance(k, tuple) and q0 is not None
                            and at_step_end(q0, q, s_sp, settings)):
            sp.tests[k] = 0.0
