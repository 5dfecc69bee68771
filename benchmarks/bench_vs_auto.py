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
  ab_fold     the fold curve from LP1 in (PAR(1), PAR(2)) (ab2p's lp_fwd)
  lrz_eq      lrz equilibria in rho
  lrz_hopf    the Hopf curve of lrz in (rho, sigma) (lrz2p's hb_fwd)
  lrz_po35    lrz periodic orbits from HB1, NTST 35 (lrz.auto's first family)
  lrz_po200   the same at NTST 200
  chu_po      chu periodic orbits from HB1 (NTST 25, a period doubling)
  ab_po       ab's seven periodic families from every HB of the p1-branches (ab.auto)
  ab_eq_f90, lrz_eq_f90   ab_eq and lrz_eq with AUTO's Fortran user files on both sides
              (washer compiles ab.f90 / lrz.f90: the corrector of equilibria in one
              foreign call per point, washer.cont.corrector_algebraic)
  ab_hopf_f90, ab_fold_f90, lrz_hopf_f90   the loci the same way (the compiled
              corrector of the fold and Hopf systems calling FUNC directly)
  lrz_po35_f90, chu_po_f90   lrz_po35 and chu_po the same way (the corrector of
              periodic orbits calling FUNC directly, washer.cont.corrector_periodic)
  lrz_eq_sympy, lrz_po35_sympy   lrz_eq and lrz_po35 with washer's lrz given as sympy
              expressions (tests/data/lrz_sym: generated C, exact f_u and f_p, JAC = 1)
the washer's own model (skipped with --quick), AUTO-07p running the same compiled
equations: washer.problems.auto07p builds AUTO's C user file washer.c, whose FUNC calls
the washer kernel's washer_rhs_rot / washer_jac_rot (analytic f_u and f_p, JAC = 1 on
both sides), linked into washer.exe once per benchmark run (the kernel's objects cached
in ~/.cache/washer/auto07p); both sides read the same constants files auto_constants/
c.washer* (NTST, DS, DSMAX, EPS*, NMX, THU, UZSTOP unchanged):
  washer_fig3     the equilibrium branch in C_p from 0 to the UZ at 0.5 (c.washer, NDIM 12)
  washer_fig4     its Hopf curve from HB1 in (C_p, Omega) to the UZ at Omega = 15 Hz
                  (c.washer.hopf.Omega; AUTO's rows include the GH points it locates)
  washer_fig4_isp0  the same with ISP = 0 on both sides: no test functions (no first
                  Lyapunov coefficient, no GH location), the continuation alone
  washer_whirl    the whirl's periodic orbits from HB1 to C_p = 0 (c.washer.po, NTST 30)
The ratio to read for the washer is us per point on the same stretch of curve: point
counts differ a little (step control, located special points).
"""
from __future__ import annotations

import argparse
import dataclasses
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from side_by_side import DEMOS, ROOT, Case, Step, compare, report  # noqa: E402

if str(ROOT) not in sys.path:          # washer.problems.auto07p builds AUTO's washer.exe
    sys.path.insert(0, str(ROOT))

DATA = ROOT / "tests" / "data"
REF = DATA / "auto_reference"
# the loci of ab2p.auto and lrz2p.auto as the tests define them (tests/auto_reference.py)
sys.path.insert(0, str(ROOT / "tests"))
from auto_reference import AB2P_LOCUS as AB2, LRZ2P_LOCUS as LRZ2  # noqa: E402
LRZ_PO = dict(IPS=2, ICP=["rho", "PERIOD"], NMX=35, NPR=2, DS=0.5)

AB_FILES = [(DATA / "ab" / "ab.py", "ab.py"), (DATA / "ab" / "c.ab", "c.ab"),
            (DEMOS / "ab" / "ab.f90", "ab.f90")]
LRZ_FILES = [(DATA / "lrz" / "lrz.py", "lrz.py"), (DATA / "lrz" / "c.lrz", "c.lrz"),
             (DEMOS / "lrz" / "lrz.f90", "lrz.f90")]
CHU_FILES = [(DATA / "chu" / "chu.py", "chu.py"), (DEMOS / "chu" / "c.chu", "c.chu"),
             (DEMOS / "chu" / "chu.f90", "chu.f90")]
ABPO_FILES = [(DATA / "ab_demo" / "ab.py", "ab.py"), (DEMOS / "ab" / "ab.f90", "ab.f90")] + [
    (DEMOS / "ab" / f"c.ab.{k}", f"c.ab.{k}") for k in (1, 2, 3)]
WASHER_FILES = [(ROOT / "auto_constants" / f, f)
                for f in ("c.washer", "c.washer.hopf.Omega", "c.washer.po")]

CASES = [
    Case("ab_eq", [Step("eq", "ab", "ab")], AB_FILES),
    Case("ab_hopf", [Step("eq", "ab", "ab", timed=False),
                     Step("hb", "ab", "ab", start="eq", irs="HB1", ov=AB2)], AB_FILES),
    Case("ab_fold", [Step("eq", "ab", "ab", timed=False),
                     Step("lp", "ab", "ab", start="eq", irs="LP1", ov=AB2)], AB_FILES),
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
AB_F90 = [(DATA / "ab" / "c.ab", "c.ab"), (DEMOS / "ab" / "ab.f90", "ab.f90")]
LRZ_F90 = [(DATA / "lrz" / "c.lrz", "c.lrz"), (DEMOS / "lrz" / "lrz.f90", "lrz.f90")]
CHU_F90 = [(DEMOS / "chu" / "c.chu", "c.chu"), (DEMOS / "chu" / "chu.f90", "chu.f90")]
CASES += [
    # the same equilibria from the Fortran user files alone (no NAME.py beside them)
    Case("ab_eq_f90", [Step("eq", "ab", "ab")], AB_F90),
    Case("lrz_eq_f90", [Step("eq", "lrz", "lrz")], LRZ_F90),
    Case("ab_hopf_f90", [Step("eq", "ab", "ab", timed=False),
                         Step("hb", "ab", "ab", start="eq", irs="HB1", ov=AB2)], AB_F90),
    Case("ab_fold_f90", [Step("eq", "ab", "ab", timed=False),
                         Step("lp", "ab", "ab", start="eq", irs="LP1", ov=AB2)], AB_F90),
    Case("lrz_hopf_f90", [Step("eq", "lrz", "lrz", timed=False),
                          Step("hb", "lrz", "lrz", start="eq", irs="HB1", ov=LRZ2)], LRZ_F90),
    Case("lrz_po35_f90", [Step("eq", "lrz", "lrz", timed=False),
                          Step("po", "lrz", "lrz", start="eq", irs="HB1", ov=LRZ_PO)], LRZ_F90),
    Case("chu_po_f90", [Step("eq", "chu", "chu", timed=False),
                        Step("po", "chu", "chu", start="eq", irs="HB1",
                             ov=dict(IPS=2, ICP=[1, 11]))], CHU_F90),
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
    Case("washer_fig3", [Step("washer", "washer", "washer")], WASHER_FILES),
    Case("washer_fig4", [Step("washer", "washer", "washer", timed=False),
                         Step("hopf", "washer.hopf.Omega", "washer", start="washer", irs="HB1")],
         WASHER_FILES),
    Case("washer_fig4_isp0", [Step("washer", "washer", "washer", timed=False),
                              Step("hopf", "washer.hopf.Omega", "washer", start="washer",
                                   irs="HB1", ov=dict(ISP=0))], WASHER_FILES),
    Case("washer_whirl", [Step("washer", "washer", "washer", timed=False),
                          Step("po", "washer.po", "washer", start="washer", irs="HB1")],
         WASHER_FILES),
]


def with_auto_washer(cases: list, folder: Path) -> list:
    """The washer cases given AUTO-07p's washer.c / washer.o / washer.exe, built once into
    `folder`; without AUTO-07p they stay washer-only (a message says so)."""
    mine = [c for c in cases if c in WASHER_CASES]
    if not mine:
        return cases
    from washer.problems import auto07p
    if not auto07p.installed():
        print("auto-07p is not installed: the washer cases run without AUTO's column")
        return [dataclasses.replace(c, auto=False) if c in mine else c for c in cases]
    print("building AUTO-07p's washer.exe (the kernel's objects are cached) ...", flush=True)
    auto07p.build_executable(folder)
    files = [(folder / f"washer{ext}", f"washer{ext}") for ext in (".c", ".o", ".exe")]
    return [dataclasses.replace(c, auto_files=files) if c in mine else c for c in cases]


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
    with tempfile.TemporaryDirectory(prefix="bench_washer_exe_") as tmp:
        cases = with_auto_washer(cases, Path(tmp))
        rows = compare(cases, repeat=a.repeat, against=a.against)
    print(report(rows, a.against))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
