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

from fprime_lite.model.errors import FwAssertionError, QueueFullError

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
        self._lock = threading.Lock()
        self._cond = threading.Condition(self._lock)
        self._waiting = 0  # threads blocked in get() or put(); nobody to notify when zero
        self.high_water = 0
        self.dropped = 0
        #: Called after each message is queued (the deterministic scheduler marks the queue busy).
        self.on_put = None

    def __len__(self) -> int:
        return len(self._heap)

    def put(self, priority: int, call: Callable, args: tuple, *, queue_full: str, port: str,
            overflow: Callable | None = None, run_inline: Callable[[], bool] | None = None,
            threaded: bool = False) -> bool:
        """Queue a message; return False if it was dropped or handed to the overflow hook."""
        queued = False
        with self._lock:
            while len(self._heap) >= self.depth:
                if queue_full == "drop":
                    self.dropped += 1
                    return False
                if queue_full == "hook":
                    self.dropped += 1
                    break
                if queue_full == "block":
                    if threaded:
                        self._waiting += 1
                        try:
                            self._cond.wait()
                        finally:
                            self._waiting -= 1
                        continue
                    break
                raise QueueFullError(
                    f"{self.owner}: queue full ({self.depth} messages) on {port}; dispatch more "
                    f"often, enlarge queue_size, or declare the port with queue_full='drop'|'hook'|'block'")
            else:
                heapq.heappush(self._heap, (-priority, next(self._seq), call, args))
                if len(self._heap) > self.high_water:
                    self.high_water = len(self._heap)
                if self._waiting:
                    self._cond.notify_all()
                queued = True
        if queued:
            if self.on_put is not None:
                self.on_put()
            return True
        # Full, and the behaviour needs work outside the lock.
        if queue_full == "hook":
            if overflow is None:
                raise FwAssertionError(f"{port}: queue_full='hook' without an overflow hook")
            overflow(*args)
            return False
        if run_inline is None:
            raise FwAssertionError(f"{port}: a full deterministic queue needs run_inline to make room")
        run_inline()  # block, deterministic: make room by running the oldest message now
        return self.put(priority, call, args, queue_full=queue_full, port=port,
                        overflow=overflow, run_inline=run_inline, threaded=threaded)

    def try_push(self, priority: int, call: Callable, args: tuple) -> bool:
        """Queue a message if there is room; False (nothing queued) when full. The fast path."""
        with self._lock:
            heap = self._heap
            if len(heap) >= self.depth:
                return False
            heapq.heappush(heap, (-priority, next(self._seq), call, args))
            if len(heap) > self.high_water:
                self.high_water = len(heap)
            if self._waiting:
                self._cond.notify_all()
        if self.on_put is not None:
            self.on_put()
        return True

    def get(self, block: bool = False, timeout: float | None = None):
        """Pop the next ``(call, args)``; None when empty (or on timeout when blocking)."""
        with self._lock:
            if block and not self._heap:
                self._waiting += 1
                try:
                    if not self._cond.wait_for(lambda: self._heap, timeout):
                        return None
                finally:
                    self._waiting -= 1
            if not self._heap:
                return None
            _, _, call, args = heapq.heappop(self._heap)
            if self._waiting:
                self._cond.notify_all()
            return call, args
