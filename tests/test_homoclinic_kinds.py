"""HomCont's other connections (IPS = 9, washer.cont.systems.homoclinic) against closed
forms: heteroclinic orbits (IEQUIB = -1, -2), a fixed test function (IFIXED), the
symmetric homoclinic orbits of a reversible system (IREV) and a homoclinic orbit to a
saddle-node (IEQUIB = 2).

Nagumo's front: u'' + c u' + k u (1 - u)(u - a) = 0 has the front
u = 1 / (1 + exp(-sqrt(k/2) t)) from (0, 0) to (1, 0) exactly where c = sqrt(2k)(a - 1/2)
(sympy below). Both equilibria are saddles; the connection is codimension one in (a, c).

Reversible: x'' = a x - x^2 is reversible under (x, y) -> (x, -y); its homoclinic orbit
(3a/2) sech^2(sqrt(a) t/2) is symmetric, reaching the section y = 0 at its peak x = 3a/2,
and exists for every a > 0 (codimension zero: one free parameter, no phase condition).

Saddle-node: in polar coordinates r' = r (nu - r^2), theta' = mu - r sin(theta): the circle
r = sqrt(nu) is invariant, and at mu = sqrt(nu) the point (0, sqrt(nu)) on it is a
saddle-node (eigenvalues 0 along the circle, -2 nu across it) whose homoclinic orbit is the
circle itself.

AUTO's demo mtn (a saddle-node homoclinic orbit with IPSI 15, 16, then the fixed psi_15 of
a non-central one) beyond the demo table: its runs 4-6 from AUTO's own solutions; AUTO's
demo rev (reversible) checked against the first integral of its equation.
"""
import shutil
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from auto_demo_compare import DEMOS, compare_files
from washer.auto.script import run_script
from washer.auto.files import read_b
from washer.cont import runner
from washer.cont.constants import Constants
from washer.cont.problem import Problem

T = 40.0               # PAR(11): the truncation interval


def _front():
    """sympy: u = 1/(1 + exp(-b t)), b = sqrt(k/2), solves Nagumo's equation at
    c = sqrt(2k)(a - 1/2); returns u(t, k) as a function."""
    t, a, k = sp.symbols("t a k", positive=True)
    b = sp.sqrt(k / 2)
    u = 1 / (1 + sp.exp(-b * t))
    c = sp.sqrt(2 * k) * (a - sp.Rational(1, 2))
    res = sp.diff(u, t, 2) + c * sp.diff(u, t) + k * u * (1 - u) * (u - a)
    assert sp.simplify(res) == 0
    return sp.lambdify((t, k), u)


def _nagumo(u_exact, a0, pvls):
    """PAR(1) = a, PAR(2) = c, PAR(3) = k; the start is the exact front at a = a0, k = 1
    (c from the closed form), centred in the interval."""
    def func(u, par):
        a, c, k = par[0], par[1], par[2]
        return np.array([u[1], -c * u[1] - k * u[0] * (1 - u[0]) * (u[0] - a)])

    def dfdu(u, par):
        a, c, k = par[0], par[1], par[2]
        x = u[0]
        return np.array([[0.0, 1.0], [-k * (-3 * x * x + 2 * (1 + a) * x - a), -c]])

    def stpnt(u, par, t):
        par[0], par[1], par[2], par[10] = a0, np.sqrt(2.0) * (a0 - 0.5), 1.0, T
        # the equilibria's guesses (IEQUIB = -2 solves for them)
        par[11:15] = [1e-3, 0.0, 1.0 - 1e-3, 0.0]
        s, h = (t - 0.5) * T, 1e-6
        u[0] = u_exact(s, 1.0)
        u[1] = (u_exact(s + h, 1.0) - u_exact(s - h, 1.0)) / (2 * h)

    def equilibria(u, par):
        par[11:15] = [0.0, 0.0, 1.0, 0.0]

    return Problem(2, func, stpnt=stpnt, dfdu=dfdu, name="nagumo", jac=-1,
                   pvls=equilibria if pvls else None)


@pytest.mark.parametrize("iequib", [-1, -2])
def test_nagumo_front_heteroclinic(iequib):
    u_exact = _front()
    c = Constants(dict(NDIM=2, IPS=9, IEQUIB=iequib, ICP=[1, 2], NTST=40, NCOL=4, JAC=-1,
                       ISP=0, ILP=0, DS=0.02, DSMAX=0.05, NMX=25, NPR=5))
    br = runner.run(c, _nagumo(u_exact, 0.3, pvls=iequib == -1))
    assert br.status == "ok"
    pts = br.specials[1:]
    assert len(pts) >= 4
    a_seen = [r.par[0] for r in pts]
    assert max(a_seen) - min(a_seen) > 0.3
    for r in pts:
        par, U = np.asarray(r.par), np.asarray(r.U)
        a, cc = par[0], par[1]
        # c on the closed form: the truncation's error is exp(-lambda T) ~ 1e-8 at
        # T = 40 and the slowest rate lambda >= 0.45 here; the collocation's ~1e-9
        assert cc == pytest.approx(np.sqrt(2.0) * (a - 0.5), abs=1e-6)
        assert np.allclose(par[11:15], [0, 0, 1, 0], atol=1e-9)
        # the profile: the front shifted in time (the phase condition picks the shift);
        # u' = u (1 - u) / sqrt(2) on it (k = 1)
        assert np.max(np.abs(U[:, 1] - U[:, 0] * (1 - U[:, 0]) / np.sqrt(2.0))) < 1e-6
        assert U[0, 0] < 1e-4 and U[-1, 0] > 1 - 1e-4


def test_nagumo_front_with_a_fixed_test_function():
    """IFIXED = [1]: psi_1 = Re(l_s + l_u) at the left equilibrium = -c held at zero, so the
    front must stand (c = 0, a = 1/2) for every k; continued in (a, c, k)."""
    u_exact = _front()
    c = Constants(dict(NDIM=2, IPS=9, IEQUIB=-1, IFIXED=[1], ICP=[1, 2, 3], NTST=40,
                       NCOL=4, JAC=-1, ISP=0, ILP=0, DS=0.05, DSMAX=0.2, NMX=20, NPR=5))
    br = runner.run(c, _nagumo(u_exact, 0.5, pvls=True))
    assert br.status == "ok"
    pts = br.specials[1:]
    ks = [r.par[2] for r in pts]
    assert max(ks) - min(ks) > 0.5
    for r in pts:
        par, U = np.asarray(r.par), np.asarray(r.U)
        assert abs(par[1]) < 1e-9 and abs(par[0] - 0.5) < 1e-6
        b = np.sqrt(par[2] / 2)
        assert np.max(np.abs(U[:, 1] - b * U[:, 0] * (1 - U[:, 0]))) < 1e-5


def _reversible(a0):
    def func(u, par):
        return np.array([u[1], par[0] * u[0] - u[0] ** 2])

    def dfdu(u, par):
        return np.array([[0.0, 1.0], [par[0] - 2 * u[0], 0.0]])

    def stpnt(u, par, t):
        # the half orbit from the saddle (t = 0) to the peak (t = 1), T/2 = 20
        par[0], par[10] = a0, T / 2
        s = (t - 1.0) * T / 2
        sech2 = 1 / np.cosh(np.sqrt(a0) * s / 2) ** 2
        u[0] = 1.5 * a0 * sech2
        u[1] = -1.5 * a0 ** 1.5 * sech2 * np.tanh(np.sqrt(a0) * s / 2)

    def equilibrium(u, par):
        par[11:13] = 0.0

    return Problem(2, func, stpnt=stpnt, dfdu=dfdu, name="rev2", jac=-1, pvls=equilibrium)


@pytest.mark.parametrize("iequib", [0, 1])
def test_reversible_symmetric_homoclinic_family(iequib):
    """IEQUIB = 0: the saddle from PVLS; 1: solved for (f(x0) = 0, PAR(12), PAR(13) free)."""
    c = Constants(dict(NDIM=2, IPS=9, IEQUIB=iequib, IREV=[0, 1], ICP=[1], NTST=30, NCOL=4,
                       JAC=-1, ISP=0, ILP=0, DS=0.05, DSMAX=0.2, NMX=20, NPR=5))
    br = runner.run(c, _reversible(1.0))
    assert br.status == "ok"
    pts = br.specials[1:]
    assert max(r.par[0] for r in pts) > 1.5
    for r in pts:
        a, U = r.par[0], np.asarray(r.U)
        # the peak at t = 1 is 3a/2 up to the truncation (exp(-sqrt(a) T/2) < 1e-8)
        assert U[-1, 1] == pytest.approx(0.0, abs=1e-12)
        assert U[-1, 0] == pytest.approx(1.5 * a, rel=1e-6)
        # energy y^2/2 - a x^2/2 + x^3/3 = 0 on the orbit: the collocation's error
        H = U[:, 1] ** 2 / 2 - a * U[:, 0] ** 2 / 2 + U[:, 0] ** 3 / 3
        assert np.max(np.abs(H)) < 1e-6
        assert np.max(np.abs(r.par[11:13])) < 1e-12      # the saddle at the origin


def _snic(T):
    """PAR(1) = mu, PAR(2) = nu; the start is the exact circle at mu = nu = 1, where
    phi = theta - pi/2 obeys phi' = 1 - cos(phi), cot(phi/2) = -t, centred in the
    interval."""
    def func(u, par):
        mu, nu = par[0], par[1]
        x, y = u
        g = nu - x * x - y * y
        return np.array([x * g - y * (mu - y), y * g + x * (mu - y)])

    def dfdu(u, par):
        mu, nu = par[0], par[1]
        x, y = u
        g = nu - x * x - y * y
        return np.array([[g - 2 * x * x, -2 * x * y - mu + 2 * y],
                         [-2 * x * y + mu - y, g - 2 * y * y - x]])

    def stpnt(u, par, t):
        par[0], par[1], par[10] = 1.0, 1.0, T
        par[11], par[12] = 0.0, 1.0
        theta = np.pi / 2 + 2 * np.arctan2(1.0, -(t - 0.5) * T)
        u[0], u[1] = np.cos(theta), np.sin(theta)

    return Problem(2, func, stpnt=stpnt, dfdu=dfdu, name="snic", jac=-1)


def _snic_family(T):
    c = Constants(dict(NDIM=2, IPS=9, IEQUIB=2, IPSI=[15, 16], ICP=[1, 2, 35, 36], NTST=40,
                       NCOL=4, JAC=-1, ISP=0, ILP=0, DS=0.05, DSMAX=0.2, NMX=15, NPR=5))
    br = runner.run(c, _snic(T))
    assert br.status == "ok"
    return br.specials[1:]


def test_saddle_node_homoclinic_circle():
    """The saddle-node conditions exactly, the orbit on the circle to O(T^-2), and the
    test functions 15, 16 of a central orbit: on the circle phi = theta - pi/2 obeys
    cot(phi/2) = -sqrt(nu) t, so the ends at t = -+T/2 lie at arc length 4/T + O(T^-3) on
    either side of x0 along the centre direction v = (1, 0): psi_16 = (x0 - u(0)) . v ->
    4/T and psi_15 = (x0 - u(1)) . v -> -4/T (neither vanishes: the orbit is central)."""
    off, psi_err = [], []
    for T_ in (40.0, 80.0):
        pts = _snic_family(T_)
        assert max(r.par[1] for r in pts) > 1.5
        worst = 0.0
        for r in pts:
            par, U = np.asarray(r.par), np.asarray(r.U)
            mu, nu = par[0], par[1]
            # f(x0) = 0 and the zero eigenvalue: the saddle-node is at (0, sqrt(nu)) with
            # mu = sqrt(nu), up to Newton's tolerance (measured: rounding)
            assert mu == pytest.approx(np.sqrt(nu), abs=1e-9)
            assert np.allclose(par[11:13], [0.0, np.sqrt(nu)], atol=1e-9)
            worst = max(worst, float(np.max(np.abs(np.hypot(U[:, 0], U[:, 1]) - np.sqrt(nu)))))
            psi_err.append((T_, abs(par[34] * T_ + 4), abs(par[35] * T_ - 4)))
        off.append(worst)
    # The orbit leaves and enters the saddle-node along its centre direction, where
    # the approach is algebraic (phi ~ 2/t): the ends sit at a distance ~ 4/T on the
    # circle, and the projection conditions put them on its tangent, off the circle by
    # O(T^-2). Measured 4.9e-3 at T = 40 and 1.2e-3 at T = 80: twice T, a quarter.
    assert off[0] < 1e-2 and 3.5 < off[0] / off[1] < 4.5, off
    # T psi_15 + 4 and T psi_16 - 4: the truncated problem's ends are not placed
    # symmetrically by the phase condition: measured at most 8.7e-3 and 0.096 at T = 40,
    # 2.1e-3 and 0.045 at T = 80 (O(T^-2) and O(T^-1) relative)
    e40 = [max(e[i] for e in psi_err if e[0] == 40.0) for i in (1, 2)]
    e80 = [max(e[i] for e in psi_err if e[0] == 80.0) for i in (1, 2)]
    assert e40[0] < 0.02 and e40[1] < 0.2, e40
    assert e80[0] < e40[0] / 3 and e80[1] < e40[1] / 1.8, (e40, e80)


@pytest.mark.slow
def test_mtn_runs_4_to_6_from_autos_own_solutions(tmp_path, monkeypatch):
    """AUTO's demo mtn (tests/data/auto_demos/mtn) runs 4-6 restarted from AUTO's own s.1:
    what these runs give from AUTO's records, whatever washer's runs 1-3 (the demo's script
    reaches them too, docs/auto_compatibility.md's demo table). Run 6 holds
    psi_15 = 0 (IFIXED = [15], IEQUIB = 2) in (PAR(3), PAR(1), PAR(2))."""
    src = DEMOS / "mtn"
    work = tmp_path / "mtn"
    shutil.copytree(src, work, ignore=shutil.ignore_patterns("autoref"))
    shutil.copy(src / "autoref" / "s.1.gz", work)      # sl('1') and s='1' read s.1.gz
    (work / "r.auto").write_text("r1=sl('1')\n"
                                 "r4=run('mtn',c='mtn.4',s='1',sv='4')\n"
                                 "r5=run(r1('UZ3'),e='mtn',c='mtn.5',sv='5')\n"
                                 "r6=run(r1('UZ1'),e='mtn',c='mtn.6',sv='6')\n")
    monkeypatch.chdir(work)
    run_script("r.auto")
    for n in (4, 6):
        a, matched, why = compare_files(work / f"b.{n}", src / "autoref" / f"b.{n}")
        assert a and len(matched) == len(a), why
    # run 5 is appended to AUTO's b.1 (its last branch): every row's PAR(1), L2-norm,
    # PAR(2), PAR(29), PAR(30) (measured: within 2.4e-6; the MAX U columns, maxima over
    # the mesh, within 1e-4)
    ours, auto = (np.array([r.values for r in read_b(f)[-1]])
                  for f in (work / "b.5", src / "autoref" / "b.1"))
    assert ours.shape == auto.shape
    cols = [0, 1, 4, 5, 6]
    assert np.max(np.abs(ours[:, cols] - auto[:, cols])) < 1e-5


@pytest.mark.slow
def test_rev_demo_orbits_are_symmetric_homoclinic_orbits(tmp_path, monkeypatch):
    """AUTO's demo rev (tests/data/auto_demos/rev), u'''' + P u'' + u - u^3 = 0 with IREV
    = [0,1,0,1] (runs 1, 2: u', u''' vanish at t = 1) and [1,0,1,0] (runs 3, 4: u, u''),
    run as shipped. Along every orbit the first integral
    H = u' u''' - u''^2/2 + P u'^2/2 + u^2/2 - u^4/4 vanishes (0 at the equilibrium), so
    the computed orbits are homoclinic orbits of the ODE whatever AUTO's run did: run 3's
    branch goes on past AUTO's MX at PAR(1) = -0.90993 (AUTO's step failure), and its UZ
    after the LP sits at PAR(1) = 1.7 where AUTO's is written at 1.698836."""
    from washer.auto.files import read_s
    work = tmp_path / "rev"
    shutil.copytree(DEMOS / "rev", work, ignore=shutil.ignore_patterns("autoref"))
    monkeypatch.chdir(work)
    run_script("rev.auto")
    for name, zero in (("s.1", [1, 3]), ("s.3", [0, 2])):
        recs = read_s(work / name)
        for r in recs[1:]:                 # the first: the dat= start as read
            U, P = np.asarray(r.U, float), r.par[0]
            u, u1, u2, u3 = U.T
            H = u1 * u3 - u2 ** 2 / 2 + P * u1 ** 2 / 2 + u ** 2 / 2 - u ** 4 / 4
            # the collocation's error at NTST = 35: measured 1.1e-5 at most (AUTO's own
            # orbits the same); the reversibility conditions hold to rounding
            assert np.max(np.abs(H)) < 5e-5, (name, r.lab, P)
            assert np.max(np.abs(U[-1, zero])) < 1e-12
    run3 = [r for r in read_s(work / "s.3") if r.lab <= 8]
    assert [round(r.par[0], 7) for r in run3 if r.lab == 4] == [1.7]
    # run 3 ends at NMX; where depends on its steps, which move with the machine's
    # rounding: PAR(1) = -0.91358 on one machine, -0.90151 on an AVX-512 AMD EPYC
    assert min(r.par[0] for r in run3) < -0.90
