"""Constants files, b/s/d files, and the command line."""
import gzip
import shutil
from pathlib import Path

import numpy as np
import pytest

from washer.auto.constants_file import ConstantsError, parse_override, read_constants
from washer.auto.files import AutoFileError, fmt_e, read_b, read_s
from washer.cont.record import find_record
from washer.run import main, run

DATA = Path(__file__).parent / "data"


def _c(tmp_path, text):
    p = tmp_path / "c.x"
    p.write_text(text)
    return p


def test_reads_auto_demo_constants_with_names_and_defaults(tmp_path):
    c = read_constants(DATA / "lrz" / "c.lrz")
    assert c.icp() == [1] and c["NMX"] == 50 and c["EPSS"] == 1e-4
    assert c.par_values("UZSTOP") == [(1, 30.0)] and c.par_index("PERIOD") == 11
    assert read_constants(_c(tmp_path, "NDIM=3"))["DSMAX"] == 0.1        # AUTO default
    c = read_constants(_c(tmp_path, "UZR = {1: [1,\n 2]}  # spans lines\nDS = 1d-2 ! comment"))
    assert c["UZR"] == {1: [1, 2]} and c["DS"] == 0.01



def test_a_constants_file_read_again_is_the_same_and_a_run_cannot_change_it(tmp_path):
    """The statements of a text parsed before in the process are reused (parse_text's
    memory): a second read of the file gives the same constants, an edited file its new
    values, and a change to what one read returned (a run's override, a list changed in
    place) does not reach the next read."""
    path = _c(tmp_path, "NDIM = 2\nUZR = {1: [1.0, 2.0]}\nNMX = 5\n")
    first = read_constants(path)
    first["UZR"][1].append(99.0)                       # changed in place by a caller
    first.set("NMX", 7, "<override>")
    again = read_constants(path)
    assert again["UZR"] == {1: [1.0, 2.0]} and again["NMX"] == 5
    path.write_text("NDIM = 2\nUZR = {1: [3.0]}\nNMX = 5\n")
    assert read_constants(path)["UZR"] == {1: [3.0]}

def test_list_of_pairs_keeps_every_user_value_of_an_index(tmp_path):
    # AUTO's older form of UZR (nag demo): one pair per value, the index repeated; each
    # value is a UZ, none replaces another. THL pairs name each index once.
    c = read_constants(_c(tmp_path, "UZR = [[1, 0.0], [1, 0.25], [-2, 3], [1, 1.0]]\n"
                                    "THL = [[11, 0.0]]"))
    assert c.par_values("UZR") == [(1, 0.0), (1, 0.25), (1, 1.0), (-2, 3.0)]
    assert c["THL"] == {11: 0.0}


def test_braces_are_a_flat_token_list_to_list_valued_constants(tmp_path):
    """AUTO's parseC reads braces as a flat list of tokens (':' and ',' alike separate):
    STOP = {'UZ1'} (a Python set, written by a user's script generator) is STOP = ['UZ1'],
    and an even number of tokens, {'LP0', 'HB1'}, is the list of both, not a dict."""
    c = read_constants(_c(tmp_path, "NDIM = 3\nSTOP = {'UZ1'}\nSP = {'LP0', 'HB1'}\n"
                                    "UZR = {1, [0.5, 1.5]}\n"))
    assert c["STOP"] == ["UZ1"] and c["SP"] == ["LP0", "HB1"]
    assert c["UZR"] == {1: [0.5, 1.5]}


def test_unquoted_words_are_strings(tmp_path):
    """AUTO's parseC reads every value as a token, quoted or not, and converts it by its
    key: AUTO's own demo constants (fnc/attr's c.attr.2) restart with IRS = UZ1, a label
    name. A word followed by '=' is the next statement, not a value."""
    c = read_constants(_c(tmp_path, "NDIM = 3, IPS = 4, IRS = UZ1, ILP = 0\n"
                                    "STOP = [UZ1, 'HB2']\ne = attr\n"))
    assert c["IRS"] == "UZ1" and c["ILP"] == 0 and c["STOP"] == ["UZ1", "HB2"]
    assert c["e"] == "attr"
    with pytest.raises(ConstantsError, match="IRS: expected a value"):
        read_constants(_c(tmp_path, "IRS = \nNMX = 5"))
    with pytest.raises(ConstantsError, match="NMX expects an integer"):
        read_constants(_c(tmp_path, "NMX = many"))


@pytest.mark.parametrize("text,message", [
    ("NDIM = 2\nFOO = 3", "c.x:2: unknown AUTO constant FOO"),
    ("NDIM = 2\nNMX = 1.5", "c.x:2: NMX expects an integer"),
    ("ICP = [1, 2", "c.x:1: unclosed '['"),
    ("DS 0.1", "c.x:1: expected '=' after DS"),
    ("e = 'ab", "unterminated string"),
    ("2 1 0 1  NDIM,IPS,IRS,ILP", "c.x:2: the file ends where the old positional format "
                                   "expects NICP"),
    ("2 1 0 1\n2 1", "c.x:2: NICP = 2 but the row lists 1 parameter index 1 and the line "
                     "ends: expected NICP"),
    ("2 1 0 1\n0 1", "c.x:2: NICP = 0: expected NICP"),
    ("2 1 0 1\n1 1\n15 4.5", "c.x:3: NCOL expects an integer, got '4.5'"),
])
def test_malformed_constants(tmp_path, text, message):
    with pytest.raises(ConstantsError, match=message.replace("[", r"\[")):
        read_constants(_c(tmp_path, text))


#: AUTO's enz demo constants in the old positional format (tabs and trailing comments
#: as shipped), after a KEY = value line, which AUTO's parseC also accepts first.
OLD_FORMAT = ("unames = {1: 's1'}\n"
              "2 1 0 1\t\t\t\tNDIM,IPS,IRS,ILP\n1 1   \t\t\t\tNICP,(ICP(I),I=1,NICP)\n"
              "15 4 3 1 1 0 0 0 \t\tNTST,NCOL,IAD,ISP,ISW,IPLT,NBC,NINT\n"
              "250 0 35 0 50 \t\t\tNMX,RL0,RL1,A0,A1\n"
              "250 -1 2 8 5 3 0\t\tNPR,MXBF,IID,ITMX,ITNW,NWTN,JAC\n"
              "1e-07 1e-07 1e-05 \t\tEPSL,EPSU,EPSS\n0.1 0.01 0.25 1 \t\tDS,DSMIN,DSMAX,IADS\n"
              "1 \t\t\t\tNTHL,/((I,THL(I)),I=1,NTHL)\n11 0.0\n0 \t\t\t\tNTHU\n"
              "2 \t\t\t\tNUZR,/((I,UZR(I)),I=1,NUZR)\n2 1\n2 5D0\n")


def test_reads_auto_old_positional_constants(tmp_path):
    c = read_constants(_c(tmp_path, OLD_FORMAT))
    assert (c["NDIM"], c["IPS"], c["IRS"], c["ILP"], c.icp()) == (2, 1, 0, 1, [1])
    assert (c["NTST"], c["NCOL"], c["ISP"], c["NINT"]) == (15, 4, 1, 0)
    assert (c["NMX"], c["RL0"], c["RL1"], c["A1"]) == (250, 0.0, 35.0, 50.0)
    assert (c["NPR"], c["MXBF"], c["ITMX"], c["ITNW"], c["JAC"]) == (250, -1, 8, 5, 0)
    assert (c["EPSL"], c["EPSS"], c["DS"], c["DSMAX"], c["IADS"]) == (1e-7, 1e-5, 0.1, 0.25, 1)
    assert c["THL"] == {11: 0.0} and c["THU"] == {} and c["unames"] == {1: "s1"}
    assert c["UZR"] == {2: [1.0, 5.0]}          # two rows for PAR(2): two values


def test_overrides():
    assert parse_override("IRS=HB1") == ("IRS", "HB1")
    assert parse_override("ICP=[1,'sigma']") == ("ICP", [1, "sigma"])
    assert parse_override("DS=-0.01") == ("DS", -0.01)


def test_fortran_number_format():
    assert fmt_e(8.20000002) == "  8.2000000200E+000"
    assert fmt_e(-1.5e-12) == " -1.5000000000E-012"
    assert fmt_e(0.0) == "  0.0000000000E+000"


def test_our_files_have_auto_layout_and_restart(tmp_path):
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    res = run(tmp_path / "c.ab", verbose=False, sv="eq")
    ref = read_s(DATA / "auto_reference" / "ab2p" / "s.eq")
    ours = read_s(tmp_path / "s.eq")
    assert [r.ty for r in ours] == [r.ty for r in ref]
    assert [r.lab for r in ours] == [r.lab for r in ref]
    hb, hb_ref = find_record(ours, "HB1"), find_record(ref, "HB1")
    np.testing.assert_allclose(hb.U, hb_ref.U, rtol=1e-6)
    assert hb.par[10] == pytest.approx(hb_ref.par[10], rel=1e-6)      # PAR(11) = period
    header = (tmp_path / "s.eq").read_text().splitlines()[0]
    assert len(header) == 93                                          # (6I6,I8,I6,I8,7I5)
    rows = [l for l in (tmp_path / "b.eq").read_text().splitlines() if not l.startswith("   0")]
    assert all(len(l) == 4 + 6 + 4 + 5 + 19 * 4 for l in rows)       # (I4,I6,I4,I5,4ES19.10)
    assert res.status == "ok" and res("HB1").lab == 2


def _same_records(a, b):
    assert [(r.br, r.pt, r.ty, r.lab) for r in a] == [(r.br, r.pt, r.ty, r.lab) for r in b]
    for r, s in zip(a, b):
        assert np.array_equal(r.par, s.par) and np.array_equal(r.U, s.U)


def test_a_gzipped_s_file_reads_and_restarts_as_the_plain_one(tmp_path, monkeypatch):
    """s.NAME.gz stands for s.NAME where s.NAME does not exist: read_s, the command
    language's sl and load(s=...), washer.run.load and a restart (IRS) read the same
    records from it as from the plain file, bit for bit (the text is the same), and a
    run restarted from it writes the same b-file rows."""
    from washer.auto import clui
    from washer.run import load
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    plain = DATA / "auto_reference" / "ab2p" / "s.eq"
    shutil.copy(plain, tmp_path / "s.eq")
    zipped = gzip.compress(plain.read_bytes())
    (tmp_path / "s.zipped.gz").write_bytes(zipped)
    (tmp_path / "s.gz.gz").write_bytes(zipped)            # the s-file of a run named 'gz'
    want = read_s(plain)
    _same_records(read_s(tmp_path / "s.zipped"), want)
    _same_records(read_s(tmp_path / "s.zipped.gz"), want)
    _same_records(read_s(tmp_path / "s.gz"), want)
    _same_records(load(tmp_path / "s.zipped"), want)
    monkeypatch.chdir(tmp_path)
    assert [s["LAB"] for s in clui.sl("zipped")] == [r.lab for r in want]
    assert clui.load(s="zipped", IRS=2)["PAR(1)"] == find_record(want, 2).par[0]
    rows = {}
    for s in ("eq", "zipped"):
        run(tmp_path / "c.ab", verbose=False, s=s, sv=f"from_{s}", IRS=3, ICP=[1], NMX=8)
        rows[s] = [(r.br, r.pt, r.ty, r.lab, r.values) for b in read_b(tmp_path / f"b.from_{s}")
                   for r in b]
    assert len(rows["eq"]) == 8 and rows["zipped"] == rows["eq"]
    assert (tmp_path / "s.zipped.gz").read_bytes() == zipped       # read, never written


def test_a_users_plain_s_file_wins_over_a_gzipped_one(tmp_path):
    """Where both s.NAME and s.NAME.gz exist, s.NAME is read (the user's own file; AUTO
    knows no .gz); a damaged gzip stream is an error naming the file."""
    full = (DATA / "auto_reference" / "ab2p" / "s.eq").read_bytes()
    first = read_s(DATA / "auto_reference" / "ab2p" / "s.eq")[:1]
    (tmp_path / "s.x.gz").write_bytes(gzip.compress(full))
    from washer.auto.files import record_text
    (tmp_path / "s.x").write_text(record_text(first[0]))
    _same_records(read_s(tmp_path / "s.x"), first)
    (tmp_path / "s.cut.gz").write_bytes(gzip.compress(full)[:200])
    with pytest.raises(AutoFileError, match=r"s\.cut\.gz: cannot read an AUTO s-file"):
        read_s(tmp_path / "s.cut")


def test_failed_run_keeps_points_and_ends_with_mx(tmp_path):
    """A run that cannot converge keeps every point so far and ends with MX."""
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    res = run(tmp_path / "c.ab", verbose=False, sv="mx", ITNW=1, DSMIN=0.005)
    rows = [r for b in read_b(tmp_path / "b.mx") for r in b]
    assert rows[-1].ty == -9 and len(rows) >= 2
    assert "No convergence" in res.status


def test_run_files_are_flushed_together_s_file_first(tmp_path):
    """A run's files are flushed every flush_seconds (and at the end), the s-file first:
    what is on disk between flushes is nothing of the point, and after a flush every label
    of the b-file has its s-record."""
    from washer.auto.files import OutputFiles, Row
    from washer.cont.record import Record
    out = OutputFiles(tmp_path, "x", flush_seconds=3600.0)
    out.column_titles = ["PAR(1)", "L2-NORM"]
    out.record(Record(1, 5, 1, 1, 1, 1, 1, 1, np.array([0.5]), np.arange(3.0)))
    out.row(Row(1, 5, 1, 1, [0.25, 0.5]))
    assert (tmp_path / "b.x").read_text() == "" and (tmp_path / "s.x").read_text() == ""
    flushed = []
    write_out = out._write_out                   # the order of the flushes
    out._write_out = lambda path, data: (flushed.append(path.name), write_out(path, data))
    out.flush()
    assert flushed == ["s.x", "b.x", "d.x"]
    out.close()
    assert [r.lab for b in read_b(tmp_path / "b.x") for r in b] == [1]
    assert [r.lab for r in read_s(tmp_path / "s.x")] == [1]


def test_a_write_failing_half_way_is_not_written_twice(tmp_path, monkeypatch):
    """A flush whose write fails after part of the text reached the file (a full disk)
    raises; closing the files afterwards writes only the rest, once."""
    import os
    from washer.auto import files
    out = files.OutputFiles(tmp_path, "x", flush_seconds=3600.0)
    out._append(out.d_path, "0123456789" * 10)
    real_write, calls = os.write, []

    def write(fd, data):                 # 40 bytes, then the disk is full
        calls.append(len(data))
        if len(calls) == 1:
            return real_write(fd, bytes(data[:40]))
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(files.os, "write", write)
    with pytest.raises(OSError):
        out.flush()
    monkeypatch.setattr(files.os, "write", real_write)
    out.close()
    assert (tmp_path / "d.x").read_text() == "0123456789" * 10


def test_cli_errors_name_file_and_line(tmp_path, capsys):
    p = _c(tmp_path, "e = 'nothere'\nNDIM = 2\nBOGUS = 1\n")
    assert main([str(p)]) == 2
    assert "c.x:3: unknown AUTO constant BOGUS" in capsys.readouterr().err
    p = _c(tmp_path, "e = 'nothere'\nNDIM = 2\n")
    assert main([str(p)]) == 2
    assert "no equations file" in capsys.readouterr().err
    p = _c(tmp_path, "e = 'washer'\nNDIM = 12\nIPS = 2\n")
    assert main([str(p)]) == 2
    assert "IPS=2 with IRS=0 needs stpnt(u, par, t)" in capsys.readouterr().err


def test_plot_cli_draws_a_diagram(tmp_path):
    from washer.plots.__main__ import main as plot_main
    for f in ("ab.py", "c.ab"):
        shutil.copy(DATA / "ab" / f, tmp_path)
    run(tmp_path / "c.ab", verbose=False, sv="eq")
    assert plot_main([str(tmp_path / "b.eq"), "--y", "2"]) == 0
    assert (tmp_path / "b_eq_diagram.png").stat().st_size > 10000
    assert plot_main([str(tmp_path / "b.missing")]) == 2


@pytest.mark.parametrize("bvp", [False, True])
def test_more_than_twenty_free_parameters_write_and_read_back(tmp_path, bvp):
    """A record with 22 free parameters (a Lin's-method BVP frees that many) holds its ICP
    as AUTO's WRTSP8/WRTBV8 write it, FORMAT (20I5): 20 indices a line, then 2. Written on
    one line, the header's NROWPR (which counts (NFPR + 19) // 20 lines) disagreed with
    the text and the record did not read back, so a restart from it was refused."""
    from washer.auto.files import record_text
    from washer.cont.record import Record
    icp = [12, 106, 54, 55, 45, 46, 61, 62, 70, 71, 100, 73, 74, 75, 78, 79, 80, 82,
           102, 103, 104, 105]
    rng = np.random.default_rng(1)
    par = rng.normal(size=200)
    if bvp:
        ntst, ncol = 3, 2
        u = rng.normal(size=(ntst * ncol + 1, 8))
        rec = Record(1, 7, 9, 2, len(icp), 1, 8, 4, u, par, icp, list(rng.normal(size=22)),
                     rng.normal(size=u.size), t=np.linspace(0, 1, len(u)), ntst=ntst,
                     ncol=ncol)
    else:
        u = rng.normal(size=8)
        rec = Record(1, 7, 9, 2, len(icp), 1, 8, 1, u, par, icp, list(rng.normal(size=22)),
                     rng.normal(size=8))
    text = record_text(rec)
    lines = text.splitlines()
    assert int(lines[0].split()[8]) == len(lines) - 1          # NROWPR: the lines after it
    first = next(k for k, line in enumerate(lines) if line.split()[:3] == ["12", "106", "54"])
    assert lines[first] == "".join(f"{i:5d}" for i in icp[:20])
    assert lines[first + 1] == "".join(f"{i:5d}" for i in icp[20:])
    (tmp_path / "s.x").write_text(text)
    back = read_s(tmp_path / "s.x")[0]
    assert list(back.icp) == icp
    assert np.allclose(back.rldot, rec.rldot, rtol=1e-9)
    assert np.allclose(np.ravel(back.udot), np.ravel(rec.udot), rtol=1e-9)
    assert np.allclose(back.par, par, rtol=1e-9)
