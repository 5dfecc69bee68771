"""Time responses of the washer: kernel DOPRI5 (default) or scipy's solve_ivp.

    python -m washer.simulate fig10 fig11        # the paper's non-autonomous spin-ups
    python -m washer.simulate fig8 fig9 --out out/sim
    python -m washer.simulate custom --system fixed --Cp 0.05 --t-end 20

Each run writes NAME.npz (t, y, metadata as JSON), NAME.csv and PNG plots.
A run that fails half-way (kernel error) keeps and writes what it computed.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from washer import kernel, layout
from washer.machine import Model

#: Initial rotating-frame height of the paper's Figs 8-9 (section 3.2.1), m.
PAPER_EPS3_0 = 0.408


@dataclass
class Response:
    """A time history. t (n,) s; y (n, 12) = (q, q_dot) or (eps, eps_dot)."""
    t: np.ndarray
    y: np.ndarray
    system: str                 # "fixed" or "rotating"
    mode: str                   # speed law or rotating frame
    method: str
    stats: dict = field(default_factory=dict)
    wall: float = 0.0           # s
    status: str = "ok"          # or the error message of a failed run
    meta: dict = field(default_factory=dict)

    @property
    def names(self) -> tuple[str, ...]:
        base = layout.Q_NAMES if self.system == "fixed" else layout.EPS_NAMES
        return base + tuple(n + "_dot" for n in base)

    def save(self, stem: Path) -> list[Path]:
        """Write stem.npz and stem.csv; returns the paths."""
        stem.parent.mkdir(parents=True, exist_ok=True)
        meta = dict(self.meta, system=self.system, mode=self.mode, method=self.method,
                    stats=self.stats, wall_s=self.wall, status=self.status,
                    kernel_inputs_sha256=kernel.inputs_hash())
        np.savez_compressed(stem.with_suffix(".npz"), t=self.t, y=self.y,
                            names=np.array(self.names), meta=json.dumps(meta))
        np.savetxt(stem.with_suffix(".csv"), np.column_stack([self.t, self.y]), delimiter=",",
                   header=",".join(("t",) + self.names), comments="")
        return [stem.with_suffix(".npz"), stem.with_suffix(".csv")]


class _Progress:
    """A one-line progress bar on stderr, shown only on a terminal."""

    def __init__(self, total: float, label: str, enabled: bool | None = None):
        self.total, self.label = total, label
        self.enabled = sys.stderr.isatty() if enabled is None else enabled
        self.t0 = time.perf_counter()

    def update(self, done: float) -> None:
        if not self.enabled:
            return
        frac = min(1.0, done / self.total) if self.total > 0 else 1.0
        bar = "#" * int(30 * frac)
        sys.stderr.write(f"\r{self.label} [{bar:<30}] {100 * frac:5.1f}% "
                         f"{time.perf_counter() - self.t0:6.1f}s")
        sys.stderr.flush()

    def close(self) -> None:
        if self.enabled:
            sys.stderr.write("\n")


def default_initial_state(model: Model, system: str) -> np.ndarray:
    """Paper's initial conditions: static equilibrium at rest (Figs 10-11), or
    eps3 = 0.408 m with everything else zero (Figs 8-9)."""
    if system == "fixed":
        return np.r_[model.static_equilibrium(), np.zeros(6)]
    y0 = np.zeros(12)
    y0[2] = PAPER_EPS3_0
    return y0


def simulate(model: Model, t_end: float, *, system: str = "fixed", law: str = "spinup",
             frame: str = "averaged", y0=None, t_eval=None, samples_per_s: float = 1000.0,
             rtol: float = 1e-8, atol: float = 1e-10, method: str = "kernel",
             progress: bool | None = None) -> Response:
    """Integrate the ground-frame (eq 48, theta(t) by `law`) or rotating-frame
    (eq 59, `frame`) system from t = 0 to t_end (s).

    method: "kernel" (DOPRI5 in C++, one call per chunk), "scipy" (solve_ivp
    DOP853 on the kernel's rhs) or "scipy-numpy" (solve_ivp DOP853 on the
    pure-numpy reference rhs; ground frame only, a baseline).
    """
    if system not in ("fixed", "rotating"):
        raise ValueError(f"system: expected 'fixed' or 'rotating', got {system!r}")
    if not (t_end > 0):
        raise ValueError(f"t_end: expected a positive time, got {t_end!r}")
    mode = law if system == "fixed" else frame
    y0 = default_initial_state(model, system) if y0 is None else np.asarray(y0, dtype=float)
    if t_eval is None:
        t_eval = np.linspace(0.0, t_end, int(round(samples_per_s * t_end)) + 1)
    t_eval = np.asarray(t_eval, dtype=float)
    meta = {"params": model.params.values, "rtol": rtol, "atol": atol, "t_end": t_end}
    t0 = time.perf_counter()
    if method == "kernel":
        r = _simulate_kernel(model, system, mode, y0, t_eval, rtol, atol, progress)
    elif method in ("scipy", "scipy-numpy"):
        r = _simulate_scipy(model, system, mode, y0, t_eval, rtol, atol, method)
    else:
        raise ValueError(f"method: expected 'kernel', 'scipy' or 'scipy-numpy', got {method!r}")
    r.wall = time.perf_counter() - t0
    r.meta = meta
    return r


def _simulate_kernel(model, system, mode, y0, t_eval, rtol, atol, progress) -> Response:
    """Integrate in ~100 chunks (the step size carries over) to show progress."""
    n_chunks = max(1, min(100, t_eval.size // 50))
    bounds = np.linspace(0, t_eval.size, n_chunks + 1).astype(int)
    Y = np.full((t_eval.size, 12), np.nan)
    stats = {"nfev": 0, "naccept": 0, "nreject": 0}
    bar = _Progress(t_eval[-1], f"{system}/{mode}", progress)
    t, y, h, status, done = 0.0, y0, 0.0, "ok", 0
    try:
        for a, b in zip(bounds[:-1], bounds[1:]):
            if b <= a:
                continue
            try:
                Yc, h, info = kernel.integrate(system, mode, t, y, model.P, t_eval[a:b], rtol,
                                               atol, h0=h)
            except kernel.KernelError as exc:
                tp, Yp, info = exc.partial
                Y[a:a + len(tp)] = Yp
                done = a + len(tp)
                status = str(exc)
                break
            finally:
                for k in stats:
                    stats[k] += info[k]
            Y[a:b] = Yc
            t, y, done = t_eval[b - 1], Yc[-1], b
            bar.update(t)
    finally:
        bar.close()
    return Response(t_eval[:done], Y[:done], system, mode, "kernel-dopri5", stats, status=status)


def _simulate_scipy(model, system, mode, y0, t_eval, rtol, atol, method) -> Response:
    from scipy.integrate import solve_ivp
    if method == "scipy-numpy":
        if system != "fixed":
            raise ValueError("method 'scipy-numpy' exists for the ground frame only")
        from washer.reference import newton_euler

        def f(t, y):
            return newton_euler.rhs_fixed(t, y, model.params, mode)
    elif system == "fixed":
        def f(t, y):
            return kernel.rhs_fixed(t, y, model.P, mode)
    else:
        def f(t, y):
            return kernel.rhs_rot(y, model.P, mode)
    sol = solve_ivp(f, (t_eval[0], t_eval[-1]), y0, method="DOP853", t_eval=t_eval,
                    rtol=rtol, atol=atol)
    stats = {"nfev": int(sol.nfev), "naccept": None, "nreject": None}
    status = "ok" if sol.success else sol.message
    return Response(sol.t, sol.y.T, system, mode, f"solve_ivp-DOP853 ({method})", stats,
                    status=status)


# ------------------------------------------------------------------------ paper setups

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


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m washer.simulate",
                                 description="Time responses of the washer model (paper section 3.2).")
    ap.add_argument("setups", nargs="+", choices=sorted(SETUPS) + ["all"],
                    help="paper setups to run (all = fig8 fig9 fig10 fig11)")
    ap.add_argument("--params", type=Path, default=None, help="TOML parameter file "
                    "(default: the shipped reference set)")
    ap.add_argument("--out", type=Path, default=Path("out/simulate"), help="output folder")
    ap.add_argument("--Cp", type=float, default=None, help="override the setup's C_p (N m s/rad)")
    ap.add_argument("--Omega", type=float, default=None, help="override Omega (Hz)")
    ap.add_argument("--t-end", type=float, default=None, help="override the duration (s)")
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--method", choices=["kernel", "scipy"], default="kernel")
    args = ap.parse_args(argv)

    import matplotlib
    matplotlib.use("Agg")
    from washer.params import ParameterError, load_params
    try:
        params = load_params(args.params)
    except ParameterError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    names = sorted(SETUPS) if "all" in args.setups else args.setups
    rc = 0
    for name in names:
        r, paths = run_setup(name, params, args.out, C_p=args.Cp, Omega=args.Omega,
                             t_end=args.t_end, rtol=args.rtol, method=args.method)
        s = r.stats
        print(f"{name}: {r.system}/{r.mode}, t = 0..{r.t[-1]:g} s, {s['nfev']} evaluations, "
              f"{s['naccept']} steps, {r.wall:.2f} s wall; {r.status}")
        for p in paths:
            print(f"  wrote {p}")
        if r.status != "ok":
            rc = 1
    return rc


if __name__ == "__main__":
    raise SystemExit(main())
