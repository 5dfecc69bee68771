"""A family of cycles whose fold is a branch point of cycles: an exact BP at an LP.

    x' = x g - w y,   y' = y g + w x,   z' = z h          (r^2 = x^2 + y^2)
    g = p1 - (r^2 - 1)^2,   w = 1 + r^2,   h = (r^2 - 1) ((r^2 - 1)^2 + p2)

(PAR(1), PAR(2) = p1, p2.) On z = 0 (invariant) the polar form is r' = r g, theta' = w:
every zero r* > 0 of g is a circle of radius r*, period T = 2 pi / (1 + r*^2), and the
family p1 = (r^2 - 1)^2 folds at r = 1, p1 = 0 (its minimum in p1). The multiplier
across the plane is exp(h(r*) T): it passes 1 at r = 1, the fold, where the circles
with z != 0 (z' = 0 needs h = 0) meet the family: a branch point of cycles at its fold
tip, PAR(1) = 0, MAX U(1) = r = 1, T = pi. Along the family the BP test is the in-plane
determinant (regular at a fold) times 1 - exp(h T): a zero of order 1 for p2 > 0 and of
order 3 for p2 = 0 (tfc's iso-periodic cycles show such a zero of high order at a fold
tip). tests/test_cycle_branch_point.py derives that with sympy.
"""
import math

import numpy as np


def _parts(u, par):
    p1, p2 = par[0], par[1]
    x, y, z = u
    e = x * x + y * y - 1                             # r^2 - 1
    return p1, p2, x, y, z, e, p1 - e * e, 2 + e, e * (e * e + p2)


def func(u, par):
    p1, p2, x, y, z, e, g, w, h = _parts(u, par)
    return np.array([x * g - w * y, y * g + w * x, z * h])


def dfdu(u, par):
    p1, p2, x, y, z, e, g, w, h = _parts(u, par)
    # d/dx of e is 2 x; g_e = -2 e, w_e = 1, h_e = 3 e^2 + p2
    gx, gy = -4 * e * x, -4 * e * y
    wx, wy = 2 * x, 2 * y
    he = 3 * e * e + p2
    return np.array([[g + x * gx - wx * y, x * gy - w - wy * y, 0.0],
                     [y * gx + w + wx * x, g + y * gy + wy * x, 0.0],
                     [z * he * 2 * x, z * he * 2 * y, h]])


def stpnt(u, par, t=0.0):
    # on the circle r = 1/2 (p1 = (1/4 - 1)^2), inside the fold
    par[0], par[1] = 0.5625, 0.0
    par[10] = 2 * math.pi / 1.25
    u[0], u[1], u[2] = 0.5 * math.cos(2 * math.pi * t), 0.5 * math.sin(2 * math.pi * t), 0.0
