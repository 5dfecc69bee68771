"""The corrector of algebraic continuation in one foreign call per point.

    corrector = compiled_corrector(system, settings, DIVERGENCE_FACTOR)   # or None
    result = corrector.correct(x_pred, x_ref, ds, counters)    # (x, iterations) or None

This is the compiled form of the package's one Newton loop (washer.cont.newton.newton as
washer.cont.iterator.Continuation.correct runs it on the sphere arclength): the same
iteration (the system's residual and Jacobian: on equilibria f(u, PAR) and the central
differences [f_u, f_PAR(ICP(1))] of Problem.jacobian with the same points and quotients;
on the fold and Hopf loci, ISW = 2, the extended systems of washer/cont/systems/fold.py
and hopf.py, their f_u and f_PAR by the same differences, the derivatives of A = f_u by
Problem.second_derivatives' mixed differences; the bordered matrix [J; 2 theta (x -
x_ref) / |ds|], x += dx) and the same stopping test (AUTO's EPSL on the principal
parameter, EPSU on the other unknowns, the divergence test of Continuation.correct),
written once in C (washer/cont/include/ae_correct.h). At the converged point the same
call evaluates the Jacobian there, which the continuation reads next (jacobian_at: the
tangent's system and the test functions); the tangent itself is solved in Python with
LAPACK (Continuation.tangent), as on every other system. The corrections' linear solves
are Gaussian elimination with partial pivoting (LAPACK's pivot order; the rounding may
differ from LAPACK's in the last bit, far inside EPSU), the small products of the loci
plain sums (BLAS may round them otherwise).

f is evaluated by
* compiled AUTO user files (washer.cont.user_problem.user_files_native): the C is part of the
* file's bridge
  (user_files_bridge.c) and calls FUNC directly;
* equations in Python (NAME.py with func): washer/cont/ae_callback.c, compiled on first
  use, calls back into Python once per Newton iteration (twice on the loci: f_u first,
  then the second differences along vectors made of it), where the user's func is called
  point by point (or in one batch) exactly as the Python loop calls it: the same values;
  on equilibria with the user's Jacobians (JAC = 1: dfdu and dfdp; JAC = -1: dfdu and
  the differenced f_PAR), twice: Problem.jacobian, then func at the iterate;
* equations as sympy expressions (washer.cont.user_problem.user_files_sympy):
* washer/cont/ae_generated.c,
  compiled on first use, calls the generated C's f (a stencil's points in one call, as
  the Python loop's func_many) and, with JAC = 1, its exact f_u and f_p (as the Python
  loop's Problem.jacobian) through C function pointers.

It applies to systems that declare their equations the problem's f itself (IPS 0, 1:
EquilibriumSystem.residual_is_func, one free parameter; FixedPoints, f^k - u, does not;
the loci FoldSystem and HopfSystem by compiled_system, two free parameters; those of
maps do not), with the sphere arclength, and difference Jacobians (JAC = 0, or no
Jacobian given) or, on equilibria, a sympy problem's exact ones (JAC = 1) or a Python
problem's own (JAC = 1, -1). Everything
else, and every case the compiled loop does not finish cleanly (a failing or non-finite
f, a non-finite Jacobian or correction, a zero pivot: the Python loop then repeats the
correction and reports or resolves it as before), is the Python loop.
`compiled_corrector` makes the choice, in one place, once per run (Continuation's set-up
calls it; Continuation.correct then uses the corrector it returned).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from washer.cont.user_problem.c_library import CompileError
from washer.cont.differences import FD_STEP
from washer.cont.newton import ConvergenceError
from washer.cont.linalg import all_finite
from washer.cont.problem import SECOND_STEP, VECTORISE_MIN

#: Sizes up to which the dense corrector is used (beyond it the work is the Jacobian's,
#: and numpy's LAPACK is the better solver).
MAX_NDIM = 50

HERE = Path(__file__).parent
_CALLBACK_CDEF = """
typedef int (*ae_callback)(int stage, int rows, int first, const double *us,
                           const double *ps, double *fs);
int washer_ae_correct_cb(ae_callback callback, int exact, int kind, int ndim, int npar,
                         int ip, int ip2, const double *par, const double *v_old,
                         const double *x_pred, const double *x_ref, const double *theta,
                         double ds, double epsl, double epsu, int itnw, double divergence,
                         double hmach, double h2, double *x, int *iterations, double *jac,
                         double *work);
size_t washer_ae_work_size(int kind, int ndim, int npar);
int washer_ae_l1_cb(ae_callback callback, int ndim, int npar, const double *x,
                    const double *par, double omega, const double *A, double *l1,
                    double *work);
size_t washer_ae_l1_work_size(int ndim, int npar);
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
                          double *work);
"""
#: (ffi, lib) of ae_callback.c and ae_generated.c once built and loaded in this process
_libraries: dict = {}
#: Why one of them could not be built or loaded in this process (CompileError, OSError),
#: raised again instead of compiling again at every run's start.
_failures: dict = {}
#: ae_correct.h's systems (AE_EQUILIBRIUM, AE_FOLD, AE_HOPF) by the name a system declares
#: (EquilibriumSystem.residual_is_func; FoldSystem, HopfSystem.compiled_system).
KINDS = {"equilibrium": 0, "fold": 1, "hopf": 2}


def sizes(kind: int, n: int) -> tuple[int, int, int]:
    """ae_sizes: (unknowns nx, difference directions k1, second-difference vectors m2)."""
    nx = 2 * n + 3 if kind == 2 else 2 * n + 2 if kind == 1 else n + 1
    return nx, (n + 1 if kind == 0 else n + 2), (3 if kind == 2 else 1 if kind == 1 else 0)


def stage_rows(kind: int, n: int) -> tuple[int, int]:
    """The rows of ae_correct.h's two stages of f: (r1 = the point and the first
    differences, r2 = the second differences of the loci)."""
    _, k1, m2 = sizes(kind, n)
    return 2 * k1 + 1, 4 * k1 * m2


def work_size(kind: int, n: int, npar: int) -> int:
    """ae_work_size: the doubles of the corrector's work array."""
    nx, k1, m2 = sizes(kind, n)
    r1, r2 = stage_rows(kind, n)
    return ((r1 + r2) * (2 * n + npar) + nx * nx + 2 * nx + npar + 2 * k1 + m2 * (1 + n)
            + k1 * m2 * n + n * k1 + n)


#: ae_lyapunov.h's AE_L1_ROWS: the rows of its larger batch of f (normal_form's second
#: stage: f at x and 12 directions times 4 offsets).
L1_ROWS = 49


def l1_work_size(n: int, npar: int) -> int:
    """ae_l1_work_size: the doubles of ae_first_lyapunov's work array."""
    return L1_ROWS * (2 * n + npar) + 2 * (n * n + 6 * n) + n * n + 40 * n


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
        from washer.cont.user_problem.c_library import build_library, declarations, source_file
        from washer.cont.user_problem.user_files_native import INCLUDE
        ffi = declarations(cdef, Path(source).stem)
        try:
            path = build_library([source_file(HERE / source)], Path(source).stem,
                                 includes=[INCLUDE])
            _libraries[source] = (ffi, ffi.dlopen(str(path)))
        except (CompileError, OSError) as exc:
            _failures[source] = exc
            raise
    return _libraries[source]


class GeneratedEquations:
    """The generated C of a sympy problem (washer.cont.user_problem.user_files_sympy) behind
    ae_generated.c:
    its washer_sym_func and (JAC = 1) washer_sym_jac passed as C function pointers, so
    the corrector calls them directly, as the Python loop calls them through
    Problem.func, func_many (the stencil in one call) and Problem.jacobian's dfdu and
    dfdp: the same values."""

    func_ready = True

    def __init__(self, compiled, ndim: int, exact: bool):
        self.ffi, self.lib = _library("ae_generated.c", _GENERATED_CDEF)
        ffi = self.ffi
        self._jwork = np.empty(ndim * (ndim + max(compiled.npar, 1)))
        g = self._g = ffi.new("ae_generated *")
        g.func = compiled.pointer("washer_sym_func", ffi, "ae_sym_func")
        g.jac = compiled.pointer("washer_sym_jac", ffi, "ae_sym_jac") if exact else ffi.NULL
        g.npar_sym = compiled.npar
        g.jwork = ffi.from_buffer("double[]", self._jwork)
        self._keep = compiled           # the library stays loaded while the pointers live

    def ae_binder(self, kind, ndim, npar, ip, ip2, arrays):
        """washer_ae_correct_gen bound to the corrector's arrays (CompiledUser.ae_binder);
        equilibria only (kind 0)."""
        if kind != 0:
            raise ValueError("the generated equations' corrector is that of equilibria")
        ffi = self.ffi
        p = {k: (ffi.from_buffer("int[]", a) if k == "iterations"
                 else ffi.from_buffer("double[]", a)) for k, a in arrays.items()}
        lib, g = self.lib, self._g

        def call(ds, epsl, epsu, itnw, divergence, hmach, h2) -> int:
            return lib.washer_ae_correct_gen(
                g, ndim, npar, ip, p["par"], p["x_pred"], p["x_ref"], p["theta"], ds, epsl,
                epsu, itnw, divergence, hmach, p["x"], p["iterations"], p["jac"], p["work"])
        return call


class PythonEquations:
    """The user's Python func behind ae_callback.c: f at the rows of the corrector's
    points, as the Python loop evaluates them (stage 0: the point itself and Problem.
    jacobian's stencil, one Problem.func_many call for them all where they are fewer than
    VECTORISE_MIN, else the point by Problem.func and the stencil by Problem.func_many,
    or one call of func per point where Problem.stencil_by_calls says so; stage 1, the
    loci's second differences: Problem.func_many, as Problem.second_derivatives; stage 2,
    the first Lyapunov coefficient's differences: Problem.func_many, as normal_form.
    _directional; with the user's Jacobians on equilibria (`exact`), stage 0 of one row,
    f at the iterate by Problem.func, and stage 3, [f_u, f_PAR(ICP(1))] there by Problem.
    jacobian into the first NDIM (NDIM + 1) values of stage 0's fs). func_many
    calls a func on the arrays of a small stencil where it gives separate calls' values
    bit for bit (washer.cont.pointwise), so every route gives the Python loop's values."""

    func_ready = True

    def __init__(self, problem, ndim: int, npar: int, kind: int = 0, free=None):
        self.problem, self.n, self.npar, self.kind = problem, ndim, npar, kind
        # the user's Jacobians (JAC = 1, -1; equilibria): Problem.jacobian in the free
        # parameter `free` (1-based ICP(1)), as EquilibriumSystem.jacobian calls it
        self.exact = kind == 0 and not problem.differenced_jacobian
        self.free = list(free) if free is not None else None
        # the free parameters differenced with u: one for equilibria, two on the loci
        self.m = 1 if kind == 0 else 2
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

    def _evaluate(self, stage, rows, first, us, ps, fs):
        # the points are in the corrector's work array, read through numpy views of it
        # made once (ae_binder: ae_correct.h's layout, each stage's us, ps, fs one after
        # the other); a C that passes other pointers or another number of rows fails
        # loudly (three pointer comparisons a call)
        if stage not in (0, 1, 2, 3) or stage == 1 and self.kind == 0 \
                or stage == 2 and self.kind != 2 or stage == 3 and not self.exact:
            raise WorkLayoutError(f"ae_correct.h asked for stage {stage} of f, which "
                                  "corrector_algebraic.PythonEquations does not know")
        slot = 0 if stage == 3 else stage   # stage 3 writes into stage 0's views
        U, P, F = self._views[slot]
        where, n = self._where[slot], self.n
        one = stage == 3 or stage == 0 and self.exact
        if us != where[0] or ps != where[1] or fs != where[2] or \
                not (rows == U.shape[0] or stage == 2 and 0 < rows <= U.shape[0]
                     or one and rows == 1 and first == 0):
            raise WorkLayoutError(
                "ae_correct.h passed points outside the views of its work array that "
                "corrector_algebraic.PythonEquations reads (the layouts differ)")
        problem = self.problem
        if one:
            # the user's Jacobian and f at the iterate, each by its own call as the
            # Python loop makes them (EquilibriumSystem.jacobian, residual), on fresh
            # copies of the point
            try:
                if stage == 3:
                    F.reshape(-1)[:n * (n + 1)] = problem.jacobian(
                        U[0].copy(), P[0].copy(), self.free).reshape(-1)
                else:
                    F[0] = problem.func(U[0].copy(), P[0].copy())
            except Exception:
                return 1    # f or the Jacobian failed: the Python loop evaluates and reports
            return 0
        if stage == 2:                      # a batch of up to L1_ROWS rows
            U, P, F = U[:rows], P[:rows], F[:rows]
        # fresh copies: every call of func gets arrays of its own, as in the Python loop
        U, P = U.copy(), P.copy()
        if stage:
            try:
                F[:] = problem.func_many(U, P)      # Problem.second_derivatives' one call
            except Exception:
                return 1
            return 0
        try:
            if not problem.stencil_by_calls(self.m) and rows - first < VECTORISE_MIN:
                # the point and its stencil in one small batch (the point's own value
                # is the one its separate call gives: func_many's rule for them)
                F[first:] = problem.func_many(U[first:], P[first:])
                return 0
            if first == 0:
                F[0] = problem.func(U[0], P[0])
            if problem.stencil_by_calls(self.m):
                fn = problem.user_func
                S = np.array([fn(U[r], P[r]) for r in range(1, rows)], dtype=float)
                if S.shape != (rows - 1, n) or not all_finite(S):
                    return 1
            else:
                S = problem.func_many(U[1:], P[1:])
            F[1:] = S
        except Exception:
            return 1            # f failed: the Python loop evaluates it again and reports
        return 0

    def ae_binder(self, kind, ndim, npar, ip, ip2, arrays):
        """washer_ae_correct_cb bound to the corrector's arrays (CompiledUser.ae_binder)."""
        ffi, d = self.ffi, self._dptr_type
        p = {k: (ffi.from_buffer("int[]", a) if k == "iterations" else ffi.from_buffer(d, a))
             for k, a in arrays.items()}
        lib, cb, exact = self.lib, self._cb, int(self.exact)
        w, work = arrays["work"], p["work"]
        views, where, start = [], [], 0
        for rows in stage_rows(kind, ndim):
            a, b, c = start + rows * ndim, start + rows * (ndim + npar), \
                start + rows * (2 * ndim + npar)
            views.append((w[start:a].reshape(rows, ndim), w[a:b].reshape(rows, npar),
                          w[b:c].reshape(rows, ndim)))
            where.append((work + start, work + a, work + b))
            start = c
        self._views, self._where = views + [None], where + [None]

        def call(ds, epsl, epsu, itnw, divergence, hmach, h2) -> int:
            self.error = None
            return lib.washer_ae_correct_cb(
                cb, exact, kind, ndim, npar, ip, ip2, p["par"], p["v_old"], p["x_pred"], p["x_ref"],
                p["theta"], ds, epsl, epsu, itnw, divergence, hmach, h2, p["x"],
                p["iterations"], p["jac"], p["work"])
        return call


    def l1_binder(self, ndim, npar, arrays):
        """washer_ae_l1_cb bound to the arrays x, par, A, l1, work (CompiledUser.l1_binder);
        stage 2's views are those of `work`."""
        ffi, d = self.ffi, self._dptr_type
        p = {k: ffi.from_buffer(d, a) for k, a in arrays.items()}
        lib, cb = self.lib, self._cb
        w, work, rows = arrays["work"], p["work"], L1_ROWS
        a, b, c = rows * ndim, rows * (ndim + npar), rows * (2 * ndim + npar)
        self._views[2] = (w[:a].reshape(rows, ndim), w[a:b].reshape(rows, npar),
                          w[b:c].reshape(rows, ndim))
        self._where[2] = (work + 0, work + a, work + b)

        def call(omega) -> int:
            self.error = None
            return lib.washer_ae_l1_cb(cb, ndim, npar, p["x"], p["par"], omega, p["A"],
                                       p["l1"], p["work"])
        return call


class CompiledCorrector:
    """washer_ae_correct of one run's compiled problem (see the module's docstring)."""

    def __init__(self, system, settings, divergence: float, equations, kind: int = 0):
        self.sys, self.s, self.divergence = system, settings, divergence
        self.user = equations           # CompiledUser or PythonEquations
        self.kind = kind
        n = system.ndim
        self.npar = len(system.par)
        nx = sizes(kind, n)[0]
        # the arrays the C reads and writes, bound once (their addresses stay)
        self.a = dict(par=np.empty(self.npar), v_old=np.zeros(n), x_pred=np.empty(nx),
                      x_ref=np.empty(nx), theta=np.ascontiguousarray(system.theta, dtype=float),
                      x=np.empty(nx), iterations=np.zeros(1, dtype=np.int32),
                      jac=np.empty((nx - 1, nx)), work=np.zeros(work_size(kind, n, self.npar)))
        ip2 = system.free[1] - 1 if kind else -1
        self._call = equations.ae_binder(kind, n, self.npar, system.free[0] - 1, ip2, self.a)
        # the call's arguments after ds, the same at every correction (settings are frozen)
        self._fixed = (settings.EPSL, settings.EPSU, settings.ITNW, divergence, FD_STEP,
                       SECOND_STEP)
        self.last = None          # (x, the system's Jacobian at x) of the last point
        if kind == 2:
            # the first Lyapunov coefficient of the GH test in C (ae_lyapunov.h)
            self.l1a = dict(x=np.empty(n), par=np.empty(self.npar), A=np.empty((n, n)),
                            l1=np.zeros(1), work=np.zeros(l1_work_size(n, self.npar)))
            self._l1_call = equations.l1_binder(n, self.npar, self.l1a)

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
        if self.kind == 2:
            a["v_old"][:] = self.sys.v_old          # HopfSystem's phase condition
        a["x_pred"][:] = x_pred
        a["x_ref"][:] = x_ref
        status = self._call(float(ds), *self._fixed)
        err = getattr(user, "error", None)
        if err is not None:
            # what stopped the call back and is not a failure of f (PythonEquations._onerror)
            user.error = None
            raise err
        self.last = None
        if status == 3:
            return None
        it = a["iterations"].item()
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
            self.last = (x, a["jac"].copy())
        return x, it

    def first_lyapunov(self, problem, x, p, omega: float, A=None) -> float:
        """normal_form.first_lyapunov(problem, x, p, omega, A) computed in C with the
        corrector's f (ae_lyapunov.h: the same stencils and formula; the values agree to
        rounding); where the C cannot finish (f failing, a singular solve) the Python
        function computes it, and reports as it does."""
        from washer.cont.normal_form import first_lyapunov
        user = self.user
        if A is None or problem is not self.sys.problem or not user.func_ready:
            return first_lyapunov(problem, x, p, omega, A)
        a = self.l1a
        a["x"][:] = x
        a["par"][:] = p
        a["A"][:] = A
        status = self._l1_call(float(omega))
        err = getattr(user, "error", None)
        if err is not None:
            user.error = None
            raise err
        if status != 0:
            return first_lyapunov(problem, x, p, omega, A)
        return float(a["l1"][0])

    def jacobian_at(self, x):
        """The system's Jacobian at x ([f_u, f_lambda] (NDIM, NDIM + 1) on equilibria, the
        loci's extended one) if x is the point the corrector has just converged to
        (computed there by the same differences as the system's jacobian: the same values
        to rounding), else None."""
        last = self.last
        if last is None:
            return None
        y = last[0]
        # (arrays of one shape: equal values as np.array_equal finds them, 0.0 == -0.0 and
        # NaN never equal, without its per-call overhead)
        if y is x or (y.tolist() == x.tolist() if type(x) is np.ndarray and x.shape == y.shape
                      else np.array_equal(y, x)):
            return last[1]
        return None


def compiled_corrector(system, settings, divergence: float):
    """The compiled corrector of `system`, or None where the Python loop runs: this one
    for equilibria and the fold and Hopf loci (the sphere arclength), corrector_periodic's for periodic
    orbits (its `plane` attribute True: Continuation.correct hands it the plane
    arclength's corrections). The branches of one run share its system and corrector."""
    problem = getattr(system, "problem", None)
    if getattr(system, "arclength", None) == "plane":
        # here: corrector_periodic brings the collocation code, which equilibria never use
        from washer.cont.corrector_periodic import periodic_corrector
        return periodic_corrector(system, settings, divergence)
    kept = getattr(system, "_compiled_corrector", None)
    if kept is not None and kept[0] is settings and kept[1] == divergence \
            and kept[2] is problem:
        # the branches of one run (BP switches) share their system: its corrector, without
        # the last point of the branch before (`jacobian_at`)
        kept[3].last = None
        return kept[3]
    corrector = _algebraic_corrector(system, settings, divergence, problem)
    if corrector is not None:
        system._compiled_corrector = (settings, divergence, problem, corrector)
    return corrector


def _algebraic_corrector(system, settings, divergence: float, problem):
    """compiled_corrector's choice on the sphere arclength (made once per system)."""
    from washer.cont.user_problem.user_files_native import CompiledProblem
    from washer.cont.problem import Problem
    from washer.cont.user_problem.user_files_sympy import SymbolicProblem
    name = "equilibrium" if getattr(system, "residual_is_func", False) else \
        getattr(system, "compiled_system", None)
    kind = KINDS.get(name)
    if kind is None or len(system.free) != (1 if kind == 0 else 2) \
            or system.arclength != "sphere" or not 0 < system.ndim <= MAX_NDIM \
            or not all(0 < i <= len(system.par) for i in system.free):
        return None
    traced = getattr(problem, "traced", False)
    if traced and (kind == 0 and not problem.differenced_jacobian
                   or problem.two_ways and problem.differenced_jacobian):
        # a Python file traced into C (washer.cont.user_problem.user_files_traced) with its own
        # Jacobians on
        # equilibria, or with a power numpy computes otherwise on a stencil's arrays
        # (with difference Jacobians: the Python file's loci with its own are the Python
        # loop): called back as the Python file's problem is (Problem.jacobian's traced
        # dfdu and dfdp, func_many's traced f in the mode of the Python problem's call)
        try:
            equations = PythonEquations(problem, system.ndim, len(system.par), kind,
                                        free=system.free)
        except (CompileError, OSError):
            return None
    elif isinstance(problem, CompiledProblem):
        # (a traced Python file differences its f as the Python file's problem does: the
        # user's Jacobians only where it has them)
        if not problem.differenced_jacobian or problem.has_func_dfdu_batch \
                or not hasattr(problem.user.lib, "washer_ae_correct") \
                or len(system.par) < getattr(problem, "npar_used", 0):
            return None
        equations = problem.user
    elif type(problem) is SymbolicProblem:
        # the generated f with differences (JAC = 0) or with its exact f_u and f_p
        # (JAC = 1; JAC = -1, exact f_u with differenced f_p, is the Python loop)
        # (equilibria: the loci of sympy problems are the Python loop)
        generated = problem.generated
        if kind or problem.jac not in (0, 1) or len(system.par) < generated.npar:
            return None
        try:
            equations = GeneratedEquations(generated, system.ndim, exact=problem.jac == 1)
        except (CompileError, OSError):
            return None
    elif type(problem) is Problem:
        # difference Jacobians of a plain func (Problem.jacobian's stencil; on the loci
        # Problem.second_derivatives' stencil of f, not the analytic Jacobians'), or on
        # equilibria the user's own (Problem.jacobian's dfdu and dfdp, called back)
        if kind and not problem.differenced_jacobian or problem.has_func_batch \
                or problem.has_func_dfdu_batch \
                or kind and getattr(problem, "_dfdu_batch", None) is not None \
                and problem.has_dfdp_batch:
            return None
        try:
            equations = PythonEquations(problem, system.ndim, len(system.par), kind,
                                        free=system.free)
        except (CompileError, OSError):
            # no C compiler, or the compiled callback cannot be built or loaded here
            # (cffi's dlopen raises OSError): the Python loop. Anything else is a bug.
            return None
    else:
        return None
    corrector = CompiledCorrector(system, settings, divergence, equations, kind)
    if kind == 2:
        system.lyapunov = corrector.first_lyapunov      # HopfSystem's GH test
    return corrector
