"""The contract between the continuation iterator and what it continues.

A *continued system* is a nonlinear system G(x) = 0 with N equations in N + 1
unknowns x = (state unknowns, free parameter(s)); the iterator adds the
arclength condition. Equilibria (AUTO's FUNI), the fold and Hopf loci (FNLP,
FNHB), periodic orbits (FNPS + collocation) are all continued systems: each
lives in `washer.cont.systems` and is found through `SYSTEMS`, keyed by AUTO's
(IPS, ISW, start kind). The iterator knows nothing else about them.

The unknown vector x always ends with the principal continuation parameter
PAR(ICP(1)) (AUTO's RL(1)); what comes before it is the system's business
(x, v, kappa, PAR(ICP(2)) on a Hopf curve; mesh values and the period on a
periodic branch).

Fields and methods, in the manner of scipy's OdeSolver contract:

Attributes
----------
n_eq : int
    N, the number of equations (the length of x is N + 1).
curve_type : int
    AUTO's ITPST: 0 on ordinary branches, 2 on fold curves, 3 on Hopf curves,
    5/7/8 on loci of cycle folds / period doublings / tori. Written codes are
    `codes.curve_code(base, curve_type)`.
arclength : str
    "sphere": AUTO's algebraic corrector (SOLVAE), |x - x_old|_theta^2 = ds^2,
    full Newton, one hidden first step. "plane": the BVP corrector (SOLVBV),
    <x - x_old, xdot_old>_theta = ds, Newton-chord (NWTN), no hidden step.
free : list[int]
    The free parameters, 1-based PAR indices, principal first (AUTO's ICP(1..NFPR)).
freezes_second_derivatives : bool
    True when `jacobian(x, frozen_second=True)` may reuse the second-derivative
    blocks of the last full evaluation (loci whose Jacobians hold f_uu terms): the
    corrector then asks for that inexact Newton matrix (the residual stays exact, so
    the point converged to is the same); tangents and tests use full evaluations.

Methods
-------
residual(x) -> ndarray (N,)
jacobian(x) -> ndarray (N, N + 1) or a scipy.sparse matrix of that shape
    dG/dx. Built from the problem's Jacobians or finite differences (JAC = 0).
    Systems with `freezes_second_derivatives` also take `frozen_second=True`.
factor(J, border) -> Factor
    A factorisation of the square matrix [J; border] (border: (N + 1,) row) with
    `.solve(rhs) -> (N + 1,)` and `.sign_logdet() -> (sign, log|det|)` (AUTO's BP
    test on algebraic branches is this determinant). `washer.cont.linalg.dense_factor`
    is the default; collocation systems supply a structured one.
inner(a, b) -> float
    AUTO's weighted inner product of two unknown vectors (THU on the state,
    THL on the parameters; integrals over [0, 1] for periodic orbits). The
    tangent is unit in this norm, so DS is in its units.
border(t) -> ndarray (N + 1,)
    The row r with r @ a == inner(a, t) for every a: the iterator borders J
    with it (pseudo-arclength row, tangent solves).
params(x) -> ndarray (NPAR,)
    The full PAR vector at x (free parameters set, PAR(11) the period where
    defined, and the user's `pvls(u, par)` applied): UZR/UZSTOP test values
    PAR(i) - value are read from it.
start() -> (x0, tangent0 or None)
    The starting point and, when the start data fix it (a stored direction, the
    Hopf eigenvector of STHOPF, a branch-switching direction), its direction.
    None lets the iterator compute the tangent (null vector of J, PAR(ICP(1))-dot > 0).
stability(x, J) -> Stability or None
    Eigenvalues (IPS = 1) or Floquet multipliers (IPS = 2) and the stable count
    (AUTO's NINS); None where stability is not defined (IPS = 0, ISW = 2 curves).
active_tests() -> list[int]
    Base codes of the test functions this system evaluates under the run's
    ILP/ISP/SP settings (UZ tests are added by the iterator).
test_functions(x, tangent, J, stability, factor, codes) -> dict[int, float | None]
    Values of the test functions `codes` (a subset of active_tests(); during
    location only the one being located is asked for, so expensive ones such
    as the first Lyapunov coefficient are not evaluated needlessly), keyed by
    base code (Code.LP, Code.BP, Code.HB, Code.BT, ...). Pure: no state is
    changed. None: undefined here. `factor` factorises [J; border(secant)].
accept(code, prev, cur) -> bool
    AUTO's acceptance rule for a sign change of test `code` between two points
    (`prev`, `cur`: `washer.cont.branch.Point`): e.g. HB only if the stable count
    changed by >= 2, PD/TR only if it changed at all.
update(x, tangent) -> None
    Called once per accepted point: move reference data that the residual uses
    (the old Hopf eigenvector, the previous orbit of the phase condition).
solution(x, tangent) -> Solution
    What the sinks write: the full PAR vector, b-file columns, the stored state
    and direction for an s-record.
column_titles() -> list[str]
    Titles of `Solution.columns` (after PAR(ICP(1))): 'L2-NORM', 'U(1)', or 'MAX U(1)'.
directions(x, tangent, code) -> list[ndarray]
    Directions of the other branch(es) at a located branch point (BP switching).
    Empty if the system cannot switch there.
located_code(key, point) -> int
    The base code a located zero of test `key` is written with (the key itself except
    where one test stands for several kinds: the combined PD/TR test of cycles is typed
    at the located point).
info(x, code) -> dict
    Extra results at a located special point of base code `code` (the first
    Lyapunov coefficient 'l1' at HB); {} where there are none.
wants_remesh(n_points) -> bool, remesh(x, *vectors) -> tuple[ndarray, ...]
    Mesh adaptation (AUTO's ADAPT every IAD points, BVPs): after the n-th written
    point the iterator asks `wants_remesh(n)` and, if so, replaces the point and its
    tangent by `remesh(x, tangent)` (both moved onto the new mesh; the system moves
    its own reference data). Systems without a mesh answer False
    (`washer.cont.systems.bvp.CollocationBVP` is the base of those with one).

Optional attributes (read with a default where a system lacks them)
--------------------------------------------------------------------
run_settings : Settings
    The settings the run uses instead of the constants' (default: those): a locus'
    generating run (NMX 5, no tests) or a system with its own NDIM (IPS = 5).
start_mode : str
    How the iterator starts: "fresh" or "switch" (default: "switch" at a BP with
    ISW = -1 on algebraic systems, else "fresh").
n_state : int
    How many leading unknowns are the state, on "plane" systems (AUTO's NEWTONBV test:
    EPSU on them, EPSL on each free parameter); without it, EPSU on every unknown but
    PAR(ICP(1)) and EPSL on that one.
null_vector(J, border) -> ndarray
    With n_state, the tangent at a start from the Jacobian's own null vector (AUTO's
    STDRBV) instead of a bordered solve.
newton_jacobian_at_point : bool
    True: at a continuation step's converged point the Jacobian of the corrector's last
    Newton iteration serves as the Jacobian there (tangent, stability, tests: AUTO's
    NEWTONBV), where that iteration evaluated it at the iterate the converging
    correction started from; default False, the Jacobian is evaluated at the point
    (collocation systems: True, `washer.cont.systems.bvp.CollocationBVP`).
newton_jacobian_serves(stability) -> bool
    With newton_jacobian_at_point, whether the stability that matrix gives is exact
    enough to stand for the point's; False: the Jacobian is evaluated at the point
    (default: always True; periodic orbits: `floquet.newton_jacobian_serves`).
header_icp : list[int]
    The free parameters the b-file header and the s-record list (AUTO's NFPR, ICP),
    where a locus counts an internal one (the cycle fold's beta); default `free`.
header_npar : int
    NPAR as the b-file header states it (default: the settings' NPAR).
npari : int
    AUTO's NPARI (s-record field 13): how many of the last PAR are the system's
    internal unknowns (default 0).
n_comp, coll, nbc, nint
    A collocation system's own NDIM, its Collocation, NBC and NINT, which the b-file
    header states (washer.auto.sinks).
leaving_direction(x, direction, key, same) -> ndarray or None
    The unit direction on from a point located on test `key` (with the tests `same`
    vanishing there too) where the default, the secant, is no guide (the torus locus at
    R1 / R2); None: the secant.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Protocol

import numpy as np

from washer.cont.linalg import Factor


def fold_test(tangent) -> float | None:
    """The fold test of every continued system (AUTO's FNLPAE, FNLPBV): the component of
    the unit tangent along the first continuation parameter, which the systems keep as
    their last unknown; None before there is a tangent."""
    return None if tangent is None else float(tangent[-1])


def determinant_test(factor: Factor) -> float:
    """The branch-point test of the algebraic systems (AUTO's FNBPAE): the determinant of
    the Newton matrix [G_x; border] from its factorisation, sign * exp(log|det|) with
    log|det| capped at 700 (exp(700) ~ 1e304: a large det stays finite)."""
    return determinant_value(*factor.sign_logdet())


def determinant_value(sign: float, logdet: float) -> float:
    """determinant_test's value from the determinant's sign and log|det|."""
    return float(sign * np.exp(min(logdet, 700.0))) if sign != 0 else 0.0


@dataclass
class Stability:
    """Spectrum at a point: `values` are eigenvalues (IPS = 1, sorted by
    decreasing real part) or Floquet multipliers (IPS = 2, the one closest to 1
    first); `n_stable` is AUTO's NINS; `stable` is the sign of PT in the b-file;
    `neutral` the real part up to which an eigenvalue counted as stable in n_stable
    (0, or AUTO's tolerance where f_u looks conservative: systems.equilibrium)."""
    values: np.ndarray
    n_stable: int
    stable: bool
    kind: str = "eigenvalues"           # or "multipliers"
    neutral: float = 0.0
    notes: list[str] = field(default_factory=list)   # e.g. "Multiplier inaccurate"


@dataclass
class Solution:
    """One point as the output files see it.

    par : (NPAR,) full parameter vector, PAR(i) = par[i - 1], PAR(11) the period.
    columns : b-file values after PAR(ICP(1)): measure (L2-NORM), then U(1..N2)
        for algebraic problems or MAX U(i) for BVPs (`column_titles` names them).
    u : stored state for the s-record: (NSTATE,) algebraic (extended on loci) or
        (NTPL, NDIM) mesh values of a periodic orbit.
    t : (NTPL,) mesh times in [0, 1] of a BVP record, None for algebraic ones.
    udot, rldot : the direction in the same layouts, and d PAR(free)/ds.
    ntst, ncol : the s-record header's NTST/NCOL of a BVP (0, 0 for algebraic).
    ndim_user : the user's NDIM (s-record field 14).
    """
    par: np.ndarray
    columns: list
    u: np.ndarray
    t: np.ndarray | None = None
    udot: np.ndarray | None = None
    rldot: list = field(default_factory=list)
    ntst: int = 0
    ncol: int = 0
    ndim_user: int = 0


class ContinuedSystem(Protocol):
    n_eq: int
    curve_type: int
    arclength: str
    free: list
    freezes_second_derivatives: bool

    def residual(self, x: np.ndarray) -> np.ndarray: ...
    def jacobian(self, x: np.ndarray): ...
    def factor(self, J, border: np.ndarray) -> Factor: ...
    def inner(self, a: np.ndarray, b: np.ndarray) -> float: ...
    def border(self, t: np.ndarray) -> np.ndarray: ...
    def params(self, x: np.ndarray) -> np.ndarray: ...
    def start(self) -> tuple[np.ndarray, np.ndarray | None]: ...
    def stability(self, x: np.ndarray, J) -> Stability | None: ...
    def active_tests(self) -> list: ...
    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict: ...
    def accept(self, code: int, prev, cur) -> bool: ...
    def update(self, x: np.ndarray, tangent: np.ndarray) -> None: ...
    def solution(self, x: np.ndarray, tangent: np.ndarray) -> Solution: ...
    def column_titles(self) -> list: ...
    def directions(self, x: np.ndarray, tangent: np.ndarray, code: int) -> list: ...
    def located_code(self, key, point) -> int: ...
    def info(self, x: np.ndarray, code: int) -> dict: ...
    def wants_remesh(self, n_points: int) -> bool: ...
    def remesh(self, x: np.ndarray, *vectors: np.ndarray) -> tuple: ...


@dataclass
class StartData:
    """What a system is built from: the user's problem, the resolved settings,
    the start state and parameters, and the restart record if any.

    u : (NDIM,) start state (IRS = 0 or an algebraic record), or the stored
        (extended) state of the record. par : (NPAR,) full parameter vector.
    record : the s-file record restarted from (washer.cont.record.Record) or None.
    kind : the start kind, AUTO's type name of the record ('EP', 'HB', 'LP',
        'BP', 'PD', ...; '' for a regular point or IRS = 0).
    data : (t (m,), U (m, NDIM)) time-column start data of dat='NAME' (AUTO's STPNUB
        reading fort.3) for a BVP started with IRS = 0, else None.
    """
    problem: object
    settings: object
    u: np.ndarray
    par: np.ndarray
    record: object = None
    kind: str = ""
    unames: dict = field(default_factory=dict)     # {U index: name} for column titles
    data: tuple | None = None


#: (IPS, ISW, start kind) -> constructor(StartData) -> ContinuedSystem. '*' matches
#: any start kind. Filled by the modules of washer.cont.systems at import.
SYSTEMS: dict[tuple[int, int, str], Callable] = {}


def register(ips: int, isw: int, kind: str = "*"):
    """Class decorator: `@register(1, 2, 'HB')` makes the class the system for
    IPS = 1, ISW = 2 restarts at HB labels."""
    def deco(cls):
        SYSTEMS[(ips, isw, kind)] = cls
        return cls
    return deco


def lookup(ips: int, isw: int, kind: str):
    """The constructor for (IPS, ISW, start kind), or a KeyError naming what exists."""
    for key in ((ips, isw, kind), (ips, isw, "*")):
        if key in SYSTEMS:
            return SYSTEMS[key]
    # What exists for this IPS (the whole registry is a page long).
    same = sorted(((w, k) for i, w, k in SYSTEMS if i == ips), key=str)
    known = ", ".join(f"ISW={w} from {'any point' if k == '*' else k}" for w, k in same) \
        or "none"
    raise KeyError(f"no continued system for IPS={ips}, ISW={isw} starting at "
                   f"'{kind or 'a regular point'}' (with IPS={ips}: {known})")
