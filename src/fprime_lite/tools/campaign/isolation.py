"""Hard timeouts: a campaign run with ``timeout_s`` flies in a run process that is killed when the
run overstays.

Each worker thread keeps one run process (``python -m fprime_lite.tools.campaign.isolation``),
started at its first run with ``timeout_s`` and reused for the next ones, so the per-run cost is a
pickle each way over a pipe, not a new interpreter. The run's own cooperative timeout still ends a
run that polls its deadline (keeping what it measured); the parent waits ``timeout_s`` plus a grace
(:func:`grace_s`) and then kills the process — a run stuck where it never polls (a loop in a
law, a blocked file system) is recorded as ``timeout`` and the next run gets a fresh process.

The run process is a plain subprocess (not ``multiprocessing``: Dask's worker processes are
daemonic and may not have multiprocessing children). Tasks and rows travel as length-prefixed
pickles over two pipes; its stdout and stderr are the worker's. It exits when the parent's pipe
closes, and a watchdog thread ends it if the parent dies while a run is still going.
"""

from __future__ import annotations

import os
import pickle
import select
import struct
import subprocess
import sys
import threading
import time

__all__ = ["fly_isolated", "run_process", "grace_s", "killed_row"]

_HEADER = struct.Struct("<Q")
_START_TIMEOUT_S = 300.0  # an interpreter start and the campaign imports, on a loaded machine
_local = threading.local()


def grace_s(timeout_s: float) -> float:
    """Wall seconds a run may take past ``timeout_s`` to stop by itself before it is killed:
    10 % of the timeout, at least 2 s (a run that polls ends well within it)."""
    return max(2.0, 0.1 * timeout_s)


def _write_frame(fd: int, payload: bytes) -> None:
    data = _HEADER.pack(len(payload)) + payload
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _read_exactly(fd: int, n: int, deadline: float | None) -> bytes | None:
    """``n`` bytes from ``fd``; None at end of file; raises TimeoutError past ``deadline``."""
    chunks, got = [], 0
    while got < n:
        if deadline is not None:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([fd], [], [], left)[0]:
                raise TimeoutError
        chunk = os.read(fd, min(n - got, 1 << 20))
        if not chunk:
            return None
        chunks.append(chunk)
        got += len(chunk)
    return b"".join(chunks)


def _read_frame(fd: int, deadline: float | None = None) -> bytes | None:
    head = _read_exactly(fd, _HEADER.size, deadline)
    if head is None:
        return None
    return _read_exactly(fd, _HEADER.unpack(head)[0], deadline)


class _RunProcess:
    """One run process and its two pipes."""

    def __init__(self, warm_task: dict | None = None):
        task_r, self.task_w = os.pipe()
        self.row_r, row_w = os.pipe()
        self.proc = subprocess.Popen([sys.executable, "-m", "fprime_lite.tools.campaign.isolation",
                                      str(task_r), str(row_w)], pass_fds=(task_r, row_w),
                                     stdin=subprocess.DEVNULL)
        os.close(task_r)
        os.close(row_w)
        try:
            _write_frame(self.task_w, pickle.dumps((list(sys.path), warm_task)))  # the same imports as this worker
            ready = _read_frame(self.row_r, time.monotonic() + _START_TIMEOUT_S)
        except OSError:  # TimeoutError included
            ready = None
        if ready != b"ready":
            code, _ = self.end(kill=True)
            raise RuntimeError(f"the run process did not start (exit status {code}; its stderr is the worker's)")

    def run(self, task: dict, out_dir, deadline: float) -> dict | None:
        """The row, or None when the process ended without one; TimeoutError past ``deadline``."""
        _write_frame(self.task_w, pickle.dumps((task, str(out_dir)), protocol=pickle.HIGHEST_PROTOCOL))
        frame = _read_frame(self.row_r, deadline)
        return None if frame is None else pickle.loads(frame)

    def end(self, kill: bool) -> tuple[int | None, float]:
        """Stop the process; return (its exit status, its CPU seconds)."""
        for fd in (self.task_w, self.row_r):
            try:
                os.close(fd)
            except OSError:
                pass
        if kill:
            self.proc.kill()
        try:
            _, status, usage = os.wait4(self.proc.pid, 0)
            self.proc.returncode = os.waitstatus_to_exitcode(status)
            return self.proc.returncode, usage.ru_utime + usage.ru_stime
        except ChildProcessError:  # already reaped
            return self.proc.returncode, 0.0


def run_process(warm_task: dict | None = None) -> _RunProcess:
    """This thread's run process, started (and waited for until ready, ``warm_task`` built in it so
    its imports are done) when it has none or it died."""
    proc = getattr(_local, "proc", None)
    if proc is None or proc.proc.poll() is not None:
        proc = _local.proc = _RunProcess(warm_task)
    return proc


def killed_row(task: dict, status: str, error: str, note: str) -> dict:
    """The row of a run that did not return one (killed, or its process died)."""
    import json

    from fprime_lite.tools.campaign.values import plain

    return {"run_id": task["run_id"], "point": task["point"], "seed_index": task["seed_index"],
            "seed": task["seed"], "status": status, "error": error,
            "values": {k: None for k in task["values"]}, "metrics": {m: None for m in task["metrics"]},
            "notes": json.dumps({"*": note}), "requested": json.dumps(plain(task["values"]), sort_keys=True)}


def fly_isolated(task: dict, out_dir) -> tuple[dict, float]:
    """Fly ``task`` in this thread's run process; return (row, the run's CPU seconds)."""
    timeout = float(task["timeout_s"])
    proc = run_process(task)  # started (and ready) before the run's time starts
    t0 = time.monotonic()
    try:
        row = proc.run(task, out_dir, t0 + timeout + grace_s(timeout))
    except TimeoutError:
        _local.proc = None
        _, cpu = proc.end(kill=True)
        wall = time.monotonic() - t0
        return killed_row(task, "timeout", f"killed after {wall:.1f} s of wall time: still running "
                                           f"{wall - timeout:.1f} s past its timeout_s of {timeout:g} s "
                                           f"(it never checked its deadline)",
                          "killed at its hard timeout"), cpu
    except OSError:  # the pipe broke: the process is gone or unusable
        _local.proc = None
        proc.end(kill=True)
        raise
    if row is None:
        _local.proc = None
        code, cpu = proc.end(kill=False)
        return killed_row(task, "failed", f"the run's process ended (exit status {code}) without a result",
                          "the run's process died"), cpu
    return row, row.pop("cpu_s")


def _watch_parent(parent: int) -> None:
    while True:
        time.sleep(1.0)
        if os.getppid() != parent:
            os._exit(1)


def main(argv: list[str]) -> int:
    """The run process: read (task, out_dir) frames, fly each, answer its row (with ``cpu_s``)."""
    import pathlib

    task_r, row_w = int(argv[0]), int(argv[1])
    threading.Thread(target=_watch_parent, args=(os.getppid(),), daemon=True).start()
    frame = _read_frame(task_r)
    if frame is None:
        return 0
    sys.path[:], warm_task = pickle.loads(frame)
    from fprime_lite.tools.campaign.task import fly, warm_up

    warm_up(warm_task)  # load the plug-ins and the kind's modules now: not on the first run's clock
    _write_frame(row_w, b"ready")
    while True:
        frame = _read_frame(task_r)
        if frame is None:
            return 0
        task, out_dir = pickle.loads(frame)
        t0 = time.perf_counter()
        cpu0 = time.process_time()
        row = fly(task, pathlib.Path(out_dir), t0)
        row["cpu_s"] = time.process_time() - cpu0
        _write_frame(row_w, pickle.dumps(row, protocol=pickle.HIGHEST_PROTOCOL))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
