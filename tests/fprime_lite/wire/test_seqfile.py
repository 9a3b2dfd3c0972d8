"""Sequence files: the binary format of fprime-seqgen 4.4.1 and its text source.

The outside authority is fprime-seqgen itself: ``tests/data/gds/example.bin`` (written by it, see
``tests/data/gds/gds_notes.md`` (c)) and, where the tool is installed, fresh runs of it.
"""

from __future__ import annotations

import re
import struct
import subprocess
import sys
import zlib
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fprime_lite.wire.seqfile import (CommandDictionary, Descriptor, FileReadStage, Record, Sequence,
                                 SequenceCrcError, SequenceEmpty, SequenceFormatError,
                                 SequenceRecordError, SequenceRecordMismatch, SequenceSizeError,
                                 SequenceTextError, SequenceTimeBaseMismatch,
                                 SequenceTimeContextMismatch, SerializeStatus, check_time,
                                 compile_text, decode_binary, encode_binary, parse_text,
                                 read_sequence)
from fprime_lite.model.types import F32, U32, String

DATA = Path(__file__).resolve().parents[2] / "data" / "gds"
DICT = DATA / "minimal_dictionary.json"
SEQGEN = Path(sys.executable).parent / "fprime-seqgen"


@pytest.fixture(scope="module")
def dictionary():
    return CommandDictionary.from_json(DICT)


def run_seqgen(tmp_path: Path, text: str, *extra: str) -> bytes:
    """Compile ``text`` with the real fprime-seqgen; return the binary it wrote."""
    if not SEQGEN.exists():
        pytest.skip(f"fprime-seqgen not installed next to {sys.executable}")
    src = tmp_path / "input.seq"
    out = tmp_path / "output.bin"
    src.write_text(text)
    done = subprocess.run([str(SEQGEN), str(src), str(out), "--dictionary", str(DICT), *extra],
                          cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stdout + done.stderr
    return out.read_bytes()


def with_crc(body: bytes) -> bytes:
    return body + struct.pack(">I", zlib.crc32(body))


# --- binary -----------------------------------------------------------------------------------

def test_example_bin_records():
    """SEQ-BIN-1: example.bin (written by fprime-seqgen) decodes to its six records."""
    seq = decode_binary((DATA / "example.bin").read_bytes())
    assert (seq.time_base, seq.context) == (0xFFFF, 0xFF)
    got = [(r.descriptor, r.seconds, r.useconds, r.opcode, r.args.hex()) for r in seq.records]
    assert got == [
        (Descriptor.RELATIVE, 0, 0, 0x100, ""),
        (Descriptor.RELATIVE, 1, 500_000, 0x1000, "00000007" "40200000" "0005" + b"hello".hex() + "00000001"),
        (Descriptor.ABSOLUTE, 1735689610, 0, 0x101, "0003" + b"abs".hex()),
        (Descriptor.RELATIVE, 0, 0, 0x1001, "3f800000" "40000000" "40400000"),
        (Descriptor.RELATIVE, 2, 0, 0x1002, "3fc00000" "3e800000" "00000002" "0001" + b"g".hex()),
        (Descriptor.RELATIVE, 0, 0, 0x1004, "0000002a"),
    ]
    assert all(r.command[:2] == b"\x00\x00" for r in seq.records)  # FW_PACKET_COMMAND


def test_encode_reproduces_example_bin():
    """SEQ-BIN-2: encoding the decoded records gives back the same bytes (CRC 0x6EB20CC6)."""
    data = (DATA / "example.bin").read_bytes()
    assert encode_binary(decode_binary(data)) == data
    assert data[-4:] == bytes.fromhex("6eb20cc6")


def test_compiled_example_seq_is_byte_identical_to_example_bin(dictionary):
    """SEQ-TXT-1: our compiler + writer on example.seq give fprime-seqgen's example.bin."""
    seq = compile_text((DATA / "example.seq").read_text(), dictionary, "example.seq")
    assert encode_binary(seq) == (DATA / "example.bin").read_bytes()


TRICKY = """\
; every lexical form seqgen accepts, against minimal_dictionary.json
R00:00:00 CdhCore.cmdDisp.CMD_NO_OP
R00:00:01.123456 MiniDep.demo.CONFIGURE 0x10, -1.5e-3, 'semi;colon', SAFE ; comment
R00:00:00.1 MiniDep.demo.CONFIGURE 1_000 \\
    7 "" SCIENCE
A2025-032T12:34:56.789 CdhCore.cmdDisp.CMD_NO_OP_STRING "x"
A1970-001T00:00:00 MiniDep.demo.SET_VEC [.5, -2, 3e2,]
R23:59:59.999999 MiniDep.demo.GAINS_PRM_SET {kp: 0.1, ki: 1e-07, mode: NOMINAL, label: "abc",}
R00:00:00 MiniDep.demo.THRESHOLD_PRM_SET 4294967295

"""


def test_our_writer_matches_fprime_seqgen(tmp_path, dictionary):
    """SEQ-TXT-2: for the same text, our bytes equal a fresh fprime-seqgen run's bytes."""
    expected = run_seqgen(tmp_path, TRICKY)
    ours = encode_binary(compile_text(TRICKY, dictionary, "tricky.seq"))
    assert ours == expected


def test_time_base_header_matches_fprime_seqgen_t(tmp_path, dictionary):
    """SEQ-TXT-3: a time base in the header is written as ``fprime-seqgen -t 2`` writes it."""
    text = "R00:00:02 CdhCore.cmdDisp.CMD_NO_OP\n"
    expected = run_seqgen(tmp_path, text, "-t", "2")
    seq = compile_text(text, dictionary)
    seq.time_base = 2
    assert encode_binary(seq) == expected
    assert expected[8:11] == bytes.fromhex("0002ff")


def test_bad_crc():
    """SEQ-BIN-3: a flipped byte is a CRC failure naming both CRCs."""
    data = bytearray((DATA / "example.bin").read_bytes())
    data[30] ^= 0x01
    with pytest.raises(SequenceCrcError, match=r"stored 0x6EB20CC6, computed 0x[0-9A-F]{8}") as err:
        decode_binary(bytes(data))
    assert err.value.stored == 0x6EB20CC6
    assert err.value.computed == zlib.crc32(bytes(data[:-4]))


def test_truncated_file():
    """SEQ-BIN-4: a file shorter than its header announces is invalid at READ_SEQ_DATA_SIZE."""
    data = (DATA / "example.bin").read_bytes()
    with pytest.raises(SequenceFormatError, match="truncated") as err:
        decode_binary(data[:100])
    assert err.value.stage == FileReadStage.READ_SEQ_DATA_SIZE
    assert err.value.error == 100 - 11  # the bytes actually there after the header


def test_truncated_header():
    """SEQ-BIN-5: fewer than 11 bytes is invalid at READ_HEADER_SIZE."""
    with pytest.raises(SequenceFormatError, match="shorter than the 11-byte header") as err:
        decode_binary(b"\x00\x00\x00")
    assert (err.value.stage, err.value.error) == (FileReadStage.READ_HEADER_SIZE, 3)


def test_size_too_small_for_crc():
    """SEQ-BIN-6: a size below 4 cannot hold the CRC (READ_SEQ_CRC)."""
    with pytest.raises(SequenceFormatError) as err:
        decode_binary(struct.pack(">IIHB", 2, 1, 0xFFFF, 0xFF) + b"\x00\x00")
    assert err.value.stage == FileReadStage.READ_SEQ_CRC


def test_bad_descriptor():
    """SEQ-BIN-7: descriptor 3 makes that record invalid (FW_DESERIALIZE_FORMAT_ERROR)."""
    data = bytearray((DATA / "example.bin").read_bytes()[:-4])
    data[0x1E] = 3  # descriptor of record 1 (record 0 is bytes 0x0B-0x1D)
    with pytest.raises(SequenceRecordError, match="record 1: descriptor 3") as err:
        decode_binary(with_crc(bytes(data)))
    assert err.value.record_number == 1
    assert err.value.error == SerializeStatus.FW_DESERIALIZE_FORMAT_ERROR


def test_command_size_beyond_data():
    """SEQ-BIN-8: a command size past the end is a size mismatch."""
    body = struct.pack(">BIII", 1, 0, 0, 50) + b"\x00" * 6
    head = struct.pack(">IIHB", len(body) + 4, 1, 0xFFFF, 0xFF)
    with pytest.raises(SequenceRecordError) as err:
        decode_binary(with_crc(head + body))
    assert err.value.error == SerializeStatus.FW_DESERIALIZE_SIZE_MISMATCH


def test_extra_bytes_and_no_records():
    """SEQ-BIN-9: bytes after the announced records, and zero records, are refused."""
    rec = Record.for_command(Descriptor.RELATIVE, 0, 0, 0x100).encode()
    head = struct.pack(">IIHB", len(rec) + 2 + 4, 1, 0xFFFF, 0xFF)
    with pytest.raises(SequenceRecordMismatch) as err:
        decode_binary(with_crc(head + rec + b"\x00\x00"))
    assert (err.value.header_records, err.value.extra_bytes) == (1, 2)
    with pytest.raises(SequenceEmpty):
        decode_binary(encode_binary(Sequence([])))


def test_text_file_without_commands_is_empty(tmp_path):
    """SEQ-TXT-EMPTY: a .seq file of blank lines and comments reads as SequenceEmpty, as the binary of no
    records fprime-seqgen would make from it does."""
    path = tmp_path / "nothing.seq"
    path.write_text("; a comment\n\n")
    with pytest.raises(SequenceEmpty):
        read_sequence(path, lookup=lambda name: None)


def test_capacity():
    """SEQ-BIN-10: a size beyond the sequencer's buffer is refused before reading on."""
    with pytest.raises(SequenceSizeError, match="173 bytes"):
        decode_binary((DATA / "example.bin").read_bytes(), capacity=100)


def test_end_of_sequence_record_round_trip():
    """SEQ-BIN-11: descriptor 2 is a lone byte that ends the sequence."""
    seq = Sequence([Record.for_command(Descriptor.ABSOLUTE, 5, 6, 0x100), Record(Descriptor.END_OF_SEQUENCE)])
    data = encode_binary(seq)
    assert data[-5] == 2
    assert decode_binary(data).records == seq.records


def test_time_checks():
    """SEQ-BIN-12: header time base/context must match the current ones unless "don't care"."""
    check_time(2, 0)(0xFFFF, 0xFF)
    check_time(2, 0)(2, 0)
    with pytest.raises(SequenceTimeBaseMismatch):
        check_time(2, 0)(1, 0xFF)
    with pytest.raises(SequenceTimeContextMismatch):
        check_time(2, 0)(2, 7)


records = st.builds(
    Record.for_command, st.sampled_from([Descriptor.ABSOLUTE, Descriptor.RELATIVE]),
    st.integers(0, 2**32 - 1), st.integers(0, 999_999), st.integers(0, 2**32 - 1),
    st.binary(max_size=40))


@settings(max_examples=60, deadline=None)
@given(st.lists(records, min_size=1, max_size=8), st.sampled_from([0, 1, 2, 0xFFFF]))
def test_round_trip(recs, time_base):
    """SEQ-BIN-13: decode(encode(s)) == s for any records."""
    seq = Sequence(recs, time_base, 0xFF)
    assert decode_binary(encode_binary(seq)) == seq


# --- text -------------------------------------------------------------------------------------

def test_parse_text_values():
    """SEQ-TXT-4: the parser's values before any dictionary."""
    [cmd] = parse_text('R01:02:03.5 a.b.C 0x2A, -3 2.5 "s" TRUE NAME [1, [2]] {k: {j: false}}\n')
    assert (cmd.line, cmd.descriptor, cmd.seconds, cmd.useconds, cmd.mnemonic) == \
        (1, Descriptor.RELATIVE, 3723, 500_000, "a.b.C")
    assert cmd.args == [42, -3, 2.5, "s", True, "NAME", [1, [2]], {"k": {"j": False}}]


def test_dictionary_lookup(dictionary):
    """SEQ-TXT-5: the JSON dictionary's commands and named types become fprime_lite types."""
    opcode, types = dictionary("MiniDep.demo.CONFIGURE")
    assert opcode == 0x1000
    assert types[:3] == [U32, F32, String(40)]
    assert types[3].name == "Demo.Mode" and [m.name for m in types[3].cls] == ["SAFE", "NOMINAL", "SCIENCE"]
    gains = dictionary("MiniDep.demo.GAINS_PRM_SET")[1][0]
    assert [n for n, _ in gains.members] == ["kp", "ki", "mode", "label"]
    with pytest.raises(KeyError):
        dictionary("MiniDep.demo.NOPE")


@pytest.mark.parametrize("line, message", [
    ("R00:00:00 CdhCore.cmdDisp.CMD_NO_OP 5", "t.seq:2: CdhCore.cmdDisp.CMD_NO_OP takes 0 argument(s), got 1"),
    ("R00:00:00 MiniDep.demo.CONFIGURE 7 2.5 \"x\" Demo.Mode.NOMINAL",
     "t.seq:2: MiniDep.demo.CONFIGURE: argument 4: write the bare constant name (NOMINAL), not Demo.Mode.NOMINAL"),
    ("R00:00:00 MiniDep.demo.CONFIGURE 7 2.5 \"x\" BAD",
     "t.seq:2: MiniDep.demo.CONFIGURE: argument 4: Demo.Mode has no constant BAD; use one of SAFE, NOMINAL, SCIENCE"),
    ("R00:00:00 MiniDep.demo.CONFIGURE 2.5 2.5 \"x\" SAFE",
     "t.seq:2: MiniDep.demo.CONFIGURE: argument 1 expects an integer (U32), got float 2.5"),
    ("R00:00:00 MiniDep.demo.CONFIGURE 7 2.5 hello SAFE",
     "t.seq:2: MiniDep.demo.CONFIGURE: argument 3 expects a quoted string, got name hello"),
    ("R00:00:00 MiniDep.demo.THRESHOLD_PRM_SET 0x100000000",
     "t.seq:2: MiniDep.demo.THRESHOLD_PRM_SET: argument 1: U32 value 4294967296 is out of range"),
    ("R00:00:00 MiniDep.demo.SET_VEC [1, 2]",
     "t.seq:2: MiniDep.demo.SET_VEC: argument 1 expects 3 element(s) (Demo.Vec3), got 2"),
    ("R00:00:00 MiniDep.demo.GAINS_PRM_SET {kp: 1, ki: 2, mode: SAFE, label: \"a\", kd: 3}",
     "t.seq:2: MiniDep.demo.GAINS_PRM_SET: argument 1: Demo.Gains has no member(s) kd"),
    ("R00:00:00 MiniDep.demo.GAINS_PRM_SET {kp: 1, ki: 2, mode: SAFE}",
     "t.seq:2: MiniDep.demo.GAINS_PRM_SET: argument 1: missing member(s) label of Demo.Gains"),
    ("R00:00:00 CdhCore.cmdDisp.NOPE", "t.seq:2: 'CdhCore.cmdDisp.NOPE' is not a command of the dictionary"),
    ("00:00:01 CdhCore.cmdDisp.CMD_NO_OP", "t.seq:2: expected a time tag at the start of"),
    ("R24:00:00 CdhCore.cmdDisp.CMD_NO_OP", "t.seq:2: invalid time tag 'R24:00:00'"),
    ("R2025-001T00:00:00 CdhCore.cmdDisp.CMD_NO_OP",
     "t.seq:2: invalid time tag 'R2025-001T00:00:00': R needs a relative time HH:MM:SS[.ffffff], got "
     "'2025-001T00:00:00'; use A for an absolute time"),
    ("R00:00:00 MiniDep.demo.SET_VEC [1, 2,", "t.seq:2: the line ends where a value was expected"),
    ("R00:00:00 MiniDep.demo.SET_VEC [1 2 3]", "t.seq:2: expected ',' or ']' in an array, got '2'"),
    ("R00:00:00 CdhCore.cmdDisp.CMD_NO_OP_STRING \"" + "x" * 41 + "\"",
     "t.seq:2: CdhCore.cmdDisp.CMD_NO_OP_STRING: argument 1: string of 41 bytes exceeds its bound of 40 bytes"),
    ("R00:00:00 CdhCore.cmdDisp.CMD_NO_OP_STRING \"x\" @", "t.seq:2: unexpected text '@'"),
])
def test_text_errors_name_file_line_and_problem(dictionary, line, message):
    """SEQ-TXT-6: each text error names file, line and what is wrong."""
    text = "; header comment\n" + line + "\nR00:00:00 CdhCore.cmdDisp.CMD_NO_OP\n"
    with pytest.raises(SequenceTextError, match="^" + re.escape(message)) as err:
        compile_text(text, dictionary, "t.seq")
    assert (err.value.path, err.value.line) == ("t.seq", 2)


def test_continued_line_reports_its_first_line(dictionary):
    """SEQ-TXT-7: in a continued line, type errors name the line the command starts on and
    syntax errors the physical line of the offending text."""
    text = "R00:00:00 MiniDep.demo.CONFIGURE 7 \\\n 2.5 \"x\" \\\n BAD\n"
    with pytest.raises(SequenceTextError, match="^t.seq:1: MiniDep.demo.CONFIGURE: argument 4"):
        compile_text(text, dictionary, "t.seq")
    with pytest.raises(SequenceTextError, match="^t.seq:3: unexpected text '@'"):
        compile_text("R00:00:00 MiniDep.demo.CONFIGURE 7 \\\n 2.5 \"x\" \\\n @\n", dictionary, "t.seq")


def test_read_sequence_picks_format_by_suffix(tmp_path, dictionary):
    """SEQ-FILE-1: *.seq is compiled as text (needs a lookup); anything else is binary."""
    text = tmp_path / "a.seq"
    text.write_text((DATA / "example.seq").read_text())
    binary = tmp_path / "a.bin"
    binary.write_bytes((DATA / "example.bin").read_bytes())
    assert read_sequence(text, lookup=dictionary) == read_sequence(binary)
    with pytest.raises(SequenceTextError, match=r"a.seq:0: text sequences need a command dictionary"):
        read_sequence(text)
    with pytest.raises(FileNotFoundError):
        read_sequence(tmp_path / "missing.bin")
