"""AUTO-07p demo 'ezp' (demos/ezp/ezp.f90): Bratu's problem in complex variables,
u1' = u2, u2' = -lam exp(u1), u1(0) = u1(1) = 0, u complex. The Fortran file declares U,
F, FB COMPLEX(KIND(1.0D0)) with NDIM = 4 reals: AUTO sees (Re u1, Im u1, Re u2, Im u2),
and the real fold of Bratu's problem is a branch point into complex solutions."""
import numpy as np


def func(u, par):
    u1 = u[0] + 1j * u[1]
    e = -par[0] * np.exp(u1)
    return np.array([u[2], u[3], e.real, e.imag])


def stpnt(u, par, t=0.0):
    u[:] = 0.0


def bcnd(u0, u1, par):
    return np.array([u0[0], u0[1], u1[0], u1[1]])
