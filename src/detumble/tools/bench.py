"""The detumble deployments' piece of ``fprime-lite bench``: each flight deployment against its
plant-only counterpart, interleaved piece by piece (reached through the ``fprime_lite.bench``
entry points, pyproject.toml).

The plant-only counterpart of a deployment flies the same scenario — the same plant configuration:
coils or rods, reaction wheels, star tracker, sensors, dynamics step — in the plant-only runner
(:func:`detumble.sim.runner.run`) with the plain-Python law that matches the deployment's
controller (:data:`PLANT_ONLY_LAWS`). Its cost per deployment tick (the deployment's fastest rate
group) is its wall time per simulated second times the tick period. The difference of the two,
the **F´ part of a tick** (µs), is what the framework, the flight components' F´ side and the
simulated drivers add to the same flight software and physics: issue 32 reports it for every
deployment, with a goal of ≤ 22 µs for adcs_ref (whose counterpart flies the same three-mode law
to the last bit). Their ratio is kept in the figures as context (the retired ≤ 1.5 goal).

The measured topology is the one given; when it is one of the repository's reference deployments
(``deployments/<name>/topology.yaml``), the other reference deployments beside it are measured too
(:data:`REFERENCE_DEPLOYMENTS`), one after the other, each with the same ``--duration``.
"""
from __future__ import annotations

import argparse
import math
import pathlib
import statistics
import time

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.svc.rate_groups import RateGroupBase
from fprime_lite.tools.plugins import BenchPiece

__all__ = ["measure_deployment", "tick_rate_group", "DEPLOYMENT_PIECE", "PLANT_ONLY_LAWS", "REFERENCE_DEPLOYMENTS",
           "SECOND_COUNTERPARTS", "FPRIME_PART_GOALS_US"]

#: Reference deployment (folder under ``deployments/``) -> the plant-only law of its counterpart:
#: proves_ref's DetumbleManager flies B-dot; adcs_ref's AttitudeController is flown plant-only by
#: ``adcs`` (:mod:`detumble.sim.adcs_law`: the same three modes, MEKF, rate observer, PD, wheel
#: allocation and dumping, at the same 50 Hz tick and 10 Hz cycle); coursework's CourseworkController
#: flies the start-up sequence's wheels_pd.
REFERENCE_DEPLOYMENTS = {"proves_ref": "bdot", "adcs_ref": "adcs", "coursework": "wheels_pd"}
#: Scenario name -> plant-only law, for a topology given by path.
PLANT_ONLY_LAWS = {"default": "bdot", "adcs": "adcs", "surrey": "wheels_pd"}
#: Plant-only law -> further counterparts timed beside it (a second row), so that a figure of an
#: earlier comparison stays available: until 2026-12-01 adcs_ref was compared with a bare B-dot.
SECOND_COUNTERPARTS = {"adcs": ("bdot",)}
#: Plant-only law -> issue 32's goal for the F´ part of the deployment's tick (µs). Only adcs_ref has
#: one: its counterpart is the same flight software without the framework.
FPRIME_PART_GOALS_US = {"adcs": 22.0}


def tick_rate_group(loaded) -> tuple[RateGroupBase, float]:
    """The deployment's fastest rate group (smallest divisor of its driver) and its period, s."""
    timer = loaded.timer
    if timer is None:
        raise ValueError("the bench deployment has no rate-group timer (topology 'rate_groups')")
    driver = timer.driver
    port = driver.output_port("CycleOut")
    best = None
    for i, divider in enumerate(driver.dividers):
        target = port.targets[i]
        if type(target) is tuple and isinstance(target[0].component, RateGroupBase):
            if best is None or divider.divisor < best[0]:
                best = (divider.divisor, target[0].component)
    if best is None:
        raise ValueError("the bench deployment's rate-group driver drives no rate group")
    return best[1], best[0] * timer.base_period_us * 1e-6


def measure_deployment(topology, duration_s: float | None = None, chunks: int | None = None,
                       law: str | None = None) -> dict:
    """A detumble deployment and its plant-only counterpart, interleaved chunk by chunk.

    The simulated time is flown in ``chunks`` pieces (default: one per 300 simulated seconds, at
    least eight); after each deployment piece the same length of plant-only flight (same
    scenario, ``law``: default :data:`PLANT_ONLY_LAWS` of the scenario, else its ``control.law``)
    is timed. The tick-cost ratio compares the fastest piece of each: on a shared machine the
    fastest piece is the one least disturbed by other work, and interleaving exposes both to the
    same conditions. The median of the per-piece ratios is reported beside it as a check that does
    not depend on one quiet moment.

    Each plant-only piece starts from the scenario's initial state (a fresh plant), so it flies the
    first ``duration_s / chunks`` seconds of the mission again and again; the deployment flies on.
    Compare like with like: while the deployment is still in the mode the counterpart's pieces fly
    (adcs_ref: DETUMBLE until about 3240 s), both sides run the same controller code path.

    The laws of :data:`SECOND_COUNTERPARTS` are timed after the main counterpart in every piece and
    reported under ``second_counterparts``.
    """
    from detumble.sim.plant import Plant
    from detumble.sim.runner import run as plant_only

    loaded = load_topology(topology)
    deployment = Deployment(loaded)
    spacecraft = loaded.resources["spacecraft"]
    scenario = spacecraft.scenario
    if law is None:
        law = PLANT_ONLY_LAWS.get(scenario.name, scenario.control.law)
    orbit_s = 2.0 * math.pi / spacecraft.plant.orbit.mean_motion
    if duration_s is None:
        duration_s = round(orbit_s)
    group, tick_s = tick_rate_group(loaded)
    deployment.start()
    if chunks is None:
        chunks = max(8, round(duration_s / 300.0))
    chunk_s = duration_s / chunks
    deployment_us, plant_us = [], []
    deployment_cpu_us, plant_cpu_us = [], []
    seconds: dict[str, tuple[list[float], list[float]]] = {
        name: ([], []) for name in SECOND_COUNTERPARTS.get(law, ()) if name != law}
    wall = 0.0
    cpu = time.thread_time
    for _ in range(chunks):
        cycles0 = group.cycles
        c0, t0 = cpu(), time.perf_counter()
        deployment.run_for(chunk_s)
        elapsed, elapsed_cpu = time.perf_counter() - t0, cpu() - c0
        wall += elapsed
        ticks = max(1, group.cycles - cycles0)
        deployment_us.append(elapsed / ticks * 1e6)
        deployment_cpu_us.append(elapsed_cpu / ticks * 1e6)
        fresh = Plant(scenario)  # built outside the timed call, as the runner's own wall time excludes it
        c0 = cpu()
        plant = plant_only(scenario, law=law, duration_s=chunk_s, plant=fresh).summary
        plant_cpu_us.append((cpu() - c0) / plant["sim_seconds"] * tick_s * 1e6)
        plant_us.append(plant["wall_seconds"] / plant["sim_seconds"] * tick_s * 1e6)
        for name, (wall_us, cpu_us) in seconds.items():
            fresh = Plant(scenario)
            c0 = cpu()
            other = plant_only(scenario, law=name, duration_s=chunk_s, plant=fresh).summary
            cpu_us.append((cpu() - c0) / other["sim_seconds"] * tick_s * 1e6)
            wall_us.append(other["wall_seconds"] / other["sim_seconds"] * tick_s * 1e6)
    timer = loaded.timer
    assert timer is not None  # tick_rate_group refused a deployment without one
    tick_hz = 1.0 / tick_s
    return {
        "topology": str(topology),
        "scenario": scenario.name,
        "plant_only_law": law,
        "tick_rate_group": group.name,
        "tick_hz": tick_hz,
        "dynamics_step_s": scenario.dynamics_step_s,
        "sim_seconds": duration_s,
        "orbit_period_s": orbit_s,
        "chunks": chunks,
        "deployment_wall_s": wall,
        "real_time_factor": duration_s / wall,
        "base_ticks_per_s": timer.driver.tick / wall,
        "ticks_per_s": group.cycles / wall,
        "deployment_us_per_tick": min(deployment_us),
        "deployment_us_per_tick_median": sorted(deployment_us)[len(deployment_us) // 2],
        "plant_only_us_per_tick": min(plant_us),
        "plant_only_us_per_tick_median": sorted(plant_us)[len(plant_us) // 2],
        "fprime_part_us_per_tick": min(deployment_us) - min(plant_us),
        "fprime_part_cpu_us_per_tick": min(deployment_cpu_us) - min(plant_cpu_us),
        "tick_cost_ratio": min(deployment_us) / min(plant_us),
        "tick_cost_ratio_median_of_pieces": statistics.median(
            d / p for d, p in zip(deployment_us, plant_us, strict=True)),
        "pieces_us_per_tick": {"deployment": deployment_us, "plant_only": plant_us},
        # The same on this thread's CPU clock: far less moved by other work on a shared machine
        # (the plant-only figure includes the runner's set-up of the law and its recording).
        "deployment_cpu_us_per_tick": min(deployment_cpu_us),
        "plant_only_cpu_us_per_tick": min(plant_cpu_us),
        "tick_cost_ratio_cpu": min(deployment_cpu_us) / min(plant_cpu_us),
        "pieces_cpu_us_per_tick": {"deployment": deployment_cpu_us, "plant_only": plant_cpu_us},
        "second_counterparts": {
            name: {"plant_only_us_per_tick": min(wall_us), "tick_cost_ratio": min(deployment_us) / min(wall_us),
                   "plant_only_cpu_us_per_tick": min(cpu_us),
                   "tick_cost_ratio_cpu": min(deployment_cpu_us) / min(cpu_us),
                   "pieces_us_per_tick": wall_us}
            for name, (wall_us, cpu_us) in seconds.items()},
        "final_rate_deg_s": spacecraft.truth().rate_deg_s,
        "plant_implementation": spacecraft.plant.implementation,  # both sides' (detumble.sim.plant_kernel)
    }


def _rows_of(d: dict, label: str) -> list[tuple[str, str, str]]:
    hz = f"{d['tick_hz']:.0f} Hz"
    goal_us = FPRIME_PART_GOALS_US.get(d["plant_only_law"])
    goal = f"≤ {goal_us:.0f} µs" if goal_us is not None else ""
    return [
        (f"{label}: {d['sim_seconds']:.0f} s simulated", f"{d['deployment_wall_s']:.1f} s wall", ""),
        ("real-time factor", f"{d['real_time_factor']:,.0f}×", ""),
        ("base ticks (1 kHz) per wall second", f"{d['base_ticks_per_s']:,.0f}", ""),
        (f"{hz} ticks per wall second", f"{d['ticks_per_s']:,.0f}", ""),
        (f"F´ part of a {hz} tick: deployment − plant-only ({d['plant_only_law']}), CPU time (fastest pieces)",
         f"{d['deployment_cpu_us_per_tick']:.1f} µs − {d['plant_only_cpu_us_per_tick']:.1f} µs = "
         f"{d['fprime_part_cpu_us_per_tick']:.1f} µs", goal),
        ("the same on the wall clock (fastest pieces)",
         f"{d['deployment_us_per_tick']:.1f} µs − {d['plant_only_us_per_tick']:.1f} µs = "
         f"{d['fprime_part_us_per_tick']:.1f} µs (ratio {d['tick_cost_ratio']:.2f}, "
         f"CPU {d['tick_cost_ratio_cpu']:.2f})", ""),
        *[(f"per {hz} tick: deployment / plant-only ({name}) (fastest piece)",
            f"{d['deployment_us_per_tick']:.1f} µs / {o['plant_only_us_per_tick']:.1f} µs = "
            f"{o['tick_cost_ratio']:.2f} (CPU {o['tick_cost_ratio_cpu']:.2f})", "")
          for name, o in d.get("second_counterparts", {}).items()],
        (f"per {hz} tick, medians",
         f"{d['deployment_us_per_tick_median']:.1f} µs / {d['plant_only_us_per_tick_median']:.1f} µs", ""),
        (f"median of the {d['chunks']} pieces' ratios", f"{d['tick_cost_ratio_median_of_pieces']:.2f}", ""),
        ("plant (deployment and plant-only alike)", d.get("plant_implementation", "python"), ""),
    ]


def _rows(d: dict) -> list[tuple[str, str, str]]:
    rows = _rows_of(d, "deployment")
    for name, other in d.get("other_deployments", {}).items():
        rows += _rows_of(other, name)
    return rows


def _siblings(topology) -> dict[str, tuple[pathlib.Path, str]]:
    """The other reference deployments beside ``topology`` (``deployments/<name>/topology.yaml``)."""
    path = pathlib.Path(topology).resolve()
    if path.name != "topology.yaml" or path.parent.name not in REFERENCE_DEPLOYMENTS:
        return {}
    root = path.parent.parent
    return {name: (root / name / "topology.yaml", law) for name, law in REFERENCE_DEPLOYMENTS.items()
            if name != path.parent.name and (root / name / "topology.yaml").is_file()}


def _measure(options: argparse.Namespace) -> dict:
    figures = measure_deployment(options.topology, options.duration)
    others = {name: measure_deployment(path, options.duration, law=law)
              for name, (path, law) in _siblings(options.topology).items()}
    if others:
        figures["other_deployments"] = others
    return figures


#: The bench piece: ``deployment`` in ``bench.json``.
DEPLOYMENT_PIECE = BenchPiece(name="deployment", measure=_measure, rows=_rows)
