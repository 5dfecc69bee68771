"""Cost estimates of a job before it starts, and the refusal of absurd ones.

A typo (n = 10**7 sweep points, t_end = 1e6 s, NTST = 100000) should not start
hours of work or a MemoryError minutes later: each front end estimates memory
and time from its inputs first, and refuses a job above the limits below with
the estimate in the message, unless the user says it is meant (`allow_large`,
on the command lines `--allow-large`).
"""
from __future__ import annotations

import math

#: Refuse a job that needs more memory than this without being asked (bytes).
MAX_BYTES = 2e9
#: ... or that is expected to take longer than this (s of wall time, one core).
MAX_SECONDS = 4 * 3600.0

#: Memory of one enumerated sweep point (its inputs, options and id as Python
#: objects, measured with tracemalloc on the shipped specs: ~1 kB).
BYTES_PER_SWEEP_POINT = 1000
#: One stored sample of a time response: t and 12 states as float64, the CSV text
#: written from it (~13 x 25 characters) and the plots' copies.
BYTES_PER_SAMPLE = 13 * 8 + 13 * 25 + 200
#: Wall time per simulated second with the kernel's DOPRI5 at rtol = 1e-8, one core
#: (the reference set at Omega = 10 Hz: ground frame ~450 steps/s of model time at
#: ~25000 steps/s; the averaged rotating frame ~750 steps/s at ~2200 steps/s).
WALL_PER_SIM_SECOND = {"fixed": 0.02, "rotating": 0.35}
#: Sparse collocation Jacobian and its LU factors: ~12 bytes per stored entry
#: (value and index), about 3 times the Jacobian's entries with fill-in and copies.
BYTES_PER_JACOBIAN_ENTRY = 12 * 3


class SizeError(ValueError):
    """A job far larger than a typical one; the message gives the estimate."""


def _fmt_bytes(b: float) -> str:
    for unit, scale in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if b >= scale:
            return f"{b / scale:.3g} {unit}"
    return f"{b:.0f} bytes"


def _fmt_seconds(s: float) -> str:
    if s >= 86400:
        return f"{s / 86400:.3g} days"
    if s >= 3600:
        return f"{s / 3600:.3g} hours"
    if s >= 60:
        return f"{s / 60:.3g} minutes"
    return f"{s:.3g} s"


def check(what: str, *, nbytes: float = 0.0, seconds: float = 0.0, allow: bool = False,
          how: str = "pass --allow-large") -> None:
    """SizeError when `nbytes` or `seconds` exceed the limits and `allow` is not set.
    `what` names the job and its inputs ("SPEC: 20000000 points")."""
    if allow:
        return
    over = []
    if not nbytes <= MAX_BYTES:
        over.append(f"about {_fmt_bytes(nbytes)} of memory (limit {_fmt_bytes(MAX_BYTES)})")
    if not seconds <= MAX_SECONDS:
        over.append(f"about {_fmt_seconds(seconds)} of computing on one core (limit "
                    f"{_fmt_seconds(MAX_SECONDS)})")
    if over:
        raise SizeError(f"{what}: needs {' and '.join(over)}; if this is meant, {how}")


def response_cost(t_end: float, n_samples: float, system: str = "fixed",
                  rtol: float = 1e-8) -> tuple[float, float]:
    """(bytes, seconds) of one time response of t_end seconds with n_samples outputs.
    Steps grow like rtol**(-1/5) for a 5th-order method."""
    per_s = WALL_PER_SIM_SECOND.get(system, max(WALL_PER_SIM_SECOND.values()))
    scale = (1e-8 / rtol) ** 0.2 if rtol > 0 else math.inf
    return n_samples * BYTES_PER_SAMPLE, t_end * per_s * scale


def collocation_bytes(ntst: int, ncol: int, ndim: int) -> float:
    """Memory of a periodic-orbit / BVP Newton step on NTST x NCOL collocation points
    in NDIM dimensions (the sparse Jacobian's blocks: NCOL*NDIM rows by (NCOL+1)*NDIM
    columns per mesh interval)."""
    return float(ntst) * ncol * ndim * (ncol + 1) * ndim * BYTES_PER_JACOBIAN_ENTRY


#: Rough wall time of one sweep point per kind of computation (s, one core; the
#: response's own estimate replaces this entry).
SECONDS_PER_POINT = {"stability": 0.05, "critical": 2.0}


def sweep_cost(spec) -> tuple[int, float, float]:
    """(points, bytes, seconds) of a washer.sweep Spec, from its studies alone (the
    points are not enumerated: that is what a huge n would make impossible)."""
    n_total, nbytes, seconds = 0, 0.0, 0.0
    for st in spec.studies:
        if st.sample == "grid":
            n = math.prod(len(a.values) for a in st.axes)
        else:
            n = st.n
        n_total += n
        nbytes += n * BYTES_PER_SWEEP_POINT
        per_point = 0.0
        for kind in st.kinds:
            if kind == "response":
                o = st.options["response"]
                b, s = response_cost(o["t_end"], o["t_end"] * o["samples_per_s"],
                                     o["system"], o["rtol"])
                per_point += s
                nbytes = max(nbytes, n * BYTES_PER_SWEEP_POINT + b)   # one response at a time
            else:
                per_point += SECONDS_PER_POINT.get(kind, 1.0)
        seconds += n * per_point
    return n_total, nbytes, seconds
