"""A chain of pitchforks (tests/closed_form_exact.py has its exact special points).

x1' = x1 (mu + x1^2 - x1^4)              pitchfork at mu = 0, folds at x1^2 = 1/2
x2' = x2 (x1^2 - a - x2^2)               pitchfork on the x1-branches at x1^2 = a
x3' = x3 (x2^2 - c - x3^2)               pitchfork on the x2-branches at x2^2 = c
x4' = (x2^2 - b) x4 - w x5 - x4 r^2      Hopf on the x2-branches at x2^2 = b
x5' = w x4 + (x2^2 - b) x5 - x5 r^2      (r^2 = x4^2 + x5^2)

Every x_i -> -x_i (and (x4, x5) -> -(x4, x5)) is a symmetry, so the two sides of
every pitchfork are mirror images. PAR(1) = mu, PAR(2..5) = a, b, c, w.
"""
import numpy as np


def func(u, par):
    x1, x2, x3, x4, x5 = u
    mu, a, b, c, w = par[:5]
    r2 = x4 * x4 + x5 * x5
    g = x2 * x2 - b
    return np.array([x1 * (mu + x1**2 - x1**4),
                     x2 * (x1**2 - a - x2**2),
                     x3 * (x2**2 - c - x3**2),
                     g * x4 - w * x5 - x4 * r2,
                     w * x4 + g * x5 - x5 * r2])


def stpnt(u, par):
    u[:] = 0.0
    par[:5] = [-0.9, 1.2, 0.1, 0.3, 2.0]
