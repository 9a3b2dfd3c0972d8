"""Campaign engine at scale (issue 31's targets), measured, not asserted.

Run: ``python benchmarks/bench_campaign_scale.py [--runs 20000] [--rows 100000] [--json FILE]``.

1. **Client throughput**: a campaign of ``--runs`` runs of the test probe kind's ``instant`` mode (a
   run that does nothing: what is left is the engine) on an embedded cluster of 2 workers, timed
   from ``run_campaign`` call to DataFrame with the cluster already up (``client=``); and where the
   time goes: the plan of a fresh campaign (one SeedSequence per run), a worker's own cost per run
   (``execute_batch`` in this process), and the client's own per-row cost (the row recorded in a
   parquet part per batch, pruner, progress) on synthetic rows. Goal ≥ 2,000 results/s.
2. **Resume and report of a 100k-row campaign**: ``--rows`` finished rows are recorded (as a
   finished campaign leaves them: one compacted part of ``results.parts/``), then
   ``run_campaign(..., resume=True)`` — plan, pre-flight, read the parts, nothing to run, write
   results.parquet, print the summary — is timed twice: without
   the folder's plan cache, then with it (as a campaign leaves its folder); the plots separately.
   Goal ≤ 10 s.
3. **Broken files reaching a worker**: every file of tests/data/campaign_broken/ through
   ``run_campaign`` with the cluster replaced by a counter. Goal 0.
4. **Bit-identity across CPUs**: dispersed values (vectors, rotations, inertias) drawn in
   subprocesses under OpenBLAS's Prescott, Nehalem, Haswell and SkylakeX kernels
   (``OPENBLAS_CORETYPE``): the engine's draws, and the same draws normalised with numpy's BLAS
   (``np.linalg.norm``, ``@``) as the engine did before; the number of distinct results of each.

The machine may be shared: the load average is printed; figures under load are not benchmarks.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import textwrap
import time

REPO = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
PROBE = "tests.fprime_lite.tools.campaign.probe_kinds:PROBE_RUN"


def _campaign(folder: pathlib.Path, runs: int, name: str) -> pathlib.Path:
    points = 100
    path = folder / f"{name}.yaml"
    path.write_text(textwrap.dedent(f"""\
        campaign: {name}
        run: {{kind: "{PROBE}", mode: instant}}
        grid:
          x: {{range: [1, {points}, 1]}}
        seeds: {max(1, runs // points)}
        metrics: [value]
        """))
    return path


def throughput(runs: int, folder: pathlib.Path) -> dict:
    from distributed import Client

    from fprime_lite.tools.campaign import run_campaign
    from fprime_lite.tools.campaign.cluster import dask_client

    path = _campaign(folder, runs, "throughput")
    with dask_client(2) as (client, _):
        assert isinstance(client, Client)
        t0 = time.perf_counter()
        df = run_campaign(path, client=client, out=folder / "tp", plots=False, summary=False)
        wall = time.perf_counter() - t0
    return {"runs": len(df), "wall_s": wall, "results_per_s": len(df) / wall, "ok": int((df["status"] == "ok").sum())}


def plan_cost(runs: int, folder: pathlib.Path) -> dict:
    """The client's plan of a fresh campaign (run ids and seeds: one SeedSequence per run)."""
    from fprime_lite.tools.campaign import load_campaign
    from fprime_lite.tools.campaign.plan import plan_runs

    c = load_campaign(_campaign(folder, runs, "plan"))
    t0 = time.perf_counter()
    tasks = plan_runs(c, folder / "plan-runs", draw=False)
    wall = time.perf_counter() - t0
    return {"runs": len(tasks), "wall_s": wall, "us_per_run": wall / len(tasks) * 1e6}


def worker_side_cost(runs: int, folder: pathlib.Path) -> dict:
    """A worker's own work per instant run (build, read back, metrics, row), in this process, in
    batches of 500 as the engine sends them (pickled)."""
    import pickle

    from fprime_lite.tools.campaign import load_campaign
    from fprime_lite.tools.campaign.plan import plan_runs
    from fprime_lite.tools.campaign.task import execute_batch

    tasks = plan_runs(load_campaign(_campaign(folder, runs, "worker")), folder / "worker-runs")
    blobs = [pickle.dumps(tasks[i:i + 500], protocol=pickle.HIGHEST_PROTOCOL) for i in range(0, len(tasks), 500)]
    execute_batch(blobs[0])  # imports and plug-ins are not the per-run cost
    t0 = time.perf_counter()
    rows = [r for b in blobs for r in execute_batch(b)]
    wall = time.perf_counter() - t0
    return {"runs": len(rows), "wall_s": wall, "us_per_run": wall / len(rows) * 1e6,
            "row_pickle_bytes": len(pickle.dumps(rows[:500])) / 500}


def client_side_cost(rows: int, folder: pathlib.Path) -> dict:
    """The client's own work per result: the row recorded (a parquet part per batch), pruner,
    progress update, and the table written at the end."""
    from fprime_lite.tools.campaign.keep import ArtifactPruner, KeepPolicy
    from fprime_lite.tools.campaign.report import progress_bar
    from fprime_lite.tools.campaign.results import ResultStore

    store = ResultStore(folder / "cs", ["x"], ["value"])
    pruner = ArtifactPruner(folder / "cs" / "runs", KeepPolicy("ranked", best=5, by="value"))
    import pandas  # noqa: F401 - imports are not the client's per-row cost
    import pyarrow.parquet  # noqa: F401

    made = [{"run_id": f"{i:016x}", "point": i % 100, "seed_index": i // 100, "seed": i, "status": "ok",
             "error": None, "values": {"x": float(i % 100)}, "metrics": {"value": float(i % 977)},
             "notes": "{}", "requested": "{}", "wall_s": 1e-4, "cpu_s": 1e-4, "worker": "w", "worker_address": None}
            for i in range(rows)]
    t0 = time.perf_counter()
    with progress_bar(rows, 0, False, log_every_s=3600) as update:
        for r in made:
            store.add(r)
            pruner.update(r)
            update(r)
    store.close()
    wall = time.perf_counter() - t0
    return {"rows": rows, "wall_s": wall, "rows_per_s": rows / wall}


def resume_and_report(rows: int, folder: pathlib.Path) -> dict:
    import io

    from rich.console import Console

    from fprime_lite.tools.campaign import load_campaign, run_campaign
    from fprime_lite.tools.campaign.plan import plan_runs

    path = _campaign(folder, rows, "big")
    out = folder / "big"
    out.mkdir()
    c = load_campaign(path)
    t0 = time.perf_counter()
    tasks = plan_runs(c, out / "runs", draw=False)
    plan_s = time.perf_counter() - t0
    from fprime_lite.tools.campaign.results import ResultStore

    store = ResultStore(out, ["x"], ["value"])  # the parts a finished campaign leaves (compacted into one)
    for t in tasks:
        x = t["values"]["x"]
        store.add({"run_id": t["run_id"], "point": t["point"], "seed_index": t["seed_index"],
                   "seed": t["seed"], "status": "ok", "error": None, "values": {"x": float(x)},
                   "metrics": {"value": 2.0 * x}, "notes": "{}", "requested": json.dumps({"x": x}),
                   "wall_s": 1e-4, "cpu_s": 1e-4, "worker": "w", "worker_address": None})
    store.close()
    timings = []
    for _ in range(2):  # the first without the folder's plan cache, the second with it (what a campaign leaves)
        t0 = time.perf_counter()
        df = run_campaign(path, workers=1, out=out, resume=True, plots=False, summary=True,
                          console=Console(file=io.StringIO(), width=120))
        timings.append(time.perf_counter() - t0)
    from fprime_lite.tools.campaign.plots import draw_plots

    t0 = time.perf_counter()
    draw_plots(df, c, out / "plots")
    plots_s = time.perf_counter() - t0
    return {"rows": len(df), "plan_s": plan_s, "resume_and_report_s_without_plan_cache": timings[0],
            "resume_and_report_s": timings[1], "plots_s": plots_s}


def broken_files() -> dict:
    import fprime_lite.tools.campaign.cluster as cluster
    from fprime_lite.model.errors import FprimeLiteError
    from fprime_lite.tools.campaign import run_campaign

    reached: list[str] = []

    class ReachedError(Exception):
        pass

    def counter(*args, **kwargs):
        raise ReachedError

    real = cluster.dask_client
    cluster.dask_client = counter
    files = sorted((REPO / "tests" / "data" / "campaign_broken").glob("*.yaml"))
    refused = 0
    try:
        for f in files:
            with tempfile.TemporaryDirectory() as tmp:
                try:
                    run_campaign(f, workers=1, out=pathlib.Path(tmp) / "o", plots=False, summary=False)
                except ReachedError:
                    reached.append(f.name)
                except FprimeLiteError:
                    refused += 1
    finally:
        cluster.dask_client = real
    return {"files": len(files), "refused_before_any_run": refused, "reached_a_worker": len(reached),
            "reached": reached}


SAMPLER = r"""
import hashlib, json, math, sys
import numpy as np
from fprime_lite.tools.campaign.dispersions import parse_dispersion
from fprime_lite.tools.campaign.seeding import key_generator, run_seed_sequence
specs = {"v": {"dist": "random_vector", "magnitude": {"dist": "uniform", "low": 5, "high": 180}},
         "q": {"dist": "random_rotation"},
         "j": {"dist": "inertia", "nominal": [[2.2e-3, 2e-5, -1.5e-5], [2e-5, 2.15e-3, 1e-5], [-1.5e-5, 1e-5, 2.05e-3]],
               "moment_std": 0.05, "axis_angle_deg": 10}}
engine, blas = [], []
for key, spec in specs.items():
    d = parse_dispersion(spec, key)
    for i in range(1000):
        engine.append(d.sample(key_generator(run_seed_sequence(2026, {"i": i}, 0), key)))
for i in range(1000):  # the former normalisation: BLAS dnrm2 and dgemm
    rng = key_generator(run_seed_sequence(2026, {"i": i}, 0), "v")
    m = 5 + 175 * rng.random(())
    g = rng.standard_normal(3)
    blas.append((m * (g / np.linalg.norm(g))).tolist())
    a = rng.standard_normal((3, 3))
    blas.append((a @ a @ a.T).tolist())
out = {k: [json.dumps(x, default=float.hex) for x in v] for k, v in (("engine", engine), ("blas", blas))}
print(json.dumps(out))
"""


def cpu_identity(folder: pathlib.Path) -> dict:
    script = folder / "sampler.py"
    script.write_text(SAMPLER)
    results = {}
    for core in ("Prescott", "Nehalem", "Haswell", "SkylakeX"):
        env = dict(os.environ, OPENBLAS_CORETYPE=core)
        r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env, timeout=300)
        if r.returncode != 0:
            raise RuntimeError(r.stderr)
        results[core] = json.loads(r.stdout)
    out = {}
    for which in ("engine", "blas"):
        variants = [results[c][which] for c in results]
        n = len(variants[0])
        differing = sum(1 for i in range(n) if len({v[i] for v in variants}) > 1)
        out[which] = {"values": n, "values_differing_across_kernels": differing,
                      "distinct_tables": len({json.dumps(v) for v in variants})}
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=20_000)
    ap.add_argument("--rows", type=int, default=100_000)
    ap.add_argument("--json", metavar="FILE")
    ap.add_argument("--only", choices=["throughput", "resume"], help="measure only this (and the costs behind it)")
    args = ap.parse_args(argv)
    report = {"load_before": os.getloadavg(), "cpus": os.cpu_count()}
    steps = [("broken_files", "broken files", broken_files),
             ("cpu_identity", "bit-identity across BLAS kernels", cpu_identity),
             ("plan", "plan (client, fresh campaign)", lambda folder: plan_cost(args.runs, folder)),
             ("worker_side", "worker-side cost", lambda folder: worker_side_cost(args.runs, folder)),
             ("client_side", "client-side cost", lambda folder: client_side_cost(args.runs, folder)),
             ("throughput", "throughput", lambda folder: throughput(args.runs, folder)),
             ("resume_and_report", "100k resume and report", lambda folder: resume_and_report(args.rows, folder))]
    chosen = {None: [s[0] for s in steps], "throughput": ["plan", "worker_side", "client_side", "throughput"],
              "resume": ["resume_and_report"]}[args.only]
    with tempfile.TemporaryDirectory(prefix="bench-campaign-scale-") as tmp:
        folder = pathlib.Path(tmp)
        for key, label, step in steps:
            if key in chosen:
                report[key] = step() if step is broken_files else step(folder)
                print(f"{label}:", report[key], flush=True)
    report["load_after"] = os.getloadavg()
    print("load average before/after:", report["load_before"], report["load_after"])
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(report, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
