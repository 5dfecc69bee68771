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
