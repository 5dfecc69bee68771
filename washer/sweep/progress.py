"""Progress of a sweep: points done, failures, rate, time left.

An injected object (as diffrax's progress meters): `NoProgress` in tests and
libraries, `TextProgress` on a terminal (one line on stderr, redrawn).
"""
from __future__ import annotations

import sys
import time


class NoProgress:
    """Counts, prints nothing."""

    def __init__(self, total: int, done: int = 0):
        self.total, self.done, self.failed, self.new = total, done, 0, 0
        self.t0 = time.perf_counter()

    def update(self, ok: int, failed: int) -> None:
        self.done += ok + failed
        self.new += ok + failed
        self.failed += failed
        self.draw()

    @property
    def rate(self) -> float:
        """Points per second computed in this run."""
        dt = time.perf_counter() - self.t0
        return self.new / dt if dt > 0 else 0.0

    def line(self) -> str:
        rate = self.rate
        left = (self.total - self.done) / rate if rate > 0 else float("nan")
        return (f"{self.done}/{self.total} points, {self.failed} failed, {rate:.1f} points/s, "
                f"{time.perf_counter() - self.t0:.0f} s elapsed" +
                (f", ~{left:.0f} s left" if left == left and self.done < self.total else ""))

    def draw(self) -> None:
        pass

    def close(self) -> None:
        pass


class TextProgress(NoProgress):
    """A one-line bar on `stream` (stderr): [#####     ] 12/40 points, 1 failed, 3.2 points/s."""

    WIDTH = 30

    def __init__(self, total: int, done: int = 0, stream=None):
        super().__init__(total, done)
        self.stream = stream or sys.stderr
        self.draw()

    def draw(self) -> None:
        frac = self.done / self.total if self.total else 1.0
        bar = "#" * int(self.WIDTH * frac)
        self.stream.write(f"\r[{bar:<{self.WIDTH}}] {self.line()}   ")
        self.stream.flush()

    def close(self) -> None:
        self.stream.write("\n")
        self.stream.flush()


def make_progress(total: int, done: int, enabled: bool | None):
    """TextProgress when enabled (None: when stderr is a terminal), else NoProgress."""
    if enabled is None:
        enabled = sys.stderr.isatty()
    return TextProgress(total, done) if enabled else NoProgress(total, done)
