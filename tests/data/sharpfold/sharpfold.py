"""An S-shaped branch whose two folds are very sharp.

mu = G(x) = s (x - r(x) + r(x - 1)),  r(y) = sqrt(eps^2 + y^2),

i.e. three straight arms of slope +s, -s, +s joined by folds near x = 0 (a
maximum of G) and x = 1 (a minimum) whose radius of curvature is about eps / s.
With s = 4 the arms meet at an angle whose tangents have a dot product of
-15/17, and with eps = 0.02 the radius (0.005) is far below DSMAX. The branch is
the graph of G, so x increases monotonically along it. PAR(1) = mu,
PAR(2) = s, PAR(3) = eps.
"""
import numpy as np


def _g(x, s, eps):
    return s * (x - np.sqrt(eps * eps + x * x) + np.sqrt(eps * eps + (x - 1) ** 2))


def func(u, par):
    return np.array([par[0] - _g(u[0], par[1], par[2])])


def stpnt(u, par):
    par[1:3] = [4.0, 0.02]
    u[0] = -1.0
    par[0] = _g(-1.0, par[1], par[2])
