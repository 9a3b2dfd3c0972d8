"""Actuator health in the reference deployment (issue #16 finding 2): a simulated driver fault that
leaves a coil on past its commanded duration is caught within one torque period, reported WARNING_HI
and the face isolated, while the other four coils keep detumbling.

Each test flies the reference topology (50 Hz, TORQUE_DURATION 320 ms) and injects the fault into the
X+ driver while that coil is on in an ACTUATING_BDOT period.
"""

import pathlib

import pytest

from detumble.components.types import DetumbleState, MagnetorquerFace
from detumble.drivers.magnetorquer_driver import SimDriverFault
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology

TOPOLOGY = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref" / "topology.yaml"
SEQUENCE = TOPOLOGY.parent / "startup.seq"
TORQUE_PERIOD_US = 320_000
TICK_US = 20_000


def fly_with_fault(fault, seconds=4.0):
    loaded = load_topology(TOPOLOGY)
    topo = loaded.topology
    manager = topo.instance("ReferenceDeployment.detumbleManager").component
    driver = topo.instance("ReferenceDeployment.drv2605Face0Manager").component
    y_plus = topo.instance("ReferenceDeployment.drv2605Face2Manager").component
    seen = {"fault_us": None, "isolated_us": None, "y_plus_on_after": 0}
    starts_after_isolation = []
    original_start = driver._start

    def counting_start(val):
        if seen["isolated_us"] is not None:
            starts_after_isolation.append(val)
        return original_start(val)

    driver._start = counting_start

    def watch(now_us):
        if seen["fault_us"] is None:
            if manager.state == DetumbleState.ACTUATING_BDOT and driver.level != 0:
                driver.set_fault(fault)
                seen["fault_us"] = now_us
            return
        if seen["isolated_us"] is None and manager.isolated_faces:
            seen["isolated_us"] = now_us
        elif seen["isolated_us"] is not None and y_plus.level != 0:
            seen["y_plus_on_after"] += 1

    loaded.scheduler.add_time_listener(watch)
    deployment = Deployment(loaded)
    deployment.start(sequence=SEQUENCE)
    deployment.run_for(seconds)
    return manager, driver, seen, starts_after_isolation


@pytest.mark.parametrize("fault", [SimDriverFault.STUCK, SimDriverFault.STOP_FAILS, SimDriverFault.LATCHED])
def test_a_coil_left_on_is_isolated_within_one_torque_period(fault):
    """Actuator Health: STUCK (level frozen, FAILURE), STOP_FAILS (stop ignored, FAILURE) and LATCHED
    (writes acknowledged, output frozen; the driver's read-back answers FAILURE): X+ is isolated
    ≤ 320 ms + one 20 ms tick after the fault, exactly once, the driver is never started again,
    and the other coils keep being driven (B-dot cycles continue)."""
    manager, driver, seen, starts_after = fly_with_fault(fault)
    assert seen["fault_us"] is not None, "the X+ coil was never on during ACTUATING_BDOT"
    assert seen["isolated_us"] is not None, "the stuck coil was never isolated"
    assert seen["isolated_us"] - seen["fault_us"] <= TORQUE_PERIOD_US + TICK_US
    assert manager.isolated_faces == (MagnetorquerFace.X_PLUS,)
    assert sum(manager._stop_failures) == 1
    assert manager.spec.event("CoilStopFailed").severity.name == "WARNING_HI"
    assert starts_after == []
    assert seen["y_plus_on_after"] > 10  # ticks with the Y+ coil driven after the isolation


def test_healthy_drivers_are_never_isolated():
    """Actuator Health: the same flight without a fault isolates nothing (the check cannot fire on
    healthy drivers)."""
    manager, _, seen, _ = fly_with_fault(SimDriverFault.NONE)
    assert seen["fault_us"] is not None and manager.isolated_faces == () and sum(manager._stop_failures) == 0
