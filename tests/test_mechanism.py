"""The mechanism study (washer.paper.mechanism) against independent statements: the exact
split of the growth rate sums to the eigenvalue's real part, the undamped pair is neutral,
the Hopf mode's ground-frame frequency is the exact torus point's, and the Campbell
diagram's frequency of the critical mode is the sweep's |2 pi Omega - Im(lambda)|."""
import numpy as np
import pytest

from washer.paper import mechanism as me


def test_damper_shares_sum_to_the_growth_rate(params):
    """Along the ray from no damping the shares integrate dRe/dC exactly; the 8-node
    Gauss rule on a smooth integrand and central differences (h = 1e-4 relative) leave
    ~1e-8 of Re(lambda) = 0.105 1/s at C_p = 0."""
    d = me.damper_shares(params.replace(C_p=0.0))
    assert d["re_lambda"] > 0.05
    assert d["sum"] == pytest.approx(d["re_lambda"], rel=1e-6)
    assert d["dampers"]["C_a"]["share"] == pytest.approx(d["re_lambda"], rel=1e-6)
    h = me.damper_shares(params)
    assert h["sum"] == pytest.approx(h["re_lambda"], abs=1e-6)
    assert h["dampers"]["C_a"]["share"] > 0 > h["dampers"]["C_oz"]["share"]


def test_without_axial_dampers_the_pair_is_neutral_then_stable(params):
    from washer.machine.model import Model
    m = Model(params.replace(C_a=0.0, C_p=0.0))
    assert abs(m.eigenvalues(m.rotating_equilibrium()).real.max()) < 1e-10
    m = Model(params.replace(C_a=0.0, C_p=0.01))
    assert m.eigenvalues(m.rotating_equilibrium()).real.max() < 0


def test_hopf_mode_frequency_is_the_exact_torus_point(params):
    """The averaged Hopf mode seen from the ground whirls at the frequency the exact torus
    point's rotation number gives (averaging is accurate to ~1e-4 there)."""
    from washer.problems import torus
    mode = me.hopf_mode(params)
    b = torus.birth(params)
    assert mode["f_whirl"] == pytest.approx(torus.whirl_frequency(b.rho, params["Omega"]),
                                            rel=1e-4)


def test_campbell_frequency_of_the_growing_mode_is_the_sweeps(params):
    from washer.sweep.tasks import stability
    c = me.campbell(params, [12.0])
    j = int(np.nanargmax(c.rate[0]))
    s = stability(params.replace(Omega=12.0))
    assert c.rate[0, j] == pytest.approx(s["stab_margin"], abs=1e-12)
    assert c.freq[0, j] == pytest.approx(s["stab_whirl_ground"] / (2 * np.pi), rel=1e-12)
