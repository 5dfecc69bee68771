"""What the fold and Hopf loci share: the parameter layout of the extended
unknowns and the derivatives of A = f_x along x and the two free parameters."""
from __future__ import annotations

import numpy as np

from washer.cont.settings import SettingsError
from washer.cont.system import StartData
from washer.cont.systems._algebraic import AlgebraicSystem

class LocusSystem(AlgebraicSystem):
    """Unknowns x = (u, extra..., PAR(ICP(2)), PAR(ICP(1))): the second free
    parameter is the last of the state unknowns, the principal one last."""

    #: False: every Newton iteration uses the full Jacobian, second-derivative blocks
    #: included, as AUTO's SOLVAE (FNHB/FNLP difference the whole extended system at
    #: every iterate). With those blocks frozen at the last point, Newton converges
    #: linearly and needs 3 iterations where AUTO needs 2, so ADPTDS grows the step by
    #: 1.1 instead of 1.5: plp's Hopf locus took 39 points to AUTO's 24 for the same
    #: stretch (NMX then ended runs before AUTO's later points). With full Newton: 23.
    freezes_second_derivatives = False

    def _setup(self, start: StartData, n_extra: int):
        s = start.settings
        if len(s.ICP) < 2:
            raise SettingsError("ISW = 2 continues a locus in two parameters: ICP needs two "
                             f"entries, got {list(s.ICP)}", keys=("ICP",))
        self.problem, self.settings = start.problem, s
        self.ndim = n = start.problem.ndim
        self.n_eq = n + n_extra + 1
        self.par = np.array(start.par, dtype=float)
        self.free = [s.ICP[0], s.ICP[1]]
        self.unames = dict(start.unames)
        # THU covers the extended unknowns too (AUTO's THU runs over the extended
        # NDIM): U(2n+1) = kappa on Hopf curves may be down-weighted.
        self.theta = np.r_[s.theta_u(n + n_extra), s.theta_par(s.ICP[1]), s.theta_par(s.ICP[0])]
        # The last second-derivative blocks of the Jacobian (see jacobian's
        # frozen_second): the corrector reuses them within a step.
        self._second = None
        self._derivatives_memo = None

    def stored_point(self, start: StartData, kind: str):
        """The extended state (n_eq,) stored with a point of the same curve (a
        restart from a record of this locus), or None for a restart at the special
        point itself. A record of another size is an error."""
        if start.kind != kind:
            return None
        stored = np.asarray(start.u, dtype=float)
        if len(stored) != self.n_eq:
            raise ValueError(f"a {kind} record stores {self.n_eq} values (NDIM = {self.ndim}), "
                             f"this one {len(stored)}")
        return stored.copy()

    def stored_direction(self, start: StartData, kind: str):
        """The direction stored with a point of the same curve and the same free
        parameters (reused on a restart, as AUTO does), else None."""
        rec = start.record
        if start.kind != kind or rec is None or rec.udot is None \
                or list(rec.icp[:2]) != self.free or len(rec.udot) != self.n_eq:
            return None
        return np.r_[rec.udot, rec.rldot[0]]

    def start(self):
        return self._x0.copy(), self.restart_direction(self._t0)

    def _p(self, x) -> np.ndarray:
        p = self.par.copy()
        p[self.free[0] - 1] = x[-1]
        p[self.free[1] - 1] = x[-2]
        return p

    def derivatives(self, u, p) -> tuple[np.ndarray, np.ndarray]:
        """f_u (n, n) and [f_PAR(ICP(1)), f_PAR(ICP(2))] (n, 2) at (u, p), from one
        `Problem.jacobian` (one stencil where they are differences), remembered for the
        last (u, p): the corrector asks for the residual and then the Jacobian at the
        same point."""
        key = (u.tobytes(), p.tobytes())
        memo = self._derivatives_memo
        if memo is None or memo[0] != key:
            J = self.problem.jacobian(u, p, self.free)
            n = self.ndim
            memo = self._derivatives_memo = (key, J[:, :n], J[:, n:])
        return memo[1], memo[2]

    def second(self, x, ws) -> np.ndarray:
        """T[s, k] = f_zz[e_s, w_k], shape (n + 2, len(ws), n): the second
        derivatives of f along e_j (j < n), then PAR(ICP(1)), then PAR(ICP(2)),
        and the state vectors ws, from one batched call of f
        (Problem.second_derivatives), whatever JAC is."""
        return self.problem.second_derivatives(x[:self.ndim], self._p(x), ws, self.free)

    def stability(self, x, J):
        """No stability on ISW = 2 curves (AUTO writes PT > 0 there)."""
        return None
