"""What a run finds and how it goes on (periodic orbits above all), on problems whose
answers are known in closed form (tests/data/mobius, rotor, cyclepf; their docstrings derive them)
and on AUTO-07p's lor demo (AUTO's own b-file, constants unchanged).

Location tolerance of a special point: EPSS (1 + sqrt|DS DSMAX|) in arclength (the
tangent is unit in the weighted norm, so a parameter is off by at most that).
"""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from demo_files import autoref, copy_demo
from tolerances import location_tolerance
from washer.run import run

DATA = Path(__file__).parent / "data"


def folder(tmp_path, name):
    for f in (DATA / name).iterdir():
        shutil.copy(f, tmp_path)
    return tmp_path


def test_pd_after_a_complex_pair_meets_the_real_axis_within_one_step(tmp_path):
    """One test function for PD and TR (AUTO's FNSPBV): from b = -0.02 (a complex pair
    inside the circle, torus type) to b = 0.02 (real, one multiplier beyond -1) the pair
    meets the axis at b = 0 and one crosses -1 at b = a^2 = 0.01. The combined test
    changes sign over the step, the located point is typed by its multipliers: PD at
    b = 0.01. (Separate PD and TR tests each saw one end of the step and found nothing;
    AUTO-07p on the same problem: PD at b = 0.010000024.)"""
    d = folder(tmp_path, "mobius")
    res = run(d / "c.mobius.spb", verbose=False, sv="spb")
    assert res.status == "ok"
    lab = [r for r in res.rows if r.lab]
    assert [r.ty for r in lab] == ["EP", "PD", "UZ"]
    assert lab[1].values[0] == pytest.approx(0.01, abs=location_tolerance(d / "c.mobius.spb"))
    assert lab[1].stability.values[1] == pytest.approx(-1.0, abs=1e-6)


def test_branch_point_of_cycles_leaves_along_the_secant_and_switches_exactly(tmp_path):
    """The pitchfork of cycles of tests/data/cyclepf at a = -sqrt(b) = -0.5: located
    (BP, to the location tolerance); the direction stored at the BP and taken from it is
    AUTO's, the secant from the previous point (CONTBV), so the run goes on along the
    primary cycle (z = 0 at every later point: U(3), U(4) never move) to the UZSTOP;
    ISW = -1 from BP1 follows the secondary family, z = sqrt(lambda) (1, sqrt b) /
    sqrt(1 + b) up to sign, lambda = a + sqrt(b): at the UZ a = -0.2, |max U(3)| or
    |min| = sqrt(0.3 / 1.25) to the collocation error (z is constant in t: exact)."""
    d = folder(tmp_path, "cyclepf")
    res = run(d / "c.cyclepf", verbose=False, sv="pf")
    assert res.status == "ok"
    lab = [r for r in res.rows if r.lab]
    assert [r.ty for r in lab] == ["EP", "BP", "UZ"]
    bp = lab[1]
    assert bp.values[0] == pytest.approx(-0.5, abs=location_tolerance(d / "c.cyclepf"))
    rows = res.rows
    k = rows.index(bp)
    # the stored direction is the unit secant: no motion of the orbit, PAR(1)-dot 1
    assert bp.rldot[0] == pytest.approx(1.0, abs=1e-12)
    assert np.max(np.abs(bp.udot)) == pytest.approx(0.0, abs=1e-9)
    assert bp.values[0] > rows[k - 1].values[0]
    for r in rows[k:]:
        assert np.max(np.abs(np.asarray(r.u)[:, 2:])) < 1e-12
    sw = run(d / "c.cyclepf.sw", verbose=False, sv="sw", s="pf")
    assert sw.status == "ok"
    uz = [r for r in sw.rows if r.lab and r.ty == "UZ"]
    assert [round(r.values[0], 9) for r in uz] == [-0.2]
    z = np.asarray(uz[0].u)[:, 2:]
    lam = -0.2 + 0.5
    assert np.max(np.abs(z[:, 0])) == pytest.approx(math.sqrt(lam / 1.25), abs=1e-8)
    assert np.ptp(z, axis=0) == pytest.approx([0, 0], abs=1e-8)


def test_a_branch_point_passed_with_negative_ds_keeps_the_direction(tmp_path):
    """x' = mu x - x^3 from mu = 1 with DS < 0: the BP at mu = 0 (exact) is passed and the
    trivial branch goes on to the UZSTOP mu = -1, as in AUTO. The secant kept at a
    located point is divided by the signed arclength of the step (it was the bare
    difference, so with DS < 0 the run turned back at the BP to mu = 1.5)."""
    (tmp_path / "pf.py").write_text(
        "import numpy as np\n"
        "def func(u, par):\n    return np.array([par[0] * u[0] - u[0] ** 3])\n"
        "def stpnt(u, par):\n    u[0] = 0.0\n    par[0] = 1.0\n")
    (tmp_path / "c.pf").write_text(
        "e = 'pf'\nNDIM = 1, IPS = 1, IRS = 0, ILP = 1\nICP = [1]\nNMX = 30, MXBF = 0\n"
        "DS = -0.1, DSMIN = 0.001, DSMAX = 0.2\nUZSTOP = {1: [-1.0, 1.5]}\n")
    res = run(tmp_path / "c.pf", verbose=False, sv="pf")
    lab = [(r.ty, r.values[0]) for r in res.rows if r.lab]
    assert [t for t, _ in lab] == ["EP", "BP", "UZ"]
    assert lab[1][1] == pytest.approx(0.0, abs=location_tolerance(tmp_path / "c.pf"))
    assert lab[2][1] == pytest.approx(-1.0)


def test_lor_demo_starts_from_data_and_doubles_twice(tmp_path):
    """AUTO-07p's demo lor as its script runs it, constants unchanged: the periodic branch
    starts from lor.dat (dat='lor': t, u1, u2, u3 rows of one period at PAR(1) = 280;
    the period PAR(11) = 0.4332 from the time column), then ISW = -1 at PD1 and at the
    next PD. Against AUTO's b.lor: the labelled rows' types and branches in order, and
    PAR(1) and PERIOD of the period doublings at 1e-5 relative (the same discrete problem;
    EPSS = 1e-4 decides the rest); the UZ stops are exactly PAR(1) = 200 here (AUTO's
    loose 199.9999902 comes from its own EPSS)."""
    from b_rows import branch_rows
    from washer.auto.files import type_name
    d = copy_demo("lor", tmp_path, DATA / "lor")
    ours = []
    for cf, s in (("c.lor.1", None), ("c.lor.2", "lor1"), ("c.lor.3", "lor2")):
        kw = {"s": s} if s else {}
        res = run(d / cf, verbose=False, sv=f"lor{cf[-1]}", e="lor", **kw)
        assert res.status == "ok", (cf, res.status)
        ours += [r for r in res.rows if r.lab]
    ref = [r for r in branch_rows(autoref("lor") / "b.lor") if r.lab]
    assert [(r.ty, abs(r.br)) for r in ours] == [(type_name(r.ty), abs(r.br)) for r in ref] == [
        ("EP", 1), ("PD", 1), ("UZ", 1), ("PD", 2), ("UZ", 2), ("PD", 3), ("UZ", 3)]
    assert ours[0].values[-1] == pytest.approx(1.4334 - 1.0002, rel=1e-12)
    for o, r in zip(ours, ref):
        if o.ty == "PD":
            assert o.values[0] == pytest.approx(r.values[0], rel=1e-5)
            assert o.values[-1] == pytest.approx(r.values[-1], rel=1e-5)
        if o.ty == "UZ":
            assert o.values[0] == pytest.approx(200.0, rel=1e-12)


def test_bad_data_files_are_named_with_line_and_expectation(tmp_path):
    """dat='NAME' errors name the file, the line and what was expected there."""
    from washer.cont.runner import RunError
    d = copy_demo("lor", tmp_path, DATA / "lor")
    with pytest.raises(RunError, match=r"dat='nothere': no data file nothere or nothere\.dat"):
        run(d / "c.lor.1", verbose=False, e="lor", dat="nothere", sv="x")
    # dat='NAME.dat' (a user's constants file: sandstede-lab's c.auto_SH_half) is the file
    # NAME.dat, as AUTO opens NAME first; missing, the message names what was looked for
    # (it said nothere.dat.dat)
    res = run(d / "c.lor.1", verbose=False, e="lor", dat="lor.dat", sv="y", NMX=3)
    assert res.status == "ok" and len(res.rows) == 3
    with pytest.raises(RunError, match=r"no data file nothere\.dat or nothere\.dat\.dat"):
        run(d / "c.lor.1", verbose=False, e="lor", dat="nothere.dat", sv="x")
    lines = (d / "lor.dat").read_text().splitlines()
    lines[4] = "0.1 2.0 x"
    (d / "bad.dat").write_text("\n".join(lines) + "\n")
    with pytest.raises(RunError, match=r"bad\.dat:5: expected 4 numbers"):
        run(d / "c.lor.1", verbose=False, e="lor", dat="bad", sv="x")
    lines[4] = "0.1 2.0 x 3"
    (d / "bad.dat").write_text("\n".join(lines) + "\n")
    with pytest.raises(RunError, match=r"bad\.dat:5: expected numbers"):
        run(d / "c.lor.1", verbose=False, e="lor", dat="bad", sv="x")


def test_stop_counts_start_afresh_on_every_switched_branch(tmp_path):
    """x' = mu x + x^3 - x^5 from mu = -1 on x = 0: a BP at mu = 0, and MXBF switching
    follows the secondary branch mu = x^4 - x^2 both ways, each with its one fold at
    mu = -1/4 (x^2 = 1/2). STOP = ['LP2'] counts per branch, as AUTO's INITSTOPCNTS at
    every branch: neither direction reaches a second LP, so both run to the window
    mu = 1 (EP) (counted over the run, the second direction stopped at its LP)."""
    (tmp_path / "qp.py").write_text(
        "import numpy as np\n"
        "def func(u, par):\n    return np.array([par[0] * u[0] + u[0] ** 3 - u[0] ** 5])\n"
        "def stpnt(u, par):\n    u[0] = 0.0\n    par[0] = -1.0\n")
    (tmp_path / "c.qp").write_text(
        "e = 'qp'\nNDIM = 1, IPS = 1, IRS = 0, ILP = 1\nICP = [1]\nNMX = 200, MXBF = 5\n"
        "DS = 0.05, DSMIN = 0.001, DSMAX = 0.05\nRL0 = -1.0, RL1 = 1.0\nSTOP = ['LP2']\n")
    res = run(tmp_path / "c.qp", verbose=False, sv="qp")
    segs = [[]]
    for r in res.rows:
        if r.pt == 1 and segs[-1]:
            segs.append([])
        if r.lab:
            segs[-1].append((r.ty, r.values[0]))
    assert [[t for t, _ in seg] for seg in segs] == [["EP", "BP", "EP"], ["LP", "EP"],
                                                    ["LP", "EP"]]
    tol = location_tolerance(tmp_path / "c.qp")
    for seg in segs[1:]:
        assert seg[0][1] == pytest.approx(-0.25, abs=tol)
        assert seg[1][1] > 1.0


def test_pvls_receives_the_orbit_with_autos_getp_helpers(tmp_path):
    """On IPS = 2, pvls(u, par) gets a washer.cont.pvls.Orbit: the node values with the
    mesh, the period and GETP's helpers. On mobius's cycle (cos 2 pi t, sin 2 pi t, 0, 0)
    the integrals are known: NRM(1)^2 = 1/2, INT(1) = 0, MAX(2) = 1 (a node at t = 1/4),
    BV0/BV1 equal (to the collocation error of the orbit at NTST = 20: its radius is
    1 - 2.5e-9; 1e-8 allowed); the transverse multipliers have |mu| = exp(a T), so a UZR value
    exp(-0.2) on the PAR that pvls fills with |mu_2| is found at a = -0.2."""
    d = folder(tmp_path, "mobius")
    src = (d / "mobius.py").read_text() + '''

def pvls(u, par):
    par[12] = u.norm(1) ** 2
    par[13] = u.integral(1)
    par[14] = u.max(2)
    par[15] = u.bv1(3) - u.bv0(3)
    par[16] = abs(u.multipliers[1])
    par[17] = u.n_stable
    par[18] = u.period
'''
    (d / "mobpv.py").write_text(src)
    c = (d / "c.mobius.tr").read_text().replace("e = 'mobius'", "e = 'mobpv'")
    c = c.replace("NPAR = 12", "NPAR = 19").replace("UZSTOP = {1: 0.3}",
                                                    "UZR = {17: 0.8187307530779818}\nUZSTOP = {1: 0.3}")
    (d / "c.mobpv").write_text(c)
    res = run(d / "c.mobpv", verbose=False, sv="pv")
    assert res.status == "ok"
    for r in res.rows:
        assert r.par[12] == pytest.approx(0.5, abs=1e-8)
        assert r.par[13] == pytest.approx(0.0, abs=1e-8)
        assert r.par[14] == pytest.approx(1.0, abs=1e-8)
        assert r.par[15] == 0.0
        assert r.par[16] == pytest.approx(math.exp(r.values[0]), rel=1e-7)
        assert r.par[18] == pytest.approx(1.0, abs=1e-10)
    uz = [r for r in res.rows if r.ty == "UZ"]
    assert uz[0].values[0] == pytest.approx(-0.2, abs=location_tolerance(d / "c.mobpv"))
    assert uz[0].par[17] == 4             # all inside: 1, exp(-2), the pair at exp(-0.2)


FOLDC = """import math
import numpy as np


def func(u, par):
    x, y = u
    r = math.sqrt(x * x + y * y)
    g = par[0] + par[1] - (r - 1) ** 2
    return np.array([x * g - y, y * g + x])


def stpnt(u, par, t=0.0):
    par[0], par[1], par[10] = 0.25, 0.0, 2 * math.pi
    u[0], u[1] = 1.5 * math.cos(2 * math.pi * t), 1.5 * math.sin(2 * math.pi * t)


def pvls(u, par):
    par[4] = u.norm(1) + par[1]
"""


def test_pvls_runs_on_the_fold_locus_of_cycles(tmp_path):
    """Circles r' = r ((p1 + p2) - (r - 1)^2), theta' = 1: r = 1 +- sqrt(p1 + p2), folding
    at r = 1 on p1 + p2 = 0 (period 2 pi). The fold locus of cycles calls the user's pvls
    at every point, as periodic branches do (AUTO's PVLSBV): PAR(5) = u.norm(1) + PAR(2) =
    1 / sqrt(2) + PAR(2) along the locus, not the restart's value carried along. r = 1
    within the corrector's tolerance (EPSU = 1e-7 relative; measured 3e-9)."""
    (tmp_path / "foldc.py").write_text(FOLDC)
    c = tmp_path / "c.foldc"
    c.write_text("e = 'foldc'\nNDIM = 2, IPS = 2, IRS = 0, ILP = 1\nICP = [1, 11]\n"
                 "NTST = 20, NCOL = 4, ISP = 2, NMX = 40, NPR = 100, NPAR = 12\n"
                 "DS = -0.02, DSMIN = 0.0001, DSMAX = 0.05\n")
    one = run(c, verbose=False, sv="one")
    assert [r.ty for r in one.rows if r.lab] == ["EP", "LP", "EP"]
    gen = run(c, verbose=False, sv="gen", restart=one, IRS="LP1", ISW=2, ICP=[1, 2, 11],
              DS=0.02)
    loc = run(c, verbose=False, sv="loc", restart=gen, IRS=gen.rows[-1].lab, ISW=2,
              ICP=[1, 2, 11], NMX=10, DS=0.05)
    assert loc.status == "ok" and len(loc.rows) == 10
    assert loc.rows[-1].par[1] < -0.3                       # PAR(2) moved along the locus
    for row in loc.rows:
        assert row.par[0] + row.par[1] == pytest.approx(0.0, abs=1e-7)
        assert row.par[4] == pytest.approx(1 / math.sqrt(2) + row.par[1], abs=1e-7)


def test_rotations_have_the_exact_period(tmp_path):
    """tests/data/rotor: U(1) = theta grows by 2 pi per period (AUTO's rotations: NRTN = 1
    from the start profile, u(0) - u(1) + 2 pi NRTN = 0 in the boundary conditions).
    Continued in a from 0 (without rotations the start is not a solution and Newton
    diverges): the period 2 pi / sqrt(1 - a^2) at the UZ points a = 0.3, 0.6 and the
    stop 0.9 to 1e-8 relative (measured 2.5e-10 at 0.9, where the rotation is most
    uneven), the profile on the invariant curve v = 1 + a sin(theta) to 1e-5 (measured
    5e-6 at 0.9: nodes inside the intervals converge as h^(NCOL + 1)), theta(1) -
    theta(0) = 2 pi. AUTO-07p on the same problem: UZ at a = 0.30000000201,
    0.60000059822, 0.90000000024, periods 6.5865678882, 7.8539860387, 14.414615697."""
    d = folder(tmp_path, "rotor")
    res = run(d / "c.rotor", verbose=False, sv="rot")
    assert res.status == "ok"
    lab = [r for r in res.rows if r.lab]
    assert [r.ty for r in lab] == ["EP", "UZ", "UZ", "UZ"]
    tol = location_tolerance(d / "c.rotor")
    for r, a_want in zip(lab[1:], (0.3, 0.6, 0.9)):
        a = r.values[0]
        assert a == pytest.approx(a_want, abs=tol)
        assert r.values[-1] == pytest.approx(2 * math.pi / math.sqrt(1 - a * a), rel=1e-8)
        u = np.asarray(r.u)
        assert u[-1, 0] - u[0, 0] == pytest.approx(2 * math.pi, abs=1e-12)
        assert np.max(np.abs(u[:, 1] - (1 + a * np.sin(u[:, 0])))) < 1e-5


def test_general_bvp_starts_from_data(tmp_path):
    """dat='NAME' for IPS = 4 too (AUTO's STPNUB is the same for every BVP): AUTO's bvp
    demo from a data file of its trivial solution (u = 0 on t in [0, 1], 11 rows) finds
    the same points as from stpnt: the branch points p1 = 1, 2, ... of u1'' = -(p1 pi)^2
    u1 + u1^2 (exact: the eigenvalues of the linearisation)."""
    d = tmp_path
    copy_demo("bvp", d, DATA / "bvp" / "bvp")
    (d / "zero.dat").write_text("".join(f"{t:.3f} 0.0 0.0\n" for t in np.linspace(0, 1, 11)))
    plain = run(d / "c.bvp", verbose=False, e="bvp", sv="plain")
    data = run(d / "c.bvp", verbose=False, e="bvp", dat="zero", sv="data")
    assert plain.status == data.status == "ok"
    got = [(r.ty, round(r.values[0], 6)) for r in data.rows if r.lab]
    assert got == [(r.ty, round(r.values[0], 6)) for r in plain.rows if r.lab]
    bps = [v for t, v in got if t == "BP"]
    assert len(bps) >= 3
    for k, v in enumerate(bps, start=1):
        assert v == pytest.approx(k, abs=location_tolerance(d / "c.bvp"))


@pytest.mark.parametrize("ty, moving, period", [("HB3", 0, 2 * math.pi), ("HB4", 2, math.pi)])
def test_ty_restarts_a_uz_label_as_a_hopf_point_with_the_period_it_names(tmp_path, ty, moving,
                                                                          period):
    """AUTO's TY constant: the restart point is taken to be of the type TY names, and
    digits after it name the PAR holding the period (TY = 'HB5': PAR(11) = PAR(5), as
    AUTO's r3b demo starts its Lyapunov families). Two Hopf normal forms in one system,
    frequencies 1 and 2: at mu = 0 the equilibrium has both pairs +-i, +-2i on the axis.
    Restarted from the UZ at mu = 0 with IPS = 2 and ISW = -1 (AUTO's INITPS makes an HB
    start ISW = 1), TY = 'HB3' (PAR(3) = 2 pi) starts the family in (x1, y1), TY = 'HB4'
    (PAR(4) = pi) the one in (x2, y2): circles of radius sqrt(mu) with the period 2 pi /
    omega, exact; at the UZSTOP mu = 0.25 the moving pair's max over the mesh nodes is
    the radius 0.5 (collocation error of a circle at NTST = 20, NCOL = 4: below 1e-7)
    up to where the nodes fall on the circle: they are 1/80 of the period apart (a
    uniform mesh on a uniform motion), so the largest node value lies within
    r (1 - cos(pi / 80)) of r, whatever the orbit's phase (AUTO's Hopf start fixes it by
    NLVC); the other pair stays 0."""
    (tmp_path / "hh.py").write_text(
        "import math\nimport numpy as np\n"
        "def func(u, par):\n"
        "    mu = par[0]\n"
        "    r1 = u[0] ** 2 + u[1] ** 2\n    r2 = u[2] ** 2 + u[3] ** 2\n"
        "    return np.array([mu * u[0] - u[1] - u[0] * r1, u[0] + mu * u[1] - u[1] * r1,\n"
        "                     mu * u[2] - 2 * u[3] - u[2] * r2,\n"
        "                     2 * u[2] + mu * u[3] - u[3] * r2])\n"
        "def stpnt(u, par):\n"
        "    u[:] = 0.0\n    par[0] = -0.5\n    par[2] = 2 * math.pi\n    par[3] = math.pi\n")
    (tmp_path / "c.hh").write_text(
        "e = 'hh'\nNDIM = 4, IPS = 1, IRS = 0, ILP = 0, ISP = 0\nICP = [1]\nNMX = 40\n"
        "DS = 0.05, DSMIN = 0.001, DSMAX = 0.1\nUZR = {1: 0.0}\nUZSTOP = {1: 0.3}\n")
    (tmp_path / "c.hh.po").write_text(
        "e = 'hh'\nNDIM = 4, IPS = 2, IRS = 2, ILP = 0, ISP = 0, ISW = -1\n"
        "ICP = [1, 11]\nNTST = 20, NCOL = 4, NMX = 200\n"
        "DS = 0.01, DSMIN = 0.0001, DSMAX = 0.05\nUZSTOP = {1: 0.25}\n"
        f"TY = '{ty}'\n")
    res = run(tmp_path / "c.hh", verbose=False, sv="eq")
    assert [r.ty for r in res.rows if r.lab] == ["EP", "UZ", "UZ"]
    assert [r.lab for r in res.rows if r.ty == "UZ"][0] == 2
    res = run(tmp_path / "c.hh.po", verbose=False, sv="po", s="eq")
    assert res.status == "ok", res.status
    end = [r for r in res.rows if r.lab][-1]
    assert end.ty == "UZ" and end.values[0] == pytest.approx(0.25)
    maxima = end.values[2:6]                                  # MAX U(1..4)
    assert end.values[-1] == pytest.approx(period, rel=1e-9)
    assert 0.5 * math.cos(math.pi / 80) - 1e-7 <= maxima[moving] <= 0.5 + 1e-7
    other = 2 - moving
    assert abs(maxima[other]) < 1e-7 and abs(maxima[other + 1]) < 1e-7


def test_r3b_circle_of_equilibria_has_autos_three_branch_points(tmp_path, monkeypatch):
    """AUTO's r3b demo, first run (its constants and Fortran file unchanged): at mu = 0 the
    unit circle is a circle of equilibria, and the families of the Lagrange points leave
    it at the angles 60, -60 and 180 degrees: BPs at (x, y) = (1/2, sqrt 3/2),
    (1/2, -sqrt 3/2), (-1, 0), then the UZ y = 0.991, as AUTO's labels 2-5. The third lies
    where a location trial lands on the BP itself (Newton's matrix singular there): the
    trials are taken from the last converged one along its own tangent, as AUTO's LCSPAE
    steps (it was left unlabelled, so the script's UZ7 did not exist). Positions to the
    location tolerance EPSS (1 + sqrt|DS DSMAX|) = 1e-4 in arclength (the circle's
    arclength is the angle)."""
    from washer.auto import clui
    for f in ("r3b.f90", "c.r3b"):
        shutil.copy(DATA / "auto_demos" / "r3b" / f, tmp_path)
    monkeypatch.chdir(tmp_path)
    r1 = clui.run("r3b", UZR={"mu": 0.063})
    sols = [s for s in r1() if s["BR"] == 1]
    assert [(s["TY"], s["LAB"]) for s in sols] == [("EP", 1), ("BP", 2), ("BP", 3), ("BP", 4),
                                                   ("UZ", 5)]
    want = [(0.5, math.sqrt(3) / 2), (0.5, -math.sqrt(3) / 2), (-1.0, 0.0)]
    for s, (x, y) in zip(sols[1:4], want):
        u = np.asarray(s.rec.u, float)
        assert math.hypot(u[0] - x, u[1] - y) < 1e-4, (s["LAB"], u[:2])
