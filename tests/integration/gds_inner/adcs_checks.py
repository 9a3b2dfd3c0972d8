"""Checks run *inside* fprime-gds's pytest plugin against the flying attitude-control deployment.

Not collected by the project's test run; ``tests/integration/test_gds_adcs.py`` starts fprime-gds and
``deployments/adcs_ref`` (realtime, a slow 0.5 °/s start and a start-up sequence that forces POINTING),
then runs this file. Figures go to the JSON file named by ``FPRIME_LITE_GDS_FIGURES``.
"""

import json
import os
import time

import pytest
from fprime_gds.common.testing_fw import predicates

CTRL = "ReferenceDeployment.attitudeController"
FIGURES: dict = {}


@pytest.fixture(scope="session", autouse=True)
def pointing_on_board(fprime_test_api_session):
    """The controller reports POINTING (forced by the start-up sequence once the tracker has a fix)."""
    api = fprime_test_api_session
    assert api.await_telemetry(f"{CTRL}.Mode", value="POINTING", timeout=40) is not None, \
        "the controller did not report POINTING within 40 s"
    yield
    path = os.environ.get("FPRIME_LITE_GDS_FIGURES")
    if path:
        with open(path, "w", encoding="utf-8") as f:
            json.dump(FIGURES, f)


def test_a_new_target_is_flown_to(fprime_test_api):
    """ADCS-050: the GDS commands a target 90° away; the controller logs TargetSet, the telemetered pointing
    error jumps to about 90° and comes back below 0.1° within 60 s of wall (= simulated) time."""
    api = fprime_test_api
    api.send_and_assert_command(f"{CTRL}.SET_TARGET_QUATERNION", ["0.7071067811865476", "0", "0.7071067811865476",
                                                                  "0"], timeout=5)
    api.assert_event(f"{CTRL}.TargetSet", timeout=5)
    t0 = time.monotonic()
    big = api.await_telemetry(f"{CTRL}.PointingError", value=predicates.greater_than(45.0), timeout=10)
    assert big is not None, "the pointing error never showed the new 90° target"
    small = api.await_telemetry(f"{CTRL}.PointingError", value=predicates.less_than(0.1), timeout=60)
    assert small is not None, "the controller did not settle within 0.1° of the new target in 60 s"
    FIGURES["slew_90_deg_settle_s"] = time.monotonic() - t0


def test_mode_commands_and_a_refused_target(fprime_test_api):
    """ADCS-051: FORCE_MODE SPIN_STABLE and SET_AUTO from the GDS give ControlModeChanged and AutonomyChanged;
    a non-unit target is refused with TargetNotUnitQuaternion."""
    api = fprime_test_api
    api.send_and_assert_command(f"{CTRL}.FORCE_MODE", ["SPIN_STABLE"], timeout=5)
    api.assert_event(f"{CTRL}.ControlModeChanged", timeout=5)
    assert api.await_telemetry(f"{CTRL}.Mode", value="SPIN_STABLE", timeout=5) is not None
    api.send_and_assert_command(f"{CTRL}.SET_AUTO", timeout=5)
    api.assert_event(f"{CTRL}.AutonomyChanged", timeout=5)
    start = api.get_event_test_history().size()
    api.send_command(f"{CTRL}.SET_TARGET_QUATERNION", ["0.5", "0", "0", "0"])
    api.assert_event(f"{CTRL}.TargetNotUnitQuaternion", start=start, timeout=5)
