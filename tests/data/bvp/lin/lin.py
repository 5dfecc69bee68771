"""AUTO-07p demo 'lin' (demos/lin/lin.f90): the linear eigenvalue problem u1' = u2,
u2' = -(p1 pi)^2 u1, u1(0) = p2, u1(1) = 0, int u1^2 dt = p3: eigenvalues p1 = 1, 2, ..."""
import math

import numpy as np


def func(u, par):
    return np.array([u[1], -(par[0] * math.pi) ** 2 * u[0]])


def stpnt(u, par, t=0.0):
    par[:3] = 0.0
    u[:] = 0.0


def bcnd(u0, u1, par):
    return np.array([u0[0] - par[1], u1[0]])


def icnd(u, uold, udot, upold, par):
    return np.array([u[0] * u[0] - par[2]])
