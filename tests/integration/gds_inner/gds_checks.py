"""Checks run *inside* fprime-gds's pytest plugin (``fprime_test_api``) against a flying deployment.

Not collected by the project's test run (the name does not match ``test_*.py``):
``tests/integration/test_gds.py`` starts fprime-gds and the deployment, then runs
``python -m pytest tests/integration/gds_inner/gds_checks.py --dictionary D --zmq-transport IN OUT``.
Round-trip figures go to the JSON file named by ``FPRIME_LITE_GDS_FIGURES`` when it is set.
``FPRIME_LITE_GDS_RUNS`` names the folder holding the deployment's run folder, which is the root of
its file services: files are uplinked into it and downlinked from it.
"""

import json
import math
import os
import time
from pathlib import Path

import pytest

DEP = "ReferenceDeployment"
FIGURES: dict = {}


@pytest.fixture
def run_root():
    """The flying deployment's run folder (the file services' root): the one folder in the runs folder."""
    runs = [p for p in Path(os.environ["FPRIME_LITE_GDS_RUNS"]).iterdir() if p.is_dir()]
    assert len(runs) == 1, f"expected one run folder, found {runs}"
    return runs[0]


@pytest.fixture(scope="session", autouse=True)
def deployment_is_flying(fprime_test_api_session):
    """The deployment's telemetry reaches the GDS (so the link is up both ways) before any check."""
    api = fprime_test_api_session
    assert api.await_telemetry(f"{DEP}.detumbleManager.Mode", timeout=30) is not None, \
        "no telemetry from the deployment within 30 s"
    yield
    path = os.environ.get("FPRIME_LITE_GDS_FIGURES")
    if path:
        with open(path, "w", encoding="utf-8") as f:
            json.dump(FIGURES, f)


def test_no_op_round_trip(fprime_test_api):
    latencies = []
    for _ in range(5):
        t0 = time.monotonic()
        fprime_test_api.send_and_assert_command("CdhCore.cmdDisp.CMD_NO_OP", timeout=5)
        latencies.append(time.monotonic() - t0)
    fprime_test_api.assert_event("CdhCore.cmdDisp.NoOpReceived", timeout=2)
    FIGURES["no_op_round_trip_s"] = latencies


def test_detumble_starts_when_set_to_auto(fprime_test_api):
    fprime_test_api.send_and_assert_command(f"{DEP}.detumbleManager.SET_MODE", ["AUTO"], timeout=5)
    fprime_test_api.assert_event(f"{DEP}.detumbleManager.DetumbleStarted", timeout=5)
    assert fprime_test_api.await_telemetry(f"{DEP}.detumbleManager.Mode", value="AUTO", timeout=5) is not None
    state = fprime_test_api.await_telemetry(f"{DEP}.detumbleManager.State", timeout=5)
    assert state is not None
    assert str(state.get_val()) in {"COOLDOWN", "SENSING_ANGULAR_VELOCITY", "SENSING_MAGNETIC_FIELD",
                                    "ACTUATING_BDOT", "ACTUATING_HYSTERESIS"}


def test_gain_parameter_set(fprime_test_api):
    fprime_test_api.send_and_assert_command(f"{DEP}.detumbleManager.GAIN_PRM_SET", ["2.5"], timeout=5)
    fprime_test_api.assert_event(f"{DEP}.detumbleManager.GainParamSet", args=[2.5], timeout=5)
    assert fprime_test_api.await_telemetry(f"{DEP}.detumbleManager.GainParam", value=2.5, timeout=5) is not None


def test_magnetic_field_reading(fprime_test_api):
    # The simulated magnetometer also sees the magnetorquers while B-dot drives them: stop them first.
    fprime_test_api.send_and_assert_command(f"{DEP}.detumbleManager.SET_MODE", ["DISABLED"], timeout=5)
    assert fprime_test_api.await_telemetry(f"{DEP}.detumbleManager.Mode", value="DISABLED", timeout=5) is not None
    fprime_test_api.send_and_assert_command(f"{DEP}.imuManager.GET_MAGNETIC_FIELD", timeout=5)
    event = fprime_test_api.assert_event(f"{DEP}.imuManager.MagneticFieldData", timeout=5)
    field = [arg.val for arg in event.get_args()]
    # Non-zero as a vector: one axis may read exactly 0 (the LIS2MDL quantises in 1.5 mG steps).
    assert len(field) == 3 and all(math.isfinite(v) for v in field) and any(v != 0.0 for v in field)
    magnitude = math.sqrt(sum(v * v for v in field))
    assert 0.1 < magnitude < 0.7, f"|B| = {magnitude} G is not the Earth's field in low Earth orbit"
    FIGURES["magnetic_field_G"] = field


def test_file_uplink_lands_byte_identical(fprime_test_api, tmp_path, run_root):
    """The GDS's file uplinker cuts the file into packets; FileUplink reassembles it on board, in its
    root (the run folder)."""
    data = os.urandom(900)  # four 256-byte chunks: the GDS paces its uplink at 0.5 s a chunk
    source, landed = tmp_path / "uplinked.bin", run_root / f"landed_{os.getpid()}.bin"
    source.write_bytes(data)
    assert fprime_test_api.uplink_file_and_await_completion(str(source), destination=landed.name, timeout=20)
    assert landed.read_bytes() == data


def test_file_downlink_reaches_the_ground_store(fprime_test_api, run_root):
    """SendFile on board (a file in the file services' root); the GDS's downlinker writes it into its store."""
    data = os.urandom(2000)
    source = run_root / f"on_board_{os.getpid()}.bin"
    source.write_bytes(data)
    name = f"downlinked_{os.getpid()}.bin"
    fprime_test_api.send_and_assert_command("FileHandling.fileDownlink.SendFile", [str(source), name], timeout=10)
    fprime_test_api.assert_event("FileHandling.fileDownlink.FileSent", timeout=5)
    landed = Path(fprime_test_api.pipeline.down_store) / name
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and not (landed.exists() and landed.read_bytes() == data):
        time.sleep(0.1)
    assert landed.read_bytes() == data


def test_uplinked_sequence_runs(fprime_test_api, tmp_path, run_root):
    """A text sequence compiled and uplinked by the GDS, then run with CS_RUN."""
    sequence = tmp_path / "ground.seq"
    sequence.write_text("; two no-ops from the ground\nR00:00:00 CdhCore.cmdDisp.CMD_NO_OP\n"
                        "R00:00:01 CdhCore.cmdDisp.CMD_NO_OP\n")
    on_board = run_root / f"ground_{os.getpid()}.bin"
    assert fprime_test_api.uplink_sequence_and_await_completion(str(sequence), destination=on_board.name,
                                                                timeout=20)
    start = fprime_test_api.get_event_test_history().size()
    fprime_test_api.send_and_assert_command(f"{DEP}.cmdSeq.CS_RUN", [str(on_board), "BLOCK"], timeout=10)
    fprime_test_api.assert_event(f"{DEP}.cmdSeq.CS_SequenceComplete", start=start, timeout=5)
    fprime_test_api.assert_event_count(2, "CdhCore.cmdDisp.NoOpReceived", start=start, timeout=5)


# --- the PROVES flight components, driven as a flight operator drives them ----------------------

def test_operator_safe_mode_round_trip(fprime_test_api):
    """FORCE_SAFE_MODE with its reason, the faces switched off, EXIT_SAFE_MODE switching them back."""
    api = fprime_test_api
    start = api.get_event_test_history().size()
    api.send_and_assert_command(f"{DEP}.modeManager.FORCE_SAFE_MODE", timeout=5)
    api.assert_event(f"{DEP}.modeManager.ManualSafeModeEntry", start=start, timeout=5)
    api.assert_event(f"{DEP}.modeManager.EnteringSafeMode", args=["Ground command"], start=start, timeout=5)
    api.send_and_assert_command(f"{DEP}.modeManager.GET_SAFE_MODE_REASON", timeout=5)
    api.assert_event(f"{DEP}.modeManager.CurrentSafeModeReasonReading", args=["GROUND_COMMAND"], start=start,
                     timeout=5)
    api.send_and_assert_command(f"{DEP}.face0LoadSwitch.GET_IS_ON", timeout=5)
    api.assert_event(f"{DEP}.face0LoadSwitch.IsOn", args=["OFF"], start=start, timeout=5)
    start = api.get_event_test_history().size()
    api.send_and_assert_command(f"{DEP}.modeManager.EXIT_SAFE_MODE", timeout=5)
    api.assert_event(f"{DEP}.modeManager.ExitingSafeMode", start=start, timeout=5)
    api.assert_event(f"{DEP}.face0LoadSwitch.StatusChanged", args=["ON"], start=start, timeout=5)
    api.send_and_assert_command(f"{DEP}.modeManager.GET_CURRENT_MODE", timeout=5)
    api.assert_event(f"{DEP}.modeManager.CurrentModeReading", args=["NORMAL"], start=start, timeout=5)


def test_operator_power_readings(fprime_test_api):
    """A face switch cycled by command; the INA219 and the power monitor read the simulated EPS."""
    api = fprime_test_api
    start = api.get_event_test_history().size()
    api.send_and_assert_command(f"{DEP}.face2LoadSwitch.TURN_OFF", timeout=5)
    api.assert_event(f"{DEP}.face2LoadSwitch.StatusChanged", args=["OFF"], start=start, timeout=5)
    api.send_and_assert_command(f"{DEP}.face2LoadSwitch.TURN_ON", timeout=5)
    api.assert_event(f"{DEP}.face2LoadSwitch.StatusChanged", args=["ON"], start=start, timeout=5)
    api.send_and_assert_command(f"{DEP}.ina219SysManager.GetVoltage", timeout=5)
    volts = api.assert_event(f"{DEP}.ina219SysManager.VoltageReading", start=start, timeout=5).get_args()[0].val
    assert 6.7 < volts < 8.4, f"bus voltage {volts} V is not a healthy 2S Li-ion battery"
    api.send_and_assert_command(f"{DEP}.powerMonitor.GET_TOTAL_POWER", timeout=5)
    energy = api.assert_event(f"{DEP}.powerMonitor.TotalPowerConsumptionReading", start=start,
                              timeout=5).get_args()[0].val
    assert energy > 0.0
    assert api.await_telemetry(f"{DEP}.ina219SolManager.Power", timeout=5) is not None
    FIGURES["bus_voltage_V"] = volts


def test_operator_cold_reset(fprime_test_api):
    """COLD_RESET: the software restarts (boot count 2) without an unintended-reboot safe mode, and
    the ground link stays up: commands work again at once. Runs last (it resets every component)."""
    api = fprime_test_api
    start = api.get_event_test_history().size()
    api.send_and_assert_command(f"{DEP}.startupManager.GET_BOOT_COUNT", timeout=5)
    api.assert_event(f"{DEP}.startupManager.CurrentBootCount", args=[1], start=start, timeout=5)
    api.send_command(f"{DEP}.resetManager.COLD_RESET")   # never answered: the processor resets
    api.assert_event(f"{DEP}.resetManager.INITIATE_COLD_RESET", start=start, timeout=5)
    api.assert_event(f"{DEP}.modeManager.PreparingForReboot", start=start, timeout=5)
    assert api.await_telemetry(f"{DEP}.startupManager.BootCount", value=2, timeout=10) is not None
    api.send_and_assert_command(f"{DEP}.startupManager.GET_BOOT_COUNT", timeout=5)
    api.assert_event(f"{DEP}.startupManager.CurrentBootCount", args=[2], start=start, timeout=5)
    api.send_and_assert_command(f"{DEP}.modeManager.GET_CURRENT_MODE", timeout=5)
    api.assert_event(f"{DEP}.modeManager.CurrentModeReading", args=["NORMAL"], start=start, timeout=5)
    api.assert_event_count(0, f"{DEP}.modeManager.UnintendedRebootDetected", start=start, timeout=1)
