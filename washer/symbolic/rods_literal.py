"""The paper's rod forces exactly as written (eqs 26-44, with errata 4 and 5).

Defined only where d x v != 0 (eq 28 divides by |d x v|). Kept as the check
of the smooth form the model uses (`washer.symbolic.rods`).
"""
from __future__ import annotations

import numpy as np


def rod_forces_literal(d, v, omega, K_s, C_a, C_p, C_ox, C_oz, l0, C_oy=None):
    """(F_o, M_o) on the rod at O (ground frame); C_oy defaults to C_oz."""
    C_oy = C_oz if C_oy is None else C_oy
    L = np.linalg.norm(d)
    t = np.cross(d, v)                                   # eq 26
    e1 = d / L                                           # eq 27
    e3 = t / np.linalg.norm(t)                           # eq 28
    e2 = np.cross(e3, e1)                                # eq 29
    F_s = -K_s * (L - l0)                                # eq 30
    F_va = C_a * (v @ e1)                                # eq 31
    v_y = v @ e2                                         # eq 32
    w_rod = -v_y / L                                     # eq 33 (erratum 4: |d|)
    M_pz = -C_p * w_rod                                  # eq 34
    M_oz = -C_oz * (w_rod - omega @ e3)                  # eq 36
    F_oy = (M_pz + M_oz) / L                             # eq 38
    M_oy = C_oy * (omega @ e2)                           # eq 39 (erratum 5)
    F_oz = -M_oy / L                                     # eq 41
    M_ox = C_ox * (omega @ e1)                           # eq 42 (erratum 5)
    F_o = (F_s + F_va) * e1 + F_oy * e2 + F_oz * e3      # eq 43
    M_o = M_ox * e1 + M_oy * e2 + M_oz * e3              # eq 44
    return F_o, M_o
