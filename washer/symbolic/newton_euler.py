"""Independent, pure-numpy equations of motion by Newton-Euler and virtual power.

Written by hand without sympy or the paper's Lagrangian route, as the second
derivation the kernel is tested against, and as the pure-numpy baseline of the
benchmarks. Slow on purpose-free grounds: clarity first.

For each rigid body: mass-centre acceleration s_ddot = Jv q_ddot + bias_v and
angular acceleration alpha = Jw q_ddot + bias_w (ground frame); the generalized
equations are sum_b [Jv^T m s_ddot + Jw^T (I alpha + w x I w)] = Q_gravity + Q_rods.
"""
from __future__ import annotations

import numpy as np

from washer.machine.params import Params

E3 = np.array([0.0, 0.0, 1.0])


def skew(r):
    return np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])


def rotation(alpha, beta, gamma):
    """A = Rx(alpha) Ry(beta) Rz(gamma), tub -> ground."""
    ca, sa, cb, sb, cg, sg = (np.cos(alpha), np.sin(alpha), np.cos(beta), np.sin(beta),
                              np.cos(gamma), np.sin(gamma))
    Rx = np.array([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
    Ry = np.array([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]])
    Rz = np.array([[cg, -sg, 0], [sg, cg, 0], [0, 0, 1]])
    return Rx @ Ry @ Rz


def rate_matrix(beta, gamma):
    """B and dB/dt-factors: omega_body = B phi_dot; returns (B, dB/dbeta, dB/dgamma)."""
    cb, sb, cg, sg = np.cos(beta), np.sin(beta), np.cos(gamma), np.sin(gamma)
    B = np.array([[cb * cg, sg, 0], [-cb * sg, cg, 0], [sb, 0, 1]])
    dB_db = np.array([[-sb * cg, 0, 0], [sb * sg, 0, 0], [cb, 0, 0]])
    dB_dg = np.array([[-cb * sg, cg, 0], [-cb * cg, -sg, 0], [0, 0, 0]])
    return B, dB_db, dB_dg


def bodies(params: Params, theta: float, w: float, wd: float):
    """Rigid bodies at basket angle theta: (m, r, r_dot, r_ddot, J_tub_axes, spin, spin_dot),
    with r the mass centre in the tub frame and spin the angular velocity relative
    to the tub (tub axes)."""
    v = params.values
    out = [(v["m_t"], np.array([v["r_tx"], v["r_ty"], v["r_tz"]]), np.zeros(3), np.zeros(3),
            np.diag([v["J_tx"], v["J_ty"], v["J_tz"]]), np.zeros(3), np.zeros(3))]
    c, s = np.cos(theta), np.sin(theta)
    Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    Jb = Rz @ np.diag([v["J_bt"], v["J_bt"], v["J_bz"]]) @ Rz.T
    out.append((v["m_b"], np.array([0, 0, v["h_b"]]), np.zeros(3), np.zeros(3), Jb,
                E3 * w, E3 * wd))
    R = v["R_u"]
    u = R * np.array([c, s, 0])
    du = R * np.array([-s, c, 0])
    out.append((v["m_u"], np.array([0, 0, v["h_u"]]) + u, du * w, -u * w**2 + du * wd,
                np.zeros((3, 3)), E3 * w, E3 * wd))
    return out


def rod_forces_smooth(d, v, omega, K_s, C_a, C_p, C_ox, C_oz, l0):
    """(F_o, M_o) on the rod at O, smooth form of docs/model.md section 2 (ground frame)."""
    L = np.linalg.norm(d)
    e1 = d / L
    va = v @ e1
    wa = omega @ e1
    F = (-K_s * (L - l0) + C_a * va) * e1 + (C_p + C_oz) * (v - va * e1) / L**2 \
        + (C_oz / L) * np.cross(omega, e1)
    M = C_ox * wa * e1 + C_oz * (omega - wa * e1) + C_oz * np.cross(d, v) / L**2
    return F, M


def rod_kinematics(params: Params, q, qd):
    """Per rod: (d = P - O, velocity of O, lever A r_d), and the tub's omega, all ground frame."""
    A = rotation(*q[3:])
    B, _, _ = rate_matrix(q[4], q[5])
    w_body = B @ qd[3:]
    omega = A @ w_body
    out = []
    for P, O in zip(params.upper_joints(), params.lower_joints()):
        arm = A @ O
        out.append((P - (q[:3] + arm), qd[:3] + A @ np.cross(w_body, O), arm))
    return out, omega, A, B


def suspension_force(params: Params, q, qd, rod_forces=rod_forces_smooth) -> np.ndarray:
    """Generalized force (6,) of all rods; the tub receives -F_o and -M_o."""
    v = params.values
    rods, omega, A, B = rod_kinematics(params, q, qd)
    Q = np.zeros(6)
    for d, vel, arm in rods:
        F_o, M_o = rod_forces(d, vel, omega, v["K_s"], v["C_a"], v["C_p"], v["C_ox"],
                              v["C_oz"], v["l0"])
        F, T = -F_o, -M_o
        Q[:3] += F
        Q[3:] += (A @ B).T @ (np.cross(arm, F) + T)
    return Q


def mass_and_bias(params: Params, q, qd, theta, w, wd):
    """M (6, 6) and h (6,) with M q_ddot + h = Q_rods (gravity in h)."""
    g = params["g"]
    A = rotation(*q[3:])
    B, dB_db, dB_dg = rate_matrix(q[4], q[5])
    phid = qd[3:]
    w_b = B @ phid
    Bdot_phid = (dB_db * qd[4] + dB_dg * qd[5]) @ phid
    M = np.zeros((6, 6))
    h = np.zeros(6)
    for m, r, rd, rdd, J, spin, spin_d in bodies(params, theta, w, wd):
        Jv = np.hstack([np.eye(3), -A @ skew(r) @ B])
        bias_v = A @ (np.cross(Bdot_phid, r) + np.cross(w_b, np.cross(w_b, r))
                      + 2 * np.cross(w_b, rd) + rdd)
        Jw = np.hstack([np.zeros((3, 3)), A @ B])
        Om = w_b + spin                        # body's angular velocity, tub axes
        omega = A @ Om
        bias_w = A @ (Bdot_phid + spin_d + np.cross(w_b, spin))
        Ig = A @ J @ A.T
        M += m * Jv.T @ Jv + Jw.T @ Ig @ Jw
        h += m * Jv.T @ bias_v + Jw.T @ (Ig @ bias_w + np.cross(omega, Ig @ omega))
        h -= Jv.T @ (m * np.array([0, 0, -g]))
    return M, h


def accelerations(params: Params, q, qd, theta, w, wd) -> np.ndarray:
    """q_ddot (6,) at basket angle theta (rad), rate w (rad/s), acceleration wd (rad/s^2)."""
    q, qd = np.asarray(q, float), np.asarray(qd, float)
    M, h = mass_and_bias(params, q, qd, theta, w, wd)
    return np.linalg.solve(M, suspension_force(params, q, qd) - h)


def speed_law(t, params: Params, law: str):
    """(theta, w, wd) of the constant-speed or spin-up law (eq 66), Omega in Hz."""
    W = 2 * np.pi * params["Omega"]
    if law == "constant":
        return W * t, W, 0.0
    ts = params["tau_s"]
    e = np.exp(-t / ts)
    return W * (t - ts * (1 - e)), W * (1 - e), W * e / ts


def rhs_fixed(t, u, params: Params, law: str = "spinup") -> np.ndarray:
    """Pure-numpy du/dt of eq 48 (the benchmark's baseline)."""
    th, w, wd = speed_law(t, params, law)
    return np.concatenate([u[6:], accelerations(params, u[:6], u[6:], th, w, wd)])


def energy(params: Params, u, theta=0.0) -> float:
    """Kinetic + gravity + spring energy (J) at rest basket (w = 0)."""
    q, qd = np.asarray(u[:6], float), np.asarray(u[6:], float)
    M, _ = mass_and_bias(params, q, np.zeros(6), theta, 0.0, 0.0)
    A = rotation(*q[3:])
    V = sum(m * params["g"] * (q[2] + (A @ r)[2])
            for m, r, *_ in bodies(params, theta, 0.0, 0.0))
    rods, _, _, _ = rod_kinematics(params, q, qd)
    V += sum(0.5 * params["K_s"] * (np.linalg.norm(d) - params["l0"]) ** 2 for d, _, _ in rods)
    return 0.5 * qd @ M @ qd + V
