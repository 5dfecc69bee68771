"""AUTO-07p's command language (the CLUI) on washer's engine.

    python -m washer.auto NAME.auto         # run an AUTO script in the current folder
    python -m washer.auto                   # interactive, like `auto`
    from washer.auto import run, load, save, append, merge, relabel, cl, ...

The commands and their meanings are AUTO's (python/auto/AUTOCommands.py): one
runner holds the current constants and restart solution; `run(data, **constants)`
restarts from a solution, a diagram (its IRS or last solution), a name (c.NAME,
s.NAME, e = NAME) or the runner's state, writes fort.7/8/9 (b./s./d.<sv> with
sv='name') and returns the bifurcation diagram (washer.auto.diagram.Diagram).
Constants keep AUTO's "None means default" semantics: a constants file given with
c= replaces every constant it does not set by its default, a keyword changes one,
DS='-' reverses the direction. The equations are NAME.py (washer's Python user
files) or AUTO's NAME.f90 / NAME.f / NAME.c, compiled on first use.

Scripts are read in AUTO's dialect: Python 2 `print "..."` statements are
accepted. An unknown command stops the script with its name and line.
"""
from __future__ import annotations

import glob
import os
import re
import shutil
import sys
from pathlib import Path

from washer.auto.constants_file import Constants, ConstantsError, read_constants
from washer.auto import diagram
from washer.auto.script_constants import (SPECIAL_KEYS, STANDARD_KEYS, AutoConstants,  # noqa: F401
                                        AutoError)
from washer.auto.files import s_file
from washer.auto.diagram import (NONE_KEYS, Diagram, Solution, SolutionList, label_selector,
                                  read_solutions, type_name)
from washer.atomic import save_figure
from washer.named_problems import named_problem

#: File name of the unsaved output of a run (AUTO's units 7, 8, 9).
FORT = ("fort.7", "fort.8", "fort.9")
#: Engine messages that mean "this kind of run is not done here" (not a user error).
REFUSED = re.compile(r"not implemented|no continued system|not supported", re.I)


def read_auto_constants(name: str) -> AutoConstants:
    """c.NAME as AUTO's parseC sees it: the keys the file sets; the rest None."""
    path = Path(f"c.{name}")
    if not path.exists():
        raise AutoError(f"{path}: no such constants file")
    try:
        c = read_constants(path)
    except ConstantsError as exc:
        raise AutoError(str(exc)) from None
    out = AutoConstants()
    for k in c.given:
        out[k] = c[k]
        out.origins[k] = c.given[k]
    return out


# ----------------------------------------------------------------------------- runner

class Runner:
    """What the CLUI remembers between commands: constants and the restart solution."""

    def __init__(self):
        self.constants = AutoConstants()
        self.solution = Solution(None)
        self._problems: dict = {}
        self.refused: list[str] = []        # runs the engine declined

    def problem(self, e: str, ndim: int, constants: Constants | None = None):
        """The equations named e in the current folder: NAME.py, else NAME.f90/.f/.c
        (compiled once, cached), or a family the package ships (e = 'washer...',
        washer.named_problems), built from the run's `constants` as `washer.run` builds
        it (e='washer' starts from the equilibrium at the constants' PAR)."""
        from washer.cont.user_problem.user_files import find_problem_file, load_user_problem
        if not e:
            raise AutoError("The equation file argument is missing.")
        folder = Path(".").resolve()
        resolve = named_problem(e)
        if resolve is not None:
            return resolve(Constants({"e": e}) if constants is None else constants, folder)
        path = find_problem_file(e, folder)
        if path is None:
            raise AutoError(f"No equations file found for: '{e}' (expected {e}.f90, {e}.f, "
                            f"{e}.c or {e}.py in {folder})")
        key = (str(path), path.stat().st_mtime_ns, ndim)
        if key not in self._problems:
            self._problems[key] = load_user_problem(e, folder, ndim)
        return self._problems[key]


_runner = Runner()


#: Options of AUTO's runner (runAUTO.py) that change only how AUTO logs and builds.
RUNNER_OPTIONS = ("verbose", "log", "err", "redir", "makefile", "clean", "auto_dir",
                  "demos_dir", "dir", "executable", "command")


def _abbrev(kw: dict) -> dict:
    """AUTO's long option names (equation, constants, solution) to the short ones."""
    out = dict(kw)
    for long, short in (("equation", "e"), ("constants", "c"), ("solution", "s"),
                        ("homcont", "h")):
        if long in out:
            v = out.pop(long)
            out.setdefault(short, v)
    return out


def _configure(data=None, **kw) -> Solution:
    """load()'s work: resolve c=/s=/e= and data into the runner; the selected solution."""
    R = _runner
    kw = _abbrev(kw)
    kw.pop("h", None)
    # AUTO's runner options about its own screen log and build (ld(verbose="no") in its
    # tutorial script): washer's output does not depend on them.
    for option in RUNNER_OPTIONS:
        kw.pop(option, None)
    resolved = {}
    missing_s = None
    for short, reader in (("c", read_auto_constants), ("s", _read_s)):
        if short in kw:
            value = kw.pop(short)
            explicit = True
        elif isinstance(data, str):
            value, explicit = data, False
        else:
            continue
        if isinstance(value, str):
            try:
                value = reader(value)
            except AutoError as exc:
                # run('NAME') reads c.NAME where there is one: a c.NAME that is there but
                # wrong is the user's error (its file and line), not a missing file
                if short == "c" and (explicit or Path(f"c.{value}").exists()):
                    raise
                if short == "s" and explicit:
                    missing_s = exc
                value = None
        resolved[short] = value
    if isinstance(data, str) and "e" not in kw:
        kw["e"] = data
    if "e" in kw:
        _check_equation(kw["e"])
    if isinstance(data, (list, tuple)) and not isinstance(data, (Diagram, SolutionList)) or \
            type(data).__name__ == "ndarray":
        # numbers: a point or an orbit column-wise (AUTO's load(array))
        resolved["s"] = Solution.from_array(data)
        data = None
    if data is not None and hasattr(data, "load") and not isinstance(data, str):
        if resolved.get("c") is not None:
            kw["constants"] = resolved["c"]
        sol = data.load(**kw)
        R.constants.update(sol.c)
        R.solution = sol
        return R.solution.load(constants=R.constants)
    if "c" in resolved and resolved["c"] is not None:
        R.constants.update(resolved["c"])
    if "s" in resolved:
        R.solution = resolved["s"] if resolved["s"] is not None else Solution(None)
    R.constants.update(kw)
    if missing_s is not None and R.constants.get("IRS"):
        raise AutoError(str(missing_s))
    return R.solution.load(constants=R.constants)


def _read_s(name: str) -> SolutionList:
    path = s_file(f"s.{name}")
    if not path.exists():
        raise AutoError(f"s.{name}: no such solution file")
    out = SolutionList(read_solutions(path))
    out.source = str(path)
    return out


def _check_equation(e) -> None:
    if not e or str(e).split(":")[0] == "washer":
        return
    for ext in (".f90", ".f", ".c", ".py"):
        if os.path.exists(f"{e}{ext}"):
            return
    raise AutoError(f"No equations file found for: '{e}' (expected {e}.f90, {e}.f, {e}.c or "
                    f"{e}.py in {Path('.').resolve()})")


def _read_data(name: str, ndim: int):
    """(t, U) of AUTO's dat= file in the current folder (rows 't U(1) ... U(NDIM)'), the
    start the engine takes from it as `washer.run` hands it over."""
    from washer.auto.files import AutoFileError, read_named_dat
    try:
        return read_named_dat(name, ndim)
    except AutoFileError as exc:
        raise AutoError(str(exc)) from None


def _execute(sol: Solution) -> Diagram:
    """One run of the engine from the selected solution; its output files parsed back."""
    from washer.cont.runner import RunError, build, execute
    from washer.cont.problem import ProblemError
    from washer.auto.sinks import FileSink, ScreenSink
    from washer.cont.user_problem.c_library import CompileError
    c = sol.c
    e = c.get("e") or ""
    if c.get("IRS") and sol.empty:
        why = getattr(sol, "missing", "")
        raise AutoError(f"Restart label IRS={c['IRS']!r} not found" +
                        (f": {why}" if why else " (no solution loaded: s='NAME' reads s.NAME)"))
    sv = c.get("sv") or ""
    try:
        wc = c.washer(f"run(e='{e}')")
        # sv stays: the b-file header names it as AUTO's does (e = 'NAME' sv = 'NAME.1');
        # the files are written here (FileSink), not by the engine from it.
        wc.set("s", "")
        problem = _runner.problem(e, wc["NDIM"], wc)
        if hasattr(problem, "fresh"):
            problem.fresh()             # AUTO runs each run in a new process
        records = data = None
        if not sol.empty and c.get("IRS"):
            wc.set("IRS", sol.rec.lab)
            records = [sol.rec]
        else:
            wc.set("IRS", 0)
            if c.get("dat"):
                # AUTO's dat='NAME': the start is the orbit in NAME.dat (columns t,
                # U(1..NDIM)), taken by the engine's start as for `washer.run`
                data = _read_data(c["dat"], problem.ndim)
        if hasattr(problem, "set_icp"):
            try:
                problem.set_icp(wc.icp())
            except ConstantsError:
                pass
        if hasattr(problem, "set_sizes"):
            problem.set_sizes(wc["NBC"], wc["NINT"])
        r, br, mode = build(wc, problem, records, name=e, records_source="the restart solution",
                            mlab=sol._mlab if records else None,
                            mbr=sol._mbr if records else None, data=data)
    except RunError as exc:
        if REFUSED.search(str(exc)):
            # A run the engine does not do: said clearly, the script goes on (later
            # commands that need its results fail with their own message).
            print(f"error: {exc}", file=sys.stderr, flush=True)
            _runner.refused.append(str(exc))
            # The run's d-file (AUTO's diagnostics) says why there is no output; an
            # earlier run's fort.7/fort.8 are not left beside it as this run's (AUTO's
            # every run starts them afresh).
            Path(f"d.{sv}" if sv else FORT[2]).write_text(
                f"   0     0 NOTE:run not done: {exc}\n")
            if not sv:
                for f in FORT[:2]:
                    Path(f).unlink(missing_ok=True)
            bd = Diagram()
            bd.status = f"refused: {exc}"
            return bd
        raise AutoError(str(exc)) from None
    except (ConstantsError, ProblemError, CompileError) as exc:
        raise AutoError(str(exc)) from None
    name = sv or ".washer-fort"
    files = FileSink(Path("."), name, fresh_s="/")
    result = execute(r, br, mode, [files, ScreenSink()])
    paths = [Path(f"{k}.{name}") for k in "bsd"]
    if not sv:
        for p, f in zip(paths, FORT):
            os.replace(p, f)
        paths = [Path(f) for f in FORT]
    if not result.started:
        # AUTO's runAUTO raises AUTORuntimeError when its run fails (the executable
        # ending in an error, no b-file written): the script stops there, unless it
        # catches the error. A branch ending at MX is a result, not an error.
        why = result.status.removeprefix("stopped: ")
        raise AutoError(f"run(e='{e}') failed at its start: {why} (what was written is in "
                        f"{', '.join(str(p) for p in paths)})")
    print(f"{e} ... done", flush=True)
    keep = AutoConstants(c)
    for k in NONE_KEYS:
        keep[k] = None
    bd = Diagram.read(*paths, c=keep)
    bd.status = result.status
    return bd


# ----------------------------------------------------------------------------- commands

def run(data=None, sv=None, ap=None, **kw) -> Diagram:
    """Run AUTO from data (solution, diagram, name or the loaded state) with constants
    kw; sv='name' saves to b./s./d.name, ap='name' appends there too."""
    if sv is not None:
        kw["sv"] = sv
    sol = _configure(data, **kw)
    res = _execute(sol)
    sv = _runner.constants.get("sv")
    _runner.constants["sv"] = None
    if sv and str(getattr(res, "status", "")).startswith("refused"):
        print(f"Nothing to save to b.{sv}, s.{sv}: d.{sv} says why")
    elif sv:
        print(f"Saving to b.{sv}, s.{sv}, and d.{sv} ... done")
        if ap is not None:
            append(sv, ap)
    elif ap is not None:
        append(ap)
    return res


def load(data=None, **kw):
    """Load files (a name: c.NAME, s.NAME, e=NAME) or return a solution of data with
    constants changed (AUTO's load)."""
    sol = _configure(data, **kw)
    return sol


def loadbd(name=None, **kw) -> Diagram:
    """The bifurcation diagram of b./s./d.NAME (fort.7/8/9 without a name)."""
    if isinstance(name, Diagram):
        return name
    paths = _existing(_names(name) if name else list(FORT))
    return Diagram.read(*paths)


def sl(name=None) -> SolutionList:
    """The solutions of s.NAME (fort.8 without a name)."""
    return SolutionList(read_solutions(f"s.{name}" if name else "fort.8"))


def cn(name=None) -> AutoConstants:
    """AUTO's cn (constantsget): the constants of c.NAME (the runner's without a name)."""
    if name is None:
        return _runner.constants.copy()
    return read_auto_constants(name)


def dg(name=None) -> Diagram:
    """The bifurcation diagram of b.NAME alone."""
    return Diagram.read(f"b.{name}" if name else "fort.7")


def _names(name) -> list[str]:
    return [f"{k}.{name}" for k in "bsd"]


def _existing(paths: list[str]) -> list[str]:
    """paths (b., s., d.) when the b- or s-file exists, else an error naming them: a
    misspelt name must not become empty output files."""
    if not (os.path.exists(paths[0]) or s_file(paths[1]).exists()):
        raise AutoError(f"no output files {paths[0]}, {paths[1]}")
    return paths


def save(name1, name2=None):
    """save(x, 'name'): write diagram x to b./s./d.name (a solution or list: s.name
    only); save('name'): copy fort.7/8/9 to b./s./d.name. Existing files -> NAME~."""
    parsed = None
    if name2 is not None:
        parsed, name1 = name1, name2
    paths = _names(name1)
    if isinstance(parsed, Diagram) and str(getattr(parsed, "status", "")).startswith("refused"):
        # the result of a run the engine declined holds nothing: no files, as run(sv=)
        print(f"Nothing to save to {paths[0]}, {paths[1]}: {parsed.status}")
        return
    for p in paths:
        if os.path.exists(p):
            shutil.copy(p, p + "~")
    if parsed is not None:
        if isinstance(parsed, list) and not isinstance(parsed, (Diagram, SolutionList)) and \
                parsed and isinstance(parsed[0], Solution):
            parsed = SolutionList(parsed)
        if isinstance(parsed, Diagram) and len(parsed) and len(parsed[0]):
            parsed.write(name1)
            print(f"Saving to {paths[0]}, {paths[1]}, and {paths[2]} ... done")
        else:
            if isinstance(parsed, Solution):
                parsed = SolutionList([parsed])
            parsed.write(paths[1])
            print(f"Saving to {paths[1]} ... done")
        return
    for f, p in zip(FORT, paths):
        if os.path.exists(f):
            shutil.copy(f, p)
            print(f"Saving {f} as {p} ... done")


def append(name1, name2=None):
    """append(x, 'name'): x to the end of b./s./d.name; append('name'): fort.7/8/9 to
    b./s./d.name; append('a', 'b'): files a to files b; append('name', x): the files
    to diagram x (in place)."""
    if isinstance(name1, Diagram) and name2 is not None and not isinstance(name2, Diagram):
        name1.write(name2, append=True)
        print(f"Appending to b.{name2}, s.{name2} and d.{name2} ... done")
        return
    if isinstance(name2, Diagram):
        other = name1 if isinstance(name1, Diagram) else loadbd(name1)
        name2.extend(other)
        return
    src = _names(name1) if name2 is not None else list(FORT)
    dst = _names(name2 if name2 is not None else name1)
    for a, b in zip(src, dst):
        try:
            with open(a, "rb") as fa, open(b, "ab") as fb:
                shutil.copyfileobj(fa, fb)
            print(f"Appending {a} to {b} ... done")
        except OSError as exc:
            print(f"Appending {a} to {b}: {exc}")


def _transform_files(name1, name2, how: str) -> None:
    src = _existing(_names(name1) if name1 else list(FORT))
    bd = Diagram.read(*src)
    new = bd.relabel() if how == "relabel" else bd.merge()
    if name2 is None:
        for p in src:
            if os.path.exists(p):
                shutil.copy(p, p + "~")
        new.write(src)
    else:
        new.write(name2)


def _delete_labels(typenames, name1, name2, keep: bool, keep_type: bool):
    """AUTO's deleteLabel: FUNC(x, list) returns a copy of the diagram or solution list
    x; FUNC(list, 'xxx'[, 'yyy']) rewrites b./s.xxx (or writes b./s.yyy);
    FUNC(list) works on fort.7/8."""
    if isinstance(typenames, (Diagram, SolutionList)):
        select = label_selector(name1)
        if isinstance(typenames, Diagram):
            return typenames.delete_labels(select, keep, keep_type)
        return SolutionList(s for s in typenames if bool(select(s)) == keep)
    select = label_selector(typenames)
    src = _existing(_names(name1) if name1 else list(FORT))
    new = Diagram.read(*src).delete_labels(select, keep, keep_type)
    if name2 is None:
        for p in src[:2]:
            if os.path.exists(p):
                shutil.copy(p, p + "~")
        new.write(src)
    else:
        new.write(name2)
    print("Deleting labels done" if not keep else "Keeping labels done")


def dsp(typenames=None, name1=None, name2=None):
    """Delete special points (default: BP LP HB PD TR EP MX), their types too."""
    return _delete_labels(typenames, name1, name2, keep=False, keep_type=False)


def ksp(typenames=None, name1=None, name2=None):
    """Keep only the special points listed (default: BP LP HB PD TR EP MX)."""
    return _delete_labels(typenames, name1, name2, keep=True, keep_type=False)


def dlb(typenames=None, name1=None, name2=None):
    """Delete labels (default: BP LP HB PD TR EP MX), keeping their types in the b-file."""
    return _delete_labels(typenames, name1, name2, keep=False, keep_type=True)


def klb(typenames=None, name1=None, name2=None):
    """Keep only the labels listed, the others' types kept in the b-file."""
    return _delete_labels(typenames, name1, name2, keep=True, keep_type=True)


def relabel(name1=None, name2=None):
    """relabel(x): a copy of diagram x with labels 1, 2, ...; relabel('name'): the files."""
    if name1 is not None and not isinstance(name1, str):
        out = name1.relabel()
        print("Relabeling done")
        return out
    _transform_files(name1, name2, "relabel")
    print("Relabeling done")


def merge(name1=None, name2=None):
    """merge(x): a copy of diagram x with branches continued both ways joined."""
    if name1 is not None and not isinstance(name1, str):
        out = name1.merge()
        print("Merge done")
        return out
    _transform_files(name1, name2, "merge")
    print("Merging done")


def clean():
    """Delete fort.*, *.o, *.exe and *.*~ in the current folder."""
    for f in sorted(set(glob.glob("fort.*") + glob.glob("*.o") + glob.glob("*.exe") +
                        glob.glob("*.*~"))):
        os.remove(f)
    print("Deleting fort.* *.o *.exe *.*~ ... done")


def df():
    """Delete fort.* files."""
    for f in glob.glob("fort.*"):
        os.remove(f)
    print("Deleting fort.* ... done")


def delete(name):
    """Delete b./s./d.NAME."""
    for p in _names(name):
        if os.path.exists(p):
            os.remove(p)
            print(f"Deleting {p} ... done")


def copy(name1, name2, name3=None, name4=None):
    """Copy c./b./s./d.name1 to name2 (folders as AUTO's copy)."""
    dir1 = dir2 = ""
    if os.path.isdir(name1):
        dir1, name1 = name1, name2
        name2 = name4 if name4 is not None else name3
        if name4 is not None:
            dir2 = name3
    elif os.path.isdir(name2):
        dir2 = name2
        name2 = name3 if name3 is not None else name1
    done = False
    for k in "bsdc":
        a, b = os.path.join(dir1, f"{k}.{name1}"), os.path.join(dir2, f"{k}.{name2}")
        if os.path.exists(a):
            shutil.copy(a, b)
            print(f"Copying {a} to {b} ... done")
            done = True
    if not done:
        raise AutoError(f"Copying: no files found for [bsdc].{name1}")


def move(name1, name2, name3=None, name4=None):
    """Move c./b./s./d.name1 to name2."""
    copy(name1, name2, name3, name4)
    for k in "bsdc":
        p = os.path.join(name1 if os.path.isdir(name1) else "", f"{k}.{name1}")
        if os.path.exists(p) and not os.path.isdir(name1):
            os.remove(p)


def ch(entry=None, value=None, **kw):
    """Change constants of the runner: ch('NMX', 50) or ch(NMX=50)."""
    if entry is not None:
        _runner.constants.update({entry: value})
        print(f"{entry} changed to {value}")
    else:
        _runner.constants.update(kw)
        print(str(kw))


def pr(parameter=None):
    """Print the runner's constants (or one)."""
    c = _runner.constants
    if parameter is not None:
        print(c.get(parameter))
        return c.get(parameter)
    for k, v in c.items():
        if v is not None:
            print(f"{k} = {v!r}")


def splabs(s, typename):
    """Labels of the solutions of type typename in s: a solution list, a diagram, or
    a name (s.NAME, as AUTO's splabs reads it)."""
    if isinstance(s, str):
        s = sl(s)
    return [x["LAB"] for x in (s if isinstance(s, SolutionList) else s())
            if x["TY"] == typename]


def wait():
    """A no-op in scripts (AUTO waits for Enter)."""


def cat(f=None):
    if f:
        sys.stdout.write(Path(f).read_text())


def ls(dir=None):
    print("\n".join(sorted(os.listdir(dir or "."))))


def cd(dir=None):
    os.chdir(os.path.expanduser(dir or "~"))


def shell(cmd):
    os.system(cmd)


def quit():
    raise SystemExit(0)


class Plot:
    """What plot() returns: the picture is a PNG file (no window); savefig writes
    another copy (any format matplotlib knows, from the file suffix)."""

    def __init__(self, bd, path: Path):
        self.bd, self.path = bd, path
        self.draw(path)

    def draw(self, path) -> None:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4.5))
        for b in self.bd:
            if not b.rows or len(b.rows[0].values) < 2:
                continue
            ax.plot([r.values[0] for r in b.rows], [r.values[1] for r in b.rows], "k-", lw=1)
            for r in b.rows:
                if r.lab and type_name(r.ty) not in ("", "RG"):
                    ax.plot(r.values[0], r.values[1], "ro", ms=3)
                    ax.annotate(f"{type_name(r.ty)}{r.lab}", (r.values[0], r.values[1]),
                                fontsize=7)
            if b.titles:
                ax.set_xlabel(b.titles[0])
                ax.set_ylabel(b.titles[1] if len(b.titles) > 1 else "")
        save_figure(fig, path, dpi=100)
        plt.close(fig)

    def savefig(self, path, **kw) -> None:
        self.draw(path)

    def config(self, *args, **kw) -> None:
        """Plot options of AUTO's plotter: accepted, without effect on the PNG."""


def plot(name=None, **kw):
    """Draw a bifurcation diagram into a PNG file instead of a window: the first
    column against the second for every branch, special points labelled. Returns a
    Plot (savefig writes other copies)."""
    bd = name if isinstance(name, Diagram) else loadbd(name)
    global _plots
    _plots += 1
    stem = name if isinstance(name, str) else "plot"
    out = Path(f"{stem}-{_plots}.png")
    p = Plot(bd, out)
    print(f"Plot written to {out}")
    return p


_plots = 0


# Solutions and diagrams run themselves (AUTO's solution.run(...)) through this module's run.
diagram._run_command = run


def info(s):
    sys.stdout.write(s)


def query_diagnostic(diagnostic: str, name=None) -> None:
    """AUTO's queryDiagnostic: print the lines of d.NAME (fort.9 without a name) that
    contain the word diagnostic."""
    path = Path(f"d.{name}" if name else FORT[2])
    if not path.exists():
        raise AutoError(f"no diagnostics file {path}")
    for line in path.read_text().splitlines():
        if diagnostic in line:
            print(line)
    print()


def _diagnostic(word: str, what: str):
    def command(name=None):
        query_diagnostic(word, name)
    command.__name__ = what
    command.__doc__ = f"Print the {what} lines of d.NAME (fort.9): AUTO's command of that name."
    return command


def plot3(name=None, **kw):
    """AUTO's 3D viewer (plaut04) needs a display: headless runs note it and go on."""
    print(f"plot3({name!r}): AUTO's 3D viewer is not part of washer; nothing drawn")


#: Every command under AUTO's names and aliases.
COMMANDS = {
    "run": run, "r": run, "rn": run, "load": load, "ld": load, "loadbd": loadbd, "bd": loadbd,
    "save": save, "sv": save, "append": append, "ap": append, "merge": merge, "mb": merge,
    "relabel": relabel, "rl": relabel, "clean": clean, "cl": clean, "delete": delete,
    "dl": delete, "copy": copy, "cp": copy, "move": move, "mv": move, "ch": ch, "cc": ch,
    "changeconstant": ch, "pr": pr, "pc": pr, "printconstant": pr, "sl": sl,
    "solutionget": sl, "dg": dg, "diagramget": dg, "df": df, "deletefort": df, "wait": wait,
    "cat": cat, "ls": ls, "cd": cd, "shell": shell, "quit": quit, "q": quit, "plot": plot,
    "pl": plot, "p2": plot, "splabs": splabs, "info": info,
    "plot3": plot3, "p3": plot3, "queryDiagnostic": query_diagnostic,
    "dsp": dsp, "ksp": ksp, "dlb": dlb, "klb": klb, "cn": cn, "constantsget": cn,
    "bt": loadbd, "diagramandsolutionget": loadbd,
    # HomCont's constants (h-file keys IEQUIB, NUNSTAB, ...) live with the others here
    "hch": ch, "hpr": pr,
}
#: AUTO's diagnostic queries (AUTOCommands.py: branchpoint ... stepsize): the word each
#: looks for in the d-file, and the command's names.
DIAGNOSTICS = {"BP": ("branchpoint", "bp", "br"), "Eigenvalue": ("eigenvalue", "ev", "eg"),
               "Mult": ("floquet", "fl"), "Hopf": ("hopf", "hp", "hb"),
               "Iterations": ("iterations", "it"), "Fold": ("limitpoint", "lm", "lp"),
               "NOTE": ("note", "nt"), "SPB": ("secondaryperiod", "sp", "sc"),
               "Step": ("stepsize", "ss", "st")}
COMMANDS.update({alias: _diagnostic(word, names[0])
                 for word, names in DIAGNOSTICS.items() for alias in names})
