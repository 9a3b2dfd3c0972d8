"""The plant-control side channel: a test process on this machine drives the simulated spacecraft.

What a bench operator does to a real board — lower the battery voltage with a bench supply,
pull the power, listen with a LoRa receiver — a test does here through this channel, while the
flight software runs and the GDS is connected (the PROVES suite's "manual" tests, through the
pytest plugin :mod:`detumble.tools.pytest_plant`).

Enabled only when the environment variable ``FPRIME_LITE_PLANT_CONTROL`` is ``HOST:PORT`` with a
loopback HOST (127.0.0.1, ::1 or localhost; anything else is refused at start-up). The deployment
then listens there (TCP, from its first 100 ms of flight) for one client at a time. Protocol: one
JSON object per line, at most 4096 bytes; each request gets one JSON line back, ``{"ok": true, ...}`` or ``{"ok": false,
"error": "..."}``. Requests are queued (at most 16 waiting; more are answered "busy") and carried
out on the deployment's own thread by a poll every 100 ms of deployment time, so nothing races the
flight software; a reply not ready within 10 s of wall time is answered "timeout".

With ``FPRIME_LITE_RTC=wall`` as well, the flight computer's real-time clock starts at the wall
clock's UTC instead of the scenario's epoch (a bench board's RTC, set and battery-backed, as the
PROVES suite's ``start=datetime.now()`` event searches assume); the orbit and the Sun stay the
scenario's, so the lighting is the scenario's.

Requests (``op``):

* ``status`` → ``bus_v``, ``soc``, ``resets``, ``burnwire_on``;
* ``battery_soc`` with ``soc`` (0…1) → sets the battery's state of charge (its open-circuit voltage
  follows: 2S NMC, 6.0 V empty … 8.4 V full) and answers the new ``ocv_v``;
* ``power_cycle`` → pulls the flight computer's reset line without warning the software (what
  cutting the power does: no clean-shutdown flag);
* ``radio_peer`` with ``max`` (bytes, ≤ 65536) → ``data`` (base64) of what the simulated LoRa ground
  peer heard since the last call.
"""

from __future__ import annotations

import base64
import json
import os
import queue
import socket
import sys
import threading
import time

from fprime_lite.deploy.resources import topology_resource
from fprime_lite.deploy.scheduler import Scheduler

from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["PlantControl", "make_plant_control", "ENV_VAR", "MAX_LINE", "MAX_PENDING", "parse_address"]

ENV_VAR = "FPRIME_LITE_PLANT_CONTROL"
RTC_ENV_VAR = "FPRIME_LITE_RTC"
MAX_LINE = 4096
MAX_PENDING = 16
POLL_US = 100_000
REPLY_TIMEOUT_S = 10.0
_LOOPBACK = {"127.0.0.1", "::1", "localhost"}


def parse_address(text: str) -> tuple[str, int]:
    """``HOST:PORT`` with a loopback host → (host, port); ValueError otherwise."""
    host, sep, port = text.rpartition(":")
    host = host.strip("[]")
    if not sep or host not in _LOOPBACK or not port.isdigit() or not 0 < int(port) < 65536:
        raise ValueError(f"{ENV_VAR}={text!r}: expected HOST:PORT with a loopback host (127.0.0.1, ::1 "
                         f"or localhost) and a port 1..65535")
    return host, int(port)


class PlantControl:
    """Serves plant-control requests for ``spacecraft`` (see the module doc)."""

    def __init__(self, spacecraft: SimulatedSpacecraft, scheduler: Scheduler, address: str | None):
        self.spacecraft = spacecraft
        self.scheduler = scheduler
        self.address = address
        self.requests: queue.Queue = queue.Queue(MAX_PENDING)
        self.served = 0
        self._server: socket.socket | None = None
        self._listen = parse_address(address) if address else None
        if self._listen is not None:
            # the socket opens at the first poll, when the deployment flies (not when `dict` or `check`
            # merely build the topology)
            scheduler.call_every(POLL_US, self.poll)
            if os.environ.get(RTC_ENV_VAR) == "wall":
                clock = scheduler.clock
                clock.epoch_us = round(time.time() * 1e6) - clock.current_us

    def _open(self) -> None:
        assert self._listen is not None
        host, port = self._listen
        server = socket.socket(socket.AF_INET6 if ":" in host else socket.AF_INET, socket.SOCK_STREAM)
        server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        server.bind((host, port))
        server.listen(1)
        self._server = server
        threading.Thread(target=self._accept, name="plant-control", daemon=True).start()

    # --- deployment thread ------------------------------------------------------------------------

    def poll(self) -> None:
        """Carry out the waiting requests (on the deployment's thread); the first poll opens the socket
        (a port that cannot be bound is reported on stderr once and the channel stays closed)."""
        if self._server is None and self._listen is not None:
            try:
                self._open()
            except OSError as exc:
                print(f"plant control: cannot listen on {self.address}: {exc}", file=sys.stderr)
                self._listen = None
                return
        while True:
            try:
                request, reply = self.requests.get_nowait()
            except queue.Empty:
                return
            try:
                reply.put(self.handle(request))
            except Exception as exc:  # noqa: BLE001 — a bad request must not reach the scheduler
                reply.put({"ok": False, "error": f"{type(exc).__name__}: {exc}"})
            self.served += 1

    def handle(self, request: dict) -> dict:
        """One request → its reply (see the module doc for the requests)."""
        craft = self.spacecraft
        op = request.get("op")
        power = craft.power
        if op == "status":
            return {"ok": True, "bus_v": power.bus_v if power else None,
                    "soc": power.battery.soc if power else None, "resets": craft.resets,
                    "burnwire_on": craft.burnwire_on}
        if op == "battery_soc":
            soc = request.get("soc")
            if power is None:
                return {"ok": False, "error": "the scenario has no electrical system"}
            if not isinstance(soc, (int, float)) or not 0.0 <= soc <= 1.0:
                return {"ok": False, "error": f"soc must be a number 0..1, got {soc!r}"}
            craft.sync()
            bat = power.battery
            bat.energy_j = float(soc) * bat.capacity_j
            return {"ok": True, "ocv_v": bat.ocv()}
        if op == "power_cycle":
            craft.request_reset("power")
            return {"ok": True}
        if op == "radio_peer":
            limit = request.get("max", 65536)
            if not isinstance(limit, int) or not 0 < limit <= 65536:
                return {"ok": False, "error": f"max must be an integer 1..65536, got {limit!r}"}
            peer = craft.radio_peer
            data = bytes(peer.popleft() for _ in range(min(limit, len(peer))))
            return {"ok": True, "data": base64.b64encode(data).decode("ascii")}
        return {"ok": False, "error": f"unknown op {op!r}; ops: status, battery_soc, power_cycle, radio_peer"}

    # --- socket thread ----------------------------------------------------------------------------

    def _accept(self) -> None:
        assert self._server is not None
        while True:
            try:
                conn, _ = self._server.accept()
            except OSError:
                return
            with conn:
                self._serve(conn)

    def _serve(self, conn: socket.socket) -> None:
        reader = conn.makefile("rb")
        while True:
            try:
                line = reader.readline(MAX_LINE + 1)
            except OSError:
                return
            if not line:
                return
            if len(line) > MAX_LINE:
                self._send(conn, {"ok": False, "error": f"request longer than {MAX_LINE} bytes"})
                return
            try:
                request = json.loads(line)
                if not isinstance(request, dict):
                    raise ValueError("a request is a JSON object")
            except ValueError as exc:
                self._send(conn, {"ok": False, "error": f"bad request: {exc}"})
                continue
            reply: queue.Queue = queue.Queue(1)
            try:
                self.requests.put_nowait((request, reply))
            except queue.Full:
                self._send(conn, {"ok": False, "error": "busy: too many requests waiting"})
                continue
            try:
                answer = reply.get(timeout=REPLY_TIMEOUT_S)
            except queue.Empty:
                answer = {"ok": False, "error": "timeout: the deployment did not answer"}
            if not self._send(conn, answer):
                return

    @staticmethod
    def _send(conn: socket.socket, answer: dict) -> bool:
        try:
            conn.sendall(json.dumps(answer).encode() + b"\n")
            return True
        except OSError:
            return False


@topology_resource
def make_plant_control(spacecraft: SimulatedSpacecraft, scheduler: Scheduler) -> PlantControl:
    """The side channel, listening where ``FPRIME_LITE_PLANT_CONTROL`` says (idle when it is unset)."""
    require_spacecraft("plant_control", spacecraft)
    return PlantControl(spacecraft, scheduler, os.environ.get(ENV_VAR) or None)
