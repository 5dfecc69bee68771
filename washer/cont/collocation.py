"""Orthogonal collocation for periodic orbits, the way AUTO-07p discretises them.

The boundary-value problem on the unit interval (AUTO's FNPS / BCPS / ICPS):

    u'(t) = T f(u(t), p),  t in [0, 1]           (T = PAR(11), the period)
    u(0) - u(1) = 0                               (periodicity, NBC = NDIM)
    int_0^1 <u(t) - u_old(t), u'_old(t)> dt = 0   (integral phase condition, NINT = 1)

is discretised on a mesh 0 = tm[0] < ... < tm[NTST] = 1 by continuous piecewise
polynomials of degree NCOL. As in AUTO (mesh.f90) the unknowns are the values at
NCOL + 1 *equally spaced* nodes per interval, tm[j] + k dtm[j] / NCOL, k = 0..NCOL
(the first node of an interval is the last of the previous one), so a profile is an
array U of shape (NTST*NCOL + 1, NDIM): exactly the t-rows of an s-file record.
The collocation equations are imposed at the NCOL Gauss-Legendre points of each
interval (CPNTS), with the Lagrange weights of GENWTS:

    sum_k WP[k, c] U[j*NCOL + k] - dtm[j] T f(sum_k WT[k, c] U[j*NCOL + k], p) = 0

(the equations are multiplied by dtm[j], as AUTO does). Integrals over [0, 1] use the
closed Newton-Cotes weights WI of the NCOL + 1 nodes (WINT), which integrate the
piecewise polynomial exactly.

Contents, with the AUTO routine each follows:

* `gauss_points`, `lagrange_weights` (CPNTS, GENWTS), `integration_weights` (WINT),
  `interpolation_weights` (INTWTS).
* `Mesh`: tm, dtm, node times (the s-record t column), node quadrature weights.
* `Collocation`: residual and sparse Jacobian of the discretised BVP with a fixed
  sparsity pattern (the CSC structure is built once per mesh, each evaluation only
  fills the values), and the dense local blocks of every interval.
* `fundamental_solution`: the discrete fundamental solution of the linearised
  equations, forward interval by interval. (The condensation CONPAR + REDUCE, which
  leaves P0 u(0) + P1 u(1) = 0, is the compiled factorisation's:
  `washer.cont.reduction.floquet_pair`.)
* `eqdf`, `new_mesh`, `interpolate` (EQDF, NEWMSH, INTERP): mesh adaptation by
  equidistribution of the (NCOL+1)-st derivative's NCOL+1-st root.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from types import SimpleNamespace
from typing import TYPE_CHECKING

import numpy as np

from washer.cont.reduction import _ptr as _cont_ptr, ffi as _ffi, lib as _lib
from washer.cont.settings import HMACH

if TYPE_CHECKING:                  # annotations only; imported where used
    import scipy.sparse as sp

try:
    # what np.einsum calls without `optimize` (the same loops, the same sums), without its
    # Python wrapper: ADAPT interpolates every IAD points
    from numpy._core.multiarray import c_einsum as _einsum
except ImportError:                # pragma: no cover (another numpy's layout)
    _einsum = np.einsum

#: AUTO's EQDF treats NCOL-th derivatives below HMACH as zero ("small derivative" case:
#: the mesh then stays uniform).
EQDF_SMALL = HMACH


# --------------------------------------------------------------------------- weights

def gauss_points(ncol: int) -> np.ndarray:
    """The NCOL Gauss-Legendre points on [0, 1] (AUTO's CPNTS), increasing, shape (ncol,)."""
    if not 1 <= ncol <= 20:
        raise ValueError(f"NCOL = {ncol}: expected 2..7 as AUTO (1..20 accepted here)")
    x, _ = np.polynomial.legendre.leggauss(ncol)
    return 0.5 * (x + 1.0)


@lru_cache(maxsize=64)
def _lagrange_nodes(nodes: tuple) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """What `_lagrange` needs of the nodes alone (every ADAPT asks for the same NCOL + 1
    equally spaced ones): the other nodes' indices of each basis function (n, n - 1),
    the denominators prod_k (x_b - x_k) (n,), and the other nodes as (n - 1, n, 1)."""
    nodes = np.array(nodes, float)
    n = len(nodes)
    others = np.array([[k for k in range(n) if k != b] for b in range(n)], dtype=int)
    others = others.reshape(n, n - 1)
    denom = np.array([np.prod(nodes[b] - nodes[others[b]]) for b in range(n)])
    return _frozen(others), _frozen(denom), _frozen(nodes[others.T][:, :, None])


def _lagrange(nodes: np.ndarray, z: np.ndarray,
              derivative: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
    """Values and derivatives of the Lagrange basis on `nodes` at points `z`:
    both of shape (len(nodes), len(z)). Every basis function b is the product over the
    other nodes k in increasing order, and its derivative the sum over l of those
    products without l; all b at once (a factor 1.0 where k = l: the same products).
    derivative=False: the values alone (None for the derivatives; interpolation asks
    for no more, and ADAPT interpolates every IAD points)."""
    nodes = np.asarray(nodes, float)
    z = np.atleast_1d(np.asarray(z, float))
    n = len(nodes)
    others, denom, nodes_others = _lagrange_nodes(tuple(nodes.tolist()))
    dz = z[None, :] - nodes_others                           # (n - 1, n, len(z)): z - x_k
    L = np.ones((n, len(z)))
    for s in range(n - 1):
        L *= dz[s]
    if not derivative:
        L /= denom[:, None]
        return L, None
    D = np.zeros((n, len(z)))
    for li in range(n - 1):
        term = np.ones((n, len(z)))
        for s in range(n - 1):
            if s != li:
                term *= dz[s]
        D += term
    L /= denom[:, None]
    D /= denom[:, None]
    return L, D


def _frozen(a: np.ndarray) -> np.ndarray:
    a.setflags(write=False)
    return a


@lru_cache(maxsize=None)
def lagrange_weights(ncol: int) -> tuple[np.ndarray, np.ndarray]:
    """(WT, WP) of GENWTS, each shape (ncol + 1, ncol): the Lagrange basis on the
    NCOL + 1 equally spaced nodes k / NCOL of [0, 1] and its derivative (per unit of
    the local variable z in [0, 1]) at the Gauss points. Computed once per NCOL
    (read-only arrays: every mesh of a run shares them)."""
    nodes = np.arange(ncol + 1) / ncol
    return tuple(_frozen(a) for a in _lagrange(nodes, gauss_points(ncol)))


@lru_cache(maxsize=None)
def integration_weights(ncol: int) -> np.ndarray:
    """WI of WINT, shape (ncol + 1,): closed Newton-Cotes weights on [0, 1] for the
    NCOL + 1 equally spaced nodes (the integrals of the Lagrange basis). Computed once
    per NCOL (read-only)."""
    nodes = np.arange(ncol + 1) / ncol
    xg, wg = np.polynomial.legendre.leggauss(ncol + 2)       # exact for degree 2 ncol + 3
    L, _ = _lagrange(nodes, 0.5 * (xg + 1), derivative=False)
    return _frozen(L @ (0.5 * wg))


def interpolation_weights(ncol: int, z) -> np.ndarray:
    """INTWTS: Lagrange weights on the nodes k / NCOL at local points z in [0, 1],
    shape (len(z), ncol + 1)."""
    L, _ = _lagrange(np.arange(ncol + 1) / ncol, z, derivative=False)
    return L.T


# --------------------------------------------------------------------------- mesh

@dataclass
class Mesh:
    """A mesh of [0, 1]: tm (NTST + 1,) increasing from 0 to 1, NCOL nodes per interval."""
    tm: np.ndarray
    ncol: int

    @classmethod
    def uniform(cls, ntst: int, ncol: int) -> "Mesh":
        """AUTO's MSH."""
        return cls(np.arange(ntst + 1) / ntst, ncol)

    @classmethod
    def computed(cls, tm: np.ndarray, ncol: int, dtm: np.ndarray, node_times: np.ndarray,
                 node_weights: np.ndarray) -> "Mesh":
        """A mesh whose interval lengths (NTST,), node times and node weights
        (NTST*NCOL + 1,) were computed with tm (`adapt`'s compiled call): kept as `dtm`,
        `node_times` and `node_weights` would keep their own (the arrays are taken, not
        copied; dtm is made read-only)."""
        mesh = cls(tm, ncol)
        key = tm.tobytes()
        dtm.setflags(write=False)
        mesh._dtm = (key, dtm)
        mesh._node_times = ((key, ncol), node_times)
        mesh._node_weights = ((key, ncol), node_weights)
        return mesh

    @property
    def ntst(self) -> int:
        return len(self.tm) - 1

    @property
    def dtm(self) -> np.ndarray:
        """The interval lengths (NTST,), read-only: asked for by every residual and
        Jacobian, so kept with the tm they were taken from (tm may be changed in place:
        the key is its bytes)."""
        key = self.tm.tobytes()
        kept = self.__dict__.get("_dtm")
        if kept is None or kept[0] != key:
            d = np.diff(self.tm)
            d.setflags(write=False)
            self._dtm = kept = (key, d)
        return kept[1]

    @property
    def n_nodes(self) -> int:
        return self.ntst * self.ncol + 1

    def node_times(self) -> np.ndarray:
        """t of every node, (NTST*NCOL + 1,): tm[j] + k dtm[j]/NCOL and finally 1
        (the t column of an s-record). Kept with the mesh it was taken on (every point's
        record asks for it); a copy is returned."""
        key = (self.tm.tobytes(), self.ncol)
        kept = self.__dict__.get("_node_times")
        if kept is None or kept[0] != key:
            k = np.arange(self.ncol) / self.ncol
            t = (self.tm[:-1, None] + self.dtm[:, None] * k[None, :]).ravel()
            self._node_times = kept = (key, np.concatenate((t, self.tm[-1:])))
        return kept[1].copy()

    def node_weights(self) -> np.ndarray:
        """Quadrature weight of every node, (NTST*NCOL + 1,): sum_j dtm[j] WI[k] over
        the intervals the node belongs to, so that int_0^1 g dt = w @ g(nodes) for
        any continuous piecewise polynomial of degree NCOL (AUTO's RINPR, RNRMSQ).
        A new array (`adapt` hands a mesh its weights computed with it: a copy of them)."""
        kept = self.__dict__.get("_node_weights")
        if kept is not None and kept[0] == (self.tm.tobytes(), self.ncol):
            return kept[1].copy()
        wi = integration_weights(self.ncol)
        m, dtm = self.ncol, self.dtm
        w = np.empty(self.n_nodes)
        # every node but the last is node k < NCOL of one interval; an interval's first
        # node is also the last (k = NCOL) of the one before: two terms, whose sum does
        # not depend on their order
        w[:-1].reshape(self.ntst, m)[...] = dtm[:, None] * wi[None, :m]
        w[m:-1:m] += dtm[:-1] * wi[m]
        w[-1] = dtm[-1] * wi[m]
        return w


# --------------------------------------------------------------------------- collocation

class Collocation:
    """The discretised periodic BVP on a fixed mesh: NDIM components, NINT integral
    conditions and NINT + 1 free parameters (AUTO's NFPR = NBC + NINT - NDIM + 1 with
    NBC = NDIM: 2 for periodic orbits, 4 for the loci of cycle folds).

    Unknown layout of the (N + 1,) vector x: the profile U (NTST*NCOL + 1, NDIM)
    flattened row by row (node-major), then the free parameters in the order the
    caller chooses (periodic.py puts PAR(ICP(2)) then PAR(ICP(1))).
    Equation layout of the (N,) residual: the collocation equations ordered by
    (interval, Gauss point, component), then the NDIM periodicity conditions
    u(0) - u(1), then the NINT integral conditions (the phase condition first).
    """

    def __init__(self, mesh: Mesh, ndim: int, nint: int = 1, general_bc: bool = False,
                 nbc: int | None = None, npar: int | None = None):
        self.mesh, self.ndim, self.nint = mesh, ndim, nint
        #: general_bc: the NBC boundary conditions are any functions of (u(0), u(1),
        #: parameters) (general BVPs, IPS = 4; the loci of period doublings and tori:
        #: v(0) + v(1) = 0, rotated copies), with dense blocks; else u(0) - u(1) with
        #: the fixed +-1 pattern (NBC = NDIM).
        self.general_bc = general_bc
        #: NBC boundary conditions (NDIM unless given) and NPAR = NBC + NINT - NDIM + 1
        #: free parameters (NINT + 1 unless given).
        self.nbc = ndim if nbc is None else int(nbc)
        self.npar = nint + 1 if npar is None else int(npar)
        if not general_bc and self.nbc != ndim:
            raise ValueError(f"periodicity is NDIM = {ndim} conditions, not NBC = {self.nbc}")
        if self.nbc + nint - ndim + 1 != self.npar:
            raise ValueError(f"NBC + NINT - NDIM + 1 = {self.nbc + nint - ndim + 1} free "
                             f"parameters, not {self.npar}")
        m, n, N = mesh.ncol, ndim, mesh.ntst
        self.WT, self.WP = lagrange_weights(m)
        self.n_u = mesh.n_nodes * n
        self.n_coll = N * m * n
        self.n_eq = self.n_coll + self.nbc + nint
        self.n_x = self.n_u + self.npar
        #: local node indices of interval j: j*m + k, shape (N, m + 1)
        self.local = local_nodes(N, m)
        self.w_node = mesh.node_weights()
        self._pattern()

    def on_mesh(self, mesh: Mesh) -> "Collocation":
        """This discretisation on another mesh of the same NTST and NCOL (ADAPT's, every IAD
        points): a new object sharing everything that depends on the sizes alone (the
        weights, the sparsity pattern), with the mesh's own node weights."""
        if (mesh.ntst, mesh.ncol) != (self.mesh.ntst, self.mesh.ncol):
            raise ValueError(f"a mesh of NTST = {mesh.ntst}, NCOL = {mesh.ncol} for a "
                             f"collocation of {self.mesh.ntst}, {self.mesh.ncol}")
        other = object.__new__(Collocation)
        other.__dict__.update(self.__dict__)
        other.mesh = mesh
        other.w_node = mesh.node_weights()
        return other

    # -- sparsity pattern: it depends on the sizes only, so the meshes of a run (ADAPT
    # moves tm, never NTST or NCOL) share one (`_sparsity`)
    def _pattern(self) -> None:
        pat = _sparsity(self.mesh.ntst, self.mesh.ncol, self.ndim, self.npar, self.nint,
                        self.nbc, self.general_bc)
        self._pat = pat
        self.nnz = pat.nnz
        self._tail_rows, self._tail_cols = pat.tail_rows, pat.tail_cols
        self._order = pat.order
        self._indices = pat.indices
        self._indptr = pat.indptr
        self._bc_vals = pat.bc_vals
        self._n_blk = pat.n_blk
        self._pos_J = pat.pos_J
        self._indptr_b = pat.indptr_b
        self._pos_border = pat.pos_border
        self._indices_b = pat.indices_b

    # -- helpers
    def profile(self, x: np.ndarray) -> np.ndarray:
        """The profile U (NTST*NCOL + 1, NDIM) of an unknown vector (a view)."""
        return x[:self.n_u].reshape(-1, self.ndim)

    def at_gauss(self, U: np.ndarray) -> np.ndarray:
        """u at the Gauss points, shape (NTST, NCOL, NDIM)."""
        return np.einsum("kc,jkn->jcn", self.WT, U[self.local])

    def integral(self, g: np.ndarray) -> float:
        """int_0^1 of the piecewise polynomial with node values g (n_nodes,)."""
        return float(self.w_node @ g)

    def residual_general(self, U: np.ndarray, F: np.ndarray, integrals, bc=None) -> np.ndarray:
        """The (N,) residual of U' = F on the mesh: F the right-hand side at the Gauss
        points (NTST, NCOL, NDIM), already scaled (T f for periodic orbits);
        `integrals` the NINT integral conditions' values; `bc` the NBC boundary
        conditions' values (default u(0) - u(1), periodicity)."""
        loc = U[self.local]                                  # (N, m+1, n)
        coll = np.einsum("kc,jkn->jcn", self.WP, loc) - self.mesh.dtm[:, None, None] * F
        bc = U[0] - U[-1] if bc is None else np.asarray(bc, float)
        return np.concatenate([coll.ravel(), bc, np.atleast_1d(integrals)])

    def residual(self, U: np.ndarray, T: float, fg: np.ndarray, U_old: np.ndarray,
                 up_old: np.ndarray, bc_offset: np.ndarray | None = None) -> np.ndarray:
        """The periodic orbit's (N,) residual (NINT = 1). U: profile; T: the period; fg: f
        at the Gauss points (NTST, NCOL, NDIM); U_old, up_old: the reference profile and
        its time derivative T_old f(U_old) at the nodes (AUTO's UOLDPS, UPOLDP);
        bc_offset (NDIM,): added to u(0) - u(1) (2 pi NRTN of rotations, BCPS)."""
        phase = self.w_node @ np.sum((U - U_old) * up_old, axis=1)
        bc = None if bc_offset is None else U[0] - U[-1] + bc_offset
        return self.residual_general(U, T * fg, [phase], bc)

    def local_blocks(self, T: float, A: np.ndarray) -> np.ndarray:
        """The dense collocation blocks d(coll_j)/d(U_j), shape (NTST, NCOL*NDIM,
        (NCOL+1)*NDIM), from A = f_u at the Gauss points (NTST, NCOL, NDIM, NDIM)
        scaled by T (T = 1 for an already scaled right-hand side): block (j, c, k) is
        WP[k, c] I - dtm[j] T WT[k, c] A[j, c] (compiled:
        washer.cont.reduction.collocation_blocks)."""
        m, n, N = self.mesh.ncol, self.ndim, self.mesh.ntst
        from washer.cont import reduction
        return reduction.collocation_blocks(self.WT, self.WP, self.mesh.dtm, T,
                                            np.reshape(A, (N, m, n, n)))

    def jacobian_general(self, blocks: np.ndarray, dF_par: np.ndarray, int_u: np.ndarray,
                         int_par: np.ndarray, bc_jac=None) -> sp.csc_matrix:
        """The sparse (N, N + 1) Jacobian. blocks: from `local_blocks`; dF_par: the
        derivatives of the (scaled) right-hand side at the Gauss points with respect to
        the free parameters, (NPAR, NTST, NCOL, NDIM); int_u: the derivatives of the
        integrands with respect to u at the nodes, (NINT, n_nodes, NDIM) (weighted here
        by the quadrature); int_par: the integral conditions' parameter derivatives,
        (NINT, NPAR); bc_jac (general_bc only): (B0, B1, Bpar), the boundary
        conditions' derivatives with respect to u(0), u(1) (NBC, NDIM) and the free
        parameters (NBC, NPAR)."""
        import scipy.sparse as sp       # here: a run without collocation never loads it
        dpar = -self.mesh.dtm[None, :, None, None] * dF_par
        nn = self.mesh.n_nodes * self.ndim
        rows_int = np.concatenate([(self.w_node[None, :, None] * int_u).reshape(self.nint, nn),
                                   np.asarray(int_par, float).reshape(self.nint, self.npar)],
                                  axis=1)
        if self.general_bc:
            B0, B1, Bp = bc_jac
            bc_vals = np.concatenate([B0, B1, Bp], axis=1).ravel()
        else:
            bc_vals = self._bc_vals
        vals = np.concatenate([blocks.ravel(), dpar.ravel(), bc_vals, rows_int.ravel()])
        return self.jacobian_from_values(vals)

    def jacobian_from_values(self, vals: np.ndarray) -> sp.csc_matrix:
        """The sparse (N, N + 1) Jacobian with the values `vals` (nnz,) in
        `jacobian_general`'s assembly order (the collocation blocks, the parameter
        columns, the boundary conditions' values, the integral rows); vals is kept."""
        # Every Jacobian of these sizes has the same pattern: the first is built (and
        # checked) by scipy, later ones are its shallow copies with their own values
        # (scipy's constructor re-validates the pattern each time, ~10-60 us; Newton asks
        # for a Jacobian per iteration). The index arrays are shared, as they already
        # are with the pattern (`_sparsity`): nothing changes a Jacobian's pattern. The
        # template is kept with that pattern, so the meshes of one run (ADAPT makes a
        # Collocation every IAD points) share it too.
        pat = self._pat
        template = pat.__dict__.get("csc_template")
        if template is None:
            # (imported here, not at every Jacobian: an import statement costs a lookup and
            # a check of the module's state)
            import scipy.sparse as sp
            template = pat.csc_template = sp.csc_matrix(
                (vals[self._order], self._indices, self._indptr), shape=(self.n_eq, self.n_x))
            if (template.indptr.dtype == self._indptr.dtype
                    and template.indices.dtype == self._indices.dtype):
                # the pattern's own arrays (scipy's may be views of them): `has_pattern`
                # then knows it by identity instead of comparing indptr at every factor
                template.indices, template.indptr = self._indices, self._indptr
        fields = pat.__dict__.get("csc_fields")
        if fields is None:
            fields = pat.csc_fields = {k: v for k, v in template.__dict__.items()
                                       if k != "data"}
        J = object.__new__(_assembled_type())
        J.__dict__.update(fields)
        # The values in assembly order, for washer.cont.reduction.pieces (which would
        # otherwise scatter J.data back): J is never changed in place (a variant is a
        # copy, which does not carry this). J.data, in CSC order, is taken from them
        # where it is first read (`AssembledJacobian`).
        J._data = None
        J.assembly = (self, vals)
        return J

    def jacobian(self, T: float, blocks: np.ndarray, dpar: np.ndarray,
                 up_old: np.ndarray) -> sp.csc_matrix:
        """The periodic orbit's Jacobian (NINT = 1). blocks: from `local_blocks`; dpar:
        the derivatives of the collocation equations (WP U - dtm T f) with respect to
        the two free parameters, (2, NTST, NCOL, NDIM); up_old: (n_nodes, NDIM)."""
        dF = -dpar / self.mesh.dtm[None, :, None, None]
        return self.jacobian_general(blocks, dF, up_old[None], np.zeros((1, 2)))

    def has_pattern(self, J) -> bool:
        """Whether J was assembled by `jacobian_general` on this mesh (this CSC pattern)."""
        kept = getattr(J, "assembly", None)
        if kept is not None and kept[0] is self:      # assembled here (never changed in place)
            return True
        import scipy.sparse as sp
        return (sp.isspmatrix_csc(J) and J.shape == (self.n_eq, self.n_x) and J.nnz == self.nnz
                and J.indices is not None
                and (J.indptr is self._indptr or np.array_equal(J.indptr, self._indptr)))

    def integral_positions(self, k: int = 0) -> np.ndarray:
        """Where the entries of integral condition k (one per column, in column order)
        sit in the data of a Jacobian of this pattern (CSC order)."""
        cache = self.__dict__.setdefault("_int_pos", {})
        if k not in cache:
            cache[k] = np.flatnonzero(self._indices == self.n_coll + self.nbc + k)
        return cache[k]

    def bordered(self, J: sp.csc_matrix, border: np.ndarray) -> sp.csc_matrix:
        """[J; border] as a CSC matrix (N + 1, N + 1). A J built by `jacobian` (this
        pattern) is bordered by filling a precomputed structure; any other by vstack."""
        import scipy.sparse as sp
        border = np.asarray(border, float)
        if self.has_pattern(J):
            data = np.empty(self.nnz + self.n_x)
            data[self._pos_J] = J.data
            data[self._pos_border] = border
            return sp.csc_matrix((data, self._indices_b, self._indptr_b),
                                 shape=(self.n_x, self.n_x))
        return sp.vstack([sp.csc_matrix(J), sp.csr_matrix(border[None, :])], format="csc")


def _assembled_jacobian():
    """The class of `Collocation.jacobian_from_values`'s matrices (made on first use: scipy
    is imported by the first Jacobian, not by this module)."""
    import scipy.sparse as sp

    class AssembledJacobian(sp.csc_matrix):
        """A CSC matrix whose `data` (nnz,) in CSC order is gathered from the values in
        assembly order (`assembly = (Collocation, values)`) where it is first read: the
        compiled factorisations read the assembly order, and the corrector makes a
        Jacobian per iteration whose CSC values nothing may ask for (a gather of nnz
        values, ~10 us at NTST 70)."""

        @property
        def data(self):
            d = self.__dict__.get("_data")
            if d is None:
                coll, vals = self.__dict__["assembly"]
                d = self.__dict__["_data"] = vals[coll._order]
            return d

        @data.setter
        def data(self, values):
            self.__dict__["_data"] = values

    AssembledJacobian.__module__ = __name__
    AssembledJacobian.__qualname__ = "AssembledJacobian"
    return AssembledJacobian


def _assembled_type():
    """`AssembledJacobian`, made once."""
    cls = globals().get("AssembledJacobian")
    if cls is None:
        cls = globals()["AssembledJacobian"] = _assembled_jacobian()
    return cls


def __getattr__(name: str):
    # `AssembledJacobian` made on first use (and found by pickle under this name)
    if name == "AssembledJacobian":
        return _assembled_type()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


@lru_cache(maxsize=16)
def _sparsity(N: int, m: int, n: int, npar: int, nint: int, nbc: int,
              general_bc: bool) -> SimpleNamespace:
    """The CSC structure of `Collocation`'s Jacobian (and of the bordered matrix) for
    NTST = N, NCOL = m, NDIM = n: index arrays only, shared by every mesh of
    these sizes (as every Jacobian of one mesh always did: never written to)."""
    n_nodes = N * m + 1
    n_u = n_nodes * n
    n_coll = N * m * n
    n_eq = n_coll + nbc + nint
    n_x = n_u + npar
    j, c, i, k, l = np.meshgrid(np.arange(N), np.arange(m), np.arange(n), np.arange(m + 1),
                                np.arange(n), indexing="ij")
    rows_blk = ((j * m + c) * n + i).ravel()
    cols_blk = ((j * m + k) * n + l).ravel()
    jj, cc, ii = np.meshgrid(np.arange(N), np.arange(m), np.arange(n), indexing="ij")
    rows_par = np.tile(((jj * m + cc) * n + ii).ravel(), npar)
    cols_par = np.repeat(n_u + np.arange(npar), N * m * n)
    pr = n_coll + np.arange(nbc)
    last = (n_nodes - 1) * n
    if general_bc:
        # rows: every BC; columns: u(0), u(1), then the parameters (row-major blocks)
        bcols = np.r_[np.arange(n), last + np.arange(n), n_u + np.arange(npar)]
        rows_bc = np.repeat(pr, len(bcols))
        cols_bc = np.tile(bcols, nbc)
    else:
        rows_bc = np.concatenate([pr, pr])
        cols_bc = np.concatenate([np.arange(n), last + np.arange(n)])
    rows_int = np.repeat(n_coll + nbc + np.arange(nint), n_x)
    cols_int = np.tile(np.arange(n_x), nint)
    rows = np.concatenate([rows_blk, rows_par, rows_bc, rows_int])
    cols = np.concatenate([cols_blk, cols_par, cols_bc, cols_int])
    p = SimpleNamespace(nnz=len(rows))
    # where the boundary and integral rows' values sit (assembly order), for
    # washer.cont.reduction, which takes those rows dense
    tail = len(rows_blk) + len(rows_par)
    p.tail_rows, p.tail_cols = rows[tail:] - n_coll, cols[tail:]
    # CSC order of the entries; entries with the same (row, col) never occur
    order = np.lexsort((rows, cols))
    p.order = order
    p.indices = rows[order].astype(np.int32)
    counts = np.bincount(cols, minlength=n_x)
    p.indptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int32)
    p.bc_vals = np.concatenate([np.ones(n), -np.ones(n)])
    p.n_blk = len(rows_blk)
    # The bordered matrix [J; border]: each column gains one entry, the border row
    # (the last row index, so it ends the column in CSC order).
    col_of = np.repeat(np.arange(n_x), counts)
    p.pos_J = np.arange(p.nnz) + col_of
    p.indptr_b = (p.indptr + np.arange(n_x + 1)).astype(np.int32)
    p.pos_border = p.indptr_b[1:] - 1
    ind_b = np.empty(p.nnz + n_x, np.int32)
    ind_b[p.pos_J] = p.indices
    ind_b[p.pos_border] = n_eq
    p.indices_b = ind_b
    return p


# --------------------------------------------------------------------------- Floquet

def fundamental_solution(blocks: np.ndarray, ndim: int) -> np.ndarray:
    """The discrete fundamental solution of a linear collocation system v' = T A(t) v
    (blocks from `Collocation.local_blocks` with NDIM = ndim): Phi (n_nodes, ndim, ndim)
    with v(node k) = Phi[k] v(0) for every solution of the collocation equations; Phi[-1]
    is the monodromy matrix whose eigenvalues are the Floquet multipliers (the same
    discrete problem as `washer.cont.reduction.floquet_pair` condenses, solved forward
    interval by interval: each interval's collocation equations give its NCOL later nodes
    from its first one).
    Forward propagation loses accuracy on strongly unstable orbits (|mu| >> 1); it
    serves the eigenfunctions of the loci, where the critical multipliers are on the
    unit circle."""
    N, mn, _ = blocks.shape
    n = ndim
    m = mn // n
    Phi = np.empty((N * m + 1, n, n))
    Phi[0] = np.eye(n)
    for j in range(N):
        B0, Br = blocks[j][:, :n], blocks[j][:, n:]
        nxt = -np.linalg.solve(Br, B0 @ Phi[j * m])                 # (m n, n)
        Phi[j * m + 1:(j + 1) * m + 1] = nxt.reshape(m, n, n)
    return Phi


# --------------------------------------------------------------------------- adaptation

def eqdf(mesh: Mesh, U: np.ndarray, periodic: bool = True) -> np.ndarray:
    """AUTO's EQDF: the monotone function (NTST + 1,) whose increments are to be
    equidistributed: the (NCOL+1)-st root of the jump of the NCOL-th derivative of
    the piecewise polynomial, summed over components, integrated over the mesh."""
    m, N = mesh.ncol, mesh.ntst
    dtm = mesh.dtm
    loc = U[local_nodes(N, m)]                                                      # (N, m+1, n)
    hd = ((m / dtm) ** m)[:, None] * _einsum("k,jkn->jn", _cntdif(m), loc)          # (N, n)
    pwr = 1.0 / (m + 1)
    eqf = np.zeros(N + 1)
    if N > 1:
        e = np.sum(np.abs(2 * (hd[1:] - hd[:-1]) / (dtm[:-1] + dtm[1:])[:, None]) ** pwr, axis=1)
        eqf[1:N] = np.cumsum(dtm[:-1] * e)
    if periodic:
        jj, dtav = 0, (dtm[-1] + dtm[0]) / 2
    else:
        jj, dtav = max(N - 2, 0), dtm[-1]
    e = np.sum(np.abs((hd[jj] - hd[-1]) / dtav) ** pwr)
    eqf[N] = eqf[N - 1] + dtm[-1] * e
    if (np.abs(hd) <= EQDF_SMALL).all():
        eqf = np.arange(N + 1, dtype=float)
    return eqf


@lru_cache(maxsize=None)
def _cntdif(m: int) -> np.ndarray:
    """CNTDIF's weights (m + 1,): (-1)^(m-k) C(m, k), the NCOL-th difference (read-only)."""
    from math import comb
    return _frozen(np.array([(-1) ** (m - k) * comb(m, k) for k in range(m + 1)], float))


@lru_cache(maxsize=16)
def local_nodes(ntst: int, ncol: int) -> np.ndarray:
    """The node indices of each interval, j * NCOL + k, shape (NTST, NCOL + 1) (read-only:
    shared by every mesh of these sizes, ADAPT's included)."""
    return _frozen(np.arange(ntst)[:, None] * ncol + np.arange(ncol + 1)[None, :])


def new_mesh(mesh: Mesh, U: np.ndarray, ntst_new: int, periodic: bool = True) -> np.ndarray:
    """AUTO's NEWMSH: a mesh (ntst_new + 1,) that divides the range of EQDF uniformly.
    ADAPT makes one every IAD points: a profile of two or more components is taken in one
    compiled call (cont_new_mesh, csrc/cont/adapt.cpp: these numpy operations in their
    order, numpy's own power loop, the same doubles), unless EQDF is not finite."""
    tm_new = _compiled_new_mesh(mesh, U, ntst_new, periodic)
    if tm_new is not None:
        return tm_new
    eqf = eqdf(mesh, U, periodic)
    if not (np.diff(eqf) > 0).all():
        # flat pieces (a component with vanishing derivative over an interval):
        # keep the function strictly increasing so the inverse is defined.
        eqf = eqf + 1e-12 * eqf[-1] * np.arange(len(eqf)) / max(len(eqf) - 1, 1)
    targets = eqf[-1] * np.arange(1, ntst_new) / ntst_new
    tm_new = np.interp(targets, eqf, mesh.tm)
    return np.concatenate((mesh.tm[:1], tm_new, mesh.tm[-1:]))


_POWER: list = []


def _power_loop():
    """numpy's power loop for doubles and its data as the compiled EQDF calls it (void *
    each), or None where numpy does not show it (EQDF is numpy's then)."""
    if not _POWER:
        from washer.cont.user_problem.tracer import TraceError, numpy_loop
        try:
            _POWER.append(tuple(_ffi.cast("void *", a) for a in numpy_loop(np.power)))
        except TraceError:
            _POWER.append(None)
    return _POWER[0]


def _compiled_new_mesh(mesh: Mesh, U: np.ndarray, ntst_new: int,
                       periodic: bool) -> np.ndarray | None:
    """`new_mesh` by cont_new_mesh, or None where numpy computes it: one component (einsum
    sums CNTDIF's terms in another order), a power loop numpy does not show, EQDF not
    finite."""
    U = np.asarray(U)
    if U.ndim != 2 or U.shape[1] < 2 or U.dtype != float or ntst_new < 1:
        return None
    if _power_loop() is None:
        return None
    m, N = mesh.ncol, mesh.ntst
    U = np.ascontiguousarray(U)
    out = np.empty(ntst_new + 1)
    status = _lib.cont_new_mesh(N, m, U.shape[1], _cont_ptr(np.ascontiguousarray(mesh.tm, float)),
                                _cont_ptr(mesh.dtm), _cont_ptr(U), int(periodic),
                                _cont_ptr(_cntdif(m)), EQDF_SMALL, *_power_loop(), ntst_new,
                                _cont_ptr(out))
    return out if status == 0 else None


def interpolate(mesh: Mesh, U: np.ndarray, tm_new: np.ndarray, ncol_new: int) -> np.ndarray:
    """AUTO's INTERP: the piecewise polynomial (mesh, U) evaluated at the nodes of the
    mesh tm_new with ncol_new nodes per interval. U (n_nodes, ...) -> (n_nodes_new, ...)."""
    return interpolator(mesh, tm_new, ncol_new)(U)


def interpolator(mesh: Mesh, tm_new: np.ndarray, ncol_new: int):
    """`interpolate` from `mesh` onto the nodes of (tm_new, ncol_new) as a function of
    U, the weights computed once: ADAPT moves the point, its directions and the phase
    reference with the same ones."""
    return mesh_interpolator(mesh, Mesh(np.asarray(tm_new, float), ncol_new))


def mesh_interpolator(mesh: Mesh, new: Mesh):
    """`interpolator` onto the nodes of the Mesh `new` (whose node times it keeps)."""
    return evaluator(mesh, new.node_times())


def evaluate(mesh: Mesh, U: np.ndarray, t) -> np.ndarray:
    """The piecewise polynomial (mesh, U) at times t in [0, 1], shape (len(t), ...)."""
    return evaluator(mesh, t)(U)


@lru_cache(maxsize=None)
def _interpolation_nodes(ncol: int) -> tuple[np.ndarray, np.ndarray]:
    """`_lagrange_nodes` of INTWTS's nodes k / NCOL as cont_mesh_weights takes them: the
    other nodes of each basis function (NCOL, NCOL + 1) C-contiguous, the denominators
    (NCOL + 1,) (read-only)."""
    _, denom, others = _lagrange_nodes(tuple((np.arange(ncol + 1) / ncol).tolist()))
    return _frozen(np.ascontiguousarray(others.reshape(ncol, ncol + 1))), denom


def evaluator(mesh: Mesh, t):
    """`evaluate` at the times t as a function of the node values U (n_nodes, ...).
    ADAPT moves a point, its directions and the phase reference every IAD points: the
    intervals and weights, and the values of U with two or more columns, are computed in
    one compiled call each (csrc/cont/adapt.cpp: numpy's operations in numpy's order,
    the same doubles); other U (one column, where einsum sums in another order), and
    times or meshes numpy's searchsorted alone orders (a NaN, a mesh out of order), by
    numpy."""
    t = np.ascontiguousarray(t, dtype=float)
    m = mesh.ncol
    others, denom = _interpolation_nodes(m)
    j = np.empty(len(t), np.intc)
    L = np.empty((m + 1, len(t)))            # INTWTS's basis; the weights W are L.T, the
    jp = _ffi.from_buffer("int[]", j)        # layout einsum's order of summation follows
    compiled = _lib.cont_mesh_weights(
        mesh.ntst, m, _cont_ptr(np.ascontiguousarray(mesh.tm, dtype=float)),
        _cont_ptr(mesh.dtm), len(t), _cont_ptr(t), _cont_ptr(others), _cont_ptr(denom), jp,
        _cont_ptr(L)) == 0
    return _values_at(mesh, t, j, L, compiled)


def _values_at(mesh: Mesh, t: np.ndarray, j: np.ndarray, L: np.ndarray, compiled: bool):
    """`evaluator`'s function of U (and optionally `out`, (len(t), width) C-contiguous, to
    write the values into) from the intervals j (intc) and basis L (NCOL + 1, len(t)) of
    the times t that cont_mesh_weights computed (compiled), else (nothing computed) by
    numpy."""
    m = mesh.ncol
    jp = _ffi.from_buffer("int[]", j)
    Lp = _cont_ptr(L)
    if compiled:
        W = L.T
    else:
        j = np.clip(np.searchsorted(mesh.tm, t, side="right") - 1, 0, mesh.ntst - 1)
        W = interpolation_weights(m, (t - mesh.tm[j]) / mesh.dtm[j])          # (len(t), m+1)
    idx = None

    def at(U, out=None):
        nonlocal idx
        U = np.asarray(U)
        if compiled and U.ndim == 2 and U.shape[1] >= 2 and U.dtype == float:
            U = np.ascontiguousarray(U)
            if out is None:
                out = np.empty((len(t), U.shape[1]))
            _lib.cont_mesh_apply(len(t), m, jp, Lp, _cont_ptr(U), U.shape[1], _cont_ptr(out))
            return out
        if idx is None:
            idx = j[:, None] * m + np.arange(m + 1)[None, :]
        values = _einsum("tk,tk...->t...", W, U[idx])
        if out is None:
            return values
        out[...] = values
        return out
    return at


@lru_cache(maxsize=None)
def _adapt_constants(m: int) -> tuple:
    """The arrays of NCOL = m that every `adapt` passes, as cont_adapt_mesh takes them:
    CNTDIF's weights, INTWTS's other nodes and denominators, the integration weights
    (double[] each; the arrays are cached read-only beside them, so they stay alive)."""
    others, denom = _interpolation_nodes(m)
    return tuple(_cont_ptr(a) for a in (_cntdif(m), others, denom, integration_weights(m)))


def adapt(mesh: Mesh, U: np.ndarray, periodic: bool = True):
    """AUTO's ADAPT of the profile U (n_nodes, k) on `mesh`: (the new Mesh of the same
    NTST and NCOL, `new_mesh`, and the function of node values moving them onto its nodes,
    `mesh_interpolator`). A profile of two or more columns in one compiled call
    (cont_adapt_mesh: the new mesh, its interval lengths, node times and node weights,
    kept with it, and the interpolation's weights, the same doubles as the steps one by
    one), every IAD points; otherwise (one column; EQDF or the times not finite) the steps
    one by one."""
    m, N = mesh.ncol, mesh.ntst
    U = np.asarray(U)
    if (U.ndim == 2 and U.shape[1] >= 2 and U.dtype == float and _power_loop() is not None):
        U = np.ascontiguousarray(U)
        n_nodes = N * m + 1
        tm, dtm, t, w = np.empty(N + 1), np.empty(N), np.empty(n_nodes), np.empty(n_nodes)
        j = np.empty(n_nodes, np.intc)
        L = np.empty((m + 1, n_nodes))
        cntdif, others, denom, wi = _adapt_constants(m)
        p = _cont_ptr
        status = _lib.cont_adapt_mesh(
            N, m, U.shape[1], p(np.ascontiguousarray(mesh.tm, float)), p(mesh.dtm), p(U),
            int(periodic), cntdif, EQDF_SMALL, *_power_loop(), others, denom, wi, p(tm),
            p(dtm), p(t), p(w), _ffi.from_buffer("int[]", j), p(L))
        if status == 0:
            return Mesh.computed(tm, m, dtm, t, w), _values_at(mesh, t, j, L, True)
    new = Mesh(new_mesh(mesh, U, N, periodic=periodic), m)
    return new, mesh_interpolator(mesh, new)


def profile_from_data(t: np.ndarray, U: np.ndarray, ntst: int, ncol: int,
                      periodic: bool = True) -> tuple[Mesh, np.ndarray, float]:
    """A start profile from time-column data (AUTO's STPNUB with dat='NAME'): the rows
    t (m,), U (m, NDIM) become a piecewise-linear profile on the data's own mesh (time
    rescaled to [0, 1] by the period t[-1] - t[0]), which ADAPT2 moves onto a mesh of
    NTST intervals adapted to it (NEWMSH) with NCOL nodes each (INTERP).
    Returns (mesh, profile (NTST*NCOL + 1, NDIM), period)."""
    t = np.asarray(t, float)
    period = float(t[-1] - t[0])
    data_mesh = Mesh((t - t[0]) / period, 1)
    data_mesh.tm[-1] = 1.0
    tm = new_mesh(data_mesh, np.asarray(U, float), ntst, periodic=periodic)
    return Mesh(tm, ncol), interpolate(data_mesh, np.asarray(U, float), tm, ncol), period
