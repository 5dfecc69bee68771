"""AUTO-07p demo 'tim' (demos/tim/tim.f90): five uncoupled Bratu problems (NDIM = 10) with
exp replaced by its 25-term Taylor polynomial, on NTST = 100 (a timing test)."""
import numpy as np


def fexp(u):
    out = np.ones_like(u)
    trm = np.ones_like(u)
    for k in range(1, 26):
        trm = trm * u / k
        out = out + trm
    return out


def func(u, par):
    f = np.empty_like(u)
    f[0::2] = u[1::2]
    f[1::2] = -par[0] * fexp(u[0::2])
    return f


def stpnt(u, par, t=0.0):
    u[:] = 0.0


def bcnd(u0, u1, par):
    fb = np.empty(len(u0))
    fb[0::2] = u0[0::2]
    fb[1::2] = u1[0::2]
    return fb
