"""Reading b-files in the tests: rows of equilibrium or periodic branches, the
branch computations they form, their labelled rows."""
import gzip
import tempfile
from pathlib import Path

from washer.auto.files import read_b


def b_branches(path: Path) -> list:
    """read_b of a b-file, gzipped (NAME.gz, as large reference files are kept) or not."""
    if path.suffix != ".gz":
        return read_b(path)
    with tempfile.TemporaryDirectory() as tmp:
        plain = Path(tmp) / path.stem
        plain.write_bytes(gzip.decompress(path.read_bytes()))
        return read_b(plain)


def branch_rows(path: Path, periodic: bool | None = None) -> list:
    """Every row of a b-file (gzipped or not); only AUTO's equilibrium rows (BR > 0,
    periodic=False) or periodic ones (BR < 0, periodic=True) when asked."""
    rows = [r for b in b_branches(Path(path)) for r in b]
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
