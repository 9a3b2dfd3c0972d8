"""PicoTempManager as flown: the RP2350's built-in die temperature sensor.

The die sits on the flight computer inside the spacecraft: it reads the simulated thermal model's
interior node (:mod:`detumble.sim.thermal`) plus ``self_heating_c`` (default 5 °C, an assumption:
the RP2350 dissipates a few hundred mW in a small package), to the ADC's 0.1 °C. The flight
computer is always powered, so the sensor is always ready.

Ground interface (flight ``Drv.PicoTempManager``, base id 0x10079000): command GetPicoTemperature (0);
channel PicoTemperature (°C); events DeviceNotReady, SensorSampleFetchFailed,
SensorChannelGetFailed, PicoTemperature(°C) (ACTIVITY_HI). Port ``picoTemperatureGet`` returns
``Result(°C, SUCCESS)`` (flight ``ref condition``).
"""

from __future__ import annotations

from fprime_lite import F64, I32, Channel, Event, PassiveComponent, Severity, sync_command, sync_input
from fprime_lite.model.fw_types import Success

from detumble.components.types import Result
from detumble.drivers.ports import PicoTemperatureGet
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["PicoTempManager"]


class PicoTempManager(PassiveComponent):
    """The RP2350 die temperature of ``spacecraft`` (instance ``picoTempManager``)."""

    @sync_input(PicoTemperatureGet)
    def picoTemperatureGet(self) -> Result:
        """The die temperature, °C."""
        t = round((self.spacecraft.temperature_c("interior") + self.self_heating_c) * 10.0) / 10.0
        self.PicoTemperature_tlm.write(t)
        return Result(t, Success.SUCCESS)

    @sync_command()
    def GetPicoTemperature(self):
        """Read the die temperature and log PicoTemperature."""
        self.PicoTemperature(self.picoTemperatureGet().value)

    #: The channel ``PicoTemperature`` (the attribute differs: the event has the same F´ name).
    PicoTemperature_tlm = Channel(F64, name="PicoTemperature", units="C")

    DeviceNotReady = Event(Severity.WARNING_LO, "Device not ready", throttle=5)
    SensorSampleFetchFailed = Event(Severity.WARNING_LO, "Sensor fetch failed with return code: {}", ret=I32,
                                    throttle=5)
    SensorChannelGetFailed = Event(Severity.WARNING_LO, "Sensor channel get failed with return code: {}", ret=I32,
                                   throttle=5)
    PicoTemperature = Event(Severity.ACTIVITY_HI, "Pico Temperature: {}°C", temperature=F64)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0, self_heating_c: float = 5.0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft
        self.self_heating_c = float(self_heating_c)
