"""Algebraic systems G(U, lambda) = 0 the engine continues, and their test functions.

* `EquilibriumSystem`: f(u, par) = 0 in one parameter (IPS = 0, 1; ISW = 1).
* `HopfSystem`: the Hopf locus in two parameters (ISW = 2 from an HB label),
  unknowns (x, v, kappa = omega^2, p2) and equations (AUTO.md section 3.3;
  Kuznetsov, Elements of Applied Bifurcation Theory, 3rd ed., eq 10.80)
      f(x) = 0,  (A^2 + kappa I) v = 0,  <v, v> - 1 = 0,  <A^T v_old - A v_old, v> = 0.
* `FoldSystem`: the fold locus (ISW = 2 from an LP label), unknowns (x, phi, p2):
      f(x) = 0,  A phi = 0,  <phi, phi> - 1 = 0.

Each system maps its unknowns to the user's state and parameters, and lists
its test functions as (AUTO type code, callable). Codes follow AUTO
(support.f90): LP 2, BP 1, HB 3, BT -1, CP -2, ZH -3, GH -32 on Hopf curves.
"""
from __future__ import annotations

import numpy as np

from washer.cont.problem import Problem

#: |Im lambda| below this counts as a real eigenvalue (AUTO's HB test needs Im != 0).
IMAG_TOL = 1e-8
#: Finite-difference steps for second and third derivatives of f (normal forms,
#: CP): about eps^(1/4) and eps^(1/5), balancing truncation and rounding errors.
FD2_STEP = 1e-3
FD3_STEP = 4e-3
#: Forward-difference step (relative) for derivatives of f_x in the Hopf-curve Jacobian.
HESS_STEP = 1e-7


def eigenvalues_sorted(A: np.ndarray) -> np.ndarray:
    lam = np.linalg.eigvals(A)
    return lam[np.argsort(-lam.real, kind="stable")]


def hopf_test(lam: np.ndarray) -> float | None:
    """Re of the complex eigenvalue closest to the imaginary axis (None if all real)."""
    cplx = lam[np.abs(lam.imag) > IMAG_TOL]
    if cplx.size == 0:
        return None
    return float(cplx[np.argmin(np.abs(cplx.real))].real)


def n_stable(lam: np.ndarray) -> int:
    return int(np.sum(lam.real <= 0.0))


class EquilibriumSystem:
    """f(u, par) = 0 with unknowns U = u and lambda = PAR(icp[0])."""
    curve_type = 0

    def __init__(self, problem: Problem, par: np.ndarray, icp: list[int], ips: int):
        self.problem, self.par, self.icp, self.ips = problem, par.copy(), icp, ips
        self.n = problem.ndim

    # unknowns <-> user data
    def state(self, U) -> np.ndarray:
        return U[:self.n]

    def params_at(self, U, lam) -> np.ndarray:
        p = self.par.copy()
        p[self.icp[0] - 1] = lam
        return p

    def secondary(self, U) -> list[float]:
        return []

    def residual(self, U, lam) -> np.ndarray:
        return self.problem.func(U, self.params_at(U, lam))

    def jacobian(self, U, lam) -> np.ndarray:
        """[G_U, G_lambda], shape (N, N + 1)."""
        p = self.params_at(U, lam)
        return np.hstack([self.problem.dfdu(U, p), self.problem.dfdp(U, p, [self.icp[0]])])

    def after_step(self, U, lam) -> None:
        """Hook after every converged point (phase conditions are updated here)."""

    def eigen(self, U, lam) -> np.ndarray:
        x = U[:self.n]
        return eigenvalues_sorted(self.problem.dfdu(x, self.params_at(U, lam)))

    def period(self, U, lam, lam_eig) -> float | None:
        """PAR(11): 2 pi / |Im| of the pair closest to the imaginary axis."""
        cplx = lam_eig[np.abs(lam_eig.imag) > IMAG_TOL]
        if cplx.size == 0:
            return None
        return float(2 * np.pi / abs(cplx[np.argmin(np.abs(cplx.real))].imag))

    def test_functions(self, ilp: int, isp: int) -> list[tuple[int, str]]:
        """(code, name) of the active tests; values come from `tests_at`."""
        out = []
        if ilp != 0:
            out.append((2, "LP"))
        if isp != 0:
            out.append((1, "BP"))
        if self.ips == 1 and isp not in (0, 3):
            out.append((3, "HB"))
        return out

    def tests_at(self, U, lam, tangent, augmented_J, lam_eig, names) -> dict[str, float | None]:
        vals = {}
        if "LP" in names:
            vals["LP"] = float(tangent[-1])
        if "BP" in names:
            sign, logdet = np.linalg.slogdet(np.vstack([augmented_J, tangent]))
            vals["BP"] = float(sign * np.exp(min(logdet, 700.0))) if sign != 0 else 0.0
        if "HB" in names:
            vals["HB"] = hopf_test(lam_eig)
        return vals


def _null_vectors(A: np.ndarray, k: int) -> np.ndarray:
    """k right singular vectors of the smallest singular values, shape (n, k)."""
    _, _, Vt = np.linalg.svd(A)
    return Vt[-k:].T


class HopfSystem(EquilibriumSystem):
    """Hopf locus: U = (x, v, kappa, p2), lambda = PAR(icp[0])."""
    curve_type = 3

    def __init__(self, problem, par, icp, U):
        """Start from extended unknowns U = (x, v, kappa, p2), e.g. a stored Hopf-curve point."""
        super().__init__(problem, par, icp, 1)
        n = self.n
        self.U0 = np.asarray(U, dtype=float).copy()
        self.v_old = self.U0[n:2 * n] / np.linalg.norm(self.U0[n:2 * n])

    @classmethod
    def at_hopf_point(cls, problem, par, icp, x0, omega2):
        """Start at an HB point x0 with omega^2: v spans the null space of A^2 + omega^2 I."""
        A = problem.dfdu(x0, par)
        v = _null_vectors(A @ A + omega2 * np.eye(len(x0)), 2)[:, 0]
        return cls(problem, par, icp, np.r_[x0, v / np.linalg.norm(v), omega2, par[icp[1] - 1]])

    def params_at(self, U, lam):
        p = self.par.copy()
        p[self.icp[0] - 1] = lam
        if len(U) > self.n:
            p[self.icp[1] - 1] = U[-1]
        return p

    def secondary(self, U):
        return [U[-1]]

    def residual(self, U, lam):
        n = self.n
        x, v, kappa = U[:n], U[n:2 * n], U[2 * n]
        p = self.params_at(U, lam)
        A = self.problem.dfdu(x, p)
        return np.r_[self.problem.func(x, p), A @ (A @ v) + kappa * v, v @ v - 1.0,
                     (A.T @ self.v_old - A @ self.v_old) @ v]

    def jacobian(self, U, lam):
        """[G_U, G_lambda] of the extended system, shape (2n+2, 2n+3).

        Blocks in v and kappa are exact; the f-rows use the problem's Jacobians;
        the derivatives of A = f_x along x, lambda and p2 (second derivatives
        of f, which problems do not supply) are forward differences of A at the
        n + 2 perturbed points, evaluated in one batched call when the problem
        offers one. AUTO differentiates its extended systems numerically too.
        """
        n = self.n
        x, v = U[:n], U[n:2 * n]
        kappa = U[2 * n]
        p = self.params_at(U, lam)
        i_lam, i_p2 = self.icp[0] - 1, self.icp[1] - 1
        A = self.problem.dfdu(x, p)
        fp = self.problem.dfdp(x, p, [self.icp[0], self.icp[1]])
        # Perturbed points: x + h e_j (j < n), then lambda + h, then p2 + h.
        steps = HESS_STEP * (1 + np.abs(np.r_[x, p[i_lam], p[i_p2]]))
        xs = np.repeat(x[None, :], n + 2, axis=0)
        ps = np.repeat(p[None, :], n + 2, axis=0)
        xs[np.arange(n), np.arange(n)] += steps[:n]
        ps[n, i_lam] += steps[n]
        ps[n + 1, i_p2] += steps[n + 1]
        dA = (self.problem.dfdu_many(xs, ps) - A) / steps[:, None, None]    # (n+2, n, n)
        Av, w = A @ v, A.T @ self.v_old - A @ self.v_old
        # d/ds (A^2 v) = A_s (A v) + A (A_s v) for each perturbation direction s.
        d_g = np.einsum("sij,j->is", dA, Av) + A @ np.einsum("sij,j->is", dA, v)
        d_phase = np.einsum("sji,j,i->s", dA, self.v_old, v) - np.einsum("sij,j,i->s", dA, self.v_old, v)
        J = np.zeros((2 * n + 2, 2 * n + 3))
        # Columns: x (0..n-1), v (n..2n-1), kappa (2n), p2 (2n+1), lambda (2n+2).
        cols_s = np.r_[np.arange(n), 2 * n + 2, 2 * n + 1]
        J[:n, :n] = A
        J[:n, 2 * n + 2] = fp[:, 0]
        J[:n, 2 * n + 1] = fp[:, 1]
        J[n:2 * n, cols_s] = d_g
        J[n:2 * n, n:2 * n] = A @ A + kappa * np.eye(n)
        J[n:2 * n, 2 * n] = v
        J[2 * n, n:2 * n] = 2 * v
        J[2 * n + 1, cols_s] = d_phase
        J[2 * n + 1, n:2 * n] = w
        return J

    def after_step(self, U, lam):
        v = U[self.n:2 * self.n]
        self.v_old = v / np.linalg.norm(v)

    def period(self, U, lam, lam_eig):
        kappa = U[2 * self.n]
        return float(2 * np.pi / np.sqrt(kappa)) if kappa > 0 else None

    def test_functions(self, ilp, isp):
        out = [(-1, "BT"), (-2, "GH"), (-3, "ZH")]
        if ilp != 0:
            out.append((2, "LP"))
        return out

    def tests_at(self, U, lam, tangent, augmented_J, lam_eig, names):
        n = self.n
        kappa = U[2 * n]
        vals = {"BT": float(kappa)}
        x, p = U[:n], self.params_at(U, lam)
        if "GH" in names:
            vals["GH"] = first_lyapunov(self.problem, x, p, np.sqrt(kappa)) if kappa > 0 else None
        if "ZH" in names:
            # Product of the eigenvalues other than the Hopf pair: changes sign
            # when a real eigenvalue crosses zero.
            if n > 2 and kappa > 0:
                k = np.argsort(np.abs(np.abs(lam_eig.imag) - np.sqrt(kappa)) + np.abs(lam_eig.real))
                rest = lam_eig[k[2:]]
                vals["ZH"] = float(np.prod(rest).real)
            else:
                vals["ZH"] = None
        if "LP" in names:
            vals["LP"] = float(tangent[-1])
        return vals


class FoldSystem(EquilibriumSystem):
    """Fold locus: U = (x, phi, p2), lambda = PAR(icp[0])."""
    curve_type = 2

    def __init__(self, problem, par, icp, U):
        """Start from extended unknowns U = (x, phi, p2), e.g. a stored fold-curve point."""
        super().__init__(problem, par, icp, 1)
        self.U0 = np.asarray(U, dtype=float).copy()
        self.w_prev = None

    @classmethod
    def at_fold_point(cls, problem, par, icp, x0):
        """Start at an LP point x0: phi spans the null space of A."""
        phi = _null_vectors(problem.dfdu(x0, par), 1)[:, 0]
        return cls(problem, par, icp, np.r_[x0, phi / np.linalg.norm(phi), par[icp[1] - 1]])

    params_at = HopfSystem.params_at
    secondary = HopfSystem.secondary

    def jacobian(self, U, lam):
        """Central differences of the extended residual; the f-rows use the
        problem's Jacobian through the residual."""
        N = len(U)
        J = np.empty((N, N + 1))
        X = np.r_[U, lam]
        for j in range(N + 1):
            h = 1e-6 * (1 + abs(X[j]))
            Xp, Xm = X.copy(), X.copy()
            Xp[j] += h
            Xm[j] -= h
            J[:, j] = (self.residual(Xp[:-1], Xp[-1]) - self.residual(Xm[:-1], Xm[-1])) / (2 * h)
        return J

    def residual(self, U, lam):
        n = self.n
        x, phi = U[:n], U[n:2 * n]
        p = self.params_at(U, lam)
        return np.r_[self.problem.func(x, p), self.problem.dfdu(x, p) @ phi, phi @ phi - 1.0]

    def period(self, U, lam, lam_eig):
        return None

    def test_functions(self, ilp, isp):
        return [(-2, "CP"), (-1, "BT")]

    def tests_at(self, U, lam, tangent, augmented_J, lam_eig, names):
        n = self.n
        x, phi = U[:n], U[n:2 * n]
        p = self.params_at(U, lam)
        A = self.problem.dfdu(x, p)
        w = _null_vectors(A.T, 1)[:, 0]
        # Keep the left null vector's orientation continuous along the curve.
        if self.w_prev is not None and w @ self.w_prev < 0:
            w = -w
        self.w_prev = w
        f = self.problem.func
        h = FD2_STEP
        fxx = (f(x + h * phi, p) - 2 * f(x, p) + f(x - h * phi, p)) / h**2
        return {"CP": float(w @ fxx), "BT": float(w @ phi)}


# ------------------------------------------------------------------ normal form

def _multilinear(problem, x, p):
    """B(a, b) and C(a, b, c) of f at x by central differences of f (real
    arguments), Richardson-extrapolated from steps h and 2h to O(h^4): the first
    Lyapunov coefficient is a small difference of such terms near a GH point."""
    f = problem.func
    hb, hc = FD2_STEP, FD3_STEP

    def B1(a, b, h):
        return (f(x + h * (a + b), p) - f(x + h * (a - b), p) - f(x - h * (a - b), p)
                + f(x - h * (a + b), p)) / (4 * h * h)

    def C1(a, b, c, h):
        s = 0.0
        for sa in (1, -1):
            for sb in (1, -1):
                for sc in (1, -1):
                    s = s + sa * sb * sc * f(x + h * (sa * a + sb * b + sc * c), p)
        return s / (8 * h**3)

    def B(a, b):
        return (4 * B1(a, b, hb) - B1(a, b, 2 * hb)) / 3

    def C(a, b, c):
        return (4 * C1(a, b, c, hc) - C1(a, b, c, 2 * hc)) / 3
    return B, C


def _complexify(form, nargs):
    """Extend a real multilinear form to complex arguments by multilinearity."""
    def g(*args):
        total = 0j
        for mask in range(2 ** nargs):
            parts, factor = [], 1 + 0j
            for k, a in enumerate(args):
                if mask >> k & 1:
                    parts.append(np.asarray(a).imag)
                    factor *= 1j
                else:
                    parts.append(np.asarray(a).real)
            if any(not np.any(q) for q in parts):
                continue
            total = total + factor * form(*parts)
        return total
    return g


def first_lyapunov(problem, x, p, omega) -> float:
    """First Lyapunov coefficient l1 at a Hopf point with frequency omega
    (Kuznetsov, 3rd ed., eq 3.20 / 10.2): negative means supercritical.

        l1 = Re[<p, C(q,q,qb)> - 2<p, B(q, A^-1 B(q,qb))> + <p, B(qb, (2 i w - A)^-1 B(q,q))>] / (2 w)
    with A q = i w q, A^T p = -i w p, <p, q> = 1 (<a, b> = conj(a) . b).
    """
    A = problem.dfdu(x, p)
    n = len(x)
    lam, V = np.linalg.eig(A)
    q = V[:, np.argmin(np.abs(lam - 1j * omega))]
    lamT, W = np.linalg.eig(A.T)
    pv = W[:, np.argmin(np.abs(lamT + 1j * omega))]
    q = q / np.linalg.norm(q)
    pv = pv / np.conj(np.conj(pv) @ q)
    Br, Cr = _multilinear(problem, x, p)
    B, C = _complexify(Br, 2), _complexify(Cr, 3)
    qb = np.conj(q)
    h11 = np.linalg.solve(A, B(q, qb))
    h20 = np.linalg.solve(2j * omega * np.eye(n) - A, B(q, q))
    val = np.conj(pv) @ (C(q, q, qb) - 2 * B(q, h11) + B(qb, h20))
    return float(val.real / (2 * omega))
