"""Equations known by name instead of by a file beside the constants file.

    resolve = named_problem("washer:frozen")    # None for a user's NAME (NAME.py, NAME.f90, ...)
    problem = resolve(constants, folder)

A constants file's e = 'NAME' or 'NAME:variant' names either a user file beside it or one
of the families below, which the package ships. The table names each family's module by
its import path, imported on first use: AUTO's command language (washer.auto.clui) looks
e up here and so stays below the problems it runs (the AUTO file layer imports no
problem of the washer's, and `import washer.auto` does not load the washer's model).
"""
from __future__ import annotations

import importlib

#: Family name (e before ':') -> the module whose resolve_problem(c, folder, params=None)
#: builds the Problem (washer.cont.problem.Problem) from the constants c.
NAMED_PROBLEMS = {"washer": "washer.problems.resolve"}


def named_problem(e: str):
    """The resolve_problem(c, folder, params=None) of the family e names ('washer',
    'washer:frozen', ...), or None when e names no family (a user's file)."""
    module = NAMED_PROBLEMS.get(e.split(":")[0])
    return None if module is None else importlib.import_module(module).resolve_problem
