"""Time integration by continuation (AUTO's IPS = -2; timeint.f90: FNTI on AUTOAE).

The time t = PAR(ICP(1)) is the continuation parameter and each step is one implicit
(backward) Euler step from the previous point (u_old, t_old):

    G(u, t) = (t - t_old) f(u, p) - u + u_old = 0

continued by AUTO's algebraic pseudo-arclength machinery, so the step in t follows
DS/DSMIN/DSMAX and the Newton iteration counts (ADPTDS) like any branch, and UZR
values of t (or of other parameters set by pvls) end or mark it. No stability, no
bifurcation tests (ISP and ILP have nothing to detect on a trajectory).
"""
from __future__ import annotations

import numpy as np

from washer.cont.system import StartData, register
from washer.cont.systems._algebraic import AlgebraicSystem


@register(-2, 1)
class TimeIntegration(AlgebraicSystem):
    """Unknowns x = (u, t = PAR(ICP(1))); the reference (u_old, t_old) is the last
    accepted point (moved in `update`)."""

    def __init__(self, start: StartData):
        self._one_parameter(start)
        self.x_old = self._x0.copy()

    def residual(self, x) -> np.ndarray:
        dt = x[-1] - self.x_old[-1]
        return dt * self.problem.func(x[:-1], self._p(x)) - x[:-1] + self.x_old[:-1]

    def jacobian(self, x) -> np.ndarray:
        """[dt f_u - I, f], shape (N, N + 1) (FNTI)."""
        p = self._p(x)
        dt = x[-1] - self.x_old[-1]
        A = self.problem.dfdu(x[:-1], p)
        return np.hstack([dt * A - np.eye(self.ndim), self.problem.func(x[:-1], p)[:, None]])

    def start(self):
        return self._x0.copy(), None

    def update(self, x, tangent) -> None:
        self.x_old = np.array(x, dtype=float)

    def stability(self, x, J):
        return None

    def active_tests(self) -> list:
        return []

    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict:
        return {}


__all__ = ["TimeIntegration"]
