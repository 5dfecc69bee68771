"""Algebraic optimisation (IPS = 5): extrema of an objective on the solutions of
f(u, p) = 0, AUTO's AUTOOP with FNC1/STPNC1 and FNC2/STPNC2 (optimization.f90).

The user's objective phi = FOPT(u, p) is PAR(10) = PAR(ICP(1)), the continuation
parameter; the free equation parameters are PAR(ICP(2..NFPR)). NFPR grows by one at
each restart from a fold (LP) of the objective, and once at the start (IRS = 0):

* NFPR = 2 (FNC1): the solution curve of f(u, p) = 0 in p = PAR(ICP(2)),

      f(u, p) = 0,   PAR(10) - phi(u, p) = 0,

  unknowns (u, p; PAR(10)). Its LP in PAR(10) is an extremum of phi along the curve.
* NFPR >= 3 (FNC2): the extrema in PAR(ICP(2..NFPR-1)) continued in PAR(ICP(NFPR)),
  with the Lagrange multipliers v (NDIM) of f and v0 of phi:

      f(u, p) = 0
      v0 grad_u phi + f_u^T v = 0
      v0 d phi / d PAR(ICP(i)) + v . d f / d PAR(ICP(i)) = 0,    i = 2 .. NFPR - 1
      v0^2 + |v|^2 - 1 = 0
      PAR(10) - phi(u, p) = 0

  unknowns (u, v, v0, PAR(ICP(2..NFPR)); PAR(10)); NDIM' = 2 NDIM + NFPR. Its LP in
  PAR(10) is an extremum in one parameter more. Starting from the LP of an NFPR = 2
  run (STPNC2), (v, v0) is the unit null vector of [[f_u^T, grad_u phi], [f_p^T,
  phi_p]] (p = PAR(ICP(2))); from the LP of an FNC2 run the record's multipliers are
  kept.

The stored state (s-file U) is AUTO's: (u, PAR(ICP(2))) for FNC1, (u, v, v0,
PAR(ICP(2..NFPR))) for FNC2; the b-file shows PAR(10), the L2 norm of u and the user's
U(i), then PAR(ICP(2..)) for every ICP entry. Derivatives of phi are central
differences of FOPT (AUTO: the user's when JAC = 1); the multiplier equations are
differenced with steps ~1e-4 relative in the Newton matrix (second derivatives of f
and phi, accurate to ~1e-8; AUTO differences FFC2 with steps 1e-7).
"""
from __future__ import annotations

import numpy as np

from washer.cont.differences import columns
from washer.cont.settings import SettingsError
from washer.cont.system import Solution, register
from washer.cont.systems._algebraic import AlgebraicSystem
from washer.cont.systems.bvp import H2
from washer.cont.linalg import null_vectors

#: The objective's PAR index, AUTO's ICP(1) of IPS = 5.
OBJECTIVE = 10


@register(5, 1)
class AlgebraicOptimisation(AlgebraicSystem):
    """The continued system of IPS = 5 (FNC1 for NFPR = 2, FNC2 for NFPR >= 3)."""

    def __init__(self, start):
        s = start.settings
        user = start.problem
        rec = start.record
        if s.ICP[0] != OBJECTIVE:
            raise SettingsError(f"ICP = {list(s.ICP)}: with IPS = 5, ICP(1) is PAR(10), the "
                             "objective FOPT (the continuation parameter); the free equation "
                             "parameters follow it", keys=("ICP",))
        if not user.has_fopt:
            raise ValueError(f"IPS = 5 needs the objective FOPT of the equations "
                             f"'{user.name}' (AUTO's FOPT(NDIM,U,ICP,PAR,IJAC,FS,DFDU,DFDP), "
                             "or fopt(u, par) in NAME.py)")
        if rec is not None and (rec.ips != 5 or np.ndim(rec.u) != 1):
            raise ValueError("IPS = 5 starts with IRS = 0 or from a label of an IPS = 5 run")
        # AUTOOP: NFPR grows by one at the start and at each restart from an LP.
        nfpr_rec = int(rec.nfpr) if rec is not None else 1
        nfpr = nfpr_rec + (1 if rec is None or start.kind == "LP" else 0)
        if len(s.ICP) < nfpr:
            raise SettingsError(f"ICP = {list(s.ICP)}: NFPR = {nfpr} free parameters (the "
                             f"objective PAR(10) and {nfpr - 1} equation parameter"
                             f"{'s' if nfpr > 2 else ''}) but ICP names {len(s.ICP)}", keys=("ICP",))
        self.problem, self.user, self.settings = user, user, s
        self.ndm = self.ndim = n = user.ndim
        self.nfpr = nfpr
        self.free = list(s.ICP[:nfpr])
        self.eq_par = self.free[1:]                 # PAR(ICP(2..NFPR)), stored in U
        self.unames = dict(start.unames)
        self.par = np.array(start.par, dtype=float)
        self.n_internal = n + 1 if nfpr == 2 else 2 * n + nfpr     # AUTO's internal NDIM
        self.n_eq = self.n_internal
        self.run_settings = s.with_(NDIM=self.n_internal)
        thu = s.theta_u(n)
        if nfpr == 2:
            self.theta = np.r_[thu, s.theta_par(self.eq_par[0]), s.theta_par(OBJECTIVE)]
        else:
            self.theta = np.r_[thu, np.ones(n + 1), [s.theta_par(i) for i in self.eq_par],
                               s.theta_par(OBJECTIVE)]
        self._x0, self._t0 = self._start_point(rec, start)

    # ------------------------------------------------------------ layout
    def _slots(self) -> list:
        """Where PAR(ICP(2..NFPR)) sit in x."""
        first = self.ndm if self.nfpr == 2 else 2 * self.ndm + 1
        return list(range(first, first + len(self.eq_par)))

    def _p(self, x) -> np.ndarray:
        p = self.par.copy()
        for k, i in zip(self._slots(), self.eq_par):
            p[i - 1] = x[k]
        p[OBJECTIVE - 1] = x[-1]
        return p

    def params(self, x) -> np.ndarray:
        p = self._p(x)
        if self.user.has_pvls:
            p = self.user.pvls(x[:self.ndm], p)
        return p

    def _phi(self, u, par) -> float:
        return float(self.user.fopt_many(np.asarray(u, float)[None, :], par)[0])

    def _grad_phi(self, u, par, indices) -> tuple[np.ndarray, np.ndarray]:
        """(grad_u phi (NDIM,), d phi / d PAR(indices)): FOPT's central differences
        (Problem.fopt_gradient, AUTO's FOPI) at the point u."""
        gu, gp = self.user.fopt_gradient(np.asarray(u, float)[None], par, indices)
        return gu[0], gp[0]

    # ------------------------------------------------------------ equations
    def residual(self, x) -> np.ndarray:
        n = self.ndm
        u, par = x[:n], self._p(x)
        f = self.user.func(u, par)
        obj = x[-1] - self._phi(u, par)
        if self.nfpr == 2:
            return np.r_[f, obj]
        return np.r_[f, self._multiplier_rows(x, par), obj]

    def _multiplier_rows(self, x, par) -> np.ndarray:
        """FFC2's rows NDIM + 1 .. NDIM' - 1: stationarity in u and in PAR(ICP(2..NFPR-1)),
        the multipliers' normalisation."""
        n = self.ndm
        u, v, v0 = x[:n], x[n:2 * n], x[2 * n]
        stat = self.eq_par[:-1]
        J = self.user.jacobian(u, par, stat)                      # [f_u, f_p]
        gu, gp = self._grad_phi(u, par, stat)
        return np.r_[v0 * gu + J[:, :n].T @ v, v0 * gp + J[:, n:].T @ v,
                     v0 * v0 + v @ v - 1.0]

    def jacobian(self, x) -> np.ndarray:
        """(N, N + 1): f's rows from the problem's Jacobian, the objective's from FOPT's
        differences, the multiplier rows by central differences with steps H2 (1 + |x|)
        (exact in v, v0, where they are linear or quadratic)."""
        n, N = self.ndm, self.n_eq
        par = self._p(x)
        u = x[:n]
        slots = self._slots()
        Jf = self.user.jacobian(u, par, self.eq_par)              # (n, n + m)
        gu, gp = self._grad_phi(u, par, self.eq_par)
        out = np.zeros((N, N + 1))
        out[:n, :n] = Jf[:, :n]
        out[:n, slots] = Jf[:, n:]
        out[-1, :n] = -gu
        out[-1, slots] = -gp
        out[-1, -1] = 1.0
        if self.nfpr > 2:
            cols = list(range(n)) + list(range(n, 2 * n + 1)) + slots
            out[n:-1, cols] = columns(lambda z: self._multiplier_rows(z, self._p(z)), x, cols, H2)
        return out

    # ------------------------------------------------------------ start
    def _start_point(self, rec, start):
        """(x0, stored direction or None): STPNC1 (IRS = 0), STPNC2 (from an LP), STPNAE
        (a restart at another label of a run with the same NFPR)."""
        n = self.ndm
        par = self.par
        if rec is None:
            # STPNC1: STPNT's u and PAR, PAR(10) = FOPT there.
            u = np.asarray(start.u, float)[:n]
            x = np.r_[u, par[self.eq_par[0] - 1], 0.0]
            x[-1] = self._phi(u, self._p(x))
            return x, None
        U = np.asarray(rec.u, float)
        u = U[:n]
        if self.nfpr == int(rec.nfpr):
            # STPNAE: the stored state as it is, its direction when stored.
            x = np.r_[U[:self.n_internal], par[OBJECTIVE - 1]]
            t = None
            if rec.udot is not None and len(rec.rldot) and len(rec.udot) >= self.n_internal:
                t = np.r_[np.asarray(rec.udot, float)[:self.n_internal], rec.rldot[0]]
            return x, t
        # STPNC2: the multipliers, then PAR(ICP(2..NFPR)) in their new places.
        if self.nfpr == 3:
            p2 = self.eq_par[0]
            J = self.user.jacobian(u, par, [p2])
            gu, gp = self._grad_phi(u, par, [p2])
            D = np.zeros((n + 1, n + 1))
            D[:n, :n] = J[:, :n].T
            D[:n, n] = gu
            D[n, :n] = J[:, n]
            D[n, n] = gp[0]
            V = null_vectors(D, 1)[:, 0]
            V = V / np.linalg.norm(V)
            par = par.copy()
            par[OBJECTIVE - 1] = self._phi(u, par)
            self.par = par
        else:
            V = U[n:2 * n + 1]
        x = np.r_[u, V, [par[i - 1] for i in self.eq_par], par[OBJECTIVE - 1]]
        return x, None

    def start(self):
        return self._x0.copy(), None if self._t0 is None else self._t0.copy()

    # ------------------------------------------------------------ tests and output
    def stability(self, x, J):
        return None

    def solution(self, x, tangent) -> Solution:
        """The b-row (L2 norm of u, U(i)) and the record: AUTO's internal U, its
        direction, RLDOT = d PAR(ICP(1..NFPR)) / ds."""
        par = self.params(x)
        u = x[:self.ndm]
        cols = [float(np.sqrt(np.sum(u ** 2)))] + [float(v) for v in u[:self.n_columns]]
        rldot = [float(tangent[-1])] + [float(tangent[k]) for k in self._slots()]
        return Solution(par=par, columns=cols, u=np.array(x[:-1]), udot=np.array(tangent[:-1]),
                        rldot=rldot, ndim_user=self.ndm)


__all__ = ["AlgebraicOptimisation"]
