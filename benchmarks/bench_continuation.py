"""Continuation speed: steps per second on AUTO's `ab` demo and on the washer
(one-parameter branch in C_p and the Hopf curve in (C_p, Omega)), with the share
of time spent evaluating the equations (the kernel for the washer).

    python benchmarks/bench_continuation.py
"""
import shutil
import tempfile
import time
from pathlib import Path

import washer.run as runmod
from washer.cont.problem import Problem

ROOT = Path(__file__).resolve().parent.parent
timer = {"t": 0.0}


def timed(fn):
    def wrapper(*a, **k):
        t0 = time.perf_counter()
        try:
            return fn(*a, **k)
        finally:
            timer["t"] += time.perf_counter() - t0
    return wrapper


_orig_init = Problem.__init__


def _timed_init(self, ndim, func, stpnt=None, dfdu=None, dfdp=None, **kw):
    _orig_init(self, ndim, timed(func), stpnt, dfdu and timed(dfdu), dfdp and timed(dfdp), **kw)


Problem.__init__ = _timed_init


def bench(label, constants, **overrides):
    timer["t"] = 0.0
    t0 = time.perf_counter()
    res = runmod.run(constants, verbose=False, **overrides)
    wall = time.perf_counter() - t0
    steps = len(res.rows)
    print(f"{label:38s} {steps:5d} points {wall:7.3f} s  {steps / wall:8.1f} points/s  "
          f"equations {100 * timer['t'] / wall:5.1f} %")
    return wall


def main():
    d = Path(tempfile.mkdtemp())
    for f in ("ab.py", "c.ab"):
        shutil.copy(ROOT / "tests" / "data" / "ab" / f, d)
    for f in ("c.washer", "c.washer.hopf.Omega"):
        shutil.copy(ROOT / "auto_constants" / f, d)
    bench("ab: equilibria in p1 (JAC=0)", d / "c.ab", sv="eq")
    bench("ab: Hopf curve from HB1", d / "c.ab", IRS="HB1", ICP=[1, 2], ISW=2, s="eq",
          sv="hb", UZSTOP={1: [0.0, 0.3], 2: [5.0, 30.0]}, PAR={})
    w1 = bench("washer: branch in C_p (Fig 3)", d / "c.washer")
    w2 = bench("washer: Hopf curve in (C_p, Omega)", d / "c.washer.hopf.Omega")
    print(f"washer branch + Hopf curve: {w1 + w2:.2f} s")


if __name__ == "__main__":
    main()
