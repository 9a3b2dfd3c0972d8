"""One campaign run on a worker: build it, read its values back, fly it, compute its metrics.

:func:`execute_run` never raises: whatever happens becomes the row's ``status`` (``ok``,
``failed`` or ``timeout``) and ``error``. The timeout is cooperative: the run kinds poll
``should_stop`` from their simulation loop, so a run past its time ends at its next check and
keeps what it measured so far (its metrics are then null with the reason "timed out").
"""

from __future__ import annotations

import json
import math
import pathlib
import shutil
import tempfile
import time
import traceback

from fprime_lite.tools.campaign.errors import MetricUnavailable
from fprime_lite.tools.campaign.kinds import RunRequest, metrics, run_kinds
from fprime_lite.tools.campaign.values import plain

__all__ = ["execute_run", "worker_name"]


def worker_name() -> str:
    """The Dask worker running this task (its name, else its address); ``local`` outside Dask."""
    try:
        from distributed import get_worker

        w = get_worker()
        return str(w.name if w.name is not None else w.address)
    except (ImportError, ValueError):
        return "local"


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


def execute_run(task: dict) -> dict:
    """Run ``task`` (made by the engine) and return its results row."""
    t0 = time.perf_counter()
    cpu0 = time.process_time()
    row = {"run_id": task["run_id"], "point": task["point"], "seed_index": task["seed_index"],
           "seed": task["seed"], "status": "ok", "error": None}
    values = task["values"]
    notes: dict[str, str] = {}
    timeout = task.get("timeout_s")
    deadline = t0 + timeout if timeout else math.inf
    keep = task.get("keep", "none")
    out_dir = pathlib.Path(tempfile.mkdtemp(prefix=f"campaign-{task['run_id']}-"))
    req = RunRequest(config=task["config"], values=values, seed=task["seed"], out_dir=out_dir,
                     base_dir=pathlib.Path(task["base_dir"]), should_stop=lambda: time.perf_counter() > deadline)
    readback = {k: None for k in values}
    metric_values = {m: None for m in task["metrics"]}
    try:
        kind = run_kinds()[task["kind"]]
        named = metrics()
        prepared = kind.prepare(req)
        probes = {}
        for name in task["metrics"]:
            m = named.get(name)
            if m is not None and m.instrument is not None:
                probes[name] = m.instrument(prepared.simulation)
        output = prepared.execute()
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
    finally:
        if keep == "all" or (keep == "failed" and row["status"] != "ok"):
            dest = pathlib.Path(task["artifacts_dir"]) / task["run_id"]
            shutil.rmtree(dest, ignore_errors=True)
            shutil.move(str(out_dir), dest)
        else:
            shutil.rmtree(out_dir, ignore_errors=True)
    row["values"] = readback
    row["metrics"] = metric_values
    row["notes"] = json.dumps(notes, sort_keys=True)
    row["requested"] = json.dumps(plain(values), sort_keys=True)
    row["wall_s"] = time.perf_counter() - t0
    row["cpu_s"] = time.process_time() - cpu0
    row["worker"] = worker_name()
    return row
