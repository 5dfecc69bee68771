"""The run's constants, resolved for the engine: AUTO's names, checked values.

`Settings.from_constants(c, ...)` maps the run's constants (washer.cont.constants.
Constants) onto this frozen record once, so that the engine never
parses names or applies AUTO's internal redefinitions again (main.f90:INIT1,
support.f90:INIT2: DS = 0 -> 0.1, DSMIN = 0 -> 1e-4 |DS|, the 1 + 1e-7
perturbations, NPAR raised to 11 or 12, THL's default {11: 0} for IPS = 2).

A constant AUTO-07p knows and washer did not: its default in DEFAULTS (the constants
files, AUTO's command language and the b-file headers' readers take their keys from it),
its type in washer.cont.constants (INT_KEYS, REAL_KEYS, ...: check_value checks by them),
and a field of Settings where the engine reads it.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace

import numpy as np


#: AUTO's HMACH, its one "machine" constant of relative size: the perturbation of DS,
#: DSMIN, DSMAX (INIT1), the finite-difference steps HMACH (1 + |u|) (FUNI, BCNI, ICNI,
#: FOPI), the lengthening of location corrections (LCSPAE, LCSPBV) and EQDF's threshold
#: of a negligible derivative.
HMACH = 1e-7

#: AUTO perturbs DS, DSMAX by (1 + HMACH) and DSMIN by 1 / (1 + HMACH) (INIT1), so
#: that b-files show 8.2000000200 rather than 8.2: we do the same.
PERTURB = 1 + HMACH


#: AUTO-07p's problem types (main.f90: AUTOI), every one of which runs here.
PROBLEM_TYPES = (-2, -1, 0, 1, 2, 4, 5, 7, 9, 11, 12, 14, 15, 16, 17)

HUGE = 1.7976e308

#: Every constant AUTO-07p knows, with its default (docs/auto.md section 1.2; main.f90:INIT):
#: one table for the engine and the constants files (washer.cont.constants.Constants).
DEFAULTS: dict[str, object] = {
    "e": "", "s": "", "dat": "", "sv": "", "unames": {}, "parnames": {}, "U": {}, "PAR": {},
    "NDIM": 2, "IPS": 1, "IRS": 0, "ILP": 1, "ICP": [1], "NTST": 20, "NCOL": 4, "IAD": 3,
    "ISP": 2, "ISW": 1, "IPLT": 0, "NBC": 0, "NINT": 0, "NMX": 0, "NPR": 0, "MXBF": 10,
    "IID": 2, "ITMX": 9, "ITNW": 5, "NWTN": 3, "JAC": 0, "EPSL": 1e-7, "EPSU": 1e-7,
    "EPSS": 1e-5, "DS": 0.01, "DSMIN": 0.005, "DSMAX": 0.1, "IADS": 1, "NPAR": 36,
    "THL": {}, "THU": {}, "RL0": -HUGE, "RL1": HUGE, "A0": -HUGE, "A1": HUGE, "UZR": {},
    "UZSTOP": {}, "SP": [], "STOP": [], "IIS": 3, "IBR": 0, "LAB": 0, "TY": "",
    "NUNSTAB": -1, "NSTAB": -1, "IEQUIB": 1, "ITWIST": 0, "ISTART": 5, "IREV": [],
    "IFIXED": [], "IPSI": [],
}
_D = DEFAULTS


class SettingsError(ValueError):
    """Constants that no run can use (a step rule that would never end, a parameter list
    ICP that the continued system cannot use, ...). `keys` names the constants at fault,
    so that the message can point at their place in the constants file."""

    def __init__(self, message: str, keys: tuple = ()):
        super().__init__(message)
        self.keys = tuple(keys)


class SettingsWarning(UserWarning):
    """A constant without effect in this run (a weight on an index it does not have)."""


def split_type_entry(entry: str) -> tuple[str, str]:
    """An SP/STOP entry as (type, count digits): the count starts at the first digit or
    '-' from the third character on (AUTO's CHECKSP/INITSTOPCNTS: SCAN(SP(I)(3:), ...)),
    so 'R11' is the first R1, 'HB3' the third HB, 'LPD1' the first LPD, 'LP0' none."""
    head, tail = entry[:2], entry[2:]
    cut = next((i for i, ch in enumerate(tail) if ch in "-0123456789"), len(tail))
    return (head + tail[:cut]).upper(), tail[cut:]


@dataclass(frozen=True)
class Settings:
    """Everything the iterator, events and systems read. Field names are AUTO's,
    defaults AUTO's (DEFAULTS, with INIT1's perturbations).

    Units: DS, DSMIN, DSMAX are arclength in the THL/THU-weighted norm of the
    unknowns; EPSL, EPSU relative Newton tolerances; EPSS the relative
    location tolerance (|delta s| / (1 + sqrt(|DS DSMAX|)) < EPSS).
    """
    IPS: int = _D["IPS"]
    ISW: int = _D["ISW"]
    ICP: tuple = tuple(_D["ICP"])          # 1-based PAR indices, principal first
    #: IPS = 15: the k of ICP's entries -(20 + k), PAR(k)'s optimality conditions with
    #: fixed values PAR(20 + k), in ICP's order (AUTO's ICP(NFPR + 1..)); ICP holds the
    #: positive entries only.
    OPT_ICP: tuple = ()
    NDIM: int = _D["NDIM"]
    NPAR: int = _D["NPAR"]
    DS: float = _D["DS"] * PERTURB
    DSMIN: float = _D["DSMIN"] / PERTURB
    DSMAX: float = _D["DSMAX"] * PERTURB
    IADS: int = _D["IADS"]
    NMX: int = _D["NMX"]
    NPR: int = _D["NPR"]
    ITMX: int = _D["ITMX"]
    ITNW: int = _D["ITNW"]
    NWTN: int = _D["NWTN"]
    EPSL: float = _D["EPSL"]
    EPSU: float = _D["EPSU"]
    EPSS: float = _D["EPSS"]
    ILP: int = _D["ILP"]
    ISP: int = _D["ISP"]
    MXBF: int = _D["MXBF"]
    JAC: int = _D["JAC"]
    RL0: float = _D["RL0"]
    RL1: float = _D["RL1"]
    A0: float = _D["A0"]
    A1: float = _D["A1"]
    NTST: int = _D["NTST"]
    NCOL: int = _D["NCOL"]
    NBC: int = _D["NBC"]
    NINT: int = _D["NINT"]
    IAD: int = _D["IAD"]
    IPLT: int = _D["IPLT"]
    IID: int = _D["IID"]
    IIS: int = _D["IIS"]
    THL: dict = field(default_factory=dict)      # {PAR index: weight}
    THU: dict = field(default_factory=dict)      # {U index (1-based): weight}
    UZR: tuple = ()            # ((PAR index, value, stop?), ...)
    STOP: dict = field(default_factory=dict)     # {'HB': 3}: stop at the 3rd HB
    SP_OFF: frozenset = frozenset()              # types switched off by SP ('LP0')
    SP_ON: frozenset = frozenset()               # types switched on by SP ('HB')
    #: HomCont's constants (IPS = 9; AUTO's h-file keys): NUNSTAB, NSTAB (-1: counted
    #: at the start's equilibrium), IEQUIB, ITWIST, ISTART, and the lists IREV, IFIXED,
    #: IPSI as tuples.
    NUNSTAB: int = _D["NUNSTAB"]
    NSTAB: int = _D["NSTAB"]
    IEQUIB: int = _D["IEQUIB"]
    ITWIST: int = _D["ITWIST"]
    ISTART: int = _D["ISTART"]
    IREV: tuple = ()
    IFIXED: tuple = ()
    IPSI: tuple = ()

    def theta_par(self, index: int) -> float:
        """THL weight of PAR(index) (1 unless set)."""
        return float(self.THL.get(index, 1.0))

    def theta_u(self, n: int) -> np.ndarray:
        """THU weights of the first n state unknowns, shape (n,)."""
        th = np.ones(n)
        for i, v in self.THU.items():
            if 1 <= i <= n:
                th[i - 1] = v
        return th

    def detects(self, name: str) -> bool:
        """Whether tests of type `name` are on (AUTO's CHECKSP, support.f90, in one
        place): LP by ILP; BP by ISP (IPS < 2, 5, 11: ISP != 0; else |ISP| >= 2 and
        != 4); HB and the codim-2 tests (BT, CP, GH, ZH) for IPS in {-1, 1, 11} and
        ISP not in {0, 3}; PD and TR of cycles for |ISP| in {2, 4} and IPS in {2, 7,
        12}. An SP entry ('LP0' off, 'HB' on) overrides."""
        if name in self.SP_OFF:
            return False
        if name in self.SP_ON:
            return True
        isp = abs(self.ISP)
        if name == "LP":
            return self.ILP != 0
        if name == "BP":
            if self.IPS < 2 or self.IPS in (5, 11):
                return isp != 0
            return isp >= 2 and isp != 4
        if name in ("HB", "BT", "CP", "GH", "ZH"):
            return self.IPS in (-1, 1, 11) and isp not in (0, 3)
        if name in ("PD", "TR"):
            if self.IPS == -1:                  # maps: any ISP but 0
                return isp != 0
            return isp in (2, 4) and self.IPS in (2, 7, 12)
        return False

    def with_(self, **kw) -> "Settings":
        return replace(self, **kw)

    @classmethod
    def from_constants(cls, c) -> "Settings":
        """Resolve AUTO constants (names, defaults, internal redefinitions).
        Raises SettingsError for step settings that cannot work."""
        src = getattr(c, "source", "<constants>")
        ds, dsmin, dsmax = c["DS"], c["DSMIN"], c["DSMAX"]
        for key, v in (("DS", ds), ("DSMIN", dsmin), ("DSMAX", dsmax), ("EPSL", c["EPSL"]),
                       ("EPSU", c["EPSU"]), ("EPSS", c["EPSS"])):
            if not math.isfinite(v):
                raise SettingsError(f"{src}: {key} = {v} is not a finite number")
        if ds == 0:
            ds = 0.1                       # AUTO (INIT1): DS = 0 means 0.1
        if dsmax <= 0:
            raise SettingsError(f"{src}: DSMAX = {dsmax}: expected a positive maximum step")
        if dsmin < 0:
            raise SettingsError(f"{src}: DSMIN = {dsmin}: expected DSMIN >= 0")
        if dsmin == 0:
            dsmin = 1e-4 * abs(ds)         # AUTO (INIT1)
        if dsmin > dsmax:
            raise SettingsError(f"{src}: DSMIN = {dsmin} > DSMAX = {dsmax}: no step size can "
                                "satisfy both; expected DSMIN <= |DS| <= DSMAX")
        for key in ("EPSL", "EPSU", "EPSS"):
            if c[key] <= 0:
                raise SettingsError(f"{src}: {key} = {c[key]}: expected a positive tolerance")
        if c["ITNW"] < 1 or c["ITMX"] < 1 and c["ITMX"] != 0:
            raise SettingsError(f"{src}: ITNW = {c['ITNW']}, ITMX = {c['ITMX']}: expected "
                                "ITNW >= 1 and ITMX >= 0")
        if (abs(c["IPS"]) in (2, 4, 7, 9) or c["IPS"] >= 12) and c["NTST"] < 1:
            # Periodic orbits and boundary value problems live on NTST mesh intervals.
            where = getattr(c, "given", {}).get("NTST", src)
            raise SettingsError(f"{where}: NTST = {c['NTST']}: IPS = {c['IPS']} solves on a "
                                "mesh of NTST intervals: expected NTST >= 1")
        icp_all = tuple(c.icp())
        ips = c["IPS"]
        icp = tuple(i for i in icp_all if i > 0)
        opt_icp = tuple(-i - 20 for i in icp_all if i < 0)
        if opt_icp and ips != 15 or not icp:
            raise SettingsError(f"{src}: ICP = {c['ICP']}: parameter indices start at 1")
        if ips == 15 and len(opt_icp) != len(icp) - 1:
            # AUTOOP: NFPR = (positive entries) + 3 free parameters (with PAR(10), the
            # objective, and the multipliers PAR(13), PAR(14)) for NINT = NFPR - 1
            # integrals: the phase, the objective, the adjoint's norm and one optimality
            # condition per negative entry.
            raise SettingsError(
                f"{c.given.get('ICP', src)}: ICP = {c['ICP']}: IPS = 15 needs one negative "
                f"entry -(20 + k) (the optimality condition of PAR(k)) fewer than positive "
                f"entries: {len(icp)} positive, so {len(icp) - 1} negative, got {len(opt_icp)}")
        if ips not in PROBLEM_TYPES:
            raise SettingsError(f"{getattr(c, 'given', {}).get('IPS', src)}: IPS = {ips} is not a problem type "
                                f"of AUTO-07p: expected one of {', '.join(map(str, PROBLEM_TYPES))}",
                                keys=("IPS",))
        npar = c["NPAR"]
        if ips in (1, -1, 2) or ips >= 7:
            npar = max(npar, 11)             # PAR(11) holds the period (INIT2)
        # PAR(12): the torus angle, where TR points are detected (INIT2: CHECKSP('TR'); an
        # SP entry 'TR' or 'TR0' overrides ISP as in `detects`).
        tr_sp = {split_type_entry(e)[0]: split_type_entry(e)[1] != "0" for e in c["SP"]}
        if tr_sp.get("TR", (ips == 2 and abs(c["ISP"]) in (2, 4))
                     or (ips == -1 and c["ISP"] != 0)) and ips in (-1, 2, 7, 12):
            npar = max(npar, 12)
        npar = max(npar, max(abs(i) for i in icp_all))
        if ips == 15:
            npar = max(npar, 14)             # PAR(12..14): the adjoint's norm, kappa, gamma
        thl = {c.par_index(k): float(v) for k, v in c["THL"].items()}
        if ips in (2, 12) and "THL" not in getattr(c, "given", {}):
            thl = {11: 0.0}
        thu = {c.u_index(k): float(v) for k, v in c["THU"].items()}
        # THU may weigh the unknowns of the extended systems too (U(NDIM + 1..) of Hopf and
        # fold loci, e.g. kappa = omega^2 of a Hopf curve): AUTO allocates THU(NDIM*8).
        for key, weights, top, what in (("THL", thl, npar, "NPAR"),
                                        ("THU", thu, 8 * c["NDIM"], "8 NDIM")):
            for i in list(weights):
                where = getattr(c, "given", {}).get(key, src)
                if i < 1:
                    raise SettingsError(f"{where}: {key} weight on index {i}: expected an index "
                                        f"in 1..{what}={top}")
                if i > top:
                    # AUTO ignores such a weight (some of its demos carry one): said, dropped.
                    warnings.warn(f"{where}: {key} weight on index {i} has no effect: not an "
                                  f"index of this run (1..{what}={top})", SettingsWarning,
                                  stacklevel=2)
                    del weights[i]
        uz = [(abs(i), v, i < 0) for i, v in c.par_values("UZR")]
        uz += [(abs(i), v, True) for i, v in c.par_values("UZSTOP")]
        for i, _, _ in uz:
            if i < 1:
                raise SettingsError(f"{src}: UZR/UZSTOP on PAR({i}): expected an index in "
                                    f"1..NPAR={npar}")
        # AUTO tests a UZR/UZSTOP value on any parameter of its PAR array, which is longer
        # than the c-file's NPAR (HomCont's demos fhh and fnb stop on PSI 13 = PAR(33) with
        # NPAR = 14, the test functions of the run before): the parameters widen to cover it.
        npar = max([npar] + [i for i, _, _ in uz])
        stop, off, on = {}, set(), set()
        for entry in list(c["STOP"]):
            name, num = split_type_entry(entry)
            stop[name] = int(num or 1)
        for entry in list(c["SP"]):
            name, num = split_type_entry(entry)
            if num == "0":
                off.add(name)
            else:
                on.add(name)
                if num:
                    stop[name] = int(num)
        isw = c["ISW"] if c["ISW"] != 0 else 1
        return cls(IPS=ips, ISW=isw, ICP=icp, OPT_ICP=opt_icp, NDIM=c["NDIM"], NPAR=npar,
                   DS=ds * PERTURB, DSMIN=dsmin / PERTURB, DSMAX=dsmax * PERTURB,
                   IADS=c["IADS"], NMX=c["NMX"], NPR=c["NPR"], ITMX=c["ITMX"], ITNW=c["ITNW"],
                   NWTN=c["NWTN"], EPSL=c["EPSL"], EPSU=c["EPSU"], EPSS=c["EPSS"],
                   ILP=c["ILP"], ISP=c["ISP"], MXBF=c["MXBF"], JAC=c["JAC"], RL0=c["RL0"],
                   RL1=c["RL1"], A0=c["A0"], A1=c["A1"], NTST=c["NTST"], NCOL=c["NCOL"],
                   NBC=c["NBC"], NINT=c["NINT"],
                   IAD=c["IAD"], IPLT=c["IPLT"], IID=c["IID"], IIS=c["IIS"], THL=thl, THU=thu,
                   UZR=tuple(uz), STOP=stop, SP_OFF=frozenset(off), SP_ON=frozenset(on),
                   NUNSTAB=int(c["NUNSTAB"]), NSTAB=int(c["NSTAB"]), IEQUIB=int(c["IEQUIB"]),
                   ITWIST=int(c["ITWIST"]), ISTART=int(c["ISTART"]),
                   IREV=tuple(int(v) for v in c["IREV"]),
                   IFIXED=tuple(int(v) for v in c["IFIXED"]),
                   IPSI=tuple(int(v) for v in c["IPSI"]))
