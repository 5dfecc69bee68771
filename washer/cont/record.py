"""One point of a run as AUTO writes it (a b-row and its s-record), in memory: the one
record type of the engine's results (washer.cont.branch.Branch.rows) and of the
records read from s-files (washer.auto.files.read_s)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from washer.cont.codes import find, split_code, type_name


@dataclass
class Record:
    """One point of a run as AUTO writes it, in memory: the b-row and the s-record's
    content. The engine's results (`Branch.rows`) and the records read from s-files
    (`washer.auto.files.read_s`) are this one type, so either restarts a run.

    br, pt, lab : branch, point number (1-based, unsigned), label (0 = none).
    code : the written type code (two-digit on ISW = 2 curves); `ty` is its name.
    nfpr, isw, ndim_user, ips : the s-record header's NFPR, ISW, user NDIM, IPS.
    u : the stored state: (NSTATE,) for algebraic problems (extended on the loci:
        2 NDIM + 1 on fold curves, 2 NDIM + 2 on Hopf curves) or (NTPL, n) mesh values
        of a BVP; `U` is the user's part of it.
    par : (NPAR,) PAR(1..NPAR), PAR(11) the period.
    icp, rldot, udot : the free parameters, d PAR(icp)/ds and the state's direction
        (udot None when no direction is stored).
    t, ntst, ncol : the mesh times (NTPL,) and the mesh of a BVP record (None, 0, 0
        for algebraic ones).
    values : the b-row's values: PAR(ICP(1)), the columns, the other free parameters.
    stable : sign of PT (True -> written negative); None = not defined.
    stability : eigenvalues or multipliers (washer.cont.system.Stability) or None.
    info : extra results (first Lyapunov coefficient 'l1' at HB, its criticality).
    npari : AUTO's NPARI (s-record field 13): how many of the last PAR are a locus'
        internal unknowns (AUTO reads the user's NPAR as NPAR - NPARI on a restart).
    """
    br: int
    pt: int
    code: int
    lab: int
    nfpr: int
    isw: int
    ndim_user: int
    ips: int
    u: np.ndarray
    par: np.ndarray
    icp: list = field(default_factory=list)
    rldot: list = field(default_factory=list)
    udot: np.ndarray | None = None
    t: np.ndarray | None = None
    ntst: int = 0
    ncol: int = 0
    values: list = field(default_factory=list)
    stable: bool | None = None
    stability: object = None                     # washer.cont.system.Stability
    info: dict = field(default_factory=dict)
    npari: int = 0

    @property
    def ty(self) -> str:
        """The type's name: 'HB', 'UZ', 'GH', ... ('' for unlabelled points)."""
        return type_name(self.code)

    @property
    def curve_type(self) -> int:
        """AUTO's ITPST of the curve the point lies on, carried by its written code:
        0 on ordinary branches, 2 fold, 3 Hopf, 5/7/8 loci of cycles."""
        return split_code(self.code)[1]

    @property
    def U(self) -> np.ndarray:
        """The user's state: the first NDIM stored values of an algebraic point, the
        whole profile of a BVP."""
        u = np.asarray(self.u)
        n = self.ndim_user or len(u)
        return u[:n] if u.ndim == 1 else u

    def __getitem__(self, key):
        return {"TY": self.ty, "LAB": self.lab, "BR": self.br, "PT": self.pt,
                "TY number": self.code}[key]

    def __repr__(self) -> str:
        """One line (a periodic record holds thousands of mesh values)."""
        name = f"{self.ty}{self.lab}" if self.lab else "point"
        free = ", ".join(f"PAR({i})={self.par[i - 1]:.6g}" for i in self.icp[:3]
                         if 0 < i <= len(self.par))
        u = np.asarray(self.U)
        shape = f"U{list(u.shape)}" if u.ndim > 1 else \
            "U=[" + ", ".join(f"{v:.6g}" for v in u[:4]) + (", ...]" if len(u) > 4 else "]")
        return f"<Record {name}: BR {self.br} PT {self.pt}; {free + '; ' if free else ''}{shape}>"


def find_record(records: list[Record], irs) -> Record:
    """AUTO's FINDLB on s-file records: a label number, -n for the n-th record, or
    'HB2' by type and count (codes.find). Raises LookupError naming what the file holds."""
    try:
        rec = find(records, irs, code=lambda r: r.code)
    except LookupError as exc:
        damaged = getattr(records, "damaged", [])
        extra = f" (a damaged record at the end was left out: {damaged[0]})" if damaged else ""
        raise LookupError(f"IRS={irs!r}: {exc} in the restart file{extra}") from None
    # Periodic solutions only: a general BVP (IPS = 4), a map's or a time integration's
    # record (IPS = -1, -2: NTST = 1 marks a stored direction) need no period.
    if rec.ntst > 0 and rec.ncol > 0 and len(rec.par) >= 11 and rec.ips in (2, 12):
        period = float(rec.par[10])
        if not (math.isfinite(period) and period > 0):
            lines = getattr(records, "header_lines", {})
            where = lines.get(id(rec), "the restart file")
            raise LookupError(f"{where}: IRS={irs!r}: the record's PAR(11) (the period) is "
                              f"{period!r}: expected a positive period; this record cannot "
                              "start a run")
    return rec


class ColumnTitle(str):
    """A b-file column title at a fixed column of its 19-character field (HEADNG's
    WRITECOL(I, ...)) where a name would otherwise be centred: a state's name as the
    IPLT column of an algebraic problem (column 2)."""

    def __new__(cls, text: str, column: int):
        obj = super().__new__(cls, text)
        obj.column = column
        return obj
