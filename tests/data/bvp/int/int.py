"""AUTO-07p demo 'int' (demos/int/int.f90): u1' = u2, u2' = -p1 exp(u1) with the
boundary condition u1(0) - u1(1) = p2 and the integral condition int u1 dt = p3;
JAC = 1 (dfdu, dfdp given)."""
import numpy as np


def func(u, par):
    return np.array([u[1], -par[0] * np.exp(u[0])])


def dfdu(u, par):
    return np.array([[0.0, 1.0], [-par[0] * np.exp(u[0]), 0.0]])


def dfdp(u, par):
    out = np.zeros((2, len(par)))
    out[1, 0] = -np.exp(u[0])
    return out


def stpnt(u, par, t=0.0):
    par[:3] = 0.0
    u[:] = 0.0


def bcnd(u0, u1, par):
    return np.array([u0[0] - u1[0] - par[1]])


def icnd(u, uold, udot, upold, par):
    return np.array([u[0] - par[2]])
