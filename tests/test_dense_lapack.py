"""The engine's dense LAPACK calls (washer.cont.linalg: solve, slogdet, eigvals, eig) give
numpy.linalg's values bit for bit: the same gesv, getrf and geev, without the wrappers."""
import numpy as np
import pytest

from washer.cont import linalg


@pytest.mark.parametrize("n", [1, 2, 3, 7, 19])
def test_the_same_values_as_numpy_linalg(n):
    rng = np.random.default_rng(n)
    for _ in range(20):
        M = rng.standard_normal((n, n + 1))[:, :n]          # strided, as J[:, :n]
        b = rng.standard_normal(n)
        assert np.array_equal(linalg.solve(M, b), np.linalg.solve(M, b))
        Mc = 2j * np.eye(n) - M                           # the first Lyapunov coefficient's
        bc = b + 1j * rng.standard_normal(n)
        assert np.array_equal(linalg.solve(Mc, bc), np.linalg.solve(Mc, bc))
        sign, logdet = np.linalg.slogdet(M)
        assert linalg.slogdet(M) == (float(sign), float(logdet))
        w = linalg.eigvals(M)
        ref = np.linalg.eigvals(M)
        assert w.dtype == ref.dtype and np.array_equal(w, ref)
        (w, V), (wr, Vr) = linalg.eig(M), np.linalg.eig(M)
        assert w.dtype == wr.dtype and np.array_equal(w, wr) and np.array_equal(V, Vr)


def test_real_spectra_come_back_real_and_complex_ones_complex():
    w = linalg.eigvals(np.diag([3.0, -1.0]))
    assert w.dtype == float and sorted(w) == [-1.0, 3.0]
    w, V = linalg.eig(np.array([[0.0, 1.0], [-4.0, 0.0]]))
    assert w.dtype == complex and np.allclose(sorted(w.imag), [-2.0, 2.0], rtol=1e-15, atol=0)  # LAPACK rounding


def test_singular_and_non_finite_matrices():
    M = np.array([[1.0, 2.0], [2.0, 4.0]])
    with np.errstate(invalid="ignore"):
        assert np.isnan(linalg.solve(M, np.ones(2))).all()
    assert linalg.slogdet(M) == (0.0, -np.inf)
    bad = np.array([[1.0, np.nan], [0.0, 1.0]])
    with pytest.raises(np.linalg.LinAlgError):
        linalg.eigvals(bad)
    with pytest.raises(np.linalg.LinAlgError):
        linalg.eig(bad)
    # the bordered factor of the engine falls back to least squares at a singular matrix
    f = linalg.dense_factor(np.array([[1.0, 2.0]]), np.array([2.0, 4.0]))
    with np.errstate(invalid="ignore"):
        x = f.solve(np.array([1.0, 2.0]))
    assert np.allclose(x, np.linalg.lstsq(f.M, [1.0, 2.0], rcond=None)[0])
