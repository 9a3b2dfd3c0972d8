"""Svc.CmdSequencer: runs fprime-seqgen files command by command, with F´'s events and channels.

Time is the harness's; nothing sleeps. The reference sequence is compiled by the real
fprime-seqgen in a temporary directory; the expected command packets are the bytes listed in
``tests/data/gds/gds_notes.md`` (c).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import zlib
from pathlib import Path

import pytest

from fprime_lite import CmdResponse, Time, TimeBase
from fprime_lite.wire.seqfile import (CommandDictionary, Descriptor, FileReadStage, Record, Sequence,
                                 encode_binary)
from fprime_lite.svc.cmd_sequencer import BlockState, CmdSequencer, SeqMode

DATA = Path(__file__).resolve().parents[2] / "data" / "gds"
DICT = DATA / "minimal_dictionary.json"
SEQGEN = Path(sys.executable).parent / "fprime-seqgen"
BASE = 0x600
T0 = 1735689600  # 2025-001T00:00:00 UTC, 10 s before example.seq's absolute command

#: The command packets of example.seq, in order (from fprime-seqgen's example.bin).
EXAMPLE_PACKETS = [bytes.fromhex(h) for h in (
    "0000" "00000100",
    "0000" "00001000" "00000007" "40200000" "0005" "68656c6c6f" "00000001",
    "0000" "00000101" "0003" "616273",
    "0000" "00001001" "3f800000" "40000000" "40400000",
    "0000" "00001002" "3fc00000" "3e800000" "00000002" "0001" "67",
    "0000" "00001004" "0000002a",
)]


@pytest.fixture(scope="module")
def seqgen_bin(tmp_path_factory) -> Path:
    """example.seq compiled by the real fprime-seqgen."""
    if not SEQGEN.exists():
        pytest.skip(f"fprime-seqgen not installed next to {sys.executable}")
    tmp = tmp_path_factory.mktemp("seqgen")
    shutil.copy(DATA / "example.seq", tmp / "example.seq")
    done = subprocess.run([str(SEQGEN), "example.seq", "example.bin", "--dictionary", str(DICT)],
                          cwd=tmp, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stdout + done.stderr
    return tmp / "example.bin"


def make(fprime_harness, tmp_path, **kwargs):
    seq = CmdSequencer("cmdSeq", base_id=BASE, base_dir=tmp_path, **kwargs)
    h = fprime_harness(seq, test_time=Time(TimeBase.TB_WORKSTATION_TIME, 0, T0, 0))
    return seq, h


def packets(h) -> list[bytes]:
    return [call.args[0] for call in h.from_port("comCmdOut")]


def respond(h, response=CmdResponse.OK, cmd_seq=0):
    """The dispatcher answers the last command sent."""
    opcode = int.from_bytes(packets(h)[-1][2:6], "big")
    h.invoke("cmdResponseIn", opcode, cmd_seq, response)
    h.dispatch_all()


def tick(h, seconds=0, useconds=0):
    h.advance_time(seconds, useconds)
    h.invoke("schedIn", 0)
    h.dispatch_all()


def command(h, name, *args):
    h.send_command(name, *args)
    h.dispatch_all()


def write_seq(tmp_path, name, records, time_base=0xFFFF) -> str:
    (tmp_path / name).write_bytes(encode_binary(Sequence(records, time_base)))
    return name


def noop(descriptor=Descriptor.RELATIVE, s=0, us=0, opcode=0x100):
    return Record.for_command(descriptor, s, us, opcode)


# --- the reference sequence -------------------------------------------------------------------

def test_runs_fprime_seqgen_sequence_with_timing(fprime_harness, tmp_path, seqgen_bin):
    """CS-1: a sequence built by fprime-seqgen sends its exact packets in order, each at its time."""
    shutil.copy(seqgen_bin, tmp_path / "example.bin")
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_RUN", "example.bin", BlockState.NO_BLOCK)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.OK)
    h.assert_event("CS_SequenceLoaded", 0, "example.bin")
    assert packets(h) == EXAMPLE_PACKETS[:1]            # R00:00:00: sent at once
    assert h.from_port("comCmdOut")[0].args[1] == 0      # Com context 0, as F´

    respond(h)                                           # t0: NO_OP done -> CONFIGURE due t0+1.5
    tick(h, 1, 499_999)
    assert len(packets(h)) == 1
    tick(h, 0, 1)
    assert packets(h) == EXAMPLE_PACKETS[:2]

    respond(h)                                           # absolute 2025-001T00:00:10
    tick(h, 8, 499_999)                                  # T0+9.999999
    assert len(packets(h)) == 2
    tick(h, 0, 1)                                        # T0+10
    assert packets(h) == EXAMPLE_PACKETS[:3]

    respond(h)                                           # R0 SET_VEC at once
    assert packets(h) == EXAMPLE_PACKETS[:4]
    respond(h)                                           # R2 GAINS_PRM_SET
    tick(h, 1, 999_999)
    assert len(packets(h)) == 4
    tick(h, 0, 1)
    assert packets(h) == EXAMPLE_PACKETS[:5]
    respond(h)                                           # R0 THRESHOLD at once
    assert packets(h) == EXAMPLE_PACKETS
    respond(h)

    assert not seq.running
    h.assert_event_count("CS_CommandComplete", 6)
    h.assert_event("CS_CommandComplete", 5, "example.bin", 5, 0x1004)
    h.assert_event("CS_SequenceComplete", 0, "example.bin")
    assert h.tlm_values("CS_CommandsExecuted") == [1, 2, 3, 4, 5, 6]
    assert h.tlm_values("CS_SequencesCompleted") == [1]
    assert h.tlm_values("CS_LoadCommands") == [1]
    h.assert_cmd_response_size(1)


def test_text_sequence_runs_like_its_binary(fprime_harness, tmp_path):
    """CS-2: a .seq file is compiled with the command lookup and sends the same packets."""
    shutil.copy(DATA / "example.seq", tmp_path / "example.seq")
    seq, h = make(fprime_harness, tmp_path, command_lookup=CommandDictionary.from_json(DICT))
    command(h, "CS_RUN", "example.seq", BlockState.NO_BLOCK)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.OK)
    for _ in range(6):
        respond(h)
        tick(h, 10)
    assert packets(h) == EXAMPLE_PACKETS
    h.assert_event_count("CS_SequenceComplete", 1)


def test_text_sequence_error_event(fprime_harness, tmp_path):
    """CS-3: a text error logs CS_TextFileInvalid with the line and reason; nothing runs."""
    (tmp_path / "bad.seq").write_text("R00:00:00 CdhCore.cmdDisp.CMD_NO_OP\nR00:00:01 Nope.CMD\n")
    seq, h = make(fprime_harness, tmp_path, command_lookup=CommandDictionary.from_json(DICT))
    command(h, "CS_RUN", "bad.seq", BlockState.NO_BLOCK)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    [(name, line, reason)] = h.events_named("CS_TextFileInvalid")
    assert (name, line) == ("bad.seq", 2)
    assert reason.startswith("'Nope.CMD' is not a command of the dictionary")
    assert packets(h) == []
    assert h.tlm_values("CS_Errors") == [1]


@pytest.mark.parametrize("text", ["", "\n\n", "; only a comment\n   \n"], ids=["empty", "blank", "comments"])
def test_text_sequence_without_commands_is_no_records_not_a_fault(fprime_harness, tmp_path, text):
    """CS-3b: a .seq file with no command (empty, blank lines, comments) is what fprime-seqgen makes a file of
    no records from: CS_NoRecords (WARNING_LO, not counted as an error), CS_RUN answers EXECUTION_ERROR,
    nothing is sent and no handler fault is reported (it was an IndexError inside the run handler)."""
    (tmp_path / "empty.seq").write_text(text)
    seq, h = make(fprime_harness, tmp_path, command_lookup=CommandDictionary.from_json(DICT))
    command(h, "CS_RUN", "empty.seq", BlockState.NO_BLOCK)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    h.assert_event("CS_NoRecords", 0, "empty.seq")
    h.assert_event_count("HandlerFault", 0)
    assert packets(h) == [] and not seq.running
    assert h.tlm_values("CS_Errors") == []


# --- file errors ------------------------------------------------------------------------------

def test_bad_crc_runs_nothing(fprime_harness, tmp_path):
    """CS-4: a corrupt file logs CS_FileCrcFailure, counts an error and sends nothing."""
    data = bytearray((DATA / "example.bin").read_bytes())
    data[40] ^= 0xFF
    (tmp_path / "bad.bin").write_bytes(bytes(data))
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_RUN", "bad.bin", BlockState.BLOCK)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    [(name, stored, computed)] = h.events_named("CS_FileCrcFailure")
    assert (name, stored) == ("bad.bin", 0x6EB20CC6) and computed != stored
    assert packets(h) == []
    assert h.tlm_values("CS_Errors") == [1]
    h.assert_no_event("CS_SequenceLoaded")
    tick(h, 100)
    assert packets(h) == []


def test_truncated_file(fprime_harness, tmp_path):
    """CS-5: a truncated file is CS_FileInvalid at READ_SEQ_DATA_SIZE with the bytes read."""
    (tmp_path / "short.bin").write_bytes((DATA / "example.bin").read_bytes()[:60])
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_RUN", "short.bin", BlockState.NO_BLOCK)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    h.assert_event("CS_FileInvalid", 0, "short.bin", FileReadStage.READ_SEQ_DATA_SIZE, 49)


def test_bad_descriptor(fprime_harness, tmp_path):
    """CS-6: a record with descriptor 7 is CS_RecordInvalid (record 1, FW_DESERIALIZE_FORMAT_ERROR)."""
    name = write_seq(tmp_path, "desc.bin", [noop(), noop()])
    data = bytearray((tmp_path / name).read_bytes()[:-4])
    data[11 + 19] = 7
    (tmp_path / name).write_bytes(bytes(data) + zlib.crc32(bytes(data)).to_bytes(4, "big"))
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_RUN", name, BlockState.NO_BLOCK)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    h.assert_event("CS_RecordInvalid", 0, name, 1, 4)
    assert packets(h) == []


def test_file_not_found(fprime_harness, tmp_path):
    """CS-7: a missing file is CS_FileNotFound."""
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_RUN", "missing.bin", BlockState.NO_BLOCK)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    h.assert_event("CS_FileNotFound", 0, "missing.bin")
    assert h.tlm_values("CS_Errors") == [1]


def test_time_base_mismatch(fprime_harness, tmp_path):
    """CS-8: a file built with -t 1 does not run on TB_WORKSTATION_TIME (2)."""
    name = write_seq(tmp_path, "tb.bin", [noop()], time_base=1)
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_RUN", name, BlockState.NO_BLOCK)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    h.assert_event("CS_TimeBaseMismatch", 0, name, 2, 1)


def test_long_file_name_is_cut_to_60_bytes_in_events(fprime_harness, tmp_path):
    """CS-9: event file names are F´ LogStringArgs of 60 bytes."""
    name = "d" * 70 + ".bin"
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_RUN", name, BlockState.NO_BLOCK)
    h.assert_event("CS_FileNotFound", 0, "d" * 60)


# --- aborts, cancel, modes --------------------------------------------------------------------

def test_failed_command_aborts(fprime_harness, tmp_path):
    """CS-10: a failed response logs CS_CommandError, ends the sequence and fails a BLOCK run."""
    name = write_seq(tmp_path, "three.bin", [noop(), noop(opcode=0x1004), noop()])
    seq, h = make(fprime_harness, tmp_path)
    h.set_port_handler("seqDone", lambda *args: None)
    command(h, "CS_RUN", name, BlockState.BLOCK)
    h.assert_cmd_response_size(0)                     # BLOCK: no answer yet
    respond(h)
    respond(h, CmdResponse.EXECUTION_ERROR, cmd_seq=9)
    h.assert_event("CS_CommandError", 0, name, 1, 0x1004, int(CmdResponse.EXECUTION_ERROR))
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    assert h.from_port("seqDone")[-1].args == (0, 0, CmdResponse.EXECUTION_ERROR)
    assert not seq.running
    tick(h, 10)
    assert len(packets(h)) == 2                        # the third command never goes out
    assert h.tlm_values("CS_Errors") == [1]
    h.assert_no_event("CS_SequenceComplete")
    h.invoke("cmdResponseIn", 0x100, 0, CmdResponse.OK)  # a late answer is unexpected
    h.dispatch_all()
    h.assert_event("CS_UnexpectedCompletion", 0, 0x100)


def test_block_wait_answers_ok_when_done(fprime_harness, tmp_path):
    """CS-11: CS_RUN with BLOCK answers OK only when the last command completed."""
    name = write_seq(tmp_path, "two.bin", [noop(), noop(s=3)])
    seq, h = make(fprime_harness, tmp_path)
    h.send_command("CS_RUN", name, BlockState.BLOCK, cmd_seq=42)
    h.dispatch_all()
    respond(h)
    tick(h, 3)
    h.assert_cmd_response_size(0)
    respond(h)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.OK, cmd_seq=42)


def test_cancel(fprime_harness, tmp_path):
    """CS-12: CS_CANCEL stops a waiting sequence; nothing more is sent; cancel when idle is OK."""
    name = write_seq(tmp_path, "wait.bin", [noop(), noop(s=5)])
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_RUN", name, BlockState.NO_BLOCK)
    respond(h)                                    # second command waits 5 s
    command(h, "CS_CANCEL")
    h.assert_cmd_response(1, "CS_CANCEL", CmdResponse.OK)
    h.assert_event("CS_SequenceCanceled", 0, name)
    assert h.tlm_values("CS_CancelCommands") == [1]
    tick(h, 10)
    assert len(packets(h)) == 1
    assert not seq.running and seq.loaded         # rewound, still loaded: CS_START reruns it
    command(h, "CS_CANCEL")
    h.assert_event_count("CS_NoSequenceActive", 1)
    h.assert_cmd_response(2, "CS_CANCEL", CmdResponse.OK)


def test_manual_mode_steps(fprime_harness, tmp_path):
    """CS-13: in MANUAL mode CS_RUN only loads, CS_START sends the first command, CS_STEP the next."""
    name = write_seq(tmp_path, "steps.bin", [noop(), noop(opcode=0x101), noop(opcode=0x102)])
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_MANUAL")
    h.assert_event("CS_ModeSwitched", 0, SeqMode.STEP)
    command(h, "CS_RUN", name, BlockState.NO_BLOCK)
    assert packets(h) == []
    command(h, "CS_STEP")                              # not started yet
    h.assert_cmd_response(2, "CS_STEP", CmdResponse.EXECUTION_ERROR)
    command(h, "CS_START")
    h.assert_cmd_response(3, "CS_START", CmdResponse.OK)
    h.assert_event("CS_CmdStarted", 0, name)
    assert [p[2:6].hex() for p in packets(h)] == ["00000100"]
    command(h, "CS_STEP")                              # the first has not completed
    h.assert_cmd_response(4, "CS_STEP", CmdResponse.EXECUTION_ERROR)
    respond(h)
    tick(h, 60)
    assert len(packets(h)) == 1                        # manual: no step on its own
    command(h, "CS_AUTO")                              # cannot switch while running
    h.assert_cmd_response(5, "CS_AUTO", CmdResponse.EXECUTION_ERROR)
    command(h, "CS_STEP")
    h.assert_cmd_response(6, "CS_STEP", CmdResponse.OK)
    h.assert_event("CS_CmdStepped", 0, name, 1)
    respond(h)
    command(h, "CS_STEP")
    respond(h)
    assert [p[2:6].hex() for p in packets(h)] == ["00000100", "00000101", "00000102"]
    h.assert_event("CS_SequenceComplete", 0, name)
    command(h, "CS_AUTO")
    h.assert_event("CS_ModeSwitched", 1, SeqMode.AUTO)


def test_join_wait(fprime_harness, tmp_path):
    """CS-14: CS_JOIN_WAIT answers when the running sequence ends (at once when none runs)."""
    name = write_seq(tmp_path, "j.bin", [noop(), noop()])
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_JOIN_WAIT")
    h.assert_cmd_response(0, "CS_JOIN_WAIT", CmdResponse.OK)
    command(h, "CS_RUN", name, BlockState.NO_BLOCK)
    command(h, "CS_JOIN_WAIT")
    h.assert_event("CS_JoinWaiting", 0, name, 0, 0x100)
    h.assert_cmd_response_size(2)
    command(h, "CS_RUN", name, BlockState.NO_BLOCK)     # busy: refused, still waiting
    h.assert_cmd_response(2, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    h.assert_event_count("CS_JoinWaitingNotComplete", 1)
    respond(h)
    respond(h)
    h.assert_cmd_response(3, "CS_JOIN_WAIT", CmdResponse.OK)


def test_command_timeout(fprime_harness, tmp_path):
    """CS-15: with timeout_s, an unanswered command times out the sequence on schedIn."""
    name = write_seq(tmp_path, "t.bin", [noop(), noop()])
    seq, h = make(fprime_harness, tmp_path, timeout_s=5)
    command(h, "CS_RUN", name, BlockState.BLOCK)
    tick(h, 4, 999_999)
    h.assert_no_event("CS_SequenceTimeout")
    tick(h, 0, 1)
    h.assert_event("CS_SequenceTimeout", 0, name, 0)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.EXECUTION_ERROR)
    assert not seq.running


def test_validate(fprime_harness, tmp_path):
    """CS-16: CS_VALIDATE loads, reports CS_SequenceValid, and leaves nothing loaded."""
    name = write_seq(tmp_path, "v.bin", [noop()])
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_VALIDATE", name)
    h.assert_cmd_response(0, "CS_VALIDATE", CmdResponse.OK)
    h.assert_event("CS_SequenceValid", 0, name)
    assert not seq.loaded and packets(h) == []
    command(h, "CS_START")
    h.assert_cmd_response(1, "CS_START", CmdResponse.EXECUTION_ERROR)


def test_seq_run_port(fprime_harness, tmp_path):
    """CS-17: seqRunIn runs a file and reports the end on seqDone; busy requests fail."""
    name = write_seq(tmp_path, "p.bin", [noop()])
    seq, h = make(fprime_harness, tmp_path)
    h.set_port_handler("seqDone", lambda *args: None)
    h.set_port_handler("seqStartOut", lambda *args: None)
    h.invoke("seqRunIn", name)
    h.dispatch_all()
    h.assert_event("CS_PortSequenceStarted", 0, name)
    assert h.from_port("seqStartOut")[0].args == (name,)
    h.invoke("seqRunIn", name)
    h.dispatch_all()
    assert h.from_port("seqDone")[-1].args == (0, 0, CmdResponse.EXECUTION_ERROR)
    respond(h)
    assert h.from_port("seqDone")[-1].args == (0, 0, CmdResponse.OK)


def test_end_of_sequence_record_and_absolute_time(fprime_harness, tmp_path):
    """CS-18: a past absolute time sends at once; descriptor 2 ends the sequence."""
    name = write_seq(tmp_path, "e.bin", [noop(Descriptor.ABSOLUTE, s=T0 - 5), Record(Descriptor.END_OF_SEQUENCE),
                                          noop()])
    seq, h = make(fprime_harness, tmp_path)
    command(h, "CS_RUN", name, BlockState.BLOCK)
    assert len(packets(h)) == 1
    respond(h)
    h.assert_event("CS_SequenceComplete", 0, name)
    h.assert_cmd_response(0, "CS_RUN", CmdResponse.OK)
    assert len(packets(h)) == 1


def test_ping(fprime_harness, tmp_path):
    """CS-19: pingIn answers on pingOut with the same key."""
    seq, h = make(fprime_harness, tmp_path)
    h.invoke("pingIn", 1234)
    h.dispatch_all()
    h.assert_from_port("pingOut", 0, 1234)


def test_unexpected_completion_when_idle(fprime_harness, tmp_path):
    """CS-20: a response with no sequence running is CS_UnexpectedCompletion."""
    seq, h = make(fprime_harness, tmp_path)
    h.invoke("cmdResponseIn", 0x55, 0, CmdResponse.OK)
    h.dispatch_all()
    h.assert_event("CS_UnexpectedCompletion", 0, 0x55)


def test_ids_match_fprime(fprime_harness, tmp_path):
    """CS-21: opcodes, event ids and channel ids are F´'s (base + local)."""
    seq, h = make(fprime_harness, tmp_path)
    assert [(c.name, c.opcode) for c in seq.spec.commands] == [
        ("CS_RUN", 0), ("CS_VALIDATE", 1), ("CS_CANCEL", 2), ("CS_START", 3), ("CS_STEP", 4),
        ("CS_AUTO", 5), ("CS_MANUAL", 6), ("CS_JOIN_WAIT", 7)]
    assert seq.event_id("CS_NoRecords") == BASE + 25
    assert seq.event_id("CS_FileCrcFailure") == BASE + 7
    assert seq.channel_id("CS_SequencesCompleted") == BASE + 4
