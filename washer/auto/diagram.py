"""AUTO's data objects as its CLUI shows them: solutions, solution lists, bifurcation diagrams.

    bd = Diagram.read("b.ab", "s.ab", "d.ab")   # AUTO's bifDiag
    bd("HB1"), bd("UZ"), bd(3), bd()            # label selection -> Solution / SolutionList
    bd[0]                                        # a Branch; bd["PAR(1)"]: a column of branch 0
    bd + other, bd.relabel(), bd.merge()         # new diagrams
    bd.write("ab")                               # b.ab, s.ab, d.ab

Labels, branch numbers and point numbers follow AUTO's python/auto (bifDiag.py,
parseB.py, parseS.py): a solution taken from a diagram carries the diagram's
largest label and branch number (`mlab`, `mbr`), from which a run restarted at it
numbers its new labels and branches. Rows and s-records are kept as read and
written back unchanged except for the fields a command changes (labels on
relabel, point numbers on merge). No numerics here.
"""
from __future__ import annotations

import copy as _copy
import re
from pathlib import Path

import numpy as np

from washer.atomic import write_text
from washer.cont.codes import split_code, split_label, type_name as _type_name
from washer.cont.constants import par_name_index
from washer.auto.files import (AutoFileError, Record, Row, _fortran_float, _read_record,
                               _read_text, fmt_e, record_text, s_file)
from washer.auto.script_constants import AutoConstants


def _run_command(data, **kw):
    """The command language's `run`, which washer.auto.clui installs here when it is
    imported (solutions and diagrams run themselves through it, as AUTO's objects do;
    the objects stay below the commands that make them)."""
    raise RuntimeError("solution.run() needs the command language: import washer.auto.clui")


def type_name(code: int) -> str:
    """AUTO's short type name of a code ('RG' for labelled regular points)."""
    if split_code(code)[0] == 4:
        return "RG"
    return _type_name(code)


def _match_type(name: str, code: int) -> bool:
    return type_name(code) == name


def _parse_key(label):
    """'HB2' -> ('HB', 2); 'HB' -> ('HB', None); 'R31' -> ('R3', 1); 3 -> 3."""
    if isinstance(label, (int, np.integer)):
        return int(label)
    try:
        return split_label(label)
    except ValueError as exc:
        raise KeyError(str(exc)) from None


class Parameters:
    """PAR of a solution as AUTO's CLUI shows it: p['name'] or p['PAR(3)'] by name,
    p(3) 1-based, p[2] 0-based, numpy array through np.asarray(p)."""

    def __init__(self, values, parnames: dict | None = None):
        self.values = np.asarray(values, dtype=float)
        self.parnames = dict(parnames or {})

    def index(self, key) -> int:
        """0-based position of a name (washer.cont.constants.par_name_index) or of
        an integer (already 0-based)."""
        if isinstance(key, str):
            i = par_name_index(key.strip(), self.parnames)
            if i is None or i < 1:
                raise KeyError(f"{key!r}: no such parameter (parnames: "
                               f"{sorted(map(str, self.parnames.values()))})")
            return i - 1
        return int(key)

    def __getitem__(self, key):
        if isinstance(key, slice):
            return self.values[key]
        return float(self.values[self.index(key)])

    def __setitem__(self, key, value):
        self.values[self.index(key)] = value

    def __call__(self, i):
        return float(self.values[int(i) - 1])

    def __len__(self):
        return len(self.values)

    def __iter__(self):
        return iter(self.values)

    def __array__(self, dtype=None, copy=None):
        return self.values if dtype is None else self.values.astype(dtype)

    def __repr__(self):
        return f"Parameters({self.values.tolist()})"


def _with_parameters(par, changes, parnames=None) -> np.ndarray:
    """PAR (a copy) with `changes` ({index or name: value} or its items) set, lengthened
    to the highest index they name (AUTO's AUTOSolution.update)."""
    items = changes.items() if isinstance(changes, dict) else changes
    names = Parameters([], parnames)
    at = [(names.index(k) if isinstance(k, str) else int(k) - 1, float(v)) for k, v in items]
    out = np.zeros(max([len(par)] + [i + 1 for i, _ in at]))
    out[:len(par)] = par
    for i, v in at:
        out[i] = v
    return out


class MeshPoint(np.ndarray):
    """One point of a solution's mesh (AUTO's SLPoint): the state U(1..NDIM) there as a
    vector indexed from 0, with p['u'] (the same vector) and p['t'] (its time in [0, 1];
    0 for the one point of an equilibrium)."""

    def __new__(cls, u, t: float):
        obj = np.array(u, dtype=float).view(cls)
        obj.time = float(t)
        return obj

    def __array_finalize__(self, obj):
        self.time = getattr(obj, "time", 0.0)

    def __getitem__(self, key):
        if isinstance(key, str):
            if key == "t":
                return self.time
            if key == "u":
                return np.asarray(self)
            raise KeyError(f"{key!r}: a mesh point has 't' and 'u'")
        return np.asarray(self)[key]


class Solution:
    """One labelled solution (AUTO's AUTOSolution): an s-record with the constants `c`
    (an AutoConstants: what a run restarted from it uses) and the b-file row `b`.

    s['PAR(1)'], s['U(1)'], names from parnames/unames, s['LAB'], s['TY'], s['BR'],
    s['PT'], s.PAR (the vector), s.U, s.t; s[i] (and s['data'][i]) the i-th point of its
    mesh (`MeshPoint`: s[0]['u'][1] is U(2) at t = 0, an equilibrium's one point too, as
    AUTO's); s.load(**constants) -> a copy with the constants changed;
    s.run(**constants); s.writeFilename(path) writes its s-record."""

    def __init__(self, record: Record | None, c=None, raw: list[str] | None = None,
                 row: Row | None = None, titles: list[str] | None = None):
        self.rec = record
        self.c = c
        self.raw = raw or []             # the record's body lines, as read
        self.row = row
        self.titles = titles or []
        self._mlab = record.lab if record is not None else 0
        self._mbr = abs(record.br) if record is not None else 0

    # ------------------------------------------------------------ identity
    def _with(self, br=None, pt=None, ty=None, lab=None) -> "Solution":
        new = _copy.copy(self)
        if self.rec is not None:
            new.rec = _copy.copy(self.rec)
            for k, v in (("br", br), ("pt", pt), ("code", ty), ("lab", lab)):
                if v is not None:
                    setattr(new.rec, k, v)
        return new

    @property
    def empty(self) -> bool:
        return self.rec is None

    def _need(self):
        if self.rec is None:
            raise KeyError("a solution without data (no restart point)")
        return self.rec

    @property
    def PAR(self) -> Parameters:
        return Parameters(self._need().par, (self.c or {}).get("parnames"))

    @classmethod
    def from_array(cls, data, c=None) -> "Solution":
        """A solution from numbers (AUTO's load(array)): a point [x, y, ...], or an orbit
        given column-wise [[t0..tn], [x0..xn], ...] (t rescaled to [0, 1], PAR(11) the
        period, NTST = n, NCOL = 1)."""
        arr = [np.asarray(a, dtype=float) for a in data]
        if all(a.ndim == 0 for a in arr):
            U = np.array([float(a) for a in arr])
            rec = Record(1, 1, 9, 1, 1, 1, len(U), 1, U, np.zeros(36))
            return cls(rec, c)
        t = arr[0]
        period = t[-1] - t[0]
        tt = (t - t[0]) / period if period else t
        U = np.column_stack(arr[1:])
        par = np.zeros(36)
        par[10] = period
        rec = Record(1, 1, 9, 1, 1, 1, U.shape[1], 4, U, par, t=tt, ntst=len(t) - 1, ncol=1)
        return cls(rec, c)

    @property
    def U(self) -> np.ndarray:
        return np.asarray(self._need().u)

    @property
    def t(self):
        return self._need().t

    def _names(self, key: str) -> dict:
        c = self.c or {}
        return {v: int(k) for k, v in (c.get(key) or {}).items()}

    def __getitem__(self, key):
        rec = self._need()
        if isinstance(key, str):
            k = key.strip()
            simple = {"LAB": rec.lab, "Label": rec.lab, "BR": rec.br, "Branch number": rec.br,
                      "PT": rec.pt, "Point number": rec.pt, "TY number": rec.code,
                      "Type number": rec.code, "TY": rec.ty,
                      "Type name": rec.ty, "ISW": rec.isw, "NTST": rec.ntst,
                      "NCOL": rec.ncol, "IPS": rec.ips, "NDIM": rec.ndim_user,
                      "PAR": self.PAR, "p": self.PAR, "U": self.U,
                      "t": rec.t if rec.t is not None else np.zeros(1),
                      "data": self, "Active ICP": list(rec.icp), "rldot": list(rec.rldot)}
            if k in simple:
                return simple[k]
            i = par_name_index(k, (self.c or {}).get("parnames"))
            if i is not None and i > 0:
                return float(rec.par[i - 1])
            m = re.fullmatch(r"U\((\d+)\)", k)
            if m:
                U = np.asarray(rec.u)
                return U[..., int(m.group(1)) - 1] if U.ndim == 2 else float(U[int(m.group(1)) - 1])
            un = self._names("unames")
            if k in un:
                U = np.asarray(rec.u)
                return U[..., un[k] - 1] if U.ndim == 2 else float(U[un[k] - 1])
            if self.row is not None and k in self.titles:
                return self.row.values[self.titles.index(k)]
            raise KeyError(f"{key!r}: not a field of this solution (LAB, TY, BR, PT, "
                           "PAR(i), U(i), a parameter or state name)")
        if isinstance(key, (int, np.integer)):
            # AUTO's Pointset: an integer selects a point of the mesh (an equilibrium
            # has one), not a component of the state
            U = np.atleast_2d(self.U)
            t = rec.t[key] if rec.t is not None and U.shape[0] > 1 else 0.0
            return MeshPoint(U[key], t)
        return self.U[key]

    def __call__(self, t: float) -> np.ndarray:
        """The state at the orbit's mesh time t (AUTO's Pointset call, `s(0)`: the first
        point), U(1..NDIM) as a vector indexed from 0: r3b's data.py builds a manifold's
        start from `s0 = solution(0)`, `s0[i] + eps * s0[i + 6]`. As AUTO's, t must be
        one of the record's times (to 1e-10, Pointset's tolerance)."""
        rec = self._need()
        U = np.asarray(rec.u, float)
        if U.ndim == 1:
            if t == 0:
                return U.copy()
            raise ValueError(f"a point has no time {t}: only solution(0) is its state")
        times = np.asarray(rec.t, float)
        k = int(np.argmin(np.abs(times - t)))
        if abs(times[k] - t) > 1e-10:
            raise ValueError(f"independent variable value not valid: {t} (not a mesh time)")
        return U[k].copy()

    def __contains__(self, key) -> bool:
        try:
            self[key]
            return True
        except (KeyError, IndexError):
            return False

    def get(self, key, default=None):
        try:
            return self[key]
        except (KeyError, IndexError):
            return default

    def __repr__(self) -> str:
        if self.rec is None:
            return "<Solution without data>"
        r = self.rec
        return (f"<Solution BR={r.br} PT={r.pt} TY={r.ty} LAB={r.lab}>")

    def __str__(self) -> str:
        if self.rec is None:
            return "Solution without data"
        r = self.rec
        lines = ["  BR    PT  TY  LAB  ISW  NTST  NCOL",
                 f"{r.br:4d}{r.pt:6d}  {r.ty:>2}{r.lab:5d}{r.isw:5d}{r.ntst:6d}{r.ncol:6d}"]
        pars = ", ".join(f"PAR({i + 1})={v:.6g}" for i, v in enumerate(r.par[:12]))
        lines.append(pars)
        return "\n".join(lines)

    # ------------------------------------------------------------ constants
    def load(self, **kw) -> "Solution":
        """A copy with constants updated (AUTO's AUTOSolution.load): kw 'constants' (an
        AutoConstants) first, then the keywords; IRS becomes this solution's label. A
        keyword LAB also relabels the copy (AUTO's data keyword: run(r1('UZ1'), LAB=1)
        restarts from a solution labelled 1, its header's IRS = 1)."""
        constants = kw.pop("constants", None)
        c = AutoConstants(self.c)
        oldirs = c.get("IRS")
        if constants is not None:
            c.update(constants)
        c.update(kw)
        if oldirs is not None and c.get("IRS") == 0:
            return Solution(None, c)
        lab = kw.get("LAB")
        new = self._with(lab=lab) if lab and self.rec is not None else self._with()
        if new.rec is not None and new.rec.lab != 0:
            c["IRS"] = new.rec.lab
        if new.rec is not None and c.get("PAR"):
            # The constants' PAR become the solution's own (AUTO's AUTOSolution.update):
            # they stay with it when a later run reads other constants (r3b's data.py
            # builds a manifold's start with load(u, PAR={..., 25..36: ...}) and runs it
            # with c='man.H1a.0', whose NPAR is 16).
            new.rec.par = _with_parameters(new.rec.par, c["PAR"], c.get("parnames"))
        new.c = c
        return new

    def run(self, **kw):
        """AUTO's solution.run(...): the command language's run from this data."""
        return _run_command(self, **kw)

    # ------------------------------------------------------------ writing
    def writeFilename(self, path, append: bool = False) -> None:
        """Write the s-record to the file path (AUTO's AUTOSolution.writeFilename),
        after what it holds with append."""
        text = self.text()
        if append and Path(path).exists():
            text = Path(path).read_text() + text
        write_text(path, text)

    def text(self) -> str:
        """The s-record: header rewritten from the fields, body as read."""
        r = self._need()
        if not self.raw:
            return record_text(r)
        head = self.raw[0].split()
        h = [int(x) for x in head]
        h[0], h[1], h[2], h[3] = abs(r.br), (abs(r.pt) - 1) % 9999 + 1, r.code, r.lab
        fmt = [6, 6, 6, 6, 6, 6, 8, 6, 8] + [5] * (len(h) - 9)
        line = "".join(f"{v:{w}d}" for v, w in zip(h, fmt))
        return "\n".join([line] + self.raw[1:]) + "\n"


class SolutionList(list):
    """AUTO's parseS: a list of Solutions with label selection by call."""

    def __call__(self, label=None):
        if label is None:
            return self
        if callable(label) and not isinstance(label, (str, Solution)):
            return SolutionList(s for s in self if label(s))
        if isinstance(label, (list, tuple)):
            out = SolutionList()
            for s in self:
                if any(_selects(s, k, self) for k in label):
                    out.append(s)
            return out
        key = _parse_key(label)
        if isinstance(key, int):
            for s in self:
                if s.rec.lab == key:
                    return s
            raise KeyError(f"Label {label} not found (labels: {self.getLabels()})")
        name, n = key
        hits = [s for s in self if _match_type(name, s.rec.code)]
        if n is None:
            return SolutionList(hits)
        if n > len(hits):
            have = sorted({type_name(s.rec.code) for s in self})
            raise KeyError(f"Label {label} not found: there are {len(hits)} {name} solutions"
                           + ("" if hits else f" (types here: {', '.join(have) or 'none'})"))
        return hits[n - 1]

    def getLabels(self) -> list[int]:
        return [s.rec.lab for s in self]

    def load(self, **kw) -> Solution:
        """The solution IRS names (the last one without IRS), with constants updated."""
        irs = kw.get("IRS")
        if irs is None and kw.get("constants") is not None:
            irs = kw["constants"].get("IRS")
        sol = None
        missing = ""
        if irs is not None:
            if irs != 0:
                try:
                    sol = self(irs)
                except KeyError as exc:
                    sol, missing = None, str(exc.args[0])
        elif len(self):
            sol = self[-1]
        else:
            raise RuntimeError("Cannot start from an empty solution list.")
        if sol is None or isinstance(sol, SolutionList):
            sol = Solution(None)
        out = sol.load(**kw)
        if out.empty and irs:
            # why IRS selects nothing, and where it was looked for (the run's message)
            where = getattr(self, "source", "")
            out.missing = f"{missing or f'Label {irs} selects a list'}" + \
                (f" in {where}" if where else "")
        return out

    def relabel(self) -> "SolutionList":
        out = SolutionList()
        for i, s in enumerate(self, 1):
            n = s._with(lab=i)
            n._mlab = len(self)
            out.append(n)
        return out

    def write(self, path) -> None:
        write_text(path, "".join(s.text() for s in self if not s.empty))

    def __add__(self, other):
        return SolutionList(list(self) + list(other))


def _selects(s: Solution, key, _lst) -> bool:
    k = _parse_key(key)
    if isinstance(k, int):
        return s.rec.lab == k
    return _match_type(k[0], s.rec.code) and k[1] is None


#: The special points AUTO's dsp/ksp/dlb/klb mean without a list (deleteLabel).
SPECIAL_TYPES = ("BP", "LP", "HB", "PD", "TR", "EP", "MX")


def label_selector(typenames):
    """AUTO's deleteLabel list as a predicate of a Solution: None (SPECIAL_TYPES), a
    label number, a type name ('UZ'), a list of those, or a predicate itself."""
    if typenames is None:
        typenames = list(SPECIAL_TYPES)
    if callable(typenames) and not isinstance(typenames, (str, Solution)):
        return typenames
    items = list(typenames) if isinstance(typenames, (list, tuple)) else [typenames]
    return lambda sol: any(_selects(sol, k, None) for k in items)


class Branch:
    """One branch of a b-file (AUTO's AUTOBranch): header lines, column titles, rows;
    labelled rows carry their Solution; `c` the constants of the run that made it."""

    def __init__(self, header=None, titles=None, rows=None, c=None):
        self.header: list[str] = list(header or [])
        self.titles: list[str] = list(titles or [])
        self.rows: list[Row] = list(rows or [])
        self.solutions: dict[int, Solution] = {}
        self.c = c
        self.diagnostics = ""

    @property
    def BR(self) -> int:
        return self.rows[0].br if self.rows else 0

    def __len__(self) -> int:
        return len(self.rows)

    def __getitem__(self, key):
        if isinstance(key, str):
            k = self._column(key)
            return np.array([r.values[k] for r in self.rows])
        return self.rows[key]

    def _column(self, key: str) -> int:
        if key in self.titles:
            return self.titles.index(key)
        c = self.c or {}
        parnames = c.get("parnames") or {}
        i = par_name_index(key, parnames)
        # a parameter's column is titled PAR(i), or by its name where parnames gives one
        for t in (f"PAR({i})", parnames.get(i, parnames.get(str(i)))):
            if i is not None and t in self.titles:
                return self.titles.index(t)
        for i, n in (c.get("unames") or {}).items():
            for t in (f"U({i})", f"MAX U({i})"):
                if n == key and t in self.titles:
                    return self.titles.index(t)
        raise KeyError(f"{key!r}: no such column (columns: {self.titles})")

    @property
    def coordnames(self) -> list[str]:
        return list(self.titles)

    def labelled(self):
        """(row index, row) of the labelled rows."""
        return [(i, r) for i, r in enumerate(self.rows) if r.lab]

    def copy(self) -> "Branch":
        b = Branch(self.header, self.titles, [_copy.copy(r) for r in self.rows], self.c)
        b.solutions = dict(self.solutions)
        b.diagnostics = self.diagnostics
        return b

    def solution_list(self, mbr=None, mlab=None) -> SolutionList:
        out = SolutionList()
        for i, r in self.labelled():
            s = self.solutions.get(i)
            if s is None:
                continue
            s = s._with(br=abs(r.br), pt=(abs(r.pt) - 1) % 9999 + 1, ty=r.ty, lab=r.lab)
            s.row, s.titles = r, self.titles
            s._mlab = mlab if mlab is not None else s.rec.lab
            s._mbr = mbr if mbr is not None else abs(r.br)
            out.append(s)
        return out

    def __call__(self, label=None):
        return self.solution_list()(label)

    def text(self) -> str:
        lines = [h for h in self.header]
        for r in self.rows:
            vals = "".join(fmt_e(v) for v in r.values)
            lines.append(f"{r.br:4d}{r.pt:6d}{r.ty:4d}{r.lab:5d}{vals}")
        return "\n".join(lines) + "\n"


class Diagram(list):
    """AUTO's bifDiag: a list of Branches (`+` concatenates, `bd[0]` a branch,
    `bd['PAR(1)']` a column of the first branch, `bd('HB1')` a solution)."""

    def __init__(self, branches=()):
        super().__init__(branches)

    @classmethod
    def read(cls, b_path, s_path=None, d_path=None, c=None) -> "Diagram":
        """Branches of a b-file with the s-file's records attached to the labelled rows
        in order, and the d-file's text on the first branch (as AUTO's bifDiag)."""
        branches = read_branches(b_path, c) if b_path and Path(b_path).exists() else []
        sols = read_solutions(s_path, c) if s_path and s_file(s_path).exists() else []
        if not branches and sols:
            return cls([_branch_of_solutions(sols, c)])
        k = 0
        sol_c = solution_constants(branches) if c is None else None
        for b in branches:
            for i, r in b.labelled():
                if k < len(sols):
                    if sols[k].c is None:
                        sols[k].c = sol_c.copy() if sol_c is not None else b.c
                    b.solutions[i] = sols[k]
                    k += 1
        if branches and d_path and Path(d_path).exists():
            branches[0].diagnostics = Path(d_path).read_text(errors="replace")
        return cls(branches)

    def __getitem__(self, key):
        if isinstance(key, str):
            return self[0][key] if len(self) else np.array([])
        out = list.__getitem__(self, key)
        return Diagram(out) if isinstance(key, slice) else out

    def __add__(self, other):
        if isinstance(other, Solution):
            other = Diagram([_branch_of_solutions([other], other.c)])
        return Diagram(list(self) + list(other))

    def __radd__(self, other):
        return Diagram(list(other) + list(self))

    def getLabels(self) -> list[int]:
        return [r.lab for b in self for _, r in b.labelled()]

    def __call__(self, label=None):
        mbr = max((abs(b.BR) for b in self), default=0)
        mlab = max(self.getLabels() or [0])
        sols = SolutionList()
        for b in self:
            sols.extend(b.solution_list(mbr, mlab))
        return sols(label)

    def load(self, **kw) -> Solution:
        return self().load(**kw)

    def run(self, **kw):
        """AUTO's solution.run(...): the command language's run from this data."""
        return _run_command(self, **kw)

    @property
    def c(self):
        return self[0].c if len(self) else None

    def relabel(self) -> "Diagram":
        """Labels 1, 2, ... in order over all branches (AUTO's relabel of a bifDiag)."""
        lab = 1
        out = []
        for b in self:
            nb = b.copy()
            for i, r in nb.labelled():
                r.lab = lab
                lab += 1
            out.append(nb)
        return Diagram(out)

    def delete_labels(self, select, keep: bool = False, keep_type: bool = False) -> "Diagram":
        """A copy without the labels whose Solution `select` accepts (keep: without the
        others): their rows lose the label and their s-records go; the type code stays on
        the row only with keep_type (AUTO's dlb/klb, for plotting; dsp/ksp drop it)."""
        out = []
        mbr = max((abs(b.BR) for b in self), default=0)
        mlab = max(self.getLabels() or [0])
        for b in self:
            nb = b.copy()
            listed = {id(sol.row): sol for sol in b.solution_list(mbr, mlab)}
            for i, r in nb.labelled():
                sol = listed.get(id(b.rows[i]))
                if sol is None or bool(select(sol)) != keep:
                    r.lab = 0
                    nb.solutions.pop(i, None)
                    if not keep_type:
                        r.ty = 0
            out.append(nb)
        return Diagram(out)

    def merge(self) -> "Diagram":
        """Join a branch and the next one when they have the same branch number, start at
        the same point and run in opposite directions (DS of opposite signs): the second
        reversed, then the first without its start point; labels renumbered from the
        smallest of the two, point numbers 1, 2, ... (AUTO's parseBR.merge)."""
        data: list[Branch] = []
        fw = None
        for bw in self:
            data.append(bw)
            if fw is None or fw.BR != bw.BR or not fw.rows or not bw.rows or (
                    fw.c is not bw.c and _ds(fw.c) * _ds(bw.c) > 0):
                fw = bw
                continue
            if fw.rows[0].values != bw.rows[0].values:
                fw = bw
                continue
            new = Branch(fw.header, fw.titles, c=fw.c)
            order = [(bw, i) for i in range(len(bw.rows) - 1, -1, -1)] + \
                    [(fw, i) for i in range(1, len(fw.rows))]
            labs = [r.lab for _, r in fw.labelled()] + [r.lab for _, r in bw.labelled()]
            lab = min(labs) if labs else 0
            for n, (src, i) in enumerate(order):
                r = _copy.copy(src.rows[i])
                sign = -1 if r.pt < 0 else 1
                r.pt = sign * (n % 9999 + 1)
                if r.lab:
                    r.lab = lab
                    lab += 1
                    if i in src.solutions:
                        new.solutions[n] = src.solutions[i]
                new.rows.append(r)
            new.diagnostics = fw.diagnostics + bw.diagnostics
            data[-2:] = [new]
            fw = None
        return Diagram(data)

    def write(self, name_or_paths, append: bool = False) -> tuple[Path, Path, Path]:
        """b.NAME, s.NAME, d.NAME (or three paths)."""
        if isinstance(name_or_paths, (tuple, list)):
            b, s, d = (Path(p) for p in name_or_paths)
        else:
            b, s, d = (Path(f"{k}.{name_or_paths}") for k in "bsd")
        # Each file is replaced whole (washer.atomic: never through a link, never
        # half-written); appending rewrites the old content followed by the new.
        def put(path: Path, text: str) -> None:
            old = path.read_text() if append and path.is_file() else ""
            write_text(path, old + text)
        put(b, "".join(br.text() for br in self if br.rows))
        put(s, "".join(sol.text() for sol in self() if not sol.empty))
        diag = "".join(br.diagnostics for br in self)
        if diag or not append:
            put(d, diag)
        return b, s, d

    def __repr__(self) -> str:
        return f"<Diagram: {len(self)} branch(es), labels {self.getLabels()}>"

    def __str__(self) -> str:
        out = []
        for b in self:
            for _, r in b.labelled():
                vals = "".join(f"{v:14.5E}" for v in r.values[:6])
                out.append(f"{r.br:4d}{r.pt:6d} {type_name(r.ty):>3}{r.lab:5d}{vals}")
        return "\n".join(out)


def _ds(c) -> float:
    try:
        v = (c or {}).get("DS")
        return 0.01 if v is None else float(v)
    except (TypeError, ValueError):
        return 0.01


def _branch_of_solutions(sols, c) -> Branch:
    """A diagram of solutions alone (no b-file): one row per solution (AUTO does the same)."""
    b = Branch(c=c)
    for i, s in enumerate(sols):
        r = s.rec
        b.rows.append(Row(r.br, r.pt, r.code, r.lab, []))
        b.solutions[i] = s
    b.header = []
    return b


# --------------------------------------------------------------------------- readers

_TITLE_SPLIT = re.compile(r"\s{2,}")


def _titles(line: str) -> list[str]:
    """Column titles of the '   0    PT  TY  LAB  PAR(1) ...' line (19-wide columns)."""
    rest = line[len("   0    PT  TY  LAB "):]
    return [rest[i:i + 19].strip() for i in range(0, len(rest), 19) if rest[i:i + 19].strip()]


#: Constants a solution of a loaded diagram does not carry to a run from it (AUTO's
#: bifDiag.nonekeys): they describe the run that wrote the files, not the next one.
NONE_KEYS = ("IRS", "PAR", "U", "sv", "s", "dat", "TY", "LAB", "IBR")


def has_constants(header: list[str]) -> bool:
    """Whether a b-file header block states a run's constants (its first line holds RL0,
    RL1, A0, A1), not only the column titles of a branch the run switched to."""
    return bool(header) and len(header[0].split()) >= 5


def _header_icp(line: str) -> list:
    """ICP of '   0   User-specified parameters:   11   17' (numbers or 'names')."""
    out = []
    for w in line.split(":", 1)[1].split():
        try:
            out.append(int(w))
        except ValueError:
            out.append(w.strip("'\""))
    return out


def header_constants(header: list[str]) -> dict:
    """The constants a b-file header states (io.f90:STHD's block), as AUTO-07p's parseB
    reads them back: RL0, RL1, A0, A1 from the first line, every KEY = value after it
    (HomCont's NUNSTAB ... ISTART, IREV, IFIXED, IPSI included), ICP from 'User-specified
    parameter(s)'. Below 'User-specified constants, where different from above' the
    user's values replace the run's own (an extended system's NDIM, NBC, NINT; NPAR;
    HomCont's NUNSTAB, NSTAB where computed): the constants are the user's. Not
    constants, and left out: the active parameters, NUZR (a count), the branch type.
    A header without the constants line (a switched-to branch) gives {}."""
    from washer.auto.constants_file import DEFAULTS, ConstantsError, parse_text
    if not has_constants(header):
        return {}
    out = {}
    try:
        for key, word in zip(("RL0", "RL1", "A0", "A1"), header[0].split()[1:5]):
            out[key] = _fortran_float(word)
    except ValueError:
        out = {}
    for line in header[1:]:
        body = line.split(None, 1)[1].strip() if len(line.split()) > 1 else ""
        if not body or body.startswith(("PT ", "Branch type", "User-specified constants",
                                        "Active continuation")):
            continue
        if body.startswith("User-specified parameter"):
            out["ICP"] = _header_icp(body)
            continue
        try:
            stmts = parse_text(re.sub(r"(?<=\d)([+-]\d{3})\b", r"e\1", body), "b-file header")
        except ConstantsError:
            continue            # a line that is not KEY = value statements
        for key, value, _ in stmts:
            if key in DEFAULTS:
                out[key] = value
    return out


def solution_constants(branches) -> AutoConstants | None:
    """The constants the solutions of a diagram read from files carry (AUTO's bifDiag):
    the first header's that states them, without NONE_KEYS; None without such a header."""
    for b in branches:
        if has_constants(b.header) and b.c is not None:
            c = AutoConstants(b.c)
            for k in NONE_KEYS:
                c[k] = None
            return c
    return None


def read_branches(path, c=None) -> list[Branch]:
    """Branches of a b-file: a new branch at each header block or change of BR. Without
    constants `c`, each branch gets the names its header states (header_constants)."""
    text = _read_text(Path(path), "an AUTO b-file")
    branches: list[Branch] = []
    header: list[str] = []
    titles: list[str] = []
    cur = None
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "0":
            header.append(line)
            if len(f) > 3 and f[1] == "PT" and f[2] == "TY":
                titles = _titles(line)
            continue
        try:
            br, pt, ty, lab = (int(x) for x in f[:4])
            vals = [float(x.replace("D", "E").replace("d", "e")) for x in f[4:]]
        except ValueError:
            raise AutoFileError(f"{path}: a row that is not numbers: {line.strip()[:60]!r}")
        if header or cur is None or br != cur.BR:
            bc = c
            if bc is None and header:
                bc = AutoConstants(header_constants(header))
            elif bc is None and cur is not None:
                bc = cur.c
            cur = Branch(header, titles, c=bc)
            branches.append(cur)
            header = []
        cur.rows.append(Row(br, pt, ty, lab, vals))
    return branches


def read_solutions(path, c=None) -> list[Solution]:
    """Solutions of an s-file (s.NAME.gz where s.NAME does not exist: files.s_file), each
    with its record's lines kept."""
    path = s_file(path)
    lines = _read_text(path, "an AUTO s-file").splitlines()
    out, i = [], 0
    while i < len(lines):
        if not lines[i].split():
            i += 1
            continue
        rec, nrowpr = _read_record(path, lines, i)
        out.append(Solution(rec, c, raw=lines[i:i + 1 + nrowpr]))
        i += 1 + nrowpr
    mlab = max((s.rec.lab for s in out), default=0)
    mbr = max((abs(s.rec.br) for s in out), default=0)
    for s in out:
        s._mlab, s._mbr = mlab, mbr
    return out
