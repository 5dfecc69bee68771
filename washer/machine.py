"""`Model`: the washing machine at one parameter set, evaluated by the kernel.

    >>> m = Model(load_params())
    >>> q_static = m.static_equilibrium()                  # (6,), Omega = 0
    >>> eps = m.rotating_equilibrium(frame="averaged")     # (6,), eqs 61-65
    >>> lam = m.eigenvalues(eps, frame="averaged")         # (12,) complex, 1/s
    >>> r = m.simulate(50.0, system="fixed", law="spinup") # time response (eq 48 + 66)

Frames: "fixed" is the ground frame (eq 48, non-autonomous); "frozen" and
"averaged" are the rotating-frame forms of eq 59 (MODEL.md section 4).
"""
from __future__ import annotations

import numpy as np

from washer import kernel, layout
from washer.params import Params

ROTATING = ("frozen", "averaged")


class EquilibriumError(RuntimeError):
    """Newton's method did not converge to an equilibrium."""


def newton(residual, jacobian, x0, tol: float = 1e-11, max_iter: int = 50, what: str = "equilibrium"):
    """Damped Newton for residual(x) = 0 (halving the step while |F| grows).

    Returns x with max|F(x)| <= tol * (1 + max|x|), or raises EquilibriumError.
    """
    x = np.array(x0, dtype=float)
    F = residual(x)
    for it in range(max_iter):
        if np.max(np.abs(F)) <= tol * (1 + np.max(np.abs(x))):
            return x
        dx = np.linalg.solve(jacobian(x), -F)
        step, norm0 = 1.0, np.linalg.norm(F)
        while True:
            try:
                Fn = residual(x + step * dx)
                ok = np.linalg.norm(Fn) < norm0 or step < 1e-3
            except kernel.KernelError:
                ok = False
            if ok:
                break
            step /= 2
            if step < 1e-6:
                raise EquilibriumError(f"{what}: Newton line search failed at iteration {it}")
        x, F = x + step * dx, Fn
    raise EquilibriumError(f"{what}: no convergence in {max_iter} Newton iterations "
                           f"(residual {np.max(np.abs(F)):.3e})")


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
        cols = [name]
        if name == "C_p" and self.params.tied:
            cols += ["C_ox", "C_oz"]
        return sum(Jp[..., kernel.DIFF_NAMES.index(c)] for c in cols)

    def mass_forces(self, q, qd, theta: float, w: float, wd: float = 0.0):
        """M (6, 6) and f (6,) with M q_ddot = f (eqs 48-49)."""
        return kernel.mass_forces(q, qd, theta, w, wd, self.P)

    # ------------------------------------------------------------------ equilibria
    def static_equilibrium(self) -> np.ndarray:
        """q* (6,) at rest: Omega = 0, basket angle 0 (imbalance on +x)."""
        P = self.params.replace(Omega=0.0).vector()

        def acc(q):
            return kernel.rhs_fixed(0.0, np.r_[q, np.zeros(6)], P, "constant")[6:]

        def jac(q):
            return kernel.jac_fixed(0.0, np.r_[q, np.zeros(6)], P, "constant")[0][6:, :6]

        return newton(acc, jac, self._hanging_guess(), what="static equilibrium")

    def _hanging_guess(self) -> np.ndarray:
        """Tub height where the rods, stretched by the weight shared equally, reach their joints."""
        v = self.params.values
        up, lo = self.params.upper_joints(), self.params.lower_joints()
        m = v["m_t"] + v["m_b"] + v["m_u"]
        L = v["l0"] + m * v["g"] / (layout.N_RODS * max(v["K_s"], 1e-9))
        dr2 = np.sum((up[:, :2] - lo[:, :2]) ** 2, axis=1)
        z = np.mean(up[:, 2] - np.sqrt(np.maximum(L**2 - dr2, 1e-6)) - lo[:, 2])
        return np.array([0, 0, z, 0, 0, 0], dtype=float)

    def rotating_equilibrium(self, frame: str = "averaged", guess=None) -> np.ndarray:
        """eps* (6,) with eps_dot = 0 of the rotating-frame system (eqs 60-65), by Newton.

        The residual is eps_ddot(eps, 0) = (M H)^-1 Psi(eps) of eq 61, zero exactly
        where Psi is; its Jacobian is the analytic d eps_ddot / d eps (eq 63).
        Without a guess, Newton starts from the static equilibrium and, if that
        fails, follows Omega up from 0 in steps (a simple homotopy)."""
        if frame not in ROTATING:
            raise ValueError(f"frame: expected one of {ROTATING}, got {frame!r}")

        def solve(P, x0):
            def res(e):
                return kernel.rhs_rot(np.r_[e, np.zeros(6)], P, frame)[6:]

            def jac(e):
                return kernel.jac_rot(np.r_[e, np.zeros(6)], P, frame)[0][6:, :6]
            return newton(res, jac, x0, what=f"{frame} rotating-frame equilibrium")

        if guess is not None:
            return solve(self.P, np.asarray(guess, dtype=float))
        x = self.static_equilibrium()
        try:
            return solve(self.P, x)
        except EquilibriumError:
            pass
        for Om in np.linspace(0, self.params["Omega"], 21)[1:]:
            x = solve(self.params.replace(Omega=Om).vector(), x)
        return x

    def eigenvalues(self, eps, frame: str = "averaged") -> np.ndarray:
        """Eigenvalues (12,) of the rotating-frame Jacobian at (eps, 0), sorted by
        decreasing real part (1/s, rotating frame)."""
        J = kernel.jac_rot(np.r_[np.asarray(eps, dtype=float), np.zeros(6)], self.P, frame)[0]
        lam = np.linalg.eigvals(J)
        return lam[np.argsort(-lam.real, kind="stable")]

    # -------------------------------------------------------------- time responses
    def simulate(self, t_end: float, **kwargs):
        """Time response; see `washer.simulate.simulate` for the arguments."""
        from washer.simulate import simulate
        return simulate(self, t_end, **kwargs)
