"""Bifurcation diagrams from b-files: stable solid, unstable dashed, special points labelled."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from washer.auto.files import read_b, type_name


#: Markers of labelled points by type (AUTO's names): Hopf star, folds diamond, branch
#: points square, period doubling / torus triangles, user points small dots.
MARKERS = {"HB": "*", "LP": "D", "BP": "s", "PD": "^", "TR": "v", "UZ": "."}


def plot_branches(ax, branches, x: int = 0, y: int = 1, xlabel: str = "", ylabel: str = "",
                  label_points: bool = True, curve: bool = False, periodic: bool = False,
                  color: str | None = None):
    """Draw rows of `branches` (from washer.auto.files.read_b) on `ax`.

    x, y: column indices in a row's values (0 = PAR(ICP(1)), 1 = norm, 2.. = U(i) of
    equilibria or MAX U(i) of periodic orbits, then the other ICP parameters; -1 is the
    last column). Stability comes from the sign of PT (negative = stable), as in AUTO;
    `curve=True` (loci of special points, ISW = 2, where PT carries no stability) draws
    everything solid. Periodic branches (BR < 0 in AUTO's b-files) are drawn in a
    second colour (also every branch when `periodic`, for files whose header says
    MAX U), so a file with both, or several files on one axes, read apart; `color`
    draws every branch in one colour instead (one colour per file).
    """
    for rows in branches:
        if not rows:
            continue
        n = min(len(r.values) for r in rows)
        if not (-n <= x < n and -n <= y < n):
            continue          # a branch without this column (PERIOD on equilibria)
        c = color or ("C1" if (periodic or rows[0].br < 0) else "C0")
        xs = np.array([r.values[x] for r in rows])
        ys = np.array([r.values[y] for r in rows])
        stable = np.array([curve or r.pt < 0 for r in rows])
        # Split into runs of equal stability, sharing the joining point.
        start = 0
        for k in range(1, len(rows) + 1):
            if k == len(rows) or stable[k] != stable[start]:
                seg = slice(start, min(k + 1, len(rows)))
                ax.plot(xs[seg], ys[seg], "-" if stable[start] else "--", color=c,
                        lw=1.6 if stable[start] else 1.0)
                start = k
        if label_points:
            for r, xv, yv in zip(rows, xs, ys):
                name = type_name(r.ty)
                if r.lab and name and name != "EP":
                    ax.plot(xv, yv, MARKERS.get(name, "o"), color="C3", ms=6)
                    ax.annotate(f"{name}{r.lab}", (xv, yv), textcoords="offset points",
                                xytext=(4, 4), fontsize=8)
    if xlabel:
        ax.set_xlabel(xlabel)
    if ylabel:
        ax.set_ylabel(ylabel)
    return ax


def column_titles(path: Path) -> list[str]:
    """Titles of the value columns from the b-file's header."""
    return header_names(path)[0]


def header_names(path: Path) -> tuple[list[str], dict, dict]:
    """(column titles, parnames, unames) from a b-file's header: the titles line
    (`0 PT TY LAB ...`, 19 characters a column) and the `parnames = {...}`,
    `unames = {...}` lines washer and AUTO-07p write."""
    import ast
    titles: list[str] = []
    names = {"parnames": {}, "unames": {}}
    text = Path(path).read_text(errors="replace")
    for line in text.splitlines():
        if line.startswith("   0    PT  TY  LAB"):
            body = line[len("   0    PT  TY  LAB "):]
            titles = [body[i:i + 19].strip() for i in range(0, len(body), 19)
                      if body[i:i + 19].strip()]
        f = line.split(None, 3)
        if len(f) == 4 and f[0] == "0" and f[1] in names and f[2] == "=":
            try:
                d = ast.literal_eval(f[3].strip())
            except (ValueError, SyntaxError):
                continue
            if isinstance(d, dict):
                names[f[1]] = {int(k): str(v) for k, v in d.items()
                               if isinstance(k, int) or str(k).isdigit()}
    return titles, names["parnames"], names["unames"]


def resolve_column(key, titles: list[str], parnames: dict, unames: dict) -> int:
    """Index in a row's values of column `key`: an integer (0-based, -1 the last), a
    title ('L2-NORM', 'PAR(1)', 'MAX U(2)', 'PERIOD'), a parameter name (parnames:
    'rho' or 'PAR(1)' whichever the file shows), a state name (unames: 'x' for U(1),
    'MAX x' for MAX U(1) of periodic orbits). KeyError naming the columns otherwise."""
    if isinstance(key, int) or (isinstance(key, str) and key.lstrip("-").isdigit()):
        k = int(key)
        if not -len(titles) <= k < len(titles) and titles:
            raise KeyError(f"column {k}: the file has {len(titles)} columns ({', '.join(titles)})")
        return k
    key = str(key).strip()
    aliases = {key}
    prefix, base = ("MAX ", key[4:].strip()) if key.upper().startswith("MAX ") else ("", key)
    for i, n in parnames.items():
        if base == n:
            aliases.add(f"PAR({i})")
        if base == f"PAR({i})":
            aliases.add(n)
    if base == "PERIOD":
        aliases.add("PAR(11)")
    if base == "PAR(11)":
        aliases.add("PERIOD")
    for i, n in unames.items():
        if base == n:
            aliases |= {f"{prefix}U({i})", f"{prefix}{n}"}
        if base == f"U({i})":
            aliases.add(f"{prefix}{n}")
    for k, t in enumerate(titles):
        if t in aliases or t.upper() in {a.upper() for a in aliases}:
            return k
    known = titles + [n for n in parnames.values() if n not in titles]
    raise KeyError(f"{key!r}: no such column (columns: {', '.join(titles)}; names: "
                   f"{', '.join(map(str, known))})")


def save_diagram(path, out: Path | None = None, x=0, y=1) -> list[Path]:
    """Plot one b-file, or several on one axes (a list: e.g. equilibria and the
    periodic orbits born at their Hopf points), to PNG and PDF; returns the paths.

    x, y: columns by index or by name (see `resolve_column`), resolved in each file
    (a name may sit in different columns of different files). Each file gets one
    colour and one legend entry; stable parts are solid, unstable dashed (the legend
    says so); labelled points are marked with their type and label (HB2, LP1, ...).
    KeyError when a file lacks a column."""
    from matplotlib.lines import Line2D
    from washer.plots import style
    paths = [Path(p) for p in path] if isinstance(path, (list, tuple)) else [Path(path)]
    fig, ax = style.figure()
    handles = []
    xlabel = ylabel = ""
    for n, p in enumerate(paths):
        titles, parnames, unames = header_names(p)
        try:
            xi = resolve_column(x, titles, parnames, unames)
            yi = resolve_column(y, titles, parnames, unames)
        except KeyError as exc:
            raise KeyError(f"{p}: {exc.args[0]}") from None
        name = lambda i: titles[i] if -len(titles) <= i < len(titles) else f"column {i}"
        xlabel = xlabel or (x if isinstance(x, str) and not x.lstrip("-").isdigit() else name(xi))
        ylabel = ylabel or (y if isinstance(y, str) and not y.lstrip("-").isdigit() else name(yi))
        curve = "Branch type:" in p.read_text(errors="replace")
        color = f"C{n % 10}"
        plot_branches(ax, read_b(p), xi, yi, curve=curve, color=color)
        handles.append(Line2D([], [], color=color, lw=1.6, label=p.name))
    handles += [Line2D([], [], color="k", lw=1.6, ls="-", label="stable"),
                Line2D([], [], color="k", lw=1.0, ls="--", label="unstable")]
    ax.legend(handles=handles, fontsize=8)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(", ".join(p.name for p in paths))
    # with_suffix() would eat the b-file's own ".NAME": build the stem from a dot-free name.
    return style.save(fig, out or paths[0].parent / (paths[0].name.replace(".", "_") + "_diagram"))
