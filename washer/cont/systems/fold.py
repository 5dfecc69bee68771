"""The fold locus in two parameters (AUTO's ISW = 2 from an LP label; FNLP,
FFLP in toolboxae.f90).

Unknowns x = (u, phi, PAR(ICP(2)), PAR(ICP(1))), 2n + 1 equations:

    f(u, p) = 0,   A phi = 0,   <phi, phi> - 1 = 0        (A = f_u(u, p))

Test functions (written as -22, -21, -23, 21 on the curve): CP (-2) the
quadratic coefficient <w, B(phi, phi)> with w the left null vector of A, BT
(-1) <w, phi>, ZH (-3) the product of Re(lambda) over the complex pairs, BP (1)
the determinant of the Newton matrix. The sign of w is kept continuous along
the curve by orienting it against the previous point's w (moved in `update`).
"""
from __future__ import annotations

import numpy as np

from washer.cont.codes import Code
from washer.cont.normal_form import FD2_STEP
from washer.cont.system import StartData, register
from washer.cont.linalg import null_vectors
from washer.cont.systems._loci import LocusSystem
from washer.cont.systems.equilibrium import eigenvalues_sorted, is_complex


@register(1, 2, "LP")
@register(0, 2, "LP")
@register(1, 2, "LP-curve")
@register(0, 2, "LP-curve")
class FoldSystem(LocusSystem):
    """The fold locus as a continued system (the module's equations and tests)."""
    curve_type = 2
    #: residual and jacobian are these equations of the problem's f and nothing more: the
    #: compiled corrector (washer.cont.corrector_algebraic, AE_FOLD) may stand in for the
    #: Python loop; a subclass with other equations sets it None. Its C repeats these
    #: equations (include/ae_correct.h): a change here is made there too.
    compiled_system = "fold"

    def __init__(self, start: StartData):
        self._setup(start, start.problem.ndim)
        n = self.ndim
        ext = self.stored_point(start, "LP-curve")
        if ext is None:
            u = np.asarray(start.u, dtype=float)[:n]
            phi = null_vectors(self.problem.dfdu(u, self.par), 1)[:, 0]
            ext = np.r_[u, phi / np.linalg.norm(phi), self.par[self.free[1] - 1]]
        self._x0 = np.r_[ext, self.par[self.free[0] - 1]]
        A = self.problem.dfdu(self._x0[:n], self._p(self._x0))
        self.w_ref = null_vectors(A.T, 1)[:, 0]
        self._t0 = self.stored_direction(start, "LP-curve")


    def residual(self, x):
        n = self.ndim
        u, phi = x[:n], x[n:2 * n]
        p = self._p(x)
        return np.r_[self.problem.func(u, p), self.derivatives(u, p)[0] @ phi, phi @ phi - 1.0]

    def jacobian(self, x, frozen_second: bool = False):
        """dG/dx, shape (2n + 1, 2n + 2): exact in phi, the problem's Jacobians in
        the f-rows, d(A phi) = f_zz[e_s, phi] from one batched stencil of f
        (Problem.second_derivatives); frozen_second reuses the last one."""
        n = self.ndim
        phi = x[n:2 * n]
        u, p = x[:n], self._p(x)
        A, fp = self.derivatives(u, p)
        if frozen_second and self._second is not None:
            T = self._second
        else:
            T = self._second = self.second(x, phi[None, :])
        J = np.zeros((2 * n + 1, 2 * n + 2))
        cols_s = np.r_[np.arange(n), 2 * n + 1, 2 * n]     # u, p1, p2
        J[:n, :n] = A
        J[:n, 2 * n + 1] = fp[:, 0]
        J[:n, 2 * n] = fp[:, 1]
        J[n:2 * n, cols_s] = T[:, 0].T                 # d(A phi)/ds = f_zz[e_s, phi]
        J[n:2 * n, n:2 * n] = A
        J[2 * n, n:2 * n] = 2 * phi
        return J

    def _w(self, A):
        w = null_vectors(A.T, 1)[:, 0]
        return w if w @ self.w_ref >= 0 else -w

    #: (x's bytes, the w_ref it was oriented by, w) of the last test_functions call: the
    #: left null vector at the point update moves to, as the tests computed it
    _w_at = None

    def update(self, x, tangent):
        # w_ref only orients the next point's w (its sign): the tests' w at this x, from
        # the Jacobian's A, serves where they were evaluated here with the same w_ref
        memo = self._w_at
        if memo is not None and memo[1] is self.w_ref and memo[0] == x.tobytes():
            self.w_ref = memo[2]
            return
        n = self.ndim
        self.w_ref = self._w(self.problem.dfdu(x[:n], self._p(x)))

    def active_tests(self) -> list:
        return [code for name, code in (("BP", Code.BP), ("CP", Code.CP), ("BT", Code.BT),
                                        ("ZH", Code.ZH))
                if self.settings.detects(name)]

    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict:
        n = self.ndim
        u, phi = x[:n], x[n:2 * n]
        p = self._p(x)
        A = np.asarray(J)[:n, :n]
        out = self._lp_bp(tangent, factor, codes)
        w = self._w(A)
        self._w_at = (x.tobytes(), self.w_ref, w)
        if Code.CP in codes:
            h = FD2_STEP
            F = self.problem.func_many(np.array([u + h * phi, u, u - h * phi]), p)
            out[Code.CP] = float(w @ ((F[0] - 2 * F[1] + F[2]) / h ** 2))
        if Code.BT in codes:
            out[Code.BT] = float(w @ phi)
        if Code.ZH in codes:
            lam = eigenvalues_sorted(A)
            pairs = lam[is_complex(lam) & (lam.imag > 0)]
            out[Code.ZH] = float(np.prod(pairs.real)) if pairs.size else None
        return out
