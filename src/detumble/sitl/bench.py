"""The detumble deployment's piece of ``fprime-lite bench``: the whole flight deployment against
its plant-only twin, interleaved piece by piece (reached through the ``fprime_lite.bench`` entry
points, pyproject.toml)."""
from __future__ import annotations

import argparse
import math
import statistics
import time

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.svc.rate_groups import RateGroupBase
from fprime_lite.tools.plugins import BenchPiece

__all__ = ["measure_deployment", "DEPLOYMENT_PIECE"]

#: The rate group whose cycles count as the deployment's ticks.
TICK_RATE_GROUP = "ReferenceDeployment.rateGroup50Hz"


def measure_deployment(topology, duration_s: float | None = None, chunks: int | None = None) -> dict:
    """The detumble deployment and its plant-only twin, interleaved chunk by chunk.

    The simulated time is flown in ``chunks`` pieces (default: one per 300 simulated seconds, at
    least eight); after each deployment piece the same length of plant-only flight (same scenario,
    50 Hz dynamics, the scenario's B-dot law) is timed. The tick-cost ratio compares the fastest
    piece of each: on a shared machine the fastest piece is the one least disturbed by other work,
    and interleaving exposes both to the same conditions. The median of the per-piece ratios is
    reported beside it as a check that does not depend on one quiet moment.
    """
    from detumble.sim.runner import run as plant_only

    loaded = load_topology(topology)
    deployment = Deployment(loaded)
    spacecraft = loaded.resources["spacecraft"]
    scenario = spacecraft.scenario
    orbit_s = 2.0 * math.pi / spacecraft.plant.orbit.mean_motion
    if duration_s is None:
        duration_s = round(orbit_s)
    rg50 = loaded.topology.instance(TICK_RATE_GROUP).component
    if not isinstance(rg50, RateGroupBase):
        raise ValueError(f"{TICK_RATE_GROUP} is a {type(rg50).__name__}, not a rate group")
    deployment.start()
    if chunks is None:
        chunks = max(8, round(duration_s / 300.0))
    chunk_s = duration_s / chunks
    deployment_us, plant_us = [], []
    wall = 0.0
    for _ in range(chunks):
        cycles0 = rg50.cycles
        t0 = time.perf_counter()
        deployment.run_for(chunk_s)
        elapsed = time.perf_counter() - t0
        wall += elapsed
        deployment_us.append(elapsed / max(1, rg50.cycles - cycles0) * 1e6)
        plant = plant_only(scenario, law="bdot", duration_s=chunk_s).summary
        plant_us.append(plant["wall_seconds"] / plant["steps"] * 1e6)
    timer = loaded.timer
    if timer is None:
        raise ValueError("the bench deployment has no rate-group timer (topology 'rate_groups')")
    return {
        "scenario": scenario.name,
        "sim_seconds": duration_s,
        "orbit_period_s": orbit_s,
        "chunks": chunks,
        "deployment_wall_s": wall,
        "real_time_factor": duration_s / wall,
        "base_ticks_per_s": timer.driver.tick / wall,
        "ticks_50hz_per_s": rg50.cycles / wall,
        "deployment_us_per_tick": min(deployment_us),
        "deployment_us_per_tick_median": sorted(deployment_us)[len(deployment_us) // 2],
        "plant_only_us_per_tick": min(plant_us),
        "plant_only_us_per_tick_median": sorted(plant_us)[len(plant_us) // 2],
        "tick_cost_ratio": min(deployment_us) / min(plant_us),
        "tick_cost_ratio_median_of_pieces": statistics.median(
            d / p for d, p in zip(deployment_us, plant_us, strict=True)),
        "pieces_us_per_tick": {"deployment": deployment_us, "plant_only": plant_us},
        "final_rate_deg_s": spacecraft.truth().rate_deg_s,
        "plant_implementation": spacecraft.plant.implementation,  # both sides' (detumble.sim.plant_kernel)
    }


def _rows(d: dict) -> list[tuple[str, str, str]]:
    return [
        (f"deployment, {d['sim_seconds']:.0f} s simulated", f"{d['deployment_wall_s']:.1f} s wall", ""),
        ("real-time factor", f"{d['real_time_factor']:,.0f}×", ""),
        ("base ticks (1 kHz) per wall second", f"{d['base_ticks_per_s']:,.0f}", ""),
        ("50 Hz ticks per wall second", f"{d['ticks_50hz_per_s']:,.0f}", ""),
        ("per 50 Hz tick: deployment / plant-only (fastest piece)",
         f"{d['deployment_us_per_tick']:.1f} µs / {d['plant_only_us_per_tick']:.1f} µs = {d['tick_cost_ratio']:.2f}",
         "≤ 1.5"),
        ("per 50 Hz tick, medians",
         f"{d['deployment_us_per_tick_median']:.1f} µs / {d['plant_only_us_per_tick_median']:.1f} µs", ""),
        (f"median of the {d['chunks']} pieces' ratios", f"{d['tick_cost_ratio_median_of_pieces']:.2f}", ""),
        ("plant (deployment and plant-only alike)", d.get("plant_implementation", "python"), ""),
    ]


def _measure(options: argparse.Namespace) -> dict:
    return measure_deployment(options.topology, options.duration)


#: The bench piece: ``deployment`` in ``bench.json``.
DEPLOYMENT_PIECE = BenchPiece(name="deployment", measure=_measure, rows=_rows)
