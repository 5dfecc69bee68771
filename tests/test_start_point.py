"""An algebraic start that is not a solution is written as given, as AUTO-07p writes it.

AUTO-07p (ae.f90, CNRLAE) takes no Newton step at the start: PT 1 is STPNT's point,
the start tangent is the null vector of [f_u f_p] there, and the first, unwritten step's
corrector (pseudo-arclength on the sphere of radius DS about the start) brings the branch
onto the solutions. Ours does the same (Continuation._begin).
tests/data/offstart: f = u - p from u = 0.01, p = 0 (|f| = 0.01), DS = DSMAX = 0.1;
b.offstart.IPS.auto are AUTO-07p 0.9.2's b-files of the same problem as Fortran
(auto_offstart.f90), IPS 0 and 1. The closed form below: the solutions are u = p = t.
"""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from b_rows import branch_rows
from washer.auto import clui
from washer.auto.script import run_script
from washer.run import run

DATA = Path(__file__).resolve().parent / "data" / "offstart"
DS = 0.1


def _rows(start_t, first_t):
    """(p, u) of PT 1..5: the start, then the unwritten step's t, each written step
    adding DS / sqrt(2) along the line (the first written one, too)."""
    return [start_t] + [(first_t + k * DS / math.sqrt(2),) * 2 for k in range(1, 5)]


#: PT 1 = STPNT's (p, u) = (0, 0.01); the unwritten step's t solves
#: (t - 0.01)^2 + t^2 = DS^2 (the sphere about the uncorrected start). (A start corrected
#: first, orthogonally to the line, would give PT 1 = (0.005, 0.005) and t = 0.005 +
#: DS / sqrt(2): 1.8e-4 away from these at PT 2..5, far beyond the tolerance below.)
ROWS = _rows((0.0, 0.01), (0.02 + math.sqrt(0.02 ** 2 - 8 * (0.01 ** 2 - DS ** 2))) / 4)


def _check(rows, expected):
    # each corrector stops at EPSL = EPSU = 1e-7 relative (values below 1 here), and the
    # b-file prints 11 digits: 1e-7 absolute.
    for r, (p, u) in zip(rows, expected, strict=True):
        assert r.values[0] == pytest.approx(p, abs=1e-7)
        assert r.values[2] == pytest.approx(u, abs=1e-7)


@pytest.mark.parametrize("ips", [0, 1])
def test_inexact_algebraic_start(ips, tmp_path):
    for f in DATA.iterdir():
        shutil.copy(f, tmp_path)
    run(tmp_path / f"c.offstart.{ips}", verbose=False, sv="w")
    ours = branch_rows(tmp_path / "b.w")
    autos = branch_rows(DATA / f"b.offstart.{ips}.auto")
    assert [(r.pt, r.lab) for r in ours] == [(r.pt, r.lab) for r in autos]
    # PT 1 is STPNT's point exactly (no correction), in AUTO's b-file and ours.
    for rows in (autos, ours):
        assert rows[0].values[0] == 0.0 and rows[0].values[2] == 0.01
    _check(autos, ROWS)
    _check(ours, ROWS)


def test_a_start_far_from_any_solution_ends_mx_at_the_start_as_auto(tmp_path):
    """f = u^2 + 1 has no solution; from u = 0.3 AUTO-07p 0.9.2 writes the start as EP at
    PT 1 and, its first step failing down to DSMIN ("No convergence with minimum step
    size"), MX at PT 2 at the same point (b.far.auto, from the Fortran twin auto_far.f90
    with c.far). Ours the same rows."""
    for f in ("far.py", "c.far"):
        shutil.copy(DATA / f, tmp_path)
    run(tmp_path / "c.far", verbose=False, sv="w")
    ours, autos = branch_rows(tmp_path / "b.w"), branch_rows(DATA / "b.far.auto")
    assert [(r.pt, r.ty, r.lab, r.values) for r in ours] == \
        [(r.pt, r.ty, r.lab, r.values) for r in autos] == \
        [(1, 9, 1, [1.0, 0.3, 0.3]), (2, -9, 2, [1.0, 0.3, 0.3])]


SIGN = Path(__file__).resolve().parent / "data" / "isw_curves" / "bp" / "sign"


def test_restart_direction_sign_rule_as_auto(tmp_path, monkeypatch):
    """STPRAE's sign rule (linalg.orient) at an ISW = -1 restart on a branch-point locus
    of the pitchfork f = (u1 (p1 - u2^2 - u1^2) + p3, u2 - p2): the null vector of
    [f_u f_p1; stored direction] is e1 (the other branch) plus a PAR(1)-dot of -U-dot(1) /
    PAR(1)-dot of the record. Where that is above EPSL (U-dot(1) = +-4.85e-3) its sign
    decides, so the two records leave opposite ways; where it is rounding (+-4.85e-163)
    U(1)-dot is made positive instead, both records going to u1 > 0. As AUTO-07p 0.9.2's
    b-files of the same four restarts (tests/data/isw_curves/README.md)."""
    for f in ("pf.f90", "c.pf"):
        shutil.copy(SIGN.parent / f, tmp_path)
    for f in SIGN.iterdir():
        shutil.copy(f, tmp_path)
    monkeypatch.chdir(tmp_path)
    clui._runner.refused.clear()
    run_script("sign.auto")
    assert not clui._runner.refused
    way = {}
    for name in ("p163", "m163", "p3", "m3"):
        ours, autos = branch_rows(f"b.out{name}"), branch_rows(SIGN / f"b.out{name}")
        assert [(abs(r.pt), r.lab) for r in ours] == [(abs(r.pt), r.lab) for r in autos], name
        # each point a Newton solution to EPSU = EPSL = 1e-7; the b-file's 11 digits
        for r, a in zip(ours, autos):
            assert np.allclose(r.values, a.values, rtol=0, atol=1e-6), name
        way[name] = np.sign(ours[1].values[2])               # U(1) at PT 2
    assert way == {"p163": 1, "m163": 1, "p3": -1, "m3": 1}
