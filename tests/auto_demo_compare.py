"""Run an AUTO-07p demo folder unchanged with `python -m washer.auto NAME.auto` and compare
every special point of every b-file AUTO wrote (tests/data/auto_demos/NAME/autoref) with ours.

A special point is a labelled b-file row other than a regular NPR output (RG). Ours matches
AUTO's when it has the same type and branch number in the same label order (the two
sequences are aligned for the most agreeing pairs, so one extra or missing point costs only
itself), and, for located points (every type but EP and MX, whose place is the step
history's), the same continuation
parameter PAR(ICP(1)) within AUTO's location tolerance and the same period (PAR(11)) where
the b-file shows it.

Location tolerance: AUTO (and washer) stop locating a zero when the arclength correction is
below EPSS (1 + sqrt(|DS DSMAX|)) (docs/auto.md section 0); the tangent is unit in a norm in which
PAR(ICP(1)) has weight 1 (THL), so each engine's parameter is within that distance of the
exact zero, and the two within twice it. EPSS, DS, DSMAX are read from the header of AUTO's
own b-file branch (the branches a run switches to, MXBF, have only column titles and keep
the run's constants). The period has no weight in the arclength of periodic orbits (THL
{11: 0}), so the tolerance does not bound it directly: it is compared at 1e-3 relative
(AUTO's UZ at PERIOD = 1000 in the ab demo is 999.88; the exact value is the UZ value
itself), or within what the arclength tolerance implies where the period changes faster
than that along the branch: |dT/ds| times the tolerance. |dT/ds| is read from AUTO's own
rows next to the point: over a step, the arclength is at least sqrt(dPAR(ICP(1))^2 + dL2^2)
(PAR(ICP(1)) has weight 1 in it, and the solution's L2 norm, the b-file's L2-NORM column,
changes by at most the norm of the change), so |dT| / sqrt(dPAR^2 + dL2^2) is at least the
step's mean |dT/ds|; the larger of the steps before and after the point is taken.
Cycles growing to a homoclinic orbit need this: their period grows without bound
while the orbit hardly moves (vhb: AUTO's UZ at PERIOD = 1e5 is written at 100396, 3.5e-6
in L2 norm beyond the row before it whose period is 87613: a tolerance of 2.3e-5 in
arclength leaves the period free by 8e4 there).

    python tests/auto_demo_compare.py [DEMO ...]     # print docs/auto_compatibility.md's table
"""
from __future__ import annotations

import gzip
import math
import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEMOS = Path(__file__).parent / "data" / "auto_demos"
sys.path.insert(0, str(ROOT))

from washer.auto.diagram import read_branches, type_name  # noqa: E402

UNLOCATED = ("EP", "MX")
PERIOD_RTOL = 1e-3

#: Demos run script by script: the scripts of the folder, in order (snh.auto runs h1b.auto,
#: cb.auto and tb.auto, then merges their outputs into b.all, which AUTO's run did not keep),
#: and demos whose script is not named after the folder (fhh and fnb are AUTO's two folders
#: of the FitzHugh-Nagumo model's homoclinic orbits, each with its own fhn.auto); man's
#: folder has AUTO's man1.auto and man2.auto beside man.auto (man2 starts from man1's s.start);
#: r3b's manifold scripts start from r3b.auto's families (each writes b.flq: the last one's
#: is compared; V1a.auto's last run stops at a label that is not there, in AUTO too, so it
#: comes last; L1a.auto stops so as well and is left out, H1b.auto and the X scripts too);
#: nbody is AUTO's demos/python/n-body, whose two scripts compute the Lagrange points (the
#: first writes each kind's last UZ to s.l1-s.l5, the second saves b.lagrange_points and
#: leaves its last run in fort.7).
SCRIPTS = {"snh": ("h1b.auto", "cb.auto", "tb.auto"), "fhh": ("fhn.auto",),
           "fnb": ("fhn.auto",), "man": ("man.auto", "man1.auto", "man2.auto"),
           "r3b": ("r3b.auto", "H1a.auto", "H1c.auto", "V1b.auto", "V1a.auto"),
           "nbody": ("compute_lagrange_points_0.5.auto",
                     "compute_lagrange_points_family.auto"),
           "pclc": ("pclc.auto",)}

#: Folders that hold another user file of a demo (AUTO's Fortran-77 NAME.f beside the
#: demo's NAME.f90) and AUTO's outputs with it: the demo's folder gives the constants and
#: scripts, without its NAME.f90 (which would win over NAME.f, runAUTO's order); or another
#: script of the demo (SCRIPTS names it) with the constants files it reads (pclc: AUTO's
#: pclc.auto beside pcl.auto, the same runs from c.pcl.1-8).
VARIANT_OF = {"cirf77": "cir", "dd2f77": "dd2", "expf77": "exp", "intf77": "int",
              "ivpf77": "ivp", "optf77": "opt", "pd1f77": "pd1", "brcf77": "brc",
              "shef77": "she", "revf77": "rev",
              "wavf77": "wav", "sanf77": "san", "pclc": "pcl",
              "pvlf77": "pvl", "opsf77": "ops",
              "mtnf77": "mtn", "kprf77": "kpr", "fhhf77": "fhh"}



@dataclass
class Point:
    file: str
    ty: str
    br: int
    lab: int
    par: float
    period: float | None
    tol: float
    #: |d PERIOD / ds| on AUTO's branch at the point, from its rows (`period_slope`)
    period_slope: float = 0.0

    @property
    def key(self):
        return (self.ty, self.br)


@dataclass
class Result:
    demo: str
    returncode: int
    seconds: float
    auto_points: int = 0
    matched: int = 0
    problems: list = field(default_factory=list)
    log: str = ""


def _text(path: Path) -> str:
    if path.suffix == ".gz":
        with gzip.open(path, "rt") as f:
            return f.read()
    return path.read_text()


def _header_value(header: list[str], key: str) -> float | None:
    for line in header:
        m = re.search(re.escape(key) + r"\s*=\s*([-+0-9.EeDd]+)", line)
        if m:
            return float(m.group(1).replace("D", "E"))
    return None


def points(path: Path, reference: bool) -> list[Point]:
    """The special points of a b-file (gzipped or not)."""
    import tempfile
    with tempfile.NamedTemporaryFile("w", suffix=".b", delete=False) as tmp:
        tmp.write(_text(path))
    try:
        branches = read_branches(tmp.name)
    finally:
        os.unlink(tmp.name)
    out = []
    # A run's header precedes its first branch only: the branches it switched to (MXBF)
    # follow with a header of column titles, and keep the run's constants.
    const = {"EPSS": 1e-5, "DS": 0.01, "DSMAX": 0.1}
    for b in branches:
        for key in const:
            v = _header_value(b.header, key) if b.header else None
            if v is not None:
                const[key] = v
        epss, ds, dsmax = const["EPSS"], abs(const["DS"]), abs(const["DSMAX"])
        tol = 2 * epss * (1 + math.sqrt(ds * dsmax))
        titles = b.titles
        k_per = k_l2 = None
        if "PERIOD" in titles[1:]:          # AUTO's title of PAR(11) on periodic orbits
            k_per = titles.index("PERIOD")
        if "L2-NORM" in titles[1:]:
            k_l2 = titles.index("L2-NORM")
        for k, r in enumerate(b.rows):
            name = type_name(r.ty)
            if r.lab and name not in ("RG", ""):
                per = r.values[k_per] if k_per is not None and k_per < len(r.values) else None
                slope = period_slope(b.rows, k, k_per, k_l2) if per is not None else 0.0
                out.append(Point(path.name.removesuffix(".gz"), name, r.br, r.lab,
                                 r.values[0] if r.values else float("nan"), per, tol, slope))
    return out


def period_slope(rows, k: int, k_per: int, k_l2: int | None) -> float:
    """|d PERIOD / ds| at row k of a branch's rows: the largest |dT| / sqrt(dPAR^2 + dL2^2)
    over the steps to the rows before and after it, each at least the step's mean |dT/ds|
    (the arclength of a step is at least that root: PAR(ICP(1)) has weight 1 in it, and the
    L2 norm changes by at most the norm of the change). 0 without an L2-NORM column (then
    the period is compared at PERIOD_RTOL only). A neighbouring row with the same printed
    PAR and L2 norm bounds nothing and is left out (an infinite rate would let any period
    pass)."""
    if k_l2 is None:
        return 0.0
    best = 0.0
    r = rows[k].values
    for j in (k - 1, k + 1):
        if not 0 <= j < len(rows):
            continue
        q = rows[j].values
        if max(k_per, k_l2) >= min(len(q), len(r)):
            continue
        dt = abs(r[k_per] - q[k_per])
        ds = math.hypot(r[0] - q[0], r[k_l2] - q[k_l2])
        if dt > 0 and ds > 0:
            best = max(best, dt / ds)
    return best


def same_value(o: Point, a: Point) -> str | None:
    """None if o's located values agree with AUTO's a, else why not."""
    if a.ty in UNLOCATED:
        return None
    if not abs(o.par - a.par) <= a.tol * max(1.0, abs(a.par)):
        return f"PAR {o.par:.10g} vs AUTO {a.par:.10g} (tol {a.tol:.2g})"
    if a.period is not None and o.period is not None and \
            not abs(o.period - a.period) <= period_tolerance(a):
        return f"period {o.period:.10g} vs AUTO {a.period:.10g} (tol {period_tolerance(a):.2g})"
    return None


def period_tolerance(a: Point) -> float:
    """How far a period may lie from AUTO's a.period: PERIOD_RTOL relative, or the
    arclength tolerance times |dT/ds| on AUTO's branch there where that is larger."""
    return max(PERIOD_RTOL * abs(a.period), a.period_slope * a.tol)


#: Weights of the alignment: a pair of the same type and branch whose located values agree
#: outweighs any number of pairs whose values differ (so an extra or missing point costs
#: only itself, whichever point it is).
AGREE, SAME_KEY = 1000, 1


def align(a: list[Point], o: list[Point]) -> list[tuple[int, int]]:
    """The pairs (i, j) of AUTO's points a[i] and ours o[j], in order on both sides, of the
    same type and branch, that make the most pairs whose values agree (`same_value`), then
    the most pairs: a weighted longest common subsequence (dynamic programming)."""
    n, m = len(a), len(o)
    score = [[0] * (m + 1) for _ in range(n + 1)]
    for i in range(n - 1, -1, -1):
        for j in range(m - 1, -1, -1):
            best = max(score[i + 1][j], score[i][j + 1])
            if a[i].key == o[j].key:
                w = AGREE if same_value(o[j], a[i]) is None else SAME_KEY
                best = max(best, score[i + 1][j + 1] + w)
            score[i][j] = best
    pairs, i, j = [], 0, 0
    while i < n and j < m:
        if a[i].key == o[j].key:
            w = AGREE if same_value(o[j], a[i]) is None else SAME_KEY
            if score[i][j] == score[i + 1][j + 1] + w:
                pairs.append((i, j))
                i, j = i + 1, j + 1
                continue
        if score[i][j] == score[i + 1][j]:
            i += 1
        else:
            j += 1
    return pairs


def compare_files(ours: Path | None, ref: Path) -> tuple[list[Point], set[int], list[str]]:
    """AUTO's points of ref, the indices of those ours matches, and the differences."""
    a = points(ref, True)
    o = points(ours, False) if ours is not None and ours.exists() else []
    matched: set[int] = set()
    why, notes = [], []
    if not o:
        return a, matched, [f"{ref.name}: no output file" if ours is None or not ours.exists()
                            else f"{ref.name}: no special points"]
    i0 = j0 = 0
    for i, j in align(a, o) + [(len(a), len(o))]:
        if i > i0 or j > j0:
            # points between two pairs: AUTO's and ours that have no counterpart
            why.append(f"{a[i0].file if i0 < len(a) else o[j0].file}: AUTO "
                       f"{[p.key for p in a[i0:i]]} vs ours {[p.key for p in o[j0:j]]}")
        if i < len(a) and j < len(o):
            bad = same_value(o[j], a[i])
            if bad is None:
                matched.add(i)
            else:
                why.append(f"{a[i].file} {a[i].ty}{a[i].lab} br {a[i].br}: {bad}")
            if o[j].lab != a[i].lab:
                # label numbers count the NPR outputs before a point, which follow the
                # step history: a note, not a mismatch
                notes.append(f"{a[i].file} {a[i].ty}: label {o[j].lab} vs AUTO {a[i].lab}")
        i0, j0 = i + 1, j + 1
    return a, matched, why + notes[:1]


def point_key(p: Point) -> tuple:
    """What counts a point once per demo (merged and saved copies of a run repeat it):
    type, PAR(ICP(1)) to 7 decimals, period to 5."""
    return p.ty, round(p.par, 7), None if p.period is None else round(p.period, 5)


def auto_point_count(demo: str) -> int:
    """How many special points AUTO's b-files of the demo hold, each counted once."""
    return len({point_key(p) for ref in reference_files(demo) for p in points(ref, True)})


#: In a variant's autoref/ (VARIANT_OF), the SHA-256 of each b-file AUTO-07p wrote with
#: the variant's user file where they are its base folder's byte for byte (`sha256sum` of
#: the b-files as AUTO wrote them, not gzipped): the folder keeps these instead of copies
#: and the comparison reads the base's (test_auto_demo_folders.py checks the digests).
SAME_AS_BASE = "b-files.sha256"


def base_digests(demo: str) -> dict[str, str]:
    """{b-file name: SHA-256} of a variant's SAME_AS_BASE, or {} where it stores its own."""
    manifest = DEMOS / demo / "autoref" / SAME_AS_BASE
    if not manifest.exists():
        return {}
    pairs = (line.split() for line in manifest.read_text().splitlines() if line.strip())
    return {name: digest for digest, name in pairs}


def reference_folder(demo: str) -> Path:
    """The autoref/ folder whose b-files are AUTO's output of the demo: its own, or its
    base demo's where they are the same (SAME_AS_BASE)."""
    return DEMOS / (VARIANT_OF[demo] if base_digests(demo) else demo) / "autoref"


def reference_files(demo: str) -> list[Path]:
    ref = reference_folder(demo)
    names = base_digests(demo)
    if names:
        return sorted(p for p in ref.iterdir() if p.name.removesuffix(".gz") in names)
    return sorted(p for p in ref.rglob("*") if p.name.startswith("b.") or
                  p.name in ("fort.7", "fort.7.gz"))


def run_demo(demo: str, workdir: Path, timeout: float = 1200) -> Result:
    """Copy the demo (without autoref) into workdir, run its script (or SCRIPTS' scripts
    in turn, each while the previous one succeeded), compare."""
    src = DEMOS / demo
    work = workdir / demo
    base = VARIANT_OF.get(demo)
    if base is not None:
        # a variant with its own user file (NAME.f, NAME.c) runs without the base's NAME.f90
        own = [f"{f.stem}.f90" for f in src.iterdir() if f.suffix in (".f", ".c")]
        shutil.copytree(DEMOS / base, work, ignore=shutil.ignore_patterns("autoref*", *own))
        shutil.copytree(src, work, ignore=shutil.ignore_patterns("autoref*"),
                        dirs_exist_ok=True)
    else:
        shutil.copytree(src, work, ignore=shutil.ignore_patterns("autoref*"))
    env = dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1")
    t0 = time.perf_counter()
    rc, log = 0, ""
    for script in scripts_of(demo):
        try:
            proc = subprocess.run([sys.executable, "-m", "washer.auto", script], cwd=work,
                                  env=env, stdin=subprocess.DEVNULL, capture_output=True,
                                  text=True, timeout=timeout)
            rc, log = proc.returncode, log + proc.stdout + proc.stderr
        except subprocess.TimeoutExpired as exc:
            rc, log = -1, log + f"timeout after {timeout} s\n{exc.stdout or ''}"
        if rc != 0:
            break
    res = Result(demo, rc, time.perf_counter() - t0, log=log)
    seen: dict = {}
    for ref in reference_files(demo):
        rel = ref.relative_to(reference_folder(demo))
        ours = work / str(rel).removesuffix(".gz")
        a, matched, why = compare_files(ours, ref)
        res.problems += why
        for i, p in enumerate(a):
            k = point_key(p)
            seen[k] = seen.get(k, False) or i in matched
    res.auto_points = len(seen)
    res.matched = sum(seen.values())
    if rc != 0:
        tail = [ln for ln in log.strip().splitlines() if ln.strip()][-3:]
        res.problems.insert(0, f"script exit {rc}: {' | '.join(tail)}")
    return res


def scripts_of(demo: str) -> tuple[str, ...]:
    """The scripts a demo runs, in order: its own in SCRIPTS, else its base demo's (a
    variant's folder gives another user file or constants file to the base's script)."""
    base = VARIANT_OF.get(demo, demo)
    return SCRIPTS.get(demo, SCRIPTS.get(base, (f"{base}.auto",)))


def all_demos() -> list[str]:
    def script(name):
        first = scripts_of(name)[0]
        own = DEMOS / name / first
        return own if own.exists() else DEMOS / VARIANT_OF.get(name, name) / first
    return sorted(p.name for p in DEMOS.iterdir() if script(p.name).exists())


def main(argv: list[str]) -> int:
    import tempfile
    demos = argv or all_demos()
    print("| demo | points matched / AUTO's | script | s | first difference |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for d in demos:
            r = run_demo(d, Path(tmp))
            first = r.problems[0] if r.problems else ""
            print(f"| {d} | {r.matched} / {r.auto_points} | "
                  f"{'ok' if r.returncode == 0 else 'exit %d' % r.returncode} | "
                  f"{r.seconds:.1f} | {first[:160].replace('|', '/')} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
