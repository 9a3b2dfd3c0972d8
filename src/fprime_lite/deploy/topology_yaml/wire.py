"""Stage 4 of loading a topology: connect the built instances.

Connections are made in the order FPP would make them: the named connection groups (the topology's,
then those of included subtopologies), the rate groups (``driver.CycleOut[i] -> group.CycleIn`` in
listed order, ``group.RateGroupMemberOut[j] -> member`` in member order), then the patterns, which
leave alone every port already connected. An endpoint is looked up before connecting (unknown
instance or port: a message with a suggestion); what the port model refuses (types differ, index
out of range, already connected) comes back as a :class:`PortConnectionError` that already reads
``what — what to do``.
"""

from __future__ import annotations

import pathlib

from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.deploy.topology import PATTERN_PORTS, Topology
from fprime_lite.deploy.topology_yaml.problems import Problems
from fprime_lite.deploy.topology_yaml.schema import EndpointRef, TopologyConfig
from fprime_lite.model.errors import PortConnectionError, did_you_mean
from fprime_lite.svc.rate_group_driver import RateGroupDriver, RateGroupTimer
from fprime_lite.svc.rate_groups import ActiveRateGroup, PassiveRateGroup

__all__ = ["wire_connections", "wire_rate_groups", "wire_patterns", "check_startup"]

Endpoint = tuple[str, str, int]


class _Wirer:
    def __init__(self, topology: Topology, problems: Problems):
        self.topology = topology
        self.problems = problems

    def endpoint(self, file: pathlib.Path, ref: EndpointRef, line: int | None, direction: str) -> Endpoint | None:
        """(qualified instance, port, index) of ``ref`` if it exists, else None (reported)."""
        instance = self.topology.instances.get(ref.instance)
        if instance is None and self.problems.already_reported(ref.instance):
            return None  # already reported where it was declared
        if instance is None:
            hint = did_you_mean(ref.instance, self.topology.instances, "declare it under 'modules'")
            self.problems.add(file, line, f"unknown instance '{ref.instance}' — {hint}")
            return None
        comp = instance.component
        ports = comp.spec.outputs if direction == "output" else comp.spec.inputs
        if ref.port not in ports:
            hint = did_you_mean(ref.port, ports, f"its {direction} ports: {', '.join(ports) or 'none'}")
            self.problems.add(file, line, f"{type(comp).__name__} {ref.instance} has no {direction} port "
                                          f"'{ref.port}' — {hint}")
            return None
        return ref.instance, ref.port, ref.index

    def connect(self, file: pathlib.Path, line: int | None, src: Endpoint, dst: Endpoint, group: str) -> None:
        try:
            self.topology.connect(*src, *dst, group=group)
        except PortConnectionError as exc:
            self.problems.add(file, line, str(exc))


def wire_connections(config: TopologyConfig, topology: Topology, problems: Problems) -> None:
    """Make the named connections of ``config`` (the topology's, then the included ones)."""
    wirer = _Wirer(topology, problems)
    for c in config.connections:
        src = wirer.endpoint(c.file, c.source, c.line, "output")
        dst = wirer.endpoint(c.file, c.target, c.line, "input")
        if src is not None and dst is not None:
            wirer.connect(c.file, c.line, src, dst, c.group)


def wire_rate_groups(config: TopologyConfig, topology: Topology, scheduler: Scheduler,
                     problems: Problems) -> RateGroupTimer | None:
    """Connect the driver to the groups and the groups to their members; the timer that ticks them."""
    cfg = config.rate_groups
    if cfg is None:
        return None
    file = config.path
    driver = topology.instances.get(cfg.driver)
    if driver is None and problems.already_reported(cfg.driver):
        return None
    if driver is None or not isinstance(driver.component, RateGroupDriver):
        problems.add(file, cfg.driver_line, f"rate group driver '{cfg.driver}' must be a RateGroupDriver "
                                            f"instance — declare one under 'modules' and name it here")
        return None
    wirer = _Wirer(topology, problems)
    for i, group in enumerate(cfg.groups):
        instance = topology.instances.get(group.name)
        if instance is None and problems.already_reported(group.name):
            continue
        if instance is None or not isinstance(instance.component, (ActiveRateGroup, PassiveRateGroup)):
            problems.add(file, group.line, f"rate group '{group.name}' must be an ActiveRateGroup or "
                                           f"PassiveRateGroup instance — declare one under 'modules'")
            continue
        wirer.connect(file, group.line, (cfg.driver, "CycleOut", i), (group.name, "CycleIn", 0), "RateGroups")
        for j, member in enumerate(group.members):
            if member.port is None:
                continue  # malformed, reported by the schema
            dst = wirer.endpoint(file, member.port, member.line, "input")
            if dst is not None:
                wirer.connect(file, member.line, (group.name, "RateGroupMemberOut", j), dst, "RateGroups")
    return RateGroupTimer(scheduler, driver.component, cfg.base_period_us)


def wire_patterns(config: TopologyConfig, topology: Topology, problems: Problems) -> None:
    """Wire every instance's special ports to the services named under ``patterns``."""
    services = {}
    for pattern in config.patterns:
        instance = topology.instances.get(pattern.instance)
        if instance is None and problems.already_reported(pattern.instance):
            continue
        if instance is None:
            problems.add(config.path, pattern.line, f"pattern '{pattern.kind}': unknown instance "
                                                    f"{pattern.instance!r} — name a Module.instance declared "
                                                    f"under 'modules'")
            continue
        spec = instance.component.spec
        missing = [p for _, p, d in PATTERN_PORTS[pattern.kind]
                   if p not in (spec.inputs if d == "to service" else spec.outputs)]
        if missing:
            problems.add(config.path, pattern.line,
                         f"pattern '{pattern.kind}': {pattern.instance} ({type(instance.component).__name__}) "
                         f"lacks port(s) {', '.join(missing)} — name the instance that serves {pattern.kind} "
                         f"connections")
            continue
        services[pattern.kind] = pattern.instance
    try:
        topology.connect_patterns(**services)
    except PortConnectionError as exc:
        problems.add(config.path, config.patterns_line, str(exc))


def check_startup(config: TopologyConfig, topology: Topology, problems: Problems) -> None:
    """The start-up sequencer must be an instance of the topology."""
    startup = config.startup
    if startup is not None and startup.sequencer not in topology.instances \
            and not problems.already_reported(startup.sequencer):
        problems.add(config.path, startup.sequencer_line,
                     f"'startup.sequencer' must name the sequencer instance, got {startup.sequencer!r} — "
                     f"name a CmdSequencer declared under 'modules'")
