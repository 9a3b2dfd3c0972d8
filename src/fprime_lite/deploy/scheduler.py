"""The deterministic scheduler: one simulated clock, an event heap, queues drained after each event.

Time is an integer number of microseconds. Events at the same time run in the order they were
scheduled (a sequence number breaks ties), so the same inputs always give the same run. After every
event the scheduler drains the queues of the queued and active components it was given, until all
are empty: an async call made while handling an event is handled before time moves on, which is
what a fast enough processor does.

Listeners registered with :meth:`Scheduler.add_time_listener` are told the new time before any event
at that time runs (the simulated spacecraft advances its physics there).

:class:`PacedScheduler` runs the same events no faster than the wall clock (times ``speed``), for a
deployment talking to a real ground system. The simulated clock still stamps everything.
"""

from __future__ import annotations

import functools
import heapq
import itertools
import logging
import time as _wall
from typing import Callable

from fprime_lite.model.time import SimulatedClock

__all__ = ["Scheduler", "PacedScheduler", "ScheduledCall", "HOLD_THRESHOLD_S"]

log = logging.getLogger("fprime_lite")


class ScheduledCall:
    """A handle to a scheduled call; :meth:`cancel` stops it (and its repetitions)."""

    __slots__ = ("fn", "period_us", "cancelled")

    def __init__(self, fn: Callable[[], None], period_us: int | None):
        self.fn = fn
        self.period_us = period_us
        self.cancelled = False

    def cancel(self) -> None:
        self.cancelled = True


class Scheduler:
    """Runs calls in simulated time order on one :class:`~fprime_lite.model.time.SimulatedClock`."""

    def __init__(self, clock: SimulatedClock | None = None):
        self.clock = clock if clock is not None else SimulatedClock()
        self._heap: list[tuple[int, int, ScheduledCall]] = []
        self._seq = itertools.count()
        self._drained: list = []
        self._busy: dict = {}  # components whose queues received messages, in arrival order
        self._listeners: list[Callable[[int], None]] = []
        self._stopped = False
        self.events_run = 0

    @property
    def now_us(self) -> int:
        return self.clock.current_us

    def call_at(self, time_us: int, fn: Callable[[], None]) -> ScheduledCall:
        """Run ``fn()`` at simulated time ``time_us`` (not before now)."""
        if time_us < self.clock.current_us:
            raise ValueError(f"cannot schedule at {time_us} us: it is already {self.clock.current_us} us")
        call = ScheduledCall(fn, None)
        heapq.heappush(self._heap, (time_us, next(self._seq), call))
        return call

    def reschedule(self, call: ScheduledCall, time_us: int) -> None:
        """Put a one-shot ``call`` that has already run back on the heap for ``time_us``."""
        if time_us < self.clock.current_us:
            raise ValueError(f"cannot schedule at {time_us} us: it is already {self.clock.current_us} us")
        heapq.heappush(self._heap, (time_us, next(self._seq), call))

    def call_later(self, delay_us: int, fn: Callable[[], None]) -> ScheduledCall:
        return self.call_at(self.clock.current_us + delay_us, fn)

    def call_every(self, period_us: int, fn: Callable[[], None], start_us: int | None = None) -> ScheduledCall:
        """Run ``fn()`` every ``period_us`` from ``start_us`` (default: now)."""
        if not isinstance(period_us, int) or period_us <= 0:
            raise ValueError(f"period must be a positive number of microseconds, got {period_us!r}")
        call = ScheduledCall(fn, period_us)
        first = self.clock.current_us if start_us is None else start_us
        heapq.heappush(self._heap, (first, next(self._seq), call))
        return call

    def drain_after_each_event(self, component) -> None:
        """Empty ``component``'s queue after every event (deterministic active components)."""
        if component not in self._drained:
            self._drained.append(component)
            component.drained_by_scheduler = True
            busy = self._busy
            component.queue.on_put = functools.partial(busy.__setitem__, component, None)
            if len(component.queue):
                busy[component] = None

    def stop_draining(self, component) -> None:
        """Undo :meth:`drain_after_each_event` (a component about to be re-initialised)."""
        if component in self._drained:
            self._drained.remove(component)
            self._busy.pop(component, None)

    def add_time_listener(self, listener: Callable[[int], None]) -> None:
        """``listener(time_us)`` is called whenever time advances, before the events at that time."""
        self._listeners.append(listener)

    def next_time_us(self) -> int | None:
        """When the next event is due, or None when nothing is scheduled."""
        while self._heap and self._heap[0][2].cancelled:
            heapq.heappop(self._heap)
        return self._heap[0][0] if self._heap else None

    def step(self) -> bool:
        """Run the next event (and drain queues); False when nothing is scheduled."""
        t = self.next_time_us()
        if t is None:
            return False
        self._run_next(t)
        return True

    def _run_next(self, t: int) -> None:
        """Run the event at the top of the heap, which is due at ``t`` and not cancelled."""
        _, _, call = heapq.heappop(self._heap)
        self._advance_to(t)
        if call.period_us is not None:
            heapq.heappush(self._heap, (t + call.period_us, next(self._seq), call))
        call.fn()
        self.events_run += 1
        if self._busy:
            self.drain()

    def _advance_to(self, t: int) -> None:
        if t != self.clock.current_us:
            self.clock.set_us(t)
            for listener in self._listeners:
                listener(t)

    def drain(self) -> None:
        """Dispatch queued messages until every drained component's queue is empty.

        Only components whose queues received a message since they were last emptied are visited;
        a message queued while draining marks its component again. A handler that raises is
        reported by the component (``report_fault``: counted in ``handler_faults``, logged, a
        ``HandlerFault`` event and the ``HandlerFaults`` channel), as on a component thread; the
        messages behind it still run and the deployment goes on.
        """
        busy = self._busy
        while busy:
            component = next(iter(busy))
            del busy[component]
            component.dispatch_all(contain_faults=True)

    def run(self, until_us: int | None = None, max_events: int | None = None) -> int:
        """Run events up to and including time ``until_us``; then set the clock to ``until_us``.

        Returns the number of events run. :meth:`stop` ends the run early.
        """
        self._stopped = False
        n = 0
        cls = type(self)
        # The plain scheduler's hook does nothing: its call is left out of the loop (a subclass's runs).
        before_event = None if cls._before_event is Scheduler._before_event else self._before_event
        if (cls.next_time_us is not Scheduler.next_time_us or cls._run_next is not Scheduler._run_next
                or cls._advance_to is not Scheduler._advance_to):
            while not self._stopped and (max_events is None or n < max_events):
                t = self.next_time_us()
                if t is None or (until_us is not None and t > until_us):
                    break
                if before_event is not None:
                    before_event(t)
                self._run_next(t)
                n += 1
        else:
            n = self._run_plain(until_us, max_events, before_event)
        if until_us is not None and not self._stopped and until_us > self.clock.current_us:
            self._before_event(until_us)
            self._advance_to(until_us)
        return n

    def _run_plain(self, until_us: int | None, max_events: int | None,
                   before_event: Callable[[int], None] | None) -> int:
        """:meth:`run`'s loop with :meth:`next_time_us`, :meth:`_run_next` and :meth:`_advance_to`
        written out (the scheduler's own, not overridden): every event of a deployment passes here,
        one a tick of the fastest rate group. The same steps in the same order: cancelled calls
        dropped from the top of the heap, the clock set (through ``set_us`` unless it is a plain
        :class:`SimulatedClock` moving forward) and the time listeners told, a periodic call put
        back before it runs, the events counted, the busy queues drained."""
        heap = self._heap
        clock = self.clock
        listeners = self._listeners
        busy = self._busy
        seq = self._seq
        heappop, heappush = heapq.heappop, heapq.heappush
        plain_clock = type(clock).set_us is SimulatedClock.set_us
        n = 0
        while not self._stopped and (max_events is None or n < max_events):
            while heap and heap[0][2].cancelled:
                heappop(heap)
            if not heap:
                break
            t = heap[0][0]
            if until_us is not None and t > until_us:
                break
            if before_event is not None:
                before_event(t)
            _, _, call = heappop(heap)
            current = clock.current_us
            if t != current:
                if plain_clock and t > current:
                    clock.current_us = t
                else:
                    clock.set_us(t)
                for listener in listeners:
                    listener(t)
            if call.period_us is not None:
                heappush(heap, (t + call.period_us, next(seq), call))
            call.fn()
            self.events_run += 1
            if busy:
                self.drain()
            n += 1
        return n

    def _before_event(self, t: int) -> None:
        """Hook for pacing; the simulated scheduler never waits."""

    def stop(self) -> None:
        """End :meth:`run` after the current event."""
        self._stopped = True

    @property
    def stopped(self) -> bool:
        """True when the last :meth:`run` was ended by :meth:`stop`."""
        return self._stopped


#: A handler that holds its component this long (wall seconds) keeps it busy as long in simulated
#: time when paced (:meth:`PacedScheduler.drain`); shorter ones count as instantaneous.
HOLD_THRESHOLD_S = 0.05


class PacedScheduler(Scheduler):
    """A scheduler that keeps simulated time from running ahead of the wall clock × ``speed``."""

    def __init__(self, clock: SimulatedClock | None = None, speed: float = 1.0,
                 sleep: Callable[[float], None] = _wall.sleep,
                 monotonic: Callable[[], float] = _wall.monotonic):
        super().__init__(clock)
        if speed <= 0:
            raise ValueError(f"speed must be positive, got {speed}")
        self.speed = speed
        self._sleep = sleep
        self._monotonic = monotonic
        self._origin: tuple[float, int] | None = None
        self.max_lag_s = 0.0
        self._held: dict = {}  # component -> simulated time (us) until which it is still busy

    def drain(self) -> None:
        """Dispatch queued messages as :meth:`Scheduler.drain` does, one message at a time, and keep
        a component whose handler held it for ``HOLD_THRESHOLD_S`` of wall time or more busy for as
        long in simulated time: the messages queued for it meanwhile (a health ping) wait until then,
        as they wait for an F´ active component's thread. In a simulated (unpaced) run a handler
        takes no simulated time; paced to the wall clock, a file operation of seconds makes the
        component late to answer its pings (F´'s Health integration test relies on it). A handler
        that models how long its operation takes on the flight hardware (it adds simulated
        microseconds to the component's ``modelled_busy_us``, e.g. FileManager's storage rate) keeps
        the component busy that long instead of its wall time, whatever the host's speed.
        """
        busy = self._busy
        held = self._held
        now = self.clock.current_us
        while busy:
            component = next(iter(busy))
            del busy[component]
            if component in held:
                continue  # its release call marks it again
            while len(component.queue):
                start = self._monotonic()
                component.dispatch_all(1, contain_faults=True)
                held_us = round((self._monotonic() - start) * 1e6 * self.speed)
                modelled = getattr(component, "modelled_busy_us", 0)
                if modelled:  # the flight hardware's time, not the host's
                    component.modelled_busy_us = 0
                    held_us = int(modelled)
                elif held_us < HOLD_THRESHOLD_S * 1e6:
                    held_us = 0
                if held_us > 0:
                    held[component] = now + held_us
                    self.call_at(now + held_us, functools.partial(self._release, component))
                    break

    def _release(self, component) -> None:
        del self._held[component]
        if len(component.queue):
            self._busy[component] = None

    def _before_event(self, t: int) -> None:
        if self._origin is None:
            self._origin = (self._monotonic(), self.clock.current_us)
        wall0, sim0 = self._origin
        due = wall0 + (t - sim0) / 1e6 / self.speed
        delay = due - self._monotonic()
        if delay > 0:
            self._sleep(delay)
        else:
            self.max_lag_s = max(self.max_lag_s, -delay)
