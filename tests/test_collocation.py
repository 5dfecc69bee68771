"""The collocation numerics (washer.cont.collocation) against AUTO's tables and
closed forms: weights, quadrature, interpolation, mesh adaptation, Floquet
multipliers of a linear periodic system, and the superconvergence of the period."""
import math

import numpy as np
import pytest

from washer.cont import collocation as col
from washer.cont import reduction
from washer.cont.floquet import pencil_multipliers

from test_reduction import random_jacobian       # a collocation Jacobian with random entries


# ---------------------------------------------------------------- weights (AUTO tables)

def test_gauss_points_match_autos_cpnts_for_ncol_4():
    # CPNTS, NCOL = 4: 0.5 -+ 0.5 sqrt(3/7 +- c4), c4 = 0.5 sqrt((6/7)^2 - 12/35) ... written
    # out in AUTO as C41/C42; the Gauss points of degree 4 are the roots of P4.
    r = 6 / 7
    c4 = 0.5 * math.sqrt(r ** 2 - 12 / 35)
    c41, c42 = 0.5 * math.sqrt(3 / 7 + c4), 0.5 * math.sqrt(3 / 7 - c4)
    np.testing.assert_allclose(col.gauss_points(4), [0.5 - c41, 0.5 - c42, 0.5 + c42, 0.5 + c41],
                               rtol=0, atol=1e-15)


@pytest.mark.parametrize("ncol,table", [
    (2, [1 / 6, 4 / 6, 1 / 6]),
    (3, [1 / 8, 3 / 8, 3 / 8, 1 / 8]),
    (4, [7 / 90, 32 / 90, 12 / 90, 32 / 90, 7 / 90]),
    (5, [19 / 288, 25 / 96, 25 / 144, 25 / 144, 25 / 96, 19 / 288]),
    (6, [41 / 840, 9 / 35, 9 / 280, 34 / 105, 9 / 280, 9 / 35, 41 / 840]),
    (7, [751 / 17280, 3577 / 17280, 49 / 640, 2989 / 17280, 2989 / 17280, 49 / 640,
         3577 / 17280, 751 / 17280]),
])
def test_integration_weights_are_autos_wint(ncol, table):
    np.testing.assert_allclose(col.integration_weights(ncol), table, rtol=1e-13)


@pytest.mark.parametrize("ncol", [2, 3, 4, 5, 6, 7])
def test_lagrange_weights_reproduce_polynomials(ncol):
    """WT interpolates and WP differentiates every polynomial of degree <= NCOL exactly."""
    WT, WP = col.lagrange_weights(ncol)
    z = col.gauss_points(ncol)
    nodes = np.arange(ncol + 1) / ncol
    for deg in range(ncol + 1):
        np.testing.assert_allclose(nodes ** deg @ WT, z ** deg, atol=1e-12)
        np.testing.assert_allclose(nodes ** deg @ WP, deg * z ** max(deg - 1, 0) if deg else 0,
                                   atol=1e-11)


def test_node_weights_integrate_piecewise_polynomials_exactly():
    rng = np.random.default_rng(1)
    tm = np.r_[0, np.sort(rng.uniform(0, 1, 6)), 1]
    mesh = col.Mesh(tm, 4)
    t = mesh.node_times()
    assert t[0] == 0 and t[-1] == 1 and len(t) == 7 * 4 + 1
    # a global polynomial of degree 4 is a piecewise one: integral exact
    g = 3 * t ** 4 - t ** 3 + 2 * t - 0.5
    assert abs(mesh.node_weights() @ g - (3 / 5 - 1 / 4 + 1 - 0.5)) < 1e-14


def test_interpolation_is_exact_for_the_piecewise_polynomial():
    rng = np.random.default_rng(2)
    mesh = col.Mesh(np.r_[0, np.sort(rng.uniform(0, 1, 9)), 1], 3)
    t = mesh.node_times()
    U = np.c_[np.cos(2 * np.pi * t), t ** 3]          # second column: a cubic, exact
    tm_new = np.linspace(0, 1, 8) ** 1.3
    V = col.interpolate(mesh, U, tm_new, 5)
    tn = col.Mesh(tm_new, 5).node_times()
    np.testing.assert_allclose(V[:, 1], tn ** 3, atol=1e-13)
    # the cosine within the cubic interpolation bound max|f''''| / 4! * max|prod(t - t_i)|,
    # with max|s (s - 1)(s - 2)(s - 3)| = 1 on [0, 3] for node spacing h / 3
    bound = (2 * np.pi) ** 4 / 24 * (np.max(mesh.dtm) / 3) ** 4
    assert np.max(np.abs(V[:, 0] - np.cos(2 * np.pi * tn))) < bound


def test_new_mesh_concentrates_where_the_profile_is_steep():
    """EQDF/NEWMSH: a profile with a sharp pulse near t = 0.3 gets small intervals there."""
    mesh = col.Mesh.uniform(40, 4)
    t = mesh.node_times()
    U = np.exp(-((t - 0.3) / 0.03) ** 2)[:, None]
    tm = col.new_mesh(mesh, U, 40)
    dt = np.diff(tm)
    assert tm[0] == 0 and tm[-1] == 1 and np.all(dt > 0)
    # 30 of the 39 interior points within the pulse's +-0.15 (uniform: 12)
    assert np.sum((tm > 0.15) & (tm < 0.45)) >= 30


def test_new_mesh_keeps_a_uniform_mesh_for_a_polynomial_of_low_degree():
    """'Small derivative' case of EQDF: NCOL-th derivative 0 -> uniform mesh."""
    mesh = col.Mesh.uniform(10, 4)
    t = mesh.node_times()
    tm = col.new_mesh(mesh, (t ** 2)[:, None], 10)
    np.testing.assert_allclose(tm, np.linspace(0, 1, 11), atol=1e-14)


# ---------------------------------------------------------------- Floquet multipliers

def _linear_blocks(A_of_t, T, mesh):
    """Collocation blocks of y' = T A(t) y on `mesh`."""
    coll = col.Collocation(mesh, A_of_t(0.0).shape[0])
    z = col.gauss_points(mesh.ncol)
    tg = mesh.tm[:-1, None] + mesh.dtm[:, None] * z[None, :]
    A = np.array([[A_of_t(t) for t in row] for row in tg])
    return coll.local_blocks(T, A)


def test_monodromy_of_a_constant_linear_system():
    """y' = T A y on [0, 1]: monodromy exp(T A); multipliers exp(T lambda_i). The
    collocation error of the exponential on 20 x 4 is far below the 1e-9 asserted."""
    A = np.array([[-0.3, 2.0, 0.0], [-2.0, -0.3, 0.0], [0.0, 0.0, 0.7]])
    T = 1.7
    mesh = col.Mesh.uniform(20, 4)
    P0, P1 = reduction.floquet_pair(_linear_blocks(lambda t: A, T, mesh), 3)
    M = -np.linalg.solve(P1, P0)
    import scipy.linalg
    np.testing.assert_allclose(M, scipy.linalg.expm(T * A), atol=1e-9)
    mu = pencil_multipliers(P0, P1)
    expect = np.exp(T * np.linalg.eigvals(A))
    for m in expect:
        assert np.min(np.abs(mu - m)) < 1e-9


def _gauss_collocation_growth(z: float, m: int) -> float:
    """The factor by which collocation at m Gauss points takes y' = lambda y over one
    interval with z = h lambda: the (m, m) Pade approximant of e^z (collocation at Gauss
    points is the Gauss-Legendre Runge-Kutta method, whose stability function it is)."""
    def p(x):
        return sum(math.factorial(2 * m - k) * math.factorial(m)
                   / (math.factorial(2 * m) * math.factorial(k) * math.factorial(m - k)) * x ** k
                   for k in range(m + 1))
    return p(z) / p(-z)


def test_huge_multipliers_do_not_overflow():
    """A multiplier near e^600 (lrz near its homoclinic orbit has such): the pencil keeps
    it finite without overflow warnings, and the others stay accurate. The discrete
    equations' own multiplier on 100 intervals of 4 Gauss points is R_44(6)^100 = e^527.8
    (R_44 the (4, 4) Pade approximant of exp: one interval's step h T lambda = 6 is far
    outside the collocation's accuracy), which the condensation must give: the
    continuous e^600 is not the discrete problem's."""
    A = np.diag([20.0, -1.0, 0.0])
    T = 30.0
    mesh = col.Mesh.uniform(100, 4)
    P0, P1 = reduction.floquet_pair(_linear_blocks(lambda t: A, T, mesh), 3)
    mu = pencil_multipliers(P0, P1)
    assert abs(mu[0] - 1) < 1e-12                      # the zero exponent: mu = 1
    big = mu[-1]
    exact_log = 100 * math.log(_gauss_collocation_growth(20.0 * T / 100, 4))   # 527.8
    assert abs(math.log(abs(big)) / exact_log - 1) < 1e-3
    assert abs(mu[1] - math.exp(-30)) < 1e-9 * math.exp(-30)


def test_multipliers_of_a_time_periodic_linear_system():
    """y' = T A(t) y with A(t) = R(t) B R(t)^T, R the rotation by 2 pi t: in rotating
    coordinates w = R^T y, w' = T (B - S/T) w with S = 2 pi [[0,-1],[1,0]], so the
    monodromy is exp(T B - S) and the multipliers its eigenvalues (closed form)."""
    B = np.array([[-0.5, 1.0], [0.2, -1.0]])
    T = 2.3
    S = 2 * np.pi * np.array([[0.0, -1.0], [1.0, 0.0]])

    def R(t):
        c, s = math.cos(2 * math.pi * t), math.sin(2 * math.pi * t)
        return np.array([[c, -s], [s, c]])

    mesh = col.Mesh.uniform(40, 4)
    P0, P1 = reduction.floquet_pair(_linear_blocks(lambda t: R(t) @ B @ R(t).T, T, mesh), 2)
    import scipy.linalg
    expect = np.linalg.eigvals(scipy.linalg.expm(T * B - S))
    mu = pencil_multipliers(P0, P1)
    for m in expect:
        assert np.min(np.abs(mu - m)) < 1e-9 * max(1, abs(m))


@pytest.mark.parametrize("general_bc", [False, True])
def test_jacobians_on_one_mesh_are_scipys_matrices_with_their_own_values(general_bc):
    """jacobian_general builds the first Jacobian of a mesh with scipy and the next ones
    as copies of its pattern: each must be the matrix scipy's constructor gives from the
    same values (dense comparison, products, a CSC matrix of the right shape), and an
    earlier Jacobian must keep its values when a later one is assembled."""
    import scipy.sparse as sp
    rng = np.random.default_rng(11)
    n, N, m, nint = 3, 7, 4, 1
    coll = col.Collocation(col.Mesh.uniform(N, m), n, nint=nint, general_bc=general_bc)
    mats, dense = [], []
    for k in range(3):
        J = random_jacobian(coll, rng, 1.0 + k)
        ref = sp.csc_matrix((J.assembly[1][coll._order], coll._indices, coll._indptr),
                            shape=(coll.n_eq, coll.n_x))
        assert sp.isspmatrix_csc(J) and J.shape == ref.shape and coll.has_pattern(J)
        np.testing.assert_array_equal(J.toarray(), ref.toarray())
        v = rng.standard_normal(coll.n_x)
        np.testing.assert_array_equal(J @ v, ref @ v)
        mats.append(J)
        dense.append(ref.toarray())
    for J, D in zip(mats, dense):
        np.testing.assert_array_equal(J.toarray(), D)
    assert not np.array_equal(dense[0], dense[1])
    # a changed copy keeps the pattern and its own values reach the factorisation's pieces
    from washer.cont import reduction
    J2 = mats[0].copy()
    J2.data[:] = rng.standard_normal(J2.nnz)
    assert coll.has_pattern(J2) and not coll.has_pattern(J2[:, :-1])
    border = rng.standard_normal(coll.n_x)
    for got, want in zip(reduction.pieces(coll, J2, border),
                         reduction.pieces(coll, _reassembled(coll, J2), border)):
        np.testing.assert_array_equal(got, want)


def _reassembled(coll, J):
    """J rebuilt by scipy from its dense values on coll's pattern (no `assembly`)."""
    import scipy.sparse as sp
    D = J.toarray()
    rows = coll._indices
    cols = np.repeat(np.arange(coll.n_x), np.diff(coll._indptr))
    return sp.csc_matrix((D[rows, cols], coll._indices.copy(), coll._indptr.copy()),
                         shape=J.shape)


def test_interval_lengths_follow_the_mesh_when_tm_changes_in_place():
    """Mesh.dtm is kept between calls (every residual asks for it); a tm changed in place
    (as the restart reader does) must give the new lengths, and the kept array is
    read-only so no caller can change it for the next."""
    mesh = col.Mesh(np.array([0.0, 0.25, 0.5, 1.0]), 4)
    np.testing.assert_array_equal(mesh.dtm, [0.25, 0.25, 0.5])
    assert mesh.dtm is mesh.dtm and not mesh.dtm.flags.writeable
    mesh.tm[-1] = 0.75
    np.testing.assert_array_equal(mesh.dtm, [0.25, 0.25, 0.25])
    mesh.tm = np.array([0.0, 0.5, 1.0])
    np.testing.assert_array_equal(mesh.dtm, [0.5, 0.5])


def test_node_times_follow_the_mesh_and_are_the_callers_own():
    """Mesh.node_times is kept per mesh: the value for a tm changed in place is new, and
    every caller gets its own array (a record may change its t column)."""
    mesh = col.Mesh(np.array([0.0, 0.5, 1.0]), 2)
    t = mesh.node_times()
    np.testing.assert_array_equal(t, [0.0, 0.25, 0.5, 0.75, 1.0])
    t[:] = -1.0
    np.testing.assert_array_equal(mesh.node_times(), [0.0, 0.25, 0.5, 0.75, 1.0])
    mesh.tm[1] = 0.25
    np.testing.assert_array_equal(mesh.node_times(), [0.0, 0.125, 0.25, 0.625, 1.0])
    mesh.ncol = 1
    np.testing.assert_array_equal(mesh.node_times(), [0.0, 0.25, 1.0])
