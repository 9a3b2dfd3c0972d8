"""Burnwire as flown: heats the antenna's burnwire, with a safety timer, on the simulated battery.

START_BURNWIRE (or ``burnStart``, from the antenna deployer) logs SetBurnwireState(ON) and
SafetyTimerState(SAFETY_TIMER) and arms the burn; the first ``schedIn`` tick after it drives both
burnwire GPIOs high (SafetyTimerStatus(ON)) and every tick counts a second. When the count reaches
``SAFETY_TIMER`` the component stops the burn itself (SafetyTimerStatus(OFF)). STOP_BURNWIRE (or
``burnStop``) drives the GPIOs low, logs SetBurnwireState(OFF) and BurnwireEndCount(seconds burnt).
Stopping a burnwire that is off still logs both events, as in flight.

The GPIOs are the simulated electrical system's burnwire heater
(:meth:`SimulatedSpacecraft.set_burnwire`): while they are high the battery feeds
``power.loads.burnwire_w`` more, which the system INA219 reads.

Ground interface (flight ``Components.Burnwire``, base id 0x1001B000): commands START_BURNWIRE (0),
STOP_BURNWIRE (1); events SetBurnwireState, SafetyTimerStatus, SafetyTimerState, BurnwireEndCount;
parameter SAFETY_TIMER (U32 s, default 10). Deviations: ``docs/components/antenna_deployer.md``.
"""

from __future__ import annotations

from fprime_lite import U32, Event, Param, PassiveComponent, Sched, Severity, sync_command, sync_input
from fprime_lite.model.fw_types import On

from detumble.drivers.ports import Signal
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["Burnwire"]


class Burnwire(PassiveComponent):
    """The antenna burnwire of ``spacecraft`` (instance ``burnwire``)."""

    # Instance state, set in __init__ (declared here: the handlers above it use it).
    state: On
    safety_counter: int

    @sync_command()
    def START_BURNWIRE(self):
        """Start a burn (the GPIOs go high on the next tick)."""
        self._start()

    @sync_command()
    def STOP_BURNWIRE(self):
        """Stop the burn now."""
        self._stop()

    SetBurnwireState = Event(Severity.ACTIVITY_HI, "Burnwire State: {}", burnwire_state=On)
    SafetyTimerStatus = Event(Severity.ACTIVITY_HI, "Safety Timer State: {} ", burnwire_state=On)
    SafetyTimerState = Event(Severity.ACTIVITY_HI, "Safety Timer Will Burn For: {} Seconds", burnwire_status=U32)
    BurnwireEndCount = Event(Severity.ACTIVITY_LO, "Burnwire Burned for {} Seconds", end_count=U32)

    @sync_input(Signal)
    def burnStart(self) -> None:
        self._start()

    @sync_input(Signal)
    def burnStop(self) -> None:
        self._stop()

    @sync_input(Sched)
    def schedIn(self, context: int) -> None:
        """1 Hz: drive the GPIOs on the first tick of a burn, count seconds, enforce the safety timer."""
        if self.state != On.ON:
            return
        self.safety_counter += 1
        if self.safety_counter == 1:
            self.spacecraft.set_burnwire(True)
            self.SafetyTimerStatus(On.ON)
        if self.safety_counter >= self.SAFETY_TIMER.value:
            self._stop()
            self.SafetyTimerStatus(On.OFF)

    SAFETY_TIMER = Param(U32, default=10, units="s")

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft
        self.state = On.OFF
        self.safety_counter = 0

    def _start(self) -> None:
        self.SetBurnwireState(On.ON)
        self.safety_counter = 0
        self.state = On.ON
        self.SafetyTimerState(self.SAFETY_TIMER.value)

    def _stop(self) -> None:
        self.SetBurnwireState(On.OFF)
        self.spacecraft.set_burnwire(False)
        self.state = On.OFF
        self.BurnwireEndCount(self.safety_counter)
