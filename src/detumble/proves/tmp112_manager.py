"""Tmp112Manager as flown: a TMP112 temperature sensor on a face board or a battery cell.

The reading is the simulated thermal model's (:mod:`detumble.sim.thermal`): a face sensor
(``face0`` … ``face5``) reads that face panel, a battery-cell sensor (``battCell1`` … ``battCell4``)
the interior node, quantised to the TMP112's 0.0625 °C. A face sensor is powered through its face's
load switch: while the switch is open the device is not ready — GetTemperature logs DeviceNotReady
(throttled) and answers EXECUTION_ERROR, ``temperatureGet`` returns FAILURE. Battery-cell sensors
are always powered. ``loadSwitchStateChanged`` (index 0 of the face's switch, as flown) answers
SUCCESS: the device is (de)initialised with its power, which the simulation reads from the switch.

Ground interface (flight ``Drv.Tmp112Manager``; base ids 0x10042000 face0 … 0x10047000 face5,
0x10048000 … 0x1004B000 battCell1 … 4): command GetTemperature (0); channel Temperature (°C);
events DeviceNotReady, DeviceInitFailed, DeviceNil, DeviceStateNil, TcaUnhealthy, MuxUnhealthy,
SensorSampleFetchFailed, SensorChannelGetFailed, Temperature(°C) in the flight order (only
DeviceNotReady and Temperature can happen here: the I²C mux and Zephyr driver are not simulated).
"""

from __future__ import annotations

from fprime_lite import F64, Channel, CmdResponse, Event, PassiveComponent, Severity, sync_command, sync_input
from fprime_lite.model.fw_types import On, Success

from detumble.components.types import Result
from detumble.drivers.ports import LoadSwitchStateChanged, TemperatureGet
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft
from detumble.proves.zephyr_sensor_events import ZephyrSensorEvents
from detumble.sim.power import FACE_SWITCHES

__all__ = ["Tmp112Manager", "SENSORS", "RESOLUTION_C"]

RESOLUTION_C = 0.0625
#: Where each sensor sits: face sensors read their face, battery-cell sensors the interior.
SENSORS = {**{f: f for f in FACE_SWITCHES}, **{f"battCell{i}": "interior" for i in range(1, 5)}}


class Tmp112Manager(ZephyrSensorEvents, PassiveComponent):
    """The TMP112 ``sensor`` (``face0`` … ``face5``, ``battCell1`` … ``battCell4``) of ``spacecraft``."""

    @sync_input(TemperatureGet)
    def temperatureGet(self) -> Result:
        """The temperature, °C, or FAILURE when the device is not powered."""
        if not self.powered():
            self.DeviceNotReady()
            return Result(0.0, Success.FAILURE)
        self.DeviceNotReady.clear_throttle()
        t = round(self.spacecraft.temperature_c(self.where) / RESOLUTION_C) * RESOLUTION_C
        self.Temperature_tlm.write(t)
        return Result(t, Success.SUCCESS)

    @sync_input(LoadSwitchStateChanged)
    def loadSwitchStateChanged(self, state: On) -> Success:
        return Success.SUCCESS

    @sync_command()
    def GetTemperature(self):
        """Read the sensor and log Temperature."""
        value, condition = self.temperatureGet()
        if condition != Success.SUCCESS:
            return CmdResponse.EXECUTION_ERROR
        self.Temperature(value)

    #: The channel ``Temperature`` (the attribute differs: the event has the same F´ name).
    Temperature_tlm = Channel(F64, name="Temperature", units="C")

    Temperature = Event(Severity.ACTIVITY_HI, "Temperature: {}°C", temperature=F64)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, sensor: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        if sensor not in SENSORS:
            raise ValueError(f"{name}: unknown TMP112 sensor {sensor!r}; sensors are {list(SENSORS)}")
        self.spacecraft = spacecraft
        self.sensor = sensor
        self.where = SENSORS[sensor]

    def powered(self) -> bool:
        """A face sensor needs its face's load switch closed; a battery-cell sensor is always powered."""
        return self.where == "interior" or self.spacecraft.load_switch(self.sensor)
