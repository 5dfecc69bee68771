"""Loci of period doublings and torus bifurcations of periodic orbits in two parameters
(IPS = 2, ISW = 2 from a PD or TR label): AUTO's FNPD / BCPD / ICPD and FNTR / BCTR /
ICTR (periodic.f90) on the collocation mesh.

Extended BVPs on [0, 1] (u the orbit, v and w the critical Floquet eigenfunction):

period doubling (NDIM -> 2 NDIM, NINT = 2; free PAR(ICP(1)), PAR(11), PAR(ICP(2))):
    u' = T f(u, p),  v' = T f_u(u, p) v
    u(0) - u(1) = 0,  v(0) + v(1) = 0                          (multiplier -1)
    int <u - u_old, u'_old> dt = 0,  int <v, v> dt - 1 = 0

torus (NDIM -> 3 NDIM, NINT = 3; free PAR(ICP(1)), PAR(11), PAR(12) = theta, PAR(ICP(2));
a restart at a point of the locus with four or more ICP entries frees ICP(1..4) as
given, as AUTO's INITPS: with a third parameter there, theta stays fixed):
    u' = T f,  v' = T f_u v,  w' = T f_u w
    u(0) - u(1) = 0
    v(1) - cos(theta) v(0) + sin(theta) w(0) = 0                (v + i w is multiplied
    w(1) - cos(theta) w(0) - sin(theta) v(0) = 0                 by exp(i theta) per period)
    int <u - u_old, u'_old> = 0,  int <v, w_old> - <w, v_old> = 0,  int <v, v> + <w, w> - 1 = 0

Unknowns x = (W (n_nodes, m NDIM) flattened node-major, PAR(11), [PAR(12),] PAR(ICP(2)),
PAR(ICP(1))), m = 2 or 3. The second derivatives f_uu v, f_up v in the Jacobian are
mixed central differences of f in batched calls (as the cycle-fold locus).

Start at the PD / TR record: the eigenfunction computed from the collocation's own
fundamental solution (collocation.fundamental_solution): v(t) = Phi(t) e with e the
eigenvector of the monodromy matrix Phi(1) for the multiplier closest to -1 (PD) or,
for TR, the one with Im > 0 closest to the unit circle (theta = its argument, which the
TR record stores as PAR(12)); normalised to int <v, v> (+ <w, w>) = 1. As AUTO's
(INITPS: ISW = -2, STPNPD / STPNTR with the norm PAR(NPAR) free), that run is a
generating run of NMX = 5 steps (ILP = ISP = 0) with the second parameter fixed and the
norm c of int <v, v> (+ <w, w>) = c free in its place: its direction scales the
eigenfunction (the orbit and the parameters stay at the bifurcation), and its end point
(EP, a record of this locus) is where the locus proper restarts (AUTO's pen and tor
demos: "generate starting data", then run(t)), with c fixed at NORM (written after
PAR(NPAR) in the s-record, as the cycle fold's).

Special points, base codes (written with the tens digit 7 or 8: 75, -76, -87, ...):
* LP (5): the locus folds with respect to PAR(ICP(1)) (ILP != 0): the tangent's
  PAR(ICP(1)) component.
* on a PD locus, R2 (-6), the 1:2 resonance: |mu_3| - 1 where mu_2 is the multiplier
  nearest -1 and mu_3 (the next, real negative) crosses the unit circle (FNSPBV's test
  on ITPST = 7, accepted only where the stable count changes).
* on a TR locus the strong resonances, where theta = PAR(12) passes 0 (R1, -5), pi/2
  (R4, -8), 2 pi/3 (R3, -7) and pi (R2, -6): AUTO's single test
  theta (theta - pi/2) (theta - 2 pi/3) (theta - pi), typed at the located point by
  the nearest of those angles, is the product of these four; each factor is its own
  test here, so each zero is located and typed by the factor that vanishes, and each
  goes on periodically past [0, pi] (floquet.torus_resonance_tests): theta continues
  through pi, where the locus turns back along itself in the parameters (R2 and the
  locus's fold are one point, typed R2: events.TORUS_FOLDS), and the resonances recur
  at 2 pi - a.
"""
from __future__ import annotations

import math

import numpy as np

from washer.cont.codes import Code
from washer.cont import collocation as col
from washer.cont import events
from washer.cont import floquet
from washer.cont.settings import SettingsError
from washer.cont.system import Solution, fold_test, register
from washer.cont.systems.bvp import CycleLocus, VectorField, onto_mesh, stored_profile

#: The fixed norm of the eigenfunction, int <v, v> (+ <w, w>) = NORM.
NORM = 1.0


class _CycleLocus(CycleLocus):
    """What the PD and TR loci share; subclasses set `copies` (m), `curve_type`, the
    angle slot and the boundary conditions."""
    copies = 2
    curve_type = 7
    #: AUTO's NPARI: the eigenfunction's norm follows PAR(1..NPAR) in the record.
    npari = 1

    @property
    def header_npar(self) -> int:
        """NPAR as the b-file header states it: PAR(1..NPAR) and the norm."""
        return len(self.par) + self.npari
    has_theta = False
    general_bc = True

    def __init__(self, data):
        s = data.settings
        self.settings, self.problem = s, data.problem
        self.n = self.ndim = s.NDIM
        self.n_comp = self.copies * s.NDIM
        self.nint = self.copies
        icp = list(s.ICP)
        others = [i for i in icp[1:] if i not in (11, 12)]
        name = "period doubling" if self.curve_type == 7 else "torus bifurcation"
        if not others:
            raise SettingsError(f"ISW = 2 at a {name} continues it in two parameters: ICP = "
                             f"{icp} names only one (give e.g. ICP = [{icp[0]}, 2])", keys=("ICP",))
        self.p1, self.p2 = icp[0], others[0]
        #: The free parameters in x's order after the profile (PAR(ICP(1)) last).
        self.xpar = [11] + ([12] if self.has_theta else []) + [self.p2, self.p1]
        self.free = [self.p1, self.p2, 11] + ([12] if self.has_theta else [])
        self.field = VectorField(self.problem, self.n)
        self.unames = dict(getattr(data, "unames", {}) or {})
        self.par = np.zeros(max(s.NPAR, 12 if self.has_theta else 11, max(icp)))
        p = np.asarray(data.par, float)
        self.par[:min(len(p), len(self.par))] = p[:len(self.par)]
        rec = data.record
        if rec is None or np.ndim(rec.U) != 2 or len(rec.U) < 2:
            raise ValueError(f"the {name} locus starts from a {data.kind or 'special'} record "
                             "of a periodic branch")
        self.p3 = None
        if self.has_theta and data.kind.endswith("-curve") and len(icp) >= 4 \
                and 12 not in icp[:4]:
            # AUTO's INITPS: a restart given NICP >= 4 frees ICP(1..4) as given, so a
            # third parameter takes the angle's place and the angle stays fixed (the
            # tor demo's "3-parameter branch fixing the angle").
            extra = [i for i in icp[:4] if i not in (self.p1, self.p2, 11)]
            if extra:
                self.p3 = extra[0]
                self.xpar = [self.p3 if i == 12 else i for i in self.xpar]
                self.free = [self.p3 if i == 12 else i for i in self.free]
        if data.kind.endswith("-curve"):
            self._from_curve(rec)
        else:
            # The generating run: the norm c (PAR(NPAR + 1) of the record) is free in
            # the second parameter's place.
            self._generating = True
            self.c_index = len(self.par) + 1
            self.xpar = [self.c_index if i == self.p2 else i for i in self.xpar]
            self.free = [self.c_index if i == self.p2 else i for i in self.free]
            self.run_settings = s.with_(NMX=5, ILP=0, ISP=0, ISW=-2)
            self._from_record(rec)

    # ------------------------------------------------------------------ set-up
    _generating = False

    def tail_weights(self) -> np.ndarray:
        # c of the generating run has AUTO's default weight THL = 1
        return np.array([1.0 if self._generating and i == self.c_index
                         else self.settings.theta_par(i) for i in self.xpar])

    def _par_value(self, i: int) -> float:
        """The start value of the unknown of slot i (c starts at NORM)."""
        return NORM if self._generating and i == self.c_index else self.par[i - 1]

    def norm_constant(self, x) -> float:
        """c of int <v, v> (+ <w, w>) = c: an unknown in the generating run, else NORM."""
        if self._generating:
            return float(x[self.coll.n_u + self.xpar.index(self.c_index)])
        return NORM

    def _from_record(self, rec) -> None:
        s, n = self.settings, self.n
        mesh_r, U_r, _ = stored_profile(rec, n)
        mesh, (U,) = onto_mesh(mesh_r, [U_r], s.NTST, s.NCOL, n)
        self.set_mesh(mesh)
        Phi = self.fundamental(U, self.par)
        mu, vec = np.linalg.eig(Phi[-1])
        V = self._eigenfunction(Phi, mu, vec)                  # (n_nodes, (m - 1) n)
        V *= math.sqrt(NORM / self.coll.integral(np.sum(V * V, axis=1)))
        self.set_phase_reference(U, self.par)
        self.set_rotations(U)
        self.V_old = V.copy()
        W = np.c_[U, V]
        self._start = (np.r_[W.ravel(), [self._par_value(i) for i in self.xpar]], None)

    def _from_curve(self, rec) -> None:
        """A restart at a point of this locus (its record stores W = (u, v[, w]) and the
        angle PAR(12) of a torus): W on the run's mesh, the eigenfunction rescaled to the
        norm NORM; the stored direction reused when the free parameters are the same."""
        s, n, m = self.settings, self.n, self.copies
        mesh_r, W_r, Wd_r = stored_profile(rec, n, m * n)
        if W_r.shape[1] != m * n:
            raise ValueError(f"a point of this locus stores {m} NDIM = {m * n} components, "
                             f"this record {W_r.shape[1]}")
        mesh, (W, Wd) = onto_mesh(mesh_r, [W_r, Wd_r], s.NTST, s.NCOL, n)
        self.set_mesh(mesh)
        W[:, n:] *= math.sqrt(NORM / self.coll.integral(np.sum(W[:, n:] ** 2, axis=1)))
        self.set_phase_reference(W[:, :n], self.par)
        self.set_rotations(W[:, :n])
        self.V_old = W[:, n:].copy()
        x0 = np.r_[W.ravel(), [self.par[i - 1] for i in self.xpar]]
        t0 = None
        rl = list(rec.rldot or [])
        if Wd is not None and len(rl) == len(self.free) and list(rec.icp) == self.free:
            d = dict(zip(self.free, rl))
            t = np.r_[Wd.ravel(), [d[i] for i in self.xpar]]
            nrm = math.sqrt(self.inner(t, t))
            t0 = t / nrm if nrm > 0 else None
        self._start = (x0, t0)

    def fundamental(self, U: np.ndarray, par: np.ndarray) -> np.ndarray:
        """Phi (n_nodes, n, n) of the variational equation along the orbit U (the u
        profile) at par: the collocation of v' = T f_u(u(t)) v on this mesh."""
        plain = col.Collocation(self.mesh, self.n)
        A = self.field.fu(plain.at_gauss(U).reshape(-1, self.n), par)
        N, m = self.mesh.ntst, self.mesh.ncol
        blocks = plain.local_blocks(par[10], A.reshape(N, m, self.n, self.n))
        return col.fundamental_solution(blocks, self.n)

    # ------------------------------------------------------------------ helpers
    def unpack(self, x):
        """(W (n_nodes, m n) view, full PAR)."""
        W = self.coll.profile(x)
        par = self.par.copy()
        for i, val in zip(self.xpar, x[self.coll.n_u:]):
            if i <= len(par):                  # (not c, PAR(NPAR + 1), of the generating run)
                par[i - 1] = val
        return W, par

    def _at_gauss(self, x):
        W, par = self.unpack(x)
        n, m = self.n, self.copies
        Wg = self.coll.at_gauss(W).reshape(-1, m * n)
        ug = Wg[:, :n]
        return W, par, Wg, ug, self.field.f(ug, par), self.field.fu(ug, par)

    def residual(self, x):
        W, par, Wg, ug, fg, A = self._at_gauss(x)
        n, m, N, c = self.n, self.copies, self.mesh.ntst, self.mesh.ncol
        T = par[10]
        parts = [T * fg] + [T * np.einsum("kij,kj->ki", A, Wg[:, k * n:(k + 1) * n])
                            for k in range(1, m)]
        F = np.concatenate(parts, axis=1).reshape(N, c, m * n)
        u = W[:, :n]
        w = self.coll.w_node
        ints = [w @ np.sum((u - self.U_old) * self.up_old, axis=1)] + \
            self._integrals(W, self.norm_constant(x))
        return self.coll.residual_general(W, F, ints, self._bc(W[0], W[-1], par))

    def jacobian(self, x):
        W, par, Wg, ug, fg, A = self._at_gauss(x)
        n, m, N, c = self.n, self.copies, self.mesh.ntst, self.mesh.ncol
        T = par[10]
        k = len(ug)
        D = np.zeros((k, m * n, m * n))
        D[:, :n, :n] = T * A
        dF = np.zeros((len(self.xpar), k, m * n))
        dF[0, :, :n] = fg                                              # d/dT
        slots = {i: j for j, i in enumerate(self.xpar)}
        # (d/dc of the generating run: the norm integral's -1 only)
        moved = ([self.p1] if self._generating else [self.p2, self.p1]) + \
            ([self.p3] if self.p3 is not None else [])
        for idx in moved:
            dF[slots[idx], :, :n] = T * self.field.fp(ug, par, idx)
        for cp in range(1, m):
            sl = slice(cp * n, (cp + 1) * n)
            vg = Wg[:, sl]
            D[:, sl, :n] = T * self.field.fuu_v(ug, vg, par)
            D[:, sl, sl] = T * A
            dF[0, :, sl] = np.einsum("kij,kj->ki", A, vg)
            for idx in moved:
                dF[slots[idx], :, sl] = T * self.field.fup_v(ug, vg, par, idx)
        blocks = self.coll.local_blocks(1.0, D.reshape(N, c, m * n, m * n))
        int_u = np.zeros((m, len(W), m * n))
        int_u[0, :, :n] = self.up_old
        self._integral_rows(W, int_u)
        int_par = np.zeros((m, len(self.xpar)))
        if self._generating:
            int_par[m - 1, slots[self.c_index]] = -1.0                 # the norm row's - c
        return self.coll.jacobian_general(blocks, dF.reshape(len(self.xpar), N, c, m * n),
                                          int_u, int_par, self._bc_jac(W[0], par))

    def active_tests(self) -> list:
        return [int(Code.LPC)] if self._run_settings().detects("LP") else []

    def _run_settings(self):
        """The constants the run goes by (the generating run's ILP = ISP = 0)."""
        return getattr(self, "run_settings", self.settings)

    def accept(self, code, prev, cur) -> bool:
        return True

    def update(self, x, tangent) -> None:
        W, par = self.unpack(x)
        self.set_phase_reference(W, par)
        self.V_old = W[:, self.n:].copy()
        self.par = par

    def remesh(self, x, *vectors):
        """ADAPT on the orbit u (the base), the eigenfunction reference moved too."""
        old = self.mesh
        out = super().remesh(x, *vectors)
        self.V_old = col.interpolate(old, self.V_old, self.mesh.tm, old.ncol)
        return out

    def solution(self, x, tangent) -> Solution:
        """b-row columns of u; the record stores W = (u, v[, w]) and PAR with the
        eigenfunction's norm appended (AUTO's internal PAR(NPAR), NPARI = 1)."""
        def rldot(t):
            t_par = dict(zip(self.xpar, t[self.coll.n_u:]))
            return [float(t_par[i]) for i in self.free]
        return self.bvp_solution(x, tangent, np.r_[self.params(x), self.norm_constant(x)],
                                 rldot)

    def directions(self, x, tangent, code) -> list:
        return []


@register(2, 2, "PD")
@register(2, 2, "PD-curve")
class PeriodDoublingLocus(_CycleLocus):
    """The locus of period doublings (FNPD/BCPD/ICPD); see the module docstring."""
    copies = 2
    curve_type = 7

    def _eigenfunction(self, Phi, mu, vec):
        i = int(np.argmin(np.abs(mu + 1)))
        if abs(mu[i] + 1) > 0.1 or abs(mu[i].imag) > 1e-6:
            raise ValueError(f"no Floquet multiplier near -1 at this PD point (nearest "
                             f"{mu[i]:.6g}): not a period doubling of this orbit")
        e = np.real(vec[:, i])
        return np.einsum("kij,j->ki", Phi, e)

    def _bc(self, W0, W1, par):
        n = self.n
        off = self.bc_offset()
        return np.r_[W0[:n] - W1[:n] + (0 if off is None else off[:n]), W0[n:] + W1[n:]]

    def _bc_jac(self, W0, par):
        n = self.n
        I = np.eye(n)
        Z = np.zeros((n, n))
        return (np.block([[I, Z], [Z, I]]), np.block([[-I, Z], [Z, I]]),
                np.zeros((2 * n, len(self.xpar))))

    def _integrals(self, W, c):
        v = W[:, self.n:]
        return [self.coll.w_node @ np.sum(v * v, axis=1) - c]

    def _integral_rows(self, W, int_u):
        int_u[1, :, self.n:] = 2 * W[:, self.n:]

    def active_tests(self) -> list:
        out = super().active_tests()
        if self._run_settings().detects("PD") and self.n > 2:
            out.append(int(Code.R2))
        return out

    def multipliers(self, x) -> np.ndarray:
        """The orbit's Floquet multipliers in FNSPBV's order on PD loci: the one nearest 1,
        the one nearest -1, then by distance from the unit circle."""
        W, par = self.unpack(x)
        return floquet.sort_on_pd_locus(
            np.linalg.eigvals(self.fundamental(W[:, :self.n], par)[-1]))

    def test_functions(self, x, tangent, J, stability, factor, codes=None) -> dict:
        codes = self.active_tests() if codes is None else [int(c) for c in codes]
        out = {}
        if Code.LPC in codes:
            out[int(Code.LPC)] = fold_test(tangent)
        if Code.R2 in codes:
            out[int(Code.R2)] = floquet.resonance_12_test(self.multipliers(x),
                                                          self.settings.EPSS)
        return out

    def accept(self, code, prev, cur) -> bool:
        """R2 only where the stable count (multipliers with |mu| <= 1 + 1e-5, the one at
        -1 and the trivial one counted as AUTO does) changes (FNSPBV)."""
        if code != Code.R2:
            return True
        return floquet.stable_count(self.multipliers(prev.x)) != \
            floquet.stable_count(self.multipliers(cur.x))


@register(2, 2, "TR")
@register(2, 2, "TR-curve")
class TorusLocus(_CycleLocus):
    """The locus of torus bifurcations (FNTR/BCTR/ICTR); see the module docstring."""
    copies = 3
    curve_type = 8
    has_theta = True

    def leaving_direction(self, x, direction, key, same=()):
        """The direction a point located on key leaves along, or None for the iterator's
        own (the secant of the step into it). At R1 and R2 (events.TORUS_FOLDS) where the
        locus folds (LP among `same`: the generic case, the pair splitting into real
        multipliers beyond) it turns back in every parameter and meets the PD locus
        (theta = pi) or the fold locus (theta = 0); the secant into the point carries the
        incoming parameters' motion, which there points along the locus it meets, and
        steps went onto that one. The torus locus goes on with the orbit, its period and
        the parameters stationary (they are even in theta - pi and in theta), theta moving
        on as the secant moves it: the direction is theta's alone, so that the step's
        arclength plane is theta = const, which the other locus (theta fixed) does not
        cross. (Where the pair only touches -1 or 1 and goes back, the locus does not
        fold, and the secant goes on along it.)"""
        if key not in events.TORUS_FOLDS.get(self.curve_type, ()) or 12 not in self.xpar \
                or not any(k in (Code.LP, Code.LPC) for k in same):
            return None
        slot = self.coll.n_u + self.xpar.index(12)
        d = np.zeros_like(direction, dtype=float)
        d[slot] = 1.0 if direction[slot] >= 0 else -1.0
        return d / math.sqrt(self.inner(d, d))

    def _eigenfunction(self, Phi, mu, vec):
        up = np.nonzero(mu.imag > 0)[0]
        if len(up) == 0:
            raise ValueError(f"no complex Floquet multiplier at this TR point (multipliers "
                             f"{np.round(mu, 6)}): not a torus bifurcation of this orbit")
        i = up[np.argmin(np.abs(np.abs(mu[up]) - 1))]
        self.par[11] = float(np.angle(mu[i]))                 # theta in (0, pi)
        z = np.einsum("kij,j->ki", Phi, vec[:, i])
        return np.c_[z.real, z.imag]

    def _vw(self, W):
        n = self.n
        return W[:, n:2 * n], W[:, 2 * n:]

    def _bc(self, W0, W1, par):
        n = self.n
        c, s = math.cos(par[11]), math.sin(par[11])
        v0, w0, v1, w1 = W0[n:2 * n], W0[2 * n:], W1[n:2 * n], W1[2 * n:]
        off = self.bc_offset()
        return np.r_[W0[:n] - W1[:n] + (0 if off is None else off[:n]), v1 - c * v0 + s * w0,
                     w1 - c * w0 - s * v0]

    def _bc_jac(self, W0, par):
        n = self.n
        c, s = math.cos(par[11]), math.sin(par[11])
        I, Z = np.eye(n), np.zeros((n, n))
        B0 = np.block([[I, Z, Z], [Z, -c * I, s * I], [Z, -s * I, -c * I]])
        B1 = np.block([[-I, Z, Z], [Z, I, Z], [Z, Z, I]])
        v0, w0 = W0[n:2 * n], W0[2 * n:]
        Bp = np.zeros((3 * n, len(self.xpar)))
        if 12 in self.xpar:                                 # (a fixed angle has no column)
            Bp[n:2 * n, 1] = s * v0 + c * w0               # d/d theta (slot 1 of xpar)
            Bp[2 * n:, 1] = s * w0 - c * v0
        return B0, B1, Bp

    def _integrals(self, W, c):
        v, w = self._vw(W)
        vo, wo = self._vw_old()
        wn = self.coll.w_node
        return [wn @ np.sum(v * wo - w * vo, axis=1), wn @ np.sum(v * v + w * w, axis=1) - c]

    def _integral_rows(self, W, int_u):
        n = self.n
        v, w = self._vw(W)
        vo, wo = self._vw_old()
        int_u[1, :, n:2 * n] = wo
        int_u[1, :, 2 * n:] = -vo
        int_u[2, :, n:2 * n] = 2 * v
        int_u[2, :, 2 * n:] = 2 * w

    def _vw_old(self):
        n = self.n
        return self.V_old[:, :n], self.V_old[:, n:]

    def active_tests(self) -> list:
        out = super().active_tests()
        if self._run_settings().detects("TR") and self.n > 2:
            out += [code for code, _ in floquet.RESONANCES]
        return out

    def test_functions(self, x, tangent, J, stability, factor, codes=None) -> dict:
        codes = self.active_tests() if codes is None else [int(c) for c in codes]
        out = {}
        if Code.LPC in codes:
            out[int(Code.LPC)] = fold_test(tangent)
        theta = float(x[self.coll.n_u + 1]) if 12 in self.xpar else float(self.par[11])
        out.update(floquet.torus_resonance_tests(theta, codes))
        return out
