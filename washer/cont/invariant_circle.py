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
that makes N n + 1 equations in the N n + 2 unknowns z = (X, rho, p): a curve, which the
continuation engine follows (`washer.cont.systems.circles`: the family born at a
Neimark-Sacker point, pseudo-arclength, its records).

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

from dataclasses import dataclass, field

import numpy as np

#: Eigenvectors whose energy in Fourier modes |k| <= K/LOW_FRACTION is at least LOW_ENERGY
#: of the total count as resolved when the normal moduli are read (Jorba's filter): the
#: high modes of a degree-K interpolant are not. (An eigenvalue of a circle shared by two
#: eigenvectors mixes them: a resolved one may show half its energy low.)
LOW_FRACTION = 3
LOW_ENERGY = 0.4
#: Moduli of one circle of eigenvalues agree to the eigensolver's accuracy (~1e-10 for the
#: resolved ones); logs closer than this are one group.
GROUP_TOL = 1e-8


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
