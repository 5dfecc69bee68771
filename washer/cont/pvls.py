"""What a user's `pvls(u, par)` receives on a periodic-orbit run (IPS = 2), and AUTO's
GETP helpers on it.

AUTO's PVLS (user file) is called at every point with the whole discretised solution
and reads it through `GETP(CODE, I, U)`. Here `pvls(u, par)` receives `u` as an
`Orbit`: a numpy array of the node values, shape (NTST*NCOL + 1, NDIM) (exactly the
t-rows of an s-record, so `u[:, 0]` and `u[0]` work as on any array), that also
carries the mesh, the period and the Floquet multipliers, with GETP's codes as
methods:

    AUTO (Fortran)            washer (Python)
    GETP('NRM', i, U)         u.norm(i)           L2 norm sqrt(int_0^1 u_i(t)^2 dt)
    GETP('INT', i, U)         u.integral(i)       int_0^1 u_i(t) dt
    GETP('MAX', i, U)         u.max(i)            max over the nodes
    GETP('MIN', i, U)         u.min(i)            min over the nodes
    GETP('BV0', i, U)         u.bv0(i)            u_i(0)
    GETP('BV1', i, U)         u.bv1(i)            u_i(1)
    GETP('EIG', i, U)         u.multipliers[i-1]  Floquet multiplier i (AUTO's order:
                                                  the one closest to 1 first); None when
                                                  ISP = 0
    GETP('STA', 0, U)         u.n_stable          AUTO's NINS
    GETP('NTST'/'NCOL', ...)  u.ntst, u.ncol
    PAR(11)                   u.period            (the same value as par[10])
    the time mesh             u.t                 node times in [0, 1], (NTPL,)

Component indices are AUTO's, 1-based, so a translated PVLS keeps its numbers.
Integrals use the collocation's own quadrature (AUTO's WINT: exact for the piecewise
polynomial), so u.integral(i) and u.norm(i) equal AUTO's to rounding on the same mesh.
On equilibrium runs (IPS = 0, 1) pvls receives the plain state vector (NDIM,).
"""
from __future__ import annotations

import math
from typing import Callable

import numpy as np


class Orbit(np.ndarray):
    """Node values (NTPL, NDIM) of a periodic solution with its mesh and multipliers.

    Build with `Orbit.of(U, t, weights, period, ntst, ncol, multipliers)`; slicing
    gives plain arrays (the helpers belong to the whole solution only).
    `multipliers` may be a callable evaluated on first use (they cost a condensation
    of the Jacobian)."""

    @classmethod
    def of(cls, U: np.ndarray, t: np.ndarray, weights: np.ndarray, period: float,
           ntst: int, ncol: int, multipliers: Callable | np.ndarray | None = None) -> "Orbit":
        obj = np.array(U, dtype=float).view(cls)
        obj.t = np.asarray(t, float)
        obj.weights = np.asarray(weights, float)
        obj.period = float(period)
        obj.ntst, obj.ncol = int(ntst), int(ncol)
        obj._mult = multipliers
        return obj

    def __getitem__(self, key):
        out = super().__getitem__(key)
        return out.view(np.ndarray) if isinstance(out, np.ndarray) else out

    def __array_wrap__(self, obj, context=None, return_scalar=False):
        # Arithmetic on an orbit gives a plain array (the mesh is not carried along).
        out = np.asarray(obj)
        return out[()] if return_scalar else out

    def _col(self, i: int) -> np.ndarray:
        n = self.shape[1]
        if not 1 <= int(i) <= n:
            raise IndexError(f"component {i}: expected 1..NDIM = {n} (AUTO's 1-based index)")
        return np.asarray(self).view(np.ndarray)[:, int(i) - 1]

    def integral(self, i: int) -> float:
        """GETP('INT', i): int_0^1 u_i(t) dt (t the scaled time: divide by nothing, as AUTO)."""
        return float(self.weights @ self._col(i))

    def norm(self, i: int) -> float:
        """GETP('NRM', i): sqrt(int_0^1 u_i(t)^2 dt)."""
        return math.sqrt(float(self.weights @ self._col(i) ** 2))

    def max(self, i: int | None = None, *args, **kw):      # noqa: A003 (AUTO's name)
        """GETP('MAX', i): the largest node value of u_i. Without i: numpy's max."""
        if i is None or args or kw:
            return np.asarray(self).max(*((i,) if i is not None else ()), *args, **kw)
        return float(np.max(self._col(i)))

    def min(self, i: int | None = None, *args, **kw):      # noqa: A003 (AUTO's name)
        """GETP('MIN', i): the smallest node value of u_i. Without i: numpy's min."""
        if i is None or args or kw:
            return np.asarray(self).min(*((i,) if i is not None else ()), *args, **kw)
        return float(np.min(self._col(i)))

    def bv0(self, i: int) -> float:
        """GETP('BV0', i): u_i(0)."""
        return float(self._col(i)[0])

    def bv1(self, i: int) -> float:
        """GETP('BV1', i): u_i(1)."""
        return float(self._col(i)[-1])

    @property
    def multipliers(self) -> np.ndarray | None:
        """GETP('EIG', i) for i = 1..NDIM: the Floquet multipliers, AUTO's order (the
        one closest to 1 first, the rest by distance from the unit circle); None when
        they are not computed (ISP = 0)."""
        m = self._mult
        if callable(m):
            m = self._mult = m()
        return None if m is None else np.asarray(m)

    @property
    def n_stable(self) -> int | None:
        """GETP('STA', 0): multipliers with |mu| <= 1 + 1e-5 (the trivial one counted)."""
        mu = self.multipliers
        if mu is None:
            return None
        return 1 + int(np.sum(np.abs(mu[1:]) <= 1 + 1e-5))
