"""The branch-point locus of a general BVP (IPS = 4, ISW = 2 or 3 from a BP label;
AUTO's FNBBP, BCBBP, ICBBP and STPNBBP in toolboxbv.f90, after F. Dercole's BPCONT).

The user's BVP: u' = f(u, p) (n = NDM components), NBC0 boundary conditions
b(u(0), u(1), p) = 0, NNT0 integral conditions int g(u, ...) dt = 0, continued in
NFPX = NBC0 + NNT0 - n + 1 parameters p_1..p_NFPX = PAR(ICP(1..NFPX)). A BP of that
branch is where the linearised operator (u, p) -> (u' - f_u u - f_p p, b_u0 u(0) +
b_u1 u(1) + b_p p, int g_u u + g_p p dt) loses rank: its adjoint has a solution
(w(t), psi = (psi_b (NBC0), psi_g (NNT0)), d (NFPX)):

    w' = -f_u^T w + g_u^T psi_g
    -w(0) + b_u0^T psi_b = 0,   w(1) + b_u1^T psi_b = 0,   d_i + b_pi^T psi_b = 0
    int (-d_i - f_pi . w + g_pi . psi_g) dt = 0                       (i = 1..NFPX)
    int |w|^2 dt + |psi|^2 - a = 0                                     (the scale)

(d splits each mixed condition into a boundary and an integral part, as AUTO does).
The continued BVP is (u, w), NDIM = 2n, NBC = NBC0 + 2n + NFPX, NINT = NNT0 + NFPX + 1,
with the user's conditions, ISW = 2 (non-generic: the unfolding b, free, enters as
u' = f - b w, b(..) + b psi_b, g + b psi_g, and stays 0 where the BP persists) or
ISW = 3 (generic: the third user parameter free instead of b). Free parameters:
PAR(ICP(1..NFPX + 1)), b or PAR(ICP(NFPX + 2)), psi, d; a is fixed.

Parameter layout, after the user's NPAR (AUTO-07p's, as its s-files store it):
psi = PAR(NPAR + 1 .. NPAR + K) (K = NBC0 + NNT0), a = PAR(NPAR + K + 1),
d = PAR(NPAR + K + 2 .. NPAR + K + 1 + NFPX), b = PAR(NPAR + K + NFPX + 2).

Start at the BP label: a generating run (AUTO's ISW = -2: NMX = 5, ILP = ISP = 0, a new
branch) that frees a instead of PAR(ICP(NFPX + 1)), which stays fixed: its solutions
are the BP with the adjoint scaled, u and p fixed, b = 0, a = |adjoint|^2. AUTO starts
it at the adjoint's zero in a 4n-component system holding both null vectors; here the
adjoint is computed directly (the null vector of the discretised adjoint equations at
the BP), scaled to a = DS^2 (zero is a singular point of the system), and grown along
that scaling. Restarting from the generating run's end (or any point of the locus)
continues the locus in the user's parameters with a fixed. A record of AUTO's
generating run (4n components (u, w, v1, v2)) restarts too: (u, w) are its first 2n.

Tests on the locus: LP (code 65) and BP (66), the BVP tests of the extended system.
Integral conditions g that read uold or upold are differentiated at uold = u,
upold = f(u) (the extended vector field does not see the previous solution).
"""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from washer.cont.differences import columns, par_points, quotient, step, u_points, u_quotient
from washer.cont.linalg import tall_null_vector
from washer.cont.problem import Problem
from washer.cont.settings import SettingsError
from washer.cont.system import StartData, register
from washer.cont.systems.general_bvp import BoundaryValueProblem

#: Relative step of the central differences of f, b and g inside the extended system
#: (f_u^T w, f_p . w, b_u^T psi, g_u^T psi): eps^(1/3), where truncation (~h^2, 4e-11)
#: and rounding (~eps / h, 2e-11) balance. (1e-4 would shift the locus by h^2 f'''/6 =
#: 1e-8 on u'' + p1 u + u^3 = 0; the Newton matrix's differences of these, step 1e-7,
#: see them as smooth to ~1e-4 relative, enough for Newton's convergence.)
DIR_STEP = 6e-6


class Layout:
    """Where the extended BVP's unknown parameters live (1-based PAR indices) and the
    sizes of the user's BVP."""

    def __init__(self, n: int, nbc0: int, nnt0: int, npar_user: int, icp: list):
        self.n, self.nbc0, self.nnt0 = n, nbc0, nnt0
        self.nfpx = nbc0 + nnt0 - n + 1
        k = nbc0 + nnt0
        # after every user parameter (NPAR, or an ICP entry beyond it)
        base = self.nuser = max([npar_user] + list(icp))
        self.psi = [base + i for i in range(1, k + 1)]
        self.a = base + k + 1
        self.d = [base + k + 1 + i for i in range(1, self.nfpx + 1)]
        self.b = base + k + self.nfpx + 2
        self.npar = self.b
        self.p = list(icp[:self.nfpx])            # the branch's own parameters p_i

    def free(self, icp: list, generic: bool, generating: bool) -> list:
        """The continued parameters in AUTO's ICP order."""
        m = self.nfpx
        user = list(icp[:m])
        second = self.a if generating else icp[m]
        third = icp[m + 1] if generic else self.b
        return user + [second, third] + self.psi + self.d


def branch_point_problem(problem, lay: Layout, generic: bool) -> Problem:
    """The extended BVP of the branch-point locus in W = (u, w) (module docstring) as a
    Problem of NDIM = 2n with its bcnd and icnd."""
    n, nbc0, nnt0, m = lay.n, lay.nbc0, lay.nnt0, lay.nfpx
    ipsi = np.array(lay.psi) - 1
    pidx = [i - 1 for i in lay.p]
    exact = problem._dfdu is not None and problem.jac != 0

    def fu(u, pars):
        """f_u at the rows of u, (k, n, n): the user's Jacobian where JAC allows, else
        central differences with steps DIR_STEP (1 + |u_l|)."""
        if exact:
            return problem.dfdu_many(u, pars)
        pts, h = u_points(u, DIR_STEP)                                   # h (k, n)
        pp = np.repeat(pars, 2 * n, axis=0)
        return u_quotient(problem.func_many(pts, pp), h)

    def fp_dot(u, w, pars):
        """f_pi . w at the rows, (k, NFPX), by central differences in p_i."""
        out = np.empty((len(u), m))
        for c, i in enumerate(pidx):
            h = step(pars[0, i], DIR_STEP)
            pp, pm = pars.copy(), pars.copy()
            pp[:, i] += h
            pm[:, i] -= h
            out[:, c] = np.sum((problem.func_many(u, pp) - problem.func_many(u, pm)) * w,
                               axis=1) / (2 * h)
        return out

    def g_refs(u, par):
        """The user's integrands' other arguments at the current point: uold = u,
        udot = 0, upold = f(u) (AUTO's FFBBP passes the previous point and udot = 0)."""
        return u, np.zeros_like(u), problem.func_many(u, par)

    def gu_psi(u, par):
        """sum_j psi_gj (g_j)_u at the rows, (k, n)."""
        psi_g = par[ipsi[nbc0:]]
        uo, ud, up = g_refs(u, par)
        out = np.zeros_like(u)
        for l in range(n):
            h = step(u[:, l], DIR_STEP)[:, None]
            E = np.zeros_like(u)
            E[:, l] = h[:, 0]
            G = quotient(problem.icnd_many(u + E, uo, ud, up, par, nnt0),
                         problem.icnd_many(u - E, uo, ud, up, par, nnt0), h)
            out[:, l] = G @ psi_g
        return out

    def func_batch(W, pars):
        W = np.asarray(W, float)
        pars = np.asarray(pars, float)
        u, w = W[:, :n], W[:, n:]
        f0 = problem.func_many(u, pars)
        if not generic:
            f0 = f0 - pars[:, lay.b - 1][:, None] * w
        wdot = -np.einsum("kji,kj->ki", fu(u, pars), w)
        if nnt0:
            wdot = wdot + gu_psi(u, pars[0])
        return np.hstack([f0, wdot])

    def func(W, par):
        return func_batch(np.asarray(W, float)[None, :], np.asarray(par, float)[None, :])[0]

    last_jb = {}

    def bcnd(W0, W1, par):
        u0, w0, u1, w1 = W0[:n], W0[n:], W1[:n], W1[n:]
        psi_b = par[ipsi[:nbc0]]
        b = problem.bcnd(u0, u1, par, nbc0)
        if not generic:
            b = b + par[lay.b - 1] * psi_b
        z = np.r_[u0, u1, par[pidx]]
        # b's Jacobian depends on (u(0), u(1), p) only: the Newton matrix's differences
        # in w, psi, d, b (most of its columns) reuse the last one.
        key = (z.tobytes(), par[:lay.nuser].tobytes())
        if last_jb.get("key") != key:
            def fb(zz):
                p = par.copy()
                p[pidx] = zz[2 * n:]
                return problem.bcnd(zz[:n], zz[n:2 * n], p, nbc0)
            last_jb["key"], last_jb["Jb"] = key, columns(fb, z, range(len(z)), DIR_STEP)
        Jb = last_jb["Jb"]                                      # (nbc0, 2n + NFPX)
        return np.r_[b, -w0 + Jb[:, :n].T @ psi_b, w1 + Jb[:, n:2 * n].T @ psi_b,
                     par[np.array(lay.d) - 1] + Jb[:, 2 * n:].T @ psi_b]

    def icnd(W, Wold, Wdot, Wpold, par):
        batch = np.ndim(W) == 2
        Wk, Wo, Wd, Wp = [np.asarray(a, float).T if batch else np.asarray(a, float)[None, :]
                          for a in (W, Wold, Wdot, Wpold)]
        u, w = Wk[:, :n], Wk[:, n:]
        pars = np.broadcast_to(np.asarray(par, float), (len(u), len(par))).copy()
        psi = par[ipsi]
        parts = []
        adj = -par[np.array(lay.d) - 1][None, :] - fp_dot(u, w, pars)
        if nnt0:
            g = problem.icnd_many(u, Wo[:, :n], Wd[:, :n], Wp[:, :n], par, nnt0)
            if not generic:
                g = g + par[lay.b - 1] * psi[nbc0:][None, :]
            parts.append(g)
            uo, ud, up = g_refs(u, par)
            for c, i in enumerate(pidx):
                h, pp, pm = par_points(par, i + 1, DIR_STEP)
                gp = quotient(problem.icnd_many(u, uo, ud, up, pp, nnt0),
                              problem.icnd_many(u, uo, ud, up, pm, nnt0), h)
                adj[:, c] += gp @ psi[nbc0:]
        parts.append(adj)
        parts.append((np.sum(w * w, axis=1) + psi @ psi - par[lay.a - 1])[:, None])
        out = np.hstack(parts)
        return out.T if batch else out[0]

    return Problem(2 * n, func, func_batch=func_batch, name=problem.name, npar=lay.npar,
                   pvls=problem._pvls, parnames=problem.parnames, unames=problem.unames,
                   jac=0, bcnd=bcnd, icnd=icnd)


@register(4, 2, "BP")
@register(4, 2, "BP-curve")
class BVPBranchPointLocus(BoundaryValueProblem):
    """The branch-point locus of a BVP (module docstring): a BoundaryValueProblem of
    `branch_point_problem` in W = (u, w)."""
    curve_type = 6

    def __init__(self, data):
        s = data.settings
        n = s.NDIM
        nfpx = s.NBC + s.NINT - n + 1
        generic = s.ISW == 3
        need = nfpx + (2 if generic else 1)
        if len(s.ICP) < need:
            raise SettingsError(f"ISW = {s.ISW} continues the branch points of a BVP with "
                             f"{nfpx} free parameter(s) in {need} parameters: ICP needs "
                             f"{need} entries, got {list(s.ICP)}", keys=("ICP",))
        if nfpx < 1:
            raise ValueError(f"NBC + NINT - NDIM + 1 = {nfpx}: expected at least 1")
        lay = self.layout = Layout(n, s.NBC, s.NINT, s.NPAR, s.ICP)
        generating = data.kind == "BP"
        self._free = lay.free(s.ICP, generic, generating)
        over = dict(NMX=5, ILP=0, ISP=0, ISW=-2) if generating else {}
        s2 = s.with_(NDIM=2 * n, NBC=s.NBC + 2 * n + nfpx, NINT=s.NINT + nfpx + 1,
                     NPAR=lay.npar, **over)
        self.run_settings = s2
        par = np.zeros(lay.npar)
        p = np.asarray(data.par, float)
        par[:min(len(p), lay.npar)] = p[:lay.npar]
        ext = branch_point_problem(data.problem, lay, generic)
        rec = data.record
        if generating:
            base = BoundaryValueProblem(StartData(data.problem, s.with_(ISW=1, ICP=s.ICP[:nfpx]),
                                                  data.u, data.par, rec, "", data.unames))
            U = base.unpack(base._start[0])[0]
            par[[i - 1 for i in lay.psi + [lay.a, lay.b] + lay.d]] = 0.0
            rec = SimpleNamespace(U=np.hstack([U, np.zeros_like(U)]), t=base.mesh.node_times(),
                                  ntst=base.mesh.ntst, ncol=base.mesh.ncol, udot=None,
                                  rldot=[], icp=[])
        self.ndm = n
        # AUTO's NPARI: the internal parameters after the user's NPAR (psi, a, d, b),
        # written in the s-records so that AUTO-07p restarts from them.
        self.npari = lay.npar - lay.nuser
        super().__init__(StartData(ext, s2, data.u, par, rec, data.kind, data.unames))
        self._generating = None
        if generating:
            self._generating = self._adjoint_start(abs(s.DS))

    def _adjoint_start(self, scale: float):
        """The generating run's start point and direction: the adjoint (w, psi, d), the
        null vector of the extended Jacobian's columns in those unknowns at the BP
        (w = 0: the rows of the adjoint equations), scaled so that
        int |w|^2 dt + |psi|^2 = a = scale^2; the direction grows that scale."""
        x0 = self._start[0].copy()
        J = self.jacobian(x0).tocsr()
        n, nn = self.ndm, self.mesh.n_nodes
        lay = self.layout
        slot = {i: self.n_u + k for k, i in enumerate(self._order)}
        cols_w = (np.arange(nn)[:, None] * 2 * n + n + np.arange(n)[None, :]).ravel()
        cols_p = np.array([slot[i] for i in lay.psi + lay.d])
        cols = np.r_[cols_w, cols_p]
        z = tall_null_vector(J[:, cols])
        W = z[:len(cols_w)].reshape(nn, n)
        psi = z[len(cols_w):len(cols_w) + len(lay.psi)]
        norm2 = float(self.w_node @ np.sum(W * W, axis=1) + psi @ psi)
        z = z * (scale / math.sqrt(norm2))
        big = np.argmax(np.abs(z[len(cols_w):])) + len(cols_w)
        if z[big] < 0:          # a sign: the largest of psi, d positive
            z = -z
        x0[cols] = z
        x0[slot[lay.a]] = scale ** 2
        t = np.zeros_like(x0)
        t[cols] = z
        t[slot[lay.a]] = 2 * scale ** 2
        return x0, t / math.sqrt(self.inner(t, t))

    def start(self):
        if self._generating is not None:
            return self._generating
        return super().start()


__all__ = ["BVPBranchPointLocus", "branch_point_problem", "Layout"]
