"""The compiled corrector of periodic orbits (washer.cont.corrector_periodic, C++ in
csrc/cont/po_correct.cpp) against the Python Newton loop it is the compiled form of
(washer.cont.newton through Continuation.correct with PeriodicOrbits' residual, difference
Jacobian and compiled factorisation): the same b- and s-files byte for byte, the same
evaluation counts, the same failures, on lrz and chu from their Hopf points (Python user
files, f called back from C++) and lrz's Fortran user file (FUNC through the batch bridge).

Exact equality is what the compiled loop promises: the same function values, the same
difference quotients and Jacobian values, the same factorisation and solve (the same C++
code), the residual's sums in numpy's order and the inner products by numpy's BLAS ddot
(corrector_periodic.numpy_ddot; where it cannot be had, test_inner_products_round_as_numpy says
so by failing).
"""
import shutil
from pathlib import Path

import numpy as np
import pytest

from corrector_runs import fast_and_slow
from washer.cont import corrector_algebraic, corrector_periodic, iterator, reduction
from washer.cont.branch import Counters
from washer.cont.newton import ConvergenceError
from washer.run import run

DATA = Path(__file__).parent / "data"
DEMOS = DATA / "auto_demos"

LRZ_PO = dict(IPS=2, ICP=["rho", "PERIOD"], NMX=25, NPR=2, DS=0.5)
CHU_PO = dict(IPS=2, ICP=[1, 11], NMX=60)


CONSTANTS = {"lrz": DATA / "lrz" / "c.lrz", "lrz_sym": DATA / "lrz_sym" / "c.lrz",
             "chu": DEMOS / "chu" / "c.chu",
             "tor": DEMOS / "tor" / "c.tor"}


def _folder(tmp_path, name, sub, user):
    d = tmp_path / sub
    d.mkdir()
    shutil.copy(CONSTANTS[name], d / f"c.{name.split('_')[0]}")
    shutil.copy(user, d)
    return d


def _po_run(d, name, ov, eq=None):
    """The equilibria (or their files copied from the folder eq), then the periodic
    orbits from their first Hopf point."""
    name = name.split("_")[0]
    if eq is None:
        run(d / f"c.{name}", verbose=False, e=name, sv="eq")
    else:
        for f in ("b.eq", "s.eq", "d.eq"):
            shutil.copy(eq / f, d)
    return run(d / f"c.{name}", verbose=False, e=name, sv="po", s="eq", IRS="HB1", **ov)


def _both(tmp_path, monkeypatch, name, user, ov):
    """((run, folder) with the compiled corrector, (run, folder) with the Python loop only,
    how the compiled corrections ended) (corrector_runs.fast_and_slow). Both start from
    one and the same equilibria's run: its located HB1 depends on the rounding of the
    algebraic corrector's elimination (tests/test_corrector_algebraic.py), which is not what
    is compared here."""
    eq = _folder(tmp_path, name, "eq", user)
    stem = name.split("_")[0]
    run(eq / f"c.{stem}", verbose=False, e=stem, sv="eq")

    def po_run(sub):
        d = _folder(tmp_path, name, sub, user)
        return _po_run(d, name, ov, eq=eq), d
    return fast_and_slow(monkeypatch, corrector_periodic.PeriodicCorrector, "correct_plane", po_run)


@pytest.mark.parametrize("name, user, ov", [
    ("lrz", DATA / "lrz" / "lrz.py", LRZ_PO),
    # beyond FU_FP_ONE_CALL_MAX Gauss points (440): f called once per set of parameters
    ("lrz", DATA / "lrz" / "lrz.py", dict(LRZ_PO, NTST=110, NMX=10)),
    ("chu", DATA / "chu" / "chu.py", CHU_PO),
])
def test_compiled_po_follows_the_python_loop(name, user, ov, tmp_path, monkeypatch):
    # the tangents at the converged points: the corrector's last factorisation re-bordered
    # (the Python loop's run factorises [J; border] afresh)
    reborders = []
    real = reduction.BorderedCollocation.reborder

    def spy(self, *a, **k):
        out = real(self, *a, **k)
        reborders.append(out)
        return out
    monkeypatch.setattr(reduction.BorderedCollocation, "reborder", spy)
    (fast, fd), (slow, sd), used = _both(tmp_path, monkeypatch, name, user, ov)
    assert len(used) >= ov["NMX"] - 1 and all(used), used      # every step (PT 1: the start)
    # (points after chord iterations evaluate the Jacobian at x afresh: no re-bordering)
    assert sum(reborders) >= 2 and all(reborders), reborders
    for f in ("b.po", "s.po"):
        assert (fd / f).read_bytes() == (sd / f).read_bytes(), f
    assert (fast.counters.residuals, fast.counters.jacobians, fast.counters.factorisations) \
        == (slow.counters.residuals, slow.counters.jacobians, slow.counters.factorisations)
    assert [(s.ty, s.lab) for s in fast.specials] == [(s.ty, s.lab) for s in slow.specials]


@pytest.mark.skipif(shutil.which("gcc") is None, reason="gcc is needed for the generated C")
@pytest.mark.parametrize("jac", [1, 0])
def test_compiled_po_with_a_sympy_problem(jac, tmp_path, monkeypatch):
    """lrz as sympy expressions (tests/data/lrz_sym): the generated f (and with JAC = 1
    its exact f_u) called from C++ through their function pointers; the same files as
    the Python loop, which calls them through Problem.func_many and dfdu_many."""
    monkeypatch.setenv("WASHER_CACHE", str(tmp_path / "cache"))
    (fast, fd), (slow, sd), used = _both(tmp_path, monkeypatch, "lrz_sym",
                                         DATA / "lrz_sym" / "lrz.py", dict(LRZ_PO, JAC=jac))
    assert len(used) >= LRZ_PO["NMX"] - 1 and all(used), used
    for f in ("b.po", "s.po"):
        assert (fd / f).read_bytes() == (sd / f).read_bytes(), f
    assert fast.counters.jacobians == slow.counters.jacobians


@pytest.mark.skipif(shutil.which("gfortran") is None, reason="gfortran is needed for AUTO's "
                    "Fortran user files")
@pytest.mark.parametrize("name, ov, min_used", [
    # JAC = 0: FUNC, f_u and f_p by differences
    ("lrz", dict(LRZ_PO, NMX=15), 14),
    # JAC = 1 (c.tor): the user's DFDU (FUNC with IJAC = 1), f_p by differences; the run
    # passes tor's fold and BP of cycles (PT 21 and 27) with their locations
    ("tor", dict(IPS=2, ICP=[1, 11], NMX=40), 39),
])
def test_compiled_po_with_a_fortran_user_file(name, ov, min_used, tmp_path, monkeypatch):
    """AUTO's lrz.f90 and tor.f90: FUNC (and with JAC = 1 DFDU) of the compiled user file
    called by the C++ loop through the bridge's function pointers (washer_po_func,
    washer_po_jac), never back through Python; the same files as the Python loop on the
    same user file, which calls them through CompiledUser.func_batch and jac_batch."""
    monkeypatch.setenv("WASHER_CACHE", str(tmp_path / "cache"))
    called_back = []
    real = corrector_periodic.PeriodicCorrector._evaluate

    def spy(self, *a):
        called_back.append(a[0])
        return real(self, *a)
    monkeypatch.setattr(corrector_periodic.PeriodicCorrector, "_evaluate", spy)
    (fast, fd), (slow, sd), used = _both(tmp_path, monkeypatch, name,
                                         DEMOS / name / f"{name}.f90", ov)
    assert len(used) >= min_used and all(used), used
    assert called_back == []
    for f in ("b.po", "s.po"):
        assert (fd / f).read_bytes() == (sd / f).read_bytes(), f
    assert (fast.counters.residuals, fast.counters.jacobians) == \
        (slow.counters.residuals, slow.counters.jacobians)


def test_inner_products_round_as_numpy():
    """The ddot handed to the C++ loop is numpy's (bit-identical phase condition and
    arclength row); without it the loop still runs, equal to rounding."""
    assert corrector_periodic.numpy_ddot() != corrector_periodic.ffi.NULL


def _system(tmp_path, monkeypatch):
    """A Continuation of lrz's periodic orbits from HB1 and its first step's predictor,
    lrz.py's func in Python (called back from C++; not traced into C)."""
    monkeypatch.setenv("WASHER_TRACE", "0")
    d = _folder(tmp_path, "lrz", "one", DATA / "lrz" / "lrz.py")
    run(d / "c.lrz", verbose=False, e="lrz", sv="eq")
    grabbed = {}
    real = iterator.Continuation.correct

    def grab(self, x_pred, x_ref, t_ref, ds, plane=None):
        if isinstance(self._compiled, corrector_periodic.PeriodicCorrector) and "c" not in grabbed:
            grabbed["c"] = (self, np.array(x_pred), np.array(x_ref), np.array(t_ref), ds)
        return real(self, x_pred, x_ref, t_ref, ds, plane)
    with monkeypatch.context() as m:
        m.setattr(iterator.Continuation, "correct", grab)
        run(d / "c.lrz", verbose=False, e="lrz", sv="po", s="eq", IRS="HB1",
            **dict(LRZ_PO, NMX=3))
    return grabbed["c"]


def test_failing_f_hands_over_to_the_python_loop(tmp_path, monkeypatch):
    """f failing inside the C++ loop: the correction is the Python loop's (None), which
    evaluates f again and reports; Ctrl-C in the user's func stops the run."""
    cont, x_pred, x_ref, t_ref, ds = _system(tmp_path, monkeypatch)
    comp = cont._compiled
    problem = comp.problem
    calls = []

    def failing(us, pars):
        calls.append(len(us))
        raise ValueError("f fails here")
    with monkeypatch.context() as m:
        m.setattr(problem, "func_many", failing)
        assert comp.correct_plane(x_pred, x_ref, t_ref, ds, Counters()) is None
    assert calls == [cont.sys.mesh.ntst * cont.sys.mesh.ncol]

    def interrupted(us, pars):
        raise KeyboardInterrupt
    with monkeypatch.context() as m:
        m.setattr(problem, "func_many", interrupted)
        with pytest.raises(KeyboardInterrupt):
            comp.correct_plane(x_pred, x_ref, t_ref, ds, Counters())
    # and it runs again after both
    x, it = comp.correct_plane(x_pred, x_ref, t_ref, ds, Counters())
    assert it >= 1 and np.isfinite(x).all()


def test_no_convergence_as_the_python_loop(tmp_path, monkeypatch):
    """ITNW = 1: the compiled loop gives up with the Python loop's message and counts."""
    import dataclasses
    cont, x_pred, x_ref, t_ref, ds = _system(tmp_path, monkeypatch)
    cont.s = cont._compiled.s = dataclasses.replace(cont.s, ITNW=1)
    out = []
    for compiled in (True, False):
        cont.counters = Counters()
        if not compiled:
            cont._compiled = None
        with pytest.raises(ConvergenceError) as err:
            cont.correct(x_pred, x_ref, t_ref, ds)
        out.append((str(err.value), cont.counters.residuals, cont.counters.jacobians))
    assert out[0] == out[1] and out[0][0] == "no convergence in ITNW = 1 iterations"


def test_where_it_applies(tmp_path, monkeypatch):
    """PeriodicOrbits with difference Jacobians only: not with the user's Jacobians, not
    on other collocation systems, nor with the Python factorisation."""
    cont, *_ = _system(tmp_path, monkeypatch)
    sysm, s = cont.sys, cont.s
    assert corrector_algebraic.compiled_corrector(sysm, s, 20.0) is not None
    from washer.cont.systems import bvp
    with monkeypatch.context() as m:
        m.setattr(bvp, "COMPILED_FACTOR", False)
        assert corrector_algebraic.compiled_corrector(sysm, s, 20.0) is None
    with monkeypatch.context() as m:
        m.setattr(type(sysm.problem), "differenced_jacobian", property(lambda self: False))
        assert corrector_algebraic.compiled_corrector(sysm, s, 20.0) is None


def test_jacobian_at_a_point_is_the_systems(tmp_path, monkeypatch):
    """cont_po_jacobian (the Jacobian at a point after chord iterations, and at a
    location's trials) against PeriodicOrbits.jacobian at the same x: the same values
    bit for bit, and the same `_last_blocks` left for the Floquet multipliers."""
    cont, x_pred, *_ = _system(tmp_path, monkeypatch)
    comp, sysm = cont._compiled, cont.sys
    J = comp.jacobian_at(x_pred)
    x_c, blocks_c, J_c = sysm._last_blocks
    assert J is J_c and np.array_equal(x_c, x_pred)
    ref = sysm.jacobian(x_pred)
    x_r, blocks_r, _ = sysm._last_blocks
    assert np.array_equal(J.indptr, ref.indptr) and np.array_equal(J.indices, ref.indices)
    assert J.data.tobytes() == ref.data.tobytes()
    assert blocks_c.tobytes() == np.ascontiguousarray(blocks_r).tobytes()


@pytest.mark.parametrize("bad", [np.inf, -np.inf, np.nan])
def test_a_non_finite_jacobian_value_hands_over(bad, tmp_path, monkeypatch):
    """A difference quotient that is not finite, wherever it falls among the Jacobian's
    values (the first, one in the middle, the last difference point): jacobian_at gives
    None (the system's own Jacobian is then evaluated); finite values give a Jacobian."""
    cont, x_pred, *_ = _system(tmp_path, monkeypatch)
    comp = cont._compiled
    problem = comp.problem
    original = problem.func_many
    k = cont.sys.mesh.ntst * cont.sys.mesh.ncol
    for where in (0, 1, "mid", -1):
        def poisoned(us, pars, where=where):
            F = np.array(original(us, pars), dtype=float)
            if len(us) > k:                   # the difference points, not the Gauss points
                F[len(F) // 2 if where == "mid" else where, 0] = bad
            return F
        with monkeypatch.context() as m:
            m.setattr(problem, "func_many", poisoned)
            assert comp.jacobian_at(x_pred) is None
    assert comp.jacobian_at(x_pred) is not None
