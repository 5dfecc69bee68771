"""The adjoint variational equation of a homoclinic orbit (HomCont's ITWIST = 1: FNHO's
second half, FBHO's "boundary conditions for normal vector", ICHO's second integral,
PREHO's perturbed start, PSIHO's 0, 13 and 14).

Beside the orbit u(t), t in [0, 1] (time scaled by T = PAR(11)), the continued system
carries v(t) in R^NDIM:

    v'(t) = T (-f_u(u(t), p)^T v(t) + PAR(10) f(u(t), p))
    v(0) orthogonal to the NUNSTAB-dimensional unstable eigenspace of A = f_u(x0, p)
    v(1) orthogonal to its NSTAB-dimensional stable eigenspace
    int_0^1 vold(t) . (v(t) - vold(t)) dt = 0

PAR(10) is a free parameter (INHO appends it to ICP after the user's ones); at a
solution it is 0 and v is the bounded solution of the adjoint equation, normal to
T W^u + T W^s along the orbit (unique up to scale where the orbit is a transversal
codimension-one connection; the integral fixes the scale against the last point).

From it (PSIHO, rows of the eigenvector matrices as in washer.cont.systems.homoclinic):
  0   the orientation: -(f(u(1)) . v(0)) (f(u(0)) . v(1)) / (|f(u(0))| |f(u(1))| |v(0)| |v(1)|),
      positive for an orientable orbit, negative for a twisted (non-orientable) one
  13  inclination flip w.r.t. the stable manifold:  v(0) . V_s e^(-T Re l_s / 2)
  14  inclination flip w.r.t. the unstable manifold: v(1) . V_{s+1} e^(T Re l_{s+1} / 2)
(V the right eigenvectors, s = NSTAB the leading stable one, s + 1 the leading unstable).
"""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from washer.cont.systems.bvp import VectorField

#: PAR(10): the adjoint's free parameter (0 at a solution).
ADJOINT_PAR = 10
#: PREHO: the adjoint's components of a restart from an orbit without them.
START_VALUE = 0.1


def field(user, ndm: int):
    """(func_batch, dfdu_batch) of the orbit and its adjoint, W = (u, v) (k, 2 NDIM),
    pars (k, NPAR) -> (k, 2 NDIM) and (k, 2 NDIM, 2 NDIM), both scaled by T = PAR(11).
    The Jacobian's block d/du (-f_u^T v) is the Hessian of -v . f (VectorField's
    `fuu_adjoint`: differences of the user's f_u, or mixed differences of f)."""
    vf = VectorField(user, ndm)

    def func_batch(W, pars):
        U, V = W[:, :ndm], W[:, ndm:]
        F = user.func_many(U, pars)
        A = user.dfdu_many(U, pars)
        G = -np.einsum("kji,kj->ki", A, V) + pars[:, ADJOINT_PAR - 1:ADJOINT_PAR] * F
        return pars[:, 10:11] * np.hstack([F, G])

    def dfdu_batch(W, pars):
        U, V = W[:, :ndm], W[:, ndm:]
        k = len(W)
        A = user.dfdu_many(U, pars)
        H = vf.fuu_adjoint(U, V, pars[0]) if k else np.zeros((0, ndm, ndm))
        J = np.zeros((k, 2 * ndm, 2 * ndm))
        J[:, :ndm, :ndm] = A
        J[:, ndm:, :ndm] = -H + pars[:, ADJOINT_PAR - 1, None, None] * A
        J[:, ndm:, ndm:] = -np.transpose(A, (0, 2, 1))
        return pars[:, 10, None, None] * J

    return func_batch, dfdu_batch


def boundary_rows(left, right, A1: np.ndarray, A2: np.ndarray, v0: np.ndarray,
                  v1: np.ndarray) -> np.ndarray:
    """FBHO's NUNSTAB + NSTAB conditions on v: v(0) against `left` (a
    homoclinic._Projection onto A1's unstable subspace), v(1) against `right` (A2's
    stable one); A1, A2 = f_u at the equilibria at t = 0 and 1 (time reversed where
    PAR(11) < 0)."""
    return np.concatenate([left.rows(A1) @ v0, right.rows(A2) @ v1])


def integrand(w, wold, ndm: int):
    """ICHO's second integrand vold . (v - vold) at one point (2 NDIM,) or a batch
    (2 NDIM, k) -> scalar or (k,)."""
    return np.sum(wold[ndm:] * (w[ndm:] - wold[ndm:]), axis=0)


def widened_start(rec, ndm: int, par: np.ndarray):
    """PREHO: a restart from an orbit stored without its adjoint gets v = 0.1 at every
    node and PAR(10) = 0 (Newton finds the adjoint); a record that has it is kept."""
    from washer.cont.systems.bvp import record_profile
    t, U, ntst, ncol = record_profile(rec, 2 * ndm)
    if U.shape[1] >= 2 * ndm:
        return rec
    par[ADJOINT_PAR - 1] = 0.0
    return SimpleNamespace(U=widened_profile(U, ndm), t=t, ntst=ntst, ncol=ncol, udot=None,
                           rldot=[], icp=[], lab=getattr(rec, "lab", 0))


def widened_profile(U: np.ndarray, ndm: int) -> np.ndarray:
    """The orbit's profile U (NTPL, >= NDIM) with v = 0.1 beside it -> (NTPL, 2 NDIM)."""
    return np.hstack([U[:, :ndm], np.full((len(U), ndm), START_VALUE)])


def orientation(f0, f1, v0, v1) -> float:
    """PSIHO's 0: -(f(u(1)) . v(0)) (f(u(0)) . v(1)) over the four norms (0 where one
    vanishes); positive: orientable, negative: twisted (FNCSHO's words)."""
    d = math.sqrt(float(f0 @ f0) * float(f1 @ f1) * float(v0 @ v0) * float(v1 @ v1))
    return -float(f1 @ v0) * float(f0 @ v1) / d if d != 0 else 0.0


def inclination(k: int, v0, v1, lam, V, T: float, nstab: int) -> float:
    """PSIHO's 13 (v(0) against the leading stable right eigenvector) and 14 (v(1)
    against the leading unstable one), lam sorted by real part, V's rows the unit right
    eigenvectors (signs continued), T = PAR(11)."""
    s = nstab - 1
    if k == 13:
        return float(v0 @ V[s] * math.exp(-T * lam[s].real / 2))
    return float(v1 @ V[s + 1] * math.exp(T * lam[s + 1].real / 2))


__all__ = ["ADJOINT_PAR", "boundary_rows", "field", "inclination", "integrand",
           "orientation", "widened_profile", "widened_start"]
