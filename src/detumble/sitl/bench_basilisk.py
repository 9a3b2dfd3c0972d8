"""fprime-lite against Basilisk, side by side in one sitting (issue #19): the ``basilisk`` piece of
``fprime-lite bench`` and ``benchmarks/bench_vs_basilisk.py``.

Four kinds of run, each in a fresh child process, interleaved round by round so that every kind
sees the same load on a shared machine:

1. ``basilisk_20hz``: Basilisk, case A, dynamics and its Python B-dot at 20 Hz (0.05 s)
   (:mod:`detumble.sitl.basilisk_case_a`);
2. ``fprime_lite_plant_20hz``: the plant-only runner, case A, kopt law, 20 Hz (what
   ``fprime-lite sim case_a --law kopt`` flies);
3. ``basilisk_50hz``: Basilisk, case A at 50 Hz (0.02 s);
4. ``fprime_lite_deployment_50hz``: the whole F´ deployment of the topology at 50 Hz (every
   component, rate group, channel and event; ``fprime-lite run`` without its output files).

Each child times only its run proper (set-up excluded) and reports the real-time factor. The
figures are the fastest round of each kind, the ratios are formed from them, and the median
round's ratios are reported beside them. Both case-A runs report when |ω| < 1 °/s, a check that
the two sides simulate the same thing. Basilisk is optional: ``pip install -e '.[bsk]'`` (PyPI
name ``bsk``); without it the piece says so and measures nothing.
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import pathlib
import statistics
import subprocess
import sys

from fprime_lite.tools.plugins import BenchPiece

__all__ = ["measure", "basilisk_installed", "BASILISK_PIECE", "INSTALL_HINT"]

ORBIT_S = 5578.0  #: one case-A orbit (420 km), simulated seconds
INSTALL_HINT = "pip install -e '.[bsk]'  (Basilisk from PyPI, package bsk)"

_PLANT = """
import json
from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario
s = run(load_scenario("case_a"), law="kopt", duration_s={duration}).summary
print(json.dumps({{"sim_seconds": s["sim_seconds"], "wall_s": s["wall_seconds"],
                  "real_time_factor": s["sim_seconds"] / s["wall_seconds"],
                  "time_below_1_deg_s": s["time_below_1_deg_s"], "final_rate_deg_s": s["final_rate_deg_s"]}}))
"""

_DEPLOYMENT = """
import json, time
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
loaded = load_topology({topology!r})
deployment = Deployment(loaded)
deployment.start()
t0 = time.perf_counter()
deployment.run_for({duration})
wall = time.perf_counter() - t0
craft = loaded.resources.get("spacecraft")
rate = craft.truth().rate_deg_s if craft is not None else None
print(json.dumps({{"sim_seconds": {duration}, "wall_s": wall, "real_time_factor": {duration} / wall,
                  "final_rate_deg_s": rate}}))
"""


def basilisk_installed() -> bool:
    return importlib.util.find_spec("Basilisk") is not None


def _child(argv: list[str]) -> dict:
    done = subprocess.run(argv, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(argv[:3])}…: failed\n{done.stderr[-2000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def measure(topology, duration_s: float = ORBIT_S, rounds: int = 3, progress=None) -> dict:
    """Fly the four kinds ``rounds`` times, interleaved; figures and ratios (see the module doc)."""
    topology = str(pathlib.Path(topology).resolve())
    case_a = [sys.executable, "-m", "detumble.sitl.basilisk_case_a", "--duration", str(duration_s)]
    kinds = {
        "basilisk_20hz": case_a + ["--step", "0.05"],
        "fprime_lite_plant_20hz": [sys.executable, "-c", _PLANT.format(duration=duration_s)],
        "basilisk_50hz": case_a + ["--step", "0.02"],
        "fprime_lite_deployment_50hz": [sys.executable, "-c",
                                        _DEPLOYMENT.format(topology=topology, duration=duration_s)],
    }
    runs: dict[str, list[dict]] = {k: [] for k in kinds}
    for r in range(rounds):
        for kind, argv in kinds.items():
            runs[kind].append(_child(argv))
            if progress is not None:
                progress(f"round {r + 1}/{rounds} {kind}: {runs[kind][-1]['real_time_factor']:.0f}× real time")
    best = {k: max(x["real_time_factor"] for x in v) for k, v in runs.items()}
    median = {k: statistics.median(x["real_time_factor"] for x in v) for k, v in runs.items()}
    return {
        "installed": True,
        "topology": topology,
        "sim_seconds": duration_s,
        "rounds": rounds,
        "runs": runs,
        "best_real_time_factor": best,
        "median_real_time_factor": median,
        "plant_20hz_over_basilisk": best["fprime_lite_plant_20hz"] / best["basilisk_20hz"],
        "deployment_50hz_over_basilisk": best["fprime_lite_deployment_50hz"] / best["basilisk_50hz"],
        "median_plant_20hz_over_basilisk": median["fprime_lite_plant_20hz"] / median["basilisk_20hz"],
        "median_deployment_50hz_over_basilisk": median["fprime_lite_deployment_50hz"] / median["basilisk_50hz"],
        "case_a_time_below_1_deg_s": {"basilisk": runs["basilisk_20hz"][0]["time_below_1_deg_s"],
                                      "fprime_lite": runs["fprime_lite_plant_20hz"][0]["time_below_1_deg_s"]},
    }


def _rows(d: dict) -> list[tuple[str, str, str]]:
    if not d.get("installed"):
        return [("Basilisk side by side", f"not measured: Basilisk is not installed — {INSTALL_HINT}", "")]
    b = d["best_real_time_factor"]
    t = d["case_a_time_below_1_deg_s"]
    return [
        (f"case A 20 Hz, {d['sim_seconds']:.0f} s: fprime-lite plant-only / Basilisk (real-time factors, "
         f"best of {d['rounds']})",
         f"{b['fprime_lite_plant_20hz']:,.0f} / {b['basilisk_20hz']:,.0f} = {d['plant_20hz_over_basilisk']:.2f} "
         f"(median rounds {d['median_plant_20hz_over_basilisk']:.2f})", "≥ 3"),
        ("50 Hz: whole deployment / Basilisk case A",
         f"{b['fprime_lite_deployment_50hz']:,.0f} / {b['basilisk_50hz']:,.0f} = "
         f"{d['deployment_50hz_over_basilisk']:.2f} (median rounds {d['median_deployment_50hz_over_basilisk']:.2f})",
         "≥ 1.5"),
        ("case A |ω| < 1 °/s at: fprime-lite / Basilisk", f"{t['fprime_lite']} s / {t['basilisk']} s", ""),
    ]


def _measure(options: argparse.Namespace) -> dict:
    if not basilisk_installed():
        return {"installed": False, "how_to_install": INSTALL_HINT}
    duration = options.duration if options.duration is not None else ORBIT_S
    return measure(options.topology, duration, progress=lambda line: print(line, file=sys.stderr, flush=True))


#: The bench piece: ``basilisk`` in ``bench.json``.
BASILISK_PIECE = BenchPiece(name="basilisk", measure=_measure, rows=_rows)
