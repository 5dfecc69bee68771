"""Optimisation of periodic solutions (IPS = 15): AUTO's AUTOOP with FNPO, BCPS, ICPO and
STPNPO (optimization.f90), after Doedel, Keller and Kernevez's extended system.

The user's periodic orbits u' = T f(u, p) carry an objective, the time average of FOPT:

    PAR(10) = int_0^1 phi(u(t), p) dt                     (phi = FOPT, the user's scalar)

and the extended system adds the adjoint w (NDIM components more, NDIM' = 2 NDIM):

    u' = T f(u, p)
    w' = -T f_u(u, p)^T w + kappa T f(u_old, p) + gamma grad_u phi(u, p)
    W(0) = W(1)                                            (NBC' = 2 NDIM, BCPS)
    int (u - u_old) . T f(u_old) dt = 0                    (the phase)
    int (PAR(10) - phi(u, p)) dt = 0                       (the objective)
    int (|w|^2 + kappa^2 + gamma^2 - PAR(12)) dt = 0       (the adjoint's size)
    int (T f_p_k(u, p) . w - gamma d phi/d p_k) dt = PAR(20 + k)    for each ICP entry -(20+k)
                                                           (k = 11: f(u) . w instead of T f_p)

with kappa = PAR(13), gamma = PAR(14) (FFPO, FIPO). PAR(20 + k) is PAR(k)'s optimality
value: the derivative of the Lagrangian gamma PAR(10) - <w, u' - T f> along PAR(k);
where it vanishes for every free PAR(k) other than the principal one, PAR(10) is
stationary on the solution manifold of the user's equations. The free parameters are
ICP's positive entries then PAR(10), PAR(13), PAR(14) (NFPR = positive entries + 3);
ICP's negative entries -(20 + k) add the optimality conditions of PAR(k) with
PAR(20 + k) fixed (NINT' = NFPR - 1: one negative entry fewer than positive ones).

The use (the ops demo): from a periodic orbit of IPS = 2, the trivial branch w = 0,
kappa = gamma = PAR(12) = 0 is the user's family in PAR(ICP(1)) with PAR(10) its objective;
where PAR(10) is extremal along the family (the optimality conditions of the fixed
parameters hold with a nonzero adjoint) the extended system has a branch point (BP,
ISP = 2). ISW = -1 there switches to the branch of nonzero adjoints (PAR(12) > 0 grows),
and restarts from its points with more positive ICP entries continue the extremum in
more parameters, PAR(20 + k) showing how far PAR(k) is from optimal (a UZ at
PAR(20 + k) = 0 is an extremum in one more parameter).

Starts (AUTOOP): from a record of fewer than 6 free parameters (a periodic orbit of
IPS = 2) STPNPO: w = 0, PAR(10) = the orbit's objective, PAR(12..NPAR) = 0, direction
computed; from a record of this system STPNBV (its direction reused when the free
parameters agree, and ISW = -1 at its BP switches branches as for general BVPs).

Discretisation, BP test and switching, mesh adaptation and output are the general BVP's
(washer.cont.systems.general_bvp): the b-file shows the user's NDIM components (NDM)
and ICP's positive entries. The derivatives of phi and of f_p are central differences
of FOPT and f (AUTO: the user's when JAC = 1), the Newton matrix's second derivatives
differences of those with steps ~1e-4 relative (accurate to ~1e-8; AUTO differences
FFPO with steps 1e-7).
"""
from __future__ import annotations

import numpy as np

from washer.cont.problem import Problem
from washer.cont.settings import SettingsError
from washer.cont.system import StartData, register
from washer.cont.differences import par_points, quotient, step
from washer.cont.systems.bvp import H2, VectorField, stored_profile
from washer.cont.systems.general_bvp import BoundaryValueProblem

#: The free parameters AUTOOP appends to ICP's positive entries: the objective PAR(10)
#: and the multipliers kappa = PAR(13), gamma = PAR(14).
APPENDED = (10, 13, 14)


def _phase_field(problem: Problem, n: int) -> Problem:
    """The extended problem as the BVP base sees it: only its phase reference reads it,
    T f(u_old) on u's components (ICPO's UPOLD), nothing on w's (AUTO computes the
    whole FNPO there, but FIPO reads the first NDM components only)."""
    def func_batch(W, pars):
        W, pars = np.asarray(W, float), np.asarray(pars, float)
        f = problem.func_many(W[:, :n], pars)
        return np.hstack([pars[:, 10:11] * f, np.zeros_like(f)])

    def func(W, par):
        return func_batch(np.asarray(W, float)[None, :], np.asarray(par, float)[None, :])[0]

    return Problem(2 * n, func, func_batch=func_batch, name=problem.name, npar=problem.npar,
                   parnames=problem.parnames, unames=problem.unames)


@register(15, 1, "*")
@register(15, -1, "BP")
class PeriodicOptimisation(BoundaryValueProblem):
    """The extended BVP of the module docstring in W = (u, w), continued in NFPR = (ICP's
    positive entries) + 3 free parameters (periodicity with the fixed +-1 pattern)."""
    general_bc = False

    def __init__(self, data):
        s = data.settings
        user = data.problem
        n = s.NDIM
        rec = data.record
        if rec is None or np.ndim(rec.U) != 2 or len(rec.U) < 2:
            raise ValueError("optimisation of periodic solutions (IPS = 15) starts from a "
                             "stored periodic orbit: IRS = the label of a solution of an "
                             "IPS = 2 or IPS = 15 run")
        if not user.has_fopt:
            raise ValueError(f"IPS = 15 needs the objective FOPT of the equations "
                             f"'{user.name}' (AUTO's FOPT(NDIM,U,ICP,PAR,IJAC,FS,DFDU,DFDP), "
                             "or fopt(u, par) in NAME.py)")
        clash = sorted(set(s.ICP) & set(APPENDED))
        if clash:
            raise SettingsError(f"ICP = {list(s.ICP)}: with IPS = 15 PAR(10), PAR(13) and PAR(14) "
                             f"are the objective and the multipliers (free already), "
                             f"not continuation parameters (PAR({clash[0]}))", keys=("ICP",))
        self.user, self.ndm = user, n
        self.ufield = VectorField(user, n)
        self._free = list(s.ICP) + list(APPENDED)
        # The run's constants as AUTO redefines them (b-file header, column titles: ICP's
        # positive entries); the base continues all NFPR free parameters.
        s2 = s.with_(NDIM=2 * n, NBC=2 * n, NINT=len(self._free) - 1)
        self.run_settings = s2
        #: AUTO's b-file header lists the internal ICP(1..NFPR) as the active parameters.
        self.header_icp = list(self._free)
        par = np.zeros(max(s.NPAR, len(data.par)))
        par[:len(data.par)] = data.par
        mesh_r, U_r, _ = stored_profile(rec, n)
        if np.any(np.rint((U_r[-1] - U_r[0]) / (2 * np.pi)) != 0):
            # BCPS's rotations (NRTN) are not carried into the extended system here.
            raise ValueError("the stored orbit rotates (u(1) - u(0) is a nonzero multiple of "
                             "2 pi in some component): optimisation of rotating orbits is "
                             "not supported")
        if int(getattr(rec, "nfpr", 0) or 0) < 6:
            # STPNPO: the objective of the stored orbit on its own mesh, then PAR(12..NPAR)
            # = 0 (the adjoint's size, the multipliers and the optimality values); w = 0 (the
            # base widens the stored profile with zeros), no stored direction.
            par[9] = float(mesh_r.node_weights() @ user.fopt_many(U_r, par))
            par[11:] = 0.0
            rec = _without_direction(rec)
        super().__init__(StartData(_phase_field(user, n), s2.with_(ICP=tuple(self._free)),
                                   data.u, par, rec, data.kind, data.unames))

    # ------------------------------------------------------------------ the extended field
    def _grad_phi(self, U: np.ndarray, par: np.ndarray) -> np.ndarray:
        """grad_u phi at the rows of U (k, NDIM): FOPT's central differences
        (Problem.fopt_gradient, AUTO's FOPI)."""
        return self.user.fopt_gradient(U, par)[0]

    def _dphi_dp(self, U: np.ndarray, par: np.ndarray, index: int) -> np.ndarray:
        """d phi / d PAR(index) at the rows of U -> (k,), central differences."""
        return self.user.fopt_gradient(U, par, [index], with_u=False)[1][:, 0]

    def _adjoint(self, u, w, f_old, par) -> np.ndarray:
        """w' = -T f_u^T w + kappa T f(u_old) + gamma grad phi (FFPO), rows (k, NDIM)."""
        T, kappa, gamma = par[10], par[12], par[13]
        fu = self.ufield.fu(u, par)
        return (-T * np.einsum("kji,kj->ki", fu, w) + kappa * T * f_old
                + gamma * self._grad_phi(u, par))

    def _rhs(self, W, U_old, par) -> np.ndarray:
        """The extended right-hand side at the rows of W (k, 2 NDIM), u_old at the same
        points (k, NDIM) -> (k, 2 NDIM) (FFPO with UPOLD = T f(u_old) at the current PAR)."""
        n = self.ndm
        u, w = W[:, :n], W[:, n:]
        f_old = self.ufield.f(U_old, par)
        return np.hstack([par[10] * self.ufield.f(u, par), self._adjoint(u, w, f_old, par)])

    def _old_at_gauss(self) -> np.ndarray:
        return self.at_gauss(self.U_old[:, :self.ndm]).reshape(-1, self.ndm)

    # ------------------------------------------------------------------ the integrands
    def _ic_nodes(self, U, par) -> np.ndarray:
        """The NINT' integrands at every node, (n_nodes, NINT') (FIPO)."""
        n = self.ndm
        u, w = U[:, :n], U[:, n:]
        T, kappa, gamma = par[10], par[12], par[13]
        cols = [np.sum((u - self.U_old[:, :n]) * self.up_old[:, :n], axis=1),
                par[9] - self.user.fopt_many(u, par),
                kappa ** 2 + gamma ** 2 - par[11] + np.sum(w * w, axis=1)]
        for k in self.settings.OPT_ICP:
            if k == 11:
                g = np.sum(self.ufield.f(u, par) * w, axis=1)
            else:
                g = T * np.sum(self.ufield.fp(u, par, k) * w, axis=1)
            cols.append(g - gamma * self._dphi_dp(u, par, k) - par[19 + k])
        return np.column_stack(cols)

    def _ic_jacobian(self, U, par):
        """(d/dW (n_nodes...), d/d free parameters) of the integrands: central differences
        with steps H2 (1 + |.|) (the integrands hold first differences already)."""
        nn, nc = U.shape
        Ju = np.empty((self.nint, nn, nc))
        for l in range(nc):
            h = step(U[:, l], H2)
            Up, Um = U.copy(), U.copy()
            Up[:, l] += h
            Um[:, l] -= h
            Ju[:, :, l] = quotient(self._ic_nodes(Up, par), self._ic_nodes(Um, par),
                                   h[:, None]).T
        Jp = np.empty((self.nint, self.nfpr))
        for j, i in enumerate(self._order):
            h, pp, pm = par_points(par, i, H2)
            Jp[:, j] = self.w_node @ (self._ic_nodes(U, pp) - self._ic_nodes(U, pm)) / (2 * h)
        return Ju, Jp

    # ------------------------------------------------------------------ contract
    def residual(self, x):
        U, par = self.unpack(x)
        N, m = self.mesh.ntst, self.mesh.ncol
        G = self._rhs(self.at_gauss(U).reshape(-1, self.ndim), self._old_at_gauss(), par)
        ints = self.w_node @ self._ic_nodes(U, par)
        return self.coll.residual_general(U, G.reshape(N, m, self.ndim), ints)

    def jacobian(self, x):
        U, par = self.unpack(x)
        N, m, n, nc = self.mesh.ntst, self.mesh.ncol, self.ndm, self.ndim
        W = self.at_gauss(U).reshape(-1, nc)
        Uo = self._old_at_gauss()
        u, w = W[:, :n], W[:, n:]
        T = par[10]
        fu = self.ufield.fu(u, par)
        f_old = self.ufield.f(Uo, par)
        A = np.zeros((len(W), nc, nc))
        A[:, :n, :n] = T * fu
        A[:, n:, n:] = -T * np.transpose(fu, (0, 2, 1))
        # d(w')/du: f_u^T w and grad phi differenced along each u_l, all points at once.
        k = len(W)
        h = step(u, H2)                                                 # (k, n)
        E = np.eye(n)[None] * h[:, :, None]                             # (k, n, n)
        up = (u[:, None] + E).reshape(-1, n)
        um = (u[:, None] - E).reshape(-1, n)
        rep = lambda a: np.repeat(a, n, axis=0)
        d = (self._adjoint(up, rep(w), rep(f_old), par)
             - self._adjoint(um, rep(w), rep(f_old), par)).reshape(k, n, n)
        A[:, n:, :n] = np.transpose(d / (2 * h[:, :, None]), (0, 2, 1))
        blocks = self.coll.local_blocks(1.0, A.reshape(N, m, nc, nc))
        dF = np.empty((self.nfpr, N, m, nc))
        for j, i in enumerate(self._order):
            hp, pp, pm = par_points(par, i, H2)
            dF[j] = quotient(self._rhs(W, Uo, pp), self._rhs(W, Uo, pm), hp).reshape(N, m, nc)
        Ju, Jp = self._ic_jacobian(U, par)
        return self.coll.jacobian_general(blocks, dF, Ju, Jp)

    def n2(self) -> int:
        """AUTO's N2: MAX U(i) columns of the user's components beside ICP's positive
        entries (the b-file shows those only)."""
        nicp = len(self.run_settings.ICP)
        return 0 if nicp > 7 else max(0, min(self.ndm, 7 - nicp))

    def params(self, x):
        """PAR at x, with the user's PVLS applied (on the whole profile W, as AUTO's)."""
        U, par = self.unpack(x)
        return self.pvls_params(U, par, par[10], problem=self.user)


def _without_direction(rec):
    """A view of a record without its stored direction (STPNPO: NODIR = 1)."""
    from types import SimpleNamespace
    return SimpleNamespace(U=rec.U, t=getattr(rec, "t", None), ntst=rec.ntst, ncol=rec.ncol,
                           udot=None, rldot=[], icp=[])


__all__ = ["PeriodicOptimisation"]
