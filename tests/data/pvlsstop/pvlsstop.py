"""PVLS stops, after AUTO's pp2 demo (PAR(9) = U(1) set in PVLS, UZSTOP on it).

x1' = mu - x1 - x1^3,  x2' = x1 - x2.  The branch is x1 = x2 with mu = x1 + x1^3,
so x1 = 1/2 is reached at mu = 5/8 exactly. PAR(1) = mu; PVLS sets PAR(9) = U(1).
"""
import numpy as np


def func(u, par):
    return np.array([par[0] - u[0] - u[0] ** 3, u[0] - u[1]])


def stpnt(u, par):
    u[:] = 0.0
    par[0] = 0.0


def pvls(u, par):
    par[8] = u[0]
