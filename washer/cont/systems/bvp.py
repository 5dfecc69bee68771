"""The base of every system discretised by collocation on [0, 1] (AUTO's BVP family:
periodic orbits, the loci of their special points, and later general BVPs): the mesh,
the unknown layout, the weighted inner product, the sparse factorisation, the phase
reference, mesh adaptation, the restart of a stored profile, the reduction of the
bordered matrix onto the boundary unknowns, and the b-file columns.

Unknowns x = (W flattened node-major (NTST*NCOL + 1, n_comp), then `n_tail` parameter
unknowns in the order the subclass chooses, PAR(ICP(1)) last). W's first NDIM components
are the user's u; loci append their extra components (v of the fold of cycles).

A subclass sets, before calling `set_mesh`: `settings`, `problem`, `ndim` (the user's
NDIM), `n_comp`, `nint` (the integral conditions), `tail_weights()` (the THL weights of
the n_tail = nint + 1 parameter unknowns, in layout order), and implements residual,
jacobian, params, period(par), stability, active_tests, test_functions, accept,
solution and directions. What it gets (the contract's BVP hooks, read by the iterator):

wants_remesh(n_points) -> bool, remesh(x, *vectors) -> tuple
    AUTO's ADAPT every IAD written points: a new mesh equidistributing the profile of u
    (same NTST, NCOL); x and the vectors (tangent, ...) are interpolated onto it, the
    phase reference too, and `mesh_changed()` drops what the subclass cached.
"""
from __future__ import annotations

import functools
import math

import numpy as np

from washer.cont.codes import Code
from washer.cont import collocation as col
from washer.cont import linalg, reduction
from washer.cont.linalg import PERMC_SPEC, SparseFactor
from washer.cont.differences import par_points, quotient, u_points, u_quotient
from washer.cont.problem import broadcast_rows
from washer.cont.pvls import Orbit
from washer.cont.system import Solution, fold_test

#: Relative step of the mixed second differences of f (eps^(1/4)).
H2 = 1e-4


#: Factorise the Newton and tangent systems with the compiled condensation and block
#: reduction (washer.cont.reduction) when it is built, instead of SuperLU: the same
#: solutions to rounding (one refinement step per solve, tests/test_reduction.py), 2-30x
#: faster per factorisation. (ab's family from HB10, under-resolved near its homoclinic
#: end, had stopped at PT 127 with it; that was the phase reference after ADAPT, fixed
#: since: both now reach AUTO's PERIOD = 1000 in 250 points.)
COMPILED_FACTOR = True


#: Up to how many points `VectorField.fu_fp` makes one call of all its stencils: beyond,
#: assembling the one call's arrays (the parameters for every stencil point) costs more
#: than the calls it saves (callgrind on lrz: 12 % fewer instructions at 140 Gauss
#: points, NTST 35; 15 % more at 800, NTST 200).
FU_FP_ONE_CALL_MAX = 400

_EPS = float(np.finfo(float).eps)


@functools.lru_cache(maxsize=None)
def _bp_void_logdet(n: int) -> float:
    """log of a bound on |det(S / |S|_F)| (as LU computes it, n x n) wherever the BP
    test's singular values could say "no test" (`CollocationBVP.bp_value`): above it they
    cannot, and are not computed. Where the computed s_{n-2} <= n eps s_0, the exact one
    is below (n + p) eps s_0 with p <= n^2 the SVD's error (in units of eps s_0); with
    s_0 <= |S|_F, |det(S / |S|_F)| <= (s_{n-2} / s_0)^2 <= (2 n^2 eps)^2. The LU's
    determinant is that of S / |S|_F + E, |E|_2 <= 8 n^4 g eps (Wilkinson's bound, in the
    2-norm, with the growth of partial pivoting g <= 2^(n-1)), which moves each of the two
    smallest singular values by at most that and the others by a factor near 1: below
    2 (2 n^2 eps (1 + 8 n^4 2^(n-1)))^2."""
    bound = 2 * (2 * n * n * _EPS * (1 + 8 * n ** 4 * 2.0 ** (n - 1))) ** 2
    return math.log(bound)


class VectorField:
    """f, f_u, f_p of a washer.cont.problem.Problem at many points at once: a thin
    adapter over Problem.func_many / dfdu_many (one batched or vectorised call per
    stencil, the user's Jacobian when JAC != 0, else central differences with AUTO's
    step, washer.cont.differences)."""

    def __init__(self, problem, ndim: int):
        self.problem, self.ndim = problem, ndim
        self._last_f = None

    def f(self, U: np.ndarray, par: np.ndarray, with_jacobian: bool = False) -> np.ndarray:
        """f at the rows of U (k, NDIM) -> (k, NDIM). The last call's values are kept:
        Newton's Jacobian (its PERIOD column T f) asks for f at the Gauss points of the
        iterate whose residual has just asked for them; a copy is returned.
        with_jacobian: f_u and f_p at these points are asked for next
        (Problem.func_many_with_jacobian: the washer's kernel gives them in the same pass)."""
        U = np.asarray(U, float)
        par = np.asarray(par, float)
        key = (U.shape, U.tobytes(), par.shape, par.tobytes())
        last = self._last_f
        if last is not None and last[0] == key:
            return last[1].copy()
        F = (self.problem.func_many_with_jacobian(U, par)
             if with_jacobian and getattr(self.problem, "has_func_dfdu_batch", False)
             else self.problem.func_many(U, par))
        self._last_f = (key, F.copy())
        return F

    def fu(self, U: np.ndarray, par: np.ndarray) -> np.ndarray:
        """f_u at the rows of U -> (k, NDIM, NDIM)."""
        U = np.asarray(U, float)
        return self.problem.dfdu_many(U, broadcast_rows(np.asarray(par, float), len(U)))

    def fp(self, U: np.ndarray, par: np.ndarray, index: int) -> np.ndarray:
        """d f / d PAR(index) at the rows of U -> (k, NDIM): the user's batched dfdp
        (JAC = 1, one call for all rows; the washer's kernel returns it with f_u), else
        central differences in two batched calls (a per-point analytic dfdp costs k
        calls: on the washer, 8640 kernel calls took 40 % of a run; the difference
        quotient is accurate to ~1e-9 relative, ample for Newton's parameter column)."""
        if self.problem.has_dfdp_batch:
            U = np.asarray(U, float)
            return self.problem.dfdp_many(U, broadcast_rows(np.asarray(par, float), len(U)), index)
        h, pp, pm = par_points(par, index)
        # straight to the problem: nobody asks for f at these parameters again, and
        # `f`'s copy kept for the PERIOD column stays
        U = np.asarray(U, float)
        return quotient(self.problem.func_many(U, pp), self.problem.func_many(U, pm), h)

    def fu_fp(self, U: np.ndarray, par: np.ndarray, indices) -> tuple[np.ndarray, list]:
        """(fu(U, par), [fp(U, par, i) for i in indices]). When all of them are central
        differences of f (no user Jacobians in use), their stencils go to the user's func
        in ONE call (f_u's 2 NDIM k points, then U at PAR(i) + h and at PAR(i) - h for
        each i): the same points and quotients as fu and fp, one call instead of
        1 + 2 len(indices) (each costs a fixed overhead that outweighs a small system's
        arithmetic), for up to FU_FP_ONE_CALL_MAX points."""
        prob = self.problem
        indices = list(indices)
        if (not indices or prob.has_dfdu or prob.has_dfdp_batch
                or len(U) > FU_FP_ONE_CALL_MAX):
            return self.fu(U, par), [self.fp(U, par, i) for i in indices]
        U = np.asarray(U, float)
        par = np.asarray(par, float)
        k = len(U)
        pts, h = u_points(U)
        m = len(pts)
        steps = [par_points(par, i) for i in indices]
        us = np.concatenate([pts] + [U] * (2 * len(steps)))
        # the parameters column by column (the user's func reads the rows of pars.T:
        # contiguous ones)
        parsT = np.empty((len(par), len(us)))
        parsT[:, :m] = par[:, None]
        for j, (_, pp, pm) in enumerate(steps):
            parsT[:, m + 2 * j * k:m + (2 * j + 1) * k] = pp[:, None]
            parsT[:, m + (2 * j + 1) * k:m + (2 * j + 2) * k] = pm[:, None]
        F = prob.func_many(us, parsT.T)
        A = u_quotient(F[:m], h)
        fps = [quotient(F[m + 2 * j * k:m + (2 * j + 1) * k],
                        F[m + (2 * j + 1) * k:m + (2 * j + 2) * k], hj)
               for j, (hj, _, _) in enumerate(steps)]
        return A, fps

    def fuu_v(self, U: np.ndarray, V: np.ndarray, par: np.ndarray) -> np.ndarray:
        """The matrices d/du (f_u(u) v) at the rows of U, V (k, NDIM) -> (k, NDIM, NDIM)
        ([:, row, column]): mixed central differences of f, one batched call of 4 NDIM k
        points, steps ~ eps^(1/4) (error ~1e-8 relative)."""
        k, n = U.shape
        vmax = np.maximum(np.max(np.abs(V), axis=1, keepdims=True), 1e-300)
        hk = H2 * (1 + np.max(np.abs(U), axis=1, keepdims=True)) / vmax      # k v small
        h = H2 * (1 + np.abs(U))                                             # (k, n)
        E = np.eye(n)[None] * h[:, :, None]                                  # (k, n, n)
        kv = (hk * V)[:, None, :]
        pts = np.concatenate([U[:, None] + E + kv, U[:, None] + E - kv,
                              U[:, None] - E + kv, U[:, None] - E - kv], axis=1)
        F = self.f(pts.reshape(-1, n), par).reshape(k, 4, n, n)
        d = (F[:, 0] - F[:, 1] - F[:, 2] + F[:, 3]) / (4 * h[:, :, None] * hk[:, :, None])
        return np.transpose(d, (0, 2, 1))

    def fuu_adjoint(self, U: np.ndarray, Phi: np.ndarray, par: np.ndarray) -> np.ndarray:
        """The matrices d/du (f_u(u)^T phi) at the rows of U, Phi (k, NDIM) -> (k, NDIM,
        NDIM) ([:, row, column]; the Hessian of phi . f, symmetric). With the user's f_u:
        its central differences, AUTO's step HMACH (1 + |u_j|) (FNPBP differences its
        extended system so; the steps stay below a small orbit's size, where the mixed
        differences of f, steps ~1e-4, straddle a non-smooth |u|: lcbp's circles shrinking
        to their Hopf point); else `fuu_v` along each unit vector (one batched call)."""
        k, n = U.shape
        if getattr(self.problem, "has_dfdu", False):
            pts, h = u_points(U)                                            # h (k, n)
            A = self.fu(pts, par).reshape(k, 2, n, n, n)                    # [k, +-, j, l, i]
            dA = quotient(A[:, 0], A[:, 1], h[:, :, None, None])
            return np.einsum("kl,kjli->kij", Phi, dA)
        M = self.fuu_v(np.tile(U, (n, 1)), np.repeat(np.eye(n), k, axis=0), par)
        return np.einsum("kl,iklj->kij", Phi, M.reshape(n, k, n, n))

    def fup_adjoint(self, U: np.ndarray, Phi: np.ndarray, par: np.ndarray,
                    index: int) -> np.ndarray:
        """d/dp (f_u(u)^T phi) for p = PAR(index) at the rows of U, Phi -> (k, NDIM):
        component i is phi . (d f_u / dp) e_i. With the user's f_u: its central
        difference in p (step HMACH (1 + |p|)); else `fup_v` along each unit vector
        (one batched call)."""
        k, n = U.shape
        if getattr(self.problem, "has_dfdu", False):
            h, pp, pm = par_points(par, index)
            dA = quotient(self.fu(U, pp), self.fu(U, pm), h)
            return np.einsum("kl,kli->ki", Phi, dA)
        M = self.fup_v(np.tile(U, (n, 1)), np.repeat(np.eye(n), k, axis=0), par, index)
        return np.einsum("kl,ikl->ki", Phi, M.reshape(n, k, n))

    def fup_v(self, U: np.ndarray, V: np.ndarray, par: np.ndarray, index: int) -> np.ndarray:
        """d/dp (f_u(u) v) for p = PAR(index) at the rows of U, V -> (k, NDIM), by mixed
        central differences of f (two batched calls)."""
        vmax = np.maximum(np.max(np.abs(V), axis=1, keepdims=True), 1e-300)
        hk = H2 * (1 + np.max(np.abs(U), axis=1, keepdims=True)) / vmax
        hp = H2 * (1 + abs(par[index - 1]))
        out = []
        for sgn in (1, -1):
            pp = np.array(par, float)
            pp[index - 1] += sgn * hp
            out.append(self.f(U + hk * V, pp) - self.f(U - hk * V, pp))
        return (out[0] - out[1]) / (4 * hp * hk)


def record_profile(rec, n_keep: int):
    """(t (NTPL,), U (NTPL, n_keep), NTST, NCOL) of an s-record of a BVP: its mesh times
    (evenly spaced where the record has none) and the first n_keep components of its
    profile; ValueError where the header's NTST and NCOL do not fit its NTPL points."""
    U_r = np.asarray(rec.U, float)[:, :n_keep]
    ntst_r, ncol_r = int(getattr(rec, "ntst", 0) or 0), int(getattr(rec, "ncol", 0) or 0)
    if not ncol_r or not ntst_r or ntst_r * ncol_r + 1 != len(U_r):
        raise ValueError(f"BVP restart: record with {len(U_r)} points but NTST = "
                         f"{ntst_r}, NCOL = {ncol_r} in its header")
    t_r = getattr(rec, "t", None)
    t_r = np.asarray(t_r if t_r is not None else np.linspace(0, 1, len(U_r)), float)
    return t_r, U_r, ntst_r, ncol_r


def stored_profile(rec, ndim: int, n_keep: int | None = None):
    """(mesh, U, udot) of an s-record of a BVP: U (NTPL, n_keep) its first n_keep (default
    NDIM) components, udot the direction's (or None when not stored)."""
    n_keep = ndim if n_keep is None else n_keep
    t_r, U_r, _, ncol_r = record_profile(rec, n_keep)
    ud_r = None
    if rec.udot is not None:
        ud_r = np.asarray(rec.udot, float).reshape(len(U_r), -1)[:, :n_keep]
    return col.Mesh(t_r[::ncol_r].copy(), ncol_r), U_r, ud_r


def onto_mesh(mesh_r: col.Mesh, profiles, ntst: int, ncol: int, guide: int):
    """AUTO's ADAPT2: stored profiles moved onto a run's mesh of NTST intervals of
    NCOL: copied when the mesh sizes agree, else NEWMSH (equidistributing the first
    `guide` components of the first profile) + INTERP. Returns (mesh, profiles); None
    profiles stay None."""
    if (mesh_r.ntst, mesh_r.ncol) == (ntst, ncol):
        return mesh_r, [None if P is None else P.copy() for P in profiles]
    mesh = col.Mesh(col.new_mesh(mesh_r, profiles[0][:, :guide], ntst, periodic=True), ncol)
    return mesh, [None if P is None else col.interpolate(mesh_r, P, mesh.tm, ncol)
                  for P in profiles]


class CollocationBVP:
    """Base class: see the module docstring."""
    curve_type = 0
    arclength = "plane"
    freezes_second_derivatives = False
    #: The corrector's last Newton matrix serves as the Jacobian at a converged point of a
    #: continuation step (tangent, Floquet multipliers, tests: AUTO's NEWTONBV), instead
    #: of f_u at every Gauss point once more (`washer.cont.iterator.Continuation.correct`).
    newton_jacobian_at_point = True
    nint = 1
    #: True: the boundary conditions are the subclass's own (`Collocation` general_bc:
    #: dense blocks in u(0), u(1) and the parameters), else periodicity u(0) = u(1).
    general_bc = False
    #: NBC boundary conditions (None: n_comp, periodicity and the loci's).
    nbc = None
    #: Mesh adaptation of a periodic profile (EQDF wraps around) or of a general BVP.
    periodic_mesh = True

    # ------------------------------------------------------------------ set-up
    @property
    def n_tail(self) -> int:
        return self.nint + 1

    def set_mesh(self, mesh: col.Mesh) -> None:
        """The mesh, its collocation and the inner product's weights. A mesh of the sizes
        of the current one (ADAPT's, every IAD points) takes the collocation on
        (`Collocation.on_mesh`)."""
        coll = self.__dict__.get("coll")
        self.mesh = mesh
        if coll is not None and self._sizes_of(coll) == self._sizes_of(mesh=mesh):
            self.coll = coll.on_mesh(mesh)
        else:
            self.coll = col.Collocation(mesh, self.n_comp, nint=self.nint,
                                        general_bc=self.general_bc, nbc=self.nbc,
                                        npar=self.n_tail)
        self.n_eq = self.coll.n_eq
        th = self._theta_u()
        if self.n_comp > self.ndim:
            th = np.concatenate((th, np.ones(self.n_comp - self.ndim)))
        # np.kron(w_node, th) of these 1-D arrays, a component at a time (numpy multiplies
        # a product over a narrow last axis element by element; ADAPT makes a mesh every
        # IAD points)
        w_node, n_u = self.coll.w_node, self.coll.n_u
        weights = np.empty(self.coll.n_x)
        by_node = weights[:n_u].reshape(-1, self.n_comp)
        for c in range(self.n_comp):
            by_node[:, c] = w_node * th[c]
        weights[n_u:] = self.tail_weights()
        self.weights = weights

    def tail_weights(self) -> np.ndarray:
        raise NotImplementedError

    def _sizes_of(self, coll=None, mesh=None) -> tuple:
        """What a Collocation is built from besides the mesh's times: (NTST, NCOL, n_comp,
        NINT, NBC, n_tail, general_bc), of `coll`, or the system's own on `mesh`."""
        if coll is not None:
            return (coll.mesh.ntst, coll.mesh.ncol, coll.ndim, coll.nint, coll.nbc, coll.npar,
                    coll.general_bc)
        return (mesh.ntst, mesh.ncol, self.n_comp, self.nint,
                self.n_comp if self.nbc is None else int(self.nbc), self.n_tail,
                self.general_bc)

    def _theta_u(self) -> np.ndarray:
        """THU of the user's NDIM components, (NDIM,) read-only: kept with the settings
        it was read from (every mesh and every point's b-row column ask for it)."""
        kept = self.__dict__.get("_thu_kept")
        if kept is None or kept[0] is not self.settings:
            thu = self.settings.theta_u(self.ndim)
            thu.setflags(write=False)
            self._thu_kept = kept = (self.settings, thu)
        return kept[1]

    def pvls_params(self, U: np.ndarray, par: np.ndarray, period: float, multipliers=None,
                    problem=None) -> np.ndarray:
        """PAR after the user's PVLS on the node values U (NTPL, k) (AUTO's PVLSBV), a copy;
        par itself without one. Every system on this base passes the same thing: a
        `washer.cont.pvls.Orbit` with this mesh, the period and GETP's helpers (a compiled
        PVLS's GETP then integrates on the adapted mesh). `multipliers`: the Floquet
        multipliers or a callable giving them (GETP's EIG, STA), else None; `problem`:
        whose pvls (default the system's problem)."""
        problem = self.problem if problem is None else problem
        if not getattr(problem, "has_pvls", False):
            return par
        orbit = Orbit.of(U, self.mesh.node_times(), self.coll.w_node, period, self.mesh.ntst,
                         self.mesh.ncol, multipliers)
        return problem.pvls(orbit, par)

    @property
    def n_state(self) -> int:
        """How many leading unknowns are the profile (the rest are free parameters):
        the corrector tests them as AUTO's NEWTONBV does (EPSU on the profile, EPSL on
        each parameter)."""
        return self.coll.n_u

    #: AUTO's NRTN (SETRTN): for each component of u, the number of turns of 2 pi it
    #: makes over one period (u(1) - u(0) = 2 pi NRTN: an angle of a pendulum-like
    #: system that rotates); None when no component rotates.
    nrtn = None

    def set_rotations(self, U: np.ndarray) -> None:
        """AUTO's SETRTN on the start profile: NRTN = NINT((u(1) - u(0)) / 2 pi)."""
        k = np.rint((U[-1, :self.ndim] - U[0, :self.ndim]) / (2 * math.pi)).astype(int)
        self.nrtn = k if np.any(k) else None

    def bc_offset(self) -> np.ndarray | None:
        """What the rotations add to W(0) - W(1) (BCPS, BCPL, BCPD, BCTR): 2 pi NRTN on
        the components of u, 0 on the loci's others; None without rotations."""
        if self.nrtn is None:
            return None
        off = np.zeros(self.n_comp)
        off[:self.ndim] = 2 * math.pi * self.nrtn
        return off

    def period(self, par) -> float:
        """The period T scaling u' = T f(u) (PAR(11))."""
        return float(par[10])

    def set_phase_reference(self, U: np.ndarray, par: np.ndarray) -> None:
        """CONTBV's STUPBV: the profile of u becomes the integral phase condition's
        reference, u'_old = T f(u_old) at the nodes (AUTO's UOLDPS, UPOLDP)."""
        self.U_old = np.array(U[:, :self.ndim])
        self.up_old = self.period(par) * self.field.f(self.U_old, par)

    # ------------------------------------------------------------------ contract
    def factor(self, J, border: np.ndarray):
        """[J; border] factorised: with COMPILED_FACTOR, a J assembled by `coll` by the
        compiled condensation and block reduction (washer.cont.reduction: the same solves
        and determinant, and the Floquet pair of the same elimination, kept as
        `self._reduced = (J, factor)` for `multipliers`); else by SuperLU."""
        border = np.asarray(border, float)
        if COMPILED_FACTOR and self.coll.has_pattern(J):
            # The compiled corrector's last factorisation of this J (AUTO's NEWTONBV
            # factorises J once per point): the collocation rows' condensation and
            # reduction do not involve the border, so the new border row is taken through
            # them and only the remaining dense system is factorised again, the bits of a
            # new factorisation (reduction.BorderedCollocation.reborder).
            reduced = getattr(self, "_reduced", None)
            if reduced is not None and reduced[0] is J and reduced[1].reborderable:
                f = reduced[1]
                f.reborderable = False        # once: the caller holds it from now on
                if f.reborder(border, dense=lambda: self.coll.bordered(J, border)):
                    return f
            f = reduction.BorderedCollocation.from_jacobian(self.coll, J, border)
            self._reduced = (J, f)
            return f
        return SparseFactor(self.coll.bordered(J, border))

    def unit_tangent(self, J, ref: np.ndarray, big: float):
        """Continuation.tangent's unit tangent at a point of Jacobian J, oriented along
        ref: the factorisation of [J; border(ref)] (`factor`) and, where it is the
        compiled one, z = [J; border(ref)]^-1 e_n made unit in `inner` in one call
        (reduction.BorderedCollocation.unit_tangent). (t, factor, True), or (None,
        factor, False) where the caller takes it on from the factorisation."""
        factor = self.factor(J, self.border(ref))
        t = (factor.unit_tangent(self.weights, big)
             if isinstance(factor, reduction.BorderedCollocation) else None)
        return t, factor, t is not None

    def inner(self, a: np.ndarray, b: np.ndarray) -> float:
        """int_0^1 sum_i THU_i a_i(t) b_i(t) dt + sum THL(k) a_k b_k over the parameter
        unknowns (AUTO's RINPR + THL; THL(11) = 0 by default)."""
        return float(np.dot(a, self.weights * b))

    def border(self, t: np.ndarray) -> np.ndarray:
        """The row r with r @ a == inner(a, t)."""
        return self.weights * np.asarray(t, float)

    def start(self):
        return self._start

    def located_code(self, key, point) -> int:
        """The base code a located zero of test `key` is written with: the key itself."""
        return key

    def info(self, x, code) -> dict:
        """Nothing is computed at special points of BVPs beyond the b-row."""
        return {}

    # ------------------------------------------------------------------ mesh adaptation
    def wants_remesh(self, n_points: int) -> bool:
        """AUTO adapts the mesh after point NTOT when IAD > 0 and NTOT % IAD == 0."""
        iad = self.settings.IAD
        return iad > 0 and n_points % iad == 0

    def remesh(self, x: np.ndarray, *vectors) -> tuple:
        """AUTO's ADAPT: a new mesh (same NTST, NCOL) equidistributing EQDF of the
        profile of u; x and every further vector in the unknown layout (tangent,
        previous point) are interpolated onto it; the phase reference too."""
        old = self.mesh
        W = self.coll.profile(x)
        # CNRLBV's ADAPT: EQDF over every component of the continued system (a locus's
        # null vectors too), extended by periodicity only for the orbits themselves
        # ((IPS = 2 or 12) and |ISW| <= 1); a locus of cycles (ISW = 2) extrapolates.
        periodic = self.periodic_mesh and abs(self.settings.ISW) <= 1
        new, onto = col.adapt(old, W, periodic=periodic)
        out = [self._moved(onto, v) for v in (x,) + vectors]
        # CONTBV after ADAPT: the phase reference's derivative is T f of the
        # interpolated profile (STUPBV), not the interpolant of the old T f: where the
        # mesh moves across a steep layer the two differ by the interpolation error.
        self.set_phase_reference(onto(self.U_old), self.par)
        self.set_mesh(new)
        self.mesh_changed()
        return tuple(out)

    def _moved(self, onto, v: np.ndarray) -> np.ndarray:
        """A vector in the unknown layout with its profile moved by `onto` (ADAPT's
        interpolation onto the new mesh, written into the new vector) and its parameter
        unknowns kept."""
        v = np.asarray(v, float)
        n_u = self.coll.n_u
        out = np.empty(len(v))
        onto(v[:n_u].reshape(-1, self.n_comp), out=out[:n_u].reshape(-1, self.n_comp))
        out[n_u:] = v[n_u:]
        return out

    def mesh_changed(self) -> None:
        """Drop what was cached on the old mesh."""

    # ------------------------------------------------------------------ reduction
    def reduce(self, J, border: np.ndarray):
        """Reduce the bordered matrix [J; border] onto the unknowns S = (W(0), the
        parameter unknowns) and the equations R = (boundary conditions, integrals,
        border): returns (Sc, X) with Sc = M_RS - M_RI M_II^-1 M_IS, a square matrix
        (n_comp + n_tail) whose determinant vanishes exactly where the bordered matrix
        is singular (M_II, the collocation equations for the nodes after t = 0, is a
        discretised initial-value problem and stays invertible), and X = M_II^-1 M_IS
        for the back substitution of the interior nodes. A Jacobian of `coll`'s pattern
        is reduced interval by interval (reduction.onto_start: M_II is block lower
        bidiagonal), any other through SuperLU."""
        if self.coll.has_pattern(J):
            return reduction.onto_start(self.coll, J, np.asarray(border, float))
        M = self.coll.bordered(J, border).tocsc()
        n, nu, nc = self.n_comp, self.coll.n_u, self.coll.n_coll
        cols_S = np.r_[np.arange(n), nu + np.arange(self.n_tail)]
        cols_I = np.arange(n, nu)
        M_II = M[:nc][:, cols_I].tocsc()
        M_IS = M[:nc][:, cols_S].toarray()
        import scipy.sparse.linalg as spla
        X = spla.splu(M_II, permc_spec=PERMC_SPEC).solve(M_IS)
        M_R = M[nc:]
        Sc = M_R[:, cols_S].toarray() - M_R[:, cols_I] @ X
        return Sc, X

    def test_functions(self, x, tangent, J, stability, factor, codes=None) -> dict:
        """The fold (LPC: the PAR(ICP(1))-component of the tangent) and branch-point
        (BPC: `bp_function`) tests of a BVP's branch, AUTO's FNLPBV and FNBPBV; None where
        there is no tangent yet or the reduced matrix could not be factorised. Systems
        with other tests (cycles: PD, TR) define their own."""
        codes = self.active_tests() if codes is None else [int(c) for c in codes]
        out = {}
        if Code.LPC in codes:
            out[int(Code.LPC)] = fold_test(tangent)
        if Code.BPC in codes:
            try:
                out[int(Code.BPC)] = None if tangent is None else self.bp_function(
                    J if J is not None else self.jacobian(x), tangent)
            except RuntimeError:
                out[int(Code.BPC)] = None
        return out

    def compiled_factor_of(self, J, factor):
        """`factor` when it is the compiled factorisation (`factor`) of this very J (its
        eliminations then serve every matrix with J's collocation rows: reduction.
        BorderedCollocation.reduced), else None."""
        reduced = getattr(self, "_reduced", None)
        if (factor is not None and reduced is not None and reduced[0] is J
                and reduced[1] is factor and isinstance(factor, reduction.BorderedCollocation)):
            return factor
        return None

    def bp_function(self, J, tangent: np.ndarray) -> float:
        """The BP test of BVPs: det of the bordered Jacobian reduced onto the boundary
        unknowns (`reduce`), as det(S / |S|_F) (`bp_value`)."""
        return self.bp_value(self.reduce(J, self.weights * tangent)[0])

    @staticmethod
    def bp_value(Sc: np.ndarray) -> float | None:
        """det(S / |S|_F) of a reduced bordered Jacobian S: bounded by 1, independent of
        the overall scale, and zero exactly where the bordered Jacobian is singular, like
        AUTO's FNBPBV (the reduced determinant over det P1). (Normalising each row instead
        would divide out the very row that vanishes at a decoupled BP, e.g.
        1 - exp((mu - a) T) of a symmetry-breaking direction.)"""
        return CollocationBVP.bp_value_of(Sc, linalg.scaled_slogdet(Sc))

    @staticmethod
    def bp_value_of(Sc: np.ndarray, got: tuple) -> float | None:
        """`bp_value` of Sc whose linalg.scaled_slogdet is `got` (computed already)."""
        if len(got) == 1:                       # |S|_F is 0 or not finite
            return 0.0
        _, sign, logdet = got
        n = len(Sc)
        if n > 1 and not logdet > _bp_void_logdet(n):
            # A determinant whose two smallest singular values are both below rounding
            # (n eps of the largest) has no sign: it is a product of noise, and flips
            # from step to step without a branch point (a cycle family nearing an
            # infinite-period limit: S's largest singular value grows like exp(lambda T)
            # while the others stay O(1)). Like FNBPBV, which does not test (ITP=0)
            # where its quotient DET/det(P1) is not representable, there is no test.
            # The singular values are taken only where the determinant is small enough
            # for that to be possible (_bp_void_logdet).
            sv = np.linalg.svd(Sc, compute_uv=False)
            if sv[-2] <= n * _EPS * sv[0]:
                return None
        return float(sign * math.exp(logdet))

    def orient_stdrbv(self, t: np.ndarray, x: np.ndarray) -> np.ndarray:
        """STDRBV's sign for a computed direction t at x: the first free parameter
        (PAR(ICP(1)) first, then ICP(2), ...) whose rate is not negligible (EPSL,
        relative) increases; else the first component of u(1) whose rate is not
        negligible (EPSU) does. At a symmetry-breaking BP of cycles (r3b's halo orbits
        from its Lyapunov family) the parameters do not move and u(1) decides which of
        the two mirror families is followed."""
        s = self.settings
        n_u, n_x = self.coll.n_u, len(t)
        for slot in [n_x - 1] + list(range(n_u, n_x - 1)):
            if abs(t[slot]) / (1 + abs(x[slot])) > s.EPSL:
                return t if t[slot] > 0 else -t
        n = self.n_comp
        for tv, xv in zip(t[n_u - n:n_u], x[n_u - n:n_u]):
            if abs(tv) / (1 + abs(xv)) > s.EPSU:
                return t if tv > 0 else -t
        return t

    def null_vector(self, J, border: np.ndarray) -> np.ndarray:
        """A null vector of the (singular or nearly singular) bordered matrix
        [J; border]: the smallest right singular vector of the reduced matrix, then the
        interior nodes by back substitution."""
        Sc, X = self.reduce(J, border)
        n, nu = self.n_comp, self.coll.n_u
        _, _, Vt = np.linalg.svd(Sc)
        zS = Vt[-1]
        z = np.zeros(self.coll.n_x)
        z[np.r_[np.arange(n), nu + np.arange(self.n_tail)]] = zS
        z[n:nu] = -X @ zS
        return z

    # ------------------------------------------------------------------ output
    @property
    def n_shown(self) -> int:
        """How many of the state's components the b-file's columns describe: NDIM here;
        a system that extends the user's state (AUTO's NDM < NDIM) says fewer."""
        return self.ndim

    def n2(self) -> int:
        """AUTO's N2: how many MAX U(i) columns the b-file shows (ICP counts at least
        two entries: the period is free on periodic branches)."""
        return max(0, min(self.ndim, 7 - max(len(self.settings.ICP), 2)))

    def measure(self, U: np.ndarray) -> float:
        """The b-file's second column by IPLT (STPLBV) on the profile of u: 0 or out of
        range: L2 norm sqrt(int sum THU_i u_i^2 dt) (RNRMSQ); 1..NDIM: max of U(IPLT);
        -NDIM..-1: min; NDIM+1..2 NDIM: integral of U(IPLT - NDIM); 2 NDIM+1..3 NDIM: L2
        norm of U(IPLT - 2 NDIM)."""
        n, iplt = self.n_shown, self.settings.IPLT
        w = self.coll.w_node
        iab = abs(iplt)
        if iplt > 0 and iab <= n:
            return float(np.max(U[:, iab - 1]))
        if iplt < 0 and iab <= n:
            return float(np.min(U[:, iab - 1]))
        if n < iplt <= 2 * n:
            return float(w @ U[:, iplt - n - 1])
        if 2 * n < iplt <= 3 * n:
            return float(math.sqrt(w @ U[:, iplt - 2 * n - 1] ** 2))
        thu = self._theta_u() if n == self.ndim else self.settings.theta_u(n)
        # (U itself where it holds just the shown components: no view to make)
        return float(math.sqrt(w @ ((U if U.shape[1] == n else U[:, :n]) ** 2 @ thu)))

    def column_titles(self) -> list:
        """HEADNG's titles: the IPLT column (named by unames where U(k) has a name:
        'INTEGRAL u', 'MAX x'), then MAX of each shown component."""
        n, iplt = self.n_shown, self.settings.IPLT
        iab = abs(iplt)
        un = self.unames
        k = (iab - 1) % n + 1 if iab else 0          # HEADNG: MOD(ABS(IPLT)-1, NDM)+1
        u = un[k] if k in un else f"U({k})"
        if iplt > 0 and iab <= n:
            first = f"MAX {u}"
        elif iplt < 0 and iab <= n:
            first = f"MIN {u}"
        elif n < iplt <= 2 * n:
            first = f"INTEGRAL {u}"
        elif 2 * n < iplt <= 3 * n:
            first = f"L2-NORM {u}"
        else:
            first = "L2-NORM"
        return [first] + [f"MAX {un[i]}" if i in un else f"MAX U({i})"
                          for i in range(1, self.n2() + 1)]

    def bvp_solution(self, x, tangent, par, rldot) -> Solution:
        """The Solution of x: b-row columns of u, the whole profile W and its direction
        stored; rldot(tangent) gives the record's parameter derivatives."""
        coll, mesh = self.coll, self.mesh
        n_comp = coll.ndim
        W = coll.profile(x)
        u = W.copy()
        n2 = self.n2()
        # the maxima of the first N2 columns, each a contiguous row of the transposed copy
        # (a maximum is exact: the same doubles as np.max of each column; numpy reduces
        # across the rows of a narrow array one element at a time, 5 us at NTPL 281)
        cols = [self.measure(W)]
        if n2:
            cols += (u if n2 == n_comp else u[:, :n2]).T.copy().max(axis=1).tolist()
        udot = None
        rl = []
        if tangent is not None:
            udot = coll.profile(tangent).copy()
            rl = rldot(tangent)
        return Solution(par, cols, u, mesh.node_times(), udot, rl, mesh.ntst, mesh.ncol,
                        self.ndim)


class CycleLocus(CollocationBVP):
    """Base of the two- and three-parameter loci of periodic orbits (folds, period
    doublings, tori, branch points of cycles): AUTO computes no stability on these curves,
    and the user's PVLS sees the orbit itself, the first NDIM columns of the profile,
    with its period PAR(11)."""

    def orbit(self, x) -> tuple[np.ndarray, np.ndarray]:
        """(u (n_nodes, NDIM), full PAR) at the unknowns x."""
        W, par = self.unpack(x)
        return W[:, :self.n], par

    def params(self, x):
        u, par = self.orbit(x)
        return self.pvls_params(u, par, par[10])

    def stability(self, x, J=None):
        return None
