"""AUTO-07p demo 'log' (the logistic map), from demos/log/log.f90.

x -> mu x (1 - x); PAR(1) = mu. Fixed points x = 0 and x = 1 - 1/mu; period
doublings at mu = 3, 1 + sqrt(6), ...
"""
import numpy as np


def func(u, par):
    return np.array([par[0] * u[0] * (1 - u[0])])


def dfdu(u, par):
    return np.array([[par[0] * (1 - 2 * u[0])]])


def dfdp(u, par):
    out = np.zeros((1, len(par)))
    out[0, 0] = u[0] * (1 - u[0])
    return out


def stpnt(u, par, t=0.0):
    par[0] = 0.0
    u[0] = 0.0
