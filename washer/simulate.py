"""Time responses of the washer from the command line.

    python -m washer.simulate fig10 fig11        # the paper's non-autonomous spin-ups
    python -m washer.simulate fig8 fig9 --out out/sim

Each run writes NAME.npz (t, y, metadata as JSON), NAME.csv and PNG plots
(`washer.machine.responses` integrates, `washer.paper.setups` holds the setups).
A run that fails half-way (kernel error) keeps and writes what it computed.
Every argument is checked before any work (one line naming it, exit status 2);
Ctrl-C stops at once (exit 130) and leaves every file whole.
"""
from __future__ import annotations

import argparse
import math
import sys
import warnings
from pathlib import Path

from washer.atomic import OutputError, check_folder
from washer.paper.setups import SETUPS, run_setup


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m washer.simulate",
                                 description="Time responses of the washer model (paper section 3.2).")
    ap.add_argument("setups", nargs="+", choices=sorted(SETUPS) + ["all"],
                    help="paper setups to run (all = fig8 fig9 fig10 fig11)")
    ap.add_argument("--params", type=Path, default=None, help="TOML parameter file "
                    "(default: the shipped reference set)")
    ap.add_argument("--out", type=Path, default=Path("out/simulate"), help="output folder")
    ap.add_argument("--Cp", type=float, default=None, help="override the setup's C_p (N m s/rad)")
    ap.add_argument("--Omega", type=float, default=None, help="override Omega (Hz)")
    ap.add_argument("--t-end", type=float, default=None, help="override the duration (s)")
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--method", choices=["kernel", "scipy"], default="kernel")
    ap.add_argument("--allow-large", action="store_true",
                    help="run a response whose estimated memory or time is far above the usual")
    args = ap.parse_args(argv)
    # Warnings (a unit slip, a constant without effect) as one plain line each.
    warnings.formatwarning = lambda message, category, *a, **k: f"warning: {message}\n"
    names = sorted(SETUPS) if "all" in args.setups else list(dict.fromkeys(args.setups))
    try:
        params = _check_arguments(args, names)
    except ArgumentError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2

    import matplotlib
    matplotlib.use("Agg")
    rc = 0
    try:
        for name in names:
            r, paths = run_setup(name, params, args.out, C_p=args.Cp, Omega=args.Omega,
                                 t_end=args.t_end, rtol=args.rtol, method=args.method,
                                 allow_large=args.allow_large)
            s = r.stats
            t_last = f"{r.t[-1]:g}" if len(r.t) else "0"
            print(f"{name}: {r.system}/{r.mode}, t = 0..{t_last} s, {s['nfev']} evaluations, "
                  f"{s['naccept']} steps, {r.wall:.2f} s wall; {r.status}")
            for p in paths:
                print(f"  wrote {p}")
            if r.status != "ok":
                rc = 1
    except KeyboardInterrupt:
        # Files are replaced whole (washer.atomic): what is on disk is complete.
        print("\ninterrupted; the files written before are complete, the run in progress "
              "wrote nothing", file=sys.stderr)
        return 130
    except OutputError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    return rc


class ArgumentError(ValueError):
    """A command-line argument no run can use; the message names it."""


def _check_arguments(args, names: list[str]):
    """Every argument checked before any work: the parameter file, the overrides (as
    the parameter set would refuse them), the duration, the tolerance, the size and
    the output folder. Returns the parameters."""
    from washer.machine.params import ParameterError, load_params
    from washer.machine.responses import response_size_check
    from washer.sizes import SizeError
    try:
        params = load_params(args.params)
    except ParameterError as exc:
        raise ArgumentError(str(exc)) from None
    for flag, key, value in (("--Cp", "C_p", args.Cp), ("--Omega", "Omega", args.Omega)):
        if value is None:
            continue
        if not math.isfinite(value):
            raise ArgumentError(f"{flag} {value}: expected a finite number")
        try:
            params.replace(**{key: value})
        except ParameterError as exc:
            raise ArgumentError(f"{flag} {value}: {str(exc).split(': ', 1)[-1]}") from None
    if args.t_end is not None and not (math.isfinite(args.t_end) and args.t_end > 0):
        raise ArgumentError(f"--t-end {args.t_end}: expected a finite positive duration (s)")
    if not (math.isfinite(args.rtol) and 0 < args.rtol < 1):
        raise ArgumentError(f"--rtol {args.rtol}: expected a relative tolerance in (0, 1)")
    for name in names:
        setup = SETUPS[name]
        t_end = args.t_end if args.t_end is not None else setup["t_end"]
        try:
            response_size_check(t_end, None, setup["system"], args.rtol,
                                allow=args.allow_large)
        except SizeError as exc:
            raise ArgumentError(f"{name}: {exc}") from None
    try:
        check_folder(args.out)
    except OutputError as exc:
        raise ArgumentError(f"--out {exc}") from None
    return params


if __name__ == "__main__":
    raise SystemExit(main())
