"""User problems as sympy expressions (washer.cont.user_problem.user_files_sympy): the generated
and compiled
f, f_u, f_p against the hand-written Lorenz equations and their Jacobian written out
by hand, and runs against the closed-form Hopf point and the Python file's run."""
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.cont.problem import ProblemError
from washer.cont.user_problem.user_files import load_python_problem
from washer.run import run

DATA = Path(__file__).parent / "data"


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.setenv("WASHER_CACHE", str(tmp_path / "cache"))
    for f in (DATA / "lrz_sym").iterdir():
        shutil.copy(f, tmp_path)
    return tmp_path


def lorenz(u, par):
    x, y, z = u
    rho, beta, sigma = par[:3]
    f = np.array([sigma * (y - x), rho * x - y - x * z, x * y - beta * z])
    J = np.array([[-sigma, sigma, 0.0], [rho - z, -1.0, -x], [y, x, -beta]])
    Jp = np.array([[0.0, 0.0, y - x], [x, 0.0, 0.0], [0.0, -z, 0.0]])
    return f, J, Jp


def test_generated_f_and_exact_jacobians_are_lorenz(folder):
    prob = load_python_problem("lrz", folder, 3).with_jac(1)
    rng = np.random.default_rng(2)
    us = rng.standard_normal((20, 3)) * 10
    pars = np.c_[rng.uniform(0, 30, (20, 1)), rng.uniform(1, 3, (20, 1)),
                 rng.uniform(5, 15, (20, 1)), rng.standard_normal((20, 2))]    # NPAR 5
    F = prob.func_many(us, pars)
    Js = prob.dfdu_many(us, pars)
    for u, p, f, J in zip(us, pars, F, Js):
        f_ref, J_ref, Jp_ref = lorenz(u, p)
        # the same arithmetic up to the order of operations: rounding only
        np.testing.assert_allclose(f, f_ref, rtol=1e-13, atol=1e-12)
        np.testing.assert_allclose(J, J_ref, rtol=0, atol=1e-13)
        np.testing.assert_allclose(prob.dfdu(u, p), J_ref, rtol=0, atol=1e-13)
        Jp = prob.dfdp(u, p, [1, 2, 3, 4])
        np.testing.assert_allclose(Jp, np.c_[Jp_ref, np.zeros(3)], rtol=0, atol=1e-13)


def test_equilibria_find_the_closed_form_hopf_point_as_the_python_file(folder, tmp_path_factory):
    """lrz's equilibria with the exact Jacobian (JAC = 1): both HBs at
    rho_H = sigma (sigma + beta + 3) / (sigma - beta - 1), located to AUTO's EPSS-based
    accuracy, and the same labelled points as the numpy file with differences (JAC = 0)."""
    r = run(folder / "c.lrz", verbose=False, sv="eq")
    beta, sigma = 8 / 3, 10.0
    rho_h = sigma * (sigma + beta + 3) / (sigma - beta - 1)
    hbs = [s for s in r.specials if s.ty == "HB"]
    assert len(hbs) == 2
    for s in hbs:
        assert s.par[0] == pytest.approx(rho_h, abs=1e-5)
    plain = tmp_path_factory.mktemp("plain")
    for f in ("lrz.py", "c.lrz"):
        shutil.copy(DATA / "lrz" / f, plain)
    ref = run(plain / "c.lrz", verbose=False, sv="eq")
    assert [s.ty for s in r.specials] == [s.ty for s in ref.specials]
    for a, b in zip(r.specials, ref.specials):
        assert a.par[0] == pytest.approx(b.par[0], abs=1e-5)


def test_periodic_orbits_from_the_compiled_problem(folder):
    run(folder / "c.lrz", verbose=False, sv="eq")
    po = run(folder / "c.lrz", verbose=False, s="eq", IRS="HB1", IPS=2, ICP=["rho", "PERIOD"],
             NMX=35, NPR=2, DS=0.5, sv="po")
    assert po.status == "ok" and len(po.rows) == 35
    # the family ends near the homoclinic orbit at rho = 13.9265 (lrz.auto's first family)
    assert po.specials[-1].par[0] == pytest.approx(13.9265, abs=1e-3)


def test_an_unknown_symbol_is_named(folder):
    (folder / "bad.py").write_text("import sympy as sp\nu = sp.symbols('x y z')\n"
                                   "par = sp.symbols('rho beta sigma')\n"
                                   "x, y, z = u\nq = sp.Symbol('q')\n"
                                   "f = [y - x, q * x, x * y - z]\n")
    with pytest.raises(ProblemError, match=r"bad\.py: f\[1\] uses \['q'\]"):
        load_python_problem("bad", folder, 3)


def test_exact_second_derivatives_are_lorenz(folder):
    """f_zz[e_s, w] from the generated Hessian: the Lorenz second derivatives written out
    (d2 f1/dsigma dx = -1, d2 f1/dsigma dy = 1, d2 f2/drho dx = 1, d2 f2/dx dz = -1,
    d2 f3/dx dy = 1, d2 f3/dbeta dz = -1)."""
    prob = load_python_problem("lrz", folder, 3)
    u, par = np.array([1.3, -0.4, 2.2]), np.array([24.0, 8 / 3, 10.0, 0.0])
    ws = np.array([[0.3, -1.1, 0.7], [2.0, 0.5, -0.25]])
    T = prob.second_derivatives(u, par, ws, [1, 3, 4])          # rows: x, y, z, rho, sigma, PAR(4)
    for k, (a, b, c) in enumerate(ws):
        expect = np.array([[0, -c, b], [0, 0, a], [0, -a, 0],   # e_x, e_y, e_z
                           [0, a, 0], [b - a, 0, 0], [0, 0, 0]])  # rho, sigma, PAR(4)
        np.testing.assert_allclose(T[:, k, :], expect, rtol=0, atol=1e-14)


def test_hopf_locus_with_exact_derivatives_is_the_closed_form(folder):
    """The Hopf locus in (rho, sigma) at beta = 8/3 (lrz2p's run), exact f_u and f_zz:
    rho_H = sigma (sigma + beta + 3) / (sigma - beta - 1) at the UZ points sigma = 5,
    10, 20, to the corrector's tolerance."""
    run(folder / "c.lrz", verbose=False, sv="eq")
    uz = []
    for ds in (0.1, -0.1):            # from sigma = 10 up to 20 and down to 5
        hb = run(folder / "c.lrz", verbose=False, s="eq", IRS="HB1", ICP=["rho", "sigma"],
                 ISW=2, NMX=300, DS=ds, DSMAX=2.0, UZR={"sigma": [5.0, 10.0, 20.0]},
                 UZSTOP={"sigma": [4.0, 40.0], "rho": 200.0}, sv="hb")
        assert hb.status == "ok"
        uz += [s for s in hb.specials if s.ty == "UZ" and round(s.par[2]) in (5, 20)]
    beta = 8 / 3
    assert sorted(round(s.par[2]) for s in uz) == [5, 20]
    for s in uz:
        sigma = s.par[2]
        assert s.par[0] == pytest.approx(sigma * (sigma + beta + 3) / (sigma - beta - 1),
                                         rel=1e-7)


def test_a_reloaded_problem_shares_the_parsed_declarations_and_the_library(folder):
    """Every run loads its problem afresh: the second load of the same file reuses the
    parsed cffi declarations and the opened library (a cdef costs milliseconds, more than
    a short run), and computes the same values."""
    a = load_python_problem("lrz", folder, 3)
    b = load_python_problem("lrz", folder, 3)
    assert a._compiled.ffi is b._compiled.ffi and a._compiled.lib is b._compiled.lib
    u, par = np.array([1.0, 2.0, 3.0]), np.array([28.0, 8 / 3, 10.0])
    np.testing.assert_array_equal(a.func(u, par), b.func(u, par))
    np.testing.assert_array_equal(b.func(u, par), [10.0 * (2 - 1), 28 - 2 - 3, 2 - 8.0])


def test_the_generated_c_is_kept_by_the_equations_not_the_file(folder, tmp_path):
    """The generated C is remembered by the equations themselves: a copy of lrz.py in
    another folder gets lrz's functions, and a file of the same name there whose
    expressions differ (sigma (y - x) replaced by 2 sigma (y - x)) gets its own, with its
    own values, in the same process."""
    u, par = np.array([1.0, 2.0, 3.0]), np.array([28.0, 8 / 3, 10.0])
    first = load_python_problem("lrz", folder, 3).func(u, par)
    copy, edited = tmp_path / "copy", tmp_path / "edited"
    for d in (copy, edited):
        d.mkdir()
        shutil.copy(folder / "lrz.py", d)
    text = (edited / "lrz.py").read_text()
    assert "f = [sigma * (y - x)," in text
    (edited / "lrz.py").write_text(text.replace("f = [sigma * (y - x),",
                                                "f = [2 * sigma * (y - x),"))
    np.testing.assert_array_equal(load_python_problem("lrz", copy, 3).func(u, par), first)
    got = load_python_problem("lrz", edited, 3).func(u, par)
    np.testing.assert_array_equal(got, [2 * first[0], first[1], first[2]])


def test_a_copy_in_another_folder_does_not_generate_again(folder, tmp_path_factory,
                                                         monkeypatch):
    """sympy's differentiation and printing (most of a short run's set-up) run once for
    the same equations in a process: a chain of runs, each in its own folder, reuses
    the C."""
    from washer.cont.user_problem import user_files_sympy
    calls = []
    real = user_files_sympy.generate_c
    monkeypatch.setattr(user_files_sympy, "generate_c", lambda *a, **k: calls.append(1) or real(*a, **k))
    monkeypatch.setattr(user_files_sympy, "_GENERATED", {})
    other = tmp_path_factory.mktemp("copy")
    shutil.copy(folder / "lrz.py", other)
    load_python_problem("lrz", folder, 3)
    load_python_problem("lrz", other, 3)
    assert len(calls) == 1
