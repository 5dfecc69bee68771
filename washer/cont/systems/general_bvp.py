"""General boundary value problems (IPS = 4): AUTO's AUTOBV with the user's FUNC,
BCND and ICND (bvp.f90, toolboxbv.f90: STPNBV, STPNUB, FNLPBV, FNBPBV).

    u'(t) = f(u(t), p),  t in [0, 1]
    b(u(0), u(1), p) = 0                                   (NBC conditions, bcnd)
    int_0^1 g(u(t), u_old(t), u'_old... , p) dt = 0         (NINT conditions, icnd)

with NFPR = NBC + NINT - NDIM + 1 free parameters PAR(ICP(1..NFPR)); further ICP
entries are only written (AUTO's "overspecified" parameters). The integrand icnd
receives u(t), the previous solution u_old(t), the branch direction udot(t) and
upold(t) = f(u_old(t), p) at each mesh node (AUTO's ICNI arguments); the integral is
the collocation's node quadrature (WINT).

Discretisation as for periodic orbits (washer.cont.collocation): NTST intervals,
NCOL Gauss points, the NCOL + 1 equally spaced nodes per interval as unknowns.
Unknowns x = (U flattened node-major, PAR(ICP(2..NFPR)), PAR(ICP(1))). The system is
a `systems.bvp.CollocationBVP`, the base of the periodic orbits and their loci: the
same collocation (`collocation.Collocation` with NBC general boundary conditions and
NFPR parameter unknowns, its sparsity pattern fixed per mesh), factorisation, inner
product, mesh adaptation (without the periodic wrap-around of EQDF), the reduction
onto the boundary unknowns for the BP test and the switching direction, and output.

Starts:
* IRS = 0: STPNT at every node time of the uniform mesh, stpnt(u, par, t) (AUTO's
  STPNUB); the direction is the null vector of the Jacobian, PAR(ICP(1))-dot > 0
  (or the first non-negligible free parameter's; STDRBV).
* a stored BVP solution: moved onto the run's mesh when NTST/NCOL differ (ADAPT2),
  its direction reused when the free parameters agree (STPNBV1).
* ISW = -1 at a BP (code 6): the null vector of the Jacobian bordered by the stored
  direction (STDRBV with IPERP = 1): the other branch. ISW = -1 at any other label
  (CNRLBV takes IPERP = 1 whenever IRS != 0 and ISW < 0): the Jacobian's null vector
  with STDRBV's orientation, the one branch through the point.

Test functions: LP (code 5) the PAR(ICP(1))-component of the unit tangent (FNLPBV),
BP (code 6) the determinant of the bordered Jacobian reduced onto (u(0), the free
parameters) and normalised (the role of FNBPBV's det(reduced)/det(P1)). No stability
(PT > 0), no automatic branch switching (MXBF is for algebraic problems).
"""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from washer.cont.codes import Code
from washer.cont import collocation as col
from washer.cont.linalg import permutation_sign
from washer.cont.differences import columns, quotient, step
from washer.cont.problem import Problem
from washer.cont.settings import SettingsError
from washer.cont.system import Solution, StartData, register
from washer.cont.systems.bvp import CollocationBVP, VectorField, record_profile

def _widen(P: np.ndarray, n: int) -> np.ndarray:
    """A stored profile (NTPL, k) with k <= n components, the others 0 (READBV)."""
    if P.shape[1] >= n:
        return P
    return np.hstack([P, np.zeros((len(P), n - P.shape[1]))])


class BoundaryValueProblem(CollocationBVP):
    """The continued system of a general BVP (IPS = 4, ISW = 1 or -1 at a BP).
    `ndim` here counts every component of the continued BVP (2 NDIM on the fold locus),
    `ndm` the user's (the b-file's columns)."""
    general_bc = True
    periodic_mesh = False
    #: ADAPT2's periodic extension when a restart's profile moves onto a mesh of another
    #: NTST (STPNPS, IPS = 7: True; STPNBV, IPS = 4: False)
    restart_periodic = False

    def __init__(self, data):
        s = data.settings
        self.settings, self.problem = s, data.problem
        self.ndim = n = s.NDIM
        self.ndm = getattr(self, "ndm", n)          # AUTO's NDM: the user's NDIM
        self.nbc, self.nint = s.NBC, s.NINT
        nfpr = self.nbc + self.nint - n + 1
        if nfpr < 1:
            raise ValueError(f"NBC = {self.nbc}, NINT = {self.nint}, NDIM = {n}: NBC + NINT - "
                             f"NDIM + 1 = {nfpr} free parameters; expected at least 1")
        if len(s.ICP) < nfpr and getattr(self, "_free", None) is None:
            raise SettingsError(f"NBC + NINT - NDIM + 1 = {nfpr} free parameters, but ICP = "
                             f"{list(s.ICP)} names {len(s.ICP)}", keys=("ICP",))
        self.nfpr = nfpr
        # The free parameters: the first NFPR of ICP, unless a subclass set its own
        # (the generating run of a fold locus frees the null vector's norm instead of
        # ICP(2), which stays written).
        self.free = list(getattr(self, "_free", None) or s.ICP[:nfpr])
        self._order = self.free[1:] + self.free[:1]      # x's parameter slots
        self.n_comp = n
        self.field = VectorField(self.problem, n)
        self.par = np.zeros(max(s.NPAR, max(s.ICP)))
        p = np.asarray(data.par, float)
        self.par[:min(len(p), len(self.par))] = p[:len(self.par)]
        self.unames = dict(getattr(data, "unames", {}) or {})
        self.kind = (data.kind or "").upper()
        self.n_points = 0
        rec = data.record
        if rec is None and getattr(data, "data", None) is not None:
            self._from_data(*data.data)
        elif rec is None:
            self._from_stpnt()
        elif np.ndim(rec.U) == 2 and len(rec.U) > 1:
            self._from_record(rec)
        else:
            # An algebraic record: a constant solution on the uniform mesh (RSPTBV).
            self._set_mesh(col.Mesh.uniform(s.NTST, s.NCOL))
            U = np.tile(np.asarray(rec.U, float)[:n], (self.mesh.n_nodes, 1))
            self._begin(U, None)

    # ------------------------------------------------------------------ set-up
    @property
    def n_tail(self) -> int:
        return self.nfpr

    def tail_weights(self) -> np.ndarray:
        return np.array([self.settings.theta_par(i) for i in self._order])

    def period(self, par) -> float:
        """No period scales a general BVP's right-hand side."""
        return 1.0

    def set_mesh(self, mesh: col.Mesh) -> None:
        super().set_mesh(mesh)
        c = self.coll
        self.n_u, self.n_coll, self.n_x = c.n_u, c.n_coll, c.n_x
        self.w_node, self.local, self.WT, self.WP = c.w_node, c.local, c.WT, c.WP

    _set_mesh = set_mesh

    def _x(self, U, par) -> np.ndarray:
        return np.r_[np.asarray(U, float).ravel(), [par[i - 1] for i in self._order]]

    def _from_stpnt(self) -> None:
        """STPNUB: stpnt(u, par, t) at every node of the uniform mesh (the parameters
        are the start data's: stpnt's at t = 0 with the constants' PAR overrides)."""
        s = self.settings
        self._set_mesh(col.Mesh.uniform(s.NTST, s.NCOL))
        U = self.problem.start_profile(self.par.copy(), self.mesh.node_times())
        self._begin(U, None)

    def _from_data(self, t, U) -> None:
        """STPNUB with dat='NAME': the data file's profile, time rescaled to [0, 1],
        moved onto an adapted mesh of NTST intervals (`collocation.profile_from_data`)."""
        s = self.settings
        mesh, U, _ = col.profile_from_data(t, U, s.NTST, s.NCOL, periodic=False)
        self._set_mesh(mesh)
        self._begin(U, None)

    def _from_record(self, rec) -> None:
        """STPNBV1 + ADAPT2: the stored solution on the run's mesh."""
        s, n = self.settings, self.ndim
        t_r, U_r, ntst_r, ncol_r = record_profile(rec, n)
        if U_r.shape[1] < n and self.ndm == n:
            # READBV: an extended system's new components from stpnt (0 without one)
            U_r = self.problem.extend_profile(U_r, self.par, t_r)
        U_r = _widen(U_r, n)
        mesh_r = col.Mesh(t_r[::ncol_r].copy(), ncol_r)
        ud_r = None
        if rec.udot is not None:
            ud_r = _widen(np.asarray(rec.udot, float).reshape(len(U_r), -1)[:, :n], n)
        if ntst_r == s.NTST and ncol_r == s.NCOL:
            mesh, U, ud = mesh_r, U_r.copy(), ud_r
        else:
            mesh = col.Mesh(col.new_mesh(mesh_r, U_r, s.NTST, periodic=self.restart_periodic),
                            s.NCOL)
            U = col.interpolate(mesh_r, U_r, mesh.tm, s.NCOL)
            ud = None if ud_r is None else col.interpolate(mesh_r, ud_r, mesh.tm, s.NCOL)
        self._set_mesh(mesh)
        rldot = list(getattr(rec, "rldot", []) or [])
        icp_r = list(getattr(rec, "icp", []) or [])
        old = None
        if ud is not None and len(rldot) >= self.nfpr and len(icp_r) >= self.nfpr:
            # The stored direction in this run's parameter order (by index).
            dpar = dict(zip(icp_r, rldot))
            if all(i in dpar for i in self.free):
                old = np.r_[ud.ravel(), [dpar[i] for i in self._order]]
        same = old is not None and icp_r[:self.nfpr] == self.free
        self._begin(U, old if (same or self.settings.ISW == -1) else None)
        # READBV reads the record's NFPR parameter rates into RLDOT(1..) in order, the
        # rest 0, whatever the run's ICP: the border of AUTO's IPERP = 1 start where the
        # free parameters changed (r3b's Floquet eigenfunction run from a halo orbit
        # stored with ICP = [1, 11] continues in [lambda, fm, rho]).
        self._stored_rows = None
        if ud is not None and self.settings.ISW == -1:
            rates = {i: (rldot[k] if k < len(rldot) else 0.0) for k, i in enumerate(self.free)}
            self._stored_rows = np.r_[ud.ravel(), [rates[i] for i in self._order]]

    def _begin(self, U, old) -> None:
        # RSPTBV: PVLS on the start "so the parameters can be initialized": its PAR is
        # the run's (pcl's PVLS sets the section offsets its boundary conditions hold,
        # on its first call of a run).
        self.par = np.asarray(self.pvls_params(np.asarray(U, float), self.par,
                                               self.par[10] if len(self.par) > 10 else 0.0),
                              float)
        self.U_old = np.array(U, float)
        self.udot_old = np.zeros_like(self.U_old)
        self.up_old = self.field.f(self.U_old, self.par)          # STUPBV
        x0 = self._x(U, self.par)
        self._stored = old
        self._start = (x0, None)

    # ------------------------------------------------------------------ helpers
    def unpack(self, x):
        par = self.par.copy()
        for k, i in enumerate(self._order):
            par[i - 1] = x[self.n_u + k]
        return x[:self.n_u].reshape(-1, self.ndim), par

    def at_gauss(self, U):
        return np.einsum("kc,jkn->jcn", self.WT, U[self.local])

    def _bc(self, U, par):
        if self.nbc == 0:
            return np.zeros(0)
        return self.problem.bcnd(U[0], U[-1], par, self.nbc)

    def _ic_nodes(self, U, par) -> np.ndarray:
        """The integrands at every node, (n_nodes, NINT)."""
        return self.problem.icnd_many(U, self.U_old, self.udot_old, self.up_old, par,
                                      self.nint)

    def gauss_f(self, ug, par) -> np.ndarray:
        """The right-hand side at the collocation points ug (NTST NCOL, NDIM), row-major
        by interval: the problem's f (a system with more terms, the implicit Euler step
        of a parabolic PDE's evolution, adds them)."""
        return self.field.f(ug, par)

    def gauss_fu_fp(self, ug, par):
        """(f_u (NTST NCOL, NDIM, NDIM), [f_PAR(i) (NTST NCOL, NDIM) for i in x's
        parameter order]) at the collocation points: `gauss_f`'s derivatives."""
        return self.field.fu(ug, par), [self.field.fp(ug, par, i) for i in self._order]

    # ------------------------------------------------------------------ contract
    def residual(self, x):
        U, par = self.unpack(x)
        N, m, n = self.mesh.ntst, self.mesh.ncol, self.ndim
        fg = self.gauss_f(self.at_gauss(U).reshape(-1, n), par).reshape(N, m, n)
        ints = self.w_node @ self._ic_nodes(U, par) if self.nint else np.zeros(0)
        return self.coll.residual_general(U, fg, ints, bc=self._bc(U, par))

    def jacobian(self, x):
        U, par = self.unpack(x)
        N, m, n = self.mesh.ntst, self.mesh.ncol, self.ndim
        ug = self.at_gauss(U).reshape(-1, n)
        fu, fp = self.gauss_fu_fp(ug, par)
        blocks = self.coll.local_blocks(1.0, fu.reshape(N, m, n, n))
        dF = np.array([d.reshape(N, m, n) for d in fp])
        if self.nbc:
            Jb = self._bc_jacobian(U, par)                  # (nbc, 2n + nfpr)
            bc_jac = (Jb[:, :n], Jb[:, n:2 * n], Jb[:, 2 * n:])
        else:
            bc_jac = (np.zeros((0, n)), np.zeros((0, n)), np.zeros((0, self.nfpr)))
        if self.nint:
            Ju, Jp = self._ic_jacobian(U, par)              # (nint, n_nodes, n), (nint, nfpr)
        else:
            Ju, Jp = np.zeros((0, len(U), n)), np.zeros((0, self.nfpr))
        return self.coll.jacobian_general(blocks, dF, Ju, Jp, bc_jac=bc_jac)

    def _bc_jacobian(self, U, par) -> np.ndarray:
        n = self.ndim
        z = np.r_[U[0], U[-1], [par[i - 1] for i in self._order]]

        def fb(zz):
            p = par.copy()
            for k, i in enumerate(self._order):
                p[i - 1] = zz[2 * n + k]
            return self.problem.bcnd(zz[:n], zz[n:2 * n], p, self.nbc)
        return columns(fb, z, range(len(z)))

    def _ic_jacobian(self, U, par):
        n, nn = self.ndim, len(U)
        Ju = np.empty((self.nint, nn, n))
        for l in range(n):
            h = step(U[:, l])
            Up, Um = U.copy(), U.copy()
            Up[:, l] += h
            Um[:, l] -= h
            Ju[:, :, l] = quotient(self._ic_nodes(Up, par), self._ic_nodes(Um, par), h[:, None]).T
        # Parameter columns by forward differences from the unperturbed integrands, as
        # AUTO's ICNI (one sweep of the mesh per parameter instead of two).
        Jp = np.empty((self.nint, self.nfpr))
        base = self.w_node @ self._ic_nodes(U, par)
        for k, i in enumerate(self._order):
            h = step(par[i - 1])
            pp = par.copy()
            pp[i - 1] += h
            Jp[:, k] = (self.w_node @ self._ic_nodes(U, pp) - base) / h
        return Ju, Jp

    def params(self, x):
        U, par = self.unpack(x)
        return self.pvls_params(U, par, par[10] if len(par) > 10 else 0.0)

    def start(self):
        x0 = self._start[0]
        J = self.jacobian(x0)
        switch = self.settings.ISW == -1
        if self._stored is not None and switch and self.kind == "BP":
            # STDRBV with IPERP = 1: the other branch at a BP.
            z = self.null_vector(J, self.weights * self._stored)
            return x0, self.orient_stdrbv(z / math.sqrt(self.inner(z, z)), x0)
        if self._stored is not None and not switch:
            nrm = math.sqrt(self.inner(self._stored, self._stored))
            if nrm > 0:
                return x0, self._stored / nrm
        # The null vector of J: bordered by PAR(ICP(1)) (the solve with that component
        # 1, as the iterator's own start), which stays well conditioned on stiff
        # problems (spb at eps = 1e-3, where the reduced matrix's smallest singular
        # vector is rounding); at a fold in PAR(ICP(1)) that border is singular and the
        # reduced matrix's null vector is taken. Where that is no null vector of J either
        # (its interior nodes, back-substituted, carry the rounding of a badly
        # conditioned reduction: kdv's second run, an orbit over T = 20 with eigenvalues
        # +-4.4, |J z| = 3 |J| |z|), the borders of the other free parameters are tried in
        # ICP's order: kdv's run moves PAR(9), in no equation, alone, and the border of
        # PAR(9) gives its unit vector exactly (AUTO's starting direction there).
        z = self._bordered_null_vector(J, self.n_x - 1)
        if z is None:
            z = self.null_vector(J, np.zeros(self.n_x))
            if not self._is_null_vector(J, z):
                for slot in range(self.coll.n_u, self.n_x - 1):
                    zb = self._bordered_null_vector(J, slot)
                    if zb is not None:
                        z = zb
                        break
        if switch and getattr(self, "_stored_rows", None) is not None:
            z = self._orthogonal_to_stored(J, z)
        return x0, self.orient_stdrbv(z / math.sqrt(self.inner(z, z)), x0)

    def _orthogonal_to_stored(self, J, z):
        """ISW = -1 away from a BP label: AUTO's start (CNRLBV's IPERP = 1 at any
        restart with ISW < 0) is the null vector of J bordered by the stored direction,
        the direction of the (near) null space of J orthogonal to it. Where J has one
        null vector z that is z itself; where a second direction is (nearly) null too,
        as on a trivial branch next to where it meets another (r3b's Floquet
        eigenfunction v = 0 with fm free, fm from PVLS 0.13 % off the multiplier), the
        stored direction picks the other branch. The second direction is taken only
        where it fits [J; border] a hundred times better than z fits the border."""
        border = self.weights * self._stored_rows
        nb = float(np.linalg.norm(border))
        if nb == 0.0:
            return z
        unit = lambda v: v / math.sqrt(self.inner(v, v))        # noqa: E731
        z1 = unit(z)
        r1 = abs(float(border @ z1)) / nb
        z2 = unit(self.null_vector(J, border))
        scale = float(abs(J).max()) if J.shape[0] else 1.0
        r2 = max(abs(float(border @ z2)) / nb,
                 float(np.linalg.norm(J @ z2)) / max(scale, 1.0))
        return z2 if r2 < 0.01 * r1 else z

    def _bordered_null_vector(self, J, slot: int):
        """The solution z of J z = 0 with z[slot] = 1 (a free parameter's rate), or None
        where that border is singular: a null vector of J, not the rounding of a singular
        border (where the branch's direction has no such component, c2c's third run:
        the trivial eigenfunction branch moves PAR(12) alone, PAR(11) = ICP(1) stays, the
        bordered solve returns a vector with |J z| ~ 1e-4 |J| |z|)."""
        e = np.zeros(self.n_x)
        e[slot] = 1.0
        rhs = np.zeros(self.n_x)
        rhs[-1] = 1.0                       # the border's row: z[slot] = 1
        try:
            with np.errstate(all="ignore"):
                z = self.factor(J, e).solve(rhs)
        except (RuntimeError, np.linalg.LinAlgError, ValueError):
            return None
        if not (np.all(np.isfinite(z)) and np.max(np.abs(z)) < 1e12):
            return None
        return z if self._is_null_vector(J, z) else None

    @staticmethod
    def _is_null_vector(J, z) -> bool:
        """|J z| <= sqrt(eps) max(|J|_max, 1) |z|."""
        scale = float(abs(J).max()) if J.shape[0] else 1.0
        return float(np.linalg.norm(J @ z)) <= \
            math.sqrt(np.finfo(float).eps) * max(scale, 1.0) * float(np.linalg.norm(z))

    def stability(self, x, J=None):
        return None

    def active_tests(self) -> list:
        out = []
        if self.settings.detects("LP"):
            out.append(int(Code.LPC))
        if self.settings.detects("BP"):
            out.append(int(Code.BPC))
        return out

    def accept(self, code, prev, cur) -> bool:
        return True

    @property
    def n_state(self) -> int:
        """The profile's unknowns come first (AUTO's NEWTONBV test: EPSU on them, EPSL
        on each free parameter)."""
        return self.n_u

    def located_code(self, key, point) -> int:
        """A located zero is written with its test's code."""
        return key

    def info(self, x, code) -> dict:
        """Nothing is computed at special points of BVPs beyond the b-row."""
        return {}

    def update(self, x, tangent) -> None:
        """CONTBV: the accepted point becomes the reference of the integral conditions
        (u_old, udot, upold = f(u_old))."""
        U, par = self.unpack(x)
        self.U_old = U.copy()
        if tangent is not None:
            self.udot_old = tangent[:self.n_u].reshape(-1, self.ndim).copy()
        self.up_old = self.field.f(U, par)
        self.par = par
        self.n_points += 1

    def set_phase_reference(self, U, par) -> None:
        """CONTBV: the accepted profile and f at it (UOLDPS, UPOLDP) are the integral
        conditions' references, all components."""
        self.U_old = np.array(U, float)
        self.up_old = self.field.f(self.U_old, par)

    def remesh(self, x, *vectors) -> tuple:
        """ADAPT (the base's), the branch direction of the integral conditions too."""
        old = self.mesh
        out = super().remesh(x, *vectors)
        self.udot_old = col.interpolate(old, self.udot_old, self.mesh.tm, old.ncol)
        return out

    # ------------------------------------------------------------------ output
    @property
    def n_shown(self) -> int:
        """The b-file's columns describe the user's components (AUTO's NDM)."""
        return self.ndm

    def n2(self) -> int:
        nicp = len(self.settings.ICP)
        return 0 if nicp > 7 else max(0, min(self.ndm, 7 - nicp))

    def solution(self, x, tangent) -> Solution:
        U, _ = self.unpack(x)
        par = self.params(x)
        cols = [self.measure(U)] + [float(np.max(U[:, i])) for i in range(self.n2())]
        udot, rldot = None, []
        if tangent is not None:
            udot = tangent[:self.n_u].reshape(-1, self.ndim).copy()
            slot = {i: self.n_u + k for k, i in enumerate(self._order)}
            rldot = [float(tangent[slot[i]]) for i in self.free]
        return Solution(par=par, columns=cols, u=U.copy(), t=self.mesh.node_times(),
                        udot=udot, rldot=rldot, ntst=self.mesh.ntst, ncol=self.mesh.ncol,
                        ndim_user=self.ndm)

    def bp_function(self, J, tangent) -> float:
        """The BP test (FNBPBV's role): the determinant of the bordered Jacobian reduced
        onto the boundary unknowns (the base's `reduce`), relative to its value at the
        branch's first evaluation: a smooth function with the determinant's zeros and
        sign. (Scaled by the reduced matrix's own norm, as for cycles, it underflows on
        pcl's trivial branch, where the decoupled Floquet block makes it ~1e-300 long
        before it changes sign at AUTO's BP, mu = -9.2836.)"""
        border = self.weights * tangent
        Sc, X = self.reduce(J, border)
        sign, logdet = np.linalg.slogdet(Sc)
        if self._schur_unreliable(J, border, Sc, X):
            sign, logdet = self._det_ratio(J, border)
        if sign == 0 or not np.isfinite(logdet):
            return 0.0
        if getattr(self, "_bp_log0", None) is None:
            self._bp_log0 = logdet
        return float(sign * math.exp(min(max(logdet - self._bp_log0, -700.0), 700.0)))

    def _schur_unreliable(self, J, border, Sc, X) -> bool:
        """Whether the computed reduced matrix Sc = M_RS - M_RI X (X = M_II^-1 M_IS, the
        interior eliminated onto u(0), which is single shooting over [0, 1]) is too
        inexact for the sign of its determinant: its rounding, eps |M_RI| |X|, reaches
        its smallest singular value. On a stiff profile X grows as the fundamental
        solution (pci's connection, exp(lambda T+) with T+ ~ 1e3: the computed det(Sc)
        then changes sign from step to step while det M and det M_II do not)."""
        M = self.coll.bordered(J, border).tocsr()
        nc, n, nu = self.coll.n_coll, self.n_comp, self.coll.n_u
        m_ri = float(np.sqrt((M[nc:, n:nu].data ** 2).sum())) if M[nc:, n:nu].nnz else 0.0
        err = np.finfo(float).eps * m_ri * float(np.linalg.norm(X))
        smin = float(np.linalg.svd(Sc, compute_uv=False)[-1]) if Sc.size else 0.0
        return not err < smin

    def _det_ratio(self, J, border) -> tuple[float, float]:
        """(sign, log|.|) of det M / det M_II from sparse LU factorisations of the bordered
        Jacobian M and of its interior block M_II (each backward stable, as AUTO's
        FNBPBV takes the determinant of its condensed system over det P1 rather than
        forming the reduced matrix): the same quotient as det(Sc)."""
        import scipy.sparse.linalg as spla
        M = self.coll.bordered(J, border).tocsc()
        nc, n, nu = self.coll.n_coll, self.n_comp, self.coll.n_u
        out_sign, out_log = 1.0, 0.0
        for A, power in ((M, 1), (M[:nc][:, n:nu].tocsc(), -1)):
            try:
                lu = spla.splu(A, permc_spec="COLAMD")
            except RuntimeError:              # exactly singular
                return (0.0, -np.inf) if power == 1 else (1.0, np.inf)
            d = lu.U.diagonal()
            out_sign *= (permutation_sign(lu.perm_r) * permutation_sign(lu.perm_c)
                         * float(np.prod(np.sign(d))))
            out_log += power * float(np.sum(np.log(np.abs(d))))
        return out_sign, out_log

    def fold_null_vector(self, x) -> np.ndarray:
        """The null vector of the Jacobian at a fold x of the branch (n_x,): the tangent,
        with PAR(ICP(1)) at rest. The direction stored with the point (else the reduced
        matrix's smallest singular vector) borders the Jacobian, and the bordered system
        is solved by the sparse factorisation: one step of inverse iteration, which makes
        the null vector exact to rounding also where the reduced matrix (single shooting
        over [0, 1]) is inexact on a stiff profile."""
        J = self.jacobian(x)
        guess = self._stored if self._stored is not None else \
            self.null_vector(J, np.zeros(self.n_x))
        e = np.zeros(self.n_x)
        e[-1] = 1.0
        z = self.factor(J, self.border(guess)).solve(e)
        return z / math.sqrt(self.inner(z, z))

    # ------------------------------------------------------------------ switching
    def directions(self, x, tangent, code) -> list:
        if int(code) != int(Code.BPC):
            return []
        z = self.null_vector(self.jacobian(x), self.weights * tangent)
        return [z / math.sqrt(self.inner(z, z))]


register(4, 1, "*")(BoundaryValueProblem)
register(4, -1, "BP")(BoundaryValueProblem)


# --------------------------------------------------------------------------- fold loci

#: Relative step of the directional differences f_u v, b_u v, g_u v of the fold locus:
#: central differences whose truncation (~1e-8 relative) and rounding (~1e-12) both
#: stay far below the location tolerance, and which the Newton matrix (differences of
#: these, step 1e-7) sees as smooth.
DIR_STEP = 1e-4


def fold_problem(problem, n: int, nbc: int, nint: int, norm_index: int,
                 null_pars: tuple = ()) -> Problem:
    """The extended BVP of a fold of a BVP (AUTO's FNBL, BCBL, ICBL) as a problem in
    W = (u, v), NDIM = 2n:

        u' = f(u, p),               v' = f_u(u, p) v + f_p q
        b(u(0), u(1), p) = 0,       b_u0 v(0) + b_u1 v(1) + b_p q = 0
        int g(u, ...) dt = 0,       int g_u v + g_p q dt = 0,
                                    int |v|^2 dt + |q|^2 - PAR(norm) = 0

    (v the null vector of the linearised BVP: NBC' = 2 NBC, NINT' = 2 NINT + 1). Where
    the BVP has m = NBC + NINT - NDIM + 1 > 1 free parameters on its branch, the null
    vector has parameter components too: `null_pars` = ((i, j), ...), the direction
    q_i = PAR(j) along PAR(i) for ICP(2..m) (AUTO's PAR(NPAR + 1..NPAR + m - 1)); f_p q
    and b_p q are then part of one central difference along (v, q), g_p q a central
    difference of its own along q (the integrand's parameters are shared by the nodes).
    Without q, f_u v is the user's dfdu times v where JAC allows, else a central
    difference along v."""
    exact = problem._dfdu is not None and problem.jac != 0
    null_pars = tuple((int(i), int(j)) for i, j in null_pars)

    def pdir(pars):
        """The parameter part of the direction, (k, NPAR): q_j at PAR(i) (None: none)."""
        if not null_pars:
            return None
        pars = np.atleast_2d(np.asarray(pars, float))
        q = np.zeros_like(pars)
        for i, j in null_pars:
            q[:, i - 1] = pars[:, j - 1]
        return q

    def steps_pq(u, v, pars, q):
        """Steps along (v, q) for central differences of f and b along the null
        vector, parameters included: the largest that moves u and each PAR(i) by at
        most DIR_STEP relative to its own size (one scale for all would let a large
        parameter, as a connection time of 200, widen the step in u by as much)."""
        h = steps(u, v)
        for i, _ in null_pars:
            h = np.minimum(h, DIR_STEP * (1 + np.abs(pars[:, i - 1]))
                           / np.maximum(np.abs(q[:, i - 1]), 1e-300))
        return h

    def steps(u, v):
        return DIR_STEP * (1 + np.max(np.abs(u), axis=1)) / \
            np.maximum(np.max(np.abs(v), axis=1), 1e-300)

    def func_batch(W, pars):
        W = np.asarray(W, float)
        u, v = W[:, :n], W[:, n:]
        f0 = problem.func_many(u, pars)
        q = pdir(pars)
        if q is not None:
            pars = np.broadcast_to(np.asarray(pars, float), q.shape)
            h = steps_pq(u, v, pars, q)[:, None]
            F = problem.func_many(np.vstack([u + h * v, u - h * v]),
                                  np.vstack([pars + h * q, pars - h * q]))
            fv = (F[:len(u)] - F[len(u):]) / (2 * h)
        elif exact:
            fv = np.einsum("kij,kj->ki", problem.dfdu_many(u, pars), v)
        else:
            h = steps(u, v)[:, None]
            F = problem.func_many(np.vstack([u + h * v, u - h * v]), np.vstack([pars, pars]))
            fv = (F[:len(u)] - F[len(u):]) / (2 * h)
        return np.hstack([f0, fv])

    def func(W, par):
        return func_batch(np.asarray(W, float)[None, :], np.asarray(par, float)[None, :])[0]

    def bcnd(W0, W1, par):
        u0, v0, u1, v1 = W0[:n], W0[n:], W1[:n], W1[n:]
        b = problem.bcnd(u0, u1, par, nbc)
        q = pdir(par)
        if q is None:
            h = DIR_STEP * (1 + max(np.max(np.abs(u0)), np.max(np.abs(u1)))) / \
                max(np.max(np.abs(v0)), np.max(np.abs(v1)), 1e-300)
            bv = (problem.bcnd(u0 + h * v0, u1 + h * v1, par, nbc)
                  - problem.bcnd(u0 - h * v0, u1 - h * v1, par, nbc)) / (2 * h)
            return np.r_[b, bv]
        par = np.asarray(par, float)
        h = float(steps_pq(np.r_[u0, u1][None, :], np.r_[v0, v1][None, :], par[None, :],
                           q)[0])
        bv = (problem.bcnd(u0 + h * v0, u1 + h * v1, par + h * q[0], nbc)
              - problem.bcnd(u0 - h * v0, u1 - h * v1, par - h * q[0], nbc)) / (2 * h)
        return np.r_[b, bv]

    def icnd(W, Wold, Wdot, Wpold, par):
        batch = np.ndim(W) == 2
        args = [np.asarray(a, float).T if batch else np.asarray(a, float)[None, :]
                for a in (W, Wold, Wdot, Wpold)]
        Wk, Wo, Wd, Wp = args
        u, v = Wk[:, :n], Wk[:, n:]
        parts = []
        q = pdir(par)
        if nint:
            rest = (Wo[:, :n], Wd[:, :n], Wp[:, :n])
            g = problem.icnd_many(u, *rest, par, nint)
            h = steps(u, v)[:, None]
            gv = (problem.icnd_many(u + h * v, *rest, par, nint)
                  - problem.icnd_many(u - h * v, *rest, par, nint)) / (2 * h)
            if q is not None and np.any(q):
                # g_p q apart from g_u v: the parameters are one vector for every node,
                # so a step along q shared by the rows, and each row's own step along v
                # as above; a node's integrand is then the same alone or in a batch (one
                # batched call per sweep instead of one per node).
                p, qp = np.asarray(par, float), q[0]
                hp = float(np.min([DIR_STEP * (1 + abs(p[i - 1])) / abs(qp[i - 1])
                                   for i, _ in null_pars if qp[i - 1] != 0]))
                gv = gv + (problem.icnd_many(u, *rest, p + hp * qp, nint)
                           - problem.icnd_many(u, *rest, p - hp * qp, nint)) / (2 * hp)
            parts += [g, gv]
        qq = 0.0 if q is None else float(sum(par[j - 1] ** 2 for _, j in null_pars))
        parts.append((np.sum(v * v, axis=1) + qq - par[norm_index - 1])[:, None])
        out = np.hstack(parts)
        return out.T if batch else out[0]

    return Problem(2 * n, func, func_batch=func_batch, name=problem.name, npar=problem.npar,
                   pvls=problem._pvls, parnames=problem.parnames, unames=problem.unames,
                   jac=0, bcnd=bcnd if nbc else None, icnd=icnd)


@register(4, 2, "LP")
@register(4, 2, "LP-curve")
class BVPFoldLocus(BoundaryValueProblem):
    """The fold locus of a BVP (ISW = 2 from an LP of code 5): the BVP `fold_problem` in
    W = (u, v) continued in the branch's m = NBC + NINT - NDIM + 1 free parameters
    PAR(ICP(1..m)) and one more, PAR(ICP(m + 1)), with PAR(NPAR + m) (AUTO's internal
    PAR(NPAR)) holding int |v|^2 dt + |q|^2, and, where m > 1, the null vector's
    parameter components q along PAR(ICP(2..m)) in PAR(NPAR + 1..NPAR + m - 1) (AUTO's
    AUTOBVP: NFPR = 2 m free parameters, NPARI = m).

    As AUTO (AUTOBVP with ISW = -2), a start at the LP itself is a generating run: the
    null vector (v, q) grows from 0 along the BVP's null vector at the LP, its norm free
    in place of PAR(ICP(m + 1)), which stays fixed, ILP = ISP = 0, NMX = 5; restarting
    from its end point (a record of this curve) continues the locus in the user's ICP.
    The parameters PAR(ICP(2..m)) of the locus need not be those of the LP's run (snh's
    tb.auto: the LP of a branch in nu1, mu, T, delta, T- continued with nu2 in place of
    mu); the BVP's null vector is then the one in the locus's parameters."""
    curve_type = 5

    def __init__(self, data):
        s = data.settings
        n = s.NDIM
        m = s.NBC + s.NINT - n + 1
        if len(s.ICP) < m + 1:
            raise SettingsError(f"ISW = 2 continues the fold locus of a BVP with NBC + NINT - "
                                f"NDIM + 1 = {m} free parameters in {m + 1}: ICP needs "
                                f"{m + 1} entries, got {list(s.ICP)}", keys=("ICP",))
        norm = s.NPAR + m
        # the null vector's parameter components: q_k = PAR(NPAR + k) along PAR(ICP(k + 1))
        null_pars = tuple((s.ICP[k], s.NPAR + k) for k in range(1, m))
        q_idx = [j for _, j in null_pars]
        generating = data.kind == "LP"
        self._free = (list(s.ICP[:m]) + [norm] + q_idx if generating
                      else list(s.ICP[:m + 1]) + q_idx)
        # AUTO's generating run has ISW = -2 internally: its branch number is new.
        over = dict(NMX=5, ILP=0, ISP=0, ISW=-2) if generating else {}
        s2 = s.with_(NDIM=2 * n, NBC=2 * s.NBC, NINT=2 * s.NINT + 1, NPAR=norm, **over)
        self.run_settings = s2
        par = np.zeros(norm)
        p = np.asarray(data.par, float)
        par[:min(len(p), norm)] = p[:norm]
        ext = fold_problem(data.problem, n, s.NBC, s.NINT, norm, null_pars)
        rec = data.record
        self._generating = generating
        if generating:
            # STPNBL: the LP's solution with v = 0, q = 0 and the norm PAR(NPAR + m) = 0, a
            # solution of the extended BVP where two families cross: the LP's branch (v =
            # 0) and the null vectors (v, q) = c phi, PAR(NPAR + m) = c^2 |phi|^2, phi the
            # BVP's null vector at the fold in (u, PAR(ICP(2..m))). The generating run
            # follows the second: AUTO's STDRBV (IPERP = 1, as CNRLBV takes for ISW < 0)
            # borders the extended Jacobian by the LP's direction (phi, 0), whose one null
            # vector orthogonal to it is (0, phi). That direction is set here from phi
            # itself: the extended Jacobian's null space is two-dimensional at this point,
            # and its null vector from the reduced matrix (single shooting over [0, 1]) is
            # rounding where the profile is stiff (snh's connection of time 200: |J z| =
            # 4e-2 |J|). The null vector's norm then grows with the arclength from 0, as
            # AUTO's (int: PAR(NPAR) = 6.6e-3 after the generating run's five points); it
            # is no scaling of the locus's equations, but it weighs v in the arclength of
            # every later step of the locus.
            base = BoundaryValueProblem(StartData(data.problem, s.with_(ISW=1, ICP=s.ICP[:m]),
                                                  data.u, data.par, rec, "", data.unames))
            x0 = base._start[0]
            U = base.unpack(x0)[0]
            phi = base.fold_null_vector(x0)
            slot = dict(zip(base._order, range(base.n_u, base.n_x)))
            par[norm - 1] = 0.0
            for j in q_idx:
                par[j - 1] = 0.0
            d_u = phi[:base.n_u].reshape(-1, n)
            rec = SimpleNamespace(U=np.hstack([U, np.zeros_like(U)]), t=base.mesh.node_times(),
                                  ntst=base.mesh.ntst, ncol=base.mesh.ncol,
                                  udot=np.hstack([np.zeros_like(d_u), d_u]),
                                  rldot=[0.0] * (m + 1) + [float(phi[slot[i]])
                                                           for i, _ in null_pars],
                                  icp=list(self._free))
        self.ndm = n
        # AUTO's NPARI: the norm's PAR(NPAR + m) and the q's are internal (AUTO-07p
        # restarts read the user's NPAR as NPAR - NPARI).
        self.npari = m
        super().__init__(StartData(ext, s2, data.u, par, rec, data.kind, data.unames))

    def start(self):
        if not self._generating:
            return super().start()
        # The generating run's direction (0, phi), oriented by STDRBV's rule.
        x0, z = self._start[0], self._stored
        return x0, self.orient_stdrbv(z / math.sqrt(self.inner(z, z)), x0)


__all__ = ["BoundaryValueProblem", "BVPFoldLocus", "fold_problem"]
