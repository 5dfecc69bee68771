"""The engine's dense LAPACK calls (washer.cont.linalg: solve, slogdet, eigvals, eig) give
numpy.linalg's values bit for bit: the same gesv, getrf and geev, without the wrappers."""
import numpy as np
import pytest

from washer.cont import linalg


@pytest.mark.parametrize("n", [1, 2, 3, 7, 19])
def test_the_same_values_as_numpy_linalg(n):
    rng = np.random.default_rng(n)
    for _ in range(20):
        M = rng.standard_normal((n, n + 1))[:, :n]          # strided, as J[:, :n]
        b = rng.standard_normal(n)
        assert np.array_equal(linalg.solve(M, b), np.linalg.solve(M, b))
        Mc = 2j * np.eye(n) - M                           # the first Lyapunov coefficient's
        bc = b + 1j * rng.standard_normal(n)
        assert np.array_equal(linalg.solve(Mc, bc), np.linalg.solve(Mc, bc))
        sign, logdet = np.linalg.slogdet(M)
        assert linalg.slogdet(M) == (float(sign), float(logdet))
        w = linalg.eigvals(M)
        ref = np.linalg.eigvals(M)
        assert w.dtype == ref.dtype and np.array_equal(w, ref)
        (w, V), (wr, Vr) = linalg.eig(M), np.linalg.eig(M)
        assert w.dtype == wr.dtype and np.array_equal(w, wr) and np.array_equal(V, Vr)


def test_real_spectra_come_back_real_and_complex_ones_complex():
    w = linalg.eigvals(np.diag([3.0, -1.0]))
    assert w.dtype == float and sorted(w) == [-1.0, 3.0]
    w, V = linalg.eig(np.array([[0.0, 1.0], [-4.0, 0.0]]))
    assert w.dtype == complex and np.allclose(sorted(w.imag), [-2.0, 2.0], rtol=1e-15, atol=0)  # LAPACK rounding


def test_singular_and_non_finite_matrices():
    M = np.array([[1.0, 2.0], [2.0, 4.0]])
    with np.errstate(invalid="ignore"):
        assert np.isnan(linalg.solve(M, np.ones(2))).all()
    assert linalg.slogdet(M) == (0.0, -np.inf)
    bad = np.array([[1.0, np.nan], [0.0, 1.0]])
    with pytest.raises(np.linalg.LinAlgError):
        linalg.eigvals(bad)
    with pytest.raises(np.linalg.LinAlgError):
        linalg.eig(bad)
    # the bordered factor of the engine falls back to least squares at a singular matrix
    f = linalg.dense_factor(np.array([[1.0, 2.0]]), np.array([2.0, 4.0]))
    with np.errstate(invalid="ignore"):
        x = f.solve(np.array([1.0, 2.0]))
    assert np.allclose(x, np.linalg.lstsq(f.M, [1.0, 2.0], rcond=None)[0])


# ------------------------------------------------ numpy's LAPACK called from C
# (csrc/cont/dense_lapack.cpp through washer.cont.lapack: the bordered factorisations and
# the sorted spectra of the algebraic systems)

compiled = pytest.mark.skipif(linalg._C is None,
                              reason="numpy links no bundled scipy-openblas here")


def _numpy_sorted(M):
    w = np.linalg.eigvals(M)
    w = w.real if (w.imag == 0).all() else w
    return w[np.argsort(-w.real, kind="stable")]


@compiled
@pytest.mark.parametrize("n", [1, 2, 3, 4, 7, 13, 25])
def test_compiled_factor_and_spectrum_are_numpys_bit_for_bit(n):
    rng = np.random.default_rng(100 + n)
    for k in range(300):
        M = rng.standard_normal((n, n)) * 10.0 ** rng.integers(-4, 5)
        if k % 5 == 0 and n > 1:
            M[:, -1] = M[:, 0]                     # singular: GETRF's zero pivot or not
        if k % 7 == 0:
            M = np.round(M)                        # ties in the pivots' and real parts' order
        f = linalg.DenseFactor(M)
        assert f._c is not None                   # the compiled path was taken
        sign, logdet = np.linalg.slogdet(M)
        assert f.sign_logdet() == (float(sign), float(logdet))
        b = rng.standard_normal(n)
        with np.errstate(invalid="ignore"):
            ref = np.linalg.solve(M, b) if sign != 0 else None
            x = f.solve(b)
        if ref is not None and np.isfinite(ref).all():
            assert np.array_equal(x, ref)
        if n > 1:                                  # [J; border] as the engine borders J
            g = linalg.dense_factor(M[:-1].copy(), M[-1].copy())
            assert g._c is not None and g.sign_logdet() == f.sign_logdet()
            assert np.array_equal(g.M, M)
            with np.errstate(invalid="ignore"):
                assert np.array_equal(g.solve(b), x, equal_nan=True)
        J = np.c_[M, rng.standard_normal(n)]
        for A in (M, J[:, :n]):                    # contiguous, and strided as f_u in J
            w, ref = linalg.eigenvalues_sorted(A), _numpy_sorted(M)
            assert w.dtype == ref.dtype and np.array_equal(w, ref)


@compiled
def test_compiled_spectrum_errors_and_ties():
    # equal real parts keep GEEV's order (the stable sort numpy's path applies)
    A = np.diag([1.0, 3.0, 1.0, -2.0, 3.0])
    assert np.array_equal(linalg.eigenvalues_sorted(A), _numpy_sorted(A))
    rot = np.array([[0.0, -2.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 0.5]])
    w = linalg.eigenvalues_sorted(rot)
    assert w.dtype == complex and np.array_equal(w, _numpy_sorted(rot))
    with pytest.raises(np.linalg.LinAlgError, match="infs or NaNs"):
        linalg.eigenvalues_sorted(np.array([[1.0, np.inf], [0.0, 1.0]]))
    # an exactly singular bordered matrix: numpy's determinant and least-squares step
    f = linalg.dense_factor(np.array([[1.0, 2.0]]), np.array([2.0, 4.0]))
    assert f._c is not None and f.sign_logdet() == (0.0, -np.inf)
    with np.errstate(invalid="ignore"):
        x = f.solve(np.array([1.0, 2.0]))
    assert np.allclose(x, np.linalg.lstsq(f.M, [1.0, 2.0], rcond=None)[0], rtol=1e-15, atol=0)


@compiled
def test_compiled_spectra_in_threads_are_each_their_own():
    # the compiled call runs without the GIL: threads computing spectra of the same size
    # at once must not share the result's buffer
    from concurrent.futures import ThreadPoolExecutor
    rng = np.random.default_rng(7)
    mats = [rng.standard_normal((4, 4)) for _ in range(8)]
    refs = [_numpy_sorted(M) for M in mats]

    def work(k):
        return all(np.array_equal(linalg.eigenvalues_sorted(mats[k]), refs[k])
                   for _ in range(400))
    with ThreadPoolExecutor(4) as pool:
        assert all(pool.map(work, range(8)))


@compiled
@pytest.mark.parametrize("n", [1, 2, 3, 6, 7, 8, 9, 16, 17, 25, 60])
def test_compiled_unit_tangent_is_numpys_bit_for_bit(n):
    # z = [J; theta ref]^-1 e_n by numpy's solve, made unit by numpy's weighted sum
    # (left to right below 8 terms, pairwise from 8 on) and division
    rng = np.random.default_rng(200 + n)
    e = np.zeros(n)
    e[-1] = 1.0
    for k in range(200):
        J = rng.standard_normal((n - 1, n)) * 10.0 ** rng.integers(-4, 5)
        ref = rng.standard_normal(n)
        theta = rng.uniform(0.1, 2.0, n) if k % 2 else np.ones(n)
        if k % 9 == 0:
            J, ref = np.round(J), np.round(ref)
        t, f, done = linalg.unit_tangent(J, theta, ref, 1e12)
        M = np.r_[J, (theta * ref)[None, :]]
        sign, logdet = np.linalg.slogdet(M)
        assert f.sign_logdet() == (float(sign), float(logdet)) and np.array_equal(f.M, M)
        if sign == 0:
            assert not done
            continue
        z = np.linalg.solve(M, e)
        nz = np.sqrt(abs((theta * z * z).sum()))
        assert done == (0 < nz <= 1e12)
        if done:
            assert np.array_equal(t, z / nz)


@compiled
def test_compiled_unit_tangent_leaves_what_it_cannot_do_to_the_caller():
    # an exactly singular [J; border]: GETRF's zero pivot, numpy's determinant
    t, f, done = linalg.unit_tangent(np.array([[1.0, 2.0]]), np.ones(2), np.array([2.0, 4.0]),
                                     1e12)
    assert t is None and not done and f.sign_logdet() == (0.0, -np.inf)
    # a solve far beyond `big` (a nearly singular matrix): not a tangent
    J = np.array([[1.0, 1.0 + 1e-14]])
    t, f, done = linalg.unit_tangent(J, np.ones(2), np.array([1.0, 1.0]), 1e12)
    assert t is None and not done
    # sizes and types it does not take: None (the caller's own way)
    assert linalg.unit_tangent(np.ones((2, 2)), np.ones(3), np.ones(3), 1e12) is None
    assert linalg.unit_tangent(np.ones((2, 3), dtype=np.float32), np.ones(3), np.ones(3),
                               1e12) is None
    assert linalg.unit_tangent(np.ones((2, 6))[:, :3], np.ones(3), np.ones(3), 1e12) is None


@compiled
@pytest.mark.parametrize("n", [1, 2, 3, 5, 6, 12])
def test_scaled_slogdet_is_numpys_norm_and_slogdet_bit_for_bit(n):
    """The BP test's determinant of a reduced matrix (systems.bvp bp_value): the compiled
    call gives numpy.linalg.norm(S) and numpy.linalg.slogdet(S / norm) bit for bit, over
    scales from 1e-150 to 1e150 (the norm's squares near the range's ends) and at
    singular matrices."""
    rng = np.random.default_rng(100 + n)
    for k in range(200):
        S = rng.standard_normal((n, n)) * 10.0 ** rng.uniform(-150, 150)
        if k % 20 == 0 and n > 1:
            S[-1] = S[0]                     # exactly singular: (0, -inf)
        scale = np.linalg.norm(S)
        got = linalg.scaled_slogdet(S)
        if not np.isfinite(scale) or scale == 0:
            assert got == (float(scale),)
            continue
        sign, logdet = np.linalg.slogdet(S / scale)
        assert got == (float(scale), float(sign), float(logdet))


def test_scaled_slogdet_of_a_zero_or_overflowing_matrix_is_its_norm_alone():
    assert linalg.scaled_slogdet(np.zeros((3, 3))) == (0.0,)
    assert linalg.scaled_slogdet(np.full((2, 2), 1e200)) == (np.inf,)
    got = linalg.scaled_slogdet(np.array([[1.0, np.nan], [0.0, 1.0]]))
    assert len(got) == 1 and np.isnan(got[0])


def _hamiltonian(rng, m):
    """A (2 m, 2 m) Hamiltonian matrix [[A, B], [C, -A^T]] (B, C symmetric): trace 0, its
    spectrum symmetric about the imaginary axis (f_u of a conservative system)."""
    A = rng.standard_normal((m, m))
    B, C = rng.standard_normal((m, m)), rng.standard_normal((m, m))
    return np.block([[A, B + B.T], [C + C.T, -A.T]])


@compiled
@pytest.mark.parametrize("ndim", [1, 2, 3, 4, 6, 8])
def test_compiled_equilibrium_point_is_the_python_functions_bit_for_bit(ndim):
    """PointValues (cont_ae_equilibrium_point) gives what the Python route of a point gives:
    linalg.unit_tangent's tangent and determinant, eigenvalues_sorted of f_u, and
    equilibrium's neutral_tolerance, stable_count and hopf_pair; it declines (a nonzero
    status) where unit_tangent leaves the tangent to its caller."""
    from washer.cont.system import determinant_test, determinant_value
    from washer.cont.systems.equilibrium import (PointValues, hopf_pair, neutral_tolerance,
                                                 stable_count)
    rng = np.random.default_rng(300 + ndim)
    n = ndim + 1
    for k in range(300):
        theta = rng.uniform(0.1, 2.0, n) if k % 2 else np.ones(n)
        call = PointValues(ndim, theta)
        J = rng.standard_normal((ndim, n)) * 10.0 ** rng.integers(-3, 4)
        if k % 3 == 0 and ndim % 2 == 0:
            J[:, :ndim] = _hamiltonian(rng, ndim // 2)     # conservative-looking
        if k % 7 == 0:
            J = np.round(J)                             # ties among real parts
        if k % 11 == 0:
            J[:, :ndim] = np.diag(rng.integers(-2, 3, ndim).astype(float))   # all real
        if k % 13 == 0 and ndim > 1:
            J[-1] = J[0]                                  # a singular bordered matrix
        ref = rng.standard_normal(n)
        got = call(J, ref, 1e12)
        t, factor, done = linalg.unit_tangent(J, theta, ref, 1e12)
        if not done:
            assert got in (1, 2)
            continue
        assert got == 0
        assert np.array_equal(call.t, t)
        sl = call.sign_logdet
        assert (sl[0], sl[1]) == factor.sign_logdet()
        assert determinant_value(sl[0], sl[1]) == determinant_test(factor)
        lam = linalg.eigenvalues_sorted(J, leading=True)
        neutral, n_stable, pair, real = call.out.tolist()
        got_lam = call.real if real else call.pairs
        assert got_lam.dtype == lam.dtype and np.array_equal(got_lam, lam)
        assert neutral == neutral_tolerance(J[:, :ndim])
        assert n_stable == stable_count(lam, neutral)
        mu = hopf_pair(lam)
        assert (pair < 0) if mu is None else (complex(lam[int(pair)]) == mu)


@compiled
def test_compiled_equilibrium_point_declines_what_it_does_not_take():
    from washer.cont.systems.equilibrium import PointValues
    call = PointValues(2, np.ones(3))
    assert call(np.ones((2, 3), dtype=np.float32), np.ones(3), 1e12) == -1
    assert call(np.ones((2, 6))[:, :3], np.ones(3), 1e12) == -1
    assert call(np.ones((3, 3)), np.ones(3), 1e12) == -1
    J = np.array([[1.0, np.nan, 0.0], [0.0, 1.0, 1.0]])
    assert call(J, np.ones(3), 1e12) != 0          # not finite: the Python route reports


@compiled
@pytest.mark.parametrize("demo", ["ab", "lrz"])
def test_equilibrium_runs_write_the_same_files_with_and_without_the_compiled_point(
        demo, tmp_path, monkeypatch):
    """An equilibrium run (its LP, BP and HB tests, located points and stability) writes
    the same b./s./d. files whether each point's values come from the compiled call
    (EquilibriumSystem.point_values) or from the Python route (tangent, stability,
    test_functions), which Continuation.evaluate takes where point_values gives None."""
    import shutil
    from pathlib import Path
    from washer.cont.systems import equilibrium
    from washer.run import run
    data = Path(__file__).parent / "data" / demo
    texts = []
    for on in (True, False):
        d = tmp_path / str(on)
        d.mkdir()
        for f in (f"{demo}.py", f"c.{demo}"):
            shutil.copy(data / f, d)
        if not on:
            monkeypatch.setattr(equilibrium.EquilibriumSystem, "point_values",
                                lambda self, *args: None)
        run(d / f"c.{demo}", verbose=False, sv="eq")
        # (the d-file's last line, AUTO's "Total Time", is the run's clock)
        texts.append([(d / f"{k}.eq").read_text() for k in "bsd"])
        assert texts[-1][2].splitlines()[-1].startswith(" Total Time")
        texts[-1][2] = texts[-1][2].rsplit(" Total Time", 1)[0]
    assert texts[0] == texts[1]
    assert "HB" in texts[0][2]          # (the test functions were used)
