"""Periodic orbits (IPS = 2, washer.cont.systems.periodic) against closed forms and
AUTO-07p's own periodic solutions.

The closed-form system is a "lambda-omega" oscillator with a non-uniform phase speed:

    r' = r (mu - r^2),   theta' = omega + b r^2 + c r cos(theta)

(in Cartesian x = r cos theta, y = r sin theta). Its orbit is the circle r = sqrt(mu);
the period is int_0^2pi dtheta / (w + c sqrt(mu) cos theta) = 2 pi / sqrt(w^2 - c^2 mu),
w = omega + b mu; the monodromy is triangular in (r, theta) with diagonal
exp(-2 mu T) (radial: d/dr r (mu - r^2) = -2 mu on the orbit) and 1 (the phase), so
the multipliers are {1, exp(-2 mu T)}. A Hopf point at mu = 0 with frequency omega.

Some branches here are computed by a small driver of this file (`_branch`: AUTO's plane
pseudo-arclength with Newton-chord and the secant direction of CONTBV, mesh adaptation
every IAD steps) that uses only the system's contract (residual, jacobian, factor,
border, inner, update) and `remesh`: an independent check of the system against the
engine's iterator, which the other tests use through washer.run.
"""
import gzip
import importlib.util
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from washer.auto.files import read_s, record_text
from washer.cont.branch import Record
from washer.cont.iterator import Continuation
from washer.cont import collocation as col
from washer.cont.codes import Code
from washer.cont.problem import Problem
from washer.cont.settings import Settings
from washer.cont.system import StartData
from washer.cont.systems.periodic import PeriodicOrbits

DATA = Path(__file__).parent / "data"
RECORDS = DATA / "auto_reference" / "records"
DEMOS = DATA / "auto_demos"


# ------------------------------------------------------------------ the closed-form system

def lw(u, par):
    x, y = u[0], u[1]
    mu, om, b, c = par[0], par[1], par[2], par[3]
    r2 = x * x + y * y
    th = om + b * r2 + c * x
    return np.array([x * (mu - r2) - y * th, y * (mu - r2) + x * th])


LW = Problem(2, lw, name="lw")
LW_PAR = (1.0, 0.5, 0.8)          # omega, b, c


def lw_period(par) -> float:
    mu, om, b, c = par[:4]
    return 2 * math.pi / math.sqrt((om + b * mu) ** 2 - c * c * mu)


def settings(ndim=2, icp=(1, 11), ntst=20, ncol=4, **kw) -> Settings:
    return Settings(IPS=2, ICP=icp, NDIM=ndim, NPAR=12, NTST=ntst, NCOL=ncol, THL={11: 0.0}, **kw)


def lw_system(mu, ntst, ncol, **kw):
    """The orbit at mu from a deliberately wrong guess: uniform phase on the exact
    circle, period 5 % off."""
    par = np.r_[mu, LW_PAR, np.zeros(8)]
    par[10] = 1.05 * lw_period(par)
    mesh = col.Mesh.uniform(ntst, ncol)
    t = mesh.node_times()
    U = math.sqrt(mu) * np.c_[np.cos(2 * np.pi * t), np.sin(2 * np.pi * t)]
    rec = SimpleNamespace(U=U, t=t, ntst=ntst, ncol=ncol, par=par, icp=[1, 11], rldot=[],
                          udot=None)
    return PeriodicOrbits(StartData(LW, settings(ntst=ntst, ncol=ncol, **kw), U[0], par, rec))


def newton_fixed(sysm, x, slot=-1, tol=1e-10, maxit=25):
    """Newton on [G(x); x[slot] = fixed] (slot -1: PAR(ICP(1)), -2: the period)."""
    e = np.zeros(len(x))
    e[slot] = 1.0
    fixed = x[slot]
    for it in range(1, maxit + 1):
        G = sysm.residual(x)
        dx = sysm.factor(sysm.jacobian(x), e).solve(-np.r_[G, x[slot] - fixed])
        x = x + dx
        if np.max(np.abs(dx)) <= tol * (1 + np.max(np.abs(x))):
            return x, it
    raise AssertionError(f"Newton did not converge in {maxit} iterations")


def _branch(sysm, n, ds, dsmax=0.5):
    """The unknowns of the start and n further points of the shipped iterator
    (washer.cont.iterator.Continuation: predictor, Newton-chord corrector, AUTO's step
    control, mesh adaptation through the system's wants_remesh/remesh) from the system's
    start, with DS = ds and DSMAX = dsmax."""
    it = Continuation(sysm, sysm.settings.with_(DS=ds, DSMAX=dsmax, DSMIN=1e-6))
    pts = []
    for step in it:
        if step.kind == "failed":
            raise AssertionError(step.text)
        if step.point is not None and step.kind != "note":
            pts.append(step.point.x.copy())
        if len(pts) > n:
            return pts
    raise AssertionError("the branch ended early")


# ------------------------------------------------------------------ closed form

def test_orbit_period_and_multipliers_of_the_closed_form_system():
    """mu = 0.25, NTST 20, NCOL 4 from a 5 %-off guess: the period to 1e-8 (the
    superconvergent error is 2e-9 here), the circle radius at every node to 1e-6 (the
    nodes inside intervals only converge as h^(NCOL+1)), the nontrivial multiplier
    exp(-2 mu T) = 0.0504 to 1e-8 and the trivial one to 1e-9."""
    sysm = lw_system(0.25, 20, 4)
    x, it = newton_fixed(sysm, sysm.start()[0])
    U, par = sysm.unpack(x)
    T = lw_period(par)
    assert abs(par[10] - T) < 1e-8
    assert np.max(np.abs(np.hypot(U[:, 0], U[:, 1]) - 0.5)) < 1e-6
    st = sysm.stability(x)
    assert st.kind == "multipliers" and not st.notes
    assert abs(st.values[0] - 1) < 1e-9
    assert abs(st.values[1] - math.exp(-2 * 0.25 * T)) < 1e-8
    assert st.n_stable == 2 and st.stable


@pytest.mark.parametrize("ncol", [2, 3, 4])
def test_period_converges_at_the_superconvergent_rate(ncol):
    """Collocation at Gauss points is superconvergent at the mesh points, O(h^(2 NCOL)),
    and so is the period. Measured orders (NTST 8 -> 16 -> 32): 3.91/3.98, 5.88/5.97,
    7.86/7.96 for NCOL 2, 3, 4; asserted: the last ratio within 0.25 of 2 NCOL (the
    pre-asymptotic drift is 0.1 at NTST = 8)."""
    errs = []
    for ntst in (8, 16, 32):
        sysm = lw_system(0.25, ntst, ncol)
        x, _ = newton_fixed(sysm, sysm.start()[0], tol=1e-13)
        errs.append(abs(x[-2] - lw_period(sysm.params(x))))
    orders = [math.log2(errs[i] / errs[i + 1]) for i in range(2)]
    assert abs(orders[-1] - 2 * ncol) < 0.25, (errs, orders)
    assert orders[0] > 2 * ncol - 0.5


def test_start_from_a_hopf_point_follows_the_closed_form_family():
    """STHOPF at mu = 0: the direction is sin(2 pi t) Re phi + cos(2 pi t) Im phi of
    the eigenvector, with no parameter motion; the branch then has mu = r^2 and the
    closed-form period at every point (1e-8), with mesh adaptation every 3 steps."""
    par = np.r_[0.0, LW_PAR, np.zeros(8)]
    par[10] = 2 * math.pi                     # PAR(11) at the HB: 2 pi / omega
    sysm = PeriodicOrbits(StartData(LW, settings(), np.zeros(2), par, None, "HB"))
    x0, t0 = sysm.start()
    assert t0[-1] == 0 and t0[-2] == 0 and abs(sysm.inner(t0, t0) - 1) < 1e-12
    V = sysm.coll.profile(t0)
    # the eigenvector of [[0, -1], [1, 0]] turns the direction into a rotation: |V(t)|
    # is constant, and V(t) . V(t + 1/4) = 0
    assert np.ptp(np.hypot(V[:, 0], V[:, 1])) < 1e-12
    quarter = col.evaluate(sysm.mesh, V, (sysm.mesh.node_times() + 0.25) % 1.0)
    assert np.max(np.abs(np.sum(V * quarter, axis=1))) < 1e-3 * np.max(V ** 2)
    pts = _branch(sysm, 12, 0.05)
    mus = []
    for x in pts[1:]:
        U = x[:-2].reshape(-1, 2)
        p = sysm.params(x)
        r2 = np.mean(U[:, 0] ** 2 + U[:, 1] ** 2)
        assert abs(r2 - p[0]) < 1e-6 * max(p[0], 1e-3)
        assert abs(p[10] - lw_period(p)) < 1e-8
        mus.append(p[0])
    assert mus[0] > 0 and np.all(np.diff(mus) > 0) and mus[-1] > 0.2


# ------------------------------------------------------------------ AUTO-07p's solutions

def _load(name, ndim):
    path = DATA / name / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"eq_{name}", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return Problem(ndim, mod.func, name=name)


def chu(u, par):
    """AUTO demo chu (chu.f90): Chua's circuit with the smooth nonlinearity."""
    alpha, beta, rk, a0, a1 = par[:5]
    ab = lambda x: 2 * x * np.arctan(rk * x) / np.pi
    h = lambda x: a1 * x + 0.5 * (a0 - a1) * (ab(x + 1) - ab(x - 1))
    x, y, z = u[0], u[1], u[2]
    return np.array([alpha * (y - h(x)), x - y + z, -beta * y])


def plp(u, par):
    """AUTO demo plp (plp.f90)."""
    s, a = u[0], u[1]
    s0, a0, al, rh, rk = par[:5]
    r = s * a / (1 + s + rk * s ** 2)
    return np.array([(s0 - s) - rh * r, al * (a0 - a) - rh * r])


def _problem(name):
    if name == "chu":
        return Problem(3, chu, name="chu")
    if name == "plp":
        return Problem(2, plp, name="plp")
    return _load(name, {"lrz": 3, "ab": 2}[name])


#: (demo, label, ICP, fixed slot): the principal parameter is fixed (-1) except where
#: the orbit is a fold in it (plp's LP) or the period is ill-conditioned in it
#: (lrz label 20: period 34 near the homoclinic orbit, where rho is flat to 1e-5):
#: there the period is fixed (-2) and PAR(ICP(1)) compared instead.
AUTO_ORBITS = [("lrz", 8, (1, 11), -1), ("lrz", 14, (1, 11), -1), ("lrz", 20, (1, 11), -2),
               ("ab", 18, (1, 11), -1), ("ab", 19, (1, 11), -1), ("chu", 8, (1, 11), -1),
               ("chu", 9, (1, 11), -1), ("plp", 5, (4, 11), -2), ("plp", 6, (4, 11), -1)]


def _auto_system(demo, lab, icp, **kw):
    rec = next(r for r in read_s(RECORDS / f"s.{demo}") if r.lab == lab and r.U.ndim == 2)
    s = settings(ndim=rec.U.shape[1], icp=icp, ntst=kw.pop("ntst", rec.ntst),
                 ncol=kw.pop("ncol", rec.ncol), **kw)
    return PeriodicOrbits(StartData(_problem(demo), s, rec.U[0], rec.par, rec)), rec


@pytest.mark.parametrize("demo,lab,icp,slot", AUTO_ORBITS)
def test_restart_from_autos_periodic_records(demo, lab, icp, slot):
    """AUTO-07p's s-records read (t column, NTST, NCOL) and Newton-converged with
    AUTO's own NTST/NCOL: the same orbit. The free quantity (period, or PAR(ICP(1))
    where the period is fixed) agrees to 1e-6 relative, the profile to 1e-5 of the
    orbit's amplitude (AUTO writes 11 digits and converges to EPSU = 1e-7)."""
    sysm, rec = _auto_system(demo, lab, icp)
    x0 = sysm.start()[0]
    np.testing.assert_allclose(sysm.mesh.node_times(), rec.t, rtol=0, atol=1e-10)  # 11 digits
    assert np.max(np.abs(sysm.residual(x0))) < 1e-6          # AUTO's solution solves ours
    x, _ = newton_fixed(sysm, x0, slot=slot)
    U = sysm.coll.profile(x)
    amp = np.max(np.ptp(rec.U, axis=0))
    assert np.max(np.abs(U - rec.U)) < 1e-5 * amp
    free = icp[0] if slot == -2 else 11
    other = x[-1] if slot == -2 else x[-2]
    assert abs(other - rec.par[free - 1]) < 1e-6 * abs(rec.par[free - 1])


@pytest.mark.parametrize("demo,lab,expect", [
    # AUTO's d-files: lrz PT 2 (label 8) and PT 14 (label 14), chu PT 30 (PD, label 8)
    ("lrz", 8, [1.0, 1.00042, 1.32699e-4]),
    ("lrz", 14, [1.0, 1.30200, 8.49175e-6]),
    ("chu", 8, [1.0, -1.0, -1.33946e-2]),
])
def test_multipliers_agree_with_autos_d_file(demo, lab, expect):
    """Floquet multipliers at AUTO's solutions against those AUTO printed (6 digits).
    Multipliers near the unit circle agree to the printed precision (6e-6 relative);
    the strongly contracting ones to 5 %: AUTO takes P0, P1 from the chord Jacobian of
    its last full-Newton iteration, and e.g. chu's -1.33946e-2 differs in the 5th digit
    from the mesh-converged -1.33941e-2 (ours at NTST 25, 50 and 100)."""
    sysm, rec = _auto_system(demo, lab, (1, 11))
    x, _ = newton_fixed(sysm, sysm.start()[0])
    mu = sysm.stability(x).values
    for m_auto in expect:
        k = np.argmin(np.abs(mu - m_auto))
        tol = 0.05 * abs(m_auto) if abs(m_auto) < 0.1 else 6e-6 * abs(m_auto)
        assert abs(mu[k] - m_auto) < tol, (mu, expect)


def test_pd_test_function_changes_sign_across_chu_period_doubling():
    """chu's orbit on both sides of AUTO's PD (label 8, PAR(1) = 8.1959951): the PD test
    |mu_2| - 1 changes sign, TPSPBV classifies the multiplier as PD (real, < -0.5), the
    stable count changes (AUTO's acceptance rule); the test value at AUTO's point is
    AUTO's printed 'SPB Function -3.40228E-07' to 1 %, and the zero (bisection on the
    parameter, NTST 25 as AUTO) is AUTO's PAR(1) to 1e-6 (measured 2e-7)."""
    from scipy.optimize import brentq
    sysm, rec = _auto_system("chu", 8, (1, 11), ISP=2)
    x, _ = newton_fixed(sysm, sysm.start()[0])

    def at(p):
        y = x.copy()
        y[-1] = p
        y, _ = newton_fixed(sysm, y)
        st = sysm.stability(y)
        return sysm.test_functions(y, None, None, st, None, [Code.PD])[Code.PD], st

    (q0, s0), (q1, s1) = at(rec.par[0] - 0.02), at(rec.par[0] + 0.02)
    assert q0 is not None and q1 is not None and q0 * q1 < 0
    assert sysm.accept(Code.PD, SimpleNamespace(stability=s0), SimpleNamespace(stability=s1))
    q_auto, _ = at(rec.par[0])
    assert abs(q_auto - (-3.40228e-07)) < 0.01 * 3.40228e-07
    p_pd = brentq(lambda p: at(p)[0], rec.par[0] - 0.02, rec.par[0] + 0.02, xtol=1e-10)
    assert abs(p_pd - rec.par[0]) < 1e-6


def test_pd_tr_never_reported_for_planar_systems():
    sysm = lw_system(0.25, 10, 4, ISP=2)
    assert Code.PD not in sysm.active_tests() and Code.TR not in sysm.active_tests()
    x, _ = newton_fixed(sysm, sysm.start()[0])
    st = sysm.stability(x)
    assert not sysm.accept(Code.PD, SimpleNamespace(stability=st), SimpleNamespace(stability=st))


def test_period_doubling_switch_starts_the_doubled_branch():
    """ISW = -1 at chu's PD (AUTO's PDBLE + STDRBV): the period doubles, the direction
    is a null vector of the doubled system orthogonal to the old direction, and the
    first steps leave the twice-traversed orbit (u(t) != u(t + 1/2)) with the period
    near twice AUTO's 2.28355."""
    rec = next(r for r in read_s(RECORDS / "s.chu") if r.lab == 8)
    s = settings(ndim=3, ntst=50, ncol=4, ISW=-1, IAD=0)
    sysm = PeriodicOrbits(StartData(_problem("chu"), s, rec.U[0], rec.par, rec, "PD"))
    x0, t0 = sysm.start()
    assert abs(x0[-2] - 2 * rec.par[10]) < 1e-12
    assert abs(sysm.inner(t0, sysm.start()[1]) - 1) < 1e-12
    assert np.max(np.abs(sysm.residual(x0))) < 1e-5
    pts = _branch(sysm, 4, 0.01)
    U = sysm.coll.profile(pts[-1])
    half = col.evaluate(sysm.mesh, U, (sysm.mesh.node_times() + 0.5) % 1.0)
    amp = np.max(np.ptp(U, axis=0))
    assert np.max(np.abs(U - half)) > 1e-3 * amp
    assert abs(pts[-1][-2] / (2 * rec.par[10]) - 1) < 0.05


# ------------------------------------------------------------------ files

def test_autos_periodic_record_round_trips_byte_for_byte():
    """An AUTO-07p periodic record (lrz label 8: NTPL 141, direction stored) read and
    written again by record_text is the same text."""
    lines = gzip.decompress((RECORDS / "s.lrz.gz").read_bytes()).decode().splitlines(True)
    i = 0
    while True:
        h = lines[i].split()
        if int(h[3]) == 8:
            original = "".join(lines[i:i + 1 + int(h[8])])
            break
        i += 1 + int(h[8])
    rec = next(r for r in read_s(RECORDS / "s.lrz") if r.lab == 8)
    assert rec.U.shape == (141, 3) and rec.ntst == 35 and rec.ncol == 4
    assert rec.t[0] == 0 and rec.t[-1] == 1 and len(rec.t) == 141
    assert record_text(rec) == original


def test_our_solution_written_and_read_back(tmp_path):
    sysm = lw_system(0.25, 10, 3)
    x, _ = newton_fixed(sysm, sysm.start()[0])
    t = np.zeros(len(x))
    t[-1] = 1.0
    sol = sysm.solution(x, t)
    assert sol.u.shape == (31, 2) and sol.ntst == 10 and sol.ncol == 3
    assert abs(sol.par[10] - lw_period(sol.par)) < 5e-5        # O(h^6): 2e-5 at NTST 10
    assert abs(sol.columns[0] - 0.5) < 5e-5                     # L2 norm of a circle: r
    assert abs(sol.columns[1] - 0.5) < 1e-3 and abs(sol.columns[2] - 0.5) < 1e-3
    assert sysm.column_titles() == ["L2-NORM", "MAX U(1)", "MAX U(2)"]
    rec = Record(1, 5, -4, 3, 2, 1, 2, 2, sol.u, sol.par, [1, 11], sol.rldot, sol.udot,
                 t=sol.t, ntst=sol.ntst, ncol=sol.ncol)
    path = tmp_path / "s.lw"
    path.write_text(record_text(rec))
    back = read_s(path)[0]
    np.testing.assert_allclose(back.U, sol.u, rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(back.t, sol.t, rtol=1e-10, atol=1e-14)
    assert (back.ntst, back.ncol, back.icp, back.lab) == (10, 3, [1, 11], 3)
    restarted = PeriodicOrbits(StartData(LW, settings(ntst=10, ncol=3), back.U[0], back.par,
                                         back))
    assert np.max(np.abs(restarted.residual(restarted.start()[0]))) < 1e-9


def test_restart_on_another_mesh_interpolates_the_orbit():
    """AUTO's ADAPT2: a record of NTST 35 restarted with NTST 50, NCOL 5 (NEWMSH +
    INTERP), then Newton: the period agrees with AUTO's to 1e-8 relative."""
    sysm, rec = _auto_system("lrz", 14, (1, 11), ntst=50, ncol=5)
    assert sysm.mesh.ntst == 50 and sysm.mesh.ncol == 5
    x, _ = newton_fixed(sysm, sysm.start()[0])
    assert abs(x[-2] / rec.par[10] - 1) < 1e-8


def test_mesh_adaptation_keeps_the_orbit_and_concentrates_points():
    """ab's UZ orbit (label 19): adapting the mesh then re-converging changes the
    period by less than 1e-7 (both meshes resolve it), and the new mesh's smallest
    interval is well below the uniform 1/70."""
    sysm, rec = _auto_system("ab", 19, (1, 11))
    x, _ = newton_fixed(sysm, sysm.start()[0])
    (y,) = sysm.remesh(x)
    y, _ = newton_fixed(sysm, y)
    assert abs(y[-2] - x[-2]) < 1e-7 * x[-2]
    assert np.min(sysm.mesh.dtm) < 0.5 / 70


# ------------------------------------------------------------------ BP of cycles

def pf(u, par):
    """A pitchfork of cycles in closed form: the planar oscillator r' = r (mu - r^2),
    theta' = omega with a transverse z' = z (r^2 - a) - z^3. On the orbit r = sqrt(mu),
    z = 0 the z-multiplier is exp((mu - a) T): a BP of cycles at mu = a, where the
    orbits z^2 = mu - a (period 2 pi / omega) branch off."""
    x, y, z = u[0], u[1], u[2]
    mu, om, a = par[0], par[1], par[2]
    r2 = x * x + y * y
    return np.array([x * (mu - r2) - om * y, y * (mu - r2) + om * x, z * (r2 - a) - z ** 3])


def test_bp_of_cycles_located_and_switched():
    """The iterator (washer.cont.iterator) locates the BP test's zero at mu = a = 0.7
    (1e-6: EPSS-based location), `directions` gives the transverse direction (pure z,
    no parameter motion) and the switched branch has z^2 = mu - a (discretisation
    error 3e-8 at NTST 10) and the period 2 pi."""
    from washer.cont.iterator import Continuation
    P = Problem(3, pf, name="pf")
    par = np.r_[0.5, 1.0, 0.7, np.zeros(9)]
    par[10] = 2 * math.pi
    mesh = col.Mesh.uniform(10, 4)
    t = mesh.node_times()
    U = np.c_[math.sqrt(0.5) * np.cos(2 * np.pi * t), math.sqrt(0.5) * np.sin(2 * np.pi * t),
              0 * t]
    rec = SimpleNamespace(U=U, t=t, ntst=10, ncol=4, par=par, icp=[1, 11], rldot=[], udot=None)
    s = settings(ndim=3, ntst=10, ncol=4, ISP=2, DS=0.05, DSMAX=0.1)
    sysm = PeriodicOrbits(StartData(P, s, U[0], par, rec))
    bp = None
    for k, step in enumerate(Continuation(sysm, s, mode="restart")):
        if step.kind == "special":
            bp = step
            break
        assert k < 20, "no BP of cycles found"
    assert bp.code == Code.BPC
    assert abs(bp.point.x[-1] - 0.7) < 1e-6
    (d,) = sysm.directions(bp.point.x, bp.point.tangent, Code.BPC)
    D = sysm.coll.profile(d)
    assert np.max(np.abs(D[:, :2])) < 1e-10 and np.max(np.abs(d[-2:])) < 1e-10
    new = []
    for step in Continuation(sysm, s, x0=bp.point.x.copy(), tangent=d, mode="switch"):
        if step.point is not None:
            new.append(step.point.x.copy())
        if len(new) == 6:
            break
    for x in new[1:]:
        U2, p2 = sysm.coll.profile(x), sysm.params(x)
        assert p2[0] > 0.7
        assert np.max(np.abs(U2[:, 2] ** 2 - (p2[0] - 0.7))) < 1e-7
        assert abs(p2[10] - 2 * math.pi) < 1e-7


# ------------------------------------------------------------------ plots

def test_plot_cli_draws_periodic_branches_and_an_orbit(tmp_path):
    """python -m washer.plots on AUTO's b.lrz (equilibria and both periodic families) with
    a periodic b-file beside it, and on an s-file label (time profile + phase
    portrait); wrong uses exit with 2."""
    import shutil
    from washer.plots.__main__ import main as plot_main
    ref = DEMOS / "lrz" / "autoref" / "b.lrz"
    shutil.copy(ref, tmp_path / "b.lrz")
    shutil.copy(RECORDS / "s.lrz.gz", tmp_path / "s.lrz.gz")
    assert plot_main([str(tmp_path / "b.lrz"), "--y", "1"]) == 0
    assert (tmp_path / "b_lrz_diagram.png").stat().st_size > 10000
    assert plot_main([str(tmp_path / "s.lrz"), "--label", "14", "--phase", "1", "3"]) == 0
    assert (tmp_path / "s_lrz_orbit14.png").stat().st_size > 10000
    assert plot_main([str(tmp_path / "s.lrz"), "--label", "4"]) == 2      # an HB: NTPL = 1
    assert plot_main([str(tmp_path / "s.lrz"), "--label", "99"]) == 2
    assert plot_main([str(tmp_path / "s.lrz")]) == 2                      # no --label


def test_isw_minus_one_restart_at_a_stored_bp_of_cycles():
    """The BP of the closed-form pitchfork written as an s-record (with its direction),
    restarted with ISW = -1 (AUTO's STDRBV, IPERP = 1): the start direction is the
    transverse one (pure z), and Newton on the plane leaves along z^2 = mu - a."""
    from washer.cont.iterator import Continuation
    P = Problem(3, pf, name="pf")
    par = np.r_[0.7, 1.0, 0.7, np.zeros(9)]
    par[10] = 2 * math.pi
    mesh = col.Mesh.uniform(10, 4)
    t = mesh.node_times()
    r = math.sqrt(0.7)
    U = np.c_[r * np.cos(2 * np.pi * t), r * np.sin(2 * np.pi * t), 0 * t]
    # the old branch's direction at the BP: d/dmu of (r cos, r sin, 0), normalised later
    ud = np.c_[np.cos(2 * np.pi * t), np.sin(2 * np.pi * t), 0 * t] / (2 * r)
    rec = Record(1, 5, 6, 2, 2, 1, 3, 2, U, par, [1, 11], [1.0, 0.0], ud, t=t, ntst=10, ncol=4)
    s = settings(ndim=3, ntst=10, ncol=4, ISW=-1, ISP=2, DS=0.02, DSMAX=0.05)
    sysm = PeriodicOrbits(StartData(P, s, U[0], par, rec, "BP"))
    x0, t0 = sysm.start()
    D = sysm.coll.profile(t0)
    assert np.max(np.abs(D[:, :2])) < 1e-8 and np.max(np.abs(D[:, 2])) > 0.5
    pts = [step.point.x.copy() for step, _ in
           zip(Continuation(sysm, s, x0=x0, tangent=t0, mode="switch"), range(4), strict=False)]
    U3, p3 = sysm.coll.profile(pts[-1]), sysm.params(pts[-1])
    assert p3[0] > 0.7 and np.max(np.abs(U3[:, 2] ** 2 - (p3[0] - 0.7))) < 1e-7


@pytest.mark.parametrize("lab,row", [
    # b.lrz rows of PT 2 (label 8) and PT 14 (label 14): L2-NORM, MAX x, MAX y, MAX z
    (8, [2.6254973901e+01, 8.2407803772e+00, 8.3540232495e+00, 2.4232463333e+01]),
    (14, [2.1019335168e+01, 1.1940944736e+01, 1.4073817927e+01, 2.7637967017e+01]),
])
def test_b_file_columns_of_autos_orbits(lab, row):
    """Our b-file columns (RNRMSQ's L2 norm with the WINT weights, RMXUPS's maxima over
    the nodes) of AUTO's stored orbits are AUTO's own, to the 11 digits it writes."""
    sysm, rec = _auto_system("lrz", lab, (1, 11))
    sol = sysm.solution(sysm.start()[0], None)
    np.testing.assert_allclose(sol.columns, row, rtol=1e-10)


def test_period_doubling_switch_through_the_runner(tmp_path):
    """chu's c.chu.3 unchanged (ISW = -1, NTST 80) restarted at AUTO's own PD record:
    the doubled branch starts at twice AUTO's period, and locates the next period
    doubling of the cascade; NTST 160 puts it at the same PAR(1) to 1e-5 (the
    collocation error is below that, so the location is the discrete problem's)."""
    import shutil
    from washer.run import run
    ref = DEMOS / "chu"
    shutil.copy(ref / "c.chu.3", tmp_path)
    shutil.copy(DATA / "chu" / "chu.py", tmp_path)
    shutil.copy(RECORDS / "s.chu.gz", tmp_path / "s.ref.gz")
    T_pd = next(r for r in read_s(RECORDS / "s.chu") if r.lab == 8).par[10]    # 2.2835478
    found = []
    for ntst in (80, 160):
        res = run(tmp_path / "c.chu.3", verbose=False, e="chu", s="ref", sv=f"pd{ntst}",
                  NMX=25, NTST=ntst)
        assert res.status == "ok"
        first = res.rows[0]
        assert abs(first.par[10] / (2 * T_pd) - 1) < 1e-9
        pds = [r for r in res.rows if r.ty == "PD"]
        assert len(pds) == 1
        found.append(pds[0].par[0])
    assert 8.40 < found[0] < 8.43
    assert abs(found[0] - found[1]) < 1e-5 * found[0]


# ------------------------------------------------------------------ fold of cycles locus

@pytest.mark.parametrize("direction,expect", [
    # AUTO's b.loci, cycle-fold branch: UZ rows (PAR(4), PAR(1), PERIOD)
    (1, [(2.9862945702, 111.0, 9.3909938218), (4.7221259912, 111.0, 6.0871698212),
         (5.2433220475, 109.0, 5.3531517159)]),
    (-1, [(2.5826424510, 109.0, 10.539411298)]),
])
def test_cycle_fold_locus_reproduces_autos_plp_loci(direction, expect):
    """ISW = 2 from plp's LP of cycles (label 5; AUTO's FNPL/BCPL/ICPL extended BVP) with
    c.plp.plp's settings (ICP = [4, 1, 11], UZR PAR(1) = 111, UZSTOP 109), in AUTO's two
    stages: the generating run (5 steps, PAR(1) fixed, the normalisation free: the orbit
    and both parameters stay at the fold), then the locus from its end point, each way:
    the UZ points of AUTO's b.loci, PAR(4) and PERIOD to 1e-7 relative (measured 3e-8;
    AUTO locates UZ to EPSS = 1e-6), PAR(1) (the UZ value itself) to the location
    tolerance EPSS (1 + sqrt(|DS DSMAX|)) = 1.5e-6: PAR(1) has weight 1 in the unit
    tangent, so it is within that of the exact zero (measured 1e-8)."""
    from washer.cont.iterator import Continuation
    from washer.cont.systems.cycle_fold import CycleFoldLocus
    spec = importlib.util.spec_from_file_location("plp_eq", DATA / "plp" / "plp.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    P = Problem(2, mod.func, dfdu=mod.dfdu, dfdp=mod.dfdp, name="plp", jac=1)
    rec = next(r for r in read_s(RECORDS / "s.plp") if r.lab == 5)
    s = Settings(IPS=2, ISW=2, ICP=(4, 1, 11), NDIM=2, NPAR=12, NTST=20, NCOL=4, IAD=3, ILP=1,
                 ISP=1, DS=direction * 0.1 * (1 + 1e-7), DSMIN=1e-4, DSMAX=3.0, ITNW=7,
                 NWTN=3, EPSL=1e-7, EPSU=1e-7, EPSS=1e-6, JAC=1,
                 UZR=((1, 111.0, False), (1, 109.0, True)))
    gen = CycleFoldLocus(StartData(P, s, rec.U[0], rec.par, rec, "LP"))
    g = gen.run_settings
    assert (g.NMX, g.ILP, g.ISP) == (5, 0, 0)
    points = []
    for step in Continuation(gen, g):
        assert step.kind not in ("failed", "special")
        if step.point is not None and step.kind != "note":
            points.append(step.point)
        if len(points) == g.NMX:
            break
    end = points[-1]
    for pt in points:                  # the generating run moves only v's normalisation
        p = gen.params(pt.x)
        assert abs(p[3] - rec.par[3]) < 1e-7 * rec.par[3] and p[0] == rec.par[0]
    sol = gen.solution(end.x, end.tangent)
    ep = Record(br=4, pt=5, code=59, lab=9, nfpr=len(gen.free), isw=-2, ndim_user=2, ips=2,
                u=np.asarray(sol.u), par=np.asarray(sol.par), icp=list(gen.free),
                rldot=list(sol.rldot)[:len(gen.free)], udot=sol.udot, t=sol.t, ntst=sol.ntst,
                ncol=sol.ncol)
    sysm = CycleFoldLocus(StartData(P, s, ep.U[0], ep.par, ep, "LPC-curve"))
    found = []
    for k, step in enumerate(Continuation(sysm, s, mode="restart")):
        assert step.kind != "failed" and k < 200
        if step.kind == "special":
            p = sysm.params(step.point.x)
            found.append((p[3], p[0], p[10]))
            if step.key == ("UZ", 1):                    # UZSTOP
                break
    assert len(found) == len(expect)
    for (p4, p1, T), (a4, a1, aT) in zip(found, expect, strict=True):
        assert abs(p4 / a4 - 1) < 1e-7 and abs(T / aT - 1) < 1e-7
        assert abs(p1 - a1) < s.EPSS * (1 + math.sqrt(abs(s.DS * s.DSMAX)))


# ------------------------------------------------------------------ the washer's whirl

@pytest.mark.slow
def test_washer_whirl_at_cp0_is_the_simulated_limit_cycle(tmp_path):
    """auto_constants/c.washer.po: the periodic orbits born at the averaged frame's Hopf
    point (C_p = 0.101) reach C_p = 0 (UZSTOP), all stable (the Hopf is supercritical).
    The orbit there is the limit cycle a long simulation of the same averaged rotating-
    frame system settles on (from eps3 = 0.408 m at rest, 60-70 s): the rotating-frame
    radius sqrt(eps1^2 + eps2^2) and the height eps3 over the cycle agree to 1e-3 of
    their values (measured 2.5e-4: NTST 30 collocation against DOPRI5 samples at
    2 kHz)."""
    import shutil
    from washer.cont import collocation as colm
    from washer.machine.model import Model
    from washer.machine.params import load_params
    from washer.run import run
    from washer.machine.responses import simulate
    root = Path(__file__).parent.parent / "auto_constants"
    for f in ("c.washer", "c.washer.po"):
        shutil.copy(root / f, tmp_path)
    assert run(tmp_path / "c.washer", verbose=False).status == "ok"
    res = run(tmp_path / "c.washer.po", verbose=False)
    assert res.status == "ok"
    assert all(r.stable for r in res.rows)
    end = res.rows[-1]
    assert end.ty == "UZ" and abs(end.par[0]) < 1e-9
    rec = next(r for r in read_s(tmp_path / "s.washer.po") if r.lab == end.lab)
    mesh = colm.Mesh(np.asarray(rec.t)[::rec.ncol].copy(), rec.ncol)
    U = colm.evaluate(mesh, rec.U, np.linspace(0, 1, 20001))
    orbit_r, orbit_z = np.hypot(U[:, 0], U[:, 1]), U[:, 2]
    sim = simulate(Model(load_params().replace(C_p=0.0)), 70.0, system="rotating",
                   frame="averaged", samples_per_s=2000.0, progress=False)
    late = sim.t >= 60
    sim_r, sim_z = np.hypot(sim.y[late, 0], sim.y[late, 1]), sim.y[late, 2]
    for a, b in ((orbit_r.min(), sim_r.min()), (orbit_r.max(), sim_r.max()),
                 (orbit_z.min(), sim_z.min()), (orbit_z.max(), sim_z.max())):
        assert abs(a - b) < 1e-3 * abs(b), (a, b)


# ------------------------------------------------------------------ torus bifurcation

def tr(u, par):
    """A torus bifurcation of cycles in closed form: the oscillator r' = r (mu - r^2),
    theta' = 1 (period 2 pi) and a decoupled linear focus (z, w) with rate mu - c and
    frequency omega2. On the orbit the multipliers are 1, exp(-2 mu T) and the pair
    exp((mu - c +- i omega2) T): it leaves the unit circle at mu = c with the angle
    omega2 T (mod 2 pi)."""
    x, y, z, w = u[0], u[1], u[2], u[3]
    mu, c, om2 = par[0], par[1], par[2]
    r2 = x * x + y * y
    return np.array([x * (mu - r2) - y, y * (mu - r2) + x,
                     (mu - c) * z - om2 * w, om2 * z + (mu - c) * w])


def test_torus_bifurcation_of_cycles_located():
    """The iterator locates the TR test's zero at mu = c = 0.6 (1e-6), AUTO's acceptance
    (the stable count drops by 2) holds, and the written PAR(12) is the angle
    omega2 T = 0.3 * 2 pi of the critical pair (1e-6)."""
    from washer.cont.iterator import Continuation
    P = Problem(4, tr, name="tr")
    par = np.r_[0.5, 0.6, 0.3, np.zeros(9)]
    par[10] = 2 * math.pi
    mesh = col.Mesh.uniform(10, 4)
    t = mesh.node_times()
    r = math.sqrt(0.5)
    U = np.c_[r * np.cos(2 * np.pi * t), r * np.sin(2 * np.pi * t), 0 * t, 0 * t]
    rec = SimpleNamespace(U=U, t=t, ntst=10, ncol=4, par=par, icp=[1, 11], rldot=[], udot=None)
    s = settings(ndim=4, ntst=10, ncol=4, ISP=2, DS=0.02, DSMAX=0.05)
    sysm = PeriodicOrbits(StartData(P, s, U[0], par, rec))
    hit = after = None
    for k, step in enumerate(Continuation(sysm, s, mode="restart")):
        if hit is not None and step.point is not None:
            after = step
            break
        if step.kind == "special":
            hit = step
            sol = sysm.solution(hit.point.x, hit.point.tangent)
        assert k < 30, "no TR found"
    assert hit.code == Code.TR
    assert abs(hit.point.x[-1] - 0.6) < 1e-6
    assert hit.prev.stability.n_stable == 4 and after.point.stability.n_stable == 2
    assert abs(sol.par[11] - 0.3 * 2 * math.pi) < 1e-6


# ------------------------------------------------------------------ profiles against AUTO's

def _aligned_difference(rec_a, rec_b) -> float:
    """max_t |u_a(t + tau) - u_b(t)| over the best phase shift tau (both orbits as the
    piecewise polynomials of their s-records), relative to u_b's amplitude."""
    from scipy.optimize import minimize_scalar
    ma = col.Mesh(np.asarray(rec_a.t)[::rec_a.ncol].copy(), rec_a.ncol)
    mb = col.Mesh(np.asarray(rec_b.t)[::rec_b.ncol].copy(), rec_b.ncol)
    t = np.linspace(0, 1, 4001)[:-1]
    Ub = col.evaluate(mb, np.asarray(rec_b.U), t)
    amp = np.max(np.ptp(Ub, axis=0))
    err = lambda tau: np.max(np.abs(col.evaluate(ma, np.asarray(rec_a.U), (t + tau) % 1.0) - Ub))
    grid = np.linspace(0, 1, 401)[:-1]
    tau0 = grid[np.argmin([err(g) for g in grid])]
    best = minimize_scalar(err, bounds=(tau0 - 0.0025, tau0 + 0.0025), method="bounded",
                           options={"xatol": 1e-10})
    return float(best.fun / amp)


@pytest.mark.parametrize("demo,script", [
    ("chu", "PD"),     # chu: run(r1("HB1"), IPS=2, ICP=[1, 11]): the PD, label 8
    ("plp", "LP"),     # plp: run(hb, c='plp.ps') from HB1: the LP of cycles, label 5
])
def test_located_orbits_agree_with_autos_profiles(tmp_path, demo, script):
    """Our orbit at a located special point of a demo run against AUTO's s-record of the
    same point, after phase alignment: max difference below 1e-5 of the amplitude (the
    criterion). Measured: chu's PD 1.5e-6 (PAR(1) 8.1959946 against AUTO's
    8.1959951), plp's LP 6.5e-6 (at a fold the orbit moves like the square root of the
    parameter distance; PAR(4) differs by 1.8e-7 relative)."""
    import shutil
    from washer.run import run
    ref = DEMOS / demo
    for f in ref.glob("c.*"):
        shutil.copy(f, tmp_path)
    shutil.copy(DATA / demo / f"{demo}.py", tmp_path)
    if demo == "chu":
        run(tmp_path / "c.chu", verbose=False, e="chu", sv="eq")
        run(tmp_path / "c.chu", verbose=False, e="chu", s="eq", sv="po", IRS="HB1", IPS=2,
            ICP=[1, 11])
    else:
        run(tmp_path / "c.plp.ss", verbose=False, e="plp", sv="eq")
        run(tmp_path / "c.plp.ps", verbose=False, e="plp", s="eq", sv="po", IRS="HB1")
    ours = next(r for r in read_s(tmp_path / "s.po") if r.ty == script)
    auto = next(r for r in read_s(RECORDS / f"s.{demo}") if r.ty in ("LP", "PD"))
    assert _aligned_difference(ours, auto) < 1e-5


LW_FILE = '''
import numpy as np
def func(u, par):
    x, y = u[0], u[1]
    mu, om, b, c = par[0], par[1], par[2], par[3]
    r2 = x * x + y * y
    th = om + b * r2 + c * x
    return np.array([x * (mu - r2) - y * th, y * (mu - r2) + x * th])
def stpnt(u, par, t=0.0):
    par[0:4] = [-0.5, 1.0, 0.5, 0.8]
    u[:] = 0.0
'''


def test_isw_minus_one_at_a_regular_orbit_continues_the_family(tmp_path):
    """Periodic orbits restarted with ISW = -1 at a label that is not a BP or PD (AUTO's
    CNRLBV takes IPERP = 1 whenever IRS != 0 and ISW < 0: STDRBV's null vector, the one
    family through a regular orbit) go on along the family instead of stopping the run:
    lw's cycles from their UZ at mu = 0.1 to the UZSTOP at mu = 0.3, every point on the
    closed-form family r^2 = mu with the closed-form period."""
    from washer.run import run
    (tmp_path / "lwf.py").write_text(LW_FILE)
    (tmp_path / "c.lwf").write_text("NDIM=2, IPS=1, ICP=[1], NMX=40, DS=0.05, DSMAX=0.1, "
                                    "NPAR=12, UZSTOP={1: 0.2}\n")
    r1 = run(tmp_path / "c.lwf", e="lwf", sv="eq", verbose=False)
    r2 = run(tmp_path / "c.lwf", e="lwf", s="eq", IRS=r1("HB1").lab, IPS=2, ICP=[1, 11],
             NTST=20, NCOL=4, UZR={1: 0.1}, UZSTOP={1: 0.15}, sv="po", verbose=False)
    r3 = run(tmp_path / "c.lwf", e="lwf", s="po", IRS=r2("UZ1").lab, IPS=2, ICP=[1, 11],
             ISW=-1, NTST=20, NCOL=4, UZR={}, UZSTOP={1: 0.3}, sv="po2", verbose=False)
    assert r3.status == "ok" and r3.specials[-1].ty == "UZ"
    assert r3.specials[-1].par[0] == pytest.approx(0.3)
    for row in r3.rows[1:]:
        p = row.par
        assert p[0] > 0.1 - 1e-9
        assert p[10] == pytest.approx(lw_period(p), rel=1e-6)


def _run_fold_of_circles():
    """AUTO's run of the cycles of x' = x g - y, y' = y g + x, g = mu + 2 r^2 - r^4, from the
    outer circle at mu = -0.5 towards their fold at mu = -1 (steps of up to 0.5)."""
    from washer.cont import runner
    from washer.cont.constants import Constants
    from washer.cont.problem import Problem

    def func(u, par):
        r2 = u[0] ** 2 + u[1] ** 2
        g = par[0] + 2 * r2 - r2 * r2
        return np.array([u[0] * g - u[1], u[1] * g + u[0]])

    def stpnt(u, par, t):
        par[0], par[10] = -0.5, 2 * np.pi
        r = math.sqrt(1 + math.sqrt(0.5))
        u[0], u[1] = r * np.cos(2 * np.pi * t), r * np.sin(2 * np.pi * t)
    return runner.run(Constants(dict(NDIM=2, IPS=2, ICP=[1, 11], NTST=20, NCOL=4, ILP=1,
                                     ISP=2, NMX=10, NPR=1000, DS=-0.1, DSMAX=0.5, ITMX=4,
                                     EPSL=1e-7, EPSU=1e-7, EPSS=1e-6)),
                      Problem(2, func, stpnt=stpnt, name="fold_of_circles"))


def test_a_fold_of_cycles_is_located_at_the_closed_forms_fold():
    """x' = x g - y, y' = y g + x with g = mu + 2 r^2 - r^4: its cycles are the circles
    g = 0, r^2 = 1 +- sqrt(1 + mu), of period 2 pi, and they fold at mu = -1, r = 1.
    Followed from the outer circle at mu = -0.5 towards the fold with steps of up to 0.5,
    the fold test changes sign over a step and the location's first trial is taken back
    from the step's end along the chord to it, on the plane across it (AUTO's LCSPBV),
    the later ones from the last trial. The LP lies at mu = -1 to 1e-9: mu is quadratic in the arclength at a fold,
    so the location tolerance EPSS (1 + sqrt|DS DSMAX|) = 1.2e-6 in arclength moves it by
    ~1e-12, and the collocation of a circle traversed at constant speed is exact to
    rounding here (measured: 0 and 1e-16)."""
    br = _run_fold_of_circles()
    folds = [rec for rec in br.specials if rec.ty == "LP"]
    assert folds, [(rec.ty, rec.par[0]) for rec in br.specials]
    lp = folds[0]
    U = np.asarray(lp.U, float)
    assert abs(lp.par[0] + 1) < 1e-9
    assert lp.par[10] == pytest.approx(2 * np.pi, abs=1e-9)
    assert np.allclose(U[:, 0] ** 2 + U[:, 1] ** 2, 1.0, atol=1e-9)


def test_a_locations_first_trial_steps_back_from_the_steps_end_along_its_unit_secant(
        monkeypatch):
    """AUTO's LCSPBV takes the first trial of a location on a BVP branch from the step's
    end: CONTBV makes the secant of the step unit (SCALEB) and STEPBV goes by the secant
    correction s - span along it, on the plane across it. The trial of the fold of the
    circles g = mu + 2 r^2 - r^4 = 0 (above) lies on that plane: <x - end, c> = s - span
    with c the unit secant, to rounding (the plane's row is linear, Newton meets it at
    every iterate). Where the branch bends within the step the secant is longer than the
    span (1.137 times here, measured) and a step of (s - span) times that ratio
    lands further back: kpr's run 7 (HomCont, its zero of PSI 9) then ended its location
    on a one-iteration trial and ADPTDS doubled the next step where AUTO's grew it by 1.5."""
    from washer.cont import iterator

    seen = []
    trial = iterator.Continuation._trial

    def spy(self, prev, s_, key, base=None, chord=None, span=None):
        pt, q = trial(self, prev, s_, key, base, chord, span)
        if base is None and chord is not None and key == iterator.Code.LPC:
            seen.append((self.sys.inner, prev.x.copy(), s_, chord.copy(), span, pt.x.copy()))
        return pt, q
    monkeypatch.setattr(iterator.Continuation, "_trial", spy)

    _run_fold_of_circles()
    assert seen
    inner, x0, s_, chord, span, x = seen[0]
    n = math.sqrt(inner(chord, chord))
    end = x0 + span * chord
    assert n > 1 + 1e-3                       # the branch bends within the step
    assert inner(x - end, chord / n) == pytest.approx(s_ - span, rel=1e-9, abs=1e-13)


def test_a_locations_later_trials_step_along_the_secant_that_reached_the_last_one(
        monkeypatch):
    """AUTO's LCSPBV calls CONTBV before every STEPBV of a location: each later trial goes
    from the last trial point along the unit secant of the trial step that reached it, on
    the plane across that secant, not along the trial point's tangent (which predicts
    better: Newton then needs an iteration fewer than AUTO's, and the located point's
    count sets the next step through ADPTDS). On the fold of the circles g = mu + 2 r^2 -
    r^4 = 0 (above) every later trial lies on that plane, <x - x0, c0> = (s - s0) /
    <c0, d> with c0 the unit secant at the last trial x0 (at s0) and d prev's step
    direction (the step is asked to land at s on prev's coordinate), to rounding: the
    plane's row is linear and Newton meets it at every iterate. The fold is still
    located at mu = -1 to 1e-9 (the closed form)."""
    from washer.cont import iterator

    seen = []
    trial = iterator.Continuation._trial

    def spy(self, prev, s_, key, base=None, chord=None, span=None):
        pt, q = trial(self, prev, s_, key, base, chord, span)
        if base is not None and key == iterator.Code.LPC:
            p0, s0 = base
            seen.append((self.sys.inner, prev.step_direction.copy(), p0.x.copy(),
                         p0.step_direction.copy(), p0.tangent.copy(), s0, s_, pt.x.copy()))
        return pt, q
    monkeypatch.setattr(iterator.Continuation, "_trial", spy)

    br = _run_fold_of_circles()
    assert seen
    for inner, d, x0, c0, t0, s0, s_, x in seen:
        assert inner(x - x0, c0) == pytest.approx((s_ - s0) / inner(c0, d), rel=1e-9,
                                                  abs=1e-13)
    lp = [rec for rec in br.specials if rec.ty == "LP"][0]
    assert abs(lp.par[0] + 1) < 1e-9
