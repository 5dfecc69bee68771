"""Time responses of the washer: the kernel's DOPRI5 (default) or scipy's solve_ivp.

    >>> r = simulate(Model(load_params()), 20.0, system="fixed", law="spinup")
    >>> r.t, r.y, r.stats, r.save(Path("out/run"))

`Model.simulate` is the usual entry; `python -m washer.simulate` the command line.
A run that fails half-way (kernel error) keeps and returns what it computed.
"""
from __future__ import annotations

import json
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from washer.machine import kernel, layout

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


def default_initial_state(model, system: str) -> np.ndarray:
    """Paper's initial conditions: static equilibrium at rest (Figs 10-11), or
    eps3 = 0.408 m with everything else zero (Figs 8-9)."""
    if system == "fixed":
        return np.r_[model.static_equilibrium(), np.zeros(6)]
    y0 = np.zeros(12)
    y0[2] = PAPER_EPS3_0
    return y0


def simulate(model, t_end: float, *, system: str = "fixed", law: str = "spinup",
             frame: str = "averaged", y0=None, t_eval=None, samples_per_s: float = 1000.0,
             rtol: float = 1e-8, atol: float = 1e-10, method: str = "kernel",
             progress: bool | None = None) -> Response:
    """Integrate the ground-frame (eq 48, theta(t) by `law`) or rotating-frame
    (eq 59, `frame`) system from t = 0 to t_end (s).

    method: "kernel" (DOPRI5 in C++, one call per chunk) or "scipy" (solve_ivp
    DOP853 on the kernel's rhs, a reference path).
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
    elif method == "scipy":
        r = _simulate_scipy(model, system, mode, y0, t_eval, rtol, atol)
    else:
        raise ValueError(f"method: expected 'kernel' or 'scipy', got {method!r}")
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


def _simulate_scipy(model, system, mode, y0, t_eval, rtol, atol) -> Response:
    from scipy.integrate import solve_ivp
    if system == "fixed":
        def f(t, y):
            return kernel.rhs_fixed(t, y, model.P, mode)
    else:
        def f(t, y):
            return kernel.rhs_rot(y, model.P, mode)
    sol = solve_ivp(f, (t_eval[0], t_eval[-1]), y0, method="DOP853", t_eval=t_eval,
                    rtol=rtol, atol=atol)
    stats = {"nfev": int(sol.nfev), "naccept": None, "nreject": None}
    status = "ok" if sol.success else sol.message
    return Response(sol.t, sol.y.T, system, mode, "solve_ivp-DOP853", stats,
                    status=status)
