"""ADCS as flown on PROVES, plus the Sun vector: the face light sensors read at 1 Hz and turned into a Sun direction.

Flight ``Components.ADCS`` (proves-core-reference, ``Components/ADCS``: passive; ``run: Svc.Sched``; output
``visibleLightGet: [numLightSensors = 6] Drv.lightGet``; instance ``adcs``, base id 0x1004C000, on the 1 Hz rate
group) calls each light sensor's ``visibleLightGet`` on every ``run`` and keeps nothing. This component does that
and adds what issue 27 asks of it (none of it in the flight's dictionary; every name below is ours):

* the least-squares Sun vector over the lit faces with a validity flag (``detumble.control.sun_vector``), port
  index ``i`` being face ``i`` (X+, X−, Y+, Y−, Z+, Z−: the project's ``veml6031Face{i}Manager``; the flight wires
  index 4 to its Face5 manager and 5 to Face6);
* ``sunVectorGet`` (sync input, ``Components.SunVectorGet``): the latest estimate for the attitude controller's
  SUN_SAFE mode (before the first ``run``: not valid, no face lit — nothing has been seen yet, which is no failure);
* telemetry SunVector (unit, B), SunVectorValid (1/0), LitFaces; events SunVectorAcquired and SunVectorLost when
  the validity changes (entering and leaving eclipse), LightSensorReadFailed(sensor) when a sensor does not
  answer (throttled; its face then counts as dark);
* parameters SUN_FULL_SCALE_LUX: the full-Sun reading at normal incidence (133 klx at 1 AU: the sensors' ground
  calibration); SUN_LIT_FRACTION: a face is lit above this fraction of it (default 0.02, 4σ of the stated noise;
  ``control.sun_vector.SUN_LIT_FRACTION``); SUN_MAGNITUDE_TOLERANCE: the estimate is valid while |s| is within this
  of 1 (default 0.25; ``control.sun_vector.SUN_MAGNITUDE_TOLERANCE``). Both act from the next ``run``;
* the Earth's albedo taken out of the Sun vector (issue 27's 5° target with the Earth's light on the faces;
  ``control.albedo``, the same module the plant-only check flies): optional output ports ``ephemerisGet`` (the
  Sun, the position and the Earth angle: ``OrbitEphemeris``), ``magneticFieldGet`` (the LIS2MDL through the IMU
  manager) and ``angularVelocityGet`` (the gyro, which carries the TRIAD attitude while the field is near the Sun
  line); the on-board field is the IGRF-2025 tilted dipole (``control.geomagnetic``). Parameters
  SUN_ALBEDO_CORRECTION (``Fw.Enabled``, default DISABLED: the simulated Earth of the deployments is dark unless
  the scenario's ``sensors.sun_sensors.albedo`` is set; a flight enables it), SUN_ALBEDO_MODEL (the Bond albedo
  of the model, default 0.30, the Earth's mean) and SUN_FIELD_MAX_AGE (s: an older magnetometer sample is stale).
  Telemetry SunVectorRaw (the uncorrected vector, every reading) and AlbedoCorrected (1 when the published
  SunVector had the albedo taken out); whenever it cannot be (no ephemeris, no or a stale magnetometer reading,
  the sub-satellite point dark, the field along the Sun with nothing to carry) the raw vector is published and
  AlbedoCorrectionUnavailable(reason) says why (throttled; re-armed by the next corrected reading).

Units: lux at the ports, the Sun vector a unit vector in the body frame B; field gauss at the port (only its
direction is used), rates rad/s, positions m (N).
"""

from __future__ import annotations

import math

from fprime_lite import F64, U32, Channel, Event, OutputPort, Param, PassiveComponent, Sched, Severity, sync_input
from fprime_lite.model.fw_types import Success
from fprime_lite.svc.health import FwEnabled

from detumble.components.attitude_types import (AlbedoUnavailableReason, AngularVelocityGet, EphemerisGet, SunVector,
                                                SunVectorGet, Vector3)
from detumble.components.types import MagneticFieldGet, Result
from detumble.control.albedo import EARTH_MEAN_ALBEDO, AlbedoCorrector
from detumble.control.geomagnetic import dipole_field_N
from detumble.control.sun_vector import SUN_LIT_FRACTION, SUN_MAGNITUDE_TOLERANCE, estimate_sun_vector
from detumble.drivers.ports import LightGet
from detumble.sim.sun_sensors import FULL_SUN_LUX

__all__ = ["ADCS", "NUM_LIGHT_SENSORS"]

#: ``numLightSensors`` of the flight FPP.
NUM_LIGHT_SENSORS = 6
_SUCCESS = Success.SUCCESS
_NAN = math.nan
_ENABLED = FwEnabled.ENABLED
#: m: the Earth's radius in the albedo share (R_E/r)² (WGS-84 equatorial; the sensor model's shadow radius).
EARTH_RADIUS_M = 6378137.0
_isfinite = math.isfinite


def _read(out, index: int = 0):
    """What the ``ref condition`` output ``out[index]`` returns, or None when it fails or is not connected."""
    if out.targets[index] is None:
        return None
    value, condition = out.calls[index]()
    return value if condition == _SUCCESS else None


def _finite(*values) -> bool:
    try:
        return all(_isfinite(v) for v in values)
    except TypeError:
        return False


class ADCS(PassiveComponent):
    """The six face light sensors read at each ``run`` (1 Hz) and the Sun vector made from them."""

    visibleLightGet = OutputPort(LightGet, size=NUM_LIGHT_SENSORS)

    SUN_FULL_SCALE_LUX = Param(F64, default=FULL_SUN_LUX, low=1.0, high=1.0e6, finite=True, units="lux")
    # fraction of SUN_FULL_SCALE_LUX above which a face is lit: below ~3σ of the noise dark faces read as lit, above
    # ~0.05 a dead zone of asin(fraction) opens where Sun pointing holds the Sun (docs/studies/sun_safe.md)
    SUN_LIT_FRACTION = Param(F64, default=SUN_LIT_FRACTION, low=0.001, high=0.5, finite=True, units="1")
    # |s| may differ from 1 by this much and the Sun vector is valid (Earth–Sun distance ±3.4 %, gain spread 2 %)
    SUN_MAGNITUDE_TOLERANCE = Param(F64, default=SUN_MAGNITUDE_TOLERANCE, low=0.01, high=0.9, finite=True, units="1")
    # take the Earth's albedo out of the Sun vector (control.albedo); needs ephemerisGet and magneticFieldGet
    SUN_ALBEDO_CORRECTION = Param(FwEnabled, default=FwEnabled.DISABLED)
    # the Bond albedo of the on-board model (the Earth's mean 0.30; the real Earth 0.06 over ocean to 0.8 over ice)
    SUN_ALBEDO_MODEL = Param(F64, default=EARTH_MEAN_ALBEDO, low=0.0, high=0.95, finite=True, units="1")
    # s: a magnetometer sample older than this is stale (the LIS2MDL samples at 10-100 Hz)
    SUN_FIELD_MAX_AGE = Param(F64, default=2.0, low=0.01, high=60.0, finite=True, units="s")

    ephemerisGet = OutputPort(EphemerisGet)  #: optional: the albedo correction's Sun, position and Earth angle
    magneticFieldGet = OutputPort(MagneticFieldGet)  #: optional: the albedo correction's field in B
    angularVelocityGet = OutputPort(AngularVelocityGet)  #: optional: carries the correction's attitude (rad/s)

    SunVector_tlm = Channel(Vector3, name="SunVector")  # unit, B (the last valid one while not valid)
    SunVectorValid = Channel(U32)  # 1 while the light sensors see the Sun as cosine detectors do
    LitFaces = Channel(U32)  # faces above the lit threshold
    SunVectorRaw = Channel(Vector3)  # unit, B: the light sensors' vector before the albedo correction
    AlbedoCorrected = Channel(U32)  # 1 when SunVector had the Earth's albedo taken out

    SunVectorAcquired = Event(Severity.ACTIVITY_LO, "Sun vector valid: ({.3f}, {.3f}, {.3f}) in B, {} faces lit",
                              x=F64, y=F64, z=F64, lit=U32)
    SunVectorLost = Event(Severity.ACTIVITY_LO, "Sun vector lost: {} faces lit, magnitude {.3f} of full Sun "
                          "(eclipse, or no usable reading)", lit=U32, magnitude=F64)
    LightSensorReadFailed = Event(Severity.WARNING_LO, "Light sensor {} did not answer: its face counts as dark",
                                  sensor=U32, throttle=5)
    AlbedoCorrectionUnavailable = Event(Severity.WARNING_LO, "Albedo correction unavailable ({}): the Sun vector is "
                                        "the uncorrected one", reason=AlbedoUnavailableReason, throttle=5)

    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self._light = self.output_port("visibleLightGet")
        self._last: SunVector | None = None
        self._valid = False
        self._direction = (0.0, 0.0, 0.0)
        self._ephemeris = self.output_port("ephemerisGet")
        self._field = self.output_port("magneticFieldGet")
        self._gyro = self.output_port("angularVelocityGet")
        self._corrector: AlbedoCorrector | None = None

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """Read every connected light sensor, estimate the Sun vector, tell the ground. A fault is reported
        (HandlerFault, HandlerFaults) and the rate group goes on."""
        try:
            self._sense()
        except Exception as exc:  # noqa: BLE001 - the rate group must keep running
            self.report_fault("run", exc)

    def _sense(self) -> None:
        readings = []
        for i in range(NUM_LIGHT_SENSORS):
            value = _NAN
            if self._light.targets[i] is not None:
                lux, condition = self._light.calls[i]()
                if condition == _SUCCESS and isinstance(lux, (int, float)):
                    value = float(lux)
                else:
                    self.LightSensorReadFailed(i)
            readings.append(value)
        est = estimate_sun_vector(readings, self.SUN_FULL_SCALE_LUX.value, lit_fraction=self.SUN_LIT_FRACTION.value,
                                  magnitude_tolerance=self.SUN_MAGNITUDE_TOLERANCE.value)
        self.SunVectorRaw.write(Vector3(list(est.direction)))
        corrected = False
        if self.SUN_ALBEDO_CORRECTION.value == _ENABLED and est.lit:
            try:
                better = self._without_albedo(readings)
            except Exception as exc:  # noqa: BLE001 - a fault in the correction leaves the uncorrected vector
                self.report_fault("albedo correction", exc)
                better = None
            if better is not None:
                est, corrected = better, True
        self.AlbedoCorrected.write(1 if corrected else 0)
        if est.valid:
            self._direction = est.direction
            if not self._valid:
                self.SunVectorAcquired(*est.direction, est.lit)
        elif self._valid:
            self.SunVectorLost(est.lit, est.magnitude)
        self._valid = est.valid
        d = self._direction
        self._last = SunVector(d[0], d[1], d[2], est.valid, est.lit, self.get_time())
        self.SunVector_tlm.write(Vector3(list(d)))
        self.SunVectorValid.write(1 if est.valid else 0)
        self.LitFaces.write(est.lit)

    def _without_albedo(self, readings):
        """The Sun vector with the albedo taken out, or None (AlbedoCorrectionUnavailable says why) when it cannot
        be: the caller then keeps the uncorrected one."""
        now_us = self.get_time().total_us
        e = _read(self._ephemeris)
        b = None
        if e is None or not _finite(e.rx, e.ry, e.rz, e.earthAngle, e.sunX, e.sunY, e.sunZ) or (
                e.rx * e.rx + e.ry * e.ry + e.rz * e.rz) <= 0.0:
            reason = AlbedoUnavailableReason.NO_EPHEMERIS
        else:
            b = _read(self._field)
            if b is None or not _finite(b.x, b.y, b.z) or b.x * b.x + b.y * b.y + b.z * b.z <= 0.0:
                reason = AlbedoUnavailableReason.NO_MAGNETOMETER
            elif not 0 <= now_us - b.timestamp.total_us <= self.SUN_FIELD_MAX_AGE.value * 1e6:
                reason = AlbedoUnavailableReason.MAGNETOMETER_STALE
            else:
                reason = None
        if reason is not None or b is None:
            self.AlbedoCorrectionUnavailable(reason)
            return None
        albedo = self.SUN_ALBEDO_MODEL.value
        if self._corrector is None or self._corrector.albedo != albedo:
            self._corrector = AlbedoCorrector(albedo, EARTH_RADIUS_M)
        corrector = self._corrector
        w = _read(self._gyro)
        if w is None or not _finite(w.x, w.y, w.z):
            corrector.reset()  # nothing carries the last attitude to now
            w = (0.0, 0.0, 0.0)
        else:
            w = (float(w.x), float(w.y), float(w.z))
        r_N = (float(e.rx), float(e.ry), float(e.rz))
        sun_N = (float(e.sunX), float(e.sunY), float(e.sunZ))
        est = corrector.estimate(readings, self.SUN_FULL_SCALE_LUX.value, now_us / 1e6, r_N=r_N, sun_N=sun_N,
                                 field_B=(float(b.x), float(b.y), float(b.z)),
                                 field_N=dipole_field_N(r_N, float(e.earthAngle)), omega_B=w,
                                 lit_fraction=self.SUN_LIT_FRACTION.value,
                                 magnitude_tolerance=self.SUN_MAGNITUDE_TOLERANCE.value)
        if not corrector.applied:
            dark = corrector.albedo <= 0.0 or (r_N[0] * sun_N[0] + r_N[1] * sun_N[1] + r_N[2] * sun_N[2]) <= 0.0
            self.AlbedoCorrectionUnavailable(AlbedoUnavailableReason.EARTH_DARK if dark
                                             else AlbedoUnavailableReason.FIELD_ALONG_SUN)
            return None
        if self.AlbedoCorrectionUnavailable.count:
            self.AlbedoCorrectionUnavailable.clear_throttle()
        return est

    @sync_input(SunVectorGet)
    def sunVectorGet(self) -> Result:
        """The latest Sun vector (``Components.SunVector``); before the first ``run`` one that is not valid."""
        if self._last is None:
            return Result(SunVector(0.0, 0.0, 0.0, False, 0, self.get_time()), _SUCCESS)
        return Result(self._last, _SUCCESS)
