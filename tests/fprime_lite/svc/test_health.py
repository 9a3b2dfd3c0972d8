"""Health: ping cycles, late warning and FATAL thresholds, wrong keys, commands, watchdog."""

import pytest

from fprime_lite import CmdResponse, Severity
from fprime_lite.svc.cmd_dispatcher import CmdDispatcher
from fprime_lite.svc.health import FwEnabled, Health, PingEntry


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(Health("health", [PingEntry("cmdDisp", 2, 4), ("prmDb", 1, 2)], base_id=0x500))


def pings(h, index):
    return [c.args[0] for c in h.port_calls if c.port == "PingSend" and c.index == index]


def test_answered_pings_never_warn(h):
    for _ in range(5):
        h.invoke("Run", 0)
        for i in range(2):
            h.invoke("PingReturn", pings(h, i)[-1], port_num=i)
    assert pings(h, 0) == [0, 2, 4, 6, 8] and pings(h, 1) == [1, 3, 5, 7, 9]
    assert h.events == []
    assert [c.args for c in h.from_port("WdogStroke")] == [(0,), (1,), (0,), (1,), (0,)]


def test_late_ping_warns_then_is_fatal(h):
    for _ in range(6):
        h.invoke("Run", 0)
    # cmdDisp (warn 2, fatal 4): ping on tick 1, warning on tick 3, FATAL on tick 5.
    assert h.events_named("HLTH_PING_WARN") == [("prmDb",), ("cmdDisp",)]
    assert h.events_named("HLTH_PING_LATE") == [("prmDb",), ("cmdDisp",)]
    assert [e.severity for e in h.events if e.name == "HLTH_PING_LATE"] == [Severity.FATAL] * 2
    assert h.tlm_values("PingLateWarnings") == [1, 2]
    assert len(pings(h, 0)) == 1  # no new ping while one is outstanding


def test_wrong_key_is_fatal(h):
    h.invoke("Run", 0)
    h.invoke("PingReturn", 0xBAD, port_num=0)
    h.invoke("Run", 0)
    h.assert_event("HLTH_PING_WRONG_KEY", 0, "cmdDisp", 0xBAD)


def test_commands(h):
    h.send_command("HLTH_CHNG_PING", "cmdDisp", 5, 3)
    h.send_command("HLTH_CHNG_PING", "nobody", 1, 2)
    h.send_command("HLTH_CHNG_PING", "cmdDisp", 3, 9)
    h.send_command("HLTH_PING_ENABLE", "prmDb", FwEnabled.DISABLED)
    h.send_command("HLTH_ENABLE", FwEnabled.DISABLED)
    h.dispatch_all()
    assert [r.response for r in h.cmd_responses] == [
        CmdResponse.VALIDATION_ERROR, CmdResponse.VALIDATION_ERROR, CmdResponse.OK, CmdResponse.OK,
        CmdResponse.OK]
    h.assert_event("HLTH_PING_INVALID_VALUES", 0, "cmdDisp", 5, 3)
    h.assert_event("HLTH_CHECK_LOOKUP_ERROR", 0, "nobody")
    h.assert_event("HLTH_PING_UPDATED", 0, "cmdDisp", 3, 9)
    h.assert_event("HLTH_CHECK_PING", 0, FwEnabled.DISABLED, "prmDb")
    h.assert_event("HLTH_CHECK_ENABLE", 0, FwEnabled.DISABLED)
    assert h.component.entries[0] == PingEntry("cmdDisp", 3, 9)
    h.invoke("Run", 0)
    assert h.from_port("PingSend") == []  # disabled: only the watchdog is stroked
    assert len(h.from_port("WdogStroke")) == 1


def test_pings_a_real_component():
    health = Health("health", [("cmdDisp", 1, 2)])
    disp = CmdDispatcher("cmdDisp")
    health.output_port("PingSend").connect(0, disp.input_port("pingIn"))
    disp.output_port("pingOut").connect(0, health.input_port("PingReturn"), 0)
    events = []
    health.output_port("logOut").connect_callable(0, lambda *a: events.append(a), "events")
    for _ in range(4):
        health.input_port("Run").entries[0](0)
        disp.dispatch_all()
    assert events == []


def test_bad_thresholds():
    with pytest.raises(ValueError, match="needs 0 < warn_cycles <= fatal_cycles"):
        Health("health", [("x", 3, 2)])
