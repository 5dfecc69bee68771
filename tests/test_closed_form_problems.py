"""AUTO-07p's semantics on problems whose bifurcation structure is known exactly.

Each problem lives in tests/data/<name>/ (equations <name>.py, constants c.<name>
written as an AUTO user would, then kept fixed); tests/closed_form_exact.py
computes the exact special points with sympy at test time. The expected types,
their order along each branch and the branch numbers follow AUTO-07p's rules
(docs/auto.md sections 1 and 3, ae.f90: CNRLAE, SWPNT, LCSPAE, STPLAE).

Tolerances. A special point is located when the locator's arclength correction
drops below EPSS (1 + sqrt|DS DSMAX|) (docs/auto.md 3.2), so the located point lies
within about that arclength of the true zero. Every coordinate of a unit tangent
(THL = THU = 1) has |d coord / ds| <= 1, so the coordinate's error is at most that
arclength, plus the Newton tolerance EPSL (1 + |value|) of the point itself:
`located_tol` below. Points on a branch are Newton-converged to EPSL/EPSU
relative increments; their residuals are checked at 10 x EPSU.
"""
import math
import shutil
import signal
import subprocess
import sys
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

import closed_form_exact as exact
from b_rows import branch_rows, labelled, segments
from tolerances import location_tolerance
from washer.auto.constants_file import read_constants
from washer.auto.files import type_name
from washer.run import run

DATA = Path(__file__).parent / "data"


def scratch(tmp_path_factory, name: str) -> Path:
    """A scratch copy of tests/data/<name> (runs write their b./s./d. files there)."""
    d = tmp_path_factory.mktemp(name)
    for f in (DATA / name).iterdir():
        shutil.copy(f, d)
    return d


def located_tol(cfile: Path, value: float, **overrides) -> float:
    """Error bound of a located coordinate (module docstring)."""
    c = read_constants(cfile)
    return (location_tolerance(c, **overrides)
            + overrides.get("EPSL", c["EPSL"]) * (1 + abs(value)))


def b_rows(folder: Path, sv: str) -> list:
    """Every row of the b-file a run wrote (AUTO's format: signed PT, integer TY code,
    values = PAR(ICP(1)), norm, U(1..), PAR(ICP(2..)) at 10 significant digits, which
    is far inside every tolerance used here)."""
    return branch_rows(folder / f"b.{sv}")


def summary(rows) -> list:
    """[(BR, [type names of the labelled rows in order])] per branch computation."""
    return [(seg[0].br, [type_name(r.ty) for r in labelled(seg)]) for seg in segments(rows)]


def special_of(out, row):
    """The run's labelled point (brief's API: .ty .br .lab .pt .par .U) of a b-file row."""
    return next(s for s in out.res.specials if s.lab == row.lab)


@dataclass
class Done:
    """A finished run: its result object and the rows of the b-file it wrote."""
    res: object
    rows: list

    @property
    def specials(self):
        return self.res.specials

    @property
    def status(self):
        return self.res.status

    def __call__(self, key):
        return self.res(key)


def do_run(cfile: Path, sv: str, **overrides) -> Done:
    res = run(cfile, verbose=False, sv=sv, **overrides)
    return Done(res, b_rows(cfile.parent, sv))


@contextmanager
def time_limit(seconds: int, what: str):
    """Fail instead of hanging (AUTO never loops forever on bad step settings)."""
    def boom(signum, frame):
        raise TimeoutError(f"{what} did not finish within {seconds} s")
    old = signal.signal(signal.SIGALRM, boom)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


# ---------------------------------------------------------------------------
# 1. A chain of pitchforks: recursive branch switching with MXBF

@pytest.fixture(scope="module")
def pfchain(tmp_path_factory):
    d = scratch(tmp_path_factory, "pfchain")
    with time_limit(120, "pfchain"):
        both = do_run(d / "c.pfchain", "both")
        one = do_run(d / "c.pfchain", "one", MXBF=-2)
        # ISW = -1 restart at the second BP of "one" (label 5, on branch 2: x1^2 = a)
        isw = do_run(d / "c.pfchain", "isw", s="one", IRS="BP2", ISW=-1)
    return dict(dir=d, both=both, one=one, isw=isw)


def test_pfchain_switches_recursively_both_directions(pfchain):
    """MXBF = 10 > 0: AUTO stores every BP it finds on any branch (up to |MXBF| at a
    time), and after each branch ends it restarts from the oldest stored BP, first with
    +DS, then -DS (both halves get the same branch number), then the next BP with the
    branch number increased (ae.f90: CNRLAE/SWPNT). The chain has 1 BP on the trivial
    branch, one on each side of level 1 (x1^2 = a), one on each direction of each level-2
    branch (x2^2 = c), and none on level 3: 1 + 2 + 4 + 8 branch computations, fewer
    than the 2 |MXBF| = 20 allowed. The two sides of every pitchfork are mirror images,
    so which side comes first does not change the types."""
    assert pfchain["both"].status == "ok"
    level1 = ["LP", "BP", "EP"]        # subcritical: fold at mu = -1/4, then BP at x1^2 = a
    level2 = ["HB", "BP", "EP"]        # Hopf at x2^2 = b, then BP at x2^2 = c
    expected = ([(1, ["EP", "BP", "EP"])] + [(2, level1)] * 2 + [(3, level2)] * 2
                + [(4, level2)] * 2 + [(br, ["EP"]) for br in (5, 5, 6, 6, 7, 7, 8, 8)])
    assert summary(pfchain["both"].rows) == expected


def test_pfchain_negative_mxbf_counts_switches(pfchain):
    """MXBF = -2: one direction per BP, the branch number grows with every switch, and
    AUTO stops after |MXBF| = 2 switches in the whole run although a third BP (level 2)
    is found and labelled."""
    assert pfchain["one"].status == "ok"
    assert summary(pfchain["one"].rows) == [(1, ["EP", "BP", "EP"]), (2, ["LP", "BP", "EP"]),
                                       (3, ["HB", "BP", "EP"])]


def test_pfchain_isw_minus1_restart_at_bp(pfchain):
    """A restart at a BP label with ISW = -1 switches branches (CNRLAE: STPRAE with the
    direction perpendicular to the stored one, then the switching step): one direction,
    branch number = the largest in the restart file + 1 = 4 (docs/auto.md 1.4), carrying the
    level-2 points; MXBF = 10 then switches at its BP (both directions, branch 5)."""
    assert pfchain["isw"].status == "ok"
    assert summary(pfchain["isw"].rows) == [(4, ["HB", "BP", "EP"]), (5, ["EP"]), (5, ["EP"])]
    ex = exact.pfchain_points()
    cfile = pfchain["dir"] / "c.pfchain"
    first = pfchain["isw"].rows[0]
    assert first.lab == 0 and first.ty == 0                        # restart row: TY 0, no label
    assert first.values[0] == pytest.approx(ex["B"]["mu"], abs=located_tol(cfile, ex["B"]["mu"]))
    hb, bp = labelled(segments(pfchain["isw"].rows)[0])[:2]
    for r, key in ((hb, "HB"), (bp, "C")):
        assert r.values[0] == pytest.approx(ex[key]["mu"], abs=located_tol(cfile, ex[key]["mu"]))
        assert abs(r.values[3]) == pytest.approx(ex[key]["x"][1], abs=located_tol(cfile, 1.0))


# Which exact point a labelled type is, by level: branch 1 (trivial), 2 (x1 != 0),
# 3 and up (x2 != 0; the level-3 branches carry no located points).
PFCHAIN_LEVELS = {1: {"BP": "A"}, 2: {"LP": "LP", "BP": "B"}, 3: {"HB": "HB", "BP": "C"}}


@pytest.mark.parametrize("name", ["both", "one"])
def test_pfchain_values(pfchain, name):
    """Located points against the exact values (located_tol, per coordinate); the HB's
    PAR(11) = 2 pi / omega to the Newton tolerance (it is computed at the located
    point from the eigenvalues, whose imaginary part is omega exactly on the branch)."""
    res, cfile = pfchain[name], pfchain["dir"] / "c.pfchain"
    ex = exact.pfchain_points()
    checked = 0
    for seg in segments(res.rows):
        br = seg[0].br
        for r in labelled(seg):
            t = type_name(r.ty)
            key = PFCHAIN_LEVELS.get(min(br, 3), {}).get(t)
            if key is None:
                continue
            e = ex[key]
            mu, x = r.values[0], np.abs(r.values[2:7])
            assert mu == pytest.approx(e["mu"], abs=located_tol(cfile, e["mu"])), (br, t)
            for xi, ei in zip(x, e["x"]):
                assert xi == pytest.approx(ei, abs=located_tol(cfile, ei)), (br, t, x)
            if t == "HB":
                assert special_of(res, r).par[10] == pytest.approx(e["period"], rel=1e-6)
            checked += 1
    assert checked == (13 if name == "both" else 5)


def test_pfchain_end_points(pfchain):
    """Branches end at the first point beyond RL1 = 1.5 (AUTO writes it as EP, no
    interpolation), so within one step (DSMAX = 0.1) of the window; the first row of the
    run is the start point mu = -0.9 labelled EP (IRS = 0)."""
    rows = pfchain["both"].rows
    assert type_name(rows[0].ty) == "EP" and rows[0].values[0] == pytest.approx(-0.9, abs=1e-12)
    for seg in segments(rows):
        last = seg[-1]
        assert type_name(last.ty) == "EP"
        assert 1.5 < last.values[0] <= 1.5 + 0.1 * (1 + 1e-6)


def test_pfchain_switched_branches_start_at_their_bp(pfchain):
    """The first row of a switched branch is the BP itself (unlabelled: AUTO restarts
    with IRS = 1, ITP = 0), at the exact BP of its level."""
    ex = exact.pfchain_points()
    start_of = {2: "A", 3: "B", 4: "B", 5: "C", 6: "C", 7: "C", 8: "C"}
    cfile = pfchain["dir"] / "c.pfchain"
    for seg in segments(pfchain["both"].rows)[1:]:
        first, e = seg[0], ex[start_of[seg[0].br]]
        assert first.lab == 0 and first.ty == 0
        assert first.values[0] == pytest.approx(e["mu"], abs=located_tol(cfile, e["mu"]))


# ---------------------------------------------------------------------------
# 2. Two Hopf loci crossing (BP on the Hopf curve) with a GH on the far locus;
# 7. the Hopf curve with JAC = 0 follows the exact locus

HB_CURVE = dict(IRS="HB1", ICP=["p1", "p2"], ISW=2, s="eq", UZSTOP={"p2": [-2.5, 1.5]})


@pytest.fixture(scope="module")
def hopfcross(tmp_path_factory):
    d = scratch(tmp_path_factory, "hopfcross")
    with time_limit(120, "hopfcross"):
        out = dict(dir=d, eq=do_run(d / "c.hopfcross", "eq"))
        out["fwd"] = do_run(d / "c.hopfcross", "fwd", DS=0.02, **HB_CURVE)
        out["bwd"] = do_run(d / "c.hopfcross", "bwd", DS=-0.02, **HB_CURVE)
        out["npr"] = do_run(d / "c.hopfcross", "npr", DS=-0.02, NPR=20, **HB_CURVE)
    return out


def test_hopfcross_equilibria(hopfcross):
    """x0 = 0 at p2 = -0.5: one HB at p1 = p2 + p2^2/2 = -0.375, then the UZ stop."""
    res, cfile = hopfcross["eq"], hopfcross["dir"] / "c.hopfcross"
    assert [s.ty for s in res.specials] == ["EP", "HB", "UZ"]
    _, p1 = exact.hopfcross_on_locus(-0.5, 0)
    assert res("HB1").par[0] == pytest.approx(p1, abs=located_tol(cfile, p1))
    assert res("HB1").par[10] == pytest.approx(2 * math.pi, rel=1e-6)   # omega = 1


def test_hopfcross_codes_order_and_branches(hopfcross):
    """Forward along E1's locus: the crossing with E2's locus is a BP of the Hopf-curve
    system (code 31 = BP + 10 x 3 on an HB curve), then the UZ stop (-34). Branch 2 = the
    label of HB1 (ISW = 2 restart, docs/auto.md 1.4). MXBF = 10 then switches at the BP onto
    E2's locus, branch 3, first with +DS: the null-vector direction is oriented to
    PAR(ICP(1))-dot > 0, which on E2's locus is p2 > 0, where the GH (-32) lies; then
    -DS, towards p2 < 0, where E2's locus folds in p1 (LP, 32). Backward from HB1 along
    E1's locus: its fold in p1 (32), then the UZ stop; no BP, so no switch."""
    def codes(res):
        return [(seg[0].br, [r.ty for r in labelled(seg)]) for seg in segments(res.rows)]
    assert hopfcross["fwd"].status == "ok" and hopfcross["bwd"].status == "ok"
    assert codes(hopfcross["fwd"]) == [(2, [31, -34]), (3, [-32, -34]), (3, [32, -34])]
    assert codes(hopfcross["bwd"]) == [(2, [32, -34])]
    # Regular points of a codim-1 curve are written with TY 0 (STPLAE sets ITP = 0 for
    # them; only labelled types carry the curve's ten's digit).
    for name in ("fwd", "bwd"):
        assert all(r.ty == 0 for r in hopfcross[name].rows if not r.lab)


def test_hopf_curve_npr_points_carry_the_curve_code(hopfcross):
    """NPR = 20 on the Hopf curve: every 20th point (PT = NTOT, so independent of the step
    sizes) is labelled with code 4 + 10 x 3 = 34 (STPLAE: ITP = 4 + 10 ITPST), the other
    special points are unchanged."""
    rows = hopfcross["npr"].rows
    for r in rows:
        if abs(r.pt) % 20 == 0 and r.ty in (0, 34):       # not displaced by another type
            assert r.ty == 34 and r.lab, r
        if r.ty == 34:
            assert abs(r.pt) % 20 == 0, r
    assert sum(r.ty == 34 for r in rows) >= 4
    assert [r.ty for r in rows if r.lab and r.ty != 34] == [32, -34]


def test_hopfcross_values(hopfcross):
    """The crossing, both folds and the GH against sympy (located_tol on p1 and p2). The
    GH test function is AUTO's first Lyapunov coefficient l1 = (x0 - 1/2) / omega here;
    an engine's finite-difference l1 error of order 1e-6 moves its zero by ~1e-6 along
    the arclength (|dl1/ds| ~ 0.4), inside the bound. UZ stops are at the UZSTOP value of
    p2 with p1 from the locus formula (Newton tolerance plus located_tol)."""
    ex = exact.hopfcross_points()
    cfile = hopfcross["dir"] / "c.hopfcross"
    def stop(p2, locus):
        x0, p1 = exact.hopfcross_on_locus(p2, locus)
        return dict(x0=x0, p1=p1, p2=p2)
    want = {("fwd", 0): [ex["BP"], stop(1.5, 0)], ("fwd", 1): [ex["GH"], stop(1.5, 1)],
            ("fwd", 2): [ex["LP_E2"], stop(-2.5, 1)], ("bwd", 0): [ex["LP_E1"], stop(-2.5, 0)]}
    for (name, k), points in want.items():
        seg = segments(hopfcross[name].rows)[k]
        assert len(labelled(seg)) == len(points), (name, k)
        for r, e in zip(labelled(seg), points):
            p1, x0, p2 = r.values[0], r.values[2], r.values[5]
            for got, key in ((p1, "p1"), (p2, "p2"), (x0, "x0")):
                assert got == pytest.approx(e[key], abs=located_tol(cfile, e[key], DS=0.02)), \
                    (name, k, type_name(r.ty), key)


def test_hopf_curve_jac0_follows_exact_locus(hopfcross):
    """JAC = 0 (finite differences, the constants file's default) on the Hopf-curve
    system: the run must start, and every point must lie on the exact locus: x0 = 0
    (branch 2, E1) or x0 = p2 (branch 3, E2), y = 0, and the pair's real part
    h = p1 - p2 - x0 - p2^2/2 = 0. Tolerance 1e-6 (1 + |p1| + |p2|): Newton stops at
    relative increments EPSL = EPSU = 1e-7 (so each coordinate is within ~1e-7 (1 + |.|)
    and h, with unit coefficients, within a few 1e-7), and a finite-difference Jacobian
    (forward: error ~sqrt(machine eps) ~ 1e-8 relative) moves the computed Hopf condition
    by less than that. Also PAR(11) = 2 pi / sqrt(kappa) = 2 pi (omega = 1)."""
    n = 0
    for name in ("fwd", "bwd"):
        res = hopfcross[name]
        for r in res.rows:
            p1, x0, y1, y2, p2 = r.values[0], *r.values[2:5], r.values[5]
            scale = 1 + abs(p1) + abs(p2)
            assert abs(p1 - p2 - x0 - p2 * p2 / 2) <= 1e-6 * scale, (name, r)
            target = 0.0 if r.br == 2 else p2
            assert abs(x0 - target) <= 1e-6 * scale, (name, r)
            assert abs(y1) + abs(y2) <= 1e-6 * scale
            n += 1
        for s in res.specials:
            assert s.par[10] == pytest.approx(2 * math.pi, rel=1e-6)
    assert n > 40        # the curves were actually followed, not just started


# ---------------------------------------------------------------------------
# 3. A very sharp fold: turn it and stay on the branch

@pytest.fixture(scope="module")
def sharpfold(tmp_path_factory):
    d = scratch(tmp_path_factory, "sharpfold")
    with time_limit(60, "sharpfold"):
        return dict(dir=d, res=do_run(d / "c.sharpfold", "sharpfold"))


def test_sharpfold_turns_both_folds(sharpfold):
    """mu = G(x) is an S with fold radii ~eps/s = 0.005, twenty times below DSMAX, and
    arms whose tangents have a dot product of -15/17: both folds must be found, in order,
    and the run must end at the UZ stop on the third arm."""
    res, cfile = sharpfold["res"], sharpfold["dir"] / "c.sharpfold"
    assert res.status == "ok"
    assert [s.ty for s in res.specials] == ["EP", "LP", "LP", "UZ"]
    assert {s.br for s in res.specials} == {1}
    ex = exact.sharpfold_points()
    for s, key in zip(res.specials[1:], ("LP1", "LP2", "UZ")):
        e = ex[key]
        # mu at a fold is stationary along the branch, so its error is second order in
        # the arclength error; x moves at |dx/ds| <= 1: located_tol for both.
        assert s.par[0] == pytest.approx(e["mu"], abs=located_tol(cfile, e["mu"])), key
        assert s.U[0] == pytest.approx(e["x"], abs=located_tol(cfile, e["x"])), key


def test_sharpfold_stays_on_the_branch(sharpfold):
    """The branch is the graph mu = G(x), traversed once with x increasing from -1 to
    ~2: a run that jumps or turns back shows x decreasing somewhere. Each row solves
    mu = G(x) to 10 EPSU (1 + |mu|) (Newton tolerance)."""
    rows = sharpfold["res"].rows
    x = np.array([r.values[2] for r in rows])
    assert np.all(np.diff(x) > 0), np.flatnonzero(np.diff(x) <= 0)
    assert x[0] == pytest.approx(-1.0) and x[-1] > 1.9
    for r in rows[:: max(1, len(rows) // 25)] + [rows[-1]]:
        mu = r.values[0]
        assert abs(mu - exact.sharpfold_G_numeric(r.values[2])) <= 1e-6 * (1 + abs(mu))


# ---------------------------------------------------------------------------
# 4. A location that fails on purpose: keep the point, no label, go on

@pytest.fixture(scope="module")
def locfail(tmp_path_factory):
    d = scratch(tmp_path_factory, "locfail")
    with time_limit(60, "locfail"):
        return dict(dir=d, res=do_run(d / "c.locfail", "locfail"))


def test_failed_location_is_not_labelled_and_run_goes_on(locfail):
    """The BP test function (the Newton matrix's determinant) jumps from +1 to -1 at
    mu = 1/2 with no zero in between. AUTO's locator (secant, then Mueller with
    bracketing, ITMX = 8) cannot bring the step below EPSS there: it writes
    "NOTE:Possible special point" in the d-file, restores the point, gives no label and
    continues (ae.f90: LCSPAE), here to the UZ stop at mu = 1."""
    res, cfile = locfail["res"], locfail["dir"] / "c.locfail"
    assert res.status == "ok"
    assert [s.ty for s in res.specials] == ["EP", "UZ"]
    assert res("UZ1").par[0] == pytest.approx(1.0, abs=located_tol(cfile, 1.0))
    mus = [r.values[0] for r in res.rows]
    assert min(mus) == pytest.approx(0.0, abs=1e-12) and max(mus) == pytest.approx(1.0, abs=1e-4)
    assert all(abs(r.values[3]) < 1e-9 for r in res.rows)            # x2 = 0 throughout
    d_text = (locfail["dir"] / "d.locfail").read_text()
    assert "NOTE:Possible special point" in d_text


def test_failed_uz_location_on_a_jumping_pvls_value(tmp_path_factory):
    """The same with a user zero: UZR on PAR(2), which the user's pvls sets to 0 or 1 by
    a jump at x = mu = 1/2. No UZ label there, a note in the d-file, and the run goes on
    to the UZSTOP at mu = 1; PAR(2) is 1 at that end point (pvls ran there)."""
    d = scratch(tmp_path_factory, "pvlsjump")
    with time_limit(60, "pvlsjump"):
        out = do_run(d / "c.pvlsjump", "pvlsjump")
    assert out.status == "ok"
    assert [s.ty for s in out.specials] == ["EP", "UZ"]
    uz = out("UZ1")
    assert uz.par[0] == pytest.approx(1.0, abs=located_tol(d / "c.pvlsjump", 1.0))
    assert uz.par[1] == 1.0
    assert "NOTE:Possible special point" in (d / "d.pvlsjump").read_text()


# ---------------------------------------------------------------------------
# 5. PVLS: PAR(9) = U(1) set by the user's pvls, and UZSTOP on it by name

@pytest.fixture(scope="module")
def pvlsstop(tmp_path_factory):
    d = scratch(tmp_path_factory, "pvlsstop")
    with time_limit(60, "pvlsstop"):
        return dict(dir=d, res=do_run(d / "c.pvlsstop", "pvlsstop"))


def test_pvls_value_stops_the_run(pvlsstop):
    """UZSTOP = {'xval': 0.5} with parnames {9: 'xval'} and pvls setting PAR(9) = U(1)
    (as AUTO's pp2 demo): the run stops at U(1) = 1/2, i.e. mu = 5/8 exactly, before the
    other stop (mu = 3). located_tol bounds both coordinates; PAR(9) written with the
    point is its own U(1) (pvls ran at that point)."""
    res, cfile = pvlsstop["res"], pvlsstop["dir"] / "c.pvlsstop"
    assert [s.ty for s in res.specials] == ["EP", "UZ"]
    uz = res("UZ1")
    assert uz.U[0] == pytest.approx(0.5, abs=located_tol(cfile, 0.5))
    assert uz.par[0] == pytest.approx(exact.pvlsstop_mu(0.5), abs=located_tol(cfile, 0.625))
    assert uz.par[8] == pytest.approx(uz.U[0], abs=1e-12)
    assert res.rows[-1].lab == uz.lab                                # the run ended there
    assert max(r.values[0] for r in res.rows) < 0.625 + 0.06        # nothing beyond


# ---------------------------------------------------------------------------
# 6. Bad step settings: AUTO's replacements, a clear error, never a hang

@pytest.fixture
def wall(tmp_path):
    for f in (DATA / "wall").iterdir():
        shutil.copy(f, tmp_path)
    return tmp_path


def test_ds_zero_is_replaced_by_0_1(wall):
    """DS = 0 becomes 0.1 (main.f90: INIT1). On the straight branch x = mu (45 degrees)
    the b-file's PT 2 lies two steps of DS from PT 1 (the unwritten first step plus the
    first written one, docs/auto.md 3.1), i.e. at mu = 2 x 0.1 / sqrt 2, times (1 + 1e-7)
    (DS is perturbed by 1e-7); Newton is exact on a linear branch: 1e-6 relative."""
    with time_limit(60, "DS=0"):
        res = do_run(wall / "c.wall", "ds0", DS=0, RL1=0.9)
    assert res.status == "ok"
    first_two = res.rows[1].values[0] - res.rows[0].values[0]
    assert first_two == pytest.approx(0.2 / math.sqrt(2), rel=1e-6)
    assert type_name(res.rows[-1].ty) == "EP" and res.rows[-1].values[0] > 0.9


def test_dsmin_above_dsmax_is_a_clear_error(wall):
    """DSMIN > DSMAX cannot be satisfied: a clear error naming both, from Python and from
    the command line (exit status 2, message on stderr), and promptly."""
    with time_limit(60, "DSMIN>DSMAX"):
        with pytest.raises(Exception) as info:
            run(wall / "c.wall", verbose=False, sv="bad", DSMIN=0.6)
    assert not isinstance(info.value, TimeoutError)
    assert "DSMIN" in str(info.value) and "DSMAX" in str(info.value)
    p = subprocess.run([sys.executable, "-m", "washer.run", str(wall / "c.wall"), "DSMIN=0.6"],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 2
    assert "DSMIN" in p.stderr and "DSMAX" in p.stderr


def test_wall_ends_with_mx_within_dsmin(wall):
    """Control for the next test: with the file's DSMIN = 0.001 the steps into the wall
    are halved until below DSMIN and the run ends with MX (-9) at the last converged
    point, less than sqrt(2) DSMIN (in mu) from the wall."""
    with time_limit(60, "wall"):
        res = do_run(wall / "c.wall", "wall")
    last = res.rows[-1]
    assert last.ty == -9
    assert 0.0 <= 1.0 - last.values[0] < math.sqrt(2) * 0.001 * (1 + 1e-6)


def test_dsmin_zero_is_replaced_and_does_not_hang(wall):
    """DSMIN = 0 becomes 1e-4 |DS| = 1e-6 (main.f90: INIT1): the halving ends and the run
    stops with MX within sqrt(2) x 1e-6 of the wall (checked at 1e-5, which still
    excludes any DSMIN >= 7e-6, e.g. the default 0.005)."""
    with time_limit(60, "DSMIN=0"):
        res = do_run(wall / "c.wall", "dsmin0", DSMIN=0)
    last = res.rows[-1]
    assert last.ty == -9
    assert 0.0 <= 1.0 - last.values[0] < 1e-5


def test_crossing_type_does_not_depend_on_which_test_is_located_first(tmp_path_factory):
    """hopfcross with k = PAR(4) = 1 (found in review): the same loci with a p2-dependent
    frequency w exp(+-p2). At the crossing both the BP and the ZH tests vanish; their linear zero
    estimates now put ZH first (0.590 against 0.593 of the step). One special point must
    be reported, as BP (31: AUTO's test order, a bifurcation first), and MXBF must still
    switch onto the second locus and find its GH (x0 = p2 = 1/2, where l1 = (x0 - 1/2) /
    omega-type factor changes sign) and its fold."""
    d = scratch(tmp_path_factory, "hopfcross")
    with time_limit(120, "hopfcross, k = 1"):
        do_run(d / "c.hopfcross", "eq", PAR={4: 1.0})
        res = do_run(d / "c.hopfcross", "fwd", DS=0.02, **HB_CURVE)
    assert res.status == "ok"
    got = [(seg[0].br, [r.ty for r in labelled(seg)]) for seg in segments(res.rows)]
    assert got == [(2, [31, -34]), (3, [-32, -34]), (3, [32, -34])]
    gh = res("GH1")
    cfile = d / "c.hopfcross"
    assert gh.par[1] == pytest.approx(0.5, abs=located_tol(cfile, 0.5, DS=0.02))
