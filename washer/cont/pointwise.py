"""Whether a user function called once with arrays of k points gives its separate calls'
values, bit for bit: the rule for calling a plain Python func with (ndim, k) arrays for a
small difference stencil (washer.cont.problem.Problem.func_many, STENCIL_MIN to
VECTORISE_MIN - 1 points) instead of once per point.

    check = PointwiseCheck()
    if not check.off:
        out = fn(us.T, pars.T)                      # one call for k points (numpy broadcasting)
        rows = check.rows(k)                        # the points to compare, or None
        ref = [fn(us[j], pars[j]) for j in rows]    # separate calls there
        if check.agree(ref, out[rows], k): ...      # use out; else separate calls, for good

The comparison is of the bytes, not a tolerance: separate calls and one call on arrays run
the same numpy operations, and IEEE arithmetic (+ - * / sqrt) is correctly rounded, so a
pointwise func built of it gives the same bits either way; a transcendental function need
not (numpy may take a SIMD loop for an array and another for a single value), nor a power
(`x ** 2` of a numpy scalar is pow, of an array a square), nor a sum whose order depends on
the shape (np.sum of 8 or more terms of a 1-D array is pairwise, over the rows of an array
sequential). Where the bits differ the vectorised call is refused for the rest of the
problem's life and the call that showed it is evaluated point by point: results are those
of separate calls throughout, except for calls before the one that showed a difference,
whose values were equal at every point compared.

What is compared: every point of the first call of each size k (up to CHECK_POINTS of
them), then one point every SPOT_EVERY calls, a different one each time. A point every call
would cost one separate call of the user's func, about half of what a continuation's 7- to
10-point stencils gain (callgrind: ab.py's 7 points 146k instructions as separate calls,
95k as one call, 125k with a point compared); every 8th call costs a sixteenth of it. A func
that mixes points (a reduction over the whole array) or raises on arrays is refused at its
first call.
"""
from __future__ import annotations

import numpy as np

#: How many points of the first call of each size are compared with separate calls.
CHECK_POINTS = 32
#: Every this many calls of a size already compared, one of its points is compared again.
SPOT_EVERY = 8


def same_bits(ref: np.ndarray, got: np.ndarray) -> bool:
    """Whether two float arrays hold the same values bit for bit: equal shapes and equal
    bytes in C order (NaN where NaN with the same payload, -0.0 apart from 0.0), whatever
    the memory layout of either."""
    return ref.shape == got.shape and ref.tobytes() == got.tobytes()


class PointwiseCheck:
    """The state of one user function's vectorised calls: unchecked, equal so far, or off
    for good (`off`). Shared by a problem's copies (Problem.with_jac): the same function."""

    __slots__ = ("off", "_sizes", "_turn")

    def __init__(self):
        self.off = False
        self._sizes = set()       # the call sizes k whose first call was compared in full
        self._turn = 0            # counts the calls of compared sizes

    def rows(self, k: int):
        """The points (row indices of a call of k points) to compare with separate calls,
        or None: up to CHECK_POINTS spread over a call of a new size (all of a small one),
        then one point every SPOT_EVERY calls, a different one each time."""
        if k in self._sizes:
            self._turn += 1
            return None if self._turn % SPOT_EVERY else [self._turn // SPOT_EVERY % k]
        if k <= CHECK_POINTS:
            return list(range(k))
        return np.linspace(0, k - 1, CHECK_POINTS).round().astype(int).tolist()

    def first(self, k: int) -> bool:
        """Whether a call of k points is the first of its size (not compared yet)."""
        return k not in self._sizes

    def agree(self, ref: np.ndarray, got: np.ndarray, k: int) -> bool:
        """Whether `got` (the vectorised call's values at `rows(k)`) are `ref` (separate
        calls') bit for bit (`same_bits`); if not, vectorised calls are off for good."""
        if not same_bits(ref, got):
            self.off = True
            return False
        self._sizes.add(k)
        return True

    def refuse(self) -> None:
        """A vectorised call failed (raised, or a result of the wrong shape): off for good."""
        self.off = True
