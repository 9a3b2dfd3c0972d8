"""One electrical + thermal step: the Python models against the compiled kernel's ``power_step``.

    python benchmarks/bench_power_step.py [--repeat N] [--number N]

Issue 32 (powerc lane): ``SimulatedSpacecraft._step_power`` integrates the electrical system and the thermal
model every ``POWER_STEP_NS`` (100 ms, 10 Hz), so a 50 Hz tick carries a fifth of one step. This times one step
(0.1 s, the adcs scenario's models, a sunlit attitude, the coils drawing 0.4 W) done by
``ElectricalSystem.step`` then ``ThermalModel.step`` ("python") and by ``plant_kernel.step_power_thermal``
("compiled", the same floats), with ``timeit``, the two in turn ``--repeat`` times so that both see the same
load, keeping the best of each (the machine is shared; the best is the least disturbed), in µs a step and,
divided by 5, a 50 Hz tick. Both variants step models of their own from the same state; each step runs from
where the last left, so the battery drains as in flight (4000 steps are 400 s: the pack stays far from empty
and full). Nothing is asserted: a measurement for reading (docs/performance.md, "Issue 32: the electrical and
thermal step compiled (powerc lane)").
"""

from __future__ import annotations

import argparse
import timeit

#: 50 Hz ticks a power step (POWER_STEP_NS / the 20 ms tick)
TICKS_PER_STEP = 5


def make_models():
    """The adcs scenario's electrical system and a fresh thermal model."""
    from detumble.sim.epoch import julian_date
    from detumble.sim.orbit import R_EARTH_EQ
    from detumble.sim.power import ElectricalSystem
    from detumble.sim.scenario import load_scenario
    from detumble.sim.thermal import ThermalModel

    sc = load_scenario("adcs")
    return ElectricalSystem(sc.power, julian_date(sc.epoch), R_EARTH_EQ), ThermalModel()


def steppers(dt: float = 0.1):
    """``(python_step, compiled_step, models)``: two calls of no argument doing one step each on their own
    models (``models`` = ``((eps, thermal), (eps, thermal))``), or ``compiled_step`` None without a kernel."""
    from detumble.sim import plant_kernel

    q = (0.9238795325112867, 0.1, -0.2, 0.3)
    n = sum(x * x for x in q) ** 0.5
    q = tuple(x / n for x in q)
    r = (6.8e6, 1.0e6, 0.5e6)
    py_eps, py_th = make_models()
    c_eps, c_th = make_models()
    t = [0.0, 0.0]

    def python_step() -> None:
        py_eps.step(dt, t[0], q, r, 0.4)
        py_th.step(dt, py_eps.face_flux_w_m2, py_eps.load_w)
        t[0] += dt

    status = plant_kernel.load()
    if status.module is None:
        return python_step, None, ((py_eps, py_th), (c_eps, c_th))
    module, constants = status.module, plant_kernel.power_constants(c_eps, c_th)

    def compiled_step() -> None:
        plant_kernel.step_power_thermal(module, constants, c_eps, c_th, dt, t[1], q, r, 0.4)
        t[1] += dt

    return python_step, compiled_step, ((py_eps, py_th), (c_eps, c_th))


def main(argv: list[str] | None = None) -> dict[str, float]:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--number", type=int, default=4000)
    args = parser.parse_args(argv)
    python_step, compiled_step, _ = steppers()
    best = {"python": float("inf"), "compiled": float("inf")}
    for _ in range(args.repeat):
        best["python"] = min(best["python"], timeit.timeit(python_step, number=args.number) / args.number * 1e6)
        if compiled_step is not None:
            best["compiled"] = min(best["compiled"],
                                   timeit.timeit(compiled_step, number=args.number) / args.number * 1e6)
    for name, us in best.items():
        if us != float("inf"):
            print(f"{name:9s} {us:6.3f} us a power step, {us / TICKS_PER_STEP:6.3f} us a 50 Hz tick")
    if compiled_step is None:
        print("compiled: no kernel on this machine")
    else:
        saved = best["python"] - best["compiled"]
        print(f"saved     {saved:6.3f} us a power step, {saved / TICKS_PER_STEP:6.3f} us a 50 Hz tick")
    return best


if __name__ == "__main__":
    main()
