"""Wrong uses mypy must report (see test_typing.py); each line marked ``# wrong`` is one error."""

from __future__ import annotations

from fprime_lite import F64, Channel, Param, PassiveComponent, Sched, String, sync_input


class Wrong(PassiveComponent):
    Temperature = Channel(F64)
    Label = Channel(String(20))
    GAIN = Param(F64, default=2.0)

    @sync_input(Sched)
    def run(self, context: int) -> None:
        self.Temperature.write("hot")  # wrong
        self.Label.write(3)  # wrong
        name: str = self.GAIN.value  # wrong
        self.Temperature.value  # wrong
        del name
