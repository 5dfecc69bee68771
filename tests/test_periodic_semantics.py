"""What a periodic-orbit run finds and how it goes on, on problems whose answers are
known in closed form (tests/data/mobius, rotor, cyclepf; their docstrings derive them)
and on AUTO-07p's lor demo (AUTO's own b-file, constants unchanged).

Location tolerance of a special point: EPSS (1 + sqrt|DS DSMAX|) in arclength (the
tangent is unit in the weighted norm, so a parameter is off by at most that).
"""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.auto.constants import read_constants
from washer.run import run

DATA = Path(__file__).parent / "data"


def located_tol(cfile: Path) -> float:
    c = read_constants(cfile)
    return c["EPSS"] * (1 + math.sqrt(abs(c["DS"] * c["DSMAX"])))


def folder(tmp_path, name):
    for f in (DATA / name).iterdir():
        shutil.copy(f, tmp_path)
    return tmp_path


def test_pd_after_a_complex_pair_meets_the_real_axis_within_one_step(tmp_path):
    """One test function for PD and TR (AUTO's FNSPBV): from b = -0.02 (a complex pair
    inside the circle, torus type) to b = 0.02 (real, one multiplier beyond -1) the pair
    meets the axis at b = 0 and one crosses -1 at b = a^2 = 0.01. The combined test
    changes sign over the step, the located point is typed by its multipliers: PD at
    b = 0.01. (Separate PD and TR tests each saw one end of the step and found nothing;
    AUTO-07p on the same problem: PD at b = 0.010000024.)"""
    d = folder(tmp_path, "mobius")
    res = run(d / "c.mobius.spb", verbose=False, sv="spb")
    assert res.status == "ok"
    lab = [r for r in res.rows if r.lab]
    assert [r.ty for r in lab] == ["EP", "PD", "UZ"]
    assert lab[1].values[0] == pytest.approx(0.01, abs=located_tol(d / "c.mobius.spb"))
    assert lab[1].stability.values[1] == pytest.approx(-1.0, abs=1e-6)
