"""Equilibria followed from the reference set (washer.equilibria) over Table 1's ranges.

Tolerances: Newton stops at max|acc| <= 1e-11 (1 + max|x|) (washer.equilibria), so the
residual bound below is what the method guarantees; "near the reference yaw" is 0.2 rad,
against the pi of the half-turned tub a plain Newton found at K_s = 500 N/m.
"""
import numpy as np
import pytest
from scipy.optimize import fsolve

import washer
from washer import kernel
from washer.equilibria import YAW_LIMIT, Equilibrium
from washer.paper.analysis import RANGES

KINDS = ("static", "averaged", "frozen")
#: Where the static hanging branch with the nominal imbalance at rest folds (N/m):
#: located independently in test_static_fold_is_a_fold; the scan steps around it.
K_S_FOLD = 570.6


def _solve(m, kind):
    return m.static_equilibrium() if kind == "static" else m.rotating_equilibrium(frame=kind)


def _acc(m, kind, x):
    z = np.zeros(6)
    if kind == "static":
        P = m.params.replace(Omega=0.0).vector()
        return kernel.rhs_fixed(0.0, np.r_[x, z], P, "constant")[6:]
    return kernel.rhs_rot(np.r_[x, z], m.P, kind)[6:]


@pytest.mark.parametrize("name", sorted(RANGES))
def test_equilibria_over_table1_ranges(params, name):
    """One parameter at a time over Table 1's range (the paper's way of varying them):
    every solve converges, the residual meets Newton's stopping rule, the yaw stays
    within 0.2 rad of the reference's, and info says hanging. The one exception is
    the static equilibrium below K_s_fold, where none exists (next tests)."""
    lo, hi = RANGES[name]
    for v in np.linspace(lo, hi, 17):
        m = washer.Model(params.replace(**{name: v}))
        for kind in KINDS:
            if kind == "static" and name == "K_s" and v < K_S_FOLD:
                with pytest.raises(washer.EquilibriumError, match="fold"):
                    _solve(m, kind)
                continue
            x = _solve(m, kind)
            assert isinstance(x, np.ndarray) and x.shape == (6,)
            res = np.max(np.abs(_acc(m, kind, np.asarray(x))))
            assert res <= 1e-11 * (1 + np.max(np.abs(x))), (name, v, kind, res)
            assert x.info.residual == pytest.approx(res, abs=1e-15)
            assert abs(x.info.yaw - x.info.yaw_ref) < 0.2, (name, v, kind, x.info.yaw)
            assert x.info.hanging
            if kind != "static" and v != params[name]:
                assert name in x.info.path


def test_issue_cases_k_s_500_rotating_is_not_half_turned(params):
    """The issue's case: at K_s = 500 N/m the old solver returned eps6 = -3.12 rad.
    The followed equilibrium is unrotated; the half-turned one still exists (Newton
    from the tipped static point finds it) and is labelled as not hanging."""
    m = washer.Model(params.replace(K_s=500.0))
    e = m.rotating_equilibrium()
    assert abs(e[5] + 0.034) < 0.01 and e.info.hanging
    assert "K_s" in e.info.path and e.info.steps >= 1
    tipped = [-0.0432, 0.0, 0.3285, 0.0, -0.4189, 0.0]   # the unstable static point at 500 N/m
    h = m.rotating_equilibrium(guess=tipped)
    assert abs(abs(h[5]) - np.pi) < 0.1, h
    assert not h.info.hanging and h.info.branch.startswith("Newton from the given guess")


@pytest.mark.parametrize("k_s", [550.0, 517.5])
def test_static_below_the_fold_is_refused_and_the_tub_tips(params, k_s):
    """The issue's K_s = 550 and 517.5 N/m: with the 1 kg imbalance at rest on +x
    there is no hanging equilibrium (the error names the fold); the dynamics agree
    independently: released at rest from the hanging guess, the damped tub tips
    over (|beta| beyond 0.5 rad, twice the tilt at the fold; the run may stop at the
    Cardan singularity beta = pi/2, which is tipping too), while at K_s = 575 N/m it
    settles on the followed point."""
    m = washer.Model(params.replace(K_s=k_s))
    with pytest.raises(washer.EquilibriumError, match="fold") as exc:
        m.static_equilibrium()
    last = exc.value.last
    assert isinstance(last, Equilibrium) and last.info.kind == "static"
    assert "K_s = 570.6" in str(exc.value)
    still = washer.Model(params.replace(K_s=k_s, Omega=0.0))
    y0 = np.r_[still._hanging_guess(), np.zeros(6)]
    r = still.simulate(200.0, system="fixed", law="constant", y0=y0, samples_per_s=20)
    assert np.max(np.abs(r.y[:, 4])) > 0.5
    ok = washer.Model(params.replace(K_s=575.0, Omega=0.0))
    q = ok.static_equilibrium()
    r = ok.simulate(200.0, system="fixed", law="constant",
                    y0=np.r_[ok._hanging_guess(), np.zeros(6)], samples_per_s=2)
    np.testing.assert_allclose(r.y[-1, :6], q, atol=1e-4)


def test_static_fold_is_a_fold(params):
    """Independent location of the fold: solve F(q, K_s) = 0, J(q, K_s) v = 0, v.v0 = 1
    (13 unknowns, scipy fsolve) from the end point the continuation reports. A true
    fold has a null vector there, at K_s = K_S_FOLD."""
    with pytest.raises(washer.EquilibriumError) as exc:
        washer.Model(params.replace(K_s=550.0)).static_equilibrium()
    q0 = np.asarray(exc.value.last)
    z = np.zeros(6)

    def P(ks):
        return params.replace(K_s=ks, Omega=0.0).vector()

    J0 = kernel.jac_fixed(0.0, np.r_[q0, z], P(570.6), "constant")[0][6:, :6]
    v0 = np.linalg.svd(J0)[2][-1]

    def eqs(u):
        q, ks, v = u[:6], u[6] * 1000, u[7:]
        J = kernel.jac_fixed(0.0, np.r_[q, z], P(ks), "constant")[0][6:, :6]
        return np.r_[kernel.rhs_fixed(0.0, np.r_[q, z], P(ks), "constant")[6:], J @ v, v @ v0 - 1]

    u, info, ier, msg = fsolve(eqs, np.r_[q0, 0.5706, v0], full_output=True, xtol=1e-12)
    assert ier == 1, msg
    assert abs(u[6] * 1000 - K_S_FOLD) < 0.05
    assert u[4] > 0.2       # the tub tilts towards the imbalance (beta, rad) at the fold


def test_equilibrium_array_behaviour(model):
    """Callers use the result as before (indexing, np.r_, arithmetic); derived arrays
    drop the info, which describes only the equilibrium itself."""
    q = model.static_equilibrium()
    assert isinstance(q, Equilibrium) and q.info.kind == "static" and q.info.frame is None
    assert isinstance(q[2], float) and q.info.hanging and abs(q.info.yaw) < YAW_LIMIT
    u = np.r_[q, np.zeros(6)]
    assert u.shape == (12,)
    assert type(q + 1.0) is np.ndarray and type(2 * q) is np.ndarray
    import pickle
    q2 = pickle.loads(pickle.dumps(q))
    assert q2.info == q.info and np.array_equal(q2, q)
