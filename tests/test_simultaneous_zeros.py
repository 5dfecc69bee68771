"""Two tests vanishing at one point, typed as AUTO's LCSPAE types it: first come, first
served in its test order (the fold, ITEST 1, before the BT, ITEST 4), a bifurcation
overriding a user value (UZ), whose UZSTOP then does not stop the run. Both on closed
forms (sympy), each run as Debian AUTO-07p 0.9.2 ran the same equations and constants.
"""
import tempfile
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from washer.cont.problem import Problem
from washer.run import run

EPSS = 1e-5


def _pitchfork(u, par):
    return np.array([par[0] * u[0] - u[0] ** 3])


def _pitchfork_start(u, par):
    par[0], u[0] = -1.0, 0.0


def _trivial_branch(**over):
    with tempfile.TemporaryDirectory() as d:
        c = Path(d) / "c.pf"
        c.write_text("NDIM = 1, IPS = 1, IRS = 0, ILP = 1, ICP = [1], ISP = 1, MXBF = 0, "
                     "NMX = 30, NPR = 100, DS = 0.1, DSMIN = 0.001, DSMAX = 0.1, EPSL = 1e-7, "
                     f"EPSU = 1e-7, EPSS = {EPSS}, NPAR = 1\n")
        return run(c, verbose=False, files=False, **over,
                   problem=Problem(1, _pitchfork, _pitchfork_start, name="pf"))


@pytest.mark.parametrize("over", [{"UZSTOP": {1: 0.0}}, {"UZR": {1: [0.0, 0.5]}}])
def test_a_branch_point_overrides_a_user_value_at_it(over):
    """u' = p u - u^3 along u = 0 from p = -1: the branch point is p = 0 (f_u = p). A
    UZSTOP or UZR value p = 0 there is that BP: AUTO-07p's b-files of these equations
    label BP at p = 1.0e-7 (PT 10) and go on to the EP at NMX = 30 (p = 2), a UZ at
    p = 0.5 after it where asked."""
    r = _trivial_branch(**over)
    got = [(s.ty, round(float(s.par[0]), 6)) for s in r.specials]
    tail = [("UZ", 0.5)] if "UZR" in over else []
    assert got == [("EP", -1.0), ("BP", 0.0)] + tail + [("EP", 2.0)]
    bp = next(s for s in r.specials if s.ty == "BP")
    assert abs(bp.par[0]) < 2 * EPSS * (1 + np.sqrt(0.1 * 0.1))


def yamada_bt():
    """(A, gamma, I) of the Bogdanov-Takens point of the laser model G' = gamma (A - G -
    G I), Q' = gamma (B - Q - a Q I), I' = (G - Q - 1) I at B = 5.8, a = 1.8 (sympy):
    the fold of the lasing equilibria, A = (1 + I)(1 + B / (1 + a I)) extremal in I, is
    a line of constant A (gamma does not enter it), and the BT on it is where the
    characteristic polynomial's linear coefficient vanishes too."""
    A, g, G, Q, I, lam = sp.symbols("A g G Q I lam")
    B, a = sp.Rational(29, 5), sp.Rational(9, 5)
    f = sp.Matrix([g * (A - G - G * I), g * (B - Q - a * Q * I), (G - Q - 1) * I])
    a_of_i = (1 + I) * (1 + B / (1 + a * I))
    i_bt = sp.nsolve(sp.diff(a_of_i, I), I, 0.64, prec=30)
    a_bt = a_of_i.subs(I, i_bt)
    at = {G: a_bt / (1 + i_bt), Q: B / (1 + a * i_bt), I: i_bt, A: a_bt}
    poly = sp.expand((lam * sp.eye(3) - f.jacobian([G, Q, I])).det())
    g_bt = sp.nsolve(poly.coeff(lam, 1).subs(at), g, 0.2, prec=30)
    assert abs(poly.coeff(lam, 0).subs(at).subs(g, g_bt)) < 1e-25      # det = 0 too
    return float(a_bt), float(g_bt), float(i_bt)


YAMADA = '''import numpy as np

def func(u, par):
    g, A, B, a = par[0], par[1], par[2], par[3]
    G, Q, I = u
    return np.array([g * (A - G - G * I), g * (B - Q - a * Q * I), (G - Q - 1) * I])

def stpnt(u, par):
    par[0], par[1], par[2], par[3] = 0.1, 6.6, 5.8, 1.8
    u[0], u[1], u[2] = 6.6, 5.8, 0.0
'''


def _lasing_branch(tmp_path):
    """The laser model's constants file in tmp_path (Python user file yam.py), its trivial
    branch saved as 'eq' and the lasing branch switched from its BP saved as 'lasing'
    (a Hopf point on it, HB1, at gamma = 0.1); returns the constants file."""
    (tmp_path / "yam.py").write_text(YAMADA)
    c = tmp_path / "c.yam"
    c.write_text("NDIM = 3, IPS = 1, ILP = 1, ISP = 2, ICP = ['A', 'gamma'], NPAR = 4, "
                 "parnames = {1: 'gamma', 2: 'A', 3: 'B', 4: 'a'}, NMX = 100, NPR = 10, "
                 "MXBF = 0, DS = 0.01, DSMIN = 0.05, DSMAX = 0.1, EPSL = 1e-6, EPSU = 1e-6, "
                 "EPSS = 1e-4, e = 'yam'\n")
    run(c, sv="eq", verbose=False)
    bp = run(c, s="eq", IRS="BP1", ISW=-1, sv="lasing", verbose=False)
    assert any(s.ty == "HB" for s in bp.specials)
    return c


def test_a_bt_that_is_a_fold_of_the_hopf_curve_is_typed_lp_and_passed(tmp_path):
    """The Hopf curve of the laser model in (A, gamma), from its Hopf point at gamma =
    0.1, backwards: it touches the fold line A = A_BT at the BT, where A is extremal
    along it, so the fold test and the BT test vanish at one point. AUTO-07p (the same
    equations in Fortran, these constants) types it LP (32) at PT 398, A = 6.0600732476,
    and goes on; so does this run, its LP within the location tolerance of the closed
    form."""
    c = _lasing_branch(tmp_path)
    hopf = run(c, s="lasing", IRS="HB1", ISW=2, DS=-5e-3, DSMIN=5e-3, DSMAX=5e-3, NMX=600,
               NPR=100, UZSTOP={}, sv="hopf", verbose=False)
    a_bt, g_bt, _ = yamada_bt()
    (lp,) = [s for s in hopf.specials if s.ty == "LP"]
    assert not [s for s in hopf.specials if s.ty == "BT"]
    tol = 1e-4 * (1 + np.sqrt(5e-3 * 5e-3))
    assert abs(lp.par[1] - a_bt) < 2 * tol and abs(lp.par[0] - g_bt) < 2 * tol
    # the curve goes on past it (A grows again), to NMX
    rows = [r for r in hopf.rows if abs(r.pt) > abs(lp.pt)]
    assert rows and hopf.specials[-1].ty == "EP" and max(r.par[1] for r in rows) > a_bt + 0.03


def yamada_slow_limit():
    """(A, I, dkappa/dgamma) where the laser model's Hopf curve meets gamma = 0 (sympy).
    The Hopf condition c2 c1 = c0 on the characteristic polynomial lam^3 + c2 lam^2 +
    c1 lam + c0 of the lasing equilibria (G = Q + 1, Q = B / (1 + a I)) is gamma^2 h(I) +
    O(gamma^3): the curve crosses gamma = 0 at a root of h, where kappa = omega^2 = c1 =
    gamma c1'(I) + O(gamma^2) changes sign (a simple zero). There J = f_u is nilpotent
    (J^2 = 0): every lasing state at gamma = 0 solves the Hopf system with kappa = 0."""
    A, g, G, Q, I, lam = sp.symbols("A g G Q I lam")
    B, a = sp.Rational(29, 5), sp.Rational(9, 5)
    f = sp.Matrix([g * (A - G - G * I), g * (B - Q - a * Q * I), (G - Q - 1) * I])
    J = f.jacobian([G, Q, I])
    lasing = {G: 1 + B / (1 + a * I), Q: B / (1 + a * I)}
    assert sp.simplify((J.subs(g, 0) ** 2).subs(lasing)) == sp.zeros(3, 3)
    poly = sp.expand((lam * sp.eye(3) - J).det())
    c2, c1, c0 = (poly.coeff(lam, k) for k in (2, 1, 0))
    h = sp.Poly(sp.expand(c2 * c1 - c0).subs(lasing), g)
    assert sp.simplify(h.coeff_monomial(1)) == 0 and sp.simplify(h.coeff_monomial(g)) == 0
    i_star = max(sp.Poly(sp.numer(sp.together(h.coeff_monomial(g ** 2))), I).nroots(n=30))
    a_star = ((1 + I) * (1 + B / (1 + a * I))).subs(I, i_star)
    slope = sp.Poly(c1.subs(lasing), g).coeff_monomial(g).subs(I, i_star)
    return float(a_star), float(i_star), float(slope)


def test_a_hopf_curve_whose_frequency_vanishes_with_gamma_stops_at_the_bt(tmp_path):
    """The laser model's Hopf curve forwards from its Hopf point at gamma = 0.1 reaches
    gamma = 0 at A = 10.44 (closed form above), where kappa changes sign: a BT, and the
    run stops there (AUTO stops at a BT on a Hopf curve; the user's UZSTOP gamma = 0 is
    the same point). The extended system's determinant (the BP test) vanishes there too,
    but to fourth order, one sign on both sides: ours -2.1e-13, -5.1e-15 at gamma =
    2.2e-5, 8.8e-6; AUTO-07p's d-file of the same run -3.0e-14, -5.6e-14 at gamma =
    1.2e-5, -1.3e-5. AUTO-07p types BP there (its test changing sign on rounding within
    a location step) and, a BP not being a BT, goes on along the neutral saddles to NMX."""
    c = _lasing_branch(tmp_path)
    hopf = run(c, s="lasing", IRS="HB1", ISW=2, DS=5e-3, DSMIN=5e-3, DSMAX=5e-3, NMX=2000,
               NPR=100, UZSTOP={}, verbose=False)
    a_star, i_star, slope = yamada_slow_limit()
    assert slope > 0                 # kappa > 0 (a Hopf pair) for gamma > 0 only
    end = hopf.specials[-1]
    assert end.ty == "BT" and abs(end.pt) < 2000
    assert not [s for s in hopf.specials if s.ty == "BP"]
    tol = 1e-4 * (1 + np.sqrt(5e-3 * 5e-3))          # AUTO's location tolerance
    assert abs(end.par[0]) < 2 * tol and abs(end.par[1] - a_star) < 2 * tol
    assert abs(end.u[2] - i_star) < 2 * tol
