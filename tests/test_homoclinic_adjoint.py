"""HomCont's adjoint (ITWIST = 1, washer.cont.systems.homoclinic_adjoint): the inclination
flips (IPSI 13, 14) of a family whose flip is known in closed form, and AUTO's demo san,
runs 2-5 (tests/data/homcont/san/san_adjoint.auto, AUTO's b-files in autoref-adjoint/).

The closed form: u = (x, y, z),

    x' = y,  y' = x - x^2 + nu y + z (x + kappa x^2),  z' = sigma mu z,   0 < mu < 1

has at nu = 0 the homoclinic orbit x = (3/2) sech^2(t/2), y = x', z = 0 of the saddle at 0
for every kappa. With sigma = -1 the leading stable eigenvalue is -mu (right eigenvector
e_z); the bounded adjoint solution is v = c (x^2 - x, y, v_z) with
v_z(t) = c int_t^oo e^(mu (t - s)) (x + kappa x^2) y ds, so v_z(t) e^(-mu t) -> c I as
t -> -oo, I = int e^(-mu s) (x + kappa x^2) x' ds, and IPSI 13 (v(0) . e_z e^(mu T / 2))
vanishes with I. By parts I = (mu / 2) int e^(-mu s) x^2 ds + kappa (mu / 3) int e^(-mu s) x^3 ds,
and int e^(-mu s) sech^(2n)(s/2) ds = 4^n B(n + mu, n - mu) (w = 1 / (1 + e^s)): the flip is at
kappa* = -5 / (4 - mu^2). With sigma = +1 the leading unstable eigenvalue is mu, IPSI 14
(v(1) . e_z e^(mu T / 2)) measures int e^(mu s) (...) and, x being even, vanishes at the same
kappa*.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from auto_demo_compare import compare_files
from demo_files import DEMOS, autoref, copy_demo
from washer.auto.files import read_s
from washer.auto.script import run_script
from washer.cont import runner
from washer.cont.constants import Constants
from washer.cont.problem import Problem
from washer.cont.user_problem.user_files import load_user_problem

DATA = Path(__file__).parent / "data" / "homcont"
MU = 0.25
T = 40.0


def _flip_kappa(mu):
    """kappa* from the Beta integrals (sympy), checked against the integrand by
    quadrature."""
    m, s = sp.Rational(mu).limit_denominator(1000), sp.symbols("s", real=True)

    def laplace(n):                    # int e^(-m s) sech^(2n)(s/2) ds
        return 4 ** n * sp.gamma(n + m) * sp.gamma(n - m) / sp.gamma(2 * n)
    x = sp.Rational(3, 2) * sp.sech(s / 2) ** 2
    i2, i3 = sp.Rational(9, 4) * laplace(2), sp.Rational(27, 8) * laplace(3)
    kappa = sp.nsimplify(sp.simplify(-(m / 2) * i2 / ((m / 3) * i3)))
    assert kappa == -5 / (4 - m ** 2)
    # the integral I itself at kappa*, by quadrature: 0
    integrand = sp.lambdify(s, sp.exp(-m * s) * (x + kappa * x ** 2) * sp.diff(x, s), "mpmath")
    import mpmath
    assert abs(mpmath.quad(integrand, [-mpmath.inf, 0, mpmath.inf])) < 1e-12
    return float(kappa)


def _problem(sigma):
    def func(u, par):
        x, y, z = u
        kappa, nu, mu = par[0], par[1], par[2]
        return np.array([y, x - x * x + nu * y + z * (x + kappa * x * x), sigma * mu * z])

    def dfdu(u, par):
        x, y, z = u
        kappa, nu, mu = par[0], par[1], par[2]
        return np.array([[0.0, 1.0, 0.0],
                         [1 - 2 * x + z * (1 + 2 * kappa * x), nu, x + kappa * x * x],
                         [0.0, 0.0, sigma * mu]])

    def stpnt(u, par, t):
        par[0], par[1], par[2], par[10] = 0.0, 0.0, MU, T
        s = (t - 0.5) * T
        u[0] = 1.5 / np.cosh(s / 2) ** 2
        u[1] = -1.5 * np.tanh(s / 2) / np.cosh(s / 2) ** 2
        u[2] = 0.0
    return Problem(3, func, stpnt=stpnt, dfdu=dfdu, name="flip", jac=-1)


# 3.3 s each: the fast loop runs IPSI 13 (the adjoint continued to its flip), -m slow both
@pytest.mark.parametrize("sigma, ipsi", [(-1, 13), pytest.param(1, 14, marks=pytest.mark.slow)])
def test_inclination_flip_at_its_closed_form_parameter(sigma, ipsi):
    kappa_star = _flip_kappa(MU)
    prob = _problem(sigma)
    base = dict(NDIM=3, IPS=9, IEQUIB=0, NTST=80, NCOL=4, JAC=-1, ISP=0, ILP=0, ITNW=7)
    # the orbit (ITWIST = 0), then san's dummy step that lets Newton find the adjoint
    # (ITWIST = 1 from v = 0.1, continued in PAR(9), which no equation reads)
    br = runner.run(Constants(dict(base, ICP=[1, 2], NMX=2, DS=-0.01)), prob)
    br = runner.run(Constants(dict(base, ICP=[9, 2], ITWIST=1, NMX=2, DS=0.01,
                                   IRS=br.specials[-1].lab)), prob, br)
    br = runner.run(Constants(dict(base, ICP=[1, 2, 10, 20 + ipsi], ITWIST=1, IPSI=[ipsi],
                                   UZR={20 + ipsi: 0.0}, NMX=100, NPR=50, DS=-0.5, DSMAX=10.0,
                                   STOP=["UZ1"], IRS=br.specials[-1].lab)), prob, br)
    assert br.status == "ok"
    uz = [p for p in br.specials if p.ty == "UZ"]
    assert len(uz) == 1
    par = np.asarray(uz[0].par)
    U = np.asarray(uz[0].U)
    assert U.shape[1] == 6
    # the orbit stays the exact one (nu = 0; PAR(10) = 0 at a solution of the adjoint):
    # the collocation's error at NTST = 80, measured ~1e-9
    assert abs(par[1]) < 1e-7 and abs(par[9]) < 1e-7
    # the adjoint is normal to f along the orbit and its planar part is grad H: rounding
    # and the discretisation (measured ~1e-9 of |v|)
    F = np.array([prob.func(u[:3], par) for u in U])
    V = U[:, 3:]
    assert np.max(np.abs(np.sum(F * V, axis=1))) < 1e-6 * np.max(np.abs(V))
    # kappa at the flip: the truncation to [-T/2, T/2] leaves out the tails of I, whose
    # integrand e^(-mu s) (x + kappa x^2) x' is O(e^(-(2 - mu) |s|)): 2.5e-8 relative at
    # T = 40 (measured 1e-12; v's planar part is normal to e_z exactly)
    assert par[0] == pytest.approx(kappa_star, abs=1e-7)


def test_unsupported_adjoint_codes_without_itwist_are_refused():
    from washer.cont.start import RunError
    prob = _problem(-1)
    c = Constants(dict(NDIM=3, IPS=9, IEQUIB=0, ICP=[1, 2], NTST=20, JAC=-1, NMX=2,
                       IPSI=[13]))
    with pytest.raises(RunError, match=r"\[13\]"):
        runner.run(c, prob)


@pytest.mark.slow          # 2.7 s: AUTO's demo runs, as the other demo folders
def test_san_adjoint_runs_match_auto(tmp_path, monkeypatch):
    work = copy_demo("san", tmp_path, DATA / "san")
    monkeypatch.chdir(work)
    run_script("san_adjoint.auto")
    why = []
    # runs 3 and 5's b-files are the demo's own (san.auto's runs 1-5 are san_adjoint.auto's)
    refs = sorted([*(DATA / "san" / "autoref-adjoint").glob("b.*"), autoref("san") / "b.3",
                   autoref("san") / "b.5"])
    assert len(refs) == 4
    for ref in refs:
        a, matched, diff = compare_files(work / ref.name, ref)
        assert a, ref
        if len(matched) != len(a):
            why += diff
    assert not why, why


def test_inclination_and_orientation_on_autos_adjoint(tmp_path):
    # san's run 3 (AUTO's s.3): PSIHO's 13 on AUTO's orbits and adjoints gives its PAR(33)
    # to its written digits, and the orientation (FNCSHO's, written to AUTO's d-file only)
    # changes sign where PAR(33) does: the inclination flip UZ6 (PAR(4) = 1.23086), from
    # orientable (> 0) to twisted (< 0), the orbit run 5 continues as "non-orientable".
    recs = read_s(DATA / "san" / "autoref-adjoint" / "s.3")              # s.3.gz
    prob = load_user_problem("san", DEMOS / "san", 3)
    c = Constants(dict(NDIM=3, IPS=9, IRS=recs[0].lab, ICP=[4, 8, 10, 21, 33], IPSI=[1, 13],
                       IEQUIB=0, ITWIST=1, NTST=35, JAC=-1, ISP=0, ILP=0))
    run, _, _ = runner.build(c, prob, [recs[0]])
    hom = run.system
    signs = []
    for rec in recs:
        U, par = np.asarray(rec.U, float), np.asarray(rec.par, float)
        assert U.shape[1] == 6
        assert hom.psi(13, U, par) == pytest.approx(par[32], rel=1e-8, abs=1e-12)
        if abs(par[32]) > 1e-6:
            signs.append((np.sign(par[32]), np.sign(hom.orientation(U, par))))
    assert signs[0] == (1, 1) and signs[-1] == (-1, -1)
    assert all(a == b for a, b in signs)
