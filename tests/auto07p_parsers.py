"""AUTO-07p's own Python parsers (parseB, parseS, parseBandS, parseD of the auto-07p
package) reading every b-, s- and d-file washer wrote in a folder, compared with what
washer's own readers (washer.auto.files.read_b, read_s) find there.

AUTO's parsers run in a child process (they are AUTO's Python 3 code as installed, not a
copy) with numpy hidden from them: parseS's data reader fails under numpy 2 on AUTO's own
files too (it compares an array with []), and without numpy AUTO uses its own pure-Python
arrays (Points.py), so every record is read in full: its mesh, state and parameters.

Per file (fort.7/8/9 as b/s/d):
  * b: the branches (BR and point count of each) and the labelled points (type code,
    label);
  * s: per record: label, type code, BR, PT, NPARI, NDIM, IPS, the number of mesh points,
    of state components, and PAR(1..NPAR) exactly (both read the same decimal text);
    parseBandS pairs the b- and s-file's labels;
  * d: parseD finds at least as many labelled point blocks as the b-file has labelled
    points. (Not the same labels, nor as many: a relabelled or merged diagram is saved
    with its d-file as it was, so AUTO's own d.ab of the ab demo holds the labels 7, 7,
    8, ... where its b.ab has 1, 2, 3, ..., and its d.3 of um3 (two runs from one start,
    merged) one block more than its b.3, the start the merge writes once; washer's are
    the same.)
"""
from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from washer.auto.files import read_b, read_s  # noqa: E402


def auto_python() -> Path | None:
    """The folder holding AUTO-07p's Python package `auto` (AUTO_DIR/python), or None."""
    candidates = [Path("/usr/lib/auto-07p/python")]
    exe = shutil.which("auto-07p")
    if exe:
        candidates.append(Path(exe).resolve().parents[1] / "python")
    for c in candidates:
        if (c / "auto" / "parseS.py").exists():
            return c
    return None


#: The child: AUTO's parsers on the files named in argv[2:], JSON written to argv[1].
_CHILD = r"""
import json, sys, traceback
sys.modules["numpy"] = None          # AUTO's pure-Python arrays (see the module docstring)
sys.path.insert(0, %r)
from auto import parseB, parseS, parseBandS, parseD
out = {}
for name in sys.argv[2:]:
    kind, base = name.split(".", 1) if not name.startswith("fort.") else (
        {"7": "b", "8": "s", "9": "d"}[name[5:]], "")
    try:
        if kind == "b":
            b = parseB.parseB(name)
            # labels branch by branch (a file may repeat a label: runs appended)
            labels = [[v["TY number"], v["LAB"]] for br in b.branches
                      for i in br.labels.getIndices() for v in br.labels[i].values()]
            assert [lab for _, lab in labels] == list(b.getLabels())
            out[name] = {"branches": [[br["BR"], len(br)] for br in b.branches],
                         "labels": labels}
        elif kind == "s":
            recs = []
            for x in parseS.parseS(name):
                recs.append([x["Label"], x["Type number"], x["BR"], x["PT"], x["NPARI"],
                             x["NDIM"], x["IPS"], len(x.indepvararray), len(x.coordarray),
                             [float(p) for p in x.PAR]])
            out[name] = {"records": recs}
            bname = "b." + base if base else "fort.7"
            try:
                bs = parseBandS.parseBandS(bname, name)
                out[name]["paired"] = list(bs.getLabels())
            except IOError:
                pass
        elif kind == "d":
            d = parseD.parseD(name)
            if len(d.data):
                d[0]        # parses every block once (indexing item by item reparses all)
            out[name] = {"labels": [x["Label"] for x in d.data if x["Label"]]}
    except Exception:
        out[name] = {"error": traceback.format_exc(limit=3)[-1500:]}
with open(sys.argv[1], "w") as f:
    json.dump(out, f)
"""


def written_files(folder: Path, source: Path | None = None) -> list[str]:
    """The b./s./d. files and fort.7/8/9 in folder that are not empty, not backups (~),
    and not a file of `source` (the demo's own input) left unchanged."""
    out = []
    for p in sorted(folder.iterdir()):
        if not p.is_file() or p.name.endswith("~") or p.stat().st_size == 0:
            continue
        if not (p.name[:2] in ("b.", "s.", "d.") or p.name in ("fort.7", "fort.8", "fort.9")):
            continue
        if source is not None and (source / p.name).exists() and \
                (source / p.name).read_bytes() == p.read_bytes():
            continue
        out.append(p.name)
    return out


def _partner(name: str, kind: str) -> str:
    if name.startswith("fort."):
        return {"b": "fort.7", "s": "fort.8", "d": "fort.9"}[kind]
    return f"{kind}.{name[2:]}"


def check_folder(folder: Path, source: Path | None = None, timeout: float = 300) -> list[str]:
    """What AUTO's parsers read differently from washer's readers in `folder` (empty when
    they agree). Raises RuntimeError when AUTO's Python package is not installed."""
    auto = auto_python()
    if auto is None:
        raise RuntimeError("AUTO-07p's Python package (AUTO_DIR/python/auto) is not installed")
    folder = Path(folder)
    names = written_files(folder, source)
    if not names:
        return []
    with tempfile.TemporaryDirectory() as tmp:
        out_json = Path(tmp) / "auto.json"
        r = subprocess.run([sys.executable, "-c", _CHILD % str(auto), str(out_json), *names],
                           cwd=folder, capture_output=True, text=True, timeout=timeout)
        if r.returncode != 0 or not out_json.exists():
            return [f"AUTO's parsers failed (exit {r.returncode}): {r.stderr[-2000:]}"]
        got = json.loads(out_json.read_text())
    problems = []
    for name in names:
        g = got.get(name, {})
        if "error" in g:
            problems.append(f"{name}: AUTO's parser fails: {g['error']}")
            continue
        kind = {"fort.7": "b", "fort.8": "s", "fort.9": "d"}.get(name, name[0])
        if kind == "b":
            ours = read_b(folder / name)
            want_br = [[b[0].br, len(b)] for b in ours]
            if g["branches"] != want_br:
                problems.append(f"{name}: AUTO's parseB reads branches (BR, points) "
                                f"{g['branches']}, washer's reader {want_br}")
            want = [[r.ty, r.lab] for b in ours for r in b if r.lab]
            if g["labels"] != want:
                problems.append(f"{name}: AUTO's parseB reads labels {g['labels']}, "
                                f"washer's reader {want}")
        elif kind == "s":
            ours = read_s(folder / name)
            want = [[r.lab, r.code, r.br, r.pt, r.npari, r.ndim_user, r.ips,
                     1 if r.t is None else len(r.t),
                     len(r.u) if r.t is None else r.u.shape[1],
                     [float(p) for p in r.par]] for r in ours]
            if len(g["records"]) != len(want):
                problems.append(f"{name}: AUTO's parseS reads {len(g['records'])} records, "
                                f"washer's reader {len(want)}")
            for a, w in zip(g["records"], want):
                if a != w:
                    fields = "LAB TY BR PT NPARI NDIM IPS NTPL N PAR".split()
                    diff = [f"{k} {x!r} vs {y!r}" for k, x, y in zip(fields, a, w) if x != y]
                    problems.append(f"{name} label {w[0]}: AUTO's parseS vs washer's reader: "
                                    + "; ".join(diff)[:400])
            if "paired" in g and g["paired"] != [r.lab for r in ours]:
                problems.append(f"{name}: AUTO's parseBandS pairs labels {g['paired']}, "
                                f"the s-file holds {[r.lab for r in ours]}")
        else:
            b = folder / _partner(name, "b")
            want = [r.lab for br in read_b(b) for r in br if r.lab] if b.exists() else None
            if want is not None and len(g["labels"]) < len(want):
                problems.append(f"{name}: AUTO's parseD finds {len(g['labels'])} labelled "
                                f"points {g['labels']}, fewer than the b-file's {len(want)} "
                                f"{want}")
    return problems
