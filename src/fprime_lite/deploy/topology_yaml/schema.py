"""Stage 2 of loading a topology: check the document's shape and turn it into typed configuration.

:func:`read_config` takes the merged document (``extends`` already applied) and returns a
:class:`TopologyConfig`: plain dataclasses whose fields have the types they name, every value
checked (keys known, names identifiers, numbers in range, paths well formed, port references
parsed) and every include file read. Nothing is imported or built here; what needs the classes
(does the port exist? is the type a component?) is checked by the build and wire stages.
"""

from __future__ import annotations

import math
import pathlib
import re
from dataclasses import dataclass, field
from typing import Any

from fprime_lite.deploy.topology import PATTERN_PORTS
from fprime_lite.deploy.topology_yaml.files import is_file, parse_into, path_problem, resolve_path
from fprime_lite.deploy.topology_yaml.parse import YList, YMap, kind
from fprime_lite.deploy.topology_yaml.problems import Problems
from fprime_lite.model.time import US_PER_S, TimeBase

__all__ = ["TopologyConfig", "TimeConfig", "ResourceConfig", "ModuleConfig", "InstanceConfig", "EndpointRef",
           "ConnectionConfig", "RateGroupsConfig", "RateGroupConfig", "MemberConfig", "PatternConfig",
           "StartupConfig", "RunConfig", "read_config", "parse_endpoint", "TYPE_PATH"]

U32_MAX = 0xFFFFFFFF

MODULE_KEYS = {"include", "instances"}
INCLUDE_KEYS = {"instances", "connections"}
INSTANCE_KEYS = {"type", "base_id", "queue_size", "args"}
RESOURCE_KEYS = {"type", "args"}
RATE_GROUP_KEYS = {"driver", "base_rate_hz", "groups"}
GROUP_KEYS = {"divisor", "offset", "members"}
MEMBER_KEYS = {"port", "context"}
STARTUP_KEYS = {"sequencer", "sequence"}
TIME_KEYS = {"time_base", "epoch_us"}
RUN_KEYS = {"duration_s"}
#: Longest default run a topology may declare, simulated seconds (a year).
MAX_RUN_S = 366 * 86400.0

#: An import path: dotted identifiers, at least module.Name, no dunder parts.
TYPE_PATH = re.compile(r"^[A-Za-z_]\w*(\.[A-Za-z_]\w*)+$")
_ENDPOINT = re.compile(r"^\s*([A-Za-z_]\w*)\.([A-Za-z_]\w*)\.([A-Za-z_]\w*)(?:\[(\d{1,9})\])?\s*$")


# --- the configuration ---------------------------------------------------------------------------

@dataclass(frozen=True)
class TimeConfig:
    """The deployment clock: its F´ time base and the epoch (µs) it starts from."""

    time_base: TimeBase = TimeBase.TB_WORKSTATION_TIME
    epoch_us: int = 0


@dataclass
class ResourceConfig:
    """``resources.NAME``: the import path of a resource class or factory and its arguments."""

    name: str
    line: int | None
    type_path: str
    type_line: int | None
    args: dict[str, Any]
    args_line: int | None
    arg_lines: dict[str, int | None] = field(default_factory=dict)


@dataclass
class InstanceConfig:
    """One component instance: where it was declared, its class path, ids and constructor args."""

    module: str
    name: str
    file: pathlib.Path
    line: int | None
    type_path: str
    type_line: int | None
    base_id: int
    args: dict[str, Any]
    args_line: int | None
    arg_lines: dict[str, int | None] = field(default_factory=dict)
    queue_size: int | None = None
    queue_line: int | None = None

    @property
    def qualified(self) -> str:
        return f"{self.module}.{self.name}"

    @property
    def where(self) -> str:
        return f"{self.file}:{self.line if self.line is not None else '?'}"


@dataclass
class ModuleConfig:
    name: str
    line: int | None
    instances: list[InstanceConfig] = field(default_factory=list)


@dataclass(frozen=True)
class EndpointRef:
    """``Module.instance.port[index]``, parsed; ``text`` as written."""

    instance: str
    port: str
    index: int
    text: str


@dataclass
class ConnectionConfig:
    file: pathlib.Path
    line: int | None
    group: str
    source: EndpointRef
    target: EndpointRef


@dataclass
class MemberConfig:
    """A rate-group member: the input port it calls and the context it passes."""

    port: EndpointRef | None   # None: malformed (reported); the member keeps its index
    context: int
    line: int | None


@dataclass
class RateGroupConfig:
    """One rate group: fires when ``tick % divisor == offset``, every ``period_us``."""

    name: str
    line: int | None
    divisor: int
    offset: int
    period_us: int
    members: list[MemberConfig] = field(default_factory=list)

    def init_args(self) -> dict[str, Any]:
        """The constructor arguments the loader gives the rate-group component."""
        return {"contexts": [m.context for m in self.members], "period_us": self.period_us}


@dataclass
class RateGroupsConfig:
    """``rate_groups``: the driver, its base tick and the groups in ``CycleOut`` order."""

    driver: str
    driver_line: int | None
    base_period_us: int
    groups: list[RateGroupConfig] = field(default_factory=list)

    def init_args(self, qualified: str) -> dict[str, Any]:
        """Constructor arguments for instance ``qualified`` (the driver, a group, or none)."""
        if qualified == self.driver:
            return {"dividers": [(g.divisor, g.offset) for g in self.groups]}
        for group in self.groups:
            if group.name == qualified:
                return group.init_args()
        return {}


@dataclass
class PatternConfig:
    kind: str
    instance: str
    line: int | None


@dataclass
class StartupConfig:
    sequencer: str
    sequencer_line: int | None
    sequence: pathlib.Path
    sequence_text: str
    sequence_line: int | None


@dataclass(frozen=True)
class RunConfig:
    """``run``: how ``fprime-lite run`` flies the deployment when the command line does not say."""

    duration_s: float | None = None
    duration_line: int | None = None


@dataclass
class TopologyConfig:
    """A whole topology file, checked and typed."""

    path: pathlib.Path
    deployment: str
    time: TimeConfig = field(default_factory=TimeConfig)
    resources: list[ResourceConfig] = field(default_factory=list)
    modules: list[ModuleConfig] = field(default_factory=list)
    connections: list[ConnectionConfig] = field(default_factory=list)
    rate_groups: RateGroupsConfig | None = None
    patterns: list[PatternConfig] = field(default_factory=list)
    patterns_line: int | None = None
    resources_line: int | None = None
    parameter_file: pathlib.Path | None = None
    parameter_file_line: int | None = None
    startup: StartupConfig | None = None
    run: RunConfig = field(default_factory=RunConfig)
    #: the ``telemetry_packets`` section as written (checked when the instances exist: packets.py)
    telemetry_packets: Any = None
    telemetry_packets_line: int | None = None

    @property
    def instances(self) -> list[InstanceConfig]:
        return [i for m in self.modules for i in m.instances]


# --- reading ---------------------------------------------------------------------------------------

def _is_int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _key_lines(value: Any) -> dict:
    return dict(value.key_lines) if isinstance(value, YMap) else {}


def parse_endpoint(text: Any) -> EndpointRef | None:
    """``Module.instance.port[index]`` → :class:`EndpointRef`, or None if it is not one."""
    m = _ENDPOINT.match(text) if isinstance(text, str) else None
    if m is None:
        return None
    module, inst, port, index = m.groups()
    return EndpointRef(f"{module}.{inst}", port, int(index) if index is not None else 0, text)


class _Reader:
    def __init__(self, path: pathlib.Path, problems: Problems):
        self.path = path
        self.base_dir = path.parent
        self.problems = problems

    def add(self, line: int | None, message: str, file: pathlib.Path | None = None) -> None:
        self.problems.add(file or self.path, line, message)

    def endpoint(self, file: pathlib.Path, text: Any, line: int | None) -> EndpointRef | None:
        ref = parse_endpoint(text)
        if ref is None:
            shown = text if isinstance(text, str) else kind(text)
            self.add(line, f"'{shown}' is not a port reference — write Module.instance.port or "
                           f"Module.instance.port[index]", file)
        return ref

    def type_path(self, file: pathlib.Path, value: Any, line: int | None, what: str) -> str | None:
        if not isinstance(value, str) or not value:
            self.add(line, f"{what} needs 'type' — give an import path such as package.module.Class", file)
            return None
        if value.startswith("fpp:"):  # an FPP component definition (docs/fpp.md): fpp:FILE.fpp[:M.Name]
            if not value[4:].split(":", 1)[0].endswith(".fpp"):
                self.add(line, f"{what}: type '{value[:80]}' must name an FPP file — write fpp:file.fpp or "
                               f"fpp:file.fpp:Module.Component", file)
                return None
            return value
        if not TYPE_PATH.match(value) or any(p.startswith("__") for p in value.split(".")):
            self.add(line, f"{what}: type '{value[:80]}' must be a dotted import path — write "
                           f"package.module.Class", file)
            return None
        return value

    def args(self, file: pathlib.Path, value: Any, line: int | None, what: str) -> dict[str, Any] | None:
        if value is None:
            return {}
        if not isinstance(value, YMap):
            self.add(line, f"{what}: 'args' must be a mapping of keyword arguments, got {kind(value)} — write "
                           f"args: {{name: value, ...}}", file)
            return None
        ok = True
        for key in value:
            if not isinstance(key, str) or not key.isidentifier():
                self.add(value.key_lines.get(key, line), f"{what}: argument name {key!r} must be an identifier "
                                                         f"— use the constructor's keyword argument names", file)
                ok = False
        return dict(value) if ok else None

    def existing_file(self, value: Any, line: int | None, key: str, what: str, fix: str) -> pathlib.Path | None:
        """The file ``value`` names (relative to the topology, or package:path), or None (reported)."""
        why = path_problem(value)
        if why is not None:
            self.add(line, f"{key} {why}")
            return None
        path = resolve_path(value, self.base_dir)
        if not is_file(path):
            self.add(line, f"{what} '{value}' not found (looked for {path}) — {fix}")
            return None
        return path

    # --- sections ---

    def read(self, doc: YMap) -> TopologyConfig:
        deployment = doc.get("deployment")
        if not isinstance(deployment, str) or not deployment.isidentifier():
            self.add(doc.key_lines.get("deployment", doc.line),
                     "'deployment' must name the deployment — give an identifier, e.g. ReferenceDeployment")
            deployment = "Deployment"
        config = TopologyConfig(self.path, deployment)
        config.time = self.time(doc)
        config.run = self.run(doc)
        config.resources = self.resources(doc)
        config.resources_line = doc.key_lines.get("resources")
        if "modules" not in doc:
            self.add(doc.line, "missing 'modules' — declare at least one module with instances")
        else:
            config.modules = self.modules(doc["modules"], doc.key_lines.get("modules"), config)
        top = doc.get("connections")
        if top is not None:
            config.connections[:0] = self.connections(self.path, top, doc.key_lines.get("connections"))
        config.rate_groups = self.rate_groups(doc)
        config.patterns, config.patterns_line = self.patterns(doc)
        config.telemetry_packets = doc.get("telemetry_packets")
        config.telemetry_packets_line = doc.key_lines.get("telemetry_packets")
        self.files(doc, config)
        return config

    def time(self, doc: YMap) -> TimeConfig:
        cfg = doc.get("time")
        if cfg is None:
            return TimeConfig()
        cfg = self.problems.expect_map(self.path, cfg, doc.key_lines.get("time"), "'time'")
        if cfg is None:
            return TimeConfig()
        self.problems.check_keys(self.path, cfg, TIME_KEYS, "'time'")
        time_base, epoch_us = TimeBase.TB_WORKSTATION_TIME, 0
        if "time_base" in cfg:
            value = cfg["time_base"]
            try:
                time_base = TimeBase[value] if isinstance(value, str) else TimeBase(value)
            except (KeyError, ValueError, TypeError):
                self.add(cfg.key_lines["time_base"], f"unknown time base {value!r} — use one of "
                                                     f"{', '.join(t.name for t in TimeBase)}")
        if "epoch_us" in cfg:
            value = cfg["epoch_us"]
            if not _is_int(value) or not 0 <= value < 2 ** 63:
                self.add(cfg.key_lines["epoch_us"], "'epoch_us' must be a non-negative integer (microseconds) — e.g. 0")
            else:
                epoch_us = value
        return TimeConfig(time_base, epoch_us)

    def run(self, doc: YMap) -> RunConfig:
        cfg = doc.get("run")
        if cfg is None:
            return RunConfig()
        cfg = self.problems.expect_map(self.path, cfg, doc.key_lines.get("run"), "'run'")
        if cfg is None:
            return RunConfig()
        self.problems.check_keys(self.path, cfg, RUN_KEYS, "'run'")
        if "duration_s" not in cfg:
            return RunConfig()
        value, line = cfg["duration_s"], cfg.key_lines.get("duration_s")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
                or not 0 < value <= MAX_RUN_S:
            self.add(line, f"'run.duration_s' must be a positive number of simulated seconds (at most "
                           f"{MAX_RUN_S:.0f}), got {value!r} — e.g. 6000")
            return RunConfig()
        return RunConfig(float(value), line)

    def resources(self, doc: YMap) -> list[ResourceConfig]:
        section = doc.get("resources")
        if section is None:
            return []
        section = self.problems.expect_map(self.path, section, doc.key_lines.get("resources"), "'resources'")
        out: list[ResourceConfig] = []
        if section is None:
            return out
        for name, spec in section.items():
            line = section.key_lines.get(name)
            if not isinstance(name, str) or not name.isidentifier():
                self.add(line, f"resource name {name!r} must be an identifier — rename it (instances refer to "
                               f"it as $name)")
                continue
            what = f"resource '{name}'"
            spec = self.problems.expect_map(self.path, spec, line, what)
            if spec is None:
                self.problems.failed_resources.add(name)
                continue
            self.problems.check_keys(self.path, spec, RESOURCE_KEYS, what)
            type_line = spec.key_lines.get("type", line)
            type_path = self.type_path(self.path, spec.get("type"), type_line, what)
            args_line = spec.key_lines.get("args", line)
            args = self.args(self.path, spec.get("args"), args_line, what)
            if type_path is None or args is None:
                self.problems.failed_resources.add(name)
                continue
            out.append(ResourceConfig(name, line, type_path, type_line, args, args_line, _key_lines(spec.get("args"))))
        return out

    def modules(self, section: Any, line: int | None, config: TopologyConfig) -> list[ModuleConfig]:
        section = self.problems.expect_map(self.path, section, line, "'modules'")
        out = []
        for module_name, module in (section or {}).items():
            mline = section.key_lines.get(module_name)
            if not isinstance(module_name, str) or not module_name.isidentifier():
                self.add(mline, f"module name {module_name!r} must be an identifier — rename it (e.g. CdhCore)")
                continue
            module = self.problems.expect_map(self.path, module, mline, f"module '{module_name}'")
            if module is None:
                self.problems.failed_modules.add(module_name)
                continue
            self.problems.check_keys(self.path, module, MODULE_KEYS, f"module '{module_name}'")
            declared: dict[Any, tuple[pathlib.Path, YMap, Any]] = {}
            if "include" in module:
                before = len(self.problems)
                self.include(module, module_name, declared, config)
                if len(self.problems) > before:
                    self.problems.failed_modules.add(module_name)
            instances = module.get("instances")
            if instances is not None:
                checked = self.problems.expect_map(self.path, instances, module.key_lines.get("instances"),
                                                   f"instances of module '{module_name}'")
                if checked is not None:
                    for name, spec in checked.items():
                        declared[name] = (self.path, checked, spec)
            parsed = ModuleConfig(module_name, mline)
            for name, (file, container, spec) in declared.items():
                before = len(self.problems)
                instance = self.instance(file, container, module_name, name, spec)
                if instance is not None:
                    parsed.instances.append(instance)
                elif len(self.problems) > before and isinstance(name, str):
                    self.problems.failed_instances.add(f"{module_name}.{name}")
            out.append(parsed)
        return out

    def include(self, module: YMap, module_name: str, declared: dict, config: TopologyConfig) -> None:
        path = self.existing_file(module["include"], module.key_lines.get("include"),
                                  f"module '{module_name}': 'include'", f"module '{module_name}': include file",
                                  "give a path relative to the topology file, or package:path")
        if path is None:
            return
        doc = parse_into(path, self.problems, (self.path, module.key_lines.get("include")))
        if doc is None and len(self.problems):
            return
        doc = self.problems.expect_map(path, doc, 1, "an included subtopology")
        if doc is None:
            return
        self.problems.check_keys(path, doc, INCLUDE_KEYS, "an included subtopology")
        instances = doc.get("instances")
        if instances is not None:
            instances = self.problems.expect_map(path, instances, doc.key_lines.get("instances"), "'instances'")
            for name, spec in (instances or {}).items():
                declared[name] = (path, instances, spec)
        if "connections" in doc:
            config.connections.extend(self.connections(path, doc["connections"], doc.key_lines.get("connections")))

    def instance(self, file: pathlib.Path, container: YMap, module: str, name: Any,
                 spec: Any) -> InstanceConfig | None:
        line = container.key_lines.get(name)
        if not isinstance(name, str) or not name.isidentifier():
            self.add(line, f"instance name {name!r} must be an identifier — rename it (e.g. cmdDisp)", file)
            return None
        what = f"instance {module}.{name}"
        spec = self.problems.expect_map(file, spec, line, what)
        if spec is None:
            return None
        self.problems.check_keys(file, spec, INSTANCE_KEYS, what)
        type_path = self.type_path(file, spec.get("type"), spec.key_lines.get("type", line), what)
        args_line = spec.key_lines.get("args", line)
        args = self.args(file, spec.get("args"), args_line, what)
        base_id = spec.get("base_id", 0)
        ok = type_path is not None and args is not None
        if not _is_int(base_id) or not 0 <= base_id <= U32_MAX:
            self.add(spec.key_lines.get("base_id", line),
                     f"{what}: base_id must be an integer in 0..0xFFFFFFFF, got {base_id!r} — give a 32-bit "
                     f"base id", file)
            ok = False
        queue_size = spec.get("queue_size")
        queue_line = spec.key_lines.get("queue_size")
        if "queue_size" in spec and (not _is_int(queue_size) or not 1 <= queue_size <= 1_000_000):
            self.add(queue_line, f"{what}: queue_size must be a positive integer (at most 1000000) — e.g. 10", file)
            ok = False
        if not ok or type_path is None or args is None:
            return None
        return InstanceConfig(module, name, file, line, type_path, spec.key_lines.get("type", line), base_id,
                              args, args_line, _key_lines(spec.get("args")), queue_size, queue_line)

    def connections(self, file: pathlib.Path, groups: Any, line: int | None) -> list[ConnectionConfig]:
        groups = self.problems.expect_map(file, groups, line, "'connections'")
        out = []
        for group, items in (groups or {}).items():
            gline = groups.key_lines.get(group)
            if not isinstance(items, YList):
                self.add(gline, f"connection group '{group}' must be a list — write one "
                               f"'- Module.inst.outPort[i] -> Module.inst.inPort[j]' per line", file)
                continue
            for text, iline in zip(items, items.item_lines, strict=True):
                if not isinstance(text, str) or text.count("->") != 1:
                    self.add(iline, f"connection {text!r} must look like "
                                    f"'Module.inst.outPort[i] -> Module.inst.inPort[j]' — write one '->' between two "
                                    f"port references", file)
                    continue
                left, right = text.split("->")
                src = self.endpoint(file, left, iline)
                dst = self.endpoint(file, right, iline)
                if src is not None and dst is not None:
                    out.append(ConnectionConfig(file, iline, str(group), src, dst))
        return out

    def rate_groups(self, doc: YMap) -> RateGroupsConfig | None:
        section = doc.get("rate_groups")
        if section is None:
            return None
        line = doc.key_lines.get("rate_groups")
        section = self.problems.expect_map(self.path, section, line, "'rate_groups'")
        if section is None:
            return None
        self.problems.check_keys(self.path, section, RATE_GROUP_KEYS, "'rate_groups'")
        base = section.get("base_rate_hz")
        if isinstance(base, bool) or not isinstance(base, (int, float)) or not math.isfinite(base) \
                or not 0 < base <= US_PER_S:
            self.add(section.key_lines.get("base_rate_hz", line),
                     "'rate_groups.base_rate_hz' must be a positive number (Hz) of at most 1000000 — e.g. 1000")
            return None
        base_period_us = round(US_PER_S / base)
        if base_period_us * base != US_PER_S:
            self.add(section.key_lines["base_rate_hz"],
                     f"base rate {base} Hz is not a whole number of microseconds — use a rate that divides 1000000")
            return None
        driver = section.get("driver")
        if not isinstance(driver, str):
            self.add(section.key_lines.get("driver", line),
                     "'rate_groups.driver' must name the RateGroupDriver instance — write Module.instance")
            return None
        groups = self.problems.expect_map(self.path, section.get("groups"), section.key_lines.get("groups", line),
                                          "'rate_groups.groups'")
        if groups is None:
            return None
        config = RateGroupsConfig(driver, section.key_lines.get("driver", line), base_period_us)
        for name, group in groups.items():
            parsed = self.rate_group(name, group, groups.key_lines.get(name), base_period_us)
            if parsed is not None:
                config.groups.append(parsed)
        return config

    def rate_group(self, name: Any, group: Any, gline: int | None, base_period_us: int) -> RateGroupConfig | None:
        group = self.problems.expect_map(self.path, group, gline, f"rate group '{name}'")
        if group is None:
            return None
        if not isinstance(name, str):
            self.add(gline, f"rate group {name!r} must be named by its instance — write Module.instance")
            return None
        self.problems.check_keys(self.path, group, GROUP_KEYS, f"rate group '{name}'")
        divisor, offset = group.get("divisor"), group.get("offset", 0)
        if not _is_int(divisor) or not 1 <= divisor <= U32_MAX:
            self.add(group.key_lines.get("divisor", gline),
                     f"rate group '{name}': divisor must be a positive integer (base ticks per cycle) — e.g. 20")
            return None
        if not _is_int(offset) or not 0 <= offset < divisor:
            self.add(group.key_lines.get("offset", gline),
                     f"rate group '{name}': offset must be an integer in 0..{divisor - 1} — give the base tick of "
                          f"the cycle on which it fires")
            return None
        members = group.get("members", YList())
        if not isinstance(members, YList):
            self.add(group.key_lines.get("members", gline),
                     f"rate group '{name}': members must be a list — write one Module.instance.port per line")
            return None
        parsed = RateGroupConfig(name, gline, divisor, offset, base_period_us * divisor)
        for member, mline in zip(members, members.item_lines, strict=True):
            context = 0
            if isinstance(member, YMap):
                self.problems.check_keys(self.path, member, MEMBER_KEYS, f"a member of rate group '{name}'")
                context = member.get("context", 0)
                member = member.get("port")
                if not _is_int(context) or not 0 <= context <= U32_MAX:
                    self.add(mline, f"rate group '{name}': member context must be a U32 — give an integer in "
                                    f"0..4294967295")
                    continue
            parsed.members.append(MemberConfig(self.endpoint(self.path, member, mline), context, mline))
        return parsed

    def patterns(self, doc: YMap) -> tuple[list[PatternConfig], int | None]:
        section = doc.get("patterns")
        line = doc.key_lines.get("patterns")
        if section is None:
            return [], line
        section = self.problems.expect_map(self.path, section, line, "'patterns'")
        if section is None:
            return [], line
        self.problems.check_keys(self.path, section, set(PATTERN_PORTS), "'patterns'")
        out = []
        for pattern_kind, name in section.items():
            if pattern_kind not in PATTERN_PORTS:
                continue
            kline = section.key_lines.get(pattern_kind)
            if not isinstance(name, str):
                self.add(kline, f"pattern '{pattern_kind}': unknown instance {name!r} — name a Module.instance "
                                f"declared under 'modules'")
                continue
            out.append(PatternConfig(pattern_kind, name, kline))
        return out, line

    def files(self, doc: YMap, config: TopologyConfig) -> None:
        if "parameter_file" in doc:
            value, line = doc["parameter_file"], doc.key_lines["parameter_file"]
            why = path_problem(value)
            if why is not None:
                self.add(line, f"'parameter_file' {why}")
            else:
                config.parameter_file = resolve_path(value, self.base_dir)
                config.parameter_file_line = line
        startup = doc.get("startup")
        if startup is None:
            return
        line = doc.key_lines.get("startup")
        startup = self.problems.expect_map(self.path, startup, line, "'startup'")
        if startup is None:
            return
        self.problems.check_keys(self.path, startup, STARTUP_KEYS, "'startup'")
        sequencer, sequence = startup.get("sequencer"), startup.get("sequence")
        if sequence is None:
            return
        sline = startup.key_lines["sequence"]
        if not isinstance(sequencer, str):
            self.add(startup.key_lines.get("sequencer", line),
                     f"'startup.sequencer' must name the sequencer instance, got {sequencer!r} — write "
                     f"Module.instance")
            return
        path = self.existing_file(sequence, sline, "'startup.sequence'", "start-up sequence",
                                  "give a path relative to the topology file")
        if path is None:
            return
        config.startup = StartupConfig(sequencer, startup.key_lines.get("sequencer", line), path, sequence, sline)


def read_config(doc: YMap, path: pathlib.Path, problems: Problems) -> TopologyConfig:
    """Check ``doc`` (the topology at ``path``, ``extends`` merged) and type it; problems go to
    ``problems``, and whatever is malformed is left out of the result."""
    return _Reader(path, problems).read(doc)

