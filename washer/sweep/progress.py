"""Progress of a sweep: points done, failures, rate, time left.

An injected object (as diffrax's progress meters): `NoProgress` in tests and
libraries, `TqdmProgress` (tqdm's own bar on stderr) on the command line. Off a
terminal (a log file, CI) the bar is still written, redrawn at most every
`LOG_INTERVAL` seconds so that a log is not flooded.
"""
from __future__ import annotations

import sys
import time

#: Seconds between redraws when stderr is not a terminal.
LOG_INTERVAL = 10.0


class NoProgress:
    """Counts, prints nothing."""

    def __init__(self, total: int, done: int = 0):
        self.total, self.done, self.failed, self.new = total, done, 0, 0
        self.t0 = time.perf_counter()

    def update(self, ok: int, failed: int) -> None:
        self.done += ok + failed
        self.new += ok + failed
        self.failed += failed

    def close(self) -> None:
        pass


class TqdmProgress(NoProgress):
    """tqdm's bar: points done of the total (resumed points count as done from the
    start), the rate of this run, time left, and the failures so far."""

    def __init__(self, total: int, done: int = 0, stream=None):
        super().__init__(total, done)
        from tqdm import tqdm
        stream = stream or sys.stderr
        tty = hasattr(stream, "isatty") and stream.isatty()
        if not tty:
            stream = _Lines(stream)      # a log gets one line per redraw, not one long line
        self.bar = tqdm(total=total, initial=done, file=stream, unit="point",
                        desc="sweep", dynamic_ncols=tty, ncols=None if tty else 100,
                        mininterval=0.1 if tty else LOG_INTERVAL, smoothing=0.1)
        self.bar.set_postfix(failed=0, refresh=False)

    def update(self, ok: int, failed: int) -> None:
        super().update(ok, failed)
        if failed:
            self.bar.set_postfix(failed=self.failed, refresh=False)
        self.bar.update(ok + failed)

    def close(self) -> None:
        self.bar.close()


class _Lines:
    """A stream for tqdm off a terminal: its carriage returns become new lines."""

    def __init__(self, stream):
        self.stream = stream

    def write(self, text: str) -> None:
        text = text.replace("\r", "\n")
        if text.strip():
            self.stream.write(text.lstrip("\n") + ("" if text.endswith("\n") else "\n"))

    def flush(self) -> None:
        self.stream.flush()


def make_progress(total: int, done: int, enabled: bool | None):
    """TqdmProgress when enabled (None: when stderr is a terminal), else NoProgress.
    Without tqdm installed (it is a dependency; a stripped install may lack it) there
    is no bar, never an error."""
    if enabled is None:
        enabled = sys.stderr.isatty()
    if enabled:
        try:
            return TqdmProgress(total, done)
        except ImportError:
            pass
    return NoProgress(total, done)
