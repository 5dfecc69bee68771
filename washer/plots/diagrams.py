"""Bifurcation diagrams from b-files: stable solid, unstable dashed, special points labelled."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from washer.auto.files import read_b, type_name


def plot_branches(ax, branches, x: int = 0, y: int = 1, xlabel: str = "", ylabel: str = "",
                  label_points: bool = True, curve: bool = False):
    """Draw rows of `branches` (from washer.auto.files.read_b) on `ax`.

    x, y: column indices in a row's values (0 = PAR(ICP(1)), 1 = norm, 2.. = U(i),
    then the other ICP parameters; -1 is the last column). Stability comes from the
    sign of PT (negative = stable), as in AUTO; `curve=True` (loci of special
    points, ISW = 2, where PT carries no stability) draws everything solid.
    """
    for rows in branches:
        xs = np.array([r.values[x] for r in rows])
        ys = np.array([r.values[y] for r in rows])
        stable = np.array([curve or r.pt < 0 for r in rows])
        # Split into runs of equal stability, sharing the joining point.
        start = 0
        for k in range(1, len(rows) + 1):
            if k == len(rows) or stable[k] != stable[start]:
                seg = slice(start, min(k + 1, len(rows)))
                ax.plot(xs[seg], ys[seg], "-" if stable[start] else "--", color="C0",
                        lw=1.6 if stable[start] else 1.0)
                start = k
        if label_points:
            for r, xv, yv in zip(rows, xs, ys):
                name = type_name(r.ty)
                if r.lab and name and name != "EP":
                    ax.plot(xv, yv, "o" if name != "HB" else "*", color="C3", ms=6)
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


def save_diagram(path: Path, out: Path | None = None, x: int = 0, y: int = 1) -> list[Path]:
    """Plot a b-file to PNG and PDF; returns the written paths."""
    from washer.plots import style
    titles = column_titles(path)
    fig, ax = style.figure()
    name = lambda i: titles[i] if -len(titles) <= i < len(titles) else f"column {i}"
    curve = "Branch type:" in Path(path).read_text()
    plot_branches(ax, read_b(path), x, y, name(x), name(y), curve=curve)
    ax.set_title(Path(path).name)
    # with_suffix() would eat the b-file's own ".NAME": build the stem from a dot-free name.
    return style.save(fig, out or Path(path).parent / (Path(path).name.replace(".", "_") + "_diagram"))
