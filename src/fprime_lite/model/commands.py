"""Commands: declaration decorators, the F´ command response codes, deferred responses.

A command is a method decorated with :func:`sync_command`, :func:`guarded_command` or
:func:`async_command`. Its arguments are annotated with F´ types and its name is the command's
mnemonic (F´ spelling)::

    @sync_command()
    def SET_MODE(self, mode: DetumbleMode):
        ...
        return CmdResponse.OK          # or None, which also means OK

The framework deserializes the arguments (undeserializable or leftover bytes answer FORMAT_ERROR
before the handler runs), calls the handler and sends its response. A handler that finishes later
calls ``self.defer_command_response()`` and answers with ``self.command_response(token, response)``.
An exception escaping a handler answers EXECUTION_ERROR.
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass, field
from typing import Any, Callable, TypeVar

from fprime_lite.model.errors import DeclarationError
from fprime_lite.model.ports import QUEUE_FULL_BEHAVIOURS
from fprime_lite.model.types import FwEnum, FwType, U8, fw_type

__all__ = ["CmdResponse", "CommandDecl", "CommandToken", "sync_command", "guarded_command",
           "async_command"]


class CmdResponse(FwEnum, namespace="Fw", rep=U8):
    """F´ command response codes (``Fw.CmdResponse``)."""

    OK = 0
    INVALID_OPCODE = 1
    VALIDATION_ERROR = 2
    FORMAT_ERROR = 3
    EXECUTION_ERROR = 4
    BUSY = 5
    CLEARED = 6


@dataclass(frozen=True)
class CommandToken:
    """Identifies one command execution, for answering it later."""

    opcode: int
    cmd_seq: int


@dataclass
class CommandDecl:
    """A declared command (user-written, or generated for a parameter)."""

    name: str
    kind: str  # "sync" | "guarded" | "async" | "set" | "save"
    args: list[tuple[str, FwType[Any]]] = field(default_factory=list)
    requested_opcode: int | None = None  # the local opcode the declaration gives, if any
    opcode: int = -1  # the local opcode, assigned when the component class is built
    priority: int = 0
    queue_full: str = "assert"
    handler: Callable[..., Any] | None = None
    param: Any = None  # the Param a set/save command belongs to

    @property
    def arg_types(self) -> list[FwType[Any]]:
        return [t for _, t in self.args]


F = TypeVar("F", bound=Callable[..., Any])


def _command_decorator(kind: str, opcode: int | None, priority: int = 0,
                       queue_full: str = "assert") -> Callable[[F], F]:
    if opcode is not None and (not isinstance(opcode, int) or opcode < 0):
        raise DeclarationError(f"command opcode must be a non-negative integer, got {opcode!r}")
    if queue_full not in QUEUE_FULL_BEHAVIOURS:
        raise DeclarationError(
            f"queue_full must be one of {', '.join(QUEUE_FULL_BEHAVIOURS)}, got {queue_full!r}")

    def decorate(fn: F) -> F:
        setattr(fn, "__fprime_command__", CommandDecl(fn.__name__, kind, requested_opcode=opcode, priority=priority,
                                                      queue_full=queue_full, handler=fn))
        return fn

    return decorate


def resolve_command_args(owner: str, decl: CommandDecl) -> None:
    """Read the argument types from the handler's annotations (called when the class is built)."""
    if decl.handler is None:
        raise DeclarationError(f"{owner}.{decl.name}: a declared command needs its handler method")
    try:
        sig = inspect.signature(decl.handler, eval_str=True)
    except Exception as exc:  # noqa: BLE001 - unresolvable annotation, reported as a declaration error
        raise DeclarationError(f"{owner}.{decl.name}: cannot resolve argument types: {exc}") from None
    args = []
    for p in list(sig.parameters.values())[1:]:
        if p.kind not in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD):
            raise DeclarationError(f"{owner}.{decl.name}: command arguments must be plain positional "
                                   f"parameters; {p.name!r} is not")
        if p.annotation is p.empty:
            raise DeclarationError(f"{owner}.{decl.name}: argument {p.name!r} needs an F´ type "
                                   f"annotation, e.g. '{p.name}: U32'")
        try:
            args.append((p.name, fw_type(p.annotation)))
        except DeclarationError as exc:
            raise DeclarationError(f"{owner}.{decl.name}: argument {p.name!r}: {exc}") from None
    decl.args = args


def sync_command(*, opcode: int | None = None) -> Callable[[F], F]:
    """Declare a sync command: it runs on the dispatcher's thread."""
    return _command_decorator("sync", opcode)


def guarded_command(*, opcode: int | None = None) -> Callable[[F], F]:
    """Declare a guarded command: it runs on the dispatcher's thread under the component lock."""
    return _command_decorator("guarded", opcode)


def async_command(*, opcode: int | None = None, priority: int = 0,
                  queue_full: str = "assert") -> Callable[[F], F]:
    """Declare an async command: queued, run by ``dispatch()`` (queued and active components)."""
    return _command_decorator("async", opcode, priority, queue_full)
