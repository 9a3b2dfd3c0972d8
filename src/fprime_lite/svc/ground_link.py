"""GroundLink: the flight side of the link to fprime-gds — TCP client, framing, routing.

One component plays the part of F´'s communication stack (``Drv.TcpClient`` + ``Svc.ComQueue`` +
framer/deframer + ``Svc.FprimeRouter``) in a deployment that runs on one thread:

- **Driver.** A *socket task* (one thread, started by :meth:`GroundLink.start_socket_task`)
  connects to the GDS as a TCP client, reconnects with exponential backoff when the link drops
  or the GDS is not up yet, receives and deframes uplinked bytes, and sends downlink frames. It
  never calls into the deployment: it only fills two thread-safe queues.
- **Uplink.** Complete command packets wait in the uplink queue until the next ``schedIn`` tick
  (a rate-group member), which hands at most :attr:`GroundLink.max_commands_per_tick` of them to
  ``commandOut`` (connected to ``cmdDisp.seqCmdBuff[k]``) on the deployment's own thread. So the
  rate groups never block on the network, the deployment stays single-threaded, and an uplinked
  command waits at most one period of the rate group (20 ms at 50 Hz) before dispatch.
- **File uplink.** File packets (``FW_PACKET_FILE``) wait in their own queue and ``schedIn``
  hands at most :attr:`GroundLink.max_file_packets_per_tick` of them, descriptor removed, to
  ``fileOut`` (connected to ``fileUplink.bufferSendIn``). The GDS sends a file as fast as TCP
  takes it, so when :attr:`GroundLink.max_file_backlog` packets are waiting the socket task stops
  reading and lets TCP flow control hold the GDS back: no file packet is ever dropped for lack
  of room (the backlog can exceed the limit by what one socket read brings, at most 64 KiB). With
  ``fileOut`` unconnected, file packets are dropped as an unknown descriptor. The stream's order
  between the two holds as on a board, where the serial line keeps a command's frame ahead of the
  file frames sent after it: a file packet that arrived behind a command handed out in this tick
  (or still waiting) waits for a later tick, so the command's handlers (a ``CreateDirectory`` the
  file is uplinked into) have run first.
- **Downlink.** ``comIn`` (connected to the ``PktSend`` of the event manager and of the telemetry
  channelizer) and ``fileIn`` (from ``fileDownlink.bufferSendOut``, file packets with their
  descriptor) only append the packet to the downlink queue and wake the socket task, which
  frames everything queued in one batch (CCSDS packs packets into 1024-byte TM frames) and sends
  it. While the link is down, up to :attr:`GroundLink.max_downlink_packets` packets are kept (the
  oldest are dropped beyond that) and sent once the GDS is back.
- **Robustness.** Keep-alives and noise between frames are skipped; a frame with a bad CRC, a bad
  length or an unknown descriptor is dropped with a throttled WARNING_LO event and the deframer
  resynchronises one byte after its start, so valid frames inside the bytes it claimed still get
  through. A frame that has started but not completed after :attr:`GroundLink.partial_frame_timeout_s`
  (a header claiming more bytes than will ever come) is abandoned (``IncompleteFrame``) and the
  frames behind it are delivered; when the connection drops, the frames already received behind a
  partial one are delivered before it is forgotten. Bytes of rejected frames are counted
  (``UplinkDroppedBytes``) and reported (``UplinkBytesDropped``, throttled). The link going
  away is a throttled WARNING_HI event, never a stop. No uplinked byte can raise into the
  deployment: the deframers never raise, and the command dispatcher answers malformed packets.

Throttled events are re-armed every :attr:`GroundLink.throttle_reset_s` seconds of deployment
time, as FPP's ``throttle N every {seconds=...}`` does.

The network stays on the loopback interface unless the user names another address; the
wildcard ``0.0.0.0`` (fprime-gds's default ``--ip-address``) means the local host.
"""

from __future__ import annotations

import collections
import logging
import select
import socket
import threading
import time as _time

from fprime_lite.model.component import PassiveComponent
from fprime_lite.model.events import Event, Severity
from fprime_lite.wire.framing import DropReason, Dropped, Framing, make_framing
from fprime_lite.model.fw_ports import BufferSend, CmdResponsePort, Com, Sched
from fprime_lite.wire.packets import Apid
from fprime_lite.model.ports import OutputPort, sync_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.types import U16, U32, U64, FwEnum, String

__all__ = ["GroundLink", "LinkState", "parse_address", "DEFAULT_HOST", "DEFAULT_PORT",
           "GROUND_LINK_BASE_ID", "GROUND_LINK_NAME"]

log = logging.getLogger("fprime_lite")

DEFAULT_HOST = "127.0.0.1"
#: fprime-gds ``--ip-port`` default.
DEFAULT_PORT = 50000
#: Base id of the link that :func:`add_ground_link` adds (clear of the reference deployment's ids).
GROUND_LINK_BASE_ID = 0x10070000
#: Instance name of the link that :func:`add_ground_link` adds.
GROUND_LINK_NAME = "comDriver"

_RECV_SIZE = 65536
_U32_MAX = 0xFFFFFFFF
_U64_MAX = (1 << 64) - 1


class LinkState(FwEnum, namespace="Svc.GroundLink"):
    """Whether the TCP connection to the ground is up."""

    DISCONNECTED = 0
    CONNECTED = 1


def parse_address(text: str | None, default_port: int = DEFAULT_PORT) -> tuple[str, int]:
    """``HOST:PORT``, ``HOST`` or ``PORT`` → ``(host, port)``; loopback when no host is given.

    Raises ValueError with a readable message for anything else.
    """
    if text is None or text == "":
        return DEFAULT_HOST, default_port
    host, sep, port_text = text.rpartition(":")
    if not sep:
        if text.isdigit():
            host, port_text = DEFAULT_HOST, text
        else:
            host, port_text = text, str(default_port)
    host = host.strip("[]") or DEFAULT_HOST
    try:
        port = int(port_text)
    except ValueError:
        raise ValueError(f"{text!r}: the port must be a number (HOST:PORT, e.g. 127.0.0.1:50000)") from None
    if not 0 < port < 65536:
        raise ValueError(f"{text!r}: port {port} is out of range 1..65535")
    return host, port


class GroundLink(PassiveComponent):
    """The ground link (instance ``comDriver`` in deployments).

    Args:
        name: instance name.
        base_id: added to the local event and channel ids.
        host: address of the GDS (default 127.0.0.1; ``0.0.0.0`` means the local host).
        port: TCP port of the GDS (fprime-gds ``--ip-port``, default 50000).
        framing: ``"ccsds"`` (fprime-gds's default, ``space-packet-space-data-link``) or
            ``"fprime"``, or a :class:`~fprime_lite.wire.framing.Framing`.
        reconnect_min_s: first wait before reconnecting (s); doubles after each failure.
        reconnect_max_s: longest wait between connection attempts (s).
        connect_timeout_s: how long one connection attempt may take (s).
        max_downlink_packets: packets kept for the downlink while the link is slow or down.
        max_uplink_packets: command packets kept until the deployment takes them.
        max_commands_per_tick: command packets handed to the dispatcher per ``schedIn`` tick
            (the dispatcher's queue holds 10 messages, responses included).
        max_file_packets_per_tick: file packets handed to ``fileOut`` per ``schedIn`` tick (keep
            it within the file uplink's queue size).
        max_file_backlog: file packets waiting for the deployment before the socket task stops
            reading from the GDS.
        throttle_reset_s: deployment seconds after which throttled events may be emitted again.
        partial_frame_timeout_s: wall-clock seconds a started frame may wait for its remaining bytes
            before it is abandoned and the deframer resynchronises (the GDS sends a frame in one
            write; raise it for slow links).
    """

    # --- ports ---------------------------------------------------------------------------------

    #: Uplinked command packets, to ``cmdDisp.seqCmdBuff[k]``.
    commandOut = OutputPort(Com)
    #: Uplinked file packets without their descriptor, to ``fileUplink.bufferSendIn``.
    fileOut = OutputPort(BufferSend)

    # --- events --------------------------------------------------------------------------------

    LinkConnected = Event(Severity.ACTIVITY_HI, "Connected to the ground system at {}:{}",
                          address=String(64), port=U16)
    LinkDisconnected = Event(Severity.WARNING_HI, "Lost the ground link: {}", reason=String(80), throttle=5)
    InvalidChecksum = Event(Severity.WARNING_LO, "Dropped an uplink frame of {} bytes: bad CRC (received 0x{x})",
                            size=U32, crc=U32, throttle=5)
    InvalidLength = Event(Severity.WARNING_LO, "Dropped an uplink frame: bad length {}", length=U32, throttle=5)
    UnknownDescriptor = Event(Severity.WARNING_LO,
                              "Dropped an uplink frame of {} bytes: unknown descriptor 0x{x}",
                              size=U32, descriptor=U32, throttle=5)
    DownlinkOverflow = Event(Severity.WARNING_LO, "Downlink queue full: {} packet(s) dropped so far",
                             dropped=U32, throttle=5)
    IncompleteFrame = Event(Severity.WARNING_LO,
                            "Abandoned an uplink frame after {} bytes: it never completed; resynchronised",
                            received=U32, throttle=5)
    UplinkBytesDropped = Event(Severity.WARNING_LO,
                               "Uplink resynchronised: {} byte(s) of rejected frames dropped ({} so far)",
                               dropped=U32, total=U64, throttle=5)

    # --- telemetry (all U32/U64 counts since start) --------------------------------------------

    State = Channel(LinkState, update="on change")
    Connections = Channel(U32, update="on change")  # connections established (1 + reconnects)
    UplinkFrames = Channel(U32, update="on change")  # frames accepted
    UplinkBytes = Channel(U64, update="on change")  # bytes received, keep-alives included
    UplinkDropped = Channel(U32, update="on change")  # frames dropped (CRC, length, descriptor)
    UplinkSkippedBytes = Channel(U64, update="on change")  # bytes skipped between frames
    DownlinkFrames = Channel(U32, update="on change")  # frames sent
    DownlinkBytes = Channel(U64, update="on change")  # bytes sent
    DownlinkDropped = Channel(U32, update="on change")  # packets dropped (queue full)
    CommandsForwarded = Channel(U32, update="on change")  # packets handed to the dispatcher
    FilePacketsForwarded = Channel(U32, update="on change")  # packets handed to the file uplink
    UplinkDroppedBytes = Channel(U64, update="on change")  # bytes of rejected frames not delivered

    def __init__(self, name: str = GROUND_LINK_NAME, *, base_id: int = 0, host: str = DEFAULT_HOST,
                 port: int = DEFAULT_PORT, framing: str | Framing = "ccsds", reconnect_min_s: float = 0.1,
                 reconnect_max_s: float = 2.0, connect_timeout_s: float = 2.0,
                 max_downlink_packets: int = 2048, max_uplink_packets: int = 64,
                 max_commands_per_tick: int = 4, max_file_packets_per_tick: int = 16,
                 max_file_backlog: int = 1024, throttle_reset_s: float = 60.0,
                 partial_frame_timeout_s: float = 1.0):
        super().__init__(name, base_id=base_id)
        if not 0 < port < 65536:
            raise ValueError(f"{name}: port {port} is out of range 1..65535")
        if not 0 < reconnect_min_s <= reconnect_max_s:
            raise ValueError(f"{name}: need 0 < reconnect_min_s <= reconnect_max_s")
        for label, value in (("max_downlink_packets", max_downlink_packets),
                             ("max_uplink_packets", max_uplink_packets),
                             ("max_commands_per_tick", max_commands_per_tick),
                             ("max_file_packets_per_tick", max_file_packets_per_tick),
                             ("max_file_backlog", max_file_backlog)):
            if not isinstance(value, int) or value < 1:
                raise ValueError(f"{name}: {label} must be a positive integer, got {value!r}")
        self.host = DEFAULT_HOST if host in ("", "0.0.0.0") else host
        self.port = port
        self.framing = make_framing(framing) if isinstance(framing, str) else framing
        self.reconnect_min_s = reconnect_min_s
        self.reconnect_max_s = reconnect_max_s
        self.connect_timeout_s = connect_timeout_s
        self.max_downlink_packets = max_downlink_packets
        self.max_uplink_packets = max_uplink_packets
        self.max_commands_per_tick = max_commands_per_tick
        self.max_file_packets_per_tick = max_file_packets_per_tick
        self.max_file_backlog = max_file_backlog
        self.throttle_reset_s = throttle_reset_s
        if not partial_frame_timeout_s > 0:
            raise ValueError(f"{name}: partial_frame_timeout_s must be positive, got {partial_frame_timeout_s!r}")
        self.partial_frame_timeout_s = partial_frame_timeout_s
        self._partial: tuple[int, float] | None = None  # (stream offset, monotonic s first seen)
        self._reported_dropped_bytes = 0

        # Shared with the socket task. deque append/popleft are atomic; the counts below are each
        # written by one thread only and read by the other (ints: no torn reads in CPython).
        self._downlink: collections.deque[bytes] = collections.deque()
        self._uplink: collections.deque[tuple[int, bytes]] = collections.deque()
        self._file_uplink: collections.deque[tuple[int, bytes]] = collections.deque()
        self._arrivals = 0  # uplinked items received (socket task): their order in the stream
        self._notices: collections.deque[tuple] = collections.deque(maxlen=64)
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._wake_r, self._wake_w = socket.socketpair()
        self._wake_r.setblocking(False)
        self._wake_w.setblocking(False)
        self._deframer = self.framing.uplink_deframer()
        self._connected = threading.Event()
        self._flush_before_stop = 0.0  # s the socket task may spend sending what is queued when stopped
        # written by the socket task
        self.connections = 0
        self.connect_attempts = 0
        self.uplink_bytes = 0
        self.downlink_frames = 0
        self.downlink_bytes = 0
        self.uplink_overflow = 0
        self.uplink_unroutable = 0  # file packets with nowhere to go (fileOut unconnected)
        # written by the deployment's thread
        self.downlink_overflow = 0
        self.commands_forwarded = 0
        self.file_packets_forwarded = 0
        self.responses: collections.Counter = collections.Counter()
        self._last_reset_us: int | None = None
        self._reported_overflow = 0

    # --- ports ---------------------------------------------------------------------------------

    @sync_input(Com)
    def comIn(self, data: bytes, context: int) -> None:
        """Queue one downlink packet (an event or telemetry packet) for the socket task."""
        queue = self._downlink
        if len(queue) >= self.max_downlink_packets:
            queue.popleft()
            self.downlink_overflow += 1
        queue.append(bytes(data))
        self._wake()

    @sync_input(BufferSend)
    def fileIn(self, fwBuffer: bytes) -> None:
        """Queue one downlink file packet (``FW_PACKET_FILE`` descriptor first) for the socket task."""
        self.comIn(fwBuffer, 0)

    @sync_input(CmdResponsePort)
    def cmdResponseIn(self, opcode: int, cmd_seq: int, response) -> None:
        """The dispatcher's answer to an uplinked command (counted; the GDS sees the events)."""
        self.responses[getattr(response, "name", str(response))] += 1

    @sync_input(Sched)
    def schedIn(self, context: int) -> None:
        """Rate-group tick: report link changes and drops, forward commands, write telemetry."""
        self._rearm_throttles()
        notices = self._notices
        while notices:
            self._report(notices.popleft())
        uplink = self._uplink
        barrier = uplink[0][0] if uplink else None  # arrival number of the first command of this tick
        for _ in range(min(len(uplink), self.max_commands_per_tick)):
            packet = uplink.popleft()[1]
            if self.is_connected("commandOut", 0):
                self.commandOut[0](packet, self.commands_forwarded & _U32_MAX)
                self.commands_forwarded += 1
        files = self._file_uplink
        if files:
            backed_up = len(files) >= self.max_file_backlog
            for _ in range(min(len(files), self.max_file_packets_per_tick)):
                if barrier is not None and files[0][0] > barrier:
                    break  # behind a command in the stream: after that command's handlers
                self.fileOut[0](files.popleft()[1][2:])
                self.file_packets_forwarded += 1
            if backed_up:
                self._wake()  # the socket task may read again
        dropped_bytes = self._deframer.dropped_bytes
        if dropped_bytes != self._reported_dropped_bytes:
            self.UplinkBytesDropped((dropped_bytes - self._reported_dropped_bytes) & _U32_MAX,
                                    dropped_bytes & _U64_MAX)
            self._reported_dropped_bytes = dropped_bytes
        if self.downlink_overflow != self._reported_overflow:
            self._reported_overflow = self.downlink_overflow
            self.DownlinkOverflow(self.downlink_overflow & _U32_MAX)
        self._write_telemetry()

    # --- the socket task -----------------------------------------------------------------------

    @property
    def connected(self) -> bool:
        """Whether the TCP connection is up (as the socket task last saw it)."""
        return self._connected.is_set()

    def wait_connected(self, timeout: float) -> bool:
        """Block until connected or ``timeout`` seconds passed; return whether connected."""
        return self._connected.wait(timeout)

    def start_socket_task(self) -> None:
        """Start the thread that connects, reconnects, receives and sends."""
        if self._thread is not None:
            raise RuntimeError(f"{self.name}: the socket task is already running")
        self._stop.clear()
        self._thread = threading.Thread(target=self._socket_task, name=f"{self.name}-socket", daemon=True)
        self._thread.start()

    def stop_socket_task(self, timeout: float = 5.0) -> None:
        """Send what is queued (for up to ``timeout`` s, if connected), close the connection, stop."""
        if self._thread is None:
            return
        self._flush_before_stop = timeout
        self._stop.set()
        self._wake()
        self._thread.join(timeout + 1.0)
        self._thread = None

    def close(self) -> None:
        """Stop the socket task and release the wake-up sockets."""
        self.stop_socket_task()
        for s in (self._wake_r, self._wake_w):
            s.close()

    def _wake(self) -> None:
        try:
            self._wake_w.send(b"\0")
        except (BlockingIOError, OSError):
            pass  # already signalled (buffer full) or closing

    def _socket_task(self) -> None:
        delay = self.reconnect_min_s
        while not self._stop.is_set():
            self.connect_attempts += 1
            try:
                sock = socket.create_connection((self.host, self.port), timeout=self.connect_timeout_s)
            except OSError as exc:
                log.debug("%s: cannot connect to %s:%d: %s", self.name, self.host, self.port, exc)
                self._stop.wait(delay)
                delay = min(delay * 2, self.reconnect_max_s)
                continue
            delay = self.reconnect_min_s
            self.connections += 1
            self._connected.set()
            self._notices.append(("connected",))
            try:
                reason = self._serve(sock)
            except Exception as exc:  # noqa: BLE001 - the task must survive anything and reconnect
                log.warning("%s: socket task fault (reported at the next schedIn): %s", self.name, exc)
                self._notices.append(("fault", exc))  # report_fault runs on the deployment's thread
                reason = f"{type(exc).__name__}: {exc}"
            finally:
                self._connected.clear()
                try:
                    sock.close()
                except OSError:
                    pass
                self._deliver(self._deframer.reset())  # frames received behind a partial one
                self._partial = None
            if reason is not None:
                self._notices.append(("disconnected", reason))
                self._stop.wait(self.reconnect_min_s)

    def _serve(self, sock: socket.socket) -> str | None:
        """Move bytes until the connection ends; return why (None: asked to stop)."""
        sock.setblocking(False)
        try:
            sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        except OSError:
            pass
        out = bytearray()
        stopping_deadline = None
        while True:
            if self._stop.is_set():
                if stopping_deadline is None:
                    stopping_deadline = _time.monotonic() + self._flush_before_stop
                if not (out or self._downlink) or _time.monotonic() > stopping_deadline:
                    return None
            if not out and self._downlink:
                out += self._frame_pending()
            # With too many file packets waiting, leave the socket unread: TCP holds the GDS back.
            reading = [sock, self._wake_r] if len(self._file_uplink) < self.max_file_backlog else [self._wake_r]
            try:
                readable, writable, _ = select.select(reading, [sock] if out else [], [], 0.5)
            except (OSError, ValueError) as exc:
                return f"select failed: {exc}"
            if self._wake_r in readable:
                try:
                    while self._wake_r.recv(4096):
                        pass
                except (BlockingIOError, OSError):
                    pass
            if sock in readable:
                try:
                    data = sock.recv(_RECV_SIZE)
                except (BlockingIOError, InterruptedError):
                    data = None
                except OSError as exc:
                    return f"receive failed: {exc}"
                if data == b"":
                    return "the ground system closed the connection"
                if data:
                    self.uplink_bytes += len(data)
                    self._received(data)
            self._expire_partial_frame()
            if out and sock in writable:
                try:
                    sent = sock.send(out)
                except (BlockingIOError, InterruptedError):
                    sent = 0
                except OSError as exc:
                    return f"send failed: {exc}"
                del out[:sent]
                self.downlink_bytes += sent

    def _frame_pending(self) -> bytes:
        packets: list[bytes] = []
        queue = self._downlink
        while queue and len(packets) < 256:
            packets.append(queue.popleft())
        try:
            frames = self.framing.frame_downlink(packets)  # one batch: CCSDS packs them into shared frames
        except ValueError:  # a packet too large for the framing: send the others, never that one
            frames = []
            for packet in packets:
                try:
                    frames += self.framing.frame_downlink([packet])
                except ValueError as exc:
                    log.warning("%s: cannot frame a downlink packet of %d bytes: %s", self.name, len(packet), exc)
        self.downlink_frames += len(frames)
        return b"".join(frames)

    def _expire_partial_frame(self) -> None:
        """Abandon a started frame that has waited longer than partial_frame_timeout_s."""
        pending = self._deframer.pending_offset
        if pending is None:
            self._partial = None
            return
        now = _time.monotonic()
        if self._partial is None or self._partial[0] != pending:
            self._partial = (pending, now)
        elif now - self._partial[1] >= self.partial_frame_timeout_s:
            self._partial = None
            self._deliver(self._deframer.expire())

    def _received(self, data: bytes) -> None:
        self._deliver(self._deframer.push(data))

    def _deliver(self, items) -> None:
        uplink = self._uplink
        for item in items:
            self._arrivals += 1
            if isinstance(item, Dropped):
                self._notices.append(("dropped", item))
            elif item[1] == Apid.FW_PACKET_FILE and item[0] == 0:
                if self.is_connected("fileOut", 0):
                    self._file_uplink.append((self._arrivals, item))  # bounded by not reading (see _serve)
                else:
                    self.uplink_unroutable += 1
                    self._notices.append(("dropped", Dropped(DropReason.UNKNOWN_DESCRIPTOR, len(item),
                                                             Apid.FW_PACKET_FILE)))
            elif len(uplink) >= self.max_uplink_packets:
                self.uplink_overflow += 1
            else:
                uplink.append((self._arrivals, item))

    # --- reporting (deployment thread) ---------------------------------------------------------

    def _report(self, notice: tuple) -> None:
        kind = notice[0]
        if kind == "connected":
            self.LinkConnected(self.host[:64], self.port)
        elif kind == "disconnected":
            self.LinkDisconnected(notice[1][:80])
        elif kind == "fault":
            self.report_fault("socket task", notice[1])
        elif kind == "dropped":
            drop: Dropped = notice[1]
            if drop.reason is DropReason.BAD_CRC:
                self.InvalidChecksum(drop.size & _U32_MAX, drop.value & _U32_MAX)
            elif drop.reason is DropReason.INCOMPLETE:
                self.IncompleteFrame(drop.value & _U32_MAX)
            elif drop.reason is DropReason.BAD_LENGTH:
                self.InvalidLength(drop.value & _U32_MAX)
            else:
                self.UnknownDescriptor(drop.size & _U32_MAX, drop.value & _U32_MAX)

    def _rearm_throttles(self) -> None:
        now = self.get_time().total_us
        if self._last_reset_us is None or now < self._last_reset_us:
            self._last_reset_us = now
        elif now - self._last_reset_us >= self.throttle_reset_s * 1e6:
            self._last_reset_us = now
            for event in (self.LinkDisconnected, self.InvalidChecksum, self.InvalidLength,
                          self.UnknownDescriptor, self.DownlinkOverflow, self.IncompleteFrame,
                          self.UplinkBytesDropped):
                event.clear_throttle()

    def _write_telemetry(self) -> None:
        deframer = self._deframer
        self.State.write(LinkState.CONNECTED if self.connected else LinkState.DISCONNECTED)
        self.Connections.write(self.connections & _U32_MAX)
        self.UplinkFrames.write(deframer.frames & _U32_MAX)
        self.UplinkBytes.write(self.uplink_bytes & _U64_MAX)
        self.UplinkDropped.write((deframer.dropped + self.uplink_unroutable) & _U32_MAX)
        self.UplinkSkippedBytes.write(deframer.skipped_bytes & _U64_MAX)
        self.DownlinkFrames.write(self.downlink_frames & _U32_MAX)
        self.DownlinkBytes.write(self.downlink_bytes & _U64_MAX)
        self.DownlinkDropped.write(self.downlink_overflow & _U32_MAX)
        self.CommandsForwarded.write(self.commands_forwarded & _U32_MAX)
        self.FilePacketsForwarded.write(self.file_packets_forwarded & _U32_MAX)
        self.UplinkDroppedBytes.write(deframer.dropped_bytes & _U64_MAX)
