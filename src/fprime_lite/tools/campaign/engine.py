"""Running a campaign: check it, plan its runs, skip those already done, submit the rest to Dask,
journal each row as it arrives, then plot and summarise.

:func:`run_campaign` is the Python entry point (it returns the results as a pandas DataFrame);
``fprime-lite campaign`` calls it.
"""

from __future__ import annotations

import datetime as _dt
import pathlib
import tempfile
import time

from fprime_lite.osal.folders import file_in_the_way, make_output_folder
from fprime_lite.tools.campaign.errors import CampaignError, RunSetupError
from fprime_lite.tools.campaign.folder_lock import campaign_folder_lock
from fprime_lite.tools.campaign.kinds import RunRequest, resolve_kind
from fprime_lite.tools.campaign.manifest import now_utc, write_manifest
from fprime_lite.tools.campaign.plan import plan_runs
from fprime_lite.tools.campaign.results import ResultStore
from fprime_lite.tools.campaign.spec import Campaign, load_campaign

__all__ = ["run_campaign", "preflight", "default_out_dir"]


def default_out_dir(campaign: Campaign) -> pathlib.Path:
    return pathlib.Path("runs") / f"campaign-{campaign.name}-{_dt.datetime.now().strftime('%Y%m%d-%H%M%S')}"


def _representatives(campaign: Campaign, tasks: list[dict]) -> list[dict]:
    """Runs whose building checks every key and every non-numeric grid value: the first run of each
    sub-grid, and a run for each distinct string value (a topology, a law) of any axis."""
    chosen, seen = [], set()

    def take(task):
        if task["run_id"] not in seen:
            seen.add(task["run_id"])
            chosen.append(task)
    first_keys = set()
    for t in tasks:
        keys = frozenset(t["values"])
        if keys not in first_keys:
            first_keys.add(keys)
            take(t)
    strings = set()
    for t in tasks:
        for k, v in t["values"].items():
            if isinstance(v, str) and (k, v) not in strings:
                strings.add((k, v))
                take(t)
    return chosen


def preflight(campaign: Campaign, tasks: list[dict]) -> None:
    """Build (without flying) the representative runs in this process; a misspelt key or a bad value
    fails here, naming the campaign file line, before any run is submitted."""
    kind = resolve_kind(campaign.kind)
    problems = []
    for task in _representatives(campaign, tasks):
        with tempfile.TemporaryDirectory(prefix="campaign-check-") as tmp:
            req = RunRequest(config=task["config"], values=task["values"], seed=task["seed"],
                             out_dir=pathlib.Path(tmp), base_dir=campaign.base_dir)
            try:
                kind.prepare(req)
            except RunSetupError as exc:
                where = campaign.where.get(exc.key, str(campaign.path)) if exc.key else str(campaign.path)
                problems.append(f"{where}: {exc}")
            except Exception as exc:  # noqa: BLE001 - whatever stops the first run stops the campaign
                problems.append(f"{campaign.path}: run {task['run_id']} cannot be built: {type(exc).__name__}: {exc}")
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


def run_campaign(campaign, *, workers: int | None = None, scheduler: str | None = None, out=None,
                 resume: bool = False, retry_failed: bool = False, progress: bool = False, plots: bool = True,
                 console=None, summary: bool = True):
    """Run a campaign (a file path or a loaded :class:`Campaign`); return its results DataFrame.

    ``workers``: size of the embedded LocalCluster (default: one per core); ``scheduler``: the
    address of an existing Dask scheduler instead. ``out``: the campaign folder (default
    ``runs/campaign-NAME-TIMESTAMP``); ``resume``: keep the rows already in ``out`` and run only the
    rest; ``retry_failed`` (implies ``resume``): also run again the runs recorded as failed or
    timeout, their new rows replacing the old (same run ids, same seeds). One process at a time
    writes into a folder (:mod:`~fprime_lite.tools.campaign.folder_lock`).
    """
    if not isinstance(campaign, Campaign):
        campaign = load_campaign(campaign)
    if workers is not None and scheduler is not None:
        raise CampaignError(["give --workers (an embedded cluster) or --scheduler (an existing one), not both"])
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
    if (out / "rows.jsonl").exists() and not resume:
        raise CampaignError([f"--out {out}: holds results already — add --resume to continue that campaign, "
                             f"or choose another folder"])
    tasks = plan_runs(campaign, out / "runs")
    preflight(campaign, tasks)
    cannot_create = make_output_folder(out)
    if cannot_create is not None:
        raise CampaignError([f"--out {out}: {cannot_create}"])
    with campaign_folder_lock(out):
        wall, ran = _run_locked(campaign, tasks, out, workers, scheduler, retry_failed, progress, console)
    from fprime_lite.tools.campaign.results import read_results

    df = read_results(out)  # the table as written: the Python API and results.parquet agree exactly
    if plots and len(df):
        from fprime_lite.tools.campaign.plots import draw_plots

        draw_plots(df, campaign, out / "plots")
    if summary:
        from fprime_lite.tools.campaign.report import print_summary

        print_summary(df, campaign, console, wall_s=wall if ran else None)
    return df


def _run_locked(campaign, tasks, out, workers, scheduler, retry_failed, progress, console):
    """The runs still to do, into ``out`` (held by this process); ``(wall s, whether any ran)``."""
    from distributed import as_completed

    store = ResultStore(out, campaign.varied_keys, campaign.metrics)
    planned = {t["run_id"] for t in tasks}
    store.rows = [r for r in store.rows if r["run_id"] in planned]  # rows of an edited campaign's old runs drop out
    done = {r["run_id"] for r in store.rows if not retry_failed or r["status"] == "ok"}
    retried = sum(1 for r in store.rows if r["run_id"] not in done)
    from fprime_lite.tools.campaign.keep import ArtifactPruner

    pruner = ArtifactPruner(out / "runs", campaign.keep)
    pruner.start(store.rows)
    # seed-major order: a campaign stopped early has the same draws done for every grid point
    todo = sorted((t for t in tasks if t["run_id"] not in done), key=lambda t: (t["seed_index"], t["point"]))
    started = now_utc()
    counts: dict = {}
    info = None
    status = "interrupted"
    t0 = time.perf_counter()
    try:
        write_manifest(out, campaign, started=started, ended=None, status="running", cluster=None,
                       runs=len(tasks), counts={}, resumed_from=len(done), retried=retried)
        if todo:
            from fprime_lite.tools.campaign.cluster import dask_client
            from fprime_lite.tools.campaign.report import progress_bar
            from fprime_lite.tools.campaign.task import execute_run

            with dask_client(workers, scheduler) as (client, info):
                pruner.remote_remove = _remote_remover(client, out / "runs")
                futures = client.map(execute_run, todo, key=[f"campaign-run-{t['run_id']}" for t in todo],
                                     pure=False)
                by_key = {f.key: t for f, t in zip(futures, todo, strict=True)}
                with progress_bar(len(tasks), len(done), progress, console) as update:
                    for future in as_completed(futures):
                        try:
                            row = future.result()
                        except Exception as exc:  # noqa: BLE001 - a lost worker fails its run, not the campaign
                            row = _lost_row(by_key[future.key], exc)
                        store.add(row)
                        pruner.update(row)
                        update(row)
                        future.release()
        status = "complete"
    finally:
        df = store.close()
        counts = df["status"].value_counts().to_dict() if len(df) else {}
        write_manifest(out, campaign, started=started, ended=now_utc(), status=status, cluster=info,
                       runs=len(tasks), counts={str(k): int(v) for k, v in counts.items()},
                       resumed_from=len(done), retried=retried)
    return time.perf_counter() - t0, bool(todo)
