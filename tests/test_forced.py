"""The forced periodic response and its Floquet multipliers (washer.forced, issue 11).

Route (b), shooting, is checked against closed forms (forced linear oscillator), an
independent spectral method (Hill's determinant for the damped Mathieu equation's
period doubling), harmonic balance (Duffing fold), finite differences of the flow and
scipy's solve_ivp; the washer orbit against its symmetry and the averaged system.
Route (a) (the engine, IPS = 2, appended oscillator) plugs into ROUTES when it exists.
"""
from dataclasses import dataclass

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, linear_sum_assignment

from washer import Model, forced, kernel

#: Tolerances of the scipy reference integrations (DOP853): far tighter than the checks.
RTOL_REF, ATOL_REF = 1e-12, 1e-14


# ------------------------------------------------------------------ generic forced systems

@dataclass
class ForcedSystem:
    """u' = f(t, u, p) with forcing of period T(p) = 2 pi / nu (through cos, sin of nu t,
    so that route (a) can generate it with an appended oscillator).
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


def shooting_route(system: ForcedSystem, u0, p):
    """Route (b): Newton shooting; returns (u0 of the periodic orbit, multipliers)."""
    u, Phi, *_ = forced.newton_periodic(lambda v: system.flow(v, p)[:2] + (0,), u0)
    return u, forced.sort_multipliers(np.linalg.eigvals(Phi))


#: Routes computing a forced periodic orbit and its multipliers. Route (a), the engine
#: with IPS = 2 and the forcing from an appended oscillator (AUTO's frc demo), is added
#: here when the periodic-orbit engine exists.
ROUTES = {"shooting": shooting_route}


def linear_oscillator(zeta=0.05, w0=3.0, F0=0.7, nu=2.3):
    """x'' + 2 zeta w0 x' + w0^2 x = F0 cos(nu t), p = F0."""
    return ForcedSystem(
        f=lambda t, u, p: np.array([u[1], p * np.cos(nu * t) - 2 * zeta * w0 * u[1]
                                    - w0 ** 2 * u[0]]),
        jac=lambda t, u, p: np.array([[0.0, 1.0], [-w0 ** 2, -2 * zeta * w0]]),
        dfdp=lambda t, u, p: np.array([0.0, np.cos(nu * t)]), nu=nu)


@pytest.mark.parametrize("route", sorted(ROUTES))
def test_forced_linear_oscillator_matches_closed_form(route):
    zeta, w0, F0, nu = 0.05, 3.0, 0.7, 2.3
    sys_ = linear_oscillator(zeta, w0, F0, nu)
    # x = A cos(nu t) + B sin(nu t): (w0^2 - nu^2) A + 2 zeta w0 nu B = F0, and
    # (w0^2 - nu^2) B - 2 zeta w0 nu A = 0.
    D = (w0 ** 2 - nu ** 2) ** 2 + (2 * zeta * w0 * nu) ** 2
    A, B = F0 * (w0 ** 2 - nu ** 2) / D, F0 * 2 * zeta * w0 * nu / D
    lam = -zeta * w0 + 1j * w0 * np.sqrt(1 - zeta ** 2)
    mu_exact = forced.sort_multipliers(np.exp(np.array([lam, lam.conjugate()]) * sys_.T))
    u, mu = ROUTES[route](sys_, np.zeros(2), F0)
    # The orbit is ~0.2 in size; DOP853 at 1e-12 leaves ~1e-12, Newton stops at 1e-10
    # relative: 1e-9 is what the two allow with margin.
    assert np.allclose(u, [A, B * nu], rtol=0, atol=1e-9)
    assert np.allclose(mu, mu_exact, rtol=0, atol=1e-9)


def test_continuation_of_linear_oscillator_is_linear_in_the_forcing():
    """The response of a linear oscillator is proportional to F0: every continued point
    must lie on the closed-form line, with the same multipliers everywhere."""
    sys_ = linear_oscillator()
    u0, _ = shooting_route(sys_, np.zeros(2), 0.7)
    b = forced.continue_orbit(sys_.flow, u0, 0.7, 2.0, name="F0", ds=0.2, ds_max=0.5)
    assert b.values[-1] >= 2.0 and len(b.values) >= 4
    assert np.allclose(b.u0, np.outer(b.values / 0.7, u0), atol=1e-9)
    assert np.allclose(b.multipliers, b.multipliers[0], atol=1e-9)
    assert b.special == []


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
    b = forced.continue_orbit(sys_.flow, u0, 0.5, 1.5, name="a", ds=0.1, ds_max=0.2)
    pd = [s for s in b.special if s.type == "PD"]
    assert [s.type for s in b.special] == ["PD", "PD"]
    exact = hill_pd_boundaries(c, q)
    # Hill's determinant with 12 odd harmonics is exact to roundoff here (q^12 / 12!^2);
    # the located values carry the flow's ~1e-11 error divided by d mu / d a ~ O(1).
    assert np.allclose([s.value for s in pd], exact, atol=1e-8)
    for s in pd:
        assert abs(s.crossing + 1) < 1e-8
    # Between the two PD points the response is unstable (a multiplier below -1).
    inside = (b.values > exact[0]) & (b.values < exact[1])
    assert inside.any() and not b.stable[inside].any() and b.stable[~inside].all()


def duffing(c=0.1, beta=1.0, nu=1.5):
    """x'' + c x' + x + beta x^3 = F cos(nu t), parameter p = F."""
    return ForcedSystem(
        f=lambda t, u, F: np.array([u[1], F * np.cos(nu * t) - c * u[1] - u[0]
                                    - beta * u[0] ** 3]),
        jac=lambda t, u, F: np.array([[0.0, 1.0], [-1 - 3 * beta * u[0] ** 2, -c]]),
        dfdp=lambda t, u, F: np.array([0.0, np.cos(nu * t)]), nu=nu)


def test_fold_of_duffing_response_is_passed_and_located():
    """Hardening Duffing above resonance: the response against forcing F is S-shaped.
    Pseudo-arclength passes both folds (LP), where a multiplier is +1; their F agree
    with one-harmonic balance to its accuracy."""
    c, beta, nu = 0.1, 1.0, 1.5
    sys_ = duffing(c, beta, nu)
    u0, _ = shooting_route(sys_, np.zeros(2), 0.1)
    b = forced.continue_orbit(sys_.flow, u0, 0.1, 1.0, name="F", ds=0.3, ds_max=1.0,
                              p_scale=0.1, max_points=200)
    lp = [s for s in b.special if s.type == "LP"]
    assert b.values[-1] >= 1.0 and len(lp) == 2
    for s in lp:
        assert abs(s.crossing - 1) < 1e-8
    # The parameter turns at each LP: the branch's F reaches a local extremum there.
    for s in lp:
        k = np.argmin(np.abs(b.values - s.value))
        nb = b.values[max(k - 2, 0):k + 3]
        assert s.value >= nb.max() - 1e-9 or s.value <= nb.min() + 1e-9
    # Harmonic balance x = a cos(nu t + phi): F^2 = a^2 ((1 - nu^2 + 3/4 beta a^2)^2 +
    # (c nu)^2); its folds are the extrema of F(a). The neglected third harmonic is
    # ~ beta a^3 / (32 nu^2) relative: a few per cent at these amplitudes.
    a = np.linspace(0.05, 3.0, 20001)
    F = a * np.sqrt((1 - nu ** 2 + 0.75 * beta * a ** 2) ** 2 + (c * nu) ** 2)
    ext = np.where(np.diff(np.sign(np.diff(F))) != 0)[0] + 1
    assert len(ext) == 2
    assert np.allclose(sorted(s.value for s in lp), sorted(F[ext]), rtol=0.05)


# ------------------------------------------------------------------ the washer kernel's flow

@pytest.fixture(scope="module")
def nominal(params):
    return forced.periodic_response(params)


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
    d = forced._direction(params, "C_p")
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
    a = forced.periodic_response(q)
    b = forced.periodic_response(q, forced.simulated_start(q))
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
    r = forced.periodic_response(params)
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
    return forced.critical_cp(params)


def test_exact_critical_cp_near_averaged_and_far_from_frozen(critical):
    """MODEL.md section 4: averaged Hopf at C_p ~ 0.1010, frozen (tau0 = 0) ~ 0.0745, and
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


def test_stability_changes_at_the_located_tr_point(params, critical):
    cp = critical["C_p_exact"]
    below = forced.periodic_response(params.replace(C_p=cp * (1 - 1e-4)))
    above = forced.periodic_response(params.replace(C_p=cp * (1 + 1e-4)))
    assert not below.stable and above.stable


def test_continuation_in_cp_detects_the_same_tr_point(params, critical):
    b = forced.continue_response(params.replace(C_p=0.08), "C_p", 0.13, ds=0.1, ds_max=0.3)
    assert [s.type for s in b.special] == ["TR"]
    # Two independent locations (Brent on C_p with Newton per value; Brent along the chord
    # with the pseudo-arclength corrector) of the same zero: 1e-9 (measured 5e-13).
    assert abs(b.special[0].value - critical["C_p_exact"]) < 1e-9
    assert not b.stable[0] and b.stable[-1]


@pytest.mark.parametrize("name", ["m_u", "R_u", "C_a", "K_s", "Omega"])
def test_tr_in_any_parameter_lies_on_the_critical_cp_surface(params, name):
    """Two-parameter consistency: the TR point found by continuing the nominal response
    (C_p = 0.101, just below the exact critical 0.1010126) in parameter `name` must be a
    point where the exact critical C_p, located independently in C_p, is 0.101. Both
    locations are converged to ~1e-12 in their parameter; the multipliers' smooth
    integration error moves them together (5e-12 between rtol 1e-10 and 1e-12 at
    nominal values), so 1e-9 is a safe bound."""
    b = forced.continue_response(params, name, 0.98 * params[name], ds=0.005, ds_max=0.01)
    tr = [s for s in b.special if s.type == "TR"]
    assert len(tr) == 1 and b.stable[-1] and not b.stable[0]
    q = params.replace(**{name: tr[0].value})
    r, sp = forced.locate_tr(q, "C_p", (0.1, 0.102), tr[0].u0)
    assert abs(sp.value - params["C_p"]) < 1e-9


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
                                               forced._direction(params, "K_s"))
    assert not s.any() and np.abs(sd).max() > 0
    assert np.abs(u1 - u1d).max() < 1e-9 and np.abs(Phi - Phid).max() < 1e-8


def test_report_section_states_the_computed_numbers(params, tmp_path):
    from washer import forced_report
    import json
    res = forced_report.compute(params, n_curve=3, ends=False, progress=lambda *_: None)
    md = forced_report.markdown(res)
    assert f"{res['nominal']['C_p_exact']:.10f}" in md
    assert f"{res['nominal']['C_p_averaged']:.10f}" in md
    f4 = res["fig4"]
    assert f4["C_p_exact"][0] == 0.0 and abs(f4["Omega"][-1] - 15.0) < 1e-12
    assert np.all(np.diff(f4["C_p_exact"]) > 0)          # the curve rises with speed
    assert md.count("\n| ") >= 3 + 3
    json.loads(json.dumps(forced_report._jsonable(res)))
