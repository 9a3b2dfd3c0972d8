"""Running a campaign: check it, plan its runs, skip those already done, submit the rest to Dask,
record each row as it arrives (parquet parts, :mod:`.results`), then plot and summarise.

:func:`run_campaign` is the Python entry point (it returns the results as a pandas DataFrame);
``fprime-lite campaign`` calls it.

Nothing flies before every name and value is checked: the file by :func:`~.spec.load_campaign`,
then :func:`preflight` builds (without flying) a run for each sub-grid, each value of each grid axis
and each dispersion's nominal value, and — when a metric is not a named metric — flies one run of
each sub-grid a few simulated seconds to learn its summary's keys.
"""

from __future__ import annotations

import collections
import datetime as _dt
import math
import pathlib
import re
import pickle
import sys
import tempfile
import time

from fprime_lite.model.errors import did_you_mean
from fprime_lite.osal.folders import file_in_the_way, make_output_folder
from fprime_lite.tools.campaign.errors import CampaignError, CampaignInterrupted, RunSetupError
from fprime_lite.tools.campaign.folder_lock import campaign_folder_lock
from fprime_lite.tools.campaign.kinds import RunRequest, metrics, resolve_kind
from fprime_lite.tools.campaign.manifest import ManifestWriter, read_manifest, resolved_configuration
from fprime_lite.tools.campaign.plan import draw_values, plan_runs, unique_points
from fprime_lite.tools.campaign.results import ResultStore, has_results
from fprime_lite.tools.campaign.spec import Campaign, load_campaign
from fprime_lite.tools.interrupt import stop_on_signals

__all__ = ["run_campaign", "preflight", "default_out_dir", "rerun"]

#: Simulated-time checks a probe flight makes before it stops (the plant checks once per recorded
#: sample, a deployment every 256 steps): enough for every summary key to exist.
PROBE_CHECKS = 5
#: Wall seconds of work a Dask task aims at when runs are short (several runs per task).
TARGET_TASK_S = 0.5
MAX_RUNS_PER_TASK = 500


def default_out_dir(campaign: Campaign) -> pathlib.Path:
    return pathlib.Path("runs") / f"campaign-{campaign.name}-{_dt.datetime.now().strftime('%Y%m%d-%H%M%S')}"


def _check_values(campaign: Campaign, tasks: list[dict]) -> list[tuple[str, str | None, dict, dict]]:
    """``(why, key checked or None, task, values)`` of the builds that check every key and value without depending on a
    seed: the first point of each sub-grid, a point for each value of each axis, and the dispersions
    at their nominal values (each choice of a ``choice``)."""
    from fprime_lite.tools.campaign.seeding import canonical

    nominal = {k: d.nominals[0] for k, d in campaign.dispersions.items() if d.nominals}
    chosen: list[tuple[str, str | None, dict, dict]] = []
    seen: set[str] = set()

    def take(why: str, task: dict, extra: dict | None = None, key: str | None = None) -> None:
        values = {**task["values"], **nominal, **(extra or {})}
        ident = canonical(values)
        if ident not in seen:
            seen.add(ident)
            chosen.append((why, key, task, values))

    firsts = [t for t in tasks if t["seed_index"] == 0]
    key_sets: set[frozenset] = set()
    for t in firsts:
        if frozenset(t["values"]) not in key_sets:
            key_sets.add(frozenset(t["values"]))
            take("the first point of a sub-grid", t)
    pairs: set[str] = set()
    for t in firsts:
        for k, v in t["values"].items():
            ident = canonical([k, v])
            if ident not in pairs:
                pairs.add(ident)
                take(f"{k} = {v!r}", t, key=k)
    for k, d in campaign.dispersions.items():
        for v in d.nominals[1:]:
            take(f"{k} = {v!r}", firsts[0], {k: v}, key=k)
    return chosen


def _build(campaign: Campaign, kind, task: dict, values: dict, tmp: pathlib.Path, should_stop=lambda: False):
    config = {**task["config"], **{k: v for k, v in values.items() if k in kind.fields}}
    req = RunRequest(config=config, values=values, seed=task["seed"], out_dir=tmp,
                     base_dir=campaign.base_dir, should_stop=should_stop)
    return kind.prepare(req)


def _problem(campaign: Campaign, exc: BaseException, why: str, key: str | None = None) -> str:
    """The problem line of a build that failed: at the line of the key at fault — the one the kind
    names, else the value this build was checking, else a varied key the message names."""
    if isinstance(exc, RunSetupError):
        culprit = exc.key if exc.key in campaign.where else key
        if culprit is None:
            culprit = next((k for k in campaign.varied_keys if k.split(".", 1)[-1] in str(exc)), None)
        where = campaign.where.get(culprit, str(campaign.path)) if culprit else str(campaign.path)
        return f"{where}: {exc}"
    where = campaign.where.get(key, str(campaign.path)) if key else str(campaign.path)
    return f"{where}: a run with {why} cannot be built: {type(exc).__name__}: {exc}"


def _summary_keys(campaign: Campaign, task: dict, values: dict) -> set[str] | None:
    """Fly ``task`` for a few simulated seconds; the keys of its summary. With ``timeout_s`` the
    probe flies in a run process killed at the timeout (None: it did not come back in time)."""
    from fprime_lite.tools.campaign.task import fly

    fields = resolve_kind(campaign.kind).fields
    probe = {**task, "values": values, "probe_checks": PROBE_CHECKS, "keep": "none",
             "config": {**task["config"], **{k: v for k, v in values.items() if k in fields}}}
    row: dict | None
    with tempfile.TemporaryDirectory(prefix="campaign-probe-") as tmp:
        if not campaign.timeout_s:
            row = fly(probe, pathlib.Path(tmp))
        else:
            from fprime_lite.tools.campaign.isolation import _RunProcess, grace_s

            proc = _RunProcess()
            try:
                row = proc.run(probe, tmp, time.monotonic() + campaign.timeout_s + grace_s(campaign.timeout_s))
            except TimeoutError:
                return None
            finally:
                proc.end(kill=True)
            if row is None:
                return None
    if row["status"] != "ok" or "summary_keys" not in row:
        raise RuntimeError(row.get("error") or "the probe flight gave no summary")
    return set(row["summary_keys"])


def _listing(names) -> str:
    """``names`` for a message, the members of a numbered family (``x.histogram_s.0`` … ``.126``)
    folded into one ``x.histogram_s.N``."""
    folded = sorted({re.sub(r"\.\d+(\.\d+)?$", ".N", name) for name in names})
    return ", ".join(folded)


def preflight(campaign: Campaign, tasks: list[dict]) -> None:
    """Build (without flying) the runs of :func:`_check_values` in this process, then check the
    metrics that are not named metrics against a short flight's summary; a misspelt key or name, or a
    bad value, fails here, naming the campaign file line, before any run is submitted."""
    kind = resolve_kind(campaign.kind)
    problems = []
    by_keys: dict[frozenset, list[tuple[dict, dict]]] = {}
    for why, key, task, values in _check_values(campaign, tasks):
        with tempfile.TemporaryDirectory(prefix="campaign-check-") as tmp:
            try:
                _build(campaign, kind, task, values, pathlib.Path(tmp))
            except Exception as exc:  # noqa: BLE001 - whatever stops a run's build stops the campaign
                problems.append(_problem(campaign, exc, why, key))
                continue
        by_keys.setdefault(frozenset(k for k in values if k not in campaign.dispersions), []).append((task, values))
    named = metrics()
    unknown = [m for m in campaign.metrics if m not in named]
    if unknown and not problems:
        keys: set[str] = set()
        for candidates in by_keys.values():
            for task, values in candidates[:3]:  # a probe that overstays timeout_s: try another point
                try:
                    learnt = _summary_keys(campaign, task, values)
                except Exception:  # noqa: BLE001 - a run that fails in flight is the runs' to record: try another
                    continue
                if learnt is not None:
                    keys |= learnt
                    break
        if keys:
            where = campaign.where.get("metrics", str(campaign.path))
            for m in unknown:
                if m not in keys:
                    choices = sorted(keys | set(named))
                    problems.append(f"{where}: metric '{m}' is neither a named metric nor a key of the run summary"
                                    + did_you_mean(m, choices, f" (named metrics: {_listing(named)}; "
                                                              f"summary keys: {_listing(keys)})",
                                                   " — did you mean '{}'?"))
    if problems:
        raise CampaignError(sorted(set(problems)))


def _lost_row(task: dict, exc: BaseException) -> dict:
    """The row of a run whose worker died or whose task could not be delivered."""
    from fprime_lite.tools.campaign.isolation import killed_row

    row = killed_row(task, "failed", f"{type(exc).__name__}: {exc}", "the worker did not return the run")
    return {**row, "wall_s": None, "cpu_s": None, "worker": None}


def _remove_run_folder(path: str) -> None:
    """Delete a per-run folder (submitted to the worker that wrote it)."""
    import shutil

    shutil.rmtree(path, ignore_errors=True)


def _remote_remover(client, artifacts_dir: pathlib.Path):
    """Ask the worker that wrote a run's folder to delete it (a cluster without a shared file system)."""
    from distributed import fire_and_forget

    def remove(run_id: str, row: dict) -> None:
        address = row.get("worker_address")
        if address:
            fire_and_forget(client.submit(_remove_run_folder, str(artifacts_dir / run_id), workers=[address],
                                          allow_other_workers=False, pure=False))
    return remove


def _check_same_campaign(out: pathlib.Path, campaign: Campaign, store: ResultStore, planned: set[str],
                         force: bool) -> None:
    """A ``--resume`` into a folder that holds another campaign is refused (without ``force``):
    another name in its manifest, or not one of its recorded runs in this campaign's plan."""
    if force:
        return
    previous = read_manifest(out) or {}
    reasons = []
    if previous.get("campaign") not in (None, campaign.name):
        reasons.append(f"it holds campaign '{previous['campaign']}', not '{campaign.name}'")
    recorded = store.done_ids()
    if recorded and recorded.isdisjoint(planned):
        reasons.append(f"none of its {len(recorded)} runs is a run of this campaign (a changed 'run' section, "
                       f"dispersions, metrics or master_seed changes every run id)")
    if reasons:
        raise CampaignError([f"--out {out}: {'; '.join(reasons)} — choose another folder, or add --force to "
                             f"resume there anyway (the other runs' rows stay in results.parts/ but leave the table)"])


def run_campaign(campaign, *, workers: int | None = None, scheduler: str | None = None, out=None,
                 resume: bool = False, retry_failed: bool = False, progress: bool = False, plots: bool = True,
                 console=None, summary: bool = True, client=None, security=None, force: bool = False,
                 wait_for_workers_s: float = 60.0, heartbeat_s: float = 60.0, interruptible: bool = False):
    """Run a campaign (a file path or a loaded :class:`Campaign`); return its results DataFrame.

    ``workers``: size of the embedded cluster (default: one per core); ``scheduler``: the address of
    an existing Dask scheduler instead (``security``: a :class:`distributed.Security` for a
    ``tls://`` one); ``client``: a ready :class:`distributed.Client` (dask-jobqueue, Kubernetes,
    Coiled…), used as it is and left open. ``out``: the campaign folder (default
    ``runs/campaign-NAME-TIMESTAMP``); ``resume``: keep the rows already in ``out`` and run only the
    rest (a folder holding another campaign is refused unless ``force``); ``retry_failed`` (implies
    ``resume``): also run again the runs recorded as failed or timeout, their new rows replacing the
    old (same run ids, same seeds). One process at a time writes into a folder
    (:mod:`~fprime_lite.tools.campaign.folder_lock`). A script may call this at its top level: the
    embedded cluster's workers are subprocesses that do not re-run it.

    ``interruptible``: SIGINT (Ctrl-C) and SIGTERM stop the campaign cleanly — nothing more is
    submitted, every row that came back is kept (runs still in flight fly again on ``resume``), the
    manifest says ``status: "interrupted"`` with the rows done and planned, the cluster is shut down —
    and then :class:`~.errors.CampaignInterrupted` is raised (no plots, no summary). Only the main
    thread takes signals; elsewhere the flag does nothing.
    """
    if not isinstance(campaign, Campaign):
        campaign = load_campaign(campaign)
    chosen = [name for name, v in (("--workers", workers), ("--scheduler", scheduler), ("client=", client))
              if v is not None]
    if len(chosen) > 1:
        raise CampaignError([f"give one of --workers (an embedded cluster), --scheduler (an existing one) or "
                             f"client= (a ready Client), not {' and '.join(chosen)}"])
    if workers is not None and workers < 1:
        raise CampaignError([f"--workers must be at least 1, got {workers}"])
    resume = resume or retry_failed
    if out is None:
        if resume:
            raise CampaignError(["--resume needs --out: the folder of the campaign to continue"])
        out = default_out_dir(campaign)
    out = pathlib.Path(out)
    in_the_way = file_in_the_way(out)
    if in_the_way is not None:
        raise CampaignError([f"--out {out}: {in_the_way}"])
    if has_results(out) and not resume:
        raise CampaignError([f"--out {out}: holds results already — add --resume to continue that campaign, "
                             f"or choose another folder"])
    from fprime_lite.tools.campaign.plan import PLAN_CACHE, write_plan_cache

    cache = out / PLAN_CACHE
    tasks = plan_runs(campaign, out / "runs", draw=False, cache=cache if resume else None)
    preflight(campaign, tasks)
    cannot_create = make_output_folder(out)
    if cannot_create is not None:
        raise CampaignError([f"--out {out}: {cannot_create}"])
    with campaign_folder_lock(out):
        write_plan_cache(cache, campaign, tasks)
        received: list[str] = []
        with stop_on_signals(lambda: None, received, enabled=interruptible):
            wall, ran = _run_locked(campaign, tasks, out, dict(workers=workers, scheduler=scheduler, client=client,
                                                               security=security,
                                                               wait_for_workers_s=wait_for_workers_s),
                                    retry_failed, progress, console, force, heartbeat_s, received)
    from fprime_lite.tools.campaign.results import read_results

    df = read_results(out)  # the table as written: the Python API and results.parquet agree exactly
    if received:
        raise CampaignInterrupted(received[0], len(df), len(tasks), out)
    if plots and len(df):
        from fprime_lite.tools.campaign.plots import draw_plots

        draw_plots(df, campaign, out / "plots")
    if summary:
        from fprime_lite.tools.campaign.report import print_summary

        print_summary(df, campaign, console, wall_s=wall if ran else None)
    return df


def _collapse_workers(infos: dict) -> list[dict]:
    """Per-worker infos grouped by identical content: ``[{..., "workers": [addresses]}]``."""
    import json

    groups: dict[str, dict] = {}
    for address, info in sorted(infos.items()):
        key = json.dumps(info, sort_keys=True)
        groups.setdefault(key, {**info, "workers": []})["workers"].append(address)
    return list(groups.values())


class _Submitter:
    """Keeps about two tasks per worker thread in flight, each holding as many runs as fill
    ``TARGET_TASK_S`` at the runs' measured speed (one run per task until one has come back)."""

    def __init__(self, client, campaign, todo: list[dict]):
        self.client = client
        self.campaign = campaign
        self.queue = collections.deque(todo)
        self.inflight: dict[str, list[dict]] = {}
        self.mean_wall: float | None = None
        self._threads_checked = 0.0
        self.threads = 1

    def window(self) -> int:
        now = time.monotonic()
        if now - self._threads_checked > 5.0:  # workers may join (or leave) a cluster while it runs
            self.threads = max(1, sum(self.client.nthreads().values()))
            self._threads_checked = now
        return 2 * self.threads + 1

    def batch_size(self) -> int:
        if self.mean_wall is None:
            return 1
        n = int(TARGET_TASK_S / max(self.mean_wall, 1e-6))
        share = math.ceil(len(self.queue) / (2 * self.threads))  # leave work for every worker
        return max(1, min(n, MAX_RUNS_PER_TASK, share))

    def observe(self, rows: list[dict]) -> None:
        walls = [r["wall_s"] for r in rows if r.get("wall_s") is not None]
        if walls:
            w = sum(walls) / len(walls)
            self.mean_wall = w if self.mean_wall is None else 0.7 * self.mean_wall + 0.3 * w

    def fill(self, ac) -> None:
        from fprime_lite.tools.campaign.task import execute_batch

        window = self.window()
        while self.queue and len(self.inflight) < window:
            chunk = [draw_values(self.queue.popleft(), self.campaign)
                     for _ in range(min(self.batch_size(), len(self.queue)))]
            future = self.client.submit(execute_batch, pickle.dumps(chunk, protocol=pickle.HIGHEST_PROTOCOL),
                                        key=f"campaign-{chunk[0]['run_id']}-{len(chunk)}", pure=False)
            self.inflight[future.key] = chunk
            ac.add(future)


def _until_signalled(ac, received: list[str]):
    """The futures of ``ac`` as they complete, until ``ac`` is empty or a signal's name is in ``received``
    (checked every 10 ms while nothing is ready: a refill waits at most that long)."""
    while not received and not ac.is_empty():
        if ac.has_ready():
            yield next(ac)
        else:
            time.sleep(0.01)


def _error_message(exc: Exception) -> str:
    """What the manifest of a session that ``exc`` ended says: a campaign error's problems, else the
    exception's type and message."""
    if isinstance(exc, CampaignError):
        return "; ".join(exc.problems)
    text = str(exc)
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def _run_locked(campaign, tasks, out, where, retry_failed, progress, console, force, heartbeat_s, received):
    """The runs still to do, into ``out`` (held by this process); ``(wall s, whether any ran)``. A
    signal's name appearing in ``received`` stops the submissions; the rows that came back are kept."""
    from distributed import as_completed

    store = ResultStore(out, campaign.varied_keys, campaign.metrics)
    plan = {t["run_id"]: t for t in tasks}
    _check_same_campaign(out, campaign, store, set(plan), force)
    store.restrict(set(plan))  # rows of an edited campaign's old runs drop out
    store.renumber(plan)  # an edited grid renumbers its points: the old rows follow their run ids
    done = store.done_ids(ok_only=retry_failed)
    retried = len(store) - len(done)
    from fprime_lite.tools.campaign.keep import ArtifactPruner

    every = campaign.keep.every
    always = frozenset(t["run_id"] for t in tasks if every and t["order"] % every == 0)
    pruner = ArtifactPruner(out / "runs", campaign.keep, always=always)
    if pruner.active:
        pruner.start(store.rows)
    # seed-major order: a campaign stopped early has the same draws done for every grid point
    todo = sorted((t for t in tasks if t["run_id"] not in done), key=lambda t: (t["seed_index"], t["point"]))
    _, merged = unique_points(campaign.grids)
    manifest = ManifestWriter(out, campaign, runs=len(tasks), resumed_with=len(done), retried=retried,
                              merged_points=[{"listed": a, "point": b} for a, b in merged],
                              resolved=resolved_configuration(tasks))
    if merged:
        print(f"campaign: {len(merged)} grid point(s) listed more than once (e.g. listed point {merged[0][0]} = "
              f"point {merged[0][1]}): each distinct point flies once", file=sys.stderr)
    status = "failed"  # until the session ends otherwise: an error is a failure, not an interruption
    error: str | None = None
    signalled = received  # the signal names this session was stopped by
    info = workers_info = None
    ran = 0
    t0 = time.perf_counter()
    try:
        manifest.write(status="running", counts={})
        if todo:
            from fprime_lite.tools.campaign.cluster import dask_client, worker_info
            from fprime_lite.tools.campaign.report import progress_bar
            from fprime_lite.tools.campaign.task import WarmUp

            with dask_client(where["workers"], where["scheduler"], security=where["security"],
                             client=where["client"], wait_for_workers_s=where["wait_for_workers_s"]) as (client, info):
                warm = draw_values(dict(todo[0], values=dict(todo[0]["values"])), campaign)
                client.register_plugin(WarmUp(warm), name=WarmUp.name)
                workers_info = _collapse_workers(client.run(worker_info))
                manifest.write(status="running", counts={}, cluster=info, workers=workers_info)
                pruner.remote_remove = _remote_remover(client, out / "runs")
                submitter = _Submitter(client, campaign, [] if received else todo)
                ac = as_completed()
                submitter.fill(ac)
                with progress_bar(len(tasks), len(done), progress, console, log_every_s=heartbeat_s,
                                  running=lambda: sum(map(len, submitter.inflight.values()))) as update:
                    for future in _until_signalled(ac, received):
                        chunk = submitter.inflight.pop(future.key)
                        try:
                            rows = future.result()
                        except Exception as exc:  # noqa: BLE001 - a lost worker fails its runs, not the campaign
                            if received:  # a worker ended by the same Ctrl-C: its runs fly again on --resume
                                break
                            rows = [_lost_row(t, exc) for t in chunk]
                        future.release()
                        submitter.observe(rows)
                        if not received:
                            submitter.fill(ac)
                        for row in rows:
                            store.add(row)
                            pruner.update(row)
                            update(row)
                            ran += 1
                try:  # a client the caller keeps (client=) should not warm this campaign's runs on later workers
                    client.unregister_worker_plugin(WarmUp.name)
                except Exception:  # noqa: BLE001 - best effort: the plug-in only builds a run
                    pass
        status = "interrupted" if received else "complete"
    except KeyboardInterrupt:  # Ctrl-C when the caller did not ask for interruptible: still a signal
        status, signalled = "interrupted", received or ["SIGINT"]
        raise
    except Exception as exc:
        error = _error_message(exc)
        raise
    finally:
        df = store.close()
        counts = df["status"].value_counts().to_dict() if len(df) else {}
        stopped = {"signal": signalled[0], "done": len(df), "planned": len(tasks)} if status == "interrupted" else None
        manifest.write(status=status, counts={str(k): int(v) for k, v in counts.items()}, cluster=info,
                       workers=workers_info, ran=ran, ended=True, interrupted=stopped, error=error)
    return time.perf_counter() - t0, bool(todo)


def rerun(campaign, run_id: str, out, *, console=None):
    """Fly the run ``run_id`` of ``campaign`` again in this process, with its seed and dispersed
    values, keeping its files in ``out/runs/RUN_ID/``; the recorded rows are not touched. Returns
    ``(row, differences)``: the metrics and read-back values that differ from the recorded row
    (empty when it reproduced bit for bit, or when the run was never recorded)."""
    import json
    import shutil

    from fprime_lite.tools.campaign.task import execute_run

    if not isinstance(campaign, Campaign):
        campaign = load_campaign(campaign)
    out = pathlib.Path(out)
    tasks = plan_runs(campaign, out / "runs", draw=False)
    task = next((t for t in tasks if t["run_id"] == run_id), None)
    if task is None:
        ids = [t["run_id"] for t in tasks]
        raise CampaignError([f"--rerun {run_id}: not a run of this campaign"
                             + did_you_mean(run_id, ids, " (the run ids are the run_id column of results.parquet)",
                                            " — did you mean {}?")])
    preflight(campaign, tasks)
    cannot_create = make_output_folder(out)
    if cannot_create is not None:
        raise CampaignError([f"--out {out}: {cannot_create}"])
    draw_values(task, campaign)
    task = {**task, "keep": "all"}
    with campaign_folder_lock(out):
        shutil.rmtree(out / "runs" / run_id, ignore_errors=True)
        row = execute_run(task)
    old = ResultStore(out, campaign.varied_keys, campaign.metrics).row(run_id)
    differences = {}
    if old is not None:
        for section in ("metrics", "values"):
            for k, v in row[section].items():
                before = old.get(section, {}).get(k)
                if json.dumps(before, allow_nan=True) != json.dumps(v, allow_nan=True):
                    differences[k] = (before, v)
        if old.get("status") != row["status"]:
            differences["status"] = (old.get("status"), row["status"])
    return row, differences
