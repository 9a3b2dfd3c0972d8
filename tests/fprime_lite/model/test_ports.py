"""Ports: connect-time type checking, port arrays, unconnected calls, guarded calls."""

import pytest

from fprime_lite import (F64, I8, U32, OutputPort, PassiveComponent, PortConnectionError, PortType,
                         Sched, UnconnectedPortError, guarded_input, sync_input)

Start = PortType("Test.Start", returns=bool, level=I8)
Stop = PortType("Test.Stop", returns=bool)
Value = PortType("Test.Value", value=F64)


class Driver(PassiveComponent):
    def __init__(self, name):
        super().__init__(name)
        self.levels = []

    @sync_input(Start)
    def start(self, level):
        self.levels.append(level)
        return True

    @sync_input(Stop)
    def stop(self):
        return False

    @sync_input(Value, size=3)
    def values(self, port_num, value):
        self.levels.append((port_num, value))

    @guarded_input(Value)
    def guarded(self, value):
        assert self._lock._is_owned()
        self.levels.append(("guarded", value))


class Manager(PassiveComponent):
    startOut = OutputPort(Start)
    stopOut = OutputPort(Stop)
    valueOut = OutputPort(Value, size=2)


def test_call_through_connected_output_reaches_handler_and_returns():
    m, d = Manager("m"), Driver("d")
    m.output_port("startOut").connect(0, d.input_port("start"))
    assert m.startOut[0](5) is True
    assert d.levels == [5]


def test_sync_single_port_binds_the_bound_method_itself():
    """The hot path: a connected output slot holds the target's handler, with no wrapper."""
    m, d = Manager("m"), Driver("d")
    m.output_port("startOut").connect(0, d.input_port("start"))
    assert m.startOut[0] == d.start
    # An exact list (not a subclass) keeps CPython's specialised list[int] indexing.
    assert type(m.startOut) is list
    assert m.startOut is m.output_port("startOut").calls


def test_component_is_connected_checks_by_port_name():
    m, d = Manager("m"), Driver("d")
    assert not m.is_connected("valueOut", 1)
    m.output_port("valueOut").connect(1, d.input_port("values"))
    assert m.is_connected("valueOut", 1) and not m.is_connected("valueOut", 0)
    with pytest.raises(KeyError, match="no output port 'nope'"):
        m.is_connected("nope")


def test_type_mismatch_names_both_ends_and_both_types():
    m, d = Manager("m"), Driver("d")
    with pytest.raises(PortConnectionError,
                       match=r"cannot connect m\.startOut\[0\] \(Test\.Start\) to d\.stop\[0\] \(Test\.Stop\): "
                             r"port types differ"):
        m.output_port("startOut").connect(0, d.input_port("stop"))
    assert not m.is_connected("startOut", 0)


def test_output_index_connects_once():
    m, d = Manager("m"), Driver("d")
    m.output_port("startOut").connect(0, d.input_port("start"))
    with pytest.raises(PortConnectionError, match=r"already connected to d\.start\[0\]"):
        m.output_port("startOut").connect(0, d.input_port("start"))


def test_inputs_accept_many_outputs():
    m1, m2, d = Manager("m1"), Manager("m2"), Driver("d")
    m1.output_port("startOut").connect(0, d.input_port("start"))
    m2.output_port("startOut").connect(0, d.input_port("start"))
    m1.startOut[0](1)
    m2.startOut[0](2)
    assert d.levels == [1, 2]


def test_index_out_of_range_is_a_connection_error():
    m, d = Manager("m"), Driver("d")
    with pytest.raises(PortConnectionError, match=r"m\.valueOut has indices 0\.\.1; index 2 does not exist"):
        m.output_port("valueOut").connect(2, d.input_port("values"))
    with pytest.raises(PortConnectionError, match=r"values has indices 0\.\.2"):
        m.output_port("valueOut").connect(0, d.input_port("values"), 3)


def test_port_array_handler_receives_input_port_number():
    m, d = Manager("m"), Driver("d")
    m.output_port("valueOut").connect(0, d.input_port("values"), 2)
    m.output_port("valueOut").connect(1, d.input_port("values"), 0)
    m.valueOut[0](1.5)
    m.valueOut[1](2.5)
    assert d.levels == [(2, 1.5), (0, 2.5)]


def test_unconnected_output_raises_and_is_connected_says_so():
    m = Manager("m")
    assert not m.is_connected("startOut", 0)
    with pytest.raises(UnconnectedPortError, match=r"output port m\.startOut\[0\] is not connected"):
        m.startOut[0](3)


def test_disconnect_restores_the_unconnected_state():
    m, d = Manager("m"), Driver("d")
    m.output_port("stopOut").connect(0, d.input_port("stop"))
    m.output_port("stopOut").disconnect(0)
    assert not m.is_connected("stopOut", 0)
    with pytest.raises(UnconnectedPortError):
        m.stopOut[0]()


def test_guarded_input_runs_under_the_component_lock():
    m, d = Manager("m"), Driver("d")
    m.output_port("valueOut").connect(0, d.input_port("guarded"))
    m.valueOut[0](4.0)
    assert d.levels == [("guarded", 4.0)]


def test_unknown_port_names_list_the_ports():
    d = Driver("d")
    with pytest.raises(KeyError, match=r"no input port 'strat'.*start"):
        d.input_port("strat")
    with pytest.raises(KeyError, match=r"no output port 'x'"):
        Manager("m").output_port("x")


def test_connecting_to_something_that_is_not_an_input_port():
    m = Manager("m")
    with pytest.raises(PortConnectionError, match="not an input port"):
        m.output_port("startOut").connect(0, Manager("n").stopOut)


def test_target_name_describes_the_connection():
    m, d = Manager("m"), Driver("d")
    m.output_port("startOut").connect(0, d.input_port("start"))
    assert m.output_port("startOut").target_name(0) == "d.start[0]"
    assert Sched.name == "Svc.Sched" and Sched.arg_names == ["context"]
    assert "U32" in repr(PortType("X.Y", a=U32))
