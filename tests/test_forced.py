"""The forced periodic response and its Floquet multipliers (washer.machine.forced).

Shooting is checked against closed forms (forced linear oscillator), an
independent spectral method (Hill's determinant for the damped Mathieu equation's
period doubling), harmonic balance (Duffing fold), finite differences of the flow and
scipy's solve_ivp; the washer orbit against its symmetry and the averaged system.
The engine (IPS = 2) on the system made autonomous by an appended oscillator
(AUTO's frc), is in ROUTES beside it, and on the washer (e='washer:forced',
auto_constants/c.washer.forced) checked against the shooting's TR point and multipliers.
"""
import math
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, linear_sum_assignment

from washer import Model
from washer.auto.constants_file import Constants
from washer.cont import floquet
from washer.cont.problem import Problem
from washer.cont.runner import run as run_in_memory, solve
from washer.machine import forced, kernel
from washer.problems import forced as shooting
from washer.run import run

#: Tolerances of the scipy reference integrations (DOP853): far tighter than the checks.
RTOL_REF, ATOL_REF = 1e-12, 1e-14
DATA = Path(__file__).parent / "data"


# ------------------------------------------------------------------ generic forced systems

@dataclass
class ForcedSystem:
    """u' = f(t, u, p) with forcing of period T(p) = 2 pi / nu (through cos, sin of nu t,
    so that the collocation run can generate it with an appended oscillator).
    jac(t, u, p) -> df/du (n, n); dfdp(t, u, p) -> df/dp (n,)."""
    f: callable
    jac: callable
    dfdp: callable
    nu: float

    @property
    def T(self):
        return 2 * np.pi / self.nu

    def flow(self, u0, p):
        """One period with its monodromy matrix and parameter sensitivity (scipy DOP853)."""
        n = len(u0)

        def aug(t, y):
            u, Phi, s = y[:n], y[n:n + n * n].reshape(n, n), y[n + n * n:]
            J = self.jac(t, u, p)
            return np.r_[self.f(t, u, p), (J @ Phi).ravel(), J @ s + self.dfdp(t, u, p)]

        y0 = np.r_[u0, np.eye(n).ravel(), np.zeros(n)]
        y = solve_ivp(aug, (0, self.T), y0, method="DOP853", rtol=RTOL_REF,
                      atol=ATOL_REF).y[:, -1]
        return y[:n], y[n:n + n * n].reshape(n, n), y[n + n * n:]


def flow_problem(system: ForcedSystem, u0, p0):
    """The system's period map as the engine's problem (washer.cont.systems.shooting):
    PAR(1) = p, PAR(11) = the forcing period; stpnt gives (u0, p0)."""
    n = len(u0)

    def stpnt(u, par):
        u[:] = u0
        par[0], par[10] = p0, system.T

    def func(u, par):
        raise AssertionError("a period map has no vector field")

    return Problem(n, func, stpnt, name="forced", flow=lambda u, par, i: system.flow(u, par[0]))


def shooting_constants(n, **kw):
    """IPS = 2 on a problem with a flow: shooting, Newton to 1e-10 (the flow's DOP853 at
    1e-12 leaves ~1e-12), location to EPSS = 1e-11 in arclength."""
    base = dict(NDIM=n, IPS=2, ICP=[1], ILP=1, ISP=2, NMX=400, NPR=0, ITNW=8, NWTN=8,
                ITMX=30, EPSL=1e-10, EPSU=1e-10, EPSS=1e-11, THL={11: 0.0})
    base.update(kw)
    return Constants(base, source="<forced test>")


def canonical(mu):
    """Multipliers in one order for comparisons between routes (a conjugate pair's
    members have equal moduli, so the engine's order leaves them as computed): by real,
    then imaginary part, rounded to 1e-12 first."""
    return np.sort_complex(np.round(np.asarray(mu, dtype=complex), 12))


def shooting_route(system: ForcedSystem, u0, p):
    """The engine's Newton at fixed p on the period map (AUTO's start correction);
    returns (u0 of the periodic orbit, multipliers in the engine's order)."""
    x, sysm, _ = solve(shooting_constants(len(u0)), flow_problem(system, u0, p))
    return x[:-1], canonical(sysm.multipliers(x))


def continue_flow(system: ForcedSystem, u0, p0, stop, ds, ds_max, p_scale=None,
                  max_points=400):
    """The engine's continuation of the forced orbit through (u0, p0) in p up to `stop`
    (UZSTOP), pseudo-arclength in the norm of (u0, p / p_scale) (THL(1) = 1 / p_scale^2;
    p_scale default max(|p0|, 1e-3)): the Branch and its arrays (p, u0, multipliers,
    stable) per point."""
    ps = p_scale if p_scale is not None else max(abs(p0), 1e-3)
    c = shooting_constants(len(u0), DS=ds, DSMAX=ds_max, DSMIN=1e-5, NMX=max_points,
                           UZSTOP={1: stop}, THL={1: 1 / ps ** 2, 11: 0.0})
    b = run_in_memory(c, flow_problem(system, u0, p0))
    assert b.status == "ok", b.status
    values = np.array([r.par[0] for r in b.rows])
    return b, values, np.array([r.U for r in b.rows]), \
        np.array([r.stability.values for r in b.rows]), np.array([bool(r.stable) for r in b.rows])


def located(b, *types):
    """The located special points of a Branch (no EP, UZ)."""
    return [r for r in b.specials if r.ty not in ("EP", "UZ", "")]


#: Collocation intervals of the collocation runs on the small test systems: the nodes' error is
#: ~1e-11 at 40 (Gauss collocation is superconvergent there), ~4e-9 at 20.
ENGINE_NTST = 40


def engine_route(system: ForcedSystem, u0, p):
    """The engine (IPS = 2, AUTO's frc way). The system is made autonomous by
    the oscillator x' = x + nu y - x (x^2 + y^2), y' = -nu x + y - y (x^2 + y^2), whose
    cycle is (sin nu t, cos nu t), with t = atan2(x, y) / nu, and continued in p from
    p = 0, where the orbit is u = 0 (the systems here have f(t, 0, 0) = 0), to UZ at p.
    u0 is not needed (a homotopy, like frc's). Returns the orbit at t = 0 (the node at
    s = 0 moved to theta = 0 by DOP853, over the ~1e-10 rad the phase condition lets it
    drift) and the multipliers without the oscillator's (1 and exp(-2 T))."""
    n, nu = len(u0), system.nu

    def func(u, par):
        x, y = u[n], u[n + 1]
        r2 = x * x + y * y
        return np.r_[system.f(np.arctan2(x, y) / nu, u[:n], par[0]),
                     x + nu * y - x * r2, -nu * x + y - y * r2]

    def stpnt(u, par, t=0.0):
        par[0], par[10] = 0.0, system.T
        u[:n] = 0.0
        u[n:] = np.sin(2 * np.pi * t), np.cos(2 * np.pi * t)

    with tempfile.TemporaryDirectory() as d:
        c = Path(d) / "c.forced"
        c.write_text(f"NDIM = {n + 2}, IPS = 2, IRS = 0, ICP = [1, 11], ISP = 2\n"
                     f"NTST = {ENGINE_NTST}, NCOL = 4, NMX = 100, EPSL = 1e-10, EPSU = 1e-10\n"
                     f"DS = {0.2 * p}, DSMAX = {p}, UZSTOP = {{1: {p}}}\n")
        res = run(c, verbose=False, problem=Problem(n + 2, func, stpnt, name="forced"))
    uz = res("UZ1")
    U = np.asarray(uz.u)
    t0 = math.atan2(U[0, n], U[0, n + 1]) / nu
    u = solve_ivp(lambda t, v: system.f(t, v, p), (t0, 0.0), U[0, :n], method="DOP853",
                  rtol=RTOL_REF, atol=ATOL_REF).y[:, -1] if t0 else U[0, :n]
    return u, _without_oscillator(uz.stability.values, uz.par[10])


def _without_oscillator(mu, T):
    """Multipliers of the collocation runs less the oscillator's trivial 1 and radial
    exp(-2 T), in the `canonical` order."""
    mu = np.asarray(mu, dtype=complex)
    mu = np.delete(mu, np.argmin(np.abs(mu - 1)))
    mu = np.delete(mu, np.argmin(np.abs(mu - np.exp(-2 * T))))
    return canonical(mu)


#: Ways of computing a forced periodic orbit and its multipliers: Newton shooting and
#: the engine with IPS = 2 and the forcing from an appended oscillator (AUTO's frc).
ROUTES = {"shooting": shooting_route, "engine": engine_route}


def linear_oscillator(zeta=0.05, w0=3.0, F0=0.7, nu=2.3):
    """x'' + 2 zeta w0 x' + w0^2 x = F0 cos(nu t), p = F0."""
    return ForcedSystem(
        f=lambda t, u, p: np.array([u[1], p * np.cos(nu * t) - 2 * zeta * w0 * u[1]
                                    - w0 ** 2 * u[0]]),
        jac=lambda t, u, p: np.array([[0.0, 1.0], [-w0 ** 2, -2 * zeta * w0]]),
        dfdp=lambda t, u, p: np.array([0.0, np.cos(nu * t)]), nu=nu)


def linear_oscillator_exact(zeta, w0, F0, nu):
    """Closed form of `linear_oscillator`: x = A cos(nu t) + B sin(nu t) with
    (w0^2 - nu^2) A + 2 zeta w0 nu B = F0 and (w0^2 - nu^2) B - 2 zeta w0 nu A = 0, and
    the multipliers exp(lambda T) of the free oscillation. Returns (A, B, multipliers)."""
    D = (w0 ** 2 - nu ** 2) ** 2 + (2 * zeta * w0 * nu) ** 2
    A, B = F0 * (w0 ** 2 - nu ** 2) / D, F0 * 2 * zeta * w0 * nu / D
    lam = -zeta * w0 + 1j * w0 * np.sqrt(1 - zeta ** 2)
    T = 2 * np.pi / nu
    return A, B, canonical(np.exp(np.array([lam, lam.conjugate()]) * T))


@pytest.mark.parametrize("route", sorted(ROUTES))
def test_forced_linear_oscillator_matches_closed_form(route):
    zeta, w0, F0, nu = 0.05, 3.0, 0.7, 2.3
    sys_ = linear_oscillator(zeta, w0, F0, nu)
    A, B, mu_exact = linear_oscillator_exact(zeta, w0, F0, nu)
    u, mu = ROUTES[route](sys_, np.zeros(2), F0)
    # The orbit is ~0.2 in size; DOP853 at 1e-12 leaves ~1e-12, Newton stops at 1e-10
    # relative: 1e-9 is what the two allow with margin.
    assert np.allclose(u, [A, B * nu], rtol=0, atol=1e-9)
    assert np.allclose(mu, mu_exact, rtol=0, atol=1e-9)


def test_forced_linear_oscillator_from_a_user_file_matches_closed_form(tmp_path):
    """The collocation run as an AUTO user runs it: tests/data/forced_linear/flin.py (the oscillator
    appended by hand, the forcing F0 cos(nu t) = F0 y) and c.flin, a homotopy in F0 from
    frc-style exact start data at F0 = 0 to UZ at F0 = 0.7. The whole orbit at every mesh
    node, at its own time t = atan2(x, y) / nu, and the multipliers against the closed
    form; the period stays 2 pi / nu. Collocation at NTST = 40 leaves ~1e-10 at the nodes
    (measured 7e-11 in w, 1e-11 in the multipliers): 1e-9."""
    for f in (DATA / "forced_linear").iterdir():
        shutil.copy(f, tmp_path)
    res = run(tmp_path / "c.flin", verbose=False)
    uz = res("UZ1")
    par = uz.par
    F0, zeta, w0, nu = par[:4]
    assert F0 == pytest.approx(0.7, abs=1e-12)
    A, B, mu_exact = linear_oscillator_exact(zeta, w0, F0, nu)
    U = np.asarray(uz.u)
    t = np.arctan2(U[:, 2], U[:, 3]) / nu
    v = A * np.cos(nu * t) + B * np.sin(nu * t)
    w = nu * (B * np.cos(nu * t) - A * np.sin(nu * t))
    assert np.abs(U[:, 0] - v).max() < 1e-9 and np.abs(U[:, 1] - w).max() < 1e-9
    assert np.abs(U[:, 2] ** 2 + U[:, 3] ** 2 - 1).max() < 1e-9
    assert abs(par[10] - 2 * np.pi / nu) < 1e-9
    assert np.allclose(_without_oscillator(uz.stability.values, par[10]), mu_exact,
                       rtol=0, atol=1e-9)


def test_continuation_of_linear_oscillator_is_linear_in_the_forcing():
    """The response of a linear oscillator is proportional to F0: every continued point
    must lie on the closed-form line, with the same multipliers everywhere."""
    sys_ = linear_oscillator()
    u0, _ = shooting_route(sys_, np.zeros(2), 0.7)
    b, values, us, mus, _ = continue_flow(sys_, u0, 0.7, 2.0, ds=0.2, ds_max=0.5)
    assert values[-1] == pytest.approx(2.0, abs=1e-12) and len(values) >= 4
    assert np.allclose(us, np.outer(values / 0.7, u0), atol=1e-9)
    assert np.allclose(mus, mus[0], atol=1e-9)
    assert located(b) == []


def mathieu(c=0.1, q=0.3, F0=0.5):
    """x'' + c x' + (a + 2 q cos 2t) x = F0 cos 2t (period pi), parameter p = a."""
    return ForcedSystem(
        f=lambda t, u, a: np.array([u[1], F0 * np.cos(2 * t) - c * u[1]
                                    - (a + 2 * q * np.cos(2 * t)) * u[0]]),
        jac=lambda t, u, a: np.array([[0.0, 1.0], [-(a + 2 * q * np.cos(2 * t)), -c]]),
        dfdp=lambda t, u, a: np.array([0.0, -u[0]]), nu=2.0)


def hill_pd_boundaries(c, q, n_harm=12):
    """Values of a where the damped Mathieu equation has a multiplier -1: zeros of Hill's
    determinant on the 2 pi-periodic, pi-antiperiodic Fourier basis e^{i n t}, n odd:
    (a - n^2 + i c n) x_n + q (x_{n-2} + x_{n+2}) = 0 (real determinant: the basis is
    closed under n -> -n with conjugation)."""
    ns = np.arange(-(2 * n_harm - 1), 2 * n_harm, 2)

    def det(a):
        M = np.diag(a - ns ** 2 + 1j * c * ns) + q * (np.eye(ns.size, k=1) + np.eye(ns.size, k=-1))
        return np.linalg.det(M).real

    # First instability tongue around a = 1: boundaries near 1 -+ sqrt(q^2 - c^2).
    w = np.sqrt(q ** 2 - c ** 2)
    return brentq(det, 1 - 2 * w, 1.0), brentq(det, 1.0, 1 + 2 * w)


def test_period_doubling_located_on_damped_mathieu_equation():
    c, q = 0.1, 0.3
    sys_ = mathieu(c, q)
    u0, _ = shooting_route(sys_, np.zeros(2), 0.5)
    b, values, _, _, stable = continue_flow(sys_, u0, 0.5, 1.5, ds=0.1, ds_max=0.2)
    pd = located(b)
    assert [s.ty for s in pd] == ["PD", "PD"]
    exact = hill_pd_boundaries(c, q)
    # Hill's determinant with 12 odd harmonics is exact to roundoff here (q^12 / 12!^2);
    # the located values carry the flow's ~1e-11 error divided by d mu / d a ~ O(1).
    assert np.allclose([s.par[0] for s in pd], exact, atol=1e-8)
    for s in pd:
        assert abs(floquet.critical(s.stability.values, trivial=False) + 1) < 1e-8
    # Between the two PD points the response is unstable (a multiplier below -1); the
    # PD rows themselves carry the stability of the point before them (AUTO's rule).
    regular = np.array([not r.lab for r in b.rows])
    inside = (values > exact[0] + 1e-6) & (values < exact[1] - 1e-6) & regular
    outside = ((values < exact[0] - 1e-6) | (values > exact[1] + 1e-6)) & regular
    assert inside.any() and not stable[inside].any() and stable[outside].all()


def duffing(c=0.1, beta=1.0, nu=1.5):
    """x'' + c x' + x + beta x^3 = F cos(nu t), parameter p = F."""
    return ForcedSystem(
        f=lambda t, u, F: np.array([u[1], F * np.cos(nu * t) - c * u[1] - u[0]
                                    - beta * u[0] ** 3]),
        jac=lambda t, u, F: np.array([[0.0, 1.0], [-1 - 3 * beta * u[0] ** 2, -c]]),
        dfdp=lambda t, u, F: np.array([0.0, np.cos(nu * t)]), nu=nu)


@pytest.mark.slow
def test_fold_of_duffing_response_is_passed_and_located():
    """Hardening Duffing above resonance: the response against forcing F is S-shaped.
    Pseudo-arclength passes both folds (LP), where a multiplier is +1; their F agree
    with one-harmonic balance to its accuracy."""
    c, beta, nu = 0.1, 1.0, 1.5
    sys_ = duffing(c, beta, nu)
    u0, _ = shooting_route(sys_, np.zeros(2), 0.1)
    b, values, _, _, _ = continue_flow(sys_, u0, 0.1, 1.0, ds=0.3, ds_max=1.0, p_scale=0.1,
                                       max_points=200)
    lp = located(b)
    assert values[-1] == pytest.approx(1.0, abs=1e-12) and [s.ty for s in lp] == ["LP", "LP"]
    for s in lp:
        assert np.abs(s.stability.values - 1).min() < 1e-8
    # The parameter turns at each LP: the branch's F reaches a local extremum there.
    for s in lp:
        k = np.argmin(np.abs(values - s.par[0]))
        nb = values[max(k - 2, 0):k + 3]
        assert s.par[0] >= nb.max() - 1e-9 or s.par[0] <= nb.min() + 1e-9
    # Harmonic balance x = a cos(nu t + phi): F^2 = a^2 ((1 - nu^2 + 3/4 beta a^2)^2 +
    # (c nu)^2); its folds are the extrema of F(a). The neglected third harmonic is
    # ~ beta a^3 / (32 nu^2) relative: a few per cent at these amplitudes.
    a = np.linspace(0.05, 3.0, 20001)
    F = a * np.sqrt((1 - nu ** 2 + 0.75 * beta * a ** 2) ** 2 + (c * nu) ** 2)
    ext = np.where(np.diff(np.sign(np.diff(F))) != 0)[0] + 1
    assert len(ext) == 2
    assert np.allclose(sorted(s.par[0] for s in lp), sorted(F[ext]), rtol=0.05)


# ------------------------------------------------------------------ the washer kernel's flow

@pytest.fixture(scope="module")
def nominal(params):
    return shooting.periodic_response(params)


def test_monodromy_matches_finite_differences_of_the_flow(params, nominal):
    """Variational equations (one kernel call) against central differences of the flow map
    (the kernel's plain DOPRI5 at rtol 1e-13). The difference combines the truncation
    error h^2 |D^3 phi| (~1e-10 with h = 1e-6 m, 1e-5 m/s) and the integration noise
    1e-13 / h (~1e-8 absolute): 1e-7 relative to max|Phi| bounds both."""
    P, T, u0 = params.vector(), nominal.T, nominal.u0
    _, Phi, _, _ = kernel.flow_variational(0.0, T, u0, P)

    def flow(u):
        return kernel.integrate("fixed", "constant", 0.0, u, P, [T], 1e-13, 1e-15)[0][0]

    h = np.r_[np.full(6, 1e-6), np.full(6, 1e-5)]
    FD = np.column_stack([(flow(u0 + h[j] * e) - flow(u0 - h[j] * e)) / (2 * h[j])
                          for j, e in enumerate(np.eye(12))])
    assert np.abs(FD - Phi).max() <= 1e-7 * np.abs(Phi).max()
    # Not the identity or a stale matrix: the flow really contracts/expands.
    assert np.abs(Phi - np.eye(12)).max() > 0.1


def test_variational_flow_matches_solve_ivp(params, nominal):
    """Same augmented system (u, Phi, du/dC_p) through scipy's DOP853 at 1e-12 with the
    kernel's rhs and Jacobians: agreement to the kernel's own tolerance (rtol 1e-10 on
    entries up to ~10: 1e-9)."""
    P, T, u0 = params.vector(), nominal.T, nominal.u0
    d = forced.direction_of(params.tied, "C_p")
    uT, Phi, s, _ = kernel.flow_variational(0.0, T, u0, P, "constant", d)

    def aug(t, y):
        J, Jp = kernel.jac_fixed(t, y[:12], P, "constant")
        return np.r_[kernel.rhs_fixed(t, y[:12], P, "constant"),
                     (J @ y[12:156].reshape(12, 12)).ravel(), J @ y[156:] + Jp @ d]

    y = solve_ivp(aug, (0, T), np.r_[u0, np.eye(12).ravel(), np.zeros(12)], method="DOP853",
                  rtol=RTOL_REF, atol=ATOL_REF).y[:, -1]
    assert np.abs(y[:12] - uT).max() < 1e-9
    assert np.abs(y[12:156].reshape(12, 12) - Phi).max() < 1e-9
    assert np.abs(y[156:] - s).max() < 1e-9 and np.abs(s).max() > 1e-3


@pytest.mark.parametrize("name", ["C_p", "Omega"])
def test_parameter_sensitivity_matches_finite_differences(params, nominal, name):
    """du(T)/dp, for Omega including the change of the period T = 1/Omega; central
    differences with h = 1e-4 (relative) at rtol 1e-13: truncation h^2 |d^3 u / dp^3| and
    noise 1e-13 / h, both below 1e-7 relative."""
    u0 = nominal.u0
    gp = forced.shoot(params, u0, name)[2]
    h = 1e-4 * params[name]

    def flow(v):
        q = params.replace(**{name: v})
        return kernel.integrate("fixed", "constant", 0.0, u0, q.vector(), [1 / q["Omega"]],
                                1e-13, 1e-15)[0][0]

    fd = (flow(params[name] + h) - flow(params[name] - h)) / (2 * h)
    assert np.abs(fd - gp).max() <= 1e-7 * np.abs(gp).max()


# ------------------------------------------------------------------ the washer orbit

def test_orbit_is_periodic_and_newton_converges_quadratically(nominal):
    assert nominal.residual < 1e-10 and nominal.iterations <= 4
    t, xi = nominal.rotating(8)
    assert xi.shape == (8, 12)


def test_long_simulation_start_reaches_the_same_orbit(params):
    """Two starts (the averaged equilibrium; 300 periods of simulation from rest) give one
    orbit where it is stable (C_p = 0.2): 1e-9, a few Newton tolerances."""
    q = params.replace(C_p=0.2)
    a = shooting.periodic_response(q)
    b = shooting.periodic_response(q, forced.simulated_start(q))
    assert np.abs(a.u0 - b.u0).max() < 1e-9
    assert np.abs(a.multipliers - b.multipliers).max() < 1e-9


def test_rotating_frame_coordinates_have_half_the_forcing_period(nominal):
    """Four identical rods: a quarter turn with theta -> theta + pi/2 is a symmetry of
    eq 48. The orbit's positions (eps1..3, a true vector) are T/4-periodic in the rotating
    frame; the Cardan angles map under a quarter turn to Ry(alpha) Rx(-beta) Rz(gamma),
    not (-beta, alpha, gamma), so eps4..6 are only T/2-periodic (a half turn maps them to
    (-alpha, -beta, gamma) exactly). Tolerance 1e-8: Newton residual 1e-10 and DOPRI5 at
    rtol 1e-10 over one period (measured ~3e-10)."""
    n = 64
    _, xi = nominal.rotating(n)
    half = np.roll(xi, -n // 2, axis=0)
    quarter = np.roll(xi, -n // 4, axis=0)
    assert np.abs(xi - half).max() < 1e-8
    pos = [0, 1, 2, 6, 7, 8]
    ang = [3, 4, 5, 9, 10, 11]
    assert np.abs(xi[:, pos] - quarter[:, pos]).max() < 1e-8
    # ... but not the angles: their T/4 mismatch (~4e-4 rad in gamma) is far above it.
    assert np.abs(xi[:, ang] - quarter[:, ang]).max() > 1e-5
    # And the orbit is not constant in the rotating frame (the 2 Omega harmonic is real).
    assert np.ptp(xi[:, 5]) > 1e-5
    # The cause is the coordinates, not the motion: the tub's orientation matrix seen from
    # the rotating frame, Rz(-tau) A(alpha, beta, gamma) Rz(tau) (eq 2), is T/4-periodic.
    t = np.arange(n) * nominal.T / n
    q = np.array([forced.ground_from_rotating(x, nominal.params["Omega"], ti)[:6]
                  for x, ti in zip(xi, t)])
    tau = 2 * np.pi * nominal.params["Omega"] * t
    B = np.array([_rot("z", -a) @ _rot("x", qi[3]) @ _rot("y", qi[4]) @ _rot("z", qi[5])
                  @ _rot("z", a) for a, qi in zip(tau, q)])
    assert np.abs(B - np.roll(B, -n // 4, axis=0)).max() < 1e-8


def _rot(axis, a):
    c, s = np.cos(a), np.sin(a)
    return {"x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
            "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])}[axis]


def _matched_errors(params):
    r = shooting.periodic_response(params)
    m = Model(params)
    eps = m.rotating_equilibrium(frame="averaged")
    mu_avg = np.exp(m.eigenvalues(eps, frame="averaged") * r.T)
    D = np.abs(r.multipliers[:, None] - mu_avg[None, :])
    i, j = linear_sum_assignment(D)
    # Size of the tau-dependent part of the rotating-frame right-hand side at eps*:
    # largest Fourier coefficient (k >= 1) of the frozen rhs over 16 frame angles.
    xi = np.r_[eps, np.zeros(6)]
    f = np.array([kernel.rhs_rot(xi, params.replace(tau0=2 * np.pi * k / 16).vector(), "frozen")
                  for k in range(16)])
    osc = np.abs(np.fft.fft(f, axis=0)[1:] / 16).max()
    return D[i, j].max(), osc


def test_multipliers_agree_with_averaged_eigenvalues_to_second_order(params):
    """Far from the TR point (C_p = 0.2: leading |mu| = 0.99, not ~1), mu = exp(lambda T)
    of the averaged system holds to the order first-order averaging promises: its error is
    second order in the size eps of the tau-dependent part of the rotating-frame equations.
    Halving the imbalance divides eps (at the equilibrium, quadratic in m_u: the 2 Omega
    Cardan harmonic) by ~3.8 and must divide the multiplier error by its square, ~15
    (a first-order error would give ~3.8): slope 2 +- 0.25. At nominal imbalance the
    error is measured 3.3e-6, hence the bound 1e-5."""
    p1 = params.replace(C_p=0.2)
    p2 = p1.replace(m_u=0.5 * p1["m_u"])
    e1, o1 = _matched_errors(p1)
    e2, o2 = _matched_errors(p2)
    assert e1 < 1e-5
    slope = np.log(e1 / e2) / np.log(o1 / o2)
    assert 1.75 < slope < 2.25, slope


# ------------------------------------------------------------------ TR: the exact critical C_p

@pytest.fixture(scope="module")
def critical(params):
    return shooting.critical_cp(params)


def test_exact_critical_cp_near_averaged_and_far_from_frozen(critical):
    """docs/model.md section 4: averaged Hopf at C_p ~ 0.1010, frozen (tau0 = 0) ~ 0.0745, and
    averaging matches the exact Floquet result to ~1e-4 relative."""
    ex, av, fr = critical["C_p_exact"], critical["C_p_averaged"], critical["C_p_frozen"]
    assert abs(av - 0.1010) < 5e-5 and abs(fr - 0.0745) < 5e-5
    assert 0 < abs(ex - av) / av < 1e-3
    # A complex pair on the unit circle (to Brent's tolerance on C_p times d|mu|/dC_p).
    mu_c = critical["critical_multiplier"]
    assert abs(abs(mu_c) - 1) < 1e-9 and abs(mu_c.imag) > 0.1
    # Its exponent is the averaged crossing pair (+-58.93i rad/s, rotating frame) seen from
    # the ground: Im = +-(omega_rot - 2 pi Omega), the ~3.9 rad/s whirl; equal to 1e-3 rad/s
    # (the exponent error of averaging is ~3e-5 1/s, second test above).
    w_avg = abs(critical["averaged_eigenvalues"][0].imag)
    assert abs(abs(critical["critical_exponent"].imag) - abs(w_avg - 2 * np.pi * 10.0)) < 1e-3


def test_critical_cp_near_the_averaged_value_is_the_whole_brackets_tr_point(params, critical):
    """critical_cp looks first within +-0.2 % of the averaged Hopf value; the whole 5 %
    bracket, continued from its lower end, locates the same TR point: to the location
    tolerance in C_p (EPSS = 1e-11 on an arclength that is C_p itself, THU = 0)."""
    av = critical["C_p_averaged"]
    _, rec = shooting.locate_tr(params, "C_p", (0.95 * av, 1.05 * av))
    assert abs(rec.par[0] - critical["C_p_exact"]) < shooting.EPS_LOCATE


def test_stability_changes_at_the_located_tr_point(params, critical):
    cp = critical["C_p_exact"]
    below = shooting.periodic_response(params.replace(C_p=cp * (1 - 1e-4)))
    above = shooting.periodic_response(params.replace(C_p=cp * (1 + 1e-4)))
    assert not below.stable and above.stable


def test_continuation_in_cp_detects_the_same_tr_point(params, engine_run):
    """The shooting continuation in C_p (pseudo-arclength in (u0, C_p)) finds one TR, at
    the C_p where the collocation run (an independent discretisation: the system made
    autonomous, Gauss collocation) finds it: 1e-9 (both are converged far below)."""
    b = shooting.continue_response(params.replace(C_p=0.08), "C_p", 0.13, ds=0.1,
                                   ds_max=0.3)
    tr = [s for s in b.specials if s.ty not in ("EP", "UZ")]
    assert [s.ty for s in tr] == ["TR"]
    assert abs(tr[0].par[0] - engine_run("TR1").par[0]) < 1e-9
    assert not b.rows[0].stable and b.rows[-1].stable


@pytest.mark.parametrize("name", ["m_u", "R_u", "C_a", "K_s", "Omega"])
def test_tr_in_any_parameter_lies_on_the_critical_cp_surface(params, name):
    """Two-parameter consistency: the TR point found by continuing the nominal response
    (C_p = 0.101, just below the exact critical 0.1010126) in parameter `name` must be a
    point where the exact critical C_p, located independently in C_p, is 0.101. Both
    locations are converged to ~1e-12 in their parameter; the multipliers' smooth
    integration error moves them together (5e-12 between rtol 1e-10 and 1e-12 at
    nominal values), so 1e-9 is a safe bound. The TR point lies ~1e-4 (relative) from the
    start, and the engine tests no sign change on its first two steps (AUTO's hidden
    first step and first written interval): the first step is 1e-5."""
    b = shooting.continue_response(params, name, 0.98 * params[name], ds=1e-5, ds_max=0.01)
    tr = [s for s in b.specials if s.ty == "TR"]
    index = {n: i for i, n in shooting.PAR_NAMES.items()}[name]
    assert len(tr) == 1 and b.rows[-1].stable and not b.rows[0].stable
    q = params.replace(**{name: float(tr[0].par[index - 1])})
    r, sp = shooting.locate_tr(q, "C_p", (0.1, 0.102), tr[0].U)
    assert abs(sp.par[0] - params["C_p"]) < 1e-9


# ------------------------------------------------------------------ the collocation run on the washer

CONSTANTS = Path(__file__).resolve().parent.parent / "auto_constants"


@pytest.fixture(scope="module")
def engine_run(tmp_path_factory):
    """auto_constants/c.washer.forced as shipped: C_p from 0 to 0.5, TR located."""
    d = tmp_path_factory.mktemp("forced")
    shutil.copy(CONSTANTS / "c.washer.forced", d)
    return run(d / "c.washer.forced", verbose=False)


def test_engine_tr_point_and_multipliers_agree_with_shooting(engine_run, critical):
    """The check of the collocation run against the shooting: the TR point in C_p and the
    multipliers there agree to 1e-6. Measured 5e-12 in C_p and 7e-12 in the multipliers:
    Gauss collocation (NTST = 20, NCOL = 4) is superconvergent at the mesh nodes (error
    h^8: 1.4e-9 at NTST = 10), the shooting's flow is at rtol 1e-10, and Muller's last step
    is far below EPSS = 1e-7; 1e-9 bounds all three with margin. The 14 multipliers are
    the shooting's 12 plus the oscillator's: the trivial 1 (first, AUTO's order) and its
    radial exp(-2 T) (the monodromy matrix is block triangular)."""
    assert engine_run.status == "ok"
    assert [r.ty for r in engine_run.specials if r.ty] == ["EP", "TR", "UZ"]
    tr = engine_run("TR1")
    assert abs(tr.par[0] - critical["C_p_exact"]) < 1e-9
    mu_a, T = np.asarray(tr.stability.values), tr.par[10]
    assert abs(mu_a[0] - 1) < 1e-9 and np.abs(mu_a - np.exp(-2 * T)).min() < 1e-9
    mu = _without_oscillator(mu_a, T)
    D = np.abs(mu[:, None] - critical["multipliers"][None, :])
    i, j = linear_sum_assignment(D)
    assert D[i, j].max() < 1e-9
    assert abs(abs(floquet.torus_pair(mu, trivial=False)) - 1) < 1e-9


def test_engine_branch_starts_on_the_orbit_and_changes_stability_at_tr(params, engine_run,
                                                                      critical):
    """The start is the shooting's orbit at the file's PAR (C_p = 0, not the reference
    0.101: stpnt is not corrected, so it must be computed there), the response is unstable
    below the TR point and stable above it up to C_p = 0.5, and the period stays 1/Omega
    on every point (the oscillator fixes it; Newton's EPSU = 1e-8 bounds its drift)."""
    rows = engine_run.rows
    cp = np.array([r.par[0] for r in rows])
    assert cp[0] == 0.0 and cp[-1] == pytest.approx(0.5, abs=1e-9)
    start = shooting.periodic_response(params.replace(C_p=0.0))
    assert np.abs(np.asarray(rows[0].u)[0, :12] - start.u0).max() < 1e-9
    stable = np.array([bool(r.stable) for r in rows])
    below, above = cp < critical["C_p_exact"] - 1e-6, cp > critical["C_p_exact"] + 1e-6
    assert below.sum() >= 3 and above.sum() >= 3
    assert not stable[below].any() and stable[above].all()
    assert max(abs(r.par[10] - 1 / params["Omega"]) for r in rows) < 1e-9


def test_forced_problem_is_the_kernel_rhs_at_the_oscillator_angle(params):
    """e='washer:forced': the washer rows are the kernel's rhs_fixed at the time
    theta / (2 pi Omega), theta = atan2(x, y), on the oscillator's cycle and off it
    (radius 0.7); the oscillator rows are frc's; the Jacobian (JAC = 1: kernel jac_fixed
    plus a central difference in theta) equals the engine's central differences of the
    whole right-hand side (JAC = 0) to their accuracy, ~1e-8 relative. stpnt's state at
    t = 0 is the shooting's orbit, periodic in t."""
    from washer.problems.washer import washer_problem
    pr = washer_problem("washer:forced", params=params)
    u0, par = pr.start(pr.npar)
    r = shooting.periodic_response(params)
    assert np.array_equal(u0[:12], r.u0) and np.array_equal(u0[12:], [0.0, 1.0])
    assert par[0] == params["C_p"] and par[10] == pytest.approx(0.1, rel=1e-15)
    P, w = params.vector(), 2 * np.pi * params["Omega"]
    rng = np.random.default_rng(11)
    for theta, rad in zip(rng.uniform(-np.pi, np.pi, 4), (1.0, 1.0, 0.7, 0.7)):
        x, y = rad * np.sin(theta), rad * np.cos(theta)
        u = np.r_[u0[:12] + 1e-3 * rng.standard_normal(12), x, y]
        f = pr.func(u, par)
        ref = kernel.rhs_fixed(theta / w, u[:12], P, "constant")
        assert np.abs(f[:12] - ref).max() <= 1e-12 * np.abs(ref).max()
        assert np.allclose(f[12:], [x + w * y - x * rad ** 2, -w * x + y - y * rad ** 2],
                           rtol=1e-15, atol=1e-12)
        J, J_fd = pr.with_jac(1).dfdu(u, par), pr.with_jac(0).dfdu(u, par)
        assert np.abs(J - J_fd).max() <= 1e-8 * np.abs(J).max()
    u1, scratch = np.zeros(14), np.zeros(16)
    pr._stpnt(u1, scratch, 1.0)
    assert np.array_equal(u1[:12], u0[:12])


def test_flow_variational_refuses_bad_input(params, nominal):
    P = params.vector()
    with pytest.raises(kernel.KernelError):
        kernel.flow_variational(0.1, 0.0, nominal.u0, P)          # t1 < t0
    with pytest.raises(kernel.KernelError):
        kernel.flow_variational(0.0, 0.1, np.full(12, np.nan), P)
    with pytest.raises(ValueError):
        kernel.flow_variational(0.0, 0.1, nominal.u0, P, direction=np.ones(3))
    # No direction: no parameter sensitivity, the flow and Phi unchanged.
    u1, Phi, s, _ = kernel.flow_variational(0.0, nominal.T, nominal.u0, P)
    u1d, Phid, sd, _ = kernel.flow_variational(0.0, nominal.T, nominal.u0, P, "constant",
                                               forced.direction_of(params.tied, "K_s"))
    assert not s.any() and np.abs(sd).max() > 0
    assert np.abs(u1 - u1d).max() < 1e-9 and np.abs(Phi - Phid).max() < 1e-8


@pytest.mark.slow
def test_report_section_fig4_is_the_torus_locus_checked_by_shooting(params, tmp_path):
    """The section's exact Fig 4 curve (quick mode) is the continued TR locus
    (collocation, c.washer.forced.tr) from C_p,crit = 0 up to Table 1's 15 Hz, and it
    agrees with the independent one-parameter TR locations by shooting (critical_cp at
    its start, locate_tr in Omega at C_p = 0 for its lower end, 6 Hz along it; the full
    mode adds points at 5 and 12.5 Hz) to CHECK_TOL = 1e-8:
    both routes are exact up to their discretisation (collocation superconvergent at
    NTST = 10, ~1e-12 in C_p and ~1e-9 Hz at the lower end; DOPRI5 at RTOL = 1e-10).
    The Markdown states the computed numbers and the JSON is valid."""
    from washer.paper import exact_stability
    import json
    import re
    res = exact_stability.compute(params, quick=True, ends=False, progress=lambda *_: None)
    f4 = res["fig4"]
    loc, tol = f4["locus"], exact_stability.CHECK_TOL
    assert f4["check_tol"] == tol == 1e-8
    # the locus itself: its ends are its UZSTOPs, and it passes the nominal TR point
    assert abs(loc["ends"]["low"]["C_p"]) < 1e-12 and loc["ends"]["high"]["Omega"] == \
        pytest.approx(15.0, abs=1e-12)
    assert loc["monotone"] and np.all(np.diff(f4["C_p_exact"]) > 0)   # rises with speed
    assert len(f4["Omega"]) >= 8 and f4["Omega"][0] < 4.0 < 14.0 < f4["Omega"][-1]
    # the independent checks: at the nominal speed (the section's own location; quick mode)
    assert len(f4["checks"]) == 1
    assert f4["checks"][0]["Omega"] == pytest.approx(params["Omega"], abs=1e-9)
    for c in f4["checks"]:
        assert abs(c["C_p_locus"] - c["C_p_shooting"]) <= tol, c
    assert f4["checks"][0]["C_p_shooting"] == res["nominal"]["C_p_exact"]
    low = f4["Omega_low"]
    assert abs(low["exact"] - low["shooting"]) <= tol
    assert 0.0 < low["averaged"] - low["exact"] < 1e-3   # averaging's lower end is close
    # exact - averaged is averaging's O(1e-5) error, positive, at every point with a Hopf
    err = f4["error"][np.isfinite(f4["error"])]
    assert len(err) == len(f4["Omega"]) - 1 and np.all((err > 0) & (err < 1e-4))
    md = exact_stability.markdown(res)
    assert f"{res['nominal']['C_p_exact']:.10f}" in md
    assert f"{res['nominal']['C_p_averaged']:.10f}" in md
    assert f"{low['shooting']:.9f}" in md and f"{low['exact']:.9f}" in md
    assert not re.search(r"\bnan\b", md) and "resonances" in md
    assert md.count("\n| ") >= 3 + 2 + len(f4["Omega"])
    json.loads(json.dumps(exact_stability._jsonable(res)))
