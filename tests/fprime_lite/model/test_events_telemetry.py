"""Events (severities, arguments, throttling, text form) and telemetry (update policies, time)."""

import pytest

from fprime_lite import (F64, I32, U32, Channel, Event, FwEnum, PassiveComponent, Severity, String,
                         Time, TimeBase)
from fprime_lite.model.errors import SerializationError
from fprime_lite.model.events import translate_format
from fprime_lite.model.types import U8


class Color(FwEnum, namespace="Test", rep=U8):
    RED = 0
    GREEN = 1


class Emitter(PassiveComponent):
    Started = Event(Severity.ACTIVITY_LO, "Started at {.2f} deg/s", w=F64, throttle=2)
    Mixed = Event(Severity.WARNING_HI, "n={d} hex={x} c={} s={} {{literal}}", n=I32, h=U32, c=Color, s=String(20))
    Plain = Event(Severity.DIAGNOSTIC, "plain")
    Count = Channel(U32)
    Level = Channel(F64, update="on change")


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(Emitter("emit", base_id=0x300), test_time=Time(TimeBase.TB_WORKSTATION_TIME, 0, 5, 250))


def test_severity_values_match_fprime():
    assert [(s.name, int(s)) for s in Severity] == [
        ("FATAL", 1), ("WARNING_HI", 2), ("WARNING_LO", 3), ("COMMAND", 4), ("ACTIVITY_HI", 5),
        ("ACTIVITY_LO", 6), ("DIAGNOSTIC", 7)]


def test_event_carries_id_time_severity_and_typed_args(h):
    h.component.Mixed(-3, 255, Color.GREEN, "hello")
    e = h.events[0]
    assert (e.name, e.id, e.severity, e.args) == ("Mixed", 0x301, Severity.WARNING_HI, (-3, 255, Color.GREEN, "hello"))
    assert e.time == Time(TimeBase.TB_WORKSTATION_TIME, 0, 5, 250)
    assert h.text_events[0].text == "(emit) Mixed: n=-3 hex=ff c=GREEN s=hello {literal}"


def test_throttle_suppresses_after_n_until_cleared(h):
    emitted = [h.component.Started(float(i)) for i in range(4)]
    assert emitted == [True, True, False, False]
    assert h.component.Started.throttled
    h.assert_event_count("Started", 2)
    h.component.Started.clear_throttle()
    h.component.Started(9.0)
    h.assert_event_count("Started", 3)
    h.assert_event("Started", 2, 9.0)
    assert h.text_events[-1].text == "(emit) Started: Started at 9.00 deg/s"


def test_event_argument_errors(h):
    with pytest.raises(TypeError, match=r"emit\.Started takes 1 argument\(s\) \(w\), got 2"):
        h.component.Started(1.0, 2.0)
    with pytest.raises(ValueError, match="string of 21 bytes exceeds its bound of 20"):
        h.component.Mixed(1, 2, Color.RED, "x" * 21)
    h.assert_events_size(0)


def test_a_bad_argument_raises_without_using_up_the_throttle_and_a_throttled_call_returns_early(h):
    with pytest.raises(SerializationError):
        h.component.Started("fast")
    assert h.component.Started.count == 0  # the failed call was not counted
    assert h.component.Started(1.0) and h.component.Started(2.0)
    # Throttled, as in F´: nothing more is done with the call, arguments included.
    assert h.component.Started("not even a number") is False
    h.assert_event_count("Started", 2)


def test_unconnected_event_ports_emit_nothing_but_still_throttle():
    e = Emitter("lonely")
    assert e.Started(1.0) and e.Started(1.0) and not e.Started(1.0)


def test_translate_format_variants():
    assert translate_format("{e} {g} {.3e} {o} {c}", [F64, F64, F64, U32, U32], "x") == "{:e} {:g} {:.3e} {:o} {:c}"


def test_always_channel_sends_every_write_with_time(h):
    h.component.Count.write(1)
    h.advance_time(1)
    h.component.Count.write(1)
    assert h.tlm_values("Count") == [1, 1]
    assert [t.time for t in h.tlm_named("Count")] == [
        Time(TimeBase.TB_WORKSTATION_TIME, 0, 5, 250), Time(TimeBase.TB_WORKSTATION_TIME, 0, 6, 250)]
    assert h.telemetry[0].id == 0x300


def test_on_change_channel_sends_first_write_then_changes_only(h):
    for v in (2.0, 2.0, 3.0, 3.0, 2.0):
        h.component.Level.write(v)
    assert h.tlm_values("Level") == [2.0, 3.0, 2.0]


def test_channel_rejects_values_of_the_wrong_type(h):
    with pytest.raises(ValueError, match=r"U32 value -1 is out of range"):
        h.component.Count.write(-1)


def test_unconnected_channel_keeps_last_value():
    e = Emitter("lonely")
    e.Level.write(4.0)
    assert e.Level.last == 4.0


def test_explicit_time_overrides_the_clock(h):
    t = Time(TimeBase.TB_WORKSTATION_TIME, 0, 99, 0)
    h.component.Count.write(3, time=t)
    assert h.tlm_named("Count")[0].time == t
