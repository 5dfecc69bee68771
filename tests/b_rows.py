"""Reading b-files in the tests: rows of equilibrium or periodic branches, the
branch computations they form, their labelled rows."""
from pathlib import Path

from washer.auto.files import read_b


def branch_rows(path: Path, periodic: bool | None = None) -> list:
    """Every row of a b-file; only AUTO's equilibrium rows (BR > 0, periodic=False) or
    periodic ones (BR < 0, periodic=True) when asked."""
    rows = [r for b in read_b(path) for r in b]
    return rows if periodic is None else [r for r in rows if (r.br < 0) == periodic]


def segments(rows) -> list:
    """Rows split into branch computations: each starts at PT 1 (AUTO resets NTOT for
    every branch it computes, the first one and every switched one)."""
    out = []
    for r in rows:
        if abs(r.pt) == 1:
            out.append([])
        out[-1].append(r)
    return out


def header_blocks(path: Path) -> list[list[str]]:
    """The b-file's header blocks (the '   0' lines before each branch's rows)."""
    blocks, cur = [], []
    for line in path.read_text().splitlines():
        if line.startswith("   0"):
            cur.append(line)
        elif cur:
            blocks.append(cur)
            cur = []
    return blocks


def labelled(seg) -> list:
    return [r for r in seg if r.lab]
