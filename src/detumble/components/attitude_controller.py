"""AttitudeController: seed 003's three-mode ADCS "brain" as a passive F´ component (namespace ``Components``).

The controller is :class:`detumble.control.three_mode.ThreeModeLaw` (framework-free; ``fprime-lite sim --law
adcs`` flies it too). This module declares what the ground sees (``docs/components/attitude_controller.md``) and
adapts the law to it: the component is the law's ``ControllerIo`` and ``DipoleProvider`` (its ports) and its
``Notify`` (events, the cycle's telemetry), and hands it the parameter values when they load and at every
PRM_SET (they act from the next cycle). ``run`` is on the 50 Hz rate group; ``tlmRun`` (1 Hz, just before
TlmChan's ``Run``) writes the cycles' telemetry (:meth:`AttitudeController.cycle_done`). Units: rad/s inside,
deg/s in parameters and telemetry; field gauss at the port; N·m, N·m·s, A·m²; quaternions ``q_BN`` scalar first.
"""

from __future__ import annotations

import math

from fprime_lite import (F64, U32, Channel, CmdResponse, Event, OutputPort, Param, PassiveComponent, Sched,
                         Severity, String, sync_command, sync_input)

from detumble.components.attitude_types import (MAX_WHEELS, AngularVelocityGet, AttitudeEstimator, BodyAxis,
                                                ControlAutonomy, ControlMode, EphemerisGet, MagPointingLaw,
                                                MagResidualMode, ModeChangeReason, PointingActuator,
                                                PointingReference, Quaternion, RateSource, SpinLaw, SunVectorGet,
                                                TargetKind, Vector3, WheelFeedForward, WheelValues)
from detumble.components.types import (AttitudeGet, DipoleMomentGet, GetSystemMode, MagneticFieldGet,
                                       StartMagnetorquer, StopMagnetorquer, Success, SystemMode, WheelEnableSet,
                                       WheelStateGet, WheelTorqueSet)
from detumble.control import attitude_defaults as _defaults
from detumble.control.mekf import Mekf
from detumble.control.spin import spin_axis_error_deg
from detumble.control.targets import Ephemeris
from detumble.control.three_mode import POINTING, SUN_SAFE, XYZ, ThreeModeLaw

__all__ = ["AttitudeController", "BORESIGHT_B"]

#: The body axis SET_TARGET_DIRECTION points (the seed's "point Z-axis at Sun/Ground").
BORESIGHT_B = _defaults.BORESIGHT_B
_SUCCESS = Success.SUCCESS
_MODES, _AUTONOMIES = tuple(ControlMode), tuple(ControlAutonomy)
_ENUMS = {"SPIN_LAW": SpinLaw, "POINTING_ACTUATOR": PointingActuator, "ESTIMATOR": AttitudeEstimator,
          "RATE_SOURCE": RateSource, "MAG_POINTING_LAW": MagPointingLaw, "MAG_RESIDUAL_MODE": MagResidualMode,
          "WHEEL_FEED_FORWARD": WheelFeedForward, "SUN_SAFE_AXIS": BodyAxis}
_COILS = ("xPlus", "xMinus", "yPlus", "yMinus", "zMinus")
_isfinite = math.isfinite


def _parameter(name: str) -> Param:
    """Parameter ``name`` as control.attitude_defaults gives it (default, units, range)."""
    units, low, high, finite = _defaults.PARAMETERS[name]
    enum = _ENUMS.get(name)
    if enum is not None:
        return Param(enum, default=enum[str(_defaults.DEFAULTS[name])])
    return Param(U32 if name == "CYCLE_TICKS" else F64, default=_defaults.DEFAULTS[name], low=low, high=high,
                 finite=finite, units=units)


def _read(out, index: int = 0):
    """What the ``ref condition`` output ``out[index]`` returns, or None when it fails or is not connected."""
    if out.targets[index] is None:
        return None
    value, condition = out.calls[index]()
    return value if condition == _SUCCESS else None


def _finite3(v) -> bool:
    """``v.x``, ``v.y``, ``v.z`` are finite numbers."""
    try:
        return _isfinite(v.x) and _isfinite(v.y) and _isfinite(v.z)
    except TypeError:
        return False


def _pad(values) -> list:
    out = [float(v) for v in values][:MAX_WHEELS]
    return out + [0.0] * (MAX_WHEELS - len(out))


class AttitudeController(PassiveComponent):
    """DETUMBLE → SPIN_STABLE → POINTING, with every trigger a parameter. ``wheel_axes``: the wheels' unit spin
    axes in B, one per connected wheel port index (default x, y, z)."""

    # --- commands (the law's; refusals in the component page) ----------------------------------

    @sync_command()
    def FORCE_MODE(self, mode: ControlMode):
        """Switch to ``mode`` and stay there (MANUAL); POINTING refused without attitude or needed wheels, SUN_SAFE
        without the light sensors' Sun vector (sunVectorGet)."""
        return CmdResponse[self.law.force_mode(int(mode))]

    @sync_command()
    def SET_AUTO(self):
        """Hand the mode to the seed's triggers (AUTO); from IDLE the next cycle starts DETUMBLE."""
        return CmdResponse[self.law.set_auto()]

    @sync_command()
    def SET_TARGET_QUATERNION(self, q0: F64, q1: F64, q2: F64, q3: F64):
        """Set the POINTING target ``q_TN`` (scalar first): unit within 1e-3, re-normalised."""
        return CmdResponse[self.law.set_target_quaternion((q0, q1, q2, q3))]

    @sync_command()
    def SET_TARGET_DIRECTION(self, x: F64, y: F64, z: F64):
        """Point the body +Z axis along the inertial direction ``(x, y, z)`` by the smallest rotation."""
        return CmdResponse[self.law.set_target_direction(x, y, z)]

    @sync_command()
    def SET_TARGET_NADIR(self, primary: BodyAxis, secondary: BodyAxis):
        """Point body ``primary`` at nadir and ``secondary`` along the velocity (LVLH); needs the ephemeris."""
        return CmdResponse[self.law.set_target_nadir(int(primary), int(secondary))]

    @sync_command()
    def SET_TARGET_GROUND_STATION(self, latitude: F64, longitude: F64, altitude: F64, primary: BodyAxis,
                                  secondary: BodyAxis):
        """Track a ground station (geodetic deg, deg, m) with ``primary`` while in view (GS_MIN_ELEVATION),
        ``secondary`` along the velocity; nadir with the same axes otherwise."""
        return CmdResponse[self.law.set_target_ground_station(latitude, longitude, altitude, int(primary),
                                                             int(secondary))]

    @sync_command()
    def SET_TARGET_SUN(self, primary: BodyAxis, secondary: BodyAxis):
        """Point body ``primary`` at the Sun, ``secondary`` toward the orbit normal; needs the ephemeris."""
        return CmdResponse[self.law.set_target_sun(int(primary), int(secondary))]

    # --- parameters: control.attitude_defaults.PARAMETERS, in the dictionary's order -----------

    for _name in _defaults.PARAMETERS:
        locals()[_name] = _parameter(_name)
    del _name

    # --- ports ---------------------------------------------------------------------------------

    angularVelocityGet = OutputPort(AngularVelocityGet)
    magneticFieldGet = OutputPort(MagneticFieldGet)
    attitudeGet = OutputPort(AttitudeGet)
    #: Optional: when connected (to a BDotDetumble), DETUMBLE takes its dipole instead of K_BDOT's.
    dipoleMomentGet = OutputPort(DipoleMomentGet)
    for _coil in _COILS:  # the five coil drivers (no Z+ coil)
        locals()[f"{_coil}Start"] = OutputPort(StartMagnetorquer)
        locals()[f"{_coil}Stop"] = OutputPort(StopMagnetorquer)
    del _coil
    wheelTorqueSet = OutputPort(WheelTorqueSet, size=MAX_WHEELS)
    wheelStateGet = OutputPort(WheelStateGet, size=MAX_WHEELS)
    wheelEnableSet = OutputPort(WheelEnableSet, size=MAX_WHEELS)
    #: Optional: the ephemeris (orbit, Earth angle, Sun) the moving targets need.
    ephemerisGet = OutputPort(EphemerisGet)
    #: Optional: the light sensors' Sun vector (the ADCS component); SUN_SAFE needs it.
    sunVectorGet = OutputPort(SunVectorGet)
    #: Optional: the spacecraft mode (ModeManager.getMode); its SAFE_MODE puts the controller in SUN_SAFE.
    getSystemMode = OutputPort(GetSystemMode)

    # --- events --------------------------------------------------------------------------------

    ControlModeChanged = Event(Severity.ACTIVITY_HI, "Attitude mode {} -> {} ({})",
                               from_mode=ControlMode, to_mode=ControlMode, reason=ModeChangeReason)
    AutonomyChanged = Event(Severity.ACTIVITY_HI, "Attitude autonomy set to {}", autonomy=ControlAutonomy)
    TargetSet = Event(Severity.ACTIVITY_HI, "Pointing target q_TN = ({.6f}, {.6f}, {.6f}, {.6f})",
                      q0=F64, q1=F64, q2=F64, q3=F64)
    TargetNotUnitQuaternion = Event(Severity.WARNING_LO,
                                    "Target ({}, {}, {}, {}) refused: norm {} is not 1 (within 1e-3)",
                                    q0=F64, q1=F64, q2=F64, q3=F64, norm=F64, throttle=5)
    TargetDirectionInvalid = Event(Severity.WARNING_LO, "Target direction ({}, {}, {}) refused: not a non-zero "
                                   "finite vector", x=F64, y=F64, z=F64, throttle=5)
    NoAttitudeKnowledge = Event(Severity.WARNING_LO, "No attitude knowledge (star tracker): pointing not available",
                                throttle=5)
    ModeUnavailableNoWheels = Event(Severity.WARNING_LO, "Mode {} needs reaction wheels and none answer",
                                    mode=ControlMode, throttle=5)
    AttitudeKnowledgeLost = Event(Severity.WARNING_HI, "Attitude knowledge lost while pointing: to SUN_SAFE (with "
                                  "light sensors) or SPIN_STABLE", throttle=5)
    GyroRetrievalFailed = Event(Severity.WARNING_LO, "Failed to retrieve angular velocity.", throttle=5)
    MagneticFieldRetrievalFailed = Event(Severity.WARNING_LO, "Failed to retrieve magnetic field.", throttle=5)
    DipoleMomentRetrievalFailed = Event(Severity.WARNING_LO, "Failed to retrieve the B-dot dipole moment.",
                                        throttle=5)
    WheelCommandFailed = Event(Severity.WARNING_LO, "Wheel {} did not accept its command", wheel=U32, throttle=5)
    EstimatorSelected = Event(Severity.ACTIVITY_HI, "Attitude estimator {} (attitude and bias carried over)",
                              estimator=AttitudeEstimator)
    AttitudeReinitialised = Event(Severity.WARNING_LO, "MEKF attitude re-initialised on the star tracker (residual or "
                                  "3-sigma above 5 deg)", throttle=5)
    InertiaModelRefused = Event(Severity.WARNING_LO, "INERTIA_* parameters do not form a positive definite matrix: "
                                "the rate observer keeps its previous model", throttle=1)
    WheelLimitReached = Event(Severity.WARNING_LO, "A wheel torque or momentum limit cut the requested torque",
                              throttle=5)
    ResidualDipoleEstimated = Event(Severity.ACTIVITY_LO, "Residual dipole estimate ready: ({}, {}, {}) A m^2",
                                    x=F64, y=F64, z=F64)
    ResidualDipoleEstimateRefused = Event(Severity.WARNING_LO, "Residual dipole estimate ({}, {}, {}) A m^2 beyond the "
                                          "coil limits or not finite: feed-forward uses MAG_RESIDUAL_DIPOLE_*",
                                          x=F64, y=F64, z=F64, throttle=5)

    TargetNadirSet = Event(Severity.ACTIVITY_HI, "Pointing target: {} to nadir, {} along the velocity",
                           primary=BodyAxis, secondary=BodyAxis)
    TargetStationSet = Event(Severity.ACTIVITY_HI, "Pointing target: ground station at {.4f} deg, {.4f} deg, {.1f} m "
                             "with {} ({} along the velocity)", latitude=F64, longitude=F64, altitude=F64,
                             primary=BodyAxis, secondary=BodyAxis)
    TargetSunSet = Event(Severity.ACTIVITY_HI, "Pointing target: {} to the Sun, {} toward the orbit normal",
                         primary=BodyAxis, secondary=BodyAxis)
    TargetAxesInvalid = Event(Severity.WARNING_LO, "Target axes {} and {} refused: give two perpendicular axes",
                              primary=BodyAxis, secondary=BodyAxis, throttle=5)
    TargetStationInvalid = Event(Severity.WARNING_LO, "Ground station ({}, {}, {}) refused: latitude in [-90, 90] "
                                 "deg, longitude in [-180, 360] deg, altitude in [-500, 10000] m, all finite",
                                 latitude=F64, longitude=F64, altitude=F64, throttle=5)
    NoEphemeris = Event(Severity.WARNING_LO, "No ephemeris (ephemerisGet): nadir, ground-station and Sun targets "
                        "are not available", throttle=5)
    EphemerisRetrievalFailed = Event(Severity.WARNING_LO, "Failed to retrieve the ephemeris: holding the last "
                                     "reference attitude", throttle=5)
    TargetReferenceUndefined = Event(Severity.WARNING_LO, "The {} target's reference is undefined now (its two "
                                     "directions are parallel): holding the last reference attitude",
                                     kind=TargetKind, throttle=5)
    GroundStationInView = Event(Severity.ACTIVITY_LO, "Ground station in view: tracking it")
    GroundStationOutOfView = Event(Severity.ACTIVITY_LO, "Ground station out of view: pointing at nadir")
    SunSafeEntered = Event(Severity.WARNING_HI, "Entering SUN_SAFE ({}): turning SUN_SAFE_AXIS to the light sensors' "
                           "Sun vector", reason=ModeChangeReason)
    SunSafeExited = Event(Severity.ACTIVITY_HI, "Leaving SUN_SAFE for {} ({})", to_mode=ControlMode,
                          reason=ModeChangeReason)
    SunSensorsUnavailable = Event(Severity.WARNING_LO, "SUN_SAFE refused: no Sun vector source (sunVectorGet) is "
                                  "connected", throttle=5)
    SunVectorRetrievalFailed = Event(Severity.WARNING_LO, "Failed to retrieve the Sun vector: carrying the last one on "
                                     "the gyro", throttle=5)
    SunSpinLowered = Event(Severity.ACTIVITY_HI, "Sun held for SUN_HOLD_DWELL: lowering the SUN_SAFE spin to {} deg/s "
                           "(below the star tracker's rate limit)", spin_rate=F64)
    MagLqrTableFailed = Event(Severity.WARNING_LO, "The magnetorquer hold's gain table failed ({}): field steering, "
                              "next attempt in {} s", reason=String(80), retry_s=F64, throttle=5)

    # --- telemetry -----------------------------------------------------------------------------

    Mode = Channel(ControlMode)
    Autonomy = Channel(ControlAutonomy)
    AngularRate = Channel(F64, format="{.3f}")  # deg/s, |ω̂|
    PointingError = Channel(F64, format="{.4f}")  # deg, estimated, in POINTING
    SpinAxisError = Channel(F64, format="{.3f}")  # deg between ω̂ and +Z
    SpinRate = Channel(F64, format="{.3f}")  # deg/s, ω̂·ẑ
    DamperState = Channel(F64)  # seed w_d (rad/s), |ω_d| of the 3-axis damper, or the spin-rate error (rad/s)
    RequestedTorque = Channel(Vector3)  # N·m, B
    CommandedDipole = Channel(Vector3)  # A·m², B, after limits and drive-level rounding
    WheelTorqueCommand = Channel(WheelValues)  # N·m per wheel
    WheelMomentum = Channel(WheelValues)  # N·m·s per wheel
    TargetQuaternion = Channel(Quaternion)
    GyroBiasEstimate = Channel(Vector3)  # deg/s, B
    AttitudeValid = Channel(U32)  # 1 while the star tracker's attitude is recent
    AttitudeSigma3 = Channel(F64, format="{.5f}")  # deg, MEKF 3·√(trace P_θθ) (not written with COMPLEMENTARY)
    FieldLineRate = Channel(F64, format="{.5f}")  # deg/s, estimated |db̂/dt| of the inertial field direction
    ResidualDipole = Channel(Vector3)  # A·m², B: the residual-dipole feed-forward in use (MAG_RESIDUAL_MODE)
    ActiveTarget = Channel(PointingReference)  # the reference POINTING follows
    ReferenceRate = Channel(Vector3)  # deg/s, in the target frame: the reference's rate relative to N
    SunVectorEstimate = Channel(Vector3)  # unit, B: the Sun vector SUN_SAFE uses (carried on the gyro)
    SunPointingError = Channel(F64, format="{.3f}")  # deg, SUN_SAFE_AXIS to the Sun vector, in SUN_SAFE

    # --- construction and the law's plant I/O --------------------------------------------------

    def __init__(self, name: str, *, base_id: int = 0, wheel_axes=XYZ):
        super().__init__(name, base_id=base_id)
        if not 3 <= len(wheel_axes) <= MAX_WHEELS:
            raise ValueError(f"wheel_axes: give 3 to {MAX_WHEELS} unit axes, got {len(wheel_axes)}")
        # The output port arrays used every tick or cycle (``targets[i]`` says whether index i is
        # connected, ``calls[i]`` calls it), looked up once instead of by name on every call.
        self._start_ports = [self.output_port(f"{c}Start") for c in _COILS]
        self._stop_ports = [self.output_port(f"{c}Stop") for c in _COILS]
        self._gyro_port = self.output_port("angularVelocityGet")
        self._attitude_port = self.output_port("attitudeGet")
        self._field_port = self.output_port("magneticFieldGet")
        self._dipole_port = self.output_port("dipoleMomentGet")
        self._torque_ports = self.output_port("wheelTorqueSet")
        self._state_ports = self.output_port("wheelStateGet")
        self._enable_ports = self.output_port("wheelEnableSet")
        self._ephemeris_port = self.output_port("ephemerisGet")
        self._sun_port = self.output_port("sunVectorGet")
        self._system_mode_port = self.output_port("getSystemMode")
        self._wheels_enabled = False
        # The cycle's telemetry kept for tlmRun (see cycle_done): the cycles' records since its last call,
        # per group the first record a command's write leaves it, and the groups never written yet.
        self._tlm_deferred = False
        self._tlm_records: list[tuple] = []
        self._tlm_floors = [0] * len(_GROUPS)
        self._tlm_unwritten: tuple[int, ...] = ()
        self._tlm_leads = tuple(getattr(self, name) for name in _GROUP_LEADS)  # each group's first channel
        self.law = ThreeModeLaw(self, self, self, wheel_axes, {n: b.value for n, b in self.params.items()})

    def parameters_loaded(self) -> None:
        self.law.set_parameters({name: bound.value for name, bound in self.params.items()})

    def parameter_updated(self, local_id: int) -> None:
        self.parameters_loaded()

    mode = property(lambda self: _MODES[self.law.mode], doc="The mode (ControlMode).")
    autonomy = property(lambda self: _AUTONOMIES[self.law.autonomy], doc="MANUAL or AUTO (ControlAutonomy).")
    target = property(lambda self: self.law.target, doc="The POINTING target q_TN (None until set or captured).")
    dipole = property(lambda self: self.law.dipole, doc="The dipole the coils' present levels give, A·m² (B).")

    @sync_input(Sched)
    def run(self, context):
        """50 Hz tick of the law. A fault is reported (HandlerFault event, HandlerFaults channel) and
        the actuators are made safe (coils off, wheels at zero torque); the rate group goes on."""
        try:
            self.law.tick()
        except Exception as exc:  # noqa: BLE001 - the rate group must keep running
            self.report_fault("run", exc)
            try:
                self.law.safe()
            except Exception as again:  # noqa: BLE001 - nor may making the actuators safe stop it
                self.report_fault("run: safing", again)

    def now_us(self) -> int:
        return self.get_time().total_us

    def gyro(self):
        w = _read(self._gyro_port)
        return (float(w.x), float(w.y), float(w.z)) if w is not None and _finite3(w) else None

    def attitude(self):
        q = _read(self._attitude_port)
        return ((q.q0, q.q1, q.q2, q.q3), q.timestamp.total_us) if q is not None and q.valid else None

    def field(self):
        b = _read(self._field_port)
        return ((float(b.x), float(b.y), float(b.z)), b.timestamp.total_us) if b is not None and _finite3(b) else None

    def has_dipole_provider(self) -> bool:
        return self._dipole_port.targets[0] is not None

    def provider_dipole(self):
        m = _read(self._dipole_port)
        return (float(m.x), float(m.y), float(m.z)) if m is not None and _finite3(m) else None

    def wheel_count(self) -> int:
        """Wheels connected (torque and momentum ports both), in index order."""
        n = 0
        torque, state = self._torque_ports.targets, self._state_ports.targets
        for i in range(len(self.law.wheel_axes)):
            if torque[i] is not None and state[i] is not None:
                n += 1
        return n

    def wheel_momenta(self):
        """Each wheel's axial momentum (N·m·s) from its driver, or None when one does not answer."""
        momenta = []
        for i in range(len(self.law.wheel_axes)):
            state = _read(self._state_ports, i)
            try:
                if state is None or not _isfinite(state.momentum):
                    return None
            except TypeError:
                return None
            momenta.append(float(state.momentum))
        return tuple(momenta)

    def set_wheel_torques(self, u):
        """One motor torque (N·m) per wheel; the first non-zero command enables every wheel first."""
        if not self._wheels_enabled and any(t != 0.0 for t in u):
            enable = self._enable_ports
            for i in range(len(u)):
                if enable.targets[i] is not None and enable.calls[i](True) != _SUCCESS:
                    self.WheelCommandFailed(i)
            self._wheels_enabled = True
        sent = []
        targets, calls = self._torque_ports.targets, self._torque_ports.calls
        for i, torque in enumerate(u):
            if targets[i] is None:
                sent.append(0.0)
                continue
            torque = float(torque)
            if calls[i](torque) != _SUCCESS:
                self.WheelCommandFailed(i)
            elif self.WheelCommandFailed.count:
                self.WheelCommandFailed.clear_throttle()
            sent.append(torque)
        return tuple(sent)

    def ephemeris(self):
        e = _read(self._ephemeris_port)
        if e is None:
            return None
        values = (e.rx, e.ry, e.rz, e.vx, e.vy, e.vz, e.earthAngle, e.sunX, e.sunY, e.sunZ)
        try:
            if not all(_isfinite(v) for v in values):
                return None
        except TypeError:
            return None
        return Ephemeris((e.rx, e.ry, e.rz), (e.vx, e.vy, e.vz), e.earthAngle, (e.sunX, e.sunY, e.sunZ))

    def has_sun_sensor(self) -> bool:
        return self._sun_port.targets[0] is not None

    def sun_vector(self):
        s = _read(self._sun_port)
        if s is None:
            return None
        try:
            valid = bool(s.valid) and _isfinite(s.x) and _isfinite(s.y) and _isfinite(s.z)
            return (float(s.x), float(s.y), float(s.z)), valid, s.timestamp.total_us
        except (TypeError, AttributeError):
            return None

    def system_safe_mode(self):
        if self._system_mode_port.targets[0] is None:
            return None
        return self._system_mode_port.calls[0]() == SystemMode.SAFE_MODE

    def drive_coils(self, levels, dipole_B) -> None:
        for port, level in zip(self._start_ports, levels, strict=True):
            if port.targets[0] is not None:
                port.calls[0](level)

    def stop_coils(self) -> None:
        for port in self._stop_ports:
            if port.targets[0] is not None:
                port.calls[0]()

    # --- the law's events and telemetry ---------------------------------------------------------

    def event(self, name: str, *args) -> None:
        getattr(self, name)(*args)

    def clear_event(self, name: str) -> None:
        event = getattr(self, name)
        if event.count:
            event.clear_throttle()

    def mode_changed(self, old: int, new: int, reason: int) -> None:
        self.ControlModeChanged(_MODES[old], _MODES[new], ModeChangeReason(reason))
        self.Mode.write(_MODES[new])
        self._tlm_floors[_G_MODE] = len(self._tlm_records)  # no older cycle's Mode may follow this write

    def target_set(self, q) -> None:
        self.TargetSet(*q)
        self.TargetQuaternion.write(Quaternion(*q))
        self._tlm_floors[_G_TARGET] = len(self._tlm_records)

    def cycle_done(self) -> None:
        """The cycle's telemetry: written now (every cycle) until ``tlmRun`` has run once, then kept as the
        cycle's record for ``tlmRun`` to write (a channel's first write still happens on its cycle)."""
        record = self._cycle_record()
        if not self._tlm_deferred:
            for present, write in _GROUPS:
                if present is None or record[present] is not None:
                    write(self, record)
            return
        records = self._tlm_records
        records.append(record)
        if self._tlm_unwritten:
            self._first_writes(record)
        if len(records) >= TLM_RECORDS_MAX:
            self._write_telemetry()

    @sync_input(Sched)
    def tlmRun(self, context):
        """Write the telemetry of the cycles since the last call: each channel's value from the latest cycle
        that wrote it, time-tagged with that cycle's time (the writes the cycles made, less those TlmChan's
        next ``Run`` would not send). Scheduled just before ``tlmSend.Run`` in the group that sends (1 Hz);
        from its first call the cycles keep their telemetry for it. A fault is reported, never raised."""
        if not self._tlm_deferred:
            self._tlm_deferred = True
            self._tlm_unwritten = tuple(g for g, lead in enumerate(self._tlm_leads) if not lead.written)
        try:
            self._write_telemetry()
        except Exception as exc:  # noqa: BLE001 - the rate group must keep running
            self.report_fault("tlmRun", exc)

    def _cycle_record(self) -> tuple:
        """The cycle's telemetry values before conversion (see the ``_R_*`` indices): the time now and the
        law's values, each an immutable number or tuple the law replaces (never changes in place), None
        where the cycle writes no such channel."""
        law = self.law
        mode = law.mode
        f = law.filter
        pe, se = law.pointing_error_deg, law.sun_error_deg
        ref = law.reference
        spec = law.target_spec
        return (self.get_time(), mode, law.autonomy, law.omega,
                pe if mode == POINTING and _isfinite(pe) else None,
                law.damper_state, law.torque_request, law.dipole, law.wheel_torques, law.wheel_momenta, f.bias,
                law.attitude_valid,
                f.attitude_sigma3_rad if isinstance(f, Mekf) and f.q is not None else None,
                law.bdot_hat_B, law.residual_ff, law.sun_B,
                se if mode == SUN_SAFE and _isfinite(se) else None,
                ref, ref if ref is not None and spec is not None and spec.needs_ephemeris else None)

    def _first_writes(self, record: tuple) -> None:
        """Write now each group of ``record`` whose channels were never written, in the cycle's order, so
        that TlmChan first receives them when it did when every cycle wrote (its packets keep that order)."""
        still = []
        for g in self._tlm_unwritten:
            present, write = _GROUPS[g]
            if self._tlm_leads[g].written:
                continue
            if present is None or record[present] is not None:
                write(self, record)
            else:
                still.append(g)
        self._tlm_unwritten = tuple(still)

    def _write_telemetry(self) -> None:
        """Write each group from the latest record that has it (not older than a command's write of it)."""
        records, floors = self._tlm_records, self._tlm_floors
        self._tlm_records, self._tlm_floors = [], [0] * len(_GROUPS)
        last = len(records) - 1
        for g, (present, write) in enumerate(_GROUPS):
            floor = floors[g]
            if present is None:
                if last >= floor:
                    write(self, records[last])
                continue
            for i in range(last, floor - 1, -1):
                record = records[i]
                if record[present] is not None:
                    write(self, record)
                    break


#: Cycles kept for ``tlmRun`` before a cycle writes them itself (10 s at 50 Hz: it is not scheduled).
TLM_RECORDS_MAX = 500

# A cycle record's fields (AttitudeController._cycle_record).
(_R_TIME, _R_MODE, _R_AUTONOMY, _R_OMEGA, _R_POINTING_ERROR, _R_DAMPER, _R_TORQUE, _R_DIPOLE, _R_WHEEL_TORQUES,
 _R_WHEEL_MOMENTA, _R_BIAS, _R_ATTITUDE_VALID, _R_SIGMA3, _R_BDOT, _R_RESIDUAL, _R_SUN, _R_SUN_ERROR, _R_REFERENCE,
 _R_MOVING_REFERENCE) = range(19)


def _w_mode(c: AttitudeController, r: tuple) -> None:
    c.Mode.write(_MODES[r[_R_MODE]], r[_R_TIME])


def _w_autonomy(c: AttitudeController, r: tuple) -> None:
    c.Autonomy.write(_AUTONOMIES[r[_R_AUTONOMY]], r[_R_TIME])


def _w_rate(c: AttitudeController, r: tuple) -> None:
    w, t = r[_R_OMEGA], r[_R_TIME]
    c.AngularRate.write(math.degrees(math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])), t)
    c.SpinAxisError.write(spin_axis_error_deg(w), t)
    c.SpinRate.write(math.degrees(w[2]), t)


def _w_pointing_error(c: AttitudeController, r: tuple) -> None:
    c.PointingError.write(r[_R_POINTING_ERROR], r[_R_TIME])


def _w_commands(c: AttitudeController, r: tuple) -> None:
    t = r[_R_TIME]
    c.DamperState.write(float(r[_R_DAMPER]), t)
    c.RequestedTorque.write(Vector3(r[_R_TORQUE]), t)
    c.CommandedDipole.write(Vector3(r[_R_DIPOLE]), t)
    c.WheelTorqueCommand.write(WheelValues(_pad(r[_R_WHEEL_TORQUES])), t)


def _w_wheel_momentum(c: AttitudeController, r: tuple) -> None:
    c.WheelMomentum.write(WheelValues(_pad(r[_R_WHEEL_MOMENTA])), r[_R_TIME])


def _w_estimate(c: AttitudeController, r: tuple) -> None:
    b, t = r[_R_BIAS], r[_R_TIME]
    c.GyroBiasEstimate.write(Vector3([math.degrees(b[0]), math.degrees(b[1]), math.degrees(b[2])]), t)
    c.AttitudeValid.write(1 if r[_R_ATTITUDE_VALID] else 0, t)


def _w_sigma3(c: AttitudeController, r: tuple) -> None:
    c.AttitudeSigma3.write(math.degrees(r[_R_SIGMA3]), r[_R_TIME])


def _w_field_line_rate(c: AttitudeController, r: tuple) -> None:
    d = r[_R_BDOT]
    c.FieldLineRate.write(math.degrees(math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])), r[_R_TIME])


def _w_residual(c: AttitudeController, r: tuple) -> None:
    c.ResidualDipole.write(Vector3(r[_R_RESIDUAL]), r[_R_TIME])


def _w_sun(c: AttitudeController, r: tuple) -> None:
    c.SunVectorEstimate.write(Vector3(list(r[_R_SUN])), r[_R_TIME])


def _w_sun_error(c: AttitudeController, r: tuple) -> None:
    c.SunPointingError.write(r[_R_SUN_ERROR], r[_R_TIME])


def _w_target(c: AttitudeController, r: tuple) -> None:
    c.ActiveTarget.write(PointingReference(r[_R_REFERENCE].label), r[_R_TIME])


def _w_reference_rate(c: AttitudeController, r: tuple) -> None:
    w = r[_R_MOVING_REFERENCE].omega_R
    c.ReferenceRate.write(Vector3([math.degrees(w[0]), math.degrees(w[1]), math.degrees(w[2])]), r[_R_TIME])


def _w_target_quaternion(c: AttitudeController, r: tuple) -> None:
    c.TargetQuaternion.write(Quaternion(*r[_R_MOVING_REFERENCE].q_RN), r[_R_TIME])


#: The cycle's telemetry in the order a cycle writes it: (the record field that must not be None for the
#: cycle to write the group, or None: every cycle; the group's writer). Each group's channels are written
#: together by every cycle that writes one of them.
_GROUPS = ((None, _w_mode), (None, _w_autonomy), (_R_OMEGA, _w_rate), (_R_POINTING_ERROR, _w_pointing_error),
           (None, _w_commands), (_R_WHEEL_MOMENTA, _w_wheel_momentum), (None, _w_estimate),
           (_R_SIGMA3, _w_sigma3), (_R_BDOT, _w_field_line_rate), (None, _w_residual), (_R_SUN, _w_sun),
           (_R_SUN_ERROR, _w_sun_error), (_R_REFERENCE, _w_target), (_R_MOVING_REFERENCE, _w_reference_rate),
           (_R_MOVING_REFERENCE, _w_target_quaternion))
#: Each group's first channel (written first: the group was written when it was).
_GROUP_LEADS = ("Mode", "Autonomy", "AngularRate", "PointingError", "DamperState", "WheelMomentum",
                "GyroBiasEstimate", "AttitudeSigma3", "FieldLineRate", "ResidualDipole", "SunVectorEstimate",
                "SunPointingError", "ActiveTarget", "ReferenceRate", "TargetQuaternion")
_G_MODE, _G_TARGET = _GROUP_LEADS.index("Mode"), _GROUP_LEADS.index("TargetQuaternion")
