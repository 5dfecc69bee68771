"""Time responses of the washer from the command line.

    python -m washer.simulate fig10 fig11        # the paper's non-autonomous spin-ups
    python -m washer.simulate fig8 fig9 --out out/sim

Each run writes NAME.npz (t, y, metadata as JSON), NAME.csv and PNG plots
(`washer.machine.responses` integrates, `washer.paper.setups` holds the setups).
A run that fails half-way (kernel error) keeps and writes what it computed.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

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
    args = ap.parse_args(argv)

    import matplotlib
    matplotlib.use("Agg")
    from washer.machine.params import ParameterError, load_params
    try:
        params = load_params(args.params)
    except ParameterError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    names = sorted(SETUPS) if "all" in args.setups else args.setups
    rc = 0
    for name in names:
        r, paths = run_setup(name, params, args.out, C_p=args.Cp, Omega=args.Omega,
                             t_end=args.t_end, rtol=args.rtol, method=args.method)
        s = r.stats
        print(f"{name}: {r.system}/{r.mode}, t = 0..{r.t[-1]:g} s, {s['nfev']} evaluations, "
              f"{s['naccept']} steps, {r.wall:.2f} s wall; {r.status}")
        for p in paths:
            print(f"  wrote {p}")
        if r.status != "ok":
            rc = 1
    return rc


if __name__ == "__main__":
    raise SystemExit(main())
