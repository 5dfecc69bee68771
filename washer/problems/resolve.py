"""The washer's equations as a constants file names them (e='washer', 'washer:frozen',
'washer:forced', 'washer:shooting'), with injected parameters: the family 'washer' of
washer.named_problems, which `washer.run` and AUTO's command language look e up in."""
from __future__ import annotations

import warnings
from pathlib import Path

from washer.cont.constants import Constants
from washer.cont.problem import Problem
from washer.cont.runner import RunError
from washer.machine.layout import PAR_NAMES
from washer.machine.params import ParameterError
from washer.problems.washer import forced_start_params, washer_problem


def from_constants(c: Constants, folder: Path, params=None) -> Problem:
    """The built-in washer problem e names (c["e"] = 'washer' or 'washer:VARIANT'), with
    `params` (a washer.Params; default: the shipped reference set) and the constants' PAR
    as its start. folder is unused (the equations are the package's, not a file's)."""
    e = c["e"]
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
                          UserWarning, stacklevel=4)
    return washer_problem(e, params=params, source=c.source)
