"""The locus of branch points of periodic orbits in two (ISW = 2) or three (ISW = 3)
parameters (IPS = 2 from a BP of cycles): AUTO's FNPBP / BCPBP / ICPBP (periodic.f90,
F. Dercole's formulation) on the collocation mesh.

A BP of cycles is where the Jacobian of the periodic-orbit BVP G(u, q1, q2) = 0 (u' = T
f(u, p), u(0) = u(1), the phase condition; free q1 = PAR(ICP(1)) and q2 = the period,
or ICP(2) when the period is fixed) loses rank: it has a left null vector, the adjoint
(phi(t), phi3) of the collocation, BC and phase rows. The extended BVP on [0, 1], unknown
profile W = (u, phi) of 2 NDIM components:

    u'   = T f(u, p) - b phi                          (18; b only ISW = 2)
    phi' = -T f_u(u, p)^T phi + phi3 u'_old            (13a)
    u(0) - u(1) + b phi(0) = 0,  phi(0) - phi(1) = 0
    int <u - u_old, u'_old> dt + b phi3 = 0            (5, 18)
    int <phi, -dG/dq1> dt = 0,  int <phi, -dG/dq2> dt = 0        (13b: dG/dq = T f_q,
                                                       or f for the period)
    int <phi, phi> dt + phi3^2 - a = 0                 (13c; a fixed)

with u'_old = T_old f(u_old) at the nodes (the phase condition's reference). The free
parameters, in AUTO's ICP order after INITPS (the record's ICP):
* ISW = 2 (non-generic: the BP persists in two parameters, e.g. by a symmetry; b, the
  unfolding, stays 0 along the locus): q1, q2, q3, b, phi3 with q3 the user's next
  parameter (ICP = [p1, p2, 11] gives q = (p1, 11, p2));
* ISW = 3 (generic: a BP of cycles is codimension two, so three parameters): q1, q2,
  q3, q4, phi3 and no b (ICP = [p1, p2, p3, 11] gives q = (p1, 11, p2, p3)).
phi3, a and b are PAR(NPAR+1..NPAR+3) (NPAR = max(user NPAR, 12)), written after PAR in
the s-record, as AUTO's NPARI internal parameters.

Unknowns x = (W flattened node-major, then the tail [q2, q3, b or q4, phi3, q1],
PAR(ICP(1)) last); b-file columns and the L2 norm are those of u.

Start (differs from AUTO, whose generating run ISW = -2 is a BVP of 4 NDIM components
(u, phi, and the two null vectors v, w with their own parameters q, r, c1, c2) started
from phi = 0): the adjoint (phi, phi3) is computed directly at the BP record: the
smallest right singular vector of the collocated adjoint equations (13a), its
periodicity and the two conditions (13b), one more equation than unknowns, exactly
consistent at the BP. The generating run (NMX = 5, ILP = ISP = 0, ISW = -2 or -3 as
AUTO's, written as a curve of type 6) then continues the extended system with q3 fixed
and the norm a free (non-generic form, b free, as AUTO's start for both ISW): Newton
puts the orbit on the exact BP and the steps only scale (phi, phi3) with a. It starts
at |(phi, phi3)| = |DS|, and AUTO's, started at phi = 0, grows |phi| by its steps, so
both end with a ~ (NMX |DS|)^2 (lcbp: AUTO 6.6e-7): phi, tiny, takes no part in the
steps of the locus. The script restarts the locus at the generating run's EP (ISW = 2
or 3 again; a record of this curve, kind 'BPC-curve').

Special points, base codes written with the tens digit 6: LP (65) where the locus folds
in PAR(ICP(1)) (ILP), BP (66) by the determinant of the reduced extended Jacobian
(`bvp.CollocationBVP.bp_function`, AUTO's FNBPBV; ISP >= 2).

Second derivatives in the Jacobian: f_uu^T phi and f_up^T phi are central differences of
the user's f_u with AUTO's step 1e-7 (1 + |u|) (as FNPBP differences its system), or, without
f_u (JAC = 0), mixed differences of f (steps ~ eps^(1/4), error ~ 1e-8); f_pq the latter
(`bvp.VectorField`).
"""
from __future__ import annotations

import math

import numpy as np

from washer.cont.codes import Code
from washer.cont.linalg import tall_null_vector
from washer.cont.settings import SettingsError
from washer.cont.system import Solution, register
from washer.cont.systems.bvp import H2, CycleLocus, VectorField, onto_mesh, stored_profile

#: How many internal parameters follow PAR(NPAR) in the record: phi3, a, b.
N_INTERNAL = 3


def rearranged(icp: list, generic: bool) -> list:
    """AUTO's INITPS for BP loci of cycles: the user's ICP -> the free parameters q
    (3 for ISW = 2, 4 for ISW = 3), the period second when ICP names 11 in the last
    needed place or gives one parameter fewer (variable period)."""
    need = 4 if generic else 3
    icp = list(icp)
    if len(icp) == need - 1 or (len(icp) >= need and icp[need - 1] == 11):
        q = [icp[0], 11] + icp[1:need - 1]
    else:
        q = icp[:need]
    if len(q) < need or len(set(q)) < need:
        what = "ICP = [p1, p2, p3, 11]" if generic else "ICP = [p1, p2, 11]"
        raise SettingsError(f"ISW = {3 if generic else 2} at a BP of cycles continues it in "
                         f"{need - 1} parameters and the period ({what}): ICP = {icp} "
                         "names too few", keys=("ICP",))
    return q


@register(2, 2, "BP")
@register(2, 2, "BPC-curve")
class CycleBranchPointLocus(CycleLocus):
    """The locus of BPs of cycles (FNPBP/BCPBP/ICPBP); see the module docstring."""
    curve_type = 6
    nint = 4
    general_bc = True

    def __init__(self, data):
        s = data.settings
        self.settings, self.problem = s, data.problem
        self.n = self.ndim = s.NDIM
        self.n_comp = 2 * s.NDIM
        self.generic = abs(s.ISW) == 3
        icp = list(s.ICP)
        self.q = rearranged(icp, self.generic)
        self.field = VectorField(self.problem, self.n)
        self.unames = dict(getattr(data, "unames", {}) or {})
        base = max(s.NPAR, 12, max(icp))
        self.i_phi3, self.i_a, self.i_b = base + 1, base + 2, base + 3
        self.par = np.zeros(base + N_INTERNAL)
        p = np.asarray(data.par, float)
        self.par[:min(len(p), len(self.par))] = p[:len(self.par)]
        rec = data.record
        if rec is None or np.ndim(rec.U) != 2 or len(rec.U) < 2:
            raise ValueError("the locus of BPs of cycles starts from a BP record of a "
                             "periodic branch (or a point of such a locus)")
        self._generating = data.kind != "BPC-curve"
        q1, q2, q3 = self.q[:3]
        if self._generating:
            self.xpar = [q2, self.i_a, self.i_b, self.i_phi3, q1]
            self.free = [q1, q2, self.i_a, self.i_b, self.i_phi3]
            self.run_settings = s.with_(NMX=5, ILP=0, ISP=0, ISW=-abs(s.ISW))
        elif self.generic:
            self.xpar = [q2, q3, self.q[3], self.i_phi3, q1]
            self.free = [q1, q2, q3, self.q[3], self.i_phi3]
        else:
            self.xpar = [q2, q3, self.i_b, self.i_phi3, q1]
            self.free = [q1, q2, q3, self.i_b, self.i_phi3]
        #: b (the unfolding of the non-generic case) in the equations
        self.with_b = self._generating or not self.generic
        if self._generating:
            self._from_bp(rec)
        else:
            self._from_curve(rec)

    # ------------------------------------------------------------------ set-up
    @property
    def npari(self) -> int:
        """AUTO's NPARI of the records: the internal parameters after PAR(1..NPAR)
        (NPAR = max(NPAR, 12)): phi3, a and b on the non-generic locus (ISW = 2), phi3
        and a on the generic one (ISW = 3, no b), as AUTO's records of these loci (3 and
        2). The generating run stores phi3, a, b too (3: AUTO's writes 9, the internals of
        its 4 NDIM generating system, which this start does not use)."""
        return 2 if (self.generic and not self._generating) else 3

    @property
    def header_npar(self) -> int:
        """NPAR as the b-file header and the s-records state it: PAR(1..NPAR) and the
        NPARI internal parameters (AUTO's 15 for ISW = 2, 14 for ISW = 3)."""
        return self.i_phi3 - 1 + self.npari

    def tail_weights(self) -> np.ndarray:
        internal = (self.i_phi3, self.i_a, self.i_b)
        return np.array([1.0 if i in internal else self.settings.theta_par(i)
                         for i in self.xpar])

    def _x(self, W):
        return np.r_[np.asarray(W, float).ravel(), [self.par[i - 1] for i in self.xpar]]

    def _from_bp(self, rec) -> None:
        s, n = self.settings, self.n
        mesh_r, U_r, _ = stored_profile(rec, n)
        mesh, (U,) = onto_mesh(mesh_r, [U_r], s.NTST, s.NCOL, n)
        self.set_mesh(mesh)
        self.set_phase_reference(U, self.par)
        self.set_rotations(U)
        for i in (self.i_phi3, self.i_a, self.i_b):
            self.par[i - 1] = 0.0
        x0 = self._x(np.c_[U, np.zeros_like(U)])
        phi, phi3 = self.adjoint(x0)
        size = abs(s.DS) / math.sqrt(self.coll.integral(np.sum(phi * phi, axis=1)) + phi3 ** 2)
        phi, phi3 = size * phi, size * phi3
        a = abs(s.DS) ** 2
        self.par[self.i_phi3 - 1], self.par[self.i_a - 1] = phi3, a
        x0 = self._x(np.c_[U, phi])
        # the generating curve's direction: (phi, phi3) scaled, a growing
        t = np.zeros_like(x0)
        t[:self.coll.n_u] = np.c_[np.zeros_like(U), phi].ravel()
        t[self.coll.n_u + self.xpar.index(self.i_phi3)] = phi3
        t[self.coll.n_u + self.xpar.index(self.i_a)] = 2 * a
        t *= math.copysign(1.0, s.DS) / math.sqrt(self.inner(t, t))
        self._start = (x0, t)

    def _from_curve(self, rec) -> None:
        """A restart at a point of this locus: W = (u, phi) (the first 2 NDIM components
        of the record: AUTO's generating run stores 4 NDIM), phi3, a, b after PAR; the
        stored direction reused when the free parameters are the same (STPNBV)."""
        s, n = self.settings, self.n
        mesh_r, W_r, Wd_r = stored_profile(rec, n, 2 * n)
        if W_r.shape[1] != 2 * n:
            raise ValueError(f"a point of a BP locus of cycles stores at least 2 NDIM = "
                             f"{2 * n} components, this record {W_r.shape[1]}")
        mesh, (W, Wd) = onto_mesh(mesh_r, [W_r, Wd_r], s.NTST, s.NCOL, n)
        self.set_mesh(mesh)
        self.set_phase_reference(W[:, :n], self.par)
        self.set_rotations(W[:, :n])
        x0 = self._x(W)
        t0 = None
        rl = list(rec.rldot or [])
        icp = list(rec.icp or [])
        if Wd is not None and len(rl) >= len(self.free) and icp[:len(self.free)] == self.free:
            d = dict(zip(self.free, rl))
            t = np.r_[Wd.ravel(), [d[i] for i in self.xpar]]
            nrm = math.sqrt(self.inner(t, t))
            t0 = t / nrm if nrm > 0 else None
        self._start = (x0, t0)

    def adjoint(self, x0: np.ndarray) -> tuple[np.ndarray, float]:
        """(phi (n_nodes, NDIM), phi3) at the orbit of x0: the smallest right singular
        vector of the collocated adjoint equations (13a), phi(0) = phi(1) and (13b) in
        the unknowns (phi, phi3), a linear system with one equation more than unknowns
        that has a null vector exactly at a BP of cycles (the left null vector of the
        orbit's Jacobian in (u, q1, q2))."""
        n, n2 = self.n, 2 * self.n
        J = self.jacobian(x0).tocsr()
        nc = self.coll.n_coll
        rows = np.r_[np.nonzero(np.arange(nc) % n2 >= n)[0], nc + n + np.arange(n),
                     nc + n2 + np.array([1, 2])]
        nu = self.coll.n_u
        cols = np.r_[np.nonzero(np.arange(nu) % n2 >= n)[0],
                     nu + self.xpar.index(self.i_phi3)]
        z = tall_null_vector(J[rows][:, cols])
        return z[:-1].reshape(-1, n), float(z[-1])

    # ------------------------------------------------------------------ helpers
    def unpack(self, x):
        """(W (n_nodes, 2 NDIM) view, PAR with phi3, a, b at PAR(NPAR+1..NPAR+3))."""
        W = self.coll.profile(x)
        par = self.par.copy()
        for i, val in zip(self.xpar, x[self.coll.n_u:]):
            par[i - 1] = val
        return W, par

    def _internal(self, par):
        b = par[self.i_b - 1] if self.with_b else 0.0
        return par[10], b, par[self.i_phi3 - 1], par[self.i_a - 1]

    def _dG(self, U, par, q):
        """dG/dq at the rows of U: f for the period, T f_q for a parameter (FNPS's DFDP)."""
        return self.field.f(U, par) if q == 11 else par[10] * self.field.fp(U, par, q)

    def _fpq(self, U, par, p, q):
        """d^2 f / dp dq at the rows of U (a mixed central difference of f)."""
        hp, hq = H2 * (1 + abs(par[p - 1])), H2 * (1 + abs(par[q - 1]))
        out = 0.0
        for sp_, sq_, w in ((1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)):
            pp = np.array(par, float)
            pp[p - 1] += sp_ * hp
            pp[q - 1] += sq_ * hq
            out = out + w * self.field.f(U, pp)
        return out / (4 * hp * hq)

    def _orth(self, U, Phi, par, q):
        """int <phi, -dG/dq> dt (13b) on the nodes."""
        return -self.coll.integral(np.sum(Phi * self._dG(U, par, q), axis=1))

    # ------------------------------------------------------------------ contract
    def _at_gauss(self, x):
        """What residual and jacobian read at an iterate x: (W (nodes, 2n), par, (T, b,
        phi3, a), u, phi and the previous point's u' at the Gauss points, each (k, n))."""
        W, par = self.unpack(x)
        n = self.n
        Wg = self.coll.at_gauss(W).reshape(-1, 2 * n)
        upg = self.coll.at_gauss(self.up_old).reshape(-1, n)
        return W, par, self._internal(par), Wg[:, :n], Wg[:, n:], upg

    def residual(self, x):
        n, N, m = self.n, self.mesh.ntst, self.mesh.ncol
        W, par, (T, b, phi3, a), ug, pg, upg = self._at_gauss(x)
        A = self.field.fu(ug, par)
        Fu = T * self.field.f(ug, par) - b * pg
        Fp = -T * np.einsum("kji,kj->ki", A, pg) + phi3 * upg
        F = np.concatenate([Fu, Fp], axis=1).reshape(N, m, 2 * n)
        U, Phi = W[:, :n], W[:, n:]
        w = self.coll.w_node
        ints = [w @ np.sum((U - self.U_old) * self.up_old, axis=1) + b * phi3,
                self._orth(U, Phi, par, self.q[0]), self._orth(U, Phi, par, self.q[1]),
                w @ np.sum(Phi * Phi, axis=1) + phi3 ** 2 - a]
        off = self.bc_offset()
        bc = np.r_[W[0, :n] - W[-1, :n] + b * W[0, n:] + (0 if off is None else off[:n]),
                   W[0, n:] - W[-1, n:]]
        return self.coll.residual_general(W, F, ints, bc)

    def jacobian(self, x):
        n, N, m = self.n, self.mesh.ntst, self.mesh.ncol
        W, par, (T, b, phi3, a), ug, pg, upg = self._at_gauss(x)
        fg, A = self.field.f(ug, par), self.field.fu(ug, par)
        k = len(ug)
        I = np.eye(n)
        D = np.zeros((k, 2 * n, 2 * n))
        D[:, :n, :n] = T * A
        D[:, :n, n:] = -b * I
        D[:, n:, :n] = -T * self.field.fuu_adjoint(ug, pg, par)
        D[:, n:, n:] = -T * np.transpose(A, (0, 2, 1))
        blocks = self.coll.local_blocks(1.0, D.reshape(N, m, 2 * n, 2 * n))
        npar = len(self.xpar)
        dF = np.zeros((npar, k, 2 * n))
        for j, i in enumerate(self.xpar):
            if i == 11:
                dF[j] = np.c_[fg, -np.einsum("kji,kj->ki", A, pg)]
            elif i == self.i_b:
                dF[j, :, :n] = -pg
            elif i == self.i_phi3:
                dF[j, :, n:] = upg
            elif i != self.i_a:
                dF[j] = np.c_[T * self.field.fp(ug, par, i),
                              -T * self.field.fup_adjoint(ug, pg, par, i)]
        # integral conditions
        U, Phi = W[:, :n], W[:, n:]
        nn = len(U)
        int_u = np.zeros((4, nn, 2 * n))
        int_par = np.zeros((4, npar))
        int_u[0, :, :n] = self.up_old
        slot = {i: j for j, i in enumerate(self.xpar)}
        if self.with_b:
            int_par[0, slot[self.i_b]] = phi3
            int_par[0, slot[self.i_phi3]] = b
        An = None
        for r, q in ((1, self.q[0]), (2, self.q[1])):
            int_u[r, :, n:] = -self._dG(U, par, q)
            if q == 11:
                An = self.field.fu(U, par) if An is None else An
                int_u[r, :, :n] = -np.einsum("kji,kj->ki", An, Phi)
            else:
                int_u[r, :, :n] = -T * self.field.fup_adjoint(U, Phi, par, q)
            for j, i in enumerate(self.xpar):
                if i in (self.i_a, self.i_b, self.i_phi3):
                    continue
                if i == 11:
                    d = 0.0 if q == 11 else -self.coll.integral(
                        np.sum(Phi * self.field.fp(U, par, q), axis=1))
                elif q == 11:
                    d = -self.coll.integral(np.sum(Phi * self.field.fp(U, par, i), axis=1))
                else:
                    d = -T * self.coll.integral(np.sum(Phi * self._fpq(U, par, i, q), axis=1))
                int_par[r, j] = d
        int_u[3, :, n:] = 2 * Phi
        int_par[3, slot[self.i_phi3]] = 2 * phi3
        if self.i_a in slot:
            int_par[3, slot[self.i_a]] = -1.0
        # boundary conditions
        Z = np.zeros((n, n))
        B0 = np.block([[I, b * I], [Z, I]])
        B1 = np.block([[-I, Z], [Z, -I]])
        Bp = np.zeros((2 * n, npar))
        if self.with_b:
            Bp[:n, slot[self.i_b]] = W[0, n:]
        return self.coll.jacobian_general(blocks, dF.reshape(npar, N, m, 2 * n), int_u,
                                          int_par, (B0, B1, Bp))

    def active_tests(self) -> list:
        s = getattr(self, "run_settings", self.settings)      # the generating run: none
        out = []
        if s.detects("LP"):
            out.append(int(Code.LPC))
        if s.detects("BP"):
            out.append(int(Code.BPC))
        return out

    def accept(self, code, prev, cur) -> bool:
        return True

    def update(self, x, tangent) -> None:
        W, par = self.unpack(x)
        self.set_phase_reference(W[:, :self.n], par)
        self.par = par

    def solution(self, x, tangent) -> Solution:
        """b-row columns of u; the record stores W = (u, phi) and PAR with phi3, a, b
        appended (AUTO's internal PAR(NPAR+1..NPAR+3); without b on the generic locus:
        `npari`)."""
        def rldot(t):
            d = dict(zip(self.xpar, t[self.coll.n_u:]))
            return [float(d[i]) for i in self.free]
        return self.bvp_solution(x, tangent, self.params(x)[:self.header_npar], rldot)

    def directions(self, x, tangent, code) -> list:
        return []
