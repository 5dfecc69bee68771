"""AUTO-07p's reference runs: of its demo scripts ab, lrz, chu, plp and frc (their demo
folders, tests/data/auto_demos/<demo>: the constants files the scripts use, the b-files
AUTO wrote in autoref/) and the Python transcriptions of their equations, with a scratch
folder to run a demo in; whole records of AUTO's s-files of those scripts
(tests/data/auto_reference/records); and the locus runs of the scripts ab2p.auto and
lrz2p.auto (tests/data/auto_reference/ab2p, lrz2p), which the tests and
benchmarks/bench_vs_auto.py repeat."""
import shutil
from pathlib import Path

from demo_files import DATA, DEMOS, autoref

#: records of AUTO's s-files of the demos' scripts (records/README.md)
RECORDS = DATA / "auto_reference" / "records"
#: each demo's equations as a Python user file
EQUATIONS = {"ab": DATA / "ab_demo" / "ab.py", "lrz": DATA / "lrz" / "lrz.py",
             "chu": DATA / "chu" / "chu.py", "plp": DATA / "plp" / "plp.py",
             "frc": DATA / "frc" / "frc.py"}

#: ab2p.auto's fold and Hopf curves from eq('LP1') and eq('HB1') in (PAR(1), PAR(2)): its
#: overrides of c.ab (the forward runs; lp_bwd and hb_bwd add DS = -0.01)
AB2P_LOCUS = dict(ICP=[1, 2], ISW=2, NMX=400, DSMAX=0.05,
                  UZSTOP={1: [0.0, 0.3], 2: [5.0, 30.0]})
#: lrz2p.auto's Hopf curve from eq('HB1') in (rho, sigma): its overrides of c.lrz (hb_fwd;
#: hb_bwd has DS = -0.1)
LRZ2P_LOCUS = dict(ICP=["rho", "sigma"], ISW=2, NMX=300, DS=0.1, DSMAX=2.0,
                   UZR={"sigma": [5.0, 10.0, 20.0]},
                   UZSTOP={"sigma": [4.0, 40.0], "rho": 200.0})


def demo_dir(tmp_path_factory, demo: str) -> Path:
    """A scratch folder with the demo's constants files (c.*) and its equations as
    DEMO.py."""
    d = tmp_path_factory.mktemp(demo)
    for f in DEMOS.joinpath(demo).glob("c.*"):
        shutil.copy(f, d)
    shutil.copy(EQUATIONS[demo], d / f"{demo}.py")
    return d
