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

Mesh adaptation (AUTO's ADAPT every IAD steps): the iterator asks `wants_remesh(n)`
after each written point and calls `remesh(x, tangent)`, which re-equidistributes the
mesh and returns x and the tangent on it (the phase reference moves too). For an
iterator without that hook, `remesh_in_update = True` makes `update` do it in place.

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
* Floquet multipliers are computed from the Jacobian at x itself (not from a chord
  Jacobian of the last iteration as AUTO does), so they are slightly more accurate
  than AUTO's at equal NTST (chu's PD: -1.33941e-2 against AUTO's -1.33946e-2; the
  mesh-converged value is -1.33941e-2).
"""
from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from washer.cont import collocation as col
from washer.auto.codes import Code
from washer.cont.problem import FD_STEP
from washer.cont.system import Solution, Stability, register

#: Stability tolerance of FNSPBV: |mu| <= 1 + STABLE_TOL counts as inside the circle.
STABLE_TOL = 1e-5
#: AUTO's "multiplier inaccurate" rule (FNSPBV): detection is suspended when the
#: multiplier closest to 1 is farther than INACCURATE from 1, resumed below ACCURATE.
INACCURATE = 5e-2
ACCURATE = 1e-2
#: SuperLU column ordering: minimum degree on A^T + A. Measured on lrz's bordered
#: collocation matrices (N = 425 / 1805): 0.7 / 3.9 ms per factorisation, fill 8.8e3 /
#: 3.6e4, against 2.1 / 15.7 ms for the default COLAMD and 2.7 / 36 ms for the natural
#: order (the dense border, phase and parameter rows/columns ruin the band otherwise).
PERMC_SPEC = "MMD_AT_PLUS_A"


class VectorField:
    """f, f_u, f_p of a washer.cont.problem.Problem at many points at once: a thin
    adapter over Problem.func_many / dfdu_many (one batched or vectorised call per
    stencil, the user's Jacobian when JAC != 0, else central differences with AUTO's
    step FD_STEP (1 + |u_i|))."""

    def __init__(self, problem, ndim: int):
        self.problem, self.ndim = problem, ndim

    def f(self, U: np.ndarray, par: np.ndarray) -> np.ndarray:
        """f at the rows of U (k, NDIM) -> (k, NDIM)."""
        return self.problem.func_many(np.asarray(U, float), par)

    def fu(self, U: np.ndarray, par: np.ndarray) -> np.ndarray:
        """f_u at the rows of U -> (k, NDIM, NDIM)."""
        U = np.asarray(U, float)
        return self.problem.dfdu_many(U, np.broadcast_to(par, (len(U), len(par))))

    def fp(self, U: np.ndarray, par: np.ndarray, index: int) -> np.ndarray:
        """d f / d PAR(index) at the rows of U -> (k, NDIM): central differences in two
        batched calls (a per-point analytic dfdp costs k calls: on the washer, 8640 kernel
        calls took 40 % of a run; the difference quotient is accurate to ~1e-9 relative,
        ample for Newton's parameter column)."""
        h = FD_STEP * (1 + abs(par[index - 1]))
        pp, pm = np.array(par, float), np.array(par, float)
        pp[index - 1] += h
        pm[index - 1] -= h
        return (self.f(U, pp) - self.f(U, pm)) / (2 * h)


class SparseFactor:
    """SuperLU factorisation (scipy.sparse.linalg.splu) of the bordered collocation
    matrix, with the determinant's sign and log-magnitude (for the contract)."""

    def __init__(self, M: sp.csc_matrix):
        self.M = M
        try:
            self.lu = spla.splu(M, permc_spec=PERMC_SPEC)
        except RuntimeError:
            # Exactly singular: at a Hopf start point the period column T f(u_HB) is 0
            # (constant solutions exist for every T). Solves fall back to least squares.
            self.lu = None

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        if self.lu is None:
            return np.linalg.lstsq(self.M.toarray(), np.asarray(rhs, float), rcond=None)[0]
        return self.lu.solve(np.asarray(rhs, float))

    def sign_logdet(self) -> tuple[float, float]:
        if self.lu is None:
            return 0.0, -np.inf
        d = self.lu.U.diagonal()
        if np.any(d == 0):
            return 0.0, -np.inf
        sign = _perm_sign(self.lu.perm_r) * _perm_sign(self.lu.perm_c) * np.prod(np.sign(d))
        return float(sign), float(np.sum(np.log(np.abs(d))))


def _perm_sign(p: np.ndarray) -> float:
    """Sign (+1/-1) of a permutation given as an index array."""
    p = np.asarray(p)
    seen = np.zeros(len(p), bool)
    sign = 1.0
    for i in range(len(p)):
        if seen[i]:
            continue
        j, length = i, 0
        while not seen[j]:
            seen[j] = True
            j = p[j]
            length += 1
        if length % 2 == 0:
            sign = -sign
    return sign


class PeriodicOrbits:
    """The continued system of periodic orbits (IPS = 2, ISW = 1 or -1).

    Attributes (contract): n_eq, curve_type (0), arclength ('plane'), free
    ([ICP(1), ICP(2)], ICP(2) = 11 when ICP has a single entry, as INITPS).
    Extra: mesh (collocation.Mesh), coll (collocation.Collocation), weights
    (the inner product's diagonal), field (VectorField).
    """
    curve_type = 0
    arclength = "plane"
    remesh_in_update = False           # True: update() adapts the mesh in place

    def __init__(self, data):
        s = data.settings
        self.settings = s
        self.problem = data.problem
        self.ndim = s.NDIM
        icp = list(s.ICP)
        if len(icp) == 1:
            icp.append(11)                      # INITPS: variable period
        self.icp = icp
        self.free = icp[:2]
        self.field = VectorField(self.problem, self.ndim)
        self.par = np.zeros(max(s.NPAR, 12, max(icp)))
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
        elif rec is None and self.kind != "HB":
            self._from_stpnt(np.asarray(data.u, float)[:self.ndim])
        else:
            self._from_hopf(np.asarray(data.u, float)[:self.ndim])

    # ------------------------------------------------------------------ set-up
    def _set_mesh(self, mesh: col.Mesh) -> None:
        self.mesh = mesh
        self.coll = col.Collocation(mesh, self.ndim)
        self.n_eq = self.coll.n_eq
        thu = self.settings.theta_u(self.ndim)
        self.weights = np.r_[np.kron(self.coll.w_node, thu),
                             self.settings.theta_par(self.free[1]),
                             self.settings.theta_par(self.free[0])]

    def _x(self, U: np.ndarray, par: np.ndarray) -> np.ndarray:
        return np.r_[U.ravel(), par[self.free[1] - 1], par[self.free[0] - 1]]

    def _from_hopf(self, u: np.ndarray) -> None:
        """AUTO's STHOPF (bvp.f90)."""
        s = self.settings
        self._set_mesh(col.Mesh.uniform(s.NTST, s.NCOL))
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
        phi = vec[:, i]
        t = self.mesh.node_times()
        S, C = np.sin(2 * math.pi * t)[:, None], np.cos(2 * math.pi * t)[:, None]
        udot = S * phi.real[None, :] + C * phi.imag[None, :]
        self.U_old = np.tile(u, (self.mesh.n_nodes, 1))
        self.up_old = C * phi.real[None, :] - S * phi.imag[None, :]
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
        self._set_mesh(col.Mesh.uniform(s.NTST, s.NCOL))
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
        self.U_old = U.copy()
        self.up_old = self._T(self.par) * self.field.f(U, self.par)       # STUPBV
        self._start = (self._x(U, self.par), None)
        self.start_kind = ""

    def _from_orbit(self, rec) -> None:
        """AUTO's STPNPS / STPNBV1 / ADAPT2 (and PDBLE for ISW = -1 at PD)."""
        s = self.settings
        U_r = np.asarray(rec.U, float)[:, :self.ndim]
        ntst_r, ncol_r = int(getattr(rec, "ntst", 0) or 0), int(getattr(rec, "ncol", 0) or 0)
        if not ncol_r or not ntst_r or ntst_r * ncol_r + 1 != len(U_r):
            raise ValueError(f"periodic restart: record with {len(U_r)} points but NTST = "
                             f"{ntst_r}, NCOL = {ncol_r} in its header")
        t_r = getattr(rec, "t", None)
        t_r = np.asarray(t_r if t_r is not None else np.linspace(0, 1, len(U_r)), float)
        mesh_r = col.Mesh(t_r[::ncol_r].copy(), ncol_r)
        rldot = list(getattr(rec, "rldot", []) or [])
        ud_r = None
        if rec.udot is not None:
            ud_r = np.asarray(rec.udot, float).reshape(len(U_r), -1)[:, :self.ndim]
        if self.isw == -1 and self.kind == "PD":
            # PDBLE: the orbit traversed twice, period doubled, mesh halved and repeated
            self.par[10] *= 2
            tm = mesh_r.tm
            mesh_r = col.Mesh(np.r_[0.5 * tm[:-1], 0.5 + 0.5 * tm], ncol_r)
            U_r = np.r_[U_r[:-1], U_r]
            ud_r = None if ud_r is None else np.r_[ud_r[:-1], ud_r]
            ntst_r *= 2
        if ntst_r == s.NTST and ncol_r == s.NCOL:
            mesh, U, ud = mesh_r, U_r.copy(), ud_r
        else:
            mesh = col.Mesh(col.new_mesh(mesh_r, U_r, s.NTST, periodic=True), s.NCOL)
            U = col.interpolate(mesh_r, U_r, mesh.tm, s.NCOL)
            ud = None if ud_r is None else col.interpolate(mesh_r, ud_r, mesh.tm, s.NCOL)
        self._set_mesh(mesh)
        self.U_old = U.copy()
        self.up_old = self._T(self.par) * self.field.f(U, self.par)        # STUPBV
        x0 = self._x(U, self.par)
        old = None
        if ud is not None and len(rldot) >= 2:
            old = np.r_[ud.ravel(), rldot[1], rldot[0]]
        t0 = None
        if self.isw == -1:
            t0 = self._switch_direction(x0, old)
        elif old is not None and list(getattr(rec, "icp", [])[:2]) == self.free:
            nrm = math.sqrt(self.inner(old, old))          # STPNBV1: same free parameters
            t0 = old / nrm if nrm > 0 else None
        self._start = (x0, t0)
        self.start_kind = self.kind

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
        return z / math.sqrt(self.inner(z, z))

    # ------------------------------------------------------------------ helpers
    def _T(self, par) -> float:
        return float(par[10])

    def unpack(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(U (n_nodes, NDIM) view, full PAR vector) of an unknown vector."""
        par = self.par.copy()
        par[self.free[1] - 1] = x[-2]
        par[self.free[0] - 1] = x[-1]
        return self.coll.profile(x), par

    # ------------------------------------------------------------------ contract
    def residual(self, x: np.ndarray) -> np.ndarray:
        U, par = self.unpack(x)
        ug = self.coll.at_gauss(U).reshape(-1, self.ndim)
        fg = self.field.f(ug, par).reshape(self.mesh.ntst, self.mesh.ncol, self.ndim)
        return self.coll.residual(U, self._T(par), fg, self.U_old, self.up_old)

    def jacobian(self, x: np.ndarray) -> sp.csc_matrix:
        U, par = self.unpack(x)
        N, m, n = self.mesh.ntst, self.mesh.ncol, self.ndim
        T = self._T(par)
        ug = self.coll.at_gauss(U).reshape(-1, n)
        A = self.field.fu(ug, par).reshape(N, m, n, n)
        blocks = self.coll.local_blocks(T, A)
        dF = np.empty((2, N, m, n))              # d(T f)/d(PAR(ICP(2)), PAR(ICP(1)))
        for slot, index in ((0, self.free[1]), (1, self.free[0])):
            if index == 11:
                dF[slot] = self.field.f(ug, par).reshape(N, m, n)
            else:
                dF[slot] = T * self.field.fp(ug, par, index).reshape(N, m, n)
        self._last_blocks = (x.copy(), blocks)
        return self.coll.jacobian_general(blocks, dF, self.up_old[None], np.zeros((1, 2)))

    def factor(self, J, border: np.ndarray) -> SparseFactor:
        return SparseFactor(self.coll.bordered(J, np.asarray(border, float)))

    def inner(self, a: np.ndarray, b: np.ndarray) -> float:
        """int_0^1 sum_i THU_i a_i(t) b_i(t) dt + sum THL(k) a_k b_k over the two free
        parameters (AUTO's RINPR + THL; THL(11) = 0 by default)."""
        return float(np.dot(a, self.weights * b))

    def start(self):
        return self._start

    def _blocks_at(self, x):
        cached = getattr(self, "_last_blocks", None)
        if cached is not None and cached[0].shape == x.shape and np.array_equal(cached[0], x):
            return cached[1]
        self.jacobian(x)
        return self._last_blocks[1]

    def multipliers(self, x: np.ndarray) -> np.ndarray:
        """Floquet multipliers at x, AUTO's order (FLOWKM + FNSPBV sorting)."""
        P0, P1 = col.condense_blocks(self._blocks_at(x), self.ndim)
        return col.floquet_multipliers(P0, P1)

    def stability(self, x: np.ndarray, J=None) -> Stability | None:
        """Floquet multipliers and AUTO's NINS (FNSPBV). None when ISP = 0.

        n_stable counts the trivial multiplier plus the others with |mu| <= 1 + 1e-5.
        While the trivial multiplier is inaccurate (|mu_1 - 1| > 0.05, until it is
        back below 0.01) PD/TR detection is suspended and NINS = 0, with the note
        'Multiplier inaccurate'. AUTO enters that state only when the multiplier
        nearest the circle is also of PD/TR type (otherwise it goes on counting the
        inaccurate multipliers: lrz's PT 28 is 'Stable: 3' in its d-file); we enter
        it whenever mu_1 is off, so such points are reported unstable, not stable."""
        if self.settings.ISP == 0:
            return None
        cached = getattr(self, "_stab_cache", None)
        if (cached is not None and cached[1] == self._suspended and cached[0].shape == x.shape
                and np.array_equal(cached[0], x)):
            return cached[2]
        mu = self.multipliers(x)
        notes = []
        err = abs(mu[0] - 1) if len(mu) else 0.0
        n_st = 1 + int(np.sum(np.abs(mu[1:]) <= 1 + STABLE_TOL))
        if err > INACCURATE or (self._suspended and err >= ACCURATE):
            notes.append("Multiplier inaccurate")
            n_st = 0
        elif self._suspended:
            notes.append("Multiplier accurate again")
        out = Stability(values=mu, n_stable=n_st, stable=n_st == self.ndim,
                        kind="multipliers", notes=notes)
        self._stab_cache = (np.array(x), self._suspended, out)
        return out

    def active_tests(self) -> list:
        """LP of cycles (ILP), BP of cycles (|ISP| >= 2, != 4), PD and TR (ISP in {2, 4},
        NDIM > 2), as support.f90:CHECKSP, SP overriding."""
        out = []
        if self.settings.detects("LP"):
            out.append(int(Code.LPC))
        if self.settings.detects("BP"):
            out.append(int(Code.BPC))
        if self.ndim > 2:
            if self.settings.detects("PD"):
                out.append(int(Code.PD))
            if self.settings.detects("TR"):
                out.append(int(Code.TR))
        return out

    def test_functions(self, x, tangent, J, stability, factor, codes=None) -> dict:
        """{Code.LPC: PAR(ICP(1))-component of the tangent (FNLPBV),
        Code.BPC: det of the bordered Jacobian reduced onto (u(0), parameters)
        (FNBPBV's normalised reduced determinant, up to a smooth nonzero factor),
        Code.PD / Code.TR: |mu_2| - 1 of the nontrivial multiplier closest to the unit
        circle when TPSPBV classifies it as PD (real, < -0.5) or TR (|Im| > sqrt(EPSS));
        None otherwise, for NDIM <= 2, or while multipliers are inaccurate}."""
        s = self.settings
        codes = self.active_tests() if codes is None else [int(c) for c in codes]
        out = {}
        if Code.LPC in codes:
            out[int(Code.LPC)] = None if tangent is None else float(tangent[-1])
        if Code.BPC in codes:
            inaccurate = stability is not None and "Multiplier inaccurate" in stability.notes
            if tangent is None or inaccurate:
                # While the trivial multiplier is inaccurate (long orbits near a homoclinic
                # one) the reduced determinant is roundoff: lrz's grows to 1e46 and flips
                # sign at T ~ 300 and 850. AUTO keeps testing there (and its value, of the
                # same size, happens not to flip); we do not report BP of cycles then.
                out[int(Code.BPC)] = None
            else:
                Jx = J if J is not None else self.jacobian(x)
                try:
                    out[int(Code.BPC)] = self.bp_function(Jx, tangent)
                except RuntimeError:
                    out[int(Code.BPC)] = None
        if Code.PD in codes or Code.TR in codes:
            pd = tr = None
            if (self.ndim > 2 and stability is not None
                    and "Multiplier inaccurate" not in stability.notes):
                kind, d = spb_type(stability.values, s.EPSS)
                if kind == Code.PD:
                    pd = d
                elif kind == Code.TR:
                    tr = d
            if Code.PD in codes:
                out[int(Code.PD)] = pd
            if Code.TR in codes:
                out[int(Code.TR)] = tr
        return out

    def border(self, t: np.ndarray) -> np.ndarray:
        """The row r with r @ a == inner(a, t)."""
        return self.weights * np.asarray(t, float)

    def params(self, x: np.ndarray) -> np.ndarray:
        """Full PAR at x: the free parameters (PAR(11) the period) and the user's pvls
        applied to the profile (NTPL, NDIM)."""
        U, par = self.unpack(x)
        if getattr(self.problem, "has_pvls", False):
            par = self.problem.pvls(U, par)
        return par

    def accept(self, code: int, prev, cur) -> bool:
        """PD/TR only if the stable count changed (FNSPBV: NINS1 == NINS -> no point),
        never for NDIM <= 2. LP/BP of cycles and UZ always."""
        if code in (Code.PD, Code.TR):
            if self.ndim <= 2 or prev.stability is None or cur.stability is None:
                return False
            return prev.stability.n_stable != cur.stability.n_stable
        return True

    def update(self, x: np.ndarray, tangent: np.ndarray) -> None:
        """CONTBV's STUPBV: the accepted profile becomes the phase condition's
        reference, u'_old = T f(u_old) at the nodes. Also moves the 'multiplier
        inaccurate' suspension state. With `remesh_in_update` (for iterators without
        the wants_remesh/remesh hook) it also adapts the mesh every IAD accepted points
        (AUTO's ADAPT after NTOT % IAD == 0, the start counting as NTOT = 1),
        interpolating x and tangent onto the new mesh *in place*."""
        U, par = self.unpack(x)
        self.U_old = U.copy()
        if getattr(self, "_keep_hopf_phase", False) and np.array_equal(x, self._start[0]):
            # At the Hopf point itself u' = 0: AUTO keeps STHOPF's UPOLDP (RSPTBV,
            # NODIR = -1) for the first step, and so do we.
            self._keep_hopf_phase = False
        else:
            self.up_old = self._T(par) * self.field.f(U, par)
        self.par = par
        self.n_points += 1
        st = None
        if self.settings.ISP != 0:
            st = self.stability(x)
        if st is not None:
            self._suspended = "Multiplier inaccurate" in st.notes
        if self.remesh_in_update and self.wants_remesh(self.n_points):
            if tangent is None:
                (xn,) = self.remesh(x)
            else:
                xn, tn = self.remesh(x, tangent)
                tangent[:] = tn
            x[:] = xn
            U = self.coll.profile(x)
            self.U_old = U.copy()
            self.up_old = self._T(par) * self.field.f(U, par)

    def wants_remesh(self, n_points: int) -> bool:
        """AUTO adapts the mesh after point NTOT when IAD > 0 and NTOT % IAD == 0."""
        iad = self.settings.IAD
        return iad > 0 and n_points % iad == 0

    def remesh(self, x: np.ndarray, *vectors) -> tuple:
        """AUTO's ADAPT: a new mesh (same NTST, NCOL) equidistributing EQDF of the
        profile of x; x and every further vector (tangent, previous point: anything in
        the unknown layout) are interpolated onto it; the phase reference too."""
        U, _ = self.unpack(x)
        tm = col.new_mesh(self.mesh, U, self.mesh.ntst, periodic=True)
        old = self.mesh
        def move(v):
            v = np.asarray(v, float)
            Uv = v[:self.coll.n_u].reshape(-1, self.ndim)
            return np.r_[col.interpolate(old, Uv, tm, old.ncol).ravel(), v[-2:]]
        out = [move(x)] + [move(v) for v in vectors]
        self.U_old = col.interpolate(old, self.U_old, tm, old.ncol)
        self.up_old = col.interpolate(old, self.up_old, tm, old.ncol)
        self._set_mesh(col.Mesh(tm, old.ncol))
        self._last_blocks = None
        self._stab_cache = None
        return tuple(out)

    # -- output
    def measure(self, U: np.ndarray) -> float:
        """The b-file's second column by IPLT (STPLBV): 0 or out of range: L2 norm
        sqrt(int sum THU_i u_i^2 dt) (RNRMSQ); 1..NDIM: max of U(IPLT); -NDIM..-1: min;
        NDIM+1..2 NDIM: integral of U(IPLT - NDIM); 2 NDIM+1..3 NDIM: L2 norm of
        U(IPLT - 2 NDIM)."""
        n, iplt = self.ndim, self.settings.IPLT
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
        thu = self.settings.theta_u(n)
        return float(math.sqrt(w @ (U ** 2 @ thu)))

    def n2(self) -> int:
        return max(0, min(self.ndim, 7 - len(self.settings.ICP if len(self.settings.ICP) > 1
                                               else self.icp)))

    def column_titles(self) -> list:
        n, iplt = self.ndim, self.settings.IPLT
        iab = abs(iplt)
        if iplt > 0 and iab <= n:
            first = f"MAX U({iab})"
        elif iplt < 0 and iab <= n:
            first = f"MIN U({iab})"
        elif n < iplt <= 2 * n:
            first = f"INTEGRAL U({iplt - n})"
        elif 2 * n < iplt <= 3 * n:
            first = f"L2-NORM U({iplt - 2 * n})"
        else:
            first = "L2-NORM"
        un = self.unames
        return [first] + [f"MAX {un[i]}" if i in un else f"MAX U({i})"
                          for i in range(1, self.n2() + 1)]

    def solution(self, x: np.ndarray, tangent: np.ndarray | None) -> Solution:
        """b-row columns and s-record of x. PAR(12) holds the torus angle |arg mu_2|
        where the nontrivial multiplier nearest the unit circle is complex (FNSPBV sets
        it wherever TPSPBV classifies the point as TR), as AUTO writes it."""
        U = self.coll.profile(x)
        par = self.params(x)
        if self.ndim > 2 and self.settings.ISP != 0 and len(par) >= 12 \
                and self.free[1] != 12 and self.free[0] != 12:
            mu = self.stability(x).values
            kind, _ = spb_type(mu, self.settings.EPSS)
            if kind == Code.TR:
                par[11] = abs(math.atan2(mu[1].imag, mu[1].real))
        cols = [self.measure(U)] + [float(np.max(U[:, i])) for i in range(self.n2())]
        udot = rldot = None
        if tangent is not None:
            udot = self.coll.profile(tangent).copy()
            rldot = [float(tangent[-1]), float(tangent[-2])]
        return Solution(par=par, columns=cols, u=U.copy(), t=self.mesh.node_times(),
                        udot=udot, rldot=rldot or [], ntst=self.mesh.ntst,
                        ncol=self.mesh.ncol, ndim_user=self.ndim)

    # -- branch switching
    def _schur(self, J, border: np.ndarray):
        """Reduce the bordered matrix [J; border] onto the unknowns S = (u(0), the two
        parameters) and the equations R = (periodicity, phase, border): returns
        (Sc, lu_II, M_IS, cols_S, cols_I) with Sc = M_RS - M_RI M_II^-1 M_IS, an
        (NDIM + 2) square matrix whose determinant vanishes exactly where the bordered
        matrix is singular (M_II, the collocation equations for the nodes after t = 0,
        is a discretised initial-value problem and stays invertible)."""
        M = self.coll.bordered(J, border).tocsc()
        n, nu, nc = self.ndim, self.coll.n_u, self.coll.n_coll
        cols_S = np.r_[np.arange(n), nu, nu + 1]
        cols_I = np.arange(n, nu)
        rows_I = np.arange(nc)
        rows_R = np.arange(nc, M.shape[0])
        M_II = M[rows_I][:, cols_I].tocsc()
        M_IS = M[rows_I][:, cols_S].toarray()
        lu = spla.splu(M_II, permc_spec=PERMC_SPEC)
        X = lu.solve(M_IS)
        M_R = M[rows_R]
        Sc = M_R[:, cols_S].toarray() - M_R[:, cols_I] @ X
        return Sc, lu, M_IS, cols_S, cols_I, X

    def bp_function(self, J, tangent: np.ndarray) -> float:
        """The BP test of cycles: det of the bordered Jacobian reduced onto (u(0),
        parameters) (`_schur`, an (NDIM + 2) square matrix S), as det(S / |S|_F): bounded
        by 1, independent of the overall scale, and zero exactly where the bordered
        Jacobian is singular, like AUTO's FNBPBV (the reduced determinant over det P1).
        (Normalising each row instead would divide out the very row that vanishes at a
        decoupled BP, e.g. 1 - exp((mu - a) T) of a symmetry-breaking direction.)"""
        Sc = self._schur(J, self.weights * tangent)[0]
        scale = np.linalg.norm(Sc)
        if not np.isfinite(scale) or scale == 0:
            return 0.0
        sign, logdet = np.linalg.slogdet(Sc / scale)
        return float(sign * math.exp(logdet))

    def null_vector(self, J, border: np.ndarray) -> np.ndarray:
        """A null vector of the (singular or nearly singular) bordered matrix
        [J; border]: the smallest right singular vector of the reduced matrix, then the
        interior nodes by back substitution."""
        Sc, lu, M_IS, cols_S, cols_I, X = self._schur(J, border)
        _, _, Vt = np.linalg.svd(Sc)
        zS = Vt[-1]
        z = np.zeros(self.coll.n_x)
        z[cols_S] = zS
        z[cols_I] = -X @ zS
        return z

    def directions(self, x, tangent, code) -> list:
        """At a BP of cycles: the direction of the other branch, the null vector of the
        Jacobian bordered by the current tangent (orthogonal to it in `inner`)."""
        if int(code) != int(Code.BPC):
            return []
        z = self.null_vector(self.jacobian(x), self.weights * tangent)
        return [z / math.sqrt(self.inner(z, z))]


def spb_type(mu: np.ndarray, epss: float) -> tuple[int, float | None]:
    """AUTO's TPSPBV + FNSPBV on multipliers sorted as `sort_multipliers`:
    (Code.PD / Code.TR / 0, |mu_2| - 1 or None). mu_2 is the nontrivial multiplier
    closest to the unit circle."""
    if len(mu) < 2:
        return 0, None
    m2 = mu[1]
    if not np.isfinite(m2):
        return 0, None
    if abs(m2.imag) > math.sqrt(epss):
        return int(Code.TR), float(abs(m2) - 1)
    if m2.real < -0.5:
        return int(Code.PD), float(abs(m2) - 1)
    return 0, None


register(2, 1, "HB")(PeriodicOrbits)
register(2, 1, "*")(PeriodicOrbits)
register(2, -1, "PD")(PeriodicOrbits)
register(2, -1, "BP")(PeriodicOrbits)
