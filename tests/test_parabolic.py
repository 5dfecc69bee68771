"""Parabolic PDEs u_t = D u_xx + f(u, p) (AUTO's IPS = 11, 12, 14, 16, 17) against closed
forms worked out with sympy: the Hopf point of the uniform states in the wave speed, the
wave trains of a conservative travelling-wave equation, the branch points of stationary
states on an interval, and implicit Euler steps of a linear heat equation. AUTO-07p's own
demos (wav, pd1, pd2, bru) are compared with AUTO's b-files in test_auto_demo_folders."""
import gzip
import math
import shutil
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from b_rows import branch_rows
import shooting
from washer.auto.files import read_s, type_name
from washer.auto.script import run_script
from washer.run import run

LOGISTIC = '''
import numpy as np
def func(u, par):
    return np.array([par[0] * u[0] * (1.0 - u[0])])
def stpnt(u, par, t=0.0):
    par[0] = 2.0          # p
    par[9] = 1.0          # the wave speed c = PAR(10)
    par[14] = 0.5         # D = PAR(15)
    u[0] = 0.0
'''


def _fnws_jacobian():
    """FNWS's Jacobian at a uniform state (u*, 0) of u' = v, v' = -(c v + f(u)) / D,
    with a = f'(u*)."""
    a, c, D = sp.symbols("a c D", real=True)
    return sp.Matrix([[0, 1], [-a / D, -c / D]]), (a, c, D)


def test_uniform_states_hopf_in_the_wave_speed(tmp_path):
    """IPS = 11, continued in the speed c = PAR(10) at the uniform state u = 0 of
    f = p u (1 - u): the eigenvalues of FNWS's Jacobian are a complex pair with real part
    -c / 2D for c^2 < 4 D p (sympy), so the HB is at c = 0 with PAR(11) = 2 pi sqrt(D / p);
    PT's sign and the b-file's NDIM are those of the 2-component system."""
    J, (a, c, D) = _fnws_jacobian()
    lam = sp.symbols("lam")
    pair = sp.solve((J - lam * sp.eye(2)).det(), lam)
    re_part = sp.simplify((pair[0] + pair[1]) / 2)       # the pair's real part
    assert sp.simplify(re_part + c / (2 * D)) == 0
    assert sp.solve(re_part, c) == [0]
    values = {a: 2, D: sp.Rational(1, 2)}
    omega = sp.sqrt(a / D).subs(values)
    assert sp.simplify(pair[0].subs(values).subs(c, 0) ** 2 + omega ** 2) == 0
    period = float(2 * sp.pi / omega)

    (tmp_path / "lg.py").write_text(LOGISTIC)
    (tmp_path / "c.lg").write_text("NDIM=1, IPS=11, ICP=[10], ILP=0, ISP=1, NMX=60, DS=-0.05, "
                                   "DSMAX=0.05, UZSTOP={10: -1.0}\n")
    r = run(tmp_path / "c.lg", e="lg", sv="lg", verbose=False)
    assert r.status == "ok"
    hb = [s for s in r.specials if s.ty == "HB"]
    assert len(hb) == 1
    # located within AUTO's location tolerance EPSS (1 + sqrt(DS DSMAX)) in arclength,
    # in which PAR(10) has weight 1
    assert hb[0].par[9] == pytest.approx(0.0, abs=2e-5)
    # the period of the pair at the located point: 2 pi / Im lam, Im lam = omega to O(c^2)
    assert hb[0].par[10] == pytest.approx(period, rel=1e-8)
    header = (tmp_path / "b.lg").read_text().splitlines()
    assert any("NDIM=   2   IPS =  11" in ln for ln in header)
    assert any(ln.strip() == "0   NDIM=   1" for ln in header)


def test_wave_trains_of_a_conservative_equation(tmp_path):
    """IPS = 12 from that HB, ICP = [10, 11] (speed and wave length free): with c = 0 the
    travelling-wave equation D u'' + f(u) = 0 conserves E = D u'^2 / 2 + F(u); for any c
    dE/dz = -c u'^2, so a periodic wave has c int u'^2 = 0: every wave train has c = 0
    (to the collocation's accuracy), and near the HB its period tends to 2 pi sqrt(D/p)."""
    z, c, D = sp.symbols("z c D", real=True)
    u = sp.Function("u")
    F = sp.integrate(2 * sp.Symbol("s") * (1 - sp.Symbol("s")), (sp.Symbol("s"), 0, u(z)))
    E = D * u(z).diff(z) ** 2 / 2 + F
    # along solutions of D u'' = -c u' - f(u): dE/dz = -c u'^2
    dE = E.diff(z).subs(u(z).diff(z, 2), (-c * u(z).diff(z) - 2 * u(z) * (1 - u(z))) / D)
    assert sp.simplify(dE + c * u(z).diff(z) ** 2) == 0

    (tmp_path / "lg.py").write_text(LOGISTIC)
    (tmp_path / "c.lg").write_text("NDIM=1, IPS=11, ICP=[10], ILP=0, ISP=1, NMX=60, DS=-0.05, "
                                   "DSMAX=0.05, UZSTOP={10: -1.0}\n")
    assert run(tmp_path / "c.lg", e="lg", sv="lg", verbose=False).status == "ok"
    (tmp_path / "c.wt").write_text("NDIM=1, IPS=12, IRS='HB1', ICP=[10, 11], ILP=0, ISP=0, "
                                   "NMX=25, DS=0.02, DSMAX=0.05, NTST=30, NCOL=4\n")
    r = run(tmp_path / "c.wt", e="lg", s="lg", sv="wt", verbose=False)
    assert r.status == "ok"
    rows = r.rows
    assert len(rows) == 25
    # c = 0 on every wave train: collocation at NTST = 30, NCOL = 4 solves the energy
    # identity to ~1e-10 of the orbit's size; Newton stops at EPSU = 1e-7 relative.
    assert max(abs(row.par[9]) for row in rows) < 1e-6
    amp = [row.values[1] for row in rows]               # MAX U(1) grows from 0
    assert amp[-1] > amp[1] > 0
    assert rows[0].par[10] == pytest.approx(2 * math.pi * math.sqrt(0.5 / 2.0), rel=1e-6)
    # the period grows with the amplitude (softening: F has a cubic term), never below
    # the linear period
    assert all(row.par[10] >= rows[0].par[10] * (1 - 1e-9) for row in rows)


CHAFEE = '''
import numpy as np
def func(u, par):
    return np.array([par[0] * u[0] - u[0] ** 3])
def stpnt(u, par, t=0.0):
    par[0] = 0.0
    par[10] = np.pi       # L = PAR(11)
    par[14] = 1.0         # D = PAR(15)
    u[:] = 0.0
def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0]])
'''


def test_stationary_states_branch_points(tmp_path):
    """IPS = 17: u_t = D u_xx + p u - u^3 on [0, L] with u(0) = u(L) = 0. Along u = 0 the
    linearisation D X'' + p X = 0 has a solution with X(0) = X(L) = 0 where
    sin(sqrt(p / D) L) = 0 (sympy): p = D (k pi / L)^2, 1 and 4 with D = 1, L = pi, where
    the stationary states branch (BP)."""
    p, D, L, x = sp.symbols("p D L x", positive=True)
    w = sp.sqrt(p / D)
    basis = [sp.sin(w * x), sp.cos(w * x)]
    assert all(sp.simplify(D * b.diff(x, 2) + p * b) == 0 for b in basis)
    # X = A sin + B cos with X(0) = X(L) = 0 has A, B != 0 where the matrix is singular
    M = sp.Matrix([[b.subs(x, 0) for b in basis], [b.subs(x, L) for b in basis]])
    assert sp.simplify(M.det() + sp.sin(w * L)) == 0
    k = sp.symbols("k", positive=True, integer=True)
    p_k = sp.solve(sp.Eq(w * L, k * sp.pi), p)[0]          # sin(w L) = 0: w L = k pi
    exact = [float(p_k.subs({D: 1, L: sp.pi, k: kk})) for kk in (1, 2)]
    assert exact == [1.0, 4.0]

    (tmp_path / "ci.py").write_text(CHAFEE)
    (tmp_path / "c.ci").write_text("NDIM=1, IPS=17, ICP=[1], ILP=1, ISP=2, NTST=20, NCOL=4, "
                                   "NMX=200, DS=0.05, DSMAX=0.1, UZSTOP={1: 5.0}\n")
    r = run(tmp_path / "c.ci", e="ci", sv="ci", verbose=False)
    assert r.status == "ok"
    bps = [s.par[0] for s in r.specials if s.ty == "BP"]
    # within the location tolerance EPSS (1 + sqrt(DS DSMAX)) = 1.07e-5 in arclength
    # (PAR(1) has weight 1; the trivial branch moves in PAR(1) alone); the collocation's
    # eigenvalue error at NTST = 20, NCOL = 4 is far below it
    assert bps == pytest.approx(exact, abs=2.2e-5)
    header = (tmp_path / "b.ci").read_text()
    assert "NDIM=   2   IPS =  17" in header and "NBC =   2" in header


HEAT = '''
import numpy as np
def func(u, par):
    return np.array([par[0] * u[0]])
def stpnt(u, par, t=0.0):
    par[0] = 0.5          # a
    par[10] = np.pi       # L
    par[14] = 1.0         # D
    u[0] = np.sin(np.pi * t)
    u[1] = np.pi * np.cos(np.pi * t) / par[10]     # u_x = u_z / L
def bcnd(u0, u1, par):
    return np.array([u0[0], u1[0]])
'''


@pytest.mark.parametrize("ips", [16, 14])
def test_time_evolution_is_implicit_euler(tmp_path, ips):
    """IPS = 16 (Dirichlet, the user's BCND) on u_t = D u_xx + a u, L = pi, from
    u = sin(x): the mode sin(x) is an eigenfunction with lambda = a - D (pi / L)^2 =
    -1/2 (sympy), so each implicit Euler step of dt multiplies it by 1 / (1 - lambda dt):
    checked on every written step (the L2 norm of u is its amplitude / sqrt 2). IPS = 14
    (periodic boundary conditions) from sin(x) on [0, 2 pi] (L = 2 pi): the same mode
    with lambda = a - D = -1/2."""
    a, D, x = sp.symbols("a D x")
    mode = sp.sin(x)
    lam = sp.simplify((D * mode.diff(x, 2) + a * mode) / mode)
    lam = float(lam.subs({a: sp.Rational(1, 2), D: 1}))
    assert lam == -0.5

    src = HEAT if ips == 16 else HEAT.replace("par[10] = np.pi", "par[10] = 2 * np.pi") \
        .replace("np.sin(np.pi * t)", "np.sin(2 * np.pi * t)") \
        .replace("np.pi * np.cos(np.pi * t) / par[10]", "2 * np.pi * np.cos(2 * np.pi * t) / par[10]")
    (tmp_path / "heat.py").write_text(src)
    (tmp_path / "c.heat").write_text(f"NDIM=1, IPS={ips}, ICP=[14], NTST=20, NCOL=4, IAD=0, NMX=200, "
                                     "DS=0.01, DSMIN=1e-3, DSMAX=0.1, UZSTOP={14: 2.0}, "
                                     "EPSL=1e-8, EPSU=1e-8\n")
    r = run(tmp_path / "c.heat", e="heat", sv="heat", verbose=False)
    assert r.status == "ok"
    rows = r.rows
    assert rows[-1].par[13] == pytest.approx(2.0, abs=1e-9)
    # the L2 norm by the collocation's node quadrature (AUTO's weights): 2e-16 here
    assert rows[0].values[1] == pytest.approx(1 / math.sqrt(2), rel=1e-12)
    for prev, cur in zip(rows, rows[1:]):
        dt = cur.par[13] - prev.par[13]
        assert 0 < dt <= 0.1 * (1 + 1e-6)
        # On a fixed mesh (IAD = 0) the step is the collocation's implicit Euler step of
        # the same discretised operator: exact but for Newton's last correction (EPSU =
        # 1e-8 on a linear problem whose difference Jacobian is exact to ~1e-8: 1e-16
        # left) and rounding. (With mesh adaptation the previous profile is interpolated
        # onto the new mesh, AUTO's ADAPT: an error of order h^5 ~ 1e-8 on such a step.)
        # The first step starts from sin itself at the nodes, not the discrete operator's
        # eigenvector: sin's collocation error (3e-12 relative on 20 intervals) enters
        # there once; 1e-10 bounds both.
        assert cur.values[1] * (1 - lam * dt) == pytest.approx(prev.values[1], rel=1e-10)
    header = (tmp_path / "b.heat").read_text()
    assert "TIME" in header and "IPS =  %2d" % ips in header


CUSP = '''
import numpy as np
def func(u, par):
    return np.array([par[0] + par[1] * u[0] - u[0] ** 3])
def stpnt(u, par, t=0.0):
    par[0] = -2.0         # p
    par[1] = 1.0          # q
    par[9] = 0.3          # c
    par[14] = 2.0         # D
    u[0] = -1.5213797068045676     # the one real root of -2 + u - u^3
'''


def test_uniform_states_fold_locus(tmp_path):
    """IPS = 11, ISW = 2 from an LP: FNWS's Jacobian at (u, 0) is singular where f_u is
    (its determinant is f_u / D), so the folds of the uniform states of f = p + q u - u^3
    are the cusp's: q = 3 u^2, p = -2 u^3, i.e. 27 p^2 = 4 q^3 (sympy), whatever c and D."""
    u, p, q, c, D, lam = sp.symbols("u p q c D lam")
    f = p + q * u - u ** 3
    J = sp.Matrix([[0, 1], [-sp.diff(f, u) / D, -c / D]])
    assert sp.simplify(J.det() - sp.diff(f, u) / D) == 0
    fold = sp.solve([f, sp.diff(f, u)], [p, q], dict=True)[0]
    assert sp.simplify(27 * fold[p] ** 2 - 4 * fold[q] ** 3) == 0

    (tmp_path / "cusp.py").write_text(CUSP)
    (tmp_path / "c.cusp").write_text("NDIM=1, IPS=11, ICP=[1], ILP=1, ISP=1, NMX=200, DS=0.02, "
                                     "DSMAX=0.05, UZSTOP={1: 2.5}\n")
    r = run(tmp_path / "c.cusp", e="cusp", sv="eq", verbose=False)
    assert r.status == "ok"
    lps = [s for s in r.specials if s.ty == "LP"]
    assert len(lps) == 2
    (tmp_path / "c.lp").write_text("NDIM=1, IPS=11, ICP=[1, 2], ISW=2, ILP=0, ISP=0, NMX=30, "
                                   "DS=0.02, DSMAX=0.05, IRS='LP1'\n")
    locus = run(tmp_path / "c.lp", e="cusp", s="eq", sv="lp", verbose=False)
    assert locus.status == "ok" and len(locus.rows) == 30
    for row in locus.rows:
        pp, qq = row.par[0], row.par[1]
        # each point solved to EPSL = EPSU = 1e-7 relative
        assert 27 * pp ** 2 == pytest.approx(4 * qq ** 3, abs=1e-6 * (1 + 4 * abs(qq) ** 3))
    assert "NDIM=   5   IPS =  11" in (tmp_path / "b.lp").read_text()


def test_uniform_states_hopf_locus(tmp_path):
    """IPS = 11, ISW = 2 from the HB in the wave speed (first test): for every p > 0 the
    pair of FNWS at u = 0 crosses at c = 0 with frequency sqrt(p / D), so the Hopf locus
    in (p, c) is c = 0 with PAR(11) = 2 pi sqrt(D / p)."""
    (tmp_path / "lg.py").write_text(LOGISTIC)
    (tmp_path / "c.lg").write_text("NDIM=1, IPS=11, ICP=[10], ILP=0, ISP=1, NMX=60, DS=-0.05, "
                                   "DSMAX=0.05, UZSTOP={10: -1.0}\n")
    assert run(tmp_path / "c.lg", e="lg", sv="lg", verbose=False).status == "ok"
    (tmp_path / "c.hb").write_text("NDIM=1, IPS=11, ICP=[1, 10], ISW=2, ILP=0, ISP=0, NMX=20, "
                                   "DS=0.05, DSMAX=0.1, IRS='HB1'\n")
    r = run(tmp_path / "c.hb", e="lg", s="lg", sv="hb", verbose=False)
    assert r.status == "ok" and len(r.rows) == 20
    assert r.rows[-1].par[0] > 2.5                     # the locus moved in p
    # PT 1 is HB1 as the first run located it (a start is written as given, as AUTO-07p
    # writes it): c within that location's tolerance in arclength, EPSS (1 + sqrt|DS
    # DSMAX|) = 1.05e-5 with the default EPSS = 1e-5 (c moves at most as fast as the
    # arclength)
    assert abs(r.rows[0].par[9]) < 1e-5 * (1 + math.sqrt(0.05 * 0.05))
    for row in r.rows:
        p = row.par[0]
        # c = 0 exactly on the locus (the Newton tolerance EPSL = 1e-7 bounds it)
        if row is not r.rows[0]:
            assert abs(row.par[9]) < 1e-7
        assert row.par[10] == pytest.approx(2 * math.pi * math.sqrt(0.5 / p), rel=1e-7)


WAV = Path(__file__).parent / "data" / "auto_demos" / "wav"


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("gfortran") is None, reason="gfortran is not installed")
def test_wave_train_fold_locus(tmp_path):
    """IPS = 12, ISW = 2: the fold locus of wav's wave trains in (PAR(3), PAR(10)). Its
    generating run ends at AUTO-07p's EP (PT 5 of AUTO's b.lp, tests/data/wave_trains); continued to the speed c = -0.1 it passes
    through the fold of the wave trains computed at that speed (IPS = 11 and 12 with
    PAR(10) = -0.1, ILP = 1), an independent computation. (AUTO-07p's own restart of the
    locus ends MX at its first points.)"""
    for f in ("wav.f90", "c.wav"):
        shutil.copy(WAV / f, tmp_path)
    c = tmp_path / "c.wav"
    trains = dict(IPS=12, IRS="HB1", ICP=[3, 11], ILP=1, ISP=0, RL1=700, DS=0.1, DSMAX=1.0,
                  NMX=120, UZR={}, verbose=False)

    def first_lp(speed, sv):
        assert run(c, e="wav", IPS=11, PAR={10: speed}, sv=sv + "0", verbose=False).status == "ok"
        r = run(c, e="wav", s=sv + "0", sv=sv, **trains)
        assert r.status == "ok"
        return next(s for s in r.specials if s.ty == "LP")

    lp = first_lp(0.05, "w")
    gen = run(c, e="wav", s="w", IRS=lp.lab, IPS=12, ISW=2, ICP=[3, 10, 11], ILP=0, NMX=20,
              DS=0.1, DSMAX=0.5, UZR={}, sv="gen", verbose=False)
    assert gen.status == "ok" and [s.ty for s in gen.specials] == ["EP"]
    ep = gen.specials[0]
    (auto_ep,) = [r for r in branch_rows(Path(__file__).parent / "data" / "wave_trains" / "autoref" / "b.lp")
                  if type_name(r.ty) == "EP"]
    assert ep.pt == abs(auto_ep.pt) == 5
    # AUTO's columns: PAR(3), L2-NORM, U(1..4), PAR(10), PAR(11). Both runs end at NMX on
    # the same steps; the generating system's points converge to EPSU = 1e-6 relative
    # (c.wav), so each column agrees within that times its size.
    for got, want in ((ep.par[2], auto_ep.values[0]), (ep.values[1], auto_ep.values[1]),
                      (ep.par[10], auto_ep.values[7])):
        assert got == pytest.approx(want, rel=1e-6, abs=1e-6)
    assert "NDIM=   8   IPS =  12" in (tmp_path / "b.gen").read_text()

    locus = run(c, e="wav", s="gen", IRS=ep.lab, IPS=12, ISW=2, ICP=[3, 10, 11], ILP=0,
                NMX=60, DS=0.1, DSMAX=0.5, UZR={10: -0.1}, UZSTOP={10: -0.2}, sv="lp",
                verbose=False)
    assert locus.status == "ok"
    at = next(s for s in locus.specials if s.ty == "UZ")
    # located within EPSS (1 + sqrt(DS DSMAX)) = 1.7e-4 in the arclength (PAR(10) weight 1)
    assert at.par[9] == pytest.approx(-0.1, abs=1.7e-4)
    fold = first_lp(-0.1, "v")
    # both located to EPSS (1 + sqrt(DS DSMAX)) = 1.2e-4 (1.7e-4 for the locus) in the
    # arclength, where PAR(3) has weight 1: 3e-4 bounds their difference; the period
    # has weight 0 (THL) and is compared through its change along the family
    # (|dT/dPAR(3)| ~ 10 near the fold: 3e-3)
    assert at.par[2] == pytest.approx(fold.par[2], abs=3e-4)
    assert at.par[10] == pytest.approx(fold.par[10], abs=3e-3)


def _wav_travelling_wave_field(par):
    """wav's travelling-wave system u' = v, v' = -(c v + f(u)) / D (c = PAR(10), D = PAR(15),
    PAR(16)) with f written again from wav.f90's FUNC: (f, jac) of the 4 components
    (u1, u2, v1, v2) at the parameters par (NPAR,), the Jacobian by sympy."""
    x = sp.symbols("u1 u2 v1 v2")
    p = sp.symbols("p1:17")
    r = x[1] / (p[4] + x[1]) * x[0] / (1 + x[0] + p[5] * x[0] ** 2)
    f = (-p[0] * (p[3] * r - (p[1] - x[0])), -p[0] * (p[3] * r - p[6] * (p[2] - x[1])))
    field = sp.Matrix([x[2], x[3], -(p[9] * x[2] + f[0]) / p[14], -(p[9] * x[3] + f[1]) / p[15]])
    values, jacobian = sp.lambdify([x, p], list(field)), sp.lambdify([x, p], field.jacobian(x))
    par = [float(v) for v in par[:16]]
    return (lambda u: np.array(values(u, par), float),
            lambda u: np.array(jacobian(u, par), float))


def _real_multiplier_nearest_minus_one(mu) -> complex:
    """The real multiplier (|Im| < 1e-6) below -0.5 nearest -1 (a PD's), None if none."""
    real = [m.real for m in mu if abs(m.imag) < 1e-6 and m.real < -0.5]
    return min(real, key=lambda m: abs(m + 1.0)) if real else None


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("gfortran") is None, reason="gfortran is not installed")
def test_wave_trains_tori_and_period_doubling(tmp_path, monkeypatch):
    """wav's wave trains with ISP = 2 (tests/data/wave_trains): AUTO-07p's two TR and its
    PD, each in AUTO's order at AUTO's PAR(3) within the location tolerance and at its wave
    length; the switch at that PD (ISW = -1, the wave length doubled) and the doubled
    family's own PD likewise.

    Between the second TR and AUTO's PD we label three more PDs (PAR(3) = 641.515,
    641.564, 640.149) that AUTO-07p 0.9.2 does not. They are real: AUTO's own d.sp shows
    each crossing (PT 44 -> 45: the pair -0.499 +- 0.387i -> -1.407, stable count 4 -> 3;
    PT 48 -> 49: -2.318 -> the pair -0.497 +- 0.369i, 2 -> 3; PT 66 -> 67: the pair
    -0.587 +- 0.256i -> -1.886, 3 -> 2), but there the multiplier nearest the circle is a
    positive real one (0.984, 1.081, 1.224), where AUTO's FNSPBV is undefined. Here single
    shooting (tests/shooting.py: DOP853 at rtol 1e-12, its own Newton, nothing of the
    collocation) at 0.003 on either side of each located PAR(3) finds a real multiplier
    on each side of -1 (-0.936 / -1.059, -1.131 / -0.842, -1.016 / -0.983)."""
    data = Path(__file__).parent / "data" / "wave_trains"
    for f in ("wav.f90", "c.wav"):
        shutil.copy(WAV / f, tmp_path)
    script = (data / "sp.auto").read_text()
    # AUTO's run 4 switches at its PD1 (PAR(3) = 621.07); ours is PD4, after the three
    # PDs AUTO does not label (asserted below)
    assert 'r3("PD1")' in script
    (tmp_path / "sp.auto").write_text(script.replace('r3("PD1")', 'r3("PD4")'))
    (tmp_path / "b.sp.ref").write_bytes(gzip.decompress((data / "autoref" / "b.sp.gz").read_bytes()))
    monkeypatch.chdir(tmp_path)
    run_script("sp.auto")
    sp_rows = [r for r in branch_rows(tmp_path / "b.sp") if r.lab]
    extra = [r for r in sp_rows if type_name(r.ty) == "PD"][:-1]
    auto_sp = [r for r in branch_rows(tmp_path / "b.sp.ref") if r.lab]
    at = [type_name(r.ty) for r in auto_sp].index("PD")
    assert [type_name(r.ty) for r in sp_rows] == (
        [type_name(r.ty) for r in auto_sp[:at]] + ["PD"] * 3 + [type_name(r.ty) for r in auto_sp[at:]])
    ours_sp = [r for r in sp_rows if all(r is not e for e in extra)]
    for ours, a in ((ours_sp, auto_sp), ([r for r in branch_rows(tmp_path / "b.pd") if r.lab],
                                         [r for r in branch_rows(data / "autoref" / "b.pd") if r.lab])):
        assert [(type_name(r.ty), r.br) for r in ours] == [(type_name(r.ty), r.br) for r in a]
        for x, y in zip(a, ours):
            if type_name(x.ty) in ("EP", "MX"):
                continue
            # located within EPSS (1 + sqrt(DS DSMAX)) in arclength by each engine, PAR(3)
            # of weight 1: twice 1e-4 (1 + sqrt(0.1)) (1 + sqrt(0.05) for the switch)
            assert y.values[0] == pytest.approx(x.values[0], abs=3e-4)
            # the wave length (weight 0 in the arclength) to AUTO's printed digits where
            # it moves slowly, else through |dT/dPAR(3)| ~ 10 times the tolerance
            assert y.values[-1] == pytest.approx(x.values[-1], abs=3e-3)

    records = {r.lab: r for r in read_s(tmp_path / "s.sp")}
    step = 0.003    # ten location tolerances in PAR(3); the nearest fold is 0.04 away
    for row in extra:
        rec = records[row.lab]
        found = {}
        for side in (-1, 0, 1):
            par = np.array(rec.par, float)
            par[2] += side * step
            f, jac = _wav_travelling_wave_field(par)
            found[side] = _real_multiplier_nearest_minus_one(
                shooting.multipliers(f, jac, rec.u[0, :4], rec.par[10]))
        assert None not in found.values()
        # a real multiplier crosses -1 between the two sides
        assert (abs(found[-1]) - 1.0) * (abs(found[1]) - 1.0) < 0
        # at the located PAR(3), within its 3e-4, mu is -1 within that times d mu / d PAR(3)
        slope = abs(found[1] - found[-1]) / (2 * step)
        assert abs(found[0] + 1.0) <= 3e-4 * slope
