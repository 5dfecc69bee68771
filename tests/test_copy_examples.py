"""--copy-examples gives a folder that works on its own: every shipped constants file,
the sweep specs and AUTO's ab demo, with comments whose commands name files that are
there; the ab demo runs from it."""
import re
from pathlib import Path

from washer.auto.constants_file import shipped_constants, shipped_examples
from washer.run import main, run

ROOT = Path(__file__).resolve().parents[1]


def test_examples_are_the_sweep_specs_and_the_ab_demo():
    names = set(shipped_examples())
    assert {"sweep_small.toml", "sweep_design.toml", "ab.py", "c.ab"} <= names


def test_copied_folder_runs_and_its_comments_name_files_that_exist(tmp_path, capsys):
    dest = tmp_path / "ex"
    assert main(["--copy-examples", str(dest)]) == 0
    files = {p.name for p in dest.iterdir()}
    assert set(shipped_constants()) | set(shipped_examples()) == files
    # Every command in a comment ("python -m washer.run c.X", "washer.sweep X.toml")
    # names a file of this folder.
    pattern = re.compile(r"python -m washer\.(?:run|sweep)\s+([^\s,;]+)")
    named = []
    for p in dest.iterdir():
        for line in p.read_text().splitlines():
            if line.lstrip().startswith("#"):
                for target in pattern.findall(line):
                    named.append((p.name, target))
    assert len(named) >= len(shipped_constants())        # each constants file says how
    missing = [(f, t) for f, t in named if not (dest / t).is_file()]
    assert not missing, missing
    # Paths to the source checkout (docs/, tests/, examples/, auto_constants/) are gone.
    for p in dest.iterdir():
        text = p.read_text()
        for prefix in ("docs/", "tests/", "examples/", "auto_constants/"):
            assert prefix not in text, (p.name, prefix)
    # AUTO's ab demo runs where it was copied; its Hopf point against the exact one
    # (tests/ab_exact.py: f = 0, trace f_u = 0 at 30 digits), to the location tolerance.
    from ab_exact import hb_p1
    hb = run(dest / "c.ab", verbose=False)("HB1")
    assert abs(hb.par[0] - hb_p1(17.0, (hb.U[0], hb.U[1], hb.par[0]))) < 1e-5
    from washer.sweep import load_spec
    assert load_spec(dest / "sweep_small.toml").studies
