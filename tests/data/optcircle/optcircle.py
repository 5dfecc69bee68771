"""Circles with an objective: the test problem of optimisation of periodic orbits (IPS = 15).

    x' = mu x - y - b x r^2,   y' = x + mu y - b y r^2,   r^2 = x^2 + y^2
    (mu = PAR(1), b = PAR(4))

For mu, b > 0 the periodic orbits are the circles r^2 = rho = mu / b, of period 2 pi
(in polar coordinates r' = r (mu - b r^2), theta' = 1), born at the Hopf point mu = 0.
The objective FOPT = x^2 - x^4 - (b - 1)^2 (x = r cos theta: the averages of x^2 and x^4
are r^2 / 2 and 3 r^4 / 8) averages over an orbit to

    J(mu, b) = rho / 2 - 3 rho^2 / 8 - (b - 1)^2,      rho = mu / b.

Along the family in mu (b fixed) J is extremal where dJ/drho = 1/2 - 3 rho / 4 = 0:
rho = 2/3, mu = 2 b / 3 (J = 1/6 - (b - 1)^2). Over both parameters J is extremal where
moreover dJ/db at fixed mu, (1/2 - 3 rho / 4)(-mu / b^2) - 2 (b - 1), vanishes: b = 1,
mu = 2/3. FOPT varies around the optimal orbit (its gradient does not vanish there), so
the adjoint of the extended system is not zero.
"""


def func(u, par):
    x, y = u[0], u[1]
    mu, b = par[0], par[3]
    r2 = x * x + y * y
    return [mu * x - y - b * x * r2, x + mu * y - b * y * r2]


def stpnt(u, par):
    u[0] = u[1] = 0.0
    par[0] = -0.2
    par[3] = 1.5


def fopt(u, par):
    x2 = u[0] * u[0]
    return x2 - x2 * x2 - (par[3] - 1.0) ** 2
