"""ISW = -1 at labels of the two-parameter curves of equilibria (fold and Hopf curves,
computed with ISW = 2), on AUTO's ab demo, against Debian AUTO-07p's own output of the same
script (tests/data/isw_curves, constants unchanged).

AUTO's FINDLB sets ITPST = 0 wherever |ISW| < 2, whatever the label's type, so the run is
an ordinary continuation of the equilibria in PAR(ICP(1)), the curve's other parameters
fixed at the label's values, from the record's first NDIM unknowns, started along CNRLAE's
STPRAE direction with IPERP = 1 (READLB's stored direction: the curve's) as a new branch.
At a point of a fold curve (the CP, a regular label, the UZ, the EP, the BT) the equilibria
have a fold: that direction's PAR(1) component is zero to rounding (1e-11), so the way
STPRAE's 'PAR(ICP(1))-dot made positive' takes is decided by rounding, in AUTO and here;
there the two runs (DS and DS = '-') are compared with AUTO's two as a pair. On the Hopf
curve away from the BT the component is 0.02 to 0.07 and each run goes AUTO's way."""
import gzip
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.auto import clui
from washer.auto.script import run_script

DATA = Path(__file__).parent / "data"

#: Labels at which the equilibria have a fold (the way is rounding's), and the others.
AT_FOLDS = ("cp", "lrg", "luz", "lep", "lbt", "hbt")
ON_HOPF_CURVE = ("hrg", "hep")


def _rows(text: str) -> np.ndarray:
    """The b-file's point rows: BR, PT, TY, LAB, then the columns."""
    out = []
    for line in text.splitlines():
        words = line.split()
        if len(words) > 4 and words[0] != "0":
            out.append([float(w) for w in words])
    return np.array(out)


def _auto(name: str) -> np.ndarray:
    return _rows(gzip.decompress((DATA / "isw_curves" / f"b.{name}.gz").read_bytes())
                 .decode())


def _same(ours: np.ndarray, auto: np.ndarray) -> bool:
    """The same points: branch, PT with its stability sign, type and label, and values
    to 1e-6 relative to 1 + |value| (each point a Newton solution to EPSU = EPSL = 1e-7).
    The first row is the label itself, where the eigenvalues with zero real part (a
    Hopf pair, the BT's double zero) make the stability sign rounding's: |PT| there."""
    if ours.shape != auto.shape:
        return False
    head_o, head_a = ours[:, :4].copy(), auto[:, :4].copy()
    head_o[0, 1], head_a[0, 1] = abs(head_o[0, 1]), abs(head_a[0, 1])
    if not np.array_equal(head_o, head_a):
        return False
    return float((np.abs(ours[:, 4:] - auto[:, 4:]) / (1 + np.abs(auto[:, 4:]))).max()) \
        < 1e-6


def _ab_script(tmp_path_factory, script: str) -> dict:
    """The b-files' rows {NAME: rows of b.NAME} of tests/data/isw_curves/`script` run in a
    fresh folder with AUTO's ab demo files; no command of it refused."""
    if shutil.which("gfortran") is None:
        pytest.skip("ab.f90 needs gfortran")
    d = tmp_path_factory.mktemp(script.replace(".", "_"))
    for f in ("ab.f90", "c.ab.1", "c.ab.2"):
        shutil.copy(DATA / "auto_demos" / "ab" / f, d)
    shutil.copy(DATA / "isw_curves" / script, d)
    mp = pytest.MonkeyPatch()
    mp.chdir(d)
    try:
        clui._runner.refused.clear()
        run_script(script)
        assert not clui._runner.refused
    finally:
        mp.undo()
    return {p.name[2:]: _rows(p.read_text()) for p in d.glob("b.*")}


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    return _ab_script(tmp_path_factory, "isw.auto")


@pytest.mark.parametrize("name", ON_HOPF_CURVE)
def test_isw_minus_one_on_the_hopf_curve_continues_the_equilibria_as_auto(runs, name):
    for suffix in ("", "m"):
        assert _same(runs[name + suffix], _auto(name + suffix)), name + suffix
    # a new branch (the file's highest + 1) along PAR(1) alone, PAR(3) held at the label's
    forward = runs[name]
    assert np.all(forward[:, 0] == 10)
    assert np.ptp(forward[:, -1]) == 0 and np.ptp(forward[:, 4]) > 0.01


@pytest.mark.parametrize("name", AT_FOLDS)
def test_isw_minus_one_at_a_fold_of_the_equilibria_continues_them_as_auto(runs, name):
    ours = (runs[name], runs[name + "m"])
    auto = (_auto(name), _auto(name + "m"))
    assert (_same(ours[0], auto[0]) and _same(ours[1], auto[1])) or \
        (_same(ours[0], auto[1]) and _same(ours[1], auto[0])), name
    # the two runs leave the label on the two sides of the fold: U(1) up and down
    start = ours[0][0, 6]
    assert (ours[0][-1, 6] - start) * (ours[1][-1, 6] - start) < 0
    assert np.ptp(ours[0][:, -1]) == 0          # PAR(3) held at the label's value


@pytest.mark.skipif(shutil.which("gfortran") is None, reason="pf.f90 needs gfortran")
def test_isw_minus_one_on_a_branch_point_locus_switches_as_auto(tmp_path, monkeypatch):
    """At a label of a branch-point locus (generic, ISW = 3, and non-generic, ISW = 2) the
    equilibria in PAR(1) have a branch point, so STPRAE's IPERP = 1 direction (the null
    vector of [f_u f_p1; the locus's direction]) leaves along the other branch: the
    pitchfork u1^2 + u2^2 = p1 (closed form), both ways, as AUTO's b-files."""
    src = DATA / "isw_curves" / "bp"
    for f in ("pf.f90", "c.pf", "pf.auto"):
        shutil.copy(src / f, tmp_path)
    monkeypatch.chdir(tmp_path)
    clui._runner.refused.clear()
    run_script("pf.auto")
    assert not clui._runner.refused
    for name in ("g", "gm", "n", "nm", "ge", "gem"):
        ours = _rows(Path(f"b.{name}").read_text())
        assert _same(ours, _rows((src / f"b.{name}").read_text())), name
        # columns PAR(1), L2-NORM, U(1), U(2): on the pitchfork, off the trivial branch;
        # each point a Newton solution to EPSU = 1e-7
        p1, u1, u2 = ours[:, 4], ours[:, 6], ours[:, 7]
        assert np.abs(u1**2 + u2**2 - p1).max() < 1e-6
        assert np.all(np.abs(u1[1:]) > 0.01)
        assert np.all(u1[1:] > 0) if not name.endswith("m") else np.all(u1[1:] < 0)


@pytest.fixture(scope="module")
def runs_isw1(tmp_path_factory):
    return _ab_script(tmp_path_factory, "isw1.auto")


def test_isw_one_at_curve_labels_continues_the_equilibria_as_auto(runs_isw1):
    """ISW = 1 at a label of a fold or Hopf curve: FINDLB's ITPST = 0 as for ISW = -1, so
    the equilibria in PAR(1) go on (the record's branch number: no switch), from the
    null vector of [f_u f_p] (STPRAE, IPERP = 0: the record's free parameters are not
    the run's). At the fold curve's labels that vector's PAR(1) component is rounding's,
    so the two ways are compared as a pair; on the Hopf curve each run goes AUTO's way."""
    for name in ("ehrg", "ehep"):
        for suffix in ("", "m"):
            assert _same(runs_isw1[name + suffix], _auto(name + suffix)), name + suffix
    for name in ("ecp", "elrg"):
        ours = (runs_isw1[name], runs_isw1[name + "m"])
        auto = (_auto(name), _auto(name + "m"))
        assert (_same(ours[0], auto[0]) and _same(ours[1], auto[1])) or \
            (_same(ours[0], auto[1]) and _same(ours[1], auto[0])), name
    assert np.all(runs_isw1["ecp"][:, 0] == 10)          # the fold curve's branch
    assert np.ptp(runs_isw1["ehrg"][:, -1]) == 0          # PAR(3) held


def test_a_restart_along_a_stored_direction_turns_it_to_a_growing_parameter_as_auto(
        runs_isw1):
    """IPS = 1: CNRLAE's STPRAE with IPERP = -1 turns the stored direction so that
    PAR(ICP(1))-dot is positive before DS's sign chooses the way. At the fold curve's UZ
    (its run's constants, ISW = 2) the curve runs towards PAR(1) growing, back towards
    the cusp; at label 12 of the equilibria, past their fold where PAR(1) decreases along
    the branch, the run goes back towards the fold. Both as AUTO's b-files."""
    for name in ("cont", "d12"):
        assert _same(runs_isw1[name], _auto(name)), name
        assert np.all(np.diff(runs_isw1[name][:, 4]) > 0), name


def test_isw_minus_two_is_refused_with_the_restart_label_named(tmp_path):
    """ISW = -2 is AUTO's generating run of a locus of cycles (ISW = 2 at an LP, PD or TR
    label of cycles does that here); at a label of a curve of equilibria AUTO-07p takes one
    step and ends MX. It is refused before any work, naming the constants file, ISW and
    the restart label, and nothing is written."""
    from washer.run import RunError, run
    for f in ("c.ab", "ab.py"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    run(tmp_path / "c.ab", sv="eq", verbose=False)
    hb = run(tmp_path / "c.ab", s="eq", IRS="HB1", ICP=[1, 3], ISW=2, NMX=10, NPR=5, sv="hb",
             verbose=False)
    lab = next(r.lab for r in hb.rows if r.lab)
    with pytest.raises(RunError, match=rf"c\.ab.*ISW=-2 \(IRS={lab}\)"):
        run(tmp_path / "c.ab", s="hb", IRS=lab, ICP=[1], ISW=-2, sv="again", verbose=False)
    assert not list(tmp_path.glob("*.again"))


def test_periodic_orbits_start_from_any_point_of_a_hopf_curve_as_auto(tmp_path_factory):
    """IPS = 2 at a label of a Hopf curve (ISW = 2 of the equilibria): AUTO's INITPS takes
    ITP = 3 or |ITP| / 10 = 3 as a Hopf point whatever |ISW| <= 1 says, so ISW = -1 at a
    regular label and ISW = 1 at the curve's EP both start the periodic orbits there, from
    the record's state and its period PAR(11) (STPNPB), as at an HB label. NEWLAB's branch
    is the record's (ITP is not 3): -9 here, not the label. Both runs as AUTO's b-files
    (tests/data/isw_curves/isw_cycles.auto). The period has no weight in the arclength
    (THL = {11: 0}): where the two Hopf curves' labels differ by dP in PAR(1) (1.5e-7,
    within EPSL), the periods of the orbits differ by up to |dT / dPAR(1)| dP along the
    family, the slope taken from AUTO's own rows."""
    runs = _ab_script(tmp_path_factory, "isw_cycles.auto")
    for name in ("hcyc", "hcycep"):
        ours, auto = runs[name], _auto(name)
        assert _same(ours[:, :-1], auto[:, :-1]), name
        slope = np.abs(np.diff(auto[:, -1]) / np.diff(auto[:, 4])).max()
        d_par = np.abs(ours[:, 4] - auto[:, 4]).max()
        assert d_par < 1e-6 and np.abs(ours[:, -1] - auto[:, -1]).max() < 2 * slope * d_par
        assert np.all(runs[name][:, 0] == -9)
        # the orbits grow from the Hopf point: L2-norm increasing, period column positive
        assert np.all(np.diff(runs[name][:, 5]) > 0)


def test_the_user_file_may_sit_in_a_subfolder_named_by_a_path_in_e(tmp_path, monkeypatch):
    """e='./model/ab' is AUTO's ab.f90 in the folder model/ (AUTO compiles e + '.f90'
    wherever that is); the run is the same as with ab.f90 beside the constants files:
    isw_cycles.auto's periodic orbits from the Hopf curve, as AUTO's own b.hcyc."""
    if shutil.which("gfortran") is None:
        pytest.skip("ab.f90 needs gfortran")
    (tmp_path / "model").mkdir()
    shutil.copy(DATA / "auto_demos" / "ab" / "ab.f90", tmp_path / "model")
    for f in ("c.ab.1", "c.ab.2"):
        shutil.copy(DATA / "auto_demos" / "ab" / f, tmp_path)
    script = (DATA / "isw_curves" / "isw_cycles.auto").read_text()
    assert "e='ab'" in script
    (tmp_path / "sub.auto").write_text(script.replace("e='ab'", "e='./model/ab'"))
    monkeypatch.chdir(tmp_path)
    clui._runner.refused.clear()
    run_script("sub.auto")
    assert not clui._runner.refused
    ours, auto = _rows(Path("b.hcyc").read_text()), _auto("hcyc")
    assert _same(ours[:, :-1], auto[:, :-1])
