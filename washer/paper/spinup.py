"""Why the tub lifts in Figs 10-11: the spin-up torque against the suspension's yaw
stiffness, and the choice of a slower spin-up (paper section 3.2.2, eq 66).

The motor sits on the tub, so the torque that accelerates the basket and the
imbalance about the spin axis acts back on the tub as a yaw moment. With the
law of eq 66, theta_ddot = (Omega / tau_s) e^(-t / tau_s) (Omega in rad/s), it
peaks at t = 0:

    T_peak = (J_bz + m_u R_u^2) * theta_ddot(0)

(basket polar inertia plus the imbalance's, about the spin axis). The four rods
hold the tub in yaw like a quadrifilar pendulum: `yaw_curve` computes the
static moment-angle curve of the model at rest (Omega = 0) under an applied yaw
moment Q (the generalised force conjugate to gamma, eq 45's moment about the
tub's z axis), continued in Q from 0 until it folds: where the twisted tub, pushed
sideways by the imbalance, tips over (an imperfect pitchfork; `twist_curve` follows
the symmetric tub's moment past its own tilt pitchfork, near the twist where the rods
turn tangent to the tub). Beyond it the tub turns until the rods lie almost flat,
which raises it (the 350-400 mm of Figs 10-11).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from washer.cont.newton import ConvergenceError, newton
from washer.machine import kernel
from washer.machine.equilibria import EquilibriumError, follow
from washer.machine.model import Model

#: Dynamic amplification allowed for in the slow spin-up: a load applied as a step
#: (eq 66's torque jumps to its peak at t = 0) drives an undamped linear oscillator
#: to at most twice its static deflection, so T_peak <= M_max / 2 keeps even the
#: overshoot below the moment at which the twisted tub tips.
STEP_AMPLIFICATION = 2.0
#: Finite-difference step of the yaw-curve Jacobian (m, rad): sqrt(machine eps)
#: relative to the O(1) coordinates.
FD_STEP = 1e-7
#: Newton's residual tolerance on the twist curve: max|acc| <= NEWTON_TOL (1 + max|x|),
#: accelerations in m/s^2 and rad/s^2, x = (x, y, z, alpha, beta, Q) (m, rad, N m: |x|
#: is |Q|, up to ~60 N m). Every point of the paper's curves meets it within 30 steps.
NEWTON_TOL = 1e-10
#: Applied yaw moment the continuation aims for (N m), beyond any fold met.
Q_TARGET = 200.0


@dataclass
class SpinTorque:
    """The spin-up torque of eq 66 (reaction on the tub, about its axis).

    J_spin: J_bz + m_u R_u^2 (kg m^2); theta_ddot0: peak angular acceleration
    (rad/s^2); T_peak: J_spin * theta_ddot0 (N m); impulse: J_spin * Omega, the
    angular momentum given to the basket (N m s)."""
    tau_s: float
    J_spin: float
    theta_ddot0: float
    T_peak: float
    impulse: float


def spin_torque(params) -> SpinTorque:
    """Peak of (J_bz + m_u R_u^2) theta_ddot(t) for the law of eq 66 (kernel's speed law)."""
    v = params.values
    J = v["J_bz"] + v["m_u"] * v["R_u"] ** 2
    _, w_end, _ = kernel.speed_law(1e9, params.vector(), "spinup")    # theta_dot at t -> inf
    _, _, wd0 = kernel.speed_law(0.0, params.vector(), "spinup")
    return SpinTorque(v["tau_s"], J, float(wd0), float(J * wd0), float(J * w_end))


@dataclass
class YawCurve:
    """Static yaw moment-angle curve at rest (Omega = 0, imbalance on +x).

    Q: applied yaw moment (n,) N m (negative: the sign of the spin-up reaction);
    gamma (n,) rad, z (n,) m: the tub's yaw and height there; k_lin: linearised
    yaw stiffness -dQ/dgamma at Q = 0 from the static Jacobian (N m/rad);
    M_max: |Q| where the curve folds (N m): the twisted tub, pushed sideways by the
    imbalance at rest, tips there (an imperfect pitchfork: without the imbalance the
    moment keeps rising and the tub loses tilt stability at a pitchfork instead, see
    `twist_curve`); gamma_max,
    z_max: yaw and height at the fold."""
    Q: np.ndarray
    gamma: np.ndarray
    z: np.ndarray
    k_lin: float
    M_max: float
    gamma_max: float
    z_max: float
    q0: np.ndarray = field(repr=False, default=None)


def yaw_curve(params, sign: float = -1.0) -> YawCurve:
    """Continue the static equilibrium under an applied yaw moment Q = sign * |Q|
    from 0 until it folds (washer.machine.equilibria.follow); the residual is the
    acceleration M^-1 (f(q) + Q e_gamma) at rest (eq 48 with an added generalised
    force), its Jacobian by forward differences."""
    m = Model(params)
    q0 = np.asarray(m.static_equilibrium())
    P = params.replace(Omega=0.0).vector()
    z6, e6 = np.zeros(6), np.eye(6)[5]

    def res(q, Q):
        M, f = kernel.mass_forces(q, z6, 0.0, 0.0, 0.0, P)
        return np.linalg.solve(M, f + e6 * Q[0])

    def jac(q, Q):
        r0 = res(q, Q)
        return np.column_stack([(res(q + FD_STEP * e, Q) - r0) / FD_STEP for e in np.eye(6)])

    # Linearised stiffness: at rest f(q0) = 0, so d acc / dq = M^-1 df/dq exactly
    # and df/dq = M J; -dQ/dgamma with the other five free is the Schur complement.
    M, _ = kernel.mass_forces(q0, z6, 0.0, 0.0, 0.0, P)
    F = M @ kernel.jac_fixed(0.0, np.r_[q0, z6], P, "constant")[0][6:, :6]
    r = slice(0, 5)
    k_lin = -(F[5, 5] - F[5, r] @ np.linalg.solve(F[r, r], F[r, 5]))

    pts = [(0.0, q0)]
    try:
        follow(res, jac, q0, np.zeros(1), np.array([sign * Q_TARGET]), what="yaw curve",
               on_step=lambda q, Q: pts.append((float(Q[0]), q.copy())))
        end = None
    except EquilibriumError as exc:
        q_end, Q_end, _ = exc.partial
        end = (float(Q_end[0]), q_end)
    Q = np.array([p[0] for p in pts])
    X = np.array([p[1] for p in pts])
    if end is None:        # pragma: no cover - the reference set folds near 18 N m
        raise RuntimeError(f"yaw curve: no fold up to |Q| = {Q_TARGET} N m")
    return YawCurve(Q, X[:, 5], X[:, 2], float(k_lin), abs(end[0]), float(end[1][5]),
                    float(end[1][2]), q0)


def slow_tau_s(params, curve: YawCurve) -> float:
    """The spin-up time constant for the 'realistic' runs: the smallest whole
    second with T_peak <= M_max / STEP_AMPLIFICATION (s)."""
    st = spin_torque(params.replace(tau_s=1.0))        # T_peak is proportional to 1/tau_s
    return float(math.ceil(st.T_peak * STEP_AMPLIFICATION / curve.M_max))


@dataclass
class YawResponse:
    """The tub's yaw and lift during the spin-up of a run (ground frame), t <= t_max.

    gamma_peak: max |gamma| (rad) at t_peak (s); lift: max z - z(0) (m) at t_lift (s)."""
    gamma_peak: float
    t_peak: float
    lift: float
    t_lift: float
    t_max: float


def yaw_response(r, t_max: float) -> YawResponse:
    """Over t <= t_max (3 tau_s: the speed at 95 %, the torque at 5 % of its peak), so
    that a whirl growing later (C_p = 0) is not counted as the spin-up's lift."""
    sel = r.t <= t_max
    g, z, t = r.y[sel, 5], r.y[sel, 2], r.t[sel]
    i, k = int(np.argmax(np.abs(g))), int(np.argmax(z))
    return YawResponse(float(abs(g[i])), float(t[i]), float(z[k] - z[0]), float(t[k]), t_max)


@dataclass
class TwistCurve:
    """The yaw moment needed to hold the tub at rest at a prescribed twist, and whether
    it stays upright there.

    gamma (n,) rad (the sign of the spin-up reaction); Q (n,) N m: the applied yaw moment
    holding it (the other five coordinates in equilibrium); z (n,) m; stiffness (n,)
    1/s^2: the smallest eigenvalue of -d(acc)/dq at fixed Q (> 0: the twisted tub is
    stable, < 0: it tips); gamma_tip, Q_tip: where that eigenvalue crosses zero (nan if it
    does not); gamma_into_tub: the twist beyond which the rods, seen from above, head into
    the tub (arccos(R_O / R_P): the rod leaves its lower joint inwards)."""
    gamma: np.ndarray
    Q: np.ndarray
    z: np.ndarray
    stiffness: np.ndarray
    gamma_tip: float
    Q_tip: float
    gamma_into_tub: float


def twist_curve(params, gamma_end: float = -1.2, n: int = 49) -> TwistCurve:
    """Q(gamma) at rest (Omega = 0) from gamma = 0 to gamma_end: Newton on the six
    accelerations in (x, y, z, alpha, beta, Q) at each prescribed gamma (continued from the
    last), forward-difference Jacobian. Unlike `yaw_curve` (continuation in Q, which stops
    where the curve folds), the twist is the coordinate, so the moment is followed past
    the point where the tub tips: without the imbalance that point is a pitchfork of the
    symmetric tub (its tilt stiffness vanishes), with it a fold (the imperfect pitchfork)."""
    m = Model(params)
    q = np.asarray(m.static_equilibrium(), dtype=float).copy()
    P = params.replace(Omega=0.0).vector()
    z6, e6 = np.zeros(6), np.eye(6)[5]

    def acc(qq, Q):
        M, f = kernel.mass_forces(qq, z6, 0.0, 0.0, 0.0, P)
        return np.linalg.solve(M, f + e6 * Q)

    def newton_step(x, r, g):
        """-J^-1 r, J the forward-difference Jacobian of the accelerations in
        (x, y, z, alpha, beta, Q) at twist g, from r = their values at x."""
        J = np.empty((6, 6))
        for k in range(6):
            dx = np.zeros(6)
            dx[k] = FD_STEP
            J[:, k] = (acc(np.r_[(x + dx)[:5], g], (x + dx)[5]) - r) / FD_STEP
        return -np.linalg.solve(J, r)

    G, Qs, Z, S = [], [], [], []
    Q = 0.0
    for g in np.linspace(0.0, gamma_end, n):
        # The package's one Newton, undamped, from the last point: the accelerations
        # (m/s^2, rad/s^2) to NEWTON_TOL (1 + max|x|); a point it does not reach is an
        # error naming the twist, never a silently unconverged row.
        try:
            x, _ = newton(lambda x: acc(np.r_[x[:5], g], x[5]),
                          lambda x, r, it: newton_step(x, r, g), np.r_[q[:5], Q],
                          max_iter=30, residual_tol=NEWTON_TOL)
        except ConvergenceError as exc:
            raise EquilibriumError(f"twist_curve at gamma = {g:.4f} rad: {exc}") from None
        q, Q = np.r_[x[:5], g], x[5]
        A = np.column_stack([(acc(q + FD_STEP * e, Q) - acc(q, Q)) / FD_STEP for e in np.eye(6)])
        G.append(g)
        Qs.append(Q)
        Z.append(q[2])
        S.append(float(np.min(np.linalg.eigvals(-A).real)))
    G, Qs, Z, S = map(np.array, (G, Qs, Z, S))
    tip = np.flatnonzero((S[:-1] > 0) & (S[1:] <= 0))
    if tip.size:
        i = tip[0]
        f = S[i] / (S[i] - S[i + 1])
        g_tip, Q_tip = G[i] + f * (G[i + 1] - G[i]), Qs[i] + f * (Qs[i + 1] - Qs[i])
    else:
        g_tip = Q_tip = np.nan
    up, lo = params.upper_joints(), params.lower_joints()
    into = float(np.arccos(np.hypot(*lo[0, :2]) / np.hypot(*up[0, :2])))
    return TwistCurve(G, Qs, Z, S, float(g_tip), float(Q_tip), into)
