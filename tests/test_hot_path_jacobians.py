"""The corrector's Jacobians on the hot path: what is taken from a shortcut must be what
the general evaluation gives.

* Small finite-difference stencils are evaluated call by call with the stencil built in
  Python floats (`Problem._jacobian_by_calls`): bit for bit the quotients of the array
  stencil that a batched func gets.
* The collocation's f_p comes from the user's batched dfdp when JAC = 1 (the washer's
  kernel returns it with f_u): exactly that column, and within the difference
  quotient's error of central differences.
"""
import importlib.util
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.cont.linalg import SMALL, all_finite
from washer.cont.problem import Problem
from washer.cont.systems.bvp import VectorField

from test_periodic import lw       # the closed-form Hopf normal form the periodic tests continue


def _demo_func(name: str):
    """func of tests/data/NAME/NAME.py, an AUTO demo's equations in Python."""
    path = Path(__file__).parent / "data" / name / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"demo_{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.func


ab = _demo_func("ab")
chua = _demo_func("chu")          # Chua's circuit: arctan, not just + - * /


def test_small_stencil_jacobian_equals_the_batched_stencil_bit_for_bit():
    plain = Problem(2, ab, npar=3)
    batched = Problem(2, ab, npar=3,
                      func_batch=lambda us, ps: np.array([ab(u, p) for u, p in zip(us, ps)]))
    rng = np.random.default_rng(7)
    for _ in range(50):
        u = rng.normal(size=2) * 10 ** rng.uniform(-3, 1)
        par = rng.normal(size=3) * 5
        for idx in ([1], [2, 1], [3]):
            assert np.array_equal(plain.jacobian(u, par, idx), batched.jacobian(u, par, idx))
        assert np.array_equal(plain.dfdu(u, par), batched.dfdu(u, par))


def lw_dfdp_batch(us, pars):
    """d f / d PAR at k points, (k, 2, NPAR): only PAR(1) = mu and PAR(2) = omega enter
    linearly (the others through th, not needed here)."""
    us, pars = np.asarray(us), np.asarray(pars)
    out = np.zeros((len(us), 2, pars.shape[1]))
    x, y = us[:, 0], us[:, 1]
    out[:, 0, 0], out[:, 1, 0] = x, y                 # d/d mu
    out[:, 0, 1], out[:, 1, 1] = -y, x                # d/d omega
    return out


def test_collocation_fp_takes_the_batched_dfdp_with_jac_1():
    rng = np.random.default_rng(3)
    U = rng.normal(size=(40, 2))
    par = np.r_[0.3, 1.0, 0.5, 0.8, np.zeros(8)]
    analytic = VectorField(Problem(2, lw, dfdp_batch=lw_dfdp_batch, jac=1), 2)
    differenced = VectorField(Problem(2, lw, dfdp_batch=lw_dfdp_batch, jac=0), 2)
    for index in (1, 2):
        exact = lw_dfdp_batch(U, np.broadcast_to(par, (40, 12)))[:, :, index - 1]
        assert np.array_equal(analytic.fp(U, par, index), exact)
        # JAC = 0 keeps AUTO's central differences (error ~1e-9 relative here)
        assert np.allclose(differenced.fp(U, par, index), exact, rtol=0, atol=1e-7)


def test_washer_batched_dfdp_is_the_pointwise_kernel_jp():
    """e='washer': dfdp_batch (the kernel's Jp from the jac_rot_batch call that gives
    f_u) equals the per-point dfdp (jac_rot's Jp, the tied dampers summed into C_p) and
    central differences of f in C_p to the quotient's error; f_u from the shared call is
    the per-point one."""
    from washer.problems.rotating import rotating_problem
    prob = rotating_problem().with_jac(1)
    u0, par0 = prob.start(17)
    rng = np.random.default_rng(5)
    us = u0 + 1e-3 * rng.normal(size=(6, 12))
    pars = np.repeat(par0[None, :], 6, axis=0)
    pars[:, 0] += np.linspace(0.0, 0.05, 6)
    Jp = prob.dfdp_many(us, pars, 1)
    fu = prob.dfdu_many(us, pars)
    for k in range(6):
        assert np.allclose(Jp[k], prob.dfdp(us[k], pars[k], [1])[:, 0], rtol=1e-12, atol=1e-12)
        assert np.allclose(fu[k], prob.dfdu(us[k], pars[k]), rtol=1e-12, atol=1e-12)
        h = 1e-6 * (1 + abs(pars[k, 0]))
        pp, pm = pars[k].copy(), pars[k].copy()
        pp[0] += h
        pm[0] -= h
        fd = (prob.func(us[k], pp) - prob.func(us[k], pm)) / (2 * h)
        assert np.allclose(Jp[k], fd, rtol=1e-6, atol=1e-6 * np.max(np.abs(fd)))


def test_washer_f_with_its_jacobians_is_f_and_then_the_jacobians_are_the_kernels():
    """e='washer': f from the kernel pass that also gives f_u and f_p
    (func_many_with_jacobian, the collocation residual before its Jacobian) is
    func_many's bit for bit, and the Jacobians asked for next at the same points
    (answered from that pass) are jac_rot_batch's bit for bit; at other points they are
    evaluated afresh."""
    from washer.problems.rotating import rotating_problem
    prob = rotating_problem().with_jac(1)
    assert prob.has_func_dfdu_batch
    u0, par0 = prob.start(17)
    rng = np.random.default_rng(7)
    us = u0 + 1e-3 * rng.normal(size=(9, 12))
    pars = np.repeat(par0[None, :], 9, axis=0)
    pars[:, 0] += np.linspace(0.0, 0.05, 9)
    f = prob.func_many_with_jacobian(us, pars)
    fu, fp = prob.dfdu_many(us, pars), prob.dfdp_many(us, pars, 1)
    other = us + 1e-4
    fu_other = prob.dfdu_many(other, pars)
    assert np.array_equal(f, prob.func_many(us, pars))
    assert np.array_equal(fu, prob.dfdu_many(us + 0.0, pars.copy()))
    fresh = rotating_problem().with_jac(1)
    assert np.array_equal(fu, fresh.dfdu_many(us, pars))
    assert np.array_equal(fp, fresh.dfdp_many(us, pars, 1))
    assert np.array_equal(fu_other, fresh.dfdu_many(other, pars))
    assert not np.array_equal(fu_other, fu)


def test_washer_pass_computes_the_f_p_columns_asked_for_with_the_same_values():
    """e='washer': once a column of f_p has been asked for alone (dfdp_many: Newton's
    free parameter), the kernel pass that gives f with its Jacobians computes that
    column only (the generated derivatives' pmask); f, f_u and that column are the full
    pass's bit for bit, and a column not computed there (Omega, PAR(2)) is evaluated
    afresh when asked, to the full pass's values too. The kernel's restricted pass:
    the asked columns bit for bit, the others 0."""
    from washer.machine import kernel
    from washer.problems.rotating import rotating_problem
    prob = rotating_problem().with_jac(1)
    u0, par0 = prob.start(17)
    rng = np.random.default_rng(11)
    us = u0 + 1e-3 * rng.normal(size=(7, 12))
    pars = np.repeat(par0[None, :], 7, axis=0)
    full = rotating_problem().with_jac(1)
    ref_f = full.func_many_with_jacobian(us, pars)
    ref_fu = full.dfdu_many(us, pars)
    ref = {i: full.dfdp_many(us, pars, i) for i in (1, 2, 3)}
    prob.dfdp_many(us + 1e-4, pars, 1)        # PAR(1) asked for once: C_p and its tied dampers
    assert np.array_equal(prob.func_many_with_jacobian(us, pars), ref_f)
    assert np.array_equal(prob.dfdu_many(us, pars), ref_fu)
    for i in (1, 2, 3):
        assert np.array_equal(prob.dfdp_many(us, pars, i), ref[i]), i
    assert np.any(ref[2] != 0) and np.any(ref[3] != 0)
    P = np.asarray(kernel_params_of(par0))
    f, J, Jp = kernel.rhs_jac_rot_batch(us, P)
    f1, J1, Jp1 = kernel.rhs_jac_rot_batch(us, P, columns=[0, 4])
    assert np.array_equal(f1, f) and np.array_equal(J1, J)
    assert np.array_equal(Jp1[:, :, [0, 4]], Jp[:, :, [0, 4]])
    assert not np.any(np.delete(Jp1, [0, 4], axis=2))


def kernel_params_of(par):
    from washer.problems.parameters import _reference_params, kernel_parameters
    return kernel_parameters(_reference_params())[0](par)


def test_parameter_rows_are_the_view_broadcast_to_gives():
    """broadcast_rows (func_many's one parameter vector for k points) is the view
    np.broadcast_to gives: same values, row stride 0, read-only, whatever the input."""
    from washer.cont.problem import broadcast_rows
    par = np.array([0.5, -2.0, 3.25])
    frozen = par.copy()
    frozen.setflags(write=False)
    for p in (par, frozen, np.arange(10.0)[::3]):
        for k in (0, 1, 7):
            got, ref = broadcast_rows(p, k), np.broadcast_to(p, (k, len(p)))
            assert got.shape == ref.shape and got.strides == (0, 8)
            np.testing.assert_array_equal(got, ref)
            assert not got.flags.writeable
    par[1] = 9.0                              # a view: it follows its vector
    assert broadcast_rows(par, 2)[1, 1] == 9.0


def test_difference_quotient_in_a_parameter_leaves_the_kept_f_and_is_the_quotient():
    """VectorField.fp by central differences (JAC = 0) is the quotient of two func_many
    calls at PAR(i) +- h, and f at the iterate, kept for the PERIOD column, is still
    answered from the kept copy afterwards."""
    from washer.cont.differences import FD_STEP
    prob = Problem(2, ab, npar=3)
    field = VectorField(prob, 2)
    rng = np.random.default_rng(2)
    U, par = rng.standard_normal((40, 2)), np.array([0.1, 8.0, 3.0])
    f0 = field.f(U, par)
    h = FD_STEP * (1 + abs(par[0]))
    pp, pm = par.copy(), par.copy()
    pp[0] += h
    pm[0] -= h
    ref = (prob.func_many(U, pp) - prob.func_many(U, pm)) / (2 * h)
    np.testing.assert_array_equal(field.fp(U, par, 1), ref)
    calls = []
    prob.func_many = lambda *a: calls.append(a) or 0 / 0     # f must not be re-evaluated
    np.testing.assert_array_equal(field.f(U, par), f0)
    assert not calls


@pytest.mark.parametrize("func, ndim, par", [
    (ab, 2, [0.13, 8.0, 3.0]),
    (chua, 3, [-1.3, 14.3, 10.0, -1.0 / 7.0, 2.0 / 7.0]),
])
def test_one_stencil_for_f_u_and_f_p_is_the_separate_quotients(func, ndim, par):
    """VectorField.fu_fp sends f_u's and f_p's difference stencils to the user's func in
    one call: the same quotients as fu and fp computed apart (bit for bit here: numpy's
    arithmetic is elementwise), for one and for two parameters, and fu alone without
    parameters."""
    rng = np.random.default_rng(7)
    U = rng.standard_normal((100, ndim))
    par = np.array(par + [0.0] * 6)
    prob = Problem(ndim, func, npar=len(par))
    field = VectorField(prob, ndim)
    field.f(U[:3], par)                   # the first vectorised call's check, out of the way
    for indices in ([1], [2, 1], []):
        A, fps = field.fu_fp(U, par, indices)
        np.testing.assert_array_equal(A, field.fu(U, par))
        assert len(fps) == len(indices)
        for i, fp in zip(indices, fps):
            np.testing.assert_array_equal(fp, field.fp(U, par, i))
    calls = []
    real = prob.func_many
    prob.func_many = lambda us, ps: calls.append(len(us)) or real(us, ps)
    field.fu_fp(U, par, [1, 3])
    assert calls == [100 * (2 * ndim + 4)]
    # beyond FU_FP_ONE_CALL_MAX points: separate calls, the same values
    from washer.cont.systems.bvp import FU_FP_ONE_CALL_MAX
    big = rng.standard_normal((FU_FP_ONE_CALL_MAX + 1, ndim))
    calls.clear()
    A, (fp,) = field.fu_fp(big, par, [1])
    assert len(calls) == 3
    prob.func_many = real
    np.testing.assert_array_equal(A, field.fu(big, par))
    np.testing.assert_array_equal(fp, field.fp(big, par, 1))


def test_one_stencil_leaves_the_users_jacobians_alone():
    """With the user's f_u in use (JAC = 1) fu_fp is fu and fp: the analytic f_u."""
    def dfdu_batch(us, pars):
        return np.full((len(us), 2, 2), 7.0)
    prob = Problem(2, ab, npar=3, dfdu_batch=dfdu_batch, jac=1)
    field = VectorField(prob, 2)
    U, par = np.zeros((5, 2)), np.array([0.1, 8.0, 3.0])
    A, (fp,) = field.fu_fp(U, par, [1])
    assert np.all(A == 7.0)
    np.testing.assert_array_equal(fp, field.fp(U, par, 1))


def test_vectorised_func_is_checked_on_a_few_points_of_its_first_call():
    """A user func that takes (ndim, k) arrays is called once for a large stencil after
    its first call's first VECTORISE_CHECK points agree with separate calls; the values
    are the separate calls' (bit for bit here)."""
    from washer.cont.problem import VECTORISE_CHECK
    calls = []

    def counted(u, par):
        calls.append(np.ndim(u))
        return ab(u, par)
    prob = Problem(2, counted, npar=3)
    rng = np.random.default_rng(3)
    us, par = rng.standard_normal((500, 2)), np.array([0.2, 8.0, 3.0])
    F = prob.func_many(us, par)
    assert calls.count(1) == VECTORISE_CHECK and calls.count(2) == 1
    np.testing.assert_array_equal(F, np.array([ab(u, par) for u in us]))
    prob.func_many(us, par)
    assert calls.count(1) == VECTORISE_CHECK and calls.count(2) == 2


def test_a_small_stencil_is_one_call_compared_at_a_point_every_spot_every_calls():
    """A small stencil (STENCIL_MIN to VECTORISE_MIN - 1 points) of a func that takes
    (ndim, k) arrays is one call, its first call of each size compared with separate calls
    at every point, later calls at one point every SPOT_EVERY calls; the values are the
    separate calls' bit for bit, in the same C-order array."""
    from washer.cont.pointwise import SPOT_EVERY
    from washer.cont.problem import STENCIL_MIN, VECTORISE_MIN
    calls = []

    def counted(u, par):
        calls.append(np.ndim(u))
        return ab(u, par)
    prob = Problem(2, counted, npar=3)
    rng = np.random.default_rng(3)
    par = np.array([0.2, 8.0, 3.0])
    for k in (STENCIL_MIN, 7, VECTORISE_MIN - 1):
        us = rng.standard_normal((k, 2))
        calls.clear()
        F = prob.func_many(us, par)
        assert calls.count(1) == k and calls.count(2) == 1
        separate = np.array([ab(u, par) for u in us])
        np.testing.assert_array_equal(F, separate)
        assert F.flags.c_contiguous
        calls.clear()
        for _ in range(2 * SPOT_EVERY):
            np.testing.assert_array_equal(prob.func_many(us, par), separate)
        assert calls.count(2) == 2 * SPOT_EVERY and calls.count(1) == 2
    calls.clear()
    prob.func_many(rng.standard_normal((STENCIL_MIN - 1, 2)), par)
    assert calls == [1] * (STENCIL_MIN - 1)


def _sum_of_terms(u, par):
    """A pointwise f whose vectorised call differs from its separate calls in the last
    bits: np.sum over 9 terms is pairwise (eight partial sums) on a 1-D array, row after
    row over axis 0 of a (9, k) array: another order of the same additions."""
    terms = np.array([par[j] * u[0] ** j for j in range(9)])
    return np.array([np.sum(terms, axis=0), u[0] - u[1]])


def _last_bit_on_arrays(u, par):
    """ab's f, except that on arrays the first component is one unit in the last place
    larger where PAR(4) > 1: a difference that only calls at such points show."""
    f = ab(u, par)
    if np.ndim(u) == 2:
        f[0] = np.where(par[3] > 1, np.nextafter(f[0], np.inf), f[0])
    return f


def test_a_vectorised_call_differing_in_the_last_bit_is_refused():
    """A func pointwise on arrays whose vectorised values differ from separate calls' in
    the last bit only (np.sum's order) is refused at its first small stencil: func_many's values
    are the separate calls' bit for bit, then and afterwards, and the difference
    stencils (Problem.jacobian) are evaluated call by call."""
    rng = np.random.default_rng(11)
    us = rng.uniform(0.5, 2.0, size=(10, 2))
    par = rng.uniform(0.1, 1.0, size=9)
    separate = np.array([_sum_of_terms(u, par) for u in us])
    at_once = _sum_of_terms(us.T, np.broadcast_to(par, (10, 9)).T).T
    # the premise: the same values to rounding, not the same bits
    assert np.allclose(at_once, separate, rtol=1e-14, atol=0)
    assert not np.array_equal(at_once, separate)
    prob = Problem(2, _sum_of_terms, npar=9)
    assert not prob.stencil_by_calls(1)
    np.testing.assert_array_equal(prob.func_many(us, par), separate)
    assert prob.stencil_by_calls(1)              # refused for good
    calls = []
    prob._func = lambda u, p: calls.append(np.ndim(u)) or _sum_of_terms(u, p)
    np.testing.assert_array_equal(prob.func_many(us, par), separate)
    assert set(calls) == {1}


def test_a_difference_showing_only_at_later_points_is_refused_there():
    """Where the vectorised call equals separate calls at the first points and differs at
    later ones, the first call of each size is compared in full and later calls at one
    point every SPOT_EVERY calls: the first call that compares a point where they differ
    is evaluated point by point (its values the separate calls'), and so is every call
    after it."""
    from washer.cont.pointwise import SPOT_EVERY
    rng = np.random.default_rng(5)
    us = rng.uniform(0.1, 1.0, size=(7, 2))
    prob = Problem(2, _last_bit_on_arrays, npar=4)
    early = np.array([0.1, 8.0, 3.0, 0.0])
    late = np.array([0.1, 8.0, 3.0, 2.0])
    f_late = np.array([_last_bit_on_arrays(u, late) for u in us])
    assert not np.array_equal(_last_bit_on_arrays(us.T, np.broadcast_to(late, (7, 4)).T).T,
                              f_late)                                  # the premise
    for _ in range(3 * SPOT_EVERY):
        np.testing.assert_array_equal(prob.func_many(us, early),
                                      np.array([ab(u, early) for u in us]))
    assert not prob.stencil_by_calls(1)
    # calls at PAR(4) = 2: the vectorised values until one call compares a point, which
    # is evaluated point by point (the separate calls' values), and so is every call after
    for n in range(1, SPOT_EVERY + 1):
        got = prob.func_many(us, late)
        if prob.stencil_by_calls(1):
            break
        assert not np.array_equal(got, f_late)
    assert prob.stencil_by_calls(1) and n <= SPOT_EVERY
    np.testing.assert_array_equal(got, f_late)
    np.testing.assert_array_equal(prob.func_many(us, late), f_late)
    np.testing.assert_array_equal(prob.func_many(us + 1.0, early),
                                  np.array([ab(u, early) for u in us + 1.0]))


@pytest.mark.parametrize("kind", ["mixes points", "raises on arrays"])
def test_a_func_that_is_not_pointwise_on_arrays_is_called_point_by_point(kind):
    """A func that reduces over the whole batch (wrong with (ndim, k) arrays, and wrong
    on every point but by a different amount) or that raises on arrays is detected on
    the first call: its values are the separate calls', now and after."""
    def mixing(u, par):
        return np.array([u[0] / np.sum(np.abs(u)), u[1]])

    def scalar_only(u, par):
        if u[0] > 0:                      # ValueError with an array
            return np.array([u[0], u[1]])
        return np.array([-u[0], u[1]])
    fn = mixing if kind == "mixes points" else scalar_only
    prob = Problem(2, fn, npar=1)
    rng = np.random.default_rng(4)
    for k in (300, 40):
        us, par = rng.standard_normal((k, 2)), np.array([0.0])
        np.testing.assert_array_equal(prob.func_many(us, par),
                                      np.array([fn(u, par) for u in us]))


@pytest.mark.parametrize("size", [1, 7, SMALL, SMALL + 1, 300])
def test_all_finite_is_numpys_check_on_both_sides_of_its_python_path(size):
    """linalg.all_finite (the finite check of f and of small solves; Python numbers up to
    SMALL entries) says what np.isfinite(a).all() says, for real and complex arrays with a
    NaN, +inf or -inf anywhere and none, in 1-D and 2-D shapes, below and above SMALL."""
    rng = np.random.default_rng(size)
    for trial in range(60):
        a = rng.standard_normal(size) * 10.0 ** rng.integers(-100, 100)
        if trial % 4:
            a[rng.integers(size)] = (np.nan, np.inf, -np.inf)[trial % 3]
        for shaped in (a, a.reshape(1, -1), a * (1 - 2j)):
            assert all_finite(shaped) == bool(np.isfinite(shaped).all())


@pytest.mark.skipif(shutil.which("gfortran") is None, reason="gfortran is not installed")
@pytest.mark.parametrize("name", ["bvp", "lin", "stw"])
def test_a_python_demo_on_arrays_is_autos_func_bit_for_bit(name, tmp_path):
    """AUTO's demos bvp, lin and stw square in FUNC (`(PAR(1)*PI)**2`, `U(1)**2`: x * x
    in gfortran's code); their Python transcriptions (tests/data/bvp/NAME/NAME.py) write
    `** 2`, which numpy computes as a square on an array (x * x) and as libm's pow on a
    numpy scalar (pow(x, 2) is not x * x at about 0.08 % of doubles). A batch of 12
    points and more is one call on arrays (Problem.func_many): AUTO's compiled FUNC
    (tests/data/auto_demos/NAME/NAME.f90) bit for bit at every point, where separate
    calls on numpy scalars are not at some: why that rule is not the small stencils'
    bitwise comparison with separate calls, which would refuse these files' arrays."""
    from washer.cont.user_problem.user_files_native import load_compiled_problem
    from washer.cont.user_problem.user_files import load_python_problem
    data = Path(__file__).parent / "data"
    shutil.copy(data / "auto_demos" / name / f"{name}.f90", tmp_path)
    fortran = load_compiled_problem(tmp_path / f"{name}.f90", 2, name)
    python = load_python_problem(name, data / "bvp" / name, 2)
    rng = np.random.default_rng(1)
    us = rng.uniform(-2.0, 2.0, size=(20000, 2))
    pars = rng.uniform(0.1, 2.0, size=(20000, 36))
    auto = fortran.func_many(us, pars)
    np.testing.assert_array_equal(python.func_many(us, pars), auto)
    scalars = np.array([python.user_func(u, p) for u, p in zip(us, pars)])
    assert not np.array_equal(scalars, auto)
