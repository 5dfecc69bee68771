"""HomCont's n-homoclinic branch switching (ISTART = -N: INHO, FNHO, FBHO, TRANHO and
CPBKHO of homcont.f90; Oldeman, Champneys and Krauskopf's numerical Lin's method).

Near an orbit or inclination flip a 1-homoclinic orbit u (PAR(11) = T) has N-homoclinic
orbits nearby: orbits that follow u N times. ISTART = -N cuts u at x_max, its mesh point
farthest from the equilibrium x0, and continues N + 1 pieces side by side, each on
[0, 1] with its own time (NDIM = (N + 1) NDM):

    piece 0        x0 -> x_max            u_0' = PAR(10) f(u_0)
    piece k        x_max -> x0 -> x_max   u_k' = PAR(19 + 2k) f(u_k)     k = 1 .. N - 1
    piece N        x_max -> x0            u_N' = PAR(11) f(u_N)

with, besides the projection conditions (u_0(0) - x0 against the stable eigenspace of
A^T, u_N(1) - x0 against its unstable one) and the equilibrium's f(x0) = 0:

    u_{k+1}(0) - u_k(1) = PAR(20 + 2k) d        (ITWIST = 1; 0 with ITWIST = 0)   NDM rows
    (u_k(1) - umax_k) . f(x_max) = 0            (a Poincare section through x_max)  1 row
    k = 0 .. N - 1, and no integral condition.

d = PAR(NPAR - 2 NDM + 1 .. NPAR - NDM) is the adjoint v (ITWIST = 1) at x_max, unit length
(Lin's direction: the gaps PAR(20 + 2k) measure the distance between the unstable and
stable manifolds across the section), f(x_max) = PAR(NPAR - NDM + 1 .. NPAR); NPAR is the
constants' NPAR + 2 NDM (AUTO's NPARI). umax_k = u_k(1) at the start of the run. With
ITWIST = 0 there is no Lin direction and the pieces join exactly; instead NDM PAR(22) is
added to each of the NUNSTAB conditions at t = 1 (FBHO adds PAR(22) once per component of
its loop: the scale of a free parameter sought at 0 is immaterial, AUTO's is kept so that
PAR(22)'s values are AUTO's).

Free: N + 1 (+ NFIXED) of ICP (sib's run 7: the middle piece's time PAR(21), the gap
PAR(22) and a system parameter), then the equilibrium's.

The start (TRANHO) from a 1-homoclinic record (and its adjoint with ITWIST = 1): the
stored orbit on [0, t_max] is piece 0, on [t_max, 1] piece N, and the orbit rotated to
start at x_max (the stored node at t = 0 following the one at t = 1) each middle piece;
PAR(10) = T t_max, PAR(11) = T (1 - t_max), PAR(19 + 2k) = T, the gaps 0. All pieces go
onto one mesh, the merge of their own meshes (2 NTST - 2 intervals), which the restart
then adapts to NTST (ADAPT2).

Orbits whose angles turn (NRTN, the stored orbit from x0 to x0 + 2 pi NRTN): the cut is at
the point farthest from both ends in the first turning angle, each middle piece starts
2 pi NRTN further than the one before, and the last piece ends at x0 + 2 pi N NRTN
(TRANHO's shifts). From STPNT: the user's stpnt fills the N + 1 pieces and PAR's times,
gaps, Lin's direction and f(x_max) (`start_dimensions`). From a stored m-homoclinic
orbit's pieces to N > m: the last loop repeated (`more_pieces`).

Back (CPBKHO): a restart with ISTART >= 0 from a record of more than 2 NDM components
puts the pieces one after the other into one orbit with PAR(11) = PAR(10) + PAR(11) +
sum PAR(19 + 2k), PAR(10) = 0.
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from washer.cont import collocation as col

#: FBHO's piece times: PAR(10) the first piece's (the unstable manifold's tail),
#: PAR(11) the last's (the stable manifold's tail), PAR(19 + 2k) the k-th middle one's.
FIRST_TIME, LAST_TIME = 10, 11


def n_pieces(istart: int) -> int:
    """N + 1 for ISTART = -N."""
    return 1 - istart


def time_index(k: int, n_piece: int) -> int:
    """The PAR index of piece k's time (of n_piece pieces)."""
    if k == 0:
        return FIRST_TIME
    if k == n_piece - 1:
        return LAST_TIME
    return 19 + 2 * k


def gap_index(k: int) -> int:
    """The PAR index of the gap between piece k and k + 1 (k = 0 .. N - 1)."""
    return 20 + 2 * k


def start_dimensions(ndm: int, istart: int, npar: int) -> tuple[int, int]:
    """(NDIM, NPAR) of ISTART = -N's pieces: (N + 1) NDM components, and INHO's NPARI =
    2 NDM after the constants' NPAR (at least the last gap's index)."""
    n_piece = n_pieces(istart)
    return n_piece * ndm, max(npar, gap_index(n_piece - 2)) + 2 * ndm


def field(user, ndm: int, n_piece: int):
    """(func_batch, dfdu_batch) of the pieces W (k, n_piece NDM), pars (k, NPAR) ->
    (k, n_piece NDM) and its block-diagonal Jacobian, each piece scaled by its time."""
    idx = [time_index(k, n_piece) - 1 for k in range(n_piece)]

    def func_batch(W, pars):
        return np.hstack([pars[:, i:i + 1] * user.func_many(W[:, k * ndm:(k + 1) * ndm], pars)
                          for k, i in enumerate(idx)])

    def dfdu_batch(W, pars):
        J = np.zeros((len(W), n_piece * ndm, n_piece * ndm))
        for k, i in enumerate(idx):
            s = slice(k * ndm, (k + 1) * ndm)
            J[:, s, s] = pars[:, i, None, None] * user.dfdu_many(W[:, s], pars)
        return J

    return func_batch, dfdu_batch


def lin_slices(npar: int, ndm: int) -> tuple[slice, slice]:
    """The 0-based PAR slices of Lin's direction d and of f(x_max)."""
    return slice(npar - 2 * ndm, npar - ndm), slice(npar - ndm, npar)


def boundary_rows(w0, w1, par, ndm: int, n_piece: int, lin: bool, umax) -> list[np.ndarray]:
    """FBHO's continuity-with-gaps and section conditions (module docstring): w0, w1 the
    pieces' ends (n_piece NDM,), umax the ends at the run's start."""
    d_sl, f_sl = lin_slices(len(par), ndm)
    d, fmax = np.asarray(par[d_sl], float), np.asarray(par[f_sl], float)
    gaps, sections = [], []
    for k in range(n_piece - 1):
        a, b = slice((k + 1) * ndm, (k + 2) * ndm), slice(k * ndm, (k + 1) * ndm)
        g = w0[a] - w1[b]
        if lin:
            g = g - par[gap_index(k) - 1] * d
        gaps.append(g)
        sections.append((w1[b] - umax[b]) @ fmax)
    return gaps + [np.array(sections)]


def pieces_from_orbit(rec, ndm: int, n_piece: int, par: np.ndarray, lin: bool, func):
    """TRANHO: the record of a 1-homoclinic orbit (its adjoint beside it where `lin`) as
    the start of ISTART = 1 - n_piece; sets PAR's times, gaps, d and f(x_max) in `par`
    (its length NPAR, in place). `func(u, par)` is the user's f. Returns the record."""
    from washer.cont.systems.bvp import record_profile
    t, U, ntst, ncol = record_profile(rec, (2 if lin else 1) * ndm)
    if lin and U.shape[1] < 2 * ndm:
        raise ValueError("ISTART < 0 with ITWIST = 1: Lin's direction is the adjoint at "
                         "x_max, and the restart record has no adjoint (restart from a "
                         "run with ITWIST = 1)")
    x0 = par[11:11 + ndm]
    tm = np.asarray(t[::ncol], float)
    turn = 2 * np.pi * rotations(U[0, :ndm], U[-1, :ndm])
    if np.any(turn):
        # an orbit whose angle turns (x0 to x0 + 2 pi NRTN): its farthest point from
        # both ends in the first turning angle (TRANHO's "point in the middle")
        i = int(np.flatnonzero(turn)[0])
        ui = U[::ncol, i]
        jmax = int(np.argmax(np.minimum(np.abs(ui - x0[i]), np.abs(ui - x0[i] - turn[i]))))
    else:
        jmax = int(np.argmax(np.sum((U[::ncol, :ndm] - x0) ** 2, axis=1)))
    if jmax in (0, ntst):
        raise ValueError("ISTART < 0: the stored orbit is farthest from the equilibrium "
                         "at an end; it is not a homoclinic orbit to PAR(12 ..)")
    tmax, k = float(tm[jmax]), jmax * ncol
    xmax = U[k, :ndm]
    d_sl, f_sl = lin_slices(len(par), ndm)
    par[f_sl] = func(xmax, par)
    T = par[LAST_TIME - 1]
    par[FIRST_TIME - 1] = T * tmax
    par[gap_index(0) - 1] = 0.0
    for j in range(1, n_piece - 1):
        par[time_index(j, n_piece) - 1] = T
        par[gap_index(j) - 1] = 0.0
    par[LAST_TIME - 1] = T * (1 - tmax)
    if lin:
        v = U[k, ndm:2 * ndm]
        par[d_sl] = v / np.linalg.norm(v)
    mesh = col.Mesh(tm, ncol)
    # the orbit from x_max round to x_max: the node at t = 0 follows the one at t = 1
    # (an angle turned on by 2 pi NRTN, so that the loop is continuous)
    rot = col.Mesh(np.r_[tm[jmax:-1] - tmax, tm[:jmax + 1] + 1 - tmax], ncol)
    U_rot = np.vstack([U[k:-1, :ndm], U[:k + 1, :ndm] + turn])
    inner = np.r_[tm[1:jmax] / tmax, rot.tm[1:-1], (tm[jmax + 1:-1] - tmax) / (1 - tmax)]
    tm_new = np.r_[0.0, np.unique(inner), 1.0]
    new = col.Mesh(tm_new, ncol)
    s = new.node_times()
    first = col.evaluate(mesh, U[:, :ndm], s * tmax)
    last = col.evaluate(mesh, U[:, :ndm], tmax + s * (1 - tmax))
    middle = col.evaluate(rot, U_rot, s)
    # each loop turns the angles once more: middle piece j starts 2 pi NRTN (j - 1) on,
    # the last 2 pi NRTN (N - 1), and ends at x0 + 2 pi N NRTN
    W = np.hstack([first] + [middle + j * turn for j in range(n_piece - 2)]
                  + [last + (n_piece - 2) * turn])
    return SimpleNamespace(U=W, t=s, ntst=new.ntst, ncol=ncol, udot=None, rldot=[], icp=[],
                           lab=getattr(rec, "lab", 0))


def more_pieces(rec, ndm: int, n_piece: int, par: np.ndarray, lin: bool):
    """PREHO's copy of the forelast piece: the record of an m-homoclinic orbit's m + 1
    pieces as the start of n_piece = N + 1 > m + 1 pieces. The pieces before the last
    stay, the last loop (piece m - 1, x_max round to x_max) is repeated N - m times, each
    copy with its time PAR(19 + 2 (m - 1)) and turned on by the loop's own 2 pi NRTN, the
    last piece after them. The gaps (in `par`, in place, with Lin's direction, ITWIST = 1)
    are the last gap before for the join into the last piece and, between the loops, the
    loop's own mismatch u(0) - u(1) along Lin's direction (Newton closes what lies
    across it). AUTO copies pieces 2m - N .. m - 1 (for N > m + 1 not each a loop; the
    forelast alone here) and takes a gap from the first components alone. Returns the
    record."""
    from washer.cont.systems.bvp import record_profile
    m_piece = np.shape(rec.U)[1] // ndm
    t, U, ntst, ncol = record_profile(rec, m_piece * ndm)
    m, extra = m_piece - 1, n_piece - m_piece
    loop = U[:, (m - 1) * ndm:m * ndm]
    turn = 2 * np.pi * rotations(U[0, :ndm], U[-1, m * ndm:]) / m
    copies = [loop + j * turn for j in range(1, extra + 1)]
    W = np.hstack([U[:, :m * ndm]] + copies + [U[:, m * ndm:] + extra * turn])
    d_sl, _ = lin_slices(len(par), ndm)
    mismatch = float((loop[0] - loop[-1] + turn) @ par[d_sl]) if lin else 0.0
    last_gap, loop_time = par[gap_index(m - 1) - 1], par[time_index(m - 1, m_piece) - 1]
    for j in range(m, n_piece - 1):
        par[time_index(j, n_piece) - 1] = loop_time
    for j in range(m - 1, n_piece - 2):
        par[gap_index(j) - 1] = mismatch
    par[gap_index(n_piece - 2) - 1] = last_gap
    return SimpleNamespace(U=W, t=np.asarray(t, float), ntst=ntst, ncol=ncol, udot=None,
                           rldot=[], icp=[], lab=getattr(rec, "lab", 0))


def rotations(u0, u1) -> np.ndarray:
    """NRTN (NDIM,): the whole turns 2 pi NRTN of each component from u0 to u1, the ends
    of an orbit whose angles turn (SETRTN's count); zeros where none turns."""
    return np.rint((np.asarray(u1, float) - np.asarray(u0, float)) / (2 * np.pi))


def orbit_from_pieces(rec, ndm: int, par: np.ndarray):
    """CPBKHO: the record of an n-homoclinic orbit's pieces (n_piece NDM components) as
    one orbit of NDM components on n_piece NTST intervals; PAR(11) becomes the total
    time, PAR(10) 0 (in `par`, in place). Returns the record."""
    from washer.cont.systems.bvp import record_profile
    U = np.asarray(rec.U, float)
    n_piece = U.shape[1] // ndm
    t, U, ntst, ncol = record_profile(rec, n_piece * ndm)
    times = [par[time_index(k, n_piece) - 1] for k in range(n_piece)]
    total = float(sum(times))
    base = np.cumsum([0.0] + times[:-1])
    ts = [(base[k] + t[:-1] * times[k]) / total for k in range(n_piece)]
    Us = [U[:-1, k * ndm:(k + 1) * ndm] for k in range(n_piece)]
    t_new = np.r_[np.concatenate(ts), 1.0]
    U_new = np.vstack(Us + [U[-1:, (n_piece - 1) * ndm:]])
    par[FIRST_TIME - 1], par[LAST_TIME - 1] = 0.0, total
    return SimpleNamespace(U=U_new, t=t_new, ntst=ntst * n_piece, ncol=ncol, udot=None,
                           rldot=[], icp=[], lab=getattr(rec, "lab", 0))


__all__ = ["boundary_rows", "field", "more_pieces", "n_pieces", "orbit_from_pieces",
           "pieces_from_orbit", "start_dimensions",
           "rotations", "time_index", "gap_index", "lin_slices"]
