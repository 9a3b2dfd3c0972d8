"""A component written as users write them: mypy must accept it (see test_typing.py)."""

from __future__ import annotations

from typing import Annotated

from fprime_lite import F64, U32, Channel, Event, OutputPort, Param, PassiveComponent, PortType, Sched, Severity
from fprime_lite import String, sync_command, sync_input
from fprime_lite.model.params import ParamEcho

SetPower = PortType("Heater.SetPower", watts=F64)


class Heater(PassiveComponent):
    TooCold = Event(Severity.WARNING_LO, "too cold: {.1f} C", temperature=F64, throttle=3)
    Temperature = Channel(F64)
    Label = Channel(String(20))
    GAIN = Param(F64, default=2.0, low=0.0, high=10.0, echo=ParamEcho(unit="W/C"))
    CYCLES = Param(U32, default=1)
    powerOut = OutputPort(SetPower)

    @sync_input(Sched)
    def run(self, context: int) -> None:
        t: float = 15.0
        self.Temperature.write(t)
        self.Label.write("ok")
        if t < 18.0:
            sent: bool = self.TooCold(t)
            del sent
        gain: float = self.GAIN.value
        cycles: int = self.CYCLES.value
        self.powerOut[0](gain * (20.0 - t) * cycles)

    @sync_command()
    def RENAME(self, name: Annotated[str, String(20)]) -> None:
        self.Label.write(name)
