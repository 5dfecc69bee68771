"""The corrector of algebraic continuation in one foreign call, for compiled equations.

    corrector = compiled_corrector(system, settings)     # None where it does not apply
    result = corrector.correct(x_pred, x_ref, ds)         # (x, iterations) or None

This is the compiled form of the package's one Newton loop (washer.cont.newton.newton as
washer.cont.iterator.Continuation.correct runs it on the sphere arclength): the same
iteration (the residual f(u, PAR), the central differences [f_u, f_PAR(ICP(1))] of
Problem.jacobian with the same points and quotients, the bordered matrix [J; 2 theta
(x - x_ref) / |ds|], x += dx) and the same stopping test (AUTO's EPSL on the parameter,
EPSU on the state, the divergence test of Continuation.correct), written in C in the
bridge of the user's file (washer/cont/compiled_shim.c: washer_ae_correct), which calls
FUNC directly: one foreign call per continuation point instead of a few hundred numpy
operations. The linear solve is Gaussian elimination with partial pivoting (LAPACK's
pivot order; its rounding may differ from LAPACK's in the last bit, far inside EPSU).

It applies to equilibria (IPS 0, 1; the system EquilibriumSystem with one free
parameter, the sphere arclength) of compiled AUTO user files (washer.cont.compiled) with
JAC = 0 (difference Jacobians). Everything else, and every case the compiled loop does
not finish cleanly (a non-finite residual, Jacobian or correction, a zero pivot: the
Python loop then repeats the correction and reports or resolves it as before), is the
Python loop. Continuation.correct makes the choice, in one place.
"""
from __future__ import annotations

import numpy as np

from washer.cont.newton import ConvergenceError
from washer.cont.settings import HMACH

#: Sizes up to which the dense corrector is used (beyond it the work is the Jacobian's,
#: and numpy's LAPACK is the better solver).
MAX_NDIM = 50


class CompiledCorrector:
    """washer_ae_correct of one run's compiled problem (see the module's docstring)."""

    def __init__(self, system, settings, divergence: float):
        self.sys, self.s, self.divergence = system, settings, divergence
        self.user = system.problem.user
        n = system.ndim
        self.npar = len(system.par)
        self.ip = system.free[0] - 1
        self.theta = np.ascontiguousarray(system.theta, dtype=float)
        k = n + 1
        self.work = np.zeros((2 * k + 1) * (2 * n + self.npar) + (n + 1) * (n + 4))
        self.x = np.empty(n + 1)
        self.iterations = np.zeros(1, dtype=np.int32)
        self.jac = np.empty((n, n + 1))
        self.tan = np.empty(3 * (n + 1) + 3)
        self.last = None          # (x, [f_u, f_lambda] at x, tangent data) of the last point

    def correct(self, x_pred, x_ref, ds: float, counters):
        """(x, iterations) of the corrector from x_pred on the sphere of radius |ds|
        about x_ref; None when the Python loop is to take over. ConvergenceError as the
        Python loop raises it (divergence, ITNW exhausted). The evaluations are added
        to `counters` (washer.cont.branch.Counters) as the Python loop counts them."""
        user, s = self.user, self.s
        if not user.func_ready:
            return None
        par = np.ascontiguousarray(self.sys.par, dtype=float)
        x_pred = np.ascontiguousarray(x_pred, dtype=float)
        x_ref = np.ascontiguousarray(x_ref, dtype=float)
        status = user.ae_correct(self.sys.ndim, self.npar, self.ip, par, x_pred, x_ref,
                                 self.theta, float(ds), s.EPSL, s.EPSU, s.ITNW,
                                 self.divergence, HMACH, self.x, self.iterations, self.jac,
                                 self.tan, self.work)
        self.last = None
        if status == 3:
            return None
        it = int(self.iterations[0])
        c = counters
        c.residuals += it
        c.jacobians += it
        c.factorisations += it
        if status == 1:
            raise ConvergenceError("Newton iterates diverge")
        if status == 2:
            raise ConvergenceError(f"no convergence in ITNW = {s.ITNW} iterations")
        x = self.x.copy()
        if status == 0:
            self.last = (x, self.jac.copy(), self.tan.copy() if self.tan[-1] == 1.0 else None)
        return x, it

    def jacobian_at(self, x):
        """[f_u, f_lambda] (NDIM, NDIM + 1) at x if x is the point the corrector has just
        converged to (computed there by the same differences as Problem.jacobian: the
        same values), else None."""
        last = self.last
        if last is not None and (last[0] is x or np.array_equal(last[0], x)):
            return last[1]
        return None

    def tangent_system(self, J, ref):
        """(z, factor) of Continuation.tangent's system [J; theta ref] z = e_last if J is
        the Jacobian of the point just converged to and ref its secant (x - x_ref) / ds:
        solved in the same foreign call, the factor giving its determinant (the BP test)
        and solves with LAPACK if anything asks for more; else None."""
        last = self.last
        if last is None or last[2] is None or J is not last[1]:
            return None
        m = len(ref)
        t = last[2]
        if not np.array_equal(t[m:2 * m], ref):
            return None
        return t[:m].copy(), _SolvedFactor(J, self.sys.border(ref), float(t[2 * m]),
                                           float(t[2 * m + 1]))


class _SolvedFactor:
    """The factor of [J; border] whose determinant the compiled corrector has computed:
    sign_logdet from it, solves (none on the continuation's path) with LAPACK."""

    def __init__(self, J, border, sign, logdet):
        self.J, self.border, self._sign_logdet = J, border, (sign, logdet)
        self._factor = None

    def sign_logdet(self) -> tuple[float, float]:
        return self._sign_logdet

    def solve(self, rhs):
        if self._factor is None:
            from washer.cont.linalg import dense_factor
            self._factor = dense_factor(self.J, self.border)
        return self._factor.solve(rhs)


def compiled_corrector(system, settings, divergence: float):
    """The compiled corrector of `system`, or None where the Python loop runs."""
    from washer.cont.compiled import CompiledProblem
    from washer.cont.systems.equilibrium import EquilibriumSystem
    problem = getattr(system, "problem", None)
    if type(system) is not EquilibriumSystem or not isinstance(problem, CompiledProblem):
        return None
    if problem.jac != 0 or problem.has_func_dfdu_batch or len(system.free) != 1 \
            or system.arclength != "sphere" or not 0 < system.ndim <= MAX_NDIM:
        return None
    if not hasattr(problem.user.lib, "washer_ae_correct"):
        return None
    return CompiledCorrector(system, settings, divergence)
