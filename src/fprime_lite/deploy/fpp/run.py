"""Fly an FPP topology: what FPP does not say, from a run file (``docs/fpp.md`` "Running an FPP topology").

An FPP topology gives the instances (component, base id, queue size) and every connection, but not
what F´ puts in a deployment's C++ topology code: the constructor arguments (here, the simulated
spacecraft a driver talks to), the rate-group divisors, and the resources. :func:`topology_yaml`
takes those from a *run file*, a YAML file in the topology schema (``docs/topology.md``) that may
hold only:

- ``resources``, ``parameter_file``, ``startup``, ``time``, ``run``: as in a topology YAML;
- ``modules: {M: {instances: {name: {args: {...}}}}}``: constructor arguments of FPP instances;
- ``rate_groups: {base_rate_hz: N, groups: {M.rateGroup: {divisor: N}}}``: the divisors. The driver,
  the groups' order and their members are the FPP's connections (``CycleOut[i] -> group.CycleIn``,
  ``group.RateGroupMemberOut[j] -> member``);
- ``telemetry_packets: {name: SET, instance: M.inst, start_level: N}``: which of the FPP's
  ``telemetry packets`` sets flies (needed when it has several), on which ``Svc.TlmPacketizer``
  instance (needed when there are several) and from which send level (default 0), what F´'s C++
  topology passes to ``setPacketList``. The packets are the FPP's, handed over as the YAML's
  ``telemetry_packets`` section (``deploy/topology_yaml/packets.py``) so both forms configure the
  packetizer alike.

It writes the topology YAML of the FPP's instances (``type: fpp:FILE.fpp:M.Name``, bound once by
:func:`~fprime_lite.deploy.fpp.loader.load_fpp`, in the FPP's order), connections (those of the
patterns left to fprime-lite's patterns, which give Health its ping entries and the run its event
and telemetry services) and what the run file adds (its paths made absolute); ``fprime-lite run``
then flies it as any YAML deployment. Anything missing or given
twice (a divisor for a group the FPP lacks, connections in the run file) is refused first.
"""

from __future__ import annotations

import inspect
import json
import os
import pathlib
from typing import Any, Iterable

import yaml

from fprime_lite.deploy.fpp.loader import FppError, FppModel, load_fpp
from fprime_lite.deploy.topology import PATTERN_PORTS
from fprime_lite.deploy.topology_yaml.files import resolve_path

__all__ = ["RUN_FILE", "topology_yaml", "write_topology_yaml"]

#: the run file looked for beside the FPP files when none is named
RUN_FILE = "run.yaml"
_ALLOWED = {"resources", "modules", "rate_groups", "parameter_file", "startup", "time", "run", "telemetry_packets"}
#: what a run file's ``telemetry_packets`` may say (the packets themselves are the FPP's)
_PACKET_CHOICES = {"name", "instance", "start_level"}
_FROM_FPP = {"deployment": "the FPP topology's name", "connections": "the FPP topology's connections",
             "patterns": "the FPP topology's pattern connections", "extends": "the FPP files"}


def _read_run_file(path: pathlib.Path) -> dict:
    try:
        doc = yaml.safe_load(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as exc:
        raise FppError([f"{path}: the run file does not read as YAML: {exc}"]) from None
    if not isinstance(doc, dict):
        raise FppError([f"{path}: the run file must be a YAML map (resources, modules, rate_groups …)"])
    return doc


def _check_run_file(path: pathlib.Path, doc: dict, model: FppModel) -> list[str]:
    problems = []
    for key in doc:
        if key in _FROM_FPP:
            problems.append(f"{path}: '{key}' is {_FROM_FPP[key]} — remove it from the run file")
        elif key not in _ALLOWED:
            problems.append(f"{path}: unknown key '{key}' — a run file holds {', '.join(sorted(_ALLOWED))}")
    for module, body in (doc.get("modules") or {}).items():
        instances = body.get("instances") if isinstance(body, dict) else None
        if not isinstance(instances, dict) or set(body) != {"instances"}:
            problems.append(f"{path}: modules.{module}: give 'instances: {{name: {{args: {{...}}}}}}' only")
            continue
        for name, entry in instances.items():
            qualified = f"{module}.{name}"
            if qualified not in model.instances:
                problems.append(f"{path}: modules.{module}.instances.{name}: the FPP topology has no instance "
                                f"{qualified}")
            elif not isinstance(entry, dict) or set(entry) - {"args"}:
                problems.append(f"{path}: modules.{module}.instances.{name}: give 'args' only (type, base id and "
                                f"queue size are the FPP's)")
    return problems


def _rate_groups(path: pathlib.Path, doc: dict, model: FppModel,
                 connections: list[tuple[str, str, int, str, str, int]]) -> tuple[dict | None, set, list[str]]:
    """(the rate_groups section, the connections it makes, problems)."""
    cycles = sorted((c for c in connections if c[1] == "CycleOut" and c[4] == "CycleIn"), key=lambda c: c[2])
    if not cycles:
        return None, set(), ([f"{path}: 'rate_groups' given, but the FPP topology connects no rate group driver"]
                             if "rate_groups" in doc else [])
    drivers = {c[0] for c in cycles}
    given = doc.get("rate_groups")
    if not isinstance(given, dict):
        return None, set(), [f"{path}: the FPP topology drives rate groups ({', '.join(c[3] for c in cycles)}) — "
                             f"give their divisors: rate_groups: {{base_rate_hz: N, groups: {{GROUP: "
                             f"{{divisor: N}}}}}}"]
    problems = []
    if len(drivers) != 1:
        problems.append(f"{path}: the FPP topology has {len(drivers)} rate group drivers ({', '.join(sorted(drivers))})"
                        f" — fprime-lite flies one")
    if [c[2] for c in cycles] != list(range(len(cycles))):
        problems.append(f"{path}: the driver's CycleOut ports are {[c[2] for c in cycles]} — connect 0, 1, … in order")
    groups_given = given.get("groups") or {}
    if not isinstance(groups_given, dict):
        groups_given = {}
        problems.append(f"{path}: rate_groups.groups must be a map GROUP: {{divisor: N}}")
    extra = set(given) - {"base_rate_hz", "groups", "driver"}
    if extra:
        problems.append(f"{path}: rate_groups: unknown key(s) {', '.join(sorted(extra))} — give base_rate_hz and "
                        f"groups (members are the FPP's connections)")
    groups = {}
    made = {c for c in cycles}
    for c in cycles:
        name = c[3]
        divisor = (groups_given.get(name) or {}).get("divisor") if isinstance(groups_given.get(name), dict) else None
        if divisor is None:
            problems.append(f"{path}: rate group {name} has no divisor — give rate_groups.groups.{name}.divisor")
        members = sorted((m for m in connections if m[0] == name and m[1] == "RateGroupMemberOut"), key=lambda m: m[2])
        if [m[2] for m in members] != list(range(len(members))):
            problems.append(f"{path}: {name}'s RateGroupMemberOut ports are {[m[2] for m in members]} — fprime-lite "
                            f"connects 0, 1, … in order")
        made.update(members)
        groups[name] = {"divisor": divisor, "members": [f"{m[3]}.{m[4]}" for m in members]}
    for name in groups_given:
        if name not in groups:
            problems.append(f"{path}: rate_groups.groups.{name}: the FPP topology's driver does not drive it "
                            f"(it drives {', '.join(groups) or 'none'})")
    if "base_rate_hz" not in given:
        problems.append(f"{path}: rate_groups.base_rate_hz is missing — the driver's tick rate, in Hz")
    section = {"driver": next(iter(sorted(drivers))), "base_rate_hz": given.get("base_rate_hz"), "groups": groups}
    return section, made, problems


def _telemetry_packets(path: pathlib.Path, doc: dict, model: FppModel) -> tuple[dict | None, list[str]]:
    """(the topology YAML's ``telemetry_packets`` section for the FPP's packet set, problems)."""
    given = doc.get("telemetry_packets")
    sets = {s["name"]: s for s in model.telemetry_packet_sets}
    if given is not None and not isinstance(given, dict):
        return None, [f"{path}: telemetry_packets must be a map {{name: SET, instance: Module.inst, start_level: N}}"]
    given = given or {}
    problems = [f"{path}: telemetry_packets.{key}: unknown key — give {', '.join(sorted(_PACKET_CHOICES))} (the "
                f"packets are the FPP's)" for key in given if key not in _PACKET_CHOICES]
    if not sets:
        if given:
            problems.append(f"{path}: telemetry_packets given, but the FPP topology declares no telemetry packets — "
                            f"remove it or declare 'telemetry packets' in the topology")
        return None, problems
    name = given.get("name")
    if name is None and len(sets) > 1:
        return None, problems + [f"{path}: the FPP topology declares {len(sets)} telemetry packet sets "
                                 f"({', '.join(sets)}) — say which flies: telemetry_packets.name"]
    name = name if name is not None else next(iter(sets))
    if name not in sets:
        return None, problems + [f"{path}: telemetry_packets.name: no packet set {name!r} in the FPP topology "
                                 f"(it declares {', '.join(sets)})"]
    where = model.packet_set_locations.get(name, str(path))
    packetizers = [q for q, inst in model.instances.items()
                   if callable(getattr(inst.component.cls, "set_packet_list", None))]
    instance = given.get("instance")
    if not packetizers:
        return None, problems + [f"{where}: telemetry packet set {name} has no Svc.TlmPacketizer instance to fly "
                                 f"it — add one to the topology (F´'s tlmSend) in place of the Svc.TlmChan"]
    if instance is None and len(packetizers) > 1:
        return None, problems + [f"{path}: the FPP topology has {len(packetizers)} TlmPacketizer instances "
                                 f"({', '.join(packetizers)}) — say which flies {name}: telemetry_packets.instance"]
    instance = instance if instance is not None else packetizers[0]
    if instance not in packetizers:
        return None, problems + [f"{path}: telemetry_packets.instance: {instance!r} is not a TlmPacketizer instance "
                                 f"of the FPP topology (it has {', '.join(packetizers)})"]
    level = given.get("start_level", 0)
    if not isinstance(level, int) or isinstance(level, bool) or level < 0:
        problems.append(f"{path}: telemetry_packets.start_level must be a non-negative integer (a group), "
                        f"got {level!r}")
    packet_set = sets[name]
    for packet in packet_set["members"]:
        twice = sorted({c for c in packet["members"] if packet["members"].count(c) > 1})
        if twice:
            at = model.packet_set_locations.get(f"{name}.{packet['name']}", where)
            problems.append(f"{at}: packet {packet['name']} lists {', '.join(twice)} more than once — a channel "
                            f"has one slot in a packet: list it once")
    section = {"name": name, "instance": instance, "start_level": level,
               "packets": {p["name"]: {"id": p["id"], "group": p["group"], "channels": list(p["members"])}
                           for p in packet_set["members"]},
               "omit": list(packet_set["omitted"])}
    return section, problems


def _patterns(connections: list[tuple[str, str, int, str, str, int]]) -> tuple[dict[str, str], set]:
    """({pattern kind: the instance serving it}, the service ports): each service is the one
    instance whose pattern port (``CdhCore.cmdDisp.compCmdReg`` …) the FPP's connections reach.
    Their connections are left to fprime-lite's patterns, which also give Health its ping entries
    and the run its event and telemetry services (the port numbers are fprime-lite's)."""
    patterns: dict[str, str] = {}
    ports: set[tuple[str, str]] = set()
    for kind, entries in PATTERN_PORTS.items():
        service_port = next(port for _, port, direction in entries if direction == "to service")
        services = {t for _, _, _, t, tp, _ in connections if tp == service_port}
        if len(services) == 1:
            patterns[kind] = service = services.pop()
            ports.update((service, port) for _, port, _ in entries)
    return patterns, ports


def _required_args(cls: type) -> list[str]:
    """The constructor arguments of component class ``cls`` without a default, beyond what every
    instance gets (its name, base id, queue size)."""
    try:
        parameters = list(inspect.signature(cls).parameters.values())[1:]  # the first is the instance name
    except (TypeError, ValueError):
        return []
    return [p.name for p in parameters if p.default is p.empty and p.name not in ("base_id", "queue_size")
            and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]


def topology_yaml(model: FppModel, run_file: pathlib.Path) -> dict:
    """The topology YAML (as data) that flies FPP model ``model`` with what ``run_file`` adds."""
    run_file = run_file.resolve()
    doc = _read_run_file(run_file)
    problems = _check_run_file(run_file, doc, model)
    rate_groups, made, found = _rate_groups(run_file, doc, model, model.connections)
    problems += found
    packets, found = _telemetry_packets(run_file, doc, model)
    problems += found
    if problems:
        raise FppError(problems)
    given = {f"{module}.{name}": entry.get("args") or {}
             for module, body in (doc.get("modules") or {}).items()
             for name, entry in (body.get("instances") or {}).items()}
    modules: dict[str, Any] = {}
    for qualified, instance in model.instances.items():
        entry: dict[str, Any] = {"type": f"fpp:{model.component_files[instance.fpp_component]}:"
                                         f"{instance.fpp_component}",
                                 "base_id": instance.component.base_id}
        if instance.queue_size is not None:
            entry["queue_size"] = instance.queue_size
        args = given.get(qualified, {})
        missing = [n for n in _required_args(instance.component.cls) if n not in args]
        if missing:
            module, _, name = qualified.rpartition(".")
            problems.append(f"{run_file}: instance {qualified} ({instance.fpp_component}, "
                            f"{instance.component.cls.__qualname__}) needs constructor argument(s) "
                            f"{', '.join(missing)} — give them in modules.{module}.instances.{name}.args")
        if args:
            entry["args"] = args
        modules.setdefault(instance.module, {"instances": {}})["instances"][instance.name] = entry
    if problems:
        raise FppError(problems)
    patterns, service_ports = _patterns(model.connections)
    connections = [f"{s}.{sp}[{si}] -> {t}.{tp}[{ti}]" for s, sp, si, t, tp, ti in model.connections
                   if (s, sp, si, t, tp, ti) not in made and (s, sp) not in service_ports
                   and (t, tp) not in service_ports]
    out: dict[str, Any] = {"deployment": model.deployment}
    out.update({key: doc[key] for key in ("resources", "time", "run") if key in doc})
    out.update({"modules": modules, "connections": {"FPP": connections}, "patterns": patterns})
    if rate_groups is not None:
        out["rate_groups"] = rate_groups
    if packets is not None:
        out["telemetry_packets"] = packets
    # the run file's own paths, absolute and normalised (so that messages name them plainly)
    if isinstance(doc.get("parameter_file"), str):
        out["parameter_file"] = _absolute(doc["parameter_file"], run_file.parent)
    if isinstance(doc.get("startup"), dict) and isinstance(doc["startup"].get("sequence"), str):
        out["startup"] = {**doc["startup"], "sequence": _absolute(doc["startup"]["sequence"], run_file.parent)}
    return out


def _absolute(value: str, folder: pathlib.Path) -> str:
    resolved = resolve_path(value, folder)
    return os.path.normpath(resolved) if resolved.is_absolute() else value


def write_topology_yaml(paths: Iterable[str | pathlib.Path], folder: pathlib.Path, *,
                        imports: Iterable[str | pathlib.Path] = (), framework: bool = True,
                        run_file: str | pathlib.Path | None = None) -> pathlib.Path:
    """Bind FPP ``paths`` (:func:`~fprime_lite.deploy.fpp.loader.load_fpp`), write the topology YAML
    that flies them into ``folder`` and return its path. ``run_file`` defaults to ``run.yaml``
    beside the first FPP file; a missing one is refused with what it must give."""
    files = [pathlib.Path(p) for p in paths]
    model = load_fpp(files, imports=imports, framework=framework)
    chosen = pathlib.Path(run_file) if run_file is not None else files[0].parent / RUN_FILE
    if not chosen.is_file():
        raise FppError([f"{chosen}: no run file — an FPP topology does not say the constructor arguments, "
                        f"rate-group divisors and resources a run needs: write them in {chosen.name} beside the "
                        f"FPP files, or name the file with --run-file (docs/fpp.md \"Running an FPP topology\")"])
    text = json.dumps(topology_yaml(model, chosen), indent=1)  # JSON is YAML: no quoting surprises
    out = folder / f"{model.deployment}.fpp-topology.yaml"
    out.write_text(text, encoding="utf-8")
    return out
