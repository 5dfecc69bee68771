"""The spin-up torque and the suspension's yaw curve (washer.paper.spinup)."""
import numpy as np
import pytest

from washer.paper import spinup as sp


def test_spin_torque_is_eq66_peak(params):
    """T_peak = (J_bz + m_u R_u^2) * 2 pi Omega / tau_s (eq 66 at t = 0, Omega in Hz)."""
    st = sp.spin_torque(params)
    J = params["J_bz"] + params["m_u"] * params["R_u"] ** 2
    assert st.T_peak == pytest.approx(J * 2 * np.pi * params["Omega"] / params["tau_s"], rel=1e-12)
    assert st.impulse == pytest.approx(J * 2 * np.pi * params["Omega"], rel=1e-9)


def test_yaw_curve_linear_stiffness_and_fold(params):
    """Two independent routes to the yaw stiffness agree: the Schur complement of the
    static Jacobian and the secant -Q/gamma of the continued curve at its first point
    (|gamma| < 0.05 rad: curvature below 1 %). At the fold the curve flattens: its
    last secant slope is under 5 % of the linear one (a fold, not a step-size stop)."""
    c = sp.yaw_curve(params)
    i = next(k for k in range(1, len(c.Q)) if abs(c.gamma[k]) > 1e-3)
    assert abs(c.gamma[i]) < 0.05
    assert c.Q[i] / c.gamma[i] == pytest.approx(c.k_lin, rel=0.01)
    slope = (c.Q[-1] - c.Q[-2]) / (c.gamma[-1] - c.gamma[-2])
    assert abs(slope) < 0.05 * c.k_lin
    assert np.all(np.diff(np.abs(c.Q)) > 0)
    assert sp.slow_tau_s(params, c) * c.M_max >= 2 * sp.spin_torque(params.replace(tau_s=1.0)).T_peak


def test_twist_curve_tips_where_the_yaw_curve_folds_and_rises_without_imbalance(params):
    """Two computations of where the twisted tub tips: `yaw_curve` continues in the moment
    until the curve folds, `twist_curve` prescribes the twist and watches the smallest
    stiffness eigenvalue cross zero (interpolated on its grid of 0.025 rad: the crossing
    within 0.01 rad, the moment within 0.2 N m). Without the imbalance the moment needed
    keeps rising past the symmetric tub's tilt pitchfork (it is not a fold)."""
    from washer.paper import spinup as sp
    fold = sp.yaw_curve(params)
    tw = sp.twist_curve(params, gamma_end=-0.8, n=33)
    assert abs(tw.gamma_tip - fold.gamma_max) < 0.01
    assert abs(abs(tw.Q_tip) - fold.M_max) < 0.2
    sym = sp.twist_curve(params.replace(m_u=0.0), gamma_end=-1.2, n=49)
    assert np.all(np.diff(np.abs(sym.Q)) > 0)
    assert np.isfinite(sym.gamma_tip) and abs(sym.Q_tip) > fold.M_max
    assert sym.stiffness[-1] < 0 < sym.stiffness[0]
