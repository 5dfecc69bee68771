"""Periodic orbits (IPS = 2) as a continued system: AUTO's FNPS/BCPS/ICPS on the
collocation mesh of `washer.cont.collocation`.

Registered for
* (2, 1, 'HB'): start from a Hopf point (AUTO's STHOPF): constant profile u_HB,
  period PAR(11) stored at the HB, direction sin(2 pi t) Re phi + cos(2 pi t) Im phi
  from the critical eigenvector phi of f_u, no parameter motion.
* (2, 1, '*'): restart from a stored periodic solution (our s-records or AUTO-07p's):
  the profile is moved onto the run's mesh (AUTO's ADAPT2: copy if NTST and NCOL
  agree, else NEWMSH + INTERP), the stored direction reused when the free
  parameters agree (STPNBV1), else the iterator computes one (STDRBV).
* (2, -1, 'PD'): period doubling switch (PDBLE: period and mesh doubled; direction the
  null vector of the doubled system bordered by the old direction, as STDRBV with
  IPERP = 1).
* (2, -1, 'BP'): branch switching at a BP of cycles (the same null-vector rule).

Unknowns x = (U flattened node-major (NTST*NCOL + 1, NDIM), PAR(ICP(2)), PAR(ICP(1)))
(ICP(2) = 11, the period, unless the user fixes the period). Equations: collocation,
periodicity, the integral phase condition against the previous point (ICPS, with
u'_old = T_old f(u_old) at the nodes: STUPBV).

The parts: the collocation BVP (mesh, norms, phase reference, mesh adaptation, the
reduction for BP of cycles, the b-file columns) is `washer.cont.systems.bvp`; the
multipliers and the tests on them are `washer.cont.floquet`; this module holds the
periodic orbit's equations, its starts and its switching.

Linear algebra: the bordered collocation matrix is factorised by SuperLU (splu); the
condensation of parameters (AUTO's CONPAR + REDUCE) is used only for the Floquet
multipliers. Measured on lrz (N = 425): splu 0.7 ms against 1.05 ms for the
vectorised condensation of the collocation blocks alone (no parameter columns, no
back substitution); at NTST = 150 (N = 1805) 3.9 against 1.7 ms, so a condensing
solver would only pay for NTST in the hundreds.

Differences from AUTO worth knowing:
* AUTO's BVP continuation uses the secant as the direction (CONTBV: (X - X_old)/DSOLD,
  SCALEB), not the tangent at the new point; regular points then follow AUTO's more
  closely (lrz PT 3: AUTO rho 24.6903, ours with the exact tangent 24.6947; located
  points agree either way).
* `border(t)` is `weights * t` (weights: the inner product's diagonal).
* At a continuation step's point the Floquet multipliers, the tangent and the tests
  come from the Jacobian of the last Newton iteration, as AUTO's NEWTONBV takes them,
  where that iteration refactorised the matrix at the iterate the converging
  correction started from (within EPSU of the point) and its trivial multiplier is
  within ACCURATE of 1 (`floquet.newton_jacobian_serves`); elsewhere, and at located
  points, from the Jacobian at x itself (chu's PD: -1.33941e-2 against AUTO's
  -1.33946e-2; the mesh-converged value is -1.33941e-2).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:                  # annotations only; imported where used
    import scipy.sparse as sp

from washer.cont import collocation as col
from washer.cont import floquet, linalg, reduction
from washer.cont.linalg import nullvc
from washer.cont.codes import Code
from washer.cont.system import Solution, Stability, register
from washer.cont.systems.bvp import CollocationBVP, VectorField, onto_mesh, stored_profile


class PeriodicOrbits(CollocationBVP):
    """The continued system of periodic orbits (IPS = 2, ISW = 1 or -1).

    Attributes (contract): n_eq, curve_type (0), arclength ('plane'), free
    ([ICP(1), ICP(2)], ICP(2) = 11 when ICP has a single entry, as INITPS).
    Extra: mesh (collocation.Mesh), coll (collocation.Collocation), weights
    (the inner product's diagonal), field (VectorField).
    """

    def __init__(self, data):
        s = data.settings
        self.settings = s
        self.problem = data.problem
        self.ndim = self.n_comp = s.NDIM
        icp = list(s.ICP)
        if len(icp) == 1:
            icp.append(11)                      # INITPS: variable period
        self.icp = icp
        self.free = icp[:2]
        self.field = VectorField(self.problem, self.ndim)
        # NPAR as AUTO's INIT2: PAR(11) the period, PAR(12) where TR is detected (in
        # s.NPAR), and a restart record's user parameters (its NPAR - NPARI) kept.
        rec = data.record
        kept = len(rec.par) - getattr(rec, "npari", 0) if rec is not None else 0
        self.par = np.zeros(max(s.NPAR, 11, max(icp), kept))
        p = np.asarray(data.par, float)
        self.par[:len(p)] = p[:len(self.par)]
        self.kind = (data.kind or "").upper()
        self.unames = dict(getattr(data, "unames", {}) or {})
        self.isw = s.ISW
        self._suspended = False
        self.n_points = 0
        rec = data.record
        if rec is not None and np.ndim(rec.U) == 2 and len(rec.U) > 1:
            self._from_orbit(rec)
        elif rec is None and getattr(data, "data", None) is not None:
            self._from_data(*data.data)
        elif rec is None and self.kind != "HB":
            self._from_stpnt(np.asarray(data.u, float)[:self.ndim])
        else:
            self._from_hopf(np.asarray(data.u, float)[:self.ndim])

    # ------------------------------------------------------------------ set-up
    def tail_weights(self) -> np.ndarray:
        return np.array([self.settings.theta_par(self.free[1]),
                         self.settings.theta_par(self.free[0])])

    def _x(self, U: np.ndarray, par: np.ndarray) -> np.ndarray:
        return np.r_[U.ravel(), par[self.free[1] - 1], par[self.free[0] - 1]]

    def _from_hopf(self, u: np.ndarray) -> None:
        """AUTO's STHOPF (bvp.f90)."""
        s = self.settings
        self.set_mesh(col.Mesh.uniform(s.NTST, s.NCOL))
        A = self.field.fu(u[None, :], self.par)[0]
        lam, vec = np.linalg.eig(A)
        T = self.par[10]
        cand = np.where(lam.imag > 0)[0]
        if len(cand) == 0:
            raise ValueError("IPS = 2 from an HB label: the Jacobian at the point has no complex "
                             f"eigenvalue pair (eigenvalues {lam})")
        if T > 0 and math.isfinite(T):
            i = cand[np.argmin(np.abs(lam[cand] - 2j * math.pi / T))]
        else:
            i = cand[np.argmin(np.abs(lam[cand].real))]
            T = 2 * math.pi / lam[i].imag
            self.par[10] = T
        # The eigenvector a + i b of i w, w = 2 pi / T, as STHOPF finds it: the null
        # vector (a, b) of [[-w I, A], [A, w I]] by NLVC, unit in the Euclidean norm.
        # Its phase (which rotation of the eigenvector) is AUTO's, and the orbits'
        # phase follows it along the branch (the phase condition only keeps it): a
        # problem that is not phase invariant downstream (pcl's normalisation of the
        # Floquet bundle at t = 0) then meets AUTO's points.
        n, w = len(u), 2 * math.pi / T
        Ar = np.real(A)
        smat = np.block([[-w * np.eye(n), Ar], [Ar, w * np.eye(n)]])
        ab = nullvc(smat, 2)
        ab /= np.linalg.norm(ab)
        a, b = ab[:n], ab[n:]
        if not np.all(np.isfinite(ab)) or np.linalg.norm(Ar @ (a + 1j * b) - 1j * w * (a + 1j * b)) \
                > 1e-6 * (1 + np.linalg.norm(Ar)):
            # Not a clean pair at 2 pi / T (a stored period off the eigenvalue): the
            # eigenvector itself.
            a, b = vec[:, i].real, vec[:, i].imag
        t = self.mesh.node_times()
        S, C = np.sin(2 * math.pi * t)[:, None], np.cos(2 * math.pi * t)[:, None]
        udot = S * a[None, :] + C * b[None, :]
        self.U_old = np.tile(u, (self.mesh.n_nodes, 1))
        self.up_old = C * a[None, :] - S * b[None, :]
        x0 = self._x(self.U_old, self.par)
        t0 = np.r_[udot.ravel(), 0.0, 0.0]
        self._start = (x0, t0 / math.sqrt(self.inner(t0, t0)))
        self.start_kind = "HB"
        self._keep_hopf_phase = True

    def _from_stpnt(self, u0: np.ndarray) -> None:
        """IRS = 0 (AUTO's STPNUB): the user's stpnt(u, par, t) at every node of a uniform
        mesh, t = j / (NTST NCOL); the parameters are the run's (stpnt's, with the
        constants' PAR overrides already applied). A stpnt without the time argument
        gives the constant profile u0. No direction: the iterator computes one."""
        s = self.settings
        self.set_mesh(col.Mesh.uniform(s.NTST, s.NCOL))
        t = self.mesh.node_times()
        U = np.tile(u0, (len(t), 1))
        if self.problem.stpnt_has_time:
            # stpnt(u, par, t) at each node; errors are the Problem's (ProblemError,
            # naming the function), never raw tracebacks.
            U = np.array([self.problem.start(len(self.par), tj)[0] for tj in t])
        if np.max(np.ptp(U, axis=0)) == 0:
            raise ValueError("IPS=2 with IRS=0 needs stpnt(u, par, t) giving a periodic orbit at "
                             "the mesh times t in [0, 1] (AUTO's STPNT with T); this stpnt gives "
                             "a constant: restart from an HB label instead (IRS='HB1')")
        self.set_phase_reference(U, self.par)
        self.set_rotations(U)
        self._start = (self._x(U, self.par), None)
        self.start_kind = ""

    def _from_data(self, t: np.ndarray, U: np.ndarray) -> None:
        """IRS = 0 with dat='NAME' (AUTO's STPNUB reading fort.3): the orbit of the data
        file, time rescaled to [0, 1] by its period t[-1] - t[0] (PAR(11), set by the
        start), moved onto an adapted mesh of NTST intervals (`collocation.
        profile_from_data`, AUTO's ADAPT2 of the piecewise-linear data). No direction:
        the iterator computes one."""
        s = self.settings
        mesh, U, _ = col.profile_from_data(t, U, s.NTST, s.NCOL, periodic=True)
        self.set_mesh(mesh)
        self.set_phase_reference(U, self.par)
        self.set_rotations(U)
        self._start = (self._x(U, self.par), None)
        self.start_kind = ""

    def _from_orbit(self, rec) -> None:
        """AUTO's STPNPS / STPNBV1 / ADAPT2 (and PDBLE for ISW = -1 at PD)."""
        s = self.settings
        mesh_r, U_r, ud_r = stored_profile(rec, self.ndim)
        rldot = list(getattr(rec, "rldot", []) or [])
        if self.isw == -1 and self.kind == "PD":
            # PDBLE: the orbit traversed twice, period doubled, mesh halved and repeated
            # (the second pass continues from the first's end, so rotating components
            # go on turning: u(1/2 + t/2) = u(1) + u(t) - u(0))
            self.par[10] *= 2
            tm = mesh_r.tm
            mesh_r = col.Mesh(np.r_[0.5 * tm[:-1], 0.5 + 0.5 * tm], mesh_r.ncol)
            U_r = np.r_[U_r[:-1], U_r[-1] + U_r - U_r[0]]
            ud_r = None if ud_r is None else np.r_[ud_r[:-1], ud_r[-1] + ud_r - ud_r[0]]
        mesh, (U, ud) = onto_mesh(mesh_r, [U_r, ud_r], s.NTST, s.NCOL, self.ndim)
        self.set_mesh(mesh)
        self.set_phase_reference(U, self.par)
        self.set_rotations(U)
        x0 = self._x(U, self.par)
        old = None
        if ud is not None and len(rldot) >= 2:
            old = np.r_[ud.ravel(), rldot[1], rldot[0]]
        t0 = None
        if self.isw == -1 and self.kind in ("BP", "PD"):
            t0 = self._switch_direction(x0, old)
        elif self.isw == -1:
            # CNRLBV's IPERP = 1 at any other label: STDRBV's null vector (computed by
            # the start), the one family through the orbit
            t0 = None
        elif old is not None and self._same_free(rec):
            nrm = math.sqrt(self.inner(old, old))          # STPNBV1: same free parameters
            t0 = old / nrm if nrm > 0 else None
        self._start = (x0, t0)
        self.start_kind = self.kind

    def _same_free(self, rec) -> bool:
        """STPNBV1's NODIR = 0: the record's free parameters are the run's, all of them
        (NFPRS = NFPR and ICPRS = ICP) and its solution has the run's NDIM. A point of a
        locus of cycles (free (ICP(1), 11, ICP(3), ...), profile (u, v)) restarted as an
        orbit (ISW = 1) gets a computed direction: the locus's tangent moves the locus's
        second parameter, which the orbit's run holds fixed (plp's isola from a point
        of the fold locus of cycles)."""
        icp = list(getattr(rec, "icp", []) or [])
        nfpr = getattr(rec, "nfpr", 0) or len(icp)
        width = np.shape(rec.U)[1] if np.ndim(rec.U) == 2 else self.ndim
        return nfpr == len(self.free) and icp[:nfpr] == self.free and width == self.ndim

    def _switch_direction(self, x0, old):
        """ISW = -1 (STDRBV with IPERP = 1): the null vector of the Jacobian bordered by
        the old branch's direction `old` (doubled at a PD): at a BP of cycles, or on the
        doubled orbit at a PD, the Jacobian has a two-dimensional null space, and this is
        its direction orthogonal (in `inner`) to the old branch."""
        if old is None:
            raise ValueError(f"ISW = -1 at {self.kind or 'this point'}: the record stores no "
                             "direction (written with IIS = 0?), so the other branch cannot "
                             "be found")
        z = self.null_vector(self.jacobian(x0), self.weights * old)
        return self.orient_stdrbv(z / math.sqrt(self.inner(z, z)), x0)

    # ------------------------------------------------------------------ helpers
    def unpack(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(U (n_nodes, NDIM) view, full PAR vector) of an unknown vector."""
        par = self.par.copy()
        par[self.free[1] - 1] = x[-2]
        par[self.free[0] - 1] = x[-1]
        return self.coll.profile(x), par

    # ------------------------------------------------------------------ equations
    def _at_gauss(self, x: np.ndarray, U: np.ndarray) -> np.ndarray:
        """u at the Gauss points (NTST*NCOL, NDIM) of the profile U of x: Newton's
        Jacobian at an iterate follows its residual, which has just interpolated them
        (the last one is kept, with the mesh it was taken on)."""
        key = (self.coll, x.tobytes())
        last = getattr(self, "_last_ug", None)
        if last is not None and last[0][0] is key[0] and last[0][1] == key[1]:
            return last[1]
        ug = self.coll.at_gauss(U).reshape(-1, self.ndim)
        ug.setflags(write=False)
        self._last_ug = (key, ug)
        return ug

    # csrc/cont/po_correct.cpp repeats residual and jacobian in C++ (the compiled
    # corrector, washer.cont.corrector_periodic): a change to either is made there too.
    def residual(self, x: np.ndarray) -> np.ndarray:
        U, par = self.unpack(x)
        ug = self._at_gauss(x, U)
        # Newton asks for the Jacobian at this iterate next (up to NWTN iterations):
        # a problem whose f comes with its Jacobians evaluates them here, once
        fg = self.field.f(ug, par, with_jacobian=True).reshape(self.mesh.ntst, self.mesh.ncol,
                                                               self.ndim)
        return self.coll.residual(U, self.period(par), fg, self.U_old, self.up_old,
                                  self.bc_offset())

    def jacobian(self, x: np.ndarray) -> sp.csc_matrix:
        U, par = self.unpack(x)
        N, m, n = self.mesh.ntst, self.mesh.ncol, self.ndim
        T = self.period(par)
        ug = self._at_gauss(x, U)
        if getattr(self.problem, "has_func_dfdu_batch", False) and 11 in self.free:
            # f (the PERIOD column) and f_u, f_p in one evaluation, unless the residual
            # at x has just made it (then every call below is answered from it)
            self.field.f(ug, par, with_jacobian=True)
        slots = ((0, self.free[1]), (1, self.free[0]))
        # f_u and the parameter columns other than the period's: one stencil (fu_fp)
        A, fps = self.field.fu_fp(ug, par, [i for _, i in slots if i != 11])
        A = A.reshape(N, m, n, n)
        blocks = self.coll.local_blocks(T, A)
        dF = np.empty((2, N, m, n))              # d(T f)/d(PAR(ICP(2)), PAR(ICP(1)))
        fps = iter(fps)
        for slot, index in slots:
            if index == 11:
                dF[slot] = self.field.f(ug, par).reshape(N, m, n)
            else:
                dF[slot] = T * next(fps).reshape(N, m, n)
        J = self.coll.jacobian_general(blocks, dF, self.up_old[None], np.zeros((1, 2)))
        self._last_blocks = (x.copy(), blocks, J)
        return J

    def params(self, x: np.ndarray) -> np.ndarray:
        """Full PAR at x: the free parameters (PAR(11) the period) and the user's pvls
        applied to the orbit: a `washer.cont.pvls.Orbit`, the node values (NTPL, NDIM)
        with the mesh, the period and AUTO's GETP helpers (norm, integral, max, min,
        bv0, bv1, the multipliers and the stable count, computed on first use; None
        with ISP = 0)."""
        U, par = self.unpack(x)
        if not getattr(self.problem, "has_pvls", False):
            return par                  # a fresh copy (`unpack`), as pvls_params gives it
        # A point's PAR is asked for twice (the UZ tests, then its b-row): the second
        # time PVLS would see the same profile, PAR and mesh, so its result is kept,
        # unless it read the multipliers (their cache follows the Jacobian and the
        # suspension state, which may move in between).
        key = (x.tobytes(), par.tobytes(), self.mesh.tm.tobytes(), self.mesh.ncol)
        kept = getattr(self, "_params_kept", None)
        if kept is not None and kept[0] == key:
            return kept[1].copy()
        asked = []

        def multipliers():
            asked.append(True)
            st = self.stability(x) if self.settings.ISP != 0 else None
            return None if st is None else st.values
        out = self.pvls_params(U, par, self.period(par), multipliers)
        self._params_kept = None if asked else (key, out.copy())
        return out

    def update(self, x: np.ndarray, tangent: np.ndarray) -> None:
        """CONTBV's STUPBV: the accepted profile becomes the phase condition's
        reference. Also moves the 'multiplier inaccurate' suspension state."""
        U, par = self.unpack(x)
        if getattr(self, "_keep_hopf_phase", False) and np.array_equal(x, self._start[0]):
            # At the Hopf point itself u' = 0: AUTO keeps STHOPF's UPOLDP (RSPTBV,
            # NODIR = -1) for the first step, and so do we.
            self._keep_hopf_phase = False
            self.U_old = U.copy()
        else:
            self.set_phase_reference(U, par)
        self.par = par
        self.n_points += 1
        st = self.stability(x) if self.settings.ISP != 0 else None
        if st is not None:
            self._suspended = floquet.inaccurate(st)

    def mesh_changed(self) -> None:
        self._last_blocks = None
        self._stab_cache = None

    # ------------------------------------------------------------------ Floquet
    def _blocks_at(self, x, J=None):
        """The collocation blocks of the Jacobian at x: of J when J is the last one
        assembled (the corrector's, serving as the Jacobian at x), else evaluated."""
        cached = getattr(self, "_last_blocks", None)
        if cached is not None and ((J is not None and cached[2] is J) or (
                cached[0].shape == x.shape and np.array_equal(cached[0], x))):
            return cached[1]
        self.jacobian(x)
        return self._last_blocks[1]

    def multipliers(self, x: np.ndarray, J=None) -> np.ndarray:
        """Floquet multipliers at x in AUTO's order, from the condensed collocation
        blocks of the Jacobian at x (CONPAR + REDUCE + FLOWKM): the pair of the compiled
        factorisation of that Jacobian when it was factorised (the tangent at a
        converged point), else the same eliminations on its blocks alone
        (reduction.floquet_pair: the same pair to the bit). J: the Jacobian at x
        when known (`_blocks_at`)."""
        blocks = self._blocks_at(x, J)
        reduced = getattr(self, "_reduced", None)
        if reduced is not None and reduced[0] is self._last_blocks[2]:
            P0, P1 = reduced[1].floquet_pair()
        else:
            P0, P1 = reduction.floquet_pair(blocks, self.ndim)
        return floquet.pencil_multipliers(P0, P1, deflate_trivial=True)

    def stability(self, x: np.ndarray, J=None) -> Stability | None:
        """Floquet multipliers and AUTO's NINS (`floquet.stability`). None when ISP = 0."""
        if self.settings.ISP == 0:
            return None
        cached = getattr(self, "_stab_cache", None)
        # (the Jacobian's identity first: a new point's J fails it without comparing x;
        # x's bits, not its values: a hit is then the same point without doubt)
        if (cached is not None and cached[1] == self._suspended and (J is None or cached[3] is J)
                and cached[0] == x.shape and cached[4] == x.tobytes()):
            return cached[2]
        out = floquet.stability(self.multipliers(x, J), self.ndim, self._suspended)
        # (x's shape and bytes: a hit compares one copy of x, not two)
        self._stab_cache = (x.shape, self._suspended, out, J, x.tobytes())
        return out

    def newton_jacobian_serves(self, stability) -> bool:
        """Whether the last Newton iteration's Jacobian, whose multipliers are
        `stability`, serves as the Jacobian at the converged point
        (`washer.cont.floquet.newton_jacobian_serves`)."""
        return floquet.newton_jacobian_serves(stability)

    def active_tests(self) -> list:
        return floquet.active_tests(self.settings, self.ndim)

    def test_functions(self, x, tangent, J, stability, factor, codes=None) -> dict:
        """The tests of cycles (`washer.cont.floquet.test_functions`); BP of cycles is
        `bp_function` on the Jacobian at x."""
        codes = self.active_tests() if codes is None else codes

        def bp():
            # The factorisation of [J; border] at x has J's collocation rows, which the
            # own-phase Jacobian shares (only its phase row differs): its eliminations
            # give the BP test's reduced matrix, from the dense rows alone.
            try:
                compiled = self.compiled_factor_of(J, factor)
                if compiled is not None and self.coll.has_pattern(J):
                    got = self._bp_reduced(compiled, J, x, tangent)
                    if got is not None:
                        return self.bp_value_of(*got)
                return self.bp_function(self._own_phase(x, J), tangent)
            except RuntimeError:
                return None
        return floquet.test_functions(codes, tangent, stability, self.settings.EPSS,
                                      self.ndim, bp, floquet.spb_kinds(self.settings))

    def _bp_reduced(self, factor, J, x: np.ndarray, tangent: np.ndarray):
        """(Sc, linalg.scaled_slogdet(Sc)) of the own-phase Jacobian at x bordered by
        `tangent` (`_own_phase`), reduced onto the boundary unknowns by `factor`, the
        compiled factorisation of J: its dense rows (reduction.dense_rows of J with the
        phase row `_own_phase_row`) taken through J's eliminations
        (BorderedCollocation.reduced) and the scaled determinant, in one compiled call
        where numpy's LAPACK is found (BorderedCollocation.bp_test), else step by step.
        None where a pivot of the factorisation was zero."""
        coll = self.coll
        lapack = linalg.compiled_lapack()
        if lapack is None:
            extra = reduction.dense_rows(coll, J, self.weights * tangent)
            extra[coll.nbc] = self._own_phase_row(x)
            Sc = factor.reduced(extra)
            return None if Sc is None else (Sc, linalg.scaled_slogdet(Sc))
        kept = self.__dict__.get("_bp_layout")
        if kept is None or kept[0] is not coll or kept[1] is not self.weights:
            # once per mesh (the weights are the mesh's too)
            kept = self._bp_layout = (coll, self.weights,
                                      reduction.BPLayout.of(coll, self.weights))
        U, par = self.unpack(x)
        F = np.ascontiguousarray(self.field.f(U, par), dtype=float)
        return factor.bp_test(lapack, reduction.dense_values_of(coll, J), kept[2],
                              self.period(par), F, np.ascontiguousarray(tangent, dtype=float))

    def _own_phase(self, x: np.ndarray, J=None):
        """The Jacobian at x with its phase row taken at x itself (u'_old = T f(u(x)))
        instead of at the previous point: the BP test is then a function of the point and
        its tangent alone. With the previous point's reference its sign can differ at one
        and the same point: a step across a sharp fold (tfc's iso-periodic family at
        PAR(3) = 0.73608, a pitchfork whose side branch it is) moves u'_old far from
        u'(x), and the test jumped where the reference changed."""
        J = self.jacobian(x) if J is None else J
        if not self.coll.has_pattern(J):
            return J
        J = J.copy()
        pos = self.coll.integral_positions(0)              # one entry per column, in order
        J.data[pos] = self._own_phase_row(x)
        return J

    def _own_phase_row(self, x: np.ndarray) -> np.ndarray:
        """The phase condition's row of the Jacobian with u'_old = T f(u(x)) (`_own_phase`):
        the node weights times T f at the nodes, 0 in the parameter columns, (n_x,)."""
        U, par = self.unpack(x)
        up = self.period(par) * self.field.f(U, par)
        return np.concatenate(((self.coll.w_node[:, None] * up).ravel(), np.zeros(self.n_tail)))

    def located_code(self, key, point) -> int:
        """PD or TR for a zero of the combined test, as TPSPBV types the located point."""
        return floquet.spb_code(key, point.stability, self.settings.EPSS)

    def accept(self, code: int, prev, cur) -> bool:
        return floquet.accept(code, prev, cur, self.ndim)

    # ------------------------------------------------------------------ output
    def solution(self, x: np.ndarray, tangent: np.ndarray | None) -> Solution:
        """b-row columns and s-record of x. PAR(12) holds the torus angle |arg mu_2|
        where the nontrivial multiplier nearest the unit circle is complex (FNSPBV sets
        it wherever TPSPBV classifies the point as TR), as AUTO writes it."""
        par = self.params(x)
        if self.ndim > 2 and self.settings.ISP != 0 and len(par) >= 12 \
                and self.free[1] != 12 and self.free[0] != 12:
            angle = floquet.torus_angle(self.stability(x).values, self.settings.EPSS)
            if angle is not None:
                par[11] = angle
        return self.bvp_solution(x, tangent, par,
                                 lambda t: [float(t[-1]), float(t[-2])])

    # ------------------------------------------------------------------ switching
    def directions(self, x, tangent, code) -> list:
        """At a BP of cycles: the direction of the other branch, the null vector of the
        Jacobian bordered by the current tangent (orthogonal to it in `inner`)."""
        if int(code) != int(Code.BPC):
            return []
        z = self.null_vector(self.jacobian(x), self.weights * tangent)
        return [z / math.sqrt(self.inner(z, z))]


register(2, 1, "HB")(PeriodicOrbits)
register(2, 1, "*")(PeriodicOrbits)
register(2, -1, "PD")(PeriodicOrbits)
register(2, -1, "BP")(PeriodicOrbits)
