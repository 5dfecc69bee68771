"""The combined PD/TR test of cycles (washer.cont.floquet.spb_test) where the multiplier
crossing -1 is not the one nearest the unit circle.

The closed-form system (5 equations) is a circle cycle x = cos t, y = sin t (period 2 pi)
carrying a Moebius band: v = R(t/2) w with w' = diag(a, b) w turns by half a revolution
in a period, so the monodromy on v is -diag(e^{2 pi a}, e^{2 pi b}). With s' = c s
beside it the multipliers are, in closed form,
    1, e^{-4 pi} (radial), -e^{2 pi a}, -e^{2 pi b}, e^{2 pi c},
and a period doubling is at a = 0. With c = -1.6e-3 the positive multiplier
e^{2 pi c} = 0.990 is nearer the circle than -e^{2 pi a} for |a| > 1.6e-3, so AUTO's
FNSPBV test (|mu_2| - 1, undefined where mu_2 is real positive) is undefined on both
sides of the PD, and a step across it sees no sign change.
"""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
import sympy as sp

from washer.cont import collocation as col
from washer.cont import floquet
from washer.cont.codes import Code
from washer.cont.iterator import Continuation
from washer.cont.problem import Problem
from washer.cont.settings import Settings
from washer.cont.system import StartData
from washer.cont.systems.periodic import PeriodicOrbits

B, C = -1.0, -1.6e-3          # PAR(2), PAR(3); PAR(1) = a is continued
EPSS = 1e-4


def band(u, par):
    """The cycle (x, y), the twisted pair (v1, v2) and s; par[0] = a, par[1] = b,
    par[2] = c. On the cycle (x, y) = (cos t, sin t), and R(t/2) diag(a, b) R(t/2)^T
    = (a + b)/2 I + (a - b)/2 [[cos t, sin t], [sin t, -cos t]]."""
    x, y, v1, v2, s = u
    a, b, c = par[0], par[1], par[2]
    r2 = x * x + y * y
    h, d = 0.5 * (a + b), 0.5 * (a - b)
    return np.array([x * (1 - r2) - y, y * (1 - r2) + x,
                     -0.5 * v2 + (h + d * x) * v1 + d * y * v2,
                     0.5 * v1 + d * y * v1 + (h - d * x) * v2,
                     c * s])


BAND = Problem(5, band, name="band")


def exact_multipliers(a: float) -> np.ndarray:
    T = 2 * math.pi
    return np.array([1.0, math.exp(-2 * T), -math.exp(a * T), -math.exp(B * T),
                     math.exp(C * T)])


def test_the_band_turns_by_half_a_revolution_in_a_period():
    """sympy: v(t) = R(t/2) diag(e^{at}, e^{bt}) v0 solves the (v1, v2) equations on the
    cycle, so the monodromy is R(pi) diag(e^{2 pi a}, e^{2 pi b}) = -diag(...)."""
    t, a, b = sp.symbols("t a b", real=True)
    R = sp.Matrix([[sp.cos(t / 2), -sp.sin(t / 2)], [sp.sin(t / 2), sp.cos(t / 2)]])
    Phi = R * sp.diag(sp.exp(a * t), sp.exp(b * t))
    h, d = (a + b) / 2, (a - b) / 2
    x, y = sp.cos(t), sp.sin(t)
    A = sp.Matrix([[h + d * x, -sp.Rational(1, 2) + d * y],
                   [sp.Rational(1, 2) + d * y, h - d * x]])
    assert sp.simplify(Phi.diff(t) - A * Phi) == sp.zeros(2, 2)
    assert sp.simplify(Phi.subs(t, 2 * sp.pi) + sp.diag(sp.exp(2 * sp.pi * a),
                                                        sp.exp(2 * sp.pi * b))) \
        == sp.zeros(2, 2)


def band_system(a: float, ntst: int = 20, ncol: int = 4, **kw) -> PeriodicOrbits:
    """The exact cycle at PAR(1) = a (v = s = 0), period 2 pi."""
    par = np.r_[a, B, C, np.zeros(9)]
    par[10] = 2 * math.pi
    mesh = col.Mesh.uniform(ntst, ncol)
    t = mesh.node_times()
    U = np.c_[np.cos(2 * np.pi * t), np.sin(2 * np.pi * t), np.zeros((len(t), 3))]
    rec = SimpleNamespace(U=U, t=t, ntst=ntst, ncol=ncol, par=par, icp=[1, 11], rldot=[],
                          udot=None)
    s = Settings(IPS=2, ICP=(1, 11), NDIM=5, NPAR=12, NTST=ntst, NCOL=ncol, EPSS=EPSS,
                 THL={11: 0.0}, **kw)
    return PeriodicOrbits(StartData(BAND, s, U[0], par, rec))


@pytest.mark.parametrize("a", [0.05, -0.05])
def test_collocated_multipliers_are_the_closed_form_ones(a):
    """NTST 20, NCOL 4 at the exact cycle: every multiplier to 1e-6 of its closed form
    (measured: 3.1e-8, the collocation error of the multipliers over a period), and
    mu_2 is the positive one."""
    sysm = band_system(a)
    st = sysm.stability(sysm.start()[0])
    got = np.sort_complex(np.asarray(st.values))
    np.testing.assert_allclose(got, np.sort(exact_multipliers(a)).astype(complex),
                               atol=1e-6)
    assert abs(floquet.critical(st.values) - math.exp(C * 2 * math.pi)) < 1e-6


def test_pd_test_is_defined_where_autos_is_not():
    """At a = +-0.05 (multiplier -1.369 and -0.730, mu_2 = 0.990 at both) AUTO's test
    (classify: mu_2 only) is undefined at both ends; the combined test takes the PD-typed
    multiplier and changes sign, |mu| - 1 to 1e-6, and the stable count changes, so the
    step is accepted; at a = 0 the located point is typed PD."""
    pts = {}
    for a in (0.05, -0.05, 0.0):
        sysm = band_system(a)
        x = sysm.start()[0]
        st = sysm.stability(x)
        pts[a] = SimpleNamespace(stability=st)
        if a:
            assert floquet.classify(st.values, EPSS) == (0, None)
            d = sysm.test_functions(x, None, None, st, None, [floquet.SPB])[floquet.SPB]
            assert abs(d - (math.exp(2 * math.pi * a) - 1)) < 1e-6
    assert sysm.accept(floquet.SPB, pts[0.05], pts[-0.05])
    assert floquet.spb_code(floquet.SPB, pts[0.0].stability, EPSS) == int(Code.PD)


def test_continuation_locates_the_period_doubling_at_a_zero():
    """The shipped iterator from a = 0.05 down with steps of 0.02 (DS = DSMAX): every
    step's ends have mu_2 = 0.990 (the step over the PD goes from 0.01, multiplier
    -1.065, to -0.01, -0.939), yet the PD is located at a = 0 to 1e-6 (measured 4e-12:
    the collocated multiplier is e^{2 pi a} to 3e-8 and the location converges on
    |mu| - 1 to EPSS)."""
    sysm = band_system(0.05)
    s = sysm.settings.with_(DS=-0.02, DSMAX=0.02, DSMIN=1e-6, NMX=8, IAD=0)
    found = []
    for k, step in enumerate(Continuation(sysm, s)):
        if step.kind == "failed":
            raise AssertionError(step.text)
        if step.kind == "special" and step.code == int(Code.PD):
            found.append(sysm.params(step.point.x)[0])
        if k > 12 or found:
            break
    assert len(found) == 1 and abs(found[0]) < 1e-6, found
