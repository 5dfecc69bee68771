"""The exact whirl: the invariant torus of the spinning washer past its Neimark-Sacker point.

At constant speed the ground-frame equations (eq 48) are T-periodic (T = 1/Omega); in the
rotating frame (eq 52) they are T/2-periodic (the half-turn symmetry of the four rods,
`washer.machine.forced`). Past the torus (TR) point of the forced response the attractor is a
two-frequency motion: the spin Omega and the whirl. Its section by the stroboscopic map
over T/2 in rotating coordinates,

    P: xi(0) -> xi(T/2),        xi = (eps, eps_dot) (12,) of eq 52,

is an invariant circle, continued by the engine as `washer.cont.systems.circles` (Fourier
collocation in the circle's angle, `washer.cont.invariant_circle`) with P and its Jacobian
from one kernel call per node
(`kernel.flow_variational`: DOPRI5 on the flow and its variational equations, plus the
derivative in the continued parameter):

    DP = G(T/2)^-1 Phi G(0),     dP/dp = G(T/2)^-1 s,

with u = G(t) xi the linear map from rotating to ground coordinates at time t (eqs 52, 55).
The family is born at the TR point with amplitude 0 and continued by pseudo-arclength
down to C_p = 0 (or any stop).

What it gives beside the averaged rotating frame's periodic orbits (first-order averaging,
`auto_constants/c.washer.po`): no averaging at all. The 2 Omega harmonic that averaging
drops (Cardan angles do not rotate like a vector, docs/model.md section 4) grows like tilt^2,
and the whirl tilts tens of degrees at C_p = 0.

Rotation number and whirl frequency. The circle's angle theta is oriented so that the
tub's offset eps1 + i eps2 turns counter-clockwise with theta; rho (turns per T/2) is then
the rotating-frame whirl per half period, and the ground-frame whirl frequency is

    f_whirl = 2 Omega (rho - 1/2)   (Hz, modulo 2 Omega),

since eps = Rz(-2 pi Omega t) x turns at f_whirl - Omega.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from washer.machine import forced, kernel, layout
from washer.machine.layout import PAR_INDEX
from washer.problems import forced as shooting
from washer.problems.parameters import set_par
from washer.cont import invariant_circle as ic
from washer.cont.branch import Branch
from washer.cont import circle_runs
from washer.machine.params import Params

TWO_PI = 2.0 * np.pi
#: Nodes on the circle (2K + 1). At C_p = 0 the circle's Fourier amplitudes fall ~2.7x
#: per mode (`ExactWhirl.tail`: 8e-8 at K = 16); K = 16 and K = 20 agree to 1e-8 in radius
#: and rotation number, and the normal multipliers need it: at K = 8 or 12 unresolved
#: modes still pass for normal ones near C_p = 0.
N_NODES = 33
#: Largest pseudo-arclength step (scaled state norm; the family spans ~1 from the TR
#: point to C_p = 0).
DS_MAX = 0.08
#: Radius (m, offset of the tub) of the first circle, born at the TR point.
FIRST_AMPLITUDE = 0.004
#: Integration tolerances of the map: those of the forced response (`washer.machine.forced`).
RTOL, ATOL = forced.RTOL, forced.ATOL
#: A multiplier is complex when |Im mu| > COMPLEX_TOL (the multipliers are ~1e-9 accurate).
COMPLEX_TOL = 1e-7


def frame_matrix(Omega: float, t: float) -> np.ndarray:
    """G(t) (12, 12): u = G(t) xi, ground-frame state of the rotating-frame state at time t
    (s), speed Omega (Hz): q = H eps, q_dot = w H' eps + H eps_dot (eqs 52, 55)."""
    w = TWO_PI * Omega
    H, H1 = forced._H(w * t)
    G = np.zeros((12, 12))
    G[:6, :6] = H
    G[6:, :6] = w * H1
    G[6:, 6:] = H
    return G


def half_period_map(params: Params, name: str = "C_p"):
    """fmap(X (m, 12), p) -> (P(X) (m, 12), DP (m, 12, 12), dP/dp (m, 12)): the stroboscopic
    map over T/2 in rotating coordinates at `params` with parameter `name` = p (any of
    `forced.PARAMETERS` but Omega, which sets the map's period). p moves the kernel
    parameters `layout.moved_by` it (C_p its tied dampers) unchecked: the map is defined
    on both sides of a physical bound (the continuation's trial points locate an end value
    C_p = 0 from both sides)."""
    if name == "Omega":
        raise ValueError("half_period_map: Omega sets the map's period; continue in another "
                         "parameter")
    Om = params["Omega"]
    T2 = 0.5 / Om
    G0, G1inv = frame_matrix(Om, 0.0), np.linalg.inv(frame_matrix(Om, T2))
    P0, d = params.vector(), forced.direction_of(params.tied, name)
    moved = [layout.INDEX[c] for c in layout.moved_by(name, params.tied)]

    def fmap(X, p):
        P = P0.copy()
        P[moved] = float(p)
        X = np.atleast_2d(X)
        F, DF, Fp = np.empty_like(X), np.empty((X.shape[0], 12, 12)), np.empty_like(X)
        for j, xi in enumerate(X):
            u1, Phi, s, _ = kernel.flow_variational(0.0, T2, G0 @ xi, P, "constant", d,
                                                    RTOL, ATOL)
            F[j], DF[j], Fp[j] = G1inv @ u1, G1inv @ Phi @ G0, G1inv @ s
        return F, DF, Fp
    return fmap


def scale(Omega: float) -> np.ndarray:
    """Component scales of xi for the continuation's inner product: m and rad for eps,
    (m, rad)/s over 2 pi Omega for eps_dot (so a whirl of r metres counts r in each)."""
    return np.r_[np.ones(6), np.full(6, TWO_PI * Omega)]


def whirl_frequency(rho, Omega: float):
    """Ground-frame whirl frequency (Hz) of rotation number rho (turns per T/2)."""
    return 2.0 * Omega * (np.asarray(rho) % 1.0 - 0.5)


@dataclass
class Birth:
    """The TR point as the birth of the circles: parameter value, the fixed point xi* (12,)
    of the T/2 map, its critical multiplier mu (|mu| = 1) and eigenvector v (12,) complex,
    oriented (eps1 + i eps2 counter-clockwise in theta)."""
    value: float
    xi: np.ndarray
    mu: complex
    v: np.ndarray

    @property
    def rho(self) -> float:
        return float(np.angle(self.mu) / TWO_PI % 1.0)


def birth(params: Params, name: str = "C_p", bracket=None) -> Birth:
    """The TR point of the forced response in `name` (default bracket: around the averaged
    Hopf value, as `washer.problems.forced.critical_cp`) and the T/2 map's critical
    eigenpair there."""
    if name == "C_p" and bracket is None:
        c = shooting.critical_cp(params)
        value, u0 = c["C_p_exact"], c["response"].u0
    else:
        r, rec = shooting.locate_tr(params, name, bracket)
        value, u0 = float(rec.par[PAR_INDEX[name] - 1]), r.u0
    q = params.replace(**{name: value})
    xi = forced.rotating_from_ground(u0, q["Omega"], 0.0)
    _, DF, _ = half_period_map(q, name)(xi[None, :], value)
    lam, V = np.linalg.eig(DF[0])
    cand = [i for i in np.argsort(-np.abs(lam))[:4] if abs(lam[i].imag) > COMPLEX_TOL]
    i = cand[0]
    v = V[:, i]
    if (v[1] / v[0]).imag > 0:           # eps2 leads eps1: clockwise; take the conjugate pair
        v, lam_i = v.conj(), lam[i].conj()
    else:
        lam_i = lam[i]
    return Birth(float(value), xi, complex(lam_i), v)


@dataclass
class ExactWhirl:
    """The continued family of invariant circles, and what it means for the machine.

    branch: the engine's `Branch` of the run (b-rows, status); circles: its circles
    (`invariant_circle.Circle`, in the order continued); birth: the `Birth`; name: the
    parameter. Per circle (arrays): value (parameter), rho, f_whirl (Hz, ground frame), mu_max
    (the largest normal multiplier modulus per T/2), stable; r_min/r_mean/r_max (m: the tub's
    distance from the axis sqrt(eps1^2 + eps2^2) over the torus), z_min/z_max (m: eps3),
    tilt_max (rad: the tub axis' angle from vertical), tail (the last Fourier amplitude over
    the first, components scaled by `scale`: the truncation's relative size), amplitude
    (m: the whirl's own size, |c_1| of eps1 + i eps2 = sum c_k e^{ik theta} on the circle,
    about its centre, which the imbalance puts off the axis)."""
    name: str
    birth: Birth
    branch: Branch
    circles: list
    params: Params
    r_min: np.ndarray
    r_mean: np.ndarray
    r_max: np.ndarray
    z_min: np.ndarray
    z_max: np.ndarray
    tilt_max: np.ndarray
    tail: np.ndarray
    amplitude: np.ndarray

    @property
    def value(self) -> np.ndarray:
        return np.array([c.p for c in self.circles])

    @property
    def rho(self) -> np.ndarray:
        return np.array([c.rho for c in self.circles])

    @property
    def reached(self) -> bool:
        """Whether the family reached its end value (the run's last point is its UZ)."""
        return circle_runs.reached(self.branch)

    @property
    def f_whirl(self) -> np.ndarray:
        return whirl_frequency(self.rho, self.params["Omega"])

    @property
    def mu_max(self) -> np.ndarray:
        """The largest normal multiplier modulus per T/2 of each circle."""
        return np.array([c.moduli.max() if c.moduli.size else np.nan for c in self.circles])

    @property
    def stable(self) -> np.ndarray:
        return np.array([c.stable for c in self.circles])


def torus_points(params: Params, circle: ic.Circle, n_theta: int = 64, n_t: int = 8):
    """Rotating-frame states (n_theta * n_t, 12) on the torus: the circle at n_theta angles
    flowed over [0, T/2) at n_t times (kernel DOPRI5 at RTOL)."""
    Om = params["Omega"]
    T2 = 0.5 / Om
    t = np.arange(n_t) * T2 / n_t
    G0 = frame_matrix(Om, 0.0)
    P = params.vector()
    out = []
    for xi in circle(np.linspace(0.0, TWO_PI, n_theta, endpoint=False)):
        Y, _, _ = kernel.integrate("fixed", "constant", 0.0, G0 @ xi, P, t, RTOL, ATOL)
        out.append(forced.rotating_from_ground(Y, Om, t))
    return np.concatenate(out)


def tilt(eps) -> np.ndarray:
    """Angle (rad) of the tub's axis from the vertical, Cardan angles eps4, eps5 (n, 12):
    A = Rx(alpha) Ry(beta) Rz(gamma), so the axis A e_z has z component cos(alpha) cos(beta)."""
    eps = np.atleast_2d(eps)
    return np.arccos(np.clip(np.cos(eps[:, 3]) * np.cos(eps[:, 4]), -1.0, 1.0))


def params_at(params: Params, name: str, value: float) -> Params:
    """`params` with `name` = value, where a value on the wrong side of a parameter's bound
    (C_p >= 0) by no more than the rounding of a located end value (the engine's
    UZ_ROUNDING: the run locates C_p = 0 from both sides) is the bound itself."""
    from washer.cont.iterator import UZ_ROUNDING
    try:
        return params.replace(**{name: value})
    except ValueError:
        if abs(value) > UZ_ROUNDING:
            raise
        return params.replace(**{name: 0.0})


def measure(params: Params, name: str, b: Birth, br: Branch) -> ExactWhirl:
    """The machine's quantities along the family (`ExactWhirl`) of the engine's run br."""
    rows = []
    found = circle_runs.circles(br)
    for c in found:
        q = params_at(params, name, c.p)
        Y = torus_points(q, c, n_theta=48, n_t=6)
        r = np.hypot(Y[:, 0], Y[:, 1])
        amp = ic.amplitudes(c.X / scale(q["Omega"]))
        z = c.X[:, 0] + 1j * c.X[:, 1]
        c1 = np.fft.fft(z)[1] / c.N
        rows.append((r.min(), r.mean(), r.max(), Y[:, 2].min(), Y[:, 2].max(),
                     tilt(Y).max(), amp[-1] / amp[1], abs(c1)))
    cols = [np.array(x) for x in zip(*rows)]
    return ExactWhirl(name, b, br, found, params, *cols)


def exact_whirl(params: Params, stop: float = 0.0, name: str = "C_p", *, N: int = N_NODES,
                ds: float = 0.02, ds_max: float = DS_MAX, max_points: int = 80,
                sinks=()) -> ExactWhirl:
    """The invariant circles of the T/2 map from the TR point in `name` (default C_p) to
    `name` = stop, with rotation numbers and normal multipliers (`ExactWhirl`).

    The first circle has radius FIRST_AMPLITUDE (m) along the critical eigenvector (its
    parameter found by Newton: near the birth the amplitude, not the parameter, is the
    coordinate); then the engine's run (`washer.cont.circle_runs.continue_circles`:
    pseudo-arclength in the inner product of `scale`, UZSTOP at `stop`, PAR as e='washer'
    numbers them) through `sinks` (b-/s-/d-files, the screen: washer.auto.sinks)."""
    b = birth(params, name)
    fmap = half_period_map(params, name)
    # first_circle scales v to a unit largest component: ask for the amplitude that makes
    # the (eps1, eps2) offset FIRST_AMPLITUDE.
    a = FIRST_AMPLITUDE * np.abs(b.v).max() / np.abs(b.v[:2]).max()
    first = circle_runs.first_circle(fmap, b.xi, b.v, b.rho, b.value, a, N)
    par = np.zeros(max(layout.PAR_NAMES) + 1)
    set_par(par, params)
    br = circle_runs.continue_circles(
        fmap, first, stop, index=PAR_INDEX[name], par=par, ds=ds, ds_max=ds_max,
        max_points=max_points, scale=scale(params["Omega"]), sinks=sinks,
        name=f"washer circles in {name}")
    return measure(params, name, b, br)


# ------------------------------------------------------------------ the long simulation beside it

def nearest_on_circle(circle: ic.Circle, xi, weights=None, n_grid: int = 1024) -> tuple:
    """For states xi (m, 12): the angle theta (m,) of the nearest point of the circle in the
    weighted norm |W (xi - x(theta))| (W = 1/weights, default `scale` of 10 Hz) and that
    distance (m,): grid search, then Newton on <x'(theta), W^2 (x(theta) - xi)> = 0."""
    xi = np.atleast_2d(np.asarray(xi, dtype=float))
    W2 = 1.0 / (np.ones(xi.shape[1]) if weights is None else np.asarray(weights)) ** 2
    X = circle.X
    D1, D2 = ic.shift_matrix(circle.N, 0.0, 1), ic.shift_matrix(circle.N, 0.0, 2)
    grid = np.linspace(0.0, TWO_PI, n_grid, endpoint=False)
    pts = circle(grid)
    d2 = ((xi[:, None, :] - pts[None, :, :]) ** 2 * W2).sum(-1)
    th = grid[np.argmin(d2, axis=1)]
    for _ in range(6):
        x, x1, x2 = ic.evaluate(X, th), ic.evaluate(D1 @ X, th), ic.evaluate(D2 @ X, th)
        g = ((x - xi) * x1 * W2).sum(1)
        dg = ((x1 * x1 + (x - xi) * x2) * W2).sum(1)
        th = th - g / dg
    dist = np.sqrt(((ic.evaluate(X, th) - xi) ** 2 * W2).sum(1))
    return th % TWO_PI, dist


def simulate_section(params: Params, xi0, t_end: float) -> tuple[np.ndarray, np.ndarray]:
    """The constant-speed ground-frame response (eq 48, kernel DOPRI5 at RTOL) from the
    rotating-frame state xi0 (12,) at t = 0, sampled at every half period: (t (m,),
    xi (m, 12) rotating-frame states), the orbit of the T/2 map."""
    Om = params["Omega"]
    T2 = 0.5 / Om
    t = np.arange(1, int(np.floor(t_end / T2)) + 1) * T2
    Y, _, _ = kernel.integrate("fixed", "constant", 0.0, frame_matrix(Om, 0.0) @ xi0,
                               params.vector(), t, RTOL, ATOL)
    return t, forced.rotating_from_ground(Y, Om, t)


def against_simulation(params: Params, circle: ic.Circle, xi0, t_end: float,
                       window: float = 20.0) -> dict:
    """The circle at `params` against a long simulation from xi0 (not on it): the weighted
    distance (m, `scale`) of every half-period sample from the circle, its decay rate fitted
    over the run's second half (1/s; the leading normal modulus predicts
    ln(mu_max) / (T/2)), and over the last `window` s: the largest distance, the
    simulation's own r = |eps1 + i eps2| mean and range, eps3 range, and its rotation number
    (the mean advance of the circle's angle per sample) beside the circle's."""
    Om = params["Omega"]
    t, xi = simulate_section(params, xi0, t_end)
    th, dist = nearest_on_circle(circle, xi, scale(Om))
    half = t >= t[-1] / 2
    rate = float(np.polyfit(t[half], np.log(dist[half]), 1)[0])
    last = t >= t[-1] - window
    adv = np.diff(np.unwrap(th[last])) / TWO_PI
    r = np.hypot(xi[last, 0], xi[last, 1])
    return {"t_end": float(t[-1]), "window": window, "t": t, "distance": dist,
            "decay_rate": rate,
            "predicted_rate": float(np.log(circle.moduli.max()) * 2 * Om),
            "distance_end": float(dist[last].max()),
            "r_mean": float(r.mean()), "r_min": float(r.min()), "r_max": float(r.max()),
            "z_min": float(xi[last, 2].min()), "z_max": float(xi[last, 2].max()),
            "rho": float(adv.mean() % 1.0), "rho_circle": circle.rho,
            "f_whirl": float(whirl_frequency(adv.mean(), Om))}


# ------------------------------------------------------------------ a design criterion

def damping_for_clearance(w: ExactWhirl, clearance) -> np.ndarray:
    """The joint damping C_p (N m s/rad) at which the whirl's largest offset from the axis
    r_max reaches `clearance` (m, scalar or array): below it the tub whirls farther. Read
    off the exact family, C_p interpolated against (r_max - r_0)^2 with r_0 the forced
    response's offset at the TR point (near it C_p,crit - C_p grows like the whirl's
    amplitude squared, so the interpolation is nearly linear there). nan where the
    clearance lies beyond the family's largest r_max (no damping in the range keeps it) or
    below r_0 (the forced response alone, the imbalance's offset, exceeds it)."""
    r0 = float(np.hypot(*w.birth.xi[:2]))
    v = np.r_[w.birth.value, w.value]
    a2 = (np.r_[r0, w.r_max] - r0) ** 2
    order = np.argsort(a2)
    c = np.asarray(clearance, dtype=float)
    out = np.interp((c - r0) ** 2, a2[order], v[order], right=np.nan)
    return np.where(c < r0, np.nan, out)


def growth_coefficient(w: ExactWhirl, a_fit: float = 0.02) -> float:
    """a (m / sqrt(N m s/rad)) in amplitude ~ a sqrt(C_p,crit - C_p), fitted (least squares
    through the origin in amplitude^2 against C_p,crit - C_p) over the circles with
    amplitude <= a_fit m."""
    d = w.birth.value - w.value
    keep = (w.amplitude <= a_fit) & (d > 0)
    return float(np.sqrt(np.sum(w.amplitude[keep] ** 2 * d[keep]) / np.sum(d[keep] ** 2)))
