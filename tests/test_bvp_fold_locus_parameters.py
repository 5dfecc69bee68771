"""Fold loci of BVPs whose branch has more than one free parameter (ISW = 2 from an LP
with m = NBC + NINT - NDIM + 1 > 1): AUTO's FNBL/BCBL/ICBL, whose null vector has
parameter components q along PAR(ICP(2..m)) in PAR(NPAR + 1..NPAR + m - 1) and whose
norm, PAR(NPAR + m), is int |v|^2 dt + |q|^2.

Two problems with the locus known independently of the engine:

* u' = 0, u(0) = p2, int (u^2 + p3 u - p1) dt = 0 (m = 2: p1, p2 on the branch). The
  branch is u = p2 = c, p1 = c^2 + p3 c; its fold in p1 lies at c = -p3 / 2 with the
  null vector v = q = 1: the locus in (p1, p3) is p1 = -p3^2 / 4, u = p2 = -p3 / 2.

* Bratu's problem shifted by a parameter in the boundary conditions, with the shift
  measured by an integral: u1' = u2, u2' = -p1 e^u1, u1(0) = u1(1) = p2, int u1 dt = p3
  (m = 2: p1, p2 on the branch, p3 fixed). With w = u1 - p2, w'' = -p1 e^p2 e^w,
  w(0) = w(1) = 0 is Bratu's problem in lam = p1 e^p2, whose solutions are
  w = 2 ln cosh(th / 4) - 2 ln cosh((t - 1/2) th / 2), lam(th) = th^2 / (2 cosh^2(th / 4));
  the integral gives p2 = p3 - I(th), I(th) = int_0^1 w dt. So ln p1 = ln lam(th) +
  I(th) - p3 along the branch: its fold is at the th* where (ln lam + I)' = 0, the same
  for every p3, and the fold locus is p1 e^p3 = lam(th*) e^I(th*) with p3 - p2 = I(th*).
  th*, lam and I are computed here with mpmath (30 digits, quadrature and root finding on
  the closed-form solution), apart from the engine. The null vector's q (along p2) enters
  the boundary conditions (b_p q) and the integral's parameter part stays zero, so the
  extended system's every part is exercised by a q that matters.
"""
import math
import shutil
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

from b_rows import branch_rows
from washer.auto.files import read_s
from washer.run import run

PROBLEM = '''
import numpy as np
def func(u, par):
    return np.array([0.0])
def stpnt(u, par, t=0.0):
    par[:3] = [2.0, 1.0, 1.0]
    u[:] = 1.0
def bcnd(u0, u1, par):
    return np.array([u0[0] - par[1]])
def icnd(u, uold, udot, upold, par):
    return np.array([u[0] ** 2 + par[2] * u[0] - par[0]])
'''


def test_bvp_fold_locus_with_two_parameters_on_the_branch(tmp_path):
    """The LP of the branch at p1 = -1/4 (p3 = 1), then the fold locus from it (the
    generating run, then both ways in (p1, p3)): every row on p1 = -p3^2/4 and
    u = p2 = -p3/2 to 1e-8 (the collocation is exact for constant u; Newton's EPSL and
    the directional differences of the null vector, ~1e-8 relative, bound it), and the
    null vector's parameter part q = PAR(NPAR + 1) nonzero, the norm PAR(NPAR + 2) its
    square (v = q on u' = 0, int v^2 + q^2 = 2 q^2)."""
    (tmp_path / "fl2.py").write_text(PROBLEM)
    (tmp_path / "c.fl2").write_text("NDIM=1, IPS=4, ICP=[1, 2], NBC=1, NINT=1, NTST=5, "
                                    "NCOL=4, ILP=1, ISP=0, NMX=60, DS=-0.05, DSMAX=0.1, "
                                    "NPAR=3, UZSTOP={1: -3.0}\n")
    r1 = run(tmp_path / "c.fl2", e="fl2", sv="fl2", verbose=False)
    lp = r1("LP1")
    assert lp.par[0] == pytest.approx(-0.25, abs=1e-8)
    gen = run(tmp_path / "c.fl2", e="fl2", s="fl2", IRS=lp.lab, ICP=[1, 2, 3], ISW=2,
              sv="gen", verbose=False)
    ends = set()
    for ds in (0.05, -0.05):
        r = run(tmp_path / "c.fl2", e="fl2", s="gen", IRS=gen.specials[-1].lab,
                ICP=[1, 2, 3], ISW=2, DS=ds, NMX=200, UZSTOP={3: [-2.0, 3.0]}, sv="loc",
                verbose=False)
        assert r.specials[-1].ty == "UZ"
        ends.add(round(r.specials[-1].par[2], 1))
        assert len(r.rows) > 10
        for row in r.rows:
            p1, p2, p3 = row.par[:3]
            assert p1 == pytest.approx(-p3 ** 2 / 4, abs=1e-8)
            assert p2 == pytest.approx(-p3 / 2, abs=1e-8)
            q, norm = row.par[3], row.par[4]
            assert abs(q) > 1e-3 and norm == pytest.approx(2 * q * q, rel=1e-6)
    assert ends == {-2.0, 3.0}


BRATU_SHIFT = '''
import numpy as np
TH = 1.0      # the start: Bratu's lower solution at th = 1, p3 = 0
def func(u, par):
    return np.array([u[1], -par[0] * np.exp(u[0])])
def stpnt(u, par, t=0.0):
    th = TH
    lam = th * th / (2 * np.cosh(th / 4) ** 2)
    x = np.linspace(0.0, 1.0, 20001)
    w = 2 * np.log(np.cosh(th / 4)) - 2 * np.log(np.cosh((x - 0.5) * th / 2))
    p2 = -np.sum((w[1:] + w[:-1]) / 2) * (x[1] - x[0])
    par[:3] = [lam * np.exp(-p2), p2, 0.0]
    u[0] = p2 + 2 * np.log(np.cosh(th / 4)) - 2 * np.log(np.cosh((t - 0.5) * th / 2))
    u[1] = -th * np.tanh((t - 0.5) * th / 2)
def bcnd(u0, u1, par):
    return np.array([u0[0] - par[1], u1[0] - par[1]])
def icnd(u, uold, udot, upold, par):
    return np.array([u[0] - par[2]])
'''


def _bratu_shift_fold():
    """(lam(th*) e^I(th*), I(th*)) of the module docstring, to 30 digits."""
    mp.mp.dps = 30
    half = mp.mpf(1) / 2

    def lam(th):
        return th ** 2 / (2 * mp.cosh(th / 4) ** 2)

    def integral(th):
        return mp.quad(lambda x: 2 * mp.log(mp.cosh(th / 4))
                       - 2 * mp.log(mp.cosh((x - half) * th / 2)), [0, half, 1])

    th = mp.findroot(lambda t: mp.diff(lambda s: mp.log(lam(s)) + integral(s), t), 9)
    return float(lam(th) * mp.exp(integral(th))), float(integral(th))


# 3.9 s: slow; the fast loop follows the first problem's locus, and this one's to p3 = 1
# in test_bvp_from_a_point_of_its_fold_locus
@pytest.mark.slow
def test_bvp_fold_locus_bratu_shifted_by_a_branch_parameter(tmp_path):
    """The LP of the branch in (p1, p2) at p3 = 0, the generating run from it and the
    locus both ways to p3 = -2 and 2: every row on p1 e^p3 = C and p3 - p2 = I*, C and
    I* from the closed-form solution (module docstring). The tolerance: the collocation
    error of the fold's steep profile (th* = 9.32, NTST = 20, NCOL = 4: the LP's own
    p1 is within 1e-10 relative of C) and Newton's EPSL = 1e-7 relative on each point,
    1e-8 relative with margin. The null vector's q = PAR(NPAR + 1) stays away from 0
    (the branch turns in p2 at the fold) and its norm PAR(NPAR + 2) is held fixed
    at the generating run's end."""
    C, I = _bratu_shift_fold()
    (tmp_path / "brs.py").write_text(BRATU_SHIFT)
    (tmp_path / "c.brs").write_text("NDIM=2, IPS=4, ICP=[1, 2], NBC=2, NINT=1, NTST=20, "
                                    "NCOL=4, ILP=1, ISP=0, NMX=100, DS=0.05, DSMAX=0.5, "
                                    "NPAR=3, STOP=['LP1']\n")
    r1 = run(tmp_path / "c.brs", e="brs", sv="brs", verbose=False)
    lp = r1("LP1")
    assert lp.par[0] == pytest.approx(C, rel=1e-8)
    assert lp.par[2] - lp.par[1] == pytest.approx(I, abs=1e-8)
    gen = run(tmp_path / "c.brs", e="brs", s="brs", IRS=lp.lab, ICP=[1, 2, 3], ISW=2,
              sv="gen", verbose=False)
    assert [s.ty for s in gen.specials] == ["EP"]
    norm = gen.specials[-1].par[4]
    assert norm > 0
    ends = set()
    for ds in (0.05, -0.05):
        r = run(tmp_path / "c.brs", e="brs", s="gen", IRS=gen.specials[-1].lab,
                ICP=[1, 2, 3], ISW=2, DS=ds, NMX=300, STOP=[], UZSTOP={3: [-2.0, 2.0]},
                sv="loc", verbose=False)
        assert r.status == "ok" and r.specials[-1].ty == "UZ"
        ends.add(round(r.specials[-1].par[2]))
        assert len(r.rows) > 20
        for row in r.rows:
            p1, p2, p3, q, nrm = row.par[:5]
            assert p1 * math.exp(p3) == pytest.approx(C, rel=1e-8)
            assert p3 - p2 == pytest.approx(I, abs=1e-8)
            assert abs(q) > 1e-3 and nrm == pytest.approx(norm, rel=1e-10)   # rows: 11 digits
    assert ends == {-2, 2}


SNH = Path(__file__).parent / "data" / "auto_demos" / "snh"
#: AUTO-07p's own records of the LPs of tb.auto's 7th run (labels 8, 9: the tangencies
#: of the codimension-zero connection at nu1 = 0.739324, 0.745796), written by AUTO-07p
#: running tb.auto with the demo's constants (s.r7 of that run, the two LP records).
SNH_R7 = Path(__file__).parent / "data" / "bvp_fold" / "s.snh7.gz"
#: AUTO-07p's own record of the end (EP, label 10) of the 8th run's generating run from
#: that LP record (tests/data/bvp_fold/README.md says how it was made).
SNH_GEN8 = Path(__file__).parent / "data" / "bvp_fold" / "s.snh8gen.gz"
#: tb.auto's constants at its 8th run (the 7th run's, with the 8th run's ICP, ISW, ISP,
#: ITMX and STOP)
SNH_8 = """e='snh', NDIM=9, IPS=4, NBC=11, NINT=2, NTST=100, NCOL=4, ILP=1, ITNW=7, ITMX=20,
DS=-0.1, DSMAX=0.1, DSMIN=1e-4, NPAR=26, ISP=0, ISW=2, THL={'T': 0, 'T-': 0},
parnames={1: 'nu1', 2: 'nu2', 3: 'd', 4: 'codim', 5: 'delta', 6: 'eps', 7: 'mu', 8: 'h',
          9: 'T-', 10: 'T+', 11: 'T', 21: 'sigma-'},
ICP=['nu1', 'T', 'delta', 'nu2', 'T-', 'mu'], STOP=['LP1']
"""


def _b_rows(path):
    """The b-file's rows (PAR(ICP(1)), L2-NORM, MAX U(1), PAR(ICP(2..))), one array."""
    return np.array([r.values for r in branch_rows(path)])


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("gfortran") is None, reason="gfortran is not installed")
def test_snh_fold_locus_from_autos_lp_follows_autos_rows(tmp_path):
    """snh's tb.auto, 8th run, from AUTO-07p's own record of the LP (5 free parameters
    on the connection's branch: nu1, mu, T, delta, T-; the locus frees nu2 in place of mu
    and adds mu, so NFPR = 10 with the null vector's q along T, delta, nu2, T-). The
    generating run ends where AUTO's does (AUTO's own end record: its null vector's norm
    PAR(31) and q along T- PAR(30), up to the null vector's sign, which AUTO's STDRBV
    takes from a rate at rounding level); the locus then follows AUTO's rows of b.tb both ways:
    12 rows towards the Hopf point of the orbit (where AUTO's LP ends the run; its
    location is singular there, the orbit's amplitude going to 0) and 36 rows the other
    way, before AUTO's steps collapse (its MX at nu1 = 1.2910; ours goes on:
    docs/auto_compatibility.md).
    Every parameter and the L2 norm within 1e-6 relative (1 + |x|): each engine's points
    are Newton's to EPSL = EPSU = 1e-7 of the discretised locus, and the steps are the
    same (measured: 1.8e-8 in nu1, 1.3e-7 in T-). MAX xgamma is a maximum over the mesh's
    nodes, which the mesh adaptation moves: left out."""
    shutil.copy(SNH / "snh.f90", tmp_path)
    shutil.copy(SNH_R7, tmp_path / "s.r7.gz")
    (tmp_path / "c.tb8").write_text(SNH_8)
    gen = run(tmp_path / "c.tb8", s="r7", IRS=8, sv="gen", verbose=False)
    end = gen.specials[-1]
    assert end.ty == "EP" and len(gen.rows) == 5
    [auto_end] = read_s(SNH_GEN8)
    assert auto_end.ty == "EP" and auto_end.pt == 5
    assert end.par[30] == pytest.approx(auto_end.par[30], rel=1e-6)
    assert abs(end.par[29]) == pytest.approx(abs(auto_end.par[29]), rel=1e-5)
    ref = _b_rows(SNH / "autoref" / "b.tb")
    cols = [0, 1, 3, 4, 5, 6, 7]
    for ds, nmx, auto in ((-0.1, 12, ref[54:66]), (0.1, 36, ref[:55][::-1][:36])):
        r = run(tmp_path / "c.tb8", s="gen", IRS=end.lab, DS=ds, NMX=nmx, sv="loc",
                verbose=False)
        ours = _b_rows(tmp_path / "b.loc")
        assert ours.shape == auto.shape
        err = np.abs(ours - auto)[:, cols] / (1 + np.abs(auto[:, cols]))
        assert err.max() < 1e-6, (ds, err.max(axis=0))


# 3.4 s against AUTO's b-file; the fast loop keeps the fold locus with two parameters
@pytest.mark.slow
def test_bvp_from_a_point_of_its_fold_locus(tmp_path):
    """ISW = 1 at a point of the fold locus (its UZ at p3 = 1) continues the BVP itself
    there, as AUTOBVP does for |ISW| < 2: the record's first NDIM components, PAR(ICP(1..2))
    free and p3 fixed. The point is a fold of that branch, p1 e^p3 = C its maximum
    (module docstring): both ways p1 e^p3 falls below C, p3 stays."""
    C, _ = _bratu_shift_fold()
    (tmp_path / "brs.py").write_text(BRATU_SHIFT)
    (tmp_path / "c.brs").write_text("NDIM=2, IPS=4, ICP=[1, 2], NBC=2, NINT=1, NTST=20, "
                                    "NCOL=4, ILP=1, ISP=0, NMX=100, DS=0.05, DSMAX=0.5, "
                                    "NPAR=3, STOP=['LP1']\n")
    c = tmp_path / "c.brs"
    r1 = run(c, e="brs", sv="brs", verbose=False)
    gen = run(c, e="brs", s="brs", IRS=r1("LP1").lab, ICP=[1, 2, 3], ISW=2, sv="gen",
              verbose=False)
    loc = run(c, e="brs", s="gen", IRS=gen.specials[-1].lab, ICP=[1, 2, 3], ISW=2, DS=-0.05,
              NMX=300, STOP=[], UZSTOP={3: 1.0}, sv="loc", verbose=False)
    uz = loc.specials[-1]
    assert uz.ty == "UZ" and uz.par[2] == pytest.approx(1.0)
    for ds in (0.05, -0.05):
        b = run(c, e="brs", s="loc", IRS=uz.lab, ICP=[1, 2], ISW=1, DS=ds, NMX=6, STOP=[],
                ILP=0, sv="bvp", verbose=False)
        assert b.status == "ok" and len(b.rows) == 6
        assert "NDIM=   2" in (tmp_path / "b.bvp").read_text()
        assert b.rows[0].par[0] * math.exp(b.rows[0].par[2]) == pytest.approx(C, rel=1e-8)
        for row in b.rows[1:]:
            assert row.par[2] == pytest.approx(uz.par[2], abs=1e-10)      # rows: 11 digits
            assert row.par[0] * math.exp(row.par[2]) < C * (1 - 1e-6)
