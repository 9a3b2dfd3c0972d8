"""Load a deployment from a topology YAML file (schema: ``docs/topology.md``).

Loading runs four stages, one module each under :mod:`fprime_lite.deploy.topology_yaml`:

1. **parse** (``parse.py``, ``files.py``): YAML to values that know their file and line, bounded
   (size, nesting, alias expansion), with ``extends`` chains merged;
2. **schema** (``schema.py``): the document checked and turned into typed configuration
   (:class:`~fprime_lite.deploy.topology_yaml.schema.TopologyConfig`), include files read;
3. **build** (``build.py``): classes imported and checked (components; marked resources), resources
   and instances constructed;
4. **wire** (``wire.py``): connection groups, rate groups and patterns connected.

Every problem found is reported as ``file:line: what is wrong — what to do``, all of them at once,
in a :class:`TopologyError`; no malformed file makes the loader raise anything else.
"""

from __future__ import annotations

import pathlib
from dataclasses import dataclass, field
from typing import Any, Callable

from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.deploy.topology import Topology, TopologyError
from fprime_lite.deploy.topology_yaml.build import build_instances, build_resources, make_scheduler
from fprime_lite.deploy.topology_yaml.packets import configure_packets
from fprime_lite.deploy.topology_yaml.files import is_file, path_problem, read_document, resolve_path
from fprime_lite.deploy.topology_yaml.problems import Problems
from fprime_lite.deploy.topology_yaml.schema import TopologyConfig, read_config
from fprime_lite.deploy.topology_yaml.wire import check_startup, wire_connections, wire_patterns, wire_rate_groups
from fprime_lite.model.time import SimulatedClock
from fprime_lite.svc.rate_group_driver import RateGroupTimer

__all__ = ["load_topology", "read_topology", "LoadedDeployment", "TopologyError", "resolve_path"]


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
    #: The checked configuration it was built from (lines of ``parameter_file``, ``startup`` …).
    config: TopologyConfig | None = None


def read_topology(path) -> TopologyConfig:
    """Stages 1 and 2 only: parse ``path`` (with what it extends and includes) and check it into a
    :class:`TopologyConfig`, importing and constructing nothing; raise :class:`TopologyError`
    listing every problem found so far. What needs the classes (ports, constructor arguments,
    connections) is checked only by :func:`load_topology`."""
    _, config, problems, _ = _read(path)
    problems.raise_if_any()
    return config


def _read(path) -> tuple[pathlib.Path, TopologyConfig, Problems, bool]:
    """(path, config, problems, whether building may go on to report more): stages 1 and 2."""
    why = path_problem(str(path))
    if why is not None:
        raise TopologyError([f"{str(path)[:200]!r}: the topology path {why}"])
    path = pathlib.Path(path)
    if not is_file(path):
        raise TopologyError([f"{path}: no such topology file — give the path of a topology YAML file"])
    if path.is_symlink():
        path = path.resolve()
    problems = Problems()
    doc = read_document(path, problems)
    if doc is None:  # the reason is among the problems
        raise problems.error()
    config = read_config(doc, path, problems)
    # with modules, building goes on despite problems so that those of the build are reported too
    return path, config, problems, "modules" in doc


def load_topology(path, overrides: dict | None = None, *, scheduler_factory: Callable | None = None,
                  role_overrides: dict | None = None) -> LoadedDeployment:
    """Load and validate a topology YAML file; raise :class:`TopologyError` listing every problem.

    ``overrides`` maps a resource name to keyword arguments that replace those in the file;
    ``role_overrides`` maps a resource role (:mod:`fprime_lite.deploy.resources`) to keyword
    arguments for the resource holding it (the command line's ``--scenario``, ``--seed``, ``--set``
    and ``--truth-interval`` use it). ``scheduler_factory(clock)`` makes
    the scheduler (default :class:`~fprime_lite.deploy.scheduler.Scheduler`; ``run --realtime`` passes a
    :class:`~fprime_lite.deploy.scheduler.PacedScheduler`).
    """
    path, config, problems, complete = _read(path)
    if not complete:
        problems.raise_if_any()

    clock, scheduler = make_scheduler(config, scheduler_factory)
    topology = Topology(config.deployment)
    resources: dict[str, Any] = {"clock": clock, "scheduler": scheduler, "topology_dir": path.parent}
    build_resources(config, resources, problems, overrides=overrides, role_overrides=role_overrides)
    build_instances(config, topology, resources, problems)

    wire_connections(config, topology, problems)
    timer = wire_rate_groups(config, topology, scheduler, problems)
    wire_patterns(config, topology, problems)
    if not len(problems):  # the channels are known only once every instance is built
        configure_packets(config, topology, problems)
    if not len(problems):  # collisions and unconnected ports only mean something in a complete build
        problems.extend(topology.problems())
    check_startup(config, topology, problems)
    problems.raise_if_any()
    startup = config.startup
    return LoadedDeployment(path, topology, scheduler, clock, resources, timer, config.parameter_file,
                            startup.sequencer if startup else None, startup.sequence if startup else None, config)
