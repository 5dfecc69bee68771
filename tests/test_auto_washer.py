"""AUTO-07p itself on the washer's equations (washer.problems.auto07p: AUTO's C user file
calling the washer kernel) against washer on the same constants files
(auto_constants/c.washer, c.washer.hopf.Omega): the check that the benchmark against
AUTO (benchmarks/bench_vs_auto.py, washer_fig3 / washer_fig4) compares like with like.

Compared, per point located by a condition (not by the step history):
* the HB point of the equilibrium branch in C_p, and the UZ point of the Hopf curve at
  Omega = 15 Hz: C_p within twice the location guarantee of a special point,
  EPSS (1 + sqrt|DS DSMAX|) + EPSL (1 + |value|) (each side is within one of the
  true value); the state u within Newton's EPSU plus that bound times u's rate of change
  in C_p (measured on washer's side between two labelled points); the period PAR(11)
  to 1e-5 relative (2 pi / Im(lambda) at C_p within that bound);
* every labelled point of AUTO's Hopf curve is a Hopf point of washer's equations:
  washer's f(u, p) ~ 0 and washer's f_u(u, p) has the eigenvalue pair +-i 2 pi / PAR(11).
* the frozen frame (c.washer.frozen, AUTO's user file built with frame='frozen'): the HB.
Needs the installed AUTO-07p (`auto-07p`, Debian's package) and a C/C++ compiler;
building the kernel's objects takes a minute or two the first time (cached).
"""
import math
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from washer.auto.files import read_s
from washer.problems import auto07p
from washer.problems.rotating import rotating_problem
from washer.run import run

ROOT = Path(__file__).resolve().parent.parent
CONSTANTS = ROOT / "auto_constants"

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(not auto07p.installed(),
                       reason="AUTO-07p is not installed (Debian: apt-get install auto-07p)"),
]

SCRIPT = """\
eq = run(e='washer', c='washer', sv='washer')
hb = run(eq('HB1'), e='washer', c='washer.hopf.Omega', sv='washer.hopf.Omega')
"""


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """(AUTO's records, washer's records) of the two runs, by sv."""
    d_auto = tmp_path_factory.mktemp("auto")
    d_ours = tmp_path_factory.mktemp("washer")
    for d in (d_auto, d_ours):
        for name in ("c.washer", "c.washer.hopf.Omega"):
            shutil.copy(CONSTANTS / name, d / name)
    auto07p.build_executable(d_auto)
    (d_auto / "washer.auto").write_text(SCRIPT)
    r = subprocess.run(["auto-07p", "washer.auto"], cwd=d_auto, capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"), stdin=subprocess.DEVNULL,
                       timeout=600)
    log = r.stdout + r.stderr
    assert r.returncode == 0 and (d_auto / "s.washer.hopf.Omega").exists(), log[-3000:]
    assert "washer kernel:" not in log, log[-3000:]        # no kernel failure in FUNC
    run(d_ours / "c.washer", verbose=False)
    run(d_ours / "c.washer.hopf.Omega", verbose=False)
    names = ("washer", "washer.hopf.Omega")
    return ({n: read_s(d_auto / f"s.{n}") for n in names},
            {n: read_s(d_ours / f"s.{n}") for n in names})


def located(records, ty):
    out = [r for r in records if r.ty == ty]
    assert out, f"no {ty} point"
    return out[0]


def guarantee(value, eps_s, eps_l, ds, dsmax):
    """The location guarantee of a special point in one coordinate of a unit tangent."""
    return eps_s * (1 + math.sqrt(abs(ds * dsmax))) + eps_l * (1 + abs(value))


def rate(r1, r2):
    """max |du| / |d C_p| between two labelled points."""
    return np.max(np.abs(r2.U[:12] - r1.U[:12])) / abs(r2.par[0] - r1.par[0])


def test_hopf_point_of_the_equilibrium_branch_agrees(runs):
    auto, ours = runs
    a, w = located(auto["washer"], "HB"), located(ours["washer"], "HB")
    # c.washer: EPSS 1e-5, EPSL 1e-7, DS 0.01, DSMAX 0.05
    tol = 2 * guarantee(w.par[0], 1e-5, 1e-7, 0.01, 0.05)
    assert abs(a.par[0] - w.par[0]) <= tol, (a.par[0], w.par[0], tol)
    assert a.par[10] == pytest.approx(w.par[10], rel=1e-5)
    du = rate(located(ours["washer"], "EP"), located(ours["washer"], "UZ"))
    assert np.max(np.abs(a.U - w.U)) <= 1e-7 * (1 + np.max(np.abs(w.U))) + du * tol


def test_hopf_curve_end_at_omega_15_agrees(runs):
    auto, ours = runs
    a, w = located(auto["washer.hopf.Omega"], "UZ"), located(ours["washer.hopf.Omega"], "UZ")
    # c.washer.hopf.Omega: EPSS 1e-5, EPSL 1e-7, DS 0.05, DSMAX 0.3
    tol = 2 * guarantee(w.par[0], 1e-5, 1e-7, 0.05, 0.3)
    for r in (a, w):
        assert abs(r.par[1] - 15.0) <= guarantee(15.0, 1e-5, 1e-7, 0.05, 0.3), r.par[1]
    assert abs(a.par[0] - w.par[0]) <= tol, (a.par[0], w.par[0], tol)
    assert a.par[10] == pytest.approx(w.par[10], rel=1e-5)
    du = rate(located(ours["washer"], "HB"), w)
    assert np.max(np.abs(a.U[:12] - w.U[:12])) <= 1e-7 * (1 + np.max(np.abs(w.U))) + du * tol


def test_autos_hopf_curve_points_are_hopf_points_of_washers_equations(runs):
    auto, _ = runs
    prob = rotating_problem("averaged").with_jac(1)
    pts = [r for r in auto["washer.hopf.Omega"]]
    assert len(pts) >= 2
    for r in pts:
        u, par = np.asarray(r.U[:12], float), np.asarray(r.par, float)
        A = prob.dfdu(u, par)
        # s-files hold 11 significant digits: f(u) is zero to |A| 1e-10 (1 + |u|)
        scale = np.max(np.abs(A)) * 1e-10 * (1 + np.max(np.abs(u)))
        assert np.max(np.abs(prob.func(u, par))) <= scale, r.lab
        lam = np.linalg.eigvals(A)
        omega = 2 * np.pi / par[10]
        k = np.argmin(np.abs(lam - 1j * omega))
        # Newton's EPSL, EPSU 1e-7 relative, times a condition number of ~10
        assert abs(lam[k] - 1j * omega) <= 1e-6 * omega, (r.lab, lam[k], omega)


def test_frozen_frame_hopf_point_agrees(tmp_path):
    """frame='frozen' (e='washer:frozen'): AUTO's HB in C_p is washer's."""
    for name in ("auto", "washer"):
        (tmp_path / name).mkdir()
        shutil.copy(CONSTANTS / "c.washer.frozen", tmp_path / name / "c.washer.frozen")
    d = tmp_path / "auto"
    auto07p.build_executable(d, frame="frozen", name="washer_frozen")
    (d / "frozen.auto").write_text("run(e='washer_frozen', c='washer.frozen', sv='frozen')\n")
    r = subprocess.run(["auto-07p", "frozen.auto"], cwd=d, capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"), stdin=subprocess.DEVNULL,
                       timeout=600)
    assert r.returncode == 0 and (d / "s.frozen").exists(), (r.stdout + r.stderr)[-3000:]
    run(tmp_path / "washer" / "c.washer.frozen", verbose=False)
    a = located(read_s(d / "s.frozen"), "HB")
    w = located(read_s(tmp_path / "washer" / "s.washer.frozen"), "HB")
    tol = 2 * guarantee(w.par[0], 1e-5, 1e-7, 0.01, 0.05)     # c.washer.frozen's constants
    assert abs(a.par[0] - w.par[0]) <= tol, (a.par[0], w.par[0], tol)
    assert a.par[10] == pytest.approx(w.par[10], rel=1e-5)
