"""Invariant circles of maps: Fourier collocation, continuation, rotation number, stability.

A smooth map x -> F(x, p) of R^n with an invariant circle on which it acts, up to a
change of the circle's angle, as the rigid rotation theta -> theta + 2 pi rho, has a
parametrisation x(theta) (2 pi-periodic, (n,)) with

    F(x(theta), p) = x(theta + 2 pi rho)        for every theta            (1)

rho is the rotation number (turns per iterate). This is the invariance equation of
quasi-periodic invariant curves (Jorba 2001, "Numerical computation of the normal
behaviour of invariant curves of n-dimensional maps", Nonlinearity 14; Schilder, Osinga
and Vogt 2005, SIAM J. Appl. Dyn. Syst. 4). It is discretised here by collocation at the
N = 2K + 1 equally spaced nodes theta_j = 2 pi j / N of the trigonometric interpolant
of degree K: the unknowns are the node values X (N, n) and rho, and x(theta_j + s) is
the interpolant shifted, R(s) X with the real N x N matrix

    R(s)_jl = (1 + 2 sum_{k=1..K} cos k (theta_j - theta_l + s)) / N.

Equation (1) fixes x only up to a shift of theta; a phase condition removes it:
sum_j <X'_ref,j, X_j - X_ref,j> = 0 with X_ref the previous circle and X'_ref its
derivative in theta (orthogonal to the shifts of the reference). With the parameter p
that makes N n + 1 equations in the N n + 2 unknowns z = (X, rho, p): a curve,
continued by pseudo-arclength (`continue_circle`).

Stability (Jorba 2001): a perturbation v(theta) of the circle is carried by DF to
DF(x(theta)) v(theta) at the image point theta + 2 pi rho, so the normal behaviour is
the generalised eigenproblem

    blockdiag(DF(X_j)) v = lambda (R(2 pi rho) (x) I_n) v.

For a reducible circle its eigenvalues lie on n circles |lambda| = const, one per
normal direction plus the tangent direction (|lambda| = 1, v = x'); the circle is
attracting when every modulus but the tangent's is below 1. The moduli are the normal
Lyapunov multipliers per iterate. Discretisation leaves the moduli of the high Fourier
modes inaccurate, so `normal_moduli` takes each circle's modulus from its
low-frequency eigenvectors (Jorba's filter).

The map enters only through

    fmap(X (N, n), p) -> (F (N, n), DF (N, n, n), Fp (N, n))

(values, Jacobians in x and derivatives in p at the N points). Nothing here knows what
the map stands for (the washer's stroboscopic map is `washer.problems.torus`).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

#: Newton stops when max|G| <= NEWTON_TOL * (1 + max|X|). The map is evaluated with an
#: error of ~1e-10 (the washer's flow at rtol 1e-10); asking less would chase noise.
NEWTON_TOL = 1e-9
NEWTON_MAX_ITER = 10
#: Eigenvectors whose energy in Fourier modes |k| <= K/LOW_FRACTION is at least LOW_ENERGY
#: of the total count as resolved when the normal moduli are read (Jorba's filter): the
#: high modes of a degree-K interpolant are not. (An eigenvalue of a circle shared by two
#: eigenvectors mixes them: a resolved one may show half its energy low.)
LOW_FRACTION = 3
LOW_ENERGY = 0.4
#: Moduli of one circle of eigenvalues agree to the eigensolver's accuracy (~1e-10 for the
#: resolved ones); logs closer than this are one group.
GROUP_TOL = 1e-8


class CircleError(RuntimeError):
    """Newton on the invariance equation did not converge."""


# ------------------------------------------------------------------ trigonometric interpolation

def nodes(N: int) -> np.ndarray:
    """The collocation angles theta_j = 2 pi j / N (N,), N odd."""
    if N % 2 != 1 or N < 3:
        raise ValueError(f"number of nodes: expected an odd N >= 3, got {N}")
    return 2.0 * np.pi * np.arange(N) / N


def shift_matrix(N: int, s: float, derivative: int = 0) -> np.ndarray:
    """R(s) (N, N): values of the degree-(N-1)/2 trigonometric interpolant of node values at
    the shifted nodes theta_j + s (derivative = 0), or the d-th derivative in s of that."""
    K = (N - 1) // 2
    th = nodes(N)
    a = th[:, None] - th[None, :] + s
    k = np.arange(1, K + 1)
    arg = a[..., None] * k
    if derivative == 0:
        return (1.0 + 2.0 * np.cos(arg).sum(-1)) / N
    if derivative == 1:
        return -2.0 * (k * np.sin(arg)).sum(-1) / N
    if derivative == 2:
        return -2.0 * (k * k * np.cos(arg)).sum(-1) / N
    raise ValueError(f"derivative: expected 0, 1 or 2, got {derivative}")


def evaluate(X, theta) -> np.ndarray:
    """The interpolant of node values X (N, n) at angles theta (m,): (m, n)."""
    X = np.asarray(X, dtype=float)
    N = X.shape[0]
    K = (N - 1) // 2
    c = np.fft.fft(X, axis=0) / N
    th = np.atleast_1d(np.asarray(theta, dtype=float))
    k = np.r_[np.arange(K + 1), np.arange(-K, 0)]
    return (np.exp(1j * th[:, None] * k[None, :]) @ c).real


def amplitudes(X) -> np.ndarray:
    """|c_k| summed over components in the 2-norm, k = 0..K (K + 1,): the Fourier spectrum
    of the circle; its tail says how well N nodes resolve it."""
    X = np.asarray(X, dtype=float)
    N = X.shape[0]
    K = (N - 1) // 2
    c = np.fft.fft(X, axis=0) / N
    amp = np.sqrt((np.abs(c[:K + 1]) ** 2).sum(axis=1))
    amp[1:] *= 2.0
    return amp


def resample(X, N: int) -> np.ndarray:
    """The circle X (M, n) represented on N nodes (interpolation, N odd)."""
    return evaluate(X, nodes(N))


# ------------------------------------------------------------------ the invariance equation

@dataclass
class Circle:
    """An invariant circle: node values X (N, n) at theta_j = 2 pi j / N, rotation number
    rho (turns per iterate), parameter p; residual max|G|; moduli: the normal Lyapunov
    multipliers per iterate (distinct values, decreasing; nan if not computed), tangent:
    the tangent direction's modulus (1 up to discretisation)."""
    X: np.ndarray
    rho: float
    p: float
    residual: float = float("nan")
    moduli: np.ndarray = field(default_factory=lambda: np.array([np.nan]))
    tangent: float = float("nan")
    iterations: int = 0

    @property
    def N(self) -> int:
        return self.X.shape[0]

    @property
    def stable(self) -> bool:
        """Attracting: every normal modulus below 1."""
        return bool(np.all(self.moduli < 1.0))

    def __call__(self, theta) -> np.ndarray:
        return evaluate(self.X, theta)


class InvarianceEquation:
    """G(z) = 0 with z = (X.ravel(), rho, p): equation (1) at the nodes and the phase
    condition against the reference X_ref. residual_jacobian(z) returns (G (N n + 1,),
    dG/dz (N n + 1, N n + 2), DF (N, n, n)) from one call of fmap."""

    def __init__(self, fmap, N: int, n: int, X_ref):
        self.fmap, self.N, self.n = fmap, N, n
        self.set_reference(X_ref)

    def set_reference(self, X_ref) -> None:
        self.X_ref = np.array(X_ref, dtype=float).reshape(self.N, self.n)
        self.dX_ref = shift_matrix(self.N, 0.0, 1) @ self.X_ref

    def split(self, z):
        Nn = self.N * self.n
        return z[:Nn].reshape(self.N, self.n), float(z[Nn]), float(z[Nn + 1])

    def residual_jacobian(self, z):
        N, n = self.N, self.n
        X, rho, p = self.split(z)
        F, DF, Fp = self.fmap(X, p)
        s = 2.0 * np.pi * rho
        R, R1 = shift_matrix(N, s), shift_matrix(N, s, 1)
        G = np.r_[(F - R @ X).ravel(), np.sum(self.dX_ref * (X - self.X_ref))]
        J = np.zeros((N * n + 1, N * n + 2))
        J[:N * n, :N * n] = -np.kron(R, np.eye(n))
        for j in range(N):
            J[j * n:(j + 1) * n, j * n:(j + 1) * n] += DF[j]
        J[:N * n, N * n] = -2.0 * np.pi * (R1 @ X).ravel()
        J[:N * n, N * n + 1] = np.asarray(Fp).ravel()
        J[N * n, :N * n] = self.dX_ref.ravel()
        return G, J, DF


def normal_moduli(X, rho: float, DF) -> tuple[np.ndarray, float, np.ndarray]:
    """Stability of the circle X (N, n) with rotation number rho from the Jacobians DF
    (N, n, n) at its nodes: the generalised eigenproblem blockdiag(DF) v = lambda (R (x) I) v.

    Returns (the distinct moduli of the normal directions in decreasing order (at most
    n - 1: a complex pair of normal multipliers shares one), the tangent direction's
    modulus, all eigenvalues (N n,)). Only resolved eigenvectors are read (at least
    LOW_ENERGY of their energy in Fourier modes |k| <= K / LOW_FRACTION: the high modes of
    a degree-K interpolant carry spurious moduli); their moduli, equal on each circle to
    the eigensolver's accuracy, are grouped where consecutive logs differ by less than
    GROUP_TOL. The tangent is the eigenvector best aligned with x'(theta); its group is
    left out."""
    X = np.asarray(X, dtype=float)
    N, n = X.shape
    K = (N - 1) // 2
    R = shift_matrix(N, 2.0 * np.pi * rho)
    A = np.zeros((N * n, N * n))
    for j in range(N):
        A[j * n:(j + 1) * n, j * n:(j + 1) * n] = DF[j]
    lam, V = np.linalg.eig(np.linalg.solve(np.kron(R, np.eye(n)), A))
    # Energy of each eigenvector in the low Fourier modes (in theta, per component).
    C = np.abs(np.fft.fft(V.reshape(N, n, -1), axis=0)) ** 2
    k = np.abs(np.r_[np.arange(K + 1), np.arange(-K, 0)])
    low = C[k <= max(1, K // LOW_FRACTION)].sum(axis=(0, 1)) / C.sum(axis=(0, 1))
    logm = np.log(np.abs(lam))
    dX = (shift_matrix(N, 0.0, 1) @ X).ravel()
    overlap = np.abs(dX @ V.conj()) / (np.linalg.norm(V, axis=0) * np.linalg.norm(dX))
    i_tan = int(np.argmax(overlap))
    tangent = float(np.exp(logm[i_tan]))
    sel = np.sort(logm[low >= LOW_ENERGY])[::-1]
    groups = np.split(sel, np.nonzero(-np.diff(sel) > GROUP_TOL)[0] + 1) if sel.size else []
    moduli = [np.exp(np.median(g)) for g in groups
              if not np.any(np.abs(g - logm[i_tan]) <= GROUP_TOL)]
    return np.array(sorted(moduli, reverse=True)), tangent, lam


def newton(eq: InvarianceEquation, z0, extra=None, tol: float = NEWTON_TOL,
           max_iter: int = NEWTON_MAX_ITER):
    """Newton on [G(z); extra(z)] = 0 (N n + 2 equations: extra(z) -> (value, gradient
    (N n + 2,)) is the arclength or amplitude condition). Returns (z, DF at z, residual,
    iterations); raises CircleError."""
    z = np.array(z0, dtype=float)
    res = np.inf
    for it in range(max_iter + 1):
        G, J, DF = eq.residual_jacobian(z)
        e, de = extra(z)
        res = float(max(np.abs(G).max(), abs(e)))
        X = z[:eq.N * eq.n]
        if res <= tol * (1.0 + np.abs(X).max()) and it > 0:
            return z, DF, res, it
        if it == max_iter or not np.isfinite(res):
            break
        dz = np.linalg.solve(np.vstack([J, de]), -np.r_[G, e])
        z = z + dz
    raise CircleError(f"invariant circle: no convergence in {max_iter} Newton iterations "
                      f"(residual {res:.3e})")


# ------------------------------------------------------------------ continuation

@dataclass
class CircleBranch:
    """A continued family of invariant circles, in the order computed: circles (list of
    Circle), p (m,), rho (m,), amplitude (m,) = the Fourier-mode-1 amplitude of the circle
    (2-norm over components: its radius for a round circle), leading (m,): the largest
    normal modulus, stable (m,), status."""
    circles: list
    status: str
    wall: float

    @property
    def p(self) -> np.ndarray:
        return np.array([c.p for c in self.circles])

    @property
    def rho(self) -> np.ndarray:
        return np.array([c.rho for c in self.circles])

    @property
    def amplitude(self) -> np.ndarray:
        return np.array([amplitudes(c.X)[1] for c in self.circles])

    @property
    def leading(self) -> np.ndarray:
        """The largest normal modulus of each circle (m,): < 1 where it attracts."""
        return np.array([c.moduli.max() if c.moduli.size else np.nan for c in self.circles])

    @property
    def stable(self) -> np.ndarray:
        return np.array([c.stable for c in self.circles])


def _weights(N: int, n: int, scale) -> np.ndarray:
    """Inner-product weights of z = (X, rho, p): node values averaged over the circle
    (1/N each, per-component scales), rho and p as they are."""
    return np.r_[np.tile(1.0 / np.asarray(scale, dtype=float) ** 2, N) / N, 1.0, 1.0]


def circle_at_amplitude(fmap, x_star, v, rho0: float, p0: float, amplitude: float,
                        N: int, dp_guess: float = 0.0, tol: float = NEWTON_TOL) -> Circle:
    """The first circle of a family born at a Neimark-Sacker point: the fixed point x_star
    (n,) at p0 with critical eigenvector v (n,) complex (DF v = mu v, arg mu = 2 pi rho0).
    Newton from x_star + amplitude Re(v e^{i theta}) (v scaled to |Re v|, |Im v| of unit
    largest component) with rho and p free and the circle's mode-1 content along v fixed
    at `amplitude` (the family's size, not the parameter, is the coordinate near the birth:
    the parameter moves like amplitude^2 there). dp_guess: p - p0 of the starting guess."""
    x_star = np.asarray(x_star, dtype=float)
    n = x_star.size
    v = np.asarray(v, dtype=complex)
    v = v / np.abs(v).max()
    th = nodes(N)
    X0 = x_star + amplitude * np.real(np.exp(1j * th)[:, None] * v[None, :])
    eq = InvarianceEquation(fmap, N, n, X0)
    # Mode-1 projection on the birth direction: (2/N) sum_j Re(conj(v e^{i th_j})) . (X_j - x*) / |v|^2.
    basis = np.real(np.exp(1j * th)[:, None] * v[None, :])
    g = np.r_[basis.ravel() / np.sum(basis * basis), 0.0, 0.0]
    ref = np.r_[np.tile(x_star, N), 0.0, 0.0]

    def extra(z):
        return float(g @ (z - ref)) - amplitude, g

    z, DF, res, it = newton(eq, np.r_[X0.ravel(), rho0, p0 + dp_guess], extra, tol)
    X, rho, p = eq.split(z)
    moduli, tangent, _ = normal_moduli(X, rho, DF)
    return Circle(X, rho, p, res, moduli, tangent, it)


def continue_circle(fmap, first: Circle, stop: float, *, second: Circle | None = None,
                    ds: float = 0.05, ds_max: float = 0.5, ds_min: float = 1e-4,
                    max_points: int = 200, scale=None, tol: float = NEWTON_TOL,
                    progress=None) -> CircleBranch:
    """Continue the invariant circles of fmap from `first` (and `second`, a nearby circle of
    the same family fixing the direction; default: the direction in which p moves towards
    `stop`) until p reaches `stop`, by pseudo-arclength in z = (X, rho, p) with the weighted
    inner product of `_weights` (scale (n,): typical size of each component; default 1).

    Secant predictor; corrector: Newton on [G; <z - z_pred, secant>] with the phase
    condition's reference moved to the last circle; steps halve on failure down to ds_min
    and grow 1.5x after an easy success (<= 3 iterations) up to ds_max; fmap may raise
    ValueError or RuntimeError where it is not defined (a parameter out of range): that
    step is halved too. The last point is
    put exactly on p = stop (a Newton with p fixed). Normal moduli at every circle.
    progress(circle) is called after each one."""
    t0 = time.perf_counter()
    N, n = first.X.shape
    w = _weights(N, n, np.ones(n) if scale is None else scale)
    eq = InvarianceEquation(fmap, N, n, first.X)

    def zof(c):
        return np.r_[c.X.ravel(), c.rho, c.p]

    circles = [first]
    if second is None:
        # Direction: the null vector of dG/dz at the first circle, p moving towards stop.
        _, J, _ = eq.residual_jacobian(zof(first))
        t = np.linalg.svd(J)[2][-1]
        if t[-1] * (stop - first.p) < 0:
            t = -t
    else:
        circles.append(second)
        t = zof(second) - zof(first)
    t = t / np.sqrt(t @ (w * t))
    h = ds
    status = "max_points"
    direction = np.sign(stop - first.p) or 1.0
    while len(circles) < max_points:
        z = zof(circles[-1])
        zp = z + h * t
        eq.set_reference(circles[-1].X)
        last = (zp[-1] - stop) * direction >= 0
        if last:        # the step would pass the end: predict onto p = stop, keep p there
            zp = z + (stop - z[-1]) / t[-1] * t
            e_p = np.zeros(zp.size)
            e_p[-1] = 1.0

            def extra(zz):
                return zz[-1] - stop, e_p
        else:
            def extra(zz, zp=zp):
                return float((w * t) @ (zz - zp)), w * t
        try:
            zn, DF, res, it = newton(eq, zp, extra, tol)
        except (CircleError, np.linalg.LinAlgError, ArithmeticError, RuntimeError, ValueError):
            h /= 2      # no convergence, or a Newton iterate outside fmap's domain
            if h < ds_min:
                status = "step too small"
                break
            continue
        X, rho, p = eq.split(zn)
        if last:
            status = "reached"
        moduli, tangent, _ = normal_moduli(X, rho, DF)
        c = Circle(X, rho, p, res, moduli, tangent, it)
        circles.append(c)
        if progress is not None:
            progress(c)
        if status == "reached":
            break
        sec = zn - z
        t = sec / np.sqrt(sec @ (w * sec))
        if it <= 3:
            h = min(ds_max, 1.5 * h)
    return CircleBranch(circles, status, time.perf_counter() - t0)
