"""Which equations a constants file's e names: a family the package ships, or the user's
file beside the constants file.

    problem = resolve_problem(constants, folder, params)    # what `washer.run` runs
    build = named_problem("washer:frozen")    # a family's from_constants, None for a file

e = 'NAME' or 'NAME:variant' names one of the families below when NAME is theirs, else
the user's NAME.py or AUTO's NAME.f90, NAME.f, NAME.c (washer.cont.user_problem.user_files). The
table
names each family's module by its import path, imported on first use: `washer.run` and
AUTO's command language (washer.auto.clui) look e up here and so stay below the problems
they run (the AUTO file layer imports no problem of the washer's, and a run of a user's
file does not load the washer's model). A new family is a module with from_constants and
a line in NAMED_PROBLEMS.
"""
from __future__ import annotations

import importlib

#: Family name (e before ':') -> the module whose from_constants(c, folder, params=None)
#: builds the Problem (washer.cont.problem.Problem) from the constants c.
NAMED_PROBLEMS = {"washer": "washer.problems.resolve"}


def named_problem(e: str):
    """The from_constants(c, folder, params=None) of the family e names ('washer',
    'washer:frozen', ...), or None when e names no family (a user's file)."""
    module = NAMED_PROBLEMS.get(e.split(":")[0])
    return None if module is None else importlib.import_module(module).from_constants


def resolve_problem(c, folder, params=None):
    """The Problem of the constants c (washer.cont.constants.Constants): the family's that
    c["e"] names, built from c and `params` (the family's parameter set, e.g. a
    washer.Params; default: its own), else the user's file in `folder` (washer.cont.
    user_files.load_user_problem). RunError naming the constants file when e is empty."""
    from washer.cont.runner import RunError
    from washer.cont.user_problem.user_files import load_user_problem
    e = c["e"]
    if not e:
        raise RunError(f"{c.source}: no equations: set e='NAME' (NAME.py, or AUTO's NAME.f90, "
                       "NAME.f or NAME.c, beside the file) or e='washer'")
    build = named_problem(e)
    if build is not None:
        return build(c, folder, params)
    # NAME.py, else AUTO's NAME.f90, NAME.f or NAME.c, compiled on first use.
    return load_user_problem(e, folder, c["NDIM"])
