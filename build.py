"""cffi builders of the compiled kernel `washer._kernel` and of the continuation
engine's linear algebra `washer._cont` (out-of-line API mode).

Used by `pip install .` through setup.py (cffi_modules), or directly for an
in-place development build: `python build.py`. `python -m build` in this folder
means the PyPA frontend (sdists, wheels), not this file: run that way, this
module hands over to the frontend (see the end of the file).
Eigen's headers are taken from $EIGEN3_INCLUDE_DIR, default /usr/include/eigen3
(Debian's libeigen3-dev).
"""
import importlib.util
import os
from pathlib import Path

import cffi

HERE = Path(__file__).resolve().parent
# washer/build_stamp.py by its path: the package itself need not be importable here.
_spec = importlib.util.spec_from_file_location("_washer_build_stamp",
                                               HERE / "washer" / "build_stamp.py")
stamp = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(stamp)
EIGEN = os.environ.get("EIGEN3_INCLUDE_DIR", "/usr/include/eigen3")
if not (Path(EIGEN) / "Eigen" / "Dense").exists():
    raise SystemExit(
        f"Eigen headers not found in {EIGEN}: install them (Debian: apt-get install "
        "libeigen3-dev) or set EIGEN3_INCLUDE_DIR")

# Each module carries the hash of the sources it is built from (washer.build_stamp: at
# import, a checkout whose csrc/ has changed since refuses the module).
_kernel_stamp = stamp.stamp_code("washer._kernel", HERE)
ffibuilder = cffi.FFI()
ffibuilder.cdef((HERE / "csrc" / "washer_api.h").read_text() + "\n" + _kernel_stamp[0])
ffibuilder.set_source(
    "washer._kernel",
    '#include "washer.h"\n' + _kernel_stamp[1],
    sources=["csrc/kernel.cpp", "csrc/integrate.cpp", "csrc/generated/washer_model.cpp"],
    include_dirs=["csrc", EIGEN],
    source_extension=".cpp",
    # -O3 (the last -O on the line wins over Python's own flags): the generated model's
    # Jacobians at the 120 Gauss points of the whirl take 13-18 % less CPU than at -O2,
    # with the same values bit for bit (no -ffast-math: IEEE arithmetic unchanged).
    extra_compile_args=["-std=c++17", "-O3", "-fno-math-errno", "-DNDEBUG"],
    # -s: strip the symbol table (the unstripped kernel is ~30 MB, mostly symbols).
    extra_link_args=["-s"],
    language="c++",
)


#: The continuation engine's compiled linear algebra (washer/cont/reduction.py).
_cont_stamp = stamp.stamp_code("washer._cont", HERE)
contbuilder = cffi.FFI()
contbuilder.cdef((HERE / "csrc" / "cont" / "cont_api.h").read_text() + "\n" + _cont_stamp[0])
contbuilder.set_source(
    "washer._cont",
    '#include "cont.h"\n' + _cont_stamp[1],
    sources=["csrc/cont/reduce.cpp", "csrc/cont/assemble.cpp", "csrc/cont/po_correct.cpp",
             "csrc/cont/es_format.cpp", "csrc/cont/auto_point.cpp",
             "csrc/cont/dense_lapack.cpp", "csrc/cont/floquet.cpp",
             "csrc/cont/fold_tests.cpp", "csrc/cont/adapt.cpp",
             "csrc/cont/bvp_tangent.cpp"],
    include_dirs=["csrc/cont", EIGEN],
    source_extension=".cpp",
    # -O3: the elimination's short row updates (sub_scaled below 24 terms) and the
    # collocation loops vectorised: 2.7 % fewer instructions on lrz's orbits (callgrind),
    # the same values bit for bit (no -ffast-math and no -march: no reassociation, no
    # fused multiply-adds; reductions stay in order; -ffp-contract=off keeps it so where
    # the target has them, as aarch64: numpy's own products and sums, bit for bit).
    extra_compile_args=["-std=c++17", "-O3", "-fno-math-errno", "-DNDEBUG",
                        "-ffp-contract=off"],
    extra_link_args=["-s"],
    language="c++",
)


def _frontend() -> None:
    """`python -m build` started this file because the project folder comes first
    on sys.path: run the PyPA `build` frontend the user asked for instead."""
    import runpy
    import sys
    here = str(HERE)
    sys.path[:] = [p for p in sys.path if p not in ("", ".", here)
                   and Path(p or ".").resolve() != HERE]
    sys.modules.pop("build", None)
    try:
        runpy.run_module("build", run_name="__main__", alter_sys=True)
    except ImportError:
        raise SystemExit("python -m build: the PyPA 'build' frontend is not installed "
                         "(pip install build); `python build.py` compiles the kernel in place")


if __name__ == "__main__":
    if __spec__ is not None:           # run as `python -m build`, not as a script
        _frontend()
    else:
        os.chdir(HERE)
        import sys
        # `python build.py cont`: only the engine's module (the kernel takes minutes)
        for builder in ([contbuilder] if sys.argv[1:] == ["cont"] else [ffibuilder, contbuilder]):
            builder.compile(verbose=True)
