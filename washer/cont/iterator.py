"""Pseudo-arclength continuation as an iterator (AUTO's CNRLAE / CNRLBV loop).

    for step in Continuation(system, settings):
        ...   # step.kind in {"start", "point", "special", "note", "failed"}

One step of the branch reads like the textbook (and like BifurcationKit's
`iterate`): predictor x + ds * tangent; corrector (Newton on [G; arclength]);
tangent at the new point (the null vector of G_x oriented by the secant just
taken, so a sharp fold is turned and not jumped); detection of sign changes of
the test functions and location of the earliest zero (`washer.cont.events`);
step control (AUTO's ADPTDS). The iterator writes nothing and decides no
stops: the consumer (`washer.cont.runner`) numbers, labels, stops and writes.

Arclength conditions (the system's `arclength`):
* "sphere" (algebraic, SOLVAE): |x - x_old|^2_theta = ds^2, full Newton each
  iteration; one hidden first step (AUTO's unwritten first STEPAE). The predictor's
  direction is AUTO's UDOT: the secant (x - x_old) / ds of the step that reached x_old
  (a regular step, the hidden one, a switch's first step; `_secant`), the start's
  direction at the start, the tangent at a located point.
* "plane" (BVP, SOLVBV): <x - x_old, d_old>_theta = ds, Newton-chord: the
  matrix is refactorised for the first NWTN iterations only. The predictor's
  direction d_old is AUTO's: the unit secant of the step that reached x_old
  (CONTBV + SCALEB; `Point.direction`), the stored or computed direction at the
  start; the exact tangent serves the test functions and the output. (The
  tangent predicts better, so Newton needs fewer iterations and ADPTDS grows
  the steps beyond AUTO's, and where mesh adaptation is marginal, as near a
  homoclinic orbit, the run then depends on a step sequence AUTO never took.)
A branch started by switching (`mode="switch"`) takes its first step on the
plane <x - x_bp - ds d, d> = 0 (AUTO's STBIF) and writes it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from washer.cont.branch import Counters, Point
from washer.cont.codes import Code
from washer.cont.corrector_algebraic import compiled_corrector
from washer.cont.events import first_zero, location_tolerance, sign_changes, signed_distance
from washer.cont.problem import ProblemError
from washer.cont.linalg import orient, quietly
from washer.cont.newton import ConvergenceError, newton  # noqa: F401 (ConvergenceError: API)

#: A Newton iterate whose correction exceeds this multiple of the first
#: correction diverges (AUTO's SOLVAE: DELREF = 20 max(...)).
DIVERGENCE_FACTOR = 20.0
#: Newton iterations allowed to correct a start point to a solution at its parameters
#: (`Continuation.correct_start`).
START_ITERATIONS = 20
#: A tangent solve whose result is this large (relative to 1) came from a
#: numerically singular bordered matrix (exactly at a branch point): the
#: secant is used instead.
SINGULAR_TANGENT = 1e12
#: A UZ test value |PAR(i) - value| below this fraction of 1 + |value| is rounding:
#: the parameter is on the value (no sign change is seen there).
UZ_ROUNDING = 1e-13
def adapt_step(ds: float, nit: int, s) -> float:
    """AUTO's ADPTDS: grow or shrink the step by the Newton iteration count of the
    last step (settings s: ITNW, DSMAX), capped at DSMAX."""
    if nit <= 1:
        f = 2.0
    elif nit == 2:
        f = 1.5
    elif 3 <= nit <= s.ITNW // 2:
        f = 1.1
    elif nit >= s.ITNW:
        f = 0.5
    else:
        f = 1.0
    new = ds * f
    return float(math.copysign(min(abs(new), s.DSMAX), new))


@dataclass(slots=True)
class Step:
    """What the iterator reports.

    kind : "start" (the first point), "point" (a regular point), "special"
        (a located zero of test `code`, base code; UZ tests have code Code.UZ
        and `key` ("UZ", k) naming the k-th UZR value), "note" (a d-file
        message: "NOTE:Possible special point", "NOTE:Retrying step"),
        "failed" (no convergence at DSMIN: the branch ends with MX).
    point : the point (None for notes). prev : the point before it.
    at_step_end : a special point that is the continuation step's end itself, not a
        trial of the location (`events.at_step_end`): its parameters are where the step
        put them, beyond the zero.
    """
    kind: str
    point: Point | None = None
    prev: Point | None = None
    code: int = 0
    key: object = None
    text: str = ""
    at_step_end: bool = False


@dataclass
class State:
    """Where a branch stands: the last accepted point, the next step size, how
    many points were written (AUTO's NTOT, for IAD), steps since the last
    adaptation (IADS), whether sign changes are detected yet, and the work done
    (`Counters`, from the start point's correction on)."""
    point: Point
    ds: float
    n_points: int = 1
    n_since_adapt: int = 0
    detect: bool = False
    counters: Counters = field(default_factory=Counters)


#: (n,) read-only vectors (0, ..., 0, 1) by n: the right-hand side of every tangent's
#: solve, made once per size instead of at every point.
_LAST_UNIT: dict = {}


def last_unit(n: int) -> np.ndarray:
    """The read-only (n,) vector (0, ..., 0, 1)."""
    e = _LAST_UNIT.get(n)
    if e is None:
        e = np.zeros(n)
        e[-1] = 1.0
        e.flags.writeable = False
        _LAST_UNIT[n] = e
    return e


def _failing_as(what: str, fn):
    """fn with the equations' failures (ProblemError) raised as ConvergenceError(what)."""
    def call(*args, **kw):
        try:
            return fn(*args, **kw)
        except ProblemError as exc:
            raise ConvergenceError(f"{what} ({exc})") from exc
    return call


class Continuation:
    """The points of one branch of `system`, lazily.

    settings : washer.cont.settings.Settings (DS, DSMIN, DSMAX, ITNW, NWTN,
        EPSL, EPSU, EPSS, ITMX, IADS, UZR). x0, tangent : start point and
        direction (from `system.start()` unless given). mode : "fresh" (hidden
        first step for algebraic systems), "switch" (x0 is a branch point and
        tangent the new branch's direction) or "restart" (no hidden step).
    """

    def __init__(self, system, settings, x0=None, tangent=None, mode: str = "fresh",
                 ds: float | None = None):
        self.sys, self.s = system, settings
        if x0 is None:
            x0, t_start = system.start()
            tangent = t_start if tangent is None else tangent
        self.x0 = np.asarray(x0, dtype=float)
        self.t0 = None if tangent is None else np.asarray(tangent, dtype=float)
        self.mode = mode
        self.ds = settings.DS if ds is None else ds
        self.uz = list(settings.UZR)
        self.tests = list(system.active_tests())
        self.state: State | None = None
        self.counters = Counters()
        self.failure = "No convergence with minimum step size"
        self._located_J = None
        # The corrector's compiled form where it applies (washer.cont.corrector_algebraic),
        # else None: the Python loop below.
        self._compiled = compiled_corrector(system, settings, DIVERGENCE_FACTOR)
        # the arclength the compiled corrector takes (plane True, sphere False)
        self._compiled_plane = getattr(self._compiled, "plane", False)
        # (x, J): the converged point of the last corrector and the Jacobian of its last
        # Newton iteration, where that serves x (`correct`); else None.
        self._newton = None
        # The last point evaluated from the corrector's Newton matrix (`evaluate`).
        self._newton_point = None
        # The system's compiled tangent (AlgebraicSystem.unit_tangent, CollocationBVP.
        # unit_tangent: `tangent`) or None.
        self._unit_tangent = getattr(system, "unit_tangent", None)
        # The system's point values in one call after the sphere's corrector (tangent,
        # stability, tests: EquilibriumSystem.point_values) or None.
        self._point_values = getattr(system, "point_values", None) \
            if system.arclength == "sphere" else None

    # ------------------------------------------------------- counted calls
    def _residual(self, x):
        self.counters.residuals += 1
        return self.sys.residual(x)

    def _jacobian(self, x, frozen: bool = False):
        self.counters.jacobians += 1
        if self._compiled is not None:
            J = self._compiled.jacobian_at(x)       # evaluated by the compiled corrector
            if J is not None:
                return J
        return self.sys.jacobian(x, frozen_second=True) if frozen else self.sys.jacobian(x)

    def _factor(self, J, border):
        self.counters.factorisations += 1
        return self.sys.factor(J, border)

    # ------------------------------------------------------------ corrector
    def correct(self, x_pred, x_ref, t_ref, ds, plane: bool | None = None):
        """Newton from x_pred on [G(x); arclength(x)] = 0 around x_ref (sphere of
        radius |ds|, or the plane <x - x_ref, t_ref> = ds). Returns (x, iterations)."""
        s, sysm = self.s, self.sys
        plane = (sysm.arclength == "plane") if plane is None else plane
        self._newton = None
        compiled = self._compiled
        if compiled is not None and self._compiled_plane == plane:
            # the same loop compiled (one foreign call); None: it hands over to this one
            if plane:
                done = compiled.correct_plane(x_pred, x_ref, t_ref, ds, self.counters)
                if done is not None:
                    # the matrix of the last iteration, as below
                    self._newton = compiled.newton
            else:
                done = compiled.correct(x_pred, x_ref, ds, self.counters)
            if done is not None:
                return done
        row_plane = sysm.border(t_ref) if plane else None
        ns = getattr(sysm, "n_state", None) if plane else None
        held = {"factor": None, "delref": None, "J": None, "it_J": 0}

        # A trial point outside the equations' domain: a failed step.
        residual = _failing_as("equations failed at a Newton iterate", self._residual)
        jacobian = _failing_as("equations failed at a Newton iterate", self._jacobian)

        def step(x, G, it):
            factor = held["factor"]
            if factor is None or not plane or it <= max(s.NWTN, 1):
                # Loci whose Jacobians hold second derivatives of f keep those
                # blocks as evaluated at the last converged point through the
                # corrector (they move by O(ds)): an inexact Newton matrix, the
                # residual and the first-derivative blocks exact, so the point
                # converged to is the same; the blocks are refreshed at every
                # converged point (evaluate), where tangent and tests need them.
                J = jacobian(x, frozen=sysm.freezes_second_derivatives)
                if plane:
                    factor = self._factor(J, row_plane)
                    held["J"], held["it_J"] = J, it
            if plane:
                c = row_plane @ (x - x_ref) - ds
            else:
                d = x - x_ref
                row = 2 * sysm.border(d) / abs(ds)
                c = (row @ d) / 2 - abs(ds)
                factor = self._factor(J, row)
            held["factor"] = factor
            rhs = np.empty(len(G) + 1)
            np.negative(G, out=rhs[:-1])
            rhs[-1] = -c
            return factor.solve(rhs)

        def converged(x_old, x, dx, it):
            if ns is not None:
                # AUTO's NEWTONBV: every free parameter's correction relative to it
                # within EPSL (the period's too), the profile's largest correction
                # relative to its largest value before the update within EPSU.
                du = np.abs(dx[:ns]).max() / (1 + np.abs(x_old[:ns]).max())
                dl = float((np.abs(dx[ns:]) / (1 + np.abs(x[ns:]))).max())
                if dl <= s.EPSL and du < s.EPSU:
                    return True
            else:
                du = np.abs(dx[:-1]).max() / (1 + np.abs(x[:-1]).max())
                dl = abs(dx[-1]) / (1 + abs(x[-1]))
                if dl <= s.EPSL and du <= s.EPSU:
                    return True
            size = max(du, dl)
            if held["delref"] is None:
                held["delref"] = DIVERGENCE_FACTOR * max(size, 1e-300)
            elif size > held["delref"]:
                raise ConvergenceError("Newton iterates diverge")
            return False

        x, it = newton(residual, step, x_pred, max_iter=s.ITNW, converged=converged,
                       exhausted=f"no convergence in ITNW = {s.ITNW} iterations")
        # AUTO's NEWTONBV: the matrix factorised at the last Newton iteration serves the
        # converged point (the fold test's direction, the Floquet multipliers of its
        # condensation, the branch-point test): no Jacobian is evaluated at x. Here for
        # the systems that say so (`newton_jacobian_at_point`: collocation BVPs, where a
        # Jacobian is f_u at every Gauss point), and only where that matrix was evaluated
        # at the iterate the converging correction started from, so that x lies within
        # EPSU / EPSL of it. (After chord iterations, beyond NWTN, AUTO takes the matrix
        # of an earlier iterate: on r3b's halo orbits, whose double trivial multiplier
        # splits as the square root of the matrix's error, it came out 0.4 off 1 from an
        # iterate 4e-5 away, and their BP of cycles went undetected while the
        # multipliers counted as inaccurate.) Algebraic systems evaluate the Jacobian at
        # x, as SOLVAE does.
        self._newton = (x, held["J"]) \
            if plane and held["J"] is not None and held["it_J"] == it \
            and not sysm.freezes_second_derivatives \
            and getattr(sysm, "newton_jacobian_at_point", False) else None
        return x, it

    def correct_start(self, x):
        """Newton with AUTO's EPSU test at fixed PAR(ICP(1)) (the matrix [J; e_last]):
        the solution at the given parameters nearest x (washer.cont.runner.solve). A run
        does not correct its start (AUTO-07p neither: see _begin)."""
        s = self.s
        x = np.array(x, dtype=float)
        e = np.zeros(len(x))
        e[-1] = 1.0

        residual = _failing_as("the equations fail at the start point", self._residual)
        jacobian = _failing_as("the equations fail at the start point", self._jacobian)

        def step(y, G, it):
            return self._factor(jacobian(y), e).solve(np.r_[-G, 0.0])

        return newton(residual, step, x, max_iter=START_ITERATIONS, residual_tol=0.0,
                      converged=lambda y0, y, dx, it:
                      np.max(np.abs(dx)) / (1 + np.max(np.abs(y[:-1]))) <= s.EPSU,
                      exhausted="the starting point is not a solution and Newton did not "
                                f"converge in {START_ITERATIONS} iterations to EPSU")[0]

    # -------------------------------------------------------------- tangent
    def tangent(self, J, ref):
        """Unit tangent at a point with Jacobian J, oriented along `ref` (the
        secant just taken); also the factorisation of [J; border(ref)], whose
        determinant is AUTO's BP test."""
        sysm = self.sys
        fast = self._unit_tangent
        got = None if fast is None else fast(J, ref, SINGULAR_TANGENT)
        if got is not None:
            # the factorisation, the solve and the norm below in one compiled call
            self.counters.factorisations += 1
            t, factor, done = got
            if done:
                return t, factor
        else:
            factor = self._factor(J, sysm.border(ref))
        z = quietly(factor.solve, last_unit(len(ref)))
        nz = math.sqrt(abs(sysm.inner(z, z))) if all(map(math.isfinite, z.tolist())) \
            else math.inf
        if not math.isfinite(nz) or nz == 0 or nz > SINGULAR_TANGENT:     # nz: a float
            z, nz = ref, math.sqrt(sysm.inner(ref, ref))
        return z / nz, factor

    def initial_tangent(self, x, J):
        """Null vector of J with AUTO's sign rule (STPRAE), unit in the inner product."""
        Jd = J if isinstance(J, np.ndarray) else None
        ns = getattr(self.sys, "n_state", None)
        if Jd is None and ns is not None and hasattr(self.sys, "null_vector"):
            # AUTO's STDRBV: the null vector of the BVP's Jacobian itself (a bordered
            # solve fixing PAR(ICP(1))-dot fails where the branch starts at a fold in
            # PAR(ICP(1)), e.g. a restart from a point of a fold locus of cycles), made
            # unit, with PAR(ICP(1))-dot > 0, or the next free parameter's, or the last
            # node's first non-negligible component.
            t = self.sys.null_vector(J, np.zeros(len(x)))
            t = t / math.sqrt(self.sys.inner(t, t))
            order = [len(t) - 1] + list(range(ns, len(t) - 1))
            for i in order:
                if abs(t[i]) / (1 + abs(x[i])) > self.s.EPSL:
                    return t if t[i] > 0 else -t
            last = np.arange(ns - self.s.NDIM, ns)
            for i in last:
                if abs(t[i]) / (1 + abs(x[i])) > self.s.EPSU:
                    return t if t[i] > 0 else -t
            return t
        if Jd is not None:
            _, _, Vt = np.linalg.svd(Jd)
            t = Vt[-1]
        else:
            e = np.zeros(len(x))
            e[-1] = 1.0
            t = self._factor(J, e).solve(e)
        t = t / math.sqrt(self.sys.inner(t, t))
        return orient(t, x, len(getattr(self.sys, "free", ())) or 1, self.s.EPSL, self.s.EPSU)

    # ----------------------------------------------------------- evaluation
    def evaluate(self, x, ref, keys=None, tangent=None, ds: float = 0.0, it: int = 0,
                 newton=None, jacobian=None) -> Point:
        """A converged point: tangent, stability and the test values `keys`
        (all active tests and UZ values when None). newton: the corrector's (x, J)
        (`correct`): when it is this x's and no tangent is given, J serves as the
        Jacobian at x (AUTO's NEWTONBV) unless the system finds the stability it gives
        too inexact (`newton_jacobian_serves`); else the Jacobian is evaluated at x.
        jacobian: the Jacobian at x as the caller has just evaluated it (the start's),
        taken instead of evaluating it again and counted as that evaluation (the
        counters stay those of two evaluations)."""
        direction = None
        if newton is not None and newton[0] is x and tangent is None:
            J = newton[1]
            stab = self.sys.stability(x, J)
            serves = getattr(self.sys, "newton_jacobian_serves", None)
            if serves is None or serves(stab):
                # The tangent is bordered by the secant, as below (the arclength row's
                # direction, the previous step's, gives another vector where the null
                # space is nearly two-dimensional: abcb's fold test then jumped next to
                # its BP of cycles).
                t, factor = self.tangent(J, ref)
                direction = ref / math.sqrt(self.sys.inner(ref, ref))     # CONTBV, SCALEB
                pt = Point(np.array(x), t, stab, {}, ds, it, direction)
                pt.tests = self._tests(pt, J, factor, keys)
                self._newton_point = pt
                return pt
        if jacobian is None:
            J = self._jacobian(x)
        else:
            self.counters.jacobians += 1
            J = jacobian
        if tangent is None and self._point_values is not None:
            # tangent, stability and the tests in one call where the system has it
            codes = self._codes(keys)
            got = self._point_values(x, J, ref, SINGULAR_TANGENT, codes)
            if got is not None:
                self.counters.factorisations += 1       # [J; border(ref)], as `tangent`
                t, stab, out = got
                pt = Point(np.array(x), t, stab, {}, ds, it, None)
                pt.tests = self._uz_tests(pt, out, keys)
                return pt
        if tangent is None:
            t, factor = self.tangent(J, ref)
            if self.sys.arclength == "plane":
                direction = ref / math.sqrt(self.sys.inner(ref, ref))     # CONTBV, SCALEB
        else:
            t = tangent
            factor = self._factor(J, self.sys.border(t))
        stab = self.sys.stability(x, J)
        pt = Point(np.array(x), t, stab, {}, ds, it, direction)
        pt.tests = self._tests(pt, J, factor, keys)
        return pt

    def _codes(self, keys) -> list:
        """The test functions' codes among keys (all active tests where None); the other
        keys are the user values' (UZR) `(kind, index)` tuples."""
        return self.tests if keys is None else [k for k in keys if isinstance(k, int)]

    def _tests(self, pt, J, factor, keys) -> dict:
        codes = self._codes(keys)
        out = dict(self.sys.test_functions(pt.x, pt.tangent, J, pt.stability, factor, codes)) \
            if codes else {}
        return self._uz_tests(pt, out, keys)

    def _uz_tests(self, pt, out: dict, keys) -> dict:
        """out with the user values' tests (UZR) `keys` asks for (all where None) at pt."""
        uz_keys = range(len(self.uz)) if keys is None else \
            [k[1] for k in keys if isinstance(k, tuple)]
        if self.uz and uz_keys:
            par = self.sys.params(pt.x)
            for k in uz_keys:
                i, v, _ = self.uz[k]
                q = float(par[i - 1]) - v       # the same double as numpy's difference
                # A parameter sitting on the value to rounding (a free parameter that
                # stays 0 while Newton leaves it at +-1e-190, as obv's multipliers on
                # their trivial branch) is on it, not crossing it back and forth.
                out[("UZ", k)] = 0.0 if abs(q) <= UZ_ROUNDING * (1 + abs(v)) else q
        return out

    # ----------------------------------------------------------------- step
    def _step(self, p: Point, ds, keys=None):
        """The continuation step of arclength ds from p (predictor + corrector)."""
        d = p.step_direction
        x, it = self.correct(p.x + ds * d, p.x, d, ds)
        # A continuation step's point takes the corrector's last matrix; the trials of a
        # location (keys given) evaluate the Jacobian at the point (`_trial`).
        secant = (x - p.x) / ds
        # (positional: keys, tangent, ds, it, newton)
        pt = self.evaluate(x, secant, keys, None, ds, it,
                           self._newton if keys is None else None)
        # (the point's x is a copy of x: its secant from p.x is this one, bit for bit)
        return self._secant(pt, p.x, ds, secant) if keys is None else pt

    def _secant(self, pt: Point, origin, ds, secant=None) -> Point:
        """pt with its step direction on the sphere: AUTO's SOLVAE predicts the next
        point along the secant of the step that reached this one, UDOT = (U - UOLD) /
        RDS (of unit length in the weighted norm to Newton's tolerance: pt lies on the
        sphere of radius |ds| about origin), not along the tangent. The tangent predicts
        better by O(ds^2), so Newton took one iteration fewer and ADPTDS grew steps
        where AUTO's stayed: ab's equilibria reached PAR(1) = 0.25 in 92 points, AUTO's
        in 107. The plane arclength of BVPs keeps its own direction (`evaluate`)."""
        if self.sys.arclength == "sphere":
            pt.direction = (pt.x - origin) / ds if secant is None else secant
        return pt

    def _retrying_step(self, p: Point, ds):
        """AUTO's STEPAE: on failure halve the step and retry, until below DSMIN.
        Yields notes; returns the new point or None (failed)."""
        while True:
            try:
                return self._step(p, ds), ds
            except (ConvergenceError, ProblemError, np.linalg.LinAlgError) as exc:
                if self.s.IADS == 0:
                    self.failure = f"No convergence with fixed step size ({exc})"
                    self._pending.append(Step("note", text=f"NOTE:{self.failure}"))
                    return None, ds
                ds /= 2
                if abs(ds) < self.s.DSMIN:
                    self.failure = f"No convergence with minimum step size ({exc})"
                    self._pending.append(Step("note", text=f"NOTE:{self.failure}"))
                    return None, ds
                self._pending.append(Step("note", text=f"NOTE:Retrying step ({exc})"))

    # ------------------------------------------------------------- location
    def _first_zero(self, prev: Point, cur: Point, ds: float):
        """The earliest accepted zero between prev and cur (`events.first_zero`)."""
        return first_zero(prev, cur, ds, self.s,
                          trial=lambda s_, key, base=None, chord=None, span=None:
                          self._trial(prev, s_, key, base, chord, span),
                          accepted=self._accepted, refresh=self._refresh, inner=self.sys.inner,
                          note=lambda text: self._pending.append(Step("note", text=text)),
                          curve_type=self.sys.curve_type,
                          secant=self.sys.arclength == "plane",
                          sphere=self.sys.arclength == "sphere",
                          resolution=self._resolution)

    def _resolution(self, key) -> float:
        """The smallest change of test key that Newton's tolerance resolves between two
        points (`events.locate`): for a user value PAR(i) - v, max(EPSL, EPSU) (1 + |v|),
        the relative tolerance to which a point's parameters (EPSL) and the quantities
        computed from its state (EPSU) are converged; below it a test's change across a
        location's bracket is Newton's noise, not a jump (kdv's run 6: the gap PAR(24)
        changes by 4.6e-10 across 2.2e-8 of arclength, EPSL = 1e-7, and AUTO labels its
        zero). 0 for the other tests, whose scale is their own."""
        if not isinstance(key, tuple):
            return 0.0
        v = self.uz[key[1]][1]
        return max(self.s.EPSL, self.s.EPSU) * (1 + abs(v))

    def _refresh(self, sp: Point) -> None:
        """All test values at a located point, at its (possibly replaced) tangent; the
        point's Jacobian is evaluated once."""
        cached = self._located_J
        if cached is None or cached[0] is not sp or not np.array_equal(cached[1], sp.x):
            cached = self._located_J = (sp, sp.x.copy(), self._jacobian(sp.x))
        J = cached[2]
        sp.tests = self._tests(sp, J, self._factor(J, self.sys.border(sp.tangent)), None)

    def _trial(self, prev: Point, s_, key, base=None, chord=None, span=None):
        """The trial point at arclength s_ from prev, evaluating test `key` only: a step
        from prev, or from `base` = (an earlier trial point, its s) by s_ - s (with a
        third item, along that point's direction as it stands:
        `events.locate_past_jump`). chord: the
        secant from prev to the far end of the interval searched per unit of its
        arclength span (`events.first_zero`): the predictor's direction on the sphere;
        on the plane, the line along which the step goes back from that end (prev's
        tangent when None)."""
        if base is not None and len(base) > 2:
            # AUTO's STEPBV from its last trial past a jump of the branch
            # (`events.locate_past_jump`): along that point's own direction, the unit
            # secant of the step that reached it (CONTBV), by the correction as it stands.
            p0, s0 = base[:2]
            ds = s_ - s0
            d0 = p0.step_direction
            x, it = self.correct(p0.x + ds * d0, p0.x, d0, ds)
            pt = self.evaluate(x, d0, [key], ds=ds, it=it)
            self._leave_along_secant(pt, p0.x, ds, d0)
            return pt, pt.tests.get(key)
        if base is not None:
            # The tangent at the trial point is oriented by (and the BP test borders the
            # Jacobian with) the earlier trial's tangent, not the secant of the step from
            # it, which is tiny near convergence and noisy (lcbp's BP of cycles came out
            # 2.2e-4 off with it, 1.2e-7 without).
            p0, s0 = base
            ds = s_ - s0
            # The step goes from the earlier trial along the unit secant of the trial
            # step that reached it (`_leave_along_secant`), on the plane across it: AUTO's
            # LCSPBV calls CONTBV before each STEPBV, and STEPBV predicts along that
            # secant, not along the trial point's tangent. The tangent predicts better,
            # so its Newton took one iteration fewer than AUTO's, and the located point's
            # count decides the next step (ADPTDS): r3b's V1b manifold run, whose UZ
            # at PAR(23) = 0 was reached by a trial of one iteration where AUTO's took
            # two, doubled its step there where AUTO's grew it by 1.5, and its steps,
            # longer ever after, failed down to DSMIN 525 steps later (AUTO ends EP at
            # NMX). A branch point's trials keep the trial point's tangent (their test
            # borders prev's; tor's LPs after its BP of cycles were lost with secants).
            d0 = p0.step_direction if self.sys.arclength == "plane" \
                and key not in (Code.BP, Code.BPC) else p0.tangent
            # s is measured along prev's step direction (`events.first_zero`'s position,
            # the coordinate in which a step from prev of arclength s lands at s); a step
            # of length d along p0's tangent moves it by d <t_p0, d_prev>: ask for the
            # step that lands on s_. Near a sharp fold, where the branch turns away from
            # prev's tangent within one step, the plain step falls short by that cosine
            # at every trial and the location creeps (pcl's LP of its heteroclinic
            # connections: ITMX used up with the trials moving 60 % of the way).
            # On the sphere arclength s is the distance from prev (the step from p0,
            # on the sphere about p0, moves it by d times the cosine of p0's tangent
            # with the radius from prev); on the plane, the projection on prev's step
            # direction.
            c = self.sys.inner(d0, self._radial(prev, p0, s0)) \
                if self.sys.arclength == "sphere" else \
                self.sys.inner(d0, prev.step_direction)
            if abs(c) > 0.05:
                ds /= c
            origin, origin_direction = p0.x, p0.step_direction
            try:
                x, it = self.correct(p0.x + ds * d0, p0.x, d0, ds)
            except ConvergenceError:
                if key not in (Code.BP, Code.BPC):
                    raise
                # The trial points of a BP carry prev's tangent (their test borders it),
                # off by the curvature over the whole step: next to the branch point,
                # where Newton's matrix is nearly singular, the step from one fails with
                # it and is taken again along the trial point's own tangent (AUTO's
                # STEPAE/STEPBV step from their current point with its own direction):
                # r3b's third BP on its circle of equilibria, the BP of its halo orbits.
                t0, _ = self.tangent(self._jacobian(p0.x), prev.tangent)
                try:
                    x, it = self.correct(p0.x + ds * t0, p0.x, t0, ds)
                except ConvergenceError:
                    # Closer still to the branch point, the period (no weight in the
                    # arclength) is so ill-determined on the plane about a trial point
                    # that Newton converges only linearly from there, whatever the
                    # direction: the step is taken from prev instead, as the location's
                    # first trial (tor's symmetry-breaking BP of cycles one step past a
                    # fold: the trial 6e-5 from the last one failed in ITNW = 5, the
                    # step of 2.9e-3 from prev converges in 2 iterations).
                    # (The location measures the point's s along prev's step
                    # direction, wherever on it the step lands.)
                    x, it = self.correct(prev.x + s_ * prev.tangent, prev.x, prev.tangent,
                                         s_)
                    ds = s_
                    origin, origin_direction = prev.x, prev.step_direction
            if key in (Code.BP, Code.BPC):
                # A branch point's test is a determinant of the Jacobian bordered by a
                # direction: the same one, prev's tangent, at every trial, so that its
                # values along the location are one function.
                pt = self.evaluate(x, prev.tangent, [key], tangent=prev.tangent, ds=ds, it=it)
            else:
                pt = self.evaluate(x, p0.tangent, [key], ds=ds, it=it)
                self._leave_along_secant(pt, origin, ds, origin_direction)
        elif key == Code.BPC:
            # The first trial of a BP of a BVP too: bordered by prev's tangent, as the
            # later ones, so that all trials evaluate one function (its own tangent,
            # oriented along a secant to a Newton iterate that may have slipped onto
            # the crossing branch, flipped the test's sign at abcb's BP of cycles).
            x, it = self.correct(prev.x + s_ * prev.tangent, prev.x, prev.tangent, s_)
            pt = self.evaluate(x, prev.tangent, [key], tangent=prev.tangent, ds=s_, it=it)
        elif chord is not None and self.sys.arclength == "sphere":
            # The sphere of radius |s_| about prev is the same whatever the predictor.
            chord = chord / math.sqrt(self.sys.inner(chord, chord))
            x, it = self.correct(prev.x + s_ * chord, prev.x, chord, s_)
            pt = self.evaluate(x, (x - prev.x) / s_, [key], ds=s_, it=it)
        elif chord is not None:
            # AUTO's LCSPBV steps back from the far end along the secant of the step
            # (CONTBV, made unit by SCALEB), by its secant correction s_ - span as it
            # stands, on the plane across the secant: not along prev's step direction, to
            # which the branch may run nearly parallel where it turns within the step
            # (pkc's fold of cycles on its second lap: the step along prev's direction
            # failed in ITNW = 5). The correction is measured along the secant, not
            # rescaled to prev's coordinate (by the secant's length per unit of it): where
            # the branch bends within the step, as kpr's run 7 at its zero of PSI 9, the
            # rescaled step went 6 % further back, landed at PSI 9 = -5.6e-6 where AUTO's
            # lands at -1.8e-6, and the location ended on a one-iteration trial, so that
            # ADPTDS doubled the next step where AUTO's grows it by 1.5. The point lands
            # off the s asked for: the location places it by its projection
            # (`events.locate`, position).
            n = math.sqrt(self.sys.inner(chord, chord))
            end = prev.x + span * chord
            back = s_ - span
            x, it = self.correct(end + back * chord / n, end, chord / n, back)
            pt = self.evaluate(x, (x - prev.x) / s_, [key], ds=s_, it=it)
            self._leave_along_secant(pt, end, back, chord / n)
        else:
            pt = self._step(prev, s_, keys=[key])
        return pt, pt.tests.get(key)

    def _leave_along_secant(self, pt: Point, origin, ds: float, fallback) -> None:
        """A location's trial point on a BVP branch leaves, if located, along the unit
        secant of the trial step that reached it, (x - origin) / ds: AUTO's CNRLBV calls
        CONTBV after LCSPBV, whose last STEPBV went from the previous trial (from the
        step's end for the first) by DSOLD. Not along a tangent: where the branch's
        null space is nearly two-dimensional the tangent is off the branch as computed
        (nag's heteroclinic orbits at PAR(1) = 1: the previous trial's tangent had
        cosine 0.73 with the branch's secant, and every step from the UZ failed down to
        DSMIN where AUTO's next step ends EP at RL1). A step shorter than the
        location's tolerance is one AUTO does not take (it stops at the trial before,
        whose next correction is below the tolerance) and its secant is Newton's noise:
        the point then keeps `fallback`, the direction its origin left along. ds is
        signed as the step (a step back from the step's end gives a secant pointing
        on along the branch)."""
        if self.sys.arclength != "plane":
            return
        if abs(ds) >= location_tolerance(self.s):
            d = (pt.x - origin) / ds
        else:
            d = fallback
        pt.direction = d / math.sqrt(self.sys.inner(d, d))

    def _radial(self, prev: Point, p: Point, s: float) -> np.ndarray:
        """The unit vector from prev to p in the system's inner product, signed as the
        step s that reached p (the direction in which the sphere coordinate s grows, as
        prev's step direction does; that direction where p is prev)."""
        d = p.x - prev.x
        n = signed_distance(d, s, self.sys.inner)
        return prev.step_direction if n == 0 else d / n

    def _accepted(self, key, prev, cur) -> bool:
        return True if isinstance(key, tuple) else self.sys.accept(key, prev, cur)

    # ------------------------------------------------------------- iterate
    def __iter__(self):
        """Start, then step until the consumer stops asking or the branch fails."""
        self._pending: list[Step] = []
        yield from self._begin()
        while self.state is not None:
            yield from self.step()

    def _begin(self):
        """The start point (as given), its tangent, and the
        first step: AUTO's hidden one, or the written plane step of a switch."""
        sysm = self.sys
        # AUTO-07p corrects no start, and neither do we: CNRLAE writes an algebraic start
        # as given at PT 1 (its tangent the null vector of [f_u f_p] there, turned by
        # STPRAE's sign rule, linalg.orient; the unwritten first step's corrector reaches
        # the solutions), CNRLBV/RSPTBV a BVP's (at a Hopf start the collocation system is
        # singular in the period). tests/test_start_point.py.
        x0 = self.x0
        J0 = _failing_as("the equations fail at the start point", self._jacobian)(x0)
        t0 = self.t0 if self.t0 is not None else self.initial_tangent(x0, J0)
        t0 = t0 / math.sqrt(sysm.inner(t0, t0))
        # (a dense J0 is taken again; a collocation system's Jacobian object is evaluated
        # afresh, as its factorisations may keep state in it)
        start = self.evaluate(x0, t0, tangent=t0, jacobian=J0) if type(J0) is np.ndarray \
            else self.evaluate(x0, t0, tangent=t0)
        sysm.update(start.x, start.tangent)
        self.state = State(start, self.ds, counters=self.counters)
        yield Step("start", start)
        st = self.state
        if self.mode == "switch":
            # First step of a switched branch: on the plane orthogonal to the new
            # direction through x_bp + ds d (AUTO's STBIF); it is written.
            ds = st.ds
            while True:                              # halved on failure, as STEPAE
                try:
                    x, it = self.correct(x0 + ds * t0, x0, t0, ds, plane=True)
                    break
                except (ConvergenceError, ProblemError, np.linalg.LinAlgError) as exc:
                    ds /= 2
                    if abs(ds) < self.s.DSMIN:
                        self.state = None
                        yield Step("failed", start, text=f"no convergence on the switched "
                                                         f"branch with minimum step size ({exc})")
                        return
                    yield Step("note", text=f"NOTE:Retrying step ({exc})")
            st.ds = ds
            pt = self._secant(self.evaluate(x, (x - x0) / ds, ds=ds, it=it), x0, ds)
            yield from self._untested(start, pt)
            pt.tests = {}                            # no detection on the first interval
            sysm.update(pt.x, pt.tangent)
            st.point, st.n_points, st.detect = pt, 2, True
            yield Step("point", pt, prev=start)
        elif sysm.arclength == "sphere" and self.mode == "fresh":
            # AUTO's unwritten first step: it only provides a secant direction.
            pt, st.ds = self._retrying_step(start, st.ds)
            yield from self._flush()
            if pt is None:
                self.state = None
                yield Step("failed", start, text=self.failure)
                return
            # No detection from the hidden point; its user values are kept for the
            # warning when one is passed on the first written (untested) interval.
            pt.tests = {k: v for k, v in pt.tests.items() if isinstance(k, tuple)}
            sysm.update(pt.x, pt.tangent)
            st.point = pt

    def step(self):
        """One step of the branch from self.state: predictor + corrector (with
        retries), then detection and location, then step control. Yields the
        notes, and the new regular or special point (or the failure)."""
        st, sysm = self.state, self.sys
        current = st.point
        nxt, st.ds = self._retrying_step(current, st.ds)
        if self._pending:                   # (most steps have no notes)
            yield from self._flush()
        if nxt is None:
            self.state = None
            yield Step("failed", current, text=self.failure)
            return
        if not st.detect:
            # Test functions start at zero (AUTO: TEST(:) = 0): nothing is detected
            # on the first written interval. The step adapts after it as after any
            # (AUTO's loop calls ADPTDS from its first point on: ab's, log's PT 3 lie
            # 2 DS beyond PT 2).
            st.detect = True
            yield from self._untested(current, nxt)
            yield self._accept(nxt, current)
            self._adapt_mesh(nxt, st.n_points)
            self._adapt_step(nxt.iterations)
            return
        changed = sign_changes(current.tests, nxt.tests)
        if changed and nxt is self._newton_point:
            # A test changes sign over the step: the point is evaluated again from the
            # Jacobian at it (as the location's trials are), so that the zeros are found
            # and located from exact values. Next to a zero of high order the Newton
            # matrix's error exceeds the test itself: at abcb's tip of its cycles, where
            # fold and branch point coincide (BP test 3e-28 against 1e-8 a step away),
            # the fold's sign change showed and the branch point's did not.
            nxt = self.evaluate(nxt.x, (nxt.x - current.x) / nxt.ds, ds=nxt.ds,
                                it=nxt.iterations)
            changed = sign_changes(current.tests, nxt.tests)
        # (no test changes sign over the step: nothing to locate, `first_zero` would
        # find no key; most steps, and its set-up costs more than this check)
        hit = self._first_zero(current, nxt, st.ds) if changed else None
        if self._pending:
            yield from self._flush()
        if hit is not None:
            # sp's located tests are stored as 0 (`events.clear_located`).
            sp, key, same = hit
            if sysm.arclength == "plane" and sp is not nxt and not sp.across_jump:
                # (past a jump the last trial's secant is the far sheet's way on, AUTO's
                # CONTBV after LCSPBV: kdv's run 3 turns back there to PAR(1) = 3)
                self._orient_located(sp, current, nxt)
            # a system may know the way on at a point where its locus meets another
            # (ContinuedSystem.leaving_direction: the torus locus at R1 / R2)
            leave = getattr(sysm, "leaving_direction", None)
            d = None if leave is None else leave(sp.x, sp.step_direction, key, same)
            if d is not None:
                sp.direction = d
            sysm.update(sp.x, sp.tangent)
            st.point = sp
            st.n_points += 1
            code = Code.UZ if isinstance(key, tuple) else sysm.located_code(key, sp)
            yield Step("special", sp, prev=current, code=int(code), key=key,
                       at_step_end=sp is nxt)
            if sysm.arclength == "plane":
                # AUTO's CNRLBV adapts after every point, located ones included (with
                # the last location step's iterations); CNRLAE only after regular ones.
                self._adapt_step(sp.iterations)
            return
        yield self._accept(nxt, current)
        self._adapt_mesh(nxt, st.n_points)
        self._adapt_step(nxt.iterations)

    def _orient_located(self, sp: Point, prev: Point, cur: Point) -> None:
        """A located point of a BVP lies between prev and cur on the branch: its
        predictor's direction (the location's secant over its last, possibly very short
        trial step, AUTO's CONTBV) points from prev towards cur. Where that secant is
        shorter than Newton's error it can point back (cir's UZ at PAR(2) = -0.01, 2e-4
        past the last point, near a Hopf point of its equilibrium: the branch turned
        back there); it is then replaced by the secant of the whole step that the
        location split (AUTO's first trial steps back from cur along that one)."""
        inner = self.sys.inner
        if inner(sp.step_direction, prev.step_direction) >= 0:
            return
        d = cur.x - prev.x
        sp.direction = d / math.sqrt(inner(d, d))
        if inner(sp.tangent, sp.direction) < 0:
            sp.tangent = -sp.tangent

    def _untested(self, prev: Point, cur: Point):
        """A warning for each user value (UZR, UZSTOP) passed on the first written
        interval, where nothing is detected (AUTO's test functions start at 0): the
        point is not labelled, a UZSTOP there does not stop the run, and with NMX = 0
        (no limit on the steps) the run may then never end."""
        for k, (i, v, stop) in enumerate(self.uz):
            q0, q1 = prev.tests.get(("UZ", k)), cur.tests.get(("UZ", k))
            if q0 is None or q1 is None or q0 * q1 >= 0:
                continue
            text = (f"WARNING:PAR({i}) passed the user value {v:g} on the first step of the "
                    "branch, where no special point is detected (as in AUTO): it is not "
                    "labelled")
            if stop:
                text += " and the run does not stop there"
                if self.s.NMX <= 0:
                    text += ("; NMX = 0 sets no limit on the steps: only another stop "
                             "(a user value, STOP, RL0/RL1/A0/A1, no convergence) ends it")
            self._pending.append(Step("note", text=text))
        yield from self._flush()

    def _adapt_step(self, iterations: int) -> None:
        """AUTO's ADPTDS every IADS points (IADS = 0: a fixed step)."""
        st = self.state
        st.n_since_adapt += 1
        if self.s.IADS > 0 and st.n_since_adapt >= self.s.IADS:
            st.ds = adapt_step(st.ds, iterations, self.s)
            st.n_since_adapt = 0

    def _accept(self, pt: Point, prev: Point) -> Step:
        """A regular point becomes the state's point: its Step, which the caller yields
        before `_adapt_mesh` (the consumer writes the point as it was accepted)."""
        st = self.state
        self.sys.update(pt.x, pt.tangent)
        st.point = pt
        st.n_points += 1
        return Step("point", pt, prev=prev)

    def _adapt_mesh(self, p: Point, n_points: int) -> None:
        """Mesh adaptation of BVP systems (AUTO's ADAPT every IAD points): the
        system moves the accepted point, its tangent and its step direction to its
        new mesh; the direction is made unit again in the new mesh's norm (CONTBV
        scales the secant after ADAPT)."""
        if self.sys.wants_remesh(n_points):
            if p.direction is None:
                p.x, p.tangent = self.sys.remesh(p.x, p.tangent)
            else:
                p.x, p.tangent, d = self.sys.remesh(p.x, p.tangent, p.direction)
                p.direction = d / math.sqrt(self.sys.inner(d, d))

    def _flush(self):
        while self._pending:
            yield self._pending.pop(0)
