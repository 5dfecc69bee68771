"""One continuation run twice, with a compiled corrector and with the Python loop alone,
for the tests that hold the two to the same result (tests/test_compiled_newton.py,
tests/test_compiled_po.py)."""
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
