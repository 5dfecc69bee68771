"""python -m washer.plots takes columns by name (parnames, unames, L2-NORM, PERIOD,
MAX x), draws one colour and legend entry per file, stable solid / unstable dashed,
and marks labelled points with their labels."""
import shutil
from pathlib import Path

import pytest

from washer.plots import diagrams
from washer.plots.__main__ import main

DATA = Path(__file__).parent / "data"
LRZ = DATA / "auto_demos" / "lrz" / "autoref" / "b.lrz"


def test_header_names_of_an_auto_b_file():
    titles, parnames, unames = diagrams.header_names(LRZ)
    assert titles[:3] == ["rho", "L2-NORM", "MAX x"] and titles[-1] == "PERIOD"
    assert parnames == {1: "rho", 2: "beta", 3: "sigma"}


@pytest.mark.parametrize("key,index", [
    ("rho", 0), ("PAR(1)", 0), ("L2-NORM", 1), ("l2-norm", 1), ("MAX x", 2),
    ("MAX U(1)", 2), ("MAX z", 4), ("PERIOD", 5), ("PAR(11)", 5), ("-1", -1), (1, 1),
])
def test_columns_by_name(key, index):
    titles = ["rho", "L2-NORM", "MAX x", "MAX y", "MAX z", "PERIOD"]
    parnames, unames = {1: "rho", 2: "beta"}, {1: "x", 2: "y", 3: "z"}
    assert diagrams.resolve_column(key, titles, parnames, unames) == index


def test_an_unknown_column_names_the_ones_there():
    with pytest.raises(KeyError, match=r"'beta': no such column \(columns: rho, L2-NORM"):
        diagrams.resolve_column("beta", ["rho", "L2-NORM"], {1: "rho", 2: "beta"}, {})


def test_one_colour_and_legend_entry_per_file(tmp_path, monkeypatch):
    for name in ("b.lrz", "b.copy"):
        shutil.copy(LRZ, tmp_path / name)
    figs = []
    from washer.plots import style
    real = style.save
    monkeypatch.setattr(style, "save", lambda fig, stem, **k: (figs.append(fig),
                                                               real(fig, stem, **k))[1])
    diagrams.save_diagram([tmp_path / "b.lrz", tmp_path / "b.copy"], tmp_path / "d",
                          "rho", "MAX x")
    ax = figs[0].axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["b.lrz", "b.copy", "stable", "unstable"]
    colours = {l.get_color() for l in ax.lines if l.get_label().startswith("_") and
               l.get_linestyle() in ("-", "--") and len(l.get_xdata()) > 1}
    assert colours == {"C0", "C1"}
    styles = {l.get_linestyle() for l in ax.lines if len(l.get_xdata()) > 1}
    assert styles == {"-", "--"}                       # stable and unstable parts
    notes = {t.get_text() for t in ax.texts}
    assert {"HB4", "HB6", "BP2"} <= notes
    assert ax.get_xlabel() == "rho" and ax.get_ylabel() == "MAX x"


def test_command_line_by_name_and_its_errors(tmp_path, capsys):
    shutil.copy(LRZ, tmp_path / "b.lrz")
    assert main([str(tmp_path / "b.lrz"), "--x", "rho", "--y", "PERIOD"]) == 0
    assert (tmp_path / "b_lrz_diagram.png").stat().st_size > 10000
    assert main([str(tmp_path / "b.lrz"), "--x", "rho", "--y", "gamma"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {tmp_path / 'b.lrz'}: 'gamma': no such column")


def test_unwritable_output_is_one_line(tmp_path, capsys):
    shutil.copy(LRZ, tmp_path / "b.lrz")
    (tmp_path / "afile").write_text("x")
    assert main([str(tmp_path / "b.lrz"), "--out", str(tmp_path / "afile" / "d")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "cannot write" in err and err.count("\n") == 1
