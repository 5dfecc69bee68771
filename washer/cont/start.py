"""Where a run starts: constants + problem + restart records -> the settings, the start
data and the continued system (AUTO's RSPTAE/RSPTBV, the registry's lookup), then the
run's numbering (NEWLAB: branch and label numbers) and the b-file's column titles.

Each function does one of those jobs; `washer.cont.runner.build` strings them together.
Errors are `RunError`s naming the constants file and what was expected.
"""
from __future__ import annotations

import re
import warnings

import numpy as np

from washer.cont.codes import split_code, type_name
from washer.cont.parabolic import PARABOLIC_KINDS, TIME, ParabolicProblem
from washer.cont.record import find_record
from washer.cont.problem import ProblemError, ProblemWarning
from washer.cont.settings import Settings, SettingsError
from washer.cont.system import StartData
from washer.cont.systems import find


class RunError(RuntimeError):
    """A run could not start (bad constants, missing restart label, ...)."""


def settings_for(c, problem) -> tuple[Settings, object]:
    """The run's Settings from the constants, checked against the equations, and the
    problem with the constants' JAC applied."""
    try:
        s = Settings.from_constants(c)
    except SettingsError as exc:
        raise RunError(str(exc)) from None
    if s.NDIM != problem.ndim:
        raise RunError(f"{c.source}: NDIM={s.NDIM} but the equations '{problem.name}' have "
                         f"{problem.ndim} unknowns")
    if s.ISW not in (1, -1, 2, 3):
        # (AUTO's ISW = -2 is the generating run of a locus of cycles, which ISW = 2 at an
        # LP, PD or TR label of cycles does here; at a label of a curve of equilibria
        # AUTO-07p takes one step and ends MX, and with one free parameter refuses.)
        raise RunError(f"{c.source}: ISW={s.ISW} (IRS={c['IRS']!r}): expected 1, -1 (branch "
                         "switching), 2 (the locus of a special point) or 3 (the "
                         "branch-point locus of a generic problem)")
    for key in ("LAB", "IBR"):
        if c[key] < 0:
            raise RunError(f"{c.source}: {key}={c[key]}: expected a number >= 0 "
                             "(0 = automatic)")
    problem = problem.with_jac(s.JAC)
    if s.IPS == 9 and hasattr(problem, "set_homcont"):
        # AUTO's INHO fills COMMON /BLHOM/ before STPNT (ISTART = 5 is 1 from STPNT)
        problem.set_homcont([s.ITWIST, 1 if s.ISTART == 5 and c["IRS"] in (0, "0") else
                             s.ISTART, s.IEQUIB, len(s.IFIXED), len(s.IPSI), s.NUNSTAB,
                             s.NSTAB, 1 if s.IREV else 0])
    if s.IPS in PARABOLIC_KINDS:
        # AUTOPE: the PDE's first-order system of 2 NDIM components (u, u_x) is what
        # every problem type of a parabolic PDE continues; the user's STPNT fills them.
        problem = ParabolicProblem(problem, PARABOLIC_KINDS[s.IPS])
    if s.IPS in (14, 16):
        # Time evolution: the time PAR(14) is the continuation parameter whatever ICP(1)
        # names, without fold or bifurcation tests (AUTOPE: ICP(1) = 14, ILP = ISP = 0).
        s = _time_first(s).with_(ILP=0, ISP=0)
    if problem.npar > s.NPAR:
        s = s.with_(NPAR=problem.npar)      # the equations read PAR up to their npar
    if s.IPS == -2 and s.ICP[0] != TIME:
        # Time integration integrates in the time PAR(14) whatever ICP(1) names (AUTO's
        # AUTOTI: ICP(1) = 14, NFPR = 1): run('x', IPS=-2, ICP=[1, ..]) leaves PAR(1) as
        # it is, where taking ICP(1) for the time would integrate with PAR(1) moving.
        s = _time_first(s)
    return s, problem


def warn_unset_dfdp(s: Settings, problem, u, par) -> None:
    """A ProblemWarning for each continuation parameter whose derivative the user's
    DFDP leaves zero at the start while f depends on it (`Problem.unset_dfdp`, at the
    start point or the first point of a start orbit), with JAC = 1. AUTO-07p's FUNC
    gets DFDP zero-filled and its Newton takes those zeros as exact, without a word:
    it may converge slowly or diverge (she.f's first step). Runs of equilibria and
    fixed points here take DFDP from the user too; orbits take their parameter
    derivatives by differences of f, and the warning says the file is wrong for AUTO."""
    unset = getattr(problem, "unset_dfdp", None)
    u = np.asarray(u, dtype=float)
    point = u if u.ndim == 1 else u[0]
    if unset is None or u.ndim > 2 or len(point) != problem.ndim:
        return
    used = s.IPS in (-1, 0, 1, 5) and u.ndim == 1
    for i, size in unset(point, par, [i for i in s.ICP if 0 < i <= len(par)]):
        what = ("JAC = 1 takes d f / d PAR({i}) from FUNC's DFDP (as AUTO-07p does)" if used
                else "AUTO-07p's JAC = 1 takes d f / d PAR({i}) from FUNC's DFDP (washer "
                "differences f for it here)").format(i=i)
        warnings.warn(f"{problem.source or problem.name}: {what}, which is zero at the "
                      f"start, but f changes with PAR({i}) (central difference: max "
                      f"|d f / d PAR({i})| = {size:.3g}): set DFDP(., {i}) in FUNC or use "
                      f"JAC = -1 (differences in the parameters)", ProblemWarning,
                      stacklevel=2)


def _time_first(s: Settings) -> Settings:
    """s with the time PAR(14) as ICP(1), the other ICP entries after it without PAR(14),
    and NPAR at least 14: the continuation parameter of time integration (IPS = -2) and
    time evolution (IPS = 14, 16)."""
    return s.with_(ICP=[TIME] + [i for i in s.ICP[1:] if i != TIME], NPAR=max(s.NPAR, TIME))


def with_record_parameters(s: Settings, rec) -> Settings:
    """s with NPAR at least the restart record's own parameters, its NPAR less its NPARI
    (AUTO's FINDLB_OR_STOP): a record's PAR past the constants' NPAR reach the equations
    and the run's records (r3b's manifold start holds the orbit's point and Floquet
    vector in PAR(25..36) and runs with NPAR = 16)."""
    if rec is None or len(rec.par) - rec.npari <= s.NPAR:
        return s
    return s.with_(NPAR=len(rec.par) - rec.npari)


def restart_record(c, problem, records, records_source: str = "the restart file"):
    """The record IRS names (AUTO's FINDLB), or None for IRS = 0."""
    irs = c["IRS"]
    if irs in (0, "0"):
        return None
    if not records:
        raise RunError(f"{c.source}: IRS={irs!r} needs a restart file (s=NAME) with records")
    try:
        rec = find_record(records, irs)
    except LookupError as exc:
        raise RunError(f"{records_source}: {exc}") from None
    # A general BVP may restart from a solution of fewer components (AUTO's READBV
    # fills the others with 0: pcl's connecting orbits start from a periodic orbit).
    ndim = getattr(problem, "ndm", problem.ndim)      # a parabolic PDE's user NDIM
    widen = c["IPS"] in (4, 7) and np.ndim(rec.u) == 2 and rec.ndim_user < ndim
    if rec.ndim_user != ndim and not widen:
        raise RunError(f"{c.source}: IRS={irs!r} names a solution of a problem with NDIM="
                         f"{rec.ndim_user}, but these equations have NDIM={ndim}")
    return rec


def start_values(c, s: Settings, problem, rec, data=None) -> tuple[np.ndarray, np.ndarray]:
    """(u, par): the record's stored state and PAR (or the problem's stpnt), with the
    constants' PAR and U overrides applied. par has at least NPAR entries. With start
    data (t, U) of dat='NAME', PAR(11) is the data's period t[-1] - t[0] where stpnt
    leaves it unset (AUTO's STPNUB sets PAR(11), then calls STPNT, then the overrides)."""
    if rec is not None:
        u = np.array(rec.u, dtype=float)
        par = np.zeros(max(s.NPAR, len(rec.par)))
        par[:len(rec.par)] = rec.par
    elif s.IPS == 9 and s.ISTART < 0:
        # HomCont's N + 1 pieces from STPNT: AUTO's STPNT fills the (N + 1) NDIM
        # components and the NPAR + NPARI parameters (Lin's direction, f(x_max))
        from washer.cont.systems import homoclinic_switching as sw
        ndim, npar = sw.start_dimensions(s.NDIM, s.ISTART, s.NPAR)
        u, par = problem.start(npar, ndim=ndim)
    else:
        u, par = problem.start(s.NPAR)
    if len(par) < s.NPAR:
        par = np.r_[par, np.zeros(s.NPAR - len(par))]
    if data is not None and rec is None and len(par) > 10 and par[10] == 0:
        par[10] = float(data[0][-1] - data[0][0])
    for k, v in c["PAR"].items():
        i = c.par_index(k)
        if not 1 <= i <= len(par):
            raise RunError(f"{c.source}: PAR={{{k!r}: ...}}: PAR({i}) is outside 1..NPAR="
                             f"{len(par)}")
        par[i - 1] = float(v)
    for k, v in c["U"].items():
        i = c.u_index(k)
        if not 1 <= i <= problem.ndim:
            raise RunError(f"{c.source}: U={{{k!r}: ...}}: U({i}) is outside 1..NDIM="
                             f"{problem.ndim}")
        if u.ndim == 1:
            u[i - 1] = float(v)
    return u, par


#: Start kinds of points of the loci of cycles (IPS = 2, ISW = 2).
CYCLE_CURVES = ("LPC-curve", "BPC-curve", "PD-curve", "TR-curve")

#: Start kinds of points of the loci of equilibria (IPS = 0 or 1, ISW = 2 or 3).
ALGEBRAIC_CURVES = ("LP-curve", "HB-curve", "BP-curve")


def start_kind(rec) -> str:
    """The registry's start kind of a record: its type name, or 'HB-curve' / 'LP-curve'
    for points of the ISW = 2 curves of algebraic problems (the record's written code
    carries the curve: a UZ on a Hopf curve is -34)."""
    if rec is None:
        return ""
    base, curve = split_code(rec.code)
    if curve in (1, 2, 3) and np.ndim(rec.u) == 1:
        return {1: "BP-curve", 2: "LP-curve", 3: "HB-curve"}[curve]
    if curve == 5 and rec.ips in (4, 7, 9):
        return "LP-curve"            # a point of the fold locus of a BVP (ISW = 2)
    if curve == 6 and rec.ips in (4, 7):
        return "BP-curve"            # a point of the branch-point locus of a BVP
    if curve in (7, 8) and rec.ips == -1 and np.ndim(rec.u) == 1:
        # a point of the period-doubling or Neimark-Sacker locus of a map (maps.f90's
        # ITPST 7, 8)
        return {7: "PD-curve", 8: "TR-curve"}[curve]
    if curve in (5, 6, 7, 8) and rec.ips in (2, 12) and np.ndim(rec.u) == 2:
        # a point of a locus of folds, branch points, period doublings or tori of cycles
        return {5: "LPC-curve", 6: "BPC-curve", 7: "PD-curve", 8: "TR-curve"}[curve]
    return type_name(base)


def restart_type(c, ty: str, par: np.ndarray) -> tuple[str, np.ndarray]:
    """AUTO's TY constant: the restart point is taken to be of type TY(1:2) (e.g. a UZ
    label restarted as 'HB' starts periodic orbits there), and digits after the name
    name the PAR index holding the period (TY = 'HB5': PAR(11) = PAR(5), as AUTO's
    Hopf starts read it: FFHBX)."""
    name, digits = ty[:2].upper(), ty[2:].strip()
    if name not in {"BP", "LP", "HB", "UZ", "PD", "TR", "EP"}:
        raise RunError(f"{c.source}: TY={ty!r}: the type must start with BP, LP, HB, UZ, PD, "
                       "TR or EP")
    if digits:
        if not digits.isdigit() or not 1 <= int(digits) <= len(par):
            raise RunError(f"{c.source}: TY={ty!r}: after the type, the index of the PAR "
                           f"holding the period (1..{len(par)}) was expected")
        par[10] = par[int(digits) - 1]
    return name, par


def system_for(c, s: Settings, problem, u, par, rec, data=None):
    """The continued system of the start (registry key (IPS, ISW, start kind)) and the
    settings it runs with (restarting a point of a curve continues the curve)."""
    irs = c["IRS"]
    kind = start_kind(rec)
    ty = str(c["TY"] or "").strip()
    if ty and rec is not None:
        kind, par = restart_type(c, ty, par)
    if s.IPS == 2 and abs(s.ISW) <= 1 and kind == "HB-curve" and np.ndim(rec.u) == 1:
        # INITPS: ITP = 3 or |ITP| / 10 = 3 starts periodic orbits as from an HB: any
        # point of a Hopf curve (its record holds the state first and the period in
        # PAR(11), as an HB's).
        kind = "HB"
    if s.IPS == 2 and kind == "HB" and s.ISW == -1:
        s = s.with_(ISW=1)          # INITPS: ISW = 1 when starting from an HB
    # A problem that supplies its period map has its periodic orbits by shooting
    # (washer.cont.systems.shooting), from its stpnt or a record of such a run.
    shooting = s.IPS == 2 and problem.has_flow
    # A general BVP or a stored periodic orbit (AUTO's CNRLBV: IPERP = 1 whenever IRS != 0
    # and ISW < 0) takes ISW = -1 at any other point as a start along the null vector of
    # its Jacobian (STDRBV's orientation): where the null space is one-dimensional that is
    # the branch itself.
    # Periodic orbits restarted from a stored orbit run by CNRLBV as well.
    stored_orbit = rec is not None and (s.IPS in (4, 7) or (s.IPS == 2 and np.ndim(rec.u) == 2))
    # Algebraic problems restarted at any other label: CNRLAE's STPRAE with IPERP = 1
    # (washer.cont.systems.equilibrium). A label of a fold, Hopf or branch-point curve
    # too: with |ISW| < 2 FINDLB sets ITPST = 0, so AUTO continues the equilibria in
    # PAR(ICP(1)) alone, the curve's other parameters fixed at the label's values, from
    # the record's first NDIM unknowns and its direction's (READLB).
    algebraic = rec is not None and s.IPS in (0, 1) and \
        (not kind.endswith("curve") or
         (s.ISW == -1 and kind in ALGEBRAIC_CURVES and np.ndim(rec.u) == 1))
    if s.ISW == -1 and kind not in ("BP", "PD") and not stored_orbit and not algebraic:
        raise RunError(f"{c.source}: ISW=-1 switches branches at a BP or PD label, got "
                         f"{kind or 'a regular point'} (IRS={irs!r})")
    if s.IPS == 2 and rec is not None and np.ndim(rec.u) == 1 and kind != "HB" \
            and not shooting:
        raise RunError(f"{c.source}: IPS=2 starts from an HB label or a stored periodic "
                         f"solution, got {kind or 'a regular point'} of an algebraic branch "
                         f"(IRS={irs!r})")
    # A start without a restart label (IRS = 0) has no special point whose locus ISW = 2
    # or 3 could continue: AUTO sets ITPST from the label's type in FINDLB, which only a
    # restart calls, so with IRS = 0 ITPST = 0 and the run is an ordinary branch from
    # STPNT (the header and the records keep the ISW given).
    fresh_locus = rec is None and s.ISW in (2, 3)
    if s.ISW == 2 and kind in ("EP", "UZ", "", "RG") and not fresh_locus:
        raise RunError(f"{c.source}: ISW=2 continues the locus of a special point: restart "
                         f"at an LP, HB, BP, PD or TR label, got {kind or 'a regular point'} "
                         f"(IRS={irs!r})")
    if s.ISW == 3 and kind not in ("BP", "BP-curve", "BPC-curve") and not fresh_locus:
        raise RunError(f"{c.source}: ISW=3 continues the branch points of a generic problem: "
                       f"restart at a BP label, got {kind or 'a regular point'} (IRS={irs!r})")
    # ISW = 1 at a label of a curve of equilibria: FINDLB's ITPST = 0 (|ISW| < 2), so
    # AUTO continues the equilibria in PAR(ICP(1)) from it, as from any label (a curve's
    # solutions carry the constants of their run, ISW = 2 or 3, so run(curve('UZ1'))
    # goes on along the curve).
    # Maps alike (AUTODS with ITPST = 0): the fixed points from a point of a locus.
    equilibria = s.IPS in (0, 1, -1) and s.ISW == 1 and \
        kind in ALGEBRAIC_CURVES + ("PD-curve", "TR-curve") and np.ndim(rec.u) == 1
    # A BVP alike (AUTOBVP continues the fold locus only for |ISW| = 2): the BVP's branch
    # from a point of its fold locus, the record's first NDIM components (READBV).
    equilibria = equilibria or (s.IPS in (4, 7) and s.ISW == 1 and kind == "LP-curve")
    if s.ISW == 1 and kind == "BP-curve" and abs(rec.isw) in (2, 3) and not equilibria:
        # ... a branch-point locus of a BVP as it was computed: non-generic (2) or
        # generic (3), which its stored unknowns mean (b or PAR(ICP(3)))
        s = s.with_(ISW=abs(rec.isw))
    # ISW = 3 (the generic BP locus) is the same system as ISW = 2 (it reads ISW).
    isw_key = -1 if s.ISW == -1 and (kind == "BP" or algebraic) else \
        (2 if (s.ISW in (2, 3) and not fresh_locus) or (kind.endswith("curve") and not equilibria)
         else 1)
    if kind in CYCLE_CURVES and s.ISW not in (2, 3):
        isw_key = 1       # ISW = 1 at a point of a locus of cycles: the orbit's branch
    try:
        ctor = find(s.IPS, isw_key, "shooting" if shooting else kind)
    except KeyError as exc:
        raise RunError(f"{c.source}: {exc.args[0]}") from None
    names = {int(k): v for k, v in c["unames"].items()}
    try:
        system = ctor(StartData(problem, s, u, par, rec, kind, names,
                                data if rec is None else None))
    except SettingsError as exc:
        # The constants are at fault (ICP names too few parameters for the system, ...),
        # not the start point: the message points at the constants' place.
        key = next((k for k in exc.keys if k in c.given), exc.keys[0] if exc.keys else None)
        place = c.given.get(key, "") if key else ""
        where = place if re.search(r":\d+$", place) else \
            (f"{c.source}: {key}" if key else c.source)
        raise RunError(f"{where}: {exc}") from None
    except (ValueError, ProblemError, np.linalg.LinAlgError) as exc:
        raise RunError(f"{c.source}: cannot start from {kind or 'this point'}: {exc}") \
            from None
    # A system may run under AUTO's internal redefinitions of the constants (the fold
    # locus of a BVP: NDIM, NBC, NINT doubled; its generating run NMX = 5, ILP = ISP = 0).
    return system, getattr(system, "run_settings", s), kind


def branch_number(c, s: Settings, rec, kind: str, records, mbr: int | None = None) -> int:
    """AUTO's NEWLAB: IBR if given; a new branch after the file's highest (or `mbr`) for
    IRS = 0 and switches; the HB's label for a periodic branch from it (and for a curve
    started at a special point; not from a point of a Hopf curve: NEWLAB asks ITP = 3);
    else the record's branch."""
    if mbr is None:
        mbr = max((abs(r.br) for r in records), default=0) if records else 0
    if c["IBR"]:
        return c["IBR"]
    if rec is None or s.ISW < 0:
        return mbr + 1
    if s.IPS in (2, 12) and s.ISW in (2, 3) and kind in ("LP", "PD", "TR", "BP"):
        # A locus of cycles started at its special point: AUTO's INITPS makes that run
        # ISW = -2 (its generating run), so NEWLAB gives it a new branch.
        return mbr + 1
    if (abs(rec.code) < 10 and abs(s.ISW) == 2) or \
            (s.IPS in (2, 12) and kind == "HB" and split_code(rec.code)[1] != 3) or \
            (s.IPS == 5 and kind == "LP"):
        # (IPS = 5: the extremum continued in one parameter more from its LP)
        return rec.lab
    return abs(rec.br)


def first_label(c, records, mlab: int | None = None) -> int:
    """The label before the run's first: LAB - 1 when LAB is given (LAB is the first
    label, AUTO's NEWLAB), else the restart file's highest (or `mlab`)."""
    if c["LAB"]:
        return c["LAB"] - 1
    if mlab is None:
        mlab = max((r.lab for r in records), default=0) if records else 0
    return mlab


def column_titles(c, s: Settings, system) -> list:
    """The b-file's titles: PAR(ICP(1)), the system's columns, the other free parameters,
    each as AUTO's HEADNG names it: the parnames name, else PERIOD for PAR(11) where
    IPS > 0 and not 4 or 7 (periodic orbits: not general BVPs, maps or algebraic
    problems), FOPT for PAR(10) with IPS 5 or 15, TIME for PAR(14) with IPS 14 or 16,
    else PAR(i)."""
    pn = {int(k): v for k, v in c["parnames"].items()}

    def title(i: int) -> str:
        if i in pn:
            return pn[i]
        if i == 11 and s.IPS > 0 and s.IPS not in (4, 7):
            return "PERIOD"
        if i == 10 and s.IPS in (5, 15):
            return "FOPT"
        if i == 14 and s.IPS in (14, 16):
            return "TIME"
        return f"PAR({i})"
    return [title(s.ICP[0])] + list(system.column_titles()) + [title(i) for i in s.ICP[1:]]
