"""Atomic saves under real SIGKILLs (issue #16 finding 7): the destination is always the old or the new
content, every temporary file left behind is recognisable and removed at the next start-up.

A child process saves the same file over and over; before each ``os.fsync`` it writes one byte to
its stdout and waits for the parent, so the parent can SIGKILL it at a chosen point: at an odd
signal the temporary file is being synced (it must be left behind), at an even one the directory
is (the rename is done: nothing may be left). Killing at a random signal covers both, and the
counts are exact rather than probabilistic.
"""

import os
import random
import signal
import subprocess
import sys
import textwrap

import pytest

from fprime_lite.osal import atomic
from fprime_lite.osal.atomic import clean_temporary_files, is_temporary_name, temporary_file

pytestmark = pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="needs POSIX signals")

KILLS = int(os.environ.get("FPRIME_LITE_KILLS", "12"))  # raise it for a campaign (docs/reliability.md)
PAYLOAD = 64 * 1024  # bytes per save; each save writes one repeated byte value

CHILD = textwrap.dedent("""
    import importlib.util, os, sys
    spec = importlib.util.spec_from_file_location("atomic", sys.argv[2])  # the module alone: a fast start
    atomic = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(atomic)
    real_fsync = os.fsync
    def announced_fsync(fd):
        sys.stdout.buffer.write(b"s"); sys.stdout.buffer.flush()
        sys.stdin.buffer.read(1)  # the parent says go on (or kills us)
        real_fsync(fd)
    atomic.os.fsync = announced_fsync
    target = sys.argv[1]
    n = 0
    while True:
        n += 1
        atomic.atomic_write_bytes(target, bytes([n % 250 + 1]) * PAYLOAD)
""").replace("PAYLOAD", str(PAYLOAD))


def _leftovers(folder):
    return sorted(p for p in os.listdir(folder) if is_temporary_name(p))


def test_kills_during_atomic_saves_never_corrupt_and_leftovers_are_cleaned(tmp_path):
    """TMP-1: KILLS (12) children SIGKILLed at a random fsync of an atomic save: the file is always whole
    (one byte value, PAYLOAD bytes, or absent before the first save); exactly the kills during the
    temporary file's fsync leave a temporary file, each recognisable, and clean_temporary_files
    removes them all while the file stays intact."""
    target = tmp_path / "PrmDb.dat"
    rng = random.Random(16)
    expected_leftovers = 0
    for _ in range(KILLS):
        child = subprocess.Popen([sys.executable, "-c", CHILD, str(target), atomic.__file__],
                                 stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        kill_at = rng.randint(1, 6)  # signals: 1 temp fsync, 2 directory fsync, 3 temp, 4 dir, ...
        for signal_number in range(1, kill_at + 1):
            assert child.stdout.read(1) == b"s"
            if signal_number < kill_at:
                child.stdin.write(b"g")
                child.stdin.flush()
        os.kill(child.pid, signal.SIGKILL)
        child.wait(timeout=10)
        child.stdin.close()
        child.stdout.close()
        assert child.returncode == -signal.SIGKILL
        expected_leftovers += kill_at % 2
        if target.exists():
            data = target.read_bytes()
            assert len(data) == PAYLOAD and len(set(data)) == 1, "a save was seen half-done"
        assert len(_leftovers(tmp_path)) == expected_leftovers
    assert expected_leftovers > 0  # the seed kills during at least one temporary fsync
    before = target.read_bytes() if target.exists() else None
    removed = clean_temporary_files(tmp_path)
    assert len(removed) == expected_leftovers and _leftovers(tmp_path) == []
    assert (target.read_bytes() if target.exists() else None) == before


def test_a_live_process_temporary_file_is_left_alone(tmp_path):
    """TMP-2: a temporary file whose process is still running is not removed; one of a process
    that has exited is; files that only look similar are never touched."""
    sleeper = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        live = tmp_path / f".fprime-lite-tmp.{sleeper.pid}.data.bin.abc.part"
        live.write_bytes(b"in progress")
        finished = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                                  capture_output=True, text=True, check=True)
        dead = tmp_path / f".fprime-lite-tmp.{int(finished.stdout)}.data.bin.def.part"
        dead.write_bytes(b"left behind")
        lookalike = tmp_path / ".data.bin.xyz.part"
        lookalike.write_bytes(b"someone else's")
        sub = tmp_path / "sub"
        sub.mkdir()
        nested = sub / dead.name
        nested.write_bytes(b"left behind too")
        assert clean_temporary_files(tmp_path) == [str(dead)]
        assert live.exists() and lookalike.exists() and nested.exists()
        assert clean_temporary_files(tmp_path, recursive=True) == [str(nested)]
    finally:
        sleeper.kill()
        sleeper.wait()


def test_temporary_names_are_recognisable(tmp_path):
    """TMP-3: temporary_file names carry the prefix, our pid and the destination's name."""
    fd, path = temporary_file(tmp_path, "summary.json")
    os.close(fd)
    name = os.path.basename(path)
    assert is_temporary_name(name) and f".{os.getpid()}.summary.json." in name
    assert not is_temporary_name("summary.json") and not is_temporary_name(".summary.json.part")
