"""The kernel's equations against independent references."""
import numpy as np
import pytest

import washer
from washer.machine import kernel
from washer.symbolic import newton_euler as ne
from washer.symbolic.rods_literal import rod_forces_literal

from conftest import random_state


def test_accelerations_equal_newton_euler(distinct_params):
    """Lagrange (sympy -> C++) vs hand-written Newton-Euler (numpy), 1e-10 relative."""
    rng = np.random.default_rng(0)
    P = distinct_params.vector()
    for _ in range(20):
        q, qd = random_state(rng)
        th, w, wd = rng.uniform(0, 2 * np.pi), rng.normal(0, 40), rng.normal(0, 20)
        M, f = kernel.mass_forces(q, qd, th, w, wd, P)
        a_kernel = np.linalg.solve(M, f)
        a_ref = ne.accelerations(distinct_params, q, qd, th, w, wd)
        assert np.max(np.abs(a_kernel - a_ref)) <= 1e-10 * np.max(np.abs(a_ref))


def test_rhs_fixed_uses_the_speed_law(distinct_params):
    rng = np.random.default_rng(1)
    q, qd = random_state(rng)
    for law in ("constant", "spinup"):
        t = 0.3
        du = kernel.rhs_fixed(t, np.r_[q, qd], distinct_params.vector(), law)
        ref = ne.rhs_fixed(t, np.r_[q, qd], distinct_params, law)
        np.testing.assert_allclose(du, ref, rtol=1e-10, atol=1e-10 * np.max(np.abs(ref)))


def test_smooth_rod_forces_equal_literal_equations():
    """docs/model.md section 2 form == eqs 30-44 wherever d x v != 0, unequal coefficients."""
    rng = np.random.default_rng(2)
    for _ in range(50):
        d = rng.normal(0, 0.3, 3) + [0, 0, 0.5]
        v, w = rng.normal(0, 1, 3), rng.normal(0, 1, 3)
        coef = dict(K_s=1800.0, C_a=97.0, C_p=0.13, C_ox=0.41, C_oz=0.27, l0=0.46)
        F1, M1 = ne.rod_forces_smooth(d, v, w, **coef)
        F2, M2 = rod_forces_literal(d, v, w, **coef)
        np.testing.assert_allclose(F1, F2, rtol=1e-12, atol=1e-12 * np.linalg.norm(F2))
        np.testing.assert_allclose(M1, M2, rtol=1e-12, atol=1e-12 * np.linalg.norm(M2))


def test_rotating_frame_equals_transformed_ground_frame(distinct_params):
    """Frozen rotating frame at tau0: eps_ddot = H^T (q_ddot - H'' w^2 eps - 2 H' w eps_dot)
    with q_ddot from the independent numpy model at theta = tau0 (eqs 52-57)."""
    rng = np.random.default_rng(3)
    eps, epsd = random_state(rng)
    tau, W = distinct_params["tau0"], 2 * np.pi * distinct_params["Omega"]
    c, s = np.cos(tau), np.sin(tau)
    R, R1 = np.array([[c, -s], [s, c]]), np.array([[-s, -c], [c, -s]])
    H, H1 = np.eye(6), np.zeros((6, 6))
    for b in (0, 3):
        H[b:b + 2, b:b + 2], H1[b:b + 2, b:b + 2] = R, R1
    H2 = -(H - np.diag([0, 0, 1, 0, 0, 1]))
    q, qd = H @ eps, W * H1 @ eps + H @ epsd
    a = ne.accelerations(distinct_params, q, qd, tau, W, 0.0)
    ref = H.T @ (a - W**2 * H2 @ eps - 2 * W * H1 @ epsd)
    got = kernel.rhs_rot(np.r_[eps, epsd], distinct_params.vector(), "frozen")
    np.testing.assert_allclose(got[6:], ref, rtol=1e-10, atol=1e-10 * np.max(np.abs(ref)))
    np.testing.assert_allclose(got[:6], epsd)


def test_rotating_frame_jacobian_is_the_transformed_ground_frame_jacobian(distinct_params):
    """The frozen frame's f_u at tau0 from the ground frame's at q = H eps, q_dot = w H' eps
    + H eps_dot, theta = tau0 (jac_fixed's a_q, a_qd, a_p; eq 57 differentiated):
    d/deps = H^T (a_q H + w a_qd H' - w^2 H''), d/deps_dot = H^T (a_qd H - 2 w H'),
    d/dP = H^T a_p, as numpy's 6 x 6 products. The kernel turns the rows and columns of
    the rotated pairs instead (H' = H K, H'' = -H D): equal to rounding (1e-13 of the
    block's largest entry: a few roundings of sums of six terms)."""
    rng = np.random.default_rng(6)
    tau, W = distinct_params["tau0"], 2 * np.pi * distinct_params["Omega"]
    c, s = np.cos(tau), np.sin(tau)
    H, H1 = np.eye(6), np.zeros((6, 6))
    for b in (0, 3):
        H[b:b + 2, b:b + 2] = [[c, -s], [s, c]]
        H1[b:b + 2, b:b + 2] = [[-s, -c], [c, -s]]
    H2 = -(H - np.diag([0, 0, 1, 0, 0, 1]))
    P = distinct_params.vector()
    for _ in range(5):
        eps, epsd = random_state(rng)
        q, qd = H @ eps, W * H1 @ eps + H @ epsd
        # the constant speed law at t = tau / w: theta = tau (to rounding), w, w_dot = 0
        Jg, Jpg = kernel.jac_fixed(tau / W, np.r_[q, qd], P, "constant")
        a_q, a_qd = Jg[6:, :6], Jg[6:, 6:]
        J, Jp = kernel.jac_rot(np.r_[eps, epsd], P, "frozen")
        for got, ref in ((J[6:, :6], H.T @ (a_q @ H + W * a_qd @ H1 - W**2 * H2)),
                         (J[6:, 6:], H.T @ (a_qd @ H - 2 * W * H1))):
            assert np.max(np.abs(got - ref)) <= 1e-13 * np.max(np.abs(ref))
        for j, name in enumerate(kernel.DIFF_NAMES):
            if name != "Omega":          # theta and w move with Omega on the ground
                ref = H.T @ Jpg[6:, j]
                assert np.max(np.abs(Jp[6:, j] - ref)) <= 1e-13 * max(np.max(np.abs(ref)),
                                                                       1e-300), name


def test_averaged_frame_is_the_mean_over_tau(distinct_params):
    rng = np.random.default_rng(4)
    xi = np.r_[random_state(rng)]
    frozen = [kernel.rhs_rot(xi, distinct_params.replace(tau0=t).vector(), "frozen")
              for t in 2 * np.pi * np.arange(16) / 16]
    np.testing.assert_allclose(kernel.rhs_rot(xi, distinct_params.vector(), "averaged"),
                               np.mean(frozen, axis=0), rtol=1e-12, atol=1e-12)


def _fd(fun, x, h):
    cols = []
    for i in range(x.size):
        e = np.zeros_like(x)
        e[i] = h * max(1.0, abs(x[i]))
        cols.append((fun(x + e) - fun(x - e)) / (2 * e[i]))
    return np.array(cols).T


@pytest.mark.parametrize("system", ["fixed-constant", "fixed-spinup", "frozen", "averaged"])
def test_jacobians_equal_central_differences(distinct_params, system):
    rng = np.random.default_rng(5)
    u = np.r_[random_state(rng)]
    P0 = distinct_params.vector()
    if system.startswith("fixed"):
        law = system.split("-")[1]
        f = lambda y, P=P0: kernel.rhs_fixed(0.4, y, P, law)
        J, Jp = kernel.jac_fixed(0.4, u, P0, law)
    else:
        f = lambda y, P=P0: kernel.rhs_rot(y, P, system)
        J, Jp = kernel.jac_rot(u, P0, system)
    Jfd = _fd(f, u, 1e-6)
    assert np.max(np.abs(J - Jfd)) <= 1e-6 * np.max(np.abs(Jfd))
    from washer.machine import layout
    for j, name in enumerate(kernel.DIFF_NAMES):
        i = layout.INDEX[name]
        col = _fd(lambda pi: f(u, np.r_[P0[:i], pi, P0[i + 1:]]), P0[i:i + 1], 1e-6)[:, 0]
        scale = max(np.max(np.abs(col)), 1e-8)
        assert np.max(np.abs(Jp[:, j] - col)) <= 1e-5 * scale, name


def test_energy_is_conserved_without_damping_and_spin(params):
    p = params.replace(C_a=0, C_p=0, C_ox=0, C_oz=0, Omega=0)
    m = washer.Model(p)
    u0 = np.r_[m.static_equilibrium() + [0.01, -0.02, 0.015, 0.02, -0.01, 0.03], np.zeros(6)]
    r = m.simulate(5.0, system="fixed", law="constant", y0=u0, samples_per_s=20,
                   rtol=1e-11, atol=1e-13)
    E = np.array([ne.energy(p, y) for y in r.y])
    assert np.ptp(r.y[:, 2]) > 1e-3                   # it really moves
    assert np.max(np.abs(E - E[0])) <= 1e-8 * abs(E[0])


def test_damping_dissipates_energy(params):
    p = params.replace(Omega=0)
    m = washer.Model(p)
    u0 = np.r_[m.static_equilibrium() + [0.01, -0.02, 0.015, 0.02, -0.01, 0.03], np.zeros(6)]
    r = m.simulate(3.0, system="fixed", law="constant", y0=u0, samples_per_s=10)
    E = np.array([ne.energy(p, y) for y in r.y])
    assert np.all(np.diff(E) <= 1e-9 * abs(E[0]))
    assert E[-1] < E[0]
