"""Homoclinic orbits (IPS = 9): AUTO's HomCont (homcont.f90: INHO, FNHO, BCHO, ICHO,
STPNHO, PREHO, FNCSHO, PSIHO) on the general BVP of washer.cont.systems.general_bvp.

An orbit u(t) of u' = f(u, p) leaving the equilibrium x0 and returning to it is
truncated to a time interval of length T = PAR(11) and rescaled to [0, 1]:

    u'(t) = T f(u(t), p),                                   t in [0, 1]
    L_s (u(0) - x0) = 0      (NSTAB rows: u(0) in the unstable eigenspace of x0)
    L_u (u(1) - x0) = 0      (NUNSTAB rows: u(1) in the stable eigenspace of x0)
    f(x0, p) = 0             (IEQUIB = 1: x0 = PAR(12 .. 11 + NDIM) is solved for)
    int_0^1 upold(t) . (u(t) - uold(t)) dt = 0              (the phase condition)

The projection boundary conditions (Beyn's): the rows of L_s span the stable
eigenspace of A^T, A = f_u(x0, p) (the orthogonal complement of A's unstable one), the
rows of L_u its unstable eigenspace; both from an ordered real Schur form (PRJCTN's
DGEES/DTRSEN), the NSTAB eigenvalues of smallest and the NUNSTAB of largest real part.
A basis of an invariant subspace is defined up to a change of basis only; the rows are
made a smooth function of the parameters (Newton's Jacobian differences them) as the
orthogonal projector onto the subspace applied to a reference basis, the subspace's
basis at the last accepted point (PRJCTN uses Beyn's normalisation against the previous
call for the same reason). With PAR(11) < 0 time runs backwards and A is -f_u.

IEQUIB = 0: the equilibrium is the user's, set into PAR(12 .. 11 + NDIM) by PVLS at
u(0) (FBHO calls PVLS(NDM, U0, PAR) at each evaluation), and only the NSTAB + NUNSTAB
projection conditions are imposed.

Heteroclinic orbits (IEQUIB = -1, -2): the orbit leaves x1 = PAR(12 .. 11 + NDIM) and
reaches x2 = PAR(12 + NDIM .. 11 + 2 NDIM); the NSTAB conditions at t = 0 are x1's, the
NUNSTAB at t = 1 x2's (both counts, where -1, from x1's eigenvalues, as STPNHO's). -1: the
user's PVLS sets both; -2: both solved for, f(x1) = f(x2) = 0 with PAR(12 .. 11 + 2 NDIM)
free.

Homoclinic to a saddle-node (IEQUIB = 2): x0 solved for as with 1, plus Re l_(NSTAB+1)
= 0 (the eigenvalues by real part, smallest first: the one between the NSTAB stable
and NUNSTAB unstable ones); NSTAB + NUNSTAB = NDIM - 1, counted without the eigenvalue
nearest zero. Test functions 15, 16: the orbit's ends seen along the centre direction
v_(NSTAB+1), (x0 - u(1)) . v and (x0 - u(0)) . v, zero for a non-central orbit.

Reversible systems (IREV, one entry per component): the orbit is the half from x0 to the
symmetric section, the components i with IREV(i) > 0 vanishing at t = 1 in place of the
NUNSTAB projection conditions there, and no phase condition (the section fixes the time
shift).

Fixed test functions (IFIXED): psi_k = 0 for each k listed (the IPSI codes below), one
more boundary condition and one more free parameter each.

Free parameters: NFPR = NBC + NINT - NDIM + 1 with NBC = NSTAB + (NUNSTAB, or the number
of IREV(i) > 0) + NFIXED + (1 for IEQUIB = 2) + NDIM per solved-for equilibrium and NINT =
1 (0 with IREV); the first NFPR - NDIM (solved-for equilibria) of ICP, then
PAR(12 .. ) of the solved-for equilibria (INHO appends them to ICP). Further ICP entries
are written only (the test functions PAR(20 + k) among them).

Starts (ISTART, INHO/STPNHO): ISTART = 5 (the default) is 1 from STPNT or a stored
homoclinic orbit, 4 from a stored orbit of another problem type (a periodic orbit of
long period); 1 and 2 start from the profile as it is; 4 first shifts the stored
periodic orbit in time so that it starts at its mesh point nearest the equilibrium
(PREHO), taking for the equilibrium (IEQUIB = 1) the node where |f| is least.

Test functions IPSI (PSIHO): PAR(20 + k) is set after every point to psi_k, for the k
of IPSI (a user's UZR on PAR(20 + k) locates its zeros, as in AUTO's demos). The
eigenvalues are ordered by real part, smallest first; s = NSTAB (leading stable), s + 1
the leading unstable one:
  1  resonant eigenvalues (neutral saddle): Re + Im of l_s + l_{s+1}
  2  double real leading stable eigenvalues (saddle to saddle-focus)
  3  double real leading unstable eigenvalues
  4  neutral saddle, saddle-focus or bi-focus: Re l_s + Re l_{s+1}
  5  neutrally divergent saddle-focus (stable complex): Re (l_{s-1} + l_s + l_{s+1})
  6  neutrally divergent saddle-focus (unstable complex): Re (l_s + l_{s+1} + l_{s+2})
  7  three leading stable eigenvalues;  8  three leading unstable eigenvalues
  9  local bifurcation, NSTAB decreases: Re l_s;  10  NSTAB increases: Re l_{s+1}
  11 orbit flip w.r.t. the leading stable direction: f(u(1)) . w_s e^(-T Re l_s / 2)
  12 orbit flip w.r.t. the leading unstable direction: f(u(0)) . w_{s+1} e^(T Re l_{s+1} / 2)
  15 non-central saddle-node homoclinic (stable side): (x0 - u(1)) . v_{s+1}
  16 non-central saddle-node homoclinic (unstable side): (x0 - u(0)) . v_{s+1}
(w the left eigenvectors, v the right ones, real parts, unit length, signs continued
from the previous evaluation as EIGHO's; all at the left equilibrium x1). With ITWIST = 1
(the adjoint v beside u: washer.cont.systems.homoclinic_adjoint, PAR(10) free after the
user's parameters):
  13 inclination flip w.r.t. the stable manifold: v(0) . v_s e^(-T Re l_s / 2)
  14 inclination flip w.r.t. the unstable manifold: v(1) . v_{s+1} e^(T Re l_{s+1} / 2)

ISTART = 3: the homotopy start (washer.cont.systems.homoclinic_homotopy): the orbit
grown from the equilibrium along its unstable manifold, no phase condition.
"""
from __future__ import annotations

import math

import numpy as np

from washer.cont import collocation as col
from washer.cont.problem import Problem
from washer.cont.settings import SettingsError
from washer.cont.system import StartData, register
from washer.cont.systems import homoclinic_adjoint as adj
from washer.cont.systems import homoclinic_homotopy as hom
from washer.cont.systems import homoclinic_switching as sw
from washer.cont.systems.general_bvp import BoundaryValueProblem

#: PAR(11): the truncation interval T of the homoclinic orbit (time scaled to [0, 1]).
PERIOD = 11
#: PAR(12 .. 11 + NDIM): the equilibrium (set by PVLS with IEQUIB = 0, solved for with 1).
EQUILIBRIUM = 12
#: PAR(20 + k): the value of test function k of IPSI after each point.
PSI = 20
#: The IPSI (and IFIXED) codes computed here (PSIHO's): see the module docstring.
PSI_CODES = frozenset(range(1, 17))
#: The codes that read the adjoint v (ITWIST = 1).
ADJOINT_CODES = frozenset((13, 14))
#: IEQUIB: 0 the user's equilibrium (PVLS), 1 solved for, 2 a saddle-node solved for,
#: -1 two equilibria from PVLS (heteroclinic), -2 two equilibria solved for.
EQUILIBRIUM_KINDS = (-2, -1, 0, 1, 2)

#: PSIHO's COMPZERO (INHO's HMACHHO): an imaginary part below it is zero.
COMPZERO = 1e-13


def homotopy_index(ndm: int, iequib: int) -> int:
    """IP of the homotopy start (ISTART = 3): eps_0 = PAR(IP), the first PAR after the
    equilibria (12 + NDIM; 12 + 2 NDIM for a heteroclinic orbit, IEQUIB < 0)."""
    return EQUILIBRIUM + ndm * (2 if iequib < 0 else 1)


def invalid(s) -> list[str]:
    """HomCont's constants whose values are none of HomCont's (empty: every value is one)."""
    out = []
    if s.ITWIST not in (0, 1):
        out.append(f"ITWIST = {s.ITWIST} (HomCont's are 0 and 1)")
    if s.IEQUIB not in EQUILIBRIUM_KINDS:
        out.append(f"IEQUIB = {s.IEQUIB} (HomCont's are -2, -1, 0, 1, 2)")
    if s.ISTART > 5:
        out.append(f"ISTART = {s.ISTART} (HomCont's are 0-5, and below 0 for "
                   "n-homoclinic branch switching)")
    if s.IREV and len(s.IREV) != s.NDIM:
        out.append(f"IREV = {list(s.IREV)} (one entry per component of NDIM = {s.NDIM})")
    codes = tuple(s.IPSI) + tuple(s.IFIXED)
    unknown = [k for k in codes if k not in PSI_CODES]
    if unknown:
        out.append(f"IPSI/IFIXED codes {unknown} (HomCont's are 1-16)")
    if s.ISTART == 3 and s.IEQUIB == 2:
        out.append("ISTART = 3 with IEQUIB = 2 (HomCont's INHO: 'IEQUIB=2 NOT ALLOWED WITH "
                   "ISTART=3')")
    if s.ISTART == 3 and (s.ITWIST or s.IREV or s.IFIXED):
        # FBHO's homotopy branch imposes none of their conditions, and INHO still counts
        # them among the free parameters: PAR(10) and the adjoint without conditions
        # (ITWIST), the equilibrium's ICP entries moved (IFIXED, IREV)
        out.append("ISTART = 3 with ITWIST, IREV or IFIXED (HomCont's homotopy conditions "
                   "replace the adjoint's, the reversibility and the fixed test functions, "
                   "which then leave the adjoint or the equilibrium undetermined: start "
                   "with ISTART = 3 without them, then restart with ISTART = 1)")
    if s.ISTART < 0 and s.IREV:
        out.append(f"ISTART = {s.ISTART} with IREV (HomCont's FBHO reads IREV for each of "
                   "the N + 1 pieces' components, past its NDIM entries)")
    adjoint = [k for k in codes if k in ADJOINT_CODES and s.ITWIST != 1]
    if adjoint:
        out.append(f"IPSI/IFIXED codes {adjoint} with ITWIST = {s.ITWIST} (13 and 14 read "
                   "the adjoint: ITWIST = 1)")
    return out


def spectrum(A: np.ndarray):
    """(eigenvalues sorted by real part, smallest first (EIGHO's order), the real parts
    of the unit right eigenvectors as rows, the same of the left ones)."""
    import scipy.linalg as sla     # here: an equilibrium run never loads scipy.linalg
    lam, W, V = sla.eig(A, left=True, right=True)
    order = np.argsort(lam.real, kind="stable")
    lam, V, W = lam[order], V[:, order], W[:, order]
    # LAPACK's vectors have unit length and a real largest component; EIGHO keeps the
    # real parts (both of a complex pair).
    return lam, np.real(V).T.copy(), np.real(W).T.copy()


def invariant_basis(A: np.ndarray, m: int, stable: bool) -> np.ndarray:
    """An orthonormal basis (n, m) of A's invariant subspace of its m eigenvalues of
    smallest (stable) or largest real part: the leading Schur vectors of a real Schur
    form ordered by a threshold between the m-th and (m+1)-th real part."""
    n = len(A)
    if m <= 0:
        return np.zeros((n, 0))
    re = np.sort(np.linalg.eigvals(A).real)
    if not stable:
        re = -re[::-1]
    cut = 0.5 * (re[m - 1] + re[m]) if m < n else math.inf
    import scipy.linalg as sla     # here: an equilibrium run never loads scipy.linalg
    if stable:
        _, Z, k = sla.schur(A, output="real", sort=lambda x, y: x < cut)
    else:
        _, Z, k = sla.schur(A, output="real", sort=lambda x, y: -x < cut)
    if k != m:
        raise np.linalg.LinAlgError(f"the {m} {'stable' if stable else 'unstable'} "
                                    "eigenvalues are not separated from the others "
                                    "(a complex pair split)")
    return Z[:, :m]


class _Projection:
    """The rows L of one projection boundary condition, L v = 0 iff v is orthogonal to
    the invariant subspace S (of A^T) of the m eigenvalues: L = R^T P with P the
    orthogonal projector onto S and R a reference basis of S (see the module
    docstring); `accept` makes the subspace at the accepted point the reference."""

    def __init__(self, m: int, stable: bool):
        self.m, self.stable, self.ref = m, stable, None

    def rows(self, At: np.ndarray) -> np.ndarray:
        """L (m, NDIM) for At = A^T (NDIM, NDIM); the first call's subspace becomes the
        reference."""
        Q = invariant_basis(At, self.m, self.stable)
        if self.ref is None:
            self.ref = Q
        return (Q @ (Q.T @ self.ref)).T

    def accept(self, At: np.ndarray) -> None:
        """The subspace of At (NDIM, NDIM) at the accepted point is the new reference,
        oriented as the old one (det(Q^T R_old) > 0)."""
        Q = invariant_basis(At, self.m, self.stable)
        if self.ref is not None and self.ref.shape == Q.shape and Q.size \
                and np.linalg.det(Q.T @ self.ref) < 0:
            # A Schur basis's orientation is LAPACK's choice: taken as it comes, the
            # rows L flip sign between two points of the branch, and with them the sign
            # of the BP test, whose values at the next point are compared with this
            # point's (snh's h1b labelled BPs at such flips, +2.4e13 to -8.5e12 from one
            # step to the next; AUTO's FNBPBV stays positive over the whole run).
            Q = Q.copy()
            Q[:, 0] *= -1
        self.ref = Q


class _SignedVectors:
    """EIGHO's sign rule for eigenvector rows: on the first call each row's largest
    component (the first of equal moduli) is made positive, afterwards each row keeps
    the sign of the previous call's row (positive dot product)."""

    def __init__(self):
        self.prev = None

    def __call__(self, V: np.ndarray) -> np.ndarray:
        V = V.copy()
        if self.prev is None or self.prev.shape != V.shape:
            for r in V:
                if r[np.argmax(np.abs(r))] < 0:
                    r *= -1
        else:
            for r, p in zip(V, self.prev):
                if r @ p < 0:
                    r *= -1
        self.prev = V.copy()
        return V


def _solved_equilibria(iequib: int) -> int:
    """How many equilibria are unknowns (PAR(12 ..) free, f = 0 imposed): IEQUIB 1, 2
    one, -2 two, 0 and -1 none (the user's PVLS sets them)."""
    return {1: 1, 2: 1, -2: 2}.get(iequib, 0)


def _counts(s, eigenvalues) -> tuple[int, int]:
    """(NSTAB, NUNSTAB): the given ones, or (INHO, GETSTAB) the rest of NDIM (NDIM - 1
    for a saddle-node) where one is given, or counted from the start's eigenvalues (a
    saddle-node's nearest zero excluded) where -1."""
    nstab, nunstab = s.NSTAB, s.NUNSTAB
    ndm = len(eigenvalues)
    nproj = (ndm - (s.IEQUIB == 2)) if -1 in (nstab, nunstab) else nstab + nunstab
    if nstab == -1 and nunstab != -1:
        nstab = nproj - nunstab
    elif nunstab == -1 and nstab != -1:
        nunstab = nproj - nstab
    re = np.asarray(eigenvalues).real
    keep = np.ones(ndm, bool)
    if s.IEQUIB == 2:
        keep[int(np.argmin(np.abs(re)))] = False
    if nstab == -1:
        nstab = int(np.sum((re < 0) & keep))
    if nunstab == -1:
        nunstab = int(np.sum((re > 0) & keep))
    return nstab, nunstab


@register(9, 1, "*")
class HomoclinicOrbits(BoundaryValueProblem):
    """The continued system of homoclinic orbits (IPS = 9, ISW = 1): see the module
    docstring. `ndim` = `ndm` = the user's NDIM; PAR(12 .. 11 + NDIM) hold x0 (x1; x2 follows for
    IEQUIB < 0)."""

    def __init__(self, data):
        s = data.settings
        wrong = invalid(s)
        if wrong:
            raise SettingsError("IPS = 9 (homoclinic orbits): " + "; ".join(wrong),
                                keys=("ITWIST", "IEQUIB", "ISTART", "IREV", "IFIXED", "IPSI"))
        user, ndm = data.problem, s.NDIM
        self.settings_user = s
        self.user, self.ndm, self.iequib = user, ndm, s.IEQUIB
        self.itwist = s.ITWIST
        #: the components u_i with IREV(i) > 0 vanish at t = 1 (IREV given), else None
        self.rev = [i for i, r in enumerate(s.IREV) if r > 0] if s.IREV else None
        self.fixed = tuple(s.IFIXED)
        n_eq = _solved_equilibria(self.iequib) * ndm
        rec = data.record
        p = np.asarray(data.par, float)
        # NPAR as AUTO's: the constants' (raised to ICP's and UZR's indices), the
        # restart's own without its internal parameters (AUTO keeps a restart's NPAR:
        # fhh's run 6, NPAR = 14, from run 3's record of 17 states 17), INHO's 20 + the
        # largest IPSI where IPSI is given, and for ISTART < 0 its NPARI after them
        rec_npari = int(getattr(rec, "npari", 0) or 0) if rec is not None else 0
        rec_npar = len(rec.par) - rec_npari if getattr(rec, "par", None) is not None else 0
        npar = max(s.NPAR, rec_npar, EQUILIBRIUM - 1 + (2 if self.iequib < 0 else 1) * ndm)
        if s.IPSI:
            npar = max(npar, PSI + max(s.IPSI))
        if s.ISTART < 0:
            # INHO's NPARI: Lin's direction and f(x_max) after the constants' NPAR
            npar = sw.start_dimensions(ndm, s.ISTART, npar)[1]
        internal = None
        if rec_npari:
            p, k = p.copy(), len(rec.par)
            internal, p[k - rec_npari:k] = p[k - rec_npari:k].copy(), 0.0
        par = np.zeros(npar)
        par[:min(len(p), npar)] = p[:npar]
        if internal is not None and s.ISTART < 0 and rec_npari == 2 * ndm:
            # a record of the pieces: Lin's direction and f(x_max), its NPARI, stay the
            # last of this run's parameters (kdv's run 5 widens NPAR from 32 to 36)
            par[-rec_npari:] = internal
        #: AUTO's NPARI (the s-records' field 13): ISTART < 0's Lin direction and f(x_max)
        self.npari = 2 * ndm if s.ISTART < 0 else 0
        istart = s.ISTART
        if istart == 5:
            istart = 4 if rec is not None and getattr(rec, "ips", 9) not in (9, 0) else 1
        #: N + 1 pieces of an N-homoclinic orbit (ISTART = -N), else 0
        self.pieces = sw.n_pieces(istart) if istart < 0 else 0
        stored = np.shape(rec.U)[1] if rec is not None and np.ndim(rec.U) == 2 else 0
        if istart >= 0 and stored > 2 * ndm:
            # CPBKHO reads the pieces' times from the record's PAR(21), PAR(23), ..,
            # within the record's NPAR, which the run keeps (fnb's run 7, NPAR = 14, from
            # run 6's 3-homoclinic orbit: NPAR 22, its NPARI 6 dropped, as AUTO's)
            rec = sw.orbit_from_pieces(rec, ndm, par)
        if istart == 4 and rec is not None:
            rec = self._shifted(rec, par)
        #: the gaps along Lin's direction (ITWIST = 1 with ISTART < 0)
        self.lin = bool(self.pieces and self.itwist)
        #: the components of u(1): the last piece's (ISTART < 0), else the orbit's
        self._last = slice(max(self.pieces - 1, 0) * ndm, max(self.pieces, 1) * ndm)
        if self.pieces:
            rec = self._pieces_start(rec, stored, par)
            self.itwist = 0                    # no adjoint among the pieces
        elif self.itwist and rec is not None and np.ndim(rec.U) == 2:
            rec = adj.widened_start(rec, ndm, par)
        self.istart = istart
        # NSTAB, NUNSTAB at the start's (left) equilibrium (STPNHO: PVLS, then GETSTAB
        # where -1; a saddle-node's eigenvalue nearest zero is neither).
        if self.iequib in (0, -1):
            par = user.pvls(self._start_u0(rec, par, data), par)
        self.nstab, self.nunstab = _counts(
            s, np.linalg.eigvals(self._A(par[EQUILIBRIUM - 1:EQUILIBRIUM - 1 + ndm], par)))
        #: (NUNSTAB, NSTAB, ISTART) as the run uses them (counted where -1, ISTART = 5
        #: resolved): what AUTO's b-file header states above the user's values
        self.homcont_internal = (self.nunstab, self.nstab, istart)
        nright = len(self.rev) if self.rev is not None else self.nunstab
        nbc = (self.nstab + nright + len(self.fixed) + (self.iequib == 2) + n_eq)
        nint = 0 if self.rev is not None else 1
        # the adjoint's: v beside u, NSTAB + NUNSTAB conditions, one integral, PAR(10)
        ndim = ndm * (1 + self.itwist)
        nbc += self.itwist * (self.nstab + self.nunstab)
        nint += self.itwist
        if self.pieces:
            # N + 1 pieces: N joins of NDM rows and N sections, no phase condition
            ndim = ndm * self.pieces
            nbc += (self.pieces - 1) * (ndm + 1)
            nint = 0
        if istart == 3:
            nbc = hom.n_conditions(ndm, n_eq // ndm, self.nunstab)
            nint = 0
        else:                               # the user's NBC and NINT (INHO adds them)
            nbc, nint = nbc + s.NBC, nint + s.NINT
        nfpr = nbc + nint - ndim + 1
        n_user = nfpr - n_eq - self.itwist
        if n_user < 1 or len(s.ICP) < n_user:
            raise SettingsError(f"IPS = 9 with NSTAB = {self.nstab}, NUNSTAB = "
                                f"{self.nunstab}: {n_user} free parameters of ICP, but "
                                f"ICP = {list(s.ICP)}", keys=("ICP",))
        self._free = (list(s.ICP[:n_user]) + ([adj.ADJOINT_PAR] if self.itwist else [])
                      + [EQUILIBRIUM + i for i in range(n_eq)])
        self._left = _Projection(self.nstab, stable=True)       # at t = 0
        self._right = _Projection(self.nunstab, stable=False)   # at t = 1
        self._right_vectors, self._left_vectors = _SignedVectors(), _SignedVectors()
        # the fixed test functions' own sign memory (EIGHO's), apart from IPSI's output
        self._fixed_vectors = (_SignedVectors(), _SignedVectors())
        # the adjoint's (ITWIST = 1): v(0) against A's unstable subspace, v(1) its stable one
        self._adj_left = _Projection(self.nunstab, stable=False)
        self._adj_right = _Projection(self.nstab, stable=True)
        # the homotopy's (ISTART = 3): its boundary conditions' eigenvectors
        self._hom_right, self._hom_left = _SignedVectors(), _SignedVectors()
        s2 = s.with_(NDIM=ndim, NBC=nbc, NINT=nint, NPAR=npar)
        self.run_settings = s2
        super().__init__(StartData(self._extended(user, ndm, nbc, nint), s2, data.u, par,
                                   rec, data.kind, data.unames, data.data))
        self.ndm = ndm

    # ------------------------------------------------------------------ the equations
    def _A(self, x0, par) -> np.ndarray:
        """f_u at the equilibrium, time reversed where PAR(11) < 0 (PRJCTN, EIGHO)."""
        A = self.user.dfdu(np.asarray(x0, float), par)
        return -A if par[PERIOD - 1] < 0 else A

    def _equilibria(self, u0, par):
        """(x1, x2, par): the left and right equilibria, PAR(12 .. 11 + NDIM) and (IEQUIB
        < 0) PAR(12 + NDIM .. 11 + 2 NDIM), after the user's PVLS at u(0) for IEQUIB = 0
        and -1 (FBHO); x2 is x1 for a homoclinic orbit, x1 + 2 pi NRTN for one whose
        angles rotate (`_begin`)."""
        if self.iequib in (0, -1):
            par = self.user.pvls(np.asarray(u0, float), par)
        n, k = self.ndm, EQUILIBRIUM - 1
        x1 = np.asarray(par[k:k + n], float)
        x2 = np.asarray(par[k + n:k + 2 * n], float) if self.iequib < 0 else x1
        if self.iequib >= 0 and self._rotations is not None:
            x2 = x1 + 2 * math.pi * self._rotations
        return x1, x2, par

    #: NRTN (NDIM,) of an orbit whose angles turn by 2 pi NRTN from t = 0 to 1 (SETRTN on
    #: the start, IEQUIB >= 0), None where none does
    _rotations = None

    def _begin(self, U, old) -> None:
        """The start's rotations (PREHO, STPNHO: SETRTN for IEQUIB >= 0), the pieces'
        ends at the start (FBHO's UMAX, ISTART < 0), then the base's."""
        U = np.asarray(U, float)
        if self.iequib >= 0:
            # N + 1 pieces of an orbit turning 2 pi NRTN per loop end at x0 + 2 pi N NRTN
            # (TRANHO's shifts): the count from the first piece's start to the last's end
            k = sw.rotations(U[0, :self.ndm], U[-1, self._last])
            self._rotations = k if np.any(k) else None
        self._umax = U[-1].copy()
        super()._begin(U, old)

    def _pieces_start(self, rec, stored: int, par: np.ndarray):
        """The start of ISTART = -N (washer.cont.systems.homoclinic_switching): a record
        of the N + 1 pieces as it is, a 1-homoclinic orbit cut into them (TRANHO)."""
        ndm, n = self.ndm, self.pieces
        if rec is None or stored == 0:
            return rec                      # STPNT's pieces (`_from_stpnt`)
        if stored >= n * ndm:
            return rec
        if stored >= 3 * ndm:
            # an m-homoclinic orbit's pieces to N > m: its last loop repeated
            return sw.more_pieces(rec, ndm, n, par, self.lin)
        try:
            return sw.pieces_from_orbit(rec, ndm, n, par, self.lin,
                                        lambda u, p: self.user.func(np.asarray(u, float), p))
        except ValueError as e:
            raise SettingsError("IPS = 9: " + str(e), keys=("ISTART", "ITWIST")) from e

    def _equilibrium(self, u0, par) -> np.ndarray:
        """x0 (the left equilibrium): PAR(12 .. 11 + NDIM), after PVLS where the user's."""
        return self._equilibria(u0, par)[0]

    def _extended(self, user, ndm: int, nbc: int, nint: int) -> Problem:
        """The Problem the general BVP continues: f scaled by T = PAR(11), the NBC
        boundary conditions (FBHO's order: projections at t = 0, projections or the
        reversibility conditions at t = 1, the fixed test functions, Re l_(NSTAB+1) = 0
        of a saddle-node, f = 0 at the solved-for equilibria) and the phase condition as
        its one integral condition (none for a reversible system: the section at t = 1
        fixes the time shift)."""
        # the user's own boundary and integral conditions (none in the homotopy, whose
        # conditions INHO counts alone)
        n_user_bc, n_user_int = ((0, 0) if self.istart == 3
                                 else (self.settings_user.NBC, self.settings_user.NINT))

        def func_batch(U, pars):
            return pars[:, 10:11] * user.func_many(U, pars)

        def func(u, par):
            return par[PERIOD - 1] * user.func(u, par)

        dfdu_batch = None
        if user.has_dfdu:
            def dfdu_batch(U, pars):
                return pars[:, 10, None, None] * user.dfdu_many(U, pars)
        if self.itwist or self.pieces:
            func_batch, dfdu_batch = (sw.field(user, ndm, self.pieces) if self.pieces
                                      else adj.field(user, ndm))

            def func(u, par):
                return func_batch(np.asarray(u, float)[None], np.asarray(par, float)[None])[0]

        def bcnd(w0, w1, par):
            w0, w1 = np.asarray(w0, float), np.asarray(w1, float)
            u0, u1 = w0[:ndm], w1[:ndm]
            x1, x2, par = self._equilibria(u0, par)
            if self.istart == 3:
                return self._homotopy_bc(u0, u1, x1, x2, par)
            A1 = self._A(x1, par)
            parts = [self._left.rows(A1.T) @ (u0 - x1)]
            if self.rev is not None:
                parts.append(u1[self.rev])
            else:
                A2 = A1 if x2 is x1 else self._A(x2, par)
                end = self._right.rows(A2.T) @ (w1[self._last] - x2)
                if self.pieces and not self.lin:
                    end = end + ndm * par[sw.gap_index(1) - 1]   # FBHO's jump, see sw
                parts.append(end)
            if self.fixed:
                U = np.vstack([w0, w1])
                parts.append([self.psi(k, U, par, self._fixed_vectors)
                              for k in self.fixed])
            if self.iequib == 2:
                parts.append([np.sort(np.linalg.eigvals(A1).real)[self.nstab]])
            if self.iequib in (1, 2, -2):
                parts.append(user.func(x1, par))
            if self.iequib == -2:
                parts.append(user.func(x2, par))
            if self.itwist:
                A2 = A1 if x2 is x1 else self._A(x2, par)
                parts.append(adj.boundary_rows(self._adj_left, self._adj_right, A1, A2,
                                               w0[ndm:], w1[ndm:]))
            if self.pieces:
                parts += sw.boundary_rows(w0, w1, par, ndm, self.pieces, self.lin,
                                          self._umax)
            if n_user_bc:                   # FBHO's BCND on all NDIM components, last
                parts.append(user.bcnd(w0, w1, par, n_user_bc))
            return np.concatenate([np.ravel(q) for q in parts])

        def icnd(u, uold, udot, upold, par):
            # one point (NDIM,) -> (NINT,); a batch (NDIM, k) -> (NINT, k): the phase
            # condition (none with IREV or for the pieces of ISTART < 0), the adjoint's,
            # then the user's NINT on the orbit's NDIM components (ICHO's ICNI)
            parts = []
            if self.rev is None and not self.pieces:
                parts.append(np.sum(upold[:ndm] * (u[:ndm] - uold[:ndm]), axis=0))
            if self.itwist:
                parts.append(adj.integrand(u, uold, ndm))
            if n_user_int:
                a = [np.asarray(v, float)[:ndm] for v in (u, uold, udot, upold)]
                if a[0].ndim == 1:
                    parts.extend(user.icnd(*a, par, n_user_int))
                else:
                    parts.extend(np.array([user.icnd(*[v[:, j] for v in a], par, n_user_int)
                                           for j in range(a[0].shape[1])]).T)
            return np.stack(parts)

        return Problem(ndm * max(1 + self.itwist, self.pieces), func, func_batch=func_batch,
                       dfdu_batch=dfdu_batch,
                       name=user.name, npar=user.npar, pvls=user._pvls,
                       parnames=user.parnames, unames=user.unames, jac=user.jac,
                       bcnd=bcnd, icnd=icnd if nint else None)

    def _homotopy_bc(self, u0, u1, x1, x2, par) -> np.ndarray:
        """FBHO with ISTART = 3 (washer.cont.systems.homoclinic_homotopy), then f = 0 at
        the solved-for equilibria (IEQUIB = 1, -2)."""
        _, V, _ = spectrum(self._A(x1, par))
        _, _, W = spectrum(self._A(x2, par))
        V, W = self._hom_right(V), self._hom_left(W)
        parts = hom.boundary_rows(u0, u1, x1, x2, par, V, W, self.nstab, self.nunstab,
                                  homotopy_index(self.ndm, self.iequib))
        if self.iequib in (1, -2):
            parts.append(self.user.func(x1, par))
        if self.iequib == -2:
            parts.append(self.user.func(x2, par))
        return np.concatenate(parts)

    def _start_u0(self, rec, par, data) -> np.ndarray:
        """u(0) of the start (for PVLS's equilibrium with IEQUIB = 0)."""
        if rec is not None and np.ndim(rec.U) == 2:
            return np.asarray(rec.U, float)[0, :self.ndm]
        if rec is None and getattr(data, "data", None) is not None:
            return np.asarray(data.data[1], float)[0, :self.ndm]
        return np.asarray(data.u, float)[:self.ndm]

    # ------------------------------------------------------------------ starts
    def _from_stpnt(self) -> None:
        """STPNBV: the user's stpnt(u, par, t) at every node of the uniform mesh."""
        s = self.settings
        self._set_mesh(col.Mesh.uniform(s.NTST, s.NCOL))
        # the N + 1 pieces of ISTART < 0 (AUTO's STPNT with their NDIM), else the orbit
        U = self.user.start_profile(self.par.copy(), self.mesh.node_times(),
                                    ndim=self.ndm * max(self.pieces, 1))
        if self.istart == 3:
            x1, x2, self.par = self._equilibria(U[0], self.par)
            lam, V, W = spectrum(self._A(x1, self.par))
            U = hom.start(x1, x2, self.par, lam, self._hom_right(V), self._hom_left(W),
                          self.mesh.node_times(), self.nstab, self.nunstab,
                          homotopy_index(self.ndm, self.iequib))
        if self.itwist:
            # the adjoint as PREHO starts a restart's (AUTO's own STPNT start leaves it 0,
            # where its integral condition is degenerate)
            U, self.par[adj.ADJOINT_PAR - 1] = adj.widened_profile(U, self.ndm), 0.0
        self._begin(U, None)

    def _shifted(self, rec, par):
        """PREHO with ISTART = 4: a stored periodic orbit moved in time so that it starts
        at its mesh point nearest the equilibrium; for IEQUIB = 1 the equilibrium
        PAR(12 ..) is first the node where |f| is least (Newton does the rest)."""
        from types import SimpleNamespace
        from washer.cont.systems.bvp import record_profile
        ndm = self.ndm
        t, U, ntst, ncol = record_profile(rec, ndm)
        if self.iequib > 0:
            F = self.user.func_many(U, par)
            par[EQUILIBRIUM - 1:EQUILIBRIUM - 1 + ndm] = U[int(np.argmin(np.sum(F * F, axis=1)))]
        x0 = par[EQUILIBRIUM - 1:EQUILIBRIUM - 1 + ndm]
        mesh_U = U[::ncol]
        j = int(np.argmin(np.sum((mesh_U - x0) ** 2, axis=1)))
        if j in (0, ntst):
            return rec
        tm = t[::ncol]
        k = j * ncol
        # nodes from mesh point j to the end, then (periodicity: U[-1] = U[0]) from the
        # first interval to mesh point j
        U2 = np.vstack([U[k:], U[1:k + 1]])
        t2 = np.r_[t[k:] - tm[j], t[1:k + 1] + 1.0 - tm[j]]
        t2[-1] = 1.0
        return SimpleNamespace(U=U2, t=t2, ntst=ntst, ncol=ncol, udot=None, rldot=[],
                               icp=[], lab=getattr(rec, "lab", 0))

    # ------------------------------------------------------------------ per point
    def pvls_params(self, U, par, period, multipliers=None, problem=None) -> np.ndarray:
        """The user's PVLS on the orbit's NDIM components alone (AUTO's PVLSBV calls
        PVLS with NDM, HomCont's user NDIM: the first piece's with ISTART < 0, the orbit's
        beside its adjoint): a PVLS that sets PAR(12 .. 11 + NDIM) from its NDIM leaves
        the pieces' times PAR(21), PAR(23), .. and the gaps alone (kdv's)."""
        return super().pvls_params(np.asarray(U, float)[:, :self.ndm], par, period,
                                   multipliers, problem)

    def update(self, x, tangent) -> None:
        """The accepted point: the integral condition's reference (the base's) and the
        projections' reference bases."""
        super().update(x, tangent)
        if self.istart == 3:
            return
        U, par = self.unpack(x)
        x1, x2, par = self._equilibria(U[0, :self.ndm], par)
        A1 = self._A(x1, par)
        self._left.accept(A1.T)
        A2 = A1 if x2 is x1 else self._A(x2, par)
        if self.rev is None:
            self._right.accept(A2.T)
        if self.itwist:
            self._adj_left.accept(A1)
            self._adj_right.accept(A2)

    def params(self, x):
        """PAR after the user's PVLS, with PAR(20 + k) = psi_k for k in IPSI (FNCSHO)."""
        par = super().params(x)
        ipsi = self.settings.IPSI
        if ipsi:
            U, _ = self.unpack(x)
            for k in ipsi:
                par[PSI - 1 + k] = self.psi(k, U, par)
        return par

    def orientation(self, U: np.ndarray, par: np.ndarray) -> float:
        """PSIHO's 0 (FNCSHO's orientable / non-orientable) of the orbit and its adjoint
        U (n_nodes, 2 NDIM): see washer.cont.systems.homoclinic_adjoint.orientation."""
        ndm = self.ndm
        f0, f1 = self.user.func(U[0, :ndm], par), self.user.func(U[-1, :ndm], par)
        return adj.orientation(f0, f1, U[0, ndm:], U[-1, ndm:])

    def psi(self, k: int, U: np.ndarray, par: np.ndarray, signs=None) -> float:
        """PSIHO's test function k (module docstring) of the orbit U (n_nodes, NDIM), the
        eigenvectors' signs continued by `signs` (right, left; IPSI's own by default)."""
        ndm, s = self.ndm, self.nstab - 1              # s: 0-based index of l_NSTAB
        x0 = np.asarray(par[EQUILIBRIUM - 1:EQUILIBRIUM - 1 + ndm], float)
        lam, V, W = spectrum(self._A(x0, par))
        right, left = signs or (self._right_vectors, self._left_vectors)
        V, W = right(V), left(W)
        rr, ri = lam.real, lam.imag
        if k == 1:
            return float(rr[s] + rr[s + 1] + ri[s] + ri[s + 1])
        if k == 2:
            return float(-(ri[s] - ri[s - 1]) ** 2 if abs(ri[s]) > COMPZERO
                         else (rr[s] - rr[s - 1]) ** 2)
        if k == 3:
            return float(-(ri[s + 1] - ri[s + 2]) ** 2 if abs(ri[s + 1]) > COMPZERO
                         else (rr[s + 1] - rr[s + 2]) ** 2)
        if k == 4:
            return float(rr[s] + rr[s + 1])
        if k == 5:
            return float(rr[s] + rr[s + 1] + rr[s - 1])
        if k == 6:
            return float(rr[s] + rr[s + 1] + rr[s + 2])
        if k == 7:
            a, b = s, s - 2
            d = rr[a] - rr[b]
            return float(d if np.abs(V[a]).sum() > np.abs(V[b]).sum() else -d)
        if k == 8:
            a, b = s + 1, s + 3
            d = rr[a] - rr[b]
            return float(d if np.abs(V[a]).sum() > np.abs(V[b]).sum() else -d)
        if k == 9:
            return float(rr[s])
        if k == 10:
            return float(rr[s + 1])
        if k == 11:
            f1 = self.user.func(U[-1, :ndm], par)
            return float(f1 @ W[s] * math.exp(-par[PERIOD - 1] * rr[s] / 2))
        if k == 12:
            f0 = self.user.func(U[0, :ndm], par)
            return float(f0 @ W[s + 1] * math.exp(par[PERIOD - 1] * rr[s + 1] / 2))
        if k in ADJOINT_CODES:
            return adj.inclination(k, U[0, ndm:], U[-1, ndm:], lam, V, par[PERIOD - 1],
                                   self.nstab)
        if k == 15:
            return float((x0 - U[-1, :ndm]) @ V[s + 1])
        if k == 16:
            return float((x0 - U[0, :ndm]) @ V[s + 1])
        raise ValueError(f"IPSI code {k}: not computed (see washer.cont.systems.homoclinic)")


__all__ = ["HomoclinicOrbits", "PSI_CODES", "invariant_basis", "spectrum"]
