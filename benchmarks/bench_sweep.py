"""Sweep speed: points per second for each kind on 1 and 2 Dask workers (and in
process), the parallel efficiency, and batched-kernel against per-point time
responses.

    python benchmarks/bench_sweep.py [--quick]

1. Kinds. For each kind a grid over (m_u, Omega) (stability: 400 points;
   critical: 64; response: 64 ground-frame spin-ups of 20 s) is run serially
   in this process and on a LocalCluster of 1 and 2 single-threaded worker
   processes (started beforehand: the start-up is timed on its own).
   Efficiency = rate(2 workers) / (2 x rate(1 worker)).
2. Batched responses. The kernel integrates one parameter set per call (C++
   DOPRI5, one call per chunk). The alternative is a DOPRI5 written in numpy over
   n parameter sets at once, each of its 7 stages one `kernel.rhs_fixed_batch`
   call (GIL released) with a common step size (the largest error of the batch
   decides, as a vectorised solver does). Both integrate n constant-speed
   responses over the same time with the same tolerances; the table gives the
   time per point and the largest difference of the final states.

Each figure is the best of --repeat runs (default 3). On a shared 2-core machine
other work shows in the load average printed before and after: with it above
~2, two workers cannot get two cores and the efficiency reads low.
"""
from __future__ import annotations

import argparse
import logging
import os
import tempfile
import time

import numpy as np

import washer
from washer.machine import kernel
from washer.sweep import parse_spec, run


def kind_spec(kind: str, n: tuple[int, int]) -> str:
    opts = {"stability": "", "critical": "[study.critical]\nfrom = 0.0\nto = 3.0\n",
            "response": "[study.response]\nsystem = 'fixed'\nlaw = 'spinup'\nt_end = 20.0\n"
                        "window = 5.0\n"}[kind]
    return (f"[[study]]\nname = '{kind}'\nkinds = ['{kind}']\n[study.vary]\n"
            f"m_u = {{from = 0.3, to = 2.5, n = {n[0]}}}\n"
            f"Omega = {{from = 6.0, to = 15.0, n = {n[1]}}}\n" + opts)


def timed_run(spec, repeat: int, **kw) -> float:
    """Points per second, best of `repeat` runs (each in a fresh folder)."""
    best = 0.0
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as out:
            t0 = time.perf_counter()
            df = run(spec, out=out, plot=False, **kw)
            best = max(best, len(df) / (time.perf_counter() - t0))
    return best


def bench_kinds(quick: bool, repeat: int) -> None:
    from distributed import Client, LocalCluster
    logging.getLogger("distributed").setLevel(logging.ERROR)
    sizes = {"stability": (20, 20), "critical": (8, 8), "response": (8, 8)}
    if quick:
        sizes = {k: (max(2, a // 2), max(2, b // 2)) for k, (a, b) in sizes.items()}
    clients = {}
    for w in (1, 2):
        t0 = time.perf_counter()
        cluster = LocalCluster(n_workers=w, threads_per_worker=1, processes=True,
                               dashboard_address=":0", silence_logs=logging.ERROR)
        client = Client(cluster)
        client.run(lambda: __import__("washer.sweep.tasks"))      # workers load the kernel
        clients[w] = (cluster, client)
        print(f"LocalCluster({w} worker{'s' if w > 1 else ''}) start-up + import: "
              f"{time.perf_counter() - t0:.2f} s")
    print(f"\n{'kind':10s} {'points':>6s} {'serial':>9s} {'1 worker':>9s} {'2 workers':>9s} "
          f"{'speed-up':>8s} {'efficiency':>10s}   (points/s)")
    try:
        for kind, n in sizes.items():
            spec = parse_spec(kind_spec(kind, n), f"<bench {kind}>")
            serial = timed_run(spec, repeat, serial=True)
            r1 = timed_run(spec, repeat, client=clients[1][1])
            r2 = timed_run(spec, repeat, client=clients[2][1])
            print(f"{kind:10s} {n[0] * n[1]:6d} {serial:9.1f} {r1:9.1f} {r2:9.1f} "
                  f"{r2 / r1:8.2f} {r2 / (2 * r1):10.2f}")
    finally:
        for cluster, client in clients.values():
            client.close()
            cluster.close()


# ----------------------------------------------------------- batched DOPRI5 (numpy)

# Dormand-Prince 5(4) tableau (Hairer, Norsett, Wanner I, Table 5.2).
C = np.array([0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1, 1])
A = [[], [1 / 5], [3 / 40, 9 / 40], [44 / 45, -56 / 15, 32 / 9],
     [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729],
     [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
     [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]]
B = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0])
E = B - np.array([5179 / 57600, 0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100,
                  1 / 40])


def dopri5_batch(Y0: np.ndarray, P: np.ndarray, t_end: float, rtol: float, atol: float,
                 law: str = "constant"):
    """Final states (n, 12) of n ground-frame responses, one step size for all
    (accepted when the worst row's error norm <= 1). Returns (Y, steps, rhs calls)."""
    Y = Y0.copy()
    n = len(Y)
    t, h, steps, calls = 0.0, 1e-3, 0, 0
    K = np.empty((7, n, 12))
    K[0] = kernel.rhs_fixed_batch(np.zeros(n), Y, P, law)
    calls += 1
    while t < t_end:
        h = min(h, t_end - t)
        for s in range(1, 7):
            Ys = Y + h * np.tensordot(A[s], K[:s], axes=1)
            K[s] = kernel.rhs_fixed_batch(np.full(n, t + C[s] * h), Ys, P, law)
        calls += 6
        Ynew = Y + h * np.tensordot(B, K, axes=1)
        err = h * np.tensordot(E, K, axes=1)
        sc = atol + rtol * np.maximum(np.abs(Y), np.abs(Ynew))
        e = np.sqrt(np.mean((err / sc) ** 2, axis=1)).max()
        if e <= 1.0:
            t, Y = t + h, Ynew
            K[0] = K[6]                                     # FSAL
            steps += 1
        h *= min(5.0, max(0.2, 0.9 * (e if e > 0 else 1e-10) ** -0.2))
    return Y, steps, calls


def bench_batched(quick: bool, repeat: int) -> None:
    base = washer.load_params()
    t_end, rtol, atol = (2.0 if quick else 5.0), 1e-8, 1e-10
    print(f"\nTime responses, ground frame at constant speed, {t_end:g} s, rtol {rtol:g}, "
          f"atol {atol:g}; n parameter sets over (m_u, Omega, C_p):")
    print(f"{'n':>5s} {'per-point kernel':>17s} {'batched numpy':>14s} {'ratio':>6s} "
          f"{'steps (batch)':>13s} {'max |dY| final':>15s}")
    rng = np.random.default_rng(0)
    for n in ((1, 16, 64) if quick else (1, 16, 64, 256)):
        ps = [base.replace(m_u=rng.uniform(0.3, 2.5), Omega=rng.uniform(6, 15),
                           C_p=rng.uniform(0.05, 0.3)) for _ in range(n)]
        P = np.array([p.vector() for p in ps])
        Y0 = np.array([np.r_[washer.Model(p).static_equilibrium(), np.zeros(6)] for p in ps])
        t_point = t_batch = np.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            ref = np.array([kernel.integrate("fixed", "constant", 0.0, Y0[i], P[i],
                                             np.array([t_end]), rtol, atol)[0][-1]
                            for i in range(n)])
            t_point = min(t_point, (time.perf_counter() - t0) / n)
            t0 = time.perf_counter()
            Yb, steps, _ = dopri5_batch(Y0, P, t_end, rtol, atol)
            t_batch = min(t_batch, (time.perf_counter() - t0) / n)
        print(f"{n:5d} {1e3 * t_point:14.2f} ms {1e3 * t_batch:11.2f} ms {t_batch / t_point:6.1f} "
              f"{steps:13d} {np.abs(Yb - ref).max():15.2e}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller sizes, one repetition")
    ap.add_argument("--repeat", type=int, default=3, help="best of this many runs (default 3)")
    args = ap.parse_args()
    repeat = 1 if args.quick else args.repeat
    print(f"load average before: {os.getloadavg()[0]:.2f} (2 cores; > 0 means other work)")
    bench_kinds(args.quick, repeat)
    bench_batched(args.quick, repeat)
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
