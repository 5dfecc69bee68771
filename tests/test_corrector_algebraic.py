"""The compiled corrector of algebraic continuation (washer.cont.corrector_algebraic, C in
washer/cont/include/ae_correct.h) against the Python Newton loop it is the compiled form
of (washer.cont.newton through Continuation.correct): the same branches, special points,
iteration counts and failures, on AUTO's ab and lrz user files (Fortran: FUNC called from
C) and their Python transcriptions (func called back from C), run both ways.

Tolerances: the two loops make the same function calls and the same quotients; only the
bordered solve is a different elimination (partial pivoting in C against LAPACK's
GESV), whose rounding differs in the last bits of a correction that converges to EPSU =
1e-7: the converged points agree to far below that (1e-9 relative is asserted, the b-file
prints 11 digits), and from a located special point on, which iterates on a test
function near its zero, within the location's tolerance (corrector_runs.assert_rows_agree:
on an AVX-512 AMD EPYC, ab's HB differed by 1e-9 relative, which is rounding, not a
difference of the loops).
"""
import shutil
from pathlib import Path

import numpy as np
import pytest

from auto_reference import AB2P_LOCUS as AB2, LRZ2P_LOCUS as LRZ2
from corrector_runs import assert_counts_agree, assert_rows_agree, fast_and_slow
from tolerances import location_tolerance
from washer.cont import corrector_algebraic
from washer.run import run

DATA = Path(__file__).parent / "data"
DEMOS = DATA / "auto_demos"

pytestmark = pytest.mark.skipif(shutil.which("gfortran") is None or shutil.which("gcc") is None,
                                reason="gcc and gfortran are needed (Debian: gcc gfortran)")


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("WASHER_CACHE", str(tmp_path / "cache"))


def _folder(tmp_path, name, sub, kind):
    d = tmp_path / sub
    d.mkdir()
    shutil.copy(DATA / name / f"c.{name}", d)
    if kind == "f90":
        shutil.copy(DEMOS / name / f"{name}.f90", d)
    elif kind == "sym":
        shutil.copy(DATA / f"{name}_sym" / f"{name}.py", d)
    else:
        shutil.copy(DATA / name / f"{name}.py", d)
    return d


def _both(tmp_path, monkeypatch, name, kind="f90", **ov):
    """The run with the compiled corrector (and how its corrections ended), then the same
    run with the Python loop only (corrector_runs.fast_and_slow)."""
    return fast_and_slow(monkeypatch, corrector_algebraic.CompiledCorrector, "correct",
                         lambda sub: run(_folder(tmp_path, name, sub, kind) / f"c.{name}",
                                         verbose=False, **ov))


@pytest.mark.parametrize("kind", ["f90", "py"])
@pytest.mark.parametrize("name", ["ab", "lrz"])
def test_compiled_corrector_follows_the_python_loop(name, kind, tmp_path, monkeypatch, cache):
    fast, slow, used = _both(tmp_path, monkeypatch, name, kind)
    # every step through C but those the Python loop takes over: at lrz's branch point
    # (the Newton matrix exactly singular on the trivial branch, where the Python loop's
    # solve falls back to least squares)
    assert len(used) > 50 and sum(used) >= len(used) - 5, used
    assert [(s.ty, s.lab) for s in fast.specials] == [(s.ty, s.lab) for s in slow.specials]
    assert_rows_agree(fast, slow, location_tolerance(DATA / name / f"c.{name}"))
    assert_counts_agree(fast, slow, DATA / name / f"c.{name}")
    assert fast.status == slow.status


@pytest.mark.parametrize("jac", [1, 0])
def test_compiled_corrector_follows_the_python_loop_on_sympy_equations(jac, tmp_path,
                                                                       monkeypatch, cache):
    """lrz as sympy expressions (tests/data/lrz_sym): the generated f and, with JAC = 1,
    its exact f_u and f_p called from C through function pointers take the same steps
    as the Python loop calling them through Problem."""
    fast, slow, used = _both(tmp_path, monkeypatch, "lrz", "sym", JAC=jac)
    assert len(used) > 50 and sum(used) >= len(used) - 5, used
    assert [(s.ty, s.lab) for s in fast.specials] == [(s.ty, s.lab) for s in slow.specials]
    assert_rows_agree(fast, slow, location_tolerance(DATA / "lrz" / "c.lrz"))
    assert_counts_agree(fast, slow, DATA / "lrz" / "c.lrz")
    assert fast.status == slow.status


@pytest.mark.parametrize("kind", ["f90", "py"])
def test_compiled_corrector_fails_as_the_python_loop(kind, tmp_path, monkeypatch, cache):
    """ITNW = 2 is too few for many of ab's steps: both loops give up on the same steps
    with the same message, halve DS the same way (the same notes in the d-files) and
    go on to the same branch."""
    fast, slow, used = _both(tmp_path, monkeypatch, "ab", kind, ITNW=2)
    assert len(used) > 100 and all(used)

    def notes(sub):
        return [line for line in (tmp_path / sub / "d.ab").read_text().splitlines()
                if "NOTE" in line]
    assert len(notes("fast")) > 20
    assert notes("fast") == notes("slow")
    assert "no convergence in ITNW = 2 iterations" in notes("fast")[0]
    assert fast.status == slow.status
    assert_rows_agree(fast, slow, location_tolerance(DATA / "ab" / "c.ab", ITNW=2))



def _failing_ab(d, condition: str):
    """A folder d with c.ab and ab.py whose func raises ValueError('outside the model')
    where `condition` (Python on par; par may be (NPAR, k) in a batch) holds."""
    d.mkdir()
    shutil.copy(DATA / "ab" / "c.ab", d)
    (d / "ab.py").write_text((DATA / "ab" / "ab.py").read_text() + (
        f"\n_func = func\n\n\ndef func(u, par):\n    if {condition}:\n"
        "        raise ValueError('outside the model')\n    return _func(u, par)\n"))
    return d

def test_failing_func_hands_over_to_the_python_loop(tmp_path, monkeypatch, cache):
    """A func that fails beyond PAR(1) = 0.1 (an exception from the user's code, called
    back from C): the Python loop takes the step over and reports the failure as it
    does without the compiled corrector; the runs end the same."""
    fast, slow, _ = fast_and_slow(
        monkeypatch, corrector_algebraic.CompiledCorrector, "correct",
        lambda sub: run(_failing_ab(tmp_path / sub, "par[0] > 0.1") / "c.ab", verbose=False))
    assert "outside the model" in fast.status
    assert fast.status == slow.status.replace("/slow/", "/fast/")    # the file is named
    assert_rows_agree(fast, slow, location_tolerance(DATA / "ab" / "c.ab"))


def test_ctrl_c_in_func_is_not_taken_for_a_failure(tmp_path, cache):
    """KeyboardInterrupt raised in the user's func while the C corrector calls it back
    (Ctrl-C arrives in Python code) interrupts the run, as it does from the Python loop,
    instead of being handed over as a failed evaluation."""
    d = tmp_path / "int"
    d.mkdir()
    shutil.copy(DATA / "ab" / "c.ab", d)
    # once, as a Ctrl-C arrives once (the Python loop would not call func into it again)
    (d / "ab.py").write_text((DATA / "ab" / "ab.py").read_text() + (
        "\n_func = func\n_sent = []\n\n\ndef func(u, par):\n"
        "    if par[0] > 0.1 and not _sent:\n        _sent.append(1)\n"
        "        raise KeyboardInterrupt\n    return _func(u, par)\n"))
    with pytest.raises(KeyboardInterrupt):
        run(d / "c.ab", verbose=False)


def test_only_compiled_equilibria_with_difference_jacobians(tmp_path, cache, monkeypatch):
    """Compiled and Python equations with difference Jacobians take the compiled loop;
    with the user's Jacobians (JAC = 1) a compiled user file keeps the Python loop and
    Python equations take the compiled one (their dfdu called back); sympy equations
    take it with differences or their generated exact Jacobians."""
    from washer.cont.user_problem.user_files_native import load_compiled_problem
    from washer.cont.settings import Settings
    from washer.cont.user_problem.user_files import load_python_problem
    from washer.cont.system import StartData
    from washer.cont.systems.equilibrium import EquilibriumSystem

    def system(problem, jac):
        s = Settings(NDIM=2, ICP=[1], IPS=1, JAC=jac)
        u, par = problem.start(36)
        return EquilibriumSystem(StartData(problem=problem.with_jac(jac), settings=s,
                                           u=u, par=par))

    compiled = load_compiled_problem(DEMOS / "ab" / "ab.f90", 2)
    monkeypatch.setenv("WASHER_TRACE", "0")      # the Python functions (the call back)
    python = load_python_problem("ab", DATA / "ab", 2)
    jac_py = tmp_path / "jac"
    jac_py.mkdir()
    (jac_py / "ab.py").write_text((DATA / "ab" / "ab.py").read_text()
                                  + "\n\ndef dfdu(u, par):\n    return np.eye(2)\n")
    with_dfdu = load_python_problem("ab", jac_py, 2)
    s = Settings(NDIM=2, ICP=[1], IPS=1)
    assert corrector_algebraic.compiled_corrector(system(compiled, 0), s, 20.0) is not None
    assert corrector_algebraic.compiled_corrector(system(compiled, 1), s, 20.0) is None
    assert corrector_algebraic.compiled_corrector(system(python, 0), s, 20.0) is not None
    assert corrector_algebraic.compiled_corrector(system(with_dfdu, 0), s, 20.0) is not None
    exact = corrector_algebraic.compiled_corrector(system(with_dfdu, 1), s, 20.0)
    assert exact is not None and exact.user.exact
    assert not corrector_algebraic.compiled_corrector(system(with_dfdu, 0), s, 20.0).user.exact
    # traced into C (washer.cont.user_problem.user_files_traced): FUNC directly with
    # differences, the call back
    # (of the traced dfdu) with the user's Jacobians
    monkeypatch.setenv("WASHER_TRACE", "1")
    traced = load_python_problem("ab", jac_py, 2)
    assert type(corrector_algebraic.compiled_corrector(system(traced, 0), s, 20.0).user) \
        is not corrector_algebraic.PythonEquations
    assert corrector_algebraic.compiled_corrector(system(traced, 1), s, 20.0).user.exact
    monkeypatch.setenv("WASHER_TRACE", "0")
    # sympy equations: their generated f and exact Jacobians are C (JAC = 1; JAC = -1,
    # exact f_u with differenced f_p, keeps the Python loop)
    sym_dir = tmp_path / "sym"
    sym_dir.mkdir()
    (sym_dir / "ab.py").write_text(
        "import sympy as sp\nu = sp.symbols('u1 u2')\npar = sp.symbols('p1 p2 p3')\n"
        "(u1, u2), (p1, p2, p3) = u, par\n"
        "f = [-u1 + p1 * (1 - u1) * sp.exp(u2),\n"
        "     -u2 + p1 * p2 * (1 - u1) * sp.exp(u2) - p3 * u2]\n"
        "def stpnt(u, par):\n    u[:] = 0.0\n    par[:3] = [0.0, 14.0, 2.0]\n")
    sym = load_python_problem("ab", sym_dir, 2)
    for jac, chosen in ((0, True), (1, True), (-1, False)):
        c = corrector_algebraic.compiled_corrector(system(sym, jac), s, 20.0)
        assert (c is not None) == chosen, jac


def test_python_jacobians_take_the_python_loops_steps(tmp_path, monkeypatch, cache):
    """plp (tests/data/plp/plp.py, JAC = 1: the user's dfdu and dfdp) on its equilibria:
    the compiled corrector calling the user's Jacobian and func back takes the Python
    loop's steps. Both solve the same bordered systems, LAPACK's GESV against the C
    elimination with the same pivots (the module docstring's tolerance of 1e-9 is what
    the two guarantee); on these 3 x 3 systems every correction came out the same bits
    (not a property of the method: AUTO's own GE pivots completely, another rounding
    still), so the b- and s-files are compared too, as the demo's files must not
    change by the choice of loop."""
    def one(sub):
        d = tmp_path / sub
        d.mkdir()
        shutil.copy(DEMOS / "plp" / "c.plp.ss", d)
        shutil.copy(DATA / "plp" / "plp.py", d)
        return run(d / "c.plp.ss", e="plp", sv="ss", verbose=False)
    fast, slow, used = fast_and_slow(monkeypatch, corrector_algebraic.CompiledCorrector,
                                     "correct", one)
    assert len(used) > 50 and all(used), used
    assert [(s.ty, s.lab) for s in fast.specials] == [(s.ty, s.lab) for s in slow.specials]
    assert_rows_agree(fast, slow, location_tolerance(DEMOS / "plp" / "c.plp.ss"))
    assert (fast.counters.residuals, fast.counters.jacobians, fast.counters.factorisations) \
        == (slow.counters.residuals, slow.counters.jacobians, slow.counters.factorisations)
    for f in ("b.ss", "s.ss"):
        assert (tmp_path / "fast" / f).read_bytes() == (tmp_path / "slow" / f).read_bytes()


def test_a_failing_python_jacobian_hands_over_to_the_python_loop(tmp_path, monkeypatch,
                                                                cache):
    """A dfdu that fails beyond PAR(4) = 3 (called back from C): the Python loop takes
    the step over and reports the failure as it does alone; the runs end the same."""
    def one(sub):
        d = tmp_path / sub
        d.mkdir()
        shutil.copy(DEMOS / "plp" / "c.plp.ss", d)
        (d / "plp.py").write_text((DATA / "plp" / "plp.py").read_text() + (
            "\n_dfdu = dfdu\n\n\ndef dfdu(u, par):\n    if par[3] > 3.0:\n"
            "        raise ValueError('outside the model')\n    return _dfdu(u, par)\n"))
        return run(d / "c.plp.ss", e="plp", sv="ss", verbose=False)
    fast, slow, used = fast_and_slow(monkeypatch, corrector_algebraic.CompiledCorrector,
                                     "correct", one)
    assert "outside the model" in fast.status and not all(used)
    assert fast.status == slow.status.replace("/slow/", "/fast/")
    np.testing.assert_allclose([r.values for r in fast.rows], [r.values for r in slow.rows],
                               rtol=1e-9, atol=1e-12)


def _ab_system(problem, settings):
    from washer.cont.system import StartData
    from washer.cont.systems.equilibrium import EquilibriumSystem
    u, par = problem.start(36)
    return EquilibriumSystem(StartData(problem=problem, settings=settings, u=u, par=par))


def test_no_c_compiler_keeps_the_python_loop_and_other_errors_propagate(monkeypatch, cache):
    """Python equations need ae_callback.c compiled: where that cannot be done
    (CompileError: no compiler, a failed compile) the Python loop runs; any other error
    of the set-up is raised, not taken for a missing compiler. A failed build is
    remembered: the next run's start does not compile again."""
    from washer.cont.user_problem import c_library as compile_module
    from washer.cont.user_problem.c_library import CompileError
    from washer.cont.settings import Settings
    from washer.cont.user_problem.user_files import load_python_problem
    s = Settings(NDIM=2, ICP=[1], IPS=1)
    monkeypatch.setenv("WASHER_TRACE", "0")      # ab.py's func in Python (the call back)
    system = _ab_system(load_python_problem("ab", DATA / "ab", 2), s)
    monkeypatch.setattr(corrector_algebraic, "_libraries", {})
    monkeypatch.setattr(corrector_algebraic, "_failures", {})
    builds = []

    def no_compiler(*a, **k):
        builds.append(1)
        raise CompileError("no c compiler: 'cc' is not on PATH")
    monkeypatch.setattr(compile_module, "build_library", no_compiler)
    assert corrector_algebraic.compiled_corrector(system, s, 20.0) is None
    assert corrector_algebraic.compiled_corrector(system, s, 20.0) is None
    assert len(builds) == 1

    monkeypatch.setattr(corrector_algebraic, "_failures", {})

    def broken(*a, **k):
        raise TypeError("a bug, not a missing compiler")
    monkeypatch.setattr(compile_module, "build_library", broken)
    with pytest.raises(TypeError, match="a bug"):
        corrector_algebraic.compiled_corrector(system, s, 20.0)


def test_a_work_layout_out_of_step_with_c_fails_loudly(cache, monkeypatch):
    """The call back reads the points through views of the C corrector's work array: if
    the pointers C passes are not where the views start (a layout changed on one side
    only), the correction raises instead of reading other numbers as the points."""
    from washer.cont.branch import Counters
    from washer.cont.settings import Settings
    from washer.cont.user_problem.user_files import load_python_problem
    s = Settings(NDIM=2, ICP=[1], IPS=1)
    monkeypatch.setenv("WASHER_TRACE", "0")      # ab.py's func in Python (the call back)
    system = _ab_system(load_python_problem("ab", DATA / "ab", 2), s)
    corrector = corrector_algebraic.compiled_corrector(system, s, 20.0)
    x0, _ = system.start()
    t = np.array([1.0, 14 / 3, 1.0])      # the branch's tangent at 0: u = PAR(1) (1, 14/3)
    x_pred = x0 + 0.01 * t / np.linalg.norm(t)
    assert corrector.correct(x_pred, x0, 0.01, Counters()) is not None   # in step: runs
    eq = corrector.user
    us, ps, fs = eq._where[0]
    eq._where = [(ps, us, fs)]           # C's ps where the views read us
    with pytest.raises(corrector_algebraic.WorkLayoutError):
        corrector.correct(x_pred, x0, 0.01, Counters())


def test_fixed_points_of_maps_keep_the_python_loop():
    """Only a system whose residual is the problem's f itself declares it
    (residual_is_func): equilibria do, the fixed points of f^k (f^k(u) - u) do not."""
    from washer.cont.systems.equilibrium import EquilibriumSystem
    from washer.cont.systems.maps import FixedPoints
    assert EquilibriumSystem.residual_is_func is True
    assert FixedPoints.residual_is_func is False


def test_an_error_of_the_call_back_itself_is_raised(cache, monkeypatch):
    """Only the user's func failing hands a correction over to the Python loop: an
    error in the call back's own code is raised, not hidden behind a Python-loop step."""
    from washer.cont.branch import Counters
    from washer.cont.settings import Settings
    from washer.cont.user_problem.user_files import load_python_problem
    s = Settings(NDIM=2, ICP=[1], IPS=1)
    monkeypatch.setenv("WASHER_TRACE", "0")      # ab.py's func in Python (the call back)
    system = _ab_system(load_python_problem("ab", DATA / "ab", 2), s)
    corrector = corrector_algebraic.compiled_corrector(system, s, 20.0)
    x0, _ = system.start()
    t = np.array([1.0, 14 / 3, 1.0])
    corrector.user._views = None          # a bug of the bridge: no views to read
    with pytest.raises(TypeError):
        corrector.correct(x0 + 0.01 * t / np.linalg.norm(t), x0, 0.01, Counters())




@pytest.mark.parametrize("kind", ["f90", "py"])
@pytest.mark.parametrize("name, label, ov", [("ab", "HB1", AB2), ("ab", "LP1", AB2),
                                             ("lrz", "HB1", LRZ2)])
def test_compiled_corrector_follows_the_python_loop_on_loci(name, label, ov, kind, tmp_path,
                                                            monkeypatch, cache):
    """The fold and Hopf curves from ab's LP1 and HB1 and lrz's HB1 (the extended systems
    of systems/fold.py and hopf.py in C): every step through C, the same points, special
    points (ab's GH, the UZ values) and evaluations (to one location trial) as the Python
    loop. Both start from one and the same equilibria's run (its located LP1 and HB1
    depend on the eliminations' rounding, see assert_rows_agree). The converged points
    agree within EPSU = 1e-7 relative (the two eliminations round differently; a located
    point iterates on them, and the curve continues from it): ab's to 2e-9, lrz's to
    4e-8."""
    eq = _folder(tmp_path, name, "eq", kind)
    run(eq / f"c.{name}", verbose=False, sv="eq")

    def locus(sub):
        d = _folder(tmp_path, name, sub, kind)
        for f in ("b.eq", "s.eq", "d.eq"):
            shutil.copy(eq / f, d)
        return run(d / f"c.{name}", verbose=False, sv="locus", s="eq", IRS=label, **ov)
    # the locus's corrections only (kind 0 is the equilibria's run before it)
    fast, slow, used = fast_and_slow(monkeypatch, corrector_algebraic.CompiledCorrector,
                                     "correct", locus, counts=lambda c: c.kind)
    assert len(used) > 80 and all(used)
    assert [(s.ty, s.lab) for s in fast.specials] == [(s.ty, s.lab) for s in slow.specials]
    if name == "ab" and label == "HB1":
        assert [s.ty for s in fast.specials].count("GH") == 1          # ab's GH
    constants = DATA / name / f"c.{name}"
    assert_rows_agree(fast, slow, location_tolerance(constants, **ov), rtol=1e-7)
    # the same steps; where a location iterates on values that round otherwise (ab's GH
    # on l1, a difference of O(1) terms near 0) it may take other trials: up to ITMX + 1
    # of them a located point, each up to ITNW corrections and the trial's own Jacobian
    assert_counts_agree(fast, slow, constants, **ov)
    assert fast.status == slow.status


def test_work_size_is_the_c_one(cache):
    """corrector_algebraic.work_size allocates what ae_correct.h's ae_work_size uses, for
    every system (a smaller array would be written past its end)."""
    _, lib = corrector_algebraic._library("ae_callback.c", corrector_algebraic._CALLBACK_CDEF)
    for kind in (0, 1, 2):
        for n in (1, 2, 3, 12):
            for npar in (3, 36):
                assert lib.washer_ae_work_size(kind, n, npar) == \
                    corrector_algebraic.work_size(kind, n, npar)


def test_map_loci_keep_the_python_loop():
    """The loci of maps (f^k - u) inherit the fold system's equations but not its
    compiled form; the flows' fold and Hopf loci declare theirs."""
    from washer.cont.systems.fold import FoldSystem
    from washer.cont.systems.hopf import HopfSystem
    from washer.cont.systems.maps import MapFoldLocus, MapPDLocus
    assert FoldSystem.compiled_system == "fold" and HopfSystem.compiled_system == "hopf"
    assert MapFoldLocus.compiled_system is None and MapPDLocus.compiled_system is None


@pytest.mark.parametrize("kind", ["f90", "py"])
@pytest.mark.parametrize("name", ["ab", "lrz"])
def test_compiled_first_lyapunov_is_normal_forms(name, kind, tmp_path, monkeypatch, cache):
    """The GH test on the Hopf curves of ab and lrz computed in C (ae_lyapunov.h, where the
    compiled corrector runs the locus) against normal_form.first_lyapunov at every point
    it is asked for: equal to rounding where l1 is well above its noise (median 1e-15
    relative);
    1e-7 absolute in all, the size of l1's own difference noise (third differences with
    h = 4e-3: eps |f| / h^3 ~ 2e-9 of f, which the rounding of q's components moves) and
    well below ab's |l1| away from its GH."""
    from washer.cont.normal_form import first_lyapunov
    pairs = []
    real = corrector_algebraic.CompiledCorrector.first_lyapunov

    def spy(self, problem, x, p, omega, A=None):
        value = real(self, problem, x, p, omega, A)
        pairs.append((value, first_lyapunov(problem, x, p, omega, A)))
        return value
    monkeypatch.setattr(corrector_algebraic.CompiledCorrector, "first_lyapunov", spy)
    d = _folder(tmp_path, name, "l1", kind)
    run(d / f"c.{name}", verbose=False, sv="eq")
    out = run(d / f"c.{name}", verbose=False, sv="hb", s="eq", IRS="HB1",
              **(AB2 if name == "ab" else LRZ2))
    c, py = np.array(pairs).T
    assert len(pairs) > 90
    np.testing.assert_allclose(c, py, rtol=0, atol=1e-7)
    big = np.abs(py) > 1e-6                 # far above the noise (lrz's l1 is ~1e-4)
    assert big.sum() > 80
    assert np.median(np.abs(c - py)[big] / np.abs(py[big])) < 1e-13
    if name == "ab":
        assert [s.ty for s in out.specials].count("GH") == 1


def test_l1_work_size_is_the_c_one(cache):
    """corrector_algebraic.l1_work_size allocates what ae_lyapunov.h's ae_l1_work_size uses."""
    _, lib = corrector_algebraic._library("ae_callback.c", corrector_algebraic._CALLBACK_CDEF)
    for n in (1, 2, 3, 12):
        for npar in (3, 36):
            assert lib.washer_ae_l1_work_size(n, npar) == corrector_algebraic.l1_work_size(n, npar)


def test_failing_func_on_a_locus_hands_over_to_the_python_loop(tmp_path, monkeypatch, cache):
    """ab.py failing beyond PAR(1) = 0.2 on the Hopf curve from HB1 (called back from C for
    f_u's stencil, the second differences and l1's batches alike): the Python loop takes
    the failing steps over and reports as it does alone; the two runs end the same."""
    def hopf_curve(sub):
        d = _failing_ab(tmp_path / sub, "(par[0] > 0.2).any()")
        run(d / "c.ab", verbose=False, sv="eq")
        return run(d / "c.ab", verbose=False, sv="hb", s="eq", IRS="HB1", **AB2)
    fast, slow, _ = fast_and_slow(monkeypatch, corrector_algebraic.CompiledCorrector, "correct",
                                  hopf_curve)
    assert "outside the model" in fast.status
    assert fast.status == slow.status.replace("/slow/", "/fast/")
    assert len(fast.rows) == len(slow.rows) > 50
    np.testing.assert_allclose([r.values for r in fast.rows], [r.values for r in slow.rows],
                               rtol=1e-7, atol=1e-7)
