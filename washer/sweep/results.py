"""The results folder: part files written as batches finish, one consolidated table.

    DIR/spec.toml            the spec as run (its text)
    DIR/sweep.json           where the spec came from, the point ids in order
    DIR/parts/part-*.parquet one file per finished batch (atomic: washer.atomic)
    DIR/results.parquet      every point of the spec exactly once, in spec order
                             (consolidated from the parts)

A sweep re-run with the same spec and folder reads the ids in the parts and
computes only the points missing from them: a part is either complete or
absent, so an interrupted sweep loses at most the batches in flight.

Units live in the Parquet schema: every column with a unit carries the field
metadata {"unit": ...} (SI, Omega in Hz; `washer.sweep.tasks.UNITS` for the
outputs, the parameter layout for the inputs), e.g.
pyarrow.parquet.read_schema(path).field("crit_value").metadata[b"unit"].
"""
from __future__ import annotations

import hashlib
import json
from pathlib import Path

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from washer.atomic import atomic_file, write_text

PARTS = "parts"
RESULTS = "results.parquet"


class ResultStore:
    """Reads and writes one sweep's folder."""

    def __init__(self, folder, units: dict | None = None):
        self.folder = Path(folder)
        self.parts = self.folder / PARTS
        self.units = units or {}

    # -------------------------------------------------------------- writing
    def prepare(self, spec_text: str, source: str, ids: list[str]) -> None:
        """Create the folder and record the spec and its point ids."""
        self.parts.mkdir(parents=True, exist_ok=True)
        write_text(self.folder / "spec.toml", spec_text)
        write_text(self.folder / "sweep.json", json.dumps(
            {"spec": str(Path(source).resolve()) if source and not source.startswith("<")
             else source, "n_points": len(ids), "ids": ids}, indent=1))

    def write_part(self, rows: list[dict]) -> Path:
        """Write one finished batch as a part file; returns its path."""
        ids = "".join(r["id"] for r in rows)
        name = f"part-{hashlib.sha256(ids.encode()).hexdigest()[:16]}.parquet"
        path = self.parts / name
        with atomic_file(path) as fh:
            write_table(pd.DataFrame(rows), fh, self.units)
        return path

    # -------------------------------------------------------------- reading
    def part_files(self) -> list[Path]:
        return sorted(self.parts.glob("part-*.parquet")) if self.parts.exists() else []

    def read_parts(self) -> pd.DataFrame:
        """All rows of all part files (possibly of earlier specs), unsorted."""
        files = self.part_files()
        if not files:
            return pd.DataFrame(columns=["id", "status"])
        return pd.concat([pd.read_parquet(f) for f in files], ignore_index=True)

    def done(self, retry_failed: bool = False) -> set[str]:
        """Ids already computed (failed ones excluded with retry_failed)."""
        df = self.read_parts()
        if retry_failed:
            df = df[df["status"] == "ok"]
        return set(df["id"])

    def consolidate(self, ids: list[str], columns: list[str] | None = None) -> pd.DataFrame:
        """Write results.parquet: the rows of `ids`, in that order, each once.

        A point recomputed with retry_failed appears in two parts: the last
        written (by file time) wins. Columns in `columns` come first."""
        files = sorted(self.part_files(), key=lambda f: f.stat().st_mtime_ns)
        frames = [pd.read_parquet(f) for f in files]
        df = pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=["id"])
        df = df.drop_duplicates("id", keep="last").set_index("id")
        df = df.reindex([i for i in ids if i in df.index]).reset_index()
        if columns:
            first = [c for c in columns if c in df.columns]
            df = df[first + [c for c in df.columns if c not in first]]
        with atomic_file(self.folder / RESULTS) as fh:
            write_table(df, fh, self.units)
        return df

    def results(self) -> pd.DataFrame:
        return pd.read_parquet(self.folder / RESULTS)

    def spec_source(self) -> str:
        return json.loads((self.folder / "sweep.json").read_text())["spec"]


def units_for(spec) -> dict:
    """{column: unit} overrides of a spec's table: crit_value and crit_averaged in the
    units of the studies' critical parameter (when they share one)."""
    from washer.machine.layout import UNITS
    pars = {st.options["critical"]["parameter"] for st in spec.studies
            if "critical" in st.kinds}
    if len(pars) != 1:
        return {}
    unit = UNITS.get(next(iter(pars)), "")
    return {"crit_value": unit, "crit_averaged": unit, "crit_clearance_value": unit,
            "crit_whirl_growth": f"m/({unit})^0.5" if unit else "m"}


def write_table(df: pd.DataFrame, path, units: dict | None = None) -> None:
    """df as Parquet at path (or into a binary file object), each column's unit in its field metadata (`tasks.units_of`)."""
    from washer.sweep.tasks import units_of
    table = pa.Table.from_pandas(df, preserve_index=False)
    u = units_of(table.column_names, units)
    fields = [f.with_metadata({"unit": u[f.name]}) if f.name in u else f for f in table.schema]
    table = table.cast(pa.schema(fields, metadata=table.schema.metadata))
    pq.write_table(table, path)

