"""F´ types and port types of the detumble application (detumble.md §1–2).

Namespaces follow the flight FPP and the seed design documents:

* ``Components`` — the DetumbleManager's own types and the ports it declares or uses from other
  PROVES components: :class:`CoilShape`, :class:`DetumbleMode`, :class:`DetumbleState`,
  :class:`DetumbleStrategy`, :class:`HysteresisAxis`, :class:`SystemMode`, :class:`AngularUnit`;
  port types ``SetDetumbleMode``, ``SystemModeChanged``, ``GetSystemMode``,
  ``AngularVelocityMagnitudeGet``, ``MagneticFieldGet`` (seed 002 names it
  ``Components.MagneticFieldGet``) and ``SamplingPeriodGet``.
* ``Drv`` — driver-side types: :class:`MagneticField` (the magnetometer reading, ``Drv::MagneticField``
  in the flight code), :class:`DipoleMoment` and the ``DipoleMomentGet`` port (seed 002), and the
  magnetorquer driver ports ``StartMagnetorquer`` / ``StopMagnetorquer`` (flight FPP).
* ``Drv`` (reaction wheels, star tracker; see ``docs/components/reaction_wheel_driver.md`` and
  ``docs/components/star_tracker.md``): :class:`WheelMode`, :class:`WheelState`,
  :class:`AttitudeQuaternion`; ports ``WheelTorqueSet``, ``WheelSpeedSet``, ``WheelEnableSet``,
  ``WheelStateGet`` (one driver instance per wheel) and ``AttitudeGet``.
* ``Fw`` — :class:`Success` and :class:`TimeIntervalValue` are re-exported from the framework
  (:mod:`fprime_lite.model.fw_types`).

``ref condition: Success`` convention
-------------------------------------
In C++ these ports return a value *and* set an out-parameter ``Fw::Success& condition``. Python has
no out-parameters, so every such port here **returns a** :class:`Result` — a two-field named tuple
``(value, condition)``. ``condition`` is :class:`Success` (``SUCCESS``/``FAILURE``); ``value`` is
meaningful only when the condition is ``SUCCESS``. A failed read is therefore never confused with a
zero value. Providers may return ``Result(v, Success.SUCCESS)`` (or ``Result.success(v)`` /
``Result.failure()``) or any 2-sequence ``(value, condition)``; consumers unpack
``value, condition = port[0](...)``. The ``condition`` argument is removed from the port's argument
list (``AngularVelocityMagnitudeGet`` therefore takes only ``unit``).

Units at every port boundary are those of the flight code: magnetic field in **gauss** (sensor
frame = body frame), angular rate in deg/s or rad/s as requested by :class:`AngularUnit`, dipole
moment in **A·m²** (body frame), durations as ``TimeIntervalValue`` ``{seconds, useconds}``, coil
drive levels as signed I8 in −127…127 (full scale = the coil's maximum current).
"""

from __future__ import annotations

from typing import Any, NamedTuple

from fprime_lite.model.fw_types import Success, TimeIntervalValue

from detumble.control.coil_layout import CoilShape as _CoilOutline
from fprime_lite.model.ports import PortType
from fprime_lite.model.time import Time
from fprime_lite.model.types import BOOL, F64, I8, FwEnum, Struct

__all__ = [
    "Success", "TimeIntervalValue", "Result",
    "CoilShape", "DetumbleMode", "DetumbleState", "DetumbleStrategy", "HysteresisAxis",
    "SystemMode", "AngularUnit", "MagnetorquerFace", "MagneticField", "DipoleMoment",
    "SetDetumbleMode", "SystemModeChanged", "GetSystemMode", "AngularVelocityMagnitudeGet",
    "MagneticFieldGet", "SamplingPeriodGet", "StartMagnetorquer", "StopMagnetorquer",
    "DipoleMomentGet",
    "WheelMode", "WheelState", "WheelTorqueSet", "WheelSpeedSet", "WheelEnableSet", "WheelStateGet",
    "AttitudeQuaternion", "AttitudeGet", "OrbitFrame", "DipoleMomentSet", "OrbitFrameGet",
]


# --- Fw ------------------------------------------------------------------------------------------

# ``Success`` and ``TimeIntervalValue`` are the framework's own (``Fw``) types, re-exported here.


class Result(NamedTuple):
    """What a ``ref condition: Success`` port returns: ``(value, condition)``.

    ``value`` is meaningful only when ``condition`` is :attr:`Success.SUCCESS`.
    """

    value: Any
    condition: Success

    @property
    def ok(self) -> bool:
        """True when the read succeeded."""
        return self.condition == Success.SUCCESS

    @classmethod
    def success(cls, value: Any) -> "Result":
        return cls(value, Success.SUCCESS)

    @classmethod
    def failure(cls, value: Any = None) -> "Result":
        return cls(value, Success.FAILURE)


# --- Components enums ----------------------------------------------------------------------------


#: ``new_result(Result, (value, condition))`` is ``Result(value, condition)``: the named tuple's generated
#: ``__new__`` does exactly that, behind a Python frame (≈ 0.3 µs) that the drivers' read paths skip.
new_result = tuple.__new__

class CoilShape(FwEnum, namespace="Components"):
    """Shape of a magnetorquer coil (sets how its area is computed); the values are the coil
    arithmetic's (:class:`detumble.control.coil_layout.CoilShape`)."""

    RECTANGULAR = _CoilOutline.RECTANGULAR.value
    CIRCULAR = _CoilOutline.CIRCULAR.value


class DetumbleMode(FwEnum, namespace="Components"):
    """Operating mode: DISABLED forces the coils off; AUTO runs the state machine."""

    DISABLED = 0
    AUTO = 1


class DetumbleState(FwEnum, namespace="Components"):
    """State of the DetumbleManager state machine."""

    COOLDOWN = 0
    SENSING_ANGULAR_VELOCITY = 1
    SENSING_MAGNETIC_FIELD = 2
    ACTUATING_BDOT = 3
    ACTUATING_HYSTERESIS = 4


class DetumbleStrategy(FwEnum, namespace="Components"):
    """Strategy chosen from the angular-rate magnitude."""

    IDLE = 0
    BDOT = 1
    HYSTERESIS = 2


class HysteresisAxis(FwEnum, namespace="Components"):
    """Body axis driven full scale by the hysteresis (bang-bang) strategy."""

    X_AXIS = 0
    Y_AXIS = 1
    Z_AXIS = 2


class SystemMode(FwEnum, namespace="Components"):
    """Spacecraft-level mode published by the mode manager."""

    SAFE_MODE = 1
    NORMAL = 2


class MagnetorquerFace(FwEnum, namespace="Components"):
    """A face that carries a magnetorquer coil: the ground-visible form of
    :data:`detumble.control.coil_layout.COIL_FACES` (same names and numbers; there is no Z+ coil)."""

    X_PLUS = 0
    X_MINUS = 1
    Y_PLUS = 2
    Y_MINUS = 3
    Z_MINUS = 5


class AngularUnit(FwEnum, namespace="Components"):
    """Unit in which an angular-rate provider answers."""

    RAD_PER_SEC = 0
    DEG_PER_SEC = 1


# --- structs -------------------------------------------------------------------------------------

class MagneticField(Struct, namespace="Drv"):
    """A magnetometer reading: ``x, y, z`` in gauss (body frame), ``timestamp`` when it was taken."""

    x: F64
    y: F64
    z: F64
    timestamp: Time


class DipoleMoment(Struct, namespace="Drv"):
    """A commanded magnetic dipole moment, ``x, y, z`` in A·m² (body frame)."""

    x: F64
    y: F64
    z: F64


# --- port types ----------------------------------------------------------------------------------

#: Set the detumble mode (the SET_MODE command without a command response).
SetDetumbleMode = PortType("Components.SetDetumbleMode", mode=DetumbleMode)
#: Notification that the system mode changed.
SystemModeChanged = PortType("Components.SystemModeChanged", mode=SystemMode)
#: Query the current system mode.
GetSystemMode = PortType("Components.GetSystemMode", returns=SystemMode)
#: |ω| in the requested unit; returns ``Result(F64, Success)``.
AngularVelocityMagnitudeGet = PortType("Components.AngularVelocityMagnitudeGet", returns=Result,
                                       unit=AngularUnit)
#: Latest magnetometer reading; returns ``Result(MagneticField, Success)``.
MagneticFieldGet = PortType("Components.MagneticFieldGet", returns=Result)
#: Magnetometer output period; returns ``Result(TimeIntervalValue, Success)``.
SamplingPeriodGet = PortType("Components.SamplingPeriodGet", returns=Result)
#: Drive one coil at ``val`` (−127…127, sign = current direction); returns Success.
StartMagnetorquer = PortType("Drv.StartMagnetorquer", returns=Success, val=I8)
#: Switch one coil off; returns Success.
StopMagnetorquer = PortType("Drv.StopMagnetorquer", returns=Success)
#: Dipole moment to command; returns ``Result(DipoleMoment, Success)``.
DipoleMomentGet = PortType("Drv.DipoleMomentGet", returns=Result)


# --- reaction wheels and attitude knowledge (issue 12) --------------------------------------------

class WheelMode(FwEnum, namespace="Drv"):
    """What a reaction-wheel driver is doing: motor off, following a torque or a speed command."""

    DISABLED = 0
    TORQUE = 1
    SPEED = 2


class WheelState(Struct, namespace="Drv"):
    """One wheel's reported state. ``speed`` rad/s relative to the body; ``momentum`` N·m·s, the
    absolute axial momentum ``J_s (Ω + gᵀω)`` along the wheel's spin axis; ``torque`` N·m, the motor
    torque applied now (after the limits; the body feels −torque along the axis); ``mode``; and
    ``timestamp``, when the reading was taken."""

    speed: F64
    momentum: F64
    torque: F64
    mode: WheelMode
    timestamp: Time


class AttitudeQuaternion(Struct, namespace="Drv"):
    """An attitude solution ``q_BN`` (scalar first: ``q0`` real part; rotates N onto B) with
    ``valid`` (false: no solution, the quaternion is the last valid one) and ``timestamp`` (when the
    tracker took the image)."""

    q0: F64
    q1: F64
    q2: F64
    q3: F64
    valid: BOOL
    timestamp: Time


#: Command motor torque ``torque`` (N·m, along the wheel's spin axis); returns Success.
WheelTorqueSet = PortType("Drv.WheelTorqueSet", returns=Success, torque=F64)
#: Command wheel speed ``speed`` (rad/s relative to the body; the wheel's own loop); returns Success.
WheelSpeedSet = PortType("Drv.WheelSpeedSet", returns=Success, speed=F64)
#: Enable (true) or disable (false) the wheel's motor; returns Success.
WheelEnableSet = PortType("Drv.WheelEnableSet", returns=Success, enable=BOOL)
#: The wheel's state; returns ``Result(WheelState, Success)``.
WheelStateGet = PortType("Drv.WheelStateGet", returns=Result)
#: Latest attitude solution; returns ``Result(AttitudeQuaternion, Success)``.
AttitudeGet = PortType("Drv.AttitudeGet", returns=Result)


# --- ideal torque rods and the orbit frame (seed 004's coursework) ----------------------------------

class OrbitFrame(Struct, namespace="Drv"):
    """The orbit frame O relative to N (``q0`` real part; scalar first), the orbit rate ``n`` rad/s
    and when it was computed."""

    q0: F64
    q1: F64
    q2: F64
    q3: F64
    n: F64
    timestamp: Time


#: Command the ideal torque rods to ``dipole`` (A·m², body frame); returns Success.
DipoleMomentSet = PortType("Drv.DipoleMomentSet", returns=Success, dipole=DipoleMoment)
#: The orbit frame now; returns ``Result(OrbitFrame, Success)``.
OrbitFrameGet = PortType("Drv.OrbitFrameGet", returns=Result)
