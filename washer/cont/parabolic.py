"""The first-order systems of a parabolic PDE u_t = D u_xx + f(u, p) (AUTO's parabolic.f90).

The user supplies f (FUNC, NDIM = n components); the diffusion coefficients are
D_i = PAR(14 + i), i = 1..n. AUTO's problem types 11, 12, 14, 16 and 17 continue
solutions of the ODE in the space variable, written as a system of 2n components
(u, v = u_z):

* travelling waves u(x - c t) with speed c = PAR(10) (IPS = 11, 12; FNWS):

      u' = v,   v' = -(c v + f(u, p)) / D

  whose equilibria (u, 0), f(u) = 0, are the spatially uniform solutions and whose
  Hopf points start wave trains (periodic orbits of this system);
* stationary states on x in [0, L], L = PAR(11), scaled to [0, 1] (IPS = 17; FNSP):

      u' = L v,   v' = -L f(u, p) / D

`ParabolicProblem` is the Problem of the 2n components built on the user's; the
continued systems (washer.cont.systems.waves, washer.cont.systems.parabolic_bvp) are the
engine's equilibria, periodic orbits and boundary value problems of it.
"""
from __future__ import annotations

import numpy as np

from washer.cont.problem import Problem, ProblemError

#: PAR(10): the wave speed c of travelling waves (FNWS).
SPEED = 10
#: PAR(11): the length L of the space interval of stationary states (FNSP), the period
#: of wave trains (IPS = 12).
LENGTH = 11
#: PAR(14 + i): the diffusion coefficient of the i-th component (FNWS, FNSP, FNPE).
DIFFUSION = 14
#: PAR(14): the time of an evolution (IPS = 14, 16; FNPE), its continuation parameter
#: (as it is of time integration, IPS = -2: washer.cont.start).
TIME = 14

#: The first-order system each problem type of a parabolic PDE continues: FNWS for
#: uniform solutions and wave trains, FNSP's for stationary states and (with FNPE's
#: implicit Euler term, added by the continued system) the time evolution.
PARABOLIC_KINDS = {11: "wave", 12: "wave", 14: "stationary", 16: "stationary",
                   17: "stationary"}


class ParabolicProblem(Problem):
    """The 2n-component first-order system of a parabolic PDE (module docstring).

    user : the Problem of f (n components). kind : 'wave' (FNWS: speed PAR(10), no
    length) or 'stationary' (FNSP: length PAR(11), no speed). Jacobians are differences
    of this system's f (AUTO's JAC = 0 differences the user's f the same way; the
    linear parts are exact to rounding either way). The user's bcnd (IPS = 17) and pvls
    see the 2n components, as AUTO's BCND and PVLS do.
    """

    def __init__(self, user: Problem, kind: str):
        if kind not in ("wave", "stationary"):
            raise ValueError(f"kind {kind!r}: expected 'wave' or 'stationary'")
        n = user.ndim
        self.user, self.kind = user, kind
        self.ndm = n              # AUTO's NDM: the user's NDIM, n
        super().__init__(2 * n, self._f, stpnt=self._stpnt, name=user.name,
                         npar=max(user.npar, DIFFUSION + n, LENGTH), func_batch=self._f_batch,
                         pvls=user._pvls, parnames=user.parnames, unames=user.unames,
                         bcnd=user._bcnd)

    def fresh(self) -> None:
        self.user.fresh()

    def _diffusion(self, pars: np.ndarray) -> np.ndarray:
        """(k, n) diffusion coefficients PAR(15..14 + n) of k parameter rows; a zero one
        is the user's error (the PDE is then not parabolic in that component)."""
        D = pars[:, DIFFUSION:DIFFUSION + self.ndm]
        if np.any(D == 0):
            raise ProblemError(f"{self.name}: a diffusion coefficient PAR(15..{DIFFUSION + self.ndm}) "
                               "is 0: a parabolic PDE needs PAR(14 + i) != 0 for each component")
        return D

    def _f_batch(self, us, pars) -> np.ndarray:
        """The 2n right-hand sides at k points: us (k, 2n), pars (k, NPAR) -> (k, 2n)."""
        us, pars = np.asarray(us, float), np.asarray(pars, float)
        n = self.ndm
        u, v = us[:, :n], us[:, n:]
        f = self.user.func_many(np.ascontiguousarray(u), pars)
        D = self._diffusion(pars)
        if self.kind == "wave":
            c = pars[:, SPEED - 1:SPEED]
            return np.hstack([v, -(c * v + f) / D])
        L = pars[:, LENGTH - 1:LENGTH]
        return np.hstack([L * v, -L * f / D])

    def _f(self, u, par) -> np.ndarray:
        return self._f_batch(np.asarray(u, float)[None, :], np.asarray(par, float)[None, :])[0]

    def _stpnt(self, u, par, t=0.0) -> None:
        """The user's stpnt on the 2n components, zero before the call (AUTO calls
        STPNT with NDIM = 2n: the user sets U(1..n) and, for a profile in x, may set
        its derivative U(n + 1..2n) too)."""
        u[:] = 0.0
        self.user._stpnt_at(u, par, t, "")

    @property
    def stpnt_has_time(self) -> bool:
        return self.user.stpnt_has_time

    @property
    def has_pvls(self) -> bool:
        return self.user.has_pvls

    def pvls(self, u, par, *args, **kwargs) -> np.ndarray:
        """The user's PVLS on the 2n components (a compiled one through its own call)."""
        return self.user.pvls(u, par, *args, **kwargs)

    def bcnd(self, u0, u1, par, nbc: int) -> np.ndarray:
        """The user's BCND on the 2n components at both ends (IPS = 17: NBC = 2n)."""
        return self.user.bcnd(u0, u1, par, nbc)


__all__ = ["ParabolicProblem", "PARABOLIC_KINDS", "SPEED", "LENGTH", "DIFFUSION", "TIME"]
