"""Plant-only throughput vs the bare-physics floor, measured in the same run.

    python benchmarks/bench_plant.py [--ticks N]

Floor: one RK4 step of the 7-state rigid body with a constant torque (``RigidBody.step``).
Ticks: ``Plant.step`` of a packaged scenario plus what a driver does each tick (read the
magnetometer and gyro; for case A also the kopt law and applying its dipole; for surrey command
the three wheels and read the star tracker), each with the pure-Python reference plant and with
the compiled kernel (detumble.sim.plant_kernel; with the wheels' step since decision 0007's
late section). The adcs_ref spacecraft (three wheels commanded, magnetometer, gyro and star tracker read)
in the centred dipole and in IGRF-14 on its 10 s table (its deployment default; the kernel interpolates, Python
evaluates one degree-13 node every 10 s) and on a 1 s table.
Reported as ticks per second, as a ratio to the floor and compiled against Python, all in one
run; timings are never asserted anywhere.
"""

from __future__ import annotations

import argparse
import functools
import time

from detumble.sim import plant_kernel
from detumble.sim.attitude import RigidBody
from detumble.sim.plant import Plant
from detumble.sim.runner import make_law
from detumble.sim.scenario import load_scenario


def _best(fn, n: int, repeats: int = 3) -> float:
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn(n)
        best = min(best, time.perf_counter() - t0)
    return n / best


def floor(n: int) -> None:
    body = RigidBody(((1.67e-3, 0, 0), (0, 1.67e-3, 0), (0, 0, 1.67e-3)))
    s = (1.0, 0.0, 0.0, 0.0, 0.3, -0.2, 0.1)
    step = body.step
    tau = (1e-7, -2e-7, 3e-7)
    for _ in range(n):
        s = step(s, 0.05, tau)


def plant_default(n: int, implementation: str) -> None:
    p = Plant(load_scenario("default"), implementation=implementation)
    step, mag, gyro = p.step, p.magnetometer_reading, p.gyro_reading
    for _ in range(n):
        step()
        mag()
        gyro()


def plant_case_a_with_law(n: int, implementation: str) -> None:
    p = Plant(load_scenario("case_a"), implementation=implementation)
    law = make_law("kopt", p)
    step, update, apply = p.step, law.update, p.apply_dipole_B
    for _ in range(n):
        bx, by, bz, t = p.magnetometer_reading()
        apply(update((bx * 1e-4, by * 1e-4, bz * 1e-4), t))
        step()


def plant_surrey_wheels(n: int, implementation: str) -> None:
    """The coursework spacecraft: three wheels commanded every tick, star tracker and gyro read."""
    p = Plant(load_scenario("surrey"), implementation=implementation)
    step, torques, star = p.step, p.set_wheel_torques, p.star_tracker_reading
    u = (1e-4, -2e-4, 5e-5)
    for _ in range(n):
        torques(u)
        star()
        step()


def adcs_ticks(p: Plant, n: int) -> None:
    """``n`` of adcs_ref's plant ticks: three wheel torques commanded, magnetometer, gyro and star tracker read."""
    step, torques, star, mag, gyro = p.step, p.set_wheel_torques, p.star_tracker_reading, p.magnetometer_reading, \
        p.gyro_reading
    u = (1e-4, -2e-4, 5e-5)
    for _ in range(n):
        torques(u)
        mag()
        gyro()
        star()
        step()


def plant_adcs(n: int, implementation: str, settings: tuple[str, ...] = ()) -> None:
    """The adcs_ref spacecraft (:func:`adcs_ticks`)."""
    adcs_ticks(Plant(load_scenario("adcs", settings=list(settings)), implementation=implementation), n)


ADCS_FIELDS = (("dipole", ("field.model=dipole",)),
               ("IGRF-14, 10 s table", ("field.model=igrf14", "field.table_step_s=10")),
               ("IGRF-14, 1 s table", ("field.model=igrf14", "field.table_step_s=1")))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ticks", type=int, default=50_000)
    n = ap.parse_args().ticks
    kernel = plant_kernel.describe("auto")
    print(f"compiled kernel: {kernel}")
    f = _best(floor, n)
    print(f"bare RK4 step (floor)                        {f:12,.0f} steps/s  ({1e6 / f:5.2f} us)   ratio 1.00")
    impls = ("python", "compiled") if kernel == "compiled" else ("python",)
    for label, fn, kinds in (("plant tick, default (coils, noisy sensors) ", plant_default, impls),
                             ("plant tick + kopt law, case A (rods, ideal)", plant_case_a_with_law, impls),
                             ("plant tick, surrey (3 wheels commanded)   ", plant_surrey_wheels, impls)):
        rates = {}
        for impl in kinds:
            r = rates[impl] = _best(functools.partial(fn, implementation=impl), n)
            print(f"{label} {impl:8s} {r:12,.0f} ticks/s  ({1e6 / r:5.2f} us)   ratio {f / r:.2f}x the floor")
        if len(rates) == 2:
            print(f"{'':44s} compiled / python: {rates['compiled'] / rates['python']:.2f}x the ticks per second")
    for name, settings in ADCS_FIELDS:
        label = f"plant tick, adcs, {name}"
        for impl in impls:
            r = _best(functools.partial(plant_adcs, implementation=impl, settings=settings), n)
            print(f"{label:44s} {impl:8s} {r:12,.0f} ticks/s  ({1e6 / r:5.2f} us)   ratio {f / r:.2f}x the floor")


if __name__ == "__main__":
    main()
