"""tests/data keeps one copy of AUTO-07p's files: a demo's files and AUTO's outputs of it
are in its folder tests/data/auto_demos/NAME (tests/demo_files.py), which every test reads,
and nowhere else; AUTO's s-files are kept gzipped (s.NAME.gz, which washer's readers take
for s.NAME)."""
import gzip
import hashlib

from demo_files import DATA, DEMOS

#: AUTO's BSD licence stands beside every folder of AUTO's files the tests carry
LICENCE = "LICENSE-AUTO07P.txt"


def _digest(path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_no_file_outside_the_demo_folders_repeats_one_of_theirs():
    demo_files = {_digest(p): p for p in DEMOS.rglob("*") if p.is_file()}
    copies = [f"{p.relative_to(DATA)} = {demo_files[d].relative_to(DATA)}"
              for p in sorted(DATA.rglob("*"))
              if p.is_file() and DEMOS not in p.parents and p.name != LICENCE
              and (d := _digest(p)) in demo_files]
    assert not copies, copies


#: A plain s-file elsewhere in tests/data may be at most this large: the few small ones
#: (ab2p's and lrz2p's, 3.4 kB at most) are edited line by line by the tests of corrupt
#: s-files; gzipped, an s-file is about a quarter of its size.
PLAIN_S_MAX_BYTES = 16_000


def _s_files():
    return [p for p in sorted(DATA.rglob("s.*")) if p.is_file()]


def test_autos_s_files_are_stored_gzipped():
    """Every s-file of AUTO's outputs (autoref*/ folders) is stored as s.NAME.gz, and so is
    any other s-file of tests/data above PLAIN_S_MAX_BYTES: stored plain, the autoref
    s-files took 991 kB, gzipped 283 kB."""
    plain = [str(p.relative_to(DATA)) for p in _s_files() if p.suffix != ".gz"
             and (p.parent.name.startswith("autoref") or p.stat().st_size > PLAIN_S_MAX_BYTES)]
    assert not plain, f"s-files stored plain (gzip -9n them, git mv first): {plain}"


def test_gzipped_s_files_are_reproducible_bytes():
    """gzip -9n: no file name or time stamp in the header (a re-gzipped file is the same
    bytes, so it never shows as a change), and a whole stream."""
    for p in _s_files():
        if p.suffix == ".gz":
            data = p.read_bytes()
            assert data[4:8] == bytes(4) and not data[3] & 0x08, f"{p}: name or mtime stored"
            assert gzip.decompress(data).startswith(b" "), p
