"""AUTO-07p's point-type codes (support.f90:LBTYPE), in one place.

A point's type is an integer `ITP`. On a one-parameter branch it is the base
code below. On a codim-1 curve continued with ISW = 2 from a point of type
ITPST (2 = LP, 3 = HB, 1 = BP, 5 = LP of cycles, 7 = PD, 8 = TR) every
nonzero code becomes `base + sign(base) * 10 * ITPST` (docs/auto.md section 2.1):
UZ -34, EP 39, BT -31, GH -32, ZH -33, BP 31, LP 32 and regular NPR points 34 on
a Hopf curve; UZ -24, EP 29, BT -21, CP -22 on a fold curve. Unlabelled points
keep code 0 everywhere.
"""
from __future__ import annotations

from enum import IntEnum


class Code(IntEnum):
    """Base type codes. `Code.GH` and `Code.CP` share the base -2: AUTO tells
    them apart by the curve (GH on Hopf curves, CP on fold curves)."""
    NONE = 0        # regular point, no label
    BP = 1          # branch point (algebraic)
    LP = 2          # fold (algebraic)
    HB = 3          # Hopf bifurcation
    RG = 4          # regular point labelled every NPR steps
    UZ = -4         # user point (UZR / UZSTOP / PVLS values)
    LPC = 5         # fold of periodic orbits (BVP)
    BPC = 6         # branch point of periodic orbits (BVP)
    PD = 7          # period doubling
    TR = 8          # torus (Neimark-Sacker)
    EP = 9          # end point
    MX = -9         # abnormal end (no convergence)
    BT = -1         # Bogdanov-Takens (codim 2)
    CP = -2         # cusp on fold curves; generalized Hopf (GH) on Hopf curves
    GH = -2         # alias of CP: the same base code, named GH on Hopf curves
    ZH = -3         # zero-Hopf
    R1 = -5
    R2 = -6
    R3 = -7
    R4 = -8


#: Two-letter names of base codes, as AUTO prints them (blank for regular points).
_NAMES = {0: "", 1: "BP", 2: "LP", 3: "HB", 4: "", -4: "UZ", 5: "LP", 6: "BP", 7: "PD",
          8: "TR", 9: "EP", -9: "MX", -1: "BT", -2: "CP", -3: "ZH", -5: "R1", -6: "R2",
          -7: "R3", -8: "R4"}
#: Name to base code (for STOP/SP lists and IRS='HB2' style labels).
BASE_OF_NAME = {"BP": 1, "LP": 2, "HB": 3, "UZ": -4, "PD": 7, "TR": 8, "EP": 9, "MX": -9,
                "BT": -1, "CP": -2, "GH": -2, "ZH": -3, "R1": -5, "R2": -6, "R3": -7, "R4": -8}


def curve_code(base: int, curve_type: int) -> int:
    """The code AUTO writes for a point of type `base` on a curve started from
    a point of type `curve_type` (0 on ordinary branches)."""
    base = int(base)
    if curve_type == 0 or base == 0:
        return base
    return base + (10 * curve_type if base > 0 else -10 * curve_type)


def split_code(code: int) -> tuple[int, int]:
    """(base, curve_type) of a written code: 34 -> (4, 3), -32 -> (-2, 3), -9 -> (-9, 0)."""
    code = int(code)
    if -9 <= code <= 9:
        return code, 0
    mag = abs(code)
    return (mag % 10) * (1 if code > 0 else -1), mag // 10


#: Written codes with names of their own (LBTYPE): the codim-2 points of maps' loci
#: found by the multiplier test, fold-flip (LPD), fold-Neimark-Sacker (LTR),
#: flip-Neimark-Sacker (PTR) and double Neimark-Sacker (TTR); AUTO names these codes
#: so whichever curve they are on.
_CURVE_NAMES = {23: "LTR", 83: "LTR", 77: "PTR", 87: "PTR", 28: "LPD", 78: "LPD", 88: "TTR"}


#: type_name's answers by code (every point's b-row and screen line asks for one of a few)
_TYPE_NAMES: dict = {}


def type_name(code: int) -> str:
    """'HB', 'UZ', 'GH', 'BT', 'LPD', ... for any written code, including curve codes."""
    name = _TYPE_NAMES.get(code)
    if name is None:
        name = _TYPE_NAMES[int(code)] = _type_name(code)
    return name


def _type_name(code: int) -> str:
    if int(code) in _CURVE_NAMES:
        return _CURVE_NAMES[int(code)]
    base, curve = split_code(code)
    if base == -2 and curve == 3:
        return "GH"
    return _NAMES.get(base, "")


#: The type names a restart label may name: the base codes', the curve codes' own
#: (LPD, LTR, PTR, TTR) and RG (an NPR point).
LABEL_NAMES = frozenset(BASE_OF_NAME) | frozenset(_CURVE_NAMES.values()) | {"RG"}


def split_label(key) -> tuple[str, int | None]:
    """'HB2' -> ('HB', 2), 'R31' -> ('R3', 1), 'LPD1' -> ('LPD', 1), 'HB' -> ('HB', None).

    AUTO's rule (parseS.getLabel): the type name is the first two characters, or three
    where the third is no digit, so the resonances' names (R1..R4) end in a digit and
    'R31' is the first R3. Raises ValueError for anything else."""
    text = str(key).strip().upper()
    size = 2 if len(text) < 3 or text[2].isdigit() else 3
    name, rest = text[:size], text[size:]
    count = int(rest) if rest.isdigit() else None
    if name not in LABEL_NAMES or (rest and not count):
        raise ValueError(f"bad label {key!r}: expected a number or a type name such as 'HB2' "
                         f"or 'R31' (types: {', '.join(sorted(LABEL_NAMES))})")
    return name, count


def parse_label(key) -> tuple[str, int] | int:
    """A restart key: an integer label, -n (the n-th record), or 'HB2' (type, count).

    Returns the integer for numeric keys, else (TYPE, count) with count >= 1."""
    if isinstance(key, bool):
        raise ValueError(f"bad label {key!r}")
    if isinstance(key, int):
        return key
    text = str(key).strip()
    if text.lstrip("+-").isdigit():
        return int(text)
    name, count = split_label(text)
    return name, (1 if count is None else count)


def has_type(code: int, name: str) -> bool:
    """Whether a written code is of type `name` ('HB', 'GH', 'RG' for NPR points, ...)."""
    if name == "RG":
        return split_code(code)[0] == 4
    return type_name(code) == name


def find(items, key, code=lambda r: r.code, lab=lambda r: r.lab):
    """AUTO's FINDLB over labelled items (s-records, points of a run in memory): an
    integer label, -n for the n-th item, or 'HB2' (the 2nd HB; 'RG1' the first NPR
    point). `code`/`lab` read an item's written type code and label. Raises
    LookupError naming what there is."""
    items = list(items)
    try:
        k = parse_label(key)
    except ValueError as exc:
        raise LookupError(str(exc)) from None
    if isinstance(k, tuple):
        name, count = k
        hits = [r for r in items if has_type(code(r), name)]
        if len(hits) < count:
            raise LookupError(f"'{key}': there are {len(hits)} {name} point(s)")
        return hits[count - 1]
    if k < 0:
        if -k > len(items):
            raise LookupError(f"{key}: there are only {len(items)} labelled points")
        return items[-k - 1]
    for r in items:
        if lab(r) == k:
            return r
    raise LookupError(f"no label {k} (labels: {[lab(r) for r in items]})")
