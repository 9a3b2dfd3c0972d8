"""Shared fixtures of the simulated-driver tests: scenarios and spacecraft on a simulated clock."""

import dataclasses

import pytest

from detumble.sim.scenario import load_scenario
from detumble.sim.sensors import GyroSpec, MagnetometerSpec
from detumble.drivers.spacecraft import SimulatedSpacecraft, scenario_epoch_us
from fprime_lite import SimulatedClock

_DEFAULT = load_scenario("default")


@pytest.fixture
def default_scenario():
    """The reference deployment's scenario: 30 deg/s tumble, noisy biased sensors, 20 ms dynamics."""
    return _DEFAULT


@pytest.fixture
def quiet_scenario():
    """The default scenario with noise-free, unbiased, unquantised (but sample-and-hold) sensors."""
    return dataclasses.replace(
        _DEFAULT,
        magnetometer=MagnetometerSpec(noise_std_gauss=0.0, bias_gauss=(0.0, 0.0, 0.0), resolution_gauss=0.0),
        gyro=GyroSpec(noise_density_dps_rthz=0.0, bias_dps=(0.0, 0.0, 0.0), resolution_dps=0.0),
    )


@pytest.fixture
def ideal_scenario():
    """The default scenario with ideal sensors (truth at the read time, no coupling)."""
    return dataclasses.replace(_DEFAULT, magnetometer=MagnetometerSpec(ideal=True), gyro=GyroSpec(ideal=True))


@pytest.fixture
def make_craft():
    """``make_craft(scenario)``: a spacecraft on a fresh clock whose epoch is the scenario's."""
    def make(scenario=_DEFAULT, **kwargs):
        clock = SimulatedClock(epoch_us=scenario_epoch_us(scenario))
        return SimulatedSpacecraft(scenario, clock=clock, **kwargs)
    return make
