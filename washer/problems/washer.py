"""The washer as a continuation problem (e='washer' in a constants file).

State u = (eps, eps_dot), NDIM = 12, of the rotating-frame system (eq 59),
averaged over the frame angle (e='washer') or frozen at tau0 (e='washer:frozen').
e='washer:forced' (NDIM = 14) is the exact ground-frame system at constant speed with
the forcing from an appended oscillator, AUTO's `frc` way (washer.problems.oscillator).
PAR indices (1-based, AUTO's PAR(11) is left to the period):
"""
from __future__ import annotations

from washer.cont.problem import Problem
from washer.machine import layout
from washer.problems.forced import shooting_problem
from washer.problems.oscillator import forced_problem
from washer.problems.rotating import rotating_problem
from washer.problems.parameters import NPAR, PAR_NAMES, _reference_params, set_par  # noqa: F401

#: PAR(i) -> kernel parameter name (washer.machine.layout.PAR_NAMES); the washer's
#: problems share the map and the reference set (washer.problems.parameters).
__doc__ += "\n".join(f"    PAR({i}) = {n} ({layout.UNITS[n]})" for i, n in PAR_NAMES.items())


def washer_problem(e: str = "washer", params=None, source: str = "<washer>") -> Problem:
    """The washer problem e names: the rotating frame ('washer' or 'washer:averaged',
    'washer:frozen'; washer.problems.rotating), the forced response with an appended
    oscillator ('washer:forced'; washer.problems.oscillator) or by shooting
    ('washer:shooting'; washer.problems.forced), as AUTO's FUNC/STPNT, with `params` (a
    washer.Params; default the shipped reference set, loaded once per process)
    injected: nothing is reloaded or changed behind the caller's back."""
    if e == "washer:forced":
        return forced_problem(params, source)
    if e == "washer:shooting":
        return shooting_problem(params)
    frame = {"washer": "averaged", "washer:averaged": "averaged",
             "washer:frozen": "frozen"}.get(e)
    if frame is None:
        from washer.cont.runner import RunError
        raise RunError(f"{source}: e='{e}': expected 'washer', 'washer:averaged', "
                       "'washer:frozen', 'washer:forced' or 'washer:shooting'")
    return rotating_problem(frame, params, name=e)


def forced_start_params(c, params=None):
    """The parameters a built-in washer problem starts from (IRS = 0): `params` (default
    the reference set) with the constants' PAR entries applied (names or indices of
    PAR_NAMES), as AUTO's STPNUS applies them after STPNT. stpnt must give the solution
    at the run's starting values, not at those PAR then overrides (a periodic start is
    not corrected: AUTO's STPNUB): this is the set it computes the equilibrium, or
    e='washer:forced''s orbit, at (the period PAR(11) follows from Omega)."""
    params = _reference_params() if params is None else params
    changes = {PAR_NAMES[c.par_index(k)]: float(v) for k, v in c["PAR"].items()
               if c.par_index(k) in PAR_NAMES}
    return params.replace(**changes) if changes else params
