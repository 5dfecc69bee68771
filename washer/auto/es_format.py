"""Fortran's ESw.d and ESw.dE3 edit descriptors as gfortran writes them: the numbers of
AUTO-07p's b-, s- and d-files. One formatter: the compiled one of the engine's module
(csrc/cont/format.cpp, `cont_format_es`), with `python_es_text` below as its reference
and the fallback where that module cannot be imported (the tests hold the two to the
same text on millions of doubles).

    es_text([1.5, -0.0], 19, 10, exp3=True)   '   1.5000000000E+000  -0.0000000000E+000'
    es_text([1e-120], 12, 4)                  ' 1.0000-120'   (ES12.4: no 'E' beyond 99)

Text only, no numerics: the digits are the correctly rounded ones (ties to even), as C's
printf and Python's float formatting give them.
"""
from __future__ import annotations

import math
import threading

import numpy as np

try:
    from washer import build_stamp
    from washer._cont import ffi as _ffi, lib as _lib
    build_stamp.check("washer._cont", _ffi, _lib)
    if not hasattr(_lib, "cont_format_es"):
        raise ImportError("washer._cont has no cont_format_es")
except ImportError:              # no compiled engine (or a stale one): the Python formatter
    _ffi = _lib = None

#: Whether the compiled formatter is in use.
COMPILED = _lib is not None


def _special(x: float, width: int) -> str | None:
    """gfortran's text for NaN (either sign) and the infinities, right-justified; None
    for finite x."""
    if math.isnan(x):
        return "NaN".rjust(width)
    if math.isinf(x):
        return ("Infinity" if x > 0 else "-Infinity").rjust(width)
    return None


def python_es_one(x: float, width: int, digits: int, exp3: bool) -> str:
    """One value as ESw.d (exp3 False: 'E' and a 2-digit exponent; beyond 99 three digits
    without the 'E', '-1.7976+308') or ESw.dE3 (exp3 True: 'E' and 3 digits),
    right-justified in `width` (never cut)."""
    x = float(x)
    special = _special(x, width)
    if special:
        return special
    mant, exp = f"{x:.{digits}e}".split("e")     # Python rounds once, correctly
    exp = int(exp)
    sign = "+" if exp >= 0 else "-"
    if exp3:
        text = f"{mant}E{sign}{abs(exp):03d}"
    elif abs(exp) <= 99:
        text = f"{mant}E{sign}{abs(exp):02d}"
    else:
        text = f"{mant}{sign}{abs(exp):03d}"
    return text.rjust(width)


def python_es_text(values, width: int, digits: int, exp3: bool = False,
                   per_line: int | None = None, indent: int = 0) -> str:
    """`es_text` in Python, value by value."""
    M = np.asarray(values, dtype=float)
    if per_line is None or M.ndim < 2:
        rows = M.reshape(1, -1)
    else:
        rows = M.reshape(M.shape[0], M.size // M.shape[0] if M.shape[0] else 0)
    lines = []
    for row in rows.tolist():
        per = per_line or max(len(row), 1)
        for i in range(0, len(row), per):
            lines.append(" " * indent + "".join(python_es_one(x, width, digits, exp3)
                                                 for x in row[i:i + per]))
    return "\n".join(lines)


_buffers = threading.local()       # the C text's buffer, grown as needed, one a thread


def _buffer(size: int):
    buf = getattr(_buffers, "buf", None)
    if buf is None or len(buf) < size:
        buf = _buffers.buf = _ffi.new("char[]", max(size, 4096))
    return buf


def es_text(values, width: int, digits: int, exp3: bool = False,
            per_line: int | None = None, indent: int = 0) -> str:
    """The values in ESw.d (exp3 False) or ESw.dE3 (exp3 True), concatenated.

    values: numbers, a sequence or an array. per_line None: all of them (flattened) on
    one line; else a 2-D array's rows (a flat sequence: one row) each start a line of at
    most `per_line` values. Every line starts with `indent` blanks; lines are joined by
    newlines, none at the end. Each value is right-justified in `width` characters and
    never cut; NaN prints as 'NaN', the infinities as 'Infinity' / '-Infinity'
    (gfortran's text)."""
    if _lib is None:
        return python_es_text(values, width, digits, exp3, per_line, indent)
    if type(values) is list or type(values) is tuple:
        k, m, v = 1, len(values), values
    else:
        a = np.ascontiguousarray(values, dtype=float)
        if a.ndim >= 2 and per_line is not None:
            k = a.shape[0]
            m = a.size // k if k else 0
        else:
            k, m = 1, a.size
        v = _ffi.from_buffer("double[]", a)
    per = per_line or max(m, 1)
    size = k * m * max(width, digits + 8) + k * (m // per + 1) * (indent + 1) + 1
    buf = _buffer(size)
    try:
        n = _lib.cont_format_es(v, k, m, per, indent, width, digits, int(exp3), buf)
    except TypeError:             # nested rows, or items a double cannot take: numpy's view
        return es_text(np.asarray(values, dtype=float), width, digits, exp3, per_line, indent)
    if n < 0:
        raise ValueError(f"cannot format {k} x {m} values as ES{width}.{digits}")
    return _ffi.unpack(buf, n).decode("ascii")
