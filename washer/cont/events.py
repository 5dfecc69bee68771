"""Special points on a branch: sign changes of test functions, their location
and AUTO's rules for them (LCSPAE / LCSPBV).

A test value changes sign between two consecutive points when the two values
have strictly opposite signs (AUTO tests Q0 * Q1 < 0 by signs, so a value
that is exactly 0 or undefined on either side never counts). The system's
`accept` rule must then agree (an HB needs the stable count to change by 2).
When several tests change sign in one step, the earliest zero along the
branch is located first, by a linear estimate, then re-checked: the interval
up to the located point is searched again, so no zero is stepped over.

Location (LCSPAE): trial points are continuation steps of arclength s from
the previous point; the first trial is the secant estimate, then Muller's
method (a parabola through the last three (s, q) pairs) kept inside the
bracket, up to ITMX iterations. A trial step that does not converge is retried
at s halved back towards the last converged trial, down to DSMIN, as AUTO's
STEPBV halves the step of its location (the bracket is kept). Converged when the last change of s satisfies
|delta s| / (1 + sqrt(|DS DSMAX|)) < EPSS: that is the location tolerance in
arclength (parameters are located to about that times the parameter's rate
along the branch; in practice much better, since Muller converges with order
~1.84 and the last step is below the tolerance). A location that does not
converge, or whose trial step fails, is not an error: the point is kept
unlabelled and the d-file says "NOTE:Possible special point" (AUTO).
"""
from __future__ import annotations

import math

import numpy as np

#: A located "zero" whose test value exceeds both bracketing values in
#: magnitude is a sign change through a pole or a jump (e.g. the first
#: Lyapunov coefficient through a zero eigenvalue), not a zero: rejected.
POLE_FACTOR = 1.0


class LocationFailed(RuntimeError):
    """The location did not converge (ITMX) or a trial step failed."""


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


def _converged_trial(trial, s_new: float, s_last: float, settings):
    """trial(s_new), or, where its step does not converge, trial at s halved back towards
    the last converged trial s_last (AUTO's LCSPBV steps from its last trial point with
    STEPBV, which halves a failing step down to DSMIN): (point, q, s). LocationFailed when
    the retried step is below DSMIN and still fails."""
    first = None
    while True:
        try:
            pt, q = trial(s_new)
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


def locate(trial, key, q_prev: float, q_cur: float, s_cur: float, settings):
    """Zero of test `key` between the previous point (s = 0, value q_prev) and
    the current one (s = s_cur, value q_cur).

    trial(s) -> (point, q): the continuation step of arclength s from the
    previous point and the test's value there (raises on failure).
    Returns (point, s) or raises LocationFailed.

    AUTO stops as soon as a correction of s is below the tolerance; a
    one-sided iteration can then stop with the zero still far inside its
    bracket. Here the sign bracket is kept and iterations go on (within ITMX)
    until it is below 10 tolerances too; if ITMX runs out first, AUTO's own
    rule decides.
    """
    tol = settings.EPSS * (1 + math.sqrt(abs(settings.DS * settings.DSMAX)))
    lo, qlo, hi, qhi = 0.0, q_prev, s_cur, q_cur          # the bracket (as s values)
    ss, qs = [0.0, s_cur], [q_prev, q_cur]
    s_new = s_cur - q_cur * s_cur / (q_cur - q_prev)       # secant (AUTO's first step)
    s_last = s_cur
    best = None
    side = 0                  # which end moved last (Illinois: halve the stale end)
    for _ in range(max(settings.ITMX, 1)):
        pt, q, s_new = _converged_trial(trial, s_new, s_last, settings)
        if q is None or not np.isfinite(q):
            raise LocationFailed("test function undefined at a trial point")
        if q == 0:
            best = (pt, s_new, q)
            break
        if (q < 0) == (qlo < 0):
            lo, qlo = s_new, q
            if side == -1:
                qhi /= 2
            side = -1
        else:
            hi, qhi = s_new, q
            if side == 1:
                qlo /= 2
            side = 1
        converged = abs(s_new - s_last) < tol
        if converged:
            best = (pt, s_new, q)
            if abs(hi - lo) < 10 * tol:
                break
        ss.append(s_new)
        qs.append(q)
        s_last = s_new
        cand = _muller(ss, qs)
        a, b = min(lo, hi), max(lo, hi)
        if cand is None or not (a < cand < b):
            cand = hi - qhi * (hi - lo) / (qhi - qlo)     # Illinois regula falsi
        s_new = cand
    if best is None:
        raise LocationFailed(f"no convergence in ITMX = {settings.ITMX} iterations")
    pt, s_best, q = best
    if abs(q) > POLE_FACTOR * max(abs(q_prev), abs(q_cur)):
        raise LocationFailed("sign change through a pole, not a zero")
    return pt, s_best
