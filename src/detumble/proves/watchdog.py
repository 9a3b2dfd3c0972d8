"""Watchdog as flown: pets the flight computer's external hardware watchdog from the 1 Hz group.

While running, every ``run`` toggles the watchdog GPIO and counts the transition
(WatchdogTransitions). START_WATCHDOG / ``start`` resume petting (WatchdogStart); STOP_WATCHDOG
calls ``prepareForReboot`` first (the stop is a deliberate reboot) and stops petting
(WatchdogStop); ``stop`` (the ModeManager's last resort on command loss, the fatal handler) stops
without it — the next boot is then an unintended one.

The hardware: the simulated watchdog resets the flight computer ``timeout_s`` after the last pet
(the reset line of :meth:`SimulatedSpacecraft.request_reset`), so a stopped watchdog power-cycles
the software as it does on the board. ``timeout_s`` (default 5 s) stands for the board's watchdog
supervisor; the flight sources do not state it.
"""

from __future__ import annotations

from fprime_lite import U32, Channel, Event, OutputPort, PassiveComponent, Sched, Severity, sync_command, sync_input
from fprime_lite.model.fw_types import On

from detumble.drivers.ports import Signal
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["Watchdog"]


class Watchdog(PassiveComponent):
    """Pets the hardware watchdog of ``spacecraft`` (instance ``watchdog``)."""

    # Instance state, set in __init__ (declared here: the handlers above it use it).
    gpio: On
    transitions: int

    @sync_command()
    def START_WATCHDOG(self):
        self.start()

    @sync_command()
    def STOP_WATCHDOG(self):
        if self.is_connected("prepareForReboot", 0):
            self.prepareForReboot[0]()
        self.stop()

    WatchdogTransitions = Channel(U32)

    WatchdogStart = Event(Severity.ACTIVITY_HI, "Watchdog started")
    WatchdogStop = Event(Severity.ACTIVITY_HI, "Watchdog stopped")

    @sync_input(Sched)
    def run(self, context: int) -> None:
        if self.running:
            self.gpio = On.OFF if self.gpio == On.ON else On.ON
            self.transitions = (self.transitions + 1) & 0xFFFFFFFF
            self.WatchdogTransitions.write(self.transitions)
            self._pet()

    @sync_input(Signal)
    def start(self) -> None:
        self.running = True
        self.WatchdogTransitions.write(self.transitions)
        self.WatchdogStart()

    @sync_input(Signal)
    def stop(self) -> None:
        self.running = False
        self.WatchdogStop()

    prepareForReboot = OutputPort(Signal)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0, timeout_s: float = 5.0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        if not timeout_s > 0:
            raise ValueError(f"{name}: timeout_s must be positive, got {timeout_s!r}")
        self.spacecraft = spacecraft
        self.timeout_us = round(timeout_s * 1e6)
        self.running = True      # the flight component pets from the first run
        self.gpio = On.OFF
        self.transitions = 0
        self._expiry = None
        self._pet()

    def _pet(self) -> None:
        """Restart the hardware watchdog's countdown (needs the spacecraft on a scheduler)."""
        scheduler = self.spacecraft.scheduler()
        if scheduler is None:
            return
        if self._expiry is not None:
            self._expiry.cancel()
        owner = self

        def expire():
            if owner._expiry is call and owner.spacecraft.reset_handler is not None:
                owner.spacecraft.request_reset("watchdog")

        call = scheduler.call_at(scheduler.now_us + self.timeout_us, expire)
        self._expiry = call
