"""A branch that runs into a wall: x' = x - mu for mu <= 1, NaN beyond.

The branch x = mu has no continuation past mu = 1, so every step whose
predictor crosses the wall fails and is halved until it falls below DSMIN;
the run then ends with MX at the last converged point, within about
sqrt(2) DSMIN of the wall (the branch makes 45 degrees with the mu axis).
PAR(1) = mu.
"""
import numpy as np


def func(u, par):
    if par[0] > 1.0:
        return np.array([np.nan])
    return np.array([u[0] - par[0]])


def stpnt(u, par):
    u[0] = 0.0
    par[0] = 0.0
