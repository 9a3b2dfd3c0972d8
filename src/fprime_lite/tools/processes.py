"""Child processes started in sessions of their own, so that each can be ended with everything it
started (fprime-gds's ``comm`` child ignores SIGTERM and outlives its parent), and loopback ports
free for a ground system.

Used by ``fprime-lite conformance`` and by the tests that fly the stock fprime-gds.
"""

from __future__ import annotations

import os
import pathlib
import signal
import socket
import subprocess
import time

__all__ = ["ProcessGroups", "free_port"]


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

    def __init__(self, log_dir: str | os.PathLike):
        self.log_dir = pathlib.Path(log_dir)
        self.procs: dict[str, subprocess.Popen] = {}

    def start(self, name: str, argv: list[str], **kwargs) -> subprocess.Popen:
        """Start ``argv`` as ``name`` (stdin closed, stdout and stderr to its log); ``kwargs`` go to Popen."""
        with open(self.log_dir / f"{name}.log", "wb") as log:
            proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                    start_new_session=True, **kwargs)
        self.procs[name] = proc
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
