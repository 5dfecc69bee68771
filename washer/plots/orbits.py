"""A labelled periodic orbit from an s-file: time profile and phase portrait."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from washer.auto.files import read_s


def find_label(records, label: int):
    """The record with label `label` (a periodic one: NTPL > 1)."""
    for r in records:
        if r.lab == label:
            if np.ndim(r.U) != 2:
                raise ValueError(f"label {label} is not a periodic solution (NTPL = 1)")
            return r
    raise KeyError(f"no label {label} (labels: {[r.lab for r in records]})")


def plot_orbit(ax_t, ax_p, rec, components=None, phase=(1, 2), names: dict | None = None):
    """Components `components` (1-based, default the first min(NDIM, 6)) against time
    t * PERIOD on ax_t, and U(phase[1]) against U(phase[0]) on ax_p. Time is the s-file's
    t in [0, 1] times PAR(11)."""
    names = names or {}
    U = np.asarray(rec.U)
    t = np.asarray(rec.t if rec.t is not None else np.linspace(0, 1, len(U)))
    T = float(rec.par[10]) if len(rec.par) > 10 else 1.0
    comps = components or list(range(1, min(U.shape[1], 6) + 1))
    name = lambda i: names.get(i, f"U({i})")
    for i in comps:
        ax_t.plot(t * T, U[:, i - 1], label=name(i))
    ax_t.set_xlabel("t (PERIOD = %.6g)" % T)
    ax_t.legend(fontsize=8, ncol=2)
    i, j = phase
    ax_p.plot(U[:, i - 1], U[:, j - 1], "-", color="C0")
    ax_p.plot(U[0, i - 1], U[0, j - 1], "o", color="C3", ms=4)
    ax_p.set_xlabel(name(i))
    ax_p.set_ylabel(name(j))
    return ax_t, ax_p


def save_orbit(path: Path, label: int, out: Path | None = None, components=None,
               phase=(1, 2)) -> list[Path]:
    """The orbit at `label` of s-file `path` to PNG and PDF; returns the written paths."""
    from washer.plots import style
    rec = find_label(read_s(path), label)
    fig, (ax_t, ax_p) = style.figure(1, 2, figsize=(10, 4))
    plot_orbit(ax_t, ax_p, rec, components, phase)
    ty = rec.ty
    fig.suptitle(f"{Path(path).name} label {label}{' ' + ty if ty else ''}: PAR(11) = "
                 f"{rec.par[10]:.6g}")
    stem = out or Path(path).parent / (Path(path).name.replace(".", "_") + f"_orbit{label}")
    return style.save(fig, stem)
