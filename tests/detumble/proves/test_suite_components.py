"""The PROVES components the upstream integration suite needs, with the port harness (fast)."""

import math

import pytest

from detumble.drivers.plant_control import PlantControl, parse_address
from detumble.proves.antenna_deployer import AntennaDeployer, DeployResult
from detumble.proves.burnwire import Burnwire
from detumble.proves.tmp112_manager import Tmp112Manager
from detumble.sim.lora_link import time_on_air_s
from detumble.sim.thermal import STEFAN_BOLTZMANN, ThermalConfig, ThermalModel
from fprime_lite import CmdResponse
from fprime_lite.model.fw_types import On


def test_burnwire_heats_from_the_battery_and_stops_on_its_safety_timer(fprime_harness, make_craft):
    """BW-001: the GPIOs go high on the first tick (the EPS load rises by burnwire_w), the safety
    timer stops the burn after SAFETY_TIMER ticks with BurnwireEndCount(ticks)."""
    craft = make_craft()
    h = fprime_harness(Burnwire("burnwire", craft, base_id=0x1001B000))
    h.load_parameters()
    h.send_command("SAFETY_TIMER_PRM_SET", 3)
    load = craft.power.switched_load_w()
    h.send_command("START_BURNWIRE")
    h.assert_cmd_response(1, "START_BURNWIRE", CmdResponse.OK)
    assert not craft.burnwire_on
    h.invoke("schedIn", 0)
    assert craft.burnwire_on
    assert craft.power.switched_load_w() == pytest.approx(load + craft.scenario.power.loads.burnwire_w)
    h.invoke("schedIn", 0)
    h.invoke("schedIn", 0)
    assert not craft.burnwire_on
    assert [e.args for e in h.events if e.name == "BurnwireEndCount"] == [(3,)]
    assert [e.args[0] for e in h.events if e.name == "SetBurnwireState"] == [On.ON, On.OFF]


def test_antenna_deployer_retries_then_fails_and_sets_the_flag(fprime_harness, make_craft):
    """AD-001: MAX_DEPLOY_ATTEMPTS burns of BURN_DURATION_SEC ticks, RETRY_DELAY_SEC apart, then
    DeployFinish(FAILED, attempts), the deployed flag set: the next DEPLOY is skipped."""
    craft = make_craft()
    h = fprime_harness(AntennaDeployer("antennaDeployer", craft, base_id=0x10022000))
    h.load_parameters()
    for name, value in (("MAX_DEPLOY_ATTEMPTS", 2), ("BURN_DURATION_SEC", 2), ("RETRY_DELAY_SEC", 1)):
        h.send_command(f"{name}_PRM_SET", value)
    h.send_command("DEPLOY")
    for _ in range(10):
        h.invoke("schedIn", 0)
    assert [e.args for e in h.events if e.name == "DeployAttempt"] == [(1,), (2,)]
    assert [e.args for e in h.events if e.name == "AntennaBurnSignalCount"] == [(2,), (2,)]
    assert [e.args for e in h.events if e.name == "DeployFinish"] == [(DeployResult.DEPLOY_RESULT_FAILED, 2)]
    # each burn ends with a stop, and finishing stops once more (as flown)
    assert len(h.from_port("burnStart")) == 2 and len(h.from_port("burnStop")) == 3
    assert craft and h.component.deployed()
    h.send_command("DEPLOY")
    assert [e.name for e in h.events][-1] == "DeploymentAlreadyComplete"
    h.send_command("SET_DEPLOYMENT_STATE", False)
    assert not h.component.deployed()


def test_a_face_sensor_is_not_ready_while_its_switch_is_open(fprime_harness, make_craft):
    """TMP-001: the face TMP112 reads the thermal model; with face 0's switch open it answers
    EXECUTION_ERROR with DeviceNotReady."""
    craft = make_craft()
    h = fprime_harness(Tmp112Manager("tmp112Face0Manager", craft, "face0", base_id=0x10042000))
    h.send_command("GetTemperature")
    h.assert_cmd_response(0, "GetTemperature", CmdResponse.OK)
    assert [e.args[0] for e in h.events if e.name == "Temperature"] == [pytest.approx(20.0, abs=0.07)]
    craft.set_load_switch("face0", False)
    h.send_command("GetTemperature")
    h.assert_cmd_response(1, "GetTemperature", CmdResponse.EXECUTION_ERROR)
    assert h.events[-1].name == "DeviceNotReady"


def test_lora_time_on_air_matches_semtechs_calculator():
    """LORA-001: SF7/125 kHz/4:5, 10 bytes, 8 preamble symbols: 41.2 ms (Semtech's calculator);
    SF12/125 kHz, 50 bytes: 2.30 s (low-data-rate optimisation on)."""
    assert time_on_air_s(10, 7, 125e3, 1) == pytest.approx(0.041216, abs=1e-6)
    assert time_on_air_s(50, 12, 125e3, 1) == pytest.approx(2.301952, abs=1e-6)
    with pytest.raises(ValueError):
        time_on_air_s(256, 7, 125e3)


def test_thermal_equilibrium_balances_absorbed_and_radiated_power():
    """TH-001: held inputs long enough, Σ α A q + P_el = Σ ε σ A T⁴ to 0.1 % (energy balance)."""
    cfg = ThermalConfig()
    model = ThermalModel(cfg)
    flux = (1361.0, 0.0, 400.0, 0.0, 0.0, 0.0)
    for _ in range(200):
        model.step(100.0, flux, 1.2)
    absorbed = sum(cfg.absorptivity * cfg.face_area_m2 * q for q in flux) + 1.2
    radiated = sum(cfg.emissivity * STEFAN_BOLTZMANN * cfg.face_area_m2 * t ** 4 for t in model.face_k)
    assert radiated == pytest.approx(absorbed, rel=1e-3)
    assert model.face_c(0) > model.interior_c > model.face_c(1)
    assert math.isfinite(model.interior_c)


def test_plant_control_sets_the_battery_and_refuses_what_it_must(make_craft):
    """PC-001: battery_soc moves the open-circuit voltage (2S: 6.45 V at 5 %); bad requests and
    non-loopback addresses are refused with a reason."""
    craft = make_craft()
    control = PlantControl(craft, scheduler=None, address=None)
    assert control.handle({"op": "battery_soc", "soc": 0.05}) == {"ok": True, "ocv_v": pytest.approx(6.45)}
    assert not control.handle({"op": "battery_soc", "soc": 2})["ok"]
    assert "unknown op" in control.handle({"op": "nope"})["error"]
    craft.radio_peer.extend(b"abc")
    assert control.handle({"op": "radio_peer", "max": 2})["data"] == "YWI="
    assert parse_address("127.0.0.1:5000") == ("127.0.0.1", 5000)
    with pytest.raises(ValueError, match="loopback"):
        parse_address("0.0.0.0:5000")


def test_flight_event_ids_of_the_sensor_managers(make_craft):
    """IDS-001: the shared Zephyr sensor events come first (ids 0…7), then each manager's own:
    Temperature 8 (TMP112), VisibleLight 12 (VEML6031); TcSecurityDeframer keeps its explicit ids."""
    from detumble.proves.tc_security_deframer import TcSecurityDeframer
    from detumble.proves.veml6031_manager import Veml6031Manager
    craft = make_craft()
    tmp = Tmp112Manager("t", craft, "battCell1", base_id=0x10048000)
    veml = Veml6031Manager("v", craft, 0, base_id=0x1004D000)
    tc = TcSecurityDeframer("tc", craft, base_id=0x2100B000)
    assert tmp.event_id("DeviceNotReady") == 0x10048000 and tmp.event_id("Temperature") == 0x10048008
    assert veml.event_id("SensorChannelGetFailed") == 0x1004D007 and veml.event_id("VisibleLight") == 0x1004D00C
    assert tc.event_id("SequenceNumberGet") == 0x2100B006 and tc.event_id("SequenceNumberReadFailed") == 0x2100B00E


def test_plant_control_serves_a_loopback_client_on_the_deployment_thread(make_craft):
    """PC-002: the socket opens at the first poll; a request is answered only when the deployment's
    thread polls; a line longer than 4096 bytes is refused and the connection closed."""
    import socket
    import threading

    from detumble.tools.pytest_plant import PlantClient

    class Scheduler:                      # what PlantControl uses of the scheduler
        def __init__(self, clock):
            self.clock, self.polls = clock, []

        def call_every(self, period_us, fn):
            self.polls.append((period_us, fn))

    craft = make_craft()
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    sched = Scheduler(craft.clock)
    control = PlantControl(craft, sched, f"127.0.0.1:{port}")
    assert sched.polls == [(100_000, control.poll)]
    control.poll()                        # opens the socket
    replies = []
    client = PlantClient(f"127.0.0.1:{port}", timeout_s=5)
    t = threading.Thread(target=lambda: replies.append(client.request("battery_soc", soc=0.5)))
    t.start()
    for _ in range(500):
        if replies:
            break
        control.poll()
        t.join(0.01)
    t.join(5)
    client.close()
    assert replies and replies[0]["ok"] and craft.power.battery.soc == pytest.approx(0.5)
    with socket.create_connection(("127.0.0.1", port), timeout=5) as raw:
        raw.sendall(b"x" * 5000 + b"\n")
        assert b"longer than 4096" in raw.makefile("rb").readline()


def test_com_delay_releases_once_per_status_every_divider_plus_one_ticks(fprime_harness):
    """CD-001: with DIVIDER 2 the held status goes out on ticks 0, 3, 6 … and only when the radio
    answered since the last release; setting DIVIDER logs DividerSet."""
    from detumble.proves.com_delay import ComDelay
    from fprime_lite.model.fw_types import Success
    h = fprime_harness(ComDelay("downlinkDelay", base_id=0x1001E000))
    h.load_parameters()
    h.send_command("DIVIDER_PRM_SET", 2)
    assert h.events[-1].name == "DividerSet" and h.events[-1].args == (2,)
    released = []
    for tick in range(9):
        before = len(h.from_port("comStatusOut"))
        h.invoke("run", 0)
        if len(h.from_port("comStatusOut")) > before:
            released.append(tick)
            if tick < 6:                      # the radio answers after each packet but the third
                h.invoke("comStatusIn", Success.SUCCESS)
    assert released == [0, 3, 6]
    h.invoke("run", 0)
    h.invoke("run", 0)
    h.invoke("run", 0)                        # tick 9: nothing held since tick 6
    assert len(h.from_port("comStatusOut")) == 3


def test_lora_sends_a_framed_beacon_to_the_peer_only_when_enabled(fprime_harness, make_craft):
    """LORA-002: an opportunity while DISABLED sends nothing; ENABLED sends one fprime frame
    (DEADBEEF …) to the ground peer and the modem stays busy for its time on air; CONTINUOUS_WAVE
    answers OK twice in a row."""
    from detumble.proves.lora import LoRa, TransmitState
    from fprime_lite.model.fw_types import Success
    craft = make_craft()
    h = fprime_harness(LoRa("lora", craft, base_id=0x1001F000))
    h.load_parameters()
    h.invoke("comStatusIn", Success.SUCCESS)
    assert not craft.radio_peer and len(h.from_port("comStatusOut")) == 1
    h.send_command("TRANSMIT", TransmitState.ENABLED)
    h.invoke("comStatusIn", Success.SUCCESS)
    heard = bytes(craft.radio_peer)
    assert heard[:4] == bytes.fromhex("DEADBEEF") and h.component.packets_sent == 1
    h.invoke("comStatusIn", Success.SUCCESS)          # same instant: still on the air
    assert h.component.packets_sent == 1
    h.send_command("CONTINUOUS_WAVE", 5)
    h.send_command("CONTINUOUS_WAVE", 5)
    assert [r.response for r in h.cmd_responses][-2:] == [CmdResponse.OK, CmdResponse.OK]
    assert not [e for e in h.events if e.name == "ConfigurationFailed"]


def test_camera_image_arrives_in_chunks_and_is_saved(fprime_harness, make_craft):
    """CAM-001: TAKE_IMAGE with face 4 powered → ImageTransferStarted(size), progress at 25/50/75 %,
    ImageTransferComplete and the file on the flash; unpowered → CommandError, EXECUTION_ERROR."""
    import os

    from detumble.proves.camera_handler import CameraHandler
    craft = make_craft()
    h = fprime_harness(CameraHandler("cameraHandler", craft, base_id=0x1002B000, image_bytes=4000,
                                     bytes_per_tick=1000))
    h.send_command("TAKE_IMAGE")
    h.assert_cmd_response(0, "TAKE_IMAGE", CmdResponse.OK)
    for _ in range(6):
        h.invoke("schedIn", 0)
    names = [e.name for e in h.events]
    assert names.count("ImageTransferStarted") == 1 and names.count("ImageTransferProgress") == 3
    done = [e for e in h.events if e.name == "ImageTransferComplete"]
    assert done and done[0].args[1] == 4000
    path = os.path.join(craft.flash_dir, done[0].args[0].lstrip("/"))
    with open(path, "rb") as fh:
        image = fh.read()
    assert len(image) == 4000 and image[:2] == b"\xff\xd8" and image[-2:] == b"\xff\xd9"
    craft.set_load_switch("face4", False)
    h.send_command("TAKE_IMAGE")
    h.assert_cmd_response(1, "TAKE_IMAGE", CmdResponse.EXECUTION_ERROR)
    assert h.events[-1].name == "CommandError"


def test_sequence_number_and_format(fprime_harness, make_craft):
    """TC-001 / FS-001: SET_SEQ_NUM persists the number GET_SEQ_NUM reads back; FORMAT empties the
    flash, after which the number reads 0 again."""
    from detumble.proves.fs_format import FsFormat
    from detumble.proves.tc_security_deframer import TcSecurityDeframer
    craft = make_craft()
    tc = fprime_harness(TcSecurityDeframer("tcSecurityDeframer", craft, base_id=0x2100B000))
    tc.load_parameters()
    fs = fprime_harness(FsFormat("fsFormat", craft, base_id=0x10078000))
    tc.send_command("SET_SEQ_NUM", 1234)
    tc.send_command("GET_SEQ_NUM")
    assert tc.events[-1].name == "SequenceNumberGet" and tc.events[-1].args == (1234,)
    fs.send_command("FORMAT")
    assert fs.events[-1].name == "FileSystemFormatted"
    tc.send_command("GET_SEQ_NUM")
    assert tc.events[-1].args == (0,)


def test_thermal_manager_warns_outside_the_limits_and_skips_unread_sensors(fprime_harness, make_craft):
    """TM-001: a face above FACE_TEMP_UPPER_THRESHOLD → TemperatureAboveThreshold(FACE, index, °C); a
    battery cell below its lower limit → TemperatureBelowThreshold(BATTERY, …); a failed read is
    skipped; throttled at 5 and re-armed when every reading is back inside."""
    from detumble.components.types import Result
    from detumble.proves.thermal_manager import TempSensorType, ThermalManager
    from fprime_lite.model.fw_types import Success
    h = fprime_harness(ThermalManager("thermalManager", base_id=0x10041000))
    h.load_parameters()
    h.set_port_return("faceTempGet", Result(20.0, Success.SUCCESS))
    h.set_port_return("battCellTempGet", Result(20.0, Success.SUCCESS))
    h.set_port_return("picoTempGet", Result(25.0, Success.SUCCESS))
    h.invoke("run", 0)
    assert not h.events
    h.send_command("FACE_TEMP_UPPER_THRESHOLD_PRM_SET", 10.0)
    h.send_command("BATT_CELL_TEMP_LOWER_THRESHOLD_PRM_SET", 25.0)
    h.invoke("run", 0)
    above = [e.args for e in h.events if e.name == "TemperatureAboveThreshold"]
    below = [e.args for e in h.events if e.name == "TemperatureBelowThreshold"]
    assert above == [(TempSensorType.FACE, i, 20.0) for i in range(5)]
    assert below == [(TempSensorType.BATTERY, i, 20.0) for i in range(4)]
    h.set_port_return("faceTempGet", Result(0.0, Success.FAILURE))
    h.set_port_return("battCellTempGet", Result(0.0, Success.FAILURE))
    h.clear_history()
    h.invoke("run", 0)
    assert not h.events


def test_light_sensor_reads_the_sun_on_its_face(fprime_harness, make_craft):
    """VEML-001: lux = the face's cosine response to the Sun (133 klx at 1 AU) with the sensor model's gain error
    and noise (sim.sun_sensors); 0 on a face turned away; not ready with its switch open."""
    from detumble.proves.veml6031_manager import Veml6031Manager
    from detumble.sim.sun_sensors import ideal_illuminance
    from fprime_lite.model.fw_types import Success
    craft = make_craft()
    craft.clock.set_us(1_000_000)             # a second of flight
    sensors = [Veml6031Manager(f"veml{f}", craft, f, base_id=0x1004D000 + f * 0x1000) for f in range(6)]
    lux = [s.visibleLightGet().value for s in sensors]
    model, plant = craft.sun_sensors, craft.plant
    s_N, d_au = model.sun(1.0)
    ideal = ideal_illuminance(model.true_sun_B(1.0, plant.q_BN), d_au, model.eclipse)
    sigma = model.spec.noise_sigma * 133_000.0
    assert all(abs(v - e * g) <= 5 * sigma for v, e, g in zip(lux, ideal, model.gains, strict=True))
    # sunlit at the default epoch: one to three faces see the Sun, and the lit readings are the components
    # of its illuminance along the body axes, 133 klx/d² = 129 klx in June (d = 1.0146 AU), to the gain errors
    lit = [v for v in lux if v > 10 * sigma]
    assert 1 <= len(lit) <= 3 and not model.eclipse
    assert sum(v * v for v in lux) ** 0.5 == pytest.approx(133_000.0 / 1.0146 ** 2, rel=0.08)
    craft.set_load_switch("face2", False)
    assert sensors[2].visibleLightGet().condition == Success.FAILURE
