"""AUTO-07p demo 'chu' (Chua's circuit), from demos/chu/chu.f90.

x' = alpha (y - h(x)),  y' = x - y + z,  z' = -beta y, with the smooth
piecewise-linear h(x) = a1 x + (a0 - a1) (|x + 1| - |x - 1|) / 2 where |v| is
approximated by 2 v atan(RK v) / pi. PAR(1..5) = alpha, beta, RK, a0, a1.
"""
import numpy as np


def func(u, par):
    alpha, beta, rk, a0, a1 = par[:5]
    x, y, z = u

    def ab(v):
        return 2 * v * np.arctan(rk * v) / np.pi

    h = a1 * x + 0.5 * (a0 - a1) * (ab(x + 1) - ab(x - 1))
    return np.array([alpha * (y - h), x - y + z, -beta * y])


def stpnt(u, par, t=0.0):
    par[:5] = [-1.0, 14.3, 10.0, -1.0 / 7.0, 2.0 / 7.0]
    u[:3] = 0.0
