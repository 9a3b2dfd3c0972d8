"""Commands: dispatch, F´ response codes, deferred responses, registration."""

import struct

import pytest

from fprime_lite import (F32, I32, U8, CmdResponse, FwAssertionError, FwEnum, PassiveComponent,
                         String, guarded_command, sync_command)


class Mode(FwEnum, namespace="Test", rep=U8):
    OFF = 0
    ON = 1


class Commanded(PassiveComponent):
    def __init__(self, name, **kw):
        super().__init__(name, **kw)
        self.calls = []
        self.pending = None

    @sync_command()
    def NO_ARGS(self):
        self.calls.append("NO_ARGS")

    @sync_command()
    def TEST(self, a: I32, b: F32, c: U8):
        self.calls.append(("TEST", a, b, c))
        return CmdResponse.OK

    @sync_command()
    def SET_MODE(self, mode: Mode):
        self.calls.append(("SET_MODE", mode))
        return CmdResponse.VALIDATION_ERROR if mode == Mode.OFF else None

    @sync_command()
    def SAY(self, text: String(8)):
        self.calls.append(("SAY", text))

    @sync_command()
    def EXPLODE(self):
        raise RuntimeError("boom")

    @sync_command()
    def LATER(self):
        self.pending = self.defer_command_response()

    @guarded_command()
    def GUARDED(self):
        self.calls.append(("GUARDED", self._lock._is_owned()))

    @sync_command()
    def WRONG_RETURN(self):
        return 5


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(Commanded("cmds", base_id=0x500))


def test_send_command_by_name_with_typed_args(h):
    h.send_command("TEST", -5, 1.5, 200, cmd_seq=11)
    assert h.component.calls == [("TEST", -5, 1.5, 200)]
    h.assert_cmd_response(0, "TEST", CmdResponse.OK, cmd_seq=11)


def test_handler_returning_none_answers_ok(h):
    h.sendCmd_NO_ARGS(0, 0)
    h.assert_cmd_response(0, "NO_ARGS", CmdResponse.OK)


def test_handler_chooses_its_response(h):
    h.send_command("SET_MODE", Mode.OFF)
    h.assert_cmd_response(0, "SET_MODE", CmdResponse.VALIDATION_ERROR)


def test_raw_bytes_command(h):
    args = struct.pack(">ifB", 7, 2.0, 3)
    h.send_raw_command(h.component.opcode("TEST"), args, cmd_seq=2)
    assert h.component.calls == [("TEST", 7, 2.0, 3)]
    h.assert_cmd_response(0, h.component.opcode("TEST"), CmdResponse.OK, cmd_seq=2)


def test_unknown_opcode_answers_invalid_opcode(h):
    h.send_raw_command(0x5FF, b"", cmd_seq=9)
    assert h.cmd_responses[0].response == CmdResponse.INVALID_OPCODE
    assert h.cmd_responses[0].opcode == 0x5FF


@pytest.mark.parametrize("args, why", [
    (struct.pack(">if", 7, 2.0), "short arguments"),
    (struct.pack(">ifBB", 7, 2.0, 3, 4), "leftover byte"),
    (b"", "no arguments"),
])
def test_undeserializable_arguments_answer_format_error_before_handler(h, args, why):
    h.send_raw_command(h.component.opcode("TEST"), args)
    assert h.component.calls == [], why
    h.assert_cmd_response(0, "TEST", CmdResponse.FORMAT_ERROR)


def test_bad_enum_value_and_bad_string_are_format_errors(h):
    h.send_raw_command(h.component.opcode("SET_MODE"), b"\x07")
    h.send_raw_command(h.component.opcode("SAY"), b"\x00\x09" + b"x" * 9)  # over the 8-byte bound
    h.send_raw_command(h.component.opcode("SAY"), b"\x00\x02\xff\xfe")  # not UTF-8
    assert h.component.calls == []
    assert [r.response for r in h.cmd_responses] == [CmdResponse.FORMAT_ERROR] * 3


def test_handler_exception_answers_execution_error_and_counts(h):
    h.send_command("EXPLODE")
    h.assert_cmd_response(0, "EXPLODE", CmdResponse.EXECUTION_ERROR)
    assert h.component.handler_faults == 1


def test_deferred_response_is_sent_later(h):
    h.send_command("LATER", cmd_seq=4)
    h.assert_cmd_response_size(0)
    h.component.command_response(h.component.pending, CmdResponse.BUSY)
    h.assert_cmd_response(0, "LATER", CmdResponse.BUSY, cmd_seq=4)


def test_defer_outside_handler_is_an_assertion(h):
    with pytest.raises(FwAssertionError, match="outside a command handler"):
        h.component.defer_command_response()


def test_guarded_command_holds_the_lock(h):
    h.send_command("GUARDED")
    assert h.component.calls == [("GUARDED", True)]


def test_handler_returning_garbage_is_an_assertion(h):
    with pytest.raises(FwAssertionError, match=r"WRONG_RETURN returned 5; return a CmdResponse or None"):
        h.send_command("WRONG_RETURN")


def test_register_commands_sends_every_global_opcode(h):
    h.component.register_commands()
    assert h.registered_opcodes == [0x500 + c.opcode for c in h.component.spec.commands]
    assert len(h.registered_opcodes) == 8


def test_response_codes_match_fprime():
    assert {r.name: int(r) for r in CmdResponse} == {
        "OK": 0, "INVALID_OPCODE": 1, "VALIDATION_ERROR": 2, "FORMAT_ERROR": 3, "EXECUTION_ERROR": 4,
        "BUSY": 5, "CLEARED": 6}


def test_unknown_command_name_lists_commands(h):
    with pytest.raises(KeyError, match=r"has no command 'NOPE'; it has NO_ARGS, TEST"):
        h.send_command("NOPE")
