"""Load FPP models: F´ component and topology definitions bound to Python implementations.

:func:`load_fpp` analyses FPP files with F´'s own analyser (``fprime-fpp-python``), with the
framework definitions fprime-lite ships (``framework/*.fpp``) or a user's F´ checkout in their place,
then binds every component definition a topology instantiates to its Python implementation class
and checks that the two declare the same members: commands (opcode, kind, arguments, priority),
events (id, severity, format, throttle, arguments), channels (id, update policy), parameters (id,
default, set/save opcodes) and general ports (direction, size, port type). Every mismatch is
refused before anything flies, as ``FPP file:line: what differs — Python file:line``.

Which class implements a component ``M.Name`` (``docs/fpp.md``), first match wins:

1. an explicit registration, :func:`register_implementation` or ``implementations=`` of
   :func:`load_fpp`;
2. an annotation on the component definition, ``@ fprime-lite: package.module.Class``;
3. fprime-lite's own services for F´'s Svc components (``Svc.CommandDispatcher`` …);
4. the naming rule: class ``Name`` in the module ``name.py`` (``Name`` in snake case) beside the
   FPP file that defines the component.
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import pathlib
import re
import sys
from dataclasses import dataclass, field
from typing import Any, Iterable

from fprime_lite.deploy.fpp.export import SVC_COMPONENT_NAMES, framework_files
from fprime_lite.deploy.topology import TopologyError
from fprime_lite.model.component import FRAMEWORK_CHANNELS, FRAMEWORK_EVENTS, ComponentSpec
from fprime_lite.deploy.fpp.synthesize import declares_nothing, synthesize
from fprime_lite.model.errors import DeclarationError
from fprime_lite.model.events import Severity

__all__ = ["FppError", "FppModel", "FppInstance", "load_fpp", "check_components", "register_implementation",
           "fpp_available", "component_class"]

_REGISTRY: dict[str, type] = {}
#: (FPP file, its mtime and size, component name) -> the class load_fpp bound it to, so that a
#: ``type: fpp:FILE:M.Name`` of the topology YAML that flies an FPP topology (run.py) is not analysed again
_BOUND: dict[tuple[str, int, int, str], type] = {}
#: The events and channel fprime-lite gives every component (HandlerFault, HandlerFaults …): an FPP
#: model need not declare them (fprime-lite's own FPP does, so that fpp-to-dict lists them too).
_FRAMEWORK_MEMBERS = frozenset(FRAMEWORK_EVENTS) | frozenset(FRAMEWORK_CHANNELS)
_ANNOTATION = re.compile(r"^\s*fprime-lite:\s*([A-Za-z_][\w.]*)\s*$")
_SEVERITY = {"Fatal": Severity.FATAL, "WarningHigh": Severity.WARNING_HI, "WarningLow": Severity.WARNING_LO,
             "Command": Severity.COMMAND, "ActivityHigh": Severity.ACTIVITY_HI,
             "ActivityLow": Severity.ACTIVITY_LO, "Diagnostic": Severity.DIAGNOSTIC}


class FppError(TopologyError):
    """An FPP model that does not analyse, or that does not fit its Python implementation."""


def fpp_available() -> bool:
    """Whether F´'s FPP analyser (the ``fprime-fpp-python`` package, extra ``fpp``) is installed."""
    return importlib.util.find_spec("fpp") is not None


def register_implementation(fpp_name: str, cls: type) -> None:
    """Bind FPP component ``fpp_name`` (``Components.Thermostat``) to Python class ``cls``."""
    _REGISTRY[fpp_name] = cls


@dataclass
class _ComponentView:
    """What the dictionary and the checks need of an instance: its spec, name and base id."""

    name: str
    base_id: int
    spec: ComponentSpec
    cls: type


@dataclass
class FppInstance:
    """A component instance of an FPP topology, bound to its implementation."""

    module: str
    component: _ComponentView
    fpp_component: str
    queue_size: int | None = None
    priority: int | None = None
    where: str = ""

    @property
    def name(self) -> str:
        return self.component.name

    @property
    def qualified_name(self) -> str:
        return f"{self.module}.{self.component.name}" if self.module else self.component.name


@dataclass
class FppModel:
    """An analysed FPP model: its topology's instances (bound) and connections. It has what
    :func:`~fprime_lite.deploy.dictionary.build_dictionary` reads of a topology."""

    deployment: str
    #: the topology's qualified name (``ReferenceDeployment.ReferenceDeployment``), the dictionary's
    #: deploymentName as fpp-to-dict writes it
    topology_name: str = ""
    instances: dict[str, FppInstance] = field(default_factory=dict)
    connections: list[tuple[str, str, int, str, str, int]] = field(default_factory=list)
    #: FPP component name -> the class bound to it
    bindings: dict[str, type] = field(default_factory=dict)
    #: the topology's telemetry packet sets, as the dictionary lists them
    telemetry_packet_sets: list[dict] = field(default_factory=list)
    #: packet set name, and ``set.packet`` for each of its packets -> where the FPP declares it
    #: (``file:line:column``)
    packet_set_locations: dict[str, str] = field(default_factory=dict)
    #: FPP component name -> the FPP file that defines it
    component_files: dict[str, str] = field(default_factory=dict)

    def to_dot(self) -> str:
        """The connection graph in Graphviz DOT."""
        lines = [f'digraph "{self.deployment}" {{', "  rankdir=LR;"]
        lines += [f'  "{s}" -> "{t}" [label="{sp}[{si}] -> {tp}[{ti}]"];' for s, sp, si, t, tp, ti in self.connections]
        return "\n".join(lines + ["}"]) + "\n"

    def to_mermaid(self) -> str:
        """The connection graph as a Mermaid flowchart."""
        lines = ["flowchart LR"]
        lines += [f"  {s.replace('.', '_')} -->|{sp}[{si}] → {tp}[{ti}]| {t.replace('.', '_')}"
                  for s, sp, si, t, tp, ti in self.connections]
        return "\n".join(lines) + "\n"


def _loc(node: Any) -> str:
    try:
        return str(node.location.display)
    except AttributeError:
        return str(getattr(node, "span", "?"))


def _python_loc(cls: type, member: Any = None) -> str:
    target = member if member is not None and inspect.isfunction(member) else cls
    try:
        path = inspect.getsourcefile(target) or "?"
        line = inspect.getsourcelines(target)[1]
    except (OSError, TypeError):
        return f"{cls.__module__}.{cls.__qualname__}"
    return f"{path}:{line} ({cls.__qualname__})"


def _snake(name: str) -> str:
    return re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", name).lower()


def _import_class(dotted: str) -> type:
    module, _, name = dotted.rpartition(".")
    return getattr(importlib.import_module(module), name)


def _implementation(fpp_name: str, node: Any, explicit: dict[str, type]) -> tuple[type | None, str]:
    """(class, how it was found) or (None, what was tried)."""
    if fpp_name in explicit:
        return explicit[fpp_name], "explicit registration"
    if fpp_name in _REGISTRY:
        return _REGISTRY[fpp_name], "register_implementation"
    for line in list(node.pre_annotation) + list(node.post_annotation):
        match = _ANNOTATION.match(line)
        if match:
            try:
                return _import_class(match.group(1)), f"annotation {match.group(1)}"
            except (ImportError, AttributeError) as exc:
                return None, f"its annotation names {match.group(1)}, which does not import ({exc})"
    reverse = {fpp: py for py, fpp in SVC_COMPONENT_NAMES.items()}
    if fpp_name in reverse:
        return _import_class(reverse[fpp_name]), "fprime-lite service"
    short = fpp_name.rsplit(".", 1)[-1]
    folder = pathlib.Path(str(node.location.uri)).parent
    candidate = folder / f"{_snake(short)}.py"
    if candidate.is_file():
        if str(folder) not in sys.path:  # so that the module's own imports of its neighbours work
            sys.path.insert(0, str(folder))
        try:
            module = _module_at(candidate)
        except Exception as exc:  # noqa: BLE001 - the user's module failed to import: reported, not raised
            return None, f"{candidate} does not import: {type(exc).__name__}: {exc}"
        cls = getattr(module, short, None)
        if isinstance(cls, type):
            return cls, f"naming rule {candidate}"
        return None, f"{candidate} has no class {short}"
    return None, (f"no registration, no '@ fprime-lite: module.Class' annotation, and no {candidate.name} "
                  f"beside {node.location.uri}")


def _module_at(path: pathlib.Path) -> Any:
    """The module of file ``path`` (loaded from that file even when a module of the same name from
    another folder was imported before)."""
    loaded = sys.modules.get(path.stem)
    if loaded is not None and pathlib.Path(getattr(loaded, "__file__", "") or "").resolve() == path.resolve():
        return loaded
    spec = importlib.util.spec_from_file_location(path.stem, path)
    if spec is None or spec.loader is None:
        raise ImportError(f"cannot load {path}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[path.stem] = module
    spec.loader.exec_module(module)
    return module


def _check_component(fpp_name: str, comp: Any, cls: type, analysis: Any) -> list[str]:
    """Every difference between FPP component ``comp`` and the class ``cls`` implementing it."""
    spec: ComponentSpec | None = getattr(cls, "__fprime_spec__", None)
    if spec is None:
        return [f"{_loc(comp.node)}: {fpp_name} is implemented by {cls.__qualname__}, which is not a component "
                f"class — {_python_loc(cls)}"]
    out: list[str] = []

    def refuse(node: Any, what: str, member: Any = None) -> None:
        out.append(f"{_loc(node)}: {fpp_name}: {what} — {_python_loc(cls, member)}")

    flown = getattr(cls, "__fprime_state_machines__", ())
    for name, instance in comp.state_machine_instance_map.items():
        if name not in flown:
            refuse(instance.node, f"state machine instance {name}: {cls.__qualname__} declares its members, and "
                                  f"fprime-lite runs an FPP state machine only in a class that supplies handlers "
                                  f"only (its actions and guards as methods, docs/fpp.md) — drop its declarations")
    kind = str(comp.node.kind).rsplit(".", 1)[-1].lower()
    if kind != spec.kind:
        refuse(comp.node, f"FPP declares a {kind} component, {cls.__qualname__} is {spec.kind}")
    # commands (the parameters' PRM_SET / PRM_SAVE are compared with the parameters)
    py_commands = {c.name: c for c in spec.commands if c.kind not in ("set", "save")}
    seen: set[str] = set()
    for opcode, command in comp.command_map.items():
        if type(command).__name__ != "NonParam":
            continue
        name, node = command.name, command.node
        seen.add(name)
        py = py_commands.get(name)
        if py is None:
            refuse(node, f"command {name} has no handler: give {cls.__qualname__} a method {name} decorated as a "
                         f"command")
            continue
        handler = getattr(cls, name, None)
        fpp_kind = type(command.kind).__name__.lower()  # NonParamKind.Sync | Guarded | Async
        if fpp_kind != py.kind:
            refuse(node, f"command {name} is {fpp_kind} in FPP, {py.kind} in Python", handler)
        elif fpp_kind == "async" and (command.kind.priority or 0) != py.priority:
            refuse(node, f"command {name} has priority {command.kind.priority} in FPP, {py.priority} in Python",
                   handler)
        if opcode != py.opcode:
            refuse(node, f"command {name} has opcode 0x{opcode:X} in FPP, 0x{py.opcode:X} in Python", handler)
        fpp_args = [p.name for p in node.params]
        py_args = [n for n, _ in py.args]
        if fpp_args != py_args:
            refuse(node, f"command {name}'s handler takes ({', '.join(py_args)}), FPP declares "
                         f"({', '.join(fpp_args)})", handler)
    for name in py_commands.keys() - seen:
        refuse(comp.node, f"{cls.__qualname__} handles command {name}, which the FPP component does not declare",
               getattr(cls, name, None))
    for _, event, pe in _paired("event", comp.event_map, spec.events, cls, comp.node, refuse):
        name, node = event.name, event.node
        severity = _SEVERITY.get(str(node.severity).rsplit(".", 1)[-1])
        if severity is not pe.severity:
            refuse(node, f"event {name} is {node.severity} in FPP, {pe.severity.name} in Python")
        if node.format != pe.format:
            refuse(node, f"event {name} formats {node.format!r} in FPP, {pe.format!r} in Python")
        throttle = event.throttle.count if event.throttle is not None else None
        if throttle != pe.throttle:
            refuse(node, f"event {name} is throttled at {throttle} in FPP, {pe.throttle} in Python")
        if [p.name for p in node.params] != [n for n, _ in pe.args]:
            refuse(node, f"event {name} takes ({', '.join(p.name for p in node.params)}) in FPP, "
                         f"({', '.join(n for n, _ in pe.args)}) in Python")
    for _, channel, pc in _paired("channel", comp.tlm_channel_map, spec.channels, cls, comp.node, refuse):
        update = "on change" if "OnChange" in str(channel.update) else "always"
        if update != pc.update:
            refuse(channel.node, f"channel {channel.name} updates {update} in FPP, {pc.update} in Python")
    for _, param, _ in _paired("parameter", comp.param_map, spec.params, cls, comp.node, refuse):
        for what, fpp_opcode in (("SET", param.set_opcode), ("SAVE", param.save_opcode)):
            py_opcode = spec.command(f"{param.name.upper()}_PRM_{what}").opcode
            if fpp_opcode != py_opcode:
                refuse(param.node, f"parameter {param.name}'s {what.lower()} opcode is 0x{fpp_opcode:X} in FPP, "
                                   f"0x{py_opcode:X} in Python")
    # general ports
    special = set(spec.special.values())
    py_ports = {n: ("input", d.kind, d.size, d.port_type.name) for n, d in spec.inputs.items() if n not in special}
    py_ports.update({n: ("output", "output", d.size, d.port_type.name)
                     for n, d in spec.outputs.items() if n not in special})
    seen = set()
    for name, port in comp.port_map.items():
        if type(port).__name__ != "General":
            continue
        seen.add(name)
        node = port.node
        direction = "input" if "Input" in str(port.direction) else "output"
        py_port = py_ports.get(name)
        handler = getattr(cls, name, None)
        if py_port is None:
            refuse(node, f"{direction} port {name} has no implementation"
                         + (f": give {cls.__qualname__} a handler method {name}" if direction == "input" else
                            f": declare {name} = OutputPort(...) in {cls.__qualname__}"))
            continue
        if direction != py_port[0]:
            refuse(node, f"port {name} is an {direction} in FPP, an {py_port[0]} in Python", handler)
        elif direction == "input":
            fpp_kind = type(port.kind).__name__.replace("Input", "").lower()  # SyncInput | GuardedInput | AsyncInput
            if fpp_kind != py_port[1]:
                refuse(node, f"input port {name} is {fpp_kind} in FPP, {py_port[1]} in Python", handler)
        if port.size != py_port[2]:
            refuse(node, f"port {name} has {port.size} index(es) in FPP, {py_port[2]} in Python", handler)
        fpp_type = _port_type_name(port, analysis)
        if fpp_type is not None and fpp_type != py_port[3]:
            refuse(node, f"port {name} is of type {fpp_type} in FPP, {py_port[3]} in Python", handler)
    for name in py_ports.keys() - seen:
        refuse(comp.node, f"{cls.__qualname__} has port {name}, which the FPP component does not declare",
               getattr(cls, name, None))
    return out


def _paired(what: str, fpp_members: dict[int, Any], py_members: Iterable[Any], cls: type, comp_node: Any,
            refuse: Any) -> list[tuple[int, Any, Any]]:
    """(FPP id, FPP member, Python member) of each ``what`` (event, channel, parameter) both sides
    declare with the same local id; a member of one side only, or with another id, is refused.
    fprime-lite's own members (HandlerFault …) need not be in the FPP."""
    by_name = {m.name: m for m in py_members}
    out, seen = [], set()
    for local_id, member in fpp_members.items():
        seen.add(member.name)
        py = by_name.get(member.name)
        if py is None:
            refuse(member.node, f"{what} {member.name} has no implementation: declare it in {cls.__qualname__}")
            continue
        if local_id != py.local_id:
            refuse(member.node, f"{what} {member.name} has id 0x{local_id:X} in FPP, 0x{py.local_id:X} in Python")
        out.append((local_id, member, py))
    for name in sorted(by_name.keys() - seen - _FRAMEWORK_MEMBERS):
        refuse(comp_node, f"{cls.__qualname__} declares {what} {name}, which the FPP component does not")
    return out


def _port_type_name(port: Any, analysis: Any) -> str | None:
    """The qualified name of a general port instance's port type (None for a serial port)."""
    definition = getattr(port.ty, "definition", None)
    symbol = analysis.symbol_map.get(definition.node_id) if definition is not None else None
    return analysis.get_qualified_name(symbol) if symbol is not None else None


def _diagnostics(model: Any) -> list[str]:
    out = []
    for diagnostic in model.diagnostics:
        if "Error" in str(diagnostic.level):
            out.append(str(getattr(diagnostic, "display", diagnostic)))
    return out


def _analyze(paths: Iterable[str | pathlib.Path], imports: Iterable[str | pathlib.Path],
             framework: bool) -> tuple[Any, list[str]]:
    """(the analysed model, the source file names); raise FppError on any FPP error."""
    if not fpp_available():
        raise FppError(["FPP models need F´'s analyser: pip install 'fprime-lite[fpp]' (fprime-fpp-python)"])
    import fpp

    sources = [str(p) for p in paths]
    imported = [str(p) for p in imports]
    missing = [p for p in sources + imported if not pathlib.Path(p).is_file()]
    if missing:
        raise FppError([f"{p}: no such FPP file — give the path of a .fpp file" for p in missing])
    if not sources:
        raise FppError(["no FPP file given — name the .fpp files of a topology or of components"])
    extra = [str(p) for p in framework_files()] if framework else []
    model = fpp.analyze(sources, imports=imported + extra or None)
    problems = _diagnostics(model)
    if problems:
        raise FppError(problems)
    return model, sources


def _bind(comp_name: str, comp: Any, explicit: dict[str, type], problems: list[str], analysis: Any) -> type | None:
    """The class implementing ``comp`` (problems appended when there is none or it does not fit): the
    class itself when it declares its members, checked against the FPP; the class the FPP makes of
    it when it supplies handlers only (:mod:`~fprime_lite.deploy.fpp.synthesize`)."""
    cls, how = _implementation(comp_name, comp.node, explicit)
    if cls is None:
        problems.append(f"{_loc(comp.node)}: component {comp_name} has no Python implementation: {how}")
        return None
    if declares_nothing(cls):
        try:
            cls = synthesize(comp_name, comp, cls, analysis, _loc)
        except DeclarationError as exc:
            problems.append(f"{exc} — {_python_loc(cls)}")
            return None
    found = _check_component(comp_name, comp, cls, analysis)
    problems += found
    return None if found else cls


def check_components(paths: Iterable[str | pathlib.Path], *, imports: Iterable[str | pathlib.Path] = (),
                     framework: bool = True, implementations: dict[str, type] | None = None) -> dict[str, type]:
    """Bind every component defined in ``paths`` (not in ``imports``) to its implementation; return
    FPP name -> class, or raise :class:`FppError` listing every problem."""
    model, sources = _analyze(paths, imports, framework)
    analysis = model.analysis
    source_files = {str(pathlib.Path(p).resolve()) for p in sources}
    explicit = dict(implementations or {})
    problems: list[str] = []
    bound: dict[str, type] = {}
    for symbol, comp in analysis.component_map.items():
        if str(pathlib.Path(str(comp.node.location.uri)).resolve()) not in source_files:
            continue
        name = analysis.get_qualified_name(symbol)
        cls = _bind(name, comp, explicit, problems, analysis)
        if cls is not None:
            bound[name] = cls
    if problems:
        raise FppError(problems)
    if not bound:
        raise FppError([f"{', '.join(sources)}: no component definition — give the files that define components"])
    return bound


def load_fpp(paths: Iterable[str | pathlib.Path], *, imports: Iterable[str | pathlib.Path] = (),
             framework: bool = True, implementations: dict[str, type] | None = None) -> FppModel:
    """Analyse FPP ``paths`` (with ``imports`` to resolve references, as ``fpp-to-dict -i``) and bind
    the components of its topology; raise :class:`FppError` listing every problem.

    The framework's definitions come from fprime-lite's ``framework/*.fpp``; with ``framework=False``
    nothing of fprime-lite's is added, and the F´ files of the user's checkout given in ``imports``
    stand in for them."""
    model, sources = _analyze(paths, imports, framework)  # first: it says so when fpp is missing
    import fpp

    analysis = model.analysis
    source_files = {str(pathlib.Path(p).resolve()) for p in sources}
    topologies = [(s, t) for s, t in analysis.topology_map.items()
                  if str(pathlib.Path(str(t.node.location.uri)).resolve()) in source_files]
    if len(topologies) != 1:
        raise FppError([f"{', '.join(sources)}: {len(topologies)} topologies — give the files of exactly one "
                        f"topology (its components may come from imports), or check components alone with "
                        f"check_components"])
    symbol, topology = topologies[0]
    qualified = analysis.get_qualified_name(symbol)
    result = FppModel(qualified.rsplit(".", 1)[-1], qualified)
    explicit = dict(implementations or {})
    problems: list[str] = []
    checked: dict[str, type | None] = {}
    for instance in topology.instance_map:
        if not isinstance(instance, fpp.InterfaceInstance.Component) or instance.component is None:
            continue  # a nested topology's instances are in the map too
        inst: Any = instance
        comp: Any = instance.component
        comp_name = analysis.get_qualified_name(comp.symbol)
        if comp_name not in checked:
            implementation = _bind(comp_name, comp, explicit, problems, analysis)
            checked[comp_name] = implementation
            if implementation is not None:
                result.bindings[comp_name] = implementation
                result.component_files[comp_name] = str(pathlib.Path(str(comp.node.location.uri)).resolve())
                _BOUND[_bound_key(result.component_files[comp_name], comp_name)] = implementation
        bound: Any = checked[comp_name]
        if bound is None:
            continue
        name = inst.qualified_name
        module, _, short = name.rpartition(".")
        view = _ComponentView(short, inst.base_id, bound.__fprime_spec__, bound)
        result.instances[name] = FppInstance(module, view, comp_name, inst.queue_size, inst.priority, _loc(inst.node))
    if problems:
        raise FppError(problems)
    order = _declaration_order(topology, qualified.rpartition(".")[0])
    result.instances = dict(sorted(result.instances.items(), key=lambda item: order.get(item[0], len(order))))
    result.connections.extend(_connections(topology))
    result.telemetry_packet_sets, result.packet_set_locations = _packet_sets(analysis, symbol, result)
    return result


def _declaration_order(topology: Any, module: str) -> dict[str, int]:
    """Qualified instance name -> its place among the topology's ``instance`` specifiers (the
    analyser's instance map is sorted by name; the order of the file is the one the YAML form has
    and the one fprime-lite's patterns number ports in)."""
    def text(node: Any) -> str:
        if hasattr(node, "data"):
            return str(node.data).lstrip("$")
        return f"{text(node.qualifier)}.{text(node.name)}"

    order: dict[str, int] = {}
    for member in topology.node.members:
        if type(member).__name__ == "SpecInstance":
            name = text(member.instance)
            for candidate in (name, f"{module}.{name}" if module else name):
                order.setdefault(candidate, len(order))
    return order


def _packet_sets(analysis: Any, symbol: Any, model: FppModel) -> tuple[list[dict], dict[str, str]]:
    """The topology's telemetry packet sets, in the dictionary's shape: packets (id, group, channels
    by name, in the FPP's order) by id and the omitted channels by id, as the YAML's
    ``telemetry_packets`` gives them; and where each set is declared."""
    dictionary = analysis.dictionary_map.get(symbol)
    if dictionary is None:
        return [], {}
    names = {}
    for instance in model.instances.values():
        component = instance.component
        for channel in component.spec.channels:
            names[component.base_id + channel.local_id] = f"{instance.qualified_name}.{channel.name}"
    out, where = [], {}
    for name, packet_set in dictionary.tlm_packet_set_map.items():
        members = [{"name": p.name, "id": packet_id, "group": p.group,
                    "members": [names.get(i, str(i)) for i in p.member_id_list]}
                   for packet_id, p in sorted(packet_set.packet_map.items())]
        out.append({"name": name, "members": members,
                    "omitted": [names.get(i, str(i)) for i in sorted(packet_set.omitted_id_set)]})
        where[name] = _loc(packet_set.node)
        where.update({f"{name}.{p.name}": _loc(p.node) for p in packet_set.packet_map.values()})
    return out, where


def _connections(topology: Any) -> list[tuple[str, str, int, str, str, int]]:
    """(source instance, port, index, target instance, port, index) of every connection: the index
    the FPP gives, else the one the analyser assigned (a pattern's, or an unnumbered connection's).
    The analyser's connection objects compare by identity, so its number maps are read by endpoints."""
    def ends(c: Any) -> tuple[str, str, str, str]:
        source, target = c.from_.port, c.to.port
        return (source.interface_instance.qualified_name, source.unqualified_name.rsplit(".", 1)[-1],
                target.interface_instance.qualified_name, target.unqualified_name.rsplit(".", 1)[-1])

    assigned: dict[str, dict[tuple[str, str, str, str], list[int]]] = {"from": {}, "to": {}}
    for side, numbers in (("from", topology.from_port_number_map), ("to", topology.to_port_number_map)):
        for c, assigned_number in numbers.items():
            assigned[side].setdefault(ends(c), []).append(assigned_number)

    def number(side: str, endpoint: Any, key: tuple[str, str, str, str]) -> int:
        if endpoint.port_number is not None:
            return int(endpoint.port_number)
        left = assigned[side].get(key)
        return left.pop(0) if left else 0

    out = []
    for connections in topology.output_connection_map.values():
        for c in connections:
            key = ends(c)
            out.append((key[0], key[1], number("from", c.from_, key), key[2], key[3], number("to", c.to, key)))
    return out


def _bound_key(path: str, name: str) -> tuple[str, int, int, str]:
    try:
        stat = pathlib.Path(path).stat()
    except OSError:
        return (path, -1, -1, name)
    return (path, stat.st_mtime_ns, stat.st_size, name)


def component_class(paths: str | pathlib.Path | Iterable[str | pathlib.Path], name: str | None = None, *,
                    imports: Iterable[str | pathlib.Path] = (),
                    implementations: dict[str, type] | None = None) -> type:
    """The component class FPP file(s) ``paths`` define, bound to its implementation (the class
    itself, checked, or the one made from a handlers-only class): what a harness test takes.
    ``name`` (``Components.Counter``) chooses among several components."""
    files = [paths] if isinstance(paths, (str, pathlib.Path)) else list(paths)
    if name is not None and len(files) == 1 and not imports and not implementations:
        cached = _BOUND.get(_bound_key(str(pathlib.Path(files[0]).resolve()), name))
        if cached is not None:
            return cached
    bound = check_components(files, imports=imports, implementations=implementations)
    if name is None and len(bound) == 1:
        return next(iter(bound.values()))
    if name not in bound:
        raise FppError([f"{', '.join(map(str, files))}: no component {name!r}; they define {', '.join(bound)}"])
    return bound[name]
