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
from washer.cont.linalg import EIG_MAX, compiled_lapack, null_vectors
from washer.cont.systems._loci import LocusSystem
from washer.cont.systems.equilibrium import IMAG_TOL, eigenvalues_sorted, is_complex

#: GESDD's and GEEV's workspaces of cont_fold_tests by size (functions of n alone; asked
#: for at the first call of a size)
_WORKSPACES: dict = {}


def fold_tests(M: np.ndarray, n: int, w_ref: np.ndarray, phi=None, F=None, zh: bool = False):
    """The fold locus's left null vector and test values at a point: (w, BT, CP, ZH).

    M : a float array whose leading (n, n) block is A = f_u (the extended Jacobian itself).
    w (n,): the left null vector of A, the right singular vector of A^T of its smallest
    singular value, oriented so that <w, w_ref> >= 0 (w_ref: the previous point's).
    BT = <w, phi> where phi (n,) is given; CP = <w, (F[0] - 2 F[1] + F[2]) / h^2> where F
    (3, n), f at u + h phi, u and u - h phi with h = FD2_STEP, is given (the quadratic
    coefficient <w, B(phi, phi)>); ZH, where asked, the product of the real parts of A's
    complex pairs (Im > 0), None where A has none. The values not asked for are None.
    In one compiled call (cont_fold_tests: numpy's GESDD, DDOT and GEEV called as
    numpy.linalg.svd, ndarray.dot and eigvals call them, the values of the numpy
    expressions below bit for bit) where numpy's bundled OpenBLAS is reachable; else by
    numpy. LinAlgError where the SVD or the eigenvalues fail, as numpy raises it."""
    C = compiled_lapack()
    if C is not None and 0 < n <= EIG_MAX and type(M) is np.ndarray and M.dtype == np.float64 \
            and M.ndim == 2 and M.flags.c_contiguous and M.shape[0] >= n and M.shape[1] >= n \
            and (F is None or F.shape == (3, n)) and w_ref.shape == (n,):
        ffi, lib = C.ffi, C.lib
        got = _WORKSPACES.get(n)
        if got is None:
            got = _WORKSPACES[n] = (ffi.new("int64_t[1]"), ffi.new("int[1]"))
        w, out, buf = np.empty(n), np.zeros(4), ffi.from_buffer
        ptr = ffi.cast("double *", 0)
        status = lib.cont_fold_tests(
            C.fold_routines, n, buf("double[]", M), M.shape[1],
            buf("double[]", np.ascontiguousarray(w_ref, dtype=float)),
            ptr if phi is None else buf("double[]", np.ascontiguousarray(phi, dtype=float)),
            ptr if F is None else buf("double[]", np.ascontiguousarray(F, dtype=float)),
            FD2_STEP ** 2, IMAG_TOL, buf("double[]", w), buf("double[]", out), got[0],
            got[1] if zh else ffi.cast("int *", 0))
        if status == 0:
            o = out.tolist()
            return (w, None if phi is None else o[0], None if F is None else o[1],
                    o[2] if zh and o[3] else None)
        if status == 1:
            raise np.linalg.LinAlgError("SVD did not converge")
        if status == 2:
            raise np.linalg.LinAlgError("Array must not contain infs or NaNs")
        if status == 3:
            raise np.linalg.LinAlgError("Eigenvalues did not converge")
        # (4: GEEV's workspace beyond the call's, -1: numpy's calls below)
    A = M[:n, :n]
    w = null_vectors(A.T, 1)[:, 0]
    w = w if w @ w_ref >= 0 else -w
    bt = None if phi is None else float(w @ phi)
    cp = None if F is None else float(w @ ((F[0] - 2 * F[1] + F[2]) / FD2_STEP ** 2))
    z = None
    if zh:
        lam = eigenvalues_sorted(A)
        pairs = lam[is_complex(lam) & (lam.imag > 0)]
        z = float(np.prod(pairs.real)) if pairs.size else None
    return w, bt, cp, z


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
        """The left null vector of A (n, n) oriented by the last point's (`fold_tests`)."""
        return fold_tests(A, self.ndim, self.w_ref)[0]

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
        out = self._lp_bp(tangent, factor, codes)
        F = None
        if Code.CP in codes:
            h = FD2_STEP
            F = self.problem.func_many(np.array([u + h * phi, u, u - h * phi]), self._p(x))
        w, bt, cp, zh = fold_tests(np.asarray(J), n, self.w_ref, phi, F, Code.ZH in codes)
        self._w_at = (x.tobytes(), self.w_ref, w)
        if Code.CP in codes:
            out[Code.CP] = cp
        if Code.BT in codes:
            out[Code.BT] = bt
        if Code.ZH in codes:
            out[Code.ZH] = zh
        return out
