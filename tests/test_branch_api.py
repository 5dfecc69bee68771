"""A run's result reads like a table in Python: print(branch) is AUTO's table of
labelled points, columns by name, a DataFrame with named and typed columns; load()
gives named columns too; a failing func says so and leaves no empty file."""
import numpy as np
import pandas as pd
import pytest

from washer.run import load, main, run

BRUSSELATOR = '''
import numpy as np
def func(u, par):
    x, y = u
    A, B = par[0], par[1]
    return np.array([A - (B + 1) * x + x * x * y, B * x - x * x * y])
def stpnt(u, par, t=0):
    par[0], par[1] = 1.0, 0.5
    u[:] = [1.0, 0.5]
'''
CONSTANTS = """e = '{e}'
NDIM = 2
ICP = ['B']
parnames = {{1: 'A', 2: 'B'}}
unames = {{1: 'x', 2: 'y'}}
NMX = 100
DS = 0.02
DSMAX = 0.1
UZSTOP = {{'B': 3.0}}
"""


@pytest.fixture
def brus(tmp_path):
    (tmp_path / "brus.py").write_text(BRUSSELATOR)
    (tmp_path / "c.brus").write_text(CONSTANTS.format(e="brus"))
    return run(tmp_path / "c.brus", verbose=False), tmp_path


def test_print_is_the_table_of_labelled_points(brus):
    b, _ = brus
    text = str(b)
    lines = text.splitlines()
    assert lines[0].split() == ["BR", "PT", "TY", "LAB", "B", "L2-NORM", "x", "y"]
    assert [l.split()[2] for l in lines[1:4]] == ["EP", "HB", "UZ"]
    assert len(text) < 1000                       # not every point's every field
    assert repr(b).startswith("<Branch: ") and "1 HB" in repr(b) and len(repr(b)) < 300


def test_columns_by_parameter_and_state_name(brus):
    b, _ = brus
    B, x, y = b["B"], b["x"], b["y"]
    assert len(B) == len(b.rows) == len(b)
    # The Brusselator's equilibrium is (x, y) = (A, B / A), with A = 1 here.
    np.testing.assert_allclose(x, 1.0, atol=1e-10)
    np.testing.assert_allclose(y, B, atol=1e-10)
    np.testing.assert_array_equal(b["PAR(2)"], B)
    np.testing.assert_array_equal(b["U(2)"], y)
    np.testing.assert_allclose(b["L2-NORM"], np.hypot(x, y), atol=1e-10)
    with pytest.raises(KeyError, match="'C': not a parameter, state or column"):
        b["C"]


def test_a_quoted_index_is_that_parameter_as_in_icp(brus):
    """'2' names PAR(2) in a branch, a loaded b-file and a solution, as ICP = ['2']
    and UZSTOP = {'2': ...} read it (one reading of a parameter's name,
    washer.cont.constants.par_name_index); '-2' is no column."""
    b, folder = brus
    np.testing.assert_array_equal(b["2"], b["B"])
    np.testing.assert_array_equal(b["PERIOD"], b["PAR(11)"])
    with pytest.raises(KeyError):
        b["-2"]
    d = load(folder / "b.brus")
    np.testing.assert_array_equal(d[0]["2"], d[0]["B"])
    hb = d("HB1")
    assert hb["2"] == hb["B"] == hb.PAR["2"] == hb.PAR["PAR(2)"]
    with pytest.raises(KeyError):
        hb.PAR["-2"]


def test_labelled_point_by_name(brus):
    b, _ = brus
    hb = b("HB1")
    # Hopf point of the Brusselator: B = 1 + A^2 (trace of the Jacobian B - 1 - A^2 = 0);
    # located to the engine's EPSS (1e-5 relative) at least.
    assert hb.par[1] == pytest.approx(2.0, abs=1e-5)
    assert hb.ty == "HB"


def test_to_dataframe_names_types_and_stability(brus):
    b, _ = brus
    df = b.to_dataframe()
    assert list(df.columns[:9]) == ["BR", "PT", "TY", "LAB", "stable", "B", "L2-NORM", "x", "y"]
    assert "A" in df.columns and (df["A"] == 1.0).all()
    assert isinstance(df["TY"].dtype, pd.CategoricalDtype)
    assert list(df.loc[df["LAB"] > 0, "TY"]) == ["EP", "HB", "UZ"]
    # Stable before the Hopf point (B < 2), unstable after it.
    assert df.loc[df["B"] < 1.99, "stable"].all()
    assert not df.loc[df["B"] > 2.01, "stable"].any()
    assert df.attrs["units"] == {}                 # a user problem states no units


def test_washer_dataframe_carries_units(tmp_path):
    (tmp_path / "c.w").write_text("e = 'washer'\nNDIM = 12\nICP = ['C_p']\nJAC = 1\nNMX = 3\n"
                                  "NPAR = 17\nDS = 0.01\nDSMAX = 0.05\n")
    df = run(tmp_path / "c.w", verbose=False).to_dataframe()
    assert df.attrs["units"]["C_p"] == "N m s/rad" and df.attrs["units"]["m_u"] == "kg"
    assert df["m_u"].nunique() == 1


def test_load_gives_named_columns(brus):
    b, folder = brus
    d = load(folder / "b.brus")
    np.testing.assert_allclose(d[0]["B"], b["B"], rtol=1e-9)
    np.testing.assert_allclose(d["L2-NORM"], b["L2-NORM"], rtol=1e-9)
    assert d("HB1")["B"] == pytest.approx(b("HB1").par[1], rel=1e-9)
    assert [r.lab for br in d for r in br if r.lab] == [1, 2, 3]    # rows as before


def test_failing_func_says_so_and_leaves_no_empty_file(tmp_path, capsys):
    (tmp_path / "bad.py").write_text(BRUSSELATOR.replace(
        "    x, y = u\n", "    raise ZeroDivisionError('boom in func')\n"))
    (tmp_path / "c.bad").write_text(CONSTANTS.format(e="bad"))
    assert main([str(tmp_path / "c.bad")]) == 1
    out, err = capsys.readouterr()
    assert "done" not in out and "Saved as" not in out
    assert "boom in func" in err and "no point was computed" in err
    assert not (tmp_path / "b.bad").exists() and not (tmp_path / "s.bad").exists()


def test_a_labelled_point_prints_in_one_line(brus):
    b, _ = brus
    text = repr(b("HB1"))
    assert text.startswith("<Record HB2: BR 1 PT ") and "PAR(2)=2" in text
    assert "\n" not in text and len(text) < 200
