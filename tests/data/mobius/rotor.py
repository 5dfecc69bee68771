"""A rotating orbit carrying mobius.py's transverse bundle: exact period, TR and PD.

    theta' = I - sin(theta)                                   (I = PAR(2) > 1)
    z' = B(cos theta, sin theta) z + (theta'/2) J z - |z|^2 z  (z = (z1, z2))

with mobius.py's B for D = [[a, 1], [b, a]] (PAR(1) = a, PAR(4) = b). The angle turns
once per period T = 2 pi / sqrt(I^2 - 1) (the integral of d theta / (I - sin theta) over
one turn), so the orbit z = 0 is a rotation (NRTN = 1). On it w(t) = R(-theta(t)/2) z(t)
obeys w' = D w exactly (the J term is theta'/2 instead of mobius.py's w/2), and theta
gains 2 pi, so z(T) = R(pi) exp(D T) z(0): the multipliers are 1 and
-exp((a +- sqrt(b)) T), as mobius.py's with T depending on I:

* b = -1: TR where a = 0, the angle pi - T (for T < pi, I > sqrt(5)); along the locus
  a = 0 in (I, a), R4 at T = pi/2 (I = sqrt(17)), R3 at T = pi/3 (I = sqrt(37));
* b = 1/4: PD where a = -1/2; the doubled orbit z = R(theta/2) w* with |w*|^2 = a + 1/2
  turns twice in its period 2 T.
"""
import importlib.util
import math
from pathlib import Path

import numpy as np

_spec = importlib.util.spec_from_file_location("mobius", Path(__file__).with_name("mobius.py"))
mobius = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(mobius)


def func(u, par):
    theta, z1, z2 = u
    speed = par[1] - math.sin(theta)
    q = np.array(par, dtype=float)
    q[1], q[2] = par[3], speed          # mobius.py's b and its rotation rate
    f = mobius.func(np.array([math.cos(theta), math.sin(theta), z1, z2]), q)
    return np.array([speed, f[2], f[3]])


def stpnt(u, par, t=0.0):
    par[0], par[1], par[3] = -0.43, 3.0, -1.0
