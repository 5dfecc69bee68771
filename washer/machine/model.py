"""`Model`: the washing machine at one parameter set, evaluated by the kernel.

    >>> m = Model(load_params())
    >>> q_static = m.static_equilibrium()                  # (6,), Omega = 0
    >>> eps = m.rotating_equilibrium(frame="averaged")     # (6,), eqs 61-65
    >>> lam = m.eigenvalues(eps, frame="averaged")         # (12,) complex, 1/s
    >>> r = m.simulate(50.0, system="fixed", law="spinup") # time response (eq 48 + 66)

Frames: "fixed" is the ground frame (eq 48, non-autonomous); "frozen" and
"averaged" are the rotating-frame forms of eq 59 (docs/model.md section 4).
"""
from __future__ import annotations

import numpy as np

from washer.cont.newton import ConvergenceError
from washer.cont.newton import newton as cont_newton
from washer.machine import kernel, layout
from washer.machine.equilibria import (YAW_LIMIT, Equilibrium, EquilibriumError, EquilibriumInfo,
                               changed_params, follow, sigma_min, yaw_of)
from washer.machine.params import Params

ROTATING = ("frozen", "averaged")


def newton(residual, jacobian, x0, tol: float = 1e-11, max_iter: int = 50, what: str = "equilibrium"):
    """Damped Newton for residual(x) = 0 (halving the step while |F| grows; a trial
    point outside the kernel's domain counts as growing): the package's one Newton
    (washer.cont.newton) with a residual test.

    Returns x with max|F(x)| <= tol * (1 + max|x|), or raises EquilibriumError.
    """
    try:
        return cont_newton(residual, lambda x, F, it: np.linalg.solve(jacobian(x), -F), x0,
                           max_iter=max_iter, residual_tol=tol, damped=True,
                           domain_errors=(kernel.KernelError,))[0]
    except ConvergenceError as exc:
        raise EquilibriumError(f"{what}: {exc}") from None


def _hanging_guess(params) -> np.ndarray:
    """Tub height where the rods, stretched by the weight shared equally, reach their joints."""
    v = params.values
    up, lo = params.upper_joints(), params.lower_joints()
    m = v["m_t"] + v["m_b"] + v["m_u"]
    L = v["l0"] + m * v["g"] / (layout.N_RODS * max(v["K_s"], 1e-9))
    dr2 = np.sum((up[:, :2] - lo[:, :2]) ** 2, axis=1)
    z = np.mean(up[:, 2] - np.sqrt(np.maximum(L**2 - dr2, 1e-6)) - lo[:, 2])
    return np.array([0, 0, z, 0, 0, 0], dtype=float)


def _residuals(kind: str, frame: str | None):
    """(res(x, P) (6,), jac(x, P) (6, 6)): accelerations at rest of the ground
    frame (eq 48 at Omega = 0) or of the rotating frame (eq 61), and d/dx."""
    z6 = np.zeros(6)
    if kind == "static":
        return (lambda q, P: kernel.rhs_fixed(0.0, np.r_[q, z6], P, "constant")[6:],
                lambda q, P: kernel.jac_fixed(0.0, np.r_[q, z6], P, "constant")[0][6:, :6])
    return (lambda e, P: kernel.rhs_rot(np.r_[e, z6], P, frame)[6:],
            lambda e, P: kernel.jac_rot(np.r_[e, z6], P, frame)[0][6:, :6])


_REFERENCE: dict = {}


def _reference_equilibrium(kind: str, frame: str | None):
    """(x_ref (6,), P_ref) at the shipped reference set, where Newton from the hanging
    guess (static) and from the static equilibrium (rotating) converges to the
    hanging, unrotated equilibrium (yaw 0 and -0.039 rad). Cached."""
    key = (kind, frame)
    if key not in _REFERENCE:
        from washer.machine.params import load_params
        ref = load_params()
        P0 = ref.replace(Omega=0.0).vector()
        res, jac = _residuals("static", None)
        q = newton(lambda x: res(x, P0), lambda x: jac(x, P0), _hanging_guess(ref),
                   what="static equilibrium at the reference set")
        _REFERENCE[("static", None)] = (q, P0)
        if kind == "rotating":
            P = ref.vector()
            res, jac = _residuals(kind, frame)
            e = newton(lambda x: res(x, P), lambda x: jac(x, P), q,
                       what=f"{frame} rotating-frame equilibrium at the reference set")
            _REFERENCE[key] = (e, P)
        x, _ = _REFERENCE[key]
        if abs(yaw_of(x)) >= YAW_LIMIT:     # pragma: no cover - guards a changed reference set
            raise EquilibriumError(f"{kind} equilibrium at the reference set has yaw {yaw_of(x):.3f} rad")
    return _REFERENCE[key]


class Model:
    """The machine at parameter set `params` (a `Params`)."""

    def __init__(self, params: Params):
        if not isinstance(params, Params):
            raise TypeError(f"Model expects a washer.Params (from load_params), got {type(params).__name__}")
        self.params = params
        self.P = params.vector()

    # ------------------------------------------------------------- right-hand sides
    def rhs_fixed(self, t: float, u, law: str = "spinup") -> np.ndarray:
        """du/dt of eq 48, u = (q, q_dot) (12,), theta(t) by `law` ('constant'|'spinup')."""
        return kernel.rhs_fixed(t, u, self.P, law)

    def jac_fixed(self, t: float, u, law: str = "spinup"):
        """(d rhs/du (12, 12), d rhs/dparams (12, n)); columns named by `diff_params`."""
        return kernel.jac_fixed(t, u, self.P, law)

    def rhs_rot(self, xi, frame: str = "averaged") -> np.ndarray:
        """d xi/dt of eq 59, xi = (eps, eps_dot) (12,)."""
        return kernel.rhs_rot(xi, self.P, frame)

    def jac_rot(self, xi, frame: str = "averaged"):
        """(d rhs/d xi (12, 12), d rhs/dparams (12, n))."""
        return kernel.jac_rot(xi, self.P, frame)

    @property
    def diff_params(self) -> tuple[str, ...]:
        """Names of the parameter-Jacobian columns. With tied dampings the
        derivative along 'C_p' of the paper is the sum of columns C_p, C_ox, C_oz
        (see `tied_column`)."""
        return kernel.DIFF_NAMES

    def tied_column(self, Jp: np.ndarray, name: str) -> np.ndarray:
        """Derivative along parameter `name` as the user moves it (C_p moves C_ox, C_oz when tied)."""
        return sum(Jp[..., kernel.DIFF_NAMES.index(c)]
                   for c in layout.moved_by(name, self.params.tied))

    def mass_forces(self, q, qd, theta: float, w: float, wd: float = 0.0):
        """M (6, 6) and f (6,) with M q_ddot = f (eqs 48-49)."""
        return kernel.mass_forces(q, qd, theta, w, wd, self.P)

    # ------------------------------------------------------------------ equilibria
    def static_equilibrium(self) -> Equilibrium:
        """q* (6,) at rest: Omega = 0, basket angle 0 (imbalance on +x); m, rad.

        The hanging equilibrium, followed by natural continuation from the
        reference set's (module `washer.machine.equilibria`) in every parameter that
        differs. Returns an `Equilibrium` (an ndarray) whose `.info` says which
        equilibrium it is (branch, residual, yaw, hanging). Raises
        EquilibriumError where that branch does not reach the parameters: it
        folds, e.g. at K_s below about 571 N/m with the nominal imbalance at rest,
        where the tub tips over towards the imbalance."""
        P = self.params.replace(Omega=0.0).vector()
        return self._follow("static", None, P)

    def rotating_equilibrium(self, frame: str = "averaged", guess=None) -> Equilibrium:
        """eps* (6,) with eps_dot = 0 of the rotating-frame system (eqs 60-65); m, rad.

        The residual is eps_ddot(eps, 0) = (M H)^-1 Psi(eps) of eq 61, zero exactly
        where Psi is; its Jacobian is the analytic d eps_ddot / d eps (eq 63).
        Without a guess: the reference set's equilibrium (Newton from the static
        one; yaw eps6 = -0.039 rad) followed by natural continuation in every
        parameter that differs, so it is the hanging, unrotated equilibrium (a
        plain Newton from the static one can land on a tub turned half a
        revolution, eps6 = -3.12 rad at K_s = 500 N/m). With a guess: Newton from
        it; `.info.hanging` then says whether the result is that same equilibrium."""
        if frame not in ROTATING:
            raise ValueError(f"frame: expected one of {ROTATING}, got {frame!r}")
        if guess is None:
            return self._follow("rotating", frame, self.P)
        res, jac = _residuals("rotating", frame)
        x = newton(lambda e: res(e, self.P), lambda e: jac(e, self.P),
                   np.asarray(guess, dtype=float), what=f"{frame} rotating-frame equilibrium")
        try:
            same = bool(np.max(np.abs(x - self._follow("rotating", frame, self.P))) < 1e-6)
        except EquilibriumError:
            same = False
        return self._result(x, "rotating", frame, self.P, "Newton from the given guess", {}, 0, 0,
                            hanging=same and abs(yaw_of(x)) < YAW_LIMIT)

    def _follow(self, kind: str, frame: str | None, P) -> Equilibrium:
        """Continue the reference set's equilibrium of `kind` to parameter vector P."""
        res, jac = _residuals(kind, frame)
        x_ref, P_ref = _reference_equilibrium(kind, frame)
        what = "static equilibrium" if kind == "static" else f"{frame} rotating-frame equilibrium"
        path = changed_params(P_ref, P)
        try:
            x, steps, halvings = follow(res, jac, x_ref, P_ref, P, what=what)
        except EquilibriumError as exc:
            xl, Pl, s = exc.partial
            where = ", ".join(f"{k} = {Pl[layout.PARAM_NAMES.index(k)]:.6g}" for k in path)
            target = ", ".join(f"{k} = {b:.6g}" for k, (a, b) in path.items())
            sig, sig0 = sigma_min(jac(xl, Pl)), sigma_min(jac(x_ref, P_ref))
            last = self._result(xl, kind, frame, Pl, "end of the branch followed from the "
                                "reference set (fold)", path, 0, 0, hanging=True)
            raise EquilibriumError(
                f"{what}: no hanging equilibrium at {target}: the branch followed from the "
                f"reference set ends at s = {s:.6f} of the way ({where}), where the Jacobian's "
                f"smallest singular value has fallen to {sig:.3g} from {sig0:.3g} at the "
                f"reference (a fold: beyond it this equilibrium does not exist); last point "
                f"{np.array2string(xl, precision=4)}", last) from None
        how = ("the reference set's equilibrium" if not path else
               "followed from the reference set by natural continuation in "
               + ", ".join(path))
        yaw_ok = abs(yaw_of(x)) < YAW_LIMIT
        return self._result(x, kind, frame, P, how, path, steps, halvings, hanging=yaw_ok)

    def _result(self, x, kind, frame, P, how, path, steps, halvings, hanging) -> Equilibrium:
        res, jac = _residuals(kind, frame)
        x_ref, _ = _reference_equilibrium(kind, frame)
        info = EquilibriumInfo(kind, frame, how, path, steps, halvings,
                               float(np.max(np.abs(res(x, P)))), yaw_of(x), yaw_of(x_ref),
                               bool(hanging), sigma_min(jac(x, P)))
        return Equilibrium(x, info)

    def _hanging_guess(self) -> np.ndarray:
        return _hanging_guess(self.params)

    def eigenvalues(self, eps, frame: str = "averaged") -> np.ndarray:
        """Eigenvalues (12,) of the rotating-frame Jacobian at (eps, 0), sorted by
        decreasing real part (1/s, rotating frame)."""
        J = kernel.jac_rot(np.r_[np.asarray(eps, dtype=float), np.zeros(6)], self.P, frame)[0]
        lam = np.linalg.eigvals(J)
        return lam[np.argsort(-lam.real, kind="stable")]

    # -------------------------------------------------------------- time responses
    def simulate(self, t_end: float, **kwargs):
        """Time response; see `washer.simulate.simulate` for the arguments."""
        from washer.machine.responses import simulate
        return simulate(self, t_end, **kwargs)
