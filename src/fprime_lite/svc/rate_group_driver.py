"""RateGroupDriver: divides one base tick into the ticks of several rate groups.

Output ``CycleOut[i]`` fires on base ticks where ``tick % divisor_i == offset_i`` (F´'s
``Svc.RateGroupDriver``). :class:`RateGroupTimer` drives it from the scheduler and jumps over base
ticks on which no output fires, so a 1 kHz base tick with 50 Hz and 1 Hz groups costs nothing on the
other 949 ticks of each second.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from fprime_lite.model.component import PassiveComponent
from fprime_lite.model.fw_ports import Cycle
from fprime_lite.model.ports import OutputPort, sync_input
from fprime_lite.model.time import Time

__all__ = ["Divider", "RateGroupDriver", "RateGroupTimer"]

#: Dividers whose pattern repeats within this many base ticks (the least common multiple of the
#: divisors) get a lookup table of what fires on each tick of the pattern; others are evaluated
#: divider by divider.
PATTERN_TABLE_MAX = 1 << 16


@dataclass(frozen=True)
class Divider:
    """Output fires when ``tick % divisor == offset``."""

    divisor: int
    offset: int = 0

    def __post_init__(self):
        if not isinstance(self.divisor, int) or self.divisor < 1:
            raise ValueError(f"divisor must be a positive integer, got {self.divisor!r}")
        if not isinstance(self.offset, int) or not 0 <= self.offset < self.divisor:
            raise ValueError(f"offset must be in 0..{self.divisor - 1}, got {self.offset!r}")


class RateGroupDriver(PassiveComponent):
    """Fans one cycle input out to up to ten rate groups by divisor and offset."""

    MAX_OUTPUTS = 10
    CycleOut = OutputPort(Cycle, size=MAX_OUTPUTS)

    def __init__(self, name: str, *, base_id: int = 0, dividers=()):
        super().__init__(name, base_id=base_id)
        dividers = [d if isinstance(d, Divider) else Divider(*d) for d in dividers]
        if len(dividers) > self.MAX_OUTPUTS:
            raise ValueError(f"{name}: at most {self.MAX_OUTPUTS} dividers, got {len(dividers)}")
        self.dividers = tuple(dividers)
        self.tick = 0  # index of the next base tick to handle
        self._table_of: object = None
        self._table_cache: tuple[tuple[int, int, int], ...] = ()
        # The firing pattern over one repetition (see _table): outputs firing on tick % period,
        # and base ticks from there to the next firing tick; None when the pattern is too long.
        self._period = 1
        self._fires: list[tuple[int, ...]] | None = None
        self._waits: list[int] | None = None
        self._cycle_targets = self.output_port("CycleOut").targets

    @sync_input(Cycle)
    def CycleIn(self, cycle_start: Time) -> None:
        tick = self.tick
        if self._table_of is not self.dividers:
            self._table()
        fires = self._fires
        outputs = (fires[tick % self._period] if fires is not None
                   else [i for i, divisor, offset in self._table_cache if tick % divisor == offset])
        if outputs:
            out = self.CycleOut
            targets = self._cycle_targets
            for i in outputs:
                if targets[i] is not None:
                    out[i](cycle_start)
        self.tick = tick + 1

    def _table(self) -> tuple[tuple[int, int, int], ...]:
        """``(output, divisor, offset)`` of every divider, rebuilt (with the firing pattern) when
        ``dividers`` is replaced."""
        dividers = self.dividers
        if self._table_of is not dividers:
            table = tuple((i, d.divisor, d.offset) for i, d in enumerate(dividers))
            period = math.lcm(*(d.divisor for d in dividers)) if dividers else 1
            if period <= PATTERN_TABLE_MAX:
                fires = [tuple(i for i, divisor, offset in table if t % divisor == offset) for t in range(period)]
                waits = [0] * period
                if table:
                    wait = next(k for k in range(period) if fires[k])  # at tick `period`, i.e. 0
                    for t in range(period - 1, -1, -1):  # ticks to the next firing tick, from the end
                        wait = 0 if fires[t] else wait + 1
                        waits[t] = wait
                self._period, self._fires, self._waits = period, fires, (waits if table else None)
            else:
                self._period, self._fires, self._waits = 1, None, None
            self._table_cache = table
            self._table_of = dividers
        return self._table_cache

    def ticks_to_next_output(self) -> int:
        """How many base ticks from now until one of the outputs fires (0: this very tick)."""
        table = self._table()
        waits = self._waits
        if waits is not None:
            return waits[self.tick % self._period]
        best = None
        tick = self.tick
        for _, divisor, offset in table:
            wait = (offset - tick) % divisor
            if best is None or wait < best:
                best = wait
        return 0 if best is None else best

    def skip_ticks(self, n: int) -> None:
        """Account for ``n`` base ticks on which nothing fires."""
        self.tick += n


class RateGroupTimer:
    """Calls a driver's ``CycleIn`` from a scheduler at a base period, skipping idle ticks."""

    def __init__(self, scheduler, driver: RateGroupDriver, base_period_us: int):
        if not isinstance(base_period_us, int) or base_period_us <= 0:
            raise ValueError(f"base period must be a positive number of microseconds, got {base_period_us!r}")
        self.scheduler = scheduler
        self.driver = driver
        self.base_period_us = base_period_us
        self.cycle_in = driver.input_port("CycleIn").entries[0]
        self.cycles = 0
        self._call = None
        self._idle_ticks = 0

    def start(self, start_us: int | None = None) -> None:
        now = self.scheduler.now_us if start_us is None else start_us
        self._schedule(now)

    def stop(self) -> None:
        """Stop ticking (a flight-software restart starts the timer again)."""
        if self._call is not None:
            self._call.cancel()
            self._call = None

    def _schedule(self, base_tick_time_us: int) -> None:
        driver = self.driver
        waits = driver._waits
        # ticks_to_next_output's table lookup, read here while the table is that of the dividers as they are
        wait = (waits[driver.tick % driver._period]
                if waits is not None and driver._table_of is driver.dividers and type(driver) is RateGroupDriver
                else driver.ticks_to_next_output())
        self._idle_ticks = wait
        due = base_tick_time_us + wait * self.base_period_us
        if self._call is None:
            self._call = self.scheduler.call_at(due, self._fire)
        else:
            self.scheduler.reschedule(self._call, due)

    def _fire(self) -> None:
        driver = self.driver
        driver.tick += self._idle_ticks  # the skipped ticks on which nothing fired
        scheduler = self.scheduler
        clock = scheduler.clock
        now = clock.current_us
        self.cycles += 1
        self.cycle_in(clock.now())
        # _schedule(now + base period), written out for a plain driver whose firing table is that of
        # its dividers and a timer still running (once a base tick that fires)
        waits = driver._waits
        call = self._call
        if (waits is None or call is None or driver._table_of is not driver.dividers
                or type(driver) is not RateGroupDriver):
            self._schedule(now + self.base_period_us)
            return
        period_us = self.base_period_us
        wait = waits[driver.tick % driver._period]
        self._idle_ticks = wait
        scheduler.reschedule(call, now + period_us + wait * period_us)
