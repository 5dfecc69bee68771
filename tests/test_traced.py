"""Python user files' func traced into compiled C (washer.cont.trace, washer.cont.traced):
the compiled function equals the Python one bit for bit, and what cannot be traced or
does not agree stays Python, saying why."""
import importlib.util
from pathlib import Path

import numpy as np
import pytest

from washer.cont.problem import Problem
from washer.cont.trace import TraceError, numpy_loop, trace_function
from washer.cont.traced import TracedProblem, traced_problem
from washer.cont.user_files import load_user_problem

DATA = Path(__file__).parent / "data"
#: Every Python user file shipped with the tests (func(u, par) defined), with its NDIM
#: from its constants files (or the size stpnt fills).
FILES = sorted(p for p in DATA.rglob("*.py") if "def func" in p.read_text())


def _ndim(path: Path) -> int:
    for c in sorted(path.parent.glob("c.*")):
        for line in c.read_text().splitlines():
            words = line.replace(",", " ").replace("=", " ").split()
            if "NDIM" in words:
                return int(words[words.index("NDIM") + 1])
            if words and words[0].isdigit() and len(words) >= 4 and "NDIM" in line:
                return int(words[0])
    return {"ab": 2, "plp": 2, "chu": 3, "frc": 3}.get(path.stem, 2)


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


def test_power_operator_falls_back(tmp_path):
    """x ** 2 rounds otherwise on a np.float64 (libm's pow) than on the arrays of a
    stencil (x * x): not traced, and said so."""
    p = traced_problem(_problem(lambda u, par: np.array([u[0] ** 2, u[1]])),
                       tmp_path / "t.py")
    assert type(p) is Problem and "x ** y" in p.route
    x = np.random.default_rng(2).uniform(-10, 10, 100_000)
    assert any(np.float64(v) ** 2 != w for v, w in zip(x, x ** 2))    # the reason


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
    from washer.cont import traced
    from washer.run import run
    refused = []
    monkeypatch.setattr(traced.TraceState, "refuse",
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
    real_build = traced._build
    monkeypatch.setattr(traced, "_build", lambda *a: built.append(1) or real_build(*a))
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
    s = 1.0 if calls[0] < 30 else 1.0 + 2.0 ** -40
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
