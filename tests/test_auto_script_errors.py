"""Broken input to `python -m washer.auto` scripts and constants files, as a user makes it:
each error names the file and line (the script's, and the constants file's where the
fault is there) and what was expected, and the script stops there."""
import shutil
import warnings
from pathlib import Path

import pytest

from washer.auto import clui
from washer.auto.constants_file import ConstantsWarning
from washer.auto.script import ScriptError, run_script

DATA = Path(__file__).parent / "data"
DEMOS = DATA / "auto_demos"


@pytest.fixture
def ab(tmp_path, monkeypatch):
    """A folder with the ab problem (ab.py, c.ab: equilibria of AUTO's ab2p demo)."""
    monkeypatch.chdir(tmp_path)
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    clui._runner.refused.clear()
    return tmp_path


def _error(script: str, name: str = "x.auto") -> str:
    Path(name).write_text(script)
    with pytest.raises(ScriptError) as err:
        run_script(name)
    return str(err.value)


def _c_ab_with(line_start: str, replacement: str, name: str) -> int:
    """c.NAME: c.ab with the line starting with line_start replaced; its line number."""
    lines = Path("c.ab").read_text().splitlines()
    row = next(i for i, ln in enumerate(lines) if ln.startswith(line_start))
    lines[row] = replacement
    Path(f"c.{name}").write_text("\n".join(lines) + "\n")
    return row + 1


def test_misspelt_constant_in_a_constants_file_names_line_and_the_nearest(ab):
    line = _c_ab_with("NMX", "NMXX=  400, NPR=  400", "typo")
    msg = _error("run('ab', c='typo')\n")
    assert msg.startswith("x.auto:1: ")
    assert f"c.typo:{line}: unknown AUTO constant NMXX (did you mean NMX?)" in msg


def test_misspelt_keyword_of_a_command_names_the_nearest(ab):
    msg = _error("r = 1\nrun('ab', NMXX=3)\n")
    assert msg.startswith("x.auto:2: ") and "Unknown option: NMXX (did you mean NMX?)" in msg


def test_a_value_that_is_not_one_names_its_key_and_line(ab):
    line = _c_ab_with("NMX", "NMX= many, NPR=  400", "typ2")
    msg = _error("run('ab', c='typ2')\n")
    # an unquoted word is a value to AUTO's parseC (IRS = UZ1); NMX's conversion refuses it
    assert f"c.typ2:{line}: NMX expects an integer, got 'many'" in msg
    msg = _error("run('ab', NMX='many')\n")
    assert "run(e='ab'): NMX expects an integer, got 'many'" in msg       # named once
    msg = _error("run('ab', UZR={'x': 1})\n")
    assert "run(e='ab'): UZR: unknown parameter 'x'" in msg


def test_an_unclosed_bracket_names_the_line_it_opens(ab):
    """ICP = [1 on line 2, the next statement on line 3: the '[' of line 2 was never
    closed (it said line 3 expected a value, found 'NMX=3')."""
    Path("c.br").write_text("NDIM=2\nICP=[1\nNMX=3\n")
    msg = _error("run('ab', c='br')\n")
    assert "c.br:2: unclosed '[': expected ']' before 'NMX=3' (line 3)" in msg
    Path("c.br").write_text("NDIM=2\nUZSTOP={1: 0.1\nNMX=3\n")
    msg = _error("run('ab', c='br')\n")
    assert "c.br:2: unclosed '{': expected '}' before 'NMX=3' (line 3)" in msg


def test_missing_equations_file_says_what_was_looked_for(ab):
    msg = _error("run(e='nosuch', c='ab')\n")
    assert msg.startswith("x.auto:1: ")
    assert "No equations file found for: 'nosuch' (expected nosuch.f90, nosuch.f, nosuch.c " \
           "or nosuch.py in" in msg


def test_python_equations_with_a_syntax_error_name_file_and_line(ab):
    Path("bad.py").write_text("import numpy as np\ndef func(u, par)\n    return u\n")
    msg = _error("run(e='bad', c='ab')\n")
    assert "bad.py: failed to import: SyntaxError" in msg and "line 2" in msg


@pytest.mark.skipif(shutil.which("gfortran") is None, reason="gfortran is not installed")
def test_fortran_equations_that_do_not_compile_name_file_and_line(ab):
    src = (DEMOS / "ab" / "ab.f90").read_text().splitlines()
    row = next(i for i, ln in enumerate(src) if "F(1)=" in ln.replace(" ", ""))
    src[row] = src[row].replace("=", "= +*", 1)
    Path("fab.f90").write_text("\n".join(src) + "\n")
    msg = _error("run(e='fab', c='ab')\n")
    assert "fab.f90: compiling failed (gfortran" in msg and f"fab.f90:{row + 1}:" in msg


def test_a_label_not_in_the_solutions(ab):
    run_script_text = "run('ab', sv='ab')\n"
    Path("a.auto").write_text(run_script_text)
    run_script("a.auto")
    # by type and count: the selection's own words, without KeyError's quotes
    msg = _error("r = loadbd('ab')\nrun(r('HB9'))\n")
    assert msg.startswith("x.auto:2: KeyError: Label HB9 not found: there are 2 HB solutions")
    # by number, in a restart file: the file and the labels it holds
    msg = _error("run('ab', s='ab', IRS=99)\n")
    assert "Restart label IRS=99 not found: Label 99 not found (labels: [1, 2, 3, 4, 5, 6]) " \
           "in s.ab" in msg
    # a type the file does not hold: the types it does
    msg = _error("run('ab', s='ab', IRS='BT1')\n")
    assert "Label BT1 not found: there are 0 BT solutions (types here: EP, HB, LP, UZ) " \
           "in s.ab" in msg


def test_a_missing_restart_file(ab):
    msg = _error("run('ab', s='nosuch', IRS=2)\n")
    assert msg.startswith("x.auto:1: ") and "s.nosuch: no such solution file" in msg


def test_script_syntax_error_names_the_line(ab):
    msg = _error("r = 1\nrun('ab'\nprint 'x'\n")
    assert msg.startswith("x.auto:2: syntax error")


def test_icp_too_short_for_the_locus_names_the_icp_line_not_the_start(ab):
    """ISW = 2 at an HB with one ICP entry: the fault is ICP (its line in c.ab, or the
    command that set it), not the HB the run starts from."""
    line = next(i for i, ln in enumerate(Path("c.ab").read_text().splitlines(), 1)
                if ln.startswith("ICP"))
    msg = _error("r = run('ab')\nrun(r('HB1'), ISW=2)\n")
    assert f"c.ab:{line}: ISW = 2 continues a locus in two parameters: ICP needs two " \
           "entries, got [1]" in msg
    assert "cannot start from" not in msg
    msg = _error("r = run('ab')\nrun(r('HB1'), ICP=[1], ISW=2)\n")
    assert "run(e='ab'): ICP: ISW = 2 continues a locus" in msg and "cannot start" not in msg


# ------------------------------------------ AUTO's old positional constants format
def _old_format(tmp_path, icp_row: str) -> None:
    """enz's constants file (AUTO's old positional format) with its ICP row replaced."""
    for f in ("enz.f90", "c.enz"):
        shutil.copy(DEMOS / "enz" / f, tmp_path)
    lines = (tmp_path / "c.enz").read_text().splitlines()
    assert lines[1].split()[:2] == ["1", "1"]
    lines[1] = icp_row
    (tmp_path / "c.enz").write_text("\n".join(lines) + "\n")


@pytest.mark.parametrize("row, listed", [
    ("2 1\t\t\t\tNICP,(ICP(I),I=1,NICP)", "1 parameter index 1 then 'NICP'"),
    ("3 1 2   NICP,(ICP(I),I=1,NICP)", "2 parameter indices 1 2 then 'NICP'"),
    ("2 1", "1 parameter index 1 and the line ends"),
])
def test_old_format_nicp_larger_than_the_indices_listed(tmp_path, monkeypatch, row, listed):
    """NICP says more parameters than the row lists before its comment: the error names
    c.enz, line 2, the indices found and what was expected (AUTO's parseC would take
    the comment's first word for a parameter name)."""
    monkeypatch.chdir(tmp_path)
    _old_format(tmp_path, row)
    msg = _error("run(e='enz', c='enz')\n")
    nicp = row.split()[0]
    assert f"c.enz:2: NICP = {nicp} but the row lists {listed}" in msg
    assert "expected NICP (the number of continuation parameters, >= 1) followed by that " \
           "many parameter indices" in msg


def test_old_format_nicp_smaller_than_the_indices_listed_warns(tmp_path, monkeypatch):
    """NICP = 1 with two indices listed: AUTO reads ICP = [1] and the rest as a comment;
    so does washer, saying so (file, line, what it took)."""
    monkeypatch.chdir(tmp_path)
    _old_format(tmp_path, "1 1 2    NICP,(ICP(I),I=1,NICP)")
    from washer.auto.constants_file import read_constants
    with pytest.warns(ConstantsWarning, match=r"c.enz:2: NICP = 1 but the row lists 2 "
                                              r"parameter indices \(1 2\): ICP = \[1\]"):
        c = read_constants(tmp_path / "c.enz")
    assert c["ICP"] == [1]
    with warnings.catch_warnings():
        warnings.simplefilter("error", ConstantsWarning)
        _old_format(tmp_path, "1 1    NICP,(ICP(I),I=1,NICP)")
        assert read_constants(tmp_path / "c.enz")["ICP"] == [1]


def test_equations_that_raise_name_the_users_file_and_line(ab, capsys):
    """A Python user file whose func raises: the run fails at its start point, saying
    which user function failed, how, and where in the user's file; the script stops
    there (AUTO's runAUTO raises AUTORuntimeError for a run that ends in an error),
    the files of the runs before it kept."""
    Path("bad.py").write_text("import numpy as np\n\n\ndef func(u, par):\n    return u[5]\n\n\n"
                              "def stpnt(u, par):\n    pass\n")
    Path("x.auto").write_text("run(e='ab', c='ab', sv='good')\nrun(e='bad', c='ab', sv='bad')\n"
                              "run(e='ab', c='ab', sv='after')\n")
    with pytest.raises(ScriptError) as err:
        run_script("x.auto")
    msg = str(err.value)
    assert msg.startswith("x.auto:2: AutoError: run(e='bad') failed at its start:")
    assert "the equations fail at the start point (bad: func(u, par) failed: IndexError" in msg
    assert f"{Path('bad.py').resolve()}:5)" in msg or "bad.py:5)" in msg
    assert isinstance(err.value.__cause__, clui.AutoError)
    assert Path("b.good").stat().st_size > 0 and Path("s.good").stat().st_size > 0
    assert Path("b.bad").exists()               # what the failed run wrote is kept
    assert not Path("b.after").exists()         # the script stopped at the failed run


def test_a_failed_run_is_raised_to_the_caller_catchable_as_autos(ab):
    """Imported use: the failed run raises AutoError, which a script catches under
    AUTO's name (AUTOExceptions.AUTORuntimeError) and goes on."""
    Path("bad.py").write_text("def func(u, par):\n    raise ValueError('no')\n\n\n"
                              "def stpnt(u, par):\n    pass\n")
    with pytest.raises(clui.AutoError, match="failed at its start"):
        clui.run(e="bad", c="ab")
    Path("x.auto").write_text("import AUTOExceptions\ntry:\n    run(e='bad', c='ab')\n"
                              "except AUTOExceptions.AUTORuntimeError as exc:\n"
                              "    caught = str(exc)\nrun(e='ab', c='ab', sv='after')\n")
    ns = run_script("x.auto")
    assert "ValueError: no" in ns["caught"]
    assert Path("b.after").stat().st_size > 0


def test_a_branch_ending_at_mx_is_not_an_error(ab):
    """No convergence during the continuation ends the branch at MX (AUTO's STEPAE:
    'No convergence with minimum step size'); the run is a result and the script goes
    on, as AUTO's does."""
    Path("wall.py").write_text("import numpy as np\n\n\ndef func(u, par):\n"
                               "    if par[0] > 1.5:\n        raise ValueError('beyond')\n"
                               "    return np.array([u[0] - par[0]])\n\n\n"
                               "def stpnt(u, par):\n    u[0] = 1.0\n    par[0] = 1.0\n")
    Path("c.wall").write_text("NDIM=1, IPS=1, ICP=[1], IRS=0, NMX=100, NPR=100, DS=0.1, DSMIN=1e-3, "
                              "DSMAX=0.1, NPAR=1\n")
    Path("x.auto").write_text("r = run(e='wall', c='wall', sv='wall')\n"
                              "run(e='ab', c='ab', sv='after')\n")
    ns = run_script("x.auto")
    assert clui.splabs(ns["r"], "MX") == [2]
    assert Path("b.after").stat().st_size > 0


def test_the_command_line_exits_nonzero_after_a_failed_run(ab):
    """`python -m washer.auto x.auto`: the error on stderr, status 1."""
    import subprocess
    import sys
    import os
    Path("bad.py").write_text("def func(u, par):\n    raise ValueError('no')\n\n\n"
                              "def stpnt(u, par):\n    pass\n")
    Path("x.auto").write_text("run(e='ab', c='ab', sv='good')\nrun(e='bad', c='ab')\n"
                              "print('after')\n")
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]))
    p = subprocess.run([sys.executable, "-m", "washer.auto", "x.auto"], capture_output=True,
                       text=True, env=env, timeout=300)
    assert p.returncode == 1
    assert "x.auto:2: AutoError: run(e='bad') failed at its start" in p.stderr
    assert "after" not in p.stdout
    assert Path("b.good").stat().st_size > 0


def test_a_broken_constants_file_read_by_name_is_the_error(ab):
    """run('NAME') reads c.NAME when it is there: a c.NAME with a fault stops the script
    with its file and line (it was taken for a missing file and the run went on with the
    default constants)."""
    line = _c_ab_with("NMX", "NMX= many, NPR=  400", "ab")
    msg = _error("run('ab')\n")
    assert msg.startswith("x.auto:1: ")
    assert f"c.ab:{line}: NMX expects an integer, got 'many'" in msg


def test_a_comma_after_a_dictionary_key_is_read_as_auto_reads_it(ab):
    """AUTO's parseC scans {'p', [0, 1]} as {'p': [0, 1]} (':' and ',' both separate its
    tokens): a constants file written so runs in AUTO-07p, and is read the same here."""
    from washer.auto.constants_file import read_constants
    Path("c.d").write_text("NDIM = 2\nUZSTOP = {1, [0, 1.0]}\nUZR = {2: 0.5, 3, -1}\n")
    c = read_constants("c.d")
    assert c["UZSTOP"] == {1: [0, 1.0]} and c["UZR"] == {2: 0.5, 3: -1}
