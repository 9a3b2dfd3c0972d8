"""The simulated drivers in a closed loop on a real Scheduler: a minimal B-dot cycle through the
ports (stand-in for the DetumbleManager, which is tested on its own) detumbles the spacecraft."""

from detumble.sim.coils import level_for_coil_dipole
from detumble.drivers.magnetorquer_driver import driver_instance_name, make_magnetorquer_drivers
from detumble.drivers.spacecraft import SimulatedSpacecraft, TruthRecorder, scenario_epoch_us
from detumble.proves.imu_manager import ImuManager
from detumble.components.types import AngularUnit, Success
from fprime_lite import SimulatedClock
from fprime_lite.deploy.scheduler import Scheduler

GAIN = 3.0  # A·m²·s/G, the DetumbleManager default


def _fly(scenario, duration_s, control=True):
    sched = Scheduler(SimulatedClock(epoch_us=scenario_epoch_us(scenario)))
    craft = SimulatedSpacecraft.for_scheduler(scenario, sched)
    imu = ImuManager("imuManager", craft)
    drivers = make_magnetorquer_drivers(craft)
    coils = scenario.spacecraft.coils
    trace = TruthRecorder()
    craft.set_trace(trace, 10_000_000)
    st = {"phase": "cooldown", "window": [], "ticks": 0, "levels": {}}

    def run():  # 50 Hz: cooldown 1 tick, 5 B samples, 16 ticks of torque (the flight cycle's shape)
        if st["phase"] == "cooldown":
            st["phase"], st["window"] = "sensing", []
        elif st["phase"] == "sensing":
            value, condition = imu.magneticFieldGet()
            assert condition == Success.SUCCESS
            st["window"].append(value)
            if len(st["window"]) == 5:
                a, b = st["window"][0], st["window"][-1]
                dt = (b.timestamp.total_us - a.timestamp.total_us) / 1e6
                m = [-GAIN * (b.x - a.x) / dt, -GAIN * (b.y - a.y) / dt, -GAIN * (b.z - a.z) / dt]
                st["levels"] = {0: level_for_coil_dipole(coils[0], m[0]), 1: -level_for_coil_dipole(coils[1], m[0]),
                                2: level_for_coil_dipole(coils[2], m[1]), 3: -level_for_coil_dipole(coils[3], m[1]),
                                5: -level_for_coil_dipole(coils[5], m[2])}
                st["phase"], st["ticks"] = "actuating", 0
        else:
            for face, level in st["levels"].items():
                assert drivers[driver_instance_name(face)].start(level) == Success.SUCCESS
            st["ticks"] += 1
            if st["ticks"] >= 16:
                for d in drivers.values():
                    assert d.stop() == Success.SUCCESS
                st["phase"] = "cooldown"

    if control:
        sched.call_every(20_000, run)
    sched.run(until_us=int(duration_s * 1e6))
    assert craft.plant.t_ns == int(duration_s * 1e9)
    return craft, imu, trace


def test_bdot_through_the_simulated_drivers_detumbles(default_scenario):
    craft, imu, trace = _fly(default_scenario, 200.0)
    w, condition = imu.angularVelocityMagnitudeGet(AngularUnit.DEG_PER_SEC)
    assert condition == Success.SUCCESS
    assert trace.rows[0].rate_deg_s > 29.9
    assert craft.plant.rate_deg_s < 25.0  # about 30 -> 23.6 deg/s in 200 s
    assert abs(w - craft.plant.rate_deg_s) < 1.0  # gyro bias and noise
    rates = [r.rate_deg_s for r in trace.rows]
    assert rates[-1] < rates[len(rates) // 2] < rates[0]


def test_without_control_the_tumble_persists(default_scenario):
    craft, _, trace = _fly(default_scenario, 200.0, control=False)
    assert abs(craft.plant.rate_deg_s - 30.0) < 0.5  # residual dipole and gravity gradient only
    assert len(trace.rows) == 21
