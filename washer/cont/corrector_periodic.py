"""The corrector of periodic orbits in one foreign call per continuation step.

    corrector = periodic_corrector(system, settings, DIVERGENCE_FACTOR)    # or None
    result = corrector.correct_plane(x_pred, x_ref, t_ref, ds, counters)   # (x, it) or None

This is the compiled form of the package's one Newton loop (washer.cont.newton.newton
as washer.cont.iterator.Continuation.correct runs it on the plane arclength of a
collocation BVP) for PeriodicOrbits (IPS 2): the same iteration (PeriodicOrbits.residual,
PeriodicOrbits.jacobian by central differences of f with VectorField.fu_fp's points and
quotients, refactorised up to NWTN iterations, chord iterations after), the same
factorisation and solve (the compiled condensation of CollocationBVP.factor) and the same
stopping test (AUTO's NEWTONBV: EPSU on the profile, EPSL on each parameter, the
divergence test of Continuation.correct), written once in C++ (csrc/cont/po_correct.cpp).
f is evaluated by the generated C of sympy problems (washer.cont.user_problem.user_files_sympy)
and by FUNC of
compiled AUTO user files (the bridge's washer_po_func,
washer.cont.user_problem.user_files_native) through
function pointers, called from C++ directly (and their exact f_u with JAC != 0, as the
Python loop's Problem.dfdu_many: the generated Jacobian, the user's DFDU by the bridge's
washer_po_jac); a Python file's f is called back from the C++ loop through
Problem.func_many (one call for the Gauss points of an iterate, one for all difference
points of a Jacobian) as the Python loop calls it. What the Python loop leaves behind for the
converged point (the last Newton Jacobian, its factorisation and Floquet pair) is left
the same way.

It applies to PeriodicOrbits with difference Jacobians (no user dfdu / dfdp in use, no
f evaluated with its Jacobians), to sympy problems and to compiled user files (JAC = 0,
1 or -1; f_p by differences, as the Python loop takes it for them). Everything else, and every case
the compiled loop does not finish cleanly (a failing or non-finite f, a non-finite
Jacobian or correction, a zero pivot: the Python loop then repeats the correction and
reports or resolves it as before), is the Python loop. washer.cont.corrector_algebraic.compiled_corrector makes the
choice, in one place.

Results: the same iterates bit for bit, so the same b- and s-files byte for byte
(tests/test_corrector_periodic.py): the same function values, quotients and Jacobian values,
the same factorisation and solve, the residual's sums in numpy's order (pairwise_sum in
po_correct.cpp) and the phase condition's and arclength row's inner products by the BLAS
ddot numpy's `@` uses (`numpy_ddot`; without it, sums in order: equal to rounding).
"""
from __future__ import annotations

import numpy as np

from washer.cont.newton import ConvergenceError
from washer.cont.differences import FD_STEP
from washer.cont.problem import Problem
from washer.cont import reduction
from washer.cont.reduction import ffi, lib
from washer.cont.systems import bvp

_ddot = None


def numpy_ddot():
    """The BLAS ddot numpy's `@` of two float vectors rounds as (scipy's, from
    scipy.linalg.cython_blas), as a cont_ddot for cont_po_correct's inner products: the
    phase condition and the border row then round as the Python loop's. Checked once
    against `@` on vectors of the lengths where BLAS kernels change their order; ffi.NULL
    (sums in order: equal to rounding) where scipy's does not agree or is missing."""
    global _ddot
    if _ddot is None:
        _ddot = ffi.NULL
        try:
            import ctypes
            from scipy.linalg import blas, cython_blas
            capsule = cython_blas.__pyx_capi__["ddot"]
            get_name = ctypes.pythonapi.PyCapsule_GetName
            get_name.restype, get_name.argtypes = ctypes.c_char_p, [ctypes.py_object]
            get_ptr = ctypes.pythonapi.PyCapsule_GetPointer
            get_ptr.restype, get_ptr.argtypes = ctypes.c_void_p, [ctypes.py_object,
                                                                  ctypes.c_char_p]
            ptr = get_ptr(capsule, get_name(capsule))
            rng = np.random.default_rng(0)
            same = all(blas.ddot(a, b) == a @ b for k in (1, 7, 31, 33, 100, 427, 2403, 9603)
                       for a, b in [rng.standard_normal((2, k))])
            if ptr and same:
                _ddot = ffi.cast("cont_ddot", ptr)
        except Exception:            # no scipy BLAS here: sums in order
            _ddot = ffi.NULL
    return _ddot


class PeriodicCorrector:
    """cont_po_correct for one run's PeriodicOrbits (see the module's docstring)."""

    #: Continuation.correct hands it the plane arclength's corrector
    plane = True

    def __init__(self, system, settings, divergence: float, generated=None, user=None):
        self.sys, self.s, self.divergence = system, settings, divergence
        self.problem = system.problem
        self.n = system.ndim
        self.error = None
        self._cb = ffi.callback("cont_po_feval", self._evaluate, onerror=self._onerror)
        # a sympy problem's generated C (washer.cont.user_problem.user_files_sympy), called from
        # C++ directly:
        # f, and its exact f_u where the Python loop uses it (Problem.has_dfdu)
        self._sfunc = self._sjac = ffi.NULL
        self._npar_jp = 0
        if generated is not None:
            self._sfunc = generated.pointer("washer_sym_func", ffi, "cont_po_sym_func")
            if self.problem.has_dfdu:
                self._sjac = generated.pointer("washer_sym_jac", ffi, "cont_po_sym_jac")
            self._npar_jp = max(generated.npar, 1)
            self._keep = generated      # the library stays loaded while the pointers live
        # a compiled user file's FUNC (washer.cont.user_problem.user_files_native.CompiledUser),
        # its pointers
        # bound afresh for each correction (CompiledUser.po_pointers)
        self._user = user
        self._npar = 0
        #: (x, J) of the last converged correction when its last iteration factorised
        #: (Continuation.correct's `_newton`), else None
        self.newton = None
        self._mesh_kept = None
        # cont_po_correct's counts, read as soon as it returns
        self._info = np.zeros(4, dtype=np.int32)
        self._info_ptr = ffi.from_buffer("int[]", self._info)

    def _onerror(self, exc, val, tb):
        # what escapes _evaluate is not a failure of f (those return 1, for the Python
        # loop to evaluate again and report): Ctrl-C in the user's func, an error of this
        # code; the C++ loop stops (1) and correct_plane raises it
        self.error = val
        return 1

    def _evaluate(self, rows, us, ps, prow, fs):
        n, npar = self.n, self._npar
        # fresh arrays for the user's func, as the Python loop gives it: one parameter
        # vector (broadcast by func_many) or the parameters point by point (columns of a
        # (NPAR, rows) array, the rows of which the user's func reads)
        U = np.frombuffer(ffi.buffer(us, 8 * rows * n), dtype=float).reshape(rows, n).copy()
        if prow:
            P = np.frombuffer(ffi.buffer(ps, 8 * rows * npar),
                              dtype=float).reshape(npar, rows).copy().T
        else:
            P = np.frombuffer(ffi.buffer(ps, 8 * npar), dtype=float).copy()
        try:
            F = self.problem.func_many(U, P)
        except Exception:
            return 1            # f failed: the Python loop evaluates it again and reports
        out = np.frombuffer(ffi.buffer(fs, 8 * rows * n), dtype=float).reshape(rows, n)
        out[...] = F
        return 0

    def _bind(self, npar: int) -> bool:
        """Ready f for a foreign call with PAR of length npar: a user file's FUNC (and
        DFDU) pointers bound to this run (CompiledUser.po_pointers); False before the
        file's first PVLS (CompiledUser.func_ready), where the Python loop calls it."""
        self._npar = npar
        if self._user is not None:
            if not self._user.func_ready:
                return False
            self._sfunc, jac = self._user.po_pointers(npar, ffi, "cont_po_sym_func",
                                                     "cont_po_sym_jac")
            self._sjac = jac if self.problem.has_dfdu else ffi.NULL
        self.error = None
        return True

    def _mesh_pointers(self, coll, mesh) -> tuple:
        """The pointers of the mesh's arrays (WT, WP, dtm, w_node) for the compiled calls,
        made once per mesh (every correction and Jacobian asks; ADAPT makes a new mesh
        every IAD points): kept while the arrays are the same objects (the kept tuple
        holds them, so an identity cannot be reused by another array)."""
        WT, WP, dtm, w_node = arrays = (coll.WT, coll.WP, mesh.dtm, coll.w_node)
        kept = self._mesh_kept
        if kept is None or kept[0][2] is not dtm or kept[0][3] is not w_node \
                or kept[0][0] is not WT or kept[0][1] is not WP:
            held = tuple(np.ascontiguousarray(a, dtype=float) for a in arrays)
            kept = self._mesh_kept = (arrays, tuple(reduction._ptr(a) for a in held), held)
        return kept[1]

    def correct_plane(self, x_pred, x_ref, t_ref, ds: float, counters):
        """(x, iterations) of the corrector from x_pred on the plane <x - x_ref,
        border(t_ref)> = ds; None when the Python loop is to take over. ConvergenceError
        as the Python loop raises it (divergence, ITNW exhausted). The evaluations are
        added to `counters` as the Python loop counts them."""
        sysm, s = self.sys, self.s
        self.newton = None
        coll, mesh = sysm.coll, sysm.mesh
        N, m, n = mesh.ntst, mesh.ncol, self.n
        par = np.ascontiguousarray(sysm.par, dtype=float)
        if not self._bind(len(par)):
            return None
        nx = coll.n_x
        row = np.ascontiguousarray(sysm.border(t_ref), dtype=float)
        x_pred = np.ascontiguousarray(x_pred, dtype=float)
        x_ref = np.ascontiguousarray(x_ref, dtype=float)
        U_old = np.ascontiguousarray(sysm.U_old, dtype=float)
        up_old = np.ascontiguousarray(sysm.up_old, dtype=float)
        bc = sysm.bc_offset()
        bc = (ffi.NULL if bc is None
              else ffi.from_buffer("double[]", np.ascontiguousarray(bc, float)))
        WT, WP, dtm, w_node = self._mesh_pointers(coll, mesh)
        fac = reduction.new_handle((N, m, n, 2))
        x, x_J = np.empty(nx), np.empty(nx)
        vals = np.empty(coll.nnz)
        P0, P1 = np.zeros((n, n)), np.zeros((n, n))
        p = reduction._ptr
        self.error = None
        status = lib.cont_po_correct(
            fac, self._cb, self._sfunc, self._sjac, self._npar_jp, numpy_ddot(), N, m, n,
            len(par), sysm.free[1] - 1, sysm.free[0] - 1, WT, WP, dtm, w_node,
            p(U_old), p(up_old), bc, p(par), p(x_pred), p(x_ref), p(row), float(ds), s.EPSL,
            s.EPSU, s.ITNW, s.NWTN, self.divergence, FD_STEP, bvp.FU_FP_ONE_CALL_MAX, p(x),
            p(x_J), p(vals), p(P0), p(P1), self._info_ptr)
        if self.error is not None:
            err, self.error = self.error, None
            raise err
        if status in (3, 4):
            return None
        it, it_J, residuals, jacobians = self._info.tolist()
        counters.residuals += residuals
        counters.jacobians += jacobians
        counters.factorisations += jacobians
        # what the Python loop leaves (also when it fails): the last Jacobian
        # (PeriodicOrbits.jacobian's `_last_blocks`), its factorisation with the Floquet
        # pair (CollocationBVP.factor's `_reduced`)
        J = coll.jacobian_from_values(vals)
        factor = reduction.BorderedCollocation.adopt(
            fac, (N, m, n, 2), P0, P1, dense=lambda: coll.bordered(J, row))
        # held by nobody else: the system's next factorisation of this J with another
        # border (the tangent at the converged point) re-borders it in place
        # (CollocationBVP.factor)
        factor.reborderable = True
        sysm._reduced = (J, factor)
        blocks = vals[:N * m * n * (m + 1) * n].reshape(N, m * n, (m + 1) * n)
        sysm._last_blocks = (x_J, blocks, J)
        if status == 1:
            raise ConvergenceError("Newton iterates diverge")
        if status == 2:
            raise ConvergenceError(f"no convergence in ITNW = {s.ITNW} iterations")
        if it_J == it:
            self.newton = (x, J)
        return x, it

    def jacobian_at(self, x):
        """PeriodicOrbits.jacobian(x) in one foreign call (cont_po_jacobian: the values
        of an iteration of the corrector at x, f evaluated as the Python Jacobian
        evaluates it), with the system's `_last_blocks` as it leaves them; None where
        the system's own is to be evaluated (f failing there, or not yet callable).
        The point a Jacobian serves after chord iterations, and the trials of a
        location, take it; the corrector's last one reaches the converged point through
        `newton`."""
        sysm = self.sys
        coll, mesh = sysm.coll, sysm.mesh
        par = np.ascontiguousarray(sysm.par, dtype=float)
        if not self._bind(len(par)):
            return None
        N, m, n = mesh.ntst, mesh.ncol, self.n
        x = np.ascontiguousarray(x, dtype=float)
        vals = np.empty(coll.nnz)
        p = reduction._ptr
        WT, WP, dtm, w_node = self._mesh_pointers(coll, mesh)
        status = lib.cont_po_jacobian(
            self._cb, self._sfunc, self._sjac, self._npar_jp, N, m, n, len(par),
            sysm.free[1] - 1, sysm.free[0] - 1, WT, WP, dtm, w_node,
            p(np.ascontiguousarray(sysm.up_old, float)), p(par), p(x), FD_STEP,
            bvp.FU_FP_ONE_CALL_MAX, p(vals))
        if self.error is not None:
            err, self.error = self.error, None
            raise err
        if status != 0:
            return None
        J = coll.jacobian_from_values(vals)
        blocks = vals[:N * m * n * (m + 1) * n].reshape(N, m * n, (m + 1) * n)
        sysm._last_blocks = (x.copy(), blocks, J)
        return J


def periodic_corrector(system, settings, divergence: float):
    """The compiled corrector of a PeriodicOrbits `system`, or None where the Python loop
    runs: other systems, the Python factorisation (bvp.COMPILED_FACTOR off), a Python
    file's Jacobians in use, f evaluated with its Jacobians (func_dfdu_batch)."""
    from washer.cont.user_problem.user_files_native import CompiledProblem
    from washer.cont.user_problem.user_files_sympy import SymbolicProblem
    from washer.cont.systems.periodic import PeriodicOrbits
    problem = getattr(system, "problem", None)
    if type(system) is not PeriodicOrbits or not bvp.COMPILED_FACTOR \
            or not isinstance(problem, Problem) or system.arclength != "plane":
        return None
    coll = system.coll
    if coll.general_bc or coll.nint != 1 or coll.npar != 2 or len(system.free) != 2 \
            or len(system.par) < 11 or problem.has_func_dfdu_batch or problem.has_dfdp_batch:
        return None
    if type(problem) is SymbolicProblem:
        # the generated f, with differences or (JAC != 0) the generated f_u
        generated = problem.generated
        if len(system.par) < generated.npar:
            return None
        return PeriodicCorrector(system, settings, divergence, generated)
    if isinstance(problem, CompiledProblem) and not getattr(problem, "two_ways", False):
        # (a traced Python file with a power numpy computes otherwise on arrays calls
        # back below: its func_many chooses FUNC's mode as the Python problem would)
        # FUNC by pointer; f_u by differences (JAC = 0) or the user's DFDU (JAC != 0),
        # f_p by differences either way, as the Python loop (VectorField.fu_fp: the
        # bridge gives no batched DFDP)
        if len(system.par) < getattr(problem, "npar_used", 0):
            return None               # a traced file's FUNC reads PAR beyond the run's
        if problem.user.po_pointers(len(system.par), ffi, "cont_po_sym_func",
                                    "cont_po_sym_jac") is None:
            return None
        return PeriodicCorrector(system, settings, divergence, user=problem.user)
    if not problem.differenced_jacobian:
        return None
    return PeriodicCorrector(system, settings, divergence)
