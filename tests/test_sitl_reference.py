"""The reference deployment as a PROVES software-in-the-loop: flight mode, power and housekeeping
components around the detumble loop, driven from a test ground (commands in, downlinked events out).
"""

import pathlib
import shutil

import pytest

from detumble.components.types import DetumbleMode, SystemMode
from detumble.proves.mode_manager import SafeModeReason
from fprime_lite.deploy.deployment import Deployment, command_lookup
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.ground.downlink import GroundRecorder
from fprime_lite.wire.packets import encode_command

ROOT = pathlib.Path(__file__).parents[1]
TOPOLOGY = ROOT / "deployments" / "proves_ref" / "topology.yaml"
FACES = (0, 1, 2, 3, 5)


class Rig:
    """A started reference deployment with a test ground on a free dispatcher port."""

    def __init__(self, tmp_path, scenario="default", settings=()):
        overrides = {"spacecraft": {"scenario": scenario, "settings": list(settings)}} if settings or \
            scenario != "default" else None
        self.loaded = load_topology(TOPOLOGY, overrides)
        self.params = tmp_path / "flight_params.dat"
        shutil.copy(ROOT / "deployments" / "proves_ref" / "flight_params.dat", self.params)
        self.deployment = Deployment(self.loaded)
        self.topology = self.loaded.topology
        self.craft = self.loaded.resources["spacecraft"]
        self.events = []
        self.responses = []
        recorder = GroundRecorder(self.topology, tmp_path / "ground", on_event=self.events.append)
        recorder.attach(self.topology, self.topology.patterns["event"], self.topology.patterns["telemetry"])
        self.recorder = recorder
        disp = self.topology.instance("CdhCore.cmdDisp").component
        status = disp.output_port("seqCmdStatus")
        used = {c.target_index for c in self.topology.connections if c.target == "CdhCore.cmdDisp"
                and c.target_port == "seqCmdBuff"}
        self.k = next(k for k in range(len(status)) if k not in used and not status.is_connected(k))
        status.connect_callable(self.k, lambda opcode, seq, response: self.responses.append((opcode, response)),
                                "test ground")
        self._disp = disp
        self.lookup = command_lookup(self.topology)
        self.deployment.start(parameter_file=self.params)

    def comp(self, name):
        return self.topology.instance(f"ReferenceDeployment.{name}").component

    def send(self, name, *args):
        opcode, types = self.lookup(name)
        payload = b"".join(t.serialize(v) for t, v in zip(types, args, strict=True))
        self._disp.input_port("seqCmdBuff").entries[self.k](encode_command(opcode, payload), 0)
        self.deployment.scheduler.drain()
        self.deployment.run_for(0.0)

    def run(self, seconds):
        self.deployment.run_for(seconds)

    def named(self, suffix):
        return [e for e in self.events if e.name.endswith("." + suffix)]


def test_faces_powered_at_boot_and_power_visible(tmp_path):
    """SITL-PWR-001: after boot the six face switches are on, the INA219s and powerMonitor read the
    simulated electrical system, and the detumble loop's coil power shows on the system rail."""
    rig = Rig(tmp_path)
    rig.run(20.0)
    for f in range(6):
        assert rig.comp(f"face{f}LoadSwitch").state.name == "ON"
    assert rig.comp("payloadPowerLoadSwitch").state.name == "OFF"
    eps = rig.craft.power
    assert eps.coil_j > 0.0                      # the coils have drawn energy
    v, i, p = rig.comp("ina219SysManager").reading()
    assert 7.0 < v < 8.4 and p > rig.craft.scenario.power.loads.avionics_w
    assert rig.comp("powerMonitor").total_power_mwh > 0.0


def test_load_switch_cuts_a_coil(tmp_path):
    """SITL-LS-001: TURN_OFF on face0LoadSwitch de-energises the X+ coil at once (no dipole), its
    driver refuses to drive it (DeviceNotReady) while the other faces keep working; TURN_ON brings
    it back after the 1 s settling time (DeviceInitialized)."""
    rig = Rig(tmp_path)
    rig.run(5.0)
    rig.send("face0LoadSwitch.TURN_OFF")
    assert rig.named("StatusChanged")[-1].args[0].name == "OFF"
    assert rig.craft.coil_level(0) == 0
    coil = rig.craft.plant.actuators.coils[0]
    levels, others = [], set()
    for _ in range(200):
        rig.run(0.05)
        levels.append(coil.level)
        others.update(rig.craft.coil_level(f) for f in (1, 2, 3, 5))
        assert coil.dipole_B() == (0.0, 0.0, 0.0)
    assert set(levels) == {0}
    assert others - {0}                           # the other faces kept detumbling
    # only face 0's devices are not ready: its coil driver and the TMP112 the thermal manager reads
    face0 = ("ReferenceDeployment.drv2605Face0Manager", "ReferenceDeployment.tmp112Face0Manager")
    assert any(e.name.startswith(face0[0]) for e in rig.named("DeviceNotReady"))
    assert all(e.name.startswith(face0) for e in rig.named("DeviceNotReady"))
    rig.send("face0LoadSwitch.TURN_ON")
    rig.run(30.0)
    assert rig.named("DeviceInitialized")
    assert rig.comp("drv2605Face0Manager")._initialized


def test_low_battery_enters_safe_mode_and_stops_the_coils(tmp_path):
    """SITL-LB-001: a nearly empty battery (bus below SafeModeEntryVoltage 6.7 V) drives the mode
    manager into LOW_BATTERY safe mode after the 10 s debounce; every load switch opens, the detumble
    manager stops and no coil is driven afterwards."""
    rig = Rig(tmp_path, settings=["power.battery.initial_soc=0.05"])
    assert rig.craft.power.battery.ocv() < 6.7
    rig.run(8.5)   # 1 Hz runs at t = 0 … 8 s: nine low readings
    assert rig.comp("modeManager").mode == SystemMode.NORMAL
    rig.run(3.0)
    mm = rig.comp("modeManager")
    assert mm.mode == SystemMode.SAFE_MODE and mm.reason == SafeModeReason.LOW_BATTERY
    entry = rig.named("AutoSafeModeEntry")
    assert entry and entry[0].args[0] == SafeModeReason.LOW_BATTERY and entry[0].args[1] < 6.7
    for f in range(6):
        assert rig.comp(f"face{f}LoadSwitch").state.name == "OFF"
    coil_j = rig.craft.power.coil_j
    rig.run(60.0)
    assert all(rig.craft.coil_level(f) == 0 for f in FACES)
    assert rig.craft.power.coil_j == coil_j
    assert rig.comp("detumbleManager").mode == DetumbleMode.DISABLED


def test_cold_reset_mid_detumble_resumes_from_the_saved_parameters(tmp_path):
    """SITL-RST-001: COLD_RESET mid-detumble: INITIATE_COLD_RESET, the clean-shutdown flag, the
    software restarts (boot count 1 -> 2, components re-initialised: an unsaved parameter change is
    gone, a saved one is reloaded from the parameter file) while the plant keeps its state and time;
    no unintended-reboot safe mode; the faces come back and detumbling continues."""
    rig = Rig(tmp_path)
    rig.run(30.0)
    assert rig.comp("startupManager").boot_count == 1
    dm = rig.comp("detumbleManager")
    rig.send("detumbleManager.GAIN_PRM_SET", 2.5)
    rig.send("detumbleManager.GAIN_PRM_SAVE")
    rig.send("FileHandling.prmDb.PRM_SAVE_FILE")
    rig.send("detumbleManager.DEADBAND_LOWER_THRESHOLD_PRM_SET", 4.0)   # not saved
    assert dm.GAIN.value == pytest.approx(2.5) and dm.DEADBAND_LOWER_THRESHOLD.value == pytest.approx(4.0)
    t_before = rig.craft.plant.t_ns
    rate_before = rig.craft.truth().rate_deg_s
    n_resp = len(rig.responses)
    rig.send("resetManager.COLD_RESET")
    assert len(rig.responses) == n_resp        # the processor resets before it can answer
    assert rig.named("INITIATE_COLD_RESET") and rig.named("PreparingForReboot")
    assert rig.deployment.restarts == 1
    assert rig.craft.plant.t_ns == t_before    # the plant did not jump or restart
    assert rig.craft.truth().rate_deg_s == pytest.approx(rate_before)
    assert dm.GAIN.value == pytest.approx(2.5)                      # saved: reloaded
    assert dm.DEADBAND_LOWER_THRESHOLD.value == pytest.approx(5.0)  # unsaved: default again
    rig.run(5.0)
    assert rig.comp("startupManager").boot_count == 2
    assert rig.comp("modeManager").mode == SystemMode.NORMAL
    assert not rig.named("UnintendedRebootDetected")
    rig.send("startupManager.GET_BOOT_COUNT")
    assert rig.named("CurrentBootCount")[-1].args[0] == 2
    for f in range(6):
        assert rig.comp(f"face{f}LoadSwitch").state.name == "ON"
    driven = set()
    for _ in range(1200):
        rig.run(0.1)
        driven.update(f for f in FACES if rig.craft.coil_level(f) != 0)
    assert driven == set(FACES)
    assert rig.craft.truth().rate_deg_s < rate_before - 0.5
