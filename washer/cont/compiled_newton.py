"""The corrector of algebraic continuation in one foreign call per point.

    corrector = compiled_corrector(system, settings, DIVERGENCE_FACTOR)   # or None
    result = corrector.correct(x_pred, x_ref, ds, counters)    # (x, iterations) or None

This is the compiled form of the package's one Newton loop (washer.cont.newton.newton as
washer.cont.iterator.Continuation.correct runs it on the sphere arclength): the same
iteration (the residual f(u, PAR), the central differences [f_u, f_PAR(ICP(1))] of
Problem.jacobian with the same points and quotients, the bordered matrix [J; 2 theta
(x - x_ref) / |ds|], x += dx) and the same stopping test (AUTO's EPSL on the parameter,
EPSU on the state, the divergence test of Continuation.correct), written once in C
(washer/cont/include/ae_correct.h). At the converged point the same call evaluates the
Jacobian there and solves the tangent system [J; theta secant] z = e_last with its
determinant (Continuation.tangent, the BP test). The linear solves are Gaussian
elimination with partial pivoting (LAPACK's pivot order; the rounding may differ from
LAPACK's in the last bit, far inside EPSU).

f is evaluated by
* compiled AUTO user files (washer.cont.compiled): the C is part of the file's bridge
  (compiled_shim.c) and calls FUNC directly;
* equations in Python (NAME.py with func): washer/cont/ae_callback.c, compiled on first
  use, calls back into Python once per Newton iteration, where the user's func is called
  point by point (or in one batch) exactly as the Python loop calls it: the same values;
* equations as sympy expressions (washer.cont.symbolic): washer/cont/ae_generated.c,
  compiled on first use, calls the generated C's f (a stencil's points in one call, as
  the Python loop's func_many) and, with JAC = 1, its exact f_u and f_p (as the Python
  loop's Problem.jacobian) through C function pointers.

It applies to systems that declare their residual the problem's f itself (IPS 0, 1:
EquilibriumSystem.residual_is_func; FixedPoints, f^k - u, does not), with one free
parameter and the sphere arclength, and difference Jacobians (JAC = 0, or no Jacobian
given) or a sympy problem's exact ones (JAC = 1). Everything else, and
every case the compiled loop does not finish cleanly (a failing or non-finite f, a
non-finite Jacobian or correction, a zero pivot: the Python loop then repeats the
correction and reports or resolves it as before), is the Python loop.
Continuation.correct makes the choice, in one place.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from washer.cont.compile import CompileError
from washer.cont.newton import ConvergenceError
from washer.cont.settings import HMACH

#: Sizes up to which the dense corrector is used (beyond it the work is the Jacobian's,
#: and numpy's LAPACK is the better solver).
MAX_NDIM = 50

HERE = Path(__file__).parent
_CALLBACK_CDEF = """
typedef int (*ae_callback)(int rows, int first, const double *us, const double *ps,
                           double *fs);
int washer_ae_correct_cb(ae_callback callback, int ndim, int npar, int ip, const double *par,
                         const double *x_pred, const double *x_ref, const double *theta,
                         double ds, double epsl, double epsu, int itnw, double divergence,
                         double hmach, double *x, int *iterations, double *jac,
                         double *tangent, double *work);
"""
_GENERATED_CDEF = """
typedef void (*ae_sym_func)(int k, const double *U, const double *P, int pstride, double *F);
typedef void (*ae_sym_jac)(int k, const double *U, const double *P, int pstride, double *J,
                           double *Jp);
typedef struct {
    ae_sym_func func;
    ae_sym_jac jac;
    int npar_sym;
    double *jwork;
} ae_generated;
int washer_ae_correct_gen(ae_generated *g, int ndim, int npar, int ip, const double *par,
                          const double *x_pred, const double *x_ref, const double *theta,
                          double ds, double epsl, double epsu, int itnw, double divergence,
                          double hmach, double *x, int *iterations, double *jac,
                          double *tangent, double *work);
"""
#: (ffi, lib) of ae_callback.c and ae_generated.c once built and loaded in this process
_libraries: dict = {}
#: Why one of them could not be built or loaded in this process (CompileError, OSError),
#: raised again instead of compiling again at every run's start.
_failures: dict = {}
class WorkLayoutError(RuntimeError):
    """The pointers ae_correct.h passes to the call back are not where PythonEquations
    reads the points (its views of the work array): the two layouts have drifted apart.
    Raised by the correction, as every error of the call back that is not the user's
    func failing."""


def _library(source: str, cdef: str):
    """(ffi, lib) of the C file `source` beside this module (ae_generated.c), compiled
    on first use (cached by content); a build or load that failed once raises the same
    error again."""
    if source in _failures:
        raise _failures[source]
    if source not in _libraries:
        from cffi import FFI
        from washer.cont.compile import build_library, source_file
        from washer.cont.compiled import INCLUDE
        ffi = FFI()
        ffi.cdef(cdef)
        try:
            path = build_library([source_file(HERE / source)], Path(source).stem,
                                 includes=[INCLUDE])
            _libraries[source] = (ffi, ffi.dlopen(str(path)))
        except (CompileError, OSError) as exc:
            _failures[source] = exc
            raise
    return _libraries[source]


class GeneratedEquations:
    """The generated C of a sympy problem (washer.cont.symbolic) behind ae_generated.c:
    its washer_sym_func and (JAC = 1) washer_sym_jac passed as C function pointers, so
    the corrector calls them directly, as the Python loop calls them through
    Problem.func, func_many (the stencil in one call) and Problem.jacobian's dfdu and
    dfdp: the same values."""

    func_ready = True

    def __init__(self, compiled, ndim: int, exact: bool):
        self.ffi, self.lib = _library("ae_generated.c", _GENERATED_CDEF)
        ffi, src = self.ffi, compiled.ffi

        def pointer(fn, kind):
            return ffi.cast(kind, int(src.cast("uintptr_t", fn)))
        self._jwork = np.empty(ndim * (ndim + max(compiled.npar, 1)))
        g = self._g = ffi.new("ae_generated *")
        g.func = pointer(compiled.lib.washer_sym_func, "ae_sym_func")
        g.jac = pointer(compiled.lib.washer_sym_jac, "ae_sym_jac") if exact else ffi.NULL
        g.npar_sym = compiled.npar
        g.jwork = ffi.from_buffer("double[]", self._jwork)
        self._keep = compiled           # the library stays loaded while the pointers live

    def ae_binder(self, ndim, npar, ip, arrays):
        """washer_ae_correct_gen bound to the corrector's arrays (CompiledUser.ae_binder)."""
        ffi = self.ffi
        p = {k: (ffi.from_buffer("int[]", a) if k == "iterations"
                 else ffi.from_buffer("double[]", a)) for k, a in arrays.items()}
        lib, g = self.lib, self._g

        def call(ds, epsl, epsu, itnw, divergence, hmach) -> int:
            return lib.washer_ae_correct_gen(
                g, ndim, npar, ip, p["par"], p["x_pred"], p["x_ref"], p["theta"], ds, epsl,
                epsu, itnw, divergence, hmach, p["x"], p["iterations"], p["jac"],
                p["tangent"], p["work"])
        return call


class PythonEquations:
    """The user's Python func behind ae_callback.c: f at the rows of the corrector's
    points, as the Python loop evaluates them (Problem.func at the point itself, then
    Problem.jacobian's stencil: one call per point below VECTORISE_MIN points, else
    Problem.func_many)."""

    func_ready = True

    def __init__(self, problem, ndim: int, npar: int):
        self.problem, self.n, self.npar = problem, ndim, npar
        self.by_calls = problem.stencil_by_calls(1)     # one free parameter
        self.ffi, self.lib = _library("ae_callback.c", _CALLBACK_CDEF)
        self.error = None
        self._cb = self.ffi.callback("ae_callback", self._evaluate, onerror=self._onerror)
        self._dptr_type = self.ffi.typeof("double[]")
        self._views = None
        self._where = None           # (us, ps, fs) pointers the views start at

    def _onerror(self, exc, val, tb):
        # Whatever escapes _evaluate is not a failure of f (those it returns as 1, for
        # the Python loop to evaluate again and report): Ctrl-C (KeyboardInterrupt) in
        # the user's func, SystemExit, a WorkLayoutError, an error of this code. The C
        # corrector is stopped (1: as a failed evaluation) and the correction raises it.
        self.error = val
        return 1

    def _evaluate(self, rows, first, us, ps, fs):
        # the points are in the corrector's work array, read through numpy views of it
        # made once (ae_binder: ae_correct.h's layout, us, ps, fs at its start); a C
        # that passes other pointers or another number of rows fails loudly (three
        # pointer comparisons a call)
        U, P, F = self._views
        where, n = self._where, self.n
        if us != where[0] or ps != where[1] or fs != where[2] or rows != U.shape[0]:
            raise WorkLayoutError(
                "ae_correct.h passed points outside the views of its work array that "
                "compiled_newton.PythonEquations reads (the layouts differ)")
        # fresh copies: every call of func gets arrays of its own, as in the Python loop
        U, P = U.copy(), P.copy()
        problem = self.problem
        try:
            if first == 0:
                F[0] = problem.func(U[0], P[0])
            if self.by_calls:
                fn = problem.user_func
                S = np.array([fn(U[r], P[r]) for r in range(1, rows)], dtype=float)
                if S.shape != (rows - 1, n) or not np.isfinite(S).all():
                    return 1
            else:
                S = problem.func_many(U[1:], P[1:])
            F[1:] = S
        except Exception:
            return 1            # f failed: the Python loop evaluates it again and reports
        return 0

    def ae_binder(self, ndim, npar, ip, arrays):
        """washer_ae_correct_cb bound to the corrector's arrays (CompiledUser.ae_binder)."""
        ffi, d = self.ffi, self._dptr_type
        p = {k: (ffi.from_buffer("int[]", a) if k == "iterations" else ffi.from_buffer(d, a))
             for k, a in arrays.items()}
        lib, cb = self.lib, self._cb
        rows, w = 2 * ndim + 3, arrays["work"]
        self._views = (w[:rows * ndim].reshape(rows, ndim),
                       w[rows * ndim:rows * (ndim + npar)].reshape(rows, npar),
                       w[rows * (ndim + npar):rows * (2 * ndim + npar)].reshape(rows, ndim))
        work = p["work"]
        self._where = (work + 0, work + rows * ndim, work + rows * (ndim + npar))

        def call(ds, epsl, epsu, itnw, divergence, hmach) -> int:
            self.error = None
            return lib.washer_ae_correct_cb(
                cb, ndim, npar, ip, p["par"], p["x_pred"], p["x_ref"], p["theta"], ds, epsl,
                epsu, itnw, divergence, hmach, p["x"], p["iterations"], p["jac"],
                p["tangent"], p["work"])
        return call


class CompiledCorrector:
    """washer_ae_correct of one run's compiled problem (see the module's docstring)."""

    def __init__(self, system, settings, divergence: float, equations):
        self.sys, self.s, self.divergence = system, settings, divergence
        self.user = equations           # CompiledUser or PythonEquations
        n = system.ndim
        self.npar = len(system.par)
        k = n + 1
        # the arrays the C reads and writes, bound once (their addresses stay)
        self.a = dict(par=np.empty(self.npar), x_pred=np.empty(n + 1), x_ref=np.empty(n + 1),
                      theta=np.ascontiguousarray(system.theta, dtype=float),
                      x=np.empty(n + 1), iterations=np.zeros(1, dtype=np.int32),
                      jac=np.empty((n, n + 1)), tangent=np.empty(3 * (n + 1) + 3),
                      work=np.zeros((2 * k + 1) * (2 * n + self.npar) + (n + 1) * (n + 4)))
        self._call = equations.ae_binder(n, self.npar, system.free[0] - 1, self.a)
        self.last = None          # (x, [f_u, f_lambda] at x, tangent data) of the last point

    def correct(self, x_pred, x_ref, ds: float, counters):
        """(x, iterations) of the corrector from x_pred on the sphere of radius |ds|
        about x_ref; None when the Python loop is to take over. ConvergenceError as the
        Python loop raises it (divergence, ITNW exhausted). The evaluations are added
        to `counters` (washer.cont.branch.Counters) as the Python loop counts them."""
        user, s = self.user, self.s
        if not user.func_ready:
            return None
        a = self.a
        a["par"][:] = self.sys.par
        a["x_pred"][:] = x_pred
        a["x_ref"][:] = x_ref
        status = self._call(float(ds), s.EPSL, s.EPSU, s.ITNW, self.divergence, HMACH)
        err = getattr(user, "error", None)
        if err is not None:
            # what stopped the call back and is not a failure of f (PythonEquations._onerror)
            user.error = None
            raise err
        self.last = None
        if status == 3:
            return None
        it = int(a["iterations"][0])
        c = counters
        c.residuals += it
        c.jacobians += it
        c.factorisations += it
        if status == 1:
            raise ConvergenceError("Newton iterates diverge")
        if status == 2:
            raise ConvergenceError(f"no convergence in ITNW = {s.ITNW} iterations")
        x = a["x"].copy()
        if status == 0:
            t = a["tangent"]
            self.last = (x, a["jac"].copy(), t.copy() if t[-1] == 1.0 else None)
        return x, it

    def jacobian_at(self, x):
        """[f_u, f_lambda] (NDIM, NDIM + 1) at x if x is the point the corrector has just
        converged to (computed there by the same differences as Problem.jacobian: the
        same values), else None."""
        last = self.last
        if last is not None and (last[0] is x or np.array_equal(last[0], x)):
            return last[1]
        return None

    def tangent_system(self, J, ref):
        """(z, factor) of Continuation.tangent's system [J; theta ref] z = e_last if J is
        the Jacobian of the point just converged to and ref its secant (x - x_ref) / ds:
        solved in the same foreign call, the factor giving its determinant (the BP test)
        and solves with LAPACK if anything asks for more; else None."""
        last = self.last
        if last is None or last[2] is None or J is not last[1]:
            return None
        m = len(ref)
        t = last[2]
        # the secant C stored, compared as Python floats (np.array_equal's overhead is
        # the larger part at these sizes; NaN equals nothing either way)
        if t[m:2 * m].tolist() != ref.tolist():
            return None
        return t[:m].copy(), _SolvedFactor(J, self.sys, ref.copy(), float(t[2 * m]),
                                           float(t[2 * m + 1]))


class _SolvedFactor:
    """The factor of [J; border(ref)] whose determinant the compiled corrector has
    computed: sign_logdet from it, solves (none on the continuation's path) with LAPACK."""

    def __init__(self, J, system, ref, sign, logdet):
        self.J, self._sys, self._ref, self._sign_logdet = J, system, ref, (sign, logdet)
        self._factor = None

    def sign_logdet(self) -> tuple[float, float]:
        return self._sign_logdet

    def solve(self, rhs):
        if self._factor is None:
            from washer.cont.linalg import dense_factor
            self._factor = dense_factor(self.J, self._sys.border(self._ref))
        return self._factor.solve(rhs)


def compiled_corrector(system, settings, divergence: float):
    """The compiled corrector of `system`, or None where the Python loop runs."""
    from washer.cont.compiled import CompiledProblem
    from washer.cont.problem import Problem
    from washer.cont.symbolic import SymbolicProblem
    problem = getattr(system, "problem", None)
    if not getattr(system, "residual_is_func", False) or len(system.free) != 1 \
            or system.arclength != "sphere" or not 0 < system.ndim <= MAX_NDIM:
        return None
    if isinstance(problem, CompiledProblem):
        if problem.jac != 0 or problem.has_func_dfdu_batch \
                or not hasattr(problem.user.lib, "washer_ae_correct"):
            return None
        equations = problem.user
    elif type(problem) is SymbolicProblem:
        # the generated f with differences (JAC = 0) or with its exact f_u and f_p
        # (JAC = 1; JAC = -1, exact f_u with differenced f_p, is the Python loop)
        generated = problem.generated
        if problem.jac not in (0, 1) or len(system.par) < generated.npar:
            return None
        try:
            equations = GeneratedEquations(generated, system.ndim, exact=problem.jac == 1)
        except (CompileError, OSError):
            return None
    elif type(problem) is Problem:
        # difference Jacobians of a plain func (Problem.jacobian's stencil)
        if not problem.differenced_jacobian or problem.has_func_batch \
                or problem.has_func_dfdu_batch:
            return None
        try:
            equations = PythonEquations(problem, system.ndim, len(system.par))
        except (CompileError, OSError):
            # no C compiler, or the compiled callback cannot be built or loaded here
            # (cffi's dlopen raises OSError): the Python loop. Anything else is a bug.
            return None
    else:
        return None
    return CompiledCorrector(system, settings, divergence, equations)
