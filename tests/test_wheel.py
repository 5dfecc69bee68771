"""A user's install: sdist -> wheel -> fresh virtual environment -> runs in another folder.

Slow (the wheel compiles the kernel, about a minute) but part of the default run: CI
runs the README's `python -m pytest -q`, and a packaging gap (a subpackage or the
constants files missing from the wheel, a path into the source checkout) only shows
in an installed copy. The build runs on a copy of the tree in a temporary folder, so
the checkout gets no build/ or egg-info litter; pip's build isolation fetches
setuptools and cffi as any user's `pip install .` does.
"""
import os
import shutil
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: What a source distribution is built from (MANIFEST.in picks the files inside).
SOURCES = ("setup.py", "pyproject.toml", "build.py", "MANIFEST.in", "README.md",
           "washer", "csrc", "auto_constants", "examples", "tests", "docs")
#: The stripped kernel is ~0.5 MB; unstripped it was ~30 MB.
MAX_KERNEL_BYTES = 5_000_000


def _sh(args, cwd, timeout=600, ok=True):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    p = subprocess.run([str(a) for a in args], cwd=cwd, env=env, capture_output=True,
                       text=True, timeout=timeout)
    if ok:
        assert p.returncode == 0, f"{args} failed ({p.returncode}):\n{p.stdout[-3000:]}\n{p.stderr[-3000:]}"
    return p


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """(source copy, sdist, wheel) built from a copy of the working tree."""
    tmp = tmp_path_factory.mktemp("wheel")
    src = tmp / "src"
    src.mkdir()
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.so", "*.egg-info", "build", "out")
    for name in SOURCES:
        s = ROOT / name
        if s.is_dir():
            shutil.copytree(s, src / name, ignore=ignore)
        else:
            shutil.copy2(s, src / name)
    _sh([sys.executable, "setup.py", "-q", "sdist", "-d", tmp / "dist"], src)
    sdist = next((tmp / "dist").glob("washer-*.tar.gz"))
    _sh([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", tmp / "wheels", sdist],
        tmp, timeout=900)
    wheel = next((tmp / "wheels").glob("washer-*.whl"))
    return src, sdist, wheel


@pytest.mark.slow
def test_sdist_has_the_tests_and_their_data(built):
    src, sdist, _ = built
    with tarfile.open(sdist) as tf:
        names = {n.split("/", 1)[1] for n in tf.getnames() if "/" in n}
    expected = {"build.py", "tests/conftest.py", "tests/ab_exact.py",
                "csrc/washer_api.h", "auto_constants/c.washer", "docs/auto_compatibility.md"}
    expected |= {str(p.relative_to(src)) for p in (src / "tests" / "data").rglob("*") if p.is_file()}
    assert not expected - names, f"missing from the sdist: {sorted(expected - names)[:10]}"


@pytest.mark.slow
def test_wheel_has_every_subpackage_the_constants_and_a_stripped_kernel(built):
    src, _, wheel = built
    with zipfile.ZipFile(wheel) as zf:
        info = {i.filename: i.file_size for i in zf.infolist()}
    packages = {str(p.parent.relative_to(src)) for p in (src / "washer").rglob("__init__.py")}
    missing = [p for p in packages if f"{p}/__init__.py" not in info]
    assert not missing, f"subpackages missing from the wheel: {missing}"
    # The C the engine compiles at run time (the user files' bridge, the correctors' C and
    # the headers they include) is read beside its module: every such file ships.
    c_files = {str(p.relative_to(src)) for e in ("*.c", "*.h") for p in (src / "washer").rglob(e)}
    assert "washer/cont/user_problem/user_files_bridge.c" in c_files
    assert not c_files - set(info), f"C files missing from the wheel: {sorted(c_files - set(info))}"
    shipped = {p.name for p in (src / "auto_constants").glob("c.*")}
    in_wheel = {Path(n).name for n in info if n.startswith("washer/auto_constants/")}
    assert shipped and shipped == in_wheel
    examples = {p.name for p in (src / "examples").glob("*.toml")} | {"ab.py", "c.ab"}
    assert "sweep_small.toml" in examples
    assert examples <= {Path(n).name for n in info if n.startswith("washer/examples/")}
    kernels = [n for n in info if n.startswith("washer/_kernel") and n.endswith(".so")]
    assert len(kernels) == 1 and info[kernels[0]] < MAX_KERNEL_BYTES, kernels
    # the continuation engine's compiled linear algebra (washer.cont.reduction)
    assert len([n for n in info if n.startswith("washer/_cont") and n.endswith(".so")]) == 1
    assert "washer/data/reference.toml" in info
    assert not [n for n in info if "__pycache__" in n or n.startswith("tests/")]


@pytest.mark.slow
def test_installed_wheel_runs_in_another_folder(built, tmp_path):
    _, _, wheel = built
    venv = tmp_path / "venv"
    # System site packages: numpy, scipy, matplotlib and cffi without a download.
    _sh([sys.executable, "-m", "venv", "--system-site-packages", venv], tmp_path)
    py = venv / "bin" / "python"
    # --ignore-installed: install into the venv even though the developer's editable
    # washer is visible through the system site packages (and never touch that one).
    _sh([py, "-m", "pip", "install", "-q", "--no-deps", "--no-index", "--ignore-installed",
         wheel], tmp_path)
    work = tmp_path / "work"
    work.mkdir()
    where = _sh([py, "-c", "import washer, washer.auto, washer.cont, washer.plots, washer.paper;"
                 "from washer.paper import runs; import washer.simulate;"
                 "print(washer.__file__); print(runs.CONSTANTS_DIR);"
                 "m = washer.Model(washer.load_params()); print(m.static_equilibrium()[2])"],
                work).stdout.split("\n")
    assert Path(where[0]).is_relative_to(venv), f"imported {where[0]}, not the installed wheel"
    assert Path(where[1]).is_relative_to(venv) and (Path(where[1]) / "c.washer").is_file()
    assert 0.3 < float(where[2]) < 0.5                          # static height z (m)

    out = _sh([py, "-m", "washer.run", "--copy-examples", "ex"], work).stdout
    assert (work / "ex" / "c.washer").is_file() and "copied" in out
    assert (work / "ex" / "sweep_small.toml").is_file() and (work / "ex" / "ab.py").is_file()
    res = _sh([py, "-m", "washer.run", "c.washer", "NMX=4"], work / "ex")
    rows = [l for l in (work / "ex" / "b.washer").read_text().splitlines()
            if not l.startswith("   0")]
    assert len(rows) == 4, res.stdout[-2000:]

    assert "usage" in _sh([py, "-m", "washer.simulate", "--help"], work).stdout.lower()
    gen = _sh([py, "-m", "washer.codegen", "--check"], work, ok=False)
    assert gen.returncode == 2 and "source checkout" in gen.stderr
