"""Time responses: kernel integrator vs solve_ivp, failure handling, CLI."""
import json

import numpy as np
import pytest

import washer
from washer import simulate
from washer.machine import kernel, responses


@pytest.mark.parametrize("system,mode", [("fixed", "spinup"), ("rotating", "averaged"),
                                         ("rotating", "frozen")])
def test_kernel_integrator_agrees_with_solve_ivp(model, system, mode):
    kw = dict(system=system, samples_per_s=50, rtol=1e-11, atol=1e-12)
    kw["law" if system == "fixed" else "frame"] = mode
    a = model.simulate(2.0, method="kernel", **kw)
    b = model.simulate(2.0, method="scipy", **kw)
    scale = np.max(np.abs(b.y), axis=0) + 1e-12
    assert a.status == b.status == "ok"
    assert np.max(np.abs(a.y - b.y) / scale) < 1e-7
    assert a.stats["nfev"] > 0 and a.stats["naccept"] > 0


def test_dense_output_matches_restarted_integration(model):
    """Output between steps (dense) == integrating exactly to that time."""
    y0 = responses.default_initial_state(model, "fixed")
    Y, _, _ = kernel.integrate("fixed", "spinup", 0.0, y0, model.P, [0.123456, 1.0], 1e-10, 1e-12)
    Z, _, _ = kernel.integrate("fixed", "spinup", 0.0, y0, model.P, [0.123456], 1e-10, 1e-12)
    assert np.max(np.abs(Y[0] - Z[0])) < 1e-8


def test_failure_keeps_partial_results(model):
    """A step limit stops the run: the points computed so far are returned and saved."""
    y0 = responses.default_initial_state(model, "fixed")
    with pytest.raises(washer.KernelError, match="step limit") as err:
        kernel.integrate("fixed", "spinup", 0.0, y0, model.P, np.linspace(0, 5, 101), 1e-8,
                         1e-10, max_steps=200)
    t, Y, info = err.value.partial
    assert 0 < len(t) < 101 and np.all(np.isfinite(Y))


def test_cli_writes_data_and_plots(tmp_path):
    rc = simulate.main(["fig11", "--t-end", "1.0", "--out", str(tmp_path)])
    assert rc == 0
    for suffix in (".npz", ".csv", "_y.png", "_z.png", "_xy.png", "_xy.pdf"):
        assert (tmp_path / f"fig11{suffix}").stat().st_size > 0
    data = np.load(tmp_path / "fig11.npz")
    meta = json.loads(str(data["meta"]))
    assert meta["params"]["C_p"] == 0.0 and data["y"].shape[1] == 12
    assert data["t"][-1] == pytest.approx(1.0)


def test_paper_fig10_settles_and_fig11_does_not(params):
    """Figs 10-11 behaviour: C_p = 0.15 reaches a steady circular orbit; C_p = 0
    keeps a growing, multi-frequency motion (ground frame, spin-up, 50 s)."""
    def radius_spread(cp):
        r = washer.Model(params.replace(C_p=cp)).simulate(50.0, samples_per_s=200)
        rad = np.hypot(r.y[:, 0], r.y[:, 1])
        late = rad[r.t >= 45.0]
        return late.max() - late.min()
    assert radius_spread(0.15) < 0.2 * radius_spread(0.0)
