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
- ``every: N`` also keeps one run in N whatever its result (the runs whose place in the campaign's
  order — grid point, then seed index — is a multiple of N): a sample of ordinary runs to look at.
  Any one of ``best``, ``worst``, ``failed: true`` and ``every`` makes a policy; ``by`` is needed
  with ``best`` / ``worst``.

With a ranking the worker keeps every run's files under ``DIR/runs/RUN_ID/``; the engine, as each
row arrives, deletes the folders of the runs that are not (or no longer) kept. On ``--resume`` it
first removes every folder that the recorded rows do not keep (displaced runs whose deletion a
kill interrupted, and runs that finished without their row reaching a results part).
"""

from __future__ import annotations

import bisect
import math
import pathlib
import shutil
from dataclasses import dataclass

__all__ = ["KeepPolicy", "KEEP_MODES", "KEEP_FIELDS", "ArtifactPruner"]

KEEP_MODES = ("none", "failed", "all")
KEEP_FIELDS = {"best", "worst", "by", "order", "failed", "every"}


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
    every: int = 0

    @property
    def worker_mode(self) -> str:
        """What the worker does with a run's files: keep them (``all``: the engine prunes a
        ranking), keep them when the run is not ok (``failed``), or drop them (``none``)."""
        if self.mode == "ranked":
            if self.best or self.worst:
                return "all"
            return "failed" if self.failed else "none"  # (``every`` runs are marked per task)
        return self.mode

    def describe(self) -> str:
        if self.mode != "ranked":
            return self.mode
        parts = [f"{w} {n}" for w, n in (("best", self.best), ("worst", self.worst)) if n]
        better = "smaller" if self.order == "min" else "larger"
        text = f"{' and '.join(parts)} by {self.by} ({better} is better)" if parts else ""
        extra = (["failed runs"] if self.failed else []) + ([f"one run in {self.every}"] if self.every else [])
        return " and ".join(([text] if text else []) + extra)


def _goodness(row: dict, policy: KeepPolicy) -> tuple:
    """Sort key, best first: numbers in the policy's order, then nulls, then grid point and seed."""
    value = row.get("metrics", {}).get(policy.by)
    null = value is None or (isinstance(value, float) and math.isnan(value))
    signed = 0.0 if null else (float(value) if policy.order == "min" else -float(value))
    return (null, signed, row["point"], row["seed_index"])


def _badness(row: dict, policy: KeepPolicy) -> tuple:
    """Sort key, worst first: the exact reverse of :func:`_goodness`."""
    null, signed, point, seed_index = _goodness(row, policy)
    return (not null, -signed, -point, -seed_index)


def kept_ids(rows, policy: KeepPolicy) -> set[str]:
    """The run ids whose files ``policy`` keeps, given every row so far."""
    if policy.mode == "all":
        return {r["run_id"] for r in rows}
    keep = {r["run_id"] for r in rows if r["status"] != "ok"} if policy.mode == "failed" or policy.failed else set()
    if policy.mode != "ranked":
        return keep
    ok = [r for r in rows if r["status"] == "ok"]
    keep |= {r["run_id"] for r in sorted(ok, key=lambda r: _goodness(r, policy))[:policy.best]}
    keep |= {r["run_id"] for r in sorted(ok, key=lambda r: _badness(r, policy))[:policy.worst]}
    return keep


class ArtifactPruner:
    """Deletes the per-run folders under ``artifacts_dir`` that a ranking no longer keeps.

    It holds the current best and worst lists (at most N entries each, kept sorted), so a new row
    costs O(N), whatever the campaign's size. ``remote_remove(run_id, row)`` (optional) is called for
    a folder that does not exist on this machine: the worker that wrote it is asked to delete it (a
    cluster without a shared file system).
    """

    def __init__(self, artifacts_dir: pathlib.Path, policy: KeepPolicy, remote_remove=None,
                 always: frozenset = frozenset()):
        self.dir = pathlib.Path(artifacts_dir)
        self.policy = policy
        self.remote_remove = remote_remove
        self.always = always  # run ids kept whatever their result (``every: N``)
        self._best: list[tuple] = []   # (goodness, run_id), best first
        self._worst: list[tuple] = []  # (badness, run_id), worst first
        self._failed: set[str] = set()
        self._rows: dict[str, dict] = {}

    @property
    def active(self) -> bool:
        return self.policy.mode == "ranked"

    @property
    def kept(self) -> set[str]:
        ranked = {i for _, i in self._best} | {i for _, i in self._worst}
        return ranked | self._failed | (self.always & self._rows.keys())

    def _admit(self, row: dict) -> None:
        run_id = row["run_id"]
        self._rows[run_id] = row
        self._failed.discard(run_id)  # a retried run replaces its failed row
        if row["status"] != "ok":
            if self.policy.failed:
                self._failed.add(run_id)
            return
        for entries, key, n in ((self._best, _goodness(row, self.policy), self.policy.best),
                                (self._worst, _badness(row, self.policy), self.policy.worst)):
            if n:
                bisect.insort(entries, (key, run_id))
                del entries[n:]

    def start(self, rows: list[dict]) -> None:
        """On (re)start: keep what the recorded rows keep; remove every other run folder."""
        if not self.active:
            return
        for row in rows:
            self._admit(row)
        kept = self.kept | self.always
        if self.dir.is_dir():
            for folder in self.dir.iterdir():
                if folder.is_dir() and folder.name not in kept:
                    shutil.rmtree(folder, ignore_errors=True)

    def update(self, row: dict) -> None:
        """A new row: delete the folders it displaced, or its own when it is not kept."""
        if not self.active:
            return
        before = self.kept
        self._admit(row)
        now = self.kept
        for run_id in sorted((before | {row["run_id"]}) - now):
            folder = self.dir / run_id
            if folder.exists():
                shutil.rmtree(folder, ignore_errors=True)
            elif self.remote_remove is not None:
                self.remote_remove(run_id, self._rows[run_id])
