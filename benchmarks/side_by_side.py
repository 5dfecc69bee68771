"""washer and AUTO-07p on the same runs, timed the same way in one benchmark run.

A case is a short chain of runs written once (`Step`) and played on both sides:
* AUTO-07p (the installed `auto-07p` CLUI, OMP_NUM_THREADS=1, the demo's Fortran
  source from tests/data/auto_demos/) runs a generated `.auto` script; its time for a
  run is the "Total Time" line AUTO prints for it (the continuation and its fort.7/8/9
  files, without the CLUI's start-up and the compilation);
* washer runs the same chain through `washer.run.run` in a worker process; its time
  for a run is the wall time of the `run()` call (constants, restart file, the
  continuation, b./s./d. files), after one untimed pass over every case (imports and
  first calls are not the engine, as AUTO's compilation is not).
Beside these wall times, each side's CPU time of the same runs: AUTO's executable's
(user + system, of the process the CLUI starts, through AUTO_COMMAND_PREFIX and a small
wrapper), washer's process time of its run() calls. On a shared, loaded machine the
CPU times are the steadier figures (a run's wall time includes the waits for a core).
Both sides write b.<sv>; the points of a run are the rows of that b-file, counted by
one function for both. Every repetition runs AUTO, then washer (and, with --against,
an older washer from a git worktree) back to back; per side the minimum over the
repetitions counts, so ratios compare figures measured minutes apart on the same
(shared, loaded) machine.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import asdict, dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEMOS = Path(__file__).resolve().parent.parent / "tests" / "data" / "auto_demos"
ENV_1 = dict(os.environ, OMP_NUM_THREADS="1")


@dataclass
class Step:
    """One run of a chain (AUTO's run(...) / washer.run.run(...)).

    sv: output name (b.<sv>, s.<sv>); with `each`, one run per restart label, named
        <sv>_<k>. c: constants file c.<c>. e: the equations (AUTO's e=). start: the sv
        (or sv prefix, with `each`) of the runs restarted from; irs: the label there
        ('HB1'); each: restart from every labelled point of this type ('HB'; '*' all)
        of every earlier run whose sv begins with `start`. ov: overrides, the same on
        both sides. timed: counted in the case's time and points.
    """
    sv: str
    c: str
    e: str
    start: str | None = None
    irs: str | None = None
    each: str | None = None
    ov: dict = field(default_factory=dict)
    timed: bool = True


@dataclass
class Case:
    """A named chain. files: (source, name) copied into the run folder; auto: whether
    AUTO-07p can run it; washer_files: copied after `files` on washer's side only (its
    own NAME.py and constants of the same equations); auto_files: copied after `files`
    on AUTO's side only, in their order (a prebuilt user file: NAME.c, NAME.o, NAME.exe)."""
    name: str
    steps: list
    files: list
    auto: bool = True
    washer_files: list = field(default_factory=list)
    auto_files: list = field(default_factory=list)


# ----------------------------------------------------------------------------- AUTO side

def auto_installed() -> bool:
    return shutil.which("auto-07p") is not None


def _auto_script(case: Case) -> str:
    """The CLUI script of a case: every run saved under its sv; the runs of an `each`
    step restart from every matching label of every earlier matching run."""
    lines = ["out = {}"]
    c_of = {}
    for s in case.steps:
        ov = "".join(f", {k}={v!r}" for k, v in s.ov.items())
        c_of[s.sv] = s.c
        if s.start is None:
            lines.append(f"out[{s.sv!r}] = run(e={s.e!r}, c={s.c!r}{ov}, sv={s.sv!r})")
        elif s.each is None:
            # A restart keeps the constants of the run it restarts from (AUTO's CLUI
            # cannot apply a constants file's PAR to a stored solution): c= only when
            # the step names another file.
            c = "" if c_of.get(s.start) == s.c else f", c={s.c!r}"
            lines.append(f"out[{s.sv!r}] = run(out[{s.start!r}]({s.irs!r}), e={s.e!r}"
                         f"{c}{ov}, sv={s.sv!r})")
        else:
            sel = "()" if s.each == "*" else f"({s.each!r})"
            lines += [f"k = 0",
                      f"for name in sorted(n for n in list(out) if n.startswith({s.start!r})):",
                      f"    for sol in out[name]{sel}:",
                      f"        sv = '{s.sv}_%d' % k",
                      f"        out[sv] = run(sol, e={s.e!r}, c={s.c!r}{ov}, sv=sv)",
                      f"        k += 1"]
    return "\n".join(lines) + "\n"


#: Runs AUTO's executable (the CLUI's AUTO_COMMAND_PREFIX) and writes its CPU time to
#: stderr: one line per run, in the order of the runs.
CPU_WRAPPER = """import resource, subprocess, sys
rc = subprocess.call(sys.argv[1:])
r = resource.getrusage(resource.RUSAGE_CHILDREN)
sys.stderr.write("BENCH_CPU %.6f\\n" % (r.ru_utime + r.ru_stime))
sys.exit(rc)
"""


def run_auto(case: Case, folder: Path) -> dict:
    """Run a case's chain with AUTO-07p in `folder` (already holding its files);
    returns sv -> (seconds (AUTO's Total Time), CPU seconds of its executable)."""
    (folder / "bench.auto").write_text(_auto_script(case))
    (folder / "bench_cpu.py").write_text(CPU_WRAPPER)
    env = dict(ENV_1, AUTO_COMMAND_PREFIX=f"{sys.executable} {folder / 'bench_cpu.py'}")
    r = subprocess.run(["auto-07p", "bench.auto"], cwd=folder, env=env, stdin=subprocess.DEVNULL,
                       capture_output=True, text=True, timeout=600)
    log = r.stdout + r.stderr
    cpu = [float(x) for x in re.findall(r"^BENCH_CPU (\S+)$", r.stderr, re.M)]
    times, last, k = {}, None, 0
    for line in r.stdout.splitlines():
        m = re.match(r"\s*Total Time\s+(\S+)", line)
        if m:
            last = float(m.group(1))
            continue
        m = re.match(r"Saving to b\.(\S+?),", line)
        if m and last is not None:
            times[m.group(1)] = (last, cpu[k] if k < len(cpu) else None)
            last, k = None, k + 1
    if r.returncode != 0 or not times:
        raise RuntimeError(f"AUTO-07p failed on {case.name}:\n{log[-2000:]}")
    return times


# ----------------------------------------------------------------------------- both sides

def b_points(path: Path) -> int:
    """Rows of a b-file (ours or AUTO's): lines whose branch number is not 0 (0 starts
    the header lines)."""
    n = 0
    for line in path.read_text().splitlines():
        head = line.split(None, 1)
        if head and re.fullmatch(r"-?\d+", head[0]) and int(head[0]) != 0:
            n += 1
    return n


def case_folder(case: Case, parent: Path) -> Path:
    d = parent / case.name
    d.mkdir(parents=True, exist_ok=True)
    for src, name in list(case.files) + list(case.auto_files):
        shutil.copy(src, d / name)
    return d


def totals(case: Case, folder: Path, times: dict) -> tuple[float, int, float | None]:
    """(seconds, points, CPU seconds or None) of a case's timed runs, from sv -> (seconds,
    CPU seconds) and the b-files."""
    t, n, cpu = 0.0, 0, 0.0
    for s in case.steps:
        if not s.timed:
            continue
        names = [k for k in times if k == s.sv or (s.each and re.fullmatch(rf"{s.sv}_\d+", k))]
        for k in names:
            wall, c = times[k]
            t += wall
            cpu = None if cpu is None or c is None else cpu + c
            n += b_points(folder / f"b.{k}")
    return t, n, cpu


# ----------------------------------------------------------------------------- washer side

WORKER = r'''
import ast, json, sys
from pathlib import Path
sys.path.insert(0, sys.argv[1])            # the benchmarks folder (this module)
from side_by_side import Case, Step, play_washer
cases = [Case(c["name"], [Step(**s) for s in c["steps"]], c["files"], c["auto"],
              c["washer_files"])
         for c in ast.literal_eval(sys.argv[3])]
folder = Path(sys.argv[2])
out = {}
for case in cases:                          # untimed: imports, first calls
    try:
        play_washer(case, folder / "warm" / case.name)
    except Exception as exc:                # a failing case is reported, the others run
        out[case.name] = {"error": f"{type(exc).__name__}: {exc}"}
for case in cases:
    if case.name not in out:
        out[case.name] = play_washer(case, folder / "timed" / case.name)
print(json.dumps(out))
'''


def play_washer(case: Case, d: Path) -> dict:
    """Run a case's chain with washer.run.run in the folder d (created, filled);
    returns sv -> (seconds, CPU seconds) of each run() call."""
    import time
    from washer.run import run
    d.mkdir(parents=True, exist_ok=True)
    for src, name in list(case.files) + list(case.washer_files):
        shutil.copy(src, d / name)
    times, runs = {}, {}
    for s in case.steps:
        plan = []
        if s.start is None:
            plan.append((s.sv, None, None))
        elif s.each is None:
            plan.append((s.sv, s.start, s.irs))
        else:
            k = 0
            for name in sorted(n for n in list(runs) if n.startswith(s.start)):
                for p in runs[name].specials:
                    if s.each in ("*", p.ty):
                        plan.append((f"{s.sv}_{k}", name, p.lab))
                        k += 1
        for sv, start, lab in plan:
            kw = dict(s.ov, e=s.e, sv=sv)
            if start is not None:
                kw.update(s=start, IRS=lab)
            t0, c0 = time.perf_counter(), time.process_time()
            runs[sv] = run(d / f"c.{s.c}", verbose=False, **kw)
            times[sv] = (time.perf_counter() - t0, time.process_time() - c0)
    return times


def run_washer(cases: list, folder: Path, code_root: Path) -> dict:
    """One worker process with the washer package at code_root: an untimed pass, then a
    timed one; returns case -> sv -> seconds (the timed pass's folders hold the b-files)."""
    env = dict(ENV_1, PYTHONPATH=str(code_root))
    # repr, not JSON: the overrides' integer keys (UZSTOP={1: ...}) must stay integers
    payload = repr([dict(name=c.name, steps=[asdict(s) for s in c.steps],
                               files=[(str(a), b) for a, b in c.files], auto=c.auto,
                               washer_files=[(str(a), b) for a, b in c.washer_files])
                          for c in cases])
    r = subprocess.run([sys.executable, "-c", WORKER, str(Path(__file__).parent), str(folder),
                        payload], env=env, capture_output=True, text=True, cwd=folder)
    if r.returncode != 0:
        raise RuntimeError(f"washer ({code_root}) failed:\n{r.stderr[-3000:]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def worktree(rev: str) -> Path:
    """A detached git worktree of rev with its own compiled modules: the current ones
    copied in where rev's C++ sources are the working tree's, else built from rev's
    (`python build.py cont` when only csrc/cont differs, `python build.py` otherwise):
    a revision before a change of the compiled engine is timed with its own."""
    tmp = Path(tempfile.mkdtemp(prefix="bench_rev_")) / "tree"
    r = subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tmp), rev],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"git worktree {rev}: {r.stderr.strip()}")

    def differs(*paths):
        return subprocess.run(["git", "-C", str(ROOT), "diff", "--quiet", rev, "--", *paths],
                              capture_output=True).returncode != 0
    kernel, cont = differs("csrc", ":(exclude)csrc/cont"), differs("csrc/cont")
    for so in (ROOT / "washer").glob("_*.so"):
        mine = so.name.startswith("_kernel") and kernel or so.name.startswith("_cont") and cont
        if not mine and not (tmp / "washer" / so.name).exists():
            shutil.copy(so, tmp / "washer" / so.name)
    if kernel or cont:
        print(f"building {rev}'s compiled modules ({'kernel and ' if kernel else ''}engine) ...",
              flush=True)
        r = subprocess.run([sys.executable, "build.py"] + ([] if kernel else ["cont"]),
                           cwd=tmp, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"building {rev}: {r.stderr[-2000:]}")
    return tmp


def compare(cases: list, repeat: int = 3, against: str | None = None) -> list[dict]:
    """Every case on every side, `repeat` back-to-back repetitions; per side and case the
    minimum time. Returns one dict per case: points and seconds per side."""
    use_auto = auto_installed()
    if not use_auto:
        print("auto-07p is not installed: AUTO-07p's columns are skipped "
              "(Debian: apt-get install auto-07p)")
    base = Path(tempfile.mkdtemp(prefix="bench_auto_"))
    old_tree = worktree(against) if against else None
    try:
        best: dict = {}
        best_cpu: dict = {}
        errors: dict = {}
        if use_auto:                      # compile every demo once, untimed
            for c in cases:
                if c.auto:
                    run_auto(c, case_folder(c, base / "auto_warm"))
        for rep in range(repeat):
            sides = {}
            if use_auto:
                sides["auto"] = {}
                for c in cases:
                    if c.auto:
                        d = case_folder(c, base / f"auto{rep}")
                        for exe in (base / "auto_warm" / c.name).glob("*.exe"):
                            shutil.copy(exe, d / exe.name)
                        sides["auto"][c.name] = totals(c, d, run_auto(c, d))
            for side, root in (("washer", ROOT), ("old", old_tree)):
                if root is None:
                    continue
                folder = base / f"{side}{rep}"
                folder.mkdir()
                res = run_washer(cases, folder, root)
                sides[side] = {}
                for c in cases:
                    if "error" in res[c.name]:
                        errors[(c.name, side)] = res[c.name]["error"]
                    else:
                        sides[side][c.name] = totals(c, folder / "timed" / c.name, res[c.name])
            for side, per_case in sides.items():
                for name, (t, n, cpu) in per_case.items():
                    key = (name, side)
                    if key not in best or t < best[key][0]:
                        best[key] = (t, n)
                    if cpu is not None and (key not in best_cpu or cpu < best_cpu[key][0]):
                        best_cpu[key] = (cpu, n)
        rows = []
        for c in cases:
            row = {"case": c.name, "errors": {s: e for (n, s), e in errors.items() if n == c.name}}
            for side in ("washer", "old", "auto"):
                if (c.name, side) in best:
                    row[side] = best[(c.name, side)]
                if (c.name, side) in best_cpu:
                    row[side + "_cpu"] = best_cpu[(c.name, side)]
            rows.append(row)
        return rows
    finally:
        if old_tree is not None:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force",
                            str(old_tree)], capture_output=True)
        shutil.rmtree(base, ignore_errors=True)


def report(rows: list[dict], against: str | None = None) -> str:
    """The table: per case and side points and microseconds per point; ratios washer /
    AUTO (and old / new with --against); then washer's and AUTO's CPU time per point and
    their ratio."""
    head = f"{'case':24s} {'points':>13s} {'washer us/pt':>13s}"
    if against:
        head += f" {against[:10] + ' us/pt':>17s} {'speed-up':>8s}"
    head += f" {'AUTO us/pt':>11s} {'washer/AUTO':>11s}"
    head += f" {'cpu us/pt':>10s} {'AUTO cpu':>9s} {'cpu w/A':>8s}"
    if against:
        head += f" {against[:7] + ' cpu':>12s} {'cpu speed-up':>12s}"
    out = [head]
    for r in rows:
        if "washer" not in r:
            out.append(f"{r['case']:24s} failed: {r['errors'].get('washer', '?')[:200]}")
            continue
        t, n = r["washer"]
        per = 1e6 * t / max(n, 1)
        pts = f"{n}"
        line = ""
        if against and "old" in r:
            to, no = r["old"]
            po = 1e6 * to / max(no, 1)
            line += f" {po:17.0f} {po / per:7.2f}x"
        elif against:
            line += f" {'failed':>17s} {'-':>8s}"
        if "auto" in r:
            ta, na = r["auto"]
            pa = 1e6 * ta / max(na, 1)
            pts += f" / {na}"
            line += f" {pa:11.1f} {per / pa:10.1f}x"
        else:
            line += f" {'-':>11s} {'-':>11s}"
        if "washer_cpu" in r:
            cw, nw = r["washer_cpu"]
            line += f" {1e6 * cw / max(nw, 1):10.1f}"
            if "auto_cpu" in r:
                ca, na = r["auto_cpu"]
                pc = 1e6 * ca / max(na, 1)
                line += f" {pc:9.1f} {1e6 * cw / max(nw, 1) / pc:7.2f}x"
            else:
                line += f" {'-':>9s} {'-':>8s}"
            if against and "old_cpu" in r:
                co, no = r["old_cpu"]
                pco = 1e6 * co / max(no, 1)
                line += f" {pco:12.1f} {pco / (1e6 * cw / max(nw, 1)):11.2f}x"
        out.append(f"{r['case']:24s} {pts:>13s} {per:13.1f}" + line)
    return "\n".join(out)
