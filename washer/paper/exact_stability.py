"""The exact stability of the forced response as a report section of `python -m
washer.paper` (which calls compute, write and markdown), with the studies behind it
(the exact Fig 4 curve, its lower end, the averaging error at Table 1's ends); on its own:

    python -m washer.paper.exact_stability [--quick] [--out out/forced]

writes OUT/forced.json (all numbers), OUT/forced.md (a Markdown section) and
OUT/fig4_exact.png/.pdf (the exact critical C_p against Omega beside the averaged and
frozen ones). From Python: `results = compute(params)`, `markdown(results)`,
`plot_fig4(ax, results)`.

Everything comes from washer.machine.forced (shooting with the kernel's variational
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

from washer.cont import floquet
from washer.machine import forced, kernel
from washer.machine.layout import PAR_INDEX
from washer.problems import forced as shooting
from washer.problems.rotating import first_hopf, hopf_or_nan
from washer.machine.params import Params, load_params
from washer.atomic import write_text

#: Points on the exact Fig 4 curve (lower end to 15 Hz); --quick uses N_CURVE_QUICK.
N_CURVE, N_CURVE_QUICK = 23, 6


def lower_end(params: Params, kind: str = "exact", bracket=(3.0, 6.0)) -> float:
    """Omega (Hz) of the lower end of the Fig 4 curve, where the critical C_p reaches 0:
    kind 'exact' (TR of the forced response at C_p = 0) or 'averaged' / 'frozen' (Hopf
    of the rotating-frame system at C_p = 0), both located by the engine in Omega. Below it the response is
    stable even without joint damping."""
    q = params.replace(C_p=0.0)
    if kind == "exact":
        rec = shooting.locate_tr(q, "Omega", bracket)[1]
        return float(rec.par[PAR_INDEX["Omega"] - 1])
    return first_hopf(q, "Omega", *bracket, frame=kind)[0]


def critical_curve(params: Params, omegas=None, n: int = 12, omega_max: float = 15.0,
                   rel_bracket: float = 0.05) -> dict:
    """The exact Fig 4 curve: critical C_p (TR of the forced response) against Omega (Hz),
    by successive one-parameter TR locations in C_p at each Omega (not a two-parameter
    TR-curve continuation), with the averaged and frozen Hopf values at the same Omega.

    omegas: Omega values (Hz); default n values from the exact lower end (`lower_end`,
    where C_p,crit = 0; ~4 Hz at the reference values) to omega_max, quadratically
    spaced (denser at the steep lower end). Returns a dict of
    arrays (len(omegas),): Omega, C_p_exact, C_p_averaged, C_p_frozen (nan where the frozen
    system has no Hopf in (0, 2)), error = exact - averaged, mu_angle (rad) of the
    critical multiplier; and 'Omega_low' = {exact, averaged} lower ends (Hz)."""
    low = {"exact": lower_end(params, "exact"), "averaged": lower_end(params, "averaged")}
    if omegas is None:          # denser near the lower end, where the curve is steep
        omegas = low["exact"] + (omega_max - low["exact"]) * np.linspace(0.0, 1.0, n) ** 2
    rows = []
    for om in omegas:
        q = params.replace(Omega=float(om))
        if abs(om - low["exact"]) <= 1e-9 * om:     # the end itself: C_p,crit = 0 by definition
            r = {"Omega": float(om), "C_p_exact": 0.0,
                 "C_p_averaged": hopf_or_nan(q, "averaged")[0],
                 "C_p_frozen": hopf_or_nan(q, "frozen")[0],
                 "critical_multiplier": floquet.torus_pair(
                     shooting.periodic_response(q.replace(C_p=0.0)).multipliers, trivial=False)}
        else:
            r = shooting.critical_cp(q, rel_bracket)
        rows.append(r)
    cp_ex = np.array([r["C_p_exact"] for r in rows])
    cp_av = np.array([r["C_p_averaged"] for r in rows])
    return {"Omega": np.array([r["Omega"] for r in rows]), "C_p_exact": cp_ex,
            "C_p_averaged": cp_av, "C_p_frozen": np.array([r["C_p_frozen"] for r in rows]),
            "error": cp_ex - cp_av,
            "mu_angle": np.array([np.angle(r["critical_multiplier"]) for r in rows]),
            "Omega_low": low}


#: Ends of Table 1's ranges of the parameters of Figs 5-7 (auto_constants/c.washer.hopf.*).
TABLE1_ENDS = (("m_u", 0.01), ("m_u", 2.5), ("R_u", 0.001), ("R_u", 0.25), ("C_a", 0.0),
               ("C_a", 5000.0), ("K_s", 500.0), ("K_s", 4500.0))


def averaging_errors(params: Params, points=TABLE1_ENDS) -> list[dict]:
    """Exact minus averaged critical C_p at parameter points [(name, value), ...] (default:
    the ends of Table 1's ranges of Figs 5-7). Each row: name, value, C_p_exact,
    C_p_averaged, C_p_frozen, error; C_p values nan (and 'note' says why) where there is no
    Hopf/TR point to compare (e.g. stable down to C_p = 0)."""
    rows = []
    for name, value in points:
        row = {"name": name, "value": float(value)}
        try:
            c = shooting.critical_cp(params.replace(**{name: value}))
            row.update(C_p_exact=c["C_p_exact"], C_p_averaged=c["C_p_averaged"],
                       C_p_frozen=c["C_p_frozen"], error=c["C_p_exact"] - c["C_p_averaged"],
                       note="undamped at C_p = 0: neutral, not a Hopf" if
                       c["C_p_averaged"] == 0.0 else "")
        except (ValueError, forced.ShootingError, kernel.KernelError) as exc:
            q = params.replace(**{name: value})
            note = f"no TR point near the averaged Hopf ({type(exc).__name__})"
            try:
                if shooting.periodic_response(q.replace(C_p=0.0)).stable:
                    note = "stable down to C_p = 0: no TR point"
            except (forced.ShootingError, kernel.KernelError):
                pass
            row.update(C_p_exact=np.nan, C_p_averaged=hopf_or_nan(q, "averaged")[0],
                       C_p_frozen=np.nan, error=np.nan, note=note)
        rows.append(row)
    return rows


def compute(params, n_curve: int = N_CURVE, ends: bool = True, progress=print) -> dict:
    """All numbers of the section: the nominal critical point (exact, averaged, frozen
    C_p, multipliers there), the exact Fig 4 curve (n_curve values of Omega from its lower
    end to 15 Hz), the averaging error at the ends of Table 1's ranges (`ends`), and
    wall times (s)."""
    out = {}
    t = time.perf_counter()
    progress("  forced response: exact critical C_p at nominal values")
    c = shooting.critical_cp(params)
    out["nominal"] = {k: c[k] for k in ("Omega", "C_p_exact", "C_p_averaged", "C_p_frozen")}
    out["nominal"].update(
        multipliers=c["multipliers"], critical_multiplier=c["critical_multiplier"],
        critical_exponent=c["critical_exponent"],
        averaged_crossing=c["averaged_eigenvalues"][0], wall=time.perf_counter() - t)
    t = time.perf_counter()
    progress(f"  forced response: exact Fig 4 curve ({n_curve} values of Omega)")
    out["fig4"] = critical_curve(params, n=n_curve)
    out["fig4"]["wall"] = time.perf_counter() - t
    if ends:
        t = time.perf_counter()
        progress("  forced response: averaging error at the ends of Table 1's ranges")
        out["ends"] = averaging_errors(params)
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
        "## Exact stability: Floquet multipliers of the forced response",
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


def plot_fig4_error(ax, res: dict) -> None:
    """Exact minus averaged critical C_p against Omega (absolute, left axis) and relative to
    the exact value (right axis): the difference Fig 4's overlay exists to show and cannot."""
    f4 = res["fig4"]
    om, ex, av = f4["Omega"], f4["C_p_exact"], f4["C_p_averaged"]
    ok = np.isfinite(ex) & np.isfinite(av)
    ax.plot(om[ok], (ex - av)[ok], "k.-", lw=1.2, label="exact - averaged")
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.set_xlabel(r"$\Omega$ (Hz)")
    ax.set_ylabel(r"$\Delta C_p$ (N m s/rad)")
    rel = ok & (np.abs(ex) > 1e-9)
    if rel.any():
        tx = ax.twinx()
        tx.plot(om[rel], 100 * ((ex - av) / ex)[rel], "C3.--", lw=0.9,
                label="relative to exact (right)")
        tx.set_ylabel("relative difference (%)", color="C3")
        tx.tick_params(axis="y", colors="C3")
        tx.grid(False)
    ax.set_title("(b) exact minus averaged", loc="left", fontsize=9)
    ax.legend(loc="upper right", fontsize=7)


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
    write_text(out / "forced.json", json.dumps(_jsonable(res), indent=1))
    write_text(out / "forced.md", markdown(res))
    from washer.plots import style
    fig, (ax, bx) = style.figure(1, 2, figsize=(10, 3.8))
    plot_fig4(ax, res)
    ax.set_title("(a) critical $C_p$: exact, averaged, frozen", loc="left", fontsize=9)
    plot_fig4_error(bx, res)
    paths = style.save(fig, out / "fig4_exact")
    return [out / "forced.json", out / "forced.md"] + paths


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m washer.paper.exact_stability",
                                 description="The exact stability numbers of the forced response (Floquet "
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
