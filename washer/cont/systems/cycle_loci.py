"""Loci of period doublings and torus bifurcations of periodic orbits in two parameters
(IPS = 2, ISW = 2 from a PD or TR label): AUTO's FNPD / BCPD / ICPD and FNTR / BCTR /
ICTR (periodic.f90) on the collocation mesh.

Extended BVPs on [0, 1] (u the orbit, v and w the critical Floquet eigenfunction):

period doubling (NDIM -> 2 NDIM, NINT = 2; free PAR(ICP(1)), PAR(11), PAR(ICP(2))):
    u' = T f(u, p),  v' = T f_u(u, p) v
    u(0) - u(1) = 0,  v(0) + v(1) = 0                          (multiplier -1)
    int <u - u_old, u'_old> dt = 0,  int <v, v> dt - 1 = 0

torus (NDIM -> 3 NDIM, NINT = 3; free PAR(ICP(1)), PAR(11), PAR(12) = theta, PAR(ICP(2))):
    u' = T f,  v' = T f_u v,  w' = T f_u w
    u(0) - u(1) = 0
    v(1) - cos(theta) v(0) + sin(theta) w(0) = 0                (v + i w is multiplied
    w(1) - cos(theta) w(0) - sin(theta) v(0) = 0                 by exp(i theta) per period)
    int <u - u_old, u'_old> = 0,  int <v, w_old> - <w, v_old> = 0,  int <v, v> + <w, w> - 1 = 0

Unknowns x = (W (n_nodes, m NDIM) flattened node-major, PAR(11), [PAR(12),] PAR(ICP(2)),
PAR(ICP(1))), m = 2 or 3. The second derivatives f_uu v, f_up v in the Jacobian are
mixed central differences of f in batched calls (as the cycle-fold locus).

Start (differs from AUTO, which first runs an ISW = -2 generation of 5 steps from
v = 0 and needs a restart from its EP; the locus proper is the same system): directly
from the PD / TR record, the eigenfunction computed from the collocation's own
fundamental solution (collocation.fundamental_solution): v(t) = Phi(t) e with e the
eigenvector of the monodromy matrix Phi(1) for the multiplier closest to -1 (PD) or,
for TR, the one with Im > 0 closest to the unit circle (theta = its argument, which the
TR record stores as PAR(12)); normalised to int <v, v> (+ <w, w>) = 1, the norm AUTO
keeps fixed as PAR(NPAR) (written after PAR(NPAR) in the s-record, as the cycle fold's).

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
  test here, so each zero is located and typed by the factor that vanishes.
"""
from __future__ import annotations

import math

import numpy as np

from washer.auto.codes import Code
from washer.cont import collocation as col
from washer.cont.system import Solution, register
from washer.cont.systems.periodic import STABLE_TOL, SparseFactor, VectorField

#: Relative step of the mixed second differences (eps^(1/4)).
H2 = 1e-4
#: The fixed norm of the eigenfunction, int <v, v> (+ <w, w>) = NORM.
NORM = 1.0
#: The torus angles of the strong resonances: (base code, angle).
RESONANCES = ((int(Code.R1), 0.0), (int(Code.R4), math.pi / 2), (int(Code.R3), 2 * math.pi / 3),
              (int(Code.R2), math.pi))
#: AUTO's window for the 1:2 resonance on PD loci (FNSPBV): mu_2 within this of -1,
#: mu_3 real to sqrt(sqrt(EPSS)).
R2_WINDOW = 5e-2


def second_uu(field: VectorField, ug: np.ndarray, vg: np.ndarray, par: np.ndarray) -> np.ndarray:
    """f_uu[v] at the rows of ug (k, n): the matrices d/du (f_u v), shape (k, n, n), by
    mixed central differences of f, one batched call of 4 n k points."""
    k, n = ug.shape
    vmax = np.maximum(np.max(np.abs(vg), axis=1, keepdims=True), 1e-300)
    hk = H2 * (1 + np.max(np.abs(ug), axis=1, keepdims=True)) / vmax
    h = H2 * (1 + np.abs(ug))                                              # (k, n)
    E = np.eye(n)[None] * h[:, :, None]                                    # (k, n, n)
    kv = (hk * vg)[:, None, :]
    pts = np.concatenate([ug[:, None] + E + kv, ug[:, None] + E - kv,
                          ug[:, None] - E + kv, ug[:, None] - E - kv], axis=1)
    F = field.f(pts.reshape(-1, n), par).reshape(k, 4, n, n)
    d = (F[:, 0] - F[:, 1] - F[:, 2] + F[:, 3]) / (4 * h[:, :, None] * hk[:, :, None])
    return np.transpose(d, (0, 2, 1))                                      # [:, row, col]


def second_up(field: VectorField, ug: np.ndarray, vg: np.ndarray, par: np.ndarray,
              index: int) -> np.ndarray:
    """f_up[v] = d/dp (f_u v) for p = PAR(index) at the rows of ug, shape (k, n)."""
    vmax = np.maximum(np.max(np.abs(vg), axis=1, keepdims=True), 1e-300)
    hk = H2 * (1 + np.max(np.abs(ug), axis=1, keepdims=True)) / vmax
    hp = H2 * (1 + abs(par[index - 1]))
    out = []
    for sgn in (1, -1):
        pp = np.array(par, float)
        pp[index - 1] += sgn * hp
        out.append(field.f(ug + hk * vg, pp) - field.f(ug - hk * vg, pp))
    return (out[0] - out[1]) / (4 * hp * hk)


class _CycleLocus:
    """What the PD and TR loci share; subclasses set `copies` (m), `curve_type`, the
    angle slot and the boundary conditions."""
    arclength = "plane"
    copies = 2
    curve_type = 7
    has_theta = False

    def __init__(self, data):
        s = data.settings
        self.settings, self.problem = s, data.problem
        self.n = s.NDIM
        icp = list(s.ICP)
        others = [i for i in icp[1:] if i not in (11, 12)]
        name = "period doubling" if self.curve_type == 7 else "torus bifurcation"
        if not others:
            raise ValueError(f"ISW = 2 at a {name} continues it in two parameters: ICP = "
                             f"{icp} names only one (give e.g. ICP = [{icp[0]}, 2])")
        self.p1, self.p2 = icp[0], others[0]
        #: The free parameters in x's order after the profile (PAR(ICP(1)) last).
        self.xpar = [11] + ([12] if self.has_theta else []) + [self.p2, self.p1]
        self.free = [self.p1, self.p2, 11] + ([12] if self.has_theta else [])
        self.field = VectorField(self.problem, self.n)
        self.unames = dict(getattr(data, "unames", {}) or {})
        self.par = np.zeros(max(s.NPAR, 12, max(icp)))
        p = np.asarray(data.par, float)
        self.par[:min(len(p), len(self.par))] = p[:len(self.par)]
        rec = data.record
        if rec is None or np.ndim(rec.U) != 2 or len(rec.U) < 2:
            raise ValueError(f"the {name} locus starts from a {data.kind or 'special'} record "
                             "of a periodic branch")
        self._from_record(rec)

    # ------------------------------------------------------------------ set-up
    def _set_mesh(self, mesh: col.Mesh) -> None:
        m, n = self.copies, self.n
        self.mesh = mesh
        self.coll = col.Collocation(mesh, m * n, nint=m, general_bc=True)
        self.n_eq = self.coll.n_eq
        thu = self.settings.theta_u(n)
        s = self.settings
        self.weights = np.r_[np.kron(self.coll.w_node, np.r_[thu, np.ones((m - 1) * n)]),
                             [s.theta_par(i) for i in self.xpar]]

    def _from_record(self, rec) -> None:
        s, n = self.settings, self.n
        U_r = np.asarray(rec.U, float)[:, :n]
        mesh_r = col.Mesh(np.asarray(rec.t, float)[::rec.ncol].copy(), rec.ncol)
        if (rec.ntst, rec.ncol) == (s.NTST, s.NCOL):
            mesh, U = mesh_r, U_r.copy()
        else:
            mesh = col.Mesh(col.new_mesh(mesh_r, U_r, s.NTST), s.NCOL)
            U = col.interpolate(mesh_r, U_r, mesh.tm, s.NCOL)
        self._set_mesh(mesh)
        T = self.par[10]
        Phi = self.fundamental(U, self.par)
        mu, vec = np.linalg.eig(Phi[-1])
        V = self._eigenfunction(Phi, mu, vec)                  # (n_nodes, (m - 1) n)
        V *= math.sqrt(NORM / self.coll.integral(np.sum(V * V, axis=1)))
        self.U_old = U.copy()
        self.up_old = T * self.field.f(U, self.par)
        self.V_old = V.copy()
        W = np.c_[U, V]
        self._start = (np.r_[W.ravel(), [self.par[i - 1] for i in self.xpar]], None)

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
        ints = [w @ np.sum((u - self.U_old) * self.up_old, axis=1)] + self._integrals(W)
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
        for idx in (self.p2, self.p1):
            dF[slots[idx], :, :n] = T * self.field.fp(ug, par, idx)
        for cp in range(1, m):
            sl = slice(cp * n, (cp + 1) * n)
            vg = Wg[:, sl]
            D[:, sl, :n] = T * second_uu(self.field, ug, vg, par)
            D[:, sl, sl] = T * A
            dF[0, :, sl] = np.einsum("kij,kj->ki", A, vg)
            for idx in (self.p2, self.p1):
                dF[slots[idx], :, sl] = T * second_up(self.field, ug, vg, par, idx)
        blocks = self.coll.local_blocks(1.0, D.reshape(N, c, m * n, m * n))
        int_u = np.zeros((m, len(W), m * n))
        int_u[0, :, :n] = self.up_old
        self._integral_rows(W, int_u)
        return self.coll.jacobian_general(blocks, dF.reshape(len(self.xpar), N, c, m * n),
                                          int_u, np.zeros((m, len(self.xpar))),
                                          self._bc_jac(W[0], par))

    def factor(self, J, border):
        return SparseFactor(self.coll.bordered(J, np.asarray(border, float)))

    def inner(self, a, b) -> float:
        return float(np.dot(a, self.weights * b))

    def border(self, t):
        return self.weights * np.asarray(t, float)

    def params(self, x):
        W, par = self.unpack(x)
        if getattr(self.problem, "has_pvls", False):
            par = self.problem.pvls(W[:, :self.n], par)
        return par

    def start(self):
        return self._start

    def stability(self, x, J=None):
        """No stability on ISW = 2 curves (AUTO writes PT > 0 there)."""
        return None

    def active_tests(self) -> list:
        return [int(Code.LPC)] if self.settings.detects("LP") else []

    def _lp(self, tangent):
        return None if tangent is None else float(tangent[-1])

    def accept(self, code, prev, cur) -> bool:
        return True

    def update(self, x, tangent) -> None:
        W, par = self.unpack(x)
        n = self.n
        self.U_old = W[:, :n].copy()
        self.up_old = par[10] * self.field.f(self.U_old, par)
        self.V_old = W[:, n:].copy()
        self.par = par

    def wants_remesh(self, n_points: int) -> bool:
        iad = self.settings.IAD
        return iad > 0 and n_points % iad == 0

    def remesh(self, x, *vectors):
        """ADAPT on the orbit u (same NTST, NCOL); the eigenfunction is interpolated."""
        W = self.coll.profile(x)
        old = self.mesh
        tm = col.new_mesh(old, W[:, :self.n], old.ntst, periodic=True)
        npar = len(self.xpar)
        mn = self.copies * self.n

        def move(vec):
            vec = np.asarray(vec, float)
            Wv = vec[:self.coll.n_u].reshape(-1, mn)
            return np.r_[col.interpolate(old, Wv, tm, old.ncol).ravel(), vec[-npar:]]
        out = [move(x)] + [move(v) for v in vectors]
        self.U_old = col.interpolate(old, self.U_old, tm, old.ncol)
        self.up_old = col.interpolate(old, self.up_old, tm, old.ncol)
        self.V_old = col.interpolate(old, self.V_old, tm, old.ncol)
        self._set_mesh(col.Mesh(tm, old.ncol))
        return tuple(out)

    def column_titles(self) -> list:
        n2 = max(0, min(self.n, 7 - len(self.settings.ICP)))
        un = self.unames
        return ["L2-NORM"] + [f"MAX {un[i]}" if i in un else f"MAX U({i})"
                              for i in range(1, n2 + 1)]

    def solution(self, x, tangent) -> Solution:
        W, par = self.unpack(x)
        u = W[:, :self.n]
        w = self.coll.w_node
        thu = self.settings.theta_u(self.n)
        n2 = max(0, min(self.n, 7 - len(self.settings.ICP)))
        cols = [math.sqrt(w @ (u ** 2 @ thu))] + [float(np.max(u[:, i])) for i in range(n2)]
        udot = rldot = None
        if tangent is not None:
            udot = self.coll.profile(tangent).copy()
            t_par = dict(zip(self.xpar, tangent[self.coll.n_u:]))
            rldot = [float(t_par[i]) for i in self.free]
        return Solution(par=np.r_[self.params(x), NORM], columns=cols, u=W.copy(),
                        t=self.mesh.node_times(), udot=udot, rldot=rldot or [],
                        ntst=self.mesh.ntst, ncol=self.mesh.ncol, ndim_user=self.n)

    def directions(self, x, tangent, code) -> list:
        return []


@register(2, 2, "PD")
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
        return np.r_[W0[:n] - W1[:n], W0[n:] + W1[n:]]

    def _bc_jac(self, W0, par):
        n = self.n
        I = np.eye(n)
        Z = np.zeros((n, n))
        return (np.block([[I, Z], [Z, I]]), np.block([[-I, Z], [Z, I]]),
                np.zeros((2 * n, len(self.xpar))))

    def _integrals(self, W):
        v = W[:, self.n:]
        return [self.coll.w_node @ np.sum(v * v, axis=1) - NORM]

    def _integral_rows(self, W, int_u):
        int_u[1, :, self.n:] = 2 * W[:, self.n:]

    def active_tests(self) -> list:
        out = super().active_tests()
        if self.settings.detects("PD") and self.n > 2:
            out.append(int(Code.R2))
        return out

    def multipliers(self, x) -> np.ndarray:
        """The orbit's Floquet multipliers in FNSPBV's order on PD loci: the one nearest 1,
        the one nearest -1, then by distance from the unit circle."""
        W, par = self.unpack(x)
        mu = np.linalg.eigvals(self.fundamental(W[:, :self.n], par)[-1])
        i1 = int(np.argmin(np.abs(mu - 1)))
        rest = np.delete(mu, i1)
        i2 = int(np.argmin(np.abs(rest + 1)))
        others = np.delete(rest, i2)
        others = others[np.argsort(np.abs(np.abs(others) - 1), kind="stable")]
        return np.r_[mu[i1], rest[i2], others]

    def test_functions(self, x, tangent, J, stability, factor, codes=None) -> dict:
        codes = self.active_tests() if codes is None else [int(c) for c in codes]
        out = {}
        if Code.LPC in codes:
            out[int(Code.LPC)] = self._lp(tangent)
        if Code.R2 in codes:
            mu = self.multipliers(x)
            r2 = None
            if (abs(mu[2].imag) < math.sqrt(math.sqrt(self.settings.EPSS)) and mu[2].real < 0
                    and abs(mu[1] + 1) < R2_WINDOW):
                r2 = float(abs(mu[2]) - 1)
            out[int(Code.R2)] = r2
        return out

    def accept(self, code, prev, cur) -> bool:
        """R2 only where the stable count (multipliers with |mu| <= 1 + 1e-5, the one at
        -1 and the trivial one counted as AUTO does) changes (FNSPBV)."""
        if code != Code.R2:
            return True
        count = lambda p: int(np.sum(np.abs(self.multipliers(p.x)) <= 1 + STABLE_TOL))
        return count(prev) != count(cur)


@register(2, 2, "TR")
class TorusLocus(_CycleLocus):
    """The locus of torus bifurcations (FNTR/BCTR/ICTR); see the module docstring."""
    copies = 3
    curve_type = 8
    has_theta = True

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
        return np.r_[W0[:n] - W1[:n], v1 - c * v0 + s * w0, w1 - c * w0 - s * v0]

    def _bc_jac(self, W0, par):
        n = self.n
        c, s = math.cos(par[11]), math.sin(par[11])
        I, Z = np.eye(n), np.zeros((n, n))
        B0 = np.block([[I, Z, Z], [Z, -c * I, s * I], [Z, -s * I, -c * I]])
        B1 = np.block([[-I, Z, Z], [Z, I, Z], [Z, Z, I]])
        v0, w0 = W0[n:2 * n], W0[2 * n:]
        Bp = np.zeros((3 * n, len(self.xpar)))
        Bp[n:2 * n, 1] = s * v0 + c * w0                   # d/d theta (slot 1 of xpar)
        Bp[2 * n:, 1] = s * w0 - c * v0
        return B0, B1, Bp

    def _integrals(self, W):
        v, w = self._vw(W)
        vo, wo = self._vw_old()
        wn = self.coll.w_node
        return [wn @ np.sum(v * wo - w * vo, axis=1), wn @ np.sum(v * v + w * w, axis=1) - NORM]

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
        if self.settings.detects("TR") and self.n > 2:
            out += [code for code, _ in RESONANCES]
        return out

    def test_functions(self, x, tangent, J, stability, factor, codes=None) -> dict:
        codes = self.active_tests() if codes is None else [int(c) for c in codes]
        out = {}
        if Code.LPC in codes:
            out[int(Code.LPC)] = self._lp(tangent)
        theta = float(x[self.coll.n_u + 1])
        for code, angle in RESONANCES:
            if code in codes:
                out[code] = theta - angle
        return out
