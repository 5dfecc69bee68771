"""The fold locus of homoclinic orbits (IPS = 9, ISW = 2 from an LP: HomCont's FNHOL,
BCHOL, ICHOL, which apply AUTO's BVP fold machinery FNBLF/BCBLF/ICBLF to FNHO, BCHO and
ICHO).

The homoclinic orbit's extended BVP (washer.cont.systems.homoclinic: the orbit scaled by
PAR(11), its projection boundary conditions, f(x0) = 0 where the equilibrium is solved
for, the phase condition) is handed as it is to the BVP fold locus of
washer.cont.systems.general_bvp (`BVPFoldLocus`: the BVP with its null vector, in the
branch's m free parameters and one more). The branch's free parameters are the
homoclinic system's (the user's first ones, PAR(10) with ITWIST = 1, then the
equilibrium's PAR(12 ..)); the one more is the user's next ICP entry. As AUTO's, the
start at the LP is a generating run and a restart from its end continues the locus.
"""
from __future__ import annotations

import numpy as np

from washer.cont.settings import SettingsError
from washer.cont.system import StartData, register
from washer.cont.systems.general_bvp import BVPFoldLocus
from washer.cont.systems.homoclinic import HomoclinicOrbits


@register(9, 2, "LP")
@register(9, 2, "LP-curve")
class HomoclinicFoldLocus(BVPFoldLocus):
    """See the module docstring. `data` is the run's: the user's problem and constants,
    the LP's record (or a record of this locus to restart from)."""

    def __init__(self, data):
        s = data.settings
        # The homoclinic system at the record (its orbit part: a locus record carries the
        # null vector beside it), for its extended BVP and its free parameters.
        orbit = HomoclinicOrbits(StartData(data.problem, s.with_(ISW=1), data.u, data.par,
                                           data.record, "", data.unames, data.data))
        hs = orbit.run_settings
        free = list(orbit._free)
        rest = [i for i in s.ICP if i not in free]
        if not rest:
            raise SettingsError(f"ISW = 2 (the fold locus of homoclinic orbits) frees one "
                                f"more parameter than the branch's {free}: ICP = "
                                f"{list(s.ICP)} names none", keys=("ICP",))
        par = np.asarray(orbit.par, float)
        rec = data.record
        npari = int(getattr(rec, "npari", 0) or 0) if data.kind != "LP" else 0
        if npari:
            # A record of this locus: the homoclinic system drops its internal parameters
            # (the null vector's parameter components q and its norm, AUTO's NPARI last
            # PAR), which the locus's equations need as they were: with q = 0 and norm 0
            # the null vector's norm condition is singular (a double zero of |v|^2 + |q|^2)
            # and the restart's first step converges or not by rounding.
            p = np.asarray(data.par, float)
            par = np.r_[par, p[len(p) - npari:]]
        s2 = hs.with_(ISW=2, ICP=free + rest, IPS=9)
        super().__init__(StartData(orbit.problem, s2, data.u, par, data.record, data.kind,
                                   data.unames))
        self.homcont_internal = orbit.homcont_internal


__all__ = ["HomoclinicFoldLocus"]
