"""Python user files' func traced into compiled C (washer.cont.user_problem.tracer,
washer.cont.user_problem.user_files_traced): the compiled function equals the Python one bit for
bit,
and what cannot be traced or does not agree stays Python, saying why."""
import importlib.util
from pathlib import Path

import numpy as np
import pytest

from washer.cont.pointwise import same_bits
from washer.cont.problem import Problem
from washer.cont.user_problem.tracer import TraceError, numpy_loop, trace_function
from washer.cont.user_problem.user_files_traced import TracedProblem, traced_problem
from washer.cont.user_problem.user_files import load_user_problem
from demo_files import copy_demo

DATA = Path(__file__).parent / "data"
#: Every Python user file shipped with the tests (func(u, par) defined), with its NDIM
#: from its constants files (or the size stpnt fills).
FILES = sorted(p for p in DATA.rglob("*.py") if "def func" in p.read_text())


def _ndim(path: Path) -> int:
    # a transcription of an AUTO demo's equations reads the demo's constants files
    beside = sorted(path.parent.glob("c.*"))
    for c in beside or sorted((DATA / "auto_demos" / path.stem).glob("c.*")):
        for line in c.read_text().splitlines():
            words = line.replace(",", " ").replace("=", " ").split()
            if "NDIM" in words:
                return int(words[words.index("NDIM") + 1])
            if words and words[0].isdigit() and len(words) >= 4 and "NDIM" in line:
                return int(words[0])
    return {"ab": 2, "plp": 2, "chu": 3, "frc": 4}.get(path.stem, 2)


def _module(path: Path):
    spec = importlib.util.spec_from_file_location(f"traced_test_{path.stem}", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(DATA)))
def test_traced_func_is_the_python_func_bit_for_bit(path):
    """At 300 random points around the file's start (offsets up to 10 times its size),
    the compiled trace's f (and dfdu, dfdp where traced) are the Python functions'
    bytes; files that do not trace are the Python problem, with the reason."""
    try:
        ndim = _ndim(path)
        problem = load_user_problem(path.stem, path.parent, ndim)
    except Exception as exc:           # a file whose NDIM this test does not guess
        pytest.skip(f"not loaded with NDIM guessed: {exc}")
    if not isinstance(problem, TracedProblem):
        assert problem.route.startswith("func(u, par) in Python: ")
        return
    py = problem.python
    rng = np.random.default_rng(7)
    u0, p0 = py.start(40) if py._stpnt is not None else (np.zeros(ndim), np.zeros(40))
    for scale in (1e-6, 1e-2, 1.0, 10.0):
        us = u0 + scale * (1 + np.abs(u0)) * rng.standard_normal((75, ndim))
        ps = p0 + scale * (1 + np.abs(p0)) * rng.standard_normal((75, len(p0)))
        got = problem.user.func_batch(us, ps)
        for j in range(len(us)):
            with np.errstate(all="ignore"):
                ref = np.asarray(py._func(us[j].copy(), ps[j].copy()), dtype=float)
            assert ref.tobytes() == got[j].tobytes(), (path, us[j], ps[j])
        if problem._dfdu is not None:
            J = problem.user.dfdu_batch(us, ps)
            for j in range(len(us)):
                with np.errstate(all="ignore"):
                    ref = np.asarray(py._dfdu(us[j].copy(), ps[j].copy()), dtype=float)
                assert ref.tobytes() == J[j].tobytes()


def test_shipped_demos_trace():
    """ab, lrz and chu (np.exp, np.arctan through numpy's own loops) are traced."""
    for name, n in (("ab", 2), ("lrz", 3), ("chu", 3)):
        assert isinstance(load_user_problem(name, DATA / name, n), TracedProblem), name


def _problem(func, ndim=2, **kw):
    return Problem(ndim, func, name="t", **kw)


def test_branch_on_a_value_falls_back_and_says_so(tmp_path):
    def func(u, par):
        if u[0] > 0:
            return np.array([u[0], u[1]])
        return np.array([-u[0], u[1]])
    p = traced_problem(_problem(func), tmp_path / "t.py")
    assert type(p) is Problem
    assert "in Python" in p.route and "comparison" in p.route


def test_unknown_function_falls_back_and_says_so(tmp_path):
    import math

    def func(u, par):
        return np.array([math.exp(u[0]), u[1] * par[0]])
    p = traced_problem(_problem(func), tmp_path / "t.py")
    assert type(p) is Problem
    assert "in Python" in p.route and "float()" in p.route


def test_write_into_a_float_array_falls_back(tmp_path):
    def func(u, par):
        f = np.zeros(2)
        f[0] = u[1]
        f[1] = -u[0]
        return f
    p = traced_problem(_problem(func), tmp_path / "t.py")
    assert type(p) is Problem and "in Python" in p.route


def test_traced_operations(tmp_path):
    """numpy ufuncs of one and two arguments (np.power among them), constants of every
    sign, abs and negation, an object array's elementwise product: the same bits at 2000
    points each."""
    def func(u, par):
        x, y = u
        a = par[0]
        v = np.array([x, y]) * 3
        return np.array([x * x - 1.5e-300 * np.power(y, 3.5) + abs(-x) / (2 + a) + v[0],
                         np.exp(-y) * np.sin(x) + np.arctan2(y, a) + np.hypot(x, 2.0)
                         + np.sqrt(abs(y)) - (-0.0) * np.tanh(x) + np.power(2, x) + v[1]])
    py = _problem(func)
    p = traced_problem(py, tmp_path / "t.py")
    assert isinstance(p, TracedProblem), getattr(p, "route", "")
    rng = np.random.default_rng(3)
    us = rng.uniform(-30, 30, (2000, 2))
    ps = rng.uniform(-5, 5, (2000, 3))
    got = p.user.func_batch(us, ps)
    with np.errstate(all="ignore"):
        ref = np.array([func(u.copy(), q.copy()) for u, q in zip(us, ps)], dtype=float)
    assert ref.tobytes() == got.tobytes()


def test_numpy_loop_is_numpy(tmp_path):
    """The loop the C calls for np.exp is numpy's: through ctypes, at 10^5 arguments
    where numpy's exp and glibc's differ in some (the reason it is called)."""
    import ctypes
    fn, data = numpy_loop(np.exp)
    proto = ctypes.CFUNCTYPE(None, ctypes.POINTER(ctypes.c_char_p),
                             ctypes.POINTER(ctypes.c_ssize_t),
                             ctypes.POINTER(ctypes.c_ssize_t), ctypes.c_void_p)
    loop = proto(fn)
    x = np.random.default_rng(1).uniform(-700, 700, 100_000)
    out = np.empty_like(x)
    args = (ctypes.c_char_p * 2)(ctypes.cast(x.ctypes.data, ctypes.c_char_p),
                                 ctypes.cast(out.ctypes.data, ctypes.c_char_p))
    n = ctypes.c_ssize_t(len(x))
    steps = (ctypes.c_ssize_t * 2)(8, 8)
    loop(args, ctypes.byref(n), steps, data)
    assert out.tobytes() == np.exp(x).tobytes()
    with pytest.raises(TraceError):
        numpy_loop(np.isnan)            # no loop from doubles to doubles


#: Every class of power numpy distinguishes (washer.cont.user_problem.tracer): the operator with a
#: Python int -1, 2 (ufuncs on arrays), a Python float 0.5, other ints and floats, the
#: loop's own fast values (0, 1, -1.0, 2.0) and np.float64 exponents, a constant base,
#: a computed exponent, PAR(i) itself as the exponent (its stride on arrays), np.power.
POWERS = [
    lambda x, y, q: x ** 2, lambda x, y, q: x ** -1, lambda x, y, q: abs(x) ** 0.5,
    lambda x, y, q: x ** 3, lambda x, y, q: x ** -2, lambda x, y, q: abs(x) ** 2.5,
    lambda x, y, q: x ** 2.0, lambda x, y, q: x ** -1.0, lambda x, y, q: x ** 0,
    lambda x, y, q: x ** 1, lambda x, y, q: x ** np.float64(2), lambda x, y, q: x ** 0.0,
    lambda x, y, q: abs(x) ** y, lambda x, y, q: 2 ** x, lambda x, y, q: 1.5 ** y,
    lambda x, y, q: abs(x) ** q, lambda x, y, q: abs(x) ** +q, lambda x, y, q: q ** x,
    lambda x, y, q: abs(x) ** (y * 1.0), lambda x, y, q: np.power(x, 2),
    lambda x, y, q: np.power(x, 2.0), lambda x, y, q: np.power(x, 3),
    lambda x, y, q: np.power(abs(x), y), lambda x, y, q: np.power(abs(x), q),
    lambda x, y, q: np.power(2.0, x), lambda x, y, q: (x * y) ** 2 - x ** 2 * y ** 2,
]
#: exponents drawn for u[1] and PAR(1): numpy's special values and ordinary ones
SPECIAL = np.array([-1.0, 0.0, 0.5, 1.0, 2.0, 3.0, 2.5, -0.5, -2.0])


def _powers(u, par):
    x, y, q = u[0], u[1], par[0]
    return np.array([f(x, y, q) for f in POWERS])


def test_every_class_of_power_is_numpys_bit_for_bit_in_each_mode(tmp_path):
    """x ** y and np.power(x, y) in every class (POWERS) at 4000 random points: the
    compiled FUNC in mode SCALARS is the Python func called with one point (numpy
    scalars: libm's pow), in mode ARRAYS the func called once on (NDIM, k) arrays with
    par's rows strided, in mode ARRAYS_PAR_BROADCAST with par one broadcast vector
    (numpy's fast paths where the exponent's stride is zero, its SIMD pow elsewhere),
    for each of the special exponents as that vector's PAR(1). Exact: the C computes
    the same operations or calls numpy's own loop. And the modes do differ (x ** 2 is
    not pow(x, 2) at some x): the test can fail."""
    from washer.cont.problem import broadcast_rows
    from washer.cont.user_problem.user_files_traced import ARRAYS, ARRAYS_PAR_BROADCAST, SCALARS
    n = len(POWERS)
    p = traced_problem(_problem(_powers, ndim=n), tmp_path / "t.py")
    assert isinstance(p, TracedProblem) and p.two_ways, getattr(p, "route", "")
    rng = np.random.default_rng(11)
    k = 4000
    us = np.zeros((k, n))
    us[:, 0] = rng.uniform(-4, 4, k) * 10.0 ** rng.integers(-3, 4, k)
    us[:, 1] = np.where(rng.random(k) < 0.5, rng.choice(SPECIAL, k), rng.uniform(-3, 3, k))
    ps = rng.uniform(-3, 3, (k, 3))
    ps[:, 0] = np.where(rng.random(k) < 0.5, rng.choice(SPECIAL, k), ps[:, 0])
    fn = p.python.user_func
    with np.errstate(all="ignore"):
        scalars = np.array([fn(u.copy(), q.copy()) for u, q in zip(us, ps)])
        assert same_bits(p.user.func_in_mode(us, ps, SCALARS), scalars)
        arrays = np.ascontiguousarray(fn(us.T, ps.T).T)
        assert same_bits(p.user.func_in_mode(us, ps, ARRAYS), arrays)
        for q in SPECIAL:
            par = np.array([q, 0.3, 0.7])
            rows = broadcast_rows(par, k)
            ref = np.ascontiguousarray(fn(us.T, rows.T).T)
            got = p.user.func_in_mode(us, np.ascontiguousarray(rows), ARRAYS_PAR_BROADCAST)
            assert same_bits(got, ref), q
            if q == 2.0:
                # PAR(1) = 2 per point (a copy, strided rows): numpy's SIMD pow, not the
                # square its broadcast vector gets
                strided = p.user.func_in_mode(us, np.array(rows), ARRAYS)
                assert same_bits(strided, np.ascontiguousarray(fn(us.T, np.array(rows).T).T))
                assert not same_bits(strided[:, 15], got[:, 15])
    assert not same_bits(scalars[:, 0], arrays[:, 0])        # x ** 2: pow or x * x


def test_a_power_file_is_called_as_the_python_problem_calls_it(tmp_path):
    """func_many of a traced file with x ** 2 makes Problem.func_many's choices: one
    point, small stencils (arrays while the bitwise comparison with separate calls
    holds), batches (arrays), par given once or per point; over a sequence of calls
    the traced problem and the Python one return the same bits, and keep the same
    state (vectorised, pointwise refused or not)."""
    def func(u, par):
        x, y = u
        return np.array([x ** 2 - par[0] * y ** 3, x * y ** 2 + abs(x) ** par[1]])
    py = _problem(func)
    traced = traced_problem(_problem(func), tmp_path / "t.py")
    assert isinstance(traced, TracedProblem) and traced.two_ways
    rng = np.random.default_rng(5)
    with np.errstate(all="ignore"):
        for call in range(400):
            k = int(rng.choice([1, 2, 6, 8, 11, 12, 40]))
            us = rng.uniform(-3, 3, (k, 2))
            pars = rng.uniform(0.1, 3, 3) if call % 2 else rng.uniform(0.1, 3, (k, 3))
            if call % 5 == 0 and pars.ndim == 1:
                pars[1] = 2.0                     # numpy's fast path on broadcast rows
            assert same_bits(traced.func_many(us, pars), py.func_many(us, pars)), call
    assert traced._pointwise.off == py._pointwise.off
    assert traced._vectorised == py._vectorised
    assert not traced.state.off


def test_a_func_not_for_arrays_is_called_point_by_point(tmp_path):
    """A traced power file whose func fails on arrays (a constant entry beside an
    array) is compiled, and its batches are separate calls' values (numpy scalars), as
    the Python problem computes them."""
    def func(u, par):
        return np.array([u[0] ** 2, 1.0])
    p = traced_problem(_problem(func), tmp_path / "t.py")
    assert isinstance(p, TracedProblem) and not p.arrays
    us = np.random.default_rng(3).uniform(-3, 3, (40, 2))
    par = np.zeros(3)
    ref = np.array([func(u, par) for u in us])
    assert same_bits(p.func_many(us, par), ref)


def test_a_dfdp_that_does_not_trace_leaves_func_traced(tmp_path):
    """dfdp filling np.zeros((n, len(par))) is not traced (len(par), a write into a float
    array): func (and dfdu) are, dfdp stays the Python function, and the route says so."""
    def func(u, par):
        return np.array([u[1], -par[0] * np.exp(u[0])])

    def dfdu(u, par):
        return np.array([[0.0, 1.0], [-par[0] * np.exp(u[0]), 0.0]])

    def dfdp(u, par):
        out = np.zeros((2, len(par)))
        out[1, 0] = -np.exp(u[0])
        return out
    p = traced_problem(_problem(func, dfdu=dfdu, dfdp=dfdp, jac=1), tmp_path / "t.py")
    assert isinstance(p, TracedProblem) and not p.dfdp_traced
    assert "traced into C" in p.route and "dfdp(u, par) in Python: len(par)" in p.route
    u, par = np.array([0.3, -0.2]), np.array([1.5, 0.0, 0.0])
    assert same_bits(p.dfdp(u, par, [1]), dfdp(u, par)[:, [0]])
    assert same_bits(p.jacobian(u, par, [1]), np.hstack([dfdu(u, par), dfdp(u, par)[:, [0]]]))


def test_par_length_is_not_traced():
    with pytest.raises(TraceError, match="len"):
        trace_function(lambda u, par: np.array([u[0] * len(par)]), 1, 36, (1,))
    with pytest.raises(TraceError, match="end"):
        trace_function(lambda u, par: np.array([u[0] * par[-1]]), 1, 36, (1,))


def test_difference_in_a_run_falls_back_for_good(tmp_path):
    """A func whose values change after it was traced (a global it reads): the run's
    first points show it, that call returns the Python values, and the problem is the
    Python one from then on (this run's rest, later runs)."""
    scale = [2.0]

    def func(u, par):
        return np.array([u[1] * scale[0], -u[0] + par[0]])
    py = _problem(func)
    p = traced_problem(py, tmp_path / "t.py")
    assert isinstance(p, TracedProblem)
    run = p.with_jac(0)
    u, par = np.array([0.3, 0.7]), np.array([0.1, 0.2, 0.3])
    assert run.func(u, par).tobytes() == func(u, par).tobytes()
    assert run.user.func_ready
    scale[0] = 3.0
    assert run.func(u, par).tobytes() == func(u, par).tobytes()
    assert not run.user.func_ready and "in Python" in run.route
    assert run.func_many(np.array([u, u]), par).tobytes() == \
        np.array([func(u, par)] * 2).tobytes()
    assert type(p.with_jac(0)) is Problem


@pytest.mark.parametrize("name, locus", [("ab", "AB2P_LOCUS"), ("lrz", "LRZ2P_LOCUS")])
def test_traced_runs_write_the_python_runs_files(name, locus, tmp_path, monkeypatch):
    """The equilibria, the Hopf locus from HB1 and the cycles from HB1 of a traced file
    (its FUNC called from the compiled correctors) write the b-, s- and d-files of the
    same runs on the Python functions (WASHER_TRACE=0) byte for byte, but for the
    d-file's Total Time: the trace is the same function, bit for bit, so every step is
    the same. The trace is taken and never refused on the way."""
    import shutil
    import auto_reference
    from washer.cont.user_problem import user_files_traced
    from washer.run import run
    refused = []
    monkeypatch.setattr(user_files_traced.TraceState, "refuse",
                        lambda self, why: refused.append(why))

    def runs(sub, trace):
        monkeypatch.setenv("WASHER_TRACE", trace)
        d = tmp_path / sub
        d.mkdir()
        shutil.copy(DATA / name / f"c.{name}", d)
        shutil.copy(DATA / name / f"{name}.py", d)
        c = d / f"c.{name}"
        run(c, sv="eq", verbose=False)
        run(c, s="eq", IRS="HB1", sv="hb", verbose=False,
            **dict(getattr(auto_reference, locus), PAR={}))
        run(c, s="eq", IRS="HB1", IPS=2, ICP=[1, 11], NMX=20, sv="po", verbose=False)
        return d

    built = []
    real_build = user_files_traced._build
    monkeypatch.setattr(user_files_traced, "_build", lambda *a: built.append(1) or real_build(*a))
    fast = runs("traced", "1")
    assert built and not refused
    slow = runs("python", "0")
    for f in ("b.eq", "s.eq", "d.eq", "b.hb", "s.hb", "d.hb", "b.po", "s.po", "d.po"):
        a, b = ((p / f).read_text().split("Total Time")[0] for p in (fast, slow))
        assert a == b, f
    assert len((fast / "b.po").read_text().splitlines()) > 20


CHANGING = '''
import numpy as np
calls = [0]
def func(u, par):
    calls[0] += 1
    # another value after loading's calls, within the run's first compared points
    s = 1.0 if calls[0] < 27 else 1.0 + 2.0 ** -40
    return np.array([par[0] - s * u[0]])
def stpnt(u, par, t=0.0):
    par[0] = 0.0
    u[0] = 0.0
'''


def test_a_refusal_during_a_run_is_said(tmp_path, capsys):
    """A func whose values change after it was traced and verified on loading (a
    module-level counter it reads): the run's first compared points show it, the run
    goes on in Python, and the verbose output says so after the run as it said the
    traced route before it."""
    from washer.run import run
    (tmp_path / "chg.py").write_text(CHANGING)
    (tmp_path / "c.chg").write_text("NDIM=1, IPS=1, ICP=[1], NMX=10, DS=0.1, DSMAX=0.1, "
                                    "ISP=0, ILP=0\n")
    r = run(tmp_path / "c.chg", e="chg", sv="chg")
    assert r.status == "ok"
    err = capsys.readouterr().err
    assert "traced into C" in err
    assert "in Python: its compiled trace gave other values than func(u, par)" in err
    assert err.index("traced into C") < err.index("in Python: its compiled trace")


def test_nothing_compared_on_loading_is_not_trusted(tmp_path):
    """A func with no finite value at any of the points near the start it is compared
    at (here: none anywhere) is not trusted with nothing verified: the Python problem,
    saying why."""
    p = traced_problem(_problem(lambda u, par: np.array([u[0] / 0.0, u[1] * np.inf])),
                       tmp_path / "t.py")
    assert type(p) is Problem and "nothing verified" in p.route


#: Folders with an AUTO script or a constants file whose Python file traces: True where
#: it has a power numpy computes otherwise on numpy scalars and on arrays (traced in two
#: modes), False for the files traced since their dfdp stays Python (np.zeros((n,
#: len(par)))) or since a value times an array of values is traced element by element.
TRACED_FOLDERS = {"bvp/bvp": True, "bvp/ext": True, "bvp/lin": True, "bvp/nep": True,
                  "bvp/non": True, "bvp/obv": True, "bvp/spb": True, "bvp/um2": True,
                  "bvp/um3": True, "optcusp": True, "pfchain": True, "pvlsstop": True,
                  "sharpfold": True, "bvp/stw": True, "bvp/int": False, "bvp/fsh": False,
                  "bvp/man": False, "maps/dd2": False, "maps/log": False}

_RUN_BOTH_WAYS = '''
import sys
from washer.cont.user_problem import user_files_traced
seen = []
real_build, real_refuse = user_files_traced._build, user_files_traced.TraceState.refuse
def build(*a):
    p = real_build(*a)
    seen.append("two ways" if p.two_ways else "one way")
    return p
def refuse(self, why):
    seen.append("refused: " + why)
    real_refuse(self, why)
user_files_traced._build, user_files_traced.TraceState.refuse = build, refuse
if sys.argv[1].endswith(".auto"):
    from washer.auto.__main__ import main
    rc = main([sys.argv[1]])
else:
    from washer.run import run
    rc = 0 if run(sys.argv[1], sv="out", verbose=False).status == "ok" else 1
print("ROUTES", seen)
sys.exit(rc)
'''


@pytest.mark.slow
@pytest.mark.parametrize("folder", sorted(TRACED_FOLDERS))
def test_traced_folders_write_the_python_runs_files(folder, tmp_path):
    """Each folder's runs (its AUTO script, else its constants file) with the traced
    func write the b-, s- and d-files of the same runs on the Python functions
    (WASHER_TRACE=0) byte for byte but for the d-files' Total Time, each in a process of
    its own as AUTO runs a script; the trace is taken (in two modes where the file has
    such powers) and never refused."""
    import os
    import shutil
    import subprocess
    import sys
    src = DATA / folder
    outs = {}
    for trace in ("0", "1"):
        d = tmp_path / trace
        kind, _, demo = folder.partition("/")
        if kind in ("bvp", "maps"):
            # AUTO's demo folder with the Python transcription of its equations beside it
            d.mkdir()
            copy_demo(demo, d, src)
        else:
            shutil.copytree(src, d)
        # the demo's own script NAME.auto (a demo folder also holds AUTO's clean.auto)
        name = folder.rpartition("/")[2]
        own = d / f"{name}.auto"
        scripts = [own] if own.exists() else sorted(d.glob("*.auto"))
        target = (scripts or sorted(d.glob("c.*")))[0]
        env = dict(os.environ, WASHER_TRACE=trace, OMP_NUM_THREADS="1",
                   PYTHONPATH=os.pathsep.join([str(Path(__file__).parents[1]),
                                               os.environ.get("PYTHONPATH", "")]))
        r = subprocess.run([sys.executable, "-c", _RUN_BOTH_WAYS, target.name], cwd=d,
                           env=env, capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr[-2000:]
        outs[trace] = (d, r.stdout)
    assert "ROUTES []" in outs["0"][1]
    way = "two ways" if TRACED_FOLDERS[folder] else "one way"
    assert f"ROUTES ['{way}']" in outs["1"][1], outs["1"][1][-500:]
    names = sorted(p.name for p in outs["0"][0].iterdir() if p.name[:2] in ("b.", "s.", "d."))
    assert names and names == sorted(p.name for p in outs["1"][0].iterdir()
                                     if p.name[:2] in ("b.", "s.", "d."))
    for name in names:
        a, b = ((outs[t][0] / name).read_text().split("Total Time")[0] for t in ("0", "1"))
        assert a == b, name


#: numpy's elementwise ufuncs of doubles that a traced func calls through numpy's loop
#: (np_loop1 / np_loop2 in the C; the gufuncs matmul, vecdot, ... are not elementwise),
#: each once (np.abs is np.absolute)
LOOPED = list({id(u): u for u in (getattr(np, n) for n in sorted(dir(np)))
               if isinstance(u, np.ufunc) and u.nout == 1 and u.nin in (1, 2)
               and u.signature is None
               and ("dd->d" if u.nin == 2 else "d->d") in u.types}.values())
#: arguments inside the domain (the file is verified where it starts, where every
#: component must be finite): |x| < 1 for these, x >= 1 for those, y >= 1 as a divisor
_UNIT = {np.arcsin, np.arccos, np.arctanh}
_ABOVE_ONE = {np.arccosh, np.log, np.log10, np.log2, np.log1p, np.sqrt, np.reciprocal}
_DIVISOR = {np.divide, np.floor_divide, np.fmod, np.remainder, np.float_power}


def _every_loop(u, par):
    out = []
    for f in LOOPED:
        x, y = u[0], u[1]
        x = x / (1 + abs(x)) if f in _UNIT else 1 + x * x if f in _ABOVE_ONE else x
        if f is np.float_power:
            x = 1 + x * x
        out.append(f(x) if f.nin == 1 else f(x, 1 + y * y if f in _DIVISOR else y))
    return np.array(out + [u[2]])


@pytest.mark.parametrize("k", [1, 63, 64, 65, 200])
@pytest.mark.parametrize("low, high", [(-1.0, 1.0), (-30.0, 30.0), (1.0, 700.0)])
def test_batched_f_is_f_point_by_point(tmp_path, k, low, high):
    """f at k points in one call (washer_traced_batch: each numpy loop called once for
    up to BATCH_CHUNK points, as numpy calls it on a vectorised func's arrays) gives the
    bytes of FUNC called point by point (one element a loop call) and of the Python func
    on numpy scalars, for every elementwise numpy ufunc of doubles (overflow to inf
    included), at k points on both sides of the chunk's boundary."""
    n = len(LOOPED) + 1
    py = _problem(_every_loop, ndim=n)
    p = traced_problem(py, tmp_path / "every.py")
    assert isinstance(p, TracedProblem), getattr(p, "route", "")
    rng = np.random.default_rng(k)
    us = rng.uniform(low, high, (k, n))
    ps = rng.uniform(-5, 5, (k, 3))
    with np.errstate(all="ignore"):
        batched = p.user.func_batch(us, ps)
        pointwise, _, _ = p.user.jac_batch(us, ps)
        ref = np.array([_every_loop(u.copy(), q.copy()) for u, q in zip(us, ps)], dtype=float)
    assert batched.tobytes() == pointwise.tobytes()
    assert batched.tobytes() == ref.tobytes()


def test_the_emitted_file_is_made_once_for_the_same_traces(tmp_path):
    """_emitted keeps the C of the same traces (a run traces afresh): its text is what
    emit_user_file writes of new traces of the same function; another function or
    another file name is another source."""
    from washer.cont.user_problem import user_files_traced as T
    from washer.cont.user_problem.tracer import emit_user_file

    def f(u, par):
        return np.array([par[0] * np.exp(u[0]) - u[1], u[0] ** 2 + par[1] * u[1]])

    def g(u, par):
        return np.array([par[0] * np.exp(u[0]) - u[1], u[0] ** 2 - par[1] * u[1]])

    def traced(fn):
        loops: list = []
        return trace_function(fn, 2, T.TRACE_NPAR, (2,), loops=loops)

    path = tmp_path / "ef.py"
    first = T._emitted(path, 2, traced(f), None, None)
    again = traced(f)
    assert T._emitted(path, 2, again, None, None) is first
    assert first.text == emit_user_file(path.name, 2, again).encode()
    other = T._emitted(path, 2, traced(g), None, None)
    assert other.text == emit_user_file(path.name, 2, traced(g)).encode()
    assert other.text != first.text and other.name != first.name
    renamed = T._emitted(tmp_path / "eg.py", 2, traced(f), None, None)
    assert renamed is not first and renamed.text != first.text
