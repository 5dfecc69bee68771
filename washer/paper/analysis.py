"""Numbers measured on the runs: trends, curve ends, the R_u-m_u fit, the C_a peak,
equilibria and the behaviour of the time responses (paper section 3).

Every function takes computed data (Curves from `washer.paper.runs`, Responses
from `washer.simulate`) and returns plain numbers; nothing here is typed in
from the paper except the paper's own figures in `PAPER`, kept apart for the
comparison.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: The paper's published figures (section 3), for comparison only.
PAPER = {
    "C_p_hopf": 0.101,          # N m s/rad, Fig 3 and section 3.2.1
    "fit_slope": 0.1387,        # R_u = 0.1387 / m_u + 0.0114 (section 3.1, Fig 5(c))
    "fit_intercept": 0.0114,
    "C_a_peak": 154.0,          # N s/m (section 3.1, Fig 6)
    "q_star": [0.0, 0.05, 0.395, 0.095, 0.0, 0.0],     # m, rad (section 3.2.2)
    "eps3": 0.408,              # m (section 3.2.1)
    "settle_fig8": 20.0,        # s, "a fixed solution is achieved after t ~ 20 s"
}

#: Table 1's ranges (Omega in Hz; Table 1 gives K_s in "N s/m", a typo for N/m).
RANGES = {"Omega": (0.0, 15.0), "m_u": (0.0, 2.5), "R_u": (0.0, 0.25), "C_a": (0.0, 5000.0),
          "K_s": (500.0, 4500.0)}

#: |C_p| below this on a Hopf curve counts as "reaches zero" (N m s/rad).
ZERO_CP = 1e-8


@dataclass
class Trend:
    """Sign of d C_p,crit / d X along a Hopf curve in (C_p, X), where C_p,crit > 0.

    sign: +1, -1 or 0 (mixed); frac_up: share of the curve's steps with a positive
    slope; x: the X interval covered; cp: C_p,crit at its ends (N m s/rad)."""
    sign: int
    frac_up: float
    x: tuple
    cp: tuple


def hopf_trend(curve) -> Trend:
    x, cp = curve.p2, curve.p1
    keep = cp > -ZERO_CP          # the curve's end at C_p,crit = 0 counts
    x, cp = x[keep], cp[keep]
    order = np.argsort(x)
    x, cp = x[order], cp[order]
    dx, dc = np.diff(x), np.diff(cp)
    steps = dx > 0
    up = np.mean(dc[steps] > 0) if np.any(steps) else np.nan
    sign = 1 if up == 1.0 else -1 if up == 0.0 else 0
    return Trend(sign, float(up), (float(x[0]), float(x[-1])), (float(cp[0]), float(cp[-1])))


def curve_end_reasons(curve, name1: str = "C_p", name2: str = "") -> list[tuple[float, float, str]]:
    """For each end of a two-parameter curve in (PAR(ICP(1)) = name1, PAR(ICP(2)) =
    name2): (value of name1, value of name2, why the curve ends there)."""
    out = []
    for k, kind in ((0, curve.ends[0]), (-1, curve.ends[1])):
        v1, v2 = float(curve.p1[k]), float(curve.p2[k])
        out.append((v1, v2, _reason(kind, ((name1, v1), (name2, v2)))))
    return out


def _reason(kind: str, values) -> str:
    for name, v in values:
        if name == "C_p" and abs(v) < ZERO_CP:
            return ("C_p,crit reaches 0: beyond, the equilibrium is stable without any joint "
                    "damping (UZ stop at C_p = 0)")
    for name, v in values:
        lo, hi = RANGES.get(name, (None, None))
        for bound in (lo, hi):
            if bound is not None and abs(v - bound) <= 1e-6 * (1 + abs(bound)):
                return f"{name} reaches Table 1's limit {bound:g} (UZ stop)"
    for name, v in values:
        if name in RANGES and RANGES[name][0] == 0.0 and 0 < v <= 0.01 + 1e-12:
            return f"{name} reaches {v:g}, the stop set just above 0 (UZ stop)"
    return {"BT": "Bogdanov-Takens point: the Hopf frequency reaches 0",
            "MX": "no convergence at the minimum step (MX)",
            "EP": "NMX points reached (EP)"}.get(kind, f"AUTO ended the curve with {kind or 'no label'}")


@dataclass
class Fit:
    """R_u = slope / m_u + intercept fitted by least squares (the paper's polyfit)."""
    slope: float
    intercept: float
    max_residual: float       # m
    n: int


def fit_inverse(m_u: np.ndarray, R_u: np.ndarray) -> Fit:
    x = 1.0 / np.asarray(m_u)
    a, b = np.polyfit(x, R_u, 1)
    res = np.abs(R_u - (a * x + b))
    return Fit(float(a), float(b), float(res.max()), int(len(x)))


def curve_peak(curve) -> tuple[float, float, bool]:
    """(X, C_p) at the maximum of C_p,crit over the curve, and whether it is an
    interior maximum located by the engine (an LP in C_p on the Hopf curve)."""
    lps = [i for t, i, _ in curve.specials if t == "LP" and curve.p2[i] >= 0 and curve.p1[i] > 0]
    if lps:
        i = max(lps, key=lambda i: curve.p1[i])
        interior = curve.p1[i] > max(curve.p1[0], curve.p1[-1])
        return float(curve.p2[i]), float(curve.p1[i]), bool(interior)
    i = int(np.argmax(curve.p1))
    return float(curve.p2[i]), float(curve.p1[i]), False


def specials_of(curve, kind: str) -> list[tuple[float, float]]:
    return [(float(curve.p2[i]) if curve.p2 is not None else float("nan"), float(curve.p1[i]))
            for t, i, _ in curve.specials if t == kind]


# ----------------------------------------------------------------- time responses

@dataclass
class Settling:
    """Rotating-frame response against the equilibrium eps*.

    dist: max over the six components of |eps - eps*| at the end (m or rad);
    settle_t: last time the distance exceeds `tol` (s; nan if it never settles);
    late_amp: peak-to-peak of eps1 over the last quarter (m); grows: amplitude of
    the last quarter larger than the quarter before; rate: decay rate of that
    amplitude between the two quarters (1/s, negative when growing)."""
    dist: float
    settle_t: float
    late_amp: float
    grows: bool
    rate: float
    tol: float


def settling(r, eps_star: np.ndarray, tol: float = 1e-3) -> Settling:
    d = np.max(np.abs(r.y[:, :6] - eps_star), axis=1)
    above = np.nonzero(d > tol)[0]
    settled = d[-1] <= tol
    settle_t = float(r.t[above[-1]]) if (settled and above.size) else (0.0 if settled else np.nan)
    n = len(r.t)
    q1, q2 = slice(n // 2, 3 * n // 4), slice(3 * n // 4, n)
    a1 = np.ptp(r.y[q1, 0])
    a2 = np.ptp(r.y[q2, 0])
    dt = r.t[3 * n // 4] - r.t[n // 2]
    rate = float(np.log(a1 / a2) / dt) if a1 > 0 and a2 > 0 else float("nan")
    return Settling(float(d[-1]), settle_t, float(a2), bool(a2 > a1), rate, tol)


@dataclass
class Orbit:
    """Motion of O_b in the ground XY plane over [t_from, t_end].

    radius: mean distance from the window's centre (m), r_max: its maximum (m),
    spread: (max-min)/mean of that distance; peaks: frequencies (Hz) of the
    spectrum's peaks of y(t) above `rel` of the largest, strongest first; amps:
    their amplitudes (m); second: the largest other peak relative to the first;
    z_mean: mean height of O_b (m), z_trend: mean z of the window's second half
    minus its first half (m); r_growth: max radius of the second half over the first."""
    t_from: float
    radius: float
    r_max: float
    spread: float
    peaks: list
    amps: list
    second: float
    z_mean: float
    z_trend: float
    r_growth: float
    df: float


def orbit(r, t_from: float, rel: float = 0.1) -> Orbit:
    sel = r.t >= t_from
    t, x, y = r.t[sel], r.y[sel, 0], r.y[sel, 1]
    cx, cy = x.mean(), y.mean()
    rad = np.hypot(x - cx, y - cy)
    f, amp = spectrum(t, y)
    # Local maxima above rel * max, excluding the DC bin.
    pk = [i for i in range(1, len(amp) - 1)
          if amp[i] >= amp[i - 1] and amp[i] > amp[i + 1] and amp[i] >= rel * amp[1:].max()]
    pk.sort(key=lambda i: -amp[i])
    allpk = sorted((i for i in range(1, len(amp) - 1) if amp[i] >= amp[i - 1] and amp[i] > amp[i + 1]),
                   key=lambda i: -amp[i])
    second = float(amp[allpk[1]] / amp[allpk[0]]) if len(allpk) > 1 else 0.0
    z = r.y[sel, 2]
    h = len(z) // 2
    return Orbit(float(t_from), float(rad.mean()), float(rad.max()), float(np.ptp(rad) / rad.mean()),
                 [float(f[i]) for i in pk[:6]], [float(amp[i]) for i in pk[:6]], second,
                 float(z.mean()), float(z[h:].mean() - z[:h].mean()),
                 float(rad[h:].max() / rad[:h].max()), float(f[1] - f[0]))


def yaw_mode(model) -> tuple[float, float]:
    """(frequency (Hz), real part (1/s)) of the slow yaw mode of the averaged frame's
    equilibrium: the complex pair whose eigenvector is mostly gamma (eps6). Yaw is axial,
    so its frequency is the same seen from the ground."""
    eps = model.rotating_equilibrium()
    lam, V = np.linalg.eig(model.jac_rot(np.r_[eps, np.zeros(6)])[0])
    share = np.abs(V[5]) ** 2 / np.sum(np.abs(V[:6]) ** 2, axis=0)
    i = int(np.argmax(np.where(lam.imag > 0, share, -1.0)))
    return float(lam[i].imag / (2 * np.pi)), float(lam[i].real)


#: Mean height above the static one that counts as "O_b higher" (m): 30 times the
#: 0.3 mm the stable spin moves it (eps3 - z at C_p = 0.15).
RISE_MIN = 0.010
#: Window-to-window rise of the mean height that counts as "still rising" (m).
RISE_STEP = 0.001


@dataclass
class Rise:
    """Height of O_b over a long run, in consecutive windows of `window` s.

    t: window starts (n,) s; z: mean z per window (n,) m; radius: max distance of O_b
    from the window's mean XY position (n,) m; z_end: the last window's mean z (m);
    dz_last: last window's mean minus the one before (m); t_level: start of the first
    window after which the mean never changes by RISE_STEP or more (s; nan if it still
    does at the end)."""
    window: float
    t: np.ndarray
    z: np.ndarray
    radius: np.ndarray
    z_end: float
    dz_last: float
    t_level: float


def height_rise(r, window: float) -> Rise:
    n = int(r.t[-1] // window)
    t0 = np.arange(n) * window
    z, rad = np.empty(n), np.empty(n)
    for k, a in enumerate(t0):
        sel = (r.t >= a) & (r.t < a + window)
        x, y = r.y[sel, 0], r.y[sel, 1]
        z[k] = r.y[sel, 2].mean()
        rad[k] = np.hypot(x - x.mean(), y - y.mean()).max()
    moving = np.nonzero(np.abs(np.diff(z)) >= RISE_STEP)[0]
    t_level = float(t0[moving[-1] + 1]) if moving.size and moving[-1] + 1 < n - 1 else (
        float("nan") if moving.size else 0.0)
    return Rise(window, t0, z, rad, float(z[-1]), float(z[-1] - z[-2]), t_level)


def spectrum(t: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum of y(t) on a uniform grid, Hann window:
    (frequencies in Hz, amplitudes in y's unit; a sinusoid of amplitude A shows A)."""
    y = y - y.mean()
    w = np.hanning(len(y))
    F = np.fft.rfft(y * w)
    amp = 2 * np.abs(F) / w.sum()
    return np.fft.rfftfreq(len(y), t[1] - t[0]), amp
