"""Event handling of the engine on AUTO's `ab` demo: several zeros in one step,
weighted arclength (THU), and equations failing at a trial point. (A zero hidden
before a located one, which linear estimates misorder, is exercised by the
washer's C_a Hopf curve in test_paper.py.)"""
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.run import run

DATA = Path(__file__).parent / "data"


@pytest.fixture
def ab(tmp_path):
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    return tmp_path / "c.ab"


def test_two_zeros_in_one_step_are_both_found_in_order(ab):
    # Two user points closer together than one step: a linear estimate could
    # take them in either order; both must be labelled, in arclength order.
    values = [0.1, 0.1000005]
    res = run(ab, verbose=False, UZR={1: values}, DS=0.05, DSMAX=0.05, NMX=20, ISP=0, ILP=0)
    uz = [s.par[0] for s in res.specials if s.ty == "UZ"]
    assert uz == [pytest.approx(v, abs=1e-9) for v in values]


def test_a_stop_next_to_another_zero_still_stops(ab):
    # A UZSTOP and a UZR zero in the same step, the UZR one first: the run must
    # label it and then stop at the UZSTOP value, not step past it.
    res = run(ab, verbose=False, UZR={1: 0.1}, UZSTOP={1: 0.1000005}, DS=0.05, DSMAX=0.05,
              NMX=20, ISP=0, ILP=0)
    uz = [s.par[0] for s in res.specials if s.ty == "UZ"]
    assert uz == [pytest.approx(0.1, abs=1e-9), pytest.approx(0.1000005, abs=1e-9)]
    assert res.specials[-1].ty == "UZ"


def test_thu_reweights_the_step(ab):
    # U(2) dominates ab's arclength at the start; weighted down, the same
    # number of steps of the same DS covers more of the parameter.
    plain = run(ab, verbose=False, NMX=5, DSMAX=0.01, ISP=0, ILP=0)
    weighted = run(ab, verbose=False, NMX=5, DSMAX=0.01, ISP=0, ILP=0, THU={2: 1e-4})
    span = lambda r: abs(r.rows[-1].values[0] - r.rows[0].values[0])
    assert span(weighted) > 2 * span(plain)


def test_equations_failing_at_a_trial_point_shrink_the_step(ab, tmp_path):
    # The equations raise beyond p1 = 0.12: the run must stop cleanly with MX
    # (after halving the step down to DSMIN), keeping the points before it.
    src = (tmp_path / "ab.py").read_text()
    (tmp_path / "ab.py").write_text(src.replace("def func(u, par):", "def func(u, par):\n"
                                                "    if par[0] > 0.12:\n"
                                                "        raise ValueError('outside the domain')",
                                                1))
    res = run(ab, verbose=False, NMX=200, ISP=0, ILP=0)
    assert res.specials[-1].ty == "MX" and "minimum step" in res.status
    p1 = np.array([r.values[0] for r in res.rows])
    assert p1.max() <= 0.12 and p1.max() > 0.11
