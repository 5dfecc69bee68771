"""The exact whirl (washer.problems.torus): the half-period map of the rotating frame and its
invariant circles, checked against independent computations: finite differences of the
map, the one-period monodromy matrix of washer.machine.forced, the normal form of a supercritical
Neimark-Sacker point, and a long simulation of eq 48 that knows nothing of the circle."""
import numpy as np
import pytest

from washer.machine import forced
from washer.problems import torus
from washer.problems import forced as shooting
from washer.cont.iterator import UZ_ROUNDING
from washer.problems.rotating import averaged_hopf


@pytest.fixture(scope="module")
def response(params):
    return shooting.periodic_response(params)


def test_forced_response_is_a_fixed_point_of_the_half_period_map(params, response):
    """The half-turn symmetry makes the rotating-frame orbit T/2-periodic: the T-periodic
    response of washer.machine.forced is a fixed point of the T/2 map (to the flow's accuracy)."""
    xi = forced.rotating_from_ground(response.u0, params["Omega"], 0.0)
    F, _, _ = torus.half_period_map(params)(xi[None, :], params["C_p"])
    assert np.abs(F[0] - xi).max() < 1e-8 * (1 + np.abs(xi).max())


def test_half_period_map_jacobian_squares_to_the_monodromy(params, response):
    """DP over T/2 (frame transforms G(T/2)^-1 Phi G(0)) squared has the eigenvalues of the
    one-period monodromy matrix computed in the ground frame by washer.forced."""
    xi = forced.rotating_from_ground(response.u0, params["Omega"], 0.0)
    _, DF, _ = torus.half_period_map(params)(xi[None, :], params["C_p"])
    mu2 = np.sort_complex(np.linalg.eigvals(DF[0] @ DF[0]))
    assert np.abs(mu2 - np.sort_complex(response.multipliers)).max() < 1e-8


def test_half_period_map_derivatives_against_finite_differences(params, response):
    """DP and dP/dC_p against central differences of P (step h: truncation ~h^2, noise
    ~rtol/h of the flow at rtol 1e-10: both below 1e-5 relative at h = 1e-5)."""
    xi = forced.rotating_from_ground(response.u0, params["Omega"], 0.0)
    xi = xi + 0.01 * np.r_[1, -1, 0, 0.5, 0.2, 0, 1, 1, 0, 0.5, -0.5, 0]
    f = torus.half_period_map(params)
    p = params["C_p"]
    F, DF, Fp = f(xi[None, :], p)
    h = 1e-5
    fd = np.empty((12, 12))
    for k in range(12):
        e = np.zeros(12)
        e[k] = h * max(1.0, abs(xi[k]))
        fd[:, k] = (f((xi + e)[None, :], p)[0][0] - f((xi - e)[None, :], p)[0][0]) / (2 * e[k])
    assert np.abs(fd - DF[0]).max() < 1e-5 * np.abs(DF[0]).max()
    fdp = (f(xi[None, :], p + h)[0][0] - f(xi[None, :], p - h)[0][0]) / (2 * h)
    assert np.abs(fdp - Fp[0]).max() < 1e-5 * max(1.0, np.abs(Fp[0]).max())


def test_birth_is_the_torus_point(params):
    """At the TR point of washer.machine.forced the T/2 map's critical multiplier is on the unit
    circle, and its square is the one-period critical multiplier."""
    b = torus.birth(params)
    c = shooting.critical_cp(params)
    assert b.value == c["C_p_exact"]
    assert abs(abs(b.mu) - 1) < 1e-6
    mu_T = c["critical_multiplier"]
    assert min(abs(b.mu**2 - mu_T), abs(b.mu.conjugate()**2 - mu_T)) < 1e-8
    # Oriented: eps1 + i eps2 turns counter-clockwise with the circle's angle.
    assert (b.v[1] / b.v[0]).imag < 0


@pytest.mark.slow
def test_exact_whirl_against_normal_form_and_long_simulation(params):
    """The family from the TR point to C_p = 0 (about 30 s), then:
    - near the birth the whirl's amplitude squared grows linearly in C_p,crit - C_p
      (supercritical Neimark-Sacker normal form): A^2 / dC_p of the first three circles
      agree within 5 % (the next order is O(A^2) relative: a few per cent at A = 28 mm);
    - the circles are resolved (Fourier tail < 1e-6) and attracting;
    - a simulation of eq 48 started 3 % off the C_p = 0 circle approaches it at the decay
      rate its leading normal multiplier predicts (within 2 %: the fit over the run's second
      half still sees the next-slowest mode), and turns about it with the circle's rotation
      number (1e-6: the phase advance over 400 half periods)."""
    w = torus.exact_whirl(params)
    assert w.reached
    # The end value is a located UZ (the engine's location on the arclength), so C_p = 0
    # to the rounding with which a UZ value counts as reached.
    assert abs(w.value[-1]) <= UZ_ROUNDING
    d = w.birth.value - w.value[:3]
    k = w.amplitude[:3] ** 2 / d
    assert np.ptp(k) < 0.05 * k.mean()
    assert np.all(w.tail < 1e-6)
    assert np.all(w.mu_max < 1.0)
    c0 = w.circles[-1]
    xi0 = c0(np.array([0.3]))[0]
    xi0 = xi0 + 0.03 * (xi0 - np.r_[0, 0, xi0[2], 0, 0, xi0[5], np.zeros(6)])
    s = torus.against_simulation(params.replace(C_p=0.0), c0, xi0, 200.0)
    assert s["decay_rate"] == pytest.approx(s["predicted_rate"], rel=0.02)
    assert s["rho"] == pytest.approx(c0.rho, abs=1e-6)
    assert s["distance"][-1] < 0.3 * s["distance"][0]
    # The sweep's clearance criterion rests on the averaged Hopf normal form's growth
    # coefficient a (amplitude = a sqrt(C_p,crit - C_p)): against the first exact circle
    # (amplitude 4 mm, where the next order is ~1e-4 relative) within 3 % (the first
    # Lyapunov coefficient's finite differences scatter by ~0.5 %, and the exact and
    # averaged critical values differ by 1e-4 relative).
    from washer.sweep.tasks import whirl_growth
    a_nf, r0, _ = whirl_growth(params, "C_p", averaged_hopf(params)[0])
    a_ex = w.amplitude[0] / np.sqrt(w.birth.value - w.value[0])
    assert a_ex == pytest.approx(a_nf, rel=0.03)
    assert r0 == pytest.approx(np.hypot(*w.birth.xi[:2]), rel=1e-3)
