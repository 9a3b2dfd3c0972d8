"""F´ command sequence files: the binary form ``fprime-seqgen`` writes, and its text source.

Binary form (big-endian), as ``fprime-seqgen`` 4.4.1 writes it and F´'s ``CmdSequencer`` reads it::

    header   U32 size          bytes after the header: all records + the 4-byte CRC
             U32 records       number of records
             U16 time base     TimeBase; 0xFFFF (TB_DONT_CARE) unless ``fprime-seqgen -t``
             U8  time context  0xFF (don't care)
    record   U8  descriptor    0 absolute, 1 relative, 2 end of sequence (nothing follows a 2)
             U32 seconds       absolute: seconds since 1970-01-01 UTC; relative: after the
             U32 useconds      previous command completed
             U32 cmd size      bytes of the command packet that follows
             U16 0             FW_PACKET_COMMAND   } the command packet, sent as is out of
             U32 opcode                            } the sequencer's comCmdOut port
             args                                  }
    trailer  U32 CRC           zlib.crc32 (plain CRC-32) of the header and the records

Text form (the input of ``fprime-seqgen``), one command per line::

    ; comment to the end of the line
    R00:00:01.5 MiniDep.demo.CONFIGURE 7, 2.5, "hello", NOMINAL   ; commas optional
    A2025-001T00:00:10 CdhCore.cmdDisp.CMD_NO_OP_STRING "abs"     ; UTC day-of-year
    R00:00:00 MiniDep.demo.GAINS_PRM_SET {kp: 1.5, ki: 0.25, mode: SCIENCE, label: "g"}

``R`` times (``HH:MM:SS[.ffffff]``) wait after the previous command completes; ``A`` times
(``YYYY-DDDTHH:MM:SS[.ffffff]``) are UTC. Arguments: integers (``-3``, ``0x2A``, ``1_000``),
floats (``2.5``, ``1e-3``, ``.5``), quoted strings (``"..."`` or ``'...'``, no escapes),
``true``/``false``, bare enum constant names, ``[a, b]`` arrays and ``{member: value}`` structs.
A ``\\`` at the end of a line continues it.

Compiling text needs a *command lookup*: ``lookup(name) -> (opcode, [FwType, ...])`` for the
command's full dictionary name (``CdhCore.cmdDisp.CMD_NO_OP``); :class:`CommandDictionary` builds
one from an F´ JSON dictionary. For the same text and dictionary :func:`compile_text` followed by
:func:`encode_binary` gives the same bytes as ``fprime-seqgen``.

Errors: binary problems raise the :class:`SequenceFileError` subclass matching the event F´'s
CmdSequencer would log; text problems raise :class:`SequenceTextError` naming ``file:line``.
"""

from __future__ import annotations

import enum
import json
import re
import struct
import types as _pytypes
import zlib
from dataclasses import dataclass, field
from datetime import datetime, timedelta
from pathlib import Path
from typing import Any, Callable

from fprime_lite.model.errors import DeclarationError, FprimeLiteError, SerializationError
from fprime_lite.wire.packets import Apid
from fprime_lite.model.types import (PRIMITIVE_TYPES, AliasType, Array, ArrayType, BoolType, EnumType, FloatType,
                                     FwEnum, FwType, IntType, String, StringType, Struct, StructType, fw_type)

__all__ = [
    "Descriptor", "FileReadStage", "SerializeStatus", "Record", "Sequence", "TextCommand",
    "HEADER_SIZE", "CRC_SIZE", "TB_DONT_CARE", "CONTEXT_DONT_CARE", "COM_BUFFER_MAX_SIZE",
    "encode_binary", "decode_binary", "check_time", "parse_text", "compile_text", "read_sequence",
    "CommandLookup", "CommandDictionary",
    "SequenceFileError", "SequenceFormatError", "SequenceSizeError", "SequenceCrcError",
    "SequenceRecordError", "SequenceRecordMismatch", "SequenceEmpty", "SequenceTimeBaseMismatch",
    "SequenceTimeContextMismatch", "SequenceTextError",
]

#: Bytes of the header: U32 size, U32 records, U16 time base, U8 context.
HEADER_SIZE = 11
#: Bytes of the CRC trailer.
CRC_SIZE = 4
TB_DONT_CARE = 0xFFFF
CONTEXT_DONT_CARE = 0xFF
#: F´'s FW_COM_BUFFER_MAX_SIZE (default config): a record's command packet must fit in it.
COM_BUFFER_MAX_SIZE = 512

_HEADER = struct.Struct(">IIHB")
_RECORD_HEAD = struct.Struct(">BIII")
_U32 = struct.Struct(">I")
_CMD_HEADER = struct.Struct(">HI")

#: ``lookup(full command name) -> (opcode, [argument FwTypes])``; raises KeyError (or returns
#: None) for an unknown command.
CommandLookup = Callable[[str], "tuple[int, list[FwType]] | None"]


class Descriptor(enum.IntEnum):
    """A record's U8 descriptor."""

    ABSOLUTE = 0
    RELATIVE = 1
    END_OF_SEQUENCE = 2


class FileReadStage(FwEnum, namespace="Svc.CmdSequencer"):
    """Where reading a binary file failed (F´'s ``Svc.CmdSequencer.FileReadStage``)."""

    READ_HEADER = 0
    READ_HEADER_SIZE = 1
    DESER_SIZE = 2
    DESER_NUM_RECORDS = 3
    DESER_TIME_BASE = 4
    DESER_TIME_CONTEXT = 5
    READ_SEQ_CRC = 6
    READ_SEQ_DATA = 7
    READ_SEQ_DATA_SIZE = 8


class SerializeStatus(enum.IntEnum):
    """F´'s ``Fw::SerializeStatus``: the error code of CS_RecordInvalid."""

    FW_SERIALIZE_OK = 0
    FW_SERIALIZE_FORMAT_ERROR = 1
    FW_SERIALIZE_NO_ROOM_LEFT = 2
    FW_DESERIALIZE_BUFFER_EMPTY = 3
    FW_DESERIALIZE_FORMAT_ERROR = 4
    FW_DESERIALIZE_SIZE_MISMATCH = 5
    FW_DESERIALIZE_TYPE_MISMATCH = 6


# --- errors ---------------------------------------------------------------------------------------

class SequenceFileError(FprimeLiteError):
    """A sequence file cannot be run. Subclasses match CmdSequencer's events."""


class SequenceFormatError(SequenceFileError):
    """The file's structure is wrong at ``stage`` (CS_FileInvalid); ``error`` is F´'s error code
    (for the ``*_SIZE`` stages, the number of bytes actually read)."""

    def __init__(self, stage: FileReadStage, error: int, message: str):
        super().__init__(message)
        self.stage = stage
        self.error = error


class SequenceSizeError(SequenceFileError):
    """The header's size exceeds the sequencer's buffer (CS_FileSizeError)."""

    def __init__(self, size: int, capacity: int):
        super().__init__(f"sequence of {size} bytes does not fit the sequencer's {capacity}-byte "
                         f"buffer; split the sequence or give the sequencer a larger buffer")
        self.size = size


class SequenceCrcError(SequenceFileError):
    """The stored CRC differs from the CRC computed over the file (CS_FileCrcFailure)."""

    def __init__(self, stored: int, computed: int):
        super().__init__(f"CRC mismatch: stored 0x{stored:08X}, computed 0x{computed:08X}; the "
                         f"file is corrupt or was edited after fprime-seqgen wrote it")
        self.stored = stored
        self.computed = computed


class SequenceRecordError(SequenceFileError):
    """Record ``record_number`` (0-based) does not deserialize (CS_RecordInvalid)."""

    def __init__(self, record_number: int, error: SerializeStatus, message: str):
        super().__init__(f"record {record_number}: {message}")
        self.record_number = record_number
        self.error = error


class SequenceRecordMismatch(SequenceFileError):
    """Bytes are left after the header's number of records (CS_RecordMismatch)."""

    def __init__(self, header_records: int, extra_bytes: int):
        super().__init__(f"the header announces {header_records} record(s) but {extra_bytes} "
                         f"byte(s) follow the last of them")
        self.header_records = header_records
        self.extra_bytes = extra_bytes


class SequenceEmpty(SequenceFileError):
    """The sequence has no records (CS_NoRecords)."""

    def __init__(self):
        super().__init__("the sequence has no records")


class SequenceTimeBaseMismatch(SequenceFileError):
    """The file's time base is neither the current one nor TB_DONT_CARE (CS_TimeBaseMismatch)."""

    def __init__(self, current: int, sequence: int):
        super().__init__(f"sequence time base {sequence} differs from the current time base "
                         f"{current}; build it with 'fprime-seqgen -t {current}' or without -t")
        self.current = current
        self.sequence = sequence


class SequenceTimeContextMismatch(SequenceFileError):
    """The file's time context is neither the current one nor 0xFF (CS_TimeContextMismatch)."""

    def __init__(self, current: int, sequence: int):
        super().__init__(f"sequence time context {sequence} differs from the current context {current}")
        self.current = current
        self.sequence = sequence


class SequenceTextError(SequenceFileError):
    """A text sequence is wrong at ``path:line``; ``reason`` says what and how to fix it."""

    def __init__(self, path: str, line: int, reason: str):
        super().__init__(f"{path}:{line}: {reason}")
        self.path = path
        self.line = line
        self.reason = reason


# --- records --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Record:
    """One record: when to send (``descriptor``, ``seconds``, ``useconds``) and what.

    ``command`` is the command packet exactly as stored (``U16 0 | U32 opcode | args``); the
    sequencer sends it unchanged. An END_OF_SEQUENCE record has no time and no command.
    """

    descriptor: Descriptor
    seconds: int = 0
    useconds: int = 0
    command: bytes = b""

    @classmethod
    def for_command(cls, descriptor: Descriptor, seconds: int, useconds: int, opcode: int,
                    args: bytes = b"") -> "Record":
        """A record sending command ``opcode`` with serialized ``args``."""
        return cls(Descriptor(descriptor), seconds, useconds,
                   _CMD_HEADER.pack(Apid.FW_PACKET_COMMAND, opcode) + bytes(args))

    @property
    def opcode(self) -> int | None:
        """The command's opcode (None when the packet is too short to hold one)."""
        if len(self.command) < _CMD_HEADER.size:
            return None
        return _CMD_HEADER.unpack_from(self.command)[1]

    @property
    def args(self) -> bytes:
        """The command's serialized arguments."""
        return self.command[_CMD_HEADER.size:]

    @property
    def time_us(self) -> int:
        """The time tag in microseconds (absolute: since 1970 UTC; relative: a delay)."""
        return self.seconds * 1_000_000 + self.useconds

    def encode(self) -> bytes:
        if self.descriptor == Descriptor.END_OF_SEQUENCE:
            return bytes([Descriptor.END_OF_SEQUENCE])
        return _RECORD_HEAD.pack(int(self.descriptor), self.seconds, self.useconds,
                                 len(self.command)) + self.command


@dataclass
class Sequence:
    """A decoded or compiled sequence: its records and the header's time base and context."""

    records: list[Record] = field(default_factory=list)
    time_base: int = TB_DONT_CARE
    context: int = CONTEXT_DONT_CARE


def encode_binary(sequence: Sequence) -> bytes:
    """The file bytes of ``sequence``: header, records, CRC (what ``fprime-seqgen`` writes)."""
    body = b"".join(r.encode() for r in sequence.records)
    data = _HEADER.pack(len(body) + CRC_SIZE, len(sequence.records), sequence.time_base,
                        sequence.context) + body
    return data + _U32.pack(zlib.crc32(data) & 0xFFFFFFFF)


def decode_binary(data: bytes, *, capacity: int | None = None,
                  check_header: Callable[[int, int], None] | None = None) -> Sequence:
    """Decode and validate a binary sequence, in the order F´'s CmdSequencer does.

    Order: header, buffer size (``capacity`` bytes of records + CRC, None = unlimited), records
    and CRC present, CRC, ``check_header(time_base, context)`` (may raise, see
    :func:`check_time`), then each record. Bytes beyond ``size`` are ignored, as in F´.
    """
    data = bytes(data)
    if len(data) < HEADER_SIZE:
        raise SequenceFormatError(FileReadStage.READ_HEADER_SIZE, len(data),
                                  f"file of {len(data)} bytes is shorter than the "
                                  f"{HEADER_SIZE}-byte header")
    size, num_records, time_base, context = _HEADER.unpack_from(data)
    if capacity is not None and size > capacity:
        raise SequenceSizeError(size, capacity)
    body = data[HEADER_SIZE:HEADER_SIZE + size]
    if len(body) != size:
        raise SequenceFormatError(FileReadStage.READ_SEQ_DATA_SIZE, len(body),
                                  f"the header announces {size} bytes of records and CRC but only "
                                  f"{len(body)} follow; the file is truncated")
    if size < CRC_SIZE:
        raise SequenceFormatError(FileReadStage.READ_SEQ_CRC, size,
                                  f"{size} byte(s) after the header cannot hold the 4-byte CRC")
    records_data = body[:-CRC_SIZE]
    stored = _U32.unpack_from(body, size - CRC_SIZE)[0]
    computed = zlib.crc32(data[:HEADER_SIZE] + records_data) & 0xFFFFFFFF
    if stored != computed:
        raise SequenceCrcError(stored, computed)
    if check_header is not None:
        check_header(time_base, context)
    if num_records == 0:
        raise SequenceEmpty()
    records = []
    offset = 0
    for number in range(num_records):
        record, offset = _decode_record(records_data, offset, number)
        records.append(record)
    if offset != len(records_data):
        raise SequenceRecordMismatch(num_records, len(records_data) - offset)
    return Sequence(records, time_base, context)


def _decode_record(data: bytes, offset: int, number: int) -> tuple[Record, int]:
    if offset >= len(data):
        raise SequenceRecordError(number, SerializeStatus.FW_DESERIALIZE_BUFFER_EMPTY,
                                  "the file ends before this record")
    descriptor = data[offset]
    if descriptor > Descriptor.END_OF_SEQUENCE:
        raise SequenceRecordError(number, SerializeStatus.FW_DESERIALIZE_FORMAT_ERROR,
                                  f"descriptor {descriptor} is not 0 (absolute), 1 (relative) or "
                                  f"2 (end of sequence)")
    if descriptor == Descriptor.END_OF_SEQUENCE:
        return Record(Descriptor.END_OF_SEQUENCE), offset + 1
    if offset + _RECORD_HEAD.size > len(data):
        raise SequenceRecordError(number, SerializeStatus.FW_DESERIALIZE_SIZE_MISMATCH,
                                  f"only {len(data) - offset} byte(s) left for the "
                                  f"{_RECORD_HEAD.size}-byte record header")
    _, seconds, useconds, cmd_size = _RECORD_HEAD.unpack_from(data, offset)
    start = offset + _RECORD_HEAD.size
    if cmd_size > len(data) - start:
        raise SequenceRecordError(number, SerializeStatus.FW_DESERIALIZE_SIZE_MISMATCH,
                                  f"command size {cmd_size} exceeds the {len(data) - start} "
                                  f"byte(s) left")
    if cmd_size + 2 > COM_BUFFER_MAX_SIZE:
        raise SequenceRecordError(number, SerializeStatus.FW_DESERIALIZE_SIZE_MISMATCH,
                                  f"command size {cmd_size} does not fit a {COM_BUFFER_MAX_SIZE}-byte "
                                  f"command buffer")
    return (Record(Descriptor(descriptor), seconds, useconds, data[start:start + cmd_size]),
            start + cmd_size)


def check_time(current_base: int, current_context: int) -> Callable[[int, int], None]:
    """A ``check_header`` for :func:`decode_binary`: the file's time base and context must be the
    current ones or "don't care" (0xFFFF, 0xFF), as F´ requires."""

    def check(time_base: int, context: int) -> None:
        if time_base != current_base and time_base != TB_DONT_CARE:
            raise SequenceTimeBaseMismatch(current_base, time_base)
        if context != current_context and context != CONTEXT_DONT_CARE:
            raise SequenceTimeContextMismatch(current_context, context)

    return check


# --- text: lexing and parsing ---------------------------------------------------------------------

class Name(str):
    """A bare identifier in a text sequence (an enum constant)."""


class Quoted(str):
    """A quoted string in a text sequence (quotes removed, no escapes processed)."""


@dataclass
class TextCommand:
    """One parsed line: ``line`` (1-based), time tag, mnemonic and argument values.

    Argument values are ``int``, ``float``, ``bool``, :class:`Quoted`, :class:`Name`, ``list``
    (arrays) or ``dict`` (structs), not yet checked against any type.
    """

    line: int
    descriptor: Descriptor
    seconds: int
    useconds: int
    mnemonic: str
    args: list[Any]


_DIGITS = r"\d(?:_?\d)*"
_TOKEN = re.compile(
    r"(?P<ws>[\t \f]+)"
    r"|(?P<cont>\\[\t \f]*\r?\n)"
    r"|(?P<newline>\r?\n)"
    r"|(?P<comment>;[^\n]*)"
    r"""|(?P<string>"(?!"").*?(?<!\\)(?:\\\\)*?"|'(?!'').*?(?<!\\)(?:\\\\)*?')"""
    r"|(?P<hex>[+-]?0[xX](?:_?[0-9a-fA-F])+)"
    rf"|(?P<float>[+-]?(?:{_DIGITS}[eE][+-]?{_DIGITS}|(?:\.{_DIGITS}|{_DIGITS}\.{_DIGITS})"
    rf"(?:[eE][+-]?{_DIGITS})?))"
    r"|(?P<dec>[+-]?(?:[1-9](?:_?\d)*|0(?:_?0)*(?![1-9xX])))"
    r"|(?P<name>\$?[^\W\d]\w*(?:\.\w+)*)"
    r"|(?P<punct>[\[\]{},:])"
)
_TIME_TAG = re.compile(
    r"(?P<kind>[RA])[\t \f]*(?:(?P<abs>\d{4}-\d{3}T\d{2}:\d{2}:\d{2}(?:\.\d{1,6})?)"
    r"|(?P<rel>\d{2}:\d{2}:\d{2}(?:\.\d{1,6})?))(?![\w.:])")
_BLANK = re.compile(r"(?:[\t \f]+|;[^\n]*|\\[\t \f]*\r?\n)*")
_BOOLEANS = {"true": True, "True": True, "TRUE": True, "false": False, "False": False, "FALSE": False}
_EPOCH = datetime(1970, 1, 1)


@dataclass
class _Tok:
    kind: str
    text: str
    line: int
    value: Any = None


def _time_tag(kind: str, rel: str | None, absolute: str | None) -> tuple[Descriptor, int, int]:
    """Seconds and microseconds of a time tag, computed as fprime-seqgen computes them."""
    if kind == "R":
        if rel is None:
            raise ValueError(f"R needs a relative time HH:MM:SS[.ffffff], got {absolute!r}; "
                             f"use A for an absolute time")
        dt = datetime.strptime(rel, "%H:%M:%S.%f" if "." in rel else "%H:%M:%S")
        delta = timedelta(hours=dt.hour, minutes=dt.minute, seconds=dt.second,
                          microseconds=dt.microsecond).total_seconds()
        descriptor = Descriptor.RELATIVE
    else:
        if absolute is None:
            raise ValueError(f"A needs an absolute time YYYY-DDDTHH:MM:SS[.ffffff], got {rel!r}; "
                             f"use R for a relative time")
        dt = datetime.strptime(absolute, "%Y-%jT%H:%M:%S.%f" if "." in absolute else "%Y-%jT%H:%M:%S")
        delta = (dt - _EPOCH).total_seconds()
        descriptor = Descriptor.ABSOLUTE
    # fprime-seqgen goes through a float; doing the same keeps the bytes identical.
    seconds = int(delta)
    return descriptor, seconds, int((delta - seconds) * 1_000_000)


def _lex_line(text: str, pos: int, line: int, path: str) -> tuple[list[_Tok], int, int]:
    """Tokens of one logical line starting at ``pos`` (after its time tag is read by the caller).
    Returns (tokens, position after the newline, line number after it)."""
    tokens: list[_Tok] = []
    n = len(text)
    while pos < n:
        m = _TOKEN.match(text, pos)
        if m is None:
            snippet = text[pos:pos + 12].split("\n")[0]
            raise SequenceTextError(path, line, f"unexpected text {snippet!r}; arguments are "
                                    f"numbers, quoted strings, true/false, enum names, [arrays] "
                                    f"or {{structs}}")
        kind = m.lastgroup
        tok_text = m.group(0)
        pos = m.end()
        if kind == "newline":
            return tokens, pos, line + 1
        if kind == "cont":
            line += 1
            continue
        if kind in ("ws", "comment"):
            continue
        if kind == "string":
            tokens.append(_Tok("value", tok_text, line, Quoted(tok_text[1:-1])))
        elif kind == "hex":
            tokens.append(_Tok("value", tok_text, line, int(tok_text, 16)))
        elif kind == "float":
            tokens.append(_Tok("value", tok_text, line, float(tok_text)))
        elif kind == "dec":
            tokens.append(_Tok("value", tok_text, line, int(tok_text)))
        elif kind == "name":
            if tok_text in _BOOLEANS:
                tokens.append(_Tok("value", tok_text, line, _BOOLEANS[tok_text]))
            else:
                tokens.append(_Tok("name", tok_text, line, Name(tok_text)))
        else:
            tokens.append(_Tok(tok_text, tok_text, line))
    return tokens, pos, line


class _Parser:
    def __init__(self, tokens: list[_Tok], path: str, line: int):
        self.tokens = tokens
        self.i = 0
        self.path = path
        self.line = line

    def error(self, reason: str) -> SequenceTextError:
        tok = self.peek()
        return SequenceTextError(self.path, tok.line if tok else self.line, reason)

    def peek(self) -> _Tok | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self, kind: str | None = None) -> _Tok | None:
        tok = self.peek()
        if tok is not None and (kind is None or tok.kind == kind):
            self.i += 1
            return tok
        return None

    def value(self) -> Any:
        tok = self.peek()
        if tok is None:
            raise self.error("the line ends where a value was expected")
        if tok.kind in ("value", "name"):
            self.i += 1
            return tok.value
        if tok.kind == "[":
            self.i += 1
            items: list[Any] = []
            while not self.take("]"):
                if items and not self.take(","):
                    raise self.error(f"expected ',' or ']' in an array, got {self._show()}")
                if self.take("]"):
                    break
                items.append(self.value())
            return items
        if tok.kind == "{":
            self.i += 1
            members: dict[str, Any] = {}
            while not self.take("}"):
                if members and not self.take(","):
                    raise self.error(f"expected ',' or '}}' in a struct, got {self._show()}")
                if self.take("}"):
                    break
                key = self.take("name")
                if key is None:
                    raise self.error(f"expected a member name in a struct, got {self._show()}")
                if not self.take(":"):
                    raise self.error(f"expected ':' after struct member {key.text!r}")
                if key.text in members:
                    raise self.error(f"struct member {key.text!r} is given twice")
                members[key.text] = self.value()
            return members
        raise self.error(f"unexpected {self._show()} where a value was expected")

    def _show(self) -> str:
        tok = self.peek()
        return "the end of the line" if tok is None else repr(tok.text)


def parse_text(text: str, path: str = "<text>") -> list[TextCommand]:
    """Parse a text sequence into :class:`TextCommand` s (no dictionary needed)."""
    commands: list[TextCommand] = []
    pos = 0
    line = 1
    n = len(text)
    while pos < n:
        # skip blank space, comments and continuations before a statement
        m = _BLANK.match(text, pos)
        assert m is not None  # _BLANK matches the empty string
        line += text.count("\n", pos, m.end())
        pos = m.end()
        if pos >= n:
            break
        if text.startswith("\n", pos) or text.startswith("\r\n", pos):
            pos = text.index("\n", pos) + 1
            line += 1
            continue
        start_line = line
        tag = _TIME_TAG.match(text, pos)
        if tag is None:
            snippet = text[pos:].split("\n", 1)[0].strip()
            raise SequenceTextError(path, line, f"expected a time tag at the start of {snippet!r}: "
                                    f"R<HH:MM:SS[.ffffff]> (relative) or "
                                    f"A<YYYY-DDDTHH:MM:SS[.ffffff]> (absolute, UTC)")
        try:
            descriptor, seconds, useconds = _time_tag(tag.group("kind"), tag.group("rel"),
                                                      tag.group("abs"))
        except ValueError as exc:
            raise SequenceTextError(path, line, f"invalid time tag {tag.group(0)!r}: {exc} (hours "
                                    f"00-23, minutes and seconds 00-59, day of year 001-366)") from None
        tokens, pos, line = _lex_line(text, tag.end(), line, path)
        parser = _Parser(tokens, path, start_line)
        mnemonic = parser.take("name")
        if mnemonic is None:
            raise parser.error(f"expected a command name after the time tag, got {parser._show()}")
        parser.take(",")
        args: list[Any] = []
        while parser.peek() is not None:
            if args:
                parser.take(",")
            args.append(parser.value())
        commands.append(TextCommand(start_line, descriptor, seconds, useconds, str(mnemonic.text), args))
    return commands


# --- text: compiling against a dictionary ---------------------------------------------------------

def _describe(value: Any) -> str:
    if isinstance(value, Quoted):
        return f'string "{value}"'
    if isinstance(value, Name):
        return f"name {value}"
    if isinstance(value, bool):
        return f"boolean {str(value).lower()}"
    if isinstance(value, list):
        return f"array of {len(value)}"
    if isinstance(value, dict):
        return "struct {" + ", ".join(value) + "}"
    return f"{type(value).__name__} {value!r}"


def _checked(t: FwType, value: Any, where: str) -> Any:
    try:
        return t.check(value)
    except SerializationError as exc:
        raise SerializationError(f"{where}: {exc}") from None


def _convert(value: Any, t: FwType, where: str) -> Any:
    """The Python value of text ``value`` for F´ type ``t``; SerializationError says why not."""
    while isinstance(t, AliasType):
        t = t.target
    if isinstance(t, IntType):
        if isinstance(value, bool) or not isinstance(value, int):
            raise SerializationError(f"{where} expects an integer ({t.name}), got {_describe(value)}")
        return _checked(t, value, where)
    if isinstance(t, FloatType):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise SerializationError(f"{where} expects a number ({t.name}), got {_describe(value)}")
        return _checked(t, float(value), where)
    if isinstance(t, BoolType):
        if not isinstance(value, bool):
            raise SerializationError(f"{where} expects true or false, got {_describe(value)}")
        return value
    if isinstance(t, StringType):
        if not isinstance(value, Quoted):
            raise SerializationError(f"{where} expects a quoted string, got {_describe(value)}; "
                                     f"write it in double or single quotes")
        return _checked(t, str(value), where)
    if isinstance(t, EnumType):
        names = ", ".join(m.name for m in t.cls)
        if not isinstance(value, Name):
            raise SerializationError(f"{where} expects a {t.name} constant ({names}), got "
                                     f"{_describe(value)}")
        if "." in value:
            raise SerializationError(f"{where}: write the bare constant name "
                                     f"({value.rsplit('.', 1)[1]}), not {value}")
        if value not in t.cls.__members__:
            raise SerializationError(f"{where}: {t.name} has no constant {value}; use one of {names}")
        return t.cls[value]
    if isinstance(t, ArrayType):
        if not isinstance(value, list):
            raise SerializationError(f"{where} expects an array [..] of {t.size} {t.elem.name}, "
                                     f"got {_describe(value)}")
        if len(value) != t.size:
            raise SerializationError(f"{where} expects {t.size} element(s) ({t.name}), got {len(value)}")
        return [_convert(v, t.elem, f"{where}[{i}]") for i, v in enumerate(value)]
    if isinstance(t, StructType):
        members = [n for n, _ in t.members]
        if not isinstance(value, dict):
            raise SerializationError(f"{where} expects a struct {{{', '.join(members)}}} ({t.name}), "
                                     f"got {_describe(value)}")
        missing = [n for n in members if n not in value]
        unknown = [k for k in value if k not in members]
        if unknown:
            raise SerializationError(f"{where}: {t.name} has no member(s) {', '.join(unknown)}; "
                                     f"its members are {', '.join(members)}")
        if missing:
            raise SerializationError(f"{where}: missing member(s) {', '.join(missing)} of {t.name}")
        return {n: _convert(value[n], mt, f"{where}.{n}") for n, mt in t.members}
    raise SerializationError(f"{where}: arguments of type {t.name} cannot be written in a sequence")


def _lookup(lookup: CommandLookup, name: str):
    try:
        return lookup(name)
    except KeyError:
        return None


def compile_text(text: str, lookup: CommandLookup, path: str = "<text>") -> Sequence:
    """Compile a text sequence to a :class:`Sequence` (time base TB_DONT_CARE, context 0xFF)."""
    records = []
    for cmd in parse_text(text, path):
        found = _lookup(lookup, cmd.mnemonic)
        if found is None:
            raise SequenceTextError(path, cmd.line, f"{cmd.mnemonic!r} is not a command of the "
                                    f"dictionary; use the full name, e.g. CdhCore.cmdDisp.CMD_NO_OP")
        opcode, arg_types = found
        arg_types = list(arg_types)
        if len(cmd.args) != len(arg_types):
            raise SequenceTextError(path, cmd.line, f"{cmd.mnemonic} takes {len(arg_types)} "
                                    f"argument(s), got {len(cmd.args)}")
        parts = []
        for i, (value, t) in enumerate(zip(cmd.args, arg_types, strict=True)):
            try:
                parts.append(t.serialize(_convert(value, t, f"argument {i + 1}")))
            except SerializationError as exc:
                raise SequenceTextError(path, cmd.line, f"{cmd.mnemonic}: {exc}") from None
        records.append(Record.for_command(cmd.descriptor, cmd.seconds, cmd.useconds, opcode,
                                          b"".join(parts)))
    return Sequence(records)


def read_sequence(path: str | Path, *, lookup: CommandLookup | None = None,
                  capacity: int | None = None,
                  check_header: Callable[[int, int], None] | None = None) -> Sequence:
    """Read a sequence file: text when it ends in ``.seq`` (needs ``lookup``), else binary.

    Raises OSError (FileNotFoundError …) when the file cannot be read, SequenceTextError or
    another SequenceFileError when it is not a valid sequence, SequenceEmpty when it holds no command
    (a text file of blank lines and comments, too).
    """
    path = Path(path)
    if path.suffix.lower() == ".seq":
        raw = path.read_bytes()
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError as exc:
            line = raw[:exc.start].count(b"\n") + 1
            raise SequenceTextError(str(path), line, "not UTF-8 text; a binary sequence must not "
                                    "end in .seq (fprime-seqgen writes .bin)") from None
        if lookup is None:
            raise SequenceTextError(str(path), 0, "text sequences need a command dictionary; give "
                                    "the sequencer a command_lookup, or compile the file with "
                                    "fprime-seqgen")
        sequence = compile_text(text, lookup, str(path))
        if not sequence.records:  # what fprime-seqgen makes of it: a file of no records (CS_NoRecords)
            raise SequenceEmpty()
        return sequence
    return decode_binary(path.read_bytes(), capacity=capacity, check_header=check_header)


# --- a command lookup from an F´ JSON dictionary --------------------------------------------------

_PRIMITIVES: dict[str, FwType] = PRIMITIVE_TYPES


class CommandDictionary:
    """The commands of an F´ JSON dictionary (``fpp-to-dict`` output), as a command lookup.

    ``CommandDictionary.from_json(path)("MiniDep.demo.CONFIGURE") -> (0x1000, [U32, F32, ...])``.
    Named types (enums, arrays, structs, aliases) become fprime_lite types.
    """

    def __init__(self, data: dict, source: str = "<dictionary>"):
        self.source = source
        self._defs = {d["qualifiedName"]: d for d in data.get("typeDefinitions", [])}
        self._types: dict[str, FwType] = {}
        self.commands: dict[str, tuple[int, list[FwType]]] = {}
        for cmd in data.get("commands", []):
            try:
                types = [self.type_of(p["type"]) for p in cmd.get("formalParams", [])]
            except (KeyError, TypeError, ValueError, DeclarationError) as exc:
                raise SequenceFileError(f"{source}: command {cmd.get('name')!r}: cannot build its "
                                        f"argument types: {exc}") from None
            self.commands[cmd["name"]] = (int(cmd["opcode"]), types)

    @classmethod
    def from_json(cls, path: str | Path) -> "CommandDictionary":
        with open(path, encoding="utf-8") as f:
            return cls(json.load(f), str(path))

    def __call__(self, name: str) -> tuple[int, list[FwType]]:
        return self.commands[name]

    def type_of(self, ref: dict) -> FwType:
        """The FwType a JSON type reference names."""
        name = ref["name"]
        if name in _PRIMITIVES:
            return _PRIMITIVES[name]
        if name == "string":
            return String(int(ref["size"]))
        if name not in self._types:
            if name not in self._defs:
                raise KeyError(f"type {name!r} is not in typeDefinitions")
            self._types[name] = self._define(self._defs[name])
        return self._types[name]

    def _define(self, d: dict) -> FwType:
        qualified = d["qualifiedName"]
        namespace, _, short = qualified.rpartition(".")
        kind = d["kind"]
        if kind == "alias":
            return AliasType(qualified, self.type_of(d["underlyingType"]))
        if kind == "enum":
            rep = _PRIMITIVES[d["representationType"]["name"]]
            constants = d["enumeratedConstants"]
            default = str(d.get("default", constants[0]["name"])).rsplit(".", 1)[-1]

            def body(ns):
                for c in constants:
                    ns[c["name"]] = int(c["value"])

            cls = _pytypes.new_class(short, (FwEnum,), {"namespace": namespace or None, "rep": rep,
                                                          "default": default}, body)
            return fw_type(cls)
        if kind == "array":
            elem = self.type_of(d["elementType"])
            cls = _pytypes.new_class(short, (Array,), {"elem": elem, "size": int(d["size"]),
                                                         "namespace": namespace or None})
            return fw_type(cls)
        if kind == "struct":
            members = sorted(d["members"].items(), key=lambda kv: kv[1]["index"])
            annotations = {}
            for member, spec in members:
                t = self.type_of(spec["type"])
                if spec.get("size") is not None:  # an inline array member
                    inline = _pytypes.new_class(f"{short}_{member}", (Array,),
                                                {"elem": t, "size": int(spec["size"]),
                                                 "namespace": namespace or None})
                    t = fw_type(inline)
                annotations[member] = t

            def body(ns):
                ns["__annotations__"] = annotations

            cls = _pytypes.new_class(short, (Struct,), {"namespace": namespace or None}, body)
            return fw_type(cls)
        raise ValueError(f"type {qualified!r} has unknown kind {kind!r}")
