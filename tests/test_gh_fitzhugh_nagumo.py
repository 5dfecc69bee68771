"""The generalized Hopf (Bautin) point of AUTO's fhn demo in closed form.

FitzHugh-Nagumo, x' = c (x - x^3/3 + y), y' = -(x - a + b y) / c with b = 0.8
(tests/data/auto_demos/fhn). Its Hopf curve in (a, c) is parametrised by the equilibrium
x0: y0 = x0^3/3 - x0, a = x0 + b y0, and the trace c (1 - x0^2) - b/c = 0 gives
c^2 = b / (1 - x0^2). The first Lyapunov coefficient along it, from the planar formula
(Guckenheimer & Holmes (3.4.11)) in coordinates where the linear part is a rotation,
vanishes exactly at x0 = 1/2 (sympy below): the GH point is (a, c) = (2/15,
sqrt(16/15)), x = 1/2. AUTO-07p's own run notes "Possible special point" there (its
location of the GH fails, see the demo table of docs/auto_compatibility.md); washer's Hopf
locus must carry a GH at that
point, to within the location tolerance EPSS (1 + sqrt|DS DSMAX|) in arclength (the tangent
is unit in a norm where PAR(1) has weight 1, so each coordinate is within that).
"""
import math
import shutil
from pathlib import Path

import pytest
import sympy as sp

from washer.run import run

DEMO = Path(__file__).parent / "data" / "auto_demos" / "fhn"
B = sp.Rational(4, 5)


def lyapunov_on_hopf_curve(x0):
    """The first Lyapunov coefficient (up to a positive factor) at the Hopf point whose
    equilibrium is x = x0."""
    X, Y, u, v = sp.symbols("X Y u v", real=True)
    y0 = x0 ** 3 / 3 - x0
    a, c = x0 + B * y0, sp.sqrt(B / (1 - x0 ** 2))
    f = [c * (X - X ** 3 / 3 + Y), -(X - a + B * Y) / c]
    f = [sp.expand(e.subs({X: X + x0, Y: Y + y0}, simultaneous=True)) for e in f]
    J = sp.Matrix(2, 2, lambda i, j: sp.diff(f[i], (X, Y)[j]).subs({X: 0, Y: 0}))
    w = sp.sqrt(J.det())
    # u = X, v = -(J11 X + J12 Y) / w: u' = -w v + ..., v' = w u + ... (G & H's form)
    sub = {X: u, Y: (-w * v - J[0, 0] * u) / J[0, 1]}
    F = sp.expand(f[0].subs(sub, simultaneous=True))
    G = sp.expand((-(J[0, 0] * f[0] + J[0, 1] * f[1]) / w).subs(sub, simultaneous=True))

    def d(e, *vs):
        return sp.diff(e, *vs).subs({u: 0, v: 0})
    return sp.simplify(
        w * (d(F, u, u, u) + d(F, u, v, v) + d(G, u, u, v) + d(G, v, v, v))
        + d(F, u, v) * (d(F, u, u) + d(F, v, v)) - d(G, u, v) * (d(G, u, u) + d(G, v, v))
        - d(F, u, u) * d(G, u, u) + d(F, v, v) * d(G, v, v))


def test_the_lyapunov_coefficient_vanishes_at_x_one_half():
    assert lyapunov_on_hopf_curve(sp.Rational(1, 2)) == 0
    below = float(lyapunov_on_hopf_curve(sp.Rational(49, 100)))
    above = float(lyapunov_on_hopf_curve(sp.Rational(51, 100)))
    assert below * above < 0                      # a transversal zero: a GH point


def test_hopf_locus_carries_the_gh_point(tmp_path):
    for f in ("fhn.f90", "c.fhn.1", "c.fhn.4"):
        shutil.copy(DEMO / f, tmp_path)
    eq = run(tmp_path / "c.fhn.1", verbose=False, sv="fhn", e="fhn")
    assert eq.status == "ok"
    # c.fhn.4: the Hopf locus from HB2 in (a, c) towards smaller c (DS < 0)
    hb = run(tmp_path / "c.fhn.4", verbose=False, sv="hb", s="fhn", e="fhn")
    gh = [r for r in hb.rows if r.lab and r.ty == "GH"]
    assert len(gh) == 1
    tol = 1e-4 * (1 + math.sqrt(0.01 * 0.05))    # c.fhn.4: EPSS, |DS|, DSMAX
    assert gh[0].par[0] == pytest.approx(2 / 15, abs=tol)
    assert gh[0].par[2] == pytest.approx(math.sqrt(16 / 15), abs=tol)
    assert gh[0].values[2] == pytest.approx(0.5, abs=tol)         # MAX U(1) = x0
