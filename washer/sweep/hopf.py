"""The continuation's Hopf curve in the two parameters of a map (for overlays and checks).

`hopf_curve(params, x, (x0, x1), y, (y0, y1), folder)` runs the engine of
washer.run (e='washer', averaged frame) in `folder`, as an AUTO script would:

1. a one-parameter continuation of the equilibrium in x across its range (y at
   mid-range, then at its ends; then the roles swapped) until a Hopf point HB1
   is found;
2. the Hopf curve from HB1 in (x, y) (ISW = 2), both directions, stopped at the
   edges of the map (UZSTOP);

and returns the curve as a list of branches, arrays (k, 2) of (x, y), from the
runs in memory (the start run writes nothing; the curve restarts from its Branch).
The curve's b-files are written to `folder` (b.hopf_fwd, b.hopf_bwd), so
`python -m washer.plots` can draw them too.

Both parameters must be PAR entries of e='washer'; every other parameter is
`params`' (injected into the problem: run(..., params=...)). The curve lies at
the value of the map's other parameters the start run found HB1 at.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from washer.atomic import write_text
from washer.machine.params import Params
from washer.sweep.tasks import critical_constants

#: The ranges are widened by this fraction of their span so that a boundary
#: lying on the map's edge is still drawn.
EDGE = 0.02
#: Steps along the curve in the normalised parameters (THL = 1/span^2 makes the
#: arclength of crossing the map about 1): DSMAX = 1/HOPF_STEPS.
HOPF_STEPS = 60
#: Weight of kappa = omega^2 (U(25), ~3e3-1e4 (rad/s)^2) in the arclength: its
#: change over a map (~1e4) then counts about as much as the parameters.
KAPPA_WEIGHT = 1e-8


class HopfCurveError(RuntimeError):
    """No Hopf curve could be computed for the map (the message says why)."""


HOPF_CONSTANTS = """# written by washer.sweep (hopf): Hopf curve in ({x}, {y}) from HB1 of the start run
e = 'washer'
parnames = {parnames}
NDIM = 12, IPS = 1, IRS = 'HB1', ILP = 1
ICP = ['{x}', '{y}']
ISP = 2, ISW = 2, MXBF = 0
NMX = {nmx}, NPR = 0, ITMX = 8, ITNW = 7, JAC = 1
EPSL = 1e-07, EPSU = 1e-07, EPSS = 1e-05
THL = {{'{x}': {thx!r}, '{y}': {thy!r}}}
THU = {{25: {kappa!r}}}
DS = {ds!r}, DSMIN = {dsmin!r}, DSMAX = {dsmax!r}, IADS = 1
NPAR = 17
UZSTOP = {{'{x}': [{x0!r}, {x1!r}], '{y}': [{y0!r}, {y1!r}]}}
"""


def hopf_curve(params: Params, x: str, xr, y: str, yr, folder) -> list[np.ndarray]:
    """Branches (k, 2) of the averaged system's Hopf curve in (x, y) within xr x yr."""
    from washer.machine.layout import PAR_NAMES
    from washer.run import run
    for name in (x, y):
        if name not in PAR_NAMES.values():
            raise HopfCurveError(f"{name!r} is not a PAR of e='washer': no continuation")
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    (x0, x1), (y0, y1) = _widen(xr), _widen(yr)
    tried = []
    for cont, (c0, c1), other, (o0, o1) in ((x, (x0, x1), y, (y0, y1)), (y, (y0, y1), x, (x0, x1))):
        for ov in (0.5 * (o0 + o1), o0, o1):
            p = params.replace(**{other: max(ov, 0.0)})
            # The start run stays in memory; the Hopf curve restarts from its Branch.
            res = run(critical_constants(cont, max(c0, 0.0), c1), verbose=False, params=p,
                      files=False)
            start = res
            tried.append(f"{cont} in [{max(c0, 0):g}, {c1:g}] at {other} = {ov:g}")
            if any(s.ty == "HB" for s in res.specials):
                break
        else:
            continue
        break
    else:
        raise HopfCurveError("no Hopf point on " + "; ".join(tried))
    c = folder / "c.hopf"
    write_text(c, HOPF_CONSTANTS.format(
        x=x, y=y, parnames=repr(dict(PAR_NAMES)), nmx=20 * HOPF_STEPS,
        thx=1.0 / (x1 - x0) ** 2, thy=1.0 / (y1 - y0) ** 2, kappa=KAPPA_WEIGHT,
        ds=0.2 / HOPF_STEPS, dsmin=1e-5, dsmax=1.0 / HOPF_STEPS,
        x0=x0, x1=x1, y0=y0, y1=y1))
    branches = []
    for sign, sv in ((1, "hopf_fwd"), (-1, "hopf_bwd")):
        res = run(c, verbose=False, params=p, sv=sv, DS=sign * 0.2 / HOPF_STEPS,
                  restart=start)
        for br in sorted({r.br for r in res.rows}):
            # b-row values: PAR(ICP(1)), L2-norm, U(1..), PAR(ICP(2)) last.
            pts = np.array([[r.values[0], r.values[-1]] for r in res.rows if r.br == br])
            if len(pts):
                branches.append(pts)
        if res.status != "ok" and not branches:
            raise HopfCurveError(f"Hopf curve continuation ended with {res.status!r}")
    return branches


def _widen(r) -> tuple[float, float]:
    lo, hi = float(min(r)), float(max(r))
    pad = EDGE * (hi - lo)
    return lo - pad, hi + pad


def crossing_on_curve(branches: list[np.ndarray], y_value: float) -> list[float]:
    """x values where the curve crosses the line y = y_value (linear interpolation)."""
    out = []
    for b in branches:
        for (xa, ya), (xb, yb) in zip(b[:-1], b[1:]):
            if (ya - y_value) * (yb - y_value) <= 0 and ya != yb:
                out.append(xa + (y_value - ya) * (xb - xa) / (yb - ya))
    return out
