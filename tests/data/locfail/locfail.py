"""A BP test function that changes sign by a jump, so its zero cannot be located.

x1' = x1 - mu,  x2' = c(x1) x2  with c = +1 for x1 < 1/2 and -1 beyond.

The branch x1 = mu, x2 = 0 is regular everywhere, but the Jacobian's
determinant jumps from +1 to -1 at mu = 1/2: the BP test function changes sign
there with no zero to converge to. AUTO's locator gives up after ITMX
iterations, writes "NOTE:Possible special point" in the d-file, labels nothing
and goes on. PAR(1) = mu.
"""
import numpy as np


def func(u, par):
    c = 1.0 if u[0] < 0.5 else -1.0
    return np.array([u[0] - par[0], c * u[1]])


def stpnt(u, par):
    u[:] = 0.0
    par[0] = 0.0
