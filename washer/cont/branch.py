"""Continuation results in memory: points, labelled points, branches.

A `Branch` is what one run computed, independent of files: it can be saved to
AUTO's b./s./d. files (`washer.cont.sinks`), restarted from (its labelled
points carry the stored solution and direction, like s-file records), and
pickled.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from washer.auto.codes import find, split_code, type_name
from washer.cont.system import Solution, Stability


@dataclass
class Point:
    """A converged point of a continued system.

    x : (N + 1,) unknowns, principal parameter last. tangent : (N + 1,) unit
    direction in the system's inner product, oriented along the branch.
    stability : spectrum or None. tests : {base code: value} of the test
    functions at x. ds : the step that reached the point. iterations : Newton
    iterations of that step.
    """
    x: np.ndarray
    tangent: np.ndarray
    stability: Stability | None = None
    tests: dict = field(default_factory=dict)
    ds: float = 0.0
    iterations: int = 0

    @property
    def lam(self) -> float:
        return float(self.x[-1])


@dataclass
class Labelled:
    """A point as AUTO writes it: b-row fields plus the s-record's content.

    br, pt, lab : branch, point number (1-based, unsigned), label (0 = none).
    code : the written type code (two-digit on ISW = 2 curves).
    stable : sign of PT (True -> written negative); None = not defined.
    solution : the system's Solution (par, columns, stored state, direction).
    info : extra results (first Lyapunov coefficient at HB, notes).
    """
    br: int
    pt: int
    code: int
    lab: int
    stable: bool | None
    solution: Solution
    stability: Stability | None = None
    info: dict = field(default_factory=dict)
    free: tuple = ()
    isw: int = 1
    ips: int = 1

    @property
    def ty(self) -> str:
        return type_name(self.code)

    @property
    def curve_type(self) -> int:
        """AUTO's ITPST of the curve the point lies on (0 on ordinary branches)."""
        return split_code(self.code)[1]

    @property
    def par(self) -> np.ndarray:
        return self.solution.par

    @property
    def U(self) -> np.ndarray:
        """The user's state (first NDIM stored unknowns of an algebraic point)."""
        u = self.solution.u
        n = self.solution.ndim_user or len(u)
        return u[:n] if u.ndim == 1 else u

    @property
    def columns(self) -> list:
        return self.solution.columns

    def __getitem__(self, key):
        return {"TY": self.ty, "LAB": self.lab, "BR": self.br, "PT": self.pt,
                "TY number": self.code}[key]


@dataclass
class Branch:
    """The points of one run, in the order written (all branches of the run,
    including those reached by branch switching), and its labelled points."""
    rows: list = field(default_factory=list)        # every Labelled point (lab 0 included)
    status: str = "ok"
    elapsed: float = 0.0

    @property
    def specials(self) -> list:
        return [r for r in self.rows if r.lab]

    def __call__(self, key):
        """r('HB1'), r('LP'), r(3), r(-1): a labelled point by type (and count), label
        or position, as AUTO's FINDLB (washer.auto.codes.find)."""
        try:
            return find(self.specials, key, code=lambda r: r.code)
        except LookupError as exc:
            raise KeyError(str(exc)) from None
