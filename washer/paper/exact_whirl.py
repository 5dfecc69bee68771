"""The exact whirl beside the averaged one: the invariant circles of the T/2 map
(`washer.problems.torus`) from the torus point down to C_p = 0, against the averaged rotating
frame's periodic orbits (`washer.paper.whirl`, c.washer.po) along the whole family and
against a long simulation of the unaveraged equations; and the joint damping needed to
keep the whirl within a clearance.

    res = compute(params, averaged=fam)       # fam: whirl.whirl_family(...) (or None: run it)
    markdown(res, "exact_whirl.png"); plot(res, out / "exact_whirl")

Every comparison is against something computed independently of the circles: the
averaged orbits come from collocation on another system (first-order averaging), the
simulation integrates eq 48 from a state 1 % off the circle and is only sampled.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from washer.problems import torus
from washer.problems.rotating import averaged_hopf

#: Length of the simulation (s) judged against the C_p = 0 circle, and of the window at its
#: end. The slowest normal mode decays at ~0.0116 1/s at C_p = 0 (the circle's leading
#: normal multiplier), so 300 s shrinks the start offset ~30-fold (120 s: ~4-fold).
T_SIM, T_SIM_QUICK, WINDOW = 300.0, 120.0, 20.0
#: Largest continuation step of the quick mode (fewer, farther apart circles).
QUICK_DS_MAX = 0.3
#: Clearances (m) for which the needed joint damping is tabulated.
CLEARANCES = (0.005, 0.01, 0.02, 0.03, 0.05, 0.1, 0.2, 0.3)
#: Circles (nearest C_p) a simulation is set beside: along the family, and at C_p = 0.
SIM_AT, SIM_AT_QUICK = (0.09, 0.05, 0.0), (0.0,)
#: Offset of the simulation's start from the circle (relative, in the scaled state).
START_OFFSET = 0.01


def averaged_family(params, progress=print):
    """Run c.washer then c.washer.po in memory (the second restarts from the first's
    Branch; nothing is written): the averaged whirl family."""
    from washer.paper import runs, whirl
    from washer.run import run
    eq = run(runs.CONSTANTS_DIR / "c.washer", verbose=False, files=False)
    return whirl.whirl_family(runs.CONSTANTS_DIR, progress=progress, restart=eq)


def along_family(w: torus.ExactWhirl, fam) -> dict:
    """The averaged family interpolated at the exact circles' C_p (both monotone in C_p):
    relative differences (averaged - exact) / exact of r_mean, r_max, eps3 mean, tilt and
    whirl frequency, arrays over the exact circles that lie inside the averaged family's
    C_p range."""
    o = np.argsort(fam.C_p)
    cp = fam.C_p[o]
    inside = (w.value >= cp[0] - 1e-12) & (w.value <= cp[-1] + 1e-12)
    Om = w.params["Omega"]

    def avg(a):
        return np.interp(w.value[inside], cp, np.asarray(a)[o])

    f_avg = Om - 1.0 / avg(fam.period)   # rotating-frame whirl is backward at Omega - f
    ex = {"r_mean": w.r_mean[inside], "r_max": w.r_max[inside],
          "z_mean": 0.5 * (w.z_min + w.z_max)[inside], "tilt_max": w.tilt_max[inside],
          "f_whirl": w.f_whirl[inside]}
    av = {"r_mean": avg(fam.r_mean), "r_max": avg(fam.r_max),
          "z_mean": 0.5 * (avg(fam.z_min) + avg(fam.z_max)), "tilt_max": avg(fam.tilt_max),
          "f_whirl": f_avg}
    rel = {k: (av[k] - ex[k]) / ex[k] for k in ex}
    # The same at equal distance below each system's own critical value: near the birth
    # the radius goes like sqrt(C_p,crit - C_p), so the small shift of the critical value
    # (exact - averaged) dominates the comparison at equal C_p there.
    shift = w.birth.value - fam.hopf_C_p
    r_shift = np.interp(w.value[inside] - shift, cp, np.asarray(fam.r_mean)[o])
    rel_shifted = (r_shift - ex["r_mean"]) / ex["r_mean"]
    return {"C_p": w.value[inside], "exact": ex, "averaged": av, "rel": rel,
            "shift": float(shift), "rel_shifted_r_mean": rel_shifted}


def compute(params, averaged=None, quick: bool = False, progress=print) -> dict:
    """Exact family, its comparison with the averaged one along the family, the long
    simulation at C_p = 0, and the damping needed for each of CLEARANCES."""
    out = {}
    t0 = time.perf_counter()
    progress("  exact whirl: invariant circles of the T/2 map, torus point to C_p = 0")
    w = torus.exact_whirl(params, ds_max=QUICK_DS_MAX if quick else torus.DS_MAX)
    out["whirl"], out["wall_family"] = w, time.perf_counter() - t0
    if averaged is None:
        averaged = averaged_family(params, progress)
    out["averaged"] = averaged
    out["along"] = along_family(w, averaged)
    t1 = time.perf_counter()
    t_sim = T_SIM_QUICK if quick else T_SIM
    out["simulations"] = []
    for target in (SIM_AT_QUICK if quick else SIM_AT):
        c = w.circles[int(np.argmin(np.abs(w.value - target)))]
        progress(f"  exact whirl: {t_sim:g} s simulation of eq 48 at C_p = {c.p:.4f} "
                 "beside the circle")
        xi0 = c(np.array([0.3]))[0]
        xi0 = xi0 + START_OFFSET * (xi0 - np.r_[0, 0, xi0[2], 0, 0, xi0[5], np.zeros(6)])
        sim = torus.against_simulation(torus.params_at(params, "C_p", c.p), c, xi0, t_sim,
                                       WINDOW)
        k = int(np.argmin(np.abs(w.value - c.p)))
        sim.update(C_p=c.p, r_mean_circle=float(w.r_mean[k]), f_circle=float(w.f_whirl[k]))
        out["simulations"].append(sim)
    out["simulation"] = out["simulations"][-1]          # the C_p = 0 one
    out["wall_simulation"] = time.perf_counter() - t1
    out["clearance"] = {"clearance": np.array(CLEARANCES),
                        "C_p": torus.damping_for_clearance(w, CLEARANCES)}
    out["r_birth"] = float(np.hypot(*w.birth.xi[:2]))
    out["growth"] = torus.growth_coefficient(w)
    from washer.sweep.tasks import whirl_growth
    out["growth_normal_form"] = whirl_growth(params, "C_p", averaged_hopf(params)[0])[0]
    return out


def _pct(x) -> str:
    return f"{100 * x:+.2f} %"


def markdown(res: dict, figure: str) -> str:
    w, a, s = res["whirl"], res["along"], res["simulation"]
    i0 = int(np.argmin(np.abs(w.value)))
    j0 = int(np.argmin(np.abs(a["C_p"])))
    rel = a["rel"]
    worst = {k: float(np.abs(v).max()) for k, v in rel.items()}
    ok_sim = all(x["distance_end"] < 0.01 * x["r_mean_circle"]
                 and abs(x["decay_rate"] / x["predicted_rate"] - 1) < 0.05
                 for x in res["simulations"])
    stable = bool(np.all(w.mu_max < 1.0))
    lines = [
        "## The exact whirl: the invariant torus from the torus point to C_p = 0",
        "",
        "Past the torus (TR) point the forced response is replaced by a two-frequency motion "
        "(the spin and the whirl): an invariant circle of the stroboscopic map over half a "
        "forcing period in the rotating frame. It is computed without averaging "
        "(`washer.problems.torus`: Fourier collocation in the circle's angle, "
        f"{w.circles[0].N} nodes, the map and its Jacobian from the kernel's variational "
        f"flow), born at the TR point C_p = {w.birth.value:.6f} and continued by the "
        f"continuation engine to C_p = 0 ({len(w.value)} circles, "
        f"{res['wall_family']:.0f} s, {'end value reached' if w.reached else w.branch.status}). "
        f"Fourier tail (last mode over the first) at C_p = 0: {w.tail[i0]:.1e}.",
        "",
        "| at C_p = 0 | mean r (mm) | r range (mm) | eps3 (mm) | max tilt (deg) | whirl (Hz) |",
        "|---|---|---|---|---|---|",
        f"| exact (invariant circle) | {1e3 * w.r_mean[i0]:.1f} | {1e3 * w.r_min[i0]:.1f} - "
        f"{1e3 * w.r_max[i0]:.1f} | {1e3 * w.z_min[i0]:.1f} - {1e3 * w.z_max[i0]:.1f} | "
        f"{np.degrees(w.tilt_max[i0]):.2f} | {w.f_whirl[i0]:.5f} |",
        f"| averaged (periodic orbit) | {1e3 * a['averaged']['r_mean'][j0]:.1f} | | "
        f"{1e3 * a['averaged']['z_mean'][j0]:.1f} (mean) | "
        f"{np.degrees(a['averaged']['tilt_max'][j0]):.2f} | {a['averaged']['f_whirl'][j0]:.5f} |",
        f"| simulation of eq 48, last {s['window']:.0f} s of {s['t_end']:.0f} s | "
        f"{1e3 * s['r_mean']:.1f} | {1e3 * s['r_min']:.1f} - {1e3 * s['r_max']:.1f} | "
        f"{1e3 * s['z_min']:.1f} - {1e3 * s['z_max']:.1f} | | {s['f_whirl']:.5f} |",
        "",
        f"Averaged minus exact along the family ({len(a['C_p'])} circles from the TR point to "
        f"C_p = 0), largest relative difference: mean radius {100 * worst['r_mean']:.2f} %, "
        f"largest radius {100 * worst['r_max']:.2f} %, height {100 * worst['z_mean']:.2f} %, "
        f"tilt {100 * worst['tilt_max']:.2f} %, whirl frequency {100 * worst['f_whirl']:.2f} %; "
        f"at C_p = 0: {_pct(rel['r_mean'][j0])}, {_pct(rel['r_max'][j0])}, "
        f"{_pct(rel['z_mean'][j0])}, {_pct(rel['tilt_max'][j0])}, {_pct(rel['f_whirl'][j0])}. "
        "Averaging is exact to first order at the birth; the terms it drops grow with the "
        "tilt (the Cardan angles' 2 Omega harmonic), so its whirl is too small and too slow "
        "by a few per cent where the tub tilts most. Near the birth the relative difference "
        "at equal C_p is the two critical values' shift "
        f"({a['shift']:.2e} N m s/rad) seen through the square root: at equal distance "
        "below each system's own critical value the mean radii differ by "
        f"{100 * abs(a['rel_shifted_r_mean'][0]):.2f} % at the first circle compared.",
        "",
        "Simulations of eq 48 at constant speed beside circles along the family (each "
        f"started {100 * START_OFFSET:.0f} % off its circle, sampled every half period, "
        f"judged over its last {s['window']:.0f} s):",
        "",
        "| C_p | mean r: circle / simulation (mm) | whirl: circle / simulation (Hz) | "
        "decay onto the circle: measured / predicted (1/s) | distance at the end (mm) |",
        "|---|---|---|---|---|",
        *[f"| {x['C_p']:.4f} | {1e3 * x['r_mean_circle']:.2f} / {1e3 * x['r_mean']:.2f} | "
          f"{x['f_circle']:.6f} / {x['f_whirl']:.6f} | {x['decay_rate']:.5f} / "
          f"{x['predicted_rate']:.5f} | {1e3 * x['distance_end']:.3f} |"
          for x in res["simulations"]],
        "",
        f"The simulation (eq 48 at constant speed, started {100 * START_OFFSET:.0f} % off the "
        f"C_p = 0 circle, sampled every half period) ends {1e3 * s['distance_end']:.2f} mm "
        f"(scaled state norm) from the circle; its distance decays at {s['decay_rate']:.5f} "
        f"1/s where the circle's leading normal multiplier predicts {s['predicted_rate']:.5f} "
        f"1/s, and its rotation number is {s['rho']:.8f} against the circle's "
        f"{s['rho_circle']:.8f}. Verdict: **{'reproduced' if ok_sim else 'not reproduced'}** "
        "(rule, for every simulation: within 1 % of the mean radius at the end, decay rate "
        "within 5 %). "
        f"Stability: the largest normal multiplier along the family is {w.mu_max.max():.6f} "
        f"per half period ({'every circle attracting' if stable else 'some circles repel'}).",
        "",
        f"![The exact whirl against the averaged one]({figure})",
        "",
    ]
    return "\n".join(lines)


def clearance_markdown(res: dict, figure: str) -> str:
    """The design criterion: joint damping needed to keep the whirl within a clearance."""
    w, cl = res["whirl"], res["clearance"]
    crit = w.birth.value
    def row(c, v):
        if np.isnan(v):
            why = ("the forced response alone reaches it" if c < res["r_birth"] else
                   "beyond the whirl at C_p = 0")
            return f"| {1e3 * c:.0f} | {why} | |"
        return f"| {1e3 * c:.0f} | {v:.6f} | {100 * (crit - v) / crit:.3f} % |"
    rows = [row(c, v) for c, v in zip(cl["clearance"], cl["C_p"])]
    i0 = int(np.argmin(np.abs(w.value)))
    return "\n".join([
        "## A design criterion: joint damping for a given clearance",
        "",
        f"The torus point is supercritical: below C_p,crit = {crit:.6f} N m s/rad the tub "
        "settles on the whirl, whose amplitude (about the forced response, "
        f"{1e3 * res['r_birth']:.2f} mm off the axis with the imbalance) grows like "
        f"{res['growth']:.2f} sqrt(C_p,crit - C_p) m near the point (fitted to the exact "
        "circles of amplitude <= 20 mm; the averaged Hopf point's normal form, which the "
        f"sweeps' clearance criterion uses, gives {res['growth_normal_form']:.2f}). The damping at which the largest offset r_max "
        "reaches a clearance (exact family):",
        "",
        "| clearance (mm) | C_p needed (N m s/rad) | below C_p,crit |",
        "|---|---|---|",
        *rows,
        "",
        "So a clearance buys almost nothing: a 30 mm gap is used up within a fraction of a "
        "per cent below the critical value, and the design value is C_p,crit itself (with "
        "the margin the estimated parameters need, see the sensitivity study). The whirl "
        f"amplitudes past that (r up to {1e3 * w.r_max[i0]:.0f} mm, tilt "
        f"{np.degrees(w.tilt_max[i0]):.0f} degrees at C_p = 0) are internal to the model: a real "
        "cabinet would stop the tub long before, so they say how violently the machine "
        "would hit its cabinet, not how it would move.",
        "",
        f"![Whirl amplitude against C_p with clearances]({figure})",
        "",
    ])


def plot(res: dict, stem: Path) -> list[Path]:
    """(a) mean and largest whirl radius against C_p, exact and averaged, the simulations';
    (b) averaged minus exact (relative) along the family; (c) whirl frequency; (d) the
    leading normal multiplier of the circles."""
    from washer.plots.style import figure, save
    w, a, s, fam = res["whirl"], res["along"], res["simulation"], res["averaged"]
    fig, ax = figure(2, 2, figsize=(9.5, 6.4))
    p = ax[0, 0]
    p.plot(w.value, 1e3 * w.r_mean, "k-", label="exact: mean r")
    p.plot(w.value, 1e3 * w.r_max, "k--", label="exact: largest r")
    p.plot(fam.C_p, 1e3 * fam.r_mean, "C0-", label="averaged: mean r")
    p.plot(fam.C_p, 1e3 * fam.r_max, "C0--", label="averaged: largest r")
    sims = res.get("simulations", [s])
    p.errorbar([x.get("C_p", 0.0) for x in sims], [1e3 * x["r_mean"] for x in sims],
               yerr=[[1e3 * (x["r_mean"] - x["r_min"]) for x in sims],
                     [1e3 * (x["r_max"] - x["r_mean"]) for x in sims]], fmt="s", color="C3",
               ms=4, capsize=3, label=f"simulations of eq 48, last {s['window']:.0f} s of "
               f"{s['t_end']:.0f} s")
    p.set_xlabel(r"$C_p$ (N m s/rad)")
    p.set_ylabel("whirl radius r (mm)")
    p.set_title("(a) whirl radius", loc="left", fontsize=9)
    p.legend(fontsize=7)
    p = ax[0, 1]
    for k, lab in (("r_mean", "mean r"), ("r_max", "largest r"), ("z_mean", r"height $\varepsilon_3$"),
                   ("tilt_max", "largest tilt"), ("f_whirl", "whirl frequency")):
        p.plot(a["C_p"], 100 * a["rel"][k], label=lab)
    p.axhline(0.0, color="k", lw=0.6)
    p.set_xlabel(r"$C_p$ (N m s/rad)")
    p.set_ylabel("(averaged - exact) / exact (%)")
    p.set_title("(b) error of averaging along the family", loc="left", fontsize=9)
    p.legend(fontsize=7)
    p = ax[1, 0]
    p.plot(w.value, w.f_whirl, "k-", label="exact (rotation number)")
    p.plot(a["C_p"], a["averaged"]["f_whirl"], "C0-", label="averaged (orbit period)")
    p.plot([x.get("C_p", 0.0) for x in sims], [x["f_whirl"] for x in sims], "s", color="C3",
           ms=4, label="simulations")
    p.set_xlabel(r"$C_p$ (N m s/rad)")
    p.set_ylabel("ground-frame whirl frequency (Hz)")
    p.set_title("(c) whirl frequency", loc="left", fontsize=9)
    p.legend(fontsize=7)
    p = ax[1, 1]
    p.plot(w.value, w.mu_max, "k.-")
    p.axhline(1.0, color="k", lw=0.6)
    p.set_xlabel(r"$C_p$ (N m s/rad)")
    p.set_ylabel(r"largest normal $|\lambda|$ per $T/2$")
    p.set_title("(d) stability of the circles (below 1: attracting)", loc="left", fontsize=9)
    return save(fig, Path(stem))


def plot_clearance(res: dict, stem: Path) -> list[Path]:
    """Largest whirl offset against C_p (exact family; the forced response above the TR
    point), with the clearances of CLEARANCES drawn and the damping each needs marked."""
    from washer.plots.style import figure, save
    w, cl = res["whirl"], res["clearance"]
    fig, (p, q) = figure(1, 2, figsize=(9.5, 3.6))
    r0 = res["r_birth"]
    a_nf = res.get("growth_normal_form", np.nan)
    for ax, lim in ((p, None), (q, 0.05)):
        ax.plot(np.r_[w.birth.value, w.value], 1e3 * np.r_[r0, w.r_max], "k.-",
                label="whirl: largest r (exact)")
        if np.isfinite(a_nf):
            d = np.linspace(0.0, w.birth.value * 0.04, 60)
            ax.plot(w.birth.value - d, 1e3 * (r0 + a_nf * np.sqrt(d)), "C0--", lw=1.0,
                    label=f"normal form r0 + {a_nf:.2f} sqrt(dC_p) (the sweeps' criterion)")
        ax.plot([w.birth.value, w.birth.value * 1.05], [1e3 * res["r_birth"]] * 2, "k:",
                label="forced response (no whirl)")
        for c, v in zip(cl["clearance"], cl["C_p"]):
            if lim is not None and c > lim:
                continue
            ax.axhline(1e3 * c, color="C3", lw=0.5, alpha=0.6)
            if np.isfinite(v):
                ax.plot([v], [1e3 * c], "o", color="C3", ms=3)
        ax.axvline(w.birth.value, color="0.5", ls="--", lw=0.8)
        ax.set_xlabel(r"$C_p$ (N m s/rad)")
        ax.set_ylabel("largest offset of the tub centre r (mm)")
    p.set_title("(a) the whirl down to C_p = 0; red: clearances", loc="left", fontsize=9)
    q.set_xlim(w.birth.value * 0.96, w.birth.value * 1.01)
    q.set_ylim(0, 1e3 * 0.06)
    q.set_title("(b) near the critical value", loc="left", fontsize=9)
    p.legend(fontsize=7)
    return save(fig, Path(stem))
