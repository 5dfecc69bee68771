"""AUTO-07p demo 'lor' (the Lorenz equations), from demos/lor/lor.f90: the periodic
branch starts from numerical data (lor.dat, dat='lor': rows t, u1, u2, u3 of one period
of an orbit at PAR(1) = 280), then switches at two period doublings.

u1' = PAR(3) (u2 - u1),  u2' = PAR(1) u1 - u2 - u1 u3,  u3' = u1 u2 - PAR(2) u3.
"""
import numpy as np


def func(u, par):
    x, y, z = u
    return np.array([par[2] * (y - x), par[0] * x - y - x * z, x * y - par[1] * z])


def stpnt(u, par, t=0.0):
    # the parameter values of the starting orbit in lor.dat (the orbit itself is read
    # from the data file)
    par[0], par[1], par[2] = 280.0, 8.0 / 3.0, 10.0
