"""AUTO demo 'lrz' (Lorenz): x' = s (y - x), y' = r x - y - x z, z' = x y - b z.
PAR(1) = rho, PAR(2) = beta, PAR(3) = sigma (par[i - 1] is PAR(i))."""
import numpy as np


def func(u, par):
    x, y, z = u
    rho, beta, sigma = par[0], par[1], par[2]
    return np.array([sigma * (y - x), rho * x - y - x * z, x * y - beta * z])


def stpnt(u, par):
    u[:] = 0.0
    par[:3] = [0.0, 8.0 / 3.0, 10.0]
