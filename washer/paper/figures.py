"""The paper's Figs 3-11 drawn from our runs: averaged frame in colour, the frozen
(tau0 = 0) frame dashed grey, the paper's own figure where it gives one.

Each function takes Curves (`washer.paper.runs`) or Responses
(`washer.machine.responses`) plus the measured numbers, and saves PNG + PDF under `stem`.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from washer.paper.analysis import PAPER, spectrum
from washer.plots import style

LABELS = {"C_p": r"$C_p$ (N m s/rad)", "Omega": r"$\Omega$ (Hz)", "m_u": r"$m_u$ (kg)",
          "R_u": r"$R_u$ (m)", "C_a": r"$C_a$ (N s/m)", "K_s": r"$K_s$ (N/m)",
          "eps3": r"$\varepsilon_3$ (m)"}
FRAME_STYLE = {"averaged": dict(color="C0", lw=1.6, label="averaged over the frame angle"),
               "frozen": dict(color="0.45", lw=1.2, ls="--", label=r"frozen at $\tau_0 = 0$")}


#: Plain names of the special points the figures mark (AUTO's codes are jargon there).
SPECIAL_NAMES = {"HB": "Hopf", "LP": "fold", "GH": "generalised Hopf",
                 "BT": "Bogdanov-Takens", "ZH": "zero-Hopf"}


def _mark_specials(ax, curve, x_of, y_of, kinds=("HB", "LP", "GH", "BT", "ZH")):
    for t, i, _ in curve.specials:
        if t in kinds:
            ax.plot(x_of[i], y_of[i], "*" if t == "HB" else "o", color="C3", ms=8 if t == "HB" else 5,
                    zorder=5)
            ax.annotate(SPECIAL_NAMES.get(t, t), (x_of[i], y_of[i]), textcoords="offset points",
                        xytext=(4, 4), fontsize=8, color="C3")


def fig3(curves: dict, stem: Path) -> list[Path]:
    """Equilibrium branches in C_p: stable thick solid, unstable dotted; HB starred."""
    fig, ax = style.figure()
    for frame, c in curves.items():
        st = FRAME_STYLE[frame]
        for k in range(len(c.p1) - 1):
            stable = c.stable[k + 1]
            ax.plot(c.p1[k:k + 2], c.norm[k:k + 2], color=st["color"],
                    lw=2.4 if stable else 1.0, ls="-" if stable else ":")
        ax.plot([], [], color=st["color"], lw=2.4, label=f"{st['label']}: stable")
        ax.plot([], [], color=st["color"], lw=1.0, ls=":", label=f"{st['label']}: unstable")
        _mark_specials(ax, c, c.p1, c.norm, ("HB",))
    ax.set_xlabel(LABELS["C_p"])
    ax.set_ylabel(r"$L_2$-norm of $(\varepsilon, \dot\varepsilon)$")
    ax.set_title(r"Fig. 3: equilibrium against $C_p$ ($C_{ox} = C_{oy} = C_{oz} = C_p$)")
    ax.legend(fontsize=8)
    return style.save(fig, stem)


def hopf_panel(ax, curves: dict, xname: str, yname: str = "C_p", note_right: bool = False):
    """Hopf curves of both frames in (xname, yname); stable side labelled."""
    for frame, c in curves.items():
        if yname == "C_p":
            x, y = c.p2, c.p1
        else:
            x, y = c.p1, c.p2
        ax.plot(x, y, **FRAME_STYLE[frame])
        _mark_specials(ax, c, x, y, ("LP", "GH", "BT", "ZH"))
    if yname == "C_p":
        ax.text(0.97 if note_right else 0.03, 0.95, "stable above H\nunstable below",
                transform=ax.transAxes, va="top", ha="right" if note_right else "left", fontsize=8)
    ax.set_xlabel(LABELS[xname])
    ax.set_ylabel(LABELS[yname] if yname != "C_p" else r"critical $C_p$ (N m s/rad)")


def fig_hopf(curves: dict, xname: str, title: str, stem: Path, paper_x: float | None = None,
             paper_label: str = "", note_right: bool = False) -> list[Path]:
    fig, ax = style.figure()
    hopf_panel(ax, curves, xname, note_right=note_right)
    if paper_x is not None:
        ax.axvline(paper_x, color="C1", lw=1, ls="-.", label=paper_label)
    ax.set_title(title)
    ax.legend(fontsize=8, loc="lower right")
    return style.save(fig, stem)


def fig5(mu: dict, ru: dict, mr: dict, fits: dict, stem: Path) -> list[Path]:
    """(a) m_u-C_p, (b) R_u-C_p, (c) m_u-R_u with the R_u = a/m_u + b fits."""
    fig, axes = style.figure(1, 3, figsize=(13, 4.0))
    hopf_panel(axes[0], mu, "m_u")
    axes[0].set_title("(a) Hopf curve in $(m_u, C_p)$")
    hopf_panel(axes[1], ru, "R_u")
    axes[1].set_title("(b) Hopf curve in $(R_u, C_p)$")
    hopf_panel(axes[2], mr, "m_u", "R_u")
    m = np.linspace(max(0.3, min(c.p1.min() for c in mr.values())), 2.5, 200)
    f = fits["averaged"]
    axes[2].plot(m, f.slope / m + f.intercept, color="C2", lw=1, ls="-.",
                 label=f"fit: $R_u$ = {f.slope:.4f}/$m_u$ + {f.intercept:.4f}")
    axes[2].plot(m, PAPER["fit_slope"] / m + PAPER["fit_intercept"], color="C1", lw=1, ls=":",
                 label=f"paper: $R_u$ = {PAPER['fit_slope']}/$m_u$ + {PAPER['fit_intercept']}")
    axes[2].set_ylim(0, 0.26)
    axes[2].set_title("(c) Hopf curve in $(m_u, R_u)$, $C_p$ fixed")
    axes[2].legend(fontsize=7)
    axes[0].legend(fontsize=7, loc="lower right")
    return style.save(fig, stem)


def fig7(ks: dict, eps3_curve, C_p: float, stem: Path) -> list[Path]:
    fig, axes = style.figure(1, 2, figsize=(10, 4.0))
    hopf_panel(axes[0], ks, "K_s")
    axes[0].set_title("(a) Hopf curve in $(K_s, C_p)$")
    axes[0].legend(fontsize=7, loc="lower right")
    order = np.argsort(eps3_curve.p1)
    axes[1].plot(eps3_curve.p1[order], eps3_curve.u[order, 2], color="C0", lw=1.6,
                 label=f"averaged system, $C_p$ = {C_p:g}")
    axes[1].axhline(PAPER["eps3"], color="C1", ls=":", lw=1, label=r"paper's $\varepsilon_3$ = 0.408 at $K_s$ = 1800")
    axes[1].set_xlabel(LABELS["K_s"])
    axes[1].set_ylabel(r"equilibrium $\varepsilon_3$ (m)")
    axes[1].set_title(r"(b) $\varepsilon_3$ at the equilibrium")
    axes[1].legend(fontsize=7)
    return style.save(fig, stem)


EPS_LABELS = [r"$\varepsilon_1$ (m)", r"$\varepsilon_2$ (m)", r"$\varepsilon_3$ (m)",
              r"$\varepsilon_4$ (rad)", r"$\varepsilon_5$ (rad)", r"$\varepsilon_6$ (rad)"]


#: Window of the envelopes of Figs 8-9 (s): several periods of the ~9.4 Hz rotating-frame
#: oscillation, short against the seconds over which the envelope moves.
ENVELOPE_WINDOW = 0.5


def envelope(t, y, window: float = ENVELOPE_WINDOW):
    """(t (m,), lower (m,), upper (m,)): min and max of y over consecutive windows of
    `window` s, at each window's centre (a last window with less than half the samples of
    the others is left out)."""
    edges = np.arange(t[0], t[-1] + window, window)
    k = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, len(edges) - 1)
    lo = np.full(len(edges), np.nan)
    hi = np.full(len(edges), np.nan)
    np.fmin.at(lo, k, y)
    np.fmax.at(hi, k, y)
    count = np.bincount(k, minlength=len(edges))
    keep = count >= 0.5 * np.median(count[count > 0])     # no partial window at the end
    return (edges + window / 2)[keep], lo[keep], hi[keep]


def fig_rotating(responses: dict, eq: dict, title: str, stem: Path) -> list[Path]:
    """Figs 8-9: the six rotating-frame components against time as envelopes (min and max
    over ENVELOPE_WINDOW s: the ~9.4 Hz oscillation as a band would hide the other frame),
    averaged frame filled, frozen frame outlined, each frame's equilibrium a thin line."""
    fig, axes = style.figure(3, 2, figsize=(10, 7.5), sharex=True)
    for i, ax in enumerate(axes.T.ravel()):
        for frame, r in responses.items():
            st = FRAME_STYLE[frame]
            tm, lo, hi = envelope(r.t, r.y[:, i])
            if frame == "averaged":
                ax.fill_between(tm, lo, hi, color=st["color"], alpha=0.35, lw=0,
                                label=f"{st['label']} (envelope)")
            else:
                ax.plot(tm, lo, color=st["color"], lw=0.9, ls=st.get("ls", "-"),
                        label=f"{st['label']} (envelope)")
                ax.plot(tm, hi, color=st["color"], lw=0.9, ls=st.get("ls", "-"))
            ax.axhline(eq[frame][i], color=st["color"], lw=0.6, ls=":")
        ax.set_ylabel(EPS_LABELS[i])
    for ax in axes[-1]:
        ax.set_xlabel("t (s)")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle(title + f"  (min-max over {ENVELOPE_WINDOW:g} s windows)")
    return style.save(fig, stem)


def fig_spinup(r, orbit, title: str, stem: Path, plot_from: float) -> list[Path]:
    """Figs 10-11: y(t), z(t) of O_b, its XY trajectory for t >= plot_from (the
    paper's windows) and the amplitude spectrum of y(t) over the orbit's window."""
    fig, axes = style.figure(2, 2, figsize=(10, 7.0))
    axes[0, 0].plot(r.t, r.y[:, 1] * 1e3, lw=0.6)
    axes[0, 0].set_xlabel("t (s)")
    axes[0, 0].set_ylabel("y (mm)")
    axes[0, 0].set_title("(a) Y-direction movement of $O_b$")
    axes[0, 1].plot(r.t, r.y[:, 2] * 1e3, lw=0.6)
    axes[0, 1].set_xlabel("t (s)")
    axes[0, 1].set_ylabel("z (mm)")
    axes[0, 1].set_title("(b) Z-direction movement of $O_b$")
    sel = r.t >= plot_from
    axes[1, 0].plot(r.y[sel, 0] * 1e3, r.y[sel, 1] * 1e3, lw=0.6)
    axes[1, 0].set_aspect("equal", adjustable="datalim")
    axes[1, 0].set_xlabel("x (mm)")
    axes[1, 0].set_ylabel("y (mm)")
    axes[1, 0].set_title(f"(c) trajectory in plane XY, t in [{plot_from:g}, {r.t[-1]:g}] s")
    sel = r.t >= orbit.t_from
    f, amp = spectrum(r.t[sel], r.y[sel, 1])
    axes[1, 1].semilogy(f, np.maximum(amp * 1e3, 1e-9), lw=0.8)
    for fp in orbit.peaks:
        axes[1, 1].axvline(fp, color="C3", lw=0.5, ls=":")
    axes[1, 1].set_xlim(0, 25)
    axes[1, 1].set_ylim(max(1e-6, amp[1:].max() * 1e3 * 1e-5), amp[1:].max() * 1e3 * 3)
    axes[1, 1].set_xlabel("frequency (Hz)")
    axes[1, 1].set_ylabel("amplitude of y (mm)")
    axes[1, 1].set_title(f"(d) spectrum of y(t), t in [{orbit.t_from:g}, {r.t[-1]:g}] s")
    fig.suptitle(title)
    return style.save(fig, stem)


def fig_yaw(study: dict, paper: dict, stem: Path, t_show: float = 10.0) -> list[Path]:
    """The lift of Figs 10-11 explained: (a) the tub's yaw gamma(t) and (b) the height
    z(t) of O_b during the spin-up, at the paper's tau_s and the slower one, for both
    C_p; (c) the static yaw moment-angle curve of the suspension with the peak
    spin-up torques (`washer.paper.spinup`)."""
    fig, axes = style.figure(1, 3, figsize=(14, 4.2))
    tau, tau_slow = study["torque"].tau_s, study["tau_slow"]
    runs = [(f"$\\tau_s$ = {tau:g} s", paper, "-"), (f"$\\tau_s$ = {tau_slow:g} s", study["slow"], "--")]
    for label, rs, ls in runs:
        for fig_name, color in (("fig10", "C0"), ("fig11", "C3")):
            r = rs[fig_name]["response"]
            sel = r.t <= t_show
            cp = "0.15" if fig_name == "fig10" else "0"
            axes[0].plot(r.t[sel], r.y[sel, 5], ls=ls, color=color, lw=0.9,
                         label=f"{label}, $C_p$ = {cp}")
            axes[1].plot(r.t[sel], r.y[sel, 2] * 1e3, ls=ls, color=color, lw=0.9)
    axes[0].set_xlabel("t (s)")
    axes[0].set_ylabel(r"yaw $\gamma$ (rad)")
    axes[0].set_title(r"(a) the tub's yaw $\gamma(t)$")
    axes[0].legend(fontsize=7)
    axes[1].set_xlabel("t (s)")
    axes[1].set_ylabel("z (mm)")
    axes[1].set_title("(b) height of $O_b$")
    c, tw = study["curve"], study.get("twist")
    axes[2].plot(np.abs(c.gamma), np.abs(c.Q), "k-", lw=1.4,
                 label="at rest, imbalance on +x (ends where the tub tips)")
    axes[2].plot(abs(c.gamma_max), c.M_max, "ko", ms=5)
    axes[2].annotate(f"tips: {c.M_max:.1f} N m", (abs(c.gamma_max), c.M_max),
                     textcoords="offset points", xytext=(-70, 8), fontsize=8)
    reach = max(y.gamma_peak for y in paper_yaw(study))
    if tw is not None:
        up = tw.stiffness > 0
        axes[2].plot(np.abs(tw.gamma[up]), np.abs(tw.Q[up]), "-", color="0.45", lw=1.0,
                     label="no imbalance: moment to hold the twist")
        axes[2].plot(np.abs(tw.gamma[~up]), np.abs(tw.Q[~up]), ":", color="0.45", lw=1.0,
                     label="  ... past its tilt pitchfork (tub unstable)")
        axes[2].plot(abs(tw.gamma_tip), abs(tw.Q_tip), "o", mfc="w", mec="0.3", ms=5)
        axes[2].axvspan(tw.gamma_into_tub, max(reach, abs(tw.gamma[-1])) * 1.02, color="C3",
                        alpha=0.08, label=f"rods would pass through the tub (> {tw.gamma_into_tub:.2f} rad)")
    for y, name in zip(paper_yaw(study), ("Fig 10", "Fig 11")):
        axes[2].axvline(y.gamma_peak, color="0.6", lw=0.6, ls="-.")
    axes[2].plot([], [], "-.", color="0.6", lw=0.6, label="twist reached, Figs 10-11 (paper)")
    g = np.linspace(0, abs(c.gamma_max), 10)
    axes[2].plot(g, c.k_lin * g, ":", color="0.4", label=f"linearised, {c.k_lin:.1f} N m/rad")
    for st, color in ((study["torque"], "C3"), (study["torque_slow"], "C2")):
        axes[2].axhline(st.T_peak, color=color, lw=1.0, ls="--",
                        label=f"peak spin-up torque, $\\tau_s$ = {st.tau_s:g} s: {st.T_peak:.1f} N m")
    axes[2].set_xlim(0, max(reach, abs(c.gamma_max)) * 1.05)
    axes[2].set_ylim(0, study["torque"].T_peak * 1.15)
    axes[2].set_xlabel(r"$|\gamma|$ (rad)")
    axes[2].set_ylabel("yaw moment (N m)")
    axes[2].set_title("(c) yaw moment at rest vs spin-up torque")
    axes[2].legend(fontsize=6, loc="center right")
    fig.suptitle("Why the tub lifts in Figs 10-11: the spin-up torque twists it past the point where it tips")
    return style.save(fig, stem)


def paper_yaw(study: dict) -> list:
    """The yaw responses of the paper's spin-ups (Figs 10, 11) in a spin-up study."""
    return [study["paper"][f] for f in ("fig10", "fig11")]


def fig_long(long: dict, stem: Path, t_paper: float) -> list[Path]:
    """Fig 11 continued: z(t) of O_b and the orbit radius per window over the long
    C_p = 0 run, the paper's 50 s window marked."""
    r, rise = long["response"], long["rise"]
    fig, axes = style.figure(1, 2, figsize=(11, 4.0))
    axes[0].plot(r.t, r.y[:, 2] * 1e3, lw=0.4, color="C0")
    axes[0].step(rise.t, rise.z * 1e3, where="post", color="k", lw=1.2,
                 label=f"mean over {rise.window:g} s windows")
    axes[0].axhline(long["z_static"] * 1e3, color="0.5", ls=":", label="static z")
    axes[1].step(rise.t, rise.radius * 1e3, where="post", color="C3", lw=1.2)
    for ax in axes:
        ax.axvline(t_paper, color="0.4", ls="--", lw=0.8)
        ax.set_xlabel("t (s)")
    axes[0].set_ylabel("z (mm)")
    axes[0].set_title(f"(b) Z-direction movement of $O_b$, $C_p$ = {long['C_p']:g}")
    axes[0].legend(fontsize=8)
    axes[1].set_ylabel("orbit radius (mm)")
    axes[1].set_title("max distance of $O_b$ from its window mean (XY)")
    fig.suptitle(f"Fig. 11 run for {r.t[-1]:g} s (dashed: the paper's {t_paper:g} s)")
    return style.save(fig, stem)
