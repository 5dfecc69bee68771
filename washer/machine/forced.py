"""The exact stability of the spinning washer: the forced periodic response and its Floquet
multipliers, by shooting with the compiled kernel (shooting).

At constant speed (theta = 2 pi Omega t) the ground-frame equations (eq 48) are
non-autonomous with period T = 1/Omega. Their steady response is a T-periodic orbit
u(t) = (q, q_dot)(t), found here by Newton on the periodicity condition

    G(u0) = phi_T(u0) - u0 = 0,      dG/du0 = Phi - I,

with phi_T the flow over one period from t = 0 (theta = 0) and Phi the monodromy matrix,
both from one kernel call (`washer.machine.kernel.flow_variational`: DOPRI5 on the flow and its
variational equations). The Floquet multipliers are the eigenvalues of Phi; the orbit is
asymptotically stable when all lie inside the unit circle. The averaged rotating-frame
system's Hopf point (docs/model.md section 4) approximates a Neimark-Sacker (torus, AUTO's TR)
bifurcation of this orbit: a complex pair leaving the unit circle.

The continuation of this response (the engine's shooting system, TR/PD/LP located, the
exact critical C_p) is washer.problems.forced:

    >>> p = load_params()
    >>> r = periodic_response(p)                  # nominal values, start from averaging
    >>> r.multipliers[:2], r.stable
    >>> b = continue_response(p, "C_p", 0.2)      # the engine: TR/PD/LP located
    >>> b("TR1").par[0]                           # 0.10101...
    >>> c = critical_cp(p)                        # exact C_p,crit beside averaged/frozen

Symmetry (checked in tests/test_forced.py). The four identical rods at 90 degrees make a
quarter turn about the vertical axis, with theta -> theta + pi/2, a symmetry of eq 48; a
quarter turn takes the Cardan angles (alpha, beta, gamma) to those of
Rz(pi/2) A Rz(pi/2)^T = Ry(alpha) Rx(-beta) Rz(gamma), which is not (-beta, alpha, gamma)
exactly (the factors are in the other order), while a half turn takes them to
(-alpha, -beta, gamma) exactly. Hence the rotating-frame coordinates eps (eq 52) of the
orbit are periodic with period T/2 = 1/(2 Omega), all six; the positions eps1..3 (a true
vector) even with T/4, but the angles eps4..6 not with T/4. This is the 2 Omega harmonic
of docs/model.md section 4 (Cardan angles do not rotate like a vector); the 4 Omega rod harmonic
respects T/4. At the reference point the tub's orientation matrix seen from the rotating
frame, Rz(-tau) A Rz(tau), is T/4-periodic and varies by only ~1e-7 over the orbit, while
eps6 (gamma) swings by 4e-4 rad: the steady response is almost a rigid whirl, and the
2 Omega harmonic of the eps coordinates is nearly all coordinate effect.

The collocation way (the engine with IPS = 2 and an appended oscillator, AUTO's `frc`
demo) is e='washer:forced' (washer.problems.oscillator.forced_problem, whose stpnt is this module's
orbit; auto_constants/c.washer.forced); tests/test_forced.py compares the two ways'
TR point and multipliers (agreement ~5e-12).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from washer.machine import kernel, layout
from washer.machine.model import Model
from washer.machine.params import Params

TWO_PI = 2.0 * np.pi

#: Integration tolerances of the shooting (relative, absolute in m, rad, m/s, rad/s).
#: 1e-10/1e-12 make the monodromy matrix accurate to ~1e-9 (checked against finite
#: differences and solve_ivp in the tests), well below the 1e-6 agreement required
#: of the located critical values.
RTOL, ATOL = 1e-10, 1e-12
#: Newton stops when max|u(T) - u0| <= NEWTON_TOL * (1 + max|u0|): about the flow's
#: accuracy at RTOL; asking for less than the integration error would only make Newton
#: chase noise.
NEWTON_TOL = 1e-10
#: Parameters the forced response can be continued in (anything with a kernel derivative).
PARAMETERS = layout.DIFF_PARAMS


class ShootingError(RuntimeError):
    """Newton on the periodicity condition did not converge."""


# ------------------------------------------------------------------ frames (eq 52)

def _H(tau: float):
    """H(tau) of eq 54 (6, 6) and dH/dtau: rotates (x, y) and (alpha, beta) by tau."""
    c, s = np.cos(tau), np.sin(tau)
    H, H1 = np.eye(6), np.zeros((6, 6))
    for b in (0, 3):
        H[b:b + 2, b:b + 2] = [[c, -s], [s, c]]
        H1[b:b + 2, b:b + 2] = [[-s, -c], [c, -s]]
    return H, H1


def ground_from_rotating(xi, Omega: float, t: float = 0.0) -> np.ndarray:
    """Ground-frame state u = (q, q_dot) (12,) of the rotating-frame state xi = (eps, eps_dot)
    (12,) at time t (s), constant speed Omega (Hz): q = H eps, q_dot = w H' eps + H eps_dot
    (eqs 52, 55 with erratum 8), tau = w t, w = 2 pi Omega."""
    xi = np.asarray(xi, dtype=float)
    w = TWO_PI * Omega
    H, H1 = _H(w * t)
    return np.r_[H @ xi[:6], w * H1 @ xi[:6] + H @ xi[6:]]


def rotating_from_ground(u, Omega: float, t) -> np.ndarray:
    """Inverse of `ground_from_rotating`; u (12,) or (n, 12) with t scalar or (n,)."""
    single = np.ndim(u) == 1
    u = np.atleast_2d(np.asarray(u, dtype=float))
    t = np.broadcast_to(np.asarray(t, dtype=float), (u.shape[0],))
    w = TWO_PI * Omega
    out = np.empty_like(u)
    for i, (ui, ti) in enumerate(zip(u, t)):
        H, H1 = _H(w * ti)
        eps = H.T @ ui[:6]
        out[i] = np.r_[eps, H.T @ (ui[6:] - w * H1 @ eps)]
    return out[0] if single else out


# ------------------------------------------------------------------ the periodic orbit

def direction_of(tied: bool, name: str) -> np.ndarray:
    """Weights of the kernel's Jp columns for a change of parameter `name` as the user
    moves it (C_p moves C_ox and C_oz too when `tied`)."""
    if name not in PARAMETERS:
        raise ValueError(f"parameter: expected one of {', '.join(PARAMETERS)}, got {name!r}")
    d = np.zeros(kernel.N_DIFF)
    for c in layout.moved_by(name, tied):
        d[kernel.DIFF_NAMES.index(c)] = 1.0
    return d


def shoot_vector(P, u0, direction=None, omega: bool = False, rtol: float = RTOL,
                 atol: float = ATOL):
    """One period T = 1/Omega of the constant-speed ground-frame flow from u0 (12,) at
    t = 0 for the kernel parameter vector P (layout order).

    Returns (u(T) (12,), Phi (12, 12) monodromy, g_p (12,), stats): g_p is the derivative
    of u(T) along `direction` (N_DIFF,) of the kernel parameters (zeros when None)
    including, when the direction is Omega's (`omega`), the change of the period."""
    T = 1.0 / P[layout.INDEX["Omega"]]
    uT, Phi, s, stats = kernel.flow_variational(0.0, T, u0, P, "constant", direction,
                                                rtol, atol)
    if omega:             # d u(T(Omega)) / d Omega = s + f(T, u(T)) dT/dOmega
        s = s + kernel.rhs_fixed(T, uT, P, "constant") * (-T * T)
    return uT, Phi, s, stats


def shoot(params: Params, u0, name: str | None = None, rtol: float = RTOL,
          atol: float = ATOL):
    """`shoot_vector` at `params`, the derivative in parameter `name` (or none)."""
    d = None if name is None else direction_of(params.tied, name)
    return shoot_vector(params.vector(), u0, d, name == "Omega", rtol, atol)


@dataclass
class ForcedResponse:
    """The T-periodic steady response at one parameter set.

    u0: ground-frame state (q, q_dot) at t = 0, theta = 0 (12,), SI units.
    T: period 1/Omega (s). monodromy: Phi (12, 12). multipliers: eigenvalues of Phi (12,)
    complex, in the engine's order (washer.cont.floquet.sort_multipliers without a
    trivial multiplier: closest to the unit circle first). residual: max|u(T) - u0| at
    the solution; iterations: Newton iterations. Computed by
    washer.problems.forced.periodic_response.
    """
    params: Params
    u0: np.ndarray
    T: float
    monodromy: np.ndarray
    multipliers: np.ndarray
    residual: float
    iterations: int = 0

    @property
    def stable(self) -> bool:
        return bool(np.abs(self.multipliers).max() < 1.0)

    @property
    def exponents(self) -> np.ndarray:
        """Floquet exponents log(mu)/T (1/s, imaginary parts modulo 2 pi/T), as multipliers."""
        return np.log(self.multipliers.astype(complex)) / self.T

    def rotating(self, n: int = 64, t=None) -> tuple[np.ndarray, np.ndarray]:
        """(t (n,), xi (n, 12)): the orbit in rotating-frame coordinates (eq 52) on
        [0, T) at n equal steps (or at the times t), kernel DOPRI5 at RTOL."""
        if t is None:
            t = np.arange(n) * self.T / n
        t = np.asarray(t, dtype=float)
        Y, _, _ = kernel.integrate("fixed", "constant", 0.0, self.u0, self.params.vector(),
                                   t, RTOL, ATOL)
        return t, rotating_from_ground(Y, self.params["Omega"], t)


def averaged_start(params: Params, frame: str = "averaged", guess=None) -> np.ndarray:
    """Starting guess u0 (12,): the rotating-frame equilibrium (eps*, 0) of the averaged
    (or frozen) system mapped to the ground frame at t = 0 (an O(averaging error) guess)."""
    eps = Model(params).rotating_equilibrium(frame=frame, guess=guess)
    return ground_from_rotating(np.r_[eps, np.zeros(6)], params["Omega"], 0.0)


def simulated_start(params: Params, periods: int = 300, u_start=None) -> np.ndarray:
    """Starting guess u0 (12,) from a long simulation: the ground-frame state after
    `periods` forcing periods at constant speed (theta = 2 pi x periods, so the phase of
    t = 0), from u_start (default: the static equilibrium at rest). Converges to the
    response only where it is stable (transients decay like max|mu|^periods); use it
    where the averaged equilibrium is not a good guess (e.g. asymmetric machines)."""
    if u_start is None:
        u_start = np.r_[Model(params).static_equilibrium(), np.zeros(6)]
    T = 1.0 / params["Omega"]
    Y, _, _ = kernel.integrate("fixed", "constant", 0.0, u_start, params.vector(),
                               [periods * T], RTOL, ATOL)
    return Y[-1]
