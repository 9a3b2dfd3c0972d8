"""The message queue of queued and active components.

Messages are ordered by priority (larger first) and then by arrival. A full queue does what the
port declared: ``assert`` raises QueueFullError, ``drop`` discards (and counts), ``hook`` calls the
component's overflow hook, ``block`` waits for room when the component has a thread, and otherwise
runs the oldest message on the caller's thread to make room (in deterministic mode nobody else
would ever empty the queue).
"""

from __future__ import annotations

import heapq
import itertools
import threading
from typing import Callable

from .errors import QueueFullError

__all__ = ["MessageQueue"]


class MessageQueue:
    """A bounded priority queue of ``(call, args)`` messages; thread-safe."""

    def __init__(self, owner: str, depth: int):
        if not isinstance(depth, int) or depth < 1:
            raise ValueError(f"{owner}: queue size must be a positive integer, got {depth!r}")
        self.owner = owner
        self.depth = depth
        self._heap: list = []
        self._seq = itertools.count()
        self._cond = threading.Condition()
        self.high_water = 0
        self.dropped = 0

    def __len__(self) -> int:
        return len(self._heap)

    def put(self, priority: int, call: Callable, args: tuple, *, queue_full: str, port: str,
            overflow: Callable | None = None, run_inline: Callable[[], bool] | None = None,
            threaded: bool = False) -> bool:
        """Queue a message; return False if it was dropped or handed to the overflow hook."""
        with self._cond:
            while len(self._heap) >= self.depth:
                if queue_full == "drop":
                    self.dropped += 1
                    return False
                if queue_full == "hook":
                    self.dropped += 1
                    break
                if queue_full == "block":
                    if threaded:
                        self._cond.wait()
                        continue
                    break
                raise QueueFullError(
                    f"{self.owner}: queue full ({self.depth} messages) on {port}; dispatch more "
                    f"often, enlarge queue_size, or declare the port with queue_full='drop'|'hook'|'block'")
            else:
                heapq.heappush(self._heap, (-priority, next(self._seq), call, args))
                self.high_water = max(self.high_water, len(self._heap))
                self._cond.notify_all()
                return True
        # Full, and the behaviour needs work outside the lock.
        if queue_full == "hook":
            overflow(*args)
            return False
        run_inline()  # block, deterministic: make room by running the oldest message now
        return self.put(priority, call, args, queue_full=queue_full, port=port,
                        overflow=overflow, run_inline=run_inline, threaded=threaded)

    def get(self, block: bool = False, timeout: float | None = None):
        """Pop the next ``(call, args)``; None when empty (or on timeout when blocking)."""
        with self._cond:
            if block:
                if not self._cond.wait_for(lambda: self._heap, timeout):
                    return None
            if not self._heap:
                return None
            _, _, call, args = heapq.heappop(self._heap)
            self._cond.notify_all()
            return call, args
