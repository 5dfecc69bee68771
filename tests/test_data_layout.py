"""tests/data keeps one copy of AUTO-07p's files: a demo's files and AUTO's outputs of it
are in its folder tests/data/auto_demos/NAME (tests/demo_files.py), which every test reads,
and nowhere else."""
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
