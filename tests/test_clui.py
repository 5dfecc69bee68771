"""AUTO's command language: the script dialect, the runner's constants, the diagram and
solution objects (label selection, relabel, merge, save), checked against AUTO-07p's own
files and, where it is installed, AUTO-07p's own parsers reading what washer saves."""
import os
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

from auto07p_parsers import auto_python
from b_rows import header_blocks
from washer.auto import clui
from washer.auto.diagram import Diagram, SolutionList
from washer.auto.script import ScriptError, run_script, translate

DEMOS = Path(__file__).parent / "data" / "auto_demos"
AUTO_PYTHON = auto_python()


def test_python2_print_statements_become_calls():
    src = ('print "\\n***Start***"\n'
           'print pgm, ": first run"\n'
           'print "%s : run"%pgm\n'
           'print x,\n'
           'print\n'
           'for i in [1]:\n'
           '    print "y"  # comment\n'
           'print("already a call")\n'
           'printer = 1\n')
    out = translate(src)
    assert out.splitlines() == ['print( "\\n***Start***")', 'print( pgm, ": first run")',
                                'print( "%s : run"%pgm)', 'print( x, end=" ")', 'print()',
                                'for i in [1]:', '    print( "y")  # comment',
                                'print("already a call")', 'printer = 1']
    compile(out, "x", "exec")          # valid Python 3


def test_autos_shorthand_lines_become_calls(tmp_path, monkeypatch):
    # AUTO's processShorthand (its tutorial script: "cd /tmp", "! rm -rf test",
    # ld(verbose="no")); a name followed by an assignment or a call stays Python.
    assert translate("! rm -rf test\n") == "shell('rm -rf test')\n"
    assert translate("  shell echo a\n") == "  shell('echo a')\n"
    assert translate("cd ..\nls\ncat c.ab\n") == "cd('..')\nls()\ncat('c.ab')\n"
    assert translate("mkdir d\ncp a b\n") == "shell('mkdir d')\nshell('cp a b')\n"
    for python in ("cd = 3\n", "ls(dir)\n", "cp('a', 'b')\n", "rm += 1\n"):
        assert translate(python) == python
    monkeypatch.chdir(tmp_path)
    Path("s.auto").write_text('ld(verbose="no")\nmkdir sub\ncd sub\n! touch here\ncd ..\n')
    run_script("s.auto")
    assert Path("sub/here").exists()


def test_delete_and_keep_labels_as_autos_dsp_ksp_dlb_klb(tmp_path, monkeypatch):
    # AUTO's int demo b/s files: EP UZ UZ LP UZ UZ EP. dsp/ksp drop the type with the
    # label, dlb/klb keep it on the row (AUTO's deleteLabel; outputs checked against
    # AUTO-07p's on the ab equations: the same BR, PT, TY, LAB columns).
    monkeypatch.chdir(tmp_path)
    bd = _diagram("int", "int")
    assert [x["TY"] for x in bd()] == ["EP", "UZ", "UZ", "LP", "UZ", "UZ", "EP"]
    clui.save(bd, "x")

    def rows(name):
        return [(r.ty, r.lab) for b in Diagram.read(f"b.{name}") for r in b.rows if r.ty]

    def types(name):
        return [x["TY"] for x in Diagram.read(f"b.{name}", f"s.{name}")()]
    clui.dsp("UZ", "x", "y")
    assert types("y") == ["EP", "LP", "EP"] and len(clui.sl("y")) == 3
    assert all(lab for ty, lab in rows("y"))                 # no UZ type left on a row
    clui.ksp(["LP"], "x", "z")
    assert types("z") == ["LP"]
    clui.dlb(None, "x", "w")                                 # BP LP HB PD TR EP MX
    assert types("w") == ["UZ"] * 4 and (5, 0) in rows("w") and (9, 0) in rows("w")
    clui.klb(2, "x", "v")
    assert [x["LAB"] for x in clui.sl("v")] == [2]
    assert [x["TY"] for x in clui.dsp(bd, "UZ")()] == ["EP", "LP", "EP"]
    assert clui.COMMANDS["bt"]("x").getLabels() == bd.getLabels()     # b. and s.x
    assert [x["TY"] for x in clui.ksp(bd(), ["EP"])] == ["EP", "EP"]


def test_file_commands_on_a_misspelt_name_are_errors(tmp_path, monkeypatch):
    """dsp/ksp/dlb/klb, relabel, merge and bd on b./s.NAME that do not exist name the
    files, and write nothing (before, the label commands wrote empty b. and s. files)."""
    monkeypatch.chdir(tmp_path)
    for call in (lambda: clui.klb(2, "nosuch"), lambda: clui.dsp("UZ", "nosuch", "out"),
                 lambda: clui.relabel("nosuch"), lambda: clui.merge("nosuch"),
                 lambda: clui.loadbd("nosuch")):
        with pytest.raises(clui.AutoError, match="no output files b.nosuch, s.nosuch"):
            call()
    assert list(tmp_path.iterdir()) == []


def test_diagnostic_queries_print_the_d_file_lines(tmp_path, monkeypatch, capsys):
    # AUTO's ev/fl/hb/lp/bp/it/nt/sp/ss print the d-file lines with their word; plot3
    # (AUTO's 3D viewer) notes that it draws nothing, and the script goes on.
    monkeypatch.chdir(tmp_path)
    Path("d.x").write_text("   1     2         Eigenvalue  1:  -1.0E+00\n"
                           "   1     2 NOTE:Retrying step\n")
    Path("q.auto").write_text("ev('x')\nnt('x')\np3('x')\nhb = 3\n")
    ns = run_script("q.auto")
    out = capsys.readouterr().out
    assert "Eigenvalue  1" in out and "NOTE:Retrying" in out and "3D viewer" in out
    assert out.count("Eigenvalue") == 1 and ns["hb"] == 3       # a name is still a name


def test_unknown_command_names_it_and_the_line(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("x.auto").write_text('print "start"\n\nfrobnicate("ab")\n')
    with pytest.raises(ScriptError) as err:
        run_script("x.auto")
    msg = str(err.value)
    assert "x.auto:3" in msg and "'frobnicate'" in msg and 'frobnicate("ab")' in msg


def test_a_failing_command_names_the_line(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("y.auto").write_text("r = 1\nrun(e='nosuch', c='nosuch')\n")
    with pytest.raises(ScriptError) as err:
        run_script("y.auto")
    assert "y.auto:2" in str(err.value) and "c.nosuch" in str(err.value)


def test_a_bad_value_of_a_constants_file_names_its_line_and_a_keywords_the_command(
        tmp_path, monkeypatch):
    # ICP names are resolved only when the run is built (against parnames): the error
    # must still point at the constants file's line, or at the command that set it.
    monkeypatch.chdir(tmp_path)
    shutil.copy(DEMOS / "ab" / "ab.f90", tmp_path)
    lines = (DEMOS / "ab" / "c.ab.1").read_text().splitlines()
    row = next(i for i, ln in enumerate(lines) if ln.startswith("ICP"))
    lines[row] = "ICP = ['nosuch']"
    Path("c.ab").write_text("\n".join(lines) + "\n")
    Path("x.auto").write_text("r = run('ab')\n")
    with pytest.raises(ScriptError) as err:
        run_script("x.auto")
    assert f"c.ab:{row + 1}" in str(err.value) and "'nosuch'" in str(err.value)
    lines[row] = "ICP = [1]"
    Path("c.ab").write_text("\n".join(lines) + "\n")
    Path("y.auto").write_text("r = run('ab', ICP=['nosuch'])\n")
    with pytest.raises(ScriptError) as err:
        run_script("y.auto")
    msg = str(err.value)
    assert "y.auto:1" in msg and "ICP" in msg and f"c.ab:{row + 1}" not in msg


def test_a_run_not_done_says_why_in_its_d_file_and_the_script_goes_on(tmp_path, monkeypatch):
    # A run of a kind the engine does not do (its build refuses it as "not supported";
    # every such kind of AUTO's is done now, so the refusal is put in the build's place)
    # is reported on the screen and in the d-file its output would have had; later
    # commands still run.
    import washer.cont.runner as runner_module
    real_build = runner_module.build

    def build(c, *args, **kw):
        if c["IPS"] == 9 and c["ISTART"] == -1:
            raise runner_module.RunError("IPS = 9 with ISTART = -1: not supported yet")
        return real_build(c, *args, **kw)
    monkeypatch.setattr(runner_module, "build", build)
    monkeypatch.chdir(tmp_path)
    for f in ("ab.f90", "c.ab.1"):
        shutil.copy(DEMOS / "ab" / f, tmp_path)
    Path("z.auto").write_text("r = run(e='ab', c='ab.1', NMX=5)\n"
                              "r = run(e='ab', c='ab.1', IPS=9, ISTART=-1, sv='hom')\n"
                              "r = run(e='ab', c='ab.1', IPS=9, ISTART=-1)\n"
                              "save(r, 'kept')\n"
                              "print 'after'\n")
    clui._runner.refused.clear()
    run_script("z.auto")
    for d in ("d.hom", "fort.9"):
        assert "run not done" in Path(d).read_text() and "ISTART = -1" in Path(d).read_text()
    assert not Path("b.hom").exists() and len(clui._runner.refused) == 2
    # fort.7/fort.8 are the refused run's (none), not the first run's beside its fort.9;
    # saving the refused run's result writes no file
    assert not Path("fort.7").exists() and not Path("fort.8").exists()
    assert not list(tmp_path.glob("*.kept")) and not list(tmp_path.glob("*kept*"))


def test_cn_reads_a_constants_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    shutil.copy(DEMOS / "ab" / "c.ab.1", tmp_path)
    c = clui.cn("ab.1")
    assert c["NDIM"] == 2 and c["ICP"] == [2] and c["DS"] is not None


def test_homcont_constants_commands_change_the_runners_constants():
    clui.COMMANDS["hch"]("IEQUIB", -1)
    assert clui.COMMANDS["hpr"]("IEQUIB") == -1


def test_constants_follow_autos_none_means_default():
    c = clui.AutoConstants(DS=0.02, NMX=40, e="ab", parnames={1: "a"})
    c["DS"] = "-"
    assert c["DS"] == -0.02
    c.update(clui.AutoConstants(NMX=5))   # a new constants file: unset keys back to default
    assert c["NMX"] == 5 and c["DS"] is None
    assert c["e"] == "ab" and c["parnames"] == {1: "a"}      # AUTO's special keys survive
    with pytest.raises(clui.AutoError, match="Unknown option: NMAX"):
        c.update(NMAX=3)
    w = c.washer("test")
    assert w["NMX"] == 5 and w["DS"] == 0.01                 # None -> AUTO's default


def _diagram(demo, name):
    ref = DEMOS / demo / "autoref"
    return Diagram.read(ref / f"b.{name}", ref / f"s.{name}")


def test_label_selection_on_autos_own_files():
    bd = _diagram("frc", "frc")
    labels = bd.getLabels()
    assert labels == [r.lab for b in bd for r in b.rows if r.lab]
    sols = bd()
    assert isinstance(sols, SolutionList) and len(sols) == len(labels)
    first = sols[0]
    assert bd(first["LAB"])["LAB"] == first["LAB"]
    by_type = {}
    for s in sols:
        by_type.setdefault(s["TY"], []).append(s["LAB"])
    for ty, labs in by_type.items():
        assert [s["LAB"] for s in bd(ty)] == labs
        assert bd(f"{ty}{len(labs)}")["LAB"] == labs[-1]
    # solutions taken from a diagram carry its largest label and branch (restart numbering)
    assert {s._mlab for s in sols} == {max(labels)}
    # a column by name, the PAR vector by index and name
    col = bd["PAR(5)"] if "PAR(5)" in bd[0].titles else bd[bd[0].titles[0]]
    assert len(col) == len(bd[0])
    assert first.PAR(5) == first["PAR(5)"] == first.PAR["PAR(5)"]
    with pytest.raises(KeyError):
        bd("HB99")


def test_a_solutions_points_and_writefilename_as_autos(tmp_path):
    """AUTO's AUTOSolution: s[i] (and s['data'][i]) is the i-th point of the mesh, with
    ['t'] and ['u'] (an equilibrium has one point: AUTO's n-body script reads
    x["data"][0]["u"][1], U(2), to sort the Lagrange points), and writeFilename writes
    the s-record: the nbody demo's s.l4, written so by AUTO, is read and written back
    byte for byte."""
    import gzip
    from washer.auto.diagram import read_solutions
    src = DEMOS / "nbody" / "autoref" / "s.l4"                # stored as s.l4.gz
    (x,) = read_solutions(src)
    autos = gzip.decompress(src.with_name("s.l4.gz").read_bytes())
    assert x["data"][0]["t"] == 0.0
    assert x["data"][0]["u"][1] == x[0][1] == x["U(2)"] == 8.6602540378e-01
    with pytest.raises(IndexError):
        x[1]                                    # an equilibrium has one point
    x.writeFilename(tmp_path / "s.l4")
    assert (tmp_path / "s.l4").read_bytes() == autos
    x.writeFilename(tmp_path / "s.l4", append=True)
    assert (tmp_path / "s.l4").read_bytes() == 2 * autos
    orbit = [s for s in read_solutions(DEMOS / "chu" / "autoref" / "s.chu")
             if s["TY"] == "PD"][0]
    assert orbit[3]["t"] == orbit.t[3] and list(orbit[3]["u"]) == list(orbit.U[3])
    assert orbit["data"][3][2] == orbit.U[3][2]


def test_splabs_reads_a_solution_file_by_name(tmp_path, monkeypatch):
    # AUTO's splabs('mu', 'LP') reads s.mu (the cusp demo passes a name)
    monkeypatch.chdir(tmp_path)
    bd = _diagram("frc", "frc")
    clui.save(bd, "x")
    for ty in {s["TY"] for s in bd()}:
        labs = [s["LAB"] for s in bd() if s["TY"] == ty]
        assert clui.splabs("x", ty) == clui.splabs(bd, ty) == labs


def test_relabel_and_save_roundtrip(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    bd = _diagram("frc", "0") + _diagram("frc", "frc")
    rl = clui.relabel(bd)
    n = len(bd.getLabels())
    assert rl.getLabels() == list(range(1, n + 1))
    assert [s["LAB"] for s in rl()] == list(range(1, n + 1))
    clui.save(rl, "both")
    back = Diagram.read("b.both", "s.both")
    assert back.getLabels() == rl.getLabels()
    for a, b in zip(back(), rl()):
        assert a["LAB"] == b["LAB"] and a["TY"] == b["TY"]
        np.testing.assert_array_equal(a.PAR, b.PAR)
        np.testing.assert_array_equal(a.U, b.U)
    rows = [r.values for br in back for r in br.rows]
    assert rows == [r.values for br in bd for r in br.rows]


def test_merge_joins_a_branch_computed_both_ways(tmp_path, monkeypatch):
    """Two runs from the same start in opposite directions become one branch: the second
    reversed, then the first without the common start; labels renumbered in order."""
    from washer.auto.diagram import Branch
    from washer.auto.files import Row
    fw = Branch(["   0 header"], ["PAR(1)", "L2-NORM"], [Row(1, 1, 9, 1, [0.0, 1.0]),
                Row(1, 2, 0, 0, [0.1, 1.1]), Row(1, 3, 9, 2, [0.2, 1.2])], {"DS": 0.1})
    bw = Branch(["   0 header"], ["PAR(1)", "L2-NORM"], [Row(1, 1, 9, 3, [0.0, 1.0]),
                Row(1, -2, 2, 4, [-0.1, 0.9]), Row(1, -3, 9, 5, [-0.2, 0.8])], {"DS": -0.1})
    m = clui.merge(Diagram([fw, bw]))
    assert len(m) == 1
    assert [r.values[0] for r in m[0].rows] == [-0.2, -0.1, 0.0, 0.1, 0.2]
    assert [r.pt for r in m[0].rows] == [-1, -2, 3, 4, 5]
    assert [r.lab for r in m[0].rows] == [1, 2, 3, 0, 4]
    # two runs in the same direction: not merged
    again = fw.copy()
    again.c = {"DS": 0.1}
    assert len(clui.merge(Diagram([fw, again]))) == 2


@pytest.mark.skipif(AUTO_PYTHON is None, reason="AUTO-07p's Python tools not installed")
def test_autos_parsers_read_what_the_clui_saves(tmp_path):
    """A demo run and saved by washer's CLUI (frc: run, save(r, name), clean) is read by
    AUTO-07p's own parseB/parseS with the same labels and types."""
    import subprocess
    work = tmp_path / "frc"
    shutil.copytree(DEMOS / "frc", work, ignore=shutil.ignore_patterns("autoref"))
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]),
               OMP_NUM_THREADS="1")
    subprocess.run([sys.executable, "-m", "washer.auto", "frc.auto"], cwd=work, env=env,
                   check=True, capture_output=True)
    code = ("import sys; sys.path.insert(0, %r)\n"
            "from auto import parseB, parseS\n"
            "b = parseB.parseB('b.frc'); s = parseS.parseS('s.frc')\n"
            "print([(p['TY name'], p['LAB']) for p in [b.getLabel(l) for l in b.getLabels()]])\n"
            "print([(x['Type name'], x['Label']) for x in s])\n" % str(AUTO_PYTHON))
    out = subprocess.run([sys.executable, "-c", code], cwd=work, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-2000:]
    b_labels, s_labels = out.stdout.strip().splitlines()
    ours = Diagram.read(work / "b.frc", work / "s.frc")
    expect = [(s["TY"], s["LAB"]) for s in ours()]
    assert eval(b_labels) == expect and eval(s_labels) == expect


# she (3.3 s) runs with -m slow
@pytest.mark.parametrize("demo, names", [("lor", ["b.lor"]), ("ffn", ["b.1", "b.2", "b.3"]),
                                         pytest.param("she", ["b.1", "b.2"], marks=pytest.mark.slow)])
def test_cluis_headers_are_autos(tmp_path, monkeypatch, demo, names):
    """Every header block of the demo's b-files is AUTO's byte for byte (autoref). lor: a
    start from lor.dat, then restarts from its labels (sv='lor'): the data start as
    AUTO's CLUI runs it, IRS = 0 with e = 'lor' s = '/' dat = 'lor' (its marker of
    constants and data read from one stream), the restarts with IRS = the label and
    e = 'lor' only. ffn: restarts with LAB=1 from r1('UZ1') (label 2), which AUTO's
    CLUI relabels 1 (a data keyword of its solutions): IRS = 1; and the IPLT column
    'L2-NORM x' by unames. she (IPS = 9, IEQUIB = -2, then -1): HomCont's line with the
    NUNSTAB, NSTAB the run counted and ISTART = 5 resolved to 1, the user's -1, -1, 5
    below."""
    work = tmp_path / demo
    shutil.copytree(DEMOS / demo, work, ignore=shutil.ignore_patterns("autoref"))
    monkeypatch.chdir(work)
    # a script starts with nothing remembered, as AUTO's in its own process (ffn's
    # parnames would otherwise name she's columns)
    monkeypatch.setattr(clui, "_runner", clui.Runner())
    run_script(f"{demo}.auto")
    for name in names:
        ours = header_blocks(work / name)
        ref = header_blocks(DEMOS / demo / "autoref" / name)
        assert ours and ours == ref, name


#: IPLT of lrz's equilibria (NDIM 3, unames x, y, z) and the U(k) its column shows
#: (ae.f90 STPLAE: U(|IPLT|), U(IPLT - NDIM), U(IPLT - 2 NDIM); 12: beyond 3 NDIM, the
#: L2 norm).
IPLT_COLUMN = {2: 2, -1: 1, 5: 2, 8: 2, 12: None}


def test_iplt_column_of_an_algebraic_problem(tmp_path, monkeypatch):
    """lrz's equilibria with IPLT = 2, -1, 5, 8, 12: the b-file's second column is
    U(k) as AUTO's STPLAE takes it (the L2 norm beyond 3 NDIM), on every row, and its
    title HEADNG's ('y' at column 2, 'INTEGRAL y', 'L2-NORM y', 'L2-NORM'); where
    AUTO-07p is installed, every header block is AUTO's own of the same runs byte for byte."""
    work = tmp_path / "w"
    work.mkdir()
    for f in ("lrz.f90", "c.lrz"):
        shutil.copy(DEMOS / "lrz" / f, work)
    script = "".join(f"run(e='lrz', c='lrz', IPLT={i}, NMX=8, sv='p{abs(i)}')\n"
                     for i in IPLT_COLUMN)
    (work / "t.auto").write_text(script)
    monkeypatch.chdir(work)
    run_script("t.auto")
    for iplt, k in IPLT_COLUMN.items():
        rows = [ln.split() for ln in (work / f"b.p{abs(iplt)}").read_text().splitlines()
                if not ln.startswith("   0")]
        assert len(rows) > 8 and any(float(r[5]) != 0 for r in rows)
        for r in rows:
            if k is None:
                norm = float(np.sqrt(sum(float(v) ** 2 for v in r[6:9])))
                assert float(r[5]) == pytest.approx(norm, rel=1e-9)
            else:
                assert r[5] == r[5 + k]                     # the same printed value
    if shutil.which("auto-07p") is None or shutil.which("gfortran") is None:
        return
    import subprocess
    ref = tmp_path / "auto"
    shutil.copytree(work, ref, ignore=shutil.ignore_patterns("b.*", "s.*", "d.*", "fort.*"))
    subprocess.run(["auto-07p", "t.auto"], cwd=ref, capture_output=True, timeout=600,
                   check=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    for iplt in IPLT_COLUMN:
        name = f"b.p{abs(iplt)}"
        assert header_blocks(work / name) == header_blocks(ref / name), name


def test_the_washers_equations_by_name_start_where_washer_run_starts(tmp_path, monkeypatch):
    """run(e='washer', c='washer') in the command language builds the washer's problem
    from the run's constants, as `washer.run` does: its first point is the equilibrium at
    the file's PAR (C_p = 0, not the reference set's C_p = 0.101) and its labelled points
    are washer.run's. The s-file holds 11 significant digits (AUTO's E19.10 format), so
    the values read back agree with the run in memory to 1e-9 relative (1e-12 absolute for
    C_p = 0 itself, where the start is exact to rounding)."""
    from washer.run import run
    shutil.copy(Path(__file__).parent.parent / "auto_constants" / "c.washer", tmp_path)
    monkeypatch.chdir(tmp_path)
    ours = clui.COMMANDS["run"](e="washer", c="washer", NMX=3, sv="w")()
    ref = run(tmp_path / "c.washer", verbose=False, files=False, NMX=3).specials
    assert [s["TY"] for s in ours] == [r.ty for r in ref] == ["EP", "EP"]
    assert abs(ours[0]["PAR"][0]) < 1e-12
    for s, r in zip(ours, ref):
        np.testing.assert_allclose(s["PAR"][0], r.par[0], rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(np.asarray(s["U"])[:12], r.U[:12], rtol=1e-9, atol=1e-12)


def test_the_command_language_loads_none_of_the_washers_problems_until_a_run_names_them():
    """The AUTO file layer and the run command stay below the washer's problems: importing
    the command language or washer.run loads neither washer.problems nor the washer's
    model (a family named by e is imported through washer.named_problems when a run asks
    for it)."""
    import subprocess
    code = ("import sys, washer.auto.clui, washer.named_problems, washer.run\n"
            "print(sorted(m for m in sys.modules if m.startswith(('washer.problems', "
            "'washer.machine'))))\n"
            "washer.named_problems.named_problem('washer')\n"
            "print('washer.problems.resolve' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=dict(os.environ, OMP_NUM_THREADS="1"), check=True)
    assert out.stdout.split("\n")[:2] == ["[]", "True"], out.stdout + out.stderr


def test_a_data_start_is_the_engines_as_for_washer_run(tmp_path, monkeypatch):
    """run(e='pen', c='pen.1') with dat = 'pen' (pen.dat: t, U rows): the command language
    hands the data to the engine's start as `washer.run` does (AUTO's STPNUB: PAR(11) the
    data's time span, then STPNT, then the constants), so both write the same b-file, and
    its first rows are AUTO's (autoref b.pen: PERIOD 1.5738797188 at PT 1, where a start
    built apart from the engine's had PERIOD 1.0). AUTO's rows are compared to 1e-6
    relative: the corrector's EPSL = EPSU = 1e-7 on both sides, a few steps on."""
    import gzip

    from washer.auto.files import read_b
    from washer.run import run
    for sub in ("clui", "run"):
        d = tmp_path / sub
        d.mkdir()
        for f in ("pen.f90", "pen.dat", "c.pen.1"):
            shutil.copy(DEMOS / "pen" / f, d)
    monkeypatch.chdir(tmp_path / "clui")
    monkeypatch.setenv("WASHER_CACHE", str(tmp_path / "cache"))
    clui.COMMANDS["run"](e="pen", c="pen.1", NMX=4, sv="pen")
    run(tmp_path / "run" / "c.pen.1", verbose=False, e="pen", NMX=4, sv="pen")
    ours = [r for b in read_b(tmp_path / "clui" / "b.pen") for r in b]
    assert [r.values for r in ours] == \
        [r.values for b in read_b(tmp_path / "run" / "b.pen") for r in b]
    (tmp_path / "b.auto").write_bytes(gzip.open(DEMOS / "pen" / "autoref" / "b.pen.gz").read())
    auto = [r for b in read_b(tmp_path / "b.auto") for r in b][:len(ours)]
    assert len(ours) == 4 and [r.pt for r in ours] == [r.pt for r in auto]
    for o, a in zip(ours, auto):
        np.testing.assert_allclose(o.values, a.values, rtol=1e-6)


def test_numpy_values_in_a_script_are_the_numbers_they_hold(tmp_path, monkeypatch):
    """AUTO's scripts are Python: UZR={1: linspace(...)} (an array) and NMX=np.int64(..)
    are values AUTO takes. On the line u = p from p = 0 the UZ labels fall on the array's
    values (the line is exact: to Newton's tolerance EPSL = 1e-7 relative)."""
    monkeypatch.chdir(tmp_path)
    clui._runner.refused.clear()
    Path("line.py").write_text(
        "import numpy as np\n"
        "def func(u, par):\n    return np.array([u[0] - par[0]])\n"
        "def stpnt(u, par):\n    u[0] = 0.0\n    par[0] = 0.0\n")
    Path("c.line").write_text("NDIM = 1, IPS = 1, IRS = 0, ILP = 0\nICP = [1]\n"
                              "DS = 0.01, DSMIN = 0.001, DSMAX = 0.05\n")
    Path("s.auto").write_text(
        "from numpy import linspace, int64\n"
        "r = run('line', UZR={1: linspace(0.25, 1.0, 4)}, UZSTOP={1: 1.2}, NMX=int64(500))\n"
        "save(r, 'out')\n")
    run_script("s.auto")
    uz = clui.loadbd("out")("UZ")
    assert [round(float(r["PAR(1)"]), 6) for r in uz] == [0.25, 0.5, 0.75, 1.0, 1.2]


def test_a_loaded_points_parameters_past_npar_stay_with_it_and_reach_the_equations(
        tmp_path, monkeypatch):
    """AUTO's r3b data.py builds a manifold's start as load(u, PAR={2, 3, 6, 12, 21..23,
    25..36}) and runs it with c='man.H1a.0' (NPAR = 16): the PAR belong to the solution
    (AUTO's AUTOSolution.update), not to constants the next c= replaces, and the run's NPAR
    is at least the record's (AUTO's FINDLB_OR_STOP), so man.f90's BCND reads the start
    u0 = PAR(25..30) + eps PAR(31..36). Here u0 is a point of the plane (mu = 0.063), v a
    direction, T = PAR(11) = 0 at the start: three steps of the time integration keep
    u(0) at u0 to Newton's tolerance (EPSU = 1e-6) and write NPAR = 36 (the constants'
    16 in the header's 'User-specified constants' line, as AUTO's b.startH1a)."""
    from washer.auto.files import read_s
    for f in ("man.f90", "c.man.H1a.0"):
        shutil.copy(DEMOS / "r3b" / f, tmp_path)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("WASHER_CACHE", str(tmp_path / "cache"))
    mu, eps = 0.063, -1e-3
    base = np.array([0.8, 0.0, 0.05, 0.0, 0.3, 0.0])
    v = np.array([0.6, 0.8, 0.0, 0.0, 0.0, 0.0])
    u = base + eps * v
    x, y, z, xp, yp, zp = u
    energy = (xp ** 2 + yp ** 2 + zp ** 2) / 2 - ((x ** 2 + y ** 2) / 2 + (1 - mu) / np.sqrt(
        (x + mu) ** 2 + y ** 2 + z ** 2) + mu / np.sqrt((x - 1 + mu) ** 2 + y ** 2 + z ** 2)) \
        - mu * (1 - mu) / 2
    par = {2: mu, 3: energy, 6: eps, 12: 0, 21: x, 22: y, 23: z}
    par.update({25 + i: base[i] for i in range(6)})
    par.update({31 + i: v[i] for i in range(6)})
    start = clui.COMMANDS["load"](list(u), PAR=par)
    assert start.PAR(36) == 0.0 and start.PAR(25) == 0.8 and start.PAR(3) == energy
    clui.COMMANDS["run"](start, e="man", c="man.H1a.0", NMX=3, NPR=1, sv="m")
    recs = read_s("s.m")
    assert len(recs) >= 2 and all(len(r.par) == 36 for r in recs)
    for r in recs:
        np.testing.assert_array_equal(r.par[24:36], np.r_[base, v])
        np.testing.assert_allclose(np.asarray(r.u)[0], u, atol=1e-6)
    assert float(recs[-1].par[10]) > 0          # the orbit grew: T = PAR(11) moved
    header = Path("b.m").read_text()
    assert "NPAR=  36" in header and "NPAR=  16" in header.split("User-specified")[1]
