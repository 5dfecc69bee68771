"""AUTO-07p demo 'spb' (demos/spb/spb.f90): a singularly perturbed BVP,
eps u1'' = rl (u1 (u1^2 - 1) u1' + u1), u1(0) = 3/2, u1(1) = gamma; PAR = (gamma, eps, rl)."""
import numpy as np


def func(u, par):
    eps, rl = par[1], par[2]
    return np.array([u[1], rl * (u[0] * (u[0] ** 2 - 1) * u[1] + u[0]) / eps])


def stpnt(u, par, t=0.0):
    par[:3] = [1.2, 0.1, 0.0]
    s = 1.2 - 1.5
    u[0] = 1.5 + s * t
    u[1] = s


def bcnd(u0, u1, par):
    return np.array([u0[0] - 1.5, u1[0] - par[0]])
