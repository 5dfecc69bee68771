"""The steps after a branch switch of an algebraic problem, against AUTO's: ppp's first run
(AUTO's demo, constants unchanged) switches at its BPs (MXBF = 10); every row of its
branches as AUTO's b.ppp (tests/data/auto_demos/ppp/autoref).

AUTO predicts the step after the switch along UDOT = (U - UOLD) / RDS, the secant of the
switch's plane step (SOLVAE), longer than unit where the new branch leaves the plane's
normal, so its predictor lands off the sphere and Newton takes 3 iterations (d-file:
'Iterations : 3', the step kept); the unit tangent converged in 1 and ADPTDS doubled the
step one point before AUTO (branch 3 had 50 rows to AUTO's 51, 6.6e-3 apart in PAR(1) from
its fourth row on). With that secant every row is AUTO's."""
import gzip
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.run import run

DEMO = Path(__file__).parent / "data" / "auto_demos" / "ppp"


def _rows(text: str) -> np.ndarray:
    """The equilibrium rows (BR > 0) of a b-file: BR, PT, TY, LAB, then the columns."""
    out = []
    for line in text.splitlines():
        words = line.split()
        if len(words) > 4 and int(words[0]) > 0:
            out.append([float(w) for w in words])
    return np.array(out)


@pytest.mark.skipif(shutil.which("gfortran") is None, reason="ppp.f90 needs gfortran")
def test_switched_branches_step_as_auto(tmp_path):
    for f in ("ppp.f90", "c.ppp"):
        shutil.copy(DEMO / f, tmp_path)
    r = run(tmp_path / "c.ppp", e="ppp", verbose=False)
    ours = _rows(Path(r.files.b_path).read_text())
    text = gzip.decompress((DEMO / "autoref" / "b.ppp.gz").read_bytes()).decode()
    # b.ppp holds the first run's branches (1 to 3), then the periodic orbits (-4)
    auto = _rows(text)
    assert ours.shape == auto.shape
    np.testing.assert_array_equal(ours[:, [0, 2, 3]], auto[:, [0, 2, 3]])
    np.testing.assert_array_equal(np.abs(ours[:, 1]), np.abs(auto[:, 1]))
    # every row: PAR(1) and the state within 1e-4 (EPSU = EPSL = 1e-6 Newton; the BPs,
    # where the branches start, are located to EPSS = 1e-4 in arclength)
    assert np.abs(ours[:, 4:] - auto[:, 4:]).max() < 1e-4
