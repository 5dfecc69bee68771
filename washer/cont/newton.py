"""The one Newton iteration of the package (AUTO's SOLVAE / NEWTONBV loop without
the arclength: the callers border and factor).

    x, iterations = newton(residual, step, x0, max_iter=..., converged=...)

Every corrector is this loop with its own correction and its own test: the
continuation's corrector (the bordered matrix [J; arclength row], Newton-chord on
BVPs, AUTO's EPSL/EPSU test on the correction and its divergence check), the start
correction (EPSU), and the machine's equilibria (a residual test, with or without
halving the step while |F| grows).

The continuation's corrector of equilibria and of the fold and Hopf loci (IPS 0, 1 with
difference Jacobians) also has a compiled form, this loop as Continuation.correct runs
it, written once in C: washer/cont/include/ae_correct.h, chosen and driven by
washer.cont.corrector_algebraic. A change to this loop, to Continuation.correct's stopping
or divergence test, to the central differences (washer.cont.differences: the step, the
points, the quotient) or Problem.second_derivatives' stencils, or to the loci's
equations (systems/fold.py, hopf.py) must be made in ae_correct.h too (the two are
held to the same iterates by tests/test_corrector_algebraic.py). The corrector of periodic
orbits (IPS 2, PeriodicOrbits with difference Jacobians) has one too, this loop with
PeriodicOrbits' residual, Jacobian and compiled factorisation in C++:
csrc/cont/po_correct.cpp, driven by washer.cont.corrector_periodic and chosen in the same place
(corrector_algebraic.compiled_corrector); a change to this loop, to Continuation.correct's
plane-arclength step or test, to PeriodicOrbits.residual / jacobian or to
VectorField.fu_fp's differences (washer.cont.differences) must be made there too (the
two give the same b- and s-files byte for byte: tests/test_corrector_periodic.py).
"""
from __future__ import annotations

import numpy as np


class ConvergenceError(RuntimeError):
    """A corrector (or start correction) did not converge."""


def newton(residual, step, x0, *, max_iter: int, residual_tol: float | None = None,
           converged=None, damped: bool = False, domain_errors: tuple = (),
           exhausted: str | None = None):
    """Newton's iteration x <- x + lam dx for residual(x) = 0.

    residual(x) -> F (m,); step(x, F, it) -> dx (n,), the Newton correction at x
    (-J^-1 F, bordered or chord-factorised as the caller decides), `it` counting
    iterations from 1. Stops with success at the first of:
    * residual_tol: max|F(x)| <= residual_tol * (1 + max|x|), tested before each
      step and after the last one (residual_tol = 0: F exactly zero);
    * converged(x_old, x_new, dx, it) -> bool, tested after each step (it may
      raise ConvergenceError itself: a divergence test).
    damped: halve lam from 1 while |F(x + lam dx)|_2 does not decrease (a lam
    below 1e-3 is taken anyway; below 1e-6 fails); residual values raising one of
    `domain_errors` count as not decreasing.
    Returns (x, iterations taken). Raises ConvergenceError (non-finite residual or
    correction, failed halving, no convergence in max_iter iterations: message
    `exhausted` if given); exceptions of residual and step propagate.
    """
    x = np.array(x0, dtype=float)
    F = None
    for it in range(1, max_iter + 1):
        if F is None:
            F = residual(x)
        if not np.isfinite(F).all():
            raise ConvergenceError("non-finite residual at a Newton iterate")
        if residual_tol is not None and np.max(np.abs(F)) <= residual_tol * (1 + np.max(np.abs(x))):
            return x, it - 1
        with np.errstate(all="ignore"):
            dx = step(x, F, it)
        if not np.isfinite(dx).all():
            raise ConvergenceError("singular Newton matrix")
        x_old = x
        if damped:
            lam, norm0 = 1.0, np.linalg.norm(F)
            while True:
                try:
                    Fn = residual(x + lam * dx)
                    ok = np.linalg.norm(Fn) < norm0 or lam < 1e-3
                except domain_errors:
                    ok = False
                if ok:
                    break
                lam /= 2
                if lam < 1e-6:
                    raise ConvergenceError(f"Newton line search failed at iteration {it}")
            x, F = x + lam * dx, Fn
        else:
            x, F = x + dx, None
        if converged is not None and converged(x_old, x, dx, it):
            return x, it
    if residual_tol is not None:
        if F is None:
            F = residual(x)
        if np.all(np.isfinite(F)) and np.max(np.abs(F)) <= residual_tol * (1 + np.max(np.abs(x))):
            return x, max_iter
    raise ConvergenceError(exhausted or f"no convergence in {max_iter} Newton iterations"
                           + ("" if F is None else f" (residual {np.max(np.abs(F)):.3e})"))
