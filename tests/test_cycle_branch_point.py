"""Loci of branch points of cycles (IPS = 2, ISW = 2 and 3 from a BP label) against a
closed form: tests/data/circlebp, two families of circles r = p1 and r = exp(p2) of the
planar system r' = r g(r), theta' = 1 + r^2 with g = (r - p1)(exp(p2) - r) + p3.

A circle r* is a zero of g, period T = 2 pi / (1 + r*^2). A BP of cycles is where the
orbit's Jacobian in (u, p1, T) loses rank: for circles, where g(r*) = 0, g_r(r*) = 0 and
g_p1(r*) = 0 (the radial equation is the only one that depends on p1; T is fixed by r*).
sympy solves that below: r* = p1 = exp(p2), p3 = 0, so along the whole locus (ISW = 2 in
(p1, p2), ISW = 3 in (p1, p2, p3)) p1 = exp(p2), p3 = 0, max U(1) = p1 and
T = 2 pi / (1 + p1^2).

Tolerance 1e-6: Newton stops when the last correction is below EPSL = EPSU = 1e-7
relative (the error after it is far smaller), the orthogonality conditions use f_p by
central differences (~1e-9 relative), the circle's collocation error at NTST = 20,
NCOL = 4 is below 1e-10.
"""
import math
import shutil
from pathlib import Path

import pytest
import sympy as sp

from tolerances import location_tolerance
from washer.auto.constants_file import read_constants
from washer.cont.start import RunError
from washer.run import run

DATA = Path(__file__).parent / "data" / "circlebp"
TOL = 1e-6


def test_closed_form_locus():
    """The BP conditions of the circles solved by sympy: r = p1 = exp(p2), p3 = 0."""
    r, p1, p2, p3 = sp.symbols("r p1 p2 p3", real=True)
    g = (r - p1) * (sp.exp(p2) - r) + p3
    sols = sp.solve([g, sp.diff(g, r), sp.diff(g, p1)], [r, p1, p3], dict=True)
    assert sols == [{r: sp.exp(p2), p1: sp.exp(p2), p3: 0}]


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    d = tmp_path_factory.mktemp("circlebp")
    for f in DATA.iterdir():
        shutil.copy(f, d)
    return d


@pytest.fixture(scope="module")
def family(folder):
    one = run(folder / "c.circlebp", verbose=False, sv="one")
    assert one.status == "ok"
    return one


def test_bp_of_cycles(family, folder):
    """The circle r = 1 meets the family r = p1 at p1 = 1 (T = pi there). The Jacobian is
    singular at the BP, so the located orbit's radius is as uncertain as the location
    (tol), and T = 2 pi / (1 + r^2) moves by pi per unit of r there."""
    tol = location_tolerance(folder / "c.circlebp")
    (bp,) = [r for r in family.rows if r.lab and r.ty == "BP"]
    assert bp.values[0] == pytest.approx(1.0, abs=tol)
    assert bp.par[10] == pytest.approx(math.pi, abs=2 * math.pi * tol)


# ISW = 3 (2.9 s) runs with -m slow
@pytest.mark.parametrize("isw, icp", [(2, [1, 2, 11]),
                                      pytest.param(3, [1, 2, 3, 11], marks=pytest.mark.slow)])
def test_bp_locus(family, folder, isw, icp):
    """From BP1: the generating run (5 points, ending with EP, written with the curve's
    codes 6x) puts the orbit on the exact BP; the locus from its EP, both ways, follows
    p1 = exp(p2), p3 = 0, r = p1, T = 2 pi / (1 + p1^2)."""
    cfile = folder / "c.circlebp.loc"
    gen = run(cfile, verbose=False, sv=f"gen{isw}", restart=family, ISW=isw, ICP=icp)
    assert gen.status == "ok"
    assert len(gen.rows) == 5
    ep = gen.rows[-1]
    assert (ep.ty, ep.code) == ("EP", 69)
    assert ep.values[0] == pytest.approx(1.0, abs=TOL)
    reached = []
    for ds in (0.05, -0.05):
        loc = run(cfile, verbose=False, sv=f"loc{isw}", restart=gen, IRS=ep.lab, ISW=isw,
                  ICP=icp, DS=ds, NMX=25)
        assert loc.status == "ok"
        assert [r.code for r in loc.rows if r.lab] == [69]
        for row in loc.rows:
            p1 = row.values[0]
            assert p1 == pytest.approx(math.exp(row.par[1]), abs=TOL)
            assert row.par[2] == pytest.approx(0.0, abs=TOL)
            assert row.values[2] == pytest.approx(p1, abs=TOL)          # MAX U(1) = r
            assert row.par[10] == pytest.approx(2 * math.pi / (1 + p1 ** 2), abs=TOL)
        reached.append(loc.rows[-1].values[0])
    assert reached[0] > 1.9 and reached[1] < 0.35


def test_isw3_needs_a_branch_point(family, folder):
    """ISW = 3 (the generic BP locus) from a label that is no BP: a clear error."""
    with pytest.raises(RunError, match="ISW=3 continues the branch points"):
        run(folder / "c.circlebp.loc", verbose=False, sv="bad", restart=family, IRS="UZ1",
            ISW=3, ICP=[1, 2, 3, 11])


FOLDBP = Path(__file__).parent / "data" / "foldbp"


def test_closed_form_bp_at_a_fold():
    """tests/data/foldbp: the circles p1 = (r^2 - 1)^2 fold at r = 1, p1 = 0 (g = g_r = 0),
    where the exponent h of the multiplier across z = 0 vanishes: the branch point of
    cycles is the fold's tip. h has a zero of order 3 there for p2 = 0, of order 1 for
    p2 = 1 (so has the BP test, the regular in-plane determinant times 1 - exp(h T))."""
    r, p1, p2 = sp.symbols("r p1 p2", real=True)
    e = r ** 2 - 1
    g, h = p1 - e ** 2, e * (e ** 2 + p2)
    # circles (r > 0) where the family folds
    folds = [s for s in sp.solve([g, sp.diff(g, r)], [r, p1], dict=True) if s[r] > 0]
    assert folds == [{r: 1, p1: 0}]
    assert h.subs(r, 1) == 0
    for p2v, order in ((0, 3), (1, 1)):
        hs = sp.expand(h.subs(p2, p2v).subs(r, 1 + sp.Symbol("d")))
        low = min(sp.Poly(hs, sp.Symbol("d")).monoms())[0]
        assert low == order


@pytest.mark.parametrize("p2, order", [(0.0, 3), (1.0, 1)])
def test_bp_of_cycles_at_a_fold_tip(tmp_path, p2, order):
    """The BP of cycles at the fold's tip (r = 1, PAR(1) = 0, T = pi) is located and
    labelled, its BP test vanishing to the order 1 or 3 (tfc's run 5 shows one of high
    order). The Muller iteration alone only creeps towards the zero of order 3 (the
    location ran out of ITMX = 12 and the point was only noted); the power law fitted to
    its one-sided trials (events._power_secant) converges. Bounds: a simple zero is
    located to 10 tolerances EPSS (1 + sqrt|DS DSMAX|) in arclength, and r moves by at
    most the arclength; a zero of order 3 only to the cube root of the test's rounding
    (~1e-12 of its values over a step of 0.1: ~1e-5), so r to 1e-4; at the fold PAR(1) =
    (r^2 - 1)^2 is then 0 to 4 (r - 1)^2, and T = 2 pi / (1 + r^2) moves by pi (r - 1)."""
    for f in FOLDBP.iterdir():
        shutil.copy(f, tmp_path)
    tol = location_tolerance(tmp_path / "c.foldbp")
    dr = 10 * tol if order == 1 else 1e-4
    res = run(tmp_path / "c.foldbp", verbose=False, sv="fold", PAR={2: p2})
    assert res.status == "ok"
    assert [r.ty for r in res.rows if r.lab] == ["EP", "BP", "EP"]
    (bp,) = [r for r in res.rows if r.ty == "BP"]
    assert bp.par[1] == p2
    assert bp.values[1] == pytest.approx(1.0, abs=dr)               # MAX U(1) = r
    assert bp.values[0] == pytest.approx(0.0, abs=4 * dr ** 2 + 1e-12)
    assert bp.par[10] == pytest.approx(math.pi, abs=math.pi * dr + 1e-9)
    assert "Possible special point" not in (tmp_path / "d.fold").read_text()


def test_isoperiodic_locus_on_autos_curve(tmp_path):
    """The tfc demo's run 6: the BP locus of cycles at fixed period (ICP = [3, 1, 6]: the
    orthogonality conditions against PAR(3) and PAR(1), not the period) from AUTO's own
    BP2 record of run 5 (tests/data/tfc_bp/s.tfc.5.gz, label 24). Every point of ours
    lies on AUTO's curve (its b.tfc.6.fw, all 50 rows, by a cubic spline in PAR(3)):
    measured 1.5e-10 in PAR(1), 1e-12 in PAR(6); 1e-8 allowed (AUTO prints 11 digits,
    the spline through rows <= 0.006 apart in PAR(3) errs by ~h^4 f''''/384, and both
    engines stop Newton at EPSL = 1e-9)."""
    import numpy as np
    from scipy.interpolate import CubicSpline

    from washer.auto.files import read_b
    demo = Path(__file__).parent / "data" / "auto_demos" / "tfc"
    for f in ("tfc.f90", "c.tfc"):
        shutil.copy(demo / f, tmp_path)
    shutil.copy(Path(__file__).parent / "data" / "tfc_bp" / "s.tfc.5.gz", tmp_path)
    # the constants run 6 inherits in tfc.auto (runs 2, 3, 5), then its own
    kw = dict(e="tfc", IPS=2, IPLT=1, EPSL=1e-9, EPSU=1e-9, EPSS=1e-7, ITMX=12,
              UZR={6: 0.013}, ILP=0, NMX=50, NPR=10, THL={}, ICP=[3, 1, 6], ISW=2, DS=0.01,
              DSMAX=0.1)
    sw = run(tmp_path / "c.tfc", verbose=False, sv="sw", s="tfc.5", IRS=24, **kw)
    assert sw.status == "ok" and [r.code for r in sw.rows if r.lab] == [69]
    fw = run(tmp_path / "c.tfc", verbose=False, sv="fw", restart=sw,
             IRS=sw.rows[-1].lab, **kw)
    assert fw.status == "ok"
    assert [r.code for r in fw.rows if r.lab] == [64, 64, 64, 64, 69]
    auto = np.array([r.values for br in read_b(demo / "autoref" / "b.tfc.6.fw")
                     for r in br])
    auto = auto[np.argsort(auto[:, 0])]
    p1, p6 = CubicSpline(auto[:, 0], auto[:, -2]), CubicSpline(auto[:, 0], auto[:, -1])
    inside = [r for r in fw.rows if auto[0, 0] <= r.values[0] <= auto[-1, 0]]
    assert len(inside) == 50
    for r in inside:
        assert r.values[-2] == pytest.approx(float(p1(r.values[0])), abs=1e-8)
        assert r.values[-1] == pytest.approx(float(p6(r.values[0])), abs=1e-8)


def _system(folder, cfile, records, **kw):
    """The continued system a run of `cfile` with `kw` starts with (through the same
    start resolution as every run)."""
    from washer.auto.files import read_s
    from washer.cont.runner import build
    from washer.cont.user_problem.user_files import load_user_problem
    c = read_constants(folder / cfile)
    for k, v in kw.items():
        c.set(k, v)
    problem = load_user_problem(c["e"], folder, c["NDIM"])
    return build(c, problem, read_s(folder / f"s.{records}"))[0].system


@pytest.mark.parametrize("case", ["circle", "tfc"])
@pytest.mark.parametrize("generating", [True, False])
def test_jacobian_is_the_residuals_derivative(tmp_path, generating, case):
    """The analytic Jacobian of the extended system (second derivatives of f by mixed
    differences) against central differences of its residual, in the generating run and
    on the locus (ISW = 3): on the circles (the period free: orthogonality to f and to
    f_p1, whose derivative in p2 is -exp(p2) x) and on tfc's BP2 at NTST = 6 (fixed
    period, ICP = [3, 1, 6, 2]: orthogonality to f_p3 and f_p1), at a point with the
    adjoint (phi, phi3) of order 1 and b = 0.3 (the identity holds anywhere; at the start
    phi is |DS| small and its terms would hide below the tolerance). Steps 1e-4 (1 + |x|):
    truncation ~1e-8, and the residual's own differences (f_p, step 1e-7) round to ~1e-9
    of f, ~1e-5 over that step; measured at most 1.4e-7 of the largest entry, 1e-6
    allowed (a wrong sign of the f_pq term, or a 1 % error in f_uu^T phi, fails it)."""
    import numpy as np
    if case == "circle":
        for f in DATA.iterdir():
            shutil.copy(f, tmp_path)
        run(tmp_path / "c.circlebp", verbose=False, sv="one")
        cfile, records = "c.circlebp.loc", "one"
        kw = dict(ICP=[1, 2, 3, 11], ISW=3, NTST=6, IRS="BP1")
    else:
        demo = Path(__file__).parent / "data" / "auto_demos" / "tfc"
        for f in ("tfc.f90", "c.tfc"):
            shutil.copy(demo / f, tmp_path)
        shutil.copy(Path(__file__).parent / "data" / "tfc_bp" / "s.tfc.5.gz", tmp_path)
        cfile, records = "c.tfc", "tfc.5"
        kw = dict(e="tfc", IPS=2, ILP=0, NTST=6, THL={}, ICP=[3, 1, 6, 2], ISW=3, DS=0.01,
                  DSMAX=0.1, IRS=24)
    if not generating:
        sw = run(tmp_path / cfile, verbose=False, sv="sw", s=records, **kw)
        kw["IRS"], records = sw.rows[-1].lab, "sw"
    sysm = _system(tmp_path, cfile, records, **kw)
    assert sysm._generating is generating
    x0 = sysm.start()[0].copy()
    n, nu = sysm.n, sysm.coll.n_u
    x0[:nu].reshape(-1, 2 * n)[:, n:] /= np.abs(x0[:nu].reshape(-1, 2 * n)[:, n:]).max()
    x0[nu + sysm.xpar.index(sysm.i_phi3)] = 0.7
    if sysm.with_b:
        x0[nu + sysm.xpar.index(sysm.i_b)] = 0.3
    J = sysm.jacobian(x0).toarray()
    fd = np.empty_like(J)
    for j in range(len(x0)):
        e = np.zeros(len(x0))
        e[j] = 1e-4 * (1 + abs(x0[j]))
        fd[:, j] = (sysm.residual(x0 + e) - sysm.residual(x0 - e)) / (2 * e[j])
    assert np.abs(J - fd).max() <= 1e-6 * np.abs(J).max()


@pytest.mark.parametrize("isw, icp", [(2, [1, 2, 11]), (3, [1, 2, 3, 11])])
def test_restart_from_autos_generating_record(tmp_path, isw, icp):
    """AUTO-07p's own record of its generating run (lcbp, s.lcbp.2.sw, written by AUTO
    here: 4 NDIM components (u, phi, v, w), PAR(13..21) = phi3, a, b, q, r, c1, c2)
    restarts our locus: (u, phi) are its first 2 NDIM components and phi3, a, b sit at
    AUTO's places. lcbp's circles have radius PAR(1) and PAR(2) and period 1, so its BP
    locus is PAR(1) = PAR(2) = r (PAR(3) = 0); checked to Newton's tolerance."""
    demo = Path(__file__).parent / "data" / "auto_demos" / "lcbp"
    for f in ("lcbp.f90", "c.lcbp"):
        shutil.copy(demo / f, tmp_path)
    shutil.copy(Path(__file__).parent / "data" / "lcbp_bp" / "s.lcbp.2.sw.gz", tmp_path)
    loc = run(tmp_path / "c.lcbp", verbose=False, sv="loc", s="lcbp.2.sw", e="lcbp", IRS=8,
              ISW=isw, ICP=icp, NMX=15, DS=0.01)
    assert loc.status == "ok"
    assert [r.code for r in loc.rows if r.lab] == [64, 69]
    assert loc.rows[-1].values[0] > 2.4
    for row in loc.rows:
        p1 = row.values[0]
        assert row.par[1] == pytest.approx(p1, abs=TOL)
        assert row.values[2] == pytest.approx(p1, abs=TOL)          # MAX U(1) = r
        assert row.par[2] == pytest.approx(0.0, abs=TOL)
        assert row.par[10] == pytest.approx(1.0, abs=TOL)


def test_adjoint_second_derivatives_both_ways():
    """VectorField.fuu_adjoint / fup_adjoint: by differences of the user's f_u (JAC = 1)
    and by mixed differences of f alone (JAC = 0) agree with the Hessian of phi . f of
    the circles written out: f = (x g - w y, y g + w x), g = (r - p1)(e^p2 - r) + p3,
    w = 1 + r^2, differentiated by sympy. Measured at most 5e-9 relative (steps FD_STEP
    on f_u, ~1e-4 on f), 1e-7 allowed."""
    import numpy as np

    from washer.cont.systems.bvp import VectorField
    from washer.cont.user_problem.user_files import load_python_problem
    x, y, p1, p2, p3, a, b = sp.symbols("x y p1 p2 p3 a b", real=True)
    r = sp.sqrt(x ** 2 + y ** 2)
    g = (r - p1) * (sp.exp(p2) - r) + p3
    w = 1 + r ** 2
    phif = a * (x * g - w * y) + b * (y * g + w * x)                 # phi . f
    hess = sp.lambdify((x, y, p1, p2, p3, a, b), sp.hessian(phif, (x, y)))
    mixed = sp.lambdify((x, y, p1, p2, p3, a, b),
                        [sp.diff(phif, v, p2) for v in (x, y)])
    rng = np.random.default_rng(7)
    U = rng.uniform(0.3, 1.5, (5, 2))
    Phi = rng.standard_normal((5, 2))
    par = np.zeros(12)
    par[:3] = 0.8, 0.2, 0.05
    want = np.array([hess(*u, *par[:3], *ph) for u, ph in zip(U, Phi)], float)
    want_p = np.array([mixed(*u, *par[:3], *ph) for u, ph in zip(U, Phi)], float)
    for jac in (1, 0):
        problem = load_python_problem("circlebp", DATA, 2).with_jac(jac)
        assert problem.has_dfdu is (jac == 1)
        field = VectorField(problem, 2)
        got = field.fuu_adjoint(U, Phi, par)
        assert np.abs(got - want).max() <= 1e-7 * np.abs(want).max()
        got_p = field.fup_adjoint(U, Phi, par, 2)
        assert np.abs(got_p - want_p).max() <= 1e-7 * np.abs(want_p).max()


def test_bp_test_of_cycles_takes_the_phase_condition_at_the_point(tmp_path):
    """The BP test of periodic orbits borders the Jacobian whose phase row is taken at the
    point itself (PeriodicOrbits._own_phase): the same matrix as the Jacobian after the
    point became the phase reference, whatever the reference was before."""
    import numpy as np
    for f in DATA.iterdir():
        shutil.copy(f, tmp_path)
    run(tmp_path / "c.circlebp", verbose=False, sv="one")
    sysm = _system(tmp_path, "c.circlebp", "one", IRS="UZ1", NTST=6)
    x0 = sysm.start()[0]
    x1 = x0.copy()
    x1[:sysm.coll.n_u] *= 1.1                       # not the phase reference's profile
    own = sysm._own_phase(x1).toarray()
    U, par = sysm.unpack(x1)
    sysm.set_phase_reference(U, par)
    want = sysm.jacobian(x1).toarray()
    assert np.abs(own - want).max() <= 1e-12 * np.abs(want).max()
    assert np.abs(sysm._own_phase(x1, sysm.jacobian(x1)).toarray() - want).max() == 0


def test_pvls_on_the_locus_receives_the_orbit(tmp_path):
    """On the BP locus of cycles the user's pvls receives what it receives on the
    periodic branch: an Orbit with GETP's helpers. PAR(5) = u.norm(1), the L2 norm of
    x(t) = r cos(2 pi t) over the period, is r / sqrt(2), r = MAX U(1) (1 on the family,
    p1 on the locus); the collocation's quadrature is exact for its piecewise
    polynomials, so the norm is as exact as the circle itself (TOL)."""
    for f in DATA.iterdir():
        shutil.copy(f, tmp_path)
    with open(tmp_path / "circlebp.py", "a") as fh:
        fh.write("\n\ndef pvls(u, par):\n    par[4] = u.norm(1)\n")
    one = run(tmp_path / "c.circlebp", verbose=False, sv="one")
    gen = run(tmp_path / "c.circlebp.loc", verbose=False, sv="gen", restart=one)
    assert gen.status == "ok" and len(gen.rows) == 5
    for row in one.rows + gen.rows:
        assert row.par[4] == pytest.approx(row.values[2] / math.sqrt(2), abs=TOL)


def _tor_field(p):
    """tor.f90's FUNC (Freire et al.'s circuit, odd: f(-u) = -f(u)) and its Jacobian."""
    import numpy as np
    rn, be, ga, r, a3, b3 = p[:6]

    def f(u):
        x, y, z = u
        return np.array([(-(be + rn) * x + be * y - a3 * x**3 + b3 * (y - x)**3) / r,
                         be * x - (be + ga) * y - z - b3 * (y - x)**3, y])

    def fu(u):
        x, y, _ = u
        q = 3 * b3 * (y - x)**2
        return np.array([[(-(be + rn) - 3 * a3 * x**2 - q) / r, (be + q) / r, 0.0],
                         [be + q, -(be + ga) - q, -1.0], [0.0, 1.0, 0.0]])
    return f, fu


@pytest.mark.slow
@pytest.mark.parametrize("window, order", [((-0.8326, -0.832), ["LP", "BP"]),
                                           ((-0.7880, -0.7870), ["BP", "LP"])],
                         ids=["PT79", "PT93"])
def test_symmetry_breaking_bp_just_past_a_fold(tmp_path, window, order):
    """tor's cycles from its Hopf point (run 2) fold at PAR(1) = -0.832514 and, 2.9e-3
    further in arclength, break their symmetry u(t + T/2) = -u(t) at PAR(1) = -0.832438
    (AUTO labels it BP at PT 79). Next to that branch point the period is so ill-determined
    that the location's short steps from its trial points fail in ITNW = 5; the branch
    point must still be located. The pair recurs further on, branch point first: a
    symmetry-breaking BP at PAR(1) = -0.787593 and the fold 3e-6 past it (-0.787590).
    There AUTO's BP test changes sign (+360, then -146 and -73 at its trials) and its
    location fails ('No convergence using minimum step size', then 'Possible special
    point'): it labels only the LP, one point earlier than ours from there on (its last LP,
    PT 124, is our PT 125, the EP at NMX). Checked independently by shooting over half a period
    (DOP853, rtol 1e-12): a symmetric orbit is a fixed point of u0 -> -phi_{T/2}(u0), and
    the symmetry breaks where -Dphi_{T/2} has the eigenvalue -1; the fold is where its
    other nontrivial eigenvalue meets +1, a separate point (0.22 in period before the BP
    at PT 79, 0.062 after it at PT 93), and the shooting system over the whole period with
    PAR(1) loses rank at the BP only: a second branch crosses there, none at the fold.
    Tolerance: the location tolerance EPSS (1 + sqrt(DS DSMAX)) in arclength, in which
    PAR(1) has weight 1, so PAR(1) is located at least that well; the collocation error
    (NTST = 25) moves the exact zero by far less (AUTO's BP lies 2e-7 from the shooting
    value)."""
    import numpy as np
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq, fsolve

    demo = Path(__file__).parent / "data" / "auto_demos" / "tor"
    for f in ("tor.f90", "c.tor"):
        shutil.copy(demo / f, tmp_path)
    tol = location_tolerance(tmp_path / "c.tor")
    eq = run(tmp_path / "c.tor", verbose=False, sv="eq", e="tor")
    cyc = run(tmp_path / "c.tor", verbose=False, sv="cyc", e="tor", restart=eq, IRS="HB1",
              IPS=2, ICP=[1, 11])
    labelled = [r for r in cyc.rows if r.lab and window[0] < r.values[0] < window[1]]
    assert [r.ty for r in labelled] == order
    bp = labelled[order.index("BP")]

    P = np.array(bp.par, float)
    U = np.asarray(bp.U)

    def half_map(u0, lam, T):
        f, fu = _tor_field(np.r_[lam, P[1:]])
        sol = solve_ivp(lambda s, y: np.r_[f(y[:3]), (fu(y[:3]) @ y[3:].reshape(3, 3)).ravel()],
                        [0, T / 2], np.r_[u0, np.eye(3).ravel()], method="DOP853",
                        rtol=1e-12, atol=1e-14)
        return sol.y[:3, -1], sol.y[3:, -1].reshape(3, 3)

    # the orbit's point where y = 0, y' > 0 (the phase condition of the shooting)
    i = np.where((U[:-1, 1] <= 0) & (U[1:, 1] > 0))[0][0]
    a = -U[i, 1] / (U[i + 1, 1] - U[i, 1])
    z = [np.r_[U[i] + a * (U[i + 1] - U[i]), P[0]]]

    def orbit(T):
        z[0] = fsolve(lambda w: np.r_[half_map(w[:3], w[3], T)[0] + w[:3], w[1]], z[0],
                      xtol=1e-13)
        return z[0]

    def r_plus_one(T):
        """The eigenvalue of -Dphi_{T/2} nearest -1, plus 1, on the symmetric orbit of
        period T."""
        w = orbit(T)
        ev = np.linalg.eigvals(-half_map(w[:3], w[3], T)[1])
        return float(np.real(ev[np.argmin(np.abs(ev + 1))]) + 1)

    T0 = P[10]
    T_bp = brentq(r_plus_one, T0 - 0.02, T0 + 0.02, xtol=1e-10)
    lam_bp = orbit(T_bp)[3]
    assert abs(bp.par[0] - lam_bp) < tol
    # The fold is within that tolerance of the branch point in PAR(1) at PT 93 (2.7e-6):
    # the period, which changes fast there, tells them apart. The shooting's period at
    # the -1 eigenvalue is the BP's, not the fold's (measured: 3.4e-3 against 0.22 at
    # PT 79, 1.6e-3 against 0.062 at PT 93).
    fold = labelled[order.index("LP")]
    assert abs(bp.par[10] - T_bp) < 0.1 * abs(fold.par[10] - T_bp)

    # The fold, where the other nontrivial eigenvalue of -Dphi_{T/2} meets the trivial 1:
    # the characteristic polynomial with the root 1 divided out, x^2 - s x + p from the
    # trace s + 1 and the determinant p (the two eigenvalues meeting there are
    # ill-conditioned, their sum and product are not), vanishing at x = 1. It is the LP
    # labelled, within the location tolerance in PAR(1), and the LP's period lies far
    # nearer it than the BP's (measured 1.6e-7 and 0.22 at PT 78, 4.7e-6 and 0.062 at
    # PT 94): a fold of its own, apart from the branch point, not a pitchfork at a fold.
    def one_minus_s_plus_p(T):
        w = orbit(T)
        H = -half_map(w[:3], w[3], T)[1]
        return float(1 - (np.trace(H) - 1) + np.linalg.det(H))

    half_gap = 0.5 * abs(fold.par[10] - bp.par[10])
    T_fold = brentq(one_minus_s_plus_p, fold.par[10] - half_gap, fold.par[10] + half_gap,
                    xtol=1e-10)
    assert abs(fold.par[0] - orbit(T_fold)[3]) < tol
    assert abs(fold.par[10] - T_fold) < 0.1 * abs(T_fold - T_bp)

    # A second branch crosses at the BP and none at the fold: the shooting system over the
    # whole period in (u0, T, PAR(1)), phi_T(u0) - u0 and the phase, has rank 4 on a branch
    # and loses it at a branch point. Its smallest singular value at T_bp is bounded by
    # T_bp's error (1e-10) times its slope (~40 per unit period) and the integration's
    # rounding (rtol 1e-12 of the largest, ~300), ~4e-9: measured 3.7e-12 at PT 79, 2.9e-10
    # at PT 93, 1e-6 allowed; at the fold it is the branch's own (0.91 at PT 78, 0.86 at
    # PT 94; 0.75 at the regular PT 92).
    def smallest_singular_value(T):
        w = orbit(T)
        u0, lam = w[:3], w[3]
        f, fu = _tor_field(np.r_[lam, P[1:]])
        r = P[3]

        def rhs(_t, y):
            A = fu(y[:3])
            return np.r_[f(y[:3]), (A @ y[3:12].reshape(3, 3)).ravel(),
                          A @ y[12:] + [-y[0] / r, 0.0, 0.0]]      # f_PAR(1) = (-x / r, 0, 0)
        y = solve_ivp(rhs, [0, T], np.r_[u0, np.eye(3).ravel(), np.zeros(3)],
                      method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
        J = np.zeros((4, 5))
        J[:3, :3], J[:3, 3], J[:3, 4] = y[3:12].reshape(3, 3) - np.eye(3), f(y[:3]), y[12:]
        J[3, :3] = f(u0) / np.linalg.norm(f(u0))
        return np.linalg.svd(J, compute_uv=False)[-1]

    assert smallest_singular_value(T_bp) < 1e-6
    assert smallest_singular_value(T_fold) > 0.1


def _abcb_field(p):
    """abcb.f90's FUNC (the A -> B -> C reaction), its derivatives in u and in PAR(1)."""
    import numpy as np
    d, al, be, b, s = p[:5]

    def f(u):
        x1, x2, x3 = u
        e, x1c = np.exp(x3), 1 - x1
        return np.array([-x1 + d * x1c * e, -x2 + d * e * (x1c - s * x2),
                         -x3 - be * x3 + d * b * e * (x1c + al * s * x2)])

    def fu(u):
        x1, x2, x3 = u
        e, x1c = np.exp(x3), 1 - x1
        return np.array([[-1 - d * e, 0.0, d * x1c * e],
                         [-d * e, -1 - d * e * s, d * e * (x1c - s * x2)],
                         [-d * b * e, d * b * e * al * s,
                          -1 - be + d * b * e * (x1c + al * s * x2)]])

    def fp(u):
        x1, x2, x3 = u
        e, x1c = np.exp(x3), 1 - x1
        return np.array([x1c * e, e * (x1c - s * x2), b * e * (x1c + al * s * x2)])
    return f, fu, fp


def test_abcb_bp_two_points_past_the_tip_is_regular(tmp_path):
    """abcb's cycles in PAR(1) (run 2) turn at a tip, PAR(1) = 0.3462085, where AUTO labels
    LP (PT 83) and, two points later, BP at 0.3458076 (PT 85). AUTO's records of those
    points and of PT 80 (tests/data/abcb_tip, AUTO-07p 0.9.2) are checked by shooting
    (DOP853, rtol 1e-12): the Jacobian of (u0, T, PAR(1)) -> (phi_T(u0) - u0, phase)
    has full rank 4 on a branch and loses it at a branch point. At the tip its smallest
    singular value is 1.5e-6 against 0.06 at PT 80: fold and branch point coincide there
    (as AUTO's own BP test says: 5e-12 at the LP). At AUTO's BP it is 0.011, as regular
    as the branch two steps from the tip: that label is where AUTO's determinant, bordered
    by the previous step's direction, changes sign as that direction turns past the tip
    (+8e-5 at PT 84, -0.67 at the same point bordered by the step back, -0.34 at the
    'located' point), not a zero. Ours labels the singular tip (LP or BP: both are right
    there), and no BP past it."""
    import numpy as np
    from scipy.integrate import solve_ivp

    from washer.auto.files import read_s
    recs = {r.lab: r for r in read_s(Path(__file__).parent / "data" / "abcb_tip" / "s.abcb.2")}

    def smallest_singular_values(rec):
        p = np.array(rec.par, float)
        f, fu, fp = _abcb_field(p)
        u0, T = np.asarray(rec.U)[0], p[10]

        def rhs(t, y):
            u, A = y[:3], fu(y[:3])
            return np.r_[f(u), (A @ y[3:12].reshape(3, 3)).ravel(), A @ y[12:] + fp(u)]
        y = solve_ivp(rhs, [0, T], np.r_[u0, np.eye(3).ravel(), np.zeros(3)],
                      method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
        assert np.max(np.abs(y[:3] - u0)) < 1e-9          # AUTO's orbit is periodic
        J = np.zeros((4, 5))
        J[:3, :3] = y[3:12].reshape(3, 3) - np.eye(3)
        J[:3, 3], J[:3, 4] = f(y[:3]), y[12:]
        J[3, :3] = f(u0) / np.linalg.norm(f(u0))
        sv = np.linalg.svd(J, compute_uv=False)
        return sv[-1], sv[0]

    regular, tip, auto_bp = (smallest_singular_values(recs[k]) for k in (16, 17, 18))
    assert [recs[k].ty for k in (17, 18)] == ["LP", "BP"]
    assert tip[0] < 1e-5 * tip[1]                 # singular at the tip (1.5e-6 / 7.9)
    assert auto_bp[0] > 1e3 * tip[0]              # regular at AUTO's BP (0.011)
    assert auto_bp[0] > 0.1 * regular[0]          # as two steps from a regular tip would be

    demo = Path(__file__).parent / "data" / "auto_demos" / "abcb"
    for name in ("abcb.f90", "c.abcb"):
        shutil.copy(demo / name, tmp_path)
    eq = run(tmp_path / "c.abcb", verbose=False, sv="eq", e="abcb")
    cyc = run(tmp_path / "c.abcb", verbose=False, sv="cyc", e="abcb", restart=eq,
              IRS="HB1", IPS=2, ICP=[1, 11], IPLT=1)
    assert cyc.status == "ok"
    assert max(r.values[0] for r in cyc.rows) < recs[17].par[0] + 1e-6
    # the singular tip itself is our one special point there, at AUTO's LP to within AUTO's
    # location tolerance 2 EPSS (1 + sqrt|DS DSMAX|) = 2.1e-6 of PAR(1), typed LP or BP:
    # fold and branch point coincide at it (shooting above), both tests change sign over
    # the step, and which location converges at the singular point (the fold test flips
    # with the tangent; the BP test has a zero of high order, located by the power law
    # through one-sided trials) turns on rounding-level differences of the points before
    # it; no BP past it
    tip_pts = [r for r in cyc.rows if r.lab and r.ty in ("LP", "BP")
               and abs(r.values[0] - recs[17].par[0]) < 1e-3]
    assert len(tip_pts) == 1
    assert tip_pts[0].values[0] == pytest.approx(recs[17].par[0], abs=2.1e-6)
    assert not [r for r in cyc.rows if r.lab and r.ty == "BP"
                and abs(r.values[0] - recs[17].par[0]) > 2.1e-6]
