"""First Lyapunov coefficient at a Hopf point (AUTO's FNGHEQ; Kuznetsov,
Elements of Applied Bifurcation Theory, 3rd ed., eq 3.20 and section 10.2).

    l1 = Re[<p, C(q,q,qb)> - 2 <p, B(q, A^-1 B(q,qb))> + <p, B(qb, (2 i w - A)^-1 B(q,q))>] / (2 w)

with A q = i w q, A^T p = -i w p, <p, q> = 1 (<a, b> = conj(a) . b); negative
means supercritical. B and C, the second and third derivatives of f, are
central differences of f along real directions (q = a + i b splits every
complex form into real ones by multilinearity), Richardson-extrapolated from
steps h and 2h to O(h^4): near a GH point l1 is a small difference of such
terms. All stencil points of one stage go to the problem in one batched call
(two calls in all: the second stage needs h11 and h20 from the first).
"""
from __future__ import annotations

import itertools

import numpy as np

#: Steps for second and third differences, about eps^(1/4) and eps^(1/5) of a
#: unit-scaled state: they balance truncation O(h^4) after extrapolation
#: against rounding eps |f| / h^2 (resp. h^3).
FD2_STEP = 1e-3
FD3_STEP = 4e-3


def _stencil_B(x, a, b, h):
    """Points and weights of B(a, b) ~ [f(x+h(a+b)) - f(x+h(a-b)) - f(x-h(a-b)) + f(x-h(a+b))] / 4h^2."""
    pts = [x + h * (a + b), x + h * (a - b), x - h * (a - b), x - h * (a + b)]
    w = np.array([1.0, -1.0, -1.0, 1.0]) / (4 * h * h)
    return pts, w


def _stencil_C(x, a, b, c, h):
    pts, w = [], []
    for sa, sb, sc in itertools.product((1, -1), repeat=3):
        pts.append(x + h * (sa * a + sb * b + sc * c))
        w.append(sa * sb * sc / (8 * h ** 3))
    return pts, np.array(w)


def _forms(problem, x, p, requests):
    """Evaluate real multilinear forms in one batched call.

    requests: list of ('B', a, b) or ('C', a, b, c). Returns a list of (n,) arrays,
    each Richardson-extrapolated (4 F(h) - F(2h)) / 3."""
    pts, plan = [], []
    for req in requests:
        kind, args = req[0], req[1:]
        h0 = FD2_STEP if kind == "B" else FD3_STEP
        entry = []
        for h in (h0, 2 * h0):
            P, w = (_stencil_B if kind == "B" else _stencil_C)(x, *args, h)
            entry.append((len(pts), w))
            pts.extend(P)
        plan.append(entry)
    F = problem.func_many(np.array(pts), p)
    out = []
    for (i1, w1), (i2, w2) in plan:
        v1 = w1 @ F[i1:i1 + len(w1)]
        v2 = w2 @ F[i2:i2 + len(w2)]
        out.append((4 * v1 - v2) / 3)
    return out


def first_lyapunov(problem, x, p, omega: float, A: np.ndarray | None = None) -> float:
    """l1 at the Hopf point x (ndim,), parameters p (npar,), frequency omega
    (rad per unit time); A = f_x(x, p) if already known."""
    if A is None:
        A = problem.dfdu(x, p)
    n = len(x)
    lam, V = np.linalg.eig(A)
    q = V[:, np.argmin(np.abs(lam - 1j * omega))]
    lamT, W = np.linalg.eig(A.T)
    pv = W[:, np.argmin(np.abs(lamT + 1j * omega))]
    q = q / np.linalg.norm(q)
    pv = pv / np.conj(np.conj(pv) @ q)
    a, b = q.real.copy(), q.imag.copy()
    Baa, Bbb, Bab, Caaa, Caab, Cabb, Cbbb = _forms(problem, x, p, [
        ("B", a, a), ("B", b, b), ("B", a, b),
        ("C", a, a, a), ("C", a, a, b), ("C", a, b, b), ("C", b, b, b)])
    B_qqb = Baa + Bbb                               # B(q, conj q)
    B_qq = Baa - Bbb + 2j * Bab                     # B(q, q)
    C_qqqb = Caaa + Cabb + 1j * (Caab + Cbbb)       # C(q, q, conj q)
    h11 = np.linalg.solve(A, B_qqb).real            # real: B(q, conj q) is real
    h20 = np.linalg.solve(2j * omega * np.eye(n) - A, B_qq)
    c, d = h20.real.copy(), h20.imag.copy()
    Bah, Bbh, Bac, Bbd, Bad, Bbc = _forms(problem, x, p, [
        ("B", a, h11), ("B", b, h11), ("B", a, c), ("B", b, d), ("B", a, d), ("B", b, c)])
    B_q_h11 = Bah + 1j * Bbh                        # B(q, h11)
    B_qb_h20 = Bac + Bbd + 1j * (Bad - Bbc)         # B(conj q, h20)
    val = np.conj(pv) @ (C_qqqb - 2 * B_q_h11 + B_qb_h20)
    return float(val.real / (2 * omega))
