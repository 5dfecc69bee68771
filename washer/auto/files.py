"""AUTO-07p's b., s. and d. files (AUTO.md section 2): writers and readers. No numerics.

Writers append and flush one point at a time, so a run that fails half-way
keeps every point computed so far.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

#: Two-letter names of AUTO's type codes (support.f90:LBTYPE), by |code| % 10.
TYPE_NAMES = {1: "BP", 2: "LP", 3: "HB", 4: "", -4: "UZ", 5: "LP", 6: "BP", 7: "PD", 8: "TR",
              9: "EP", -9: "MX", -1: "BT", -2: "CP", -3: "ZH", 0: ""}


def type_name(code: int) -> str:
    """'HB', 'UZ', 'GH', ... for an ITP code, including curve codes like -34 or 39."""
    if code in (-32,):
        return "GH"
    base = code % 10 if code >= 0 else -((-code) % 10)
    return TYPE_NAMES.get(base, "")


def fmt_e(x: float, width: int = 19, digits: int = 10) -> str:
    """Fortran ESw.dE3: mantissa in [1, 10) and a 3-digit exponent."""
    if x == 0 or not math.isfinite(x):
        mant, exp = (0.0, 0) if x == 0 else (x, 0)
    else:
        exp = int(math.floor(math.log10(abs(x))))
        mant = x / 10**exp
        if round(abs(mant), digits) >= 10:
            mant, exp = mant / 10, exp + 1
    s = f"{mant:.{digits}f}E{'+' if exp >= 0 else '-'}{abs(exp):03d}"
    if x == 0 and math.copysign(1, x) < 0:
        s = "-" + s
    return s.rjust(width)


def _dict_str(d: dict) -> str:
    items = []
    for k, v in d.items():
        key = f"'{k}'" if isinstance(k, str) else str(k)
        vals = v if isinstance(v, list) else [v]
        txt = [str(int(x)) if float(x).is_integer() and abs(x) < 1e15 else fmt_e(x).strip()
               for x in vals]
        items.append(f"{key}: " + (f"[{', '.join(txt)}]" if isinstance(v, list) else txt[0]))
    return "{" + ", ".join(items) + "}"


@dataclass
class Row:
    """One continuation point as the b-file shows it."""
    br: int
    pt: int               # signed: negative = stable
    ty: int
    lab: int
    values: list          # PAR(ICP(1)), norm, U(1..N2), PAR(ICP(2..))


@dataclass
class Record:
    """One labelled solution (s-file record)."""
    br: int
    pt: int
    ty: int
    lab: int
    nfpr: int
    isw: int
    ndim_user: int
    ips: int
    U: np.ndarray                     # stored (possibly extended) state
    par: np.ndarray                   # PAR(1..NPAR)
    icp: list = field(default_factory=list)
    rldot: list = field(default_factory=list)
    udot: np.ndarray | None = None

    def text(self) -> str:
        n = len(self.U)
        npar = len(self.par)
        has_dir = self.udot is not None
        nrow = n // 7 + 1 + (npar + 6) // 7
        if has_dir:
            nrow += (self.nfpr + 19) // 20 + (self.nfpr + 6) // 7 + (n + 6) // 7
        head = (f"{self.br:6d}{self.pt:6d}{self.ty:6d}{self.lab:6d}{self.nfpr:6d}{self.isw:6d}"
                f"{1:8d}{n + 1:6d}{nrow:8d}{int(has_dir):5d}{0:5d}{npar:5d}{0:5d}"
                f"{self.ndim_user:5d}{self.ips:5d}{0:5d}")
        lines = [head]
        vals = [0.0] + list(self.U)
        lines += _rows(vals[:7]) + _rows(vals[7:])
        if has_dir:
            lines.append("".join(f"{i:5d}" for i in self.icp[:self.nfpr]))
            lines += _rows(self.rldot)
            lines += _rows(list(self.udot))
        lines += _rows(list(self.par))
        return "\n".join(lines) + "\n"


def _rows(vals) -> list[str]:
    return ["    " + "".join(fmt_e(v) for v in vals[i:i + 7]) for i in range(0, len(vals), 7)]


class OutputFiles:
    """b./s./d. files of one run (sv name), written point by point."""

    def __init__(self, folder: Path, name: str):
        self.b_path, self.s_path, self.d_path = (folder / f"{k}.{name}" for k in "bsd")
        for p in (self.b_path, self.s_path, self.d_path):
            p.write_text("")

    def _append(self, path: Path, text: str) -> None:
        with open(path, "a") as fh:
            fh.write(text)
            fh.flush()

    def header(self, c, ndim_internal: int, npar: int, column_titles: list[str],
               curve_type: int = 0, curve_name: str = "") -> None:
        lines = [f"   0 {fmt_e(c['RL0'], 12, 4)}{fmt_e(c['RL1'], 12, 4)}{fmt_e(c['A0'], 12, 4)}"
                 f"{fmt_e(c['A1'], 12, 4)}".replace("E+308", "+308").replace("E-308", "-308")]
        d3 = lambda *kv: "   0" + "".join(f"{k:>8}{fmt_e(v, 11, 4)}" for k, v in kv)
        i4 = lambda *kv: "   0" + "".join(f"{k:>8}{v:4d}" for k, v in kv)
        lines.append(d3(("EPSL=", c["EPSL"]), ("EPSU =", c["EPSU"]), ("EPSS =", c["EPSS"])))
        lines.append(d3(("DS  =", c["DS"]), ("DSMIN=", c["DSMIN"]), ("DSMAX=", c["DSMAX"])))
        irs = c["IRS"] if isinstance(c["IRS"], int) else 1
        lines.append(i4(("NDIM=", ndim_internal), ("IPS =", c["IPS"]), ("IRS =", irs),
                        ("ILP =", c["ILP"])))
        lines.append(i4(("NTST=", c["NTST"]), ("NCOL=", c["NCOL"]), ("IAD =", c["IAD"]),
                        ("ISP =", c["ISP"])))
        lines.append(i4(("ISW =", c["ISW"]), ("IPLT=", c["IPLT"]), ("NBC =", c["NBC"]),
                        ("NINT=", c["NINT"])))
        lines.append(f"   0{'NMX=':>7}{c['NMX']:5d}{'NPR=':>7}{c['NPR']:5d}{'MXBF=':>8}{c['MXBF']:4d}"
                     f"{'IID =':>8}{c['IID']:4d}{'IADS=':>8}{c['IADS']:4d}")
        nuzr = sum(len(v) if isinstance(v, list) else 1
                   for key in ("UZR", "UZSTOP") for v in c[key].values())
        lines.append(i4(("ITMX=", c["ITMX"]), ("ITNW=", c["ITNW"]), ("NWTN=", c["NWTN"]),
                        ("JAC =", c["JAC"]), ("NUZR=", nuzr)))
        lines.append(f"   0   NPAR={npar:4d}   THL = {_dict_str(c['THL'])}    THU = {_dict_str(c['THU'])}")
        for key in ("UZR", "UZSTOP"):
            if c[key]:
                lines.append(f"   0   {key} = {_dict_str(c[key])}")
        strs = " ".join(f"{k} = '{c[k]}'" for k in ("e", "s", "dat", "sv") if c[k])
        if strs:
            lines.append("   0   " + strs)
        if c["parnames"]:
            lines.append(f"   0   parnames = {c['parnames']}")
        if c["unames"]:
            lines.append(f"   0   unames   = {c['unames']}")
        icp = c["ICP"]
        label = "parameters:" if len(icp) > 1 else "parameter: "
        fmt_icp = "".join(f"{i:>5}" if isinstance(i, int) else f" '{i}'" for i in icp)
        lines.append(f"   0   User-specified {label}      {fmt_icp}")
        lines.append(f"   0   Active continuation {label}  {fmt_icp}")
        if curve_type:
            lines.append(f"   0   Branch type: {curve_type:2d}    TY = '{curve_name:<3}'")
        self._append(self.b_path, "\n".join(lines) + "\n")
        self.column_titles = column_titles

    def branch_start(self) -> None:
        """The two-line column header written at the first point of every branch."""
        titles = "".join(t.ljust(19) for t in self.column_titles)
        self._append(self.b_path, f"   0\n   0    PT  TY  LAB {titles}\n")

    def row(self, r: Row) -> None:
        vals = "".join(fmt_e(v) for v in r.values)
        self._append(self.b_path, f"{r.br:4d}{r.pt:6d}{r.ty:4d}{r.lab:5d}{vals}\n")

    def record(self, rec: Record) -> None:
        self._append(self.s_path, rec.text())

    def diag(self, text: str) -> None:
        self._append(self.d_path, text if text.endswith("\n") else text + "\n")


# ----------------------------------------------------------------------- readers

def read_b(path: Path) -> list[list[Row]]:
    """Branches of a b-file: lists of Rows (header lines skipped)."""
    branches: list[list[Row]] = []
    new = True
    for line in Path(path).read_text().splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "0":
            new = True
            continue
        try:
            br, pt, ty, lab = (int(x) for x in f[:4])
            vals = [float(x.replace("D", "E")) for x in f[4:]]
        except ValueError:
            continue
        if new or not branches:
            branches.append([])
            new = False
        branches[-1].append(Row(br, pt, ty, lab, vals))
    return branches


def read_s(path: Path) -> list[Record]:
    """All records of an s-file (ours or AUTO's)."""
    lines = Path(path).read_text().splitlines()
    out, i = [], 0
    while i < len(lines):
        h = lines[i].split()
        if not h:
            i += 1
            continue
        h = [int(x) for x in h]
        br, ntot, itp, lab, nfpr, isw, ntpl, nar, nrowpr = h[:9]
        ntst = h[9]
        npar = h[11]
        ndim_user = h[13] if len(h) > 13 else nar - 1
        ips = h[14] if len(h) > 14 else 1
        body = lines[i + 1:i + 1 + nrowpr]
        i += 1 + nrowpr
        n = nar - 1
        k = n // 7 + 1                                  # lines of one t-block
        tvals = [float(x) for ln in body[:k * ntpl] for x in ln.split()]
        U = np.array(tvals[1:nar]) if ntpl == 1 else np.array(tvals).reshape(ntpl, nar)[:, 1:]
        rest = body[k * ntpl:]
        icp, rldot, udot = [], [], None
        has_dir = ntst > 0 and nrowpr > (n // 7 + 1) * ntpl + (npar + 6) // 7
        if has_dir:
            nicp = (nfpr + 19) // 20
            icp = [int(x) for ln in rest[:nicp] for x in ln.split()]
            nr = (nfpr + 6) // 7
            rldot = [float(x) for ln in rest[nicp:nicp + nr] for x in ln.split()]
            nu = ((n + 6) // 7) * ntpl
            udot = np.array([float(x) for ln in rest[nicp + nr:nicp + nr + nu] for x in ln.split()])
            rest = rest[nicp + nr + nu:]
        par = np.array([float(x) for ln in rest for x in ln.split()])
        out.append(Record(br, ntot, itp, lab, nfpr, isw, ndim_user, ips, U, par, icp, rldot, udot))
    return out


def find_record(records: list[Record], irs) -> Record:
    """AUTO's FINDLB: a label number, -n for the n-th record, or 'HB2' by type and count."""
    if isinstance(irs, str) and not irs.lstrip("-").isdigit():
        name = irs.rstrip("0123456789")
        count = int(irs[len(name):] or 1)
        hits = [r for r in records if type_name(r.ty) == name.upper()]
        if len(hits) < count:
            raise LookupError(f"IRS='{irs}': the restart file has {len(hits)} {name} point(s)")
        return hits[count - 1]
    irs = int(irs)
    if irs < 0:
        if -irs > len(records):
            raise LookupError(f"IRS={irs}: the restart file has only {len(records)} records")
        return records[-irs - 1]
    for r in records:
        if r.lab == irs:
            return r
    raise LookupError(f"IRS={irs}: no label {irs} in the restart file "
                      f"(labels: {[r.lab for r in records]})")
