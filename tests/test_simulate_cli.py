"""washer.simulate: every bad argument is one line and exit 2 before any work; Ctrl-C
stops at once with exit 130 and every file whole; Model.simulate checks its inputs."""
import os
import sys
from pathlib import Path

import numpy as np
import pytest

import washer
from washer.machine import responses
from washer.simulate import main
from washer.sizes import SizeError

from test_interrupts import PROMPT_EXIT_S, interrupt_after_ready

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("args,message", [
    (["--Cp", "-1"], "--Cp -1.0: C_p = -1.0: expected a value >= 0"),
    (["--Cp", "nan"], "--Cp nan: expected a finite number"),
    (["--Omega", "-3"], "--Omega -3.0: Omega = -3.0: expected a value >= 0"),
    (["--Omega", "inf"], "--Omega inf: expected a finite number"),
    (["--t-end", "inf"], "--t-end inf: expected a finite positive duration"),
    (["--t-end", "nan"], "--t-end nan: expected a finite positive duration"),
    (["--t-end", "0"], "--t-end 0.0: expected a finite positive duration"),
    (["--t-end", "-5"], "--t-end -5.0: expected a finite positive duration"),
    (["--rtol", "0"], "--rtol 0.0: expected a relative tolerance in (0, 1)"),
    (["--rtol", "nan"], "--rtol nan: expected a relative tolerance in (0, 1)"),
    (["--rtol", "2"], "--rtol 2.0: expected a relative tolerance in (0, 1)"),
    (["--params", "missing.toml"], "missing.toml: cannot read parameter file"),
    (["--out", "afile"], "--out afile: cannot write output here: it exists and is not a folder"),
    (["--out", "afile/sub"], "--out afile/sub: cannot create the output folder"),
    (["--t-end", "1e7"], "fig10: a fixed-frame response of t_end = 1e+07 s"),
])
def test_bad_arguments_are_one_line_and_exit_2_before_any_work(tmp_path, monkeypatch, capsys,
                                                               args, message):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "afile").write_text("x")
    ran = []
    monkeypatch.setattr("washer.simulate.run_setup", lambda *a, **k: ran.append(a))
    assert main(["fig10"] + args) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {message}"), err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert ran == []                                      # nothing computed


def test_huge_response_names_its_estimate_and_the_flag(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr("washer.simulate.run_setup", lambda *a, **k: 1 / 0)
    assert main(["fig8", "--t-end", "1e6"]) == 2
    err = capsys.readouterr().err
    assert "GB of memory" in err and "days of computing" in err and "--allow-large" in err


def test_latin1_parameter_file_names_file_line_and_byte(tmp_path, capsys):
    ref = washer.load_params().source
    p = tmp_path / "p.toml"
    p.write_bytes(Path(ref).read_bytes().replace(b"\n", b"\n# r\xe9glage\n", 1))
    with pytest.raises(washer.ParameterError, match=r"p.toml:2: byte 0xe9 is not UTF-8"):
        washer.load_params(p)
    assert main(["fig10", "--params", str(p), "--out", str(tmp_path / "o")]) == 2
    assert "p.toml:2: byte 0xe9 is not UTF-8" in capsys.readouterr().err


@pytest.mark.parametrize("kw,message", [
    (dict(t_eval=[0.0, np.nan]), r"t_eval\[1\] = nan: expected finite times"),
    (dict(t_eval=[0.0, np.inf]), r"t_eval\[1\] = inf: expected finite times"),
    (dict(t_eval=[0.0, 2.0, 1.0]), r"t_eval\[2\] = 1.0 < t_eval\[1\] = 2.0"),
    (dict(t_eval=[-1.0, 0.0]), r"t_eval\[0\] = -1.0: the integration starts at t = 0"),
    (dict(rtol=0.0), r"rtol: expected a tolerance in \(0, 1\)"),
    (dict(atol=np.nan), r"atol: expected a tolerance"),
    (dict(samples_per_s=0.0), r"samples_per_s: expected a finite positive rate"),
    (dict(y0=np.full(12, np.nan)), r"y0: expected 12 finite numbers"),
    (dict(y0=np.zeros(3)), r"y0: expected 12 finite numbers, got shape \(3,\)"),
])
def test_model_simulate_checks_inputs_before_integrating(model, kw, message):
    with pytest.raises(ValueError, match=message):
        model.simulate(1.0, **kw)


@pytest.mark.parametrize("t_end", [np.nan, np.inf, 0.0])
def test_model_simulate_refuses_unreachable_end_times(model, t_end):
    with pytest.raises(ValueError, match="t_end: expected a finite positive time"):
        model.simulate(t_end)


def test_model_simulate_refuses_huge_responses_unless_allowed(model, monkeypatch):
    with pytest.raises(SizeError, match="t_end = 1e\\+06 s.*allow_large=True"):
        model.simulate(1e6, system="rotating")
    calls = []
    monkeypatch.setattr(responses, "_simulate_kernel", lambda *a: calls.append(a) or
                        responses.Response(np.zeros(1), np.zeros((1, 12)), "rotating",
                                           "averaged", "stub"))
    model.simulate(1e6, system="rotating", samples_per_s=1e-3, allow_large=True)
    assert len(calls) == 1


def test_interrupted_save_leaves_the_previous_files(tmp_path, model, monkeypatch):
    r = model.simulate(0.05, progress=False)
    paths = r.save(tmp_path / "run")
    before = {p: p.read_bytes() for p in paths}
    real = np.savez_compressed

    def interrupted(file, **arrays):
        real(file, **arrays)
        file.write(b"more")
        raise KeyboardInterrupt
    monkeypatch.setattr(np, "savez_compressed", interrupted)
    with pytest.raises(KeyboardInterrupt):
        r.save(tmp_path / "run")
    assert {p: p.read_bytes() for p in paths} == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.csv", "run.npz"]
    with np.load(tmp_path / "run.npz") as z:
        assert z["y"].shape == (51, 12)


def test_writes_replace_planted_links(tmp_path, model):
    victim = tmp_path / "victim"
    victim.write_text("precious")
    for ext in ("npz", "csv"):
        (tmp_path / f"run.{ext}").symlink_to(victim)
    model.simulate(0.02, progress=False).save(tmp_path / "run")
    assert victim.read_text() == "precious"


def test_ctrl_c_exits_130_at_once(tmp_path):
    code = ("import sys, washer.machine.responses as R\n"
            "real = R._simulate_kernel\n"
            "def announce(*a):\n    print('ready', flush=True)\n    return real(*a)\n"
            "R._simulate_kernel = announce\n"
            "from washer.simulate import main\n"
            f"sys.exit(main(['fig9', '--t-end', '1000', '--out', {str(tmp_path / 'o')!r}]))\n")
    dt, rc, out, err = interrupt_after_ready(code)
    assert rc == 130, err
    assert dt < PROMPT_EXIT_S and "interrupted" in err and "Traceback" not in err
    assert not list((tmp_path / "o").glob("fig9*"))      # nothing half-written
