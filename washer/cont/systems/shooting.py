"""Periodic orbits of periodically forced systems by single shooting (IPS = 2 for a
problem that supplies its flow over one forcing period): the zeros of

    G(u0, p) = phi_T(u0; p) - u0,        G_u0 = Phi - I,  G_p = d phi_T / d p,

with phi_T the flow over one forcing period T from t = 0 and Phi its monodromy matrix,
both supplied by the problem in one call, `Problem.period_map(u0, par, index)` ->
(phi_T(u0) (NDIM,), Phi (NDIM, NDIM), d phi_T / d PAR(index) (NDIM,)), with the period
of the forcing T(par) inside the flow (so d/dp includes a change of T with p).

Unknowns x = (u0, PAR(ICP(1))); the corrector, the norm, BP switching and the b-file
columns are the algebraic systems' (AUTO's ae.f90: the problem is a fixed point of the
period map, like IPS = -1 maps). Stability and the tests of cycles are
`washer.cont.floquet`'s without a trivial multiplier (a forced orbit has none): the
multipliers are the eigenvalues of Phi in the one order (closest to the unit circle
first), NINS counts those inside, LP of cycles is the PAR(ICP(1))-component of the
tangent, BP the determinant of the Newton matrix, PD and TR the one test |mu_c| - 1 of
the critical multiplier where it is negative real / complex, typed at the located
point; PD and TR are accepted only where the stable count changes.

Registered as (2, 1, 'shooting'): `washer.cont.start` chooses it for IPS = 2 when the
problem supplies a period map, from its stpnt (IRS = 0) or a record of such a run.
"""
from __future__ import annotations

import numpy as np

from washer.cont import floquet
from washer.cont.system import Stability, StartData, determinant_test, register
from washer.cont.systems._algebraic import AlgebraicSystem

#: Stability tolerance on |mu| - 1: the monodromy matrix of a variational flow is as
#: accurate as the integration (1e-9 and better at the usual 1e-10 tolerances), far
#: better than the 1e-5 AUTO allows collocation multipliers (floquet.STABLE_TOL), which
#: would call an orbit 1e-6 past its torus point stable and hide the TR point.
STABLE_TOL = 1e-9


@register(2, 1, "shooting")
class ForcedOrbits(AlgebraicSystem):
    """phi_T(u0) - u0 = 0 with unknowns x = (u0, PAR(ICP(1)))."""

    def __init__(self, start: StartData):
        self._one_parameter(start)
        self._last = None

    def _map(self, x):
        """(phi_T, Phi, d phi_T / d PAR(ICP(1))) at x, one flow per distinct x."""
        if self._last is None or not np.array_equal(self._last[0], x):
            out = self.problem.period_map(x[:-1], self._p(x), self.free[0])
            self._last = (np.array(x), out)
        return self._last[1]

    # ------------------------------------------------------------------ contract
    def start(self):
        return self._x0.copy(), self._t0

    def residual(self, x) -> np.ndarray:
        uT, _, _ = self._map(x)
        return uT - x[:-1]

    def jacobian(self, x) -> np.ndarray:
        _, Phi, dp = self._map(x)
        return np.hstack([Phi - np.eye(self.ndim), np.asarray(dp, float)[:, None]])


    def multipliers(self, x) -> np.ndarray:
        """The eigenvalues of the monodromy matrix at x, closest to the circle first."""
        return floquet.sort_multipliers(np.linalg.eigvals(self._map(x)[1]), trivial=False)

    def stability(self, x, J) -> Stability | None:
        if self.settings.ISP == 0:
            return None
        return floquet.stability(self.multipliers(x), self.ndim, False, trivial=False,
                                 tol=STABLE_TOL)

    def active_tests(self) -> list:
        return floquet.active_tests(self.settings, self.ndim, trivial=False)

    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict:
        return floquet.test_functions(codes, tangent, stability, self.settings.EPSS,
                                      self.ndim, lambda: determinant_test(factor),
                                      floquet.spb_kinds(self.settings),
                                      trivial=False)

    def located_code(self, key, point) -> int:
        """PD or TR for a zero of the combined test, as TPSPBV types the located point."""
        return floquet.spb_code(key, point.stability, self.settings.EPSS, trivial=False)

    def accept(self, code, prev, cur) -> bool:
        return floquet.accept(code, prev, cur, self.ndim, trivial=False)

    def solution(self, x, tangent):
        sol = super().solution(x, tangent)
        st = self.stability(x, None)
        angle = None if st is None else floquet.torus_angle(st.values, self.settings.EPSS,
                                                             trivial=False)
        if angle is not None and len(sol.par) >= 12 and 12 not in self.free:
            sol.par[11] = angle             # AUTO's PAR(12) at TR: the torus angle
        return sol
