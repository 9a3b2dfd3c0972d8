"""Simulated ImuManager: the PROVES IMU manager's ports, backed by the simulated LIS2MDL and LSM6DSO.

Same ports, parameters, commands, channels and unit conventions as the flight
``Components.ImuManager`` (PROVES reference), so the DetumbleManager cannot tell it from the real
one. Sensor frame = body frame B under AXIS_ORIENTATION = STANDARD; the other orientations rotate
every reading about z as the flight code does. Deviations: ``docs/components/simulated_drivers.md``.

Ports (all sync; every ``ref condition`` port returns a :class:`~detumble.components.types.Result`):

===============================  ==================================================================
``run(context)``                 Svc.Sched: read all three sensors and write their channels
``accelerationGet()``            ``Result(Acceleration, Success)``, m/s² (bias + noise + centripetal)
``angularVelocityGet()``         ``Result(AngularVelocity, Success)``, rad/s, ω_BN in B (held gyro sample)
``angularVelocityMagnitudeGet``  ``(unit) -> Result(F64, Success)``, |ω| in deg/s or rad/s
``magneticFieldGet()``           ``Result(MagneticField, Success)``, gauss in B, ``timestamp`` = the time
                                 the sensor took the sample (sample-and-hold at the ODR)
``magneticFieldSamplingPeriodGet``  ``Result(TimeIntervalValue, Success)``: 1 / MAGNETOMETER_SAMPLING_FREQUENCY
===============================  ==================================================================

Fault injection (simulation only): :meth:`ImuManager.set_read_fault` or the ``SIM_SET_READ_FAULT``
command. ``FAIL`` makes reads of that sensor return ``FAILURE`` with a throttled WARNING_LO event;
``NAN`` / ``INF`` make them *succeed* with NaN / +inf components (a corrupted sample the driver
did not catch), which is what the consumers must survive.
"""

from __future__ import annotations

import logging
import math

from fprime_lite import (F64, I32, Channel, Event, FwEnum, Param, PassiveComponent,
                         PortType, Sched, Severity, Struct, sync_command, sync_input)
from fprime_lite.model.types import U8

from detumble.components.types import (AngularUnit, AngularVelocityMagnitudeGet, MagneticField, MagneticFieldGet,
                                       Result, SamplingPeriodGet, Success, TimeIntervalValue)
from detumble.components.types import new_result as _new_result  # Result(...) without its Python frame
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

# the gyro types are shared with the attitude controller, which may not import proves
from detumble.components.attitude_types import AngularVelocity, AngularVelocityGet

__all__ = ["ImuManager", "AxisOrientation", "Acceleration", "AngularVelocity", "AccelerationGet", "AngularVelocityGet",
           "Lis2mdlSamplingFrequency", "Lsm6dsoSamplingFrequency", "SimImuSensor", "SimReadFault",
           "LIS2MDL_HZ", "LSM6DSO_HZ"]

log = logging.getLogger("detumble.proves")

_NAN = float("nan")
_INF = float("inf")


# --- types (flight Drv.Acceleration / Drv.AngularVelocity and ImuManager.fpp enums) ---------------

class Acceleration(Struct, namespace="Drv"):
    """An accelerometer reading ``x, y, z`` in m/s² (body frame)."""

    x: F64
    y: F64
    z: F64


#: Acceleration in m/s²; returns ``Result(Acceleration, Success)``.
AccelerationGet = PortType("Components.AccelerationGet", returns=Result)


class Lis2mdlSamplingFrequency(FwEnum, namespace="Components"):
    """LIS2MDL output data rates (flight ImuManager.fpp)."""

    SF_10Hz = 0
    SF_20Hz = 1
    SF_50Hz = 2
    SF_100Hz = 3


class Lsm6dsoSamplingFrequency(FwEnum, namespace="Components"):
    """LSM6DSO output data rates (flight ImuManager.fpp)."""

    SF_12_5Hz = 0
    SF_26Hz = 1
    SF_52Hz = 2
    SF_104Hz = 3
    SF_208Hz = 4
    SF_416Hz = 5
    SF_833Hz = 6
    SF_1_66kHz = 7
    SF_3_33kHz = 8
    SF_6_66kHz = 9


LIS2MDL_HZ = {Lis2mdlSamplingFrequency.SF_10Hz: 10.0, Lis2mdlSamplingFrequency.SF_20Hz: 20.0,
              Lis2mdlSamplingFrequency.SF_50Hz: 50.0, Lis2mdlSamplingFrequency.SF_100Hz: 100.0}
LSM6DSO_HZ = {Lsm6dsoSamplingFrequency.SF_12_5Hz: 12.5, Lsm6dsoSamplingFrequency.SF_26Hz: 26.0,
              Lsm6dsoSamplingFrequency.SF_52Hz: 52.0, Lsm6dsoSamplingFrequency.SF_104Hz: 104.0,
              Lsm6dsoSamplingFrequency.SF_208Hz: 208.0, Lsm6dsoSamplingFrequency.SF_416Hz: 416.0,
              Lsm6dsoSamplingFrequency.SF_833Hz: 833.0, Lsm6dsoSamplingFrequency.SF_1_66kHz: 1666.0,
              Lsm6dsoSamplingFrequency.SF_3_33kHz: 3333.0, Lsm6dsoSamplingFrequency.SF_6_66kHz: 6666.0}


class AxisOrientation(FwEnum, namespace="Components"):
    """How the IMU board is mounted (flight ImuManager.fpp): readings are rotated about z."""

    STANDARD = 0
    ROTATED_90_DEG_CW = 1
    ROTATED_90_DEG_CCW = 2
    ROTATED_180_DEG = 3


class SimImuSensor(FwEnum, namespace="Sim", rep=U8):
    """Target of an IMU fault. ``MAGNETOMETER_PERIOD`` is the sampling-period port."""

    ALL = 0
    MAGNETOMETER = 1
    GYROSCOPE = 2
    ACCELEROMETER = 3
    MAGNETOMETER_PERIOD = 4


class SimReadFault(FwEnum, namespace="Sim", rep=U8):
    """Injected read fault: NONE (healthy), FAIL (condition FAILURE), NAN / INF (corrupted values)."""

    NONE = 0
    FAIL = 1
    NAN = 2
    INF = 3


_SENSORS = (SimImuSensor.MAGNETOMETER, SimImuSensor.GYROSCOPE, SimImuSensor.ACCELEROMETER,
            SimImuSensor.MAGNETOMETER_PERIOD)
# looked up once: the reads below run at the controller's 50 Hz
_STANDARD = AxisOrientation.STANDARD
_CW = AxisOrientation.ROTATED_90_DEG_CW
_CCW = AxisOrientation.ROTATED_90_DEG_CCW
_HALF_TURN = AxisOrientation.ROTATED_180_DEG
_NO_FAULT = SimReadFault.NONE
_FAIL = SimReadFault.FAIL
_SUCCESS = Success.SUCCESS
_GYROSCOPE = SimImuSensor.GYROSCOPE


def _rotated(o, x: float, y: float, z: float) -> tuple[float, float, float]:
    """``(x, y, z)`` in the board axes of orientation ``o`` (a rotation about the board's z axis)."""
    if o == _STANDARD:
        return x, y, z
    if o == _CW:
        return y, -x, z
    if o == _CCW:
        return -y, x, z
    if o == _HALF_TURN:
        return -x, -y, z
    return x, y, z


class ImuManager(PassiveComponent):
    """Simulated IMU manager (LIS2MDL magnetometer + LSM6DSO gyro/accelerometer) on a
    :class:`~detumble.drivers.spacecraft.SimulatedSpacecraft`.

    Args:
        name: instance name (the reference deployment's is ``imuManager``).
        spacecraft: the simulated spacecraft whose sensors are read.
        stamp_with_read_time: stamp magnetic-field readings with the read time (``getTime()``, as the
            flight code does) instead of the sensor's sample time (default False: sample time).
    """

    # --- ports ---------------------------------------------------------------------------------

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """Read every sensor and write its channel (the flight 1 Hz collection)."""
        self.accelerationGet_handler()
        self.angularVelocityGet_handler()
        self.magneticFieldGet_handler()

    @sync_input(AccelerationGet)
    def accelerationGet(self) -> Result:
        """Acceleration, m/s², body frame."""
        return self.accelerationGet_handler()

    @sync_input(AngularVelocityGet)
    def angularVelocityGet(self) -> Result:
        """Angular velocity ω_BN_B, rad/s (the held gyro sample).

        The read itself (the attitude controller calls this port every tick; the other readers go
        through :meth:`angularVelocityGet_handler`).
        """
        if self._faults[_GYROSCOPE] == _NO_FAULT:
            # _read written out for a healthy gyro (the attitude controller reads it every tick);
            # AngularVelocity has no time stamp, so the sample's time is not asked for. Kept (issue
            # 26) with _orient below: 0.56-1.18 µs less a read than the calls, one read an adcs_ref
            # (≈ 77 µs of CPU) or coursework (≈ 71 µs) tick: 0.7-1.7 % of it;
            # `python benchmarks/bench_inlined.py gyro_read`
            # (3 sittings on the shared 2-core machine, 2026-12-03, each the best of 40).
            try:
                v = self.spacecraft.gyro_sample(False)
            except Exception as exc:  # noqa: BLE001 - a simulation fault is a failed read, never an exception
                self.report_fault(f"{_GYROSCOPE.name} read", exc)
                self.Lsm6dsoDeviceNotReady()
                return Result(AngularVelocity(0.0, 0.0, 0.0), Success.FAILURE)
            failed = self.Lsm6dsoDeviceNotReady
            if failed.count:  # clear_throttle, where there is something to clear
                failed.clear_throttle()
        else:
            v, _, ok = self._read(_GYROSCOPE, self.spacecraft.gyro_sample, self.Lsm6dsoDeviceNotReady)
            if not ok:
                return Result(AngularVelocity(0.0, 0.0, 0.0), Success.FAILURE)
        o = self.AXIS_ORIENTATION.value  # _orient, written out for the standard orientation
        self.AxisOrientation.write(o)
        if o == _STANDARD:
            value = AngularVelocity(v[0], v[1], v[2])
        else:
            value = AngularVelocity(*_rotated(o, v[0], v[1], v[2]))
        self.AngularVelocity.write(value)
        return _new_result(Result, (value, _SUCCESS))

    @sync_input(AngularVelocityMagnitudeGet)
    def angularVelocityMagnitudeGet(self, unit: AngularUnit) -> Result:
        """|ω| in ``unit`` (DEG_PER_SEC or RAD_PER_SEC). An unknown unit fails (InvalidAngularUnit)."""
        valid = isinstance(unit, int) and not isinstance(unit, bool)
        if valid and unit == AngularUnit.DEG_PER_SEC:
            scale = 180.0 / math.pi
        elif valid and unit == AngularUnit.RAD_PER_SEC:
            scale = 1.0
        else:
            code = int(unit) if valid and -2**31 <= unit < 2**31 else -1
            self.InvalidAngularUnit(code)
            return Result(_NAN, Success.FAILURE)
        value, condition = self.angularVelocityGet_handler()
        if condition != Success.SUCCESS:
            return Result(_NAN, Success.FAILURE)
        x, y, z = value.x, value.y, value.z
        return Result(math.sqrt(x * x + y * y + z * z) * scale, Success.SUCCESS)

    @sync_input(MagneticFieldGet)
    def magneticFieldGet(self) -> Result:
        """Magnetic field in gauss (body frame) with the sample's time stamp."""
        return self.magneticFieldGet_handler()

    @sync_input(SamplingPeriodGet)
    def magneticFieldSamplingPeriodGet(self) -> Result:
        """The magnetometer output period ``{0 s, 1e6 / f µs}`` from MAGNETOMETER_SAMPLING_FREQUENCY."""
        if self._faults[SimImuSensor.MAGNETOMETER_PERIOD] != SimReadFault.NONE:
            self.MagnetometerSamplingFrequencyGetFailed()
            return Result(TimeIntervalValue(0, 0), Success.FAILURE)
        hz = LIS2MDL_HZ.get(self.MAGNETOMETER_SAMPLING_FREQUENCY.value, 0.0)
        if hz <= 0.0:  # pragma: no cover - the enum has no 0 Hz value
            self.MagnetometerSamplingFrequencyZeroHz()
            return Result(TimeIntervalValue(0, 0), Success.FAILURE)
        if self.MagnetometerSamplingFrequencyGetFailed.count:  # clear_throttle, where there is something to clear
            self.MagnetometerSamplingFrequencyGetFailed.clear_throttle()
        return Result(TimeIntervalValue(0, int(1.0 / hz * 1e6)), Success.SUCCESS)

    # --- parameters (flight ids) ---------------------------------------------------------------

    ACCELEROMETER_SAMPLING_FREQUENCY = Param(Lsm6dsoSamplingFrequency, default=Lsm6dsoSamplingFrequency.SF_12_5Hz,
                                             id=0)
    GYROSCOPE_SAMPLING_FREQUENCY = Param(Lsm6dsoSamplingFrequency, default=Lsm6dsoSamplingFrequency.SF_104Hz, id=1)
    MAGNETOMETER_SAMPLING_FREQUENCY = Param(Lis2mdlSamplingFrequency, default=Lis2mdlSamplingFrequency.SF_100Hz,
                                            id=2)
    AXIS_ORIENTATION = Param(AxisOrientation, default=AxisOrientation.STANDARD, id=3)

    # --- channels (flight order) ---------------------------------------------------------------

    AxisOrientation = Channel(AxisOrientation)
    Acceleration = Channel(Acceleration, units="m/s^2")
    AngularVelocity = Channel(AngularVelocity, units="rad/s")
    MagneticField = Channel(MagneticField, units="G")
    AccelerometerSamplingFrequency = Channel(Lsm6dsoSamplingFrequency, update="on change")
    GyroscopeSamplingFrequency = Channel(Lsm6dsoSamplingFrequency, update="on change")
    MagnetometerSamplingFrequency = Channel(Lis2mdlSamplingFrequency, update="on change")

    # --- events (flight order, severities and formats; then the simulation's own) --------------

    Lis2mdlDeviceNotReady = Event(Severity.WARNING_HI, "LIS2MDL device not ready", throttle=5)
    Lsm6dsoDeviceNotReady = Event(Severity.WARNING_HI, "LSM6DSO device not ready", throttle=5)
    AccelerometerSamplingFrequencyNotConfigured = Event(
        Severity.WARNING_HI, "LSM6DSO accelerometer sampling frequency not configured", throttle=5)
    GyroscopeSamplingFrequencyNotConfigured = Event(
        Severity.WARNING_HI, "LSM6DSO gyroscope sampling frequency not configured", throttle=5)
    MagnetometerSamplingFrequencyNotConfigured = Event(
        Severity.WARNING_HI, "LIS2MDL magnetomiter sampling frequency not configured", throttle=5)
    MagnetometerSamplingFrequencyGetFailed = Event(
        Severity.WARNING_LO, "Failed to retrieve LIS2MDL magnetometer sampling frequency", throttle=5)
    MagnetometerSamplingFrequencyZeroHz = Event(
        Severity.WARNING_LO, "LIS2MDL magnetometer sampling frequency is set to 0 Hz", throttle=5)
    AccelerationData = Event(Severity.ACTIVITY_LO, "Acceleration: x={} m/s^2, y={} m/s^2, z={} m/s^2",
                             x=F64, y=F64, z=F64)
    AngularVelocityData = Event(Severity.ACTIVITY_LO, "Angular Velocity: x={} rad/s, y={} rad/s, z={} rad/s",
                                x=F64, y=F64, z=F64)
    MagneticFieldData = Event(Severity.ACTIVITY_LO, "Magnetic Field: x={} gauss, y={} gauss, z={} gauss",
                              x=F64, y=F64, z=F64)
    InvalidAngularUnit = Event(Severity.WARNING_LO, "Invalid angular unit {d}; use RAD_PER_SEC or DEG_PER_SEC",
                               unit=I32, throttle=5, id=0x80)
    SimReadFaultSet = Event(Severity.ACTIVITY_HI, "SIM: {} read fault set to {}", sensor=SimImuSensor,
                            fault=SimReadFault)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0,
                 stamp_with_read_time: bool = False):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft
        self.stamp_with_read_time = bool(stamp_with_read_time)
        self._faults = {s: SimReadFault.NONE for s in _SENSORS}

    # --- fault injection -----------------------------------------------------------------------

    def set_read_fault(self, sensor: SimImuSensor, fault: SimReadFault) -> None:
        """Make reads of ``sensor`` (or ALL) fail (FAIL), return NaN (NAN) or +inf (INF), or heal (NONE)."""
        sensor = SimImuSensor(sensor)
        fault = SimReadFault(fault)
        for s in (_SENSORS if sensor == SimImuSensor.ALL else (sensor,)):
            self._faults[s] = fault
        self.SimReadFaultSet(sensor, fault)

    def fail_reads(self, enable: bool = True) -> None:
        """Shorthand: every read fails (``enable``) or every sensor is healthy again."""
        self.set_read_fault(SimImuSensor.ALL, SimReadFault.FAIL if enable else SimReadFault.NONE)

    def read_fault(self, sensor: SimImuSensor) -> SimReadFault:
        return self._faults[SimImuSensor(sensor)]

    # --- commands (flight) ---------------------------------------------------------------------

    @sync_command()
    def GET_ACCELERATION(self):
        """Read the accelerometer and log AccelerationData (as flown: OK, zeros after a failed read)."""
        value, _ = self.accelerationGet_handler()
        self.AccelerationData(value.x, value.y, value.z)

    @sync_command()
    def GET_ANGULAR_VELOCITY(self):
        """Read the gyro and log AngularVelocityData (rad/s)."""
        value, _ = self.angularVelocityGet_handler()
        self.AngularVelocityData(value.x, value.y, value.z)

    @sync_command()
    def GET_MAGNETIC_FIELD(self):
        """Read the magnetometer and log MagneticFieldData (gauss)."""
        value, _ = self.magneticFieldGet_handler()
        self.MagneticFieldData(value.x, value.y, value.z)

    @sync_command()
    def SIM_SET_READ_FAULT(self, sensor: SimImuSensor, fault: SimReadFault):
        """SIMULATION ONLY: inject (or clear with NONE) a read fault on ``sensor``."""
        self.set_read_fault(sensor, fault)

    # --- parameter hooks -----------------------------------------------------------------------

    def parameters_loaded(self) -> None:
        """Configure the simulated sensors' ODRs from the parameters (flight ``configure()``)."""
        self._configure_sensors()

    def parameter_updated(self, local_id: int) -> None:
        """A sampling-frequency change reconfigures the sensors (the flight run() does it on its
        next call; here it is at once). AXIS_ORIENTATION applies from the next read."""
        self._configure_sensors()

    def _configure_sensors(self) -> None:
        mag = self.MAGNETOMETER_SAMPLING_FREQUENCY.value
        gyro = self.GYROSCOPE_SAMPLING_FREQUENCY.value
        accel = self.ACCELEROMETER_SAMPLING_FREQUENCY.value
        self.spacecraft.set_magnetometer_odr_hz(LIS2MDL_HZ[mag])
        self.spacecraft.set_gyro_odr_hz(LSM6DSO_HZ[gyro])
        self.spacecraft.set_accelerometer_odr_hz(LSM6DSO_HZ[accel])
        self.MagnetometerSamplingFrequency.write(mag)
        self.AccelerometerSamplingFrequency.write(accel)
        self.GyroscopeSamplingFrequency.write(gyro)

    def _orient(self, x: float, y: float, z: float) -> tuple[float, float, float]:
        """Apply AXIS_ORIENTATION (a rotation about the board's z axis) and write its channel."""
        o = self.AXIS_ORIENTATION.value
        self.AxisOrientation.write(o)
        return _rotated(o, x, y, z)

    # --- reads ---------------------------------------------------------------------------------

    def _read(self, sensor: SimImuSensor, read, failed_event):
        """``(components, stamp, ok)`` after applying the injected fault; never raises."""
        fault = self._faults[sensor]
        if fault == _FAIL:
            failed_event()
            return None, None, False
        try:
            values = read()
        except Exception as exc:  # noqa: BLE001 - a simulation fault is a failed read, never an exception
            self.report_fault(f"{sensor.name} read", exc)
            failed_event()
            return None, None, False
        if failed_event.count:  # clear_throttle, where there is something to clear
            failed_event.clear_throttle()
        if fault == _NO_FAULT:
            return values, (values[3] if len(values) > 3 else None), True
        if fault == SimReadFault.NAN:
            values = (_NAN, _NAN, _NAN) + tuple(values[3:])
        elif fault == SimReadFault.INF:
            values = (_INF, _INF, _INF) + tuple(values[3:])
        return values, (values[3] if len(values) > 3 else None), True

    def accelerationGet_handler(self) -> Result:
        v, _, ok = self._read(SimImuSensor.ACCELEROMETER, self.spacecraft.acceleration,
                              self.Lsm6dsoDeviceNotReady)
        if not ok:
            return Result(Acceleration(0.0, 0.0, 0.0), Success.FAILURE)
        value = Acceleration(*self._orient(v[0], v[1], v[2]))
        self.Acceleration.write(value)
        return Result(value, Success.SUCCESS)

    def angularVelocityGet_handler(self) -> Result:
        """The gyro read (:meth:`angularVelocityGet`), for the 1 Hz collection and the commands."""
        return self.angularVelocityGet()

    def magneticFieldGet_handler(self) -> Result:
        v, stamp, ok = self._read(SimImuSensor.MAGNETOMETER, self.spacecraft.magnetometer_sample,
                                  self.Lis2mdlDeviceNotReady)
        if not ok:
            return Result(MagneticField(0.0, 0.0, 0.0, self.spacecraft.now()), Success.FAILURE)
        if self.stamp_with_read_time:
            stamp = self.spacecraft.now()
        value = MagneticField(*self._orient(v[0], v[1], v[2]), stamp)
        self.MagneticField.write(value)
        return _new_result(Result, (value, _SUCCESS))
