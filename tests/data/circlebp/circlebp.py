"""Two families of circles crossing: an exact branch point of cycles and its locus.

    x' = x g(r) - w(r) y,   y' = y g(r) + w(r) x          (r^2 = x^2 + y^2)
    g(r) = (r - p1) (exp(p2) - r) + p3,   w(r) = 1 + r^2

(PAR(1..3) = p1, p2, p3.) In polar form r' = r g(r), theta' = w(r): every zero r* > 0
of g is a circle of radius r*, period T = 2 pi / (1 + r*^2). For p3 = 0 the circles
r = p1 and r = exp(p2) cross at p1 = exp(p2): a transcritical bifurcation of cycles,
which persists along the curve p1 = exp(p2) in (p1, p2) (a non-generic BP: ISW = 2)
and, with p3 free, is the codimension-two set g = g_r = g_p1 = 0, i.e. p1 = exp(p2),
p3 = 0 (the generic case: ISW = 3). tests/test_cycle_branch_point.py derives that with sympy.
"""
import math

import numpy as np


def func(u, par):
    p1, p2, p3 = par[0], par[1], par[2]
    x, y = u
    r = math.sqrt(x * x + y * y)
    g = (r - p1) * (math.exp(p2) - r) + p3
    w = 1 + r * r
    return np.array([x * g - w * y, y * g + w * x])


def dfdu(u, par):
    p1, p2, p3 = par[0], par[1], par[2]
    x, y = u
    r = math.sqrt(x * x + y * y)
    g = (r - p1) * (math.exp(p2) - r) + p3
    w = 1 + r * r
    gr = (math.exp(p2) + p1 - 2 * r) / r              # g_r / r (w_r / r = 2)
    return np.array([[g + x * x * gr - 2 * x * y, x * y * gr - w - 2 * y * y],
                     [x * y * gr + w + 2 * x * x, g + y * y * gr + 2 * x * y]])


def stpnt(u, par, t=0.0):
    # on the circle r = exp(p2) = 1, where r = p1 = 0.5 is the other family
    par[0], par[1], par[2] = 0.5, 0.0, 0.0
    par[10] = math.pi                                  # T = 2 pi / (1 + 1)
    u[0], u[1] = math.cos(2 * math.pi * t), math.sin(2 * math.pi * t)
