"""AUTO-07p's demo folders run unchanged with `python -m washer.auto NAME.auto`.

Each folder of tests/data/auto_demos (AUTO's own files as shipped, and AUTO's outputs
in autoref/) is copied to a temporary folder and its script run there; every special
point of every b-file AUTO wrote is compared with ours: type, label order, branch
number, the continuation parameter within AUTO's location tolerance and the period
(tests/auto_demo_compare.py says how). README's table lists the counts per demo and
why any point differs.

Demos whose runs need what the engine does not do yet are expected to fail with the
reason (strict=False: they report XPASS once the engine does them).
"""
import pytest

from auto_demo_compare import all_demos, run_demo

#: Demos in the default run (a few seconds each, IPS 1 and 2, Fortran user files, dat=
#: starts, save/append/relabel): the others are marked slow (the whole set takes minutes).
FAST = {"frc", "lrz", "lor", "chu"}

BVP = "boundary-value problems (IPS = 4) are not in the engine yet"
MAPS = "maps (IPS = -1) are not in the engine yet"
#: Why a demo does not match AUTO yet.
EXPECTED_FAIL = {
    "abcb": "ISW = 3 (branch-point loci of generic BVPs) is not implemented; the cycle run "
            "stops with no convergence before AUTO's fold of cycles",
    "apbp": "branch-point continuation (ISW = 2 at a BP, ISW = 3) is not implemented",
    "lcbp": "branch-point continuation of cycles (ISW = 2, 3 at a BP) is not implemented",
    "tfc": "branch-point continuation of cycles (ISW = 2 at a BP) is not implemented",
    "ops": "optimisation (IPS = 15) is not supported",
    "ivp": "time integration (IPS = -2) is not in the engine yet",
    "dd2": MAPS, "log": MAPS,
    "pcl": BVP, "ph1": BVP, "bvp": BVP, "ext": BVP, "ezp": BVP, "fnc": BVP, "fsh": BVP,
    "int": BVP, "lin": BVP, "man": BVP, "nep": BVP, "non": BVP, "obv": BVP, "pvl": BVP,
    "spb": BVP, "sspg": BVP, "stw": BVP, "tim": BVP, "um2": BVP, "um3": BVP,
    "r3b": "the restarts of the periodic orbits of r3b differ from AUTO's",
}


def _params():
    out = []
    for d in all_demos():
        marks = []
        if d not in FAST:
            marks.append(pytest.mark.slow)
        if d in EXPECTED_FAIL:
            marks.append(pytest.mark.xfail(reason=EXPECTED_FAIL[d], strict=False))
        out.append(pytest.param(d, marks=marks, id=d))
    return out


@pytest.mark.parametrize("demo", _params())
def test_demo_folder_matches_auto(demo, tmp_path):
    r = run_demo(demo, tmp_path)
    assert r.returncode == 0, f"{demo}: the script failed:\n{r.log[-3000:]}"
    assert r.auto_points > 0
    assert r.matched == r.auto_points, (f"{demo}: {r.matched} of AUTO's {r.auto_points} "
                                        "special points matched:\n" + "\n".join(r.problems[:20]))
