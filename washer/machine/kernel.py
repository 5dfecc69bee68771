"""Thin numpy wrapper of the compiled kernel `washer._kernel` (C ABI in csrc/washer_api.h).

Every function takes and returns float64 numpy arrays, checks shapes, and
turns the kernel's error codes into `KernelError`. cffi releases the GIL during
each call, so threads can evaluate in parallel.
"""
from __future__ import annotations

import numpy as np

from washer.machine import layout

try:
    from washer._kernel import ffi, lib
except ImportError as exc:  # pragma: no cover - exercised only on broken installs
    raise ImportError(
        "the compiled kernel washer._kernel is missing: install the package with "
        "`pip install .` (needs a C++ compiler and libeigen3-dev), or build in place "
        "with `python build.py`") from exc

from washer import build_stamp  # noqa: E402  (after the import it checks)

build_stamp.check("washer._kernel", ffi, lib)

#: Speed laws of theta(t) and rotating-frame variants, by name.
LAWS = {"constant": 0, "spinup": 1}
FRAMES = {"frozen": 0, "averaged": 1}
N_DIFF = lib.washer_n_diff()
#: Parameter names of the columns of every parameter Jacobian.
DIFF_NAMES = tuple(layout.PARAM_NAMES[lib.washer_diff_param(j)] for j in range(N_DIFF))


class KernelError(RuntimeError):
    """The kernel refused an evaluation (NaN input, singular mass matrix, ...)."""

    def __init__(self, code: int, where: str):
        self.code = code
        super().__init__(f"{where}: {ffi.string(lib.washer_error_message(code)).decode()}")


def _check_layout() -> None:
    names = tuple(ffi.string(lib.washer_param_name(i)).decode()
                  for i in range(lib.washer_n_params()))
    if names != layout.PARAM_NAMES:
        raise ImportError("washer._kernel was built from another parameter layout than "
                          "washer/machine/layout.py: regenerate (python -m washer.codegen) and rebuild")


_check_layout()


def inputs_hash() -> str:
    """The code generator's input hash the kernel was compiled from."""
    return ffi.string(lib.washer_inputs_hash()).decode()


def _in(a, n: int | None = None, name: str = "array") -> np.ndarray:
    a = np.ascontiguousarray(a, dtype=float)
    if n is not None and a.shape != (n,):
        raise ValueError(f"{name}: expected shape ({n},), got {a.shape}")
    return a


def _ptr(a: np.ndarray):
    return ffi.cast("double *", ffi.from_buffer(a)) if a is not None else ffi.NULL


#: The kernel's code for an integration stopped by Ctrl-C (csrc/washer.h).
EINTERRUPTED = 7


def _call(rc: int, where: str) -> None:
    if rc == EINTERRUPTED:
        raise KeyboardInterrupt(f"{where}: interrupted")
    if rc:
        raise KernelError(rc, where)


def request_interrupt() -> None:
    """Stop every integration running in the kernel (from any thread) after its
    current step; each raises KeyboardInterrupt in its caller. Ctrl-C does this
    by itself while an integration runs."""
    lib.washer_request_interrupt()


def _law(law: str) -> int:
    if law not in LAWS:
        raise ValueError(f"law: expected one of {sorted(LAWS)}, got {law!r}")
    return LAWS[law]


def _frame(frame: str) -> int:
    if frame not in FRAMES:
        raise ValueError(f"frame: expected one of {sorted(FRAMES)}, got {frame!r}")
    return FRAMES[frame]


def _params(P) -> np.ndarray:
    return _in(P, layout.N_PARAMS, "parameter vector")


def mass_forces(q, qd, theta, w, wd, P):
    """M (6, 6) and f (6,) of eq 48 at given theta (rad), w (rad/s), wd (rad/s^2)."""
    M, f = np.empty((6, 6)), np.empty(6)
    _call(lib.washer_mass_forces(_ptr(_in(q, 6, "q")), _ptr(_in(qd, 6, "q_dot")), theta, w, wd,
                                 _ptr(_params(P)), _ptr(M), _ptr(f)), "mass_forces")
    return M, f


def speed_law(t: float, P, law: str) -> np.ndarray:
    """[theta, theta_dot, theta_ddot] (rad, rad/s, rad/s^2) at time t (s)."""
    out = np.empty(3)
    _call(lib.washer_speed_law(t, _ptr(_params(P)), _law(law), _ptr(out)), "speed_law")
    return out


def rhs_fixed(t: float, u, P, law: str = "spinup") -> np.ndarray:
    """du/dt of the ground-frame system (eq 48), u = (q, q_dot), shape (12,)."""
    du = np.empty(12)
    _call(lib.washer_rhs_fixed(t, _ptr(_in(u, 12, "u")), _ptr(_params(P)), _law(law), _ptr(du)),
          "rhs_fixed")
    return du


def jac_fixed(t: float, u, P, law: str = "spinup"):
    """(J (12, 12), Jp (12, N_DIFF)) of the ground-frame system; Jp columns: DIFF_NAMES."""
    J, Jp = np.empty((12, 12)), np.empty((12, N_DIFF))
    _call(lib.washer_jac_fixed(t, _ptr(_in(u, 12, "u")), _ptr(_params(P)), _law(law), _ptr(J),
                               _ptr(Jp)), "jac_fixed")
    return J, Jp


def rhs_rot(xi, P, frame: str = "averaged") -> np.ndarray:
    """d xi/dt of the rotating-frame system (eq 59), xi = (eps, eps_dot), shape (12,)."""
    out = np.empty(12)
    _call(lib.washer_rhs_rot(_ptr(_in(xi, 12, "xi")), _ptr(_params(P)), _frame(frame), _ptr(out)),
          "rhs_rot")
    return out


def jac_rot(xi, P, frame: str = "averaged"):
    """(J (12, 12), Jp (12, N_DIFF)) of the rotating-frame system."""
    J, Jp = np.empty((12, 12)), np.empty((12, N_DIFF))
    _call(lib.washer_jac_rot(_ptr(_in(xi, 12, "xi")), _ptr(_params(P)), _frame(frame), _ptr(J),
                             _ptr(Jp)), "jac_rot")
    return J, Jp


def _batch_params(P, n: int):
    P = np.ascontiguousarray(P, dtype=float)
    if P.shape == (layout.N_PARAMS,):
        return P, 0
    if P.shape == (n, layout.N_PARAMS):
        return P, layout.N_PARAMS
    raise ValueError(f"parameters: expected shape ({layout.N_PARAMS},) or ({n}, "
                     f"{layout.N_PARAMS}), got {P.shape}")


def _batch_states(X, name: str) -> np.ndarray:
    X = np.ascontiguousarray(X, dtype=float)
    if X.ndim != 2 or X.shape[1] != 12:
        raise ValueError(f"{name}: expected shape (n, 12), got {X.shape}")
    return X


def _batch_call(fn, n: int, where: str, *args) -> None:
    nfail = ffi.new("int *")
    rc = fn(n, *args, nfail)
    if rc:
        raise KernelError(rc, f"{where} (row {nfail[0]})")


def rhs_fixed_batch(t, U, P, law: str = "spinup") -> np.ndarray:
    """Ground-frame rhs for n states U (n, 12) at times t (n,), one or n parameter sets."""
    U = _batch_states(U, "U")
    n = U.shape[0]
    t = np.ascontiguousarray(np.broadcast_to(np.asarray(t, dtype=float), (n,)))
    P, stride = _batch_params(P, n)
    out = np.empty_like(U)
    _batch_call(lib.washer_rhs_fixed_batch, n, "rhs_fixed_batch", _ptr(t), _ptr(U), _ptr(P),
                stride, _law(law), _ptr(out))
    return out


def rhs_rot_batch(X, P, frame: str = "averaged") -> np.ndarray:
    """Rotating-frame rhs for n states X (n, 12), one or n parameter sets."""
    X = _batch_states(X, "X")
    P, stride = _batch_params(P, X.shape[0])
    out = np.empty_like(X)
    _batch_call(lib.washer_rhs_rot_batch, X.shape[0], "rhs_rot_batch", _ptr(X), _ptr(P), stride,
                _frame(frame), _ptr(out))
    return out


def jac_rot_batch(X, P, frame: str = "averaged"):
    """Rotating-frame Jacobians for n states: (J (n, 12, 12), Jp (n, 12, N_DIFF))."""
    X = _batch_states(X, "X")
    n = X.shape[0]
    P, stride = _batch_params(P, n)
    J, Jp = np.empty((n, 12, 12)), np.empty((n, 12, N_DIFF))
    _batch_call(lib.washer_jac_rot_batch, n, "jac_rot_batch", _ptr(X), _ptr(P), stride,
                _frame(frame), _ptr(J), _ptr(Jp))
    return J, Jp


def rhs_jac_rot_batch(X, P, frame: str = "averaged", columns=None):
    """Rotating-frame rhs and Jacobians for n states in one pass: (f (n, 12), J (n, 12, 12),
    Jp (n, 12, N_DIFF)); f is a by-product of the Jacobians (the values of rhs_rot_batch,
    bit for bit) at the cost of jac_rot_batch alone. columns: the columns of Jp computed
    (indices into DIFF_NAMES; None: all), the others 0; each column's values are the same
    whatever else is computed (the parameter derivatives not asked for are skipped)."""
    X = _batch_states(X, "X")
    n = X.shape[0]
    P, stride = _batch_params(P, n)
    mask = (1 << N_DIFF) - 1 if columns is None else sum(1 << j for j in set(columns))
    out, J, Jp = np.empty_like(X), np.empty((n, 12, 12)), np.empty((n, 12, N_DIFF))
    _batch_call(lib.washer_rhs_jac_rot_batch, n, "rhs_jac_rot_batch", _ptr(X), _ptr(P), stride,
                _frame(frame), _ptr(out), _ptr(J), _ptr(Jp), mask)
    return out, J, Jp


def integrate(system: str, mode: str, t0: float, y0, P, tout, rtol: float, atol: float,
              h0: float = 0.0, max_steps: int = 0):
    """Integrate with the kernel's DOPRI5 and dense output.

    system: "fixed" (mode = speed law) or "rotating" (mode = frame).
    Returns (Y (len(tout), 12), last step size, stats dict with nfev/naccept/nreject).
    tout must be finite and non-decreasing (KernelError otherwise, before any step);
    Ctrl-C stops the integration after the current step with KeyboardInterrupt.
    On failure raises KernelError carrying the outputs written so far in `.partial`.
    """
    if system == "fixed":
        sys_code, mode_code = 0, _law(mode)
    elif system == "rotating":
        sys_code, mode_code = 1, _frame(mode)
    else:
        raise ValueError(f"system: expected 'fixed' or 'rotating', got {system!r}")
    tout = np.ascontiguousarray(tout, dtype=float)
    Y = np.full((tout.size, 12), np.nan)
    h = ffi.new("double *", h0)
    stats = ffi.new("long[5]")
    rc = lib.washer_integrate(sys_code, mode_code, t0, _ptr(_in(y0, 12, "y0")), _ptr(_params(P)),
                              rtol, atol, tout.size, _ptr(tout), _ptr(Y), h, max_steps, stats)
    info = {"nfev": stats[0], "naccept": stats[1], "nreject": stats[2], "nout": stats[4]}
    if rc == EINTERRUPTED:
        raise KeyboardInterrupt(f"integrate ({system}, {mode}): interrupted")
    if rc:
        err = KernelError(rc, f"integrate ({system}, {mode})")
        err.partial = (tout[:stats[4]], Y[:stats[4]], info)
        raise err
    return Y, h[0], info


def flow_variational(t0: float, t1: float, u0, P, law: str = "constant", direction=None,
                     rtol: float = 1e-10, atol: float = 1e-12, h0: float = 0.0,
                     max_steps: int = 0):
    """Ground-frame flow of eq 48 with its variational equations, in one kernel call.

    Integrates u' = f(t, u), Phi' = J(t, u) Phi (Phi(t0) = I) and, if `direction` is
    given, s' = J s + Jp @ direction (s(t0) = 0) with DOPRI5, error control on all
    components. `direction` (N_DIFF,) weighs the parameter-Jacobian columns DIFF_NAMES
    (e.g. C_p + C_ox + C_oz for the tied joint damping).

    Returns (u1 (12,) = u(t1), Phi (12, 12) = du(t1)/du0, s (12,) = du(t1)/dp or zeros,
    stats dict nfev/naccept/nreject). With law 'constant' and t1 - t0 = 1/Omega (s),
    Phi is the monodromy matrix of the forced response.
    """
    u1, Phi, s = np.empty(12), np.empty((12, 12)), np.zeros(12)
    d = None if direction is None else _in(direction, N_DIFF, "direction")
    h = ffi.new("double *", h0)
    stats = ffi.new("long[5]")
    _call(lib.washer_flow_variational(_law(law), t0, t1, _ptr(_in(u0, 12, "u0")),
                                      _ptr(_params(P)), _ptr(d), rtol, atol, _ptr(u1),
                                      _ptr(Phi), _ptr(s), h, max_steps, stats),
          "flow_variational")
    return u1, Phi, s, {"nfev": stats[0], "naccept": stats[1], "nreject": stats[2]}
