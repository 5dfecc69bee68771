"""What the continuation engine solves: u' = f(u, par), AUTO's FUNC, STPNT, PVLS.

A problem wraps the user's callables with checks and finite-difference
fallbacks (AUTO's JAC = 0). Arrays are 0-based as in AUTO's C interface:
par[i - 1] is PAR(i).

User problems live in NAME.py beside the constants file (e='NAME'):

    def func(u, par):             # required: right-hand side, numpy arrays (NDIM,), (NPAR,)
    def stpnt(u, par):            # required for IRS = 0: fill u and par in place
    def dfdu(u, par): ...         # optional (used when JAC = 1 or -1), (NDIM, NDIM)
    def dfdp(u, par): ...         # optional (used when JAC = 1), (NDIM, NPAR)
    def pvls(u, par): ...         # optional, AUTO's PVLS: set PAR entries in place
                                  # from the solution u ((NDIM,) for equilibria; for
                                  # BVPs and periodic orbits a washer.cont.pvls.Orbit:
                                  # (NTPL, NDIM) mesh values with GETP's helpers)
    def bcnd(u0, u1, par): ...    # boundary value problems (IPS = 4), AUTO's BCND:
                                  # the NBC boundary conditions (the first NBC of
                                  # what it returns, as AUTO's FB(1..NBC)), from
                                  # u0 = u(0), u1 = u(1) (NDIM,) each
    def icnd(u, uold, udot, upold, par): ...
                                  # IPS = 4, AUTO's ICND: the NINT integrands, (NINT,),
                                  # at one point t of the mesh: u(t), the previous
                                  # solution uold(t), the branch direction udot(t)
                                  # and upold(t) = f(uold(t)) (for phase conditions);
                                  # the engine integrates them over [0, 1]
    def fopt(u, par): ...         # optimisation (IPS = 5, 15), AUTO's FOPT: the scalar
                                  # objective at the state u (NDIM,) (its derivatives
                                  # are taken by central differences)

Periodically forced problems may supply their flow over one forcing period beside
func, `flow(u0, par, index)` -> (phi_T(u0) (NDIM,), monodromy matrix (NDIM, NDIM),
d phi_T / d PAR(index) (NDIM,)): their periodic orbits (IPS = 2) are then computed by
shooting (washer.cont.systems.shooting).

Built-in problems may also pass batched callables, `func_batch(us, pars)`
((k, NDIM), (k, NPAR) -> (k, NDIM)) and `dfdu_batch(us, pars)` (-> (k, NDIM,
NDIM)): every finite-difference stencil of the engine (Jacobians, the second
and third derivatives of the first Lyapunov coefficient) is evaluated as one
batched call, so a compiled right-hand side pays the Python overhead once per
stencil, not once per point. With `dfdu_batch` and `dfdp_batch` (JAC = 1) the second
derivatives of the fold and Hopf loci are differences of those analytic Jacobians
along the few vectors they are needed on (1 Jacobian per vector, forward from the point's
own), not second differences of f (4 (NDIM + 2) values of f per vector). A problem
whose f comes with its Jacobians at no extra cost (the washer's kernel) may pass
`func_dfdu_batch(us, pars)` (-> (k, NDIM)): f, with dfdu_batch and dfdp_batch at the same
points then answered from that one evaluation (`func_many_with_jacobian`). Where one
column of f_p costs less than all of them, `dfdp_batch_column(us, pars, index)` (-> (k,
NDIM), d f / d PAR(index), the values of dfdp_batch's column) answers dfdp_many.
"""
from __future__ import annotations

import copy
import functools
import inspect
import types
from pathlib import Path

import numpy as np

from washer.cont.differences import (par_points, quotient, shared_step, step, u_points,
                                     u_quotient)
from washer.cont.linalg import all_finite
from washer.cont.pointwise import PointwiseCheck
from washer.cont.pvls import Orbit
#: Batches of at least this many points call a plain user func once with (ndim, k)
#: arrays, checked once on the first call's first VECTORISE_CHECK points against separate
#: calls (rtol 1e-14) and off for good on a mismatch. Not washer.cont.pointwise's bitwise
#: rule: `x ** 2` is a square on an array and libm's pow on a numpy scalar, and the square
#: is AUTO's Fortran x**2 (bvp.py, lin.py and stw.py on arrays are their FUNC bit for bit,
#: separate calls are not: tests/test_hot_path_jacobians.py), which that rule would refuse.
#: Nor does one bitwise rule against calls of one point on (ndim, 1) arrays serve both
#: sizes: it takes numpy's SIMD pow for x ** 3 and up (not correctly rounded at 2.7 % of
#: doubles in [-3, 3], libm's pow at 0.07 %) where small stencils keep separate calls.
VECTORISE_MIN = 12
#: How many points of the first vectorised batch are checked against separate calls.
VECTORISE_CHECK = 32
#: Difference stencils of STENCIL_MIN to VECTORISE_MIN - 1 points (the corrector's of
#: equilibria and the fold and Hopf loci: 6 to 10 points for NDIM 2 and 3) call the func
#: once with (ndim, k) arrays where it gives separate calls' values bit for bit
#: (washer.cont.pointwise); below STENCIL_MIN separate calls are cheaper: one call on
#: arrays of ab.py or lrz.py costs about three separate calls.
STENCIL_MIN = 4
#: Step of the second-derivative stencils, about eps^(1/4) (see second_derivatives).
SECOND_STEP = 1.2e-4
#: Step of the forward differences of analytic Jacobians (second_derivatives with
#: dfdu_batch and dfdp_batch): truncation h |f_uuu| / 2 ~1e-7 relative, rounding
#: eps |f_u| / h ~1e-9 |f_u| / |f_uu| (~1e-7 on the stiff washer, where |f_u| is ~100
#: times |f_uu|). The loci's Newton matrices need no more; central differences would
#: give 1e-11 for twice the Jacobians.
JACOBIAN_STEP = 1e-7
#: The signs (a, b) of the four points z + a h e_s + b k w of a mixed second difference.
_SIGN_A = np.array([1.0, 1.0, -1.0, -1.0])
_SIGN_B = np.array([1.0, -1.0, 1.0, -1.0])
#: A central difference of f in a parameter (step differences.FD_STEP (1 + |PAR(i)|))
#: rounds to about eps T / h ~ 2e-9 T, T the size of f's terms, taken as |f_u| (1 + |u|):
#: a derivative five hundred times that is f's own (`Problem.unset_dfdp`).
DEPENDENCE_FLOOR = 1e-6


def user_frame(exc: BaseException) -> str:
    """' (FILE:LINE)' of the deepest traceback frame of `exc` in the user's own code (not
    washer's, not the standard library's or an installed package's), or '': where a
    user's func, stpnt, pvls ... failed."""
    import sysconfig
    import traceback
    # whole folders (a user's folder named washer2 beside the package is the user's)
    skip = [Path(__file__).resolve().parents[1]] + [
        Path(p).resolve() for k, p in sysconfig.get_paths().items()
        if k in ("stdlib", "platstdlib", "purelib", "platlib")]
    where = ""
    for fr in traceback.extract_tb(exc.__traceback__):
        name = fr.filename or ""
        if not name or name.startswith("<"):
            continue
        full = Path(name).resolve()
        if any(full.is_relative_to(folder) for folder in skip):
            continue
        where = f" ({name}:{fr.lineno})"
    return where


def broadcast_rows(par: np.ndarray, k: int) -> np.ndarray:
    """np.broadcast_to(par, (k, len(par))) for a 1-D float array: the same read-only
    view (row stride 0) without broadcast_to's generic set-up (several us; func_many
    makes one per stencil)."""
    par = np.ascontiguousarray(par)
    v = np.ndarray((k, par.shape[0]), dtype=par.dtype, buffer=par, strides=(0, par.itemsize))
    v.flags.writeable = False
    return v


class ProblemError(RuntimeError):
    """The user's equations are missing, malformed or failed to evaluate."""


class ProblemWarning(UserWarning):
    """The user's equations look inconsistent (a derivative they give disagrees with f)."""


def user_failure(name: str, what: str, exc: BaseException) -> "ProblemError":
    """The ProblemError of a user function that raised: '{name}: {what} failed:
    {exception type}: {message} (FILE:LINE)', the place as `user_frame` finds it."""
    return ProblemError(f"{name}: {what} failed: {type(exc).__name__}: {exc}{user_frame(exc)}")


class Problem:
    """The user's equations with checks and batched finite-difference fallbacks.

    `npar` is the length of PAR the equations need (0: no requirement; the run's
    NPAR is raised to it). `jac` is AUTO's JAC: 0 finite differences, 1 dfdu and dfdp supplied,
    -1 dfdu only. Use `with_jac` for a configured copy (problems are never
    changed behind their owner's back).
    """

    #: The file the equations come from, where there is one (messages name it).
    source: str = ""

    def __init__(self, ndim: int, func, stpnt=None, dfdu=None, dfdp=None, name: str = "",
                 npar: int = 0, dfdu_batch=None, func_batch=None, pvls=None,
                 parnames: dict | None = None, unames: dict | None = None, jac: int = 0,
                 bcnd=None, icnd=None, flow=None, fopt=None, fopt_batch=None,
                 dfdp_batch=None, func_dfdu_batch=None, dfdp_batch_column=None):
        self.ndim, self.name, self.npar = ndim, name, npar
        self._func_dfdu_batch = func_dfdu_batch
        self._fopt, self._fopt_batch = fopt, fopt_batch
        self._fopt_vectorised = None      # does fopt accept (ndim, k) arrays? (checked once)
        self._flow = flow
        self._bcnd, self._icnd = bcnd, icnd
        self._icnd_vectorised = None      # does icnd accept (ndim, k) arrays? (checked once)
        self._func, self._stpnt, self._dfdu, self._dfdp = func, stpnt, dfdu, dfdp
        self._dfdu_batch, self._func_batch, self._pvls = dfdu_batch, func_batch, pvls
        self._dfdp_batch, self._dfdp_batch_column = dfdp_batch, dfdp_batch_column
        self._vectorised = None       # does func accept (ndim, k) arrays? (checked once)
        self._pointwise = PointwiseCheck()    # func on the arrays of a small stencil
        self.parnames = dict(parnames or {})
        self.unames = dict(unames or {})
        self.jac = jac

    def with_jac(self, jac: int) -> "Problem":
        """A copy using AUTO's JAC = jac (0, 1 or -1)."""
        p = copy.copy(self)
        p.jac = jac
        return p

    def fresh(self) -> None:
        """A new run begins (AUTO starts each run in a new process): equations that keep
        state between calls start afresh. Nothing to do for Python problems."""

    @property
    def has_dfdu(self) -> bool:
        """Whether f_u is the user's own (JAC != 0 and a Jacobian given), not differences."""
        return self.jac != 0 and (self._dfdu is not None or self._dfdu_batch is not None)

    @property
    def has_pvls(self) -> bool:
        return self._pvls is not None

    @property
    def has_fopt(self) -> bool:
        """Whether the problem has an objective (AUTO's FOPT, IPS = 5 and 15)."""
        return self._fopt is not None or self._fopt_batch is not None

    def fopt_many(self, us, pars) -> np.ndarray:
        """The objective FOPT at k points: us (k, ndim), pars (k, npar) or (npar,) -> (k,)."""
        us = np.asarray(us, dtype=float)
        pars = np.asarray(pars, dtype=float)
        if not self.has_fopt:
            raise ProblemError(f"{self.name}: no objective: optimisation (IPS = 5, 15) needs "
                               "fopt(u, par) (AUTO's FOPT)")
        if self._fopt_batch is not None:
            out = self._call(self._fopt_batch, "fopt", us, pars)
        else:
            if pars.ndim == 1:
                pars = np.broadcast_to(pars, (len(us), len(pars)))
            out = None
            if self._fopt_vectorised is not False and len(us) >= VECTORISE_MIN:
                out = self._fopt_at_once(us, pars)
            if out is None:
                try:
                    out = np.array([float(self._fopt(u, p)) for u, p in zip(us, pars)])
                except Exception as exc:
                    raise user_failure(self.name, "fopt(u, par)", exc) from exc
        if out.shape != (len(us),) or not np.all(np.isfinite(out)):
            raise ProblemError(f"{self.name}: fopt(u, par) returned non-finite or non-scalar "
                               "values; expected one finite number per point")
        return out

    def fopt_gradient(self, us, par, indices=(), with_u: bool = True):
        """AUTO's FOPI: central differences of FOPT at the rows of us (k, NDIM), in u with
        each row's step HMACH (1 + max_i |u_i|), in PAR(i) for the 1-based `indices` with
        HMACH (1 + |PAR(i)|), all in one fopt_many batch. Returns (grad_u (k, NDIM), or None
        without `with_u`; d FOPT / d PAR(indices) (k, len(indices)))."""
        us = np.atleast_2d(np.asarray(us, dtype=float))
        par = np.asarray(par, dtype=float)
        k, n = us.shape
        m, nu = len(indices), (n if with_u else 0)
        hu = step(np.max(np.abs(us), axis=1))
        hp = np.array([step(par[i - 1]) for i in indices])
        s = 2 * (nu + m)
        U = np.repeat(us[:, None], s, axis=1)
        P = np.repeat(par[None, None], k, axis=0).repeat(s, axis=1)
        for j in range(nu):
            U[:, 2 * j, j] += hu
            U[:, 2 * j + 1, j] -= hu
        for q, i in enumerate(indices):
            P[:, 2 * (nu + q), i - 1] += hp[q]
            P[:, 2 * (nu + q) + 1, i - 1] -= hp[q]
        F = self.fopt_many(U.reshape(-1, n), P.reshape(k * s, -1)).reshape(k, s)
        gu = quotient(F[:, 0:2 * nu:2], F[:, 1:2 * nu:2], hu[:, None]) if with_u else None
        return gu, quotient(F[:, 2 * nu::2], F[:, 2 * nu + 1::2], hp) if m else np.zeros((k, 0))

    def _fopt_at_once(self, us, pars):
        """fopt at k points in one call with u (ndim, k), par (npar, k), as func's
        `_call_vectorised`: checked once against separate calls, off for good on any
        failure or mismatch (then None)."""
        try:
            with np.errstate(all="ignore"):
                out = np.asarray(self._fopt(us.T, pars.T), dtype=float)
            if out.shape != (len(us),):
                raise ValueError("shape")
        except Exception:
            self._fopt_vectorised = False
            return None
        if self._fopt_vectorised is None:
            try:
                ref = np.array([float(self._fopt(u, p)) for u, p in zip(us, pars)])
            except Exception:
                self._fopt_vectorised = False
                return None
            self._fopt_vectorised = bool(np.allclose(ref, out, rtol=1e-14, atol=0))
            return ref
        return out

    @property
    def has_flow(self) -> bool:
        return self._flow is not None

    def period_map(self, u0, par, index: int):
        """(phi_T(u0) (NDIM,), Phi (NDIM, NDIM), d phi_T / d PAR(index) (NDIM,)) from the
        problem's flow over one forcing period, checked."""
        if self._flow is None:
            raise ProblemError(f"{self.name}: no flow(u0, par, index) for shooting")
        try:
            uT, Phi, dp = self._flow(np.asarray(u0, float), np.asarray(par, float), index)
        except ProblemError:
            raise
        except Exception as exc:
            raise user_failure(self.name, f"flow(u0, par, {index})", exc) from exc
        n = self.ndim
        uT, Phi, dp = (np.asarray(a, dtype=float) for a in (uT, Phi, dp))
        if uT.shape != (n,) or Phi.shape != (n, n) or dp.shape != (n,):
            raise ProblemError(f"{self.name}: flow returned shapes {uT.shape}, {Phi.shape}, "
                               f"{dp.shape}; expected ({n},), ({n}, {n}), ({n},)")
        if not (np.all(np.isfinite(uT)) and np.all(np.isfinite(Phi))):
            raise ProblemError(f"{self.name}: flow returned non-finite values")
        return uT, Phi, dp

    # ------------------------------------------------------------------ calls
    def _call(self, fn, what: str, *args) -> np.ndarray:
        """Call a user function; any failure becomes a ProblemError naming it.
        (Floating-point warnings of trial points are silenced by the runner.)"""
        try:
            return np.asarray(fn(*args), dtype=float)
        except ProblemError:
            raise
        except Exception as exc:
            raise user_failure(self.name, f"{what}(u, par)", exc) from exc

    def func(self, u, par) -> np.ndarray:
        f = self._call(self._func, "func", u, par)
        if f.shape != (self.ndim,):
            raise ProblemError(f"{self.name}: func returned shape {f.shape}, expected ({self.ndim},)")
        if not all_finite(f):
            raise ProblemError(f"{self.name}: func(u, par) returned non-finite values at "
                               f"u = {np.array2string(np.asarray(u), precision=6)}")
        return f

    def func_many(self, us, pars) -> np.ndarray:
        """f at k points: us (k, ndim), pars (k, npar) or (npar,) -> (k, ndim)."""
        us = np.asarray(us, dtype=float)
        pars = np.asarray(pars, dtype=float)
        if pars.ndim == 1:
            pars = broadcast_rows(pars, len(us))
        if self._func_batch is not None:
            out = self._call(self._func_batch, "func_batch", us, np.ascontiguousarray(pars))
            if out.shape != (len(us), self.ndim):
                raise ProblemError(f"{self.name}: func_batch returned shape {out.shape}, "
                                   f"expected ({len(us)}, {self.ndim})")
            return out
        k = len(us)
        if k >= VECTORISE_MIN and self._vectorised is not False:
            out = self._call_vectorised(us, pars)
            if out is not None:
                return out
        elif STENCIL_MIN <= k < VECTORISE_MIN and not self._pointwise.off:
            out = self._call_stencil(us, pars)
            if out is not None:
                return out
        # Point by point: the user's func directly (one wrapper and one check for
        # the whole stencil, not per point: small problems are dominated by that).
        fn = self._func
        try:
            out = np.array([fn(u, p) for u, p in zip(us, pars)], dtype=float)
        except Exception as exc:
            raise user_failure(self.name, "func(u, par)", exc) from exc
        if out.shape != (len(us), self.ndim):
            raise ProblemError(f"{self.name}: func returned shape {out.shape[1:]}, expected "
                               f"({self.ndim},)")
        if not np.isfinite(out).all():
            raise ProblemError(f"{self.name}: func(u, par) returned non-finite values")
        return out

    @property
    def has_func_batch(self) -> bool:
        """Whether f at many points is the user's func_batch (one call for them all)."""
        return self._func_batch is not None

    @property
    def user_func(self):
        """The user's func(u, par) itself, without `func`'s checks: what the difference
        stencils call point by point (`_jacobian_by_calls`), checking the whole stencil
        once."""
        return self._func

    @property
    def has_func_dfdu_batch(self) -> bool:
        """Whether `func_many_with_jacobian` evaluates the Jacobians with f (a
        func_dfdu_batch given and the user's Jacobians in use, JAC != 0)."""
        return getattr(self, "_func_dfdu_batch", None) is not None and self.jac != 0

    def func_many_with_jacobian(self, us, pars) -> np.ndarray:
        """`func_many`, for points whose Jacobians are asked for next: a problem whose f
        is a by-product of its Jacobians (func_dfdu_batch: the washer's kernel) computes
        them in the same pass, and its dfdu_batch / dfdp_batch at these points then
        return them without a second evaluation. The same values as func_many."""
        if not self.has_func_dfdu_batch:
            return self.func_many(us, pars)
        us = np.asarray(us, dtype=float)
        pars = np.asarray(pars, dtype=float)
        if pars.ndim == 1:
            pars = broadcast_rows(pars, len(us))
        out = self._call(self._func_dfdu_batch, "func_dfdu_batch", us, np.ascontiguousarray(pars))
        if out.shape != (len(us), self.ndim):
            raise ProblemError(f"{self.name}: func_dfdu_batch returned shape {out.shape}, "
                               f"expected ({len(us)}, {self.ndim})")
        return out

    def _call_vectorised(self, us, pars):
        """f at k points in one call of the user's func with u (ndim, k) and par
        (npar, k) (numpy broadcasting: `u[0] * par[1]` works on rows). The first
        call is checked, on its first VECTORISE_CHECK points, against separate calls;
        any failure or mismatch turns it off for good (None: evaluate point by point)."""
        try:
            with np.errstate(all="ignore"):
                out = np.asarray(self._func(us.T, pars.T), dtype=float)
            if out.shape != (self.ndim, len(us)):
                raise ValueError("shape")
            out = out.T
        except Exception:
            self._vectorised = False
            return None
        if self._vectorised is None:
            # The check: the first VECTORISE_CHECK points against separate calls (a
            # func that mixes points, reducing over the batch, shows it there; checking
            # every point of a first call of 6400, NTST 200's difference stencil, cost
            # a short run a fifth of its time). On a mismatch the caller evaluates the
            # whole call point by point.
            m = min(len(us), VECTORISE_CHECK)
            ref = np.array([self.func(u, p) for u, p in zip(us[:m], pars[:m])])
            same = np.array_equal(ref, out[:m]) or np.allclose(ref, out[:m], rtol=1e-14,
                                                               atol=0)
            self._vectorised = bool(same)
            if not same:
                return None
        return out

    def _call_stencil(self, us, pars):
        """f at the k points of a small stencil (STENCIL_MIN <= k < VECTORISE_MIN) in one
        call of the user's func with u (ndim, k) and par (npar, k), where it gives
        separate calls' values bit for bit at the points washer.cont.pointwise compares
        (all of a first call of each size, up to its CHECK_POINTS, then one every
        SPOT_EVERY calls); None where it does not (off for good: the caller evaluates
        point by point), or where a value is not finite (the point-by-point evaluation
        reports it)."""
        check, k, fn = self._pointwise, len(us), self._func
        rows = check.rows(k)
        try:
            if check.first(k):
                # the first call of its size may be a func not meant for arrays: quiet
                with np.errstate(all="ignore"):
                    out = np.asarray(fn(us.T, pars.T), dtype=float)
            else:
                out = np.asarray(fn(us.T, pars.T), dtype=float)
            if out.shape != (self.ndim, k):
                raise ValueError("not one column per point")
        except Exception:
            check.refuse()
            return None
        # (k, ndim) in C order, as the point-by-point route gives it: the values are the
        # same bits, and so must be what is computed from them (a BLAS product or LAPACK
        # call may round otherwise on a transposed layout)
        out = np.ascontiguousarray(out.T)
        if rows is not None:
            try:
                # separate calls as func_many makes them, each with arrays of its own
                if len(rows) == 1:
                    j = rows[0]
                    ref, got = np.asarray(fn(us[j].copy(), pars[j].copy()), dtype=float), out[j]
                else:
                    ref = np.array([fn(us[j].copy(), pars[j].copy()) for j in rows],
                                   dtype=float)
                    got = out[rows]
            except Exception:
                return None       # the point-by-point evaluation raises it, and reports
            if not check.agree(ref, got, k):
                return None
        return out if all_finite(out) else None

    def dfdu(self, u, par, shared: bool = False) -> np.ndarray:
        """(ndim, ndim) Jacobian: the user's (JAC != 0) or central differences in one batch
        (shared: every component moved by one step, AUTO's FUNI's, `differences.shared_step`)."""
        if self._dfdu is not None and self.jac != 0:
            J = self._call(self._dfdu, "dfdu", u, par)
            if J.shape != (self.ndim, self.ndim):
                raise ProblemError(f"{self.name}: dfdu returned shape {J.shape}, expected "
                                   f"({self.ndim}, {self.ndim})")
            if not np.isfinite(J).all():
                raise ProblemError(f"{self.name}: dfdu(u, par) returned non-finite values")
            return J
        u = np.asarray(u, dtype=float)
        if shared:
            h = np.full(len(u), shared_step(u))
        elif self.stencil_by_calls(0):
            return self._jacobian_by_calls(u, np.asarray(par, dtype=float), [])
        else:
            h = step(u)
        E = np.diag(h)
        F = self.func_many(np.vstack([u + E, u - E]), par)
        n = self.ndim
        return quotient(F[:n], F[n:], h[:, None]).T

    @property
    def differenced_jacobian(self) -> bool:
        """Whether `jacobian` takes central differences of f for [f_u, f_p] (neither the
        user's dfdu with JAC != 0 nor the user's dfdp with JAC = 1 in use)."""
        return not ((self._dfdu is not None and self.jac != 0)
                    or (self._dfdp is not None and self.jac == 1))

    def stencil_by_calls(self, m: int) -> bool:
        """Whether central differences over u and m parameters, 2 (NDIM + m) points, are
        evaluated one call of the user's func per point (`_jacobian_by_calls`, as
        func_many makes them): no batched func, and fewer points than STENCIL_MIN, or
        fewer than VECTORISE_MIN and a func not called on arrays (washer.cont.pointwise
        refused it). Asked at each stencil: the answer changes when a call is refused."""
        k = 2 * (self.ndim + m)
        return self._func_batch is None and (k < STENCIL_MIN or k < VECTORISE_MIN
                                             and self._pointwise.off)

    def jacobian(self, u, par, indices) -> np.ndarray:
        """[f_u, f_PAR(indices)], shape (ndim, ndim + len(indices)): the user's
        Jacobians where JAC allows, else central differences over u and the
        parameters together, one stencil of 2 (ndim + m) points (AUTO's FUNI)."""
        if not self.differenced_jacobian:
            return np.hstack([self.dfdu(u, par), self.dfdp(u, par, indices)])
        u = np.asarray(u, dtype=float)
        par = np.asarray(par, dtype=float)
        n, m = self.ndim, len(indices)
        k = n + m
        pidx = [i - 1 for i in indices]
        if self.stencil_by_calls(m):
            return self._jacobian_by_calls(u, par, pidx)
        z = np.concatenate((u, par[pidx]))
        h = step(z)
        us = np.repeat(u[None, :], 2 * k, axis=0)
        ps = np.repeat(par[None, :], 2 * k, axis=0)
        idx = np.arange(n)
        us[idx, idx] += h[:n]
        us[k + idx, idx] -= h[:n]
        for j, i in enumerate(pidx):
            ps[n + j, i] += h[n + j]
            ps[k + n + j, i] -= h[n + j]
        F = self.func_many(us, ps)
        return quotient(F[:k], F[k:], h[:, None]).T

    def _jacobian_by_calls(self, u, par, pidx) -> np.ndarray:
        """`jacobian`'s central differences for a small stencil, one call of the user's
        func per point (as func_many makes them below VECTORISE_MIN points), the stencil
        built in Python floats: the same points (u_j +- h_j, PAR +- h), the same
        quotients, bit for bit, without the array set-up that costs more than the calls
        at these sizes. Every call gets its own copies of u and par."""
        n = self.ndim
        ul, pl = u.tolist(), par.tolist()
        hs = [step(v) for v in ul] + [step(pl[i]) for i in pidx]
        fn = self._func
        rows = []
        try:
            for sign in (1.0, -1.0):              # x + (-h) is x - h exactly (IEEE)
                for j in range(n):
                    a = u.copy()
                    a[j] = ul[j] + sign * hs[j]
                    rows.append(fn(a, par.copy()))
                for jj, i in enumerate(pidx):
                    b = par.copy()
                    b[i] = pl[i] + sign * hs[n + jj]
                    rows.append(fn(u.copy(), b))
            F = np.array(rows, dtype=float)
        except Exception as exc:
            raise user_failure(self.name, "func(u, par)", exc) from exc
        k = len(hs)
        if F.shape != (2 * k, n):
            raise ProblemError(f"{self.name}: func returned shape {F.shape[1:]}, expected "
                               f"({n},)")
        if not np.isfinite(F).all():
            raise ProblemError(f"{self.name}: func(u, par) returned non-finite values")
        return quotient(F[:k], F[k:], np.array(hs)[:, None]).T

    def dfdu_many(self, us, pars) -> np.ndarray:
        """Jacobians at k points at once: us (k, ndim), pars (k, npar) -> (k, ndim, ndim)."""
        if self._dfdu_batch is not None and self.jac != 0:
            return self._call(self._dfdu_batch, "dfdu_batch", us, pars)
        if self._dfdu is not None and self.jac != 0:
            return np.array([self.dfdu(u, p) for u, p in zip(us, pars)])
        # Central differences at all k points in one batched call.
        us = np.asarray(us, dtype=float)
        pars = np.asarray(pars, dtype=float)
        k, n = us.shape
        pts, h = u_points(us)
        # one parameter vector for all points (the callers' broadcast view, row stride 0)
        # stays a view: only its values reach the user's func
        rep = (broadcast_rows(pars[0], 2 * n * k)
               if k and pars.ndim == 2 and pars.strides[0] == 0 else np.repeat(pars, 2 * n, axis=0))
        return u_quotient(self.func_many(pts, rep), h)

    @property
    def has_dfdp_batch(self) -> bool:
        """Whether dfdp_many uses the user's batched dfdp (supplied, JAC = 1)."""
        return self._dfdp_batch is not None and self.jac == 1

    def dfdp_many(self, us, pars, index: int) -> np.ndarray:
        """d f / d PAR(index) at k points from the user's dfdp_batch (JAC = 1): us (k, ndim),
        pars (k, npar) -> (k, ndim)."""
        if not self.has_dfdp_batch:
            raise ProblemError(f"{self.name}: no batched dfdp (dfdp_batch with JAC = 1)")
        us = np.asarray(us, dtype=float)
        if self._dfdp_batch_column is not None:
            col = self._call(self._dfdp_batch_column, "dfdp_batch_column", us, pars, index)
            if col.shape != (len(us), self.ndim):
                raise ProblemError(f"{self.name}: dfdp_batch_column returned shape {col.shape}, "
                                   f"expected ({len(us)}, {self.ndim})")
        else:
            out = self._call(self._dfdp_batch, "dfdp_batch", us, pars)
            if out.ndim != 3 or out.shape[:2] != (len(us), self.ndim) or out.shape[2] < index:
                raise ProblemError(f"{self.name}: dfdp_batch returned shape {out.shape}, "
                                   f"expected ({len(us)}, {self.ndim}, >= {index})")
            col = out[:, :, index - 1]
        if not np.all(np.isfinite(col)):
            raise ProblemError(f"{self.name}: dfdp_batch returned non-finite values")
        return col

    def dfdp(self, u, par, indices) -> np.ndarray:
        """Columns d f / d PAR(i) for the 1-based `indices`, shape (ndim, len(indices))."""
        if self._dfdp is not None and self.jac == 1:
            full = self._call(self._dfdp, "dfdp", u, par)
            if full.ndim != 2 or full.shape[0] != self.ndim or full.shape[1] < max(indices):
                raise ProblemError(f"{self.name}: dfdp returned shape {full.shape}, expected "
                                   f"({self.ndim}, >= {max(indices)})")
            return full[:, [i - 1 for i in indices]]
        return self._dfdp_differences(u, par, indices)

    def _dfdp_differences(self, u, par, indices) -> np.ndarray:
        """`dfdp`'s central differences of f, shape (ndim, len(indices))."""
        par = np.asarray(par, dtype=float)
        m = len(indices)
        points = [par_points(par, i) for i in indices]
        h = np.array([hi for hi, _, _ in points])
        pars = np.array([pp for _, pp, _ in points] + [pm for _, _, pm in points]).reshape(
            2 * m, len(par))
        F = self.func_many(np.repeat(np.asarray(u, float)[None, :], 2 * m, axis=0), pars)
        return quotient(F[:m], F[m:], h[:, None]).T

    def unset_dfdp(self, u, par, indices) -> list[tuple[int, float]]:
        """(i, max_j |d f_j / d PAR(i)|) for each 1-based index i of `indices` whose
        column of the user's dfdp (in use: JAC = 1) is exactly zero at (u, par) while a
        central difference of f shows f moving with PAR(i), above DEPENDENCE_FLOOR
        (1 + |f_u| (1 + |u|)). AUTO's FUNC gets DFDP zero-filled and a user file that
        never sets it (AUTO's she.f) gives zero parameter derivatives, which Newton takes
        as exact. Empty without a user dfdp in use."""
        if self._dfdp is None or self.jac != 1 or not indices:
            return []
        u = np.asarray(u, dtype=float)
        given = self.dfdp(u, par, indices)
        zero = [j for j in range(len(indices)) if not np.any(given[:, j])]
        if not zero:
            return []
        found = self._dfdp_differences(u, par, [indices[j] for j in zero])
        terms = float(np.max(np.abs(self.dfdu(u, par)), initial=0.0)) * \
            (1 + float(np.max(np.abs(u), initial=0.0)))
        size = np.max(np.abs(found), axis=0)
        return [(indices[j], float(d)) for j, d in zip(zero, size)
                if d > DEPENDENCE_FLOOR * (1 + terms)]

    def second_derivatives(self, u, par, ws, par_indices) -> np.ndarray:
        """Mixed second derivatives f_zz[e_s, w_k] along every unit direction e_s
        of z = (u, PAR(par_indices)) and the state vectors w_k, from f alone:

            [f(z + h e_s + k w) - f(z + h e_s - k w) - f(z - h e_s + k w)
             + f(z - h e_s - k w)] / (4 h k)

        all 4 (ndim + len(par_indices)) len(ws) points in one batched call.
        ws: (m, ndim). Returns (ndim + len(par_indices), m, ndim). Steps are
        eps^(1/4) scaled (central O(h^2) truncation ~1e-8 against rounding
        eps / (h k) ~1e-8); a derivative of f costs one f per point here,
        where differencing Jacobians costs a Jacobian per point (but see
        _second_from_jacobians: batched analytic Jacobians, differenced along each w_k).
        include/ae_correct.h repeats this stencil in C for the fold and Hopf loci: a
        change here is made there too."""
        u = np.asarray(u, dtype=float)
        par = np.asarray(par, dtype=float)
        ws = np.atleast_2d(np.asarray(ws, dtype=float))
        if self._dfdu_batch is not None and self.has_dfdp_batch:
            return self._second_from_jacobians(u, par, ws, par_indices)
        n, m, q = self.ndim, len(ws), len(par_indices)
        ns, npar = n + q, len(par)
        pidx = [i - 1 for i in par_indices]
        h = SECOND_STEP * (1 + np.abs(np.concatenate((u, par[pidx]))))
        wn = np.maximum(np.abs(ws).max(axis=1), 1e-300)
        k = SECOND_STEP * (1 + np.abs(u).max()) / wn                        # (m,)
        # z + a h e_s + b k w, in that order of additions, for all s and the four sign
        # pairs (a, b) = (1, 1), (1, -1), (-1, 1), (-1, -1) at once
        us = np.empty((ns, m, 4, n))
        np.add(u, _SIGN_B[:, None] * (k[:, None] * ws)[:, None, :], out=us)
        ah = _SIGN_A * h[:, None]                                            # (ns, 4)
        # one direction at a time: basic slices (the same additions as one fancy-indexed
        # update, which costs more than the whole loop at these sizes)
        for j in range(n):
            us[j, :, :, j] += ah[j]
        ps = np.empty((ns, m, 4, npar))
        ps[:] = par
        for j, i in enumerate(pidx):
            ps[n + j, :, :, i] += ah[n + j]
        F = self.func_many(us.reshape(-1, n), ps.reshape(-1, npar)).reshape(ns, m, 4, n)
        num = F[:, :, 0] - F[:, :, 1] - F[:, :, 2] + F[:, :, 3]
        return num / (4 * h[:, None, None] * k[None, :, None])

    def _second_from_jacobians(self, u, par, ws, par_indices) -> np.ndarray:
        """second_derivatives from batched analytic Jacobians (dfdu_batch, dfdp_batch,
        JAC = 1): f_zz[e_s, w] = d/de of column s of [f_u, f_PAR(par_indices)] at
        (u + e w, par), forward differences with step JACOBIAN_STEP (1 + max|u|) / max|w|
        from the Jacobians at (u, par) themselves (dfdu, dfdp: the loci ask for them at the
        same point first, so a problem that remembers its last point computes them once),
        the len(ws) points in one batched call of each. Shape (n + q, m, n)."""
        n, m = self.ndim, len(ws)
        k = JACOBIAN_STEP * (1 + np.max(np.abs(u))) / np.maximum(np.max(np.abs(ws), axis=1),
                                                                   1e-300)
        us = u + k[:, None] * ws
        pars = np.repeat(par[None, :], m, axis=0)
        fu = self._call(self._dfdu_batch, "dfdu_batch", us, pars)
        fp = self._call(self._dfdp_batch, "dfdp_batch", us, pars)
        q = max(par_indices, default=0)
        if fu.shape != (m, n, n) or fp.ndim != 3 or fp.shape[:2] != (m, n) or fp.shape[2] < q:
            raise ProblemError(f"{self.name}: dfdu_batch, dfdp_batch returned shapes "
                               f"{fu.shape}, {fp.shape}, expected ({m}, {n}, {n}) and "
                               f"({m}, {n}, >= {q})")
        D = np.concatenate((fu, fp[:, :, [i - 1 for i in par_indices]]), axis=2)
        if not np.all(np.isfinite(D)):
            raise ProblemError(f"{self.name}: dfdu_batch or dfdp_batch returned non-finite "
                               "values")
        base = np.hstack((self.dfdu(u, par), self.dfdp(u, par, par_indices)))
        T = (D - base) / k[:, None, None]                      # (m, n, n + q): [k, i, s]
        return np.transpose(T, (2, 0, 1))

    def pvls(self, u, par) -> np.ndarray:
        """PAR after the user's pvls(u, par) (a copy; unchanged without pvls)."""
        par = np.array(par, dtype=float)
        if self._pvls is not None:
            try:
                # An Orbit (washer.cont.pvls: a BVP solution with its mesh and AUTO's
                # GETP helpers) is a fresh array already: passed as it is.
                self._pvls(u if isinstance(u, Orbit) else np.array(u, dtype=float), par)
            except Exception as exc:
                raise user_failure(self.name, "pvls(u, par)", exc) from exc
        return par

    def bcnd(self, u0, u1, par, nbc: int) -> np.ndarray:
        """AUTO's BCND: the (nbc,) boundary conditions at u(0) = u0, u(1) = u1."""
        if self._bcnd is None:
            raise ProblemError(f"{self.name}: NBC = {nbc} boundary conditions but no "
                               "bcnd(u0, u1, par)")
        fb = np.atleast_1d(self._call(self._bcnd, "bcnd", u0, u1, par))
        if fb.ndim == 1 and len(fb) > nbc:
            fb = fb[:nbc]                 # the first NBC, as AUTO's FB(1..NBC)
        if fb.shape != (nbc,):
            raise ProblemError(f"{self.name}: bcnd returned shape {fb.shape}, expected "
                               f"({nbc},) (NBC)")
        if not np.all(np.isfinite(fb)):
            raise ProblemError(f"{self.name}: bcnd(u0, u1, par) returned non-finite values")
        return fb

    def icnd(self, u, uold, udot, upold, par, nint: int) -> np.ndarray:
        """AUTO's ICND: the (nint,) integrands at one mesh point."""
        if self._icnd is None:
            raise ProblemError(f"{self.name}: NINT = {nint} integral conditions but no "
                               "icnd(u, uold, udot, upold, par)")
        fi = np.atleast_1d(self._call(self._icnd, "icnd", u, uold, udot, upold, par))
        if fi.ndim == 1 and len(fi) > nint:
            fi = fi[:nint]                # the first NINT, as AUTO's FI(1..NINT)
        if fi.shape != (nint,):
            raise ProblemError(f"{self.name}: icnd returned shape {fi.shape}, expected "
                               f"({nint},) (NINT)")
        if not np.all(np.isfinite(fi)):
            raise ProblemError(f"{self.name}: icnd(u, uold, udot, upold, par) returned "
                               "non-finite values")
        return fi

    def icnd_many(self, U, Uold, Udot, Upold, par, nint: int) -> np.ndarray:
        """The integrands at k mesh points at once: each argument (k, ndim) -> (k, nint).
        A user's icnd written with numpy operations on rows (`u[0] - par[1]`) is called
        once with (ndim, k) arrays, after a first call has been checked point by point;
        otherwise once per point (one check for the whole batch)."""
        if self._icnd is None:
            raise ProblemError(f"{self.name}: NINT = {nint} integral conditions but no "
                               "icnd(u, uold, udot, upold, par)")
        args = [np.asarray(a, dtype=float) for a in (U, Uold, Udot, Upold)]
        k = len(args[0])
        if self._icnd_vectorised is not False and k > 1:
            try:
                with np.errstate(all="ignore"):
                    out = np.asarray(self._icnd(*[a.T for a in args], par), dtype=float)
                if out.ndim != 2 or out.shape[1] != k or out.shape[0] < nint:
                    raise ValueError("not a batch")
                out = out[:nint].T
            except Exception:
                self._icnd_vectorised = False
            else:
                if self._icnd_vectorised is None:
                    ref = np.array([self.icnd(*[a[j] for a in args], par, nint)
                                    for j in range(k)])
                    self._icnd_vectorised = bool(np.allclose(ref, out, rtol=1e-13, atol=0))
                    return ref
                if np.all(np.isfinite(out)):
                    return np.array(out)
        fn = self._icnd
        try:
            out = np.array([np.atleast_1d(fn(*[a[j] for a in args], par))[:nint]
                            for j in range(k)], dtype=float)
        except Exception as exc:
            raise user_failure(self.name, "icnd(u, uold, udot, upold, par)", exc) from exc
        if out.shape != (k, nint):
            raise ProblemError(f"{self.name}: icnd returned shape {out.shape[1:]}, expected "
                               f"({nint},) (NINT)")
        if not np.all(np.isfinite(out)):
            raise ProblemError(f"{self.name}: icnd(u, uold, udot, upold, par) returned "
                               "non-finite values")
        return out

    @functools.cached_property
    def stpnt_has_time(self) -> bool:
        """Whether stpnt takes AUTO's time argument: stpnt(u, par, t), t in [0, 1]
        (a periodic orbit's start for IPS = 2). Looked up once per problem (a signature
        costs a tenth of a millisecond)."""
        f = self._stpnt
        if f is None:
            return False
        if type(f) is types.FunctionType and not hasattr(f, "__wrapped__") \
                and not hasattr(f, "__signature__"):
            # a plain function's positional parameters are its code's co_argcount (what
            # the signature below reads from it), without the signature's tenth of a ms
            code = f.__code__
            return code.co_argcount >= 3 or bool(code.co_flags & inspect.CO_VARARGS)
        try:
            params = inspect.signature(f).parameters.values()
        except (TypeError, ValueError):
            return False
        positional = [p for p in params if p.kind in (p.POSITIONAL_ONLY,
                                                      p.POSITIONAL_OR_KEYWORD)]
        return len(positional) >= 3 or any(p.kind == p.VAR_POSITIONAL for p in params)

    def start_profile(self, par, times, ndim: int | None = None) -> np.ndarray:
        """AUTO's STPNUB: stpnt(u, par, t) at every time of `times` in turn, with one
        PAR array throughout (an stpnt that sets PAR at t = 0 and reads it later, as
        fsh's, sees its own values). Returns the states, shape (len(times), ndim);
        `par` is changed in place. ndim: the length of u where a system's start fills
        more than the user's NDIM (HomCont's N + 1 pieces, ISTART < 0)."""
        if self._stpnt is None:
            raise ProblemError(f"{self.name}: no stpnt(u, par) to start from (IRS = 0)")
        rows = []
        for t in times:
            u = np.zeros(ndim or self.ndim)
            self._stpnt_at(u, par, t, "")
            rows.append(u)
        U = np.array(rows)
        if not np.all(np.isfinite(U)):
            raise ProblemError(f"{self.name}: stpnt(u, par, t) left non-finite values in u")
        return U

    def _stpnt_at(self, u, par, t, doing: str) -> None:
        """The user's stpnt on u and par in place, at time t where it takes one (AUTO's
        STPNT(NDIM, U, PAR, T)); a ProblemError naming what it was `doing` ('' or a
        phrase ending in a space), t and the user's file and line if it raises."""
        try:
            if self.stpnt_has_time:
                self._stpnt(u, par, float(t))
            else:
                self._stpnt(u, par)
        except Exception as exc:
            raise ProblemError(f"{self.name}: stpnt(u, par, t) failed {doing}at t = {t}: "
                               f"{type(exc).__name__}: {exc}{user_frame(exc)}") from exc

    def extend_profile(self, U, par, times) -> np.ndarray:
        """AUTO's READBV/READLB for a system extended at a restart (NDIM larger than the
        stored solution's k components): stpnt(u, p, t) at each stored point, u holding
        the stored values then zeros and p a copy of PAR (not written back), and only
        the components beyond k kept (c2c's stpnt copies the cycle and its
        eigenfunction into U(7:12) when NDIM grows from 6 to 12). Without stpnt the
        extension is 0. U: (m, k), times (m,); returns (m, ndim)."""
        U = np.asarray(U, dtype=float)
        m, k = U.shape
        out = np.zeros((m, self.ndim))
        out[:, :k] = U[:, :self.ndim]
        if k >= self.ndim or self._stpnt is None:
            return out
        p = np.array(par, dtype=float)
        for j, t in enumerate(times):
            u = out[j].copy()
            self._stpnt_at(u, p, t, f"extending the restart to NDIM = {self.ndim} ")
            out[j, k:] = u[k:]
        if not np.all(np.isfinite(out)):
            raise ProblemError(f"{self.name}: stpnt(u, par, t) left non-finite values "
                               "extending the restart")
        return out

    def start(self, npar: int, t: float = 0.0,
              ndim: int | None = None) -> tuple[np.ndarray, np.ndarray]:
        """AUTO's STPNT: the starting state (ndim,) and parameters (npar,); a stpnt
        with the time argument is called at `t` (in [0, 1]). ndim: as `start_profile`'s."""
        if self._stpnt is None:
            raise ProblemError(f"{self.name}: no stpnt(u, par) to start from (IRS = 0)")
        u, par = np.zeros(ndim or self.ndim), np.zeros(npar)
        args = (u, par, float(t)) if self.stpnt_has_time else (u, par)
        what = "stpnt(u, par, t)" if self.stpnt_has_time else "stpnt(u, par)"
        try:
            self._stpnt(*args)
        except Exception as exc:
            raise user_failure(self.name, what, exc) from exc
        if not (np.all(np.isfinite(u)) and np.all(np.isfinite(par))):
            raise ProblemError(f"{self.name}: {what} left non-finite values in u or par")
        return u, par
