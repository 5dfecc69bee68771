"""Stationary states and time evolution of a parabolic PDE u_t = D u_xx + f(u, p) on
x in [0, L], L = PAR(11), D_i = PAR(14 + i) (AUTO's IPS = 17, 14, 16; parabolic.f90:
FNSP, FNPE, BCNI, BCPS, ICPE).

Both are boundary value problems (general_bvp.BoundaryValueProblem) of the PDE's
first-order system in x scaled to [0, 1] (washer.cont.parabolic, kind 'stationary'),
with NDIM = 2n, NBC = 2n, NINT = 0 and one free parameter (AUTOPE):

* IPS = 17, stationary states: u' = L v, v' = -L f(u, p) / D with the user's 2n
  boundary conditions (BCND), continued in PAR(ICP(1)) with the BVP's LP and BP tests.
* IPS = 14 and 16, time evolution by implicit Euler steps in the time t = PAR(14), the
  continuation parameter (ICP(1) = 14, ILP = ISP = 0):

      u' = L v,   v' = L ((u - u_old) / dt - f(u, p)) / D,    dt = t - t_old

  u_old the previous point's profile at the same collocation point and t_old its time
  (AUTO keeps it in PAR(12)); dt = 1 where t = t_old (the start, where u = u_old: the
  start profile is not corrected, and its tangent is the time's own). The boundary
  conditions are periodic, u(0) = u(1) for all 2n components (IPS = 14, BCPS), or the
  user's (IPS = 16). The step in t follows DS, DSMIN, DSMAX like any branch.

The b-file shows MAX U(1..n) of the user's components (AUTO's NDM stays n here), the
header NDIM = 2n with the user's NDIM below it.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from washer.cont.parabolic import DIFFUSION, LENGTH, TIME
from washer.cont.system import StartData, register
from washer.cont.systems.general_bvp import BoundaryValueProblem

#: PAR(12): where AUTO keeps the time of the previous point of an evolution (FNCSPE).
OLD_TIME = 12


class _ParabolicBVP(BoundaryValueProblem):
    """A BVP of the 2n-component system of a parabolic PDE (NBC = 2n, NINT = 0)."""

    def __init__(self, start: StartData):
        problem = start.problem
        n2 = problem.ndim
        self.ndm = problem.ndm           # the user's n: BoundaryValueProblem's NDM
        s = start.settings.with_(NDIM=n2, NBC=n2, NINT=0)
        super().__init__(replace(start, settings=s))
        self.run_settings = s


@register(17, 1, "*")
@register(17, -1, "BP")
class StationaryStates(_ParabolicBVP):
    """Stationary states (IPS = 17; FNSP, BCNI, ICPE on AUTOBV)."""


class _Evolution(_ParabolicBVP):
    """Time evolution (IPS = 14, 16; FNPE on AUTOBV): the implicit Euler term."""

    def __init__(self, start: StartData):
        super().__init__(start)
        self.t_old = float(self.par[OLD_TIME - 1])

    def _dt(self, par) -> float:
        """The Euler step in time, t - t_old; 1 at the start, where t = t_old."""
        t = par[TIME - 1]
        return 1.0 if t == self.t_old else t - self.t_old

    def _memory(self, ug, par):
        """(u - u_old at the collocation points (NTST NCOL, n), L / D (n,), dt)."""
        n = self.ndm
        uold = self.at_gauss(self.U_old).reshape(-1, self.ndim)[:, :n]
        ratio = par[LENGTH - 1] / par[DIFFUSION:DIFFUSION + n]
        return ug[:, :n] - uold, ratio, self._dt(par)

    def gauss_f(self, ug, par) -> np.ndarray:
        """FNSP's right-hand side at the collocation points ug (NTST NCOL, 2n) with the
        Euler term L (u - u_old) / (D dt) added to the v' rows (FNPE)."""
        f = super().gauss_f(ug, par)
        du, ratio, dt = self._memory(ug, par)
        f[:, self.ndm:] += ratio * du / dt
        return f

    def gauss_fu_fp(self, ug, par):
        """`gauss_f`'s derivatives: (f_u (NTST NCOL, 2n, 2n), [f_PAR(i) (NTST NCOL, 2n)
        in x's parameter order]), the Euler term's included."""
        fu, fp = super().gauss_fu_fp(ug, par)
        du, ratio, dt = self._memory(ug, par)
        n = self.ndm
        idx = np.arange(n)
        fu[:, n + idx, idx] += ratio / dt
        # d/dt of the Euler term (the only free parameter is the time; FNPE's DFDP)
        for k, i in enumerate(self._order):
            if i == TIME:
                fp[k] = fp[k].copy()
                fp[k][:, n:] += -ratio * du / dt ** 2
        return fu, fp

    def update(self, x, tangent) -> None:
        """The accepted point is the next step's u_old and t_old (FNCSPE's PAR(12))."""
        super().update(x, tangent)
        self.t_old = float(x[-1])

    def params(self, x):
        par = super().params(x)
        par[OLD_TIME - 1] = self.t_old if x[-1] != self.t_old else float(x[-1])
        return par


@register(16, 1, "*")
class UserBoundaryEvolution(_Evolution):
    """Time evolution with the user's boundary conditions (IPS = 16; BCNI)."""


@register(14, 1, "*")
class PeriodicEvolution(_Evolution):
    """Time evolution with periodic boundary conditions (IPS = 14; BCPS)."""

    def _bc(self, U, par):
        """BCPS: u(0) - u(1), (2n,), from the profile U (n_nodes, 2n)."""
        return U[0] - U[-1]

    def _bc_jacobian(self, U, par) -> np.ndarray:
        """d `_bc` / d (u(0), u(1), free parameters): (2n, 4n + NFPR), exact."""
        n = self.ndim
        return np.hstack([np.eye(n), -np.eye(n), np.zeros((n, self.nfpr))])


__all__ = ["StationaryStates", "UserBoundaryEvolution", "PeriodicEvolution"]
