"""The compiled kernel exists and matches the sources it was generated from."""
from pathlib import Path

import washer
from washer import codegen
from washer.machine import kernel, layout


def test_compiled_extension_is_importable():
    import washer._kernel as k
    assert Path(k.__file__).suffix == ".so", "washer._kernel must be a compiled extension"
    assert k.lib.washer_n_params() == layout.N_PARAMS


def test_kernel_was_built_from_the_committed_generated_code():
    header = (codegen.OUT_DIR / "washer_model.h").read_text()
    assert kernel.inputs_hash() == codegen.stamp_of(header)


def test_public_api():
    for name in ("load_params", "Model", "Params", "ParameterError", "KernelError"):
        assert hasattr(washer, name)


def test_python_m_build_at_the_root_is_the_pypa_frontend_not_the_cffi_builder():
    """build.py (the cffi builder, as the project layout asks) shadows the PyPA `build`
    frontend for `python -m build` run in this folder: it must hand over (the frontend's
    usage, or a message that the frontend is not installed), never compile in place."""
    import subprocess
    import sys
    root = Path(__file__).resolve().parent.parent
    r = subprocess.run([sys.executable, "-m", "build", "--help"], cwd=root,
                       capture_output=True, text=True, timeout=120)
    out = r.stdout + r.stderr
    assert "generating" not in out.lower() and "washer._kernel" not in out
    if r.returncode == 0:
        assert "usage" in out.lower() and "--sdist" in out
    else:
        assert "PyPA 'build' frontend is not installed" in out
