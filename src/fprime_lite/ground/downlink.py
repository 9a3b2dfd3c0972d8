"""Ground-side decoding of downlinked packets, and recorders that stream them to log files.

:class:`GroundDecoder` turns event and telemetry packets back into named, typed values using the
topology's own declarations (what fprime-gds does with the dictionary). :class:`GroundRecorder`
listens to the deployment's downlink (EventManager's and TlmChan's or TlmPacketizer's ``PktSend``;
a packetizer's packets through :mod:`fprime_lite.ground.packetized`) and writes
``events.log`` (one line per event: time, name, severity, text, as the GDS logs them) and
``channels.csv`` (time, channel, value) as packets arrive, and ``channels_wide.csv`` (one column per
channel, see :mod:`fprime_lite.ground.wide_table`), so memory stays flat however long the run.
Files are written under a temporary name and renamed into place when the recorder closes. Files
the deployment downlinks (``fileDownlink.SendFile``) are reassembled under ``downlink/`` by a
:class:`~fprime_lite.ground.files.FileReceiver`, as fprime-gds does in its downlink store.
"""

from __future__ import annotations

import csv
import enum
import json
import os
import pathlib
from collections import Counter
from itertools import chain
from dataclasses import dataclass
from typing import Any, Callable

from fprime_lite.model.errors import SerializationError
from fprime_lite.osal.atomic import clean_temporary_files, open_temporary
from fprime_lite.model.events import Severity, translate_format
from fprime_lite.ground.files import FileReceiver
from fprime_lite.ground.packet_layout import LayoutCache, TelemetryLayout
from fprime_lite.ground.packetized import PacketizedDecoder
from fprime_lite.ground.time_text import time_text
from fprime_lite.ground.wide_table import WideTelemetryTable, csv_cell, csv_field
from fprime_lite.wire.packets import Apid, decode_event, decode_telemetry
from fprime_lite.model.time import US_PER_S, Time
from fprime_lite.deploy.topology import Topology
from fprime_lite.model.types import deserialize_values

__all__ = ["GroundDecoder", "GroundRecorder", "DecodedEvent", "DecodedChannel", "format_time", "channel_text"]


@dataclass(frozen=True)
class DecodedEvent:
    time: Time
    name: str
    severity: Severity
    args: tuple
    text: str


@dataclass(frozen=True)
class DecodedChannel:
    time: Time
    name: str
    value: Any
    text: str


def format_time(t: Time) -> str:
    """UTC ISO 8601 for workstation (Unix) time; ``seconds.useconds`` for any other base
    (:func:`~fprime_lite.ground.time_text.time_text`)."""
    us = t.total_us
    return time_text(t.time_base, us // US_PER_S, us % US_PER_S)


def _plain(value):
    """A JSON-able form of a decoded value (enums by name, structs as dicts)."""
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if hasattr(value, "__dataclass_fields__"):
        return {k: _plain(getattr(value, k)) for k in value.__dataclass_fields__}
    if isinstance(value, Time):
        return format_time(value)
    return value


class GroundDecoder:
    """Decodes packets with the declarations of every instance in a topology."""

    def __init__(self, topology: Topology):
        self.events: dict[int, tuple[str, Any]] = {}
        self.channels: dict[int, tuple[str, Any, str | None]] = {}
        #: channel name → (F´ type, units or None), in declaration order
        self.channel_types: dict[str, tuple[Any, str | None]] = {}
        #: channel name → its update policy ("always" or "on change"), the dictionary's telemetryUpdate
        self.update_policies: dict[str, str] = {}
        for instance in topology.instances.values():
            comp = instance.component
            for e in comp.spec.events:
                self.events[comp.base_id + e.local_id] = (f"{instance.qualified_name}.{e.name}", e)
            for c in comp.spec.channels:
                template = translate_format(c.format, [c.type], c.name) if c.format else None
                self.channels[comp.base_id + c.local_id] = (f"{instance.qualified_name}.{c.name}", c.type, template)
                self.channel_types[f"{instance.qualified_name}.{c.name}"] = (c.type, getattr(c, "units", None))
                self.update_policies[f"{instance.qualified_name}.{c.name}"] = c.update
        packet_sets = list(getattr(topology, "telemetry_packet_sets", None) or [])
        #: the compiled layouts of the packet set the topology's TlmPacketizer flies (None without one)
        self.packetized: PacketizedDecoder | None = (
            PacketizedDecoder(packet_sets[0], self.channels, self.update_policies, channel_text)
            if packet_sets else None)

    def decode_event(self, packet: bytes) -> DecodedEvent:
        event_id, time, args = decode_event(packet)
        known = self.events.get(event_id)
        if known is None:
            raise SerializationError(f"event id 0x{event_id:X} is not in the dictionary")
        name, decl = known
        values = tuple(deserialize_values(decl.arg_types, args))
        return DecodedEvent(time, name, decl.severity, values, decl.render(values))

    def decode_telemetry(self, packet: bytes) -> list[DecodedChannel]:
        def value_end(channel_id, data, offset):
            known = self.channels.get(channel_id)
            if known is None:
                raise SerializationError(f"channel id 0x{channel_id:X} is not in the dictionary")
            return known[1].deserialize(data, offset)[1]

        out = []
        for channel_id, time, raw in decode_telemetry(packet, value_end):
            name, ftype, template = self.channels[channel_id]
            value = ftype.deserialize(raw)[0]
            out.append(DecodedChannel(time, name, value, channel_text(value, template)))
        return out

    def layout(self, packet: bytes, cells_of=None) -> TelemetryLayout | None:
        """The :class:`~fprime_lite.ground.packet_layout.TelemetryLayout` of telemetry ``packet``, or
        None when it has none (a string value, an unknown id, a malformed packet); ``cells_of`` as
        the layout takes it."""
        def value_end(channel_id, data, offset):
            known = self.channels.get(channel_id)
            if known is None:
                raise SerializationError(f"channel id 0x{channel_id:X} is not in the dictionary")
            return known[1].deserialize(data, offset)[1]

        try:
            records = decode_telemetry(packet, value_end)
            channels = [(cid, *self.channels[cid]) for cid, _, _ in records]
            if cells_of is None:
                return TelemetryLayout(channels, channel_text)
            return TelemetryLayout(channels, channel_text, cells_of)
        except (SerializationError, ValueError):
            return None


def channel_text(value, template: str | None) -> str:
    """A decoded channel value as ``channels.csv`` shows it: through the channel's format string when it
    has one, an enum by its constant's name, a float as ``repr``, a struct or array as JSON."""
    if template is not None:
        return template.format(value)
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, (int, float, str, bool)):
        return repr(value) if isinstance(value, float) else str(value)
    return json.dumps(_plain(value))


class StreamedFile:
    """A text file written under a temporary name and renamed into place on close."""

    def __init__(self, path: pathlib.Path, newline: str | None = None):
        self.path = path
        self.file, self.tmp = open_temporary(path, "w", encoding="utf-8", newline=newline)

    def close(self) -> None:
        if self.file.closed:
            return
        self.file.flush()
        os.fsync(self.file.fileno())
        self.file.close()
        os.replace(self.tmp, self.path)


class GroundRecorder:
    """Receives the downlink of a deployment and streams it to ``events.log`` and ``channels.csv``.

    Attach it to the ``PktSend`` ports of the event manager and the telemetry channelizer with
    :meth:`attach`. ``on_event`` and ``on_channel`` callbacks see every decoded item.
    """

    def __init__(self, topology: Topology, out_dir, *, on_event: Callable[[DecodedEvent], None] | None = None,
                 on_channel: Callable[[DecodedChannel], None] | None = None, clock=None,
                 telemetry_sink: Callable[[bytes, int], None] | None = None, telemetry_only: bool = False):
        """``clock`` (the deployment's, a :class:`~fprime_lite.model.time.Clock`) times the rows of
        ``channels_wide.csv`` by reception; without one a row is started whenever a channel's own
        time stamp changes.

        The two halves of a recorder split between processes (:mod:`fprime_lite.ground.writer_process`):
        with ``telemetry_sink`` (and a ``clock``) telemetry packets are not recorded here but handed to
        ``telemetry_sink(packet, reception_us)`` (µs of ``clock.now()``), and ``channels.csv`` and
        ``channels_wide.csv`` are not opened; ``telemetry_only`` records the telemetry alone (no
        ``events.log``)."""
        if telemetry_sink is not None and (clock is None or on_channel is not None or telemetry_only):
            raise ValueError("telemetry_sink needs a clock, no on_channel and not telemetry_only")
        self.decoder = GroundDecoder(topology)
        out_dir = pathlib.Path(out_dir)
        out_dir.mkdir(parents=True, exist_ok=True)
        clean_temporary_files(out_dir)  # what a killed recorder left (a live one's are kept)
        self._events = None if telemetry_only else StreamedFile(out_dir / "events.log")
        self._clock = clock
        self._sink = telemetry_sink
        if telemetry_sink is None:
            self._channels = StreamedFile(out_dir / "channels.csv", newline="")
            self._csv = csv.writer(self._channels.file, lineterminator="\n")
            self._csv.writerow(["time", "channel", "value"])
            self._wide_file = StreamedFile(out_dir / "channels_wide.csv", newline="")
            self._wide = WideTelemetryTable(self._wide_file.file, self.decoder.channel_types,
                                            start=clock.now() if clock is not None else None)
        self.on_event = on_event
        self.on_channel = on_channel
        self.events_by_severity: Counter = Counter()
        self.events_by_name: Counter = Counter()
        #: severity name → Counter of the event names downlinked at that severity
        self.event_names_by_severity: dict[str, Counter] = {}
        self.channel_updates = 0
        self.undecodable = 0
        #: Downlinked files, written under ``downlink/`` (the directory appears with the first file).
        self.files = FileReceiver(out_dir / "downlink")
        self._layouts = LayoutCache()
        #: layout → (wide-table column, number cell) of its plain numbers, and the wide table's columns
        #: of its other values' cells (those values in the layout's order, each one's cells in order)
        self._wide_plans: dict[TelemetryLayout, tuple[list[tuple[int, int]], list[int]]] = {}

    def attach(self, topology: Topology, event_manager: str | None, telemetry: str | None) -> None:
        """Tap ``PktSend`` of the named event manager and telemetry instances.

        An unconnected ``PktSend`` is connected to the recorder; a connected one (to a ground link,
        say) keeps its connection and the recorder sees each packet first.
        """
        for name in (event_manager, telemetry):
            if name:
                self._tap(topology.instance(name).component.output_port("PktSend"))

    def attach_file_downlink(self, topology: Topology, file_downlink: str | None) -> None:
        """Receive the file packets of the named FileDownlink's ``bufferSendOut``.

        As in :meth:`attach`, an existing connection keeps working and the recorder sees each
        packet first.
        """
        if file_downlink:
            self._tap(topology.instance(file_downlink).component.output_port("bufferSendOut"))

    def _tap(self, port) -> None:
        """Have :meth:`receive` see every packet of output ``port`` (index 0), before its target."""
        receive = self.receive
        if not port.is_connected(0):
            port.connect_callable(0, receive, "ground recorder")
            return
        downstream = port.calls[0]

        def tap(*args):
            receive(*args)
            return downstream(*args)

        port.calls[0] = tap
        port.targets[0] = f"ground recorder, then {port.target_name(0)}"

    def receive(self, data: bytes, context: int = 0) -> None:
        """Handle one downlinked packet (a Com buffer)."""
        try:
            descriptor = int.from_bytes(data[:2], "big")
            if self._sink is not None and (descriptor == Apid.FW_PACKET_TELEM or (
                    descriptor == Apid.FW_PACKET_PACKETIZED_TLM and self.decoder.packetized is not None)):
                self._sink(data, self._clock.now().total_us)
            elif descriptor == Apid.FW_PACKET_LOG:
                self._event(self.decoder.decode_event(data))
            elif descriptor == Apid.FW_PACKET_TELEM:
                if self.on_channel is not None or self._clock is None or not self._telemetry(data):
                    for channel in self.decoder.decode_telemetry(data):
                        self._channel(channel)
            elif descriptor == Apid.FW_PACKET_PACKETIZED_TLM and self.decoder.packetized is not None:
                self._packetized(data)
            elif descriptor == Apid.FW_PACKET_FILE:
                self.files.receive(data)
            else:
                self.undecodable += 1
        except SerializationError:
            self.undecodable += 1

    def _telemetry(self, packet: bytes) -> bool:
        """Record telemetry ``packet`` through its compiled layout; False when it has none (the caller
        then decodes it channel by channel)."""
        for layout in self._layouts.candidates(packet):
            decoded = layout.decode(packet)
            if decoded is not None:
                break
        else:
            learned = self.decoder.layout(packet, self._wide_cells)
            decoded = learned.decode(packet) if learned is not None else None
            if learned is None or decoded is None:
                return False
            layout = learned
            self._layouts.add(packet, layout)
            self._wide_plans[layout] = (
                [(index, cell) for name, cells in layout.simple
                 for (index, _), cell in zip(self._wide.slots(name), cells, strict=True)],
                # the other values' columns, in layout.complex's order, each value's in its slots' order
                [index for name, _ in layout.complex for index, _ in self._wide.slots(name)])
        lines, cells, wide = decoded
        self._channels.file.write(lines)
        self.channel_updates += layout.records
        row = self._wide.at(self._clock.now())
        simple, complex_ = self._wide_plans[layout]
        for index, cell in simple:
            row[index] = cells[cell]
        for index, text in zip(complex_, chain.from_iterable(wide), strict=True):
            row[index] = text
        return True

    def _packetized(self, packet: bytes) -> None:
        """Record a TlmPacketizer packet: the updates its compiled layout gives, stamped with the
        packet's time (:mod:`fprime_lite.ground.packetized`)."""
        assert self.decoder.packetized is not None  # receive() checked
        time, updates = self.decoder.packetized.decode(packet)
        if not updates:
            return
        stamp = f"{time.seconds}.{time.useconds:06d},"
        self._channels.file.write("".join(f"{stamp}{name},{csv_field(text)}\n" for name, _, text in updates))
        self.channel_updates += len(updates)
        row = self._wide.at(self._clock.now() if self._clock is not None else time)
        slots = self._wide.slots
        for name, value, text in updates:
            for index, get in slots(name):
                row[index] = csv_cell(get(value))
            if self.on_channel is not None:
                self.on_channel(DecodedChannel(time, name, value, text))

    def _wide_cells(self, name: str, value) -> list[str]:
        """The wide table's cells of a decoded value of channel ``name``."""
        return [csv_cell(get(value)) for _, get in self._wide.slots(name)]

    def _event(self, e: DecodedEvent) -> None:
        self.events_by_severity[e.severity.name] += 1
        self.events_by_name[e.name] += 1
        self.event_names_by_severity.setdefault(e.severity.name, Counter())[e.name] += 1
        assert self._events is not None, "a telemetry-only recorder got an event"
        self._events.file.write(f"{format_time(e.time)} {e.name} {e.severity.name} {e.text}\n")
        if self.on_event is not None:
            self.on_event(e)

    def _channel(self, c: DecodedChannel) -> None:
        self.channel_updates += 1
        self._csv.writerow([f"{c.time.seconds}.{c.time.useconds:06d}", c.name, c.text])
        self._wide.add(self._clock.now() if self._clock is not None else c.time, c.name, c.value)
        if self.on_channel is not None:
            self.on_channel(c)

    def close(self) -> None:
        if self._events is not None:
            self._events.close()
        if self._sink is None:
            self._channels.close()
            self._wide.close()
            self._wide_file.close()
        self.files.close()
