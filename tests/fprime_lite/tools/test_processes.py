"""ProcessGroups' watchdog: an owner killed by SIGKILL leaves none of the groups it started."""

from __future__ import annotations

import os
import pathlib
import signal
import subprocess
import sys
import textwrap
import time

#: The owner: starts a group whose leader has a child of its own (as fprime-gds has its comm),
#: prints both pids, then waits to be killed.
OWNER = textwrap.dedent("""
    import sys, time
    from fprime_lite.tools.processes import ProcessGroups
    groups = ProcessGroups(sys.argv[1], watchdog={watchdog})
    leader = groups.start("sleeper", [sys.executable, "-c", "import subprocess, time; "
        "c = subprocess.Popen(['sleep', '600']); print(c.pid, flush=True); time.sleep(600)"])
    time.sleep(0.5)
    {after}
    print(leader.pid, flush=True)  # only once ``after`` has run: the test kills the owner when it reads this
    time.sleep(600)
""")


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().split(") ")[-1][0] != "Z"  # a zombie is dead
    except OSError:
        return False


def _run_owner(tmp_path: pathlib.Path, watchdog: bool, after: str = "") -> tuple[int, int]:
    """Start the owner, SIGKILL it once its group runs; the group leader's pid and its child's."""
    owner = subprocess.Popen([sys.executable, "-c", OWNER.format(watchdog=watchdog, after=after), str(tmp_path)],
                             stdout=subprocess.PIPE, text=True, start_new_session=True)
    try:
        leader = int(owner.stdout.readline())  # type: ignore[union-attr]
        deadline = time.monotonic() + 20
        log = tmp_path / "sleeper.log"
        while not log.read_text().strip() and time.monotonic() < deadline:
            time.sleep(0.05)
        child = int(log.read_text().split()[0])
        assert _alive(leader) and _alive(child)
    finally:
        owner.kill()
        owner.wait()
    return leader, child


def _gone_within(pids, seconds: float) -> bool:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if not any(_alive(p) for p in pids):
            return True
        time.sleep(0.1)
    return False


def _survive_then_kill(pids) -> bool:
    """Whether ``pids`` are all still running 1.5 s on; they are killed either way."""
    try:
        return not _gone_within(pids, 1.5)
    finally:
        for pid in pids:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass


def test_a_sigkilled_owner_leaves_no_process_behind(tmp_path):
    """With the watchdog the group leader and its own child end within seconds of the owner's SIGKILL
    (SIGTERM first: the sleepers take it)."""
    pids = _run_owner(tmp_path, watchdog=True)
    assert _gone_within(pids, 10), "the owner's processes outlived it"


def test_without_the_watchdog_they_would_outlive_it(tmp_path):
    """The case the watchdog is for: without it, the same processes are still running."""
    assert _survive_then_kill(_run_owner(tmp_path, watchdog=False))


def test_a_clean_close_kills_nothing(tmp_path):
    """After close() ("done") the watchdog ends without touching the groups: a group the owner left
    running on purpose survives the owner's later death."""
    assert _survive_then_kill(_run_owner(tmp_path, watchdog=True, after="groups.close()"))
