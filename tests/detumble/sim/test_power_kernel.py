"""The compiled electrical and thermal step (``plant_kernel.step_power_thermal``, issue 32) against the
Python models (``ElectricalSystem.step`` then ``ThermalModel.step``), and the fallback to them.

Equality is on ``repr``: the same floats bit for bit, the sign of zero included (0 ulp), for every
attribute the two models hold (battery, bus, array, loads, energy accumulators, face fluxes, eclipse flag,
face and interior temperatures).
"""

import math
import pathlib
import random

import pytest

from detumble.sim import plant_kernel
from detumble.sim.power import SWITCH_NAMES, BatteryConfig, ElectricalSystem, PowerConfig, SolarConfig
from detumble.sim.thermal import ThermalConfig, ThermalModel

JD = 2460676.5
R_SHADOW_M = 6.378137e6


def _module():
    status = plant_kernel.load()
    if status.outcome == "no toolchain":
        pytest.skip(f"no compiled kernel on this machine: {status.reason}")
    assert status.module is not None, f"compiled kernel {status.outcome}: {status.reason}"
    return status.module


def _state(eps, thermal):
    """Every attribute of the electrical system, its battery and the thermal model, as reprs."""
    out = {}
    for prefix, obj in (("eps", eps), ("battery", eps.battery), ("thermal", thermal)):
        for name, value in vars(obj).items():
            if name not in ("cfg", "battery", "sun"):  # sun: a test's stand-in for the Sun's position
                out[f"{prefix}.{name}"] = repr(value)
    return out


def _pair(cfg, thermal_cfg):
    return (ElectricalSystem(cfg, JD, R_SHADOW_M), ThermalModel(thermal_cfg),
            ElectricalSystem(cfg, JD, R_SHADOW_M), ThermalModel(thermal_cfg))


def _random_run(module, seed, steps, cfg, thermal_cfg=None, zeros=False):
    """Both implementations stepped on the same random inputs; returns how often each branch ran."""
    rng = random.Random(seed)
    thermal_cfg = ThermalConfig() if thermal_cfg is None else thermal_cfg
    ref, ref_th, got, got_th = _pair(cfg, thermal_cfg)
    constants = plant_kernel.power_constants(got, got_th)
    hits = dict.fromkeys(("eclipse", "shunt", "brown-out", "empty", "substeps", "sunlit"), 0)
    for k in range(steps):
        if zeros:  # the Sun along body axes with signed zeros: each face's cosine 0.0 from +0.0 and -0.0
            s = tuple(rng.choice((0.0, -0.0, 1.0, -1.0)) for _ in range(3))
            d = rng.uniform(0.98, 1.02)
            for e in (ref, got):
                e.sun = lambda t, s=s, d=d: (s, d)
            q = rng.choice(((1.0, 0.0, 0.0, 0.0), (-1.0, -0.0, 0.0, -0.0), (0.0, 1.0, 0.0, 0.0)))
        else:
            q = tuple(rng.gauss(0.0, 1.0) for _ in range(4))
            n = math.sqrt(sum(x * x for x in q))
            q = tuple(x / n for x in q)
        r = tuple(rng.gauss(0.0, 1.0) * 7.0e6 for _ in range(3))
        dt = rng.choice((0.1, 0.1, 0.1, 0.12, 0.02, 1.0, 1.005, 0.2505, 2.5, 3.0, 7.3))
        t_s = k * rng.choice((0.1, 30.0, 61.0))
        coil_w = rng.choice((0.0, rng.uniform(0.0, 4.0)))
        if rng.random() < 0.1:
            for name in SWITCH_NAMES:
                on = rng.random() < 0.5
                ref.set_switch(name, on)
                got.set_switch(name, on)
            ref.burnwire_on = got.burnwire_on = rng.random() < 0.3
        before = (ref.shunted_j, ref.unserved_j, ref.battery.energy_j)
        ref.step(dt, t_s, q, r, coil_w)
        ref_th.step(dt, ref.face_flux_w_m2, ref.load_w)
        plant_kernel.step_power_thermal(module, constants, got, got_th, dt, t_s, q, r, coil_w)
        assert _state(got, got_th) == _state(ref, ref_th), f"step {k}"
        hits["eclipse" if ref.eclipse else "sunlit"] += 1
        hits["shunt"] += ref.shunted_j > before[0]
        hits["brown-out"] += ref.unserved_j > before[1] and ref.battery.energy_j > 0.0
        hits["empty"] += ref.unserved_j > before[1] and ref.battery.energy_j == 0.0 and before[2] > 0.0
        hits["substeps"] += dt > thermal_cfg.max_substep_s
    return hits


def test_random_power_and_thermal_steps_are_the_same_floats():
    """EPS-FLT-003: 6000 random steps (attitudes, positions in and out of the Earth's shadow, 0.02 … 7.3 s
    steps, switch and burnwire changes, coil power) on a small pack with large panels that fills, browns out
    and empties: every attribute of both models is the same float as the Python models', and every branch ran."""
    module = _module()
    cfg = PowerConfig(battery=BatteryConfig(capacity_wh=0.02, initial_soc=0.95, internal_resistance_ohm=1.5),
                      solar=SolarConfig(efficiency=0.8))
    hits = _random_run(module, 3, 6000, cfg)
    assert min(hits.values()) > 0, hits


def test_signed_zero_sun_cosines_give_the_same_floats():
    """EPS-FLT-004: the Sun exactly along body axes (direction components +0.0, -0.0, ±1.0): the lit and
    unlit faces' cosines and fluxes, zeros and their signs, are the Python models'."""
    module = _module()
    hits = _random_run(module, 4, 2000, PowerConfig(), zeros=True)
    assert hits["sunlit"] > 0 and hits["eclipse"] > 0, hits


def test_a_pack_without_resistance_and_the_default_pack_give_the_same_floats():
    """EPS-FLT-005: the ``R <= 0`` current branch (``P / OCV``) and the default 20 Wh pack."""
    module = _module()
    _random_run(module, 5, 1500, PowerConfig(battery=BatteryConfig(internal_resistance_ohm=0.0, capacity_wh=0.02)))
    _random_run(module, 6, 1500, PowerConfig())


def test_thermal_substeps_give_the_same_floats():
    """THM-FLT-002: a 0.25 s longest sub-step (1 to 30 sub-steps a step) and hot and cold starts: the face
    and interior temperatures are the Python model's."""
    module = _module()
    for initial_c in (-60.0, 20.0, 90.0):
        hits = _random_run(module, 7, 800, PowerConfig(), ThermalConfig(max_substep_s=0.25, initial_c=initial_c))
        assert hits["substeps"] > 0


def test_zero_step_changes_nothing():
    """THM-FLT-003: ``dt = 0`` leaves both models as they were, as the Python steps do."""
    module = _module()
    _, _, got, got_th = _pair(PowerConfig(), ThermalConfig())
    before = _state(got, got_th)
    plant_kernel.step_power_thermal(module, plant_kernel.power_constants(got, got_th), got, got_th, 0.0, 0.0,
                                    (1.0, 0.0, 0.0, 0.0), (7e6, 0.0, 0.0), 0.0)
    assert _state(got, got_th) == before


@pytest.mark.parametrize("where", ["accumulators", "interior", "face"])
def test_a_kernel_whose_power_step_is_off_by_one_ulp_is_refused(monkeypatch, where):
    """SIM-KRN-031: the load-time check covers the power step: one ulp off in the energies, the interior
    or a face temperature and the kernel is refused (the plant falls back to Python)."""
    real = _module()

    def power_step(*args):
        out = list(real.power_step(*args))
        if where == "accumulators":
            acc = out[6]
            out[6] = (*acc[:3], math.nextafter(acc[3], math.inf), *acc[4:])
        elif where == "interior":
            out[7] = math.nextafter(out[7], math.inf)
        else:
            args[9][2] = math.nextafter(args[9][2], math.inf)
        return tuple(out)

    fake = type("FakeModule", (), {"Kernel": real.Kernel, "SOURCE_KEY": real.SOURCE_KEY,
                                   "power_step": staticmethod(power_step)})
    problem = plant_kernel.mismatch(fake)
    assert problem is not None and problem.startswith("power step")
    monkeypatch.setattr(plant_kernel, "_status", None)
    monkeypatch.setattr(plant_kernel, "_import", lambda path: fake)
    assert plant_kernel.load().outcome == "refused"
    plant_kernel._reset_for_tests()


def _fly(monkeypatch, implementation, seconds):
    """adcs_ref for ``seconds``: at every tick the electrical and thermal models' every attribute."""
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology_loader import load_topology

    monkeypatch.setenv(plant_kernel.ENV_VAR, implementation)
    topology = pathlib.Path(__file__).parents[3] / "deployments" / "adcs_ref" / "topology.yaml"
    loaded = load_topology(topology)
    craft = loaded.topology.instance("ReferenceDeployment.imuManager").component.spacecraft
    ticks = []
    loaded.scheduler.add_time_listener(lambda now_us: ticks.append((now_us, _state(craft.power, craft.thermal),
                                                                    craft.energy_j())))
    deployment = Deployment(loaded)
    deployment.start(sequence=topology.parent / "startup.seq")
    deployment.run_for(seconds)
    return craft, ticks


def test_adcs_flight_has_the_same_power_and_thermal_floats_with_either_step(monkeypatch):
    """SIM-KRN-032: deployments/adcs_ref for 20 s (the B-dot detumble driving the coils): the electrical
    and thermal state at every tick is the same with the compiled step and with FPRIME_LITE_PLANT=python."""
    _module()
    craft_py, ticks_py = _fly(monkeypatch, "python", 20.0)
    craft_c, ticks_c = _fly(monkeypatch, "compiled", 20.0)
    assert craft_py._power_kernel is None and craft_c._power_kernel is not None
    assert len(ticks_py) > 900 and ticks_py == ticks_c
    assert craft_c.power.coil_j > 0.0 and craft_c.power.solar_j > 0.0  # coils and array both work


def test_without_the_kernel_the_python_models_step(monkeypatch):
    """SIM-KRN-033: with the kernel unavailable (``auto``) the spacecraft steps the Python models and
    still integrates them."""
    from detumble.drivers.spacecraft import SimulatedSpacecraft

    monkeypatch.delenv(plant_kernel.ENV_VAR, raising=False)
    monkeypatch.setattr(plant_kernel, "_status", plant_kernel.KernelStatus(None, "test: no kernel",
                                                                           outcome="no toolchain"))
    craft = SimulatedSpacecraft("adcs")
    assert craft.plant.implementation == "python" and craft._power_kernel is None
    craft.advance_to_us(craft.origin_us + 1_000_000)
    assert craft.power.load_j > 0.0 and craft.thermal.interior_k != 20.0 + 273.15
