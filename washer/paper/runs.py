"""The AUTO runs behind the paper's Figs 3-7, executed from `auto_constants/`.

Every run is a constants file a user can rerun by hand. The files are copied
into `<out>/auto/` and run there, so the b./s./d. files sit beside the exact
constants that made them; a curve traced both ways is two runs, the second with
AUTO's `DS='-'` (as AUTO-07p scripts do), saved as `<name>.bwd`.
"""
from __future__ import annotations

import os
import shutil
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from washer.auto.constants_file import read_constants, shipped_constants_dir
from washer.auto.files import read_b, type_name
from washer.run import run

#: Folder of the shipped constants files: auto_constants/ of a checkout, or the
#: copy an installed wheel carries as washer/auto_constants/.
CONSTANTS_DIR = shipped_constants_dir() or Path(__file__).resolve().parents[2] / "auto_constants"

#: The frames compared throughout: AUTO equation names and file suffixes.
FRAMES = {"averaged": ("washer", ""), "frozen": ("washer:frozen", ".frozen")}

#: Second parameter of each Hopf curve in (C_p, X), and the paper's figure.
HOPF_CURVES = {"Omega": "Fig. 4", "m_u": "Fig. 5(a)", "R_u": "Fig. 5(b)", "C_a": "Fig. 6",
               "K_s": "Fig. 7(a)"}

#: Quick mode: steps this many times larger (DS and DSMAX) on every curve.
QUICK_STEP_FACTOR = 3.0


@dataclass
class Curve:
    """A continuation curve from one or two b-files, ordered along the curve.

    p1: PAR(ICP(1)) (n,), p2: PAR(ICP(2)) (n,) or None for a one-parameter
    branch, norm: AUTO's L2-norm of the state (n,), u: U(1..5) as written in the b-file (n, 5), stable: (n,) bool (branches
    only), specials: (type, index into the arrays, label) of labelled points;
    ends: for each end, the point type AUTO wrote there ('UZ', 'EP', 'MX', 'BT', ...).
    """
    name: str
    p1: np.ndarray
    p2: np.ndarray | None
    norm: np.ndarray
    u: np.ndarray
    stable: np.ndarray
    specials: list = field(default_factory=list)
    ends: tuple = ("", "")


@dataclass
class RunLog:
    """What was run: command lines (relative to the output folder), timings and the
    status of each run ("ok" when it finished normally)."""
    commands: list = field(default_factory=list)
    seconds: dict = field(default_factory=dict)
    status: dict = field(default_factory=dict)

    def failed(self) -> dict:
        """{run label: status} of the runs that did not finish "ok"."""
        return {k: v for k, v in self.status.items() if v != "ok"}


def read_curve(folder: Path, name: str, two_par: bool) -> Curve:
    """The curve of b.<name> joined with b.<name>.bwd when that exists (an output folder
    read back: the job itself builds its curves from the runs in memory)."""
    read = lambda path: [r for branch in read_b(path) for r in branch] if path.exists() else []
    fwd, bwd = read(folder / f"b.{name}"), read(folder / f"b.{name}.bwd")
    if not (fwd or bwd):
        raise FileNotFoundError(f"no b.{name} in {folder}")
    return curve_of(name, fwd, bwd, two_par, type_of=lambda r: type_name(r.ty),
                    stable_of=lambda r: r.pt < 0)


def curve_of(name: str, fwd: list, bwd: list, two_par: bool,
             type_of=lambda r: r.ty, stable_of=lambda r: bool(r.stable)) -> Curve:
    """A Curve from the rows of a run (washer.cont.branch.Record: a run's Branch.rows) and
    of its backward run: backward part reversed, then the forward part (their shared
    start point once). type_of/stable_of read a row's type name and stability (b-file
    rows: type_name(TY), PT < 0)."""
    bwd = list(bwd)[::-1]
    rows = bwd[:-1] + list(fwd) if (bwd and fwd) else bwd + list(fwd)
    if not rows:
        raise ValueError(f"{name}: no points")
    vals = np.array([r.values for r in rows])
    names = [(type_of(r), r.lab) for r in rows]
    specials = [(t, i, lab) for i, (t, lab) in enumerate(names) if t and lab]
    return Curve(name, vals[:, 0], vals[:, -1] if two_par else None, vals[:, 1],
                 vals[:, 2:-1] if two_par else vals[:, 2:7],
                 np.array([stable_of(r) for r in rows]), specials,
                 (names[0][0], names[-1][0]))


def _run(folder: Path, cfile: str, log: RunLog, label: str, **overrides):
    """One AUTO run; its status goes into the log. A run that raises is recorded as
    failed and the others still run (the report then gives no verdicts); an
    interrupt (Ctrl-C, which the engine turns into a status) stops the whole job."""
    t0 = time.perf_counter()
    args = " ".join(f"{k}={v}" for k, v in overrides.items())
    log.commands.append(f"python -m washer.run auto/{cfile} {args}".rstrip())
    try:
        res = run(folder / cfile, verbose=False, **overrides)
        status = str(res.status)
    except Exception as exc:      # noqa: BLE001 - any failure of one run is that run's status
        res, status = None, f"error: {type(exc).__name__}: {exc}"
    log.seconds[label] = time.perf_counter() - t0
    log.status[label] = status
    if status.startswith("interrupted"):
        raise KeyboardInterrupt(f"run {label}: {status}")
    return res


def _read(folder: Path, name: str, two_par: bool, log: RunLog, labels, runs=None
          ) -> Curve | None:
    """The curve of a run (and its backward run) from the Branches in memory `runs`
    (forward, backward or None), else read back from its b-files; None when one of its
    runs failed or left no points."""
    if any(log.status.get(k) != "ok" for k in labels):
        return None
    try:
        if runs is not None and runs[0] is not None:
            return curve_of(name, runs[0].rows, runs[1].rows if runs[1] is not None else [],
                            two_par)
        return read_curve(folder, name, two_par)
    except (OSError, ValueError) as exc:
        for k in labels:
            log.status[k] = f"finished, but its points cannot be read: {exc}"
        return None


def run_all(out: Path, quick: bool = False, progress=print) -> tuple[dict, dict, RunLog]:
    """Run every constants file of the paper's Figs 3-7 into out/auto.

    Returns (branches, results, log): branches maps a run name ('washer',
    'washer.hopf.C_a.frozen', ...) to its Curve (None when a run failed: see
    log.failed()); results maps the one-parameter
    runs to their RunResult (labelled points with eigenvalue information).
    """
    if not CONSTANTS_DIR.is_dir():
        raise FileNotFoundError(f"{CONSTANTS_DIR}: the constants files are not there; run "
                                "from a source checkout (pip install -e .)")
    final = out / "auto"
    final.mkdir(parents=True, exist_ok=True)
    # The runs write into a fresh folder beside the previous results, which stay
    # untouched until every run is over: an interrupt or a crash loses nothing.
    folder = Path(tempfile.mkdtemp(prefix=".auto.new-", dir=out))
    try:
        for c in sorted(CONSTANTS_DIR.glob("c.washer*")):
            shutil.copy(c, folder / c.name)
        curves, results, log = _run_all_in(folder, quick, progress)
    except BaseException:
        shutil.rmtree(folder, ignore_errors=True)
        raise
    _replace_files(folder, final)
    return curves, results, log


def _replace_files(new: Path, final: Path) -> None:
    """Move every file of `new` into `final` (each replaces its namesake in one step),
    remove the b/s/d files of `final` the new runs did not write, then `new`."""
    names = set()
    for f in sorted(new.iterdir()):
        os.replace(f, final / f.name)
        names.add(f.name)
    for old in final.glob("[bsd].*"):
        if old.name not in names:
            old.unlink()
    new.rmdir()


def _run_all_in(folder: Path, quick: bool, progress) -> tuple[dict, dict, "RunLog"]:
    """The runs of run_all, in `folder`."""
    log = RunLog()
    curves, results = {}, {}
    for frame, (_, suffix) in FRAMES.items():
        name = f"washer{suffix}"
        progress(f"  Fig 3 branch in C_p ({frame})")
        results[name] = _run(folder, f"c.{name}", log, name)
        curves[name] = _read(folder, name, False, log, [name], (results[name], None))
    def both_ways(name: str, two_par: bool):
        fwd, bwd = {}, {"DS": "-"}
        if quick:
            c = read_constants(folder / f"c.{name}")
            ds = c["DS"] * QUICK_STEP_FACTOR
            fwd = {"DS": ds, "DSMAX": c["DSMAX"] * QUICK_STEP_FACTOR}
            bwd = dict(fwd, DS=-ds)
        runs = (_run(folder, f"c.{name}", log, name, **fwd),
                _run(folder, f"c.{name}", log, f"{name}.bwd", **bwd, sv=f"{name}.bwd"))
        curves[name] = _read(folder, name, two_par, log, [name, f"{name}.bwd"], runs)

    for key, fig in list(HOPF_CURVES.items()) + [("m_u_R_u", "Fig. 5(c)")]:
        for frame, (_, suffix) in FRAMES.items():
            progress(f"  {fig} Hopf curve {key} ({frame})")
            both_ways(f"washer.hopf.{key}{suffix}", two_par=True)
    progress("  Fig. 7(b) equilibrium in K_s")
    both_ways("washer.eps3", two_par=False)
    return curves, results, log
