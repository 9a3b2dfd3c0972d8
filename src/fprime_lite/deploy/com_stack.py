"""Adding the ground link to a loaded topology, wired as F´ wires its com stack."""
from __future__ import annotations

from fprime_lite.deploy.topology import TopologyError
from fprime_lite.svc.file_downlink import FileDownlink
from fprime_lite.svc.file_uplink import FileUplink
from fprime_lite.svc.ground_link import (DEFAULT_HOST, DEFAULT_PORT, GROUND_LINK_BASE_ID, GROUND_LINK_NAME,
                                         Framing, GroundLink)
from fprime_lite.svc.rate_groups import RateGroupBase

__all__ = ["add_ground_link"]


def add_ground_link(topology, *, host: str = DEFAULT_HOST, port: int = DEFAULT_PORT,
                    framing: str | Framing = "ccsds", module: str | None = None, name: str = GROUND_LINK_NAME,
                    base_id: int | None = None, rate_group: str | None = None, **link_args) -> GroundLink:
    """Add a :class:`GroundLink` to a loaded topology and wire it as F´ wires its com stack.

    - events and telemetry: the ``PktSend`` of the topology's ``event`` and ``telemetry`` services
      connect to ``comIn``;
    - commands: ``commandOut`` connects to the first free ``seqCmdBuff[k]`` of the ``command``
      service, whose ``seqCmdStatus[k]`` answers on ``cmdResponseIn``;
    - files: ``fileOut`` connects to the ``bufferSendIn`` of the topology's FileUplink, and its
      FileDownlink's ``bufferSendOut`` to ``fileIn`` (when the topology has them);
    - the link's own events, telemetry and time connect to the same services as everyone else's;
    - ``schedIn`` becomes a member of ``rate_group`` (default: the fastest rate group with room).

    ``module`` defaults to the module named after the deployment (``ReferenceDeployment``), else
    ``Com``. ``base_id`` defaults to ``GROUND_LINK_BASE_ID`` (0x10070000), or, when an instance of
    the topology already has its base id in that 0x1000 block (the coursework deployment's star
    tracker), to the first 0x1000 block above every instance's base id. Raises
    :class:`~fprime_lite.deploy.topology.TopologyError` when the topology cannot take it.
    """
    problems = [f"the topology has no '{kind}' pattern; the ground link needs its {kind} service"
                for kind in ("command", "event", "telemetry") if kind not in topology.patterns]
    if problems:
        raise TopologyError(problems)
    if module is None:
        module = topology.deployment if any(i.module == topology.deployment
                                            for i in topology.instances.values()) else "Com"
    if base_id is None:
        base_id = _free_base_id(topology)
    link = GroundLink(name, base_id=base_id, host=host, port=port, framing=framing, **link_args)
    qualified = f"{module}.{name}"
    topology.add(module, link, where=f"{qualified} (added for the ground link)")

    for kind, service_port in (("event", "LogRecv"), ("text_event", "TextLogger"), ("telemetry", "TlmRecv"),
                               ("time", "timeGetPort")):
        client_port = link.spec.special.get({"event": "event", "text_event": "text event",
                                             "telemetry": "telemetry", "time": "time get"}[kind])
        service = topology.patterns.get(kind)
        if client_port is not None and service is not None:
            topology.connect(qualified, client_port, 0, service, service_port, 0, group=f"pattern:{kind}")

    for kind in ("event", "telemetry"):
        service = topology.patterns[kind]
        pkt_send = topology.instance(service).component.output_port("PktSend")
        if pkt_send.is_connected(0):
            raise TopologyError([f"{service}.PktSend is already connected to {pkt_send.target_name(0)}; "
                                 f"the ground link needs it"])
        topology.connect(service, "PktSend", 0, qualified, "comIn", 0, group="Downlink")

    dispatcher_name = topology.patterns["command"]
    dispatcher = topology.instance(dispatcher_name).component
    used = {c.target_index for c in topology.connections
            if c.target == dispatcher_name and c.target_port == "seqCmdBuff"}
    status = dispatcher.output_port("seqCmdStatus")
    free = [k for k in range(len(status)) if k not in used and not status.is_connected(k)]
    if not free:
        raise TopologyError([f"{dispatcher_name}.seqCmdBuff has no free index for the ground link"])
    k = free[0]
    topology.connect(qualified, "commandOut", 0, dispatcher_name, "seqCmdBuff", k, group="Uplink")
    topology.connect(dispatcher_name, "seqCmdStatus", k, qualified, "cmdResponseIn", 0, group="Uplink")

    for instance in list(topology.instances.values()):
        comp = instance.component
        if isinstance(comp, FileUplink) and not link.is_connected("fileOut", 0):
            topology.connect(qualified, "fileOut", 0, instance.qualified_name, "bufferSendIn", 0, group="Uplink")
        elif isinstance(comp, FileDownlink) and not comp.is_connected("bufferSendOut", 0):
            topology.connect(instance.qualified_name, "bufferSendOut", 0, qualified, "fileIn", 0, group="Downlink")

    groups = [i for i in topology.instances.values() if isinstance(i.component, RateGroupBase)]
    if rate_group is not None:
        groups = [i for i in groups if i.qualified_name == rate_group]
        if not groups:
            raise TopologyError([f"no rate group {rate_group!r} for the ground link"])
    groups.sort(key=lambda i: i.component.period_us or float("inf"))
    for group in groups:
        members = group.component.output_port("RateGroupMemberOut")
        slot = next((j for j in range(len(members)) if not members.is_connected(j)), None)
        if slot is not None:
            topology.connect(group.qualified_name, "RateGroupMemberOut", slot, qualified, "schedIn", 0,
                             group="RateGroups")
            break
    else:
        raise TopologyError(["no rate group has a free member slot for the ground link's schedIn"])

    problems = topology.problems()
    if problems:
        raise TopologyError(problems)
    return link


def _free_base_id(topology) -> int:
    """GROUND_LINK_BASE_ID unless an instance's base id lies in its 0x1000 block, else the first
    0x1000 block above every base id (the topology's own check still refuses any id clash)."""
    blocks = {instance.component.base_id & ~0xFFF for instance in topology.instances.values()}
    if GROUND_LINK_BASE_ID not in blocks:
        return GROUND_LINK_BASE_ID
    return max(blocks) + 0x1000
