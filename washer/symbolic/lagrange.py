"""Lagrange's equations of the washing/spinning assembly (paper eqs 8-22, 47-51).

Result: the mass matrix M(q, theta) (eq 49) and the generalized force
f(q, q_dot, theta, w, w_dot) such that M q_ddot = f (eq 48), where theta is
the prescribed basket angle, w = theta_dot, w_dot = theta_ddot (rad, rad/s,
rad/s^2). The spinning bodies' own equation (the theta row of eq 47) is
dropped because theta is prescribed.
"""
from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from washer.symbolic.bodies import Structure
from washer.symbolic.kinematics import (eccentric_offset, rate_matrix_b, rotation_bc,
                                     rotation_rb, tilde)
from washer.symbolic.rods import suspension_force


@dataclass(frozen=True)
class Coordinates:
    """The symbols the equations are written in."""
    q: sp.Matrix        # [x, y, z, alpha, beta, gamma]
    qd: sp.Matrix       # their rates
    theta: sp.Symbol    # basket angle (rad)
    w: sp.Symbol        # theta_dot (rad/s)
    wd: sp.Symbol       # theta_ddot (rad/s^2)


def coordinates() -> Coordinates:
    q = sp.Matrix(sp.symbols("x y z alpha beta gamma", real=True))
    qd = sp.Matrix(sp.symbols("xd yd zd alphad betad gammad", real=True))
    return Coordinates(q, qd, *sp.symbols("theta w wd", real=True))


@dataclass(frozen=True)
class EquationsOfMotion:
    M: sp.Matrix        # 6x6, eq 49
    f: sp.Matrix        # 6, right-hand side of eq 48 (everything but M q_ddot)
    coords: Coordinates


def _velocity_maps(S: Structure, c: Coordinates):
    """Per body: (m, Jv, bv, I, Jw, bw) with mass-centre velocity Jv qd + bv w
    (ground frame, eqs 6, 13) and angular velocity Jw qd + bw w with inertia I
    (both in tub-frame components, eqs 7, 14; the kinetic energy is invariant)."""
    A = rotation_rb(*c.q[3:, :])
    B = rate_matrix_b(c.q[4], c.q[5])
    I3, Z3 = sp.eye(3), sp.zeros(3, 3)
    e = sp.Matrix([0, 0, 1])
    out = []
    for body in S.tub_bodies:                                    # eqs 1-9
        r = sp.Matrix(body.r)
        Jv = sp.Matrix.hstack(I3, -A * tilde(r) * B)
        Jw = sp.Matrix.hstack(Z3, B)
        out.append((body.m, Jv, sp.zeros(3, 1), sp.diag(*body.J), Jw, sp.zeros(3, 1)))
    for body in S.spinning_bodies:                               # eqs 10-17
        th_c = body.ratio * c.theta
        u = eccentric_offset(body.R, th_c)
        r = sp.Matrix(body.axis) + u
        Jv = sp.Matrix.hstack(I3, -A * tilde(r) * B)
        bv = A * u.diff(c.theta)                                 # includes the ratio p_j
        Abc = rotation_bc(th_c)
        I_tub = Abc * sp.diag(*body.J) * Abc.T                   # inertia in tub axes
        Jw = sp.Matrix.hstack(Z3, B)
        out.append((body.m, Jv, bv, I_tub, Jw, e * body.ratio))
    return out


def equations_of_motion(S: Structure, c: Coordinates | None = None) -> EquationsOfMotion:
    """Lagrange's equations (eq 47) with theta prescribed (eq 48)."""
    c = c or coordinates()
    M = sp.zeros(6, 6)
    Gamma = sp.zeros(6, 1)          # eq 51: coupling of q_dot with theta_dot
    m_tt = sp.Integer(0)            # theta-theta inertia, for dT/dq
    for m, Jv, bv, I, Jw, bw in _velocity_maps(S, c):
        M += m * Jv.T * Jv + Jw.T * I * Jw                       # eqs 9, 16, 19
        Gamma += m * Jv.T * bv + Jw.T * I * bw
        m_tt += m * bv.dot(bv) + (bw.T * I * bw)[0, 0]
    # Kinetic energy, eq 18: T = 1/2 qd^T M qd + qd^T Gamma w + 1/2 m_tt w^2.
    T = (c.qd.T * M * c.qd)[0, 0] / 2 + (c.qd.T * Gamma)[0, 0] * c.w + m_tt * c.w**2 / 2
    # Geopotential energy, eqs 20-22.
    A = rotation_rb(*c.q[3:, :])
    V = sp.Integer(0)
    for body in S.tub_bodies:
        V += body.m * S.g * (c.q[2] + (A[2, :] * sp.Matrix(body.r))[0, 0])
    for body in S.spinning_bodies:
        r = sp.Matrix(body.axis) + eccentric_offset(body.R, body.ratio * c.theta)
        V += body.m * S.g * (c.q[2] + (A[2, :] * r)[0, 0])
    # Generalized momentum p = dT/dqd = M qd + Gamma w; its time derivative
    # along the motion, minus the M q_ddot part (eq 50's terms).
    p = M * c.qd + Gamma * c.w
    dp_dt = p.jacobian(c.q) * c.qd + p.diff(c.theta) * c.w + Gamma * c.wd
    dT_dq = sp.Matrix([T.diff(qi) for qi in c.q])
    dV_dq = sp.Matrix([V.diff(qi) for qi in c.q])
    B = rate_matrix_b(c.q[4], c.q[5])
    Q = suspension_force(S, c.q[:3, :], A, B, c.qd[3:, :], c.qd[:3, :])   # eq 46
    f = Q - dV_dq + dT_dq - dp_dt                                           # eq 48
    return EquationsOfMotion(M, f, c)
