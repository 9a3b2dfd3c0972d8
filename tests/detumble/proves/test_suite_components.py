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
