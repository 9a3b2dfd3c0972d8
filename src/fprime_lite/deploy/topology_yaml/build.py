"""Stage 3 of loading a topology: import the classes it names and build resources and instances.

What a topology may name as a ``type`` is deliberately narrow, because loading (and so
``fprime-lite check``) constructs what it names:

- an instance's type must be a component class (a subclass of
  :class:`~fprime_lite.model.component.Component`);
- a resource's type must have declared itself a topology resource with
  :func:`~fprime_lite.deploy.resources.topology_resource` — a class or factory whose construction
  has no effect outside the process. Any other callable (``os.system``, ``subprocess.run``,
  ``shutil.rmtree``…) is refused before it is called;
- nothing is imported from the Python standard library (it holds no components or resources, and
  some of its modules act when imported, e.g. ``antigravity`` opens a web browser).

Importing the module that holds a named class runs that module's top level, as any Python
import does; the topology cannot name a module without naming a class in it.
"""

from __future__ import annotations

import importlib
import inspect
import pathlib
import sys
from typing import Any, Callable

from fprime_lite.deploy.resources import ROLES, RoleOptionError, resource_role
from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.deploy.topology import Topology
from fprime_lite.deploy.topology_yaml.problems import Problems
from fprime_lite.deploy.topology_yaml.schema import InstanceConfig, ResourceConfig, TopologyConfig
from fprime_lite.model.component import Component
from fprime_lite.model.errors import DeclarationError, PortConnectionError, did_you_mean
from fprime_lite.model.time import SimulatedClock

__all__ = ["import_type", "build_resources", "build_instances", "make_scheduler", "BUILTIN_RESOURCES"]

#: Resources every topology has (``$clock``, ``$scheduler``, ``$topology_dir``).
BUILTIN_RESOURCES = ("clock", "scheduler", "topology_dir")

_RESOURCE_FIX = ("a resource is a class or factory marked with @topology_resource "
                 "(fprime_lite.deploy.resources); name one, or mark yours")


def import_type(file: pathlib.Path, type_path: str, line: int | None, what: str, problems: Problems) -> Any:
    """The object at ``type_path`` (``package.module.Name``), or None with the problem reported."""
    parts = type_path.split(".")
    if parts[0] in sys.stdlib_module_names:
        problems.add(file, line, f"{what}: type '{type_path}' is in the Python standard library, which holds no "
                                 f"components or resources — give the import path of a component class or "
                                 f"topology resource")
        return None
    module = None
    first_error: Exception | None = None
    split = len(parts) - 1
    for split in range(len(parts) - 1, 0, -1):  # the longest importable module prefix
        module_name = ".".join(parts[:split])
        try:
            module = importlib.import_module(module_name)
            break
        except ModuleNotFoundError as exc:
            if exc.name is None or not module_name.startswith(exc.name):
                problems.add(file, line, f"{what}: importing '{module_name}' failed: {exc} — install what it needs")
                return None
            first_error = first_error or exc
        except DeclarationError as exc:
            problems.add(file, line, f"{what}: {exc} — fix the declaration")
            return None
        except (Exception, SystemExit) as exc:  # noqa: BLE001 - a broken module is reported, not raised
            problems.add(file, line, f"{what}: importing '{module_name}' failed: {type(exc).__name__}: {exc} — fix "
                                     f"that module")
            return None
    if module is None:
        problems.add(file, line, f"{what}: cannot import module '{'.'.join(parts[:-1])}' ({first_error}) — check "
                                 f"the type path")
        return None
    obj: Any = module
    for depth, attr in enumerate(parts[split:]):
        owner = obj
        try:
            obj = getattr(owner, attr, None)
        except Exception:  # noqa: BLE001 - a property or module __getattr__ that raises: "has no"
            obj = None
        if obj is None:
            names = [n for n in dir(owner) if not n.startswith("_")]
            prefix = ".".join(parts[:split + depth])
            hint = " — " + did_you_mean(attr, names, "check the type path", f"did you mean '{prefix}.{{}}'?")
            problems.add(file, line, f"{what}: module '{prefix}' has no '{attr}'{hint}")
            return None
    return obj


def _fpp_component(spec: InstanceConfig, what: str, problems: Problems) -> Any:
    """The component class of ``type: fpp:FILE.fpp[:Module.Component]`` (FILE relative to the
    topology file), bound to its implementation; None with the problems reported."""
    from fprime_lite.deploy.fpp.loader import FppError, component_class

    file_part, _, name = spec.type_path[4:].partition(":")
    path = (spec.file.parent / file_part).resolve()
    try:
        return component_class(path, name or None)
    except FppError as exc:
        for problem in exc.problems:
            problems.add(spec.file, spec.type_line, f"{what}: {problem}")
        return None


class _Args:
    """Resolves ``$name`` references in constructor arguments."""

    def __init__(self, resources: dict[str, Any], problems: Problems):
        self.resources = resources
        self.problems = problems
        self.ok = True  # the last resolve() found every reference

    def resolve(self, file: pathlib.Path, args: dict[str, Any], line_of: Callable[[str], int | None],
                what: str) -> dict[str, Any] | None:
        """Arguments with references replaced; None when one names a resource that failed or is unknown."""
        self.ok = True
        out = {key: self.value(file, value, line_of(key), what) for key, value in args.items()}
        return out if self.ok else None

    def value(self, file: pathlib.Path, value: Any, line: int | None, what: str) -> Any:
        if isinstance(value, str) and value.startswith("$"):
            name = value[1:]
            if name in self.problems.failed_resources:
                self.ok = False  # its own failure has been reported
                return None
            if name not in self.resources:
                self.problems.add(file, line, f"{what}: unknown resource '{value[:80]}' — resources: "
                                              f"{', '.join('$' + r for r in self.resources)}")
                self.ok = False
                return None
            return self.resources[name]
        if isinstance(value, dict):
            return {k: self.value(file, v, line, what) for k, v in value.items()}
        if isinstance(value, list):
            return [self.value(file, v, line, what) for v in value]
        return value


def build_resources(config: TopologyConfig, resources: dict[str, Any], problems: Problems, *,
                    overrides: dict | None = None, role_overrides: dict | None = None) -> None:
    """Build ``config``'s resources into ``resources`` (which holds the built-in ones)."""
    overrides, role_overrides = overrides or {}, role_overrides or {}
    roles_built: set[str] = set()
    args = _Args(resources, problems)
    for spec in config.resources:
        if not _build_resource(spec, config.path, resources, args, problems, overrides, role_overrides,
                               roles_built):
            problems.failed_resources.add(spec.name)
    for role in role_overrides:  # options meant for a resource role that no resource holds
        if role not in roles_built and not problems.failed_resources:
            problems.add(config.path, config.resources_line,
                         f"no resource holds the role '{role}', so {ROLES.get(role, role)} cannot apply "
                         f"— leave those options out for this topology")


def _build_resource(spec: ResourceConfig, file: pathlib.Path, resources: dict[str, Any], args: _Args,
                    problems: Problems, overrides: dict, role_overrides: dict, roles_built: set[str]) -> bool:
    what = f"resource '{spec.name}'"
    factory = import_type(file, spec.type_path, spec.type_line, what, problems)
    if factory is None:
        return False
    role = resource_role(factory)
    if role is None or not (inspect.isclass(factory) or inspect.isfunction(factory)):
        problems.add(file, spec.type_line, f"{what}: type '{spec.type_path}' is not a topology resource — "
                                           f"{_RESOURCE_FIX}")
        return False
    kwargs = args.resolve(file, spec.args, lambda key: spec.arg_lines.get(key, spec.args_line), what)
    if kwargs is None:
        return False
    kwargs.update(overrides.get(spec.name, {}))
    if role:
        roles_built.add(role)
        kwargs.update(role_overrides.get(role, {}))
    try:
        resources[spec.name] = factory(**kwargs)
    except RoleOptionError:
        raise  # the command line's option is wrong, not the topology: its message says which
    except Exception as exc:  # noqa: BLE001 - any construction failure is a user-facing problem
        given = role_overrides.get(role, {}) if role else {}
        options = f" with the {role} options {given}" if given else ""
        problems.add(file, spec.line, f"{what} could not be created{options}: {exc} — check its args")
        return False
    return True


def build_instances(config: TopologyConfig, topology: Topology, resources: dict[str, Any],
                    problems: Problems) -> None:
    """Construct every instance of ``config`` and add it to ``topology``."""
    args = _Args(resources, problems)
    for spec in config.instances:
        if not _build_instance(spec, config, topology, args, problems):  # reported, or quietly skipped
            problems.failed_instances.add(spec.qualified)


def _build_instance(spec: InstanceConfig, config: TopologyConfig, topology: Topology, args: _Args,
                    problems: Problems) -> bool:
    what = f"instance {spec.qualified}"
    if spec.type_path.startswith("fpp:"):
        cls = _fpp_component(spec, what, problems)
    else:
        cls = import_type(spec.file, spec.type_path, spec.type_line, what, problems)
    if cls is None:
        return False
    if not (inspect.isclass(cls) and issubclass(cls, Component)):
        problems.add(spec.file, spec.type_line, f"{what}: type '{spec.type_path}' is not a component class — derive "
                                                f"it from PassiveComponent, QueuedComponent or ActiveComponent")
        return False
    kwargs = args.resolve(spec.file, spec.args, lambda key: spec.arg_lines.get(key, spec.args_line), what)
    if kwargs is None:
        return False
    kwargs["base_id"] = spec.base_id
    if spec.queue_size is not None:
        if getattr(cls, "__fprime_kind__", None) == "passive":
            problems.add(spec.file, spec.queue_line, f"{what}: {cls.__name__} is passive and has no queue — remove "
                                                     f"queue_size")
            return False
        kwargs["queue_size"] = spec.queue_size
    if config.rate_groups is not None:
        kwargs.update(config.rate_groups.init_args(spec.qualified))
    try:
        component = cls(spec.name, **kwargs)
    except TypeError as exc:
        problems.add(spec.file, spec.line, f"{what}: cannot create {cls.__name__} with args "
                                           f"{sorted(k for k in kwargs if k != 'base_id')}: {exc} — give the "
                                           f"arguments its constructor takes")
        return False
    except Exception as exc:  # noqa: BLE001 - reported with its location
        problems.add(spec.file, spec.line, f"{what}: {cls.__name__} raised while being created: {exc} — check its args")
        return False
    try:
        instance = topology.add(spec.module, component, where=spec.where)
    except PortConnectionError as exc:
        problems.add(spec.file, spec.line, str(exc))
        return False
    instance.init_kwargs = dict(kwargs)  # for Deployment.restart_software
    return True


def make_scheduler(config: TopologyConfig, factory: Callable | None) -> tuple[SimulatedClock, Scheduler]:
    """The deployment's clock (``time:``) and the scheduler ``factory(clock)`` makes."""
    clock = SimulatedClock(time_base=config.time.time_base, epoch_us=config.time.epoch_us)
    return clock, (factory or Scheduler)(clock)
