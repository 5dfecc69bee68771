"""Stability and Hopf points where f_u looks conservative (even dimension, trace zero).

A reversible system keeps pairs of eigenvalues on the imaginary axis along whole
branches; their computed real parts round to +-1e-16 of either sign, and counted with
tolerance 0 the stable count flips by 2 at nearly every step, each flip with a sign
change of the HB test a false Hopf point (8 on this file's first branch at c85472f). AUTO-07p's STABEQ counts Re <= 1e-5 as stable where NDIM is even and
|trace f_u| < 1e-7 max |f_u[i, j]|; a dissipative 2-equation system's trace vanishes at its
Hopf point too, so where a step lands within 1e-7 of it that point's pair counts as
stable, and a Hopf point decided point by point is lost (AUTO-07p 0.9.2 loses the one of
the last test so). The engine counts with the tolerance only across a step whose ends
both look conservative, and across such steps a Hopf point is where a pair leaves the
axis by colliding with another (Re(d^2) - 1e-10, smooth through the collision). Closed
forms with sympy; AUTO-07p 0.9.2, run on these problems, labels what is asserted here
except the two Hopf points (at the collision and at the step end)."""
import math
from types import SimpleNamespace

import numpy as np
import pytest
import sympy as sp

from washer.auto.constants_file import read_constants
from washer.cont.events import location_tolerance
from washer.cont.system import Stability
from washer.cont.systems.equilibrium import (hopf_accepted, neutral_hopf_test,
                                              neutral_tolerance, spectrum)
from washer.run import run

#: u'''' + a u'' + b u = u^2 as a first-order system (spatial dynamics of a
#: Swift-Hohenberg-like steady state; reversible under (u1, u2, u3, u4, z) ->
#: (u1, -u2, u3, -u4, -z)). PAR(1) = b, PAR(2) = a.
REVERSIBLE = '''
import numpy as np
def func(u, par):
    b, a = par[0], par[1]
    return np.array([u[1], u[2], u[3], -b * u[0] - a * u[2] + u[0] ** 2])
def stpnt(u, par, t=0.0):
    par[0] = 1.0
    par[1] = 3.0
    u[:] = 0.0
'''

#: x' = mu x - 2 y - x r^2, y' = 2 x + mu y - y r^2 (PAR(1) = mu): dissipative, Hopf at
#: mu = 0.
DISSIPATIVE = '''
import numpy as np
def func(u, par):
    x, y, mu = u[0], u[1], par[0]
    r2 = x * x + y * y
    return np.array([mu * x - 2 * y - x * r2, 2 * x + mu * y - y * r2])
def stpnt(u, par, t=0.0):
    par[0] = -0.5
    u[:] = 0.0
'''


def _reversible_jacobian():
    u = sp.symbols("u1:5", real=True)
    a, b = sp.symbols("a b", real=True)
    f = sp.Matrix([u[1], u[2], u[3], -b * u[0] - a * u[2] + u[0] ** 2])
    return f.jacobian(sp.Matrix(u)), u, a, b


def _run(tmp_path, name, text, constants):
    (tmp_path / f"{name}.py").write_text(text)
    (tmp_path / f"c.{name}").write_text(constants)
    r = run(tmp_path / f"c.{name}", e=name, sv=name, verbose=False)
    assert r.status == "ok"
    c = read_constants(tmp_path / f"c.{name}")
    return r, location_tolerance(SimpleNamespace(EPSS=c["EPSS"], DS=c["DS"], DSMAX=c["DSMAX"]))


def test_reversible_trivial_branch_has_no_hopf_point(tmp_path):
    """The trivial state continued in b at a = 3: trace f_u = 0 at every state (sympy), the
    characteristic polynomial is l^4 + a l^2 + b, so for 0 < b < a^2/4 both l^2 are negative
    and all four eigenvalues lie on the imaginary axis (no Hopf point: nothing crosses it),
    and det f_u = b: at b = 0 a zero eigenvalue (BP: the branch u1 = b crosses), for b < 0
    one positive real eigenvalue. Labels: EP, BP at b = 0, the UZ at b = -0.5; points before
    the BP stable (the neutral pairs count as stable), after it unstable."""
    J, u, a, b = _reversible_jacobian()
    assert sp.simplify(J.trace()) == 0
    lam = sp.symbols("lam")
    at0 = J.subs({s: 0 for s in u})
    assert sp.expand((lam * sp.eye(4) - at0).det() - (lam ** 4 + a * lam ** 2 + b)) == 0
    at0 = at0.subs(a, 3)
    assert at0.det() == b
    squares = sp.solve(sp.Symbol("s") ** 2 + 3 * sp.Symbol("s") + b, sp.Symbol("s"))
    for bb in (sp.Rational(1, 100), 1, 2):               # both roots l^2 < 0: l imaginary
        assert all(sq.subs(b, bb) < 0 for sq in squares)
    assert sorted(float(sq.subs(b, -sp.Rational(1, 2))) > 0 for sq in squares) == [False, True]

    r, tol = _run(tmp_path, "rv", REVERSIBLE, "NDIM=4, IPS=1, ICP=[1], ILP=1, ISP=1, NMX=200, "
                  "DS=-0.01, DSMAX=0.02, MXBF=0, UZSTOP={1: -0.5}\n")
    assert [s.ty for s in r.specials] == ["EP", "BP", "UZ"]
    bp = r.specials[1]
    # PAR(1) has weight 1 in the arclength: located within the location's tolerance
    assert bp.par[0] == pytest.approx(0.0, abs=tol)
    for row in r.rows:
        if row.par[0] > tol:
            assert row.stability.n_stable == 4 and row.stable
        elif row.par[0] < -tol:
            assert row.stability.n_stable == 3 and not row.stable


def test_reversible_pairs_colliding_on_the_axis_make_a_hopf_point(tmp_path):
    """The trivial state continued in a at b = 1: for a > 2 two imaginary pairs i w1, i w2
    with (w1 - w2)^2 = a - 2; at a = 2 they collide and for |a| < 2 leave the axis as
    +-sqrt(2 - a)/2 +- i sqrt(2 + a)/2 (sympy). The stable count is 4 down to a = 2 and 2
    once sqrt(2 - a)/2 exceeds the tolerance 1e-5 (a < 2 - 4e-10): one HB, at a = 2 within
    the location's tolerance, located on Re(d^2) - 1e-10 (d half the distance between the
    upper eigenvalues: (2 - a)/4 on both sides). AUTO-07p 0.9.2 labels none here: its test,
    the signed real part of one eigenvalue of the quartet, rounds to +-1e-17 before the
    collision and takes the sign of whichever of +-sqrt(2 - a)/2 it picks after it."""
    J, u, a, b = _reversible_jacobian()
    A = J.subs({s: 0 for s in u}).subs(b, 1)
    lam = sp.symbols("lam")
    for aa in (sp.Rational(1, 2), sp.Rational(-3, 2)):
        roots = sp.solve(A.subs(a, aa).charpoly(lam).as_expr(), lam)
        assert sorted(sp.nsimplify(sp.re(z)) for z in roots) == \
            sorted([sp.sqrt(2 - aa) / 2] * 2 + [-sp.sqrt(2 - aa) / 2] * 2)
    for aa in (sp.Rational(5, 2), 3):
        roots = sp.solve(A.subs(a, aa).charpoly(lam).as_expr(), lam)
        assert all(sp.re(z) == 0 for z in roots)
        w = sorted(sp.im(z) for z in roots if sp.im(z) > 0)
        assert sp.simplify((w[1] - w[0]) ** 2 - (aa - 2)) == 0

    r, tol = _run(tmp_path, "rv", REVERSIBLE, "NDIM=4, IPS=1, ICP=[2], ILP=1, ISP=1, NMX=200, "
                  "DS=-0.01, DSMAX=0.02, MXBF=0, UZSTOP={2: 1.0}\n")
    assert [s.ty for s in r.specials] == ["EP", "HB", "UZ"]
    assert r.specials[1].par[1] == pytest.approx(2.0, abs=tol)
    for row in (row for row in r.rows if not row.lab):         # the regular points
        if row.par[1] > 2:
            assert row.stability.n_stable == 4 and row.stable
        elif math.sqrt(2 - row.par[1]) / 2 > 2e-5:
            assert row.stability.n_stable == 2 and not row.stable


def test_dissipative_hopf_point_at_a_step_end_is_kept(tmp_path):
    """x' = mu x - 2 y - x r^2, y' = 2 x + mu y - y r^2 from mu = -0.5, DS = 0.05: f_u at 0
    has eigenvalues mu +- 2 i (sympy) and trace 2 mu, which the step to mu = 5e-8 (AUTO-07p's
    step and ours) makes smaller than 1e-7 max |f_u| = 2e-7. Counted point by point that
    end's pair (Re = 5e-8) is stable as the previous one's, the HB test's sign change is
    refused and the next step has none: AUTO-07p 0.9.2 labels no HB on this branch. Across
    that step the previous end is not conservative, the count is 2 -> 0, and the HB is at
    mu = 0 within the location's tolerance, with PAR(11) = pi."""
    x, y, mu = sp.symbols("x y mu", real=True)
    lam = sp.symbols("lam")
    r2 = x ** 2 + y ** 2
    f = sp.Matrix([mu * x - 2 * y - x * r2, 2 * x + mu * y - y * r2])
    A = f.jacobian(sp.Matrix([x, y])).subs({x: 0, y: 0})
    assert set(sp.solve(A.charpoly(lam).as_expr(), lam)) == {mu - 2 * sp.I, mu + 2 * sp.I}

    r, tol = _run(tmp_path, "hp", DISSIPATIVE, "NDIM=2, IPS=1, ICP=[1], ILP=1, ISP=1, "
                  "NMX=40, DS=0.05, DSMAX=0.1, UZSTOP={1: 0.2}\n")
    # the situation tested: a point within the band where f_u looks conservative
    assert any(neutral_tolerance(np.array([[p, -2.0], [2.0, p]])) > 0
               for p in (row.par[0] for row in r.rows))
    hb = [s for s in r.specials if s.ty == "HB"]
    assert len(hb) == 1
    assert hb[0].par[0] == pytest.approx(0.0, abs=tol)
    assert hb[0].par[10] == pytest.approx(math.pi, rel=1e-6)


def test_collision_test_is_smooth_through_the_collision():
    """neutral_hopf_test on the spectra of l^4 + a l^2 + 1 at a = 2 +- h: (2 - a)/4 - 1e-10
    on both sides (the closed form of Re(d^2), d half the distance between the upper
    eigenvalues), to rounding of the eigenvalues (~1e-16 relative, squared distances)."""
    for h in (1e-2, 1e-4, -1e-4, -1e-2):
        aa = 2 - h
        A = np.array([[0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1], [-1.0, 0, -aa, 0]])
        st = spectrum(np.linalg.eigvals(A), neutral_tolerance(A))
        assert st.neutral == 1e-5
        assert neutral_hopf_test(st) == pytest.approx(h / 4 - 1e-10, abs=1e-12)


def test_acceptance_counts_with_the_tolerance_only_across_conservative_steps():
    """The rule itself: a pair at +-1e-16 counts as stable at a conservative-looking point;
    a step between two such points whose rounding flips the pair's sign is no Hopf point;
    a step from a dissipative point (-0.1 +- i) to one at +4e-8 +- i (trace 8e-8 of
    max |f_u| = 1: conservative-looking) is."""
    def point(re, A):
        lam = np.array([complex(re, 1.0), complex(re, -1.0)])
        return spectrum(lam, neutral_tolerance(A))

    def rot(re):
        return np.array([[re, -1.0], [1.0, re]])

    on_axis = point(1e-16, rot(1e-16)), point(-1e-16, rot(-1e-16))
    assert [p.n_stable for p in on_axis] == [2, 2]
    assert not hopf_accepted(*on_axis)
    before, near = point(-0.1, rot(-0.1)), point(4e-8, rot(4e-8))
    assert near.neutral > 0 and near.n_stable == 2 and before.neutral == 0
    assert hopf_accepted(before, near)
    assert isinstance(near, Stability)
