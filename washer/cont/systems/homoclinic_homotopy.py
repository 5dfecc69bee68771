"""HomCont's homotopy start (ISTART = 3: STPNHO's set-up and FBHO's "starting solutions
using homotopy"): a homoclinic orbit grown from the equilibrium along its unstable
manifold, with no phase condition (NINT = 0).

The orbit leaves x0 at a fixed small distance eps_0 = PAR(IP) along the unstable
eigenspace, IP the first PAR after the equilibria (12 + NDIM for IEQUIB >= 0, 12 + 2 NDIM
for a heteroclinic orbit: washer.cont.systems.homoclinic's `homotopy_index`):

    NUNSTAB = 1:  u(0) = x0 + eps_0 v_{s+1}                                 (NDIM rows)
    NUNSTAB > 1:  u(0) = x0 + sum_j xi_j v_{s+j},  sum_j xi_j^2 = eps_0^2    (NDIM + 1 rows)
                  xi_j = PAR(IP + j)
    (u(1) - x0') . w_{s+i} = omega_i,  i = 1 .. NUNSTAB                     (NUNSTAB rows)
    f(x0) = 0 (IEQUIB = 1)

with v, w the right and left eigenvectors of A = f_u(x0) (rows sorted by real part,
s = NSTAB; x0' = x0 for a homoclinic orbit), omega_i = PAR(KP + i), KP = IP + NUNSTAB
(`omega_base`). The omega_i measure how far u(1) is from the stable manifold's tangent
space: continuing in T = PAR(11) and the omega_i until they
vanish (UZR on them) brings u(1) onto it, after which a regular run (ISTART = 1) takes
the orbit over with the projection conditions.

The start (IRS = 0, after the user's STPNT has set eps_0 and PAR): xi_1 = eps_0, the
other xi 0; u(t) = x0 + eps_0 v_{s+1} e^(l_{s+1} T t) on the uniform mesh (the linear
flow along the leading unstable direction) and omega_i its value at t = 1.
"""
from __future__ import annotations

import math

import numpy as np

def omega_base(ip: int, nunstab: int) -> int:
    """KP: PAR(KP + i) is omega_i, i = 1 .. NUNSTAB, after eps_0 = PAR(IP) and the xi_j =
    PAR(IP + j) (xi_1 alone, a copy of eps_0, for NUNSTAB = 1): KP = IP + NUNSTAB."""
    return ip + nunstab


def n_conditions(ndm: int, n_solved: int, nunstab: int) -> int:
    """INHO's NBC for ISTART = 3: NDIM (start) + NDIM per solved-for equilibrium
    (n_solved: 1 for IEQUIB = 1, 2 for -2) + 1 + (NUNSTAB with NUNSTAB > 1)."""
    return ndm * (1 + n_solved) + 1 + (nunstab if nunstab > 1 else 0)


def boundary_rows(u0, u1, x0, x1, par, V, W, nstab: int, nunstab: int,
                  ip: int) -> list[np.ndarray]:
    """FBHO's homotopy conditions (the module docstring) but for f(x0) = 0: u0, u1 the
    orbit's ends, x0, x1 the equilibria at t = 0 and 1 (NDIM,), V, W the right and left
    eigenvectors as rows (sorted by real part, signs continued)."""
    if nunstab == 1:
        start = [u0 - x0 - par[ip - 1] * V[nstab]]
    else:
        xi = np.array([par[ip - 1 + j] for j in range(1, nunstab + 1)])
        start = [u0 - x0 - xi @ V[nstab:nstab + nunstab],
                 np.array([xi @ xi - par[ip - 1] ** 2])]
    kp = omega_base(ip, nunstab)
    omega = np.array([(u1 - x1) @ W[nstab + i] - par[kp + i] for i in range(nunstab)])
    return start + [omega]


def start(x0, x1, par, lam, V, W, times, nstab: int, nunstab: int, ip: int) -> np.ndarray:
    """STPNHO's homotopy start: sets xi and omega in par (in place) and returns the
    profile (len(times), NDIM) along the leading unstable direction (module docstring);
    x0, x1 the equilibria at t = 0 and 1, lam x0's eigenvalues sorted by real part, V, W
    as in `boundary_rows` (both x0's, as STPNHO's), times the mesh's node times in
    [0, 1]."""
    eps0 = par[ip - 1]
    par[ip] = eps0
    for i in range(2, nunstab + 1):
        par[ip - 1 + i] = 0.0
    kp = omega_base(ip, nunstab)
    T = par[10]
    rate = float(lam[nstab].real)
    U = x0[None, :] + eps0 * V[nstab][None, :] * np.exp(rate * T * np.asarray(times))[:, None]
    end = x0 - x1 + eps0 * V[nstab] * math.exp(rate * T)
    for i in range(1, nunstab + 1):
        par[kp - 1 + i] = float(end @ W[nstab - 1 + i])
    return U


__all__ = ["boundary_rows", "n_conditions", "omega_base", "start"]
