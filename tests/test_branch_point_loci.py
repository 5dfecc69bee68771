"""The loci of branch points (AUTO's ISW = 2 and ISW = 3 restarts at a BP label):
driven through `washer.run` on problems whose loci are known in closed form."""
from __future__ import annotations

import numpy as np
import pytest

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
