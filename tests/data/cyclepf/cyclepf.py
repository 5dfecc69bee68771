"""A pitchfork of cycles with exact branches: a branch point of periodic orbits (BP of
cycles) at a known parameter, and both branches through it in closed form.

    x' = x (1 - r^2) - w y,   y' = y (1 - r^2) + w x,     z' = D z - |z|^2 z

with D = [[a, 1], [b, a]] (PAR(1) = a, PAR(2) = b > 0, PAR(3) = w) and, with PAR(4) = c,
c z1^2 added to z1' (c = 0 below; c != 0 breaks the symmetry z -> -z and makes the branch
point transcritical, at the same a, the primary cycle z = 0 unchanged). The cycle
x = cos(w t), y = sin(w t) with z = 0 exists for every a; its transverse multipliers are
exp((a +- sqrt(b)) T), T = 2 pi / w, and the symmetry z -> -z makes the crossing of +1
at a = -sqrt(b) a pitchfork: for a > -sqrt(b) the cycles with z constant,

    z = +- sqrt(lambda) (1, sqrt(b)) / sqrt(1 + b),   lambda = a + sqrt(b)

(D z = lambda z and |z|^2 = lambda), same period T. So the primary branch keeps z = 0
beyond the BP and the secondary one has max U(3) = sqrt(lambda / (1 + b)).
"""
import math

import numpy as np


def func(u, par):
    a, b, w = par[0], par[1], par[2]
    x, y, z1, z2 = u
    r2 = x * x + y * y
    q = z1 * z1 + z2 * z2
    return np.array([x * (1 - r2) - w * y, y * (1 - r2) + w * x,
                     a * z1 + z2 - q * z1 + par[3] * z1 * z1, b * z1 + a * z2 - q * z2])


def stpnt(u, par, t=0.0):
    par[0], par[1], par[2] = -0.83, 0.25, 2 * math.pi
    par[10] = 1.0
    u[0], u[1], u[2], u[3] = math.cos(2 * math.pi * t), math.sin(2 * math.pi * t), 0.0, 0.0
