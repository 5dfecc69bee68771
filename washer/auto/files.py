"""AUTO-07p's b., s. and d. files (docs/auto.md section 2): writers and readers. No numerics.

Writers append one point at a time and flush after every write, or (a run's files,
`washer.auto.sinks.FileSink`) every FLUSH_SECONDS and at the end, so a run that fails
half-way keeps every point computed so far. The layouts are AUTO-07p's (io.f90: STHD,
HEADNG, WRLINE; ae.f90: WRTSP8, PRINTEIG), so AUTO's own Python tools (parseB,
parseS, parseD) read what washer writes:
  * a b-file header is written together with the branch's first point, so a run
    that fails before its first point leaves an empty b-file, not a header
    without data (which parseB cannot read);
  * every point is repeated in the d-file in screen format after a bar of 47
    '=', as AUTO does, so parseD finds each point's branch, number, label and
    eigenvalues.
Outputs never follow a symlink (a link at an output path is replaced, its
target untouched) and never truncate a protected file (the restart source).
"""
from __future__ import annotations

import functools
import gzip
import math
import os
import re
import time
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from washer.auto.es_format import es_text, point_bytes, point_text
from washer.cont.codes import find, parse_label, type_name  # noqa: F401 (re-exported)
from washer.cont.record import Record
from washer.text_files import decode_text

#: The d-file's separator between steps (ae.f90: WRBAR('=', 47)); parseD splits on it.
D_BAR = "=" * 47


class AutoFileError(ValueError):
    """An AUTO file that cannot be read: the message names the file, the line and what
    was expected there."""


def fmt_e(x: float, width: int = 19, digits: int = 10) -> str:
    """Fortran ESw.dE3: mantissa in [1, 10) and a 3-digit exponent (b- and s-file data)."""
    return es_text([x], width, digits, exp3=True)


def fmt_es(x: float, width: int, digits: int) -> str:
    """Fortran ESw.d (no Ee): a 2-digit exponent 'E-07'; for |exponent| > 99 the 'E' is
    dropped ('-1.7976+308'), as gfortran does. b-file header reals (ES11.4, ES12.4) and
    d-file values (ES14.5)."""
    return es_text([x], width, digits)


def fmt_e_many(values, width: int = 19, digits: int = 10) -> str:
    """fmt_e of every value, concatenated (a 2-D array row after row)."""
    return es_text(values, width, digits, exp3=True)


def fmt_es_many(values, width: int, digits: int) -> str:
    """fmt_es of every value, concatenated (a 2-D array row after row)."""
    return es_text(values, width, digits)


def _fortran_float(token: str) -> float:
    """A real as AUTO writes it: 1.0E-07, 1.0D-07, 1.0-100 (ESw.d with a 3-digit exponent)."""
    try:
        return float(token)
    except ValueError:
        pass
    t = token.replace("D", "E").replace("d", "e")
    m = re.fullmatch(r"([+-]?\d*\.?\d*)([+-]\d{3})", t)
    if m and m.group(1) not in ("", "+", "-"):
        t = f"{m.group(1)}E{m.group(2)}"
    return float(t)          # ValueError if still not a number


def _index_str(k) -> str:
    """A dict key as STHD writes it: a number plain, a name quoted."""
    if isinstance(k, str) and not k.strip().lstrip("-").isdigit():
        return f"'{k}'"
    return str(int(k))


def _value_str(x) -> str:
    """A dict value as STHD writes it: integral values as integers (I19), else ES19.10E3."""
    x = float(x)
    if x.is_integer() and abs(x) < 2**31:
        return str(int(x))
    return fmt_e(x).strip()


def _dict_str(d: dict) -> str:
    """AUTO's WRITELIST/WRITEUZRLIST: {11: 0}, {2: [14, 15]}; brackets only for 2+ values."""
    items = []
    for k, v in d.items():
        vals = v if isinstance(v, (list, tuple)) else [v]
        txt = [_value_str(x) for x in vals]
        items.append(f"{_index_str(k)}: " + (f"[{', '.join(txt)}]" if len(txt) > 1 else txt[0]))
    return "{" + ", ".join(items) + "}"


def _names_str(d: dict) -> str:
    """AUTO's WRITESTRLIST: {1: 'x', 2: 'y'}."""
    return "{" + ", ".join(f"{int(k)}: '{v}'" for k, v in d.items()) + "}"


#: Where HEADNG's WRITECOL puts a column title (1-based start in a 19-character
#: field): PAR(i) and L2-NORM at 4, U(i) at 6, MAX/MIN U(i) at 4, PERIOD at 5,
#: INTEGRAL/L2-NORM U(i) at 2; any other title is a user's name, centred.
_TITLE_COLUMNS = ((r"PAR\(\d+\)", 4), (r"L2-NORM", 4), (r"U\(\d+\)", 6), (r"(MAX|MIN) U\(\d+\)", 4),
                  (r"PERIOD", 5), (r"(INTEGRAL|L2-NORM) U\(\d+\)", 2))
#: AUTO keeps names in CHARACTER(13) (io.f90: getname).
NAME_LENGTH = 13


def column_title(title: str) -> str:
    """The 19-character b-file column title of HEADNG (the screen and d-file show its
    first 14 characters). A name is centred at column max(7 - (len - 1) // 2, 2); a
    title that carries its column (washer.cont.record.ColumnTitle) is placed there."""
    column = getattr(title, "column", None)
    if column is not None:
        return (" " * (column - 1) + str(title).strip()[:NAME_LENGTH]).ljust(19)[:19]
    return _column_title(str(title))


@functools.lru_cache(maxsize=1024)
def _column_title(title: str) -> str:
    title = title.strip()
    for pattern, col in _TITLE_COLUMNS:
        if re.fullmatch(pattern, title):
            break
    else:
        # a name (CHARACTER(13) in AUTO), alone or after HEADNG's 'MAX ', 'INTEGRAL ', ...
        m = re.fullmatch(r"(MAX |MIN |INTEGRAL |L2-NORM )?(.*)", title)
        title = (m.group(1) or "") + m.group(2)[:NAME_LENGTH]
        col = max(7 - (len(title) - 1) // 2, 2)
    return (" " * (col - 1) + title).ljust(19)[:19]


def screen_heading(titles: list[str]) -> str:
    """'  BR    PT  TY  LAB ' and the A14 column titles (screen and d-file), at most 8 columns."""
    return "  BR    PT  TY  LAB " + "".join(column_title(t)[:14] for t in titles[:8])


@dataclass
class Row:
    """One continuation point as the b-file shows it."""
    br: int
    pt: int               # signed: negative = stable
    ty: int
    lab: int
    values: list          # PAR(ICP(1)), norm, U(1..N2), PAR(ICP(2..))


def _mtot(pt: int) -> int:
    """The step number an s-file header holds: AUTO's MTOT = MOD(NTOT-1, 9999) + 1 (WRTSP8,
    WRTBV8), so that it fits its I6 field: a raw 100000 would run into the branch number
    before it and the header would read as one integer fewer."""
    return (pt - 1) % 9999 + 1 if pt > 0 else -((-pt - 1) % 9999) - 1


def record_text(rec: Record) -> str:
    """The s-file text of a record (algebraic: WRTSP8; BVP: `_record_text_bvp`)."""
    if np.ndim(rec.u) == 2:
        return _record_text_bvp(rec)
    return _record_text_algebraic(rec)


def _record_text_algebraic(rec: Record) -> str:
    """An algebraic record as ae.f90:WRTSP8 writes it: t = 0 and the stored state, then
    ICP, RLDOT and UDOT if the direction is stored, then PAR."""
    n = len(rec.u)
    npar = len(rec.par)
    has_dir = rec.udot is not None
    nrow = n // 7 + 1 + (npar + 6) // 7
    if has_dir:
        nrow += (rec.nfpr + 19) // 20 + (rec.nfpr + 6) // 7 + (n + 6) // 7
    head = (f"{rec.br:6d}{_mtot(rec.pt):6d}{rec.code:6d}{rec.lab:6d}{rec.nfpr:6d}{rec.isw:6d}"
            f"{1:8d}{n + 1:6d}{nrow:8d}{int(has_dir):5d}{0:5d}{npar:5d}{rec.npari:5d}"
            f"{rec.ndim_user:5d}{rec.ips:5d}{0:5d}")
    # t and the state (the first line t and U(1..6)), RLDOT, UDOT, PAR: each 7 a line
    groups = [[0.0] + np.asarray(rec.u, float).tolist()]
    if has_dir:
        groups += [list(rec.rldot), np.asarray(rec.udot, float).tolist()]
    groups.append(np.asarray(rec.par, float).tolist())
    blocks = _group_rows(groups)
    lines = [head] + blocks[0]
    if has_dir:
        lines += _icp_lines(rec.icp[:rec.nfpr]) + blocks[1] + blocks[2]
    lines += blocks[-1]
    return "\n".join(lines) + "\n"


#: The width of an s-file value, ES19.10E3: every double's text fills it exactly (sign,
#: 12 digits and the point, E and a signed 3-digit exponent: 18 characters at most; NaN and
#: the infinities right-justified in it).
S_FIELD = 19


def _group_rows(groups: list) -> list[list[str]]:
    """`_rows` of each group of values (lists of floats), as lines, from one formatted
    call: the values' ES19.10E3 fields lie side by side in it, and a line is 4 blanks and
    up to 7 of them."""
    flat = [v for g in groups for v in g]
    text = es_text(flat, S_FIELD, 10, exp3=True)
    if len(text) != S_FIELD * len(flat):         # (not expected: each group on its own)
        return [_rows(g) for g in groups]
    out, pos = [], 0
    for g in groups:
        lines = []
        for k in range(0, len(g), 7):
            m = min(7, len(g) - k)
            lines.append("    " + text[pos * S_FIELD:(pos + m) * S_FIELD])
            pos += m
        out.append(lines)
    return out


def _record_text_bvp(rec: Record) -> str:
    """A BVP/periodic record as bvp.f90:WRTBV8 writes it: NTPL blocks `t U(1..NDIM)`
    (7 values a line), then ICP, RLDOT and NTPL blocks of UDOT (without t) if the
    direction is stored, then PAR."""
    U = np.asarray(rec.u, float)
    ntpl, n = U.shape
    t = np.linspace(0, 1, ntpl) if rec.t is None else np.asarray(rec.t, float)
    npar = len(rec.par)
    has_dir = rec.udot is not None
    nrow = (n // 7 + 1) * ntpl + (npar + 6) // 7
    if has_dir:
        nrow += (rec.nfpr + 19) // 20 + (rec.nfpr + 6) // 7 + ((n + 6) // 7) * ntpl
    head = (f"{rec.br:6d}{_mtot(rec.pt):6d}{rec.code:6d}{rec.lab:6d}{rec.nfpr:6d}{rec.isw:6d}"
            f"{ntpl:8d}{n + 1:6d}{nrow:8d}{rec.ntst:5d}{rec.ncol:5d}{npar:5d}{rec.npari:5d}"
            f"{rec.ndim_user:5d}{rec.ips:5d}{0:5d}")
    lines = [head]
    lines += _block_lines(np.column_stack([t, U]))     # t-blocks: t, U(1..NDIM)
    if has_dir:
        ud = np.asarray(rec.udot, float).reshape(ntpl, n)
        lines += _icp_lines(rec.icp[:rec.nfpr])
        lines += _rows(rec.rldot)
        lines += _block_lines(ud)
    lines += _rows(list(rec.par))
    return "\n".join(lines) + "\n"


def _icp_lines(icp) -> list[str]:
    """The free-parameter indices as AUTO's WRTSP8/WRTBV8 write them, FORMAT (20I5): 20 a
    line, so that a record with more than 20 (NROWPR counts (NFPR + 19) // 20 lines) reads
    back, by AUTO and by `read_solutions`."""
    return ["".join(f"{i:5d}" for i in icp[k:k + 20]) for k in range(0, len(icp), 20)]


def _rows(vals) -> list[str]:
    """Values 7 a line (ES19.10E3 after 4 blanks), as AUTO's s-files: the lines as one
    string (joined by newlines) in a list, [] for no values."""
    text = es_text(vals, 19, 10, exp3=True, per_line=7, indent=4)
    return [text] if text else []


def _block_lines(M: np.ndarray) -> list[str]:
    """`_rows` of every row of M (k, m), each row on lines of its own: the text of the
    whole block (thousands of values in a BVP record's profile) in one call, as one string
    in a list, [] for an empty M."""
    M = np.asarray(M, dtype=float)
    if M.size == 0:
        return []
    return [es_text(M, 19, 10, exp3=True, per_line=7, indent=4)]


def prepare_output(path: Path, protect=()) -> Path | None:
    """Make `path` ready to be written from scratch, safely.

    A symlink at `path` is removed (the new file replaces the link; its target
    is never opened). An existing file that is one of `protect` (the restart
    source, compared by identity, not by name) is renamed to `path~` instead of
    being truncated: its records survive a crash of the new run. Returns that
    backup path, or None.
    """
    path = Path(path)
    if path.is_symlink():
        path.unlink()
        return None
    if path.exists():
        for q in protect:
            try:
                same = q is not None and Path(q).exists() and os.path.samefile(path, q)
            except OSError:
                same = False
            if same:
                backup = path.with_name(path.name + "~")
                os.replace(path, backup)
                return backup
    return None


#: The bytes held back for a flush at most (beyond them the files are written at once).
MAX_HELD = 1 << 20


def _open_fd(path: Path) -> int:
    """A descriptor appending to `path` that never follows a symlink (O_NOFOLLOW)."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_APPEND | getattr(os, "O_NOFOLLOW", 0)
    return os.open(path, flags, 0o666)


def _open_output(path: Path, append: bool):
    """A text handle on `path` that never follows a symlink (O_NOFOLLOW)."""
    flags = os.O_WRONLY | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0)
    flags |= os.O_APPEND if append else os.O_TRUNC
    return os.fdopen(os.open(path, flags, 0o666), "a" if append else "w", encoding="utf-8")


class OutputFiles:
    """b./s./d. files of one run (sv name), written point by point; flushed after every
    write, or at most `flush_seconds` apart and at `close`.

    protect: files that must not be truncated, above all the s-file the run
    restarts from (AUTO's default sv is the restart file's own name): if an
    output path is one of them, the old file is kept as `NAME~` (see
    `prepare_output`; `.backups` lists them). Construct OutputFiles only after
    the restart data has been read into memory.
    """

    def __init__(self, folder: Path, name: str, protect=(), flush_seconds: float = 0.0):
        folder = Path(folder)
        self.flush_seconds = flush_seconds
        self.b_path, self.s_path, self.d_path = (folder / f"{k}.{name}" for k in "bsd")
        self.backups: list[Path] = []
        for p in (self.b_path, self.s_path, self.d_path):
            try:
                backup = prepare_output(p, protect)
                if backup is not None:
                    self.backups.append(backup)
                with _open_output(p, append=False):
                    pass
            except OSError as exc:      # found before any computation, not after it
                raise AutoFileError(f"{p}: cannot write this output file "
                                    f"({exc.strerror or exc})") from None
        # The text written and not yet flushed, a buffer a file (by the Path object's
        # identity, the three paths being this object's own: a Path's hash is a
        # Python-level call), and the files' descriptors, opened on first flush.
        self._buffers = {id(p): bytearray() for p in (self.b_path, self.s_path, self.d_path)}
        self._b = self._buffers[id(self.b_path)]
        self._s = self._buffers[id(self.s_path)]
        self._d = self._buffers[id(self.d_path)]
        self._fds: dict = {}
        self.column_titles: list[str] = []
        self._pending_b = ""        # header lines waiting for the branch's first point
        self._flushed = time.monotonic()
        # the column titles the d-file's screen heading was made for, and the text before a
        # point's screen line: the heading, and the bar and the heading
        self._heading = (None, "", "")
        self._d_points = 0

    def _append(self, path: Path, text: str, path2: Path | None = None,
                text2: str = "") -> None:
        """Append text to path (and text2 to path2), and flush all files when
        `flush_seconds` have passed since the last flush (0: after every write)."""
        buffers = self._buffers
        buffers[id(path)] += text.encode("utf-8")
        if path2 is not None:
            buffers[id(path2)] += text2.encode("utf-8")
        self._written()

    def _written(self) -> None:
        """After a write: all files flushed when `flush_seconds` have passed since the last
        flush, or when the text held back grows large (a run of big s-records)."""
        now = time.monotonic()
        if now - self._flushed >= self.flush_seconds or len(self._s) + len(self._d) > MAX_HELD:
            self.flush()
            self._flushed = now

    def flush(self) -> None:
        """Everything written so far to disk: the s-file first, so that each label of
        the b-file has its record there (an s-record is written before its b-row)."""
        for path in (self.s_path, self.b_path, self.d_path):
            buf = self._buffers[id(path)]
            if buf:
                self._write_out(path, buf)
                del buf[:]

    def _write_out(self, path: Path, data: bytearray) -> None:
        """data appended to the file at path (opened on first use without following
        symlinks; it stays open for the run) and taken out of data as it is written: a
        write that fails part-way (a full disk) leaves only the rest to write, so that
        `close` does not write the first part twice."""
        fd = self._fds.get(path)
        if fd is None:
            fd = self._fds[path] = _open_fd(path)
        done = 0
        try:
            while done < len(data):
                # (a copy of the rest only after a short write, which regular files
                # hardly ever make)
                done += os.write(fd, data[done:] if done else data)
        finally:
            del data[:done]

    def close(self) -> None:
        """End of the run: everything written is flushed (the s-file first) and the
        files closed; a header still pending had no point to go with, and is dropped so
        that the b-file never holds a header without data."""
        self._pending_b = ""
        try:
            self.flush()
        finally:
            for fd in self._fds.values():
                os.close(fd)
            self._fds.clear()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def header(self, c, ndim_internal: int, npar: int, column_titles: list[str],
               curve_type: int = 0, curve_name: str = "", *, irs: int | None = None,
               nfpr: int | None = None, ds: float | None = None, dsmin: float | None = None,
               dsmax: float | None = None, active: list | None = None,
               internal: dict | None = None, s_name: str | None = None,
               homcont: tuple | None = None) -> None:
        """The run's header block (io.f90:STHD), in AUTO-07p's exact layout.

        c: the user's constants; ndim_internal, npar: NDIM and NPAR as the
        engine uses them (extended NDIM on ISW=2 curves, NPAR raised to 11 for
        IPS=1); irs: the restart label actually used (default: IRS if it is a
        number, else 0); nfpr: number of free parameters (default 2 on |ISW|=2
        curves, else 1); ds, dsmin, dsmax: the engine's step sizes (default the
        user's); active: the run's internal ICP(1..NFPR) where it is not the user's
        (IPS = 15 appends PAR(10), PAR(13), PAR(14)); internal: the run's own ILP, ISP,
        ISW, NMX, NBC, NINT where they are not the user's (an extended system's boundary
        and integral conditions, a generating run's ISW = -2, NMX = 5). Where an internal
        value differs from the user's, AUTO lists the user's under 'User-specified
        constants, where different from above' (AUTO-07p's parseB reads those back).
        s_name: the s the header names where it is not c's (AUTO's CLUI: '/').
        homcont: (NUNSTAB, NSTAB, ISTART) as an IPS = 9 run uses them (default the user's);
        IPS = 9 headers state them with IEQUIB, ITWIST (and IREV, IFIXED, IPSI where set),
        the user's NUNSTAB, NSTAB, ISTART below where they differ.
        The block is written with the first point (`row`), never alone.
        """
        user_irs = c["IRS"] if isinstance(c["IRS"], int) else None
        irs = irs if irs is not None else (user_irs or 0)
        nfpr = nfpr if nfpr is not None else (2 if abs(c["ISW"]) == 2 else 1)
        steps = {"DS": ds, "DSMIN": dsmin, "DSMAX": dsmax}
        steps = {k: (c[k] if v is None else v) for k, v in steps.items()}
        run = {k: c[k] for k in ("ILP", "ISP", "ISW", "NMX", "NBC", "NINT")}
        run.update(internal or {})
        d3 = lambda *kv: "   0" + "".join(f"{k:>8}{fmt_es(v, 11, 4)}" for k, v in kv)
        i4 = lambda *kv: "   0" + "".join(f"{k:>8}{v:4d}" for k, v in kv)
        lines = ["   0 " + "".join(fmt_es(c[k], 12, 4) for k in ("RL0", "RL1", "A0", "A1"))]
        lines.append(d3(("EPSL=", c["EPSL"]), ("EPSU =", c["EPSU"]), ("EPSS =", c["EPSS"])))
        lines.append(d3(("DS  =", steps["DS"]), ("DSMIN=", steps["DSMIN"]),
                        ("DSMAX=", steps["DSMAX"])))
        lines.append(i4(("NDIM=", ndim_internal), ("IPS =", c["IPS"]), ("IRS =", irs),
                        ("ILP =", run["ILP"])))
        lines.append(i4(("NTST=", c["NTST"]), ("NCOL=", c["NCOL"]), ("IAD =", c["IAD"]),
                        ("ISP =", run["ISP"])))
        lines.append(i4(("ISW =", run["ISW"]), ("IPLT=", c["IPLT"]), ("NBC =", run["NBC"]),
                        ("NINT=", run["NINT"])))
        lines.append(f"   0{' NMX=':>7}{run['NMX']:5d}{'NPR=':>7}{c['NPR']:5d}{'MXBF=':>8}{c['MXBF']:4d}"
                     f"{'IID =':>8}{c['IID']:4d}{'IADS=':>8}{c['IADS']:4d}")
        nuzr = sum(len(v) if isinstance(v, (list, tuple)) else 1
                   for key in ("UZR", "UZSTOP") for v in c[key].values())
        lines.append(i4(("ITMX=", c["ITMX"]), ("ITNW=", c["ITNW"]), ("NWTN=", c["NWTN"]),
                        ("JAC =", c["JAC"]), ("  NUZR=", nuzr)))
        if c["IBR"] > 0 or c["LAB"] > 0 or c["TY"].strip() or c["IIS"] < 3:
            extra = [("IIS =", c["IIS"])] if c["IIS"] < 3 else []
            extra += [(k, c[k[:3]]) for k in ("IBR =", "LAB =") if c[k[:3]] > 0]
            line = i4(*extra)
            if c["TY"].strip():
                line += f"{chr(39).join(['TY = ', '']):>9}{c['TY'].strip()}'"
            lines.append(line)
        lines.append(f"   0   NPAR={npar:4d}   THL = {_dict_str(c['THL'])}"
                     f"    THU = {_dict_str(c['THU'])}")
        for key in ("UZR", "UZSTOP"):
            if c[key]:
                lines.append(f"   0   {key} = {_dict_str(c[key])}")
        if c["IPS"] == 9:
            lines += self._homcont(c, homcont)
        names = {k: c[k] for k in ("e", "s", "dat", "sv")}
        if s_name is not None:
            names["s"] = s_name
        strs = "".join(f" {k} = '{v}'" for k, v in names.items() if v)
        if strs:
            lines.append("   0  " + strs)
        if c["parnames"]:
            lines.append(f"   0   parnames = {_names_str(c['parnames'])}")
        if c["unames"]:
            lines.append(f"   0   unames   = {_names_str(c['unames'])}")
        if c["PAR"]:
            lines.append(f"   0   PAR     = {_dict_str(c['PAR'])}")
        if c["U"]:
            lines.append(f"   0   U       = {_dict_str(c['U'])}")
        for key, label in (("SP", "SP="), ("STOP", "STOP=")):
            if c[key]:
                lines.append(f"   0   {label}[" + ", ".join(f"'{s}'" for s in c[key]) + "]")
        lines += self._user_specified(c, ndim_internal, npar, irs, user_irs, steps, run)
        if c["IPS"] == 9:
            lines += self._homcont_user(c, homcont)
        icp_user = c["ICP"]
        names = {int(k): v for k, v in c["parnames"].items()}
        lines.append("   0   User-specified parameter" + (":       " if len(icp_user) == 1 else
                     "s:      ") + "".join(f"   {i}" if isinstance(i, int) else f" '{i}'"
                                           for i in icp_user))
        active = list(active) if active is not None else c.icp()[:nfpr]
        lines.append("   0   Active continuation parameter" + (":  " if nfpr == 1 else "s: ")
                     + "".join(f" '{names[i]}'" if i in names else f"   {i}" for i in active))
        if curve_type:
            lines.append(f"   0   Branch type: {curve_type:2d}    TY = '{curve_name:<3}'")
        self._pending_b += "\n".join(lines) + "\n"
        self.column_titles = column_titles

    @staticmethod
    def _homcont(c, internal) -> list[str]:
        """STHD's HomCont lines of an IPS = 9 run: NUNSTAB, NSTAB, ISTART as the run uses
        them, the user's IEQUIB, ITWIST ('(2(A,I4),2(A8,I2),(A8,I4))'); IREV, IFIXED, IPSI
        where one is set."""
        nunstab, nstab, istart = internal or (c["NUNSTAB"], c["NSTAB"], c["ISTART"])
        lines = [f"   0   NUNSTAB={nunstab:4d} NSTAB={nstab:4d}{'IEQUIB=':>8}{c['IEQUIB']:2d}"
                 f"{'ITWIST=':>8}{c['ITWIST']:2d}{'ISTART=':>8}{istart:4d}"]
        lists = "".join(f" {k}=[" + ", ".join(str(int(i)) for i in c[k]) + "]"
                        for k in ("IREV", "IFIXED", "IPSI") if c[k])
        if lists:
            lines.append("   0  " + lists)
        return lines

    @staticmethod
    def _homcont_user(c, internal) -> list[str]:
        """The user's NUNSTAB, NSTAB, ISTART where the run's differ (STHD, after the
        'User-specified constants' lines)."""
        if internal is None:
            return []
        user = (c["NUNSTAB"], c["NSTAB"], c["ISTART"])
        if user == tuple(internal):
            return []
        fmts = ("NUNSTAB={:4d}", " NSTAB={:4d}", " ISTART={:4d}")
        return ["   0   " + "".join(f.format(u) for f, u, a in zip(fmts, user, internal)
                                    if u != a)]

    @staticmethod
    def _user_specified(c, ndim, npar, irs, user_irs, steps, run) -> list[str]:
        """STHD's 'User-specified constants, where different from above' lines: the
        step sizes; NDIM, IRS, ILP, NPAR; NMX, ISP, ISW, NBC, NINT."""
        ds_diff = [(k, fmt_es(c[k], 11, 4)) for k in ("DS", "DSMIN", "DSMAX")
                   if fmt_es(c[k], 11, 4) != fmt_es(steps[k], 11, 4)]
        ints = [("NDIM=", c["NDIM"], ndim), ("IRS =", user_irs, irs), ("ILP =", c["ILP"], run["ILP"]),
                ("NPAR=", c["NPAR"], npar)]
        int_diff = [(k, u) for k, u, a in ints if u is not None and u != a]
        runs = [("NMX=", "NMX"), ("ISP =", "ISP"), ("ISW =", "ISW"), ("NBC =", "NBC"),
                ("NINT=", "NINT")]
        run_diff = [(k, c[key]) for k, key in runs if c[key] != run[key]]
        if not ds_diff and not int_diff and not run_diff:
            return []
        lines = ["   0   User-specified constants, where different from above:"]
        if ds_diff:
            label = {"DS": "DS  =", "DSMIN": "DSMIN=", "DSMAX": "DSMAX="}
            lines.append("   0" + "".join(f"{label[k]:>8}{v}" for k, v in ds_diff))
        if int_diff:
            lines.append("   0" + "".join(f"{k:>8}{u:4d}" for k, u in int_diff))
        if run_diff:
            # NMX is (A7,I5), the others (A8,I4)
            lines.append("   0" + "".join(f"{k:>7}{u:5d}" if k == "NMX=" else f"{k:>8}{u:4d}"
                                          for k, u in run_diff))
        return lines

    def branch_start(self) -> None:
        """The two-line column header written at the first point of every branch
        (HEADNG, unit 7); it goes to the file with that first point."""
        titles = "".join(column_title(t) for t in self.column_titles)
        self._pending_b += f"   0\n   0    PT  TY  LAB {titles}\n"

    def row(self, r: Row, eigen=None) -> None:
        """One b-file line (WRLINE, unit 7), after any pending header; the d-file gets
        the same point in screen format (unit 9), opening the point's block, and with
        eigen = (br, pt, eigenvalues) PRINTEIG's block after it (`eigenvalues`), with
        eigen = (br, pt, multipliers, stable count) PVSPBV's Floquet block (`multipliers`)."""
        self.point_row(r.br, r.pt, r.ty, r.lab, r.values, eigen)

    def point_row(self, br: int, pt: int, ty: int, lab: int, values, eigen=None) -> None:
        """`row` of the Row (br, pt, ty, lab, values)."""
        heading = self._heading
        if heading[0] != self.column_titles:
            text = screen_heading(self.column_titles)
            heading = self._heading = (list(self.column_titles), f"\n{text}\n",
                                       f"{D_BAR}\n\n{text}\n")
        # the bar and the heading before every point's block but the first
        dhead = heading[2] if self._d_points else heading[1]
        self._d_points += 1
        data, nb = point_bytes(br, pt, ty, lab, type_name(ty), values, dhead, eigen)
        if self._pending_b:
            self._b += self._pending_b.encode("utf-8")
            self._pending_b = ""
        self._b += data[:nb]
        self._d += data[nb:]
        self._written()

    def eigenvalues(self, br: int, pt: int, eig) -> None:
        """AUTO's PRINTEIG block in the d-file: the number of stable eigenvalues, then
        'Eigenvalue  k:' with real and imaginary parts (ES14.5). pt: unsigned point number."""
        self.diag(point_text(0, 0, 0, 0, "", None, "", (br, pt, eig))[1])

    def multipliers(self, br: int, pt: int, mults, n_stable: int) -> None:
        """AUTO's Floquet block in the d-file (PVSPBV): 'Multipliers:     Stable:' and one
        'Multiplier  k ' line per multiplier with real, imaginary part and modulus (ES14.5)."""
        self.diag(point_text(0, 0, 0, 0, "", None, "", (br, pt, mults, n_stable))[1])

    def record(self, rec: Record) -> None:
        self._append(self.s_path, record_text(rec))

    def diag(self, text: str) -> None:
        self._append(self.d_path, text if text.endswith("\n") else text + "\n")


# ----------------------------------------------------------------------- readers

#: The suffix of a file kept gzipped: NAME.gz holds NAME's text.
GZIP_SUFFIX = ".gz"


def s_file(path) -> Path:
    """The file that s-file `path` (s.NAME) names: `path` itself where it exists, so a
    user's plain s.NAME always wins; else s.NAME.gz beside it where that exists (an
    s-file kept gzipped, as large reference files are); else `path`, so that a missing
    file is reported by the name the user wrote."""
    path = Path(path)
    if path.exists():
        return path
    gz = path.with_name(path.name + GZIP_SUFFIX)
    return gz if gz.exists() else path


def _read_text(path: Path, what: str) -> str:
    """A file's text, decompressed where its name ends in .gz; AutoFileError for a
    missing, binary or non-UTF-8 file or a damaged gzip stream."""
    try:
        data = Path(path).read_bytes()
        if Path(path).name.endswith(GZIP_SUFFIX):
            data = gzip.decompress(data)
    except (gzip.BadGzipFile, EOFError, zlib.error) as exc:
        raise AutoFileError(f"{path}: cannot read {what}: not a whole gzip file ({exc})") \
            from None
    except OSError as exc:
        raise AutoFileError(f"{path}: cannot read {what} ({exc.strerror})") from None
    return decode_text(data, str(path), what, AutoFileError)


def read_b(path: Path) -> list[list[Row]]:
    """Branches of a b-file: lists of Rows (header lines skipped)."""
    branches: list[list[Row]] = []
    new = True
    for line in _read_text(path, "an AUTO b-file").splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "0":
            new = True
            continue
        try:
            br, pt, ty, lab = (int(x) for x in f[:4])
            vals = [_fortran_float(x) for x in f[4:]]
        except ValueError:
            continue
        if new or not branches:
            branches.append([])
            new = False
        branches[-1].append(Row(br, pt, ty, lab, vals))
    return branches


#: Names of the s-file header integers (bvp.f90:WRTBV8), for error messages.
S_HEADER = "IBR NTOT ITP LAB NFPR ISW NTPL NAR NROWPR NTST NCOL NPAR [NPARI NDIM IPS IPRIV]"


def read_s(path: Path) -> list[Record]:
    """All records of an s-file (ours or AUTO's), checked.

    Each record is a header of 12 or 16 integers and NROWPR lines of numbers
    (docs/auto.md 2.2); a header that is not integers, a record cut short, a number
    that does not parse or a block of the wrong size raises AutoFileError naming
    the file, the line and what was expected there, so a corrupt restart file
    never starts a run from wrong data. s.NAME.gz is read where s.NAME does not
    exist (`s_file`).
    """
    path = s_file(path)
    lines = _read_text(path, "an AUTO s-file").splitlines()
    out, i = Records(), 0
    while i < len(lines):
        if not lines[i].split():
            i += 1
            continue
        try:
            rec, nrowpr = _read_record(path, lines, i)
        except AutoFileError as exc:
            # The last record of a file whose writer was killed may be cut short:
            # the records before it are intact and stay usable; what is lost is named.
            if out and _is_last_record(lines, i):
                out.damaged.append(str(exc))
                break
            raise
        out.header_lines[id(rec)] = f"{path}:{i + 1}"
        out.append(rec)
        i += 1 + nrowpr
    return out


class Records(list):
    """The records of an s-file; `.damaged` names a trailing record that could not
    be read (cut short by a killed writer), which is left out; `.header_lines` gives
    each record's "file:line" (by id) for messages."""

    def __init__(self, *args):
        super().__init__(*args)
        self.damaged: list[str] = []
        self.header_lines: dict[int, str] = {}


def _is_last_record(lines: list[str], i: int) -> bool:
    """No other record header (a line of 12 or 16 integers) after line i."""
    for line in lines[i + 1:]:
        f = line.split()
        if len(f) in (12, 16) and all(x.lstrip("-").isdigit() for x in f):
            return False
    return True


def _read_record(path: Path, lines: list[str], i: int) -> tuple[Record, int]:
    """The record whose header is lines[i], and its NROWPR."""
    where = f"{path}:{i + 1}"
    try:
        h = [int(x) for x in lines[i].split()]
    except ValueError:
        raise AutoFileError(f"{where}: expected an s-file record header of 12 or 16 integers "
                            f"({S_HEADER}), got {lines[i].strip()[:60]!r}") from None
    if len(h) not in (12, 16):
        raise AutoFileError(f"{where}: an s-file record header has 12 or 16 integers "
                            f"({S_HEADER}), this one has {len(h)}")
    br, ntot, itp, lab, nfpr, isw, ntpl, nar, nrowpr, ntst, ncol, npar = h[:12]
    for name, value, low in (("NFPR", nfpr, 0), ("NTPL", ntpl, 1), ("NAR", nar, 2),
                             ("NROWPR", nrowpr, 1), ("NPAR", npar, 0)):
        if value < low:
            raise AutoFileError(f"{where}: header field {name} = {value}, expected >= {low}")
    npari = h[12] if len(h) > 12 else 0
    if not 0 <= npari <= npar:
        raise AutoFileError(f"{where}: header field NPARI = {npari}, expected 0..NPAR = {npar} "
                            "(the internal parameters among the NPAR stored)")
    ndim_user = h[13] if len(h) > 13 else nar - 1
    ips = h[14] if len(h) > 14 else 1
    if i + 1 + nrowpr > len(lines):
        raise AutoFileError(f"{where}: the record announces NROWPR = {nrowpr} lines, only "
                            f"{len(lines) - i - 1} follow: the file is truncated")
    first = i + 1                                    # index of the body's first line

    def numbers(a: int, b: int, count: int, what: str, conv=_fortran_float) -> list:
        """`count` numbers from body lines a..b (0-based in the body)."""
        vals = []
        for k in range(a, b):
            for tok in lines[first + k].split():
                try:
                    vals.append(conv(tok))
                except ValueError:
                    raise AutoFileError(f"{path}:{first + k + 1}: expected a number in {what}, "
                                        f"got {tok!r}") from None
        if len(vals) != count:
            raise AutoFileError(f"{path}:{first + a + 1}: {what} should hold {count} numbers "
                                f"(header at line {i + 1}), found {len(vals)}")
        return vals

    n = nar - 1
    k = n // 7 + 1                                   # lines of one t-block
    tvals = numbers(0, k * ntpl, ntpl * nar, "the solution block (t, U)")
    U = np.array(tvals[1:nar]) if ntpl == 1 else np.array(tvals).reshape(ntpl, nar)[:, 1:]
    pos = k * ntpl
    icp, rldot, udot = [], [], None
    has_dir = ntst > 0 and nrowpr > (n // 7 + 1) * ntpl + (npar + 6) // 7
    if has_dir:
        nicp, nr, nu = (nfpr + 19) // 20, (nfpr + 6) // 7, ((n + 6) // 7) * ntpl
        icp = numbers(pos, pos + nicp, nfpr, "the free-parameter indices ICP", int)
        rldot = numbers(pos + nicp, pos + nicp + nr, nfpr, "the parameter direction RLDOT")
        udot = np.array(numbers(pos + nicp + nr, pos + nicp + nr + nu, n * ntpl,
                                "the direction UDOT"))
        pos += nicp + nr + nu
    par = np.array(numbers(pos, nrowpr, npar, "the parameters PAR(1..NPAR)"))
    t = np.array(tvals[::nar]) if ntpl > 1 else None
    return Record(br, ntot, itp, lab, nfpr, isw, ndim_user, ips, U, par, icp, rldot, udot,
                  t=t, ntst=ntst, ncol=ncol, npari=npari), nrowpr


def read_named_dat(name: str, ndim: int, folder: Path = Path(".")
                   ) -> tuple[np.ndarray, np.ndarray]:
    """read_dat of AUTO's dat='NAME' in `folder`: the file NAME where it exists
    (dat='rev.dat.1' in demo rev, dat='x.dat' in a user's constants), else NAME.dat,
    the order AUTO opens them in. Neither there raises AutoFileError naming both (AUTO:
    "Datafile NAME not found")."""
    folder = Path(folder)
    path = folder / name if (folder / name).is_file() else folder / f"{name}.dat"
    if not path.is_file():
        raise AutoFileError(f"dat='{name}': no data file {name} or {name}.dat in "
                            f"{folder.resolve()}")
    return read_dat(path, ndim)


def read_dat(path: Path, ndim: int) -> tuple[np.ndarray, np.ndarray]:
    """A data file of AUTO's `dat='NAME'` (NAME.dat, copied by AUTO's CLUI to fort.3 and
    read by STPNUB): one row per time point, `t u(1) ... u(NDIM)`, blank-separated, in
    any Fortran real notation (1.0D+01 as well). Blank lines and lines starting with
    '#' are skipped.

    Returns (t (m,), U (m, NDIM)) with m >= 2 and t strictly increasing; anything else
    raises AutoFileError naming the file, the line and what was expected. Columns beyond
    NDIM + 1 are an error too (a file written for another problem)."""
    path = Path(path)
    text = _read_text(path, "a data file (t, u(1..NDIM) per line)")
    rows, where = [], []
    for k, line in enumerate(text.splitlines(), start=1):
        toks = line.split()
        if not toks or toks[0].startswith("#"):
            continue
        if len(toks) != ndim + 1:
            raise AutoFileError(f"{path}:{k}: expected {ndim + 1} numbers (t and U(1..{ndim})),"
                                f" got {len(toks)}")
        try:
            rows.append([_fortran_float(x) for x in toks])
        except ValueError:
            raise AutoFileError(f"{path}:{k}: expected numbers, got {line.strip()!r}") from None
        if not all(math.isfinite(v) for v in rows[-1]):
            raise AutoFileError(f"{path}:{k}: non-finite value in {line.strip()!r}")
        where.append(k)
    if len(rows) < 2:
        raise AutoFileError(f"{path}: expected at least two rows (t, U(1..{ndim})), "
                            f"got {len(rows)}")
    data = np.array(rows)
    t = data[:, 0]
    bad = np.nonzero(np.diff(t) <= 0)[0]
    if len(bad):
        k = bad[0] + 1
        raise AutoFileError(f"{path}:{where[k]}: t = {t[k]!r} does not increase (previous "
                            f"t = {t[k - 1]!r})")
    return t, data[:, 1:]
