"""What the continuation engine solves: u' = f(u, par), AUTO's FUNC and STPNT.

A problem is any object with `ndim`, `func(u, par) -> (ndim,)`, optionally
`dfdu(u, par) -> (ndim, ndim)` and `dfdp(u, par) -> (ndim, npar)`, and
`stpnt(u, par)` filling the starting point in place. Arrays are 0-based as in
AUTO's C interface: par[i - 1] is PAR(i). Missing Jacobians are finite
differences, as AUTO's JAC = 0.

User problems live in NAME.py beside the constants file (e='NAME'):

    def func(u, par):             # required: right-hand side, numpy arrays
    def stpnt(u, par):            # required: fill u and par in place
    def dfdu(u, par): ...         # optional (used when JAC = 1 or -1)
    def dfdp(u, par): ...         # optional (used when JAC = 1)

Built-in problems may also pass `dfdu_batch(us, pars)` (k Jacobians in one
call), which the Hopf-curve Jacobian uses for its k = ndim + 2 perturbed points.
"""
from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np

#: Relative finite-difference step for Jacobians (AUTO uses 1e-7 (1 + |u|) too).
FD_STEP = 1e-7


class ProblemError(RuntimeError):
    """The user's equations are missing, malformed or failed to evaluate."""


class Problem:
    """Wraps user callables with checks and finite-difference fallbacks."""

    def __init__(self, ndim: int, func, stpnt=None, dfdu=None, dfdp=None, name: str = "",
                 npar: int = 36, dfdu_batch=None):
        self.ndim, self.name, self.npar = ndim, name, npar
        self._dfdu_batch = dfdu_batch
        self._func, self._stpnt, self._dfdu, self._dfdp = func, stpnt, dfdu, dfdp
        self.jac_mode = 0            # AUTO's JAC: 0 FD, 1 both analytic, -1 dfdu analytic

    def _call(self, fn, what: str, *args) -> np.ndarray:
        """Call a user function; any failure becomes a ProblemError naming it."""
        try:
            return np.asarray(fn(*args), dtype=float)
        except Exception as exc:
            raise ProblemError(f"{self.name}: {what}(u, par) failed: {type(exc).__name__}: "
                               f"{exc}") from exc

    def func(self, u, par) -> np.ndarray:
        f = self._call(self._func, "func", u, par)
        if f.shape != (self.ndim,):
            raise ProblemError(f"{self.name}: func returned shape {f.shape}, expected ({self.ndim},)")
        return f

    def dfdu_many(self, us, pars) -> np.ndarray:
        """Jacobians at k points at once: us (k, ndim), pars (k, npar) -> (k, ndim, ndim).

        Problems may supply a batched `dfdu_batch(us, pars)` (one call into compiled
        code); otherwise this loops over `dfdu`."""
        if self._dfdu_batch is not None and self.jac_mode != 0:
            return self._call(self._dfdu_batch, "dfdu_batch", us, pars)
        return np.array([self.dfdu(u, p) for u, p in zip(us, pars)])

    def dfdu(self, u, par) -> np.ndarray:
        if self._dfdu is not None and self.jac_mode != 0:
            return self._call(self._dfdu, "dfdu", u, par)
        J = np.empty((self.ndim, self.ndim))
        for i in range(self.ndim):
            h = FD_STEP * (1 + abs(u[i]))
            up, um = u.copy(), u.copy()
            up[i] += h
            um[i] -= h
            J[:, i] = (self.func(up, par) - self.func(um, par)) / (2 * h)
        return J

    def dfdp(self, u, par, indices) -> np.ndarray:
        """Columns d f / d PAR(i) for the 1-based `indices`, shape (ndim, len(indices))."""
        if self._dfdp is not None and self.jac_mode == 1:
            full = self._call(self._dfdp, "dfdp", u, par)
            return full[:, [i - 1 for i in indices]]
        out = np.empty((self.ndim, len(indices)))
        for k, i in enumerate(indices):
            h = FD_STEP * (1 + abs(par[i - 1]))
            pp, pm = par.copy(), par.copy()
            pp[i - 1] += h
            pm[i - 1] -= h
            out[:, k] = (self.func(u, pp) - self.func(u, pm)) / (2 * h)
        return out

    def start(self, npar: int) -> tuple[np.ndarray, np.ndarray]:
        if self._stpnt is None:
            raise ProblemError(f"{self.name}: no stpnt(u, par) to start from (IRS = 0)")
        u, par = np.zeros(self.ndim), np.zeros(npar)
        self._stpnt(u, par)
        return u, par


def load_python_problem(name: str, folder: Path, ndim: int) -> Problem:
    """The user's equations from folder/NAME.py (functions func, stpnt, dfdu, dfdp)."""
    path = folder / f"{name}.py"
    if not path.exists():
        raise ProblemError(f"e='{name}': no equations file {path} (expected func(u, par) and "
                           "stpnt(u, par) there)")
    spec = importlib.util.spec_from_file_location(f"auto_user_{name}", path)
    mod = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(mod)
    except Exception as exc:
        raise ProblemError(f"{path}: failed to import: {exc}") from exc
    if not callable(getattr(mod, "func", None)):
        raise ProblemError(f"{path}: defines no func(u, par)")
    return Problem(ndim, mod.func, getattr(mod, "stpnt", None), getattr(mod, "dfdu", None),
                   getattr(mod, "dfdp", None), name=name)
