"""A fold locus that turns at a cusp: both parameters reverse there, the curve of the
fold system (f, f_u phi, <phi, phi> - 1) is regular through it, and the run passes it
with one CP and no BP.

On f = a + b u - u^3 (sympy) the folds are f = f_u = 0: (a, b) = (-2 u^3, 3 u^2), a
curve smooth in u whose projection on (a, b) has a cusp at u = 0, where f_uu = 0 (the
CP test, <w, B(phi, phi)>, changes sign) and nothing else: f_u's null space stays one
dimensional and the fold system's Jacobian keeps full rank, so its determinant (the BP
test) keeps its sign. Debian AUTO-07p 0.9.2 on the same equations (Fortran) and
constants: CP at PT 53, (a, b) = (1.8e-20, 9.3e-14), EP at PT 60, (a, b) =
(-8.14497e-2, 3.55109e-1).
"""
import numpy as np
import pytest
import sympy as sp

from washer.run import run

CUSP = '''import numpy as np

def func(u, par):
    return np.array([par[0] + par[1] * u[0] - u[0] ** 3])

def stpnt(u, par):
    par[0], par[1] = -2.0, 3.0
    u[0] = -2.0
'''

EPSU = EPSS = 1e-7


def fold_curve():
    """(a(u), b(u), f_uu(u)) along the folds of a + b u - u^3 (sympy), and the u where the
    fold system's Jacobian in (u, phi, a, b) loses rank (none)."""
    u, a, b, phi = sp.symbols("u a b phi")
    f = a + b * u - u ** 3
    (sol,) = sp.solve([f, sp.diff(f, u)], [a, b], dict=True)
    G = sp.Matrix([f, sp.diff(f, u) * phi, phi ** 2 - 1])
    J = G.jacobian([u, phi, a, b]).subs(sol).subs(phi, 1)
    # rank < 3 where every 3x3 minor vanishes
    minors = [J[:, [i for i in range(4) if i != k]].det() for k in range(4)]
    singular = sp.solve(minors, u)
    return sol[a], sol[b], sp.diff(f, u, 2), singular, u


def test_the_fold_locus_passes_its_cusp_with_one_cp_and_no_bp(tmp_path):
    a_of, b_of, fuu, singular, u = fold_curve()
    assert sp.simplify(a_of + 2 * u ** 3) == 0 and sp.simplify(b_of - 3 * u ** 2) == 0
    assert singular == []                         # a regular curve: no branch point on it
    assert sp.solve(fuu, u) == [0]                # the cusp, at (a, b) = (0, 0)
    (tmp_path / "cusp.py").write_text(CUSP)
    c = tmp_path / "c.cusp"
    c.write_text("NDIM = 1, IPS = 1, ILP = 1, ISP = 1, ICP = [1], NPAR = 2, NMX = 50, "
                 "NPR = 1000, MXBF = 0, DS = 0.05, DSMIN = 1e-4, DSMAX = 0.1, "
                 f"EPSL = {EPSU}, EPSU = {EPSU}, EPSS = {EPSS}, e = 'cusp'\n")
    eq = run(c, sv="eq", verbose=False)
    assert [s.ty for s in eq.specials] == ["EP", "LP", "EP"]          # the LP at u = -1
    fold = run(c, s="eq", IRS="LP1", ICP=[1, 2], ISW=2, DS=-0.05, NMX=60, sv="fold",
               verbose=False)
    assert [(s.ty, abs(s.pt)) for s in fold.specials] == [("CP", 53), ("EP", 60)]
    cp, ep = fold.specials
    # the CP is located to EPSS in arclength; the curve's speed there is |du/ds| <= 1
    assert abs(cp.u[0]) < 10 * EPSS and abs(cp.par[0]) < 10 * EPSS and abs(cp.par[1]) < 10 * EPSS
    # every point is on the folds to the corrector's tolerance (its last Newton step is
    # below EPSU (1 + |x|) and the convergence quadratic: the error is below that step)
    us = np.array([r.u[0] for r in fold.rows])
    a = np.array([r.par[0] for r in fold.rows])
    b = np.array([r.par[1] for r in fold.rows])
    assert np.allclose(a, -2 * us ** 3, atol=1e-6) and np.allclose(b, 3 * us ** 2, atol=1e-6)
    # the run passes the cusp: u changes sign and b, having fallen to 0, grows again
    assert us[0] < 0 < us[-1] and b[-1] > 100 * abs(cp.par[1])
    assert ep.par[0] == pytest.approx(-8.14497e-2, abs=2e-7)
    assert ep.par[1] == pytest.approx(3.55109e-1, abs=2e-6)
