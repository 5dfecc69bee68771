"""Floquet multipliers of periodic orbits and the test functions on them, in one place
for every system that has multipliers (collocation, shooting): AUTO's FLOWKM (the
multipliers), FNSPBV (stability, 'multiplier inaccurate'), TPSPBV (PD or TR) and the
tests of cycles FNLPBV (LP), FNBPBV (BP), FNSPBV (PD, TR).

Order of the multipliers (AUTO's, `sort_multipliers`): the one closest to 1 first (the
trivial multiplier of an autonomous orbit), then the others by increasing distance of
|mu| from the unit circle, so mu[1] is the nontrivial multiplier nearest the circle.
The orbits of periodically forced systems (shooting) have no trivial multiplier
(`trivial=False` throughout): all are sorted by their distance from the circle and
mu[0] is the critical one.

The tests, with the sign conventions of AUTO:
* LP of cycles: the PAR(ICP(1))-component of the unit tangent.
* BP of cycles: a determinant of the bordered Jacobian reduced to the boundary
  unknowns, supplied by the system (it depends on the discretisation).
* PD and TR: ONE test, |mu| - 1 of the nontrivial multiplier nearest the circle among
  those TPSPBV classes as a period doubling (real, < -0.5) or a torus
  (|Im| > sqrt(EPSS)) of a kind being detected, undefined if none (AUTO's FNSPBV takes
  mu_2 only, and is undefined where mu_2 is real above -0.5: `spb_test`); its key is
  SPB, and the located zero is typed by TPSPBV at the located point (`spb_code`). One
  function for both matters where a complex pair meets the negative real axis and one
  of the pair crosses -1 within a step: the previous point is of torus type inside the
  circle, the next of PD type outside; separate PD and TR functions each see only one
  end of the step and miss the PD. This is the only torus test of the engine.
PD and TR are accepted only where the stable count changed (FNSPBV), and undefined
while the multipliers are inaccurate or with fewer than two nontrivial multipliers (a
planar autonomous orbit has one, real and positive).
"""
from __future__ import annotations

import cmath
import math
from typing import Callable

import numpy as np

from washer.cont.codes import Code
from washer.cont.system import Stability, fold_test

#: Stability tolerance of FNSPBV: |mu| <= 1 + STABLE_TOL counts as inside the circle.
STABLE_TOL = 1e-5
#: AUTO's "multiplier inaccurate" rule (FNSPBV): detection is suspended when the
#: multiplier closest to 1 is farther than INACCURATE from 1, resumed below ACCURATE.
INACCURATE = 5e-2
ACCURATE = 1e-2
#: The multipliers of a Jacobian evaluated at a Newton iterate within EPSU of the point
#: (AUTO's NEWTONBV takes them so) stand for the point's where their trivial multiplier is
#: within this of 1 (`newton_jacobian_serves`): that matrix never suspends the tests by
#: itself; where its multipliers would count as inaccurate (or stay so, past ACCURATE),
#: the Jacobian at the point decides.
NEWTON_TRIVIAL = ACCURATE
#: A multiplier is complex when |Im mu| > COMPLEX_TOL (1 + |mu|).
COMPLEX_TOL = 1e-10
#: The note a Stability carries while the multipliers are inaccurate.
INACCURATE_NOTE = "Multiplier inaccurate"
#: The key of the combined test of period doublings and tori (FNSPBV's one function);
#: a located zero is written as PD or TR by `spb_code`.
SPB = int(Code.PD)


# The compiled sort (csrc/cont/floquet.cpp's cont_multipliers_sorted: the order below, from
# the same values of numpy's complex absolute value); without washer._cont the Python serves.
try:
    from washer._cont import ffi as _FFI, lib as _LIB
    _SORTED = getattr(_LIB, "cont_multipliers_sorted", None)
except ImportError:                         # pragma: no cover - not built
    _SORTED = None


def sort_multipliers(mu, trivial: bool = True) -> np.ndarray:
    """AUTO's order: the multiplier closest to 1 first (when the orbit has a trivial
    one), then by ||mu| - 1| (a stable sort: ties keep the order they came in)."""
    mu = np.asarray(mu, complex)
    if len(mu) == 0:
        return mu
    out = np.empty(len(mu), complex)
    if _SORTED is not None and mu.ndim == 1 and mu.flags.c_contiguous and _SORTED(
            len(mu), _FFI.from_buffer("double[]", mu), trivial,
            _FFI.from_buffer("double[]", out)) == 0:
        return out                  # csrc/cont/floquet.cpp: the same order, in one call
    with np.errstate(invalid="ignore"):
        if trivial:
            # np.nanargmin's choice (NaN distances never win; all NaN is an error),
            # without its wrappers: this runs at every point of a periodic branch
            d = np.abs(mu - 1)
            nan = np.isnan(d)
            if nan.all():
                raise ValueError("All-NaN slice encountered")
            i1 = int(np.argmin(np.where(nan, np.inf, d)))
            out[0] = mu[i1]
            mu = np.concatenate((mu[:i1], mu[i1 + 1:]))
        out[len(out) - len(mu):] = mu[np.argsort(np.abs(np.abs(mu) - 1), kind="stable")]
    return out


#: The imaginary unit as scipy.linalg._decomp's _geneig writes alpha = alphar + _I alphai
#: (the same bits, so that `_pencil_eigvals` is scipy.linalg.eigvals exactly).
_I = np.array(1j, dtype="F")
_GGEV = []
_GGEV_LWORK: dict = {}


def _scipy_linalg():
    """scipy.linalg, imported on first use (its import outweighs a short run; the import
    statement at every point costs a lookup and a check of the module's state)."""
    import scipy.linalg
    return scipy.linalg


def _pencil_eigvals(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """scipy.linalg.eigvals(A, B) for finite real square A, B: the same LAPACK calls
    (dggev's workspace query, made once per order, then dggev without vectors) and the
    same alpha / beta (beta = 0: inf, or nan when alpha = 0 too), without scipy's argument
    checks and wrappers (about 100 us a call; the multipliers are asked for at every
    point).
    Anything else (non-finite entries, LAPACK's failure) goes to scipy.linalg.eigvals,
    which raises what it raises."""
    A = np.asarray(A)
    B = np.asarray(B)
    if (A.dtype != np.float64 or B.dtype != np.float64 or A.ndim != 2 or A.shape != B.shape
            or A.shape[0] != A.shape[1] or A.size == 0
            or not (np.isfinite(A).all() and np.isfinite(B).all())):
        return _scipy_linalg().eigvals(A, B)
    if not _GGEV:
        _GGEV.append(_scipy_linalg().get_lapack_funcs(("ggev",), (A, B))[0])
    ggev = _GGEV[0]
    n = A.shape[0]
    lwork = _GGEV_LWORK.get(n)
    if lwork is None:        # LAPACK's workspace query: a function of the order alone
        lwork = _GGEV_LWORK[n] = ggev(A, B, lwork=-1)[-2][0].real.astype(np.int_)
    alphar, alphai, beta, _, _, _, info = ggev(A, B, 0, 0, lwork, False, False)
    if info != 0:
        return _scipy_linalg().eigvals(A, B)
    alpha = alphar + _I * alphai
    if beta.all():
        # no infinite eigenvalue (the common case): the quotients below, in one division
        return alpha / beta
    w = np.empty_like(alpha)
    alpha_zero = alpha == 0
    beta_zero = beta == 0
    beta_nonzero = ~beta_zero
    w[beta_nonzero] = alpha[beta_nonzero] / beta[beta_nonzero]
    w[~alpha_zero & beta_zero] = np.inf
    if np.all(alpha.imag == 0):
        w[alpha_zero & beta_zero] = np.nan
    else:
        w[alpha_zero & beta_zero] = complex(np.nan, np.nan)
    return w


def pencil_multipliers(P0: np.ndarray, P1: np.ndarray,
                       deflate_trivial: bool = False) -> np.ndarray:
    """Eigenvalues of the monodromy matrix -P1^-1 P0 (FLOWKM; P0, P1 from
    `washer.cont.reduction.floquet_pair`), as the generalized eigenvalues of the
    pencil (P0, -P1) by QZ, so that huge multipliers (long orbits near a homoclinic one)
    come out as large or infinite values instead of overflowing; infinite ones are inf.
    deflate_trivial: the orbit has a trivial multiplier (an autonomous periodic orbit),
    deflated first (`deflated_pencil`), as AUTO's FLOWKM does; a pencil without one (a
    forced or general linear system) must not be deflated: the null vector of C0 - C1
    is then no eigenvector and the deflation moves every multiplier.
    Sorted by `sort_multipliers`. Shape (NDIM,), complex."""
    if deflate_trivial:
        mu = _compiled_deflated_eigvals(P0, P1, sort=True)
        if mu is not None:
            return mu
    C0, C1 = np.asarray(P0, float), -np.asarray(P1, float)
    with np.errstate(all="ignore"):
        mu = _deflated_eigvals(C0, C1) if deflate_trivial else _pencil_eigvals(C0, C1)
    mu = np.where(np.isfinite(mu), mu, np.inf + 0j)
    return sort_multipliers(mu)


def deflated_pencil(C0: np.ndarray, C1: np.ndarray):
    """The circuit pencil (C0, C1) (n, n) with its multiplier at +1 split off
    (Fairgrieve and Jepson, SIAM J. Numer. Anal. 28 (1991), the method of AUTO's FLOWKM):
    X, the right singular vector of C0 - C1's smallest singular value (the trivial
    multiplier's eigenvector), is the last column of an orthogonal H1 = (X_perp | X); a
    Householder reflection H2 takes (C0 X / |C0 X| + C1 X / |C1 X|) / 2 to a multiple of
    e_1. Then H2 (C0, C1) H1 is block upper triangular up to the rounding of X, and the
    multipliers are (H2 C0 H1)[0, -1] / (H2 C1 H1)[0, -1] (the trivial one, real) and the
    eigenvalues of the pencil of rows 1.. and columns ..n-2. Why: on a family of
    conservative orbits (r3b's halo orbits) the trivial multiplier is double, with one
    eigenvector; the whole pencil's QZ splits such a pair into 1 +- i 1e-5 or 1 +- 1e-5 as
    its rounding falls, the deflated pencil leaves the second one real. Returns (the
    trivial multiplier, the deflated pencil's two (n - 1, n - 1) matrices)."""
    n = len(C0)
    _, _, vt = np.linalg.svd(C0 - C1)
    H1 = vt.T                       # its columns: the singular vectors, X last
    A = C0 @ H1
    B = C1 @ H1
    y = A[:, -1] / np.linalg.norm(A[:, -1]) + B[:, -1] / np.linalg.norm(B[:, -1])
    v = y.copy()
    v[0] += math.copysign(np.linalg.norm(y), y[0] if y[0] != 0 else 1.0)
    beta = 2.0 / float(v @ v)
    A -= beta * np.outer(v, v @ A)
    B -= beta * np.outer(v, v @ B)
    return A[0, -1] / B[0, -1], A[1:, :n - 1], B[1:, :n - 1]


def _deflated_eigvals(C0: np.ndarray, C1: np.ndarray) -> np.ndarray:
    """The pencil's eigenvalues with the trivial one deflated (`deflated_pencil`); the
    whole pencil's where it has no finite entries to deflate or is 1 x 1."""
    if len(C0) < 2 or not (np.isfinite(C0).all() and np.isfinite(C1).all()):
        return _pencil_eigvals(C0, C1)
    try:
        one, A, B = deflated_pencil(C0, C1)
    except np.linalg.LinAlgError:           # the SVD did not converge
        return _pencil_eigvals(C0, C1)
    if not (np.isfinite(one) and np.isfinite(A).all() and np.isfinite(B).all()):
        return _pencil_eigvals(C0, C1)      # C0 X or C1 X zero: nothing to deflate by
    return np.r_[complex(one), _pencil_eigvals(A, B)]


#: the compiled deflation and QZ (`compiled_routines`): empty until first asked, then
#: [None] (numpy and scipy serve) or [(ffi, lib, the routines' addresses)]
_COMPILED: list = []
#: GESDD's and DGGEV's workspace by order n, asked for by the first call of each n
_COMPILED_LWORK: dict = {}


def compiled_routines():
    """(ffi, lib, routines) of csrc/cont/floquet.cpp, or None where numpy's or scipy's
    bundled OpenBLAS or the compiled call is missing (washer.cont.lapack)."""
    if not _COMPILED:
        from washer.cont.lapack import floquet_routines
        found = floquet_routines()
        if found is None:
            _COMPILED.append(None)
        else:
            from washer._cont import ffi, lib
            _COMPILED.append((ffi, lib, ffi.new("void *[]", list(found))))
    return _COMPILED[0]


def _compiled_deflated_eigvals(P0, P1, sort: bool = False) -> np.ndarray | None:
    """`_deflated_eigvals(P0, -P1)` with non-finite values as inf, made by
    csrc/cont/floquet.cpp in one call (the same LAPACK and BLAS calls of numpy's and
    scipy's libraries, the same arithmetic: the same bits, without the Python around
    some fifteen numpy calls), or None where it does not serve: no compiled routines, not
    C-contiguous float64 square matrices of order >= 2, or a case the C++ leaves to the
    Python (nothing finite to deflate by, LAPACK's failure, infinite eigenvalues).
    sort: in AUTO's order (`sort_multipliers`, compiled in the same call)."""
    got = compiled_routines()
    if (got is None or type(P0) is not np.ndarray or type(P1) is not np.ndarray
            or P0.dtype != np.float64 or P1.dtype != np.float64 or P0.ndim != 2
            or P0.shape != P1.shape or P0.shape[0] != P0.shape[1] or P0.shape[0] < 2
            or not (P0.flags.c_contiguous and P1.flags.c_contiguous)):
        return None
    ffi, lib, routines = got
    n = P0.shape[0]
    lwork = _COMPILED_LWORK.get(n)
    if lwork is None:
        lwork = _COMPILED_LWORK[n] = ffi.new("int64_t[2]")
    mu = np.empty(n, complex)
    call = lib.cont_floquet_multipliers if sort else lib.cont_floquet_deflated
    rc = call(routines, n, ffi.from_buffer("double[]", P0), ffi.from_buffer("double[]", P1),
              ffi.from_buffer("double[]", mu), lwork)
    if rc == 5 and sort:
        return sort_multipliers(mu)          # the compiled sort left them: the Python's
    return mu if rc == 0 else None


def critical(mu: np.ndarray, trivial: bool = True) -> complex | None:
    """The nontrivial multiplier closest to the unit circle (mu_2 of AUTO's FNSPBV) of
    multipliers sorted by `sort_multipliers`, or None."""
    k = 1 if trivial else 0
    return complex(mu[k]) if len(mu) > k else None


def torus_pair(mu, trivial: bool = True) -> complex:
    """The complex multiplier (Im > 0) closest to the unit circle among the nontrivial
    ones, nan if all are real: the pair whose crossing of |mu| = 1 is a torus (TR)
    bifurcation; the analogue for multipliers mu = exp(lambda T) of the eigenvalue pair
    closest to the imaginary axis (washer.cont.systems.equilibrium.hopf_pair). Unlike
    `critical` (the nontrivial multiplier closest to the circle, real or complex: AUTO's
    mu_2, which types PD/TR), real multipliers are skipped."""
    mu = sort_multipliers(mu, trivial)[1 if trivial else 0:]
    cpx = mu[mu.imag > 0]
    cpx = cpx[np.abs(cpx.imag) > COMPLEX_TOL * (1 + np.abs(cpx))]
    return complex(cpx[0]) if cpx.size else complex(np.nan, np.nan)


def _kind(m: complex, epss: float) -> int:
    """TPSPBV's type of one multiplier: Code.TR if complex (|Im| > sqrt(EPSS)), Code.PD if
    real and below -0.5, else 0 (real above -0.5: no PD/TR through it)."""
    if not cmath.isfinite(m):
        return 0
    if abs(m.imag) > math.sqrt(epss):
        return int(Code.TR)
    if m.real < -0.5:
        return int(Code.PD)
    return 0


def classify(mu: np.ndarray, epss: float, trivial: bool = True) -> tuple[int, float | None]:
    """AUTO's TPSPBV + FNSPBV on sorted multipliers: (Code.PD / Code.TR / 0,
    |mu_2| - 1 or None); mu_2 is the nontrivial multiplier closest to the circle."""
    m2 = critical(mu, trivial)
    kind = 0 if m2 is None else _kind(m2, epss)
    return (kind, float(abs(m2) - 1)) if kind else (0, None)


def spb_test(mu: np.ndarray, epss: float, kinds: tuple, trivial: bool = True) -> float | None:
    """The combined PD/TR test: |mu| - 1 of the nontrivial multiplier closest to the circle
    among those TPSPBV types as one of `kinds` (sorted multipliers, so the first such),
    None if there is none.

    Where mu_2 (the closest of all) is of such a kind this is AUTO's FNSPBV, |mu_2| - 1.
    AUTO's test is undefined wherever mu_2 is real above -0.5, even while another real
    multiplier below -0.5 is crossing -1: a step from -1.956 to -0.916 that starts with
    +0.649 nearest the circle changes no defined sign and the PD is missed. Skipping the
    untyped multipliers keeps the test defined through such a step. A switch between two
    typed multipliers on either side of the circle can change its sign without a
    crossing; `accept` (the stable count must change) rejects that, as it does for
    AUTO's mu_2 switching."""
    k = 1 if trivial else 0
    for m in mu[k:]:
        m = complex(m)
        if _kind(m, epss) in kinds:
            return float(abs(m) - 1)
    return None


def torus_angle(mu: np.ndarray, epss: float, trivial: bool = True) -> float | None:
    """|arg mu_2| where TPSPBV classes the point as TR (AUTO writes it to PAR(12)), else None."""
    kind, _ = classify(mu, epss, trivial)
    if kind != Code.TR:
        return None
    m2 = critical(mu, trivial)
    return abs(math.atan2(m2.imag, m2.real))


def stability(mu: np.ndarray, ndim: int, suspended: bool, trivial: bool = True,
              tol: float = STABLE_TOL) -> Stability:
    """Stable count (AUTO's NINS) and notes of sorted multipliers (FNSPBV).

    n_stable counts the trivial multiplier plus the others with |mu| <= 1 + STABLE_TOL.
    While the trivial multiplier is inaccurate (|mu_1 - 1| > INACCURATE, until it is
    back below ACCURATE; `suspended` says whether it was at the previous point) NINS = 0
    with the note INACCURATE_NOTE. AUTO enters that state only when the multiplier
    nearest the circle is also of PD/TR type (otherwise it goes on counting the
    inaccurate multipliers: lrz's PT 28 is 'Stable: 3' in its d-file); this enters it
    whenever mu_1 is off, so such points are reported unstable, not stable. Without a
    trivial multiplier (forced orbits) NINS counts those with |mu| <= 1 + tol; `tol`
    (default AUTO's STABLE_TOL) is the multipliers' accuracy."""
    if not trivial:
        n_st = int(np.count_nonzero(np.abs(mu) <= 1 + tol))
        return Stability(values=mu, n_stable=n_st, stable=n_st == ndim, kind="multipliers")
    notes = []
    err = abs(mu[0] - 1) if len(mu) else 0.0
    # (count_nonzero: the count np.sum gives, without its Python wrapper; every point asks)
    n_st = 1 + int(np.count_nonzero(np.abs(mu[1:]) <= 1 + STABLE_TOL))
    if err > INACCURATE or (suspended and err >= ACCURATE):
        notes.append(INACCURATE_NOTE)
        n_st = 0
    elif suspended:
        notes.append("Multiplier accurate again")
    return Stability(values=mu, n_stable=n_st, stable=n_st == ndim, kind="multipliers",
                     notes=notes)


def newton_jacobian_serves(st: Stability | None, trivial: bool = True) -> bool:
    """Whether multipliers computed from the last Newton iteration's Jacobian serve as
    the point's: their trivial multiplier (first in AUTO's order) within NEWTON_TRIVIAL of
    1; always without multipliers (ISP = 0) or without a trivial one. (A double trivial
    multiplier, r3b's halo orbits, splits as the square root of the matrix's error: 1e-3
    to 2e-2 there from an iterate 1e-8 away, against 4e-5 from the Jacobian at the
    point; a long orbit near a homoclinic one amplifies the error as its multipliers
    grow.)"""
    if st is None or not trivial or len(st.values) == 0:
        return True
    return bool(abs(st.values[0] - 1) <= NEWTON_TRIVIAL)


def inaccurate(st: Stability | None) -> bool:
    """Whether the stability `st` carries AUTO's "Multiplier inaccurate" note."""
    return st is not None and INACCURATE_NOTE in st.notes


def active_tests(settings, ndim: int, trivial: bool = True) -> list:
    """LP of cycles (ILP), BP of cycles (|ISP| >= 2, != 4), PD and TR (ISP in {2, 4},
    at least two nontrivial multipliers: NDIM > 2 for autonomous orbits), as
    support.f90:CHECKSP, SP overriding (Settings.detects)."""
    out = []
    if settings.detects("LP"):
        out.append(int(Code.LPC))
    if settings.detects("BP"):
        out.append(int(Code.BPC))
    if ndim - trivial >= 2 and (settings.detects("PD") or settings.detects("TR")):
        out.append(SPB)
    return out


def spb_kinds(settings) -> tuple:
    """The kinds (Code.PD, Code.TR) the combined test reports under `settings` (kept for
    the last settings asked about: they are frozen, and every point of a run asks)."""
    kept = _SPB_KINDS
    if kept[0] is not settings:
        kept[:] = [settings, tuple(int(c) for c, name in ((Code.PD, "PD"), (Code.TR, "TR"))
                                   if settings.detects(name))]
    return kept[1]


#: spb_kinds' last (settings, kinds)
_SPB_KINDS: list = [None, ()]
#: the codes of `test_functions` as ints (an IntEnum's int() at every point costs)
_LPC, _BPC = int(Code.LPC), int(Code.BPC)


def spb_code(key, stability: Stability | None, epss: float, trivial: bool = True):
    """The written base code of a located zero of test `key`: for SPB, PD or TR as TPSPBV
    classes the multipliers at the located point; any other key is its own code."""
    if key != SPB or stability is None:
        return key
    kind, _ = classify(stability.values, epss, trivial)
    return kind or key


def test_functions(codes, tangent, st: Stability | None, epss: float, ndim: int,
                   bp: Callable[[], float | None] | None = None,
                   kinds: tuple = (int(Code.PD), int(Code.TR)), trivial: bool = True) -> dict:
    """{Code.LPC, Code.BPC, SPB: value or None} for the requested codes.

    tangent : the unit tangent (its last component is PAR(ICP(1))-dot) or None.
    st : the point's Stability (sorted multipliers) or None.
    bp : computes the system's BP determinant; called only when BPC is asked for, the
        tangent is known and the multipliers are accurate (while the trivial multiplier
        is inaccurate, long orbits near a homoclinic one, the reduced determinant is
        roundoff: lrz's grows to 1e46 and flips sign at T ~ 300 and 850; AUTO keeps
        testing there and its value happens not to flip; BP of cycles is not reported).
    kinds : the kinds of the combined test being detected (`spb_kinds`): at a point of
        another kind it is undefined (AUTO's CHECKSP sets ITP = 0, so no D).
    """
    codes = [int(c) for c in codes]
    out = {}
    if _LPC in codes:
        out[_LPC] = fold_test(tangent)
    if _BPC in codes:
        out[_BPC] = None if (tangent is None or inaccurate(st) or bp is None) else bp()
    if SPB in codes:
        d = None
        if ndim - trivial >= 2 and st is not None and not inaccurate(st):
            d = spb_test(st.values, epss, kinds, trivial)
        out[SPB] = d
    return out


def accept(code: int, prev, cur, ndim: int, trivial: bool = True) -> bool:
    """PD/TR (the combined test SPB) only if the stable count changed (FNSPBV: NINS1 ==
    NINS -> no point), never with fewer than two nontrivial multipliers. LP/BP of
    cycles and UZ always."""
    if code in (SPB, Code.TR):
        if ndim - trivial < 2 or prev.stability is None or cur.stability is None:
            return False
        return prev.stability.n_stable != cur.stability.n_stable
    return True


# ---------------------------------------------------------------- tests on the loci
#: The torus angles of the strong resonances on a TR locus: (base code, angle). AUTO's
#: FNSPBV tests theta (theta - pi/2) (theta - 2 pi/3) (theta - pi) and types the located
#: zero by NINT(6 theta / pi) (TPSPBV); here each resonance is its own test, so each zero
#: is located and typed by the test that vanishes.
RESONANCES = ((int(Code.R1), 0.0), (int(Code.R4), math.pi / 2), (int(Code.R3), 2 * math.pi / 3),
              (int(Code.R2), math.pi))
#: FNSPBV's window for the 1:2 resonance on PD loci: mu_2 within this of -1.
R2_WINDOW = 5e-2


def torus_resonance_tests(theta: float, codes) -> dict:
    """{R1, R4, R3, R2: test} for the requested codes (TR loci).

    The 1:q resonance is exp(i theta)^q = 1: theta = +-2 pi/q modulo 2 pi. For theta in
    [0, pi] the tests are AUTO's factors theta - a (a = 0, pi/2, 2 pi/3, pi); beyond, they
    go on periodically, so that each vanishes, with a sign change, wherever the angle
    passes a resonance:

        R1: 2 asin(sin(theta / 2))           (theta on [-pi, pi])
        R2: 2 asin(sin((theta - pi) / 2))    (theta - pi on [0, 2 pi])
        R4, R3: arccos(cos(theta)) - a       (the angle folded onto [0, pi])

    The angle a locus carries is continued through pi (the locus passes the R2 point
    turning back along itself in the parameters, theta going on to 2 pi - a) and through
    0: there each resonance recurs at 2 pi - a or -a, where AUTO's product, zero only at
    0, pi/2, 2 pi/3, pi themselves, misses it."""
    folded = math.acos(max(-1.0, min(1.0, math.cos(theta))))
    values = {int(Code.R1): 2 * math.asin(math.sin(theta / 2)),
              int(Code.R2): 2 * math.asin(math.sin((theta - math.pi) / 2)),
              int(Code.R4): folded - math.pi / 2, int(Code.R3): folded - 2 * math.pi / 3}
    return {code: values[code] for code, _ in RESONANCES if code in codes}


def sort_on_pd_locus(mu) -> np.ndarray:
    """FNSPBV's order on a PD locus: the multiplier nearest 1, the one nearest -1, then
    the others by distance from the unit circle."""
    mu = np.asarray(mu, complex)
    i1 = int(np.argmin(np.abs(mu - 1)))
    rest = np.delete(mu, i1)
    i2 = int(np.argmin(np.abs(rest + 1)))
    others = np.delete(rest, i2)
    others = others[np.argsort(np.abs(np.abs(others) - 1), kind="stable")]
    return np.r_[mu[i1], rest[i2], others]


def resonance_12_test(mu, epss: float) -> float | None:
    """The 1:2 resonance on a PD locus (FNSPBV with ITPST = 7): |mu_3| - 1 where mu
    (sorted by `sort_on_pd_locus`) has mu_2 within R2_WINDOW of -1 and mu_3 real (to
    sqrt(sqrt(EPSS))) and negative; else undefined."""
    if len(mu) < 3:
        return None
    if abs(mu[2].imag) < math.sqrt(math.sqrt(epss)) and mu[2].real < 0 \
            and abs(mu[1] + 1) < R2_WINDOW:
        return float(abs(mu[2]) - 1)
    return None


def stable_count(mu) -> int:
    """Multipliers with |mu| <= 1 + STABLE_TOL (every one counted, AUTO's NINS1 on loci)."""
    return int(np.sum(np.abs(np.asarray(mu)) <= 1 + STABLE_TOL))
