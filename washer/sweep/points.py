"""Points of a sweep: grids, seeded random samples, Latin hypercubes; stable ids.

A point is plain data (a dict), so that it pickles to any Dask worker:

    {"id": "3f2a...", "study": "map", "index": 7,
     "set": {"Omega": 12.0, "m_u": 0.8, "C_p": 0.101},   # parameters given to Params.replace
     "inputs": {"Omega": 12.0, "m_u": 0.8, ...},          # the table's input columns
     "kinds": ["stability", ...], "options": {"stability": {...}, ...}}

The id is a hash of everything that determines the point's result: the base
parameter values, the parameters set, the kinds and their options, and the
study's name. Re-running a spec therefore finds the same ids, whatever the
order of points or the batch size.
"""
from __future__ import annotations

import hashlib
import itertools
import json

import numpy as np

from washer.machine import layout
from washer.sweep.spec import Spec, Study

#: Hex digits of a point id (64 bits: collisions are negligible below ~1e8 points).
ID_DIGITS = 16


def base_data(spec: Spec) -> dict:
    """The base parameter set as plain data (what workers rebuild `Params` from)."""
    b = spec.base
    return {"values": dict(b.values), "tied": b.tied, "source": b.source}


def sample(study: Study) -> np.ndarray:
    """Values of the swept parameters, shape (n_points, n_axes), in the study's axis order.

    grid: the Cartesian product, first axis slowest. random: uniform (or
    log-uniform) draws from numpy's default_rng(seed). lhs: scipy's
    LatinHypercube(seed) scaled to the ranges (in log space for log axes)."""
    axes = study.axes
    if study.sample == "grid":
        return np.array(list(itertools.product(*[a.values for a in axes])), dtype=float)
    d = len(axes)
    if study.sample == "random":
        u = np.random.default_rng(study.seed).random((study.n, d))
    else:
        from scipy.stats import qmc
        gen = np.random.default_rng(study.seed)
        try:
            lhs = qmc.LatinHypercube(d=d, rng=gen)
        except TypeError:               # scipy < 1.15 names the generator `seed`
            lhs = qmc.LatinHypercube(d=d, seed=gen)
        u = lhs.random(study.n)
    out = np.empty_like(u)
    for j, a in enumerate(axes):
        if a.log:
            out[:, j] = np.exp(np.log(a.lo) + u[:, j] * (np.log(a.hi) - np.log(a.lo)))
        else:
            out[:, j] = a.lo + u[:, j] * (a.hi - a.lo)
    return out


def input_columns(spec: Spec) -> list[str]:
    """Parameters that appear as input columns: every swept or fixed one, in spec order."""
    cols: list[str] = []
    for st in spec.studies:
        for name in list(st.names) + list(st.fixed):
            if name not in cols:
                cols.append(name)
    return cols


def point_id(base: dict, study: str, setting: dict, kinds, options: dict) -> str:
    """Stable id of a point: a hash of its inputs (floats in repr, exact)."""
    doc = {"base": sorted(base["values"].items()), "tied": base["tied"], "study": study,
           "set": sorted(setting.items()), "kinds": list(kinds),
           "options": {k: sorted(options[k].items()) for k in kinds}}
    return hashlib.sha256(json.dumps(doc).encode()).hexdigest()[:ID_DIGITS]


def make_points(spec: Spec) -> list[dict]:
    """Every point of the spec, in study order, then sample order."""
    base = base_data(spec)
    cols = input_columns(spec)
    points: list[dict] = []
    for st in spec.studies:
        X = sample(st)
        opts = {k: dict(st.options[k]) for k in st.kinds}
        for i, row in enumerate(X):
            setting = dict(st.fixed)
            setting.update({a.name: float(v) for a, v in zip(st.axes, row)})
            inputs = {c: setting.get(c, _effective(base, setting, c)) for c in cols}
            points.append({"id": point_id(base, st.name, setting, st.kinds, opts),
                           "study": st.name, "index": i, "set": setting, "inputs": inputs,
                           "kinds": list(st.kinds), "options": opts})
    return points


def _effective(base: dict, setting: dict, name: str) -> float:
    """Value of `name` at a point: set, else tied to C_p, else the base value."""
    leader = layout.TIED_TO.get(name)
    if base["tied"] and leader in setting:
        return setting[leader]
    return float(base["values"][name])
