"""The compiled kernel exists and matches the sources it was generated from."""
from pathlib import Path

import washer
from washer import codegen, kernel, layout


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
