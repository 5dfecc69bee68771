"""Loading NAME.py: every run executes the file afresh (an edited file is the edited
equations, module-level state is the run's own) while its compiled source is kept in the
process; whether stpnt takes the time argument; the points a traced file is checked at."""
import functools
import inspect

import numpy as np

from washer.cont.user_problem import user_files, user_files_traced
from washer.cont.problem import Problem
from washer.cont.user_problem.user_files import load_python_problem

FILE = """import numpy as np
CALLS = []


def func(u, par):
    CALLS.append(1)
    return np.array([-u[0] + par[0] * {k}])


def stpnt(u, par):
    u[:] = 0.0
"""


def test_an_edited_file_is_the_edited_equations_and_each_load_its_own_module(tmp_path):
    (tmp_path / "one.py").write_text(FILE.format(k=1.0))
    a = load_python_problem("one", tmp_path, 1)
    b = load_python_problem("one", tmp_path, 1)
    par = np.array([2.0])
    assert a.python._func(np.array([0.5]), par)[0] == 1.5
    # the same source compiled once, executed twice: two modules, two states
    assert a.python._func.__code__ is b.python._func.__code__
    assert a.python._func.__globals__ is not b.python._func.__globals__
    assert a.python._func.__globals__["__file__"] == str(tmp_path / "one.py")
    (tmp_path / "one.py").write_text(FILE.format(k=3.0))
    c = load_python_problem("one", tmp_path, 1)
    assert c.python._func(np.array([0.5]), par)[0] == 5.5
    assert c.python._func.__code__ is not a.python._func.__code__
    assert len(user_files._CODE) <= user_files._CODE_MAX


def _positional(f) -> bool:
    """What stpnt_has_time answered before its fast path: the signature's count."""
    params = inspect.signature(f).parameters.values()
    positional = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    return len(positional) >= 3 or any(p.kind == p.VAR_POSITIONAL for p in params)


def test_stpnt_time_argument_is_the_signatures():
    def two(u, par): pass
    def three(u, par, t): pass
    def default(u, par, t=0.0): pass
    def star(u, *rest): pass
    def only(u, par, /, t): pass
    def kwonly(u, par, *, t=0.0): pass
    def kwargs(u, par, **kw): pass

    @functools.wraps(two)
    def wrapped(*args): return two(*args)
    lam = lambda u, par, t: None      # noqa: E731
    cases = [two, three, default, star, only, kwonly, kwargs, wrapped, lam,
             functools.partial(three, 1.0)]
    for f in cases:
        p = Problem(1, lambda u, par: u, f)
        assert p.stpnt_has_time == _positional(f), f


def _setter(u0, p0):
    def stpnt(u, par):
        u[:] = u0
        par[:] = p0
    return stpnt


def test_start_points_are_the_row_by_row_formula():
    """`_start_points` builds its rows in two vectorised calls: the same doubles as
    u0 + s (1 + |u0|) z taken one row at a time."""
    rng = np.random.default_rng(3)
    for n in (1, 2, 3, 7):
        u0 = rng.standard_normal(n) * 10.0 ** rng.uniform(-5, 5, n)
        p0 = np.zeros(user_files_traced.TRACE_NPAR)
        p0[:4] = rng.standard_normal(4)

        us, ps = user_files_traced._start_points(Problem(n, lambda u, par: u, _setter(u0, p0)))
        zu, zp = user_files_traced._load_deviates(user_files_traced.LOAD_SEED, n, len(p0))
        scales = np.geomspace(1e-3, 1.0, user_files_traced.LOAD_POINTS - 1)
        rows_u = np.array([u0] + [u0 + s * (1 + np.abs(u0)) * z for s, z in zip(scales, zu)])
        rows_p = np.array([p0] + [p0 + s * (1 + np.abs(p0)) * z for s, z in zip(scales, zp)])
        assert us[0].tobytes() == u0.tobytes()          # the file's start itself
        assert us.tobytes() == rows_u.tobytes() and us.shape == rows_u.shape
        assert ps.tobytes() == rows_p.tobytes() and ps.shape == rows_p.shape


def test_a_library_key_follows_its_sources_and_headers(tmp_path):
    """library_key's results are kept in the process by the sources' bytes and the
    headers' names, sizes and modification times: an edited source or header, a header
    added, is another key, and the kept key is the one hashed afresh."""
    import os
    from washer.cont.user_problem import c_library
    inc = tmp_path / "include"
    inc.mkdir()
    (inc / "a.h").write_text("#define A 1\n")
    src = [c_library.source_text("x.c", "int x(void) { return A; }\n")]

    def fresh():
        c_library._KEYS.clear()
        return c_library.library_key(src, [inc])
    k0 = c_library.library_key(src, [inc])
    assert k0 == c_library.library_key(src, [inc]) == fresh()
    assert c_library.library_key([c_library.source_text("x.c", "int x(void) { return 2; }\n")],
                                 [inc]) != k0
    st = os.stat(inc / "a.h")
    (inc / "a.h").write_text("#define A 2\n")               # the same size
    os.utime(inc / "a.h", ns=(st.st_atime_ns, st.st_mtime_ns + 1000))
    k1 = c_library.library_key(src, [inc])
    assert k1 != k0 and k1 == fresh()
    (inc / "b.h").write_text("\n")
    assert c_library.library_key(src, [inc]) not in (k0, k1)


def test_a_library_keys_headers_are_what_glob_lists(tmp_path):
    """library_key reads a folder's headers with os.scandir: the names and files that
    sorted(Path(folder).glob('*.h')) lists (a hidden header too, not a '.hpp' or a file
    without the suffix), nothing for a folder that is not there."""
    from pathlib import Path
    from washer.cont.user_problem import c_library
    for name in ("b.h", "a.h", ".hidden.h", "c.hpp", "h", "z.H"):
        (tmp_path / name).write_text("\n")
    (tmp_path / "sub.h").mkdir()
    listed = c_library._headers(tmp_path)
    assert listed == [(p.name, str(p)) for p in sorted(Path(tmp_path).glob("*.h"))]
    assert [n for n, _ in listed] == [".hidden.h", "a.h", "b.h", "sub.h"]
    assert c_library._headers(tmp_path / "missing") == [] == list(
        Path(tmp_path / "missing").glob("*.h"))
