"""An example fprime_lite component: a bang-bang heater controller with hysteresis.

It shows every kind of member a component declares: a rate-group input, an output port that
returns a value, an output that returns nothing, a command, parameters, events (one throttled) and
channels. ``tests/examples/test_heater_controller.py`` drives it end to end with the harness.
"""

from __future__ import annotations

from fprime_lite import (BOOL, F64, Channel, CmdResponse, Event, FwEnum, OutputPort, Param,
                         PassiveComponent, PortType, Sched, Severity, Struct, sync_command, sync_input)
from fprime_lite.model.types import U8


class HeaterState(FwEnum, namespace="Examples", rep=U8):
    OFF = 0
    ON = 1


class TemperatureReading(Struct, namespace="Examples"):
    """A thermistor reading: ``celsius`` is meaningful only when ``valid`` is True."""

    celsius: F64
    valid: BOOL


TemperatureGet = PortType("Examples.TemperatureGet", returns=TemperatureReading)
HeaterSet = PortType("Examples.HeaterSet", on=BOOL)


class HeaterController(PassiveComponent):
    """Keeps a temperature between ``SETPOINT - HYSTERESIS`` and ``SETPOINT`` (°C)."""

    temperatureGet = OutputPort(TemperatureGet)
    heaterSet = OutputPort(HeaterSet)

    SETPOINT = Param(F64, default=20.0)
    HYSTERESIS = Param(F64, default=2.0)

    HeaterOn = Event(Severity.ACTIVITY_LO, "Heater on at {.1f} C", temperature=F64)
    HeaterOff = Event(Severity.ACTIVITY_LO, "Heater off at {.1f} C", temperature=F64)
    SensorFailed = Event(Severity.WARNING_LO, "Thermistor read failed", throttle=3)
    EnableRefused = Event(Severity.WARNING_LO, "Cannot enable: hysteresis {.1f} C is not positive",
                          hysteresis=F64)

    Temperature = Channel(F64, format="{.2f}")
    State = Channel(HeaterState, update="on change")

    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self.enabled = False
        self.state = HeaterState.OFF

    @sync_input(Sched)
    def run(self, context: int) -> None:
        if not self.enabled:
            return
        reading = self.temperatureGet[0]()
        if not reading.valid:
            self.SensorFailed()
            self._switch(HeaterState.OFF, reading.celsius)
            return
        self.SensorFailed.clear_throttle()
        self.Temperature.write(reading.celsius)
        low = self.SETPOINT.value - self.HYSTERESIS.value
        if reading.celsius < low:
            self._switch(HeaterState.ON, reading.celsius)
        elif reading.celsius >= self.SETPOINT.value:
            self._switch(HeaterState.OFF, reading.celsius)
        self.State.write(self.state)  # "on change": only transitions reach the ground

    def _switch(self, state: HeaterState, celsius: float) -> None:
        if state != self.state:
            self.state = state
            self.heaterSet[0](state == HeaterState.ON)
            (self.HeaterOn if state == HeaterState.ON else self.HeaterOff)(celsius)

    @sync_command()
    def SET_ENABLED(self, enabled: BOOL):
        if enabled and self.HYSTERESIS.value <= 0.0:
            self.EnableRefused(self.HYSTERESIS.value)
            return CmdResponse.VALIDATION_ERROR
        self.enabled = enabled
        if not enabled:
            self._switch(HeaterState.OFF, float("nan"))
        return CmdResponse.OK
