"""The BP test of BVPs and cycles (`CollocationBVP.bp_value`, FNBPBV's role) gives no
value where the reduced bordered Jacobian's determinant is rounding noise.

A cycle family nearing an infinite-period limit makes the reduced matrix S span many
decades: its largest singular value grows like exp(lambda T) while two others fall below
rounding relative to it. det(S) is then a product of noise and its sign flips from step
to step without any branch point; AUTO does not test there (FNBPBV returns ITP=0 when
its quotient is not representable). The matrices below are built from a known SVD, so
the determinant's sign and the singular values are known exactly by construction."""

import math

import numpy as np
import pytest

from washer.cont.systems.bvp import CollocationBVP


def _with_singular_values(sv, signs, seed):
    """Q diag(signs * sv) Q^T with Q orthogonal (QR of a seeded Gaussian): its
    determinant is prod(signs * sv) exactly, its singular values are sv."""
    rng = np.random.default_rng(seed)
    q, _ = np.linalg.qr(rng.standard_normal((len(sv), len(sv))))
    return q @ np.diag(np.asarray(signs) * np.asarray(sv)) @ q.T


@pytest.mark.parametrize("seed", range(5))
def test_two_singular_values_below_rounding_give_no_test(seed):
    # the figures of a 10x10 reduced matrix near an infinite-period limit: largest
    # 1e22, the two smallest 1e-3 and 1e-1 (relative 1e-25, 1e-23 < 10 eps)
    sv = [1e22, 1e6, 1e4, 1e3, 1e2, 1e1, 1.0, 1.0, 1e-1, 1e-3]
    S = _with_singular_values(sv, [1] * 10, seed)
    assert CollocationBVP.bp_value(S) is None


@pytest.mark.parametrize("sign", [1, -1])
def test_near_branch_point_keeps_its_sign(sign):
    # a simple branch point: one singular value tends to zero (here 1e-14 relative,
    # closer than a locator's last iterate need come), the others are resolved;
    # the sign of the determinant is the sign of the vanishing one
    sv = [1e3, 1e2, 1e1, 1.0, 1.0, 1e-11]
    S = _with_singular_values(sv, [1, 1, 1, 1, 1, sign], 3)
    v = CollocationBVP.bp_value(S)
    assert v is not None and np.sign(v) == sign
    # and its size is det(S / |S|_F): the product of sv over |S|_F^n, to the rounding
    # of the smallest one (eps sv[0] / sv[-1] ~ 2e-2 relative, backward stability)
    expect = np.prod(sv) / np.linalg.norm(sv) ** len(sv)
    assert abs(v) == pytest.approx(expect, rel=5e-2)


def _bp_value_by_definition(S):
    """The test as defined: no value where the two smallest singular values are both
    below n eps of the largest, else det(S / |S|_F) (LAPACK's LU through slogdet)."""
    scale = np.linalg.norm(S)
    if len(S) > 1:
        sv = np.linalg.svd(S, compute_uv=False)
        if sv[-2] <= len(S) * np.finfo(float).eps * sv[0]:
            return None
    sign, logdet = np.linalg.slogdet(S / scale)
    return float(sign * math.exp(logdet))


@pytest.mark.parametrize("n", [2, 3, 5, 8, 14, 16])
def test_singular_values_only_where_the_determinant_is_small(n):
    """bp_value skips the SVD where the determinant is far above what a void test allows
    (bvp._bp_void_logdet): the same value, bit for bit, as the test by definition, over
    matrices from well conditioned to one, two and three singular values at and around
    rounding, spanning up to 30 decades."""
    rng = np.random.default_rng(n)
    for case in range(60):
        top = 10.0 ** rng.uniform(0, 30)
        sv = np.sort(10.0 ** rng.uniform(-2, np.log10(top), n))[::-1]
        sv[0] = top
        k = min(case % 4, n)               # how many singular values go to rounding
        if k:
            sv[n - k:] = top * np.finfo(float).eps * 10.0 ** rng.uniform(-3, 1.5, k)
        S = _with_singular_values(np.sort(sv)[::-1], rng.choice([-1, 1], n), case)
        a, b = CollocationBVP.bp_value(S), _bp_value_by_definition(S)
        assert (a is None and b is None) or a == b, (case, a, b)
