"""Exact special points of AUTO's `ab` demo, computed independently of the engine.

sympy gives exact derivatives of f; Hopf points solve f = 0, trace(f_u) = 0 (n = 2)
with mpmath at 30 digits; the Bautin (GH) point is where the first Lyapunov
coefficient (Kuznetsov, 3rd ed., eq 3.20, built from those exact derivatives)
vanishes along the Hopf curve. Used to decide between the engine and AUTO-07p
where the two disagree by more than AUTO's location tolerance.
"""
from functools import lru_cache

import numpy as np
import sympy as sp
from scipy.optimize import brentq

u1, u2, p1, p2 = sp.symbols("u1 u2 p1 p2")
P3 = 3
F = sp.Matrix([-u1 + p1 * (1 - u1) * sp.exp(u2),
               -u2 + p1 * p2 * (1 - u1) * sp.exp(u2) - P3 * u2])
X = sp.Matrix([u1, u2])
J = F.jacobian(X)


def hopf_point(fixed: dict, unknowns, guess):
    """Solve f = 0, trace(J) = 0 for `unknowns` with the other symbols `fixed`."""
    eqs = [e.subs(fixed) for e in list(F) + [J.trace()]]
    sol = sp.nsolve(eqs, unknowns, guess, prec=30)
    return [float(v) for v in sol]


def hb_p1(p2_value: float, guess) -> float:
    """PAR(1) of the Hopf point at p2 = p2_value; guess = (u1, u2, p1) to start Newton."""
    return hopf_point({p2: p2_value}, [u1, u2, p1], list(guess))[2]


def _l1(p1_value: float) -> float:
    x1, x2, q2 = hopf_point({p1: p1_value}, [u1, u2, p2], [0.578, 1.593, 11.0])
    sub = {u1: x1, u2: x2, p1: p1_value, p2: q2}
    A = np.array(J.subs(sub).evalf(30), dtype=float)
    om = np.sqrt(np.linalg.det(A))
    lam, V = np.linalg.eig(A)
    q = V[:, np.argmin(abs(lam - 1j * om))]
    lt, W = np.linalg.eig(A.T)
    pv = W[:, np.argmin(abs(lt + 1j * om))]
    pv = pv / np.conj(np.conj(pv) @ q)
    d2 = [[[float(sp.diff(F[i], X[j], X[k]).subs(sub)) for k in range(2)] for j in range(2)]
          for i in range(2)]
    d3 = [[[[float(sp.diff(F[i], X[j], X[k], X[m]).subs(sub)) for m in range(2)]
            for k in range(2)] for j in range(2)] for i in range(2)]
    B = lambda a, b: np.einsum("ijk,j,k->i", np.array(d2), a, b)
    C = lambda a, b, c: np.einsum("ijkm,j,k,m->i", np.array(d3), a, b, c)
    qb = np.conj(q)
    h11 = np.linalg.solve(A, B(q, qb))
    h20 = np.linalg.solve(2j * om * np.eye(2) - A, B(q, q))
    return float((np.conj(pv) @ (C(q, q, qb) - 2 * B(q, h11) + B(qb, h20))).real / (2 * om))


@lru_cache(maxsize=None)
def gh_p1() -> float:
    """PAR(1) of the Bautin point on ab's Hopf curve (p3 = 3)."""
    return brentq(_l1, 0.27, 0.29, xtol=1e-13)
