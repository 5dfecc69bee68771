"""The user's equations from a file beside the constants file (AUTO's e='NAME').

    problem = load_user_problem("ab", folder, ndim=2)

NAME.py wins when it exists: Python functions (func, stpnt, dfdu, dfdp, pvls, bcnd, icnd;
docs/continuation.md, "Your own equations") or sympy expressions u, par, f (generated into C
and compiled:
washer.cont.user_problem.user_files_sympy). Otherwise AUTO's own user file NAME.f90, NAME.f or
NAME.c, compiled on first use (washer.cont.user_problem.user_files_native). NAME is looked up
beside the constants file; as AUTO's e it may also be a path without the suffix
(e='./functions/yamada' is functions/yamada.f90 in the constants file's folder).
"""
from __future__ import annotations

import importlib.util
from pathlib import Path

from washer.cont.problem import Problem, ProblemError


def _check_file_name(name: str) -> None:
    """ProblemError unless name ends in a file's name (a path's last part: not empty, '.',
    '..' or hidden)."""
    last = name.replace("\\", "/").rsplit("/", 1)[-1]
    if not last or last.startswith(".") or "\0" in name:
        raise ProblemError(f"e='{name}': expected the name of NAME.py (or NAME.f90, NAME.f, "
                           "NAME.c), or its path without the suffix")


def find_problem_file(name: str, folder: Path) -> Path | None:
    """folder/NAME.py, else AUTO's NAME.f90, NAME.f or NAME.c (runAUTO's order); None if
    there is none. ProblemError for a name that names no file."""
    _check_file_name(name)
    py = Path(folder) / f"{name}.py"
    if py.exists():
        return py
    from washer.cont.user_problem.user_files_native import find_user_file
    return find_user_file(name, folder)


def load_user_problem(name: str, folder: Path, ndim: int) -> Problem:
    """The Problem of e='NAME' in `folder` (see the module's docstring)."""
    path = find_problem_file(name, folder)
    if path is None or path.suffix == ".py":
        return load_python_problem(name, folder, ndim)
    from washer.cont.user_problem.user_files_native import load_compiled_problem
    return load_compiled_problem(path, ndim, name=name)


#: (path, source bytes) -> the code object of the files loaded in this process: every run
#: executes NAME.py afresh (it may have changed, and its module-level state is the run's
#: own), but compiling the same source again, where no bytecode is cached
#: (PYTHONDONTWRITEBYTECODE, a read-only folder), cost each short run about a tenth of a ms
_CODE: dict = {}
_CODE_MAX = 32


def _module_code(path: Path):
    """The code of the Python file at path, as importlib's source loader compiles it."""
    source = path.read_bytes()
    key = (str(path), source)
    code = _CODE.get(key)
    if code is None:
        if len(_CODE) >= _CODE_MAX:
            _CODE.clear()
        code = _CODE[key] = compile(source, str(path), "exec", dont_inherit=True)
    return code


def load_python_problem(name: str, folder: Path, ndim: int) -> Problem:
    """The user's equations from folder/NAME.py (functions func, stpnt, dfdu, dfdp, pvls,
    bcnd, icnd, fopt).

    NAME is looked up in `folder` (a path without the suffix: in its folder there)."""
    _check_file_name(name)
    path = Path(folder) / f"{name}.py"
    if not path.exists():
        raise ProblemError(f"e='{name}': no equations file {path} (expected func(u, par) and "
                           "stpnt(u, par) there)")
    spec = importlib.util.spec_from_file_location(f"auto_user_{path.stem}", path)
    mod = importlib.util.module_from_spec(spec)
    try:
        # what spec.loader.exec_module does, with the compiled source remembered
        exec(_module_code(path), mod.__dict__)
    except Exception as exc:
        raise ProblemError(f"{path}: failed to import: {type(exc).__name__}: {exc}") from exc
    from washer.cont.user_problem import user_files_sympy
    if user_files_sympy.is_symbolic(mod):
        # u, par, f as sympy expressions: generated into C and compiled (user_files_sympy.py)
        return user_files_sympy.symbolic_problem(mod, path, ndim, name)
    if not callable(getattr(mod, "func", None)):
        raise ProblemError(f"{path}: defines no func(u, par) (nor sympy expressions u, par "
                           "and f)")
    problem = Problem(ndim, mod.func, getattr(mod, "stpnt", None), getattr(mod, "dfdu", None),
                      getattr(mod, "dfdp", None), name=name, pvls=getattr(mod, "pvls", None),
                      bcnd=getattr(mod, "bcnd", None), icnd=getattr(mod, "icnd", None),
                      fopt=getattr(mod, "fopt", None))
    # func (dfdu, dfdp) traced into compiled C where that is verified to be the same
    # function bit for bit; else this problem (washer.cont.user_problem.user_files_traced)
    from washer.cont.user_problem.user_files_traced import traced_problem
    return traced_problem(problem, path)
