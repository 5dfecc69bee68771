"""Homoclinic orbits (IPS = 9, washer.cont.systems.homoclinic) against a closed form and
against AUTO-07p's own output.

Closed form: x'' = a (x - c) - (x - c)^2 + mu x' has, at mu = 0 and every a > 0, the
homoclinic orbit x - c = (3a/2) sech^2(sqrt(a) t / 2) to the saddle (c, 0); along it
H = y^2/2 - a (x - c)^2/2 + (x - c)^3/3 = 0 (sympy checks both below). Continued in (a, mu)
with the equilibrium solved for (IEQUIB = 1), the family must keep mu = 0, x0 = (c, 0) and
H = 0 on the profile to the discretisation's accuracy.

AUTO: its demo san (tests/data/homcont/README.md), runs 1 and 6-11 (IEQUIB = 0, the test
function IPSI = 11 in run 11), run by `run_script` as AUTO ran them.
"""
import shutil
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from auto_demo_compare import compare_files
from demo_files import DEMOS, autoref, copy_demo
from washer.auto.files import read_s
from washer.auto.script import run_script
from washer.cont import runner
from washer.cont.constants import Constants
from washer.cont.problem import Problem
from washer.cont.start import RunError
from washer.cont.user_problem.user_files import load_user_problem

DATA = Path(__file__).parent / "data" / "homcont"
T = 40.0               # PAR(11): the truncation interval
C = 0.5                # the saddle's x


def _exact_orbit():
    """sympy: x(t) - c = (3a/2) sech^2(sqrt(a) t/2) solves x'' = a (x-c) - (x-c)^2 and
    H vanishes on it; returns (x(t) - c, H) as functions."""
    t, a, X, Y = sp.symbols("t a X Y", positive=True)
    xi = sp.Rational(3, 2) * a * sp.sech(sp.sqrt(a) * t / 2) ** 2
    assert sp.simplify((sp.diff(xi, t, 2) - (a * xi - xi ** 2)).rewrite(sp.exp)) == 0
    H = Y ** 2 / 2 - a * X ** 2 / 2 + X ** 3 / 3
    assert sp.simplify(H.subs({X: xi, Y: sp.diff(xi, t)}).rewrite(sp.exp)) == 0
    return sp.lambdify((t, a), xi), sp.lambdify((X, Y, a), H)


def _problem(xi):
    def func(u, par):
        a, mu = par[0], par[1]
        x = u[0] - par[2]
        return np.array([u[1], a * x - x * x + mu * u[1]])

    def dfdu(u, par):
        return np.array([[0.0, 1.0], [par[0] - 2 * (u[0] - par[2]), par[1]]])

    def stpnt(u, par, t):
        par[0], par[1], par[2], par[10] = 1.0, 0.0, C, T
        par[11], par[12] = C + 1e-3, 1e-3          # a guess: IEQUIB = 1 solves for x0
        s = (t - 0.5) * T
        h = 1e-6
        u[0] = C + xi(s, 1.0)
        u[1] = (xi(s + h, 1.0) - xi(s - h, 1.0)) / (2 * h)
    return Problem(2, func, stpnt=stpnt, dfdu=dfdu, name="exact", jac=-1)


def _family(ntst):
    xi, H = _exact_orbit()
    c = Constants(dict(NDIM=2, IPS=9, IEQUIB=1, ICP=[1, 2, 21, 29, 30], IPSI=[1, 9, 10],
                       NTST=ntst, NCOL=4, JAC=-1, ISP=0, ILP=0, DS=0.05, DSMAX=0.2, NMX=30,
                       NPR=5))
    br = runner.run(c, _problem(xi))
    assert br.status == "ok"
    # the first point is the start as given (AUTO writes it uncorrected)
    return br.specials[1:], H


def test_exact_homoclinic_family_with_the_equilibrium_solved_for():
    pts, H = _family(40)
    assert len(pts) >= 5 and pts[-1].par[0] > 2.5          # a from 1 to past 2.5
    h_max = 0.0
    for r in pts:
        par, U = np.asarray(r.par), np.asarray(r.U)
        a, mu = par[0], par[1]
        x0 = par[11:13]
        # mu, x0: the discretisation's error (H's below, ~1e-6 at NTST = 40) bounds them;
        # measured ~1e-10
        assert abs(mu) < 1e-6 and np.max(np.abs(x0 - [C, 0.0])) < 1e-6
        # IPSI 1, 9, 10 (PAR(21), PAR(29), PAR(30)): the eigenvalues of f_u at the computed
        # x0, (mu +- sqrt(mu^2 + 4 (a - 2 (x0 - c)))) / 2 in closed form: rounding only
        d = a - 2 * (x0[0] - C)
        lam = np.array([mu - np.sqrt(mu * mu + 4 * d), mu + np.sqrt(mu * mu + 4 * d)]) / 2
        assert par[28] == pytest.approx(lam[0], rel=1e-12)
        assert par[29] == pytest.approx(lam[1], rel=1e-12)
        assert par[20] == pytest.approx(lam.sum(), abs=1e-12)
        h_max = max(h_max, float(np.max(np.abs(H(U[:, 0] - x0[0], U[:, 1] - x0[1], a)))))
    assert h_max < 1e-4
    # Collocation with NCOL = 4 converges at least as h^4 at every node (h^5 between mesh
    # points, h^8 at them): twice the intervals divide H's error on the profile by >= 16.
    pts2, _ = _family(80)
    h_max2 = max(float(np.max(np.abs(H(np.asarray(r.U)[:, 0] - r.par[11],
                                          np.asarray(r.U)[:, 1] - r.par[12], r.par[0]))))
                 for r in pts2)
    assert h_max / h_max2 > 16, (h_max, h_max2)


def test_homcont_values_refused_by_name(tmp_path):
    """A value that is none of HomCont's is said to be so, naming the constant."""
    xi, _ = _exact_orbit()
    base = dict(NDIM=2, IPS=9, IEQUIB=1, ICP=[1, 2], NTST=20, JAC=-1, NMX=2)
    for extra, words in ((dict(ITWIST=2), "ITWIST = 2"), (dict(IEQUIB=3), "IEQUIB = 3"),
                         (dict(ISTART=7), "ISTART = 7"), (dict(IPSI=[1, 13]), "[13]"),
                         (dict(IFIXED=[14]), "[14]"), (dict(IPSI=[17]), "[17]"),
                         (dict(IREV=[0, 1, 0]), "IREV"),
                         (dict(ISTART=3, IEQUIB=2), "NOT ALLOWED"),
                         (dict(ISTART=3, ITWIST=1), "ISTART = 3 with ITWIST"),
                         (dict(ISTART=3, IFIXED=[1]), "ISTART = 3 with ITWIST, IREV or "
                                                      "IFIXED")):
        with pytest.raises(RunError) as err:
            runner.run(Constants({**base, **extra}), _problem(xi))
        assert words in str(err.value)
        assert "not supported yet" not in str(err.value)


def test_san_runs_match_auto(tmp_path, monkeypatch):
    work = copy_demo("san", tmp_path, DATA / "san")
    monkeypatch.chdir(work)
    run_script("san9.auto")
    why = []
    # run 11's b-file is the demo's own (san.auto's runs 6-11 are san9.auto's)
    for ref in sorted([*(DATA / "san" / "autoref").glob("b.*"), autoref("san") / "b.11"]):
        a, matched, diff = compare_files(work / ref.name, ref)
        assert a, ref
        if len(matched) != len(a):
            why += diff
    assert not why, why


def test_orbit_flip_test_function_on_autos_solutions(tmp_path):
    # PSIHO's 11 on AUTO's own orbits: the start of san's run 11 (the end of run 10) and
    # its end, in the order the run meets them (the eigenvectors' signs follow the run):
    # AUTO's PAR(31) to its 11 written digits.
    recs = []
    for n in (10, 11):
        recs.append(read_s(DATA / "san" / "autoref" / f"s.{n}")[-1])      # s.NAME.gz
    prob = load_user_problem("san", DEMOS / "san", 3)
    c = Constants(dict(NDIM=3, IPS=9, IRS=recs[0].lab, ICP=[7, 8, 31], IPSI=[11], IEQUIB=0,
                       NTST=35, JAC=-1, ISP=0, ILP=0))
    run, _, _ = runner.build(c, prob, [recs[0]])
    hom = run.system
    # AUTO's PAR(31) at run 11's start: its b-file's first row (the s-record of run 10
    # was written before run 11 computed it), at its end: its s-record
    rows = [ln.split() for ln in (autoref("san") / "b.11").read_text().splitlines()
            if ln.split() and ln.split()[0] != "0"]
    for rec, expected in zip(recs, (float(rows[0][-1].replace("E", "e")), recs[1].par[30])):
        U, par = np.asarray(rec.U, float)[:, :3], np.asarray(rec.par, float)
        assert hom.psi(11, U, par) == pytest.approx(expected, rel=1e-10)


#: cir's special points of run 2 that differ from AUTO's (docs/continuation.md, "Homoclinic
#: orbits"): near
#: PAR(2) = 0 the equilibrium's stable pair crosses the imaginary axis (a Hopf point: the
#: truncated problem is ill-conditioned there), and UZ6-UZ8 differ from AUTO's by 5e-5 in
#: PAR(1), the size of the discretisation error there (NTST = 70 instead of 35 moves ours by
#: 4e-5). After UZ8 both branches go on to their EP at NMX (the located point's direction
#: is kept pointing along the branch: `iterator.Continuation._orient_located`).
#: UZ6's difference is at the location tolerance: it matches on an AVX-512 AMD EPYC and
#: not on the machine the demo table's count was made on
#: (docs/auto_compatibility.md).
CIR_DIFFER = {("b.2", "UZ", 6), ("b.2", "UZ", 7), ("b.2", "UZ", 8)}
CIR_AT_TOLERANCE = {("b.2", "UZ", 6)}


@pytest.mark.slow
def test_cir_runs_match_auto_away_from_the_hopf_point(tmp_path, monkeypatch):
    work = tmp_path / "cir"
    shutil.copytree(DEMOS / "cir", work, ignore=shutil.ignore_patterns("autoref"))
    monkeypatch.chdir(work)
    run_script("cir.auto")
    unmatched = set()
    for ref in sorted(autoref("cir").glob("b.*")):
        a, matched, why = compare_files(work / ref.name, ref)
        assert a, ref
        unmatched |= {(ref.name, p.ty, p.lab) for i, p in enumerate(a) if i not in matched}
        # no point of ours without AUTO's counterpart (the branch that turned back after
        # UZ8 added two UZ before its EP)
        assert not [w for w in why if " vs ours " in w], why
    assert CIR_DIFFER - CIR_AT_TOLERANCE <= unmatched <= CIR_DIFFER


def test_start_from_a_periodic_orbit_shifted_to_the_equilibrium():
    # ISTART = 5 from a record of another problem type is ISTART = 4 (PREHO): a long
    # periodic orbit, here the exact homoclinic orbit stored as one that starts at its
    # peak (the equilibrium in the middle of [0, 1]), is moved in time to start at its
    # mesh point nearest the equilibrium, taken (IEQUIB = 1) as its node of least |f|.
    from washer.cont import collocation as col
    from washer.cont.record import Record
    xi, H = _exact_orbit()
    mesh = col.Mesh.uniform(40, 4)
    t = mesh.node_times()
    s = np.mod(t * T + T / 2, T) - T / 2               # the peak at t = 0 and t = 1
    h = 1e-6
    U = np.c_[C + xi(s, 1.0), (xi(s + h, 1.0) - xi(s - h, 1.0)) / (2 * h)]
    par = np.zeros(36)
    par[[0, 2, 10]] = 1.0, C, T
    rec = Record(br=1, pt=10, code=-4, lab=1, nfpr=2, isw=1, ndim_user=2, ips=2, u=U,
                 par=par, icp=[11, 1], t=t, ntst=40, ncol=4)
    c = Constants(dict(NDIM=2, IPS=9, IRS=1, IEQUIB=1, ICP=[1, 2], NTST=40, NCOL=4, JAC=-1,
                       ISP=0, ILP=0, DS=0.05, DSMAX=0.2, NMX=4, NPR=1))
    br = runner.run(c, _problem(xi), restart=[rec])
    assert br.status == "ok" and len(br.specials) >= 4
    for r in br.specials[1:]:
        par, U = np.asarray(r.par), np.asarray(r.U)
        x0 = par[11:13]
        # as in the family above: the discretisation's error bounds mu, x0 and H
        assert abs(par[1]) < 1e-6 and np.max(np.abs(x0 - [C, 0.0])) < 1e-6
        assert np.max(np.abs(H(U[:, 0] - x0[0], U[:, 1] - x0[1], par[0]))) < 1e-4
        # both ends at the equilibrium (the orbit's tails, e^(-T/2) of its size)
        assert np.max(np.abs(U[[0, -1]] - x0)) < 1e-6


EXACT_F90 = """
      SUBROUTINE FUNC(NDIM,U,ICP,PAR,IJAC,F,DFDU,DFDP)
      IMPLICIT DOUBLE PRECISION (A-H,O-Z)
      DIMENSION U(NDIM),PAR(*),F(NDIM),DFDU(NDIM,*),DFDP(NDIM,*)
      X = U(1) - PAR(3)
      F(1) = U(2)
      F(2) = PAR(1)*X - X*X + PAR(2)*U(2)
      END
      SUBROUTINE STPNT(NDIM,U,PAR,T)
      IMPLICIT DOUBLE PRECISION (A-H,O-Z)
      DIMENSION U(NDIM),PAR(*)
      COMMON /BLHOM/ ITWIST,ISTART,IEQUIB,NFIXED,NPSI,NUNSTAB,NSTAB,NREV
      PAR(1) = 1.0D0
      PAR(2) = 0.0D0
      PAR(3) = 0.5D0
      PAR(11) = 40.0D0
      IF (IEQUIB.NE.0) THEN
        PAR(12) = 0.5D0
        PAR(13) = 0.0D0
      ELSE
        PAR(12) = 9.0D0
      ENDIF
      S = (T - 0.5D0) * PAR(11)
      U(1) = PAR(3) + 1.5D0 / COSH(S / 2) ** 2
      U(2) = -1.5D0 * TANH(S / 2) / COSH(S / 2) ** 2
      END
      SUBROUTINE PVLS
      END
      SUBROUTINE BCND
      END
      SUBROUTINE ICND
      END
      SUBROUTINE FOPT
      END
"""


#: The same file in C: AUTO's C user files declare the block as `blhom_1` (fnb's and kdv's
#: STPNT read ISTART and IEQUIB from it).
EXACT_C = """
#include "auto_f2c.h"
extern struct { integer itwist, istart, iequib, nfixed, npsi, nunstab, nstab, nrev; } blhom_1;
int func(integer ndim, const doublereal *u, const integer *icp, const doublereal *par,
         integer ijac, doublereal *f, doublereal *dfdu, doublereal *dfdp)
{
    doublereal x = u[0] - par[2];
    f[0] = u[1];
    f[1] = par[0] * x - x * x + par[1] * u[1];
    return 0;
}
int stpnt(integer ndim, doublereal t, doublereal *u, doublereal *par)
{
    doublereal s;
    par[0] = 1.0; par[1] = 0.0; par[2] = 0.5; par[10] = 40.0;
    if (blhom_1.iequib != 0) { par[11] = 0.5; par[12] = 0.0; } else { par[11] = 9.0; }
    s = (t - 0.5) * par[10];
    u[0] = par[2] + 1.5 / (cosh(s / 2) * cosh(s / 2));
    u[1] = -1.5 * tanh(s / 2) / (cosh(s / 2) * cosh(s / 2));
    return 0;
}
int bcnd() { return 0; }
int icnd() { return 0; }
int fopt() { return 0; }
int pvls() { return 0; }
"""


@pytest.mark.skipif(shutil.which("gfortran") is None or shutil.which("gcc") is None,
                    reason="gcc and gfortran are needed (Debian: gcc gfortran)")
@pytest.mark.parametrize("source", ["hx.f90", "hx.c"])
def test_a_user_files_stpnt_reads_homconts_common_block(tmp_path, source):
    # AUTO's user files read HomCont's constants from COMMON /BLHOM/ (kpr's STPNT sets the
    # equilibrium only for IEQUIB /= 0): this one writes PAR(12) = 0.5 there, else 9.
    (tmp_path / source).write_text(EXACT_F90 if source.endswith(".f90") else EXACT_C)
    prob = load_user_problem("hx", tmp_path, 2)
    c = Constants(dict(NDIM=2, IPS=9, IEQUIB=1, ICP=[1, 2], NTST=40, NCOL=4, JAC=0, ISP=0,
                       ILP=0, DS=0.05, DSMAX=0.2, NMX=3, NPR=1))
    br = runner.run(c, prob)
    assert br.status == "ok"
    # the first row is the start as STPNT left it; the later ones the corrected family
    assert br.rows[0].par[11] == 0.5
    assert all(abs(r.par[1]) < 1e-6 and abs(r.par[11] - C) < 1e-6 for r in br.rows[1:])


def test_users_boundary_and_integral_conditions_with_ipsi_9():
    """The user's NBC = 1 and NINT = 1 beside HomCont's (FBHO's BCND, ICHO's ICNI), each
    with one more free parameter: PAR(4) = int_0^1 (x - x0_1) dt and PAR(5) = a^2. On the
    exact family (mu = 0) the integral over the truncated orbit is
    (1/T) int_{-T/2}^{T/2} (3a/2) sech^2(sqrt(a) s/2) ds = 6 sqrt(a) tanh(sqrt(a) T/4) / T."""
    xi, _ = _exact_orbit()
    prob = _problem(xi)
    prob._bcnd = lambda u0, u1, par: [par[4] - par[0] ** 2]
    prob._icnd = lambda u, uold, udot, upold, par: [u[0] - par[11] - par[3]]
    def exact(a):
        return 6 * np.sqrt(a) * np.tanh(np.sqrt(a) * T / 4) / T
    # the start's PAR(4), PAR(5) are the closed form's at a = 1 (stpnt's)
    c = Constants(dict(NDIM=2, IPS=9, IEQUIB=1, ICP=[1, 2, 4, 5], NBC=1, NINT=1, NTST=40,
                       NCOL=4, JAC=-1, ISP=0, ILP=0, DS=0.05, DSMAX=0.2, NMX=12, NPR=4,
                       PAR={4: exact(1.0), 5: 1.0}))
    br = runner.run(c, prob)
    assert br.status == "ok"
    pts = br.specials[1:]
    assert len(pts) >= 3 and pts[-1].par[0] > 1.3
    for r in pts:
        par = np.asarray(r.par)
        a = par[0]
        # mu: the discretisation's error, as in the family above (measured ~1e-10)
        assert abs(par[1]) < 1e-6
        assert par[4] == pytest.approx(a * a, abs=1e-12)              # rounding only
        # the integral: the collocation's quadrature of the profile (H's error, 1e-6) and
        # the truncated orbit's deviation from the exact one, O(e^(-sqrt(a) T / 2)) = 2e-9
        # (measured 7e-10)
        assert par[3] == pytest.approx(exact(a), abs=1e-6)


@pytest.mark.slow
def test_a_free_parameter_in_no_equation_is_the_start_direction(tmp_path, monkeypatch):
    # kdv's second run (AUTO's demo, tests/data/auto_demos/kdv) adds the adjoint to run 1's
    # orbit with ICP = [3, 9]: PAR(9) is in no equation, so the Jacobian's null vector is
    # PAR(9)'s unit vector, and the run's one step moves PAR(9) by DS = -0.01 and nothing
    # else (AUTO's d.2: starting direction PAR(9) 1, PAR(3) 0, PAR(10) 0). The border of
    # PAR(ICP(1)) = PAR(3) is singular there, and the reduced matrix of the long orbit
    # (T = 20, eigenvalues +-4.4) gives a "null vector" with |J z| = 3 |J| |z|: before,
    # the start took it and PAR(9) went to -4.93.
    from washer.auto.files import read_b
    src = Path(__file__).parent / "data" / "auto_demos" / "kdv"
    work = tmp_path / "kdv"
    shutil.copytree(src, work, ignore=shutil.ignore_patterns("autoref"))
    (work / "two.auto").write_text("r1=run('kdv',sv='1')\nr2=run(r1,c='kdv.2',sv='2')\n")
    monkeypatch.chdir(work)
    run_script("two.auto")
    rows = [r for b in read_b(work / "b.2") for r in b]
    start, end = rows[0].values, rows[-1].values
    # the b-file's columns: PAR(3), L2-NORM, MAX U(1..4), PAR(9)
    assert abs(end[-1] - (-0.01)) < 1e-9          # DS (AUTO: -1.0000001e-2, its perturbed DS)
    assert abs(end[0]) < 1e-12                    # PAR(3) = 0: the Hamiltonian orbit
    assert abs(end[1] - start[1]) < 1e-8          # the orbit has not moved


def test_the_projection_rows_keep_their_orientation_across_an_accepted_point():
    """The projection boundary condition's rows L = R^T P (P the projector onto the
    invariant subspace, R the reference basis taken at the last accepted point) must be a
    continuous function along the branch, across the accepted points too: the tests at
    the next point are compared with those stored at this one. A Schur basis's orientation
    is arbitrary (LAPACK may return -Z for the same subspace), so taking it as the new
    reference as it comes flips the sign of L's rows, and with them the sign of the BP
    determinant, between two points of the branch that differ by a step: snh's h1b had
    its BP test (AUTO's FNBPBV: 1e14 to 1e16, positive over the whole run) change sign
    at accepted points (+2.4e13 to -8.5e12 between two steps) and labelled BPs there.
    The new reference keeps the old one's orientation (det(Q^T R_old) > 0)."""
    from washer.cont.systems.homoclinic import _Projection
    rng = np.random.default_rng(3)
    At = np.diag([-2.0, -1.0, 1.5]) + 0.1 * rng.standard_normal((3, 3))
    for m, stable in ((1, False), (2, True)):
        proj = _Projection(m, stable)
        before = proj.rows(At)
        # a reference of the other orientation, as an earlier Schur call may have given
        proj.ref = proj.ref.copy()
        proj.ref[:, 0] *= -1
        flipped = proj.rows(At)
        assert np.allclose(flipped[0], -before[0])
        proj.accept(At)
        assert np.allclose(proj.rows(At), flipped, atol=1e-12)
