"""Runs of invariant circles of a map (the continued system is
washer.cont.systems.circles.InvariantCircles): the constants of a circle run, the first
circle of the family born at a Neimark-Sacker point (the engine's corrector), the family
continued in a parameter as an engine run (`continue_circles`: runner.execute, sinks for
b-/s-/d-files) and the circles read back from the run's Branch.

    first = first_circle(fmap, x_star, v, rho0, p0, amplitude, N)
    branch = continue_circles(fmap, first, stop)
    circles(branch), reached(branch)

fmap(X (N, n), p) -> (F (N, n), DF (N, n, n), Fp (N, n)) as in washer.cont.invariant_circle.
"""
from __future__ import annotations

import math

import numpy as np

from washer.cont import invariant_circle as ic
from washer.cont.branch import Branch, Record
from washer.cont.constants import Constants
from washer.cont.iterator import Continuation
from washer.cont.runner import Run, execute
from washer.cont.settings import Settings
from washer.cont.systems.circles import (COLUMNS, EPS_LOCATE, NEWTON_MAX_ITER, NEWTON_TOL,
                                         InvariantCircles)


def constants(index: int, stop: float, n: int, *, ds: float, ds_max: float, ds_min: float,
              max_points: int, tol: float = NEWTON_TOL, **kw) -> Constants:
    """The constants of a circle run in PAR(index) up to PAR(index) = stop (UZSTOP), n the
    map's dimension: full Newton (NWTN = ITNW) to EPSL = EPSU = tol (relative corrections),
    AUTO's step control between ds_min and ds_max, NMX = max_points, every point a
    regular one (NPR = 0), no tests but the UZ value."""
    base = dict(e="circle", NDIM=n, IPS=-1, IRS=0, ISW=1, ICP=[index], ILP=0, ISP=0,
                NMX=max_points, NPR=0, MXBF=0, ITNW=NEWTON_MAX_ITER,
                NWTN=NEWTON_MAX_ITER, ITMX=30, EPSL=tol, EPSU=tol, EPSS=EPS_LOCATE,
                DS=ds, DSMIN=ds_min, DSMAX=ds_max, IADS=1, NPAR=max(index, 12),
                UZSTOP={index: stop})
    base.update(kw)
    return Constants(base, source="<invariant circles>")


def first_circle(fmap, x_star, v, rho0: float, p0: float, amplitude: float, N: int,
                 dp_guess: float = 0.0, tol: float = NEWTON_TOL) -> ic.Circle:
    """The first circle of the family born at a Neimark-Sacker point: the fixed point
    x_star (n,) at p0 with critical eigenvector v (n,) complex (DF v = mu v, arg mu =
    2 pi rho0). The engine's corrector from x_star + amplitude Re(v e^{i theta}) (v scaled
    to a unit largest component) with rho and p free on the plane that fixes the circle's
    mode-1 content along v at `amplitude` (near the birth the family's size, not the
    parameter, is the coordinate: p moves like amplitude^2). dp_guess: p - p0 of the guess.
    Raises ConvergenceError."""
    x_star = np.asarray(x_star, dtype=float)
    n = x_star.size
    v = np.asarray(v, dtype=complex)
    v = v / np.abs(v).max()
    th = ic.nodes(N)
    basis = np.real(np.exp(1j * th)[:, None] * v[None, :])
    X0 = x_star + amplitude * basis
    s = Settings.from_constants(constants(1, p0, n, ds=amplitude, ds_max=1.0, ds_min=1e-12,
                                          max_points=1, tol=tol))
    sysm = InvariantCircles(fmap, ic.Circle(X0, rho0, p0), s)
    # Mode-1 projection on the birth direction, (2/N) sum_j Re(conj(v e^{i th_j})) .
    # (X_j - x*) / |v|^2 = g . (x - x_ref): the plane <x - x_ref, t>_w = amplitude of the
    # corrector with border(t) = w t = g.
    g = np.r_[basis.ravel() / np.sum(basis * basis), 0.0, 0.0]
    x_ref = np.r_[np.tile(x_star, N), 0.0, 0.0]
    x, it = Continuation(sysm, s, x0=sysm._x0, tangent=g).correct(
        np.r_[X0.ravel(), rho0, p0 + dp_guess], x_ref, g / sysm.theta, amplitude, plane=True)
    c = sysm.circle(x)
    st = sysm.stability(x, None)
    c.moduli, c.tangent, c.iterations = st.values, st.tangent, it
    c.residual = float(np.abs(sysm.residual(x)).max())
    return c


def circle_of(record: Record) -> ic.Circle:
    """The circle of a written point (its stored profile without the closing node, rho
    from the ROTATION column, the normal moduli from its stability)."""
    U = np.asarray(record.u, dtype=float)[:-1]
    st = record.stability
    return ic.Circle(U.copy(), float(record.values[1 + COLUMNS.index("ROTATION")]),
                     float(record.values[0]),
                     moduli=st.values if st is not None else np.array([np.nan]),
                     tangent=getattr(st, "tangent", math.nan))


def circles(branch: Branch) -> list:
    """The circles of a run's rows, in the order computed (`circle_of`)."""
    return [circle_of(r) for r in branch.rows]


def reached(branch: Branch) -> bool:
    """Whether the run ended at its UZSTOP value (its last point a UZ)."""
    return bool(branch.rows) and branch.rows[-1].ty == "UZ"


def continue_circles(fmap, first: ic.Circle, stop: float, *, index: int = 1, par=None,
                     ds: float = 0.05, ds_max: float = 0.5, ds_min: float = 1e-4,
                     max_points: int = 200, scale=None, tol: float = NEWTON_TOL,
                     sinks=(), name: str = "circle") -> Branch:
    """The family of invariant circles of fmap from `first` until PAR(index) = p reaches
    `stop` (UZSTOP), as an engine run: `runner.execute` on `InvariantCircles` with
    `constants(...)`, through `sinks` (washer.auto.sinks: b-/s-/d-files, the screen).
    par: the full PAR vector written to the records (default zeros, PAR(index) = p);
    scale (n,): the components' typical sizes for the inner product (default 1).
    Returns the engine's Branch (`circles(branch)` reads the circles; `reached(branch)`
    whether the end value was reached). ds, ds_max, ds_min: arclength in that norm."""
    c = constants(index, stop, first.X.shape[1], ds=ds, ds_max=ds_max, ds_min=ds_min,
                  max_points=max_points, tol=tol)
    s = Settings.from_constants(c)
    if par is not None and len(par) > s.NPAR:
        s = s.with_(NPAR=len(par))
    full = np.zeros(s.NPAR)
    if par is not None:
        full[:len(par)] = par
    sysm = InvariantCircles(fmap, first, s, full, scale)
    pn = c["parnames"]
    titles = [pn.get(index, f"PAR({index})")] + sysm.column_titles()
    run = Run(c, s, sysm, name, titles, 0)
    return execute(run, 1, "fresh", sinks)
