"""FPP telemetry packets (docs/fpp.md "Telemetry packets"): a topology's `telemetry packets … omit`
configures its Svc.TlmPacketizer instance as the YAML's `telemetry_packets` does, and the exporter
writes a YAML packet set as FPP. The packetized proves_ref exists in both forms
(`deployments/proves_ref/topology_packetized.yaml`, `deployments/proves_ref/fpp_packetized/`)."""

from __future__ import annotations

import json
import pathlib

import pytest

pytest.importorskip("fpp", reason="FPP models need fprime-fpp-python (the test extra installs it)")

from fprime_lite.deploy.dictionary import build_dictionary  # noqa: E402
from fprime_lite.deploy.fpp import export  # noqa: E402
from fprime_lite.deploy.fpp.dict_diff import dictionary_differences  # noqa: E402
from fprime_lite.deploy.fpp.loader import FppError, load_fpp  # noqa: E402
from fprime_lite.deploy.fpp.run import write_topology_yaml  # noqa: E402
from fprime_lite.deploy.topology_loader import load_topology  # noqa: E402
from fprime_lite.tools.cli import main  # noqa: E402

#: each loads or flies proves_ref (about a second or two each on 2 cores); CI runs them
pytestmark = pytest.mark.slow

ROOT = pathlib.Path(__file__).resolve().parents[3]
YAML = ROOT / "deployments" / "proves_ref" / "topology_packetized.yaml"
FOLDER = ROOT / "deployments" / "proves_ref" / "fpp_packetized"
FILES = [str(FOLDER / "components.fpp"), str(FOLDER / "topology.fpp")]


def test_fpp_and_yaml_packetized_proves_ref_give_the_same_dictionary():
    """FPPK-001: the FPP form's dictionary (`fprime-lite dict`) is the YAML form's, packet set
    included entry for entry and in the same order (packets by id, omitted channels by id)."""
    from_fpp = build_dictionary(load_fpp(FILES))  # type: ignore[arg-type]
    from_yaml = build_dictionary(load_topology(YAML).topology)
    assert dictionary_differences(from_fpp, from_yaml, left="fpp", right="yaml") == []
    assert from_fpp["telemetryPacketSets"] == from_yaml["telemetryPacketSets"]
    (packet_set,) = from_fpp["telemetryPacketSets"]
    assert packet_set["name"] == "ReferenceDeploymentPackets" and len(packet_set["members"]) == 20
    assert len(packet_set["omitted"]) == 41


def _fly(topology: pathlib.Path, out: pathlib.Path, seconds: float) -> list[bytes]:
    """Fly ``topology`` for ``seconds``; return every packet CdhCore.tlmSend sent, in order."""
    from fprime_lite.tools.api import load
    from fprime_lite.tools.runner import run_deployment

    loaded = load(str(topology))
    port = loaded.topology.instance("CdhCore.tlmSend").component.output_port("PktSend")
    sent: list[bytes] = []
    if port.is_connected(0):
        downstream = port.calls[0]

        def tap(data, context=0):
            sent.append(bytes(data))
            return downstream(data, context)
        port.calls[0] = tap
    else:
        port.connect_callable(0, lambda data, context=0: sent.append(bytes(data)), "test")
    run_deployment(loaded, out, duration_s=seconds, plots=False, quiet=True)
    return sent


def _without_wall_clock(packets: list[bytes]) -> list[bytes]:
    """``packets`` with the slots of the rate groups' RgMaxTime (wall-clock microseconds, different
    in every run) zeroed; the layout is the YAML packet set's."""
    from fprime_lite.svc.tlm_packetizer import packet_list

    topology = load_topology(YAML).topology
    (packet_set,) = topology.telemetry_packet_sets
    specs, _ = packet_list(topology, packet_set)
    wall = {i for name, i in _channel_ids(topology).items() if name.endswith(".RgMaxTime")}
    masks: dict[int, list[tuple[int, int]]] = {}
    for spec in specs:
        offset = 4 + 11  # descriptor, packet id, time
        for chan_id, size in spec.channels:
            if chan_id in wall:
                masks.setdefault(spec.id, []).append((offset, size))
            offset += size
    out = []
    for packet in packets:
        data = bytearray(packet)
        for offset, size in masks.get(int.from_bytes(packet[2:4], "big"), ()):
            data[offset:offset + size] = bytes(size)
        out.append(bytes(data))
    return out


def _channel_ids(topology) -> dict[str, int]:
    return {f"{inst.qualified_name}.{ch.name}": inst.component.base_id + ch.local_id
            for inst in topology.instances.values() for ch in inst.component.spec.channels}


def test_fpp_and_yaml_packetized_proves_ref_send_the_same_packets(tmp_path):
    """FPPK-002: flown for 6 s, the FPP form's packetizer sends the YAML form's packets byte for
    byte (ids, slots, time stamps; the rate groups' wall-clock RgMaxTime slots, which differ between
    any two runs, left out), at the send level the run file gives (1: the Beacon, Health and
    HealthWarnings packets), and the runs write the same dictionary, events and channels (but for
    RgMaxTime)."""
    flown = write_topology_yaml(FILES, tmp_path)
    from_fpp = _fly(flown, tmp_path / "fpp", 6.0)
    from_yaml = _fly(YAML, tmp_path / "yaml", 6.0)
    assert len(from_yaml) > 5
    assert [len(p) for p in from_fpp] == [len(p) for p in from_yaml]
    assert _without_wall_clock(from_fpp) == _without_wall_clock(from_yaml)
    assert sum(p != q for p, q in zip(from_fpp, _without_wall_clock(from_fpp), strict=True)) > 0  # masks something
    assert {int.from_bytes(p[:2], "big") for p in from_fpp} == {4}  # FW_PACKET_PACKETIZED_TLM
    sent_ids = {int.from_bytes(p[2:4], "big") for p in from_fpp}
    assert {1, 2} <= sent_ids <= {1, 2, 3}  # the group-1 packets, no other
    for name in ("dictionary.json", "events.log"):
        assert (tmp_path / "fpp" / name).read_bytes() == (tmp_path / "yaml" / name).read_bytes(), name

    def channels(folder: str) -> list[str]:
        return [line for line in (tmp_path / folder / "channels.csv").read_text().splitlines()
                if "RgMaxTime" not in line]
    assert channels("fpp") == channels("yaml")


def _mutated(tmp_path: pathlib.Path, old: str, new: str, run_change: tuple[str, str] | None = None) -> list[str]:
    """A copy of fpp_packetized/ (with the files its run.yaml names) in which ``old`` of topology.fpp
    is ``new`` and the run file has ``run_change``."""
    text = pathlib.Path(FILES[1]).read_text()
    assert old in text
    folder = tmp_path / "fpp_packetized"
    folder.mkdir()
    for name in ("flight_params.dat", "startup.seq"):
        (tmp_path / name).write_bytes((FOLDER.parent / name).read_bytes())
    (folder / "components.fpp").write_text(pathlib.Path(FILES[0]).read_text())
    (folder / "topology.fpp").write_text(text.replace(old, new, 1))
    run_text = (FOLDER / "run.yaml").read_text()
    if run_change is not None:
        assert run_change[0] in run_text
        run_text = run_text.replace(*run_change)
    (folder / "run.yaml").write_text(run_text)
    return [str(folder / "components.fpp"), str(folder / "topology.fpp")]


def _line_of(path: str, text: str) -> int:
    return next(n for n, line in enumerate(pathlib.Path(path).read_text().splitlines(), 1) if text in line)


@pytest.mark.parametrize("old, new, marker, expected", [
    ("        startupManager.BootCount\n", "        startupManager.BootCounts\n", "startupManager.BootCounts",
     "BootCounts is not a telemetry channel of component StartupManager"),
    ("packet Imu id 7 group 2", "packet Imu id 1 group 2", "packet Imu id 1", "duplicate identifier value"),
    ("        startupManager.BootCount\n", "        startupManager.BootCount\n        startupManager.BootCount\n",
     "packet Beacon id", "packet Beacon lists ReferenceDeployment.startupManager.BootCount more than once"),
])
def test_a_packet_set_that_cannot_fly_is_refused_with_its_fpp_line(tmp_path, capsys, old, new, marker, expected):
    """FPPK-003: an unknown channel and a packet id used twice (F´'s analyser finds them), and a
    channel listed twice in one packet (which the analyser takes and a packetizer cannot lay out),
    are refused with the FPP file:line, exit 2, before anything flies."""
    files = _mutated(tmp_path, old, new)
    out = tmp_path / "out"
    assert main(["run", *files, "--duration", "1", "--out", str(out), "--no-plots", "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert expected in err
    assert f"topology.fpp:{_line_of(files[1], marker)}:" in err
    assert "Traceback" not in err and not out.exists()


_NO_PACKETIZER = """module Dep {
  instance counter: Components.Counter base id 0x1000
  deployment topology Dep {
    instance counter
    telemetry packets DepPackets {
      packet Counts id 1 group 1 {
        counter.Count
      }
    } omit {
    }
  }
}
"""


def test_a_packet_set_without_a_packetizer_instance_is_refused_with_its_fpp_line(tmp_path, capsys, monkeypatch):
    """FPPK-006: `run` of a topology whose packet set no TlmPacketizer instance could fly is refused
    with the packet set's FPP file:line, exit 2; `dict` of it still works (fpp-to-dict's dictionary
    of such a model lists the set too)."""
    assert main(["new", "component", "Counter", "--fpp", "--dir", str(tmp_path)]) == 0
    monkeypatch.syspath_prepend(str(tmp_path))
    (tmp_path / "dep.fpp").write_text(_NO_PACKETIZER)
    (tmp_path / "run.yaml").write_text("{}\n")
    files = [str(tmp_path / "counter.fpp"), str(tmp_path / "dep.fpp")]
    capsys.readouterr()
    out = tmp_path / "out"
    assert main(["run", *files, "--run-file", str(tmp_path / "run.yaml"), "--duration", "1", "--out", str(out),
                 "--no-plots", "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert (f"dep.fpp:{_line_of(files[1], 'telemetry packets')}:5: telemetry packet set DepPackets has no "
            f"Svc.TlmPacketizer instance to fly it") in err
    assert "Traceback" not in err and not out.exists()
    assert main(["dict", *files, "-o", str(tmp_path / "dictionary.json")]) == 0
    assert json.loads((tmp_path / "dictionary.json").read_text())["telemetryPacketSets"][0]["name"] == "DepPackets"


@pytest.mark.parametrize("run_change, expected", [
    (("  start_level: 1\n", "  start_level: 2\n"), {"start_level": 2}),
    (("  start_level: 1\n", ""), {"start_level": 0}),
    (("  instance: CdhCore.tlmSend\n", "  instance: CdhCore.cmdDisp\n"),
     "telemetry_packets.instance: 'CdhCore.cmdDisp' is not a TlmPacketizer instance of the FPP topology "
     "(it has CdhCore.tlmSend)"),
    (("  name: ReferenceDeploymentPackets\n", "  name: Other\n"),
     "telemetry_packets.name: no packet set 'Other' in the FPP topology (it declares ReferenceDeploymentPackets)"),
    (("  start_level: 1\n", "  start_level: 1\n  packets: {}\n"), "telemetry_packets.packets: unknown key"),
])
def test_the_run_file_says_which_set_flies_where_and_from_which_level(tmp_path, run_change, expected):
    """FPPK-004: the run file's telemetry_packets names the set, the instance and the start level
    (default 0, as the YAML's); the packets come from the FPP only; a wrong name is refused."""
    files = _mutated(tmp_path, "deployment topology", "deployment topology", run_change)
    if isinstance(expected, str):
        with pytest.raises(FppError, match=".*" + expected.replace("(", r"\(").replace(")", r"\)")):
            write_topology_yaml(files, tmp_path)
        return
    section = json.loads(write_topology_yaml(files, tmp_path).read_text())["telemetry_packets"]
    assert section["start_level"] == expected["start_level"] and section["instance"] == "CdhCore.tlmSend"
    assert [p["id"] for p in section["packets"].values()] == sorted(p["id"] for p in section["packets"].values())
    loaded = load_topology(write_topology_yaml(files, tmp_path))
    assert loaded.topology.instance("CdhCore.tlmSend").component.start_level == expected["start_level"]


def test_the_exporter_writes_the_packet_set_as_fpp_and_it_reads_back(tmp_path, monkeypatch):
    """FPPK-005: `python -m fprime_lite.deploy.fpp.export deployments/proves_ref/topology_packetized.yaml`
    writes fpp_packetized/ (the committed files are what it writes now), its topology holds the
    packet set as `telemetry packets … omit`, and loading that FPP gives back the YAML's packet set."""
    assert export.default_out_dir(YAML) == FOLDER
    monkeypatch.chdir(ROOT)  # the files name their source as the command named it
    texts = export.deployment_texts("deployments/proves_ref/topology_packetized.yaml")
    for name, text in texts.items():
        assert (FOLDER / name).read_text() == text, f"{FOLDER / name} is stale: regenerate it"
        (tmp_path / name).write_text(text)
    text = texts["topology.fpp"]
    assert "deployment topology ReferenceDeployment {" in text
    assert "telemetry packets ReferenceDeploymentPackets {" in text and "} omit {" in text
    back = load_fpp([tmp_path / "components.fpp", tmp_path / "topology.fpp"]).telemetry_packet_sets
    assert back == load_topology(YAML).topology.telemetry_packet_sets


def test_fpp_to_dict_lists_the_same_packet_set(tmp_path):
    """FPPK-007: F´'s fpp-to-dict 3.0, run on fpp_packetized/ (spelled `topology`, which it parses,
    where fpp-python needs `deployment topology`), lists the packet set fprime-lite's dictionary has:
    the same packets (ids, groups, channels in order) and omitted channels. Its packets and omitted
    channels come in another order (neither order means anything: the GDS finds a packet by id);
    the rest differs only by the definitions docs/fpp.md "Differences from fpp-to-dict" names."""
    import shutil
    import subprocess

    tool = shutil.which("fpp-to-dict")
    if tool is None:
        pytest.skip("fpp-to-dict is not installed (pip install 'fprime-lite[fpp]' installs fprime-fpp-to-dict)")
    topology = tmp_path / "topology.fpp"
    text = pathlib.Path(FILES[1]).read_text()
    assert "deployment topology ReferenceDeployment {" in text
    topology.write_text(text.replace("deployment topology ReferenceDeployment {", "topology ReferenceDeployment {"))
    imports = ",".join(str(p) for p in export.framework_files())
    subprocess.run([tool, "-i", imports, FILES[0], str(topology), "-d", str(tmp_path)], check=True,
                   capture_output=True, timeout=120)
    (theirs_path,) = tmp_path.glob("*Dictionary.json")
    theirs = json.loads(theirs_path.read_text())
    ours = build_dictionary(load_topology(YAML).topology)
    (their_set,), (our_set,) = theirs["telemetryPacketSets"], ours["telemetryPacketSets"]
    assert sorted(their_set["members"], key=lambda p: p["id"]) == our_set["members"]
    assert sorted(their_set["omitted"]) == sorted(our_set["omitted"]) and their_set["name"] == our_set["name"]
    theirs["telemetryPacketSets"] = ours["telemetryPacketSets"]  # compared above
    assert dictionary_differences(ours, theirs) == [
        "constants ComCfg.SpacecraftId: only in ours", "constants ComCfg.TmFrameFixedSize: only in ours",
        "typeDefinitions ComCfg.Apid: only in ours", "typeDefinitions FwIdType: only in ours",
        "typeDefinitions FwPrmIdType: only in ours"]
