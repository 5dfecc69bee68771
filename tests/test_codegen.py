"""Generated code is up to date and reproducible byte for byte."""
import pytest
from washer import codegen


def test_stamp_matches_current_inputs():
    """Fails when the model sources changed but csrc/generated was not regenerated."""
    for name in ("washer_model.h", "washer_model.cpp"):
        text = (codegen.OUT_DIR / name).read_text()
        assert codegen.stamp_of(text) == codegen.input_hash(), (
            f"{name} is stale: run `python -m washer.codegen`")


@pytest.mark.slow
def test_regeneration_is_byte_identical():
    files = codegen.generate()
    for name, text in files.items():
        assert (codegen.OUT_DIR / name).read_text() == text, f"{name} differs from generator output"
