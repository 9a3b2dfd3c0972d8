"""pytest plugin: the PROVES suite's six "manual" tests, with the simulated plant as the bench operator.

PROVES's integration suite (``test/int``) skip-marks six tests that need a person at the bench: lower
the battery voltage, pull the power, point a camera, listen with a LoRa receiver. Against the
simulated spacecraft this plugin does those steps, through the deployment's plant-control side
channel (:mod:`detumble.drivers.plant_control`), and un-skips the six tests — without editing the
test files. It is installed with fprime-lite (entry point ``pytest11``) and does nothing unless
pytest is given ``--sim-plant HOST:PORT`` (the address the deployment was started with in
``FPRIME_LITE_PLANT_CONTROL``; loopback only).

What it does around each test body (after the test's fixtures have set up):

* ``mode_manager_test.py::test_safe_05_auto_entry_low_voltage`` — battery state of charge to
  ``LOW_SOC`` (open-circuit 6.45 V, below the 6.7 V entry threshold) for the test; the charge is
  restored afterwards;
* ``…::test_safe_06_auto_recovery_voltage`` — first the low battery until the mode manager's
  AutoSafeModeEntry (the test wants LOW_BATTERY safe mode, which its own set-up fixture just left),
  then ``HIGH_SOC`` (8.3 V, above the 8.0 V recovery threshold) for the test body;
* ``…::test_safe_07_unintended_reboot_detection`` — a power cycle (no clean-shutdown flag), then
  waits for UnintendedRebootDetected to reach the test API's history;
* ``…::test_safe_08_clean_reboot_no_safe_mode`` — nothing: the test commands COLD_RESET and the
  simulated board reboots and reconnects by itself;
* ``camera_handler_test.py::test_01_take_image`` — nothing: the simulated camera on face 4 answers;
* ``lora_passthrough_test.py::test_lora_downlink_reaches_passthrough`` — a pseudo-terminal stands
  for the passthrough board's serial port (``LORA_PASSTHROUGH_TTY``, set when the plugin is
  configured, before the test module reads it); while the test runs, what the simulated ground peer
  hears from the radio is written to it.

It also makes ``Framing/src/`` in the working directory, where ``sync_sequence_number_test.py`` writes
the uplink sequence number for PROVES's GDS framing plugin (PROVES runs the suite from its repository,
which has that folder).

Only the standard library and pytest are imported, so the plugin loads in the suite's own Python
(PROVES needs ≥ 3.12) with fprime-lite installed there without its dependencies.
"""

from __future__ import annotations

import base64
import json
import os
import socket
import threading
import time
from typing import BinaryIO

import pytest

__all__ = ["PlantClient", "MANUAL_TESTS", "LOW_SOC", "HIGH_SOC"]

#: Battery state of charge giving an open-circuit 2 x 3.225 V = 6.45 V (below the 6.7 V entry threshold).
LOW_SOC = 0.05
#: … and 2 x 4.15 V = 8.3 V (above the 8.0 V recovery threshold).
HIGH_SOC = 0.95
MODE_MANAGER = "ReferenceDeployment.modeManager"

#: The skip-marked tests the plugin runs (file name, test name).
MANUAL_TESTS = {
    ("mode_manager_test.py", "test_safe_05_auto_entry_low_voltage"),
    ("mode_manager_test.py", "test_safe_06_auto_recovery_voltage"),
    ("mode_manager_test.py", "test_safe_07_unintended_reboot_detection"),
    ("mode_manager_test.py", "test_safe_08_clean_reboot_no_safe_mode"),
    ("camera_handler_test.py", "test_01_take_image"),
    ("lora_passthrough_test.py", "test_lora_downlink_reaches_passthrough"),
}


class PlantClient:
    """A client of the plant-control side channel (one JSON line out, one back)."""

    def __init__(self, address: str, timeout_s: float = 15.0):
        host, _, port = address.rpartition(":")
        if host.strip("[]") not in ("127.0.0.1", "::1", "localhost") or not port.isdigit():
            raise pytest.UsageError(f"--sim-plant {address!r}: expected HOST:PORT on the loopback interface")
        self.address = (host.strip("[]"), int(port))
        self.timeout_s = timeout_s
        self._lock = threading.Lock()
        self._sock: socket.socket | None = None
        self._reader: BinaryIO | None = None

    def request(self, op: str, **args) -> dict:
        """Send one request; the reply, or RuntimeError naming what the deployment said."""
        with self._lock:
            for attempt in (0, 1):  # the connection may have dropped: reconnect once
                try:
                    if self._sock is None or self._reader is None:
                        self._sock = socket.create_connection(self.address, timeout=self.timeout_s)
                        self._reader = self._sock.makefile("rb")
                    self._sock.sendall(json.dumps({"op": op, **args}).encode() + b"\n")
                    line = self._reader.readline(1 << 20)
                    if not line:
                        raise OSError("connection closed")
                    break
                except OSError:
                    self.close()
                    if attempt:
                        raise
        reply = json.loads(line)
        if not reply.get("ok"):
            raise RuntimeError(f"plant control {op}: {reply.get('error')}")
        return reply

    def close(self) -> None:
        if self._sock is not None:
            self._sock.close()
        self._sock = self._reader = None


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--sim-plant", metavar="HOST:PORT", default=None,
                     help="fprime-lite: drive the simulated spacecraft's plant at HOST:PORT (the deployment's "
                          "FPRIME_LITE_PLANT_CONTROL) and run the PROVES suite's manual tests")


def pytest_configure(config: pytest.Config) -> None:
    address = config.getoption("--sim-plant", default=None)
    if not address:
        return
    # PROVES runs its suite from its repository, where sync_sequence_number_test.py writes the uplink
    # sequence number for its GDS framing plugin: Framing/src/ relative to the working directory
    os.makedirs(os.path.join("Framing", "src"), exist_ok=True)
    master, slave = os.openpty()
    os.environ["LORA_PASSTHROUGH_TTY"] = os.ttyname(slave)
    config.stash[_STATE] = {"client": PlantClient(address), "pty": (master, slave)}


def pytest_unconfigure(config: pytest.Config) -> None:
    state = config.stash.get(_STATE, None)
    if state is None:
        return
    state["client"].close()
    for fd in state["pty"]:
        os.close(fd)


_STATE = pytest.StashKey[dict]()


def _manual_name(item: pytest.Item) -> str | None:
    key = (os.path.basename(str(item.path)), item.name)
    return key[1] if key in MANUAL_TESTS else None


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if _STATE not in config.stash:
        return
    for item in items:
        if _manual_name(item) is not None:
            item.own_markers[:] = [m for m in item.own_markers if m.name != "skip"]


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_call(item: pytest.Item):
    state = item.config.stash.get(_STATE, None)
    name = _manual_name(item) if state is not None else None
    if state is None or name is None:
        yield
        return
    client: PlantClient = state["client"]
    api = item.funcargs.get("fprime_test_api")  # type: ignore[attr-defined]
    before = client.request("status")
    pump = None
    if name == "test_safe_05_auto_entry_low_voltage":
        client.request("battery_soc", soc=LOW_SOC)
    elif name == "test_safe_06_auto_recovery_voltage":
        client.request("battery_soc", soc=LOW_SOC)
        api.assert_event(f"{MODE_MANAGER}.AutoSafeModeEntry", timeout=30)
        client.request("battery_soc", soc=HIGH_SOC)
    elif name == "test_safe_07_unintended_reboot_detection":
        client.request("power_cycle")
        api.assert_event(f"{MODE_MANAGER}.UnintendedRebootDetected", timeout=30)
    elif name == "test_lora_downlink_reaches_passthrough":
        client.request("radio_peer", max=65536)      # forget what was heard before the test
        pump = _RadioPump(client, state["pty"][0])
        pump.start()
    try:
        yield
    finally:
        if pump is not None:
            pump.stop()
        if before.get("soc") is not None and name in ("test_safe_05_auto_entry_low_voltage",
                                                      "test_safe_06_auto_recovery_voltage"):
            client.request("battery_soc", soc=before["soc"])


class _RadioPump(threading.Thread):
    """Copies what the simulated LoRa ground peer hears to the pseudo-terminal, twice a second."""

    def __init__(self, client: PlantClient, fd: int):
        super().__init__(name="lora-peer-pump", daemon=True)
        self.client = client
        self.fd = fd
        self._stop_event = threading.Event()

    def run(self) -> None:
        while not self._stop_event.wait(0.5):
            try:
                data = base64.b64decode(self.client.request("radio_peer", max=4096)["data"])
                if data:
                    os.write(self.fd, data)
            except (OSError, RuntimeError):
                time.sleep(0.5)

    def stop(self) -> None:
        self._stop_event.set()
        self.join(5)
