"""Linear algebra of the continuation: the bordered Newton matrix [J; border] and
its factorisations (AUTO's GEL for dense algebraic systems, SuperLU for the sparse
collocation matrices), null vectors, and the orientation rule of a fresh tangent.

Every factorisation honours `Factor`: `.solve(rhs)` and `.sign_logdet()` (AUTO's BP
test on algebraic branches is the determinant of the bordered matrix).
"""
from __future__ import annotations

import cmath
import math
import threading
import warnings
from typing import TYPE_CHECKING, Protocol

import numpy as np

# scipy is imported where it is used: its import (scipy.linalg above all) costs more
# than a whole short run of a small problem, which needs none of it.
if TYPE_CHECKING:                  # annotations only
    import scipy.sparse as sp

#: SuperLU column ordering: minimum degree on A^T + A. Measured on lrz's bordered
#: collocation matrices (N = 425 / 1805): 0.7 / 3.9 ms per factorisation, fill 8.8e3 /
#: 3.6e4, against 2.1 / 15.7 ms for the default COLAMD and 2.7 / 36 ms for the natural
#: order (the dense border, phase and parameter rows/columns ruin the band otherwise).
PERMC_SPEC = "MMD_AT_PLUS_A"


# numpy's LAPACK gufuncs (gesv, getrf for the determinant, geev), called without the
# Python wrappers of numpy.linalg: at the sizes of algebraic continuation (N < 20) the
# wrappers' type dispatch, checks and error-state contexts cost 3 to 5 times the LAPACK
# call (np.linalg.eigvals 19 us against 3.5 us for a 2 x 2 matrix), and an equilibrium
# point takes about six of these calls. The same routines give the same values; without
# the module (another numpy) the public functions are used.
try:
    from numpy.linalg import _umath_linalg as _lapack
    _GESV, _SLOGDET, _EIGVALS, _EIG = (_lapack.solve1, _lapack.slogdet, _lapack.eigvals,
                                       _lapack.eig)
except (ImportError, AttributeError):       # pragma: no cover - another numpy
    _lapack = None


# numpy's floating-point error state set to "ignore" for one call: np.errstate builds its
# state object on every entry (about 3 us, a fortieth of an equilibrium point, where the
# tangent's solve is made quiet); the same state built once and set through numpy's
# context variable is the same behaviour. Without it (another numpy) np.errstate serves.
try:
    from numpy._core._ufunc_config import _extobj_contextvar as _FP_STATE
    from numpy._core.umath import _make_extobj
    _FP_IGNORE = _make_extobj(all="ignore")
except (ImportError, AttributeError, TypeError):    # pragma: no cover - another numpy
    _FP_STATE = None


def quietly(fn, *args):
    """fn(*args) with numpy's floating-point errors ignored (as inside
    np.errstate(all="ignore")): no warning for a NaN from a singular solve."""
    if _FP_STATE is None:                   # pragma: no cover
        with np.errstate(all="ignore"):
            return fn(*args)
    token = _FP_STATE.set(_FP_IGNORE)
    try:
        return fn(*args)
    finally:
        _FP_STATE.reset(token)


def solve(M: np.ndarray, b: np.ndarray) -> np.ndarray:
    """np.linalg.solve(M, b) for a square M (n, n) and b (n,), real or complex, except that
    a singular M gives NaN (and the floating-point 'invalid' flag: a warning where they
    are on, outside a run) instead of LinAlgError."""
    if _lapack is None:                     # pragma: no cover
        try:
            return np.linalg.solve(M, b)
        except np.linalg.LinAlgError:
            return np.full(len(b), np.nan)
    cplx = _complex(M) or _complex(b)
    return _GESV(M, b, signature="DD->D" if cplx else "dd->d")


def _complex(a) -> bool:
    """np.iscomplexobj(a), an array's dtype read directly (the function's dispatch costs
    more than the check at these sizes)."""
    return a.dtype.kind == "c" if type(a) is np.ndarray else np.iscomplexobj(a)


def slogdet(M: np.ndarray) -> tuple[float, float]:
    """np.linalg.slogdet of a real square M: (sign, log|det|), (0, -inf) if singular."""
    if _lapack is None:                     # pragma: no cover
        sign, logdet = np.linalg.slogdet(M)
    else:
        sign, logdet = _SLOGDET(M, signature="d->dd")
    return float(sign), float(logdet)


def scaled_slogdet(S: np.ndarray) -> tuple[float, float, float] | tuple[float]:
    """(scale, sign, log|det|) of a real square S: scale = np.linalg.norm(S) (Frobenius),
    (sign, log|det|) = np.linalg.slogdet(S / scale), (0, -inf) if that is singular; (scale,)
    alone where scale is 0 or not finite. One compiled call (csrc/cont/dense_lapack.cpp
    cont_scaled_slogdet: numpy's own CBLAS DDOT and GETRF, numpy's values bit for bit)
    where numpy's OpenBLAS is found, else numpy's calls."""
    n = len(S)
    if _C is None or type(S) is not np.ndarray or S.dtype != np.float64 \
            or not S.flags.c_contiguous or S.shape != (n, n) or n == 0:
        scale = float(np.linalg.norm(S))
        if not math.isfinite(scale) or scale == 0:
            return (scale,)
        return (scale,) + slogdet(S / scale)
    ffi = _C.ffi
    bufs = _SLOGDET_BUFFERS.__dict__.get(n)
    if bufs is None:
        bufs = _SLOGDET_BUFFERS.__dict__[n] = (ffi.new("double[]", 2 * n * n),
                                               ffi.new("int64_t[]", n), ffi.new("double[3]"))
    work, ipiv, out = bufs
    rc = _C.lib.cont_scaled_slogdet(_C.getrf, _C.ddot, n, ffi.from_buffer("double[]", S),
                                    work, ipiv, out)
    if rc == 1:
        return (out[0],)
    return out[0], out[1], out[2]


#: scaled_slogdet's work buffers by size, one set a thread (cffi's call releases the GIL)
_SLOGDET_BUFFERS = threading.local()


#: Up to this many entries the finite checks run on Python floats (numpy's per-call
#: overhead of isfinite and all exceeds the whole check at these sizes).
SMALL = 64


def all_finite(a: np.ndarray) -> bool:
    """np.isfinite(a).all() for a real or complex array: on Python numbers up to SMALL
    entries (a small problem's f, a bordered solve's solution), by numpy above."""
    if a.size <= SMALL:
        # math's test where it can (cmath's costs half as much again per value)
        return all(map(cmath.isfinite if a.dtype.kind == "c" else math.isfinite,
                       a.ravel().tolist()))
    return bool(np.isfinite(a).all())


def eigvals(A: np.ndarray) -> np.ndarray:
    """np.linalg.eigvals of a real square A: real if every eigenvalue is, else complex.
    LinAlgError for non-finite entries or when the QR iteration does not converge."""
    if _lapack is None:                     # pragma: no cover
        return np.linalg.eigvals(A)
    if not all_finite(A):
        raise np.linalg.LinAlgError("Array must not contain infs or NaNs")
    w = _EIGVALS(A, signature="d->D")
    if A.size <= SMALL:
        zs = w.tolist()                     # all_finite's check, and the real check below
        if not all(map(cmath.isfinite, zs)):
            raise np.linalg.LinAlgError("Eigenvalues did not converge")
        return w.real if all(z.imag == 0 for z in zs) else w
    if not np.isfinite(w).all():
        raise np.linalg.LinAlgError("Eigenvalues did not converge")
    return w.real if (w.imag == 0).all() else w


def eigenvalues_sorted(A: np.ndarray, leading: bool = False) -> np.ndarray:
    """`eigvals` of A (n, n) by decreasing real part (a stable sort: equal real parts keep
    LAPACK's order): the order of an equilibrium's eigenvalues in the engine's stability
    (systems.equilibrium) and in a compiled user file's PVLS. leading: A is (n, m), m >= n,
    and the eigenvalues are those of its leading block A[:, :n] (f_u of [f_u, f_PAR]).
    Up to EIG_MAX rows in one compiled call (csrc/cont/dense_lapack.cpp: numpy's own GEEV
    as numpy.linalg.eigvals calls it, the same values, the same errors)."""
    n = len(A)
    if n <= EIG_MAX and _C is not None and type(A) is np.ndarray \
            and (A.dtype is _F64 or A.dtype == np.float64) \
            and A.ndim == 2 and (A.shape[1] == n or leading and A.shape[1] > n):
        if not A.flags.c_contiguous:
            A = np.ascontiguousarray(A)
        call, geev, work, wptr, lwork, real, pairs = \
            _EIG_BUFFERS.__dict__.get(n) or _eig_buffers(n)
        status = call(geev, n, _C.ffi.from_buffer("double[]", A), A.shape[1], wptr, work,
                      EIG_WORK * n, lwork)
        if status == 4:                     # all real: the real parts, as eigvals' w.real
            return real.copy()
        if status == 0:
            return pairs.copy()
        if status == 1:
            raise np.linalg.LinAlgError("Array must not contain infs or NaNs")
        if status == 2:
            raise np.linalg.LinAlgError("Eigenvalues did not converge")
        # (3: a workspace beyond the buffer's: numpy's call below)
    if leading:
        A = A[:, :n]
    lam = eigvals(A)
    re = lam.real.tolist()
    # Python's sort is stable as argsort(kind="stable") is, and stays so reversed (equal
    # real parts keep their order): the order of a stable sort by -Re, without numpy's
    # per-call overhead at the sizes of equilibria
    return lam[sorted(range(len(re)), key=re.__getitem__, reverse=True)]


#: Sizes up to which eigenvalues_sorted and DenseFactor call LAPACK from C (beyond, the
#: LAPACK work outweighs numpy's per-call overhead).
EIG_MAX = 60


class _Compiled:
    """washer._cont's ffi and lib with the addresses of numpy's GETRF, GETRS, GEEV, CBLAS
    DDOT and GESDD (washer.cont.lapack)."""

    def __init__(self, ffi, lib, routines):
        self.ffi, self.lib = ffi, lib
        self.getrf, self.getrs, self.geev, self.ddot, self.gesdd = routines
        # cont_fold_tests' routines (GESDD, DDOT, GEEV), kept alive with this object
        self.fold_routines = ffi.new("void *[3]", [self.gesdd, self.ddot, self.geev])
        # cont_ae_equilibrium_point's routines (GETRF, GETRS, GEEV)
        self.point_routines = ffi.new("void *[3]", [self.getrf, self.getrs, self.geev])


#: eigenvalues_sorted's buffers by size, one set a thread (cffi's call releases the GIL)
_EIG_BUFFERS = threading.local()


def _dense() -> _Compiled | None:
    """The compiled dense LAPACK calls where washer._cont and numpy's bundled OpenBLAS
    are both there, else None: numpy.linalg's gufuncs serve."""
    from washer.cont.lapack import routines
    found = routines()
    if found is None:
        return None
    from washer._cont import ffi, lib
    return _Compiled(ffi, lib, found)


#: the compiled calls of this process (`_dense`), or None
_C: _Compiled | None = _dense()


def compiled_lapack() -> _Compiled | None:
    """The compiled dense LAPACK calls of this process (washer._cont's ffi and lib, the
    routines' addresses), or None where numpy.linalg's gufuncs serve."""
    return _C


#: GEEV's workspace in eigenvalues_sorted's buffers: EIG_WORK n doubles (its optimum
#: is 34 n at these sizes: 2 n + n times DGEHRD's block size 32)
EIG_WORK = 64


def _eig_buffers(n: int):
    """(cont_eigenvalues_sorted, GEEV, work, out's pointer, GEEV's lwork, out's real parts,
    out as complex values) for size n, out (2 n,) the (re, im) pairs the call writes, made
    once per size and thread; lwork starts at 0: the first call asks GEEV (as numpy asks
    it at every call) and keeps its answer."""
    ffi = _C.ffi
    buf = np.empty(2 * n)
    work = ffi.new("double[]", n * n + 2 * n + EIG_WORK * n)
    got = _EIG_BUFFERS.__dict__[n] = (_C.lib.cont_eigenvalues_sorted, _C.geev, work,
                                      ffi.from_buffer("double[]", buf), ffi.new("int *", 0),
                                      buf[0::2], buf.view(np.complex128))
    return got


#: float64's dtype (arrays of native doubles carry this object)
_F64 = np.dtype(np.float64)


def eig(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """np.linalg.eig of a real square A: (eigenvalues, eigenvectors as columns), real if
    every eigenvalue is, else complex. LinAlgError as `eigvals`."""
    if _lapack is None:                     # pragma: no cover
        return tuple(np.linalg.eig(A))
    if not np.isfinite(A).all():
        raise np.linalg.LinAlgError("Array must not contain infs or NaNs")
    w, v = _EIG(A, signature="d->DD")
    if not np.isfinite(w).all():
        raise np.linalg.LinAlgError("Eigenvalues did not converge")
    if (w.imag == 0).all():
        return w.real, v.real
    return w, v


class Factor(Protocol):
    """A factorisation of a square (N + 1) x (N + 1) matrix [J; border]: `solve(rhs)` with
    rhs (N + 1,) -> (N + 1,), `sign_logdet()` -> (sign, log|det|) (the BP test)."""
    def solve(self, rhs: np.ndarray) -> np.ndarray: ...
    def sign_logdet(self) -> tuple[float, float]: ...


class DenseFactor:
    """A dense square system [J; border] (AUTO's GEL: Gaussian elimination with
    pivoting). Small systems are LU-factorised once by numpy's own GETRF called from C
    (csrc/cont/dense_lapack.cpp), whose GETRS solves then give numpy.linalg.solve's
    (GESV's) values and whose diagonal numpy.linalg.slogdet's determinant, bit for bit,
    without numpy's per-call overhead; without that call (another numpy's LAPACK), by
    numpy's GESV on each solve. Larger ones are LU-factorised through scipy for
    Newton-chord reuse."""

    #: Above this size the LU factors are kept for repeated solves.
    LU_SIZE = 60

    def __init__(self, M: np.ndarray | None, J: np.ndarray | None = None,
                 border: np.ndarray | None = None):
        """M (n, n), or M = None with J (n - 1, n) and border (n,): M = [J; border]
        (made only where a numpy call needs it: `M`)."""
        self._M, self._J, self._border = M, J, border
        self.lu = None
        self._c = None        # the compiled LU: (lu, pivots, (sign, log|det|), GETRF's info)
        n = len(M) if M is not None else len(border)
        if n > self.LU_SIZE:
            import scipy.linalg
            with warnings.catch_warnings():
                # An exactly singular matrix (at a branch point) is handled in solve().
                warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
                self.lu = scipy.linalg.lu_factor(self.M, check_finite=False)
            return
        if _C is None:
            return
        rows, last = (M, _C.ffi.NULL) if M is not None else (J, border)
        if type(rows) is np.ndarray and rows.dtype == np.float64 and rows.flags.c_contiguous \
                and rows.shape == (n - (M is None), n) and (M is not None or (
                    type(border) is np.ndarray and border.dtype == np.float64
                    and border.shape == (n,))):
            ffi = _C.ffi
            lu, ipiv, sl = ffi.new("double[]", n * n), ffi.new("int64_t[]", n), \
                ffi.new("double[2]")
            info = _C.lib.cont_dense_lu(
                _C.getrf, n, ffi.from_buffer("double[]", rows), n,
                last if M is not None else ffi.from_buffer("double[]", border), lu, ipiv, sl)
            # a singular M (GETRF's info > 0) leaves its solves to numpy's GESV: NaN and
            # the floating-point flag as before
            self._c = (lu, ipiv, (sl[0], sl[1]), info)

    @classmethod
    def factored(cls, J: np.ndarray, border: np.ndarray, c: tuple) -> "DenseFactor":
        """[J; border] with its compiled LU c = (lu, pivots, (sign, log|det|), GETRF's info)
        already made (`unit_tangent`)."""
        f = cls.__new__(cls)
        f._M, f._J, f._border, f.lu, f._c = None, J, border, None, c
        return f

    @property
    def M(self) -> np.ndarray:
        """The matrix (n, n)."""
        if self._M is None:
            J = np.asarray(self._J)
            M = np.empty((len(J) + 1, J.shape[1]))
            M[:-1] = J
            M[-1] = self._border
            self._M = M
        return self._M

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        c = self._c
        if c is not None and c[3] == 0 and type(rhs) is np.ndarray \
                and rhs.dtype == np.float64 and rhs.flags.c_contiguous:
            ffi = _C.ffi
            x = np.empty(len(rhs))
            if _C.lib.cont_dense_lu_solve(_C.getrs, len(x), c[0], c[1],
                                          ffi.from_buffer("double[]", rhs),
                                          ffi.from_buffer("double[]", x)) == 0:
                return x
        try:
            if self.lu is not None:
                import scipy.linalg
                x = scipy.linalg.lu_solve(self.lu, rhs, check_finite=False)
            else:
                x = solve(self.M, rhs)
        except np.linalg.LinAlgError:
            x = np.full(len(rhs), np.nan)
        if not all_finite(x):
            # Exactly at a branch point the Newton matrix is singular but the
            # system is consistent: take the minimum-norm least-squares step.
            x = np.linalg.lstsq(self.M, rhs, rcond=None)[0]
        return x

    def sign_logdet(self) -> tuple[float, float]:
        if self._c is not None:
            return self._c[2]
        return slogdet(self.M)


def unit_tangent(J, theta: np.ndarray, ref: np.ndarray, big: float):
    """The tangent of a dense algebraic point in one compiled call (cont_ae_tangent): the
    DenseFactor of [J; theta * ref] (J (n - 1, n)) and z = [J; theta ref]^-1 e_n made unit
    in the weighted inner product <a, b> = sum(theta * a * b): (t, factor, True), the same
    values as factor.solve, the inner product summed as numpy sums it and the division;
    (None, factor, False) where z is not that tangent (GETRF's exact zero pivot, z not
    finite, its norm 0, not finite or above big): the caller's way on from factor. None
    where the call does not apply (no compiled LAPACK, sizes, types)."""
    n = len(ref)
    if _C is None or n > DenseFactor.LU_SIZE or type(J) is not np.ndarray \
            or J.dtype != np.float64 or J.shape != (n - 1, n) or not J.flags.c_contiguous \
            or type(ref) is not np.ndarray or ref.dtype != np.float64 \
            or not ref.flags.c_contiguous or theta.shape != (n,):
        return None
    border, t = np.empty(n), np.empty(n)
    got = _TANGENT_SCRATCH.__dict__.get("last")
    if got is None or got[0] is not theta:
        got = _tangent_scratch(theta)
    _, theta_c, sl, info, call, getrf, getrs, new, buf = got
    # the factors stay with the DenseFactor (its later solves); the determinant's sign and
    # logarithm and GETRF's info are read at once, from the thread's scratch
    lu, ipiv = new("double[]", n * n + n), new("int64_t[]", n)
    status = call(getrf, getrs, n, buf("double[]", J), n, buf("double[]", ref), theta_c, big,
                  buf("double[]", border), lu, ipiv, sl, info, buf("double[]", t))
    if status < 0:
        return None
    factor = DenseFactor.factored(J, border, (lu, ipiv, (sl[0], sl[1]), info[0]))
    return (t, factor, True) if status == 0 else (None, factor, False)


#: unit_tangent's scratch of this thread (`_tangent_scratch`), made for the weights theta
#: of its last call: a run passes the same theta at every point.
_TANGENT_SCRATCH = threading.local()


def _tangent_scratch(theta: np.ndarray) -> tuple:
    """(theta, a pointer to its data, sign_logdet (2,), info, cont_ae_tangent, GETRF, GETRS,
    ffi.new, ffi.from_buffer) for unit_tangent in this thread (theta kept with its
    pointer: the array stays alive while the pointer is used)."""
    ffi = _C.ffi
    got = _TANGENT_SCRATCH.last = (theta, ffi.from_buffer("double[]", theta),
                                   ffi.new("double[2]"), ffi.new("int *"),
                                   _C.lib.cont_ae_tangent, _C.getrf, _C.getrs, ffi.new,
                                   ffi.from_buffer)
    return got


def dense_factor(J, border: np.ndarray) -> DenseFactor:
    """Default `factor`: LU of [J; border] for dense J."""
    if _C is not None and type(J) is np.ndarray:
        return DenseFactor(None, J, border)
    J = np.asarray(J)
    M = np.empty((len(J) + 1, J.shape[1]))
    M[:-1] = J
    M[-1] = border
    return DenseFactor(M)


class SparseFactor:
    """SuperLU factorisation (scipy.sparse.linalg.splu) of the bordered collocation
    matrix, with the determinant's sign and log-magnitude (for the contract)."""

    def __init__(self, M: sp.csc_matrix):
        import scipy.sparse.linalg as spla
        self.M = M
        try:
            self.lu = spla.splu(M, permc_spec=PERMC_SPEC)
        except RuntimeError:
            # Exactly singular: at a Hopf start point the period column T f(u_HB) is 0
            # (constant solutions exist for every T). Solves fall back to least squares.
            self.lu = None

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        if self.lu is None:
            return np.linalg.lstsq(self.M.toarray(), np.asarray(rhs, float), rcond=None)[0]
        return self.lu.solve(np.asarray(rhs, float))

    def sign_logdet(self) -> tuple[float, float]:
        if self.lu is None:
            return 0.0, -np.inf
        d = self.lu.U.diagonal()
        if np.any(d == 0):
            return 0.0, -np.inf
        sign = (permutation_sign(self.lu.perm_r) * permutation_sign(self.lu.perm_c)
                * np.prod(np.sign(d)))
        return float(sign), float(np.sum(np.log(np.abs(d))))


def permutation_sign(p: np.ndarray) -> float:
    """Sign (+1/-1) of the permutation i -> p[i], an index array (n,) (by its cycles: a
    sparse LU's perm_r/perm_c enter the sign of its determinant)."""
    p = np.asarray(p)
    seen = np.zeros(len(p), bool)
    sign = 1.0
    for i in range(len(p)):
        if seen[i]:
            continue
        j, length = i, 0
        while not seen[j]:
            seen[j] = True
            j = p[j]
            length += 1
        if length % 2 == 0:
            sign = -sign
    return sign


def null_vectors(A: np.ndarray, k: int) -> np.ndarray:
    """k right singular vectors of the smallest singular values, shape (cols, k). A real
    matrix goes to np.linalg.svd's own LAPACK call (the same vectors) without its
    wrappers, which cost more than the call at the loci's sizes."""
    if _lapack is not None and isinstance(A, np.ndarray) and A.dtype == np.float64 \
            and A.ndim == 2 and A.size:
        with np.errstate(invalid="ignore"):
            _, s, Vt = _lapack.svd_f(A, signature="d->ddd")
        if np.isnan(s).any():
            raise np.linalg.LinAlgError("SVD did not converge")
        return Vt[-k:].T
    _, _, Vt = np.linalg.svd(A)
    return Vt[-k:].T


def tall_null_vector(M) -> np.ndarray:
    """The unit right singular vector of the smallest singular value of a sparse
    matrix M (m x k, m >= k) that is nearly rank-deficient by one (the collocated
    adjoint equations at a located BP of a BVP or of cycles): inverse iteration on
    M^T M (sparse, banded for a collocation matrix) shifted by 1e-13 of its largest
    entry, where a dense SVD would cost O(m k^2). The shift is far below the next singular value squared, so
    each iteration gains that ratio; rounding in M^T M (~eps |M|^2) moves the vector
    by ~eps over that gap."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    M = sp.csr_matrix(M)
    A = (M.T @ M).tocsc()
    shift = 1e-13 * abs(A).max()
    lu = spla.splu((A + shift * sp.identity(A.shape[0], format="csc")).tocsc(),
                   permc_spec=PERMC_SPEC)
    z = np.ones(A.shape[0]) / np.sqrt(A.shape[0])
    for _ in range(4):
        z = lu.solve(z)
        z /= np.linalg.norm(z)
    return z


def nullvc(A: np.ndarray, k: int) -> np.ndarray:
    """A null vector of the m x n matrix A with a k-dimensional null space, chosen as
    AUTO's NULLVC chooses it (support.f90): Gaussian elimination with complete pivoting
    over the first n - k pivots, then the last k unknowns of the pivoted order set to 1
    and the others back-substituted. Where the null space has more than one dimension
    this fixes WHICH null vector: the Hopf start of cycles (STHOPF) takes its phase
    from it, and everything computed downstream that is not phase invariant (a
    boundary condition at t = 0 of an extended BVP, pcl's PAR(13) = |v(0)|^2) follows
    that phase."""
    a = np.array(A, dtype=float)
    m, n = a.shape
    cpiv = np.arange(n)
    amax = 0.0
    for jj in range(n - k):
        sub = np.abs(a[jj:, jj:])
        # Fortran's loop keeps the first strict maximum in row-major order (i, then j).
        flat = int(np.argmax(sub))
        i, j = divmod(flat, sub.shape[1])
        piv = sub[i, j]
        ip, jp = jj + i, jj + j
        if jj == 0:
            amax = piv
        if piv <= amax / np.finfo(float).max:
            a[ip, jp] = max(amax / np.finfo(float).max, np.finfo(float).tiny)
        if ip != jj:
            a[[jj, ip], :] = a[[ip, jj], :]
        cpiv[jj] = jp
        if jp != jj:
            a[:, [jj, jp]] = a[:, [jp, jj]]
        rm = a[jj + 1:, jj] / a[jj, jj]
        a[jj + 1:, jj + 1:] -= np.outer(rm, a[jj, jj + 1:])
    u = np.zeros(n)
    u[n - k:] = 1.0
    for i in range(n - k - 1, -1, -1):
        u[i] = -(a[i, i + 1:] @ u[i + 1:]) / a[i, i]
    for i in range(n - k - 1, -1, -1):
        j = cpiv[i]
        if j != i:
            u[i], u[j] = u[j], u[i]
    return u


def orient(t: np.ndarray, x: np.ndarray, nfpr: int, epsl: float, epsu: float) -> np.ndarray:
    """AUTO-07p's sign rule for the start direction of an algebraic run (ae.f90 STPRAE,
    every IPERP: a fresh null vector, the null vector of [f_u f_p; stored direction], or
    the stored direction itself), for t of unit length and the point x, both laid out as
    AUTO's U(1..NDIM + 1): PAR(ICP(1)) last, PAR(ICP(2..NFPR)) in U(NDIM - NFPR + 2..NDIM).
    PAR(ICP(1))-dot is made positive where |t_last| / (1 + |x_last|) > EPSL; where it is
    not (rounding at a pitchfork, a fold in PAR(ICP(1))), the first of U(NDIM - NFPR + 2
    ..NDIM), then U(1..NDIM - NFPR + 1), with |t_j| / (1 + |x_j|) > EPSU is made positive
    (AUTO-07p 0.9.2: a restart on a branch-point locus whose PAR(1)-dot is 1e-163 goes the
    same way whatever that rounding's sign). Nothing above the thresholds: t as given."""
    n = len(t) - 1
    if abs(t[n]) / (1 + abs(x[n])) > epsl:
        return -t if t[n] < 0 else t
    for j in [*range(n - nfpr + 1, n), *range(n - nfpr + 1)]:
        if abs(t[j]) / (1 + abs(x[j])) > epsu:
            return -t if t[j] < 0 else t
    return t
