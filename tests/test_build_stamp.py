"""Each compiled module is tied to the sources it was built from (washer.build_stamp):
the stamp build.py compiled in is the hash the import computes, and a checkout whose
csrc/ differs by one byte refuses the module with the command that rebuilds it.
Nothing is compiled here: the sources are copied and changed, the built modules are
the checkout's."""
import os
import shutil
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

from washer import build_stamp
from washer.cont import reduction
from washer.machine import kernel

ROOT = Path(__file__).resolve().parent.parent
MODULES = {"washer._kernel": (kernel.ffi, kernel.lib, "csrc/kernel.cpp"),
           "washer._cont": (reduction.ffi, reduction.lib, "csrc/cont/reduce.cpp")}


def flip_one_byte(path: Path) -> None:
    data = bytearray(path.read_bytes())
    data[len(data) // 2] ^= 0x01
    path.write_bytes(bytes(data))


@pytest.fixture
def sources(tmp_path):
    """A copy of the checkout's csrc/ under a root of its own."""
    shutil.copytree(ROOT / "csrc", tmp_path / "csrc",
                    ignore=shutil.ignore_patterns("*.o", "__pycache__"))
    return tmp_path


@pytest.mark.parametrize("module", sorted(MODULES))
def test_the_built_stamp_is_the_hash_of_the_checkouts_sources(module):
    ffi, lib, _ = MODULES[module]
    stamp = ffi.string(getattr(lib, build_stamp.FUNCTIONS[module])()).decode()
    assert stamp == build_stamp.sources_hash(module, ROOT)
    assert len(stamp) == 64 and int(stamp, 16) >= 0


@pytest.mark.parametrize("module", sorted(MODULES))
def test_one_changed_byte_makes_the_module_stale_and_the_other_not(module, sources):
    ffi, lib, changed = MODULES[module]
    build_stamp.check(module, ffi, lib, sources)            # an exact copy: accepted
    flip_one_byte(sources / changed)
    with pytest.raises(ImportError) as err:
        build_stamp.check(module, ffi, lib, sources)
    msg = str(err.value)
    assert msg.startswith(f"{module} was built from other sources than the ones in ")
    assert "python build.py" in msg and "pip install -e ." in msg
    (other,) = set(MODULES) - {module}
    build_stamp.check(other, *MODULES[other][:2], sources)  # its own sources are unchanged


def test_which_files_count(sources):
    """A new header counts; a compiler's object file or an editor's backup does not."""
    before = build_stamp.sources_hash("washer._kernel", sources)
    (sources / "csrc" / "kernel.o").write_bytes(b"\0object")
    (sources / "csrc" / "kernel.cpp~").write_text("backup")
    assert build_stamp.sources_hash("washer._kernel", sources) == before
    (sources / "csrc" / "extra.h").write_text("#pragma once\n")
    assert build_stamp.sources_hash("washer._kernel", sources) != before
    names = [p.relative_to(sources).as_posix()
             for p in build_stamp.source_files("washer._kernel", sources)]
    assert names == sorted(names) and not any(n.startswith("csrc/cont/") for n in names)
    assert "csrc/generated/washer_model.cpp" in names


def test_a_module_without_a_stamp_is_stale_and_an_installed_one_is_not_checked(tmp_path,
                                                                               sources):
    old = SimpleNamespace()                      # built before modules carried a stamp
    with pytest.raises(ImportError, match="carries no stamp.*python build.py cont"):
        build_stamp.check("washer._cont", reduction.ffi, old, sources)
    installed = tmp_path / "site-packages"       # no csrc/ beside the package
    installed.mkdir()
    build_stamp.check("washer._cont", reduction.ffi, old, installed)


@pytest.mark.parametrize("module, importer", [("washer._cont", "washer.cont.reduction"),
                                              ("washer._kernel", "washer.machine.kernel")])
def test_importing_a_stale_module_fails_with_the_rebuild_command(module, importer, sources):
    """The check runs at import: a copy of the package with the checkout's compiled
    modules, beside a csrc/ with one byte changed."""
    shutil.copytree(ROOT / "washer", sources / "washer",
                    ignore=shutil.ignore_patterns("__pycache__"))
    flip_one_byte(sources / MODULES[module][2])
    env = dict(os.environ, PYTHONPATH=str(sources), OMP_NUM_THREADS="1")
    r = subprocess.run([sys.executable, "-c", f"import {importer}"], env=env,
                       capture_output=True, text=True, timeout=120, cwd=sources)
    assert r.returncode != 0
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith(f"ImportError: {module} was built from other sources than the ones "
                           f"in {sources / 'csrc'}")
    assert "python build.py" in last
