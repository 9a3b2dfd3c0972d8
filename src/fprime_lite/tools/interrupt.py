"""SIGINT (Ctrl-C) and SIGTERM as a request to stop, for the verbs that keep what they finished.

``fprime-lite run`` stops its flight at the next tick and writes the outputs up to there;
``fprime-lite campaign`` stops submitting, keeps every row that came back and shuts its cluster down.
Both then exit as a shell reports a process ended by the signal: 128 + its number (130 for SIGINT,
143 for SIGTERM).
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Callable, Iterator

__all__ = ["stop_on_signals", "exit_status", "SIGNALS"]

#: The signals that ask a verb to stop.
SIGNALS = (signal.SIGINT, signal.SIGTERM)


@contextlib.contextmanager
def stop_on_signals(stop: Callable[[], None], received: list[str], *, enabled: bool = True) -> Iterator[None]:
    """While the block runs, SIGINT and SIGTERM append the signal's name (``"SIGINT"``/``"SIGTERM"``)
    to ``received`` and call ``stop()`` instead of raising wherever the main thread happens to be; the
    previous handlers come back after the block, so a second Ctrl-C while the outputs are written acts
    as usual. Only the main thread can take signals: elsewhere, or when not ``enabled``, nothing changes."""
    if not enabled or threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum, _frame) -> None:
        received.append(signal.Signals(signum).name)
        stop()

    previous = {sig: signal.signal(sig, handler) for sig in SIGNALS}
    try:
        yield
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old)


def exit_status(signal_name: str) -> int:
    """The exit status of a verb ended by ``signal_name``: 128 + the signal's number, as a shell says."""
    return 128 + signal.Signals[signal_name].value
