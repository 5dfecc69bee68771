"""A user value (PVLS) that jumps: a UZR on it cannot be located.

x' = x - mu; pvls sets PAR(2) = 0 while x < 1/2 and 1 beyond. UZR = {2: 0.5} then
changes sign by a jump at mu = 1/2 with no zero to converge to: AUTO's locator gives
up ("NOTE:Possible special point" in the d-file), labels nothing and goes on.
PAR(1) = mu, PAR(2) = the user value.
"""
import numpy as np


def func(u, par):
    return np.array([u[0] - par[0]])


def stpnt(u, par):
    u[0] = 0.0
    par[:2] = [0.0, 0.0]


def pvls(u, par):
    par[1] = 0.0 if u[0] < 0.5 else 1.0
