"""A quadratic objective on the cusp surface: the test problem of algebraic optimisation
(IPS = 5).

    f(u, p) = u^3 - p1 u - p2 = 0          (p1 = PAR(1), p2 = PAR(2))
    FOPT = u + p1 - p1^2 - p2^2

Started at u = 1, p1 = 0.9, p2 = 0.1 (f = 0). With p1 free (p2 = 0.1) the solutions are
the curve p1 = u^2 - p2 / u, and FOPT along it is extremal where
d/du [u + p1 - p1^2] = 1 + (1 - 2 p1)(2 u + p2 / u^2) = 0; with p1 and p2 free, where
grad FOPT = lambda grad f in (u, p1, p2) on f = 0 (Lagrange). tests/test_algebraic_optimisation.py
solves both with sympy.
"""


def func(u, par):
    x, p1, p2 = u[0], par[0], par[1]
    return [x ** 3 - p1 * x - p2]


def stpnt(u, par):
    u[0] = 1.0
    par[0] = 0.9
    par[1] = 0.1


def fopt(u, par):
    p1, p2 = par[0], par[1]
    return u[0] + p1 - p1 * p1 - p2 * p2
