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
  of 1 (default 0.25; ``control.sun_vector.SUN_MAGNITUDE_TOLERANCE``). Both act from the next ``run``.

Units: lux at the ports, the Sun vector a unit vector in the body frame B.
"""

from __future__ import annotations

import math

from fprime_lite import F64, U32, Channel, Event, OutputPort, Param, PassiveComponent, Sched, Severity, sync_input
from fprime_lite.model.fw_types import Success

from detumble.components.attitude_types import SunVector, SunVectorGet, Vector3
from detumble.components.types import Result
from detumble.control.sun_vector import SUN_LIT_FRACTION, SUN_MAGNITUDE_TOLERANCE, estimate_sun_vector
from detumble.drivers.ports import LightGet
from detumble.sim.sun_sensors import FULL_SUN_LUX

__all__ = ["ADCS", "NUM_LIGHT_SENSORS"]

#: ``numLightSensors`` of the flight FPP.
NUM_LIGHT_SENSORS = 6
_SUCCESS = Success.SUCCESS
_NAN = math.nan


class ADCS(PassiveComponent):
    """The six face light sensors read at each ``run`` (1 Hz) and the Sun vector made from them."""

    visibleLightGet = OutputPort(LightGet, size=NUM_LIGHT_SENSORS)

    SUN_FULL_SCALE_LUX = Param(F64, default=FULL_SUN_LUX, low=1.0, high=1.0e6, finite=True, units="lux")
    # fraction of SUN_FULL_SCALE_LUX above which a face is lit: below ~3σ of the noise dark faces read as lit, above
    # ~0.05 a dead zone of asin(fraction) opens where Sun pointing holds the Sun (docs/studies/sun_safe.md)
    SUN_LIT_FRACTION = Param(F64, default=SUN_LIT_FRACTION, low=0.001, high=0.5, finite=True, units="1")
    # |s| may differ from 1 by this much and the Sun vector is valid (Earth–Sun distance ±3.4 %, gain spread 2 %)
    SUN_MAGNITUDE_TOLERANCE = Param(F64, default=SUN_MAGNITUDE_TOLERANCE, low=0.01, high=0.9, finite=True, units="1")

    SunVector_tlm = Channel(Vector3, name="SunVector")  # unit, B (the last valid one while not valid)
    SunVectorValid = Channel(U32)  # 1 while the light sensors see the Sun as cosine detectors do
    LitFaces = Channel(U32)  # faces above the lit threshold

    SunVectorAcquired = Event(Severity.ACTIVITY_LO, "Sun vector valid: ({.3f}, {.3f}, {.3f}) in B, {} faces lit",
                              x=F64, y=F64, z=F64, lit=U32)
    SunVectorLost = Event(Severity.ACTIVITY_LO, "Sun vector lost: {} faces lit, magnitude {.3f} of full Sun "
                          "(eclipse, or no usable reading)", lit=U32, magnitude=F64)
    LightSensorReadFailed = Event(Severity.WARNING_LO, "Light sensor {} did not answer: its face counts as dark",
                                  sensor=U32, throttle=5)

    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self._light = self.output_port("visibleLightGet")
        self._last: SunVector | None = None
        self._valid = False
        self._direction = (0.0, 0.0, 0.0)

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

    @sync_input(SunVectorGet)
    def sunVectorGet(self) -> Result:
        """The latest Sun vector (``Components.SunVector``); before the first ``run`` one that is not valid."""
        if self._last is None:
            return Result(SunVector(0.0, 0.0, 0.0, False, 0, self.get_time()), _SUCCESS)
        return Result(self._last, _SUCCESS)
