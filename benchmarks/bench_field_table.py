"""CPU per adcs plant tick with each field: the centred dipole, IGRF-14 on its table with the environment in the
compiled kernel (the default since issue 27), and IGRF-14 with the environment in Python (as before).

    python benchmarks/bench_field_table.py [--ticks N] [--rounds R]

A tick is what adcs_ref's drivers do: three wheel torques commanded, the magnetometer, gyro and star tracker read,
one ``Plant.step``. Configurations are interleaved round by round and the minimum process time of each is kept,
so that the figures are comparable under load; they are measurements, never asserted anywhere. "Python
environment" gives the kernel no environment (its RK4 step stays compiled): what a tabulated field got before
the kernel learned to interpolate tables.
"""

from __future__ import annotations

import argparse
import time

from bench_plant import adcs_ticks  # this folder is on the path when run as a script

from detumble.sim import plant_kernel
from detumble.sim.plant import Plant
from detumble.sim.scenario import load_scenario

CONFIGS = {
    "dipole": (("field.model=dipole",), True),
    "IGRF-14, 10 s table": (("field.model=igrf14", "field.table_step_s=10"), True),
    "IGRF-14, 1 s table": (("field.model=igrf14", "field.table_step_s=1"), True),
    "IGRF-14, 10 s table, Python environment": (("field.model=igrf14", "field.table_step_s=10"), False),
    "IGRF-14, 1 s table, Python environment": (("field.model=igrf14", "field.table_step_s=1"), False),
}


def make_plant(settings: tuple[str, ...], kernel_environment: bool) -> Plant:
    real = plant_kernel.kernel_for
    if not kernel_environment:
        def without_environment(body, orbit, field, implementation=None, wheels=None):
            return real(body, orbit, None, implementation, wheels)
        plant_kernel.kernel_for = without_environment
    try:
        return Plant(load_scenario("adcs", settings=list(settings)), implementation="compiled")
    finally:
        plant_kernel.kernel_for = real


def cpu_per_tick_us(plant: Plant, n: int) -> float:
    t0 = time.process_time()
    adcs_ticks(plant, n)
    return (time.process_time() - t0) / n * 1e6


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ticks", type=int, default=5000, help="ticks per round (5000 = 100 s of flight)")
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    if plant_kernel.describe("auto") != "compiled":
        raise SystemExit(f"the compiled plant kernel is needed: {plant_kernel.describe('auto')}")
    best = dict.fromkeys(CONFIGS, float("inf"))
    for _ in range(args.rounds):
        for name, (settings, kernel_environment) in CONFIGS.items():
            best[name] = min(best[name], cpu_per_tick_us(make_plant(settings, kernel_environment), args.ticks))
    for name, us in best.items():
        print(f"{name:42s} {us:6.1f} us CPU per tick")


if __name__ == "__main__":
    main()
