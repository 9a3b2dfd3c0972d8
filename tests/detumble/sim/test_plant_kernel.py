"""The compiled plant kernel against the pure-Python reference plant, and the fallback to the reference.

Equality here is ``==`` on floats: the kernel repeats the reference's arithmetic operation for
operation, so the bound is 0 ulp (bit-identical), for the state, the environment and every sensor
sample, and event times (|omega| < 1 deg/s, the flight manager's state changes) are the same instants.
"""

import dataclasses
import logging
import math
import pathlib

import pytest

from detumble.sim import plant_kernel
from detumble.sim.plant import Plant
from detumble.sim.runner import make_law, run
from detumble.sim.scenario import load_scenario, scenario_from_dict

BASILISK_DETUMBLED_S = 2817.0  # case A: Basilisk's |omega| < 1 deg/s instant (docs/shared simulation spec)


@pytest.fixture
def fresh_kernel(monkeypatch, tmp_path):
    """An empty kernel cache and no kernel loaded in this process; the real one is restored after."""
    monkeypatch.setenv(plant_kernel.CACHE_ENV_VAR, str(tmp_path / "cache"))
    monkeypatch.delenv(plant_kernel.ENV_VAR, raising=False)
    plant_kernel._reset_for_tests()
    yield tmp_path / "cache"
    plant_kernel._reset_for_tests()


def _kernel_or_skip():
    """Skip on a machine without a C compiler or Python's headers; a kernel that fails to build, to
    import or to reproduce the reference is a failure."""
    status = plant_kernel.load()
    if status.outcome == "no toolchain":
        pytest.skip(f"no compiled kernel on this machine: {status.reason}")
    assert status.module is not None, f"compiled kernel {status.outcome}: {status.reason}"


def _case_a_trajectory(implementation, seconds):
    """Case A as the plant-only runner flies it (kopt law at 20 Hz on the ideal magnetometer): every
    step's state, position and field, and the first instant |omega| < 1 deg/s."""
    p = Plant(load_scenario("case_a"), implementation=implementation)
    law = make_law("kopt", p)
    states, env, t_below = [], [], None
    for _ in range(int(round(seconds / p.dynamics_step_s))):
        bx, by, bz, t = p.magnetometer_reading()
        p.apply_dipole_B(law.update((bx * 1e-4, by * 1e-4, bz * 1e-4), t))
        p.step()
        s = p.state
        states.append(s)
        env.append((p.r_N, p._r_hat_N, p.b_N))
        if t_below is None and math.degrees(math.sqrt(s[4] ** 2 + s[5] ** 2 + s[6] ** 2)) < 1.0:
            t_below = p.t
    return p, states, env, t_below


def test_case_a_detumble_is_bit_identical_with_the_same_detumble_time():
    """SIM-KRN-001: case A, 3000 s (past detumbling) at 0.05 s: the compiled kernel's 60 000 states,
    positions and fields are the pure-Python plant's floats (0 ulp), and |omega| < 1 deg/s is reached
    at the same instant, within +-10 % of Basilisk's 2817 s."""
    _kernel_or_skip()
    ref, ref_states, ref_env, ref_below = _case_a_trajectory("python", 3000.0)
    got, states, env, below = _case_a_trajectory("compiled", 3000.0)
    assert (ref.implementation, got.implementation) == ("python", "compiled")
    first_diff = next((k for k, (a, b) in enumerate(zip(states, ref_states, strict=True)) if a != b), None)
    assert first_diff is None, f"state differs from step {first_diff}: {states[first_diff]} != {ref_states[first_diff]}"
    assert env == ref_env
    assert below == ref_below
    assert ref_below is not None and abs(ref_below - BASILISK_DETUMBLED_S) <= 0.1 * BASILISK_DETUMBLED_S


def test_plant_only_runner_summaries_agree():
    """SIM-KRN-002: `fprime-lite sim case_a --law kopt` for 1200 s: every recorded row and the whole
    summary but the wall-clock figures are equal between the two implementations."""
    _kernel_or_skip()
    sc = load_scenario("case_a")
    a = run(sc, law="kopt", duration_s=1200.0, plant=Plant(sc, implementation="python"))
    b = run(sc, law="kopt", duration_s=1200.0, plant=Plant(sc, implementation="compiled"))
    assert a.rows == b.rows and a.adcs_rows == b.adcs_rows
    assert (a.summary["plant_implementation"], b.summary["plant_implementation"]) == ("python", "compiled")
    wall = {"wall_seconds", "real_time_factor", "plant_implementation"}
    same = [k for k in a.summary if k not in wall]
    assert len(same) > 10 and [a.summary[k] for k in same] == [b.summary[k] for k in same]


def _noisy_flight(scenario, implementation, steps):
    """A coil pattern, every sensor read each step: states, magnetometer and gyro samples."""
    p = Plant(scenario, seed=11, implementation=implementation)
    out = []
    for k in range(steps):
        if k % 40 == 0:
            level = (k // 40) * 37 % 255 - 127
            p.set_coil_level(0, level)
            p.set_coil_level(1, -level)
            p.set_coil_level(5, level // 3)
        p.step_ns(20_000_000 if k % 7 else 13_000_000)  # partial steps too, as the bridge makes them
        out.append((p.state, p.b_N, p._r_hat_N, p.magnetometer_reading(), p.gyro_reading()))
    return p.implementation, out


def test_default_scenario_with_coils_noise_and_gravity_gradient_is_bit_identical():
    """SIM-KRN-003: the reference deployment's scenario (five face coils, noisy biased LIS2MDL with coil
    coupling, LSM6DSO, gravity gradient) with a full inertia tensor and a residual dipole: states and
    every sensor sample are equal over 3000 steps of 20 and 13 ms."""
    _kernel_or_skip()
    sc = load_scenario("default")
    sc = dataclasses.replace(sc, spacecraft=dataclasses.replace(
        sc.spacecraft, inertia_kg_m2=((2.0e-3, 1.0e-4, -5.0e-5), (1.0e-4, 2.2e-3, 8.0e-5), (-5.0e-5, 8.0e-5, 1.9e-3)),
        residual_dipole_am2=(1e-3, -2e-3, 5e-4), wheel_momentum_nms=(1e-5, 0.0, -2e-5)))
    impl_a, a = _noisy_flight(sc, "python", 3000)
    impl_b, b = _noisy_flight(sc, "compiled", 3000)
    assert (impl_a, impl_b) == ("python", "compiled")
    assert a == b


@pytest.mark.parametrize("settings", [
    ["integrator_substeps=3"],  # the kernel's step_env in the sub-step loop, its environment after
    ["field.model=orbit_constant", "field.b_orbit_t=[2.0e-5, -1.0e-5, 3.0e-5]"],  # kernel RK4, Python field
    ["orbit.j2=true"],
])
def test_other_plant_paths_are_bit_identical(settings):
    """SIM-KRN-004: sub-steps, a field the kernel does not model (its RK4 with the Python field) and a J2
    orbit: 1500 steps equal between the implementations."""
    _kernel_or_skip()
    sc = load_scenario("default", settings=settings)
    assert _noisy_flight(sc, "python", 1500) == ("python", _noisy_flight(sc, "compiled", 1500)[1])


def test_reference_deployment_is_the_same_flight_with_either_plant(monkeypatch):
    """SIM-KRN-005: the whole reference deployment for 40 s (the flight DetumbleManager's B-dot cycles,
    five drivers, noisy sensors) with FPRIME_LITE_PLANT=python and =compiled: the truth trace every
    20 ms and the manager's state at every tick are the same (the same event times)."""
    _kernel_or_skip()
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology_loader import load_topology

    topology = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml"

    def fly(implementation):
        monkeypatch.setenv(plant_kernel.ENV_VAR, implementation)
        loaded = load_topology(topology)
        topo = loaded.topology
        craft = topo.instance("ReferenceDeployment.imuManager").component.spacecraft
        manager = topo.instance("ReferenceDeployment.detumbleManager").component
        trace, states = [], []
        craft.set_trace(lambda s: trace.append(tuple(s)), 20_000)
        loaded.scheduler.add_time_listener(lambda now_us: states.append((now_us, manager.state)))
        deployment = Deployment(loaded)
        deployment.start(sequence=topology.parent / "startup.seq")
        deployment.run_for(40.0)
        return craft.plant.implementation, trace, states

    impl_a, trace_a, states_a = fly("python")
    impl_b, trace_b, states_b = fly("compiled")
    assert (impl_a, impl_b) == ("python", "compiled")
    assert len(trace_a) > 1900 and trace_a == trace_b
    assert len({s for _, s in states_a}) > 1 and states_a == states_b


def test_kernel_functions_equal_the_reference_on_random_inputs():
    """SIM-KRN-006: 20 000 random calls each (seeded): the kernel's step_env equals RigidBody.step_env
    (random full inertia, wheel momentum, state up to 3 rad/s, dipole, field, gravity gradient, extra
    torque, dt up to 0.2 s) and its environment equals CircularOrbit.position_N + DipoleField.b_N (random
    J2 orbits, Earth angles and times up to 10^7 s): 0 ulp."""
    _kernel_or_skip()
    import random

    from detumble.sim.attitude import RigidBody
    from detumble.sim.field import DipoleField
    from detumble.sim.orbit import CircularOrbit

    rng = random.Random(7)
    module = plant_kernel.load().module

    def vec(scale):
        return (rng.uniform(-scale, scale), rng.uniform(-scale, scale), rng.uniform(-scale, scale))

    for _ in range(200):
        d = (rng.uniform(1e-3, 5e-3), rng.uniform(1e-3, 5e-3), rng.uniform(1e-3, 5e-3))
        p = vec(2e-4)
        body = RigidBody(((d[0], p[0], p[1]), (p[0], d[1], p[2]), (p[1], p[2], d[2])), vec(1e-4))
        orbit = CircularOrbit(rng.uniform(300e3, 2000e3), rng.uniform(0.0, math.pi), rng.uniform(-4.0, 4.0),
                              rng.uniform(-4.0, 4.0), j2=rng.choice((0.0, 1.0826267e-3)))
        field = DipoleField(theta0_rad=rng.uniform(-4.0, 4.0))
        kernel = module.Kernel(body._j, body._jinv, body.wheel_momentum_B,
                               plant_kernel.environment_parameters(orbit, field))
        for _ in range(100):
            q = vec(1.0) + (rng.uniform(-1.0, 1.0),)
            n = math.sqrt(sum(x * x for x in q))
            s = tuple(x / n for x in q) + vec(3.0)
            r_hat = vec(1.0)
            args = (rng.uniform(1e-3, 0.2), vec(0.2), vec(5e-5), rng.uniform(0.0, 1e-5), r_hat, vec(1e-6))
            assert kernel.step_env(s, *args) == body.step_env(s, *args)
            assert kernel.step_env(s, *args[:5]) == body.step_env(s, *args[:5])
            t = rng.uniform(0.0, 1e7)
            r = orbit.position_N(t)
            rn = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
            assert kernel.environment(t) == (r, (r[0] / rn, r[1] / rn, r[2] / rn), field.b_N(t, r))


# --- choosing and falling back -----------------------------------------------------------------


def test_without_a_compiler_the_python_plant_is_chosen_with_a_logged_note(fresh_kernel, monkeypatch, caplog):
    """SIM-KRN-010: no C compiler ($CC names none): a plant is built all the same, in pure Python, and
    the reason is logged at INFO; FPRIME_LITE_PLANT=compiled then fails with that reason."""
    monkeypatch.setenv("CC", "/nonexistent/cc")
    with caplog.at_level(logging.INFO, logger="detumble.sim.plant_kernel"):
        p = Plant(load_scenario("case_a"))
    assert p.implementation == "python" and plant_kernel.load().outcome == "no toolchain"
    assert any("compiled plant kernel unavailable" in r.getMessage() and "/nonexistent/cc" in r.getMessage()
               for r in caplog.records)
    assert not fresh_kernel.exists() or not list(fresh_kernel.glob("plant_kernel-*"))
    p.step()  # and it flies
    monkeypatch.setenv(plant_kernel.ENV_VAR, "compiled")
    with pytest.raises(plant_kernel.KernelUnavailableError, match=r"FPRIME_LITE_PLANT=compiled .*no C compiler"):
        Plant(load_scenario("case_a"))


def test_a_compiler_that_fails_falls_back(fresh_kernel, monkeypatch):
    """SIM-KRN-016: a C compiler that exits with an error ($CC=false): the Python plant, the reason kept."""
    monkeypatch.setenv("CC", "false")
    status = plant_kernel.load()
    assert status.module is None and status.outcome == "build failed" and "exit 1" in status.reason
    assert Plant(load_scenario("case_a")).implementation == "python"


def test_a_cached_kernel_that_cannot_be_imported_falls_back(fresh_kernel):
    """SIM-KRN-011: a damaged file where the cached kernel should be: the import fails and the plant is
    the Python one (nothing is raised)."""
    fresh_kernel.mkdir(parents=True)
    path = fresh_kernel / f"plant_kernel-{plant_kernel.source_key()}{plant_kernel._ext_suffix()}"
    path.write_bytes(b"not a shared object")
    status = plant_kernel.load()
    assert status.module is None and status.outcome == "import failed" and "remove it to rebuild" in status.reason
    assert Plant(load_scenario("case_a")).implementation == "python"


def test_a_kernel_that_does_not_reproduce_the_reference_is_refused(fresh_kernel, monkeypatch):
    """SIM-KRN-012: a kernel whose step is off by one ulp in one component fails the load-time check
    and is not used."""
    _kernel_or_skip()
    real = plant_kernel.load().module

    class OffByOneUlp:
        def __init__(self, *args):
            self._k = real.Kernel(*args)
            self.has_environment = self._k.has_environment
            self.environment = self._k.environment

        def step_env(self, *args):
            s = self._k.step_env(*args)
            return (*s[:5], math.nextafter(s[5], math.inf), s[6])

    fake = type("FakeModule", (), {"Kernel": OffByOneUlp, "SOURCE_KEY": real.SOURCE_KEY})
    assert plant_kernel.mismatch(real) is None
    assert plant_kernel.mismatch(fake) is not None
    plant_kernel._reset_for_tests()
    monkeypatch.setattr(plant_kernel, "_import", lambda path: fake)
    status = plant_kernel.load()
    assert status.module is None and status.outcome == "refused"
    assert "does not reproduce the Python reference" in status.reason
    assert Plant(load_scenario("case_a")).implementation == "python"


def test_the_kernel_is_built_once_into_the_cache_and_reused(fresh_kernel):
    """SIM-KRN-013: first use compiles into the (empty) cache; a second process-load reuses the file."""
    _kernel_or_skip()
    status = plant_kernel.load()
    assert status.build_seconds is not None and pathlib.Path(status.path).parent == fresh_kernel
    plant_kernel._reset_for_tests()
    again = plant_kernel.load()
    assert again.module is not None and again.path == status.path and again.build_seconds is None


def test_the_python_reference_can_be_forced_and_a_bad_choice_is_named(monkeypatch):
    """SIM-KRN-014: FPRIME_LITE_PLANT=python gives the reference plant; an unknown value is an error
    naming the variable and the choices."""
    monkeypatch.setenv(plant_kernel.ENV_VAR, "python")
    assert Plant(load_scenario("case_a")).implementation == "python"
    assert plant_kernel.describe() == "python (FPRIME_LITE_PLANT=python)"
    monkeypatch.setenv(plant_kernel.ENV_VAR, "fast")
    with pytest.raises(ValueError, match=r"FPRIME_LITE_PLANT must be one of auto, python, compiled, got 'fast'"):
        Plant(load_scenario("case_a"))


def test_wheels_keep_the_python_plant():
    """SIM-KRN-015: a spacecraft with reaction wheels (no compiled twin of their integrator) is the
    Python plant even when the kernel is there."""
    sc = scenario_from_dict({"spacecraft": {"reaction_wheels": {"model": "cubesat_1u"}}})
    assert Plant(sc, implementation="auto").implementation == "python"
