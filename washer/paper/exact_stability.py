"""The exact stability of the forced response as a report section of `python -m
washer.paper` (which calls compute, write and markdown), with the studies behind it
(the exact Fig 4 curve, its lower end, the averaging error at Table 1's ends); on its own:

    python -m washer.paper.exact_stability [--quick] [--out out/forced]

writes OUT/forced.json (all numbers), OUT/forced.md (a Markdown section) and
OUT/fig4_exact.png/.pdf (the exact critical C_p against Omega beside the averaged and
frozen ones). From Python: `results = compute(params)`, `markdown(results)`,
`plot_fig4(ax, results)`.

The nominal critical point comes from washer.machine.forced (shooting with the kernel's
variational flow: one-parameter TR location in C_p). The exact Fig 4 curve is the TR
locus continued in (Omega, C_p) by the engine (collocation of e='washer:forced',
auto_constants/c.washer.forced then c.washer.forced.tr, ISW = 2) from that point up to
Table 1's 15 Hz and down to its lower end, where C_p,crit = 0; one-parameter locations by
shooting at a few of its points and at its lower end are its independent check
(CHECK_TOL).
"""
from __future__ import annotations

import argparse
import json
import re
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

#: Table 1's upper end of Omega (Hz): the locus is continued from the TR point at the
#: nominal speed up to it, and down to the lower end where C_p,crit = 0.
OMEGA_MAX = 15.0
#: Omega values (Hz) of the independent checks (shooting, TR located in C_p alone): the
#: locus's points nearest these, besides its start (params' Omega, whose location the
#: section computes anyway) and its lower end (located in Omega at C_p = 0 by shooting,
#: 6 Hz along the locus from its start); the quick mode has only those two.
CHECK_OMEGAS, CHECK_OMEGAS_QUICK = (5.0, 12.5), ()
#: Agreement (N m s/rad) asked of the locus (collocation, c.washer.forced.tr) with the
#: one-parameter locations (shooting), and (Hz) of their lower ends. Both routes are exact
#: up to their discretisation: Gauss collocation is superconvergent at the mesh points
#: (h^(2 NCOL); C_p to ~1e-11 at NTST = 20 and ~4e-13 at NTST = 10 at the nominal point,
#: c.washer.forced's header), the shooting integrates with DOPRI5 at RTOL = 1e-10; the
#: locus's points are Newton solutions to EPSU = EPSL = 1e-8 (relative corrections), its
#: lower end is located to EPSS = 1e-7 in arclength (Muller's last step far below). 1e-8.
CHECK_TOL = 1e-8
#: Steps of the locus: DS = DSMAX = 1 in the arclength, about 1 Hz in Omega (the constants
#: file's DS = 0.05 grows by 1.1 per step, three Newton iterations each: 3.5 times the
#: steps on the same curve). Quick: NTST = 10 (see CHECK_TOL; at 7 the lower end moves by
#: 2e-8 Hz, at 5 by 3e-7) and about 2 Hz.
LOCUS = {"DS": 1.0, "DSMAX": 1.0}
QUICK_LOCUS = {"NTST": 10, "DS": 2.0, "DSMAX": 2.0}


def _run_ok(res, what: str):
    if res.status != "ok":
        raise RuntimeError(f"exact Fig 4 locus: {what} ended with status {res.status!r}")
    return res


def torus_locus(params: Params, omega_max: float = OMEGA_MAX, quick: bool = False,
                cp_start: float = 0.0) -> dict:
    """The exact Fig 4 curve as one continued locus: the torus bifurcation (TR) of the
    forced response (e='washer:forced', collocation) continued in (Omega, C_p) by the
    engine's ISW = 2 runs of auto_constants/c.washer.forced.tr, in memory (nothing is
    written): c.washer.forced in C_p from cp_start (below the TR point) at params' Omega
    up to its TR1, the generating run
    from TR1 (5 steps, ending at an EP), then the locus from that EP both ways (LOCUS's
    steps; quick: QUICK_LOCUS): up to Omega = omega_max (Table 1's end) and down to
    C_p = 0, the lower end (both UZSTOP).

    Returns a dict: Omega (Hz), C_p (N m s/rad), theta (rad; PAR(12), the angle of the
    critical multiplier pair exp(+-i theta)), slope (dC_p/dOmega, N m s/rad/Hz, from the
    tangent): arrays over the locus's points from its lower end up; 'start' (the index of params' Omega, the TR point both runs start
    from); 'specials' [(type, Omega, C_p, theta)] of the labelled points other than the
    ends; 'ends' {low, high}: {Omega, C_p, theta, why}; 'monotone' (Omega rises along the
    whole locus: no fold in Omega); 'points' of each run (each includes the start);
    'ntst'. RuntimeError if a run fails."""
    from washer.paper import runs
    from washer.run import run
    steps = dict(QUICK_LOCUS if quick else LOCUS)
    mesh = {"NTST": steps.pop("NTST")} if "NTST" in steps else {}
    folder = runs.CONSTANTS_DIR
    one = _run_ok(run(folder / "c.washer.forced", verbose=False, files=False, params=params,
                      PAR={"C_p": cp_start}, STOP=["TR1"], **mesh), "c.washer.forced")
    if not [r for r in one.specials if r.ty == "TR"]:
        raise RuntimeError("exact Fig 4 locus: c.washer.forced found no TR point")
    gen = _run_ok(run(folder / "c.washer.forced.tr", verbose=False, files=False,
                      params=params, restart=one, PAR={}, UZR={}, **mesh),
                  "the generating run of c.washer.forced.tr")
    ep = [r for r in gen.specials if r.ty == "EP"][-1].lab
    ways = {}
    for end, sign in (("low", -1.0), ("high", 1.0)):
        ways[end] = _run_ok(run(
            folder / "c.washer.forced.tr", verbose=False, files=False, params=params,
            restart=gen, PAR={}, IRS=ep, NMX=300, NPR=0, DS=sign * steps["DS"],
            DSMAX=steps["DSMAX"], UZR={},
            UZSTOP={"Omega": [0.0, omega_max], "C_p": [0.0, 10.0]}, **mesh),
            f"c.washer.forced.tr toward the {end} end")
    rows = ways["low"].rows[::-1] + ways["high"].rows[1:]
    ends = {k: w.rows[-1] for k, w in ways.items()}
    # the parameters' places in PAR (the one map, washer.machine.layout); theta is the
    # locus's own PAR(12)
    i_cp, i_om, i_theta = PAR_INDEX["C_p"] - 1, PAR_INDEX["Omega"] - 1, 11

    def why(r):
        if abs(r.par[i_cp]) <= 1e-12:
            return "C_p,crit = 0: the lower end (UZSTOP C_p = 0)"
        if abs(r.par[i_om] - omega_max) <= 1e-9 * omega_max:
            return f"Table 1's end, Omega = {omega_max:g} Hz (UZSTOP)"
        return f"{r.ty} (not a UZSTOP: the locus stops short)"

    def point(r):
        return float(r.par[i_om]), float(r.par[i_cp]), float(r.par[i_theta])

    def slope(r):               # dC_p/dOmega from the tangent d PAR(ICP)/ds
        d = dict(zip(r.icp, r.rldot))
        return d[PAR_INDEX["C_p"]] / d[PAR_INDEX["Omega"]]
    omega = np.array([r.par[i_om] for r in rows])
    return {"Omega": omega,
            "C_p": np.array([r.par[i_cp] for r in rows]),
            "theta": np.array([r.par[i_theta] for r in rows]),
            "slope": np.array([slope(r) for r in rows]),
            "start": len(ways["low"].rows) - 1,
            "specials": [(r.ty,) + point(r) for r in
                         ways["low"].specials[::-1] + ways["high"].specials
                         if not any(r is e for e in ends.values())],
            "ends": {k: dict(zip(("Omega", "C_p", "theta"), point(r)), why=why(r))
                     for k, r in ends.items()},
            "monotone": bool(np.all(np.diff(omega) > 0)),
            "points": {k: len(w.rows) for k, w in ways.items()},
            "ntst": int(ends["high"].ntst)}           # the mesh the locus ran on


#: Half-width (relative) of the bracket of the lower end's shooting location around an
#: estimate (the locus's end), and the location's first step, a quarter of it: the TR
#: point is reached in 3 steps instead of 8 from (3, 6) Hz (locate_tr tests no sign change
#: on its first two steps); where it is not there, the whole bracket.
NEAR_END = 1e-3


def lower_end(params: Params, kind: str = "exact", bracket=(3.0, 6.0),
              near: float | None = None) -> float:
    """Omega (Hz) of the lower end of the Fig 4 curve, where the critical C_p reaches 0:
    kind 'exact' (TR of the forced response at C_p = 0, by shooting: the independent
    check of the locus's end; searched first within +-NEAR_END of `near`, an estimate in
    Hz, if given) or 'averaged' / 'frozen' (Hopf of the rotating-frame system at
    C_p = 0), both located by the engine in Omega. Below it the response is stable even
    without joint damping."""
    q = params.replace(C_p=0.0)
    if kind == "exact":
        if near is not None:
            h = NEAR_END * near
            try:
                rec = shooting.locate_tr(q, "Omega", (near - h, near + h), first_step=h / 4)[1]
                return float(rec.par[PAR_INDEX["Omega"] - 1])
            except (ValueError, forced.ShootingError):
                pass
        rec = shooting.locate_tr(q, "Omega", bracket)[1]
        return float(rec.par[PAR_INDEX["Omega"] - 1])
    return first_hopf(q, "Omega", *bracket, frame=kind)[0]


def critical_curve(params: Params, quick: bool = False, omega_max: float = OMEGA_MAX,
                   nominal: dict | None = None) -> dict:
    """The exact Fig 4 curve: critical C_p (TR of the forced response) against Omega (Hz)
    as the continued TR locus (`torus_locus`) from the exact lower end (C_p,crit = 0) to
    omega_max, with the averaged and frozen Hopf values at its points, and its
    independent checks: one-parameter TR locations in C_p by shooting
    (shooting.critical_cp) at params' Omega (`nominal`: that result, if already computed)
    and at the locus's points nearest CHECK_OMEGAS, and the lower end located in Omega at
    C_p = 0 by shooting.

    Returns a dict: 'locus' (torus_locus's); arrays over the locus's points: Omega,
    C_p_exact, C_p_averaged, C_p_frozen (nan where there is no Hopf point), error =
    exact - averaged, mu_angle (rad, the critical multiplier's angle); 'Omega_low'
    {exact (the locus's end), shooting, averaged}; 'checks' [{Omega, C_p_locus,
    C_p_shooting, difference}]; 'check_tol' (CHECK_TOL)."""
    # c.washer.forced starts at 0.8 of the nominal critical C_p where it is known: 4 steps
    # to its TR point instead of 9 from 0, and |mu| - 1 = +2.1e-3 there, far beyond the
    # stability tolerance 1e-5 that the count must cross
    loc = torus_locus(params, omega_max, quick,
                      0.0 if nominal is None else 0.8 * nominal["C_p_exact"])
    om, cp = loc["Omega"], loc["C_p"]
    low = {"exact": loc["ends"]["low"]["Omega"], "averaged": lower_end(params, "averaged")}
    low["shooting"] = lower_end(params, "exact", near=low["exact"])
    at = sorted({loc["start"]} | {int(np.argmin(np.abs(om - x)))
                                  for x in (CHECK_OMEGAS_QUICK if quick else CHECK_OMEGAS)})
    checks = []
    for i in at:
        # the start is params' Omega up to the TR location's accuracy (~1e-10 Hz): C_p
        # moves by that times dC_p/dOmega (< 0.1), far below CHECK_TOL
        c = nominal if nominal is not None and abs(om[i] - nominal["Omega"]) <= 1e-9 else \
            shooting.critical_cp(params.replace(Omega=float(om[i])))
        checks.append({"Omega": float(om[i]), "C_p_locus": float(cp[i]),
                       "C_p_shooting": float(c["C_p_exact"]),
                       "difference": float(cp[i] - c["C_p_exact"])})
    hopf = np.array([[hopf_or_nan(params.replace(Omega=float(x)), frame)[0]
                      for frame in ("averaged", "frozen")] for x in om])
    return {"locus": loc, "Omega": om, "C_p_exact": cp, "C_p_averaged": hopf[:, 0],
            "C_p_frozen": hopf[:, 1], "error": cp - hopf[:, 0], "mu_angle": loc["theta"],
            "Omega_low": low, "checks": checks, "check_tol": CHECK_TOL}


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


def compute(params, quick: bool = False, ends: bool = True, progress=print) -> dict:
    """All numbers of the section: the nominal critical point (exact, averaged, frozen
    C_p, multipliers there), the exact Fig 4 curve (`critical_curve`: the TR locus from its
    lower end to 15 Hz and its checks; quick: the quick mode's locus, fewer table rows and
    checks), the averaging error at the ends of Table 1's ranges (`ends`), and wall
    times (s)."""
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
    progress("  forced response: exact Fig 4 curve (TR locus in Omega and C_p)")
    out["fig4"] = critical_curve(params, quick, nominal=c)
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
    loc, low = f4["locus"], f4["Omega_low"]
    ends = loc["ends"]
    found = ", ".join(f"{t} at Omega = {om:.6f} Hz (C_p = {cp:.8f}, theta = {th:.6f})"
                      for t, om, cp, th in loc["specials"]) or "none"
    lines += [
        "### Fig 4 exactly: critical C_p against Omega",
        "",
        "The curve is the torus bifurcation (TR) of the forced response continued in "
        "(Omega, C_p): collocation of e='washer:forced' (NTST = "
        f"{loc['ntst']}, NCOL = 4), the engine's ISW = 2 runs of "
        "auto_constants/c.washer.forced.tr from the TR point at "
        f"{res['nominal']['Omega']:g} Hz, both ways: {len(loc['Omega'])} points from "
        f"{ends['low']['Omega']:.6f} to {ends['high']['Omega']:g} Hz.",
        "",
        f"- Ends: low at Omega = {ends['low']['Omega']:.9f} Hz, {ends['low']['why']}; "
        f"high at {ends['high']['Omega']:g} Hz (C_p = {ends['high']['C_p']:.8f}), "
        f"{ends['high']['why']}.",
        f"- Omega {'rises along the whole locus: no fold' if loc['monotone'] else 'turns back: the locus folds'}"
        f" in Omega. The critical pair's angle theta runs from "
        f"{ends['low']['theta']:.6f} rad at the lower end to {ends['high']['theta']:.6f} "
        "rad at the upper, clear of the strong resonances R1 (0), R4 (pi/2), R3 (2 pi/3) "
        f"and R2 (pi). Special points the engine labels between the ends: {found}.",
        f"- Lower end (C_p,crit = 0): locus {low['exact']:.9f} Hz; TR located in Omega at "
        f"C_p = 0 by shooting {low['shooting']:.9f} Hz (difference "
        f"{low['exact'] - low['shooting']:+.1e}); averaged Hopf {low['averaged']:.6f} Hz. "
        "Below it the response is stable even without joint damping.",
        "",
        "Independent check, one-parameter TR locations in C_p by shooting (DOPRI5 at "
        "RTOL = 1e-10) at points of the locus; both routes are exact up to their "
        f"discretisation, so they must agree to {f4['check_tol']:.0e} (collocation is "
        "superconvergent, ~1e-11 here):",
        "",
        "| Omega (Hz) | locus | shooting | locus - shooting |",
        "|---|---|---|---|",
    ]
    for c in f4["checks"]:
        lines.append(f"| {c['Omega']:.6f} | {c['C_p_locus']:.12f} | {c['C_p_shooting']:.12f} "
                     f"| {c['difference']:+.1e} |")
    lines += [
        "",
        "The locus's points beside the averaged and frozen Hopf values at their Omega "
        "(C_p in N m s/rad; theta in rad):",
        "",
        "| Omega (Hz) | exact | averaged | frozen | exact - averaged | theta |",
        "|---|---|---|---|---|---|",
    ]
    for om, ex, av, fr, er, th in zip(f4["Omega"], f4["C_p_exact"], f4["C_p_averaged"],
                                      f4["C_p_frozen"], f4["error"], f4["mu_angle"]):
        lines.append(f"| {om:.4f} | {max(ex, 0.0):.8f} | {av:.8f} | {fr:.6f} | {er:.3e} "
                     f"| {th:.4f} |")
    if "ends" in res:
        lines += ["", "### Averaging error at the ends of Table 1's ranges", "",
                  "| parameter | value | exact | averaged | frozen | exact - averaged | note |",
                  "|---|---|---|---|---|---|---|"]
        for r in res["ends"]:
            lines.append(f"| {r['name']} | {r['value']:g} | {r['C_p_exact']:.8f} | "
                         f"{r['C_p_averaged']:.8f} | {r['C_p_frozen']:.6f} | "
                         f"{r['error']:.3e} | {r['note']} |")
    lines.append("")
    return re.sub(r"\bnan\b", "-", "\n".join(lines))


def plot_fig4(ax, res: dict) -> None:
    """Overlay the exact (the TR locus, a line; its one-parameter checks, markers),
    averaged and frozen critical curves of `compute` on ax."""
    from scipy.interpolate import CubicHermiteSpline
    f4 = res["fig4"]
    loc = f4["locus"]
    # between the locus's points (~1 Hz apart), the cubic through their values and
    # tangents: error O(h^4), where straight segments show corners at the steep lower end
    om = np.linspace(loc["Omega"][0], loc["Omega"][-1], 400)
    ax.plot(om, CubicHermiteSpline(loc["Omega"], loc["C_p"], loc["slope"])(om), "k-",
            lw=1.5, label="exact (TR locus)")
    ax.plot(loc["Omega"], loc["C_p"], "k.", ms=3)
    chk = f4["checks"]
    ax.plot([c["Omega"] for c in chk] + [f4["Omega_low"]["shooting"]],
            [c["C_p_shooting"] for c in chk] + [0.0], "ko", mfc="none", ms=6,
            label="exact check (shooting, TR in one parameter)")
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
                    help="a coarser Fig 4 locus, checked at the nominal point and the lower "
                    "end only, no Table 1 ends")
    args = ap.parse_args(argv)
    res = compute(load_params(), args.quick, ends=not args.quick)
    write(args.out, res)
    print(f"wrote {args.out}/forced.json, forced.md, fig4_exact.png/.pdf", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
