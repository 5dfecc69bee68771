"""auto_constants/c.washer finds the paper's Hopf point; the Hopf curve in (C_p, Omega)."""
import shutil
from pathlib import Path

import pytest

from washer.run import run

CONSTANTS = Path(__file__).resolve().parent.parent / "auto_constants"


@pytest.fixture(scope="module")
def washer_eq(tmp_path_factory):
    d = tmp_path_factory.mktemp("washer")
    for f in ("c.washer", "c.washer.hopf.Omega"):
        shutil.copy(CONSTANTS / f, d)
    return d, run(d / "c.washer", verbose=False)


def test_one_parameter_branch_finds_the_hopf_point(washer_eq):
    _, res = washer_eq
    hb = res("HB1")
    assert hb.par[0] == pytest.approx(0.101, rel=0.02)
    assert [s.ty for s in res.specials] == ["EP", "HB", "UZ"]
    assert res("UZ1").par[0] == pytest.approx(0.5)
    # Unstable below the Hopf point, stable above (the paper's Fig 3).
    assert res("EP1").stable is False and res("UZ1").stable is True
    assert hb.par[10] == pytest.approx(2 * 3.14159265 / 58.9, rel=0.01)   # PAR(11), rotating frame


@pytest.mark.slow
def test_hopf_curve_grows_with_omega(washer_eq):
    d, _ = washer_eq
    fwd = run(d / "c.washer.hopf.Omega", verbose=False, NMX=60)
    rows = fwd.rows
    cp = [r.values[0] for r in rows]
    om = [r.values[-1] for r in rows]
    assert om[-1] > om[0] and cp[-1] > cp[0]          # d C_p,crit / d Omega > 0 (paper, Fig 4)
