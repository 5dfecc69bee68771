"""AUTO-07p constants files (c.NAME): parsing, overrides, the shipped examples. No numerics.
The Constants they are read into (every constant with its default, each value checked)
are the engine's: washer.cont.constants.

Syntax (docs/auto.md section 1.1): free-form `KEY = value` statements separated by
commas, blanks or newlines; `#` and `!` start comments; values are Fortran
numbers, quoted strings, [lists] and {dicts} (brackets may span lines); indices
in ICP, THL, THU, UZR, UZSTOP, U and PAR may be names from parnames/unames, and
'PERIOD' means 11. Defaults are AUTO-07p's (main.f90:INIT).
"""
from __future__ import annotations

import copy
import re
import shutil
from pathlib import Path

# the constants a run receives are the engine's (read into here, re-exported)
from washer.cont.constants import Constants, ConstantsError  # noqa: F401
from washer.cont.settings import DEFAULTS, HUGE  # noqa: F401 (AUTO's table, re-exported)
from washer.text_files import decode_text

#: Constants accepted but without effect in this engine, with the reason.
IGNORED = {
    "IID": "the d-file is always written at AUTO's level 2",
    "IIS": "the direction is always stored in the s-file (AUTO's IIS = 3)",
}


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
                if self.peek() == "}":
                    # a key without a value: the braces held an odd number of tokens.
                    # AUTO's parseC reads braces as a flat list of tokens, which
                    # list-valued constants take as the list: STOP={'UZ1'} (a Python
                    # set in a user's script) is STOP=['UZ1'].
                    self.advance()
                    return [t for kv in items.items() for t in kv] + [key]
                # AUTO's parseC (scanvalue) reads a dictionary as a flat list of tokens
                # in which ':' and ',' alike separate: {'theta', [0, 1]} is
                # {'theta': [0, 1]} to AUTO-07p, so a ',' stands for the ':' here too.
                if self.advance() not in (":", ","):
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
        m = re.compile(r"[A-Za-z_][\w.]*").match(self.text, self.i)
        if m and not re.compile(r"\s*=").match(self.text, m.end()):
            # an unquoted word (IRS = UZ1, STOP = [UZ1]): AUTO's parseC reads every value
            # as a token, quoted or not, and converts it by its key (IRS a label name)
            self.i = m.end()
            return m.group()
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


#: parse_text's statements of the texts parsed in this process (a chain of runs reads
#: the same constants file again and again; its character scanner cost a short run of a
#: small problem a twentieth of its time). Callers get deep copies. A text in the new
#: KEY = value format is remembered by the text alone: its statements do not depend on
#: the file it came from (the source names only errors, which are not remembered), so a
#: copy of the file in another folder is not scanned again; one in the old positional
#: format by (text, source), as its parse may warn naming the file.
_PARSED: dict = {}
_PARSED_MAX = 64


def parse_text(text: str, source: str = "<string>") -> list[tuple[str, object, int]]:
    """Statements (key, value, line) of a constants file: KEY = value statements, and,
    from the first line that starts with a digit on, AUTO's old positional format
    (AUTO's parseC reads both so: new-style lines such as parnames may come first)."""
    statements = _PARSED.get(text)
    if statements is None:
        statements = _PARSED.get((text, source))
    if statements is None:
        if len(_PARSED) >= _PARSED_MAX:
            _PARSED.clear()
        statements, old = _parse_text(text, source)
        _PARSED[(text, source) if old else text] = statements
    return [(k, _copied(v), line) for k, v, line in statements]


def _copied(value):
    """A copy of a parsed value: its lists, tuples and dicts new, numbers and strings
    shared (immutable); copy.deepcopy's generality costs it as much as the parse."""
    if isinstance(value, list):
        return [_copied(v) for v in value]
    if isinstance(value, tuple):
        return tuple(_copied(v) for v in value)
    if isinstance(value, dict):
        return {k: _copied(v) for k, v in value.items()}
    if isinstance(value, (int, float, str, bool, type(None))):
        return value
    return copy.deepcopy(value)


def _parse_text(text: str, source: str) -> tuple[list[tuple[str, object, int]], bool]:
    """(statements, whether the text goes on in the old positional format)."""
    sc = _Scanner(text, source)
    out = []
    while True:
        sc.skip()
        if sc.peek() == "":
            return out, False
        if sc.peek().isdigit():
            names = [v for k, v, _ in out if k == "parnames" and isinstance(v, dict)]
            return out + parse_old(text.splitlines(), sc.line - 1, source,
                                   [str(x) for d in names for x in d.values()]), True
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
