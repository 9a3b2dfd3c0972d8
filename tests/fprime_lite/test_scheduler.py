"""The deterministic scheduler and its wall-clock-paced variant."""

import pytest

from fprime_lite import U32, ActiveComponent, PortType, async_input
from fprime_lite.scheduler import PacedScheduler, Scheduler


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


def test_queues_are_drained_after_each_event_until_quiet():
    s = Scheduler()
    log = []
    b = Sink("b", log)
    a = Sink("a", log, forward=b)
    b.forward = a
    s.drain_after_each_event(a)
    s.drain_after_each_event(b)
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
