"""The equilibrium runs (IPS = 1, ISW = 1 and 2) of AUTO-07p's demo scripts ab, lrz, chu
and plp, against AUTO-07p's own output.

tests/data/auto_demos/<demo>/ holds each demo's script (<demo>.auto), constants files
(c.*, unchanged) and in autoref/ the b-files AUTO-07p wrote (see the README of
tests/data/auto_demos); the equations are our own Python versions of <demo>.f90
(tests/data/<demo>/<demo>.py; ab's in tests/data/ab_demo/ because tests/data/ab/ab.py
starts elsewhere). Each run passes only the overrides the .auto script passes (e=,
IRS= through the restart solution, DS='-').

Compared: the labelled rows of every branch in order (type code and branch number),
and PAR(ICP(1)) (and PAR(ICP(2)) on two-parameter curves) at 1e-5 relative (absolute
for values of magnitude below 1), except end points (EP): where a branch ends by NMX or
a window depends on the whole step-size history, not on a located zero, so only its
type is compared. Where an exact value is known (sympy, tests/closed_form_exact.py and
tests/ab_exact.py), ours must also lie within the location guarantee of the exact
value, EPSS (1 + sqrt|DS DSMAX|) + EPSL (1 + |value|) in each coordinate of a unit
tangent: this is the check that decides where AUTO itself is looser than 1e-5 (chu's
HB: EPSS = 1e-4 there, AUTO is 1.4e-5 relative off the exact value).
"""
import functools
import math
from pathlib import Path

import numpy as np
import pytest

import ab_exact
from auto_reference import autoref, demo_dir
from b_rows import branch_rows, segments
import closed_form_exact as exact
from tolerances import location_tolerance
from washer.auto.constants_file import read_constants
from washer.auto.files import type_name
from washer.run import run



#: Rows of the equilibrium branches of a b-file (AUTO's BR > 0; periodic BR < 0).
rows = functools.partial(branch_rows, periodic=False)


def run_rows(cfile: Path, sv: str, **overrides) -> list:
    res = run(cfile, verbose=False, sv=sv, **overrides)
    assert res.status == "ok", res.status
    return rows(cfile.parent / f"b.{sv}")


def located_tol(cfile: Path, value: float, **overrides) -> float:
    c = read_constants(cfile)
    return (location_tolerance(c, **overrides)
            + overrides.get("EPSL", c["EPSL"]) * (1 + abs(value)))


def compare(ours: list, ref: list, npar: int = 1) -> None:
    """Labelled rows: same (BR, TY) sequence; PAR values at 1e-5 (EP excluded)."""
    lab_o = [r for r in ours if r.lab]
    lab_r = [r for r in ref if r.lab]
    assert [(r.br, r.ty) for r in lab_o] == [(r.br, r.ty) for r in lab_r]
    for o, r in zip(lab_o, lab_r):
        if type_name(r.ty) == "EP":
            continue
        pars = [0] + ([len(r.values) - 1] if npar == 2 else [])
        for k in pars:
            tol = 1e-5 * max(1.0, abs(r.values[k]))
            assert abs(o.values[k] - r.values[k]) <= tol, (type_name(r.ty), k, o.values, r.values)


# ---------------------------------------------------------------------------
# ab: start = run(e='ab', c='ab.1'); for each solution: run(solution, c='ab.2')

@pytest.fixture(scope="module")
def ab(tmp_path_factory):
    d = demo_dir(tmp_path_factory, "ab")
    res = run(d / "c.ab.1", verbose=False, e="ab", sv="start")
    out = dict(dir=d, start=res, start_rows=rows(d / "b.start"), p2=[])
    for s in res.specials:
        out[s.lab] = run_rows(d / "c.ab.2", f"from{s.lab}", e="ab", s="start", IRS=s.lab)
        out["p2"].append(s.par[1])
    return out


def test_ab_start_run(ab):
    """c.ab.1 continues the trivial state u = 0 in PAR(2) from 8: UZ at 14, 15, 16, 17
    and the UZSTOP at 18 (AUTO's run.log: EP 1, UZ 2..6, BR 1). Not saved by the
    script, so the exact values decide."""
    assert ab["start"].status == "ok"
    lab = [r for r in ab["start_rows"] if r.lab]
    assert [(r.br, type_name(r.ty)) for r in lab] == [(1, "EP")] + [(1, "UZ")] * 5
    cfile = ab["dir"] / "c.ab.1"
    for r, v in zip(lab, [8.0, 14.0, 15.0, 16.0, 17.0, 18.0]):
        assert r.values[0] == pytest.approx(v, abs=located_tol(cfile, v))
        assert abs(r.values[1]) < 1e-9                               # L2-norm of u = 0


@pytest.mark.parametrize("k", range(6))
def test_ab_families_match_auto(ab, k):
    """The k-th run of the script's loop against the k-th equilibrium branch of b.ab
    (relabelled by the script, so labels are not compared)."""
    ref = segments(rows(autoref("ab") / "b.ab.gz"))
    assert len(ref) == 6
    lab = sorted(s.lab for s in ab["start"].specials)[k]
    compare(ab[lab], ref[k])


@pytest.mark.parametrize("k", range(6))
def test_ab_families_exact(ab, k):
    """HB (f = 0, trace = 0, tests/ab_exact.py), LP (ab_lp_p1) and the UZ stop at
    p1 = 0.25 against exact values, within the location guarantee. The starts are c.ab.1's
    UZ points, the ends of the steps that pass PAR(2) = 14 .. 17 (within the location
    tolerance, as AUTO's: its folds at 0.1219011504, 0.1170147341 are those of
    PAR(2) = 17.0000009, not 17). Just beyond the cusp (PAR(2) = 16.0000008) the two folds
    lie sqrt(1 - 16 / p2) = 2.2e-4 apart in u1, within one step (DSMAX = 0.05): the fold
    test changes sign twice in it and neither is seen, as in AUTO's family there."""
    lab = sorted(s.lab for s in ab["start"].specials)[k]
    p2 = ab["p2"][k]
    cfile = ab["dir"] / "c.ab.2"
    lps = exact.ab_lp_p1(p2) if p2 > 16 and math.sqrt(1 - 16 / p2) > 0.05 else []
    hbs, n_lp = [], 0
    for r in ab[lab]:
        t = type_name(r.ty) if r.lab else ""
        if t == "HB":
            hbs.append(r)
            p1, _, x1, x2 = r.values[:4]
            want = ab_exact.hb_p1(p2, (x1, x2, p1))
            assert p1 == pytest.approx(want, abs=located_tol(cfile, want))
        elif t == "LP":
            assert r.values[0] == pytest.approx(lps[n_lp], abs=located_tol(cfile, lps[n_lp]))
            n_lp += 1
        elif t == "UZ":
            assert r.values[0] == pytest.approx(0.25, abs=located_tol(cfile, 0.25))
    assert n_lp == len(lps)
    assert len(hbs) == (0 if p2 < 10 else 1 if p2 < 16.5 else 2)


# ---------------------------------------------------------------------------
# lrz: run('lrz')

@pytest.fixture(scope="module")
def lrz(tmp_path_factory):
    d = demo_dir(tmp_path_factory, "lrz")
    return dict(dir=d, rows=run_rows(d / "c.lrz", "lrz", e="lrz"))


def test_lrz_matches_auto(lrz):
    """BR 1: EP, BP (rho = 1), UZ stop (30); MXBF = 10 switches at the BP: BR 2 in both
    directions (the two symmetric nontrivial branches), each with HB and the UZ stop."""
    compare(lrz["rows"], rows(autoref("lrz") / "b.lrz"))
    assert [len(s) > 1 for s in segments(lrz["rows"])] == [True] * 3


def test_lrz_exact(lrz):
    """BP at rho = 1 and HB at rho = 470/19 (sympy, Routh-Hurwitz)."""
    ex = exact.lrz_points()
    cfile = lrz["dir"] / "c.lrz"
    for r in lrz["rows"]:
        t = type_name(r.ty) if r.lab else ""
        if t in ("BP", "HB"):
            assert r.values[0] == pytest.approx(ex[t], abs=located_tol(cfile, ex[t])), t


# ---------------------------------------------------------------------------
# chu: run(e='chu', c='chu')

@pytest.fixture(scope="module")
def chu(tmp_path_factory):
    d = demo_dir(tmp_path_factory, "chu")
    return dict(dir=d, rows=run_rows(d / "c.chu", "chu", e="chu"))


def test_chu_matches_auto(chu):
    """MXBF = -2: BR 1 (EP, BP at alpha = 0, EP at NMX), one direction from that BP along
    the line of equilibria at alpha = 0 (BR 2: BP where it meets x = x*, EP at the
    A1 = 5 window), then from that BP in alpha (BR 3: HB, EP at NMX); no third switch.
    AUTO's chu HB (6.8044337) is 1.4e-5 relative from the exact 6.8043401 (EPSS = 1e-4
    here), so that value is compared with the exact one (test_chu_exact) instead."""
    ref = rows(autoref("chu") / "b.chu")
    ours = chu["rows"]
    lab_o = [r for r in ours if r.lab]
    lab_r = [r for r in ref if r.lab]
    assert [(r.br, r.ty) for r in lab_o] == [(r.br, r.ty) for r in lab_r]
    ex = exact.chu_points()
    assert abs(lab_r[5].values[0] - ex["HB"]) > 1e-5 * ex["HB"]     # AUTO is looser here
    not_hb = lambda rs: [r for r in rs if type_name(r.ty) != "HB"]
    compare(not_hb(ours), not_hb(ref))


def test_chu_exact(chu):
    """BP 1 at alpha = 0; BP 2 at |x| = x*, the nonzero root of h (with alpha = 0 on that
    branch); HB on branch 3 (x = x* fixed) from the characteristic polynomial. Both ours
    and AUTO's within the location guarantee of the exact values."""
    ex = exact.chu_points()
    cfile = chu["dir"] / "c.chu"
    for rs in (chu["rows"], rows(autoref("chu") / "b.chu")):
        lab = [r for r in rs if r.lab and type_name(r.ty) in ("BP", "HB")]
        assert [type_name(r.ty) for r in lab] == ["BP", "BP", "HB"]
        assert lab[0].values[0] == pytest.approx(0.0, abs=located_tol(cfile, 0.0))
        assert lab[1].values[0] == pytest.approx(0.0, abs=1e-12)
        assert abs(lab[1].values[2]) == pytest.approx(ex["x_star"], abs=located_tol(cfile, 1.5))
        assert lab[2].values[0] == pytest.approx(ex["HB"], abs=located_tol(cfile, ex["HB"]))
        assert abs(lab[2].values[2]) == pytest.approx(ex["x_star"], abs=1e-6)


# ---------------------------------------------------------------------------
# plp: plp = run(e='plp', c='plp.ss'); the Hopf locus from HB1 with c='plp.hb',
# run(hbstart) and run(hbstart, DS='-')

@pytest.fixture(scope="module")
def plp(tmp_path_factory):
    d = demo_dir(tmp_path_factory, "plp")
    out = dict(dir=d, ss=run_rows(d / "c.plp.ss", "ss", e="plp"))
    out["fwd"] = run_rows(d / "c.plp.hb", "hb_fwd", e="plp", s="ss", IRS="HB1")
    out["bwd"] = run_rows(d / "c.plp.hb", "hb_bwd", e="plp", s="ss", IRS="HB1", DS="-")
    return out


def test_plp_equilibria_match_auto(plp):
    """EP, HB (3.49995), HB (4.65046), UZ stop at PAR(4) = 6, branch 1."""
    ref = segments(rows(autoref("plp") / "b.plp"))[0]
    compare(plp["ss"], ref)


def test_plp_hopf_locus_matches_auto(plp):
    """ISW = 2 from HB1 (label 2, so branch 2), ICP = [4, 1]: forward to the UZSTOP
    PAR(1) = 109 at PAR(4) = 5.10967, backward (DS='-') to PAR(1) = 109 at 3.10386; UZ on
    an HB curve is code -34. b.loci holds both halves merged by the script (the backward
    half reversed first), so each run is compared with its end of that branch."""
    loci = segments(rows(autoref("plp") / "b.loci"))[0]
    uz = [r for r in loci if r.lab]
    assert [r.ty for r in uz] == [-34, -34]
    compare(plp["fwd"], [uz[1]], npar=2)
    compare(plp["bwd"], [uz[0]], npar=2)


def test_plp_hopf_locus_steps_as_auto(plp):
    """DS, DSMAX and NMX mean what they mean in AUTO: the forward Hopf locus from HB1 to
    the UZSTOP PAR(1) = 109 steps as AUTO's (24 rows of b.loci from the HB on, PAR(4) >=
    3.4999). The step rule and the norm are AUTO's (THU over the extended unknowns (u, v,
    kappa, PAR(ICP(2))), THL on PAR(ICP(1)), full Newton; the hidden first step, then
    ADPTDS after every regular point from the first written one on): the first seven
    steps are AUTO's to 1e-4 (2 Newton iterations per step, DS grows by 1.5). At the
    ninth AUTO's Newton needs a third iteration where ours needs two (DS grows by 1.1
    there, by 1.5 here), so the count may differ by two at the UZ stop. With the second
    derivatives frozen inside a step Newton needed 3 iterations, DS grew by 1.1 and the
    locus took 39 points."""
    loci = segments(rows(autoref("plp") / "b.loci"))[0]
    hb = plp["fwd"][0].values[0]
    auto_fwd = [r for r in loci if r.values[0] >= hb - 1e-4]
    assert len(auto_fwd) == 24
    # The steps (the HB they start from is located 8e-7 apart by the two engines).
    ours = np.diff([r.values[0] for r in plp["fwd"][:8]])
    auto = np.diff([r.values[0] for r in auto_fwd[:8]])
    np.testing.assert_allclose(ours, auto, rtol=1e-4)
    assert abs(len(plp["fwd"]) - len(auto_fwd)) <= 2


def test_plp_exact(plp):
    """Hopf points (f = 0, trace = 0 in (s, a, PAR(4)), sympy) at PAR(1) = 110 (HB1) and at
    the UZ stops PAR(1) = 109 of the locus."""
    ss = [r for r in plp["ss"] if r.lab and type_name(r.ty) == "HB"]
    cf = plp["dir"] / "c.plp.ss"
    for r in ss:
        want = exact.plp_hopf_p4(110.0, (r.values[2], r.values[3], r.values[0]))
        assert r.values[0] == pytest.approx(want, abs=located_tol(cf, want))
    ch = plp["dir"] / "c.plp.hb"
    for name in ("fwd", "bwd"):
        r = [r for r in plp[name] if r.lab][-1]
        want = exact.plp_hopf_p4(109.0, (r.values[2], r.values[3], r.values[0]))
        assert r.values[0] == pytest.approx(want, abs=located_tol(ch, want))
        assert r.values[-1] == pytest.approx(109.0, abs=located_tol(ch, 109.0))
