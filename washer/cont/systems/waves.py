"""Travelling waves of a parabolic PDE u_t = D u_xx + f(u, p) (AUTO's IPS = 11 and 12;
parabolic.f90: FNWS, FNWL, FNHW, FNWP).

A wave u(x - c t) of speed c = PAR(10) solves the 2n-component system of FNWS
(washer.cont.parabolic, kind 'wave'):

    u' = v,   v' = -(c v + f(u, p)) / D,    D_i = PAR(14 + i)

* IPS = 11: its equilibria (u, 0), the spatially uniform solutions, continued as the
  engine's equilibria (equilibrium.EquilibriumSystem: LP, BP, HB with the eigenvalues of
  the 2n x 2n Jacobian, PT's sign from them) and, with ISW = 2, their fold and Hopf loci
  (fold.FoldSystem, hopf.HopfSystem). A Hopf point is where wave trains are born.
* IPS = 12: wave trains, the periodic orbits of that system (periodic.PeriodicOrbits:
  started at an HB of IPS = 11 or from a stored wave train); PAR(11) is the wave length
  (free with ICP(2) = 11, else fixed and ICP(2), e.g. the speed PAR(10), is free), and
  with ISW = 2 their fold locus (cycle_fold.CycleFoldLocus).

Each system runs under AUTO's redefinition NDIM = 2n (AUTOPE): the b-file header states
it, with the user's NDIM below it, and the s-records the user's NDIM with 2n stored
components, as AUTO writes them.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from washer.cont.system import StartData, register
from washer.cont.systems.cycle_fold import CycleFoldLocus
from washer.cont.systems.equilibrium import EquilibriumSystem
from washer.cont.systems.fold import FoldSystem
from washer.cont.systems.hopf import HopfSystem
from washer.cont.systems.periodic import PeriodicOrbits


def doubled(start: StartData) -> StartData:
    """The start data of the 2n-component system (AUTOPE: NDIM = 2 NDIM; the problem is
    already the PDE's first-order system, washer.cont.start.settings_for): the settings'
    NDIM doubled, a state of n components (an IPS = 1 label) extended by v = u' = 0."""
    n2 = start.problem.ndim
    u = np.asarray(start.u, dtype=float)
    if u.ndim == 1 and len(u) < n2:
        u = np.r_[u, np.zeros(n2 - len(u))]
    return replace(start, u=u, settings=start.settings.with_(NDIM=n2))


class _UserNdim:
    """The s-records of a doubled system carry the user's NDIM (AUTO's field 14: NDM of
    the user, 2n values stored per point); the run's settings are the doubled ones."""

    def _doubled_init(self, base, start: StartData) -> None:
        inner = doubled(start)
        self.ndm = start.problem.ndm
        base.__init__(self, inner)
        if not hasattr(self, "run_settings"):
            self.run_settings = inner.settings

    def solution(self, x, tangent):
        sol = super().solution(x, tangent)
        sol.ndim_user = self.ndm
        return sol


@register(11, 1)
@register(11, -1, "BP")
@register(11, -1, "*")
class UniformSolutions(_UserNdim, EquilibriumSystem):
    """Spatially uniform solutions (IPS = 11, ISW = 1 or -1; FNWS on AUTOAE)."""

    def __init__(self, start: StartData):
        self._doubled_init(EquilibriumSystem, start)


@register(11, 2, "LP")
@register(11, 2, "LP-curve")
class UniformFolds(_UserNdim, FoldSystem):
    """The fold locus of uniform solutions (IPS = 11, ISW = 2; FNWL)."""

    def __init__(self, start: StartData):
        self._doubled_init(FoldSystem, start)


@register(11, 2, "HB")
@register(11, 2, "HB-curve")
class UniformHopf(_UserNdim, HopfSystem):
    """The Hopf locus of uniform solutions, where wave trains are born (IPS = 11,
    ISW = 2; FNHW)."""

    def __init__(self, start: StartData):
        self._doubled_init(HopfSystem, start)


@register(12, 1, "HB")
@register(12, 1, "*")
@register(12, -1, "PD")
@register(12, -1, "BP")
class WaveTrains(_UserNdim, PeriodicOrbits):
    """Wave trains (IPS = 12; FNWP, BCPS, ICPS on AUTOBV): ISW = 1, and ISW = -1 at a PD
    (the wave length doubled, STPNPS's PDBLE) or a BP of wave trains."""

    def __init__(self, start: StartData):
        self._doubled_init(PeriodicOrbits, start)


@register(12, 2, "LP")
@register(12, 2, "LPC-curve")
class WaveTrainFolds(_UserNdim, CycleFoldLocus):
    """The fold locus of wave trains (IPS = 12, ISW = 2; FNWPL: the fold of cycles of
    FNWP), with its generating run from the LP."""

    def __init__(self, start: StartData):
        self._doubled_init(CycleFoldLocus, start)


__all__ = ["UniformSolutions", "UniformFolds", "UniformHopf", "WaveTrains", "WaveTrainFolds",
           "doubled"]
