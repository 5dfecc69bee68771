"""AUTO-07p demo 'man' (demos/man/man.f90): the Lorenz system's stable manifold of the
origin grown as orbits from a circle of radius PAR(4) in the plane of the eigenvectors
V1, V2 (angle h = PAR(5)), end points PAR(6..8), |u(1)| = PAR(9), arclength-like integral
int |f| dt = PAR(12). The Fortran's 1./2.66667 and 22.8277 are single-precision
constants (REAL), as evaluated there."""
import math

import numpy as np

V13 = float(np.float32(1.0) / np.float32(2.66667))
SCALE = float(np.float32(22.8277))


def eigv(par):
    v1 = np.array([0.0, 0.0, V13])
    e = -(11 + math.sqrt(1201.0)) / 2
    v2 = np.array([1 + e, par[0], 0.0])
    ss = math.sqrt(v2[0] ** 2 + v2[1] ** 2)
    v2[:2] = v2[:2] / (ss * SCALE)
    return v1, v2


def func(u, par):
    period = par[10]
    return period * np.array([par[2] * (u[1] - u[0]),
                              par[0] * u[0] - u[1] - u[0] * u[2],
                              u[0] * u[1] - par[1] * u[2]])


def stpnt(u, par, t=0.0):
    par[0] = 28.0
    par[1] = 8.0 / 3.0
    par[2] = 10.0
    rad, h, period = 5.0, 0.1, 1e-5
    par[3] = rad
    par[4] = h
    v1, v2 = eigv(par)
    theta = 2 * math.pi * h
    u[:] = rad * (math.cos(theta) * v1 + math.sin(theta) * v2)
    par[5:8] = u
    par[8] = math.sqrt(np.sum(u ** 2))
    par[10] = period
    par[11] = 0.0


def bcnd(u0, u1, par):
    v1, v2 = eigv(par)
    theta = 2 * math.pi * par[4]
    w = par[3] * (math.cos(theta) * v1 + math.sin(theta) * v2)
    return np.array([u0[0] - w[0], u0[1] - w[1], u0[2] - w[2], u1[0] - par[5],
                     u1[1] - par[6], u1[2] - par[7],
                     math.sqrt(u1[0] ** 2 + u1[1] ** 2 + u1[2] ** 2) - par[8]])


def icnd(u, uold, udot, upold, par):
    f = func(u, par)
    return np.array([math.sqrt(f[0] ** 2 + f[1] ** 2 + f[2] ** 2) - par[11]])
