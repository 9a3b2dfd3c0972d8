"""One campaign run on a worker: build it, read its values back, fly it, compute its metrics.

:func:`execute_run` never raises: whatever happens becomes the row's ``status`` (``ok``,
``failed`` or ``timeout``) and ``error``. The timeout works in two steps: the run kinds poll
``should_stop`` from their simulation loop, so a run past its time ends at its next check and
keeps what it measured so far (its metrics are then null with the reason "timed out"); a run that
does not stop by itself (stuck where it never polls) is killed with its run process
(:mod:`.isolation`) a grace period later and recorded as ``timeout`` all the same.
"""

from __future__ import annotations

import itertools
import json
import math
import os
import pathlib
import shutil
import tempfile
import time
import traceback
import uuid

from fprime_lite.tools.campaign.errors import MetricUnavailable
from fprime_lite.tools.campaign.kinds import RunRequest, metrics, resolve_kind
from fprime_lite.tools.campaign.values import plain

__all__ = ["execute_run", "execute_batch", "fly", "worker_name", "worker_address", "warm_up", "WarmUp"]


def worker_name() -> str:
    """The Dask worker running this task (its name, else its address); ``local`` outside Dask."""
    try:
        from distributed import get_worker

        w = get_worker()
        return str(w.name if w.name is not None else w.address)
    except (ImportError, ValueError):
        return "local"


def worker_address() -> str | None:
    """The address of the Dask worker running this task; None outside Dask."""
    try:
        from distributed import get_worker

        return str(get_worker().address)
    except (ImportError, ValueError):
        return None


def _number(value):
    if isinstance(value, bool):
        return float(value)
    if isinstance(value, (int, float)):
        return float(value)
    return None


def _metric(name: str, named: dict, output, probes: dict):
    """(value, reason-when-null) of one metric: a named metric, else a run-summary key."""
    if name in named:
        try:
            value = named[name].compute(output, probes.get(name))
        except MetricUnavailable as exc:
            return None, str(exc)
        if value is None:
            return None, "the metric gave no value"
        return float(value), None
    if name not in output.summary:
        return None, f"not a named metric and not in the run summary (summary keys: {', '.join(output.summary)})"
    raw = output.summary[name]
    if raw is None:
        return None, "null in the run summary (not reached within the run)"
    value = _number(raw)
    if value is None:
        return None, f"the run summary's {name} is not a number ({type(raw).__name__})"
    return value, None


def fly(task: dict, out_dir: pathlib.Path, t0: float | None = None) -> dict:
    """Build, read back, fly and measure ``task`` in this process, its files in ``out_dir``; return
    the row without wall time, CPU time and worker. ``t0``: when the run's time started."""
    t0 = time.perf_counter() if t0 is None else t0
    row = {"run_id": task["run_id"], "point": task["point"], "seed_index": task["seed_index"],
           "seed": task["seed"], "status": "ok", "error": None}
    values = task["values"]
    notes: dict[str, str] = {}
    timeout = task.get("timeout_s")
    deadline = t0 + timeout if timeout else math.inf
    should_stop = lambda: time.perf_counter() > deadline  # noqa: E731
    probe = task.get("probe_checks")
    if probe:  # a pre-flight probe: stop after a few checks, report the summary's keys
        checks = [0]

        def should_stop() -> bool:
            checks[0] += 1
            return checks[0] >= probe or time.perf_counter() > deadline
    req = RunRequest(config=task["config"], values=values, seed=task["seed"], out_dir=out_dir,
                     base_dir=pathlib.Path(task["base_dir"]), should_stop=should_stop,
                     write_files=task.get("keep", "none") != "none")
    readback = {k: None for k in values}
    metric_values = {m: None for m in task["metrics"]}
    try:
        kind = resolve_kind(task["kind"])
        named = metrics()
        prepared = kind.prepare(req)
        probes = {}
        for name in task["metrics"]:
            m = named.get(name)
            if m is not None and m.instrument is not None:
                probes[name] = m.instrument(prepared.simulation)
        output = prepared.execute()
        if probe:
            row["summary_keys"] = sorted(output.summary)
            return row
        timed_out = req.should_stop()
        for key in values:
            try:
                readback[key] = plain(prepared.readback(key))
            except (KeyError, ValueError, AttributeError) as exc:
                notes[key] = f"not read back: {exc}"
        for name in task["metrics"]:
            if timed_out:
                notes[name] = f"timed out after {timeout:g} s of wall time"
                continue
            metric_values[name], reason = _metric(name, named, output, probes)
            if reason is not None:
                notes[name] = reason
        if timed_out:
            row["status"] = "timeout"
            sim_s = output.summary.get('sim_seconds', 0)
            row["error"] = f"timed out after {timeout:g} s of wall time at {sim_s:.0f} simulated s"
    except Exception as exc:  # noqa: BLE001 - a run that raises is recorded and the campaign goes on
        row["status"] = "failed"
        last = traceback.extract_tb(exc.__traceback__)[-1:] if exc.__traceback__ else []
        where = f" (at {pathlib.Path(last[0].filename).name}:{last[0].lineno})" if last else ""
        row["error"] = f"{type(exc).__name__}: {exc}{where}"
    row["values"] = readback
    row["metrics"] = metric_values
    row["notes"] = json.dumps(notes, sort_keys=True)
    row["requested"] = json.dumps(plain(values), sort_keys=True)
    return row


def _dispose_files(task: dict, row: dict, out_dir: pathlib.Path) -> None:
    """Move the run's folder to ``artifacts_dir/RUN_ID`` when ``keep`` asks, else delete it."""
    if not os.path.isdir(out_dir):  # (most runs write nothing: one stat, no rmtree)
        return
    keep = task.get("keep", "none")
    empty = not any(out_dir.iterdir())
    if not empty and (keep == "all" or (keep == "failed" and row["status"] != "ok")):
        dest = pathlib.Path(task["artifacts_dir"]) / task["run_id"]
        shutil.rmtree(dest, ignore_errors=True)
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.move(str(out_dir), dest)
    else:
        shutil.rmtree(out_dir, ignore_errors=True)


def warm_up(task: dict | None) -> None:
    """Load the plug-ins and build ``task`` (without flying it) in this process, so that the imports
    a first run would pay for are not on its clock (``wall_s``). Errors are the run's to report."""
    kinds_ = __import__("fprime_lite.tools.campaign.kinds", fromlist=["run_kinds"])
    kinds_.run_kinds(), kinds_.metrics()
    if task is None:
        return
    with tempfile.TemporaryDirectory(prefix="campaign-warm-up-") as tmp:
        try:
            resolve_kind(task["kind"]).prepare(RunRequest(config=task["config"], values=task["values"],
                                                          seed=task["seed"], out_dir=pathlib.Path(tmp),
                                                          base_dir=pathlib.Path(task["base_dir"])))
        except Exception:  # noqa: BLE001 - the real run reports it
            pass


try:
    from distributed.diagnostics.plugin import WorkerPlugin as _WorkerPlugin
except ImportError:  # pragma: no cover - distributed is a dependency
    _WorkerPlugin = object  # type: ignore[assignment,misc]


class WarmUp(_WorkerPlugin):
    """A Dask worker plug-in: :func:`warm_up` on every worker, including those that join later."""

    name = "fprime-lite-campaign-warm-up"

    def __init__(self, task: dict | None):
        self.task = task

    def setup(self, worker) -> None:
        warm_up(self.task)  # (a run process, with timeout_s, warms itself: isolation.main)


def execute_batch(tasks) -> list[dict]:
    """Run several short runs in one Dask task (fewer round trips); the rows in the same order.
    ``tasks``: the list, or its pickle (bytes: Dask then does not walk every nested value of every
    task looking for dependencies, which costs the client more than the runs themselves when they
    are short)."""
    if isinstance(tasks, bytes):
        import pickle

        tasks = pickle.loads(tasks)
    where = (worker_name(), worker_address())  # once per task, not per run
    return [execute_run(t, where) for t in tasks]


_run_folders = itertools.count()


def _run_folder(run_id: str) -> pathlib.Path:
    """A fresh folder name for a run's files (not made: a kind that writes files makes it)."""
    global _TMP
    if _TMP is None:
        _TMP = tempfile.gettempdir()
    return pathlib.Path(f"{_TMP}/campaign-{run_id}-{_TOKEN}-{next(_run_folders)}")


_TMP: str | None = None
_TOKEN = uuid.uuid4().hex[:12]  # this process's: no two processes (nor a pid reused) share a folder name


def execute_run(task: dict, where: tuple[str, str | None] | None = None) -> dict:
    """Run ``task`` (made by the engine) and return its results row.

    With ``timeout_s`` the run flies in this worker's run process (:mod:`.isolation`), which is
    killed if the run is still going ``timeout_s`` plus a grace after it started; without, here.
    ``wall_s`` starts once the run process is up: its start is not the run's time. ``where``: the
    worker's name and address, when the caller has them.
    """
    if task.get("timeout_s"):
        from fprime_lite.tools.campaign.isolation import run_process

        try:
            run_process(task)
        except (OSError, RuntimeError):
            pass  # fly_isolated tries again and records the failure
    t0 = time.perf_counter()
    cpu0 = time.process_time()
    # named, not made: a kind that writes files makes it (a run that writes none costs no mkdir/rmdir)
    out_dir = _run_folder(task["run_id"])
    if task.get("timeout_s"):
        from fprime_lite.tools.campaign.isolation import fly_isolated, killed_row

        try:
            row, cpu_s = fly_isolated(task, out_dir)
        except (OSError, RuntimeError) as exc:  # no run process (cannot start, pipe broken): this run fails
            row = killed_row(task, "failed", f"no run process: {type(exc).__name__}: {exc}",
                             "the run process could not be used")
            cpu_s = time.process_time() - cpu0
    else:
        row = fly(task, out_dir, t0)
        cpu_s = time.process_time() - cpu0
    _dispose_files(task, row, out_dir)
    row["wall_s"] = time.perf_counter() - t0
    row["cpu_s"] = cpu_s
    row["worker"], row["worker_address"] = where if where is not None else (worker_name(), worker_address())
    return row
