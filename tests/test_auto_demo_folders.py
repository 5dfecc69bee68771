"""AUTO-07p's demo folders run unchanged with `python -m washer.auto NAME.auto`.

Each folder of tests/data/auto_demos (AUTO's own files as shipped, and AUTO's outputs
in autoref/) is copied to a temporary folder and its script run there; every special
point of every b-file AUTO wrote is compared with ours: type, label order, branch
number, the continuation parameter within AUTO's location tolerance and the period
(tests/auto_demo_compare.py says how). The demo table (docs/auto_compatibility.md, DEMO_TABLE)
lists the counts per demo and why any point differs.

Every demo must match exactly the count of AUTO's points the demo table states for it
(matched and AUTO's): a demo short of AUTO's is then an expected failure with the reason
for the rest, and fails outright if it matches fewer, or more, than the table says (the
table is the one record of the counts: a change in either direction is written there).

AUTO-07p's own Python parsers (parseB, parseS, parseBandS, parseD) then read every b-, s-
and d-file the demo's script wrote in that folder and must find what washer's readers
find there (tests/auto07p_parsers.py says what is compared); skipped with a message
where AUTO-07p is not installed.
"""
from pathlib import Path

import pytest

from auto07p_parsers import auto_python, check_folder
from auto_demo_compare import (DEMOS, VARIANT_OF, all_demos, auto_point_count, base_digests,
                               reference_files, run_demo)

#: Demos in the default run (a few seconds each, IPS 1 and 2, Fortran user files, dat=
#: starts, save/append/relabel): the others are marked slow (the whole set takes minutes).
FAST = {"frc", "lrz", "lor", "chu", "opt"}

#: The documentation file whose demo table holds every demo's counts (read by _demo_table).
DEMO_TABLE = Path(__file__).resolve().parents[1] / "docs" / "auto_compatibility.md"

#: Why a demo does not match all of AUTO's points (the demo table has the count and the
#: detail; the reason is said after that count).
EXPECTED_FAIL = {
    "pci": "AUTO's backward run 8 turns to NaN after its BP and ends with an EP of "
           "NaNs at NMX = 1000; ours goes on through finite solutions and ends MX",
    "abcb": "at run 2's tip (PAR(1) = 0.3462, where fold and branch point coincide) "
            "AUTO labels LP, ours BP (its fold location does not converge within ITMX: the "
            "fold test scatters by 8e-6 there); AUTO's BP two points on is not a branch "
            "point (shooting, tests/test_cycle_branch_point.py)",
    "tfc": "run 5's first BP of cycles is the tip of a fold (a zero of third "
           "order): ours there, AUTO's where its location stopped on a jump of its test; the "
           "BP locus ends at that tip, AUTO's end 0.01 before it; where the BP locus meets a "
           "fold AUTO's forward run labels BP a little earlier, ours LP",
    "kar": "AUTO's UZ at PAR(1) = 0 is written at -0.00845 (its location stalls); ours is "
           "at 2e-6 (tests/data/auto_demos/README.md)",
    "enz": "where the branch from the BP passes the other pitchfork (a fold and a "
           "branch point at one point, by symmetry) AUTO's fold location stops 13 "
           "tolerances short of it (tests/test_symmetric_pitchfork.py): AUTO labels LP and "
           "BP one step apart, we the one point once, BP",
    "tor": "a symmetry-breaking BP of cycles at PAR(1) = -0.787593 (b.1; shooting "
           "confirms it, tests/test_cycle_branch_point.py) whose location fails in AUTO "
           "(it only notes it) is labelled by us and takes one step, so AUTO's last LP "
           "(PT 124) is our EP at NMX",
    "rev": "the differences are AUTO's (tests/test_homoclinic_kinds.py: the first integral vanishes "
           "on every orbit): its UZ for PAR(1) = 1.7 after the LP is written at 1.698836, and "
           "its run 3 ends MX at -0.90993 where ours goes on to NMX",
    "mtnf77": "mtn.f's DFDP(1,1) lacks the term u1^2 / (2 K^2) of dF1/dK (sympy): AUTO's "
              "Newton, with JAC = 1, takes it and shrinks its steps, so its run 1 ends before "
              "psi_15 = 0 and its script stops at run 3 (no UZ1); ours differences the "
              "parameter derivatives of HomCont's orbits and runs as with mtn.f90",
    "fhhf77": "fhh's fhn.f leaves DFDP unset while the constants ask for JAC = 1: AUTO's run 2 "
              "(PAR(2) free) ends MX at its second point and its script stops at run 3; ours "
              "differences HomCont's parameter derivatives and runs the whole script as with fhn.f90",
    "kprf77": "the same as kpr's (AUTO's b-files with kpr.f are its b-files with kpr.f90)",
    "revf77": "the same as rev's (AUTO's b-files with rev.f are its b-files with rev.f90)",
    "kpr": "run 10, continued past a zero of PSI 9 (the equilibrium's leading "
           "stable eigenvalue crossing 0, where the truncated problem is ill-posed), ends "
           "earlier in ours (MX) than in AUTO (EP at NMX); run 8's UZ11, in run 7's ill-posed "
           "region, lies 2.07e-5 from AUTO's in PAR(1), tolerance 2e-5",
    "snh": "tb.auto's 8th run, away from the Hopf point, goes on where AUTO's steps "
           "collapse (its MX at nu1 = 1.2910) to an LP at nu1 = 1.417015, where the "
           "other tangency locus comes too; a point of ours past AUTO's MX is a fold of "
           "the connection's branch (docs/auto_compatibility.md); run 9 the other way reaches "
           "that meeting point too (LP at nu1 = 1.418), where AUTO's ends MX at 1.1917",
    "fhh": "AUTO's UZ for PAR(2) = 0 in run 5 is written at -7.53e-4 (its "
           "location stopped on step size off the zero); run 8 (IFIXED = [13]) ends MX in "
           "ours where PSI 2 = 0, AUTO's steps pass it to EP at NMX",
    "fnb": "run 6's UZ for Lin's gap PAR(22) = 0 (3-homoclinic orbits) lie "
           "0.002-1.7 apart in the pieces' time PAR(21), where the gap is exponentially "
           "small in it (which engine's are nearer the exact zeros is not found out yet)",
    "kdv": "AUTO's UZ for PAR(1) = 3 past run 3's Newton jump is at 2.72951, ours at "
           "2.72961 (the sheet the jump reached is ill-determined: the first trials land "
           "1e-4 apart); run 4 (ISTART = -3) cuts the reversible orbit at the other of its "
           "two equal peaks of |u - x0| (the adapted mesh decides), so run 5 has no UZ and "
           "r5('UZ1') is not found",
    "r3b": "V1b.auto's seven UZ lie 0.17 % later in PAR(11) than AUTO's: its start, V1's "
           "label 12, lies further along the vertical family than AUTO's (period 5.20876, "
           "AUTO 5.19993: the step after the BP at PT 10 goes further); V1b's start run ends MX at "
           "PT 740 (its steps fail down to DSMIN, 525 steps after its last UZ) where AUTO's "
           "ends EP at NMX = 800",
    "cir": "run 2's UZ7 and UZ8 lie 1e-4 from AUTO's in PAR(1), near PAR(2) = 0, where the "
           "equilibrium's stable pair crosses the imaginary axis: the size of the "
           "discretisation error there (tests/test_homoclinic.py)",
    "cirf77": "the same as cir's (AUTO's b-files with cir.f are its b-files with cir.f90)",
    "ppp": "AUTO's artefacts (tests/test_ppp_exact.py): its GH at PT 4 of the "
           "switched Hopf loci where the exact l1 is -0.662 (its test reads a Newton "
           "residual), and its BP of cycles 7.0e-4 before HB7, where the family ends "
           "(ours at HB7 to 1e-7)",
}

#: Demos whose script stops at a restart label it does not find (a point of AUTO's that
#: ours does not label before it, EXPECTED_FAIL says why; san's AUTO stops there too: its
#: run 11 has no UZ for run 12 to start from, with san.f as with san.f90, and r3b's V1a.auto, whose last run asks for
#: label 13 of a run that has 9): what the log says at that stop.
STOPS_AT_LABEL = {"kdv": "Label UZ1 not found",
                  "san": "Label UZ1 not found", "sanf77": "Label UZ1 not found",
                  "r3b": "Restart label IRS=13 not found"}

#: Demos whose count moves with rounding that depends on the machine (its BLAS kernels and
#: libm): the other count measured, and why. Measured on an AVX-512 AMD EPYC against the
#: demo table's counts (made on another machine).
ROUNDING_DEPENDENT = {
    "cirf77": (10, "as cir's"),
    "cir": (10, "run 2's UZ6 lies at the location tolerance from AUTO's: matched on this "
                "machine, not on the one of the first count (tests/test_homoclinic.py)"),
    "ppp": (46, "run 2's cycles from HB2 shrink onto HB7, where the family ends on the "
                "equilibria (zero amplitude, u3 at 1e-32: the BP there is located to the closed "
                "form, tests/test_ppp_exact.py, whatever the rounding); the step after that BP "
                "starts from a cycle of zero amplitude, where the collocation system is "
                "singular, and either turns back along the family to EP at NMX (AUTO's, and "
                "ours with OpenBLAS's SkylakeX kernels) or fails to MX (ours with its Haswell "
                "kernels, where HB2 and the BP, 6e-9 in PAR(1) apart from the SkylakeX run's, "
                "move with the rounding of the equilibria's points after their BP)"),
    "lcbp": (7, "run 3's backward run (the generic BP locus, ISW = 3) ends at PAR(1) = 0, "
                "its UZSTOP, where the circles shrink to the Hopf point: its BP test is at "
                "its noise floor there (-3.6e-51 to +2.3e-58 over the last step here, "
                "AUTO's 2.2e-61 to -5.8e-62) and changes sign in the UZ's step or the one "
                "before as rounding falls; in the UZ's step the point is typed UZ here, BP "
                "in AUTO (whose BP check, after the UZ's, retypes the step's end)"),
}


def _params():
    out = []
    for d in all_demos():
        marks = []
        if d not in FAST:
            marks.append(pytest.mark.slow)
        out.append(pytest.param(d, marks=marks, id=d))
    return out


#: Each demo's run, once per test session: (its folder, compare's Result).
_RUNS: dict = {}


def _run(demo, tmp_path_factory):
    """The demo run in a fresh folder (once: both tests of a demo read the same run)."""
    if demo not in _RUNS:
        work = tmp_path_factory.mktemp(demo)
        # A demo expected to fall short gets 15 minutes, five times what the longest of
        # them (pci, about 3 minutes on one core) takes: a run that goes wrong may not end
        # (with NMX = 0 nothing but a stop condition ends it).
        r = run_demo(demo, work, timeout=900 if demo in EXPECTED_FAIL else 1800)
        _RUNS[demo] = (work / demo, r)
    return _RUNS[demo]


@pytest.mark.parametrize("demo", _params())
def test_demo_folder_matches_auto(demo, tmp_path_factory):
    matched, auto_points = _demo_table()[0][demo]
    _, r = _run(demo, tmp_path_factory)
    if demo in ROUNDING_DEPENDENT and r.matched == ROUNDING_DEPENDENT[demo][0] != matched:
        pytest.xfail(f"{r.matched} of {r.auto_points} here, {matched} in the demo table: "
                     f"{ROUNDING_DEPENDENT[demo][1]}")
    assert (r.matched, r.auto_points) == (matched, auto_points), (
        f"{demo}: {r.matched} of AUTO's {r.auto_points} special points matched, the demo "
        f"table says {matched} / {auto_points}:\n" + "\n".join(r.problems[:20])
        + f"\n{r.log[-3000:]}")
    if demo in STOPS_AT_LABEL:
        assert r.returncode != 0 and STOPS_AT_LABEL[demo] in r.log, \
            f"{demo}: the script did not stop where the demo table says:\n{r.log[-3000:]}"
    else:
        assert r.returncode == 0, f"{demo}: the script failed:\n{r.log[-3000:]}"
    if demo in EXPECTED_FAIL:
        # the counts are the demo table's: what is left is the known difference
        pytest.xfail(f"{matched} of {auto_points}: {EXPECTED_FAIL[demo]}")


def _parser_params():
    return [pytest.param(d, marks=[] if d in FAST else [pytest.mark.slow], id=d)
            for d in all_demos()]


@pytest.mark.parametrize("demo", _parser_params())
def test_autos_parsers_read_the_demos_files(demo, tmp_path_factory):
    """AUTO-07p's parseB, parseS, parseBandS and parseD read every b-, s- and d-file the
    demo's script wrote (whether or not its points all match AUTO's) with the branches,
    labels, type codes, record headers, record sizes and PAR values washer's own readers
    find (tests/auto07p_parsers.py)."""
    if auto_python() is None:
        pytest.skip("AUTO-07p's Python package is not installed: the files washer wrote "
                    "are not checked with AUTO's parsers")
    folder, _ = _run(demo, tmp_path_factory)
    problems = check_folder(folder, DEMOS / demo)
    assert not problems, f"{demo}:\n" + "\n".join(problems[:20])


#: HomCont's demo folders (IPS = 9 runs), whose b-file headers carry HomCont's constants.
HOMCONT = ("fhh", "fnb", "kdv", "kpr", "mtn", "rev", "she", "sib", "snh")
#: Header lines of HomCont's runs that differ from AUTO's for a known reason, by (demo,
#: b-file): the restart label where an earlier run's labels differ (the demo table).
HEADER_DIFFERS = {("fnb", "b.7"): "IRS ="}


def _header_blocks(path):
    """The header blocks (lines starting '   0 ') of a b-file, in order."""
    import gzip
    opener = gzip.open if path.suffix == ".gz" else open
    blocks, cur = [], []
    with opener(path, "rt") as f:
        for line in f:
            if line.startswith("   0 "):
                cur.append(line.rstrip("\n"))
            elif cur:
                blocks.append(cur)
                cur = []
    return blocks + ([cur] if cur else [])


@pytest.mark.slow
@pytest.mark.parametrize("demo", [d for d in HOMCONT if d in all_demos()])
def test_homcont_b_file_headers_are_autos(demo, tmp_path_factory):
    """Every header block washer writes in a HomCont demo's b-files is AUTO's byte for
    byte (NPAR as AUTO's: the constants', the restart's without its internal parameters,
    20 + the largest IPSI, NPARI after them for ISTART < 0; HomCont's constants line),
    for every block both engines wrote."""
    from auto_demo_compare import reference_files
    folder, _ = _run(demo, tmp_path_factory)
    problems = []
    for ref in reference_files(demo):
        if not ref.name.startswith("b."):
            continue
        name = ref.name.removesuffix(".gz")
        ours = folder / ref.relative_to(DEMOS / demo / "autoref").with_name(name)
        if not ours.exists():
            continue
        skip = HEADER_DIFFERS.get((demo, name))
        for i, (a, w) in enumerate(zip(_header_blocks(ref), _header_blocks(ours))):
            if skip:
                a, w = ([ln for ln in x if skip not in ln] for x in (a, w))
            if a != w:
                problems.append(f"{name} block {i}: AUTO\n" + "\n".join(a)
                                + "\nours\n" + "\n".join(w))
    assert not problems, f"{demo}:\n" + "\n".join(problems[:3])


def _demo_table():
    """The per-demo table of DEMO_TABLE: {demo: (matched, AUTO's)} and the total row's pair."""
    import re
    text = DEMO_TABLE.read_text()
    rows, total = {}, None
    for line in text.splitlines():
        m = re.match(r"\| (\*\*total\*\*|[a-z0-9]+) \|[^|]*\| (?:\*\*)?(\d+) / (\d+)", line)
        if m and m[1] == "**total**":
            total = (int(m[2]), int(m[3]))
        elif m:
            rows[m[1]] = (int(m[2]), int(m[3]))
    return rows, total


def test_demo_table_agrees_with_folders_and_expected_failures():
    """The table has a row per demo folder, each row's count of AUTO's points is that of
    the folder's AUTO files, its total is the sum of its rows, and the demos it shows
    short of AUTO's count are exactly the expected failures."""
    rows, total = _demo_table()
    assert sorted(rows) == all_demos()
    assert {d: a for d, (_, a) in rows.items()} == {d: auto_point_count(d) for d in rows}
    assert all(a > 0 for _, a in rows.values())
    assert total == (sum(m for m, _ in rows.values()), sum(a for _, a in rows.values()))
    assert sorted(d for d, (m, a) in rows.items() if m < a) == sorted(EXPECTED_FAIL)


def test_autos_output_with_a_variants_user_file_is_its_bases_where_the_table_says():
    """Where the demo table says AUTO-07p's b-files with a variant's user file (AUTO's
    Fortran-77 NAME.f) are its b-files with the base's NAME.f90 byte for byte, the
    variant's autoref/ keeps their SHA-256 (SAME_AS_BASE) instead of copies, and the
    base folder's b-files have those digests: each of them, and no other."""
    import gzip
    import hashlib
    import re
    said = set()
    for line in DEMO_TABLE.read_text().splitlines():
        m = re.match(r"\| ([a-z0-9]+) \|", line)
        if m and re.search(r"AUTO's (?:\w+ )?b-files? with it (?:are|is) its b-files? with "
                           r"`\w+\.f90`, byte for byte", line):
            said.add(m[1])
    stored = {d for d in VARIANT_OF if base_digests(d)}
    assert said == stored and len(stored) == 10
    for demo in sorted(stored):
        digests = base_digests(demo)
        files = reference_files(demo)
        assert all(f.parent == DEMOS / VARIANT_OF[demo] / "autoref" for f in files)
        got = {f.name.removesuffix(".gz"): hashlib.sha256(
            gzip.decompress(f.read_bytes()) if f.suffix == ".gz" else f.read_bytes()).hexdigest()
            for f in files}
        assert got == digests, demo
        assert not [p.name for p in (DEMOS / demo / "autoref").glob("b.*")], demo


def test_demo_table_by_kind_of_run_sums_its_rows():
    """The sentence under the demo table that splits its total by kind of run (IPS 0, 1, 2
    only; any IPS 9; the rest) gives the sums of the rows of each kind, and the three add up
    to the total."""
    import re
    text = DEMO_TABLE.read_text()
    sums = {"012": [0, 0], "9": [0, 0], "other": [0, 0]}
    for line in text.splitlines():
        m = re.match(r"\| ([a-z0-9]+) \| ([-0-9 ]+) \| (\d+) / (\d+)", line)
        if not m:
            continue
        ips = set(m[2].split())
        kind = "012" if ips <= {"0", "1", "2"} else "9" if "9" in ips else "other"
        sums[kind][0] += int(m[3])
        sums[kind][1] += int(m[4])
    said = re.search(r"\(IPS 0, 1, 2 only\) (\d+) / (\d+) \(([\d.]+) %\).*?\(IPS 9\)\s+"
                     r"(\d+) / (\d+) \(([\d.]+) %\).*?IPS 0-2\) (\d+) / (\d+) \(([\d.]+) %\)",
                     text, re.S)
    assert said, "the split by kind of run is not under the demo table"
    g = said.groups()
    for k, kind in enumerate(("012", "9", "other")):
        m, a = sums[kind]
        assert (int(g[3 * k]), int(g[3 * k + 1])) == (m, a), kind
        assert float(g[3 * k + 2]) == round(100 * m / a, 1), kind
    rows, total = _demo_table()
    assert tuple(map(sum, zip(*sums.values()))) == total
