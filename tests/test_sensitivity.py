"""The sensitivity study (washer.paper.sensitivity): its perturbations move what they say,
and one row checked against the exact torus point computed independently."""
import numpy as np
import pytest

from washer.problems import forced as shooting
from washer.paper import sensitivity as se


def test_scaled_moves_every_joint_of_the_group(params):
    q = se.scaled(params, "R_O", 1.2)
    assert np.allclose(np.hypot(*q.lower_joints()[:, :2].T),
                       1.2 * np.hypot(*params.lower_joints()[:, :2].T))
    assert np.allclose(q.upper_joints(), params.upper_joints())
    q = se.scaled(params, "J_t", 0.8)
    assert q["J_tx"] == pytest.approx(0.8 * params["J_tx"]) and q["J_tz"] == params["J_tz"]


def test_moving_the_upper_joints_up_changes_nothing(params):
    """Translation invariance: raising the cabinet's joints raises the hanging tub by the
    same amount and leaves the critical value (to Brent's 1e-12) unchanged."""
    a, b = se.critical(params), se.critical(se.scaled(params, "z_P", 1.2))
    assert b["C_p"] == pytest.approx(a["C_p"], abs=1e-9)
    assert b["z_static"] - a["z_static"] == pytest.approx(0.2 * params["Pz0"], abs=1e-9)


def test_a_row_against_the_exact_torus_point(params):
    """r_tz + 20 %: the averaged critical value within 1e-3 relative of the exact one
    (averaging's error, ~1e-4 at the reference point), and well off the nominal."""
    q = se.scaled(params, "r_tz", 1.2)
    avg = se.critical(q)["C_p"]
    ex = shooting.critical_cp(q)["C_p_exact"]
    assert avg == pytest.approx(ex, rel=1e-3)
    assert avg > 1.2 * se.critical(params)["C_p"]
