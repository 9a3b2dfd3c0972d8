"""adcs_ref's wheel telemetry `run`s fly in the 1 Hz rate group (where PROVES flies its sensor managers'
telemetry): a wheel held at its momentum limit must still report MomentumSaturated within that period.

The wheel is held at the limit by a stuck motor: from a chosen instant the plant's wheel applies its full
torque whatever the controller commands, so it reaches its momentum limit a couple of seconds later at a
time the test reads from the plant (its ``momentum_limited`` flag, 20 ms steps).
"""

import pathlib

import pytest

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology

TOPOLOGY = pathlib.Path(__file__).parents[1] / "deployments" / "adcs_ref" / "topology.yaml"
STEP_S = 0.02  # the 50 Hz tick


@pytest.mark.parametrize("wheel, stuck_at_s", [(0, 2.3), (1, 2.98), (2, 3.02)])
def test_a_wheel_at_its_momentum_limit_reports_it_within_a_second(wheel, stuck_at_s):
    """TICK-030: in the adcs_ref deployment, a wheel whose motor sticks at full torque reaches its momentum
    limit and its driver's MomentumSaturated (WARNING_HI) fires no later than 1 s after the limit is first
    reached (the 1 Hz group's period), and not before; the three onsets fall at different phases of the
    second (.30, .98 and .02 s after the whole second)."""
    loaded = load_topology(TOPOLOGY)
    driver = {c.name: c for c in loaded.topology.components()}[f"reactionWheel{wheel}"]
    wheels = driver.spacecraft.plant.wheels
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(stuck_at_s)
    set_torque = wheels.set_torque
    wheels.set_torque = lambda i, u: set_torque(i, driver.max_torque_nm if i == wheel else u)  # the stuck motor
    driver.torqueSet(driver.max_torque_nm)
    clock = driver.spacecraft.clock
    limit_us = event_us = None
    for _ in range(int(10.0 / STEP_S)):
        deployment.run_for(STEP_S)
        if limit_us is None and wheels.momentum_limited[wheel]:
            limit_us = clock.current_us
        if driver.MomentumSaturated.count:
            event_us = clock.current_us
            break
    assert limit_us is not None, "the stuck wheel never reached its momentum limit"
    assert event_us is not None, "no MomentumSaturated within 10 s"
    assert 0 <= event_us - limit_us <= 1_000_000
    assert driver.MomentumSaturated.count == 1
