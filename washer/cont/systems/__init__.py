"""The continued systems, one module each; importing a module fills its entries of the
registry `washer.cont.system.SYSTEMS` (each module registers its classes), and a run
imports those of its IPS only (`find`): all of them, with the collocation code they
share, are a third of a short equilibrium run's instructions where Python compiles
their sources afresh.

equilibrium  f(u, par) = 0 in one parameter (IPS = 0, 1; AUTO's FUNI)
fold         the fold locus in two parameters (ISW = 2 from LP; FNLP)
hopf         the Hopf locus in two parameters (ISW = 2 from HB; FNHB)
branch_point the branch-point locus of algebraic problems (ISW = 2 or 3 from BP; FNBP)
algebraic_optimisation
             extrema of FOPT on f = 0 (IPS = 5; FNC1, FNC2)
periodic     periodic orbits by collocation (IPS = 2; FNPS), PD and BP switching
cycle_fold   the locus of folds of cycles in two parameters (IPS = 2, ISW = 2; FNPL)
cycle_pd_tr  the loci of period doublings and tori (IPS = 2, ISW = 2; FNPD, FNTR)
cycle_branch_point
             the locus of branch points of cycles (IPS = 2, ISW = 2 or 3; FNPBP)
bvp          the collocation base of periodic orbits and their loci (registers nothing)
general_bvp  general boundary value problems (IPS = 4; BCND, ICND), BP switching, and
             their fold locus (ISW = 2 from LP; FNBL)
homoclinic   homoclinic orbits on the general BVP (IPS = 9, HomCont; FNHO, BCHO, ICHO)
homoclinic_adjoint, homoclinic_homotopy, homoclinic_switching
             HomCont's adjoint (ITWIST = 1), homotopy start (ISTART = 3) and n-homoclinic
             branch switching (ISTART = -N) (register nothing: parts of homoclinic's system)
homoclinic_fold
             the fold locus of homoclinic orbits (IPS = 9, ISW = 2 from LP; FNHOL)
bvp_branch_point
             the branch-point locus of general BVPs (IPS = 4, ISW = 2 or 3; FNBBP)
bvp_floquet  general BVPs whose points carry Floquet multipliers (IPS = 7)
waves        travelling waves of a parabolic PDE (IPS = 11, 12; FNWS, FNWL, FNHW, FNWP)
parabolic_bvp
             stationary states and time evolution of a parabolic PDE (IPS = 17, 14, 16;
             FNSP, FNPE)
periodic_optimisation
             optimisation of periodic orbits (IPS = 15; FNPO, BCPS, ICPO)
shooting     periodic orbits of a problem that supplies its period map (IPS = 2)
maps         fixed points of maps (IPS = -1; FNDS), PD switching, fold/PD/NS loci
timeint      time integration by implicit Euler steps (IPS = -2; FNTI)
circles      invariant circles of maps (Fourier collocation), born at a Neimark-Sacker point;
             constructed by its runs (washer.cont.circle_runs), not from AUTO constants
_algebraic, _loci  the bases of the algebraic systems
"""
import importlib

from washer.cont.system import lookup

#: IPS -> the modules registering its systems (tests/test_engine_contract.py reads every
#: module's register() calls against it; one missing here costs a run time, not its system:
#: `find` then imports them all).
MODULES = {
    0: ("equilibrium", "fold", "branch_point"),
    1: ("equilibrium", "fold", "hopf", "branch_point"),
    -1: ("maps",),
    -2: ("timeint",),
    2: ("periodic", "shooting", "cycle_fold", "cycle_pd_tr", "cycle_branch_point"),
    4: ("general_bvp", "bvp_branch_point"),
    5: ("algebraic_optimisation",),
    7: ("bvp_floquet",),
    9: ("homoclinic", "homoclinic_fold"),
    11: ("waves",),
    12: ("waves",),
    14: ("parabolic_bvp",),
    15: ("periodic_optimisation",),
    16: ("parabolic_bvp",),
    17: ("parabolic_bvp",),
}


def load(ips: int | None = None) -> None:
    """Import the modules registering the systems of `ips` (None: every module)."""
    if ips is None:
        import pkgutil
        names = [m.name for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_")]
    else:
        names = MODULES.get(ips, ())
    for name in names:
        importlib.import_module(f"{__name__}.{name}")


def find(ips: int, isw: int, kind: str):
    """The constructor for (IPS, ISW, start kind) (washer.cont.system.lookup), its IPS's
    modules imported first; a KeyError naming what exists when there is none."""
    load(ips)
    try:
        return lookup(ips, isw, kind)
    except KeyError:
        load()
        return lookup(ips, isw, kind)
