"""A short run from the command line loads what it uses and nothing else: `python -m
washer.run c.ab` (an equilibrium branch of a Python user file, traced into C) imports
neither scipy nor the plotting, symbolic, table or cluster libraries, nor cffi's C parser
(the bridge's declarations come from the compile cache), nor the collocation code of the
other systems. Each of those, imported at module level somewhere on the path, costs such
a run a large part of its time (docs/speed.md)."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DATA = Path(__file__).parent / "data"

#: Packages a short equilibrium run must not import.
NOT_IMPORTED = ("scipy", "matplotlib", "sympy", "symengine", "pandas", "dask", "pycparser")
#: Modules of the engine an equilibrium run must not import (collocation: BVPs only).
NOT_IMPORTED_ENGINE = ("washer.cont.collocation", "washer.cont.systems.bvp",
                       "washer.cont.systems.periodic", "washer.cont.corrector_periodic")

#: `python -m washer.run ARGS` (runpy, as -m runs it), then the names in sys.modules and
#: the exit status into modules.json.
CHILD = """
import json, runpy, sys
status = 0
try:
    runpy.run_module("washer.run", run_name="__main__", alter_sys=True)
except SystemExit as exc:
    status = exc.code
with open("modules.json", "w") as f:
    json.dump({"status": status, "modules": sorted(sys.modules)}, f)
"""


def _run(folder: Path, *args: str) -> dict:
    env = dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1")
    proc = subprocess.run([sys.executable, "-c", CHILD, *args], cwd=folder, env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    return json.loads((folder / "modules.json").read_text())


def test_a_short_equilibrium_run_imports_only_what_it_uses(tmp_path):
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    # the first run in a compile cache compiles the traced func and writes cffi's modules
    # of the declarations (with cffi's parser): what every later run finds there
    assert _run(tmp_path, "c.ab")["status"] == 0
    report = _run(tmp_path, "c.ab")
    assert report["status"] == 0 and (tmp_path / "b.ab").stat().st_size > 0
    modules = set(report["modules"])
    assert "washer.cont.user_problem.user_files_traced" in modules
    assert "washer.cont.systems.equilibrium" in modules
    loaded = sorted(m for m in modules
                    if m.split(".")[0] in NOT_IMPORTED or m in NOT_IMPORTED_ENGINE)
    assert loaded == []
