"""Campaign throughput on this machine: runs per hour, orchestration overhead, 2-worker speed-up.

Run: ``python benchmarks/bench_campaign.py [--plant-runs 8] [--deployment-runs 4] [--timeout-s S] [--json FILE]``.
With ``--timeout-s`` the engine's runs get that ``timeout_s`` and so fly in killable run processes
(hard timeouts) while the bare loop stays in-process: the overhead then includes the isolation.

For one-orbit plant-only runs and one-orbit deployment runs (5580 simulated s each) it measures, in
one process and one sitting:

- a bare loop: the same runs called one after the other in this process (``execute_run``), no Dask;
- the campaign engine with an embedded LocalCluster of 1 and of 2 workers (``run_campaign``),
  wall time from call to DataFrame, and the LocalCluster start-up + shut-down alone;
- whether the three tables are bit-identical (all columns but wall time and worker).

Overhead per run = (campaign at 1 worker − cluster start/stop − bare loop) / runs, and — robust to
other work on the machine, since both sides are timed at once — the engine's own overhead:
(campaign wall − start/stop − the runs' summed wall time / workers) × workers / runs. Speed-up =
campaign at 1 worker / campaign at 2 workers (both without the start-up). The machine is shared:
the load average before and after is printed, and only ratios from one sitting mean anything.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import sys
import tempfile
import textwrap
import time

REPO = pathlib.Path(__file__).resolve().parents[1]

PLANT = """\
campaign: bench_plant
master_seed: 1
run: {kind: plant, scenario: default, law: bdot, duration_s: 5580}
dispersions:
  scenario.initial.rate.magnitude_deg_s: {dist: uniform, low: 10, high: 60}
seeds: N
metrics: [final_rate_deg_s, coil_energy_j]
"""

TINY = PLANT.replace("bench_plant", "bench_tiny").replace("duration_s: 5580", "duration_s: 1")

DEPLOYMENT = f"""\
campaign: bench_deployment
master_seed: 1
run: {{kind: deployment, topology: {REPO / 'deployments/proves_ref/topology.yaml'}, duration_s: 5580}}
dispersions:
  scenario.initial.rate.magnitude_deg_s: {{dist: uniform, low: 10, high: 60}}
seeds: N
metrics: [final_rate_deg_s, coil_energy_j, detumble_complete_s]
"""


def _comparable(df):
    return df.drop(columns=["wall_s", "cpu_s", "worker"]).reset_index(drop=True)


def _cluster_start_stop(workers: int) -> float:
    from fprime_lite.tools.campaign.cluster import dask_client

    t0 = time.perf_counter()
    with dask_client(workers):
        pass
    return time.perf_counter() - t0


def measure(text: str, runs: int, folder: pathlib.Path, timeout_s: float | None = None) -> dict:
    import pandas as pd

    from fprime_lite.tools.campaign import load_campaign, run_campaign
    from fprime_lite.tools.campaign.plan import plan_runs
    from fprime_lite.tools.campaign.results import rows_to_frame
    from fprime_lite.tools.campaign.task import execute_run

    path = folder / "c.yaml"
    text = textwrap.dedent(text).replace("seeds: N", f"seeds: {runs}")
    if timeout_s is not None:
        text += f"timeout_s: {timeout_s}\n"  # the engine's runs fly in run processes (hard timeouts)
    path.write_text(text, encoding="utf-8")
    campaign = load_campaign(path)
    # the bare loop flies in this process (no run process), so the overhead includes the isolation
    tasks = [dict(t, timeout_s=None) for t in plan_runs(campaign, folder / "artifacts")]
    t0 = time.perf_counter()
    rows = [execute_run(t) for t in tasks]
    bare = time.perf_counter() - t0
    bare_df = rows_to_frame(rows, campaign.varied_keys, campaign.metrics)
    out = {"runs": runs, "bare_s": bare, "timeout_s": timeout_s}
    frames = {}
    for workers in (1, 2):
        start = _cluster_start_stop(workers)
        t0 = time.perf_counter()
        frames[workers] = run_campaign(campaign, workers=workers, out=folder / f"w{workers}", plots=False,
                                       summary=False)
        wall = time.perf_counter() - t0
        out[f"workers_{workers}"] = {"wall_s": wall, "cluster_start_stop_s": start,
                                     "runs_per_hour": runs / wall * 3600,
                                     "runs_per_hour_without_start": runs / (wall - start) * 3600}
        df = frames[workers]
        # time a worker spent outside the runs: scheduling, transfer, journaling, parquet rewrites
        busy = df["wall_s"].sum() / workers
        out[f"workers_{workers}"]["engine_overhead_per_run_s"] = (wall - start - busy) * workers / runs
        out[f"workers_{workers}"]["run_cpu_s_mean"] = float(df["cpu_s"].mean())
        out[f"workers_{workers}"]["run_wall_s_mean"] = float(df["wall_s"].mean())
    w1, w2 = out["workers_1"], out["workers_2"]
    out["overhead_per_run_s"] = (w1["wall_s"] - w1["cluster_start_stop_s"] - bare) / runs
    out["overhead_per_run_with_start_s"] = (w1["wall_s"] - bare) / runs
    out["speedup_2_workers"] = (w1["wall_s"] - w1["cluster_start_stop_s"]) / (w2["wall_s"] - w2["cluster_start_stop_s"])
    out["speedup_2_workers_with_start"] = w1["wall_s"] / w2["wall_s"]
    out["bare_runs_per_hour"] = runs / bare * 3600
    statuses = set(frames[1]["status"]) | set(frames[2]["status"]) | set(bare_df["status"])
    out["statuses"] = sorted(statuses)
    try:
        pd.testing.assert_frame_equal(_comparable(frames[1]), _comparable(frames[2]), check_exact=True)
        pd.testing.assert_frame_equal(_comparable(frames[1]), _comparable(bare_df), check_exact=True,
                                      check_dtype=False)
        out["bit_identical_bare_1_2"] = True
    except AssertionError as exc:
        out["bit_identical_bare_1_2"] = f"no: {str(exc)[:300]}"
    return out


def measure_isolation(runs: int, folder: pathlib.Path) -> dict:
    """The hard-timeout mechanism alone: the same tiny runs flown alternately in this process and in
    the run process (``timeout_s`` set), in one loop, so both see the same load."""
    import statistics

    from fprime_lite.tools.campaign import load_campaign
    from fprime_lite.tools.campaign.isolation import run_process
    from fprime_lite.tools.campaign.plan import plan_runs
    from fprime_lite.tools.campaign.task import execute_run

    path = folder / "c.yaml"
    path.write_text(textwrap.dedent(TINY).replace("seeds: N", f"seeds: {runs}"), encoding="utf-8")
    tasks = plan_runs(load_campaign(path), folder / "artifacts")
    execute_run(tasks[0])  # imports, in both processes, before timing
    t0 = time.perf_counter()
    run_process()
    start = time.perf_counter() - t0
    execute_run(dict(tasks[0], timeout_s=600.0))
    inside, isolated = [], []
    for t in tasks:
        for timeout, into in ((None, inside), (600.0, isolated)):
            t0 = time.perf_counter()
            execute_run(dict(t, timeout_s=timeout))
            into.append(time.perf_counter() - t0)
    return {"runs": runs, "run_process_start_s": start, "in_process_run_s_median": statistics.median(inside),
            "isolated_run_s_median": statistics.median(isolated),
            "isolation_overhead_per_run_s_median": statistics.median(
                b - a for a, b in zip(inside, isolated, strict=True)),
            "isolation_overhead_per_run_s_mean": statistics.fmean(isolated) - statistics.fmean(inside)}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--plant-runs", type=int, default=8)
    p.add_argument("--deployment-runs", type=int, default=4)
    p.add_argument("--tiny-runs", type=int, default=40, help="1-second plant runs: the engine's overhead alone")
    p.add_argument("--timeout-s", type=float, metavar="S",
                   help="give the engine's runs this timeout_s: each flies in a killable run process")
    p.add_argument("--isolation-runs", type=int, default=0,
                   help="tiny runs flown alternately in-process and in the run process: the hard timeout's cost")
    p.add_argument("--json", metavar="FILE")
    args = p.parse_args(argv)
    result = {"load_before": os.getloadavg(), "cores": os.cpu_count()}
    with tempfile.TemporaryDirectory(prefix="bench-campaign-") as tmp:
        tmp = pathlib.Path(tmp)
        for name, text, n in (("tiny_1s_plant", TINY, args.tiny_runs), ("plant_one_orbit", PLANT, args.plant_runs),
                              ("deployment_one_orbit", DEPLOYMENT, args.deployment_runs)):
            if n > 0:
                (tmp / name).mkdir()
                result[name] = measure(text, n, tmp / name, args.timeout_s)
                print(name, json.dumps(result[name], indent=2), flush=True)
        if args.isolation_runs > 0:
            (tmp / "isolation").mkdir()
            result["isolation"] = measure_isolation(args.isolation_runs, tmp / "isolation")
            print("isolation", json.dumps(result["isolation"], indent=2), flush=True)
    result["load_after"] = os.getloadavg()
    print("load average before", result["load_before"], "after", result["load_after"])
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(result, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
