"""Symbolic kinematics of the tub frame X_b Y_b Z_b (paper eqs 1-17).

Everything here is a sympy expression builder: no numbers, no solving.
Coordinates q = [x, y, z, alpha, beta, gamma] (m, m, m, rad, rad, rad): the
position of O_b (centre of plane A) in the ground frame and Cardan angles.
"""
from __future__ import annotations

import sympy as sp


def tilde(r: sp.Matrix) -> sp.Matrix:
    """Skew matrix of a 3-vector: tilde(r) @ v == r x v (the paper's r~)."""
    return sp.Matrix([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])


def rotation_rb(alpha, beta, gamma) -> sp.Matrix:
    """A^rb, tub frame -> ground frame, A = Rx(alpha) Ry(beta) Rz(gamma) (eq 2)."""
    ca, sa = sp.cos(alpha), sp.sin(alpha)
    cb, sb = sp.cos(beta), sp.sin(beta)
    cg, sg = sp.cos(gamma), sp.sin(gamma)
    return sp.Matrix([
        [cb * cg, -cb * sg, sb],
        [sa * sb * cg + ca * sg, -sa * sb * sg + ca * cg, -sa * cb],
        [-ca * sb * cg + sa * sg, ca * sb * sg + sa * cg, ca * cb],
    ])


def rate_matrix_b(beta, gamma) -> sp.Matrix:
    """B with omega_b = B phi_dot, omega_b expressed in the tub frame (eqs 4-5)."""
    cb, sb = sp.cos(beta), sp.sin(beta)
    cg, sg = sp.cos(gamma), sp.sin(gamma)
    return sp.Matrix([[cb * cg, sg, 0], [-cb * sg, cg, 0], [sb, 0, 1]])


def rotation_bc(theta_c) -> sp.Matrix:
    """A^bc of a spinning body, its own frame -> tub frame (eq 15)."""
    c, s = sp.cos(theta_c), sp.sin(theta_c)
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def eccentric_offset(R, theta_c) -> sp.Matrix:
    """u of a spinning body's mass centre about its axis (eq 11)."""
    return sp.Matrix([R * sp.cos(theta_c), R * sp.sin(theta_c), 0])
