"""AUTO-07p constants files (c.NAME): parsing, defaults, overrides. No numerics.

Syntax (docs/auto.md section 1.1): free-form `KEY = value` statements separated by
commas, blanks or newlines; `#` and `!` start comments; values are Fortran
numbers, quoted strings, [lists] and {dicts} (brackets may span lines); indices
in ICP, THL, THU, UZR, UZSTOP, U and PAR may be names from parnames/unames, and
'PERIOD' means 11. Defaults are AUTO-07p's (main.f90:INIT).
"""
from __future__ import annotations

import math
import re
import shutil
from pathlib import Path

from washer.cont.settings import DEFAULTS, HUGE  # noqa: F401 (AUTO's table, re-exported)

INT_KEYS = {"NDIM", "IPS", "ILP", "NTST", "NCOL", "IAD", "ISP", "ISW", "IPLT", "NBC", "NINT",
            "NMX", "NPR", "MXBF", "IID", "ITMX", "ITNW", "NWTN", "JAC", "IADS", "NPAR", "IIS",
            "IBR", "LAB", "NUNSTAB", "NSTAB", "IEQUIB", "ITWIST", "ISTART"}
REAL_KEYS = {"EPSL", "EPSU", "EPSS", "DS", "DSMIN", "DSMAX", "RL0", "RL1", "A0", "A1"}
STR_KEYS = {"e", "s", "dat", "sv", "TY"}
#: Constants accepted but without effect in this engine, with the reason.
IGNORED = {
    "IID": "the d-file is always written at AUTO's level 2",
    "IIS": "the direction is always stored in the s-file (AUTO's IIS = 3)",
    "NUNSTAB": "HomCont", "NSTAB": "HomCont", "IEQUIB": "HomCont", "ITWIST": "HomCont",
    "ISTART": "HomCont", "IREV": "HomCont", "IFIXED": "HomCont", "IPSI": "HomCont",
}


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


class _Scanner:
    """Character scanner over the text with line numbers."""

    def __init__(self, text: str, source: str):
        self.text, self.source, self.i, self.line = text.replace("\t", " "), source, 0, 1

    def error(self, what: str) -> ConstantsError:
        return ConstantsError(f"{self.source}:{self.line}: {what}")

    def peek(self) -> str:
        return self.text[self.i] if self.i < len(self.text) else ""

    def advance(self) -> str:
        c = self.peek()
        self.i += 1
        if c == "\n":
            self.line += 1
        return c

    def skip(self, newlines: bool = True, commas: bool = True) -> None:
        """Skip blanks, separators and comments."""
        while self.i < len(self.text):
            c = self.peek()
            if c in "#!":
                while self.peek() not in ("\n", ""):
                    self.advance()
            elif c == "\n" and newlines or c in " \r" or c == "," and commas:
                self.advance()
            else:
                break

    def word(self) -> str:
        m = re.compile(r"[A-Za-z_][A-Za-z0-9_]*").match(self.text, self.i)
        if not m:
            raise self.error(f"expected a constant name, found {self.text[self.i:self.i + 10]!r}")
        self.i = m.end()
        return m.group()

    def value(self):
        self.skip()
        c = self.peek()
        if c == "[":
            opened = self.line
            self.advance()
            items = []
            while True:
                self.skip()
                if self.peek() == "]":
                    self.advance()
                    return items
                if self.peek() == "":
                    raise self.error("unclosed '[': expected ']'")
                if re.compile(r"[A-Za-z_]\w*\s*=").match(self.text, self.i):
                    # the next statement: the list was never closed
                    raise ConstantsError(
                        f"{self.source}:{opened}: unclosed '[': expected ']' before "
                        f"{self.text[self.i:].splitlines()[0].strip()!r} (line {self.line})")
                items.append(self.value())
        if c == "{":
            opened = self.line
            self.advance()
            items = {}
            while True:
                self.skip()
                if self.peek() == "}":
                    self.advance()
                    return items
                if self.peek() == "":
                    raise self.error("unclosed '{': expected '}'")
                if re.compile(r"[A-Za-z_]\w*\s*=").match(self.text, self.i):
                    raise ConstantsError(
                        f"{self.source}:{opened}: unclosed '{{': expected '}}' before "
                        f"{self.text[self.i:].splitlines()[0].strip()!r} (line {self.line})")
                m = re.compile(r"[A-Za-z_][A-Za-z0-9_()]*(?=\s*:)").match(self.text, self.i)
                if m and m.group() not in ("None", "True", "False"):
                    # an unquoted name as a key ({epsilon: [1e-4]}): AUTO's READC takes it
                    self.i = m.end()
                    key = m.group()
                else:
                    key = self.value()
                self.skip(commas=False)
                if self.advance() != ":":
                    raise self.error("expected ':' after a dictionary key")
                items[key] = self.value()
        if c in "'\"":
            return self._string(c)
        m = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?").match(self.text, self.i)
        if m and m.group():
            self.i = m.end()
            s = m.group().replace("d", "e").replace("D", "e")
            return int(s) if re.fullmatch(r"[+-]?\d+", s) else float(s)
        m = re.compile(r"[A-Za-z_][A-Za-z0-9_]*").match(self.text, self.i)
        if m and m.group() in ("None", "True", "False"):
            self.i = m.end()
            return {"None": None, "True": True, "False": False}[m.group()]
        raise self.error(f"expected a value (number, 'string', [list] or {{dict}}), found "
                         f"{self.text[self.i:self.i + 12]!r}")

    def _string(self, quote: str) -> str:
        self.advance()
        out = []
        while True:
            c = self.advance()
            if c == "":
                raise self.error("unterminated string")
            if c == quote:
                if self.peek() == quote:
                    out.append(self.advance())
                    continue
                return "".join(out)
            out.append(c)


#: The rows of AUTO's old positional constants format after NDIM..ILP and ICP
#: (python/auto/parseC.py line_comments): a row may hold fewer values (the others keep
#: their defaults) and anything after its last value is a comment.
OLD_ROWS = (("NTST", "NCOL", "IAD", "ISP", "ISW", "IPLT", "NBC", "NINT"),
            ("NMX", "RL0", "RL1", "A0", "A1"),
            ("NPR", "MXBF", "IID", "ITMX", "ITNW", "NWTN", "JAC"),
            ("EPSL", "EPSU", "EPSS"),
            ("DS", "DSMIN", "DSMAX", "IADS"))


def _old_number(word: str, key: str, where: str):
    """One value of the old format: an integer for AUTO's I-N names, else a Fortran real."""
    try:
        if key[0] in "IJKLMN":
            return int(word)
        return float(word.replace("d", "e").replace("D", "e"))
    except ValueError:
        kind = "an integer" if key[0] in "IJKLMN" else "a number"
        raise ConstantsError(f"{where}: {key} expects {kind}, got {word!r}") from None


class ConstantsWarning(UserWarning):
    """A constants file AUTO reads, but not as its author probably meant (an ICP row
    listing more indices than its NICP)."""


def _int_or_name(word: str):
    """A positional row's index: an integer, else a name from parnames (or a label, IRS)."""
    try:
        return int(word)
    except ValueError:
        return word


def _old_icp(words: list[str], n: int, line: str, source: str, names) -> list:
    """ICP of the old format's second row `NICP ICP(1) .. ICP(NICP) [comment]`: the first
    NICP words after NICP, as AUTO's parseC takes them (integers, or names of parnames:
    `names`, the parnames given before the positional rows). A row whose NICP does not
    match the indices it lists is an error naming what was expected (AUTO itself would
    take a word of the comment for a parameter name); indices beyond NICP are taken as
    the comment, as AUTO does, with a ConstantsWarning."""
    import warnings
    where = f"{source}:{n}"
    nicp = _old_number(words[0], "NICP", where)

    def is_index(w: str) -> bool:
        name = w.lstrip("-")
        return bool(re.fullmatch(r"-?\d+", w)) or name in names or name == "PERIOD" or \
            bool(re.fullmatch(r"PAR\(\d+\)", name))

    listed = []                         # the indices the row lists, up to its comment
    for w in words[1:]:
        if not is_index(w):
            break
        listed.append(w)
    expected = (f"expected NICP (the number of continuation parameters, >= 1) followed "
                f"by that many parameter indices, e.g. '2 1 11'; found {' '.join(line.split())!r}")
    if nicp < 1:
        raise ConstantsError(f"{where}: NICP = {nicp}: {expected}")
    if len(listed) < nicp:
        after = words[1 + len(listed)] if len(words) > 1 + len(listed) else None
        what = f"then {after!r}, which is neither an integer nor a name of parnames" \
            if after is not None else "and the line ends"
        raise ConstantsError(f"{where}: NICP = {nicp} but the row lists {len(listed)} "
                             f"parameter ind{'ex' if len(listed) == 1 else 'ices'} "
                             f"{' '.join(listed)} {what}: {expected}")
    if len(listed) > nicp:
        warnings.warn(f"{where}: NICP = {nicp} but the row lists {len(listed)} parameter "
                      f"indices ({' '.join(listed)}): ICP = [{', '.join(listed[:nicp])}] as AUTO reads it, "
                      f"{' '.join(listed[nicp:])} taken as a comment (raise NICP to "
                      f"{len(listed)} to continue in them all)", ConstantsWarning, stacklevel=2)
    return [_int_or_name(w) for w in listed[:nicp]]


def parse_old(lines: list[str], first: int, source: str,
              parnames=()) -> list[tuple[str, object, int]]:
    """Statements (key, value, line) of AUTO's old positional format (parseC.read):
    NDIM IPS IRS ILP / NICP ICP(1..NICP) / the OLD_ROWS / NTHL, then NTHL rows `I THL(I)`,
    likewise THU and UZR. lines[first] is the first positional row (line first + 1).
    parnames: the parameter names given before the positional rows."""
    out: list[tuple[str, object, int]] = []
    pos = first

    def row(what: str, need: int) -> tuple[list[str], int]:
        nonlocal pos
        if pos >= len(lines):
            raise ConstantsError(f"{source}:{pos + 1}: the file ends where the old "
                                 f"positional format expects {what}")
        words, n = lines[pos].replace(",", " ").split(), pos + 1
        pos += 1
        if len(words) < need:
            raise ConstantsError(f"{source}:{n}: expected {what}, found {lines[n - 1]!r}")
        return words, n

    words, n = row("NDIM IPS IRS ILP", 4)
    for key, word in zip(("NDIM", "IPS", "IRS", "ILP"), words):
        out.append((key, _int_or_name(word) if key == "IRS" else
                    _old_number(word, key, f"{source}:{n}"), n))
    words, n = row("NICP and the NICP indices of ICP", 1)
    out.append(("ICP", _old_icp(words, n, lines[n - 1], source, set(parnames)), n))
    for keys in OLD_ROWS:
        words, n = row(" ".join(keys), 1)
        out += [(k, _old_number(w, k, f"{source}:{n}"), n) for k, w in zip(keys, words)]
    for key in ("THL", "THU", "UZR"):
        words, n = row(f"N{key}, the number of {key} rows that follow", 1)
        count = _old_number(words[0], "N" + key, f"{source}:{n}")
        entries: dict = {}
        for _ in range(count):
            words, m = row(f"a {key} row: a parameter index and a value", 2)
            k, v = _int_or_name(words[0]), _old_number(words[1], key, f"{source}:{m}")
            if key == "UZR" and k in entries:       # repeated index: a list of values
                prev = entries[k]
                entries[k] = (prev if isinstance(prev, list) else [prev]) + [v]
            else:
                entries[k] = v
        out.append((key, entries, n))
    return out


def parse_text(text: str, source: str = "<string>") -> list[tuple[str, object, int]]:
    """Statements (key, value, line) of a constants file: KEY = value statements, and,
    from the first line that starts with a digit on, AUTO's old positional format
    (AUTO's parseC reads both so: new-style lines such as parnames may come first)."""
    sc = _Scanner(text, source)
    out = []
    while True:
        sc.skip()
        if sc.peek() == "":
            return out
        if sc.peek().isdigit():
            names = [v for k, v, _ in out if k == "parnames" and isinstance(v, dict)]
            return out + parse_old(text.splitlines(), sc.line - 1, source,
                                   [str(x) for d in names for x in d.values()])
        line = sc.line
        key = sc.word()
        sc.skip(newlines=False, commas=False)
        if sc.advance() != "=":
            raise ConstantsError(f"{source}:{line}: expected '=' after {key}")
        try:
            value = sc.value()
        except ConstantsError as exc:
            # the key whose value is wrong, in its statement's words
            raise ConstantsError(str(exc).replace(": expected a value", f": {key}: expected a "
                                                  "value", 1)) from None
        out.append((key, value, line))


def check_value(key: str, value, where: str):
    """Type-check one constant; returns the normalised value."""
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
    """Refuse a path in a name constant (e, s, dat, sv).

    AUTO uses these as name suffixes: sv='x' writes b.x, s.x, d.x in the run's
    folder. A separator or '..' would make washer read or write outside that
    folder, which a constants file should never do by accident.
    """
    bad = [c for c in ("/", "\\", "\0") if c in value]
    if bad or ".." in value:
        what = "a path separator" if bad and bad[0] != "\0" else "a NUL byte" if bad else "'..'"
        role = ("e='NAME' loads NAME.py beside the constants file" if key == "e" else
                "AUTO writes and reads b.NAME, s.NAME, d.NAME in the constants file's folder")
        raise ConstantsError(
            f"{where}: {key}={value!r} contains {what}: {key} is a name ({role}), not a path; "
            "run from the folder you want the files in, or copy the files there")


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
        """1-based PAR index of an integer or a name (parnames, 'PERIOD' = 11);
        a leading '-' on a name gives a negative index. `where` (file:line) names the
        place in errors, else the constants' source."""
        where = where or self.source
        if isinstance(key, bool):
            raise ConstantsError(f"{where}: bad parameter index {key!r}")
        if isinstance(key, int):
            return key
        if isinstance(key, str):
            sign = -1 if key.startswith("-") else 1
            name = key.lstrip("-")
            if name == "PERIOD":
                return 11 * sign
            for i, n in self["parnames"].items():
                if n == name:
                    return int(i) * sign
            if re.fullmatch(r"PAR\(\d+\)", name):
                return int(name[4:-1]) * sign
        raise ConstantsError(f"{where}: unknown parameter {key!r}; parnames = "
                             f"{self['parnames']}")

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


def decode_text(data: bytes, source: str, what: str, error=ValueError) -> str:
    """UTF-8 text of a file's bytes, or `error` naming the file, line and the bad byte.

    AUTO's files are plain ASCII; a NUL byte or an undecodable byte means a
    binary or corrupt file, which must not be read as (partly) empty.
    """
    nul = data.find(b"\0")
    if nul >= 0:
        line = data.count(b"\n", 0, nul) + 1
        raise error(f"{source}:{line}: a NUL byte: this is a binary file, not {what}")
    try:
        return data.decode("utf-8-sig")          # an editor's BOM is not content
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise error(f"{source}:{line}: byte 0x{data[exc.start]:02x} is not UTF-8 text: "
                    f"expected {what} (plain text)") from None


def read_constants(path: str | Path) -> Constants:
    """Read and check a constants file; errors name the file and line."""
    path = Path(path)
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        hint = ""
        if path.name in shipped_constants():
            hint = ("; washer ships a constants file of that name: copy the examples with "
                    "`python -m washer.run --copy-examples DIR`")
        raise ConstantsError(f"{path}: no such constants file{hint}") from None
    except OSError as exc:
        raise ConstantsError(f"{path}: cannot read constants file ({exc.strerror})") from None
    text = decode_text(data, str(path), "an AUTO constants file", ConstantsError)
    c = Constants(source=str(path))
    statements = parse_text(text, str(path))
    if not statements and text.strip():
        raise ConstantsError(f"{path}: no KEY = value statements (only comments): expected "
                             "an AUTO constants file such as `NDIM = 2, ICP = [1]`")
    for key, value, line in statements:
        c.set(key, value, f"{path}:{line}")
    return c


# ------------------------------------------------------------- shipped examples

def shipped_constants_dir() -> Path | None:
    """Folder of the constants files shipped with washer, or None.

    An installed wheel carries them as washer/auto_constants/ (setup.py copies
    them there); a source checkout (editable install) has auto_constants/ at
    the top of the tree.
    """
    pkg = Path(__file__).resolve().parents[1]
    for folder in (pkg / "auto_constants", pkg.parent / "auto_constants"):
        if folder.is_dir() and any(folder.glob("c.*")):
            return folder
    return None


def shipped_constants() -> dict[str, Path]:
    """{file name: path} of every shipped constants file (c.washer, c.washer.hopf.Omega, ...)."""
    folder = shipped_constants_dir()
    return {p.name: p for p in sorted(folder.glob("c.*"))} if folder else {}


#: AUTO's `ab` demo shipped as an example (equations and constants): its place in a checkout.
AB_DEMO = ("tests/data/ab/ab.py", "tests/data/ab/c.ab")


def shipped_examples() -> dict[str, Path]:
    """{file name: path} of the other shipped examples: the sweep specs (sweep_*.toml)
    and AUTO's ab demo (ab.py, c.ab). A wheel carries them as washer/examples/
    (setup.py); a checkout has them in examples/ and tests/data/ab/."""
    pkg = Path(__file__).resolve().parents[1]
    inside = pkg / "examples"
    if inside.is_dir():
        return {f.name: f for f in sorted(inside.iterdir())
                if f.is_file() and not f.name.startswith((".", "_"))}
    root = pkg.parent
    out = {f.name: f for f in sorted((root / "examples").glob("*.toml"))}
    for rel in AB_DEMO:
        if (root / rel).is_file():
            out[Path(rel).name] = root / rel
    return out


def copy_examples(dest: str | Path, overwrite: bool = False) -> tuple[list[Path], list[Path]]:
    """Copy the shipped constants files and examples (sweep specs, AUTO's ab demo)
    into `dest` (created if missing).

    Returns (copied, skipped): an existing file is kept unless overwrite=True,
    so a user's edited constants are never replaced silently.
    """
    files = shipped_constants()
    if files:
        files = dict(files, **shipped_examples())
    if not files:
        raise ConstantsError("no shipped constants files found: this washer installation "
                             "lacks washer/auto_constants/ (reinstall the package)")
    dest = Path(dest)
    try:
        dest.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ConstantsError(f"{dest}: cannot create the folder ({exc.strerror})") from None
    copied, skipped = [], []
    for name, src in files.items():
        target = dest / name
        if target.exists() and not overwrite:
            skipped.append(target)
            continue
        shutil.copyfile(src, target)
        copied.append(target)
    return copied, skipped


def parse_override(text: str) -> tuple[str, object]:
    """'KEY=value' from a command line, with AUTO's value syntax (bare words are strings)."""
    if "=" not in text:
        raise ConstantsError(f"override {text!r}: expected KEY=value")
    key, raw = text.split("=", 1)
    key = key.strip()
    try:
        stmts = parse_text(f"{key} = {raw}", "<command line>")
        return key, stmts[0][1]
    except ConstantsError:
        return key, raw.strip()          # e.g. IRS=HB1 or e=ab without quotes
