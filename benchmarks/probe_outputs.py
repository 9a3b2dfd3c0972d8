#!/usr/bin/env python3
"""Probes behind docs/performance.md's "Issue 32: the last points of a run's outputs" (one orbit of proves_ref).

    python benchmarks/probe_outputs.py startup           # imports, load and start, timed in one process
    python benchmarks/probe_outputs.py closes [--writer inline|process]
    python benchmarks/probe_outputs.py fork plain|fork   # the flight alone, or after forking an idle child
    python benchmarks/probe_outputs.py busy SECONDS      # a Python formatting loop (pin it: taskset -c 1 …)

``startup``: what ``bench_vs_basilisk.py``'s ``fprime_lite_run_50hz`` kind times and its
``fprime_lite_deployment_50hz`` kind does not (the imports, ``load_topology``, ``Deployment(...).start()``).
``closes``: ``fprime-lite run --no-plots`` (``run_deployment``) with the wall time of each output step summed
(the writer process's fork, the dictionary, the sends, the truth rows, the closes at the end), the run's
wall and CPU seconds. ``fork``: a no-output flight's CPU seconds, with ``fork`` after an ``os.fork()`` whose
child waits on a pipe (the copy-on-write the writer process's fork costs the flight; count the page faults
with ``perf stat -e page-faults --no-inherit``). ``busy``: the load to put on the other core beside
``fork plain`` pinned to the first (``taskset -c 0``).
"""

from __future__ import annotations

import argparse
import csv
import functools
import io
import os
import sys
import tempfile
import time

TOPOLOGY = "deployments/proves_ref/topology.yaml"
ORBIT_S = 5578.0


def startup() -> None:
    t0 = time.perf_counter()
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology_loader import load_topology
    t1 = time.perf_counter()
    from fprime_lite.tools.runner import run_deployment  # noqa: F401  (its import is what is timed)
    t2 = time.perf_counter()
    loaded = load_topology(TOPOLOGY)
    t3 = time.perf_counter()
    Deployment(loaded).start()
    t4 = time.perf_counter()
    print(f"import deployment+loader {t1 - t0:.3f} s, the runner {t2 - t1:.3f} s, load {t3 - t2:.3f} s, "
          f"Deployment+start {t4 - t3:.3f} s")


def closes(writer: str) -> None:
    from fprime_lite.deploy.topology_loader import load_topology
    from fprime_lite.ground import downlink, writer_process
    from fprime_lite.tools import runner
    from detumble.reports import detumble_report

    spent: dict[str, float] = {}

    def timed(owner, name: str, label: str) -> None:
        f = getattr(owner, name)

        @functools.wraps(f)
        def wrapper(*args, **kwargs):
            t = time.perf_counter()
            try:
                return f(*args, **kwargs)
            finally:
                spent[label] = spent.get(label, 0.0) + time.perf_counter() - t

        setattr(owner, name, wrapper)

    timed(writer_process.OutputWriter, "__init__", "fork")
    timed(writer_process.OutputWriter, "_send", "sends")
    timed(writer_process.OutputWriter, "close", "writer close (waits for the child)")
    timed(runner, "write_dictionary", "dictionary (here)")
    timed(downlink.GroundRecorder, "close", "recorder close")
    timed(detumble_report.DetumbleRunReport, "_sample", "truth rows")
    timed(detumble_report.DetumbleRunReport, "finish", "report finish (truth.csv's close)")
    loaded = load_topology(TOPOLOGY)
    wall0, cpu0 = time.perf_counter(), time.process_time()
    with tempfile.TemporaryDirectory() as out:
        runner.run_deployment(loaded, out, duration_s=ORBIT_S, plots=False, quiet=True, allow_warnings=True,
                              writer=writer)
        wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    print(f"{writer}: wall {wall:.3f} s, cpu {cpu:.3f} s")
    for label, seconds in spent.items():
        print(f"  {label:36s} {seconds * 1000:8.1f} ms")


def fork(kind: str) -> None:
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology_loader import load_topology

    loaded = load_topology(TOPOLOGY)
    cpu0 = time.process_time()
    if kind == "fork":
        r, w = os.pipe()
        pid = os.fork()
        if pid == 0:
            os.read(r, 1)
            os._exit(0)
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(ORBIT_S)
    if kind == "fork":
        os.write(w, b"x")
        os.waitpid(pid, 0)
    print(f"{kind}: cpu {time.process_time() - cpu0:.3f} s")


def busy(seconds: float) -> None:
    end = time.time() + seconds
    buffer = io.StringIO()
    rows = csv.writer(buffer)
    while time.time() < end:
        for i in range(1000):
            rows.writerow([i * 1.000001, f"{i:.6f}", "abc", i])
        if buffer.tell() > 1 << 24:
            buffer = io.StringIO()
            rows = csv.writer(buffer)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("probe", choices=("startup", "closes", "fork", "busy"))
    parser.add_argument("arg", nargs="?")
    parser.add_argument("--writer", default="process", choices=("inline", "process"))
    args = parser.parse_args(argv)
    if args.probe == "startup":
        startup()
    elif args.probe == "closes":
        closes(args.writer)
    elif args.probe == "fork":
        fork(args.arg or "plain")
    else:
        busy(float(args.arg or 60))
    return 0


if __name__ == "__main__":
    sys.exit(main())
