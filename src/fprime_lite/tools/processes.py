"""Child processes started in sessions of their own, so that each can be ended with everything it
started (fprime-gds's ``comm`` child ignores SIGTERM and outlives its parent), and loopback ports
free for a ground system.

A process killed outright (SIGKILL) cannot clean up after itself; ``ProcessGroups(watchdog=True)``
starts a small watchdog process for that case: it is told each group as it starts and ends (through
a pipe only the owner holds), and when the pipe closes without a "done" — the owner died, however —
it sends SIGTERM to every group still known, waits ``WATCHDOG_GRACE_S``, then SIGKILLs them.

Used by ``fprime-lite conformance`` and by the tests that fly the stock fprime-gds.
"""

from __future__ import annotations

import os
import pathlib
import signal
import socket
import subprocess
import sys
import time

__all__ = ["ProcessGroups", "free_port", "WATCHDOG_GRACE_S"]

#: How long the watchdog waits after SIGTERM before SIGKILL (the deployment writes its outputs).
WATCHDOG_GRACE_S = 20.0

#: The watchdog's program (``python -c``): reads "PGID" / "-PGID" / "done" lines until end of file.
_WATCHDOG = """
import os, signal, sys, time
groups = set()
for line in sys.stdin:
    line = line.strip()
    if line == "done":
        sys.exit(0)
    if line.startswith("-"):
        groups.discard(int(line[1:]))
    elif line:
        groups.add(int(line))
for sig in (signal.SIGTERM, signal.SIGKILL):
    for group in sorted(groups):
        try:
            os.killpg(group, sig)
        except OSError:
            groups.discard(group)
    deadline = time.monotonic() + float(sys.argv[1])
    while sig == signal.SIGTERM and groups and time.monotonic() < deadline:
        time.sleep(0.2)
        for group in sorted(groups):
            try:
                os.killpg(group, 0)
            except OSError:
                groups.discard(group)
"""


def free_port(host: str = "127.0.0.1") -> int:
    """A port free on ``host`` for both TCP and UDP (fprime-gds's ip adapter binds both).

    Free when asked: another program may take it before the caller binds it; the caller's failure
    to start is then reported like any other.
    """
    for _ in range(50):
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as tcp:
            tcp.bind((host, 0))
            port = tcp.getsockname()[1]
            with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as udp:
                try:
                    udp.bind((host, port))
                except OSError:
                    continue
        return port
    raise OSError(f"no port free for both TCP and UDP on {host} after 50 tries")


class ProcessGroups:
    """Processes each started in a new session (its own process group), their output in
    ``log_dir/<name>.log``; :meth:`stop` and :meth:`stop_all` end whole groups."""

    def __init__(self, log_dir: str | os.PathLike, watchdog: bool = False):
        self.log_dir = pathlib.Path(log_dir)
        self.procs: dict[str, subprocess.Popen] = {}
        self._watchdog: subprocess.Popen | None = None
        if watchdog:  # its own session: a signal to the owner's group does not reach it
            self._watchdog = subprocess.Popen([sys.executable, "-c", _WATCHDOG, str(WATCHDOG_GRACE_S)],
                                              stdin=subprocess.PIPE, stdout=subprocess.DEVNULL,
                                              stderr=subprocess.DEVNULL, start_new_session=True, text=True)

    def _tell_watchdog(self, line: str) -> None:
        if self._watchdog is not None and self._watchdog.stdin is not None:
            try:
                self._watchdog.stdin.write(line + "\n")
                self._watchdog.stdin.flush()
            except (BrokenPipeError, ValueError):  # the watchdog ended: nothing to tell
                pass

    def close(self) -> None:
        """Tell the watchdog all is cleaned up ("done") and let it end (call after stopping every group)."""
        self._tell_watchdog("done")
        if self._watchdog is not None:
            try:
                self._watchdog.stdin.close()  # type: ignore[union-attr]
                self._watchdog.wait(5)
            except (OSError, subprocess.TimeoutExpired):  # pragma: no cover - it exits on "done"
                self._watchdog.kill()
            self._watchdog = None

    def start(self, name: str, argv: list[str], **kwargs) -> subprocess.Popen:
        """Start ``argv`` as ``name`` (stdin closed, stdout and stderr to its log); ``kwargs`` go to Popen."""
        with open(self.log_dir / f"{name}.log", "wb") as log:
            proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                    start_new_session=True, **kwargs)
        self.procs[name] = proc
        self._tell_watchdog(str(proc.pid))  # a new session: its group id is its pid
        return proc

    def log_path(self, name: str) -> pathlib.Path:
        return self.log_dir / f"{name}.log"

    def log(self, name: str, chars: int = 4000) -> str:
        """The last ``chars`` characters of ``name``'s output."""
        path = self.log_path(name)
        return path.read_text(errors="replace")[-chars:] if path.exists() else ""

    def signal(self, name: str, sig: int) -> None:
        """Send ``sig`` to ``name``'s whole process group (nothing if it has ended)."""
        try:
            os.killpg(self.procs[name].pid, sig)
        except ProcessLookupError:
            pass

    def stop(self, name: str, grace_s: float = 5.0, sig: int | None = None) -> int | None:
        """Send ``sig`` (default SIGTERM) to ``name``'s group, wait up to ``grace_s`` for its leader,
        then SIGKILL whatever is left of the group; the leader's exit status (None if it had to be
        killed)."""
        proc = self.procs[name]
        if proc.poll() is None:
            self.signal(name, signal.SIGTERM if sig is None else sig)
            try:
                proc.wait(grace_s)
            except subprocess.TimeoutExpired:
                pass
        status = proc.poll()
        self.signal(name, signal.SIGKILL)  # children that outlived or ignored the signal
        try:
            proc.wait(5)
        except subprocess.TimeoutExpired:  # pragma: no cover - a process SIGKILL cannot end
            pass
        self._tell_watchdog(f"-{proc.pid}")
        return status

    def stop_all(self, grace_s: float = 5.0) -> None:
        """SIGTERM every group, wait up to ``grace_s`` in all, then SIGKILL every group."""
        for name in self.procs:
            self.signal(name, signal.SIGTERM)
        deadline = time.monotonic() + grace_s
        for proc in self.procs.values():
            try:
                proc.wait(max(0.1, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                pass
        for name, proc in self.procs.items():
            self.signal(name, signal.SIGKILL)
            try:
                proc.wait(5)
            except subprocess.TimeoutExpired:  # pragma: no cover
                pass
            self._tell_watchdog(f"-{proc.pid}")
