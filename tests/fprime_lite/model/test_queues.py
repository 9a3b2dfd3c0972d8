"""Queued and active components: priorities, dispatch, queue-full behaviours, threads."""

import threading

import pytest

from fprime_lite import (U32, ActiveComponent, CmdResponse, FwAssertionError, PortType,
                         QueuedComponent, QueueFullError, async_command, async_input)

Item = PortType("Test.Item", value=U32)


class Worker(QueuedComponent):
    def __init__(self, name, **kw):
        super().__init__(name, **kw)
        self.seen = []
        self.overflowed = []

    @async_input(Item)
    def normal(self, value):
        self.seen.append(("normal", value))

    @async_input(Item, priority=5)
    def urgent(self, value):
        self.seen.append(("urgent", value))

    @async_input(Item, queue_full="drop")
    def droppy(self, value):
        self.seen.append(("droppy", value))

    @async_input(Item, queue_full="hook")
    def hooky(self, value):
        self.seen.append(("hooky", value))

    def hooky_overflow_hook(self, value):
        self.overflowed.append(value)

    @async_input(Item, queue_full="block")
    def blocky(self, value):
        self.seen.append(("blocky", value))

    @async_input(Item, size=2)
    def multi(self, port_num, value):
        self.seen.append(("multi", port_num, value))

    @async_command()
    def WORK(self, n: U32):
        self.seen.append(("WORK", n))


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(Worker("worker", queue_size=3))


def test_async_calls_wait_for_dispatch(h):
    h.invoke("normal", 1)
    assert h.component.seen == []
    assert h.dispatch() is True
    assert h.component.seen == [("normal", 1)]
    assert h.dispatch() is False


def test_priority_first_then_arrival_order(h):
    h.invoke("normal", 1)
    h.invoke("normal", 2)
    h.invoke("urgent", 3)
    assert h.dispatch_all() == 3
    assert h.component.seen == [("urgent", 3), ("normal", 1), ("normal", 2)]


def test_full_queue_asserts_by_default(h):
    for i in range(3):
        h.invoke("normal", i)
    with pytest.raises(QueueFullError, match=r"worker: queue full \(3 messages\) on worker\.normal\[0\]"):
        h.invoke("normal", 9)


def test_full_queue_drop_discards_and_counts(h):
    for i in range(4):
        h.invoke("droppy", i)
    h.dispatch_all()
    assert h.component.seen == [("droppy", 0), ("droppy", 1), ("droppy", 2)]
    assert h.component.queue.dropped == 1


def test_full_queue_hook_calls_the_overflow_hook(h):
    for i in range(4):
        h.invoke("hooky", i)
    assert h.component.overflowed == [3]


def test_full_queue_block_without_thread_runs_oldest_inline(h):
    for i in range(4):
        h.invoke("blocky", i)
    assert h.component.seen == [("blocky", 0)]
    h.dispatch_all()
    assert [v for _, v in h.component.seen] == [0, 1, 2, 3]


def test_async_port_array_keeps_port_numbers(h):
    h.invoke("multi", 7, port_num=1)
    h.dispatch()
    assert h.component.seen == [("multi", 1, 7)]


def test_async_command_is_queued_then_answered(h):
    h.send_command("WORK", 4, cmd_seq=2)
    h.assert_cmd_response_size(0)
    h.dispatch()
    assert h.component.seen == [("WORK", 4)]
    h.assert_cmd_response(0, "WORK", CmdResponse.OK, cmd_seq=2)


def test_high_water_mark(h):
    h.invoke("normal", 1)
    h.invoke("normal", 2)
    h.dispatch_all()
    assert h.component.queue.high_water == 2


class Threaded(ActiveComponent):
    def __init__(self, name, **kw):
        super().__init__(name, **kw)
        self.seen = []
        self.done = threading.Event()

    @async_input(Item, queue_full="block")
    def item(self, value):
        self.seen.append((value, threading.current_thread().name))
        if value == 99:
            self.done.set()


def test_active_component_is_deterministic_unless_started(fprime_harness):
    h = fprime_harness(Threaded("active"))
    h.invoke("item", 1)
    assert h.component.seen == []
    h.dispatch_all()
    assert h.component.seen == [(1, threading.current_thread().name)]


def test_active_component_thread_handles_messages_in_order(fprime_harness):
    h = fprime_harness(Threaded("active", queue_size=2))
    h.component.start()
    for v in range(10):
        h.invoke("item", v)
    h.invoke("item", 99)
    assert h.component.done.wait(timeout=10)
    h.component.exit()
    assert [v for v, _ in h.component.seen] == list(range(10)) + [99]
    assert {t for _, t in h.component.seen} == {"active"}


def test_dispatch_on_a_passive_component_is_an_assertion(fprime_harness):
    from fprime_lite import PassiveComponent

    class P(PassiveComponent):
        pass

    h = fprime_harness(P("p"))
    with pytest.raises(FwAssertionError, match="p is passive and has no queue"):
        h.dispatch()


def test_queue_size_must_be_positive():
    with pytest.raises(ValueError, match="queue size must be a positive integer"):
        Worker("w", queue_size=0)
