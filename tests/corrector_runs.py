"""One continuation run twice, with a compiled corrector and with the Python loop alone,
for the tests that hold the two to the same result (tests/test_corrector_algebraic.py,
tests/test_corrector_periodic.py)."""
from washer.cont import iterator
from washer.cont.newton import ConvergenceError


def fast_and_slow(monkeypatch, corrector, method: str, run, counts=None):
    """(run("fast"), run("slow"), used): `run` with the compiled corrector, then with the
    Python loop only (Continuation is offered no compiled corrector, as where none
    applies). used records every call of corrector.method in the first run for which
    counts(corrector_object) holds (default: every call): True where the compiled loop
    decided the step (a converged point, or a ConvergenceError raised from it), False
    where it handed the step to the Python loop. The second run never reaches it."""
    used = []
    real = getattr(corrector, method)

    def spy(self, *a, **k):
        counted = counts is None or counts(self)
        try:
            out = real(self, *a, **k)
        except ConvergenceError:
            if counted:
                used.append(True)                  # decided in C: no convergence
            raise
        if counted:
            used.append(out is not None)
        return out
    with monkeypatch.context() as m:
        m.setattr(corrector, method, spy)
        fast = run("fast")
    n_fast = len(used)
    with monkeypatch.context() as m:
        m.setattr(corrector, method, spy)
        m.setattr(iterator, "compiled_corrector", lambda *a, **k: None)
        slow = run("slow")
    assert len(used) == n_fast                     # the reference never went through C
    return fast, slow, used


#: Point types whose rows are not located by iterating on a test function.
UNLOCATED = ("", "EP", "MX", "RG")


def assert_rows_agree(fast, slow, location_tol: float, rtol: float = 1e-9):
    """The two runs' b-rows: the same points, to rtol up to the first located special
    point (both loops make the same corrections; only the eliminations' rounding
    differs), and from it on within twice the location's tolerance in each value. Each
    run stops a location within location_tol of the test function's zero in arclength,
    and a value moves by at most the arclength; the test function near its zero is a
    difference of O(1) terms whose rounding (which depends on the machine's BLAS and
    libm) moves the iterates by its error over its slope, and the branch goes on from
    the located point, so the later points are shifted along it as much."""
    import numpy as np
    assert [r.pt for r in fast.rows] == [r.pt for r in slow.rows]
    assert [r.ty for r in fast.rows] == [r.ty for r in slow.rows]
    located = False
    for f, s in zip(fast.rows, slow.rows):
        located = located or f.ty not in UNLOCATED
        if located:
            np.testing.assert_allclose(f.values, s.values, rtol=0, atol=2 * location_tol,
                                       err_msg=f"{f.ty} PT {f.pt}")
        else:
            np.testing.assert_allclose(f.values, s.values, rtol=rtol, atol=1e-12,
                                       err_msg=f"PT {f.pt}")


def assert_counts_agree(fast, slow, constants, what=("residuals", "jacobians",
                                                     "factorisations"), **ov):
    """The evaluations of the two runs: the same steps, and where a location iterates on
    a test function that rounds otherwise (see assert_rows_agree) other trials: up to
    ITMX + 1 of them a located point, each up to ITNW corrections and its own Jacobian
    and factorisation. Equal counts where nothing is located."""
    from washer.auto.constants_file import read_constants
    c = dict(read_constants(constants), **ov)
    located = sum(r.ty not in UNLOCATED for r in fast.rows)
    for w in what:
        assert abs(getattr(fast.counters, w) - getattr(slow.counters, w)) \
            <= located * (c["ITMX"] + 1) * (c["ITNW"] + 1), w
