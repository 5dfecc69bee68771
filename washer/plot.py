"""Bifurcation diagram of a b-file: `python -m washer.plot b.NAME [--x 0] [--y 1] [--out STEM]`.

Columns are those of the b-file rows: 0 = PAR(ICP(1)), 1 = L2-norm, 2.. = U(i), then the
other ICP parameters (-1 = the last one, e.g. the second parameter of a Hopf curve).
Writes STEM.png and STEM.pdf (default: b.NAME_diagram).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m washer.plot", description=__doc__.split("\n")[0])
    ap.add_argument("bfile", type=Path)
    ap.add_argument("--x", type=int, default=0, help="column on the x axis (default 0)")
    ap.add_argument("--y", type=int, default=1, help="column on the y axis (default 1)")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args(argv)
    if not args.bfile.exists():
        print(f"error: {args.bfile}: no such file", file=sys.stderr)
        return 2
    import matplotlib
    matplotlib.use("Agg")
    from washer.plots.diagrams import save_diagram
    for p in save_diagram(args.bfile, args.out, args.x, args.y):
        print(f"wrote {p}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
