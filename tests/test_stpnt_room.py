"""A Fortran STPNT that sets more components than the run's NDIM (a script's NDIM=3 on a
user file written for 4, which sets U(4)): AUTO's U has room for them (NDIM + 1 for
algebraic problems), and washer's must too. Written past the end of a 3-element buffer
they corrupted the heap, and the process aborted at exit ('double free or corruption')
after writing its files."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

USER = """      SUBROUTINE FUNC(NDIM,U,ICP,PAR,IJAC,F,DFDU,DFDP)
      IMPLICIT NONE
      INTEGER, INTENT(IN) :: NDIM, ICP(*), IJAC
      DOUBLE PRECISION, INTENT(IN) :: U(NDIM), PAR(*)
      DOUBLE PRECISION, INTENT(OUT) :: F(NDIM)
      DOUBLE PRECISION, INTENT(INOUT) :: DFDU(NDIM,NDIM), DFDP(NDIM,*)
      F(1) = PAR(1) - U(1)
      F(2) = U(1) - U(2)
      F(3) = U(2) - U(3)
      END SUBROUTINE FUNC
      SUBROUTINE STPNT(NDIM,U,PAR,T)
      IMPLICIT NONE
      INTEGER, INTENT(IN) :: NDIM
      DOUBLE PRECISION, INTENT(INOUT) :: U(NDIM),PAR(*)
      DOUBLE PRECISION, INTENT(IN) :: T
      PAR(1) = 1.0
      U(1) = 1.0
      U(2) = 1.0
      U(3) = 1.0
      U(4) = 7.0
      END SUBROUTINE STPNT
      SUBROUTINE BCND
      END SUBROUTINE BCND
      SUBROUTINE ICND
      END SUBROUTINE ICND
      SUBROUTINE FOPT
      END SUBROUTINE FOPT
      SUBROUTINE PVLS
      END SUBROUTINE PVLS
"""


@pytest.mark.skipif(shutil.which("gfortran") is None, reason="needs gfortran")
def test_stpnt_setting_one_component_more_than_ndim(tmp_path):
    (tmp_path / "ovr.f90").write_text(USER)
    (tmp_path / "c.ovr").write_text("e='ovr'\nNDIM=3, IPS=1, ICP=[1], NMX=5, DS=0.1, "
                                    "DSMAX=0.1, NPAR=1\n")
    env = dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1")
    proc = subprocess.run([sys.executable, "-m", "washer.run", "c.ovr"], cwd=tmp_path,
                          env=env, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stdout[-500:] + proc.stderr[-500:]
    rows = [ln.split() for ln in (tmp_path / "b.ovr").read_text().splitlines()
            if ln.split() and ln.split()[0] != "0"]
    # the start is STPNT's U(1..3) = 1 at PAR(1) = 1 (its U(4) is not the run's)
    par, _, *u = (float(v) for v in rows[0][4:9])
    assert (par, u) == (1.0, [1.0, 1.0, 1.0])
    assert len(rows) == 5
