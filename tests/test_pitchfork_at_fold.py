"""A branch that passes a symmetric pitchfork at its fold: the fold and the branch point
are one point, labelled once, on the branch, against the closed form (sympy), and typed
as AUTO-07p's rule types it.

u = (u1, u2), m = (u1 + u2) / 2, a = (u1 - u2) / 2, p = PAR(1), k = PAR(2):
    F1 = m - p,  F2 = a (k m - a^2),  f = (F1 + F2, F1 - F2),
symmetric under u1 <-> u2 (a -> -a). The symmetric branch is a = 0, m = p; the
asymmetric one m = p = a^2 / k crosses it at the origin, where, p being even in a along
it, p is extremal: a fold (the tangent's p-component vanishes) and a branch point
(det f_u = 0 with the two branches crossing) at one point. Followed from a = -1 through
the origin, the step over it sees both tests change sign.

AUTO's rule (ae.f90's CNRLAE and LCSPAE; bvp.f90's CNRLBV and LCSPBV the same): after a
step each test is visited once, in its order (the fold, ITEST 1, before the branch point,
ITEST 2), at the point the tests before it left, the step's end or a located point. The
fold is located first; the branch-point test is then taken at the located fold: where
its secant zero from there lies within the location tolerance, its Q1 is set to 0 (no
sign change, no second location: first come, first served) and the point is the fold's,
LP; where it lies beyond and the test has changed sign, the branch point is located
between the previous point and the fold, and the point is its, BP (the fold test,
evaluated afresh there, counts again on the next step if its zero lies beyond). Where
the fold's location fails ('Possible special point': its trial steps next to the
singular point do not converge above DSMIN), the branch point is located from the step's
end: BP. Both locations measure their trials by the distance from the previous point
(the sphere arclength), whether a trial is a step from the previous point or from the
last trial.
"""
import tempfile
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from washer.cont.problem import Problem
from washer.run import run

EPSS, DSMAX = 1e-5, 0.25
EPSU = 1e-7


def func(u, par):
    m, a = (u[0] + u[1]) / 2, (u[0] - u[1]) / 2
    F1, F2 = m - par[0], a * (par[1] * m - a * a)
    return np.array([F1 + F2, F1 - F2])


def closed_form(k: float):
    """The crossing of the asymmetric branch with the symmetric one (sympy): its (u1, u2,
    p), checked to be a fold of the asymmetric branch and a singular f_u."""
    a = sp.Symbol("a", real=True)
    u1_, u2_, p_ = sp.symbols("u1 u2 p", real=True)
    m_, a_ = (u1_ + u2_) / 2, (u1_ - u2_) / 2
    F1, F2 = m_ - p_, a_ * (k * m_ - a_**2)
    f = sp.Matrix([F1 + F2, F1 - F2])
    branch = {u1_: a**2 / k + a, u2_: a**2 / k - a, p_: a**2 / k}
    assert sp.simplify(f.subs(branch)) == sp.zeros(2, 1)
    (a0,) = sp.solve(sp.diff(branch[p_], a), a)          # the fold: dp/da = 0
    at = {s: e.subs(a, a0) for s, e in branch.items()}
    assert sp.simplify(f.jacobian([u1_, u2_]).subs(at).det()) == 0
    return np.array([float(at[u1_]), float(at[u2_]), float(at[p_])])


def stpnt_at(a0: float, k: float):
    def stpnt(u, par):
        par[0], par[1] = a0 * a0 / k, k
        u[0], u[1] = a0 * a0 / k + a0, a0 * a0 / k - a0
    return stpnt


#: AUTO-07p's labels of the crossing over the 14 pairs of pf.auto (its b-files in
#: tests/data/pitchfork_at_fold, `test_autos_labels_are_the_table`), each AUTO's rule
#: (module docstring) on its own locations, as its d-files say (pf.auto run again with
#: IID = 4, nothing else changed, for the trials): BP alone where its fold location failed
#: ('NOTE:Possible special point': a trial step next to the singular point not converging
#: above DSMIN = 0.01) and the branch point was located from the step's end, at (1.0, 0.05),
#: (1.0, 0.0625), (1.0, 0.1), (2.0, 0.07), (0.5, 0.03); BP at (1.5, 0.17), where the fold
#: converged and the branch point was then located 4.6e-5 short of it (the last located
#: types the point); LP alone where the fold converged at the crossing and the branch
#: point was absorbed, at (3.0, 0.13), (5.0, 0.11); LP, then BP on the next step, where
#: the fold's location stopped short of the crossing (its Muller correction below the
#: tolerance while the point lay 14 (1.0, 0.13) and 2.3 (3.0, 0.2) tolerances off it:
#: `OFF`) with the branch-point test not yet changed there; nothing where both locations
#: failed (1.0, 0.2) or, at k = 0.3, as ours (NOT_YET).
AUTOS_LABELS = {
    **dict.fromkeys([(1.0, 0.05), (1.0, 0.0625), (1.0, 0.1), (2.0, 0.07), (1.5, 0.17),
                     (0.5, 0.03)], ["BP"]),
    **dict.fromkeys([(1.0, 0.13), (3.0, 0.2)], ["LP", "BP"]),
    **dict.fromkeys([(3.0, 0.13), (5.0, 0.11)], ["LP"]),
    **dict.fromkeys([(1.0, 0.2), (0.3, 0.05), (0.3, 0.1), (0.3, 0.0625)], []),
}
#: Steps that do not give one point at the crossing, and why (kept to be seen when they
#: change). AUTO-07p's own runs give no one point either at (1.0, 0.13), (3.0, 0.2) and
#: k = 0.3 (`test_autos_runs_of_the_same_equations`); at (1.5, 0.17) its BP is at the
#: crossing, and ours is wrong there.
NOT_YET = {
    (1.0, 0.13): "a step lands 1.2e-4 from the crossing: the fold's location stops 14 "
                 "tolerances early on the creeping test (AUTO's rule, as AUTO at enz's other "
                 "pitchfork), and the BP, whose test has not changed sign there, is located "
                 "on the next step: LP, BP at PTs 21, 22, as AUTO-07p's",
    (0.3, 0.1): "the step from PT 28 crosses the pitchfork and both locations fail (their "
                "trial steps do not converge above DSMIN = 0.01, 'Possible special point'): "
                "nothing labelled, as in AUTO-07p's run, whose 60 rows ours are",
    (0.3, 0.0625): "as (0.3, 0.1), from PT 29: nothing labelled, AUTO-07p's 60 rows",
    (1.5, 0.17): "the fold's location fails, and the BP is located at PAR(1) = u1 = u2 = "
                 "6.8e-4, on the symmetric branch 28 location tolerances from the crossing "
                 "(AUTO-07p's BP at PT 12: 1.6e-6 from it)",
    (0.3, 0.05): "the step to PT 28, predicted along the secant of the last step (AUTO's "
                 "SOLVAE), converges onto the symmetric branch before the crossing and the "
                 "next ends MX: AUTO-07p's own run of these equations (Fortran, the same "
                 "constants) does the same, its PT 26-29 ours to their 11 digits",
}


def _run(k: float, ds: float, notes: list | None = None):
    """Our run of the equations from the start at PAR(1) = -1 with the constants of
    pf.auto (the ones AUTO-07p's b-files here were made with), DS = -ds. notes: a list
    that receives the d-file's NOTE lines (the files are then written, in a temporary
    folder)."""
    with tempfile.TemporaryDirectory() as d:
        c = Path(d) / "c.pf"
        c.write_text(f"NDIM = 2, IPS = 1, IRS = 0, ICP = [1], ISP = 1, ILP = 1, NMX = 60, "
                     f"DS = {-ds}, DSMIN = 0.01, DSMAX = {DSMAX}, EPSS = {EPSS}, "
                     f"EPSL = 1e-7, EPSU = {EPSU}, ITMX = 8, RL0 = -5, RL1 = 5\n")
        r = run(c, verbose=False, problem=Problem(2, func, stpnt_at(-1.0, k), name="pf"),
                files=notes is not None)
        if notes is not None:
            notes += [line for line in (Path(d) / "d.pf").read_text().splitlines()
                      if "NOTE:" in line]
        return r

#: The 14 (k, DS) pairs of pf.auto.
PAIRS = [(1.0, 0.05), (1.0, 0.0625), (1.0, 0.1), (1.0, 0.2), (1.0, 0.13), (0.3, 0.05),
         (0.3, 0.1), (0.3, 0.0625), (3.0, 0.13), (3.0, 0.2), (2.0, 0.07), (1.5, 0.17),
         (0.5, 0.03), (5.0, 0.11)]


def _location_tolerance(ds: float) -> float:
    """Twice the location tolerance in arclength (AUTO's EPSS (1 + sqrt|DS DSMAX|)):
    along the asymmetric branch at the crossing the unknowns move at most at rate 1 per
    unit of arclength (the tangent is unit), and a location converges to within it."""
    return 2 * EPSS * (1 + np.sqrt(ds * DSMAX))


@pytest.mark.parametrize("k, ds", [
    pytest.param(k, ds, marks=pytest.mark.xfail(reason=NOT_YET[(k, ds)], strict=True))
    if (k, ds) in NOT_YET else (k, ds) for k, ds in PAIRS])
def test_the_pitchfork_at_the_fold_is_one_point_typed_by_autos_rule(k, ds):
    """One labelled point, at the closed-form crossing to within the location tolerance,
    typed by AUTO's rule: LP where the fold was located (the branch point, vanishing
    there, absorbed), BP where the fold's location failed (its 'Possible special point'
    note at that point) and the branch point was located."""
    P = closed_form(k)
    notes: list = []
    r = _run(k, ds, notes)
    labelled = [s for s in r.specials if s.ty != "EP"]
    assert len(labelled) == 1, [s.ty for s in labelled]
    (sp,) = labelled
    fold_failed = any(line.split()[:2] == ["1", str(sp.pt - 1)]
                      and "Possible special point (LP" in line for line in notes)
    assert sp.ty == ("BP" if fold_failed else "LP"), notes
    got = np.r_[sp.u, sp.par[0]]
    assert np.abs(got - P).max() < _location_tolerance(ds), (got, P)


AUTO_RUNS = Path(__file__).parent / "data" / "pitchfork_at_fold"


def _autos_rows(k: float, ds: float) -> dict:
    from washer.auto.files import read_b
    return {r.pt: r for branch in read_b(AUTO_RUNS / f"b.k{k}_ds{ds}") for r in branch
            if r.br == 1}


@pytest.mark.parametrize("k, ds", [(0.3, 0.1), (0.3, 0.0625), (1.0, 0.13)])
def test_autos_runs_of_the_same_equations(k, ds):
    """AUTO-07p on these equations (pf.f90) with the same constants: at (0.3, 0.1) and
    (0.3, 0.0625) both engines cross the pitchfork in one step, fail both locations and
    label nothing, on the same 60 rows (each engine's row is within its last Newton
    correction, below EPSU (1 + |u|), of the same solution of the same step); at
    (1.0, 0.13) both label LP at PT 21 and BP at PT 22 and nothing else, ours the BP
    within the location tolerance of the closed form (NOT_YET)."""
    ref = _autos_rows(k, ds)
    r = _run(k, ds)
    ours = {abs(row.pt): row for row in r.rows if abs(row.br) == 1}
    autos_labels = [(pt, row.ty) for pt, row in sorted(ref.items()) if row.ty not in (0, 9)]
    our_labels = [(pt, row.ty) for pt, row in sorted(ours.items()) if row.ty not in ("", "EP")]
    if k == 0.3:
        assert autos_labels == [] and our_labels == []
        assert sorted(ours) == sorted(ref)
        for pt, row in ref.items():
            want = np.array(row.values[:4])
            tol = 2 * EPSU * (1 + np.abs(want).max())      # both engines' corrections
            assert np.abs(np.array(ours[pt].values[:4]) - want).max() < tol, pt
    else:
        assert autos_labels == [(21, 2), (22, 1)]          # AUTO's codes: LP 2, BP 1
        assert our_labels == [(21, "LP"), (22, "BP")]
        bp = ours[22]
        assert abs(bp.values[0] - closed_form(k)[2]) < _location_tolerance(ds)


def _labels(rows: dict) -> list[tuple[int, str]]:
    """(PT, type name) of the labelled rows of branch 1 but the run's ends (EP, MX)."""
    from washer.cont.codes import type_name
    named = [(pt, r.ty if isinstance(r.ty, str) else type_name(r.ty))
             for pt, r in sorted(rows.items())]
    return [(pt, ty) for pt, ty in named if ty not in ("", "RG", "EP", "MX")]


def test_autos_labels_are_the_table():
    """AUTOS_LABELS, the table this module documents, is what AUTO-07p's b-files say."""
    assert sorted(AUTOS_LABELS) == sorted(PAIRS)
    for pair in PAIRS:
        assert [ty for _, ty in _labels(_autos_rows(*pair))] == AUTOS_LABELS[pair], pair


#: The pairs where AUTO-07p labels the crossing and ours too, but no label is at the same
#: PT with the same type: AUTO's BP at the PT of our LP, where AUTO's fold location failed
#: and ours converged (AUTOS_LABELS).
LABELLED_APART = {(1.0, 0.05), (1.0, 0.0625), (1.0, 0.1), (2.0, 0.07)}

#: Where both engines label the same type at the same PT but their rows differ by more
#: than two location tolerances, the closed form says which is off: the engine named
#: here is farther than two location tolerances from the crossing, the other within them.
OFF = {
    (3.0, 0.2, "LP"): "AUTO",        # AUTO-07p's LP at PT 8: 2.8e-5 from the crossing
    (1.5, 0.17, "BP"): "ours",       # NOT_YET
    (1.0, 0.13, "LP"): "both",       # NOT_YET: ours 1.8e-4, AUTO-07p's 4.7e-5
}


@pytest.mark.parametrize("k, ds", PAIRS)
def test_rows_where_both_engines_label(k, ds):
    """Every point both engines label with one type at one PT: the two rows (PAR(1),
    L2-NORM, U(1), U(2)) agree within twice the location tolerance (each located to its
    own), or the closed form (the crossing at the origin) names the one that is off
    (OFF)."""
    ref = _autos_rows(k, ds)
    ours = {abs(row.pt): row for row in _run(k, ds).rows if abs(row.br) == 1}
    crossing = np.r_[closed_form(k)[2], 0.0, closed_form(k)[:2]]   # PAR(1), |u|, u
    tol = _location_tolerance(ds)
    both = sorted(set(_labels(ref)) & set(_labels(ours)))
    assert bool(both) == (bool(_labels(ref)) and (k, ds) not in LABELLED_APART)
    for pt, ty in both:
        a, o = np.array(ref[pt].values[:4]), np.array(ours[pt].values[:4])
        off = {name for name, row in (("AUTO", a), ("ours", o))
               if np.abs(row - crossing).max() >= tol}
        if np.abs(a - o).max() < tol and not off:
            assert (k, ds, ty) not in OFF
            continue
        assert (k, ds, ty) in OFF, (pt, ty, a, o)
        assert off == ({"AUTO", "ours"} if OFF[(k, ds, ty)] == "both" else {OFF[(k, ds, ty)]})
