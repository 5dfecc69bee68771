"""Equilibria followed from the reference parameter set by natural continuation.

Newton's method started from a fixed guess finds *an* equilibrium, not
necessarily the one meant: at K_s = 500 N/m the rotating-frame Newton from the
static equilibrium lands on a tub turned half a revolution (eps6 = -3.12), and
at rest near K_s = 550 N/m it finds nothing. The machine's equilibrium of
interest is the *hanging, unrotated* one, and that is defined by connection:
the one reached from the reference set (`washer/data/reference.toml`, where
Newton from the hanging guess converges) by moving the parameters continuously.

`follow` does that: P(s) = P_ref + s (P_target - P_ref), s from 0 to 1, Newton
at each substep from a secant predictor, the step halved when a substep fails,
doubled after a success. A substep fails when Newton does not converge in
`NEWTON_ITER` iterations, when it moves more than `MAX_CORRECTION` away from
the predictor (a jump to another equilibrium), or when the sign of det J
changes (the path has passed a fold and Newton found the other branch). When
the step falls below `H_MIN` the branch ends before the target: the
equilibrium does not exist there (a fold), and `EquilibriumError` says where.

The result is an `Equilibrium`: the (6,) ndarray the callers always had, with
`.info` (an `EquilibriumInfo`) telling which equilibrium it is.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from washer.cont.newton import ConvergenceError, newton
from washer.machine import kernel, layout

#: Newton iterations per substep. From a secant predictor Newton converges
#: quadratically in 2-4 iterations; needing more means the step is too long.
NEWTON_ITER = 8
#: Largest accepted distance between a substep's predictor and its solution
#: (max-norm over [x, y, z] in m and angles in rad). Away from folds the other
#: equilibria met in Table 1's ranges lie >= 0.3 away (the half-turned tub: pi in
#: yaw; the tipped static branch: beta of the other sign), while a halved step
#: brings a legitimate correction (O(h^2) from the secant predictor) under this
#: bound. Near a fold the other branch comes close; the det-sign test catches it.
MAX_CORRECTION = 0.05
#: Smallest continuation step in s (the fraction of the parameter change).
H_MIN = 1e-7
#: Yaw (rad) beyond which an equilibrium is not the unrotated one: the suspension
#: holds the tub within a few hundredths of a radian at every set we followed.
YAW_LIMIT = 0.5


class EquilibriumError(RuntimeError):
    """No equilibrium found. `last` (an `Equilibrium` or None) is the last point
    of the branch reached before the continuation stopped."""

    def __init__(self, message: str, last=None):
        super().__init__(message)
        self.last = last


@dataclass(frozen=True)
class EquilibriumInfo:
    """Which equilibrium an `Equilibrium` is.

    kind: "static" (at rest, ground frame) or "rotating" (eqs 60-65);
    frame: None for static, else "averaged" or "frozen";
    branch: how it was reached, in words;
    path: {parameter: (reference value, target value)} of the parameters changed
      along the continuation (empty at the reference set or from a guess);
    steps, halvings: accepted substeps and step halvings of the continuation;
    residual: max |acceleration| at the solution (m/s^2, rad/s^2);
    yaw: the tub's yaw there (gamma at rest, eps6 rotating; rad);
    yaw_ref: the same at the reference set (rad);
    hanging: True when the point lies on the branch connected to the reference's
      hanging equilibrium (no fold passed) and |yaw| < YAW_LIMIT;
    sigma_min: smallest singular value of the 6x6 Jacobian d acc / d q (1/s^2;
      tends to 0 at a fold).
    """
    kind: str
    frame: str | None
    branch: str
    path: dict = field(default_factory=dict)
    steps: int = 0
    halvings: int = 0
    residual: float = float("nan")
    yaw: float = float("nan")
    yaw_ref: float = float("nan")
    hanging: bool = False
    sigma_min: float = float("nan")


class Equilibrium(np.ndarray):
    """An equilibrium q* or eps* (6,): a float ndarray with `.info`.

    Arithmetic on it gives plain ndarrays: a shifted point is no longer the
    equilibrium the info describes."""

    def __new__(cls, x, info: EquilibriumInfo | None = None):
        obj = np.array(x, dtype=float).view(cls)
        obj.info = info
        return obj

    def __array_finalize__(self, obj):
        self.info = getattr(obj, "info", None) if type(obj) is Equilibrium else None

    def __array_wrap__(self, arr, context=None, return_scalar=False):
        # ufunc results (q + dq, 2 * q, ...) are plain arrays without the claim.
        arr = np.asarray(arr)
        return arr[()] if return_scalar else arr

    def __reduce__(self):
        return (Equilibrium, (np.asarray(self), self.info))


def yaw_of(x) -> float:
    """Yaw of the tub (gamma, or eps6 in the rotating frame; index 5), rad."""
    return float(np.asarray(x)[5])


def changed_params(P_ref: np.ndarray, P_target: np.ndarray) -> dict:
    """{name: (reference value, target value)} of the kernel parameters that differ."""
    d = {}
    for i, name in enumerate(layout.PARAM_NAMES):
        if P_ref[i] != P_target[i]:
            d[name] = (float(P_ref[i]), float(P_target[i]))
    return d


def _newton(res, jac, x0, tol, max_iter):
    """Plain Newton (no damping: a substep that needs damping is too long), the
    package's one Newton (washer.cont.newton) with a residual test. Returns x or None."""
    try:
        return newton(res, lambda x, F, it: np.linalg.solve(jac(x), -F), x0,
                      max_iter=max_iter, residual_tol=tol)[0]
    except (ConvergenceError, kernel.KernelError, np.linalg.LinAlgError):
        return None


def follow(res, jac, x_ref, P_ref, P_target, *, tol: float = 1e-11, what: str = "equilibrium",
           on_step=None):
    """Natural continuation of res(x, P) = 0 from (x_ref, P_ref) to P_target.

    res(x, P) -> (n,), jac(x, P) -> (n, n); x_ref must solve res(x, P_ref) = 0;
    P may be any float vector (the kernel's parameters, or one applied load).
    on_step(x, P), when given, is called at every accepted point (the curve).
    Returns (x, steps, halvings). Raises EquilibriumError (with `.partial` =
    (x, P) at the last accepted point) when the step falls below H_MIN."""
    P_ref, P_target = np.asarray(P_ref, float), np.asarray(P_target, float)
    dP = P_target - P_ref
    x, s, h = np.array(x_ref, dtype=float), 0.0, 1.0
    x_prev, h_prev = None, None
    sign0 = np.sign(np.linalg.det(jac(x, P_ref)))
    steps = halvings = 0
    while s < 1.0:
        h = min(h, 1.0 - s)
        P = P_ref + min(s + h, 1.0) * dP
        # Secant predictor along the last accepted step (first step: constant).
        x_pred = x if x_prev is None else x + (x - x_prev) * (h / h_prev)
        xn = _newton(lambda y: res(y, P), lambda y: jac(y, P), x_pred, tol, NEWTON_ITER)
        ok = (xn is not None and np.max(np.abs(xn - x_pred)) <= MAX_CORRECTION
              and np.sign(np.linalg.det(jac(xn, P))) == sign0)
        if not ok:
            h /= 2
            halvings += 1
            if h < H_MIN:
                err = EquilibriumError(what)
                err.partial = (x, P_ref + s * dP, s)
                raise err
            continue
        x_prev, h_prev, x, s = x, h, xn, s + h
        steps += 1
        if on_step is not None:
            on_step(x, P)
        h = min(2 * h, 1.0)
    return x, steps, halvings


def sigma_min(J: np.ndarray) -> float:
    return float(np.linalg.svd(J, compute_uv=False)[-1])
