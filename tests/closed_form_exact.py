"""Exact special points of the closed-form test problems in tests/data and of AUTO demos.

Everything here is derived at test time with sympy from the equations (written out
again below, independently of the problem files the engine runs), never from the
engine: branch conditions, singularity conditions and Hopf conditions are solved
symbolically, or with sympy.nsolve at 30 digits where no closed form exists. The
first Lyapunov coefficient follows Kuznetsov (3rd ed., eq. 3.20) with exact
derivatives, as in tests/ab_exact.py.
"""
from functools import lru_cache

import numpy as np
import sympy as sp
from scipy.optimize import brentq

# ---------------------------------------------------------------------------
# Generic tools


def first_lyapunov(F: sp.Matrix, X: list, subs: dict) -> float:
    """l1 of x' = F(x) at a Hopf point `subs` (Kuznetsov 3rd ed. eq. 3.20)."""
    n = len(X)
    A = np.array(F.jacobian(X).subs(subs).evalf(30), dtype=float)
    lam, V = np.linalg.eig(A)
    k = int(np.argmax(lam.imag))
    om = lam[k].imag
    q = V[:, k] / np.linalg.norm(V[:, k])
    lt, W = np.linalg.eig(A.T)
    pv = W[:, int(np.argmin(abs(lt + 1j * om)))]
    pv = pv / np.conj(np.conj(pv) @ q)
    d2 = np.array([[[float(sp.diff(F[i], X[j], X[k2]).subs(subs)) for k2 in range(n)]
                    for j in range(n)] for i in range(n)])
    d3 = np.array([[[[float(sp.diff(F[i], X[j], X[k2], X[m]).subs(subs)) for m in range(n)]
                     for k2 in range(n)] for j in range(n)] for i in range(n)])
    B = lambda a, b: np.einsum("ijk,j,k->i", d2, a, b)
    C = lambda a, b, c: np.einsum("ijkm,j,k,m->i", d3, a, b, c)
    qb = np.conj(q)
    h11 = np.linalg.solve(A, B(q, qb))
    h20 = np.linalg.solve(2j * om * np.eye(n) - A, B(q, q))
    return float((np.conj(pv) @ (C(q, q, qb) - 2 * B(q, h11) + B(qb, h20))).real / (2 * om))


def _positive(sols, var):
    """The solutions (dicts) with var real and positive."""
    return [s for s in sols if s[var].is_real and s[var] > 0]


# ---------------------------------------------------------------------------
# tests/data/pfchain: the pitchfork chain

MU, A_, B_, C_, W_ = sp.symbols("mu a b c w", real=True)
X5 = sp.symbols("x1:6", real=True)


def pfchain_rhs() -> sp.Matrix:
    x1, x2, x3, x4, x5 = X5
    r2 = x4**2 + x5**2
    g = x2**2 - B_
    return sp.Matrix([x1 * (MU + x1**2 - x1**4), x2 * (x1**2 - A_ - x2**2),
                      x3 * (x2**2 - C_ - x3**2), g * x4 - W_ * x5 - x4 * r2,
                      W_ * x4 + g * x5 - x5 * r2])


PFCHAIN_PAR = {A_: sp.Rational(6, 5), B_: sp.Rational(1, 10), C_: sp.Rational(3, 10), W_: 2}


@lru_cache(maxsize=None)
def pfchain_points() -> dict:
    """Exact special points of the chain, by level: name -> dict(mu, x=|x_i| list, period)."""
    F = pfchain_rhs().subs(PFCHAIN_PAR)
    J = F.jacobian(X5)
    x1, x2, x3, x4, x5 = X5
    zero = {x: 0 for x in X5}
    out = {}
    # Trivial branch: det J(0, mu) = 0.
    mu_a = sp.solve(J.subs(zero).det(), MU)
    out["A"] = dict(mu=float(mu_a[0]), x=[0.0] * 5)
    # Level 1 (x1 != 0, x2 = x3 = x4 = x5 = 0): branch g1 = f1 / x1 = 0.
    g1 = sp.cancel(F[0] / x1)
    lp = _positive(sp.solve([g1, sp.diff(g1, x1)], [MU, x1], dict=True), x1)  # d mu/d x1 = 0
    out["LP"] = dict(mu=float(lp[0][MU]), x=[float(lp[0][x1]), 0, 0, 0, 0])
    lvl1 = {x2: 0, x3: 0, x4: 0, x5: 0}
    bp_b = _positive(sp.solve([g1, J[1, 1].subs(lvl1)], [MU, x1], dict=True), x1)  # df2/dx2 = 0
    out["B"] = dict(mu=float(bp_b[0][MU]), x=[float(bp_b[0][x1]), 0, 0, 0, 0])
    # Level 2 (x1, x2 != 0): branches g1 = 0, g2 = f2 / x2 = 0.
    g2 = sp.cancel(F[1] / x2)
    lvl2 = {x3: 0, x4: 0, x5: 0}
    # Hopf: the (x4, x5) block has eigenvalues re +- i w; re = 0.
    block = J[3:5, 3:5].subs(lvl2)
    re = sp.simplify(block.trace() / 2)
    hb = sp.solve([g1, g2, re], [MU, x1, x2], dict=True)
    hb = [s for s in hb if s[x1] > 0 and s[x2] > 0]
    om = sp.sqrt(block.det().subs(hb[0]))
    out["HB"] = dict(mu=float(hb[0][MU]), x=[float(hb[0][x1]), float(hb[0][x2]), 0, 0, 0],
                     period=float(2 * sp.pi / om))
    bp_c = sp.solve([g1, g2, J[2, 2].subs(lvl2)], [MU, x1, x2], dict=True)
    bp_c = [s for s in bp_c if s[x1] > 0 and s[x2] > 0]
    out["C"] = dict(mu=float(bp_c[0][MU]), x=[float(bp_c[0][x1]), float(bp_c[0][x2]), 0, 0, 0])
    return out


# ---------------------------------------------------------------------------
# tests/data/hopfcross: two Hopf loci crossing, GH on the second

P1, P2, OM = sp.symbols("p1 p2 omega", real=True)
X3 = sp.symbols("x0 y1 y2", real=True)


def hopfcross_rhs(omega=1) -> sp.Matrix:
    x0, y1, y2 = X3
    h = P1 - P2 - x0 - P2**2 / 2
    lc = x0 - sp.Rational(1, 2)
    r2 = y1**2 + y2**2
    return sp.Matrix([x0 * (P2 - x0), h * y1 - omega * y2 + lc * y1 * r2,
                      omega * y1 + h * y2 + lc * y2 * r2])


@lru_cache(maxsize=None)
def hopfcross_loci():
    """(x0(p2), p1(p2)) of the two Hopf loci, from the equilibria and trace = 0."""
    F = hopfcross_rhs()
    x0, y1, y2 = X3
    eqs = sp.solve(F[0], x0)                      # equilibria with y = 0: x0 = 0, x0 = p2
    J = F.jacobian(X3)
    loci = []
    for e in sorted(eqs, key=lambda v: str(v)):
        tr = J[1:, 1:].subs({x0: e, y1: 0, y2: 0}).trace()  # the (y1, y2) pair's 2 Re
        loci.append((sp.Lambda(P2, e), sp.Lambda(P2, sp.solve(tr, P1)[0])))
    return loci                                   # [E1: x0 = 0, E2: x0 = p2]


@lru_cache(maxsize=None)
def hopfcross_points() -> dict:
    """Crossing (BP on the Hopf curve), the folds of both loci in p1 (LP on the Hopf
    curve) and the Bautin point on E2's locus."""
    (x0_1, p1_1), (x0_2, p1_2) = hopfcross_loci()
    out = {}
    cross = sp.solve([p1_1(P2) - p1_2(P2), x0_1(P2) - x0_2(P2)], P2, dict=True)
    q = cross[0][P2]
    out["BP"] = dict(p1=float(p1_1(q)), p2=float(q), x0=float(x0_1(q)))
    for name, (x0f, p1f) in (("LP_E1", (x0_1, p1_1)), ("LP_E2", (x0_2, p1_2))):
        q = sp.solve(sp.diff(p1f(P2), P2), P2)[0]
        out[name] = dict(p1=float(p1f(q)), p2=float(q), x0=float(x0f(q)))
    F = hopfcross_rhs()
    x0, y1, y2 = X3

    def l1(p2v):
        return first_lyapunov(F, list(X3), {x0: float(x0_2(p2v)), y1: 0, y2: 0,
                                            P1: float(p1_2(p2v)), P2: p2v})
    q = brentq(l1, 0.1, 1.0, xtol=1e-14)
    out["GH"] = dict(p1=float(p1_2(q)), p2=q, x0=float(x0_2(q)))
    return out


def hopfcross_on_locus(p2v: float, locus: int) -> tuple:
    """(x0, p1) on locus 0 (E1) or 1 (E2) at p2 = p2v."""
    x0f, p1f = hopfcross_loci()[locus]
    return float(x0f(p2v)), float(p1f(p2v))


# ---------------------------------------------------------------------------
# tests/data/sharpfold

XS = sp.Symbol("x", real=True)


def sharpfold_G(s=4, eps=sp.Rational(1, 50)):
    r = lambda y: sp.sqrt(eps**2 + y**2)
    return s * (XS - r(XS) + r(XS - 1))


@lru_cache(maxsize=None)
def sharpfold_points() -> dict:
    """x and mu of the two folds (G'(x) = 0) and of the UZ stop G(x) = 4."""
    G = sharpfold_G()
    dG = sp.diff(G, XS)
    out = {}
    for name, guess in (("LP1", 0.0), ("LP2", 1.0)):
        x = sp.nsolve(dG, XS, guess, prec=30)
        out[name] = dict(x=float(x), mu=float(G.subs(XS, x)))
    x = sp.nsolve(G - 4, XS, 2.0, prec=30)
    out["UZ"] = dict(x=float(x), mu=4.0)
    return out


def sharpfold_G_numeric(x):
    return float(sharpfold_G().subs(XS, x))


# ---------------------------------------------------------------------------
# tests/data/pvlsstop

def pvlsstop_mu(x1_value) -> float:
    """mu on the branch (f1 = mu - x1 - x1^3 = 0) where x1 = x1_value."""
    x1, mu = sp.symbols("x1 mu")
    return float(sp.solve(mu - x1 - x1**3, mu)[0].subs(x1, sp.nsimplify(x1_value)))


# ---------------------------------------------------------------------------
# AUTO demos

def lrz_points() -> dict:
    """Lorenz (beta = 8/3, sigma = 10): the pitchfork of the origin and the Hopf point of
    the nontrivial equilibria (Routh-Hurwitz a2 a1 = a0 of the characteristic polynomial)."""
    x, y, z, rho = sp.symbols("x y z rho", real=True)
    beta, sigma = sp.Rational(8, 3), 10
    F = sp.Matrix([sigma * (y - x), rho * x - y - x * z, x * y - beta * z])
    J = F.jacobian([x, y, z])
    bp = sp.solve(J.subs({x: 0, y: 0, z: 0}).det(), rho)
    xe = sp.sqrt(beta * (rho - 1))
    Je = J.subs({x: xe, y: xe, z: rho - 1})
    lam = sp.Symbol("lam")
    c = sp.Poly(Je.charpoly(lam).as_expr(), lam).all_coeffs()      # lam^3 + a2 lam^2 + ...
    hb = [r for r in sp.solve(sp.simplify(c[1] * c[2] - c[3]), rho) if r > 1]
    return dict(BP=float(bp[0]), HB=float(hb[0]))


def chu_points() -> dict:
    """Chua's circuit (chu demo): the nontrivial zero x* of h (with RK = 10), where the
    line of equilibria at alpha = 0 meets the branch x = x*, and the Hopf value of alpha
    on that branch (equilibrium (x*, 0, -x*) for every alpha)."""
    x, al = sp.symbols("x alpha", real=True)
    beta, rk, a0, a1 = sp.Rational(143, 10), 10, sp.Rational(-1, 7), sp.Rational(2, 7)
    ab = lambda v: 2 * v * sp.atan(rk * v) / sp.pi
    h = a1 * x + sp.Rational(1, 2) * (a0 - a1) * (ab(x + 1) - ab(x - 1))
    xs = sp.nsolve(h, x, 1.5, prec=30)
    hp = sp.diff(h, x).subs(x, xs)
    J = sp.Matrix([[-al * hp, al, 0], [1, -1, 1], [0, -beta, 0]])
    lam = sp.Symbol("lam")
    c = sp.Poly(J.charpoly(lam).as_expr(), lam).all_coeffs()
    hb = [r for r in sp.solve(c[1] * c[2] - c[3], al) if r.is_real and r > 0]
    return dict(x_star=float(xs), HB=float(min(hb)))


def plp_hopf_p4(p1_value: float, guess) -> float:
    """PAR(4) of plp's Hopf point at PAR(1) = p1_value (f = 0, trace = 0), from (s, a, p4)."""
    s, a, s0, a0, al, rh, rk = sp.symbols("s a s0 a0 al rh rk")
    d = 1 + s + rk * s**2
    r = s * a / d
    F = sp.Matrix([(s0 - s) - rh * r, al * (a0 - a) - rh * r])
    par = {s0: p1_value, a0: 500, al: sp.Rational(1, 5), rk: sp.Rational(1, 10)}
    eqs = [e.subs(par) for e in list(F) + [F.jacobian([s, a]).trace()]]
    return float(sp.nsolve(eqs, [s, a, rh], list(guess), prec=30)[2])


def ab_lp_p1(p2_value: float, p3_value: float = 3.0) -> list:
    """PAR(1) of the folds of ab's equilibria at (p2, p3), increasing u1: on the branch
    u2 = p2 u1 / (1 + p3) and p1 = u1 e^-u2 / (1 - u1) (f = 0); folds where
    d p1 / d u1 = 0."""
    # Solved for k = p2 / (1 + p3) as a symbol, then evaluated: solve() with p2 a rational
    # of many digits (a start value such as 17.0000009 at a step's end) does not finish.
    u1, k = sp.symbols("u1 k", positive=True)
    p1 = u1 * sp.exp(-k * u1) / (1 - u1)
    roots = sp.solve(sp.diff(p1, u1), u1)          # (1 -+ sqrt(1 - 4 / k)) / 2
    kv = sp.Float(p2_value, 30) / (1 + sp.Float(p3_value, 30))
    out = []
    for r in roots:
        v = complex(r.subs(k, kv).evalf(30))
        if v.imag == 0 and 0 < v.real < 1:
            out.append((v.real, float(p1.subs(u1, r).subs(k, kv).evalf(30))))
    return [p for _, p in sorted(out)]
