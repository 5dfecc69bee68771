"""AUTO-07p demo 'ext' (demos/ext/ext.f90): u1' = u2, u2' = -(p1 pi)^2 sin(u1 + u1^2 +
u1^3), u1(0) = u1(1) = 0: branch points on the trivial branch at p1 = 1, 2, 3, ..."""
import math

import numpy as np


def func(u, par):
    p = u[0] + u[0] ** 2 + u[0] ** 3
    return np.array([u[1], -(par[0] * math.pi) ** 2 * np.sin(p)])


def stpnt(u, par, t=0.0):
    par[0] = 0.0
    u[:] = 0.0


def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0]])
