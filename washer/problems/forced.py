"""The washer's forced response on the continuation engine.

e='washer:shooting' (`shooting_problem`): the periodic response of the ground-frame
equations at constant speed (eq 48), NDIM = 12, u = (q, q_dot) at t = 0 (theta = 0), by
shooting on the kernel's flow with its variational equations
(washer.machine.forced.shoot); the engine's system is washer.cont.systems.shooting
(residual phi_T(u0) - u0, multipliers of the monodromy matrix, TR/PD/LP of cycles).
PAR as e='washer' (washer.problems.washer.PAR_NAMES), PAR(11) = 1/Omega the period.

On it, as engine runs in memory:
* `periodic_response(params, u0)`: the response at one parameter set (the engine's
  Newton at fixed parameters, AUTO's start correction), 3-4 iterations from averaging;
* `continue_response(params, name, stop)`: the branch in any kernel parameter with
  TR/PD/LP located;
* `locate_tr(params, name, bracket)`: the torus (Neimark-Sacker) point in one parameter;
* `critical_cp(params)`: the exact critical C_p beside the averaged and frozen Hopf ones.
"""
from __future__ import annotations

import numpy as np

from washer.cont.constants import Constants
from washer.cont import floquet
from washer.cont.problem import Problem
from washer.cont.runner import run as run_in_memory, solve
from washer.machine import forced
from washer.machine.forced import ForcedResponse, ShootingError
from washer.machine.layout import PAR_INDEX
from washer.problems.parameters import (NPAR, PAR_NAMES, _reference_params, kernel_parameters,
                                        set_par)
from washer.problems.rotating import hopf_or_nan

#: Newton's tolerance (EPSU = EPSL): relative corrections below the flow's accuracy at
#: forced.RTOL are noise (machine.forced.NEWTON_TOL).
EPS_NEWTON = forced.NEWTON_TOL
#: Location tolerance (EPSS) in arclength: the located parameter is accurate to about
#: this times its rate along the branch (Muller's last step is far below it).
EPS_LOCATE = 1e-11
#: First step of `locate_tr` as a fraction of the bracket: the engine tests no sign change
#: on its first two steps (AUTO's hidden first step and first written interval), so they
#: are kept to ~3e-2 of the bracket (DS doubles after easy steps, up to a quarter of it);
#: the callers bracket the TR point around an estimate in the middle.
FIRST_STEP = 1e-2
#: `critical_cp` searches first within +-NEAR |C_p,avg| of the averaged Hopf value (averaging
#: is 1.2e-4 relative off at nominal values), from its lower end with a first step of a
#: quarter of NEAR: the two steps on which no sign change is tested end half-way to the
#: averaged value, and the TR point is reached in 3 steps instead of 8 (from the 5 %
#: bracket's end with FIRST_STEP); where no TR point is found there, the whole bracket.
NEAR = 2e-3
#: Newton iterations per step (ITNW), location iterations (ITMX).
ITNW, ITMX = 8, 30


#: The last period map computed (key: the kernel parameters, u0, the derivative's
#: parameter; value: (u(T), Phi, d u(T)/dp)). A run started from `periodic_response`'s
#: orbit asks first for the flow that response ended with, and `locate_tr`'s response at
#: the located point for the flow its location ended with: one flow, not two.
_LAST_FLOW: list = [None]


def shooting_problem(params=None, u0=None) -> Problem:
    """e='washer:shooting' at `params` (default the reference set): flow(u0, par, index)
    is one forcing period of the kernel's DOPRI5 with the variational equations, the
    derivative in PAR(index) moving the tied dampers with C_p. stpnt: PAR from `params`,
    PAR(11) = 1/Omega, u = u0 (default the averaged start, an O(averaging) guess that the
    engine's start correction turns into the orbit)."""
    params = _reference_params() if params is None else params
    kernel_params = kernel_parameters(params)[0]
    index = forced.layout.INDEX

    def flow(u, par, i):
        P = kernel_params(par)
        name = PAR_NAMES.get(i)
        key = (P.tobytes(), np.asarray(u, dtype=float).tobytes(), name, params.tied)
        last = _LAST_FLOW[0]            # one read: (key, out) stays a pair across threads
        if last is not None and last[0] == key:
            return last[1]
        d = None if name is None else forced.direction_of(params.tied, name)
        out = forced.shoot_vector(P, u, d, omega=(name == "Omega"))[:3]
        _LAST_FLOW[0] = (key, out)
        return out

    def func(u, par):
        raise ValueError("e='washer:shooting' is a period map (flow), not a vector field: "
                         "use IPS = 2")

    def stpnt(u, par):
        set_par(par, params)
        if len(par) >= 11:
            par[10] = 1.0 / params["Omega"]
        u[:] = forced.averaged_start(params) if u0 is None else u0

    def pvls(u, par):
        par = np.array(par, dtype=float)
        par[10] = 1.0 / kernel_params(par)[index["Omega"]]
        return par

    return Problem(12, func, stpnt, name="washer:shooting", npar=NPAR, pvls=pvls,
                   parnames=dict(PAR_NAMES), flow=flow)


def constants(name: str, **kw) -> Constants:
    """The constants of a shooting run in parameter `name` (one of PAR_NAMES)."""
    if name not in PAR_INDEX:
        raise ValueError(f"parameter: expected one of {', '.join(PAR_INDEX)}, got {name!r}")
    base = dict(e="washer:shooting", NDIM=12, IPS=2, IRS=0, ISW=1, ICP=[PAR_INDEX[name]],
                ILP=1, ISP=2, NMX=400, NPR=0, MXBF=0, ITNW=ITNW, NWTN=ITNW, ITMX=ITMX,
                EPSL=EPS_NEWTON, EPSU=EPS_NEWTON, EPSS=EPS_LOCATE, NPAR=NPAR,
                THL={11: 0.0})
    base.update(kw)
    return Constants(base, source=f"<washer:shooting in {name}>")


def _response(params, sysm, x, iterations: int) -> ForcedResponse:
    uT = sysm.residual(x) + x[:-1]
    J = sysm.jacobian(x)
    return ForcedResponse(params, np.array(x[:-1]), 1.0 / params["Omega"],
                          J[:, :-1] + np.eye(12), sysm.multipliers(x),
                          float(np.abs(uT - x[:-1]).max()), iterations)


def periodic_response(params, u0=None) -> ForcedResponse:
    """The T-periodic response at `params` (u0: a starting guess, default the averaged
    start): the engine's Newton at fixed parameters (exact Jacobian Phi - I, quadratic).
    Raises ShootingError if it does not converge."""
    from washer.cont.iterator import ConvergenceError
    from washer.cont.problem import ProblemError
    try:
        x, sysm, work = solve(constants("C_p"), shooting_problem(params, u0))
    except (ConvergenceError, ProblemError) as exc:
        raise ShootingError(f"periodic response: {exc}") from exc
    return _response(params, sysm, x, work.residuals)


def continue_response(params, name: str, stop: float, *, start=None, ds: float = 0.02,
                      ds_max: float = 0.1, ds_min: float = 1e-5, max_points: int = 400):
    """The washer's forced response continued in parameter `name` (any of PAR_NAMES) from
    its value in `params` to `stop`, TR/PD/LP located: a washer.cont.branch.Branch
    (rows with multipliers; `specials`). start: a ForcedResponse at `params`.
    Pseudo-arclength in the norm of (u0, p / p_scale) (THL = 1 / p_scale^2, p_scale =
    max(|p0|, 1e-3)): steps ds are relative to the starting value, and folds of the
    response are passed."""
    p0 = params[name]
    scale = max(abs(p0), 1e-3)
    index = PAR_INDEX[name]
    c = constants(name, DS=ds if stop >= p0 else -ds, DSMAX=ds_max, DSMIN=ds_min,
                  NMX=max_points, UZSTOP={index: stop}, THL={index: 1 / scale ** 2, 11: 0.0})
    # The branch starts on the orbit at p0 itself (the engine's start correction moves
    # a start that is not a solution orthogonally to the branch, p included).
    r = start if start is not None else periodic_response(params)
    return run_in_memory(c, shooting_problem(params, r.u0))


def locate_tr(params, name: str, bracket: tuple[float, float], u0=None,
              first_step: float | None = None):
    """The torus (Neimark-Sacker, TR) point in parameter `name` inside `bracket` (a, b):
    the engine continues the response from a to b in the parameter alone (THU = 0: the
    TR point is no fold of the response) and stops at the first TR, located by the one TR
    test (|mu_c| - 1 of the critical complex multiplier). first_step: the first step in
    the parameter (default FIRST_STEP of the bracket); no TR point is seen within the
    first two. Returns (the ForcedResponse at the TR point, its Record). ValueError if
    there is none in the bracket."""
    a, b = bracket
    index = PAR_INDEX[name]
    ds = (b - a) * FIRST_STEP if first_step is None else float(np.copysign(first_step, b - a))
    c = constants(name, DS=ds, DSMAX=abs(b - a) / 4, DSMIN=abs(b - a) * 1e-9,
                  THU={i: 0.0 for i in range(1, 13)}, UZSTOP={index: b}, STOP=["TR1"],
                  ILP=0, NMX=200)
    at_a = params.replace(**{name: a})
    br = run_in_memory(c, shooting_problem(at_a, periodic_response(at_a, u0).u0))
    tr = [r for r in br.specials if r.ty == "TR"]
    if not tr:
        raise ValueError(f"locate_tr: no TR point for {name} in [{a}, {b}] ({br.status})")
    rec = tr[0]
    at = params.replace(**{name: float(rec.par[index - 1])})
    return periodic_response(at, rec.U), rec


def critical_cp(params, rel_bracket: float = 0.05, abs_bracket: float = 1e-3) -> dict:
    """The exact critical C_p (TR of the forced response) at the other values of `params`,
    beside the averaged and frozen (tau0 = params['tau0']) Hopf values.

    The TR point is searched within +-NEAR |C_p,avg| of the averaged Hopf value (a few steps
    from its lower end), then, where it is not there, within +-(rel_bracket |C_p,avg| +
    abs_bracket) (clipped at C_p = 0): averaging is accurate to far better (docs/model.md
    section 4; here 1e-5 absolute). Returns a dict: C_p_exact/averaged/frozen (nan where the
    frozen system has no Hopf in (0, 2)), the multipliers at the exact point (12,), the
    critical multiplier and its Floquet exponent log(mu)/T (1/s, imaginary part modulo
    2 pi Omega: the ground-frame whirl), the averaged eigenvalues at the averaged Hopf
    point (1/s), and the ForcedResponse there."""
    cp_avg, lam_avg = hopf_or_nan(params, "averaged")
    cp_frozen, _ = hopf_or_nan(params, "frozen")
    if np.isnan(cp_avg):        # below the averaged curve's lower end: search from C_p = 0
        r, rec = locate_tr(params, "C_p", (0.0, 2 * abs_bracket))
    else:
        r = rec = None
        near = NEAR * abs(cp_avg)
        if near < rel_bracket * abs(cp_avg) + abs_bracket and cp_avg - near > 0:
            try:
                r, rec = locate_tr(params, "C_p", (cp_avg - near, cp_avg + near),
                                   forced.averaged_start(params.replace(C_p=cp_avg - near)),
                                   first_step=near / 4)
            except (ValueError, ShootingError):     # not there: the whole bracket
                pass
        if rec is None:
            half = rel_bracket * abs(cp_avg) + abs_bracket
            bracket = (max(cp_avg - half, 0.0), cp_avg + half)
            r, rec = locate_tr(params, "C_p", bracket,
                               forced.averaged_start(params.replace(C_p=bracket[0])))
    mu_c = floquet.torus_pair(r.multipliers, trivial=False)
    return {"Omega": params["Omega"], "C_p_exact": float(rec.par[0]), "C_p_averaged": cp_avg,
            "C_p_frozen": cp_frozen, "multipliers": r.multipliers,
            "critical_multiplier": mu_c, "critical_exponent": np.log(mu_c) / r.T,
            "averaged_eigenvalues": lam_avg, "response": r}
