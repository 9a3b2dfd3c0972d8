"""Simulated drivers and the spacecraft they drive: the hardware side of the software-in-the-loop.

* :mod:`.spacecraft` — :class:`~.spacecraft.SimulatedSpacecraft`: the plant of :mod:`detumble.sim`
  stepped in lock-step with the scheduler clock, its truth trace, and :func:`~.spacecraft.make_spacecraft`,
  the topology's ``simulation`` resource;
* :mod:`.magnetorquer_driver` — :class:`~.magnetorquer_driver.MagnetorquerDriver`: one DRV2605-driven face coil;
* :mod:`.reaction_wheel_driver` — :class:`~.reaction_wheel_driver.ReactionWheelDriver`: one reaction wheel;
* :mod:`.torque_rod_driver` — the coursework's ideal torque rods;
* :mod:`.star_tracker` — :class:`~.star_tracker.StarTracker`: the attitude ``q_BN``;
* :mod:`.orbit_ephemeris` — the orbit frame as an on-board propagator would know it;
* :mod:`.ports` — the PROVES port types the drivers and the flight components share (flight FPP names).

The PROVES flight components that read this hardware are in :mod:`detumble.proves`. See
``docs/components/simulated_drivers.md`` and a page per component beside it.
"""
