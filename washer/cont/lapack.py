"""numpy's own LAPACK routines reached from the compiled engine: the addresses of
GETRF, GETRS and GEEV in the OpenBLAS numpy is linked with (its wheels bundle
scipy-openblas, ILP64, whose symbols are scipy_dgetrf_64_ etc.), for
csrc/cont/dense_lapack.cpp, which calls them as numpy.linalg's gufuncs do.

    routines()     # (getrf, getrs, geev) as cffi `void *` of washer._cont, or None

None where numpy links another LAPACK (a distribution's, MKL, Accelerate), the library
is not found or washer._cont lacks the calls: the callers then use numpy.linalg's
gufuncs, the same routines' values by another path. The library is the file
numpy.linalg has loaded, opened again: the same code, so the same bits.
"""
from __future__ import annotations

import ctypes
from pathlib import Path

#: the bundled OpenBLAS's file names and symbols (64-bit integers); no other is used
_PATTERN = "*scipy_openblas64_*"
_SYMBOLS = ("scipy_dgetrf_64_", "scipy_dgetrs_64_", "scipy_dgeev_64_")

#: the opened library: it stays loaded while the addresses are in use
_handles: list = []


def library_file() -> Path | None:
    """The scipy-openblas file numpy.linalg is linked with, beside numpy (numpy.libs on
    Linux wheels, numpy/.dylibs on macOS ones), or None."""
    import numpy
    root = Path(numpy.__file__).resolve().parent
    for folder in (root.parent / "numpy.libs", root / ".dylibs"):
        if folder.is_dir():
            for f in sorted(folder.glob(_PATTERN)):
                if f.suffix in (".so", ".dylib"):
                    return f
    return None


def routines():
    """(getrf, getrs, geev) of numpy's bundled OpenBLAS as `void *` of washer._cont's
    ffi, or None (see the module's docstring)."""
    try:
        from washer._cont import ffi, lib
    except ImportError:
        return None
    if not hasattr(lib, "cont_dense_lu"):
        return None
    import numpy.linalg  # noqa: F401  (numpy's own load of the library comes first)
    path = library_file()
    if path is None:
        return None
    try:
        handle = ctypes.CDLL(str(path))
        found = tuple(ffi.cast("void *", ctypes.cast(getattr(handle, name), ctypes.c_void_p).value)
                      for name in _SYMBOLS)
    except (OSError, AttributeError):
        return None
    _handles.append(handle)
    return found
