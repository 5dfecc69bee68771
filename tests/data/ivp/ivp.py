"""AUTO-07p demo 'ivp' (demos/ivp/ivp.f90): time integration (IPS = -2) of
u1' = p2 u1 (1 - u1) - u1 u2 - p1 (1 - exp(-p3 u1)), u2' = -u2 + p4 u1 u2, the time in
PAR(14). STPNT's 0.3 is a single-precision constant in the Fortran file:
0.30000001192092896 in AUTO's output."""
import numpy as np


def func(u, par):
    e = np.exp(-par[2] * u[0])
    return np.array([par[1] * u[0] * (1 - u[0]) - u[0] * u[1] - par[0] * (1 - e),
                     -u[1] + par[3] * u[0] * u[1]])


def stpnt(u, par, t=0.0):
    par[:4] = [0.0, 3.0, 5.0, 3.0]
    u[:] = float(np.float32(0.3))
