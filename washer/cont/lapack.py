"""numpy's and scipy's own LAPACK and BLAS routines reached from the compiled engine:
the addresses of GETRF, GETRS, GEEV, GESDD and CBLAS DDOT in the OpenBLAS numpy is linked
with (its wheels bundle scipy-openblas, ILP64, whose symbols are scipy_dgetrf_64_ etc.),
for csrc/cont/dense_lapack.cpp and fold_tests.cpp, which call them as numpy.linalg's
gufuncs and ndarray.dot do; and numpy's
GESDD, CBLAS DGEMM, DGEMV and DDOT with scipy's DGGEV (scipy's wheels bundle their own
scipy-openblas, LP64, symbols scipy_dggev_ etc.) for csrc/cont/floquet.cpp, which makes
the calls washer.cont.floquet's deflated pencil makes through numpy and scipy.

    routines()           # (getrf, getrs, geev, ddot, gesdd) as cffi `void *` of washer._cont,
                         # or None
    floquet_routines()   # (gesdd, dgemm, dgemv, ddot, dggev), or None

None where numpy or scipy links another LAPACK (a distribution's, MKL, Accelerate), the
library is not found or washer._cont lacks the calls: the callers then use numpy.linalg
and scipy.linalg, the same routines' values by another path. The libraries are the files
numpy and scipy have loaded, opened again: the same code, so the same bits.
"""
from __future__ import annotations

import ctypes
from pathlib import Path

#: the bundled OpenBLAS's file names and symbols (64-bit integers); no other is used
_PATTERN = "*scipy_openblas64_*"
_SYMBOLS = ("scipy_dgetrf_64_", "scipy_dgetrs_64_", "scipy_dgeev_64_", "scipy_cblas_ddot64_",
            "scipy_dgesdd_64_")
_FLOQUET_SYMBOLS = ("scipy_dgesdd_64_", "scipy_cblas_dgemm64_", "scipy_cblas_dgemv64_",
                    "scipy_cblas_ddot64_")
#: scipy's bundled OpenBLAS (32-bit integers), which scipy.linalg's flapack calls
_SCIPY_PATTERN = "libscipy_openblas-*"
_SCIPY_SYMBOLS = ("scipy_dggev_",)

#: the opened library: it stays loaded while the addresses are in use
_handles: list = []


def library_file(package=None, pattern: str = _PATTERN) -> Path | None:
    """The scipy-openblas file a package (numpy by default) is linked with, beside it
    (PACKAGE.libs on Linux wheels, PACKAGE/.dylibs on macOS ones), or None."""
    if package is None:
        import numpy as package
    root = Path(package.__file__).resolve().parent
    for folder in (root.parent / f"{root.name}.libs", root / ".dylibs"):
        if folder.is_dir():
            for f in sorted(folder.glob(pattern)):
                if f.suffix in (".so", ".dylib"):
                    return f
    return None


def _addresses(path: Path | None, names: tuple, ffi) -> tuple | None:
    """The symbols' addresses in the library file as cffi `void *`, the library kept
    open; None if it or a symbol is missing."""
    if path is None:
        return None
    try:
        handle = ctypes.CDLL(str(path))
        found = tuple(ffi.cast("void *", ctypes.cast(getattr(handle, name), ctypes.c_void_p).value)
                      for name in names)
    except (OSError, AttributeError):
        return None
    _handles.append(handle)
    return found


def routines():
    """(getrf, getrs, geev, cblas ddot, gesdd) of numpy's bundled OpenBLAS as `void *` of
    washer._cont's ffi, or None (see the module's docstring)."""
    try:
        from washer._cont import ffi, lib
    except ImportError:
        return None
    if not hasattr(lib, "cont_dense_lu") or not hasattr(lib, "cont_fold_tests"):
        return None
    import numpy.linalg  # noqa: F401  (numpy's own load of the library comes first)
    return _addresses(library_file(), _SYMBOLS, ffi)


def floquet_routines():
    """(gesdd, dgemm, dgemv, ddot) of numpy's bundled OpenBLAS and dggev of scipy's as
    `void *` of washer._cont's ffi, or None (see the module's docstring)."""
    try:
        from washer._cont import ffi, lib
    except ImportError:
        return None
    if not hasattr(lib, "cont_floquet_deflated"):
        return None
    import numpy.linalg  # noqa: F401  (numpy's and scipy's own loads come first)
    try:
        import scipy
        import scipy.linalg  # noqa: F401
    except ImportError:
        return None
    ours = _addresses(library_file(), _FLOQUET_SYMBOLS, ffi)
    theirs = _addresses(library_file(scipy, _SCIPY_PATTERN), _SCIPY_SYMBOLS, ffi)
    return None if ours is None or theirs is None else ours + theirs
