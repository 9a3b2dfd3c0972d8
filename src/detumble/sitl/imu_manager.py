"""Simulated ImuManager: the PROVES IMU manager's ports, backed by the simulated LIS2MDL and LSM6DSO.

Same ports, parameters, commands, channels and unit conventions as the flight
``Components.ImuManager`` (PROVES reference), so the DetumbleManager cannot tell it from the real
one. Sensor frame = body frame B (the flight ``AXIS_ORIENTATION`` parameter is not modelled).

Ports (all sync; every ``ref condition`` port returns a :class:`~detumble.components.types.Result`):

===============================  ==================================================================
``run(context)``                 Svc.Sched: read all three sensors and write their channels
``accelerationGet()``            ``Result(Acceleration, Success)``, m/s² (zero: free fall)
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

from fprime_lite import (F64, I32, Channel, CmdResponse, Event, FwEnum, Param, PassiveComponent,
                         PortType, Sched, Severity, Struct, sync_command, sync_input)
from fprime_lite.model.types import U8

from detumble.components.types import (AngularUnit, AngularVelocityMagnitudeGet, MagneticField, MagneticFieldGet,
                                       Result, SamplingPeriodGet, Success, TimeIntervalValue)
from detumble.sitl.spacecraft import SimulatedSpacecraft

__all__ = ["ImuManager", "Acceleration", "AngularVelocity", "AccelerationGet", "AngularVelocityGet",
           "Lis2mdlSamplingFrequency", "Lsm6dsoSamplingFrequency", "SimImuSensor", "SimReadFault",
           "LIS2MDL_HZ", "LSM6DSO_HZ"]

log = logging.getLogger("detumble.sitl")

_NAN = float("nan")
_INF = float("inf")


# --- types (flight Drv.Acceleration / Drv.AngularVelocity and ImuManager.fpp enums) ---------------

class Acceleration(Struct, namespace="Drv"):
    """An accelerometer reading ``x, y, z`` in m/s² (body frame)."""

    x: F64
    y: F64
    z: F64


class AngularVelocity(Struct, namespace="Drv"):
    """A gyro reading ``x, y, z`` in rad/s (ω_BN expressed in the body frame)."""

    x: F64
    y: F64
    z: F64


#: Acceleration in m/s²; returns ``Result(Acceleration, Success)``.
AccelerationGet = PortType("Components.AccelerationGet", returns=Result)
#: Angular velocity in rad/s; returns ``Result(AngularVelocity, Success)``.
AngularVelocityGet = PortType("Components.AngularVelocityGet", returns=Result)


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


class ImuManager(PassiveComponent):
    """Simulated IMU manager (LIS2MDL magnetometer + LSM6DSO gyro/accelerometer) on a
    :class:`~detumble.sitl.spacecraft.SimulatedSpacecraft`.

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
        """Angular velocity ω_BN_B, rad/s (the held gyro sample)."""
        return self.angularVelocityGet_handler()

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
            self.MagnetometerSamplingFrequencyGetFailed()
            return Result(TimeIntervalValue(0, 0), Success.FAILURE)
        self.MagnetometerSamplingFrequencyGetFailed.clear_throttle()
        return Result(TimeIntervalValue(0, int(1.0 / hz * 1e6)), Success.SUCCESS)

    # --- parameters (flight ids) ---------------------------------------------------------------

    GYROSCOPE_SAMPLING_FREQUENCY = Param(Lsm6dsoSamplingFrequency, default=Lsm6dsoSamplingFrequency.SF_104Hz, id=1)
    MAGNETOMETER_SAMPLING_FREQUENCY = Param(Lis2mdlSamplingFrequency, default=Lis2mdlSamplingFrequency.SF_100Hz,
                                            id=2)

    # --- channels ------------------------------------------------------------------------------

    Acceleration = Channel(Acceleration, units="m/s^2")
    AngularVelocity = Channel(AngularVelocity, units="rad/s")
    MagneticField = Channel(MagneticField, units="G")
    GyroscopeSamplingFrequency = Channel(Lsm6dsoSamplingFrequency, update="on change")
    MagnetometerSamplingFrequency = Channel(Lis2mdlSamplingFrequency, update="on change")

    # --- events --------------------------------------------------------------------------------

    AccelerationData = Event(Severity.ACTIVITY_LO, "Acceleration: {.6f}, {.6f}, {.6f} m/s^2", x=F64, y=F64, z=F64)
    AngularVelocityData = Event(Severity.ACTIVITY_LO, "Angular velocity: {.6f}, {.6f}, {.6f} rad/s",
                                x=F64, y=F64, z=F64)
    MagneticFieldData = Event(Severity.ACTIVITY_LO, "Magnetic field: {.6f}, {.6f}, {.6f} G", x=F64, y=F64, z=F64)
    MagnetometerReadFailed = Event(Severity.WARNING_LO, "LIS2MDL magnetometer read failed", throttle=5)
    GyroscopeReadFailed = Event(Severity.WARNING_LO, "LSM6DSO gyroscope read failed", throttle=5)
    AccelerometerReadFailed = Event(Severity.WARNING_LO, "LSM6DSO accelerometer read failed", throttle=5)
    MagnetometerSamplingFrequencyGetFailed = Event(
        Severity.WARNING_LO, "Failed to retrieve LIS2MDL magnetometer sampling frequency", throttle=5)
    InvalidAngularUnit = Event(Severity.WARNING_LO, "Invalid angular unit {d}; use RAD_PER_SEC or DEG_PER_SEC",
                               unit=I32, throttle=5)
    GyroscopeSamplingFrequencyParamSet = Event(
        Severity.ACTIVITY_HI, "GYROSCOPE_SAMPLING_FREQUENCY parameter set to {}.", value=Lsm6dsoSamplingFrequency)
    MagnetometerSamplingFrequencyParamSet = Event(
        Severity.ACTIVITY_HI, "MAGNETOMETER_SAMPLING_FREQUENCY parameter set to {}.", value=Lis2mdlSamplingFrequency)
    SimReadFaultSet = Event(Severity.ACTIVITY_HI, "SIM: {} read fault set to {}", sensor=SimImuSensor,
                            fault=SimReadFault)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0,
                 stamp_with_read_time: bool = False):
        super().__init__(name, base_id=base_id)
        if not isinstance(spacecraft, SimulatedSpacecraft):
            raise TypeError(f"{name}: spacecraft must be a SimulatedSpacecraft, got {spacecraft!r}")
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

    @sync_command()
    def SIM_SET_READ_FAULT(self, sensor: SimImuSensor, fault: SimReadFault):
        """SIMULATION ONLY: inject (or clear with NONE) a read fault on ``sensor``."""
        self.set_read_fault(sensor, fault)

    # --- commands (flight) ---------------------------------------------------------------------

    @sync_command()
    def GET_ACCELERATION(self):
        """Read the accelerometer and log AccelerationData (EXECUTION_ERROR if the read fails)."""
        value, condition = self.accelerationGet_handler()
        if condition != Success.SUCCESS:
            return CmdResponse.EXECUTION_ERROR
        self.AccelerationData(value.x, value.y, value.z)
        return CmdResponse.OK

    @sync_command()
    def GET_ANGULAR_VELOCITY(self):
        """Read the gyro and log AngularVelocityData (rad/s)."""
        value, condition = self.angularVelocityGet_handler()
        if condition != Success.SUCCESS:
            return CmdResponse.EXECUTION_ERROR
        self.AngularVelocityData(value.x, value.y, value.z)
        return CmdResponse.OK

    @sync_command()
    def GET_MAGNETIC_FIELD(self):
        """Read the magnetometer and log MagneticFieldData (gauss)."""
        value, condition = self.magneticFieldGet_handler()
        if condition != Success.SUCCESS:
            return CmdResponse.EXECUTION_ERROR
        self.MagneticFieldData(value.x, value.y, value.z)
        return CmdResponse.OK

    # --- parameter hooks -----------------------------------------------------------------------

    def parameters_loaded(self) -> None:
        """Configure the simulated sensors' ODRs from the parameters (flight ``configure()``)."""
        self._configure_sensors()

    def parameter_updated(self, local_id: int) -> None:
        if local_id == self.spec.param("MAGNETOMETER_SAMPLING_FREQUENCY").local_id:
            self.MagnetometerSamplingFrequencyParamSet(self.MAGNETOMETER_SAMPLING_FREQUENCY.value)
        elif local_id == self.spec.param("GYROSCOPE_SAMPLING_FREQUENCY").local_id:
            self.GyroscopeSamplingFrequencyParamSet(self.GYROSCOPE_SAMPLING_FREQUENCY.value)
        self._configure_sensors()

    def _configure_sensors(self) -> None:
        mag = self.MAGNETOMETER_SAMPLING_FREQUENCY.value
        gyro = self.GYROSCOPE_SAMPLING_FREQUENCY.value
        self.spacecraft.set_magnetometer_odr_hz(LIS2MDL_HZ[mag])
        self.spacecraft.set_gyro_odr_hz(LSM6DSO_HZ[gyro])
        self.MagnetometerSamplingFrequency.write(mag)
        self.GyroscopeSamplingFrequency.write(gyro)

    # --- reads ---------------------------------------------------------------------------------

    def _read(self, sensor: SimImuSensor, read, failed_event):
        """``(components, stamp, ok)`` after applying the injected fault; never raises."""
        fault = self._faults[sensor]
        if fault == SimReadFault.FAIL:
            failed_event()
            return None, None, False
        try:
            values = read()
        except Exception as exc:  # noqa: BLE001 - a simulation fault is a failed read, never an exception
            self.report_fault(f"{sensor.name} read", exc)
            failed_event()
            return None, None, False
        failed_event.clear_throttle()
        if fault == SimReadFault.NAN:
            values = (_NAN, _NAN, _NAN) + tuple(values[3:])
        elif fault == SimReadFault.INF:
            values = (_INF, _INF, _INF) + tuple(values[3:])
        return values, (values[3] if len(values) > 3 else None), True

    def accelerationGet_handler(self) -> Result:
        v, _, ok = self._read(SimImuSensor.ACCELEROMETER, self.spacecraft.acceleration,
                              self.AccelerometerReadFailed)
        if not ok:
            return Result(Acceleration(0.0, 0.0, 0.0), Success.FAILURE)
        value = Acceleration(v[0], v[1], v[2])
        self.Acceleration.write(value)
        return Result(value, Success.SUCCESS)

    def angularVelocityGet_handler(self) -> Result:
        v, _, ok = self._read(SimImuSensor.GYROSCOPE, self.spacecraft.gyro_sample, self.GyroscopeReadFailed)
        if not ok:
            return Result(AngularVelocity(0.0, 0.0, 0.0), Success.FAILURE)
        value = AngularVelocity(v[0], v[1], v[2])
        self.AngularVelocity.write(value)
        return Result(value, Success.SUCCESS)

    def magneticFieldGet_handler(self) -> Result:
        v, stamp, ok = self._read(SimImuSensor.MAGNETOMETER, self.spacecraft.magnetometer_sample,
                                  self.MagnetometerReadFailed)
        if not ok:
            return Result(MagneticField(0.0, 0.0, 0.0, self.spacecraft.now()), Success.FAILURE)
        if self.stamp_with_read_time:
            stamp = self.spacecraft.now()
        value = MagneticField(v[0], v[1], v[2], stamp)
        self.MagneticField.write(value)
        return Result(value, Success.SUCCESS)
