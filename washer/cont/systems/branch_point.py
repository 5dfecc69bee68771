"""The branch-point locus of algebraic problems (AUTO's ISW = 2 or 3 from a BP
label, IPS = 0 or 1; FNBP, FFBP, STPNBP in toolboxae.f90, after F. Dercole's BPCONT).

A BP of the one-parameter branch f(u, p1) = 0 is where the n x (n + 1) matrix
[f_u  f_p1] loses rank: a left null vector phi* with f_u^T phi* = 0 and
f_p1 . phi* = 0. Unknowns x = (u, phi*, PAR(ICP(2)), z, PAR(ICP(1))), 2n + 2
equations:

    f(u, p) + b phi* = 0         (ISW = 2, z = b: the non-generic case)
    f(u, p) = 0                  (ISW = 3, z = PAR(ICP(3)): the generic case)
    f_u(u, p)^T phi* = 0
    f_p1(u, p) . phi* = 0
    <phi*, phi*> - 1 = 0

A BP is not generic in one parameter: it needs a symmetry or another structure
(ISW = 2, where the unfolding b stays 0 along the locus and the locus lies in two
parameters) or a third parameter (ISW = 3). The stored state is AUTO's U(1..2n + 2)
= (u, phi*, PAR(ICP(2)), z); its written codes carry curve type 1 (ITPST).

Tests on the locus: LP (the PAR(ICP(1))-component of the tangent) and BP (the
determinant of the Newton matrix), AUTO's FNLPAE and FNBPAE on the extended system.
"""
from __future__ import annotations

import numpy as np

from washer.cont.linalg import null_vectors
from washer.cont.settings import SettingsError
from washer.cont.system import Solution, StartData, register
from washer.cont.systems._loci import LocusSystem

#: Relative step of the second differences of f in two parameters (eps^(1/4)).
PAR_STEP = 1e-4


def adjoint_null_vector(A: np.ndarray, fp: np.ndarray) -> np.ndarray:
    """phi* with [A  fp]^T phi* = 0, unit (STPNBP: the left null vector of the
    n x (n + 1) matrix [f_u  f_p1] at a BP); the sign makes its largest entry
    positive."""
    phi = null_vectors(np.column_stack([A, fp]).T, 1)[:, 0]
    phi = phi / np.linalg.norm(phi)
    return phi if phi[np.argmax(np.abs(phi))] > 0 else -phi


@register(1, 2, "BP")
@register(0, 2, "BP")
@register(1, 2, "BP-curve")
@register(0, 2, "BP-curve")
class BranchPointLocus(LocusSystem):
    """The branch-point locus as a continued system (the module's equations and tests)."""
    curve_type = 1

    def __init__(self, start: StartData):
        s = start.settings
        self.generic = s.ISW == 3
        self._setup(start, start.problem.ndim + 1)
        n = self.ndim
        if self.generic:
            if len(s.ICP) < 3:
                raise SettingsError("ISW = 3 continues the branch points of a generic problem in "
                                 f"three parameters: ICP needs three entries, got {list(s.ICP)}", keys=("ICP",))
            self.free = [s.ICP[0], s.ICP[1], s.ICP[2]]
        # AUTO's weights: THU over the extended state U(1..2n + 2), THL on PAR(ICP(1)).
        self.theta = np.r_[s.theta_u(2 * n + 2), s.theta_par(s.ICP[0])]
        ext = self.stored_point(start, "BP-curve")
        if ext is None:
            u = np.asarray(start.u, dtype=float)[:n]
            A = self.problem.dfdu(u, self.par)
            fp = self.problem.dfdp(u, self.par, [self.free[0]])[:, 0]
            z = self.par[self.free[2] - 1] if self.generic else 0.0
            ext = np.r_[u, adjoint_null_vector(A, fp), self.par[self.free[1] - 1], z]
        self._x0 = np.r_[ext, self.par[self.free[0] - 1]]
        self._t0 = self.stored_direction(start, "BP-curve")

    # ------------------------------------------------------------------ layout
    def _p(self, x) -> np.ndarray:
        n = self.ndim
        p = self.par.copy()
        p[self.free[0] - 1] = x[-1]
        p[self.free[1] - 1] = x[2 * n]
        if self.generic:
            p[self.free[2] - 1] = x[2 * n + 1]
        return p

    def stored_direction(self, start: StartData, kind: str):
        rec = start.record
        if start.kind != kind or rec is None or rec.udot is None \
                or list(rec.icp[:len(self.free)]) != self.free or len(rec.udot) != self.n_eq:
            return None
        return np.r_[rec.udot, rec.rldot[0]]

    # ------------------------------------------------------------------ system
    def residual(self, x):
        n = self.ndim
        u, phi = x[:n], x[n:2 * n]
        p = self._p(x)
        f = self.problem.func(u, p)
        if not self.generic:
            f = f + x[2 * n + 1] * phi
        A = self.problem.dfdu(u, p)
        fp = self.problem.dfdp(u, p, [self.free[0]])[:, 0]
        return np.r_[f, A.T @ phi, fp @ phi, phi @ phi - 1.0]

    def _par_second(self, u, p, phi) -> np.ndarray:
        """phi . f_{p1 pj} for the free parameters pj (in `free` order): central
        second differences of f in the parameters (the state-parameter ones come
        from Problem.second_derivatives)."""
        i1 = self.free[0] - 1
        h1 = PAR_STEP * (1 + abs(p[i1]))
        out = []
        for j in self.free:
            ij = j - 1
            hj = PAR_STEP * (1 + abs(p[ij]))
            pts = []
            for a, b in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
                q = p.copy()
                q[i1] += a * h1
                q[ij] += b * hj
                pts.append(q)
            F = self.problem.func_many(np.tile(u, (4, 1)), np.array(pts))
            out.append(phi @ (F[0] - F[1] - F[2] + F[3]) / (4 * h1 * hj))
        return np.array(out)

    def jacobian(self, x, frozen_second: bool = False):
        """dG/dx, (2n + 2, 2n + 3): the problem's f_u, f_p in the f-rows, the
        second derivatives d(f_u^T phi)/ds = phi . f_zz[e_s, e_i] and
        d(f_p1 . phi)/du_s = phi . f_zz[e_p1, e_s] from one batched stencil of f
        (Problem.second_derivatives), phi . f_{p1 pj} by second differences."""
        n = self.ndim
        u, phi = x[:n], x[n:2 * n]
        p = self._p(x)
        A = self.problem.dfdu(u, p)
        fp = self.problem.dfdp(u, p, self.free)               # (n, nfree)
        T = self.second(x, np.eye(n))                         # (n + nfree, n, n)
        # Columns of z = (u, free params in `free` order) -> their slots in x.
        cols = list(range(n)) + [2 * n + 2, 2 * n] + ([2 * n + 1] if self.generic else [])
        J = np.zeros((2 * n + 2, 2 * n + 3))
        J[:n, :n] = A
        J[:n, 2 * n + 2] = fp[:, 0]
        J[:n, 2 * n] = fp[:, 1]
        if self.generic:
            J[:n, 2 * n + 1] = fp[:, 2]
        else:
            J[:n, n:2 * n] = x[2 * n + 1] * np.eye(n)
            J[:n, 2 * n + 1] = phi
        # d(A^T phi)_i / dz_s = phi . T[s, i]
        J[n:2 * n][:, cols] = np.einsum("sik,k->is", T, phi)
        J[n:2 * n, n:2 * n] = A.T
        # d(f_p1 . phi)/du_s = phi . f_zz[e_p1, e_s] = phi . T[n, s]
        J[2 * n, :n] = T[n] @ phi
        J[2 * n, [cols[n + k] for k in range(len(self.free))]] = self._par_second(u, p, phi)
        J[2 * n, n:2 * n] = fp[:, 0]
        J[2 * n + 1, n:2 * n] = 2 * phi
        return J

    def update(self, x, tangent):
        """Nothing moves along the locus."""

    # ------------------------------------------------------------------ output
    def solution(self, x, tangent) -> Solution:
        """The record: U = (u, phi*, PAR(ICP(2)), z) and its direction; RLDOT the
        free parameters' rates in ICP order."""
        n = self.ndim
        par = self.params(x)
        u = x[:n]
        cols = [float(np.sqrt(np.sum(u ** 2)))] + [float(v) for v in u[:self.n_columns]]
        slots = [2 * n + 2, 2 * n] + ([2 * n + 1] if self.generic else [])
        return Solution(par=par, columns=cols, u=np.array(x[:-1]), udot=np.array(tangent[:-1]),
                        rldot=[float(tangent[k]) for k in slots], ndim_user=n)


__all__ = ["BranchPointLocus", "adjoint_null_vector"]
