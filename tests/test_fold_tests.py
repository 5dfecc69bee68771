"""The fold locus's test functions in one compiled call (washer.cont.systems.fold.
fold_tests, csrc/cont/fold_tests.cpp) give the values of the numpy expressions that
define them bit for bit: numpy's GESDD, DDOT and GEEV are called from C with numpy's
workspaces and the elementwise arithmetic in numpy's order. The reference below is the
definition in public numpy (np.linalg.svd, ndarray @, np.linalg.eigvals, np.prod)."""
import numpy as np
import pytest

from washer.cont import linalg
from washer.cont.normal_form import FD2_STEP
from washer.cont.systems import fold
from washer.cont.systems.equilibrium import IMAG_TOL

compiled = pytest.mark.skipif(linalg.compiled_lapack() is None,
                              reason="numpy links no bundled scipy-openblas here")


def reference(A, w_ref, phi, F):
    """(w, BT, CP, ZH) by numpy: the left null vector of A from the SVD of A^T, turned
    against w_ref; <w, phi>; <w, second difference of f along phi>; the product of the
    real parts of the complex pairs with Im > 0, by decreasing real part."""
    w = np.linalg.svd(A.T)[2][-1]
    w = w if w @ w_ref >= 0 else -w
    lam = np.linalg.eigvals(A)
    lam = lam[np.argsort(-lam.real, kind="stable")]
    lam = lam if (lam.imag != 0).any() else lam.real
    pairs = lam[(np.abs(lam.imag) > IMAG_TOL * (1 + np.abs(lam))) & (lam.imag > 0)]
    return (w, float(w @ phi), float(w @ ((F[0] - 2 * F[1] + F[2]) / FD2_STEP ** 2)),
            float(np.prod(pairs.real)) if pairs.size else None)


def same(a, b) -> bool:
    return np.asarray(a, float).tobytes() == np.asarray(b, float).tobytes()


@compiled
@pytest.mark.parametrize("n", [1, 2, 3, 4, 7, 12, 25])
def test_the_values_of_the_numpy_definition_bit_for_bit(n):
    rng = np.random.default_rng(100 + n)
    checked_pairs = 0
    for k in range(150):
        # the extended Jacobian's leading block (row stride 2 n + 2), as the locus hands it
        J = rng.standard_normal((2 * n + 1, 2 * n + 2))
        if k % 3 == 0:                       # singular A, as at every point of the locus
            v = rng.standard_normal(n)
            J[:n, :n] -= np.outer(J[:n, :n] @ v, v) / (v @ v)
        if k % 5 == 1:                       # integer entries: ties in the spectrum
            J[:n, :n] = rng.integers(-3, 4, (n, n))
        A = J[:n, :n]
        w_ref, phi = rng.standard_normal(n), rng.standard_normal(n)
        F = rng.standard_normal((3, n)) * 10.0 ** rng.integers(-3, 3)
        got = fold.fold_tests(J, n, w_ref, phi, F, zh=True)
        ref = reference(A, w_ref, phi, F)
        assert same(got[0], ref[0])
        assert same(got[1], ref[1]) and same(got[2], ref[2])
        assert (got[3] is None) == (ref[3] is None) and (ref[3] is None or same(got[3], ref[3]))
        checked_pairs += ref[3] is not None
        # the null vector alone (the locus's update), from a contiguous A
        assert same(fold.fold_tests(np.ascontiguousarray(A), n, w_ref)[0], ref[0])
    assert n < 2 or checked_pairs > 10        # complex pairs were among the cases


@compiled
def test_what_is_not_asked_for_is_none_and_failures_raise_as_numpy():
    A = np.array([[1.0, 2.0], [2.0, 4.0]])
    w, bt, cp, zh = fold.fold_tests(A, 2, np.array([1.0, 0.0]))
    assert bt is None and cp is None and zh is None
    assert np.allclose(abs(w @ A), 0, atol=1e-15) and w[0] > 0      # 1 and 2 eps of |A|
    # a rotation block: one complex pair, its real part 0.5
    A = np.array([[0.5, -2.0, 0.0], [2.0, 0.5, 0.0], [0.0, 0.0, 0.0]])
    assert fold.fold_tests(A, 3, np.ones(3), zh=True)[3] == 0.5
    bad = np.array([[1.0, np.nan], [0.0, 1.0]])
    with pytest.raises(np.linalg.LinAlgError):
        fold.fold_tests(bad, 2, np.ones(2))
