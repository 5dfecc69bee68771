"""Time integration by continuation (IPS = -2): AUTO-07p's ivp demo against its b-file,
and the implicit Euler relation checked on every written step of a linear ODE."""
from pathlib import Path

import numpy as np
import pytest

from b_rows import branch_rows
from demo_files import autoref, copy_demo
from washer.auto.files import type_name
from washer.run import run

#: the Python transcription of ivp's equations, which the test runs in place of ivp.f90
PYTHON = Path(__file__).parent / "data" / "ivp"


def test_ivp_demo(tmp_path):
    """ivp: 500 implicit Euler steps from (0.3, 0.3) (single precision in AUTO's STPNT):
    EP at the start and at NMX, as AUTO's; the trajectory ends at the stable
    equilibrium u1 = 1/p4 = 1/3, u2 = p2 (1 - u1) = 2 (p1 = 0) that AUTO's end point
    approaches; the first written point (2 DS: the hidden step and the first) is
    AUTO's to 1e-9 (later steps follow the Newton counts, which differ)."""
    copy_demo("ivp", tmp_path, PYTHON)
    r = run(tmp_path / "c.ivp", e="ivp", sv="ivp", verbose=False)
    assert r.status == "ok"
    ref = [x for x in branch_rows(autoref("ivp") / "b.ivp")]
    assert [(s.ty, s.br, s.pt) for s in r.specials] == \
        [(type_name(x.ty), x.br, x.pt) for x in ref if x.lab] == [("EP", 1, 1), ("EP", 1, 500)]
    assert r.rows[1].values[0] == pytest.approx(ref[1].values[0], abs=1e-9)
    end = r.specials[-1]
    np.testing.assert_allclose(end.U, [1 / 3, 2.0], atol=1e-4)
    np.testing.assert_allclose(ref[-1].values[2:4], [1 / 3, 2.0], atol=1e-4)


LINEAR = '''
import numpy as np
def func(u, par):
    return np.array([-par[0] * u[0], u[0]])
def stpnt(u, par, t=0.0):
    par[0] = 2.0
    u[:] = [1.0, 0.0]
'''


def test_implicit_euler_steps(tmp_path):
    """u1' = -a u1, u2' = u1 with the time PAR(14): every written step satisfies the
    backward Euler relation u1_k+1 (1 + a dt) = u1_k, u2_k+1 = u2_k + dt u1_k+1 to the
    Newton tolerance, the step follows DS/DSMAX, and UZR on the time marks t = 1."""
    (tmp_path / "lin.py").write_text(LINEAR)
    (tmp_path / "c.lin").write_text("NDIM=2, IPS=-2, ICP=[14], ILP=0, ISP=0, NMX=200, DS=0.01, "
                                    "DSMIN=1e-5, DSMAX=0.05, NPAR=14, UZR={14: 1.0}, "
                                    "UZSTOP={14: 3.0}\n")
    r = run(tmp_path / "c.lin", e="lin", sv="lin", verbose=False)
    assert r.status == "ok"
    assert [s.ty for s in r.specials] == ["EP", "UZ", "UZ"]
    assert r.specials[1].par[13] == pytest.approx(1.0, abs=1e-9)
    rows = r.rows
    for a, b in zip(rows[1:-1], rows[2:]):
        dt = b.par[13] - a.par[13]
        assert 0 < dt <= 0.05 * 1.01
        assert b.U[0] * (1 + 2.0 * dt) == pytest.approx(a.U[0], abs=1e-9)
        assert b.U[1] == pytest.approx(a.U[1] + dt * b.U[0], abs=1e-9)
