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


@pytest.mark.parametrize("trivial", [True, False])
def test_sort_multipliers_orders_near_ties_as_numpys_absolute_value_does(trivial):
    """Moduli a few units in the last place apart, whose order numpy's complex absolute
    value (not libm's hypot: they differ in the last bit for a third of random numbers)
    decides; the compiled sort where washer._cont is built."""
    rng = np.random.default_rng(6)
    for _ in range(2000):
        n = int(rng.integers(2, 8))
        r = 1.0 + rng.choice([-1, 1]) * 0.3 + rng.integers(-4, 5, n) * 2.0 ** -52
        mu = r * np.exp(1j * rng.uniform(-np.pi, np.pi, n))
        if rng.random() < 0.3:
            mu[0] = 1.0 + rng.integers(-3, 4) * 2.0 ** -52 * 1j
        with np.errstate(invalid="ignore"):
            ref = reference_order(mu, trivial)
        assert floquet.sort_multipliers(mu, trivial).tobytes() == ref.tobytes(), mu


def test_the_trivial_multiplier_is_deflated_so_its_double_partner_stays_real():
    """On a family of conservative orbits (AUTO's r3b halo and vertical families) the
    trivial multiplier 1 is double with one eigenvector (a Jordan block). A monodromy
    matrix M = S J S^-1 with that block, a real pair (10, 0.1) and a pair on the unit
    circle, perturbed by 1e-10: QZ on the whole pencil (M, I) splits the double 1 into
    1 +- 1e-5 or 1 +- i 1e-5 as the perturbation falls (both happen over the seeds);
    the deflated pencil (AUTO's FLOWKM: Fairgrieve and Jepson's deflation) keeps both
    real, as AUTO's d-files show them and as r3b's PVLS, which reads 'all four nontrivial
    multipliers complex' as fm = 1, needs. The other multipliers are M's (numpy's
    eigenvalues of M, the reference) to 1e-8 relative: the deflation's error is the
    rounding of the null vector, not the perturbation's square root."""
    rng = np.random.default_rng(7)
    th = 0.7
    J = np.zeros((6, 6))
    J[:2, :2] = [[1, 1], [0, 1]]
    J[2:4, 2:4] = [[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]]
    J[4, 4], J[5, 5] = 10.0, 0.1
    complex_whole = 0
    for _ in range(40):
        S = rng.standard_normal((6, 6))
        M = S @ J @ np.linalg.inv(S) + 1e-10 * rng.standard_normal((6, 6))
        whole = floquet.sort_multipliers(scipy.linalg.eigvals(M, np.eye(6)))
        complex_whole += abs(whole[0].imag) > 0
        mu = floquet.pencil_multipliers(M, -np.eye(6), deflate_trivial=True)
        near_one = mu[np.abs(mu - 1) < 1e-3]
        assert len(near_one) == 2 and np.all(near_one.imag == 0), mu
        ref = np.linalg.eigvals(M)
        for m in mu[np.abs(mu - 1) >= 1e-3]:
            assert np.min(np.abs(ref - m)) < 1e-8 * abs(m), (m, ref)
    assert 0 < complex_whole < 40


# ------------------------------------------- the deflated pencil in one compiled call
# (csrc/cont/floquet.cpp: numpy's GESDD, DGEMM, DGEMV, DDOT and scipy's DGGEV called as
# numpy and scipy call them, so the multipliers are the Python's to the bit)

compiled = pytest.mark.skipif(floquet.compiled_routines() is None, reason="numpy or scipy links no bundled scipy-openblas here")


def python_deflated(P0, P1):
    """pencil_multipliers' Python before the sort."""
    with np.errstate(all="ignore"):
        mu = floquet._deflated_eigvals(P0, -P1)
    return np.where(np.isfinite(mu), mu, np.inf + 0j)


def orbit_pairs(seed, n, count):
    """(P0, P1) with a multiplier at 1 (P0 = -P1 M, M x = x), of magnitudes 1e-3 to 1e3,
    every fifth rounded to eighths (ties in QZ's and the sort's choices)."""
    rng = np.random.default_rng(seed)
    for k in range(count):
        M = rng.standard_normal((n, n)) * 10.0 ** rng.integers(-2, 3)
        x = rng.standard_normal(n)
        M -= np.outer(M @ x - x, x) / (x @ x)
        P1 = rng.standard_normal((n, n)) * 10.0 ** rng.integers(-3, 4)
        P0 = -P1 @ M
        if k % 5 == 0:
            P0 = np.round(P0 * 8) / 8
        yield P0, P1


@compiled
@pytest.mark.parametrize("n", [2, 3, 4, 6, 12])
def test_compiled_deflation_is_the_pythons_bit_for_bit(n):
    served = 0
    for P0, P1 in orbit_pairs(10 + n, n, 200):
        got = floquet._compiled_deflated_eigvals(P0, P1)
        if got is None:                      # left to the Python (infinite eigenvalues)
            continue
        served += 1
        ref = python_deflated(P0, P1)
        assert got.tobytes() == ref.tobytes(), (P0, P1, got, ref)
        assert floquet.pencil_multipliers(P0, P1, True).tobytes() == \
            floquet.sort_multipliers(ref).tobytes()
    assert served >= 180                     # the compiled call is what runs


@compiled
def test_compiled_deflation_leaves_what_it_cannot_do_to_the_python():
    P1 = -np.eye(3)
    P0 = np.diag([1.0, 2.0, 0.5])
    assert floquet._compiled_deflated_eigvals(P0, P1) is not None
    bad = P0.copy()
    bad[1, 2] = np.nan
    assert floquet._compiled_deflated_eigvals(bad, P1) is None      # nothing to deflate
    assert floquet._compiled_deflated_eigvals(np.asfortranarray(P0 + 0.1), P1) is None
    singular = -np.diag([1.0, 1.0, 0.0])                              # an infinite multiplier
    assert floquet._compiled_deflated_eigvals(P0, singular) is None
    mu = floquet.pencil_multipliers(P0, singular, True)
    assert np.isinf(mu).sum() == 1 and mu[0] == 1.0
