"""A forced linear oscillator made autonomous as in AUTO's demo 'frc':

    v' = w,  w' = F0 x - 2 zeta w0 w - w0^2 v          (x replaces cos(nu t))
    x' =  x + nu y - x (x^2 + y^2),   y' = -nu x + y - y (x^2 + y^2)

The appended oscillator's stable limit cycle is x = sin(nu t), y = cos(nu t), so the
forcing F0 cos(nu t) is F0 y. PAR(1..4) = F0, zeta, w0, nu (rad/s); PAR(11) = period
2 pi / nu. stpnt(u, par, t): the exact periodic solution at F0 = 0 (v = w = 0, the
oscillator on its cycle) at the scaled time t in [0, 1], as frc's STPNT at r = 0.
"""
import numpy as np


def func(u, par):
    F0, zeta, w0, nu = par[:4]
    v, w, x, y = u
    ss = x * x + y * y
    return np.array([w, F0 * y - 2 * zeta * w0 * w - w0 * w0 * v,
                     x + nu * y - x * ss, -nu * x + y - y * ss])


def stpnt(u, par, t=0.0):
    par[:4] = [0.0, 0.05, 3.0, 2.3]
    par[10] = 2 * np.pi / par[3]
    u[:4] = [0.0, 0.0, np.sin(2 * np.pi * t), np.cos(2 * np.pi * t)]
