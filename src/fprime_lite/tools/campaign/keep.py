"""Which runs keep their per-run files (``keep:`` of the campaign file) and the pruning that
enforces it while a campaign runs.

``keep`` is ``none``, ``failed`` or ``all``, or a ranking::

    keep: {best: 5, worst: 2, by: detumble_time_s, order: min, failed: true}

- ``best: N`` / ``worst: N`` (at least one): the N best / worst runs by the metric ``by`` (one of
  the campaign's ``metrics``); ``order: min`` (default) means smaller is better, ``max`` larger.
- Only runs with status ``ok`` are ranked. A null value (e.g. never detumbled) ranks after every
  number: the last of the best, the first of the worst. Ties go to the lower grid point, then the
  lower seed index, so the kept set depends only on the rows, never on the order runs finished.
- ``failed: true`` also keeps every failed or timed-out run.

With a ranking the worker keeps every run's files under ``DIR/runs/RUN_ID/``; the engine, as each
row arrives, deletes the folders of the runs that are not (or no longer) kept. On ``--resume`` it
first removes every folder that the journal's rows do not keep (displaced runs whose deletion a
kill interrupted, and runs that finished without their row reaching the journal).
"""

from __future__ import annotations

import math
import pathlib
import shutil
from dataclasses import dataclass

__all__ = ["KeepPolicy", "KEEP_MODES", "KEEP_FIELDS", "ArtifactPruner"]

KEEP_MODES = ("none", "failed", "all")
KEEP_FIELDS = {"best", "worst", "by", "order", "failed"}


@dataclass(frozen=True)
class KeepPolicy:
    """``mode``: none / failed / all / ranked; for ``ranked``: ``best``, ``worst`` (counts), ``by``
    (the metric), ``order`` (min: smaller is better), ``failed`` (also keep failed runs)."""

    mode: str = "none"
    best: int = 0
    worst: int = 0
    by: str | None = None
    order: str = "min"
    failed: bool = False

    @property
    def worker_mode(self) -> str:
        """What the worker does with a run's files: keep them (``all``: the engine prunes a
        ranking), keep them when the run is not ok (``failed``), or drop them (``none``)."""
        if self.mode == "ranked":
            return "all"
        return self.mode

    def describe(self) -> str:
        if self.mode != "ranked":
            return self.mode
        parts = [f"{w} {n}" for w, n in (("best", self.best), ("worst", self.worst)) if n]
        better = "smaller" if self.order == "min" else "larger"
        return f"{' and '.join(parts)} by {self.by} ({better} is better){' and failed runs' if self.failed else ''}"


def _goodness(row: dict, policy: KeepPolicy) -> tuple:
    """Sort key, best first: numbers in the policy's order, then nulls, then grid point and seed."""
    value = row.get("metrics", {}).get(policy.by)
    null = value is None or (isinstance(value, float) and math.isnan(value))
    signed = 0.0 if null else (float(value) if policy.order == "min" else -float(value))
    return (null, signed, row["point"], row["seed_index"])


def kept_ids(rows, policy: KeepPolicy) -> set[str]:
    """The run ids whose files ``policy`` keeps, given every row so far."""
    if policy.mode == "all":
        return {r["run_id"] for r in rows}
    keep = {r["run_id"] for r in rows if r["status"] != "ok"} if policy.mode == "failed" or policy.failed else set()
    if policy.mode != "ranked":
        return keep
    ranked = sorted((r for r in rows if r["status"] == "ok"), key=lambda r: _goodness(r, policy))
    keep |= {r["run_id"] for r in ranked[:policy.best]}
    if policy.worst:
        keep |= {r["run_id"] for r in ranked[-policy.worst:]}
    return keep


class ArtifactPruner:
    """Deletes the per-run folders under ``artifacts_dir`` that a ranking no longer keeps.

    ``remote_remove(run_id, row)`` (optional) is called for a folder that does not exist on this
    machine: the worker that wrote it is asked to delete it (a cluster without a shared file system).
    """

    def __init__(self, artifacts_dir: pathlib.Path, policy: KeepPolicy, remote_remove=None):
        self.dir = pathlib.Path(artifacts_dir)
        self.policy = policy
        self.remote_remove = remote_remove
        self.kept: set[str] = set()

    @property
    def active(self) -> bool:
        return self.policy.mode == "ranked"

    def start(self, rows: list[dict]) -> None:
        """On (re)start: keep what the journal's rows keep; remove every other run folder."""
        if not self.active:
            return
        self.kept = kept_ids(rows, self.policy)
        if self.dir.is_dir():
            for folder in self.dir.iterdir():
                if folder.is_dir() and folder.name not in self.kept:
                    shutil.rmtree(folder, ignore_errors=True)

    def update(self, rows: list[dict], row: dict) -> None:
        """``row`` has just been added to ``rows``: delete the folders it displaced (or its own)."""
        if not self.active:
            return
        now = kept_ids(rows, self.policy)
        by_id = {r["run_id"]: r for r in rows}
        for run_id in sorted((self.kept | {row["run_id"]}) - now):
            folder = self.dir / run_id
            if folder.exists():
                shutil.rmtree(folder, ignore_errors=True)
            elif self.remote_remove is not None and run_id in by_id:
                self.remote_remove(run_id, by_id[run_id])
        self.kept = now
