"""The locus of folds of periodic orbits in two parameters (IPS = 2, ISW = 2 from an LP
of cycles): AUTO's FNPL / BCPL / ICPL (periodic.f90) on the collocation mesh.

Extended BVP on [0, 1], unknown profile W = (u, v) of 2 NDIM components:

    u' = T f(u, p)
    v' = T f_u(u, p) v + beta f(u, p)              (FFPL with ICP(2) = 11)
    W(0) = W(1)
    int <u - u_old, u'_old> dt = 0                   (phase, ICPS)
    int <v, u'_old> dt = 0                           (v is not the phase shift)
    int <v, v> dt + beta^2 - c = 0                   (normalisation, c fixed)

with u'_old = T_old f(u_old) at the nodes. beta is AUTO-07p 0.9.2's (its records of this
locus satisfy these equations with their PAR(NPAR-1) as stored; beta / T there would put a
record of either engine, read by the other, off the locus by the factor T). Four free
parameters (NFPR = 4): PAR(ICP(1)), the period PAR(11), the second parameter (the first
ICP entry after ICP(1) that is not 11) and beta (AUTO's PAR(NPAR-1), internal). Unknowns
x = (W flattened node-major, PAR(11), PAR(p2), beta, PAR(ICP(1))); b-file columns and the
L2 norm are those of u.

Start at the LP record (AUTO's INITPS with ITP = 5: ISW = -2, ICP(3) = NPAR + 2): a
generating run of NMX = 5 steps with the second parameter fixed and the normalisation c
free in its place (ILP = ISP = 0), from the LP record's stored direction (udot, T-dot,
PAR(ICP(1))-dot ~ 0): at a fold of cycles (udot, T-dot) is the null vector of the
periodic orbit's Jacobian in (u, T), so v = s udot, beta = s T-dot with s setting
int <v, v> + beta^2 = c = 1, and Newton (the iterator's corrector) refines it; the
steps only scale (v, beta) with c, so the orbit and the parameters stay at the fold.
Its end point (EP, a record of this curve) is where the script restarts the locus in
both directions (AUTO's plp and abcb demos: run(lpstart) and DS='-'). The second
derivatives (f_uu v, f_up v) are mixed central differences of f in one batched call
(steps ~ eps^(1/4), error ~ 1e-8).
"""
from __future__ import annotations

import math

import numpy as np

from washer.cont.codes import Code
from washer.cont.settings import SettingsError
from washer.cont.system import Solution, fold_test, register
from washer.cont.systems.bvp import CycleLocus, VectorField, onto_mesh, stored_profile

#: The normalisation constant c of int <v, v> + beta^2 = c.
NORM = 1.0


@register(2, 2, "LP")
@register(2, 2, "LPC-curve")
class CycleFoldLocus(CycleLocus):
    """The locus of folds of cycles (FNPL/BCPL/ICPL); see the module docstring."""
    curve_type = 5
    nint = 3
    _generating = False
    #: AUTO's NPARI: beta and c follow PAR(1..NPAR) in the record (AUTO-07p restarts
    #: read the user's NPAR as NPAR - NPARI, and beta, c after it).
    npari = 2

    def __init__(self, data):
        s = data.settings
        self.settings, self.problem = s, data.problem
        self.n = self.ndim = s.NDIM
        self.n_comp = 2 * s.NDIM
        icp = list(s.ICP)
        others = [i for i in icp[1:] if i != 11]
        if not others:
            raise SettingsError("ISW = 2 at an LP of cycles continues the fold in two parameters: "
                                f"ICP = {icp} names only one (give e.g. ICP = [{icp[0]}, 2, 11])",
                                keys=("ICP",))
        self.p1, self.p2 = icp[0], others[0]
        self.free = [self.p1, 11, self.p2]
        self.field = VectorField(self.problem, self.n)
        self.unames = dict(getattr(data, "unames", {}) or {})
        self.par = np.zeros(max(s.NPAR, 11, max(icp)))
        p = np.asarray(data.par, float)
        self.par[:min(len(p), len(self.par))] = p[:len(self.par)]
        rec = data.record
        if data.kind == "LPC-curve":
            self._from_curve(rec)
            return
        if rec is None or np.ndim(rec.U) != 2 or rec.udot is None or len(rec.rldot) < 2:
            raise ValueError("the fold of cycles is continued from an LP record of a periodic "
                             "branch with its direction (IIS > 0)")
        self._generating = True
        self.c_index = len(self.par) + 2            # PAR(NPAR + 2) of the record
        self.free = [self.p1, 11, self.c_index]
        self.run_settings = s.with_(NMX=5, ILP=0, ISP=0, ISW=-2)
        self._from_lp(rec)

    # ------------------------------------------------------------------ set-up
    @property
    def header_npar(self) -> int:
        """NPAR as the b-file header states it: PAR(1..NPAR), beta and c."""
        return len(self.par) + self.npari

    @property
    def header_icp(self) -> list:
        """The header's active continuation parameters: the free ones and beta's index
        (AUTO's NFPR counts beta, which the record keeps after PAR(1..NPAR))."""
        return list(self.free) + [len(self.par) + 1]

    def tail_weights(self) -> np.ndarray:
        s = self.settings
        second = 1.0 if self._generating else s.theta_par(self.p2)       # c: THL 1
        return np.r_[s.theta_par(11), second, 1.0, s.theta_par(self.p1)]

    def _from_lp(self, rec) -> None:
        s, n = self.settings, self.n
        mesh_r, U_r, ud_r = stored_profile(rec, n)
        mesh, (U, V) = onto_mesh(mesh_r, [U_r, ud_r], s.NTST, s.NCOL, n)
        self.set_mesh(mesh)
        T = self.par[10]
        rl = dict(zip(list(rec.icp)[:2], rec.rldot[:2], strict=False))
        beta = rl.get(11, 0.0)
        scale = math.sqrt(NORM / (self.coll.integral(np.sum(V * V, axis=1)) + beta ** 2))
        V, beta = V * scale, beta * scale
        self.set_phase_reference(U, self.par)
        self.set_rotations(U)
        W = np.c_[U, V]
        slot = NORM if self._generating else self.par[self.p2 - 1]
        self._start = (np.r_[W.ravel(), T, slot, beta, self.par[self.p1 - 1]], None)

    def _from_curve(self, rec) -> None:
        """A restart at a point of this locus (its record stores W = (u, v) and, after
        PAR(1..NPAR), beta and c, as AUTO's PAR(NPAR-1), PAR(NPAR)): W on the run's mesh,
        v and beta rescaled to int <v, v> + beta^2 = 1; the stored direction reused when
        the free parameters are the same (STPNBV)."""
        s, n = self.settings, self.n
        mesh_r, W_r, Wd_r = stored_profile(rec, n, 2 * n)
        if W_r.shape[1] != 2 * n:
            raise ValueError(f"a point of a fold locus of cycles stores 2 NDIM = {2 * n} "
                             f"components, this record {W_r.shape[1]}")
        mesh, (W, Wd) = onto_mesh(mesh_r, [W_r, Wd_r], s.NTST, s.NCOL, n)
        self.set_mesh(mesh)
        beta = float(rec.par[-2])
        scale = math.sqrt(NORM / (self.coll.integral(np.sum(W[:, n:] ** 2, axis=1)) + beta ** 2))
        W[:, n:] *= scale
        beta *= scale
        self.set_phase_reference(W[:, :n], self.par)
        self.set_rotations(W[:, :n])
        x0 = np.r_[W.ravel(), self.par[10], self.par[self.p2 - 1], beta, self.par[self.p1 - 1]]
        t0 = None
        rl = list(rec.rldot or [])
        if Wd is not None and len(rl) >= 4 and list(rec.icp)[:3] == self.free:
            t = np.r_[Wd.ravel(), rl[1], rl[2], rl[3], rl[0]]
            nrm = math.sqrt(self.inner(t, t))
            t0 = t / nrm if nrm > 0 else None
        self._start = (x0, t0)

    # ------------------------------------------------------------------ helpers
    def unpack(self, x):
        """(u (n_nodes, NDIM), v (n_nodes, NDIM), PAR, beta)."""
        W = self.coll.profile(x)
        par = self.par.copy()
        par[10], par[self.p1 - 1] = x[-4], x[-1]
        if not self._generating:
            par[self.p2 - 1] = x[-3]
        return W[:, :self.n], W[:, self.n:], par, float(x[-2])

    def norm_constant(self, x) -> float:
        """c of int <v, v> + beta^2 = c: an unknown (in the second parameter's slot) in
        the generating run, else NORM."""
        return float(x[-3]) if self._generating else NORM

    # ------------------------------------------------------------------ contract
    def _at_gauss(self, x):
        """What the residual and the Jacobian both need: the unknowns unpacked, the
        mesh profile W, the period T, (u, v) at the Gauss points and f, f_u there."""
        u, v, par, beta = self.unpack(x)
        W = self.coll.profile(x)
        n = self.n
        Wg = self.coll.at_gauss(W).reshape(-1, 2 * n)
        ug, vg = Wg[:, :n], Wg[:, n:]
        return u, v, par, beta, W, par[10], ug, vg, self.field.f(ug, par), self.field.fu(ug, par)

    def residual(self, x):
        u, v, par, beta, W, T, ug, vg, fg, A = self._at_gauss(x)
        n, N, m = self.n, self.mesh.ntst, self.mesh.ncol
        Fu = T * fg
        Fv = T * np.einsum("kij,kj->ki", A, vg) + beta * fg
        F = np.concatenate([Fu, Fv], axis=1).reshape(N, m, 2 * n)
        w = self.coll.w_node
        ints = [w @ np.sum((u - self.U_old) * self.up_old, axis=1),
                w @ np.sum(v * self.up_old, axis=1),
                w @ np.sum(v * v, axis=1) + beta ** 2 - self.norm_constant(x)]
        off = self.bc_offset()
        return self.coll.residual_general(W, F, ints, None if off is None else W[0] - W[-1] + off)

    def jacobian(self, x):
        u, v, par, beta, W, T, ug, vg, fg, A = self._at_gauss(x)
        n, N, m = self.n, self.mesh.ntst, self.mesh.ncol
        Buv = self.field.fuu_v(ug, vg, par)                                # f_uu v
        k = len(ug)
        D = np.zeros((k, 2 * n, 2 * n))
        D[:, :n, :n] = T * A
        D[:, n:, :n] = T * Buv + beta * A
        D[:, n:, n:] = T * A
        blocks = self.coll.local_blocks(1.0, D.reshape(N, m, 2 * n, 2 * n))
        Av = np.einsum("kij,kj->ki", A, vg)
        dF = np.zeros((4, k, 2 * n))
        dF[0] = np.c_[fg, Av]                                             # d/dT
        for slot, idx in ((1, self.p2), (3, self.p1)):
            if slot == 1 and self._generating:
                continue                                                   # d/dc: integral only
            fp = self.field.fp(ug, par, idx)
            dF[slot] = np.c_[T * fp, T * self.field.fup_v(ug, vg, par, idx) + beta * fp]
        dF[2] = np.c_[np.zeros_like(fg), fg]                              # d/dbeta
        nn = len(u)
        int_u = np.zeros((3, nn, 2 * n))
        int_u[0, :, :n] = self.up_old
        int_u[1, :, n:] = self.up_old
        int_u[2, :, n:] = 2 * v
        int_par = np.zeros((3, 4))
        int_par[2, 2] = 2 * beta
        if self._generating:
            int_par[2, 1] = -1.0
        return self.coll.jacobian_general(blocks, dF.reshape(4, N, m, 2 * n), int_u, int_par)

    def orbit(self, x):
        u, v, par, beta = self.unpack(x)
        return u, par

    def active_tests(self) -> list:
        s = getattr(self, "run_settings", self.settings)      # the generating run: ILP = 0
        return [int(Code.LP)] if (s.ILP != 0 and "LP" not in s.SP_OFF) else []

    def test_functions(self, x, tangent, J, stability, factor, codes=None) -> dict:
        codes = self.active_tests() if codes is None else codes
        out = {}
        if Code.LP in codes:
            out[int(Code.LP)] = fold_test(tangent)
        return out

    def accept(self, code, prev, cur) -> bool:
        return True

    def update(self, x, tangent) -> None:
        u, v, par, beta = self.unpack(x)
        self.set_phase_reference(u, par)
        self.par = par

    def solution(self, x, tangent) -> Solution:
        """b-row columns of u; the record stores W = (u, v) and PAR with AUTO's NPARI = 2
        internal parameters (beta, c) appended."""
        beta = self.unpack(x)[3]
        return self.bvp_solution(
            x, tangent, np.r_[self.params(x), beta, self.norm_constant(x)],
            lambda t: [float(t[-1]), float(t[-4]), float(t[-3]), float(t[-2])])

    def directions(self, x, tangent, code) -> list:
        return []
