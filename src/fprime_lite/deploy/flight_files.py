"""Checks of the flight files a deployment starts with: the parameter file and a command sequence.

``fprime-lite check`` runs them on the files a topology names (:func:`deployment_file_problems`);
``fprime-lite run`` can run them on ``--params`` / ``--seq`` before anything flies
(:func:`parameter_file_problems`, :func:`sequence_file_problems`). Each returns a list of
problems, ``file: what is wrong — what to do`` (empty when the file is good), and never raises for
a bad file.

What is checked:

- a parameter file: it exists and is readable, decodes as an F´ PrmDb file (CRC and records), every
  record's id is a parameter of an instance of the topology, and every value deserializes as that
  parameter's type with no byte left over (PrmDb would load the default instead, silently);
- a sequence: it exists and is readable, and decodes (text ``.seq`` compiled against the
  topology's commands; binary as ``fprime-seqgen`` writes it), and every record's command is in
  the dictionary with arguments that deserialize as that command's argument types.
"""

from __future__ import annotations

import os
import pathlib
from typing import Any, Callable, Iterable

from fprime_lite.deploy.deployment import command_lookup
from fprime_lite.deploy.topology import Topology
from fprime_lite.model.errors import SerializationError
from fprime_lite.model.types import deserialize_values
from fprime_lite.svc.prm_db import ParamFileError, decode_param_file
from fprime_lite.wire.seqfile import Descriptor, SequenceFileError, SequenceTextError, read_sequence

__all__ = ["parameter_file_problems", "sequence_file_problems", "deployment_file_problems"]

#: Largest flight file read for checking (a PrmDb or sequence file is kilobytes).
MAX_FILE_BYTES = 16 << 20


def _unreadable(path: pathlib.Path, what: str) -> str | None:
    try:
        if not path.exists():
            return f"{path}: {what} not found — give the path of an existing file"
        if not path.is_file():
            return f"{path}: {what} is not a regular file — give the path of a file"
        if path.stat().st_size > MAX_FILE_BYTES:
            return f"{path}: {what} is larger than {MAX_FILE_BYTES} bytes — is this the right file?"
        with open(path, "rb"):
            pass
    except (OSError, ValueError) as exc:
        return f"{path}: {what} cannot be read ({getattr(exc, 'strerror', None) or exc}) — check the path " \
               f"and its permissions"
    return None


def _by_id(topology: Topology, members: Callable[[Any], Iterable[tuple[int, str, Any]]]) -> dict[int, tuple]:
    """Global id → (qualified member name, type) for ``members(spec)`` = (local id, name, type)."""
    table = {}
    for instance in topology.instances.values():
        comp = instance.component
        for local_id, name, what in members(comp.spec):
            table[comp.base_id + local_id] = (f"{instance.qualified_name}.{name}", what)
    return table


def parameter_file_problems(path: str | os.PathLike, topology: Topology) -> list[str]:
    """Problems of the PrmDb file at ``path`` for ``topology`` (empty: it loads as written)."""
    path = pathlib.Path(path)
    unreadable = _unreadable(path, "parameter file")
    if unreadable:
        return [unreadable]
    try:
        records = decode_param_file(path.read_bytes()).records
    except (ParamFileError, OSError) as exc:
        return [f"{path}: not a valid parameter file: {exc} — write it with 'fprime-lite params' or PRM_SAVE_FILE"]
    params = _by_id(topology, lambda spec: ((p.local_id, p.name, p.type) for p in spec.params))
    problems = []
    for index, (prm_id, value) in enumerate(records):
        if prm_id not in params:
            problems.append(f"{path}: record {index}: parameter id 0x{prm_id:X} is not a parameter of this "
                            f"deployment — regenerate the file for this topology ('fprime-lite params')")
            continue
        name, ptype = params[prm_id]
        try:
            deserialize_values([ptype], value)
        except (SerializationError, ValueError) as exc:
            problems.append(f"{path}: record {index}: the value of {name} (0x{prm_id:X}) is not a "
                            f"{getattr(ptype, 'name', ptype)}: {exc} — PrmDb would load its default instead; "
                            f"write the file again")
    return problems


def sequence_file_problems(path: str | os.PathLike, topology: Topology) -> list[str]:
    """Problems of the sequence at ``path`` for ``topology`` (empty: every command would be sent)."""
    path = pathlib.Path(path)
    unreadable = _unreadable(path, "sequence")
    if unreadable:
        return [unreadable]
    lookup = command_lookup(topology)
    try:
        sequence = read_sequence(path, lookup=lookup)
    except SequenceTextError as exc:  # already names the file and line
        text = str(exc)
        return [text if " — " in text else f"{text} — fix that line of the sequence"]
    except (SequenceFileError, OSError) as exc:
        return [f"{path}: not a valid sequence: {exc} — fix the file (text .seq, or binary from fprime-seqgen)"]
    commands = _by_id(topology, lambda spec: ((c.opcode, c.name, c.arg_types) for c in spec.commands))
    problems = []
    for index, record in enumerate(sequence.records):
        if record.descriptor == Descriptor.END_OF_SEQUENCE:
            continue
        opcode = record.opcode
        if opcode is None or opcode not in commands:
            shown = "no opcode" if opcode is None else f"opcode 0x{opcode:X}"
            problems.append(f"{path}: record {index}: {shown} is not a command of this deployment — the "
                            f"sequence was built for another dictionary; rebuild it")
            continue
        name, arg_types = commands[opcode]
        try:
            deserialize_values(list(arg_types), record.args)
        except (SerializationError, ValueError) as exc:
            problems.append(f"{path}: record {index}: the arguments of {name} do not decode: {exc} — rebuild "
                            f"the sequence with this deployment's dictionary")
    return problems


def deployment_file_problems(loaded) -> list[str]:
    """Problems of the parameter file and start-up sequence a loaded topology names, each prefixed
    with the topology line that names it. ``loaded`` is a
    :class:`~fprime_lite.deploy.topology_loader.LoadedDeployment`."""
    config = loaded.config
    problems = []
    checks = []
    if loaded.parameter_file is not None:
        line = config.parameter_file_line if config is not None else None
        checks.append(("parameter_file", line, parameter_file_problems(loaded.parameter_file, loaded.topology)))
    if loaded.startup_sequence is not None:
        line = config.startup.sequence_line if config is not None and config.startup else None
        checks.append(("startup.sequence", line, sequence_file_problems(loaded.startup_sequence, loaded.topology)))
    for key, line, found in checks:
        where = f"{getattr(line, 'file', loaded.path)}:{line if line is not None else '?'}"
        problems.extend(f"{where}: '{key}': {p}" for p in found)
    return problems
