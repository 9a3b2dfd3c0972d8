"""Run a loaded topology: start-up in F´'s order, then the scheduler.

Start-up, as an F´ deployment's ``setupTopology`` does it:

1. queued and active components are drained by the scheduler after every event (deterministic);
2. every component registers its commands with the dispatcher;
3. PrmDb reads the parameter file (a bad file is reported by event and nothing is loaded from it);
4. every component loads its parameters (and runs its ``parameters_loaded`` hook);
5. the rate-group timer starts;
6. the start-up sequence, if any, is handed to the sequencer.
"""

from __future__ import annotations

import os
from typing import Callable

from fprime_lite.model.component import QueuedComponent
from fprime_lite.deploy.topology_loader import LoadedDeployment
from fprime_lite.model.types import FwType

__all__ = ["Deployment", "command_lookup"]


def command_lookup(topology) -> Callable[[str], tuple[int, list[FwType]]]:
    """``lookup(name) -> (opcode, argument types)`` for ``Module.inst.CMD`` or, if unique, ``inst.CMD``."""
    full: dict[str, tuple[int, list[FwType]]] = {}
    short: dict[str, list[tuple[int, list[FwType]]]] = {}
    for instance in topology.instances.values():
        comp = instance.component
        for c in comp.spec.commands:
            entry = (comp.base_id + c.opcode, c.arg_types)
            full[f"{instance.qualified_name}.{c.name}"] = entry
            short.setdefault(f"{instance.name}.{c.name}", []).append(entry)

    def lookup(name: str) -> tuple[int, list[FwType]]:
        if name in full:
            return full[name]
        matches = short.get(name, [])
        if len(matches) == 1:
            return matches[0]
        if len(matches) > 1:
            raise KeyError(f"command {name!r} is ambiguous; write it with its module (Module.{name})")
        raise KeyError(f"no command {name!r} in the dictionary")

    return lookup


class Deployment:
    """A started (or startable) deployment: the topology, its scheduler, clock and resources."""

    def __init__(self, loaded: LoadedDeployment):
        self.loaded = loaded
        self.topology = loaded.topology
        self.scheduler = loaded.scheduler
        self.clock = loaded.clock
        self.resources = loaded.resources
        self.started = False

    def service(self, pattern: str):
        """The component serving a pattern (``command``, ``param``, …), or None."""
        name = self.topology.patterns.get(pattern)
        return self.topology.instance(name).component if name else None

    def start(self, *, parameter_file: str | os.PathLike | None = None,
              sequence: str | os.PathLike | None = None) -> None:
        """Start up in F´'s order; ``parameter_file`` and ``sequence`` override the topology's."""
        if self.started:
            raise RuntimeError("the deployment is already started")
        self.started = True
        topo, scheduler = self.topology, self.scheduler
        lookup = command_lookup(topo)
        for comp in topo.components():
            if isinstance(comp, QueuedComponent):
                scheduler.drain_after_each_event(comp)
            if getattr(comp, "command_lookup", False) is None:
                setattr(comp, "command_lookup", lookup)  # the components that declare the attribute
        for comp in topo.components():
            comp.register_commands()
        scheduler.drain()
        prm_db = self.service("param")
        param_path = parameter_file or self.loaded.parameter_file
        if prm_db is not None and hasattr(prm_db, "read_param_file"):
            if param_path is not None:
                prm_db.file_path = os.fspath(param_path)
            prm_db.read_param_file()  # a missing or bad file is reported by PrmDb's own event
            scheduler.drain()
        for comp in topo.components():
            comp.load_parameters()
        scheduler.drain()
        if self.loaded.timer is not None:
            self.loaded.timer.start(scheduler.now_us)
        sequence = sequence or self.loaded.startup_sequence
        if sequence is not None:
            sequencer = self.loaded.startup_sequencer
            if sequencer is None:
                raise RuntimeError("a start-up sequence needs 'startup.sequencer' in the topology")
            run = topo.instance(sequencer).component.input_port("seqRunIn").entries[0]
            scheduler.call_at(scheduler.now_us, lambda: run(os.fspath(sequence)))

    def run_for(self, seconds: float) -> int:
        """Run ``seconds`` of simulated time; return the number of scheduler events."""
        return self.scheduler.run(until_us=self.scheduler.now_us + round(seconds * 1_000_000))
