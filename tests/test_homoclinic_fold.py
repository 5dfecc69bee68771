"""The fold locus of homoclinic orbits (IPS = 9, ISW = 2 from an LP:
washer.cont.systems.homoclinic_fold) on a family whose folds are known in closed form.

x'' = x - x^2 + (alpha - mu^2 - beta) x' has a homoclinic orbit of the saddle at 0 (the
sech^2 orbit x = (3/2) sech^2(t/2)) exactly where its damping vanishes,
alpha = mu^2 + beta: continued in (alpha, mu) the branch is a parabola whose fold in alpha
is at mu = 0, alpha = beta; the fold locus, continued in (alpha, mu, beta), is
alpha = beta, mu = 0.
"""
from __future__ import annotations

import numpy as np
import pytest

from washer.cont import runner
from washer.cont.constants import Constants
from washer.cont.problem import Problem

T = 30.0


def _problem():
    def func(u, par):
        return np.array([u[1], u[0] - u[0] ** 2 + (par[0] - par[1] ** 2 - par[2]) * u[1]])

    def dfdu(u, par):
        return np.array([[0.0, 1.0], [1 - 2 * u[0], par[0] - par[1] ** 2 - par[2]]])

    def stpnt(u, par, t):
        par[0], par[1], par[2], par[10] = 0.25, -0.5, 0.0, T
        par[11], par[12] = 0.0, 0.0
        z = (t - 0.5) * T
        u[0] = 1.5 / np.cosh(z / 2) ** 2
        u[1] = -1.5 * np.tanh(z / 2) / np.cosh(z / 2) ** 2
    return Problem(2, func, stpnt=stpnt, dfdu=dfdu, name="hfold", jac=-1)


def test_the_fold_locus_of_homoclinic_orbits_is_alpha_equal_beta():
    prob = _problem()
    base = dict(NDIM=2, IPS=9, IEQUIB=1, NTST=40, NCOL=4, JAC=-1, ISP=0, NPAR=20)
    br1 = runner.run(Constants(dict(base, ICP=[1, 2], ILP=1, NMX=30, NPR=50, DS=-0.02,
                                    DSMAX=0.05)), prob)
    lps = [p for p in br1.specials if p.ty == "LP"]
    assert br1.status == "ok" and len(lps) == 1
    # the fold of the parabola alpha = mu^2 (beta = 0): the truncation to T = 30 (the
    # orbit's ends e^(-T/2) = 3e-7 from the saddle, the projection conditions' error
    # quadratic in it) and the location's tolerance bound it (measured 6e-11)
    assert abs(lps[0].par[0]) < 1e-6 and abs(lps[0].par[1]) < 1e-6
    # AUTO's generating run (the null vector grows from 0), then the locus in
    # (alpha, mu, beta)
    br2 = runner.run(Constants(dict(base, ICP=[1, 2, 3], ISW=2, IRS=lps[0].lab, NMX=5,
                                    DS=0.01, DSMAX=0.05)), prob, br1)
    assert br2.status == "ok"
    br3 = runner.run(Constants(dict(base, ICP=[1, 2, 3], ISW=2, IRS=br2.specials[-1].lab,
                                    NMX=20, NPR=5, DS=0.05, DSMAX=0.1)), prob, br2)
    assert br3.status == "ok" and len(br3.specials) >= 4
    # The null vector at this fold is (v, q) = (0, q along mu): the orbit does not depend
    # on mu where alpha - mu^2 - beta is held, so the generating run grows q alone (v
    # stays rounding, as AUTO-07p's: 8e-21 there). Its parameter components and norm are
    # the last NPARI parameters, PAR(21 .. 23) and PAR(24) = |v|^2 + |q|^2, held fixed
    # along the locus: the restart keeps them (AUTO's s-records of this problem hold
    # PAR(21) = 0.08097885, PAR(24) = 0.00655757 at both runs' points). With them dropped
    # the norm condition is a double zero and the first step converged by rounding.
    end = np.asarray(br2.specials[-1].par, float)
    npari = br2.specials[-1].npari
    assert npari == 4 and end[-1] > 0
    assert end[-npari] ** 2 == pytest.approx(end[-1], rel=1e-12)
    for rec in br3.specials:
        assert np.asarray(rec.par, float)[-npari:] == pytest.approx(end[-npari:], rel=1e-12)
    for rec in br3.specials:
        par, U = np.asarray(rec.par, float), np.asarray(rec.U, float)
        # the locus alpha = beta, mu = 0 (as the fold above: measured 4e-13)
        assert par[0] == pytest.approx(par[2], abs=1e-6)
        assert abs(par[1]) < 1e-6
        # (u, v): the orbit and the branch's null vector beside it
        assert U.shape[1] == 4
    assert br3.specials[-1].par[2] > 1.0
