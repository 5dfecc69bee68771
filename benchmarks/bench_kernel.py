"""Kernel speed against pure-numpy baselines, measured in one run.

    python benchmarks/bench_kernel.py [--full]

Prints: (1) one right-hand-side evaluation of the ground-frame system (eq 48)
inside C++ (a batched call, so no Python per evaluation), through cffi from
Python, and in pure numpy (washer.symbolic.newton_euler); (2) the 50 s spin-up
of Fig 10 with the kernel's DOPRI5 and with solve_ivp(DOP853) on the numpy rhs.
Without --full the numpy spin-up runs the first 5 s and is scaled by its
evaluation count ratio (printed as such).
"""
import argparse
import time

import numpy as np

import washer
from washer.machine import kernel
from washer.symbolic import newton_euler


def best_of(fn, repeat=5):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--full", action="store_true", help="run the numpy baseline over all 50 s")
    args = ap.parse_args()
    params = washer.load_params().replace(C_p=0.15)
    model = washer.Model(params)
    rng = np.random.default_rng(0)
    n = 20000
    U = np.c_[rng.normal(0, 0.02, (n, 6)) + [0, 0, 0.39, 0, 0, 0], rng.normal(0, 0.2, (n, 6))]
    t = rng.uniform(0, 5, n)

    t_batch = best_of(lambda: kernel.rhs_fixed_batch(t, U, model.P)) / n
    m = 2000
    t_cffi = best_of(lambda: [kernel.rhs_fixed(t[i], U[i], model.P) for i in range(m)]) / m
    k = 200
    t_numpy = best_of(lambda: [newton_euler.rhs_fixed(t[i], U[i], params, "spinup")
                               for i in range(k)], repeat=3) / k
    print("right-hand side of eq 48, one evaluation")
    print(f"  C++ (batched, inside the kernel) : {t_batch * 1e6:8.3f} us")
    print(f"  C++ via cffi from Python         : {t_cffi * 1e6:8.3f} us")
    print(f"  pure numpy (Newton-Euler)        : {t_numpy * 1e6:8.1f} us")
    print(f"  ratio numpy / C++                : {t_numpy / t_batch:8.0f} x")

    r = model.simulate(50.0, samples_per_s=200, rtol=1e-8, atol=1e-10)
    wall_k = best_of(lambda: model.simulate(50.0, samples_per_s=200, rtol=1e-8, atol=1e-10),
                     repeat=3)
    print("\n50 s spin-up of Fig 10 (Omega = 10 Hz, tau_s = 0.45 s, C_p = 0.15, rtol 1e-8)")
    print(f"  kernel DOPRI5        : {wall_k:8.3f} s wall, {r.stats['nfev']} evaluations, "
          f"{r.stats['naccept']} steps")
    t_np_end = 50.0 if args.full else 5.0
    t0 = time.perf_counter()
    # The baseline: DOP853 on the pure-numpy Newton-Euler right-hand side.
    from scipy.integrate import solve_ivp
    y0 = np.r_[model.static_equilibrium(), np.zeros(6)]
    sol = solve_ivp(lambda t, y: newton_euler.rhs_fixed(t, y, model.params, "spinup"), (0.0, t_np_end), y0,
                    method="DOP853", t_eval=np.linspace(0, t_np_end, int(200 * t_np_end) + 1),
                    rtol=1e-8, atol=1e-10)
    rn_nfev = sol.nfev
    wall_n = time.perf_counter() - t0
    if not args.full:
        rk5 = model.simulate(5.0, samples_per_s=200, rtol=1e-8, atol=1e-10)
        # Scale by DOP853's evaluations per simulated second over the first 5 s
        # relative to the kernel's own count over 5 s vs 50 s (the same problem).
        scale = r.stats["nfev"] / rk5.stats["nfev"]
        print(f"  solve_ivp + numpy    : {wall_n:8.3f} s for the first 5 s, {rn_nfev} "
              f"evaluations; scaled to 50 s by the kernel's evaluation ratio {scale:.2f}:")
        wall_n *= scale
    print(f"  solve_ivp + numpy    : {wall_n:8.3f} s wall{' (estimated)' if not args.full else ''}")
    print(f"  ratio                : {wall_n / wall_k:8.0f} x")


if __name__ == "__main__":
    main()
