"""Checks made before a deployment flies: the parameter file and the start-up sequence it will load.

PrmDb and CmdSequencer report a bad file with a WARNING_HI event once the deployment runs; a run
that was meant to use the file then flies without it. ``fprime-lite run`` calls these first so the
user hears about the mistake in one line, before anything flies.

- :func:`check_parameter_file`: the file decodes as F´'s PrmDb format (CRC included) and every
  record's id is a parameter of the topology whose value deserializes as that parameter's type.
- :func:`check_sequence`: the file decodes (text ``.seq`` compiled against the topology's commands,
  or binary as ``fprime-seqgen`` writes it), every record's opcode is a command of the topology and
  its arguments deserialize; the topology has the sequencer to run it.

Each raises :class:`PreflightError` (a one-line message naming the file and what to do).
:func:`topology_file_problems` (``fprime-lite check``) lists the problems of the files a topology
names, each placed at the topology line that names the file.
"""
from __future__ import annotations

import os
import pathlib

from fprime_lite.model.errors import FprimeLiteError, SerializationError
from fprime_lite.model.types import deserialize_values
from fprime_lite.deploy.deployment import command_lookup
from fprime_lite.deploy.topology import Topology
from fprime_lite.svc.prm_db import ParamFileError, decode_param_file
from fprime_lite.wire.seqfile import Descriptor, SequenceEmpty, SequenceFileError, SequenceTextError, read_sequence

__all__ = ["PreflightError", "check_parameter_file", "check_sequence", "check_run_files", "topology_file_problems",
           "topology_warnings"]


class PreflightError(FprimeLiteError):
    """A file the deployment would load is not usable."""


def _read(path, what: str) -> bytes:
    p = pathlib.Path(path)
    if p.is_dir():
        raise PreflightError(f"{what} {path}: is a folder — give the path of a file")
    try:
        return p.read_bytes()
    except FileNotFoundError:
        raise PreflightError(f"{what} {path}: no such file") from None
    except OSError as exc:
        raise PreflightError(f"{what} {path}: cannot read it ({exc.strerror})") from None


def check_parameter_file(topology: Topology, path) -> int:
    """Validate parameter file ``path`` against ``topology``; return the number of records."""
    data = _read(path, "parameter file")
    try:
        records = decode_param_file(data).records
    except ParamFileError as exc:
        raise PreflightError(f"parameter file {path}: not a valid PrmDb file: {exc} — write one with "
                             f"'fprime-lite params -o FILE' or fprime-prm-write") from None
    params = {}
    for instance in topology.instances.values():
        comp = instance.component
        for p in comp.spec.params:
            params[comp.base_id + p.local_id] = (f"{instance.qualified_name}.{p.name}", p)
    for index, (prm_id, value) in enumerate(records):
        known = params.get(prm_id)
        if known is None:
            raise PreflightError(f"parameter file {path}: record {index} has id 0x{prm_id:X}, which is no "
                                 f"parameter of deployment {topology.deployment} (fprime-lite dict lists them)")
        name, decl = known
        try:
            deserialize_values([decl.type], value)
        except (SerializationError, ValueError) as exc:
            raise PreflightError(f"parameter file {path}: record {index} ({name}): the value does not "
                                 f"deserialize as {decl.type.name}: {exc}") from None
    return len(records)


def check_sequence(topology: Topology, path, sequencer: str | None) -> int:
    """Validate sequence file ``path`` for ``topology`` run by instance ``sequencer``; return the
    number of commands."""
    if sequencer is None:
        raise PreflightError(f"sequence {path}: deployment {topology.deployment} has no start-up sequencer "
                             f"— add 'startup: {{sequencer: Module.cmdSeq}}' to the topology (docs/topology.md)")
    _read(path, "sequence")
    lookup = command_lookup(topology)
    try:
        sequence = read_sequence(os.fspath(path), lookup=lookup)
    except SequenceTextError as exc:  # already names path:line
        raise PreflightError(f"sequence {exc}") from None
    except SequenceEmpty:
        raise PreflightError(f"sequence {path}: it holds no command (CmdSequencer would ignore it with "
                             f"CS_NoRecords) — write one command a line, e.g. 'R00:00:05 "
                             f"CdhCore.cmdDisp.CMD_NO_OP' (docs/sequences.md), or leave the sequence out") from None
    except SequenceFileError as exc:
        raise PreflightError(f"sequence {path}: {exc}") from None
    except OSError as exc:
        raise PreflightError(f"sequence {path}: cannot read it ({exc.strerror})") from None
    commands = {}
    for instance in topology.instances.values():
        comp = instance.component
        for c in comp.spec.commands:
            commands[comp.base_id + c.opcode] = (f"{instance.qualified_name}.{c.name}", c.arg_types)
    count = 0
    for number, record in enumerate(sequence.records):
        if record.descriptor == Descriptor.END_OF_SEQUENCE:
            continue
        opcode = record.opcode
        known = commands.get(opcode) if opcode is not None else None
        if known is None:
            what = "no opcode" if opcode is None else f"opcode 0x{opcode:X}"
            raise PreflightError(f"sequence {path}: record {number} has {what}, which is no command of "
                                 f"deployment {topology.deployment} (fprime-lite dict lists them)")
        name, types = known
        try:
            deserialize_values(types, record.args)
        except (SerializationError, ValueError) as exc:
            raise PreflightError(f"sequence {path}: record {number} ({name}): its arguments do not "
                                 f"deserialize: {exc}") from None
        count += 1
    return count


def check_run_files(loaded, *, parameter_file=None, sequence=None) -> None:
    """Check the files a run of ``loaded`` (a LoadedDeployment) would load: ``parameter_file`` and
    ``sequence`` when given, else the topology's own.

    A topology's own parameter file may not exist yet (PrmDb then starts from the defaults, as F´
    does on a first boot); one given explicitly must.
    """
    params = parameter_file or loaded.parameter_file
    if params is not None and (parameter_file is not None or pathlib.Path(params).exists()):
        check_parameter_file(loaded.topology, params)
    seq = sequence or loaded.startup_sequence
    if seq is not None:
        check_sequence(loaded.topology, seq, loaded.startup_sequencer)


def topology_file_problems(loaded) -> list[str]:
    """Problems of the parameter file and start-up sequence a loaded topology names (empty: both
    good), each ``topology.yaml:LINE: 'key': what — what to do``. Unlike a run, which starts from
    the defaults when the topology's parameter file does not exist yet, this reports it missing:
    ``check`` validates the files a topology names."""
    config = loaded.config
    checks = []
    if loaded.parameter_file is not None:
        checks.append(("parameter_file", config.parameter_file_line if config else None,
                       lambda: check_parameter_file(loaded.topology, loaded.parameter_file)))
    if loaded.startup_sequence is not None:
        checks.append(("startup.sequence", config.startup.sequence_line if config and config.startup else None,
                       lambda: check_sequence(loaded.topology, loaded.startup_sequence, loaded.startup_sequencer)))
    problems = []
    for key, line, check in checks:
        try:
            check()
        except PreflightError as exc:
            message = str(exc)
            fix = "" if " — " in message else " — fix the file or the path"
            problems.append(f"{getattr(line, 'file', loaded.path)}:{line if line is not None else '?'}: '{key}': "
                            f"{message}{fix}")
    return problems


def topology_warnings(loaded) -> list[str]:
    """What ``fprime-lite check`` warns about in a topology that loads (it still flies): a topology with
    no ``patterns:``, whose components' commands, events, telemetry and time are then connected to no
    service unless ``connections`` wires each by hand — a run records nothing on the ground."""
    warnings = []
    if not loaded.topology.patterns:
        warnings.append(f"{loaded.path}: warning: no 'patterns:' — no component's commands, events, telemetry "
                        f"or time reach a service, so the ground receives nothing; add e.g. patterns: "
                        f"{{command: CdhCore.cmdDisp, event: CdhCore.events, telemetry: CdhCore.tlmSend, "
                        f"time: <Module>.<clock>}} (docs/topology.md, Patterns)")
    return warnings
