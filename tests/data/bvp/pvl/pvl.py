"""AUTO-07p demo 'pvl' (demos/pvl/pvl.f90): the 1-D Bratu problem u1' = u2,
u2' = -p1 exp(u1), u1(0) = u1(1) = 0, with a PVLS that writes solution measures into
PAR(2..5) (GETP: the L2 norm of U(1), the minimum of U(2), U(2) at t = 0, and U(2) at
the first node)."""
import numpy as np


def func(u, par):
    return np.array([u[1], -par[0] * np.exp(u[0])])


def stpnt(u, par, t=0.0):
    par[0] = 0.0
    u[:] = 0.0


def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0]])


def pvls(u, par):
    par[1] = u.norm(1)
    par[2] = u.min(2)
    par[3] = u.bv0(2)
    par[4] = u[0, 1]
