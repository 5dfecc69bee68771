"""Ctrl-C stops every long computation at once and reaches the caller as
KeyboardInterrupt; inputs that would never let an integration end are refused first."""
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import washer
from washer.machine import kernel

ROOT = Path(__file__).resolve().parents[1]


def _env():
    return dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1")


# How soon after SIGINT the child must have exited. The interrupted calls run for minutes
# to hours (washer.simulate fig9 --t-end 1000: over 100 s), and an idle machine exits in
# 0.1-0.5 s; on a loaded 2-core machine the scheduler and the interpreter's teardown alone
# have taken over 1.5 s, so the bound tells "stopped at once" from "waited for the call"
# with room for load, not the idle figure.
PROMPT_EXIT_S = 10.0


# CPU time the child must have spent after printing `ready` before SIGINT is sent. What
# the child runs between the print and the long call takes microseconds, so 0.2 s of its
# CPU proves it is inside the call (the kernel's SIGINT handler installed). A wall-clock
# wait does not: on a loaded machine the child may not run at all for a second after the
# print, and a SIGINT that arrives before the call reaches Python's handler only, whose
# KeyboardInterrupt waits for the call to end (hours).
BUSY_CPU_S = 0.2


def _cpu_seconds(pid: int) -> float:
    """User + system CPU time of process pid so far (Linux: /proc/PID/stat)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _wait_busy(proc, seconds: float, timeout: float) -> None:
    """Return once proc has used `seconds` of CPU more than now; AssertionError if it
    ends first or takes longer than `timeout` of wall time."""
    start, t0 = _cpu_seconds(proc.pid), time.monotonic()
    while _cpu_seconds(proc.pid) - start < seconds:
        if proc.poll() is not None:
            raise AssertionError(f"the child ended right after getting ready: "
                                 f"{proc.stderr.read()[-2000:]}")
        if time.monotonic() - t0 > timeout:
            proc.kill()
            raise AssertionError(f"the child used under {seconds} s of CPU in {timeout} s")
        time.sleep(0.02)


def interrupt_after_ready(code: str, *, ready: str = "ready", timeout: float = 60.0,
                          cwd=None, args=None):
    """Run `code` (or `args`) in a child with Python's own SIGINT handler; once it prints
    `ready` and has then computed for BUSY_CPU_S of CPU time, send SIGINT and measure how
    long it takes to exit. Returns (seconds from SIGINT to exit, return code, stdout,
    stderr)."""
    cmd = args or [sys.executable, "-c",
                   "import signal; signal.signal(signal.SIGINT, signal.default_int_handler)\n"
                   + code]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=_env(), cwd=cwd)
    out_lines = []
    t_start = time.monotonic()
    while True:
        line = proc.stdout.readline()
        if not line:
            proc.wait()
            raise AssertionError(f"the child ended before '{ready}': {proc.stderr.read()}")
        out_lines.append(line)
        if ready in line:
            break
        if time.monotonic() - t_start > timeout:
            proc.kill()
            raise AssertionError("the child never got ready")
    _wait_busy(proc, BUSY_CPU_S, timeout)        # inside the long call now
    proc.send_signal(signal.SIGINT)
    t0 = time.monotonic()
    try:
        out, err = proc.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        raise AssertionError(f"Ctrl-C did not stop the child within 30 s: {err[-2000:]}")
    return time.monotonic() - t0, proc.returncode, "".join(out_lines) + out, err


@pytest.mark.parametrize("tout", [[np.nan], [0.0, np.inf], [np.inf], [0.0, 1.0, np.nan]])
def test_integrator_refuses_times_it_could_never_reach(model, tout):
    y0 = np.r_[model.static_equilibrium(), np.zeros(6)]
    t0 = time.monotonic()
    with pytest.raises(kernel.KernelError, match="non-finite"):
        kernel.integrate("fixed", "constant", 0.0, y0, model.P, tout, 1e-8, 1e-10)
    assert time.monotonic() - t0 < 1.0


def test_integrator_refuses_decreasing_times(model):
    y0 = np.r_[model.static_equilibrium(), np.zeros(6)]
    with pytest.raises(kernel.KernelError, match="decreasing times"):
        kernel.integrate("fixed", "constant", 0.0, y0, model.P, [1.0, 0.5], 1e-8, 1e-10)


def test_flow_refuses_a_nan_end_time(model):
    y0 = np.r_[model.static_equilibrium(), np.zeros(6)]
    with pytest.raises(kernel.KernelError, match="non-finite"):
        kernel.flow_variational(0.0, np.nan, y0, model.P)


_LONG_INTEGRATION = """
import numpy as np, washer
from washer.machine import kernel
m = washer.Model(washer.load_params())
y0 = np.r_[m.static_equilibrium(), np.zeros(6)]
print("ready", flush=True)
try:
    {call}
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
    raise
"""


@pytest.mark.parametrize("call", [
    'kernel.integrate("fixed", "constant", 0.0, y0, m.P, [1e9], 1e-10, 1e-12)',
    'kernel.flow_variational(0.0, 1e9, y0, m.P)',
])
def test_ctrl_c_stops_a_long_kernel_integration_at_once(call):
    # Without the kernel's check between steps, this integration runs for hours and
    # SIGINT waits for it (Python handles signals only between bytecodes).
    dt, rc, out, err = interrupt_after_ready(_LONG_INTEGRATION.format(call=call))
    assert "KeyboardInterrupt" in out, err
    assert rc != 0 and "KeyboardInterrupt" in err
    assert dt < PROMPT_EXIT_S, f"took {dt:.2f} s after SIGINT"


def test_request_interrupt_from_another_thread(model):
    y0 = np.r_[model.static_equilibrium(), np.zeros(6)]
    timer = threading.Timer(0.3, kernel.request_interrupt)
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        kernel.integrate("fixed", "constant", 0.0, y0, model.P, [1e9], 1e-10, 1e-12)
    assert time.monotonic() - t0 < 1.3
    timer.join()
    # The flag does not outlive the call it stopped: the next integration runs.
    Y, _, _ = kernel.integrate("fixed", "constant", 0.0, y0, model.P, [0.01], 1e-8, 1e-10)
    assert np.all(np.isfinite(Y))


# ------------------------------------------------------------------ the engine
DATA = Path(__file__).parent / "data"


def _ab(tmp_path):
    import shutil
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    return tmp_path / "c.ab"


class _CtrlCAtPoint:
    """A sink that plays the user pressing Ctrl-C when the n-th point arrives."""

    def __init__(self, n):
        self.n, self.seen = n, 0

    def begin(self, run):
        pass

    def branch_start(self, br):
        pass

    def point(self, lab, point):
        self.seen += 1
        if self.seen == self.n:
            raise KeyboardInterrupt

    def note(self, *a):
        pass

    def end(self, status, elapsed):
        pass


def test_run_raises_keyboard_interrupt_after_writing_the_files(tmp_path):
    """From Python, Ctrl-C is an exception, never a result a loop carries on with."""
    from washer.run import load, run
    c = _ab(tmp_path)
    with pytest.raises(KeyboardInterrupt) as err:
        run(c, verbose=False, sinks=[_CtrlCAtPoint(30)])
    assert "interrupted" in str(err.value)
    partial = err.value.branch
    rows = [r for b in load(tmp_path / "b.ab") for r in b]
    assert len(rows) == len(partial.rows) >= 29       # every point so far is in the file
    labels = [r.lab for r in rows if r.lab]
    assert [r.lab for r in load(tmp_path / "s.ab")] == labels
    # A loop over runs stops at the interrupt instead of starting the next one.
    started = []
    with pytest.raises(KeyboardInterrupt):
        for k in range(3):
            started.append(k)
            run(c, verbose=False, sinks=[_CtrlCAtPoint(5)], sv=f"loop{k}")
    assert started == [0]


def test_run_command_exits_130_on_ctrl_c(tmp_path, capsys):
    from washer.run import main
    import washer.auto.sinks as sinks
    c = _ab(tmp_path)
    real = sinks.ScreenSink.point
    calls = []

    def point(self, lab, pt):
        calls.append(1)
        if len(calls) == 20:
            raise KeyboardInterrupt
        return real(self, lab, pt)

    sinks.ScreenSink.point = point
    try:
        assert main([str(c)]) == 130
    finally:
        sinks.ScreenSink.point = real
    err = capsys.readouterr().err
    assert "interrupted" in err and "Saved as" not in err


def test_ctrl_c_stops_the_forced_washer_run_and_keeps_its_points(tmp_path):
    """python -m washer.run on the forced washer (shooting and collocation, kernel
    integrations inside): exit 130 at once, the b-file readable with the
    points so far, and every label of the b-file has its s-record."""
    import shutil
    from washer.run import load
    shutil.copy(ROOT / "auto_constants" / "c.washer.forced", tmp_path)
    code = ("import sys\nimport washer.auto.sinks as S\n"
            "real = S.ScreenSink.point\n"
            "def point(self, lab, pt):\n"
            "    real(self, lab, pt)\n"
            "    if lab.pt == 3: print('ready', flush=True)\n"
            "S.ScreenSink.point = point\n"
            "from washer.run import main\n"
            f"sys.exit(main([{str(tmp_path / 'c.washer.forced')!r}, 'NMX=400', 'UZSTOP={{}}']))\n")
    dt, rc, out, err = interrupt_after_ready(code, timeout=120)
    assert rc == 130, err
    assert dt < PROMPT_EXIT_S, f"took {dt:.2f} s"
    assert "interrupted" in err and "Traceback" not in err
    rows = [r for b in load(tmp_path / "b.washer.forced") for r in b]
    assert len(rows) >= 3
    labels = [r.lab for r in rows if r.lab]
    assert [r.lab for r in load(tmp_path / "s.washer.forced")] == labels
