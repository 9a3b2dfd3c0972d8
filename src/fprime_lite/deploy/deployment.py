"""Run a loaded topology: start-up in F´'s order, then the scheduler.

Start-up, as an F´ deployment's ``setupTopology`` does it:

1. queued and active components are drained by the scheduler after every event (deterministic);
2. every component registers its commands with the dispatcher;
3. PrmDb reads the parameter file (a bad file is reported by event and nothing is loaded from it);
4. every component loads its parameters (and runs its ``parameters_loaded`` hook);
5. the rate-group timer starts;
6. the start-up sequence, if any, is handed to the sequencer.

Software restart (a cold reset of the flight computer): :meth:`Deployment.restart_software`
re-initialises every component the topology file declared — each is constructed afresh in place
(same object, same arguments: state, queues, throttles and parameters back to their initial values)
and keeps its wiring — then runs the start-up above again: commands are registered, the parameter
file is read again and the parameters are reloaded, the rate groups restart, the start-up sequence
runs. Resources (the simulated hardware) keep running; one that holds the reset line (a
:class:`~fprime_lite.deploy.resources.ResetLine`) gets the deployment at its first start, so that
the line can call :meth:`request_reset`, and is told before each restart (what a reset does to its
hardware). Components added outside the file (the ground link) are not re-initialised: the
ground's connection survives.

What the deployment asks of its parts is declared, not probed: every component has the start-up
hooks ``clean_temporary_files()`` and ``use_command_lookup(lookup)`` (no-ops unless overridden),
PrmDb is the ``param`` service that reads the parameter file, and the start-up sequence goes into
the sequencer's one input port of type ``Svc.CmdSeqIn``.
"""

from __future__ import annotations

import os
from typing import Any, Callable

from fprime_lite.model.component import QueuedComponent
from fprime_lite.model.time import US_PER_S
from fprime_lite.deploy.resources import ResetLine
from fprime_lite.deploy.scheduler import ScheduledCall
from fprime_lite.deploy.topology import sequence_run_port
from fprime_lite.deploy.topology_loader import LoadedDeployment
from fprime_lite.model.types import FwType
from fprime_lite.svc.file_root import FileRoot
from fprime_lite.svc.prm_db import PrmDb

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
        #: completed software restarts
        self.restarts = 0
        #: ``fprime-lite run``'s writer process (:class:`fprime_lite.ground.writer_process.OutputWriter`),
        #: which a report's row streams use (``open_row_stream``); None: outputs are written in this process
        self.output_writer: Any = None
        self._start_args: dict = {}
        self._startup_call: ScheduledCall | None = None
        #: Calls that set up components after construction (the runner's file roots); a software restart
        #: re-initialises the components, then makes these calls again before starting up.
        self.component_setup: list = []

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
        self._start_args = {"parameter_file": parameter_file, "sequence": sequence}
        topo, scheduler = self.topology, self.scheduler
        prm_db = self.service("param")
        param_path = parameter_file or self.loaded.parameter_file
        reads_file = isinstance(prm_db, PrmDb)
        if reads_file and param_path is not None:
            prm_db.file_path = os.fspath(param_path)
        swept: set[str] = set()  # file services' roots swept already (they usually share one: sweep it once)
        for comp in topo.components():  # what a killed earlier run left half-written
            if isinstance(comp, FileRoot):
                if comp.root_path in swept:
                    continue
                swept.add(comp.root_path)
            comp.clean_temporary_files()
        lookup = command_lookup(topo)
        for comp in topo.components():
            if isinstance(comp, QueuedComponent):
                scheduler.drain_after_each_event(comp)
            comp.use_command_lookup(lookup)
        for comp in topo.components():
            comp.register_commands()
        scheduler.drain()
        if reads_file:
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
            component = topo.instance(sequencer).component
            port = sequence_run_port(component)
            if port is None:  # the loader refuses such a topology; a Topology built in Python may have one
                raise RuntimeError(f"the start-up sequencer {sequencer} needs exactly one input port of type "
                                   f"Svc.CmdSeqIn")
            run = component.input_port(port).entries[0]
            self._startup_call = scheduler.call_at(scheduler.now_us, lambda: run(os.fspath(sequence)))
        if self.restarts == 0:
            for resource in list(self.resources.values()):
                if isinstance(resource, ResetLine):
                    resource.attach_flight_software(self)

    def request_reset(self, kind: str = "cold") -> None:
        """Restart the software once the present event has finished (a reset line was pulled)."""
        self.scheduler.call_at(self.scheduler.now_us, self.restart_software)

    def restart_software(self) -> None:
        """Re-initialise the declared components in place and start up again (see the module doc)."""
        if not self.started:
            raise RuntimeError("the deployment has not started; there is nothing to restart")
        topo, scheduler = self.topology, self.scheduler
        for resource in list(self.resources.values()):
            if isinstance(resource, ResetLine):
                resource.flight_software_reset()
        if self.loaded.timer is not None:
            self.loaded.timer.stop()
        if self._startup_call is not None:
            self._startup_call.cancel()
            self._startup_call = None
        renewed = set()
        for instance in topo.instances.values():
            if instance.init_kwargs is None:
                continue
            comp = instance.component
            wiring = {name: (list(port.targets), list(port.calls)) for name, port in comp._outputs.items()}
            scheduler.stop_draining(comp)
            type(comp).__init__(comp, comp.name, **instance.init_kwargs)
            for name, (targets, calls) in wiring.items():
                port = comp._outputs[name]
                port.targets[:] = targets
                port.calls[:] = calls
                port.version += 1
            renewed.add(instance.qualified_name)
        for c in topo.connections:  # calls into a renewed component go to its new input entries
            if c.target not in renewed:
                continue
            src = topo.instance(c.source).component.output_port(c.source_port)
            if isinstance(src.targets[c.source_index], str):
                continue  # a tap (ground recorder) holds the call; entries of passive ports stay valid
            dst = topo.instance(c.target).component.input_port(c.target_port)
            src.calls[c.source_index] = dst.entries[c.target_index]
            src.targets[c.source_index] = (dst, c.target_index)
            src.version += 1
        for setup in self.component_setup:
            setup()
        self.restarts += 1
        self.started = False
        self.start(**self._start_args)

    def run_for(self, seconds: float) -> int:
        """Run ``seconds`` of simulated time; return the number of scheduler events."""
        return self.scheduler.run(until_us=self.scheduler.now_us + round(seconds * US_PER_S))
