"""A topology: component instances grouped in modules, and the connections between them.

Instances are named as F´ v4 names them in dictionaries: the module plus the instance name
(``CdhCore.cmdDisp``, ``ReferenceDeployment.detumbleManager``). Connections belong to named groups,
as FPP's ``connections Name { a.out[i] -> b.in[j] }``. Pattern connections wire every instance's
special ports to the services that serve them, as FPP's ``command connections instance cmdDisp``
does; an index already connected explicitly is left alone.

:meth:`Topology.problems` lists what would stop the topology from running: id or opcode collisions
between instances and required output ports left unconnected.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterator, NamedTuple

from fprime_lite.model.component import Component
from fprime_lite.model.errors import FprimeLiteError, PortConnectionError
from fprime_lite.model.fw_ports import CmdSeqIn, Ping
from fprime_lite.svc.health import Health

__all__ = ["Topology", "Instance", "Connection", "PATTERN_PORTS", "TopologyError", "sequence_run_port"]


def sequence_run_port(component: Component) -> str | None:
    """The input port through which ``component`` runs a sequence file: its one input port of F´'s
    ``Svc.CmdSeqIn`` type (CmdSequencer's ``seqRunIn``); None when it has none or several."""
    ports = [name for name, decl in component.spec.inputs.items() if decl.port_type is CmdSeqIn]
    return ports[0] if len(ports) == 1 else None


class TopologyError(FprimeLiteError):
    """A topology cannot be built; ``problems`` lists each issue (``file:line: what — what to do``)."""

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        count = len(self.problems)
        super().__init__(f"{count} problem{'s' if count != 1 else ''} in the topology:\n"
                         + "\n".join(f"  {p}" for p in self.problems))


#: Pattern kind -> [(special port kind on the client, service port name, direction)].
#: "to service": the client's output connects to the service's input; "from service": the reverse.
PATTERN_PORTS = {
    "command": [("command reg", "compCmdReg", "to service"), ("command recv", "compCmdSend", "from service"),
                ("command resp", "compCmdStat", "to service")],
    "event": [("event", "LogRecv", "to service")],
    "text_event": [("text event", "TextLogger", "to service")],
    "telemetry": [("telemetry", "TlmRecv", "to service")],
    "param": [("param get", "getPrm", "to service"), ("param set", "setPrm", "to service")],
    "time": [("time get", "timeGetPort", "to service")],
    # FPP's health pattern: every other instance with a Svc.Ping input and output is pinged.
    "health": [("ping", "PingReturn", "to service"), ("ping", "PingSend", "from service")],
}

#: Thresholds (health Run ticks) of the ping entries the health pattern makes, as F´'s Ref deployment.
HEALTH_WARN_CYCLES = 3
HEALTH_FATAL_CYCLES = 5


@dataclass
class Instance:
    """A component instance placed in a module; ``where`` says where it was declared."""

    module: str
    component: Component
    where: str = ""
    #: the keyword arguments the component was made with (set by the YAML loader); a software
    #: restart re-initialises the component with them
    init_kwargs: dict | None = None

    @property
    def name(self) -> str:
        return self.component.name

    @property
    def qualified_name(self) -> str:
        return f"{self.module}.{self.component.name}"


class Connection(NamedTuple):
    group: str
    source: str
    source_port: str
    source_index: int
    target: str
    target_port: str
    target_index: int

    def __str__(self) -> str:
        return (f"{self.source}.{self.source_port}[{self.source_index}] -> "
                f"{self.target}.{self.target_port}[{self.target_index}]")


@dataclass
class Topology:
    """Instances and connections of one deployment."""

    deployment: str
    instances: dict[str, Instance] = field(default_factory=dict)
    connections: list[Connection] = field(default_factory=list)
    patterns: dict[str, str] = field(default_factory=dict)
    #: telemetry packet sets in the JSON dictionary's shape (``telemetry_packets`` of a YAML topology)
    telemetry_packet_sets: list[dict] = field(default_factory=list)

    def add(self, module: str, component: Component, where: str = "") -> Instance:
        """Place ``component`` in ``module``; its qualified name must be unique."""
        instance = Instance(module, component, where)
        name = instance.qualified_name
        if name in self.instances:
            raise PortConnectionError(f"instance {name} is declared twice", "rename one of them")
        self.instances[name] = instance
        return instance

    def instance(self, qualified_name: str) -> Instance:
        try:
            return self.instances[qualified_name]
        except KeyError:
            raise KeyError(f"no instance {qualified_name!r}; instances: {', '.join(self.instances)}") from None

    def components(self) -> Iterator[Component]:
        for instance in self.instances.values():
            yield instance.component

    def connect(self, source: str, source_port: str, source_index: int, target: str, target_port: str,
                target_index: int = 0, group: str = "") -> Connection:
        """Connect ``source.source_port[source_index] -> target.target_port[target_index]``."""
        src = self.instance(source).component
        dst = self.instance(target).component
        src.output_port(source_port).connect(source_index, dst.input_port(target_port), target_index)
        connection = Connection(group, source, source_port, source_index, target, target_port, target_index)
        self.connections.append(connection)
        return connection

    def connect_patterns(self, **services: str) -> None:
        """Wire special ports to services, e.g. ``connect_patterns(command="CdhCore.cmdDisp", ...)``."""
        unknown = set(services) - set(PATTERN_PORTS)
        if unknown:
            raise KeyError(f"unknown pattern kind(s) {sorted(unknown)}; kinds: {', '.join(PATTERN_PORTS)}")
        for kind, service_name in services.items():
            service = self.instance(service_name).component
            self.patterns[kind] = service_name
            if kind == "health":
                self._connect_health(service_name)
                continue
            next_index: dict[str, int] = {}
            for client in self.instances.values():
                comp = client.component
                special = comp.spec.special
                for special_kind, service_port, direction in PATTERN_PORTS[kind]:
                    client_port = special.get(special_kind)
                    if client_port is None:
                        continue
                    if direction == "to service":
                        out = comp.output_port(client_port)
                        if out.is_connected(0):
                            continue
                        target = service.input_port(service_port)
                        index = self._pattern_index(kind, service_port, target, next_index, service_name)
                        self.connect(client.qualified_name, client_port, 0, service_name, service_port, index,
                                     group=f"pattern:{kind}")
                    else:
                        out = service.output_port(service_port)
                        index = self._pattern_index(kind, service_port, out, next_index, service_name)
                        self.connect(service_name, service_port, index, client.qualified_name, client_port, 0,
                                     group=f"pattern:{kind}")

    def _connect_health(self, service_name: str) -> None:
        """Ping every instance that answers pings, one ``PingSend``/``PingReturn`` index each, and
        give the health component a ping entry per instance, named by its qualified name."""
        health = self.instance(service_name).component
        if not isinstance(health, Health):
            raise PortConnectionError(f"{service_name} is a {type(health).__name__}, not an Svc.Health: the "
                                      f"health pattern needs the health component")
        send = health.output_port("PingSend")
        entries = [entry.name for entry in health.entries]
        for client in self.instances.values():
            comp = client.component
            if comp is health:
                continue
            ping_in = [n for n, port in comp.input_ports.items() if port.port_type is Ping]
            ping_out = [n for n, port in comp.output_ports.items() if port.port_type is Ping]
            if len(ping_in) != 1 or len(ping_out) != 1 or comp.output_port(ping_out[0]).is_connected(0):
                continue
            index = len(entries)
            if index >= len(send):
                raise PortConnectionError(f"{service_name}.PingSend has {len(send)} indices, too few for every "
                                          f"component that answers pings", "leave some out of the health pattern")
            self.connect(service_name, "PingSend", index, client.qualified_name, ping_in[0], 0, group="pattern:health")
            self.connect(client.qualified_name, ping_out[0], 0, service_name, "PingReturn", index,
                         group="pattern:health")
            # F´'s generated ping entries are named FileHandling_fileManager: the qualified name with '_'
            entries.append(client.qualified_name.replace(".", "_"))
        health.set_ping_entries([*health.entries, *((name, HEALTH_WARN_CYCLES, HEALTH_FATAL_CYCLES)
                                                     for name in entries[len(health.entries):])])

    def _pattern_index(self, kind, service_port, port, next_index, service_name) -> int:
        # Command registration and dispatch share one index per client, as FPP allocates them.
        key = "command" if kind == "command" and service_port in ("compCmdReg", "compCmdSend") else service_port
        if len(port) == 1 and key != "command":
            return 0
        index = next_index.get(key, 0)
        if index >= len(port):
            raise PortConnectionError(
                f"{service_name}.{service_port} has {len(port)} indices, too few for every {kind} client",
                "use a service with a larger port array or fewer instances")
        if key == "command":
            if service_port == "compCmdSend":
                next_index[key] = index + 1
        else:
            next_index[key] = index + 1
        return index

    # --- checks ----------------------------------------------------------------------------------

    def id_collisions(self) -> list[str]:
        """Global opcodes, event, channel or parameter ids used by two instances (or members)."""
        problems = []
        for what, ids_of in (("opcode", _opcodes), ("event id", _event_ids), ("channel id", _channel_ids),
                             ("parameter id", _param_ids)):
            seen: dict[int, tuple[Instance, str]] = {}
            for instance in self.instances.values():
                for global_id, member in ids_of(instance.component):
                    if global_id in seen:
                        other, other_member = seen[global_id]
                        problems.append(
                            f"{instance.where or instance.qualified_name}: {what} 0x{global_id:X} of "
                            f"{instance.qualified_name}.{member} is also used by {other.qualified_name}.{other_member}"
                            f" (declared at {other.where or '?'}) — give the instances base ids further apart")
                    else:
                        seen[global_id] = (instance, member)
        return problems

    def unconnected_required_ports(self) -> list[str]:
        problems = []
        for instance in self.instances.values():
            for name, port in instance.component.output_ports.items():
                if port.required:
                    for i in range(len(port)):
                        if not port.is_connected(i):
                            problems.append(
                                f"{instance.where or instance.qualified_name}: required output port "
                                f"{instance.qualified_name}.{name}[{i}] is not connected — connect it in "
                                f"'connections'")
        return problems

    def problems(self) -> list[str]:
        return self.id_collisions() + self.unconnected_required_ports()

    # --- export ----------------------------------------------------------------------------------

    def to_dot(self, include_patterns: bool = False) -> str:
        """Graphviz DOT: one cluster per module, one edge per connection labelled with the ports."""
        lines = [f'digraph "{self.deployment}" {{', "  rankdir=LR;", '  node [shape=box, fontname="Helvetica"];']
        modules: dict[str, list[Instance]] = {}
        for inst in self.instances.values():
            modules.setdefault(inst.module, []).append(inst)
        for module, members in modules.items():
            lines.append(f'  subgraph "cluster_{module}" {{')
            lines.append(f'    label="{module}";')
            for inst in members:
                lines.append(f'    "{inst.qualified_name}" [label="{inst.name}\\n{type(inst.component).__name__}"];')
            lines.append("  }")
        for c in self._exported(include_patterns):
            lines.append(f'  "{c.source}" -> "{c.target}" [label="{c.source_port}[{c.source_index}] → '
                         f'{c.target_port}[{c.target_index}]"];')
        lines.append("}")
        return "\n".join(lines) + "\n"

    def to_mermaid(self, include_patterns: bool = False) -> str:
        """Mermaid flowchart: one subgraph per module."""
        ids = {name: f"n{i}" for i, name in enumerate(self.instances)}
        lines = ["flowchart LR"]
        modules: dict[str, list[Instance]] = {}
        for inst in self.instances.values():
            modules.setdefault(inst.module, []).append(inst)
        for module, members in modules.items():
            lines.append(f"  subgraph {module}")
            for inst in members:
                lines.append(f'    {ids[inst.qualified_name]}["{inst.name}<br/>{type(inst.component).__name__}"]')
            lines.append("  end")
        for c in self._exported(include_patterns):
            lines.append(f'  {ids[c.source]} -->|"{c.source_port} → {c.target_port}"| {ids[c.target]}')
        return "\n".join(lines) + "\n"

    def _exported(self, include_patterns: bool) -> list[Connection]:
        return [c for c in self.connections if include_patterns or not c.group.startswith("pattern:")]


def _opcodes(comp):
    return [(comp.base_id + c.opcode, c.name) for c in comp.spec.commands]


def _event_ids(comp):
    return [(comp.base_id + e.local_id, e.name) for e in comp.spec.events]


def _channel_ids(comp):
    return [(comp.base_id + c.local_id, c.name) for c in comp.spec.channels]


def _param_ids(comp):
    return [(comp.base_id + p.local_id, p.name) for p in comp.spec.params]
