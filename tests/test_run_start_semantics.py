"""How a run starts, as AUTO starts it: which null vector a Hopf start takes (NLVC), the
user file's saved state afresh for every run (a new process per run in AUTO), and a
warning where a user value is passed on the first step, where nothing is detected."""
import shutil
from pathlib import Path

import numpy as np

from washer.cont.linalg import nullvc
from washer.run import run

DATA = Path(__file__).parent / "data"


def test_nullvc_is_a_null_vector_with_the_pivoted_free_unknowns_one():
    """AUTO's NULLVC on a 6 x 6 matrix of rank 4 built from random factors: A u = 0 to
    rounding, and the two unknowns left free by complete pivoting are 1 (so u is not
    the unit SVD vector: which null vector comes out is fixed by the elimination, and
    the Hopf start's orbit phase with it)."""
    rng = np.random.default_rng(3)
    A = rng.standard_normal((6, 4)) @ rng.standard_normal((4, 6))
    u = nullvc(A, 2)
    assert np.linalg.norm(A @ u) < 1e-12 * np.linalg.norm(A) * np.linalg.norm(u)
    # the last two unknowns of the pivoted order are exactly 1: two entries of u are 1
    assert np.sum(u == 1.0) >= 2
    # it lies in the null space (its projection onto it is itself)
    _, _, Vt = np.linalg.svd(A)
    N = Vt[-2:].T
    assert np.linalg.norm(u - N @ (N.T @ u)) < 1e-12 * np.linalg.norm(u)


def test_user_file_saved_state_starts_afresh_for_every_run():
    """pcl's PVLS sets PAR(21) = U(0)(7) - 10 on its FIRST call only (a SAVEd flag): AUTO
    runs every run in a new process, so every run's first call sets it. The compiled
    library reloaded (`fresh`) behaves so; without the reload the second call is a no-op."""
    from washer.cont.user_problem.user_files_native import load_compiled_problem
    p = load_compiled_problem(DATA / "auto_demos" / "pcl" / "pcl.f90", 9)

    def pvls_once():
        u = np.zeros(9)
        u[6] = 3.0
        par = np.zeros(36)
        p.user.pvls(u, par)
        return par[20]
    p.fresh()
    assert pvls_once() == -7.0 and pvls_once() == 0.0
    p.fresh()
    assert pvls_once() == -7.0


def test_a_user_value_passed_on_the_first_step_is_a_warning(tmp_path):
    """The line u = p continued from p = 0 with DS = 0.5: the hidden first step ends at
    p = 0.5, the first written one at p = 1, and UZSTOP p = 0.7 lies inside it, where no
    test is made (AUTO's tests start at 0): it is not labelled and the run goes on to
    NMX; the d-file says so."""
    (tmp_path / "line.py").write_text(
        "import numpy as np\n"
        "def func(u, par):\n    return np.array([u[0] - par[0]])\n"
        "def stpnt(u, par):\n    u[0] = 0.0\n    par[0] = 0.0\n")
    (tmp_path / "c.line").write_text(
        "e = 'line'\nNDIM = 1, IPS = 1, IRS = 0, ILP = 0, ISP = 0\nICP = [1]\nNMX = 4\n"
        "DS = 0.5, DSMIN = 0.01, DSMAX = 0.5\nUZSTOP = {1: 0.7}\n")
    res = run(tmp_path / "c.line", verbose=False, sv="line")
    assert res.status == "ok"
    d = (tmp_path / "d.line").read_text()
    assert [r.ty for r in res.rows if r.lab] == ["EP", "EP"]
    assert "WARNING:PAR(1) passed the user value 0.7 on the first step" in d
    assert "does not stop there" in d


def test_washer_starts_at_the_constants_par_values(tmp_path):
    """c.washer sets PAR = {'C_p': 0.0}: as AUTO's STPNUS (STPNT, then the constants' PAR
    override its values), the run starts at C_p = 0, and at the equilibrium there (the
    state the built-in stpnt computes at the start parameters), not at the reference
    set's C_p = 0.101: the first point is C_p = 0 to Newton's tolerance (EPSL = 1e-7
    relative) and its state is the model's rotating-frame equilibrium at C_p = 0 to EPSU."""
    import washer
    shutil.copy(Path(__file__).resolve().parents[1] / "auto_constants" / "c.washer",
                tmp_path / "c.washer")
    first = run(tmp_path / "c.washer", verbose=False, files=False, NMX=3).rows[0]
    assert first.ty == "EP" and abs(first.par[0]) <= 1e-7
    params = washer.load_params()
    assert params["C_p"] > 0.05                  # the reference set is not at C_p = 0
    eq0 = washer.Model(params.replace(C_p=0.0)).rotating_equilibrium(frame="averaged")
    assert np.max(np.abs(first.U[:6] - eq0)) <= 1e-7 * (1 + np.max(np.abs(eq0)))
    # the start is not the reference set's equilibrium carried to C_p = 0
    eq_ref = washer.Model(params).rotating_equilibrium(frame="averaged")
    assert np.max(np.abs(eq_ref - eq0)) > 1e-7 * (1 + np.max(np.abs(eq0)))


def test_isw2_without_a_restart_label_continues_the_branch_itself(tmp_path):
    """ISW = 2 with IRS = 0: no label names a special point whose locus to continue (AUTO
    sets ITPST from the restart label's type, FINDLB, which only a restart calls), so
    AUTO-07p runs the ordinary branch from STPNT. The cubic p = u^3 - 3u from u = -2
    (p = -2) has its folds at u = -1, p = 2 and u = 1, p = -2 (dp/du = 3u^2 - 3 = 0):
    both are found, to the location tolerance EPSS (1 + sqrt(|DS DSMAX|)) in p, and the
    run is the ISW = 1 run row for row (ISW has no part in it)."""
    (tmp_path / "cub.py").write_text(
        "import numpy as np\n"
        "def func(u, par):\n    return np.array([par[0] - u[0]**3 + 3*u[0]])\n"
        "def stpnt(u, par):\n    u[0] = -2.0\n    par[0] = -2.0\n")
    (tmp_path / "c.cub").write_text(
        "e = 'cub'\nNDIM = 1, IPS = 1, IRS = 0, ILP = 1, ISW = 2\nICP = [1]\nNMX = 200\n"
        "DS = 0.05, DSMIN = 0.001, DSMAX = 0.1\nEPSS = 1e-6\nRL0 = -3, RL1 = 3\n")
    res = run(tmp_path / "c.cub", verbose=False, files=False)
    assert res.status == "ok"
    lps = [r for r in res.rows if r.ty == "LP"]
    tol = 1e-6 * (1 + np.sqrt(0.05 * 0.1))
    assert [round(float(r.par[0])) for r in lps] == [2, -2]
    assert all(abs(abs(float(r.par[0])) - 2.0) <= tol for r in lps)
    plain = run(tmp_path / "c.cub", verbose=False, files=False, ISW=1)
    assert [(r.ty, r.lab) for r in plain.rows] == [(r.ty, r.lab) for r in res.rows]
    assert [float(r.par[0]) for r in plain.rows] == [float(r.par[0]) for r in res.rows]


def test_time_integration_integrates_in_par14_whatever_icp_names(tmp_path):
    """IPS = -2 with ICP = [1, 2] (a script's run(..., IPS=-2) after equilibrium runs in
    PAR(1)): AUTO's AUTOTI sets ICP(1) = 14, so time is PAR(14) and PAR(1) keeps its
    value. u' = -a u, a = PAR(1) = 2: every step is a backward Euler step,
    u_k = u_{k-1} / (1 + a (t_k - t_{k-1})), to Newton's tolerance EPSU (relative), with
    a = 2 at every point and t = PAR(14) increasing from 0."""
    (tmp_path / "dec.py").write_text(
        "import numpy as np\n"
        "def func(u, par):\n    return np.array([-par[0] * u[0]])\n"
        "def stpnt(u, par):\n    u[0] = 1.0\n    par[0] = 2.0\n    par[1] = 5.0\n")
    (tmp_path / "c.dec").write_text(
        "e = 'dec'\nNDIM = 1, IPS = -2, IRS = 0\nICP = [1, 2]\nNMX = 30, NPR = 1\n"
        "DS = 0.01, DSMIN = 0.001, DSMAX = 0.1\nEPSU = 1e-8, EPSL = 1e-8\n")
    res = run(tmp_path / "c.dec", verbose=False, files=False)
    assert res.status == "ok" and len(res.rows) >= 20
    a = np.array([float(r.par[0]) for r in res.rows])
    t = np.array([float(r.par[13]) for r in res.rows])
    u = np.array([float(r.U[0]) for r in res.rows])
    assert np.all(a == 2.0) and t[0] == 0.0 and np.all(np.diff(t) > 0)
    # (from the second row: between the first two lies the start's unwritten step)
    pred = u[1:-1] / (1 + 2.0 * np.diff(t[1:]))
    assert np.max(np.abs(u[2:] - pred) / np.abs(pred)) < 1e-7
    assert u[1] < 1 / (1 + 2.0 * t[1]) < 1.0    # two Euler steps lose more than one


FHN_WAVES = """import numpy as np
def func(u, par):
    v, d, w = u[0], u[1], u[2]
    p, s, delta, alpha, gamma, eps = par[0], par[1], par[2], par[3], par[4], par[5]
    f = v * (v - 1) * (alpha - v)
    return np.array([d, (s * d + w - p - f) / delta, eps * (v - gamma * w) / s])
def stpnt(u, par):
    u[:] = 0.0
    par[:6] = [0.0, 1.0, 5.0, 0.1, 1.0, 0.01]
"""


def test_hopf_locus_start_takes_autos_vector_of_the_eigenplane(tmp_path, monkeypatch):
    """FitzHugh-Nagumo travelling waves (v' = d, d' = (s d + w - p - f(v)) / delta,
    w' = eps (v - gamma w) / s, f = v (v - 1)(alpha - v)) have a Hopf point in p at
    s = 1. The Hopf locus starts with v, a null vector of A^2 + kappa I, whose null space
    is a plane; NLVC's pivot picks which one, and here the first row of A^2 + kappa I
    holds s / delta and 1 / delta, equal (0.2) in exact arithmetic: the rounding of the
    differenced f_u decides. AUTO-07p 0.9.2 on these equations (Fortran FUNC, JAC = 0)
    starts from v = (0.5792664, -0.5734987, 0.5792664); the other vector NLVC can give
    is (0.579, 0.579, -0.573), which ours took while f_u was differenced with a step per
    component instead of AUTO's FUNI's one step HMACH (1 + max |u|), and the locus's
    steps (measured with v's components) then fell one point later than AUTO's. The
    tolerance 1e-4: the two HB points are located to EPSS, ours and AUTO's u 3e-5 apart,
    and v moves with u; the wrong vector is 1.15 away."""
    from washer.auto import clui
    from washer.auto.files import read_s
    from washer.auto.script import run_script
    monkeypatch.chdir(tmp_path)
    clui._runner.refused.clear()
    (tmp_path / "fhn.py").write_text(FHN_WAVES)
    (tmp_path / "c.fhn").write_text(
        "e = 'fhn'\nNDIM = 3, IPS = 1, IRS = 0, ILP = 0, ISP = 2\nICP = [1]\n"
        "NMX = 50, NPR = 100, ITMX = 8, ITNW = 7, NWTN = 3\n"
        "EPSL = 1e-7, EPSU = 1e-7, EPSS = 1e-4\nDS = 0.1, DSMIN = 0.01, DSMAX = 5.0\n")
    (tmp_path / "x.auto").write_text(
        "a = run('fhn')\nrun(a('HB1'), ISW=2, ICP=[1, 2], NMX=2, NPR=1, sv='hb')\n")
    run_script("x.auto")
    start = read_s(tmp_path / "s.hb")[0]
    v = np.asarray(start.u, float)[3:6]           # (u, v, kappa, PAR(ICP(2)))
    auto = np.array([0.5792664334, -0.5734987344, 0.5792664334])
    assert np.max(np.abs(v - auto)) < 1e-4, v
