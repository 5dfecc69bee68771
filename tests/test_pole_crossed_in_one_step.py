"""A test function that changes sign through a pole crossed in one step is no special point.

On f = (u1 - p, u2 / (u1 - c)^3) the branch u = (p, 0) has f_u = diag(1, (p - c)^-3),
regular wherever it is defined, and the branch-point test (the determinant of the Newton
matrix bordered by the branch's direction) is sqrt(2) (p - c)^-3 (sympy below): no zero,
one sign change, through the pole at p = c. With DS = DSMAX = 0.1 one step goes from
p = 0.28284 (test -9.3e3) to 0.35355 (6.3e7) over c = 0.35: the secant puts the zero
next to the step's start, and the trials there move away from the pole, the test growing
in magnitude. Debian AUTO-07p 0.9.2 on the same equations (Fortran) and constants: no
label, "NOTE:Possible special point" at PT 4 (its Muller iteration runs out of ITMX), EP
at PT 10, p = 0.707107. The location's last converged trial there had the test at -1.24e5
against -1.22e5 at the step's start and +1.7e8 at its end (n-body's collinear branch
through the massless primary has the same shape), which the comparison with the larger end
alone passed as a zero.
"""
import numpy as np
import sympy as sp

from washer.cont.problem import Problem
from washer.run import run

C = 0.35


def _func(u, par):
    return np.array([u[0] - par[0], u[1] / (u[0] - C) ** 3])


def _stpnt(u, par):
    par[0], u[0], u[1] = 0.0, 0.0, 0.0


def bp_test_along_branch():
    """The branch-point test along u = (p, 0) (sympy): det [f_u f_p; t] with t the unit
    tangent (1, 0, 1) / sqrt(2), as a function of p."""
    u1, u2, p, c = sp.symbols("u1 u2 p c")
    f = sp.Matrix([u1 - p, u2 / (u1 - c) ** 3])
    J = f.jacobian([u1, u2, p]).subs({u1: p, u2: 0})
    M = J.col_join(sp.Matrix([[1, 0, 1]]) / sp.sqrt(2))
    return sp.simplify(M.det()), p, c


def test_a_sign_change_through_a_pole_is_not_labelled(tmp_path):
    q, p, c = bp_test_along_branch()
    assert sp.simplify(q - sp.sqrt(2) / (p - c) ** 3) == 0
    assert sp.solve(sp.numer(sp.together(q)), p) == []     # no zero, only the pole
    c_file = tmp_path / "c.pole"
    c_file.write_text("NDIM = 2, IPS = 1, ILP = 1, ICP = [1], ISP = 1, MXBF = 0, NMX = 10, "
                      "NPR = 100, DS = 0.1, DSMIN = 0.001, DSMAX = 0.1, EPSL = 1e-7, "
                      "EPSU = 1e-7, EPSS = 1e-4, NPAR = 1\n")
    r = run(c_file, verbose=False, files=False, problem=Problem(2, _func, _stpnt, name="pole"))
    got = [(s.ty, abs(s.pt), round(float(s.par[0]), 6)) for s in r.specials]
    assert got == [("EP", 1, 0.0), ("EP", 10, 0.707107)]
    pars = [float(x.par[0]) for x in r.rows]
    # the pole was crossed in one step, each step after the first 0.1 in arclength
    i = next(k for k, v in enumerate(pars) if v > C)
    assert pars[i - 1] < C < pars[i] and np.allclose(np.diff(pars)[1:], 0.1 / np.sqrt(2))
