"""RateGroupDriver dividers, the skipping timer, rate-group members, slips and faults."""

import pytest

from fprime_lite import PassiveComponent, Sched, Severity, Time, TimeBase, sync_input
from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.svc.rate_group_driver import Divider, RateGroupDriver, RateGroupTimer
from fprime_lite.svc.rate_groups import ActiveRateGroup, PassiveRateGroup


class Member(PassiveComponent):
    def __init__(self, name, log, clock=None, consume_us=0, fail=False):
        super().__init__(name)
        self.log, self.clock, self.consume_us, self.fail = log, clock, consume_us, fail

    @sync_input(Sched)
    def run(self, context):
        self.log.append((self.name, context, self.clock.current_us if self.clock else None))
        if self.fail:
            raise RuntimeError("sensor bus stuck")
        if self.consume_us:
            self.clock.advance_us(self.consume_us)


def test_divider_validation():
    with pytest.raises(ValueError, match="divisor must be a positive integer"):
        Divider(0)
    with pytest.raises(ValueError, match=r"offset must be in 0\.\.4"):
        Divider(5, 5)


def test_driver_fires_outputs_by_divisor_and_offset(fprime_harness):
    h = fprime_harness(RateGroupDriver("rgDriver", dividers=[(1, 0), (2, 1), (4, 0)]))
    for tick in range(8):
        h.invoke("CycleIn", Time(TimeBase.TB_WORKSTATION_TIME, 0, 0, tick))
    fired = [(c.index, c.args[0].useconds) for c in h.from_port("CycleOut")]
    assert [t for i, t in fired if i == 0] == list(range(8))
    assert [t for i, t in fired if i == 1] == [1, 3, 5, 7]
    assert [t for i, t in fired if i == 2] == [0, 4]


@pytest.mark.parametrize("dividers", [[(20, 0), (100, 0), (1000, 0)], [(3, 2), (7, 0), (10, 4)], [(1, 0)],
                                      [(65537, 3), (2, 1)], [(7, 6)]])
def test_driver_pattern_table_agrees_with_the_divider_rule(dividers, monkeypatch):
    """RGD-004: what fires on each base tick and the wait to the next firing tick, read from the
    driver's pattern table, are those of F´'s rule ``tick % divisor == offset`` over three periods of
    the pattern (or 3000 ticks of a pattern too long for a table), also after the dividers change."""
    from fprime_lite.svc import rate_group_driver

    for table_max in (rate_group_driver.PATTERN_TABLE_MAX, 0):  # the table, then the fallback
        monkeypatch.setattr(rate_group_driver, "PATTERN_TABLE_MAX", table_max)
        driver = RateGroupDriver("rgDriver", dividers=[(5, 1)])
        fired = []
        for i in range(10):
            driver.output_port("CycleOut").connect_callable(
                i, lambda t, i=i, fired=fired: fired.append((t, i)), f"out{i}")
        driver.CycleIn(Time())
        driver.dividers = tuple(Divider(*d) for d in dividers)  # replaced: the table is rebuilt
        driver.tick = 0
        fired.clear()
        import math
        span = min(3 * math.lcm(*(d for d, _ in dividers)), 3000)
        for tick in range(span):
            expected_wait = min((o - tick) % d for d, o in dividers)
            assert driver.ticks_to_next_output() == expected_wait, (tick, table_max)
            driver.CycleIn(tick)
        assert fired == [(t, i) for t in range(span) for i, (d, o) in enumerate(dividers) if t % d == o]


def test_timer_skips_idle_ticks_but_counts_them():
    s = Scheduler()
    driver = RateGroupDriver("rgDriver", dividers=[(20, 0), (1000, 0)])
    log = []
    fast, slow = Member("fast", log, s.clock), Member("slow", log, s.clock)
    rg50 = PassiveRateGroup("rg50", contexts=[7])
    rg1 = PassiveRateGroup("rg1", contexts=[9])
    driver.output_port("CycleOut").connect(0, rg50.input_port("CycleIn"))
    driver.output_port("CycleOut").connect(1, rg1.input_port("CycleIn"))
    rg50.output_port("RateGroupMemberOut").connect(0, fast.input_port("run"))
    rg1.output_port("RateGroupMemberOut").connect(0, slow.input_port("run"))
    timer = RateGroupTimer(s, driver, base_period_us=1000)
    timer.start(0)
    s.run(until_us=2_000_000)
    fast_times = [t for n, _, t in log if n == "fast"]
    assert fast_times == list(range(0, 2_000_001, 20_000))
    assert [t for n, _, t in log if n == "slow"] == [0, 1_000_000, 2_000_000]
    assert {c for n, c, _ in log if n == "fast"} == {7}
    # Only ticks on which something fires were scheduled (the 1 Hz ticks coincide with 50 Hz ones),
    # yet the driver counted every base tick.
    assert timer.cycles == 101
    assert driver.tick == 2001


def test_active_rate_group_runs_members_in_order_on_dispatch(fprime_harness):
    log = []
    h = fprime_harness(ActiveRateGroup("rg", contexts=[1, 2, 3], period_us=20_000))
    for i in range(3):
        m = Member(f"m{i}", log)
        h.component.output_port("RateGroupMemberOut").disconnect(i)
        h.component.output_port("RateGroupMemberOut").connect(i, m.input_port("run"))
    h.invoke("CycleIn", Time())
    assert log == []
    h.dispatch_all()
    assert [(n, c) for n, c, _ in log] == [("m0", 1), ("m1", 2), ("m2", 3)]
    h.assert_event_count("RateGroupStarted", 1)
    h.assert_tlm_count("RgMaxTime", 1)
    h.assert_no_event("RateGroupCycleSlip")


def test_active_rate_groups_under_a_scheduler_run_when_posted_in_driver_order():
    """In a deterministic deployment an idle group's cycle runs without a queue hop, in the order
    the driver posts the cycles (the order the scheduler's drain used to give)."""
    s = Scheduler()
    driver = RateGroupDriver("rgDriver", dividers=[(1, 0), (2, 0)])
    log = []
    groups = [ActiveRateGroup(n, contexts=[0], period_us=1000) for n in ("rgFast", "rgSlow")]
    for i, rg in enumerate(groups):
        rg.output_port("timeCaller").connect_callable(0, s.clock.now, "simulated clock")
        driver.output_port("CycleOut").connect(i, rg.input_port("CycleIn"))
        rg.output_port("RateGroupMemberOut").connect(0, Member(f"m{i}", log, s.clock).input_port("run"))
        s.drain_after_each_event(rg)
    RateGroupTimer(s, driver, base_period_us=1000).start(0)
    s.run(until_us=3000)
    assert [(n, t) for n, _, t in log] == [("m0", 0), ("m1", 0), ("m0", 1000), ("m0", 2000), ("m1", 2000),
                                           ("m0", 3000)]
    assert [rg.queue.high_water for rg in groups] == [0, 0]  # no cycle went through a queue
    assert [rg.cycles for rg in groups] == [4, 2] and [rg.slips for rg in groups] == [0, 0]


def test_cycle_arriving_while_previous_one_is_queued_is_a_slip(fprime_harness):
    h = fprime_harness(ActiveRateGroup("rg", period_us=20_000))
    h.invoke("CycleIn", Time())
    h.invoke("CycleIn", Time())
    h.dispatch_all()
    h.assert_event("RateGroupCycleSlip", 0, 0)
    assert h.tlm_values("RgCycleSlips") == [1]
    assert h.events_named("RateGroupCycleSlip") and \
        [e.severity for e in h.events if e.name == "RateGroupCycleSlip"] == [Severity.WARNING_HI]


def test_members_overrunning_the_period_in_simulated_time_slip():
    s = Scheduler()
    log = []
    rg = PassiveRateGroup("rg", contexts=[0, 0], period_us=20_000)
    rg.output_port("timeCaller").connect_callable(0, s.clock.now, "simulated clock")
    quick = Member("quick", log, s.clock, consume_us=5_000)
    hog = Member("hog", log, s.clock, consume_us=16_000)
    rg.output_port("RateGroupMemberOut").connect(0, quick.input_port("run"))
    rg.input_port("CycleIn").entries[0](s.clock.now())
    assert rg.slips == 0
    rg.output_port("RateGroupMemberOut").connect(1, hog.input_port("run"))
    rg.input_port("CycleIn").entries[0](s.clock.now())
    assert rg.slips == 1


def test_member_fault_is_an_event_and_the_group_goes_on(fprime_harness):
    log = []
    h = fprime_harness(PassiveRateGroup("rg", contexts=[0, 0]))
    bad, good = Member("bad", log, fail=True), Member("good", log)
    for i, m in enumerate((bad, good)):
        h.component.output_port("RateGroupMemberOut").disconnect(i)
        h.component.output_port("RateGroupMemberOut").connect(i, m.input_port("run"))
    for _ in range(7):
        h.invoke("CycleIn", Time())
    assert [n for n, _, _ in log].count("good") == 7
    h.assert_event_count("RateGroupMemberFault", 5)  # throttled at 5
    h.assert_event("RateGroupMemberFault", 0, 0, "RuntimeError: sensor bus stuck")
    assert h.tlm_values("RgMemberFaults")[-1] == 7


def test_passive_rate_group_reentry_is_a_slip(fprime_harness):
    h = fprime_harness(PassiveRateGroup("rg"))
    rg = h.component

    class Reenter(PassiveComponent):
        @sync_input(Sched)
        def run(self, context):
            rg.input_port("CycleIn").entries[0](Time())

    member = Reenter("re")
    rg.output_port("RateGroupMemberOut").disconnect(0)
    rg.output_port("RateGroupMemberOut").connect(0, member.input_port("run"))
    h.invoke("CycleIn", Time())
    assert rg.slips == 1


def test_slip_event_throttle_decays_on_good_cycles_as_in_fprime(fprime_harness):
    """RG: after the throttle is reached, each good cycle allows one more slip report (F´'s overrun throttle)."""
    h = fprime_harness(ActiveRateGroup("rg", period_us=20_000, queue_size=10))
    for _ in range(7):  # cycles 1-6 each find another cycle waiting: six slips in a row; cycle 7 is good
        h.invoke("CycleIn", Time())
    h.dispatch_all()
    assert h.component.slips == 6
    h.assert_event_count("RateGroupCycleSlip", 5)  # the sixth report was throttled
    h.invoke("CycleIn", Time())
    h.invoke("CycleIn", Time())  # one more slip: the good cycle 7 made room for its report
    h.dispatch_all()
    h.assert_event_count("RateGroupCycleSlip", 6)
