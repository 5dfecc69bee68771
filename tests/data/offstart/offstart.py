"""f(u, p) = u - p, started off its solutions: STPNT u = 0.01, p = 0 (|f| = 0.01).

The solutions are the line u = p. AUTO writes the start as given at PT 1; its first
(unwritten) step goes from the start along the null vector (1, 1)/sqrt(2) of [f_u f_p]
onto the sphere of radius DS about the start: u = p = t with (t - 0.01)^2 + t^2 = DS^2.
PAR(1) = p.
"""
import numpy as np


def func(u, par):
    return np.array([u[0] - par[0]])


def stpnt(u, par):
    u[0] = 0.01
    par[0] = 0.0
