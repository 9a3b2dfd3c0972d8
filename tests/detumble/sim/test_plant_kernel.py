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
from detumble.sim.coils import X_PLUS
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


def _assert_runner_runs_agree(scenario, law, seconds):
    """The plant-only runner with either plant: every recorded row and the whole summary but the
    wall-clock figures are equal."""
    _kernel_or_skip()
    sc = load_scenario(scenario)
    a = run(sc, law=law, duration_s=seconds, plant=Plant(sc, implementation="python"))
    b = run(sc, law=law, duration_s=seconds, plant=Plant(sc, implementation="compiled"))
    assert a.rows == b.rows and a.adcs_rows == b.adcs_rows
    assert (a.summary["plant_implementation"], b.summary["plant_implementation"]) == ("python", "compiled")
    wall = {"wall_seconds", "real_time_factor", "plant_implementation"}
    same = [k for k in a.summary if k not in wall]
    assert len(same) > 10 and [a.summary[k] for k in same] == [b.summary[k] for k in same]


def test_plant_only_runner_summaries_agree():
    """SIM-KRN-002: `fprime-lite sim case_a --law kopt` for 1200 s: every recorded row and the whole
    summary but the wall-clock figures are equal between the two implementations."""
    _assert_runner_runs_agree("case_a", "kopt", 1200.0)


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
    the reason is logged at INFO (a wheel plant too); FPRIME_LITE_PLANT=compiled then fails with that
    reason."""
    monkeypatch.setenv("CC", "/nonexistent/cc")
    with caplog.at_level(logging.INFO, logger="detumble.sim.plant_kernel"):
        p = Plant(load_scenario("case_a"))
    assert p.implementation == "python" and plant_kernel.load().outcome == "no toolchain"
    assert any("compiled plant kernel unavailable" in r.getMessage() and "/nonexistent/cc" in r.getMessage()
               for r in caplog.records)
    assert not fresh_kernel.exists() or not list(fresh_kernel.glob("plant_kernel-*"))
    p.step()  # and it flies
    wheels = Plant(load_scenario("surrey"))
    assert wheels.implementation == "python" and wheels._step_wheels is None and wheels._kernel_step_wheels is None
    wheels.set_wheel_torque(0, 1e-4)
    wheels.step()
    assert wheels.wheel_momenta[0] > 0.0
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


def test_a_passed_check_is_stamped_and_later_processes_skip_it(fresh_kernel, monkeypatch):
    """SIM-KRN-037: the first load checks the kernel and leaves a stamp beside it; a later process in the
    same configuration takes the stamp's word (the check is not run); one whose configuration differs (here
    the CPU's identity) checks again and leaves its own stamp."""
    _kernel_or_skip()
    first = plant_kernel.load()
    assert first.checked == "now"
    stamps = sorted(p.name for p in fresh_kernel.iterdir() if ".checked-" in p.name)
    assert stamps == [pathlib.Path(plant_kernel.check_stamp_path(first.path)).name]

    def must_not_run(module):
        raise AssertionError("the load-time check ran although a stamp vouches for this configuration")

    plant_kernel._reset_for_tests()
    with monkeypatch.context() as m:
        m.setattr(plant_kernel, "mismatch", must_not_run)
        again = plant_kernel.load()
    assert again.module is not None and again.checked == "stamp" and again.outcome == "ok"

    ran = []
    checked = plant_kernel.mismatch
    monkeypatch.setattr(plant_kernel, "mismatch", lambda module: ran.append(module) or checked(module))
    monkeypatch.setattr(plant_kernel, "_cpu_identity", lambda: "another CPU")
    plant_kernel._reset_for_tests()
    other = plant_kernel.load()
    assert other.checked == "now" and len(ran) == 1
    assert len([p for p in fresh_kernel.iterdir() if ".checked-" in p.name]) == 2


def test_a_refused_kernel_leaves_no_stamp_and_no_libm_means_no_stamp(fresh_kernel, monkeypatch):
    """SIM-KRN-038: a kernel that fails the check is refused and stamps nothing (the next process checks
    again); where the libm in use cannot be named the check runs in every process and nothing is stamped."""
    _kernel_or_skip()
    for stamp in fresh_kernel.glob("*.checked-*"):  # the good kernel's own, from its first load
        stamp.unlink()
    plant_kernel._reset_for_tests()
    with monkeypatch.context() as m:
        m.setattr(plant_kernel, "mismatch", lambda module: "state 3 off by one ulp (test)")
        refused = plant_kernel.load()
    assert refused.module is None and refused.outcome == "refused"
    assert not [p for p in fresh_kernel.iterdir() if ".checked-" in p.name]
    plant_kernel._reset_for_tests()
    monkeypatch.setattr(plant_kernel, "_libm_identity", lambda: None)
    unnamed = plant_kernel.load()
    assert unnamed.module is not None and unnamed.checked == "now"
    assert plant_kernel.check_stamp_path(unnamed.path) is None
    assert not [p for p in fresh_kernel.iterdir() if ".checked-" in p.name]


def test_the_check_key_names_the_kernel_file_and_every_reference_source(tmp_path, monkeypatch):
    """SIM-KRN-039: the stamp's key changes with one byte of the kernel file, of any module of
    ``detumble.sim`` or ``detumble.control``, or of ``detumble.errors`` (a copy of the package is edited)."""
    import shutil

    package = pathlib.Path(plant_kernel.__file__).parent.parent
    copy = tmp_path / "detumble"
    for part in ("sim", "control"):
        shutil.copytree(package / part, copy / part, ignore=shutil.ignore_patterns("__pycache__", "scenarios"))
    shutil.copy(package / "errors.py", copy / "errors.py")
    kernel = tmp_path / "kernel.so"
    kernel.write_bytes(b"\x7fELF kernel bytes")
    monkeypatch.setattr(plant_kernel, "__file__", str(copy / "sim" / "plant_kernel.py"))
    monkeypatch.setattr(plant_kernel, "_libm_identity", lambda: "/lib/libm.so.6:1:2:3")
    base = plant_kernel.check_key(str(kernel))
    assert base is not None and base == plant_kernel.check_key(str(kernel))
    seen = {base}
    for edited in (kernel, copy / "sim" / "wheels.py", copy / "control" / "bdot.py", copy / "errors.py"):
        original = edited.read_bytes()
        edited.write_bytes(original + b" ")
        key = plant_kernel.check_key(str(kernel))
        assert key not in seen, f"editing {edited.name} left the key as it was"
        seen.add(key)
        edited.write_bytes(original)
    assert plant_kernel.check_key(str(kernel)) == base


def test_the_python_reference_can_be_forced_and_a_bad_choice_is_named(monkeypatch):
    """SIM-KRN-014: FPRIME_LITE_PLANT=python gives the reference plant; an unknown value is an error
    naming the variable and the choices."""
    monkeypatch.setenv(plant_kernel.ENV_VAR, "python")
    assert Plant(load_scenario("case_a")).implementation == "python"
    assert plant_kernel.describe() == "python (FPRIME_LITE_PLANT=python)"
    monkeypatch.setenv(plant_kernel.ENV_VAR, "fast")
    with pytest.raises(ValueError, match=r"FPRIME_LITE_PLANT must be one of auto, python, compiled, got 'fast'"):
        Plant(load_scenario("case_a"))


def test_a_wheel_plant_gets_the_kernel_and_the_python_plant_when_asked():
    """SIM-KRN-015: a spacecraft with reaction wheels gets the compiled kernel (RK4 and environment) on
    auto; FPRIME_LITE_PLANT=python keeps the reference; more wheels than the kernel takes keep the Python
    plant on auto and are an error naming the limit with compiled."""
    _kernel_or_skip()
    sc = scenario_from_dict({"spacecraft": {"reaction_wheels": {"model": "cubesat_1u"}}})
    p = Plant(sc, implementation="auto")
    assert p.implementation == "compiled" and p._kernel_step_wheels is not None
    assert Plant(sc, implementation="python").implementation == "python"
    many = dataclasses.replace(sc, spacecraft=dataclasses.replace(
        sc.spacecraft, reaction_wheels=sc.spacecraft.reaction_wheels[:1] * (plant_kernel.MAX_WHEELS + 1)))
    assert Plant(many, implementation="auto").implementation == "python"
    with pytest.raises(plant_kernel.KernelUnavailableError,
                       match=r"at most 16 reaction wheels \(this spacecraft has 17\)"):
        Plant(many, implementation="compiled")


# --- reaction wheels -------------------------------------------------------------------------------


@pytest.mark.parametrize("settings", [["field.model=igrf14", "field.table_step_s=0.5"],
                                      ["field.model=igrf14", "field.table_step_s=10"]], ids=["0.5 s", "10 s"])
def test_igrf14_on_its_table_is_the_kernel_s_and_bit_identical(settings):
    """SIM-KRN-030 (issue 27): IGRF-14 on its table runs the kernel's fused step and environment (the kernel
    interpolates, Python computes each node once): states, field, nadir and both sensors equal over 1500 steps
    of 20 and 13 ms (a 0.5 s table: 55 nodes crossed), without and with wheels."""
    _kernel_or_skip()
    sc = load_scenario("default", settings=settings)
    assert Plant(sc, implementation="compiled")._kernel_step is not None
    assert _noisy_flight(sc, "python", 1500) == ("python", _noisy_flight(sc, "compiled", 1500)[1])
    wheels = _wheel_scenario(True, settings)
    assert Plant(wheels, implementation="compiled")._kernel_step_wheels is not None
    assert _wheel_flight(wheels, "python", 1500) == ("python", _wheel_flight(wheels, "compiled", 1500)[1])


def _wheel_scenario(friction, settings=()):
    """The default scenario (five coils, noisy sensors with coil coupling, gravity gradient, full
    inertia) with four 1U-class wheels in a pyramid, one started near its momentum limit; with
    ``friction`` viscous and Coulomb bearing friction (one wheel's smoothing band wide enough that its
    speed stays inside it)."""
    from detumble.sim.wheels import WheelSpec

    sc = load_scenario("default", settings=settings)
    c, s3 = math.sqrt(2.0 / 3.0), math.sqrt(1.0 / 3.0)
    axes = ((c, 0.0, s3), (0.0, c, s3), (-c, 0.0, s3), (0.0, -c, s3))
    specs = tuple(WheelSpec(axis, 1.43e-5, 4.0e-3, 1.5e-2,
                            viscous_friction_nms=2e-7 * (i + 1) if friction else 0.0,
                            coulomb_friction_nm=4e-5 if friction else 0.0,
                            coulomb_smoothing_rad_s=2000.0 if i == 3 else 0.1,
                            initial_momentum_nms=(1.4e-2, -2e-3, 0.0, 5e-4)[i])
                  for i, axis in enumerate(axes))
    return dataclasses.replace(sc, spacecraft=dataclasses.replace(
        sc.spacecraft, inertia_kg_m2=((2.2e-3, 2.0e-5, -1.5e-5), (2.0e-5, 2.15e-3, 1.0e-5), (-1.5e-5, 1.0e-5, 2.05e-3)),
        reaction_wheels=specs))


def _wheel_flight(scenario, implementation, steps):
    """Torque commands (some beyond the 4 mN m limit, one wheel pushed into its momentum limit and held
    there), speed-mode commands, a wheel disabled and enabled again, coil levels, partial steps; every
    step: the state, the wheels' momenta, applied torques and limit flags, the environment and both
    sensors."""
    p = Plant(scenario, seed=5, implementation=implementation)
    out = []
    for k in range(steps):
        if k % 50 == 0:
            j = k // 50
            p.set_wheel_torque(0, 3e-3)  # wheel 0 starts at 14 of 15 mN m s: reaches the limit and stays
            p.set_wheel_torque(1, (-1) ** j * 1e-3 * (j % 7))  # up to 6 mN m: clipped at 4
            if j % 9 < 6:
                p.set_wheel_speed(2, 40.0 * ((j % 5) - 2))
            else:
                p.set_wheel_torque(2, -2.5e-3)
            p.set_wheel_torque(3, 5e-4 * math.sin(0.7 * j))
            p.set_wheel_enabled(3, j % 6 != 5)
            level = j * 37 % 255 - 127
            p.set_coil_level(0, level)
            p.set_coil_level(5, -level // 2)
        p.step_ns(20_000_000 if k % 7 else 13_000_000)
        w = p.wheels
        out.append((p.state, w.h, tuple(w.torque_applied), tuple(w.torque_clipped), tuple(w.momentum_limited),
                    p.b_N, p._r_hat_N, p.magnetometer_reading(), p.gyro_reading()))
    return p.implementation, out


@pytest.mark.parametrize("friction", [False, True], ids=["frictionless", "friction"])
def test_wheel_plant_is_bit_identical_over_a_long_commanded_run(friction):
    """SIM-KRN-020: a four-wheel plant for 20 000 steps (about 370 s) of torque and speed commands with
    torque clipping, the momentum limit, a wheel disabled and enabled, coils and noisy sensors (with and
    without bearing friction): every state, wheel momentum, applied torque, limit flag, field and sensor
    sample is equal between the implementations (0 ulp), so every saturation happens at the same step; the
    compiled plant's torques and flags come from the kernel's ``motor_torques``."""
    _kernel_or_skip()
    sc = _wheel_scenario(friction)
    impl_a, a = _wheel_flight(sc, "python", 20_000)
    impl_b, b = _wheel_flight(sc, "compiled", 20_000)
    assert (impl_a, impl_b) == ("python", "compiled")
    first_diff = next((k for k, (x, y) in enumerate(zip(a, b, strict=True)) if x != y), None)
    assert first_diff is None, f"step {first_diff} differs: {b[first_diff]} != {a[first_diff]}"
    # the run covers what it claims: clipping, the momentum limit, a disabled wheel, the speed loop
    assert any(row[3][1] for row in a) and any(row[4][0] for row in a)
    assert any(row[2][3] == 0.0 for row in a) and len({row[2][2] for row in a}) > 100
    assert abs(a[-1][1][0]) <= 1.5e-2 and max(abs(row[1][0]) for row in a) > 1.49e-2
    assert Plant(sc).wheels.friction == friction
    assert Plant(sc, implementation="compiled").wheels.compiled is not None
    assert Plant(sc, implementation="python").wheels.compiled is None


@pytest.mark.parametrize("settings", [
    ["integrator_substeps=3"],  # the kernel's step_wheels in the sub-step loop, its environment after
    ["field.model=none"],  # the kernel's step_wheels, the environment in Python
    ["field.model=orbit_constant", "field.b_orbit_t=[2.0e-5, -1.0e-5, 3.0e-5]"],  # the kernel's field
])
def test_other_wheel_plant_paths_are_bit_identical(settings):
    """SIM-KRN-021: a wheel plant with sub-steps, without a field and with the orbit-constant field:
    2000 commanded steps equal between the implementations."""
    _kernel_or_skip()
    sc = _wheel_scenario(True, settings)
    assert _wheel_flight(sc, "python", 2000) == ("python", _wheel_flight(sc, "compiled", 2000)[1])


def test_coursework_plant_only_run_is_bit_identical():
    """SIM-KRN-022: `fprime-lite sim surrey --law wheels_pd` (seed 004's 214 deg/s tumble, three wheels,
    the orbit-constant field, ideal sensors) for 600 s: the rows and the summary are equal between the
    implementations."""
    _assert_runner_runs_agree("surrey", "wheels_pd", 600.0)


def _fly_wheel_deployment(monkeypatch, implementation, topology, module, controller, seconds, sequence=None,
                          settings=()):
    """One deployment run (scenario values overridden by ``settings``): the truth trace every 20 ms and,
    at every tick, the controller's mode or law, the wheels' momenta, applied torques and limit flags."""
    from detumble.drivers import spacecraft as spacecraft_module
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology_loader import load_topology

    original = spacecraft_module.load_scenario

    def load_with_settings(name, settings_given=(), **kwargs):
        return original(name, settings=[*kwargs.pop("settings", settings_given), *settings], **kwargs)

    monkeypatch.setattr(spacecraft_module, "load_scenario", load_with_settings)
    monkeypatch.setenv(plant_kernel.ENV_VAR, implementation)
    loaded = load_topology(topology)
    topo = loaded.topology
    ctrl = topo.instance(f"{module}.{controller}").component
    craft = topo.instance(f"{module}.imuManager").component.spacecraft
    trace, ticks = [], []
    craft.set_trace(lambda s: trace.append(tuple(s)), 20_000)

    def tick(now_us):
        w = craft.plant.wheels
        ticks.append((now_us, getattr(ctrl, "mode", None), getattr(ctrl, "_law", None), w.h, tuple(w.torque_applied),
                      tuple(w.torque_clipped), tuple(w.momentum_limited)))

    loaded.scheduler.add_time_listener(tick)
    deployment = Deployment(loaded)
    deployment.start(sequence=sequence or topology.parent / "startup.seq")
    deployment.run_for(seconds)
    return craft.plant.implementation, trace, ticks


def test_adcs_deployment_pointing_on_wheels_is_the_same_flight_with_either_plant(monkeypatch, tmp_path):
    """SIM-KRN-023: deployments/adcs_ref, started slow (0.5 deg/s) and forced to POINTING after 5 s: the
    AttitudeController slews 45 deg on its three wheels (the PD law, up to 0.28 mN m a wheel) and
    holds the target, 60 s in all. The truth every 20 ms and the wheels' state and the mode at every tick are the same
    floats and the same instants with either plant."""
    _kernel_or_skip()
    topology = pathlib.Path(__file__).parents[3] / "deployments" / "adcs_ref" / "topology.yaml"
    seq = tmp_path / "point.seq"
    seq.write_text("R00:00:00 ReferenceDeployment.attitudeController.SET_TARGET_QUATERNION "
                   "0.9238795325112867 0.0 0.3826834323650898 0.0\n"
                   "R00:00:05 ReferenceDeployment.attitudeController.FORCE_MODE POINTING\n")
    settings = ("initial.rate.magnitude_deg_s=0.5", "initial.rate.axis=[0, 0, 1]")
    runs = [_fly_wheel_deployment(monkeypatch, impl, topology, "ReferenceDeployment", "attitudeController",
                                  60.0, seq, settings) for impl in ("python", "compiled")]
    (impl_a, trace_a, ticks_a), (impl_b, trace_b, ticks_b) = runs
    assert (impl_a, impl_b) == ("python", "compiled")
    assert len(trace_a) > 2900 and trace_a == trace_b
    assert ticks_a == ticks_b
    assert len({t[1] for t in ticks_a}) == 2  # IDLE, then POINTING
    assert max(abs(u) for t in ticks_a for u in t[4]) > 1e-4  # the wheels work


def test_coursework_deployment_is_the_same_flight_with_either_plant(monkeypatch):
    """SIM-KRN-024: deployments/coursework (the CourseworkController's wheel PD law at 100 Hz on the
    214 deg/s tumble, the wheels spinning up to about 3 mN m s in 30 s) for 30 s: truth every 20 ms and
    the wheels' state and the controller's law at every tick are the same with either plant."""
    _kernel_or_skip()
    topology = pathlib.Path(__file__).parents[3] / "deployments" / "coursework" / "topology.yaml"
    runs = [_fly_wheel_deployment(monkeypatch, impl, topology, "CourseworkDeployment", "controller", 30.0)
            for impl in ("python", "compiled")]
    (impl_a, trace_a, ticks_a), (impl_b, trace_b, ticks_b) = runs
    assert (impl_a, impl_b) == ("python", "compiled")
    assert len(trace_a) > 1400 and trace_a == trace_b
    assert ticks_a == ticks_b
    assert max(abs(h) for h in ticks_a[-1][3]) > 1e-3  # the wheels work


@pytest.mark.parametrize("where", ["frictionless state", "frictionless momentum", "friction state",
                                   "friction momentum", "orbit-constant field", "tabulated field"])
def test_a_kernel_whose_wheel_step_or_field_is_off_by_one_ulp_is_refused(fresh_kernel, monkeypatch, where):
    """SIM-KRN-025: the load-time check covers the wheel step (both branches, state and wheel momenta),
    the orbit-constant field and the tabulated field (IGRF-14's): one ulp off in one of them and the kernel
    is refused."""
    _kernel_or_skip()
    real = plant_kernel.load().module

    def bump(v, i):
        return (*v[:i], math.nextafter(v[i], math.inf), *v[i + 1:])

    class OneUlpOff:
        def __init__(self, *args):
            self._k = real.Kernel(*args)
            env = len(args[3]) if len(args) > 3 and args[3] is not None else 0
            self.field = (env, where) in ((10, "orbit-constant field"), (9, "tabulated field"))
            for name in ("has_environment", "has_wheels", "wheel_friction", "wheel_count", "step_env", "step"):
                setattr(self, name, getattr(self._k, name))

        def _off(self, branch):
            return where.startswith(branch) and bool(self._k.wheel_friction) == (branch == "friction")

        def environment(self, t):
            r, rh, b = self._k.environment(t)
            return (r, rh, bump(b, 1)) if self.field else (r, rh, b)

        def step_wheels(self, *args):
            s, h = self._k.step_wheels(*args)
            for branch in ("frictionless", "friction"):
                if self._off(branch):
                    return (bump(s, 4), h) if where.endswith("state") else (s, bump(h, 2))
            return s, h

        def step_wheels_env(self, *args):  # (…, t1[, torque_B]): the step's arguments without t1
            s, h = self.step_wheels(*args[:8], *args[9:])
            return (s, h, *self.environment(args[8]))

    fake = type("FakeModule", (), {"Kernel": OneUlpOff, "SOURCE_KEY": real.SOURCE_KEY})
    problem = plant_kernel.mismatch(fake)
    assert problem is not None
    assert (where.split()[0] in problem) if where.endswith("field") else (
        f"friction {where.startswith('friction ')}" in problem)
    plant_kernel._reset_for_tests()
    monkeypatch.setattr(plant_kernel, "_import", lambda path: fake)
    assert plant_kernel.load().outcome == "refused"
    assert Plant(load_scenario("adcs")).implementation == "python"


def test_wheel_step_and_orbit_constant_field_equal_the_reference_on_random_inputs():
    """SIM-KRN-026: 20 000 random wheel steps (seeded: 1 to 6 wheels on random axes, random inertia,
    friction or none, momenta near and beyond the limits, torques, states up to 3 rad/s, dt up to 0.2 s)
    equal wheels.step_with_wheels, and 5000 random times of the orbit-constant field on random orbits
    equal CircularOrbit + OrbitConstantField: 0 ulp."""
    _kernel_or_skip()
    import random

    from detumble.sim.attitude import RigidBody
    from detumble.sim.field import OrbitConstantField
    from detumble.sim.orbit import CircularOrbit
    from detumble.sim.wheels import WheelAssembly, WheelSpec, step_with_wheels

    rng = random.Random(11)
    module = plant_kernel.load().module

    def vec(scale):
        return (rng.uniform(-scale, scale), rng.uniform(-scale, scale), rng.uniform(-scale, scale))

    def unit():
        v = vec(1.0)
        n = math.sqrt(sum(x * x for x in v))
        return tuple(x / n for x in v)

    for _ in range(200):
        d = (rng.uniform(1e-3, 5e-3), rng.uniform(1e-3, 5e-3), rng.uniform(1e-3, 5e-3))
        p = vec(2e-4)
        body = RigidBody(((d[0], p[0], p[1]), (p[0], d[1], p[2]), (p[1], p[2], d[2])), vec(1e-4))
        friction = rng.random() < 0.5
        specs = tuple(WheelSpec(unit(), rng.uniform(5e-6, 1e-4), 4e-3, 1.5e-2,
                                viscous_friction_nms=rng.uniform(0.0, 1e-6) if friction else 0.0,
                                coulomb_friction_nm=rng.uniform(0.0, 1e-4) if friction else 0.0,
                                coulomb_smoothing_rad_s=rng.choice((0.1, 5.0, 1e3)))
                      for _ in range(rng.randint(1, 6)))
        wheels = WheelAssembly(specs)
        kernel = module.Kernel(body._j, body._jinv, body.wheel_momentum_B, None, plant_kernel.wheel_parameters(wheels))
        assert not kernel.has_environment and kernel.wheel_count == len(specs)
        for _ in range(100):
            q = vec(1.0) + (rng.uniform(-1.0, 1.0),)
            n = math.sqrt(sum(x * x for x in q))
            s = tuple(x / n for x in q) + vec(3.0)
            h = tuple(rng.uniform(-2e-2, 2e-2) for _ in specs)
            u = tuple(rng.uniform(-5e-3, 5e-3) for _ in specs)
            args = (rng.uniform(1e-3, 0.2), vec(0.2), vec(5e-5), rng.uniform(0.0, 1e-5), vec(1.0))
            assert kernel.step_wheels(s, h, u, *args) == step_with_wheels(body, s, h, u, wheels, *args)
    for _ in range(50):
        orbit = CircularOrbit(rng.uniform(300e3, 2000e3), rng.uniform(0.0, math.pi), rng.uniform(-4.0, 4.0),
                              rng.uniform(-4.0, 4.0), j2=rng.choice((0.0, 1.0826267e-3)))
        field = OrbitConstantField(vec(5e-5), orbit)
        kernel = module.Kernel(body._j, body._jinv, body.wheel_momentum_B,
                               plant_kernel.environment_parameters(orbit, field))
        for _ in range(100):
            t = rng.uniform(0.0, 1e7)
            r = orbit.position_N(t)
            rn = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
            assert kernel.environment(t) == (r, (r[0] / rn, r[1] / rn, r[2] / rn), field.b_N(t, r))


_SURFACES = ["spacecraft.surfaces.drag=true", "spacecraft.surfaces.solar_pressure=true",
             "spacecraft.surfaces.cp_offset_m=[0.004, -0.003, 0.012]", "spacecraft.surfaces.specular_reflectivity=0.2"]


@pytest.mark.parametrize("friction,settings", [
    (False, []), (True, []), (True, ["integrator_substeps=3"]), (False, ["field.model=none"]),
], ids=["wheels", "friction", "substeps", "python-environment"])
def test_drag_and_solar_pressure_are_bit_identical_with_wheels(friction, settings):
    """SIM-KRN-023: drag and solar-pressure torques on (``spacecraft.surfaces``): a commanded wheel plant for 3000
    steps gives equal floats in both implementations on every path (fused kernel step, sub-steps, the environment
    in Python); and the torque acts (the flight differs from the same one with both off)."""
    _kernel_or_skip()
    sc = _wheel_scenario(friction, [*settings, *_SURFACES])
    on = _wheel_flight(sc, "python", 3000)
    assert on == ("python", _wheel_flight(sc, "compiled", 3000)[1])
    assert on[1] != _wheel_flight(_wheel_scenario(friction, settings), "python", 3000)[1]


@pytest.mark.parametrize("settings", [[], ["integrator_substeps=2"]], ids=["fused", "substeps"])
def test_drag_and_solar_pressure_are_bit_identical_without_wheels(settings):
    """SIM-KRN-024: the same without wheels (the kernel's ``step`` and ``step_env`` with their torque argument)."""
    _kernel_or_skip()
    sc = load_scenario("default", settings=[*settings, *_SURFACES])

    def fly(implementation):
        p = Plant(sc, seed=3, implementation=implementation)
        rows = []
        for k in range(3000):
            if k % 100 == 0:
                p.set_coil_level(0, (k // 100) * 37 % 255 - 127)
            p.step_ns(20_000_000)
            rows.append((p.state, p.surface_torque_B, p.gyro_reading()))
        return p.implementation, rows

    a, b = fly("python"), fly("compiled")
    assert (a[0], b[0]) == ("python", "compiled") and a[1] == b[1]
    assert max(abs(c) for row in a[1] for c in row[1]) > 1e-9  # the surfaces' torque is there


@pytest.mark.parametrize("which", ["step_env", "step", "step_wheels", "step_wheels_env"])
def test_a_kernel_that_drops_the_external_torque_is_refused(which):
    """SIM-KRN-027: the load-time check passes the drag/solar-pressure torque argument to every step function: a
    kernel whose one function ignores it is refused."""
    _kernel_or_skip()
    real = plant_kernel.load().module
    n_without = {"step_env": 6, "step": 7, "step_wheels": 8, "step_wheels_env": 9}[which]

    class DropsTorque:
        def __init__(self, *args):
            self._k = real.Kernel(*args)
            for name in ("has_environment", "has_wheels", "wheel_friction", "wheel_count", "environment",
                         "step_env", "step", "step_wheels", "step_wheels_env"):
                setattr(self, name, getattr(self._k, name))
            fn = getattr(self._k, which)
            setattr(self, which, lambda *a: fn(*a[:n_without]))

    fake = type("FakeModule", (), {"Kernel": DropsTorque, "SOURCE_KEY": real.SOURCE_KEY})
    assert plant_kernel.mismatch(fake) is not None


def _noisy_sensor_flight(implementation):
    """A noisy plant (magnetometer and gyro noise, bias, coil coupling) stepped 600 times with the coils
    switching: the magnetometer and gyro samples read at irregular steps (several left unread between
    reads), and each generator's state after the flight."""
    plant = Plant(scenario_from_dict({
        "dynamics_step_s": 0.02,
        "sensors": {"magnetometer": {"noise_std_gauss": 0.003, "bias_gauss": [0.012, -0.008, 0.005]},
                    "gyro": {"noise_density_dps_rthz": 0.0038, "bias_dps": [0.2, -0.1, 0.05]}},
        "initial": {"rate": {"omega_deg_s": [20.0, -10.0, 5.0]}},
    }), implementation=implementation)
    reads = []
    for k in range(1, 601):
        if k % 50 == 0:
            plant.set_coil_level(X_PLUS, 127 if k % 100 else -60)
        plant.step()
        if k % 7 in (0, 3):
            reads.append((k, "mag", plant.magnetometer.sample_gauss))
        if k % 5 == 0 or k % 11 == 0:
            reads.append((k, "gyro", plant.gyro.sample_rad_s))
    return plant, reads, (plant.magnetometer.rng.getstate(), plant.gyro.rng.getstate())


def test_the_sensor_samples_are_bit_identical_with_either_plant():
    """SIM-KRN-034: a noisy plant's magnetometer and gyro samples, read at irregular steps with unread ones
    between, are the same floats with the held samples resolved in the kernel and in Python, and the two
    generators end in the same state (the noise draws consumed alike)."""
    _kernel_or_skip()
    python, python_reads, python_rngs = _noisy_sensor_flight("python")
    compiled, compiled_reads, compiled_rngs = _noisy_sensor_flight("compiled")
    assert python.magnetometer.compiled is None and python.gyro.compiled is None
    assert compiled.magnetometer.compiled is not None and compiled.gyro.compiled is not None
    assert len(python_reads) > 300 and python_reads == compiled_reads
    assert python_rngs == compiled_rngs


@pytest.mark.parametrize("which", ["magnetometer", "gyro"])
def test_a_kernel_whose_sensor_sample_is_off_by_one_ulp_is_refused(monkeypatch, which):
    """SIM-KRN-035: the load-time check covers both sensors' compiled resolve: one ulp off in one axis of
    one of them and the kernel is refused, naming the sensor; the plant then flies the Python reference."""
    _kernel_or_skip()
    real = plant_kernel.load().module

    def off(fn):
        def sample(*args):
            x, y, z = fn(*args)
            return (x, math.nextafter(y, math.inf), z)
        return staticmethod(sample)

    members = {"Kernel": real.Kernel, "SOURCE_KEY": real.SOURCE_KEY, "power_step": staticmethod(real.power_step),
               "magnetometer_sample": staticmethod(real.magnetometer_sample),
               "gyro_sample": staticmethod(real.gyro_sample)}
    members[f"{which}_sample"] = off(getattr(real, f"{which}_sample"))
    fake = type("FakeModule", (), members)
    problem = plant_kernel.mismatch(fake)
    assert problem is not None and problem.startswith(f"{which} sample")
    monkeypatch.setattr(plant_kernel, "_status", None)  # the real status is put back after the test
    monkeypatch.setattr(plant_kernel, "_import", lambda path: fake)
    assert plant_kernel.load().outcome == "refused"
    plant = Plant(load_scenario("adcs"))
    assert plant.implementation == "python" and plant.magnetometer.compiled is None


def test_a_kernel_whose_motor_torques_are_off_by_one_ulp_is_refused(monkeypatch):
    """SIM-KRN-036: the load-time check covers ``Kernel.motor_torques``: one ulp off in one wheel's torque and
    the kernel is refused, naming the motor torques; the plant then flies the Python reference."""
    _kernel_or_skip()
    real = plant_kernel.load().module

    class OneUlpOff:
        def __init__(self, *args):
            self._k = real.Kernel(*args)
            for name in ("has_environment", "has_wheels", "wheel_friction", "wheel_count", "step_env", "step",
                         "environment", "step_wheels", "step_wheels_env"):
                setattr(self, name, getattr(self._k, name))

        def motor_torques(self, *args):
            u = self._k.motor_torques(*args)
            return (*u[:1], math.nextafter(u[1], math.inf), *u[2:])

    members = {name: getattr(real, name) for name in ("SOURCE_KEY",)}
    members.update({name: staticmethod(getattr(real, name))
                    for name in ("power_step", "magnetometer_sample", "gyro_sample")})
    fake = type("FakeModule", (), {**members, "Kernel": OneUlpOff})
    problem = plant_kernel.mismatch(fake)
    assert problem is not None and problem.startswith("wheel motor torques")
    monkeypatch.setattr(plant_kernel, "_status", None)  # the real status is put back after the test
    monkeypatch.setattr(plant_kernel, "_import", lambda path: fake)
    assert plant_kernel.load().outcome == "refused"
    plant = Plant(_wheel_scenario(False))
    assert plant.implementation == "python" and plant.wheels.compiled is None
