"""PowerMonitor as flown: energy accounting from the two INA219 monitors.

Every ``run`` (1 Hz) reads voltage, current and power of the system rail and of the solar array
through its six output ports, then integrates ``P · dt`` into TotalPowerConsumption and the solar
power into TotalPowerGenerated (mWh, F32). As in the flight code the "consumption" integrates the
*sum* of the system and solar powers, readings outside 0…1000 W are skipped, and an interval is
credited only when 0 < dt < 10 s (the first run only starts the clock). Deviation: the flight
code measures the generation interval after the consumption update has already moved the time
stamp, so its TotalPowerGenerated never grows; here both use the same interval.

Ground interface (flight): commands RESET_TOTAL_POWER, RESET_TOTAL_GENERATION, GET_TOTAL_POWER;
channels TotalPowerConsumption, TotalPowerGenerated (mWh); events TotalPowerReset,
TotalGenerationReset, TotalPowerConsumptionReading ("Total power consumption: {} mWh").
"""

from __future__ import annotations

from fprime_lite import F32, Channel, Event, OutputPort, PassiveComponent, Sched, Severity, sync_command, sync_input

from detumble.drivers.ports import CurrentGet, PowerGet, VoltageGet

__all__ = ["PowerMonitor"]


class PowerMonitor(PassiveComponent):
    """Integrates the INA219 powers (the reference deployment's ``powerMonitor``)."""

    @sync_input(Sched)
    def run(self, context: int) -> None:
        self._call("sysVoltageGet")
        self._call("sysCurrentGet")
        sys_w = self._call("sysPowerGet")
        self._call("solVoltageGet")
        self._call("solCurrentGet")
        sol_w = self._call("solPowerGet")
        self._integrate(sys_w + sol_w, sol_w)

    sysVoltageGet = OutputPort(VoltageGet)
    sysCurrentGet = OutputPort(CurrentGet)
    sysPowerGet = OutputPort(PowerGet)
    solVoltageGet = OutputPort(VoltageGet)
    solCurrentGet = OutputPort(CurrentGet)
    solPowerGet = OutputPort(PowerGet)

    @sync_command()
    def RESET_TOTAL_POWER(self):
        self.total_power_mwh = 0.0
        self._last_s = self._now_s()
        self.TotalPowerReset()

    @sync_command()
    def RESET_TOTAL_GENERATION(self):
        self.total_generation_mwh = 0.0
        self.TotalGenerationReset()

    @sync_command()
    def GET_TOTAL_POWER(self):
        self.TotalPowerConsumptionReading(self.total_power_mwh)

    TotalPowerConsumption = Channel(F32)
    TotalPowerGenerated = Channel(F32)

    TotalPowerReset = Event(Severity.ACTIVITY_LO, "Total power consumption reset to 0 mWh")
    TotalGenerationReset = Event(Severity.ACTIVITY_LO, "Total power generation reset to 0 mWh")
    TotalPowerConsumptionReading = Event(Severity.ACTIVITY_LO, "Total power consumption: {} mWh", power=F32)

    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self.total_power_mwh = 0.0
        self.total_generation_mwh = 0.0
        self._last_s = 0.0

    def _call(self, port: str) -> float:
        return float(getattr(self, port)[0]()) if self.is_connected(port, 0) else 0.0

    def _now_s(self) -> float:
        return self.get_time().total_us / 1e6

    def _integrate(self, consumption_w: float, generation_w: float) -> None:
        now = self._now_s()
        if self._last_s == 0.0:              # the first run only starts the clock
            self._last_s = now
            self.TotalPowerConsumption.write(self.total_power_mwh)
            self.TotalPowerGenerated.write(self.total_generation_mwh)
            return
        dt = now - self._last_s
        self._last_s = now
        if 0.0 < dt < 10.0:
            if 0.0 <= consumption_w <= 1000.0:
                self.total_power_mwh += consumption_w * dt / 3600.0 * 1000.0
            if 0.0 <= generation_w <= 1000.0:
                self.total_generation_mwh += generation_w * dt / 3600.0 * 1000.0
        self.TotalPowerConsumption.write(self.total_power_mwh)
        self.TotalPowerGenerated.write(self.total_generation_mwh)
