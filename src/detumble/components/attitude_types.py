"""F´ types and port types of the attitude controller (seed 003) and the attitude sensors it reads.

Frames and units at every port: body frame B, inertial frame N; angular rate rad/s; quaternions
``q_BN`` scalar first (``detumble.control.quaternion``); torque N·m; angular momentum N·m·s;
dipole A·m². ``ref condition`` ports return a :class:`~detumble.components.types.Result`.
"""

from __future__ import annotations

from fprime_lite import BOOL, F64, U8, Array, FwEnum, PortType, Struct, Time

from detumble.components.types import Result

__all__ = ["ControlMode", "ControlAutonomy", "SpinLaw", "PointingActuator", "MagPointingLaw", "MagResidualMode",
           "ModeChangeReason", "AlbedoUnavailableReason",
           "AttitudeEstimator", "RateSource", "WheelFeedForward", "BodyAxis", "PointingReference", "TargetKind",
           "Ephemeris", "EphemerisGet", "SunVector", "SunVectorGet",
           "Vector3", "Quaternion", "WheelValues", "AngularVelocity", "AngularVelocityGet", "MAX_WHEELS"]

#: Wheel channels carry this many values (unused wheels read 0).
MAX_WHEELS = 4


class ControlMode(FwEnum, namespace="Components"):
    """What the attitude controller does: IDLE (actuators off), one of seed 003's three modes, or SUN_SAFE (a face
    to the Sun on the light sensors' Sun vector, no attitude needed)."""

    IDLE = 0
    DETUMBLE = 1
    SPIN_STABLE = 2
    POINTING = 3
    SUN_SAFE = 4


class ControlAutonomy(FwEnum, namespace="Components"):
    """MANUAL: the mode stays where it was commanded; AUTO: the seed's triggers choose it."""

    MANUAL = 0
    AUTO = 1


class SpinLaw(FwEnum, namespace="Components"):
    """The SPIN_STABLE law: seed 003's damper as written, the classical 3-axis damper, or the rate
    regulator that holds a spin about any axis (the default)."""

    SEED_KANE_DAMPER = 0
    VIRTUAL_DAMPER = 1
    RATE_REGULATOR = 2


class PointingActuator(FwEnum, namespace="Components"):
    """POINTING actuator: ANY (wheels when present, else magnetorquers), WHEELS only, or
    MAGNETORQUERS only."""

    ANY = 0
    WHEELS = 1
    MAGNETORQUERS = 2


class AttitudeEstimator(FwEnum, namespace="Components"):
    """The attitude estimator: the complementary filter (gains FILTER_KP/KI) or the MEKF (noise from the
    sensors' specifications)."""

    COMPLEMENTARY = 0
    MEKF = 1


class RateSource(FwEnum, namespace="Components"):
    """The body rate the wheel PD's derivative term uses: the bias-corrected gyro, or the model-aided
    rate observer (``detumble.control.rate_observer``)."""

    GYRO = 0
    OBSERVER = 1


class MagPointingLaw(FwEnum, namespace="Components"):
    """POINTING on the magnetorquers: seed 003's PD projected ⟂ B (SEED_PD, diverges: see
    docs/studies/magnetic_pointing.md) or the PD that steers the along-field error (FIELD_STEERING)."""

    SEED_PD = 0
    FIELD_STEERING = 1


class MagResidualMode(FwEnum, namespace="Components"):
    """Residual-dipole feed-forward on the magnetorquers in POINTING: none (OFF), the ground-calibrated
    MAG_RESIDUAL_DIPOLE_X/Y/Z (PARAMETER), or the on-board torque-balance estimate (ESTIMATE; the
    parameters until the estimate is ready)."""

    OFF = 0
    PARAMETER = 1
    ESTIMATE = 2


class WheelFeedForward(FwEnum, namespace="Components"):
    """What the wheel law feeds forward: a moving target's own torque ``I (α_r − ω × ω_r)`` (REFERENCE), that
    plus the gyroscopic ``ω × (I ω + h_w)`` (REFERENCE_GYROSCOPIC), or both plus minus the modelled
    gravity-gradient torque ``3 μ/r³ r̂ × (I r̂)`` (REFERENCE_GYROSCOPIC_GRAVITY; the last two also for an
    inertial target)."""

    REFERENCE = 0
    REFERENCE_GYROSCOPIC = 1
    REFERENCE_GYROSCOPIC_GRAVITY = 2


class BodyAxis(FwEnum, namespace="Components"):
    """A body axis a target points (``control.targets.BODY_AXES``)."""

    PLUS_X = 0
    MINUS_X = 1
    PLUS_Y = 2
    MINUS_Y = 3
    PLUS_Z = 4
    MINUS_Z = 5


class PointingReference(FwEnum, namespace="Components"):
    """The reference POINTING follows (``control.targets.LABELS``): an inertial attitude, nadir (LVLH), a
    ground station in view, the nadir fallback of a station out of view, or the Sun."""

    INERTIAL = 0
    NADIR = 1
    GROUND_STATION = 2
    STATION_FALLBACK = 3
    SUN = 4


class TargetKind(FwEnum, namespace="Components"):
    """The kind of target commanded (``control.targets.TARGET_KINDS``)."""

    INERTIAL = 0
    NADIR = 1
    GROUND_STATION = 2
    SUN = 3


class ModeChangeReason(FwEnum, namespace="Components"):
    """Why the mode changed (argument of ControlModeChanged)."""

    COMMAND = 0
    AUTO_START = 1
    RATE_HIGH = 2
    RATE_LOW = 3
    SPIN_STABLE_REACHED = 4
    ATTITUDE_LOST = 5
    SYSTEM_SAFE_MODE = 6
    KNOWLEDGE_RESTORED = 7


class AlbedoUnavailableReason(FwEnum, namespace="Components"):
    """Why the ADCS component published the uncorrected Sun vector (argument of AlbedoCorrectionUnavailable): no
    ephemeris (the Sun, the position and the field model's Earth angle), no magnetometer reading, a magnetometer
    sample older than SUN_FIELD_MAX_AGE, the sub-satellite point dark (eclipse: no albedo to take out), or the
    field within 10° of the Sun line with no attitude to carry on the gyro (TRIAD undefined)."""

    NO_EPHEMERIS = 0
    NO_MAGNETOMETER = 1
    MAGNETOMETER_STALE = 2
    EARTH_DARK = 3
    FIELD_ALONG_SUN = 4


class Vector3(Array, namespace="Components", elem=F64, size=3):
    """Three F64 components in the body frame (unit given by the channel)."""


class WheelValues(Array, namespace="Components", elem=F64, size=MAX_WHEELS):
    """One F64 per wheel (unit given by the channel); unused wheels read 0."""


class Quaternion(Struct, namespace="Components"):
    """An attitude quaternion ``q_BN``, scalar first."""

    q0: F64
    q1: F64
    q2: F64
    q3: F64


class AngularVelocity(Struct, namespace="Drv"):
    """A gyro reading ``x, y, z`` in rad/s (ω_BN expressed in the body frame)."""

    x: F64
    y: F64
    z: F64


#: Angular velocity in rad/s; returns ``Result(AngularVelocity, Success)`` (the IMU manager's port).
AngularVelocityGet = PortType("Components.AngularVelocityGet", returns=Result)


class Ephemeris(Struct, namespace="Drv"):
    """Where the spacecraft is: position ``rx, ry, rz`` (m) and velocity ``vx, vy, vz`` (m/s) in N, the Earth
    rotation angle ``earthAngle`` (rad) and the Sun's unit direction ``sunX, sunY, sunZ`` in N."""

    rx: F64
    ry: F64
    rz: F64
    vx: F64
    vy: F64
    vz: F64
    earthAngle: F64
    sunX: F64
    sunY: F64
    sunZ: F64


#: The ephemeris now; returns ``Result(Ephemeris, Success)`` (an on-board orbit propagator or GPS).
EphemerisGet = PortType("Drv.EphemerisGet", returns=Result)


class SunVector(Struct, namespace="Components"):
    """The Sun's direction from the face light sensors: unit vector ``x, y, z`` in B, ``valid`` (false: eclipse or
    no usable reading; the vector is then the last valid one or zero), ``litFaces`` (sensors above the lit
    threshold) and ``timestamp`` (when the sensors were read)."""

    x: F64
    y: F64
    z: F64
    valid: BOOL
    litFaces: U8
    timestamp: Time


#: The latest Sun vector; returns ``Result(SunVector, Success)`` (the ADCS light-sensor component).
SunVectorGet = PortType("Components.SunVectorGet", returns=Result)

