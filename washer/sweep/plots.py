"""Maps of a sweep: `python -m washer.sweep plot DIR` (also run at the end of a sweep).

For every study over two parameters, one figure per kind in DIR/plots/:

- STUDY_stability.png   margin (largest real part, 1/s) as a colour map, the
  sweep's boundary (margin = 0) in black;
- STUDY_critical.png    the critical value as a colour map with contours; the
  contour at the study's own value of that parameter is the sweep's boundary;
- STUDY_response.png    steady whirl radius (log colour scale);

each with the continuation's Hopf curve in the same two parameters overlaid
(dashed red; `washer.sweep.hopf`, b-files in DIR/hopf/STUDY/), and failed
points as grey crosses. On critical maps the points stable over the whole
search range (with C_p from 0: stable without joint damping, critical value 0)
are white rings on their colour, those unstable over it red triangles; with
the option `clearance`, a dashed line where the whirl at the study's value just
reaches the clearance (crit_clearance_value = that value). Studies over one parameter give line plots; studies
over more than two are not drawn (the table has them).
"""
from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd

from washer.atomic import write_text
from washer.sweep.results import ResultStore
from washer.sweep.spec import Spec, Study, parse_spec

log = logging.getLogger(__name__)

#: Decades of whirl radius shown below the largest one on response maps.
RADIUS_DECADES = 3

LABELS = {"stab_margin": "stability margin max Re(λ) (1/s)",
          "crit_value": "critical {p}",
          "resp_whirl_radius": "steady whirl radius (m)"}


def load_dir_spec(folder) -> Spec:
    """The spec a results folder was run with (relative parameter paths resolved
    against the original spec's folder)."""
    folder = Path(folder)
    src = ResultStore(folder).spec_source()
    base_dir = Path(src).parent if src and not src.startswith("<") else folder
    return parse_spec((folder / "spec.toml").read_text(), src, base_dir=base_dir)


def plot_dir(folder, spec: Spec | None = None, hopf: bool = True) -> list[Path]:
    """Draw every map of a results folder; returns the files written."""
    folder = Path(folder)
    spec = spec or load_dir_spec(folder)
    df = ResultStore(folder).results()
    paths = []
    for st in spec.studies:
        sub = df[df["study"] == st.name]
        if sub.empty or len(st.axes) > 2:
            continue
        curve, note = None, ""
        if hopf and len(st.axes) == 2:
            curve, note = study_hopf_curve(spec, st, folder)
        for kind in st.kinds:
            paths += _plot_kind(folder, spec, st, kind, sub, curve, note)
    return paths


def study_hopf_curve(spec: Spec, st: Study, folder: Path):
    """(branches or None, note): the Hopf curve over the study's map, cached in DIR/hopf/STUDY."""
    from washer.sweep.hopf import hopf_curve
    x, y = st.names
    xr, yr = _range(st, 0), _range(st, 1)
    where = folder / "hopf" / st.name
    key = json.dumps({"x": x, "y": y, "xr": xr, "yr": yr, "fixed": sorted(st.fixed.items()),
                      "base": sorted(spec.base.values.items())})
    cache = where / "curve.json"
    if cache.exists():
        got = json.loads(cache.read_text())
        if got["key"] == key:
            return ([np.array(b) for b in got["branches"]] or None), got["note"]
    try:
        branches = hopf_curve(spec.base.replace(**st.fixed), x, xr, y, yr, where)
        note = ""
    except Exception as exc:  # noqa: BLE001 - HopfCurveError or an engine error: no overlay
        branches, note = [], f"no continuation curve: {exc}"
        log.info("study %s: %s", st.name, note)
    where.mkdir(parents=True, exist_ok=True)
    write_text(cache, json.dumps({"key": key, "note": note,
                                  "branches": [b.tolist() for b in branches]}))
    return (branches or None), note


def _range(st: Study, j: int) -> tuple[float, float]:
    a = st.axes[j]
    vals = a.values if a.values is not None else (a.lo, a.hi)
    return float(min(vals)), float(max(vals))


def _label(name: str) -> str:
    from washer.machine import layout
    unit = layout.UNITS.get(name, "")
    return f"{name} ({unit})" if unit else name


def _plot_kind(folder, spec, st, kind, sub, curve, note) -> list[Path]:
    from washer.plots import style
    col = {"stability": "stab_margin", "critical": "crit_value",
           "response": "resp_whirl_radius"}[kind]
    if col not in sub:
        return []
    fig, ax = style.figure()
    ok = sub[sub[col].notna()]
    bad = sub[sub[col].isna()]
    label = LABELS[col].format(p=_label(st.options.get("critical", {}).get("parameter", "")))
    if len(st.axes) == 1:
        x = st.names[0]
        ax.plot(ok[x], ok[col], "o-", ms=3)
        ax.set_xlabel(_label(x))
        ax.set_ylabel(label)
        if kind == "stability":
            ax.axhline(0, color="k", lw=0.8)
    else:
        x, y = st.names
        _colour_map(fig, ax, st, ok, x, y, col, kind, label, spec)
        if curve:
            for i, b in enumerate(curve):
                ax.plot(b[:, 0], b[:, 1], "--", color="tab:red", lw=1.6,
                        label="Hopf curve (continuation)" if i == 0 else None)
        (xl, xh), (yl, yh) = _range(st, 0), _range(st, 1)
        ax.set_xlim(xl, xh)
        ax.set_ylim(yl, yh)
        ax.set_xlabel(_label(x))
        ax.set_ylabel(_label(y))
        if kind == "critical" and "crit_status" in sub:
            _mark_answers(ax, st, sub, x, y)
            bad = sub[sub["crit_status"] == "failed"]
        if len(bad):
            ax.plot(bad[x], bad[y], "x", color="0.4", ms=5, label=f"failed ({len(bad)})")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="best", fontsize=8)
    title = f"{st.name}: {kind}"
    fixed = ", ".join(f"{k} = {v:g}" for k, v in st.fixed.items())
    ax.set_title(title + (f"  ({fixed})" if fixed else ""), fontsize=9)
    if note:
        ax.text(0.01, 0.01, note[:90], transform=ax.transAxes, fontsize=6, color="0.4")
    return style.save(fig, folder / "plots" / f"{st.name}_{kind}", formats=("png",))


def _mark_answers(ax, st, sub, x, y) -> None:
    """Critical maps: the points stable over the whole search range (critical value at
    most `from`; with C_p from 0, stable without joint damping) and those unstable over
    it (more than `to` needed) are answers, marked as such."""
    opt = st.options["critical"]
    stable = sub[sub["crit_status"] == "stable"]
    unstable = sub[sub["crit_status"] == "unstable"]
    if len(stable):
        what = ("stable without joint damping" if opt["parameter"] == "C_p" and opt["from"] == 0
                else f"stable from {opt['parameter']} = {opt['from']:g}")
        ax.plot(stable[x], stable[y], "o", mfc="none", mec="w", ms=6, mew=1.2,
                label=f"{what} ({len(stable)})")
    if len(unstable):
        ax.plot(unstable[x], unstable[y], "^", color="tab:red", ms=5,
                label=f"unstable up to {opt['parameter']} = {opt['to']:g} ({len(unstable)})")


def _colour_map(fig, ax, st, ok, x, y, col, kind, label, spec) -> None:
    from matplotlib import colors
    v = ok[col].to_numpy(float)
    if not len(v):
        return
    grid = st.sample == "grid"
    line_col = col              # the column whose contour at `levels` is the boundary
    if kind == "stability":
        lim = float(np.nanmax(np.abs(v))) or 1.0
        norm, cmap = colors.TwoSlopeNorm(0.0, -lim, lim), "RdBu_r"
        levels = [0.0]
    elif kind == "response":
        # Log scale over at most RADIUS_DECADES below the largest radius (without
        # an imbalance the radius is round-off, ~1e-16 m, and would take the scale).
        pos = v[v > 0]
        norm = None
        if len(pos) and pos.max() > 10 * pos.min():
            norm = colors.LogNorm(max(pos.min(), pos.max() * 10.0 ** -RADIUS_DECADES),
                                  pos.max(), clip=True)
        cmap, levels = "viridis", None
        if "stab_margin" in ok and ok["stab_margin"].notna().all():
            line_col, levels = "stab_margin", [0.0]
    else:
        norm, cmap = None, "viridis"
        par = st.options["critical"]["parameter"]
        here = st.fixed.get(par, spec.base[par])
        levels = [here] if np.nanmin(v) < here < np.nanmax(v) else None
    if grid:
        piv = ok.pivot_table(index=y, columns=x, values=col)
        X, Y = np.meshgrid(piv.columns.to_numpy(float), piv.index.to_numpy(float))
        m = ax.pcolormesh(X, Y, piv.to_numpy(float), shading="nearest", norm=norm, cmap=cmap)
        if levels and piv.shape[0] > 1 and piv.shape[1] > 1:
            lines = ok.pivot_table(index=y, columns=x, values=line_col).to_numpy(float)
            ax.contour(X, Y, lines, levels=levels, colors="k", linewidths=1.4)
            ax.plot([], [], "k-", label="sweep boundary" + (" (margin = 0)" if kind == "response"
                                                            else ""))
        if kind == "critical" and piv.shape[0] > 1 and piv.shape[1] > 1:
            ax.contour(X, Y, piv.to_numpy(float), levels=8, colors="w", linewidths=0.5,
                       alpha=0.6)
            clear = st.options["critical"].get("clearance", float("nan"))
            if levels and "crit_clearance_value" in ok and np.isfinite(clear):
                cv = ok.pivot_table(index=y, columns=x, values="crit_clearance_value")
                cv = cv.reindex(index=piv.index, columns=piv.columns).to_numpy(float)
                if np.isfinite(cv).sum() >= 4 and np.nanmin(cv) < levels[0] < np.nanmax(cv):
                    ax.contour(X, Y, cv, levels=levels, colors="k", linewidths=1.2,
                               linestyles="--")
                    ax.plot([], [], "k--", label=f"whirl reaches the {1e3 * clear:g} mm "
                            "clearance")
    else:
        m = ax.scatter(ok[x], ok[y], c=ok[col].to_numpy(float), s=18, norm=norm, cmap=cmap)
        if levels and len(ok) >= 4:
            try:
                ax.tricontour(ok[x], ok[y], ok[line_col].to_numpy(float), levels=levels,
                              colors="k", linewidths=1.4)
                ax.plot([], [], "k-", label="sweep boundary")
            except Exception:  # noqa: BLE001 - degenerate triangulations: no line
                pass
    fig.colorbar(m, ax=ax, label=label)


def boundary_crossings(df: pd.DataFrame, x: str, y: str, col: str = "stab_margin",
                       level: float = 0.0) -> pd.DataFrame:
    """Where `col` crosses `level` between neighbours along x on a grid, per y value:
    columns y, x_lo, x_hi (the bracketing grid values) and x (linear interpolation)."""
    rows = []
    for yv, g in df.dropna(subset=[col]).groupby(y):
        g = g.sort_values(x)
        xs, vs = g[x].to_numpy(float), g[col].to_numpy(float) - level
        for i in range(len(xs) - 1):
            if vs[i] == 0 or vs[i] * vs[i + 1] < 0:
                xi = xs[i] - vs[i] * (xs[i + 1] - xs[i]) / (vs[i + 1] - vs[i])
                rows.append({y: yv, "x_lo": xs[i], "x_hi": xs[i + 1], "x": xi})
    return pd.DataFrame(rows)
