"""AUTO demo 'ab' (A -> B reaction): u1' = -u1 + p1 (1 - u1) e^u2,
u2' = -u2 + p1 p2 (1 - u1) e^u2 - p3 u2. PAR(i) is par[i - 1]."""
import numpy as np


def func(u, par):
    e = np.exp(u[1])
    return np.array([-u[0] + par[0] * (1 - u[0]) * e,
                     -u[1] + par[0] * par[1] * (1 - u[0]) * e - par[2] * u[1]])


def stpnt(u, par):
    u[:] = 0.0
    par[:3] = [0.0, 14.0, 2.0]
