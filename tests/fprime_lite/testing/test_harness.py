"""The harness itself: histories, stubs, assertion messages, F´ spellings, the pytest fixture."""

import pytest

from fprime_lite import (F64, I8, U32, Channel, CmdResponse, Event, FwAssertionError, OutputPort, Param,
                         ParamValid, PassiveComponent, PortType, Sched, Severity, Time, TimeBase, sync_command,
                         sync_input)
from fprime_lite.testing import ComponentHarness, PortCall

Start = PortType("Test.Start", returns=bool, level=I8)
Read = PortType("Test.Read", returns=F64)
Note = PortType("Test.Note", value=U32)


class Device(PassiveComponent):
    startOut = OutputPort(Start, size=2)
    readOut = OutputPort(Read)
    noteOut = OutputPort(Note)
    Value = Channel(F64)
    Read = Event(Severity.ACTIVITY_HI, "read {f}", v=F64)

    @sync_input(Sched)
    def run(self, context):
        v = self.readOut[0]()
        self.Value.write(v)
        self.Read(v)
        ok = self.startOut[0](1) and self.startOut[1](-1)
        self.noteOut[0](context)
        return ok


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(Device("dev"))


def test_every_output_call_is_recorded_in_order(h):
    h.set_port_return("readOut", 2.5)
    h.set_port_return("startOut", True)
    assert h.invoke_to_run(0, 7) is True
    assert h.port_calls == [PortCall("readOut", 0, ()), PortCall("startOut", 0, (1,)),
                            PortCall("startOut", 1, (-1,)), PortCall("noteOut", 0, (7,))]
    h.assert_from_port_size("startOut", 2)
    h.assert_from_port("startOut", 1, -1)
    h.assert_from_port_history_size(4)


def test_per_index_handler_overrides_the_port_handler(h):
    h.set_port_return("readOut", 1.0)
    h.set_port_return("startOut", True)
    h.set_port_return("startOut", False, index=1)
    assert h.invoke("run", 0) is False


def test_unstubbed_returning_port_explains_what_to_do(h):
    with pytest.raises(FwAssertionError, match=r"readOut\[0\] returns a value and no stub was given; "
                                               r"call set_port_return\('readOut', value\)"):
        h.invoke("run", 0)


def test_failure_messages_show_the_history(h):
    h.set_port_return("readOut", 2.5)
    h.set_port_return("startOut", True)
    h.invoke("run", 0)
    with pytest.raises(AssertionError, match=r"(?s)expected Read\[0\] with args \(3\.0,\).*ACTIVITY_HI Read\(2\.5,\)"):
        h.assert_event("Read", 0, 3.0)
    with pytest.raises(AssertionError, match=r"(?s)expected 3 call\(s\) out of startOut, got 2.*noteOut"):
        h.assert_from_port_size("startOut", 3)
    with pytest.raises(AssertionError, match=r"(?s)expected Value\[0\] == 1\.0.*Value = 2\.5"):
        h.assert_tlm("Value", 0, 1.0)
    with pytest.raises(AssertionError, match=r"expected 1 command response\(s\), got 0:\n  \(empty\)"):
        h.assert_cmd_response_size(1)


def test_approx_works_in_asserts(h):
    h.set_port_return("readOut", 0.1 + 0.2)
    h.set_port_return("startOut", True)
    h.invoke("run", 0)
    h.assert_tlm("Value", 0, pytest.approx(0.3))
    h.assert_event("Read", 0, pytest.approx(0.3))


def test_clear_history_forgets_records_but_keeps_stubs(h):
    h.set_port_return("readOut", 1.0)
    h.set_port_return("startOut", True)
    h.invoke("run", 0)
    h.clearHistory()
    assert (h.port_calls, h.events, h.telemetry, h.text_events) == ([], [], [], [])
    h.invoke("run", 0)
    h.assert_tlm_size(1)
    h.assert_events_size(1)


def test_test_time_stamps_everything(h):
    h.set_port_return("readOut", 1.0)
    h.set_port_return("startOut", True)
    h.setTestTime(Time(TimeBase.TB_PROC_TIME, 1, 10, 5))
    h.invoke("run", 0)
    assert h.advance_time(0, 999_999) == Time(TimeBase.TB_PROC_TIME, 1, 11, 4)
    h.invoke("run", 0)
    assert [t.time.useconds for t in h.tlm_named("Value")] == [5, 4]


def test_unknown_member_names_raise(h):
    with pytest.raises(KeyError, match="no event 'Nope'"):
        h.events_named("Nope")
    with pytest.raises(KeyError, match="no channel 'Nope'"):
        h.tlm_values("Nope")
    with pytest.raises(AttributeError, match="no attribute 'frobnicate'"):
        h.frobnicate()


def test_harness_works_without_the_fixture():
    h = ComponentHarness(Device("dev2"))
    h.set_port_handler("readOut", lambda: 4.0)
    h.set_port_handler("startOut", lambda level: level > 0)
    assert h.invoke("run", 1) is False
    assert h.test_time == Time(TimeBase.TB_NONE, 0, 0, 0)


def test_optional_outputs_can_be_left_unconnected():
    h = ComponentHarness(Device("dev3"), unconnected=("noteOut",))
    h.set_port_return("readOut", 1.0)
    h.set_port_return("startOut", True)
    assert not h.component.is_connected("noteOut")
    with pytest.raises(Exception, match=r"output port dev3\.noteOut\[0\] is not connected"):
        h.invoke("run", 3)
    with pytest.raises(KeyError, match="no output port 'nope'"):
        ComponentHarness(Device("dev4"), unconnected=("nope",))


class Counter(PassiveComponent):
    """A component with one of each member, to drive through F´'s tester names."""

    LIMIT = Param(U32, default=3)
    Counted = Event(Severity.ACTIVITY_LO, "count {} of {}", n=U32, limit=U32)
    Count = Channel(U32)

    def __init__(self, name, **kw):
        super().__init__(name, **kw)
        self.n = 0

    @sync_input(Sched)
    def run(self, context):
        self.n += context
        self.Count.write(self.n)
        self.Counted(self.n, self.LIMIT.value)

    @sync_command()
    def RESET(self, start: U32):
        self.n = start


def test_fprime_tester_names_take_fprime_arguments(fprime_harness):
    """FH-004: TesterBase/GTestBase spellings take F´'s arguments: invoke_to_<port>(portNum, args),
    sendCmd_<CMD>(instance, cmdSeq, args), paramSend_/paramSave_(instance, cmdSeq),
    assertEvents_<E>_size(size), assertEvents_<E>(index, args), assertTlm_<C>_size(size),
    assertTlm_<C>(index, value), assertCmdResponse(index, opCode, cmdSeq, response)."""
    h = fprime_harness(Counter("counter", base_id=0x100))
    h.load_parameters()
    h.invoke_to_run(0, 2)
    h.invoke_to_run(0, 3)
    h.assertEvents_size(2)
    h.assertEvents_Counted_size(2)
    h.assertEvents_Counted(1, 5, 3)
    h.assertTlm_size(2)
    h.assertTlm_Count_size(2)
    h.assertTlm_Count(0, 2)
    h.assertFromPortHistory_size(0)
    h.sendCmd_RESET(0, 7, 10)
    h.assertCmdResponse_size(1)
    h.assertCmdResponse(0, h.component.opcode("RESET"), 7, CmdResponse.OK)
    assert h.component.n == 10
    h.paramSet_LIMIT(9, ParamValid.VALID)
    h.paramSend_LIMIT(0, 8)
    h.assertCmdResponse(1, h.component.opcode("LIMIT_PRM_SET"), 8, CmdResponse.OK)
    assert h.component.LIMIT.value == 9
    with pytest.raises(AssertionError):
        h.assertCmdResponse(0, h.component.opcode("RESET"), 6, CmdResponse.OK)  # wrong cmdSeq
    with pytest.raises(AssertionError):
        h.assertEvents_Counted(0, 5, 3)
    with pytest.raises(AttributeError, match="no event 'Nope"):
        h.assertEvents_Nope_size(1)
    with pytest.raises(FwAssertionError, match="port_num 1 is out of range"):
        h.invoke_to_run(1, 2)
