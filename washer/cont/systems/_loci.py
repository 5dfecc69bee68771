"""What the fold and Hopf loci share: the parameter layout of the extended
unknowns and the derivatives of A = f_x along x and the two free parameters."""
from __future__ import annotations

import numpy as np

from washer.cont.system import StartData
from washer.cont.systems._algebraic import AlgebraicSystem

#: Central-difference steps (relative) for the derivatives of A = f_x, which
#: the Jacobians of the loci need (second derivatives of f). Central errors
#: are h^2 |f_xxxx| / 6 + noise(A) / h, smallest at h ~ (3 noise)^(1/3): with
#: an analytic A (JAC != 0, noise ~ machine eps) h ~ 7e-6; with a
#: finite-difference A (JAC = 0, rounding ~1e-9 relative from its 1e-7 steps)
#: h ~ 1.4e-3. A forward difference would leave an O(h) error in the curve's
#: tangent, which moves located folds of the curve (seen: 4.5e-5 in p2).
DA_STEP_ANALYTIC = 7e-6
DA_STEP_FD = 1.4e-3


class LocusSystem(AlgebraicSystem):
    """Unknowns x = (u, extra..., PAR(ICP(2)), PAR(ICP(1))): the second free
    parameter is the last of the state unknowns, the principal one last."""

    def _setup(self, start: StartData, n_extra: int):
        s = start.settings
        if len(s.ICP) < 2:
            raise ValueError("ISW = 2 continues a locus in two parameters: ICP needs two "
                             f"entries, got {list(s.ICP)}")
        self.problem, self.settings = start.problem, s
        self.ndim = n = start.problem.ndim
        self.n_eq = n + n_extra + 1
        self.par = np.array(start.par, dtype=float)
        self.free = [s.ICP[0], s.ICP[1]]
        self.unames = dict(start.unames)
        # THU covers the extended unknowns too (AUTO's THU runs over the extended
        # NDIM): U(2n+1) = kappa on Hopf curves may be down-weighted.
        self.theta = np.r_[s.theta_u(n + n_extra), s.theta_par(s.ICP[1]), s.theta_par(s.ICP[0])]
        self.da_step = DA_STEP_FD if start.problem.jac == 0 else DA_STEP_ANALYTIC

    def _p(self, x) -> np.ndarray:
        p = self.par.copy()
        p[self.free[0] - 1] = x[-1]
        p[self.free[1] - 1] = x[-2]
        return p

    def params(self, x) -> np.ndarray:
        p = self._p(x)
        if self.problem.has_pvls:
            p = self.problem.pvls(x[:self.ndim], p)
        return p

    def f_blocks(self, x):
        """A = f_x (n, n), f_p = [f_{p1}, f_{p2}] (n, 2) and dA (n + 2, n, n): the
        derivatives of A along e_j (j < n), then PAR(ICP(1)), then PAR(ICP(2)),
        central differences of A at the 2 (n + 2) perturbed points in one batch."""
        n = self.ndim
        u = x[:n]
        p = self._p(x)
        i1, i2 = self.free[0] - 1, self.free[1] - 1
        A = self.problem.dfdu(u, p)
        fp = self.problem.dfdp(u, p, self.free)
        steps = self.da_step * (1 + np.abs(np.r_[u, p[i1], p[i2]]))
        m = n + 2
        us = np.repeat(u[None, :], 2 * m, axis=0)
        ps = np.repeat(p[None, :], 2 * m, axis=0)
        idx = np.arange(n)
        us[idx, idx] += steps[:n]
        us[m + idx, idx] -= steps[:n]
        ps[n, i1] += steps[n]
        ps[m + n, i1] -= steps[n]
        ps[n + 1, i2] += steps[n + 1]
        ps[m + n + 1, i2] -= steps[n + 1]
        As = self.problem.dfdu_many(us, ps)
        dA = (As[:m] - As[m:]) / (2 * steps[:, None, None])
        return A, fp, dA

    def stability(self, x, J):
        """No stability on ISW = 2 curves (AUTO writes PT > 0 there)."""
        return None

    def solution(self, x, tangent):
        sol = super().solution(x, tangent)
        sol.par = self.params(x)
        return sol
