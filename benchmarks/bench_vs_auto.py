"""Continuation speed per point, washer against AUTO-07p run in the same benchmark run.

    python benchmarks/bench_vs_auto.py [--quick] [--repeat N] [--only NAME,...] [--against REV]

Every case runs its chain of runs on AUTO-07p (installed `auto-07p`, one OpenMP thread,
the demos' Fortran sources in tests/data/auto_demos/) and on washer, with the same
constants files and the same overrides; how each side is timed is in
benchmarks/side_by_side.py (AUTO: its "Total Time" per run; washer: the run() call,
files written; points: the rows of each side's b-file; minimum of N back-to-back
repetitions). Without `auto-07p` the AUTO columns are skipped with a message.
--against REV adds a column for the washer of git revision REV (a temporary worktree),
measured in the same repetitions: before/after figures of a change.

Cases (demo constants unchanged; overrides as in the AUTO scripts of
tests/data/auto_reference):
  ab_eq       ab equilibria in PAR(1) (ab2p's first run), 107 points
  ab_hopf     the Hopf curve from HB1 in (PAR(1), PAR(2)) (ab2p's hb_fwd)
  lrz_eq      lrz equilibria in rho
  lrz_hopf    the Hopf curve of lrz in (rho, sigma) (lrz2p's hb_fwd)
  lrz_po35    lrz periodic orbits from HB1, NTST 35 (lrz.auto's first family)
  lrz_po200   the same at NTST 200
  chu_po      chu periodic orbits from HB1 (NTST 25, a period doubling)
  ab_po       ab's seven periodic families from every HB of the p1-branches (ab.auto)
  lrz_eq_sympy, lrz_po35_sympy   lrz_eq and lrz_po35 with washer's lrz given as sympy
              expressions (tests/data/lrz_sym: generated C, exact f_u and f_p, JAC = 1)
washer-only (no AUTO column; skipped with --quick):
  washer_fig3     the equilibrium branch in C_p (c.washer, NDIM 12)
  washer_fig4     its Hopf curve in (C_p, Omega) (c.washer.hopf.Omega)
  washer_whirl    the whirl's periodic orbits (c.washer.po, NDIM 12, NTST 30)
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from side_by_side import DEMOS, ROOT, Case, Step, compare, report  # noqa: E402

DATA = ROOT / "tests" / "data"
REF = DATA / "auto_reference"
AB2 = dict(ICP=[1, 2], ISW=2, NMX=400, DSMAX=0.05, UZSTOP={1: [0.0, 0.3], 2: [5.0, 30.0]})
LRZ2 = dict(ICP=["rho", "sigma"], ISW=2, NMX=300, DS=0.1, DSMAX=2.0,
            UZR={"sigma": [5.0, 10.0, 20.0]}, UZSTOP={"sigma": [4.0, 40.0], "rho": 200.0})
LRZ_PO = dict(IPS=2, ICP=["rho", "PERIOD"], NMX=35, NPR=2, DS=0.5)

AB_FILES = [(DATA / "ab" / "ab.py", "ab.py"), (DATA / "ab" / "c.ab", "c.ab"),
            (DEMOS / "ab" / "ab.f90", "ab.f90")]
LRZ_FILES = [(DATA / "lrz" / "lrz.py", "lrz.py"), (DATA / "lrz" / "c.lrz", "c.lrz"),
             (DEMOS / "lrz" / "lrz.f90", "lrz.f90")]
CHU_FILES = [(DATA / "chu" / "chu.py", "chu.py"), (REF / "periodic" / "chu" / "c.chu", "c.chu"),
             (DEMOS / "chu" / "chu.f90", "chu.f90")]
ABPO_FILES = [(DATA / "ab_demo" / "ab.py", "ab.py"), (DEMOS / "ab" / "ab.f90", "ab.f90")] + [
    (REF / "periodic" / "ab" / f"c.ab.{k}", f"c.ab.{k}") for k in (1, 2, 3)]
WASHER_FILES = [(ROOT / "auto_constants" / f, f)
                for f in ("c.washer", "c.washer.hopf.Omega", "c.washer.po")]

CASES = [
    Case("ab_eq", [Step("eq", "ab", "ab")], AB_FILES),
    Case("ab_hopf", [Step("eq", "ab", "ab", timed=False),
                     Step("hb", "ab", "ab", start="eq", irs="HB1", ov=AB2)], AB_FILES),
    Case("lrz_eq", [Step("eq", "lrz", "lrz")], LRZ_FILES),
    Case("lrz_hopf", [Step("eq", "lrz", "lrz", timed=False),
                      Step("hb", "lrz", "lrz", start="eq", irs="HB1", ov=LRZ2)], LRZ_FILES),
    Case("lrz_po35", [Step("eq", "lrz", "lrz", timed=False),
                      Step("po", "lrz", "lrz", start="eq", irs="HB1", ov=LRZ_PO)], LRZ_FILES),
    Case("lrz_po200", [Step("eq", "lrz", "lrz", timed=False),
                       Step("po", "lrz", "lrz", start="eq", irs="HB1",
                            ov=dict(LRZ_PO, NTST=200))], LRZ_FILES),
    Case("chu_po", [Step("eq", "chu", "chu", timed=False),
                    Step("po", "chu", "chu", start="eq", irs="HB1", ov=dict(IPS=2, ICP=[1, 11]))],
         CHU_FILES),
    Case("ab_po", [Step("start", "ab.1", "ab", timed=False),
                   Step("eq", "ab.2", "ab", start="start", each="*", timed=False),
                   Step("po", "ab.3", "ab", start="eq_", each="HB")], ABPO_FILES),
]
SYM = [(DATA / "lrz_sym" / "lrz.py", "lrz.py"), (DATA / "lrz_sym" / "c.lrz", "c.lrz")]
CASES += [
    # washer with the Lorenz equations as sympy expressions, compiled, exact f_u and f_p
    # (JAC = 1); AUTO with its Fortran file and JAC = 0 as in lrz_eq / lrz_po35
    Case("lrz_eq_sympy", [Step("eq", "lrz", "lrz")], LRZ_FILES, washer_files=SYM),
    Case("lrz_po35_sympy", [Step("eq", "lrz", "lrz", timed=False),
                            Step("po", "lrz", "lrz", start="eq", irs="HB1", ov=LRZ_PO)],
         LRZ_FILES, washer_files=SYM),
]
WASHER_CASES = [
    Case("washer_fig3", [Step("washer", "washer", "washer")], WASHER_FILES, auto=False),
    Case("washer_fig4", [Step("washer", "washer", "washer", timed=False),
                         Step("hopf", "washer.hopf.Omega", "washer", start="washer", irs="HB1")],
         WASHER_FILES, auto=False),
    Case("washer_whirl", [Step("washer", "washer", "washer", timed=False),
                          Step("po", "washer.po", "washer", start="washer", irs="HB1")],
         WASHER_FILES, auto=False),
]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="skip the washer-only cases")
    ap.add_argument("--repeat", type=int, default=3, help="back-to-back repetitions (min counts)")
    ap.add_argument("--only", default="", help="comma-separated case names")
    ap.add_argument("--against", default=None, help="git revision of a washer to compare with")
    a = ap.parse_args(argv)
    cases = CASES + ([] if a.quick else WASHER_CASES)
    if a.only:
        names = a.only.split(",")
        unknown = set(names) - {c.name for c in CASES + WASHER_CASES}
        if unknown:
            ap.error(f"unknown case(s) {sorted(unknown)}")
        cases = [c for c in CASES + WASHER_CASES if c.name in names]
    rows = compare(cases, repeat=a.repeat, against=a.against)
    print(report(rows, a.against))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
