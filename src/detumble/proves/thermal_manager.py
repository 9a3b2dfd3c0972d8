"""ThermalManager as flown: reads the face, battery-cell and RP2350 temperatures once a second.

Every ``run`` (1 Hz) reads ``faceTempGet[0..4]`` and ``battCellTempGet[0..3]`` (TMP112 managers) and
``picoTempGet`` (the die sensor). A face reading outside [FACE_TEMP_LOWER_THRESHOLD,
FACE_TEMP_UPPER_THRESHOLD] logs TemperatureBelowThreshold / TemperatureAboveThreshold(FACE, index,
°C), a battery cell outside [BATT_CELL_TEMP_LOWER_THRESHOLD, BATT_CELL_TEMP_UPPER_THRESHOLD] the same
with BATTERY. A sensor that cannot be read (its face unpowered) is skipped. Unconnected ports are
skipped. The events are throttled (5 each, re-armed when every reading is back inside its limits):
the flight events are not, but at 1 Hz an unthrottled warning would flood the downlink.

Ground interface (flight ``Components.ThermalManager``, base id 0x10041000): parameters
FACE_TEMP_LOWER_THRESHOLD (-40 °C), FACE_TEMP_UPPER_THRESHOLD (60 °C), BATT_CELL_TEMP_LOWER_THRESHOLD
(5 °C), BATT_CELL_TEMP_UPPER_THRESHOLD (60 °C); events TemperatureBelowThreshold,
TemperatureAboveThreshold.
"""

from __future__ import annotations

from fprime_lite import F64, U32, Event, FwEnum, OutputPort, Param, PassiveComponent, Sched, Severity, sync_input
from fprime_lite.model.fw_types import Success

from detumble.drivers.ports import PicoTemperatureGet, TemperatureGet

__all__ = ["ThermalManager", "TempSensorType", "FACE_SENSORS", "BATT_CELL_SENSORS"]

FACE_SENSORS = 5
BATT_CELL_SENSORS = 4


class TempSensorType(FwEnum, namespace="Components.ThermalManager"):
    FACE = 0
    BATTERY = 1


class ThermalManager(PassiveComponent):
    """Watches the spacecraft's temperatures (instance ``thermalManager``)."""

    FACE_TEMP_LOWER_THRESHOLD = Param(F64, default=-40.0, units="C")
    FACE_TEMP_UPPER_THRESHOLD = Param(F64, default=60.0, units="C")
    BATT_CELL_TEMP_LOWER_THRESHOLD = Param(F64, default=5.0, units="C")
    BATT_CELL_TEMP_UPPER_THRESHOLD = Param(F64, default=60.0, units="C")

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """1 Hz: read every sensor, warn about the ones outside their limits."""
        inside = True
        inside &= self._check(self.faceTempGet, FACE_SENSORS, TempSensorType.FACE,
                              self.FACE_TEMP_LOWER_THRESHOLD.value, self.FACE_TEMP_UPPER_THRESHOLD.value)
        inside &= self._check(self.battCellTempGet, BATT_CELL_SENSORS, TempSensorType.BATTERY,
                              self.BATT_CELL_TEMP_LOWER_THRESHOLD.value, self.BATT_CELL_TEMP_UPPER_THRESHOLD.value)
        if self.is_connected("picoTempGet", 0):
            self.picoTempGet[0]()
        if inside:
            self.TemperatureBelowThreshold.clear_throttle()
            self.TemperatureAboveThreshold.clear_throttle()

    faceTempGet = OutputPort(TemperatureGet, size=FACE_SENSORS)
    battCellTempGet = OutputPort(TemperatureGet, size=BATT_CELL_SENSORS)
    picoTempGet = OutputPort(PicoTemperatureGet)

    TemperatureBelowThreshold = Event(Severity.WARNING_LO, "{} temperature below threshold: Sensor {} at {} °C",
                                      sensorType=TempSensorType, sensorId=U32, temperature=F64, throttle=5)
    TemperatureAboveThreshold = Event(Severity.WARNING_LO, "{} temperature above threshold: Sensor {} at {} °C",
                                      sensorType=TempSensorType, sensorId=U32, temperature=F64, throttle=5)

    def _check(self, port, n: int, kind: TempSensorType, low: float, high: float) -> bool:
        name = "faceTempGet" if kind == TempSensorType.FACE else "battCellTempGet"
        inside = True
        for i in range(n):
            if not self.is_connected(name, i):
                continue
            value, condition = port[i]()
            if condition != Success.SUCCESS:
                continue
            if value < low:
                inside = False
                self.TemperatureBelowThreshold(kind, i, value)
            elif value > high:
                inside = False
                self.TemperatureAboveThreshold(kind, i, value)
        return inside
