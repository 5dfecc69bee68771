"""The sweep's command line: bad arguments are one line and their own exit code, quickly;
sizes are estimated before anything is enumerated; one writer per results folder;
a different spec into a used folder warns; Ctrl-C in --serial stops the sweep."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from washer.locks import output_lock
from washer.sizes import SizeError
from washer.sweep import SpecChangedWarning, parse_spec, run
from washer.sweep.cli import EXIT_LOCKED, EXIT_SCHEDULER, main
from washer.sweep.execute import SCHEDULER_TIMEOUT

ROOT = Path(__file__).resolve().parents[1]
SMALL = ROOT / "examples" / "sweep_small.toml"

#: A one-point stability study: the cheapest sweep there is.
TINY = """
[[study]]
name = "one"
sample = "grid"
kinds = ["stability"]
[study.vary]
C_p = [0.1]
"""


def _spec(tmp_path, text=TINY, name="tiny.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


@pytest.mark.parametrize("address", ["nonsense::", "tcp://host:notaport", "tcp://h:70000"])
def test_malformed_scheduler_address_is_one_line(tmp_path, capsys, address):
    t0 = time.monotonic()
    assert main([str(_spec(tmp_path)), "--scheduler", address, "--out",
                 str(tmp_path / "o")]) == EXIT_SCHEDULER
    assert time.monotonic() - t0 < 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("error: --scheduler") and "Traceback" not in err


# 5 s: Dask's connection timeout to a closed port is what it measures
@pytest.mark.slow
def test_unreachable_scheduler_is_one_line_within_seconds(tmp_path, capsys):
    t0 = time.monotonic()
    assert main([str(_spec(tmp_path)), "--scheduler", "tcp://127.0.0.1:9", "--out",
                 str(tmp_path / "o")]) == EXIT_SCHEDULER
    # The client waits SCHEDULER_TIMEOUT (5 s); Dask's default would wait 30 s. 20 s of wall
    # time tells the two apart even when a loaded machine stretches the 5 s wait fourfold.
    assert SCHEDULER_TIMEOUT < 20
    assert time.monotonic() - t0 < 20
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "no Dask scheduler answered" in err


@pytest.mark.parametrize("bad", ["file", "under_a_file"])
def test_unusable_out_is_refused_before_any_work(tmp_path, capsys, bad):
    f = tmp_path / "afile"
    f.write_text("x")
    out = f if bad == "file" else f / "sub"
    assert main([str(_spec(tmp_path)), "--serial", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {out}") and err.count("\n") == 1


def test_latin1_spec_names_file_line_and_byte(tmp_path, capsys):
    p = tmp_path / "l1.toml"
    p.write_bytes(b"# r\xe9glage\n" + TINY.encode())
    assert main([str(p), "--serial", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert f"{p}:1: byte 0xe9 is not UTF-8 text" in err


def test_huge_sweep_is_refused_with_its_estimate_before_enumerating(tmp_path):
    spec = parse_spec(TINY.replace("C_p = [0.1]", "C_p = {from = 0.0, to = 1.0, n = 4000}\n"
                                   "m_u = {from = 0.5, to = 2.0, n = 5000}"), "<huge>")
    t0 = time.monotonic()
    with pytest.raises(SizeError, match=r"<huge>: 20000000 points: needs about 20 GB of "
                                        r"memory .*--allow-large"):
        run(spec, serial=True, out=tmp_path / "o")
    assert time.monotonic() - t0 < 2
    assert not (tmp_path / "o" / "spec.toml").exists()


def test_huge_sweep_on_the_command_line(tmp_path, capsys):
    p = _spec(tmp_path, TINY.replace('kinds = ["stability"]', 'kinds = ["response"]')
              + "[study.response]\nt_end = 1e6\n")
    assert main([str(p), "--serial", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "1 points: needs about" in err and "of computing" in err and "--allow-large" in err


def test_second_sweep_into_one_folder_is_refused(tmp_path, capsys):
    out = tmp_path / "o"
    out.mkdir()
    with output_lock(out, "sweep"):
        assert main([str(_spec(tmp_path)), "--serial", "--out", str(out)]) == EXIT_LOCKED
    err = capsys.readouterr().err
    assert f"process {os.getpid()}" in err and "being written by" in err


def test_a_different_spec_into_a_used_folder_warns(tmp_path, capsys):
    out = tmp_path / "o"
    run(_spec(tmp_path), serial=True, out=out, plot=False)
    with pytest.warns(SpecChangedWarning, match="holds the results of another spec"):
        df = run(_spec(tmp_path, TINY.replace("[0.1]", "[0.2]"), "other.toml"), serial=True,
                 out=out, plot=False)
    assert list(df["C_p"]) == [0.2]
    # The same spec again: no warning.
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error", SpecChangedWarning)
        run(_spec(tmp_path, TINY.replace("[0.1]", "[0.2]"), "other.toml"), serial=True,
            out=out, plot=False)
    # On the command line, one 'warning:' line.
    assert main([str(_spec(tmp_path)), "--serial", "--out", str(out), "--no-plot",
                 "--no-progress"]) == 0
    assert "warning: " in capsys.readouterr().err


def test_progress_bar_is_shown_off_a_terminal(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "washer.sweep", str(_spec(tmp_path)),
                           "--serial", "--no-plot", "--out", str(tmp_path / "o")],
                          capture_output=True, text=True, timeout=120,
                          env=dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1"))
    assert proc.returncode == 0, proc.stderr
    assert "1/1" in proc.stderr and "point" in proc.stderr       # tqdm's bar, in a pipe


CRITICAL = """
batch_size = 1
[[study]]
name = "crit"
sample = "grid"
kinds = ["critical"]
[study.vary]
m_u = {from = 0.5, to = 2.0, n = 12}
[study.critical]
parameter = "C_p"
from = 0.0
to = 3.0
"""


@pytest.mark.slow
def test_ctrl_c_stops_a_serial_sweep_and_records_nothing_wrong(tmp_path):
    """Ctrl-C in --serial: exit 130 within a second or two, only finished points in the
    parts (the point in flight is not recorded as a result), and a re-run resumes."""
    import pandas as pd
    from washer.sweep.results import ResultStore
    spec = _spec(tmp_path, CRITICAL)
    out = tmp_path / "o"
    env = dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1")
    code = ("import signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler)\n"
            "from washer.sweep.cli import main; sys.exit(main(sys.argv[1:]))")
    proc = subprocess.Popen([sys.executable, "-c", code, str(spec), "--serial", "--no-plot",
                             "--no-progress", "--out", str(out)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not list((out / "parts").glob("part-*.parquet")) and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(0.05)                                  # inside the next point
    proc.send_signal(signal.SIGINT)
    t0 = time.monotonic()
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert time.monotonic() - t0 < 3, "Ctrl-C took too long"
    assert "interrupted" in err and "Traceback" not in err
    parts = ResultStore(out).read_parts()
    assert 1 <= len(parts) < 12
    assert (parts["status"] == "ok").all(), parts[["status", "error"]]
    # The re-run computes only the rest, and what was kept equals an uninterrupted sweep.
    df = run(spec, serial=True, out=out, plot=False)
    assert len(df) == 12 and df["id"].is_unique
    fresh = run(spec, serial=True, out=tmp_path / "fresh", plot=False).set_index("id")
    cols = ["crit_value", "crit_source"]
    assert fresh.loc[parts["id"], cols].equals(parts.set_index("id")[cols])


@pytest.mark.slow
def test_local_cluster_announces_its_dashboard(tmp_path, caplog):
    import logging
    caplog.set_level(logging.INFO, logger="washer.sweep")
    run(_spec(tmp_path), n_workers=1, out=tmp_path / "o", plot=False)
    msgs = [r.getMessage() for r in caplog.records]
    from washer.sweep.execute import _has_bokeh
    if _has_bokeh():      # Dask serves the dashboard: its link is announced
        assert any(m.startswith("Dask dashboard") and "http://" in m for m in msgs), msgs
    else:                 # no dashboard without bokeh (an optional extra): the hint instead
        assert any("local Dask workers started" in m and "washer[dashboard]" in m
                   for m in msgs), msgs


def test_ctrl_c_after_the_last_point_is_exit_130_without_a_traceback(tmp_path, monkeypatch,
                                                                       capsys):
    """Ctrl-C while the table is consolidated (every point done): the parts are kept, the
    command says so in one line and exits 130."""
    from washer.sweep import results

    def interrupted(self, *a, **k):
        raise KeyboardInterrupt
    monkeypatch.setattr(results.ResultStore, "consolidate", interrupted)
    out = tmp_path / "o"
    assert main([str(_spec(tmp_path)), "--serial", "--no-plot", "--no-progress",
                 "--out", str(out)]) == 130
    err = capsys.readouterr().err
    assert "interrupted" in err and "Traceback" not in err
    assert list((out / "parts").glob("part-*.parquet"))
