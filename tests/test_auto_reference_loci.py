"""The scripts ab2p.auto and lrz2p.auto (the equilibria of AUTO-07p's demos ab and lrz,
then ab's fold locus and both Hopf loci in two parameters) against AUTO-07p's own
output (tests/data/auto_reference/ab2p, lrz2p) and closed forms.

Special points are compared by type, order and parameter values at 1e-6
relative. Where AUTO-07p's own location is less accurate than that (it stops
when the arclength correction drops below EPSS), a closed form decides: ours
must match the exact value to 1e-8 and AUTO's to 2e-5 (documented per point).
"""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from auto_reference import AB2P_LOCUS, LRZ2P_LOCUS
from tolerances import location_tolerance
from washer.auto.files import read_b, type_name
from washer.run import run

DATA = Path(__file__).parent / "data"
REF = DATA / "auto_reference"


def scratch_copy(tmp_path_factory, demo: str) -> Path:
    """A scratch folder holding tests/data/DEMO's equations DEMO.py and constants c.DEMO."""
    d = tmp_path_factory.mktemp(demo)
    for f in (f"{demo}.py", f"c.{demo}"):
        shutil.copy(DATA / demo / f, d)
    return d


@pytest.fixture(scope="module")
def ab_runs(tmp_path_factory):
    d = scratch_copy(tmp_path_factory, "ab")
    out = {"eq": run(d / "c.ab", verbose=False, sv="eq")}
    common = dict(AB2P_LOCUS, PAR={}, s="eq", verbose=False)
    for name, irs, ds in (("lp_fwd", "LP1", 0.01), ("lp_bwd", "LP1", -0.01),
                          ("hb_fwd", "HB1", 0.01), ("hb_bwd", "HB1", -0.01)):
        out[name] = run(d / "c.ab", IRS=irs, DS=ds, sv=name, **common)
    out["dir"] = d
    return out


@pytest.fixture(scope="module")
def lrz_runs(tmp_path_factory):
    d = scratch_copy(tmp_path_factory, "lrz")
    out = {"eq": run(d / "c.lrz", verbose=False, sv="eq")}
    common = dict(LRZ2P_LOCUS, s="eq", IRS="HB1", verbose=False)
    out["hb_fwd"] = run(d / "c.lrz", sv="hb_fwd", **common)
    out["hb_bwd"] = run(d / "c.lrz", sv="hb_bwd", **dict(common, DS=-0.1))
    out["dir"] = d
    return out


def special_rows(path):
    """(type, branch, PAR(ICP(1)), PAR(ICP(2)) or None) of labelled non-regular, non-EP rows."""
    out = []
    for branch in read_b(path):
        for r in branch:
            name = type_name(r.ty)
            if r.lab and name not in ("", "EP"):
                out.append((name, r.br, r.values[0], r.values[-1]))
    return out


def auto_loose(run_name: str, k: int, ref_row):
    """Exact PAR(ICP(1)) of points where AUTO-07p's own value is off by more than
    1e-6 (computed by tests/ab_exact.py, independently of the engine), else None:
    ab's second HB, the UZ stop at p1 = 0.25, and ab's GH."""
    import ab_exact
    if run_name == "eq" and k == 3:
        par1, _, x1, x2 = ref_row[:4]             # Newton starts from AUTO's own row
        return ab_exact.hb_p1(17.0, (x1, x2, par1))
    if run_name == "eq" and k == 4:
        return 0.25                                   # the UZSTOP value itself
    if run_name == "hb_fwd" and k == 0:
        return ab_exact.gh_p1()
    return None


@pytest.mark.parametrize("name", ["eq", "lp_fwd", "lp_bwd", "hb_fwd", "hb_bwd"])
def test_ab_matches_auto(ab_runs, name):
    ours = special_rows(ab_runs["dir"] / f"b.{name}")
    ref = special_rows(REF / "ab2p" / f"b.{name}")
    ref_values = [r.values for b in read_b(REF / "ab2p" / f"b.{name}") for r in b
                  if r.lab and type_name(r.ty) not in ("", "EP")]
    assert [(t, b) for t, b, *_ in ours] == [(t, b) for t, b, *_ in ref]
    for k, (o, r) in enumerate(zip(ours, ref)):
        exact = auto_loose(name, k, ref_values[k])
        if exact is None:
            assert o[2] == pytest.approx(r[2], rel=1e-6), (k, o, r)
            assert o[3] == pytest.approx(r[3], rel=1e-6), (k, o, r)
        else:
            # Where AUTO-07p's own value is loose (it stops on EPSS), the exact value
            # judges both: ours within the documented location guarantee and closer
            # to it than AUTO's (by a factor 40-400 on this machine: a margin that
            # no floating-point detail of another machine erases); AUTO's within 2e-5.
            from washer.auto.constants_file import read_constants
            c = read_constants(DATA / "ab" / "c.ab")
            assert abs(o[2] - exact) <= location_tolerance(c)
            assert abs(o[2] - exact) < abs(r[2] - exact) / 10
            assert r[2] == pytest.approx(exact, rel=2e-5)


def test_ab_equilibria_follow_auto_row_by_row(ab_runs):
    """Every row of ab's equilibria (c.ab: 107 points to the UZSTOP at PAR(1) = 0.25)
    is AUTO-07p's: the same point numbers, stability signs, types and labels, and
    PAR(1) within what the methods leave open. The step sizes are AUTO's only if each
    step's Newton count is AUTO's (ADPTDS grows the step by 1.5 after 2 iterations,
    keeps it after 3): that holds with SOLVAE's predictor, the secant of the step that
    reached the point, and not with the tangent (92 points, PAR(1) 1.2337e-2 at PT 4
    against AUTO's 1.0784e-2). Regular rows before the first located point: within
    EPSL (1 + |PAR(1)|), the Newton tolerance that leaves each point open (the two
    difference Jacobians differ in their steps: AUTO's 1e-7 (1 + max|U|) for every
    column, ours per component). The located rows and the rows after them: within
    the location guarantee, to which AUTO's location is loose too (its UZ at
    0.24999901)."""
    from washer.auto.constants_file import read_constants
    c = read_constants(DATA / "ab" / "c.ab")
    ours = [r for b in read_b(ab_runs["dir"] / "b.eq") for r in b]
    ref = [r for b in read_b(REF / "ab2p" / "b.eq") for r in b]
    assert len(ref) == 107
    assert [(r.br, r.pt, r.ty, r.lab) for r in ours] == [(r.br, r.pt, r.ty, r.lab) for r in ref]
    located = False
    for o, r in zip(ours, ref):
        located = located or type_name(r.ty) not in ("", "EP")
        tol = location_tolerance(c) if located else c["EPSL"] * (1 + abs(r.values[0]))
        assert abs(o.values[0] - r.values[0]) <= tol, (r.pt, o.values[0], r.values[0])


def test_ab_closed_forms(ab_runs):
    cp = ab_runs["lp_fwd"]("CP1")
    assert cp.par[0] == pytest.approx(math.exp(-2), rel=1e-7)
    assert cp.par[1] == pytest.approx(16.0, rel=1e-7)
    for name in ("lp_bwd", "hb_bwd"):
        bt = ab_runs[name]("BT1")
        assert bt.par[1] == pytest.approx(64 / 3, rel=1e-6)
        np.testing.assert_allclose(bt.U, [0.25, 4 / 3], rtol=1e-5)
    # Folds satisfy u1 (1 - u1) = (1 + p3) / p2 (docs/auto.md 6.1).
    for lp in (ab_runs["eq"]("LP1"), ab_runs["eq"]("LP2")):
        assert lp.U[0] * (1 - lp.U[0]) == pytest.approx(4 / 17, rel=1e-8)


def test_hb_first_lyapunov_coefficient_is_kuznetsovs(ab_runs):
    """l1 at ab's HB1 (p2 = 17, p3 = 3) against Kuznetsov's eq 3.20 with sympy's exact
    derivatives at the exact Hopf point (mpmath, 30 digits; tests/closed_form_exact.py),
    both with |q| = 1 and <p, q> = 1. The engine's l1 is a Richardson-extrapolated finite
    difference, O(h^4) ~ 1e-9 relative here, at a Hopf point located to ~1e-8 in p1:
    1e-6 relative bounds both. The criticality follows its sign."""
    from ab_exact import F, X, hopf_point, p1, p2, u1, u2
    from closed_form_exact import first_lyapunov
    hb1 = ab_runs["eq"]("HB1")
    x1, x2, q1 = hopf_point({p2: 17.0}, [u1, u2, p1], [hb1.U[0], hb1.U[1], hb1.par[0]])
    exact = first_lyapunov(F, list(X), {u1: x1, u2: x2, p1: q1, p2: 17.0})
    assert abs(hb1.par[0] - q1) < 1e-7
    assert hb1.info["l1"] == pytest.approx(exact, rel=1e-6)
    assert hb1.info["criticality"] == ("supercritical" if exact < 0 else "subcritical")


def test_lorenz_matches_auto(lrz_runs):
    for name in ("eq", "hb_fwd", "hb_bwd"):
        ours = special_rows(lrz_runs["dir"] / f"b.{name}")
        ref = special_rows(REF / "lrz2p" / f"b.{name}")
        assert [(t, b) for t, b, *_ in ours] == [(t, b) for t, b, *_ in ref], name
        for o, r in zip(ours, ref):
            assert o[2] == pytest.approx(r[2], rel=1e-6), (name, o, r)


def test_lorenz_closed_forms(lrz_runs):
    from washer.auto.constants_file import read_constants
    c = read_constants(DATA / "lrz" / "c.lrz")
    hb = lrz_runs["eq"]("HB1")
    # The run uses JAC = 0: the Hopf test function is evaluated on central-difference
    # Jacobians, whose rounding noise (~1e-8 relative) makes it non-monotone at that
    # level, so no location can promise 1e-9 here. Asserted: the documented guarantee,
    # and docs/auto.md's comparison tolerance for located points (1e-6 relative; AUTO-07p's
    # own value, 24.736843683, is 6.4e-8 off).
    assert abs(hb.par[0] - 470 / 19) <= location_tolerance(c)
    assert hb.par[0] == pytest.approx(470 / 19, rel=1e-6)
    assert lrz_runs["eq"]("BP1").par[0] == pytest.approx(1.0, abs=1e-8)
    beta = 8 / 3
    for s in lrz_runs["hb_fwd"].specials + lrz_runs["hb_bwd"].specials:
        if s.ty == "UZ":
            # rho_H = sigma (sigma + beta + 3) / (sigma - beta - 1), written as a residual:
            # near sigma = 4 the locus is steep (d rho / d sigma ~ -300) and Newton's
            # EPSU tolerance on sigma would dominate a direct comparison of rho.
            rho, sigma = s.par[0], s.par[2]
            g = rho * (sigma - beta - 1) - sigma * (sigma + beta + 3)
            assert abs(g) <= 1e-6 * rho * sigma
            assert s.par[10] == pytest.approx(2 * np.pi / np.sqrt(beta * (sigma + s.par[0])), rel=1e-6)
