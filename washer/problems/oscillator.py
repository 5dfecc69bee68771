"""e='washer:forced': the washer's forced response at constant speed as an autonomous
system, the forcing angle taken from an appended oscillator (AUTO's `frc` way), NDIM = 14,
for the engine's collocation (IPS = 2). Its shooting counterpart, e='washer:shooting', is
washer.problems.forced."""
from __future__ import annotations

import numpy as np

from washer.cont.problem import Problem
from washer.machine import kernel, layout
from washer.problems.forced import periodic_response
from washer.problems.parameters import NPAR, PAR_NAMES, _reference_params, set_par

#: Forcing-angle step (rad) of the central difference d f / d theta, the washer rows'
#: dependence on the oscillator in the Jacobian: truncation h^2 |f'''| / 6 and rounding
#: eps |f| / h are both ~1e-10 relative at h = 1e-5. This column cannot move the Floquet
#: multipliers (the oscillator does not feel the washer: the monodromy matrix is block
#: triangular); it only serves Newton.
THETA_STEP = 1e-5
#: Tolerances of the kernel DOPRI5 run that samples the start orbit at stpnt's times:
#: well below the shooting's own 1e-10, so stpnt is the shooting orbit to its accuracy.
STPNT_RTOL, STPNT_ATOL = 1e-12, 1e-14
#: NDIM of e='washer:forced': the washer's (q, q_dot) and the oscillator's (x, y).
FORCED_NDIM = 14


def forced_problem(params=None, source: str = "<washer>") -> Problem:
    """e='washer:forced': the forced response at constant speed as an autonomous system
    (AUTO's `frc` demo, docs/auto.md section 3.5), NDIM = 14.

    u = (q, q_dot, x, y): the ground-frame state of eq 48 and an appended oscillator

        x' =  x + beta y - x (x^2 + y^2),   y' = -beta x + y - y (x^2 + y^2),

    beta = 2 pi PAR(2), whose stable limit cycle is x = sin(beta t), y = cos(beta t).
    The forcing angle is the oscillator's, theta = atan2(x, y): the kernel's rhs_fixed
    with law 'constant' (theta = beta t, theta_dot = beta) at t = theta / beta. The
    period PAR(11) is formally free but stays 1/Omega (the oscillator fixes it), and the
    monodromy matrix is block triangular: its multipliers are the washer's 12 (those of
    washer.machine.forced, by shooting) plus the oscillator's 1 (the trivial one) and exp(-2 PAR(11))
    (its radial decay, 0.819 at 10 Hz).

    PAR as e='washer' (PAR_NAMES; PAR(11) the period). stpnt(u, par, t) gives the
    periodic response at the values of `params` (Newton shooting, washer.machine.forced, done on
    the first call) at the scaled time t in [0, 1], the washer part by the kernel's
    DOPRI5 from t = 0 at 1e-12: exact, as frc's STPNT is. Jacobian (JAC = 1): the
    kernel's jac_fixed for the washer block, the oscillator's exactly, d f / d theta by
    central differences (THETA_STEP); dfdp by the engine's differences (JAC = 1 or 0).
    """
    if params is None:
        params = _reference_params()
    base = params.vector()
    idx = np.array([layout.INDEX[n] for n in PAR_NAMES.values()])
    par_idx = np.array([i - 1 for i in PAR_NAMES])
    tied_idx = [layout.INDEX["C_ox"], layout.INDEX["C_oz"]] if params.tied else []

    def setup(us, pars):
        """(q-states (k, 12), kernel parameters (k, N_PARAMS), t (k,), beta (k,), x, y)."""
        us, pars = np.atleast_2d(np.asarray(us, float)), np.atleast_2d(np.asarray(pars, float))
        P = np.repeat(base[None, :], len(us), axis=0)
        P[:, idx] = np.broadcast_to(pars[:, par_idx], (len(us), len(idx)))
        P[:, tied_idx] = np.broadcast_to(pars[:, :1], (len(us), 1))
        beta = 2 * np.pi * P[:, layout.INDEX["Omega"]]
        if not np.all(beta > 0):
            # Omega is the drum's speed (Hz, >= 0 in every parameter set); at 0 the
            # forcing angle theta = atan2(x, y) is no time, below it no washer.
            bad = float(P[np.argmin(beta), layout.INDEX["Omega"]])
            raise ValueError(f"Omega = {bad:g} Hz: the forced response is defined for "
                             "Omega > 0 (the drum's speed); the continuation stops here")
        x, y = us[:, 12], us[:, 13]
        return us[:, :12], P, np.arctan2(x, y) / beta, beta, x, y

    def func_batch(us, pars):
        q, P, t, beta, x, y = setup(us, pars)
        r2 = x * x + y * y
        return np.column_stack([kernel.rhs_fixed_batch(t, q, P, "constant"),
                                x + beta * y - x * r2, -beta * x + y - y * r2])

    def func(u, par):
        return func_batch(u, par)[0]

    def dfdu_batch(us, pars):
        q, P, t, beta, x, y = setup(us, pars)
        k = len(q)
        J = np.zeros((k, FORCED_NDIM, FORCED_NDIM))
        for i in range(k):
            J[i, :12, :12] = kernel.jac_fixed(t[i], q[i], P[i], "constant")[0]
        dt = THETA_STEP / beta
        f = kernel.rhs_fixed_batch(np.r_[t + dt, t - dt], np.r_[q, q], np.r_[P, P], "constant")
        f_theta = (f[:k] - f[k:]) / (2 * THETA_STEP)
        r2 = np.maximum(x * x + y * y, np.finfo(float).tiny)
        J[:, :12, 12] = f_theta * (y / r2)[:, None]         # d theta / dx = y / r^2
        J[:, :12, 13] = -f_theta * (x / r2)[:, None]        # d theta / dy = -x / r^2
        r2 = x * x + y * y
        J[:, 12, 12] = 1 - r2 - 2 * x * x
        J[:, 12, 13] = beta - 2 * x * y
        J[:, 13, 12] = -beta - 2 * x * y
        J[:, 13, 13] = 1 - r2 - 2 * y * y
        return J

    def dfdu(u, par):
        return dfdu_batch(u, par)[0]

    cache = {}          # scaled time -> (q, q_dot); "response": the shooting's orbit

    def washer_state(t):
        """The response's (q, q_dot) at scaled time t (cached: stpnt is called per node)."""
        t = float(t) % 1.0
        if t not in cache:
            if "response" not in cache:
                cache["response"] = periodic_response(params)
            r = cache["response"]
            cache[t] = r.u0 if t == 0 else kernel.integrate(
                "fixed", "constant", 0.0, r.u0, base, [t * r.T], STPNT_RTOL, STPNT_ATOL)[0][0]
        return cache[t]

    def stpnt(u, par, t=0.0):
        set_par(par, params)
        if len(par) >= 11:
            par[10] = 1.0 / params["Omega"]
        u[:12] = washer_state(t)
        u[12:] = np.sin(2 * np.pi * t), np.cos(2 * np.pi * t)

    return Problem(FORCED_NDIM, func, stpnt, dfdu, None, name="washer:forced", npar=NPAR,
                   dfdu_batch=dfdu_batch, func_batch=func_batch, parnames=dict(PAR_NAMES))
