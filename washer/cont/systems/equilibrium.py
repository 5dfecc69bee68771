"""Equilibria f(u, par) = 0 continued in PAR(ICP(1)) (AUTO's IPS = 0, 1; FUNI,
STPNAE; test functions FNLPAE, FNBPAE, FNHBEQ).

Unknowns x = (u, PAR(ICP(1))), N = NDIM equations. Stability (IPS = 1): the
eigenvalues of f_u sorted by decreasing real part; NINS counts Re <= 0, or Re <= 1e-5
where f_u looks conservative (AUTO's STABEQ: N even, |trace| < 1e-7 max |f_u[i, j]|).
Test functions: LP the lambda-component of the unit tangent, BP the
determinant of the Newton matrix, HB the real part of the complex pair
closest to the imaginary axis, accepted only if the stable count changed by >= 2
(a real pair crossing zero is no Hopf point), counted with the tolerance only where
both ends of the step look conservative (`hopf_accepted`).
"""
from __future__ import annotations

from itertools import chain

import numpy as np

from washer.cont.codes import Code
from washer.cont.normal_form import first_lyapunov
from washer.cont.system import Stability, StartData, determinant_value, fold_test, register
from washer.cont.linalg import EIG_WORK, compiled_lapack, eigenvalues_sorted, null_vectors, \
    nullvc
from washer.cont.systems._algebraic import AlgebraicSystem

#: |Im lambda| below this fraction of (1 + |lambda|) counts as real: AUTO's HB
#: test needs Im != 0, and finite-difference Jacobians leave rounding-level
#: imaginary parts on real pairs.
IMAG_TOL = 1e-8


def is_complex(lam: np.ndarray) -> np.ndarray:
    """Which of the eigenvalues `lam` are complex (bool, lam's shape): |Im| above
    IMAG_TOL (1 + |lambda|)."""
    return np.abs(lam.imag) > IMAG_TOL * (1 + np.abs(lam))


def hopf_pair(lam: np.ndarray) -> complex | None:
    """The complex eigenvalue closest to the imaginary axis (None if all are real):
    the pair AUTO's HB test and PAR(11) follow; for multipliers: floquet.torus_pair.
    Complex means is_complex (|Im| above IMAG_TOL (1 + |lambda|)); of equally close
    ones the first."""
    if lam.dtype.kind != "c":
        return None
    best = None
    for z in lam.tolist():                  # Python complex: abs is hypot, as numpy's
        if abs(z.imag) > IMAG_TOL * (1 + abs(z)) and (best is None
                                                       or abs(z.real) < abs(best.real)):
            best = z
    return best


def hopf_test(mu: complex | None) -> float | None:
    """AUTO's HB test of `mu`, the pair `hopf_pair` finds: Re mu (None if all are real)."""
    return None if mu is None else mu.real


def hopf_period(mu: complex | None) -> float | None:
    """PAR(11) = 2 pi / |Im mu| of the pair `hopf_pair` finds (PVLSAE; None if all are
    real)."""
    return None if mu is None else float(2 * np.pi / abs(mu.imag))


#: Re(lambda) up to which an eigenvalue counts as stable where f_u looks conservative
#: (AUTO's STABEQ): a Hamiltonian or reversible system keeps pairs on the imaginary axis
#: along whole branches, their computed real parts rounding (+-1e-16) of either sign.
#: Counted with tolerance 0, the stable count changes by 2 at nearly every step there and
#: each sign change is a false HB.
CONSERVATIVE_TOL = 1e-5
#: |trace f_u| below this fraction of max |f_u[i, j]| looks conservative (STABEQ's HMACH).
TRACE_TOL = 1e-7


#: Up to this NDIM neutral_tolerance sums the trace in order on Python floats, and a
#: point's values come from one compiled call (`PointValues`) that sums it so too.
POINT_NDIM = 8


def neutral_tolerance(A: np.ndarray) -> float:
    """Re up to which an eigenvalue of f_u (A: (n, n)) counts as stable: CONSERVATIVE_TOL
    where A looks conservative (n even, |trace A| < TRACE_TOL max |A[i, j]|), else 0."""
    n = len(A)
    if n == 0 or n % 2:
        return 0.0
    if n <= POINT_NDIM:
        # Python floats: on the 2-8 equations of most problems numpy's trace, abs and max
        # were 8 us a point, 6 % of an equilibrium step; the same sums (in order) and max
        rows = A.tolist()
        trace = 0.0
        for i in range(n):
            trace += rows[i][i]
        largest = max(map(abs, chain.from_iterable(rows)))   # (the same order, in C)
    else:
        trace, largest = np.trace(A), np.max(np.abs(A))
    return CONSERVATIVE_TOL if abs(trace) < TRACE_TOL * largest else 0.0


def stable_count(lam, neutral: float) -> int:
    """AUTO's NINS: how many of the eigenvalues `lam` (NDIM,) have Re <= neutral."""
    re = lam.real if type(lam) is np.ndarray else np.real(lam)    # (np.real: two Python calls)
    count = 0
    for v in re.tolist():               # (a plain loop: no generator at these sizes)
        if v <= neutral:
            count += 1
    return count


def spectrum(lam: np.ndarray, neutral: float = 0.0) -> Stability:
    """The Stability of eigenvalues `lam` (NDIM,): AUTO's NINS counts Re <= neutral (0, or
    `neutral_tolerance` where f_u looks conservative), stable when every one does."""
    n_stable = stable_count(lam, neutral)
    # (positional: values, n_stable, stable, kind, neutral)
    return Stability(lam, n_stable, n_stable == len(lam), "eigenvalues", neutral)


#: The test key of Hopf points across conservative steps (located points are HB). In a
#: conservative system the spectrum is symmetric about the imaginary axis, and a pair
#: leaves the axis only by colliding with another: i w1 and i w2 meet and split into
#: +-alpha + i beta, both signs of Re at once (l^4 + a l^2 + 1 at a = 2: Re = +-sqrt(2 - a)/2
#: after it). The signed real part, rounding on the axis before, changes sign there or
#: not by chance. With d half the distance from the eigenvalue closest to the axis to its
#: nearest neighbour in the same half plane, Re(d^2) is -(w1 - w2)^2/4 before and alpha^2
#: after, smooth through the collision (the unfolding (l - i w)^2 ~ c mu; (2 - a)/4 on
#: both sides above); Re(d^2) - CONSERVATIVE_TOL^2 changes sign where alpha passes the
#: tolerance, that is where the stable count changes.
NEUTRAL_HB = 100 + Code.HB


def neutral_hopf_test(st: Stability) -> float | None:
    """NEUTRAL_HB's value, Re(d^2) - neutral^2, where f_u looks conservative (st.neutral
    > 0); None elsewhere or without two complex eigenvalues in the upper half plane."""
    mu = hopf_pair(st.values) if st.neutral > 0 else None
    if mu is None:
        return None
    mu = complex(mu.real, abs(mu.imag))
    upper = [z for z in np.asarray(st.values).tolist() if isinstance(z, complex)
             and z.imag > IMAG_TOL * (1 + abs(z)) and z != mu]
    if not upper:
        return None
    d = min(upper, key=lambda z: abs(z - mu)) - mu
    return (d * d).real / 4 - st.neutral ** 2


def hopf_accepted(prev: Stability, cur: Stability) -> bool:
    """An HB test's sign change between two points is a Hopf point where the stable count
    changed by >= 2, counted with the conservative tolerance only where both points look
    conservative. A conservative system's trace vanishes along the whole branch, a
    dissipative one's only at isolated points: in 2 equations at the Hopf point itself,
    where a step that lands within 1e-7 of it would otherwise count the pair (Re ~ 1e-8)
    as stable at that end, the sign change and the count's change fall on different
    steps and the Hopf point is lost (AUTO-07p's STABEQ, which decides point by point,
    loses it so: x' = mu x - y, y' = x + mu y from mu = -0.5 with DS = 0.05)."""
    tol = min(prev.neutral, cur.neutral)
    return abs(stable_count(prev.values, tol) - stable_count(cur.values, tol)) >= 2


#: float64's dtype (arrays of native doubles carry this object)
_F64 = np.dtype(np.float64)


class PointValues:
    """An equilibrium's tangent, spectrum and test values after its corrector in one
    compiled call (csrc/cont/dense_lapack.cpp cont_ae_equilibrium_point): the values of
    linalg.unit_tangent, eigenvalues_sorted of f_u, neutral_tolerance, stable_count and
    hopf_pair, bit for bit (numpy's GETRF, GETRS and GEEV, the same sums and comparisons),
    with the buffers of one system's size and weights bound once."""

    def __init__(self, ndim: int, theta: np.ndarray):
        C = compiled_lapack()
        ffi, n = C.ffi, ndim + 1
        self.ndim, self._theta = ndim, np.ascontiguousarray(theta, dtype=float)
        self.t, self.w, self.out = np.empty(n), np.empty(2 * ndim), np.empty(4)
        self.real, self.pairs = self.w[0::2], self.w.view(np.complex128)
        self.sign_logdet = ffi.new("double[2]")
        buf = ffi.from_buffer
        self._lib_call, self._buf = C.lib.cont_ae_equilibrium_point, buf
        # the arguments after J and ref, the same at every call (big: the caller's)
        self._rest = (ffi.new("double[]", n), ffi.new("double[]", n * n + n),
                      ffi.new("int64_t[]", n), self.sign_logdet, ffi.new("int *"),
                      buf("double[]", self.t), buf("double[]", self.w),
                      ffi.new("double[]", ndim * ndim + 2 * ndim + EIG_WORK * ndim),
                      EIG_WORK * ndim, ffi.new("int *", 0), buf("double[]", self.out))
        self._head = (C.point_routines, ndim)
        self._tols = (IMAG_TOL, TRACE_TOL, CONSERVATIVE_TOL)
        self._theta_c = buf("double[]", self._theta)

    def __call__(self, J, ref, big: float) -> int:
        """Status of cont_ae_equilibrium_point on J = [f_u f_PAR] (NDIM, NDIM + 1) and the
        secant ref (NDIM + 1,) (0: every value in t, w, out, sign_logdet); -1 where the call
        does not take these arrays (types, shapes, layouts)."""
        n = self.ndim
        if type(J) is not np.ndarray or J.dtype is not _F64 or J.shape != (n, n + 1) \
                or not J.flags.c_contiguous or type(ref) is not np.ndarray \
                or ref.dtype is not _F64 or ref.shape != (n + 1,) or not ref.flags.c_contiguous:
            return -1
        buf = self._buf
        return self._lib_call(*self._head, buf("double[]", J), buf("double[]", ref),
                              self._theta_c, big, *self._tols, *self._rest)


@register(0, 1)
@register(1, 1)
@register(0, -1, "BP")
@register(1, -1, "BP")
@register(0, -1, "*")
@register(1, -1, "*")
class EquilibriumSystem(AlgebraicSystem):
    """f(u, par) = 0 with unknowns x = (u, PAR(ICP(1))).

    ISW = -1 at a BP label switches to the other branch; at any other label (AUTO's
    CNRLAE: IRS != 0 and ISW < 0) the start direction is STPRAE's with IPERP = 1, the
    'null vector' of [f_u f_lambda; stored direction], and the first step is a branch
    switch's (on the plane orthogonal to it): there the null space of [f_u f_lambda] is
    one-dimensional, so the run continues the one branch, as a new branch."""

    #: residual(x) is the problem's f(u, PAR) at x = (u, PAR(ICP(1))) and jacobian(x)
    #: Problem.jacobian's [f_u, f_PAR(ICP(1))], nothing more: the compiled corrector of
    #: equilibria (washer.cont.corrector_algebraic) may stand in for the Python loop.
    #: A subclass that changes the equations sets it False (FixedPoints).
    residual_is_func = True
    #: the compiled point values of this system (`PointValues`), or None
    _point_call = None

    def __init__(self, start: StartData):
        self._one_parameter(start)
        self._switch = start.settings.ISW == -1 and start.kind == "BP"
        self._perp = start.settings.ISW == -1 and start.kind != "BP" and \
            start.record is not None and start.settings.IPS in (0, 1)
        self._stored = None
        rec = start.record
        if self._perp:
            # READLB's UDOT: the record's direction whatever its free parameters (none
            # stored: zeros, and the vector is f's null vector itself)
            self._stored = np.zeros(self.ndim + 1)
            if rec.udot is not None and len(rec.rldot) and len(rec.udot) >= self.ndim:
                self._stored = np.r_[np.asarray(rec.udot, float)[:self.ndim], rec.rldot[0]]

        # one compiled call for a point's tangent, stability and tests (`point_values`)
        # where this class's own stability, tests and weighted tangent are the system's
        self._point_call = None
        cls = type(self)
        if compiled_lapack() is not None and start.settings.IPS in (1, 11) \
                and 0 < self.ndim <= POINT_NDIM \
                and cls.stability is EquilibriumSystem.stability \
                and cls.test_functions is EquilibriumSystem.test_functions \
                and cls.unit_tangent is AlgebraicSystem.unit_tangent \
                and cls.inner is AlgebraicSystem.inner and len(self.theta) == self.ndim + 1:
            self._point_call = PointValues(self.ndim, self.theta)

    @property
    def start_mode(self) -> str | None:
        return "switch" if self._perp else None

    # ------------------------------------------------------------ equations
    def residual(self, x) -> np.ndarray:
        return self.problem.func(x[:-1], self._p(x))

    #: How many of the last `jacobian`s are kept (by x's bytes)
    JACOBIANS_KEPT = 8
    #: (x's bytes, PAR's bytes, problem) -> the Jacobian there, of the last `jacobian`s
    #: (this system's own, made by the first)
    _jacobians = None

    def jacobian(self, x) -> np.ndarray:
        """[f_u, f_lambda], shape (N, N + 1) (a new array). An x asked for again among the
        last JACOBIANS_KEPT is not evaluated again: at a branch point its refresh, the
        directions and the start of each branch switched to there ask for the same one
        (between the two starts, the first switched branch's first steps ask for others)."""
        # (with the fixed parameters and the problem: the same f at the same x)
        key = (x.tobytes(), self.par.tobytes(), self.problem) \
            if type(x) is np.ndarray and x.dtype == np.float64 else None
        kept = self._jacobians
        if kept is None:
            kept = self._jacobians = {}
        if key is not None and key in kept:
            return kept[key].copy()
        J = self.problem.jacobian(x[:-1], self._p(x), self.free)
        if key is not None and type(J) is np.ndarray:
            if len(kept) >= self.JACOBIANS_KEPT:
                del kept[next(iter(kept))]          # the oldest
            kept[key] = J.copy()
        return J

    def start(self):
        if self._perp:
            # STPRAE, IPERP = 1: NLVC of the square matrix [f_u f_lambda; UDOT] (its
            # complete pivoting drops the row eliminated last), scaled to unit length
            # in the weighted norm and turned by STPRAE's sign rule; DS's sign then
            # chooses the way.
            J = np.asarray(self.jacobian(self._x0), dtype=float)
            d = nullvc(np.vstack([J, self._stored]), 1)
            return self._x0.copy(), self.orient(d / np.sqrt(self.inner(d, d)), self._x0)
        if self._switch:
            # ISW = -1 at a BP label: start along the other branch (AUTO's STBIF).
            t = self._t0
            if t is None:
                t = null_vectors(self.jacobian(self._x0), 1)[:, 0]
            d = self.directions(self._x0, t / np.sqrt(self.inner(t, t)), Code.BP)
            return self._x0.copy(), (d[0] if d else None)
        return self._x0.copy(), self.restart_direction(self._t0)

    # ------------------------------------------------------------ stability
    def stability(self, x, J) -> Stability | None:
        if self.settings.IPS not in (1, 11):
            return None
        J = np.asarray(J)
        lam = eigenvalues_sorted(J, leading=True)     # of f_u
        self._last_spectrum = (x.tolist(), lam)      # reused by solution() for PAR(11)
        return spectrum(lam, neutral_tolerance(J[:, :len(J)]))

    def point_values(self, x, J, ref, big: float, codes):
        """A point's (tangent, stability, test values `codes`) from its Jacobian J = [f_u
        f_PAR] and the secant ref in one compiled call (`PointValues`): what
        Continuation.tangent (unit_tangent with its bound `big`), stability and
        test_functions give, the same values in the same order; None where that call
        does not apply or the tangent or the eigenvalues need the general route (a
        singular or nearly singular bordered matrix, a failing GEEV), which repeats the
        work and handles or reports it."""
        call = self._point_call
        if call is None or call(J, ref, big) != 0:
            return None
        t = call.t.copy()
        neutral, n_stable, k, real = call.out.tolist()
        lam = call.real.copy() if real else call.pairs.copy()
        self._last_spectrum = (x.tolist(), lam)      # reused by solution() for PAR(11)
        n_stable = int(n_stable)
        # (positional: values, n_stable, stable, kind, neutral)
        stab = Stability(lam, n_stable, n_stable == self.ndim, "eigenvalues", neutral)
        # hopf_pair(lam), as `_pair` keeps it for the HB test and PAR(11)
        mu = None if k < 0 else complex(*call.w[2 * int(k):2 * int(k) + 2].tolist())
        self._pair_memo = (lam, mu)
        out = {}
        if not codes:
            return t, stab, out
        if Code.LP in codes:
            out[Code.LP] = fold_test(t)
        if Code.BP in codes:
            sl = call.sign_logdet
            out[Code.BP] = determinant_value(sl[0], sl[1])      # determinant_test
        return t, stab, self._hopf_tests(out, stab, codes)

    def active_tests(self) -> list:
        out = [code for name, code in (("LP", Code.LP), ("BP", Code.BP), ("HB", Code.HB))
               if self.settings.detects(name)]
        if Code.HB in out and self.settings.IPS in (1, 11):
            out.append(NEUTRAL_HB)
        return out

    def located_code(self, key, point) -> int:
        """NEUTRAL_HB's zeros are Hopf points (HB); other keys are their own codes."""
        return Code.HB if key == NEUTRAL_HB else key

    #: (spectrum, hopf_pair of it) of the last spectrum asked for (`_pair`)
    _pair_memo = None

    def _pair(self, lam: np.ndarray) -> complex | None:
        """hopf_pair(lam), once per spectrum: a point's HB test and its PAR(11) read the
        same pair of the same array (spectra are not changed in place)."""
        memo = self._pair_memo
        if memo is None or memo[0] is not lam:
            memo = self._pair_memo = (lam, hopf_pair(lam))
        return memo[1]

    def test_functions(self, x, tangent, J, stability, factor, codes) -> dict:
        return self._hopf_tests(self._lp_bp(tangent, factor, codes), stability, codes)

    def _hopf_tests(self, out: dict, stability: Stability | None, codes) -> dict:
        """out with the HB and NEUTRAL_HB tests' values where codes ask for them (of
        test_functions and point_values)."""
        if Code.HB in codes:
            out[Code.HB] = hopf_test(self._pair(stability.values)) \
                if stability is not None else None
        if NEUTRAL_HB in codes:
            # (None where f_u does not look conservative: neutral_hopf_test's value there)
            out[NEUTRAL_HB] = neutral_hopf_test(stability) \
                if stability is not None and stability.neutral > 0 else None
        return out

    def accept(self, code, prev, cur) -> bool:
        if code in (Code.HB, NEUTRAL_HB):
            if prev.stability is None or cur.stability is None:
                return False
            # across a conservative step the HB test's sign is rounding: NEUTRAL_HB's there
            conservative = min(prev.stability.neutral, cur.stability.neutral) > 0
            if conservative != (code == NEUTRAL_HB):
                return False
            return hopf_accepted(prev.stability, cur.stability)
        return True

    def solution(self, x, tangent):
        values = x.tolist()
        sol = self._solution(x, tangent, values)
        if self.settings.IPS in (1, 11) and len(sol.par) >= 11:
            cached = getattr(self, "_last_spectrum", None)
            if cached is not None and cached[0] == values:
                lam = cached[1]
            else:
                lam = eigenvalues_sorted(self.problem.dfdu(x[:-1], self._p(x)))
            per = hopf_period(self._pair(lam))
            if per is not None:
                sol.par[10] = per
        return sol

    def info(self, x, code) -> dict:
        """At an HB: the frequency and the first Lyapunov coefficient (d-file, API)."""
        if code != Code.HB or self.settings.IPS not in (1, 11):
            return {}
        p = self._p(x)
        A = self.problem.dfdu(x[:-1], p)
        mu = hopf_pair(eigenvalues_sorted(A))
        if mu is None:
            return {}
        omega = abs(mu.imag)
        return {"omega": omega, "l1": first_lyapunov(self.problem, x[:-1], p, omega, A)}


__all__ = ["EquilibriumSystem", "hopf_pair", "eigenvalues_sorted", "hopf_test", "hopf_period",
           "neutral_tolerance", "hopf_accepted", "neutral_hopf_test", "NEUTRAL_HB"]
