"""Continuation engine speed, against the engine as it was before the reshape
(commit BASELINE, checked out into a temporary git worktree and run in the
same session) and against AUTO-07p's own run times.

    python benchmarks/bench_engine.py [--no-baseline]

Cases: AUTO's `ab` (equilibria in p1 with JAC = 0, then the Hopf curve from
HB1: ab2p's first and fourth runs), and the washer's Fig 3 branch (c.washer)
plus Fig 4 Hopf curve (c.washer.hopf.Omega). Each case runs three times in a
fresh process per engine; the best wall time counts (these machines are
noisy; each process runs every case once untimed first, so imports are not
counted). "engine" times exclude file writing: the run goes through the runner
with no sinks (the baseline cannot do that: its times include its files).
AUTO-07p's times are the "Total Time" lines of its own run log
(tests/data/auto_reference/ab2p/run.log: 107 points in 6.05 ms for the
equilibria, 151 points in 21.5 ms for the Hopf curve).
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: The last commit of the engine before the reshape (issue 8).
BASELINE = "2952d5b"
AUTO_TIMES = {"ab_eq": (6.05e-3, 107), "ab_hb": (21.5e-3, 151)}
REPEAT = 3

CASE_SCRIPT = r'''
import json, shutil, sys, tempfile, time
from pathlib import Path
root, mode = Path(sys.argv[1]), sys.argv[2]
from washer.run import run
d = Path(tempfile.mkdtemp())
for f in ("ab.py", "c.ab"):
    shutil.copy(root / "tests" / "data" / "ab" / f, d)
for f in ("c.washer", "c.washer.hopf.Omega"):
    shutil.copy(root / "auto_constants" / f, d)
hb = dict(IRS="HB1", ICP=[1, 2], ISW=2, s="eq", sv="hb", UZSTOP={1: [0.0, 0.3], 2: [5.0, 30.0]},
          PAR={})
cases = {"ab_eq": (d / "c.ab", dict(sv="eq")), "ab_hb": (d / "c.ab", hb),
         "washer_fig3": (d / "c.washer", {}), "washer_fig4": (d / "c.washer.hopf.Omega", {})}
out = {}
for name, (c, kw) in cases.items():
    # A first, untimed run: imports and the kernel's first calls are not the engine.
    run(c, verbose=False, **dict(kw, sv=f"warm_{name}")) if "s" not in kw else None
    t0 = time.perf_counter()
    res = run(c, verbose=False, **kw)
    wall = time.perf_counter() - t0
    out[name] = {"wall": wall, "points": len(res.rows), "status": res.status}
    if mode == "new":
        # The same run without sinks: the engine's own time.
        from washer.auto.constants import read_constants
        from washer.cont.runner import build, execute
        from washer.run import resolve_problem
        from washer.auto.files import read_s
        cc = read_constants(c)
        for k, v in kw.items():
            cc.set(k, v)
        if cc["e"] == "washer":
            from washer.auto_washer import PAR_NAMES
            cc = cc.with_default_names(PAR_NAMES)
        prob = resolve_problem(cc, d)
        recs = read_s(d / f"s.{cc['s']}") if cc["IRS"] not in (0, "0") else None
        r, br, m = build(cc, prob, recs)
        t0 = time.perf_counter()
        b = execute(r, br, m, [])
        out[name]["engine"] = time.perf_counter() - t0
print(json.dumps(out))
'''


def measure(code_root: Path, mode: str) -> dict:
    """Best of REPEAT fresh processes running every case with the washer package
    found at code_root."""
    env = dict(os.environ, PYTHONPATH=str(code_root))
    best: dict = {}
    for _ in range(REPEAT):
        r = subprocess.run([sys.executable, "-c", CASE_SCRIPT, str(ROOT), mode], env=env,
                           capture_output=True, text=True, cwd=tempfile.gettempdir())
        if r.returncode != 0:
            raise RuntimeError(f"{mode} engine failed:\n{r.stderr[-2000:]}")
        res = json.loads(r.stdout.strip().splitlines()[-1])
        for k, v in res.items():
            if k not in best or v["wall"] < best[k]["wall"]:
                best[k] = v
    return best


def baseline_tree() -> Path | None:
    """A worktree of BASELINE with the current compiled kernel copied in (the
    C ABI it uses is unchanged), or None without git."""
    tmp = Path(tempfile.mkdtemp()) / "baseline"
    r = subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tmp), BASELINE],
                       capture_output=True, text=True)
    if r.returncode != 0:
        print(f"(no baseline: {r.stderr.strip()})")
        return None
    for so in (ROOT / "washer").glob("_kernel*.so"):
        shutil.copy(so, tmp / "washer" / so.name)
    return tmp


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    new = measure(ROOT, "new")
    old = None
    tree = None if "--no-baseline" in argv else baseline_tree()
    try:
        if tree is not None:
            old = measure(tree, "old")
    finally:
        if tree is not None:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(tree)],
                           capture_output=True)
    print(f"{'case':14s} {'points':>6s} {'wall s':>8s} {'engine s':>9s} {'us/point':>9s}"
          f" {'baseline s':>10s} {'speed-up':>8s}  AUTO-07p us/point (ratio)")
    for k, v in new.items():
        per = 1e6 * v["engine"] / max(v["points"], 1)
        line = f"{k:14s} {v['points']:6d} {v['wall']:8.3f} {v['engine']:9.3f} {per:9.0f}"
        if old is not None and k in old:
            line += f" {old[k]['wall']:10.3f} {old[k]['wall'] / v['wall']:7.2f}x"
        else:
            line += f" {'-':>10s} {'-':>8s}"
        if k in AUTO_TIMES:
            t, n = AUTO_TIMES[k]
            line += f"  {1e6 * t / n:6.0f} ({per / (1e6 * t / n):.0f}x slower)"
        print(line + ("" if v["status"] == "ok" else f"  [{v['status']}]"))
    if old is not None:
        w_new = new["washer_fig3"]["wall"] + new["washer_fig4"]["wall"]
        w_old = old["washer_fig3"]["wall"] + old["washer_fig4"]["wall"]
        print(f"washer Fig 3 branch + Fig 4 Hopf curve: {w_old:.2f} s -> {w_new:.2f} s "
              f"({w_old / w_new:.1f}x faster)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
