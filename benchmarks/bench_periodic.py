"""Periodic-orbit continuation speed (IPS = 2), against AUTO-07p's own run times.

    python benchmarks/bench_periodic.py [--quick]

Cases, each with the demo's constants unchanged and the script's overrides:
* lrz: the family from HB1 (NTST 35, 35 points, out to the homoclinic orbit);
* chu: the family from HB1 (NTST 25, 100 points, a period doubling);
* ab: the seven families from every HB of the six p1-branches (NTST 70, to p1 = 0.25 or
  PERIOD = 1000);
* washer: the whirl from the averaged Hopf point to C_p = 0 (auto_constants/c.washer.po,
  NDIM 12, NTST 30) (skipped with --quick).
For each: points per second of the run (best of 2, files written, as AUTO's times
include its files), and from one profiled run the share of the time spent in the
linear solver (SuperLU factorisations and solves) and in the right-hand side (the
user's func or the washer kernel, Jacobians included). AUTO-07p's times are the
"Total Time" lines of the reference run logs (tests/data/auto_reference/periodic/*/
run.log), its point counts the rows of its b-files.
"""
from __future__ import annotations

import cProfile
import os
import pstats
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
REF = ROOT / "tests" / "data" / "auto_reference" / "periodic"
EQ = {"lrz": ROOT / "tests/data/lrz/lrz.py", "chu": ROOT / "tests/data/chu/chu.py",
      "ab": ROOT / "tests/data/ab_demo/ab.py"}
#: AUTO-07p (run.log "Total Time", b-file rows): seconds, points.
AUTO = {"lrz": (3.06, 35), "chu": (3.98, 100),
        "ab": (0.0922 + 0.127 + 0.168 + 0.0779 + 0.200 + 0.0749 + 0.252,
               161 + 222 + 309 + 116 + 349 + 67 + 372)}

#: Profile entries counted as linear solver / right-hand side (substrings of names).
LINEAR = ("gstrf", "of 'SuperLU' objects")
RHS_FILES = ("lrz.py", "chu.py", "ab.py")
RHS_NAMES = ("washer_rhs_rot_batch", "washer_jac_rot_batch", "washer_rhs_rot",
             "washer_jac_rot")


def _setup(d: Path) -> None:
    for demo in ("lrz", "chu", "ab"):
        for f in REF.joinpath(demo).glob("c.*"):
            shutil.copy(f, d / f.name)
        shutil.copy(EQ[demo], d / f"{demo}.py")
    for f in ("c.washer", "c.washer.po"):
        shutil.copy(ROOT / "auto_constants" / f, d / f)


def _prepare(d: Path, quick: bool) -> dict:
    """Equilibrium runs the periodic cases restart from; returns case -> callable."""
    from washer.run import run
    run(d / "c.lrz", verbose=False, e="lrz", sv="lrz")
    run(d / "c.chu", verbose=False, e="chu", sv="chu")
    start = run(d / "c.ab.1", verbose=False, e="ab", sv="abstart")
    ab_runs = []
    for s in start.specials:
        eq = run(d / "c.ab.2", verbose=False, e="ab", s="abstart", IRS=s.lab, sv=f"abeq{s.lab}")
        ab_runs += [(f"abeq{s.lab}", h.lab) for h in eq.specials if h.ty == "HB"]
    cases = {
        "lrz": lambda: [run(d / "c.lrz", verbose=False, e="lrz", s="lrz", sv="polrz", IRS="HB1",
                            IPS=2, ICP=["rho", "PERIOD"], NMX=35, NPR=2, DS=0.5)],
        "chu": lambda: [run(d / "c.chu", verbose=False, e="chu", s="chu", sv="pochu",
                            IRS="HB1", IPS=2, ICP=[1, 11])],
        "ab": lambda: [run(d / "c.ab.3", verbose=False, e="ab", s=s, IRS=lab, sv=f"poab{lab}")
                       for s, lab in ab_runs],
    }
    if not quick:
        run(d / "c.washer", verbose=False)
        cases["washer"] = lambda: [run(d / "c.washer.po", verbose=False)]
    return cases


def _shares(fn) -> tuple[float, float, float]:
    pr = cProfile.Profile()
    t0 = time.perf_counter()
    pr.enable()
    fn()
    pr.disable()
    wall = time.perf_counter() - t0
    lin = rhs = 0.0
    for (path, _, name), (_, _, tt, _ct, _) in pstats.Stats(pr).stats.items():
        if any(k in name for k in LINEAR):
            lin += tt
        elif (name == "func" and path.endswith(RHS_FILES)) or any(k in name for k in RHS_NAMES):
            rhs += tt
    return wall, lin / wall, rhs / wall


def main(argv=None) -> int:
    quick = "--quick" in (argv if argv is not None else sys.argv[1:])
    d = Path(tempfile.mkdtemp(prefix="bench_periodic_"))
    _setup(d)
    cwd = os.getcwd()
    os.chdir(d)
    try:
        cases = _prepare(d, quick)
        print(f"{'case':8} {'points':>7} {'wall s':>8} {'pts/s':>8} {'linear':>7} {'rhs':>6}"
              f" {'AUTO pts/s':>11}")
        for name, fn in cases.items():
            best, npts = float("inf"), 0
            for _ in range(2):
                t0 = time.perf_counter()
                res = fn()
                best = min(best, time.perf_counter() - t0)
                npts = sum(len(r.rows) for r in res)
                assert all(r.status == "ok" for r in res), [r.status for r in res]
            _, lin, rhs = _shares(fn)
            auto = AUTO.get(name)
            auto_txt = f"{auto[1] / auto[0]:11.0f}" if auto else f"{'-':>11}"
            print(f"{name:8} {npts:7d} {best:8.2f} {npts / best:8.1f} {lin:7.0%} {rhs:6.0%}"
                  f" {auto_txt}")
    finally:
        os.chdir(cwd)
        shutil.rmtree(d, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
