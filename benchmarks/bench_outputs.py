#!/usr/bin/env python3
"""What a ``fprime-lite run``'s outputs cost: the same flight with and without them, like for like.

    python benchmarks/bench_outputs.py [TOPOLOGY] [--duration S] [--rounds N] [--writer-process]
                                       [--vs-basilisk] [--base-src OTHER/src] [--json FILE]

Each round flies two kinds, each in a fresh child process that has already imported what both need:

- ``deployment``: load the topology, ``Deployment(...).start()``, ``run_for(duration)``: no output;
- ``run``: load the topology, ``run_deployment(..., plots=False)`` into a temporary folder: every
  output ``fprime-lite run --no-plots --writer inline`` writes (events.log, channels.csv,
  channels_wide.csv, truth.csv, summary.json, dictionary.json), all in the flight's process;
- ``run_process`` (with ``--writer-process``): the same outputs, the telemetry files and truth rows
  formatted by the writer process (``--writer process``, what ``fprime-lite run`` does on two cores).
  Its CPU seconds are the flight's process's only; its wall time is the measure.

Both are timed from the same point (after the imports, before the load) to the last file written
(before the temporary folder is removed), on the wall clock and in CPU seconds of the child
(``time.process_time``: steadier on a shared machine). The outputs' share of a run is
``1 − deployment / run`` of the fastest rounds (issue 32's goal: ≤ 10 %), and
``1 − deployment / run_process`` with the writer process.

**Whole-process timing** (``process_wall_s``): each child is also timed from outside, from its start
to its exit (the interpreter's start, the imports — the ``run`` kinds import the runner, the
``deployment`` kind only what it flies with —, the load, the flight, the outputs, the writer process's
join and the interpreter's exit); ``outputs_share_process_wall`` (and ``…_writer_process``) is the
outputs' share by that measure, like for like. ``benchmarks/bench_vs_basilisk.py``'s kinds
``fprime_lite_run_50hz`` and ``fprime_lite_deployment_50hz`` are not like for like: the first is
timed from before its imports, the second only around ``run_for`` (it times ``run`` as users run it,
for the comparison with Basilisk), so their difference also holds the imports, the topology's load
and the start (about 0.3 s of a one-orbit run: docs/performance.md, "Issue 32: … (outputs lane,
2026-12-04)"). ``--vs-basilisk`` flies those two kinds too (the same child code, imported from
``benchmarks/basilisk/bench.py``), so that both measures come from one sitting: ``outputs_share_vs_basilisk``
is ``1 − deployment / run`` by their own timings.

The children run with Python's bytecode cache on (``basilisk.bench``'s ``_child_env``, warmed before the
first round), as ``bench_vs_basilisk.py``'s do: a user's install runs from compiled bytecode, and the
whole-process timing would otherwise count the compilation of every module imported.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import time

REPO = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "benchmarks"))
from basilisk.bench import _DEPLOYMENT, _RUN, _child_env, _warm_bytecode  # noqa: E402  (benchmarks/ on the path)

_CHILD = """
import json, sys, tempfile, time
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
kind, topology, duration = sys.argv[1], sys.argv[2], float(sys.argv[3])
if kind != "deployment":  # the runner's imports are part of what the outputs cost (whole-process timing)
    from fprime_lite.tools.runner import run_deployment
wall0, cpu0 = time.perf_counter(), time.process_time()
loaded = load_topology(topology)
if kind == "deployment":
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(duration)
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
else:
    with tempfile.TemporaryDirectory() as out:
        run_deployment(loaded, out, duration_s=duration, plots=False, quiet=True, allow_warnings=True,
                       writer="process" if kind == "run_process" else "inline")
        wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0  # before the folder's removal
print(json.dumps({"wall_s": wall, "cpu_s": cpu}))
"""

KINDS = ("deployment", "run")
#: bench_vs_basilisk.py's two fprime-lite kinds of proves_ref (their own timing windows; ``--vs-basilisk``)
VS_BASILISK = {"vs_basilisk_deployment": _DEPLOYMENT, "vs_basilisk_run": _RUN}


def _env(src: str | None) -> dict[str, str]:
    """The children's environment (:func:`basilisk.bench._child_env`); with ``src``, that folder's
    ``fprime_lite`` and ``detumble`` first on the path (another checkout's ``src``: ``--base-src``)."""
    env = _child_env()
    if src is not None:
        env["PYTHONPATH"] = os.pathsep.join([str(src), env["PYTHONPATH"]])
    return env


def fly(kind: str, topology: str, duration_s: float, src: str | None = None) -> dict:
    """One child's ``{"wall_s", "cpu_s", "process_wall_s"}``: its own timing of the load, flight and
    outputs, and the whole process's wall time seen from here (start to exit). ``src``: fly that
    folder's sources (default: what the environment's ``PYTHONPATH`` and install give)."""
    if kind in VS_BASILISK:
        argv = [sys.executable, "-c", VS_BASILISK[kind].format(topology=topology, duration=duration_s)]
    else:
        argv = [sys.executable, "-c", _CHILD, kind, topology, str(duration_s)]
    wall0 = time.perf_counter()
    out = subprocess.run(argv, capture_output=True, text=True, check=True, cwd=REPO, env=_env(src))
    process_wall = time.perf_counter() - wall0
    figures = json.loads(out.stdout.strip().splitlines()[-1])
    return {"wall_s": figures["wall_s"], "cpu_s": figures.get("cpu_s"), "process_wall_s": process_wall}


#: What each kind's best round keeps: the child's own timing and the whole process's wall time.
MEASURES = ("wall_s", "cpu_s", "process_wall_s")


def _figures(runs: dict[str, list[dict]]) -> dict:
    """Each kind's best (fastest round in each measure) and median rounds, and the outputs' shares."""
    kinds = tuple(runs)

    def pick(kind: str, m: str, how) -> float | None:
        values = [r[m] for r in runs[kind] if r.get(m) is not None]
        return how(values) if values else None

    best = {k: {m: pick(k, m, min) for m in MEASURES} for k in kinds}
    median = {k: {m: pick(k, m, statistics.median) for m in MEASURES} for k in kinds}

    def share(kind: str, m: str) -> float:
        return 1.0 - best["deployment"][m] / best[kind][m]

    result = {"best": best, "median": median, "runs": runs,
              "outputs_share_wall": share("run", "wall_s"), "outputs_share_cpu": share("run", "cpu_s"),
              "outputs_share_process_wall": share("run", "process_wall_s")}
    if "run_process" in kinds:
        result["outputs_share_wall_writer_process"] = share("run_process", "wall_s")
        result["outputs_share_cpu_writer_process"] = share("run_process", "cpu_s")
        result["outputs_share_process_wall_writer_process"] = share("run_process", "process_wall_s")
    if "vs_basilisk_run" in kinds:
        result["outputs_share_vs_basilisk"] = 1.0 - (best["vs_basilisk_deployment"]["wall_s"]
                                                     / best["vs_basilisk_run"]["wall_s"])
    return result


def measure(topology: str, duration_s: float, rounds: int, kinds=KINDS, fly=fly, base_src: str | None = None) -> dict:
    """Each kind's fastest wall, CPU and whole-process seconds over ``rounds`` alternating rounds, and the
    outputs' share by each measure (``1 − deployment / run``). ``base_src``: each round also flies every
    kind with that folder's sources first (another revision's ``src``, before/after in one sitting); its
    figures under ``"base"``, this checkout's (its ``src``) at the top."""
    trees: list[str | None] = [None] if base_src is None else [str(base_src), str(REPO / "src")]
    runs: dict = {tree: {k: [] for k in kinds} for tree in trees}
    for _ in range(rounds):
        for tree in trees:
            for kind in kinds:
                runs[tree][kind].append(fly(kind, topology, duration_s) if tree is None
                                        else fly(kind, topology, duration_s, src=tree))
    result = {"topology": topology, "duration_s": duration_s, "rounds": rounds, **_figures(runs[trees[-1]])}
    if base_src is not None:
        result["src"] = trees[-1]
        result["base"] = {"src": trees[0], **_figures(runs[trees[0]])}
    return result


def _print(result: dict) -> None:
    for kind, b in result["best"].items():
        cpu = f"{b['cpu_s']:8.3f} s" if b["cpu_s"] is not None else "       —  "
        print(f"{kind:22s} wall {b['wall_s']:8.3f} s   cpu {cpu}   whole process {b['process_wall_s']:8.3f} s")
    print(f"outputs' share of a run: wall {result['outputs_share_wall']:.1%}, cpu {result['outputs_share_cpu']:.1%}, "
          f"whole process {result['outputs_share_process_wall']:.1%} (goal <= 10 %)")
    if "outputs_share_wall_writer_process" in result:
        print(f"with the writer process: wall {result['outputs_share_wall_writer_process']:.1%}, "
              f"cpu of the flight's process {result['outputs_share_cpu_writer_process']:.1%}, "
              f"whole process {result['outputs_share_process_wall_writer_process']:.1%}")
    if "outputs_share_vs_basilisk" in result:
        print(f"bench_vs_basilisk's kinds (their timing windows): {result['outputs_share_vs_basilisk']:.1%}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("topology", nargs="?", default="deployments/proves_ref/topology.yaml")
    parser.add_argument("--duration", type=float, default=5578.0, help="simulated seconds a flight (one orbit)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--json", help="also write the figures to this file")
    parser.add_argument("--writer-process", action="store_true",
                        help="also fly the kind run_process (the outputs formatted by the writer process)")
    parser.add_argument("--base-src", help="also fly each kind with this folder's sources in every round, first "
                        "(another revision's src/: before and after in one sitting)")
    parser.add_argument("--vs-basilisk", action="store_true",
                        help="also fly bench_vs_basilisk.py's two fprime-lite kinds (its timing windows)")
    args = parser.parse_args(argv)
    kinds = KINDS + (("run_process",) if args.writer_process else ()) + (tuple(VS_BASILISK) if args.vs_basilisk else ())
    _warm_bytecode()
    if args.base_src:
        subprocess.run([sys.executable, "-m", "compileall", "-q", args.base_src], capture_output=True, check=False,
                       env=_env(args.base_src))
    result = measure(args.topology, args.duration, args.rounds, kinds, base_src=args.base_src)
    if args.base_src:
        print(f"base: {args.base_src}")
        _print(result["base"])
        print(f"this checkout: {result['src']}")
    _print(result)
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(result, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
