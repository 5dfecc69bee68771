"""Pseudo-arclength continuation of algebraic systems, the way AUTO's ae.f90 does it.

One branch: predictor X + ds * Xdot; full-Newton corrector on G(X) = 0 plus the
spherical arclength condition |X - X_old|_theta^2 = ds^2; step control by the
Newton iteration count (ADPTDS); test functions after each converged point;
zeros located by regula falsi (Illinois) on the arclength from the previous
point; AUTO's stop rules (window, NMX, UZSTOP, STOP/SP counts, negative
ILP/ISP, MX). The engine knows only the `systems` interface and reports every
point to a `sink` (see washer.cont.driver); it does no file I/O itself.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from washer.cont.problem import ProblemError

#: AUTO perturbs DS, DSMAX by (1 + 1e-7) and DSMIN by 1 / (1 + 1e-7) (INIT1).
PERTURB = 1 + 1e-7
#: A Newton iterate farther than this multiple of the first correction diverges (SOLVAE).
DIVERGENCE_FACTOR = 20.0
#: Regula falsi trials stay this fraction of the bracket away from its ends.
LOCATE_GUARD = 1e-3
#: Location stops when the arclength bracket is this small relative to (1 + |DS|).
LOCATE_TOL = 1e-10
LOCATE_MAX_ITER = 60


class ConvergenceError(RuntimeError):
    pass


@dataclass
class Point:
    U: np.ndarray
    lam: float
    tangent: np.ndarray = None
    eig: np.ndarray = None
    tests: dict = field(default_factory=dict)

    @property
    def X(self) -> np.ndarray:
        return np.r_[self.U, self.lam]


@dataclass
class Settings:
    """The constants the engine uses, already resolved (indices, perturbed steps)."""
    ds: float
    dsmin: float
    dsmax: float
    itnw: int
    epsl: float
    epsu: float
    iads: int
    nmx: int
    npr: int
    ilp: int
    isp: int
    rl0: float
    rl1: float
    a0: float
    a1: float
    uz: list          # (par index, value, stop?)
    theta: np.ndarray  # weights of X in the arclength norm
    stop_counts: dict  # {'HB': 3, ...}: stop at the n-th point of a type


class Engine:
    def __init__(self, system, settings: Settings, sink):
        self.sys, self.s, self.sink = system, settings, sink

    # ------------------------------------------------------------------ Newton
    def correct(self, X_pred, X_ref, ds, hyperplane=None):
        """Newton on [G(X); constraint]. Sphere around X_ref of radius |ds|, or the
        hyperplane <X - X_ref - ds d, d> = 0 when `hyperplane` = d is given."""
        s, th = self.s, self.s.theta
        X = X_pred.copy()
        delref = None
        for it in range(1, s.itnw + 1):
            U, lam = X[:-1], X[-1]
            try:
                J = self.sys.jacobian(U, lam)
                G = self.sys.residual(U, lam)
            except ProblemError as exc:
                # A trial point outside the equations' domain (e.g. a negative
                # mass): a failed step, retried with a smaller one.
                raise ConvergenceError(f"equations failed at a Newton iterate ({exc})") from exc
            if not (np.all(np.isfinite(J)) and np.all(np.isfinite(G))):
                raise ConvergenceError("non-finite residual or Jacobian at a Newton iterate")
            if hyperplane is None:
                d = X - X_ref
                c = (th * d) @ d / abs(ds) - abs(ds)
                row = 2 * th * d / abs(ds)
            else:
                c = hyperplane @ (X - X_ref - ds * hyperplane)
                row = hyperplane
            M, rhs = np.vstack([J, row]), -np.r_[G, c]
            try:
                dX = np.linalg.solve(M, rhs)
            except np.linalg.LinAlgError:
                # Exactly at a branch point the Newton matrix is singular but the
                # system is consistent: take the least-squares (minimum-norm) step.
                dX = np.linalg.lstsq(M, rhs, rcond=None)[0]
            X = X + dX
            if not np.all(np.isfinite(X)):
                raise ConvergenceError("non-finite Newton iterate")
            du = np.max(np.abs(dX[:-1])) / (1 + np.max(np.abs(X[:-1])))
            dl = abs(dX[-1]) / (1 + abs(X[-1]))
            if dl <= s.epsl and du <= s.epsu:
                return X, it
            size = max(du, dl)
            if delref is None:
                delref = DIVERGENCE_FACTOR * max(size, 1e-30)
            elif size > delref:
                raise ConvergenceError("Newton iterates diverge")
        raise ConvergenceError(f"no convergence in ITNW = {s.itnw} iterations")

    def tangent(self, X, T_ref):
        """Unit null vector of [G_U G_lambda] at X, oriented like T_ref; also
        returns the augmented matrix used by the BP test."""
        J = self.sys.jacobian(X[:-1], X[-1])
        A = np.vstack([J, T_ref])
        e = np.zeros(len(X))
        e[-1] = 1.0
        try:
            z = np.linalg.solve(A, e)
        except np.linalg.LinAlgError:
            z = np.linalg.svd(J)[2][-1]        # singular exactly at a BP
        # Unit length in the arclength norm (THU/THL weights), as AUTO scales its
        # direction vector: a predictor X + ds T then lands on the sphere of radius ds.
        z /= np.sqrt(self.s.theta @ z**2)
        if z @ T_ref < 0:
            z = -z
        return z, J

    def evaluate(self, X, T_ref, names) -> Point:
        """A converged point with tangent, eigenvalues and test-function values."""
        T, J = self.tangent(X, T_ref)
        p = Point(X[:-1].copy(), float(X[-1]), T)
        p.eig = self.sys.eigen(p.U, p.lam)
        p.tests = self.sys.tests_at(p.U, p.lam, T, J, p.eig,
                                    [n for _, n in names if not n.startswith("UZ")])
        par = self.sys.params_at(p.U, p.lam)
        for k, (i, v, _) in enumerate(self.s.uz):
            p.tests[f"UZ{k}"] = float(par[i - 1] - v)
        return p

    # ---------------------------------------------------------------- location
    def locate(self, prev: Point, cur: Point, name: str, ds: float, names) -> tuple[Point, float]:
        """Zero of test `name` between prev and cur (at arclength ds from prev) by
        Illinois regula falsi on the arclength s from prev (each trial point is a
        continuation step). Returns the point and its arclength from prev."""
        a, fa = 0.0, prev.tests[name]
        b, fb = ds, cur.tests[name]
        best, s_best = cur, ds
        for _ in range(LOCATE_MAX_ITER):
            s_new = b - fb * (b - a) / (fb - fa)
            # Keep the trial strictly inside the bracket: a test that starts at a
            # located zero (value ~1e-300) would otherwise put it on prev (s = 0).
            lo, hi = min(a, b), max(a, b)
            s_new = min(max(s_new, lo + LOCATE_GUARD * (hi - lo)), hi - LOCATE_GUARD * (hi - lo))
            X, _ = self.correct(prev.X + s_new * prev.tangent, prev.X, s_new)
            pt = self.evaluate(X, prev.tangent, names)
            fc = pt.tests[name]
            best, s_best = pt, s_new
            if fc is None or fc == 0:
                break
            if np.sign(fc) == np.sign(fb):
                fa /= 2
            else:
                a, fa = b, fb
            b, fb = s_new, fc
            if abs(b - a) < LOCATE_TOL * (1 + abs(self.s.ds)):
                break
        return best, s_best

    def first_zero(self, prev: Point, cur: Point, ds: float, names):
        """The first zero of any test function between prev and cur: (point, code,
        name), or None. Linear estimates can misorder zeros that lie close
        together (a GH next to a UZ stop): after locating one, the interval up to
        it is searched again, so an earlier zero is never stepped over."""
        target, span, found = cur, ds, None
        for _ in range(len(names) + 1):       # each pass moves to a strictly earlier zero
            hits = [h for h in self.crossings(prev, target, names)
                    if found is None or h[2] != found[2]]
            if not hits:
                return found
            _, code, name = hits[0]
            sp, s_sp = self.locate(prev, target, name, span, names)
            found = (sp, code, name)
            target, span = sp, s_sp
        return found

    # -------------------------------------------------------------------- loop
    def crossings(self, prev: Point, cur: Point, names) -> list[tuple[float, int, str]]:
        """(estimated fraction of the step, code, name) of test functions that changed sign."""
        out = []
        for code, name in names:
            a, b = prev.tests.get(name), cur.tests.get(name)
            if a is None or b is None or not (a * b < 0):
                continue
            if name == "HB" and abs(stable_count(prev.eig) - stable_count(cur.eig)) < 2:
                continue          # a real eigenvalue pair, not a Hopf point (AUTO's rule)
            out.append((a / (a - b), code, name))
        return sorted(out)

    def run(self, X0, T0, names, switched: bool = False):
        """Continue one branch from X0 with direction T0; reports points to the sink.
        `switched`: X0 is a branch point and T0 the new branch's direction (MXBF).
        Returns the list of BP points met (for MXBF branch switching)."""
        s = self.s
        ds = s.ds
        bps = []
        start = self.evaluate(X0, T0, names)
        self.sink.start(start, switched=switched)
        current = start
        if switched:
            # First step of a switched branch: hyperplane orthogonal to the new direction.
            X, _ = self.correct(X0 + ds * T0, X0, ds, hyperplane=T0)
            current = self.evaluate(X, T0, names)
            self.sys.after_step(current.U, current.lam)
            if self.sink.regular(current, start):
                return bps
            current.tests = {}           # no detection on the first interval
        else:
            # AUTO's unwritten first step: it only provides a secant direction, and
            # the test functions start at zero, so nothing is detected up to PT 2.
            got = self._retrying_step(start, ds)
            if got is None:
                return bps
            X, _, ds = got
            current = self.evaluate(X, start.tangent, names)
            current.tests = {}
            self.sys.after_step(current.U, current.lam)
        counts: dict[str, int] = {}
        n_since_adapt = 0
        while True:
            got = self._retrying_step(current, ds)
            if got is None:
                return bps
            X, it, ds = got
            nxt = self.evaluate(X, current.tangent, names)
            hit = self.first_zero(current, nxt, ds, names)
            if hit is not None:
                sp, code, name = hit
                # Past the located zero the test keeps the sign it has beyond it.
                sp.tests[name] = 1e-300 * np.sign(nxt.tests[name])
                self.sys.after_step(sp.U, sp.lam)
                kind = "UZ" if name.startswith("UZ") else name
                counts[kind] = counts.get(kind, 0) + 1
                stop = self.sink.special(sp, current, code, name)
                if name == "BP":
                    bps.append(sp)
                stop = stop or self._stops(kind, name, counts)
                if stop:
                    return bps
                current = sp
                continue
            self.sys.after_step(nxt.U, nxt.lam)
            if self.sink.regular(nxt, current):
                return bps
            current = nxt
            n_since_adapt += 1
            if s.iads > 0 and n_since_adapt >= s.iads:
                ds = adapt_step(ds, it, s)
                n_since_adapt = 0

    def _step(self, p: Point, ds):
        return self.correct(p.X + ds * p.tangent, p.X, ds)

    def _retrying_step(self, p: Point, ds):
        """A step from p; on failure halve and retry until below DSMIN, then end
        the branch with MX (AUTO's STEPAE). Returns (X, iterations, ds) or None."""
        while True:
            try:
                X, it = self._step(p, ds)
                return X, it, ds
            except ConvergenceError as exc:
                ds /= 2
                self.sink.note(f"NOTE:Retrying step ({exc})")
                if abs(ds) < self.s.dsmin:
                    self.sink.failed(p, "No convergence with minimum step size")
                    return None

    def _stops(self, kind, name, counts) -> bool:
        s = self.s
        if name.startswith("UZ"):
            k = int(name[2:])
            return s.uz[k][2]
        if kind == "LP" and s.ilp < 0:
            return True
        if kind in ("BP", "HB") and s.isp < 0:
            return True
        if kind == "BT" and self.sys.curve_type == 3:
            return True               # AUTO always stops at BT on a Hopf curve
        n = s.stop_counts.get(kind)
        return n is not None and counts[kind] >= n


def stable_count(eig) -> int:
    return -1 if eig is None else int(np.sum(eig.real <= 0.0))


def adapt_step(ds: float, nit: int, s: Settings) -> float:
    """AUTO's ADPTDS: grow or shrink by the Newton iteration count, cap at DSMAX."""
    if nit <= 1:
        f = 2.0
    elif nit == 2:
        f = 1.5
    elif 3 <= nit <= s.itnw // 2:
        f = 1.1
    elif nit >= s.itnw:
        f = 0.5
    else:
        f = 1.0
    new = ds * f
    return float(np.sign(new) * min(abs(new), s.dsmax))
