"""Bad input gives clear errors; nothing crashes the interpreter."""
import numpy as np
import pytest

import washer
from washer.machine import kernel
from washer.machine.params import ParameterError, load_params

REF = load_params().source


def _write(tmp_path, text):
    p = tmp_path / "p.toml"
    p.write_text(text)
    return p


def _edit(old, new):
    text = open(REF).read()
    assert old in text
    return text.replace(old, new, 1)


@pytest.mark.parametrize("old,new,message", [
    ("m_u = 1.0", "m_u = 1.0\nbogus = 3", "[imbalance] bogus: unknown key"),
    ("R_u = 0.15 ", "", "[imbalance] R_u: missing key"),
    ("m = 12.0", "m = -12.0", "[tub] m = -12.0: expected a value > 0"),
    ("K_s = 1800.0", "K_s = -1.0", "[suspension] K_s = -1.0: expected a value >= 0"),
    ("K_s = 1800.0", "K_s = nan", "[suspension] K_s: expected a finite number"),
    ("upper_z = 0.87", "upper_z = -0.2", "rod 0 cannot reach"),
    ("n_rods = 4", "n_rods = 6", "n_rods = 6: the compiled kernel was generated for 4 rods"),
    ("[environment]", "[environmnt]", "unknown section [environmnt]"),
    ("r = [0.0, 0.0, 0.25]", "r = [0.0, 0.25]", "[tub] r: expected a list of 3 numbers"),
])
def test_bad_parameter_files(tmp_path, old, new, message):
    with pytest.raises(ParameterError) as err:
        load_params(_write(tmp_path, _edit(old, new)))
    assert message in str(err.value)
    assert str(tmp_path / "p.toml") in str(err.value)


def test_unreadable_and_malformed_files(tmp_path):
    with pytest.raises(ParameterError, match="cannot read"):
        load_params(tmp_path / "missing.toml")
    with pytest.raises(ParameterError, match="not valid TOML"):
        load_params(_write(tmp_path, "[operation\nOmega = 1"))


def test_replace_validates(params):
    with pytest.raises(ParameterError, match="m_u"):
        params.replace(m_u=-1)
    with pytest.raises(ParameterError, match="unknown parameter"):
        params.replace(Cp=1)
    assert params.replace(C_p=0.2)["C_ox"] == 0.2                 # tied
    untied = params.replace(C_ox=0.05)
    assert untied.replace(C_p=0.3)["C_ox"] == 0.05 and not untied.tied


def test_nan_state_is_an_exception(model):
    u = np.r_[model.static_equilibrium(), np.zeros(6)]
    u[3] = np.nan
    with pytest.raises(washer.KernelError, match="non-finite"):
        model.rhs_fixed(0.0, u)
    with pytest.raises(washer.KernelError, match="non-finite"):
        model.jac_rot(u)


def test_singular_mass_matrix_is_an_exception(params):
    P = params.vector()
    P[[washer.machine.layout.INDEX[n] for n in ("m_t", "m_b", "m_u", "J_tx", "J_ty", "J_tz", "J_bt", "J_bz")]] = 0
    with pytest.raises(washer.KernelError, match="singular"):
        kernel.rhs_fixed(0.0, np.r_[0, 0, 0.39, 0, 0, 0, np.zeros(6)], P)


def test_bad_names_and_shapes(model):
    with pytest.raises(ValueError, match="law"):
        model.rhs_fixed(0.0, np.zeros(12), law="fast")
    with pytest.raises(ValueError, match="frame"):
        model.rhs_rot(np.zeros(12), frame="spinning")
    with pytest.raises(ValueError, match="shape"):
        model.rhs_rot(np.zeros(11))
    with pytest.raises(TypeError, match="load_params"):
        washer.Model({"C_p": 1})


@pytest.mark.parametrize("old,new,field,hint", [
    ("Omega = 10.0", "Omega = 600.0", "[operation] Omega = 600", "Omega is in Hz"),
    ("m_u = 1.0", "m_u = 1000.0", "[imbalance] m_u = 1000", "1000 g is 1 kg"),
    ("R_u = 0.15", "R_u = 150.0", "[imbalance] R_u = 150", "150 mm is 0.15 m"),
    ("l0 = 0.4603496155090264", "l0 = 460.3", "[suspension] l0 = 460.3", "460 mm is 0.46 m"),
    ("m = 12.0", "m = 12000.0", "[tub] m = 12000", "12000 g is 12 kg"),
    ("upper_z = 0.87", "upper_z = 870.0", "[suspension] upper_z = 870", "upper_z is in m"),
    ("g = 9.81", "g = 981.0", "[environment] g = 981", "9.81 on Earth"),
])
def test_unit_slips_warn_naming_field_and_unit(tmp_path, old, new, field, hint):
    p = _write(tmp_path, _edit(old, new))
    with pytest.warns(washer.machine.params.ParameterWarning) as rec:
        load_params(p)
    msgs = [str(w.message) for w in rec]
    assert any(m.startswith(f"{p}: {field}") and hint in m for m in msgs), msgs


def test_absurd_rod_lengths_warn(tmp_path):
    p = _write(tmp_path, _edit("upper_z = 0.87", "upper_z = 2.9"))    # rods ~2.9 m long
    with pytest.warns(washer.machine.params.ParameterWarning, match=r"rod 0 is 2.9\d* m long"):
        load_params(p)


def test_the_reference_set_raises_no_warning():
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        load_params()
