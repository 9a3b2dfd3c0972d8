"""The results of a campaign: a journal of rows as they complete, and ``results.parquet``.

- ``rows.jsonl`` is the journal: one JSON line per finished run, appended and fsync'ed as each
  arrives. A line cut short by a kill is dropped when the journal is read again (that run simply
  runs again on ``--resume``). A run id journaled twice (a failed run retried with
  ``--retry-failed``) counts by its last line.
- ``results.parquet`` is rewritten from the journal atomically (temporary file, fsync,
  ``os.replace``) at most every ``snapshot_s`` seconds and at the end, so whatever stops the
  campaign — Ctrl-C, SIGKILL, a power cut — leaves the previous complete file in place.

Floats go through JSON as Python's shortest round-trip repr, so the table is bit-identical to the
values the workers computed.
"""

from __future__ import annotations

import io
import json
import os
import pathlib
import time

__all__ = ["ResultStore", "rows_to_frame", "read_results", "FIXED_COLUMNS"]

FIXED_COLUMNS = ["run_id", "point", "seed_index", "seed", "status"]
TAIL_COLUMNS = ["error", "notes", "requested", "wall_s", "cpu_s", "worker"]


def rows_to_frame(rows: list[dict], varied: list[str], metric_names: list[str]):
    """One row per run, ordered by grid point then seed index: the fixed columns, every varied key
    (as read back), every metric, then error, notes (why a value is null), requested, wall_s,
    cpu_s (the run's own CPU seconds), worker."""
    import pandas as pd

    records = []
    for r in rows:
        rec = {k: r.get(k) for k in FIXED_COLUMNS}
        values = r.get("values", {})
        rec.update({k: values.get(k) for k in varied})
        m = r.get("metrics", {})
        rec.update({k: m.get(k) for k in metric_names})
        rec.update({k: r.get(k) for k in TAIL_COLUMNS})
        records.append(rec)
    columns = FIXED_COLUMNS + varied + [m for m in metric_names if m not in varied] + TAIL_COLUMNS
    df = pd.DataFrame.from_records(records, columns=columns)
    for m in metric_names:
        df[m] = pd.to_numeric(df[m], errors="coerce").astype("float64")
    if len(df):
        df = df.sort_values(["point", "seed_index"], kind="stable").reset_index(drop=True)
    return df


def _write_parquet(df, path: pathlib.Path) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    from fprime_lite.osal.atomic import atomic_write_bytes

    buf = io.BytesIO()
    pq.write_table(pa.Table.from_pandas(df, preserve_index=False), buf)
    atomic_write_bytes(path, buf.getvalue())


def read_results(out_dir):
    """The results table of a campaign folder as a pandas DataFrame (from ``results.parquet``)."""
    import pandas as pd

    return pd.read_parquet(pathlib.Path(out_dir) / "results.parquet")


class ResultStore:
    """Rows of one campaign folder: ``add`` journals a row; ``snapshot`` rewrites the parquet file."""

    def __init__(self, out_dir: pathlib.Path, varied: list[str], metric_names: list[str], *,
                 snapshot_s: float = 1.0):
        self.out_dir = pathlib.Path(out_dir)
        self.journal = self.out_dir / "rows.jsonl"
        self.parquet = self.out_dir / "results.parquet"
        self.varied = varied
        self.metric_names = metric_names
        self.snapshot_s = snapshot_s
        self.rows: list[dict] = self._read_journal()
        self._fh: io.BufferedWriter | None = None
        self._last_snapshot = 0.0

    def _read_journal(self) -> list[dict]:
        if not self.journal.exists():
            return []
        data = self.journal.read_bytes()
        rows, good = [], 0
        for line in data.splitlines(keepends=True):
            if not line.endswith(b"\n"):
                break  # a line cut short by a kill
            try:
                rows.append(json.loads(line))
            except json.JSONDecodeError:
                break
            good += len(line)
        if good != len(data):
            with open(self.journal, "r+b") as fh:
                fh.truncate(good)
        latest = {r["run_id"]: r for r in rows}  # the last line of a run id replaces the earlier ones
        return list(latest.values())

    @property
    def done_ids(self) -> set[str]:
        return {r["run_id"] for r in self.rows}

    def add(self, row: dict) -> None:
        fh = self._fh
        if fh is None:
            self.out_dir.mkdir(parents=True, exist_ok=True)
            self._fh = fh = open(self.journal, "ab")
        fh.write(json.dumps(row, allow_nan=True).encode("utf-8") + b"\n")
        fh.flush()
        os.fsync(fh.fileno())
        if row["run_id"] in self.done_ids:
            self.rows = [r for r in self.rows if r["run_id"] != row["run_id"]]
        self.rows.append(row)
        if time.monotonic() - self._last_snapshot >= self.snapshot_s:
            self.snapshot()

    def frame(self):
        return rows_to_frame(self.rows, self.varied, self.metric_names)

    def snapshot(self):
        df = self.frame()
        _write_parquet(df, self.parquet)
        self._last_snapshot = time.monotonic()
        return df

    def close(self):
        df = self.snapshot()
        if self._fh is not None:
            self._fh.close()
            self._fh = None
        return df
