"""Algebraic optimisation (IPS = 5) against extrema solved with sympy.

tests/data/optcusp/optcusp.py: FOPT = u + p1 - p1^2 - p2^2 on the cusp surface
u^3 - p1 u - p2 = 0 (its docstring states the conditions). The first run (IRS = 0, NFPR = 2:
p1 free) follows the curve p1 = u^2 - p2 / u at p2 = 0.1 and its LP in PAR(10) is the
extremum of FOPT along it; the second, from that LP (NFPR = 3: the extremum in p1
continued in p2, with the Lagrange multipliers), has its LP at the extremum over the
surface, where grad FOPT = lambda grad f. sympy reduces both to polynomials in u and finds
their real roots; the multipliers the record stores (v, v0) give lambda = -v / v0.

Tolerance: a located LP lies within AUTO's location tolerance EPSS (1 + sqrt|DS DSMAX|)
in arclength of the exact fold, the tangent being unit in a norm in which every unknown
has weight 1: each coordinate is within that distance.
"""
import shutil
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from tolerances import location_tolerance
from washer.cont.runner import RunError
from washer.run import run

DATA = Path(__file__).parent / "data" / "optcusp"


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    d = tmp_path_factory.mktemp("optcusp")
    for f in DATA.iterdir():
        shutil.copy(f, d)
    return d


@pytest.fixture(scope="module")
def runs(folder):
    c = folder / "c.optcusp"
    r1 = run(c, verbose=False, sv="1")
    r2 = run(c, verbose=False, s="1", sv="2", IRS="LP1")
    assert r1.status == r2.status == "ok"
    return r1, r2


def tol(folder) -> float:
    return location_tolerance(folder / "c.optcusp")


def real_roots(expr, u):
    num = sp.numer(sp.together(expr))
    return [sp.N(r, 30) for r in sp.Poly(num, u).real_roots()]


def test_extremum_along_the_curve(runs, folder):
    r1, _ = runs
    u = sp.symbols("u")
    p2 = sp.Rational(1, 10)
    p1 = u ** 2 - p2 / u
    phi = u + p1 - p1 ** 2 - p2 ** 2
    # the curve's branch through the start u = 1 (u > 0); FOPT's critical points on it
    roots = [r for r in real_roots(sp.diff(phi, u), u) if r > 0]
    (lp,) = [r for r in r1.rows if r.ty == "LP"]
    best = min(roots, key=lambda r: abs(float(r) - lp.u[0]))
    t = tol(folder)
    assert lp.values[0] == pytest.approx(float(phi.subs(u, best)), abs=t)      # PAR(10)
    assert lp.u[0] == pytest.approx(float(best), abs=t)
    assert lp.par[0] == pytest.approx(float(p1.subs(u, best)), abs=t)
    assert lp.par[1] == 0.1
    # NFPR = 2: the record stores (u, PAR(1)), the free parameters PAR(10), PAR(1)
    assert len(lp.u) == 2 and lp.u[1] == lp.par[0] and lp.icp == [10, 1]
    assert r1.titles[0] == "FOPT"


def test_extremum_over_the_surface(runs, folder):
    r1, r2 = runs
    # Lagrange: 1 = l (3 u^2 - p1), 1 - 2 p1 = -l u, -2 p2 = -l, and f = 0, reduced to u
    u = sp.symbols("u")
    p2 = (u ** 3 - u / 2) / (1 + u ** 2)
    p1 = (1 + 2 * p2 * u) / 2
    (root,) = real_roots(2 * p2 * (3 * u ** 2 - p1) - 1, u)      # one critical point
    P1, P2 = p1.subs(u, root), p2.subs(u, root)
    (lp,) = [r for r in r2.rows if r.ty == "LP"]
    t = tol(folder)
    assert lp.values[0] == pytest.approx(float(root + P1 - P1 ** 2 - P2 ** 2), abs=t)
    assert lp.u[0] == pytest.approx(float(root), abs=t)
    assert lp.par[0] == pytest.approx(float(P1), abs=t)
    assert lp.par[1] == pytest.approx(float(P2), abs=t)
    # NFPR = 3: the record stores (u, v, v0, PAR(1), PAR(2)); lambda = -v / v0 = 2 p2
    x, v, v0, q1, q2 = lp.u
    assert (q1, q2) == (lp.par[0], lp.par[1])
    assert v * v + v0 * v0 == pytest.approx(1.0, abs=1e-8)
    assert -v / v0 == pytest.approx(2 * lp.par[1], abs=1e-7)
    # the restart's branch is the LP's label (AUTO's NEWLAB for IPS = 5 at an LP)
    (lp1,) = [r for r in r1.rows if r.ty == "LP"]
    assert lp.icp == [10, 1, 2] and lp.br == lp1.lab


def test_refusals(folder):
    c = folder / "c.optcusp"
    with pytest.raises(RunError, match="ICP\\(1\\) is PAR\\(10\\)"):
        run(c, verbose=False, files=False, ICP=[1, 2])
    with pytest.raises(RunError, match="NFPR = 2 free parameters"):
        run(c, verbose=False, files=False, ICP=[10])
    eq = run(c, verbose=False, files=False, IPS=1, ICP=[1], NMX=3)
    with pytest.raises(RunError, match="label of an IPS = 5 run"):
        run(c, verbose=False, files=False, restart=eq, IRS="EP1")


SYMBOLIC = '''
import sympy as sp
u = sp.symbols("x")
par = sp.symbols("p1 p2")
x, (p1, p2) = u, par
f = [x ** 3 - p1 * x - p2]
def stpnt(u, par):
    u[0], par[0], par[1] = 1.0, 0.9, 0.1
def fopt(u, par):
    return u[0] + par[0] - par[0] ** 2 - par[1] ** 2
'''


def test_symbolic_equations_take_fopt(runs, folder, tmp_path):
    """The same problem with f as sympy expressions (compiled) and fopt a plain function:
    the same extremum along the curve."""
    r1, _ = runs
    (tmp_path / "symcusp.py").write_text(SYMBOLIC)
    shutil.copy(folder / "c.optcusp", tmp_path / "c.optcusp")
    r = run(tmp_path / "c.optcusp", verbose=False, files=False, e="symcusp")
    (lp,) = [x for x in r.rows if x.ty == "LP"]
    (ref,) = [x for x in r1.rows if x.ty == "LP"]
    assert lp.values[0] == pytest.approx(ref.values[0], abs=tol(folder))
    assert lp.u == pytest.approx(ref.u, abs=tol(folder))


PITCHFORK = '''
def func(u, par):
    return [u[0] ** 3 - par[0] * u[0]]
def stpnt(u, par):
    u[0], par[0] = 1.0, 1.0
def fopt(u, par):
    return u[0] + par[0]
'''


def test_branch_point_next_to_the_crossing_branch(tmp_path):
    """u^3 - p1 u = 0 followed along p1 = u^2 (FOPT = u + p1 = PAR(10) the continuation
    parameter) through its pitchfork at u = p1 = 0, where the trivial branch u = 0
    crosses it. The step that passes the pitchfork ends on the parabola's other side
    (u < 0), with the trivial branch between its ends: the location's trial points must
    stay on the parabola. The BP is at u = p1 = PAR(10) = 0 and the extremum of
    FOPT = u + u^2 on the parabola at u = -1/2 (LP: PAR(10) = -1/4, p1 = 1/4); each
    located coordinate within the location tolerance (the tangent is unit in a norm in
    which every unknown has weight 1). Every row lies on the parabola to Newton's
    tolerance EPSU (the iterates' last correction bounds the residual's size there)."""
    (tmp_path / "pfk.py").write_text(PITCHFORK)
    (tmp_path / "c.pfk").write_text(
        "e = 'pfk', NDIM = 1, IPS = 5, IRS = 0, ILP = 1, ICP = [10, 1], ISP = 1, ISW = 1\n"
        "NMX = 100, NPR = 100, MXBF = 0, ITMX = 8, ITNW = 7, NWTN = 3, JAC = 0\n"
        "EPSL = 1e-08, EPSU = 1e-08, EPSS = 1e-06\n"
        "DS = -0.02, DSMIN = 0.0001, DSMAX = 0.05, IADS = 1, NPAR = 10\n")
    r = run(tmp_path / "c.pfk", verbose=False, sv="pfk")
    t = location_tolerance(tmp_path / "c.pfk")
    assert [s.ty for s in r.specials] == ["EP", "BP", "LP", "EP"]
    bp, lp = r.specials[1], r.specials[2]
    assert bp.u[0] == pytest.approx(0, abs=t) and bp.par[0] == pytest.approx(0, abs=t)
    assert bp.values[0] == pytest.approx(0, abs=2 * t)
    assert lp.u[0] == pytest.approx(-0.5, abs=t) and lp.par[0] == pytest.approx(0.25, abs=t)
    assert lp.values[0] == pytest.approx(-0.25, abs=t)
    for row in r.rows:
        assert row.par[0] == pytest.approx(row.u[0] ** 2, abs=1e-8)
    assert "Possible special point" not in (tmp_path / "d.pfk").read_text()


def test_fopt_gradient_against_the_closed_form():
    """Problem.fopt_gradient (AUTO's FOPI, shared by IPS = 5 and 15) against sympy's
    gradient of phi = p1 u1^2 u2 + sin(p2 u2) + p2^3 at three rows. Central differences
    with h = 1e-7 (1 + |.|): truncation ~h^2 |phi'''| ~ 1e-13, rounding ~eps |phi| / h
    ~ 1e-8, so 1e-7 absolute on values of order 1."""
    import sympy as sp
    from washer.cont.problem import Problem
    u1, u2, p1, p2 = sp.symbols("u1 u2 p1 p2")
    phi = p1 * u1 ** 2 * u2 + sp.sin(p2 * u2) + p2 ** 3
    grad = sp.lambdify((u1, u2, p1, p2), [sp.diff(phi, v) for v in (u1, u2, p1, p2)])
    prob = Problem(2, lambda u, par: np.zeros(2), npar=3,
                   fopt=lambda u, par: par[0] * u[0] ** 2 * u[1] + np.sin(par[1] * u[1])
                   + par[1] ** 3)
    par = np.array([0.7, -1.3, 5.0])
    U = np.array([[0.5, 2.0], [-1.5, 0.25], [3.0, -0.75]])
    gu, gp = prob.fopt_gradient(U, par, [1, 2])
    want = np.array([grad(u[0], u[1], par[0], par[1]) for u in U])
    assert gu.shape == (3, 2) and gp.shape == (3, 2)
    assert np.allclose(gu, want[:, :2], rtol=0, atol=1e-7)
    assert np.allclose(gp, want[:, 2:], rtol=0, atol=1e-7)
    none, gp2 = prob.fopt_gradient(U, par, [2], with_u=False)
    assert none is None and np.allclose(gp2[:, 0], want[:, 3], rtol=0, atol=1e-7)
