"""Pieces shared by the Basilisk equivalents (case A, adcs_ref, coursework): attitude conversions,
the rotating Earth, the scenario's wheels, task set-up with truth recorders. Needs Basilisk
(``pip install -e '.[bsk]'``).
"""
from __future__ import annotations

import math

from Basilisk.architecture import messaging
from Basilisk.simulation import planetEphemeris, reactionWheelStateEffector
from Basilisk.utilities import macros, simIncludeRW

__all__ = ["mrp", "quat", "rotating_earth", "balanced_wheels", "schedule", "wheel_momenta"]

_RPM = 2.0 * math.pi / 60.0  #: rad/s per rpm


def mrp(q) -> list[float]:
    """MRP σ of the scalar-first quaternion ``q`` (the short way: |σ| ≤ 1)."""
    if q[0] < 0.0:
        q = (-q[0], -q[1], -q[2], -q[3])
    return [q[1] / (1.0 + q[0]), q[2] / (1.0 + q[0]), q[3] / (1.0 + q[0])]


def quat(sigma) -> tuple[float, float, float, float]:
    """Scalar-first quaternion of the MRP ``sigma``."""
    s2 = sigma[0] ** 2 + sigma[1] ** 2 + sigma[2] ** 2
    d = 1.0 + s2
    return ((1.0 - s2) / d, 2.0 * sigma[0] / d, 2.0 * sigma[1] / d, 2.0 * sigma[2] / d)


def rotating_earth(angle0_rad: float, rate_rad_s: float) -> planetEphemeris.PlanetEphemeris:
    """A ``planetEphemeris`` whose Earth turns about N's z axis at ``rate_rad_s`` from ``angle0_rad``
    (its J20002Pfix is the Earth-fixed frame the centred dipole is defined in). Its heliocentric
    "orbit" is a 1 m circle, so the planet stays at the origin for the field module."""
    ephemeris = planetEphemeris.PlanetEphemeris()
    ephemeris.ModelTag = "earthRotation"
    ephemeris.setPlanetNames(planetEphemeris.StringVector(["earth"]))
    here = planetEphemeris.ClassicElements()
    here.a, here.e, here.i, here.Omega, here.omega, here.f = 1.0, 0.0, 0.0, 0.0, 0.0, 0.0
    ephemeris.planetElements = planetEphemeris.classicElementVector([here])
    ephemeris.rightAscension = planetEphemeris.DoubleVector([0.0])
    ephemeris.declination = planetEphemeris.DoubleVector([math.pi / 2])
    ephemeris.lst0 = planetEphemeris.DoubleVector([angle0_rad])
    ephemeris.rotRate = planetEphemeris.DoubleVector([rate_rad_s])
    return ephemeris


def balanced_wheels(sc, specs, omega0_B):
    """``(factory, effector)``: the scenario's wheels ``specs`` (``detumble.sim.wheels.WheelSpec``) as
    ``reactionWheelStateEffector`` BalancedWheels on ``sc``: axis, J_s, torque limit (enforced),
    Ω_max = h_max / J_s. Each starts at the speed relative to the body that gives its absolute
    momentum J_s (Ω + g·ω) the spec's initial one, as the plant's wheels start."""
    factory = simIncludeRW.rwFactory()
    for i, w in enumerate(specs):
        g = w.axis_B
        relative = w.initial_momentum_nms / w.inertia_kg_m2 - sum(g[j] * omega0_B[j] for j in range(3))
        factory.create("custom", list(g), Js=w.inertia_kg_m2, u_max=w.max_torque_nm, useMaxTorque=True,
                       Omega_max=w.max_momentum_nms / w.inertia_kg_m2 / _RPM, Omega=relative / _RPM,
                       RWModel=messaging.BalancedWheels, label=f"rw{i}")
    effector = reactionWheelStateEffector.ReactionWheelStateEffector()
    effector.ModelTag = "wheels"
    factory.addToSpacecraft("wheels", effector, sc)
    return factory, effector


def schedule(sim, dynamics: list, fsw: list, sc, wheels, interval_s: float):
    """Add ``dynamics`` and ``fsw`` to their tasks in this order (first runs first) and two truth
    recorders every ``interval_s`` on the dynamics task; returns ``(state_log, speed_log)``."""
    for priority, model in enumerate(reversed(dynamics)):
        sim.AddModelToTask("dynamics", model, 10 + priority)
    for priority, model in enumerate(reversed(fsw)):
        sim.AddModelToTask("fsw", model, 10 + priority)
    interval = macros.sec2nano(interval_s)
    state_log = sc.scStateOutMsg.recorder(interval)
    speed_log = wheels.rwSpeedOutMsg.recorder(interval)
    sim.AddModelToTask("dynamics", state_log)
    sim.AddModelToTask("dynamics", speed_log)
    return state_log, speed_log


def wheel_momenta(specs, speeds, omega_B) -> list[float]:
    """Absolute axial momenta J_s (Ω_i + g_i·ω) (N·m·s) from Basilisk's relative wheel speeds."""
    return [w.inertia_kg_m2 * (speeds[i] + sum(w.axis_B[j] * omega_B[j] for j in range(3)))
            for i, w in enumerate(specs)]
