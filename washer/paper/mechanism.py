"""The mechanism of the whirl: which damper drives it, which mode it is, how the modes move
with the speed.

Three measurements on the averaged rotating frame (the system whose Hopf point is the
critical C_p to ~1e-5, docs/model.md section 4):

* `damper_shares`: the growth rate of the critical mode split by damper, exactly (the
  undamped pair is neutral, so Re(lambda) is the integral of its damping derivatives
  along the ray from no damping); 4 pi share / omega is the energy each damper puts into
  the mode per cycle as a fraction of the mode's energy.
* `campbell`: the eigenfrequencies against Omega, seen from the ground. A rotating-frame
  mode e^{i w t} whose tub offset eps1 + i eps2 = a e^{i w t} + b e^{-i w t} appears in the
  ground frame (x + i y = e^{i 2 pi Omega t} (eps1 + i eps2)) at 2 pi Omega + w (from a)
  and 2 pi Omega - w (from b); the larger of |a|, |b| (tilt included) names its frequency,
  signed (> 0: forward whirl). Axisymmetric modes (bounce, yaw) keep w.
* `hopf_mode`: the critical eigenvector in the ground frame: translation and tilt
  amplitudes and the height on the tub's axis that stands still (the whirl's pivot).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from washer.machine.model import Model
from washer.machine.params import Params
from washer.problems.rotating import averaged_hopf

TWO_PI = 2.0 * np.pi
#: The dampers: kernel parameter and what it is (with tied dampings C_p moves the three
#: joint coefficients together; here they are split).
DAMPERS = {"C_a": "axial dampers (along the rods)",
           "C_p": "joint damping P (rod swinging, translation)",
           "C_ox": "joint damping about the rod axis",
           "C_oz": "joint damping across the rod axis"}
#: Relative step of the central differences in each damping coefficient (the eigenvalue
#: is smooth in them; truncation ~h^2, round-off ~1e-13/h).
REL_STEP = 1e-4


def _critical_eigenvalue(params: Params, near: complex, eps_guess=None):
    """(lambda nearest `near` (Im > 0), its right eigenvector (12,), eps*) at params."""
    m = Model(params)
    eps = m.rotating_equilibrium(guess=eps_guess) if eps_guess is not None else \
        m.rotating_equilibrium()
    J = m.jac_rot(np.r_[eps, np.zeros(6)])[0]
    lam, V = np.linalg.eig(J)
    i = int(np.argmin(np.abs(lam - near)))
    return lam[i], V[:, i], eps


def untied(params: Params) -> Params:
    """The same machine with its joint coefficients given one by one (C_ox, C_oz = C_p
    when tied), so each can be moved alone."""
    return params.replace(C_ox=params["C_ox"], C_oz=params["C_oz"])


#: Gauss-Legendre nodes on the ray s C, s in (0, 1), of the exact split.
RAY_NODES = 8


def damper_shares(params: Params) -> dict:
    """Split of the critical mode's growth rate by damper at `params`.

    Every damping force is linear in its coefficient, and with all dampings zero the
    critical pair lies on the imaginary axis, so along the ray s C (s from 0 to 1)

        Re lambda(C) = sum_k C_k int_0^1 dRe(lambda)/dC_k (s C) ds

    exactly (the Aumann-Shapley split; it reduces to C_k dRe/dC_k when Re(lambda) is
    first order in the dampings, which it is not here: the axial dampers alone give
    Re(lambda) ~ C_a^0.6). Each term is that damper's share of the growth rate; 4 pi
    share / Im(lambda) is the energy it puts into the mode per cycle, as a fraction of the
    mode's energy (a mode e^{lambda t} changes its energy by 2 Re(lambda) 2 pi / omega per
    cycle). The integral: RAY_NODES Gauss-Legendre nodes, the mode followed from s = 1
    down by nearest eigenvalue, derivatives by central differences (REL_STEP).

    Returns lambda (the critical eigenvalue: largest real part with Im > 0, 1/s), per
    damper: what, value, dRe_dC at C itself, share (1/s), energy_per_cycle; 'sum' of the
    shares against 're_lambda' (their difference is the quadrature's error)."""
    p = untied(params)
    m = Model(p)
    eps0 = m.rotating_equilibrium()
    lam_all = m.eigenvalues(eps0)
    lam0 = complex(lam_all[np.argmax(np.where(lam_all.imag > 0, lam_all.real, -np.inf))])
    x, wq = np.polynomial.legendre.leggauss(RAY_NODES)
    nodes, weights = 0.5 * (x + 1.0), 0.5 * wq
    C = {k: p[k] for k in DAMPERS}
    integral = {k: 0.0 for k in DAMPERS}
    at_one = {}
    near, eps = lam0, eps0
    for s in [1.0] + sorted(nodes, reverse=True):
        ps = p.replace(**{k: s * c for k, c in C.items()})
        near, _, eps = _critical_eigenvalue(ps, near, eps)
        for k, c in C.items():
            sc = s * c
            h = REL_STEP * max(abs(sc), 1.0 if k == "C_a" else 1e-3)
            lo, hi = max(sc - h, 0.0), sc + h
            l_hi = _critical_eigenvalue(ps.replace(**{k: hi}), near, eps)[0]
            l_lo = _critical_eigenvalue(ps.replace(**{k: lo}), near, eps)[0]
            d = (l_hi.real - l_lo.real) / (hi - lo)
            if s == 1.0:
                at_one[k] = d
            else:
                integral[k] += weights[np.argmin(np.abs(nodes - s))] * c * d
    rows = {k: {"what": DAMPERS[k], "value": C[k], "dRe_dC": at_one[k], "share": integral[k],
                "energy_per_cycle": 4 * np.pi * integral[k] / lam0.imag} for k in DAMPERS}
    return {"lambda": lam0, "dampers": rows, "sum": sum(integral.values()),
            "re_lambda": lam0.real}


@dataclass
class Campbell:
    """Omega (n,) Hz; freq (n, 6) Hz: ground-frame frequency of each mode pair (signed:
    > 0 forward whirl, < 0 backward), rate (n, 6) 1/s: its real part, kind (n, 6) str:
    'whirl' (translation/tilt, in the plane) or 'axial' (bounce/yaw)."""
    Omega: np.ndarray
    freq: np.ndarray
    rate: np.ndarray
    kind: np.ndarray


def ground_frequency(lam: complex, v: np.ndarray, Omega: float) -> tuple[float, str]:
    """The ground-frame frequency (Hz, signed) of the rotating-frame mode lambda (Im > 0),
    eigenvector v (12,), at speed Omega (Hz) (module docstring)."""
    w = lam.imag
    a = b = 0.0
    for i, j in ((0, 1), (3, 4)):       # tub offset and tilt: the in-plane content
        a += abs((v[i] + 1j * v[j]) / 2) ** 2
        b += abs((np.conj(v[i]) + 1j * np.conj(v[j])) / 2) ** 2
    axial = abs(v[2]) ** 2 + abs(v[5]) ** 2
    if axial > a + b:
        return w / TWO_PI, "axial"
    W = TWO_PI * Omega
    return ((W + w) if a > b else (W - w)) / TWO_PI, "whirl"


def campbell(params: Params, omegas) -> Campbell:
    """Ground-frame frequencies and real parts of the six mode pairs of the averaged
    system's equilibrium at each Omega (Hz), other parameters from `params`."""
    F, R, K = [], [], []
    for om in omegas:
        m = Model(params.replace(Omega=float(om)))
        eps = m.rotating_equilibrium()
        lam, V = np.linalg.eig(m.jac_rot(np.r_[eps, np.zeros(6)])[0])
        up = np.flatnonzero(lam.imag > 1e-9)
        rows = sorted(((ground_frequency(lam[i], V[:, i], om), lam[i].real) for i in up),
                      key=lambda r: abs(r[0][0]))
        F.append([r[0][0] for r in rows][:6] + [np.nan] * (6 - len(rows[:6])))
        K.append([r[0][1] for r in rows][:6] + [""] * (6 - len(rows[:6])))
        R.append([r[1] for r in rows][:6] + [np.nan] * (6 - len(rows[:6])))
    return Campbell(np.asarray(omegas, float), np.array(F), np.array(R), np.array(K))


def rod_lines_meet(params: Params) -> float:
    """Height (m, above plane A at the static equilibrium) where the lines of the rods
    meet the vertical axis, for the symmetric layout (all upper joints on one radius and
    height, all lower ones on another): the instantaneous centre of a small swing of the
    tub on its rods, from the geometry alone."""
    up, lo = params.upper_joints(), params.lower_joints()
    R_P, z_P = float(np.hypot(*up[0, :2])), float(up[0, 2])
    R_O = float(np.hypot(*lo[0, :2]))
    z_A = float(Model(params).static_equilibrium()[2]) + float(lo[0, 2])
    return -R_O * (z_P - z_A) / (R_P - R_O)


def hopf_mode(params: Params) -> dict:
    """The critical mode at the averaged Hopf point in C_p: ground-frame whirl frequency
    (Hz), the tub's translation amplitude per unit tilt (m/rad), and the pivot: the height
    s (m, along the tub axis from plane A) where the point of the axis stands still,
    s = -<r, t> / <t, t> with r = eps1 + i eps2 and t = eps5 - i eps4 the complex
    translation and tilt (small angles: the axis point at s moves by r + s t)."""
    cp, lam = averaged_hopf(params)
    q = params.replace(C_p=cp)
    pair = lam[np.argmax(np.where(lam.imag > 0, -np.abs(lam.real), -np.inf))]
    lam_c, v, eps = _critical_eigenvalue(q, pair)
    f_g, _ = ground_frequency(lam_c, v, q["Omega"])
    # Whirl components in the ground frame: the dominant circular component of each.
    use_b = abs((np.conj(v[0]) + 1j * np.conj(v[1])) / 2) > abs((v[0] + 1j * v[1]) / 2)
    def circ(x, y):
        return (np.conj(x) + 1j * np.conj(y)) / 2 if use_b else (x + 1j * y) / 2
    r = circ(v[0], v[1])
    t = circ(v[4], -v[3])            # axis direction A e_z ~ (beta, -alpha) for small angles
    s = float(-(np.conj(t) * r).real / abs(t) ** 2)
    return {"C_p": float(cp), "lambda": complex(lam_c), "f_whirl": float(f_g),
            "r_per_tilt": float(abs(r) / abs(t)), "pivot": s,
            "phase": float(np.angle(r / t)), "bounce": float(abs(v[2]) / abs(r)),
            "yaw": float(abs(v[5]) / abs(t)), "eps": np.asarray(eps),
            "r": complex(r / abs(t)), "t": complex(t / abs(t))}


# ------------------------------------------------------------------ report

#: Speeds of the Campbell diagram (Hz).
CAMPBELL_OMEGA = np.linspace(0.5, 15.0, 30)


def compute(params: Params, progress=print) -> dict:
    """Everything the mechanism section states: the damper split at the averaged Hopf point
    and at C_p = 0, the C_a = 0 check, the Hopf mode and the Campbell diagram."""
    progress("  mechanism: damper shares, Hopf mode, Campbell diagram")
    mode = hopf_mode(params)
    at_hopf = damper_shares(params.replace(C_p=mode["C_p"]))
    at_zero = damper_shares(params.replace(C_p=0.0))
    m = Model(params.replace(C_a=0.0, C_p=0.0))
    lam_free = m.eigenvalues(m.rotating_equilibrium())
    no_axial = {"max_re_undamped": float(lam_free.real.max())}
    for cp in (0.01, 0.101):
        mm = Model(params.replace(C_a=0.0, C_p=cp))
        no_axial[f"max_re_C_p_{cp:g}"] = float(mm.eigenvalues(mm.rotating_equilibrium()).real.max())
    return {"mode": mode, "at_hopf": at_hopf, "at_zero": at_zero, "no_axial": no_axial,
            "rod_lines_meet": rod_lines_meet(params),
            "campbell": campbell(params, CAMPBELL_OMEGA), "Omega": params["Omega"]}


def markdown(res: dict, figure: str) -> str:
    h, z, mo, na = res["at_hopf"], res["at_zero"], res["mode"], res["no_axial"]
    rows = [f"| {k} | {r['what']} | {r['value']:g} | {r['share']:+.4f} | "
            f"{100 * r['energy_per_cycle']:+.2f} % | {z['dampers'][k]['share']:+.4f} |"
            for k, r in h["dampers"].items()]
    return "\n".join([
        "## The mechanism: a pendulum whirl driven by the axial dampers",
        "",
        f"The critical mode is a forward whirl of the tub on its rods at "
        f"{mo['f_whirl']:.3f} Hz (ground frame) at the Hopf point, C_p = {mo['C_p']:.5f}: "
        f"the tub translates {mo['r_per_tilt']:.2f} m per radian of tilt, nearly in phase "
        f"({np.degrees(mo['phase']):.1f} deg), so it swings about a point of its axis "
        f"{abs(mo['pivot']):.2f} m below plane A (the rods' lines meet the axis "
        f"{abs(res['rod_lines_meet']):.2f} m below it: the suspension's virtual pivot); "
        f"bounce and yaw take part only at {100 * mo['bounce']:.1f} % and "
        f"{100 * mo['yaw']:.1f} %.",
        "",
        "Growth rate of that mode split by damper (exact split along the ray from no "
        "damping, `washer.paper.mechanism.damper_shares`; energy per cycle as a fraction of "
        "the mode's energy; > 0 feeds the whirl):",
        "",
        "| damper | what | value | share at the Hopf point (1/s) | energy per cycle | "
        "share at C_p = 0 (1/s) |",
        "|---|---|---|---|---|---|",
        *rows,
        f"| sum | | | {h['sum']:+.2e} (Re lambda {h['re_lambda']:+.2e}) | | "
        f"{z['sum']:+.4f} (Re lambda {z['re_lambda']:+.4f}) |",
        "",
        "The axial dampers are the only source: they feed the whirl about "
        f"{100 * h['dampers']['C_a']['energy_per_cycle']:.1f} % of its energy per cycle, and "
        "the joint damping takes it out again (mostly the bending coefficient C_oz). Without "
        f"axial dampers (C_a = 0) the pair is neutral at C_p = 0 (largest real part "
        f"{na['max_re_undamped']:.1e} 1/s) and stable for any joint damping "
        f"({na['max_re_C_p_0.01']:.4f} 1/s at C_p = 0.01): C_p,crit = 0. A damper that "
        "feeds a mode is the signature of a dissipation-induced instability (damping "
        "acting on a gyroscopic system: here the spinning basket and the imbalance, seen "
        "from the frame that turns with them); the table measures the effect per damper, "
        "it does not by itself decide the energy argument behind it.",
        "",
        f"![Campbell diagram and damper shares]({figure})",
        "",
    ])


def plot(res: dict, stem) -> list:
    """(a) Campbell diagram: ground-frame frequencies of the mode pairs against Omega,
    unstable points marked; (b) the damper shares at the Hopf point and at C_p = 0; (c) the
    Hopf mode's shape: the tub's axis at eight phases of a cycle, with its pivot."""
    from pathlib import Path

    from washer.plots.style import figure, save
    c = res["campbell"]
    fig, (a, b, m) = figure(1, 3, figsize=(14, 3.9))
    for j in range(c.freq.shape[1]):
        f = np.abs(c.freq[:, j])
        fwd = c.freq[:, j] > 0
        a.plot(c.Omega, f, "-", color="0.6", lw=0.8)
        a.plot(c.Omega[fwd], f[fwd], "^", color="C0", ms=3)
        a.plot(c.Omega[~fwd], f[~fwd], "v", color="C1", ms=3)
        uns = c.rate[:, j] > 0
        a.plot(c.Omega[uns], f[uns], "o", mfc="none", mec="C3", ms=7)
    a.plot([], [], "^", color="C0", ms=3, label="forward whirl / axial")
    a.plot([], [], "v", color="C1", ms=3, label="backward whirl")
    a.plot([], [], "o", mfc="none", mec="C3", label="growing (reference C_p)")
    a.axvline(res["Omega"], color="0.5", ls=":", lw=0.8)
    a.set_xlabel(r"$\Omega$ (Hz)")
    a.set_ylabel("ground-frame frequency (Hz)")
    a.set_title("(a) Campbell diagram of the suspension modes (averaged frame)", loc="left",
                fontsize=9)
    a.legend(fontsize=7)
    names = list(res["at_hopf"]["dampers"])
    xs = np.arange(len(names))
    b.bar(xs - 0.2, [100 * res["at_hopf"]["dampers"][k]["energy_per_cycle"] for k in names],
          0.4, label=f"Hopf point (C_p = {res['mode']['C_p']:.3f})")
    b.bar(xs + 0.2, [100 * res["at_zero"]["dampers"][k]["energy_per_cycle"] for k in names],
          0.4, label="C_p = 0")
    b.axhline(0, color="k", lw=0.6)
    b.set_xticks(xs, names)
    b.set_ylabel("energy into the whirl per cycle (% of its energy)")
    b.set_title("(b) what each damper does to the critical mode", loc="left", fontsize=9)
    b.legend(fontsize=7)
    # (c) The mode's shape seen from the side: the tub's axis (plane A at s = 0 to 0.5 m
    # above it) at eight phases of one cycle, for a tilt of 0.1 rad, x = Re(e^{i phi}
    # (r + s t)); the point that stands still is the pivot.
    mo = res["mode"]
    s_axis = np.linspace(-1.2, 0.5, 50)
    tilt = 0.1
    for k, ph in enumerate(np.linspace(0, 2 * np.pi, 8, endpoint=False)):
        x = tilt * (np.exp(1j * ph) * (mo["r"] + s_axis * mo["t"])).real
        tub = s_axis >= 0
        m.plot(x[tub], s_axis[tub], "-", color="C0", lw=2.0, alpha=0.7)
        m.plot(x[~tub], s_axis[~tub], ":", color="C0", lw=0.8, alpha=0.5)
    m.plot([0], [mo["pivot"]], "ko", ms=5, label=f"pivot of the mode, {mo['pivot']:.2f} m")
    m.plot([0], [res["rod_lines_meet"]], "k^", ms=5,
           label=f"rod lines meet the axis, {res['rod_lines_meet']:.2f} m")
    m.axhline(0.0, color="0.5", lw=0.6)
    m.set_xlabel("horizontal offset of the axis (m), tilt 0.1 rad")
    m.set_ylabel("height along the tub axis above plane A (m)")
    m.set_title(f"(c) the Hopf mode: a pendulum whirl, {mo['f_whirl']:.3f} Hz", loc="left",
                fontsize=9)
    m.legend(fontsize=7, loc="lower right")
    return save(fig, Path(stem))
