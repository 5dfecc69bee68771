"""A continuation step's point on a collocation BVP takes its Jacobian from the corrector's
last Newton iteration (AUTO's NEWTONBV: the fold test's direction, the Floquet
multipliers and the branch-point test come from the matrix it factorised last), instead
of evaluating f_u at every Gauss point once more.

Checked along chu's periodic family through its period doubling (AUTO's record, label 8;
ISP = 2, ILP = 1: fold, BP of cycles and PD/TR tests all active), with the shipped
iterator:
* where the converging correction started from the iterate the matrix was evaluated at,
  no Jacobian is evaluated at the point itself; after chord iterations (NWTN = 1) it is;
* the tangent, the multipliers and the test values taken so agree with those of the
  Jacobian evaluated at the point (the same iterator's evaluation without the Newton
  matrix, before the phase reference moves on), to what the matrix's error allows: it
  was evaluated within EPSU (1e-7 relative) of the point.
"""
import numpy as np

from washer.cont import corrector_periodic, floquet
from washer.cont.codes import Code
from washer.cont.iterator import Continuation

from test_periodic import _auto_system


class Twice(Continuation):
    """The shipped iterator, which also evaluates every regular point a second time
    without the Newton matrix (the Jacobian at x), before the system moves its phase
    reference to the point, and records how far the two evaluations differ there (the
    accepted point's tangent is later moved onto the adapted mesh)."""

    def __init__(self, *a, **kw):
        super().__init__(*a, **kw)
        self.diffs = []

    def evaluate(self, x, ref, keys=None, tangent=None, ds=0.0, it=0, newton=None):
        a = super().evaluate(x, ref, keys, tangent, ds, it, newton)
        if newton is not None:
            b = super().evaluate(x, ref, keys, tangent, ds, it)
            dt = a.tangent - b.tangent
            self.diffs.append({
                "tangent": float(np.sqrt(self.sys.inner(dt, dt))),
                "mu": float(np.max(np.abs(a.stability.values - b.stability.values))),
                "stable": (a.stability.n_stable, b.stability.n_stable),
                "tests": {k: (a.tests.get(k), b.tests.get(k)) for k in b.tests}})
        return a


def _chu(**kw):
    sysm, rec = _auto_system("chu", 8, (1, 11), ISP=2, ILP=1, **kw)
    return sysm


def _run(it, n):
    """The first n points of the branch as (point, its unknowns' bytes when written: the
    mesh adaptation after a point moves its x onto the new mesh)."""
    pts = []
    for step in it:
        assert step.kind != "failed", step.text
        if step.kind in ("point", "special"):
            pts.append((step.point, step.point.x.tobytes()))
        if len(pts) >= n:
            return pts
    raise AssertionError("the branch ended early")


def _spy(sysm, monkeypatch):
    """Record the unknowns at which the Jacobian is evaluated (bytes of x): sysm.jacobian,
    or the compiled corrector's form of it (corrector_periodic.PeriodicCorrector.jacobian_at)."""
    seen = []
    jac = sysm.jacobian

    def spy(x, *a, **kw):
        seen.append(np.asarray(x, float).tobytes())
        return jac(x, *a, **kw)
    sysm.jacobian = spy
    compiled_jac = corrector_periodic.PeriodicCorrector.jacobian_at

    def compiled_spy(self, x):
        J = compiled_jac(self, x)
        if J is not None:
            seen.append(np.asarray(x, float).tobytes())
        return J
    monkeypatch.setattr(corrector_periodic.PeriodicCorrector, "jacobian_at", compiled_spy)
    return seen


def test_regular_points_evaluate_no_jacobian_of_their_own(monkeypatch):
    sysm = _chu()
    seen = _spy(sysm, monkeypatch)
    s = sysm.settings.with_(DS=0.02, DSMAX=0.1, NWTN=3, ITNW=7)
    pts = _run(Continuation(sysm, s), 12)
    regular = [xb for p, xb in pts[1:] if 1 <= p.iterations <= s.NWTN
               and floquet.newton_jacobian_serves(p.stability)]
    assert len(regular) >= 8
    for xb in regular:
        assert xb not in seen


def test_after_chord_iterations_the_point_evaluates_its_jacobian(monkeypatch):
    """NWTN = 1: a point converged in two or more iterations has its matrix from the
    first iterate (chord iterations since), and evaluates the Jacobian at itself."""
    sysm = _chu()
    seen = _spy(sysm, monkeypatch)
    s = sysm.settings.with_(DS=0.02, DSMAX=0.1, NWTN=1, ITNW=7)
    pts = _run(Continuation(sysm, s), 6)
    chord = [xb for p, xb in pts[1:] if p.iterations >= 2]
    assert chord
    for xb in chord:
        assert xb in seen


def test_newton_matrix_quantities_are_those_of_the_jacobian_at_the_point():
    """Along 25 points through chu's PD: the matrix of the last iteration is within EPSU
    = 1e-7 (relative) of the Jacobian at the point, so the unit tangent differs by about
    that times the bordered matrix's condition (bound 1e-6; measured 7e-8), the
    multipliers by that times their sensitivity (bound 1e-4; measured 7e-6: chu's
    largest multiplier is about 70 times more sensitive), and every test value has the
    same sign and agrees to 1e-4 relative (measured 1e-6): the same stable counts and
    the same detections."""
    sysm = _chu()
    s = sysm.settings.with_(DS=0.02, DSMAX=0.1, NWTN=3, ITNW=7)
    it = Twice(sysm, s)
    _run(it, 25)
    assert len(it.diffs) >= 15
    for d in it.diffs:
        assert d["tangent"] < 1e-6
        assert d["mu"] < 1e-4
        assert d["stable"][0] == d["stable"][1]
        for key, (qa, qb) in d["tests"].items():
            assert (qa is None) == (qb is None), key
            if qb is not None:
                assert qa * qb > 0, key
                assert abs(qa - qb) <= 1e-4 * abs(qb), key
    # the family crosses the PD: its test is evaluated from the Newton matrix on both sides
    pd = [d["tests"][floquet.SPB][1] for d in it.diffs
          if d["tests"].get(floquet.SPB, (None, None))[1] is not None]
    assert min(pd) < 0 < max(pd) or len(pd) >= 3
