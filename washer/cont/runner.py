"""One AUTO run: constants + problem (+ restart records) -> branches, through sinks.

This is AUTO's AUTOAE/AUTOBV driver: it resolves the start (IRS, ISW, the
restart record's type) to a continued system from the registry
(`washer.cont.start`), numbers points and labels as AUTO does, applies the stop rules (NMX, the
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

from washer.cont.codes import Code, curve_code, type_name
from washer.cont import start
from washer.cont.branch import Branch, Point, Record
from washer.cont.iterator import Continuation, ConvergenceError
from washer.cont.problem import ProblemError
from washer.cont.settings import Settings
from washer.cont.start import RunError  # noqa: F401  (the run's start errors)


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


class _Executor:
    """The bookkeeping of one run over its branches (labels, points, stops)."""

    def __init__(self, run: Run, sinks, c):
        self.run, self.sinks, self.c = run, list(sinks), c
        self.s = run.settings
        self.label = 0
        self.counts: dict[str, int] = {}
        self.bp_queue: deque = deque()
        self.n_bp = 0
        #: (point, its x, its tangent, their Solution) made by `_ends_here` for the A0..A1
        #: window, taken by the `labelled` that follows for the same point while its x and
        #: tangent are still those objects (a periodic orbit's Solution costs a pass over
        #: its profile); anything else in between drops it.
        self._window_solution = None
        # the sinks' point methods, looked up once (every record calls each)
        self._point_sinks = [sink.point for sink in self.sinks]
        # PAR indices (0-based) of the b-row's values after the columns: ICP(2), ICP(3), ...
        self._icp_rest = [i - 1 for i in self.s.ICP[1:]]

    def emit(self, what: str, *args) -> None:
        for sink in self.sinks:
            getattr(sink, what)(*args)

    def labelled(self, br, pt, point: Point, base: int, stable, label: bool, info=None) -> Record:
        sysm, s = self.run.system, self.s
        lab = 0
        if label:
            self.label += 1
            lab = self.label
        kept, self._window_solution = self._window_solution, None
        if kept is not None and kept[0] is point and kept[1] is point.x \
                and kept[2] is point.tangent:
            sol = kept[3]
        else:
            sol = sysm.solution(point.x, point.tangent)
        values = [float(point.x[-1]), *sol.columns]
        if self._icp_rest:
            par = sol.par
            values += [float(par[i]) for i in self._icp_rest]
        # The record's NFPR, ICP and RLDOT are AUTO's: all the free parameters, a locus'
        # internal ones included where AUTO counts them (the cycle fold's beta, PAR(NPAR+1):
        # periodic.f90 INITPS, NFPR = NBC + NINT - NDIM + 1 = 4), as the header lists them.
        icp = list(getattr(sysm, "header_icp", sysm.free))
        nfpr = len(icp)
        # (positional: Record's fields in their order)
        out = Record(br, pt, curve_code(base, sysm.curve_type), lab, nfpr, s.ISW,
                     sol.ndim_user, s.IPS, np.asarray(sol.u), np.asarray(sol.par), icp,
                     list(sol.rldot[:nfpr]), sol.udot, sol.t, sol.ntst, sol.ncol, values,
                     stable, point.stability, info or {}, getattr(sysm, "npari", 0))
        self.run.branch.rows.append(out)
        for sink_point in self._point_sinks:
            sink_point(out, point)
        return out

    def info_at(self, point: Point, base: int) -> dict:
        self._window_solution = None
        try:
            info = self.run.system.info(point.x, base)
        except (ProblemError, np.linalg.LinAlgError, ValueError):
            return {}
        if "l1" in info:
            info["criticality"] = "supercritical" if info["l1"] < 0 else "subcritical"
        return info

    def branch(self, br: int, it: Continuation, first_label: bool) -> None:
        """Follow one branch to its end, writing through the sinks; the branch's work
        is added to the run's counters. STOP and SP counts start afresh on every branch
        (AUTO's INITSTOPCNTS at each computed branch, each MXBF switch included)."""
        self.counts = {}
        try:
            self._follow(br, it, first_label)
        finally:
            self.run.branch.counters.add(it.counters)

    def _follow(self, br: int, it: Continuation, first_label: bool) -> None:
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
                # A restart's first point is an NPR output when NPR divides its number
                # (NPR = 1: AUTO's STPLAE/STPLBV label PT 1 of a restart, spb's runs).
                npr = not first_label and s.NPR > 0 and pt % s.NPR == 0
                code = Code.EP if first_label else (Code.RG if npr else Code.NONE)
                self.labelled(br, pt, p, code, _stable(p), first_label or npr)
                continue
            if step.kind == "special":
                base = step.code
                name = type_name(curve_code(base, sysm.curve_type))
                # Bifurcation points carry the previous point's stability ("for
                # plotter", AUTO); user points their own.
                stable = _stable(p) if base == Code.UZ else _stable(step.prev)
                if base == Code.BP and sysm.arclength == "sphere" and self.s.MXBF != 0 \
                        and self.n_bp < abs(self.s.MXBF):
                    self.n_bp += 1
                    self.bp_queue.append((p.x.copy(), p.tangent.copy()))
                lam = None
                if base == Code.UZ and isinstance(step.key, tuple) and not step.at_step_end:
                    i, v, _ = self.s.UZR[step.key[1]]
                    if i == self.s.ICP[0]:
                        # A UZ on PAR(ICP(1)) that the location's trials aimed at is at
                        # its value v (on which side of v the last trial ends is
                        # round-off): a UZ at RL1 itself, as nag's UZR = 1 with RL1 = 1,
                        # is inside the window, as AUTO writes it (its next point ends
                        # the branch). One located at the step's end is where the step
                        # put it, beyond v: outside the window when v is RL1 (phs), an EP
                        # as AUTO's STPLAE writes it.
                        lam = v
                if self._ends_here(p, pt, lam):
                    # AUTO's STPLAE / STPLBV: a located point at PT = NMX or outside the
                    # RL0..RL1, A0..A1 window ends the branch and is written as its EP.
                    self.labelled(br, pt, p, Code.EP, stable, True)
                    return
                self.labelled(br, pt, p, base, stable, True, self.info_at(p, base))
                self.counts[name] = self.counts.get(name, 0) + 1
                if self._stops(base, name, step.key):
                    return
                continue
            # A regular point: end point (window, NMX), NPR label, or plain.
            if self._ends_here(p, pt):
                self.labelled(br, pt, p, Code.EP, _stable(p), True)
                return
            npr = s.NPR > 0 and pt % s.NPR == 0
            self.labelled(br, pt, p, Code.RG if npr else Code.NONE, _stable(p), npr)

    def _ends_here(self, p: Point, pt: int, lam: float | None = None) -> bool:
        """The branch ends at its pt-th point p: PT = NMX, or PAR(ICP(1)) (p's, or `lam`
        where the point's value is known exactly) outside RL0..RL1, or the b-file's
        measure outside A0..A1 (AUTO's STPLAE / STPLBV)."""
        s = self.s
        if s.NMX > 0 and pt >= s.NMX:
            return True
        if not (s.RL0 <= (p.x[-1] if lam is None else lam) <= s.RL1):
            return True
        if s.A0 > -1e307 or s.A1 < 1e307:
            sol = self.run.system.solution(p.x, p.tangent)
            self._window_solution = (p, p.x, p.tangent, sol)
            measure = sol.columns[0]
            return not (s.A0 <= measure <= s.A1)
        return False

    def _stops(self, base: int, name: str, key) -> bool:
        s = self.s
        if base == Code.UZ and s.UZR[key[1]][2]:
            return True                       # UZSTOP (or a negative UZR index)
        # STOP counts apply to UZ too (AUTO's STOPPED: fnc's STOP=['UZ1'], ['UZ3'])
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


def build(c, problem, records=None, name: str = "", records_source: str = "the restart file",
          mlab: int | None = None, mbr: int | None = None, data=None) -> tuple[Run, int, str]:
    """Resolve constants + problem + restart records into a Run (system and
    settings), the branch number and the start mode (`washer.cont.start`).
    records_source names the s-file in messages. mlab, mbr: the largest label and
    branch number of the data the restart record came from (default: of `records`;
    AUTO's CLUI passes them with a single solution). data: (t, U) of dat='NAME' (the
    start of a BVP with IRS = 0). Raises RunError."""
    s, problem = start.settings_for(c, problem)
    rec = start.restart_record(c, problem, records, records_source)
    s = start.with_record_parameters(s, rec)
    u, par = start.start_values(c, s, problem, rec, data)
    start.warn_unset_dfdp(s, problem, u, par)
    system, s, kind = start.system_for(c, s, problem, u, par, rec, data)
    # Numbering continues the restart file's only when restarting from it.
    known = records if rec is not None else []
    br = start.branch_number(c, s, rec, kind, known, mbr=mbr if rec is not None else None)
    run = Run(c, s, system, name or problem.name, start.column_titles(c, s, system),
              rec.lab if rec is not None else 0, first_label=rec is None,
              label0=start.first_label(c, known, mlab=mlab if rec is not None else None))
    mode = getattr(system, "start_mode", None) or \
        ("switch" if (s.ISW == -1 and kind == "BP" and system.arclength == "sphere") else "fresh")
    return run, br, mode


def execute(run: Run, br: int, mode: str = "fresh", sinks=()) -> Branch:
    """Run the branches of `run` (the first one, then MXBF switches) through sinks."""
    t0 = time.perf_counter()
    c = run.constants                # a fresh result for every execution, its columns named
    run.branch = Branch(titles=list(run.titles),
                        parnames={int(k): v for k, v in c["parnames"].items()},
                        unames={int(k): v for k, v in c["unames"].items()})
    ex = _Executor(run, sinks, run.constants)
    ex.label = run.label0
    ex.emit("begin", run)
    status, interrupted = "ok", False
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
        interrupted = True
    except (ConvergenceError, ProblemError, FloatingPointError, np.linalg.LinAlgError) as exc:
        status = f"stopped: {exc}"
        # Failing before the first point is a failed run (the caller may raise, as
        # AUTO's CLUI does); a failure after it ends the run with what it computed.
        run.branch.started = bool(run.branch.rows)
    finally:
        np.seterr(**err)
    run.branch.status = status
    run.branch.elapsed = time.perf_counter() - t0
    ex.emit("end", status, run.branch.elapsed)
    if interrupted:
        # The sinks are closed (every point so far is in the files): the interrupt
        # goes on to the caller, never a result a loop around the run carries on with.
        exc = KeyboardInterrupt(status)
        exc.branch = run.branch
        raise exc
    return run.branch


def restart_records(restart, c) -> tuple[list, str]:
    """The records a run may restart from, and how messages name them: a Branch (its
    labelled points), one Record (IRS = 0 then means that record) or a list of Records
    (an s-file's: washer.auto.files.read_s; the engine reads no files)."""
    if restart is None:
        return [], "the restart file"
    if isinstance(restart, Branch):
        return list(restart.specials), "the restart branch"
    if isinstance(restart, Record):
        if c["IRS"] in (0, "0"):
            c.set("IRS", -1, "<restart record>")        # FINDLB: the first record
        return [restart], "the restart record"
    if isinstance(restart, (list, tuple)):
        return list(restart), "the restart records"
    raise RunError(f"restart={restart!r}: expected a Branch, a Record or a list of Records "
                   "(an s-file's records: washer.auto.files.read_s)")


def solve(c, problem, restart=None):
    """The start point of a run corrected by Newton at fixed PAR(ICP(1))
    (Continuation.correct_start; the engine's one Newton): (x, system, counters),
    x the system's unknowns (state, then PAR(ICP(1))), the system for its stability(x,
    J), params(x), and the work done (Counters: one residual per Newton iteration).
    Raises ConvergenceError, RunError."""
    c = c.copy()
    records, source = restart_records(restart, c)
    r, _, _ = build(c, problem, records, name=problem.name, records_source=source)
    it = Continuation(r.system, r.settings)
    return it.correct_start(it.x0), r.system, it.counters


def run(c, problem, restart=None, sinks=(), name: str = "") -> Branch:
    """One run in memory: constants `c` (washer.cont.constants.Constants) and the
    equations `problem` (washer.cont.problem.Problem), restarting at c['IRS'] from
    `restart` (a Branch, a Record or a list of Records), through
    `sinks` (none needed: nothing is written unless a sink writes it). Returns the
    Branch (rows, labelled points `specials`, status, counters)."""
    c = c.copy()
    records, source = restart_records(restart, c)
    r, br, mode = build(c, problem, records, name=name or problem.name, records_source=source)
    return execute(r, br, mode, sinks)
