"""The results of a campaign: a dataset of parquet parts written as rows arrive, and ``results.parquet``.

- ``results.parts/`` is the campaign's record of finished runs: ``part-NNNNNNNN.parquet`` files, each a
  batch of rows, written once and never rewritten. A batch is flushed at most ``flush_s`` (0.5 s)
  after its first row (a background thread sees to it even when no further row comes), at once when
  it reaches ``batch_rows``, and at the end. Each part is written atomically (a recognisable
  temporary file, fsync, ``os.replace``, folder fsync), so a SIGKILL, Ctrl-C or power cut loses at
  most the rows not yet flushed (those runs simply fly again on ``--resume``) and never damages a
  committed part; a temporary file a kill left behind is removed at the next start. A run id
  recorded twice (a failed run retried with ``--retry-failed``, or a part written again by a
  compaction) counts by its last record, in part order.
- ``results.parquet`` is the table users read: the campaign's rows in grid order, written
  atomically at the end of each session (however the session ends, short of a SIGKILL); while a
  campaign runs, or after a kill, :func:`read_results` builds the same table from the parts.
- At the end of a session the parts are compacted into one (written first, then the older ones
  removed: a kill in between leaves duplicates that the last-record rule resolves), so a resume
  reads one file, not one per batch.
- ``rows.jsonl``, the per-row JSON journal of earlier versions, is still read (before the parts) so
  an older campaign folder resumes; it is no longer written, and the first compaction moves its rows
  into a part and renames it ``rows.jsonl.migrated``.

Floats travel as float64 (JSON, in the old journal, as Python's shortest round-trip repr), so the
table is bit-identical to the values the workers computed.
"""

from __future__ import annotations

import io
import json
import pathlib
import re
import threading
import time

from fprime_lite.tools.campaign.errors import CampaignError

__all__ = ["ResultStore", "rows_to_frame", "read_results", "has_results", "FIXED_COLUMNS", "PARTS"]

FIXED_COLUMNS = ["run_id", "point", "seed_index", "seed", "status"]
TAIL_COLUMNS = ["error", "notes", "requested", "wall_s", "cpu_s", "worker"]
#: Kept in the parts (a resumed campaign's pruner asks that worker to delete a folder), not in the table.
PART_ONLY = ["worker_address"]
PARTS = "results.parts"
LEGACY_JOURNAL = "rows.jsonl"
_PART_NAME = re.compile(r"part-(\d{8})\.parquet\Z")


def _columns(varied: list[str], metric_names: list[str]) -> list[str]:
    return FIXED_COLUMNS + varied + [m for m in metric_names if m not in varied] + TAIL_COLUMNS


def rows_to_frame(rows: list[dict], varied: list[str], metric_names: list[str]):
    """One row per run, ordered by grid point then seed index: the fixed columns, every varied key
    (as read back), every metric, then error, notes (why a value is null), requested, wall_s,
    cpu_s (the run's own CPU seconds), worker."""
    return _frame([_record(r, varied, metric_names) for r in rows], varied, metric_names)


def _record(r: dict, varied: list[str], metric_names: list[str]) -> dict:
    """A row (as a worker returns it: values and metrics nested) as one flat record."""
    rec = {k: r.get(k) for k in FIXED_COLUMNS}
    values = r.get("values", {})
    rec.update({k: values.get(k) for k in varied})
    m = r.get("metrics", {})
    rec.update({k: m.get(k) for k in metric_names})
    rec.update({k: r.get(k) for k in TAIL_COLUMNS})
    rec["worker_address"] = r.get("worker_address")
    return rec


def _frame(records: list[dict], varied: list[str], metric_names: list[str], extra: tuple = (), sort: bool = True):
    import pandas as pd

    columns = _columns(varied, metric_names) + list(extra)
    df = pd.DataFrame.from_records(records, columns=columns)
    for m in metric_names:
        df[m] = pd.to_numeric(df[m], errors="coerce").astype("float64")
    if sort and len(df):
        df = df.sort_values(["point", "seed_index"], kind="stable").reset_index(drop=True)
    return df


def _arrow(records: list[dict], varied: list[str], metric_names: list[str], extra: tuple = ()):
    import pyarrow as pa

    return pa.Table.from_pandas(_frame(records, varied, metric_names, extra, sort=False), preserve_index=False)


def _parquet_bytes(table) -> bytes:
    import pyarrow.parquet as pq

    buf = io.BytesIO()
    pq.write_table(table, buf)
    return buf.getvalue()


def _concat(tables: list):
    import pyarrow as pa

    tables = [t for t in tables if t is not None]
    if not tables:
        return None
    if len(tables) == 1:
        return tables[0]
    return pa.concat_tables(tables, promote_options="permissive")  # a column null in one batch, typed in another


def _last_per_run(table):
    """``table`` with, for each run id, only its last record (in table order)."""
    import pyarrow as pa

    ids = table.column("run_id").to_pylist()
    last = {rid: i for i, rid in enumerate(ids)}
    if len(last) == len(ids):
        return table
    keep = [False] * len(ids)
    for i in last.values():
        keep[i] = True
    return table.filter(pa.array(keep))


def _part_files(parts_dir: pathlib.Path) -> list[tuple[int, pathlib.Path]]:
    if not parts_dir.is_dir():
        return []
    found = []
    for p in parts_dir.iterdir():
        m = _PART_NAME.match(p.name)
        if m:
            found.append((int(m.group(1)), p))
    return sorted(found)


def _read_part(path: pathlib.Path):
    import pyarrow.parquet as pq

    try:
        return pq.read_table(path)
    except (OSError, ValueError) as exc:  # (pyarrow's ArrowInvalid is a ValueError)
        raise CampaignError([f"{path}: this results part cannot be read ({exc}) — parts are written whole or not "
                             f"at all, so something else damaged it; move it out of {path.parent} and "
                             f"--resume: its runs fly again"]) from None


def _read_legacy_journal(path: pathlib.Path) -> list[dict]:
    """The rows of an older folder's ``rows.jsonl`` (a line cut short by a kill is dropped)."""
    if not path.exists():
        return []
    rows = []
    for line in path.read_bytes().splitlines(keepends=True):
        if not line.endswith(b"\n"):
            break
        try:
            rows.append(json.loads(line))
        except json.JSONDecodeError:
            break
    return rows


def has_results(out_dir) -> bool:
    """Whether the campaign folder ``out_dir`` holds results (parts, an older version's journal, or only
    ``results.parquet``: a folder committed or copied without its parts)."""
    out_dir = pathlib.Path(out_dir)
    return ((out_dir / LEGACY_JOURNAL).exists() or bool(_part_files(out_dir / PARTS))
            or (out_dir / "results.parquet").is_file())


def _table_as_first_part(out_dir: pathlib.Path, varied: list[str] | None) -> None:
    """A folder holding ``results.parquet`` but no parts (the parts are not committed with a campaign's results,
    nor copied by whoever moved the folder): the table becomes part 0, so a resumed campaign counts its runs as
    done and its table keeps them. Without this a ``--resume`` flew every run again and, stopped early, wrote a
    table of only the new rows over the old one."""
    import pyarrow.parquet as pq

    from fprime_lite.osal.atomic import atomic_write_bytes, fsync_directory

    table_path = out_dir / "results.parquet"
    try:
        table = pq.read_table(table_path)
    except (OSError, ValueError) as exc:
        raise CampaignError([f"{table_path}: this results table cannot be read ({exc}); it is left as it is — "
                             f"move it out of {out_dir} to fly the campaign afresh there"]) from None
    if "run_id" not in table.schema.names:
        raise CampaignError([f"{table_path}: not a campaign's results table (no run_id column); it is left as it "
                             f"is — move it out of {out_dir} or choose another --out"])
    names = [n for n in table.schema.names if n not in FIXED_COLUMNS + TAIL_COLUMNS + PART_ONLY]
    split = len([n for n in names if n in varied]) if varied is not None else len(names)
    table = table.replace_schema_metadata({b"fprime_lite_varied": str(split).encode()})
    parts_dir = out_dir / PARTS
    parts_dir.mkdir(exist_ok=True)
    atomic_write_bytes(parts_dir / "part-00000000.parquet", _parquet_bytes(table))
    fsync_directory(parts_dir)


def read_results(out_dir):
    """The results table of a campaign folder as a pandas DataFrame: ``results.parquet`` when it is
    up to date with the parts (a finished or stopped campaign), else the same table built from the
    parts (a running campaign, or one killed: every row flushed so far)."""
    import pandas as pd

    out_dir = pathlib.Path(out_dir)
    table_path = out_dir / "results.parquet"
    parts = _part_files(out_dir / PARTS)
    if table_path.exists():
        import pyarrow.parquet as pq

        meta = pq.read_schema(table_path).metadata or {}
        last = int(meta.get(b"fprime_lite_last_part", b"-1"))
        if not parts or parts[-1][0] <= last:
            return pd.read_parquet(table_path)
    if not parts and not (out_dir / PARTS).is_dir() and not (out_dir / LEGACY_JOURNAL).exists():
        return pd.read_parquet(table_path)  # (its FileNotFoundError names the file)
    # a parts folder with no part yet: a campaign whose first batch is not flushed (an empty table)
    store = ResultStore(out_dir, None, None, reader=True)
    return store.frame()


class ResultStore:
    """Rows of one campaign folder: ``add`` records a row (flushed in batches as a new part),
    ``close`` flushes, compacts the parts and writes ``results.parquet``.

    ``varied``/``metric_names``: the table's columns (None: those the parts have, for a reader
    without the campaign file). ``reader``: only reading (:func:`read_results`, perhaps on another
    host than the writer's): the temporary files of parts being written are left alone.
    """

    def __init__(self, out_dir: pathlib.Path, varied: list[str] | None, metric_names: list[str] | None, *,
                 flush_s: float = 0.5, batch_rows: int = 20_000, reader: bool = False):
        from fprime_lite.osal.atomic import clean_temporary_files

        self.out_dir = pathlib.Path(out_dir)
        self.parts_dir = self.out_dir / PARTS
        self.parquet = self.out_dir / "results.parquet"
        self.flush_s = flush_s
        self.batch_rows = batch_rows
        if not reader:  # (a writer holds the folder's lock: no other process is writing a part)
            clean_temporary_files(self.parts_dir)  # a part a kill interrupted before its rename
        legacy = _read_legacy_journal(self.out_dir / LEGACY_JOURNAL)
        files = _part_files(self.parts_dir)
        if not reader and not files and not legacy and self.parquet.is_file():
            _table_as_first_part(self.out_dir, varied)
            files = _part_files(self.parts_dir)
        tables = [_read_part(p) for _, p in files]
        if varied is None or metric_names is None:
            varied, metric_names = self._columns_of(tables, legacy)
        self.varied, self.metric_names = varied, metric_names
        self._legacy = bool(legacy)
        if legacy:
            tables.insert(0, _arrow([_record(r, varied, metric_names) for r in legacy], varied, metric_names,
                                    tuple(PART_ONLY)))
        self._old = _concat(tables)  # what earlier sessions recorded: one record per run id
        if self._old is not None:
            self._old = _last_per_run(self._old)
        self._part_numbers = [n for n, _ in files]
        self._next_part = (files[-1][0] + 1) if files else 0
        self._new: dict[str, dict] = {}  # this session's records, by run id (a retried run: its latest)
        self._pending: list[dict] = []  # records not yet in a part
        self._oldest_pending = 0.0
        self._lock = threading.Lock()  # the pending rows and this session's records
        self._flushing = threading.Lock()  # a part being written
        self._wake = threading.Event()
        self._closed = False
        self._flusher: threading.Thread | None = None
        self.flush_error: BaseException | None = None

    @staticmethod
    def _columns_of(tables: list, legacy: list[dict]) -> tuple[list[str], list[str]]:
        """Varied and metric columns of the parts (or the old journal): those between the fixed
        and the tail columns; float64 ones after the first non-float64 are taken as metrics."""
        if tables:
            names = [n for n in tables[-1].schema.names if n not in FIXED_COLUMNS + TAIL_COLUMNS + PART_ONLY]
            meta = tables[-1].schema.metadata or {}
            split = int(meta.get(b"fprime_lite_varied", str(len(names)).encode()))
            return names[:split], names[split:]
        if legacy:
            return list(legacy[-1].get("values", {})), list(legacy[-1].get("metrics", {}))
        return [], []

    # ---- what earlier sessions recorded
    def _old_column(self, name: str) -> list:
        return [] if self._old is None else self._old.column(name).to_pylist()

    def __len__(self) -> int:
        n = 0 if self._old is None else self._old.num_rows
        return n + sum(1 for rid in self._new if not self._in_old(rid))

    def _in_old(self, rid: str) -> bool:
        if self._old is None:
            return False
        if not hasattr(self, "_old_ids"):
            self._old_ids = set(self._old_column("run_id"))
        return rid in self._old_ids

    def _set_old(self, table) -> None:
        self._old = table
        self.__dict__.pop("_old_ids", None)

    def done_ids(self, *, ok_only: bool = False) -> set[str]:
        """The run ids recorded (``ok_only``: with status ``ok``)."""
        ids = self._old_column("run_id")
        if ok_only:
            ids = [rid for rid, s in zip(ids, self._old_column("status"), strict=True) if s == "ok"]
        with self._lock:
            new = {rid for rid, rec in self._new.items() if not ok_only or rec["status"] == "ok"}
            if ok_only:
                return (set(ids) - set(self._new)) | new
            return set(ids) | new

    def restrict(self, run_ids: set[str]) -> None:
        """Leave out of the table every earlier record whose run id is not in ``run_ids`` (an
        edited campaign's old runs); the parts keep them."""
        if self._old is None:
            return
        import pyarrow as pa
        import pyarrow.compute as pc

        mask = pc.is_in(self._old.column("run_id"), value_set=pa.array(sorted(run_ids), pa.string()))
        self._set_old(self._old.filter(mask))

    def renumber(self, plan: dict[str, dict]) -> None:
        """Give every earlier record the grid point and seed index its run id has in ``plan`` (run
        id → task), so that a resumed campaign whose grid was edited numbers its old rows as its new ones."""
        if self._old is None or not self._old.num_rows:
            return
        import pyarrow as pa

        ids = self._old_column("run_id")
        points, seeds = self._old_column("point"), self._old_column("seed_index")
        new_points = [plan[r]["point"] if r in plan else p for r, p in zip(ids, points, strict=True)]
        new_seeds = [plan[r]["seed_index"] if r in plan else s for r, s in zip(ids, seeds, strict=True)]
        if new_points != points or new_seeds != seeds:
            t = self._old
            t = t.set_column(t.schema.get_field_index("point"), "point", pa.array(new_points, pa.int64()))
            t = t.set_column(t.schema.get_field_index("seed_index"), "seed_index", pa.array(new_seeds, pa.int64()))
            self._set_old(t)

    @property
    def rows(self) -> list[dict]:
        """Every recorded row, as a worker returned it (values and metrics nested)."""
        recs = [] if self._old is None else self._old.to_pylist()
        with self._lock:
            new = dict(self._new)
        recs = [r for r in recs if r["run_id"] not in new] + list(new.values())
        return [self._nested(r) for r in recs]

    def row(self, run_id: str) -> dict | None:
        """The recorded row of ``run_id`` (values and metrics nested), or None."""
        if run_id in self._new:
            return self._nested(self._new[run_id])
        if self._old is None:
            return None
        import pyarrow.compute as pc

        found = self._old.filter(pc.equal(self._old.column("run_id"), run_id)).to_pylist()
        return self._nested(found[-1]) if found else None

    def _nested(self, rec: dict) -> dict:
        row = {k: rec.get(k) for k in FIXED_COLUMNS + TAIL_COLUMNS + PART_ONLY}
        row["values"] = {k: rec.get(k) for k in self.varied}
        row["metrics"] = {k: rec.get(k) for k in self.metric_names}
        return row

    # ---- this session's rows
    def add(self, row: dict) -> None:
        rec = _record(row, self.varied, self.metric_names)
        with self._lock:
            if not self._pending:
                self._oldest_pending = time.monotonic()
            self._pending.append(rec)
            self._new.pop(rec["run_id"], None)  # a retried run's new row replaces (and follows) the old
            self._new[rec["run_id"]] = rec
            full = len(self._pending) >= self.batch_rows
        if full:
            self.flush()
        elif self._flusher is None:
            self._flusher = threading.Thread(target=self._flush_in_time, name="campaign-results-flush", daemon=True)
            self._flusher.start()
        if self.flush_error is not None:
            raise self.flush_error

    def _flush_in_time(self) -> None:
        """Flush each batch ``flush_s`` after its first row (a row is never left unflushed for
        long because no other row came)."""
        while not self._closed:
            with self._lock:
                due = self._oldest_pending + self.flush_s if self._pending else None
            wait = self.flush_s if due is None else max(0.0, due - time.monotonic())
            if self._wake.wait(wait):
                return
            if due is not None and time.monotonic() >= due:
                try:
                    self.flush()
                except BaseException as exc:  # noqa: BLE001 - reported to the engine by the next add()
                    self.flush_error = exc
                    return

    def flush(self) -> None:
        """Write the pending rows as a new part (atomically); nothing when none is pending."""
        from fprime_lite.osal.atomic import atomic_write_bytes

        with self._flushing:  # one flush at a time, in order; add() only waits for the hand-over below
            with self._lock:
                if not self._pending:
                    return
                batch, self._pending = self._pending, []
                number = self._next_part
                self._next_part += 1
            atomic_write_bytes(self.parts_dir / f"part-{number:08d}.parquet", _parquet_bytes(self._part_table(batch)))
            self._part_numbers.append(number)

    def _part_table(self, records: list[dict]):
        t = _arrow(records, self.varied, self.metric_names, tuple(PART_ONLY))
        meta = dict(t.schema.metadata or {})
        meta[b"fprime_lite_varied"] = str(len(self.varied)).encode()
        return t.replace_schema_metadata(meta)

    def _all_records(self):
        """Earlier sessions' records and this session's, one per run id (this session's last)."""
        with self._lock:
            new = list(self._new.values())
        new_table = _arrow(new, self.varied, self.metric_names, tuple(PART_ONLY)) if new else None
        old = self._old
        if old is not None and new:
            import pyarrow as pa
            import pyarrow.compute as pc

            old = old.filter(pc.invert(pc.is_in(old.column("run_id"), value_set=pa.array(list(self._new)))))
        return _concat([old, new_table])

    def frame(self):
        """The results table (pandas): one row per run, in grid order, without ``worker_address``."""
        import pyarrow as pa

        table = self._all_records()
        columns = _columns(self.varied, self.metric_names)
        if table is None:
            return _frame([], self.varied, self.metric_names)
        for name in columns:  # a column an older part lacks
            if name not in table.schema.names:
                table = table.append_column(name, pa.nulls(table.num_rows))
        table = table.select(columns).sort_by([("point", "ascending"), ("seed_index", "ascending")])
        return table.to_pandas()

    def compact(self) -> None:
        """Replace the parts by one holding every run's last record (written before the others go)."""
        self.flush()
        with self._lock:
            numbers = list(self._part_numbers)
        if len(numbers) <= 1 and not self._legacy:
            return
        from fprime_lite.osal.atomic import atomic_write_bytes, fsync_directory

        tables = [_read_part(self.parts_dir / f"part-{n:08d}.parquet") for n in numbers]
        if self._legacy:  # an older folder's journal moves into the compacted part (it is read first)
            legacy = _read_legacy_journal(self.out_dir / LEGACY_JOURNAL)
            tables.insert(0, _arrow([_record(r, self.varied, self.metric_names) for r in legacy], self.varied,
                                    self.metric_names, tuple(PART_ONLY)))
        every = _last_per_run(_concat(tables))
        number = self._next_part
        self._next_part += 1
        names = every.schema.names
        meta = {b"fprime_lite_varied": str(len([n for n in names if n in self.varied])).encode()}
        every = every.replace_schema_metadata(meta)
        atomic_write_bytes(self.parts_dir / f"part-{number:08d}.parquet", _parquet_bytes(every))
        for n in numbers:
            (self.parts_dir / f"part-{n:08d}.parquet").unlink(missing_ok=True)
        if self._legacy:  # kept for its owner, no longer read
            (self.out_dir / LEGACY_JOURNAL).replace(self.out_dir / (LEGACY_JOURNAL + ".migrated"))
            self._legacy = False
        fsync_directory(self.parts_dir)
        self._part_numbers = [number]

    def close(self):
        """Flush, compact, and write ``results.parquet`` atomically; returns the table."""
        from fprime_lite.osal.atomic import atomic_write_bytes

        self._closed = True
        self._wake.set()
        if self._flusher is not None:
            self._flusher.join(timeout=30)
        self.compact()
        df = self.frame()
        import pyarrow as pa

        table = pa.Table.from_pandas(df, preserve_index=False)
        last = max(self._part_numbers) if self._part_numbers else -1
        meta = dict(table.schema.metadata or {})
        meta[b"fprime_lite_last_part"] = str(last).encode()
        atomic_write_bytes(self.parquet, _parquet_bytes(table.replace_schema_metadata(meta)))
        return df
