"""AUTO demo 'lrz' (Lorenz) as sympy expressions: washer generates and compiles f and
its exact Jacobians (washer.cont.user_problem.user_files_sympy). The same equations as
tests/data/lrz/lrz.py."""
import sympy as sp

u = sp.symbols("x y z")
par = sp.symbols("rho beta sigma")          # PAR(1), PAR(2), PAR(3)
x, y, z = u
rho, beta, sigma = par
f = [sigma * (y - x), rho * x - y - x * z, x * y - beta * z]


def stpnt(u, par):
    u[:] = 0.0
    par[:3] = [0.0, 8.0 / 3.0, 10.0]
