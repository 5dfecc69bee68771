"""Invariant circles of maps as a continued system: the family born at a Neimark-Sacker
(TR) point of a map x -> F(x, p), continued in p by the engine's iterator.

The circle's mathematics (Fourier collocation at N nodes, the invariance equation
F(x(theta), p) = x(theta + 2 pi rho) with its phase condition, the normal multipliers) is
`washer.cont.invariant_circle`; this module makes it a `ContinuedSystem`:

    unknowns   x = (X.ravel() (N n,), rho, PAR(ICP(1)))         (N n + 2,)
    equations  G(x) = invariance at the N nodes, phase condition  (N n + 1,)

with AUTO's BVP corrector (arclength "plane": <x - x_old, t_old> = ds, Newton with the
matrix refactorised every iteration when NWTN = ITNW), the inner product of the circles
(node values averaged over the circle, per-component scales; rho and p as they are),
the phase condition's reference moved to every accepted circle (`update`, as the
previous orbit of a periodic branch), and the normal moduli as stability (`Stability`
with kind "multipliers": values the distinct normal moduli, decreasing; `tangent` the
tangent direction's modulus). The run (`continue_circles`) is `runner.execute` with
constants like any other: UZSTOP at the end value, NMX, EP/MX, sinks for b-/s-/d-files.

Written points: the b-row's columns after PAR(ICP(1)) are AMPLITUDE (the mode-1 Fourier
amplitude, 2-norm over components: the radius of a round circle), ROTATION (rho, turns
per iterate) and MU_MAX (the largest normal modulus); the s-record stores the circle as
a closed profile of N + 1 points at t = theta / 2 pi (NTST = N, NCOL = 1), the last the
first again, so that any periodic-orbit plotter draws it. Records carry their own curve
type (`CURVE_TYPE`): EP 99, UZ -94, MX -99.

The map enters only as `fmap(X (N, n), p) -> (F (N, n), DF (N, n, n), Fp (N, n))`
(`washer.cont.invariant_circle`); an error of fmap where it is not defined (a parameter
out of range: ValueError, RuntimeError, ArithmeticError) is a `ProblemError`, so the
iterator halves the step as for any failed trial point.
"""
from __future__ import annotations

import math

import numpy as np

from washer.cont.constants import Constants
from washer.cont import invariant_circle as ic
from washer.cont.branch import Branch, Record
from washer.cont.problem import ProblemError
from washer.cont.settings import Settings
from washer.cont.system import Solution, Stability
from washer.cont.systems._algebraic import AlgebraicSystem

#: AUTO's ITPST of a family of invariant circles (none in AUTO: 1-8 are taken by the loci
#: of special points; written codes are `codes.curve_code(base, CURVE_TYPE)`).
CURVE_TYPE = 9
#: b-file titles of the columns after PAR(ICP(1)).
COLUMNS = ["AMPLITUDE", "ROTATION", "MU_MAX"]
#: Newton's tolerance (EPSL = EPSU: relative corrections). The map is evaluated with an
#: error of ~1e-10 (the washer's flow at rtol 1e-10); asking less would chase noise.
NEWTON_TOL = 1e-9
#: Newton iterations per step (ITNW = NWTN: the matrix is refactorised every iteration).
NEWTON_MAX_ITER = 10
#: Location tolerance (EPSS) of the end value in arclength.
EPS_LOCATE = 1e-10


class InvariantCircles(AlgebraicSystem):
    """The invariance equation at N nodes with its phase condition, in the unknowns
    x = (X, rho, PAR(ICP(1))) (`washer.cont.system.ContinuedSystem`). From the algebraic
    systems it takes the weighted inner product (weights `theta`), dense linear algebra
    and the defaults of a system without mesh, switching or extra results; its corrector
    is the BVPs' (a plane), its tests the UZ values only.

    fmap : the map and its derivatives at N points (module docstring).
    first : `invariant_circle.Circle`, the start (used as given: a BVP start is not
        corrected). settings : the run's `Settings` (ICP(1) the parameter fmap's p is).
    par : (NPAR,) the fixed parameters written to the records (PAR(ICP(1)) = p).
    scale : (n,) typical size of each component (default 1) for the inner product.
    direction : +1 / -1: the start's tangent moves p up / down (default: towards the
        first UZSTOP value, else up).
    """
    arclength = "plane"
    curve_type = CURVE_TYPE
    freezes_second_derivatives = False

    def __init__(self, fmap, first: ic.Circle, settings: Settings, par=None, scale=None,
                 direction: float | None = None):
        self.fmap, self.settings = fmap, settings
        self.N, self.n = first.X.shape
        self.n_eq = self.N * self.n + 1
        self.free = [settings.ICP[0]]
        self.par = np.zeros(settings.NPAR) if par is None else np.array(par, dtype=float)
        sc = np.ones(self.n) if scale is None else np.asarray(scale, dtype=float)
        # Node values averaged over the circle (1/N each, per-component scales); rho and
        # p as they are.
        self.theta = np.r_[np.tile(1.0 / sc ** 2, self.N) / self.N, 1.0, 1.0]
        self.equation = ic.InvarianceEquation(self._checked_map, self.N, self.n, first.X)
        self._x0 = np.r_[first.X.ravel(), first.rho, first.p]
        if direction is None:
            stops = [v - first.p for i, v, stop in settings.UZR if stop and i == self.free[0]]
            direction = math.copysign(1.0, stops[0]) if stops and stops[0] != 0 else 1.0
        self.direction = direction
        self._last = None

    # ------------------------------------------------------------------ the map
    def _checked_map(self, X, p):
        """fmap at (X, p), the last one kept (residual and Jacobian of one iterate, the
        multipliers of a converged circle: one evaluation); failures are ProblemErrors."""
        key = np.r_[X.ravel(), p]
        if self._last is None or not np.array_equal(self._last[0], key):
            try:
                out = self.fmap(X, p)
            except (ValueError, RuntimeError, ArithmeticError) as exc:
                raise ProblemError(f"invariant circle: the map failed at p = {p:.6g} "
                                   f"({type(exc).__name__}: {exc})") from exc
            if not all(np.all(np.isfinite(a)) for a in out):
                raise ProblemError(f"invariant circle: the map is not finite at p = {p:.6g}")
            self._last = (key, out)
        return self._last[1]

    def circle(self, x) -> ic.Circle:
        """The unknowns as a Circle (no multipliers)."""
        X, rho, p = self.equation.split(np.asarray(x, dtype=float))
        return ic.Circle(X.copy(), rho, p)

    # ------------------------------------------------------------------ contract
    def start(self):
        """The first circle and the null vector of dG/dx there, p moving in `direction`."""
        x0 = self._x0.copy()
        t = np.linalg.svd(self.jacobian(x0))[2][-1]
        if t[-1] * self.direction < 0:
            t = -t
        return x0, t / math.sqrt(self.inner(t, t))

    def residual(self, x) -> np.ndarray:
        return self.equation.residual_jacobian(np.asarray(x, dtype=float))[0]

    def jacobian(self, x) -> np.ndarray:
        return self.equation.residual_jacobian(np.asarray(x, dtype=float))[1]

    def params(self, x) -> np.ndarray:
        p = self.par.copy()
        p[self.free[0] - 1] = x[-1]
        return p

    def stability(self, x, J) -> Stability:
        """The normal moduli (Jorba's generalised eigenproblem, `normal_moduli`): values
        the distinct moduli, decreasing; n_stable those below 1; `tangent` the tangent
        direction's modulus (1 up to discretisation)."""
        X, rho, p = self.equation.split(np.asarray(x, dtype=float))
        _, DF, _ = self._checked_map(X, p)
        moduli, tangent, _ = ic.normal_moduli(X, rho, DF)
        n_stable = int(np.sum(moduli < 1.0))
        st = Stability(values=moduli, n_stable=n_stable, stable=n_stable == moduli.size,
                       kind="multipliers")
        st.tangent = tangent
        return st

    def active_tests(self) -> list:
        return []               # UZ values only (the iterator adds them)

    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict:
        return {}

    def update(self, x, tangent) -> None:
        """The phase condition's reference moves to the accepted circle."""
        self.equation.set_reference(self.equation.split(np.asarray(x, dtype=float))[0])

    def solution(self, x, tangent) -> Solution:
        X, rho, p = self.equation.split(np.asarray(x, dtype=float))
        dX = tangent[:self.N * self.n].reshape(self.N, self.n)
        _, DF, _ = self._checked_map(X, p)
        moduli = ic.normal_moduli(X, rho, DF)[0]
        t = np.arange(self.N + 1) / self.N
        return Solution(par=self.params(x),
                        columns=[float(ic.amplitudes(X)[1]), rho,
                                 float(moduli.max()) if moduli.size else math.nan],
                        u=np.vstack([X, X[:1]]), t=t, udot=np.vstack([dX, dX[:1]]),
                        rldot=[float(tangent[-1])], ntst=self.N, ncol=1, ndim_user=self.n)

    def column_titles(self) -> list:
        return list(COLUMNS)

    def directions(self, x, tangent, code) -> list:
        return []               # no branch points are looked for


# ------------------------------------------------------------------ runs

def constants(index: int, stop: float, n: int, *, ds: float, ds_max: float, ds_min: float,
              max_points: int, tol: float = NEWTON_TOL, **kw) -> Constants:
    """The constants of a circle run in PAR(index) up to PAR(index) = stop (UZSTOP), n the
    map's dimension: full Newton (NWTN = ITNW) to EPSL = EPSU = tol (relative corrections),
    AUTO's step control between ds_min and ds_max, NMX = max_points, every point a
    regular one (NPR = 0), no tests but the UZ value."""
    base = dict(e="circle", NDIM=n, IPS=-1, IRS=0, ISW=1, ICP=[index], ILP=0, ISP=0,
                NMX=max_points, NPR=0, MXBF=0, ITNW=NEWTON_MAX_ITER,
                NWTN=NEWTON_MAX_ITER, ITMX=30, EPSL=tol, EPSU=tol, EPSS=EPS_LOCATE,
                DS=ds, DSMIN=ds_min, DSMAX=ds_max, IADS=1, NPAR=max(index, 12),
                UZSTOP={index: stop})
    base.update(kw)
    return Constants(base, source="<invariant circles>")


def first_circle(fmap, x_star, v, rho0: float, p0: float, amplitude: float, N: int,
                 dp_guess: float = 0.0, tol: float = NEWTON_TOL) -> ic.Circle:
    """The first circle of the family born at a Neimark-Sacker point: the fixed point
    x_star (n,) at p0 with critical eigenvector v (n,) complex (DF v = mu v, arg mu =
    2 pi rho0). The engine's corrector from x_star + amplitude Re(v e^{i theta}) (v scaled
    to a unit largest component) with rho and p free on the plane that fixes the circle's
    mode-1 content along v at `amplitude` (near the birth the family's size, not the
    parameter, is the coordinate: p moves like amplitude^2). dp_guess: p - p0 of the guess.
    Raises ConvergenceError."""
    from washer.cont.iterator import Continuation
    x_star = np.asarray(x_star, dtype=float)
    n = x_star.size
    v = np.asarray(v, dtype=complex)
    v = v / np.abs(v).max()
    th = ic.nodes(N)
    basis = np.real(np.exp(1j * th)[:, None] * v[None, :])
    X0 = x_star + amplitude * basis
    s = Settings.from_constants(constants(1, p0, n, ds=amplitude, ds_max=1.0, ds_min=1e-12,
                                          max_points=1, tol=tol))
    sysm = InvariantCircles(fmap, ic.Circle(X0, rho0, p0), s)
    # Mode-1 projection on the birth direction, (2/N) sum_j Re(conj(v e^{i th_j})) .
    # (X_j - x*) / |v|^2 = g . (x - x_ref): the plane <x - x_ref, t>_w = amplitude of the
    # corrector with border(t) = w t = g.
    g = np.r_[basis.ravel() / np.sum(basis * basis), 0.0, 0.0]
    x_ref = np.r_[np.tile(x_star, N), 0.0, 0.0]
    x, it = Continuation(sysm, s, x0=sysm._x0, tangent=g).correct(
        np.r_[X0.ravel(), rho0, p0 + dp_guess], x_ref, g / sysm.theta, amplitude, plane=True)
    c = sysm.circle(x)
    st = sysm.stability(x, None)
    c.moduli, c.tangent, c.iterations = st.values, st.tangent, it
    c.residual = float(np.abs(sysm.residual(x)).max())
    return c


def circle_of(record: Record) -> ic.Circle:
    """The circle of a written point (its stored profile without the closing node, rho
    from the ROTATION column, the normal moduli from its stability)."""
    U = np.asarray(record.u, dtype=float)[:-1]
    st = record.stability
    return ic.Circle(U.copy(), float(record.values[1 + COLUMNS.index("ROTATION")]),
                     float(record.values[0]),
                     moduli=st.values if st is not None else np.array([np.nan]),
                     tangent=getattr(st, "tangent", math.nan))


def circles(branch: Branch) -> list:
    """The circles of a run's rows, in the order computed (`circle_of`)."""
    return [circle_of(r) for r in branch.rows]


def reached(branch: Branch) -> bool:
    """Whether the run ended at its UZSTOP value (its last point a UZ)."""
    return bool(branch.rows) and branch.rows[-1].ty == "UZ"


def continue_circles(fmap, first: ic.Circle, stop: float, *, index: int = 1, par=None,
                     ds: float = 0.05, ds_max: float = 0.5, ds_min: float = 1e-4,
                     max_points: int = 200, scale=None, tol: float = NEWTON_TOL,
                     sinks=(), name: str = "circle") -> Branch:
    """The family of invariant circles of fmap from `first` until PAR(index) = p reaches
    `stop` (UZSTOP), as an engine run: `runner.execute` on `InvariantCircles` with
    `constants(...)`, through `sinks` (washer.auto.sinks: b-/s-/d-files, the screen).
    par: the full PAR vector written to the records (default zeros, PAR(index) = p);
    scale (n,): the components' typical sizes for the inner product (default 1).
    Returns the engine's Branch (`circles(branch)` reads the circles; `reached(branch)`
    whether the end value was reached). ds, ds_max, ds_min: arclength in that norm."""
    from washer.cont.runner import Run, execute
    c = constants(index, stop, first.X.shape[1], ds=ds, ds_max=ds_max, ds_min=ds_min,
                  max_points=max_points, tol=tol)
    s = Settings.from_constants(c)
    if par is not None and len(par) > s.NPAR:
        s = s.with_(NPAR=len(par))
    full = np.zeros(s.NPAR)
    if par is not None:
        full[:len(par)] = par
    sysm = InvariantCircles(fmap, first, s, full, scale)
    pn = c["parnames"]
    titles = [pn.get(index, f"PAR({index})")] + sysm.column_titles()
    run = Run(c, s, sysm, name, titles, 0)
    return execute(run, 1, "fresh", sinks)
