"""The comparison of special points with AUTO's (tests/auto_demo_compare.py) on made-up
b-files whose branch is known in closed form.

A family of cycles growing to a homoclinic orbit: at a fixed parameter the period grows
without bound while the orbit's L2 norm L tends to 1; here T(L) = 1 / (1 - L). A UZ at
PERIOD = 100 lies at L = 0.99, where dT/dL = T^2 = 1e4: AUTO's location tolerance in
arclength (EPSS (1 + sqrt|DS DSMAX|), PAR(ICP(1)) and the solution's L2 norm in it) leaves
the period free by about 1e4 times that there, more than PERIOD_RTOL.
"""
import math

import pytest
import sympy as sp

from auto_demo_compare import PERIOD_RTOL, points, same_value

EPSS, DS, DSMAX = 1e-5, 0.1, 0.2
#: twice AUTO's location tolerance in arclength (each engine within it of the zero)
TOL = 2 * EPSS * (1 + math.sqrt(DS * DSMAX))

_L = sp.Symbol("L")
_T = 1 / (1 - _L)


def _norm_at(period: float) -> float:
    """The L2 norm where the closed-form family has this period (sympy)."""
    return float(sp.solve(sp.Eq(_T, period), _L)[0])


def _period(norm: float) -> float:
    return float(_T.subs(_L, norm))


def _bfile(tmp_path, uz_norm: float, par: float = 0.0):
    """A b-file of the family: regular rows at L = 0.95 .. 0.989 and a UZ (the branch's
    last row) at L = uz_norm, all at PAR(1) = par."""
    head = [
        "   0  -1.0000E+06  1.0000E+06  0.0000E+00  1.0000E+06",
        f"   0   EPSL= 1.0000E-07  EPSU = 1.0000E-07  EPSS = {EPSS:.4E}",
        f"   0   DS  = {DS:.4E}  DSMIN= 1.0000E-03  DSMAX= {DSMAX:.4E}",
        "   0   NDIM=   2   IPS =   2   IRS =   2   ILP =   0",
        "   0",
        "   0    PT  TY  LAB " + "".join(f"{t:>19}" for t in
                                         ("PAR(1)", "L2-NORM", "MAX U(1)", "PERIOD")),
    ]
    norms = [0.95, 0.97, 0.98, 0.985, 0.989]
    rows = []
    for i, n in enumerate(norms + [uz_norm], start=1):
        last = i == len(norms) + 1
        ty, lab = (-4, 2) if last else (4, 1) if i == 1 else (0, 0)
        rows.append(f"  -2  {i:4d}  {ty:2d}  {lab:3d}  {par: .10E}  {n: .10E}  {n: .10E}  "
                    f"{_period(n): .10E}")
    path = tmp_path / "b.fam"
    path.write_text("\n".join(head + rows) + "\n")
    return points(path, True)


def _uz(pts):
    (uz,) = [p for p in pts if p.ty == "UZ"]
    return uz


def test_period_slope_is_the_period_rate_on_the_branch(tmp_path):
    """The rate read from AUTO's rows estimates the exact |dT/ds| = |dT/dL| at the point
    (over the step before it: the secant of a convex T(L) falls short of the derivative
    at the step's end by less than half)."""
    n = _norm_at(100.0) + 0.3 * TOL
    uz = _uz(_bfile(tmp_path, n))
    exact = float(sp.diff(_T, _L).subs(_L, n))
    assert 0.5 * exact <= uz.period_slope <= exact


def test_period_of_a_located_point_is_compared_in_the_arclength(tmp_path):
    """Ours exactly at PERIOD = 100; AUTO's at 0.5 tolerances of arclength beyond it
    agrees (its period is 0.11 % off, more than PERIOD_RTOL), at 5 tolerances does not."""
    near = _uz(_bfile(tmp_path, _norm_at(100.0) + 0.5 * TOL))
    ours = type(near)(near.file, "UZ", near.br, near.lab, near.par, 100.0, near.tol)
    assert abs(near.period - 100.0) > PERIOD_RTOL * near.period      # old rule: differ
    assert same_value(ours, near) is None

    far = _uz(_bfile(tmp_path, _norm_at(100.0) + 5 * TOL))
    assert far.period == pytest.approx(101.15, abs=0.01)
    why = same_value(ours, far)
    assert why is not None and why.startswith("period")


def test_parameter_is_still_compared_to_the_location_tolerance(tmp_path):
    """The period's allowance does not relax the continuation parameter's."""
    auto = _uz(_bfile(tmp_path, _norm_at(100.0), par=0.5))
    ours = type(auto)(auto.file, "UZ", auto.br, auto.lab, 0.5 + 3 * TOL, auto.period,
                      auto.tol)
    assert same_value(ours, auto).startswith("PAR")
