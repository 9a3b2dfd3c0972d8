"""Simulated ImuManager through the port harness: ports, units, time stamps, commands, faults."""

import math

import pytest

from detumble.sim.coils import X_PLUS
from detumble.proves.imu_manager import AxisOrientation, Lsm6dsoSamplingFrequency
from detumble.proves.imu_manager import (Acceleration, AngularVelocity, ImuManager, Lis2mdlSamplingFrequency,
                                         SimImuSensor, SimReadFault)
from detumble.components.types import AngularUnit, MagneticField, Success, TimeIntervalValue
from fprime_lite import CmdResponse, Severity



@pytest.fixture
def rig(fprime_harness, make_craft, request):
    """``(harness, spacecraft)``; the scenario fixture is chosen by the ``scenario`` marker name."""
    scenario = request.getfixturevalue(getattr(request, "param", "default_scenario"))
    craft = make_craft(scenario)
    h = fprime_harness(ImuManager("imuManager", craft, base_id=0x2000))
    h.set_test_time(craft.now())
    return h, craft


def _at(h, craft, time_us):
    craft.clock.set_us(time_us)
    h.set_test_time(craft.now())


def test_magnetic_field_is_the_held_sample_in_gauss_with_its_sample_time(rig):
    h, craft = rig
    _at(h, craft, 25_000)
    value, condition = h.invoke("magneticFieldGet")
    assert condition == Success.SUCCESS
    assert isinstance(value, MagneticField)
    assert (value.x, value.y, value.z) == craft.plant.magnetometer.sample_gauss
    assert value.timestamp.total_us == craft.clock.epoch_us + 20_000  # the 100 Hz sample at 20 ms
    assert 0.19 < math.sqrt(value.x ** 2 + value.y ** 2 + value.z ** 2) < 0.55  # gauss, LEO
    assert h.tlm_values("MagneticField") == [value]


@pytest.mark.parametrize("rig", ["ideal_scenario"], indirect=True)
def test_ideal_magnetometer_reads_the_true_field(rig):
    h, craft = rig
    _at(h, craft, 12_345)
    value, _ = h.invoke("magneticFieldGet")
    assert (value.x, value.y, value.z) == pytest.approx(tuple(b * 1e4 for b in craft.plant.b_B), rel=1e-15)
    assert value.timestamp == craft.now()


def test_read_time_stamping_option(fprime_harness, make_craft):
    craft = make_craft()
    h = fprime_harness(ImuManager("imuManager", craft, stamp_with_read_time=True))
    craft.clock.set_us(25_000)
    value, _ = h.invoke("magneticFieldGet")
    assert value.timestamp == craft.now()


@pytest.mark.parametrize("rig", ["quiet_scenario"], indirect=True)
def test_coil_coupling_is_visible_while_a_coil_is_on(rig):
    """A reading taken while X+ is driven full scale includes K·m = 1.6e-3 T/(A·m²) × 0.0581 A·m²
    = 0.93 G on x; once the coil is off, the next sample is the geomagnetic field again."""
    h, craft = rig
    k_gauss = 1.6e-3 * 1e4
    m_max = 96 * 0.053 * 0.045 * 3.3 / 13
    _at(h, craft, 10_000)
    craft.set_coil_level(X_PLUS, 127)
    _at(h, craft, 20_000)  # an ODR instant: the sample is taken now, with the coil on
    value, _ = h.invoke("magneticFieldGet")
    truth = [b * 1e4 for b in craft.plant.b_B]
    assert value.x - truth[0] == pytest.approx(k_gauss * m_max, rel=1e-9)
    assert value.y == pytest.approx(truth[1], abs=1e-12)
    assert value.z == pytest.approx(truth[2], abs=1e-12)
    craft.set_coil_level(X_PLUS, 0)
    _at(h, craft, 25_000)  # still the sample held from 20 ms: contaminated
    assert h.invoke("magneticFieldGet").value.x == value.x
    _at(h, craft, 30_000)  # a fresh sample, coil off
    clean, _ = h.invoke("magneticFieldGet")
    assert clean.x == pytest.approx(craft.plant.b_B[0] * 1e4, abs=1e-12)


@pytest.mark.parametrize("rig", ["ideal_scenario"], indirect=True)
def test_angular_velocity_rad_s_and_magnitude_units(rig):
    h, craft = rig
    _at(h, craft, 40_000)
    w, condition = h.invoke("angularVelocityGet")
    assert condition == Success.SUCCESS and isinstance(w, AngularVelocity)
    assert (w.x, w.y, w.z) == craft.plant.omega_BN_B
    rad, c1 = h.invoke("angularVelocityMagnitudeGet", AngularUnit.RAD_PER_SEC)
    deg, c2 = h.invoke("angularVelocityMagnitudeGet", AngularUnit.DEG_PER_SEC)
    assert c1 == c2 == Success.SUCCESS
    assert rad == pytest.approx(math.radians(30.0), rel=1e-3)
    assert deg == pytest.approx(rad * 180.0 / math.pi, rel=1e-15)
    assert deg == pytest.approx(craft.plant.rate_deg_s, rel=1e-12)
    assert h.tlm_values("AngularVelocity")[-1] == w


def test_noisy_gyro_is_the_held_lsm6dso_sample(rig):
    h, craft = rig
    _at(h, craft, 30_000)
    w, _ = h.invoke("angularVelocityGet")
    assert (w.x, w.y, w.z) == craft.plant.gyro.sample_rad_s
    deg, _ = h.invoke("angularVelocityMagnitudeGet", AngularUnit.DEG_PER_SEC)
    assert deg == pytest.approx(30.0, abs=1.0)  # bias (0.3, -0.2, 0.1) deg/s + noise


@pytest.mark.parametrize("unit", [7, -1, True, None, 1.0, "DEG_PER_SEC"])
def test_invalid_unit_fails_without_raising(rig, unit):
    h, _ = rig
    value, condition = h.invoke("angularVelocityMagnitudeGet", unit)
    assert condition == Success.FAILURE and math.isnan(value)
    assert h.events[-1].name == "InvalidAngularUnit"
    assert h.events[-1].severity == Severity.WARNING_LO


def test_acceleration_reads_bias_noise_and_the_centripetal_term(rig):
    """IMU-ACC-001: the LSM6DSO in free fall reads its zero-g offset plus the centripetal term at its
    lever arm, with white noise: never exactly 0; the register holds a sample for one output period;
    the mean of 400 reads is within 4 sigma/sqrt(n) of bias + w x (w x r), and the spread matches the
    noise std within 20 %."""
    h, craft = rig
    reads, truth = [], []
    for k in range(400):
        _at(h, craft, k * 10_000)  # one read per LSM6DSO output period (104 Hz)
        value, condition = h.invoke("accelerationGet")
        assert condition == Success.SUCCESS
        reads.append((value.x, value.y, value.z))
        truth.append(craft.accelerometer.true_specific_force(craft.plant.omega_BN_B))
    assert h.tlm_values("Acceleration")[-1] == Acceleration(*reads[-1])
    assert all(r != (0.0, 0.0, 0.0) for r in reads)
    assert h.invoke("accelerationGet").value == Acceleration(*reads[-1])  # same output period
    spec = craft.scenario.accelerometer
    n = len(reads)
    expected = [spec.bias_mps2[k] + sum(t[k] for t in truth) / n for k in range(3)]
    for k in range(3):
        xs = [r[k] for r in reads]
        mean = sum(xs) / n
        std = math.sqrt(sum((x - mean) ** 2 for x in xs) / (n - 1))
        assert abs(mean - expected[k]) < 4 * spec.noise_std_mps2 / math.sqrt(n)
        assert abs(std / spec.noise_std_mps2 - 1.0) < 0.2


def test_run_writes_every_reading_channel(rig):
    """IMU-RUN-001: run reads the three sensors; as flown, each read also writes AxisOrientation."""
    h, _ = rig
    h.invoke("run", 0)
    assert [t.name for t in h.telemetry] == ["AxisOrientation", "Acceleration", "AxisOrientation",
                                             "AngularVelocity", "AxisOrientation", "MagneticField"]


def test_flight_ids_of_parameters_channels_and_events(rig):
    """IMU-ID-001: parameter ids 0..3 (ACCELEROMETER, GYROSCOPE, MAGNETOMETER sampling frequencies,
    AXIS_ORIENTATION), channels and events in the flight declaration order; defaults as flown."""
    h, _ = rig
    c = h.component
    assert [(p.name, p.local_id) for p in c.spec.params] == [
        ("ACCELEROMETER_SAMPLING_FREQUENCY", 0), ("GYROSCOPE_SAMPLING_FREQUENCY", 1),
        ("MAGNETOMETER_SAMPLING_FREQUENCY", 2), ("AXIS_ORIENTATION", 3)]
    assert c.ACCELEROMETER_SAMPLING_FREQUENCY.value == Lsm6dsoSamplingFrequency.SF_12_5Hz
    assert [ch.name for ch in c.spec.channels][:7] == [
        "AxisOrientation", "Acceleration", "AngularVelocity", "MagneticField", "AccelerometerSamplingFrequency",
        "GyroscopeSamplingFrequency", "MagnetometerSamplingFrequency"]
    assert [e.name for e in c.spec.events][:10] == [
        "Lis2mdlDeviceNotReady", "Lsm6dsoDeviceNotReady", "AccelerometerSamplingFrequencyNotConfigured",
        "GyroscopeSamplingFrequencyNotConfigured", "MagnetometerSamplingFrequencyNotConfigured",
        "MagnetometerSamplingFrequencyGetFailed", "MagnetometerSamplingFrequencyZeroHz", "AccelerationData",
        "AngularVelocityData", "MagneticFieldData"]
    assert [e.local_id for e in c.spec.events][:10] == list(range(10))
    # the parameters come first in the flight FPP, so their SET/SAVE opcodes are 0..7
    assert [(d.name, d.opcode) for d in c.spec.commands][6:11] == [
        ("AXIS_ORIENTATION_PRM_SET", 6), ("AXIS_ORIENTATION_PRM_SAVE", 7), ("GET_ACCELERATION", 8),
        ("GET_ANGULAR_VELOCITY", 9), ("GET_MAGNETIC_FIELD", 10)]


@pytest.mark.parametrize("orientation, expect", [
    (AxisOrientation.STANDARD, lambda x, y, z: (x, y, z)),
    (AxisOrientation.ROTATED_90_DEG_CW, lambda x, y, z: (y, -x, z)),
    (AxisOrientation.ROTATED_90_DEG_CCW, lambda x, y, z: (-y, x, z)),
    (AxisOrientation.ROTATED_180_DEG, lambda x, y, z: (-x, -y, z)),
])
def test_axis_orientation_rotates_every_reading(rig, orientation, expect):
    """IMU-AXIS-001: AXIS_ORIENTATION rotates magnetometer, gyro and accelerometer readings about z as
    the flight applyAxisOrientation does, and is reported on the AxisOrientation channel."""
    h, craft = rig
    h.param_set("AXIS_ORIENTATION", orientation)
    h.load_parameters()
    _at(h, craft, 30_000)
    raw_b = craft.magnetometer_sample()[:3]
    raw_w = craft.gyro_sample()[:3]
    raw_a = craft.acceleration()
    b = h.invoke("magneticFieldGet").value
    w = h.invoke("angularVelocityGet").value
    a = h.invoke("accelerationGet").value
    assert (b.x, b.y, b.z) == expect(*raw_b)
    assert (w.x, w.y, w.z) == expect(*raw_w)
    assert (a.x, a.y, a.z) == expect(*raw_a)
    assert h.tlm_values("AxisOrientation")[-1] == orientation


def test_accelerometer_sampling_frequency_parameter(rig):
    """IMU-ACC-002: ACCELEROMETER_SAMPLING_FREQUENCY (default 12.5 Hz) sets the accelerometer's ODR:
    reads 50 ms apart share one sample at 12.5 Hz and differ at 104 Hz."""
    h, craft = rig
    h.load_parameters()
    assert h.tlm_values("AccelerometerSamplingFrequency") == [Lsm6dsoSamplingFrequency.SF_12_5Hz]
    _at(h, craft, 0)
    first = h.invoke("accelerationGet").value
    _at(h, craft, 50_000)
    assert h.invoke("accelerationGet").value == first
    h.param_set("ACCELEROMETER_SAMPLING_FREQUENCY", Lsm6dsoSamplingFrequency.SF_104Hz)
    h.load_parameters()
    _at(h, craft, 60_000)
    second = h.invoke("accelerationGet").value
    _at(h, craft, 70_000)
    assert h.invoke("accelerationGet").value != second


def test_sampling_period_follows_the_parameter_and_reconfigures_the_sensor(rig):
    """MAGNETOMETER_SAMPLING_FREQUENCY (flight enum, default SF_100Hz) sets the reported period and
    the simulated LIS2MDL's output data rate."""
    h, craft = rig
    h.load_parameters()
    assert h.invoke("magneticFieldSamplingPeriodGet") == (TimeIntervalValue(0, 10_000), Success.SUCCESS)
    assert h.tlm_values("MagnetometerSamplingFrequency") == [Lis2mdlSamplingFrequency.SF_100Hz]
    h.param_set("MAGNETOMETER_SAMPLING_FREQUENCY", Lis2mdlSamplingFrequency.SF_50Hz)
    h.param_send("MAGNETOMETER_SAMPLING_FREQUENCY")
    h.assert_cmd_response(0, "MAGNETOMETER_SAMPLING_FREQUENCY_PRM_SET", CmdResponse.OK)
    h.assert_events_size(0)  # as flown: a parameter change logs no event of the IMU manager
    assert h.invoke("magneticFieldSamplingPeriodGet") == (TimeIntervalValue(0, 20_000), Success.SUCCESS)
    assert craft.magnetometer_period_us == 20_000
    _at(h, craft, 35_000)
    assert h.invoke("magneticFieldGet").value.timestamp.total_us == craft.clock.epoch_us + 20_000
    h.param_set("MAGNETOMETER_SAMPLING_FREQUENCY", Lis2mdlSamplingFrequency.SF_10Hz)
    h.load_parameters()
    assert h.invoke("magneticFieldSamplingPeriodGet").value == TimeIntervalValue(0, 100_000)


@pytest.mark.parametrize("port, args, event, severity", [
    ("magneticFieldGet", (), "Lis2mdlDeviceNotReady", Severity.WARNING_HI),
    ("angularVelocityGet", (), "Lsm6dsoDeviceNotReady", Severity.WARNING_HI),
    ("angularVelocityMagnitudeGet", (AngularUnit.DEG_PER_SEC,), "Lsm6dsoDeviceNotReady", Severity.WARNING_HI),
    ("accelerationGet", (), "Lsm6dsoDeviceNotReady", Severity.WARNING_HI),
    ("magneticFieldSamplingPeriodGet", (), "MagnetometerSamplingFrequencyGetFailed", Severity.WARNING_LO),
])
def test_failed_reads_return_failure_with_a_throttled_warning(rig, port, args, event, severity):
    """IMU-FAIL-001: a device that does not answer fails the read with the flight's throttled
    device-not-ready event (LIS2MDL / LSM6DSO); a good read clears the throttle."""
    h, _ = rig
    h.component.fail_reads()
    h.clear_history()
    for _ in range(7):
        _, condition = h.invoke(port, *args)
        assert condition == Success.FAILURE
    h.assert_event_count(event, 5)  # throttle 5
    assert all(e.severity == severity for e in h.events)
    assert h.telemetry == []  # a failed read writes no reading
    h.component.fail_reads(False)
    assert h.invoke(port, *args).condition == Success.SUCCESS  # recovery clears the throttle
    h.component.fail_reads()
    h.invoke(port, *args)
    h.assert_event_count(event, 6)


def test_one_sensor_can_fail_alone(rig):
    h, _ = rig
    h.component.set_read_fault(SimImuSensor.GYROSCOPE, SimReadFault.FAIL)
    assert h.invoke("angularVelocityGet").condition == Success.FAILURE
    assert h.invoke("magneticFieldGet").condition == Success.SUCCESS
    assert h.invoke("magneticFieldSamplingPeriodGet").condition == Success.SUCCESS
    h.component.set_read_fault(SimImuSensor.MAGNETOMETER_PERIOD, SimReadFault.FAIL)
    assert h.invoke("magneticFieldSamplingPeriodGet").condition == Success.FAILURE
    assert h.invoke("magneticFieldGet").condition == Success.SUCCESS


@pytest.mark.parametrize("fault, check", [(SimReadFault.NAN, math.isnan),
                                          (SimReadFault.INF, lambda v: v == math.inf)])
def test_corrupted_readings_succeed_with_nan_or_inf(rig, fault, check):
    h, craft = rig
    _at(h, craft, 20_000)
    h.send_command("SIM_SET_READ_FAULT", SimImuSensor.ALL, fault)
    h.assert_cmd_response(0, "SIM_SET_READ_FAULT", CmdResponse.OK)
    h.assert_event("SimReadFaultSet", 0, SimImuSensor.ALL, fault)
    b, c = h.invoke("magneticFieldGet")
    assert c == Success.SUCCESS and all(check(v) for v in (b.x, b.y, b.z))
    assert b.timestamp.total_us == craft.clock.epoch_us + 20_000
    w, c = h.invoke("angularVelocityMagnitudeGet", AngularUnit.DEG_PER_SEC)
    assert c == Success.SUCCESS and check(w)
    tlm = h.tlm_values("MagneticField")[-1]
    assert check(tlm.x)  # NaN / inf survive serialization to the ground
    h.send_command("GET_MAGNETIC_FIELD")
    assert check(h.events_named("MagneticFieldData")[-1][0])
    assert h.invoke("magneticFieldSamplingPeriodGet").condition == Success.FAILURE


@pytest.mark.parametrize("command, event, port", [
    ("GET_ACCELERATION", "AccelerationData", "accelerationGet"),
    ("GET_ANGULAR_VELOCITY", "AngularVelocityData", "angularVelocityGet"),
    ("GET_MAGNETIC_FIELD", "MagneticFieldData", "magneticFieldGet"),
])
def test_get_commands_log_the_reading(rig, command, event, port):
    h, craft = rig
    _at(h, craft, 50_000)
    h.send_command(command, cmd_seq=3)
    h.assert_cmd_response(0, command, CmdResponse.OK, cmd_seq=3)
    value = h.invoke(port).value
    h.assert_event(event, 0, value.x, value.y, value.z)
    assert h.events[0].severity == Severity.ACTIVITY_LO
    h.component.fail_reads()
    h.send_command(command)
    h.assert_cmd_response(1, command, CmdResponse.OK)   # as flown: the zeros of a failed read are logged
    h.assert_event(event, 1, 0.0, 0.0, 0.0)


def test_rejects_a_non_spacecraft():
    with pytest.raises(TypeError, match="SimulatedSpacecraft"):
        ImuManager("imuManager", object())


def test_a_plant_exception_is_a_failed_read(rig, monkeypatch):
    h, craft = rig

    def broken():
        raise RuntimeError("boom")

    monkeypatch.setattr(craft, "magnetometer_sample", broken)
    assert h.invoke("magneticFieldGet").condition == Success.FAILURE
    h.assert_event_count("Lis2mdlDeviceNotReady", 1)
    assert h.component.handler_faults == 1 and h.events_named("HandlerFault")[0][1] == "RuntimeError: boom"


def test_a_gyro_exception_is_a_failed_read_and_a_good_read_clears_its_throttle(rig, monkeypatch):
    """The healthy-gyro read (written out, no time stamp asked for) fails as the generic read does: FAILURE,
    Lsm6dsoDeviceNotReady, HandlerFault naming the sensor; the next good read clears the event's throttle and
    returns the sample the spacecraft holds."""
    h, craft = rig

    def broken(stamped=True):
        raise RuntimeError("boom")

    monkeypatch.setattr(craft, "gyro_sample", broken)
    assert h.invoke("angularVelocityGet").condition == Success.FAILURE
    h.assert_event_count("Lsm6dsoDeviceNotReady", 1)
    fault = h.events_named("HandlerFault")[0]
    assert h.component.handler_faults == 1 and fault[1] == "RuntimeError: boom" and "GYROSCOPE" in fault[0]
    assert h.component.Lsm6dsoDeviceNotReady.count == 1
    monkeypatch.undo()
    value, condition = h.invoke("angularVelocityGet")
    assert condition == Success.SUCCESS and h.component.Lsm6dsoDeviceNotReady.count == 0
    assert (value.x, value.y, value.z) == craft.gyro_sample()[:3] == tuple(craft.gyro_sample(False))
