"""The README's two commands exist and .ci/run runs the test command verbatim."""
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _commands():
    lines = (ROOT / "README.md").read_text().splitlines()
    return [l.strip() for l in lines if l.startswith("    apt-get")]


def test_readme_has_exactly_two_setup_commands():
    cmds = _commands()
    assert len(cmds) == 2
    assert "pytest" not in cmds[0] and "python -m washer" in cmds[0]
    # the whole suite: the slow tests that plain `python -m pytest` deselects included
    assert cmds[1].endswith('python -m pytest -q -m "slow or not slow"')


def test_ci_runs_the_readme_test_command():
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert _commands()[1] in [l.strip() for l in ci]
