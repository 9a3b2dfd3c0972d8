"""Parameters: PRM_SET/PRM_SAVE, validity, loading and the hooks."""

import struct

import pytest

from fprime_lite import F64, U8, CmdResponse, FwEnum, Param, ParamValid, PassiveComponent, Struct


class Axis(FwEnum, namespace="Test", rep=U8):
    X = 0
    Y = 1


class Interval(Struct, namespace="Test"):
    seconds: U8
    useconds: U8


class Tunable(PassiveComponent):
    GAIN = Param(F64, default=3.0, id=39)
    AXIS = Param(Axis, default=Axis.Y)
    WINDOW = Param(Interval, default=Interval(0, 20))
    NO_DEFAULT = Param(F64)

    def __init__(self, name, **kw):
        super().__init__(name, **kw)
        self.updated = []
        self.loaded_values = None

    def parameter_updated(self, local_id):
        self.updated.append(local_id)

    def parameters_loaded(self):
        self.loaded_values = (self.GAIN.value, self.AXIS.value, self.WINDOW.value)


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(Tunable("tun", base_id=0x1000))


def test_values_before_loading_are_defaults_uninit(h):
    assert h.component.GAIN.value == 3.0
    assert h.component.GAIN.validity == ParamValid.UNINIT
    assert h.component.GAIN.id == 0x1000 + 39


def test_prm_set_updates_value_validity_and_calls_hook(h):
    h.send_raw_command(h.component.opcode("GAIN_PRM_SET"), struct.pack(">d", 4.5), cmd_seq=1)
    h.assert_cmd_response(0, "GAIN_PRM_SET", CmdResponse.OK, cmd_seq=1)
    assert h.component.GAIN.value == 4.5
    assert h.component.GAIN.validity == ParamValid.VALID
    assert h.component.updated == [39]


def test_prm_set_with_bad_bytes_is_validation_error_and_changes_nothing(h):
    h.send_raw_command(h.component.opcode("GAIN_PRM_SET"), b"\x01\x02")
    h.send_raw_command(h.component.opcode("AXIS_PRM_SET"), b"\x09")
    h.send_raw_command(h.component.opcode("GAIN_PRM_SET"), struct.pack(">d", 1.0) + b"\x00")
    assert [r.response for r in h.cmd_responses] == [CmdResponse.VALIDATION_ERROR] * 3
    assert h.component.GAIN.value == 3.0 and h.component.AXIS.value == Axis.Y
    assert h.component.updated == []


def test_prm_save_pushes_serialized_value(h):
    h.send_raw_command(h.component.opcode("WINDOW_PRM_SET"), bytes([1, 2]))
    h.paramSave_WINDOW(0, 5)
    h.assert_cmd_response(1, "WINDOW_PRM_SAVE", CmdResponse.OK, cmd_seq=5)
    assert h.saved_params == [("WINDOW", h.component.param_id("WINDOW"), Interval(1, 2))]


def test_prm_save_without_prmdb_is_execution_error():
    comp = Tunable("alone")
    responses = []
    comp.output_port("cmdResponseOut").connect_callable(0, lambda *a: responses.append(a), "test")
    comp.input_port("cmdIn").entries[0](comp.opcode("GAIN_PRM_SAVE"), 3, b"")
    assert responses == [(comp.opcode("GAIN_PRM_SAVE"), 3, CmdResponse.EXECUTION_ERROR)]


def test_load_parameters_takes_valid_values_and_falls_back_to_defaults(h):
    h.paramSet_GAIN(6.0, ParamValid.VALID)
    h.param_set("AXIS", Axis.X, ParamValid.INVALID)
    h.load_parameters()
    c = h.component
    assert (c.GAIN.value, c.GAIN.validity) == (6.0, ParamValid.VALID)
    assert (c.AXIS.value, c.AXIS.validity) == (Axis.Y, ParamValid.DEFAULT)
    assert (c.WINDOW.value, c.WINDOW.validity) == (Interval(0, 20), ParamValid.DEFAULT)
    assert c.NO_DEFAULT.validity == ParamValid.INVALID
    assert c.loaded_values == (6.0, Axis.Y, Interval(0, 20)), "hook runs after every parameter is loaded"


def test_undeserializable_stored_value_falls_back_to_default():
    comp = Tunable("t")
    comp.output_port("prmGetOut").connect_callable(0, lambda pid: (ParamValid.VALID, b"\x00"), "test")
    comp.load_parameters()
    assert comp.GAIN.value == 3.0 and comp.GAIN.validity == ParamValid.DEFAULT


def test_param_send_uses_prm_set(h):
    h.param_set("GAIN", 9.0)
    h.paramSend_GAIN(0, 8)
    assert h.component.GAIN.value == 9.0
    h.assert_cmd_response(0, "GAIN_PRM_SET", CmdResponse.OK, cmd_seq=8)


def test_param_validity_codes_match_fprime():
    assert [(v.name, int(v)) for v in ParamValid] == [
        ("UNINIT", 0), ("VALID", 1), ("INVALID", 2), ("DEFAULT", 3)]


def test_param_units_are_documentation_text_like_a_channels():
    """UNITS-001: `Param(..., units=)` keeps the text (frames included); it must be a non-empty text
    without ']' (the same rule and wording as a channel's units); None means none declared."""
    from fprime_lite import Channel
    from fprime_lite.model.errors import DeclarationError

    assert Param(F64, default=1.0, units="N·m, body frame").units == "N·m, body frame"
    assert Param(F64, default=1.0).units is None
    for bad in ("", "  ", "A [peak]", 3, b"V"):
        with pytest.raises(DeclarationError, match=r"param units must be a non-empty text without '\]'"):
            Param(F64, default=1.0, units=bad)
        with pytest.raises(DeclarationError, match=r"channel units must be a non-empty text without '\]'"):
            Channel(F64, units=bad)


def test_param_units_change_no_id_value_or_command(fprime_harness):
    """UNITS-002: units are documentation only: the same component with and without them has the
    same parameter ids, opcodes, defaults and serialized values."""

    class Plain(PassiveComponent):
        GAIN = Param(F64, default=3.0, id=39)
        RATE = Param(F64, default=0.5)

    class WithUnits(PassiveComponent):
        GAIN = Param(F64, default=3.0, id=39, units="A·m²·s/G")
        RATE = Param(F64, default=0.5, units="deg/s")

    def shape(cls):
        comp = cls("c", base_id=0x100)
        return ([(p.name, p.local_id, p.default, p.type.serialize(p.default)) for p in comp.spec.params],
                [(c.name, c.opcode) for c in comp.spec.commands])

    assert shape(Plain) == shape(WithUnits)
    assert [p.units for p in WithUnits("c", base_id=0).spec.params] == ["A·m²·s/G", "deg/s"]
