"""AUTO-07p demo 'dd2' (a discrete predator-prey map), from demos/dd2/dd2.f90.

u1 -> p1 u1 (1 - u1) - p2 u1 u2,  u2 -> (1 - p3) u2 + p2 u1 u2.
"""
import numpy as np


def func(u, par):
    p1, p2, p3 = par[:3]
    return np.array([p1 * u[0] * (1 - u[0]) - p2 * u[0] * u[1],
                     (1 - p3) * u[1] + p2 * u[0] * u[1]])


def dfdu(u, par):
    p1, p2, p3 = par[:3]
    return np.array([[p1 * (1 - 2 * u[0]) - p2 * u[1], -p2 * u[0]],
                     [p2 * u[1], 1 - p3 + p2 * u[0]]])


def dfdp(u, par):
    out = np.zeros((2, len(par)))
    out[0, 0] = u[0] * (1 - u[0])
    out[0, 1] = -u[0] * u[1]
    out[1, 1] = u[0] * u[1]
    return out


def stpnt(u, par, t=0.0):
    par[:3] = [0.0, 0.2, 0.1]
    u[:2] = 0.0
