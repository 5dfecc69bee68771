"""Bad AUTO input is a clear error naming file, line and expectation; outputs never
escape the run's folder, follow a symlink or truncate the restart file."""
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.auto.constants_file import Constants, ConstantsError, parse_override, read_constants
from washer.auto.files import AutoFileError, OutputFiles, read_b, read_s

from test_auto_formats import check_parseB_rules

DATA = Path(__file__).parent / "data"
S_EQ = DATA / "auto_reference" / "ab2p" / "s.eq"
#: The built-in washer's parameter names (auto_washer.PAR_NAMES), typed from docs/continuation.md.
WASHER_NAMES = {1: "C_p", 2: "Omega", 3: "m_u", 4: "R_u", 5: "h_u", 6: "C_a", 7: "K_s",
                8: "C_ox", 9: "C_oz", 10: "l0", 13: "J_bz", 14: "J_bt", 15: "m_b", 16: "h_b",
                17: "m_t"}


def _c(tmp_path, text, name="c.x"):
    p = tmp_path / name
    p.write_bytes(text if isinstance(text, bytes) else text.encode())
    return p


# ------------------------------------------------------------ name constants
@pytest.mark.parametrize("stmt", ["sv = '../x'", "sv = 'out/x'", "s = '..'", "s = '/tmp/eq'",
                                  "sv = 'a\\b'", "dat = 'x/../../y'"])
def test_paths_in_names_are_refused_in_files(tmp_path, stmt):
    with pytest.raises(ConstantsError) as err:
        read_constants(_c(tmp_path, f"NDIM = 2\n{stmt}\n"))
    msg = str(err.value)
    assert msg.startswith(f"{tmp_path / 'c.x'}:2:") and "is a name" in msg and "not a path" in msg


@pytest.mark.parametrize("override", ["sv=../x", "s=../../etc/x", "sv=sub/x"])
def test_paths_in_names_are_refused_as_overrides(override):
    key, value = parse_override(override)
    with pytest.raises(ConstantsError, match="is a name"):
        Constants().set(key, value)


def test_plain_names_pass():
    c = Constants({"sv": "hopf.bwd", "s": "eq", "e": "washer:frozen"})
    assert (c["sv"], c["s"], c["e"]) == ("hopf.bwd", "eq", "washer:frozen")


def test_e_may_be_a_path_as_auto_reads_it(tmp_path):
    """AUTO's e is the user file's path without its suffix (e='./functions/yamada'
    compiles ./functions/yamada.f90): only read, so a path is kept (s, dat, sv are
    names: above)."""
    c = read_constants(_c(tmp_path, "NDIM = 2\ne = './functions/model'\n"))
    assert c["e"] == "./functions/model"
    assert Constants({"e": "../models/m"})["e"] == "../models/m"


# ----------------------------------------------------------- values and ICP
@pytest.mark.parametrize("stmt,message", [
    ("DS = 1e999", "DS expects a finite number"),
    ("DSMAX = 1d400", "DSMAX expects a finite number"),
    ("DSMIN = -0.001", "DSMIN expects a value >= 0.0"),
    ("DSMAX = 0", "DSMAX expects a value > 0.0"),
    ("EPSL = -1e-7", "EPSL expects a value >= 0.0"),
    ("NDIM = 0", "NDIM expects a value >= 1"),
    ("ICP = [0]", "ICP entries are parameter indices >= 1"),
    ("ICP = [1, -1]", "ICP entries are parameter indices >= 1"),
])
def test_bad_values_name_file_and_line(tmp_path, stmt, message):
    with pytest.raises(ConstantsError, match=message) as err:
        read_constants(_c(tmp_path, f"NDIM = 2\n\n{stmt}\n"))
    assert str(err.value).startswith(f"{tmp_path / 'c.x'}:3:")


@pytest.mark.parametrize("key", ["DS", "DSMIN", "DSMAX", "EPSL", "EPSU", "EPSS"])
def test_nan_and_inf_overrides(key):
    for bad in (float("nan"), float("inf")):
        with pytest.raises(ConstantsError, match=f"{key} expects a finite number"):
            Constants().set(key, bad)


def test_icp_name_resolving_to_par0_is_refused():
    with pytest.raises(ConstantsError, match=r"ICP entry 'PAR\(0\)' is PAR\(0\)"):
        Constants({"ICP": ["PAR(0)"]}).icp()


# --------------------------------------------------- binary and garbage files
@pytest.mark.parametrize("content,line,message", [
    (b"NDIM = 2\n\x00\x01\x02\x03", 2, "a NUL byte: this is a binary file"),
    (b"NDIM = 2\nICP = [1]\n# caf\xe9\n", 3, "byte 0xe9 is not UTF-8 text"),
    (b"\x1f\x8b\x08\x00garbage", 1, "a NUL byte: this is a binary file"),      # gzip
    (b"NDIM = 2\n\x01\x02 ~~~ garbage", 2, "expected a constant name"),
    (b"# only a comment\n! and another\n", None, "no KEY = value statements"),
])
def test_binary_and_garbage_constants_files(tmp_path, content, line, message):
    with pytest.raises(ConstantsError, match=message) as err:
        read_constants(_c(tmp_path, content))
    where = str(tmp_path / "c.x") + (f":{line}:" if line else ":")
    assert str(err.value).startswith(where)


def test_missing_file_names_the_shipped_examples(tmp_path):
    with pytest.raises(ConstantsError, match="--copy-examples"):
        read_constants(tmp_path / "c.washer")


# ------------------------------------------------------- corrupt s-files
def _corrupt(tmp_path, edit) -> Path:
    lines = S_EQ.read_text().splitlines(keepends=True)
    p = tmp_path / "s.eq"
    data = edit(lines)
    p.write_bytes(data if isinstance(data, bytes) else "".join(data).encode())
    return p


@pytest.mark.parametrize("edit,line,message", [
    (lambda L: L[:5], 1, "announces NROWPR = 6 lines, only 4 follow"),   # the only record
    (lambda L: ["   garbage in the header\n"] + L[1:], 1, "expected an s-file record header"),
    (lambda L: [L[0].replace("    0\n", "    0    7\n")] + L[1:], 1, "this one has 17"),
    (lambda L: [L[0], L[1].replace("E+000", "E+0x0", 1)] + L[2:], 2,
     "expected a number in the solution block"),
    (lambda L: L[:5] + [L[5].rsplit(" ", 1)[0] + "\n"] + L[6:], 6,
     "the parameters PAR(1..NPAR) should hold 11 numbers"),
    (lambda L: "".join(L).encode()[:300] + b"\xff\xfe" + "".join(L).encode()[300:], 6,
     "not UTF-8"),
    (lambda L: [L[0].replace("   11    0    2", "   11   12    2")] + L[1:], 1,
     "NPARI = 12, expected 0..NPAR = 11"),
    (lambda L: [L[0].replace("   11    0    2", "   11   -1    2")] + L[1:], 1,
     "NPARI = -1, expected 0..NPAR = 11"),
])
def test_corrupt_s_files_are_clear_errors(tmp_path, edit, line, message):
    p = _corrupt(tmp_path, edit)
    with pytest.raises(AutoFileError) as err:
        read_s(p)
    assert str(err.value).startswith(f"{p}:{line}:"), str(err.value)
    assert message in str(err.value)


def test_truncated_last_record_leaves_the_others_readable(tmp_path):
    """A killed writer may cut the last record short: the intact ones are read, the
    damaged one is named (file, line, what is missing), never silently dropped."""
    recs = read_s(_corrupt(tmp_path, lambda L: L[:-2]))
    assert [r.lab for r in recs] == [1, 2, 3, 4, 5]
    assert len(recs.damaged) == 1
    assert recs.damaged[0].startswith(f"{tmp_path / 's.eq'}:36:")
    assert "only 4 follow: the file is truncated" in recs.damaged[0]
    assert recs.header_lines[id(recs[1])] == f"{tmp_path / 's.eq'}:8"   # header + 6 lines


def test_reference_s_file_reads_unchanged():
    """The checks accept AUTO's own file (6 records, HB at label 2)."""
    recs = read_s(S_EQ)
    assert [r.lab for r in recs] == [1, 2, 3, 4, 5, 6] and recs[1].code == 3
    assert len(recs[1].U) == 2 and len(recs[1].par) == 11


def test_binary_b_file_is_an_error(tmp_path):
    p = tmp_path / "b.x"
    p.write_bytes(b"\x00" * 10)
    with pytest.raises(AutoFileError, match="binary"):
        read_b(p)


# ------------------------------------------------------------ output safety
def test_outputs_replace_symlinks_never_their_targets(tmp_path):
    precious = tmp_path / "precious.txt"
    precious.write_text("keep me")
    (tmp_path / "b.x").symlink_to(precious)
    (tmp_path / "d.x").symlink_to(tmp_path / "missing-target")
    out = OutputFiles(tmp_path, "x")
    out.diag("a note")
    assert precious.read_text() == "keep me"
    assert not (tmp_path / "b.x").is_symlink() and (tmp_path / "b.x").read_text() == ""
    assert not (tmp_path / "missing-target").exists()


def test_unwritable_output_is_a_clear_error_before_the_run(tmp_path):
    (tmp_path / "s.x").mkdir()                      # a folder where the s-file should go
    with pytest.raises(AutoFileError, match=r"s\.x: cannot write this output file"):
        OutputFiles(tmp_path, "x")


def test_restart_file_is_kept_not_truncated(tmp_path):
    """sv equal to the restart file's name: the old records move to s.x~ first."""
    shutil.copy(S_EQ, tmp_path / "s.x")
    (tmp_path / "sub").mkdir()
    restart = tmp_path / "sub" / ".." / "s.x"          # same file, other spelling
    out = OutputFiles(tmp_path, "x", protect=[restart])
    assert out.backups == [tmp_path / "s.x~"]
    assert (tmp_path / "s.x~").read_text() == S_EQ.read_text()
    assert (tmp_path / "s.x").read_text() == ""
    # Without protection an output of the same name is started afresh (AUTO's behaviour).
    OutputFiles(tmp_path, "y")
    assert (tmp_path / "s.y").read_text() == ""


# ------------------------------------------------------- default parnames
def test_default_names_complete_but_never_override_the_users():
    c = Constants({"e": "washer", "ICP": ["m_u", "Omega"]})
    with pytest.raises(ConstantsError, match="unknown parameter 'm_u'"):
        c.icp()
    assert c.with_default_names(WASHER_NAMES).icp() == [3, 2]
    # The user's names win: index 5 is called 'Omega' here, so the default for 2 is skipped.
    mine = Constants({"parnames": {5: "Omega", 3: "mass"}, "ICP": ["Omega", "mass", "K_s"]})
    named = mine.with_default_names(WASHER_NAMES)
    assert named.icp() == [5, 3, 7]
    assert 2 not in named["parnames"] and named["parnames"][17] == "m_t"
    assert mine["parnames"] == {5: "Omega", 3: "mass"}               # a copy, not an edit
    assert "parnames" not in c.with_default_names(WASHER_NAMES).given  # defaults, not the user's


def test_builtin_washer_supplies_its_names():
    from washer.machine.layout import PAR_NAMES
    assert PAR_NAMES == WASHER_NAMES


# ------------------------------------------------------- through washer.run
def _ab(tmp_path):
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    return tmp_path / "c.ab"


def test_command_line_refuses_paths_and_corrupt_restarts(tmp_path, capsys):
    from washer.run import main
    c = _ab(tmp_path)
    assert main([str(c), "sv=../escape"]) == 2
    assert "is a name" in capsys.readouterr().err
    assert not (tmp_path.parent / "b.escape").exists()
    _corrupt(tmp_path, lambda L: L[:-2])                        # tmp_path / s.eq, truncated
    # The labels before the damaged record still restart, with a note naming it.
    assert main([str(c), "IRS=2", "s=eq", "sv=again", "NMX=3"]) == 0
    err = capsys.readouterr().err
    assert "s.eq:36:" in err and "truncated" in err and "records before it are used" in err
    # The damaged one is refused, and the message says why it is missing.
    assert main([str(c), "IRS=6", "s=eq", "sv=again"]) == 2
    err = capsys.readouterr().err
    assert "IRS=6" in err and "s.eq:36:" in err and "truncated" in err


def test_restart_from_a_record_without_a_positive_period(tmp_path):
    """PAR(11) of a periodic record is its period: NaN, 0 or negative cannot start a run."""
    from washer.auto.files import record_text
    from washer.cont.record import find_record
    src = DATA / "auto_reference" / "records" / "s.ab"
    recs = read_s(src)
    rec = next(r for r in recs if r.lab == 18)
    assert rec.ntst > 0 and rec.par[10] > 0
    for bad in (float("nan"), 0.0, -2.0):
        rec.par[10] = bad
        p = tmp_path / "s.bad"
        p.write_text("".join(record_text(r) for r in recs))
        with pytest.raises(LookupError, match=r"PAR\(11\) \(the period\) is") as err:
            find_record(read_s(p), 18)
        assert str(err.value).startswith(f"{p}:")
    assert find_record(read_s(src), 18).lab == 18          # the unedited record starts


@pytest.mark.parametrize("stmt,message", [
    ("STOP = [3]", "STOP entries are a point type and an optional count"),
    ("SP = ['LP0', 2]", "SP entries are a point type"),
    ("UZR = {1: 'a'}", r"UZR\[1\] expects a number, got 'a'"),
    ("UZR = {1: [0.1, 'b']}", r"UZR\[1\] expects a number, got 'b'"),
    ("PAR = {1: 'x'}", r"PAR\[1\] expects a number, got 'x'"),
    ("PAR = {2: 1e999}", r"PAR\[2\] expects a finite number"),
    ("THL = {1: 'w'}", r"THL\[1\] expects a number"),
    ("THL = {1: -1}", r"THL\[1\] = -1: weights of the arclength norm are >= 0"),
    ("THU = {2: -0.5}", r"THU\[2\] = -0.5: weights"),
    ("UZR = {1: []}", r"UZR\[1\] is an empty list"),
    ("parnames = {1: 2}", r"parnames\[1\] expects a name in quotes, got 2"),
    ("unames = {'a': 'x'}", r"unames keys are indices 1, 2, ..., got 'a'"),
])
def test_mistyped_lists_and_dicts_name_file_and_line(tmp_path, stmt, message):
    with pytest.raises(ConstantsError, match=message) as err:
        read_constants(_c(tmp_path, f"NDIM = 2\n\n{stmt}\n"))
    assert str(err.value).startswith(f"{tmp_path / 'c.x'}:3:")


def test_duplicate_icp_entries_are_refused(tmp_path):
    c = read_constants(_c(tmp_path, "NDIM = 2\nparnames = {1: 'a'}\nICP = [1, 'a']\n"))
    with pytest.raises(ConstantsError, match=r"names PAR\(1\) twice \(1 and 'a'\)") as err:
        c.icp()
    assert str(err.value).startswith(f"{tmp_path / 'c.x'}:3:")


@pytest.mark.parametrize("stmt,message", [
    ("THL = {-1: 1.0}", r"THL weight on index -1: expected an index in 1..NPAR=11"),
    ("THU = {0: 1.0}", r"THU weight on index 0: expected an index in 1..8 NDIM=16"),
    ("IPS = 2\nNTST = 0", r"NTST = 0: IPS = 2 solves on a mesh of NTST intervals"),
])
def test_weights_on_indices_that_do_not_exist(tmp_path, stmt, message):
    from washer.run import RunError, run
    from washer.cont.settings import SettingsError
    c = _ab(tmp_path)
    c.write_text(c.read_text() + stmt + "\n")
    lines = c.read_text().splitlines()
    with pytest.raises((SettingsError, RunError), match=message) as err:
        run(c, verbose=False)
    assert str(err.value).startswith(f"{c}:{len(lines)}:")


def test_run_failing_before_its_first_point_leaves_a_readable_b_file(tmp_path):
    """Equations that are NaN at the start point: no point, so no header-only b-file."""
    (tmp_path / "nanf.py").write_text(
        "import numpy as np\n"
        "def func(u, par):\n    return np.full(2, np.nan)\n"
        "def stpnt(u, par):\n    u[:] = 0.0\n    par[:2] = [0.0, 1.0]\n")
    c = _c(tmp_path, "e = 'nanf'\nNDIM = 2\nICP = [1]\nNMX = 5\n")
    from washer.run import main
    assert main([str(c)]) != 0                          # the run did fail
    b = tmp_path / "b.x"
    if b.exists():
        assert check_parseB_rules(b.read_text()) == 0    # empty: nothing parseB chokes on


def test_icp_by_washer_name_without_parnames(tmp_path):
    """e='washer' knows its parameter names: ICP=['m_u'] with no parnames in the file."""
    from washer.run import run
    c = _c(tmp_path, "e = 'washer'\nNDIM = 12\nICP = ['m_u']\nJAC = 1\nNMX = 3\nNPAR = 16\n"
                     "DS = 0.01\nDSMAX = 0.05\n", name="c.names")
    res = run(c, verbose=False)
    rows = [r for b in read_b(tmp_path / "b.names") for r in b]
    assert len(rows) == 3
    par3 = [r.values[0] for r in rows]
    assert len(set(par3)) == 3                            # PAR(3) = m_u moves along the branch
    header = [l for l in (tmp_path / "b.names").read_text().splitlines() if l.startswith("   0")]
    assert header[-3].endswith(" 'm_u'") and "Active continuation parameter" in header[-3]
    assert header[-1].split()[4] == "m_u"                # the first column's title


@pytest.mark.parametrize("stmt,message", [
    ("THL = {12: 1.0}", r"THL weight on index 12 has no effect: not an index of this run "
                        r"\(1..NPAR=11\)"),
    ("THU = {17: 1.0}", r"THU weight on index 17 has no effect: not an index of this run "
                        r"\(1..8 NDIM=16\)"),
])
def test_weights_beyond_the_run_are_said_and_dropped(tmp_path, stmt, message):
    """AUTO ignores them (its r3b demo has THL on PAR(23) with NPAR 22): a warning, not
    silence, and the run goes on."""
    from washer.cont.settings import SettingsWarning
    from washer.run import run
    c = _ab(tmp_path)
    c.write_text(c.read_text() + stmt + "\nNMX = 5\n")
    with pytest.warns(SettingsWarning, match=message) as rec:
        res = run(c, verbose=False)
    assert str(rec[0].message).startswith(f"{c}:{len(c.read_text().splitlines()) - 1}:")
    assert len(res.rows) == 5


def test_huge_mesh_is_refused_with_its_estimate(tmp_path, capsys):
    """NTST = 100000 on the forced washer (NDIM 14) would need ~14 GB: refused at once."""
    import time
    from washer.run import main
    shutil.copy(Path(__file__).resolve().parents[1] / "auto_constants" / "c.washer.forced",
                tmp_path)
    t0 = time.monotonic()
    assert main([str(tmp_path / "c.washer.forced"), "NTST=100000"]) == 2
    assert time.monotonic() - t0 < 10
    err = capsys.readouterr().err
    assert "NTST = 100000, NCOL = 4, NDIM = 14: needs about 14.1 GB of memory" in err
    assert "--allow-large" in err and not (tmp_path / "b.washer.forced").exists()


def test_forced_par_values_are_named_by_the_constants_file(tmp_path):
    from washer.run import RunError, run
    c = tmp_path / "c.washer.forced"
    text = (Path(__file__).resolve().parents[1] / "auto_constants" / "c.washer.forced").read_text()
    c.write_text(text + "PAR = {'m_u': -1.0}\n")
    with pytest.raises(RunError, match=r"PAR: m_u = -1.0: expected a value >= 0") as err:
        run(c, verbose=False)
    assert str(err.value).startswith(f"{c}:{len(c.read_text().splitlines())}:")
    assert "reference.toml" not in str(err.value)


def test_forced_washer_refuses_omega_not_positive():
    """Continuing the forced response in Omega stops at Omega = 0 with a reason instead
    of continuing into a drum turning backwards."""
    from washer.cont.problem import ProblemError
    from washer.problems.oscillator import forced_problem
    from washer.problems.washer import PAR_NAMES
    P = forced_problem()
    par = np.zeros(17)
    par[[i - 1 for i, n in PAR_NAMES.items() if n == "Omega"][0]] = -1.0
    u = np.r_[np.zeros(12), 0.0, 1.0]
    with pytest.raises((ValueError, ProblemError),
                       match=r"Omega = -1 Hz: the forced response is defined for Omega > 0"):
        P.func(u, par)


@pytest.mark.parametrize("par,message", [
    ("{'m_t': 0.0}", r"PAR: m_t = 0.0: expected a value > 0"),
    ("{'Omega': -1.0}", r"PAR: Omega = -1.0: expected a value >= 0"),
])
def test_washer_par_values_are_checked_as_a_parameter_set(tmp_path, par, message):
    from washer.run import RunError, run
    c = tmp_path / "c.w"
    c.write_text(f"e = 'washer'\nNDIM = 12\nICP = ['C_p']\nNMX = 3\nPAR = {par}\n")
    with pytest.raises(RunError, match=message) as err:
        run(c, verbose=False)
    assert str(err.value).startswith(f"{c}:5:")


def test_washer_icp_outside_its_parameters_warns(tmp_path):
    from washer.run import run
    c = tmp_path / "c.w"
    c.write_text("e = 'washer'\nNDIM = 12\nICP = [30]\nNMX = 3\nJAC = 1\n")
    with pytest.warns(UserWarning, match=r"c.w:3: ICP: PAR\(30\) is not a parameter of "
                                         r"e='washer'"):
        run(c, verbose=False)


# ------------------------------------------------ restarts and ICP of the loci
def test_icp_errors_name_the_icp_line(tmp_path):
    c = read_constants(_c(tmp_path, "NDIM = 3\nIPS = 15\n\nICP = ['foo']\n"))
    with pytest.raises(ConstantsError, match="unknown parameter 'foo'") as err:
        c.icp()
    assert str(err.value).startswith(f"{tmp_path / 'c.x'}:4:")
    c = read_constants(_c(tmp_path, "NDIM = 3\nIPS = 15\nICP = [3, 11, 12, 22, -22, -22, -31]\n"))
    with pytest.raises(ConstantsError, match=r"names the optimality condition -22 twice") as err:
        c.icp()
    assert str(err.value).startswith(f"{tmp_path / 'c.x'}:3:")


def test_isw2_at_a_regular_label_names_the_labels_it_takes(tmp_path):
    from washer.run import RunError, run
    c = _ab(tmp_path)
    run(c, verbose=False, sv="eq")
    with pytest.raises(RunError, match=r"ISW=2 .* restart at an LP, HB, BP, PD or TR label, "
                                       r"got EP \(IRS='EP1'\)") as err:
        run(c, verbose=False, s="eq", sv="loc", IRS="EP1", ISW=2, ICP=[1, 2])
    assert str(err.value).startswith(f"{c}:")


def test_missing_system_lists_what_exists_for_that_ips():
    """IPS = 5 has no ISW = 2 system: the refusal says what IPS = 5 does, not the
    whole registry."""
    from washer.cont.systems import find
    with pytest.raises(KeyError) as err:
        find(5, 2, "LP")
    msg = err.value.args[0]
    assert "IPS=5, ISW=2 starting at 'LP'" in msg and "with IPS=5: ISW=1 from any point" in msg
    assert "IPS=2" not in msg


def test_every_failing_user_function_names_its_line():
    """A user's function that raises is named with the place it raised, whichever it is
    (func, the objective FOPT, the flow of shooting): the deepest frame outside washer."""
    import re
    from washer.cont.problem import Problem, ProblemError

    def fails(*args):
        raise ValueError("not here")
    line = fails.__code__.co_firstlineno + 1
    p = Problem(1, fails, fopt=fails, flow=fails, name="bad")
    calls = {"func(u, par)": lambda: p.func(np.zeros(1), np.zeros(1)),
             "fopt(u, par)": lambda: p.fopt_many(np.zeros((1, 1)), np.zeros(1)),
             "flow(u0, par, 1)": lambda: p.period_map(np.zeros(1), np.zeros(1), 1)}
    for what, call in calls.items():
        with pytest.raises(ProblemError) as info:
            call()
        assert re.fullmatch(rf"bad: {re.escape(what)} failed: ValueError: not here "
                            rf"\(.*test_bad_input\.py:{line}\)", str(info.value)), str(info.value)


def test_a_failing_stpnt_of_a_profile_names_its_time_and_the_users_line(tmp_path):
    """stpnt(u, par, t) raising at one time of a BVP's start profile, or while a restart
    is extended to a larger NDIM: a ProblemError naming the time, what was being done and
    the user's file and line."""
    from washer.cont.problem import Problem, ProblemError
    from washer.cont.user_problem.user_files import load_python_problem
    (tmp_path / "bad.py").write_text(
        "def func(u, par):\n    return -u\n\n\n"
        "def stpnt(u, par, t):\n    if t > 0.5:\n        raise ValueError('no start here')\n"
        "    u[:] = t\n")
    prob = load_python_problem("bad", tmp_path, 2)
    assert isinstance(prob, Problem)
    with pytest.raises(ProblemError, match=r"failed at t = 0\.75: ValueError: no start here "
                                           r"\(.*bad\.py:7\)"):
        prob.start_profile(np.zeros(3), [0.0, 0.25, 0.75])
    with pytest.raises(ProblemError, match=r"failed extending the restart to NDIM = 2 at "
                                           r"t = 1\.0: ValueError"):
        prob.extend_profile(np.zeros((2, 1)), np.zeros(3), [0.0, 1.0])


def test_uzr_on_a_parameter_past_npar_widens_the_parameters(tmp_path):
    """AUTO tests UZR/UZSTOP on any parameter of its PAR array, longer than NPAR (HomCont's
    fhh demo stops on PAR(33) with NPAR = 14): the run goes on with the parameters widened
    to that index (a value never reached labels nothing), an index below 1 is refused."""
    from washer.run import RunError, run
    c = _ab(tmp_path)
    base = c.read_text()
    c.write_text(base + "UZSTOP = {20: 1.0}\nNMX = 5\n")
    br = run(c, verbose=False)
    assert br.status == "ok" and len(br.rows) == 5
    assert all(len(r.par) >= 20 and r.par[19] == 0.0 for r in br.rows)
    c.write_text(base + "UZR = {-0: 1.0}\n")
    with pytest.raises(RunError, match=r"UZR/UZSTOP on PAR\(0\)"):
        run(c, verbose=False)


def test_quoted_indices_are_parameter_indices(tmp_path):
    """ICP = ['3','1'] with no parnames (a user's constants file, run by AUTO-07p 0.9.2
    as PAR(3), PAR(1): its b-file's first column PAR(3)): a string no parnames entry
    holds that spells an index is that index; a parnames entry of that spelling wins."""
    c = read_constants(_c(tmp_path, b"NDIM = 5, IPS = 1\nICP =  ['3','1']\n"
                                    b"UZSTOP = {'3': 10.0}\n"))
    assert c.icp() == [3, 1]
    assert c.par_values("UZSTOP") == [(3, 10.0)]
    assert c.par_index("3") == 3 and c.par_index("-3") == -3
    named = Constants({"parnames": {5: "3"}})
    assert named.par_index("3") == 5
    with pytest.raises(ConstantsError, match="unknown parameter '3a'"):
        named.par_index("3a")
