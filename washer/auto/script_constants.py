"""AUTO's constants as the command language holds them (AUTO's parseC), and its error.

Every standard key is present, None meaning AUTO's default; a constants file given with c=
resets the keys it does not set, keywords change one, DS='-' reverses the direction.
"""
from __future__ import annotations

from washer.auto.constants_file import DEFAULTS, Constants

#: Constants a constants file resets to "default" when it does not set them (parseC's
#: list); the special keys e, unames, parnames survive a new constants file.
STANDARD_KEYS = [k for k in DEFAULTS if k not in ("e", "unames", "parnames")]
SPECIAL_KEYS = ("e", "unames", "parnames", "homcont")


class AutoError(RuntimeError):
    """A command failed (AUTO's AUTORuntimeError)."""


class AutoConstants(dict):
    """AUTO's constants as the CLUI holds them (parseC): every standard key present,
    None meaning AUTO's default; updates replace values, None included.

    `origins` maps a key read from a constants file to its place there ('c.NAME:LINE'),
    so that an error found only when a run is built names that line; a value set by a
    command keyword has no origin (the error names the command)."""

    def __init__(self, other=None, **kw):
        super().__init__({k: None for k in STANDARD_KEYS})
        self.origins: dict[str, str] = dict(getattr(other, "origins", {}))
        if other is not None:
            for k, v in dict(other).items():
                dict.__setitem__(self, k, _copyval(v))
        if kw:
            self.update(kw)

    def __setitem__(self, key, value):
        self.origins.pop(key, None)
        if key == "DS" and value in ("-", "+"):
            cur = self.get("DS")
            cur = 0.01 if cur is None else float(cur)
            value = -cur if value == "-" else abs(cur)
        if key in ("SP", "STOP") and isinstance(value, str):
            value = [value]                      # AUTO accepts STOP='UZ2' for ['UZ2']
        dict.__setitem__(self, key, _copyval(value))

    def update(self, d=None, **kw):
        items = dict(d or {})
        items.update(kw)
        origins = getattr(d, "origins", {})
        for k, v in items.items():
            if k in self or k in SPECIAL_KEYS:
                self[k] = v
                if k in origins and k not in kw:
                    self.origins[k] = origins[k]
            elif not str(k).startswith("Active "):
                import difflib
                near = difflib.get_close_matches(str(k), [x for x in self if x.isupper()] or
                                                 list(self), n=1)
                raise AutoError(f"Unknown option: {k}" +
                                (f" (did you mean {near[0]}?)" if near else
                                 " (expected an AUTO constant such as NMX, DS or ICP)"))

    def copy(self) -> "AutoConstants":
        return AutoConstants(self)

    def washer(self, source: str) -> Constants:
        """The engine's checked Constants (defaults where None)."""
        c = Constants(source=source)
        for k, v in self.items():
            if v is None or k == "homcont":
                continue
            c.set(k, v, self.origins.get(k, f"{source}: {k}"))
        return c


def _copyval(v):
    return v.copy() if isinstance(v, (dict, list)) else v
