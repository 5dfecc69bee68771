"""ADAPT's interpolation (collocation.evaluator: the intervals, the Lagrange weights and
the values in compiled calls, csrc/cont/adapt.cpp) gives numpy's values bit for bit: the
definition below is the numpy expression it replaces (searchsorted, INTWTS's basis,
einsum over the interval's nodes)."""
import numpy as np
import pytest

from washer.cont import collocation as col


def numpy_evaluate(mesh, U, t):
    """The piecewise polynomial (mesh, U) at the times t, in numpy alone."""
    m = mesh.ncol
    j = np.clip(np.searchsorted(mesh.tm, t, side="right") - 1, 0, mesh.ntst - 1)
    W = col.interpolation_weights(m, (t - mesh.tm[j]) / mesh.dtm[j])
    idx = j[:, None] * m + np.arange(m + 1)[None, :]
    return np.einsum("tk,tk...->t...", W, np.asarray(U)[idx])


def random_mesh(rng, ntst, ncol):
    d = rng.uniform(0.05, 1.0, ntst) ** 3                    # lengths over two decades
    tm = np.concatenate(([0.0], np.cumsum(d)))
    tm /= tm[-1]
    tm[-1] = 1.0
    return col.Mesh(tm, ncol)


@pytest.mark.parametrize("ncol", [1, 2, 3, 4, 5, 7])
def test_the_same_values_as_numpy(ncol):
    rng = np.random.default_rng(ncol)
    for ntst in (1, 2, 5, 70):
        old = random_mesh(rng, ntst, ncol)
        new = random_mesh(rng, max(ntst, 3), ncol)
        times = [new.node_times(), rng.uniform(0.0, 1.0, 50),
                 np.array([0.0, 1.0, -0.25, 1.5]), old.tm.copy()]       # ends, outside, nodes
        for t in times:
            at = col.evaluator(old, t)
            for shape in [(old.n_nodes, 2), (old.n_nodes, 3), (old.n_nodes, 12),
                          (old.n_nodes, 1), (old.n_nodes,), (old.n_nodes, 2, 3)]:
                U = rng.standard_normal(shape) * 10.0 ** rng.integers(-8, 8)
                got, ref = at(U), numpy_evaluate(old, U, t)
                assert got.shape == ref.shape and np.array_equal(got, ref)
            Uf = np.asfortranarray(rng.standard_normal((old.n_nodes, 4)))  # a column-major U
            assert np.array_equal(at(Uf), numpy_evaluate(old, Uf, t))


def test_nan_times_and_unordered_meshes_are_numpy_s():
    rng = np.random.default_rng(0)
    mesh = random_mesh(rng, 6, 4)
    U = rng.standard_normal((mesh.n_nodes, 2))
    t = np.array([0.1, np.nan, 0.7])
    assert np.array_equal(col.evaluator(mesh, t)(U), numpy_evaluate(mesh, U, t), equal_nan=True)
    bad = col.Mesh(mesh.tm[[0, 2, 1, 3, 4, 5, 6]], 4)
    t = np.linspace(0, 1, 9)
    assert np.array_equal(col.evaluator(bad, t)(U), numpy_evaluate(bad, U, t), equal_nan=True)


def numpy_new_mesh(mesh, U, ntst_new, periodic):
    """NEWMSH on EQDF in numpy alone (collocation.eqdf, then new_mesh's inversion)."""
    eqf = col.eqdf(mesh, U, periodic)
    if not (np.diff(eqf) > 0).all():
        eqf = eqf + 1e-12 * eqf[-1] * np.arange(len(eqf)) / max(len(eqf) - 1, 1)
    targets = eqf[-1] * np.arange(1, ntst_new) / ntst_new
    return np.concatenate((mesh.tm[:1], np.interp(targets, eqf, mesh.tm), mesh.tm[-1:]))


@pytest.mark.parametrize("ncol", [1, 2, 3, 4, 5, 7])
def test_new_mesh_is_numpy_s(ncol):
    """cont_new_mesh against numpy's EQDF and NEWMSH: profiles smooth and steep, widths 1 to
    20 (pairwise sums from 8 terms on), flat components, a constant profile (EQDF's small
    derivative), periodic or not, other numbers of intervals."""
    rng = np.random.default_rng(10 + ncol)
    for ntst in (1, 2, 3, 5, 20, 70):
        mesh = random_mesh(rng, ntst, ncol)
        t = mesh.node_times()
        for n in (1, 2, 3, 7, 8, 9, 12, 20):
            k = rng.integers(1, 6, n)
            U = np.sin(2 * np.pi * k * t[:, None] + rng.uniform(0, 6, n)) * rng.uniform(0.1, 10, n)
            U[:, 0] = np.tanh(40 * (t - 0.5)) if n > 2 else U[:, 0]       # a steep layer
            for V in (U, np.where(rng.uniform(size=n) < 0.3, 1.0, U),   # flat components
                      np.ones_like(U), U * 1e-300):
                for periodic in (True, False):
                    for new in (ntst, max(ntst - 1, 1), ntst + 3):
                        got = col.new_mesh(mesh, V, new, periodic)
                        assert np.array_equal(got, numpy_new_mesh(mesh, V, new, periodic))


def test_new_mesh_of_a_non_finite_profile_is_numpy_s():
    rng = np.random.default_rng(1)
    mesh = random_mesh(rng, 8, 4)
    U = rng.standard_normal((mesh.n_nodes, 3))
    for bad in (np.nan, np.inf):
        V = U.copy()
        V[5, 1] = bad
        with np.errstate(invalid="ignore"):
            assert np.array_equal(col.new_mesh(mesh, V, 8), numpy_new_mesh(mesh, V, 8, True),
                                  equal_nan=True)


def loop_node_weights(mesh):
    """Mesh.node_weights as a sum over the intervals, node by node in order."""
    wi = col.integration_weights(mesh.ncol)
    w = np.zeros(mesh.n_nodes)
    m = mesh.ncol
    for k in range(m + 1):
        w[k:k + mesh.ntst * m:m] += mesh.dtm * wi[k]
    return w


@pytest.mark.parametrize("ncol", [1, 2, 3, 4, 5, 7])
def test_node_weights_are_the_interval_sums(ncol):
    rng = np.random.default_rng(20 + ncol)
    for ntst in (1, 2, 5, 70):
        mesh = random_mesh(rng, ntst, ncol)
        assert np.array_equal(mesh.node_weights(), loop_node_weights(mesh))


@pytest.mark.parametrize("ncol", [1, 2, 3, 4, 5, 7])
def test_adapt_is_the_steps_one_by_one(ncol):
    """collocation.adapt (cont_adapt_mesh: the new mesh, its lengths, node times, node
    weights and the interpolation's weights in one call) against new_mesh, a fresh Mesh's
    dtm, node_times, node_weights and mesh_interpolator, bit for bit; one column and a
    non-finite profile take the steps themselves."""
    rng = np.random.default_rng(30 + ncol)
    for ntst in (1, 2, 3, 20, 70):
        mesh = random_mesh(rng, ntst, ncol)
        t = mesh.node_times()
        for n in (1, 2, 3, 12):
            U = np.sin(2 * np.pi * rng.integers(1, 6, n) * t[:, None] + rng.uniform(0, 6, n))
            U[:, 0] = np.tanh(40 * (t - 0.5))                             # a steep layer
            for periodic in (True, False):
                new, onto = col.adapt(mesh, U, periodic)
                ref = col.Mesh(col.new_mesh(mesh, U, ntst, periodic), ncol)
                assert np.array_equal(new.tm, ref.tm) and np.array_equal(new.dtm, ref.dtm)
                assert np.array_equal(new.node_times(), ref.node_times())
                assert np.array_equal(new.node_weights(), ref.node_weights())
                ref_onto = col.mesh_interpolator(mesh, ref)
                for V in (U, rng.standard_normal((mesh.n_nodes, 5)), U[:, :1]):
                    assert np.array_equal(onto(V), ref_onto(V))
                    out = np.empty((new.n_nodes, V.shape[1]))
                    assert onto(V, out=out) is out and np.array_equal(out, ref_onto(V))
    V = U.copy()
    V[3, 1] = np.nan
    with np.errstate(invalid="ignore"):
        new, _ = col.adapt(mesh, V)
        assert np.array_equal(new.tm, col.new_mesh(mesh, V, mesh.ntst), equal_nan=True)


def test_a_computed_mesh_keeps_its_arrays_until_tm_changes():
    """Mesh.computed takes the lengths, node times and node weights computed with tm (the
    very arrays, dtm read-only), and recomputes them as any Mesh does once tm changes."""
    tm = np.array([0.0, 0.25, 1.0])
    ref = col.Mesh(tm.copy(), 2)
    dtm, t, w = np.diff(tm), ref.node_times(), ref.node_weights()
    mesh = col.Mesh.computed(tm, 2, dtm, t, w)
    assert mesh.dtm is dtm and not dtm.flags.writeable
    assert np.array_equal(mesh.node_times(), t) and np.array_equal(mesh.node_weights(), w)
    mesh.tm[1] = 0.5
    moved = col.Mesh(np.array([0.0, 0.5, 1.0]), 2)
    assert np.array_equal(mesh.dtm, moved.dtm)
    assert np.array_equal(mesh.node_times(), moved.node_times())
    assert np.array_equal(mesh.node_weights(), moved.node_weights())
