"""Fixed points of maps u -> f(u, p) (AUTO's IPS = -1; maps.f90: FNDS, STPNDS,
PVLSDS, FNHBDS, TPSPAE) and their loci in two parameters (ISW = 2: folds FNLPDS,
period doublings FNLPDS with ITPST = 7, Neimark-Sacker points FNNS).

The user's func is the map f itself. AUTO continues zeros of

    F(u, p) = f^k(u, p) - u,       k = NINT(PAR(11)) (1 when PAR(11) = 0)

so a fixed point of the k-th iterate is a period-k orbit; switching at a period
doubling (ISW = -1 at a PD label) doubles PAR(11) and follows the period-2k
branch, which crosses the period-k one there as a branch point of F.

Stability (PVLSDS): the multipliers mu of D f^k = F_u + I. AUTO works with
log(mu): NINS counts multipliers with log|mu| <= 0 (inside the unit circle),
PT < 0 when all are. The test function of PD and TR (FNHBDS) is log|mu| of the
multiplier closest to the unit circle among those that are not positive reals;
its type at the zero (TPSPAE) is PD when that multiplier is a negative real
(|arg mu - pi| <= sqrt(EPSS)), TR when it is complex (|arg mu| > sqrt(EPSS)),
and it is accepted only if NINS changed. It is ONE test whatever the kind of the
multiplier at either end of a step: a real multiplier leaving through -1 and the
pair it then forms with another negative one (the Henon map's PD at beta = 0.633
and the collision just after it) both lie inside one step, and the zero is
typed where it is located. At TR points PAR(12) holds the angle
arg mu. LP and BP are AUTO's algebraic tests (FNLPAE, FNBPAE) on F.
"""
from __future__ import annotations

import math

import numpy as np

from washer.cont.codes import Code
from washer.cont.differences import columns
from washer.cont.problem import Problem
from washer.cont.system import Stability, StartData, register
from washer.cont.floquet import torus_resonance_tests
from washer.cont.linalg import null_vectors
from washer.cont.systems._algebraic import AlgebraicSystem
from washer.cont.systems._loci import LocusSystem
from washer.cont.systems.equilibrium import EquilibriumSystem
from washer.cont.systems.fold import FoldSystem

#: log|mu| for a zero multiplier (PVLSDS: RLARGE), a superstable direction.
LOG_ZERO = -1.0e30


def iterations(par) -> int:
    """k = NINT(PAR(11)), at least 1 (FNDS: one application when PAR(11) < 2)."""
    return max(1, int(round(float(par[10])))) if len(par) > 10 else 1


def iterated_problem(problem: Problem) -> Problem:
    """The problem F(u, p) = f^k(u, p) - u of AUTO's FNDS, k = NINT(PAR(11)) read
    from the parameters at each call. Batched: a finite-difference stencil of F
    is k batched calls of f. Jacobians by the chain rule where the user supplies
    them (JAC = 1 or -1), else central differences of F."""
    n = problem.ndim

    def orbit_batch(us, pars):
        us = np.asarray(us, dtype=float)
        pars = np.asarray(pars, dtype=float)
        ks = np.maximum(1, np.rint(pars[:, 10]).astype(int)) if pars.shape[1] > 10 \
            else np.ones(len(us), dtype=int)
        x = us.copy()
        for i in range(int(ks.max(initial=1))):
            live = ks > i
            if live.all():
                x = problem.func_many(x, pars)
            else:
                x[live] = problem.func_many(x[live], pars[live])
        return x - us

    def F(u, par):
        return orbit_batch(np.asarray(u, float)[None, :], np.asarray(par, float)[None, :])[0]

    def dfdu(u, par):
        x = np.asarray(u, dtype=float)
        J = np.eye(n)
        for _ in range(iterations(par)):
            J = problem.dfdu(x, par) @ J
            x = problem.func(x, par)
        return J - np.eye(n)

    def dfdp(u, par):
        x = np.asarray(u, dtype=float)
        idx = list(range(1, len(par) + 1))
        P = np.zeros((n, len(par)))
        for _ in range(iterations(par)):
            # D_p f(x_i(p), p) = f_u(x_i) D_p x_i + f_p(x_i): the chain rule of FNDS.
            P = problem.dfdu(x, par) @ P + problem.dfdp(x, par, idx)
            x = problem.func(x, par)
        return P

    out = Problem(n, F, stpnt=problem._stpnt, dfdu=dfdu if problem._dfdu is not None else None,
                  dfdp=dfdp if problem._dfdp is not None else None, name=problem.name,
                  npar=problem.npar, func_batch=orbit_batch, pvls=problem._pvls,
                  parnames=problem.parnames, unames=problem.unames, jac=problem.jac)
    return out


def log_multipliers(A: np.ndarray) -> np.ndarray:
    """log(mu) of the multipliers mu of D f^k = A + I (A = F_u), sorted by
    decreasing real part (|mu| decreasing), as PVLSDS hands them to STABEQ."""
    mu = np.linalg.eigvals(np.asarray(A) + np.eye(len(A))).astype(complex)
    with np.errstate(divide="ignore"):
        lg = np.where(mu == 0, complex(LOG_ZERO, 0.0), np.log(np.where(mu == 0, 1.0, mu)))
    return lg[np.argsort(-lg.real, kind="stable")]


def critical(lg: np.ndarray) -> complex | None:
    """The log-multiplier closest to the unit circle among those with Im != 0
    (complex or negative real multipliers: STABEQ's LOC for ITPST = 0)."""
    cand = lg[lg.imag != 0]
    if cand.size == 0:
        return None
    return complex(cand[np.argmin(np.abs(cand.real))])


def map_type(lg_loc: complex | None, epss: float) -> int:
    """TPSPAE on a plain branch: Code.PD, Code.TR or Code.NONE for the critical
    log-multiplier (its imaginary part is arg mu)."""
    if lg_loc is None:
        return Code.NONE
    arg = abs(lg_loc.imag)
    if abs(arg - math.pi) <= math.sqrt(epss):
        return Code.PD
    if arg > math.sqrt(epss):
        return Code.TR
    return Code.NONE


def map_stability(A: np.ndarray) -> Stability:
    """NINS = multipliers with log|mu| <= tol (STABEQ, with its tolerance 1e-5 for
    an even dimension and a traceless F_u, the conservative guess); `values` are
    the multipliers mu themselves."""
    lg = log_multipliers(A)
    n = len(A)
    tol = 0.0
    if n % 2 == 0 and abs(np.trace(A)) < 1e-7 * np.max(np.abs(A), initial=0.0):
        tol = 1e-5
    n_stable = int(np.sum(lg.real <= tol))
    st = Stability(values=np.exp(lg), n_stable=n_stable, stable=n_stable == n,
                   kind="multipliers")
    st.log = lg
    return st


@register(-1, 1)
@register(-1, -1, "BP")
class FixedPoints(EquilibriumSystem):
    """Fixed points of f^k, unknowns x = (u, PAR(ICP(1))). ISW = -1 at a PD label
    starts the period-doubled branch (k doubled) in the direction orthogonal to
    the stored one (STPRAE with IPERP = 1): `start_mode` is then "switch"."""

    #: the residual is f^k(u) - u (iterated_problem), not the user's f: the Python loop
    residual_is_func = False

    def __init__(self, start: StartData):
        par = np.array(start.par, dtype=float)
        if len(par) > 10 and par[10] == 0:
            par[10] = 1.0                       # STPNDS: PAR(11) = 1 when unset
        self._pd_switch = start.settings.ISW == -1 and start.kind == "PD"
        if start.settings.ISW == -1 and start.kind == "TR":
            raise ValueError("ISW = -1 at a TR label of a map (a resonant torus) is not "
                             "supported yet")
        if self._pd_switch:
            par[10] *= 2                        # STPNDS: period doubling
        start = StartData(iterated_problem(start.problem), start.settings, start.u, par,
                          start.record, start.kind, start.unames)
        super().__init__(start)
        if self._pd_switch:
            self._switch = True

    @property
    def start_mode(self) -> str:
        return "switch" if self._switch else "fresh"

    def start(self):
        if self._pd_switch:
            # The branch of period 2k crosses the period-k one at the PD: the new
            # direction is the null vector of [F_u F_lambda; t_stored] (IPERP = 1).
            J = np.asarray(self.jacobian(self._x0))
            t = self._t0
            if t is None:
                t = null_vectors(J, 1)[:, 0]
            d = null_vectors(np.vstack([J, t]), 1)[:, 0]
            d = d / math.sqrt(self.inner(d, d))
            return self._x0.copy(), self.orient(d, self._x0)
        return super().start()

    # ------------------------------------------------------------ stability
    def stability(self, x, J) -> Stability:
        return map_stability(np.asarray(J)[:, :self.ndim])

    def active_tests(self) -> list:
        # PD and TR are one test (FNHBDS), keyed PD and typed where it vanishes.
        tests = [code for name, code in (("LP", Code.LP), ("BP", Code.BP))
                 if self.settings.detects(name)]
        if self.settings.detects("PD") or self.settings.detects("TR"):
            tests.append(Code.PD)
        return tests

    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict:
        out = self._lp_bp(tangent, factor, codes)
        if Code.PD in codes:
            loc = critical(stability.log)
            out[Code.PD] = None if loc is None else float(loc.real)
        return out

    def located_code(self, key, point) -> int:
        """PD or TR for a zero of the combined test, by the critical multiplier at the
        located point (TPSPAE); a zero whose multiplier is neither (|arg mu| below
        sqrt(EPSS)) keeps the kind nearest its argument."""
        if key != Code.PD or point.stability is None:
            return key
        loc = critical(point.stability.log)
        kind = map_type(loc, self.settings.EPSS)
        if kind == Code.NONE:
            kind = Code.PD if loc is not None and abs(loc.imag) > math.pi / 2 else Code.TR
        return kind

    def accept(self, code, prev, cur) -> bool:
        if code in (Code.PD, Code.TR):
            if prev.stability is None or cur.stability is None:
                return False
            return prev.stability.n_stable != cur.stability.n_stable
        return True

    def solution(self, x, tangent):
        sol = AlgebraicSystem.solution(self, x, tangent)
        if len(sol.par) >= 12:
            lg = log_multipliers(self.problem.dfdu(x[:-1], self._p(x)))
            loc = critical(lg)
            if map_type(loc, self.settings.EPSS) == Code.TR:
                sol.par[11] = abs(loc.imag)           # PVLSDS: PAR(12) = the angle at TR
        return sol

    def info(self, x, code) -> dict:
        return {}


def locus_multipliers(A: np.ndarray, n_curve: int) -> tuple[complex | None, int]:
    """STABEQ with N = n_curve + 1 on a locus of maps (PVLSDS with ITPST != 0): of the
    log-multipliers log(mu) of D f^k = A + I, the n_curve closest to the imaginary axis
    (|log|mu|| smallest) are the curve's own (+1 on folds, -1 on flips, the pair on
    Neimark-Sacker curves); LOC is the next one, real or complex. NINS counts those with
    log|mu| <= tol, the curve's own counted as inside. Returns (log mu at LOC, NINS)."""
    lg = log_multipliers(A)
    n = len(A)
    tol = 1e-5 if n % 2 == 0 and abs(np.trace(A)) < 1e-7 * np.max(np.abs(A), initial=0.0) \
        else 0.0
    chosen: list[int] = []
    for _ in range(n_curve + 1):
        best, arev = None, math.inf
        for i in range(n):
            # AR <= AREV: among equals the last one in the sorted order
            if i not in chosen and abs(lg[i].real) <= arev:
                best, arev = i, abs(lg[i].real)
        if best is None:
            return None, n
        chosen.append(best)
    own = chosen[:-1]
    nins = sum(1 for i in range(n) if lg[i].real <= tol or i in own)
    return complex(lg[chosen[-1]]), nins


#: TPSPAE on the loci of maps: (curve type, kind of the multiplier at LOC) -> the base
#: code written (LBITP: LPD 8, LTR 3, PTR 7, TTR 8; curve_code makes 28, 78, 23, 83,
#: 77, 87, 88), None where AUTO labels nothing.
_LOCUS_KIND = {(2, "flip"): 8, (2, "torus"): 3, (2, "fold"): None,
               (7, "flip"): None, (7, "torus"): 7, (7, "fold"): 8,
               (8, "flip"): 7, (8, "torus"): 8, (8, "fold"): 3}


def multiplier_kind(lg_loc: complex, epss: float) -> str:
    """'flip' (|arg mu - pi| <= sqrt(EPSS)), 'torus' (arg mu > sqrt(EPSS)) or 'fold'."""
    arg = abs(lg_loc.imag)
    if abs(arg - math.pi) <= math.sqrt(epss):
        return "flip"
    return "torus" if arg > math.sqrt(epss) else "fold"


class _MapLocus:
    """Loci of maps: the user's f replaced by F = f^k - u. Their codim-2 points
    (FNCSDS): the resonances (FNRNDS: R1 on folds and R2 on flips where the curve's
    multiplier is double, BT-like, FNBTAE <w, phi>; R1..R4 on Neimark-Sacker curves
    by the angle) and, from the multiplier test FNHBDS, a second multiplier on the
    unit circle: fold-flip LPD, fold-Neimark-Sacker LTR, flip-Neimark-Sacker PTR,
    double Neimark-Sacker TTR (TPSPAE by the curve and the multiplier's argument,
    accepted only where NINS changed)."""

    #: The equations are f^k - u, not the user's f: the Python loop corrects them.
    compiled_system = None
    #: Multipliers on the unit circle that define the curve (STABEQ's N - 1).
    n_curve = 1
    #: Code of the multiplier test's key (typed where located).
    MULT = Code.TR

    @staticmethod
    def map_start(start: StartData) -> StartData:
        par = np.array(start.par, dtype=float)
        if len(par) > 10 and par[10] == 0:
            par[10] = 1.0
        return StartData(iterated_problem(start.problem), start.settings, start.u, par,
                         start.record, start.kind, start.unames)

    def _codim2_on(self) -> bool:
        # CHECKSP: R1..R4, LPD, LTR, PTR, TTR of maps whenever ISP != 0
        return self.settings.ISP != 0

    def resonance_codes(self) -> list:
        return []

    def active_tests(self) -> list:
        tests = [code for name, code in (("LP", Code.LP), ("BP", Code.BP))
                 if self.settings.detects(name)]
        if self._codim2_on():
            tests += self.resonance_codes() + [self.MULT]
        return tests

    def stability(self, x, J):
        """NINS of the locus (the curve's own multipliers inside) for the multiplier
        test's rule; never 'stable' (AUTO writes PT > 0 on loci)."""
        A = self.problem.dfdu(x[:self.ndim], self._p(x))
        lg, nins = locus_multipliers(A, self.n_curve)
        st = Stability(values=np.exp(log_multipliers(A)), n_stable=nins, stable=False,
                       kind="multipliers")
        st.log = lg
        return st

    def resonance_tests(self, x, codes) -> dict:
        return {}

    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict:
        out = self._lp_bp(tangent, factor, codes)
        out.update(self.resonance_tests(x, codes))
        if self.MULT in codes:
            # FNHBDS is 0 (no test) where TPSPAE names no point for the multiplier at
            # LOC: the flip multiplier on a flip curve (its double -1 is R2), a real
            # positive one on a fold curve (R1)
            lg = None if stability is None else stability.log
            out[self.MULT] = None if lg is None or self._locus_kind(lg) is None \
                else float(lg.real)
        return out

    def _locus_kind(self, lg: complex) -> int | None:
        return _LOCUS_KIND[(self.curve_type, multiplier_kind(lg, self.settings.EPSS))]

    def accept(self, code, prev, cur) -> bool:
        if code == self.MULT:
            if prev.stability is None or cur.stability is None:
                return False
            return prev.stability.n_stable != cur.stability.n_stable
        return True

    def located_code(self, key, point) -> int:
        if key != self.MULT or point.stability is None or point.stability.log is None:
            return key
        kind = self._locus_kind(point.stability.log)
        return key if kind is None else kind

    def _bt(self, x, shift: float) -> float:
        """FNBTAE: <w, phi> with w the left null vector of F_u + shift I (the curve's
        matrix), oriented as at the previous point: zero where the multiplier is double."""
        n = self.ndim
        A = self.problem.dfdu(x[:n], self._p(x)) + shift * np.eye(n)
        w = null_vectors(A.T, 1)[:, 0]
        if getattr(self, "w_ref", None) is not None and len(self.w_ref) == n \
                and w @ self.w_ref < 0:
            w = -w
        return float(w @ x[n:2 * n])


@register(-1, 2, "LP")
@register(-1, 2, "LP-curve")
class MapFoldLocus(_MapLocus, FoldSystem):
    """Folds of fixed points of f^k in two parameters (FNLPDS): the fold locus of F."""
    curve_type = 2

    def __init__(self, start: StartData):
        FoldSystem.__init__(self, self.map_start(start))

    def resonance_codes(self) -> list:
        return [Code.R1]

    def resonance_tests(self, x, codes) -> dict:
        """R1 (1:1 resonance): the multiplier +1 is double (FNBTAE on F_u)."""
        return {Code.R1: self._bt(x, 0.0)} if Code.R1 in codes else {}


@register(-1, 2, "PD")
@register(-1, 2, "PD-curve")
class MapPDLocus(_MapLocus, FoldSystem):
    """Period doublings in two parameters (FNLPDS with ITPST = 7, FFLP):

        F(u, p) = 0,   (F_u + 2 I) phi = 0,   <phi, phi> - 1 = 0

    (F_u + 2 I = D f^k + I: a multiplier -1), unknowns (u, phi, PAR(ICP(2)), PAR(ICP(1)))."""
    curve_type = 7
    SHIFT = 2.0

    def __init__(self, start: StartData):
        start = self.map_start(start)
        self._setup(start, start.problem.ndim)
        n = self.ndim
        # a restart from a point of this locus: its stored (u, phi, PAR(ICP(2))) and
        # direction (STPNLPF reads them as FNLPDS's unknowns)
        ext = self.stored_point(start, "PD-curve")
        if ext is None:
            u = np.asarray(start.u, dtype=float)[:n]
            phi = null_vectors(self.problem.dfdu(u, self.par) + self.SHIFT * np.eye(n),
                               1)[:, 0]
            ext = np.r_[u, phi / np.linalg.norm(phi), self.par[self.free[1] - 1]]
        self._x0 = np.r_[ext, self.par[self.free[0] - 1]]
        self.w_ref = null_vectors((self.problem.dfdu(ext[:n], self._p(self._x0))
                                   + self.SHIFT * np.eye(n)).T, 1)[:, 0]
        self._t0 = self.stored_direction(start, "PD-curve")

    def residual(self, x):
        r = FoldSystem.residual(self, x)
        n = self.ndim
        r[n:2 * n] += self.SHIFT * x[n:2 * n]
        return r

    def jacobian(self, x, frozen_second: bool = False):
        J = FoldSystem.jacobian(self, x, frozen_second)
        n = self.ndim
        J[n:2 * n, n:2 * n] += self.SHIFT * np.eye(n)
        return J

    def update(self, x, tangent):
        """The left null vector of F_u + 2 I moves (the sign of the R2 test)."""
        n = self.ndim
        self.w_ref = self._w(self.problem.dfdu(x[:n], self._p(x)) + self.SHIFT * np.eye(n))

    def resonance_codes(self) -> list:
        return [Code.R2]

    def resonance_tests(self, x, codes) -> dict:
        """R2 (1:2 resonance): the multiplier -1 is double (FNBTAE on F_u + 2 I)."""
        return {Code.R2: self._bt(x, self.SHIFT)} if Code.R2 in codes else {}


@register(-1, 2, "TR")
@register(-1, 2, "TR-curve")
class MapTorusLocus(_MapLocus, LocusSystem):
    """Neimark-Sacker points in two parameters (FNNS, FFNSX; Kuznetsov, 3rd ed.,
    eq. 10.83). With A = D f^k = F_u + I and c = cos(theta):

        F(u, p) = 0,   (A^2 - 2 c A + I) v = 0,   <v, v> - 1 = 0,
        <B^T v_old - B v_old, v> = 0          (B = F_u, v_old the previous v)

    unknowns (u, v, theta, PAR(ICP(2)), PAR(ICP(1))); theta starts at PAR(12)
    of the TR point and is written to PAR(12). The Jacobian is by central
    differences of these equations (maps are small)."""
    curve_type = 8
    n_curve = 2
    freezes_second_derivatives = False

    def resonance_codes(self) -> list:
        return [Code.R1, Code.R4, Code.R3, Code.R2]

    def resonance_tests(self, x, codes) -> dict:
        """R1..R4: the angle theta of the multipliers through 0, pi/2, 2 pi/3, pi (FNRNDS)."""
        return torus_resonance_tests(float(x[2 * self.ndim]), codes)

    def __init__(self, start: StartData):
        start = self.map_start(start)
        self._setup(start, start.problem.ndim + 1)
        n = self.ndim
        # a restart from a point of this locus: its stored (u, v, theta, PAR(ICP(2)))
        # and direction (STPNHBF reads them as FNNS's unknowns)
        ext = self.stored_point(start, "TR-curve")
        if ext is None:
            u = np.asarray(start.u, dtype=float)[:n]
            theta = self.par[11] if len(self.par) > 11 else 0.0
            if not theta > 0:
                raise ValueError("the TR record has no angle PAR(12) > 0 to start the "
                                 "Neimark-Sacker curve from")
            A = self.problem.dfdu(u, self.par) + np.eye(n)
            M = A @ A - 2 * math.cos(theta) * A + np.eye(n)
            v = null_vectors(M, 2)[:, 0]
            ext = np.r_[u, v / np.linalg.norm(v), theta, self.par[self.free[1] - 1]]
        self._x0 = np.r_[ext, self.par[self.free[0] - 1]]
        self.v_old = self._x0[n:2 * n] / np.linalg.norm(self._x0[n:2 * n])
        self._t0 = self.stored_direction(start, "TR-curve")

    def residual(self, x):
        n = self.ndim
        u, v, theta = x[:n], x[n:2 * n], x[2 * n]
        p = self._p(x)
        B = self.problem.dfdu(u, p)
        f = 2 * (1 - math.cos(theta))
        M = B @ B + f * B + f * np.eye(n)
        vo = self.v_old
        return np.r_[self.problem.func(u, p), M @ v, v @ v - 1.0, (B.T @ vo - B @ vo) @ v]

    def jacobian(self, x, frozen_second: bool = False):
        x = np.asarray(x, dtype=float)
        return columns(self.residual, x, range(len(x)))

    def update(self, x, tangent):
        v = x[self.ndim:2 * self.ndim]
        self.v_old = v / np.linalg.norm(v)

    def solution(self, x, tangent):
        sol = LocusSystem.solution(self, x, tangent)
        if len(sol.par) >= 12:
            sol.par[11] = x[2 * self.ndim]
        return sol


__all__ = ["FixedPoints", "MapFoldLocus", "MapPDLocus", "MapTorusLocus", "iterated_problem"]
