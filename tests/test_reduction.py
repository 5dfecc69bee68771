"""The compiled factorisation of bordered collocation matrices (washer.cont.reduction,
AUTO's condensation of parameters and block reduction) against dense LAPACK on the
assembled matrix: solves, the determinant (sign and log-magnitude: the BP test of
cycles), and the Floquet pair against the null space of the collocation rows and
against the monodromy matrix propagated forward interval by interval
(collocation.fundamental_solution); the pair of the blocks alone (reduction.floquet_pair)
against the bordered factorisation's."""
import numpy as np
import pytest

from washer.cont import collocation as col
from washer.cont import floquet, reduction


def random_system(rng, N, m, n, npar):
    mn = m * n
    blocks = rng.standard_normal((N, mn, (m + 1) * n))
    parcols = rng.standard_normal((N, mn, npar))
    nx = (N * m + 1) * n + npar
    extra = rng.standard_normal((n + npar, nx))
    M = np.zeros((nx, nx))
    for j in range(N):
        M[j * mn:(j + 1) * mn, j * mn:j * mn + (m + 1) * n] = blocks[j]
        M[j * mn:(j + 1) * mn, nx - npar:] = parcols[j]
    M[N * mn:] = extra
    return blocks, parcols, extra, M


@pytest.mark.parametrize("N, m, n, npar", [(1, 1, 1, 0), (1, 3, 2, 2), (2, 1, 3, 1),
                                           (7, 4, 3, 2), (12, 3, 2, 4), (5, 2, 4, 0)])
def test_solve_and_determinant_match_dense_lapack(N, m, n, npar):
    rng = np.random.default_rng(N * 100 + m * 10 + n)
    blocks, parcols, extra, M = random_system(rng, N, m, n, npar)
    f = reduction.BorderedCollocation(blocks, parcols, extra)
    rhs = rng.standard_normal(len(M))
    x = f.solve(rhs)
    # Relative to the conditioning of random matrices: LU with pivoting inside blocks
    # is backward stable enough for a residual at rounding level.
    assert np.linalg.norm(M @ x - rhs) <= 1e-10 * np.linalg.norm(M, 1) * np.linalg.norm(x)
    np.testing.assert_allclose(x, np.linalg.solve(M, rhs), rtol=1e-8, atol=1e-8)
    sign, logdet = np.linalg.slogdet(M)
    s2, l2 = f.sign_logdet()
    assert s2 == sign
    assert l2 == pytest.approx(logdet, rel=1e-10, abs=1e-9)


def test_floquet_pair_annihilates_the_collocation_null_space():
    rng = np.random.default_rng(3)
    N, m, n, npar = 9, 4, 3, 2
    blocks, parcols, extra, M = random_system(rng, N, m, n, npar)
    f = reduction.BorderedCollocation(blocks, parcols, extra)
    P0, P1 = f.floquet_pair()
    C = M[:N * m * n, :(N * m + 1) * n]              # collocation rows, parameters held
    _, s, Vt = np.linalg.svd(C)
    null = Vt[-n:]                                    # n-dimensional null space
    for v in null:
        u0, u1 = v[:n], v[N * m * n:]
        assert np.linalg.norm(P0 @ u0 + P1 @ u1) <= 1e-10 * np.linalg.norm(np.c_[P0, P1])
    assert np.linalg.matrix_rank(np.c_[P0, P1]) == n


def test_collocation_jacobian_against_superlu_and_forward_monodromy():
    """A Jacobian assembled by Collocation (a linear periodic system's blocks): the same
    Newton step as the sparse LU, the same determinant, the same multipliers as the
    monodromy matrix of the same discrete equations propagated forward
    (collocation.fundamental_solution, another elimination: the multipliers here are of
    modulus 0.2-0.8, where forward propagation loses nothing); the pair of the blocks
    alone (reduction.floquet_pair) is the bordered factorisation's to the bit (the
    pivots are chosen in the same columns)."""
    from washer.cont.linalg import SparseFactor
    rng = np.random.default_rng(11)
    n, N, m = 3, 20, 4
    mesh = col.Mesh.uniform(N, m)
    coll = col.Collocation(mesh, n)
    A = np.array([[-0.1, 2.0, 0.0], [-2.0, -0.1, 0.3], [0.0, -0.3, -1.0]])
    Ag = np.broadcast_to(A + 0.05 * rng.standard_normal((N, m, n, n)), (N, m, n, n))
    T = 1.7
    blocks = coll.local_blocks(T, Ag)
    dpar = rng.standard_normal((2, N, m, n))
    up_old = rng.standard_normal((mesh.n_nodes, n))
    J = coll.jacobian(T, blocks, dpar, up_old)
    border = rng.standard_normal(coll.n_x)
    f = reduction.BorderedCollocation.from_jacobian(coll, J, border)
    ref = SparseFactor(coll.bordered(J, border))
    rhs = rng.standard_normal(coll.n_x)
    np.testing.assert_allclose(f.solve(rhs), ref.solve(rhs), rtol=1e-9, atol=1e-11)
    s_ref, l_ref = ref.sign_logdet()
    s, l = f.sign_logdet()
    assert s == s_ref and l == pytest.approx(l_ref, rel=1e-11)
    mu = floquet.pencil_multipliers(*f.floquet_pair())
    P0, P1 = reduction.floquet_pair(blocks, n)
    assert np.array_equal(P0, f.floquet_pair()[0]) and np.array_equal(P1, f.floquet_pair()[1])
    mu_ref = floquet.sort_multipliers(np.linalg.eigvals(col.fundamental_solution(blocks, n)[-1]))
    # the same set (a complex pair ties in AUTO's order by modulus: compare sorted)
    key = lambda z: np.lexsort((z.imag, np.round(z.real, 8)))     # noqa: E731
    np.testing.assert_allclose(mu[key(mu)], mu_ref[key(mu_ref)], rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("general_bc, nint, m", [(False, 1, 4), (True, 3, 3), (False, 2, 2)])
def test_from_jacobian_is_the_factorisation_of_its_pieces(general_bc, nint, m):
    """from_jacobian's one compiled call (the pieces made from the assembled values in
    C++, cont_bvp_factor_values) factorises what `pieces` gives, to the bit: solves,
    determinant, Floquet pair."""
    rng = np.random.default_rng(17 + nint)
    n, N = 3, 7
    coll = col.Collocation(col.Mesh.uniform(N, m), n, nint=nint, general_bc=general_bc)
    J = random_jacobian(coll, rng, 0.9)
    border = rng.standard_normal(coll.n_x)
    f = reduction.BorderedCollocation.from_jacobian(coll, J, border)
    ref = reduction.BorderedCollocation(*reduction.pieces(coll, J, border))
    rhs = rng.standard_normal(coll.n_x)
    assert np.array_equal(f.solve(rhs), ref.solve(rhs))
    assert f.sign_logdet() == ref.sign_logdet()
    assert all(np.array_equal(a, b) for a, b in zip(f.floquet_pair(), ref.floquet_pair()))
    assert f.singular == ref.singular and f.shape == ref.shape


@pytest.mark.parametrize("general_bc", [False, True])
def test_collocation_jacobians_with_their_boundary_rows_against_superlu(general_bc):
    """Periodic boundary rows and general ones (B0 u(0) + B1 u(1) + Bp p, the loci of
    cycles), with three integral conditions: the dense rows come from the pattern."""
    from washer.cont.linalg import SparseFactor
    rng = np.random.default_rng(5)
    n, N, m, nint = 4, 9, 3, 3
    coll = col.Collocation(col.Mesh.uniform(N, m), n, nint=nint, general_bc=general_bc)
    J = random_jacobian(coll, rng, 1.3)
    border = rng.standard_normal(coll.n_x)
    f = reduction.BorderedCollocation.from_jacobian(coll, J, border)
    ref = SparseFactor(coll.bordered(J, border))
    rhs = rng.standard_normal(coll.n_x)
    np.testing.assert_allclose(f.solve(rhs), ref.solve(rhs), rtol=1e-9, atol=1e-11)
    assert f.sign_logdet()[0] == ref.sign_logdet()[0]
    assert f.sign_logdet()[1] == pytest.approx(ref.sign_logdet()[1], rel=1e-11)


def random_jacobian(coll, rng, T: float):
    """coll.jacobian_general with random entries: f_u blocks at period T, the parameter
    columns, the integral rows and, with coll.general_bc, boundary rows B0, B1, Bp."""
    n, N, m, nint = coll.ndim, coll.mesh.ntst, coll.mesh.ncol, coll.nint
    blocks = coll.local_blocks(T, rng.standard_normal((N, m, n, n)))
    dF = rng.standard_normal((nint + 1, N, m, n))
    int_u = rng.standard_normal((nint, coll.mesh.n_nodes, n))
    int_par = rng.standard_normal((nint, nint + 1))
    bc = (rng.standard_normal((n, n)), rng.standard_normal((n, n)),
          rng.standard_normal((n, nint + 1))) if coll.general_bc else None
    return coll.jacobian_general(blocks, dF, int_u, int_par, bc_jac=bc)


def random_general_system(rng, general_bc, nbc, nint):
    """A collocation Jacobian with random blocks, integral rows and (general_bc) boundary
    rows: NDIM 3, NTST 11, NCOL 4, NPAR = NBC + NINT - NDIM + 1 (IPS = 4). Returns
    (coll, J, n, npar)."""
    n, N, m = 3, 11, 4
    npar = nbc + nint - n + 1
    coll = col.Collocation(col.Mesh.uniform(N, m), n, nint=nint, general_bc=general_bc,
                           nbc=nbc, npar=npar)
    blocks = coll.local_blocks(0.9, rng.standard_normal((N, m, n, n)))
    bc = (rng.standard_normal((nbc, n)), rng.standard_normal((nbc, n)),
          rng.standard_normal((nbc, npar))) if general_bc else None
    J = coll.jacobian_general(blocks, rng.standard_normal((npar, N, m, n)),
                              rng.standard_normal((nint, coll.mesh.n_nodes, n)),
                              rng.standard_normal((nint, npar)), bc_jac=bc)
    return coll, J, n, npar


@pytest.mark.parametrize("general_bc, nbc, nint", [(False, 3, 1), (True, 3, 2), (True, 4, 0),
                                                    (True, 2, 1)])
def test_reduction_onto_the_start_node_is_the_sparse_schur_complement(general_bc, nbc, nint):
    """reduction.onto_start (forward substitution over the intervals) against the Schur
    complement formed with SuperLU on the assembled matrix; periodic and general
    boundary conditions, NBC = NDIM or not (IPS = 4: NPAR = NBC + NINT - NDIM + 1)."""
    import scipy.sparse.linalg as spla
    rng = np.random.default_rng(8)
    coll, J, n, npar = random_general_system(rng, general_bc, nbc, nint)
    border = rng.standard_normal(coll.n_x)
    Sc, X = reduction.onto_start(coll, J, border)
    M = coll.bordered(J, border).tocsc()
    S = np.r_[np.arange(n), coll.n_u + np.arange(npar)]
    I = np.arange(n, coll.n_u)
    X_ref = spla.splu(M[:coll.n_coll][:, I].tocsc()).solve(M[:coll.n_coll][:, S].toarray())
    Sc_ref = M[coll.n_coll:][:, S].toarray() - M[coll.n_coll:][:, I] @ X_ref
    np.testing.assert_allclose(X, X_ref, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(Sc, Sc_ref, rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("N, m, n", [(1, 1, 1), (6, 4, 3), (3, 2, 5), (4, 7, 2)])
def test_collocation_blocks_are_their_definition(N, m, n):
    """Collocation.local_blocks (compiled: reduction.collocation_blocks) is the definition
    WP[k, c] delta_il - dtm[j] T WT[k, c] A[j, c, i, l] written out here, to rounding
    (two products and a difference of numbers of norm ~1: 1e-14)."""
    rng = np.random.default_rng(N + 10 * m + 100 * n)
    mesh = col.Mesh(np.r_[0.0, np.sort(rng.random(N - 1)), 1.0], m)
    coll = col.Collocation(mesh, n)
    A = rng.standard_normal((N, m, n, n))
    T = 2.7
    blocks = coll.local_blocks(T, A)
    WT, WP = col.lagrange_weights(m)
    for j in range(N):
        for c in range(m):
            for k in range(m + 1):
                want = WP[k, c] * np.eye(n) - mesh.dtm[j] * T * WT[k, c] * A[j, c]
                got = blocks[j, c * n:(c + 1) * n, k * n:(k + 1) * n]
                np.testing.assert_allclose(got, want, rtol=1e-14, atol=1e-15)


@pytest.mark.parametrize("general_bc, nbc, nint", [(False, 3, 1), (True, 3, 2), (True, 4, 0),
                                                    (True, 2, 1)])
def test_factorisation_reduces_other_dense_rows_as_onto_start(general_bc, nbc, nint):
    """BorderedCollocation.reduced: a factorisation of [J; border] reduces the matrix
    with J's collocation rows and other dense rows (another integral row, another
    border: the BP test of cycles at a point's own phase) onto (U(0), parameters) as
    reduction.onto_start does on that matrix (forward substitution with LAPACK's
    solves, a separate elimination): equal to rounding (random blocks of norm ~1 and
    N = 11 intervals: 1e-10 relative)."""
    rng = np.random.default_rng(21 + nbc + nint)
    coll, J, n, npar = random_general_system(rng, general_bc, nbc, nint)
    f = reduction.BorderedCollocation.from_jacobian(coll, J, rng.standard_normal(coll.n_x))
    J2 = J.copy()
    if nint:
        pos = coll.integral_positions(0)
        J2.data[pos] = rng.standard_normal(len(pos))
    border2 = rng.standard_normal(coll.n_x)
    Sc_ref, _ = reduction.onto_start(coll, J2, border2)
    Sc = f.reduced(reduction.pieces(coll, J2, border2)[2])
    np.testing.assert_allclose(Sc, Sc_ref, rtol=1e-10, atol=1e-10 * np.abs(Sc_ref).max())


@pytest.mark.parametrize("N, m, n", [(1, 1, 1), (7, 4, 3), (25, 4, 3), (4, 3, 5)])
def test_the_compiled_bp_test_of_cycles_is_its_steps(N, m, n):
    """BorderedCollocation.bp_test (one compiled call) against its steps one by one: the
    dense rows of J (reduction.dense_rows) with the phase row w_node * (T F) and the border
    theta * tangent, BorderedCollocation.reduced and linalg.scaled_slogdet: the same bits."""
    from washer.cont import linalg
    lapack = linalg.compiled_lapack()
    if lapack is None:
        pytest.skip("numpy's LAPACK not found: the steps serve")
    rng = np.random.default_rng(N + 10 * m + 100 * n)
    coll = col.Collocation(col.Mesh(np.r_[0.0, np.sort(rng.random(N - 1)), 1.0], m), n)
    J = random_jacobian(coll, rng, 1.7)
    f = reduction.BorderedCollocation.from_jacobian(coll, J, rng.standard_normal(coll.n_x))
    F = rng.standard_normal((coll.mesh.n_nodes, n))
    theta, tangent = rng.random(coll.n_x), rng.standard_normal(coll.n_x)
    T = 3.3
    extra = reduction.dense_rows(coll, J, theta * tangent)
    extra[coll.nbc] = np.concatenate(((coll.w_node[:, None] * (T * F)).ravel(),
                                      np.zeros(coll.npar)))
    Sc_ref = f.reduced(extra)
    layout = reduction.BPLayout.of(coll, theta)
    Sc, got = f.bp_test(lapack, reduction.dense_values_of(coll, J), layout, T, F, tangent)
    assert np.array_equal(Sc, Sc_ref)
    assert got == linalg.scaled_slogdet(Sc_ref)


@pytest.mark.parametrize("N, m, n, npar", [(1, 3, 2, 2), (7, 4, 3, 2), (12, 3, 2, 4),
                                           (30, 4, 3, 2)])
def test_a_new_border_row_gives_the_bits_of_a_new_factorisation(N, m, n, npar):
    """reborder keeps the collocation rows' eliminations and factorises the dense system
    again: the same operations on the same numbers as a factorisation of the matrix with
    that row, so the solves, determinant and Floquet pair are equal to the bit (and
    re-bordering twice is the same as once)."""
    rng = np.random.default_rng(N * 100 + m * 10 + n + 7)
    blocks, parcols, extra, M = random_system(rng, N, m, n, npar)
    rows = rng.standard_normal((2, M.shape[0]))
    f = reduction.BorderedCollocation(blocks, parcols, extra)
    rhs = rng.standard_normal(len(M))
    for row in rows:
        extra2 = extra.copy()
        extra2[-1] = row
        fresh = reduction.BorderedCollocation(blocks, parcols, extra2)
        assert f.reborder(row)
        assert not f.singular
        assert f.solve(rhs).tobytes() == fresh.solve(rhs).tobytes()
        assert f.sign_logdet() == fresh.sign_logdet()
        for a, b in zip(f.floquet_pair(), fresh.floquet_pair()):
            assert a.tobytes() == b.tobytes()
        other = extra2.copy()
        other[0] = rng.standard_normal(len(M))
        a, b = f.reduced(other), fresh.reduced(other)     # None both where P1 is singular
        assert (a is None) == (b is None)
        if a is not None:
            assert a.tobytes() == b.tobytes()
        # and the solve is that of the matrix with the new row
        M2 = M.copy()
        M2[-1] = row
        x = f.solve(rhs)
        assert np.linalg.norm(M2 @ x - rhs) <= 1e-10 * np.linalg.norm(M2, 1) * np.linalg.norm(x)


def test_a_border_row_that_makes_the_matrix_singular():
    """A border row in the span of the other dense rows' reduction: the remaining dense
    system has a zero pivot, as in a new factorisation (singular, determinant 0)."""
    rng = np.random.default_rng(5)
    N, m, n, npar = 4, 2, 2, 1
    blocks, parcols, extra, M = random_system(rng, N, m, n, npar)
    f = reduction.BorderedCollocation(blocks, parcols, extra)
    row = extra[0].copy()
    extra2 = extra.copy()
    extra2[-1] = row
    fresh = reduction.BorderedCollocation(blocks, parcols, extra2)
    assert f.reborder(row)
    assert f.singular == fresh.singular
    assert f.sign_logdet() == fresh.sign_logdet()


@pytest.mark.parametrize("N, m, n, npar", [(1, 3, 2, 2), (7, 4, 3, 2), (12, 3, 2, 4),
                                           (70, 4, 2, 2)])
def test_the_compiled_unit_tangent_is_the_iterator_s(N, m, n, npar):
    """BorderedCollocation.unit_tangent against Continuation.tangent's Python way on the
    same factorisation (the solve of e_n, CollocationBVP.inner's numpy dot, the division):
    the same doubles; None where that way would not take z (its norm above big)."""
    rng = np.random.default_rng(N * 100 + m * 10 + n + 11)
    blocks, parcols, extra, M = random_system(rng, N, m, n, npar)
    f = reduction.BorderedCollocation(blocks, parcols, extra)
    theta = rng.uniform(0.0, 2.0, len(M))
    theta[-npar:] = [0.0, 1.0][:npar] + [0.5] * (npar - 2)
    e = np.zeros(len(M))
    e[-1] = 1.0
    z = f.solve(e)
    nz = np.sqrt(abs(float(np.dot(z, theta * z))))
    t = f.unit_tangent(theta, 1e30)
    assert t is not None and t.tobytes() == (z / nz).tobytes()
    assert f.unit_tangent(theta, 0.5 * nz) is None
