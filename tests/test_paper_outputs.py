"""`python -m washer.paper` keeps the previous results until the new ones exist, checks
its output folder before any work and runs once per folder at a time."""
from types import SimpleNamespace

from washer.locks import output_lock
from washer.paper import job
from washer.paper import runs


def _writing_run(calls):
    """A washer.run.run stand-in that writes a b-file like a real run, and is
    interrupted at its third call."""
    def run(path, verbose=False, **overrides):
        calls.append(path)
        if len(calls) == 3:
            raise KeyboardInterrupt("run: interrupted (Ctrl-C)")
        label = overrides.get("sv") or path.name[2:]
        (path.parent / f"b.{label}").write_text("new\n")
        return SimpleNamespace(status="ok", specials=[], rows=[])
    return run


def test_an_interrupted_rerun_keeps_the_previous_results(tmp_path, monkeypatch):
    auto = tmp_path / "auto"
    auto.mkdir()
    (auto / "b.washer").write_text("previous\n")
    (auto / "s.washer").write_text("previous\n")
    calls = []
    monkeypatch.setattr(runs, "run", _writing_run(calls))
    monkeypatch.setattr(runs, "curve_of", lambda name, fwd, bwd, two_par, **k: name)
    try:
        runs.run_all(tmp_path, progress=lambda *a: None)
    except KeyboardInterrupt:
        pass
    else:
        raise AssertionError("the interrupt did not reach the caller")
    assert (auto / "b.washer").read_text() == "previous\n"
    assert (auto / "s.washer").read_text() == "previous\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["auto"]    # no staging left


def test_a_finished_rerun_replaces_the_results(tmp_path, monkeypatch):
    auto = tmp_path / "auto"
    auto.mkdir()
    (auto / "b.washer").write_text("previous\n")
    (auto / "b.gone").write_text("a run that no longer exists\n")
    monkeypatch.setattr(runs, "run", lambda path, verbose=False, **o: (
        (path.parent / f"b.{o.get('sv') or path.name[2:]}").write_text("new\n"),
        SimpleNamespace(status="ok", specials=[], rows=[]))[1])
    monkeypatch.setattr(runs, "curve_of", lambda name, fwd, bwd, two_par, **k: name)
    runs.run_all(tmp_path, progress=lambda *a: None)
    assert (auto / "b.washer").read_text() == "new\n"
    assert not (auto / "b.gone").exists()
    assert (auto / "c.washer").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["auto"]


def test_unusable_out_is_refused_before_any_work(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(job, "run_all", lambda *a, **k: 1 / 0)
    (tmp_path / "afile").write_text("x")
    assert job.main(["--out", str(tmp_path / "afile")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {tmp_path / 'afile'}: cannot write output here")
    assert err.count("\n") == 1


def test_second_job_in_one_folder_is_refused(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(job, "run_all", lambda *a, **k: 1 / 0)
    with output_lock(tmp_path, "paper"):
        assert job.main(["--out", str(tmp_path)]) == 75
    assert "being written by process" in capsys.readouterr().err


def test_ctrl_c_after_the_runs_is_exit_130_not_a_traceback(tmp_path, monkeypatch, capsys):
    def late(args):
        raise KeyboardInterrupt
    monkeypatch.setattr(job, "_main", late)
    assert job.main(["--out", str(tmp_path)]) == 130
    assert "interrupted" in capsys.readouterr().err
    assert not (tmp_path / ".paper.lock").exists()
