"""Reproduce the paper's section 3 (Figs 3-11) and report how close it comes.

    python -m washer.paper [--quick] [--out out/paper]

Runs every AUTO constants file of Figs 3-7 (copied into OUT/auto and run
there), the time responses of Figs 8-11, measures what the paper claims, and
writes the figures (PNG + PDF) and OUT/report.md. `--quick` takes steps three
times larger on every curve and shortens Figs 8-9 to 25 s: the same analyses,
coarser. Parameters: the shipped reference set (`washer/data/reference.toml`).
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from washer.machine.model import Model
from washer.paper import analysis as an
from washer.paper import spinup as sp
from washer.paper.runs import FRAMES, run_all
from washer.machine.params import load_params
from washer.paper.setups import SETUPS
from washer.machine.responses import simulate
from washer.atomic import write_text

#: Figs 8-9 duration in quick mode (s); otherwise the paper's setups
#: (`washer.paper.setups.SETUPS`: C_p, durations, the trajectory windows of Figs 10c/11c).
T_ROT_QUICK = 25.0
#: Start of the late window for the orbit measures and spectra (s; 20 s: 0.05 Hz bins).
SPECTRUM_FROM = 30.0
#: The long C_p = 0 run lasts the paper's 50 s plus this many e-folding times of
#: the unstable whirl (e^20 ~ 5e8: any seed from numerical noise up grows to its
#: nonlinear size or diverges well within the run).
LONG_EFOLDINGS = 20.0
#: Samples per second of the long run (Nyquist 50 Hz, above the 10 Hz spin).
LONG_SAMPLES = 100.0
#: Window of the long run's mean height and orbit radius (s).
WINDOW = 10.0


def time_responses(params, quick: bool, progress=print) -> dict:
    """Figs 8-9 in both frames and Figs 10-11, with their measurements."""
    out = {}
    for fig in ("fig8", "fig9"):
        cp = SETUPS[fig]["C_p"]
        t_end = T_ROT_QUICK if quick else SETUPS[fig]["t_end"]
        model = Model(params.replace(C_p=cp))
        rs, eqs, meas, sigma = {}, {}, {}, {}
        for frame in FRAMES:
            # Initial state: the paper's eps3 = 0.408 m, all else zero (the default).
            progress(f"  {fig}: rotating frame ({frame}), C_p = {cp:g}, {t_end:g} s")
            rs[frame] = simulate(model, t_end, system="rotating", frame=frame,
                                 samples_per_s=200.0, progress=False)
            eqs[frame] = model.rotating_equilibrium(frame=frame)
            meas[frame] = an.settling(rs[frame], eqs[frame])
            # Linear decay rate of the slowest mode at eps* (1/s; negative: growth).
            lam = model.eigenvalues(eqs[frame], frame=frame)
            sigma[frame] = float(-lam.real.max())
        out[fig] = dict(C_p=cp, responses=rs, eq=eqs, settling=meas, sigma=sigma)
    for fig in ("fig10", "fig11"):
        cp, t_end = SETUPS[fig]["C_p"], SETUPS[fig]["t_end"]
        progress(f"  {fig}: spin-up (eq 66), C_p = {cp:g}, {t_end:g} s")
        model = Model(params.replace(C_p=cp))
        r = simulate(model, t_end, system="fixed", law="spinup", samples_per_s=500.0,
                     progress=False)
        out[fig] = dict(C_p=cp, response=r, orbit=an.orbit(r, SPECTRUM_FROM),
                        yaw_mode=an.yaw_mode(model), Omega=float(params["Omega"]),
                        z_static=float(model.static_equilibrium()[2]),
                        yaw=sp.yaw_response(r, 3 * params["tau_s"]))
    out["spinup"] = spinup_study(params, out, progress)
    out["fig11_long"] = long_whirl(params, progress)
    return out


def spinup_study(params, resp: dict, progress=print) -> dict:
    """The lift of Figs 10-11 (washer.paper.spinup): the spin-up torque against the
    suspension's static yaw curve, and Figs 10-11 rerun with the slower spin-up
    that curve calls for (tau_s from `spinup.slow_tau_s`)."""
    curve = sp.yaw_curve(params)
    tau = sp.slow_tau_s(params, curve)
    slow = {}
    for fig in ("fig10", "fig11"):
        cp, t_end = SETUPS[fig]["C_p"], SETUPS[fig]["t_end"]
        progress(f"  {fig} with a slower spin-up: tau_s = {tau:g} s, C_p = {cp:g}, {t_end:g} s")
        model = Model(params.replace(C_p=cp, tau_s=tau))
        r = simulate(model, t_end, system="fixed", law="spinup", samples_per_s=500.0,
                     progress=False)
        slow[fig] = dict(response=r, orbit=an.orbit(r, SPECTRUM_FROM),
                         yaw=sp.yaw_response(r, 3 * tau))
    paper = {fig: resp[fig]["yaw"] for fig in ("fig10", "fig11")}
    # The symmetric tub's twist curve, followed past its tilt pitchfork out to the twist
    # the paper's spin-ups reach (the curve in Q above stops where the tub tips).
    reach = max(y.gamma_peak for y in paper.values())
    twist = sp.twist_curve(params.replace(m_u=0.0), gamma_end=-max(1.2, 1.05 * reach),
                           n=max(49, int(60 * reach)))
    return dict(curve=curve, twist=twist, torque=sp.spin_torque(params),
                torque_slow=sp.spin_torque(params.replace(tau_s=tau)), tau_slow=tau, slow=slow,
                paper=paper)


def long_whirl(params, progress=print) -> dict:
    """Fig 11 (C_p = 0) run long enough for the whirl to grow: the paper's 50 s plus
    LONG_EFOLDINGS e-folding times of the averaged system's unstable pair at C_p = 0."""
    cp = SETUPS["fig11"]["C_p"]
    model = Model(params.replace(C_p=cp))
    sigma = float(model.eigenvalues(model.rotating_equilibrium()).real.max())   # 1/s
    t_end = float(np.ceil((SETUPS["fig11"]["t_end"] + LONG_EFOLDINGS / sigma) / 10) * 10)
    progress(f"  fig11 long: C_p = {cp:g}, {t_end:g} s (growth rate {sigma:.4f} 1/s)")
    r = simulate(model, t_end, system="fixed", law="spinup", samples_per_s=LONG_SAMPLES,
                 progress=False)
    return dict(C_p=cp, sigma=sigma, efoldings=LONG_EFOLDINGS, response=r, z_static=float(model.static_equilibrium()[2]),
                rise=an.height_rise(r, WINDOW))


def simulation_failures(resp: dict) -> dict:
    """{run: status} of the time responses that did not reach their end ("ok")."""
    runs = {f"{fig} ({frame})": r for fig in ("fig8", "fig9")
            for frame, r in resp[fig]["responses"].items()}
    runs.update({fig: resp[fig]["response"] for fig in ("fig10", "fig11")})
    runs.update({f"{fig} (tau_s = {resp['spinup']['tau_slow']:g} s)": v["response"]
                 for fig, v in resp["spinup"]["slow"].items()})
    runs["fig11 long"] = resp["fig11_long"]["response"]
    return {k: r.status for k, r in runs.items() if r.status != "ok"}


def measure(curves: dict, results: dict, params) -> dict:
    """Everything the report states, from the runs."""
    m = {"hopf": {}, "trends": {}, "ends": {}, "fit": {}, "peak": {}, "gh": {}}
    for frame, (_, sfx) in FRAMES.items():
        hb = results[f"washer{sfx}"]("HB1")
        m["hopf"][frame] = dict(C_p=float(hb.par[0]), omega=2 * np.pi / float(hb.par[10]),
                                l1=hb.info.get("l1"), criticality=hb.info.get("criticality"),
                                stable_low=bool(results[f"washer{sfx}"]("EP1").stable),
                                stable_high=bool(results[f"washer{sfx}"]("UZ1").stable))
        for key in ("Omega", "m_u", "R_u", "C_a", "K_s"):
            c = curves[f"washer.hopf.{key}{sfx}"]
            m["trends"][(key, frame)] = an.hopf_trend(c)
            m["ends"][(key, frame)] = an.curve_end_reasons(c, "C_p", key)
            m["gh"][(key, frame)] = an.specials_of(c, "GH")
        c = curves[f"washer.hopf.C_a{sfx}"]
        m["peak"][frame] = an.curve_peak(c)
        mr = curves[f"washer.hopf.m_u_R_u{sfx}"]
        inside = (mr.p1 > 0) & (mr.p2 > 0)
        m["fit"][frame] = an.fit_inverse(mr.p1[inside], mr.p2[inside])
        m["ends"][("m_u_R_u", frame)] = an.curve_end_reasons(mr, "m_u", "R_u")
    model = Model(params)
    m["q_star"] = model.static_equilibrium()
    m["q_star_no_imbalance"] = Model(params.replace(m_u=0.0)).static_equilibrium()
    m["eps_star"] = {f: model.rotating_equilibrium(frame=f) for f in FRAMES}
    e3 = curves["washer.eps3"]
    order = np.argsort(e3.p1)
    m["eps3_K_s"] = (e3.p1[order], e3.u[order, 2])
    return m


def write_summary(path: Path, m: dict, resp: dict) -> None:
    """The headline numbers in machine-readable form (SI units, Omega in Hz)."""
    from dataclasses import asdict
    out = {"hopf": m["hopf"],
           "C_a_peak": {f: dict(zip(("C_a", "C_p", "interior"), v)) for f, v in m["peak"].items()},
           "fit_R_u_vs_inv_m_u": {f: asdict(v) for f, v in m["fit"].items()},
           "trends": {f"{k}/{f}": asdict(v) for (k, f), v in m["trends"].items()},
           "q_star": list(m["q_star"]), "eps_star": {f: list(v) for f, v in m["eps_star"].items()}}
    for fig in ("fig8", "fig9"):
        out[fig] = {f: dict(asdict(resp[fig]["settling"][f]), sigma=resp[fig]["sigma"][f])
                    for f in FRAMES}
    for fig in ("fig10", "fig11"):
        out[fig] = asdict(resp[fig]["orbit"])
    S, c = resp["spinup"], resp["spinup"]["curve"]
    out["spinup"] = dict(torque=asdict(S["torque"]), torque_slow=asdict(S["torque_slow"]),
                         yaw_stiffness_lin=c.k_lin, yaw_moment_max=c.M_max,
                         gamma_at_fold=c.gamma_max, tau_slow=S["tau_slow"],
                         paper={f: asdict(v) for f, v in S["paper"].items()},
                         slow={f: dict(yaw=asdict(v["yaw"]), orbit=asdict(v["orbit"]))
                               for f, v in S["slow"].items()})
    L = resp["fig11_long"]
    rise = L["rise"]
    out["fig11_long"] = dict(sigma=L["sigma"], t_end=float(L["response"].t[-1]),
                             z_static=L["z_static"], z_end=rise.z_end, dz_last=rise.dz_last,
                             t_level=rise.t_level, radius_end=float(rise.radius[-1]),
                             window_z=rise.z.tolist(), window_radius=rise.radius.tolist())
    write_text(path, json.dumps(out, indent=1, default=float))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m washer.paper", description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="coarser steps, shorter Figs 8-9")
    ap.add_argument("--out", type=Path, default=Path("out/paper"), help="output folder")
    args = ap.parse_args(argv)
    from washer.atomic import OutputError, check_folder
    from washer.locks import LockedError, output_lock
    try:
        check_folder(args.out)          # before hours of work, not after
        with output_lock(args.out, "paper", what=f"the reproduction in {args.out}"):
            return _main(args)
    except KeyboardInterrupt as exc:
        # Anywhere in the job (runs, figures, the sections beyond the paper): the report
        # is written last and whole, so an interrupt leaves the previous one.
        print(f"\ninterrupted{': ' + str(exc) if str(exc) else ''}; no report written",
              file=sys.stderr)
        return 130
    except OutputError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except LockedError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 75


def _main(args) -> int:
    """The job of `main`, with args.out checked and locked."""
    import matplotlib
    matplotlib.use("Agg")
    from washer.paper import report
    from washer.paper import figures as plots

    t0 = time.perf_counter()
    params = load_params()
    mode = "quick" if args.quick else "full"
    print(f"Reproducing the paper's section 3 ({mode} mode) into {args.out}")
    try:
        print("AUTO runs (Figs 3-7):")
        curves, results, log = run_all(args.out, quick=args.quick)
        t_auto = time.perf_counter() - t0
        print("Time responses (Figs 8-11):")
        t1 = time.perf_counter()
        resp = time_responses(params, args.quick)
        t_sim = time.perf_counter() - t1
    except KeyboardInterrupt as exc:
        print(f"\ninterrupted{': ' + str(exc) if str(exc) else ''}; no report written",
              file=sys.stderr)
        return 130
    # Judging a curve that did not finish would call a partial result "reproduced":
    # any failed run (AUTO or time response) means no verdicts, only the failures.
    failed = dict(log.failed(), **simulation_failures(resp))
    if failed:
        timing = dict(auto=t_auto, sim=t_sim, total=time.perf_counter() - t0)
        path = report.write_incomplete(args.out, failed, log, mode=mode, timing=timing)
        for k, v in failed.items():
            print(f"error: run {k} failed: {v}", file=sys.stderr)
        print(f"Report (incomplete, no verdicts): {path}", file=sys.stderr)
        return 1
    meas = measure(curves, results, params)

    print("Figures:")
    figs = {}
    both = lambda key: {f: curves[f"{key}{sfx}"] for f, (_, sfx) in FRAMES.items()}
    d = args.out
    figs["fig3"] = plots.fig3(both("washer"), d / "fig3_branch_Cp")
    figs["fig4"] = plots.fig_hopf(both("washer.hopf.Omega"), "Omega",
                                  r"Fig. 4: Hopf curve in $(\Omega, C_p)$", d / "fig4_hopf_Omega")
    figs["fig5"] = plots.fig5(both("washer.hopf.m_u"), both("washer.hopf.R_u"),
                              both("washer.hopf.m_u_R_u"), meas["fit"], d / "fig5_hopf_imbalance")
    figs["fig6"] = plots.fig_hopf(both("washer.hopf.C_a"), "C_a",
                                  r"Fig. 6: Hopf curve in $(C_a, C_p)$", d / "fig6_hopf_Ca",
                                  paper_x=an.PAPER["C_a_peak"],
                                  paper_label=f"paper's peak, $C_a$ = {an.PAPER['C_a_peak']:g}",
                                  note_right=True)
    figs["fig7"] = plots.fig7(both("washer.hopf.K_s"), curves["washer.eps3"], params["C_p"],
                              d / "fig7_Ks")
    for fig, title in (("fig8", "Fig. 8: rotating frame, $C_p$ = 0.15 N m s/rad"),
                       ("fig9", "Fig. 9: rotating frame, $C_p$ = 0 N m s/rad")):
        figs[fig] = plots.fig_rotating(resp[fig]["responses"], resp[fig]["eq"], title,
                                       d / f"{fig}_rotating")
    for fig, title in (("fig10", "Fig. 10: spin-up, $C_p$ = 0.15 N m s/rad"),
                       ("fig11", "Fig. 11: spin-up, $C_p$ = 0 N m s/rad")):
        figs[fig] = plots.fig_spinup(resp[fig]["response"], resp[fig]["orbit"], title,
                                     d / f"{fig}_spinup", plot_from=SETUPS[fig]["orbit_from"])
    figs["spinup"] = plots.fig_yaw(resp["spinup"], {f: resp[f] for f in ("fig10", "fig11")},
                                   d / "fig10_11_yaw")
    figs["fig11_long"] = plots.fig_long(resp["fig11_long"], d / "fig11_long",
                                        SETUPS["fig11"]["t_end"])
    for fig in ("fig10", "fig11"):
        resp[fig]["response"].save(d / "data" / fig)
        resp["spinup"]["slow"][fig]["response"].save(d / "data" / f"{fig}_slow")
    resp["fig11_long"]["response"].save(d / "data" / "fig11_long")
    for fig in ("fig8", "fig9"):
        for frame, r in resp[fig]["responses"].items():
            r.save(d / "data" / f"{fig}_{frame}")
    # The exact question behind Figs 3-4: Floquet stability of the forced
    # periodic response of eq 48 at constant speed, beside the averaged/frozen Hopf.
    print("Exact stability of the forced response (Floquet multipliers, shooting):")
    from washer.paper import exact_stability
    t2 = time.perf_counter()
    exact = exact_stability.compute(params, args.quick, ends=not args.quick,
                                    progress=lambda m: print(m, flush=True))
    exact_files = exact_stability.write(d, exact)
    t_exact = time.perf_counter() - t2
    # The whirl past the Hopf point: the periodic orbits down to C_p = 0
    # against the long-time envelope of the Fig 9 simulation.
    print("The self-excited whirl (periodic orbits, IPS = 2):")
    from washer.paper import whirl
    fam = whirl.whirl_family(d / "auto", progress=lambda m: print(m, flush=True))
    if fam.status != "ok":
        print(f"error: run washer.po failed: {fam.status}", file=sys.stderr)
        return 1
    env = whirl.simulated_envelope(params, whirl.T_LONG_QUICK if args.quick else whirl.T_LONG)
    whirl_cmp = whirl.compare(fam, env)
    whirl_files = whirl.plot(fam, whirl_cmp, d / "whirl_orbits")
    # Beyond the paper: the exact whirl (no averaging) beside the averaged orbits, the
    # damping a clearance needs, the mechanism, and the estimates' weight.
    print("Beyond the paper: exact whirl, clearance, mechanism, sensitivity:")
    from washer.paper import exact_whirl, mechanism, sensitivity
    say = lambda m: print(m, flush=True)
    t3 = time.perf_counter()
    ex = exact_whirl.compute(params, averaged=fam, quick=args.quick, progress=say)
    mech = mechanism.compute(params, progress=say)
    sens = sensitivity.compute(params, progress=say)
    beyond_files = (exact_whirl.plot(ex, d / "exact_whirl")
                    + exact_whirl.plot_clearance(ex, d / "clearance")
                    + mechanism.plot(mech, d / "mechanism"))
    t_beyond = time.perf_counter() - t3
    wall = time.perf_counter() - t0
    write_summary(d / "measurements.json", meas, resp)
    path = report.write(d, params, meas, resp, figs, log, mode=mode,
                        timing=dict(auto=t_auto, sim=t_sim, total=wall))
    # The report is replaced whole (washer.atomic), never appended to in place.
    write_text(path, path.read_text(encoding="utf-8")
               + "\n" + whirl.markdown(fam, whirl_cmp, "whirl_orbits.png") + "\n"
               + "\n" + exact_stability.markdown(exact)
               + f"\n![Exact critical C_p on Fig 4](fig4_exact.png)\n\n"
               f"(computed in {t_exact:.1f} s: `python -m washer.paper.exact_stability` reruns it)\n"
               + "\n" + exact_whirl.markdown(ex, "exact_whirl.png") + "\n"
               + "\n" + exact_whirl.clearance_markdown(ex, "clearance.png") + "\n"
               + "\n" + mechanism.markdown(mech, "mechanism.png") + "\n"
               + "\n" + sensitivity.markdown(sens)
               + f"\n(these four sections computed in {t_beyond:.1f} s)\n")
    for k, paths in figs.items():
        print(f"  {k}: " + ", ".join(p.name for p in paths))
    print("  forced: " + ", ".join(p.name for p in exact_files))
    print("  whirl: " + ", ".join(p.name for p in whirl_files))
    print("  beyond: " + ", ".join(p.name for p in beyond_files))
    print(f"Report: {path}")
    print(f"Wall time ({mode} mode): {time.perf_counter() - t0:.1f} s "
          f"(AUTO runs {t_auto:.1f} s, time responses {t_sim:.1f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
