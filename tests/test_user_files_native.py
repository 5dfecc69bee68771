"""AUTO user files in Fortran and C, compiled on the fly (washer.cont.user_problem.c_library,
.compiled).

Checked against independent references: the Python transcription of the same equations
(tests/data/ab_demo/ab.py), central differences for the user's Jacobians, closed-form
integrals for GETP's solution measures; the cache by file modification; compiler errors
by the file and line they name.
"""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.cont.user_problem.c_library import CompileError, build_library, source_file, source_text
from washer.cont.user_problem.user_files_native import load_compiled_problem
from washer.cont.user_problem.user_files import load_python_problem

DATA = Path(__file__).parent / "data"
AB_F90 = DATA / "auto_demos" / "ab" / "ab.f90"

pytestmark = pytest.mark.skipif(shutil.which("gfortran") is None or shutil.which("gcc") is None,
                                reason="gcc and gfortran are needed (Debian: gcc gfortran)")


@pytest.fixture
def cache(tmp_path, monkeypatch):
    d = tmp_path / "cache"
    monkeypatch.setenv("WASHER_CACHE", str(d))
    return d


def _points(rng, k=20):
    us = rng.normal(0, 0.5, (k, 2))
    pars = np.zeros((k, 36))
    pars[:, :3] = rng.uniform(0.05, 5.0, (k, 3))
    return us, pars


@pytest.mark.parametrize("source", [AB_F90, DATA / "compiled" / "ab.c"], ids=["fortran", "c"])
def test_user_file_equals_python_transcription(source, cache, tmp_path):
    p = load_compiled_problem(source, 2)
    ref = load_python_problem("ab", DATA / "ab_demo", 2)
    rng = np.random.default_rng(1)
    us, pars = _points(rng)
    np.testing.assert_allclose(p.func_many(us, pars), ref.func_many(us, pars), rtol=1e-14,
                               atol=1e-15)
    for u, par in zip(us[:3], pars[:3]):
        np.testing.assert_allclose(p.func(u, par), ref.func(u, par), rtol=1e-14, atol=1e-15)
    u, par = p.start(36)
    u_ref, par_ref = ref.start(36)
    np.testing.assert_array_equal(u, u_ref)
    np.testing.assert_array_equal(par, par_ref)


def test_user_jacobians_used_with_jac1(cache):
    """JAC = 1: DFDU and DFDP from FUNC with IJAC = 2, against central differences."""
    p = load_compiled_problem(DATA / "compiled" / "jac.f90", 2)
    rng = np.random.default_rng(2)
    us, pars = _points(rng, 5)
    for u, par in zip(us, pars):
        fd = p.with_jac(0).jacobian(u, par, [1, 2, 3])
        analytic = p.with_jac(1).jacobian(u, par, [1, 2, 3])
        np.testing.assert_allclose(analytic, fd, rtol=1e-7, atol=1e-8)
        # the analytic one is exactly the closed form
        expect_u = [[par[0] - 3 * u[0] ** 2, par[1]], [-1 - 2 * u[0] * u[1], par[2] - u[0] ** 2]]
        np.testing.assert_allclose(analytic[:, :2], expect_u, rtol=1e-15)
    batch = p.with_jac(1).dfdu_many(us, pars)
    assert batch.shape == (5, 2, 2)
    np.testing.assert_allclose(batch[0], p.with_jac(1).dfdu(us[0], pars[0]), rtol=1e-15)


def test_getp_measures_of_an_orbit(cache):
    """GETP in PVLS on u1 = sin 2 pi t, u2 = t over NTST = 10, NCOL = 4: AUTO's quadrature
    (Newton-Cotes on each interval) against the closed forms."""
    p = load_compiled_problem(DATA / "compiled" / "jac.f90", 2)
    ntst, ncol = 10, 4
    t = np.linspace(0, 1, ntst * ncol + 1)
    U = np.column_stack([np.sin(2 * np.pi * t), t])
    par = p.pvls(U, np.zeros(36), t=t, ntst=ntst, ncol=ncol)
    assert par[20] == pytest.approx(math.sqrt(0.5), abs=1e-6)     # NRM: (int u1^2)^(1/2)
    assert par[21] == pytest.approx(0.0, abs=1e-12)               # INT u1
    assert par[22] == pytest.approx(1.0, abs=1e-15)               # MAX u1 (t = 1/4 is a node)
    assert par[23] == pytest.approx(-1.0, abs=1e-15)              # MIN u1
    assert (par[24], par[25]) == (0.0, 1.0)                       # BV0, BV1 of u2
    assert par[26] == pytest.approx(0.25, abs=1e-15)              # MXT: t of the maximum
    assert (par[27], par[28]) == (ntst, ncol)
    # algebraic problems: GETP returns the component (AUTO's GETP for IPS <= 1)
    par = p.pvls(np.array([-0.3, 0.7]), np.zeros(36))
    assert par[20] == pytest.approx(0.3) and par[22] == pytest.approx(-0.3)


def test_getp_of_an_orbit_in_one_call(cache):
    """PVLS on an orbit (a washer.cont.pvls.Orbit, as the periodic systems pass it) in one
    foreign call: the same PAR bit for bit as the routines called one by one (GETP's
    measures on a non-uniform mesh, whose intervals the bridge takes from the node
    times); GETP('EIG') and 'STA' the orbit's multipliers, asked for on the first call
    (which is repeated with them, PAR restored) and given from then on."""
    from washer.cont.pvls import Orbit
    p = load_compiled_problem(DATA / "compiled" / "jac.f90", 2)
    ntst, ncol = 10, 4
    knots = np.cumsum(np.r_[0.0, np.linspace(1.0, 2.0, ntst)])
    knots /= knots[-1]
    t = np.concatenate([knots[j] + (knots[j + 1] - knots[j]) * np.arange(ncol) / ncol
                        for j in range(ntst)] + [knots[-1:]])
    U = np.column_stack([np.sin(2 * np.pi * t), t])
    mu = np.array([1.0 + 0j, 0.5 + 0.2j])
    asked = []

    def multipliers():
        asked.append(1)
        return mu
    orbit = Orbit.of(U, t, np.zeros(len(t)), 2.0, ntst, ncol, multipliers)
    par0 = np.arange(34.0)             # shorter than AUTO's PAR: padded for PVLS
    assert not p.user.pvls_wants_eigenvalues
    out = p.pvls(orbit, par0)
    assert p.user.pvls_wants_eigenvalues and asked == [1]
    p.user.set_multipliers(mu)
    one_by_one = p.pvls(U, par0, t=t, ntst=ntst, ncol=ncol)
    np.testing.assert_array_equal(out, one_by_one)
    np.testing.assert_array_equal(out[29:33], [1.0, 0.0, 0.5, 0.2])
    assert out[33] == 2                                          # STA: |mu| <= 1
    # the mesh's own intervals: NRM by its quadrature, MXT the time of the largest node
    assert out[20] == pytest.approx(math.sqrt(0.5), abs=1e-5)
    assert out[26] == pytest.approx(t[np.argmax(U[:, 0])], abs=1e-15)
    assert (out[27], out[28]) == (ntst, ncol)
    np.testing.assert_array_equal(out[:20], par0[:20])
    # learnt: the next orbit's PVLS is one call with its multipliers
    mu = np.array([1.0 + 0j, 2.0 + 0j])
    out = p.pvls(Orbit.of(U, t, np.zeros(len(t)), 2.0, ntst, ncol, mu), par0)
    np.testing.assert_array_equal(out[29:34], [1.0, 0.0, 2.0, 0.0, 1])


def test_getp_eigenvalues_of_an_equilibrium(cache):
    """GETP('EIG') on an equilibrium: the eigenvalues of f_u (real, imaginary parts
    alternating, by decreasing real part), here of the closed-form Jacobian; 'STA' the
    number with negative real part."""
    p = load_compiled_problem(DATA / "compiled" / "jac.f90", 2).with_jac(1)
    u = np.array([0.3, -0.2])
    par = np.zeros(36)
    par[:3] = [0.5, -2.0, 0.1]
    out = p.pvls(u, par)
    A = np.array([[par[0] - 3 * u[0] ** 2, par[1]], [-1 - 2 * u[0] * u[1], par[2] - u[0] ** 2]])
    lam = np.linalg.eigvals(A)
    lam = lam[np.argsort(-lam.real, kind="stable")]
    np.testing.assert_allclose(out[29:33], [lam[0].real, lam[0].imag, lam[1].real, lam[1].imag],
                               rtol=1e-12, atol=1e-14)
    assert out[33] == np.sum(lam.real < 0)


def test_cache_reuses_and_rebuilds(cache, tmp_path):
    src = tmp_path / "ab.f90"
    shutil.copy(AB_F90, src)
    lib1 = build_library([source_file(src)], "ab")
    mtime = lib1.stat().st_mtime_ns
    assert build_library([source_file(src)], "ab") == lib1          # from the cache
    assert lib1.stat().st_mtime_ns == mtime
    src.write_text(src.read_text().replace("F(1)=-U1", "F(1)=-2*U1"))
    lib2 = build_library([source_file(src)], "ab")
    assert lib2 != lib1 and lib2.exists()
    # and the rebuilt equations are the edited ones
    p = load_compiled_problem(src, 2)
    par = np.zeros(36)
    assert p.func(np.array([1.0, 0.0]), par)[0] == -2.0



def test_a_user_file_edited_in_the_same_process_is_built_again(cache, tmp_path):
    """In one process (library_key remembers the keys it hashed, by the sources' content)
    the same file twice is the same library, an edited one a new library with the
    edited equations, and the library is checked to exist before it is reused."""
    from washer.cont.user_problem.user_files_native import compile_user_file
    src = tmp_path / "ab.f90"
    shutil.copy(AB_F90, src)
    lib1 = compile_user_file(src)
    assert compile_user_file(src) == lib1
    src.write_text(src.read_text().replace("F(1)=-U1", "F(1)=-2*U1"))
    lib2 = compile_user_file(src)
    assert lib2 != lib1 and lib2.exists()
    assert load_compiled_problem(src, 2).func(np.array([1.0, 0.0]), np.zeros(36))[0] == -2.0
    lib2.unlink()                                 # the cache emptied under the process
    assert compile_user_file(src).exists()

def test_a_user_files_library_is_named_by_library_key_alone(cache, tmp_path, monkeypatch):
    """One definition of what decides a user file's library: c_library.library_key. A
    change that key sees (here a key made to differ, as an edited include file or a new
    compiler makes it) gives another library in the same process; no second key beside
    it can keep the first library."""
    from washer.cont.user_problem import c_library
    from washer.cont.user_problem.user_files_native import compile_user_file
    src = tmp_path / "ab.f90"
    shutil.copy(AB_F90, src)
    lib1 = compile_user_file(src)
    key = c_library.library_key
    monkeypatch.setattr(c_library, "library_key", lambda *a, **k: "0" * 20)
    lib2 = compile_user_file(src)
    assert lib2 != lib1 and lib2.name == "ab-" + "0" * 20 + ".so" and lib2.exists()
    monkeypatch.setattr(c_library, "library_key", key)
    assert compile_user_file(src) == lib1


def test_compile_error_names_file_and_line(cache, tmp_path):
    bad = tmp_path / "bad.f90"
    bad.write_text(AB_F90.read_text().replace("E=EXP(U2)", "E=EXP(U2"))
    line = next(i for i, s in enumerate(bad.read_text().splitlines(), 1) if "E=EXP(U2" in s)
    with pytest.raises(CompileError) as err:
        load_compiled_problem(bad, 2)
    assert f"bad.f90:{line}" in str(err.value)
    c_bad = tmp_path / "bad.c"
    c_bad.write_text('#include "auto_f2c.h"\nint func(integer ndim) { return x; }\n')
    with pytest.raises(CompileError) as err:
        load_compiled_problem(c_bad, 2)
    assert "bad.c:2" in str(err.value)


def test_generated_sources_compile_too(cache):
    """The compile step is not tied to user files: any C text, cached the same way."""
    from cffi import FFI
    lib = build_library([source_text("twice.c", "double twice(double x) { return 2 * x; }\n")],
                        "twice")
    ffi = FFI()
    ffi.cdef("double twice(double x);")
    assert ffi.dlopen(str(lib)).twice(21.0) == 42.0


def test_fortran_and_c_runs_give_the_same_branch(cache, tmp_path):
    """The ab demo's first run (c.ab.1) from the Fortran and the C file: same b-file rows."""
    from washer.auto.files import read_b
    from washer.run import run
    rows = {}
    for src in (AB_F90, DATA / "compiled" / "ab.c"):
        d = tmp_path / src.suffix[1:]
        d.mkdir()
        shutil.copy(src, d / src.name)
        shutil.copy(DATA / "auto_demos" / "ab" / "c.ab.1", d / "c.ab.1")
        run(d / "c.ab.1", verbose=False, sv="out", e="ab")
        rows[src.suffix] = [(r.pt, r.ty, r.lab, r.values) for b in read_b(d / "b.out") for r in b]
    assert rows[".f90"] == rows[".c"] and len(rows[".c"]) > 10


def test_a_stub_icnd_with_integral_conditions_stops_the_run_by_name(cache, tmp_path,
                                                                     monkeypatch):
    """AUTO-07p's Fortran-77 bvp.f (tests/data/auto_demos/bvpf77) has a stub ICND, while
    the demo's constants ask for NINT = 1: FI(1) is never set. AUTO-07p 0.9.2 computes
    NaN from its second point on (its b-file, kept beside the file); the integrand left
    unset stops washer's run at its start, naming ICND, instead of being read as 0 (a
    condition 0 = 0 that left PAR(2) free and went to PAR(1) = 5.5 on the trivial branch
    without a branch point)."""
    import gzip

    from washer.auto.script import run_script
    demos = DATA / "auto_demos"
    rows = [ln.split() for ln in gzip.open(demos / "bvpf77" / "autoref" / "b.bvp.gz", "rt")
            if not ln.startswith("   0")]
    assert rows[0][1] == "1" and all(r[4] == "NaN" for r in rows[1:]) and len(rows) == 200
    for f in (demos / "bvp").iterdir():
        if f.is_file() and f.name != "bvp.f90":
            shutil.copy(f, tmp_path)
    shutil.copy(demos / "bvpf77" / "bvp.f", tmp_path)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(Exception, match=r"ICND returned non-finite values or left some of "
                                        r"FI\(1\.\.NINT = 1\) unset"):
        run_script("bvp.auto")


INCLUDING_F = """\
      SUBROUTINE FUNC(NDIM,U,ICP,PAR,IJAC,F,DFDU,DFDP)
      IMPLICIT DOUBLE PRECISION (A-H,O-Z)
      INCLUDE 'rate.inc'
      DIMENSION U(NDIM),PAR(*),F(NDIM)
      F(1)=RATE*U(1)
      RETURN
      END
      SUBROUTINE STPNT(NDIM,U,PAR)
      IMPLICIT DOUBLE PRECISION (A-H,O-Z)
      DIMENSION U(NDIM),PAR(*)
      U(1)=1.D0
      RETURN
      END
      SUBROUTINE BCND
      RETURN
      END
      SUBROUTINE ICND
      RETURN
      END
      SUBROUTINE FOPT
      RETURN
      END
      SUBROUTINE PVLS
      RETURN
      END
"""

INCLUDING_C = """\
#include "auto_f2c.h"
#include "rate.h"
int func(integer ndim, const doublereal *u, const integer *icp, const doublereal *par,
         integer ijac, doublereal *f, doublereal *dfdu, doublereal *dfdp)
{ f[0] = RATE * u[0]; return 0; }
int stpnt(integer ndim, doublereal t, doublereal *u, doublereal *par) { u[0] = 1.0; return 0; }
int bcnd(integer ndim, const doublereal *par, const integer *icp, integer nbc,
         const doublereal *u0, const doublereal *u1, integer ijac, doublereal *fb,
         doublereal *dbc) { return 0; }
int icnd(integer ndim, const doublereal *par, const integer *icp, integer nint,
         const doublereal *u, const doublereal *uold, const doublereal *udot,
         const doublereal *upold, integer ijac, doublereal *fi, doublereal *dint) { return 0; }
int fopt(integer ndim, const doublereal *u, const integer *icp, const doublereal *par,
         integer ijac, doublereal *fs, doublereal *dfdu, doublereal *dfdp) { return 0; }
int pvls(integer ndim, const doublereal *u, doublereal *par) { return 0; }
"""


@pytest.mark.parametrize("kind", ["fortran", "c"])
def test_a_user_file_is_built_again_when_a_file_it_includes_changes(kind, cache, tmp_path):
    """AUTO's brc.f takes its dimensions from brc.inc (INCLUDE 'brc.inc'), a C file may
    #include "x.h" of its own: the library is keyed by the included files too, so an
    edited include file gives the edited equations, in the same process (library_key's
    memo) and in a new one (build_library's key)."""
    from washer.cont.user_problem import c_library
    from washer.cont.user_problem.user_files_native import compile_user_file
    if kind == "fortran":
        src, inc = tmp_path / "rate.f", tmp_path / "rate.inc"
        src.write_text(INCLUDING_F)
        write = lambda r: inc.write_text(f"      PARAMETER (RATE={r}D0)\n")  # noqa: E731
    else:
        src, inc = tmp_path / "rate.c", tmp_path / "rate.h"
        src.write_text(INCLUDING_C)
        write = lambda r: inc.write_text(f"#define RATE {r}\n")  # noqa: E731
    write(2.0)
    assert c_library.included_files(src) == [inc]
    lib2 = compile_user_file(src)
    assert load_compiled_problem(src, 1).func(np.array([1.5]), np.zeros(36))[0] == 3.0
    write(3.0)
    lib3 = compile_user_file(src)
    assert lib3 != lib2
    assert load_compiled_problem(src, 1).func(np.array([1.5]), np.zeros(36))[0] == 4.5
    key3 = c_library.library_key([source_file(src)])
    write(2.0)
    assert c_library.library_key([source_file(src)]) != key3
    assert compile_user_file(src) == lib2     # the first library, from the cache


#: A fold x^2 = PAR(1) whose FUNC gives DFDU but leaves DFDP as the caller filled it
#: (zeros), as AUTO's she.f and fhh's fhn.f do; DFDP_LINE is the line that sets it.
UNSET_DFDP_F = """\
      SUBROUTINE FUNC(NDIM,U,ICP,PAR,IJAC,F,DFDU,DFDP)
      IMPLICIT NONE
      INTEGER NDIM, ICP(*), IJAC
      DOUBLE PRECISION U(NDIM), PAR(*), F(NDIM)
      DOUBLE PRECISION DFDU(NDIM,NDIM), DFDP(NDIM,*)
      F(1) = PAR(1) - U(1)**2 + PAR(2)*U(2)
      F(2) = -U(2)
      IF (IJAC.EQ.0) RETURN
      DFDU(1,1) = -2*U(1)
      DFDU(1,2) = PAR(2)
      DFDU(2,1) = 0
      DFDU(2,2) = -1
      IF (IJAC.EQ.1) RETURN
C     DFDP_LINE
      END
      SUBROUTINE STPNT(NDIM,U,PAR,T)
      IMPLICIT NONE
      INTEGER NDIM
      DOUBLE PRECISION U(NDIM), PAR(*), T
      PAR(1) = 1
      PAR(2) = 0.5
      U(1) = 1
      U(2) = 0
      END
"""


@pytest.mark.parametrize("jac, icp, dfdp, warned", [
    (1, [1], "", ["PAR(1)"]),        # DFDP unset, f moves with PAR(1): said once
    (1, [1, 2], "", ["PAR(1)"]),     # d f / d PAR(2) = U(2) = 0 at the start: no word
    (1, [1], "DFDP(1,1) = 1", []),   # DFDP set
    (-1, [1], "", []),               # JAC = -1: DFDP is not used (differences)
    (0, [1], "", [])])
def test_a_dfdp_left_unset_is_named_once(cache, tmp_path, jac, icp, dfdp, warned):
    """FUNC gets DFDP zero-filled (as in AUTO-07p), so a user file that never sets it
    gives zero parameter derivatives that JAC = 1 takes as exact: one ProblemWarning
    per such continuation parameter at the run's start, naming the file and PAR(i),
    where a central difference of f shows f depends on it."""
    import warnings
    from washer.cont.problem import ProblemWarning
    from washer.run import run
    src = tmp_path / "fold.f"
    src.write_text(UNSET_DFDP_F.replace("C     DFDP_LINE", f"      {dfdp}" if dfdp else
                                        "C     DFDP left unset"))
    (tmp_path / "c.fold").write_text(f"e = 'fold'\nNDIM = 2\nICP = {icp}\nJAC = {jac}\n"
                                     "NMX = 20\nDS = -0.05\nDSMAX = 0.1\nISP = 0\n")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run(tmp_path / "c.fold", verbose=False)
    said = [str(w.message) for w in caught if issubclass(w.category, ProblemWarning)]
    assert len(said) == len(warned)
    for text, name in zip(said, warned):
        assert str(src) in text and f"d f / d {name}" in text
