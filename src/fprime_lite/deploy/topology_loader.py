"""Load a deployment from a topology YAML file (schema: ``docs/topology.md``).

The file is parsed with PyYAML's SafeLoader (node composition plus safe scalars, which is what
``yaml.safe_load`` does) so that every value keeps its line; nothing in the file is executed except
importing the component and resource classes it names. Every problem found is reported as
``file:line: what is wrong — what to do``, all of them at once, in a :class:`TopologyError`.
"""

from __future__ import annotations

import difflib
import importlib
import inspect
import math
import pathlib
import re
from dataclasses import dataclass, field
from typing import Any

import yaml

from fprime_lite.model.component import Component
from fprime_lite.model.errors import DeclarationError, PortConnectionError
from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.svc.rate_group_driver import RateGroupDriver, RateGroupTimer
from fprime_lite.svc.rate_groups import ActiveRateGroup, PassiveRateGroup
from fprime_lite.model.time import SimulatedClock, TimeBase
from fprime_lite.deploy.resources import ROLES, resource_role
from fprime_lite.deploy.topology import PATTERN_PORTS, Topology, TopologyError

__all__ = ["load_topology", "LoadedDeployment", "TopologyError"]

US_PER_S = 1_000_000

TOP_KEYS = {"deployment", "extends", "resources", "modules", "patterns", "connections", "rate_groups",
            "parameter_file", "startup", "time"}
MODULE_KEYS = {"include", "instances"}
INCLUDE_KEYS = {"instances", "connections"}
INSTANCE_KEYS = {"type", "base_id", "queue_size", "args"}
RESOURCE_KEYS = {"type", "args"}
RATE_GROUP_KEYS = {"driver", "base_rate_hz", "groups"}
GROUP_KEYS = {"divisor", "offset", "members"}
MEMBER_KEYS = {"port", "context"}
STARTUP_KEYS = {"sequencer", "sequence"}
TIME_KEYS = {"time_base", "epoch_us"}

_ENDPOINT = re.compile(r"^\s*([A-Za-z_]\w*)\.([A-Za-z_]\w*)\.([A-Za-z_]\w*)(?:\[(\d+)\])?\s*$")


# --- YAML with lines ----------------------------------------------------------------------------

class Loc(int):
    """A line number that also knows its file (so merged documents report the right file)."""

    file: pathlib.Path

    def __new__(cls, line: int, file: pathlib.Path):
        loc = super().__new__(cls, line)
        loc.file = file
        return loc


class YMap(dict):
    """A mapping that remembers its line and the line of each key."""

    line: int
    key_lines: dict


class YList(list):
    line: int
    item_lines: list


def _to_python(loader: yaml.SafeLoader, node: yaml.Node, path: pathlib.Path):
    if isinstance(node, yaml.MappingNode):
        loader.flatten_mapping(node)
        out = YMap()
        out.line = Loc(node.start_mark.line + 1, path)
        out.key_lines = {}
        for key_node, value_node in node.value:
            key = _to_python(loader, key_node, path)
            out.key_lines[key] = Loc(key_node.start_mark.line + 1, path)
            out[key] = _to_python(loader, value_node, path)
        return out
    if isinstance(node, yaml.SequenceNode):
        items = YList(_to_python(loader, n, path) for n in node.value)
        items.line = Loc(node.start_mark.line + 1, path)
        items.item_lines = [Loc(n.start_mark.line + 1, path) for n in node.value]
        return items
    return loader.construct_object(node, deep=True)


def parse_yaml(path: pathlib.Path):
    """Parse ``path`` safely into YMap/YList values that carry line numbers."""
    text = path.read_text(encoding="utf-8")
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = f"{mark.line + 1}" if mark is not None else "?"
        problem = getattr(exc, "problem", None) or str(exc)
        raise TopologyError([f"{path}:{line}: invalid YAML: {problem} — fix the syntax"]) from None
    finally:
        loader.dispose()
    return None if node is None else _to_python(loader, node, path)


# --- the result ---------------------------------------------------------------------------------

@dataclass
class LoadedDeployment:
    """A topology built from YAML, with the scheduler and clock that run it."""

    path: pathlib.Path
    topology: Topology
    scheduler: Scheduler
    clock: SimulatedClock
    resources: dict[str, Any] = field(default_factory=dict)
    timer: RateGroupTimer | None = None
    parameter_file: pathlib.Path | None = None
    startup_sequencer: str | None = None
    startup_sequence: pathlib.Path | None = None


# --- loading ------------------------------------------------------------------------------------

class _Loader:
    def __init__(self, path: pathlib.Path, overrides: dict | None, scheduler_factory=None,
                 role_overrides: dict | None = None):
        self.path = path.resolve() if path.is_symlink() else path
        self.scheduler_factory = scheduler_factory or Scheduler
        self.base_dir = self.path.parent
        self.problems: list[str] = []
        self.overrides = overrides or {}
        self.role_overrides = role_overrides or {}
        self.roles_built: set[str] = set()
        self.failed_instances: set[str] = set()
        #: Resources that could not be built (reported once); whatever uses them is skipped quietly.
        self.failed_resources: set[str] = set()
        self.quiet_skips = 0
        self.failed_modules: set[str] = set()  # modules whose include could not be read
        self.included_connections: list = []

    def at(self, file: pathlib.Path, line: int | None) -> str:
        return f"{file}:{line if line is not None else '?'}"

    def problem(self, file: pathlib.Path, line: int | None, message: str) -> None:
        if isinstance(line, Loc):
            file = line.file  # the node came from this file (an included or extended one)
        self.problems.append(f"{self.at(file, line)}: {message}")

    def check_keys(self, file, mapping: YMap, allowed: set, what: str) -> None:
        for key in mapping:
            if key not in allowed:
                guess = difflib.get_close_matches(str(key), sorted(allowed), n=1)
                hint = f"did you mean '{guess[0]}'?" if guess else f"allowed keys: {', '.join(sorted(allowed))}"
                self.problem(file, mapping.key_lines.get(key), f"unknown key '{key}' in {what} — {hint}")

    def expect_map(self, file, value, line, what) -> YMap | None:
        if not isinstance(value, YMap):
            self.problem(file, getattr(value, "line", line), f"{what} must be a mapping, got {_kind(value)}")
            return None
        return value

    def fail_if_problems(self) -> None:
        if self.problems:
            raise TopologyError(self.problems)

    # --- top level ---

    def load(self) -> LoadedDeployment:
        if not self.path.is_file():
            raise TopologyError([f"{self.path}: no such topology file — give the path of a topology YAML file"])
        doc = self.read_document(self.path, ())
        if doc is None:
            self.fail_if_problems()
        assert doc is not None  # read_document records a problem whenever it gives no document
        deployment = doc.get("deployment")
        if not isinstance(deployment, str) or not deployment.isidentifier():
            self.problem(self.path, doc.key_lines.get("deployment", doc.line),
                         "'deployment' must name the deployment (an identifier, e.g. ReferenceDeployment)")
            deployment = "Deployment"
        if "modules" not in doc:
            self.problem(self.path, doc.line, "missing 'modules' — declare at least one module with instances")
            self.fail_if_problems()

        clock = self.make_clock(doc)
        scheduler = self.scheduler_factory(clock)
        topology = Topology(deployment)
        resources = {"clock": clock, "scheduler": scheduler, "topology_dir": self.base_dir}
        self.build_resources(doc, resources)
        rate_cfg = self.read_rate_groups(doc)
        self.build_modules(doc, topology, resources, rate_cfg)

        self.connect_groups(self.path, doc.get("connections"), doc.key_lines.get("connections"), topology)
        for file, connections, line in self.included_connections:
            self.connect_groups(file, connections, line, topology)
        timer = self.wire_rate_groups(doc, topology, scheduler, rate_cfg)
        self.wire_patterns(doc, topology)
        if not self.problems:  # collisions and unconnected ports only mean something in a complete build
            self.problems.extend(topology.problems())
        deployment_obj = LoadedDeployment(self.path, topology, scheduler, clock, resources, timer)
        self.read_startup(doc, topology, deployment_obj)
        self.fail_if_problems()
        return deployment_obj

    # --- documents and extends ---

    def read_document(self, path: pathlib.Path, chain: tuple) -> YMap | None:
        """Parse ``path``; if it ``extends`` a base topology, merge it onto that base."""
        try:
            doc = parse_yaml(path)
        except TopologyError as exc:
            self.problems.extend(exc.problems)
            return None
        doc = self.expect_map(path, doc, 1, "the topology file")
        if doc is None:
            return None
        self.check_keys(path, doc, TOP_KEYS, "the topology file")
        if chain:  # a base document: its relative paths are relative to its own folder
            _absolutize_paths(doc, path.parent)
        if "extends" not in doc:
            return doc
        line = doc.key_lines["extends"]
        target = doc["extends"]
        if not isinstance(target, str):
            self.problem(path, line, "'extends' must be the path of a base topology file")
            return doc
        base_path = resolve_path(target, path.parent)
        if base_path.resolve() in chain or base_path.resolve() == path.resolve():
            self.problem(path, line, f"'extends: {target}' makes a cycle of topology files — remove it")
            return doc
        if not base_path.is_file():
            self.problem(path, line, f"base topology '{target}' not found (looked for {base_path})")
            return doc
        base = self.read_document(base_path, chain + (path.resolve(),))
        return doc if base is None else _merge(base, doc)

    def make_clock(self, doc: YMap) -> SimulatedClock:
        cfg = doc.get("time")
        time_base, epoch_us = TimeBase.TB_WORKSTATION_TIME, 0
        if cfg is not None:
            cfg = self.expect_map(self.path, cfg, doc.key_lines.get("time"), "'time'")
            if cfg is not None:
                self.check_keys(self.path, cfg, TIME_KEYS, "'time'")
                if "time_base" in cfg:
                    try:
                        time_base = TimeBase[cfg["time_base"]] if isinstance(cfg["time_base"], str) \
                            else TimeBase(cfg["time_base"])
                    except (KeyError, ValueError):
                        self.problem(self.path, cfg.key_lines["time_base"],
                                     f"unknown time base {cfg['time_base']!r} — use one of "
                                     f"{', '.join(t.name for t in TimeBase)}")
                if "epoch_us" in cfg:
                    epoch_us = cfg["epoch_us"]
                    if not isinstance(epoch_us, int) or isinstance(epoch_us, bool) or epoch_us < 0:
                        self.problem(self.path, cfg.key_lines["epoch_us"],
                                     "'epoch_us' must be a non-negative integer (microseconds)")
                        epoch_us = 0
        return SimulatedClock(time_base=time_base, epoch_us=epoch_us)

    # --- resources ---

    def build_resources(self, doc: YMap, resources: dict) -> None:
        section = doc.get("resources")
        if section is not None:
            section = self.expect_map(self.path, section, doc.key_lines.get("resources"), "'resources'")
        if section is not None:
            for name, spec in section.items():
                if not self._build_resource(name, spec, section, resources):
                    self.failed_resources.add(name)
        self.check_roles_taken(doc)

    def check_roles_taken(self, doc: YMap) -> None:
        """Options meant for a resource role that no resource of the topology holds."""
        for role in self.role_overrides:
            if role not in self.roles_built and not self.failed_resources:
                self.problem(self.path, doc.key_lines.get("resources"),
                             f"no resource holds the role '{role}', so {ROLES.get(role, role)} cannot apply "
                             f"— leave those options out for this topology")

    def _build_resource(self, name, spec, section: YMap, resources: dict) -> bool:
        """Build one resource into ``resources``; False (problem reported) when it cannot be."""
        line = section.key_lines.get(name)
        spec = self.expect_map(self.path, spec, line, f"resource '{name}'")
        if spec is None:
            return False
        self.check_keys(self.path, spec, RESOURCE_KEYS, f"resource '{name}'")
        factory = self.import_object(self.path, spec.get("type"), spec.key_lines.get("type", line),
                                     f"resource '{name}'")
        if factory is None:
            return False
        args = self.resolve_args(self.path, spec.get("args"), spec.key_lines.get("args", line), resources,
                                 f"resource '{name}'")
        if args is None:
            return False
        args.update(self.overrides.get(name, {}))
        role = resource_role(factory)
        if role:
            self.roles_built.add(role)
            args.update(self.role_overrides.get(role, {}))
        try:
            resources[name] = factory(**args)
        except Exception as exc:  # noqa: BLE001 - any construction failure is a user-facing problem
            given = self.role_overrides.get(role, {}) if role else {}
            options = f" with the {role} options {given}" if given else ""
            self.problem(self.path, line, f"resource '{name}' could not be created{options}: {exc}")
            return False
        return True

    def import_object(self, file, type_path, line, what):
        if not isinstance(type_path, str) or not type_path:
            self.problem(file, line, f"{what} needs 'type': an import path such as package.module.Class")
            return None
        parts = type_path.split(".")
        if len(parts) < 2:
            self.problem(file, line, f"{what}: type '{type_path}' must be a dotted import path (package.module.Class)")
            return None
        module = None
        first_error: ModuleNotFoundError | None = None
        for split in range(len(parts) - 1, 0, -1):  # the longest importable module prefix
            module_name = ".".join(parts[:split])
            try:
                module = importlib.import_module(module_name)
                break
            except ModuleNotFoundError as exc:
                if exc.name is None or not module_name.startswith(exc.name):
                    self.problem(file, line, f"{what}: importing '{module_name}' failed: {exc}")
                    return None
                first_error = first_error if split < len(parts) - 1 else exc
            except DeclarationError as exc:
                self.problem(file, line, f"{what}: {exc}")
                return None
            except Exception as exc:  # noqa: BLE001 - a broken module is reported, not raised
                self.problem(file, line, f"{what}: importing '{module_name}' failed: {type(exc).__name__}: {exc}")
                return None
        if module is None:
            module_name = ".".join(parts[:-1])
            self.problem(file, line, f"{what}: cannot import module '{module_name}' ({first_error}) — check the "
                                     f"type path")
            return None
        obj: Any = module
        for depth, attr in enumerate(parts[split:]):
            owner = obj
            obj = getattr(owner, attr, None)
            if obj is None:
                names = [n for n in dir(owner) if not n.startswith("_")]
                guess = difflib.get_close_matches(attr, names, n=1)
                prefix = ".".join(parts[:split + depth])
                hint = f" — did you mean '{prefix}.{guess[0]}'?" if guess else ""
                self.problem(file, line, f"{what}: module '{prefix}' has no '{attr}'{hint}")
                return None
        return obj

    def resolve_args(self, file, args, line, resources, what) -> dict | None:
        if args is None:
            return {}
        if not isinstance(args, YMap):
            self.problem(file, line, f"{what}: 'args' must be a mapping of keyword arguments, got {_kind(args)}")
            return None
        skips = self.quiet_skips
        out = {}
        for key, value in args.items():
            out[key] = self.resolve_value(file, value, args.key_lines.get(key), resources, what)
        return None if self.quiet_skips > skips else out

    def resolve_value(self, file, value, line, resources, what):
        if isinstance(value, str) and value.startswith("$"):
            name = value[1:]
            if name in self.failed_resources:
                self.quiet_skips += 1  # its own failure has been reported
                return None
            if name not in resources:
                self.problem(file, line, f"{what}: unknown resource '{value}' — resources: "
                                         f"{', '.join('$' + r for r in resources)}")
                return None
            return resources[name]
        if isinstance(value, dict):
            return {k: self.resolve_value(file, v, line, resources, what) for k, v in value.items()}
        if isinstance(value, list):
            return [self.resolve_value(file, v, line, resources, what) for v in value]
        return value

    # --- modules and instances ---

    def build_modules(self, doc, topology: Topology, resources, rate_cfg) -> None:
        modules = self.expect_map(self.path, doc["modules"], doc.key_lines.get("modules"), "'modules'")
        if modules is None:
            return
        for module_name, module in modules.items():
            line = modules.key_lines.get(module_name)
            if not isinstance(module_name, str) or not module_name.isidentifier():
                self.problem(self.path, line, f"module name {module_name!r} must be an identifier (e.g. CdhCore)")
                continue
            module = self.expect_map(self.path, module, line, f"module '{module_name}'")
            if module is None:
                continue
            self.check_keys(self.path, module, MODULE_KEYS, f"module '{module_name}'")
            declared: dict[str, tuple[pathlib.Path, YMap, YMap]] = {}
            if "include" in module:
                self.read_include(module, module_name, declared)
            instances = module.get("instances")
            if instances is not None:
                instances = self.expect_map(self.path, instances, module.key_lines.get("instances"),
                                            f"instances of module '{module_name}'")
                for name, spec in (instances or {}).items():
                    assert instances is not None  # the loop is over its items
                    declared[name] = (self.path, instances, spec)
            for name, (file, container, spec) in declared.items():
                self.build_instance(file, container, module_name, name, spec, topology, resources, rate_cfg)

    def read_include(self, module: YMap, module_name: str, declared: dict) -> None:
        before = len(self.problems)
        try:
            self._read_include(module, module_name, declared)
        finally:
            if len(self.problems) > before:
                self.failed_modules.add(module_name)

    def _already_reported(self, qualified: str) -> bool:
        """The instance failed to build, or its module's include failed: said once already."""
        return qualified in self.failed_instances or qualified.split(".", 1)[0] in self.failed_modules

    def _read_include(self, module: YMap, module_name: str, declared: dict) -> None:
        line = module.key_lines.get("include")
        target = module["include"]
        if not isinstance(target, str):
            self.problem(self.path, line, f"module '{module_name}': 'include' must be a file path")
            return
        path = resolve_path(target, self.base_dir)
        if not path.is_file():
            self.problem(self.path, line, f"module '{module_name}': include file '{target}' not found "
                                          f"(looked for {path}) — give a path relative to the topology file, "
                                          f"or package:path")
            return
        try:
            doc = parse_yaml(path)
        except TopologyError as exc:
            self.problems.extend(exc.problems)
            return
        doc = self.expect_map(path, doc, 1, "an included subtopology")
        if doc is None:
            return
        self.check_keys(path, doc, INCLUDE_KEYS, "an included subtopology")
        instances = doc.get("instances")
        if instances is not None:
            instances = self.expect_map(path, instances, doc.key_lines.get("instances"), "'instances'")
            for name, spec in (instances or {}).items():
                declared[name] = (path, instances, spec)
        if "connections" in doc:
            self.included_connections.append((path, doc["connections"], doc.key_lines.get("connections")))

    def build_instance(self, file, container: YMap, module: str, name, spec, topology: Topology, resources,
                       rate_cfg) -> None:
        problems_before, skips_before = len(self.problems), self.quiet_skips
        try:
            self._build_instance(file, container, module, name, spec, topology, resources, rate_cfg)
        finally:
            if len(self.problems) > problems_before or self.quiet_skips > skips_before:
                self.failed_instances.add(f"{module}.{name}")

    def _build_instance(self, file, container: YMap, module: str, name, spec, topology: Topology, resources,
                        rate_cfg) -> None:
        line = container.key_lines.get(name)
        what = f"instance {module}.{name}"
        if not isinstance(name, str) or not name.isidentifier():
            self.problem(file, line, f"instance name {name!r} must be an identifier (e.g. cmdDisp)")
            return
        spec = self.expect_map(file, spec, line, what)
        if spec is None:
            return
        self.check_keys(file, spec, INSTANCE_KEYS, what)
        cls = self.import_object(file, spec.get("type"), spec.key_lines.get("type", line), what)
        if cls is None:
            return
        if not (inspect.isclass(cls) and issubclass(cls, Component)):
            self.problem(file, spec.key_lines.get("type", line),
                         f"{what}: type '{spec['type']}' is not a component class (derive from "
                         f"PassiveComponent, QueuedComponent or ActiveComponent)")
            return
        kwargs = self.resolve_args(file, spec.get("args"), spec.key_lines.get("args", line), resources, what)
        if kwargs is None:
            return
        base_id = spec.get("base_id", 0)
        if isinstance(base_id, bool) or not isinstance(base_id, int) or not 0 <= base_id <= 0xFFFFFFFF:
            self.problem(file, spec.key_lines.get("base_id", line),
                         f"{what}: base_id must be an integer in 0..0xFFFFFFFF, got {base_id!r}")
            return
        kwargs["base_id"] = base_id
        if "queue_size" in spec:
            q = spec["queue_size"]
            if isinstance(q, bool) or not isinstance(q, int) or q < 1:
                self.problem(file, spec.key_lines["queue_size"], f"{what}: queue_size must be a positive integer")
                return
            if cls.__fprime_kind__ == "passive":
                self.problem(file, spec.key_lines["queue_size"],
                             f"{what}: {cls.__name__} is passive and has no queue — remove queue_size")
                return
            kwargs["queue_size"] = q
        qualified = f"{module}.{name}"
        kwargs.update(rate_cfg.get("init", {}).get(qualified, {}))
        try:
            component = cls(name, **kwargs)
        except TypeError as exc:
            self.problem(file, line, f"{what}: cannot create {cls.__name__} with args "
                                     f"{sorted(k for k in kwargs if k != 'base_id')}: {exc}")
            return
        except Exception as exc:  # noqa: BLE001 - reported with its location
            self.problem(file, line, f"{what}: {cls.__name__} raised while being created: {exc}")
            return
        try:
            instance = topology.add(module, component, where=self.at(file, line))
            instance.init_kwargs = dict(kwargs)  # for Deployment.restart_software
        except PortConnectionError as exc:
            self.problem(file, line, f"{exc} — rename one of them")

    # --- connections ---

    def endpoint(self, file, text, line, topology: Topology, direction: str):
        """Parse ``Module.instance.port[index]``; return (qualified instance, port, index) or None."""
        m = _ENDPOINT.match(text) if isinstance(text, str) else None
        if m is None:
            self.problem(file, line, f"'{text}' is not a port reference — write Module.instance.port or "
                                     f"Module.instance.port[index]")
            return None
        module, inst, port, index = m.group(1), m.group(2), m.group(3), m.group(4)
        qualified = f"{module}.{inst}"
        instance = topology.instances.get(qualified)
        if instance is None and self._already_reported(qualified):
            return None  # already reported where it was declared
        if instance is None:
            guess = difflib.get_close_matches(qualified, list(topology.instances), n=1)
            hint = f"did you mean '{guess[0]}'?" if guess else "declare it under 'modules'"
            self.problem(file, line, f"unknown instance '{qualified}' — {hint}")
            return None
        comp = instance.component
        ports = comp.spec.outputs if direction == "output" else comp.spec.inputs
        if port not in ports:
            guess = difflib.get_close_matches(port, list(ports), n=1)
            hint = f"did you mean '{guess[0]}'?" if guess else f"its {direction} ports: {', '.join(ports) or 'none'}"
            self.problem(file, line, f"{type(comp).__name__} {qualified} has no {direction} port '{port}' — {hint}")
            return None
        return qualified, port, int(index) if index is not None else 0

    def connect_groups(self, file, groups, line, topology: Topology) -> None:
        if groups is None:
            return
        groups = self.expect_map(file, groups, line, "'connections'")
        for group, items in (groups or {}).items():
            gline = groups.key_lines.get(group)
            if not isinstance(items, YList):
                self.problem(file, gline, f"connection group '{group}' must be a list of 'a.b.out[i] -> c.d.in[j]'")
                continue
            for text, iline in zip(items, items.item_lines, strict=True):
                if not isinstance(text, str) or text.count("->") != 1:
                    self.problem(file, iline, f"connection {text!r} must look like "
                                              f"'Module.inst.outPort[i] -> Module.inst.inPort[j]'")
                    continue
                left, right = text.split("->")
                src = self.endpoint(file, left, iline, topology, "output")
                dst = self.endpoint(file, right, iline, topology, "input")
                if src is None or dst is None:
                    continue
                self.connect(file, iline, topology, src, dst, str(group))

    def connect(self, file, line, topology, src, dst, group) -> None:
        try:
            topology.connect(src[0], src[1], src[2], dst[0], dst[1], dst[2], group=group)
        except PortConnectionError as exc:
            message = str(exc)
            if "port types differ" in message:
                message += " — connect ports of the same port type"
            elif "already connected" in message:
                message = message.replace("; an output index", " — an output index")
            elif "does not exist" in message or "has indices" in message:
                message += " — use an index within the port array"
            self.problem(file, line, message)

    # --- rate groups ---

    def read_rate_groups(self, doc) -> dict:
        cfg: dict = {"init": {}, "groups": []}
        section = doc.get("rate_groups")
        if section is None:
            return cfg
        line = doc.key_lines.get("rate_groups")
        section = self.expect_map(self.path, section, line, "'rate_groups'")
        if section is None:
            return cfg
        self.check_keys(self.path, section, RATE_GROUP_KEYS, "'rate_groups'")
        base = section.get("base_rate_hz")
        if isinstance(base, bool) or not isinstance(base, (int, float)) or not math.isfinite(base) or base <= 0:
            self.problem(self.path, section.key_lines.get("base_rate_hz", line),
                         "'rate_groups.base_rate_hz' must be a positive number (Hz), e.g. 1000")
            return cfg
        base_period_us = round(US_PER_S / base)
        if base_period_us * base != US_PER_S:
            self.problem(self.path, section.key_lines["base_rate_hz"],
                         f"base rate {base} Hz is not a whole number of microseconds — use a rate that divides "
                         f"1000000")
            return cfg
        driver = section.get("driver")
        if not isinstance(driver, str):
            self.problem(self.path, section.key_lines.get("driver", line),
                         "'rate_groups.driver' must name the RateGroupDriver instance (Module.instance)")
            return cfg
        groups = self.expect_map(self.path, section.get("groups"), section.key_lines.get("groups", line),
                                 "'rate_groups.groups'")
        if groups is None:
            return cfg
        dividers = []
        for name, group in groups.items():
            gline = groups.key_lines.get(name)
            group = self.expect_map(self.path, group, gline, f"rate group '{name}'")
            if group is None:
                continue
            self.check_keys(self.path, group, GROUP_KEYS, f"rate group '{name}'")
            divisor, offset = group.get("divisor"), group.get("offset", 0)
            if isinstance(divisor, bool) or not isinstance(divisor, int) or divisor < 1:
                self.problem(self.path, group.key_lines.get("divisor", gline),
                             f"rate group '{name}': divisor must be a positive integer (base ticks per cycle)")
                continue
            if isinstance(offset, bool) or not isinstance(offset, int) or not 0 <= offset < divisor:
                self.problem(self.path, group.key_lines.get("offset", gline),
                             f"rate group '{name}': offset must be an integer in 0..{divisor - 1}")
                continue
            members = group.get("members", YList())
            if not isinstance(members, YList):
                self.problem(self.path, group.key_lines.get("members", gline),
                             f"rate group '{name}': members must be a list of Module.instance.port")
                continue
            parsed = []
            for member, mline in zip(members, members.item_lines, strict=True):
                context = 0
                if isinstance(member, YMap):
                    self.check_keys(self.path, member, MEMBER_KEYS, f"a member of rate group '{name}'")
                    context = member.get("context", 0)
                    member = member.get("port")
                    if isinstance(context, bool) or not isinstance(context, int) or not 0 <= context <= 0xFFFFFFFF:
                        self.problem(self.path, mline, f"rate group '{name}': member context must be a U32")
                        continue
                parsed.append((member, context, mline))
            period_us = base_period_us * divisor
            dividers.append((divisor, offset))
            cfg["groups"].append((name, gline, parsed))
            cfg["init"][name] = {"contexts": [c for _, c, _ in parsed], "period_us": period_us}
        cfg["init"][driver] = {"dividers": dividers}
        cfg["driver"] = (driver, section.key_lines.get("driver", line))
        cfg["base_period_us"] = base_period_us
        return cfg

    def wire_rate_groups(self, doc, topology: Topology, scheduler, cfg) -> RateGroupTimer | None:
        if "driver" not in cfg:
            return None
        driver_name, dline = cfg["driver"]
        driver = topology.instances.get(driver_name)
        if driver is None and self._already_reported(driver_name):
            return None
        if driver is None or not isinstance(driver.component, RateGroupDriver):
            self.problem(self.path, dline, f"rate group driver '{driver_name}' must be an instance of "
                                           f"RateGroupDriver declared under 'modules'")
            return None
        for i, (name, gline, members) in enumerate(cfg["groups"]):
            group = topology.instances.get(name)
            if group is None and self._already_reported(name):
                continue
            if group is None or not isinstance(group.component, (ActiveRateGroup, PassiveRateGroup)):
                self.problem(self.path, gline, f"rate group '{name}' must be an ActiveRateGroup or "
                                               f"PassiveRateGroup instance declared under 'modules'")
                continue
            self.connect(self.path, gline, topology, (driver_name, "CycleOut", i), (name, "CycleIn", 0),
                         "RateGroups")
            for j, (member, _context, mline) in enumerate(members):
                dst = self.endpoint(self.path, member, mline, topology, "input")
                if dst is None:
                    continue
                self.connect(self.path, mline, topology, (name, "RateGroupMemberOut", j), dst, "RateGroups")
        return RateGroupTimer(scheduler, driver.component, cfg["base_period_us"])

    # --- patterns ---

    def wire_patterns(self, doc, topology: Topology) -> None:
        section = doc.get("patterns")
        if section is None:
            return
        line = doc.key_lines.get("patterns")
        section = self.expect_map(self.path, section, line, "'patterns'")
        if section is None:
            return
        self.check_keys(self.path, section, set(PATTERN_PORTS), "'patterns'")
        services = {}
        for kind, name in section.items():
            if kind not in PATTERN_PORTS:
                continue
            kline = section.key_lines.get(kind)
            instance = topology.instances.get(name) if isinstance(name, str) else None
            if instance is None and isinstance(name, str) and self._already_reported(name):
                continue
            if instance is None:
                self.problem(self.path, kline, f"pattern '{kind}': unknown instance {name!r} — name a "
                                               f"Module.instance declared under 'modules'")
                continue
            missing = [p for _, p, d in PATTERN_PORTS[kind]
                       if p not in (instance.component.spec.inputs if d == "to service"
                                    else instance.component.spec.outputs)]
            if missing:
                self.problem(self.path, kline, f"pattern '{kind}': {name} ({type(instance.component).__name__}) "
                                               f"lacks port(s) {', '.join(missing)} — name the instance that "
                                               f"serves {kind} connections")
                continue
            services[kind] = name
        try:
            topology.connect_patterns(**services)
        except (PortConnectionError, KeyError) as exc:
            self.problem(self.path, line, str(exc))

    # --- parameters and start-up ---

    def read_startup(self, doc, topology: Topology, deployment: LoadedDeployment) -> None:
        if "parameter_file" in doc:
            value = doc["parameter_file"]
            if not isinstance(value, str):
                self.problem(self.path, doc.key_lines["parameter_file"], "'parameter_file' must be a file path")
            else:
                deployment.parameter_file = resolve_path(value, self.base_dir)
        startup = doc.get("startup")
        if startup is None:
            return
        line = doc.key_lines.get("startup")
        startup = self.expect_map(self.path, startup, line, "'startup'")
        if startup is None:
            return
        self.check_keys(self.path, startup, STARTUP_KEYS, "'startup'")
        sequencer, sequence = startup.get("sequencer"), startup.get("sequence")
        if sequence is None:
            return
        if not isinstance(sequencer, str) or sequencer not in topology.instances:
            self.problem(self.path, startup.key_lines.get("sequencer", line),
                         f"'startup.sequencer' must name the sequencer instance, got {sequencer!r}")
            return
        path = resolve_path(str(sequence), self.base_dir)
        if not path.is_file():
            self.problem(self.path, startup.key_lines["sequence"], f"start-up sequence '{sequence}' not found "
                                                                   f"(looked for {path})")
            return
        deployment.startup_sequencer = sequencer
        deployment.startup_sequence = path


def _is_package_path(value: str) -> bool:
    package, sep, _ = value.partition(":")
    return bool(sep) and len(package) > 1 and package.replace(".", "").replace("_", "").isalnum()


def _absolute(value, folder: pathlib.Path):
    if not isinstance(value, str) or _is_package_path(value) or pathlib.Path(value).is_absolute():
        return value
    return str(folder.resolve() / value)


def _absolutize_paths(doc: YMap, folder: pathlib.Path) -> None:
    """Make the file paths of ``doc`` absolute, so a document merged into another keeps them."""
    if "parameter_file" in doc:
        doc["parameter_file"] = _absolute(doc["parameter_file"], folder)
    startup = doc.get("startup")
    if isinstance(startup, YMap) and "sequence" in startup:
        startup["sequence"] = _absolute(startup["sequence"], folder)
    modules = doc.get("modules")
    if isinstance(modules, YMap):
        for module in modules.values():
            if isinstance(module, YMap) and "include" in module:
                module["include"] = _absolute(module["include"], folder)


def _copy_map(m: YMap) -> YMap:
    out = YMap(m)
    out.line = m.line
    out.key_lines = dict(m.key_lines)
    return out


def _merge_maps(base: YMap, over: YMap, deep=()) -> YMap:
    """``base`` with ``over``'s entries added or replacing; keys in ``deep`` merge one level down."""
    out = _copy_map(base)
    for key, value in over.items():
        if key in deep and isinstance(out.get(key), YMap) and isinstance(value, YMap):
            value = _merge_maps(out[key], value)
        out[key] = value
        out.key_lines[key] = over.key_lines[key]
    return out


def _merge(base: YMap, over: YMap) -> YMap:
    """A topology that ``extends`` another: maps merge by name (modules, instances, resources,
    patterns, connection groups); anything else in the extending file replaces the base's."""
    out = _copy_map(base)
    out.pop("extends", None)
    for key, value in over.items():
        if key == "extends":
            continue
        if key == "modules" and isinstance(out.get(key), YMap) and isinstance(value, YMap):
            modules = _copy_map(out[key])
            for name, module in value.items():
                if isinstance(modules.get(name), YMap) and isinstance(module, YMap):
                    module = _merge_maps(modules[name], module, deep=("instances",))
                modules[name] = module
                modules.key_lines[name] = value.key_lines[name]
            value = modules
        elif key in ("resources", "patterns", "connections") and isinstance(out.get(key), YMap) \
                and isinstance(value, YMap):
            value = _merge_maps(out[key], value)
        out[key] = value
        out.key_lines[key] = over.key_lines[key]
    return out


def resolve_path(value: str, base_dir: pathlib.Path) -> pathlib.Path:
    """A path relative to ``base_dir``, or ``package:relative/path`` inside an installed package."""
    if ":" in value and not pathlib.Path(value).is_absolute():
        package, _, rest = value.partition(":")
        if package.replace(".", "").replace("_", "").isalnum() and len(package) > 1:
            try:
                module = importlib.import_module(package)
            except ImportError:
                return base_dir / value
            if module.__file__ is None:  # a namespace package has no __init__ to locate it by
                return base_dir / value
            return pathlib.Path(module.__file__).parent / rest
    path = pathlib.Path(value)
    return path if path.is_absolute() else base_dir / path


def _kind(value) -> str:
    if value is None:
        return "nothing"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    return f"{type(value).__name__} {value!r}"


def load_topology(path, overrides: dict | None = None, *, scheduler_factory=None,
                  role_overrides: dict | None = None) -> LoadedDeployment:
    """Load and validate a topology YAML file; raise :class:`TopologyError` listing every problem.

    ``overrides`` maps a resource name to keyword arguments that replace those in the file;
    ``role_overrides`` maps a resource role (:mod:`fprime_lite.deploy.resources`) to keyword
    arguments for the resource holding it (the command line's ``--scenario``, ``--seed``, ``--set``
    and ``--truth-interval`` use it). ``scheduler_factory(clock)`` makes
    the scheduler (default :class:`~fprime_lite.deploy.scheduler.Scheduler`; ``run --realtime`` passes a
    :class:`~fprime_lite.deploy.scheduler.PacedScheduler`).
    """
    return _Loader(pathlib.Path(path), overrides, scheduler_factory, role_overrides).load()
