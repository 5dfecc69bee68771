"""The washer as a continuation problem (e='washer' in a constants file).

State u = (eps, eps_dot), NDIM = 12, of the rotating-frame system (eq 59),
averaged over the frame angle (e='washer') or frozen at tau0 (e='washer:frozen').
PAR indices (1-based, AUTO's PAR(11) is left to the period):
"""
from __future__ import annotations

import functools

import numpy as np

from washer import kernel, layout
from washer.cont.problem import Problem
from washer.machine import Model
from washer.params import load_params

#: PAR(i) -> kernel parameter name. C_p moves C_ox and C_oz with it when the
#: parameter file ties them (the paper's C_ox = C_oy = C_oz = C_p).
PAR_NAMES = {1: "C_p", 2: "Omega", 3: "m_u", 4: "R_u", 5: "h_u", 6: "C_a", 7: "K_s",
             8: "C_ox", 9: "C_oz", 10: "l0", 12: "J_bz", 13: "J_bt", 14: "m_b", 15: "h_b",
             16: "m_t"}
__doc__ += "\n".join(f"    PAR({i}) = {n} ({layout.UNITS[n]})" for i, n in PAR_NAMES.items())
NPAR = 16


def washer_problem(e: str = "washer", params=None, source: str = "<washer>") -> Problem:
    """The washer as AUTO's FUNC/STPNT for the rotating frame named by e
    ('washer' or 'washer:averaged', 'washer:frozen'), with `params` (a
    washer.Params; default the shipped reference set, loaded once per process)
    injected: nothing is reloaded or changed behind the caller's back."""
    frame = {"washer": "averaged", "washer:averaged": "averaged",
             "washer:frozen": "frozen"}.get(e)
    if frame is None:
        from washer.cont.runner import RunError
        raise RunError(f"{source}: e='{e}': expected 'washer', 'washer:averaged' or "
                       "'washer:frozen'")
    if params is None:
        params = _reference_params()
    base = params.vector()
    tied = params.tied
    cols = {name: kernel.DIFF_NAMES.index(name) for name in PAR_NAMES.values()}
    idx = np.array([layout.INDEX[n] for n in PAR_NAMES.values()])
    par_idx = np.array([i - 1 for i in PAR_NAMES])

    def kernel_params(par):
        P = base.copy()
        P[idx] = np.asarray(par)[par_idx]
        if tied:
            P[layout.INDEX["C_ox"]] = P[layout.INDEX["C_oz"]] = par[0]
        return P

    def kernel_params_many(pars):
        pars = np.asarray(pars, dtype=float)
        P = np.repeat(base[None, :], len(pars), axis=0)
        P[:, idx] = pars[:, par_idx]
        if tied:
            P[:, layout.INDEX["C_ox"]] = P[:, layout.INDEX["C_oz"]] = pars[:, 0]
        return P

    # jac_rot returns J and Jp together: dfdu and dfdp at the same point (every
    # Newton step asks for both) share one kernel call through this cache.
    last = {"key": None, "val": None}

    def jac(u, par):
        key = (np.asarray(u, float).tobytes(), np.asarray(par, float).tobytes())
        if last["key"] != key:
            last["key"], last["val"] = key, kernel.jac_rot(u, kernel_params(par), frame)
        return last["val"]

    def func(u, par):
        return kernel.rhs_rot(u, kernel_params(par), frame)

    def func_batch(us, pars):
        return kernel.rhs_rot_batch(np.ascontiguousarray(us), kernel_params_many(pars), frame)

    def dfdu(u, par):
        return jac(u, par)[0].copy()

    def dfdu_batch(us, pars):
        return kernel.jac_rot_batch(np.ascontiguousarray(us), kernel_params_many(pars), frame)[0]

    def dfdp(u, par):
        Jp = jac(u, par)[1]
        out = np.zeros((12, len(par)))
        for i, name in PAR_NAMES.items():
            if i <= len(par):
                out[:, i - 1] = Jp[:, cols[name]]
        if tied:
            out[:, 0] += Jp[:, cols["C_ox"]] + Jp[:, cols["C_oz"]]
            out[:, 7] = out[:, 8] = 0.0
        return out

    def stpnt(u, par):
        for i, name in PAR_NAMES.items():
            if i <= len(par):
                par[i - 1] = params[name]
        u[:] = np.r_[Model(params).rotating_equilibrium(frame=frame), np.zeros(6)]

    return Problem(12, func, stpnt, dfdu, dfdp, name=e, npar=NPAR, dfdu_batch=dfdu_batch,
                   func_batch=func_batch, parnames=dict(PAR_NAMES))


@functools.lru_cache(maxsize=1)
def _reference_params():
    """The shipped reference parameter set, read once per process."""
    return load_params()
