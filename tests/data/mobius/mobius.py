"""A limit cycle with a Moebius-band transverse bundle: exact PD, TR and resonances.

    x' = x (1 - r^2) - w y,   y' = y (1 - r^2) + w x          (r^2 = x^2 + y^2)
    z' = B(x, y) z + (w / 2) J z - |z|^2 z                     (z = (z1, z2))

with J = [[0, -1], [1, 0]] and B(x, y) = R(theta/2) D R(-theta/2) written without
the half angle: for D = [[a, 1], [b, a]] (PAR(1) = a, PAR(2) = b),

    B = a I - (1 - b)/2 J + (1 + b)/2 [[-y, x], [x, y]]         (x, y = cos, sin theta on r = 1)

The cycle is x = cos(w t), y = sin(w t), z = 0, period T = 2 pi / w (PAR(3) = w). On it
w(t) = R(-w t / 2) z(t) obeys w' = D w, so z(T) = R(pi) exp(D T) z(0): the Floquet
multipliers are 1, exp(-2 T) (radial) and -exp((a +- sqrt(b)) T) (transverse), so

* b > 0: period doubling where a + sqrt(b) = 0 (or a - sqrt(b) = 0); the doubled
  orbit is z = R(w t / 2) w*, with w* the eigenvector of D for lambda = a + sqrt(b) and
  |w*|^2 = lambda (exact: w' = D w - |w|^2 w has that fixed point), period 2 T;
* b < 0: a complex pair -exp(a T) exp(+-i sqrt(-b) T): a torus bifurcation at a = 0
  with angle |arg mu| = pi - sqrt(-b) T (for sqrt(-b) T < pi); 1:4 at sqrt(-b) T = pi/2,
  1:3 at pi/3, 1:2 at b = 0, where the pair meets the negative real axis;
* the cycle itself never depends on a or b (continuation in a or b moves only the
  multipliers), so the located parameters are exact.
"""
import math

import numpy as np


def func(u, par):
    a, b, w = par[0], par[1], par[2]
    x, y, z1, z2 = u
    r2 = x * x + y * y
    q = z1 * z1 + z2 * z2
    s, k = 0.5 * (1 + b), 0.5 * (1 - b) - 0.5 * w      # J coefficient: -(1-b)/2 + w/2
    # B z + (w/2) J z = a z - k J z + s [[-y, x], [x, y]] z
    f3 = a * z1 + k * z2 + s * (-y * z1 + x * z2) - q * z1
    f4 = a * z2 - k * z1 + s * (x * z1 + y * z2) - q * z2
    return np.array([x * (1 - r2) - w * y, y * (1 - r2) + w * x, f3, f4])


def stpnt(u, par, t=0.0):
    par[0], par[1], par[2] = -0.5, -1.0, 2 * math.pi
    par[10] = 1.0                                    # T = 2 pi / w
    u[0], u[1], u[2], u[3] = math.cos(2 * math.pi * t), math.sin(2 * math.pi * t), 0.0, 0.0
