"""A Python user file's func (and dfdu, dfdp) traced into C that computes the same doubles.

    tape = trace_function(func, ndim, npar, (ndim,))       # or raises TraceError
    text = emit_user_file(func_tape, dfdu_tape, dfdp_tape)  # AUTO's C user file (FUNC)

The function is called once with stand-ins for u and par: sequences whose elements are
`Value`s, each standing for the np.float64 that indexing a float array gives (u[0],
par[2], unpacking `x, y, z = u`, slices of them). Every arithmetic operation on a Value
is recorded in the order Python evaluates it, with numpy's scalar semantics (NEP 50: a
Python int or float operand is a double), so the C computes the same IEEE doubles:

    a + b, a - b, a * b, a / b, -a, +a     IEEE operations (correctly rounded either way)
    abs(a)                                 fabs
    np.add, np.multiply, ... np.sqrt,      the same IEEE operations (numpy's loops compute
                                           them correctly rounded, as C does)
    np.square, np.absolute, np.negative
    a ** b, np.power(a, b)                 as numpy computes them on numpy scalars and
                                           on arrays (below)
    any other numpy ufunc of one or two    numpy's own compiled loop for doubles, called
    doubles (np.exp, np.sin, np.arctan,    through its pointer (the ufunc's `functions`
    np.hypot, ...)                         table): numpy's exp differs from glibc's in a
                                           few per cent of arguments on AVX-512 machines,
                                           so the C calls numpy's implementation itself; a
                                           scalar and an array's elements go through the
                                           same loop (the same values, strided or not)

Constants are written as hexadecimal floats (exact). The generated C is compiled with
-ffp-contract=off (no fused multiply-adds) and without -ffast-math.

`x ** y` and np.power(x, y) are traced as numpy computes them, which depends on whether
func was called with one point (u[i] a np.float64) or with the (NDIM, k) arrays of a
difference stencil or a batch (washer.cont.problem.Problem.func_many), so the C holds
both and a mode says which (`washer_traced_mode`; washer.cont.user_problem.user_files_traced
chooses it per call
as the Python problem would call func):

    mode 0, numpy scalars    x ** y is libm's pow (numpy's scalar power: npy_pow);
                             np.power(x, y) numpy's power loop with a zero exponent
                             stride (0-d operands)
    mode 1, 2, arrays        x ** -1, x ** 2, x ** 0.5 (a Python int, int, float) are
                             numpy's reciprocal, square, sqrt (fast_scalar_power in
                             numpy's number.c): 1.0 / x, x * x, sqrt(x); any other
                             exponent goes to numpy's power loop, which takes its own
                             fast paths (-1, 0, 0.5, 1, 2) where the exponent's stride
                             is zero (a constant; PAR(i) itself where par's rows are
                             one broadcast vector, mode 2) and its SIMD pow otherwise
                             (PAR(i) from a (k, NPAR) array, mode 1; u[i]; a computed
                             value): the C calls that loop with the same strides.

libm's pow is not x * x for y = 2 at about 0.08 % of doubles, and numpy's SIMD pow
differs from libm's at several per cent, so each route is reproduced exactly, not
approximately; tests/test_user_files_traced.py compares every class of exponent bit for bit.

What cannot be traced honestly raises TraceError, and the problem keeps its Python func:
a branch or loop on a value (bool(), a comparison), conversion to a Python number
(float(), int(), math.exp(x), writing a value into a float array), operations that
are not listed (//, %, divmod, a ufunc with out= or where=, a reduction), a write into u
or par, operands of other types (complex, float32), a result that is not one double per
component. A value with an array (of values, or of numbers: `par[10] * np.array([...])`)
is the array's ufunc element by element, each element's operation traced. An operation
on an object array the user built from values (A @ v, np.sum(v), v ** 2) is traced
element by element and can round otherwise than on floats; the comparison of the
compiled function with the Python one (washer.cont.user_problem.user_files_traced) is what
tells, and refuses it.
"""
from __future__ import annotations

import ctypes
import math
import re

import numpy as np


#: The exponents numpy's array power replaces by a ufunc (number.c, fast_scalar_power:
#: a Python int -1 or 2, a Python float 0.5) and the C of each (numpy's loops for
#: doubles compute these correctly rounded, as C does).
_FAST_OPERATOR = {(int, -1): "(1.0 / {0})", (int, 2): "({0} * {0})",
                  (float, 0.5): "sqrt({0})"}
#: The C of numpy's power loop's own fast paths for an exponent of zero stride
#: (loops_umath_fp's POWER_FAST_PATH), by the exponent's value.
_FAST_LOOP = {-1.0: "(1.0 / {0})", 0.0: "1.0", 0.5: "sqrt({0})", 1.0: "{0}",
              2.0: "({0} * {0})"}


class TraceError(Exception):
    """The function does something the tracer cannot reproduce in C exactly."""


#: IEEE operations of the ufuncs computed in C directly (numpy's double loops compute
#: them correctly rounded, as C does).
_C_BINARY = {"add": "+", "subtract": "-", "multiply": "*", "divide": "/",
             "true_divide": "/"}
_C_UNARY = {"negative": "-{}", "positive": "{}", "absolute": "fabs({})", "fabs": "fabs({})",
            "sqrt": "sqrt({})", "square": "({0} * {0})", "reciprocal": "(1.0 / {})"}
#: NPY_DOUBLE, numpy's type number of float64 in a ufunc's `types` table
NPY_DOUBLE = 12
#: The largest integer a Python int operand may have: exactly a double.
_EXACT_INT = 2 ** 53


#: A temporary's name in a C expression (the prefixes trace_function is given: t, a, b).
_NAME = re.compile(r"\b[a-z]\d+\b")


class Tape:
    """The recorded operations: `lines` (one temporary and its C expression each), the numpy loops used
    (their ufunc objects, in the order of `loops`)."""

    def __init__(self, loops: list | None = None, prefix: str = "t"):
        self.lines: list[tuple[str, str]] = []      # (temporary, its C expression)
        self.loops: list = [] if loops is None else loops     # shared by a file's tapes
        self._n = 0
        self._prefix = prefix
        self.npar_used = 0        # PAR(1 ..) read: the run's PAR must be this long
        # a power whose C on numpy scalars differs from its C on arrays (the mode decides)
        self.two_ways = False

    def temp(self, expr: str) -> "Value":
        name = f"{self._prefix}{self._n}"
        self._n += 1
        self.lines.append((name, expr))
        return Value(self, name)

    def live_lines(self, outputs) -> list[str]:
        """The C lines of the temporaries the `outputs` (C expressions) need, in order
        (a value computed and not used is not computed: every operation is a pure
        function of its operands)."""
        need = set(_NAME.findall(" ".join(outputs)))
        keep = []
        for name, expr in reversed(self.lines):
            if name in need:
                need.update(_NAME.findall(expr))
                keep.append(f"    const double {name} = {expr};")
        return keep[::-1]

    def loop_index(self, ufunc) -> int:
        for i, u in enumerate(self.loops):
            if u is ufunc:
                return i
        self.loops.append(ufunc)
        return len(self.loops) - 1


def constant(x) -> str:
    """The C literal of the double x, exact (hexadecimal); TraceError for a NaN (its
    payload is not written)."""
    x = float(x)
    if math.isnan(x):
        raise TraceError("a NaN constant")
    if math.isinf(x):
        return "HUGE_VAL" if x > 0 else "(-HUGE_VAL)"
    return f"({x.hex()})" if x < 0 or x == 0 and math.copysign(1, x) < 0 else x.hex()


def _operand(tape: Tape, x) -> str:
    """The C of an operand: a Value of this tape, or a Python int, float or np.float64
    constant (a double, as numpy converts it)."""
    if isinstance(x, Value):
        if x.tape is not tape:
            raise TraceError("a value of another trace")
        return x.ref
    if type(x) in (float, np.float64):
        return constant(x)
    if type(x) is int or type(x) is np.int64:
        if abs(int(x)) > _EXACT_INT:
            raise TraceError(f"the integer {x} is not a double exactly")
        return constant(float(x))
    raise TraceError(f"an operand of type {type(x).__name__}")


def _object_array(x) -> np.ndarray:
    """x as an object array (a Value as a 0-d one: not a ufunc's override any more)."""
    if isinstance(x, np.ndarray):
        return x.astype(object)
    a = np.empty((), dtype=object)
    a[()] = x
    return a


def _refuse(what):
    def method(self, *args, **kwargs):
        raise TraceError(f"{what} of a traced value (a branch, loop or conversion that "
                         "depends on u or par)")
    return method


class Value:
    """A traced double: the np.float64 of u[i] or par[i], or a result computed from them.
    `ref` is its C expression (u[i], par[i] or a temporary)."""

    __slots__ = ("tape", "ref")
    __array_priority__ = 1000

    def __init__(self, tape: Tape, ref: str):
        self.tape, self.ref = tape, ref

    def _bin(self, op: str, a, b) -> "Value":
        if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
            return NotImplemented     # the array's operator: element by element (below)
        return self.tape.temp(f"{_operand(self.tape, a)} {op} {_operand(self.tape, b)}")

    def __add__(self, o):
        return self._bin("+", self, o)

    def __radd__(self, o):
        return self._bin("+", o, self)

    def __sub__(self, o):
        return self._bin("-", self, o)

    def __rsub__(self, o):
        return self._bin("-", o, self)

    def __mul__(self, o):
        return self._bin("*", self, o)

    def __rmul__(self, o):
        return self._bin("*", o, self)

    def __truediv__(self, o):
        return self._bin("/", self, o)

    def __rtruediv__(self, o):
        return self._bin("/", o, self)

    def __pow__(self, o, mod=None):
        if mod is not None:
            raise TraceError("pow(x, y, mod)")
        return _power(self.tape, self, o, operator=True)

    def __rpow__(self, o):
        return _power(self.tape, o, self, operator=True)

    def __neg__(self):
        return self.tape.temp(f"-{self.ref}")

    def __pos__(self):
        # +a of an array is a new array: PAR(i) itself no more (its stride, _power)
        return self.tape.temp(self.ref) if self.ref.startswith("par[") else self

    def __abs__(self):
        return self.tape.temp(f"fabs({self.ref})")

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        if method != "__call__" or kwargs:
            raise TraceError(f"np.{ufunc.__name__}.{method} with {sorted(kwargs)}")
        if ufunc.nout != 1 or ufunc.nin not in (1, 2) or len(inputs) != ufunc.nin:
            raise TraceError(f"np.{ufunc.__name__}: not a function of one or two doubles")
        if any(isinstance(x, np.ndarray) for x in inputs):
            # a value with an array (of values, or of numbers): the same ufunc element by
            # element, each element's operation traced
            each = np.frompyfunc(lambda *a: ufunc(*a), ufunc.nin, 1)
            return each(*(_object_array(x) for x in inputs))
        tape = self.tape
        args = [_operand(tape, x) for x in inputs]
        name = ufunc.__name__
        if ufunc.nin == 2 and name in _C_BINARY:
            return tape.temp(f"{args[0]} {_C_BINARY[name]} {args[1]}")
        if ufunc.nin == 1 and name in _C_UNARY:
            return tape.temp(_C_UNARY[name].format(args[0]))
        if ufunc is np.power:
            return _power(tape, inputs[0], inputs[1], operator=False)
        numpy_loop(ufunc)           # a double loop exists (else TraceError)
        i = tape.loop_index(ufunc)
        if ufunc.nin == 1:
            return tape.temp(f"np_loop1({i}, {args[0]})")
        return tape.temp(f"np_loop2({i}, {args[0]}, {args[1]})")

    __bool__ = _refuse("bool()")
    __float__ = _refuse("float()")
    __int__ = _refuse("int()")
    __index__ = _refuse("an index")
    __complex__ = _refuse("complex()")
    __round__ = _refuse("round()")
    __trunc__ = _refuse("trunc()")
    __floor__ = _refuse("floor()")
    __ceil__ = _refuse("ceil()")
    __lt__ = _refuse("a comparison")
    __le__ = _refuse("a comparison")
    __gt__ = _refuse("a comparison")
    __ge__ = _refuse("a comparison")
    __eq__ = _refuse("a comparison")
    __ne__ = _refuse("a comparison")
    __hash__ = None
    __floordiv__ = __rfloordiv__ = _refuse("//")
    __mod__ = __rmod__ = _refuse("%")
    __divmod__ = __rdivmod__ = _refuse("divmod")


def _power(tape: Tape, base, exp, operator: bool) -> Value:
    """base ** exp (`operator`) or np.power(base, exp) as numpy computes it in each mode
    (the module's docstring): one C expression where the modes agree, else
    `washer_mode ? <arrays> : <numpy scalars>`."""
    b, e = _operand(tape, base), _operand(tape, exp)
    i = tape.loop_index(np.power)
    numpy_loop(np.power)
    if isinstance(exp, Value):
        # its stride on arrays: zero only for PAR(i) itself with par's rows broadcast
        stride = "washer_mode == 2" if exp.ref.startswith("par[") else "0"
        arrays = f"np_pow({i}, {b}, {e}, {stride})"
    else:
        value = float(exp)
        kind = type(exp) if type(exp) in (int, float) else None
        fast = _FAST_OPERATOR.get((kind, value)) if operator else None
        if fast is None:
            fast = _FAST_LOOP.get(value, f"np_pow({i}, {b}, {e}, 1)")
        arrays = fast.format(b)
    # numpy scalars: np.float64's power is libm's pow; np.power of 0-d operands is the
    # loop with a zero exponent stride
    scalars = f"c_pow({b}, {e})" if operator else (
        f"np_pow({i}, {b}, {e}, 1)" if isinstance(exp, Value)
        else _FAST_LOOP.get(float(exp), f"np_pow({i}, {b}, {e}, 1)").format(b))
    if scalars == arrays:
        return tape.temp(arrays)
    tape.two_ways = True
    return tape.temp(f"washer_mode ? {arrays} : {scalars}")


class Vector:
    """The stand-in for u or par: indexing, slicing, unpacking and len() give Values;
    anything else (arithmetic on the whole vector, writing into it, numpy functions of
    it) raises TraceError."""

    __slots__ = ("_items", "_sized", "used")

    def __init__(self, items, sized: bool = True):
        self._items = list(items)
        # par's length is the run's NPAR, not the traced one: len(par), par[-1], par[k:]
        # and iterating over all of par would be traced for one length only
        self._sized = sized
        self.used = -1            # the highest index read

    def __len__(self):
        if not self._sized:
            raise TraceError("len(par) (the run's NPAR is not the traced one)")
        return len(self._items)

    def __iter__(self):
        if not self._sized:
            raise TraceError("iterating over all of par")
        self.used = len(self._items) - 1
        return iter(self._items)

    def __getitem__(self, i):
        if isinstance(i, slice):
            if not self._sized and (i.stop is None or i.stop < 0 or (i.start or 0) < 0):
                raise TraceError("a slice of par relative to its end")
            idx = range(len(self._items))[i]
            if len(idx):
                self.used = max(self.used, max(idx))
            return Vector(self._items[i])
        if type(i) is not int and not isinstance(i, np.integer):
            raise TraceError(f"u or par indexed by {type(i).__name__}")
        i = int(i)
        if i < 0 and not self._sized:
            raise TraceError("par indexed from its end")
        v = self._items[i]
        self.used = max(self.used, i % len(self._items))
        return v

    def __setitem__(self, i, v):
        raise TraceError("a write into u or par")

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        raise TraceError(f"np.{ufunc.__name__} of the whole of u or par")

    def __array_function__(self, func, types, args, kwargs):
        raise TraceError(f"np.{func.__name__} of u or par")

    __array__ = _refuse("u or par as an array")
    __bool__ = _refuse("bool()")


def _arith(name):
    def method(self, *args):
        raise TraceError(f"arithmetic on the whole of u or par ({name})")
    return method


for _name in ("add", "radd", "sub", "rsub", "mul", "rmul", "truediv", "rtruediv", "pow",
              "rpow", "neg", "pos", "abs", "matmul", "rmatmul", "floordiv", "mod"):
    setattr(Vector, f"__{_name}__", _arith(_name))


def trace_function(fn, ndim: int, npar: int, shape: tuple, *, min_cols: int = 0,
                   loops: list | None = None, prefix: str = "t"):
    """Trace fn(u, par) (u of ndim, par of npar entries): (the tape, the C expressions of
    its result, an object array of `shape`; shape (n, None): dfdp's, at least `min_cols`
    columns). `loops`: the numpy ufuncs of the file's other tapes (shared numbering);
    `prefix`: of the temporaries' names. TraceError where it cannot be traced."""
    tape = Tape(loops, prefix)
    u = Vector(Value(tape, f"u[{i}]") for i in range(ndim))
    par = Vector((Value(tape, f"par[{i}]") for i in range(npar)), sized=False)
    try:
        with np.errstate(all="ignore"):
            out = fn(u, par)
    except TraceError:
        raise
    except Exception as exc:
        raise TraceError(f"{type(exc).__name__}: {exc}") from exc
    try:
        arr = np.asarray(out, dtype=object)
    except TraceError:
        raise
    except Exception as exc:
        raise TraceError(f"the result is not an array: {exc}") from exc
    if shape[1:] == (None,):
        if arr.ndim != 2 or arr.shape[0] != shape[0] or arr.shape[1] < min_cols:
            raise TraceError(f"the result has shape {arr.shape}, expected ({shape[0]}, >= "
                             f"{min_cols})")
    elif arr.shape != shape:
        raise TraceError(f"the result has shape {arr.shape}, expected {shape}")
    exprs = np.empty(arr.shape, dtype=object)
    for idx, v in np.ndenumerate(arr):
        exprs[idx] = _operand(tape, v) if not isinstance(v, np.ndarray) else None
        if exprs[idx] is None:
            raise TraceError("a result entry is an array")
    tape.npar_used = par.used + 1
    return tape, exprs


# ------------------------------------------------------------------ numpy's loops

class _UFunc(ctypes.Structure):
    """The head of numpy's PyUFuncObject (numpy/ufuncobject.h, public C API)."""
    _fields_ = [("ob_refcnt", ctypes.c_ssize_t), ("ob_type", ctypes.c_void_p),
                ("nin", ctypes.c_int), ("nout", ctypes.c_int), ("nargs", ctypes.c_int),
                ("identity", ctypes.c_int), ("functions", ctypes.POINTER(ctypes.c_void_p)),
                ("data", ctypes.POINTER(ctypes.c_void_p)), ("ntypes", ctypes.c_int),
                ("reserved1", ctypes.c_int), ("name", ctypes.c_char_p),
                ("types", ctypes.POINTER(ctypes.c_char))]


_LOOPS: dict = {}


def numpy_loop(ufunc) -> tuple[int, int]:
    """(the loop's address, its data pointer) of numpy's loop of `ufunc` for doubles
    (all types NPY_DOUBLE), read from the ufunc object's `functions` and `data` tables;
    TraceError where there is none, or where the object's head does not read back as the
    ufunc (nin, nout, ntypes, name: a numpy whose layout differs)."""
    if not isinstance(ufunc, np.ufunc):
        raise TraceError(f"{ufunc!r} is not a numpy ufunc")
    key = id(ufunc)
    hit = _LOOPS.get(key)
    if hit is not None and hit[0] is ufunc:
        return hit[1]
    head = _UFunc.from_address(id(ufunc))
    if (head.nin, head.nout, head.ntypes) != (ufunc.nin, ufunc.nout, ufunc.ntypes) \
            or head.name is None or head.name.decode() != ufunc.__name__ \
            or not head.functions or not head.types:
        raise TraceError(f"np.{ufunc.__name__}: its loop table cannot be read here")
    nargs = ufunc.nin + ufunc.nout
    for i in range(head.ntypes):
        if all(ord(head.types[i * nargs + j]) == NPY_DOUBLE for j in range(nargs)):
            fn, data = head.functions[i], head.data[i] if head.data else None
            if not fn:
                break
            found = (int(fn), int(data or 0))
            _LOOPS[key] = (ufunc, found)
            return found
    raise TraceError(f"np.{ufunc.__name__} has no loop for doubles")


# ------------------------------------------------------------------ C

_PRELUDE = """/* Generated by washer.cont.user_problem.tracer from {source}: its func{others}
 * traced into C (the same operations in the same order); not to be edited. */
#include <math.h>
#include <stddef.h>
#include "auto_f2c.h"

/* numpy's compiled loops for doubles (washer_traced_bind sets them) */
typedef void np_loop_t(char **args, const ptrdiff_t *n, const ptrdiff_t *steps, void *data);
static np_loop_t *np_loops[{nloops}];
static void *np_data[{nloops}];

int washer_traced_bind(int k, void *const *loops, void *const *data)
{{
    if (k != {nloops}) return 1;
    for (int i = 0; i < k; i++) {{
        np_loops[i] = (np_loop_t *)loops[i];
        np_data[i] = data[i];
    }}
    return 0;
}}

static double np_loop1(int i, double a)
{{
    double out;
    char *args[2] = {{(char *)&a, (char *)&out}};
    const ptrdiff_t n = 1, steps[2] = {{sizeof(double), sizeof(double)}};
    np_loops[i](args, &n, steps, np_data[i]);
    return out;
}}

/* numpy's loop i on n contiguous doubles (a, out; a, b, out): `np_loop1` and `np_loop2`
 * over a chunk of points (out may be a) */
static void np_vec1(int i, const double *a, double *out, int n)
{{
    char *args[2] = {{(char *)a, (char *)out}};
    const ptrdiff_t nn = n, steps[2] = {{sizeof(double), sizeof(double)}};
    np_loops[i](args, &nn, steps, np_data[i]);
}}

static void np_vec2(int i, const double *a, const double *b, double *out, int n)
{{
    char *args[3] = {{(char *)a, (char *)b, (char *)out}};
    const ptrdiff_t nn = n, steps[3] = {{sizeof(double), sizeof(double), sizeof(double)}};
    np_loops[i](args, &nn, steps, np_data[i]);
}}

static double np_loop2(int i, double a, double b)
{{
    double out;
    char *args[3] = {{(char *)&a, (char *)&b, (char *)&out}};
    const ptrdiff_t n = 1, steps[3] = {{sizeof(double), sizeof(double), sizeof(double)}};
    np_loops[i](args, &n, steps, np_data[i]);
    return out;
}}

/* How numpy was called (washer.cont.user_problem.tracer): 0 numpy scalars, 1 arrays, 2 arrays with
 * par's rows one broadcast vector (stride 0). */
static int washer_mode;

void washer_traced_mode(int mode)
{{
    washer_mode = mode;
}}

/* numpy's power loop for doubles at one point, the exponent's stride zero or not: with
 * a zero stride the loop takes its fast paths (exponent -1, 0, 0.5, 1, 2), else its
 * SIMD pow */
static double np_pow(int i, double a, double b, int zero_stride)
{{
    double out;
    char *args[3] = {{(char *)&a, (char *)&b, (char *)&out}};
    const ptrdiff_t n = 1;
    const ptrdiff_t steps[3] = {{sizeof(double), zero_stride ? 0 : sizeof(double),
                                sizeof(double)}};
    np_loops[i](args, &n, steps, np_data[i]);
    return out;
}}

/* libm's pow through a pointer: the compiler may not rewrite pow(x, 2.0) as x * x
 * (numpy's scalar power is libm's pow, which rounds otherwise at some x) */
static double (*volatile c_pow_fn)(double, double) = pow;

static double c_pow(double a, double b)
{{
    return c_pow_fn(a, b);
}}
"""

_TAIL = """
static int stpnt(integer ndim, doublereal t, doublereal *u, doublereal *par)
{ (void)ndim; (void)t; (void)u; (void)par; return 0; }
static int bcnd(integer ndim, const doublereal *par, const integer *icp, integer nbc,
                const doublereal *u0, const doublereal *u1, integer ijac, doublereal *fb,
                doublereal *dbc)
{ (void)ndim; (void)par; (void)icp; (void)nbc; (void)u0; (void)u1; (void)ijac; (void)fb;
  (void)dbc; return 0; }
static int icnd(integer ndim, const doublereal *par, const integer *icp, integer nint,
                const doublereal *u, const doublereal *uold, const doublereal *udot,
                const doublereal *upold, integer ijac, doublereal *fi, doublereal *dint)
{ (void)ndim; (void)par; (void)icp; (void)nint; (void)u; (void)uold; (void)udot;
  (void)upold; (void)ijac; (void)fi; (void)dint; return 0; }
static int fopt(integer ndim, const doublereal *u, const integer *icp, const doublereal *par,
                integer ijac, doublereal *fs, doublereal *dfdu, doublereal *dfdp)
{ (void)ndim; (void)u; (void)icp; (void)par; (void)ijac; (void)fs; (void)dfdu; (void)dfdp;
  return 0; }
static int pvls(integer ndim, const doublereal *u, doublereal *par)
{ (void)ndim; (void)u; (void)par; return 0; }
"""


def emit_user_file(source: str, ndim: int, func, dfdu=None, dfdp=None) -> str:
    """AUTO's C user file of traced functions. func, dfdu, dfdp: (tape, expressions) of
    trace_function (one `loops` list shared by their tapes, whose order
    washer_traced_bind's tables follow), or None; FUNC computes f, with IJAC >= 1 DFDU
    (column-major, as AUTO's) and with IJAC = 2 DFDP (as many columns as dfdp returned),
    each from its own trace, as the Python functions are separate calls. STPNT, BCND,
    ICND, FOPT and PVLS are empty: the Python file's own are used."""
    def block(traced, out: str, guard: str = "") -> list[str]:
        tape, exprs = traced
        lines = [guard] if guard else []
        lines += ["    {"] + ["    " + ln for ln in tape.live_lines(list(exprs.flat))]
        lines += [f"        {out}[{idx[0] + (idx[1] * ndim if len(idx) > 1 else 0)}] = {e};"
                  for idx, e in np.ndenumerate(exprs)]
        return lines + ["    }"]

    body = block(func, "f")
    if dfdu is not None:
        body += block(dfdu, "dfdu", "    if (ijac < 1) return 0;")
    if dfdp is not None:
        body += block(dfdp, "dfdp", "    if (ijac < 2) return 0;")
    others = "".join(f", {n}" for n, t in (("dfdu", dfdu), ("dfdp", dfdp)) if t is not None)
    nloops = max(len(func[0].loops), 1)
    head = _PRELUDE.format(source=source, others=others, nloops=nloops)
    fn = ["", "static int func(integer ndim, const doublereal *u, const integer *icp,",
          "                const doublereal *par, integer ijac, doublereal *f,",
          "                doublereal *dfdu, doublereal *dfdp)", "{",
          "    (void)ndim; (void)icp; (void)ijac; (void)dfdu; (void)dfdp; (void)u; (void)par;",
          *body, "    return 0;", "}", ""]
    return head + "\n".join(fn) + "\n".join(_batch(func, ndim)) + _TAIL


#: Points per pass of the batched f (`_batch`): each temporary is an array of this many
#: doubles on the stack, and numpy's loops get that many elements a call.
BATCH_CHUNK = 64
#: A line of the tape that is one numpy loop of temporaries, constants, u[i] or par[i].
_LOOP_LINE = re.compile(r"np_loop([12])\((\d+), (.+)\)")


def _batch(func, ndim: int) -> list[str]:
    """washer_traced_batch: f at k points (the bridge's washer_func_batch calls it for
    the rows of us and pars), the same operations as `func` on each point, with every
    temporary an array over up to BATCH_CHUNK points: numpy's loops (np_loop1,
    np_loop2: exp, arctan, ...) are called once for the chunk, as numpy calls them on
    the arrays of a vectorised func, instead of once a point (their SIMD kernels
    compute a vector's lanes independently, so each element is the double a call with
    one element gives: the lanes of a call with one element are masked, not another
    formula; tests/test_user_files_traced.py compares both on every traced ufunc).
    Everything else is per point, as in `func` (the power's modes included). A func
    without numpy loops gains nothing by it (lrz's f: 4.6M instructions a run more than
    FUNC point by point, callgrind): its washer_traced_batch returns 1, and the bridge
    calls FUNC point by point."""
    tape, exprs = func
    outputs = list(exprs.flat)
    lines = tape.live_lines(outputs)
    ch = BATCH_CHUNK
    if not any(_LOOP_LINE.fullmatch(ln.strip()[len("const double "):-1].split(" = ", 1)[1])
               for ln in lines):
        return ["", "/* f at k points: FUNC point by point (no numpy loop to batch) */",
                "int washer_traced_batch(int k, int ndim, const double *us, const double *pars,",
                "                        int par_stride, double *fs)", "{",
                "    (void)k; (void)ndim; (void)us; (void)pars; (void)par_stride; (void)fs;",
                "    return 1;", "}", ""]
    per_q = "const double *u = uq + (size_t)q * " + str(ndim) + \
            ", *par = pq + (size_t)q * par_stride; (void)u; (void)par;"

    def at_q(expr: str) -> str:
        return _NAME.sub(lambda m: f"{m.group(0)}[q]", expr)

    def each(target: str, expr: str) -> str:
        return f"        for (int q = 0; q < c; q++) {{ {per_q} {target}[q] = {at_q(expr)}; }}"

    out = ["", "/* f at k points (see tracer._batch): us (k, NDIM), pars (k, NPAR) with row",
           " * stride par_stride (0: one PAR for all), fs (k, NDIM); 0, or 1 for another NDIM */",
           "int washer_traced_batch(int k, int ndim, const double *us, const double *pars,",
           "                        int par_stride, double *fs)", "{",
           f"    if (ndim != {ndim}) return 1;",
           f"    for (int q0 = 0; q0 < k; q0 += {ch}) {{",
           f"        const int c = k - q0 < {ch} ? k - q0 : {ch};",
           f"        const double *uq = us + (size_t)q0 * {ndim};",
           "        const double *pq = pars + (size_t)q0 * par_stride;",
           f"        double *fq = fs + (size_t)q0 * {ndim};",
           f"        double arg2[{ch}];", "        (void)arg2;"]
    for line in lines:
        name, expr = line.strip()[len("const double "):-1].split(" = ", 1)
        out.append(f"        double {name}[{ch}];")
        m = _LOOP_LINE.fullmatch(expr)
        if m is None:
            out.append(each(name, expr))
            continue
        nin, i, args = int(m.group(1)), m.group(2), [a.strip() for a in m.group(3).split(",")]
        arrays = []
        for j, a in enumerate(args):
            if _NAME.fullmatch(a):
                arrays.append(a)                     # a temporary: already an array
            else:                                    # u[i], par[i], a constant
                target = name if j == 0 else "arg2"
                out.append(each(target, a))
                arrays.append(target)
        out.append(f"        np_vec{nin}({i}, {', '.join(arrays)}, {name}, c);")
    for j, e in enumerate(outputs):
        out.append(f"        for (int q = 0; q < c; q++) {{ {per_q} "
                   f"fq[(size_t)q * {ndim} + {j}] = {at_q(e)}; }}")
    return out + ["    }", "    return 0;", "}", ""]
