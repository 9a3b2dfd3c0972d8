"""CourseworkController: seed 004's three detumbling controllers as one passive F´ component.

Behaviour and requirements: ``docs/components/coursework_controller.md``. The laws are
:mod:`detumble.control.coursework` (in the report's own convention); this module adapts them to
ports, parameters, commands, events and telemetry, so that the flight software flies exactly what
``fprime-lite sim --law cross_product|beta_pd|wheels_pd`` flies plant-only.

Each ``run`` (the deployment schedules it at the coursework's 100 Hz control rate) is one control
cycle: read the magnetometer (gauss → T), the gyro (rad/s), and for the wheel law the star tracker
(q_BN), the orbit frame (q_ON) and the three wheels' momenta; compute; command the torque rods
(A·m², each axis clipped to ``DIPOLE_LIMIT``) and the wheels (N·m, limited as the report does).
A failed read, a non-finite result or an exception inside the cycle puts the actuators safe (rods
0, wheel torques 0), raises a throttled WARNING_HI and the next cycle tries again; an exception
(a non-finite result is one) is also reported (``report_fault``: HandlerFault, HandlerFaults).
"""
from __future__ import annotations

import math

from fprime_lite import (BOOL, F64, Channel, CmdResponse, Event, FwEnum, OutputPort, Param, PassiveComponent, Sched,
                         Severity, String, sync_command, sync_input)

from detumble.components.attitude_types import AngularVelocityGet, Vector3
from detumble.components.types import (AttitudeGet, DipoleMoment, DipoleMomentSet, MagneticFieldGet, OrbitFrameGet,
                                       Success, WheelStateGet, WheelTorqueSet)
from detumble.control import coursework as cw
from detumble.control.units import TESLA_PER_GAUSS

__all__ = ["CourseworkController", "CourseworkLaw", "WheelError"]

_ZERO = (0.0, 0.0, 0.0)
_SUCCESS = Success.SUCCESS
_WHEEL_LABELS = ("wheel 0", "wheel 1", "wheel 2")  # what a failed wheel read names
_isfinite = math.isfinite


class CourseworkLaw(FwEnum, namespace="Components"):
    """Which of seed 004's controllers flies (OFF: actuators at zero)."""

    OFF = 0
    CROSS_PRODUCT = 1
    BETA_PD = 2
    WHEELS_PD = 3


class WheelError(FwEnum, namespace="Components"):
    """The wheel law's quaternion error: the report's eq. 25 as written, or the shortest path."""

    REPORT = 0
    SHORTEST_PATH = 1


# Read once: an enum class attribute costs a metaclass lookup, and the cycle compares three a call.
_OFF, _CROSS_PRODUCT, _BETA_PD = CourseworkLaw.OFF, CourseworkLaw.CROSS_PRODUCT, CourseworkLaw.BETA_PD


def _quat_conj_mul(p, q):
    """``conj(p) ⊗ q``, the Hamilton product (scalar first, the plant's convention) of the
    conjugate of ``p`` and ``q``: the same floats as conjugating first and multiplying (negating is
    exact, and ``a - (-b)`` rounds as ``a + b``)."""
    return (p[0] * q[0] + p[1] * q[1] + p[2] * q[2] + p[3] * q[3],
            p[0] * q[1] - p[1] * q[0] - p[2] * q[3] + p[3] * q[2],
            p[0] * q[2] + p[1] * q[3] - p[2] * q[0] - p[3] * q[1],
            p[0] * q[3] - p[1] * q[2] + p[2] * q[1] - p[3] * q[0])


def _quat_conj_mul_scalar_last(p, q):
    """``conj(p) ⊗ q`` as :func:`_quat_conj_mul` computes it (``p``, ``q`` scalar first), returned in
    the report's scalar-last order: ``from_plant_quaternion(_quat_conj_mul(p, q))`` without the
    reordering call (its ``float()`` is left to the law, which applies it to what it is given)."""
    return (p[0] * q[1] - p[1] * q[0] - p[2] * q[3] + p[3] * q[2],
            p[0] * q[2] + p[1] * q[3] - p[2] * q[0] - p[3] * q[1],
            p[0] * q[3] - p[1] * q[2] + p[2] * q[1] - p[3] * q[0],
            p[0] * q[0] + p[1] * q[1] + p[2] * q[2] + p[3] * q[3])


class CourseworkController(PassiveComponent):
    """Seed 004's controllers: ``LAW`` chooses, the parameters are the report's gains."""

    magneticFieldGet = OutputPort(MagneticFieldGet)
    angularVelocityGet = OutputPort(AngularVelocityGet)
    attitudeGet = OutputPort(AttitudeGet)
    orbitFrameGet = OutputPort(OrbitFrameGet)
    wheelStateGet = OutputPort(WheelStateGet, size=3)
    wheelTorqueSet = OutputPort(WheelTorqueSet, size=3)
    dipoleSet = OutputPort(DipoleMomentSet)

    LAW = Param(CourseworkLaw, default=CourseworkLaw.OFF)
    CROSS_PRODUCT_GAIN = Param(F64, default=146.0, units="A·m²/(rad/s·T)")  # k of M = k (ω × B), body frame
    BETA_KS = Param(F64, default=990.0, units="A·m²/(rad/s)")   # K_s, on the body-y rate error
    BETA_KD = Param(F64, default=0.06, units="A·m²/(rad/s)")    # K_d, on β̇
    BETA_SWITCHED = Param(BOOL, default=True)        # eq. 23 or 24, as the equations and figures (True); both (False)
    WHEEL_KP = Param(F64, default=5.0, units="1/s²")  # K_p (times I)
    WHEEL_KD = Param(F64, default=9.0, units="1/s")   # K_d (times I)
    WHEEL_ERROR = Param(WheelError, default=WheelError.SHORTEST_PATH)  # REPORT: eq. 25 as written (the long way)
    INERTIA_XX = Param(F64, default=1.67e-3, units="kg·m², body frame")  # principal (products taken as zero)
    INERTIA_YY = Param(F64, default=1.67e-3, units="kg·m², body frame")
    INERTIA_ZZ = Param(F64, default=1.67e-3, units="kg·m², body frame")
    DIPOLE_LIMIT = Param(F64, default=1.0, units="A·m² per body axis")
    WHEEL_TORQUE_LIMIT = Param(F64, default=1e-3, units="N·m per wheel")
    WHEEL_MOMENTUM_LIMIT = Param(F64, default=0.1, units="N·m·s per wheel")
    DUMP_GAIN = Param(F64, default=0.0, units="1/s")  # magnetic momentum dumping with WHEELS_PD (0: none)

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """One control cycle (see the module docstring)."""
        law = self._law
        if law == _OFF:
            return
        try:
            self._cycle(law)
        except Exception as exc:  # noqa: BLE001 - a fault in the cycle must leave the actuators safe
            self.report_fault("run", exc)
            try:
                self._safe()
            except Exception as safing:  # noqa: BLE001 - reported, never raised into the rate group
                self.report_fault("run: safing", safing)
                return
            self.ControlFault(type(exc).__name__, str(exc)[:80])

    @sync_command()
    def SET_LAW(self, law: CourseworkLaw):
        """Fly ``law`` from the next cycle (OFF: actuators at zero). Same as LAW_PRM_SET, plus an event."""
        self.LAW.set(law)
        self._select(CourseworkLaw(law))
        return CmdResponse.OK

    @sync_command()
    def SET_TARGET(self, q0: F64, q1: F64, q2: F64, q3: F64):
        """The wheel law's target attitude relative to the orbit frame, ``q_BO`` scalar first;
        refused (VALIDATION_ERROR) unless it is a unit quaternion within 1e-6."""
        q = (q0, q1, q2, q3)
        norm = math.sqrt(sum(c * c for c in q)) if all(math.isfinite(c) for c in q) else math.nan
        if not abs(norm - 1.0) <= 1e-6:
            self.TargetRejected(q0, q1, q2, q3)
            return CmdResponse.VALIDATION_ERROR
        self._target = q
        self._rebuild()
        self.TargetSet(q0, q1, q2, q3)
        return CmdResponse.OK

    LawChanged = Event(Severity.ACTIVITY_HI, "Coursework law now {}", law=CourseworkLaw)
    TargetSet = Event(Severity.ACTIVITY_HI, "Wheel target q_BO set to ({.6f}, {.6f}, {.6f}, {.6f})",
                      q0=F64, q1=F64, q2=F64, q3=F64)
    TargetRejected = Event(Severity.WARNING_LO, "Target ({}, {}, {}, {}) is not a unit quaternion; kept the old one",
                           q0=F64, q1=F64, q2=F64, q3=F64)
    SensorReadFailed = Event(Severity.WARNING_HI, "{} read failed; actuators safe", sensor=String(40), throttle=10)
    ControlFault = Event(Severity.WARNING_HI, "Control cycle raised {}: {}; actuators safe", kind=String(40),
                         text=String(80), throttle=10)

    Law = Channel(CourseworkLaw, update="on change")
    DipoleCommand = Channel(Vector3)        # A·m², body frame, after the limits
    WheelTorqueCommand = Channel(Vector3)   # N·m per wheel (x, y, z), after the limits
    Beta = Channel(F64)                     # rad: angle between body y and the field (BETA_PD)

    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self._law = CourseworkLaw.OFF
        self._target = (1.0, 0.0, 0.0, 0.0)
        self._beta: cw.BetaPd | None = None
        self._wheels: cw.WheelsPd | None = None

    # --- parameters ----------------------------------------------------------------------------

    def parameters_loaded(self) -> None:
        self._select(CourseworkLaw(self.LAW.value))

    def parameter_updated(self, param_id: int) -> None:
        self._select(CourseworkLaw(self.LAW.value))

    def _select(self, law: CourseworkLaw) -> None:
        changed = law != self._law
        self._law = law
        self._rebuild()
        if changed:
            self._safe()
            self.LawChanged(law)
        self.Law.write(law)

    def _rebuild(self) -> None:
        """New law objects from the parameters (their memory starts again)."""
        self._beta = cw.BetaPd(self.BETA_KS.value, self.BETA_KD.value, switched=bool(self.BETA_SWITCHED.value))
        inertia = ((self.INERTIA_XX.value, 0.0, 0.0), (0.0, self.INERTIA_YY.value, 0.0),
                   (0.0, 0.0, self.INERTIA_ZZ.value))
        self._wheels = cw.WheelsPd(self.WHEEL_KP.value, self.WHEEL_KD.value, inertia,
                                   cw.from_plant_quaternion(self._target),
                                   shortest_path=self.WHEEL_ERROR.value == WheelError.SHORTEST_PATH)

    # --- the cycle -----------------------------------------------------------------------------

    def _cycle(self, law: CourseworkLaw) -> None:
        read = self._read
        field = read(self.magneticFieldGet, "magnetometer")
        rate = read(self.angularVelocityGet, "gyro")
        if field is None or rate is None:
            return
        w_B = (rate.x, rate.y, rate.z)
        if law == _CROSS_PRODUCT:
            b_B = (field.x * TESLA_PER_GAUSS, field.y * TESLA_PER_GAUSS, field.z * TESLA_PER_GAUSS)
            self._command_dipole(cw.cross_product_dipole(self.CROSS_PRODUCT_GAIN.value, w_B, b_B))
        elif law == _BETA_PD:
            assert self._beta is not None
            b_B = (field.x * TESLA_PER_GAUSS, field.y * TESLA_PER_GAUSS, field.z * TESLA_PER_GAUSS)
            m = self._beta.dipole(field.timestamp.total_us * 1e-6, w_B, b_B)
            if self._beta.previous is not None:
                self.Beta.write(self._beta.previous[1])
            self._command_dipole(m)
        else:  # the wheel law needs no b_B here (with DUMP_GAIN > 0 it reads the field again)
            self._wheel_cycle(w_B)

    def _wheel_cycle(self, w_B) -> None:
        read = self._read
        attitude = read(self.attitudeGet, "star tracker")
        frame = read(self.orbitFrameGet, "orbit frame")
        wheels = self.wheelStateGet
        s0 = read(wheels, _WHEEL_LABELS[0], 0)  # all three read, in order, whatever the others gave
        s1 = read(wheels, _WHEEL_LABELS[1], 1)
        s2 = read(wheels, _WHEEL_LABELS[2], 2)
        if attitude is None or frame is None or s0 is None or s1 is None or s2 is None or not attitude.valid:
            if attitude is not None and not attitude.valid:
                self._safe()
                self.SensorReadFailed("star tracker (no valid solution)")
            return
        q_BO = _quat_conj_mul_scalar_last((frame.q0, frame.q1, frame.q2, frame.q3),
                                          (attitude.q0, attitude.q1, attitude.q2, attitude.q3))
        h = (s0.momentum, s1.momentum, s2.momentum)
        law = self._wheels
        assert law is not None
        law.n = frame.n
        torque = cw.limit_wheel_torque(law.torque(q_BO, w_B, h), h, self.WHEEL_TORQUE_LIMIT.value,
                                       self.WHEEL_MOMENTUM_LIMIT.value)
        t0, t1, t2 = torque
        if not (_isfinite(t0) and _isfinite(t1) and _isfinite(t2)):
            raise ArithmeticError(f"non-finite wheel torque {torque}")
        set_torque = self.wheelTorqueSet
        set_torque[0](t0)
        set_torque[1](t1)
        set_torque[2](t2)
        self.WheelTorqueCommand.write(Vector3(torque))
        if self.DUMP_GAIN.value > 0.0:
            field = read(self.magneticFieldGet, "magnetometer")
            if field is not None:
                b_B = (field.x * TESLA_PER_GAUSS, field.y * TESLA_PER_GAUSS, field.z * TESLA_PER_GAUSS)
                self._command_dipole(cw.dumping_dipole(self.DUMP_GAIN.value, h, b_B))

    def _command_dipole(self, m) -> None:
        m = cw.clip_dipole(m, self.DIPOLE_LIMIT.value)
        if not (_isfinite(m[0]) and _isfinite(m[1]) and _isfinite(m[2])):
            raise ArithmeticError(f"non-finite dipole {m}")
        self.dipoleSet[0](DipoleMoment(*m))
        self.DipoleCommand.write(Vector3(m))

    def _read(self, port, what: str, index: int = 0):
        value, condition = port[index]()
        if condition != _SUCCESS:
            self._safe()
            self.SensorReadFailed(what)
            return None
        return value

    def _safe(self) -> None:
        """Rods and wheels to zero (what is connected)."""
        if self.is_connected("dipoleSet", 0):
            self.dipoleSet[0](DipoleMoment(*_ZERO))
        for i in range(3):
            if self.is_connected("wheelTorqueSet", i):
                self.wheelTorqueSet[i](0.0)
