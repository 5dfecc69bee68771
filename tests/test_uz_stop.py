"""A UZR value and a UZSTOP value at the same parameter value: one UZ, and the run goes on.

AUTO-07p's UZ tests come first among its test functions, in IUZ's order (UZR's values as
listed, then UZSTOP's, each stored with a negative index: stop). Once the UZR value is
located, the UZSTOP test vanishes at the same point, within the location tolerance, and
LCSPAE / LCSPBV store it as 0: it neither labels the point again nor stops the run.
tests/data/uz_stop holds AUTO-07p 0.9.2's b-files of that experiment on equilibria (ab,
IPS = 1), cycles (ab, IPS = 2) and a BVP (exp, IPS = 4); washer's rule is
events._same_user_point, the same for every IPS.
"""
import math
import os
import shutil
from pathlib import Path

import pytest

from b_rows import branch_rows
from washer.auto import clui
from washer.auto.script import run_script

HERE = Path(__file__).resolve().parent / "data"
DATA = HERE / "uz_stop"
DEMOS = HERE / "auto_demos"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    d = tmp_path_factory.mktemp("uz_stop")
    for f in DATA.iterdir():
        shutil.copy(f, d)
    for demo, files in (("ab", ("ab.f90", "c.ab.1", "c.ab.2")), ("exp", ("exp.f90",))):
        for f in files:
            shutil.copy(DEMOS / demo / f, d)
    cwd = os.getcwd()
    os.chdir(d)
    try:
        clui._runner.refused.clear()
        run_script("uz.auto")
        assert not clui._runner.refused
    finally:
        os.chdir(cwd)
    return d


# (b-file, the c-file's DS, DSMAX, EPSS, NMX, the value of UZR and UZSTOP)
CASES = {"ae": (0.1, 0.2, 1e-5, 60, 18.0), "po": (0.01, 0.5, 1e-5, 170, 0.25),
         "bvp": (0.01, 0.2, 1e-4, 30, 3.0)}


@pytest.mark.parametrize("name", sorted(CASES))
def test_uzr_and_uzstop_at_one_value_label_once_and_do_not_stop(runs, name):
    ds, dsmax, epss, nmx, value = CASES[name]
    auto_file = DATA / (f"b.{name}.gz" if name == "po" else f"b.{name}")
    ours = [r for r in branch_rows(runs / f"b.{name}") if r.ty != 0]
    autos = [r for r in branch_rows(auto_file) if r.ty != 0]
    # the same labelled points: one UZ at the value, the run's end at PT = NMX (EP)
    assert [(abs(r.pt), r.ty, r.lab) for r in ours] == \
        [(abs(r.pt), r.ty, r.lab) for r in autos]
    assert ours[-1].ty == 9 and abs(ours[-1].pt) == nmx
    at_value = [r for r in ours if r.ty == -4 and abs(r.values[0] - value) < 1e-3]
    assert len(at_value) == 1
    # Each location stops within EPSS (1 + sqrt(DS DSMAX)) of arclength of the zero, and
    # PAR(ICP(1)) moves by at most the arclength (its weight THL is 1): AUTO's UZ and ours
    # lie that close to the value.
    tol = epss * (1 + math.sqrt(ds * dsmax))
    for rows in (ours, autos):
        uz = [r for r in rows if r.ty == -4 and abs(r.values[0] - value) < 1e-3]
        assert abs(uz[0].values[0] - value) <= tol
