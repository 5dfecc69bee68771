"""The washer as a continuation problem (e='washer' in a constants file).

State u = (eps, eps_dot), NDIM = 12, of the rotating-frame system (eq 59),
averaged over the frame angle (e='washer') or frozen at tau0 (e='washer:frozen').
PAR indices (1-based, AUTO's PAR(11) is left to the period):
"""
from __future__ import annotations

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


def washer_problem(e: str, constants) -> Problem:
    frame = {"washer": "averaged", "washer:averaged": "averaged",
             "washer:frozen": "frozen"}.get(e)
    if frame is None:
        from washer.cont.driver import RunError
        raise RunError(f"{constants.source}: e='{e}': expected 'washer', 'washer:averaged' or "
                       "'washer:frozen'")
    params = load_params()
    base = params.vector()
    tied = params.tied
    cols = {name: kernel.DIFF_NAMES.index(name) for name in PAR_NAMES.values()}

    def kernel_params(par):
        P = base.copy()
        for i, name in PAR_NAMES.items():
            P[layout.INDEX[name]] = par[i - 1]
        if tied:
            P[layout.INDEX["C_ox"]] = P[layout.INDEX["C_oz"]] = par[0]
        return P

    def func(u, par):
        return kernel.rhs_rot(u, kernel_params(par), frame)

    def dfdu(u, par):
        return kernel.jac_rot(u, kernel_params(par), frame)[0]

    def dfdu_batch(us, pars):
        return kernel.jac_rot_batch(us, np.array([kernel_params(p) for p in pars]), frame)[0]

    def dfdp(u, par):
        Jp = kernel.jac_rot(u, kernel_params(par), frame)[1]
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

    return Problem(12, func, stpnt, dfdu, dfdp, name=e, npar=NPAR, dfdu_batch=dfdu_batch)
