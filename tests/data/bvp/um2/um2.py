"""AUTO-07p demo 'um2' (demos/um2/um2.f90): orbits of x' = T (eps x - y^3),
y' = T (y + x^3) from a circle of radius r0 (angle theta) to a circle of radius r1;
PAR = (theta, eps, r0, r1), PAR(11) = T."""
import math

import numpy as np


def func(u, par):
    eps, period = par[1], par[10]
    x, y = u
    return np.array([period * (eps * x - y ** 3), period * (y + x ** 3)])


def stpnt(u, par, t=0.0):
    theta, eps, r0, period = 0.25, 0.5, 0.1, 1e-4
    par[:4] = [theta, eps, r0, r0]
    par[10] = period
    u[0] = r0 * math.cos(2 * math.pi * theta)
    u[1] = r0 * math.sin(2 * math.pi * theta)


def bcnd(u0, u1, par):
    theta, r0, r1 = par[0], par[2], par[3]
    return np.array([u0[0] - r0 * math.cos(2.0 * math.pi * theta),
                     u0[1] - r0 * math.sin(2.0 * math.pi * theta),
                     math.sqrt(u1[0] ** 2 + u1[1] ** 2) - r1])
