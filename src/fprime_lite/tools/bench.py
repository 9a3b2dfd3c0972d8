"""``fprime-lite bench``: speed and memory of the reference deployment, as ratios measured in one run.

    fprime-lite bench [--duration S] [--json FILE] [--memory]

Measures, in this order and in this one process:

1. a call through a connected output port vs a plain bound-method call (ns, ratio);
2. the reference deployment over one orbit of its scenario at 50 Hz: real-time factor, base ticks
   and 50 Hz ticks per wall second;
3. the same scenario plant-only (dynamics at the same 50 Hz step, the scenario's reference B-dot
   law), flown in pieces interleaved with the deployment's, and the ratio of the deployment's
   per-tick cost to the plant-only per-tick cost (fastest piece of each);
4. the peak resident memory of this process;
5. with ``--memory``: peak memory of separate ``fprime-lite run`` processes of 1 h and 24 h of
   simulated time (streaming outputs must keep memory flat).

Timings depend on the machine; compare the ratios. Nothing here is asserted by the test suite.
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import timeit

from fprime_lite.osal.atomic import atomic_write_text

__all__ = ["main", "measure_port_call", "measure_deployment"]

DEFAULT_TOPOLOGY = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml"


def measure_port_call(number: int = 2_000_000, repeat: int = 7) -> dict:
    """ns per call through a connected output port vs a plain bound-method call."""
    from fprime_lite.model.component import PassiveComponent
    from fprime_lite.model.ports import OutputPort, PortType, sync_input
    from fprime_lite.model.types import I8

    start_type = PortType("Bench.Start", returns=bool, level=I8)

    class Driver(PassiveComponent):
        @sync_input(start_type)
        def start(self, level):
            return True

    class Caller(PassiveComponent):
        startOut = OutputPort(start_type)

    caller, driver = Caller("caller"), Driver("driver")
    caller.output_port("startOut").connect(0, driver.input_port("start"))
    env = {"caller": caller, "driver": driver}
    plain_timer = timeit.Timer("driver.start(5)", globals=env)
    port_timer = timeit.Timer("caller.startOut[0](5)", globals=env)
    plain = port = math.inf
    for _ in range(repeat):  # interleaved, so both see the same load on a shared machine
        plain = min(plain, plain_timer.timeit(number) / number)
        port = min(port, port_timer.timeit(number) / number)
    return {"plain_ns": plain * 1e9, "port_ns": port * 1e9, "ratio": port / plain}


def _peak_rss_mb(who=resource.RUSAGE_SELF) -> float:
    return resource.getrusage(who).ru_maxrss / 1024.0  # Linux reports KiB


def measure_deployment(topology=DEFAULT_TOPOLOGY, duration_s: float | None = None,
                       chunks: int | None = None) -> dict:
    """The reference deployment and its plant-only twin, interleaved chunk by chunk.

    The simulated time is flown in ``chunks`` pieces (default: one per 300 simulated seconds, at
    least eight); after each deployment piece the same length of plant-only flight (same scenario,
    50 Hz dynamics, the scenario's B-dot law) is timed. The tick-cost ratio compares the fastest
    piece of each: on a shared machine the fastest piece is the one least disturbed by other work,
    and interleaving exposes both to the same conditions. The median of the per-piece ratios is
    reported beside it as a check that does not depend on one quiet moment.
    """
    from detumble.sim.runner import run as plant_only

    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology_loader import load_topology

    loaded = load_topology(topology)
    deployment = Deployment(loaded)
    spacecraft = loaded.resources["spacecraft"]
    scenario = spacecraft.scenario
    orbit_s = 2.0 * math.pi / spacecraft.plant.orbit.mean_motion
    if duration_s is None:
        duration_s = round(orbit_s)
    rg50 = loaded.topology.instance("ReferenceDeployment.rateGroup50Hz").component
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
        "tick_cost_ratio_median_of_pieces": statistics.median(d / p for d, p in zip(deployment_us, plant_us)),
        "pieces_us_per_tick": {"deployment": deployment_us, "plant_only": plant_us},
        "final_rate_deg_s": spacecraft.truth().rate_deg_s,
    }


def _child_peak_memory(topology, seconds: float) -> dict:
    """Run ``fprime-lite run`` for ``seconds`` in a fresh process; return its peak RSS."""
    with tempfile.TemporaryDirectory() as out:
        code = ("import json, resource, sys; from fprime_lite.tools.cli import main; "
                f"rc = main(['run', {str(topology)!r}, '--duration', '{seconds}', '--out', {out + '/run'!r}, "
                "'--no-progress', '--no-plots']); "
                "print(json.dumps({'rc': rc, 'peak_rss_mb': resource.getrusage(resource.RUSAGE_SELF).ru_maxrss "
                "/ 1024}))")
        t0 = time.perf_counter()
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
        wall = time.perf_counter() - t0
    line = done.stdout.strip().splitlines()[-1] if done.stdout.strip() else "{}"
    result = json.loads(line)
    result.update({"sim_seconds": seconds, "wall_s": wall})
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="fprime-lite bench", description=__doc__.splitlines()[0])
    parser.add_argument("--topology", default=str(DEFAULT_TOPOLOGY), help="topology to measure")
    parser.add_argument("--duration", type=float, help="simulated seconds (default: one orbit)")
    parser.add_argument("--json", metavar="FILE", default="bench.json", help="where to write the figures")
    parser.add_argument("--memory", action="store_true", help="also measure 1 h and 24 h runs' peak memory")
    args = parser.parse_args(argv)

    results = {"python": sys.version.split()[0]}
    results["port_call"] = measure_port_call()
    results["deployment"] = measure_deployment(args.topology, args.duration)
    results["peak_rss_mb"] = _peak_rss_mb()
    if args.memory:
        one_hour = _child_peak_memory(args.topology, 3600)
        one_day = _child_peak_memory(args.topology, 86400)
        results["memory"] = {"run_1h": one_hour, "run_24h": one_day,
                             "growth_ratio": one_day.get("peak_rss_mb", 0) / max(one_hour.get("peak_rss_mb", 1), 1e-9)}
    atomic_write_text(args.json, json.dumps(results, indent=2) + "\n")
    _print(results)
    print(f"figures written to {args.json}")
    return 0


def _print(r: dict) -> None:
    from rich.console import Console
    from rich.table import Table

    p, d = r["port_call"], r["deployment"]
    table = Table(title="fprime-lite bench (ratios are what to compare)", show_header=True)
    table.add_column("figure")
    table.add_column("value", justify="right")
    table.add_column("target", justify="right")
    table.add_row("port call / plain call", f"{p['port_ns']:.1f} ns / {p['plain_ns']:.1f} ns = {p['ratio']:.2f}",
                  "≤ 1.5")
    table.add_row(f"deployment, {d['sim_seconds']:.0f} s simulated", f"{d['deployment_wall_s']:.1f} s wall", "")
    table.add_row("real-time factor", f"{d['real_time_factor']:,.0f}×", "")
    table.add_row("base ticks (1 kHz) per wall second", f"{d['base_ticks_per_s']:,.0f}", "")
    table.add_row("50 Hz ticks per wall second", f"{d['ticks_50hz_per_s']:,.0f}", "")
    table.add_row("per 50 Hz tick: deployment / plant-only (fastest piece)",
                  f"{d['deployment_us_per_tick']:.1f} µs / {d['plant_only_us_per_tick']:.1f} µs = "
                  f"{d['tick_cost_ratio']:.2f}", "≤ 2.5")
    table.add_row("per 50 Hz tick, medians", f"{d['deployment_us_per_tick_median']:.1f} µs / "
                  f"{d['plant_only_us_per_tick_median']:.1f} µs", "")
    table.add_row(f"median of the {d['chunks']} pieces' ratios", f"{d['tick_cost_ratio_median_of_pieces']:.2f}", "")
    table.add_row("peak RSS (this process)", f"{r['peak_rss_mb']:.0f} MB", "")
    if "memory" in r:
        m = r["memory"]
        table.add_row("peak RSS, 1 h run", f"{m['run_1h'].get('peak_rss_mb', float('nan')):.0f} MB", "")
        table.add_row("peak RSS, 24 h run", f"{m['run_24h'].get('peak_rss_mb', float('nan')):.0f} MB", "≤ 200 MB")
        table.add_row("24 h / 1 h", f"{m['growth_ratio']:.3f}", "≤ 1.10")
    Console().print(table)


if __name__ == "__main__":
    sys.exit(main())
