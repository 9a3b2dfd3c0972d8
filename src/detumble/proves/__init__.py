"""PROVES flight components as flown: their ground interface (ids, names, formats) and behaviour, on
the simulated hardware of :mod:`detumble.drivers`.

* :mod:`.mode_manager` — :class:`~.mode_manager.ModeManager`: NORMAL / SAFE_MODE, safe-mode reasons,
  low battery, command loss, persistence;
* :mod:`.imu_manager` — :class:`~.imu_manager.ImuManager`: LIS2MDL magnetometer + LSM6DSO gyro/accelerometer;
* power: :mod:`.load_switch`, :mod:`.ina219_manager`, :mod:`.power_monitor` on the simulated electrical
  system (:mod:`detumble.sim.power`);
* housekeeping: :mod:`.rtc_manager`, :mod:`.startup_manager`, :mod:`.watchdog`, :mod:`.reset_manager`.

Deviations from the flight code: a page per component in ``docs/components/``.
"""
