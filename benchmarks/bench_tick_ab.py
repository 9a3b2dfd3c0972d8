"""Before/after of a change: the per-tick cost ratio of the reference deployments at two revisions,
measured alternately in one sitting on the CPU clock.

    python benchmarks/bench_tick_ab.py BASE [HEAD] [--deployments proves_ref,adcs_ref,coursework]
                                       [--duration S] [--rounds N]

``BASE`` and ``HEAD`` (default: the work tree) are git revisions of this repository; each one's
``src`` is exported to a temporary folder and every measurement runs in a child process with that
folder first on ``PYTHONPATH``, revision after revision, round after round, so that both see the
same load. A measurement flies the deployment for ``--duration`` simulated seconds in four pieces,
each followed by the same length of its plant-only counterpart (``detumble.tools.bench``: the
runner on the deployment's scenario with the matching law), timed with ``time.thread_time`` —
a loaded shared machine moves wall-clock times by 2-4x and CPU times far less. Printed per
deployment and revision: the fastest piece of each side over all rounds (µs a tick) and their
ratio. It uses only interfaces both revisions have (the topology loader, ``Deployment``, the
plant-only runner), so older revisions can be measured too. Timings are never asserted anywhere.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import subprocess
import sys
import tarfile
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]

#: deployment -> (plant-only law, fastest rate group, its period in s)
DEPLOYMENTS = {
    "proves_ref": ("bdot", "ReferenceDeployment.rateGroup50Hz", 0.02),
    "adcs_ref": ("bdot", "ReferenceDeployment.rateGroup50Hz", 0.02),
    "coursework": ("wheels_pd", "CourseworkDeployment.rateGroup100Hz", 0.01),
}

_CHILD = r"""
import json, sys, time
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
from detumble.sim.runner import run as plant_only
topology, law, group_name = sys.argv[1], sys.argv[3], sys.argv[4]
duration, tick_s = float(sys.argv[2]), float(sys.argv[5])
loaded = load_topology(topology)
deployment = Deployment(loaded)
scenario = loaded.resources["spacecraft"].scenario
group = loaded.topology.instance(group_name).component
deployment.start()
cpu = time.thread_time
dep, plant = [], []
for _ in range(4):
    c0, t0 = group.cycles, cpu()
    deployment.run_for(duration / 4)
    dep.append((cpu() - t0) / (group.cycles - c0) * 1e6)
    t0 = cpu()
    s = plant_only(scenario, law=law, duration_s=duration / 4).summary
    plant.append((cpu() - t0) / s["sim_seconds"] * tick_s * 1e6)
print(json.dumps({"deployment_us": min(dep), "plant_only_us": min(plant)}))
"""


def _export(revision: str | None, into: pathlib.Path) -> pathlib.Path:
    """The ``src`` folder of ``revision`` (None: the work tree's own)."""
    if revision is None:
        return ROOT / "src"
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", revision, "src"], capture_output=True, check=False)
    if archive.returncode:
        raise SystemExit(f"bench_tick_ab: git archive {revision}: {archive.stderr.decode().strip()}")
    tar_path = into / "src.tar"
    tar_path.write_bytes(archive.stdout)
    with tarfile.open(tar_path) as tar:
        tar.extractall(into, filter="data")
    return into / "src"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("base", help="git revision before the change")
    parser.add_argument("head", nargs="?", help="git revision after it (default: the work tree)")
    parser.add_argument("--deployments", default=",".join(DEPLOYMENTS), help="comma-separated, from "
                        + ", ".join(DEPLOYMENTS))
    parser.add_argument("--duration", type=float, default=300.0, help="simulated seconds a measurement")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)
    names = [n for n in args.deployments.split(",") if n]
    unknown = [n for n in names if n not in DEPLOYMENTS]
    if unknown:
        print(f"bench_tick_ab: unknown deployment(s) {', '.join(unknown)}; known: {', '.join(DEPLOYMENTS)}",
              file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        trees = {}
        for label, revision in (("base " + args.base, args.base), ("head " + (args.head or "work tree"), args.head)):
            folder = pathlib.Path(tmp) / str(len(trees))
            folder.mkdir()
            trees[label] = _export(revision, folder)
        best: dict[tuple[str, str], list[float]] = {}
        for _ in range(args.rounds):
            for name in names:
                law, group, tick_s = DEPLOYMENTS[name]
                topology = ROOT / "deployments" / name / "topology.yaml"
                for label, src in trees.items():
                    done = subprocess.run(
                        [sys.executable, "-c", _CHILD, str(topology), str(args.duration), law, group, str(tick_s)],
                        env=dict(os.environ, PYTHONPATH=str(src)), capture_output=True, text=True, check=False)
                    if done.returncode:
                        print(f"bench_tick_ab: {name} at {label} failed:\n{done.stderr[-2000:]}", file=sys.stderr)
                        return 1
                    figures = json.loads(done.stdout.strip().splitlines()[-1])
                    mins = best.setdefault((name, label), [float("inf"), float("inf")])
                    mins[0] = min(mins[0], figures["deployment_us"])
                    mins[1] = min(mins[1], figures["plant_only_us"])
    for (name, label), (dep, plant) in best.items():
        print(f"{name:11s} {label:24s} deployment {dep:6.1f} µs / plant-only {plant:6.1f} µs a tick "
              f"= {dep / plant:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
