"""Which conclusions survive the estimated parameters: the critical C_p (the averaged
rotating frame's Hopf point, within ~1e-5 of the exact torus point) with each estimated
parameter of the reference set moved by +-20 %, one at a time, and with all of them at
their adverse ends together.

The paper gives none of the masses, inertias, heights or the rod geometry (docs/model.md
section 5): they are engineering estimates, and J_bz and l0 are calibrated (to the
paper's critical C_p and static height). The study says how much the model's headline
numbers lean on them.
"""
from __future__ import annotations

import numpy as np

from washer.machine import layout
from washer.problems import forced as shooting
from washer.machine.model import Model
from washer.machine.params import Params
from washer.problems.rotating import averaged_hopf

#: Relative change of each estimated parameter.
CHANGE = 0.2

#: The estimated parameters: name -> (what, kernel parameters moved together).
ESTIMATED = {
    "m_t": ("tub mass", ("m_t",)),
    "r_tz": ("tub mass-centre height", ("r_tz",)),
    "J_t": ("tub transverse inertia", ("J_tx", "J_ty")),
    "J_tz": ("tub polar inertia", ("J_tz",)),
    "m_b": ("basket mass", ("m_b",)),
    "h_b": ("basket mass-centre height", ("h_b",)),
    "J_bt": ("basket transverse inertia", ("J_bt",)),
    "J_bz": ("basket polar inertia (calibrated)", ("J_bz",)),
    "R_P": ("upper joints' radius", tuple(f"P{a}{k}" for k in range(layout.N_RODS)
                                          for a in "xy")),
    "z_P": ("upper joints' height", tuple(f"Pz{k}" for k in range(layout.N_RODS))),
    "R_O": ("lower joints' radius", tuple(f"O{a}{k}" for k in range(layout.N_RODS)
                                          for a in "xy")),
    "l0": ("rod free length (calibrated)", ("l0",)),
}


def scaled(params: Params, key: str, factor: float) -> Params:
    """params with the estimated parameter `key` (ESTIMATED) multiplied by factor."""
    return params.replace(**{n: params[n] * factor for n in ESTIMATED[key][1]})


def critical(params: Params) -> dict:
    """Averaged critical C_p, the crossing pair's ground-frame whirl frequency (Hz), the
    static height (m) and the whirl's growth coefficient a (m per sqrt(N m s/rad), Hopf
    normal form, `washer.sweep.tasks.whirl_growth`: nan when the first Lyapunov
    coefficient is not negative, i.e. the point is not supercritical); nan where the
    machine has no hanging equilibrium or no Hopf point in C_p in [0, 2]."""
    try:
        cp, lam = averaged_hopf(params)
        pair = lam[np.argmin(np.where(lam.imag > 0, np.abs(lam.real), np.inf))]
        f = (2 * np.pi * params["Omega"] - abs(pair.imag)) / (2 * np.pi)
        z = float(Model(params.replace(m_u=0.0)).static_equilibrium()[2])
        from washer.sweep.tasks import whirl_growth
        a, _, _ = whirl_growth(params, "C_p", cp)
        return {"C_p": float(cp), "f_whirl": float(f), "z_static": z, "growth": a, "note": ""}
    except ValueError:          # no sign change of the margin for C_p in [0, 2]
        try:
            m = Model(params.replace(C_p=0.0))
            margin = float(m.eigenvalues(m.rotating_equilibrium()).real.max())
        except Exception as exc:  # noqa: BLE001 - recorded: outside the model's reach
            return {"C_p": np.nan, "f_whirl": np.nan, "z_static": np.nan,
                    "note": f"no hanging equilibrium ({type(exc).__name__})"}
        if margin < 0:
            return {"C_p": 0.0, "f_whirl": np.nan, "z_static": np.nan,
                    "note": "stable without joint damping"}
        return {"C_p": np.nan, "f_whirl": np.nan, "z_static": np.nan,
                "note": "unstable up to C_p = 2"}
    except Exception as exc:  # noqa: BLE001 - recorded: the set is outside the model's reach
        return {"C_p": np.nan, "f_whirl": np.nan, "z_static": np.nan,
                "note": f"{type(exc).__name__}: {str(exc)[:80]}"}


def undamped_margin(params: Params) -> float:
    """Largest real part (1/s) at C_a = C_p = 0 (no damping at all): 0 to round-off when
    the whirl needs a damper to grow."""
    try:
        m = Model(params.replace(C_a=0.0, C_p=0.0))
        return float(m.eigenvalues(m.rotating_equilibrium()).real.max())
    except Exception:  # noqa: BLE001 - no hanging equilibrium: nothing to say
        return np.nan


def compute(params: Params, progress=print) -> dict:
    """One-at-a-time +-CHANGE rows, elasticities d ln C_p,crit / d ln p (central), and the
    combined adverse and favourable corners (every parameter at the end that raises,
    resp. lowers, C_p,crit)."""
    progress(f"  sensitivity: critical C_p with each estimate moved by +-{100 * CHANGE:.0f} %")
    nominal = critical(params)
    rows = []
    for key, (what, _) in ESTIMATED.items():
        lo, hi = critical(scaled(params, key, 1 - CHANGE)), critical(scaled(params, key, 1 + CHANGE))
        for c, f in ((lo, 1 - CHANGE), (hi, 1 + CHANGE)):
            c["undamped_margin"] = undamped_margin(scaled(params, key, f))
        el = (np.log(hi["C_p"]) - np.log(lo["C_p"])) / (np.log(1 + CHANGE) - np.log(1 - CHANGE))
        rows.append({"key": key, "what": what, "minus": lo, "plus": hi, "elasticity": float(el)})
    corners = {}
    for name, sign in (("adverse", 1.0), ("favourable", -1.0)):
        q = params
        for r in rows:
            if np.isfinite(r["elasticity"]):
                q = scaled(q, r["key"], 1 + CHANGE * sign * np.sign(r["elasticity"]))
        corners[name] = critical(q)
        if np.isfinite(corners[name]["C_p"]) and corners[name]["C_p"] > 0:
            try:            # the exact torus point beside it: averaging holds out there too
                corners[name]["exact"] = float(shooting.critical_cp(q)["C_p_exact"])
            except Exception:  # noqa: BLE001 - reported as missing
                corners[name]["exact"] = np.nan
    return {"nominal": nominal, "rows": rows, "corners": corners, "change": CHANGE}


def markdown(res: dict) -> str:
    n = res["nominal"]
    pct = 100 * res["change"]

    def cell(c):
        if not np.isfinite(c["C_p"]) or c["note"]:
            return f"{c['C_p']:.4f} ({c['note']})" if np.isfinite(c["C_p"]) else c["note"]
        return f"{c['C_p']:.4f} ({100 * (c['C_p'] / n['C_p'] - 1):+.0f} %)"

    lines = [
        f"## Sensitivity of the critical C_p to the estimated parameters (+-{pct:.0f} %)",
        "",
        "The paper gives no masses, inertias or rod geometry; the reference set estimates "
        "them (and calibrates J_bz and l0). Critical C_p of the averaged frame (within "
        f"~1e-5 of the exact torus point) at Omega = 10 Hz, nominal {n['C_p']:.4f} N m s/rad "
        f"(whirl {n['f_whirl']:.3f} Hz), each estimate moved alone:",
        "",
        f"| parameter | what | -{pct:.0f} % | +{pct:.0f} % | elasticity |",
        "|---|---|---|---|---|",
    ]
    for r in sorted(res["rows"], key=lambda r: -abs(np.nan_to_num(r["elasticity"]))):
        lines.append(f"| {r['key']} | {r['what']} | {cell(r['minus'])} | {cell(r['plus'])} | "
                     f"{r['elasticity']:+.2f} |")
    a, f = res["corners"]["adverse"], res["corners"]["favourable"]
    big = [r["key"] for r in res["rows"] if abs(np.nan_to_num(r["elasticity"])) >= 1.0]
    fw = [c["f_whirl"] for r in res["rows"] for c in (r["minus"], r["plus"])
          if np.isfinite(c["f_whirl"])]
    cps = [c["C_p"] for r in res["rows"] for c in (r["minus"], r["plus"])
           if np.isfinite(c["C_p"])]
    und = [abs(c["undamped_margin"]) for r in res["rows"] for c in (r["minus"], r["plus"])
           if np.isfinite(c["undamped_margin"])]
    grow = [c.get("growth", np.nan) for r in res["rows"] for c in (r["minus"], r["plus"])
            if np.isfinite(c["C_p"]) and c["C_p"] > 0]
    sup = all(np.isfinite(g) for g in grow)
    exact = (f" (exact torus point {a['exact']:.4f})" if np.isfinite(a.get("exact", np.nan))
             else "")
    lines += [
        "",
        f"All estimates at their adverse ends together: critical C_p {cell(a)}{exact}; at "
        f"their favourable ends: {cell(f)}. The elasticity is d ln C_p,crit / d ln p. The "
        f"whirl frequency at the critical point stays within {min(fw):.3f}-{max(fw):.3f} Hz "
        "over the single changes. Moving the upper joints' height changes nothing: the "
        "tub hangs correspondingly higher on the same rods (a check of the model's "
        "translation invariance, not an estimate that matters). "
        + (f"The critical value leans strongly (|elasticity| >= 1) on {', '.join(big)}: "
           "its value is the estimates' as much as the model's. " if big else "")
        + (f"Every single change keeps an instability at 10 Hz with little joint damping "
           f"(critical C_p between {min(cps):.4f} and {max(cps):.4f}) "
           if min(cps) > 0 else "Some single changes remove the instability altogether "
           "(critical C_p 0) ")
        + (f"and the mechanism: with no damping at all the pair is neutral in every row "
           f"(largest real part at most {max(und):.0e} 1/s), so it is the dampers that move "
           "it. " if max(und) < 1e-9 else "; with no damping at all some rows are not "
           f"neutral (largest real part {max(und):.2e} 1/s). ")
        + (f"The Hopf point stays supercritical in every row (a small stable whirl, growing "
           f"like a sqrt(C_p,crit - C_p) with a = {min(grow):.2f}-{max(grow):.2f} m per "
           "sqrt(N m s/rad): the clearance criterion's slope moves with the estimates too). "
           if sup else "Some rows are not supercritical (no small stable whirl there). ")
        + "What does not survive: the critical value's size, to tens of per cent; a design "
        "needs the real machine's masses and geometry, or the margin of the adverse corner.",
        "",
    ]
    return "\n".join(lines)
