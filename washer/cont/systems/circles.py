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
tangent direction's modulus). Its runs (washer.cont.circle_runs: the first circle at
the birth, `continue_circles`) are `runner.execute` with constants like any other:
UZSTOP at the end value, NMX, EP/MX, sinks for b-/s-/d-files.

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

from washer.cont import invariant_circle as ic
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
