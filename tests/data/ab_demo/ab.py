"""AUTO-07p demo 'ab' exactly as demos/ab/ab.f90 (start PAR = 0, 8, 3; u = 0).

u1' = -u1 + p1 (1 - u1) e^u2,  u2' = -u2 + p1 p2 (1 - u1) e^u2 - p3 u2.
(tests/data/ab/ab.py starts elsewhere; its constants file overrides PAR.)
"""
import numpy as np


def func(u, par):
    e = np.exp(u[1])
    return np.array([-u[0] + par[0] * (1 - u[0]) * e,
                     -u[1] + par[0] * par[1] * (1 - u[0]) * e - par[2] * u[1]])


def stpnt(u, par, t=0.0):
    u[:2] = 0.0
    par[:3] = [0.0, 8.0, 3.0]
