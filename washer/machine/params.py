"""Parameter sets: read and validate TOML files, build the kernel's vector.

The file layout and units are those of `washer/data/reference.toml` (a copy of
the project's reference set, docs/model.md section 5): SI units, Omega in Hz.
Errors name the file, the field and what was expected.

    >>> p = load_params()                 # the shipped reference set
    >>> p["C_p"], p.vector().shape
    (0.101, (48,))
    >>> p2 = p.replace(C_p=0.15)          # C_ox and C_oz follow C_p unless set
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import numpy as np

from washer.machine import layout
from washer.text_files import decode_text


class ParameterError(ValueError):
    """A parameter file or value is invalid; the message names the field."""


# Schema: section -> {key: kind}. Kinds: "pos" > 0, "nonneg" >= 0, "real", "int",
# "vec3"/"vec3nonneg" 3-vectors, "joints" list of 3-vectors. Optional keys in OPTIONAL.
SCHEMA: dict[str, dict[str, str]] = {
    "operation": {"Omega": "nonneg", "tau_s": "pos", "tau0": "real"},
    "imbalance": {"m_u": "nonneg", "R_u": "nonneg", "h_u": "real"},
    "suspension": {"K_s": "nonneg", "C_a": "nonneg", "C_p": "nonneg", "C_ox": "nonneg",
                   "C_oz": "nonneg", "l0": "pos", "n_rods": "int", "upper_radius": "pos",
                   "upper_z": "real", "lower_radius": "pos", "first_rod_deg": "real",
                   "upper_joints": "joints", "lower_joints": "joints"},
    "tub": {"m": "pos", "r": "vec3", "J": "vec3nonneg"},
    "basket": {"m": "nonneg", "h": "real", "J_t": "nonneg", "J_z": "nonneg"},
    "environment": {"g": "nonneg"},
}
OPTIONAL = {("operation", "tau0"), ("suspension", "C_ox"), ("suspension", "C_oz"),
            ("suspension", "upper_joints"), ("suspension", "lower_joints"),
            ("suspension", "upper_radius"), ("suspension", "upper_z"),
            ("suspension", "lower_radius"), ("suspension", "first_rod_deg")}

#: Flat names of the scalar fields: (section, key) -> kernel name.
FLAT = {("operation", "Omega"): "Omega", ("operation", "tau_s"): "tau_s",
        ("operation", "tau0"): "tau0", ("imbalance", "m_u"): "m_u",
        ("imbalance", "R_u"): "R_u", ("imbalance", "h_u"): "h_u",
        ("suspension", "K_s"): "K_s", ("suspension", "C_a"): "C_a",
        ("suspension", "C_p"): "C_p", ("suspension", "C_ox"): "C_ox",
        ("suspension", "C_oz"): "C_oz", ("suspension", "l0"): "l0",
        ("tub", "m"): "m_t", ("basket", "m"): "m_b", ("basket", "h"): "h_b",
        ("basket", "J_t"): "J_bt", ("basket", "J_z"): "J_bz", ("environment", "g"): "g"}
NONNEG = {"Omega", "m_u", "R_u", "K_s", "C_a", "C_p", "C_ox", "C_oz", "m_b", "J_bt",
          "J_bz", "J_tx", "J_ty", "J_tz", "g"}
POSITIVE = {"tau_s", "l0", "m_t"}


class ParameterWarning(UserWarning):
    """A value far outside what a domestic washing machine has (a unit slip?)."""


#: Plausible ranges of a vertical-axis washer, (low, high, what a value beyond them
#: probably is): a value outside is accepted (studies may go there on purpose) with a
#: ParameterWarning naming the field and the likely slip (rpm for Hz, mm for m, g for kg).
PLAUSIBLE = {
    ("operation", "Omega"): (0.0, 30.0, "Omega is in Hz: 600 rpm is 10 Hz"),
    ("operation", "tau_s"): (0.01, 600.0, "tau_s is in s"),
    ("imbalance", "m_u"): (0.0, 10.0, "m_u is in kg: 1000 g is 1 kg"),
    ("imbalance", "R_u"): (0.0, 0.5, "R_u is in m: 150 mm is 0.15 m"),
    ("imbalance", "h_u"): (-1.0, 1.0, "h_u is in m"),
    ("suspension", "K_s"): (0.0, 1e5, "K_s is in N/m"),
    ("suspension", "C_a"): (0.0, 1e4, "C_a is in N s/m"),
    ("suspension", "C_p"): (0.0, 50.0, "C_p is in N m s/rad"),
    ("suspension", "l0"): (0.05, 2.0, "l0 is in m: 460 mm is 0.46 m"),
    ("suspension", "upper_radius"): (0.02, 1.0, "upper_radius is in m"),
    ("suspension", "upper_z"): (0.1, 3.0, "upper_z is in m"),
    ("suspension", "lower_radius"): (0.02, 1.0, "lower_radius is in m"),
    ("tub", "m"): (1.0, 200.0, "the tub's m is in kg: 12000 g is 12 kg"),
    ("basket", "m"): (0.0, 100.0, "the basket's m is in kg"),
    ("basket", "h"): (-1.0, 1.5, "h is in m"),
    ("basket", "J_t"): (0.0, 20.0, "J_t is in kg m^2"),
    ("basket", "J_z"): (0.0, 20.0, "J_z is in kg m^2"),
    ("environment", "g"): (9.7, 9.9, "g is in m/s^2 (9.81 on Earth)"),
}
#: Rods shorter or longer than this (m, at the reference pose) are implausible.
ROD_LENGTH = (0.1, 2.0)


def _plausibility(raw: dict, vals: dict, source: str) -> None:
    """ParameterWarning for each value outside PLAUSIBLE and each implausible rod."""
    import warnings
    for key, (lo, hi, hint) in PLAUSIBLE.items():
        v = raw.get(key)
        if v is not None and not lo <= v <= hi:
            warnings.warn(f"{_where(source, *key)} = {v:g}: outside the plausible range "
                          f"{lo:g} to {hi:g} of a washing machine ({hint})",
                          ParameterWarning, stacklevel=4)
    odd = []
    for k in range(layout.N_RODS):
        P = np.array([vals[layout.rod_param(f, k)] for f in ("Px", "Py", "Pz")])
        O = np.array([vals[layout.rod_param(f, k)] for f in ("Ox", "Oy", "Oz")])
        length = float(np.linalg.norm(P - O))
        if not ROD_LENGTH[0] <= length <= ROD_LENGTH[1]:
            odd.append(f"rod {k} is {length:.3g} m long")
    if odd:
        warnings.warn(f"{_where(source, 'suspension')}: {', '.join(odd)} between its joints "
                      f"(plausible {ROD_LENGTH[0]:g} to {ROD_LENGTH[1]:g} m; joints are in m)",
                      ParameterWarning, stacklevel=4)


def default_params_path() -> Path:
    """The reference parameter set shipped with the package."""
    return Path(str(resources.files("washer.data") / "reference.toml"))


@dataclass(frozen=True)
class Params:
    """A validated parameter set.

    values: kernel-named scalars and rod joints (see `washer.machine.layout`).
    tied:   when True, C_ox and C_oz equal C_p (the paper's C_ox = C_oy = C_oz = C_p)
            and `replace(C_p=...)` moves all three.
    """
    values: dict = field(repr=False)
    tied: bool = True
    source: str = "<dict>"

    def __getitem__(self, name: str) -> float:
        if name not in self.values:
            raise KeyError(f"unknown parameter {name!r}; known: {', '.join(layout.PARAM_NAMES)}")
        return self.values[name]

    def replace(self, **changes: float) -> "Params":
        """A copy with some parameters changed (validated). Setting C_ox or
        C_oz unties them from C_p."""
        vals = dict(self.values)
        tied = self.tied and not (layout.TIED_TO.keys() & changes.keys())
        for k, v in changes.items():
            if k not in vals:
                raise ParameterError(f"unknown parameter {k!r}")
            vals[k] = float(v)
        if tied:
            _tie(vals)
        _check_values(vals, self.source)
        return Params(vals, tied, self.source)

    def vector(self) -> np.ndarray:
        """Kernel parameter vector, shape (layout.N_PARAMS,), order of washer.machine.layout."""
        return np.array([self.values[n] for n in layout.PARAM_NAMES], dtype=float)

    def upper_joints(self) -> np.ndarray:
        """Joints P of the rods, ground frame, shape (n_rods, 3), m."""
        return np.array([[self.values[layout.rod_param(f, k)] for f in ("Px", "Py", "Pz")]
                         for k in range(layout.N_RODS)])

    def lower_joints(self) -> np.ndarray:
        """Joints O of the rods, tub frame, shape (n_rods, 3), m."""
        return np.array([[self.values[layout.rod_param(f, k)] for f in ("Ox", "Oy", "Oz")]
                         for k in range(layout.N_RODS)])


def _where(source: str, section: str, key: str | None = None) -> str:
    return f"{source}: [{section}]" + (f" {key}" if key else "")


def _number(x, where: str) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        raise ParameterError(f"{where}: expected a number, got {x!r}")
    if not math.isfinite(x):
        raise ParameterError(f"{where}: expected a finite number, got {x!r}")
    return float(x)


def _vec3(x, where: str) -> list[float]:
    if not isinstance(x, list) or len(x) != 3:
        raise ParameterError(f"{where}: expected a list of 3 numbers, got {x!r}")
    return [_number(v, where) for v in x]


def _check_values(vals: dict, source: str) -> None:
    """Sign checks on the flat values (shared by files and `replace`)."""
    for name, v in vals.items():
        if not math.isfinite(v):
            raise ParameterError(f"{source}: {name} = {v!r}: expected a finite number")
        if name in NONNEG and v < 0:
            raise ParameterError(f"{source}: {name} = {v}: expected a value >= 0")
        if name in POSITIVE and v <= 0:
            raise ParameterError(f"{source}: {name} = {v}: expected a value > 0")
    for k in range(layout.N_RODS):
        P = np.array([vals[layout.rod_param(f, k)] for f in ("Px", "Py", "Pz")])
        O = np.array([vals[layout.rod_param(f, k)] for f in ("Ox", "Oy", "Oz")])
        # At the reference pose (q = 0) every rod must hang from above its tub
        # joint, or it cannot carry the tub (and its length must exceed zero).
        if P[2] - O[2] <= 0:
            raise ParameterError(
                f"{source}: rod {k} cannot reach: its upper joint P (z = {P[2]}) must lie "
                f"above its lower joint O (z = {O[2]}) at the reference pose")


def params_from_dict(data: dict, source: str = "<dict>") -> Params:
    """Validate a nested dict with the layout of reference.toml."""
    for section in data:
        if section not in SCHEMA:
            raise ParameterError(f"{source}: unknown section [{section}]; expected one of "
                                 f"{', '.join('[' + s + ']' for s in SCHEMA)}")
    vals: dict[str, float] = {}
    raw: dict[tuple[str, str], object] = {}
    for section, keys in SCHEMA.items():
        got = data.get(section)
        if got is None:
            raise ParameterError(f"{source}: missing section [{section}]")
        if not isinstance(got, dict):
            raise ParameterError(f"{_where(source, section)}: expected a table")
        for key in got:
            if key not in keys:
                raise ParameterError(f"{_where(source, section, key)}: unknown key; expected "
                                     f"one of {', '.join(keys)}")
        for key, kind in keys.items():
            if key not in got:
                if (section, key) not in OPTIONAL:
                    raise ParameterError(f"{_where(source, section, key)}: missing key")
                continue
            where, x = _where(source, section, key), got[key]
            if kind == "int":
                if isinstance(x, bool) or not isinstance(x, int):
                    raise ParameterError(f"{where}: expected an integer, got {x!r}")
                raw[(section, key)] = x
            elif kind in ("vec3", "vec3nonneg"):
                v = _vec3(x, where)
                if kind == "vec3nonneg" and min(v) < 0:
                    raise ParameterError(f"{where}: expected values >= 0, got {v}")
                raw[(section, key)] = v
            elif kind == "joints":
                if not isinstance(x, list):
                    raise ParameterError(f"{where}: expected a list of [x, y, z] joints")
                raw[(section, key)] = [_vec3(j, where) for j in x]
            else:
                v = _number(x, where)
                if kind == "pos" and v <= 0:
                    raise ParameterError(f"{where} = {v}: expected a value > 0")
                if kind == "nonneg" and v < 0:
                    raise ParameterError(f"{where} = {v}: expected a value >= 0")
                raw[(section, key)] = v
                if (section, key) in FLAT:
                    vals[FLAT[(section, key)]] = v
    vals.setdefault("tau0", 0.0)
    tied = not (layout.TIED_TO.keys() & vals.keys())
    if tied:
        _tie(vals)
    elif not layout.TIED_TO.keys() <= vals.keys():
        raise ParameterError(f"{_where(source, 'suspension')}: give both C_ox and C_oz, or "
                             "neither (then both equal C_p)")
    vals["r_tx"], vals["r_ty"], vals["r_tz"] = raw[("tub", "r")]
    vals["J_tx"], vals["J_ty"], vals["J_tz"] = raw[("tub", "J")]
    _rods(raw, vals, source)
    _check_values(vals, source)
    _plausibility(raw, vals, source)
    return Params(vals, tied, source)


def _rods(raw: dict, vals: dict, source: str) -> None:
    """Rod joints from explicit lists or the radius/height/angle form."""
    n = raw[("suspension", "n_rods")]
    where = _where(source, "suspension", "n_rods")
    if n != layout.N_RODS:
        raise ParameterError(
            f"{where} = {n}: the compiled kernel was generated for {layout.N_RODS} rods "
            "(change N_RODS in washer/machine/layout.py, run `python -m washer.codegen` and reinstall)")
    joints = {}
    for end, z_key in (("upper", "upper_z"), ("lower", None)):
        explicit = raw.get(("suspension", f"{end}_joints"))
        if explicit is not None:
            if len(explicit) != n:
                raise ParameterError(f"{_where(source, 'suspension', end + '_joints')}: "
                                     f"expected {n} joints, got {len(explicit)}")
            joints[end] = explicit
            continue
        need = [f"{end}_radius", "first_rod_deg"] + ([z_key] if z_key else [])
        for key in need:
            if ("suspension", key) not in raw:
                raise ParameterError(f"{_where(source, 'suspension', key)}: missing key "
                                     f"(or give {end}_joints)")
        r = raw[("suspension", f"{end}_radius")]
        z = raw[("suspension", z_key)] if z_key else 0.0
        a0 = math.radians(raw[("suspension", "first_rod_deg")])
        joints[end] = [[r * math.cos(a0 + 2 * math.pi * k / n),
                        r * math.sin(a0 + 2 * math.pi * k / n), z] for k in range(n)]
    for k in range(n):
        for i, f in enumerate(("Px", "Py", "Pz")):
            vals[layout.rod_param(f, k)] = joints["upper"][k][i]
        for i, f in enumerate(("Ox", "Oy", "Oz")):
            vals[layout.rod_param(f, k)] = joints["lower"][k][i]


def _tie(vals: dict) -> None:
    """Apply the tie rule (layout.TIED_TO: C_ox = C_oz = C_p) in place."""
    for name, leader in layout.TIED_TO.items():
        vals[name] = vals[leader]


def load_params(path: str | Path | None = None) -> Params:
    """Read and validate a TOML parameter file (default: the shipped reference set)."""
    path = Path(path) if path is not None else default_params_path()
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise ParameterError(f"{path}: cannot read parameter file ({exc.strerror})") from None
    # TOML is UTF-8: a Latin-1 byte (an editor's 'é' in a comment) is named, not a traceback.
    text = decode_text(data, str(path), "a parameter file (TOML, UTF-8)", ParameterError)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError(f"{path}: not valid TOML: {exc}") from None
    return params_from_dict(data, str(path))
