"""ISW = -1 at a regular label of a general BVP whose Jacobian has a second (nearly)
null direction: the start is the null vector orthogonal to the stored direction (AUTO's
CNRLBV takes IPERP = 1 at every restart with ISW < 0, and READBV reads the record's
parameter rates into RLDOT(1..) in order).

AUTO's demo r3b (H1a.auto .. V1b.auto) computes the Floquet eigenfunction of a halo orbit:
the orbit's 6 equations with v' = T f_u(u) v, v(1) = fm v(0), int |v|^2 = rho, free
[lambda, fm, rho], from a record of the orbits (ICP = [1, 11]). On v = 0 every fm solves
it (the trivial branch), and the eigenfunction branch crosses it where fm is a Floquet
multiplier; PVLS sets fm to the largest real multiplier of the 6-dimensional orbit, a
little off the discretised one, so the start lies on the trivial branch next to the
crossing. AUTO's border (the record's direction, its second rate, -1.61, in fm's place)
leaves the eigenfunction: its run goes to rho = 1 (UZ) with fm at the multiplier. The
independent reference is the multiplier by shooting over the period (DOP853, rtol 1e-12).

Data: tests/data/floquet_switch/s.H1.gz is the halo family's label 7 (one record of
AUTO's s.H1 from r3b.auto, Debian's auto-07p 0.9.2), b.flq AUTO's run of
`run(H1(7), c='r3b.flq')` from it; r3b.f90 and c.r3b.flq are the demo folder's.
"""
import gzip
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.auto import clui

DATA = Path(__file__).parent / "data"
HERE = DATA / "floquet_switch"
R3B = DATA / "auto_demos" / "r3b"


def _rows(path: Path) -> np.ndarray:
    """The b-file's rows: (PT, TY, PAR(1), L2-NORM, ..., fm, rho) as floats."""
    out = []
    for line in path.read_text().splitlines():
        s = line.split()
        if len(s) > 5 and s[0] != "0":
            out.append([float(v) for v in s[1:3] + s[4:]])
    return np.array(out)


def _multiplier_by_shooting(record_lines: list[str]) -> float:
    """The largest real Floquet multiplier of the record's orbit: the monodromy matrix
    of the circular restricted three-body problem (r3b.f90's FUNC with lambda) over
    the period, by DOP853."""
    from scipy.integrate import solve_ivp
    h = record_lines[0].split()
    npar = int(h[11])
    u0 = np.array([float(v) for v in record_lines[1].split()[1:7]])
    par = np.array(" ".join(record_lines[-((npar + 6) // 7):]).split(), float)
    lam, mu, period = par[0], par[1], par[10]

    def rhs(_t, w):
        r, v = w[:3], w[3:6]
        H = np.diag([1.0, 1.0, 0.0])        # the centrifugal term's Hessian
        acc = np.array([r[0], r[1], 0.0]) + 2 * np.array([v[1], -v[0], 0.0]) + lam * v
        for m, c in ((1 - mu, np.array([-mu, 0, 0])), (mu, np.array([1 - mu, 0, 0]))):
            d = r - c
            n = np.linalg.norm(d)
            acc -= m * d / n ** 3
            H += m * (3 * np.outer(d, d) / n ** 5 - np.eye(3) / n ** 3)
        A = np.zeros((6, 6))
        A[:3, 3:] = np.eye(3)
        A[3:, :3] = H
        A[3:, 3:] = [[lam, 2, 0], [-2, lam, 0], [0, 0, lam]]
        return np.r_[v, acc, (A @ w[6:].reshape(6, 6)).ravel()]

    sol = solve_ivp(rhs, (0, period), np.r_[u0, np.eye(6).ravel()], method="DOP853",
                    rtol=1e-12, atol=1e-12)
    assert np.abs(sol.y[:6, -1] - u0).max() < 1e-8          # the orbit closes
    ev = np.linalg.eigvals(sol.y[6:, -1].reshape(6, 6))
    real = ev[np.abs(ev.imag) < 1e-9].real
    return float(real[np.argmax(np.abs(real))])


@pytest.mark.slow
def test_floquet_eigenfunction_branch_from_a_stored_orbit(tmp_path, monkeypatch):
    for f in ("r3b.f90", "c.r3b.flq"):
        shutil.copy(R3B / f, tmp_path)
    text = gzip.decompress((HERE / "s.H1.gz").read_bytes()).decode()
    (tmp_path / "s.H1").write_text(text)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(clui, "_runner", clui.Runner())
    clui.run(e="r3b", c="r3b.flq", s="H1", IRS=7, sv="flq")

    ours, autos = _rows(tmp_path / "b.flq"), _rows(HERE / "b.flq")
    fm_exact = _multiplier_by_shooting(text.splitlines())
    # The branch leaves v = 0 at once: fm at the multiplier from the second point on,
    # rho growing to the UZ at rho = 1 (UZSTOP), as AUTO's 22 rows.
    assert ours.shape == autos.shape == (22, 10)
    assert ours[-1, 1] == -4 and ours[-1, -1] == pytest.approx(1.0, abs=1e-9)
    # fm to the shooting's multiplier: the collocation's error (NTST = 50, NCOL = 4)
    # of the multiplier, measured 1e-10 relative; asserted at EPSL = 1e-6.
    assert np.abs(ours[1:, -2] / fm_exact - 1).max() < 1e-6
    # Every row AUTO's within its Newton tolerances (EPSU = EPSL = 1e-6, relative):
    # measured 1.4e-7 in rho, 5e-8 in the L2 norm.
    np.testing.assert_allclose(ours[:, 2:], autos[:, 2:], rtol=1e-6, atol=1e-6)


def test_a_solution_called_at_a_mesh_time_is_the_state_there(tmp_path):
    """AUTO's `solution(t)` (Pointset's call), which r3b's data.py uses to build the
    manifold's start (`s0 = solution(0)`, `s0[i]`): the state U(1..NDIM) at that mesh time;
    a time between mesh times is refused, as AUTO's."""
    from washer.auto.diagram import read_solutions
    path = tmp_path / "s.H1"
    path.write_text(gzip.decompress((HERE / "s.H1.gz").read_bytes()).decode())
    (s,) = read_solutions(path)
    U, t = np.asarray(s.U), np.asarray(s.t)
    np.testing.assert_array_equal(s(0), U[0])
    np.testing.assert_array_equal(s(t[5]), U[5])
    np.testing.assert_array_equal(s(1.0), U[-1])
    assert s(0)[1] == s["U(2)"][0]
    with pytest.raises(ValueError):
        s((t[5] + t[6]) / 2)
