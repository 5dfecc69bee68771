"""Equilibria followed from the reference set (washer.machine.equilibria) over Table 1's ranges.

Tolerances: Newton stops at max|acc| <= 1e-11 (1 + max|x|) (washer.machine.equilibria), so the
residual bound below is what the method guarantees; "near the reference yaw" is 0.2 rad,
against the pi of the half-turned tub a plain Newton found at K_s = 500 N/m.
"""
import re

import numpy as np
import pytest
from scipy.optimize import fsolve

import washer
from washer.machine import kernel
from washer.machine.equilibria import YAW_LIMIT, Equilibrium
from washer.paper.analysis import RANGES

KINDS = ("static", "averaged", "frozen")


def _reported_fold(exc) -> float:
    """The K_s (N/m) where washer.machine.equilibria says the static branch ends (its message:
    "ends at s = ... of the way (K_s = ...)")."""
    return float(re.search(r"\(K_s = ([0-9.]+)\)", str(exc)).group(1))


@pytest.fixture(scope="module")
def static_fold(params):
    """Where the static hanging branch with the nominal imbalance at rest folds, located
    independently of washer.machine.equilibria: solve F(q, K_s) = 0, J(q, K_s) v = 0, v.v0 = 1
    (13 unknowns, scipy fsolve), started from the point the continuation reports at
    K_s = 550 and 1 N/m on the branch's side of the K_s it reports (started on that K_s
    itself, fsolve's difference Jacobian stalls: ier 5). Returns (K_s (N/m), the
    fsolve solution, ier, msg, the message)."""
    with pytest.raises(washer.EquilibriumError) as exc:
        washer.Model(params.replace(K_s=550.0)).static_equilibrium()
    q0 = np.asarray(exc.value.last)
    ks0 = _reported_fold(exc.value)
    z = np.zeros(6)

    def P(ks):
        return params.replace(K_s=ks, Omega=0.0).vector()

    J0 = kernel.jac_fixed(0.0, np.r_[q0, z], P(ks0), "constant")[0][6:, :6]
    v0 = np.linalg.svd(J0)[2][-1]

    def eqs(u):
        q, ks, v = u[:6], u[6] * 1000, u[7:]
        J = kernel.jac_fixed(0.0, np.r_[q, z], P(ks), "constant")[0][6:, :6]
        return np.r_[kernel.rhs_fixed(0.0, np.r_[q, z], P(ks), "constant")[6:], J @ v, v @ v0 - 1]

    u, info, ier, msg = fsolve(eqs, np.r_[q0, (ks0 + 1.0) / 1000, v0], full_output=True,
                               xtol=1e-12)
    return u[6] * 1000, u, ier, msg, str(exc.value)


def _solve(m, kind):
    return m.static_equilibrium() if kind == "static" else m.rotating_equilibrium(frame=kind)


def _acc(m, kind, x):
    z = np.zeros(6)
    if kind == "static":
        P = m.params.replace(Omega=0.0).vector()
        return kernel.rhs_fixed(0.0, np.r_[x, z], P, "constant")[6:]
    return kernel.rhs_rot(np.r_[x, z], m.P, kind)[6:]


@pytest.mark.parametrize("name", sorted(RANGES))
def test_equilibria_over_table1_ranges(params, name, static_fold):
    """One parameter at a time over Table 1's range (the paper's way of varying them):
    every solve converges, the residual meets Newton's stopping rule, the yaw stays
    within 0.2 rad of the reference's, and info says hanging. The one exception is
    the static equilibrium below K_s_fold, where none exists (next tests)."""
    lo, hi = RANGES[name]
    for v in np.linspace(lo, hi, 17):
        m = washer.Model(params.replace(**{name: v}))
        for kind in KINDS:
            if kind == "static" and name == "K_s" and v < static_fold[0]:
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


def test_k_s_500_rotating_is_not_half_turned(params):
    """The case: at K_s = 500 N/m the old solver returned eps6 = -3.12 rad.
    The followed equilibrium is unrotated; the half-turned one still exists (Newton
    from the tipped static point finds it) and is labelled as not hanging."""
    m = washer.Model(params.replace(K_s=500.0))
    e = m.rotating_equilibrium()
    assert abs(e[5]) < 0.1 and e.info.hanging          # unrotated, not pi away
    assert "K_s" in e.info.path and e.info.steps >= 1
    tipped = [-0.0432, 0.0, 0.3285, 0.0, -0.4189, 0.0]   # the unstable static point at 500 N/m
    h = m.rotating_equilibrium(guess=tipped)
    assert abs(abs(h[5]) - np.pi) < 0.1, h
    assert not h.info.hanging and h.info.branch.startswith("Newton from the given guess")


@pytest.mark.parametrize("k_s", [550.0, 517.5])
def test_static_below_the_fold_is_refused_and_the_tub_tips(params, k_s, static_fold):
    """K_s = 550 and 517.5 N/m: with the 1 kg imbalance at rest on +x
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
    # The end the error names is the independently located fold (0.05 N/m: the bound
    # the continuation's step halving stops within; measured 3e-4).
    assert abs(_reported_fold(exc.value) - static_fold[0]) < 0.05
    still = washer.Model(params.replace(K_s=k_s, Omega=0.0))
    y0 = np.r_[still._hanging_guess(), np.zeros(6)]
    r = still.simulate(200.0, system="fixed", law="constant", y0=y0, samples_per_s=20)
    assert np.max(np.abs(r.y[:, 4])) > 0.5
    ok = washer.Model(params.replace(K_s=575.0, Omega=0.0))
    q = ok.static_equilibrium()
    r = ok.simulate(200.0, system="fixed", law="constant",
                    y0=np.r_[ok._hanging_guess(), np.zeros(6)], samples_per_s=2)
    np.testing.assert_allclose(r.y[-1, :6], q, atol=1e-4)


def test_static_fold_is_a_fold(static_fold):
    """The independent location (the fixture) converges: a true fold, with a null
    vector, inside Table 1's K_s range, where the tub tilts towards the imbalance."""
    ks, u, ier, msg, _ = static_fold
    assert ier == 1, msg
    assert 500.0 < ks < 4500.0
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
