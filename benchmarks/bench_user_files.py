"""What a compiled AUTO user file costs per call and per point, against the Python user
file of the same equations and the washer's own kernel path.

    python benchmarks/bench_user_files.py [--repeat N]

Cases: AUTO's `ab` demo (tests/data/auto_demos/ab/ab.f90, compiled through
washer.cont.user_problem.user_files_native) and its Python transcription
(tests/data/ab_demo/ab.py), both
through Problem.func_many on k points (k = 1: the fixed cost of one call; k = 1000: the
per-point cost of a batch, as the engine's stencils and collocation points call it);
the washer's built-in problem (e='washer', NDIM 12, the C++ kernel through cffi) the same
way. Then one whole run: lrz's first periodic family (lrz.auto, NTST 20) from the
Fortran file and from the Python file, in the same process. Minimum of --repeat timings.
"""
from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
DATA = ROOT / "tests" / "data"


def best(fn, repeat: int, inner: int) -> float:
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        out.append((time.perf_counter() - t0) / inner)
    return min(out)


def per_call(problem, ndim: int, npar: int, repeat: int) -> tuple[float, float]:
    rng = np.random.default_rng(0)
    par = np.zeros(npar)
    par[:3] = [0.1, 14.0, 2.0]
    if problem.name.startswith("washer"):
        _, par = problem.start(npar)
    u1 = rng.normal(0, 0.01, (1, ndim))
    uk = rng.normal(0, 0.01, (1000, ndim))
    one = best(lambda: problem.func_many(u1, par), repeat, 2000)
    many = best(lambda: problem.func_many(uk, par), repeat, 20)
    return one, many / 1000


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    from washer.cont.user_problem.user_files_native import load_compiled_problem
    from washer.cont.user_problem.user_files import load_python_problem
    from washer.problems.washer import washer_problem
    cases = [("ab.f90 (compiled)", load_compiled_problem(DATA / "auto_demos" / "ab" / "ab.f90", 2),
              2, 36),
             ("ab.py (Python)", load_python_problem("ab", DATA / "ab_demo", 2), 2, 36),
             ("washer (C++ kernel)", washer_problem("washer"), 12, 36)]
    print(f"{'problem':<22}{'1 point / call':>16}{'per point, k=1000':>20}")
    for name, p, ndim, npar in cases:
        one, each = per_call(p, ndim, npar, args.repeat)
        print(f"{name:<22}{one * 1e6:>13.2f} us{each * 1e9:>17.1f} ns")

    # A whole periodic-orbit run from either user file (lrz.auto's first family).
    from washer.run import run
    times = {}
    for src in (DATA / "auto_demos" / "lrz" / "lrz.f90", DATA / "lrz" / "lrz.py"):
        with tempfile.TemporaryDirectory() as tmp:
            shutil.copy(src, Path(tmp) / src.name)
            shutil.copy(DATA / "auto_demos" / "lrz" / "c.lrz", Path(tmp) / "c.lrz")
            run(Path(tmp) / "c.lrz", verbose=False, sv="eq", e="lrz")
            common = dict(IPS=2, ICP=["rho", "PERIOD"], NMX=35, NPR=2, DS=0.5, IRS="HB1",
                          s="eq", e="lrz", verbose=False)
            t = []
            for _ in range(max(1, args.repeat // 2)):
                t0 = time.perf_counter()
                run(Path(tmp) / "c.lrz", sv="po", **common)
                t.append(time.perf_counter() - t0)
            times[src.suffix] = min(t)
    print(f"lrz periodic family (35 points): lrz.f90 {times['.f90']:.3f} s, lrz.py "
          f"{times['.py']:.3f} s (ratio py/f90 {times['.py'] / times['.f90']:.2f})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
