"""Which equations a constants file's e names: the washer's built-in problems (e='washer',
'washer:frozen', 'washer:forced', 'washer:shooting') with injected parameters, else the user's
NAME.py or AUTO's NAME.f90 / NAME.f / NAME.c beside the constants file
(washer.cont.user_files). Used by `washer.run` and by AUTO's command language."""
from __future__ import annotations

import warnings
from pathlib import Path

from washer.cont.constants import Constants
from washer.cont.problem import Problem
from washer.cont.runner import RunError
from washer.cont.user_files import load_user_problem


def resolve_problem(c: Constants, folder: Path, params=None) -> Problem:
    """The equations named by e: the built-in washer (with `params`, a
    washer.Params, or the shipped reference set) or NAME.py beside the file."""
    e = c["e"]
    if not e:
        raise RunError(f"{c.source}: no equations: set e='NAME' (NAME.py, or AUTO's NAME.f90, "
                       "NAME.f or NAME.c, beside the file) or e='washer'")
    if e.split(":")[0] == "washer":
        from washer.machine.layout import PAR_NAMES
        from washer.machine.params import ParameterError
        from washer.problems.washer import forced_start_params, washer_problem
        # The PAR values of the constants file must be a valid parameter set (m_t > 0,
        # Omega >= 0, ...), as a parameter file's would: checked here, named by the file.
        try:
            start = forced_start_params(c, params)
        except ParameterError as exc:
            detail = str(exc).split(": ", 1)[-1]
            raise RunError(f"{c.given.get('PAR', c.source)}: PAR: {detail}") from None
        if c["IRS"] in (0, "0"):
            # AUTO's STPNUS: STPNT, then the constants' PAR override its values; the
            # state stpnt gives must then be the solution at those values (the
            # equilibrium at C_p = 0 of c.washer, not at the reference C_p), which it is
            # when stpnt computes it at the start parameters.
            params = start
        for i in c.icp():
            if i not in PAR_NAMES and i not in (11, 12) and c["ISW"] in (0, 1, -1):
                warnings.warn(f"{c.given.get('ICP', c.source)}: ICP: PAR({i}) is not a "
                              f"parameter of e={e!r} (its parameters: "
                              f"{', '.join(f'{k}={n}' for k, n in PAR_NAMES.items())}): "
                              "the branch continues a value the equations do not read",
                              UserWarning, stacklevel=3)
        return washer_problem(e, params=params, source=c.source)
    # NAME.py, else AUTO's NAME.f90, NAME.f or NAME.c, compiled on first use.
    return load_user_problem(e, folder, c["NDIM"])
