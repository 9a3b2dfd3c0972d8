"""The deterministic scheduler and its wall-clock-paced variant."""

import pytest

from fprime_lite import U32, ActiveComponent, PortType, async_input
from fprime_lite.deploy.scheduler import PacedScheduler, Scheduler


def test_events_run_in_time_order_with_ties_in_scheduling_order():
    s = Scheduler()
    log = []
    s.call_at(30, lambda: log.append("c"))
    s.call_at(10, lambda: log.append("a1"))
    s.call_at(10, lambda: log.append("a2"))
    s.call_at(20, lambda: log.append("b"))
    assert s.run() == 4
    assert log == ["a1", "a2", "b", "c"]
    assert s.now_us == 30


def test_periodic_calls_and_run_until_sets_the_clock():
    s = Scheduler()
    times = []
    s.call_every(20_000, lambda: times.append(s.now_us), start_us=0)
    s.run(until_us=100_000)
    assert times == [0, 20_000, 40_000, 60_000, 80_000, 100_000]
    s.run(until_us=130_000)
    assert times[-1] == 120_000 and s.now_us == 130_000


def test_time_listeners_see_each_new_time_before_its_events():
    s = Scheduler()
    seen = []
    s.add_time_listener(lambda t: seen.append(("advance", t)))
    s.call_at(5, lambda: seen.append(("event", s.now_us)))
    s.call_at(5, lambda: seen.append(("event", s.now_us)))
    s.run(until_us=8)
    assert seen == [("advance", 5), ("event", 5), ("event", 5), ("advance", 8)]


def test_cancel_and_stop():
    s = Scheduler()
    log = []
    handle = s.call_every(10, lambda: log.append(s.now_us), start_us=0)
    s.call_at(25, handle.cancel)
    s.call_at(100, s.stop)
    s.call_at(200, lambda: log.append("never"))
    s.run()
    assert log == [0, 10, 20]
    assert s.now_us == 100


def test_cannot_schedule_in_the_past_or_with_bad_period():
    s = Scheduler()
    s.run(until_us=50)
    with pytest.raises(ValueError, match="cannot schedule at 10 us: it is already 50 us"):
        s.call_at(10, lambda: None)
    with pytest.raises(ValueError, match="period must be a positive number of microseconds"):
        s.call_every(0, lambda: None)


Item = PortType("Test.Item", value=U32)


class Sink(ActiveComponent):
    def __init__(self, name, log, forward=None):
        super().__init__(name)
        self.log = log
        self.forward = forward

    @async_input(Item)
    def item(self, value):
        self.log.append((self.name, value))
        if self.forward is not None and value < 3:
            self.forward.input_port("item").entries[0](value + 1)


def _ping_pong(s, log):
    """Two active components drained by ``s`` that pass an item back and forth up to 3; the first."""
    b = Sink("b", log)
    a = Sink("a", log, forward=b)
    b.forward = a
    s.drain_after_each_event(a)
    s.drain_after_each_event(b)
    return a


def test_queues_are_drained_after_each_event_until_quiet():
    s = Scheduler()
    log = []
    a = _ping_pong(s, log)
    s.call_at(10, lambda: a.input_port("item").entries[0](0))
    s.call_at(20, lambda: log.append(("event at", s.now_us)))
    s.run()
    assert log == [("a", 0), ("b", 1), ("a", 2), ("b", 3), ("event at", 20)]


def test_same_inputs_give_identical_runs():
    def one_run():
        s = Scheduler()
        log = []
        for period in (7, 11, 13):
            s.call_every(period, lambda p=period: log.append((s.now_us, p)), start_us=0)
        s.run(until_us=1000)
        return log

    assert one_run() == one_run()


def test_paced_scheduler_waits_for_the_wall_clock():
    wall = [100.0]
    sleeps = []

    def sleep(dt):
        sleeps.append(round(dt, 6))
        wall[0] += dt

    s = PacedScheduler(speed=2.0, sleep=sleep, monotonic=lambda: wall[0])
    ran = []
    s.call_every(1_000_000, lambda: ran.append(s.now_us), start_us=0)
    s.run(until_us=3_000_000)
    assert ran == [0, 1_000_000, 2_000_000, 3_000_000]
    assert sleeps == [0.5, 0.5, 0.5]  # one simulated second per half wall second at speed 2


def test_paced_scheduler_records_lag_when_behind():
    wall = [0.0]

    def slow_event():
        wall[0] += 3.0

    s = PacedScheduler(sleep=lambda dt: None, monotonic=lambda: wall[0])
    s.call_every(1_000_000, slow_event, start_us=0)
    s.run(until_us=2_000_000)
    assert s.max_lag_s == pytest.approx(4.0)
    with pytest.raises(ValueError, match="speed must be positive"):
        PacedScheduler(speed=0)


class Slow(ActiveComponent):
    """``item`` takes ``cost[value]`` seconds of (fake) wall time."""

    def __init__(self, name, log, wall, cost, clock):
        super().__init__(name)
        self.log, self.wall, self.cost, self.clock = log, wall, cost, clock

    @async_input(Item)
    def item(self, value):
        self.log.append((value, self.clock.current_us))
        self.wall[0] += self.cost.get(value, 0.0)


def test_paced_scheduler_keeps_a_component_busy_as_long_as_its_handler_held_it():
    """A 3 s handler keeps its component's queue waiting 3 simulated seconds, as an F´ thread would
    (what makes a busy FileManager late to answer Health's pings); short handlers take no time."""
    from fprime_lite.deploy.scheduler import HOLD_THRESHOLD_S

    wall = [0.0]
    s = PacedScheduler(sleep=lambda dt: wall.__setitem__(0, wall[0] + dt), monotonic=lambda: wall[0])
    log = []
    slow = Slow("slow", log, wall, {0: 3.0, 2: HOLD_THRESHOLD_S / 2}, s.clock)
    s.drain_after_each_event(slow)
    port = slow.input_port("item").entries[0]
    s.call_at(0, lambda: port(0))
    s.call_at(1_000_000, lambda: port(1))  # queued while the 3 s handler holds the component
    s.call_at(4_000_000, lambda: port(2))  # short: handled at once …
    s.call_at(4_000_000, lambda: port(3))  # … and so is the message behind it
    s.run(until_us=5_000_000)
    assert log == [(0, 0), (1, 3_000_000), (2, 4_000_000), (3, 4_000_000)]


class Eager(ActiveComponent):
    """An active component whose ``item`` port runs at once when it is idle."""

    def __init__(self, name, log, forward=None, fail_on=None):
        super().__init__(name)
        self.log = log
        self.forward = forward
        self.fail_on = fail_on

    @async_input(Item, run_when_idle=True)
    def item(self, value):
        self.log.append((self.name, value))
        if value == self.fail_on:
            raise RuntimeError("handler failed")
        if self.forward is not None and value < 3:
            self.forward.input_port("item").entries[0](value + 1)
            self.log.append((self.name, "forwarded", value))


def test_run_when_idle_runs_at_once_under_a_scheduler_and_is_queued_otherwise():
    s = Scheduler()
    log = []
    eager = Eager("eager", log)
    eager.input_port("item").entries[0](1)  # no scheduler drains it yet: queued as any async call
    assert log == [] and len(eager.queue) == 1
    eager.dispatch_all()
    s.drain_after_each_event(eager)
    eager.input_port("item").entries[0](2)  # idle and drained by the scheduler: runs on the caller
    assert log == [("eager", 1), ("eager", 2)] and len(eager.queue) == 0
    assert eager.queue.high_water == 1  # the second call never touched the queue


def test_run_when_idle_queues_behind_waiting_messages_and_during_a_handler():
    s = Scheduler()
    log = []
    eager = Eager("eager", log)
    eager.forward = eager  # a handler calling its own port must not recurse into itself
    s.drain_after_each_event(eager)
    s.call_at(10, lambda: eager.input_port("item").entries[0](0))
    s.run()
    # Each forwarded call waited for the running handler to finish, as a queue hop does.
    assert log == [("eager", 0), ("eager", "forwarded", 0), ("eager", 1), ("eager", "forwarded", 1),
                   ("eager", 2), ("eager", "forwarded", 2), ("eager", 3)]
    # A waiting message is not overtaken.
    log.clear()
    eager.forward = None
    eager.queue.put(0, eager.item, (7,), queue_full="assert", port="item")
    eager.input_port("item").entries[0](8)
    assert log == [] and len(eager.queue) == 2
    s.drain()
    assert log == [("eager", 7), ("eager", 8)]


def test_run_when_idle_keeps_scheduler_order_across_components():
    """Inline runs give the order the scheduler's drain gives: first posted, first run."""
    log = []
    s = Scheduler()
    later = Sink("later", log)
    eager = Eager("eager", log, forward=later)
    for c in (later, eager):
        s.drain_after_each_event(c)
    s.call_at(5, lambda: (eager.input_port("item").entries[0](0), log.append(("caller", "continues"))))
    s.run()
    assert log == [("eager", 0), ("eager", "forwarded", 0), ("caller", "continues"), ("later", 1)]


def test_handler_faults_in_a_deployment_are_counted_and_the_run_goes_on(caplog):
    """As on a component thread: a handler that raises is logged and counted, inline or drained."""
    s = Scheduler()
    log = []
    eager = Eager("eager", log, fail_on=1)
    sink = Sink("sink", log)
    calls = []

    def flaky(value):
        calls.append(value)
        if value == 5:
            raise RuntimeError("queued handler failed")

    sink_entry = sink._make_enqueuer(sink.input_port("item").decl, flaky, 0)
    for c in (eager, sink):
        s.drain_after_each_event(c)
    eager.input_port("item").entries[0](1)  # inline, raises: counted
    eager.input_port("item").entries[0](2)  # not stuck "busy": still runs at once
    assert log == [("eager", 1), ("eager", 2)] and len(eager.queue) == 0 and eager.handler_faults == 1
    s.call_at(10, lambda: [sink_entry(v) for v in (4, 5, 6)])
    s.call_at(20, lambda: log.append(("later event", s.now_us)))
    s.run()
    assert calls == [4, 5, 6] and sink.handler_faults == 1  # the message behind the fault still ran
    assert log[-1] == ("later event", 20)
    # The log names the component and the port (for the queued call, its handler).
    assert "eager: item raised" in caplog.text and "sink: flaky raised" in caplog.text


def test_a_harness_still_sees_handler_faults():
    eager = Eager("eager", [], fail_on=1)  # not drained by a scheduler: a unit test
    eager.input_port("item").entries[0](1)
    with pytest.raises(RuntimeError, match="handler failed"):
        eager.dispatch_all()


def test_run_when_idle_is_a_plain_queue_hop_for_a_threaded_component():
    import threading

    log = []
    done = threading.Event()

    class Threaded(Eager):
        @async_input(Item, run_when_idle=True)
        def item(self, value):
            log.append((threading.current_thread().name, value))
            done.set()

    s = Scheduler()
    comp = Threaded("threaded", log)
    s.drain_after_each_event(comp)
    comp.start()
    try:
        comp.input_port("item").entries[0](4)
        assert done.wait(5)
    finally:
        comp.exit()
    assert log == [("threaded", 4)]


def test_run_when_idle_must_be_a_bool():
    from fprime_lite.model.errors import DeclarationError

    with pytest.raises(DeclarationError, match="run_when_idle must be True or False, got 'yes'"):
        async_input(Item, run_when_idle="yes")


class Modelled(Slow):
    """``item`` takes no wall time but models ``cost[value]`` seconds of its hardware's time."""

    @async_input(Item)
    def item(self, value):
        self.log.append((value, self.clock.current_us))
        self.modelled_busy_us = round(self.cost.get(value, 0.0) * 1e6)


def test_paced_scheduler_holds_a_component_for_its_modelled_time_whatever_the_host():
    """A handler that models 2.5 s of its hardware's time (FileManager's storage rate) keeps its queue
    waiting 2.5 simulated seconds although it took no wall time; a modelled 10 ms (below the wall
    threshold) holds it 10 ms, not zero."""
    wall = [0.0]
    s = PacedScheduler(sleep=lambda dt: wall.__setitem__(0, wall[0] + dt), monotonic=lambda: wall[0])
    log = []
    comp = Modelled("modelled", log, wall, {0: 2.5, 2: 0.01}, s.clock)
    s.drain_after_each_event(comp)
    port = comp.input_port("item").entries[0]
    s.call_at(0, lambda: port(0))
    s.call_at(1_000_000, lambda: port(1))  # waits for the modelled 2.5 s
    s.call_at(3_000_000, lambda: port(2))
    s.call_at(3_005_000, lambda: port(3))  # 5 ms later: waits until 3.010 s
    s.run(until_us=4_000_000)
    assert log == [(0, 0), (1, 2_500_000), (2, 3_000_000), (3, 3_010_000)]


class _GeneralLoop(Scheduler):
    """A scheduler whose ``_run_next`` is its own (the same steps): ``run`` takes the general loop."""

    def _run_next(self, t):
        super()._run_next(t)


def _busy_flight(scheduler_class):
    """A seeded mix of one-shot, periodic, cancelled, re-entrant and queue-draining events; what they saw."""
    import random

    rng = random.Random(7)
    s = scheduler_class()
    log = []
    a = _ping_pong(s, log)
    s.add_time_listener(lambda t: log.append(("listener", t)))
    calls = []
    for k in range(40):
        at = rng.randrange(0, 5000)
        if k % 5 == 0:
            calls.append(s.call_every(rng.randrange(50, 400), lambda k=k: log.append(("every", k, s.now_us)),
                                      start_us=at))
        elif k % 7 == 0:
            calls.append(s.call_at(at, lambda: a.input_port("item").entries[0](0)))
        else:
            calls.append(s.call_at(at, lambda k=k: log.append(("once", k, s.now_us, s.clock.now().total_us))))
    for call in calls[3::4]:
        call.cancel()
    s.call_at(2500, lambda: calls[0].cancel())
    runs = [s.run(until_us=1200), s.run(max_events=17), s.run(until_us=4000), s.run(until_us=6000)]
    return log, runs, s.events_run, s.now_us


def test_the_plain_loop_runs_what_the_general_loop_runs():
    """FSWTICK-001: ``Scheduler.run``'s written-out loop (``_run_plain``) and the general loop (a subclass's
    ``_run_next``) run the same events at the same times, tell the listeners, drain the queues, skip
    cancelled calls, count the events and stop where the general loop stops."""
    plain = _busy_flight(Scheduler)
    assert plain == _busy_flight(_GeneralLoop)
    log, runs, events_run, now_us = plain
    assert sum(runs) == events_run > 60 and now_us == 6000
    assert ("a", 0) in log and ("b", 3) in log and any(e[0] == "every" for e in log)


def test_the_plain_loop_still_refuses_to_run_the_clock_backwards():
    """FSWTICK-002: a periodic call first due before the clock's present time (``call_every``'s start is not
    checked) reaches ``SimulatedClock.set_us``, which refuses it, in the written-out loop as in the general one."""
    for scheduler_class in (Scheduler, _GeneralLoop):
        s = scheduler_class()
        s.run(until_us=100)
        s.call_every(10, lambda: None, start_us=50)
        with pytest.raises(ValueError, match="backwards"):
            s.run(until_us=200)
