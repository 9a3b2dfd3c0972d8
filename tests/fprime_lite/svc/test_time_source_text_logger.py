"""TimeSource (the deployment's clock behind every time-get port) and TextLogger."""

import io

import pytest

from fprime_lite import Event, PassiveComponent, Severity, SimulatedClock, Time, TimeBase, U32
from fprime_lite.svc.text_logger import TextLogger, format_text_event
from fprime_lite.svc.time_source import TimeSource


class Talker(PassiveComponent):
    Said = Event(Severity.ACTIVITY_HI, "Said {}", n=U32)


def test_time_source_returns_clock_now(fprime_harness):
    clock = SimulatedClock(TimeBase.TB_PROC_TIME, context=3, start_us=5_000_001)
    h = fprime_harness(TimeSource("time", clock))
    assert h.invoke("timeGetPort") == Time(TimeBase.TB_PROC_TIME, 3, 5, 1)
    clock.advance_us(999_999)
    assert h.invoke("timeGetPort") == Time(TimeBase.TB_PROC_TIME, 3, 6, 0)


def test_time_source_stamps_events():
    clock = SimulatedClock(start_us=2_500_000)
    time = TimeSource("time", clock)
    talker = Talker("talker", base_id=0x40)
    talker.output_port("timeCaller").connect(0, time.input_port("timeGetPort"))
    got = []
    talker.output_port("logOut").connect_callable(0, lambda i, t, s, a: got.append(t), "rec")
    talker.Said(1)
    assert got == [Time(TimeBase.TB_WORKSTATION_TIME, 0, 2, 500000)]


def test_time_source_needs_a_clock():
    with pytest.raises(TypeError, match="clock must be a fprime_lite.model.time.Clock"):
        TimeSource("time", object())


def test_text_logger_lines_in_f_prime_format():
    out = io.StringIO()
    logger = TextLogger("textLogger", out)
    talker = Talker("talker", base_id=0x40)
    talker.output_port("logTextOut").connect(0, logger.input_port("TextLogger"))
    talker.Said(7)
    assert out.getvalue() == "EVENT: (64) (0:0,0) ACTIVITY_HI: (talker) Said: Said 7\n"
    assert logger.lines_written == 1


def test_text_logger_defaults_to_stdout(capsys):
    logger = TextLogger("textLogger")
    logger.input_port("TextLogger").entries[0](5, Time(TimeBase.TB_WORKSTATION_TIME, 0, 1, 2),
                                               Severity.WARNING_HI, "hot")
    assert capsys.readouterr().out == "EVENT: (5) (2:1,2) WARNING_HI: hot\n"


def test_text_logger_never_raises():
    class Broken(io.StringIO):
        def write(self, s):
            raise OSError("disk gone")

    logger = TextLogger("textLogger", Broken())
    logger.input_port("TextLogger").entries[0](5, Time(), 99, "x")
    assert logger.lines_written == 0
    assert format_text_event(1, Time(), 99, "t") == "EVENT: (1) (0:0,0) SEVERITY_99: t"
