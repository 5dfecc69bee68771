"""The washer's rotating-frame equilibria as a continuation problem (e='washer',
'washer:averaged', 'washer:frozen': the system of eq 59 averaged over the frame angle or
frozen at tau0, NDIM = 12, u = (eps, eps_dot)), and the one search for its Hopf point
in a parameter: the engine's HB location along the equilibrium branch (AUTO's FNHBEQ
test, Muller location), not a root search on max Re(lambda).
"""
from __future__ import annotations

import numpy as np

from washer.cont.constants import Constants
from washer.cont.problem import Problem
from washer.cont.runner import run as run_in_memory
from washer.machine import kernel, layout
from washer.machine.model import Model
from washer.problems.parameters import (NPAR, PAR_NAMES, _reference_params, kernel_parameters,
                                        set_par)

#: Steps of the Hopf search: DSMAX = range / HOPF_STEPS keeps two Hopf points of one
#: range apart; the first step is HOPF_FIRST of the range (the engine tests no sign
#: change on its first two steps, AUTO's rule: the Hopf point must lie beyond them).
HOPF_STEPS = 80
HOPF_FIRST = 1e-6
#: Location tolerance (EPSS) of the search: Muller converges far below it in C_p.
HOPF_EPSS = 1e-9


def rotating_problem(frame: str = "averaged", params=None, name: str = "washer") -> Problem:
    """The washer as AUTO's FUNC/STPNT in the rotating frame `frame` ('averaged' or
    'frozen') with `params` (a washer.Params; default the shipped reference set)
    injected: nothing is reloaded or changed behind the caller's back."""
    if params is None:
        params = _reference_params()
    tied = params.tied
    cols = {name: kernel.DIFF_NAMES.index(name) for name in PAR_NAMES.values()}
    kernel_params, kernel_params_many = kernel_parameters(params)

    tied_names = layout.moved_by("C_p", tied)[1:]
    tied_pars = {layout.PAR_INDEX[n] for n in tied_names}

    def jp_columns(index: int) -> list:
        """The kernel's Jp columns (kernel.DIFF_NAMES) d f / d PAR(index) is made of: its
        parameter's, with the tied dampers' for C_p; none for the tied dampers' own PAR
        (they move with C_p) and for PAR the equations do not read."""
        name = PAR_NAMES.get(index)
        if name is None or index in tied_pars:
            return []
        return [cols[name]] + ([cols[n] for n in tied_names] if name == "C_p" else [])

    def par_column(Jp, index: int) -> np.ndarray:
        """d f / d PAR(index) from the kernel's Jp (..., 12, N_DIFF) -> (..., 12)."""
        out = np.zeros(Jp.shape[:-1])
        for j in jp_columns(index):       # C_p's column, then the tied ones added
            out += Jp[..., j]
        return out

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

    # The batched Jacobians of the last points: (J, Jp, the Jp columns computed, None for
    # all of them). The collocation Jacobian asks for f_u and then f_p at the points
    # whose f has just been evaluated (func_dfdu_batch): one kernel pass serves all three.
    last_batch = {"key": None, "val": None}
    # The Jp columns that pass computes: those of the PAR asked for one at a time so far
    # (dfdp_column: Newton's free parameters), all before the first such ask. The
    # parameter derivatives not asked for are a fifth of a pass; a column's values do not
    # depend on the others computed with it, so this history sets the cost, never a value.
    asked = {"columns": None}

    def batch_key(us, pars):
        return (us.shape, us.tobytes(), pars.shape, pars.tobytes())

    def jac_batch(us, pars, need=None):
        """(J, Jp) at the points, Jp holding at least the columns `need` (None: all)."""
        us, pars = np.ascontiguousarray(us, float), np.asarray(pars, float)
        key = batch_key(us, pars)
        if last_batch["key"] == key:
            J, Jp, columns = last_batch["val"]
            if columns is None or (need is not None and set(need) <= columns):
                return J, Jp
        last_batch["key"] = None
        J, Jp = kernel.jac_rot_batch(us, kernel_params_many(pars), frame)
        last_batch["val"] = (J, Jp, None)
        last_batch["key"] = key
        return J, Jp

    def dfdu_batch(us, pars):
        return jac_batch(us, pars, need=())[0].copy()

    def func_dfdu_batch(us, pars):
        # f with J and Jp from one kernel pass (f is their by-product): the Jacobians
        # asked for next at these points (the collocation Jacobian after its residual)
        # come from the cache
        us, pars = np.ascontiguousarray(us, float), np.asarray(pars, float)
        key = batch_key(us, pars)
        columns = asked["columns"]
        last_batch["key"] = None
        f, J, Jp = kernel.rhs_jac_rot_batch(us, kernel_params_many(pars), frame, columns)
        last_batch["val"] = (J, Jp, None if columns is None else frozenset(columns))
        last_batch["key"] = key
        return f

    def dfdp_column(us, pars, index):
        need = jp_columns(index)
        columns = asked["columns"]
        asked["columns"] = set(need) if columns is None else columns | set(need)
        return par_column(jac_batch(us, pars, need)[1], index)

    def dfdp_batch(us, pars):
        Jp = jac_batch(us, pars)[1]
        out = np.zeros((len(Jp), 12, np.shape(pars)[-1]))
        for i in PAR_NAMES:
            if i <= out.shape[2]:
                out[:, :, i - 1] = par_column(Jp, i)
        return out

    def dfdp(u, par):
        Jp = jac(u, par)[1]
        out = np.zeros((12, len(par)))
        for i in PAR_NAMES:
            if i <= len(par):
                out[:, i - 1] = par_column(Jp, i)
        return out

    def stpnt(u, par):
        set_par(par, params)
        u[:] = np.r_[Model(params).rotating_equilibrium(frame=frame), np.zeros(6)]

    return Problem(12, func, stpnt, dfdu, dfdp, name=name, npar=NPAR, dfdu_batch=dfdu_batch,
                   func_batch=func_batch, dfdp_batch=dfdp_batch, parnames=dict(PAR_NAMES),
                   func_dfdu_batch=func_dfdu_batch, dfdp_batch_column=dfdp_column)


def first_hopf(params, name: str = "C_p", lo: float = 0.0, hi: float = 2.0,
               frame: str = "averaged") -> tuple[float, np.ndarray]:
    """The first Hopf point of the rotating-frame equilibrium in parameter `name` (one of
    PAR_NAMES) from lo to hi, the others from `params`: the engine continues the
    equilibrium from its value at lo and stops at the first HB. Returns (the value, the
    eigenvalues there (12,), 1/s, by decreasing real part); ValueError if there is none.
    At lo itself: a neutral start (max Re(lambda) = 0 exactly, no damping at all) is
    returned as the Hopf point."""
    at_lo = params.replace(**{name: lo})
    m = Model(at_lo)
    lam = m.eigenvalues(m.rotating_equilibrium(frame=frame), frame=frame)
    if lam.real.max() == 0.0:
        return float(lo), lam
    index = layout.PAR_INDEX[name]
    span = hi - lo
    c = Constants({"NDIM": 12, "IPS": 1, "IRS": 0, "ICP": [index], "ILP": 0, "ISP": 1,
                   "ISW": 1, "MXBF": 0, "NMX": 20 * HOPF_STEPS, "NPR": 0, "JAC": 1,
                   "ITNW": 7, "ITMX": 30, "EPSL": 1e-10, "EPSU": 1e-10, "EPSS": HOPF_EPSS,
                   "DS": span * HOPF_FIRST, "DSMIN": span * 1e-12, "DSMAX": span / HOPF_STEPS,
                   "IADS": 1, "NPAR": NPAR, "UZSTOP": {index: hi}, "STOP": ["HB1"]},
                  source=f"<Hopf search in {name}>")
    br = run_in_memory(c, rotating_problem(frame, at_lo))
    hb = [r for r in br.specials if r.ty == "HB"]
    if not hb:
        raise ValueError(f"no Hopf point ({frame}) for {name} in [{lo}, {hi}] ({br.status})")
    return float(hb[0].par[index - 1]), np.asarray(hb[0].stability.values)


def averaged_hopf(params, frame: str = "averaged", c_max: float = 2.0):
    """C_p of the first Hopf point of the averaged (or frozen) rotating-frame system from
    C_p = 0 to c_max, and the eigenvalues there (`first_hopf`)."""
    return first_hopf(params, "C_p", 0.0, c_max, frame)


def hopf_or_nan(params, frame: str):
    """`averaged_hopf`, or (nan, nan eigenvalues) where there is no Hopf point."""
    try:
        return averaged_hopf(params, frame)
    except ValueError:
        return float("nan"), np.full(12, np.nan, dtype=complex)
