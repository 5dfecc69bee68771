"""Command line of washer.sweep.

    python -m washer.sweep SPEC.toml [--out DIR] [--scheduler tcp://HOST:PORT | --serial]
                           [--workers N] [--batch-size N] [--retry-failed] [--no-plot]
                           [--progress | --no-progress] [--allow-large]
    python -m washer.sweep plot DIR [--no-hopf]

Exit status: 0 when every point has its answers, 1 when some failed (they are
in the table with their errors; a point stable without joint damping is an
answer, critical C_p = 0, not a failure), 2 for a bad spec or arguments (an
unusable --out, a sweep far larger than usual without --allow-large), 3 when no
Dask scheduler answers at --scheduler, 75 when another sweep is writing into
--out, 130 when interrupted (re-run the same command to resume).
"""
from __future__ import annotations

import argparse
import logging
import sys
import time
import warnings
from pathlib import Path

EXIT_SCHEDULER = 3
EXIT_LOCKED = 75


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] == "plot":
        return _plot(argv[1:])
    ap = argparse.ArgumentParser(prog="python -m washer.sweep",
                                 description="Parameter sweeps of the washer (stability, "
                                 "critical values, time responses) on Dask. "
                                 "`python -m washer.sweep plot DIR` redraws the maps.")
    ap.add_argument("spec", type=Path, help="sweep spec (TOML; see examples/sweep_small.toml)")
    ap.add_argument("--out", type=Path, default=None,
                    help="results folder (default out/sweep/SPEC-NAME); re-using it resumes")
    how = ap.add_mutually_exclusive_group()
    how.add_argument("--scheduler", metavar="ADDRESS",
                     help="address of a running Dask scheduler, e.g. tcp://10.0.0.5:8786")
    how.add_argument("--serial", action="store_true", help="compute in this process")
    ap.add_argument("--workers", type=int, default=None,
                    help="local worker processes (default: one per core)")
    ap.add_argument("--batch-size", type=int, default=None, help="points per task")
    ap.add_argument("--retry-failed", action="store_true",
                    help="recompute the points recorded as failed")
    ap.add_argument("--no-plot", action="store_true", help="skip the maps at the end")
    bar = ap.add_mutually_exclusive_group()
    bar.add_argument("--progress", dest="progress", action="store_true", default=True,
                     help="a progress bar on stderr (the default, on a terminal or not)")
    bar.add_argument("--no-progress", dest="progress", action="store_false")
    ap.add_argument("--allow-large", action="store_true",
                    help="run a sweep whose estimated memory or time is far above the usual")
    args = ap.parse_args(argv)

    from washer.atomic import OutputError, check_folder
    from washer.locks import LockedError
    from washer.sizes import SizeError
    from washer.sweep import SpecChangedWarning, SpecError, SweepInterrupted, load_spec, run
    from washer.sweep.execute import SchedulerError, check_address
    if args.workers is not None and args.workers < 1 or \
            args.batch_size is not None and args.batch_size < 1:
        print("error: --workers and --batch-size must be >= 1", file=sys.stderr)
        return 2
    out = args.out or Path("out/sweep") / args.spec.name.removesuffix(".toml")
    try:
        spec = load_spec(args.spec)
        if args.scheduler:
            check_address(args.scheduler)
        check_folder(out)
    except (SpecError, OutputError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except SchedulerError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_SCHEDULER
    # What the sweep says on the way (the dashboard's address, a replaced spec) is one
    # plain line each on stderr.
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(message)s"))
    logger = logging.getLogger("washer.sweep")
    logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("always", SpecChangedWarning)
            # Said when it happens (before the computation), one line each.
            warnings.showwarning = lambda message, *a, **k: print(f"warning: {message}",
                                                                  file=sys.stderr)
            df = run(spec, args.scheduler, out=out, serial=args.serial,
                     n_workers=args.workers, batch_size=args.batch_size,
                     progress=args.progress, plot=not args.no_plot,
                     retry_failed=args.retry_failed, allow_large=args.allow_large)
    except SweepInterrupted as exc:
        print(f"\n{exc}", file=sys.stderr)
        return 130
    except KeyboardInterrupt:
        # After the last point (while the table is consolidated or the maps drawn): the
        # parts are complete, a re-run only rebuilds the table.
        print(f"\ninterrupted: the finished points are kept in {out / 'parts'} (re-run the "
              "same command to write the table and maps)", file=sys.stderr)
        return 130
    except (SizeError, OutputError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except SchedulerError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_SCHEDULER
    except LockedError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_LOCKED
    finally:
        logger.removeHandler(handler)
    failed = df[df["status"] != "ok"]
    print(f"{len(df)} points ({len(failed)} failed) in {time.perf_counter() - t0:.1f} s; "
          f"table {out / 'results.parquet'}, maps in {out / 'plots'}")
    if "crit_status" in df:
        counts = df["crit_status"].value_counts()
        print("  critical: " + ", ".join(f"{n} {k}" for k, n in counts.items())
              + " (stable: stable over the whole search range)")
    for _, r in failed.head(5).iterrows():
        print(f"  failed {r['study']}[{r['index']}] {r['id']}: {r['error']}")
    if len(failed) > 5:
        print(f"  ... and {len(failed) - 5} more (column 'error' of the table)")
    return 1 if len(failed) else 0


def _plot(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="python -m washer.sweep plot",
                                 description="Draw the maps of a sweep's results folder.")
    ap.add_argument("folder", type=Path)
    ap.add_argument("--no-hopf", action="store_true",
                    help="skip the continuation's Hopf curve overlay")
    args = ap.parse_args(argv)
    if not (args.folder / "results.parquet").exists():
        print(f"error: {args.folder}: no results.parquet (run a sweep there first)",
              file=sys.stderr)
        return 2
    from washer.sweep.plots import plot_dir
    for p in plot_dir(args.folder, hopf=not args.no_hopf):
        print(f"wrote {p}")
    return 0
