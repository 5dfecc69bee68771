"""What the algebraic systems (equilibria, fold and Hopf loci) share: the
weighted norm, the sphere corrector, dense linear algebra, b-file columns,
branch-point directions and the BP/LP test functions (AUTO's ae.f90)."""
from __future__ import annotations

import math

import numpy as np

from washer.cont.codes import Code
from washer.cont.linalg import dense_factor, null_vectors, orient, unit_tangent
from washer.cont.record import ColumnTitle
from washer.cont.system import Solution, determinant_test, fold_test

#: Sums of up to this many terms numpy adds left to right (its pairwise summation
#: starts at 8): `inner` adds them in Python floats below it, the same result.
SEQUENTIAL_SUM = 7


class AlgebraicSystem:
    """Base of systems G(x) = 0 whose unknowns are a plain vector.

    Subclasses set `n_eq`, `free`, `theta` ((N + 1,) THU/THL weights), `ndim`,
    `par` (the fixed parameters) and implement residual and jacobian; `_p` (PAR at x)
    and `params` (PAR written, after PVLS) are a one-parameter system's by default.
    """
    arclength = "sphere"
    curve_type = 0
    freezes_second_derivatives = False

    def _one_parameter(self, start) -> None:
        """The set-up of systems with unknowns x = (u, PAR(ICP(1))): problem, settings,
        N = NDIM, the weights, the start point and a stored direction reused when the
        record has the same free parameter (AUTO)."""
        s = start.settings
        self.problem, self.settings = start.problem, s
        self.ndim = self.n_eq = start.problem.ndim
        self.par = np.array(start.par, dtype=float)
        self.free = [s.ICP[0]]
        self.unames = dict(start.unames)
        self.theta = np.r_[s.theta_u(self.ndim), s.theta_par(s.ICP[0])]
        u = np.asarray(start.u, dtype=float)[:self.ndim]
        self._x0 = np.r_[u, self.par[s.ICP[0] - 1]]
        self._t0 = None
        rec = start.record
        # STPNAE: the stored direction only where the record has the run's free
        # parameters (NFPR and ICP(1:NFPR) the same; a point of a two-parameter curve
        # restarted in one parameter gets a fresh one)
        if rec is not None and rec.udot is not None and len(rec.rldot) and \
                rec.nfpr == 1 and list(rec.icp[:1]) == self.free and \
                len(rec.udot) >= self.ndim:
            self._t0 = np.r_[np.asarray(rec.udot, float)[:self.ndim], rec.rldot[0]]

    def _p(self, x) -> np.ndarray:
        """PAR at x of a one-parameter system: the fixed parameters with PAR(ICP(1)) =
        x[-1] (systems with more free parameters place them themselves)."""
        p = self.par.copy()
        p[self.free[0] - 1] = x[-1]
        return p

    #: (x's bytes, PAR's bytes, PVLS's PAR) of the last point PVLS was called at (`params`)
    _pvls_memo = None

    def params(self, x) -> np.ndarray:
        """PAR written with the point x: `_p(x)` after the user's PVLS (AUTO calls it on
        every written point), which may set parameters from the solution u = x[:NDIM].
        PVLS once a point, as AUTO calls it: the UZ tests and the output row ask for the
        same x one after the other."""
        p = self._p(x)
        if self.problem.has_pvls:
            # the same bytes of x and PAR: the same call (bytes compare without making
            # NPAR Python floats)
            key, pl = x.tobytes(), p.tobytes()
            memo = self._pvls_memo
            if memo is not None and memo[0] == key and memo[1] == pl:
                return memo[2].copy()
            out = self.problem.pvls(x[:self.ndim], p)
            self._pvls_memo = (key, pl, out.copy())
            return out
        return p

    def restart_direction(self, t):
        """A stored direction the run restarts along (AUTO's CNRLAE: STPRAE with
        IPERP = -1 where |IPS| = 1 or IPS = 11): made unit and turned by STPRAE's sign
        rule (`orient`), DS's sign then choosing the way; kept as stored for IPS = 0.
        None stays None."""
        if t is None or abs(self.settings.IPS) != 1 and self.settings.IPS != 11:
            return t
        return self.orient(t / math.sqrt(self.inner(t, t)), self._x0)

    def orient(self, t, x):
        """AUTO's sign rule for a start direction t (unit in `inner`) at x (STPRAE;
        linalg.orient) with this run's NFPR = len(free), EPSL and EPSU."""
        s = self.settings
        return orient(t, x, len(self.free), s.EPSL, s.EPSU)

    # --------------------------------------------------------------- norms
    def inner(self, a, b) -> float:
        if type(a) is np.ndarray and type(b) is np.ndarray and len(a) <= SEQUENTIAL_SUM \
                and len(a) == len(b) == len(self.theta):
            # numpy's sum of up to 7 terms adds them left to right: the same float from
            # Python floats, without numpy's per-call overhead at these sizes
            terms = [t * u * v for t, u, v in zip(self.theta.tolist(), a.tolist(), b.tolist())]
            total = terms[0]
            for term in terms[1:]:
                total += term
            return total
        return float((self.theta * a * b).sum())

    def border(self, t) -> np.ndarray:
        return self.theta * t

    def factor(self, J, border):
        return dense_factor(J, border)

    def unit_tangent(self, J, ref, big: float):
        """linalg.unit_tangent with this system's border, factor and inner product (the
        weights theta): (t, factor, done) or None."""
        return unit_tangent(J, self.theta, ref, big)

    def update(self, x, tangent) -> None:
        """Nothing moves with the branch by default."""

    def located_code(self, key, point) -> int:
        """The base code a located zero of test `key` is written with: the key itself."""
        return key

    def info(self, x, code) -> dict:
        """No extra results by default."""
        return {}

    def wants_remesh(self, n_points: int) -> bool:
        """Algebraic systems have no mesh."""
        return False

    def remesh(self, x, *vectors) -> tuple:
        return (x,) + vectors

    # ------------------------------------------------------------- tests
    def active_tests(self) -> list:
        """LP and BP where the constants detect them (a system with more tests, or
        other ones, says so itself)."""
        return [code for name, code in (("LP", Code.LP), ("BP", Code.BP))
                if self.settings.detects(name)]

    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict:
        return self._lp_bp(tangent, factor, codes)

    def _lp_bp(self, tangent, factor, codes) -> dict:
        out = {}
        if Code.LP in codes:
            out[Code.LP] = fold_test(tangent)
        if Code.BP in codes:
            out[Code.BP] = determinant_test(factor)
        return out

    def accept(self, code, prev, cur) -> bool:
        return True

    def directions(self, x, tangent, code) -> list:
        """At a BP: the null direction of G_x orthogonal to the branch's tangent."""
        J = np.asarray(self.jacobian(x))
        V = null_vectors(J, 2)
        n1, n2 = V[:, 0], V[:, 1]
        # The null direction orthogonal to the branch's tangent in the run's own
        # (THL/THU-weighted) inner product.
        d = n1 * self.inner(n2, tangent) - n2 * self.inner(n1, tangent)
        nd = np.sqrt(self.inner(d, d))
        if not np.isfinite(nd) or nd < 1e-12:
            return []
        return [self.orient(d / nd, x)]

    # ------------------------------------------------------------- output
    def measure(self, x) -> float:
        """The b-file's second column by IPLT (ae.f90 STPLAE's AMP) on AUTO's U(1..NDIM)
        = x[:-1] (NDIM the system's own: extended on the loci): U(|IPLT|) for 1 <= |IPLT|
        <= NDIM, U(IPLT - NDIM) up to 2 NDIM, U(IPLT - 2 NDIM) up to 3 NDIM, else the L2
        norm of the user's U."""
        return _measure(x, self.settings.IPLT, self.ndim)

    def solution(self, x, tangent) -> Solution:
        return self._solution(x, tangent, x.tolist())

    def _solution(self, x, tangent, values: list) -> Solution:
        """`solution` with values = x.tolist() (the caller's)."""
        par = self.params(x)
        ncols = self.n_columns
        cols = [_measure(x, self.settings.IPLT, self.ndim, values)] + values[:ncols]  # (<= NDIM)
        m = len(self.free)
        rldot = tangent[-m:].tolist()[::-1] if m > 1 else [float(tangent[-1])]
        # (positional: par, columns, u, t, udot, rldot, ntst, ncol, ndim_user)
        return Solution(par, cols, x[:-1].copy(), None, tangent[:-1].copy(), rldot,
                        0, 0, self.ndim)

    def column_titles(self) -> list:
        un = self.unames
        return [self.measure_title()] + [un.get(i, f"U({i})")
                                         for i in range(1, self.n_columns + 1)]

    def measure_title(self) -> str:
        """HEADNG's title of the IPLT column (io.f90), by the user's NDIM (NDM) and
        unames: 'L2-NORM' for IPLT = 0 or beyond -NDM..3 NDM; else of U(k), k =
        MOD(|IPLT| - 1, NDM) + 1: its name at column 2 (or 'U(k)') for |IPLT| <= NDM,
        'INTEGRAL' and 'L2-NORM' with it above NDM and 2 NDM (the value is STPLAE's
        U(IPLT - NDIM), ...: AUTO titles it so)."""
        n, iplt = self.ndim, self.settings.IPLT
        if iplt == 0 or iplt < -n or iplt > 3 * n:
            return "L2-NORM"
        k = (abs(iplt) - 1) % n + 1
        name = self.unames.get(k)
        if abs(iplt) <= n:
            return ColumnTitle(name, 2) if name else f"U({k})"
        what = "INTEGRAL" if iplt <= 2 * n else "L2-NORM"
        return f"{what} {name}" if name else f"{what} U({k})"

    @property
    def n_columns(self) -> int:
        """AUTO's N2 = min(NDM, 7 - NICP): how many U(i) the b-file shows."""
        nicp = len(self.settings.ICP)
        return 0 if nicp > 7 else min(self.ndim, 7 - nicp)


def _measure(x, iplt: int, ndim: int, values: list | None = None) -> float:
    """AlgebraicSystem.measure of x by IPLT, the user's NDIM = ndim; values: x.tolist()
    where the caller has it."""
    nd = len(x) - 1
    if 0 < abs(iplt) <= nd:
        return float(x[abs(iplt) - 1])
    if nd < iplt <= 3 * nd:
        return float(x[(iplt - 1) % nd])
    if ndim <= SEQUENTIAL_SUM:
        # the same float as numpy's below (squares, a left-to-right sum, and a correctly
        # rounded square root)
        total = 0.0
        for k, v in enumerate(values[:ndim] if values is not None else x[:ndim].tolist()):
            total = v * v if k == 0 else total + v * v
        return math.sqrt(total)
    u = x[:ndim]
    return float(np.sqrt((u ** 2).sum()))
