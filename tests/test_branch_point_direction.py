"""The direction an algebraic run leaves a located branch point with, against the closed
form (sympy) and AUTO-07p's own run of the same equations.

f(u, p) = v (p - v^2), v = u - p - p^2 (p = PAR(1)): two branches cross at the origin,
the curved u = p + p^2 (tangent (1, 1) / sqrt 2 there, curvature 1 / sqrt 2) and the
pitchfork p = v^2 (tangent (1, 0)). Followed from p = -0.5 along the curved one, the run
locates the BP at the origin and goes on along that branch. AUTO-07p leaves every
converged step along its secant (SOLVAE: UDOT = (U - UOLD) / RDS), its location's steps
included, so it leaves the BP along the secant of its last location step: the followed
branch's tangent there to within that step's length times the curvature plus Newton's
error over it. That UDOT is also what its s-file holds at the BP and a branch switch
starts from. The tangent solve cannot give it (G_x's null space is two-dimensional), and
the chord from the previous point, which washer took, is off by half the branch's turn
over the step (8.5e-3 here). washer estimates that tangent from the location's points
(`events.branch_point_tangent`).
"""
import tempfile
from pathlib import Path

import numpy as np
import sympy as sp

from washer.auto.files import read_s
from washer.cont.problem import Problem
from washer.run import run

DATA = Path(__file__).parent / "data" / "bp_direction"
#: The constants of DATA/bpd.auto, with which AUTO-07p wrote DATA/b.bpd and s.bpd.
EPSS, EPSU, DS, DSMAX = 1e-5, 1e-8, 0.05, 0.1
CONSTANTS = (f"NDIM = 1, IPS = 0, IRS = 0, ICP = [1], ISP = 1, ILP = 0, MXBF = 0, NMX = 30, "
             f"DS = {DS}, DSMIN = 1e-4, DSMAX = {DSMAX}, EPSS = {EPSS}, EPSL = 1e-8, "
             f"EPSU = {EPSU}, ITMX = 8, RL0 = -1, RL1 = 1\n")


def func(u, par):
    p = par[0]
    v = u[0] - p - p * p
    return np.array([v * (p - v * v)])


def stpnt(u, par):
    par[0], u[0] = -0.5, -0.25


def closed_form():
    """The followed branch (u(p), as a function) and, at the crossing (0, 0), its unit
    tangent (u', p') and the largest |x'''| (third derivative in arclength) for |p| <=
    0.06, all from sympy; the crossing is checked to be a zero of f with f_u = f_p = 0
    (both branches through it)."""
    u, p = sp.symbols("u p", real=True)
    v = u - p - p**2
    f = v * (p - v**2)
    branch = p + p**2
    assert sp.simplify(f.subs(u, branch)) == 0
    at = {u: 0, p: 0}
    assert f.subs(at) == 0 and sp.diff(f, u).subs(at) == 0 and sp.diff(f, p).subs(at) == 0
    x = sp.Matrix([branch, p])
    speed = sp.sqrt(x.diff(p).dot(x.diff(p)))
    t = x.diff(p) / speed
    x3 = (t.diff(p) / speed).diff(p) / speed
    third = sp.lambdify(p, sp.sqrt(x3.dot(x3)))
    tangent = np.array([float(c) for c in t.subs(p, 0)])
    return sp.lambdify(p, branch), tangent, max(third(np.linspace(-0.06, 0.06, 241)))


def _run():
    with tempfile.TemporaryDirectory() as d:
        c = Path(d) / "c.bpd"
        c.write_text(CONSTANTS)
        return run(c, verbose=False, problem=Problem(1, func, stpnt, name="bpd"), files=False)


def _unit(d):
    return d / np.linalg.norm(d)


def test_the_run_leaves_the_branch_point_along_the_followed_branch():
    u_of, tangent, x3 = closed_form()
    r = _run()
    (bp,) = [s for s in r.specials if s.ty == "BP"]
    rows = {abs(row.pt): row for row in r.rows if abs(row.br) == 1}
    prev, nxt = rows[bp.pt - 1], rows[bp.pt + 1]
    tol = EPSS * (1 + np.sqrt(DS * DSMAX))             # the location's, in arclength
    assert np.hypot(bp.u[0], bp.par[0]) < tol + EPSU

    # The bound of `branch_point_tangent`: the quadratic through the BP and a point on
    # either side of it at h_a, h_b (h_a + h_b <= the step over the BP, `span`: the
    # step after it has its arclength, as CNRLAE adapts steps after regular points
    # only) is off the tangent by h_a h_b max|x'''| / 6 <= span^2 max|x'''| / 24, and
    # its points' Newton errors eps = EPSU (1 + |x|) add 2 eps / min(h) <= 2 eps / tol.
    span = np.hypot(nxt.values[2] - bp.u[0], nxt.values[0] - bp.par[0])
    bound = span**2 * x3 / 24 + 2 * EPSU * (1 + 0.1) / tol
    leave = _unit(np.r_[bp.udot, bp.rldot[0]])
    assert np.linalg.norm(leave - tangent) < bound, (leave, tangent, bound)
    # what the chord from the previous point gives is outside that bound
    chord = _unit(np.array([-prev.values[2], -prev.values[0]]))
    assert np.linalg.norm(chord - tangent) > 2 * bound

    # AUTO-07p's own run: its BP's UDOT is the followed branch's tangent to the same bound
    autos = next(rec for rec in read_s(DATA / "s.bpd") if rec.ty == "BP")
    auto_leave = _unit(np.r_[autos.udot, autos.rldot[0]])
    assert np.linalg.norm(auto_leave - tangent) < bound
    # and the next point is on the followed branch, beyond the crossing
    assert nxt.values[0] > 0
    assert abs(nxt.values[2] - u_of(nxt.values[0])) < 10 * EPSU
