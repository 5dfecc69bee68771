"""HomCont's homotopy start (ISTART = 3, washer.cont.systems.homoclinic_homotopy) on the
family x'' = a (x - c) - (x - c)^2 + mu x' (the equilibrium x0 = (c, 0) solved for,
IEQUIB = 1), whose homoclinic orbit at mu = 0 is (3a/2) sech^2(sqrt(a) t / 2) for every a.

Run 1 grows the orbit from x0 + eps_0 v_u (eps_0 = PAR(14)) in T = PAR(11) and
omega = PAR(16), the distance of u(1) from x0's stable eigenline along the left unstable
eigenvector; each of its orbits is the trajectory of the ODE from that start over the
time T (checked with an independent integrator, and by the energy it conserves). Run 2
holds T and brings omega to 0 with mu free; run 3 (ISTART = 1, the projection conditions
and the phase condition) takes the orbit over and continues it in a towards the exact
family's mu = 0.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from washer.cont import runner
from washer.cont.constants import Constants
from washer.cont.problem import Problem

C = 0.3
EPS0 = 1e-4


def _problem():
    def func(u, par):
        a, mu = par[0], par[1]
        x = u[0] - C
        return np.array([u[1], a * x - x * x + mu * u[1]])

    def dfdu(u, par):
        return np.array([[0.0, 1.0], [par[0] - 2 * (u[0] - C), par[1]]])

    def stpnt(u, par, t):
        par[0], par[1], par[10] = 1.0, 0.0, 0.1
        par[11], par[12] = C, 0.0                   # x0 (IEQUIB = 1 solves f(x0) = 0)
        par[13] = EPS0                              # eps_0 = PAR(12 + NDIM IEQUIB)
        u[:] = par[11:13]
    return Problem(2, func, stpnt=stpnt, dfdu=dfdu, name="homotopy", jac=-1)


def _energy(U, a):
    """H = y^2/2 - a xi^2/2 + xi^3/3, xi = x - c: conserved at mu = 0, 0 on the
    homoclinic orbit."""
    xi, y = U[:, 0] - C, U[:, 1]
    return y * y / 2 - a * xi * xi / 2 + xi ** 3 / 3


def test_homotopy_start_grows_the_orbit_and_hands_it_to_the_projection_conditions():
    prob = _problem()
    base = dict(NDIM=2, IPS=9, IEQUIB=1, NTST=40, NCOL=4, JAC=-1, ISP=0, ILP=0, ITNW=7,
                NPAR=20)
    br1 = runner.run(Constants(dict(base, ICP=[11, 16], ISTART=3, NMX=200, DS=0.1,
                                    DSMAX=2.0, UZR={11: 15.0}, STOP=["UZ1"])), prob)
    assert br1.status == "ok"
    uz = [p for p in br1.specials if p.ty == "UZ"]
    assert len(uz) == 1
    for rec in [br1.specials[0], uz[0]]:
        U, par = np.asarray(rec.U, float), np.asarray(rec.par, float)
        T, eps0, omega = par[10], par[13], par[15]
        # the start condition u(0) = x0 + eps_0 v_u, v_u = (1, sqrt(a)) / |.| (signed
        # as EIGHO's: the largest component positive): rounding
        v_u = np.array([1.0, 1.0]) / np.sqrt(2.0)
        assert np.allclose(U[0], [C, 0.0] + eps0 * v_u, atol=1e-14)
        assert par[14] == eps0                   # xi_1 = eps_0 (STPNHO)
        # the orbit is the ODE's trajectory from u(0) over T: an independent integrator
        # (rtol 1e-12) against the collocation (NTST = 40, NCOL = 4), whose error the
        # flow amplifies by up to e^T near the saddle (measured 6e-8 at T = 15; past
        # T ~ 20 the end point is ill-conditioned at this mesh)
        sol = solve_ivp(lambda t, u: prob.func(u, par), (0, T), U[0], rtol=1e-12,
                        atol=1e-15, method="DOP853")
        assert np.allclose(sol.y[:, -1], U[-1], atol=1e-6)
        # omega = (u(1) - x0) . w_u, w_u = (1, 1) / sqrt(2) the left unstable eigenvector
        assert omega == pytest.approx((U[-1] - [C, 0.0]) @ v_u, abs=1e-12)
        # mu = 0 all along: the energy is conserved on the profile (its value at u(0),
        # O(eps_0^3) off the homoclinic orbit's 0) up to the collocation's error at the
        # nodes inside the mesh intervals (h = T / NTST up to 0.375: measured 5e-8)
        H = _energy(U, par[0])
        assert np.max(np.abs(H - H[0])) < 1e-6
    # run 2: T fixed, omega to 0 with mu free
    br2 = runner.run(Constants(dict(base, ICP=[16, 2], ISTART=3, NMX=50, DS=-0.001, DSMIN=1e-5,
                                    DSMAX=0.002, UZR={16: 0.0}, STOP=["UZ1"],
                                    IRS=uz[0].lab)), prob, br1)
    uz2 = [p for p in br2.specials if p.ty == "UZ"]
    assert br2.status == "ok" and len(uz2) == 1
    assert abs(uz2[0].par[15]) < 1e-10
    # run 3: the projection boundary conditions take over (ISTART = 1), continued in a
    br3 = runner.run(Constants(dict(base, ICP=[1, 2], ISTART=1, NMX=20, NPR=5, DS=0.05,
                                    DSMAX=0.2, IRS=uz2[0].lab)), prob, br2)
    assert br3.status == "ok" and len(br3.specials) >= 3
    mus = []
    for rec in br3.specials:
        par, U = np.asarray(rec.par, float), np.asarray(rec.U, float)
        x0 = par[11:13]
        # the equilibrium stays (c, 0) (f(x0) = 0 solved for): rounding
        assert np.allclose(x0, [C, 0.0], atol=1e-12)
        mus.append(abs(par[1]))
    # The homotopy's orbit is truncated unevenly (its start 1e-4 from x0, its end 0.18):
    # the projection conditions' error, of the order of the product of the two ends'
    # distances (which shrink as sqrt(a) grows), leaves mu off the family's 0 by 3e-4 at
    # a = 1.25, falling with every point to 2e-7 at a = 3.4 (measured)
    assert all(b < a for a, b in zip(mus, mus[1:]))
    assert mus[-1] < 1e-6 and br3.specials[-1].par[0] > 3


def test_an_orbit_whose_angle_turns_once_ends_at_the_equilibrium_plus_2_pi():
    # The pendulum theta'' = -a sin(theta) + mu theta': at mu = 0 the orbit
    # theta = 4 arctan(e^(sqrt(a) t)) - pi (sympy below) leaves the saddle (-pi, 0) and
    # reaches (pi, 0), the same equilibrium of the angle: SETRTN's NRTN = 1 puts the end's
    # equilibrium at x0 + 2 pi (FBHO's XEQUIB2), and the family is continued in (a, mu).
    import sympy as sp
    t, a = sp.symbols("t a", positive=True)
    th = 4 * sp.atan(sp.exp(sp.sqrt(a) * t)) - sp.pi
    residual = sp.diff(th, t, 2) + a * sp.sin(th)
    for tv, av in ((sp.Rational(-3, 2), 1), (sp.Rational(1, 3), 2), (2, sp.Rational(1, 2))):
        assert abs(sp.N(residual.subs({t: tv, a: av}), 40)) < 1e-35
    from pendulum_orbit import pendulum
    prob = pendulum(24.0)
    br = runner.run(Constants(dict(NDIM=2, IPS=9, IEQUIB=1, ICP=[1, 2], NTST=40, NCOL=4,
                                   JAC=-1, ISP=0, ILP=0, NMX=12, NPR=4, DS=0.05, DSMAX=0.2)),
                    prob)
    assert br.status == "ok" and br.specials[-1].par[0] > 1.5
    for rec in br.specials[1:]:
        par, U = np.asarray(rec.par, float), np.asarray(rec.U, float)
        # the equilibrium and mu of the exact family: the truncation to T = 24 (the ends
        # e^(-sqrt(a) T / 2) ~ 6e-6 from the saddle, the projection conditions' error
        # quadratic in it) and the collocation's error
        assert np.allclose(par[11:13], [-np.pi, 0.0], atol=1e-10)
        assert abs(par[1]) < 1e-6
        # the energy, 0 on the orbit, up to the collocation's error at the nodes inside
        # the mesh intervals (h = T / NTST = 0.6 against the front's width 1 / sqrt(a):
        # measured 1e-5 at a = 2)
        H = U[:, 1] ** 2 / 2 - par[0] * (1 + np.cos(U[:, 0]))
        assert np.max(np.abs(H)) < 1e-4
        assert U[-1, 0] == pytest.approx(np.pi, abs=1e-4)
