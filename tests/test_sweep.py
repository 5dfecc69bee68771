"""washer.sweep: specs, points, serial == Dask, resume after a kill, failures, and the
sweep's stability boundary against the continuation's Hopf curve."""
from __future__ import annotations

import hashlib
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import washer
from washer.sweep import SpecError, load_spec, parse_spec, run
from washer.sweep.hopf import crossing_on_curve, hopf_curve
from washer.sweep.plots import boundary_crossings
from washer.sweep.points import make_points, sample
from washer.sweep.results import ResultStore

ROOT = Path(__file__).resolve().parents[1]
SMALL = ROOT / "examples" / "sweep_small.toml"
DESIGN = ROOT / "examples" / "sweep_design.toml"
#: Columns that legitimately differ between two runs of the same points.
TIMING = ["elapsed_s"]


def code_fingerprint() -> str:
    """sha256 of the washer package on disk (sources, compiled modules, data: what a
    process imports), file names included."""
    root = Path(washer.__file__).parent
    h = hashlib.sha256()
    for f in sorted(root.rglob("*")):
        if f.is_file() and "__pycache__" not in f.parts:
            h.update(f.relative_to(root).as_posix().encode() + b"\0" + f.read_bytes())
    return h.hexdigest()


#: The package as this process imported it (washer is imported with the test modules).
CODE_AT_IMPORT = code_fingerprint()


@pytest.fixture(scope="module")
def small_serial(tmp_path_factory):
    out = tmp_path_factory.mktemp("small_serial")
    return out, run(SMALL, serial=True, out=out, plot=False)


# ------------------------------------------------------------------ specs and points

def test_shipped_specs_parse_and_are_big_enough():
    small, design = load_spec(SMALL), load_spec(DESIGN)
    pts = make_points(small)
    assert len(pts) >= 12
    assert {k for p in pts for k in p["kinds"]} == {"stability", "critical", "response"}
    assert all(len(s.axes) == 2 for s in small.studies + design.studies)
    ids = [p["id"] for p in make_points(design)]
    assert len(ids) == len(set(ids))


@pytest.mark.parametrize("text, where, what", [
    ("[[study]]\nkinds = ['stability']\n[study.vary]\nOmegga = [1.0, 2.0]\n", ":4", "Omegga"),
    ("[[study]]\nkinds = ['stability', 'swirl']\n[study.vary]\nOmega = [1.0]\n", ":2", "kinds"),
    ("[[study]]\nkinds = ['critical']\n[study.vary]\nC_p = [0.1, 0.2]\n", ":", "also swept"),
    ("[[study]]\nkinds = ['response']\n[study.vary]\nm_u = [1.0]\n[study.response]\n"
     "t_end = 5.0\nwindow = 10.0\n", ":7", "window"),
    ("[[study]]\nkinds = ['stability']\nsample = 'lhs'\nn = 5\n[study.vary]\nm_u = [1.0]\n", ":6",
     "explicit values"),
    ("[[study]]\nkinds = ['critical']\n[study.vary]\nm_u = [1.0]\n[study.critical]\n"
     "engine = 'exact'\n", ":6", "engine"),
])
def test_spec_errors_name_file_line_and_cause(text, where, what):
    with pytest.raises(SpecError) as err:
        parse_spec(text, "bad.toml")
    msg = str(err.value)
    assert msg.startswith("bad.toml" + where), msg
    assert what in msg


def test_critical_uses_the_spec_base_parameters(tmp_path):
    """The continuation gets the point's whole parameter set (run(..., params=)), not
    the reference set: with a heavier tub inertia (not a PAR entry) and untied joint
    dampings, the critical C_p must equal the root of the stability margin of that
    set (Brent on Model.eigenvalues, an independent route; both locate the same
    crossing, the engine to ~1e-8 relative: tolerance 1e-6) and differ from the
    reference set's."""
    from scipy.optimize import brentq

    import washer
    from washer.machine.params import default_params_path
    from washer.sweep.tasks import stability
    ref = default_params_path().read_text()
    assert "J = [0.9, 0.9, 0.9]" in ref and "\nC_p = 0.101" in ref
    (tmp_path / "heavy.toml").write_text(
        ref.replace("J = [0.9, 0.9, 0.9]", "J = [1.3, 1.3, 0.9]")
           .replace("\nC_p = 0.101", "\nC_p = 0.101\nC_ox = 0.05\nC_oz = 0.2"))
    (tmp_path / "s.toml").write_text("params = 'heavy.toml'\n[[study]]\nkinds = ['critical']\n"
                                     "[study.vary]\nm_u = [1.5, 2.0]\n")
    spec = load_spec(tmp_path / "s.toml")
    assert not spec.base.tied and spec.base["J_tx"] == 1.3
    df = run(spec, serial=True, out=tmp_path / "out", plot=False)
    assert (df["status"] == "ok").all() and (df["crit_source"] == "HB").all()
    for _, r in df.iterrows():
        p = spec.base.replace(m_u=r["m_u"])
        root = brentq(lambda c: stability(p.replace(C_p=c))["stab_margin"], 0.0, 3.0, xtol=1e-12)
        assert r["crit_value"] == pytest.approx(root, rel=1e-6)
        p_ref = washer.load_params().replace(m_u=r["m_u"])
        root_ref = brentq(lambda c: stability(p_ref.replace(C_p=c))["stab_margin"], 0.0, 3.0)
        assert abs(root - root_ref) > 1e-3 * root_ref


def test_random_and_lhs_samples_are_seeded_and_in_range():
    text = ("[[study]]\nkinds = ['stability']\nsample = '{s}'\nn = 40\nseed = 3\n[study.vary]\n"
            "Omega = {{from = 5.0, to = 15.0}}\nK_s = {{from = 500.0, to = 4500.0, log = true}}\n")
    for s in ("random", "lhs"):
        st = parse_spec(text.format(s=s)).studies[0]
        X = sample(st)
        assert X.shape == (40, 2)
        assert np.array_equal(X, sample(st))                  # same seed, same points
        assert (X[:, 0] >= 5).all() and (X[:, 0] <= 15).all()
        assert (X[:, 1] >= 500).all() and (X[:, 1] <= 4500).all()
    lhs = sample(parse_spec(text.format(s="lhs")).studies[0])
    # Latin hypercube: exactly one point in each of the 40 equal strata of each axis.
    strata = np.floor((lhs[:, 0] - 5) / 10 * 40).astype(int)
    assert sorted(strata) == list(range(40))


def test_point_ids_depend_on_inputs_only():
    a = [p["id"] for p in make_points(load_spec(SMALL))]
    text = SMALL.read_text()
    assert a == [p["id"] for p in make_points(parse_spec(text + "\n# a comment\n"))]
    changed = [p["id"] for p in make_points(parse_spec(text.replace("t_end = 20.0", "t_end = 21.0")))]
    assert not set(a) & set(changed)


# ------------------------------------------------------------------ execution

def test_small_sweep_serial_results(small_serial):
    out, df = small_serial
    pts = make_points(load_spec(SMALL))
    assert list(df["id"]) == [p["id"] for p in pts]
    ok = df[df["status"] == "ok"]
    # Stable equilibrium exactly where the critical C_p lies below the C_p of the map.
    both = ok.dropna(subset=["crit_value"])
    assert len(both) >= 12
    assert ((both["stab_margin"] < 0) == (both["crit_value"] < both["C_p"])).all()
    # The spin-up's ground-frame whirl: the leading peak is the synchronous one
    # (Omega) where the equilibrium is stable, and where the whirl stays small
    # (margin < 0.2 1/s: decaying, or a limit cycle close to the linear mode) the
    # spectrum has the rotating-frame mode seen from the ground,
    # |2 pi Omega - whirl| / 2 pi, to the FFT's resolution 1/window = 0.2 Hz.
    # (Farther out the limit cycle's frequency moves away from the linear one.)
    stable = ok[ok["stab_margin"] < -0.02]
    assert len(stable) >= 3
    assert np.allclose(stable["resp_freq1"], stable["Omega"], atol=0.2)
    near_linear = ok[ok["stab_margin"] < 0.2]
    assert len(near_linear) >= 8
    f_mode = near_linear["stab_whirl_ground"] / (2 * np.pi)
    off = np.minimum(abs(near_linear["resp_freq1"] - f_mode), abs(near_linear["resp_freq2"] - f_mode))
    assert (off <= 0.2).all(), off


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
@pytest.mark.slow
def test_dask_results_identical_to_serial(small_serial, tmp_path):
    """Bit for bit: a row is a function of its point's inputs alone, with no randomness
    and no state carried between points (measured bit-identical with 1 or 2 BLAS
    threads, in forward, reversed and interleaved point order, in batches of 1 to 4).
    The serial rows come from the modules this process imported when the tests were
    collected, the workers import washer from disk when the cluster starts: if the
    package's files changed in between (merges into the checkout under a running suite),
    the two tables are two versions of the code, whose HB locations differ in their
    last bits with any change of the engine's step history; the test then says that
    instead of comparing them."""
    out, serial = small_serial
    dask = run(SMALL, out=tmp_path, n_workers=2, plot=False)
    if code_fingerprint() != CODE_AT_IMPORT:
        pytest.fail(f"washer's files under {Path(washer.__file__).parent} changed while the "
                    "tests ran: the Dask workers imported other code than the serial rows "
                    "were computed with; run the suite on a checkout nobody updates meanwhile")
    a = serial.drop(columns=TIMING)
    b = dask.drop(columns=TIMING)
    pd.testing.assert_frame_equal(a, b, check_exact=True)


def _ids_in_parts(folder: Path) -> list[str]:
    return [i for f in ResultStore(folder).part_files() for i in pd.read_parquet(f)["id"]]


@pytest.mark.slow
def test_killed_sweep_resumes_with_every_point_once(tmp_path):
    out = tmp_path / "killed"
    cmd = [sys.executable, "-m", "washer.sweep", str(SMALL), "--out", str(out), "--workers", "2",
           "--batch-size", "1", "--no-plot", "--no-progress"]
    proc = subprocess.Popen(cmd, cwd=ROOT, start_new_session=True, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120
        while not ResultStore(out).part_files():
            assert proc.poll() is None, "the sweep ended before writing a part"
            assert time.monotonic() < deadline, "no part file within 120 s"
            time.sleep(0.02)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)      # the sweep and its Dask workers
        proc.wait()
    before = {f: f.stat().st_mtime_ns for f in ResultStore(out).part_files()}
    n_total = len(make_points(load_spec(SMALL)))
    assert 0 < len(before) < n_total, "the kill came too late to test a resume"
    assert not (out / "results.parquet").exists()

    df = run(SMALL, serial=True, out=out, plot=False)
    ids = _ids_in_parts(out)
    assert len(ids) == len(set(ids)) == n_total                 # each point computed once
    assert all(f.stat().st_mtime_ns == t for f, t in before.items())   # nothing redone
    assert list(df["id"]) == [p["id"] for p in make_points(load_spec(SMALL))]
    # And a third run has nothing left to do.
    run(SMALL, serial=True, out=out, plot=False)
    assert len(_ids_in_parts(out)) == n_total


def test_failing_point_is_recorded_and_the_rest_complete(tmp_path):
    spec = parse_spec("""
[[study]]
name = "bad"
kinds = ["stability", "response"]
[study.vary]
m_u = [-1.0, 0.5, 1.0]
K_s = [1800.0, 2400.0]
[study.response]
t_end = 2.0
window = 1.0
""", "inline.toml")
    df = run(spec, serial=True, out=tmp_path, plot=False)
    assert len(df) == 6
    bad = df[df["m_u"] < 0]
    assert (bad["status"] == "failed").all()
    assert bad["error"].str.contains("m_u = -1.0: expected a value >= 0").all()
    assert bad["stab_margin"].isna().all()
    good = df[df["m_u"] >= 0]
    assert (good["status"] == "ok").all() and (good["error"] == "").all()
    assert good["stab_margin"].notna().all() and good["resp_whirl_radius"].notna().all()


def test_spinup_settles_on_the_averaged_equilibrium_where_stable(tmp_path):
    """Two independent routes to the steady whirl: the ground-frame spin-up (eq 48,
    60 s, kernel DOPRI5) and the averaged rotating-frame equilibrium (Newton). Where
    the margin is below -0.2 1/s the transient has decayed by e^-10 by the window
    (50-60 s), and the averaged and exact systems differ by ~1e-4 relative
    (docs/model.md section 4): radii must agree to 1e-3 relative (measured ~3e-7)."""
    spec = parse_spec("""
[[study]]
kinds = ["stability", "response"]
[study.vary]
C_p = [0.3, 0.4]
m_u = [0.5, 0.8, 1.0]
[study.response]
t_end = 60.0
window = 10.0
""", "settle.toml")
    df = run(spec, serial=True, out=tmp_path, plot=False)
    assert (df["status"] == "ok").all() and (df["stab_margin"] < -0.2).all()
    rel = abs(df["resp_whirl_radius"] - df["stab_radius"]) / df["stab_radius"]
    assert (rel < 1e-3).all(), rel.tolist()
    spread = (df["resp_whirl_radius_max"] - df["resp_whirl_radius_min"]) / df["stab_radius"]
    assert (spread < 1e-2).all(), spread.tolist()          # a circle: the whirl is steady
    assert np.allclose(df["resp_freq1"], 10.0, atol=0.1)     # synchronous with Omega (Hz)


# ------------------------------------------------------------------ against the continuation

def test_stability_boundary_matches_continuation_hopf_curve(tmp_path):
    """Grid over (C_p, m_u) at the reference point: along each m_u row the margin
    changes sign between two grid C_p values; the continuation's Hopf curve must
    cross that row inside the same cell (the margin's sign at grid nodes is exact,
    so the bracket is the grid spacing, 0.02 N m s/rad)."""
    cps = [round(0.02 * i, 2) for i in range(21)]               # 0 .. 0.4
    spec = parse_spec(f"""
[[study]]
name = "cp_mu"
kinds = ["stability"]
[study.vary]
C_p = {cps}
m_u = {{from = 0.4, to = 2.0, n = 9}}
[[study]]
name = "crit_mu"
kinds = ["critical"]
[study.vary]
m_u = [0.6, 1.0, 1.4, 1.8]
""", "boundary.toml")
    df = run(spec, serial=True, out=tmp_path, plot=False)
    assert (df["status"] == "ok").all(), df.loc[df["status"] != "ok", "error"].tolist()
    grid = df[df["study"] == "cp_mu"]
    cells = boundary_crossings(grid, "C_p", "m_u")
    curve = hopf_curve(spec.base, "C_p", (0.0, 0.4), "m_u", (0.4, 2.0), tmp_path / "hopf")
    assert len(cells) >= 7                                      # the boundary crosses the map
    for _, c in cells.iterrows():
        xs = crossing_on_curve(curve, c["m_u"])
        assert len(xs) == 1, (c["m_u"], xs)
        assert c["x_lo"] - 1e-9 <= xs[0] <= c["x_hi"] + 1e-9, (c.to_dict(), xs)
        assert abs(xs[0] - c["x"]) <= 0.02                       # interpolated: within a cell
    # The critical kind is the same engine's HB: on the curve up to the curve's
    # piecewise-linear interpolation (steps of 1/60 of the map; measured <= 2e-4).
    crit = df[df["study"] == "crit_mu"]
    for _, r in crit.iterrows():
        xs = crossing_on_curve(curve, r["m_u"])
        assert len(xs) == 1 and abs(xs[0] - r["crit_value"]) <= 1e-3, (r["m_u"], xs, r["crit_value"])


def test_critical_floquet_engine_is_the_forced_response_tr_point(params):
    """engine = 'floquet': the exact critical C_p is where the forced response changes
    stability, checked without any location: the periodic response (Newton on the
    period map, multipliers of its monodromy matrix) is unstable 1e-5 (relative) below
    the value and stable 1e-5 above (|mu| - 1 moves by ~1e-7 there, 100 times the
    multipliers' accuracy). The averaged value is where the averaged equilibrium's
    leading eigenvalue crosses the imaginary axis (Model.eigenvalues 1e-4 either side:
    the HB is located to EPSS = 1e-5 in arclength), and the two differ by the averaging
    error (1.2e-5 at nominal values: asserted below 1e-3 relative)."""
    from washer.machine.model import Model
    from washer.problems.forced import periodic_response
    from washer.sweep.tasks import critical
    got = critical(params, "C_p", 0.0, 3.0, "floquet")
    assert got["crit_source"] == "floquet"
    cp, ca = got["crit_value"], got["crit_averaged"]
    assert not periodic_response(params.replace(C_p=cp * (1 - 1e-5))).stable
    assert periodic_response(params.replace(C_p=cp * (1 + 1e-5))).stable

    def leading(c):
        m = Model(params.replace(C_p=c))
        return m.eigenvalues(m.rotating_equilibrium(frame="averaged"), frame="averaged")[0].real
    assert leading(ca * (1 - 1e-4)) > 0 > leading(ca * (1 + 1e-4))
    assert 0 < abs(cp - ca) < 1e-3 * cp


# ------------------------------------------------------------------ result semantics

def test_stable_without_joint_damping_is_an_answer(params):
    """At Omega = 6 Hz, m_u = 0.25 kg the equilibrium is stable at C_p = 0 (every
    eigenvalue in the left half plane: checked here directly) and the continuation finds
    no Hopf point up to C_p = 3: the critical C_p is 0, status 'stable', not a failure."""
    from washer.machine.model import Model
    from washer.sweep.tasks import compute_point, critical
    p = params.replace(Omega=6.0, m_u=0.25)
    m = Model(p.replace(C_p=0.0))
    assert m.eigenvalues(m.rotating_equilibrium()).real.max() < 0
    got = critical(p, "C_p", 0.0, 3.0)
    assert got["crit_status"] == "stable" and got["crit_value"] == 0.0
    assert got["crit_n_hopf"] == 0.0
    point = {"id": "x", "study": "s", "index": 0, "inputs": {}, "kinds": ["critical"],
             "set": {"Omega": 6.0, "m_u": 0.25},
             "options": {"critical": {"parameter": "C_p", "from": 0.0, "to": 3.0,
                                      "engine": "continuation"}}}
    base = {"values": dict(params.values), "tied": params.tied, "source": params.source}
    row = compute_point(point, base)
    assert row["status"] == "ok" and row["error"] == "" and row["crit_status"] == "stable"
    # Without an imbalance the whirl pair is undamped at C_p = 0 (neutral to round-off)
    # and stable for any joint damping: critical C_p = 0 too.
    free = critical(params.replace(m_u=0.0), "C_p", 0.0, 3.0)
    assert free["crit_status"] == "stable" and free["crit_value"] == 0.0


def test_unstable_over_the_range_is_an_answer(params):
    """Searching C_p only in [0, 0.05] at the nominal point (critical 0.101): unstable
    throughout, crit_value NaN, status 'unstable'."""
    from washer.sweep.tasks import critical
    got = critical(params, "C_p", 0.0, 0.05)
    assert got["crit_status"] == "unstable" and np.isnan(got["crit_value"])


def test_crossing_on_the_engines_first_steps_is_located_by_the_engine_over_them(params):
    """At Omega = 9 Hz, m_u = 0.25 kg the crossing (C_p ~ 1.5e-4) lies on the engine's
    first two steps over [0, 3] (its first written point is C_p = 0.03), where it tests no
    sign change: the engine run again over [0, 0.03] locates it. Independent check: the
    root of the stability margin max Re(lambda) (Brent on the rotating-frame eigenvalues),
    equal to the HB location's accuracy (~1e-8 relative of the range: 1e-9 here), and the
    crossing pair's frequency there."""
    from scipy.optimize import brentq
    from washer.machine.model import Model
    from washer.sweep.tasks import critical, stability
    p = params.replace(Omega=9.0, m_u=0.25)
    got = critical(p, "C_p", 0.0, 3.0)
    assert got["crit_source"] == "first steps" and got["crit_status"] == "hopf"
    assert got["crit_n_hopf"] == 1.0
    root = brentq(lambda c: stability(p.replace(C_p=c))["stab_margin"], 0.0, 0.01,
                  xtol=1e-15)
    assert got["crit_value"] == pytest.approx(root, abs=1e-9)
    m = Model(p.replace(C_p=root))
    lam = m.eigenvalues(m.rotating_equilibrium())
    assert got["crit_whirl"] == pytest.approx(abs(lam[np.argmax(lam.real)].imag), rel=1e-6)


def test_units_are_in_the_parquet_schema(small_serial):
    """Every output and input column with a unit carries it as field metadata."""
    import pyarrow.parquet as pq
    out, _ = small_serial
    schema = pq.read_schema(out / "results.parquet")
    unit = {f.name: (f.metadata or {}).get(b"unit", b"").decode() for f in schema}
    assert unit["stab_margin"] == "1/s" and unit["crit_value"] == "N m s/rad"
    assert unit["Omega"] == "Hz" and unit["m_u"] == "kg" and unit["resp_whirl_radius"] == "m"
    assert unit["resp_tau_s"] == "s"


def test_small_example_has_no_failed_points(small_serial):
    """The shipped small example: every point answers (the corner stable without joint
    damping included), so `python -m washer.sweep` exits 0 on it."""
    _, df = small_serial
    assert (df["status"] == "ok").all(), df.loc[df["status"] != "ok", "error"].tolist()
    assert (df["crit_status"] == "stable").any()
    stable = df[df["crit_status"] == "stable"]
    assert (stable["crit_value"] == 0.0).all() and (stable["stab_margin"] < 0).all()


def test_clearance_based_critical_value(params):
    """With a clearance the critical kind adds the damping at which the whirl reaches it:
    below the critical value by ((clearance - r0) / a)^2 (normal form), NaN when the forced
    response's own offset r0 already exceeds the clearance; r0 is the averaged
    equilibrium's offset (checked against the stability kind's radius)."""
    from washer.machine.model import Model
    from washer.sweep.tasks import critical_with_clearance, stability
    got = critical_with_clearance(params, "C_p", 0.0, 3.0, "continuation", 0.03)
    a = got["crit_whirl_growth"]
    r0 = stability(params.replace(C_p=got["crit_value"]))["stab_radius"]
    assert got["crit_clearance_value"] == pytest.approx(
        got["crit_value"] - ((0.03 - r0) / a) ** 2, rel=1e-12)
    assert 0 < got["crit_value"] - got["crit_clearance_value"] < 0.01 * got["crit_value"]
    small = critical_with_clearance(params, "C_p", 0.0, 3.0, "continuation", 0.5 * r0)
    assert np.isnan(small["crit_clearance_value"])
    # Just above the clearance value the linearised whirl is small; at it, the whirl's
    # amplitude a sqrt(crit - value) plus r0 is the clearance by construction: the check
    # of a against the exact invariant circles is tests/test_torus.py's slow test.
    assert not np.isfinite(critical_with_clearance(params, "C_p", 0.0, 3.0,
                                                   "continuation")["crit_clearance_value"])
