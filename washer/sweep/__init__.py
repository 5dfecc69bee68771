"""Parameter sweeps of the washer on Dask: stability, critical values and time responses.

    python -m washer.sweep SPEC.toml --out DIR           # LocalCluster, one worker a core
    python -m washer.sweep SPEC.toml --out DIR --scheduler tcp://HOST:8786
    python -m washer.sweep SPEC.toml --out DIR --serial  # in one process (debugging)
    python -m washer.sweep plot DIR                      # the maps again

    from washer.sweep import run, load_spec
    df = run("examples/sweep_small.toml", out="out/small")   # pandas DataFrame, one row a point

Modules: spec (TOML specs, validated), points (grids, random, Latin hypercube;
stable ids), tasks (the per-point computations, plain functions of plain
data), execute (serial or Dask), results (part files, consolidation, resume),
progress, hopf (the continuation's Hopf curve over a map), plots.
"""
from washer.sweep.execute import SpecChangedWarning, SweepInterrupted, run
from washer.sweep.spec import Spec, SpecError, load_spec, parse_spec

__all__ = ["run", "load_spec", "parse_spec", "Spec", "SpecError", "SweepInterrupted",
           "SpecChangedWarning"]
