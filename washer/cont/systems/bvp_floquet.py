"""Boundary value problems with Floquet multipliers (AUTO's IPS = 7).

A general BVP (general_bvp.BoundaryValueProblem: the user's FUNC, BCND, ICND, its LP and
BP tests, starts and restarts) whose points also carry the multipliers of the linearised
equation over [0, 1]: the eigenvalues of the monodromy matrix -P1^-1 P0 of the condensed
collocation system P0 y(0) + P1 y(1) = 0 (AUTO's CONPAR, REDUCE, FLOWKM), as for periodic
orbits. They are meant for a periodic orbit posed by the user as a BVP (periodicity in
BCND, a phase condition in ICND, the period a parameter of FUNC): AUTO-07p then writes
them to the d-file, counts them as it counts a cycle's (the multiplier closest to 1 is
the trivial one; 'Multiplier inaccurate' when it is not within 5e-2 of 1) and gives the
b-file's PT the sign of stability (negative when all NDIM count as stable), with the
tests of cycles where ISP asks for them (PD and TR: washer.cont.floquet).

AUTO-07p runs it as its periodic orbits (AUTOPS: FUNI, BCNI, ICNI with STPNPS and
FNCSPS, the tests of cycles; a restart moved onto another NTST by the periodic ADAPT2).
Its fold and branch-point loci (ISW = 2, 3) are IPS = 4's (AUTO's AUTOBVP continues
both problem types by FNBL and FNBBP), registered here for IPS = 7.
"""
from __future__ import annotations

import numpy as np

from washer.cont import floquet, reduction
from washer.cont.system import Stability, register
from washer.cont.systems.bvp_branch_point import BVPBranchPointLocus
from washer.cont.systems.general_bvp import BoundaryValueProblem, BVPFoldLocus

for _kind in ("LP", "LP-curve"):
    register(7, 2, _kind)(BVPFoldLocus)
for _kind in ("BP", "BP-curve"):
    register(7, 2, _kind)(BVPBranchPointLocus)


@register(7, 1, "*")
@register(7, -1, "BP")
class BoundaryValueFloquet(BoundaryValueProblem):
    """The continued system of IPS = 7 (IPS = 4's, with multipliers and the tests of
    cycles)."""

    _suspended = False
    restart_periodic = True          # STPNPS's ADAPT2

    def multipliers(self, x) -> np.ndarray:
        """The multipliers at x in AUTO's order (floquet.pencil_multipliers), from the
        collocation blocks of f_u at x."""
        U, par = self.unpack(x)
        N, m, n = self.mesh.ntst, self.mesh.ncol, self.ndim
        fu, _ = self.gauss_fu_fp(self.at_gauss(U).reshape(-1, n), par)
        blocks = self.coll.local_blocks(1.0, fu.reshape(N, m, n, n))
        return floquet.pencil_multipliers(*reduction.floquet_pair(blocks, n))

    def stability(self, x, J=None) -> Stability | None:
        """Multipliers and AUTO's NINS (floquet.stability); None when ISP = 0."""
        if self.settings.ISP == 0:
            return None
        return floquet.stability(self.multipliers(x), self.ndim, self._suspended)

    def active_tests(self) -> list:
        return floquet.active_tests(self.settings, self.ndim)

    def test_functions(self, x, tangent, J, stability, factor, codes=None) -> dict:
        codes = self.active_tests() if codes is None else [int(c) for c in codes]
        out = super().test_functions(x, tangent, J, stability, factor,
                                     [c for c in codes if c != floquet.SPB])
        if floquet.SPB in codes:
            out.update(floquet.test_functions([floquet.SPB], tangent, stability,
                                              self.settings.EPSS, self.ndim,
                                              kinds=floquet.spb_kinds(self.settings)))
        return out

    def accept(self, code, prev, cur) -> bool:
        return floquet.accept(code, prev, cur, self.ndim)

    def located_code(self, key, point) -> int:
        return floquet.spb_code(key, point.stability, self.settings.EPSS)

    def update(self, x, tangent) -> None:
        """The BVP's references move (general_bvp), and the 'multiplier inaccurate'
        state with the accepted point."""
        super().update(x, tangent)
        st = self.stability(x)
        if st is not None:
            self._suspended = floquet.inaccurate(st)


__all__ = ["BoundaryValueFloquet"]
