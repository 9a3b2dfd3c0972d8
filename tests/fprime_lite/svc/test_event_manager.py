"""EventManager: one packet per event, severity and id filters, FATAL announcement, counters."""

import struct

import pytest

from fprime_lite import CmdResponse, Severity, Time, TimeBase, TimeInterval
from fprime_lite.wire.packets import decode_event
from fprime_lite.svc.event_manager import (DEFAULT_SEVERITY_FILTER, ID_FILTER_SIZE, Enabled,
                                           EventManager, FilterSeverity)

T = Time(TimeBase.TB_WORKSTATION_TIME, 0, 100, 250000)


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(EventManager("events", base_id=0x200), test_time=T)


def sent(h):
    return [decode_event(c.args[0]) for c in h.from_port("PktSend")]


def test_f_prime_declarations():
    em = EventManager("events")
    assert [(c.name, c.opcode, c.kind) for c in em.spec.commands] == [
        ("SET_EVENT_FILTER", 0, "sync"), ("SET_ID_FILTER", 2, "async"), ("DUMP_FILTER_STATE", 3, "async")]
    assert {e.name: (e.local_id, e.severity) for e in em.spec.own_events} == {
        "SEVERITY_FILTER_STATE": (0, Severity.ACTIVITY_LO), "ID_FILTER_ENABLED": (1, Severity.ACTIVITY_HI),
        "ID_FILTER_LIST_FULL": (2, Severity.WARNING_LO), "ID_FILTER_REMOVED": (3, Severity.ACTIVITY_HI),
        "ID_FILTER_NOT_FOUND": (4, Severity.WARNING_LO)}
    assert em.input_port("LogRecv").decl.kind == "sync"
    assert set(em.output_ports) >= {"PktSend", "FatalAnnounce"}


def test_each_event_is_its_own_packet(h):
    """One FW_PACKET_LOG packet per event: descriptor, id, time, arguments."""
    h.invoke("LogRecv", 0x1000, T, Severity.ACTIVITY_HI, b"\x01\x02")
    h.invoke("LogRecv", 0x1001, T, Severity.WARNING_HI, b"")
    packets = [c.args for c in h.from_port("PktSend")]
    assert packets[0] == (struct.pack(">HI", 2, 0x1000) + struct.pack(">HBII", 2, 0, 100, 250000)
                          + b"\x01\x02", 0)
    assert sent(h) == [(0x1000, T, b"\x01\x02"), (0x1001, T + TimeInterval(0, 1), b"")]  # emitted after it
    assert h.component.events_sent == 2


def test_events_of_one_instant_are_stamped_in_emission_order():
    """FH-006: events emitted at one simulated instant reach the ground with strictly increasing
    stamps in emission order (1 µs apart), as on hardware where time passes between emissions;
    the next instant's events keep their own time; distinct_times=False keeps the raw stamps."""
    from fprime_lite.testing import ComponentHarness

    h = ComponentHarness(EventManager("events", base_id=0x200))
    later = T + TimeInterval(0, 1000)
    for t in (T, T, T, later, later):
        h.invoke("LogRecv", 0x1000, t, Severity.ACTIVITY_HI, b"")
    assert [e[1].total_us - T.total_us for e in sent(h)] == [0, 1, 2, 1000, 1001]
    raw = ComponentHarness(EventManager("events", base_id=0x200, distinct_times=False))
    for t in (T, T):
        raw.invoke("LogRecv", 0x1000, t, Severity.ACTIVITY_HI, b"")
    assert [e[1] for e in sent(raw)] == [T, T]


def test_default_filters_stop_diagnostic_only(h):
    assert DEFAULT_SEVERITY_FILTER[Severity.DIAGNOSTIC] is False
    for sev in Severity:
        h.invoke("LogRecv", int(sev), T, sev, b"")
    assert [e[0] for e in sent(h)] == [1, 2, 3, 4, 5, 6]
    assert h.component.filtered_by_severity == 1


def test_set_event_filter(h):
    """SET_EVENT_FILTER(level, DISABLED) stops that severity; ENABLED sends it again."""
    h.send_command("SET_EVENT_FILTER", FilterSeverity.ACTIVITY_HI, Enabled.DISABLED)
    h.assert_cmd_response(0, "SET_EVENT_FILTER", CmdResponse.OK)  # sync: answered at once
    h.invoke("LogRecv", 7, T, Severity.ACTIVITY_HI, b"")
    h.invoke("LogRecv", 8, T, Severity.ACTIVITY_LO, b"")
    h.send_command("SET_EVENT_FILTER", FilterSeverity.DIAGNOSTIC, Enabled.ENABLED)
    h.invoke("LogRecv", 9, T, Severity.DIAGNOSTIC, b"")
    assert [e[0] for e in sent(h)] == [8, 9]
    assert not h.component.severity_enabled(Severity.ACTIVITY_HI)


def test_bad_filter_level_is_format_error(h):
    h.send_raw_command(h.component.opcode("SET_EVENT_FILTER"), b"\x09\x00")
    h.assert_cmd_response(0, "SET_EVENT_FILTER", CmdResponse.FORMAT_ERROR)


def test_fatal_passes_every_filter_and_is_announced(h):
    for level in FilterSeverity:
        h.send_command("SET_EVENT_FILTER", level, Enabled.DISABLED)
    h.send_command("SET_ID_FILTER", 0x55, Enabled.ENABLED)
    h.dispatch_all()
    h.clear_history()
    h.invoke("LogRecv", 0x55, T, Severity.FATAL, b"\x00")
    h.invoke("LogRecv", 0x56, T, Severity.WARNING_HI, b"")
    assert [e[0] for e in sent(h)] == [0x55]
    assert h.from_port("FatalAnnounce")[0].args == (0x55,)


def test_id_filter_add_remove_and_errors(h):
    h.send_command("SET_ID_FILTER", 0x300, Enabled.ENABLED, cmd_seq=1)
    h.dispatch_all()
    h.assert_cmd_response(0, "SET_ID_FILTER", CmdResponse.OK, cmd_seq=1)
    h.assert_event("ID_FILTER_ENABLED", 0, 0x300)
    h.invoke("LogRecv", 0x300, T, Severity.WARNING_HI, b"")
    assert h.from_port("PktSend") == []
    assert h.component.filtered_by_id == 1
    h.send_command("SET_ID_FILTER", 0x300, Enabled.DISABLED, cmd_seq=2)
    h.send_command("SET_ID_FILTER", 0x301, Enabled.DISABLED, cmd_seq=3)
    h.dispatch_all()
    h.assert_event("ID_FILTER_REMOVED", 0, 0x300)
    h.assert_event("ID_FILTER_NOT_FOUND", 0, 0x301)
    h.assert_cmd_response(2, "SET_ID_FILTER", CmdResponse.EXECUTION_ERROR, cmd_seq=3)
    h.invoke("LogRecv", 0x300, T, Severity.WARNING_HI, b"")
    assert len(h.from_port("PktSend")) == 1


def test_id_filter_list_full(fprime_harness):
    h = fprime_harness(EventManager("events", queue_size=40))
    for i in range(ID_FILTER_SIZE + 1):
        h.send_command("SET_ID_FILTER", 1000 + i, Enabled.ENABLED)
    h.send_command("SET_ID_FILTER", 1000, Enabled.ENABLED)  # already there: not "full"
    h.dispatch_all()
    h.assert_event("ID_FILTER_LIST_FULL", 0, 1000 + ID_FILTER_SIZE)
    h.assert_cmd_response(ID_FILTER_SIZE, "SET_ID_FILTER", CmdResponse.EXECUTION_ERROR)
    h.assert_cmd_response(ID_FILTER_SIZE + 1, "SET_ID_FILTER", CmdResponse.OK)
    assert len(h.component.filtered_ids) == ID_FILTER_SIZE


def test_dump_filter_state(h):
    h.send_command("SET_EVENT_FILTER", FilterSeverity.COMMAND, Enabled.DISABLED)
    h.send_command("SET_ID_FILTER", 0x20, Enabled.ENABLED)
    h.send_command("SET_ID_FILTER", 0x10, Enabled.ENABLED)
    h.dispatch_all()
    h.clear_history()
    h.send_command("DUMP_FILTER_STATE")
    h.dispatch_all()
    assert h.events_named("SEVERITY_FILTER_STATE") == [
        (FilterSeverity.WARNING_HI, True), (FilterSeverity.WARNING_LO, True),
        (FilterSeverity.COMMAND, False), (FilterSeverity.ACTIVITY_HI, True),
        (FilterSeverity.ACTIVITY_LO, True), (FilterSeverity.DIAGNOSTIC, False)]
    assert h.events_named("ID_FILTER_ENABLED") == [(0x10,), (0x20,)]
    h.assert_cmd_response(0, "DUMP_FILTER_STATE", CmdResponse.OK)
    assert h.text_events[0].text == "(events) SEVERITY_FILTER_STATE: WARNING_HI filter state. True"


@pytest.mark.parametrize("severity, time, args", [
    (99, T, b""),                               # not a severity
    (Severity.WARNING_HI, "not a time", b""),   # unserializable time
    (Severity.WARNING_HI, T, bytes(600)),       # larger than a com buffer
    (Severity.WARNING_HI, T, None),             # not bytes
])
def test_bad_events_are_dropped_and_counted_never_raised(h, severity, time, args):
    h.invoke("LogRecv", 1, time, severity, args)
    assert h.from_port("PktSend") == []
    assert h.component.dropped == 1
    h.invoke("run", 0)
    h.dispatch_all()
    assert h.tlm_values("EventsDropped") == [1]


def test_own_events_loop_through_log_recv():
    """Wired as in a deployment (logOut -> LogRecv), its own events are filtered and sent too."""
    em = EventManager("events", base_id=0x200)
    em.output_port("logOut").connect(0, em.input_port("LogRecv"), 0)
    packets = []
    em.output_port("PktSend").connect_callable(0, lambda data, ctx: packets.append(decode_event(data)), "ground")
    em.input_port("cmdIn").entries[0](em.opcode("SET_ID_FILTER"), 0, struct.pack(">IB", 7, 0))
    em.dispatch_all()
    assert [p[0] for p in packets] == [em.event_id("ID_FILTER_ENABLED")]
    assert packets[0][2] == struct.pack(">I", 7)


def test_ping(h):
    h.invoke("pingIn", 5)
    h.dispatch_all()
    assert h.from_port("pingOut")[0].args == (5,)


def test_constructor_filter_override():
    em = EventManager("events", severity_filter={Severity.DIAGNOSTIC: True, Severity.COMMAND: False})
    assert em.severity_enabled(Severity.DIAGNOSTIC) and not em.severity_enabled(Severity.COMMAND)
    with pytest.raises(ValueError, match="FATAL events cannot be filtered"):
        EventManager("events", severity_filter={Severity.FATAL: False})
