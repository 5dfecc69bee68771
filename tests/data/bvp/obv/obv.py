"""AUTO-07p demo 'obv' (demos/obv/obv.f90): optimisation of a BVP by continuation of
the extended system (the adjoint u3, u4 and the multipliers PAR(13..18)); icnd gives
five integrands of which the run uses the first NINT (3, 4 or 5)."""
import numpy as np


def func(u, par):
    p = u[0] + par[1] * u[0] ** 2 + par[2] * u[0] ** 4
    e = np.exp(p)
    return np.array([u[1], -par[0] * e,
                     par[0] * e * (1 + 2 * par[1] * u[0] + 4 * par[2] * u[0] ** 3) * u[3]
                     + par[14] * 2 * (u[0] - 1.0),
                     -u[2]])


def stpnt(u, par, t=0.0):
    par[0] = 0.001
    par[9] = 1.0
    u[:] = 0.0


def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0], u0[2] - par[12], u0[3], u1[2] + par[13], u1[3]])


def icnd(u, uold, udot, upold, par):
    p = u[0] + par[1] * u[0] ** 2 + par[2] * u[0] ** 4
    e = np.exp(p)
    return np.array([u[2] ** 2 - par[15],
                     par[9] - (u[0] - 1.0) ** 2 - 0.1 * (par[0] ** 2 + par[1] ** 2 + par[2] ** 2),
                     -e * u[3] - par[14] * 0.2 * par[0],
                     -par[0] * e * u[0] ** 2 * u[3] - par[14] * 0.2 * par[1] - par[16],
                     -par[0] * e * u[0] ** 4 * u[3] - par[14] * 0.2 * par[2] - par[17]])
