"""Sweep specifications: TOML files, validated, with errors naming file and line.

A spec names the base parameter set, one or more studies (each: the swept
parameters and how to sample them, and what to compute per point) and, per
kind of computation, its options::

    params = "reference"        # or a parameter TOML, relative to this file
    batch_size = 0              # points per task; 0 = automatic

    [fixed]                     # applied to every point (kernel names, SI, Omega in Hz)
    C_p = 0.101

    [[study]]
    name = "map"
    sample = "grid"             # "grid" | "random" | "lhs" (Latin hypercube)
    kinds = ["stability", "critical", "response"]
    [study.vary]
    Omega = [6.0, 9.0, 12.0]             # grid: explicit values
    m_u = {from = 0.5, to = 2.0, n = 4}  # grid: n values, ends included; random/lhs: the range
    [study.critical]
    parameter = "C_p"
    from = 0.0
    to = 3.0
    clearance = 0.03            # m (optional): also the damping that keeps the whirl within it
    [study.response]
    system = "fixed"
    law = "spinup"
    tau_s = 4.0                 # spin-up time constant, s (default: the parameter set's)
    t_end = 30.0
    window = 10.0

`load_spec(path)` returns a `Spec`; every problem raises `SpecError` with
"file:line: what was expected".
"""
from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from washer.machine.params import Params, ParameterError, load_params
from washer.text_files import decode_text

KINDS = ("stability", "critical", "response")
SAMPLES = ("grid", "random", "lhs")

#: Options per kind: name -> (default, allowed values or type). None default = required.
KIND_OPTIONS: dict[str, dict[str, tuple]] = {
    "stability": {"frame": ("averaged", ("averaged", "frozen"))},
    "critical": {"parameter": ("C_p", str), "from": (0.0, float), "to": (None, float),
                 "engine": ("continuation", ("continuation", "floquet")),
                 # clearance to the cabinet (m): adds the damping that keeps the whirl
                 # within it (crit_clearance_value); NaN: not asked
                 "clearance": (math.nan, float)},
    "response": {"system": ("fixed", ("fixed", "rotating")),
                 "law": ("spinup", ("spinup", "constant")),
                 "frame": ("averaged", ("averaged", "frozen")),
                 "t_end": (30.0, float), "window": (10.0, float),
                 "samples_per_s": (200.0, float), "rtol": (1e-8, float),
                 "atol": (1e-10, float),
                 # spin-up time constant of eq 66 (s); NaN: the parameter set's
                 # (the paper's 0.45 s is a violent start: a motor takes seconds)
                 "tau_s": (math.nan, float)},
}
#: Default upper end of the critical search per parameter (kernel units): the
#: Hopf curves of Figs 4-7 stay below C_p = 2 over Table 1's ranges.
CRITICAL_DEFAULT_TO = {"C_p": 3.0}


class SpecError(ValueError):
    """A malformed sweep spec: the message names the file and line."""


@dataclass(frozen=True)
class Axis:
    """One swept parameter: explicit grid values, or a range for random/LHS samples."""
    name: str
    values: tuple[float, ...] | None = None     # grid
    lo: float | None = None                     # random / lhs
    hi: float | None = None
    log: bool = False


@dataclass(frozen=True)
class Study:
    """A set of points and what to compute at each."""
    name: str
    sample: str
    axes: tuple[Axis, ...]
    kinds: tuple[str, ...]
    options: dict = field(default_factory=dict)   # kind -> {option: value}
    fixed: dict = field(default_factory=dict)     # parameter -> value (after the spec's [fixed])
    n: int = 0                                    # random / lhs sample size
    seed: int = 0

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(a.name for a in self.axes)


@dataclass(frozen=True)
class Spec:
    """A validated sweep spec."""
    source: str
    text: str
    base: Params
    studies: tuple[Study, ...]
    batch_size: int = 0
    params_path: str = "reference"

    def study(self, name: str) -> Study:
        return next(s for s in self.studies if s.name == name)


class _Where:
    """Line numbers for TOML keys (tomllib gives none): a light scan of the text."""

    HEADER = re.compile(r"^\s*(\[\[?)\s*([^\]]+?)\s*\]")

    def __init__(self, text: str, source: str):
        self.lines, self.source = text.splitlines(), source

    def __call__(self, table: str = "", key: str | None = None, occurrence: int = 0) -> str:
        """'file:line' of `key` in `[table]` (of the `occurrence`-th `[[study]]` for
        study tables), else of the table's header, else just the file."""
        study, current, header = -1, "", None
        for i, line in enumerate(self.lines, 1):
            m = self.HEADER.match(line)
            if m:
                current = m.group(2).strip()
                if m.group(1) == "[[" and current == "study":
                    study += 1
                if header is None and self._here(current, study, table, occurrence):
                    header = i
                continue
            if key and self._here(current, study, table, occurrence) and \
                    re.match(rf"^\s*{re.escape(key)}\s*=", line):
                return f"{self.source}:{i}"
        return f"{self.source}:{header}" if header else self.source

    @staticmethod
    def _here(current: str, study: int, table: str, occurrence: int) -> bool:
        return current == table and (not table.startswith("study") or study == occurrence)


def load_spec(path, overrides: dict | None = None) -> Spec:
    """Read and validate a spec file. `overrides` replace top-level keys (e.g. batch_size)."""
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise SpecError(f"{path}: cannot read the spec: {exc.strerror}") from None
    text = decode_text(data, str(path), "a sweep spec (TOML, UTF-8)", SpecError)
    return parse_spec(text, str(path), base_dir=path.parent, overrides=overrides)


def parse_spec(text: str, source: str = "<spec>", base_dir: Path | None = None,
               overrides: dict | None = None) -> Spec:
    """Validate spec text (see the module docstring for the layout)."""
    where = _Where(text, source)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SpecError(f"{source}: not valid TOML: {exc}") from None
    data.update(overrides or {})
    known = {"params", "batch_size", "fixed", "study", "title"}
    for k in data:
        if k not in known:
            raise SpecError(f"{where('', k)}: unknown key {k!r}; expected one of "
                            f"{', '.join(sorted(known))}")
    params_path = data.get("params", "reference")
    if not isinstance(params_path, str):
        raise SpecError(f"{where('', 'params')}: expected a file name or \"reference\"")
    try:
        if params_path == "reference":
            base = load_params()
        else:
            p = Path(params_path)
            base = load_params(p if p.is_absolute() else (base_dir or Path(".")) / p)
    except (ParameterError, OSError) as exc:
        raise SpecError(f"{where('', 'params')}: base parameters: {exc}") from None
    batch = data.get("batch_size", 0)
    if isinstance(batch, bool) or not isinstance(batch, int) or batch < 0:
        raise SpecError(f"{where('', 'batch_size')}: expected an integer >= 0, got {batch!r}")
    fixed = _fixed(data.get("fixed", {}), base, lambda k=None: where("fixed", k))
    studies = data.get("study")
    if not isinstance(studies, list) or not studies:
        raise SpecError(f"{source}: no [[study]]: a spec needs at least one")
    out = []
    for i, st in enumerate(studies):
        out.append(_study(st, i, base, fixed, where))
    names = [s.name for s in out]
    for n in names:
        if names.count(n) > 1:
            raise SpecError(f"{source}: study name {n!r} is used twice")
    return Spec(source, text, base, tuple(out), batch, params_path)


def _fixed(table, base: Params, where) -> dict:
    if not isinstance(table, dict):
        raise SpecError(f"{where()}: [fixed] must be a table of parameter = value")
    out = {}
    for k, v in table.items():
        _check_param(k, base, where(k))
        out[k] = _num(v, where(k), k)
    return out


def _check_param(name: str, base: Params, at: str) -> None:
    if name not in base.values:
        raise SpecError(f"{at}: unknown parameter {name!r}; use kernel names "
                        "(C_p, Omega, m_u, R_u, h_u, C_a, K_s, l0, J_bz, m_b, ... see washer/machine/layout.py)")


def _num(v, at: str, what: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise SpecError(f"{at}: {what}: expected a finite number, got {v!r}")
    return float(v)


def _study(st, i: int, base: Params, spec_fixed: dict, where) -> Study:
    def at(key=None, table="study"):
        return where(table, key, i)

    if not isinstance(st, dict):
        raise SpecError(f"{at()}: [[study]] must be a table")
    known = {"name", "sample", "n", "seed", "kinds", "vary", "fixed"} | set(KINDS)
    for k in st:
        if k not in known:
            raise SpecError(f"{at(k)}: unknown key {k!r} in [[study]]; expected one of "
                            f"{', '.join(sorted(known))}")
    name = st.get("name", f"study{i + 1}")
    if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
        raise SpecError(f"{at('name')}: name: expected letters, digits, _ . -, got {name!r}")
    sample = st.get("sample", "grid")
    if sample not in SAMPLES:
        raise SpecError(f"{at('sample')}: sample: expected one of {SAMPLES}, got {sample!r}")
    kinds = st.get("kinds")
    if not isinstance(kinds, list) or not kinds or any(k not in KINDS for k in kinds):
        raise SpecError(f"{at('kinds')}: kinds: expected a non-empty list from {KINDS}, got {kinds!r}")
    if len(set(kinds)) != len(kinds):
        raise SpecError(f"{at('kinds')}: kinds: {kinds!r} names a kind twice")
    n, seed = st.get("n", 0), st.get("seed", 0)
    for key, v in (("n", n), ("seed", seed)):
        if isinstance(v, bool) or not isinstance(v, int) or v < 0:
            raise SpecError(f"{at(key)}: {key}: expected an integer >= 0, got {v!r}")
    if sample != "grid" and n < 1:
        raise SpecError(f"{at('sample')}: sample = {sample!r} needs n = number of points (>= 1)")
    vary = st.get("vary")
    if not isinstance(vary, dict) or not vary:
        raise SpecError(f"{at()}: study {name!r}: [study.vary] must name at least one parameter")
    axes = tuple(_axis(k, v, sample, base, where("study.vary", k, i)) for k, v in vary.items())
    fixed = dict(spec_fixed)
    fixed.update(_fixed(st.get("fixed", {}), base, lambda k=None: where("study.fixed", k, i)))
    for a in axes:
        fixed.pop(a.name, None)
    options = {}
    for kind in KINDS:
        table = st.get(kind, {})
        if kind not in kinds:
            if table:
                raise SpecError(f"{at(table=f'study.{kind}')}: options for {kind!r}, which is "
                                "not in kinds")
            continue
        options[kind] = _options(kind, table, lambda k=None, t=kind: where(f"study.{t}", k, i))
    if "critical" in options:
        _check_critical(options["critical"], axes, lambda k=None: where("study.critical", k, i))
    if "response" in options:
        r = options["response"]
        if not 0 < r["window"] <= r["t_end"]:
            raise SpecError(f"{where('study.response', 'window', i)}: window = {r['window']}: "
                            f"expected 0 < window <= t_end = {r['t_end']}")
        if r["samples_per_s"] < 4 / r["window"] or r["rtol"] <= 0 or r["atol"] <= 0:
            raise SpecError(f"{where('study.response', None, i)}: samples_per_s, rtol, atol: "
                            "expected positive values (at least 4 samples in the window)")
    return Study(name, sample, axes, tuple(kinds), options, fixed, n, seed)


def _axis(name: str, v, sample: str, base: Params, at: str) -> Axis:
    _check_param(name, base, at)
    if isinstance(v, list):
        if sample != "grid":
            raise SpecError(f"{at}: {name}: explicit values need sample = \"grid\"; for "
                            f"{sample!r} give {{from = .., to = ..}}")
        vals = tuple(_num(x, at, name) for x in v)
        if not vals:
            raise SpecError(f"{at}: {name}: expected at least one value")
        if len(set(vals)) != len(vals):
            raise SpecError(f"{at}: {name}: repeated values {list(vals)}")
        return Axis(name, values=vals)
    if not isinstance(v, dict):
        raise SpecError(f"{at}: {name}: expected a list of values or {{from, to, n}}")
    for k in v:
        if k not in ("from", "to", "n", "log"):
            raise SpecError(f"{at}: {name}: unknown key {k!r}; expected from, to, n, log")
    if "from" not in v or "to" not in v:
        raise SpecError(f"{at}: {name}: expected both from and to")
    lo, hi = _num(v["from"], at, f"{name}.from"), _num(v["to"], at, f"{name}.to")
    log = v.get("log", False)
    if not isinstance(log, bool):
        raise SpecError(f"{at}: {name}.log: expected true or false")
    if not lo < hi:
        raise SpecError(f"{at}: {name}: expected from < to, got {lo} and {hi}")
    if log and lo <= 0:
        raise SpecError(f"{at}: {name}: log spacing needs from > 0")
    if sample == "grid":
        n = v.get("n")
        if isinstance(n, bool) or not isinstance(n, int) or n < 2:
            raise SpecError(f"{at}: {name}.n: a grid range needs n >= 2 values, got {n!r}")
        import numpy as np
        vals = np.geomspace(lo, hi, n) if log else np.linspace(lo, hi, n)
        return Axis(name, values=tuple(float(x) for x in vals), lo=lo, hi=hi, log=log)
    if "n" in v:
        raise SpecError(f"{at}: {name}.n: for sample = {sample!r} the study's n sets the size")
    return Axis(name, lo=lo, hi=hi, log=log)


def _options(kind: str, table, at) -> dict:
    if not isinstance(table, dict):
        raise SpecError(f"{at()}: [{kind}] must be a table")
    allowed = KIND_OPTIONS[kind]
    for k in table:
        if k not in allowed:
            raise SpecError(f"{at(k)}: unknown {kind} option {k!r}; expected one of "
                            f"{', '.join(allowed)}")
    out = {}
    for k, (default, kind_of) in allowed.items():
        v = table.get(k, default)
        if k not in table and isinstance(default, float) and math.isnan(default):
            out[k] = default            # "not given": the kind takes it from the parameters
            continue
        if v is None:
            if kind == "critical" and k == "to":
                out[k] = None           # filled from CRITICAL_DEFAULT_TO
                continue
            raise SpecError(f"{at()}: {kind}: missing option {k!r}")
        if kind_of is float:
            v = _num(v, at(k), k)
        elif kind_of is str:
            if not isinstance(v, str):
                raise SpecError(f"{at(k)}: {k}: expected a string, got {v!r}")
        elif v not in kind_of:
            raise SpecError(f"{at(k)}: {k}: expected one of {kind_of}, got {v!r}")
        out[k] = v
    return out


def _check_critical(opt: dict, axes, at) -> None:
    from washer.machine.layout import PAR_NAMES
    par = opt["parameter"]
    if par not in PAR_NAMES.values():
        raise SpecError(f"{at('parameter')}: critical parameter {par!r}: the continuation "
                        f"problem e='washer' varies only {', '.join(PAR_NAMES.values())}")
    if par in [a.name for a in axes]:
        raise SpecError(f"{at('parameter')}: critical parameter {par!r} is also swept; "
                        "sweep other parameters")
    if opt["to"] is None:
        if par not in CRITICAL_DEFAULT_TO:
            raise SpecError(f"{at()}: critical: give to = upper end of the search for {par!r}")
        opt["to"] = CRITICAL_DEFAULT_TO[par]
    if not opt["from"] < opt["to"]:
        raise SpecError(f"{at('to')}: critical: expected from < to, got {opt['from']}, {opt['to']}")
