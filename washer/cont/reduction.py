"""The bordered collocation matrix factorised the way AUTO-07p does it, compiled
(csrc/cont/reduce.cpp, the module washer._cont): condensation of parameters (CONPAR),
the reduction of the chain of intervals (REDUCE) and the remaining dense system in
(U(0), U(1), parameters) (DIMRGE), one elimination that gives

* solves of the Newton and tangent systems (any number of right-hand sides; each with
  one step of iterative refinement against the matrix as given: the pivoting confined
  to the blocks lets the elimination grow more than LAPACK's),
* the determinant's sign and log-magnitude (the BP test of cycles),
* the pair (P0, P1) with P0 U(0) + P1 U(1) = 0 on the collocation rows with the
  parameters held: the Floquet multipliers are the eigenvalues of -P1^-1 P0
  (floquet.pencil_multipliers), without a second condensation.

The matrix layout is washer.cont.collocation.Collocation's: `BorderedCollocation.from_jacobian`
takes its sparse Jacobian (the values are unpacked from the fixed sparsity pattern)
and the border row.
"""
from __future__ import annotations

import numpy as np

from washer import build_stamp

try:
    from washer._cont import ffi, lib
except ImportError as exc:
    raise ImportError(
        "the compiled engine washer._cont is missing: install the package with "
        "`pip install .` (needs a C++ compiler and libeigen3-dev), or build in place "
        "with `python build.py cont`") from exc

build_stamp.check("washer._cont", ffi, lib)


def pieces(coll, J, border) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(blocks, parcols, extra) of [J; border] for J assembled by `coll.jacobian_general`
    (its CSC pattern; the values are unpacked, nothing is searched): the layout of
    csrc/cont/cont_api.h."""
    m, n, N = coll.mesh.ncol, coll.ndim, coll.mesh.ntst
    npar = coll.npar
    vals = _assembled(coll, J)
    nb = coll._n_blk
    blocks = vals[:nb].reshape(N, m * n, (m + 1) * n)
    npc = N * m * n * npar
    parcols = vals[nb:nb + npc].reshape(npar, N, m * n).transpose(1, 2, 0)
    return blocks, parcols, _dense_rows(coll, vals, border)


def dense_rows(coll, J, border) -> np.ndarray:
    """`pieces`' third: the dense rows of [J; border] alone (NDIM + NPAR, nx)."""
    return _dense_rows(coll, _assembled(coll, J), border)


def _assembled(coll, J) -> np.ndarray:
    """J's values in `coll`'s assembly order (those kept by the assembly, else unpacked)."""
    kept = getattr(J, "assembly", None)
    if kept is not None and kept[0] is coll:
        return kept[1]                                   # as assembled
    vals = np.empty(coll.nnz)
    vals[coll._order] = J.data                           # back to assembly order
    return vals


def _dense_rows(coll, vals: np.ndarray, border) -> np.ndarray:
    # the boundary conditions (periodic or general) and integral rows, dense
    # (NBC + NINT + 1 = NDIM + NPAR rows: NPAR = NBC + NINT - NDIM + 1), then the border
    extra = np.zeros((coll.ndim + coll.npar, coll.n_x))
    extra[coll._tail_rows, coll._tail_cols] = dense_values(coll, vals)
    extra[-1] = border
    return extra


def dense_values(coll, vals: np.ndarray) -> np.ndarray:
    """The values of the boundary and integral rows among `coll`'s assembled values vals
    (a view, in the order of coll._tail_rows, coll._tail_cols): those after the blocks
    and the parameter columns."""
    return vals[coll._n_blk + coll.mesh.ntst * coll.mesh.ncol * coll.ndim * coll.npar:]


def dense_values_of(coll, J) -> np.ndarray:
    """`dense_values` of the Jacobian J assembled by `coll`."""
    return dense_values(coll, _assembled(coll, J))


def onto_start(coll, J, border) -> tuple[np.ndarray, np.ndarray]:
    """[J; border] reduced onto S = (U(0), the parameters) and the dense rows R:
    (Sc, X) with Sc = M_RS - M_RI M_II^-1 M_IS and X = M_II^-1 M_IS (see
    systems.bvp.CollocationBVP.reduce). M_II, the collocation rows in the nodes after
    t = 0, is block lower bidiagonal: interval j's own nodes form the square block B_j,
    its first node couples to the interval before, so X follows interval by interval
    (forward substitution) after one batched solve of every B_j."""
    blocks, parcols, extra = pieces(coll, J, border)
    N, mn, w = blocks.shape
    n = w - mn
    A, B = blocks[:, :, :n], blocks[:, :, n:]
    RHS = np.concatenate([np.zeros((N, mn, n)), parcols], axis=2)     # columns (U(0), par)
    RHS[0, :, :n] = A[0]
    P = np.linalg.solve(B, RHS)                      # B_j^-1 RHS_j
    Q = np.linalg.solve(B, A)                        # B_j^-1 A_j
    Y = P
    for j in range(1, N):
        Y[j] -= Q[j] @ Y[j - 1, -n:]
    X = Y.reshape(N * mn, -1)
    cols_S = np.concatenate([np.arange(n), coll.n_u + np.arange(coll.npar)])
    Sc = extra[:, cols_S] - extra[:, n:coll.n_u] @ X
    return Sc, X


_DDOT: list = []


def _numpy_ddot():
    """numpy's own CBLAS ddot (the one numpy's dot of two float vectors calls) as a cffi
    `void *`, or None where it is not found (washer.cont.lapack.routines)."""
    if not _DDOT:
        from washer.cont import lapack
        found = lapack.routines()
        _DDOT.append(None if found is None else found[3])
    return _DDOT[0]


#: (coll._tail_rows, coll._tail_cols, their int32 copies, pointers) of the last layout
_TAIL: list = [None]


def _tail_pointers(coll) -> tuple:
    """(rows, cols, ntail): the positions of `coll`'s boundary and integral rows' values
    among the dense rows as int[] for the compiled calls, made once per layout (the meshes
    of a run share the arrays; the kept entry holds them, so an identity is not reused)."""
    kept = _TAIL[0]
    if kept is None or kept[0] is not coll._tail_rows or kept[1] is not coll._tail_cols:
        held = (np.ascontiguousarray(coll._tail_rows, dtype=np.int32),
                np.ascontiguousarray(coll._tail_cols, dtype=np.int32))
        if held[0].shape != held[1].shape:
            raise ValueError(f"rows {held[0].shape} and cols {held[1].shape} differ")
        kept = _TAIL[0] = (coll._tail_rows, coll._tail_cols, held,
                           (ffi.from_buffer("int[]", held[0]),
                            ffi.from_buffer("int[]", held[1]), len(held[0])))
    return kept[3]


def _ptr(a: np.ndarray):
    """The data of a C-contiguous float64 array as a double[] for the compiled calls (one
    from_buffer with the type: a fifth of the cost of from_buffer and a cast, and a
    factorisation passes a dozen)."""
    return ffi.from_buffer("double[]", a)


#: Factorisation objects (cont_bvp) whose owners have gone, by shape (NTST, NCOL, NDIM,
#: NPAR), for the next factorisation of that shape: a new one costs its allocations
#: (6 us at NTST 70, a third of a factorisation), and a continuation makes one or more per
#: point. A factorisation overwrites all of an object's state before anything reads it.
_KEPT: dict = {}
#: how many objects of one shape are kept, and of how many shapes (the latest)
_KEEP_PER_SHAPE, _KEEP_SHAPES = 4, 8


def new_handle(shape: tuple):
    """A cont_bvp of shape (NTST, NCOL, NDIM, NPAR) owned by the returned cdata: kept for
    reuse (`_KEPT`) when that is collected, or freed. MemoryError where none can be made."""
    kept = _KEPT.get(shape)
    raw = kept[1].pop() if kept and kept[1] else lib.cont_bvp_new(*shape)
    if raw == ffi.NULL:
        raise MemoryError(f"no memory for a factorisation of shape {shape}")
    if kept is None:
        kept = _KEPT[shape] = (_releaser(shape), [])
        while len(_KEPT) > _KEEP_SHAPES:              # the oldest shape's objects go
            for old in _KEPT.pop(next(iter(_KEPT)))[1]:
                lib.cont_bvp_free(old)
    return ffi.gc(raw, kept[0])


def _releaser(shape: tuple):
    """The destructor of `new_handle`'s objects of this shape: kept, or freed."""
    def release(raw) -> None:
        kept = _KEPT.get(shape)
        if kept is not None and len(kept[1]) < _KEEP_PER_SHAPE:
            kept[1].append(raw)
        else:
            lib.cont_bvp_free(raw)
    return release


def collocation_blocks(WT: np.ndarray, WP: np.ndarray, dtm: np.ndarray, T: float,
                       A: np.ndarray) -> np.ndarray:
    """The collocation blocks (NTST, NCOL*NDIM, (NCOL+1)*NDIM) from the Jacobians A
    (NTST, NCOL, NDIM, NDIM) of f at the Gauss points, the period T and the weights
    WT, WP (NCOL + 1, NCOL) (csrc/cont/assemble.cpp: the operations of
    Collocation.local_blocks' numpy expression, in its order)."""
    A = np.ascontiguousarray(A, dtype=float)
    N, m, n, _ = A.shape
    WT = np.ascontiguousarray(WT, dtype=float)
    WP = np.ascontiguousarray(WP, dtype=float)
    dtm = np.ascontiguousarray(dtm, dtype=float)
    if WT.shape != (m + 1, m) or WP.shape != (m + 1, m) or dtm.shape != (N,) or A.shape[3] != n:
        raise ValueError(f"collocation_blocks: shapes {WT.shape}, {WP.shape}, {dtm.shape}, "
                         f"{A.shape}")
    out = np.empty((N, m * n, (m + 1) * n))
    lib.cont_coll_blocks(N, m, n, _ptr(WT), _ptr(WP), _ptr(dtm), float(T), _ptr(A), _ptr(out))
    return out


def floquet_pair(blocks: np.ndarray, ndim: int) -> tuple[np.ndarray, np.ndarray]:
    """(P0, P1), each (NDIM, NDIM), with P0 y(0) + P1 y(1) = 0 for every solution y of the
    homogeneous collocation equations with these blocks (NTST, NCOL*NDIM, (NCOL+1)*NDIM)
    (AUTO's CONPAR + REDUCE): the Floquet pair of `BorderedCollocation`, made by the same
    eliminations without parameter columns or dense rows of a continuation. The pivots
    are chosen in the columns of U alone, so the pair of a Jacobian's blocks is, to the
    bit, the one its bordered factorisation gives."""
    blocks = np.ascontiguousarray(blocks, dtype=float)
    N, mn, w = blocks.shape
    n = ndim
    m = mn // n
    if w != mn + n or mn != m * n:
        raise ValueError(f"floquet_pair: blocks of shape {blocks.shape} for NDIM = {n}")
    handle = new_handle((N, m, n, 0))
    # NDIM dense rows of zeros: the eliminations carry them along, the pair does not
    # read them (the remaining system is then singular, which the pair does not use)
    extra = np.zeros((n, (N * m + 1) * n))
    P0, P1 = np.zeros((n, n)), np.zeros((n, n))
    lib.cont_bvp_factor(handle, _ptr(blocks), ffi.NULL, _ptr(extra), ffi.NULL, _ptr(P0),
                        _ptr(P1))
    return P0, P1


class BPLayout:
    """What BorderedCollocation.bp_test takes from a mesh, as the compiled call's pointers
    (made once per mesh and inner product): the positions rows, cols (ntail,) of the
    boundary and integral rows' values among the dense rows, the phase row's index, the
    node weights w_node (nodes,) and the inner product's weights theta (nx,)."""

    __slots__ = ("rows", "cols", "ntail", "phase", "w_node", "theta", "_held")

    def __init__(self, rows, cols, phase: int, w_node, theta):
        held = (np.ascontiguousarray(rows, dtype=np.int32),
                np.ascontiguousarray(cols, dtype=np.int32),
                np.ascontiguousarray(w_node, dtype=float), np.ascontiguousarray(theta, dtype=float))
        if held[0].shape != held[1].shape:
            raise ValueError(f"rows {held[0].shape} and cols {held[1].shape} differ")
        self.rows, self.cols = ffi.from_buffer("int[]", held[0]), ffi.from_buffer("int[]", held[1])
        self.ntail, self.phase = len(held[0]), int(phase)
        self.w_node, self.theta = _ptr(held[2]), _ptr(held[3])
        self._held = held            # the arrays the pointers read

    @classmethod
    def of(cls, coll, theta) -> "BPLayout":
        """The layout of `coll`'s dense rows (its tail's positions, the integral row's
        index NBC) with the inner product's weights theta."""
        return cls(coll._tail_rows, coll._tail_cols, coll.nbc, coll.w_node, theta)


class BorderedCollocation:
    """A factorised bordered collocation matrix (the `Factor` contract: solve,
    sign_logdet) with the Floquet pair.

    blocks (NTST, NCOL*NDIM, (NCOL+1)*NDIM), parcols (NTST, NCOL*NDIM, NPAR), extra
    (NDIM + NPAR, nx): see csrc/cont/cont_api.h. `singular` is True when a pivot was
    exactly zero (the solves are then least squares on the assembled matrix, which
    `dense` must give)."""

    #: whether the owner lets a factorisation of the same J with another border replace
    #: this one in place (`reborder`; CollocationBVP.factor)
    reborderable = False

    def __init__(self, blocks, parcols, extra, dense=None):
        blocks = np.ascontiguousarray(blocks, dtype=float)
        parcols = np.ascontiguousarray(parcols, dtype=float)
        extra = np.ascontiguousarray(extra, dtype=float)
        N, mn, w = blocks.shape
        n = w - mn
        m = mn // n
        npar = parcols.shape[2]
        nx = (N * m + 1) * n + npar
        if (parcols.shape[:2] != (N, mn) or extra.shape != (n + npar, nx)
                or mn != m * n):
            raise ValueError(f"inconsistent shapes {blocks.shape}, {parcols.shape}, "
                             f"{extra.shape}")
        handle = new_handle((N, m, n, npar))
        P0, P1 = np.zeros((n, n)), np.zeros((n, n))
        rc = lib.cont_bvp_factor(handle, _ptr(blocks), _ptr(parcols), _ptr(extra),
                                 ffi.NULL, _ptr(P0), _ptr(P1))
        self._hold(handle, (N, m, n, npar), P0, P1, rc == 1, dense)

    @classmethod
    def adopt(cls, handle, shape, P0, P1, dense=None) -> "BorderedCollocation":
        """A factorisation made elsewhere (washer.cont.corrector_periodic: the compiled corrector's
        last one, non-singular): the cont_bvp `handle` (owned by the object from now on),
        shape (NTST, NCOL, NDIM, NPAR) and its Floquet pair."""
        self = object.__new__(cls)
        self._hold(handle, shape, P0, P1, False, dense)
        return self

    def _hold(self, handle, shape, P0, P1, singular: bool, dense) -> None:
        """The object's state, a factorisation in the cont_bvp `handle` (freed with the
        object) of shape (NTST, NCOL, NDIM, NPAR), with its Floquet pair P0, P1 (NDIM,
        NDIM) and whether a pivot was zero."""
        N, m, n, npar = shape
        self.shape = (N, m, n, npar)
        self.nx = (N * m + 1) * n + npar
        self._f = handle
        self.P0, self.P1 = P0, P1
        self.singular = singular
        # the determinant on request (collocation systems never ask: their BP test is the
        # reduced matrix's)
        self._sl = None
        self._dense = dense

    @classmethod
    def from_jacobian(cls, coll, J, border) -> "BorderedCollocation":
        """From a Jacobian assembled by `coll.jacobian_general` (its CSC pattern) and
        the border row (nx,)."""
        border = np.ascontiguousarray(border, dtype=float)
        vals = _assembled(coll, J)
        N, m, n, npar = shape = (coll.mesh.ntst, coll.mesh.ncol, coll.ndim, coll.npar)
        if border.shape != ((N * m + 1) * n + npar,):
            raise ValueError(f"border row of shape {border.shape} for {shape}")
        rows, cols, ntail = _tail_pointers(coll)
        handle = new_handle(shape)
        P0, P1 = np.zeros((n, n)), np.zeros((n, n))
        # the pieces (`pieces`) made from vals and the factorisation in one call
        rc = lib.cont_bvp_factor_values(handle, N, m, n, npar, _ptr(vals), ntail, rows, cols,
                                        _ptr(border), _ptr(P0), _ptr(P1))
        if rc == 2:
            raise ValueError(f"cont_bvp_factor_values: bad sizes {shape}")
        self = object.__new__(cls)
        self._hold(handle, shape, P0, P1, rc == 1, lambda: coll.bordered(J, border))
        return self

    def reborder(self, border: np.ndarray, dense=None) -> bool:
        """The factorisation of the same matrix with the border row (the last dense row)
        `border` (nx,) instead, in place: the collocation rows' eliminations kept, only the
        new row taken through them and the remaining dense system factorised again (csrc/
        cont/reduce.cpp cont_bvp_reborder), so the solves, determinant and Floquet pair
        are to the bit those of a new factorisation with that row. dense: the assembled
        matrix with it, on request (the solves of a singular one). False (nothing
        changed) where the eliminations before the dense system met a zero pivot."""
        border = np.ascontiguousarray(border, dtype=float)
        if border.shape != (self.nx,):
            raise ValueError(f"border row of shape {border.shape}, expected {(self.nx,)}")
        rc = lib.cont_bvp_reborder(self._f, _ptr(border))
        if rc not in (0, 1):
            return False
        self.singular = rc == 1
        self._sl = None
        self._dense = dense
        return True

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        rhs = np.ascontiguousarray(rhs, dtype=float)
        if self.singular:
            M = self._dense()
            M = M.toarray() if hasattr(M, "toarray") else np.asarray(M)
            return np.linalg.lstsq(M, rhs, rcond=None)[0]
        x = np.empty(self.nx)
        lib.cont_bvp_solve(self._f, _ptr(rhs), _ptr(x))
        return x

    def unit_tangent(self, theta: np.ndarray, big: float) -> np.ndarray | None:
        """z / sqrt|<z, theta z>| of z = M^-1 e_n, the unit tangent Continuation.tangent
        makes from this factorisation with CollocationBVP.inner (theta (nx,) its weights),
        in one compiled call (cont_bvp_unit_tangent: the same solve, numpy's dot of two
        vectors through numpy's own CBLAS ddot, the same doubles). None where the caller
        computes it: a zero pivot (least squares), z or its norm not finite, the norm 0
        or above big, numpy's ddot not found."""
        ddot = _numpy_ddot()
        if self.singular or ddot is None:
            return None
        theta = np.ascontiguousarray(theta, dtype=float)
        t = np.empty(self.nx)
        if len(theta) != self.nx or lib.cont_bvp_unit_tangent(
                self._f, self.nx, _ptr(theta), float(big), ddot, _ptr(t)) != 0:
            return None
        return t

    def sign_logdet(self) -> tuple[float, float]:
        if self._sl is None:
            sl = np.zeros(2)
            lib.cont_bvp_sign_logdet(self._f, _ptr(sl))
            self._sl = (float(sl[0]), float(sl[1]))
        return self._sl

    def reduced(self, extra: np.ndarray) -> np.ndarray | None:
        """The matrix with these collocation rows and the dense rows `extra`
        (NDIM + NPAR, nx) instead of the factorised ones, reduced onto S = (U(0), the
        parameters): Sc (NDIM + NPAR, NDIM + NPAR), as `onto_start` (the factorisation's
        eliminations replayed on the new rows, csrc/cont/reduce.cpp cont_bvp_schur).
        None where a pivot of the factorisation was zero."""
        N, m, n, npar = self.shape
        extra = np.ascontiguousarray(extra, dtype=float)
        if extra.shape != (n + npar, self.nx):
            raise ValueError(f"dense rows of shape {extra.shape}, expected {(n + npar, self.nx)}")
        Sc = np.empty((n + npar, n + npar))
        rc = lib.cont_bvp_schur(self._f, _ptr(extra), _ptr(Sc))
        return Sc if rc == 0 else None

    def bp_test(self, lapack, tail, layout: "BPLayout", T: float, F, tangent):
        """`reduced` of the dense rows (NDIM + NPAR, nx) that are zero but for the values
        tail at the layout's (rows, cols), the own-phase row (the layout's w_node * (T F)
        on the nodes, F (nodes, NDIM) f there; 0 in the parameter columns) and the border
        row theta * tangent, and linalg.scaled_slogdet of it, in one compiled call
        (cont_bvp_bp_test: the same values as those steps one by one). lapack:
        linalg.compiled_lapack(). (Sc, scaled_slogdet's tuple), or None where a pivot of
        the factorisation was zero (as `reduced`)."""
        N, m, n, npar = self.shape
        nodes = N * m + 1
        # (the compiled call reads these sizes through bare pointers)
        if tail.size != layout.ntail or F.size != nodes * n or tangent.size != nodes * n + npar:
            raise ValueError(f"bp_test: tail ({tail.size}), F ({F.size}) or tangent "
                             f"({tangent.size}) not of sizes {layout.ntail}, {nodes * n}, "
                             f"{nodes * n + npar}")
        ne = n + npar
        Sc = np.empty((ne, ne))
        out = np.empty(3)
        rc = lib.cont_bvp_bp_test(self._f, lapack.getrf, lapack.ddot, _ptr(tail), layout.rows,
                                  layout.cols, layout.ntail, layout.phase, layout.w_node, T,
                                  _ptr(F), layout.theta, _ptr(tangent), _ptr(Sc), _ptr(out))
        if rc == 1:
            return Sc, (float(out[0]),)
        if rc in (0, 2):
            return Sc, (float(out[0]), float(out[1]), float(out[2]))
        if rc == 11:
            return None
        raise RuntimeError(f"cont_bvp_bp_test failed ({rc})")

    def floquet_pair(self) -> tuple[np.ndarray, np.ndarray]:
        """(P0, P1): P0 U(0) + P1 U(1) = 0 for the linearised collocation equations."""
        return self.P0, self.P1
