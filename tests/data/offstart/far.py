import numpy as np


def func(u, par):
    return np.array([u[0] ** 2 + 1.0 + 0 * par[0]])


def stpnt(u, par):
    u[0] = 0.3
    par[0] = 1.0
