"""Generalized forces of the suspension rods (paper eqs 23-46), smooth form.

The paper's rod frame (eqs 26-29) takes e3 = d x v / |d x v|, undefined when
the joint velocity v is zero or parallel to d (at every equilibrium). With
C_oy = C_oz the same forces have the smooth vector form of docs/model.md section 2,
used here; `washer.symbolic.rods_literal` keeps the literal eqs 30-44 and a
test checks that both agree wherever the literal ones are defined.
"""
from __future__ import annotations

import sympy as sp

from washer.symbolic.bodies import Rod, Structure
from washer.symbolic.kinematics import tilde


def rod_force_and_torque(d, v, w, K_s, C_a, C_p, C_ox, C_oz, l0):
    """Force F_o and torque M_o exerted on the rod at its lower joint O (ground frame).

    d = P - O (m), v = velocity of O (m/s), w = tub angular velocity (rad/s),
    all ground-frame 3-vectors. Equivalent to eqs 30-44 with C_oy = C_oz:
    spring (30) and axial damper (31) along e1; tangential joint dampings
    (32-42) as a force along v_perp and (omega x e1), and a joint torque.
    """
    L = sp.sqrt(d.dot(d))
    e1 = d / L
    v_axial = v.dot(e1)
    v_perp = v - v_axial * e1
    w_axial = w.dot(e1)
    F_o = (-K_s * (L - l0) + C_a * v_axial) * e1 \
        + (C_p + C_oz) * v_perp / L**2 + (C_oz / L) * w.cross(e1)
    M_o = C_ox * w_axial * e1 + C_oz * (w - w_axial * e1) + C_oz * d.cross(v) / L**2
    return F_o, M_o


def rod_generalized_force(rod: Rod, S: Structure, x, A, B, phi_dot, x_dot) -> sp.Matrix:
    """Generalized force (6-vector) of one rod on q (eq 45, corrected per docs/model.md).

    The tub receives F = -F_o at O and the torque T = -M_o; by virtual power
    Q = [F; (A B)^T ((A r_d) x F + T)].
    """
    r_d = sp.Matrix(rod.O)
    w_body = B * phi_dot                         # eq 4
    w = A * w_body                               # eq 35
    s_d = x + A * r_d                            # eq 23
    v = x_dot + A * tilde(w_body) * r_d          # eq 24 (erratum 3)
    d = sp.Matrix(rod.P) - s_d                   # eq 25
    F_o, M_o = rod_force_and_torque(d, v, w, S.K_s, S.C_a, S.C_p, S.C_ox, S.C_oz, S.l0)
    F, T = -F_o, -M_o
    arm = A * r_d
    return sp.Matrix.vstack(F, (A * B).T * (arm.cross(F) + T))   # eq 45


def suspension_force(S: Structure, x, A, B, phi_dot, x_dot) -> sp.Matrix:
    """Total generalized force of the suspension, Q = sum_i Q_i (eq 46)."""
    Q = sp.zeros(6, 1)
    for rod in S.rods:
        Q += rod_generalized_force(rod, S, x, A, B, phi_dot, x_dot)
    return Q
