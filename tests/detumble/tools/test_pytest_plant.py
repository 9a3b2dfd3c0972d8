"""The manual-test plugin: inert without --sim-plant; with it, un-skips the named tests and drives the plant."""

import json
import os
import socket
import subprocess
import sys
import textwrap
import threading

SUITE = {
    "mode_manager_test.py": '''
        import os
        import pytest

        @pytest.mark.skip(reason="Requires voltage control - run manually with low battery")
        def test_safe_05_auto_entry_low_voltage():
            assert os.path.isdir("Framing/src")

        @pytest.mark.skip(reason="not a manual test of the plugin's list")
        def test_other():
            pass
    ''',
    "lora_passthrough_test.py": '''
        import os
        TTY = os.environ.get("LORA_PASSTHROUGH_TTY")

        def test_tty_is_a_terminal():
            assert TTY and os.isatty(os.open(TTY, os.O_RDWR | os.O_NOCTTY))
    ''',
}


class FakePlant(threading.Thread):
    """A plant-control server that records the requests and answers like the deployment."""

    def __init__(self):
        super().__init__(daemon=True)
        self.server = socket.create_server(("127.0.0.1", 0))
        self.address = f"127.0.0.1:{self.server.getsockname()[1]}"
        self.requests = []

    def run(self):
        while True:
            try:
                conn, _ = self.server.accept()
            except OSError:
                return
            with conn, conn.makefile("rb") as reader:
                for line in reader:
                    request = json.loads(line)
                    self.requests.append(request)
                    conn.sendall(json.dumps({"ok": True, "soc": 0.9, "data": ""}).encode() + b"\n")


def _run(tmp_path, *args):
    for name, text in SUITE.items():
        (tmp_path / name).write_text(textwrap.dedent(text))
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs", str(tmp_path), *args],
                          cwd=tmp_path, capture_output=True, text=True, timeout=120,
                          env={k: v for k, v in os.environ.items() if k != "LORA_PASSTHROUGH_TTY"})


def test_inert_without_the_option(tmp_path):
    """PLUG-001: without --sim-plant the manual test stays skipped and no terminal is made."""
    result = _run(tmp_path)
    assert "1 failed" in result.stdout and "2 skipped" in result.stdout, result.stdout


def test_runs_the_manual_test_and_drives_the_battery(tmp_path):
    """PLUG-002: with --sim-plant the listed test runs (only it), with the battery low during the test
    and restored after; the LoRa passthrough gets a pseudo-terminal; Framing/src exists."""
    plant = FakePlant()
    plant.start()
    try:
        result = _run(tmp_path, "--sim-plant", plant.address)
    finally:
        plant.server.close()
    assert "2 passed" in result.stdout and "1 skipped" in result.stdout, result.stdout + result.stderr
    ops = [(r["op"], r.get("soc")) for r in plant.requests]
    assert ops == [("status", None), ("battery_soc", 0.05), ("battery_soc", 0.9)]
