"""`python -m washer.paper` when runs fail or are interrupted:
non-zero exit naming the run, no verdicts on unfinished curves, Ctrl-C stops the job.
The AUTO runs are replaced by stand-ins here (the real ones are test_paper's)."""
from types import SimpleNamespace

import pytest

from washer.paper import job as figures
from washer.paper import runs
from washer.paper.runs import RunLog


def _fake_run(statuses):
    """A washer.run.run stand-in: status by constants-file name and sv."""
    def run(path, verbose=False, **overrides):
        label = overrides.get("sv") or path.name[2:]
        st = statuses.get(label, "ok")
        if isinstance(st, Exception):
            raise st
        return SimpleNamespace(status=st, specials=[], rows=[])
    return run


def test_a_failing_run_is_recorded_and_the_others_still_run(tmp_path, monkeypatch):
    monkeypatch.setattr(runs, "run", _fake_run({"washer.hopf.K_s": "stopped: MX at K_s = 612",
                                                "washer.eps3.bwd": ValueError("garbage")}))
    monkeypatch.setattr(runs, "curve_of", lambda name, fwd, bwd, two_par, **k: f"curve {name}")
    curves, results, log = runs.run_all(tmp_path, progress=lambda *a: None)
    failed = log.failed()
    assert failed == {"washer.hopf.K_s": "stopped: MX at K_s = 612",
                      "washer.eps3.bwd": "error: ValueError: garbage"}
    # Curves of failed runs are absent (None), the rest are read.
    assert curves["washer.hopf.K_s"] is None and curves["washer.eps3"] is None
    assert curves["washer.hopf.K_s.frozen"] == "curve washer.hopf.K_s.frozen"
    assert len(log.status) == 2 + 2 * 2 * 6 + 2       # every run was attempted


def test_an_interrupted_run_stops_the_whole_job(tmp_path, monkeypatch):
    calls = []

    def run(path, verbose=False, **overrides):
        calls.append(path.name)
        return SimpleNamespace(status="interrupted (Ctrl-C): the points computed so far "
                               "are in the files")
    monkeypatch.setattr(runs, "run", run)
    with pytest.raises(KeyboardInterrupt, match="washer"):
        runs.run_all(tmp_path, progress=lambda *a: None)
    assert calls == ["c.washer"]


def _stub_main(monkeypatch, log, sim_status="ok"):
    monkeypatch.setattr(figures, "run_all", lambda out, quick=False: ({}, {}, log))
    monkeypatch.setattr(figures, "time_responses", lambda params, quick: "resp")
    monkeypatch.setattr(figures, "simulation_failures",
                        lambda resp: {} if sim_status == "ok" else {"fig11 long": sim_status})
    monkeypatch.setattr(figures, "measure", lambda *a: pytest.fail("judged despite a failed run"))


def test_figures_exits_nonzero_and_judges_nothing_when_a_run_failed(tmp_path, monkeypatch, capsys):
    log = RunLog(commands=["python -m washer.run auto/c.washer.hopf.K_s"],
                 seconds={"washer": 0.1, "washer.hopf.K_s": 0.2},
                 status={"washer": "ok", "washer.hopf.K_s": "stopped: MX at K_s = 612"})
    _stub_main(monkeypatch, log)
    assert figures.main(["--quick", "--out", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert "washer.hopf.K_s" in err and "MX at K_s = 612" in err
    report = (tmp_path / "report.md").read_text()
    assert "INCOMPLETE" in report and "washer.hopf.K_s" in report
    assert "reproduced" not in report


def test_figures_exits_nonzero_when_a_time_response_failed(tmp_path, monkeypatch, capsys):
    log = RunLog(status={"washer": "ok"}, seconds={"washer": 0.1})
    _stub_main(monkeypatch, log, sim_status="integrator step size fell below its minimum")
    assert figures.main(["--out", str(tmp_path)]) == 1
    assert "fig11 long" in capsys.readouterr().err


def test_figures_interrupt_exits_130_without_a_report(tmp_path, monkeypatch):
    def interrupted(out, quick=False):
        raise KeyboardInterrupt("run washer.hopf.C_a: interrupted (Ctrl-C)")
    monkeypatch.setattr(figures, "run_all", interrupted)
    assert figures.main(["--out", str(tmp_path)]) == 130
    assert not (tmp_path / "report.md").exists()
