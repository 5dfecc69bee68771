"""AUTO-07p demo 'fsh' (demos/fsh/fsh.f90): Fisher's travelling waves as a connecting
orbit, u1' = T u2, u2' = T (c u2 - u1 (1 - u1)), with the unstable eigenvector of the
saddle (1, 0) in PAR(12..14), PAR(2) = c, PAR(4) = eps1, PAR(11) = T."""
import math

import numpy as np


def ffff(u, par):
    c = par[1]
    f = np.array([u[1], c * u[1] - u[0] * (1 - u[0])])
    dfdu = np.array([[0.0, 1.0], [-1 + 2 * u[0], c]])
    return f, dfdu


def func(u, par):
    return par[10] * np.array([u[1], par[1] * u[1] - u[0] * (1 - u[0])])


def stpnt(u, par, t=0.0):
    if t == 0:
        period, c, ep1 = 0.01, 11.0, 0.001
        d = math.sqrt(c * c + 4)
        par[1] = c
        par[3] = ep1
        par[10] = period
        par[11] = (c - d) / 2
        par[12] = 1.0 / math.sqrt(1 + par[11] ** 2)
        par[13] = par[11] / math.sqrt(1 + par[11] ** 2)
    c, ep1 = par[1], par[3]
    d = math.sqrt(c * c + 4)
    rmu1 = (c - d) / 2
    v11 = 1.0 / math.sqrt(1 + rmu1 ** 2)
    v12 = rmu1 / math.sqrt(1 + rmu1 ** 2)
    u[0] = 1 - ep1 * v11
    u[1] = -ep1 * v12


def bcnd(u0, u1, par):
    v1 = np.array([u1[0] + par[3] * par[12], u1[1] + par[3] * par[13]])
    g1, dg = ffff(v1, par)
    return np.array([dg[0, 0] * par[12] + dg[0, 1] * par[13] - par[11] * par[12],
                     dg[1, 0] * par[12] + dg[1, 1] * par[13] - par[11] * par[13],
                     par[12] ** 2 + par[13] ** 2 - 1, g1[0], g1[1]])


def icnd(u, uold, udot, upold, par):
    f, dfdu = ffff(u, par)
    f0, _ = ffff(uold, par)
    return np.array([(f[0] - f0[0]) * (dfdu[0, 0] * f[0] + dfdu[0, 1] * f[1])
                     + (f[1] - f0[1]) * (dfdu[1, 0] * f[0] + dfdu[1, 1] * f[1])])
