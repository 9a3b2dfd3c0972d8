"""AttitudeController's cycle telemetry written by ``tlmRun`` (issue 32, ctltlm): once its ``tlmRun`` port has run,
the 10 Hz cycles keep their telemetry and ``tlmRun`` (scheduled just before TlmChan's ``Run``) writes each channel's
value and time tag from the latest cycle that wrote it; what TlmChan sends must be what it sent when every cycle wrote.

The harness flights below fly one script twice, every cycle writing (``tlmRun`` never called) and with ``tlmRun``
called at each send, and compare what a TlmChan would send (its model: the latest write of each channel since the
previous send, in the order the channels were first received). Time: the harness's test time, 20 ms a tick.
"""

import pytest

from detumble.components import attitude_controller
from detumble.components.attitude_types import BodyAxis, ControlMode
from tests.detumble.components.test_attitude_controller import _ephemeris_port, make

TICK_US = 20_000
SEND_TICKS = 50  # TlmChan's Run at 1 Hz: every 50 ticks of the 50 Hz group


def _script(h, n: int, after_run: bool) -> None:
    """The commands and sensor changes of the script at tick ``n``: before the tick's run, or after it (at the
    same instant, before that instant's send)."""
    w = h.world
    if not after_run:
        if n == 0:
            w.omega = (0.05, -0.02, 0.03)  # rad/s
            h.send_command("SET_AUTO")
        elif n == 3:  # between cycles: PointingError from the next cycle
            h.send_command("FORCE_MODE", ControlMode.POINTING)
        elif n == 77:  # SunPointingError first written after ReferenceRate in the same second
            h.send_command("FORCE_MODE", ControlMode.SUN_SAFE)
        elif n == 140:
            w.tracker_valid = False  # the attitude is lost (ATTITUDE_TIMEOUT 0.5 s): POINTING goes to SUN_SAFE
        elif n == 180:
            w.tracker_valid = True  # known again for SUN_SAFE_EXIT_DWELL (1 s): back to POINTING
        elif n == 293:
            h.send_command("SET_AUTO")
        return
    # after the cycle of a send instant, before the send: the command's own write of Mode or TargetQuaternion
    # is the one sent
    if n == 50:  # a moving target: ReferenceRate (first written) and TargetQuaternion every cycle
        h.send_command("SET_TARGET_NADIR", BodyAxis.PLUS_Z, BodyAxis.PLUS_X)
    elif n == 100:
        h.send_command("FORCE_MODE", ControlMode.POINTING)
    elif n == 200:  # the target set by command, no longer by the cycles
        h.send_command("SET_TARGET_QUATERNION", 0.0, 0.0, 0.0, 1.0)
    elif n == 250:
        h.send_command("FORCE_MODE", ControlMode.SUN_SAFE)
    elif n == 275:  # SUN_SAFE left in the middle of a second: SunPointingError stops
        h.send_command("FORCE_MODE", ControlMode.POINTING)


def _fly(fprime_harness, *, deferred: bool, cycle_ticks: int, send_phase: int, ticks: int = 320):
    """``(what a TlmChan would send, each send a list of (channel, time, value); the channels in the order first
    received; the events; the number of channel writes)``."""
    h = make(fprime_harness, sun=True, params={"CYCLE_TICKS": cycle_ticks, "ATTITUDE_TIMEOUT": 0.5,
                                                 "SUN_SAFE_EXIT_DWELL": 1.0})
    _ephemeris_port(h)
    h.world.sun = (0.6, 0.0, 0.8)
    latest: dict[str, tuple] = {}
    sent: dict[str, tuple] = {}
    seen = 0
    sends = []
    for n in range(ticks):
        _script(h, n, after_run=False)
        h.invoke("run", 0)
        _script(h, n, after_run=True)
        if n % SEND_TICKS == send_phase:
            if deferred:
                h.invoke("tlmRun", 0)
            for record in h.telemetry[seen:]:
                latest[record.name] = (record.time, repr(record.value))
            seen = len(h.telemetry)
            send = [(name, *entry) for name, entry in latest.items() if sent.get(name) is not entry]
            sent.update(latest)
            sends.append(send)
        h.advance_time(useconds=TICK_US)
    events = [(e.name, e.time, e.args) for e in h.events]
    return sends, list(latest), events, len(h.telemetry)


@pytest.mark.parametrize("cycle_ticks, send_phase", [(5, 0), (3, 0), (5, 7)])
def test_tlm_run_sends_what_every_cycle_writing_sent(fprime_harness, cycle_ticks, send_phase):
    """TICK-031: through mode changes (POINTING, SUN_SAFE entered by command and by attitude loss, left mid-second),
    a moving target, commands that write Mode and TargetQuaternion after the cycle of a send instant, with the cycle
    at 10 Hz or 16.7 Hz (CYCLE_TICKS 3: no cycle at the send) and the send on a cycle's tick or between cycles:
    every send holds the same channels, values and time tags, the channels are first received in the same order,
    and the events are the same with the same times, as when every cycle writes. The writes fall to under a
    quarter."""
    every = _fly(fprime_harness, deferred=False, cycle_ticks=cycle_ticks, send_phase=send_phase)
    kept = _fly(fprime_harness, deferred=True, cycle_ticks=cycle_ticks, send_phase=send_phase)
    sends, order, events, writes = every
    names = {name for send in sends for name, *_ in send}
    # the script reaches what it is meant to: each conditional channel, and a command's Mode and target
    assert {"PointingError", "SunPointingError", "ReferenceRate", "TargetQuaternion", "SunVectorEstimate",
            "ActiveTarget", "AttitudeSigma3"} <= names
    assert [e[0] for e in events].count("ControlModeChanged") >= 7
    for i, (mine, theirs) in enumerate(zip(kept[0], sends, strict=True)):
        assert mine == theirs, f"send {i} differs"
    assert kept[1] == order
    assert kept[2] == events
    assert kept[3] < writes / 4, (kept[3], writes)


def test_cycles_write_themselves_when_tlm_run_stops(fprime_harness, monkeypatch):
    """TICK-033: once ``tlmRun`` has run, the cycles keep at most TLM_RECORDS_MAX records; the cycle that would
    keep one more writes them (each channel's latest value with its cycle's time) instead of keeping them all."""
    monkeypatch.setattr(attitude_controller, "TLM_RECORDS_MAX", 7)
    h = make(fprime_harness)
    h.invoke("run", 0)
    h.invoke("tlmRun", 0)
    cycle_times = []
    for n in range(1, 5 * 20 + 1):
        h.advance_time(useconds=TICK_US)
        if n % 5 == 0:
            cycle_times.append(h.test_time)
        h.invoke("run", 0)
        assert len(h.comp._tlm_records) < 7
    mode_times = [t.time for t in h.tlm_named("Mode")]
    # the first cycle's own write, then the 7th and 14th cycle after tlmRun wrote the 7 kept each time
    assert mode_times == [mode_times[0], cycle_times[6], cycle_times[13]]
