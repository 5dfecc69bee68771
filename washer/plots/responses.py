"""Plots of time responses: y(t), z(t), the XY orbit of O_b, rotating-frame components."""
from __future__ import annotations

from pathlib import Path

from washer.plots import style

UNITS = ("m", "m", "m", "rad", "rad", "rad")


def plot_component(ax, r, i: int, label: str | None = None):
    """Component i of response r against time on axis `ax`."""
    ax.plot(r.t, r.y[:, i], label=label)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(f"{r.names[i]} ({UNITS[i % 6]})")
    return ax


def plot_orbit(ax, r, t_from: float = 0.0):
    """Trajectory of O_b projected on the ground XY plane for t >= t_from."""
    sel = r.t >= t_from
    ax.plot(r.y[sel, 0] * 1e3, r.y[sel, 1] * 1e3)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(f"O_b in plane XY, t in [{t_from:g}, {r.t[-1]:g}] s")
    return ax


def save_response_figures(r, stem: Path, title: str = "", orbit_from: float | None = None):
    """Write the standard figures of a response; returns their paths."""
    paths = []
    if r.system == "fixed":
        for i, tag in ((1, "y"), (2, "z")):
            fig, ax = style.figure()
            plot_component(ax, r, i)
            ax.set_title(f"{title}: {tag}(t) of O_b")
            paths += style.save(fig, Path(f"{stem}_{tag}"))
        fig, ax = style.figure(figsize=(5, 5))
        plot_orbit(ax, r, orbit_from if orbit_from is not None else max(0.0, r.t[-1] - 5))
        paths += style.save(fig, Path(f"{stem}_xy"))
    else:
        fig, axes = style.figure(3, 2, figsize=(8, 7), sharex=True)
        for i, ax in enumerate(axes.T.ravel()):
            plot_component(ax, r, i)
        fig.suptitle(f"{title}: rotating-frame components ({r.mode})")
        paths += style.save(fig, Path(f"{stem}_eps"))
    return paths
