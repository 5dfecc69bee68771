"""Run AUTO constants files: `python -m washer.run c.NAME [KEY=value ...]`.

    python -m washer.run c.NAME --allow-large  # a mesh far larger than usual (NTST)
    python -m washer.run --copy-examples DIR   # the shipped constants files, sweep specs
                                               # and AUTO's ab demo into DIR

Like AUTO's run(c='NAME'): reads c.NAME, loads the equations named by e
(e='washer' is the built-in model, e='washer:frozen' its frozen rotating
frame; any other e='X' loads X.py beside the constants file), restarts from
s.<s> (or s.NAME) when IRS is set, and writes b.<sv>, s.<sv>, d.<sv> (sv
defaults to NAME) beside the constants file, printing AUTO's table of labelled
points. Constants given on the command line override the file (ICP=[1,2],
IRS=HB1, DS=-0.01, sv=hb).

Exit status: 0 done, 1 the run stopped early (its points are kept), 2 bad input,
75 another run is writing the same b/s/d files (it is named), 130 interrupted.

From Python, runs chain like an AUTO script (c.ab and ab.py: AUTO's `ab` demo, as in
the repository's tests/data/ab/):
    from washer.run import run, load
    eq = run("c.ab", sv="eq")
    hb = run("c.ab", IRS="HB1", ICP=[1, 2], ISW=2, s="eq", sv="hb")
    eq("HB1").par, load("b.hb")
    print(eq); eq["PAR(1)"]; eq.to_dataframe()   # AUTO's table; a column; a DataFrame
"""
from __future__ import annotations

import contextlib
import os
import sys
import warnings
from pathlib import Path

from washer.auto.constants_file import (DEFAULTS, IGNORED, Constants, ConstantsError, copy_examples,
                                   parse_override, read_constants)
from washer.auto.files import AutoFileError, read_named_dat, read_s, s_file
from washer.cont.branch import Branch
from washer.cont.user_problem.c_library import CompileError
from washer.cont.problem import Problem, ProblemError
from washer.cont.runner import RunError, build, execute, restart_records
from washer.auto.sinks import FileSink, ScreenSink
from washer import sizes
from washer.locks import LockedError, output_lock
from washer.named_problems import resolve_problem
from washer.sizes import SizeError

#: Exit status when another run is writing the same output names (EX_TEMPFAIL: try later).
EXIT_LOCKED = 75

#: What `run` returns: the run in memory (labelled points, every row, status),
#: with `.files` naming the b./s./d. files written.
RunResult = Branch


def _restart_file(path) -> list:
    """The records of the s-file a run restarts from (a RunError naming what is wrong
    where it cannot be read); a damaged record is noted and the records before it used."""
    try:
        records = read_s(path)
    except AutoFileError as exc:
        raise RunError(str(exc)) from None
    for what in records.damaged:
        print(f"note: {what}; the records before it are used", file=sys.stderr)
    return records


def run(constants, verbose: bool = True, problem: Problem | None = None, params=None,
        sinks=None, restart=None, files: bool = True, allow_large: bool = False,
        **overrides) -> RunResult:
    """Run a constants file (path) or a Constants object with overrides.

    problem: the equations (default: from e=, see resolve_problem); params: the
    washer's parameters for e='washer' (default: the shipped reference set);
    sinks: extra sinks (washer.auto.sinks) besides the files and the screen;
    restart: what IRS is looked up in: a Branch (a previous run's result), a Record,
    a list of Records or an s-file path (default: the s-file s.<s> beside the
    constants file); files: write b./s./d. files (False: the run stays in memory,
    nothing is written). Returns the run in memory (a washer.cont.branch.Branch:
    `.specials`, `.rows`, `.status`, `.counters`, `r('HB1')`), with `.files` (the
    b./s./d. paths, None when nothing was written).
    Ctrl-C raises KeyboardInterrupt once the files hold every point computed so
    far (the partial run is its `.branch`); another run writing the same b/s/d
    names in the folder raises washer.locks.LockedError before anything is written."""
    if isinstance(constants, Constants):
        c, path = constants.copy(), Path(constants.source)
    else:
        path = Path(constants)
        c = read_constants(path)
    for k, v in overrides.items():
        c.set(k, v, "<override>")
    if c["e"].split(":")[0] == "washer":
        # The built-in problem names its parameters, so ICP=['m_u'] works without
        # parnames in the constants file (names the file gives win).
        from washer.machine.layout import PAR_NAMES
        c = c.with_default_names(PAR_NAMES)
    if verbose:
        # Constants without effect here are said so, never silently ignored.
        for key, why in IGNORED.items():
            if key in c.given and c[key] != DEFAULTS[key]:
                print(f"note: {c.given[key]}: {key} has no effect here ({why})", file=sys.stderr)
    folder = path.parent if path.name else Path(".")
    default_name = path.name[2:] if path.name.startswith("c.") else path.name
    name = c["sv"] or default_name
    # Restarts read s.<s>, else s.NAME of the constants file (AUTO's load('NAME')):
    # sv names only what is written.
    restart_from, restart = restart, s_file(folder / f"s.{c['s'] or default_name}")
    if problem is None:
        problem = resolve_problem(c, folder, params)
    route = getattr(problem, "route", None)
    if verbose and route:
        # how a Python file's func is evaluated (washer.cont.user_problem.user_files_traced),
        # and why
        print(f"note: e='{c['e']}': {route}", file=sys.stderr)
    _check_size(c, problem, allow_large)
    # The restart data is read whole before any output file is opened: the
    # default sv is the restart file's own name, and it must survive.
    records = None
    protect = ()
    if isinstance(restart_from, (str, os.PathLike)):
        source, protect = str(restart_from), (Path(restart_from),)
        records = _restart_file(restart_from)
    elif restart_from is not None:
        records, source = restart_records(restart_from, c)
    elif c["IRS"] not in (0, "0"):
        source = str(restart)
        protect = (restart,)
        if not restart.exists():
            raise RunError(f"{c.source}: IRS={c['IRS']!r} needs the restart file {restart}, "
                           "which does not exist (set s='NAME' to read s.NAME)")
        records = _restart_file(restart)
    else:
        source = str(restart)
    data = None
    if c["dat"] and c["IRS"] in (0, "0"):
        # AUTO's dat='NAME': the start orbit from NAME (or NAME.dat) beside the
        # constants file.
        try:
            data = read_named_dat(c["dat"], problem.ndim, folder)
        except AutoFileError as exc:
            raise RunError(f"{c.source}: dat='{c['dat']}': {exc}") from None
    r, br, mode = build(c, problem, records, name=c["e"] or problem.name,
                        records_source=source, data=data)
    # One run at a time writes b/s/d.<sv> in a folder (a second one would interleave
    # its rows with ours): the lock is taken before any of them is opened.
    lock = output_lock(folder, name, what=f"b.{name}, s.{name}, d.{name}") if files \
        else contextlib.nullcontext()
    with lock:
        file_sink = FileSink(folder, name, protect=protect) if files else None
        all_sinks = ([file_sink] if files else []) + ([ScreenSink()] if verbose else []) + \
            list(sinks or [])
        result = execute(r, br, mode, all_sinks)
    result.files = file_sink.files if files else None
    if verbose and getattr(problem, "route", None) != route:
        # a traced func refused during the run (a difference seen): said, not only done
        print(f"note: e='{c['e']}': {problem.route}", file=sys.stderr)
    if files and not result.rows:
        # No point: empty b- and s-files would only hide that the run failed.
        for p in (result.files.b_path, result.files.s_path):
            with contextlib.suppress(OSError):
                if not p.is_symlink() and p.stat().st_size == 0:
                    p.unlink()
    if c["e"].split(":")[0] == "washer":
        from washer.machine.layout import UNITS
        result.units = dict(UNITS)
    if verbose:
        if result.status == "ok":
            print(f"{c['e'] or problem.name} ... done")
        else:
            print(f"{c['e'] or problem.name} ... failed", file=sys.stderr)
    return result


def _check_size(c: Constants, problem: Problem, allow: bool) -> None:
    """A mesh problem's Newton matrices estimated from NTST, NCOL and NDIM before the
    run starts (NTST = 100000 would end in a MemoryError minutes later)."""
    ips = c["IPS"]
    if not (abs(ips) in (2, 4, 7, 9) or ips >= 12):
        return
    ndim = getattr(problem, "ndim", None) or c["NDIM"]
    nbytes = sizes.collocation_bytes(c["NTST"], c["NCOL"], ndim)
    sizes.check(f"{c.given.get('NTST', c.source)}: NTST = {c['NTST']}, NCOL = {c['NCOL']}, "
                f"NDIM = {ndim}", nbytes=nbytes, allow=allow,
                how="pass --allow-large (run(..., allow_large=True)), or lower NTST")


def load(path):
    """Read an AUTO b- or s-file (ours or AUTO-07p's).

    A b-file gives AUTO's bifurcation diagram (washer.auto.diagram.Diagram): a list of
    branches whose rows iterate as before and whose columns are named by the file's
    titles (`load('b.ab')[0]['L2-NORM']`, `load('b.ab')['PAR(1)']`, a labelled
    point `load('b.ab')('HB1')` when the s-file is beside it). An s-file gives its
    records (washer.cont.branch.Record), which restart runs."""
    p = Path(path)
    if p.name.startswith("s."):
        return read_s(p)
    from washer.auto.diagram import Diagram
    s_path = p.with_name("s." + p.name[2:]) if p.name.startswith("b.") else None
    return Diagram.read(p, s_path)


def _copy_examples(args: list[str]) -> int:
    """`--copy-examples DIR`: the shipped constants files into DIR, to run them there."""
    if len(args) != 1:
        print("usage: python -m washer.run --copy-examples DIR", file=sys.stderr)
        return 2
    try:
        copied, skipped = copy_examples(args[0])
    except ConstantsError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    for p in copied:
        print(f"copied {p}")
    for p in skipped:
        print(f"kept {p} (exists; not overwritten)")
    print(f"run one with: cd {args[0]} && python -m washer.run c.washer")
    return 0


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    # Warnings (a unit slip, a constant without effect) as one plain line each.
    warnings.formatwarning = lambda message, category, *a, **k: f"warning: {message}\n"
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv else 2
    if argv[0] == "--copy-examples":
        return _copy_examples(argv[1:])
    allow_large = "--allow-large" in argv[1:]
    try:
        overrides = dict(parse_override(a) for a in argv[1:] if a != "--allow-large")
        res = run(argv[0], allow_large=allow_large, **overrides)
    except LockedError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_LOCKED
    except (ConstantsError, AutoFileError, RunError, ProblemError, CompileError,
            SizeError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:
        print(f"interrupted{': ' + str(exc) if str(exc) else ''}", file=sys.stderr)
        return 130
    except Exception as exc:        # noqa: BLE001 - a defect: say so, without a traceback
        print(f"error: {argv[0]}: the run failed unexpectedly: {type(exc).__name__}: {exc} "
              "(please report this with the constants file; set WASHER_TRACEBACK=1 for the "
              "traceback)", file=sys.stderr)
        if os.environ.get("WASHER_TRACEBACK"):
            raise
        return 2
    written = [str(p) for p in (res.files.b_path, res.files.s_path, res.files.d_path)
               if p.exists()]
    if res.status == "ok":
        print(f"Saved as {', '.join(written)}")
        return 0
    kept = (f"{len(res.rows)} points computed before it are in {', '.join(written)}"
            if res.rows else f"no point was computed (diagnostics in {res.files.d_path})")
    print(f"error: {argv[0]}: the run {res.status}; {kept}", file=sys.stderr)
    return 1


if __name__ == "__main__":
    raise SystemExit(main())
