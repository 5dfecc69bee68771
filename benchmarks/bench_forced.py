"""Speed of the exact stability analysis (shooting with the kernel).

    python benchmarks/bench_forced.py

Prints, at nominal values (reference set, Omega = 10 Hz):
  (1) one period of the flow with the monodromy matrix (one kernel call), and the same
      augmented system through scipy's solve_ivp (DOP853) with the kernel's rhs and
      Jacobian called from Python, both at rtol 1e-10;
  (2) one periodic response with its Floquet multipliers (Newton shooting from the
      averaged rotating-frame equilibrium, including finding that equilibrium);
  (3) the located TR point in C_p (Brent on C_p within +-5% of the averaged Hopf value,
      a converged periodic response per evaluation), and the same via pseudo-arclength
      continuation from C_p = 0.08 to 0.13 with detection and location;
  (4) the exact critical C_p with the averaged and frozen Hopf values (`critical_cp`);
  (5) the collocation run, the engine (IPS = 2, e='washer:forced', NTST = 20, NCOL = 4, NDIM = 14):
      the start (stpnt: the shooting's orbit sampled at the 81 mesh nodes), one periodic
      response with its 14 multipliers (a continuation step: Newton on the collocation
      system, then the multipliers; mean over 10 steps in C_p = 0.2 -> 0.3, no special
      point), the TR point located (C_p 0.08 -> 0.12), and the shipped
      auto_constants/c.washer.forced (C_p 0 -> 0.5, 31 points).
Best of 3 wall times; 2 shared cores, so other load inflates them.
"""
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

import washer
from washer.cont import floquet
from washer.machine import forced, kernel
from washer.problems import forced as shooting
from washer.problems.washer import washer_problem
from washer.run import run
from washer.problems.rotating import averaged_hopf

CONSTANTS = Path(__file__).resolve().parent.parent / "auto_constants" / "c.washer.forced"


def best_of(fn, repeat=3):
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main():
    params = washer.load_params()
    P = params.vector()
    r = shooting.periodic_response(params)
    T, u0 = r.T, r.u0

    t_k, (_, _, _, st) = best_of(lambda: kernel.flow_variational(0.0, T, u0, P), 5)

    def aug(t, y):
        J, _ = kernel.jac_fixed(t, y[:12], P, "constant")
        return np.r_[kernel.rhs_fixed(t, y[:12], P, "constant"),
                     (J @ y[12:].reshape(12, 12)).ravel()]

    t_s, sol = best_of(lambda: solve_ivp(aug, (0, T), np.r_[u0, np.eye(12).ravel()],
                                         method="DOP853", rtol=1e-10, atol=1e-12))
    print("one period (T = 0.1 s) with the monodromy matrix, rtol 1e-10")
    print(f"  kernel (washer_flow_variational) : {t_k * 1e3:8.2f} ms, {st['nfev']} evaluations")
    print(f"  solve_ivp DOP853, kernel rhs/jac : {t_s * 1e3:8.2f} ms, {sol.nfev} evaluations")

    t_r, r = best_of(lambda: shooting.periodic_response(params))
    print("\nperiodic response with Floquet multipliers (from the averaged equilibrium)")
    print(f"  {t_r * 1e3:8.1f} ms, {r.iterations} Newton iterations, residual {r.residual:.1e}, "
          f"max|mu| = {np.abs(r.multipliers).max():.9f}")

    cp_avg, _ = averaged_hopf(params)
    start = forced.averaged_start(params.replace(C_p=cp_avg))
    t_tr, (_, sp) = best_of(lambda: shooting.locate_tr(
        params, "C_p", (0.95 * cp_avg, 1.05 * cp_avg), start))
    print("\nTR point in C_p")
    print(f"  locate_tr (C_p alone)            : {t_tr:8.3f} s, C_p = {sp.par[0]:.12f}")
    t_c, b = best_of(lambda: shooting.continue_response(params.replace(C_p=0.08), "C_p", 0.13,
                                                        ds=0.1, ds_max=0.3))
    tr = [s for s in b.specials if s.ty == "TR"]
    print(f"  continuation 0.08 -> 0.13 + locate: {t_c:8.3f} s, {len(b.rows)} points, "
          f"C_p = {tr[0].par[0]:.12f}")
    t_cc, c = best_of(lambda: shooting.critical_cp(params))
    print(f"  critical_cp (exact, averaged, frozen): {t_cc:8.3f} s: "
          f"{c['C_p_exact']:.10f}, {c['C_p_averaged']:.10f}, {c['C_p_frozen']:.10f}")
    collocation_run(params, c)


def collocation_run(params, crit):
    """The engine on e='washer:forced' (outputs in a temporary folder)."""
    print("\nthe collocation run: the engine, IPS = 2, e='washer:forced', NTST 20 x NCOL 4")

    def start():
        pr = washer_problem("washer:forced", params=params)
        u, scratch = np.zeros(14), np.zeros(16)
        for t in np.arange(81) / 80:
            pr._stpnt(u, scratch, t)

    t_s, _ = best_of(start)
    print(f"  start (stpnt: the shooting's orbit at 81 nodes): {t_s * 1e3:8.1f} ms")
    with tempfile.TemporaryDirectory() as d:
        cfile = Path(d) / "c.washer.forced"
        shutil.copy(CONSTANTS, cfile)

        def go(**kw):
            return lambda: run(cfile, verbose=False, sv="bench", **kw)

        window = dict(PAR={"C_p": 0.2}, UZSTOP={"C_p": [0.0, 0.3]}, DSMAX=0.01)
        t1, _ = best_of(go(NMX=2, **window))          # the start and one step
        t11, r = best_of(go(NMX=12, **window))        # the start and 11 steps
        assert [x.ty for x in r.specials if x.ty in ("TR", "PD", "LP", "BP")] == []
        print(f"  one periodic response + 14 multipliers: {(t11 - t1) / 10 * 1e3:8.1f} ms "
              f"(a continuation step; mean of 10)")
        # From 0.08: from 0.09 a step lands at 0.100993, where |mu| - 1 = 2e-6 is inside
        # AUTO's stability tolerance 1e-5 (already counted stable), so the sign change of
        # the TR test after it comes with no change of the stable count and is not a TR.
        t_tr, r = best_of(go(PAR={"C_p": 0.08}, UZSTOP={"C_p": [0.0, 0.12]}))
        tr = r("TR1")
        mu = np.asarray(tr.stability.values)
        print(f"  TR located, C_p 0.08 -> 0.12          : {t_tr:8.3f} s, {len(r.rows)} points, "
              f"C_p = {tr.par[0]:.12f} (shooting {crit['C_p_exact']:.12f}), "
              f"critical mu = {floquet.torus_pair(mu):.9f}")
        t_all, r = best_of(go())
        print(f"  c.washer.forced, C_p 0 -> 0.5         : {t_all:8.3f} s, {len(r.rows)} points")


if __name__ == "__main__":
    main()
