"""The per-point helpers of equilibria that work on Python floats for small sizes give
the values numpy's forms give, bit for bit (the b-, s- and d-files must not change with
them): eigenvalues sorted by decreasing real part (ties in LAPACK's order), the pair
closest to the imaginary axis, NINS, the weighted inner product and the L2 norm.
Random matrices and vectors over many magnitudes, with repeated eigenvalues (zero rows)
and real/complex mixes."""
import numpy as np
import pytest

from washer.cont import linalg
from washer.cont.settings import Settings
from washer.cont.systems import equilibrium as eq
from washer.cont.systems._algebraic import SEQUENTIAL_SUM


def _reference_sorted(A):
    w = np.linalg.eigvals(A)
    lam = w.real if (w.imag == 0).all() else w
    return lam[np.argsort(-lam.real, kind="stable")]


def _reference_pair(lam):
    c = lam[eq.is_complex(lam)]
    return None if c.size == 0 else complex(c[np.argmin(np.abs(c.real))])


@pytest.mark.parametrize("n", [1, 2, 3, 4, 7, 9])
def test_spectrum_helpers_equal_numpy(n):
    rng = np.random.default_rng(n)
    for k in range(400):
        A = rng.standard_normal((n, n)) * 10.0 ** rng.integers(-3, 4)
        if k % 5 == 0:
            A[0, :] = A[:, 0] = 0.0                   # a zero eigenvalue, ties in the sort
        if k % 7 == 0 and n >= 2:
            A[:2, :2] = [[0.0, 1.0], [-1.0, 0.0]]      # a pair on the imaginary axis
        ref, lam = _reference_sorted(A), eq.eigenvalues_sorted(A)
        assert lam.dtype == ref.dtype and np.array_equal(lam, ref)
        assert eq.hopf_pair(lam) == _reference_pair(ref)
        assert eq.spectrum(lam).n_stable == int((ref.real <= 0).sum())


def test_eigvals_rejects_non_finite_matrices():
    with pytest.raises(np.linalg.LinAlgError):
        linalg.eigvals(np.array([[1.0, np.nan], [0.0, 1.0]]))
    with pytest.raises(np.linalg.LinAlgError):
        linalg.eigvals(np.full((9, 9), np.inf))


class _Weights:
    """The two methods under test on a plain object holding THU/THL weights."""
    inner = eq.EquilibriumSystem.inner
    measure = eq.EquilibriumSystem.measure

    def __init__(self, theta, ndim):
        self.theta, self.ndim = theta, ndim
        self.settings = Settings(NDIM=ndim, ICP=[1], IPLT=0)


@pytest.mark.parametrize("m", range(2, SEQUENTIAL_SUM + 4))
def test_inner_and_norm_equal_numpy(m):
    rng = np.random.default_rng(100 + m)
    for _ in range(500):
        theta = rng.choice([0.0, 1.0, 0.5, 3.0], size=m)
        a, b = (rng.standard_normal(m) * 10.0 ** rng.integers(-8, 8, m) for _ in range(2))
        w = _Weights(theta, m - 1)
        assert w.inner(a, b) == float((theta * a * b).sum())
        assert w.measure(a) == float(np.sqrt((a[:m - 1] ** 2).sum()))


@pytest.mark.parametrize("shape", [(1, 1), (2, 3), (3, 2), (4, 4), (5, 7), (12, 12)])
def test_null_vectors_are_numpys_svd(shape):
    """linalg.null_vectors (LAPACK's SVD called without numpy's wrappers) returns the
    right singular vectors np.linalg.svd returns, bit for bit, for square and rectangular
    matrices, rank-deficient ones among them."""
    rng = np.random.default_rng(sum(shape))
    for k in range(50):
        A = rng.standard_normal(shape) * 10.0 ** rng.integers(-3, 4)
        if k % 3 == 0 and min(shape) > 1:
            A[-1] = A[0]                                   # rank-deficient
        for j in (1, min(2, shape[1])):
            ref = np.linalg.svd(A)[2][-j:].T
            assert np.array_equal(linalg.null_vectors(A, j), ref)
    with pytest.raises(np.linalg.LinAlgError):
        linalg.null_vectors(np.full(shape, np.nan), 1)
