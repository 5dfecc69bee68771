"""AUTO-07p demo 'stw' (demos/stw/stw.f90): a sharp travelling wave as a connecting
orbit, u1' = T fa(u1) u2, u2' = T (-c u2 - fb(u1) u2^2 - fc(u1)), its coefficients
homotoped by PAR(1); the end points on the saddles' eigenvectors (PAR(12..19)) and an
integral phase condition."""
import numpy as np


def coefficients(par):
    s = par[0]
    return {2: 2.0, 3: s, 4: 2 * (1 - s), 5: s, 6: 0.0, 7: 0.0, 8: 1.0, 9: -1.0}


def ffff(u, par):
    p = coefficients(par)
    fa = p[2] * u[0] + p[3] * u[0] ** 2
    fb = p[4] + p[5] * u[0] + p[6] * u[0] ** 2
    fc = p[7] + p[8] * u[0] + p[9] * u[0] ** 2
    c = par[9]
    f = np.array([fa * u[1], -c * u[1] - fb * u[1] ** 2 - fc])
    dfa = p[2] + 2 * p[3] * u[0]
    dfb = p[5] + 2 * p[6] * u[0]
    dfc = p[8] + 2 * p[9] * u[0]
    dfdu = np.array([[dfa * u[1], fa], [-dfb * u[1] ** 2 - dfc, -c - 2 * fb * u[1]]])
    return f, dfdu


def func(u, par):
    return par[10] * ffff(u, par)[0]


def stpnt(u, par, t=0.0):
    period = 100.0
    par[0] = 0.0
    par[9] = 1.0
    par[10] = period
    par[11] = 0.5 * np.sqrt(5.0) / (1 + np.exp(0.5 * period))
    par[12] = par[11]
    par[13] = 1.0
    par[14] = -1.0
    par[15] = 2 / np.sqrt(5.0)
    par[16] = 1 / np.sqrt(5.0)
    par[17] = 1.0
    par[18] = 0.0
    e = np.exp(period * (t - 0.5))
    u[0] = 1 / (1 + e)
    u[1] = -0.5 * e / (1 + e)


def bcnd(u0, u1, par):
    v0 = np.array([u0[0] - par[11] * par[15], u0[1] - par[11] * par[16]])
    v1 = np.array([u1[0] - par[12] * par[17], u1[1] - par[12] * par[18]])
    g0, d0 = ffff(v0, par)
    g1, d1 = ffff(v1, par)
    return np.array([d0[0, 0] * par[15] + d0[0, 1] * par[16] - par[13] * par[15],
                     d0[1, 0] * par[15] + d0[1, 1] * par[16] - par[13] * par[16],
                     d1[0, 0] * par[17] + d1[0, 1] * par[18] - par[14] * par[17],
                     d1[1, 0] * par[17] + d1[1, 1] * par[18] - par[14] * par[18],
                     par[15] ** 2 + par[16] ** 2 - 1, par[17] ** 2 + par[18] ** 2 - 1,
                     g0[0], g0[1], g1[0], g1[1]])


def icnd(u, uold, udot, upold, par):
    f, dfdu = ffff(u, par)
    f0, _ = ffff(uold, par)
    return np.array([(f[0] - f0[0]) * (dfdu[0, 0] * f[0] + dfdu[0, 1] * f[1])
                     + (f[1] - f0[1]) * (dfdu[1, 0] * f[0] + dfdu[1, 1] * f[1])])
