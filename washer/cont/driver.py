"""One AUTO run: constants + problem -> branches written to b./s./d. files.

Maps AUTO's constants onto the engine (IRS/ISW start data, labels and branch
numbers as AUTO numbers them, stop rules on the written points, MXBF branch
switching) and turns engine events into file rows and screen lines.
"""
from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from washer.auto.constants import Constants
from washer.auto.files import OutputFiles, Record, Row, fmt_e, read_s, find_record, type_name
from washer.cont.engine import PERTURB, ConvergenceError, Engine, Settings, stable_count
from washer.cont.problem import Problem, ProblemError
from washer.cont._legacy_systems import EquilibriumSystem, FoldSystem, HopfSystem, first_lyapunov


class RunError(RuntimeError):
    """A run could not start (bad constants, missing restart label, ...)."""


@dataclass
class Special:
    """A labelled point of a run, as on AUTO's screen."""
    br: int
    pt: int
    ty: str
    lab: int
    par: np.ndarray
    U: np.ndarray
    norm: float
    stable: bool | None
    info: dict = field(default_factory=dict)

    def __getitem__(self, key):
        return {"TY": self.ty, "LAB": self.lab, "BR": self.br, "PT": self.pt}[key]


@dataclass
class RunResult:
    """What a run produced: labelled points, all rows, files and timing."""
    specials: list
    rows: list
    files: OutputFiles | None
    elapsed: float
    status: str = "ok"

    def __call__(self, key):
        """r('HB1'), r('LP'), r(3): a labelled point by type (and count) or label."""
        if isinstance(key, int):
            return next(s for s in self.specials if s.lab == key)
        name = key.rstrip("0123456789")
        n = int(key[len(name):] or 1)
        return [s for s in self.specials if s.ty == name][n - 1]


class _Sink:
    """Receives engine events; writes rows, records, screen and diagnostics."""

    def __init__(self, run: "Run"):
        self.r = run
        self.pt = 0
        self.headed = False

    # -- helpers
    def _par(self, p):
        par = self.r.system.params_at(p.U, p.lam)
        per = self.r.system.period(p.U, p.lam, p.eig) if p.eig is not None else None
        if per is not None and len(par) >= 11:
            par[10] = per
        return par

    def _stable(self, p) -> bool | None:
        if self.r.c["IPS"] != 1 or self.r.system.curve_type != 0 or p.eig is None:
            return None
        return stable_count(p.eig) == len(p.eig)

    def _code(self, base: int) -> int:
        ct = self.r.system.curve_type
        if ct == 0 or base in (0, 4, -9):
            return base
        return base + int(np.sign(base)) * 10 * ct

    def _emit(self, p, code: int, labelled: bool, stable, info=None) -> None:
        r = self.r
        self.pt += 1
        ptn = (self.pt - 1) % 9999 + 1
        sign = -1 if stable else 1
        lab = 0
        if labelled:
            r.label += 1
            lab = r.label
        par = self._par(p)
        x = p.U[:r.ndim]
        norm = float(np.sqrt(np.sum(x**2)))
        vals = [p.lam, norm] + list(x[:r.n2]) + [par[i - 1] for i in r.icp[1:]]
        row = Row(r.br, sign * ptn, code, lab, vals)
        r.rows.append(row)
        r.files.row(row)
        if p.eig is not None and r.c["IPS"] == 1:
            r.files.diag(f"\n{r.br:4d}{ptn:6d}         Eigenvalues  :   Stable:{stable_count(p.eig):4d}")
            for k, e in enumerate(p.eig, 1):
                r.files.diag(f"{r.br:4d}{ptn:6d}         Eigenvalue{k:3d}:{fmt_e(e.real, 14, 5)}"
                             f"{fmt_e(e.imag, 14, 5)}")
        if labelled:
            nf = len(r.free)
            rldot = [p.tangent[-1]] + ([p.tangent[-2]] if nf > 1 else [])
            rec = Record(r.br, self.pt, code, lab, nf, r.c["ISW"], r.ndim, r.c["IPS"], p.U.copy(),
                         par, list(r.free), rldot, p.tangent[:-1].copy())
            r.files.record(rec)
            sp = Special(r.br, self.pt, type_name(code) or "", lab, par, x.copy(), norm, stable,
                         info or {})
            r.specials.append(sp)
            self._screen(row, type_name(code))

    def _screen(self, row: Row, ty: str) -> None:
        r = self.r
        if not r.verbose:
            return
        if not self.headed:
            titles = "".join(t.strip().center(14) for t in r.titles[:7])
            print(f"\n  BR    PT  TY  LAB {titles}")
            self.headed = True
        vals = "".join(f"{v:14.5E}" for v in row.values[:7])
        print(f"{row.br:4d}{abs(row.pt):6d} {ty:>3}{row.lab:5d}{vals}", flush=True)

    # -- engine events
    def start(self, p, switched: bool) -> None:
        r = self.r
        r.files.branch_start()
        self.pt = 0
        if switched:
            self._emit(p, 0, False, self._stable(p))
        elif r.c["IRS"] in (0, "0"):
            self._emit(p, 9, True, self._stable(p))
        else:
            self._emit(p, 0, False, self._stable(p))

    def regular(self, p, prev) -> bool:
        r, c = self.r, self.r.c
        norm = float(np.sqrt(np.sum(p.U[:r.ndim] ** 2)))
        outside = not (c["RL0"] <= p.lam <= c["RL1"]) or not (c["A0"] <= norm <= c["A1"])
        at_nmx = c["NMX"] > 0 and self.pt + 1 >= c["NMX"]
        if outside or at_nmx:
            self._emit(p, self._code(9), True, self._stable(p))
            return True
        npr = c["NPR"]
        labelled = npr > 0 and (self.pt + 1) % npr == 0
        self._emit(p, self._code(4) if labelled else 0, labelled, self._stable(p))
        return False

    def special(self, p, prev, base: int, name: str) -> bool:
        info = {}
        if name == "HB" or (name == "GH"):
            x = p.U[:self.r.ndim]
            par = self.r.system.params_at(p.U, p.lam)
            cplx = p.eig[np.abs(p.eig.imag) > 1e-8]
            if cplx.size:
                om = abs(cplx[np.argmin(np.abs(cplx.real))].imag)
                l1 = first_lyapunov(self.r.problem, x, par, om)
                info = {"omega": om, "l1": l1,
                        "criticality": "supercritical" if l1 < 0 else "subcritical"}
                self.r.files.diag(f"{self.r.br:4d}{self.pt + 1:6d}         First Lyapunov "
                                  f"coefficient:{fmt_e(l1, 14, 5)} ({info['criticality']})")
        # Bifurcation points carry the previous point's stability (AUTO, "for plotter").
        stable = self._stable(p) if name.startswith("UZ") else self._stable(prev)
        code = self._code(-4 if name.startswith("UZ") else base)
        self._emit(p, code, True, stable, info)
        return False

    def failed(self, p, message: str) -> None:
        self.r.status = message
        self.r.files.diag(f"{self.r.br:4d}{self.pt:6d} NOTE:{message}")
        self._emit(p, -9, True, self._stable(p))

    def note(self, text: str) -> None:
        self.r.files.diag(f"{self.r.br:4d}{self.pt:6d} {text}")


class Run:
    """Set up and execute one run of constants `c` on `problem` in `folder`."""

    def __init__(self, c: Constants, problem: Problem, folder: Path, name: str,
                 restart_file: Path | None = None, verbose: bool = True):
        self.c, self.problem, self.folder, self.name = c, problem, folder, name
        self.verbose = verbose
        self.specials, self.rows = [], []
        self.status = "ok"
        if c["IPS"] not in (0, 1):
            raise RunError(f"{c.source}: IPS={c['IPS']} is not implemented (only algebraic "
                           "problems, IPS = 0 and 1: periodic orbits and BVPs are future work)")
        if c["NDIM"] != problem.ndim:
            raise RunError(f"{c.source}: NDIM={c['NDIM']} but the equations '{problem.name}' "
                           f"have {problem.ndim} unknowns")
        problem.jac = c["JAC"]
        self.ndim = problem.ndim
        self.icp = c.icp()
        isw = c["ISW"] if c["ISW"] not in (0, -1) else 1
        self.npar = max(c["NPAR"], 11) if c["IPS"] == 1 else c["NPAR"]
        self.free = self.icp[:2] if isw == 2 else self.icp[:1]
        self._setup_start(isw, restart_file)
        nicp = len(self.icp)
        self.n2 = 0 if nicp > 7 else min(self.ndim, 7 - nicp)
        self.titles = self._titles()

    # ------------------------------------------------------------------ start data
    def _setup_start(self, isw: int, restart_file: Path | None) -> None:
        c = self.c
        irs = c["IRS"]
        self.label, self.br = c["LAB"], c["IBR"]
        mlab, mbr = 0, 0
        if irs in (0, "0"):
            u, par = self.problem.start(self.npar)
            rec = None
        else:
            if restart_file is None or not restart_file.exists():
                raise RunError(f"{c.source}: IRS={irs!r} needs a restart file "
                               f"({restart_file or 's=NAME'}) that does not exist")
            records = read_s(restart_file)
            try:
                rec = find_record(records, irs)
            except LookupError as exc:
                raise RunError(f"{restart_file}: {exc}") from None
            mlab = max(r.lab for r in records)
            mbr = max(r.br for r in records)
            u = np.asarray(rec.U, dtype=float)[:self.ndim].copy()
            par = np.zeros(max(self.npar, len(rec.par)))
            par[:len(rec.par)] = rec.par
        for k, v in c["PAR"].items():
            par[c.par_index(k) - 1] = float(v)
        for k, v in c["U"].items():
            u[c.u_index(k) - 1] = float(v)
        if self.label == 0:
            self.label = mlab
        ty = type_name(rec.ty) if rec is not None else ""
        if isw == 2:
            if len(self.icp) < 2:
                raise RunError(f"{c.source}: ISW=2 continues a locus in two parameters: ICP "
                               "needs two entries")
            # A record of a Hopf or fold curve stores the extended unknowns
            # (2n + 2 or 2n + 1 values); an HB or LP label of a branch stores x only.
            stored = np.asarray(rec.U, dtype=float) if rec is not None else np.empty(0)
            if len(stored) == 2 * self.ndim + 2:
                self.system = HopfSystem(self.problem, par, self.icp, stored)
            elif len(stored) == 2 * self.ndim + 1:
                self.system = FoldSystem(self.problem, par, self.icp, stored)
            elif ty == "HB":
                if par[10] <= 0:
                    raise RunError(f"{restart_file}: HB label has no period PAR(11)")
                self.system = HopfSystem.at_hopf_point(self.problem, par, self.icp, u,
                                                       (2 * math.pi / par[10]) ** 2)
            elif ty == "LP":
                self.system = FoldSystem.at_fold_point(self.problem, par, self.icp, u)
            else:
                raise RunError(f"{c.source}: ISW=2 needs an LP or HB restart label, got "
                               f"{ty or 'a regular point'} (IRS={irs!r})")
            U0 = self.system.U0
            if self.br == 0:
                self.br = rec.lab if rec is not None and abs(rec.ty) < 10 else rec.br
        else:
            self.system = EquilibriumSystem(self.problem, par, self.icp, c["IPS"])
            U0 = u
            if self.br == 0:
                self.br = mbr + 1 if rec is None else rec.br
        self.X0 = np.r_[U0, par[self.icp[0] - 1]]
        # Stored direction is reused when restarting a regular point with the same
        # free parameters (AUTO); otherwise a new tangent with PAR(ICP(1))-dot > 0.
        self.T0 = None
        if rec is not None and rec.udot is not None and list(rec.icp[:len(self.free)]) == self.free \
                and len(rec.udot) == len(U0):
            self.T0 = np.r_[rec.udot, rec.rldot[0]]

    def _titles(self) -> list[str]:
        c = self.c
        pn = {int(k): v for k, v in c["parnames"].items()}
        un = {int(k): v for k, v in c["unames"].items()}
        t = [pn.get(self.icp[0], f"PAR({self.icp[0]})"), "L2-NORM"]
        t += [un.get(i, f"U({i})") for i in range(1, self.n2 + 1)]
        t += [pn.get(i, f"PAR({i})") for i in self.icp[1:]]
        return t

    def _settings(self) -> Settings:
        c = self.c
        ds = c["DS"] if c["DS"] != 0 else 0.1
        dsmin = c["DSMIN"] if c["DSMIN"] != 0 else 1e-4 * abs(ds)
        uz = [(i, v, False) for i, v in c.par_values("UZR")]
        uz = [(abs(i), v, i < 0) for i, v, _ in uz] + [(abs(i), v, True) for i, v in c.par_values("UZSTOP")]
        N = len(self.X0)
        theta = np.ones(N)
        # THU weighs U(i) in the arclength; on ISW = 2 curves it may also name the
        # extended unknowns (Hopf: U(2n+1) = kappa = omega^2, whose scale can
        # dominate the step), as AUTO's THU covers the extended NDIM.
        n_state = N - len(self.free)       # X = (state unknowns, free parameters)
        for i, v in c["THU"].items():
            k = c.u_index(i) - 1
            if k < n_state:
                theta[k] = float(v)
        thl = {c.par_index(k): float(v) for k, v in c["THL"].items()}
        theta[-1] = thl.get(self.icp[0], 1.0)
        if len(self.free) > 1:
            theta[-2] = thl.get(self.icp[1], 1.0)
        stops = {}
        for entry in c["STOP"] + [s for s in c["SP"] if s[-1:].isdigit()]:
            name = entry.rstrip("0123456789")
            stops[name.upper()] = int(entry[len(name):])
        return Settings(ds * PERTURB, dsmin / PERTURB, c["DSMAX"] * PERTURB, c["ITNW"], c["EPSL"],
                        c["EPSU"], c["IADS"], c["NMX"], c["NPR"], c["ILP"], c["ISP"], c["RL0"],
                        c["RL1"], c["A0"], c["A1"], uz, theta, stops)

    def _names(self, s: Settings):
        names = [(-4, f"UZ{k}") for k in range(len(s.uz))]
        tests = self.system.test_functions(s.ilp, s.isp)
        off = {sp[:2].upper() for sp in self.c["SP"] if sp[2:] == "0"}
        on_only = {sp[:2].upper() for sp in self.c["SP"] if sp[2:] != "0"}
        for code, name in tests:
            if name not in off:
                names.append((code, name))
        for code, name in ((2, "LP"), (1, "BP"), (3, "HB")):
            if name in on_only and (code, name) not in names and self.system.curve_type == 0:
                names.append((code, name))
        return names

    # ------------------------------------------------------------------------ run
    def execute(self) -> RunResult:
        t0 = time.perf_counter()
        c = self.c
        self.files = OutputFiles(self.folder, self.name)
        self.files.header(c, len(self.X0) - 1, self.npar, self.titles, self.system.curve_type,
                          {2: "LP", 3: "HB"}.get(self.system.curve_type, ""))
        s = self._settings()
        engine = Engine(self.system, s, _Sink(self))
        names = self._names(s)
        if self.verbose:
            print(f"Starting {c['e'] or self.problem.name} ...")
        try:
            X0 = self._initial_correction()
            T0 = self.T0 if self.T0 is not None else self._initial_tangent(X0)
            # The sign of DS sets the direction: steps are X + ds * T with T as chosen.
            bps = engine.run(X0, T0, names)
            if c["MXBF"] != 0 and self.system.curve_type == 0:
                self._switch_branches(engine, bps[:abs(c["MXBF"])], names)
        except KeyboardInterrupt:
            self.status = "interrupted (Ctrl-C): the points computed so far are in the files"
            print(f"\n{self.status}", file=sys.stderr)
        except (ConvergenceError, ProblemError, FloatingPointError, np.linalg.LinAlgError) as exc:
            self.status = f"stopped: {exc}"
            print(f"error: {self.status}; the points computed so far are in the files",
                  file=sys.stderr)
        elapsed = time.perf_counter() - t0
        self.files.diag(f"\n{'=' * 47}\n\n Total Time {elapsed:12.3E}")
        if self.verbose:
            print(f"\n Total Time {elapsed:12.3E}")
            print(f"{c['e'] or self.problem.name} ... done")
        return RunResult(self.specials, self.rows, self.files, elapsed, self.status)

    def _initial_correction(self) -> np.ndarray:
        """Newton at fixed parameter: a start point that is not quite a solution
        (STPNT rounding, a restart in other parameters) is corrected first."""
        X = self.X0.copy()
        for _ in range(20):
            G = self.system.residual(X[:-1], X[-1])
            if np.max(np.abs(G)) < 1e-10 * (1 + np.max(np.abs(X))):
                return X
            J = self.system.jacobian(X[:-1], X[-1])[:, :-1]
            X[:-1] -= np.linalg.solve(J, G)
        raise ConvergenceError("the starting point is not a solution and Newton did not fix it")

    def _initial_tangent(self, X) -> np.ndarray:
        J = self.system.jacobian(X[:-1], X[-1])
        _, _, Vt = np.linalg.svd(J)
        T = Vt[-1]
        # Sign rule (STPRAE): PAR(ICP(1))-dot > 0, else the first non-negligible component.
        ref = T[-1] if abs(T[-1]) / (1 + abs(X[-1])) > self.c["EPSL"] else \
            T[np.argmax(np.abs(T) > 1e-8)]
        return T if ref > 0 else -T

    def _switch_branches(self, engine: Engine, bps, names) -> None:
        """MXBF: restart at each BP along the direction orthogonal to the old tangent."""
        for bp in bps:
            J = self.system.jacobian(bp.U, bp.lam)
            _, _, Vt = np.linalg.svd(J)
            n1, n2 = Vt[-1], Vt[-2]
            d = n1 * (n2 @ bp.tangent) - n2 * (n1 @ bp.tangent)
            if np.linalg.norm(d) < 1e-12:
                continue
            d /= np.linalg.norm(d)
            self.br += 1
            for sign in ((1, -1) if self.c["MXBF"] > 0 else (1,)):
                engine.run(bp.X, sign * d, names, switched=True)
