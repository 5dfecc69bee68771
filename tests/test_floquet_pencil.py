"""The multipliers' eigenvalue call and AUTO's order of multipliers, against their
definitions: scipy.linalg.eigvals of the pencil (bit for bit: the same LAPACK routine
with the same arguments) and np.nanargmin / a stable sort by ||mu| - 1|."""
import numpy as np
import pytest
import scipy.linalg

from washer.cont import floquet


def pencils(seed=3, count=400):
    rng = np.random.default_rng(seed)
    for t in range(count):
        n = int(rng.integers(1, 7))
        A, B = rng.standard_normal((n, n)), rng.standard_normal((n, n))
        kind = t % 5
        if kind == 1:
            B[:, 0] = 0                      # an infinite eigenvalue
        elif kind == 2:
            A[:, 0] = B[:, 0] = 0            # a singular pencil: 0/0
        elif kind == 3:
            A, B = np.round(A), np.round(B)  # exact small integers: ties, real pairs
        elif kind == 4:
            B = np.zeros((n, n))
        yield A, B


def test_pencil_eigenvalues_are_scipys_bit_for_bit():
    for A, B in pencils():
        with np.errstate(all="ignore"):
            ref = scipy.linalg.eigvals(A, B)
            got = floquet._pencil_eigvals(A, B)
        assert got.dtype == ref.dtype and got.tobytes() == ref.tobytes(), (A, B, ref, got)


def test_pencil_eigenvalues_of_non_finite_matrices_raise_as_scipy_does():
    A = np.eye(2)
    A[0, 1] = np.nan
    with pytest.raises(ValueError):
        floquet._pencil_eigvals(A, np.eye(2))


def reference_order(mu, trivial):
    mu = np.asarray(mu, complex)
    head = []
    if trivial:
        i1 = int(np.nanargmin(np.abs(mu - 1)))
        head, mu = [mu[i1]], np.delete(mu, i1)
    return np.r_[head, mu[np.argsort(np.abs(np.abs(mu) - 1), kind="stable")]].astype(complex)


@pytest.mark.parametrize("trivial", [True, False])
def test_sort_multipliers_is_autos_order(trivial):
    rng = np.random.default_rng(4)
    for A, B in pencils(seed=5, count=300):
        with np.errstate(all="ignore"):
            mu = scipy.linalg.eigvals(A, B)
        mu = np.where(np.isfinite(mu), mu, np.inf + 0j)
        if rng.random() < 0.2 and len(mu) > 1:
            mu[int(rng.integers(len(mu)))] = np.nan
        with np.errstate(invalid="ignore"):
            ref = reference_order(mu, trivial)
        got = floquet.sort_multipliers(mu, trivial)
        assert got.tobytes() == ref.tobytes(), (mu, ref, got)
    # the multiplier closest to 1 leads, then ||mu| - 1| ascending, ties in their order
    mu = np.array([2.0, complex(-1.0, 0.0), 1.0 + 1e-9, 1.0, 0.5, complex(-1.0, -0.0)])
    got = floquet.sort_multipliers(mu)
    assert list(got.real) == [1.0, -1.0, -1.0, 1.0 + 1e-9, 0.5, 2.0]
    assert not np.signbit(got[1].imag) and np.signbit(got[2].imag)     # the tie's order
    with pytest.raises(ValueError):
        floquet.sort_multipliers(np.array([np.nan + 0j]))
