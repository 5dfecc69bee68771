"""The paper's time-response setups (section 3.2): Figs 8-11."""
from __future__ import annotations

from pathlib import Path

from washer.machine.model import Model
from washer.machine.responses import Response

#: The paper's time-response setups (section 3.2). Fig 10/11: non-autonomous
#: spin-up, Omega = 10 Hz, tau_s = 0.45 s, 50 s, orbit shown over the last
#: 20 s (Fig 10c) or 5 s (Fig 11c). Figs 8/9: rotating frame from eps3 = 0.408.
SETUPS = {
    "fig10": dict(system="fixed", law="spinup", C_p=0.15, t_end=50.0, orbit_from=30.0),
    "fig11": dict(system="fixed", law="spinup", C_p=0.0, t_end=50.0, orbit_from=45.0),
    "fig8": dict(system="rotating", frame="averaged", C_p=0.15, t_end=50.0),
    "fig9": dict(system="rotating", frame="averaged", C_p=0.0, t_end=50.0),
}


def run_setup(name: str, params, out: Path, **overrides) -> tuple[Response, list[Path]]:
    """Run one named setup and write its data and plots into `out`."""
    from washer.plots import responses as plots
    setup = dict(SETUPS[name], **{k: v for k, v in overrides.items() if v is not None})
    model = Model(params.replace(C_p=setup.pop("C_p"), Omega=setup.pop("Omega", params["Omega"])))
    orbit_from = setup.pop("orbit_from", None)
    t_end = setup.pop("t_end")
    r = model.simulate(t_end, **setup)
    paths = r.save(out / name)
    paths += plots.save_response_figures(r, out / name, title=f"{name}: C_p = {model.params['C_p']:g}",
                                         orbit_from=orbit_from)
    return r, paths
