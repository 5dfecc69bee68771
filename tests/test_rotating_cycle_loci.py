"""A rotation (a periodic orbit whose angle gains 2 pi per period, NRTN) started from a
data file, its torus locus and its period doubling, against closed forms:
tests/data/mobius/rotor.py (its docstring derives them). The orbit's angle obeys
theta' = I - sin(theta): period T = 2 pi / sqrt(I^2 - 1), the transverse multipliers
-exp((a +- sqrt(b)) T).

The data file is the angle over one turn from scipy's integration (rtol 1e-12), an
independent route to the orbit; the collocation's error at NTST = 20, NCOL = 4 is
superconvergent at the mesh points (1e-9 allowed on T and the angle, as in
test_cycle_loci.py); located parameters are within the location tolerance EPSS
(1 + sqrt|DS DSMAX|) of the zero.
"""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from washer.run import run
from tests.test_cycle_loci import COLLOCATION, generated
from tolerances import location_tolerance

DATA = Path(__file__).parent / "data" / "mobius"


def period(I):
    return 2 * math.pi / math.sqrt(I * I - 1)


@pytest.fixture(scope="module")
def rotor(tmp_path_factory):
    d = tmp_path_factory.mktemp("rotor")
    for name in ("mobius.py", "rotor.py", "c.rotor", "c.rotor.trloc"):
        shutil.copy(DATA / name, d)
    T = period(3.0)
    sol = solve_ivp(lambda t, y: [3.0 - math.sin(y[0])], (0, T), [0.0], rtol=1e-12,
                    atol=1e-12, dense_output=True)
    t = np.linspace(0, T, 201)
    theta = sol.sol(t)[0]
    assert theta[-1] == pytest.approx(2 * math.pi, abs=1e-9)    # one turn in T
    np.savetxt(d / "rot.dat", np.c_[t, theta, 0 * t, 0 * t])
    return d


def test_rotation_from_data_torus_bifurcation(rotor):
    """From rot.dat (a rotation: the angle's jump of 2 pi enters the boundary
    conditions): every cycle has T = 2 pi / sqrt(8); TR at a = 0 with the angle
    PAR(12) = pi - T."""
    res = run(rotor / "c.rotor", dat="rot", verbose=False, sv="rot")
    assert res.status == "ok"
    T = period(3.0)
    for r in res.rows:
        assert r.par[10] == pytest.approx(T, abs=COLLOCATION)
        U = np.asarray(r.U)
        assert U[-1, 0] - U[0, 0] == pytest.approx(2 * math.pi, abs=COLLOCATION)
    (tr,) = [r for r in res.rows if r.ty == "TR"]
    assert tr.par[0] == pytest.approx(0.0, abs=location_tolerance(rotor / "c.rotor"))
    assert tr.par[11] == pytest.approx(math.pi - T, abs=COLLOCATION)


# 5 s: a torus locus of a rotating family; the fast loop keeps the rotating family's TR
@pytest.mark.slow
def test_rotation_torus_locus_resonances(rotor):
    """The torus locus in (I, a) from the generating run's EP, I growing: a = 0,
    T = 2 pi / sqrt(I^2 - 1) and theta = pi - T all along; R4 (-88) at I = sqrt(17),
    R3 (-87) at sqrt(37), then the UZSTOP I = 7."""
    run(rotor / "c.rotor", dat="rot", verbose=False, sv="rot")
    gen = run(rotor / "c.rotor.trloc", verbose=False, sv="rtrgen", s="rot", ICP=[1, 2])
    loc = run(rotor / "c.rotor.trloc", verbose=False, sv="rtrloc", s="rtrgen",
              IRS=generated(gen))
    assert loc.status == "ok"
    tol = location_tolerance(rotor / "c.rotor.trloc")
    lab = [r for r in loc.rows if r.lab]
    assert [r.code for r in lab] == [-88, -87, -84]
    assert lab[0].par[1] == pytest.approx(math.sqrt(17), abs=tol)
    assert lab[1].par[1] == pytest.approx(math.sqrt(37), abs=tol)
    for r in loc.rows:
        I, T = r.par[1], period(r.par[1])
        assert r.par[0] == pytest.approx(0.0, abs=COLLOCATION)
        assert r.par[10] == pytest.approx(T, abs=COLLOCATION)
        assert r.par[11] == pytest.approx(math.pi - T, abs=COLLOCATION)


def test_rotation_period_doubling_turns_twice(rotor):
    """b = 1/4: PD at a = -1/2; ISW = -1 there doubles the period and the mesh, and the
    doubled orbits turn twice: the angle gains 4 pi over 2 T, and |z|^2 = a + 1/2."""
    one = run(rotor / "c.rotor", dat="rot", verbose=False, sv="rotpd",
              PAR={1: -1.13, 4: 0.25}, UZSTOP={1: 0.1})
    (pd,) = [r for r in one.rows if r.ty == "PD"]
    assert pd.par[0] == pytest.approx(-0.5, abs=location_tolerance(rotor / "c.rotor"))
    dbl = run(rotor / "c.rotor", verbose=False, files=False, s="rotpd", IRS="PD1", ISW=-1,
              NMX=20, UZSTOP={})
    assert dbl.status == "ok" and dbl.rows[-1].par[0] > 0
    T = period(3.0)
    for r in dbl.rows:
        # the doubled orbits carry z != 0: their collocation error is larger than on
        # z = 0 (measured up to 1.1e-9 in the period)
        U = np.asarray(r.U)
        assert r.par[10] == pytest.approx(2 * T, abs=1e-8)
        assert U[-1, 0] - U[0, 0] == pytest.approx(4 * math.pi, abs=COLLOCATION)
        # |z|^2 at every stored point, between the mesh points too, where the collocation
        # error is O(h^(NCOL + 1)) of a profile turning twice (measured up to 5.6e-6)
        assert U[:, 1] ** 2 + U[:, 2] ** 2 == pytest.approx(r.par[0] + 0.5, abs=1e-5)
