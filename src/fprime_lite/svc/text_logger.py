"""TextLogger: writes text events as lines to a stream (standard output by default).

F´'s ``Svc.PassiveTextLogger``: every component's ``logTextOut`` connects to ``TextLogger``. Each
event becomes one line in F´'s format::

    EVENT: (1234) (2:100,250000) ACTIVITY_HI: (heater) HeaterOn: Heater on at 17.5 C

i.e. ``EVENT: (id) (time base:seconds,microseconds) SEVERITY: text``. Nothing is filtered (use the
EventManager's filters for what reaches the ground).
"""

from __future__ import annotations

import logging
import sys
import threading
from typing import TextIO

from fprime_lite.model.component import PassiveComponent
from fprime_lite.model.events import Severity
from fprime_lite.model.fw_ports import LogText
from fprime_lite.model.ports import sync_input

__all__ = ["TextLogger", "format_text_event"]

log = logging.getLogger("fprime_lite")


def format_text_event(event_id: int, time, severity, text: str) -> str:
    """One log line (no newline) in F´'s PassiveTextLogger format."""
    try:
        severity_name = Severity(severity).name
    except ValueError:
        severity_name = f"SEVERITY_{severity}"
    return (f"EVENT: ({event_id}) ({int(time.time_base)}:{time.seconds},{time.useconds}) "
            f"{severity_name}: {text}")


class TextLogger(PassiveComponent):
    """Prints text events.

    Args:
        name: instance name (``textLogger`` in F´ deployments).
        stream: where the lines go; ``None`` means ``sys.stdout`` at the time of each write.
        base_id: unused (TextLogger has no commands, events or channels).
    """

    def __init__(self, name: str = "textLogger", stream: TextIO | None = None, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self.stream = stream
        self.lines_written = 0
        self._write_lock = threading.Lock()
        self._reporting = False  # inside report_fault: its event comes back to this port

    @sync_input(LogText)
    def TextLogger(self, event_id: int, time, severity, text: str) -> None:
        """Write one line for the text event (never raises: a stream that fails is a fault,
        reported with ``report_fault``)."""
        try:
            line = format_text_event(event_id, time, severity, text) + "\n"
            stream = self.stream if self.stream is not None else sys.stdout
            with self._write_lock:
                stream.write(line)
                stream.flush()
            self.lines_written += 1
        except Exception as exc:  # noqa: BLE001 - logging must never break the component emitting
            if self._reporting:  # the fault's own HandlerFault event, failing the same way: logged only
                log.warning("%s: cannot write text event %r: %s", self.name, event_id, exc)
                return
            self._reporting = True
            try:
                self.report_fault("TextLogger", exc)
            finally:
                self._reporting = False
