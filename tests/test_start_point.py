"""An algebraic start that is not a solution: AUTO-07p writes it as given, ours corrects it.

AUTO-07p (ae.f90, CNRLAE) takes no Newton step at the start: PT 1 is STPNT's point,
the start tangent is the null vector of [f_u f_p] there, and the first, unwritten step's
corrector (pseudo-arclength on the sphere of radius DS about the start) brings the branch
onto the solutions. Ours first corrects the start orthogonally to the branch
(Continuation.correct_start; why: the comment in Continuation._begin).
tests/data/offstart: f = u - p from u = 0.01, p = 0 (|f| = 0.01), DS = DSMAX = 0.1;
b.offstart.IPS.auto are AUTO-07p 0.9.2's b-files of the same problem as Fortran
(auto_offstart.f90), IPS 0 and 1. Both closed forms below: the solutions are u = p = t.
"""
import math
import shutil
from pathlib import Path

import pytest

from b_rows import branch_rows
from washer.run import run

DATA = Path(__file__).resolve().parent / "data" / "offstart"
DS = 0.1


def _rows(start_t, first_t):
    """(p, u) of PT 1..5: the start, then the unwritten step's t, each written step
    adding DS / sqrt(2) along the line (the first written one, too)."""
    return [start_t] + [(first_t + k * DS / math.sqrt(2),) * 2 for k in range(1, 5)]


#: AUTO: PT 1 = STPNT's (p, u) = (0, 0.01); the unwritten step's t solves
#: (t - 0.01)^2 + t^2 = DS^2 (the sphere about the uncorrected start).
AUTO_ROWS = _rows((0.0, 0.01), (0.02 + math.sqrt(0.02 ** 2 - 8 * (0.01 ** 2 - DS ** 2))) / 4)
#: Ours: the start corrected orthogonally to the line, to u = p = 0.005, then
#: t = 0.005 + DS / sqrt(2).
OUR_ROWS = _rows((0.005, 0.005), 0.005 + DS / math.sqrt(2))


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
    # AUTO's PT 1 is STPNT's point exactly (no correction); ours is on the solutions.
    assert autos[0].values[0] == 0.0 and autos[0].values[2] == 0.01
    _check(autos, AUTO_ROWS)
    _check(ours, OUR_ROWS)
