"""Simulated drivers of the reference deployment, flying the plant of :mod:`detumble.sim`.

* :mod:`.spacecraft` — :class:`SimulatedSpacecraft`: the plant stepped in lock-step with the
  scheduler clock; truth trace.
* :mod:`.imu_manager` — :class:`ImuManager`: LIS2MDL magnetometer + LSM6DSO gyro/accelerometer.
* :mod:`.magnetorquer_driver` — :class:`MagnetorquerDriver`: one DRV2605-driven face coil.
* :mod:`.mode_manager` — :class:`ModeManager`: the flight mode manager (safe-mode reasons, low
  battery, command loss, persistence).
* power: :mod:`.load_switch`, :mod:`.ina219_manager`, :mod:`.power_monitor` on the simulated
  electrical system (:mod:`detumble.sim.power`).
* housekeeping: :mod:`.rtc_manager`, :mod:`.startup_manager`, :mod:`.watchdog`, :mod:`.reset_manager`.
* :mod:`.reaction_wheel_driver` — :class:`ReactionWheelDriver`: one reaction wheel.
* :mod:`.star_tracker` — :class:`StarTracker`: the attitude q_BN.

See ``docs/components/simulated_drivers.md`` and a page per flight component beside it.
"""

from detumble.sitl.imu_manager import (Acceleration, AccelerationGet, AngularVelocity, AngularVelocityGet, ImuManager,
                          Lis2mdlSamplingFrequency, Lsm6dsoSamplingFrequency, SimImuSensor, SimReadFault)
from detumble.sitl.magnetorquer_driver import (DRIVER_FACES, MagnetorquerDriver, SimDriverFault, driver_instance_name,
                                  make_magnetorquer_drivers)
from detumble.sitl.mode_manager import MODE_CHANGED_PORTS, ForceSafeModeWithReason, ModeManager, SafeModeReason
from detumble.sitl.reaction_wheel_driver import (ReactionWheelDriver, SimWheelFault, make_reaction_wheel_drivers,
                                                 wheel_instance_name)
from detumble.sitl.spacecraft import SimulatedSpacecraft, TruthRecorder, TruthSample, scenario_epoch_us
from detumble.sitl.star_tracker import SimStarTrackerFault, StarTracker

__all__ = [
    "SimulatedSpacecraft", "TruthRecorder", "TruthSample", "scenario_epoch_us",
    "ImuManager", "Acceleration", "AngularVelocity", "AccelerationGet", "AngularVelocityGet",
    "Lis2mdlSamplingFrequency", "Lsm6dsoSamplingFrequency", "SimImuSensor", "SimReadFault",
    "MagnetorquerDriver", "SimDriverFault", "DRIVER_FACES", "driver_instance_name", "make_magnetorquer_drivers",
    "ModeManager", "ForceSafeModeWithReason", "SafeModeReason", "MODE_CHANGED_PORTS",
    "ReactionWheelDriver", "SimWheelFault", "make_reaction_wheel_drivers", "wheel_instance_name",
    "StarTracker", "SimStarTrackerFault",
]
