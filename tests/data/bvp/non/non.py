"""AUTO-07p demo 'non' (demos/non/non.f90): a non-autonomous BVP made autonomous,
u1' = u2, u2' = -p1 exp(x^3 u1), x' = 1; u1(0) = u1(1) = 0, x(0) = 0."""
import numpy as np


def func(u, par):
    return np.array([u[1], -par[0] * np.exp(u[2] ** 3 * u[0]), 1.0])


def stpnt(u, par, t=0.0):
    par[0] = 0.0
    u[0] = u[1] = 0.0
    u[2] = t


def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0], u0[2]])
