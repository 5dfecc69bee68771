"""The engine's shape: every registered system honours the contract, runs live
in memory without any sink, a run's result pickles and re-executes identically, and the
test switches follow AUTO's CHECKSP table (docs/auto.md section 1.3)."""
import ast
import pickle
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.cont import systems
from washer.auto.constants_file import Constants, read_constants
from washer.auto.files import read_s
from washer.cont.user_problem.user_files import load_python_problem
from washer.cont.runner import RunError, build, execute
from washer.cont.runner import run as run_in_memory
from washer.cont.settings import Settings
from washer.cont.system import SYSTEMS, ContinuedSystem
from washer.run import run

DATA = Path(__file__).parent / "data"
systems.load()          # every module of washer.cont.systems: the whole registry


@pytest.mark.parametrize("key", sorted(SYSTEMS, key=str))
def test_every_registered_system_has_the_whole_contract(key):
    cls = SYSTEMS[key]
    methods = [m for m in ContinuedSystem.__dict__ if callable(getattr(ContinuedSystem, m))
               and not m.startswith("_")]
    assert methods, "the Protocol lists its methods"
    for m in methods:
        assert callable(getattr(cls, m, None)), f"{cls.__name__} lacks {m}()"
    for attr in ("curve_type", "arclength"):
        assert hasattr(cls, attr), f"{cls.__name__} lacks {attr}"
    assert cls.arclength in ("sphere", "plane")


def _registered_ips(source: str) -> set:
    """The IPS values of a module's register(IPS, ...) calls (decorators and plain calls),
    read from its source."""
    found = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "register":
            found.add(ast.literal_eval(node.args[0]))
    return found


def test_a_run_imports_the_modules_of_its_ips():
    """systems.MODULES names, for each IPS, every module registering a system of that IPS
    (read from the modules' register calls), so that a run of one IPS imports those only;
    and every IPS of the registry is in it."""
    folder = Path(systems.__file__).parent
    for path in sorted(folder.glob("*.py")):
        for ips in _registered_ips(path.read_text()):
            assert path.stem in systems.MODULES.get(ips, ()), \
                f"{path.name} registers IPS={ips}: add it to MODULES[{ips}]"
    assert {ips for ips, _, _ in SYSTEMS} == set(systems.MODULES)


def _fd_jacobian(sysm, x, h=1e-4):
    """Central differences of the residual, column by column (dense)."""
    cols = []
    for j in range(len(x)):
        e = np.zeros(len(x))
        e[j] = h * (1 + abs(x[j]))
        cols.append((sysm.residual(x + e) - sysm.residual(x - e)) / (2 * e[j]))
    return np.column_stack(cols)


def _ab_system(tmp_path, **overrides):
    """The system a run of AUTO's ab demo starts with (after the equilibrium run's s-file
    is written), through the same start resolution as every run."""
    from washer.auto.files import read_s
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    if not (tmp_path / "s.eq").exists():
        run(tmp_path / "c.ab", verbose=False, sv="eq")
    c = read_constants(tmp_path / "c.ab")
    for k, v in overrides.items():
        c.set(k, v)
    problem = load_python_problem("ab", tmp_path, 2)
    records = read_s(tmp_path / "s.eq") if c["IRS"] not in (0, "0") else None
    r, _, _ = build(c, problem, records)
    return r.system, r.settings


@pytest.mark.parametrize("overrides", [
    {},                                                           # equilibria (FUNI)
    {"IRS": "LP1", "ICP": [1, 2], "ISW": 2},                      # fold curve (FNLP)
    {"IRS": "HB1", "ICP": [1, 2], "ISW": 2},                      # Hopf curve (FNHB)
    {"IRS": "HB1", "IPS": 2, "ICP": [1, 11], "NTST": 10},         # periodic orbits (FNPS)
], ids=["equilibrium", "fold", "hopf", "periodic"])
def test_systems_honour_the_contract_at_their_start(tmp_path, overrides):
    """What the iterator relies on, checked on each system as a run builds it: shapes
    (N equations, N + 1 unknowns), the Jacobian against central differences of the
    residual with steps 1e-4 (1 + |x_j|), to 1e-5 of max|J| (the loci's residuals hold
    f_u as central differences themselves, ab having JAC = 0, whose ~1e-9 noise the step
    divides to ~1e-5 at most; the truncation is ~1e-8 times the third derivatives;
    measured 3e-7 on the fold and Hopf curves, 6e-10 on the periodic orbits),
    border(t) @ a == inner(a, t), params(x) holding x's
    principal parameter, the
    test values a subset of the active tests, and update/remesh leaving a point that
    still solves the equations."""
    sysm, s = _ab_system(tmp_path, **overrides)
    x0, t0 = sysm.start()
    n = sysm.n_eq
    assert x0.shape == (n + 1,) and sysm.residual(x0).shape == (n,)
    J = sysm.jacobian(x0)
    Jd = J.toarray() if hasattr(J, "toarray") else np.asarray(J)
    assert Jd.shape == (n, n + 1)
    fd = _fd_jacobian(sysm, x0)
    assert np.abs(Jd - fd).max() <= 1e-5 * max(1.0, np.abs(Jd).max())
    rng = np.random.default_rng(3)
    a, t = rng.standard_normal(n + 1), rng.standard_normal(n + 1)
    assert sysm.border(t) @ a == pytest.approx(sysm.inner(a, t), rel=1e-12)
    assert sysm.params(x0)[s.ICP[0] - 1] == x0[-1]
    tangent = t0 if t0 is not None else t / np.sqrt(sysm.inner(t, t))
    st = sysm.stability(x0, J)
    tests = sysm.test_functions(x0, tangent, J, st, sysm.factor(J, sysm.border(tangent)),
                                sysm.active_tests())
    assert set(tests) <= set(sysm.active_tests())
    sysm.update(x0, tangent)
    moved = sysm.remesh(x0, tangent) if sysm.wants_remesh(3) else (x0, tangent)
    r0 = np.abs(sysm.residual(x0)).max()
    assert np.abs(sysm.residual(moved[0])).max() <= max(10 * r0, 1e-6)


def test_a_run_in_memory_needs_no_sink_pickles_and_repeats(tmp_path):
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    on_disk = run(tmp_path / "c.ab", verbose=False, sv="eq")
    c = read_constants(tmp_path / "c.ab")
    problem = load_python_problem("ab", tmp_path, 2)
    r, br, mode = build(c, problem)
    first = execute(r, br, mode, sinks=[])
    types = lambda b: [(s.ty, s.br, round(float(s.par[0]), 9)) for s in b.specials]
    assert types(first) == types(on_disk)
    again = pickle.loads(pickle.dumps(first))
    assert types(again) == types(first) and again("HB2").lab == first("HB2").lab
    # A second execution starts a fresh result (the system's state is re-initialised by
    # its start): the same labelled points, not twice as many rows.
    second = execute(r, br, mode, sinks=[])
    assert types(second) == types(first) and len(second.rows) == len(first.rows)
    assert sorted(set(p.name for p in tmp_path.iterdir())) == sorted(
        ["ab.py", "c.ab", "b.eq", "s.eq", "d.eq"] + [p.name for p in tmp_path.glob("__pycache__")])


@pytest.mark.parametrize("ips, isp, ilp, on", [
    # docs/auto.md 1.3: HB (and BT, GH, ZH, CP) iff IPS in {-1, 1, 11} and ISP not in {0, 3};
    # BP for IPS < 2: iff ISP != 0, else |ISP| >= 2 and != 4; PD/TR iff ISP in {2, 4} and
    # IPS in {2, 7, 12}; LP by ILP.
    (1, 2, 1, {"LP", "BP", "HB", "GH", "ZH", "BT"}),
    (1, 3, 0, {"BP"}),
    (0, 2, 1, {"LP", "BP"}),
    (1, 0, 1, {"LP"}),
    (2, 2, 1, {"LP", "BP", "PD", "TR"}),
    (2, 4, 0, {"PD", "TR"}),
    (2, 1, 1, {"LP"}),
    (2, -3, 0, {"BP"}),
])
def test_test_switches_follow_autos_checksp(ips, isp, ilp, on):
    c = Constants({"IPS": ips, "ISP": isp, "ILP": ilp, "NDIM": 3})
    s = Settings.from_constants(c)
    got = {n for n in ("LP", "BP", "HB", "GH", "ZH", "BT", "PD", "TR") if s.detects(n)}
    assert got == on


def test_sp_overrides_the_switches():
    c = Constants({"IPS": 1, "ISP": 2, "SP": ["LP0", "TR"], "NDIM": 3})
    s = Settings.from_constants(c)
    assert not s.detects("LP") and s.detects("TR") and s.detects("HB")


def test_a_chain_of_runs_restarts_from_branches_in_memory(tmp_path):
    """The Hopf curve of ab restarted from the equilibrium run's Branch, and from one of
    its Records, is the curve restarted from the s-file the file-writing run wrote: the
    same labelled points, PAR(1) and PAR(2) equal to the digit from the s-file in memory,
    and to 1e-6 relative from the Branch (its start is the exact point, the s-file's
    is rounded to 11 digits: located points move within the location tolerance,
    EPSS = 1e-5 in arclength). The in-memory runs write nothing."""
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    two_par = dict(IRS="HB1", ICP=[1, 2], ISW=2, NMX=200, UZSTOP={2: 20.0})
    eq_file = run(tmp_path / "c.ab", verbose=False, sv="eq")
    hb_file = run(tmp_path / "c.ab", verbose=False, s="eq", sv="hb", **two_par)
    written = sorted(p.name for p in tmp_path.iterdir())
    c = read_constants(tmp_path / "c.ab")
    problem = load_python_problem("ab", tmp_path, 2)
    eq = run_in_memory(c, problem)
    c2 = c.copy()
    for k, v in two_par.items():
        c2.set(k, v)
    from_branch = run_in_memory(c2, problem, restart=eq)
    c3 = c2.copy()
    c3.set("IRS", 0)
    from_record = run_in_memory(c3, problem, restart=eq("HB1"))
    from_sfile = run_in_memory(c2, problem, restart=read_s(tmp_path / "s.eq"))
    key = lambda b: [(s.ty, s.br, f"{s.par[0]:.10E}", f"{s.par[1]:.10E}") for s in b.specials]
    kind = lambda b: [(s.ty, s.br) for s in b.specials]
    pars = lambda b: np.array([s.par[:2] for s in b.specials])
    assert len(hb_file.specials) >= 2 and eq.status == hb_file.status == "ok"
    assert key(eq) == key(eq_file) and key(from_sfile) == key(hb_file)
    for other in (from_branch, from_record):
        assert kind(other) == kind(hb_file)
        np.testing.assert_allclose(pars(other), pars(hb_file), rtol=1e-6)
    assert sorted(p.name for p in tmp_path.iterdir()) == written
    # the engine reads no files: an s-file's path is read by washer.run or read_s
    with pytest.raises(RunError, match="read_s"):
        run_in_memory(c2, problem, restart=tmp_path / "s.eq")


def test_the_engine_counts_its_work_and_the_d_file_shows_it(tmp_path):
    """Every point evaluates the Jacobian at least once and every Newton iteration
    evaluates the residual and factorises the bordered matrix: the counters bound
    those from below, and the d-file's last block shows the run's totals."""
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    res = run(tmp_path / "c.ab", verbose=False, sv="eq")
    n = res.counters
    iterations = sum(1 for _ in res.rows)
    assert n.jacobians >= len(res.rows) and n.residuals >= iterations
    assert n.factorisations >= n.residuals
    d = (tmp_path / "d.eq").read_text()
    assert (f"Evaluations: residual {n.residuals}, Jacobian {n.jacobians}, factorisations "
            f"{n.factorisations}") in d
