"""AUTO-07p demo 'plp' (a model of a chemical reaction), from demos/plp/plp.f90.

s' = (s0 - s) - rho R,  a' = alpha (a0 - a) - rho R,  R = s a / (1 + s + kappa s^2).
PAR(1..5) = s0, a0, alpha, rho, kappa. The demo's constants use JAC = 1, so
dfdu and dfdp are given as in the Fortran.
"""
import numpy as np


def _r(u, par):
    s, a = u
    rk = par[4]
    d = 1 + s + rk * s * s
    r = s * a / d
    drds = (a * d - s * a * (1 + 2 * rk * s)) / d**2
    drda = s / d
    drdk = -s**3 * a / d**2
    return r, drds, drda, drdk


def func(u, par):
    s, a = u
    s0, a0, al, rh = par[:4]
    r = _r(u, par)[0]
    return np.array([(s0 - s) - rh * r, al * (a0 - a) - rh * r])


def dfdu(u, par):
    al, rh = par[2], par[3]
    _, drds, drda, _ = _r(u, par)
    return np.array([[-1 - rh * drds, -rh * drda],
                     [-rh * drds, -al - rh * drda]])


def dfdp(u, par):
    s, a = u
    a0, rh = par[1], par[3]
    r, _, _, drdk = _r(u, par)
    out = np.zeros((2, len(par)))
    out[0, :5] = [1.0, 0.0, 0.0, -r, -rh * drdk]
    out[1, :5] = [0.0, par[2], a0 - a, -r, -rh * drdk]
    return out


def stpnt(u, par, t=0.0):
    par[:5] = [110.0, 500.0, 0.2, 2.021628, 0.1]
    u[:2] = [4.555974e+01, 1.777987e+02]
