"""Optimisation of periodic solutions (IPS = 15) against closed forms.

tests/data/optcircle/optcircle.py: circles r^2 = rho = mu / b of period 2 pi (mu = PAR(1),
b = PAR(4)) with the objective FOPT = x^2 - x^4 - (b - 1)^2, whose average over an
orbit is J(mu, b) = rho / 2 - 3 rho^2 / 8 - (b - 1)^2 (its docstring derives both). Hence:
* on the trivial branch (adjoint w = 0) from an IPS = 2 orbit, PAR(10) = J exactly, and
  the branch point where J is extremal along the family in mu is mu = 2 b / 3 (1 at
  b = 1.5);
* ISW = -1 there generates the adjoint: the orbit stays (mu = 1), PAR(12) = |w|^2 +
  kappa^2 + gamma^2 grows from 0, with w not zero (grad FOPT does not vanish on the
  orbit);
* with ICP = [1, 4, 11, 24, -24, -21, -31] the extremum in mu is continued in (mu, b):
  mu = 2 b / 3 and PAR(10) = 1/6 - (b - 1)^2 all along, and PAR(24), the optimality
  value of b, is int T f_b . w - gamma phi_b = 2 gamma (b - 1): f_b = -rho f_mu on the
  circle, and int T f_mu . w = gamma int phi_mu + PAR(21) = 0 (phi does not depend on
  mu, PAR(21) = 0 is imposed); so its zero, the extremum of J over both parameters,
  is at b = 1, mu = 2/3.
The adjoint equation, the optimality integrals and the multipliers all enter: the
relations hold only where w solves the adjoint problem with PAR(21) = PAR(31) = 0.

Tolerances: located points within AUTO's location tolerance EPSS (1 + sqrt|DS DSMAX|)
in PAR(ICP(1)) (the tangent is unit in a norm in which it has weight 1); relations on
every point within 2e-7: the collocation error of these circles at NTST = 20, NCOL = 4
(r^2 off by 2e-8 on the IPS = 2 orbit) and the Newton tolerance EPSL = EPSU = 1e-8
(measured: up to 7e-8 in PAR(10)).
"""
import math
import shutil
from pathlib import Path

import pytest

from tolerances import location_tolerance
from washer.auto.constants_file import ConstantsError, read_constants
from washer.cont.runner import RunError
from washer.run import run

DATA = Path(__file__).parent / "data" / "optcircle"
EXACT = 2e-7
ICP1 = [1, 11, 12, 24, -24, -21, -31]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    d = tmp_path_factory.mktemp("optcircle")
    for f in DATA.iterdir():
        shutil.copy(f, d)
    c = d / "c.optcircle"
    eq = run(c, verbose=False, sv="eq")
    po = run(c, verbose=False, s="eq", sv="po", IRS="HB1", IPS=2, ICP=[1, 11],
             UZSTOP={1: 1.2}, NMX=100)
    o1 = run(c, verbose=False, s="po", sv="o1", IRS="UZ1", IPS=15, ICP=ICP1, ISP=2, ILP=0,
             DS=-0.05, NMX=8, UZSTOP={})
    o2 = run(c, verbose=False, s="o1", sv="o2", IRS="BP1", IPS=15, ICP=ICP1, ISP=0,
             ISW=-1, DS=-0.05, NMX=5, UZSTOP={})
    last = [r for r in o2.rows if r.lab][-1].lab
    o3 = run(c, verbose=False, s="o2", sv="o3", IRS=last, IPS=15,
             ICP=[1, 4, 11, 24, -24, -21, -31], ISP=0, DS=-0.05, NMX=40, UZR={24: 0.0},
             UZSTOP={4: 0.7})
    for r in (eq, po, o1, o2, o3):
        assert r.status == "ok"
    return d, o1, o2, o3


def J(mu, b):
    rho = mu / b
    return rho / 2 - 3 * rho ** 2 / 8 - (b - 1) ** 2


def test_trivial_branch_objective_and_extremum(runs):
    d, o1, _, _ = runs
    c = read_constants(d / "c.optcircle")
    for r in o1.rows:
        mu, b = r.par[0], r.par[3]
        assert r.par[9] == pytest.approx(J(mu, b), abs=EXACT)       # PAR(10)
        assert r.par[11] == 0.0 and r.par[23] == pytest.approx(0.0, abs=EXACT)
    (bp,) = [r for r in o1.rows if r.ty == "BP"]
    assert bp.values[0] == pytest.approx(1.0, abs=location_tolerance(c, DS=0.05))
    # The b-file's columns: PAR(1), L2-NORM, MAX U(1..2), PERIOD, PAR(12), PAR(24).
    assert o1.titles[-3:] == ["PERIOD", "PAR(12)", "PAR(24)"]
    assert bp.values[-3] == pytest.approx(2 * math.pi, rel=EXACT)
    # The record holds u and the adjoint (2 NDIM components), the free parameters
    # AUTO's internal ICP (positive entries, then 10, 13, 14).
    assert bp.u.shape[1] == 4 and bp.icp == [1, 11, 12, 24, 10, 13, 14]


def test_switching_at_the_extremum_generates_the_adjoint(runs):
    _, _, o2, _ = runs
    norms = [r.par[11] for r in o2.rows]
    assert norms[0] == 0.0 and all(b > a for a, b in zip(norms, norms[1:]))
    for r in o2.rows:
        assert r.par[0] == pytest.approx(1.0, abs=EXACT)                # the orbit stays
        assert r.par[12] == pytest.approx(0.0, abs=EXACT)               # kappa
        # PAR(24) = 2 gamma (b - 1) with b = 1.5
        assert r.par[23] == pytest.approx(r.par[13], abs=EXACT)
    last = o2.rows[-1]
    assert abs(last.par[13]) > 0.1 and abs(last.u[:, 2:]).max() > 1e-3     # w is not 0


def test_two_parameter_extremum(runs):
    d, _, _, o3 = runs
    c = read_constants(d / "c.optcircle")
    for r in o3.rows:
        mu, b = r.par[0], r.par[3]
        assert mu == pytest.approx(2 * b / 3, abs=EXACT)
        assert r.par[9] == pytest.approx(1 / 6 - (b - 1) ** 2, abs=EXACT)
        assert r.par[23] == pytest.approx(2 * r.par[13] * (b - 1), abs=EXACT)   # gamma
    uz = [r for r in o3.rows if r.ty == "UZ"]
    assert uz[0].values[0] == pytest.approx(2 / 3, abs=location_tolerance(c, DS=0.05))
    assert uz[0].par[3] == pytest.approx(1.0, abs=2 * location_tolerance(c, DS=0.05))
    assert uz[-1].par[3] == pytest.approx(0.7, abs=EXACT)                # UZSTOP on b


def test_negative_icp_entries(tmp_path):
    for f in DATA.iterdir():
        shutil.copy(f, tmp_path)
    c = tmp_path / "c.optcircle"
    # negative entries are optimality conditions of IPS = 15 only
    with pytest.raises((ConstantsError, RunError), match="IPS = 15"):
        run(c, verbose=False, files=False, ICP=[1, -21])
    # -(20 + k) with k outside 1..11 is nonsense
    with pytest.raises((ConstantsError, RunError), match="-21..-31"):
        run(c, verbose=False, files=False, IPS=15, ICP=[1, 11, -35])
    # one negative entry fewer than positive ones
    with pytest.raises(RunError, match="2 positive, so 1 negative, got 2"):
        run(c, verbose=False, files=False, IPS=15, ICP=[1, 11, -21, -31])
    # IPS = 15 starts from a stored periodic orbit
    with pytest.raises(RunError, match="stored periodic orbit"):
        run(c, verbose=False, files=False, IPS=15, ICP=[1, 11, -21])


ROTOR = '''
import math
def func(u, par):
    return [par[0], -u[1]]
def stpnt(u, par, t=0.0):
    par[0], par[10] = 1.0, 2 * math.pi
    u[0], u[1] = 2 * math.pi * t, 0.0
def fopt(u, par):
    return u[1]
'''


def test_rotating_orbits_are_refused(tmp_path):
    """theta' = PAR(1), v' = -v: theta gains 2 pi over a period (AUTO's NRTN), which the
    extended system does not carry: refused by name rather than solved wrongly."""
    (tmp_path / "rotor.py").write_text(ROTOR)
    (tmp_path / "c.rotor").write_text("e = 'rotor'\nNDIM=2, IPS=2, ICP=[1, 11], NMX=3, "
                                      "NTST=10, NCOL=4, ISP=0, ILP=0\n")
    orbits = run(tmp_path / "c.rotor", verbose=False, sv="rotor")
    assert orbits.status == "ok"
    with pytest.raises(RunError, match="rotates"):
        run(tmp_path / "c.rotor", verbose=False, files=False, restart=orbits, IRS=1,
            IPS=15, ICP=[1, 11, -21])
