"""Ina219Manager as flown: a current/voltage/power monitor reading the simulated electrical system.

The PROVES reference has two: ``ina219SysManager`` on the system rail (bus voltage, the current and
power the spacecraft draws) and ``ina219SolManager`` on the solar-array output. Readings come from
:class:`detumble.sim.power.ElectricalSystem` (``rail="system"`` or ``"solar"``), quantised to the
INA219's resolution (4 mV bus voltage; 0.1 mA current, the reference's calibration).

Ground interface (flight): commands GetVoltage, GetCurrent, GetPower (each reads, logs
VoltageReading / CurrentReading / PowerReading and answers OK); channels Voltage (V), Current (A),
Power (W), written on every read; event DeviceNotReady (WARNING_HI, throttled 5). Ports
``voltageGet`` / ``currentGet`` / ``powerGet`` (``-> F64``); a device that is not ready returns 0.
``SIM_SET_NOT_READY`` (simulation only) makes the device not ready.
"""

from __future__ import annotations

from fprime_lite import BOOL, F64, Channel, Event, PassiveComponent, Severity, sync_command, sync_input

from detumble.drivers.ports import CurrentGet, PowerGet, VoltageGet
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["Ina219Manager", "VOLTAGE_LSB_V", "CURRENT_LSB_A"]

VOLTAGE_LSB_V = 0.004
CURRENT_LSB_A = 0.0001
RAILS = ("system", "solar")


class Ina219Manager(PassiveComponent):
    """The INA219 on ``rail`` (``system`` or ``solar``) of ``spacecraft``."""

    @sync_input(VoltageGet)
    def voltageGet(self) -> float:
        """Bus voltage, V."""
        return self._read(0, self.Voltage)

    @sync_input(CurrentGet)
    def currentGet(self) -> float:
        """Current, A."""
        return self._read(1, self.Current)

    @sync_input(PowerGet)
    def powerGet(self) -> float:
        """Power, W."""
        return self._read(2, self.Power)

    Voltage = Channel(F64)
    Current = Channel(F64)
    Power = Channel(F64)

    DeviceNotReady = Event(Severity.WARNING_HI, "INA219 device not ready", throttle=5)
    VoltageReading = Event(Severity.ACTIVITY_LO, "Voltage: {} V", voltage=F64)
    CurrentReading = Event(Severity.ACTIVITY_LO, "Current: {} A", current=F64)
    PowerReading = Event(Severity.ACTIVITY_LO, "Power: {} W", power=F64)

    @sync_command()
    def GetVoltage(self):
        self.VoltageReading(self.voltageGet())

    @sync_command()
    def GetCurrent(self):
        self.CurrentReading(self.currentGet())

    @sync_command()
    def GetPower(self):
        self.PowerReading(self.powerGet())

    @sync_command()
    def SIM_SET_NOT_READY(self, not_ready: BOOL):
        """SIMULATION ONLY: make the device (not) ready."""
        self.not_ready = bool(not_ready)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, rail: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        if rail not in RAILS:
            raise ValueError(f"{name}: rail must be one of {RAILS}, got {rail!r}")
        if spacecraft.power is None:
            raise ValueError(f"{name}: the scenario has no electrical system (power.enabled: false)")
        self.spacecraft = spacecraft
        self.rail = rail
        self.not_ready = False

    def reading(self) -> tuple[float, float, float]:
        """``(V, A, W)`` as the device reports them (quantised)."""
        self.spacecraft.sync()
        eps = self.spacecraft.power
        assert eps is not None  # checked in __init__
        v, i, _ = eps.system_reading() if self.rail == "system" else eps.solar_reading()
        v = round(v / VOLTAGE_LSB_V) * VOLTAGE_LSB_V
        i = round(i / CURRENT_LSB_A) * CURRENT_LSB_A
        return v, i, v * i

    def _read(self, k: int, channel) -> float:
        if self.not_ready:
            self.DeviceNotReady()
            return 0.0
        self.DeviceNotReady.clear_throttle()
        value = self.reading()[k]
        channel.write(value)
        return value
