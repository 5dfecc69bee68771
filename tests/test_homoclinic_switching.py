"""HomCont's n-homoclinic branch switching (ISTART = -N,
washer.cont.systems.homoclinic_switching): the cut of a 1-homoclinic orbit into N + 1
pieces (TRANHO) and back (CPBKHO) on an orbit whose collocation polynomials are exact,
and AUTO's demo sib, runs 7-9 (tests/data/homcont/sib: the switch to the 2-homoclinic
orbit along Lin's direction, its gap closed in (PAR(4), PAR(5)), the orbit continued as
one), row for row against AUTO-07p's output from the same start.
"""
from __future__ import annotations

import shutil
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from b_rows import branch_rows
from washer.auto.script import run_script
from washer.cont import collocation as col
from washer.cont.systems import homoclinic_switching as sw

DATA = Path(__file__).parent / "data" / "homcont" / "sib"
DEMO = Path(__file__).parent / "data" / "auto_demos" / "sib"
NDM = 3


def _orbit(t):
    """A closed curve through x0 = 0 (u(0) = u(1) = 0), polynomial of degree 4 in t:
    NCOL = 4 collocation polynomials represent it exactly, so every cut and join below
    is exact to rounding. Its farthest point from 0 is at t = 0.5."""
    t = np.asarray(t, float)[:, None]
    s = t * (1 - t)
    return np.hstack([4 * s, 16 * s ** 2, s * (2 * t - 1)])


def _record(ncol=4):
    tm = np.r_[0.0, np.sort(np.random.default_rng(3).uniform(0.02, 0.98, 18)), 1.0]
    tm[9] = 0.5                                    # a mesh point at the farthest point
    tm = np.sort(tm)
    t = col.Mesh(tm, ncol).node_times()
    U = _orbit(t)
    V = np.tile([0.0, 3.0, 4.0], (len(t), 1))      # an "adjoint": Lin's direction (0, .6, .8)
    return SimpleNamespace(U=np.hstack([U, V]), t=t, ntst=len(tm) - 1, ncol=ncol, udot=None,
                           rldot=[], icp=[], lab=1)


def test_pieces_of_an_exact_orbit_and_back():
    rec = _record()
    T, npar = 7.0, 36 + 2 * NDM
    par = np.zeros(npar)
    par[10] = T

    def f(u, p):                                   # only f(x_max) is stored
        return np.array([1.0, 2.0, 3.0]) + u
    out = sw.pieces_from_orbit(rec, NDM, 3, par, True, f)
    # the times: PAR(10) = T t_max, PAR(21) = T, PAR(11) = T (1 - t_max); gaps 0
    assert (par[9], par[20], par[10]) == (3.5, 7.0, 3.5)
    assert par[19] == par[21] == 0.0
    d, fm = sw.lin_slices(npar, NDM)
    assert np.allclose(par[d], [0.0, 0.6, 0.8], atol=1e-15)
    assert np.allclose(par[fm], f(_orbit([0.5])[0], par), atol=1e-15)
    # the merged mesh: 2 NTST - 2 intervals, AUTO's count (no two meshes share a point)
    assert out.ntst == 2 * rec.ntst - 2 and out.U.shape == (out.ntst * 4 + 1, 3 * NDM)
    s = out.t
    # piece 0 = u on [0, 1/2], the middle piece u from 1/2 round to 1/2, the last u on
    # [1/2, 1]: exact polynomials, rounding only
    assert np.allclose(out.U[:, :3], _orbit(s / 2), atol=1e-13)
    assert np.allclose(out.U[:, 3:6], _orbit((s + 0.5) % 1.0), atol=1e-13)
    assert np.allclose(out.U[:, 6:], _orbit(0.5 + s / 2), atol=1e-13)
    # the pieces join: each end is the next start
    assert np.allclose(out.U[-1, :6], out.U[0, 3:], atol=1e-13)
    # back to one orbit: twice round the curve in PAR(11) = 2 T
    back = sw.orbit_from_pieces(out, NDM, par)
    assert (par[9], par[10]) == (0.0, 2 * T)
    assert back.ntst == 3 * out.ntst and back.U.shape == (back.ntst * 4 + 1, NDM)
    assert np.allclose(back.U, _orbit((2 * back.t) % 1.0), atol=1e-13)


def _turning_orbit(t):
    """An orbit whose first component, an angle, turns once: -pi + 2 pi t from x0 =
    (-pi, 0, 0) to x0 + (2 pi, 0, 0), the others `_orbit`'s (polynomials of degree <= 4,
    exact in the collocation). Its farthest point from both ends in the angle is t = 0.5."""
    t = np.asarray(t, float)
    U = _orbit(t)
    U[:, 0] = -np.pi + 2 * np.pi * t
    return U


def test_pieces_of_an_orbit_whose_angle_turns_and_back():
    # TRANHO with rotations: each loop turns the angle once more, so the pieces join and
    # the last ends at x0 + 2 pi N (N = 3 here); joined back (CPBKHO) the orbit turns 3 times
    rec = _record()
    rec.U[:, :NDM] = _turning_orbit(rec.t)
    T, npar = 7.0, 36 + 2 * NDM
    par = np.zeros(npar)
    par[10], par[11] = T, -np.pi
    out = sw.pieces_from_orbit(rec, NDM, 4, par, True, lambda u, p: u)
    assert (par[9], par[20], par[22], par[10]) == (3.5, 7.0, 7.0, 3.5)
    s, two_pi = out.t, np.array([2 * np.pi, 0.0, 0.0])
    assert np.allclose(out.U[:, :3], _turning_orbit(s / 2), atol=1e-13)
    lap = _turning_orbit((s + 0.5) % 1.0) + np.outer(s + 0.5 >= 1.0, two_pi)
    assert np.allclose(out.U[:, 3:6], lap, atol=1e-13)
    assert np.allclose(out.U[:, 6:9], lap + two_pi, atol=1e-13)
    assert np.allclose(out.U[:, 9:], _turning_orbit(0.5 + s / 2) + 2 * two_pi, atol=1e-13)
    assert np.allclose(out.U[-1, :9], out.U[0, 3:], atol=1e-13)
    assert out.U[-1, 9] == pytest.approx(-np.pi + 3 * 2 * np.pi, abs=1e-13)
    assert np.array_equal(sw.rotations(out.U[0, :3], out.U[-1, 9:]), [3, 0, 0])
    back = sw.orbit_from_pieces(out, NDM, par)
    assert par[10] == 3 * T
    t = back.t
    assert np.allclose(back.U[:, 0], -np.pi + 6 * np.pi * t, atol=1e-12)
    assert np.allclose(back.U[:, 1:], _orbit((3 * t) % 1.0)[:, 1:], atol=1e-12)


@pytest.mark.parametrize("orbit", [_orbit, _turning_orbit], ids=["plain", "turning"])
def test_an_m_homoclinic_orbits_pieces_grow_to_n_greater_than_m(orbit):
    # PREHO's copy of the forelast piece: the 2-homoclinic cut's three pieces grown to
    # four and to five are the 3- and 4-homoclinic cuts of the same orbit (exact
    # polynomials: to rounding), times, gaps and the angle's turns included
    rec = _record()
    rec.U[:, :NDM] = orbit(rec.t)
    npar = 36 + 2 * NDM

    def start(n_piece):
        par = np.zeros(npar)
        par[10], par[11] = 7.0, rec.U[0, 0]
        return par, sw.pieces_from_orbit(rec, NDM, n_piece, par, True, lambda u, p: u)
    par3, three = start(3)
    for n_piece in (4, 5):
        par, direct = start(n_piece)
        grown = sw.more_pieces(three, NDM, n_piece, par3.copy(), True)
        assert np.allclose(grown.U, direct.U, atol=1e-12)
        assert np.array_equal(grown.t, direct.t)
        p = par3.copy()
        sw.more_pieces(three, NDM, n_piece, p, True)
        times = [sw.time_index(k, n_piece) - 1 for k in range(n_piece)]
        gaps = [sw.gap_index(k) - 1 for k in range(n_piece - 1)]
        assert np.allclose(p[times], par[times], atol=1e-14)
        assert np.allclose(p[gaps], 0.0, atol=1e-13)


def test_piece_times_and_gaps_are_autos_parameters():
    # FFHO's IT and FBHO's gaps: PAR(10), PAR(21), PAR(23), .., PAR(11); PAR(20), PAR(22), ..
    assert [sw.time_index(k, 4) for k in range(4)] == [10, 21, 23, 11]
    assert [sw.gap_index(k) for k in range(3)] == [20, 22, 24]
    assert sw.n_pieces(-3) == 4


def _rows(path):
    return [r for r in branch_rows(path)]


#: the b-rows' MAX U(1) .. MAX U(3) columns (after PAR(ICP(1)) and the L2 norm)
MAX_COLUMNS = slice(2, 5)


def _assert_rows_match(ours, auto, skip_last=False):
    """Every row: PT and TY AUTO's; the parameter columns and the L2 norm to 2e-6
    relative (both solve the same collocation equations, Newton to EPSL = EPSU = 1e-7 in
    relative change at each point; measured at most 1.7e-6 over the 70 rows), values
    near 0 to 1e-7 absolute. The MAX U columns are the largest node values, which
    depend on where the mesh puts its nodes: the start's mesh from ADAPT2 is not AUTO's
    (PT 1: MAX U(2) 0.3847327 against 0.3848650, while the L2 norm, an integral, agrees
    to 2e-9; why the two adapted meshes differ is not traced), so over the first 6 rows of
    a run, while the mesh adapts to the solution at every step (IAD = 1), they agree to
    1e-3 (measured 9e-4), then to 2e-6 as the rest."""
    assert [(r.pt, r.ty) for r in ours] == [(r.pt, r.ty) for r in auto]
    for o, a in zip(ours[:-1] if skip_last else ours, auto):
        ov, av = np.array(o.values), np.array(a.values)
        if o.pt <= 6:
            assert np.allclose(ov[MAX_COLUMNS], av[MAX_COLUMNS], rtol=1e-3)
            ov[MAX_COLUMNS] = av[MAX_COLUMNS]
        assert np.allclose(ov, av, rtol=2e-6, atol=1e-7), (o.pt, o.values, a.values)


@pytest.mark.slow
def test_sib_switch_to_the_2_homoclinic_orbit_matches_auto(tmp_path, monkeypatch):
    work = tmp_path / "sib"
    work.mkdir()
    for f in ("c.sib", "sib.c"):
        shutil.copy(DEMO / f, work)
    shutil.copy(DATA / "sib_switch.auto", work)
    shutil.copy(DATA / "s.6.gz", work)
    monkeypatch.chdir(work)
    run_script("sib_switch.auto")
    ref = DATA / "autoref"
    # run 7: the 2-homoclinic start and its gap PAR(22) opened to 0.2 (38 rows)
    _assert_rows_match(_rows(work / "b.7"), _rows(ref / "b.7"))
    # run 8: the gap closed in (PAR(4), PAR(5)): UZ at PAR(4) = 0.074 and at PAR(22) = 0,
    # the 2-homoclinic orbit. AUTO locates that zero to its EPSS = 1e-5 (PAR(22) =
    # 2.3e-6 there), ours to Newton's tolerance; the located points agree to that
    ours, auto = _rows(work / "b.8"), _rows(ref / "b.8")
    _assert_rows_match(ours, auto, skip_last=True)
    assert ours[-1].ty == -4 and abs(ours[-1].values[-1]) < 1e-10
    assert np.allclose(ours[-1].values[:-1], auto[-1].values[:-1], rtol=1e-5)


@pytest.mark.slow
def test_sib_2_homoclinic_orbit_continued_as_one_from_autos_orbit(tmp_path, monkeypatch):
    # run 9 from AUTO's own 2-homoclinic orbit (its s.8, UZ23): the pieces joined into one
    # orbit (CPBKHO) continued with the projection conditions (ISTART = 1). Rows 1-7 (to the
    # UZ at PAR(4) = 0.15) are AUTO's; after the located UZ (AUTO's at 0.1499999, ours at
    # 0.15) both leave along the secant of the location's last trial and take the same
    # steps (PAR(4) within 1e-7 at every PT), along the same curve.
    work = tmp_path / "sib"
    work.mkdir()
    for f in ("c.sib", "sib.c"):
        shutil.copy(DEMO / f, work)
    shutil.copy(DATA / "sib_run9.auto", work)
    shutil.copy(DATA / "autoref" / "s.8.gz", work)          # the script's restart reads it
    monkeypatch.chdir(work)
    run_script("sib_run9.auto")
    ours, auto = _rows(work / "b.9"), _rows(DATA / "autoref" / "b.9")
    assert [r.ty for r in ours[:7]] == [r.ty for r in auto[:7]] and ours[6].ty == -4
    for o, a in zip(ours[:6], auto[:6]):
        assert np.allclose(o.values, a.values, rtol=1e-6, atol=1e-7), (o.pt, o.values, a.values)
    # the UZ: PAR(4) = 0.15 located by both (AUTO's at 0.14999991), PAR(5) there
    assert ours[6].values[0] == pytest.approx(0.15, abs=1e-12)
    assert ours[6].values[-1] == pytest.approx(auto[6].values[-1], abs=1e-8)
    # past it, the same curve PAR(5)(PAR(4)): ours interpolated (a cubic spline through
    # our points, 0.004-0.015 apart in PAR(4)) at AUTO's PAR(4)
    from scipy.interpolate import CubicSpline
    p4, p5 = (np.array([r.values[0] for r in ours[6:]]),
              np.array([r.values[-1] for r in ours[6:]]))
    order = np.argsort(p4)
    curve = CubicSpline(p4[order], p5[order])
    # AUTO's points within our range or within 1e-6 of its ends: with the same steps the two
    # runs end within rounding of each other (7e-9 in PAR(4)), where the spline's
    # extrapolation over 1e-6 errs by at most |dPAR(5)/dPAR(4)| 1e-6 (the slope is ~0.05)
    reach = 1e-6
    inside = [a for a in auto[7:] if p4.min() - reach <= a.values[0] <= p4.max() + reach]
    err = np.array([abs(curve(a.values[0]) - a.values[-1]) for a in inside])
    # the spline's own error where our points are farthest apart and the curve bends
    # most (PAR(4) 0.12-0.15: measured 5e-7), rounding where they are dense (measured
    # 1.3e-9, 20 of AUTO's 23 points)
    assert len(inside) == 23 and err.max() < 1e-6
    assert np.sum(err < 2e-9) >= 19


@pytest.mark.slow
def test_sib_all_fourteen_runs_match_auto_with_jac_0(tmp_path, monkeypatch):
    # AUTO's whole script with JAC = 0 from run 4 (sib_jac0.auto; AUTO's b-files in
    # autoref-jac0/): the homoclinic orbit from the long cycle (run 4), its adjoint (5),
    # the inclination flip (6), the 2- and 3-homoclinic switches and the orbits continued
    # as one (runs 7-14, appended to b.6 as the script does). Every special point is AUTO's
    # (compare_files: type, order, parameter within AUTO's location tolerance) but one:
    # run 6's second zero of PAR(33) at PAR(4) = -0.071178, which AUTO's PT 29 brackets
    # (UZ, its PAR(33) -3.2e-4 there) and ours steps onto at PT 30 = NMX (PAR(33) = 1e-11,
    # written EP).
    from auto_demo_compare import compare_files
    work = tmp_path / "sib"
    work.mkdir()
    for f in ("c.sib", "sib.c"):
        shutil.copy(DEMO / f, work)
    shutil.copy(DATA / "sib_jac0.auto", work)
    monkeypatch.chdir(work)
    run_script("sib_jac0.auto")
    missed = []
    for ref in sorted((DATA / "autoref-jac0").glob("b.*")):
        a, matched, _ = compare_files(work / ref.name, ref)
        assert a, ref
        missed += [(ref.name, p.ty, round(p.par, 5)) for i, p in enumerate(a)
                   if i not in matched]
    assert missed == [("b.6", "UZ", -0.07118)], missed


def test_switching_on_an_orbit_whose_angle_turns_keeps_the_exact_family():
    # The pendulum theta'' = -a sin(theta) + mu theta' (tests/test_homoclinic_homotopy.py:
    # at mu = 0 its orbit leaves the saddle (-pi, 0) and reaches (pi, 0), NRTN = 1). Cut at
    # its farthest point from both ends in the angle (ISTART = -1: two pieces, ITWIST = 0)
    # and continued in a, the pieces keep the family's mu = 0 and end at x0 + 2 pi; the
    # 2-homoclinic cut (ISTART = -2) starts with its last piece at x0 + 4 pi and joins back
    # (ISTART = 1) into one orbit that turns twice (only the start and the join: a planar
    # flow has no 2-homoclinic orbits to continue).
    from washer.cont import runner
    from washer.cont.constants import Constants
    from pendulum_orbit import pendulum
    T = 24.0
    prob = pendulum(T)
    base = dict(NDIM=2, IPS=9, IEQUIB=1, NTST=40, NCOL=4, JAC=-1, ISP=0, ILP=0, NPR=4,
                DS=0.05, DSMAX=0.2)
    one = runner.run(Constants(dict(base, ICP=[1, 2], NMX=3)), prob)
    lab = one.specials[-1].lab
    two = runner.run(Constants(dict(base, ICP=[1, 2], NMX=12, IRS=lab, ISTART=-1,
                                    NTST=80)), prob, restart=one)
    assert two.status == "ok" and two.specials[-1].par[0] > 1.8
    for rec in two.specials:
        par, U = np.asarray(rec.par, float), np.asarray(rec.U, float)
        # the pieces' times T t_max and T (1 - t_max): the cut at the orbit's middle
        assert (par[9], par[10]) == pytest.approx((T / 2, T / 2), abs=1e-9)
        # mu of the exact family (the truncation and collocation errors, as the orbit's
        # own continuation: measured 3e-13)
        assert abs(par[1]) < 1e-10
        # x0 to x0 + 2 pi, joined at x_max (to the collocation's error, ends 6e-6 from
        # the saddles)
        assert np.allclose(U[-1, :2], U[0, 2:], atol=1e-10)
        assert U[-1, 2] == pytest.approx(np.pi, abs=1e-4)
    three = runner.run(Constants(dict(base, ICP=[1, 2, 21], NMX=1, IRS=lab, ISTART=-2,
                                      NTST=80)), prob, restart=one)
    U = np.asarray(three.specials[0].U, float)
    assert U[-1, 4] == pytest.approx(-np.pi + 4 * np.pi, abs=1e-4)
    assert np.allclose(U[-1, :4], U[0, 2:], atol=1e-12)
    joined = runner.run(Constants(dict(base, ICP=[1, 2], NMX=1, IRS=three.specials[0].lab,
                                       ISTART=1, NTST=240)), prob, restart=three)
    U = np.asarray(joined.specials[0].U, float)
    assert joined.specials[0].par[10] == pytest.approx(2 * T)
    assert U[0, 0] == pytest.approx(-np.pi, abs=1e-4)
    assert U[-1, 0] == pytest.approx(3 * np.pi, abs=1e-4)


def test_pieces_from_stpnt_follow_the_exact_family():
    # ISTART < 0 from STPNT (AUTO's STPNHO calls STPNT with the pieces' NDIM): the
    # user's stpnt gives x'' = a x - x^2 + mu x''s orbit (3a/2) sech^2(sqrt(a) t / 2)
    # (mu = 0; sympy below) cut at its peak into two pieces (ISTART = -1, ITWIST = 0),
    # their times PAR(10) = PAR(11) = T/2 and f(x_max) in PAR(NPAR - 1 .. NPAR). Continued
    # in a, the pieces keep the family's mu = 0 and join at its peak (3a/2, 0), the
    # Poincare section x' = 0 through the start's x_max.
    import sympy as sp
    from washer.cont import runner
    from washer.cont.constants import Constants
    from washer.cont.problem import Problem
    ts, av = sp.symbols("t a", positive=True)
    x = 3 * av / 2 * sp.sech(sp.sqrt(av) * ts / 2) ** 2
    assert sp.simplify((sp.diff(x, ts, 2) - av * x + x ** 2).rewrite(sp.exp)) == 0
    T, npar = 30.0, 22 + 2 * 2          # the constants' NPAR = 22 (the gap PAR(22)), NPARI

    def func(u, par):
        return np.array([u[1], par[0] * u[0] - u[0] ** 2 + par[1] * u[1]])

    def dfdu(u, par):
        return np.array([[0.0, 1.0], [par[0] - 2 * u[0], par[1]]])

    def stpnt(u, par, s):
        a = 1.0
        par[0], par[1], par[9], par[10] = a, 0.0, T / 2, T / 2
        par[npar - 2:] = [0.0, -0.75 * a ** 2]              # f(x_max), x_max = (3a/2, 0)
        for k, z in enumerate(((s - 1) * T / 2, s * T / 2)):   # the peak at t = 0
            c = 1 / np.cosh(np.sqrt(a) * z / 2)
            u[2 * k] = 1.5 * a * c ** 2
            u[2 * k + 1] = -1.5 * a ** 1.5 * c ** 2 * np.tanh(np.sqrt(a) * z / 2)
    prob = Problem(2, func, stpnt=stpnt, dfdu=dfdu, name="sech2", jac=-1)
    br = runner.run(Constants(dict(NDIM=2, IPS=9, IEQUIB=1, ISTART=-1, ICP=[1, 2], NPAR=22,
                                   NTST=60, NCOL=4, JAC=-1, ISP=0, ILP=0, NMX=12, NPR=4,
                                   DS=0.05, DSMAX=0.2)), prob)
    assert br.status == "ok" and br.specials[-1].par[0] > 1.6
    for rec in br.specials:
        par, U = np.asarray(rec.par, float), np.asarray(rec.U, float)
        a = par[0]
        assert U.shape[1] == 4 and len(par) == npar
        # mu and the equilibrium of the exact family (measured: mu 7e-13; the ends
        # e^(-sqrt(a) T / 2) ~ 3e-7 from the saddle and the projection conditions' error
        # quadratic in that, 1e-13, with the collocation's error)
        assert abs(par[1]) < 1e-10
        assert np.allclose(par[11:13], 0.0, atol=1e-12)
        # the join at the peak: x' = 0 (the section), x = 3a/2 (measured 3.5e-12)
        assert np.allclose(U[-1, :2], U[0, 2:], atol=1e-12)
        assert U[-1, :2] == pytest.approx([1.5 * a, 0.0], abs=1e-10)


KDV = Path(__file__).parent / "data" / "homcont" / "kdv"


@pytest.mark.slow
def test_kdv_switch_to_3_homoclinic_orbits_matches_auto(tmp_path, monkeypatch):
    # AUTO's demo kdv, runs 4 and 5 (ISTART = -3: four pieces, Lin's gaps PAR(22), PAR(24))
    # from AUTO's own run 3 (its s.3: from washer's own s.3 run 4 cuts the reversible
    # orbit at the other of its two equal peaks, docs/auto_compatibility.md's table).
    # Run 4 continues the pieces in (PAR(3), PAR(21), PAR(22), PAR(24)) to PAR(21) = 3.5,
    # run 5 restarts from its pieces' record with NPAR 32 widened to 36 (Lin's direction
    # and f(x_max) stay the last parameters) and closes the gaps in PAR(2).
    work = tmp_path / "kdv"
    work.mkdir()
    for f in ("kdv.c", "c.kdv.4", "c.kdv.5"):
        shutil.copy(DEMO.parent / "kdv" / f, work)
    shutil.copy(KDV / "kdv_switch.auto", work)
    shutil.copy(KDV / "s.3.gz", work)
    monkeypatch.chdir(work)
    run_script("kdv_switch.auto")
    ref = DEMO.parent / "kdv" / "autoref"
    for n in (4, 5):
        ours, auto = _rows(work / f"b.{n}"), _rows(ref / f"b.{n}")
        assert [(r.pt, r.ty, r.lab) for r in ours if r.ty] == \
            [(r.pt, r.ty, r.lab) for r in auto if r.ty]
    # run 4 up to the first zero of the gap PAR(22) (PT 23): PAR(3), the L2 norm and
    # PAR(21) AUTO's to Newton's tolerance EPSL = EPSU = 1e-6 (measured: 6e-11, 2.6e-8
    # and 1.4e-6 in PAR(21) ~ 10-20), the gaps (of order 1e-7 to 3e-6, below that
    # tolerance) to 5e-8 (measured 7e-9 and 1.9e-8)
    ours, auto = _rows(work / "b.4"), _rows(ref / "b.4")
    o = np.array([r.values for r in ours if r.pt <= 22])
    a = np.array([r.values for r in auto if r.pt <= 22])
    assert np.allclose(o[:, [0, 1, 5]], a[:, [0, 1, 5]], rtol=1e-6, atol=1e-7)
    assert np.allclose(o[:, 6:], a[:, 6:], atol=5e-8)
    uz = {r.lab: np.array(r.values) for r in ours if r.ty == -4}
    uz_auto = {r.lab: np.array(r.values) for r in auto if r.ty == -4}
    # UZ9, PAR(22) = 0: a zero of a gap that stays below Newton's tolerance along the
    # branch (its values 1e-8 to 1e-7 near it: not linear there, the rows' secant puts
    # it at PAR(21) = 10.19), so both engines' zeros are where their iterates cross it:
    # PAR(21) = 9.8564 (ours), 9.8460 (AUTO's); PAR(3) and the norm agree to 1e-7
    assert abs(uz[9][6]) < 1e-10 and abs(uz_auto[9][6]) < 1e-10
    assert uz[9][5] == pytest.approx(uz_auto[9][5], abs=0.02)
    assert np.allclose(uz[9][:2], uz_auto[9][:2], atol=1e-7)
    # UZ11, PAR(21) = 3.5: ours to Newton's tolerance, AUTO's to its location tolerance
    # EPSS (3.4999936); the gaps there AUTO's to 1e-4 relative (they change by 2e-4 per
    # unit of PAR(21) there)
    assert uz[11][5] == pytest.approx(3.5, abs=1e-8)
    assert uz[11][6:] == pytest.approx(uz_auto[11][6:], rel=1e-4)
    # run 5: PAR(2), the norm AUTO's to 1e-6 up to the gap's zero UZ13 (PAR(22) = 0), at
    # PAR(2) = 2.3204492 (AUTO 2.3204432: the gaps are 1e-10 to 1e-8 there, below
    # Newton's tolerance)
    ours, auto = _rows(work / "b.5"), _rows(ref / "b.5")
    o = np.array([r.values for r in ours if r.pt <= 12])
    a = np.array([r.values for r in auto if r.pt <= 12])
    assert np.allclose(o[:, :2], a[:, :2], rtol=1e-6)
    uz, uz_auto = [r for r in ours if r.ty == -4][0], [r for r in auto if r.ty == -4][0]
    assert uz.values[0] == pytest.approx(uz_auto.values[0], rel=1e-5)


FNB = Path(__file__).parent / "data" / "homcont" / "fnb"


@pytest.mark.slow
def test_fnb_3_homoclinic_gaps_from_autos_orbit_are_autos(tmp_path, monkeypatch):
    # AUTO's demo fnb, run 6 (ISTART = -2, Lin's gap PAR(22), UZR on its zeros), from
    # AUTO's own run-5 orbit (tests/data/homcont/fnb). From washer's own run 5 the zeros
    # differ from AUTO's by up to 0.09 in PAR(21) (the demo table): x_max, the cut and the
    # Poincare section, is a mesh point of the stored orbit, and the two engines' adapted
    # meshes put it at PAR(10) = 77.964 (ours) and 77.795 (AUTO's), so the section, Lin's
    # direction and the gap as a function of PAR(21) differ. Both engines' zeros are
    # independent of NTST there (80 and 160: to 1e-4, measured), so neither is a
    # discretisation error. From the same orbit ours are AUTO's: below PAR(21) = 430 to
    # 1e-3 (measured 1e-4); above it the long orbits are under-resolved at NTST = 80 (at
    # NTST = 160 both engines find the zeros 20 apart in PAR(21) on up to 640, at 80 a
    # sequence irregular above 480).
    work = tmp_path / "fnb"
    work.mkdir()
    for f in ("fhn.c", "c.fhn.6"):
        shutil.copy(DEMO.parent / "fnb" / f, work)
    shutil.copy(FNB / "fnb_switch.auto", work)
    shutil.copy(FNB / "s.5.gz", work)
    monkeypatch.chdir(work)
    run_script("fnb_switch.auto")
    ours = [r.values[0] for r in _rows(work / "b.6") if r.ty == -4 and r.values[0] < 430]
    auto = [r.values[0] for r in _rows(DEMO.parent / "fnb" / "autoref" / "b.6")
            if r.ty == -4 and r.values[0] < 430]
    assert len(ours) == len(auto) == 19
    assert np.allclose(ours, auto, atol=1e-3)


@pytest.mark.slow
def test_kdv_run_6_labels_the_gaps_zero_below_newtons_tolerance(tmp_path, monkeypatch):
    # AUTO's demo kdv, run 6 (from run 5's UZ1, AUTO's own s.3 as above): Lin's gap
    # PAR(24) stays of order 1e-10, below Newton's tolerance EPSL = 1e-7, and crosses 0 at
    # PT 23, where AUTO labels UZ15 (PAR(23) = 14.875802). Its change across the
    # location's last bracket (4.6e-10 over 2.2e-8 of arclength) is Newton's noise, not a
    # jump of the test: before, the location was refused as a jump, and every later label
    # of run 6 was one lower than AUTO's.
    work = tmp_path / "kdv"
    work.mkdir()
    for f in ("kdv.c", "c.kdv.4", "c.kdv.5", "c.kdv.6"):
        shutil.copy(DEMO.parent / "kdv" / f, work)
    script = (KDV / "kdv_switch.auto").read_text() + \
        "r6=run(r5('UZ1'),c='kdv.6',sv='6')\n"
    (work / "six.auto").write_text(script)
    shutil.copy(KDV / "s.3.gz", work)
    monkeypatch.chdir(work)
    run_script("six.auto")
    ref = DEMO.parent / "kdv" / "autoref"
    ours, auto = _rows(work / "b.6"), _rows(ref / "b.6")
    # the special points up to the output point at PT 35: AUTO's PT, type and label
    assert [(r.pt, r.ty, r.lab) for r in ours if r.ty and r.pt <= 35] == \
        [(r.pt, r.ty, r.lab) for r in auto if r.ty and r.pt <= 35] == [(23, -4, 15), (35, 4, 16)]
    uz, uz_auto = ([r.values for r in rows if r.lab == 15][0] for rows in (ours, auto))
    # PAR(2) and the norm AUTO's to 1e-5 relative (measured 2.6e-6 and 1.2e-6: both engines'
    # Newton stops at EPSL = 1e-7 in relative change, on different meshes); PAR(23) where the gap crosses 0 in each engine's iterates: the
    # gap changes by 1.9e-9 over the step's 0.71 in PAR(23) against a noise of 4.6e-10,
    # so its zero is fixed only to about 0.71 * 4.6e-10 / 1.9e-9 = 0.17 (measured: 14.876075
    # ours, 14.875802 AUTO's)
    assert np.allclose(uz[:2], uz_auto[:2], rtol=1e-5)
    assert abs(uz[4] - uz_auto[4]) < 0.17
    assert abs(uz[5]) < 1e-9 and abs(uz_auto[5]) < 1e-9
