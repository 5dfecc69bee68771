"""Periodic orbits and their Floquet multipliers by single shooting: a reference for the
collocated multipliers that shares nothing with the engine's discretisation.

The orbit and its variational equations are integrated together by scipy's DOP853 at
rtol = atol = 1e-12; Newton corrects the start point and the period at fixed parameters
(phi_T(u0) = u0 and a Poincare phase condition through the first guess). The monodromy
matrix is the variational solution after one period; its eigenvalues are the multipliers.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp


def monodromy(f, jac, u0, period: float) -> tuple[np.ndarray, np.ndarray]:
    """(phi_T(u0), d phi_T / d u0): f(u) -> (n,), jac(u) -> (n, n), u0 (n,)."""
    n = len(u0)

    def rhs(_t, y):
        return np.concatenate([f(y[:n]), (jac(y[:n]) @ y[n:].reshape(n, n)).ravel()])

    sol = solve_ivp(rhs, (0.0, period), np.concatenate([u0, np.eye(n).ravel()]),
                    method="DOP853", rtol=1e-12, atol=1e-12)
    assert sol.success, sol.message
    return sol.y[:n, -1], sol.y[n:, -1].reshape(n, n)


def periodic_orbit(f, jac, u0, period: float, steps: int = 15):
    """Newton on (u0, T) from a guess near a periodic orbit: returns (u0, T, the
    monodromy matrix (n, n), the closing residual max |phi_T(u0) - u0|)."""
    u0 = np.asarray(u0, float).copy()
    guess, normal = u0.copy(), f(u0)
    n = len(u0)
    for _ in range(steps):
        end, m = monodromy(f, jac, u0, period)
        r = np.concatenate([end - u0, [normal @ (u0 - guess)]])
        a = np.zeros((n + 1, n + 1))
        a[:n, :n], a[:n, n], a[n, :n] = m - np.eye(n), f(end), normal
        d = np.linalg.solve(a, -r)
        u0, period = u0 + d[:n], period + d[n]
        if np.max(np.abs(d)) < 1e-10:
            break
    end, m = monodromy(f, jac, u0, period)
    return u0, period, m, float(np.max(np.abs(end - u0)))


def multipliers(f, jac, u0, period: float) -> np.ndarray:
    """The Floquet multipliers of the periodic orbit through (about) u0, nearest 1 first
    (the trivial one first)."""
    *_, m, residual = periodic_orbit(f, jac, u0, period)
    assert residual < 1e-8, f"shooting did not close the orbit: residual {residual:.1e}"
    mu = np.linalg.eigvals(m)
    return mu[np.argsort(np.abs(mu - 1.0))]
