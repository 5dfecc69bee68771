"""First Lyapunov coefficient at a Hopf point (AUTO's FNGHEQ; Kuznetsov,
Elements of Applied Bifurcation Theory, 3rd ed., eq 3.20 and section 10.2).

    l1 = Re[<p, C(q,q,qb)> - 2 <p, B(q, A^-1 B(q,qb))> + <p, B(qb, (2 i w - A)^-1 B(q,q))>] / (2 w)

with A q = i w q, A^T p = -i w p, <p, q> = 1 (<a, b> = conj(a) . b); negative
means supercritical. B and C, the second and third derivatives of f, are
symmetric central differences of f along real directions (q = a + i b splits
every complex form into real ones by multilinearity, and polarisation turns
the mixed forms into derivatives along a, b, a + b, a - b), Richardson-
extrapolated from steps h and 2h to O(h^4): near a GH point l1 is a small
difference of such terms. All stencil points of one stage go to the problem
in one batched call (two calls, 41 + 49 points: the second stage needs h11
and h20 from the first).

washer/cont/include/ae_lyapunov.h is the compiled form of first_lyapunov (the GH test
where the compiled corrector runs the Hopf locus): a change here is made there too
(tests/test_corrector_algebraic.py compares the two at every point of ab's and lrz's Hopf
curves).
"""
from __future__ import annotations

import numpy as np

from washer.cont.linalg import eig, solve

#: Steps for second and third differences, about eps^(1/4) and eps^(1/5) of a
#: unit-scaled state: they balance truncation O(h^4) after extrapolation
#: against rounding eps |f| / h^2 (resp. h^3).
FD2_STEP = 1e-3
FD3_STEP = 4e-3


#: The stencil offsets of second and third differences, in units of the direction: h and
#: 2h either side (h = FD2_STEP), h, 2h and 4h either side (h = FD3_STEP).
_C2 = np.array([FD2_STEP, -FD2_STEP, 2 * FD2_STEP, -2 * FD2_STEP])
_C3 = np.array([FD3_STEP, -FD3_STEP, 2 * FD3_STEP, -2 * FD3_STEP, 4 * FD3_STEP, -4 * FD3_STEP])


def _directional(problem, x, p, W2, W3=None):
    """Symmetric directional derivatives of f at x along the rows of W2 (second) and W3
    (third), all in one batched call. Central differences along w,
        D2 ~ [f(x+hw) - 2f(x) + f(x-hw)] / h^2,
        D3 ~ [f(x+2hw) - 2f(x+hw) + 2f(x-hw) - f(x-2hw)] / (2h^3),
    each Richardson-extrapolated from h and 2h to O(h^4): (4 D(h) - D(2h)) / 3.
    Returns D2 (k2, n) and D3 (k3, n) (None without W3)."""
    # Points x + (c h) w for all directions of one order at once (c = +-1, +-2, and
    # +-4 for third derivatives): the same arithmetic as point by point.
    n = len(x)
    k2 = len(W2)
    blocks = [x[None, :], (x + _C2[None, :, None] * W2[:, None, :]).reshape(-1, n)]
    if W3 is not None:
        blocks.append((x + _C3[None, :, None] * W3[:, None, :]).reshape(-1, n))
    F = problem.func_many(np.concatenate(blocks), p)
    f0 = F[0]
    F2 = F[1:1 + k2 * 4].reshape(-1, 4, n)
    h2, h3 = FD2_STEP, FD3_STEP
    d_h = (F2[:, 0] - 2 * f0 + F2[:, 1]) / h2 ** 2
    d_2h = (F2[:, 2] - 2 * f0 + F2[:, 3]) / (2 * h2) ** 2
    D2 = (4 * d_h - d_2h) / 3
    if W3 is None:
        return D2, None
    F3 = F[1 + k2 * 4:].reshape(-1, 6, n)
    d_h = (F3[:, 2] - 2 * F3[:, 0] + 2 * F3[:, 1] - F3[:, 3]) / (2 * h3 ** 3)
    d_2h = (F3[:, 4] - 2 * F3[:, 2] + 2 * F3[:, 3] - F3[:, 5]) / (2 * (2 * h3) ** 3)
    return D2, (4 * d_h - d_2h) / 3


def _bilinear(d2_sum, d2_diff):
    """B(u, w) = [D2(u + w) - D2(u - w)] / 4 (polarisation of the quadratic form)."""
    return (d2_sum - d2_diff) / 4


def first_lyapunov(problem, x, p, omega: float, A: np.ndarray | None = None) -> float:
    """l1 at the Hopf point x (ndim,), parameters p (npar,), frequency omega
    (rad per unit time); A = f_x(x, p) if already known."""
    x = np.asarray(x, dtype=float)
    if A is None:
        A = problem.dfdu(x, p)
    n = len(x)
    lam, V = eig(A)
    q = V[:, np.argmin(np.abs(lam - 1j * omega))]
    lamT, W = eig(A.T)
    pv = W[:, np.argmin(np.abs(lamT + 1j * omega))]
    qr, qi = q.real, q.imag
    q = q / np.sqrt(qr.dot(qr) + qi.dot(qi))          # np.linalg.norm(q), the same sums
    pv = pv / np.conj(np.conj(pv) @ q)
    a, b = q.real.copy(), q.imag.copy()
    # Stage 1, by polarisation of symmetric directional derivatives along a, b, a +- b:
    # D3(a+b) + D3(a-b) = 2 C(a,a,a) + 6 C(a,b,b), D3(a+b) - D3(a-b) = 6 C(a,a,b) + 2 C(b,b,b).
    dirs = np.array([a, b, a + b, a - b])
    (D2a, D2b, D2s, D2d), (D3a, D3b, D3s, D3d) = _directional(problem, x, p, dirs, dirs)
    Bab = _bilinear(D2s, D2d)
    B_qqb = D2a + D2b                               # B(q, conj q)
    B_qq = D2a - D2b + 2j * Bab                     # B(q, q)
    re_C = (2 / 3) * D3a + (D3s + D3d) / 6          # C(a,a,a) + C(a,b,b)
    im_C = (2 / 3) * D3b + (D3s - D3d) / 6          # C(a,a,b) + C(b,b,b)
    C_qqqb = re_C + 1j * im_C                       # C(q, q, conj q)
    with np.errstate(invalid="ignore"):             # a singular A: NaN, raised below
        h11 = solve(A, B_qqb).real                  # real: B(q, conj q) is real
        h20 = solve(2j * omega * np.eye(n) - A, B_qq)
    if not (np.isfinite(h11).all() and np.isfinite(h20).all()):
        raise np.linalg.LinAlgError("Singular matrix")
    c, d = h20.real, h20.imag
    # Stage 2: B(u, w) of the pairs (a, h11), (b, h11), (a, c), (b, d), (a, d), (b, c).
    U = np.array([a, b, a, b, a, b])
    Wp = np.array([h11, h11, c, d, d, c])
    D2, _ = _directional(problem, x, p, np.concatenate((U + Wp, U - Wp)))
    Bah, Bbh, Bac, Bbd, Bad, Bbc = _bilinear(D2[:6], D2[6:])
    B_q_h11 = Bah + 1j * Bbh                        # B(q, h11)
    B_qb_h20 = Bac + Bbd + 1j * (Bad - Bbc)         # B(conj q, h20)
    val = np.conj(pv) @ (C_qqqb - 2 * B_q_h11 + B_qb_h20)
    return float(val.real / (2 * omega))
