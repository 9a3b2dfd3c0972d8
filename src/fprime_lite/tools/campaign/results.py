"""The results of a campaign: a journal of rows as they complete, and ``results.parquet``.

- ``rows.jsonl`` is the journal: one JSON line per finished run, written (to the kernel) as each
  arrives, so a SIGKILL or Ctrl-C of the campaign loses no row; it is fsync'ed at most every
  ``fsync_s`` (0.5 s) and at the end, so a power cut loses at most that much (those runs simply
  run again on ``--resume``). A line cut short is dropped when the journal is read again. A run id
  journaled twice (a failed run retried with ``--retry-failed``) counts by its last line.
- ``results.parquet`` is rewritten from the journal atomically (temporary file, fsync,
  ``os.replace``) at most every ``snapshot_s`` seconds — and never more often than 10 times the
  time the last rewrite took, so a 100,000-row table costs the client a few per cent — and at the
  end, so whatever stops the campaign leaves the previous complete file in place. Each row is
  flattened once (not again at every rewrite).

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
    return _frame([_record(r, varied, metric_names) for r in rows], varied, metric_names)


def _record(r: dict, varied: list[str], metric_names: list[str]) -> dict:
    rec = {k: r.get(k) for k in FIXED_COLUMNS}
    values = r.get("values", {})
    rec.update({k: values.get(k) for k in varied})
    m = r.get("metrics", {})
    rec.update({k: m.get(k) for k in metric_names})
    rec.update({k: r.get(k) for k in TAIL_COLUMNS})
    return rec


def _frame(records: list[dict], varied: list[str], metric_names: list[str]):
    import pandas as pd

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
                 snapshot_s: float = 1.0, fsync_s: float = 0.5):
        self.out_dir = pathlib.Path(out_dir)
        self.journal = self.out_dir / "rows.jsonl"
        self.parquet = self.out_dir / "results.parquet"
        self.varied = varied
        self.metric_names = metric_names
        self.snapshot_s = snapshot_s
        self.fsync_s = fsync_s
        self._by_id: dict[str, dict] = {r["run_id"]: r for r in self._read_journal()}
        self._records: dict[str, dict] = {}
        self._fh: io.BufferedWriter | None = None
        self._last_snapshot = 0.0
        self._snapshot_cost = 0.0
        self._last_fsync = time.monotonic()
        self._unsynced = False

    @property
    def rows(self) -> list[dict]:
        return list(self._by_id.values())

    @rows.setter
    def rows(self, rows: list[dict]) -> None:
        self._by_id = {r["run_id"]: r for r in rows}
        self._records = {}

    def renumber(self, plan: dict[str, dict]) -> None:
        """Give every row the grid point and seed index its run id has in ``plan`` (run id → task),
        so that a resumed campaign whose grid was edited numbers its old rows as its new ones."""
        for rid, r in self._by_id.items():
            t = plan.get(rid)
            if t is not None and (r["point"], r["seed_index"]) != (t["point"], t["seed_index"]):
                r["point"], r["seed_index"] = t["point"], t["seed_index"]
                self._records.pop(rid, None)

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
        return set(self._by_id)

    def add(self, row: dict) -> None:
        fh = self._fh
        if fh is None:
            self.out_dir.mkdir(parents=True, exist_ok=True)
            self._fh = fh = open(self.journal, "ab")
        fh.write(json.dumps(row, allow_nan=True).encode("utf-8") + b"\n")
        fh.flush()  # in the kernel: a kill of this process loses nothing
        now = time.monotonic()
        self._unsynced = True
        if now - self._last_fsync >= self.fsync_s:
            self.sync()
        rid = row["run_id"]
        self._by_id.pop(rid, None)  # a retried run's new row replaces (and follows) the old
        self._by_id[rid] = row
        self._records.pop(rid, None)
        if now - self._last_snapshot >= max(self.snapshot_s, 10.0 * self._snapshot_cost):
            self.snapshot()

    def sync(self) -> None:
        """fsync the journal (a power cut loses nothing journaled before this)."""
        if self._fh is not None and self._unsynced:
            os.fsync(self._fh.fileno())
        self._unsynced = False
        self._last_fsync = time.monotonic()

    def frame(self):
        records = self._records
        for rid, r in self._by_id.items():
            if rid not in records:
                records[rid] = _record(r, self.varied, self.metric_names)
        return _frame([records[rid] for rid in self._by_id], self.varied, self.metric_names)

    def snapshot(self):
        t0 = time.monotonic()
        df = self.frame()
        _write_parquet(df, self.parquet)
        self._last_snapshot = time.monotonic()
        self._snapshot_cost = self._last_snapshot - t0
        return df

    def close(self):
        self.sync()
        df = self.snapshot()
        if self._fh is not None:
            self._fh.close()
            self._fh = None
        return df
