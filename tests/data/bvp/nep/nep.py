"""AUTO-07p demo 'nep' (demos/nep/nep.f90): a nonlinear eigenvalue problem,
u1' = u2, u2' = -p2 u1, u3' = -u2^2/2 - p2; u1(0) = u1(1) = 0, u3(0) = p1, u3(1) = -p1."""
import numpy as np


def func(u, par):
    return np.array([u[1], -par[1] * u[0], -u[1] ** 2 / 2 - par[1]])


def stpnt(u, par, t=0.0):
    par[:2] = 0.0
    u[:] = 0.0


def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0], u0[2] - par[0], u1[2] + par[0]])
