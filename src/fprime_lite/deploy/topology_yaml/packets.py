"""The ``telemetry_packets`` section: a topology's packet set, checked against its channels and handed
to the TlmPacketizer instance that flies it (FPP's ``telemetry packets`` … ``omit`` in YAML).

.. code-block:: yaml

    telemetry_packets:
      name: ReferenceDeploymentPackets   # the packet set's name in the dictionary
      instance: CdhCore.tlmSend          # a Svc.TlmPacketizer (fprime_lite.svc.tlm_packetizer)
      start_level: 1                     # packets of group <= this are sent from start-up
      packets:
        Beacon: {id: 1, group: 1, channels: [ReferenceDeployment.modeManager.CurrentMode]}
      omit: [CdhCore.cmdDisp.CommandErrors]   # or `omit: rest`: every channel in no packet

Every channel of the topology must be in a packet or omitted (as FPP requires), unless ``omit: rest``.
The set goes into the dictionary's ``telemetryPacketSets`` in fpp-to-dict's shape (packets by id).
"""

from __future__ import annotations

from typing import Any

from fprime_lite.deploy.topology import Topology
from fprime_lite.deploy.topology_yaml.problems import Problems
from fprime_lite.deploy.topology_yaml.schema import TopologyConfig
from fprime_lite.model.errors import did_you_mean

__all__ = ["configure_packets"]

PACKETS_KEYS = {"name", "instance", "start_level", "packets", "omit"}
PACKET_KEYS = {"id", "group", "channels"}
#: Largest packet id (FwTlmPacketizeIdType is U16) and group (F´'s levels are FwChanIdType, U32).
MAX_PACKET_ID = 0xFFFF
MAX_GROUP = 0xFFFFFFFF


def _uint(value: Any, top: int) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and 0 <= value <= top


def configure_packets(config: TopologyConfig, topology: Topology, problems: Problems) -> None:
    """Check ``config.telemetry_packets`` against ``topology``'s channels; on success set
    ``topology.telemetry_packet_sets`` and the packetizer's packet list, else add problems."""
    section, line, path = config.telemetry_packets, config.telemetry_packets_line, config.path
    if section is None:
        return
    add = lambda where, message: problems.add(path, where, message)  # noqa: E731 - a short local alias
    section = problems.expect_map(path, section, line, "'telemetry_packets'")
    if section is None:
        return
    problems.check_keys(path, section, PACKETS_KEYS, "'telemetry_packets'")
    lines = section.key_lines
    name = section.get("name")
    if not isinstance(name, str) or not name.isidentifier():
        add(lines.get("name", line), "'telemetry_packets.name' must name the packet set — give an identifier, "
                                     "e.g. ReferenceDeploymentPackets")
        return
    instance_name = section.get("instance")
    instance = topology.instances.get(instance_name) if isinstance(instance_name, str) else None
    if instance is None:
        add(lines.get("instance", line), f"'telemetry_packets.instance': no instance {instance_name!r} — "
            + did_you_mean(instance_name, topology.instances, "name the TlmPacketizer instance as Module.instance"))
        return
    packetizer: Any = instance.component
    if not callable(getattr(packetizer, "set_packet_list", None)):
        add(lines.get("instance", line), f"'telemetry_packets.instance': {instance_name} is a "
            f"{type(packetizer).__name__}, which does not packetize — make it a "
            f"fprime_lite.svc.tlm_packetizer.TlmPacketizer")
        return
    start_level = section.get("start_level", 0)
    if not _uint(start_level, MAX_GROUP):
        add(lines.get("start_level", line), f"'telemetry_packets.start_level' must be a non-negative integer "
                                            f"(a group), got {start_level!r} — e.g. 1")
        return

    channels: dict[str, int] = {}
    for inst in topology.instances.values():
        comp = inst.component
        for ch in comp.spec.channels:
            channels[f"{inst.qualified_name}.{ch.name}"] = comp.base_id + ch.local_id
    before = len(problems)

    def channel_names(value: Any, where: int | None, what: str) -> list[str]:
        if not isinstance(value, list):
            add(where, f"{what} must be a list of channel names (Module.instance.Channel)")
            return []
        out = []
        for item in value:
            if not isinstance(item, str) or item not in channels:
                add(getattr(item, "line", where), f"{what}: no channel {item!r} in the topology — "
                    + did_you_mean(item, channels, "write Module.instance.Channel as the dictionary names it"))
            else:
                out.append(str(item))
        return out

    packets = problems.expect_map(path, section.get("packets"), lines.get("packets", line),
                                  "'telemetry_packets.packets'")
    members: list[dict[str, Any]] = []
    ids: set[int] = set()
    packet_lines = packets.key_lines if packets is not None else {}
    for packet_name, packet in (packets.items() if packets is not None else ()):
        pline = packet_lines.get(packet_name)
        what = f"packet '{packet_name}'"
        if not isinstance(packet_name, str) or not packet_name.isidentifier():
            add(pline, f"packet name {packet_name!r} must be an identifier — rename it")
            continue
        packet = problems.expect_map(path, packet, pline, what)
        if packet is None:
            continue
        problems.check_keys(path, packet, PACKET_KEYS, what)
        packet_id: Any = packet.get("id")
        group = packet.get("group")
        if not _uint(packet_id, MAX_PACKET_ID):
            add(packet.key_lines.get("id", pline),
                f"{what}: 'id' must be an integer 0..{MAX_PACKET_ID}, got {packet_id!r}")
            continue
        if packet_id in ids:
            add(packet.key_lines.get("id", pline), f"{what}: id {packet_id} is already another packet's — give "
                                                   f"each packet its own id")
            continue
        ids.add(packet_id)
        if not _uint(group, MAX_GROUP):
            add(packet.key_lines.get("group", pline), f"{what}: 'group' must be a non-negative integer, got {group!r}")
            continue
        names = channel_names(packet.get("channels"), packet.key_lines.get("channels", pline), what)
        members.append({"name": packet_name, "id": packet_id, "group": group, "members": names})

    used = {n for packet in members for n in packet["members"]}
    omit = section.get("omit", [])
    if omit == "rest":
        omitted = [n for n in channels if n not in used]
    else:
        omitted = channel_names(omit, lines.get("omit", line), "'telemetry_packets.omit'")
        both = sorted(used.intersection(omitted))
        if both:
            add(lines.get("omit", line), f"'telemetry_packets.omit' lists channel(s) also in a packet: "
                                         f"{', '.join(both)} — remove them from one of the two")
        missing = [n for n in channels if n not in used and n not in omitted]
        if missing:
            shown = ", ".join(missing[:5]) + (f" and {len(missing) - 5} more" if len(missing) > 5 else "")
            add(line, f"'telemetry_packets': channel(s) in no packet and not omitted: {shown} — add them to "
                      f"a packet or to 'omit' (or write 'omit: rest')")
    if len(problems) > before:
        return
    packet_set = {"name": name, "members": sorted(members, key=lambda p: p["id"]),
                  "omitted": sorted(omitted, key=channels.__getitem__)}
    from fprime_lite.svc.tlm_packetizer import packet_list  # the packetizer module only where it flies

    try:
        specs, omitted_ids = packet_list(topology, packet_set)
        packetizer.set_packet_list(specs, omitted_ids, start_level)
    except (TypeError, ValueError) as exc:  # a type without a known size, a packet too large
        add(line, f"'telemetry_packets': {exc}")
        return
    topology.telemetry_packet_sets = [packet_set]
