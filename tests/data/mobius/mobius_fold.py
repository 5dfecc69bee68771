"""mobius.py's cycle with its transverse matrix D = [[a, 1], [b, a]] moved along a
parabola, so that the PD and TR loci fold and the torus angle sweeps the resonances:

    a = PAR(1) - PAR(2)^2,   b = PAR(4) + PAR(5) PAR(2)

(PAR(3) = w as in mobius.py; T = 2 pi / w = 1). The transverse multipliers are
-exp((a +- sqrt(b)) T) (mobius.py's docstring), so with p1, p2 = PAR(1), PAR(2):

* PAR(4) = -1, PAR(5) = -1 (b = -(1 + p2) < 0 for p2 > -1): TR where a = 0, the locus
  p1 = p2^2, folding in p1 at (0, 0), with the angle theta = pi - sqrt(1 + p2):
  1:3 at p2 = pi^2/9 - 1, 1:4 at pi^2/4 - 1, 1:2 at p2 = -1 (b = 0), 1:1 at pi^2 - 1;
* PAR(4) = 1/4, PAR(5) = 0: PD where a + 1/2 = 0, the locus p1 = p2^2 - 1/2, folding
  in p1 at (-1/2, 0).
"""
import importlib.util
from pathlib import Path

import numpy as np

_spec = importlib.util.spec_from_file_location("mobius", Path(__file__).with_name("mobius.py"))
mobius = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(mobius)


def func(u, par):
    q = np.array(par, dtype=float)
    q[0] = par[0] - par[1] ** 2
    q[1] = par[3] + par[4] * par[1]
    return mobius.func(u, q)


def stpnt(u, par, t=0.0):
    mobius.stpnt(u, par, t)
    par[0], par[1], par[3], par[4] = -0.18, -0.5, -1.0, -1.0
