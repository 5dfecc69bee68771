"""What a sweep computes at a point: plain functions of plain data.

`compute_batch(points, base)` is the unit of work shipped to a worker: a list
of point dicts (see `washer.sweep.points`) and the base parameter set as
{"values", "tied", "source"}; it returns one flat row (dict) per point. Every
kind is wrapped so that an exception becomes the point's error and never stops
the batch. Workers import the kernel through these imports (cffi objects never
cross a process boundary).

Kinds and their output columns (SI units, Omega in Hz, angles in rad):

stability  averaged (or frozen) rotating-frame equilibrium eps* (eqs 60-65) and
           the eigenvalues of its Jacobian (12, sorted by real part):
    stab_margin          largest real part, 1/s (< 0: stable)
    stab_whirl           |Im| of that eigenvalue, rad/s, rotating frame
    stab_whirl_ground    |2 pi Omega - stab_whirl|, rad/s: the same mode seen from
                         the ground (a whirl of the (x, y) plane; ~4 rad/s at the
                         reference point, as docs/model.md section 4)
    stab_damping_ratio   -Re/|lambda| of that eigenvalue (negative when unstable)
    stab_eps1..6         eps* (m, m, m, rad, rad, rad)
    stab_radius          hypot(eps1, eps2), m: the steady whirl radius of the
                         periodic response the equilibrium stands for
    stab_status          "stable", "unstable" or "failed"
critical   the critical value of one parameter at this point: the first Hopf
           point (HB) of a one-parameter continuation of the averaged equilibrium
           from `from` to `to` (the engine of washer.run, e='washer', with the
           point's parameter set injected: run(..., params=...)):
    crit_status          the answer: "hopf" (a critical value in the range),
                         "stable" (stable over the whole range, or neutral at `from`
                         and stable above: the critical value is at most `from`, and
                         crit_value = `from`; with C_p from 0, stable without joint
                         damping), "unstable" (unstable over the
                         whole range: more than `to` is needed, crit_value NaN), or
                         "failed" (no answer: the row's error says why)
    crit_value           the parameter at the HB (its units), `from` when stable
    crit_whirl           the crossing frequency 2 pi / PAR(11), rad/s, rotating frame
    crit_n_hopf          stability crossings located in [from, to] (HB points, or
                         the one root of the whirl pair's real part; 0 when stable
                         or unstable throughout)
    crit_whirl_growth    a in: the whirl's amplitude grows as a sqrt(critical - value)
                         below the critical value (m per sqrt of the parameter's unit;
                         Hopf normal form, `whirl_growth`); with option `clearance`
    crit_clearance_value the value at which the whirl's largest offset from the axis
                         reaches the option `clearance` (m): critical -+ ((clearance -
                         r0) / a)^2 (on the whirl's side), r0 the forced response's offset; NaN when r0 alone
                         exceeds the clearance or without the option; equal to
                         crit_value where stable throughout. Near the Hopf point only
                         (the normal form): for clearances of a few centimetres
    crit_source          how it was found: "HB" (the engine's Hopf point), "first steps"
                         (an HB on the engine's untested first steps, located by the
                         engine run again over them, see _critical_fallback), "ends"
                         (stable or unstable at both ends, no HB between),
                         "floquet" (engine = "floquet")
response   a time response (kernel DOPRI5) summarised over the last `window` s:
    resp_whirl_radius    mean of hypot(x, y) over the window, m (x, y: tub origin,
                         plane A; eps1, eps2 in the rotating frame: same radius)
    resp_whirl_radius_min, resp_whirl_radius_max    over the window, m
    resp_lift_max        max of z - z_static over the whole response, m
    resp_tilt_max        max tilt of the tub axis arccos(cos alpha cos beta) over
                         the whole response, rad (Cardan x-y-z, eq 2; in the rotating
                         frame from eps4, eps5: the same tilt to first order)
    resp_freq1, resp_freq2     the two largest peaks of the spectrum of
                         x + i y (mean removed, Hann window) over the window, Hz,
                         signed (> 0: counter-clockwise), in the simulated frame
    resp_amp1, resp_amp2 their amplitudes, m
    resp_nfev            right-hand-side evaluations
    resp_tau_s           the spin-up time constant used (s; the option `tau_s`, else
                         the parameter set's), NaN at constant speed
    resp_status          "ok" or "failed"

A row's `status` is "ok" when every kind gave its answer (a point stable without
joint damping is an answer, not a failure) and "failed" only when one could not
(its message in `error`). Units of every column: `UNITS` (also written into the
Parquet schema as field metadata, `washer.sweep.results`).
"""
from __future__ import annotations

import math
import time

import numpy as np

from washer.machine.model import Model
from washer.machine.params import Params

#: Output columns per kind (every row of a kind has all of them; NaN on failure).
OUTPUTS: dict[str, tuple[str, ...]] = {
    "stability": ("stab_status", "stab_margin", "stab_whirl", "stab_whirl_ground",
                  "stab_damping_ratio", "stab_eps1", "stab_eps2", "stab_eps3", "stab_eps4",
                  "stab_eps5", "stab_eps6", "stab_radius"),
    "critical": ("crit_status", "crit_value", "crit_whirl", "crit_n_hopf", "crit_source",
                 "crit_whirl_growth", "crit_clearance_value"),
    "response": ("resp_status", "resp_whirl_radius", "resp_whirl_radius_min",
                 "resp_whirl_radius_max", "resp_lift_max", "resp_tilt_max", "resp_freq1",
                 "resp_amp1", "resp_freq2", "resp_amp2", "resp_nfev", "resp_tau_s"),
}
#: Per-kind status column of each kind ("failed" when the kind raised).
STATUS = {"stability": "stab_status", "critical": "crit_status", "response": "resp_status"}
#: Output columns holding text (empty when the kind failed); the others are floats (NaN).
TEXT_OUTPUTS = {"crit_source"} | set(STATUS.values())
#: Units of the output columns ("" for dimensionless or text; crit_value has the units
#: of the study's parameter: `units_of` fills it in).
UNITS = {"stab_margin": "1/s", "stab_whirl": "rad/s", "stab_whirl_ground": "rad/s",
         "stab_damping_ratio": "", "stab_eps1": "m", "stab_eps2": "m", "stab_eps3": "m",
         "stab_eps4": "rad", "stab_eps5": "rad", "stab_eps6": "rad", "stab_radius": "m",
         "crit_whirl": "rad/s", "crit_n_hopf": "", "crit_averaged": None,
         "crit_clearance_value": None, "crit_whirl_growth": None,
         "crit_multiplier_angle": "rad",
         "resp_whirl_radius": "m", "resp_whirl_radius_min": "m", "resp_whirl_radius_max": "m",
         "resp_lift_max": "m", "resp_tilt_max": "rad", "resp_freq1": "Hz", "resp_amp1": "m",
         "resp_freq2": "Hz", "resp_amp2": "m", "resp_nfev": "", "resp_tau_s": "s",
         "elapsed_s": "s"}


def empty_outputs(kind: str) -> dict:
    """The kind's columns as they stand when it fails."""
    out = {c: "" if c in TEXT_OUTPUTS else math.nan for c in OUTPUTS[kind]}
    out[STATUS[kind]] = "failed"
    return out


#: Bins either side of the first spectral peak excluded when looking for the
#: second (a Hann window spreads one line over about 2 bins each side).
PEAK_GUARD_BINS = 3


class PointError(RuntimeError):
    """A kind could not produce its outputs at a point (the message says why)."""


# ------------------------------------------------------------------------ kinds

def stability(params: Params, frame: str = "averaged") -> dict:
    """Equilibrium of the rotating-frame system and its leading eigenvalue."""
    m = Model(params)
    eps = m.rotating_equilibrium(frame=frame)
    lam = m.eigenvalues(eps, frame=frame)
    lead = lam[0]
    whirl = abs(lead.imag)
    out = {"stab_margin": float(lead.real), "stab_whirl": float(whirl),
           "stab_whirl_ground": float(abs(2 * math.pi * params["Omega"] - whirl)),
           "stab_damping_ratio": float(-lead.real / abs(lead)) if abs(lead) > 0 else math.nan,
           "stab_radius": float(math.hypot(eps[0], eps[1])),
           "stab_status": "stable" if lead.real < 0 else "unstable"}
    out.update({f"stab_eps{i + 1}": float(e) for i, e in enumerate(eps)})
    return out


#: Constants of the one-parameter search for `critical` (AUTO names; see
#: auto_constants/c.washer, which this mirrors). Steps scale with the range:
#: DSMAX = range / CRIT_STEPS keeps two Hopf points of one range from falling
#: into one step; NMX allows for step reductions and a fold or two.
CRIT_STEPS = 40
#: Margins within this of zero count as neutral, not unstable, in the fallback
#: (1/s): without an imbalance (m_u = 0) at C_p = 0 the whirl pair is undamped
#: and its real part is round-off, |margin| ~ 1e-15; the smallest true margins
#: seen near there are ~1e-7.
NEUTRAL_MARGIN = 1e-9
#: Tolerance of the critical value, as a fraction of the range: the engine's HB
#: location (its EPSS, in arclength, which PAR(ICP(1)) enters with weight 1: AUTO's
#: location accepts a step's end whose secant correction is below it, so c.washer's
#: EPSS = 1e-5 would leave ~1e-5 of C_p) and the fallback root search.
CRIT_XTOL = 1e-9


def critical_constants(name: str, lo: float, hi: float):
    """The constants (washer.cont.constants.Constants, in memory) of the one-parameter
    search for the first HB: the averaged equilibrium (e='washer') continued in `name`
    from lo to hi (as auto_constants/c.washer, but located to CRIT_XTOL of the range);
    the other parameters come with the problem (run(..., params=...))."""
    from washer.cont.constants import Constants
    from washer.machine.layout import PAR_NAMES
    span = hi - lo
    return Constants({
        "e": "washer", "parnames": dict(PAR_NAMES), "NDIM": 12, "IPS": 1, "IRS": 0,
        "ILP": 1, "ICP": [name], "ISP": 2, "ISW": 1, "MXBF": 0, "NMX": 10 * CRIT_STEPS,
        "NPR": 0, "ITMX": 8, "ITNW": 7, "JAC": 1, "EPSL": 1e-07, "EPSU": 1e-07,
        "EPSS": CRIT_XTOL * span, "DS": span / (5 * CRIT_STEPS), "DSMIN": span * 1e-6,
        "DSMAX": span / CRIT_STEPS, "IADS": 1, "NPAR": 17, "PAR": {name: float(lo)},
        "UZSTOP": {name: float(hi)}}, source=f"<critical search in {name}>")


def critical(params: Params, parameter: str = "C_p", lo: float = 0.0, hi: float = 3.0,
             engine: str = "continuation") -> dict:
    """Critical value of `parameter`: its first Hopf point from lo to hi.

    engine: "continuation" (the averaged system's Hopf point, washer.run) or
    "floquet": the exact result, the Neimark-Sacker (TR) point of the periodic
    response at constant speed (docs/model.md section 4; washer.machine.forced, shooting with
    the kernel's variational flow), bracketed around the averaged value (averaging
    is accurate to ~1e-4 relative: FLOQUET_BRACKET leaves a wide margin).
    Adds crit_averaged (the averaged value) and crit_multiplier_angle (rad)."""
    if engine == "floquet":
        return _critical_floquet(params, parameter, lo, hi)
    if engine != "continuation":
        raise PointError(f"critical: unknown engine {engine!r}")
    from washer.machine.layout import PAR_INDEX
    from washer.run import run
    idx = PAR_INDEX[parameter]
    res = run(critical_constants(parameter, lo, hi), verbose=False, params=params,
              files=False)
    hbs = [s for s in res.specials if s.ty == "HB"]
    if hbs:
        period = float(hbs[0].par[10])
        return {"crit_status": "hopf", "crit_value": float(hbs[0].par[idx - 1]),
                "crit_whirl": 2 * math.pi / period if period > 0 else math.nan,
                "crit_n_hopf": float(len(hbs)), "crit_source": "HB"}
    first = float(res.rows[1].par[idx - 1]) if len(res.rows) > 1 else hi
    return _critical_fallback(params, parameter, lo, hi, res.status, first)


#: Half-width of the exact (Floquet) bracket around the averaged critical value:
#: this fraction of the value plus FLOQUET_ABS of the search range.
FLOQUET_BRACKET = 0.05
FLOQUET_ABS = 1e-3


def _critical_floquet(params: Params, parameter: str, lo: float, hi: float) -> dict:
    """The exact critical value: the averaged one (continuation), then the TR point of
    the forced response within a bracket around it (washer.problems.forced.locate_tr:
    the engine's shooting continuation, TR located by the one TR test)."""
    from washer.cont import floquet
    from washer.machine import forced
    from washer.machine.layout import PAR_INDEX
    from washer.problems import forced as shooting
    avg = critical(params, parameter, lo, hi, "continuation")
    if avg["crit_status"] != "hopf":        # no crossing in the range: the same answer
        return avg | {"crit_averaged": avg["crit_value"], "crit_multiplier_angle": math.nan}
    v = avg["crit_value"]
    half = FLOQUET_BRACKET * abs(v) + FLOQUET_ABS * (hi - lo)
    bracket = (max(v - half, lo), min(v + half, hi))
    try:
        start = forced.averaged_start(params.replace(**{parameter: bracket[0]}))
        r, sp = shooting.locate_tr(params, parameter, bracket, start)
    except Exception as exc:  # noqa: BLE001 - recorded per point
        raise PointError(f"critical (floquet): no TR point of the forced response in "
                         f"[{bracket[0]:.6g}, {bracket[1]:.6g}] around the averaged "
                         f"{v:.6g}: {exc}") from None
    mu = floquet.torus_pair(r.multipliers, trivial=False)
    return {"crit_status": "hopf", "crit_value": float(sp.par[PAR_INDEX[parameter] - 1]), "crit_whirl": avg["crit_whirl"],
            "crit_n_hopf": avg["crit_n_hopf"], "crit_source": "floquet",
            "crit_averaged": float(v), "crit_multiplier_angle": float(abs(np.angle(mu)))}


def _critical_fallback(params: Params, parameter: str, lo: float, hi: float,
                       status: str, first: float) -> dict:
    """No HB on the branch. From the stability at the two ends:

    - stable at both: the answer "stable" (crit_value = lo: with C_p from 0, stable
      without joint damping), the engine having found no crossing between; also when
      neutral at lo (within NEUTRAL_MARGIN: without an imbalance the whirl pair is
      undamped at C_p = 0) and stable at hi;
    - unstable at both: the answer "unstable" (more than `hi` needed);
    - unstable at lo, stable at hi: the crossing lies on the engine's first two steps
      from lo to `first` (its first written point), where it tests no sign change (AUTO's
      hidden first step and first written interval; seen at Omega = 9 Hz, m_u = 0.25 kg:
      crossing at C_p ~ 1.5e-4, first = 0.03): the engine again over [lo, first] alone,
      its steps 1/100 of that, so its HB location finds it (`critical`, recursively: a
      crossing inside that run's first steps too is found one level down);
    - anything else (or a failed continuation) raises, with the margins at the ends."""
    def eig(v):
        m = Model(params.replace(**{parameter: v}))
        return m.eigenvalues(m.rotating_equilibrium())

    try:
        lam_lo, lam_hi = eig(lo), eig(hi)
    except Exception as exc:  # noqa: BLE001 - only explains the failure
        raise PointError(f"critical: no Hopf point for {parameter} in [{lo:g}, {hi:g}]; "
                         f"equilibrium not found at the ends ({exc})") from None
    m_lo, m_hi = float(lam_lo.real.max()), float(lam_hi.real.max())

    def state(m):
        return "neutral" if abs(m) <= NEUTRAL_MARGIN else "stable" if m < 0 else "unstable"

    ends = f"margin {m_lo:.3g} 1/s at {lo:g}, {m_hi:.3g} at {hi:g}"
    if status == "ok" and state(m_lo) == "neutral" and state(m_hi) == "stable":
        # Neutral at lo (no imbalance: the whirl pair is undamped at C_p = 0) and stable
        # above it: the critical value is lo itself.
        return {"crit_status": "stable", "crit_value": float(lo), "crit_whirl": math.nan,
                "crit_n_hopf": 0.0, "crit_source": "ends"}
    if status == "ok" and state(m_lo) == state(m_hi) in ("stable", "unstable"):
        return {"crit_status": state(m_lo), "crit_value": float(lo) if m_lo < 0 else math.nan,
                "crit_whirl": math.nan, "crit_n_hopf": 0.0, "crit_source": "ends"}
    if state(m_lo) == "unstable" and state(m_hi) == "stable" and status == "ok":
        if lo < first < hi and first - lo > CRIT_XTOL * (hi - lo):
            got = critical(params, parameter, lo, first)
            if got["crit_status"] == "hopf":
                return got | {"crit_source": "first steps"}
    why = f"continuation ended with status {status!r}; " if status != "ok" else ""
    why += f"{state(m_lo)} at {lo:g}, {state(m_hi)} at {hi:g} ({ends})"
    raise PointError(f"critical: no Hopf point for {parameter} in [{lo:g}, {hi:g}]: {why}")


#: Relative step of the central difference of the critical eigenvalue in the parameter
#: (smooth; truncation ~h^2, round-off ~1e-13/h).
GROWTH_REL_STEP = 1e-5


def whirl_growth(params: Params, parameter: str, value: float) -> tuple[float, float, float]:
    """(a, r0, slope): the whirl born at the averaged Hopf point `parameter` = value grows as
    a sqrt(|parameter - value|) (m per sqrt of the parameter's unit) about the forced
    response's offset r0 = hypot(eps1, eps2) (m).

    From the Hopf normal form z' = (mu + i w) z + c1 |z|^2 z on the centre manifold
    x = x* + z q + conj(z q) (Kuznetsov's normalisation: |q| = 1, <p, q> = 1, l1 = Re c1 /
    w, `washer.cont.normal_form.first_lyapunov`): the cycle has |z|^2 = -mu / (l1 w),
    mu = dRe(lambda)/dp (p - value); the tub's offset eps1 + i eps2 = z (q1 + i q2) +
    conj(z) (conj(q1) + i conj(q2)) turns on a circle of radius |z| times the larger of
    the two (the other is the small opposite-turning part); slope = dRe(lambda)/dp (< 0:
    stable above the critical value, the whirl below it). a is nan where l1 >= 0 (a
    subcritical point: no small stable whirl)."""
    from washer.cont.normal_form import first_lyapunov
    from washer.problems.parameters import NPAR, set_par
    from washer.problems.washer import washer_problem
    q = params.replace(**{parameter: value})
    m = Model(q)
    eps = m.rotating_equilibrium()
    x = np.r_[eps, np.zeros(6)]
    A = m.jac_rot(x)[0]
    lam, V = np.linalg.eig(A)
    i = int(np.argmin(np.abs(lam.real) + 1e3 * (lam.imag <= 0)))
    w = float(lam[i].imag)
    par = np.zeros(NPAR)
    set_par(par, q)
    l1 = first_lyapunov(washer_problem("washer", q), x, par, w, A)
    h = GROWTH_REL_STEP * max(abs(value), 1e-3)

    def re_lam(v):
        mm = Model(params.replace(**{parameter: v}))
        lm = mm.eigenvalues(mm.rotating_equilibrium(guess=eps))
        return float(lm[np.argmin(np.abs(lm - lam[i]))].real)

    d = (re_lam(value + h) - re_lam(max(value - h, 0.0))) / (value + h - max(value - h, 0.0))
    v = V[:, i] / np.linalg.norm(V[:, i])
    circ = max(abs(v[0] + 1j * v[1]), abs(np.conj(v[0]) + 1j * np.conj(v[1])))
    r0 = float(np.hypot(eps[0], eps[1]))
    if not l1 < 0:
        return float("nan"), r0, float(d)
    return float(circ * np.sqrt(abs(d) / (abs(l1) * w))), r0, float(d)


def response(params: Params, system: str = "fixed", law: str = "spinup",
             frame: str = "averaged", t_end: float = 30.0, window: float = 10.0,
             samples_per_s: float = 200.0, rtol: float = 1e-8, atol: float = 1e-10,
             tau_s: float = math.nan) -> dict:
    """Time response from the paper's initial state, summarised (see module docstring).
    tau_s (s): the spin-up time constant (eq 66); NaN: the parameter set's."""
    if not math.isnan(tau_s):
        params = params.replace(tau_s=tau_s)
    spin = system == "fixed" and law == "spinup"
    m = Model(params)
    r = m.simulate(t_end, system=system, law=law, frame=frame, samples_per_s=samples_per_s,
                   rtol=rtol, atol=atol, progress=False)
    if r.status != "ok":
        raise PointError(f"response: integration stopped at t = {r.t[-1] if len(r.t) else 0:g} "
                         f"s: {r.status}")
    return summarise_response(r.t, r.y, m.static_equilibrium()[2], window) | {
        "resp_nfev": float(r.stats["nfev"]), "resp_status": "ok",
        "resp_tau_s": float(params["tau_s"]) if spin else math.nan}


def summarise_response(t: np.ndarray, y: np.ndarray, z_static: float, window: float) -> dict:
    """Summaries of one history t (n,), y (n, 12) = (x, y, z, alpha, beta, gamma, rates)."""
    x, yy, z, a, b = y[:, 0], y[:, 1], y[:, 2], y[:, 3], y[:, 4]
    w = t >= t[-1] - window - 1e-12
    rad = np.hypot(x[w], yy[w])
    tilt = np.arccos(np.clip(np.cos(a) * np.cos(b), -1.0, 1.0))
    out = {"resp_whirl_radius": float(rad.mean()), "resp_whirl_radius_min": float(rad.min()),
           "resp_whirl_radius_max": float(rad.max()),
           "resp_lift_max": float(np.max(z - z_static)), "resp_tilt_max": float(tilt.max())}
    (f1, a1), (f2, a2) = dominant_frequencies(t[w], x[w] + 1j * yy[w])
    out.update(resp_freq1=f1, resp_amp1=a1, resp_freq2=f2, resp_amp2=a2)
    return out


def dominant_frequencies(t: np.ndarray, s: np.ndarray):
    """The two largest spectral lines of a complex signal s(t) on a uniform grid:
    ((f1 Hz, amplitude1), (f2, amplitude2)); frequencies signed, amplitudes of
    A e^{i 2 pi f t} in the units of s. The second is looked for outside
    PEAK_GUARD_BINS of the first."""
    n = len(s)
    if n < 4:
        return (math.nan, math.nan), (math.nan, math.nan)
    dt = (t[-1] - t[0]) / (n - 1)
    win = np.hanning(n)
    S = np.fft.fft((s - s.mean()) * win) / win.sum()
    f = np.fft.fftfreq(n, dt)
    A = np.abs(S)
    k1 = int(np.argmax(A))
    mask = np.ones(n, bool)
    idx = (np.arange(k1 - PEAK_GUARD_BINS, k1 + PEAK_GUARD_BINS + 1)) % n
    mask[idx] = False
    k2 = int(np.flatnonzero(mask)[np.argmax(A[mask])])
    return (float(f[k1]), float(A[k1])), (float(f[k2]), float(A[k2]))


def critical_with_clearance(params: Params, parameter: str, lo: float, hi: float,
                            engine: str, clearance: float = math.nan) -> dict:
    """`critical`, plus the clearance-based critical value when a clearance (m) is given."""
    out = critical(params, parameter, lo, hi, engine)
    out.setdefault("crit_whirl_growth", math.nan)
    out.setdefault("crit_clearance_value", math.nan)
    if math.isnan(clearance):
        return out
    if out["crit_status"] == "stable":
        out["crit_clearance_value"] = out["crit_value"]
    elif out["crit_status"] == "hopf":
        at = out.get("crit_averaged", out["crit_value"])
        a, r0, slope = whirl_growth(params, parameter, at)
        out["crit_whirl_growth"] = a
        if clearance > r0 and np.isfinite(a):
            # The whirl lives on the unstable side: below the critical value when the
            # margin falls as the parameter grows (C_p: less damping), else above.
            side = -1.0 if slope < 0 else 1.0
            out["crit_clearance_value"] = out["crit_value"] + side * ((clearance - r0) / a) ** 2
    return out


KINDS = {"stability": lambda p, o: stability(p, **o),
         "critical": lambda p, o: critical_with_clearance(
             p, o["parameter"], o["from"], o["to"], o["engine"], o.get("clearance", math.nan)),
         "response": lambda p, o: response(p, **o)}


# ------------------------------------------------------------------------ batches

def compute_point(point: dict, base: dict) -> dict:
    """One row: the point's id, study, index, inputs, status, error, timing and outputs."""
    t0 = time.perf_counter()
    row = {"id": point["id"], "study": point["study"], "index": point["index"]}
    row.update(point["inputs"])
    errors = []
    for kind in point["kinds"]:
        row.update(empty_outputs(kind))
    try:
        params = Params(dict(base["values"]), base["tied"], base["source"]).replace(**point["set"])
    except Exception as exc:  # noqa: BLE001 - any bad point is recorded, never raised
        errors.append(f"parameters: {exc}")
    else:
        for kind in point["kinds"]:
            try:
                row.update(KINDS[kind](params, point["options"][kind]))
            except Exception as exc:  # noqa: BLE001
                msg = str(exc)
                errors.append(msg if msg.startswith(kind) else f"{kind}: {type(exc).__name__}: {msg}")
    # A kind that answered (even "stable throughout") is ok; only a fault fails the row.
    row["status"] = "failed" if errors else "ok"
    row["error"] = "; ".join(errors)
    row["elapsed_s"] = time.perf_counter() - t0
    return row


def units_of(columns, parameter_units: dict | None = None) -> dict:
    """{column: unit} for the columns of a results table: outputs from UNITS, swept and
    fixed inputs from the parameter layout (SI, Omega in Hz), crit_value and
    crit_averaged in the units of the critical parameter (parameter_units: {column:
    unit} overrides, e.g. {"crit_value": "N m s/rad"})."""
    from washer.machine.layout import UNITS as PARAM_UNITS
    out = {}
    for c in columns:
        if parameter_units and c in parameter_units:
            out[c] = parameter_units[c]
        elif c in UNITS and UNITS[c] is not None:
            out[c] = UNITS[c]
        elif c in PARAM_UNITS:
            out[c] = PARAM_UNITS[c]
    return out


def compute_batch(points: list[dict], base: dict) -> list[dict]:
    """Rows of a batch of points (the task a worker runs)."""
    return [compute_point(p, base) for p in points]
