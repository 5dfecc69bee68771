"""AUTO-07p's reference runs of its demo scripts ab, lrz, chu, plp and frc
(tests/data/auto_reference/periodic/<demo>: the constants files the scripts use and the
b-files AUTO wrote) and the Python transcriptions of their equations, with a scratch
folder to run a demo in."""
import shutil
from pathlib import Path

DATA = Path(__file__).parent / "data"
#: AUTO's constants and output of each demo
REF = DATA / "auto_reference" / "periodic"
#: each demo's equations as a Python user file
EQUATIONS = {"ab": DATA / "ab_demo" / "ab.py", "lrz": DATA / "lrz" / "lrz.py",
             "chu": DATA / "chu" / "chu.py", "plp": DATA / "plp" / "plp.py",
             "frc": DATA / "frc" / "frc.py"}


def demo_dir(tmp_path_factory, demo: str) -> Path:
    """A scratch folder with the demo's constants files (c.*) and its equations as
    DEMO.py."""
    d = tmp_path_factory.mktemp(demo)
    for f in REF.joinpath(demo).glob("c.*"):
        shutil.copy(f, d)
    shutil.copy(EQUATIONS[demo], d / f"{demo}.py")
    return d
