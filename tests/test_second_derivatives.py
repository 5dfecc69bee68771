"""The loci's second derivatives f_zz[e_s, w] (Problem.second_derivatives) from a problem's
batched analytic Jacobians (dfdu_batch and dfdp_batch, JAC = 1): against exact values of a small
problem designed with sympy, and on the washer against the differences of f alone.
"""
import numpy as np
import pytest
import sympy as sp

from washer.cont.problem import Problem, ProblemError
from washer.problems.rotating import rotating_problem

U = sp.symbols("u0:3")
P = sp.symbols("p0:4")
F = sp.Matrix([U[0] ** 2 * P[0] + sp.sin(U[1]) * P[1],
               U[0] * U[1] * U[2] + sp.exp(P[2] * U[2]),
               sp.cos(U[0] * P[2]) + U[1] ** 3])
Z = list(U) + list(P)
f_n = sp.lambdify((U, P), list(F), "numpy")
fu_n = sp.lambdify((U, P), F.jacobian(U), "numpy")
fp_n = sp.lambdify((U, P), F.jacobian(P), "numpy")


def small_problem(with_batch: bool) -> Problem:
    def dfdu_batch(us, pars):
        return np.array([fu_n(u, p) for u, p in zip(us, pars)], dtype=float)

    def dfdp_batch(us, pars):
        return np.array([fp_n(u, p) for u, p in zip(us, pars)], dtype=float)
    return Problem(3, lambda u, p: np.array(f_n(u, p), dtype=float),
                   dfdu=lambda u, p: np.array(fu_n(u, p), dtype=float),
                   dfdp=lambda u, p: np.array(fp_n(u, p), dtype=float),
                   dfdu_batch=dfdu_batch if with_batch else None,
                   dfdp_batch=dfdp_batch if with_batch else None, jac=1)


def exact(u, par, ws, idx):
    """f_zz[e_s, w_k] from sympy's Hessians, (3 + len(idx), m, 3)."""
    zs = list(U) + [P[i - 1] for i in idx]
    sub = dict(zip(Z, list(u) + list(par)))
    H = [sp.hessian(F[i], zs).subs(sub) for i in range(3)]
    H = np.array([[[float(h[s, j]) for j in range(len(zs))] for s in range(len(zs))]
                  for h in H])                                # (i, s, j)
    # w_k moves only the state: the first 3 entries of z
    return np.einsum("isj,kj->ski", H[:, :, :3], ws)


def test_second_derivatives_from_jacobians_are_the_exact_ones():
    u, par = np.array([0.3, -0.7, 0.5]), np.array([1.5, -0.4, 0.8, 2.0])
    ws = np.array([[1.0, 0.2, -0.3], [0.0, -2.0, 0.5]])
    idx = [1, 3]
    ref = exact(u, par, ws, idx)
    got = small_problem(True).second_derivatives(u, par, ws, idx)
    # forward differences of exact Jacobians, step 1e-7 (1 + |u|) / |w|: truncation
    # h |f_uuu| / 2 ~ 1e-7 (the third derivatives here are of the size of the second)
    assert got.shape == ref.shape
    assert np.max(np.abs(got - ref)) <= 1e-6 * (1 + np.max(np.abs(ref)))
    # the differences of f alone are the older path, accurate to ~1e-8
    old = small_problem(False).second_derivatives(u, par, ws, idx)
    assert np.max(np.abs(old - ref)) <= 1e-6 * (1 + np.max(np.abs(ref)))


def test_bad_batched_jacobians_are_a_problem_error():
    p = Problem(3, lambda u, q: np.zeros(3), dfdu=lambda u, q: np.eye(3),
                dfdp=lambda u, q: np.zeros((3, 4)), jac=1,
                dfdu_batch=lambda us, pars: np.zeros((len(us), 3, 2)),
                dfdp_batch=lambda us, pars: np.zeros((len(us), 3, 4)))
    with pytest.raises(ProblemError, match="dfdu_batch"):
        p.second_derivatives(np.zeros(3), np.zeros(4), np.ones((1, 3)), [1])


def test_washer_second_derivatives_agree_with_differences_of_f():
    prob = rotating_problem("averaged").with_jac(1)
    u, par = prob.start(17)
    rng = np.random.default_rng(1)
    ws = rng.standard_normal((3, 12)) * np.r_[np.full(6, 1e-2), np.full(6, 1.0)]
    fast = prob.second_derivatives(u, par, ws, [1, 2])
    slow = prob.with_jac(0).second_derivatives(u, par, ws, [1, 2])
    # the differences of f are O(h^2) ~ 1e-8 relative (SECOND_STEP) plus rounding, those of
    # the Jacobians ~1e-7 (JACOBIAN_STEP)
    scale = np.max(np.abs(slow), axis=(0, 2), keepdims=True)
    assert np.max(np.abs(fast - slow) / scale) <= 1e-6
