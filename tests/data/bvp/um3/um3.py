"""AUTO-07p demo 'um3' (demos/um3/um3.f90): orbits of x' = T (eps x - y^3 + z^3),
y' = T (y + x^3), z' = T (-z + x^2) from a circle of radius r0 in z = 0 (angle theta)
to the sphere of radius r1; PAR = (theta, eps, r0, r1), PAR(11) = T."""
import math

import numpy as np


def func(u, par):
    eps, period = par[1], par[10]
    x, y, z = u
    return np.array([period * (eps * x - y ** 3 + z ** 3), period * (y + x ** 3),
                     period * (-z + x ** 2)])


def stpnt(u, par, t=0.0):
    theta, eps, r0, period = 0.25, 0.5, 0.03, 1e-4
    par[:4] = [theta, eps, r0, r0]
    par[10] = period
    u[0] = r0 * math.cos(2 * math.pi * theta)
    u[1] = r0 * math.sin(2 * math.pi * theta)
    u[2] = 0.0


def bcnd(u0, u1, par):
    theta, r0, r1 = par[0], par[2], par[3]
    return np.array([u0[0] - r0 * math.cos(2.0 * math.pi * theta),
                     u0[1] - r0 * math.sin(2.0 * math.pi * theta), u0[2],
                     math.sqrt(u1[0] ** 2 + u1[1] ** 2 + u1[2] ** 2) - r1])
