"""AUTO's constants as a run receives them: `Constants`, a dict of every constant AUTO-07p
knows with its default filled in (washer.cont.settings.DEFAULTS), each value checked as it
is set (`check_value`), with the names resolved (parnames, unames, 'PERIOD') and the place
each was given (`.given`, `.source`) for error messages. The engine's runs read them
(`Settings.from_constants`, `washer.cont.start`); washer.auto.constants_file reads constants
files into them. No file handling here.
"""
from __future__ import annotations

import math
import re

from washer.cont.settings import DEFAULTS

INT_KEYS = {"NDIM", "IPS", "ILP", "NTST", "NCOL", "IAD", "ISP", "ISW", "IPLT", "NBC", "NINT",
            "NMX", "NPR", "MXBF", "IID", "ITMX", "ITNW", "NWTN", "JAC", "IADS", "NPAR", "IIS",
            "IBR", "LAB", "NUNSTAB", "NSTAB", "IEQUIB", "ITWIST", "ISTART"}
REAL_KEYS = {"EPSL", "EPSU", "EPSS", "DS", "DSMIN", "DSMAX", "RL0", "RL1", "A0", "A1"}
STR_KEYS = {"e", "s", "dat", "sv", "TY"}


#: Name constants: AUTO appends them to 'b.', 's.', 'd.' (or reads NAME.py for e), so
#: they are file-name suffixes in the run's folder, never paths.
NAME_KEYS = ("e", "s", "dat", "sv")
#: Reals AUTO needs finite (an infinite step or tolerance never ends a step loop).
FINITE_KEYS = ("DS", "DSMIN", "DSMAX", "EPSL", "EPSU", "EPSS")
#: Lower bounds of reals and integers: (bound, strict).
LOWER_BOUNDS = {"DSMIN": (0.0, False), "DSMAX": (0.0, True), "EPSL": (0.0, False),
                "EPSU": (0.0, False), "EPSS": (0.0, False), "NDIM": (1, False),
                "NPAR": (1, False), "NMX": (0, False), "NPR": (0, False)}
#: Dictionaries whose values are numbers: {index or name: value (or list of values)}.
NUMBER_DICTS = ("PAR", "U", "THL", "THU", "UZR", "UZSTOP")
#: Weights: a negative one would make the arclength norm indefinite.
WEIGHT_KEYS = ("THL", "THU")
#: SP and STOP entries: a point type, then an optional count ('HB3', 'LP0', 'BP').
_TYPE_ENTRY = re.compile(r"[A-Za-z]{1,3}\d*")


class ConstantsError(ValueError):
    """A malformed constants file or value: the message gives file, line and expectation."""


def _plain(value):
    """numpy values as the Python numbers and lists they hold, inside dicts and lists too:
    AUTO's scripts are Python, and UZR={10: linspace(11, 0, 100)} or NMX=np.int64(5) are
    values there (AUTO iterates an array as a list)."""
    if isinstance(value, dict):
        return {_plain(k): _plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_plain(v) for v in value]
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):
        return _plain(value.tolist())
    return value


def check_value(key: str, value, where: str):
    """Type-check one constant; returns the normalised value."""
    value = _plain(value)
    # every message below names the key: a place that names it too ('run(e='ab'): NMX',
    # a command's keyword) would say it twice
    named = where.removesuffix(f": {key}")
    if key not in DEFAULTS:
        import difflib
        near = difflib.get_close_matches(str(key), list(DEFAULTS), n=1)
        raise ConstantsError(f"{named}: unknown AUTO constant {key}" +
                             (f" (did you mean {near[0]}?)" if near else ""))
    if key in INT_KEYS:
        if isinstance(value, float) and value.is_integer():
            value = int(value)
        if not isinstance(value, int) or isinstance(value, bool):
            raise ConstantsError(f"{named}: {key} expects an integer, got {value!r}")
        _check_bound(key, value, named)
    elif key in REAL_KEYS:
        if key == "DS" and value == "-":
            return value            # AUTO CLUI: flip the sign of the current DS
        if not isinstance(value, (int, float)) or isinstance(value, bool):
            raise ConstantsError(f"{named}: {key} expects a number, got {value!r}")
        value = float(value)
        if math.isnan(value) or (key in FINITE_KEYS and math.isinf(value)):
            raise ConstantsError(f"{named}: {key} expects a finite number, got {value!r}")
        _check_bound(key, value, named)
    elif key in STR_KEYS:
        if not isinstance(value, str):
            raise ConstantsError(f"{named}: {key} expects a quoted string, got {value!r}")
        if key in NAME_KEYS:
            check_name(key, value, named)
    elif key == "IRS":
        if not isinstance(value, (int, str)) or isinstance(value, bool):
            raise ConstantsError(f"{named}: IRS expects a label number or a name like 'HB1'")
    elif key == "ICP":
        if isinstance(value, (int, str)):
            value = [value]
        if not isinstance(value, list) or not value:
            raise ConstantsError(f"{named}: ICP expects a list of parameter indices or names")
        for i in value:
            # -21..-31: optimality conditions of IPS = 15 (checked against IPS by icp()).
            if isinstance(i, bool) or not isinstance(i, (int, str)) or \
                    isinstance(i, int) and i < 1 and not -31 <= i <= -21:
                raise ConstantsError(f"{named}: ICP entries are parameter indices >= 1 "
                                     f"(PAR(1), PAR(2), ...) or names (or, with IPS = 15, "
                                     f"-21..-31: optimality conditions), got {i!r}")
    elif key in ("SP", "STOP", "IREV", "IFIXED", "IPSI"):
        if isinstance(value, (dict, set, tuple)):
            # braces are a flat list of tokens to AUTO's parseC ({'LP1', 'HB2'}), and
            # a Python set or tuple in a script is a list of entries
            value = [t for kv in value.items() for t in kv] if isinstance(value, dict) \
                else sorted(value, key=str) if isinstance(value, set) else list(value)
        if not isinstance(value, list):
            raise ConstantsError(f"{named}: {key} expects a list")
        if key in ("SP", "STOP"):
            for entry in value:
                if not isinstance(entry, str) or not _TYPE_ENTRY.fullmatch(entry):
                    raise ConstantsError(
                        f"{named}: {key} entries are a point type and an optional count "
                        f"in quotes, like {key}=['HB3'] (the 3rd Hopf point) or ['LP0'], "
                        f"got {entry!r}")
    else:   # dicts
        if isinstance(value, list) and key in NUMBER_DICTS and \
                all(isinstance(v, list) and len(v) == 2 for v in value):
            value = _pairs_dict(key, value)
        if not isinstance(value, dict):
            raise ConstantsError(f"{named}: {key} expects a {{key: value}} dictionary")
        if key in NUMBER_DICTS:
            _check_number_dict(key, value, where)
        if key in ("parnames", "unames"):
            for k, n in value.items():
                if isinstance(k, bool) or not isinstance(k, int) or k < 1:
                    raise ConstantsError(f"{named}: {key} keys are indices 1, 2, ..., "
                                         f"got {k!r}")
                if not isinstance(n, str) or not n.strip():
                    raise ConstantsError(f"{named}: {key}[{k}] expects a name in quotes, "
                                         f"got {n!r}")
    return value


def _pairs_dict(key: str, pairs: list) -> dict:
    """AUTO's older list form [[i, v], ...] as a dict. UZR and UZSTOP may name one
    index several times (UZR = [[1, 0.25], [1, 0.75]]: a UZ at each value), so their
    values are gathered in a list; for the others the last pair wins, as in AUTO."""
    out: dict = {}
    for k, v in pairs:
        if key in ("UZR", "UZSTOP") and k in out:
            prev = out[k]
            out[k] = (prev if isinstance(prev, list) else [prev]) + \
                (v if isinstance(v, list) else [v])
        else:
            out[k] = v
    return out


def _check_number_dict(key: str, value: dict, where: str) -> None:
    """PAR, U, THL, THU, UZR, UZSTOP: index (or name) -> finite number (UZR, UZSTOP:
    or a list of them); THL/THU weights >= 0."""
    for k, v in value.items():
        if isinstance(k, bool) or not isinstance(k, (int, str)):
            raise ConstantsError(f"{where}: {key} keys are indices or names, got {k!r}")
        vals = v if isinstance(v, list) and key in ("UZR", "UZSTOP") else [v]
        if not vals:
            raise ConstantsError(f"{where}: {key}[{k!r}] is an empty list: expected a value "
                                 "or a list of values")
        for x in vals:
            if isinstance(x, bool) or not isinstance(x, (int, float)):
                raise ConstantsError(f"{where}: {key}[{k!r}] expects a number, got {x!r}")
            if not math.isfinite(x):
                raise ConstantsError(f"{where}: {key}[{k!r}] expects a finite number, got {x!r}")
            if key in WEIGHT_KEYS and x < 0:
                raise ConstantsError(f"{where}: {key}[{k!r}] = {x!r}: weights of the "
                                     "arclength norm are >= 0 (0 leaves the unknown out)")


def _check_bound(key: str, value, where: str) -> None:
    if key in LOWER_BOUNDS:
        bound, strict = LOWER_BOUNDS[key]
        if value < bound or strict and value == bound:
            raise ConstantsError(f"{where}: {key} expects a value {'>' if strict else '>='} "
                                 f"{bound}, got {value!r}")


def check_name(key: str, value: str, where: str) -> None:
    """Refuse a path in a name constant (s, dat, sv), and a NUL byte in any (e too).

    AUTO uses s, dat, sv as name suffixes: sv='x' writes b.x, s.x, d.x in the run's
    folder. A separator or '..' would make washer read or write outside that
    folder, which a constants file should never do by accident. e is the user
    file's path without its suffix, as AUTO's (e='./functions/yamada' compiles
    ./functions/yamada.f90, relative to the constants file's folder): only read.
    """
    if key == "e" and "\0" not in value:
        return
    bad = [c for c in ("/", "\\", "\0") if c in value]
    if bad or ".." in value:
        what = "a path separator" if bad and bad[0] != "\0" else "a NUL byte" if bad else "'..'"
        role = ("e='NAME' loads NAME.py (NAME.f90, NAME.f, NAME.c)" if key == "e" else
                "AUTO writes and reads b.NAME, s.NAME, d.NAME in the constants file's folder")
        raise ConstantsError(
            f"{where}: {key}={value!r} contains {what}: {key} is a name ({role}), not a path; "
            "run from the folder you want the files in, or copy the files there")


def par_name_index(name: str, parnames: dict) -> int | None:
    """1-based PAR index a name spells, or None: a parnames entry ({index: name}),
    'PERIOD' (11), 'PAR(3)', or the index spelled as a string, '3' (AUTO-07p reads a
    name that no parnames entry holds as the index it spells, ICP = ['3', '1']). A
    leading '-' gives the negative index. The one reading of a parameter's name: the
    constants, a run's branch and the command language's branches all use it."""
    sign = -1 if name.startswith("-") else 1
    name = name.lstrip("-")
    if name == "PERIOD":
        return 11 * sign
    for i, n in (parnames or {}).items():
        if n == name:
            return int(i) * sign
    m = re.fullmatch(r"(?:PAR\((\d+)\)|(\d+))", name)
    if m:
        return int(m.group(1) or m.group(2)) * sign
    return None


class Constants(dict):
    """AUTO constants: a dict of every constant, defaults filled in.

    `.given` holds the keys set by the user (file or overrides), `.source` the file.
    """

    def __init__(self, values: dict | None = None, source: str = "<defaults>"):
        super().__init__({k: (v.copy() if isinstance(v, (dict, list)) else v)
                          for k, v in DEFAULTS.items()})
        self.source = source
        self.given: dict[str, str] = {}
        for k, v in (values or {}).items():
            self.set(k, v, source)

    def set(self, key: str, value, where: str = "<override>") -> None:
        value = check_value(key, value, where)
        if key == "DS" and value == "-":
            value = -self["DS"]
        self[key] = value
        self.given[key] = where

    def copy(self) -> "Constants":
        c = Constants(source=self.source)
        dict.update(c, {k: (v.copy() if isinstance(v, (dict, list)) else v) for k, v in self.items()})
        c.given = dict(self.given)
        return c

    # ----------------------------------------------------------------- names
    def par_index(self, key, where: str | None = None) -> int:
        """1-based PAR index of an integer or a name (see `par_name_index`); a leading
        '-' on a name gives a negative index. `where` (file:line) names the place in
        errors, else the constants' source."""
        where = where or self.source
        if isinstance(key, bool):
            raise ConstantsError(f"{where}: bad parameter index {key!r}")
        if isinstance(key, int):
            return key
        i = par_name_index(key, self["parnames"]) if isinstance(key, str) else None
        if i is None:
            raise ConstantsError(f"{where}: unknown parameter {key!r}; parnames = "
                                 f"{self['parnames']}")
        return i

    def u_index(self, key) -> int:
        if isinstance(key, int) and not isinstance(key, bool):
            return key
        for i, n in self["unames"].items():
            if n == key:
                return int(i)
        raise ConstantsError(f"{self.source}: unknown state name {key!r}; unames = {self['unames']}")

    def icp(self) -> list[int]:
        """ICP as 1-based PAR indices (names resolved); every entry >= 1, except that
        optimisation of periodic solutions (IPS = 15) takes entries -(20 + k), k = 1..11:
        the optimality condition of PAR(k), whose value PAR(20 + k) is fixed (AUTO's
        AUTOOP, optimization.f90)."""
        where = self.given.get('ICP', self.source)
        out = [self.par_index(k, where) for k in self["ICP"]]
        for k, i in zip(self["ICP"], out):
            if i < 1 and self["IPS"] == 15 and -31 <= i <= -21:
                continue
            if i < 1 and self["IPS"] == 15:
                raise ConstantsError(f"{where}: ICP entry {k!r}: with IPS = 15 a negative entry "
                                     "-(20 + k) names the optimality condition of PAR(k), "
                                     "k = 1..11 (-21..-31)")
            if i < 1:
                raise ConstantsError(f"{where}: ICP entry {k!r} is "
                                     f"PAR({i}): continuation parameters are PAR(1), PAR(2), ..."
                                     " (negative entries are optimality conditions of IPS = 15 "
                                     "only)")
        seen: dict[int, object] = {}
        for k, i in zip(self["ICP"], out):
            if i in seen:
                what = f"PAR({i})" if i > 0 else f"the optimality condition {i}"
                raise ConstantsError(f"{where}: ICP = {self['ICP']} names {what} twice "
                                     f"({seen[i]!r} and {k!r}): each free parameter once")
            seen[i] = k
        return out

    def with_default_names(self, parnames: dict | None = None,
                           unames: dict | None = None) -> "Constants":
        """A copy whose parnames/unames are completed by a problem's own names.

        parnames, unames: {1-based index: name}, e.g. the built-in washer's
        {1: 'C_p', 2: 'Omega', ...}. Names the constants file (or an override)
        gives win: a default is skipped when its index is named already or its
        name is used for another index, so the user's meaning never changes.
        The defaults are not marked as given by the user.
        """
        c = self.copy()
        for key, defaults in (("parnames", parnames), ("unames", unames)):
            if not defaults:
                continue
            names = {int(i): n for i, n in c[key].items()}
            used = set(names.values())
            for i, n in defaults.items():
                if int(i) not in names and n not in used:
                    names[int(i)] = n
                    used.add(n)
            dict.__setitem__(c, key, dict(sorted(names.items())))
        return c

    def par_values(self, key: str) -> list[tuple[int, float]]:
        """(index, value) pairs of UZR/UZSTOP/THL/PAR-style dicts, lists expanded."""
        out = []
        where = self.given.get(key, self.source)
        if not re.search(r":\d+$", where):
            where = f"{where.removesuffix(f': {key}')}: {key}"     # name the constant
        for k, v in self[key].items():
            for x in (v if isinstance(v, list) else [v]):
                out.append((self.par_index(k, where), float(x)))
        return out

