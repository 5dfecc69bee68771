"""The loci of branch points (AUTO's ISW = 2 and ISW = 3 restarts at a BP label):
driven through `washer.run` on problems whose loci are known in closed form."""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from b_rows import branch_rows
from washer.run import run

# u1' = u1 (p1 - u2^2 - u1^2) [+ p3], u2 = p2: the trivial branch u1 = 0 has a
# pitchfork (BP) at p1 = p2^2, kept by the symmetry u1 -> -u1 for p3 = 0. The BP
# conditions f = 0, f_u^T phi = 0, f_p1 . phi = 0 give u1 = 0, phi = (1, 0),
# p1 = u2^2 = p2^2 and p3 = 0 (derived by hand; checked below on every point).
PITCHFORK = '''
import numpy as np
def func(u, par):
    return np.array([u[0] * (par[0] - u[1] ** 2 - u[0] ** 2) + par[2], u[1] - par[1]])
def stpnt(u, par, t=0.0):
    par[:3] = [0.0, 0.5, 0.0]
    u[:] = [0.0, 0.5]
'''


@pytest.mark.parametrize("isw", [2, 3])
def test_algebraic_branch_point_locus_closed_form(tmp_path, isw):
    """ISW = 2 (the unfolding b free, non-generic) and ISW = 3 (PAR(3) free, generic):
    both ways from the BP of the trivial branch to p2 = +-1 (through the fold of the
    locus in p1 at p2 = 0), every point on
    p1 = p2^2 with u1 = 0, phi* = (1, 0), and b (or p3) = 0. Newton stops at EPSU =
    EPSL = 1e-8 relative corrections and converges quadratically on this regular
    locus, so 1e-8 bounds the error."""
    (tmp_path / "pf.py").write_text(PITCHFORK)
    (tmp_path / "c.pf").write_text("NDIM=2, IPS=1, ICP=[1], ILP=1, ISP=1, NMX=50, DS=0.01, "
                                   "DSMAX=0.05, NPAR=3, UZSTOP={1: 1.0}\n")
    r1 = run(tmp_path / "c.pf", e="pf", sv="pf", verbose=False)
    bp = r1("BP1")
    assert bp.par[0] == pytest.approx(0.25, abs=1e-6)
    icp = [1, 2] if isw == 2 else [1, 2, 3]
    ends = set()
    for ds in (0.05, -0.05):
        r = run(tmp_path / "c.pf", e="pf", s="pf", IRS=bp.lab, ICP=icp, ISW=isw, DS=ds,
                DSMAX=0.1, NMX=200, UZSTOP={2: [-1.0, 1.0]}, sv="bp", verbose=False)
        assert r.status == "ok" and r.specials[-1].ty == "UZ"
        end = round(r.specials[-1].par[1])
        ends.add(end)
        # The codes carry curve type 1 (AUTO's ITPST). On the way to p2 = -1 the locus
        # turns in p1 at its minimum p1 = p2^2 = 0: an LP (location tolerance EPSS).
        want = [("LP", 12), ("UZ", -14)] if end == -1 else [("UZ", -14)]
        assert [(s.ty, s.code) for s in r.specials] == want
        if end == -1:
            assert abs(r.specials[0].par[1]) < 1e-5
        for row in r.rows:
            assert row.par[0] == pytest.approx(row.par[1] ** 2, abs=1e-8)
            assert abs(row.par[2]) < 1e-8
        for s in r.specials:
            u1, u2, phi1, phi2, p2, z = s.u
            assert max(abs(u1), abs(phi2), abs(z)) < 1e-8
            assert abs(phi1) == pytest.approx(1.0, abs=1e-8)
            assert u2 == pytest.approx(p2, abs=1e-8)
    assert ends == {-1, 1}
    # A point of the locus restarted with ISW = 1: AUTO's FINDLB sets ITPST = 0 for
    # |ISW| < 2, so the equilibria in PAR(1) go on from it, PAR(2) held (AUTO-07p does
    # so on this problem): from the branch point the label is, along the trivial branch
    # u1 = 0, u2 = p2, PAR(1) growing.
    end = r.specials[-1]
    r = run(tmp_path / "c.pf", e="pf", s="bp", IRS=end.lab, ICP=icp, ISW=1,
            DS=0.05, DSMAX=0.1, NMX=5, sv="again", verbose=False)
    assert r.status == "ok" and len(r.rows) == 5 and r.rows[-1].isw == 1
    for row in r.rows:
        assert abs(row.u[0]) < 1e-8 and row.u[1] == pytest.approx(end.par[1], abs=1e-8)
        assert row.par[1] == pytest.approx(end.par[1], abs=1e-12)
    assert np.all(np.diff([row.par[0] for row in r.rows]) > 0.04)
    assert all(abs(row.par[2]) < 1e-8 for row in r.rows)


# u'' + p1 u + u^3 = 0 (u1 = u, u2 = u'), u(0) = 0, u'(1) = p2 u(1) [+ p3 in the ODE]:
# the trivial branch u = 0 has a BP where the linearisation u'' + p1 u = 0 has a
# solution sin(k t), k = sqrt(p1), with k cos k = p2 sin k (kept by u -> -u for p3 = 0).
ROBIN = '''
import numpy as np
def func(u, par):
    return np.array([u[1], -par[0] * u[0] - u[0] ** 3 - par[2]])
def stpnt(u, par, t=0.0):
    par[:3] = [1.0, 0.0, 0.0]
    u[:] = 0.0
def bcnd(u0, u1, par):
    return np.array([u0[0], u1[1] - par[1] * u1[0]])
'''


@pytest.mark.parametrize("isw", [2, 3])
def test_bvp_branch_point_locus_closed_form(tmp_path, isw):
    """The BP locus of a BVP (IPS = 4), ISW = 2 (b free) and ISW = 3 (PAR(3) free): the
    generating run at the first BP of the trivial branch (k = pi/2, p2 = 0), then both
    ways to p2 = -1 and 0.9; on every point sqrt(p1) cos sqrt(p1) = p2 sin sqrt(p1),
    u = 0 and b (or p3) = 0. Tolerance 1e-9: the collocation error of the eigenvalue
    at NTST = 20, NCOL = 4 (O(h^8): pi^2 / 4 - p1 is 3e-14 at the BP), the central
    differences of f_u in the extended system (truncation h^2 = 3.6e-11 for u^3) and
    Newton (quadratic, stopped at EPSL = 1e-8 corrections) stay below it; a step of
    1e-4 there shifted the locus by 1e-8."""
    (tmp_path / "rob.py").write_text(ROBIN)
    (tmp_path / "c.rob").write_text("NDIM=2, IPS=4, ICP=[1], NBC=2, NINT=0, NTST=20, NCOL=4, "
                                    "ILP=1, ISP=2, NMX=40, DS=0.05, DSMAX=0.2, NPAR=3, "
                                    "UZSTOP={1: 3.0}\n")
    r1 = run(tmp_path / "c.rob", e="rob", sv="rob", verbose=False)
    bp = r1("BP1")
    assert bp.par[0] == pytest.approx(np.pi ** 2 / 4, abs=1e-9)
    icp = [1, 2] if isw == 2 else [1, 2, 3]
    gen = run(tmp_path / "c.rob", e="rob", s="rob", IRS=bp.lab, ICP=icp, ISW=isw, sv="gen",
              verbose=False)
    assert [(s.ty, s.code, s.pt) for s in gen.specials] == [("EP", 69, 5)]
    end = gen.specials[-1]
    # the generating run grows the adjoint only: p1 and p2 stay at the BP
    assert end.par[0] == pytest.approx(bp.par[0], abs=1e-8) and abs(end.par[1]) < 1e-8
    ends = set()
    for ds in (0.05, -0.05):
        r = run(tmp_path / "c.rob", e="rob", s="gen", IRS=end.lab, ICP=icp, ISW=isw, DS=ds,
                NMX=200, UZSTOP={2: [-1.0, 0.9]}, sv="loc", verbose=False)
        assert r.status == "ok"
        assert [(s.ty, s.code) for s in r.specials] == [("UZ", -64)]
        ends.add(round(r.specials[-1].par[1], 1))
        for row in r.rows:
            k = np.sqrt(row.par[0])
            assert k * np.cos(k) - row.par[1] * np.sin(k) == pytest.approx(0, abs=1e-9)
            assert abs(row.par[2]) < 1e-9                          # p3 (ISW = 3) stays 0
        rec = r.specials[-1]
        # b = PAR(NPAR + NBC + NINT + NFPX + 2) = PAR(8) stays 0 (ISW = 2)
        assert abs(rec.par[7]) < 1e-9
        assert np.max(np.abs(rec.u[:, :2])) < 1e-8                # u = 0 on the locus
        assert np.max(np.abs(rec.u[:, 2:])) > 1e-3                # the adjoint w is not
    assert ends == {-1.0, 0.9}



# The same equation with an integral condition int (u + u^3) dt = p4 and p4 in the
# Robin condition u'(1) = p2 u(1) + p4: two parameters (p1, p4) on the BVP's branch
# (NFPX = 2). On u = 0 the kernel sin(k t), p4 = (1 - cos k) / k gives the BP locus
# k cos k - p2 sin k - (1 - cos k) / k = 0; the integral's multiplier psi_g is not 0
# there (it carries p4's condition), so the g-terms of the adjoint are exercised.
ROBIN_INT = ROBIN.replace("par[:3] = [1.0, 0.0, 0.0]", "par[:4] = [0.5, 0.0, 0.0, 0.0]") \
    .replace("u1[1] - par[1] * u1[0]", "u1[1] - par[1] * u1[0] - par[3]") + \
    """def icnd(u, uold, udot, upold, par):
    return np.array([u[0] + u[0] ** 3 - par[3]])
"""


def test_bvp_branch_point_locus_with_an_integral_condition(tmp_path):
    """ISW = 2, ICP = [1, 4, 2] from the BP of the trivial branch in (p1, p4): both
    ways to p2 = -1 and 0.4, every point on the closed form to 1e-9 (as above; at
    NTST = 10 the collocation error is still below it: 2e-14 at the BP), p4 = 0,
    and the integral's adjoint multiplier psi_g = PAR(7) nonzero."""
    (tmp_path / "robi.py").write_text(ROBIN_INT)
    (tmp_path / "c.robi").write_text("NDIM=2, IPS=4, ICP=[1, 4], NBC=2, NINT=1, NTST=10, "
                                     "NCOL=4, ILP=1, ISP=2, NMX=40, DS=0.05, DSMAX=0.2, "
                                     "NPAR=4, UZSTOP={1: 3.0}\n")

    def on_locus(p1, p2):
        k = np.sqrt(p1)
        return k * np.cos(k) - p2 * np.sin(k) - (1 - np.cos(k)) / k
    r1 = run(tmp_path / "c.robi", e="robi", sv="robi", verbose=False)
    bp = r1("BP1")
    assert on_locus(bp.par[0], 0.0) == pytest.approx(0, abs=1e-9)
    gen = run(tmp_path / "c.robi", e="robi", s="robi", IRS=bp.lab, ICP=[1, 4, 2], ISW=2,
              sv="gen", verbose=False)
    ends = set()
    for ds in (0.05, -0.05):
        r = run(tmp_path / "c.robi", e="robi", s="gen", IRS=gen.specials[-1].lab,
                ICP=[1, 4, 2], ISW=2, DS=ds, NMX=200, UZSTOP={2: [-1.0, 0.4]}, sv="loc",
                verbose=False)
        assert [(s.ty, s.code) for s in r.specials] == [("UZ", -64)]
        ends.add(round(r.specials[-1].par[1], 1))
        for row in r.rows:
            assert on_locus(row.par[0], row.par[1]) == pytest.approx(0, abs=1e-9)
            assert abs(row.par[3]) < 1e-9
        # psi = PAR(5..7) (two boundary conditions, one integral), a = PAR(8)
        assert abs(r.specials[-1].par[6]) > 1e-2
    assert ends == {-1.0, 0.4}

# AUTO's sspg demo (size-structured plant growth) in Python: u1' = -u2,
# u2' = -u1 u2 - m u2, u1(1) = 0, u2(0) = s u1(0), m = PAR(1), s = PAR(2). On the
# trivial branch the linearisation u2 = c e^(-m t), u1 = c (e^(-m t) - e^(-m)) / m
# meets the second condition where s (1 - e^(-m)) = m: the BP locus in closed form.
SSPG = '''
import numpy as np
def func(u, par):
    return np.array([-u[1], -u[0] * u[1] - par[0] * u[1]])
def stpnt(u, par, t=0.0):
    par[:2] = [1.0, 4.0]
    u[:] = 0.0
def bcnd(u0, u1, par):
    return np.array([u1[0], -u0[1] + par[1] * u0[0]])
'''
SSPG_C = ("NDIM=2, IPS=4, ICP=[1], NTST=100, NCOL=4, IAD=3, ISP=2, ILP=1, NBC=2, NINT=0, "
          "NMX=50, NPR=10, DS=0.01, DSMAX=0.1, NPAR=2\n")
DATA = Path(__file__).parent / "data"


def _on_sspg_locus(m, s):
    return s * (1 - np.exp(-m)) - m


@pytest.mark.slow
def test_sspg_locus_closed_form_auto_and_restart_from_auto(tmp_path):
    """The sspg demo's runs (its constants) in Python: BP1 of the trivial branch on
    4 (1 - e^-m) = m (located to EPSS), the generating run and the locus forward and
    backward, every point on s (1 - e^-m) = m to 1e-9 (the profiles are exponentials,
    resolved far below that at NTST = 100; Newton converges quadratically). AUTO's own
    b-file rows of the same runs (10 digits) lie on it to 1e-8: AUTO and washer agree.
    Restarted from AUTO-07p's generating-run record (4n components (u, w, v1, v2) and
    its parameter layout, tests/data/bvp_bp, written by auto-07p 0.9.x on the demo),
    the locus is the same."""
    (tmp_path / "sspg.py").write_text(SSPG)
    (tmp_path / "c.sspg").write_text(SSPG_C)
    r1 = run(tmp_path / "c.sspg", e="sspg", sv="sspg", verbose=False)
    bp = r1("BP1")
    assert _on_sspg_locus(bp.par[0], 4.0) == pytest.approx(0, abs=1e-5)
    sw = run(tmp_path / "c.sspg", e="sspg", s="sspg", IRS=bp.lab, ICP=[1, 2], ISW=2,
             sv="sw", verbose=False)
    assert [(s.ty, s.br, s.pt) for s in sw.specials] == [("EP", 2, 5)]
    for ds in (0.01, -0.01):
        r = run(tmp_path / "c.sspg", e="sspg", s="sw", IRS=sw.specials[-1].lab, ICP=[1, 2],
                ISW=2, DS=ds, sv="loc", verbose=False)
        assert [(s.ty, s.br, s.pt) for s in r.specials if s.ty] == [("EP", 2, 50)]
        for row in r.rows:
            assert _on_sspg_locus(row.par[0], row.par[1]) == pytest.approx(0, abs=1e-9)
    for name in ("b.sspg.2.fw", "b.sspg.2.bw"):
        rows = branch_rows(DATA / "auto_demos" / "sspg" / "autoref" / name)
        assert len(rows) == 50
        for row in rows:
            assert _on_sspg_locus(row.values[0], row.values[-1]) == pytest.approx(0, abs=1e-8)
    shutil.copy(DATA / "bvp_bp" / "s.sspg.2.sw.gz", tmp_path / "s.auto.gz")
    r = run(tmp_path / "c.sspg", e="sspg", s="auto", IRS=8, ICP=[1, 2], ISW=2, sv="fromauto",
            verbose=False)
    assert r.status == "ok" and len(r.rows) == 50
    for row in r.rows:
        assert _on_sspg_locus(row.par[0], row.par[1]) == pytest.approx(0, abs=1e-9)


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("auto-07p") is None or shutil.which("gfortran") is None,
                    reason="AUTO-07p (auto-07p and gfortran) is not installed")
def test_auto07p_restarts_from_washers_generating_run(tmp_path):
    """AUTO-07p itself continues sspg's BP locus from washer's generating-run record
    (its s-record header carries NPARI = 5, the internal parameters psi, a, d, b after
    the user's NPAR = 2, in AUTO's layout): AUTO's 50 points lie on s (1 - e^-m) = m to
    1e-8 (its 10-digit output) and end at its EP, PT 50."""
    (tmp_path / "sspg.py").write_text(SSPG)
    (tmp_path / "c.sspg").write_text(SSPG_C)
    r1 = run(tmp_path / "c.sspg", e="sspg", sv="sspg", verbose=False)
    sw = run(tmp_path / "c.sspg", e="sspg", s="sspg", IRS=r1("BP1").lab, ICP=[1, 2], ISW=2,
             sv="ours", verbose=False)
    assert (tmp_path / "s.ours").read_text().split("\n")[0].split()[12] == "5"
    demo = DATA / "auto_demos" / "sspg"
    auto = tmp_path / "auto"
    auto.mkdir()
    for name in ("sspg.f90", "c.sspg"):
        shutil.copy(demo / name, auto / name)
    shutil.copy(tmp_path / "s.ours", auto / "s.ours")
    (auto / "r.auto").write_text(f"run('sspg', s='ours', IRS={sw.specials[-1].lab}, "
                                 "ICP=[1, 2], ISW=2, NMX=50, NPR=10, sv='fw')\n")
    env = dict(os.environ, OMP_NUM_THREADS="1")
    subprocess.run(["auto-07p", "r.auto"], cwd=auto, env=env, capture_output=True,
                   timeout=600, check=True)
    rows = branch_rows(auto / "b.fw")
    assert len(rows) == 50 and (rows[-1].ty, rows[-1].pt) == (69, 50)       # EP on curve 6
    for row in rows:
        assert _on_sspg_locus(row.values[0], row.values[-1]) == pytest.approx(0, abs=1e-8)


def test_branch_point_loci_refuse_what_they_cannot_start(tmp_path):
    """Clear errors naming the constants file: too few ICP for the locus (two for
    ISW = 2 on a BVP with one free parameter, three for ISW = 3), and ISW = 3 away from
    a BP."""
    from washer.cont.start import RunError
    (tmp_path / "rob.py").write_text(ROBIN)
    (tmp_path / "c.rob").write_text("NDIM=2, IPS=4, ICP=[1], NBC=2, NINT=0, NTST=10, NCOL=4, "
                                    "ISP=2, NMX=40, DS=0.05, DSMAX=0.2, NPAR=3, "
                                    "UZSTOP={1: 3.0}\n")
    run(tmp_path / "c.rob", e="rob", sv="rob", verbose=False)
    for kw, message in ((dict(IRS="BP1", ICP=[1], ISW=2), r"ICP needs 2 entries, got \[1\]"),
                        (dict(IRS="BP1", ICP=[1, 2], ISW=3), r"ICP needs 3 entries"),
                        (dict(IRS="UZ1", ICP=[1, 2, 3], ISW=3), "restart at a BP label, got UZ")):
        with pytest.raises(RunError, match=message) as err:
            run(tmp_path / "c.rob", e="rob", s="rob", sv="x", verbose=False, **kw)
        assert "c.rob" in str(err.value)
