"""Every output file is replaced in one step, through an unpredictable temporary name,
never through a link planted at its name or at a temporary name."""
import os
import stat

import pytest

from washer.atomic import OutputError, atomic_file, check_folder, save_figure, write_text


def test_write_replaces_a_link_never_its_target(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    (tmp_path / "out.md").symlink_to(victim)
    write_text(tmp_path / "out.md", "report")
    assert victim.read_text() == "precious"
    assert not (tmp_path / "out.md").is_symlink()
    assert (tmp_path / "out.md").read_text() == "report"


def test_predictable_temporary_names_are_not_used(tmp_path):
    """Links planted at every name an older writer used (.NAME.<pid>.tmp, NAME.tmp)."""
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    for name in (f".spec.toml.{os.getpid()}.tmp", "spec.toml.tmp", ".spec.toml.tmp"):
        (tmp_path / name).symlink_to(victim)
    write_text(tmp_path / "spec.toml", "n = 3\n")
    assert victim.read_text() == "precious"
    assert (tmp_path / "spec.toml").read_text() == "n = 3\n"


def test_temporary_names_differ_between_writes(tmp_path, monkeypatch):
    seen = []
    real = os.replace
    monkeypatch.setattr(os, "replace", lambda a, b: (seen.append(os.path.basename(a)),
                                                     real(a, b)))
    for _ in range(3):
        write_text(tmp_path / "x.csv", "a,b\n")
    assert len(set(seen)) == 3 and all(s.startswith(".x.csv.") for s in seen)
    assert all(s.endswith(".csv") for s in seen)           # writers see the right format


def test_a_writer_that_fails_leaves_the_old_file_and_no_debris(tmp_path):
    p = tmp_path / "data.npz"
    write_text(p, "old")
    for exc in (RuntimeError("disk on fire"), KeyboardInterrupt()):
        with pytest.raises(type(exc)):
            with atomic_file(p) as fh:
                fh.write(b"half of the new")
                raise exc
        assert p.read_text() == "old"
        assert sorted(x.name for x in tmp_path.iterdir()) == ["data.npz"]


def test_new_files_get_the_usual_permissions(tmp_path):
    old = os.umask(0o022)
    try:
        write_text(tmp_path / "r.md", "x")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "r.md").stat().st_mode) == 0o644


def test_figures_are_saved_atomically_in_the_format_of_their_suffix(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    ax.plot([0, 1], [1, 0])
    victim = tmp_path / "victim.png"
    victim.write_bytes(b"precious")
    (tmp_path / "fig.png").symlink_to(victim)
    save_figure(fig, tmp_path / "fig.png")
    save_figure(fig, tmp_path / "fig.pdf")
    plt.close(fig)
    assert victim.read_bytes() == b"precious"
    assert (tmp_path / "fig.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (tmp_path / "fig.pdf").read_bytes()[:5] == b"%PDF-"


def test_check_folder_names_what_is_wrong(tmp_path):
    (tmp_path / "afile").write_text("x")
    with pytest.raises(OutputError, match="exists and is not a folder"):
        check_folder(tmp_path / "afile")
    with pytest.raises(OutputError, match="afile/sub: cannot create the output folder"):
        check_folder(tmp_path / "afile" / "sub")
    assert check_folder(tmp_path / "new" / "deep").is_dir()
    if os.geteuid() != 0:                       # root writes anywhere
        ro = tmp_path / "ro"
        ro.mkdir()
        ro.chmod(0o500)
        try:
            with pytest.raises(OutputError, match="cannot write output files in this folder"):
                check_folder(ro)
        finally:
            ro.chmod(0o700)


def test_sweep_parts_never_follow_planted_links(tmp_path):
    import hashlib
    from washer.sweep.results import ResultStore
    victim = tmp_path / "victim"
    victim.write_text("precious")
    store = ResultStore(tmp_path / "out")
    store.prepare("n = 1\n", "<test>", ["a"])
    name = f"part-{hashlib.sha256(b'a').hexdigest()[:16]}.parquet"
    (store.parts / f".{name}.{os.getpid()}.tmp").symlink_to(victim)
    (store.parts / name).symlink_to(victim)
    store.write_part([{"id": "a", "status": "ok"}])
    assert victim.read_text() == "precious"
    assert list(store.read_parts()["id"]) == ["a"]


def test_clui_diagram_writes_replace_links_and_append_whole(tmp_path):
    from pathlib import Path
    from washer.auto.diagram import Diagram
    ref = Path(__file__).parent / "data" / "auto_reference" / "ab2p"
    d = Diagram.read(ref / "b.eq", ref / "s.eq")
    victim = tmp_path / "victim"
    victim.write_text("precious")
    for k in "bsd":
        (tmp_path / f"{k}.out").symlink_to(victim)
    b, s, _ = d.write([tmp_path / f"{k}.out" for k in "bsd"])
    assert victim.read_text() == "precious"
    once = b.read_text()
    d.write([tmp_path / f"{k}.out" for k in "bsd"], append=True)
    assert b.read_text() == once + once
    assert len(Diagram.read(b, s)) == 2 * len(d)
