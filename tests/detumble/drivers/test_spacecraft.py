"""SimulatedSpacecraft: lock-step stepping with the scheduler clock, time stamps, truth trace."""

import math

import pytest

from detumble.sim.coils import X_PLUS
from detumble.sim.plant import Plant
from detumble.drivers.spacecraft import SimulatedSpacecraft, TruthRecorder, TruthSample, scenario_epoch_us
from fprime_lite import SimulatedClock, Time, TimeBase
from fprime_lite.deploy.scheduler import Scheduler

US = 1_000_000  # µs per second


def _scheduled(scenario, **kwargs):
    sched = Scheduler(SimulatedClock(epoch_us=scenario_epoch_us(scenario)))
    return sched, SimulatedSpacecraft.for_scheduler(scenario, sched, **kwargs)


def _record_steps(craft):
    """Wrap the plant's step (``step_ns``, what the spacecraft calls) to record the plant time (ns)
    after every step."""
    ends = []
    step = craft.plant.step_ns

    def recording(dt_ns):
        step(dt_ns)
        ends.append(craft.plant.t_ns)

    craft.plant.step_ns = recording
    return ends


def test_scenario_epoch_is_unix_microseconds(default_scenario):
    # 2025-06-01T00:00:00Z
    assert scenario_epoch_us(default_scenario) == 1_748_736_000 * US


@pytest.mark.parametrize("until_us", [0, 1, 19_999, 20_000, 1_234_567, 3 * US + 7])
def test_physics_time_equals_scheduler_time_after_run(default_scenario, until_us):
    sched, craft = _scheduled(default_scenario)
    sched.call_every(20_000, lambda: None)
    sched.run(until_us=until_us)
    assert sched.now_us == until_us
    assert craft.plant.t_ns == until_us * 1000
    assert craft.plant_time_us == until_us


def test_physics_follows_time_even_without_events(default_scenario):
    sched, craft = _scheduled(default_scenario)
    sched.run(until_us=2 * US + 500)
    assert craft.plant.t_ns == (2 * US + 500) * 1000


def test_dynamics_steps_stay_on_the_fixed_grid(default_scenario):
    """Events every 15 ms with a 20 ms dynamics step: each step ends on the 20 ms grid or at an
    event time, and no step is longer than the dynamics step."""
    sched, craft = _scheduled(default_scenario)
    ends = _record_steps(craft)
    sched.call_every(15_000, lambda: None)
    sched.run(until_us=200_000)
    grid = 20_000_000
    events = {k * 15_000_000 for k in range(20)}
    prev = 0
    for end in ends:
        assert end % grid == 0 or end in events or end == 200_000_000
        assert 0 < end - prev <= grid
        prev = end
    assert ends[-1] == 200_000_000


def test_lock_step_equals_stepping_the_plant_directly(default_scenario):
    """A 50 Hz scheduler on the 20 ms dynamics grid flies exactly the plant's own trajectory."""
    sched, craft = _scheduled(default_scenario)
    sched.call_every(20_000, lambda: None)
    sched.run(until_us=2 * US)
    direct = Plant(default_scenario)
    direct.advance_to(2.0)
    assert craft.plant.state == direct.state
    assert craft.plant.magnetometer.sample_gauss == direct.magnetometer.sample_gauss


def test_never_integrates_backwards(make_craft):
    craft = make_craft()
    craft.advance_to_us(100_000)
    with pytest.raises(ValueError, match="cannot integrate backwards"):
        craft.advance_to_us(50_000)
    craft.advance_to_us(100_000)  # the same time is a no-op
    assert craft.plant.t_ns == 100_000_000


def test_attach_requires_the_spacecraft_clock(default_scenario):
    craft = SimulatedSpacecraft(default_scenario)
    with pytest.raises(ValueError, match="another clock"):
        craft.attach(Scheduler())


def test_origin_is_the_clock_reading_at_creation(default_scenario):
    sched = Scheduler(SimulatedClock(start_us=5 * US))
    craft = SimulatedSpacecraft.for_scheduler(default_scenario, sched)
    assert craft.plant.t_ns == 0
    sched.run(until_us=5 * US + 40_000)
    assert craft.plant.t_ns == 40_000_000


def test_coil_level_set_at_t_acts_only_after_t(default_scenario):
    """A coil switched on by an event at t = 1 s: the trajectory up to and at t is that of the
    coil-less run; right after t it differs, in the direction of the torque m x B."""
    sched_a, a = _scheduled(default_scenario)
    sched_b, b = _scheduled(default_scenario)
    seen = {}

    def switch_on():
        seen["before"] = b.plant.state
        b.set_coil_level(X_PLUS, 127)
        seen["after"] = b.plant.state
        seen["m"] = b.plant.m_coils_B
        seen["b"] = b.plant.b_B

    sched_b.call_at(1 * US, switch_on)
    for s in (sched_a, sched_b):
        s.call_every(20_000, lambda: None)
    sched_a.run(until_us=1 * US)
    sched_b.run(until_us=1 * US)
    assert seen["before"] == seen["after"] == a.plant.state == b.plant.state
    sched_a.run(until_us=1 * US + 20_000)
    sched_b.run(until_us=1 * US + 20_000)
    wa, wb = a.plant.omega_BN_B, b.plant.omega_BN_B
    assert wa != wb
    # dω ≈ J⁻¹ (m × B) dt for the extra dipole
    m, bb = seen["m"], seen["b"]
    torque = (m[1] * bb[2] - m[2] * bb[1], m[2] * bb[0] - m[0] * bb[2], m[0] * bb[1] - m[1] * bb[0])
    dw = [wb[i] - wa[i] for i in range(3)]
    cos = sum(dw[i] * torque[i] for i in range(3)) / (math.hypot(*dw) * math.hypot(*torque))
    assert cos > 0.99


def test_magnetometer_sample_and_hold_time_stamps(make_craft):
    """100 Hz LIS2MDL: a read at 15 ms returns the 10 ms sample stamped 10 ms; at 20 ms, the
    20 ms sample. Stamps are deployment times (scenario epoch + plant time)."""
    craft = make_craft()
    epoch = craft.clock.epoch_us
    craft.clock.set_us(15_000)
    bx, by, bz, stamp = craft.magnetometer_sample()
    assert stamp == Time.from_us(epoch + 10_000, TimeBase.TB_WORKSTATION_TIME)
    craft.clock.set_us(19_999)
    assert craft.magnetometer_sample() == (bx, by, bz, stamp)  # held
    craft.clock.set_us(20_000)
    *b2, stamp2 = craft.magnetometer_sample()
    assert stamp2.total_us == epoch + 20_000
    assert tuple(b2) != (bx, by, bz)


def test_ideal_sensors_are_stamped_now(make_craft, ideal_scenario):
    craft = make_craft(ideal_scenario)
    craft.clock.set_us(15_000)
    *b, stamp = craft.magnetometer_sample()
    assert stamp.total_us == craft.clock.epoch_us + 15_000
    assert tuple(b) == pytest.approx(tuple(x * 1e4 for x in craft.plant.b_B), rel=1e-15)


def test_magnetometer_odr_can_be_reconfigured(make_craft):
    craft = make_craft()
    craft.set_magnetometer_odr_hz(50.0)
    assert craft.magnetometer_period_us == 20_000
    craft.clock.set_us(35_000)
    assert craft.magnetometer_sample()[3].total_us == craft.clock.epoch_us + 20_000
    with pytest.raises(ValueError, match="positive"):
        craft.set_magnetometer_odr_hz(0.0)


def test_truth_trace_at_exact_instants(default_scenario):
    """A 30 ms trace on a 20 ms dynamics grid, driven by 50 Hz events: rows at exactly k * 30 ms,
    and the extra (partial) steps change the trajectory only at the integrator's truncation level."""
    sched, craft = _scheduled(default_scenario)
    rec = TruthRecorder()
    craft.set_trace(rec, 30_000)
    sched.call_every(20_000, lambda: None)
    sched.run(until_us=300_000)
    epoch = craft.clock.epoch_us
    assert [r.time_us - epoch for r in rec.rows] == [k * 30_000 for k in range(11)]
    assert [r.t_s for r in rec.rows] == pytest.approx([k * 0.03 for k in range(11)], abs=1e-12)
    row = rec.rows[-1]
    assert isinstance(row, TruthSample)
    assert row.rate_deg_s == pytest.approx(30.0, abs=0.01)
    assert math.degrees(math.hypot(*row.omega_BN_B)) == pytest.approx(row.rate_deg_s)
    assert 1.9e-5 < math.hypot(*row.b_B) < 5.5e-5  # tesla, LEO
    assert row.m_coils_B == (0.0, 0.0, 0.0) and set(row.coil_levels) == {0, 1, 2, 3, 5}
    direct = Plant(default_scenario)
    direct.advance_to(0.3)
    assert craft.plant.omega_BN_B == pytest.approx(direct.omega_BN_B, rel=1e-9)
    craft.set_trace(None)
    sched.run(until_us=600_000)
    assert len(rec.rows) == 11


def test_truth_recorder_writes_csv(make_craft, tmp_path):
    craft = make_craft()
    rec = TruthRecorder()
    craft.set_trace(rec, 100_000)
    craft.clock.set_us(250_000)
    craft.sync()
    path = tmp_path / "truth.csv"
    rec.write_csv(str(path))
    lines = path.read_text().splitlines()
    assert lines[0].split(",") == list(TruthSample.CSV_HEADER)
    assert len(lines) == 1 + 3  # t = 0, 0.1, 0.2 s
    assert float(lines[2].split(",")[1]) == pytest.approx(0.1)


def test_trace_interval_must_be_positive(make_craft):
    with pytest.raises(ValueError, match="interval_us"):
        make_craft().set_trace(lambda s: None, 0)


def test_time_of_follows_the_clock_settings_and_the_origin(make_craft):
    """TICK-015: ``time_of`` hands out one Time per plant instant, and a new one after the clock's
    epoch, base or context is set (an RTC set) or the origin moves, never the one it kept."""
    craft = make_craft()
    epoch = craft.clock.epoch_us
    t = craft.time_of(40_000_000)
    assert craft.time_of(40_000_000) is t and t.total_us == epoch + craft.origin_us + 40_000
    for k in range(12):  # more instants than it keeps: every one is still right
        assert craft.time_of(k * 1_000_000).total_us == epoch + craft.origin_us + k * 1_000
    craft.clock.epoch_us = epoch + 7_000_000
    assert craft.time_of(40_000_000).total_us == epoch + 7_000_000 + craft.origin_us + 40_000
    craft.clock.time_base = TimeBase.TB_PROC_TIME
    craft.clock.context = 2
    moved = craft.time_of(40_000_000)
    assert (moved.time_base, moved.context) == (TimeBase.TB_PROC_TIME, 2)
    craft.origin_us += 5
    assert craft.time_of(40_000_000).total_us == moved.total_us + 5


def test_written_out_samples_match_the_plant_getters_they_replace():
    """SCRAFT-101: the spacecraft's wheel, star-tracker, orbit-frame and ideal-magnetometer samples
    (the plant getters written out, for the 100 Hz wheel cycle) give exactly what the plant's own
    getters give at the same instant — the wheel momentum noise as WheelAssembly.measured_momentum
    draws it — and advance the physics to the clock's time first."""
    from detumble.sim import frames
    from detumble.sim.scenario import load_scenario
    from detumble.sim.sensors import GAUSS_PER_TESLA
    from detumble.sim.vec import rotate_n_to_b

    clock = SimulatedClock()
    noisy = ["spacecraft.reaction_wheels.momentum_noise_std_nms=1.0e-04"]
    craft = SimulatedSpacecraft(load_scenario("surrey", settings=noisy), clock=clock)
    plant, wheels = craft.plant, craft.plant.wheels
    assert wheels.specs[0].momentum_noise_std_nms == 1e-4
    for k in range(1, 40):
        clock.current_us = 10_000 * k + (3_000 if k % 3 else 0)  # on and between the dynamics steps
        for i in range(3):
            if k % 5 == 0:
                craft.set_wheel_torque(i, 1e-4 * (i + 1) * (-1) ** k)
                assert wheels.command[i] == 1e-4 * (i + 1) * (-1) ** k
            rng_state = wheels.rng.getstate()
            speed, h, u, stamp = craft.wheel_sample(i)
            assert plant.t_ns == (clock.current_us - craft.origin_us) * 1000
            after = wheels.rng.getstate()
            wheels.rng.setstate(rng_state)
            assert h == wheels.measured_momentum(i) and h != wheels.h[i]
            wheels.rng.setstate(rng_state)
            assert (speed, h, u) == plant.wheel_reading(i)[:3] and wheels.rng.getstate() == after
            assert stamp == craft.time_of(plant.t_ns)
        q, valid, stamp = craft.star_tracker_sample()
        r = plant.star_tracker_reading()
        assert (q, valid) == (r[:4], r[4]) and stamp == craft.time_of(int(round(r[5] * 1e9)))
        q_on, n, stamp = craft.orbit_frame_sample()
        assert q_on == frames.q_ON(plant.orbit, plant.t) and n == plant.orbit.mean_motion
        bx, by, bz, stamp = craft.magnetometer_sample()
        b = plant.b_B
        assert (bx, by, bz) == (b[0] * GAUSS_PER_TESLA, b[1] * GAUSS_PER_TESLA, b[2] * GAUSS_PER_TESLA)
        assert b == rotate_n_to_b(plant.q_BN, plant._b_N) and stamp == craft.time_of(plant.t_ns)
