"""Bifurcation diagrams and periodic orbits from AUTO files.

    python -m washer.plots b.NAME [b.OTHER ...] [--x rho] [--y L2-NORM] [--out STEM]
    python -m washer.plots s.NAME --label 8 [--components 1 2 3] [--phase 1 2] [--out STEM]

b-files: --x and --y name columns as the b-file's header does: a parameter by its parnames
name or PAR(i), a state by its unames name or U(i) ('MAX x' or 'MAX U(1)' for periodic
orbits), L2-NORM, PERIOD; or by position (0 = PAR(ICP(1)), 1 = the norm, -1 the last).
Several b-files go on one axes, one colour and legend entry each; stable parts solid,
unstable dashed; HB, LP, BP, PD, TR, UZ marked with their labels. Writes STEM.png and
STEM.pdf (default: b.NAME_diagram).
s-files: the periodic solution with label --label: its components against time and a
phase portrait (default: s.NAME_orbitLABEL).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path


def main(argv: list[str] | None = None) -> int:
    from washer.atomic import OutputError
    try:
        return _main(argv)
    except OutputError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130


def _main(argv: list[str] | None) -> int:
    ap = argparse.ArgumentParser(prog="python -m washer.plots",
                                 description="Bifurcation diagrams (b-files) and periodic "
                                             "orbits (s-files, --label)")
    ap.add_argument("files", type=Path, nargs="+", metavar="FILE")
    ap.add_argument("--x", default="0", help="column on the x axis: a name (parnames, "
                    "unames, PAR(i), U(i), 'MAX x', L2-NORM, PERIOD) or a position "
                    "(default 0, the first continuation parameter)")
    ap.add_argument("--y", default="1", help="column on the y axis (default 1, the norm)")
    ap.add_argument("--label", type=int, default=None,
                    help="s-file: the label of the periodic solution to draw")
    ap.add_argument("--components", type=int, nargs="+", default=None,
                    help="s-file: components U(i) against time (default: the first 6)")
    ap.add_argument("--phase", type=int, nargs=2, default=(1, 2),
                    help="s-file: components of the phase portrait (default 1 2)")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args(argv)
    from washer.auto.files import s_file           # s.NAME may be kept as s.NAME.gz
    for f in args.files:
        if not (s_file(f) if f.name.startswith("s.") else f).exists():
            print(f"error: {f}: no such file", file=sys.stderr)
            return 2
    import matplotlib
    matplotlib.use("Agg")
    if args.label is not None or args.files[0].name.startswith("s."):
        if args.label is None or len(args.files) != 1:
            print("error: an s-file takes one file and --label N (the periodic solution)",
                  file=sys.stderr)
            return 2
        from washer.plots.orbits import save_orbit
        try:
            written = save_orbit(args.files[0], args.label, args.out, args.components,
                                 tuple(args.phase))
        except (KeyError, ValueError, IndexError) as exc:
            print(f"error: {args.files[0]}: {exc}", file=sys.stderr)
            return 2
    else:
        from washer.plots.diagrams import save_diagram
        try:
            written = save_diagram(args.files, args.out, args.x, args.y)
        except KeyError as exc:
            print(f"error: {exc.args[0]}", file=sys.stderr)
            return 2
    for p in written:
        print(f"wrote {p}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
