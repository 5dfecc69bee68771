"""AUTO-07p user files in Fortran or C as continuation problems.

    problem = load_compiled_problem("ab.f90", ndim=2)     # or ab.f, ab.c

compiles the user file with washer's bridge (user_files_bridge.c) into a shared
library (washer.cont.user_problem.c_library: once, cached by content hash, recompiled when the
file changes), loads it through cffi and returns a washer.cont.problem.Problem
calling AUTO's user ABI:

    FUNC(NDIM,U,ICP,PAR,IJAC,F,DFDU,DFDP)   right-hand side; IJAC = 1 (JAC = 1, -1):
                                            DFDU, IJAC = 2 (JAC = 1): DFDP too
    STPNT(NDIM,U,PAR,T)                     start (T in [0, 1] for orbits)
    PVLS(NDIM,U,PAR)                        solution measures, with GETP
    BCND, ICND, FOPT                        boundary / integral conditions, objective

C files follow AUTO's auto_f2c.h conventions (0-based arrays, column-major
Jacobians); washer ships that header (washer/cont/include). The batched entries
of the bridge evaluate a whole stencil or all collocation points in one foreign
call, so the per-point cost is the user's code plus a few nanoseconds.
"""
from __future__ import annotations

import weakref
from pathlib import Path

import numpy as np

from washer.cont.user_problem.c_library import (CompileError, build_library, declarations,
                                                source_file, source_text)
from washer.cont.linalg import eigenvalues_sorted
from washer.cont.problem import Problem, ProblemError

HERE = Path(__file__).parent
SHIM = HERE / "user_files_bridge.c"
# The headers the bridge includes (auto_f2c.h, ae_correct.h, ae_lyapunov.h) are the engine's,
# shared with the compiled correctors' own C: washer/cont/include/, one folder up.
INCLUDE = HERE.parent / "include"
#: User-file suffixes, in AUTO's order of lookup (runAUTO: .f90, .f, .c).
SUFFIXES = (".f90", ".f", ".c")
#: Length of the ICP array passed to user routines (AUTO passes its NPARX-long ICP).
ICP_LENGTH = 200
#: The least length of the PAR a user routine that writes PAR (STPNT, PVLS) receives:
#: AUTO's NPARX. AUTO's PAR is that long whatever NPAR, and user files write past NPAR
#: (kdv's PVLS sets PAR(12 .. 11 + NDIM) for the NDIM it is called with: 8 with HomCont's
#: adjoint, past its NPAR = 15).
PAR_LENGTH = 36


#: (library, arguments) of the process's last washer_po_bind (CompiledUser.po_pointers):
#: one record for all libraries, as two handles of one file share the bridge's storage.
_PO_BOUND: list = [None]


def _writable_par(par: np.ndarray):
    """(buffer, copy_back): `par` where it is PAR_LENGTH long or more, else a zero-padded
    copy; copy_back() puts the copy's first len(par) values into `par`."""
    if len(par) >= PAR_LENGTH:
        return par, lambda: None
    buf = np.zeros(PAR_LENGTH)
    buf[:len(par)] = par

    def copy_back():
        par[:] = buf[:len(par)]
    return buf, copy_back

CDEF = """
void washer_set_context(int ips, int ndim, int ntst, int ncol, int nbc, int nint,
                        const double *dtm);
void washer_set_measures(double rds, double fldf, double hbff, double biff, double spbf,
                         int nins, const double *eig);
int washer_has(const char *name);
int washer_eig_wanted(void);
void washer_func_batch(int k, int ndim, int npar, const double *us, const double *pars,
                       int par_stride, const int *icp, double *fs, double *scratch);
void washer_jac_batch(int k, int ndim, int npar, const double *us, const double *pars,
                      int par_stride, const int *icp, int ijac, double *fs, double *dfdus,
                      double *dfdps, double *scratch);
void washer_stpnt(int ndim, double t, double *u, double *par);
void washer_po_bind(int ndim, int npar, const int *icp, double *scratch);
void washer_po_func(int k, const double *us, const double *pars, int pstride, double *fs);
void washer_po_jac(int k, const double *us, const double *pars, int pstride, double *J,
                   double *Jp);
void washer_pvls(int ndim, const double *u, double *par);
int washer_pvls_ae(int ndim, const double *u, double *par, double *first, int npar);
int washer_pvls_bvp(int ips, int ndim, int ntst, int ncol, int nbc, int nint, int ntpl,
                    const double *u, const double *t, double *dtm, double *ups, int nins,
                    const double *eig, double *par, double *first, int npar);
void washer_set_homcont(const int *values);
void washer_bcnd(int ndim, const double *par, const int *icp, int nbc, const double *u0,
                 const double *u1, int ijac, double *fb, double *dbc);
void washer_icnd_batch(int k, int ndim, const double *par, const int *icp, int nint,
                       const double *u, const double *uold, const double *udot,
                       const double *upold, double *fi, double *scratch);
void washer_fopt(int ndim, const double *u, const int *icp, const double *par, int ijac,
                 double *fs, double *dfdu, double *dfdp);
void washer_fopt_batch(int k, int ndim, const double *us, const double *pars, int par_stride,
                       const int *icp, double *fs, double *scratch);
int washer_ae_correct(int kind, int ndim, int npar, int ip, int ip2, const int *icp,
                      const double *par, const double *v_old, const double *x_pred,
                      const double *x_ref, const double *theta, double ds, double epsl,
                      double epsu, int itnw, double divergence, double hmach, double h2,
                      double *x, int *iterations, double *jac, double *work,
                      double *scratch);
int washer_ae_l1(int ndim, int npar, const int *icp, const double *x, const double *par,
                 double omega, const double *A, double *l1, double *work, double *scratch);
"""

_ffi = declarations(CDEF, "bridge")
_libs: dict[str, object] = {}          # one dlopen per library file
_users: dict[str, "weakref.WeakSet"] = {}   # the CompiledUsers of each library file


def find_user_file(name: str, folder: Path) -> Path | None:
    """folder/NAME.f90, NAME.f or NAME.c (AUTO's order), or None."""
    for suffix in SUFFIXES:
        p = Path(folder) / f"{name}{suffix}"
        if p.exists():
            return p
    return None


def compile_user_file(path) -> Path:
    """The shared library of a user file and the bridge (compiled or from the cache),
    named by c_library.library_key alone (which remembers its keys in this process)."""
    path = Path(path)
    sources = [source_file(path), source_text("washer_shim.c", SHIM.read_bytes())]
    return build_library(sources, path.stem, includes=[INCLUDE],
                         defines={"WASHER_FORTRAN": int(path.suffix != ".c")})


def _open(lib_path: Path):
    key = str(lib_path)
    if key not in _libs:
        _libs[key] = _ffi.dlopen(key)
    return _libs[key]


#: The C type of the arrays passed, resolved once (a type string is parsed again on
#: every from_buffer call: a tenth of a collocation run's time in man's profile).
_DOUBLES = _ffi.typeof("double[]")
_INTS = _ffi.typeof("int[]")


def _dptr(a: np.ndarray):
    return _ffi.from_buffer(_DOUBLES, a)


class CompiledUser:
    """The user routines of one compiled file, with numpy in and out.

    Arrays passed in must be float64; they are made C-contiguous here. PAR
    arrays are passed whole (the user may read any PAR(i) up to their length)."""

    def __init__(self, path: Path, ndim: int, lib_path: Path | None = None):
        """path: the user file; lib_path: its library when built otherwise (generated
        C: washer.cont.user_problem.user_files_traced), else compiled here with the bridge."""
        self.path, self.ndim = Path(path), ndim
        self._lib_path = compile_user_file(path) if lib_path is None else Path(lib_path)
        self.lib = _open(self._lib_path)
        _users.setdefault(str(self._lib_path), weakref.WeakSet()).add(self)
        self.has = {n: bool(self.lib.washer_has(n.encode()))
                    for n in ("func", "stpnt", "bcnd", "icnd", "fopt", "pvls")}
        if not self.has["func"]:
            raise ProblemError(f"{path}: defines no FUNC (AUTO's FUNC(NDIM,U,ICP,PAR,IJAC,F,"
                               "DFDU,DFDP) is required)")
        self.icp = np.zeros(ICP_LENGTH, dtype=np.int32)
        self.icp[0] = 1
        self._icp_ptr = _ffi.from_buffer("int[]", self.icp)
        self._scratch = np.zeros(0)
        self._scratch_ptr = None
        self._pvls_seen = not self.has["pvls"]
        self.nbc = self.nint = 0
        self.pvls_wants_eigenvalues = False     # learnt on the first PVLS that asks GETP
        self._pvls_first = None                 # PAR before PVLS (`pvls_plain`, `pvls_orbit`)
        # AUTO's UPS and GETP's mesh intervals for `pvls_orbit`: the bridge's context
        # keeps pointing at the intervals after the call, as at the multipliers (_eig)
        self._ups = self._dtm = np.zeros(0)

    def reload(self) -> None:
        """Unload and load the library again: the user file's SAVEd and module variables
        start afresh, as they do in AUTO, where every run is a new process (pcl's PVLS
        sets up its boundary conditions on its FIRST call of each run). Every
        CompiledUser of the file gets the new handle."""
        key = str(self._lib_path)
        old = _libs.pop(key, None)
        if old is not None:
            _ffi.dlclose(old)              # first: dlopen of a loaded file is the same copy
        lib = _open(self._lib_path)
        for user in list(_users.get(key, ())):
            user.lib = lib
            user._pvls_seen = not user.has["pvls"]

    def _first_pvls(self, u, pars) -> None:
        """AUTO calls PVLS on the starting point before FUNC, and user files rely on it
        for one-time set-up (the brc and brf demos allocate FUNC's matrices there): the
        first FUNC call of this library is preceded by a PVLS call on its point, with
        PAR a scratch copy (its changes are not kept)."""
        self._pvls_seen = True
        par = np.array(pars[0] if np.ndim(pars) == 2 else pars, dtype=float)
        self.pvls(np.array(u[0], dtype=float), par)

    def set_icp(self, icp) -> None:
        """The run's ICP (what FUNC, BCND, ICND see as ICP(1..))."""
        self.icp[:] = 0
        self.icp[:len(icp)] = icp

    def set_sizes(self, nbc: int, nint: int) -> None:
        """The run's NBC and NINT (what PVLS reads with GETP('NBC'), GETP('NINT'))."""
        self.nbc, self.nint = int(nbc), int(nint)

    def _scratch_for(self, npar: int, extra: int = 0):
        need = self.ndim * (self.ndim + npar) + extra
        if len(self._scratch) < need:
            self._scratch = np.zeros(max(need, self.ndim * (self.ndim + 64)))
            self._scratch_ptr = _dptr(self._scratch)
        return self._scratch_ptr

    @staticmethod
    def _pars(pars, k):
        pars = np.ascontiguousarray(pars, dtype=float)
        if pars.ndim == 1:
            return pars, pars.shape[0], 0
        return pars, pars.shape[1], pars.shape[1]

    def func_batch(self, us, pars) -> np.ndarray:
        """f at the rows of us (k, NDIM); pars (k, NPAR) or (NPAR,) -> (k, NDIM)."""
        us = np.ascontiguousarray(us, dtype=float)
        if not self._pvls_seen:
            self._first_pvls(us, pars)
        k = us.shape[0]
        pars, npar, stride = self._pars(pars, k)
        fs = np.empty((k, self.ndim))
        self.lib.washer_func_batch(k, self.ndim, npar, _dptr(us), _dptr(pars), stride,
                                   self._icp_ptr, _dptr(fs), self._scratch_for(npar))
        return fs

    def func(self, u, par) -> np.ndarray:
        return self.func_batch(np.asarray(u, float).reshape(1, -1), par)[0]

    def jac_batch(self, us, pars, with_dfdp: bool = False):
        """(f, dfdu (k, NDIM, NDIM), dfdp (k, NDIM, NPAR) or None) from FUNC with IJAC = 1/2."""
        us = np.ascontiguousarray(us, dtype=float)
        if not self._pvls_seen:
            self._first_pvls(us, pars)
        k = us.shape[0]
        pars, npar, stride = self._pars(pars, k)
        fs = np.empty((k, self.ndim))
        J = np.empty((k, self.ndim, self.ndim))
        P = np.empty((k, self.ndim, npar)) if with_dfdp else None
        self.lib.washer_jac_batch(k, self.ndim, npar, _dptr(us), _dptr(pars), stride,
                                  self._icp_ptr, 2 if with_dfdp else 1, _dptr(fs), _dptr(J),
                                  _dptr(P) if with_dfdp else _ffi.NULL,
                                  self._scratch_for(npar))
        return fs, J, P

    @property
    def func_ready(self) -> bool:
        """Whether FUNC may be called directly (the first PVLS call has been made)."""
        return self._pvls_seen

    def ae_binder(self, kind, ndim, npar, ip, ip2, arrays):
        """washer_ae_correct (user_files_bridge.c; washer.cont.corrector_algebraic) of system `kind`
        bound to the corrector's arrays (float64, C-contiguous; `iterations` int32): a
        function of (ds, epsl, epsu, itnw, divergence, hmach, h2) returning the status."""
        p = {k: (_ffi.from_buffer(_INTS, a) if k == "iterations" else _dptr(a))
             for k, a in arrays.items()}

        def call(ds, epsl, epsu, itnw, divergence, hmach, h2) -> int:
            return self.lib.washer_ae_correct(
                kind, ndim, npar, ip, ip2, self._icp_ptr, p["par"], p["v_old"], p["x_pred"],
                p["x_ref"], p["theta"], ds, epsl, epsu, itnw, divergence, hmach, h2, p["x"],
                p["iterations"], p["jac"], p["work"], self._scratch_for(npar))
        return call

    def po_pointers(self, npar: int, ffi, func_kind: str, jac_kind: str):
        """(f, f_u) for the corrector of periodic orbits (csrc/cont/po_correct.cpp):
        washer_po_func and (JAC != 0) washer_po_jac of this file's bridge as C function
        pointers of the types `func_kind`, `jac_kind` declared by `ffi`, bound to this
        run's ICP and NPAR (washer_po_bind: call it again before every correction, as
        another run of the same library may have bound its own). None where the library
        has no such entries (a bridge built before them). f_u is NULL with JAC = 0."""
        lib = self.lib
        if not hasattr(lib, "washer_po_func"):
            return None
        # (made again only where the process's last binding was another library's or
        # had other arguments)
        bind = (lib, self.ndim, npar, self._icp_ptr, self._scratch_for(npar, extra=self.ndim))
        if _PO_BOUND[0] != bind:
            lib.washer_po_bind(*bind[1:])
            _PO_BOUND[0] = bind
        # the pointers themselves stay those of this library handle (`reload` makes a new
        # one): cast once per handle and kinds, not at every correction
        key = (ffi, func_kind, jac_kind)
        kept = self.__dict__.get("_po_kept")
        if kept is not None and kept[0] is lib and kept[1] == key:
            return kept[2]

        def pointer(name, kind):
            return ffi.cast(kind, int(_ffi.cast("uintptr_t", _ffi.addressof(lib, name))))
        pointers = (pointer("washer_po_func", func_kind), pointer("washer_po_jac", jac_kind))
        self._po_kept = (lib, key, pointers)
        return pointers

    def l1_binder(self, ndim, npar, arrays):
        """washer_ae_l1 (user_files_bridge.c, ae_lyapunov.h) bound to the arrays x, par, A, l1,
        work: a function of omega returning the status."""
        p = {k: _dptr(a) for k, a in arrays.items()}

        def call(omega) -> int:
            return self.lib.washer_ae_l1(ndim, npar, self._icp_ptr, p["x"], p["par"], omega,
                                         p["A"], p["l1"], p["work"], self._scratch_for(npar))
        return call

    def dfdu(self, u, par) -> np.ndarray:
        return self.jac_batch(np.asarray(u, float).reshape(1, -1), par)[1][0]

    def dfdu_batch(self, us, pars) -> np.ndarray:
        return self.jac_batch(us, pars)[1]

    def dfdp(self, u, par) -> np.ndarray:
        return self.jac_batch(np.asarray(u, float).reshape(1, -1), par, True)[2][0]

    def stpnt(self, u, par, t: float = 0.0) -> None:
        """AUTO's STPNT into u (NDIM,) and par (NPAR,) in place."""
        if not self.has["stpnt"]:
            raise ProblemError(f"{self.path}: defines no STPNT (needed to start with IRS = 0)")
        buf, copy_back = _writable_par(par)
        # NDIM as AUTO passes it: u's length (HomCont's pieces fill (N + 1) NDIM).
        # A user's STPNT may set more components than that (a script's NDIM=3 on a file
        # written for 4 sets U(4)): AUTO's U there has room for them (NDIM + 1 for
        # algebraic problems, the extended systems' NDIM beyond), so they are lost
        # without harm. Written into u itself they would land past its end in the heap.
        n = len(u)
        room = np.zeros(2 * n + 1)
        room[:n] = u
        self.lib.washer_stpnt(n, float(t), _dptr(room), _dptr(buf))
        u[:] = room[:n]
        copy_back()

    def pvls(self, u, par, t=None, ntst: int = 0, ncol: int = 0, ips: int | None = None) -> None:
        """AUTO's PVLS on u: (NDIM,) for algebraic problems, (NTPL, NDIM) mesh values of
        a BVP (t: the NTPL mesh times, or uniform). Sets par in place."""
        u = np.ascontiguousarray(u, dtype=float)
        par, copy_back = _writable_par(par)     # copy_back writes into the caller's
        keep = []
        if u.ndim == 2:
            ntpl = u.shape[0]
            if not (ntst and ncol):
                ncol = 4 if (ntpl - 1) % 4 == 0 else 1
                ntst = (ntpl - 1) // ncol
            dtm = _ffi.NULL
            if t is not None and len(t) == ntpl:
                d = np.ascontiguousarray(np.diff(np.asarray(t, float)[::ncol]))
                keep.append(d)
                dtm = _dptr(d)
            # UPS(NDIM*NCOL, NTST+1): the mesh points in a row, padded to full columns.
            # On loci the solution has more components than the user's NDIM (AUTO passes
            # the extended NDIM then).
            ndim = u.shape[1]
            ups = np.zeros(ndim * ncol * (ntst + 1))
            ups[:u.size] = u.ravel()
            self.lib.washer_set_context(2 if ips is None else ips, ndim, ntst, ncol,
                                        self.nbc, self.nint, dtm)
            self.lib.washer_pvls(ndim, _dptr(ups), _dptr(par))
        else:
            self.lib.washer_set_context(1 if ips is None else ips, self.ndim, 0, 0, 0, 0,
                                        _ffi.NULL)
            self.lib.washer_pvls(self.ndim, _dptr(u), _dptr(par))
        copy_back()

    def pvls_plain(self, u, par) -> np.ndarray | None:
        """AUTO's PVLS on an algebraic problem's u (NDIM,) without eigenvalues for GETP,
        par (NPAR,) set in place, in one foreign call (washer_pvls_ae): None, or where
        GETP asked for eigenvalues, a copy of par from before the call (then
        `set_multipliers` and `pvls` repeat it). A library built without that entry
        makes the calls one by one."""
        first = self._pvls_first
        if first is None or len(first) != len(par):
            first = self._pvls_first = np.empty(len(par))
        if not hasattr(self.lib, "washer_pvls_ae"):         # pragma: no cover - older build
            self.set_multipliers(None)
            first[:] = par
            self.pvls(u, par)
            return first.copy() if self.eig_wanted() else None
        self._eig = None
        u = np.ascontiguousarray(u, dtype=float)
        if self.lib.washer_pvls_ae(self.ndim, _dptr(u), _dptr(par), _dptr(first), len(par)):
            return first.copy()
        return None

    def eig_wanted(self) -> bool:
        """Whether the last PVLS asked GETP for 'EIG' or 'STA' that were not set."""
        return bool(self.lib.washer_eig_wanted())

    def _measures(self, mu, stable=None) -> tuple:
        """(pointer, nins) of GETP's 'EIG' and 'STA' for the multipliers (or eigenvalues)
        mu (None: NULL, 0); stable(mu) -> bool array says which count as stable (default
        |mu| <= 1). The values are held in `_eig` while the bridge's context points at
        them."""
        if mu is None:
            self._eig = None
            return _ffi.NULL, 0
        mu = np.asarray(mu, dtype=complex)
        self._eig = np.ascontiguousarray(np.column_stack([mu.real, mu.imag]).ravel())
        nins = int(np.sum(stable(mu))) if stable else int(np.sum(np.abs(mu) <= 1 + 1e-5))
        return _dptr(self._eig), nins

    def set_multipliers(self, mu, stable=None) -> None:
        """Floquet multipliers (or eigenvalues) for GETP's 'EIG' and 'STA' (None: none);
        stable(mu) -> bool array says which count as stable (default |mu| <= 1)."""
        eig, nins = self._measures(mu, stable)
        self.lib.washer_set_measures(0.0, 0.0, 0.0, 0.0, 0.0, nins, eig)

    def pvls_orbit(self, u, par, t, ntst: int, ncol: int, mu=None) -> np.ndarray | None:
        """AUTO's PVLS on a boundary-value solution in one foreign call (washer_pvls_bvp):
        u the node values (NTPL, k), t their times (NTPL,) (None: a uniform mesh), mu
        the Floquet multipliers for GETP's EIG and STA (None: none); par (NPAR,) set in
        place. None, or where GETP asked for multipliers it did not have, a copy of par
        from before the call (then the caller calls again with them). The calls `pvls`
        with `set_multipliers` make one by one, with the same values."""
        u = np.ascontiguousarray(u, dtype=float)
        ntpl, k = u.shape
        buf, copy_back = _writable_par(par)
        first = self._pvls_first
        if first is None or len(first) != len(buf):
            first = self._pvls_first = np.empty(len(buf))
        size = k * ncol * (ntst + 1)
        if len(self._ups) != size:
            self._ups = np.empty(size)
        tp = _ffi.NULL
        if t is not None and len(t) == ntpl:
            t = np.ascontiguousarray(t, dtype=float)
            if len(self._dtm) != ntst:
                self._dtm = np.empty(ntst)
            tp = _dptr(t)
        eig, nins = self._measures(mu)
        wanted = self.lib.washer_pvls_bvp(2, k, ntst, ncol, self.nbc, self.nint, ntpl,
                                          _dptr(u), tp, _dptr(self._dtm), _dptr(self._ups),
                                          nins, eig, _dptr(buf), _dptr(first), len(buf))
        copy_back()
        return first[:len(par)].copy() if wanted else None

    def bcnd(self, par, nbc: int, u0, u1) -> np.ndarray:
        """AUTO's BCND: the NBC boundary conditions at u(0) = u0, u(1) = u1."""
        par = np.ascontiguousarray(par, dtype=float)
        # NaN until BCND sets them: a condition it leaves unset (a stub BCND with NBC > 0)
        # is then refused by name (`CompiledProblem.bcnd`), not read as 0
        fb = np.full(nbc, np.nan)
        dbc = np.zeros(max(1, nbc * (2 * self.ndim + len(par))))
        self.lib.washer_bcnd(self.ndim, _dptr(par), self._icp_ptr, nbc,
                             _dptr(np.ascontiguousarray(u0, float)),
                             _dptr(np.ascontiguousarray(u1, float)), 0, _dptr(fb), _dptr(dbc))
        return fb

    def fopt_batch(self, us, pars) -> np.ndarray:
        """AUTO's FOPT (the objective of IPS = 5 and 15, value only) at the rows of us
        (k, NDIM); pars (k, NPAR) or (NPAR,) -> (k,)."""
        if not self.has["fopt"]:
            raise ProblemError(f"{self.path}: defines no FOPT (the objective "
                               "FOPT(NDIM,U,ICP,PAR,IJAC,FS,DFDU,DFDP) of IPS = 5 and 15)")
        us = np.ascontiguousarray(us, dtype=float)
        k = us.shape[0]
        pars, npar, stride = self._pars(pars, k)
        fs = np.empty(k)
        self.lib.washer_fopt_batch(k, self.ndim, _dptr(us), _dptr(pars), stride,
                                   self._icp_ptr, _dptr(fs), self._scratch_for(npar))
        return fs

    def icnd_batch(self, par, nint: int, u, uold, udot, upold) -> np.ndarray:
        """AUTO's ICND at k points (k, NDIM) each -> (k, NINT) integrands."""
        arrs = [np.ascontiguousarray(a, dtype=float) for a in (u, uold, udot, upold)]
        k = arrs[0].shape[0]
        par = np.ascontiguousarray(par, dtype=float)
        # NaN until ICND sets them (as fb in `bcnd`): AUTO-07p's own Fortran-77 bvp.f,
        # whose ICND is a stub, with the demo's NINT = 1 solved 0 = 0 silently; AUTO
        # computes NaN from its second point on (tests/test_user_files_native.py)
        fi = np.full((k, nint), np.nan)
        scratch = np.zeros(max(1, nint * (self.ndim + len(par))))
        self.lib.washer_icnd_batch(k, self.ndim, _dptr(par), self._icp_ptr, nint,
                                   *(_dptr(a) for a in arrs), _dptr(fi), _dptr(scratch))
        return fi


class CompiledProblem(Problem):
    """A Problem whose equations are a compiled AUTO user file (`.user` holds the
    routines: bcnd, icnd_batch, fopt for the boundary-value engine)."""

    def __init__(self, user: CompiledUser, name: str):
        self.user = user
        self.source = str(user.path)
        super().__init__(user.ndim, user.func, stpnt=user.stpnt if user.has["stpnt"] else None,
                         dfdu=user.dfdu, dfdp=user.dfdp, name=name,
                         dfdu_batch=user.dfdu_batch, func_batch=user.func_batch,
                         pvls=user.pvls if user.has["pvls"] else None,
                         bcnd=self._no_bcnd if user.has["bcnd"] else None,
                         icnd=self._no_icnd if user.has["icnd"] else None,
                         fopt_batch=user.fopt_batch if user.has["fopt"] else None)

    def fresh(self) -> None:
        """A new run: the user file's saved state starts afresh (`CompiledUser.reload`)."""
        self.user.reload()

    def set_homcont(self, values) -> None:
        """HomCont's constants into AUTO's COMMON /BLHOM/ of the user file: (ITWIST,
        ISTART, IEQUIB, NFIXED, NPSI, NUNSTAB, NSTAB, NREV)."""
        v = np.ascontiguousarray(values, dtype=np.int32)
        self.user.lib.washer_set_homcont(_ffi.from_buffer("int[]", v))

    # BCND and ICND need NBC / NINT, which the Problem passes to its methods: the
    # methods below call the compiled routines; the callables above only mark them present.
    @staticmethod
    def _no_bcnd(u0, u1, par):
        raise ProblemError("BCND is called through CompiledProblem.bcnd")

    @staticmethod
    def _no_icnd(u, uold, udot, upold, par):
        raise ProblemError("ICND is called through CompiledProblem.icnd")

    def bcnd(self, u0, u1, par, nbc: int) -> np.ndarray:
        """AUTO's BCND: the (nbc,) boundary conditions at u(0) = u0, u(1) = u1."""
        fb = self.user.bcnd(par, nbc, u0, u1)
        if not np.all(np.isfinite(fb)):
            raise ProblemError(f"{self.name}: BCND returned non-finite values or left "
                               f"some of FB(1..NBC = {nbc}) unset")
        return fb

    def icnd(self, u, uold, udot, upold, par, nint: int) -> np.ndarray:
        """AUTO's ICND at one mesh point: the (nint,) integrands."""
        return self.icnd_many(*(np.atleast_2d(np.asarray(a, float))
                                for a in (u, uold, udot, upold)), par, nint)[0]

    def icnd_many(self, U, Uold, Udot, Upold, par, nint: int) -> np.ndarray:
        """ICND at k mesh points in one foreign call: each argument (k, NDIM) -> (k, nint)."""
        fi = self.user.icnd_batch(par, nint, U, Uold, Udot, Upold)
        if not np.all(np.isfinite(fi)):
            raise ProblemError(f"{self.name}: ICND returned non-finite values or left "
                               f"some of FI(1..NINT = {nint}) unset")
        return fi

    def pvls(self, u, par, t=None, ntst: int = 0, ncol: int = 0) -> np.ndarray:
        """PAR after the user's PVLS (a copy). u: the state (NDIM,), or the node values
        (NTPL, NDIM) of an orbit: a washer.cont.pvls.Orbit carries its mesh (t, ntst,
        ncol) and multipliers (GETP's EIG, STA), else t, ntst, ncol say it."""
        par = np.array(par, dtype=float)
        if self._pvls is None:
            return par
        if getattr(u, "ntst", None):
            # An Orbit: its multipliers (GETP's EIG, STA) cost a condensation, so they are
            # computed only for a PVLS that asks for them (learnt on its first call).
            orbit, user = u, self.user
            t, ntst, ncol = orbit.t, orbit.ntst, orbit.ncol
            u = np.asarray(orbit).view(np.ndarray)
            wants = user.pvls_wants_eigenvalues
            first = user.pvls_orbit(u, par, t, ntst, ncol,
                                    orbit.multipliers if wants else None)
            if first is not None and not wants:
                user.pvls_wants_eigenvalues = True
                par[:] = first
                user.pvls_orbit(u, par, t, ntst, ncol, orbit.multipliers)
            return par
        if np.ndim(u) == 2:
            self.user.pvls(u, par, t=t, ntst=ntst, ncol=ncol)
            return par
        # Equilibria: GETP's EIG/STA are the eigenvalues of f_u (AUTO's order as the
        # d-file's), computed only for a PVLS that asks for them (learnt on its first call).
        if self.user.pvls_wants_eigenvalues:
            self._set_eigenvalues(u, par)
            self.user.pvls(u, par)
            return par
        first = self.user.pvls_plain(u, par)
        if first is not None:
            self.user.pvls_wants_eigenvalues = True
            par[:] = first
            self._set_eigenvalues(u, par)
            self.user.pvls(u, par)
        return par

    def _set_eigenvalues(self, u, par) -> None:
        lam = eigenvalues_sorted(self.dfdu(np.asarray(u, float), par))
        self.user.set_multipliers(lam, stable=lambda m: m.real < 0)

    def set_icp(self, icp) -> None:
        self.user.set_icp(icp)

    def set_sizes(self, nbc: int, nint: int) -> None:
        self.user.set_sizes(nbc, nint)


def load_compiled_problem(path, ndim: int, name: str = "") -> CompiledProblem:
    """The Problem of an AUTO user file (.f90, .f or .c). Raises CompileError (with the
    compiler's messages) or ProblemError."""
    path = Path(path)
    return CompiledProblem(CompiledUser(path, ndim), name or path.stem)


__all__ = ["CompileError", "CompiledProblem", "CompiledUser", "find_user_file",
           "compile_user_file", "load_compiled_problem"]
