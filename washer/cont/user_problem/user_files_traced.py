"""A Python user file's func (and its dfdu, dfdp) as compiled C, where that is what the
Python functions compute, bit for bit.

    problem = traced_problem(python_problem, path)   # a TracedProblem, or python_problem

washer.cont.user_problem.tracer records func (and dfdu, dfdp when the file has them) on
stand-ins and
writes AUTO's C user file of the same operations; it is compiled with washer's bridge
(user_files_bridge.c: the path of NAME.c user files, cached by content, with
-ffp-contract=off) and loaded as a compiled user file
(washer.cont.user_problem.user_files_native), so the
compiled correctors of equilibria, the fold and Hopf loci and periodic orbits call FUNC
directly. STPNT, PVLS, BCND, ICND and FOPT stay the Python file's.

A func with a power that numpy computes otherwise on numpy scalars than on arrays
(washer.cont.user_problem.tracer: `x ** 2` is libm's pow on a np.float64, x * x on an array) is
called in the mode the Python problem would have called it with: its `func_many` makes
Problem.func_many's choices (one point at a time; one call on arrays for a batch of
VECTORISE_MIN points and more, checked once against separate calls; one call on arrays
for a small stencil while washer.cont.pointwise's bitwise comparison with separate calls
holds), with the two modes of the compiled FUNC standing for the two kinds of calls, on
the same state objects. The compiled correctors then call back (corrector_algebraic's
PythonEquations, corrector_periodic's call back) instead of calling FUNC directly.

Trusted only where verified, byte for byte (the rule of washer.cont.pointwise: IEEE
arithmetic is the same whichever code runs it, so equal values are expected everywhere
and a single difference means the trace is not the function):
* on loading, at LOAD_POINTS points around the file's starting point (stpnt; random
  offsets of several sizes, a fixed seed): f (and the Jacobians) of the compiled FUNC
  against the Python functions called one point at a time;
* in every run, the first RUN_POINTS points whose f the run asks for through the
  problem (the start, the first Jacobians' stencils) and the first Jacobians.
A difference, or a Python function that traces to nothing honest (washer.cont.user_problem.tracer:
a branch on a value, an unknown function), and the problem is the Python one for good:
the call that showed the difference returns the Python values, the compiled correctors
hand the rest of the run to the Python loop (`func_ready` False) and later runs take the
Python problem (`with_jac`). Which path a problem took, and why, is its `route` (a note
of washer.run's verbose output).
"""
from __future__ import annotations

import copy
import functools
import hashlib
import os
import random
from pathlib import Path

import numpy as np

from washer.cont.linalg import all_finite
from washer.cont.pointwise import same_bits
from washer.cont.problem import (Problem, ProblemError, STENCIL_MIN, VECTORISE_CHECK,
                                 VECTORISE_MIN, broadcast_rows)
from washer.cont.user_problem.c_library import (CompileError, build_library, declarations,
                                                source_text)
from washer.cont.user_problem.tracer import (TraceError, emit_user_file, numpy_loop,
                                             trace_function)
from washer.cont.user_problem.user_files_native import (SHIM, INCLUDE, CompiledProblem,
                                                        CompiledUser)

#: The length of PAR the functions are traced with (AUTO's NPARX): a func reading
#: PAR beyond it is not traced.
TRACE_NPAR = 36
#: Points compared when the file is loaded (around its starting point).
LOAD_POINTS = 24
#: Points compared in each run (the first ones it evaluates through the problem).
RUN_POINTS = 32
#: Extra options of the C compiler: no fused multiply-add (x * y + z rounded twice, as
#: Python computes it).
FLAGS = ("-ffp-contract=off",)
#: What the bridge's cffi declarations lack: washer_traced_bind of the generated C.
_BIND_CDEF = """int washer_traced_bind(int k, void *const *loops, void *const *data);
void washer_traced_mode(int mode);"""
#: washer_traced_mode's modes (washer.cont.user_problem.tracer): func on numpy scalars (one
#point), on
#: arrays, on arrays whose par rows are one broadcast vector (row stride 0)
SCALARS, ARRAYS, ARRAYS_PAR_BROADCAST = 0, 1, 2

_FFI: list = []
#: library path -> its handle by _FFI (kept open: the loops bound stay bound)
_BOUND: dict = {}


class _Refused(Exception):
    """A compared call of a two-way FUNC differed: the call is made again in Python."""


class TraceState:
    """Whether a traced problem is still trusted (shared by its copies, `with_jac`), and
    what was said about its route."""

    __slots__ = ("off", "route")

    def __init__(self, route: str):
        self.off = False
        self.route = route

    def refuse(self, why: str) -> None:
        self.off = True
        self.route = f"func(u, par) in Python: {why}"


class TracedUser(CompiledUser):
    """The compiled FUNC of a traced file: ready while the trace is trusted."""

    def __init__(self, path, ndim, lib_path, state: TraceState):
        super().__init__(path, ndim, lib_path=lib_path)
        self.state = state
        self._pvls_seen = True         # the generated file's PVLS is empty
        self._modes = _BOUND[str(lib_path)]

    def func_in_mode(self, us, pars, mode: int) -> np.ndarray:
        """func_batch with FUNC's powers computed as numpy does in `mode` (SCALARS,
        ARRAYS, ARRAYS_PAR_BROADCAST); the mode is SCALARS again after the call."""
        self._modes.washer_traced_mode(mode)
        try:
            return self.func_batch(us, pars)
        finally:
            self._modes.washer_traced_mode(SCALARS)

    @property
    def func_ready(self) -> bool:
        return not self.state.off

    def reload(self) -> None:
        """Nothing: the generated FUNC keeps no state between calls (and its numpy loops
        stay bound)."""


class TracedProblem(CompiledProblem):
    """A Python file's problem whose func (and dfdu, dfdp) are compiled traces; its
    STPNT, PVLS, BCND, ICND and FOPT the Python file's. `python` is the Python problem
    it stands for."""

    #: a Python file's functions traced (washer.cont.corrector_algebraic asks)
    traced = True
    pvls = Problem.pvls
    bcnd = Problem.bcnd
    icnd = Problem.icnd
    icnd_many = Problem.icnd_many

    def __init__(self, user: TracedUser, python: Problem, npar_used: int,
                 two_ways: bool = False, arrays: bool = True, dfdp_traced: bool = True):
        self.user, self.python, self.state = user, python, user.state
        #: the file's dfdp is compiled (else the Python function)
        self.dfdp_traced = dfdp_traced
        self.npar_used = npar_used
        #: FUNC computes a power otherwise on numpy scalars and on arrays
        self.two_ways = two_ways
        #: the Python func can be called on arrays (else Problem.func_many never does)
        self.arrays = arrays
        py = python
        Problem.__init__(self, py.ndim, None, py._stpnt, name=py.name, npar=py.npar,
                         dfdu_batch=user.dfdu_batch if py._dfdu is not None else None,
                         pvls=py._pvls, bcnd=py._bcnd, icnd=py._icnd, fopt=py._fopt,
                         jac=py.jac)
        self._bind_checked()
        self._left = 0               # points still to compare in this run

    def _bind_checked(self) -> None:
        """f and the Jacobians through this object's compared calls (a copy's own)."""
        py = self.python
        self._func, self._func_batch = self._checked_func, self._checked_batch
        self._dfdu = self._checked_dfdu if py._dfdu is not None else None
        self._dfdp = self._checked_dfdp if py._dfdp is not None and self.dfdp_traced \
            else py._dfdp

    @property
    def route(self) -> str:
        return self.state.route

    def fresh(self) -> None:
        """A new run: its first RUN_POINTS points are compared again."""
        self._left = RUN_POINTS

    def with_jac(self, jac: int) -> Problem:
        """The problem of a run with AUTO's JAC = jac: this one (its first points
        compared again), or the Python problem once a difference was seen."""
        if self.state.off:
            return self.python.with_jac(jac)
        p = copy.copy(self)
        p.jac = jac
        p._left = RUN_POINTS
        p._bind_checked()
        return p

    # ------------------------------------------------- the Python problem's choices
    def func_many(self, us, pars) -> np.ndarray:
        """f at k points as Problem.func_many computes it; for a `two_ways` FUNC each call
        in the mode of the call Problem.func_many would make (the module's docstring)."""
        if self.two_ways and not self.state.off and not self._short_par(np.asarray(pars)):
            try:
                return self._as_python_calls(np.asarray(us, dtype=float),
                                             np.asarray(pars, dtype=float))
            except _Refused:
                pass                 # now the Python problem's: the call again by it
        pars = np.asarray(pars, dtype=float)
        if pars.ndim == 1 and not self.two_ways and self._func_batch is not None:
            # One PAR for every row, passed once (row stride 0, as the compiled correctors
            # pass it) instead of copied to each row by Problem.func_many: the generated
            # FUNC only reads PAR (the phase reference's f at the mesh nodes, every point).
            # The checked batch gives values of the right shape or raises ProblemError.
            return self._checked_batch(us, pars)
        return Problem.func_many(self, us, pars)

    def _as_python_calls(self, us, pars) -> np.ndarray:
        """Problem.func_many's choices (on this problem's `_vectorised` and `_pointwise`,
        as the Python problem keeps them) with the compiled FUNC in their modes."""
        k = len(us)
        if pars.ndim == 1:
            pars = broadcast_rows(pars, k)
        mode = ARRAYS_PAR_BROADCAST if k and pars.strides[0] == 0 else ARRAYS
        if self.arrays and k >= VECTORISE_MIN and self._vectorised is not False:
            # Problem._call_vectorised: its first call checked against separate calls
            out = self._in_mode(us, pars, mode)
            if self._vectorised is None:
                m = min(k, VECTORISE_CHECK)
                ref = self._in_mode(us[:m], pars[:m], SCALARS)
                if not all_finite(ref):
                    raise ProblemError(f"{self.name}: func(u, par) returned non-finite "
                                       "values")
                self._vectorised = bool(np.array_equal(ref, out[:m]) or np.allclose(
                    ref, out[:m], rtol=1e-14, atol=0))
            if self._vectorised:
                return out
        elif self.arrays and STENCIL_MIN <= k < VECTORISE_MIN and not self._pointwise.off:
            # Problem._call_stencil: compared with separate calls at check.rows(k)
            check = self._pointwise
            rows = check.rows(k)
            out = self._in_mode(us, pars, mode)
            if (rows is None or check.agree(self._in_mode(us[rows], pars[rows], SCALARS),
                                            out[rows], k)) and all_finite(out):
                return out
        out = self._in_mode(us, pars, SCALARS)
        if not np.isfinite(out).all():
            raise ProblemError(f"{self.name}: func(u, par) returned non-finite values")
        return out

    def _in_mode(self, us, pars, mode: int) -> np.ndarray:
        """The compiled FUNC at the rows us, pars in `mode`, the first points of a run
        compared with the Python func called as the mode says (separate calls, or one
        call on arrays with par's rows as given)."""
        out = self.user.func_in_mode(us, np.ascontiguousarray(pars), mode)
        m = min(self._left, len(us))
        if m <= 0:
            return out
        self._left -= m
        fn = self.python.user_func
        try:
            with np.errstate(all="ignore"):
                if mode == SCALARS:
                    ref = np.array(self._python_rows(fn, us[:m], pars[:m]), dtype=float)
                else:
                    ref = np.asarray(fn(us.T, pars.T), dtype=float).T[:m]
        except Exception:
            ref = None
        if ref is not None and same_bits(np.ascontiguousarray(ref), out[:m]):
            return out
        self.state.refuse("its compiled trace gave other values than func(u, par) at a "
                          "point of the run (compared bit for bit)")
        self._switch_to_python()
        raise _Refused()

    # ---------------------------------------------------------------- compared calls
    def _python_rows(self, fn, us, pars):
        return [np.asarray(fn(u.copy(), p.copy()), dtype=float) for u, p in zip(us, pars)]

    def _compare(self, got, fn, us, pars, what: str) -> np.ndarray | None:
        """Python's values where they differ from `got` (the compiled values at the rows
        us, pars; the first `_left` of them compared): None where they agree."""
        m = min(self._left, len(us))
        if m <= 0:
            return None
        self._left -= m
        try:
            ref = self._python_rows(fn, us[:m], pars[:m])
            ref = np.array(ref, dtype=float)
        except Exception:
            ref = None                       # the Python call raises: not the same
        if ref is not None and same_bits(ref, got[:m]):
            return None
        self.state.refuse(f"its compiled trace gave other values than {what} at a point "
                          "of the run (compared bit for bit)")
        self._switch_to_python()
        return ref

    def _switch_to_python(self) -> None:
        """The rest of this run on the Python functions (the compiled correctors see
        func_ready False and hand over to the Python loop)."""
        py = self.python
        self._func, self._dfdu, self._dfdp = py._func, py._dfdu, py._dfdp
        self._func_batch = self._dfdu_batch = None

    def _pars(self, us, pars):
        pars = np.asarray(pars, dtype=float)
        if pars.ndim == 1:
            pars = np.broadcast_to(pars, (len(us), len(pars)))
        return pars

    def _short_par(self, pars) -> bool:
        return pars.shape[-1] < self.npar_used

    def _checked_batch(self, us, pars) -> np.ndarray:
        us = np.asarray(us, dtype=float)
        if self.state.off or self._short_par(np.asarray(pars)):
            return self.python.func_many(us, pars)
        out = self.user.func_batch(us, pars)
        if self._left > 0:
            ref = self._compare(out, self.python.user_func, us, self._pars(us, pars),
                                "func(u, par)")
            if ref is not None or self.state.off:
                return self.python.func_many(us, pars)
        if len(us) < VECTORISE_MIN and not np.isfinite(out).all():
            # as the Python route reports it (func_many: point by point below
            # VECTORISE_MIN points)
            raise ProblemError(f"{self.name}: func(u, par) returned non-finite values")
        return out

    def _checked_func(self, u, par) -> np.ndarray:
        return self._checked_batch(np.asarray(u, dtype=float)[None, :], par)[0]

    def _checked_dfdu(self, u, par) -> np.ndarray:
        if self.state.off or self._short_par(np.asarray(par)):
            return self.python._dfdu(u, par)
        J = self.user.dfdu(u, par)
        if self._left > 0:
            u1, p1 = np.asarray(u, float)[None], np.asarray(par, float)[None]
            ref = self._compare(J[None], self.python._dfdu, u1, p1, "dfdu(u, par)")
            if ref is not None or self.state.off:
                return self.python._dfdu(u, par)
        return J

    def _checked_dfdp(self, u, par) -> np.ndarray:
        if self.state.off or self._short_par(np.asarray(par)):
            return self.python._dfdp(u, par)
        P = self.user.dfdp(u, par)
        if self._left > 0:
            ref = np.asarray(self.python._dfdp(np.array(u, float), np.array(par, float)),
                             dtype=float)
            self._left -= 1
            # the compiled DFDP has NPAR columns (zero beyond the Python's)
            if ref.ndim != 2 or not same_bits(ref, P[:, :ref.shape[1]]):
                self.state.refuse("its compiled trace gave other values than dfdp(u, par) "
                                  "at a point of the run (compared bit for bit)")
                self._switch_to_python()
                return ref
        return P


def _ffi():
    if not _FFI:
        _FFI.append(declarations(_BIND_CDEF, "traced_bind"))
    return _FFI[0]


def _bind(lib_path: Path, ufuncs: list) -> None:
    """numpy's double loops of `ufuncs` into the library's tables (washer_traced_bind),
    through a handle kept open (a reload of the file by another handle keeps them)."""
    ffi = _ffi()
    key = str(lib_path)
    if key not in _BOUND:
        _BOUND[key] = ffi.dlopen(key)
    loops = [numpy_loop(u) for u in ufuncs]
    k = max(len(loops), 1)
    fns = ffi.new("void *[]", [ffi.cast("void *", f) for f, _ in loops] or [ffi.NULL])
    data = ffi.new("void *[]", [ffi.cast("void *", d) for _, d in loops] or [ffi.NULL])
    if _BOUND[key].washer_traced_bind(k, fns, data) != 0:
        raise TraceError("the generated C's loop table has another size")


#: The seed of the offsets of the points compared on loading (`_start_points`).
LOAD_SEED = 20261202


@functools.lru_cache(maxsize=None)
def _load_deviates(seed: int, n: int, npar: int) -> tuple[np.ndarray, np.ndarray]:
    """The normal deviates of `_start_points`, read-only: LOAD_POINTS - 1 rows of n for
    u, then as many rows of npar for PAR, drawn in that order from Python's generator
    seeded with `seed` (importing numpy.random costs a short run more than drawing these
    few hundred numbers one by one). The same numbers for every file of these sizes, so
    drawn once in a process: every run loads its file again."""
    rng = random.Random(seed)
    k = LOAD_POINTS - 1
    zu = np.array([[rng.gauss(0.0, 1.0) for _ in range(n)] for _ in range(k)]).reshape(k, n)
    zp = np.array([[rng.gauss(0.0, 1.0) for _ in range(npar)]
                   for _ in range(k)]).reshape(k, npar)
    zu.setflags(write=False)
    zp.setflags(write=False)
    return zu, zp


def _start_points(python: Problem, seed: int = LOAD_SEED) -> tuple[np.ndarray, np.ndarray]:
    """LOAD_POINTS points (u, par) around the file's starting point (stpnt, else u = 0
    and PAR = 0): offsets of relative sizes 1e-3 to 1 (and the point itself), normal
    deviates of `_load_deviates`."""
    n = python.ndim
    try:
        u0, p0 = python.start(TRACE_NPAR)
    except Exception:
        u0, p0 = np.zeros(n), np.zeros(TRACE_NPAR)
    zu, zp = _load_deviates(seed, n, len(p0))
    scales = _load_scales()
    # row k: u0 + s_k (1 + |u0|) z_k, the same operations in the same order as one row at
    # a time (elementwise, broadcast): the same doubles in two numpy calls a vector
    us, ps = np.empty((LOAD_POINTS, n)), np.empty((LOAD_POINTS, len(p0)))
    us[0], ps[0] = u0, p0
    np.add(u0, scales * (1 + np.abs(u0)) * zu, out=us[1:])
    np.add(p0, scales * (1 + np.abs(p0)) * zp, out=ps[1:])
    return us, ps


@functools.lru_cache(maxsize=1)
def _load_scales() -> np.ndarray:
    """The offsets' relative sizes of `_start_points`, (LOAD_POINTS - 1, 1), read-only."""
    scales = np.geomspace(1e-3, 1.0, LOAD_POINTS - 1)[:, None]
    scales.setflags(write=False)
    return scales


def _agree(compiled: np.ndarray, fn, us, pars, what: str) -> None:
    """TraceError unless `compiled` (rows) equals fn at every point where fn gives finite
    values, bit for bit, and there is at least one such point (none compared is nothing
    verified)."""
    compared = 0
    with np.errstate(all="ignore"):
        refs = []
        for u, p in zip(us, pars):
            try:
                refs.append(np.asarray(fn(u.copy(), p.copy()), dtype=float))
            except Exception:
                refs.append(None)    # not a point of the function's domain
    for j, ref in enumerate(refs):
        if ref is None:
            continue
        if not np.isfinite(ref).all():
            continue
        if not same_bits(ref, compiled[j][tuple(slice(0, s) for s in ref.shape)]):
            raise TraceError(f"the compiled trace of {what} differs from it at a point "
                             "near the start (compared bit for bit)")
        compared += 1
    if not compared:
        raise TraceError(f"{what} gave no finite values at the {len(us)} points near the "
                         "start it is compared at: nothing verified")


def traced_problem(python: Problem, path: Path) -> Problem:
    """The TracedProblem of a Python file's problem, or the problem itself (its `route`
    says why) where its functions cannot be traced, compiled or verified, or where
    $WASHER_TRACE is 0 (the Python functions throughout: a benchmark's reference)."""
    if os.environ.get("WASHER_TRACE", "1") == "0":
        python.route = "func(u, par) in Python: WASHER_TRACE=0"
        return python
    try:
        return _build(python, Path(path))
    except (TraceError, CompileError, OSError) as exc:
        python.route = f"func(u, par) in Python: {exc}"
        return python


def _build(python: Problem, path: Path) -> TracedProblem:
    n = python.ndim
    loops: list = []
    traced_f = trace_function(python._func, n, TRACE_NPAR, (n,), loops=loops)
    traced_j = traced_p = None
    if python._dfdu is not None:
        traced_j = trace_function(python._dfdu, n, TRACE_NPAR, (n, n), loops=loops,
                                  prefix="a")
    python_dfdp = ""
    if python._dfdp is not None:
        try:
            traced_p = trace_function(python._dfdp, n, TRACE_NPAR, (n, None), loops=loops,
                                      prefix="b")
        except TraceError as exc:
            # (typically np.zeros((n, len(par))) filled in): dfdp stays the Python
            # function, called as the Python problem calls it (one point at a time; no
            # compiled path reads FUNC's DFDP of a traced file but TracedProblem's own)
            python_dfdp = f"; dfdp(u, par) in Python: {exc}"
    npar_used = max(t[0].npar_used for t in (traced_f, traced_j, traced_p) if t is not None)
    lib = build_library([_emitted(path, n, traced_f, traced_j, traced_p), _shim_source()],
                        f"{path.stem}_traced", includes=[INCLUDE],
                        defines={"WASHER_FORTRAN": 0, "WASHER_TRACED_BATCH": 1}, flags=FLAGS)
    _bind(lib, loops)
    state = TraceState("func(u, par) traced into C (compared with the Python func bit for "
                       "bit at the start and at the first points of each run)" + python_dfdp)
    user = TracedUser(path, n, lib, state)
    # verified where the file starts before it is trusted
    us, ps = _start_points(python)
    two_ways, arrays = traced_f[0].two_ways, True
    with np.errstate(all="ignore"):
        _agree(user.func_batch(us, ps), python._func, us, ps, "func(u, par)")
        if two_ways:
            arrays = _agree_on_arrays(user, python._func, us, ps)
        if traced_j is not None:
            _agree(user.dfdu_batch(us, ps), python._dfdu, us, ps, "dfdu(u, par)")
        if traced_p is not None:
            P = np.array([user.dfdp(u, p) for u, p in zip(us, ps)])
            _agree(P, python._dfdp, us, ps, "dfdp(u, par)")
    return TracedProblem(user, python, npar_used, two_ways, arrays,
                         dfdp_traced=traced_p is not None)


#: `_emitted`'s sources by everything emit_user_file reads of its traces, of this process
_EMITTED: dict = {}
_EMITTED_MAX = 32


def _trace_key(traced) -> tuple | None:
    """What emit_user_file reads of one (tape, expressions) of trace_function: the tape's
    lines and the expressions with their shape (None for no trace)."""
    if traced is None:
        return None
    tape, exprs = traced
    return tuple(tape.lines), exprs.shape, tuple(exprs.flat)


def _emitted(path: Path, n: int, traced_f, traced_j, traced_p):
    """The C user file of the traces (emit_user_file) as the Source build_library takes,
    named by a hash of its text; made once per process for the same traces (a run
    traces the file's functions afresh, and the same file traces to the same tapes: the
    text, its hash and its bytes are then those of the first run, whose bytes also keep
    their hash for library_key's memo)."""
    key = (path.name, path.stem, n, len(traced_f[0].loops), _trace_key(traced_f),
           _trace_key(traced_j), _trace_key(traced_p))
    src = _EMITTED.get(key)
    if src is None:
        text = emit_user_file(path.name, n, traced_f, traced_j, traced_p)
        tag = hashlib.sha256(text.encode()).hexdigest()[:12]
        src = source_text(f"{path.stem}_traced_{tag}.c", text)
        if len(_EMITTED) >= _EMITTED_MAX:
            _EMITTED.clear()
        _EMITTED[key] = src
    return src


#: (SHIM's size and modification time, its Source) of the last read
_SHIM_SOURCE: list = [None, None]


def _shim_source():
    """washer_shim.c (SHIM) as a Source, read again only where the file changed (its size
    or modification time)."""
    st = os.stat(SHIM)
    stamp = (st.st_size, st.st_mtime_ns)
    if _SHIM_SOURCE[0] != stamp:
        _SHIM_SOURCE[:] = [stamp, source_text("washer_shim.c", SHIM.read_bytes())]
    return _SHIM_SOURCE[1]


def _agree_on_arrays(user: TracedUser, fn, us, ps) -> bool:
    """Whether fn can be called on arrays (as Problem.func_many calls it): False where
    it raises or gives another shape; else TraceError unless the compiled FUNC in the
    modes ARRAYS and ARRAYS_PAR_BROADCAST gives its values bit for bit at every point
    where they are finite (par's rows strided, then one broadcast vector, the start's)."""
    k, n = us.shape
    for pars, mode in ((ps, ARRAYS), (broadcast_rows(ps[0], k), ARRAYS_PAR_BROADCAST)):
        try:
            ref = np.asarray(fn(us.T, pars.T), dtype=float)
        except Exception:
            return False
        if ref.shape != (n, k):
            return False
        ref = np.ascontiguousarray(ref.T)
        got = user.func_in_mode(us, np.ascontiguousarray(pars), mode)
        finite = np.isfinite(ref).all(axis=1)
        if not finite.any():
            raise TraceError("func(u, par) on arrays gave no finite values at the points "
                             "near the start it is compared at: nothing verified")
        if not same_bits(ref[finite], got[finite]):
            raise TraceError("the compiled trace of func(u, par) on arrays differs from "
                             "it at a point near the start (compared bit for bit)")
    return True
