"""A driven rotor whose rotations have an exact period (a pendulum-like system on the
cylinder: U(1) = theta grows by 2 pi per period).

    theta' = v,   v' = a cos(theta) v + k (w + a sin(theta) - v)

The curve v = w + a sin(theta) is invariant (on it v' = a cos(theta) theta') and
attracting for k > 0; on it theta' = w + a sin(theta), a rotation (|a| < w) of period

    T = int_0^{2 pi} d theta / (w + a sin theta) = 2 pi / sqrt(w^2 - a^2).

PAR(1) = a, PAR(2) = w, PAR(3) = k. The start (a = 0) is theta = 2 pi t, v = w, T = 2 pi / w.
"""
import math

import numpy as np


def func(u, par):
    a, w, k = par[0], par[1], par[2]
    th, v = u
    return np.array([v, a * np.cos(th) * v + k * (w + a * np.sin(th) - v)])


def stpnt(u, par, t=0.0):
    par[0], par[1], par[2] = 0.0, 1.0, 1.0
    par[10] = 2 * math.pi
    u[0], u[1] = 2 * math.pi * t, 1.0
