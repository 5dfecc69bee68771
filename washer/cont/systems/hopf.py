"""The Hopf locus in two parameters (AUTO's ISW = 2 from an HB label; FNHB,
FFHB, STPNHB in equilibrium.f90; Kuznetsov, 3rd ed., eqs 10.80 and 10.83).

Unknowns x = (u, v, kappa = omega^2, PAR(ICP(2)), PAR(ICP(1))), 2n + 2 equations:

    f(u, p) = 0,   (A^2 + kappa I) v = 0,   <v, v> - 1 = 0,   <A^T v_old - A v_old, v> = 0

with A = f_u(u, p) and v_old the previous point's v (moved in `update`).
Test functions (base codes; written as -31, -32, -33, 32, 31 on the curve):
BT (-1) kappa crosses 0 (the run always stops there), GH (-2) the first
Lyapunov coefficient, ZH (-3) a real eigenvalue crosses 0, LP (2) the curve
folds with respect to PAR(ICP(1)), BP (1) the Newton matrix is singular (a
crossing with another Hopf locus that shares the frequency, or a branch point
of the equilibria on the locus); MXBF switching there follows the other branch.
"""
from __future__ import annotations

import math

import numpy as np

from washer.cont.codes import Code
from washer.cont.normal_form import first_lyapunov
from washer.cont.system import StartData, register
from washer.cont.linalg import nullvc
from washer.cont.systems._loci import LocusSystem
from washer.cont.systems.equilibrium import eigenvalues_sorted


@register(1, 2, "HB")
@register(1, 2, "HB-curve")
class HopfSystem(LocusSystem):
    """The Hopf locus as a continued system (the module's equations and tests)."""
    curve_type = 3
    #: residual and jacobian are these equations of the problem's f and nothing more, with
    #: v_old: the compiled corrector (washer.cont.corrector_algebraic, AE_HOPF) may stand in
    #: for the Python loop; a subclass with other equations sets it None. Its C repeats
    #: these equations (include/ae_correct.h): a change here is made there too.
    compiled_system = "hopf"
    #: first_lyapunov(problem, x, p, omega, A): normal_form's, or its compiled form where
    #: the compiled corrector runs this locus (corrector_algebraic.compiled_corrector sets it).
    lyapunov = staticmethod(first_lyapunov)

    def __init__(self, start: StartData):
        self._setup(start, start.problem.ndim + 1)
        n = self.ndim
        p2 = self.par[self.free[1] - 1]
        ext = self.stored_point(start, "HB-curve")
        if ext is None:
            u = np.asarray(start.u, dtype=float)[:n]
            period = self.par[10] if len(self.par) > 10 else 0.0
            if not period > 0:
                raise ValueError("the HB record has no period PAR(11) > 0 to start the Hopf "
                                 "curve from")
            kappa = (2 * np.pi / period) ** 2
            # f_u differenced as AUTO's FUNI does, one step for all components: where
            # A^2 + kappa I has equal entries in exact arithmetic, its rounding decides
            # NLVC's pivot and so which v (fhn's travelling waves: 0.2 and 0.2 in its
            # first row; with per-component steps v came out the other vector of the
            # plane, the locus's steps, measured with v's components, fell one point
            # later than AUTO's, and a later restart from label 20 found no label 20).
            A = self.problem.dfdu(u, self.par, shared=True)
            # STPNHBF: which vector of the two-dimensional null space is AUTO's
            # NLVC's (the last two pivoted unknowns set to 1); the phase condition then
            # keeps v near it, so the locus's v, and every tangent with components in
            # v (the first step of a branch switched at a BP on the locus), are AUTO's.
            v = nullvc(A @ A + kappa * np.eye(n), 2)
            ext = np.r_[u, v / np.linalg.norm(v), kappa, p2]
        self._x0 = np.r_[ext, self.par[self.free[0] - 1]]
        self.v_old = self._x0[n:2 * n] / np.linalg.norm(self._x0[n:2 * n])
        self._t0 = self.stored_direction(start, "HB-curve")

    # ------------------------------------------------------------ equations
    def residual(self, x):
        n = self.ndim
        u, v, kappa = x[:n], x[n:2 * n], x[2 * n]
        p = self._p(x)
        A, _ = self.derivatives(u, p)
        return np.concatenate((self.problem.func(u, p), A @ (A @ v) + kappa * v,
                               [v @ v - 1.0, (A.T @ self.v_old - A @ self.v_old) @ v]))

    def jacobian(self, x, frozen_second: bool = False):
        """dG/dx, shape (2n + 2, 2n + 3). Blocks in v and kappa are exact; the
        f-rows use the problem's Jacobians; the derivatives of A (second
        derivatives of f, which problems do not supply) are central mixed
        differences of f in one batched call (Problem.second_derivatives).
        frozen_second: reuse those second-derivative blocks from the last full
        evaluation (the corrector's later iterations within a step)."""
        n = self.ndim
        v, kappa = x[n:2 * n], x[2 * n]
        u, p = x[:n], self._p(x)
        A, fp = self.derivatives(u, p)
        vo = self.v_old
        w = A.T @ vo - A @ vo
        if frozen_second and self._second is not None:
            d_g, d_phase = self._second
        else:
            T = self.second(x, np.array([A @ v, v, vo]))
            FAv, Fv, Fvo = T[:, 0], T[:, 1], T[:, 2]             # (n + 2, n) each
            # d/ds (A^2 v) = A_s (A v) + A (A_s v), A_s w = f_zz[e_s, w].
            d_g = FAv.T + A @ Fv.T
            # d/ds <A^T v_old - A v_old, v> = <v_old, A_s v> - <v, A_s v_old>.
            d_phase = Fv @ vo - Fvo @ v
            self._second = (d_g, d_phase)
        J = np.zeros((2 * n + 2, 2 * n + 3))
        # Columns: u (0..n-1), v (n..2n-1), kappa (2n), p2 (2n+1), p1 (2n+2); the
        # derivative blocks come in the order (u, p1, p2).
        cols = self._derivative_columns()
        J[:n, :n] = A
        J[:n, cols[n:]] = fp
        J[n:2 * n, cols] = d_g
        AA = A @ A
        AA.flat[::n + 1] += kappa                  # A^2 + kappa I
        J[n:2 * n, n:2 * n] = AA
        J[n:2 * n, 2 * n] = v
        J[2 * n, n:2 * n] = 2 * v
        J[2 * n + 1, cols] = d_phase
        J[2 * n + 1, n:2 * n] = w
        return J

    def _derivative_columns(self) -> np.ndarray:
        """The columns of J holding the derivatives along (u, PAR(ICP(1)), PAR(ICP(2)))."""
        cols = getattr(self, "_cols", None)
        if cols is None:
            n = self.ndim
            cols = self._cols = np.r_[np.arange(n), 2 * n + 2, 2 * n + 1]
        return cols

    def update(self, x, tangent):
        v = x[self.ndim:2 * self.ndim]
        # np.linalg.norm's own formula for a real vector (the square root of v.dot(v)),
        # without its Python dispatch: the same double
        self.v_old = v / math.sqrt(v.dot(v))

    # ---------------------------------------------------------------- tests
    def active_tests(self) -> list:
        return [code for name, code in (("LP", Code.LP), ("BP", Code.BP), ("BT", Code.BT),
                                        ("GH", Code.GH), ("ZH", Code.ZH))
                if self.settings.detects(name)]

    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict:
        n = self.ndim
        kappa = x[2 * n]
        out = self._lp_bp(tangent, factor, codes)
        if Code.BT in codes:
            out[Code.BT] = float(kappa)
        A = np.asarray(J)[:n, :n]
        if Code.CP in codes:           # GH: base code -2 on a Hopf curve
            out[Code.CP] = self.lyapunov(self.problem, x[:n], self._p(x), np.sqrt(kappa), A) \
                if kappa > 0 else None
        if Code.ZH in codes:
            # Product of the eigenvalues other than the Hopf pair: it changes sign
            # when a real eigenvalue crosses zero.
            if n > 2 and kappa > 0:
                lam = eigenvalues_sorted(A)
                k = np.argsort(np.abs(np.abs(lam.imag) - np.sqrt(kappa)) + np.abs(lam.real))
                out[Code.ZH] = float(np.prod(lam[k[2:]]).real)
            else:
                out[Code.ZH] = None
        return out

    def solution(self, x, tangent):
        sol = super().solution(x, tangent)
        kappa = x[2 * self.ndim]
        if len(sol.par) >= 11 and kappa > 0:
            sol.par[10] = 2 * np.pi / np.sqrt(kappa)     # PAR(11), as AUTO on Hopf curves
        return sol

    def info(self, x, code) -> dict:
        """Extra results for the d-file and the API at a labelled point."""
        n = self.ndim
        kappa = x[2 * n]
        if code == Code.CP and kappa > 0:
            l1 = first_lyapunov(self.problem, x[:n], self._p(x), np.sqrt(kappa))
            return {"omega": float(np.sqrt(kappa)), "l1": l1}
        return {}
