"""AUTO-07p demo 'bvp' (demos/bvp/bvp.f90): u1' = u2, u2' = -(p1 pi)^2 u1 + u1^2 on
[0, 1], u1(0) = u1(1) = 0, int_0^1 (u1 - p2) dt = 0. The trivial branch u = 0 has
branch points at p1 = 1, 2, 3, ... (the eigenvalues of the linearisation)."""
import math

import numpy as np


def func(u, par):
    return np.array([u[1], -(par[0] * math.pi) ** 2 * u[0] + u[0] ** 2])


def stpnt(u, par, t=0.0):
    par[0] = par[1] = 0.0
    u[:] = 0.0


def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0]])


def icnd(u, uold, udot, upold, par):
    return np.array([u[0] - par[1]])
