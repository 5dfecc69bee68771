"""Continuation results in memory: points, records (b-rows with their s-record), branches.

A `Branch` is what one run computed, independent of files: it can be saved to
AUTO's b./s./d. files (`washer.auto.sinks`), restarted from (its labelled
points carry the stored solution and direction, like s-file records), and
pickled.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from washer.cont.codes import find
from washer.cont.constants import par_name_index
from washer.cont.record import Record  # noqa: F401  (the rows of a Branch)
from washer.cont.system import Stability


@dataclass
class Counters:
    """Work done on a branch, as scipy's solvers keep nfev/njev/nlu: evaluations of
    the system's residual G(x) (each one evaluates f at every collocation point of a
    BVP), of its Jacobian, and factorisations of the bordered Newton matrix."""
    residuals: int = 0
    jacobians: int = 0
    factorisations: int = 0

    def add(self, other: "Counters") -> None:
        self.residuals += other.residuals
        self.jacobians += other.jacobians
        self.factorisations += other.factorisations


@dataclass(slots=True)
class Point:
    """A converged point of a continued system.

    x : (N + 1,) unknowns, principal parameter last. tangent : (N + 1,) unit
    direction in the system's inner product, oriented along the branch.
    stability : spectrum or None. tests : {base code: value} of the test
    functions at x. ds : the step that reached the point. iterations : Newton
    iterations of that step. direction : the predictor's direction and the
    arclength plane's normal for the step from this point where it is not the
    tangent: on BVP branches the unit secant of the step that reached the point
    (AUTO's CONTBV), on algebraic ones that step's secant (x - x_old) / ds
    (SOLVAE's UDOT, not the arclength's normal there); None means the tangent.
    across_jump : the point was located beyond a jump of the branch (a user value
    crossed by Newton leaving for another sheet of solutions, `events.first_zero`): its
    direction is the location's last step on that sheet, kept as it is even where it
    points back against the previous point's.
    """
    x: np.ndarray
    tangent: np.ndarray
    stability: Stability | None = None
    tests: dict = field(default_factory=dict)
    ds: float = 0.0
    iterations: int = 0
    direction: np.ndarray | None = None
    across_jump: bool = False

    @property
    def step_direction(self) -> np.ndarray:
        return self.tangent if self.direction is None else self.direction

    @property
    def lam(self) -> float:
        return float(self.x[-1])


@dataclass
class Branch:
    """The points of one run, in the order written (all branches of the run,
    including those reached by branch switching), and its labelled points.

    As AUTO's CLUI and pandas users expect it:
        print(branch)           AUTO's table of labelled points (BR PT TY LAB and columns)
        branch('HB1')           a labelled point (Record) by type and count, label or position
        branch['B'], branch['PAR(3)'], branch['L2-NORM']
                                one value per point (ndarray): a parameter or state by name
                                (parnames, unames) or index, or a b-file column by title
        branch.to_dataframe()   one row per point: BR, PT, TY, LAB, stable, the b-file
                                columns by name, every named parameter; units in .attrs
    """
    rows: list = field(default_factory=list)        # every Record (lab 0 included)
    status: str = "ok"
    #: False when the run failed before its first point (the equations failing at the
    #: start, the start's Newton not converging): AUTO's run that ends in an error,
    #: unlike a branch that ends at MX.
    started: bool = True
    elapsed: float = 0.0
    counters: Counters = field(default_factory=Counters)    # summed over the branches
    #: The b-file's column titles of `Record.values` (PAR(ICP(1)) or its name, the
    #: system's columns, the other free parameters); names of PAR and U indices; units
    #: by name (where the problem states them).
    titles: list = field(default_factory=list)
    parnames: dict = field(default_factory=dict)
    unames: dict = field(default_factory=dict)
    units: dict = field(default_factory=dict)

    @property
    def specials(self) -> list:
        return [r for r in self.rows if r.lab]

    # ------------------------------------------------------------ reading it
    def __len__(self) -> int:
        return len(self.rows)

    def __repr__(self) -> str:
        kinds: dict[str, int] = {}
        for r in self.specials:
            kinds[r.ty] = kinds.get(r.ty, 0) + 1
        found = ", ".join(f"{n} {k}" for k, n in kinds.items()) or "none"
        return (f"<Branch: {len(self.rows)} points, labelled: {found}; status {self.status!r}"
                f"{'; columns ' + ', '.join(self.titles) if self.titles else ''}>")

    def __str__(self) -> str:
        """AUTO's table of labelled points (the screen format: I4, I6, A3, I5, ES14.5)."""
        titles = self.titles or [f"column {i + 1}" for i in range(
            max((len(r.values) for r in self.rows), default=0))]
        head = "  BR    PT  TY  LAB" + "".join(f"{t[:13]:>14}" for t in titles)
        lines = [head]
        for r in self.specials:
            pt = (r.pt - 1) % 9999 + 1
            lines.append(f"{r.br:4d}{pt:6d} {r.ty:>3}{r.lab:5d}"
                         + "".join(f"{v:14.5E}" for v in r.values))
        if not self.specials:
            lines.append("  (no labelled points)")
        lines.append(f"{len(self.rows)} points; status: {self.status}")
        return "\n".join(lines)

    def _index(self, names: dict, key: str) -> int | None:
        for i, n in names.items():
            if n == key:
                return int(i)
        return None

    def __getitem__(self, key) -> np.ndarray:
        """One value per point: branch['B'] (a parameter by name: PAR of every point),
        branch['x'] (a state by name: U of every point; the mesh profile of a BVP
        point is (NTPL,) so the result is (npoints, NTPL)), branch['PAR(3)'],
        branch['3'] (PAR(3), as ICP = ['3'] reads it), branch['U(1)'], branch['PERIOD'],
        or a b-file column by title
        ('L2-NORM', 'MAX U(1)', ...)."""
        if not isinstance(key, str):
            raise TypeError(f"branch[{key!r}]: index with a name ('B', 'PAR(1)', "
                            "'L2-NORM'); rows are branch.rows, labelled points branch('HB1')")
        i = par_name_index(key, self.parnames)
        if i is not None and i > 0:
            return np.array([r.par[i - 1] if len(r.par) >= i else np.nan for r in self.rows])
        j = self._index(self.unames, key)
        if j is None and key.startswith("U(") and key.endswith(")") and key[2:-1].isdigit():
            j = int(key[2:-1])
        if j is not None and key not in self.titles:
            cols = [np.asarray(r.U) for r in self.rows]
            return np.array([c[j - 1] if c.ndim == 1 else c[:, j - 1] for c in cols])
        if key in self.titles:
            k = self.titles.index(key)
            return np.array([r.values[k] for r in self.rows])
        known = sorted(set(map(str, self.parnames.values())) | set(map(str, self.unames.values()))
                       | set(self.titles))
        raise KeyError(f"{key!r}: not a parameter, state or column of this branch "
                       f"(known: {', '.join(known)}; or PAR(i), U(i))")

    def to_dataframe(self):
        """A pandas DataFrame, one row per point: BR, PT, TY (categorical: '' for
        unlabelled points, 'HB', 'LP', ...), LAB, stable (bool, NaN where undefined),
        the b-file's columns by their titles, then every named parameter not among
        them. `df.attrs['units']` gives the unit of each column where known."""
        import pandas as pd
        data = {"BR": [r.br for r in self.rows], "PT": [r.pt for r in self.rows],
                "TY": pd.Categorical([r.ty for r in self.rows]),
                "LAB": [r.lab for r in self.rows],
                "stable": pd.array([r.stable for r in self.rows], dtype="boolean")}
        for k, t in enumerate(self.titles):
            data[t] = [r.values[k] if k < len(r.values) else np.nan for r in self.rows]
        for i, n in sorted((int(i), n) for i, n in self.parnames.items()):
            if n not in data:
                data[n] = self[n]
        df = pd.DataFrame(data)
        df.attrs["units"] = {c: self.units[c] for c in df.columns if c in self.units}
        return df

    def __call__(self, key):
        """r('HB1'), r('LP'), r(3), r(-1): a labelled point by type (and count), label
        or position, as AUTO's FINDLB (washer.cont.codes.find)."""
        try:
            return find(self.specials, key, code=lambda r: r.code)
        except LookupError as exc:
            raise KeyError(str(exc)) from None
