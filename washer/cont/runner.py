"""One AUTO run: constants + problem (+ restart records) -> branches, through sinks.

This is AUTO's AUTOAE/AUTOBV driver: it resolves the start (IRS, ISW, the
restart record's type) to a continued system from the registry, numbers
branches, points and labels as AUTO does, applies the stop rules (NMX, the
RL0/RL1/A0/A1 window, UZSTOP and negative UZR, STOP/SP counts, negative
ILP/ISP, BT on Hopf curves, MX) and switches branches at BPs (MXBF, a queue:
BPs found on switched branches are switched at too, up to |MXBF| in the whole
run; positive MXBF traces both directions, negative one). Points go to the
sinks; the result is an in-memory `Branch`.
"""
from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass, field

import numpy as np

import washer.cont.systems  # noqa: F401  (fills the registry)
from washer.cont.branch import Branch, Labelled, Point
from washer.auto.codes import Code, curve_code, split_code, type_name
from washer.auto.files import find_record as files_find_record
from washer.cont.iterator import Continuation, ConvergenceError
from washer.cont.problem import ProblemError
from washer.cont.settings import Settings, SettingsError
from washer.cont.system import StartData, lookup


class RunError(RuntimeError):
    """A run could not start (bad constants, missing restart label, ...)."""


@dataclass
class Run:
    """What sinks may read about the run being executed."""
    constants: object
    settings: Settings
    system: object
    name: str
    titles: list
    irs_label: int
    first_label: bool = True         # the start point is labelled EP (IRS = 0 only)
    label0: int = 0                  # labels continue from here (LAB, or the restart file's)
    branch: Branch = field(default_factory=Branch)


def find_record(records, irs):
    """AUTO's FINDLB (washer.auto.files.find_record) with a RunError."""
    try:
        return files_find_record(records, irs)
    except LookupError as exc:
        raise RunError(str(exc)) from None


def start_kind(rec, ndim: int) -> str:
    """The registry's start kind of a record: its type name, or 'HB-curve' /
    'LP-curve' for points of ISW = 2 curves (the stored state is extended)."""
    if rec is None:
        return ""
    base, curve = split_code(rec.ty)
    stored = np.asarray(rec.U)
    if stored.ndim == 1 and curve == 0:
        if len(stored) == 2 * ndim + 2:
            curve = 3
        elif len(stored) == 2 * ndim + 1:
            curve = 2
    if curve in (2, 3) and stored.ndim == 1:
        return {2: "LP-curve", 3: "HB-curve"}[curve]
    return type_name(base)


class _Executor:
    """The bookkeeping of one run over its branches (labels, points, stops)."""

    def __init__(self, run: Run, sinks, c):
        self.run, self.sinks, self.c = run, list(sinks), c
        self.s = run.settings
        self.label = 0
        self.counts: dict[str, int] = {}
        self.bp_queue: deque = deque()
        self.n_bp = 0

    def emit(self, what: str, *args) -> None:
        for sink in self.sinks:
            getattr(sink, what)(*args)

    def labelled(self, br, pt, point: Point, base: int, stable, label: bool, info=None) -> Labelled:
        sysm, s = self.run.system, self.s
        lab = 0
        if label:
            self.label += 1
            lab = self.label
        sol = sysm.solution(point.x, point.tangent)
        values = [float(point.x[-1])] + list(sol.columns) + [float(sol.par[i - 1]) for i in s.ICP[1:]]
        out = Labelled(br=br, pt=pt, code=curve_code(base, sysm.curve_type), lab=lab,
                       stable=stable, solution=sol, stability=point.stability, info=info or {},
                       free=tuple(sysm.free), isw=s.ISW, ips=s.IPS)
        out.values = values
        self.run.branch.rows.append(out)
        self.emit("point", out, point)
        return out

    def info_at(self, point: Point, base: int) -> dict:
        f = getattr(self.run.system, "info", None)
        if f is None:
            return {}
        try:
            info = f(point.x, base)
        except (ProblemError, np.linalg.LinAlgError, ValueError):
            return {}
        if "l1" in info:
            info["criticality"] = "supercritical" if info["l1"] < 0 else "subcritical"
        return info

    def branch(self, br: int, it: Continuation, first_label: bool) -> None:
        """Follow one branch to its end, writing through the sinks."""
        s, sysm = self.s, self.run.system
        self.emit("branch_start", br)
        pt = 0
        for step in it:
            if step.kind == "note":
                self.emit("note", br, pt, step.text)
                continue
            if step.kind == "failed":
                pt += 1
                self.labelled(br, pt, step.point, Code.MX, _stable(step.point), True)
                self.run.branch.status = f"stopped: {step.text}"
                return
            pt += 1
            p = step.point
            if step.kind == "start":
                self.labelled(br, pt, p, Code.EP if first_label else Code.NONE, _stable(p),
                              first_label)
                continue
            if step.kind == "special":
                base = step.code
                name = type_name(curve_code(base, sysm.curve_type))
                # Bifurcation points carry the previous point's stability ("for
                # plotter", AUTO); user points their own.
                stable = _stable(p) if base == Code.UZ else _stable(step.prev)
                self.labelled(br, pt, p, base, stable, True, self.info_at(p, base))
                self.counts[name] = self.counts.get(name, 0) + 1
                if base == Code.BP and sysm.arclength == "sphere" and self.s.MXBF != 0 \
                        and self.n_bp < abs(self.s.MXBF):
                    self.n_bp += 1
                    self.bp_queue.append((p.x.copy(), p.tangent.copy()))
                if self._stops(base, name, step.key) or (s.NMX > 0 and pt >= s.NMX):
                    return
                continue
            # A regular point: end point (window, NMX), NPR label, or plain.
            lam = p.x[-1]
            sol_measure = None
            outside = not (s.RL0 <= lam <= s.RL1)
            if not outside and (s.A0 > -1e307 or s.A1 < 1e307):
                sol_measure = sysm.solution(p.x, p.tangent).columns[0]
                outside = not (s.A0 <= sol_measure <= s.A1)
            if outside or (s.NMX > 0 and pt >= s.NMX):
                self.labelled(br, pt, p, Code.EP, _stable(p), True)
                return
            npr = s.NPR > 0 and pt % s.NPR == 0
            self.labelled(br, pt, p, Code.RG if npr else Code.NONE, _stable(p), npr)

    def _stops(self, base: int, name: str, key) -> bool:
        s = self.s
        if base == Code.UZ:
            return bool(s.UZR[key[1]][2])
        if base == Code.LP and s.ILP < 0:
            return True
        if base in (Code.BP, Code.HB, Code.PD, Code.TR) and s.ISP < 0:
            return True
        if base == Code.BT and self.run.system.curve_type == 3:
            return True                       # AUTO always stops at BT on a Hopf curve
        n = s.STOP.get(name)
        return n is not None and self.counts[name] >= n


def _stable(p: Point) -> bool | None:
    return None if p is None or p.stability is None else bool(p.stability.stable)


def build(c, problem, records=None, name: str = "", records_source: str = "the restart file"
          ) -> tuple[Run, int, str]:
    """Resolve constants + problem + restart records into a Run (system and
    settings), the branch number and the start mode. records_source names the
    s-file in messages. Raises RunError."""
    try:
        s = Settings.from_constants(c)
    except SettingsError as exc:
        raise RunError(str(exc)) from None
    if s.NDIM != problem.ndim:
        raise RunError(f"{c.source}: NDIM={s.NDIM} but the equations '{problem.name}' have "
                       f"{problem.ndim} unknowns")
    if s.ISW not in (1, -1, 2):
        raise RunError(f"{c.source}: ISW={s.ISW} is not implemented (1, -1 and 2 are: ISW = 3 "
                       "loci of branch points in generic systems are not)")
    for key in ("LAB", "IBR"):
        if c[key] < 0:
            raise RunError(f"{c.source}: {key}={c[key]}: expected a number >= 0 (0 = automatic)")
    problem = problem.with_jac(s.JAC)
    if problem.npar > s.NPAR:
        s = s.with_(NPAR=problem.npar)      # the equations read PAR up to their npar
    irs = c["IRS"]
    mlab = mbr = 0
    rec = None
    if irs not in (0, "0"):
        if not records:
            raise RunError(f"{c.source}: IRS={irs!r} needs a restart file (s=NAME) with records")
        try:
            rec = find_record(records, irs)
        except RunError as exc:
            raise RunError(f"{records_source}: {exc}") from None
        if rec.ndim_user != problem.ndim:
            raise RunError(f"{c.source}: IRS={irs!r} names a solution of a problem with NDIM="
                           f"{rec.ndim_user}, but these equations have NDIM={problem.ndim}")
        mlab = max(r.lab for r in records)
        mbr = max(abs(r.br) for r in records)
        u = np.array(rec.U, dtype=float)
        par = np.zeros(max(s.NPAR, len(rec.par)))
        par[:len(rec.par)] = rec.par
    else:
        u, par = problem.start(s.NPAR)
    if len(par) < s.NPAR:
        par = np.r_[par, np.zeros(s.NPAR - len(par))]
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
    kind = start_kind(rec, problem.ndim)
    if s.ISW == -1 and kind not in ("BP", "PD"):
        raise RunError(f"{c.source}: ISW=-1 switches branches at a BP or PD label, got "
                       f"{kind or 'a regular point'} (IRS={irs!r})")
    if s.IPS == 2 and rec is not None and np.asarray(rec.U).ndim == 1 and kind != "HB":
        raise RunError(f"{c.source}: IPS=2 starts from an HB label or a stored periodic "
                       f"solution, got {kind or 'a regular point'} of an algebraic branch "
                       f"(IRS={irs!r})")
    if s.ISW == 2 and kind in ("EP", "UZ", "", "RG"):
        raise RunError(f"{c.source}: ISW=2 continues the locus of a special point: restart at "
                       f"an LP or HB label, got {kind or 'a regular point'} (IRS={irs!r})")
    if s.IPS in (0, 1) and s.ISW == 1 and kind in ("HB-curve", "LP-curve"):
        s = s.with_(ISW=2)          # restarting a point of a curve continues the curve
    isw_key = -1 if s.ISW == -1 and kind == "BP" else (2 if s.ISW == 2 or kind.endswith("curve") else 1)
    try:
        ctor = lookup(s.IPS, isw_key, kind)
    except KeyError as exc:
        raise RunError(f"{c.source}: {exc.args[0]}") from None
    names = {int(k): v for k, v in c["unames"].items()}
    start = StartData(problem, s, u, par, rec, kind, names)
    try:
        system = ctor(start)
    except (ValueError, ProblemError, np.linalg.LinAlgError) as exc:
        raise RunError(f"{c.source}: cannot start from {kind or 'this point'}: {exc}") from None
    # Branch number (AUTO's NEWLAB).
    if c["IBR"]:
        br = c["IBR"]
    elif rec is None or s.ISW < 0:
        br = mbr + 1
    elif (abs(rec.ty) < 10 and abs(s.ISW) == 2) or (s.IPS == 2 and kind == "HB"):
        br = rec.lab
    else:
        br = abs(rec.br)
    pn = {int(k): v for k, v in c["parnames"].items()}
    titles = [pn.get(s.ICP[0], f"PAR({s.ICP[0]})")] + list(system.column_titles()) + \
        [("PERIOD" if i == 11 and 11 not in pn else pn.get(i, f"PAR({i})")) for i in s.ICP[1:]]
    run = Run(c, s, system, name or problem.name, titles, rec.lab if rec is not None else 0,
              first_label=rec is None, label0=c["LAB"] or mlab)
    mode = "switch" if (s.ISW == -1 and kind == "BP" and system.arclength == "sphere") else "fresh"
    return run, br, mode


def execute(run: Run, br: int, mode: str = "fresh", sinks=()) -> Branch:
    """Run the branches of `run` (the first one, then MXBF switches) through sinks."""
    t0 = time.perf_counter()
    run.branch = Branch()            # a fresh result for every execution
    ex = _Executor(run, sinks, run.constants)
    ex.label = run.label0
    ex.emit("begin", run)
    status = "ok"
    # Trial points of Newton and location may overflow (exp of a diverging
    # iterate): the step is then retried smaller; the warnings are noise.
    err = np.seterr(over="ignore", invalid="ignore", divide="ignore")
    try:
        ex.branch(br, Continuation(run.system, run.settings, mode=mode), run.first_label)
        next_br = br
        directions = (1, -1) if run.settings.MXBF > 0 else (1,)
        while ex.bp_queue:
            x_bp, t_bp = ex.bp_queue.popleft()
            # The system's reference data (the Hopf eigenvector of the phase condition)
            # must be the BP's own, not the last point's of the branch just ended.
            run.system.update(x_bp, t_bp)
            dirs = run.system.directions(x_bp, t_bp, Code.BP)
            if not dirs:
                ex.emit("note", next_br, 0, "NOTE:No branch direction at BP (not switched)")
                continue
            next_br = max(next_br, br) + 1
            for sign in directions:
                it = Continuation(run.system, run.settings, x0=x_bp, tangent=sign * dirs[0],
                                  mode="switch")
                ex.branch(next_br, it, False)
        status = run.branch.status
    except KeyboardInterrupt:
        status = "interrupted (Ctrl-C): the points computed so far are written"
    except (ConvergenceError, ProblemError, FloatingPointError, np.linalg.LinAlgError) as exc:
        status = f"stopped: {exc}"
    finally:
        np.seterr(**err)
    run.branch.status = status
    run.branch.elapsed = time.perf_counter() - t0
    ex.emit("end", status, run.branch.elapsed)
    return run.branch
