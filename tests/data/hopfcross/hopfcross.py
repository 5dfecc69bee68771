"""Two Hopf loci that cross, with a Bautin (GH) point on one of them
(tests/closed_form_exact.py has the exact points).

x0' = x0 (p2 - x0)                       equilibria E1: x0 = 0 and E2: x0 = p2
y1' = h y1 - w y2 + l y1 (y1^2 + y2^2)   (they exchange stability at p2 = 0)
y2' = w y1 + h y2 + l y2 (y1^2 + y2^2)

with h = p1 - p2 - x0 - p2^2 / 2 and l = x0 - 1/2. Hopf locus of E1:
p1 = p2 + p2^2/2; of E2: p1 = 2 p2 + p2^2/2. They cross at p = (0, 0), where E1
and E2 meet, so the Hopf-curve system has a branch point there. The first
Lyapunov coefficient is l / w, zero on E2's locus at x0 = p2 = 1/2 (GH).
PAR(1) = p1, PAR(2) = p2, PAR(3) = w, PAR(4) = k: the rotation terms are
w exp(+-k p2) y (k = 0 by default). k = 1 keeps both loci and the GH but makes the
frequency depend on p2, so that at the crossing the ZH test's linear zero
estimate comes before the BP test's (found in review: the type reported at the
crossing must not depend on which estimate is smaller).
"""
import numpy as np


def func(u, par):
    x0, y1, y2 = u
    p1, p2, w, k = par[:4]
    h = p1 - p2 - x0 - p2 * p2 / 2
    lc = x0 - 0.5
    r2 = y1 * y1 + y2 * y2
    return np.array([x0 * (p2 - x0),
                     h * y1 - w * np.exp(k * p2) * y2 + lc * y1 * r2,
                     w * np.exp(-k * p2) * y1 + h * y2 + lc * y2 * r2])


def stpnt(u, par):
    u[:] = 0.0
    par[:4] = [-2.0, -0.5, 1.0, 0.0]
