"""CmdDispatcher: registration, dispatch, sequence tracking, its own commands, error paths."""

import struct

import pytest

from fprime_lite import CmdResponse, FwAssertionError, Severity, Time, TimeBase
from fprime_lite.model.fw_ports import CmdResponsePort
from fprime_lite.wire.packets import encode_command
from fprime_lite.svc.cmd_dispatcher import (COMMAND_PORTS, SEQUENCE_PORTS, CmdDispatcher,
                                            DeserialStatus)

BASE = 0x100
T0 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 50, 0)


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(CmdDispatcher("cmdDisp", base_id=BASE), test_time=T0)


def dispatched(h):
    return [c for c in h.port_calls if c.port == "compCmdSend"]


def statuses(h):
    return [(c.index, c.args) for c in h.port_calls if c.port == "seqCmdStatus"]


def test_ports_are_the_topology_contract():
    """The topology loader wires these names; sizes as specified."""
    c = CmdDispatcher("cmdDisp")
    assert set(c.input_ports) >= {"compCmdReg", "compCmdStat", "seqCmdBuff", "pingIn", "cmdIn"}
    assert set(c.output_ports) >= {"compCmdSend", "seqCmdStatus", "pingOut", "cmdRegOut",
                                   "cmdResponseOut", "logOut", "tlmOut"}
    assert len(c.input_port("compCmdReg")) == COMMAND_PORTS == len(c.output_port("compCmdSend"))
    assert len(c.input_port("seqCmdBuff")) == SEQUENCE_PORTS == len(c.output_port("seqCmdStatus"))
    assert c.input_port("seqCmdBuff").decl.kind == "async"
    assert c.input_port("compCmdStat").decl.kind == "async"


def test_f_prime_ids_and_severities():
    """CD-003: F´'s opcodes, event ids/severities/argument counts and channel ids."""
    c = CmdDispatcher("cmdDisp", base_id=BASE)
    assert [(x.name, x.opcode) for x in c.spec.commands] == [
        ("CMD_NO_OP", 0), ("CMD_NO_OP_STRING", 1), ("CMD_TEST_CMD_1", 2), ("CMD_CLEAR_TRACKING", 3)]
    events = {e.name: (e.local_id, e.severity, len(e.args)) for e in c.spec.events}
    assert events["OpCodeDispatched"] == (1, Severity.COMMAND, 2)  # the GDS test API matches 2 args
    assert events["OpCodeCompleted"] == (2, Severity.COMMAND, 1)   # ... and 1 arg
    assert events["OpCodeRegistered"] == (0, Severity.DIAGNOSTIC, 3)
    assert events["OpCodeError"] == (3, Severity.COMMAND, 2)
    assert events["MalformedCommand"] == (4, Severity.WARNING_HI, 1)
    assert events["InvalidCommand"] == (5, Severity.WARNING_HI, 1)
    assert events["TooManyCommands"] == (6, Severity.WARNING_HI, 1)
    assert events["NoOpReceived"] == (7, Severity.ACTIVITY_HI, 0)
    assert events["NoOpStringReceived"] == (8, Severity.ACTIVITY_HI, 1)
    assert events["TestCmd1Args"] == (9, Severity.ACTIVITY_HI, 3)
    assert events["OpCodeReregistered"] == (10, Severity.DIAGNOSTIC, 2)
    assert c.channel_id("CommandsDispatched") == BASE and c.channel_id("CommandErrors") == BASE + 1


def test_registration_reregistration_and_conflict(h):
    """CD-001: registering on index i maps the opcode to compCmdSend[i]."""
    h.invoke("compCmdReg", 0x2000, port_num=3)
    h.invoke("compCmdReg", 0x2001, port_num=3)
    h.invoke("compCmdReg", 0x2000, port_num=3)
    h.assert_event("OpCodeRegistered", 0, 0x2000, 3, 0)
    h.assert_event("OpCodeRegistered", 1, 0x2001, 3, 1)
    h.assert_event("OpCodeReregistered", 0, 0x2000, 3)
    assert h.component.dispatch_table == {0x2000: 3, 0x2001: 3}
    with pytest.raises(FwAssertionError, match=r"opcode 0x2000 is already registered on compCmdReg\[3\]"):
        h.invoke("compCmdReg", 0x2000, port_num=4)


def test_dispatch_track_and_answer_with_context(h):
    """CD-001/CD-002: dispatch with a fresh sequence number; the answer carries the source context."""
    h.invoke("compCmdReg", 0x2000, port_num=7)
    h.clear_history()
    h.invoke("seqCmdBuff", encode_command(0x2000, b"\x01\x02"), 0xCAFE, port_num=2)
    h.invoke("seqCmdBuff", encode_command(0x2000), 0xBEEF, port_num=5)
    assert h.dispatch_all() == 2
    assert [(c.index, c.args) for c in dispatched(h)] == [(7, (0x2000, 0, b"\x01\x02")), (7, (0x2000, 1, b""))]
    h.assert_event("OpCodeDispatched", 0, 0x2000, 7)
    assert h.tlm_values("CommandsDispatched") == [1, 2]
    assert h.component.pending == {0: (0x2000, 0xCAFE, 2), 1: (0x2000, 0xBEEF, 5)}
    # Answers in the other order.
    h.invoke("compCmdStat", 0x2000, 1, CmdResponse.EXECUTION_ERROR)
    h.invoke("compCmdStat", 0x2000, 0, CmdResponse.OK)
    h.dispatch_all()
    assert statuses(h) == [(5, (0x2000, 0xBEEF, CmdResponse.EXECUTION_ERROR)),
                           (2, (0x2000, 0xCAFE, CmdResponse.OK))]
    h.assert_event("OpCodeError", 0, 0x2000, CmdResponse.EXECUTION_ERROR)
    h.assert_event("OpCodeCompleted", 0, 0x2000)
    assert h.tlm_values("CommandErrors") == [1]
    assert h.component.pending == {}


def test_unknown_opcode_answers_invalid_opcode(h):
    """An unregistered opcode: InvalidCommand, INVALID_OPCODE back to the source, an error counted."""
    h.invoke("seqCmdBuff", encode_command(0x9999), 4, port_num=1)
    h.dispatch_all()
    h.assert_event("InvalidCommand", 0, 0x9999)
    assert h.events[-1].severity == Severity.WARNING_HI
    assert statuses(h) == [(1, (0x9999, 4, CmdResponse.INVALID_OPCODE))]
    assert h.tlm_values("CommandErrors") == [1]
    assert dispatched(h) == []


def test_registered_but_unconnected_port_is_invalid(fprime_harness):
    """F´ dispatches only through a connected compCmdSend index."""
    h = fprime_harness(CmdDispatcher("cmdDisp", base_id=BASE))
    h.invoke("compCmdReg", 0x2000, port_num=9)
    h.component.output_port("compCmdSend").disconnect(9)
    h.invoke("seqCmdBuff", encode_command(0x2000), 0, port_num=0)
    h.dispatch_all()
    h.assert_event("InvalidCommand", 0, 0x2000)


@pytest.mark.parametrize("packet, status, opcode", [
    (b"", DeserialStatus.BUFFER_EMPTY, 0),
    (b"\x00", DeserialStatus.BUFFER_EMPTY, 0),
    (b"\x00\x00\x00\x01", DeserialStatus.BUFFER_EMPTY, 0),
    (struct.pack(">HI", 2, 0x2000), DeserialStatus.TYPE_MISMATCH, 0),
    (encode_command(0x2000, bytes(600)), DeserialStatus.SIZE_MISMATCH, 0x2000),
    (None, DeserialStatus.FORMAT_ERROR, 0),
])
def test_malformed_packets_never_raise(h, packet, status, opcode):
    """A malformed packet: MalformedCommand(status) and VALIDATION_ERROR to the source."""
    h.invoke("compCmdReg", 0x2000, port_num=0)
    h.clear_history()
    h.invoke("seqCmdBuff", packet, 77, port_num=3)
    h.dispatch_all()
    h.assert_event("MalformedCommand", 0, status)
    assert statuses(h) == [(3, (opcode, 77, CmdResponse.VALIDATION_ERROR))]
    assert dispatched(h) == []


def test_too_many_commands(fprime_harness):
    """A full tracking table: TooManyCommands and EXECUTION_ERROR; nothing dispatched."""
    h = fprime_harness(CmdDispatcher("cmdDisp", base_id=BASE, tracking_size=2))
    h.invoke("compCmdReg", 0x2000, port_num=0)
    for ctx in range(3):
        h.invoke("seqCmdBuff", encode_command(0x2000), ctx, port_num=0)
    h.dispatch_all()
    assert len(dispatched(h)) == 2
    h.assert_event("TooManyCommands", 0, 0x2000)
    assert statuses(h) == [(0, (0x2000, 2, CmdResponse.EXECUTION_ERROR))]
    # CMD_CLEAR_TRACKING frees the table; a late answer then reaches no source.
    h.send_command("CMD_CLEAR_TRACKING", cmd_seq=9)
    h.dispatch_all()
    h.assert_cmd_response(0, "CMD_CLEAR_TRACKING", CmdResponse.OK, cmd_seq=9)
    assert h.component.pending == {}
    h.invoke("compCmdStat", 0x2000, 0, CmdResponse.OK)
    h.dispatch_all()
    assert len(statuses(h)) == 1
    h.assert_event("OpCodeCompleted", 0, 0x2000)


def test_untracked_when_source_has_no_status_port(h):
    """F´ tracks only commands whose source can be answered."""
    h.invoke("compCmdReg", 0x2000, port_num=0)
    h.component.output_port("seqCmdStatus").disconnect(6)
    h.invoke("seqCmdBuff", encode_command(0x2000), 1, port_num=6)
    h.dispatch_all()
    assert len(dispatched(h)) == 1 and h.component.pending == {}


def test_target_that_raises_is_answered_execution_error(h):
    """A faulty target cannot take the dispatcher down."""
    h.invoke("compCmdReg", 0x2000, port_num=2)

    def boom(*args):
        raise RuntimeError("target fault")

    h.set_port_handler("compCmdSend", boom, index=2)
    h.invoke("seqCmdBuff", encode_command(0x2000), 5, port_num=0)
    h.dispatch_all()
    assert statuses(h) == [(0, (0x2000, 5, CmdResponse.EXECUTION_ERROR))]
    h.assert_event("OpCodeError", 0, 0x2000, CmdResponse.EXECUTION_ERROR)
    assert h.component.pending == {}


def test_queue_overflow_drops_and_counts(fprime_harness):
    """F´ v4 hook: a full queue drops the packet with CommandDroppedQueueOverflow (throttled 5)."""
    h = fprime_harness(CmdDispatcher("cmdDisp", base_id=BASE, queue_size=1))
    h.invoke("seqCmdBuff", encode_command(0x2000), 0, port_num=0)
    for ctx in range(1, 8):
        h.invoke("seqCmdBuff", encode_command(0x2000 + ctx), ctx, port_num=0)
    h.assert_event_count("CommandDroppedQueueOverflow", 5)
    h.assert_event("CommandDroppedQueueOverflow", 0, 0x2001, 1)
    assert h.component.commands_dropped == 7
    assert h.tlm_values("CommandsDropped")[-1] == 7


def test_own_commands(h):
    """CD-005: CMD_NO_OP, CMD_NO_OP_STRING and CMD_TEST_CMD_1 echo with F´'s events."""
    h.send_command("CMD_NO_OP", cmd_seq=1)
    h.send_command("CMD_NO_OP_STRING", "hello", cmd_seq=2)
    h.send_command("CMD_TEST_CMD_1", -5, 1.5, 200, cmd_seq=3)
    assert h.cmd_responses == []  # async: nothing until dispatched
    h.dispatch_all()
    h.assert_event("NoOpReceived", 0)
    h.assert_event("NoOpStringReceived", 0, "hello")
    h.assert_event("TestCmd1Args", 0, -5, 1.5, 200)
    assert [r.response for r in h.cmd_responses] == [CmdResponse.OK] * 3
    assert h.text_events[0].text == "(cmdDisp) NoOpReceived: Received a NO-OP command"
    assert h.text_events[2].text == "(cmdDisp) TestCmd1Args: TEST_CMD_1 args: I32: -5, F32: 1.500000, U8: 200"


def test_own_command_format_error(h):
    """Undeserializable arguments answer FORMAT_ERROR before the handler runs."""
    h.send_raw_command(h.component.opcode("CMD_NO_OP_STRING"), b"\x00\x50abc", cmd_seq=4)
    h.dispatch_all()
    h.assert_cmd_response(0, "CMD_NO_OP_STRING", CmdResponse.FORMAT_ERROR, cmd_seq=4)
    h.assert_no_event("NoOpStringReceived")


def test_run_and_ping(h):
    h.invoke("run", 0)
    h.invoke("pingIn", 0x1234)
    h.dispatch_all()
    assert h.from_port("pingOut")[0].args == (0x1234,)
    assert h.tlm_values("CommandsDispatched") == [0]
    assert h.tlm_values("CommandErrors") == [0]


def test_self_registration_and_self_dispatch_end_to_end():
    """CD-005 through the real ports: cmdRegOut -> compCmdReg[k], compCmdSend[k] -> cmdIn,
    cmdResponseOut -> compCmdStat, as F´'s CdhCore wires cmdDisp to itself."""
    disp = CmdDispatcher("cmdDisp", base_id=BASE)
    k = 5
    disp.output_port("cmdRegOut").connect(0, disp.input_port("compCmdReg"), k)
    disp.output_port("compCmdSend").connect(k, disp.input_port("cmdIn"), 0)
    disp.output_port("cmdResponseOut").connect(0, disp.input_port("compCmdStat"), 0)
    events, answers = [], []
    disp.output_port("logOut").connect_callable(0, lambda i, t, s, a: events.append(i - BASE), "events")
    disp.output_port("seqCmdStatus").connect_callable(0, lambda *a: answers.append(a), "ground")
    disp.register_commands()
    assert disp.dispatch_table == {BASE + op: k for op in range(4)}
    assert events == [0, 0, 0, 0]  # OpCodeRegistered x4
    events.clear()
    disp.input_port("seqCmdBuff").entries[0](encode_command(BASE), 42)
    disp.dispatch_all()
    # OpCodeDispatched, NoOpReceived, OpCodeCompleted — the order the GDS test API waits for.
    assert events == [1, 7, 2]
    assert answers == [(BASE, 42, CmdResponse.OK)]


def test_threaded_dispatch_round_trip():
    """With a real thread the same round trip completes (no sleeps: waits on the answer)."""
    import queue as _q

    disp = CmdDispatcher("cmdDisp", base_id=BASE)
    disp.output_port("cmdRegOut").connect(0, disp.input_port("compCmdReg"), 0)
    disp.output_port("compCmdSend").connect(0, disp.input_port("cmdIn"), 0)
    disp.output_port("cmdResponseOut").connect(0, disp.input_port("compCmdStat"), 0)
    answers = _q.Queue()
    disp.output_port("seqCmdStatus").connect_callable(0, lambda *a: answers.put(a), "ground")
    disp.register_commands()
    disp.start()
    try:
        disp.input_port("seqCmdBuff").entries[0](encode_command(BASE + 1, b"\x00\x02hi"), 3)
        assert answers.get(timeout=5) == (BASE + 1, 3, CmdResponse.OK)
    finally:
        disp.exit()


def test_response_port_type_is_fw_cmd_response():
    assert CmdDispatcher("c").output_port("seqCmdStatus").port_type is CmdResponsePort
