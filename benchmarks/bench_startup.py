"""Whole-process time of a short run: `python -m washer.run c.NAME` against AUTO-07p's
executable on the same constants file.

    python benchmarks/bench_startup.py [--repeat N] [--only ab_eq,lrz_eq] [--against REV]

Cases: bench_vs_auto.py's ab_eq (ab's equilibria in PAR(1), 107 points) and lrz_eq
(Lorenz equilibria in rho), each in a folder of its own with the Python user file, the
constants file and AUTO's Fortran file. AUTO's side is the executable its CLUI builds from
ab.f90 / lrz.f90 (side_by_side.run_auto, once, untimed), then started directly as the
CLUI starts it: the constants as fort.2, fort.7/8/9 written, one OpenMP thread. washer's
side is `sys.executable -m washer.run c.NAME` (b-, s-, d-files written, the table printed
to a pipe), with the compile cache warm (the traced func and cffi's modules of the
declarations built by an untimed first run), in two ways:
  source    as this environment starts Python: with PYTHONDONTWRITEBYTECODE=1 (set here)
            every washer module is compiled from its source at every start
  bytecode  washer's modules' bytecode cached (PYTHONPYCACHEPREFIX, a temporary folder,
            filled by the untimed run): as an installed package starts
Each repetition runs every side back to back; per side the minimum over the repetitions
counts (wall seconds, and CPU seconds: user + system of the child, the steadier figure
on a loaded machine). `python -c pass` and `python -c 'import numpy'` are measured the
same way: the part of the budget that is Python's and numpy's own. --against REV adds
the washer of git revision REV (a temporary worktree, side_by_side.worktree).

The target: a short run's whole process under TARGET_S seconds of wall time.
"""
from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_vs_auto import CASES  # noqa: E402
from side_by_side import ENV_1, ROOT, auto_installed, case_folder, run_auto, worktree  # noqa: E402

#: The whole-process wall time a short equilibrium run should stay under.
TARGET_S = 0.5
#: The cases of bench_vs_auto.py timed here (one run each, IRS = 0).
NAMES = ("ab_eq", "lrz_eq")


def timed(cmd: list[str], cwd: Path, env: dict) -> tuple[float, float]:
    """(wall seconds, CPU seconds (user + system)) of one child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(cmd, cwd=cwd, env=env, stdin=subprocess.DEVNULL, capture_output=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} in {cwd} failed ({r.returncode}):\n"
                           f"{r.stderr.decode()[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def washer_env(code_root: Path, pycache: Path | None) -> dict:
    """The child's environment: washer from code_root; pycache None: sources compiled at
    every start (PYTHONDONTWRITEBYTECODE=1), else bytecode cached under pycache."""
    env = dict(ENV_1, PYTHONPATH=str(code_root))
    if pycache is None:
        env["PYTHONDONTWRITEBYTECODE"] = "1"
        env.pop("PYTHONPYCACHEPREFIX", None)
    else:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = str(pycache)
    return env


def auto_exe(case, folder: Path) -> Path:
    """AUTO's executable of a case, built by its CLUI in `folder` (one untimed run), with
    the constants file beside it as fort.2."""
    run_auto(case, folder)
    exe = next(folder.glob("*.exe"))
    c_file = next(s.c for s in case.steps)
    shutil.copy(folder / f"c.{c_file}", folder / "fort.2")
    return exe


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=10, help="repetitions (the minimum counts)")
    ap.add_argument("--only", default="", help="comma-separated case names " + str(NAMES))
    ap.add_argument("--against", default=None, help="git revision of a washer to compare with")
    a = ap.parse_args(argv)
    names = a.only.split(",") if a.only else list(NAMES)
    unknown = set(names) - set(NAMES)
    if unknown:
        ap.error(f"unknown case(s) {sorted(unknown)}")
    cases = [c for c in CASES if c.name in names]
    base = Path(tempfile.mkdtemp(prefix="bench_startup_"))
    old_tree = worktree(a.against) if a.against else None
    roots = {"washer": ROOT} | ({a.against[:10]: old_tree} if old_tree else {})
    try:
        # side -> (command, folder, env) per case; "python" rows: Python's and numpy's own
        py = sys.executable
        plain = dict(ENV_1)
        sides: dict = {("python", "-c pass"): ([py, "-c", "pass"], base, plain),
                       ("python", "-c 'import numpy'"): ([py, "-c", "import numpy"], base, plain)}
        use_auto = auto_installed()
        if not use_auto:
            print("auto-07p is not installed: AUTO-07p's rows are skipped")
        for case in cases:
            c_file = next(s.c for s in case.steps)
            if use_auto:
                d = case_folder(case, base / "auto")
                exe = auto_exe(case, d)
                sides[(case.name, "AUTO-07p " + exe.name)] = ([str(exe)], d, ENV_1)
            for label, root in roots.items():
                for mode in ("source", "bytecode"):
                    d = case_folder(case, base / f"{label}_{mode}")
                    env = washer_env(root, None if mode == "source" else
                                     base / f"pycache_{label}")
                    cmd = [py, "-m", "washer.run", f"c.{c_file}"]
                    timed(cmd, d, env)           # untimed: compile cache, bytecode
                    sides[(case.name, f"{label} ({mode})")] = (cmd, d, env)
        best: dict = {}
        for rep in range(a.repeat):
            for key, (cmd, d, env) in sides.items():
                wall, cpu = timed(cmd, d, env)
                w0, c0 = best.get(key, (wall, cpu))
                best[key] = (min(w0, wall), min(c0, cpu))
        print(report(best, a.repeat))
    finally:
        if old_tree is not None:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force",
                            str(old_tree)], capture_output=True)
        shutil.rmtree(base, ignore_errors=True)
    return 0


def report(best: dict, repeat: int) -> str:
    """Per case and side: wall and CPU seconds (minimum of `repeat`), ratios to AUTO's
    executable, and whether the wall time is under TARGET_S."""
    load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
    out = [f"whole process, minimum of {repeat} runs; target: a short run under "
           f"{TARGET_S} s wall (load average now {load} on {os.cpu_count()} cores: under "
           "load, wall time waits for a core and CPU time is the figure to read)",
           f"{'case':8s} {'side':28s} {'wall s':>7s} {'cpu s':>7s} {'wall/AUTO':>9s} "
           f"{'cpu/AUTO':>8s}  target"]
    autos = {case: v for (case, side), v in best.items() if side.startswith("AUTO")}
    for (case, side), (wall, cpu) in best.items():
        line = f"{case:8s} {side:28s} {wall:7.3f} {cpu:7.3f}"
        ref = autos.get(case)
        if ref and not side.startswith("AUTO"):
            line += f" {wall / ref[0]:8.1f}x {cpu / max(ref[1], 1e-3):7.1f}x"
        else:
            line += f" {'':9s} {'':8s}"
        if case != "python" and not side.startswith("AUTO"):
            line += "  met" if wall < TARGET_S else "  missed"
        out.append(line)
    return "\n".join(out)


if __name__ == "__main__":
    raise SystemExit(main())
