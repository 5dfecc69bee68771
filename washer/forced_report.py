"""The exact stability numbers of issue 11, as a report section of `python -m
washer.figures` (which calls compute, write and markdown) or on its own:

    python -m washer.forced_report [--quick] [--out out/forced]

writes OUT/forced.json (all numbers), OUT/forced.md (a Markdown section) and
OUT/fig4_exact.png/.pdf (the exact critical C_p against Omega beside the averaged and
frozen ones). From Python: `results = compute(params)`, `markdown(results)`,
`plot_fig4(ax, results)`.

Everything comes from washer.forced (route b: shooting with the kernel's variational
flow); the exact curve is obtained by successive one-parameter TR locations in C_p at
each Omega, not by a two-parameter TR-curve continuation.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from washer import forced
from washer.params import load_params

#: Points on the exact Fig 4 curve (lower end to 15 Hz); --quick uses N_CURVE_QUICK.
N_CURVE, N_CURVE_QUICK = 23, 6


def compute(params, n_curve: int = N_CURVE, ends: bool = True, progress=print) -> dict:
    """All numbers of the section: the nominal critical point (exact, averaged, frozen
    C_p, multipliers there), the exact Fig 4 curve (n_curve values of Omega from its lower
    end to 15 Hz), the averaging error at the ends of Table 1's ranges (`ends`), and
    wall times (s)."""
    out = {}
    t = time.perf_counter()
    progress("  forced response: exact critical C_p at nominal values")
    c = forced.critical_cp(params)
    out["nominal"] = {k: c[k] for k in ("Omega", "C_p_exact", "C_p_averaged", "C_p_frozen")}
    out["nominal"].update(
        multipliers=c["multipliers"], critical_multiplier=c["critical_multiplier"],
        critical_exponent=c["critical_exponent"],
        averaged_crossing=c["averaged_eigenvalues"][0], wall=time.perf_counter() - t)
    t = time.perf_counter()
    progress(f"  forced response: exact Fig 4 curve ({n_curve} values of Omega)")
    out["fig4"] = forced.critical_curve(params, n=n_curve)
    out["fig4"]["wall"] = time.perf_counter() - t
    if ends:
        t = time.perf_counter()
        progress("  forced response: averaging error at the ends of Table 1's ranges")
        out["ends"] = forced.averaging_errors(params)
        out["ends_wall"] = time.perf_counter() - t
    return out


def _fmt_mu(mu: complex) -> str:
    return f"{mu.real:+.6f} {'+' if mu.imag >= 0 else '-'} {abs(mu.imag):.6f}i"


def markdown(res: dict) -> str:
    """The report section (Markdown) for the results of `compute`."""
    n = res["nominal"]
    mu = np.asarray(n["multipliers"])
    rel = (n["C_p_exact"] - n["C_p_averaged"]) / n["C_p_averaged"]
    lines = [
        "## Exact stability: Floquet multipliers of the forced response (issue 11)",
        "",
        "The ground-frame equations at constant speed (eq 48, theta = 2 pi Omega t) have a "
        "periodic steady response of period T = 1/Omega; it is computed by Newton shooting "
        "with the kernel's DOPRI5 on the flow and its variational equations (monodromy "
        "matrix in one call), and its stability is that of its Floquet multipliers. The "
        "averaged system's Hopf point approximates a Neimark-Sacker (TR) point of it.",
        "",
        f"| at nominal values (Omega = {n['Omega']:g} Hz) | critical C_p (N m s/rad) |",
        "|---|---|",
        f"| exact (TR of the forced response) | {n['C_p_exact']:.10f} |",
        f"| averaged rotating frame (Hopf) | {n['C_p_averaged']:.10f} |",
        f"| frozen rotating frame, tau0 = 0 (Hopf) | {n['C_p_frozen']:.10f} |",
        "",
        f"Exact minus averaged: {n['C_p_exact'] - n['C_p_averaged']:.3e} "
        f"({rel:.2e} relative); the frozen frame is off by "
        f"{(n['C_p_frozen'] - n['C_p_exact']) / n['C_p_exact']:+.1%}.",
        f"Critical multiplier pair {_fmt_mu(n['critical_multiplier'])} and conjugate "
        f"(|mu| = {abs(n['critical_multiplier']):.12f}, angle "
        f"{np.angle(n['critical_multiplier']):.6f} rad); Floquet exponent "
        f"{n['critical_exponent'].real:+.1e} +- {abs(n['critical_exponent'].imag):.6f}i 1/s: "
        f"the ground-frame whirl, |{abs(n['averaged_crossing'].imag):.6f} - 2 pi Omega| "
        "rad/s with the averaged crossing pair's rotating-frame frequency.",
        "Moduli of all 12 multipliers there: "
        + ", ".join(f"{m:.6f}" for m in np.abs(mu)[::2]) + " (each twice: complex pairs).",
        "",
    ]
    f4 = res["fig4"]
    lines += [
        "### Fig 4 exactly: critical C_p against Omega",
        "",
        f"Lower end of the curve (C_p,crit = 0): exact {f4['Omega_low']['exact']:.6f} Hz, "
        f"averaged {f4['Omega_low']['averaged']:.6f} Hz. Successive one-parameter TR "
        "locations in C_p at each Omega (not a two-parameter TR continuation).",
        "",
        "| Omega (Hz) | exact | averaged | frozen | exact - averaged |",
        "|---|---|---|---|---|",
    ]
    for om, ex, av, fr, er in zip(f4["Omega"], f4["C_p_exact"], f4["C_p_averaged"],
                                  f4["C_p_frozen"], f4["error"]):
        lines.append(f"| {om:.4f} | {ex:.8f} | {av:.8f} | {fr:.6f} | {er:.3e} |")
    if "ends" in res:
        lines += ["", "### Averaging error at the ends of Table 1's ranges", "",
                  "| parameter | value | exact | averaged | frozen | exact - averaged | note |",
                  "|---|---|---|---|---|---|---|"]
        for r in res["ends"]:
            lines.append(f"| {r['name']} | {r['value']:g} | {r['C_p_exact']:.8f} | "
                         f"{r['C_p_averaged']:.8f} | {r['C_p_frozen']:.6f} | "
                         f"{r['error']:.3e} | {r['note']} |")
    lines.append("")
    return "\n".join(lines).replace("nan", "-")


def plot_fig4(ax, res: dict) -> None:
    """Overlay the exact, averaged and frozen critical curves of `compute` on ax."""
    f4 = res["fig4"]
    ax.plot(f4["Omega"], f4["C_p_exact"], "k-", lw=1.5, label="exact (Floquet, TR)")
    ax.plot(f4["Omega"], f4["C_p_averaged"], "C0--", lw=1.2, label="averaged (Hopf)")
    ax.plot(f4["Omega"], f4["C_p_frozen"], "C1:", lw=1.2, label=r"frozen $\tau_0=0$ (Hopf)")
    ax.set_xlabel(r"$\Omega$ (Hz)")
    ax.set_ylabel(r"critical $C_p$ (N m s/rad)")
    ax.legend(loc="best", fontsize=8)


def _jsonable(x):
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return [_jsonable(v) for v in x.tolist()]
    if isinstance(x, complex) or isinstance(x, np.complexfloating):
        return {"re": float(x.real), "im": float(x.imag)}
    if isinstance(x, (float, np.floating)):
        return None if not np.isfinite(x) else float(x)
    return x


def write(out: Path, res: dict) -> list[Path]:
    """OUT/forced.json, OUT/forced.md and OUT/fig4_exact.png/.pdf from `compute`'s results."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "forced.json").write_text(json.dumps(_jsonable(res), indent=1))
    (out / "forced.md").write_text(markdown(res))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 3.5))
    plot_fig4(ax, res)
    fig.tight_layout()
    paths = []
    for ext in ("png", "pdf"):
        paths.append(out / f"fig4_exact.{ext}")
        fig.savefig(paths[-1], dpi=150)
    plt.close(fig)
    return [out / "forced.json", out / "forced.md"] + paths


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m washer.forced_report",
                                 description="The exact stability numbers of issue 11 (Floquet "
                                 "multipliers of the forced response): JSON, Markdown, Fig 4.")
    ap.add_argument("--out", type=Path, default=Path("out/forced"))
    ap.add_argument("--quick", action="store_true",
                    help=f"{N_CURVE_QUICK} points on the Fig 4 curve, no Table 1 ends")
    args = ap.parse_args(argv)
    res = compute(load_params(), N_CURVE_QUICK if args.quick else N_CURVE,
                  ends=not args.quick)
    write(args.out, res)
    print(f"wrote {args.out}/forced.json, forced.md, fig4_exact.png/.pdf", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
