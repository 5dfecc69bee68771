"""Boundary value problems with Floquet multipliers (IPS = 7): a periodic orbit posed by
the user as a general BVP (periodicity in BCND, the phase in ICND) carries the multipliers
of its linearisation, against the closed form and AUTO-07p's own b- and d-file."""
import math
import re
import shutil
from pathlib import Path

import pytest
import sympy as sp

from washer.run import run

DATA = Path(__file__).parent / "data" / "bvp_floquet"

HNF = '''
import numpy as np
def func(u, par):
    r2 = u[0] ** 2 + u[1] ** 2
    return par[10] * np.array([par[0] * u[0] - u[1] - u[0] * r2,
                               u[0] + par[0] * u[1] - u[1] * r2])
def stpnt(u, par, t=0.0):
    par[0] = 1.0
    par[10] = 2 * np.pi
    u[:] = [np.cos(2 * np.pi * t), np.sin(2 * np.pi * t)]
def bcnd(u0, u1, par):
    return u0 - u1
def icnd(u, uold, udot, upold, par):
    return np.array([(u[0] - uold[0]) * upold[0] + (u[1] - uold[1]) * upold[1]])
'''

CONSTANTS = ("NDIM=2, IPS={ips}, ICP=[1, 11], NTST=20, NCOL=4, ISP=2, NBC=2, NINT=1, NMX=40, "
             "NPR=10, DS=-0.05, DSMIN=1e-4, DSMAX=0.1, UZR={{1: [0.5]}}, UZSTOP={{1: 0.2}}\n")


def exact_multiplier():
    """The nontrivial multiplier of the circle r^2 = p of r' = r (p - r^2), theta' = 1
    (sympy): exp(T d/dr [r (p - r^2)]) at r = sqrt(p), T = 2 pi."""
    r, p = sp.symbols("r p", positive=True)
    rate = sp.diff(r * (p - r ** 2), r).subs(r, sp.sqrt(p))
    assert sp.simplify(rate + 2 * p) == 0
    return sp.lambdify(p, sp.exp(2 * sp.pi * rate))


def test_multipliers_of_a_user_posed_cycle(tmp_path):
    """Every point's multipliers: the trivial one 1 and exp(-4 pi p); stable points have a
    negative PT in the b-file (AUTO's STPLBV: all NDIM multipliers stable); IPS = 4 runs
    the same branch without them."""
    mu_exact = exact_multiplier()
    (tmp_path / "hnf.py").write_text(HNF)
    (tmp_path / "c.hnf").write_text(CONSTANTS.format(ips=7))
    r = run(tmp_path / "c.hnf", e="hnf", sv="hnf", verbose=False)
    assert r.status == "ok"
    assert [s.ty for s in r.specials] == ["EP", "UZ", "UZ"]
    assert len(r.rows) == 14
    for row in r.rows:
        p = row.par[0]
        mu = row.stability.values
        assert row.stability.kind == "multipliers" and row.stability.stable
        # the trivial multiplier and exp(-4 pi p): the point is solved to EPSU = 1e-7
        # relative (the default), whose error enters the Jacobian the multipliers come
        # from (3e-8 and 1.1e-7 relative at most here; the collocation's own error at
        # NTST = 20, NCOL = 4 is far smaller): 1e-6 bounds both
        assert abs(mu[0] - 1) < 1e-6
        assert mu[1].real == pytest.approx(mu_exact(p), rel=1e-6)
        assert abs(mu[1].imag) < 1e-12
    b = (tmp_path / "b.hnf").read_text().splitlines()
    pts = [int(ln.split()[1]) for ln in b if ln.startswith("   1 ")]
    assert pts and all(pt < 0 for pt in pts)
    # IPS = 4: the same points, no multipliers, PT positive
    (tmp_path / "c.four").write_text(CONSTANTS.format(ips=4))
    r4 = run(tmp_path / "c.four", e="hnf", sv="four", verbose=False)
    assert [round(row.par[0], 9) for row in r4.rows] == [round(row.par[0], 9) for row in r.rows]
    assert all(row.stability is None for row in r4.rows)


def _d_multipliers(path) -> dict:
    """{PT: (mu_1, mu_2)} of a d-file's 'Multiplier k' lines (real parts)."""
    out = {}
    for line in Path(path).read_text().splitlines():
        m = re.match(r"\s+1\s+(\d+)\s+Multiplier\s+(\d)\s+(\S+)\s+(\S+)", line)
        if m:
            out.setdefault(int(m[1]), [None, None])[int(m[2]) - 1] = float(m[3])
    return out


@pytest.mark.skipif(shutil.which("gfortran") is None, reason="gfortran is not installed")
def test_against_auto07p(tmp_path):
    """AUTO-07p's Fortran user file and constants unchanged: the b-file's rows (PT with
    its stability sign, PAR(1)) and the d-file's multipliers are AUTO's, to the digits
    AUTO prints (6 significant in the d-file) and its location tolerance for the UZ."""
    for f in ("hnf.f90", "c.hnf"):
        shutil.copy(DATA / f, tmp_path)
    r = run(tmp_path / "c.hnf", e="hnf", sv="hnf", verbose=False)
    assert r.status == "ok"

    def rows(path):
        return [(int(ln.split()[1]), int(ln.split()[2]), float(ln.split()[4]))
                for ln in Path(path).read_text().splitlines() if ln.startswith("   1 ")]
    ours, auto = rows(tmp_path / "b.hnf"), rows(DATA / "autoref" / "b.hnf")
    assert [(pt, ty) for pt, ty, _ in ours] == [(pt, ty) for pt, ty, _ in auto]
    for (_, _, a), (_, _, b) in zip(ours, auto):
        # regular points are AUTO's steps to 1e-9; the UZ within EPSS (1 + sqrt(DS DSMAX))
        assert a == pytest.approx(b, abs=2e-5)
    mo, ma = _d_multipliers(tmp_path / "d.hnf"), _d_multipliers(DATA / "autoref" / "d.hnf")
    assert sorted(mo) == sorted(ma) and len(ma) == 14
    for pt in ma:
        assert mo[pt][0] == pytest.approx(ma[pt][0], abs=1e-5)
        # AUTO prints ES14.5: 6 significant digits; its UZ points lie 5e-7 off ours in p,
        # which moves exp(-4 pi p) by 6e-6 relative
        assert mo[pt][1] == pytest.approx(ma[pt][1], rel=2e-5)
    assert math.isclose(mo[1][1], math.exp(-4 * math.pi), rel_tol=1e-5)
