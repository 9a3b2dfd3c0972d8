"""Mutation fuzzing of every flight parser except the topology loader (issue #16, ``docs/reliability.md``).

Parsers: parameter files (PrmDb), binary and text sequence files, raw command packets (as the ground
link hands them to CmdDispatcher, routed to the dispatcher's own commands or a component's command
input, arguments deserialised there), both uplink deframers, file packets.

Each parser gets inputs mutated from valid seeds (bit flips, byte sets, interesting integers, inserts,
deletes, duplicated ranges, splices, truncation, plus pure random bytes). An input *crashes* when the
parser raises anything but its documented error, or breaks an invariant checked below; it *hangs*
when it takes more than ``HANG_S`` of CPU time (a CPU-time timer, ``ITIMER_VIRTUAL``, interrupts it,
so a machine busy with other work does not count as a hang).

- Default suite: ``BOUNDED_INPUTS`` inputs per parser with a fixed seed (about a second each).
- Long mode: ``pytest -m fuzz tests/fuzz`` runs ``FPRIME_LITE_FUZZ_INPUTS`` inputs per parser
  (default 1 000 000) and at least ``FPRIME_LITE_FUZZ_MIN_S`` seconds each (default 0); the figures
  go to the JSON file ``FPRIME_LITE_FUZZ_REPORT`` when it is set.
"""

from __future__ import annotations

import collections
import json
import os
import random
import signal
import struct
import time
import zlib

import pytest

from fprime_lite import (BOOL, F32, F64, I8, I16, I64, U16, U32, U64, CmdResponse, FwEnum, Param,
                         PassiveComponent, String, Struct, fw_type, sync_command)
from fprime_lite.model.errors import SerializationError
from fprime_lite.svc.cmd_dispatcher import COM_BUFFER_MAX_SIZE, CmdDispatcher
from fprime_lite.svc.prm_db import ParamFileError, decode_param_file, encode_param_file, param_file_crc
from fprime_lite.testing import ComponentHarness
from fprime_lite.wire.file_packet import (CancelPacket, DataPacket, EndPacket, FilePacketError, StartPacket,
                                          decode_file_packet, encode_file_packet)
from fprime_lite.wire.framing import Dropped, make_framing
from fprime_lite.wire.packets import decode_command, encode_command
from fprime_lite.wire.seqfile import (Record, Sequence, SequenceFileError, SequenceTextError, compile_text,
                                      decode_binary, encode_binary)

BOUNDED_INPUTS = 20_000
HANG_S = 2.0  # s of CPU time
_INTERESTING = (0, 1, 0x7F, 0x80, 0xFF, 0x7FFF, 0x8000, 0xFFFF, 0x7FFFFFFF, 0x80000000, 0xFFFFFFFF)


class Hang(Exception):
    pass


# --- the mutator -------------------------------------------------------------------------------------

def mutate(rng: random.Random, seeds: list[bytes]) -> bytes:
    """One input: a seed with 1–8 random mutations, or (1 in 32) pure random bytes."""
    if rng.random() < 1 / 32:
        return rng.randbytes(rng.randrange(0, 200))
    data = bytearray(rng.choice(seeds))
    for _ in range(rng.randint(1, 8)):
        op = rng.randrange(9)
        n = len(data)
        if op == 0 and n:
            i = rng.randrange(n)
            data[i] ^= 1 << rng.randrange(8)
        elif op == 1 and n:
            data[rng.randrange(n)] = rng.randrange(256)
        elif op == 2 and n >= 2:
            width = rng.choice((2, 4))
            value = rng.choice(_INTERESTING + (n, n - 1, n + 1)) & ((1 << (8 * width)) - 1)
            i = rng.randrange(max(1, n - width + 1))
            data[i:i + width] = value.to_bytes(width, "big")
        elif op == 3:
            i = rng.randrange(n + 1)
            data[i:i] = rng.randbytes(rng.randrange(1, 16))
        elif op == 4 and n:
            i = rng.randrange(n)
            del data[i:i + rng.randrange(1, 16)]
        elif op == 5 and n:
            i = rng.randrange(n)
            j = rng.randrange(i, min(n, i + 32) + 1)
            k = rng.randrange(n + 1)
            data[k:k] = data[i:j]
        elif op == 6:
            other = rng.choice(seeds)
            if other:
                cut = rng.randrange(len(other))
                data = data[:rng.randrange(n + 1)] + bytearray(other[cut:])
        elif op == 7 and n:
            del data[rng.randrange(n):]
        elif op == 8 and n:
            i = rng.randrange(n)
            data[i:i] = bytes([data[i]]) * rng.randrange(1, 64)
    return bytes(data)


# --- the parsers and what each must never do --------------------------------------------------------

def _prm_seeds():
    records = [(0x1005A000 + i, struct.pack(">d", 1.5 * i)) for i in range(5)] + [(7, b"\x00\x00\x00\x05")]
    return [encode_param_file(records), encode_param_file(records, with_crc=False),
            encode_param_file(records[:1]), encode_param_file([])]


def fix_prm_crc(data: bytes) -> bytes:
    """Give a mutated file a CRC that matches, so the records behind it get parsed."""
    if len(data) < 4:
        return data
    return struct.pack(">I", param_file_crc(data[4:])) + data[4:]


def check_prm(data: bytes) -> None:
    try:
        decoded = decode_param_file(data)
    except ParamFileError:
        return
    for prm_id, value in decoded.records:
        assert isinstance(prm_id, int) and isinstance(value, bytes)


def _seq_records():
    return [Record.for_command(0, 0, 0, 0x01000100, b""),
            Record.for_command(1, 1, 500_000, 0x1005A000, b"\x00\x00\x00\x01"),
            Record.for_command(1, 0, 20_000, 0x42, b"\x00\x05hello\x3f\x80\x00\x00")]


def _seq_binary_seeds():
    records = _seq_records()
    return [encode_binary(Sequence(records)), encode_binary(Sequence(records[:1])),
            encode_binary(Sequence(records * 4))]


def fix_seq_size_and_crc(data: bytes) -> bytes:
    """Make a mutated file's header size and CRC consistent, so its records get decoded."""
    if len(data) < 15:
        return data
    records = data[11:-4]
    head = struct.pack(">I", len(records) + 4) + data[4:11]
    return head + records + struct.pack(">I", zlib.crc32(head + records) & 0xFFFFFFFF)


def check_seq_binary(data: bytes) -> None:
    try:
        decoded = decode_binary(data)
    except SequenceFileError:
        return
    assert decode_binary(encode_binary(decoded)) == decoded  # what decodes re-encodes to the same


class _Mode(FwEnum, namespace="Fuzz"):
    OFF = 0
    ON = 1


class _Pair(Struct, namespace="Fuzz"):
    a: U16
    b: F64


_COMMANDS = {
    "Fuzz.target.NO_ARGS": (0x100, []),
    "Fuzz.target.NUMBERS": (0x101, [I8, U16, U32, I64, F32, F64, BOOL]),
    "Fuzz.target.TEXT": (0x102, [String(40), _Mode]),
}


def _lookup(name):
    """The sequence compiler's dictionary look-up (KeyError: not a command)."""
    opcode, types = _COMMANDS[name]
    return opcode, [fw_type(t) for t in types]


_TEXT_SEEDS = [
    b"; a sequence\nR00:00:00 Fuzz.target.NO_ARGS\nR00:00:01.5 Fuzz.target.NUMBERS -5 7 100000 -9 2.5 -1e3 TRUE\n",
    b'R00:00:00 Fuzz.target.TEXT "hello, world" ON\nA2025-06-01T00:00:00 Fuzz.target.NO_ARGS\n',
    b"R01:02:03 Fuzz.target.NUMBERS 127 65535 4294967295 9223372036854775807 3.4e38 1.7e308 FALSE ; c\n",
]


def check_seq_text(data: bytes) -> None:
    text = data.decode("utf-8", errors="replace")
    try:
        compile_text(text, _lookup, "fuzz.seq")
    except SequenceTextError as exc:
        assert str(exc).startswith("fuzz.seq:"), f"a text error must name file:line, got {exc}"


class FuzzTarget(PassiveComponent):
    """Commands of every argument kind, and parameters, for the command-packet fuzzer."""

    @sync_command()
    def NO_ARGS(self):
        return CmdResponse.OK

    @sync_command()
    def NUMBERS(self, a: I8, b: U16, c: U32, d: I64, e: F32, f: F64, g: BOOL):
        return CmdResponse.OK

    @sync_command()
    def TEXT(self, s: String(40), mode: _Mode):
        return CmdResponse.OK

    @sync_command()
    def PAIR(self, p: _Pair, big: U64, small: I16):
        return CmdResponse.OK

    GAIN = Param(F64, default=1.0)
    MODE = Param(_Mode, default=_Mode.OFF)
    PAIR_PRM = Param(_Pair, default=_Pair(a=1, b=2.0))


class CommandPath:
    """Command packets as the ground link hands them over: into ``CmdDispatcher.seqCmdBuff``, routed
    by opcode (to the dispatcher's own commands or a component's ``cmdIn``, arguments deserialised
    there), answered through ``compCmdStat`` and the dispatcher's tracking table, out of
    ``seqCmdStatus``. Every packet gets exactly one answer, on the port it came in, with its context
    (and its opcode when it decodes); nothing raises and no command stays tracked."""

    SOURCE = 2  # the seqCmdBuff / seqCmdStatus index the "ground link" uses
    CLEAR_TRACKING = 0x103

    def __init__(self):
        self.disp = CmdDispatcher("cmdDisp", base_id=0x100)
        self.h = ComponentHarness(FuzzTarget("target", base_id=0x1000), unconnected=("cmdRegOut", "cmdResponseOut"))
        disp, target = self.disp, self.h.component
        disp.output_port("cmdRegOut").connect(0, disp.input_port("compCmdReg"), 0)  # as CdhCore wires it
        disp.output_port("compCmdSend").connect(0, disp.input_port("cmdIn"), 0)
        disp.output_port("cmdResponseOut").connect(0, disp.input_port("compCmdStat"), 0)
        target.output_port("cmdRegOut").connect(0, disp.input_port("compCmdReg"), 9)
        disp.output_port("compCmdSend").connect(9, target.input_port("cmdIn"), 0)
        target.output_port("cmdResponseOut").connect(0, disp.input_port("compCmdStat"), 0)
        self.answers: list[tuple] = []
        disp.output_port("seqCmdStatus").connect_callable(
            self.SOURCE, lambda opcode, context, response: self.answers.append((opcode, context, response)), "ground")
        disp.register_commands()
        target.register_commands()
        self.opcodes = sorted(disp.dispatch_table)
        assert len(self.opcodes) == 4 + len(target.spec.commands)
        self.seeds = []
        rng = random.Random(3)
        for opcode in self.opcodes:
            self.seeds.append(encode_command(opcode, rng.randbytes(rng.randrange(0, 40))))
        self.seeds.append(encode_command(0x1001, struct.pack(">bHIqfd?", -1, 2, 3, -4, 5.0, 6.0, True)))
        self.seeds.append(encode_command(0x1002, b"\x00\x03abc\x00\x00\x00\x01"))
        self.seeds.append(encode_command(0x101, b"\x00\x02hi"))  # cmdDisp.CMD_NO_OP_STRING
        self.context = 0
        #: (who answered: "cmdDisp" or "target", response name) -> count, to show what was reached
        self.outcomes: collections.Counter = collections.Counter()

    def __call__(self, data: bytes) -> None:
        self.context = (self.context + 1) & 0xFFFFFFFF
        self.answers.clear()
        self.disp.input_port("seqCmdBuff").entries[self.SOURCE](data, self.context)
        self.disp.dispatch_all()  # the packet, then the answer the target queued back (compCmdStat)
        try:
            decoded, args = decode_command(data)
        except SerializationError:
            decoded, args = None, None
        # CMD_CLEAR_TRACKING forgets every tracked command, itself included, so (as in F´) its own
        # OK reaches only the event log, not the source
        expected = 0 if decoded == self.CLEAR_TRACKING and args == b"" and len(data) <= COM_BUFFER_MAX_SIZE else 1
        assert len(self.answers) == expected, f"a command got {len(self.answers)} answers, not {expected}"
        if expected:
            opcode, context, response = self.answers[0]
            assert context == self.context and isinstance(response, CmdResponse)
            if decoded is not None:
                assert opcode == decoded, "answered for another opcode"
            self.outcomes["target" if opcode >= 0x1000 else "cmdDisp", response.name] += 1
        assert not self.disp.pending, "a command is still tracked after its answer"
        if len(self.h.port_calls) + len(self.h.events) > 10_000:
            self.h.clear_history()


def _file_seeds():
    return [encode_file_packet(p, descriptor=False) for p in (
        StartPacket(0, 1234, "ground/source.bin", "seq/run.bin"), DataPacket(3, 512, bytes(range(200))),
        EndPacket(9, 0xDEADBEEF), CancelPacket(4))]


def check_file_packet(data: bytes) -> None:
    decoded = decode_file_packet(data)
    assert isinstance(decoded, (StartPacket, DataPacket, EndPacket, CancelPacket, FilePacketError))


class Deframing:
    """Mutated streams of valid frames, pushed in two pieces, then the link drops (reset): nothing raises,
    the buffer stays bounded, every packet is a command or file packet, and an input the mutator left
    intact is delivered whole."""

    def __init__(self, name: str):
        self.framing = make_framing(name)
        rng = random.Random(5)
        commands = [encode_command(0x1000 + i, rng.randbytes(rng.randrange(0, 60))) for i in range(6)]
        frames = [self.framing.frame_uplink(c) for c in commands]
        #: seed stream -> the packets it must deliver
        self.expected = {b"".join(frames): commands,
                         frames[0] + b"sitting well" + frames[1]: commands[:2],
                         frames[2] * 3: [commands[2]] * 3,
                         self._bogus_header() + b"".join(frames[:3]): commands[:3]}
        self.seeds = list(self.expected)
        self.cut_rng = random.Random(6)

    def _bogus_header(self) -> bytes:
        if self.framing.name == "ccsds":
            return struct.pack(">HHB", (1 << 13) | 0x44, (1 << 10) | 1023, 0)
        return struct.pack(">II", 0xDEADBEEF, 4000)

    def __call__(self, data: bytes) -> None:
        deframer = self.framing.uplink_deframer()
        k = self.cut_rng.randrange(len(data) + 1)
        out = deframer.push(data[:k])
        assert deframer.buffered <= 4095 + 12
        out += deframer.push(data[k:])
        assert deframer.buffered <= 4095 + 12
        out += deframer.reset()
        for item in out:
            assert isinstance(item, Dropped) or item[:2] in (b"\x00\x00", b"\x00\x03")
        expected = self.expected.get(data)
        if expected is not None:
            assert [o for o in out if isinstance(o, bytes)] == expected, "a valid frame was lost"


def parsers():
    command = CommandPath()
    fprime, ccsds = Deframing("fprime"), Deframing("ccsds")
    return {  # name: (check, seeds, fix-up applied to half the inputs or None)
        "prmdb_file": (check_prm, _prm_seeds(), fix_prm_crc),
        "sequence_binary": (check_seq_binary, _seq_binary_seeds(), fix_seq_size_and_crc),
        "sequence_text": (check_seq_text, _TEXT_SEEDS, None),
        "command_packet": (command, command.seeds, None),
        "deframer_fprime": (fprime, fprime.seeds, None),
        "deframer_ccsds": (ccsds, ccsds.seeds, None),
        "file_packet": (check_file_packet, _file_seeds(), None),
    }


PARSERS = list(parsers())


# --- the runner --------------------------------------------------------------------------------------

def _on_timer(signum, frame):
    raise Hang()


def campaign(name: str, inputs: int, min_seconds: float = 0.0, seed: int = 16, hang_s: float = HANG_S) -> dict:
    """Run ``inputs`` mutated inputs (and at least ``min_seconds``) through parser ``name``."""
    check, seeds, fixup = parsers()[name]
    for s in seeds:  # the seeds themselves must pass
        check(s)
    rng = random.Random(seed)
    crashes: list[tuple[str, str]] = []
    hangs: list[str] = []
    slowest = 0.0
    count = 0
    previous = signal.signal(signal.SIGVTALRM, _on_timer)
    start = time.perf_counter()
    try:
        while count < inputs or time.perf_counter() - start < min_seconds:
            data = mutate(rng, seeds)
            if fixup is not None and rng.random() < 0.5:
                data = fixup(data)
            count += 1
            t0 = time.process_time()
            signal.setitimer(signal.ITIMER_VIRTUAL, hang_s)
            try:
                check(data)
            except Hang:
                hangs.append(data.hex())
            except Exception as exc:  # noqa: BLE001 - every unexpected exception is a finding
                crashes.append((data.hex(), f"{type(exc).__name__}: {exc}"[:300]))
            finally:
                signal.setitimer(signal.ITIMER_VIRTUAL, 0)
            slowest = max(slowest, time.process_time() - t0)
    finally:
        signal.signal(signal.SIGVTALRM, previous)
    return {"parser": name, "inputs": count, "seconds": round(time.perf_counter() - start, 1),
            "crashes": len(crashes), "hangs": len(hangs), "slowest_input_cpu_ms": round(slowest * 1e3, 2),
            "first_crashes": crashes[:5], "first_hangs": hangs[:5]}


@pytest.mark.parametrize("name", PARSERS)
def test_bounded_fuzz(name):
    """FUZZ-1: BOUNDED_INPUTS mutated inputs per parser (fixed seed): no crash, no hang, every
    invariant holds."""
    result = campaign(name, BOUNDED_INPUTS)
    assert result["crashes"] == 0, result["first_crashes"]
    assert result["hangs"] == 0, result["first_hangs"]


def test_the_fuzzer_finds_a_planted_bug():
    """FUZZ-2: the campaign is not blind: a parser that fails on one byte value and loops forever on
    inputs of some lengths (bugs planted for this test) is reported as crashing and as hanging."""
    def planted(data):
        if len(data) > 8 and data[8] == 0x42:
            raise IndexError("planted")
        if len(data) % 211 == 0:
            while True:
                pass

    original = parsers

    def with_planted():
        table = original()
        table["planted"] = (planted, _seq_binary_seeds(), None)
        return table

    globals()["parsers"] = with_planted
    try:
        result = campaign("planted", 3000, hang_s=0.02)
    finally:
        globals()["parsers"] = original
    assert result["crashes"] > 0 and "planted" in result["first_crashes"][0][1]
    assert result["hangs"] > 0 and len(bytes.fromhex(result["first_hangs"][0])) % 211 == 0


def test_the_command_path_goes_through_the_dispatcher(monkeypatch):
    """FUZZ-4: the command fuzzer sends packets the way the ground link does, through CmdDispatcher:
    its inputs reach every routing outcome (a component's command run or refused for its
    arguments, the dispatcher's own commands, unknown opcodes, malformed packets), and a bug
    planted in the dispatcher's packet parsing is found."""
    import fprime_lite.svc.cmd_dispatcher as cmd_dispatcher

    path = parsers()["command_packet"][0]
    rng = random.Random(21)
    for _ in range(3000):
        path(mutate(rng, path.seeds))
    reached = path.outcomes
    for outcome in [("target", "OK"), ("target", "FORMAT_ERROR"), ("cmdDisp", "OK"),
                    ("cmdDisp", "INVALID_OPCODE"), ("cmdDisp", "VALIDATION_ERROR")]:
        assert reached[outcome] > 0, (outcome, reached)

    parse = cmd_dispatcher._parse_command

    def planted(data):
        if len(data) > 7 and data[7] == 0x42:
            raise IndexError("planted")
        return parse(data)

    monkeypatch.setattr(cmd_dispatcher, "_parse_command", planted)
    result = campaign("command_packet", 3000)
    assert result["crashes"] > 0, result


@pytest.mark.fuzz
@pytest.mark.parametrize("name", PARSERS)
def test_long_fuzz(name):
    """FUZZ-3 (long mode, ``-m fuzz``): FPRIME_LITE_FUZZ_INPUTS inputs per parser (default 1 M)."""
    inputs = int(os.environ.get("FPRIME_LITE_FUZZ_INPUTS", "1000000"))
    min_s = float(os.environ.get("FPRIME_LITE_FUZZ_MIN_S", "0"))
    result = campaign(name, inputs, min_s, seed=int(os.environ.get("FPRIME_LITE_FUZZ_SEED", "16")))
    report = os.environ.get("FPRIME_LITE_FUZZ_REPORT")
    if report:
        with open(report, "a", encoding="utf-8") as f:
            f.write(json.dumps(result) + "\n")
    assert result["crashes"] == 0, result["first_crashes"]
    assert result["hangs"] == 0, result["first_hangs"]
