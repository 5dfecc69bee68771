"""Invariant circles of maps (washer.cont.invariant_circle, continued by the engine as
washer.cont.systems.circles) on a map whose circle, rotation number and normal multipliers
are known in closed form.

The map is designed with sympy: the Neimark-Sacker normal form in the plane,
z' = e^{2 pi i (rho0 + b |z|^2)} z (1 + mu - |z|^2) (z = x + i y), has the invariant circle
|z|^2 = mu on which it rotates rigidly by rho = rho0 + b mu turns, with radial multiplier
d r'/d r = 1 - 2 mu. A third coordinate w' = kappa w + eps (x^2 - y^2) is driven by the
angle phi: on the circle w(phi) = Re(W e^{2 i phi}) with W = eps mu / (e^{4 pi i rho} - kappa)
(from w(phi + 2 pi rho) = kappa w(phi) + eps mu cos 2 phi), normal multiplier kappa. The
whole is then conjugated by the nonlinear change of coordinates
H(x, y, w) = (x + a y^2, y + c sin 3x, w) (a triangular map: its inverse is explicit), so the
circle is no longer round, its Fourier series is infinite, and the map's Jacobian is
nowhere a rotation; the rotation number and the normal multipliers' moduli are conjugacy
invariants. Nothing in the code under test knows any of this.
"""
import numpy as np
import pytest
import sympy as sp

from washer.cont import invariant_circle as ic
from washer.auto.sinks import FileSink
from washer.auto.files import read_b, read_s
from washer.cont import circle_runs as runs
from washer.cont.systems import circles as cs

RHO0, B, KAPPA, EPS, A, C = 0.3, 0.5, 0.5, 0.4, 0.6, 0.3


def _design():
    x, y, w, mu = sp.symbols("x y w mu", real=True)
    # H^-1 of H(x, y, w) = (h2(h1(x, y)), w), h1(x, y) = (x, y + c sin 3x), h2(x, y) = (x + a y^2, y)
    x1, y1 = x - A * y**2, y                      # h2^-1
    x0, y0 = x1, y1 - C * sp.sin(3 * x1)          # h1^-1
    r2 = x0**2 + y0**2
    psi = 2 * sp.pi * (RHO0 + B * r2)
    g = 1 + mu - r2
    xn, yn = g * (x0 * sp.cos(psi) - y0 * sp.sin(psi)), g * (x0 * sp.sin(psi) + y0 * sp.cos(psi))
    wn = KAPPA * w + EPS * (x0**2 - y0**2)
    F = sp.Matrix([xn + A * (yn + C * sp.sin(3 * xn))**2, yn + C * sp.sin(3 * xn), wn])
    v = sp.Matrix([x, y, w])
    f = sp.lambdify((x, y, w, mu), F, "numpy")
    df = sp.lambdify((x, y, w, mu), F.jacobian(v), "numpy")
    fp = sp.lambdify((x, y, w, mu), F.diff(mu), "numpy")
    return f, df, fp


@pytest.fixture(scope="module")
def fmap():
    f, df, fp = _design()

    def m(X, p):
        F = np.array([np.ravel(f(*xi, p)) for xi in X])
        DF = np.array([np.array(df(*xi, p), dtype=float) for xi in X])
        Fp = np.array([np.ravel(fp(*xi, p)) for xi in X])
        return F, DF, Fp
    return m


def exact_error(circle) -> float:
    """Largest distance of the computed circle (at 4N angles) from the exact one, in the
    normal-form coordinates: | |z| - sqrt(mu) | and |w - Re(W e^{2 i phi})|."""
    pts = circle(np.linspace(0, 2 * np.pi, 4 * circle.N, endpoint=False))
    x, y, w = pts.T
    x0 = x - A * y**2
    y0 = y - C * np.sin(3 * x0)
    phi = np.arctan2(y0, x0)
    mu = circle.p
    rho = RHO0 + B * mu
    W = EPS * mu / (np.exp(4j * np.pi * rho) - KAPPA)
    return float(max(np.abs(np.hypot(x0, y0) - np.sqrt(mu)).max(),
                     np.abs(w - (W * np.exp(2j * phi)).real).max()))


def birth(fmap, N, amplitude):
    """The first circle from the Neimark-Sacker point mu = 0 at the origin."""
    _, DF, _ = fmap(np.zeros((1, 3)), 0.0)
    lam, V = np.linalg.eig(DF[0])
    i = int(np.argmax(lam.imag))
    return runs.first_circle(fmap, np.zeros(3), V[:, i], np.angle(lam[i]) / (2 * np.pi), 0.0,
                           amplitude, N)


def test_shift_matrix_is_exact_on_trigonometric_polynomials():
    """R(s) moves a degree-K trigonometric polynomial exactly; its derivative matches."""
    N, s = 11, 0.7
    th = ic.nodes(N)
    f = lambda t: 1 + np.cos(t) - 2 * np.sin(3 * t) + 0.5 * np.cos(5 * t)
    df = lambda t: -np.sin(t) - 6 * np.cos(3 * t) - 2.5 * np.sin(5 * t)
    assert np.allclose(ic.shift_matrix(N, s) @ f(th), f(th + s), atol=1e-13)
    assert np.allclose(ic.shift_matrix(N, s, 1) @ f(th), df(th + s), atol=1e-12)
    assert np.allclose(ic.evaluate(f(th)[:, None], [0.3, 2.0])[:, 0], f(np.r_[0.3, 2.0]),
                       atol=1e-13)


def test_circle_born_at_the_neimark_sacker_point_is_the_exact_one(fmap):
    """Started from the fixed point and the critical eigenvector, Newton lands on the exact
    circle: mu, rho = rho0 + b mu, the normal moduli {kappa, 1 - 2 mu} and the tangent's 1."""
    c = birth(fmap, 31, 0.1)
    mu = c.p
    assert 0 < mu < 0.05
    # Spectral accuracy: the conjugated circle's Fourier tail at K = 15 is far below 1e-10.
    assert exact_error(c) < 1e-10
    assert c.rho == pytest.approx(RHO0 + B * mu, abs=1e-11)
    assert c.moduli == pytest.approx(sorted([KAPPA, 1 - 2 * mu], reverse=True), abs=1e-8)
    assert c.tangent == pytest.approx(1.0, abs=1e-8)
    assert c.stable


@pytest.mark.slow          # 3 s; the fast loop continues circles in the file sink's test
def test_continued_family_follows_the_closed_form(fmap):
    """Pseudo-arclength from the birth to mu = 0.18: every circle exact, its rotation number
    and moduli as the closed form says; the last circle exactly at mu = 0.18. (The end is
    not mu = 0.2, where rho = 2/5 exactly: at a rational rho = p/q with q <= K the
    parametrisation of the circle is not unique (modes q, 2q, ... of a reparametrisation
    solve the linearised equation), so the collocation is singular there; on the way the
    family passes rationals harmlessly, e.g. 1/3 near mu = 0.067.)"""
    c0 = birth(fmap, 31, 0.05)
    br = runs.continue_circles(fmap, c0, 0.18, ds=0.02, ds_max=0.05)
    assert runs.reached(br)
    circles = runs.circles(br)
    p = np.array([c.p for c in circles])
    assert p[-1] == pytest.approx(0.18, abs=1e-12)
    assert len(circles) >= 4
    for c in circles:
        assert exact_error(c) < 1e-8, c.p
        assert c.rho == pytest.approx(RHO0 + B * c.p, abs=1e-10)
        assert c.moduli == pytest.approx(sorted([KAPPA, 1 - 2 * c.p], reverse=True), abs=1e-6)
    assert np.all(np.diff(p) > 0)


def test_too_few_modes_are_visible_in_the_error_and_the_spectrum(fmap):
    """With K = 3 the circle (Fourier-infinite after H) is not resolved: the error against the
    closed form is large, and the spectrum's tail (amplitudes) says so before any comparison."""
    c_fine = birth(fmap, 31, 0.3)
    X = ic.resample(c_fine.X, 7)
    assert ic.amplitudes(c_fine.X)[3] > 1e-6          # mode 3 is present, so K = 3 truncates
    br = runs.continue_circles(fmap, ic.Circle(X, c_fine.rho, c_fine.p), c_fine.p + 1e-3,
                             ds=0.01, max_points=3)
    assert exact_error(runs.circles(br)[-1]) > 1e3 * exact_error(c_fine)


def test_circle_run_writes_auto_files(fmap, tmp_path):
    """The family as an engine run through the file sink: b-rows with the circle's curve
    type (EP 99 at the start, UZ -94 at the end value), the columns AMPLITUDE, ROTATION,
    MU_MAX of each circle, and s-records holding the closed profile (N + 1 points, the last
    the first) that read back to the circle."""
    c0 = birth(fmap, 15, 0.1)
    br = runs.continue_circles(fmap, c0, c0.p + 0.02, ds=0.01, ds_max=0.02,
                             sinks=[FileSink(tmp_path, "circ")])
    rows = read_b(tmp_path / "b.circ")[0]
    assert [r.ty for r in rows if r.lab] == [99, -94]
    assert len(rows) == len(br.rows)
    last = runs.circles(br)[-1]
    assert rows[-1].values[0] == pytest.approx(c0.p + 0.02, abs=1e-9)
    assert rows[-1].values[2] == pytest.approx(last.rho, rel=1e-9)
    assert rows[-1].values[3] == pytest.approx(last.moduli.max(), rel=1e-9)
    rec = read_s(tmp_path / "s.circ")[-1]
    U = np.asarray(rec.u)
    assert U.shape == (16, 3)
    assert np.abs(U[-1] - U[0]).max() < 1e-9
    assert np.abs(U[:-1] - last.X).max() < 1e-9 * (1 + np.abs(last.X).max())


def test_circle_system_honours_the_engine_contract(fmap):
    """InvariantCircles has every method of the ContinuedSystem Protocol, and its Jacobian
    (invariance equation, phase condition, d/d rho, d/dp) is the derivative of its residual
    (central differences, step 1e-6: truncation ~1e-12, rounding ~1e-10)."""
    from washer.cont.settings import Settings
    from washer.cont.system import ContinuedSystem
    c0 = birth(fmap, 9, 0.1)
    sysm = cs.InvariantCircles(fmap, c0, Settings.from_constants(
        runs.constants(1, 0.2, 3, ds=0.01, ds_max=0.1, ds_min=1e-6, max_points=5)))
    for m in ContinuedSystem.__dict__:
        if callable(getattr(ContinuedSystem, m)) and not m.startswith("_"):
            assert callable(getattr(sysm, m, None)), m
    x0, t0 = sysm.start()
    x = x0 + 0.01 * np.sin(np.arange(len(x0)))
    J = sysm.jacobian(x)
    h = 1e-6
    fd = np.array([(sysm.residual(x + h * e) - sysm.residual(x - h * e)) / (2 * h)
                   for e in np.eye(len(x))]).T
    assert np.abs(fd - J).max() < 1e-7 * np.abs(J).max()
    assert np.abs(sysm.jacobian(x0) @ t0).max() < 1e-10      # the start's tangent is a null vector
    assert sysm.inner(t0, t0) == pytest.approx(1.0) and t0[-1] > 0   # towards the UZSTOP value
