"""What the washer's continuation problems share: AUTO's PAR map of the kernel's
parameters (washer.machine.layout.PAR_NAMES; PAR(11) is left to the period), the
kernel parameter vector for a PAR vector (the tied dampers moving with C_p), and the
shipped reference set, read once per process."""
from __future__ import annotations

import functools

import numpy as np

from washer.machine import layout
from washer.machine.params import load_params

#: PAR(i) -> kernel parameter name (washer.machine.layout.PAR_NAMES). C_p moves C_ox
#: and C_oz with it when the parameter file ties them (layout.moved_by).
PAR_NAMES = layout.PAR_NAMES
NPAR = 17


def set_par(par: np.ndarray, params) -> None:
    """AUTO's PAR vector (NPAR,) filled in place from a washer.Params (an stpnt's job):
    PAR(i) = params[PAR_NAMES[i]] for every mapped i <= len(par); the others (PAR(11),
    the period; PAR(12)) are left as they are."""
    for i, name in PAR_NAMES.items():
        if i <= len(par):
            par[i - 1] = params[name]


def kernel_parameters(params):
    """(kernel_params(par) -> P, kernel_params_many(pars) -> (k, N_PARAMS)): the kernel's
    parameter vector for AUTO's PAR vector(s), the other entries from `params`; the tied
    dampers move with C_p = PAR(1) (layout.moved_by)."""
    base = params.vector()
    tied = params.tied
    idx = np.array([layout.INDEX[n] for n in PAR_NAMES.values()])
    par_idx = np.array([i - 1 for i in PAR_NAMES])

    def kernel_params(par):
        P = base.copy()
        P[idx] = np.asarray(par)[par_idx]
        for name in layout.moved_by("C_p", tied)[1:]:
            P[layout.INDEX[name]] = par[0]
        return P

    def kernel_params_many(pars):
        pars = np.asarray(pars, dtype=float)
        P = np.repeat(base[None, :], len(pars), axis=0)
        P[:, idx] = pars[:, par_idx]
        for name in layout.moved_by("C_p", tied)[1:]:
            P[:, layout.INDEX[name]] = pars[:, 0]
        return P
    return kernel_params, kernel_params_many


@functools.lru_cache(maxsize=1)
def _reference_params():
    """The shipped reference parameter set, read once per process."""
    return load_params()
