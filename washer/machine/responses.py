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

from washer import sizes
from washer.atomic import atomic_file
from washer.machine import kernel, layout

#: Initial rotating-frame height of the paper's Figs 8-9 (section 3.2.1), m.
PAPER_EPS3_0 = 0.408
#: Output samples per simulated second unless told otherwise (1/s).
SAMPLES_PER_S = 1000.0


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
        """Write stem.npz and stem.csv; returns the paths. Each file replaces the old
        one in one step (washer.atomic): an interrupted save leaves the previous
        files, never a truncated one, and never writes through a link."""
        stem = Path(stem)
        stem.parent.mkdir(parents=True, exist_ok=True)
        meta = dict(self.meta, system=self.system, mode=self.mode, method=self.method,
                    stats=self.stats, wall_s=self.wall, status=self.status,
                    kernel_inputs_sha256=kernel.inputs_hash())
        with atomic_file(stem.with_suffix(".npz")) as fh:
            np.savez_compressed(fh, t=self.t, y=self.y, names=np.array(self.names),
                                meta=json.dumps(meta))
        with atomic_file(stem.with_suffix(".csv")) as fh:
            np.savetxt(fh, np.column_stack([self.t, self.y]), delimiter=",",
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
             frame: str = "averaged", y0=None, t_eval=None, samples_per_s: float = SAMPLES_PER_S,
             rtol: float = 1e-8, atol: float = 1e-10, method: str = "kernel",
             progress: bool | None = None, allow_large: bool = False) -> Response:
    """Integrate the ground-frame (eq 48, theta(t) by `law`) or rotating-frame
    (eq 59, `frame`) system from t = 0 to t_end (s).

    method: "kernel" (DOPRI5 in C++, one call per chunk) or "scipy" (solve_ivp
    DOP853 on the kernel's rhs, a reference path). Every input is checked before
    the integration starts (ValueError naming it); a response whose memory or time
    estimate is far above the usual raises washer.sizes.SizeError unless
    `allow_large`. Ctrl-C raises KeyboardInterrupt within a step.
    """
    if system not in ("fixed", "rotating"):
        raise ValueError(f"system: expected 'fixed' or 'rotating', got {system!r}")
    if not (np.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end: expected a finite positive time (s), got {t_end!r}")
    for name, v in (("rtol", rtol), ("atol", atol)):
        if not (np.isfinite(v) and 0 < v < 1):
            raise ValueError(f"{name}: expected a tolerance in (0, 1), got {v!r}")
    mode = law if system == "fixed" else frame
    if y0 is None:
        y0 = default_initial_state(model, system)
    y0 = np.asarray(y0, dtype=float)
    if y0.shape != (12,) or not np.all(np.isfinite(y0)):
        raise ValueError(f"y0: expected 12 finite numbers, got shape {y0.shape}"
                         + ("" if y0.shape != (12,) else " with NaN or inf"))
    if t_eval is None:
        if not (np.isfinite(samples_per_s) and samples_per_s > 0):
            raise ValueError(f"samples_per_s: expected a finite positive rate (1/s), got "
                             f"{samples_per_s!r}")
        n_samples = samples_per_s * t_end + 1
    else:
        t_eval = np.asarray(t_eval, dtype=float)
        n_samples = t_eval.size
        _check_times(t_eval)
    response_size_check(t_end, n_samples, system, rtol, allow=allow_large)
    if t_eval is None:
        t_eval = np.linspace(0.0, t_end, int(round(samples_per_s * t_end)) + 1)
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


def response_size_check(t_end: float, n_samples: float | None, system: str, rtol: float,
                        allow: bool = False) -> None:
    """washer.sizes.SizeError, with the estimate, for a response far above the usual
    (n_samples None: SAMPLES_PER_S over t_end)."""
    if n_samples is None:
        n_samples = SAMPLES_PER_S * t_end + 1
    nbytes, seconds = sizes.response_cost(t_end, n_samples, system, rtol)
    sizes.check(f"a {system}-frame response of t_end = {t_end:g} s with {n_samples:.4g} "
                "samples", nbytes=nbytes, seconds=seconds, allow=allow,
                how="pass allow_large=True (--allow-large), or shorten t_end or the sampling")


def _check_times(t_eval: np.ndarray) -> None:
    """Output times the integration (from t = 0) can reach, in order."""
    if t_eval.ndim != 1 or t_eval.size == 0:
        raise ValueError(f"t_eval: expected a non-empty 1-D array of times, got shape "
                         f"{t_eval.shape}")
    bad = np.flatnonzero(~np.isfinite(t_eval))
    if bad.size:
        raise ValueError(f"t_eval[{bad[0]}] = {float(t_eval[bad[0]])}: expected finite times (s)")
    if t_eval[0] < 0:
        raise ValueError(f"t_eval[0] = {float(t_eval[0])}: the integration starts at t = 0")
    dec = np.flatnonzero(np.diff(t_eval) < 0)
    if dec.size:
        k = dec[0] + 1
        raise ValueError(f"t_eval[{k}] = {float(t_eval[k])} < t_eval[{k - 1}] = "
                         f"{float(t_eval[k - 1])}: "
                         "expected non-decreasing times")


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
            info = None      # an interrupt raises before the kernel returns any
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
                if info is not None:
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
