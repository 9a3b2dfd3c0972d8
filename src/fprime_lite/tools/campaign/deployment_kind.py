"""The framework's run kind ``deployment``: fly a whole topology (the flight software) for a while.

Run section::

    run:
      kind: deployment
      topology: ../deployments/proves_ref/topology.yaml   # relative to the campaign file
      duration_s: 5580
      parameter_file: flight.dat      # optional: base parameter file (default: the topology's)
      sequence: startup.seq           # optional: start-up sequence (default: the topology's)
      stop_on_events: [ReferenceDeployment.detumbleManager.DetumbleCompleted]   # optional
      stop_when: ["spin_settled_for_s >= 300"]   # optional: conditions on the reports' progress values

``duration_s`` may be left out: the topology's ``run.duration_s`` (else 600 s) is used. The run ends
early at the first listed event, or once every ``stop_when`` condition holds
(:mod:`fprime_lite.tools.stop_condition`); its summary's ``stopped_by`` says which.

Varied keys: ``topology``, ``duration_s``, ``params.Module.inst.PARAM`` (a struct member as
``params.Module.inst.PARAM.member``) and ``scenario.KEY.PATH``.

- Parameters are written into a parameter file (the base file's records, these replaced) that
  PrmDb loads at start-up, as an uplinked file would be; they are read back from the component
  after the run (``paramGet``'s value).
- Scenario values go to the resource holding the ``simulation`` role
  (:mod:`fprime_lite.deploy.resources`) as ``settings: ["KEY.PATH=VALUE", ...]`` with the run's
  ``seed``, and are read back before the run flies from the built resource that offers
  ``read_setting(key_path)``.
"""

from __future__ import annotations

import dataclasses
import pathlib

from fprime_lite.model.errors import did_you_mean
from fprime_lite.tools.campaign.errors import RunSetupError
from fprime_lite.tools.campaign.kinds import Prepared, RunKind, RunOutput, RunRequest
from fprime_lite.tools.campaign.values import plain, yaml_text

__all__ = ["DEPLOYMENT_RUN"]

FIELDS = frozenset({"topology", "duration_s", "parameter_file", "sequence", "stop_on_events", "stop_when"})
REQUIRED = frozenset({"topology"})


def check_key(key: str) -> str | None:
    if key in ("topology", "duration_s"):
        return None
    if key.startswith("params."):
        if len(key.split(".")) < 4:
            return "a parameter key is params.Module.instance.PARAM (or params.Module.instance.PARAM.member)"
        return None
    if key.startswith("scenario.") and len(key) > len("scenario."):
        return None
    return ("a deployment run varies topology, duration_s, params.Module.instance.PARAM or "
            "scenario.KEY.PATH")


def _declared(topology) -> dict:
    out = {}
    for instance in topology.instances.values():
        comp = instance.component
        for p in comp.spec.params:
            out[f"{instance.qualified_name}.{p.name}"] = (instance.qualified_name, comp.base_id + p.local_id, p)
    return out


def _split_param(key: str, declared: dict) -> tuple[str, list[str]]:
    parts = key[len("params."):].split(".")
    name = ".".join(parts[:3])
    if name not in declared:
        hint = did_you_mean(name, declared, " (fprime-lite dict lists the parameters)", " — did you mean params.{}?")
        raise RunSetupError(f"the topology has no parameter {name}{hint}", key)
    return name, parts[3:]


def _with_member(value, members: list[str], new, key: str):
    if not members:
        return new
    if not dataclasses.is_dataclass(value) or isinstance(value, type):
        raise RunSetupError(f"{key}: {type(value).__name__} has no members", key)
    head = members[0]
    if head not in {f.name for f in dataclasses.fields(value)}:
        names = ", ".join(f.name for f in dataclasses.fields(value))
        raise RunSetupError(f"{key}: {type(value).__name__} has no member {head!r} (members: {names})", key)
    return dataclasses.replace(value, **{head: _with_member(getattr(value, head), members[1:], new, key)})


def _member(value, members: list[str]):
    for m in members:
        value = getattr(value, m)
    return value


def _resolve(base_dir: pathlib.Path, value) -> pathlib.Path:
    p = pathlib.Path(str(value))
    return p if p.is_absolute() else base_dir / p


def _parameter_file(loaded, base_file, overrides: dict, declared: dict, out_dir: pathlib.Path):
    """Write the base file's records with ``overrides`` (name → checked value) replaced."""
    from fprime_lite.osal.atomic import atomic_write_bytes
    from fprime_lite.svc.prm_db import decode_param_file, encode_param_file

    records = {}
    if base_file is not None:
        records = dict(decode_param_file(pathlib.Path(base_file).read_bytes()).records)
    for name, value in overrides.items():
        _, pid, p = declared[name]
        records[pid] = p.type.serialize(value)
    path = out_dir / "campaign_params.dat"
    atomic_write_bytes(path, encode_param_file(sorted(records.items())))
    return path


def _base_value(p, pid: int, base_records: dict):
    data = base_records.get(pid)
    if data is not None:
        try:
            return p.type.deserialize(data)[0]
        except Exception:  # noqa: BLE001 - an unreadable record is loaded as the default by PrmDb too
            pass
    return p.default


def _stop_events(raw, topology) -> list[str]:
    """``stop_on_events``: full event names of the topology (a misspelt one would never stop the run)."""
    if raw is None:
        return []
    if not (isinstance(raw, list) and all(isinstance(n, str) for n in raw)):
        raise RunSetupError("stop_on_events is a list of full event names, e.g. "
                            "[ReferenceDeployment.detumbleManager.DetumbleCompleted]", "stop_on_events")
    declared = [f"{i.qualified_name}.{e.name}" for i in topology.instances.values() for e in i.component.spec.events]
    for name in raw:
        if name not in declared:
            hint = did_you_mean(name, declared, " (fprime-lite dict lists the events)", " — did you mean {}?")
            raise RunSetupError(f"stop_on_events: the topology has no event {name}{hint}", "stop_on_events")
    return list(raw)


def _check_progress_keys(conditions, loaded) -> None:
    """Each ``stop_when`` key must be one a report publishes (its ``progress_keys``); a key no report
    publishes would never hold, and the run would fly its whole duration. Reports that do not declare
    their keys leave the check out."""
    reports = [r for name, r in loaded.resources.items() if hasattr(r, "progress")]
    if not conditions or any(not hasattr(r, "progress_keys") for r in reports):
        return
    keys = sorted({k for r in reports for k in r.progress_keys})
    for c in conditions:
        if c.key not in keys:
            hint = did_you_mean(c.key, keys, f" (the reports publish: {', '.join(keys) or 'nothing'})",
                                " — did you mean '{}'?")
            raise RunSetupError(f"stop_when: no report of this topology publishes '{c.key}'{hint}", "stop_when")


def prepare(req: RunRequest) -> Prepared:
    from fprime_lite.deploy.topology import TopologyError
    from fprime_lite.deploy.topology_loader import load_topology
    from fprime_lite.model.errors import SerializationError
    from fprime_lite.svc.prm_db import decode_param_file
    from fprime_lite.tools.runner import run_deployment, run_duration
    from fprime_lite.tools.stop_condition import StopConditionError, parse_stop_condition

    cfg, values = req.config, req.values
    topology_path = _resolve(req.base_dir, cfg["topology"])
    if not topology_path.is_file():
        raise RunSetupError(f"topology {cfg['topology']} not found (looked for {topology_path})", "topology")
    scenario_keys = [k for k in values if k.startswith("scenario.")]
    settings = [f"{k[len('scenario.'):]}={yaml_text(values[k])}" for k in scenario_keys]
    simulation = {"simulation": {"settings": settings, "seed": req.seed}}
    try:
        try:
            loaded = load_topology(topology_path, role_overrides=simulation)
        except TopologyError as exc:
            if scenario_keys or not any("role 'simulation'" in p for p in exc.problems):
                raise
            loaded = load_topology(topology_path)  # nothing simulated to seed: a framework-only topology
    except TopologyError as exc:
        culprit = next((k for k in scenario_keys if f"'{k[len('scenario.'):]}=" in str(exc)), None)
        raise RunSetupError(" / ".join(exc.problems), culprit) from None
    readers = [r for r in loaded.resources.values() if hasattr(r, "read_setting")]
    scenario_back = {}
    for key in scenario_keys:
        if not readers:
            raise RunSetupError("no resource of the topology can report scenario values back (read_setting)", key)
        sim = readers[0]
        try:
            scenario_back[key] = plain(sim.read_setting(key[len("scenario."):]))
        except (KeyError, ValueError) as exc:
            raise RunSetupError(f"{key}: cannot be read back from the built simulation: {exc}", key) from None

    declared = _declared(loaded.topology)
    base_file = _resolve(req.base_dir, cfg["parameter_file"]) if cfg.get("parameter_file") else loaded.parameter_file
    base_records = dict(decode_param_file(pathlib.Path(base_file).read_bytes()).records) if base_file else {}
    param_values: dict[str, object] = {}
    param_keys = {}
    for key in (k for k in values if k.startswith("params.")):
        name, members = _split_param(key, declared)
        _, pid, p = declared[name]
        current = param_values.get(name, _base_value(p, pid, base_records))
        try:
            param_values[name] = p.type.check(_with_member(current, members, values[key], key))
        except (SerializationError, ValueError, TypeError) as exc:
            raise RunSetupError(f"{key}: not a valid {p.type.name}: {exc}", key) from None
        param_keys[key] = (name, members)
    req.out_dir.mkdir(parents=True, exist_ok=True)
    param_file = _parameter_file(loaded, base_file, param_values, declared, req.out_dir) if param_values \
        else base_file
    duration = run_duration(loaded, cfg.get("duration_s"))
    if not duration > 0:
        raise RunSetupError(f"duration_s must be positive, got {duration}", "duration_s")
    stop_events = _stop_events(cfg.get("stop_on_events"), loaded.topology)
    raw_conditions = cfg.get("stop_when") or []
    if not isinstance(raw_conditions, list):
        raise RunSetupError("stop_when is a list of conditions, e.g. ['mode == POINTING']", "stop_when")
    try:
        conditions = [parse_stop_condition(text) for text in raw_conditions]
    except StopConditionError as exc:
        raise RunSetupError(f"stop_when: {exc}", "stop_when") from None
    _check_progress_keys(conditions, loaded)

    def execute() -> RunOutput:
        scheduler = loaded.scheduler
        checks = [0]

        def watchdog(_time_us: int) -> None:
            checks[0] += 1
            if checks[0] % 256 == 0 and req.should_stop():
                scheduler.stop()
        scheduler.add_time_listener(watchdog)
        sequence = _resolve(req.base_dir, cfg["sequence"]) if cfg.get("sequence") else None
        summary = run_deployment(loaded, req.out_dir, duration_s=duration, parameter_file=param_file,
                                 sequence=sequence, plots=False, quiet=True, stop_on_events=stop_events,
                                 stop_when=conditions)
        return RunOutput(summary=summary, out_dir=req.out_dir,
                         stopped_early=summary["sim_seconds"] < duration - 1e-6)

    def readback(key: str):
        if key in scenario_back:
            return scenario_back[key]
        if key in param_keys:
            name, members = param_keys[key]
            qualified, _, p = declared[name]
            bound = loaded.topology.instance(qualified).component.params[p.name]
            return plain(_member(bound.get(), members))
        if key == "topology":
            return str(cfg["topology"])
        if key == "duration_s":
            return duration
        raise KeyError(key)

    return Prepared(simulation=loaded, readback=readback, execute=execute)


def fingerprint(config: dict, base_dir: pathlib.Path) -> dict:
    """What the topology's resources resolve from (each resource's ``fingerprint`` hook, e.g. the
    simulated spacecraft's default scenario), keyed ``topology:RESOURCE``; reads the topology
    (``extends`` merged) and imports the resource factories, builds nothing."""
    import importlib

    from fprime_lite.deploy.resources import resource_fingerprint
    from fprime_lite.deploy.topology_loader import read_topology

    out: dict = {}
    for resource in read_topology(_resolve(base_dir, config["topology"])).resources:
        module, _, attr = resource.type_path.rpartition(".")
        found = resource_fingerprint(getattr(importlib.import_module(module), attr), resource.args)
        if found:
            out[f"{config['topology']}:{resource.name}"] = found
    return out


DEPLOYMENT_RUN = RunKind(name="deployment", fields=FIELDS, required=REQUIRED, check_key=check_key,
                         prepare=prepare, description="a whole F´ deployment (topology) flown for duration_s",
                         fingerprint=fingerprint)
