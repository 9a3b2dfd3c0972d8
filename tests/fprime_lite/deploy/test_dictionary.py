"""The JSON dictionary: shape, qualified names, framework types, and loading with fprime-gds 4.4.1."""

import json

import pytest

from fprime_lite import (F64, U8, U32, Array, Channel, Event, FwEnum, Param, PassiveComponent, Severity, String,
                         Struct, Time, sync_command)
from fprime_lite.deploy.dictionary import build_dictionary, write_dictionary
from fprime_lite.deploy.topology import Topology


class Mode(FwEnum, namespace="Demo", rep=U8):
    SAFE = 0
    NOMINAL = 1


class Reading(Struct, namespace="Demo"):
    value: F64
    stamp: Time
    mode: Mode


class Vec3(Array, namespace="Demo", elem=F64, size=3):
    pass


class Widget(PassiveComponent):
    GAIN = Param(F64, default=3.0, id=39)
    LABEL = Param(String(16), default="abc")
    Started = Event(Severity.ACTIVITY_LO, "Started at {.2f} deg/s", w=F64, throttle=1)
    Saw = Event(Severity.ACTIVITY_HI, "saw {} {}", r=Reading, v=Vec3)
    Level = Channel(F64, update="on change", format="{.3f}", high={"yellow": 5.0, "red": 6.0})
    State = Channel(Mode)

    @sync_command()
    def SET_MODE(self, mode: Mode):
        pass

    @sync_command()
    def SAY(self, text: String(40), n: U32):
        pass


class Core(PassiveComponent):
    @sync_command(opcode=0)
    def CMD_NO_OP(self):
        pass


def _demo(component) -> Topology:
    t = Topology("Demo")
    t.add("CdhCore", Core("cmdDisp", base_id=0x100))
    t.add("Demo", component)
    return t


@pytest.fixture
def topology():
    return _demo(Widget("widget", base_id=0x1005A000))


def test_top_level_keys_and_metadata(topology):
    d = build_dictionary(topology)
    assert list(d) == ["metadata", "typeDefinitions", "constants", "commands", "parameters", "events",
                       "telemetryChannels", "records", "containers", "telemetryPacketSets"]
    assert d["metadata"]["deploymentName"] == "Demo.Demo"  # FPP topology Demo in module Demo, as fpp-to-dict
    assert d["metadata"]["dictionarySpecVersion"] == "1.0.0"
    assert {c["qualifiedName"]: c["value"] for c in d["constants"]} == {
        "ComCfg.SpacecraftId": 0x44, "ComCfg.TmFrameFixedSize": 1024,
        "Fw.DpCfg.CONTAINER_USER_DATA_SIZE": 32}  # fpp-to-dict lists it in every dictionary


def test_names_are_module_qualified_with_global_ids(topology):
    d = build_dictionary(topology)
    cmds = {c["name"]: c for c in d["commands"]}
    assert cmds["CdhCore.cmdDisp.CMD_NO_OP"]["opcode"] == 0x100
    assert cmds["Demo.widget.GAIN_PRM_SET"]["commandKind"] == "set"
    assert cmds["Demo.widget.GAIN_PRM_SAVE"]["commandKind"] == "save"
    assert cmds["Demo.widget.SET_MODE"]["formalParams"] == [
        {"name": "mode", "type": {"name": "Demo.Mode", "kind": "qualifiedIdentifier"}, "ref": False}]
    events = {e["name"]: e for e in d["events"]}
    assert events["Demo.widget.Started"] == {
        "name": "Demo.widget.Started", "severity": "ACTIVITY_LO", "id": 0x1005A000,
        "formalParams": [{"name": "w", "type": {"name": "F64", "kind": "float", "size": 64}, "ref": False}],
        "format": "Started at {.2f} deg/s", "throttle": 1}
    chans = {c["name"]: c for c in d["telemetryChannels"]}
    assert chans["Demo.widget.Level"]["telemetryUpdate"] == "on change"
    assert chans["Demo.widget.Level"]["limits"] == {"high": {"yellow": 5.0, "red": 6.0}}
    params = {p["name"]: p for p in d["parameters"]}
    assert params["Demo.widget.GAIN"] == {"name": "Demo.widget.GAIN", "type": {"name": "F64", "kind": "float",
                                                                                "size": 64},
                                          "id": 0x1005A000 + 39, "default": 3.0}


class Wheel(PassiveComponent):
    SPIN_RATE = Param(F64, default=0.5, units="deg/s, body +Z")
    FRICTION = Param(F64, default=1e-6, units="N·m·s/rad")
    LABEL = Param(String(16), default="abc")


@pytest.fixture
def wheel_topology():
    return _demo(Wheel("wheel", base_id=0x2000))


def test_a_parameter_with_units_carries_them_as_its_annotation_after_default(wheel_topology):
    """UNITS-003: `units=` is the parameter's optional F´ `annotation` ("units: …"), written after
    `default` as fpp-to-dict orders the fields; its PRM_SET and PRM_SAVE commands carry the same
    annotation (as fpp-to-dict gives them), a parameter without units has no annotation, and no
    other entry gains one."""
    d = build_dictionary(wheel_topology)
    params = {p["name"]: p for p in d["parameters"]}
    spin = params["Demo.wheel.SPIN_RATE"]
    assert list(spin) == ["name", "type", "id", "default", "annotation"]
    assert spin["annotation"] == "units: deg/s, body +Z"
    assert params["Demo.wheel.FRICTION"]["annotation"] == "units: N·m·s/rad"
    assert list(params["Demo.wheel.LABEL"]) == ["name", "type", "id", "default"]
    commands = {c["name"]: c for c in d["commands"]}
    assert commands["Demo.wheel.SPIN_RATE_PRM_SET"]["annotation"] == "units: deg/s, body +Z"
    assert commands["Demo.wheel.SPIN_RATE_PRM_SAVE"]["annotation"] == "units: deg/s, body +Z"
    assert "annotation" not in commands["Demo.wheel.LABEL_PRM_SET"]
    assert all("annotation" not in entry for key in ("events", "telemetryChannels") for entry in d[key])
    assert all("annotation" not in c for c in d["commands"] if not c["name"].endswith(("_PRM_SET", "_PRM_SAVE")))


def test_fprime_gds_loads_parameters_with_annotations(wheel_topology, tmp_path):
    """UNITS-004: fprime-gds 4.4.1 loads a dictionary whose parameters carry annotations, and its
    parameter templates keep their ids, types and defaults."""
    from fprime_gds.common.loaders.prm_json_loader import PrmJsonLoader
    from fprime_gds.common.models.dictionaries import Dictionaries

    path = tmp_path / "dictionary.json"
    write_dictionary(wheel_topology, path)
    assert "\\u00b7" in path.read_text()  # written as json.dumps writes every dictionary (ASCII escapes)
    Dictionaries().load_dictionaries(str(path), None, None)
    params = PrmJsonLoader(str(path)).get_name_dict(None)
    assert params["Demo.wheel.SPIN_RATE"].get_id() == 0x2000
    assert params["Demo.wheel.SPIN_RATE"].prm_default_val == 0.5
    assert params["Demo.wheel.FRICTION"].get_type_obj().__name__ == "F64Type"


def test_type_definitions_include_used_and_framework_types(topology):
    defs = {t["qualifiedName"]: t for t in build_dictionary(topology)["typeDefinitions"]}
    for name in ("FwOpcodeType", "FwChanIdType", "FwEventIdType", "FwPrmIdType", "FwPacketDescriptorType",
                 "FwSizeStoreType", "FwTimeBaseStoreType", "FwTimeContextStoreType", "TimeBase", "ComCfg.Apid",
                 "Demo.Mode", "Demo.Reading", "Demo.Vec3", "Fw.TimeValue"):
        assert name in defs, name
    assert defs["FwOpcodeType"]["underlyingType"] == {"name": "U32", "kind": "integer", "size": 32, "signed": False}
    assert [c["name"] for c in defs["ComCfg.Apid"]["enumeratedConstants"]][:3] == [
        "FW_PACKET_COMMAND", "FW_PACKET_TELEM", "FW_PACKET_LOG"]
    assert defs["Demo.Reading"]["members"]["stamp"] == {"type": {"name": "Fw.TimeValue",
                                                                 "kind": "qualifiedIdentifier"}, "index": 1}


def test_dictionary_loads_with_fprime_gds_loaders(topology, tmp_path):
    """Compatibility: fprime-gds 4.4.1's own loaders accept the dictionary and see every member."""
    from fprime_gds.common.models.dictionaries import Dictionaries
    from fprime_gds.common.loaders.prm_json_loader import PrmJsonLoader

    path = tmp_path / "dictionary.json"
    written = write_dictionary(topology, path)
    assert json.loads(path.read_text()) == written
    d = Dictionaries()
    d.load_dictionaries(str(path), None, None)
    assert d.command_name["CdhCore.cmdDisp.CMD_NO_OP"].get_id() == 0x100
    assert d.command_name["Demo.widget.SAY"].get_id() == 0x1005A000 + 5
    assert d.event_name["Demo.widget.Saw"].get_id() == 0x1005A001
    assert d.channel_name["Demo.widget.State"].get_id() == 0x1005A001
    params = PrmJsonLoader(str(path)).get_name_dict(None)
    assert params["Demo.widget.LABEL"].get_id() == 0x1005A000 + 40


def test_gds_encodes_our_commands_and_decodes_our_events(topology, tmp_path):
    """Compatibility: a command encoded by fprime-gds reaches our component; our event decodes in the GDS."""
    from fprime_gds.common.data_types.cmd_data import CmdData
    from fprime_gds.common.decoders.event_decoder import EventDecoder
    from fprime_gds.common.encoders.cmd_encoder import CmdEncoder
    from fprime_gds.common.models.dictionaries import Dictionaries

    from fprime_lite.wire.packets import decode_command, encode_event
    from fprime_lite.testing import ComponentHarness

    path = tmp_path / "dictionary.json"
    write_dictionary(topology, path)
    d = Dictionaries.load_dictionaries_into_config(str(path))
    widget = topology.instance("Demo.widget").component
    h = ComponentHarness(widget)
    wire = CmdEncoder().encode_api(CmdData(("hello", "7"), d.command_name["Demo.widget.SAY"]))
    opcode, args = decode_command(wire[8:])  # after the GDS-internal "ZZZZ" + length header
    h.send_raw_command(opcode, args)
    assert h.cmd_responses[0].response.name == "OK"

    widget.Started(12.345)
    e = h.events[0]
    packet = encode_event(e.id, e.time, widget.Started.decl.arg_types[0].serialize(12.345))
    decoded = EventDecoder(d.event_id).decode_api(packet[2:])
    assert decoded[0].template.get_full_name() == "Demo.widget.Started"
    assert decoded[0].get_display_text() == "Started at 12.35 deg/s"
