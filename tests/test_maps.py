"""Fixed points of maps (IPS = -1): AUTO-07p's demos log and dd2 against AUTO's own
b-files (their constants unchanged, the scripts' overrides only), and maps designed
with closed-form fold, period-doubling and Neimark-Sacker points.

Located points are compared with AUTO's to the location tolerance both engines
promise, EPSS (1 + sqrt(|DS DSMAX|)) on the arclength (the tangent is unit, so a
parameter moves by at most that much); exact values (the logistic map's period
doublings from an independent high-precision solve) judge where AUTO's own value
is loose.
"""
import math
from pathlib import Path

import mpmath
import numpy as np
import pytest

from b_rows import branch_rows
from demo_files import autoref, copy_demo
from tolerances import location_tolerance
from washer.auto.constants_file import read_constants
from washer.auto.files import type_name
from washer.cont.runner import RunError
from washer.run import run

#: the Python transcriptions of the demos' equations (NAME/NAME.py), which the tests run
#: in place of AUTO's NAME.f90
PYTHON = Path(__file__).parent / "data" / "maps"


def demo(tmp_path: Path, name: str) -> Path:
    return copy_demo(name, tmp_path, PYTHON / name)


def labelled(path: Path, br=None) -> list:
    """(type, branch, PAR(ICP(1))) of the labelled rows of a b-file."""
    return [(type_name(r.ty), r.br, r.values[0]) for r in branch_rows(path)
            if r.lab and (br is None or r.br in br)]


def logistic_pd(k: int) -> float:
    """mu of the period doubling of the period-2^k orbit of x -> mu x (1 - x),
    solved directly (f^(2^k)(x) = x, (f^(2^k))'(x) = -1) with 40 digits: a
    second derivation, independent of the engine."""
    mpmath.mp.dps = 40
    n = 2 ** k
    guesses = {0: (3.0, 2 / 3), 1: (3.449, 0.44), 2: (3.544, 0.52), 3: (3.5644, 0.49),
               4: (3.56876, 0.50), 5: (3.56969, 0.4985)}

    def eqs(mu, x):
        y, d = x, mpmath.mpf(1)
        for _ in range(n):
            d *= mu * (1 - 2 * y)
            y = mu * y * (1 - y)
        return [y - x, d + 1]
    mu, x = mpmath.findroot(eqs, guesses[k])
    return float(mu)


# 2.8 s: AUTO's log demo; the fast loop keeps the map closed forms
@pytest.mark.slow
def test_logistic_map_demo(tmp_path):
    """log.auto: the fixed points (BP at mu = 1, PD at mu = 3, UZSTOP 3.6), then five
    switches at PD (ISW = -1, SP = ['BP0']), each doubling PAR(11) and finding the
    next period doubling: types, order and branches as AUTO's b.log, values within
    the location tolerance of AUTO's and of the exact ones (AUTO: 3.4494897431,
    ours within 1e-11 of 1 + sqrt(6))."""
    d = demo(tmp_path, "log")
    c = read_constants(d / "c.log")
    tol = location_tolerance(c)
    r = run(d / "c.log", e="log", sv="log", verbose=False)
    assert r.status == "ok"
    runs, prev = [r], "log"
    for i in range(5):
        pd = r("PD1")
        r = run(d / "c.log", e="log", s=prev, IRS=pd.lab, ISW=-1, SP=["BP0"], sv=f"pd{i}",
                verbose=False)
        assert r.status == "ok"
        assert r("PD1").par[10] == 2 ** (i + 1)          # PAR(11): the iterate followed
        runs.append(r)
        prev = f"pd{i}"
    ours = [(s.ty, s.br, s.par[0]) for x in runs for s in x.specials]
    ref = labelled(autoref("log") / "b.log")
    assert [(t, b) for t, b, _ in ours] == [(t, b) for t, b, _ in ref]
    for (t, b, o), (_, _, a) in zip(ours, ref):
        assert abs(o - a) <= tol, (t, b, o, a)
    pds = [p for t, _, p in ours if t == "PD"]
    for k, p in enumerate(pds):
        assert p == pytest.approx(logistic_pd(k), abs=1e-8)
    bp = runs[0]("BP1")
    assert bp.par[0] == pytest.approx(1.0, abs=1e-8)


def test_dd2_demo(tmp_path):
    """dd2.auto: fixed points with two BPs (MXBF switching), PD at p1 = 3; the period
    doubling and the next one (ISW = -1 twice). Types, order, branches as AUTO's
    b.dd2; located values within the location tolerance of AUTO's (its own PD at
    3.4494928592 is 3e-6 from 1 + sqrt(6), ours 1e-9). End points (EP) depend on
    the step history: type only."""
    d = demo(tmp_path, "dd2")
    c = read_constants(d / "c.dd2")
    tol = location_tolerance(c)
    r1 = run(d / "c.dd2", e="dd2", sv="dd2", verbose=False)
    r3 = run(d / "c.dd2", e="dd2", s="dd2", IRS=r1("PD1").lab, ISW=-1, sv="r3", verbose=False)
    r4 = run(d / "c.dd2", e="dd2", s="r3", IRS=r3("PD1").lab, ISW=-1, sv="r4", verbose=False)
    ours = [(s.ty, s.br, s.par[0]) for x in (r1, r3, r4) for s in x.specials]
    ref = labelled(autoref("dd2") / "b.dd2")
    # The period-doubling locus in (p1, p2): p1 = 3 while u2 = 0, to NMX (EP 79).
    r2 = run(d / "c.dd2", e="dd2", s="dd2", IRS=r1("PD1").lab, ICP=[1, 2], ISW=2, sv="pd",
             verbose=False)
    assert [(s.code, s.br) for s in r2.specials] == \
        [(r.ty, r.br) for r in branch_rows(autoref("dd2") / "b.pd") if r.lab] == [(79, 5)]
    assert all(row.par[0] == pytest.approx(3.0, abs=1e-9) for row in r2.rows)
    assert [(t, b) for t, b, _ in ours] == [(t, b) for t, b, _ in ref]
    for (t, b, o), (_, _, a) in zip(ours, ref):
        if t != "EP":
            assert abs(o - a) <= tol, (t, b, o, a)
    assert r3("PD1").par[0] == pytest.approx(1 + math.sqrt(6), abs=1e-8)
    assert r4("PD1").par[0] == pytest.approx(logistic_pd(2), abs=1e-8)
    # The predator-prey BP: the second multiplier 1 - p3 + p2 u1 = 1 at u1 = 1/2.
    bp = r1("BP2")
    assert bp.par[0] == pytest.approx(2.0, abs=1e-8)
    np.testing.assert_allclose(bp.U, [0.5, 0.0], atol=1e-8)


#: AUTO-07p's fold and period-doubling loci of u -> u + p - q u - u^2 (README.md there)
FQ = Path(__file__).parent / "data" / "maps" / "fq"

FOLD_MAP = '''
import numpy as np
def func(u, par):
    return np.array([u[0] + par[0] - u[0] ** 2])
def stpnt(u, par, t=0.0):
    par[0] = 4.0
    u[0] = 2.0
'''

NS_MAP = '''
import numpy as np
def func(u, par):
    a, b = par[0], par[1]
    x, y = u
    r2 = x * x + y * y
    return np.array([a * x - b * y - x * r2, b * x + a * y - y * r2 + x * x])
def stpnt(u, par, t=0.0):
    par[0] = 0.2
    par[1] = 0.8
    u[:] = 0.0
'''


def test_fold_and_period_doubling_closed_form(tmp_path):
    """u -> u + p - u^2: fixed points u^2 = p with multiplier 1 - 2u, so a period
    doubling at u = 1, p = 1 and a fold at u = p = 0. Coming down from p = 4 the
    branch is unstable above p = 1, stable in (0, 1), and the PD and LP carry the
    stability of the point before them (PT sign), as AUTO writes them."""
    (tmp_path / "fold.py").write_text(FOLD_MAP)
    (tmp_path / "c.fold").write_text("NDIM=1, IPS=-1, ICP=[1], ILP=1, ISP=1, NMX=300, "
                                     "DS=-0.01, DSMAX=0.05, DSMIN=1e-4, NPAR=2, EPSS=1e-6, "
                                     "UZSTOP={1: [-1.0, 5.0]}\n")
    r = run(tmp_path / "c.fold", e="fold", sv="fold", verbose=False)
    c = read_constants(tmp_path / "c.fold")
    tol = location_tolerance(c)
    assert [s.ty for s in r.specials] == ["EP", "PD", "LP", "UZ"]
    pd, lp = r("PD1"), r("LP1")
    assert abs(pd.par[0] - 1.0) <= tol and pd.U[0] == pytest.approx(1.0, abs=tol)
    assert abs(lp.par[0]) <= tol and abs(lp.U[0]) <= math.sqrt(tol)
    assert pd.stable is False and lp.stable is True
    assert r("UZ1").U[0] == pytest.approx(-math.sqrt(5.0), rel=1e-9)


def test_neimark_sacker_closed_form(tmp_path):
    """u -> A(a, b) u + cubic terms, A = [[a, -b], [b, a]]: the fixed point 0 has the
    multipliers a +- i b, so a TR (Neimark-Sacker) point at a^2 + b^2 = 1 with angle
    atan2(b, a) in PAR(12), and its locus in (a, b) is the unit circle."""
    (tmp_path / "ns.py").write_text(NS_MAP)
    (tmp_path / "c.ns").write_text("NDIM=2, IPS=-1, ICP=[1], ILP=1, ISP=1, NMX=200, DS=0.01, "
                                   "DSMAX=0.05, DSMIN=1e-4, NPAR=2, EPSS=1e-6, "
                                   "UZSTOP={1: 1.0}\n")
    r = run(tmp_path / "c.ns", e="ns", sv="ns", verbose=False)
    tol = location_tolerance(read_constants(tmp_path / "c.ns"))
    assert [s.ty for s in r.specials] == ["EP", "TR", "UZ"]
    tr = r("TR1")
    assert abs(tr.par[0] - 0.6) <= tol
    assert tr.par[11] == pytest.approx(math.atan2(0.8, 0.6), abs=1e-6)
    assert tr.stable is True and r("UZ1").stable is False
    for ds in (0.01, -0.01):
        loc = run(tmp_path / "c.ns", e="ns", s="ns", IRS="TR1", ICP=[1, 2], ISW=2, DS=ds,
                  UZR={1: [0.5]}, UZSTOP={2: [0.3, 0.99]}, sv="nsl", verbose=False)
        assert loc.status == "ok"
        assert loc.rows and all(row.code in (0, -84, 89) for row in loc.rows[1:])
        for row in loc.rows:
            a, b = row.par[0], row.par[1]
            assert a * a + b * b == pytest.approx(1.0, abs=1e-9)
            assert row.par[11] == pytest.approx(math.atan2(b, a), abs=1e-9)


def test_map_fold_locus(tmp_path):
    """The fold locus of u -> u + p - q u - u^2 (fixed points u^2 + q u = p): folds at
    u = -q/2, p = -q^2/4, followed in (p, q) from the LP of the q = 0 branch."""
    (tmp_path / "fq.py").write_text(FOLD_MAP.replace("u[0] + par[0] - u[0] ** 2",
                                                     "u[0] + par[0] - par[1] * u[0] - u[0] ** 2"))
    (tmp_path / "c.fq").write_text("NDIM=1, IPS=-1, ICP=[1], ILP=1, ISP=1, NMX=300, DS=-0.01, "
                                   "DSMAX=0.05, DSMIN=1e-4, NPAR=2, EPSS=1e-6, "
                                   "UZSTOP={1: [-1.0, 5.0]}\n")
    run(tmp_path / "c.fq", e="fq", sv="fq", verbose=False)
    loc = run(tmp_path / "c.fq", e="fq", s="fq", IRS="LP1", ICP=[1, 2], ISW=2, DS=0.01,
              UZSTOP={2: [-1.0, 1.0]}, sv="fql", verbose=False)
    assert loc.status == "ok" and loc.rows[-1].ty == "UZ"
    for row in loc.rows:
        p, q = row.par[0], row.par[1]
        assert p == pytest.approx(-q * q / 4, abs=1e-8)
        assert row.U[0] == pytest.approx(-q / 2, abs=1e-6)


HENON = '''
import numpy as np
def func(u, par):
    return np.array([u[1], par[0] - par[1] * u[0] - u[1] ** 2])
def stpnt(u, par, t=0.0):
    par[0], par[1] = 2.0, 0.0
    u[:] = 1.0
'''


def test_henon_codim2_points_closed_form(tmp_path):
    """The Henon map (x, y) -> (y, a - b x - y^2), fixed points x = y, y^2 + (1 + b) y = a,
    multipliers mu^2 + 2 y mu + b = 0 (product b). Along a = 2 the PD (mu = -1) is at
    2 y = 1 + b with 3 y^2 = a, b = 2 sqrt(2/3) - 1, and the TR at b = 1 (|mu|^2 = b).
    The Neimark-Sacker locus is b = 1 with cos(theta) = -y, y = -1 + sqrt(1 + a): the
    resonances R1 (theta = 0), R4 (pi/2), R3 (2 pi/3), R2 (pi) at a = -1, 0, 5/4, 3.
    The flip locus (2 y = 1 + b, a = 3 y^2) has R2 at (3, 1) and the fold-flip LPD
    where the other multiplier -b is +1: (0, -1); the fold locus (2 y = -(1 + b),
    a = -y^2) has R1 at (-1, 1) and LPD where the other multiplier b is -1: (0, -1)."""
    (tmp_path / "hen.py").write_text(HENON)
    (tmp_path / "c.hen").write_text(
        "NDIM=2, IPS=-1, ICP=[2], ILP=1, ISP=1, NMX=200, DS=0.02, DSMIN=5e-4, DSMAX=0.1, "
        "NPAR=3, EPSL=1e-6, EPSU=1e-6, EPSS=1e-4, STOP=['TR1'], "
        "UZSTOP={1: [-2.0, 4.0], 2: [-3.0, 3.0]}\n")
    tol = location_tolerance(read_constants(tmp_path / "c.hen"))
    r = run(tmp_path / "c.hen", e="hen", sv="beta", verbose=False)
    assert [s.ty for s in r.specials] == ["EP", "PD", "TR"]
    assert abs(r("PD1").par[1] - (2 * math.sqrt(2 / 3) - 1)) <= tol
    assert abs(r("TR1").par[1] - 1.0) <= tol

    def locus(irs, ds, sv, **kw):
        return run(tmp_path / "c.hen", e="hen", s="beta", IRS=irs, ICP=[1, 2], ISW=2, ILP=0,
                   DS=ds, sv=sv, verbose=False, **kw)

    found = {}
    for ds in (0.02, -0.02):
        loc = locus("TR1", ds, "ns", STOP=["R11", "R21"])
        assert loc.status == "ok"
        for s in loc.specials:
            found.setdefault(s.ty, []).append(s.par[0])
        for row in loc.rows:        # on the locus to Newton's tolerance EPSL
            assert row.par[1] == pytest.approx(1.0, abs=1e-6)
    for ty, a in (("R1", -1.0), ("R4", 0.0), ("R3", 1.25), ("R2", 3.0)):
        assert len(found[ty]) == 1 and abs(found[ty][0] - a) <= tol, (ty, found)
    # the run towards R1 stops there (STOP 'R11' is the first R1, not an 'R' count of 11)
    assert found["R1"] and "EP" not in [s.ty for s in loc.specials]

    for irs, expect in (("PD1", {"R2": (3.0, 1.0), "LPD": (0.0, -1.0)}),):
        seen = {}
        for ds in (0.02, -0.02):
            for s in locus(irs, ds, "pd").specials:
                seen[s.ty] = (s.par[0], s.par[1])
        for ty, (a, b) in expect.items():
            assert seen[ty][0] == pytest.approx(a, abs=tol) and \
                seen[ty][1] == pytest.approx(b, abs=tol), (ty, seen)

    r4 = run(tmp_path / "c.hen", e="hen", ICP=[1], DS=-0.02, STOP=["LP1"], sv="alpha",
             verbose=False)
    seen = {}
    for ds in (0.02, -0.02):
        for s in run(tmp_path / "c.hen", e="hen", s="alpha", IRS="LP1", ICP=[1, 2], ISW=2,
                     ILP=0, DS=ds, sv="lp", verbose=False).specials:
            seen[s.ty] = (s.par[0], s.par[1])
    assert r4("LP1").par[0] == pytest.approx(-0.25, abs=tol)
    for ty, (a, b) in {"R1": (-1.0, 1.0), "LPD": (0.0, -1.0)}.items():
        assert seen[ty][0] == pytest.approx(a, abs=tol) and \
            seen[ty][1] == pytest.approx(b, abs=tol), (ty, seen)


@pytest.mark.parametrize("ips", [3, 6, 8, 10, 13, 18])
def test_unknown_problem_types_are_refused(tmp_path, ips):
    """Every problem type of AUTO-07p runs; any other IPS is refused naming the line
    and what AUTO has (AUTO itself stops with 'Initialization Error')."""
    (tmp_path / "fold.py").write_text(FOLD_MAP)
    (tmp_path / "c.x").write_text(f"NDIM=1, IPS={ips}, ICP=[1]\n")
    with pytest.raises(RunError, match=rf"c.x:1: IPS = {ips} is not a problem type of "
                                       r"AUTO-07p: expected one of -2, -1, 0, 1, 2, 4, 5, 7, "):
        run(tmp_path / "c.x", e="fold", verbose=False)


def test_map_loci_restart_from_their_points(tmp_path):
    """A point of a locus of a map (a UZ of the fold, period-doubling or Neimark-Sacker
    curve) restarts that curve with ISW = 2, from the record's extended unknowns and
    direction, as AUTO's STPNLPF / STPNHBF read them; with ISW = 1 it restarts the fixed
    points in PAR(ICP(1)) (FINDLB: ITPST = 0). u -> u + p - q u - u^2: folds on
    p = -q^2/4 (u = -q/2), period doublings (multiplier 1 - q - 2u = -1) on
    p = 1 - q^2/4 (u = 1 - q/2); the Neimark-Sacker map's locus is the unit circle with
    theta = atan2(b, a). Each restarted locus on its closed form to the tolerances of the
    loci from the special points themselves (test_map_fold_locus,
    test_neimark_sacker_closed_form)."""
    (tmp_path / "fq.py").write_text(FOLD_MAP.replace("u[0] + par[0] - u[0] ** 2",
                                                     "u[0] + par[0] - par[1] * u[0] - u[0] ** 2"))
    (tmp_path / "c.fq").write_text("NDIM=1, IPS=-1, ICP=[1], ILP=1, ISP=1, NMX=300, DS=-0.01, "
                                   "DSMAX=0.05, DSMIN=1e-4, NPAR=2, EPSS=1e-6, "
                                   "UZSTOP={1: [-1.0, 5.0]}\n")
    c = tmp_path / "c.fq"
    run(c, e="fq", sv="fq", verbose=False)
    closed = {"LP": lambda q: -q * q / 4, "PD": lambda q: 1 - q * q / 4}
    ends = {}
    for ty, curve in (("LP", "fql"), ("PD", "pdl")):
        loc = run(c, e="fq", s="fq", IRS=f"{ty}1", ICP=[1, 2], ISW=2, DS=0.01,
                  UZSTOP={2: [-1.0, 1.0]}, sv=curve, verbose=False)
        end = loc.specials[-1]
        assert end.ty == "UZ" and abs(end.par[1]) == pytest.approx(1.0)
        if ty == "LP":
            # PAR(1)-dot is 0 at the start: STPRAE's rule makes PAR(2)-dot positive, as
            # AUTO-07p's b-file of this run (tests/data/maps/fq/README.md: the PD
            # locus's way is AUTO's difference noise)
            auto_end = [r for r in branch_rows(FQ / "b.fql.auto") if r.ty != 0][-1]
            assert end.par[1] == pytest.approx(auto_end.values[-1]) == 1.0
        ends[ty] = end.par[1]
        again = run(c, e="fq", s=curve, IRS=end.lab, ICP=[1, 2], ISW=2, DS=0.01,
                    UZSTOP={2: [-1.0, 1.0]}, sv="again", verbose=False)
        assert again.status == "ok" and again.specials[-1].ty == "UZ"
        assert again.specials[-1].par[1] == pytest.approx(-end.par[1])
        assert len(again.rows) > 20
        for row in again.rows:
            assert row.par[0] == pytest.approx(closed[ty](row.par[1]), abs=1e-8)
    # ISW = 1 at the fold locus's end (q = 1, located): the fixed points u^2 + q u = p
    # at that q, which stays fixed
    fixed = run(c, e="fq", s="fql", IRS="UZ1", ICP=[1], ISW=1, DS=0.01, NMX=20, UZSTOP={},
                sv="fixed", verbose=False)
    assert fixed.status == "ok" and len(fixed.rows) == 20
    q = fixed.rows[0].par[1]
    assert q == pytest.approx(ends["LP"], abs=1e-8)
    for row in fixed.rows:
        assert row.par[1] == q
        assert row.U[0] ** 2 + q * row.U[0] == pytest.approx(row.par[0], abs=1e-9)
    (tmp_path / "ns.py").write_text(NS_MAP)
    (tmp_path / "c.ns").write_text("NDIM=2, IPS=-1, ICP=[1], ILP=1, ISP=1, NMX=200, DS=0.01, "
                                   "DSMAX=0.05, DSMIN=1e-4, NPAR=2, EPSS=1e-6, "
                                   "UZSTOP={1: 1.0}\n")
    run(tmp_path / "c.ns", e="ns", sv="ns", verbose=False)
    loc = run(tmp_path / "c.ns", e="ns", s="ns", IRS="TR1", ICP=[1, 2], ISW=2, DS=0.01,
              UZSTOP={2: 0.3}, sv="nsl", verbose=False)
    end = loc.specials[-1]
    assert end.ty == "UZ" and end.par[1] == pytest.approx(0.3)
    again = run(tmp_path / "c.ns", e="ns", s="nsl", IRS=end.lab, ICP=[1, 2], ISW=2,
                DS=-0.01, UZSTOP={2: 0.99}, sv="again", verbose=False)
    assert again.status == "ok" and again.specials[-1].ty == "UZ"
    assert len(again.rows) > 20
    for row in again.rows:
        a, b = row.par[0], row.par[1]
        assert a * a + b * b == pytest.approx(1.0, abs=1e-9)
        assert row.par[11] == pytest.approx(math.atan2(b, a), abs=1e-9)
