"""One place for figure styling: sizes, fonts, resolution, and saving PNG + PDF."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt

from washer.atomic import check_folder, save_figure

RC = {"figure.figsize": (6.4, 4.0), "font.size": 10, "axes.grid": True, "grid.alpha": 0.3,
      "lines.linewidth": 1.0, "savefig.dpi": 150, "legend.frameon": False}


def figure(nrows: int = 1, ncols: int = 1, **kw):
    """A styled figure and its axes (object-oriented API, nothing shown)."""
    with plt.rc_context(RC):
        return plt.subplots(nrows, ncols, constrained_layout=True, **kw)


def save(fig, stem: Path, formats=("png", "pdf")) -> list[Path]:
    """Save `fig` as stem.png and stem.pdf, close it, return the paths."""
    check_folder(stem.parent)            # OutputError naming the folder, not an OSError
    paths = []
    with plt.rc_context(RC):
        for ext in formats:
            p = stem.with_suffix("." + ext)
            save_figure(fig, p)          # never through a planted link, never half-written
            paths.append(p)
    plt.close(fig)
    return paths
