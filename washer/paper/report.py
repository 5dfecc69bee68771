"""The Markdown report of `python -m washer.paper`: a table, row per claim of the
paper, with our numbers for both rotating-frame levels and a verdict computed by
the rules below; then where each curve ends, the parameters and how to rerun.

Numbers come from the measurements (`washer.paper.analysis`); the paper's own
figures from `analysis.PAPER`. The verdict rules (tolerances) are stated here
and printed in the report.
"""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from washer.machine import kernel
from washer.paper.analysis import PAPER, RANGES, RISE_MIN, RISE_STEP
from washer.machine.params import default_params_path
from washer.paper.setups import SETUPS
from washer.atomic import write_text

#: A number matches the paper when within this relative difference.
MATCH_REL = 0.02
#: "Qualitatively" when the feature exists and is within this relative difference.
CLOSE_REL = 0.25

NAMES = {"Omega": "Ω", "m_u": "m_u", "R_u": "R_u", "C_a": "C_a", "K_s": "K_s"}
UNITS = {"Omega": "Hz", "m_u": "kg", "R_u": "m", "C_a": "N s/m", "K_s": "N/m", "C_p": "N m s/rad"}
FIG_OF = {"Omega": "Fig. 4", "m_u": "Fig. 5(a)", "R_u": "Fig. 5(b)", "C_a": "Fig. 6",
          "K_s": "Fig. 7(a)"}


def _g(x, n=4):
    return "0" if abs(x) < 1e-9 else f"{x:.{n}g}"


def _rel(a, b):
    return (a - b) / b


def _vec(v, n=4):
    return "[" + ", ".join(f"{x:.{n}f}" for x in v) + "]"


def _trend_cell(t, key):
    s = {1: "increasing", -1: "decreasing", 0: "mixed"}[t.sign]
    return (f"{s} ({100 * t.frac_up:.0f}% of steps up): C_p,crit {_g(t.cp[0], 3)} → {_g(t.cp[1], 3)} "
            f"over {NAMES[key]} ∈ [{_g(t.x[0], 4)}, {_g(t.x[1], 4)}] {UNITS[key]}")


def _verdict_sign(ta, tf):
    if ta.sign == 1 and tf.sign == 1:
        return "**reproduced** (both frames, over the whole curve)"
    if ta.sign == 1:
        return "**reproduced** (averaged); frozen frame mixed"
    return "**not reproduced**: the averaged curve is not increasing everywhere"


def claims(m: dict, resp: dict) -> list[tuple[str, str, str, str, str]]:
    """Rows (claim, paper, ours averaged, ours frozen, verdict)."""
    rows = []
    ha, hf = m["hopf"]["averaged"], m["hopf"]["frozen"]
    ea = _rel(ha["C_p"], PAPER["C_p_hopf"])
    ef = _rel(hf["C_p"], PAPER["C_p_hopf"])
    v = ("**reproduced by calibration**: J_bz of the reference set was chosen to put it here"
         if abs(ea) <= MATCH_REL else f"**not reproduced** ({100 * ea:+.1f}%)")
    v += f"; the frozen frame's Hopf differs by {100 * ef:+.0f}%"
    rows.append(("Hopf point in C_p at nominal values (Fig. 3)", f"C_p = {PAPER['C_p_hopf']}",
                 f"C_p = {ha['C_p']:.4f}, ±{ha['omega']:.2f}i rad/s, {ha['criticality'] or '?'}",
                 f"C_p = {hf['C_p']:.4f}, ±{hf['omega']:.2f}i rad/s, {hf['criticality'] or '?'}", v))
    ok = all(not h["stable_low"] and h["stable_high"] for h in (ha, hf))
    st = lambda h: (f"{'stable' if h['stable_low'] else 'unstable'} at C_p = 0, "
                    f"{'stable' if h['stable_high'] else 'unstable'} at C_p = 0.5")
    rows.append(("Unstable below the Hopf point, stable above (Fig. 3)", "unstable → stable",
                 st(ha), st(hf), "**reproduced**" if ok else "**not reproduced**"))
    for key in ("Omega", "m_u", "R_u", "K_s"):
        ta, tf = m["trends"][(key, "averaged")], m["trends"][(key, "frozen")]
        rows.append((f"sign of d C_p,crit / d {NAMES[key]} ({FIG_OF[key]})", "positive",
                     _trend_cell(ta, key), _trend_cell(tf, key), _verdict_sign(ta, tf)))
    (xa, ca, ia), (xf, cf, if_) = m["peak"]["averaged"], m["peak"]["frozen"]
    e = _rel(xa, PAPER["C_a_peak"])
    if ia and abs(e) <= MATCH_REL:
        v = "**reproduced**"
    elif ia and abs(e) <= CLOSE_REL:
        v = f"**qualitatively**: interior maximum, at {100 * e:+.0f}% of the paper's C_a"
    elif ia:
        v = f"**qualitatively**: interior maximum, but {100 * e:+.0f}% off the paper's C_a"
    else:
        v = "**not reproduced**: no interior maximum"
    rows.append(("C_p,crit rises with C_a, peaks, then falls (Fig. 6)",
                 f"peak at C_a = {PAPER['C_a_peak']:g} N s/m",
                 f"peak at C_a = {xa:.1f} N s/m (C_p = {ca:.4f})" if ia else "no interior peak",
                 f"peak at C_a = {xf:.1f} N s/m (C_p = {cf:.4f})" if if_ else "no interior peak", v))
    fa, ff = m["fit"]["averaged"], m["fit"]["frozen"]
    es, ei = _rel(fa.slope, PAPER["fit_slope"]), fa.intercept - PAPER["fit_intercept"]
    # Both curves pass through the nominal point (1 kg, 0.15 m), where the Hopf C_p was
    # calibrated, so a + b = 0.15 holds by construction: the split into a and b is the test.
    if abs(es) <= MATCH_REL and abs(ei) <= 0.002:
        v = (f"**reproduced**: slope {100 * es:+.1f}%, intercept {1e3 * ei:+.1f} mm (a + b = "
             f"R_u at m_u = 1 kg is fixed by the calibrated nominal point; the split is the test). "
             "What it tests: R_u ~ 1/m_u says the boundary depends on the imbalance mostly "
             "through its moment m_u R_u (the forcing); the small intercept b is what the "
             "imbalance's own mass and inertia add. It does not test the rest of the dynamics")
    elif fa.slope > 0:
        v = (f"**qualitatively**: R_u falls as 1/m_u (max residual {1e3 * fa.max_residual:.1f} mm); "
             f"slope {100 * es:+.0f}%, intercept {1e3 * ei:+.1f} mm off the paper's")
    else:
        v = "**not reproduced**"
    fit = lambda f: f"R_u = {f.slope:.4f}/m_u {f.intercept:+.4f} ({f.n} points, max residual {1e3 * f.max_residual:.1f} mm)"
    rows.append(("Hopf curve in (m_u, R_u): R_u = a/m_u + b (Fig. 5(c))",
                 f"R_u = {PAPER['fit_slope']}/m_u + {PAPER['fit_intercept']}", fit(fa), fit(ff), v))
    q, q0 = m["q_star"], m["q_star_no_imbalance"]
    rows.append(("Static equilibrium q* = [x, y, z, α, β, γ] (section 3.2.2)", _vec(PAPER["q_star"], 3),
                 f"{_vec(q)} with the imbalance at rest on +x; {_vec(q0)} without it", "(frame-independent)",
                 f"z **reproduced by calibration** (l0 set for z = 0.395 m without the imbalance: "
                 f"{q0[2]:.4f}); y = {PAPER['q_star'][1]} m and α = {PAPER['q_star'][3]} rad "
                 "**not reproduced**: a centred model cannot produce them (they imply an off-centre "
                 "cabinet the paper does not describe)"))
    e3a, e3f = m["eps_star"]["averaged"][2], m["eps_star"]["frozen"][2]
    e = _rel(e3a, PAPER["eps3"])
    rows.append(("ε3 at the equilibrium (section 3.2.1, Fig. 7(b))", f"{PAPER['eps3']} m",
                 f"{e3a:.4f} m", f"{e3f:.4f} m",
                 "**reproduced**" if abs(e) <= MATCH_REL else
                 f"**not reproduced** ({100 * e:+.1f}%): in our model spinning moves the height "
                 f"by {1e3 * (e3a - q0[2]):+.1f} mm from the static z, while the paper's ε3 is "
                 f"{1e3 * (PAPER['eps3'] - PAPER['q_star'][2]):+.0f} mm above its static q*; the "
                 "paper does not give what would explain the difference"))
    ks, e3 = m["eps3_K_s"]
    up = np.all(np.diff(e3) > 0)
    if up and e3[0] <= PAPER["eps3"] <= e3[-1]:
        k408 = float(np.interp(PAPER["eps3"], e3, ks))
        rows[-1] = rows[-1][:4] + (rows[-1][4] + f"; our ε3 reaches {PAPER['eps3']} m at "
                                   f"K_s = {k408:.0f} N/m (Fig. 7(b))",)
    rows.append(("ε3 falls as K_s decreases: small K_s puts the tub too low (Fig. 7(b))",
                 "ε3 increasing in K_s",
                 f"ε3 {e3[0]:.4f} m at K_s = {ks[0]:g} → {e3[-1]:.4f} m at {ks[-1]:g} N/m", "—",
                 "**reproduced**" if up else "**not reproduced**"))
    for fig, claim, want_settle in (("fig8", "Fig. 8: C_p = 0.15 converges to the equilibrium "
                                     "(after t ≈ 20 s)", True),
                                    ("fig9", "Fig. 9: C_p = 0 does not converge", False)):
        cells, kinds = [], []
        for frame in ("averaged", "frozen"):
            s = resp[fig]["settling"][frame]
            sig = resp[fig]["sigma"][frame]
            r = resp[fig]["responses"][frame]
            lin = (f"slowest mode at ε*: σ = {sig:.3f} 1/s" +
                   (f" (e-folding {1 / sig:.1f} s)" if sig > 0 else " (growing)"))
            if np.isfinite(s.settle_t):
                cells.append(f"within {1e3 * s.tol:g} mm/mrad of ε* from t = {s.settle_t:.1f} s; {lin}")
                kinds.append("settled")
            else:
                cells.append(f"at t = {r.t[-1]:g} s still {s.dist:.3g} from ε*; late ε1 "
                             f"peak-to-peak {1e3 * s.late_amp:.1f} mm, "
                             f"{'growing' if s.grows else 'on its limit cycle' if sig < 0 else f'decaying at {s.rate:.3f} 1/s'}; {lin}")
                kinds.append("growing" if s.grows else
                             "on its limit cycle" if sig < 0 else "decaying")
        a = kinds[0]
        if want_settle:
            if a == "settled":
                t_a = resp[fig]["settling"]["averaged"].settle_t
                v = f"**reproduced**: settles at {t_a:.1f} s (paper ≈{PAPER['settle_fig8']:g} s)"
            elif a == "decaying":
                v = ("**qualitatively**: converges, but more slowly than the paper's ≈"
                     f"{PAPER['settle_fig8']:g} s (the decay rate σ is small this close to the Hopf point)")
            else:
                v = "**not reproduced**: the response does not converge"
        else:
            v = ("**reproduced**: the equilibrium is unstable and the response " +
                 ("still grows" if a == "growing" else "has reached its limit cycle (the "
                  "whirl), neither converging nor growing")
                 if a in ("growing", "on its limit cycle") else
                 "**not reproduced**: the response decays")
        if kinds[1] != a:
            v += f"; frozen frame: {kinds[1]}"
        rows.append((claim, "converges" if want_settle else "oscillates", cells[0], cells[1], v))
    o10, o11 = resp["fig10"]["orbit"], resp["fig11"]["orbit"]
    pk = lambda o: ", ".join(f"{f:.2f}" for f in o.peaks)
    single = len(o10.peaks) == 1
    rows.append(("Fig. 10: spin-up at C_p = 0.15 tends to a circle (a periodic solution)",
                 "circle", f"over t ∈ [{o10.t_from:g}, 50] s: radius {1e3 * o10.radius:.2f} mm "
                 f"(max {1e3 * o10.r_max:.2f}); spectral peak of y at {pk(o10)} Hz, next peak "
                 f"{100 * o10.second:.1f}% of it", "— (ground frame)",
                 "**reproduced**: one frequency, the spin speed" if single else
                 "**not reproduced**: more than one frequency"))
    multi = len(o11.peaks) > 1
    v11 = f"**reproduced**: {len(o11.peaks)} frequencies" if multi else "**not reproduced**"
    if multi and "yaw_mode" in resp["fig11"]:
        f_yaw = resp["fig11"]["yaw_mode"][0]
        om = resp["fig11"]["Omega"]
        tol = 2 * o11.df
        side = [f for f in o11.peaks if min(abs(f - om - f_yaw), abs(f - om + f_yaw)) <= tol]
        spin = [f for f in o11.peaks if abs(f - om) <= tol]
        if side:
            v11 = (f"**reproduced as a transient**: besides the spin ({', '.join(f'{f:.2f}' for f in spin) or 'none'} Hz) "
                   f"the lines {', '.join(f'{f:.2f}' for f in side)} Hz are Ω ± {f_yaw:.2f} Hz, "
                   "sidebands of the slow yaw mode ringing after the 0.45 s spin-up (its "
                   "damping is tiny at C_p = 0); they are not the steady state, which is the "
                   "whirl (its own frequency, below 1 Hz, see the exact whirl) on top of the spin")
    rows.append(("Fig. 11: spin-up at C_p = 0: more than one frequency at the steady state",
                 "several frequencies", f"spectral peaks of y at {pk(o11)} Hz (≥10% of the largest)",
                 "— (ground frame)", v11))
    ratio = o11.r_max / o10.r_max
    rows.append(("Fig. 11: the vibration amplitude is very large at C_p = 0", "large",
                 f"max radius {1e3 * o11.r_max:.1f} mm over t ∈ [{o11.t_from:g}, 50] s, "
                 f"{ratio:.1f}× Fig. 10's; after the whirl has grown (the long run of Fig. 11(b)'s "
                 f"row) {1e3 * resp['fig11_long']['rise'].radius[-1]:.0f} mm, "
                 f"{resp['fig11_long']['rise'].radius[-1] / o10.r_max:.0f}× Fig. 10's",
                 "— (ground frame)",
                 "**reproduced**" if ratio > 3 else
                 f"**qualitatively**: larger than at C_p = 0.15 (×{ratio:.1f}; max radius of the "
                 f"window's second half {o11.r_growth:.2f}× its first)" if ratio > 1 else
                 "**not reproduced**"))
    rows.append(fig11b_row(resp))
    return rows


def fig11b_row(resp: dict) -> tuple[str, str, str, str, str]:
    """Fig 11(b) judged on the long C_p = 0 run (`figures.long_whirl`): "higher and
    higher" is reproduced when the last window's mean height is RISE_MIN above the
    static one and still rising (by RISE_STEP per window); qualitatively when it rose
    that much and then levelled off; not reproduced otherwise."""
    o11, L = resp["fig11"]["orbit"], resp["fig11_long"]
    rise, z0, r = L["rise"], L["z_static"], L["response"]
    t_paper = SETUPS["fig11"]["t_end"]
    k50 = int(np.searchsorted(rise.t, t_paper))
    k50 = min(k50, len(rise.t) - 1)
    short = (f"in the paper's 50 s: late mean z {o11.z_mean:.4f} m "
             f"({1e3 * (o11.z_mean - resp['fig11']['z_static']):+.1f} mm from static), trend over "
             f"[{o11.t_from:g}, 50] s {1e3 * o11.z_trend:+.2f} mm")
    up = rise.z_end - z0
    long = (f"run for {r.t[-1]:g} s = 50 s + {_long_duration(L)}: mean z per "
            f"{rise.window:g} s window {rise.z[k50]:.4f} m at t = {rise.t[k50]:g} s → "
            f"{rise.z_end:.4f} m at the end ({1e3 * up:+.0f} mm from static); orbit radius "
            f"{1e3 * rise.radius[k50]:.0f} → {1e3 * rise.radius[-1]:.0f} mm")
    if up > RISE_MIN and rise.dz_last >= RISE_STEP:
        v = f"**reproduced**: still rising at the end ({1e3 * rise.dz_last:+.1f} mm in the last window)"
    elif up > RISE_MIN:
        v = (f"**qualitatively**: O_b rises by {1e3 * (rise.z_end - rise.z[k50]):.0f} mm after the "
             f"paper's window while the whirl grows, then levels off from t = {rise.t_level:g} s "
             f"(last window {1e3 * rise.dz_last:+.2f} mm): a limit cycle of radius "
             f"{1e3 * rise.radius[-1]:.0f} mm (the model has no cabinet: only the rods limit the "
             "swing), higher but not higher and higher")
        if o11.z_trend < 0:
            v += ("; within the paper's 50 s the mean height falls: what is high there is the "
                  "spin-up's lift decaying (section below)")
    else:
        v = (f"**not reproduced**: the mean height ends {1e3 * up:+.1f} mm from static "
             f"(rule: > {1e3 * RISE_MIN:g} mm)")
    return ("Fig. 11(b): O_b gets higher and higher at C_p = 0", "z rising",
            short + "; " + long, "— (ground frame)", v)


def _long_duration(L) -> str:
    """How the long run's duration was chosen, from its growth rate."""
    extra = L["response"].t[-1] - SETUPS["fig11"]["t_end"]
    return (f"{extra:g} s ≥ {L['efoldings']:g} e-folding times 1/σ = {1 / L['sigma']:.1f} s of the averaged "
            f"system's unstable pair at C_p = 0 (σ = {L['sigma']:.4f} 1/s)")


def spinup_section(resp: dict) -> list[str]:
    """The lift of Figs 10-11: spin-up torque (eq 66) against the suspension's yaw
    curve, with the verdict rule stated: the lift is explained by the torque when the
    peak torque exceeds the yaw moment at which the tub tips at rest (M_tip, the fold of
    the curve) and the simulated yaw passes the fold's angle; the slower spin-up is chosen
    so that T_peak <= M_tip / 2 (`spinup.slow_tau_s`)."""
    S = resp["spinup"]
    c, T, Ts, tau = S["curve"], S["torque"], S["torque_slow"], S["tau_slow"]
    L = ["## The lift of the tub in Figs 10-11: spin-up torque against the suspension's yaw\n"]
    over = T.T_peak / c.M_max
    t_over = T.tau_s * np.log(over) if over > 1 else 0.0
    L.append(
        f"The motor sits on the tub, so accelerating the basket by eq 66 "
        f"(θ̈ = (Ω/τ_s) e^(−t/τ_s), Ω = {T.impulse / T.J_spin:.2f} rad/s) twists the tub the other way with the moment "
        f"(J_bz + m_u R_u²) θ̈: J = {T.J_spin:.4f} kg m², θ̈(0) = {T.theta_ddot0:.1f} rad/s², so "
        f"**T_peak = {T.T_peak:.1f} N m** at τ_s = {T.tau_s:g} s (of the basket's final angular "
        f"momentum, {T.impulse:.1f} N m s, 1 − 1/e = 63% is delivered within the first τ_s).\n")
    tw = S.get("twist")
    L.append(
        f"The suspension's yaw resistance, computed from the model at rest (Ω = 0, imbalance on +x) "
        f"under an applied yaw moment Q continued from 0 (`washer.paper.spinup.yaw_curve`): "
        f"linearised stiffness **{c.k_lin:.1f} N m/rad** (the Schur complement of the static "
        f"Jacobian in γ, other coordinates free); the curve folds at **M_tip = {c.M_max:.1f} N m**, "
        f"γ = {c.gamma_max:+.3f} rad (z {1e3 * (c.z_max - c.q0[2]):+.0f} mm). That fold is where "
        "the twisted tub, pushed sideways by the imbalance at rest, tips over: an imperfect "
        "pitchfork, not the most moment the rods can hold.")
    if tw is not None:
        k8 = int(np.argmin(np.abs(np.abs(tw.gamma) - 0.8)))
        L[-1] += (
            f" Without the imbalance (`spinup.twist_curve`, the twist prescribed) the moment "
            f"needed to twist the tub keeps rising ({abs(tw.Q[k8]):.1f} N m at "
            f"{abs(tw.gamma[k8]):.2f} rad, {abs(tw.Q[-1]):.1f} N m at {abs(tw.gamma[-1]):.2f} rad), "
            f"but the symmetric twisted tub loses its tilt stiffness at **{abs(tw.gamma_tip):.3f} "
            f"rad, {abs(tw.Q_tip):.1f} N m** (the pitchfork the imbalance unfolds into the fold "
            f"above), which is where the rods, seen from above, turn tangent to the tub: "
            f"arccos(R_O/R_P) = {tw.gamma_into_tub:.3f} rad. Beyond it they would run into the "
            "tub's wall; the model has no contact, so twists past about that angle are "
            "outside what it describes.")
    L[-1] += "\n"
    pf = S["paper"]
    verdict = ("explained" if over > 1 and all(pf[f].gamma_peak > abs(c.gamma_max) for f in pf)
               else "not explained by the torque")
    L.append(
        f"At τ_s = {T.tau_s:g} s the peak torque is **{over:.1f}× M_tip** and stays above it for "
        f"the first τ_s ln(T_peak/M_tip) = {t_over:.2f} s, so the tub twists past the point "
        f"where it tips: the simulated yaw peaks at |γ| = {pf['fig10'].gamma_peak:.2f} rad "
        f"(t = {pf['fig10'].t_peak:.2f} s, C_p = 0.15) and {pf['fig11'].gamma_peak:.2f} rad "
        f"(C_p = 0), the rods swing towards horizontal and lift O_b by "
        f"{1e3 * pf['fig10'].lift:.0f} and {1e3 * pf['fig11'].lift:.0f} mm "
        f"(t ≈ {pf['fig10'].t_lift:.2f} s). Verdict (rule: T_peak > M_tip and the simulated |γ| "
        f"passes the tipping twist {abs(c.gamma_max):.2f} rad): the lift is **{verdict}** by the "
        "spin-up torque; it is not a numerical artefact, but a model without contact between "
        "rods and tub carries it further than a machine could go.\n")
    sl = S["slow"]
    L.append(
        f"**Slower spin-up, τ_s = {tau:g} s**, chosen as the smallest whole second with "
        f"T_peak ≤ M_tip/2 (a torque applied as a step, as eq 66's is at t = 0, at most doubles "
        f"an undamped oscillator's static deflection; M_tip, the moment at which the tub tips "
        f"with the imbalance at rest, is the smaller of the two limits above): "
        f"T_peak = {Ts.T_peak:.2f} N m, quasi-static "
        f"twist T_peak/k = {Ts.T_peak / c.k_lin:.2f} rad; the simulated peaks "
        f"({sl['fig10']['yaw'].gamma_peak:.2f} and {sl['fig11']['yaw'].gamma_peak:.2f} rad) are "
        f"{sl['fig10']['yaw'].gamma_peak * c.k_lin / Ts.T_peak:.2f} and "
        f"{sl['fig11']['yaw'].gamma_peak * c.k_lin / Ts.T_peak:.2f} times it. The speed reaches 95% at 3τ_s = "
        f"{3 * tau:g} s; washing-machine motors are ramped to spin speed over seconds to tens "
        f"of seconds, not the paper's 0.45 s (95% at 1.35 s), so this is also the more "
        f"realistic run. The same runs (Figs 10-11, 50 s):\n")
    rows = []
    for fig, cp in (("fig10", 0.15), ("fig11", 0.0)):
        for label, y, o in ((f"{T.tau_s:g} s (paper)", pf[fig], resp[fig]["orbit"]),
                            (f"{tau:g} s", sl[fig]["yaw"], sl[fig]["orbit"])):
            rows.append((f"{fig}, C_p = {cp:g}", label, f"{y.gamma_peak:.3f} (t = {y.t_peak:.2f} s)",
                         f"{1e3 * y.lift:.1f}", f"{1e3 * o.r_max:.1f}", f"{o.z_mean:.4f}",
                         ", ".join(f"{f:.2f}" for f in o.peaks)))
    L.append(_table(["run", "τ_s", "peak of γ's magnitude (rad), t ≤ 3τ_s", "lift of O_b for t ≤ 3τ_s (mm)",
                     f"max orbit radius, t ∈ [{resp['fig10']['orbit'].t_from:g}, 50] s (mm)",
                     "late mean z (m)", "spectral peaks of y (Hz)"], rows) + "\n")
    ratio = max(sl[f]["yaw"].lift for f in sl) / min(pf[f].lift for f in pf)
    o_p, o_s = resp["fig11"]["orbit"], sl["fig11"]["orbit"]
    L.append(f"With τ_s = {tau:g} s the spin-up's lift is at most {100 * ratio:.0f}% of the paper "
             f"runs'. At C_p = 0 the equilibrium is unstable whatever the spin-up: by t = 50 s the "
             f"whirl's radius is {1e3 * o_s.r_max:.0f} mm with the slow spin-up against "
             f"{1e3 * o_p.r_max:.0f} mm with the paper's (Fig. 11(b)'s row judges the long run).\n")
    return L


def params_table(path: Path | None = None) -> list[tuple[str, str, str, str]]:
    """(section, name, value, note) of the parameter file, notes from its comments:
    which values are Table 1's, which estimated, which calibrated."""
    path = path or default_params_path()
    out, section = [], ""
    for line in Path(path).read_text().splitlines():
        sec = re.match(r"\[(\w+)\]", line.strip())
        if sec:
            section = sec.group(1)
            continue
        kv = re.match(r"\s*(\w+)\s*=\s*([^#]+?)\s*(?:#\s*(.*))?$", line)
        if kv and section:
            out.append((section, kv.group(1), kv.group(2), kv.group(3) or ""))
    return out


def _table(header, rows) -> str:
    esc = lambda s: str(s).replace("|", "\\|")
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(esc(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def write_incomplete(out: Path, failed: dict, log, mode: str, timing: dict) -> Path:
    """The report when runs failed: which, why, and how to rerun; no claim is judged
    (a partial curve must never count as reproduced). Returns the path."""
    L = ["# washer: reproduction of the paper's section 3 — INCOMPLETE\n",
         f"`python -m washer.paper{' --quick' if mode == 'quick' else ''}` ({mode} mode, "
         f"{timing['total']:.1f} s): {len(failed)} run(s) did not finish, so **no claim of the "
         "paper is judged** in this report. Fix or rerun them first.\n",
         _table(["run", "status"], sorted(failed.items())) + "\n",
         "## How to rerun\n", "```\n" + "\n".join(log.commands) + "\n```\n",
         _table(["run", "seconds", "status"],
                [(k, f"{v:.2f}", log.status[k]) for k, v in log.seconds.items()]) + "\n"]
    out.mkdir(parents=True, exist_ok=True)
    path = out / "report.md"
    write_text(path, "\n".join(L))
    return path


def write(out: Path, params, m: dict, resp: dict, figs: dict, log, mode: str, timing: dict) -> Path:
    """Write out/report.md; returns its path."""
    L = []
    L.append("# washer: reproduction of the paper's section 3 (Figs 3-11)\n")
    L.append(f"Generated by `python -m washer.paper{' --quick' if mode == 'quick' else ''}` "
             f"({mode} mode) in {timing['total']:.1f} s (AUTO runs {timing['auto']:.1f} s, time "
             f"responses {timing['sim']:.1f} s). Kernel inputs sha256 `{kernel.inputs_hash()[:16]}`. "
             "Every number below is computed by that run; the paper's figures are quoted for "
             "comparison.\n")
    L.append("Two levels of the paper's \"autonomous\" rotating-frame system are compared "
             "(docs/model.md section 4): **averaged** over the frame angle τ (the sound reading, our "
             "default) and **frozen** at τ0 = 0 (the paper's literal eq 59). The rotating-frame "
             "system still depends on τ (four discrete rods, Cardan angles), so the two differ.\n")
    L.append(f"Verdict rules: *reproduced* within {100 * MATCH_REL:g}% (or the same sign/feature); "
             f"*qualitatively* when the feature exists but the number is off; *not reproduced* "
             f"otherwise, with the reason. *By calibration* means a parameter the paper does not "
             f"give was fitted to that very number, so agreement there is not evidence.\n")
    L.append("## Claims of the paper\n")
    L.append(_table(["claim (paper)", "paper", "ours: averaged frame", "ours: frozen τ0 = 0",
                     "verdict"], claims(m, resp)) + "\n")

    L.extend(spinup_section(resp))

    L.append("## Where each curve ends\n")
    L.append(f"Curves are traced both ways from the nominal Hopf point over Table 1's ranges "
             f"({', '.join(f'{NAMES[k]} ∈ [{lo:g}, {hi:g}] {UNITS[k]}' for k, (lo, hi) in RANGES.items())}).\n")
    rows = []
    for (key, frame), ends in m["ends"].items():
        for v1, v2, why in ends:
            if key == "m_u_R_u":
                where = f"m_u = {v1:.4g} kg, R_u = {v2:.4g} m"
            else:
                where = f"{NAMES[key]} = {v2:.5g} {UNITS[key]}, C_p = {v1:.4g}"
            rows.append((key if key != "m_u_R_u" else "(m_u, R_u)", frame, where, why))
    L.append(_table(["curve", "frame", "end point", "why it ends there"], rows) + "\n")
    for (key, frame), pts in m["gh"].items():
        if pts:
            xs, cs = [p[0] for p in pts], [p[1] for p in pts]
            if max(cs) >= 1e-3:
                L.append(f"- generalised Hopf (GH) point(s) on the {NAMES[key]} curve ({frame}): "
                         + "; ".join(f"{NAMES[key]} = {x:.4g}, C_p = {c:.4g}" for x, c in pts))
                continue
            L.append(f"- {len(pts)} generalised Hopf (GH) point(s) on the {NAMES[key]} curve "
                     f"({frame}), all within {NAMES[key]} ∈ [{min(xs):.3g}, {max(xs):.3g}], "
                     f"C_p ≤ {max(cs):.2g}: next to the end where C_p,crit and {NAMES[key]} vanish "
                     "together and the system has no damping left, the first Lyapunov coefficient "
                     "(finite differences) is ill-conditioned, so these locate a degenerate corner, "
                     "not a reliable codimension-2 point.")
    for frame in ("averaged", "frozen"):
        x, c, interior = m["peak"][frame]
        L.append(f"- C_a curve ({frame}): C_p,crit is largest at C_a = {x:.1f} N s/m "
                 f"(C_p = {c:.4f}; located as a fold of the Hopf curve in C_p).")
    L.append("")

    L.append("## Figures\n")
    captions = {
        "fig3": "Fig. 3: the equilibrium continued in C_p (thick: stable; dotted: unstable; * Hopf).",
        "fig4": "Fig. 4: Hopf curve in (Ω, C_p); the equilibrium is stable above the curve.",
        "fig5": "Fig. 5: Hopf curves in (m_u, C_p), (R_u, C_p) and (m_u, R_u) with the 1/m_u fits.",
        "fig6": "Fig. 6: Hopf curve in (C_a, C_p) with the paper's peak location.",
        "fig7": "Fig. 7: (a) Hopf curve in (K_s, C_p); (b) ε3 at the equilibrium against K_s.",
        "fig8": "Fig. 8: rotating-frame response at C_p = 0.15 from ε3 = 0.408 m (dotted: ε*).",
        "fig9": "Fig. 9: rotating-frame response at C_p = 0.",
        "fig10": "Fig. 10: spin-up (eq 66) at C_p = 0.15: y, z of O_b, XY trajectory, spectrum of y.",
        "fig11": "Fig. 11: spin-up at C_p = 0.",
        "spinup": "Figs 10-11's spin-up: the tub's yaw γ(t), the height of O_b, and the "
                  "suspension's static yaw moment-angle curve against the peak spin-up torques.",
        "fig11_long": "Fig. 11 at C_p = 0 run long enough for the whirl to grow: z(t) of O_b and "
                      "the orbit radius per window.",
    }
    for k, paths in figs.items():
        png = next(p for p in paths if p.suffix == ".png")
        pdf = next(p for p in paths if p.suffix == ".pdf")
        L.append(f"![{captions[k]}]({png.name})\n\n*{captions[k]}* ([PDF]({pdf.name}))\n")

    L.append("## Parameters\n")
    L.append(f"From `{default_params_path().name}` (shipped with washer; docs/model.md section 5). The "
             "paper gives only Table 1 and a few values in section 3; masses, inertias and "
             "geometry are our estimates, and two values are calibrated (their notes say so):\n")
    L.append(_table(["group", "name", "value", "source / note"], params_table()) + "\n")

    L.append("## How to rerun\n")
    L.append("Each run below is a constants file in `auto/` (copied from `auto_constants/`), "
             "run from this folder; the b./s./d. files beside them are the ones plotted here:\n")
    L.append("```\n" + "\n".join(log.commands) + "\n```\n")
    L.append(_table(["run", "seconds", "status"],
                    [(k, f"{v:.2f}", log.status[k]) for k, v in log.seconds.items()]) + "\n")
    L.append("Time responses: kernel DOPRI5, rtol 1e-8; Figs 8-9 from ε3 = 0.408 m, all else 0 "
             "(section 3.2.1); Figs 10-11 from the static equilibrium at rest (section 3.2.2). "
             "Data: `data/*.npz`, `data/*.csv`.\n")
    path = out / "report.md"
    write_text(path, "\n".join(L))
    return path
