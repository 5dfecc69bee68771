"""Bifurcation diagrams from b-files: stable solid, unstable dashed, special points labelled."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from washer.auto.files import read_b, type_name


#: Markers of labelled points by type (AUTO's names): Hopf star, folds diamond, branch
#: points square, period doubling / torus triangles, user points small dots.
MARKERS = {"HB": "*", "LP": "D", "BP": "s", "PD": "^", "TR": "v", "UZ": "."}


def plot_branches(ax, branches, x: int = 0, y: int = 1, xlabel: str = "", ylabel: str = "",
                  label_points: bool = True, curve: bool = False, periodic: bool = False):
    """Draw rows of `branches` (from washer.auto.files.read_b) on `ax`.

    x, y: column indices in a row's values (0 = PAR(ICP(1)), 1 = norm, 2.. = U(i) of
    equilibria or MAX U(i) of periodic orbits, then the other ICP parameters; -1 is the
    last column). Stability comes from the sign of PT (negative = stable), as in AUTO;
    `curve=True` (loci of special points, ISW = 2, where PT carries no stability) draws
    everything solid. Periodic branches (BR < 0 in AUTO's b-files) are drawn in a
    second colour (also every branch when `periodic`, for files whose header says
    MAX U), so a file with both, or several files on one axes, read apart.
    """
    for rows in branches:
        if not rows:
            continue
        color = "C1" if (periodic or rows[0].br < 0) else "C0"
        xs = np.array([r.values[x] for r in rows])
        ys = np.array([r.values[y] for r in rows])
        stable = np.array([curve or r.pt < 0 for r in rows])
        # Split into runs of equal stability, sharing the joining point.
        start = 0
        for k in range(1, len(rows) + 1):
            if k == len(rows) or stable[k] != stable[start]:
                seg = slice(start, min(k + 1, len(rows)))
                ax.plot(xs[seg], ys[seg], "-" if stable[start] else "--", color=color,
                        lw=1.6 if stable[start] else 1.0)
                start = k
        if label_points:
            for r, xv, yv in zip(rows, xs, ys):
                name = type_name(r.ty)
                if r.lab and name and name != "EP":
                    ax.plot(xv, yv, MARKERS.get(name, "o"), color="C3", ms=6)
                    ax.annotate(f"{name}{r.lab}", (xv, yv), textcoords="offset points",
                                xytext=(4, 4), fontsize=8)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    return ax


def column_titles(path: Path) -> list[str]:
    """Titles of the value columns from the b-file's header."""
    for line in Path(path).read_text().splitlines():
        if line.startswith("   0    PT  TY  LAB"):
            body = line[len("   0    PT  TY  LAB "):]
            return [body[i:i + 19].strip() for i in range(0, len(body), 19) if body[i:i + 19].strip()]
    return []


def save_diagram(path, out: Path | None = None, x: int = 0, y: int = 1) -> list[Path]:
    """Plot one b-file, or several on one axes (a list: e.g. equilibria and the
    periodic orbits born at their Hopf points), to PNG and PDF; returns the paths.
    Axis titles come from the first file's header."""
    from washer.plots import style
    paths = [Path(p) for p in path] if isinstance(path, (list, tuple)) else [Path(path)]
    titles = column_titles(paths[0])
    fig, ax = style.figure()
    name = lambda i: titles[i] if -len(titles) <= i < len(titles) else f"column {i}"
    for p in paths:
        curve = "Branch type:" in p.read_text()
        periodic = any(t.startswith("MAX ") for t in column_titles(p))
        plot_branches(ax, read_b(p), x, y, name(x), name(y), curve=curve, periodic=periodic)
    ax.set_title(", ".join(p.name for p in paths))
    # with_suffix() would eat the b-file's own ".NAME": build the stem from a dot-free name.
    return style.save(fig, out or paths[0].parent / (paths[0].name.replace(".", "_") + "_diagram"))
