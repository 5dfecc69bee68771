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

    >>> p = load_params()
    >>> r = periodic_response(p)                  # nominal values, start from averaging
    >>> r.multipliers[:2], r.stable
    >>> b = continue_response(p, "C_p", 0.2)      # pseudo-arclength, TR/PD/LP located
    >>> b.special[0].type, b.special[0].value     # ('TR', 0.10101...)
    >>> c = critical_cp(p)                        # exact C_p,crit beside averaged/frozen
    >>> curve = critical_curve(p, np.linspace(4.5, 15, 8))   # the exact Fig 4 curve

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
demo) is e='washer:forced' (washer.problems.washer.forced_problem, whose stpnt is this module's
orbit; auto_constants/c.washer.forced); tests/test_forced.py compares the two ways'
TR point and multipliers (agreement ~5e-12).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

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
NEWTON_MAX_ITER = 12
#: A multiplier is complex when |Im mu| > COMPLEX_TOL (it is ~1e-9 accurate).
COMPLEX_TOL = 1e-7

#: A located zero of the TR function is a torus bifurcation when the leading complex pair
#: lies on the unit circle to this (the multipliers' accuracy is ~1e-9).
TR_ACCEPT = 1e-6

#: Parameters the forced response can be continued in (anything with a kernel derivative).
PARAMETERS = layout.DIFF_PARAMS

#: Special-point codes, as AUTO labels them for periodic orbits.
TYPES = ("TR", "PD", "LP")


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

def _direction(params: Params, name: str) -> np.ndarray:
    """Weights of the kernel's Jp columns for a change of parameter `name` as the user
    moves it (C_p moves C_ox and C_oz too when tied)."""
    if name not in PARAMETERS:
        raise ValueError(f"parameter: expected one of {', '.join(PARAMETERS)}, got {name!r}")
    d = np.zeros(kernel.N_DIFF)
    for c in layout.moved_by(name, params.tied):
        d[kernel.DIFF_NAMES.index(c)] = 1.0
    return d


def shoot(params: Params, u0, name: str | None = None, rtol: float = RTOL,
          atol: float = ATOL):
    """One period of the constant-speed ground-frame flow from u0 (12,) at t = 0.

    Returns (u(T) (12,), Phi (12, 12) monodromy, g_p (12,), stats): g_p is the derivative
    of u(T) with respect to parameter `name` including, for Omega, the change of the
    period T = 1/Omega (zeros when name is None)."""
    P = params.vector()
    T = 1.0 / params["Omega"]
    d = None if name is None else _direction(params, name)
    uT, Phi, s, stats = kernel.flow_variational(0.0, T, u0, P, "constant", d, rtol, atol)
    if name == "Omega":   # d u(T(Omega)) / d Omega = s + f(T, u(T)) dT/dOmega
        s = s + kernel.rhs_fixed(T, uT, P, "constant") * (-T * T)
    return uT, Phi, s, stats


@dataclass
class ForcedResponse:
    """The T-periodic steady response at one parameter set.

    u0: ground-frame state (q, q_dot) at t = 0, theta = 0 (12,), SI units.
    T: period 1/Omega (s). monodromy: Phi (12, 12). multipliers: eigenvalues of Phi (12,)
    complex, by decreasing modulus. residual: max|u(T) - u0| at the solution.
    """
    params: Params
    u0: np.ndarray
    T: float
    monodromy: np.ndarray
    multipliers: np.ndarray
    residual: float
    iterations: int
    nfev: int

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


def sort_multipliers(mu) -> np.ndarray:
    """Multipliers (n,) complex by decreasing modulus, each pair's Im > 0 member first."""
    mu = np.asarray(mu, dtype=complex)
    return mu[np.lexsort((-mu.imag, -np.abs(mu)))]


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


def newton_periodic(flow, u0, tol: float = NEWTON_TOL, max_iter: int = NEWTON_MAX_ITER):
    """Newton on the periodicity condition flow(u0)[0] - u0 = 0 of any T-periodic system.

    flow(u0) -> (u(T) (n,), Phi (n, n), nfev): the flow over one period and its monodromy
    matrix (any integrator: the kernel's for the washer, scipy's in the tests). Exact
    Jacobian Phi - I, so convergence is quadratic. Returns (u0, Phi, residual, iterations,
    nfev); raises ShootingError after max_iter iterations."""
    u = np.array(u0, dtype=float)
    nfev = 0
    for it in range(max_iter + 1):
        uT, Phi, n = flow(u)
        nfev += n
        G = uT - u
        res = float(np.abs(G).max())
        if res <= tol * (1 + np.abs(u).max()):
            return u, Phi, res, it, nfev
        if it == max_iter:
            break
        u = u - np.linalg.solve(Phi - np.eye(u.size), G)
    raise ShootingError(f"periodic response: no convergence in {max_iter} Newton iterations "
                        f"(residual {res:.3e})")


def periodic_response(params: Params, u0=None, *, tol: float = NEWTON_TOL,
                      max_iter: int = NEWTON_MAX_ITER) -> ForcedResponse:
    """The T-periodic response of the washer (eq 48, constant speed) by Newton shooting
    (`newton_periodic` with the kernel's flow), u0 from `averaged_start` if None:
    3-4 iterations from there. Raises ShootingError if Newton fails."""
    u = averaged_start(params) if u0 is None else np.array(u0, dtype=float)

    def flow(v):
        uT, Phi, _, st = shoot(params, v)
        return uT, Phi, st["nfev"]

    u, Phi, res, it, nfev = newton_periodic(flow, u, tol, max_iter)
    return ForcedResponse(params, u, 1.0 / params["Omega"], Phi,
                          sort_multipliers(np.linalg.eigvals(Phi)), res, it, nfev)


# ------------------------------------------------------------------ test functions

def bifurcation_functions(mu) -> dict[str, float]:
    """Test functions of the special points, zero at them, continuous in the multipliers mu
    (n,) (through collisions of real multipliers into complex pairs too):

    TR (Neimark-Sacker): prod over i < j of (mu_i mu_j - 1), zero when a complex pair has
    |mu| = 1 (also at a 'neutral saddle', two real mu with product 1: a sign change there
    is rejected after location, as AUTO does);
    PD (period doubling): det(Phi + I) = prod (mu + 1);
    LP (fold of the forced response): det(Phi - I) = prod (mu - 1).
    Each changes sign when one multiplier (pair) crosses the unit circle its way."""
    mu = np.asarray(mu, dtype=complex)
    i, j = np.triu_indices(mu.size, 1)
    return {"TR": float(np.prod(mu[i] * mu[j] - 1.0).real),
            "PD": float(np.prod(mu + 1.0).real),
            "LP": float(np.prod(mu - 1.0).real)}


def critical_pair(mu) -> complex:
    """The leading complex multiplier (Im > 0, largest modulus; nan if none): the pair whose
    exit through |mu| = 1 makes the response lose stability at a TR point."""
    mu = np.asarray(mu, dtype=complex)
    cpx = mu[mu.imag > COMPLEX_TOL]
    return complex(cpx[np.argmax(np.abs(cpx))]) if cpx.size else complex(np.nan)


# ------------------------------------------------------------------ continuation

@dataclass
class SpecialPoint:
    """A located special point: type (TR, PD, LP), parameter `name` = value, the orbit's
    initial state u0 (n,) and multipliers (n,) there, and max|u(T) - u0| at it."""
    type: str
    name: str
    value: float
    u0: np.ndarray
    multipliers: np.ndarray
    residual: float

    @property
    def crossing(self) -> complex:
        """The critical multiplier: leading complex one (TR), or the real one nearest -1/+1."""
        mu = self.multipliers
        if self.type == "TR":
            return critical_pair(mu)
        target = -1.0 if self.type == "PD" else 1.0
        return complex(mu[np.argmin(np.abs(mu - target))])


@dataclass
class Branch:
    """A continued branch of periodic orbits in parameter `name`.

    values (m,): parameter; u0 (m, n): the orbit's state at t = 0; multipliers (m, n),
    each row by decreasing modulus; stable (m,) bool; special: located TR/PD/LP points in
    the order met; wall: seconds."""
    name: str
    values: np.ndarray
    u0: np.ndarray
    multipliers: np.ndarray
    stable: np.ndarray
    special: list = field(default_factory=list)
    wall: float = 0.0


class _Continuer:
    """Pseudo-arclength continuation of G(u0, p) = u(T; u0, p) - u0 = 0 in X = (u0, p / ps).

    flow(u0, p) -> (u(T) (n,), Phi (n, n), du(T)/dp (n,)): one period of any periodically
    forced system with its monodromy matrix and parameter sensitivity."""

    def __init__(self, flow, n: int, ps: float):
        self.flow, self.n, self.ps = flow, n, ps

    def G(self, X):
        n = self.n
        uT, Phi, gp = self.flow(X[:n], X[n] * self.ps)
        A = np.hstack([Phi - np.eye(n), (np.asarray(gp) * self.ps)[:, None]])
        return uT - X[:n], A, Phi

    def correct(self, Xp, tangent, tol=NEWTON_TOL, max_iter=8):
        """Newton on [G(X); tangent . (X - Xp)] = 0 from the predictor Xp."""
        X = Xp.copy()
        for it in range(max_iter):
            G, A, Phi = self.G(X)
            if np.abs(G).max() <= tol * (1 + np.abs(X[:self.n]).max()) and it > 0:
                return X, A, Phi
            dX = np.linalg.solve(np.vstack([A, tangent]), -np.r_[G, tangent @ (X - Xp)])
            X = X + dX
        raise ShootingError("continuation corrector did not converge")

    @staticmethod
    def tangent(A, prev=None):
        """Unit null vector of the n x (n + 1) Jacobian A, oriented along prev."""
        t = np.linalg.svd(A)[2][-1]
        if prev is not None and t @ prev < 0:
            t = -t
        return t


def continue_orbit(flow, u0, p0: float, stop: float, *, name: str = "p", ds: float = 0.02,
                   ds_max: float = 0.1, ds_min: float = 1e-5, max_points: int = 400,
                   p_scale: float | None = None, locate: bool = True) -> Branch:
    """Continue the T-periodic orbit through (u0, p0) (u0 a converged orbit) until the
    parameter reaches `stop`, for any forced system given by its one-period
    flow(u0, p) -> (u(T), Phi, du(T)/dp).

    Pseudo-arclength, so folds of the response are passed, in X = (u0, p / p_scale)
    (p_scale default max(|p0|, 1e-3): steps ds are then relative to the starting value);
    secant predictor along the tangent; steps halve on corrector failure and grow 1.5x
    after each success up to ds_max. Multipliers at every point; sign changes of the
    `bifurcation_functions` between consecutive points are located (`locate=True`) by
    Brent's method along the chord between them (corrector orthogonal to the chord), so
    LP is located as well as TR and PD."""
    import time
    t_wall = time.perf_counter()
    u0 = np.asarray(u0, dtype=float)
    n = u0.size
    c = _Continuer(flow, n, p_scale if p_scale is not None else max(abs(p0), 1e-3))
    X = np.r_[u0, p0 / c.ps]
    _, A, Phi = c.G(X)
    direction = np.sign(stop - p0) or 1.0
    tan = c.tangent(A)
    if tan[n] * direction < 0:
        tan = -tan
    pts = [(X, sort_multipliers(np.linalg.eigvals(Phi)))]
    special = []
    h = ds
    while len(pts) < max_points:
        try:
            Xn, An, Phin = c.correct(X + h * tan, tan)
        except (ShootingError, kernel.KernelError, np.linalg.LinAlgError):
            h /= 2
            if h < ds_min:
                break
            continue
        mu = sort_multipliers(np.linalg.eigvals(Phin))
        tf0, tf1 = bifurcation_functions(pts[-1][1]), bifurcation_functions(mu)
        if locate:
            for typ in TYPES:
                if tf0[typ] != 0 and np.sign(tf0[typ]) != np.sign(tf1[typ]):
                    sp = _locate_on_chord(c, X, Xn, typ, name)
                    if sp is not None:
                        special.append(sp)
        tan = c.tangent(An, tan)
        X = Xn
        pts.append((X, mu))
        h = min(ds_max, 1.5 * h)
        if (X[n] * c.ps - stop) * direction >= 0:
            break
    Xs = np.array([x for x, _ in pts])
    mus = np.array([m for _, m in pts])
    return Branch(name, Xs[:, n] * c.ps, Xs[:, :n], mus, np.abs(mus).max(axis=1) < 1.0,
                  special, time.perf_counter() - t_wall)


def _locate_on_chord(c: _Continuer, Xa, Xb, typ: str, name: str, xtol: float = 1e-12):
    """Zero of bifurcation function `typ` between branch points Xa, Xb: points of the branch
    on the hyperplanes orthogonal to the chord at fraction sigma, Brent on sigma."""
    chord = Xb - Xa
    unit = chord / np.linalg.norm(chord)
    cache = {}

    def point(sigma):
        X, _, Phi = c.correct(Xa + sigma * chord, unit)
        mu = sort_multipliers(np.linalg.eigvals(Phi))
        cache[sigma] = (X, mu)
        return bifurcation_functions(mu)[typ]

    try:
        sigma = brentq(point, 0.0, 1.0, xtol=xtol, rtol=4 * np.finfo(float).eps)
        if sigma not in cache:
            point(sigma)
    except (ValueError, ShootingError, kernel.KernelError, np.linalg.LinAlgError):
        return None
    X, mu = cache[sigma]
    if typ == "TR" and not abs(abs(critical_pair(mu)) - 1.0) < TR_ACCEPT:
        return None             # a neutral saddle (real mu_i mu_j = 1), not a torus bifurcation
    G = c.G(X)[0]
    return SpecialPoint(typ, name, float(X[c.n] * c.ps), X[:c.n], mu, float(np.abs(G).max()))


def washer_flow(params: Params, name: str):
    """flow(u0, p) of the washer (eq 48, constant speed) with parameter `name` set to p."""
    def flow(u0, p):
        uT, Phi, gp, _ = shoot(params.replace(**{name: p}), u0, name)
        return uT, Phi, gp
    return flow


def continue_response(params: Params, name: str, stop: float, *, start=None,
                      **kwargs) -> Branch:
    """Continue the washer's forced response in parameter `name` (one of PARAMETERS:
    C_p, Omega, m_u, R_u, C_a, K_s, ...) from its value in `params` to `stop`, with the
    multipliers at every point and TR/PD/LP located (`continue_orbit`; kwargs: ds, ds_max,
    ds_min, max_points, locate). start: a ForcedResponse at `params` (default: computed)."""
    if name not in PARAMETERS:
        raise ValueError(f"parameter: expected one of {', '.join(PARAMETERS)}, got {name!r}")
    r = start if start is not None else periodic_response(params)
    return continue_orbit(washer_flow(params, name), r.u0, params[name], stop, name=name,
                          **kwargs)


# ------------------------------------------------------------------ TR in one and two parameters

def tr_test(params: Params, name: str, value: float, u0=None) -> tuple[float, ForcedResponse]:
    """|mu_c| - 1 of the leading complex pair at parameter `name` = value, and the response."""
    r = periodic_response(params.replace(**{name: value}), u0)
    return abs(critical_pair(r.multipliers)) - 1.0, r


def locate_tr(params: Params, name: str, bracket: tuple[float, float], u0=None,
              xtol: float = 1e-12) -> tuple[ForcedResponse, SpecialPoint]:
    """The Neimark-Sacker (TR) point in parameter `name` inside `bracket` (a, b), where
    |mu_c| - 1 changes sign: Brent's method on the parameter, each evaluation a converged
    periodic response (warm-started from the last). The TR point is not a fold of the
    response, so the parameter is a good coordinate there. Returns (the ForcedResponse at
    the TR point, the SpecialPoint)."""
    state = {"u0": u0}

    def g(v):
        val, r = tr_test(params, name, v, state["u0"])
        state["u0"], state["r"] = r.u0, r
        return val

    a, b = bracket
    ga, gb = g(a), g(b)
    if np.sign(ga) == np.sign(gb):
        raise ValueError(f"locate_tr: |mu|-1 has the same sign at {name} = {a} and {b} "
                         f"({ga:+.3e}, {gb:+.3e})")
    v = brentq(g, a, b, xtol=xtol, rtol=4 * np.finfo(float).eps)
    _, r = tr_test(params, name, v, state["u0"])
    return r, SpecialPoint("TR", name, v, r.u0, r.multipliers, r.residual)


def averaged_hopf(params: Params, frame: str = "averaged", c_max: float = 2.0,
                  n_scan: int = 81, xtol: float = 1e-12) -> tuple[float, np.ndarray]:
    """C_p of the first Hopf point of the averaged (or frozen) rotating-frame system
    (eq 59) at the other parameters of `params`, scanning C_p from 0 up to c_max in n_scan
    values for the first sign change of max Re(lambda) at the equilibrium (Hopf curves can
    turn back at large C_p), then Brent. Returns (C_p, eigenvalues (12,) there, 1/s);
    ValueError if there is none."""
    state = {"eps": None}

    def g(cp):
        m = Model(params.replace(C_p=cp))
        state["eps"] = m.rotating_equilibrium(frame=frame, guess=state["eps"])
        state["lam"] = m.eigenvalues(state["eps"], frame=frame)
        return float(state["lam"].real.max())

    grid = np.linspace(0.0, c_max, n_scan)
    g_prev = g(grid[0])
    if g_prev == 0.0:           # no damping at all (C_a = 0 too): neutral at C_p = 0
        return 0.0, state["lam"]
    for a, b in zip(grid[:-1], grid[1:]):
        g_b = g(b)
        if np.sign(g_b) != np.sign(g_prev):
            cp = brentq(g, a, b, xtol=xtol)
            g(cp)
            return cp, state["lam"]
        g_prev = g_b
    raise ValueError(f"averaged_hopf ({frame}): no Hopf point for C_p in [0, {c_max}]")


def hopf_or_nan(params: Params, frame: str):
    """`averaged_hopf`, or (nan, nan eigenvalues) where there is no Hopf point."""
    try:
        return averaged_hopf(params, frame)
    except ValueError:          # no sign change of max Re(lambda) in the bracket: no Hopf
        return float("nan"), np.full(12, np.nan, dtype=complex)


def critical_cp(params: Params, rel_bracket: float = 0.05, abs_bracket: float = 1e-3) -> dict:
    """The exact critical C_p (TR of the forced response) at the other values of `params`,
    beside the averaged and frozen (tau0 = params['tau0']) Hopf values.

    The TR point is bracketed within +-(rel_bracket |C_p,avg| + abs_bracket) of the averaged
    Hopf value (clipped at C_p = 0): averaging is accurate to far better (docs/model.md section 4;
    here 1e-5 absolute). Returns a dict: C_p_exact/averaged/frozen (nan where the frozen
    system has no Hopf in (0, 2)), the multipliers at the exact point (12,), the critical
    multiplier and its Floquet exponent log(mu)/T (1/s, imaginary part modulo 2 pi Omega:
    the ground-frame whirl), the averaged eigenvalues at the averaged Hopf point (1/s),
    and the ForcedResponse there."""
    cp_avg, lam_avg = hopf_or_nan(params, "averaged")
    cp_frozen, _ = hopf_or_nan(params, "frozen")
    if np.isnan(cp_avg):        # below the averaged curve's lower end: search from C_p = 0
        bracket, start = (0.0, 2 * abs_bracket), None
    else:
        half = rel_bracket * abs(cp_avg) + abs_bracket
        bracket = (max(cp_avg - half, 0.0), cp_avg + half)
        start = averaged_start(params.replace(C_p=cp_avg))
    r, sp = locate_tr(params, "C_p", bracket, start)
    mu_c = critical_pair(r.multipliers)
    return {"Omega": params["Omega"], "C_p_exact": sp.value, "C_p_averaged": cp_avg,
            "C_p_frozen": cp_frozen, "multipliers": r.multipliers,
            "critical_multiplier": mu_c, "critical_exponent": np.log(mu_c) / r.T,
            "averaged_eigenvalues": lam_avg, "response": r}
