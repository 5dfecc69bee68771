"""AUTO-07p's demo folders, the one copy the tests read: tests/data/auto_demos/NAME holds
AUTO's files of demo NAME (constants c.*, script NAME.auto, user file NAME.f90, data) and
in NAME/autoref/ the files AUTO wrote running them (tests/data/auto_demos/README.md)."""
import shutil
from pathlib import Path

DATA = Path(__file__).parent / "data"
#: AUTO-07p's demo folders
DEMOS = DATA / "auto_demos"


def autoref(name: str) -> Path:
    """The folder of AUTO's own output files of demo NAME (its s-files stored as s.X.gz,
    which washer's readers take for `autoref(NAME) / "s.X"`)."""
    return DEMOS / name / "autoref"


def copy_demo(name: str, dest: Path, *extra: Path) -> Path:
    """`dest` with demo NAME's files (not its autoref/), then each file of the folders in
    `extra` (a test's own files, such as a Python transcription NAME.py of the equations,
    which wins over AUTO's NAME.f90 beside it: washer.cont.user_problem.user_files). Returns
    dest."""
    for folder in (DEMOS / name, *extra):
        for f in folder.iterdir():
            if f.is_file():
                shutil.copy(f, dest)
    return dest
