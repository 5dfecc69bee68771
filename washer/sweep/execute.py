"""Running a sweep: points -> batches -> executor -> part files -> one table.

    from washer.sweep import run
    df = run("examples/sweep_small.toml", out="out/small")            # LocalCluster, one worker a core
    df = run(spec, client=Client("tcp://host:8786"), out="out/big")    # an existing Dask cluster
    df = run(spec, serial=True, out="out/debug")                      # in this process

The unit of work is a batch of points (`tasks.compute_batch`, a plain function
of plain data); the driver writes each finished batch as a part file, so a
re-run with the same spec and folder computes only what is missing.
"""
from __future__ import annotations

import logging
import math
import os
import warnings
from pathlib import Path

import pandas as pd

from washer import sizes
from washer.atomic import check_folder
from washer.locks import output_lock

from washer.sweep import tasks
from washer.sweep.points import base_data, input_columns, make_points
from washer.sweep.progress import make_progress
from washer.sweep.results import ResultStore, units_for
from washer.sweep.spec import Spec, load_spec

#: Batches per worker when the batch size is automatic: a few, so that a slow
#: batch does not idle the other workers at the end, and few enough that task
#: overhead (~1 ms each on Dask) and part files stay negligible.
BATCHES_PER_WORKER = 4
#: Largest automatic batch: bounds what an interruption loses.
MAX_AUTO_BATCH = 50


#: Seconds to wait for a Dask scheduler given by its address.
SCHEDULER_TIMEOUT = 5


class SchedulerError(ConnectionError):
    """No Dask scheduler at the given address (or the address is malformed)."""


def check_address(address: str) -> str:
    """A Dask scheduler address, 'tcp://HOST:PORT' (or tls://, ws://, wss://, ucx://,
    inproc://) or 'HOST:PORT'; SchedulerError naming what is wrong."""
    import re
    m = re.fullmatch(r"(?:(tcp|tls|ws|wss|ucx|inproc)://)?(\[[0-9a-fA-F:]+\]|[\w.-]+)"
                     r"(?::(\d+))?/?", address.strip())
    if not m or m.group(1) != "inproc" and m.group(3) is None:
        raise SchedulerError(f"--scheduler {address!r}: expected a Dask scheduler address "
                             "like tcp://10.0.0.5:8786")
    if m.group(3) is not None and not 0 < int(m.group(3)) < 65536:
        raise SchedulerError(f"--scheduler {address!r}: port {m.group(3)} is not 1..65535")
    return address.strip()


class connect:
    """A Client of the scheduler at `address`, closed at the end; SchedulerError in
    SCHEDULER_TIMEOUT seconds when nobody answers."""

    def __init__(self, address: str):
        self.address = check_address(address)

    def __enter__(self):
        from distributed import Client
        try:
            self.client = Client(self.address, timeout=SCHEDULER_TIMEOUT)
        except (OSError, TimeoutError) as exc:
            reason = str(exc).split("\n")[0] or type(exc).__name__
            raise SchedulerError(f"--scheduler {self.address}: no Dask scheduler answered "
                                 f"within {SCHEDULER_TIMEOUT} s ({reason[:160]})") from None
        return self.client

    def __exit__(self, *exc):
        self.client.close()


class SweepInterrupted(KeyboardInterrupt):
    """The sweep was interrupted; finished batches are kept (re-run to resume)."""


def run(spec, client=None, *, out=None, serial: bool = False, n_workers: int | None = None,
        batch_size: int | None = None, progress: bool | None = False, plot: bool = True,
        retry_failed: bool = False, allow_large: bool = False) -> pd.DataFrame:
    """Run (or resume) a sweep; returns the consolidated table (one row per point).

    spec: a `Spec` or a path to a spec TOML. client: a `distributed.Client` or a
    scheduler's address (checked after the spec; SchedulerError when nobody answers
    within SCHEDULER_TIMEOUT) (then n_workers is ignored); without one a `LocalCluster` is started with
    `n_workers` processes (default: one per core), one thread each, and closed
    at the end; serial=True computes in this process. out: the results folder
    (default out/sweep/<spec name>). batch_size: points per task (default: the
    spec's, else automatic). progress: a bar on stderr (None: on a terminal).
    plot: write the maps at the end (`washer.sweep.plots`). retry_failed:
    recompute points recorded as failed. allow_large: run a sweep whose estimated
    memory or time exceeds washer.sizes' limits (else SizeError with the estimate).

    Another sweep writing into `out` raises washer.locks.LockedError; a spec other
    than the one `out` holds gives a SpecChangedWarning (its points are computed
    beside the old ones, the table holds the new spec's). Ctrl-C raises
    SweepInterrupted once the finished batches are saved."""
    if not isinstance(spec, Spec):
        spec = load_spec(spec)
    n_points, nbytes, seconds = sizes.sweep_cost(spec)
    sizes.check(f"{spec.source}: {n_points} points", nbytes=nbytes, seconds=seconds / max(
        1, 1 if serial else (n_workers or os.cpu_count() or 1)), allow=allow_large,
        how="pass --allow-large (run(..., allow_large=True)) or reduce the studies' n")
    if out is None:
        out = Path("out/sweep") / Path(spec.source).name.removesuffix(".toml")
    check_folder(out)
    with output_lock(out, "sweep", what=f"the sweep results in {out}"):
        if isinstance(client, str):
            with connect(client) as c:
                return _run_locked(spec, c, Path(out), serial, n_workers, batch_size,
                                   progress, plot, retry_failed)
        return _run_locked(spec, client, Path(out), serial, n_workers, batch_size, progress,
                           plot, retry_failed)


class SpecChangedWarning(UserWarning):
    """A results folder re-used with another spec."""


def _run_locked(spec, client, out, serial, n_workers, batch_size, progress, plot,
                retry_failed) -> pd.DataFrame:
    store = ResultStore(out, units_for(spec))
    old_spec = out / "spec.toml"
    if old_spec.is_file() and old_spec.read_text(errors="replace") != spec.text:
        warnings.warn(f"{out} holds the results of another spec (its spec.toml differs from "
                      f"{spec.source}): that spec.toml is replaced; points both specs share "
                      "are not recomputed; use another --out to keep them apart",
                      SpecChangedWarning, stacklevel=3)
    points = make_points(spec)
    ids = [p["id"] for p in points]
    store.prepare(spec.text, spec.source, ids)
    done = store.done(retry_failed) & set(ids)
    todo = [p for p in points if p["id"] not in done]
    base = base_data(spec)
    columns = ["id", "study", "index"] + input_columns(spec) + ["status", "error"]

    if serial:
        workers = 1
    elif client is not None:
        workers = max(1, len(client.scheduler_info().get("workers", {})))
    else:
        workers = n_workers or os.cpu_count() or 1
    size = batch_size or spec.batch_size or _auto_batch(len(todo), workers)
    batches = _batches(todo, size)
    bar = make_progress(len(points), len(done), progress)
    try:
        if not batches:
            pass
        elif serial:
            for b in batches:
                _finish(store, bar, tasks.compute_batch(b, base))
        elif client is not None:
            _run_dask(client, batches, base, store, bar)
        else:
            with _local_client(workers) as c:
                _run_dask(c, batches, base, store, bar)
    except KeyboardInterrupt:
        bar.close()
        store.consolidate(ids, columns)
        raise SweepInterrupted(f"interrupted: {bar.done} of {len(points)} points kept in "
                               f"{store.folder}; run the same command again to resume") from None
    bar.close()
    df = store.consolidate(ids, columns)
    if plot:
        from washer.sweep import plots
        try:
            plots.plot_dir(store.folder, spec=spec)
        except Exception as exc:  # noqa: BLE001 - a figure never loses the results
            logging.getLogger(__name__).warning("plots failed: %s", exc)
    return df


def _auto_batch(n_todo: int, workers: int) -> int:
    return max(1, min(MAX_AUTO_BATCH, math.ceil(n_todo / (BATCHES_PER_WORKER * workers))))


def _batches(points: list[dict], size: int) -> list[list[dict]]:
    """Consecutive chunks of `size` points, never mixing studies (similar costs per batch)."""
    out: list[list[dict]] = []
    for p in points:
        if out and len(out[-1]) < size and out[-1][0]["study"] == p["study"]:
            out[-1].append(p)
        else:
            out.append([p])
    return out


def _finish(store: ResultStore, bar, rows: list[dict]) -> None:
    store.write_part(rows)
    failed = sum(r["status"] != "ok" for r in rows)
    bar.update(len(rows) - failed, failed)


def _failed_rows(batch: list[dict], message: str) -> list[dict]:
    """Rows for points whose task died (worker lost, ...): inputs, NaN outputs, the error."""
    rows = []
    for p in batch:
        row = {"id": p["id"], "study": p["study"], "index": p["index"], **p["inputs"]}
        for kind in p["kinds"]:
            row.update(tasks.empty_outputs(kind))
        row.update(status="failed", error=message, elapsed_s=math.nan)
        rows.append(row)
    return rows


def _run_dask(client, batches, base, store, bar) -> None:
    from distributed import as_completed
    futures = {client.submit(tasks.compute_batch, b, base, pure=False): b for b in batches}
    try:
        for fut in as_completed(list(futures)):
            try:
                rows = fut.result()
            except Exception as exc:  # noqa: BLE001 - e.g. KilledWorker: record, go on
                rows = _failed_rows(futures[fut], f"task: {type(exc).__name__}: {exc}")
            _finish(store, bar, rows)
            fut.release()
    finally:
        client.cancel([f for f in futures if not f.done()])


class _local_client:
    """A LocalCluster of `n` single-threaded worker processes and its Client.

    Dask's nanny sets OMP/MKL/OPENBLAS_NUM_THREADS = 1 in workers by default
    (distributed.nanny.pre-spawn-environ), so numpy's eigen-solvers stay on one core."""

    def __init__(self, n: int):
        self.n = n

    def __enter__(self):
        from distributed import Client, LocalCluster
        self.cluster = LocalCluster(n_workers=self.n, threads_per_worker=1, processes=True,
                                    dashboard_address=":0", silence_logs=logging.ERROR)
        self.client = Client(self.cluster)
        log = logging.getLogger("washer.sweep")
        if _has_bokeh():
            log.info("Dask dashboard (workers, tasks, memory): %s", self.client.dashboard_link)
        else:
            log.info("%d local Dask workers started; for their dashboard install bokeh "
                     "(pip install 'washer[dashboard]')", self.n)
        return self.client

    def __exit__(self, *exc):
        self.client.close()
        self.cluster.close()


def _has_bokeh() -> bool:
    """Dask serves its dashboard only with bokeh installed (an optional extra)."""
    import importlib.util
    return importlib.util.find_spec("bokeh") is not None
