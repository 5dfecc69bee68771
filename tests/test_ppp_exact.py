"""AUTO's ppp demo (tests/data/auto_demos/ppp) checked against closed forms (sympy) and a
shooting computation (scipy), independent of both engines, where washer and AUTO-07p
label different points.

    u1' = u1 (1 - u1) - p4 u1 u2
    u2' = -p2 u2 + p4 u1 u2 - p5 u2 u3 - p1 (1 - exp(-p6 u2))
    u3' = -p3 u3 + p5 u2 u3,          p2, p3, p5, p6 = 1/4, 1/2, 3, 5

The plane u3 = 0 is invariant, and the Jacobian there is block triangular: the planar
block and lambda3 = -p3 + p5 u2. On it the Hopf locus in (p1, p4) is explicit in u2
(`boundary_hopf`): u1 = 1 - p4 u2 (from u1' = 0), p1 from u2' = 0, and the planar trace
0 is a quadratic in p4.

1. The Hopf locus run (ICP = [1, 4], ISW = 2) has branch points where this locus crosses the
   Hopf locus of the interior equilibria (u2 = p3 / p5 = 1/6): there lambda3 = 0, so the
   Jacobian has the one imaginary pair (a 3-dimensional system has no room for a second)
   and a zero eigenvalue: the same Hopf pair on both loci, a transcritical of equilibria.
   AUTO labels GH at PT 4 of every branch it switches to there along u3 = 0. The first
   Lyapunov coefficient along that locus (Kuznetsov's formula with exact derivatives:
   with q3 = 0 and the block structure it is the planar system's) is -0.662 and smooth
   there: no zero. AUTO's GH test (FNGHEQ) takes second differences (f(U + h q) +
   f(U - h q)) / h^2 with h ~ 6.6e-6 and leaves out -2 f(U), so a Newton residual of
   1e-11 moves it by O(1); its corrector accepts PT 4 after one iteration, and its
   "located" GH has a test value of -0.662 (its GH moves with DS: PT 5 at DS = 0.005,
   none at DS = 0.02). washer's test (washer.cont.normal_form) keeps f(x) in its
   differences and agrees with the closed form. The GH points both engines find, on the
   interior locus, are zeros of the same l1.
2. The cycles from HB8 shrink onto HB7 (p4 = 3 on this locus: p1 = 0.2923570163,
   period 8.3834185), where the family ends on the equilibria (a branch point of the
   periodic problem, both engines label it BP). washer's BP is there; AUTO's lies 7.0e-4
   back on the family, where shooting finds a cycle whose multipliers are 1, 0.998 and
   2.55: no second multiplier 1, so no branch point of cycles.
"""
import dataclasses
import gzip
import math
import shutil
from pathlib import Path
from types import SimpleNamespace

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

from washer.auto.constants_file import read_constants
from washer.auto.diagram import type_name
from washer.auto.files import read_b
from washer.cont.events import location_tolerance
from washer.cont.normal_form import first_lyapunov
from washer.cont.user_problem.user_files import load_user_problem
from washer.run import run

DEMO = Path(__file__).parent / "data" / "auto_demos" / "ppp"

u1, u2, u3, p1, p4 = sp.symbols("u1 u2 u3 p1 p4")
P2, P3, P5, P6 = sp.Rational(1, 4), sp.Rational(1, 2), 3, 5
U = (u1, u2, u3)
F = sp.Matrix([u1 * (1 - u1) - p4 * u1 * u2,
               -P2 * u2 + p4 * u1 * u2 - P5 * u2 * u3 - p1 * (1 - sp.exp(-P6 * u2)),
               -P3 * u3 + P5 * u2 * u3])
JAC = F.jacobian(U)
_ARGS = (u1, u2, u3, p1, p4)
_J = sp.lambdify(_ARGS, JAC, "mpmath")
_H = sp.lambdify(_ARGS, [[[sp.diff(F[i], U[j], U[k]) for k in range(3)] for j in range(3)]
                         for i in range(3)], "mpmath")
_T = sp.lambdify(_ARGS, [[[[sp.diff(F[i], U[j], U[k], U[m]) for m in range(3)]
                           for k in range(3)] for j in range(3)] for i in range(3)], "mpmath")

# The Hopf locus on u3 = 0: u1 from u1' = 0, p1 from u2' = 0, then the planar trace
# (J11 + J22 = 0) times (1 - exp(-p6 u2)) is a quadratic in p4 with coefficients in u2.
_U1 = 1 - p4 * u2
_P1 = sp.solve(F[1].subs({u3: 0, u1: _U1}), p1)[0]
_TRACE = sp.expand(sp.simplify((JAC[0, 0] + JAC[1, 1]).subs({u3: 0, u1: _U1, p1: _P1})
                               * (1 - sp.exp(-P6 * u2))))
_QUAD = [sp.lambdify(u2, c, "mpmath") for c in sp.Poly(_TRACE, p4).all_coeffs()]
_P1F = sp.lambdify((u2, p4), _P1, "mpmath")
_TRACEF = sp.lambdify((u2, p4), _TRACE, "mpmath")

#: The crossing of the two Hopf loci: u2 = p3 / p5 (lambda3 = 0) on the u3 = 0 locus.
U2_CROSS = sp.Rational(1, 6)
#: PAR(4) there (AUTO's and washer's BP at PAR(1) = 0.0772911), to pick the quadratic's root.
P4_NEAR_CROSS = 5.43
#: The demo's constants; ppp.auto's third run, the Hopf loci from HB2: its constants over them.
CONSTANTS = read_constants(DEMO / "c.ppp")
HOPF_RUN = dict(ICP=[1, 4], ILP=0, ISW=2, NMX=100, RL1=0.58, DSMAX=0.1)
#: Where both engines locate a special point of the Hopf loci: within EPSS (1 + sqrt(|DS
#: DSMAX|)) = 1.03e-4 in arclength, which bounds PAR(1) and PAR(4) (weight 1: each moves
#: at most as fast as the arclength).
LOCATED_HB = location_tolerance(
    SimpleNamespace(EPSS=CONSTANTS["EPSS"], DS=CONSTANTS["DS"], DSMAX=HOPF_RUN["DSMAX"]))


def corrected_hb(row) -> float:
    """How far a converged point of a Hopf locus may lie from its step's solution: the
    corrector's last change, below EPSU (1 + max |x|) on the unknowns (EPSL on PAR(1), here
    the same), x = (u, v with |v| = 1, kappa = omega^2, PAR(4)) (washer.cont.systems.hopf)."""
    kappa = (2 * math.pi / row.par[10]) ** 2
    big = max(np.max(np.abs(row.U)), abs(row.par[3]), kappa, 1.0)
    assert CONSTANTS["EPSL"] == CONSTANTS["EPSU"]
    return CONSTANTS["EPSU"] * (1 + max(big, abs(row.par[0])))


def _digits30(fn):
    """Run fn at 30 significant digits (mpmath's working precision, restored after)."""
    def wrapped(*args, **kw):
        with mp.workdps(30):
            return fn(*args, **kw)
    return wrapped


@_digits30
def boundary_hopf(x2, p4_near=P4_NEAR_CROSS):
    """(u1, u2, p1, p4) of the Hopf point of u3 = 0 whose equilibrium has u2 = x2 (mpf),
    on the root of the quadratic in p4 nearest p4_near."""
    x2 = mp.mpf(x2)
    roots = mp.polyroots([c(x2) for c in _QUAD], maxsteps=200, extraprec=60)
    q4 = min((mp.re(r) for r in roots if abs(mp.im(r)) < 1e-20), key=lambda r: abs(r - p4_near))
    return 1 - q4 * x2, x2, _P1F(x2, q4), q4


@_digits30
def lyapunov_exact(x, q1, q4):
    """Kuznetsov's first Lyapunov coefficient (Elements of Applied Bifurcation Theory, 3rd
    ed., eq 3.20) at the state x, p1 = q1, p4 = q4: exact second and third derivatives,
    eigenvectors at 30 digits, <q, q> = 1, <p, q> = 1. Returns (l1, eigenvalues)."""
    a = [mp.mpf(v) for v in (*x, q1, q4)]
    A = mp.matrix(_J(*a))
    H, T = _H(*a), _T(*a)
    ev, V = mp.eig(A)
    k = max(range(3), key=lambda i: mp.im(ev[i]))
    om = mp.im(ev[k])
    evl, W = mp.eig(A.T)
    kl = min(range(3), key=lambda i: abs(evl[i] - mp.conj(ev[k])))
    q = V[:, k] / mp.norm(V[:, k])
    p = W[:, kl]
    p = p / mp.conj(sum(mp.conj(p[i]) * q[i] for i in range(3)))

    def B(x, y):
        return mp.matrix([sum(H[i][j][m] * x[j] * y[m] for j in range(3) for m in range(3))
                          for i in range(3)])

    def C(x, y, z):
        return mp.matrix([sum(T[i][j][m][n] * x[j] * y[m] * z[n] for j in range(3)
                              for m in range(3) for n in range(3)) for i in range(3)])
    qb = mp.matrix([mp.conj(v) for v in q])
    h11 = mp.lu_solve(A, B(q, qb))
    h20 = mp.lu_solve(2j * om * mp.eye(3) - A, B(q, q))
    w = C(q, q, qb) - 2 * B(q, h11) + B(qb, h20)
    return mp.re(sum(mp.conj(p[i]) * w[i] for i in range(3))) / (2 * om), ev


def _auto_rows(name, tmp_path):
    """AUTO's own b-file rows (autoref b.NAME.gz), all branches: Rows with ty a name."""
    path = tmp_path / f"b.{name}"
    with gzip.open(DEMO / "autoref" / f"b.{name}.gz", "rt") as f:
        path.write_text(f.read())
    return [dataclasses.replace(r, pt=abs(r.pt), ty=type_name(r.ty))
            for branch in read_b(path) for r in branch]


#: ppp.auto's second run, the cycles from HB2: its constants over the demo's.
CYCLES_RUN = dict(IPS=2, ICP=[1, 11], ILP=0, NMX=15, NPR=50, DS=0.1, DSMAX=0.5)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """washer's runs of ppp.auto (the demo's constants unchanged), in memory."""
    folder = tmp_path_factory.mktemp("ppp")
    for f in ("ppp.f90", "c.ppp"):
        shutil.copy(DEMO / f, folder)
    c = folder / "c.ppp"
    eq = run(c, verbose=False, e="ppp", files=False)
    cycles = run(c, verbose=False, e="ppp", files=False, restart=eq, IRS="HB2", **CYCLES_RUN)
    hb = run(c, verbose=False, e="ppp", files=False, restart=eq, IRS="HB2", **HOPF_RUN)
    return folder, eq, cycles, hb


def _segments(rows):
    """The rows by continuation direction (each restarts at PT 1)."""
    segs = []
    for r in rows:
        if r.pt == 1 or not segs:
            segs.append([])
        segs[-1].append(r)
    return segs


# ------------------------------------------------------------------ the crossing
def test_the_hopf_loci_cross_where_lambda3_vanishes_with_one_imaginary_pair(tmp_path):
    x1, x2, q1, q4 = boundary_hopf(U2_CROSS)
    A = sp.Matrix(JAC.subs({u1: sp.Float(x1, 30), u2: U2_CROSS, u3: 0, p1: sp.Float(q1, 30),
                            p4: sp.Float(q4, 30)}))
    lam = sp.symbols("lam")
    c = [sp.N(v, 30) for v in sp.Poly(A.charpoly(lam).as_expr(), lam).all_coeffs()]
    # lam (lam^2 + w^2): trace 0 (Hopf), det 0 (lambda3 = -p3 + p5 u2 = 0), w^2 > 0
    assert abs(c[1]) < 1e-25 and abs(c[3]) < 1e-25 and c[2] > 0.4
    # AUTO's BP of the Hopf locus there (b.hb label 18, PAR(1), PAR(4)): the same point
    # within its location tolerance LOCATED_HB. Measured: 1.6e-6 and 1.7e-5.
    bp = [r for r in _auto_rows("hb", tmp_path) if r.lab == 18][0]
    assert bp.ty == "BP"
    assert bp.values[0] == pytest.approx(float(q1), abs=LOCATED_HB)
    assert bp.values[-1] == pytest.approx(float(q4), abs=LOCATED_HB)


# ------------------------------------------------------- l1 on the boundary locus
def test_l1_on_the_boundary_hopf_locus_is_negative_and_smooth_across_autos_gh_points(tmp_path):
    gh = [r for r in _auto_rows("hb", tmp_path) if r.ty == "GH" and r.values[0] < 0.08
          and abs(r.values[4]) < 1e-12]                   # U(3) = 0: the boundary locus
    assert len(gh) == 12                                  # PT 4 of 6 branches, both ways
    for r in gh:
        assert r.pt == 4
        x1, x2, q1, q4 = boundary_hopf(r.values[3])       # U(2)
        # AUTO's point lies on the closed-form locus (its PAR(1), PAR(4), U(1)) as closely
        # as its Newton leaves it: the last correction was below EPSL = EPSU = 1e-6
        # relative, and the iterates contract (quadratically, up to its difference
        # Jacobians' error) far below that after it: 1e-8 (1 + |x|), a hundredth of the
        # last correction's bound, allows a contraction of 1e-2. U(2), the input, is
        # printed to 11 digits: its rounding (5e-12) moves the closed form by up to 2e-10
        # (PAR(4) moves 37 times as fast as U(2) here). Measured: 1.3e-10 on PAR(1),
        # 7.2e-10 on PAR(4), 9.2e-11 on U(1).
        for exact, auto in ((q1, r.values[0]), (q4, r.values[-1]), (x1, r.values[2])):
            assert float(exact) == pytest.approx(auto, abs=1e-8 * (1 + abs(auto)))
        l1, _ = lyapunov_exact((x1, x2, 0), q1, q4)
        # exact (30 digits) at these points: -0.66198 .. -0.66172, l1's own variation
        # along them (U(2) 0.16577 .. 0.16758); the band is that again either side: the
        # value -0.662 with no zero, not a tolerance on a computation
        assert -0.6622 < l1 < -0.6616, (r.br, r.lab, l1)
    # The whole stretch of AUTO's PT 1 .. 6 either side of the crossing (U(2) from
    # 0.16499 to 0.16838), 1/6 itself left out (there A is singular): one sign, no zero.
    values = []
    for x2 in np.linspace(0.1645, 0.1690, 46):
        if abs(x2 - 1 / 6) > 1e-6:
            x1, x2, q1, q4 = boundary_hopf(x2)
            values.append(float(lyapunov_exact((x1, x2, 0), q1, q4)[0]))
    assert max(values) < -0.661 and min(values) > -0.663
    assert max(abs(np.diff(values))) < 1e-4               # smooth: no jump either


@pytest.mark.slow           # the demo's three runs: about 9 s on a loaded machine
def test_washers_gh_test_on_the_switched_branches_agrees_with_the_closed_form(runs):
    folder, _, _, hb = runs
    problem = load_user_problem("ppp", folder, 3)
    boundary = [s for s in _segments(hb.rows)
                if abs(s[0].par[0] - 0.0772911) < 1e-5 and abs(s[1].U[1] - 1 / 6) > 1e-6]
    # AUTO switches at six crossings, both ways (12 segments), and so does washer.
    assert len(boundary) == 12, len(boundary)
    for seg in boundary:
        assert not [r for r in seg[:20] if r.ty == "GH"]
        for r in seg[1:7]:
            x1, x2, q1, q4 = boundary_hopf(r.U[1])
            exact = float(lyapunov_exact((x1, x2, 0), q1, q4)[0])
            omega = 2 * math.pi / r.par[10]
            l1 = first_lyapunov(problem, r.U, r.par, omega)
            # fourth-order differences at h = 1e-3, 4e-3: truncation ~1e-10 here
            assert l1 == pytest.approx(exact, abs=1e-7)
            # a Newton residual of 1e-9 (f(U) != 0) leaves it in place: the differences
            # keep f(U) (AUTO's leave it out, h ~ 6.6e-6: O(1) for a residual 1e-11)
            A = problem.dfdu(r.U, r.par)
            shifted = r.U + np.linalg.solve(A, np.array([1e-9, -1e-9, 0.0]))
            assert first_lyapunov(problem, shifted, r.par, omega) == \
                pytest.approx(exact, abs=1e-6)


@pytest.mark.slow
def test_washers_gh_on_the_interior_locus_are_zeros_of_the_exact_l1(runs):
    """The GH points both engines find (on the interior locus u2 = 1/6, PAR(1) = 0.49876
    and 0.068383) are zeros of the same exact l1, with a sign change between the points
    either side: the closed form tells real GH points from AUTO's."""
    _, _, _, hb = runs
    located = set()
    for seg in _segments(hb.rows):
        for k, r in enumerate(seg):
            if r.ty != "GH":
                continue
            located.add(round(float(r.par[0]), 4))
            assert r.U[1] == pytest.approx(1 / 6, abs=1e-9)
            l1 = [float(lyapunov_exact(q.U, q.par[0], q.par[3])[0])
                  for q in (seg[k - 1], r, seg[k + 1])]
            assert l1[0] * l1[2] < 0
            # located to EPSS (1 + sqrt(DS DSMAX)) = 1.03e-4 in arclength: l1 within that
            # times its rate, at most |dl1| / chord between the neighbours (the chord in
            # (PAR(1), PAR(4), U) is at most their arclength)
            chord = np.linalg.norm(np.r_[seg[k + 1].par[[0, 3]] - seg[k - 1].par[[0, 3]],
                                         seg[k + 1].U - seg[k - 1].U])
            assert abs(l1[1]) < 1.03e-4 * abs(l1[2] - l1[0]) / chord
    # both of the interior locus's GH points (PAR(1) = 0.49876 and 0.068383) are among them
    assert {0.4988, 0.0684} <= located, located


# ------------------------------------------------ the switched loci's first steps
def _halves(rows, br):
    """The rows of branch br by continuation direction (`_segments`)."""
    return list(_segments([r for r in rows if r.br == br]))


@pytest.mark.slow
def test_the_loci_switched_at_the_first_hopf_locus_bp_follow_autos_rows(runs, tmp_path):
    """The first step of a locus switched at a BP of a Hopf locus goes DS along the null
    direction in all 2 n + 3 unknowns, the eigenvector v among them, so where it lands
    depends on which unit v of the two-dimensional null space of A^2 + kappa I the locus
    carries: AUTO's is NLVC's at the Hopf start (STPNHBF), which the phase condition then
    keeps. Branch 9 leaves the first locus's BP (the locus from HB2, where v is the start's
    all along u3 = 0): its first ten rows each way are AUTO's to twice the corrector's
    tolerance (`corrected_hb`: each engine's row within it of the same step's solution;
    2 EPSU (1 + 3.35) = 8.7e-6 with PAR(4) = 3.35 the largest unknown; PT 1, the BP, is
    the corrected last trial of the same location from the same bracket) (measured: 7.4e-7
    at PT 1, 1.4e-7 .. 2.9e-7 after it; with another unit v of that plane they were 7.6e-5
    apart at PT 2 and 1.1e-3 at PT 10)."""
    _, _, _, hb = runs
    ours = _halves(hb.rows, 9)
    auto = _halves(_auto_rows("hb", tmp_path), 9)
    assert len(ours) == len(auto) == 2
    for o, a in zip(ours, auto):
        for ro, ra in zip(o[:10], a[:10]):
            got = np.r_[ro.par[0], ro.U, ro.par[3]]
            want = np.array(ra.values[:1] + ra.values[2:6])
            assert np.max(np.abs(got - want)) <= 2 * corrected_hb(ro), (ro.pt, got - want)


@pytest.mark.slow
def test_the_eighteenth_locus_reaches_autos_bp_on_its_forward_half(runs, tmp_path):
    """The 18th locus (switched at the BP of the 14th) passes the crossing at PAR(1) =
    0.0772911 on both halves within NMX = 100 as AUTO's does (PT 91 forward, PT 86
    backward). Its v is inherited along the 14th locus, whose steps differ from AUTO's
    after AUTO's GH at its PT 4 (a label takes a step there), so its rows are not AUTO's
    to the corrector's tolerance: its start, the BP each engine located on the 14th, is
    within the location tolerance LOCATED_HB of that BP for each, and PT 2 one corrected
    step DS along the inherited direction from it: within 2 (LOCATED_HB + `corrected_hb`)
    = 2.2e-4 of AUTO's (measured 2.3e-6; 1.3e-4 with another unit v at the Hopf start)
    and the gap grows by about that per step. The BPs at PT 91 and 86 are the crossing
    with the interior locus (u2 = 1/6) in closed form, located to LOCATED_HB (measured
    3.5e-11 and 1.0e-10 in PAR(1))."""
    _, _, _, hb = runs
    bps = [[r for r in seg if r.ty == "BP"] for seg in _halves(hb.rows, 18)]
    assert [[r.pt for r in seg] for seg in bps] == [[91], [86]]
    _, _, q1, q4 = boundary_hopf(U2_CROSS)
    for seg in bps:
        assert seg[0].par[0] == pytest.approx(float(q1), abs=LOCATED_HB)
        assert seg[0].par[3] == pytest.approx(float(q4), abs=LOCATED_HB)
    ours = _halves(hb.rows, 18)
    auto = _halves(_auto_rows("hb", tmp_path), 18)
    for o, a in zip(ours, auto):
        got = np.r_[o[1].par[0], o[1].U, o[1].par[3]]
        assert np.max(np.abs(got - np.array(a[1].values[:1] + a[1].values[2:6]))) <= \
            2 * (LOCATED_HB + corrected_hb(o[1]))


# ------------------------------------------------------- the cycles end at HB7
@_digits30
def _hb7():
    x2 = mp.findroot(lambda v: _TRACEF(v, 3), mp.mpf("0.2"))     # p4 = 3: the demo's
    x1, x2, q1, q4 = boundary_hopf(x2, 3.0)
    A = mp.matrix(_J(x1, x2, 0, q1, q4))
    omega = mp.sqrt(A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0])
    return float(x1), float(x2), float(q1), float(2 * mp.pi / omega)


def test_hb7_in_closed_form(tmp_path):
    x1, x2, q1, period = _hb7()
    # The closed form's values (mpmath at 30 digits, exact to the float's last bit) as
    # first computed, kept to 12 and 9 decimals so that a change in the derivation (the
    # quadratic's root, findroot's start) shows: half a unit of the last digit kept.
    assert q1 == pytest.approx(0.292357016267, abs=5e-13)
    assert period == pytest.approx(8.383418464, abs=5e-10)
    # AUTO's HB7 (first run, PAR(1) of weight 1): within its location tolerance in
    # arclength EPSS (1 + sqrt(DS DSMAX)) = 1.014e-4 (DS = 0.01, DSMAX = 0.02; 2.6e-5)
    hb7 = [r for r in _auto_rows("ppp", tmp_path) if r.lab == 7][0]
    assert hb7.ty == "HB" and \
        hb7.values[0] == pytest.approx(q1, abs=1e-4 * (1 + (0.01 * 0.02) ** 0.5))


@pytest.mark.slow
def test_the_cycles_from_hb8_end_at_hb7_where_washer_places_the_bp(runs):
    _, _, cycles, _ = runs
    x1, x2, q1, period = _hb7()
    bp = [r for r in cycles.rows if r.ty == "BP"]
    assert len(bp) == 1
    # located to EPSS (1 + sqrt(DS DSMAX)) = 1.22e-4 in arclength (PAR(1) weight 1)
    located = location_tolerance(
        SimpleNamespace(EPSS=CONSTANTS["EPSS"], DS=CYCLES_RUN["DS"], DSMAX=CYCLES_RUN["DSMAX"]))
    assert bp[0].par[0] == pytest.approx(q1, abs=located)
    assert bp[0].par[10] == pytest.approx(period, rel=1e-4)
    assert bp[0].values[2] == pytest.approx(x1, abs=1e-4)        # MAX U(1): amplitude ~0


def _planar(t, y, q1):
    a, b = y[:2]
    f1 = a * (1 - a) - 3 * a * b
    f2 = -0.25 * b + 3 * a * b - q1 * (1 - math.exp(-5 * b))
    div = (1 - 2 * a - 3 * b) + (-0.25 + 3 * a - 5 * q1 * math.exp(-5 * b))
    return [f1, f2, div, -0.5 + 3 * b]


def _cycle_multipliers(q1, y0, period):
    """The cycle of the plane u3 = 0 (p4 = 3) at p1 = q1 by shooting from the section
    u2 = y0[1]: Newton on (u1, T); returns its nontrivial multipliers: within the plane
    exp(int div f dt) (Liouville: the other is 1), across it exp(int lambda3 dt)."""
    def flow(a, T):
        s = solve_ivp(_planar, (0, T), [a, y0[1], 0.0, 0.0], args=(q1,), method="DOP853",
                      rtol=1e-12, atol=1e-14)
        return s.y[:, -1]

    a, T = y0[0], period
    for _ in range(30):
        e = flow(a, T)
        g = np.array([e[0] - a, e[1] - y0[1]])
        if np.abs(g).max() < 1e-11:
            break
        d = 1e-7
        ea, eT = flow(a + d, T), flow(a, T + d)
        M = np.array([[(ea[0] - e[0]) / d - 1, (eT[0] - e[0]) / d],
                      [(ea[1] - e[1]) / d, (eT[1] - e[1]) / d]])
        da, dT = np.linalg.solve(M, -g)
        a, T = a + da, T + dT
    e = flow(a, T)
    return a, T, math.exp(e[2]), math.exp(e[3])


def test_autos_bp_of_cycles_is_not_a_branch_point(tmp_path):
    """AUTO's BP (b.ppp label 12) lies 7.0e-4 before HB7, on the family (its MAX U(1) is
    0.0173 above the equilibrium's); the cycle there, by shooting, has multipliers 1,
    0.998 and 2.55: none but the trivial one is 1, as a branch point of cycles needs."""
    x1, x2, q1, period = _hb7()
    bp = [r for r in _auto_rows("ppp", tmp_path) if r.lab == 12][0]
    assert bp.ty == "BP"
    par, umax = bp.values[0], bp.values[2]
    assert q1 - par == pytest.approx(6.97e-4, abs=1e-5)     # 5.7 times 1.22e-4
    assert umax - x1 == pytest.approx(0.0173, abs=1e-4)
    a, T, mu2, mu3 = _cycle_multipliers(par, (umax, x2), bp.values[-1])
    assert T == pytest.approx(bp.values[-1], rel=1e-4)        # AUTO's cycle (period)
    assert a == pytest.approx(umax, abs=2e-3)
    assert 1e-3 < 1 - mu2 < 3e-3                              # 0.998: in the plane
    assert mu3 > 2                                            # 2.55: across it
