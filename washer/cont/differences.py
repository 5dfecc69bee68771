"""Central differences, the engine's one definition of them: the step h = rel (1 + |x_j|)
per component (rel = HMACH, AUTO's; AUTO-07p 0.9.2's FUNI, BCNI, ICNI take one step rel
(1 + max_i |x_i|) for all components of x: `shared_step`, which the Hopf locus's start
uses), the points x + h e_j and x - h e_j, and the quotient
(f(x + h e_j) - f(x - h e_j)) / (2 h).

Every finite-difference first derivative of the engine (f_u, f_PAR, the derivatives of
bcnd, icnd and fopt, the Jacobians of the extended systems) is built from these, so that
the same point gives the same bits whichever system asks for it. Error: truncation
h^2 |f'''| / 6 against rounding eps |f| / h, about 1e-9 relative at rel = HMACH = 1e-7
for f of order one (AUTO's choice). Systems that difference a first difference again
pass a larger rel (bvp.H2, the loci's DIR_STEP); the mixed second differences of
Problem.second_derivatives have their own stencil.

The compiled correctors repeat these differences in C: washer/cont/include/ae_correct.h
(equilibria, fold and Hopf loci) and csrc/cont/po_correct.cpp (periodic orbits). A change
here is made there too; tests/test_corrector_algebraic.py and tests/test_corrector_periodic.py hold
the two forms to the same iterates.
"""
from __future__ import annotations

import numpy as np

from washer.cont.settings import HMACH

#: Relative step of the finite-difference Jacobians: AUTO's HMACH = 1e-7.
FD_STEP = HMACH


def step(x, rel: float = FD_STEP):
    """The step at x: rel (1 + |x|), for a float or elementwise for an array (same shape)."""
    return rel * (1 + abs(x))


def shared_step(u, rel: float = FD_STEP) -> float:
    """AUTO-07p 0.9.2's own step for f_u (FUNI of its INTERFACES module, JAC = 0): one
    step rel (1 + max_i |u_i|) for every component of u (seen in the arguments its FUNC
    is called with: u_2 = 0.01 beside u_1 = 10 is moved by 1.1e-6). The engine's
    Jacobians take `step` per component (a small component keeps a step its own size);
    the Hopf locus's start takes this one,
    where the rounding of f_u picks one vector of a two-dimensional null space
    (`washer.cont.systems.hopf`)."""
    return rel * (1 + float(np.max(np.abs(u)))) if len(u) else rel


def quotient(f_plus, f_minus, h):
    """(f_plus - f_minus) / (2 h): the derivative from f at x + h e and at x - h e. h
    broadcasts against the values (a float, or h[:, None] for one step per row)."""
    return (f_plus - f_minus) / (2 * h)


def par_points(par, index: int, rel: float = FD_STEP):
    """(h, PAR + h e_index, PAR - h e_index): the parameter vectors (new float arrays,
    shape of par) of a central difference in PAR(index) (1-based), h = step(PAR(index))."""
    h = step(par[index - 1], rel)
    pp, pm = np.array(par, float), np.array(par, float)
    pp[index - 1] += h
    pm[index - 1] -= h
    return h, pp, pm


def u_points(us: np.ndarray, rel: float = FD_STEP) -> tuple[np.ndarray, np.ndarray]:
    """The points of central differences in u at the rows of us (k, n): (pts (2 n k, n):
    for each row u, u + h_j e_j for j = 0..n-1, then u - h_j e_j; h (k, n) = step(us)).
    `u_quotient` turns f at these points into the k Jacobians."""
    k, n = us.shape
    h = step(us, rel)                                   # (k, n)
    pts = np.empty((k, 2 * n, n))
    pts[:] = us[:, None, :]
    # the diagonals of the +h and -h blocks as strided views (basic slices: no
    # fancy-index set-up; the same additions)
    flat = pts.reshape(k, 2 * n * n)
    flat[:, 0:n * n:n + 1] += h
    flat[:, n * n::n + 1] -= h
    return pts.reshape(-1, n), h


def u_quotient(F: np.ndarray, h: np.ndarray) -> np.ndarray:
    """The Jacobians d f / d u (k, m, n) ([:, row, column]) from f (2 n k, m) at
    `u_points`' points with their steps h (k, n)."""
    k, n = h.shape
    F = F.reshape(k, 2 * n, -1)
    return np.transpose(quotient(F[:, :n], F[:, n:], h[:, :, None]), (0, 2, 1))


def columns(fun, z: np.ndarray, cols, rel: float = FD_STEP) -> np.ndarray:
    """d fun / d z_j for j in cols, one call of fun per point (fun: (len(z),) -> (m,)):
    shape (m, len(cols))."""
    out = []
    for j in cols:
        h = step(z[j], rel)
        zp, zm = z.copy(), z.copy()
        zp[j] += h
        zm[j] -= h
        out.append(quotient(fun(zp), fun(zm), h))
    return np.array(out).T
