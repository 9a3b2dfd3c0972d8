"""Version: start-up reporting, the VERSION and ENABLE commands, custom versions through the ports,
truncation to F´'s string bounds, and the dictionary as fprime-gds sees it."""

import importlib.metadata
import struct

import pytest

from fprime_lite import CmdResponse, Severity, String
from fprime_lite.svc import version as version_module
from fprime_lite.svc.version import (
    CustomVersionDb,
    Version,
    VersionEnabled,
    VersionEnum,
    VersionStatus,
    VersionType,
)

LIBS = [f"lib{i}@{i}.0" for i in range(12)]  # more libraries than channels, as F´'s own test


@pytest.fixture
def h(fprime_harness):
    return fprime_harness(Version("version", "fw-1.2", "proj-3.4", LIBS, base_id=0x3000))


def custom(slot, value, status=VersionStatus.OK):
    return CustomVersionDb(VersionEnum(slot), value, status)


def set_versions(h, slots, status=VersionStatus.OK):
    for slot in slots:
        assert h.invoke("setVersion", VersionEnum(slot), f"ver_{slot}", status) == (f"ver_{slot}", status)


# --- start-up -------------------------------------------------------------------------------------

def test_startup_reports_framework_project_and_libraries_once(h):
    h.load_parameters()
    h.load_parameters()  # a second load does not report again
    names = [e.name for e in h.events]
    assert names == ["FrameworkVersion", "ProjectVersion"] + ["LibraryVersions"] * 12
    h.assert_event("FrameworkVersion", 0, "fw-1.2")
    h.assert_event("ProjectVersion", 0, "proj-3.4")
    assert h.events_named("LibraryVersions") == [(lib,) for lib in LIBS]
    assert all(e.severity == Severity.ACTIVITY_LO for e in h.events)
    assert h.tlm_values("FrameworkVersion") == ["fw-1.2"]
    assert h.tlm_values("ProjectVersion") == ["proj-3.4"]
    for i in range(10):
        assert h.tlm_values(f"LibraryVersion{i + 1:02d}") == [LIBS[i]]
    assert len(h.telemetry) == 12  # libraries 11 and 12 have events only
    assert h.component.started


def test_startup_does_not_report_custom_versions(h):
    set_versions(h, [1])
    h.clear_history()
    h.load_parameters()
    h.assert_no_event("CustomVersions")
    h.assert_tlm_count("CustomVersion02", 0)


def test_startup_report_can_be_turned_off(fprime_harness):
    h = fprime_harness(Version("version", "fw", "proj", report_at_startup=False))
    h.load_parameters()
    assert h.events == [] and h.telemetry == []
    h.component.start()  # F´'s start(): reports on demand
    assert [e.name for e in h.events] == ["FrameworkVersion", "ProjectVersion"]


def test_startup_with_no_libraries_reports_framework_and_project_only(fprime_harness):
    h = fprime_harness(Version("version", "fw", "proj"))
    h.load_parameters()
    assert [(e.name, e.args) for e in h.events] == [("FrameworkVersion", ("fw",)), ("ProjectVersion", ("proj",))]
    assert [(t.name, t.value) for t in h.telemetry] == [("FrameworkVersion", "fw"), ("ProjectVersion", "proj")]


def test_text_events_carry_fprime_formats(h):
    h.load_parameters()
    set_versions(h, [2])
    texts = [t.text for t in h.text_events]
    assert texts[0] == "(version) FrameworkVersion: Framework Version: [fw-1.2]"
    assert texts[1] == "(version) ProjectVersion: Project Version: [proj-3.4]"
    assert texts[2] == "(version) LibraryVersions: Libary Versions: [lib0@0.0]"  # F´'s spelling
    assert texts[-1] == "(version) CustomVersions: Custom Versions: [PROJECT_VERSION_02] [ver_2]"


# --- VERSION command ------------------------------------------------------------------------------

def test_version_framework_reports_framework_only(h):
    h.send_command("VERSION", VersionType.FRAMEWORK, cmd_seq=9)
    h.assert_cmd_response(0, "VERSION", CmdResponse.OK, cmd_seq=9)
    assert [(e.name, e.args) for e in h.events] == [("FrameworkVersion", ("fw-1.2",))]
    assert [(t.name, t.value) for t in h.telemetry] == [("FrameworkVersion", "fw-1.2")]


def test_version_project_reports_project_only(h):
    h.send_command("VERSION", VersionType.PROJECT)
    h.assert_cmd_response(0, "VERSION", CmdResponse.OK)
    assert [(e.name, e.args) for e in h.events] == [("ProjectVersion", ("proj-3.4",))]
    assert [(t.name, t.value) for t in h.telemetry] == [("ProjectVersion", "proj-3.4")]


def test_version_library_reports_every_library_and_ten_channels(h):
    h.send_command("VERSION", VersionType.LIBRARY)
    h.assert_cmd_response(0, "VERSION", CmdResponse.OK)
    assert h.events_named("LibraryVersions") == [(lib,) for lib in LIBS]
    assert [(t.name, t.value) for t in h.telemetry] == [
        (f"LibraryVersion{i + 1:02d}", LIBS[i]) for i in range(10)]


def test_version_custom_reports_only_the_slots_set(h):
    set_versions(h, [2, 9])
    set_versions(h, [3, 6], VersionStatus.FAILURE)
    h.clear_history()
    h.send_command("VERSION", VersionType.CUSTOM)
    h.assert_cmd_response(0, "VERSION", CmdResponse.OK)
    assert h.events_named("CustomVersions") == [
        (VersionEnum(s), f"ver_{s}") for s in (2, 3, 6, 9)]
    h.assert_tlm("CustomVersion03", 0, custom(2, "ver_2"))
    h.assert_tlm("CustomVersion04", 0, custom(3, "ver_3", VersionStatus.FAILURE))
    h.assert_tlm("CustomVersion07", 0, custom(6, "ver_6", VersionStatus.FAILURE))
    h.assert_tlm("CustomVersion10", 0, custom(9, "ver_9"))
    h.assert_tlm_size(4)


def test_version_custom_with_nothing_set_reports_nothing(h):
    h.send_command("VERSION", VersionType.CUSTOM)
    h.assert_cmd_response(0, "VERSION", CmdResponse.OK)
    assert h.events == [] and h.telemetry == []


def test_version_all_reports_project_framework_libraries_then_custom(h):
    set_versions(h, [0])
    h.clear_history()
    h.send_command("VERSION", VersionType.ALL)
    h.assert_cmd_response(0, "VERSION", CmdResponse.OK)
    names = [e.name for e in h.events]
    assert names == ["ProjectVersion", "FrameworkVersion"] + ["LibraryVersions"] * 12 + ["CustomVersions"]
    assert [t.name for t in h.telemetry] == (["ProjectVersion", "FrameworkVersion"]
                                             + [f"LibraryVersion{i:02d}" for i in range(1, 11)]
                                             + ["CustomVersion01"])


def test_version_with_unknown_type_answers_format_error(h):
    h.send_raw_command(h.component.opcode("VERSION"), struct.pack(">i", 5), cmd_seq=4)
    h.assert_cmd_response(0, "VERSION", CmdResponse.FORMAT_ERROR, cmd_seq=4)
    assert h.events == [] and h.telemetry == []


# --- ENABLE command and verbosity -----------------------------------------------------------------

def test_enable_disabled_keeps_custom_events_and_stops_custom_telemetry(h):
    h.send_command("ENABLE", VersionEnabled.DISABLED, cmd_seq=9)
    h.assert_cmd_response(0, "ENABLE", CmdResponse.OK, cmd_seq=9)
    assert h.component.verbose is False
    set_versions(h, range(10))
    assert h.events_named("CustomVersions") == [(VersionEnum(s), f"ver_{s}") for s in range(10)]
    assert h.telemetry == []
    h.clear_history()
    h.send_command("VERSION", VersionType.CUSTOM)
    h.assert_event_count("CustomVersions", 10)
    assert h.telemetry == []


def test_enable_enabled_writes_custom_telemetry_with_each_set(h):
    h.send_command("ENABLE", VersionEnabled.DISABLED)
    h.send_command("ENABLE", VersionEnabled.ENABLED)
    assert [r.response for r in h.cmd_responses] == [CmdResponse.OK, CmdResponse.OK]
    assert h.component.verbose is True
    set_versions(h, range(10))
    h.assert_event_count("CustomVersions", 10)
    for s in range(10):
        h.assert_tlm(f"CustomVersion{s + 1:02d}", 0, custom(s, f"ver_{s}"))
    h.assert_tlm_size(10)


def test_enable_does_not_touch_framework_project_or_library_reports(h):
    h.send_command("ENABLE", VersionEnabled.DISABLED)
    h.send_command("VERSION", VersionType.ALL)
    h.assert_tlm_count("FrameworkVersion", 1)
    h.assert_tlm_count("ProjectVersion", 1)
    h.assert_tlm_count("LibraryVersion01", 1)


def test_startup_verbose_option_and_config_set_verbosity(fprime_harness):
    h = fprime_harness(Version("version", "fw", "proj", startup_verbose=False))
    assert h.component.verbose is False
    set_versions(h, [4])
    assert h.telemetry == []
    h.component.config(True)  # F´'s config(true)
    set_versions(h, [4])
    h.assert_tlm("CustomVersion05", 0, custom(4, "ver_4"))


# --- custom versions through the ports ------------------------------------------------------------

def test_get_version_returns_what_set_version_stored(h):
    set_versions(h, [2, 9])
    set_versions(h, [3, 6], VersionStatus.FAILURE)
    assert h.invoke("getVersion", VersionEnum.PROJECT_VERSION_02, "", VersionStatus.OK) == \
        ("ver_2", VersionStatus.OK)
    assert h.invoke("getVersion", VersionEnum.PROJECT_VERSION_03, "", VersionStatus.OK) == \
        ("ver_3", VersionStatus.FAILURE)
    assert h.invoke("getVersion", 6, "ignored", VersionStatus.OK) == ("ver_6", VersionStatus.FAILURE)
    assert h.invoke("getVersion", "PROJECT_VERSION_09", "", VersionStatus.FAILURE) == ("ver_9", VersionStatus.OK)


def test_get_version_of_an_unset_slot_is_no_ver_failure(h):
    assert h.invoke("getVersion", VersionEnum.PROJECT_VERSION_05, "", VersionStatus.OK) == \
        ("no_ver", VersionStatus.FAILURE)
    assert h.events == [] and h.telemetry == []


def test_set_version_rewrites_a_slot_and_reports_each_write(h):
    h.invoke("setVersion", VersionEnum.PROJECT_VERSION_01, "a", VersionStatus.FAILURE)
    h.invoke("setVersion", VersionEnum.PROJECT_VERSION_01, "b", VersionStatus.OK)
    assert h.events_named("CustomVersions") == [(VersionEnum.PROJECT_VERSION_01, "a"),
                                                (VersionEnum.PROJECT_VERSION_01, "b")]
    assert h.tlm_values("CustomVersion02") == [custom(1, "a", VersionStatus.FAILURE), custom(1, "b")]
    assert h.invoke("getVersion", 1, "", VersionStatus.OK) == ("b", VersionStatus.OK)
    h.clear_history()
    h.send_command("VERSION", VersionType.CUSTOM)
    assert h.events_named("CustomVersions") == [(VersionEnum.PROJECT_VERSION_01, "b")]


def test_bad_port_arguments_are_refused_without_raising(h):
    comp = h.component
    assert h.invoke("setVersion", 10, "x", VersionStatus.OK) == ("x", VersionStatus.FAILURE)
    assert h.invoke("setVersion", "NOT_A_SLOT", "x", VersionStatus.OK) == ("x", VersionStatus.FAILURE)
    assert h.invoke("setVersion", True, "x", VersionStatus.OK) == ("x", VersionStatus.FAILURE)
    assert h.invoke("setVersion", 1, b"bytes", VersionStatus.OK) == (b"bytes", VersionStatus.FAILURE)
    assert h.invoke("setVersion", 1, "x", 7) == ("x", VersionStatus.FAILURE)
    assert h.invoke("getVersion", -1, "", VersionStatus.OK) == ("", VersionStatus.FAILURE)
    assert comp.rejected_calls == 6
    assert h.events == [] and h.telemetry == []
    assert h.invoke("getVersion", 1, "", VersionStatus.OK) == ("no_ver", VersionStatus.FAILURE)


# --- string bounds --------------------------------------------------------------------------------

def test_long_strings_are_truncated_to_fprime_bounds(fprime_harness):
    long = "v" * 100
    h = fprime_harness(Version("version", long, "p" * 41, ["l" * 64]))
    h.load_parameters()
    h.assert_event("FrameworkVersion", 0, "v" * 40)
    h.assert_tlm("FrameworkVersion", 0, "v" * 40)
    h.assert_event("ProjectVersion", 0, "p" * 40)
    h.assert_tlm("ProjectVersion", 0, "p" * 40)
    h.assert_event("LibraryVersions", 0, "l" * 40)
    h.assert_tlm("LibraryVersion01", 0, "l" * 40)
    assert h.invoke("setVersion", 0, long, VersionStatus.OK) == (long, VersionStatus.OK)
    h.assert_event("CustomVersions", 0, VersionEnum.PROJECT_VERSION_00, "v" * 40)  # event: 40 bytes
    h.assert_tlm("CustomVersion01", 0, custom(0, "v" * 80))                       # struct: 80 bytes
    assert h.invoke("getVersion", 0, "", VersionStatus.OK) == ("v" * 80, VersionStatus.OK)
    assert h.component.framework_version == long  # kept whole; cut only where F´ bounds it


def test_truncation_keeps_whole_utf8_characters(fprime_harness):
    h = fprime_harness(Version("version", "a" + "é" * 20, "\u00e9" * 30))  # 41 and 60 bytes
    h.load_parameters()
    h.assert_event("FrameworkVersion", 0, "a" + "é" * 19)  # 39 bytes: the 2-byte é would not fit
    h.assert_event("ProjectVersion", 0, "é" * 20)          # exactly 40 bytes
    h.invoke("setVersion", 3, "\ud800bad", VersionStatus.OK)  # a lone surrogate is not UTF-8
    h.assert_event("CustomVersions", 0, VersionEnum.PROJECT_VERSION_03, "?bad")


# --- construction ---------------------------------------------------------------------------------

def test_framework_version_defaults_to_the_installed_package():
    comp = Version()
    assert comp.name == "version"
    assert comp.framework_version == importlib.metadata.version("fprime-lite")
    assert comp.project_version == "unknown"
    assert comp.library_versions == ()
    assert comp.verbose is True


def test_framework_version_is_unknown_when_the_package_is_not_installed(monkeypatch):
    def missing(name):
        raise importlib.metadata.PackageNotFoundError(name)

    monkeypatch.setattr(version_module.importlib.metadata, "version", missing)
    assert Version().framework_version == "unknown"


def test_constructor_refuses_non_text_versions():
    with pytest.raises(TypeError, match="project_version"):
        Version("version", "fw", 3)
    with pytest.raises(TypeError, match="library_versions"):
        Version("version", "fw", "p", "just-one-string")


def test_declarations_match_fprime_v4():
    comp = Version("version", "fw", base_id=0x1000)
    spec = comp.spec
    assert [(c.name, c.opcode, c.kind, [(n, t.name) for n, t in c.args]) for c in spec.commands] == [
        ("ENABLE", 0, "guarded", [("enable", "Svc.VersionEnabled")]),
        ("VERSION", 1, "guarded", [("version_type", "Svc.VersionType")])]
    assert [(e.name, e.local_id, e.severity, e.format, [(n, t.name if t.kind != "string" else t.size)
                                                        for n, t in e.args]) for e in spec.own_events] == [
        ("FrameworkVersion", 0, Severity.ACTIVITY_LO, "Framework Version: [{}]", [("version", 40)]),
        ("ProjectVersion", 1, Severity.ACTIVITY_LO, "Project Version: [{}]", [("version", 40)]),
        ("LibraryVersions", 2, Severity.ACTIVITY_LO, "Libary Versions: [{}]", [("version", 40)]),
        ("CustomVersions", 3, Severity.ACTIVITY_LO, "Custom Versions: [{}] [{}]",
         [("version_enum", "Svc.VersionCfg.VersionEnum"), ("version_value", 40)])]
    channels = [(c.name, c.local_id, c.type) for c in spec.own_channels]
    assert channels[:2] == [("FrameworkVersion", 0, String(40)), ("ProjectVersion", 1, String(40))]
    assert channels[2:12] == [(f"CustomVersion{i:02d}", i + 1, CustomVersionDb.__fprime_type__)
                              for i in range(1, 11)]
    assert channels[12:] == [(f"LibraryVersion{i:02d}", i + 11, String(40)) for i in range(1, 11)]
    assert all(c.update == "always" for c in spec.own_channels)
    assert comp.opcode("VERSION") == 0x1001 and comp.channel_id("LibraryVersion10") == 0x1015
    assert comp.event_id("CustomVersions") == 0x1003 and comp.channel_id("ProjectVersion") == 0x1001
    db = CustomVersionDb.__fprime_type__
    assert db.name == "Svc.CustomVersionDb"
    assert [(n, t.name if t.kind != "string" else t.size) for n, t in db.members] == [
        ("version_enum", "Svc.VersionCfg.VersionEnum"), ("version_value", 80),
        ("version_status", "Svc.VersionStatus")]
    assert VersionEnum.__fprime_rep__.name == "U32"
    assert [(m.name, int(m)) for m in VersionEnum] == [(f"PROJECT_VERSION_{i:02d}", i) for i in range(10)]
    assert [(m.name, int(m)) for m in VersionType] == [("PROJECT", 0), ("FRAMEWORK", 1), ("LIBRARY", 2),
                                                       ("CUSTOM", 3), ("ALL", 4)]
    assert [(m.name, int(m)) for m in VersionStatus] == [("OK", 0), ("FAILURE", 1)]
    assert [(m.name, int(m)) for m in VersionEnabled] == [("DISABLED", 0), ("ENABLED", 1)]
    assert sorted(comp.input_ports) == ["cmdIn", "getVersion", "setVersion"]
    assert comp.input_port("getVersion").decl.kind == "guarded"
    assert comp.input_port("setVersion").port_type.name == "Svc.Version"
    # The attribute of the shared name is the event; the channel is reached through .channels.
    assert comp.FrameworkVersion is comp.events["FrameworkVersion"]
    assert comp.channels["FrameworkVersion"].id == 0x1000


# --- the ground's view ----------------------------------------------------------------------------

def test_fprime_gds_encodes_the_commands_and_decodes_the_reports(tmp_path):
    pytest.importorskip("fprime_gds", reason="fprime-gds 4.4.1 is a test dependency: pip install -e .[test]")
    from fprime_gds.common.data_types.cmd_data import CmdData
    from fprime_gds.common.decoders.ch_decoder import ChDecoder
    from fprime_gds.common.decoders.event_decoder import EventDecoder
    from fprime_gds.common.encoders.cmd_encoder import CmdEncoder
    from fprime_gds.common.models.dictionaries import Dictionaries

    from fprime_lite.deploy.dictionary import write_dictionary
    from fprime_lite.wire.packets import decode_command
    from fprime_lite.model.time import TIME, Time, TimeBase
    from fprime_lite.deploy.topology import Topology

    comp = Version("version", "fw-9", "proj-9", ["libA@1"], base_id=0x01000400)
    topology = Topology("VersionTest")
    topology.add("CdhCore", comp)
    write_dictionary(topology, tmp_path / "dict.json")
    gds = Dictionaries.load_dictionaries_into_config(str(tmp_path / "dict.json"))

    time = Time(TimeBase.TB_WORKSTATION_TIME, 0, 100, 5)
    events, channels, answers = [], [], []
    comp.output_port("timeCaller").connect_callable(0, lambda: time, "clock")
    comp.output_port("logOut").connect_callable(
        0, lambda i, t, sev, args: events.append(struct.pack(">I", i) + TIME.serialize(t) + args), "ground")
    comp.output_port("tlmOut").connect_callable(
        0, lambda i, t, value: channels.append(struct.pack(">I", i) + TIME.serialize(t) + value), "ground")
    comp.output_port("cmdResponseOut").connect_callable(0, lambda *a: answers.append(a), "ground")

    def uplink(name, *args):
        packet = CmdEncoder().encode_api(CmdData(list(args), gds.command_name[name]))[8:]
        opcode, data = decode_command(packet)
        comp.input_port("cmdIn").entries[0](opcode, 1, data)

    uplink("CdhCore.version.ENABLE", "ENABLED")
    comp.input_port("setVersion").entries[0](VersionEnum.PROJECT_VERSION_04, "fpga-7", VersionStatus.OK)
    uplink("CdhCore.version.VERSION", "ALL")
    assert [a[2] for a in answers] == [CmdResponse.OK, CmdResponse.OK]

    decoded = [EventDecoder(gds.event_id).decode_api(p)[0] for p in events]
    assert [(e.get_template().get_full_name(), [a.val for a in e.get_args()]) for e in decoded] == [
        ("CdhCore.version.CustomVersions", ["PROJECT_VERSION_04", "fpga-7"]),
        ("CdhCore.version.ProjectVersion", ["proj-9"]),
        ("CdhCore.version.FrameworkVersion", ["fw-9"]),
        ("CdhCore.version.LibraryVersions", ["libA@1"]),
        ("CdhCore.version.CustomVersions", ["PROJECT_VERSION_04", "fpga-7"])]
    values = [(c.get_template().get_full_name(), c.get_val_obj().val)
              for p in channels for c in ChDecoder(gds.channel_id).decode_api(p)]
    db = {"version_enum": "PROJECT_VERSION_04", "version_value": "fpga-7", "version_status": "OK"}
    assert values == [("CdhCore.version.CustomVersion05", db), ("CdhCore.version.ProjectVersion", "proj-9"),
                      ("CdhCore.version.FrameworkVersion", "fw-9"), ("CdhCore.version.LibraryVersion01", "libA@1"),
                      ("CdhCore.version.CustomVersion05", db)]
