"""cffi builder of the compiled kernel `washer._kernel` (out-of-line API mode).

Used by `pip install .` through setup.py (cffi_modules), or directly for an
in-place development build: `python build_kernel.py`.
Eigen's headers are taken from $EIGEN3_INCLUDE_DIR, default /usr/include/eigen3
(Debian's libeigen3-dev).
"""
import os
from pathlib import Path

import cffi

HERE = Path(__file__).resolve().parent
EIGEN = os.environ.get("EIGEN3_INCLUDE_DIR", "/usr/include/eigen3")
if not (Path(EIGEN) / "Eigen" / "Dense").exists():
    raise SystemExit(
        f"Eigen headers not found in {EIGEN}: install them (Debian: apt-get install "
        "libeigen3-dev) or set EIGEN3_INCLUDE_DIR")

ffibuilder = cffi.FFI()
ffibuilder.cdef((HERE / "csrc" / "washer_api.h").read_text())
ffibuilder.set_source(
    "washer._kernel",
    '#include "washer.h"',
    sources=["csrc/kernel.cpp", "csrc/integrate.cpp", "csrc/generated/washer_model.cpp"],
    include_dirs=["csrc", EIGEN],
    source_extension=".cpp",
    extra_compile_args=["-std=c++17", "-O2", "-fno-math-errno", "-DNDEBUG"],
    # -s: strip the symbol table (the unstripped kernel is ~30 MB, mostly symbols).
    extra_link_args=["-s"],
    language="c++",
)

if __name__ == "__main__":
    os.chdir(HERE)
    ffibuilder.compile(verbose=True)
