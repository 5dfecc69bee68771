"""Two runs writing the same output names: the second stops at once and names the first."""
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from washer.locks import LockedError, output_lock

DATA = Path(__file__).parent / "data"
ROOT = Path(__file__).resolve().parents[1]


def _ab(tmp_path):
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    return tmp_path / "c.ab"


def test_second_run_of_one_constants_file_stops_and_names_the_first(tmp_path, capsys):
    from washer.run import EXIT_LOCKED, main
    c = _ab(tmp_path)
    assert main([str(c)]) == 0
    before = (tmp_path / "b.ab").read_bytes()
    capsys.readouterr()
    with output_lock(tmp_path, "ab"):                 # the first run, still writing
        t0 = time.monotonic()
        assert main([str(c)]) == EXIT_LOCKED
        assert time.monotonic() - t0 < 5               # at once, not after a computation
    err = capsys.readouterr().err
    assert f"process {os.getpid()}" in err and "b.ab, s.ab, d.ab" in err
    assert (tmp_path / "b.ab").read_bytes() == before  # nothing of ours touched
    # Another name in the same folder is free; and once the first ends, so is this one.
    assert main([str(c), "sv=other"]) == 0
    assert main([str(c)]) == 0
    assert not (tmp_path / ".ab.lock").exists()


def test_lock_of_a_killed_holder_does_not_block(tmp_path):
    code = ("import sys, time; sys.path.insert(0, %r)\n"
            "from washer.locks import output_lock\n"
            "with output_lock(%r, 'x'):\n    print('held', flush=True); time.sleep(60)\n"
            % (str(ROOT), str(tmp_path)))
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "held"
    with pytest.raises(LockedError, match=f"process {proc.pid} on"):
        with output_lock(tmp_path, "x"):
            pass
    proc.kill()
    proc.wait()
    with output_lock(tmp_path, "x"):                   # the file is left, the lock is not
        pass


def test_lock_file_is_not_followed_when_it_is_a_link(tmp_path):
    victim = tmp_path / "victim"
    victim.write_text("precious")
    (tmp_path / ".x.lock").symlink_to(victim)
    with pytest.raises(LockedError, match="cannot create the lock"):
        with output_lock(tmp_path, "x"):
            pass
    assert victim.read_text() == "precious"
