"""ISW = -1 at a label that is not a branch point, on an algebraic problem (IPS = 1):
AUTO's CNRLAE restarts with STPRAE's IPERP = 1 direction (the 'null vector' of
[f_u f_lambda; the stored direction]) and a branch switch's first step. At a regular
point that continues the one branch as a new branch; at ab's end UZ the direction lies
nearly across the branch and the first step ends MX. Compared with Debian AUTO-07p's
own output of the same script on its ab demo (constants unchanged)."""
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.auto import clui
from washer.auto.script import run_script

DATA = Path(__file__).parent / "data"


def _rows(path: Path) -> np.ndarray:
    """The b-file's point rows: BR, PT, TY, LAB, then the columns."""
    out = []
    for line in path.read_text().splitlines():
        words = line.split()
        if len(words) > 4 and words[0] != "0":
            out.append([float(w) for w in words])
    return np.array(out)


@pytest.mark.skipif(shutil.which("gfortran") is None, reason="ab.f90 needs gfortran")
def test_isw_minus_one_at_labels_that_are_not_branch_points_as_auto(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for f in ("ab.f90", "c.ab.1", "c.ab.2"):
        shutil.copy(DATA / "auto_demos" / "ab" / f, tmp_path)
    shutil.copy(DATA / "isw_ae" / "isw.auto", tmp_path)
    clui._runner.refused.clear()
    run_script("isw.auto")
    for name in ("hb", "rg", "rgm", "uz"):
        ours, auto = _rows(Path(f"b.{name}")), _rows(DATA / "isw_ae" / f"b.{name}")
        # the same points: branch 2 (a new branch), PT with stability sign, types, labels
        assert ours.shape == auto.shape, name
        if name == "hb":
            # The restart point is a located Hopf point: its pair's real part is zero to
            # the location's tolerance (AUTO's and ours within +-3e-9 of it, either
            # sign), so its stability sign is either; every other row's is compared.
            ours[0, 1], auto[0, 1] = abs(ours[0, 1]), abs(auto[0, 1])
        np.testing.assert_array_equal(ours[:, :4], auto[:, :4], err_msg=name)
        # values: each point is a Newton solution to EPSU = EPSL = 1e-7 (relative to
        # 1 + |value|); the UZ restart starts from the UZ each located (AUTO's 4.5e-7
        # below PAR(1) = 0.25, ours at it)
        err = np.abs(ours[:, 4:] - auto[:, 4:]) / (1 + np.abs(auto[:, 4:]))
        assert err.max() < 1e-6, (name, err.max())
    # the forward and backward runs from the regular label go the two ways of PAR(1)
    assert np.all(np.diff(_rows(Path("b.rg"))[:, 4]) > 0)
    assert np.all(np.diff(_rows(Path("b.rgm"))[:, 4]) < 0)
    assert _rows(Path("b.uz"))[-1, 2] == -9          # MX, and the script went on
