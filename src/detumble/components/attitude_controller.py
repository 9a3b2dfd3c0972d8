"""AttitudeController: seed 003's three-mode ADCS "brain" as a passive fprime_lite component.

Behaviour and requirements: ``docs/components/attitude_controller.md``. The laws are plain
functions in :mod:`detumble.control` (quaternion math, B-dot, dampers, PD pointing, dipole
projection, wheel allocation, momentum dumping, the attitude filter); this module adapts them to
ports, parameters, commands, events and telemetry.

Timing: ``run`` is scheduled on the 50 Hz rate group. Every ``CYCLE_TICKS`` ticks (default 5, so
10 Hz) one control cycle runs on tick 0: read the gyro, the star tracker and the magnetometer,
update the attitude filter, choose the mode, compute and actuate. The coils are switched off on the
last tick of each cycle, so the magnetometer reading of the next cycle (one tick = 20 ms later; the
LIS2MDL samples at 100 Hz) is free of the coils' own field (their coupling into the magnetometer
is 30 times the Earth's field at full drive). Coils therefore drive 80 % of the time
(``(CYCLE_TICKS − 1)/CYCLE_TICKS``); wheels are commanded once per cycle and hold their torque.

Modes (``ControlMode``): IDLE (coils off, wheels at zero torque), DETUMBLE (B-dot),
SPIN_STABLE (``SPIN_LAW``), POINTING (quaternion PD on the wheels, or on the magnetorquers).
In AUTO the seed's triggers choose the mode; in MANUAL it stays where FORCE_MODE put it.

Frames and units: body frame B, inertial frame N; rates rad/s inside (deg/s in parameters and
telemetry, as the ground reads them); field tesla inside (gauss at the port); torque N·m; momentum
N·m·s; dipole A·m²; quaternions ``q_BN`` scalar first.
"""

from __future__ import annotations

import logging
import math

from fprime_lite import (F64, U32, Channel, CmdResponse, Event, OutputPort, Param, PassiveComponent, Sched,
                         Severity, sync_command, sync_input)

from detumble.components.attitude_types import (MAX_WHEELS, AngularVelocityGet, AttitudeEstimator, ControlAutonomy,
                                                ControlMode, MagPointingLaw, MagResidualMode, ModeChangeReason,
                                                PointingActuator,
                                                Quaternion, RateSource, SpinLaw, Vector3, WheelValues)
from detumble.components.types import (AttitudeGet, DipoleMomentGet, MagneticFieldGet, StartMagnetorquer,
                                       StopMagnetorquer, Success, WheelEnableSet, WheelStateGet, WheelTorqueSet)
from detumble.control import attitude_defaults as _defaults
from detumble.control.attitude_filter import AttitudeFilter
from detumble.control.mekf import Mekf
from detumble.control.rate_observer import RateObserver, applied_torque
from detumble.control.magnetic import bdot_dipole, clip_to_limits, dump_torque, project_dipole_weighted, scale_to_limits
from detumble.control.magnetic_pointing import FieldDirectionRate, ResidualDipoleEstimator, field_steering_torque
from detumble.control.magnetorquer import face_coil_levels
from detumble.control.pointing import ErrorIntegrator, pd_torque
from detumble.control.quaternion import (is_unit_quaternion, quat_angle, quat_normalize, quat_shortest,
                                         target_pointing_axis)
from detumble.control.spin import SeedKaneDamper, SpinRateRegulator, VirtualDamper, spin_errors
from detumble.control.wheel_allocation import WheelAllocator

__all__ = ["AttitudeController", "BORESIGHT_B"]

log = logging.getLogger("detumble.components.attitude_controller")

#: The body axis SET_TARGET_DIRECTION points (the seed's "point Z-axis at Sun/Ground").
BORESIGHT_B = _defaults.BORESIGHT_B
_TESLA_PER_GAUSS = 1e-4
_DEG = math.pi / 180.0
_ARCSEC = _DEG / 3600.0
_ZERO = (0.0, 0.0, 0.0)
_SUCCESS = Success.SUCCESS
_isfinite = math.isfinite


def _finite(*values) -> bool:
    try:
        for v in values:
            if not _isfinite(v):
                return False
    except TypeError:
        return False
    return True


def _finite3(x, y, z) -> bool:
    """``_finite(x, y, z)`` for three values (the field's components, every cycle)."""
    try:
        return _isfinite(x) and _isfinite(y) and _isfinite(z)
    except TypeError:
        return False


def _call_ref(out, index: int = 0):
    """Call output ``out[index]`` (a ``ref condition`` port); ``(ok, value)``. Unconnected counts as a failure."""
    if out.targets[index] is None:
        return False, None
    value, condition = out.calls[index]()
    return condition == _SUCCESS, value


def _norm(v) -> float:
    return math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])


class AttitudeController(PassiveComponent):
    """DETUMBLE → SPIN_STABLE → POINTING, with every trigger a parameter (F´ namespace ``Components``).

    Args:
        name: instance name.
        base_id: F´ base id.
        wheel_axes: unit spin axes of the wheels in B, one per connected wheel port index
            (default: three orthogonal wheels on x, y, z).
    """

    # --- commands ------------------------------------------------------------------------------

    @sync_command()
    def FORCE_MODE(self, mode: ControlMode):
        """Switch to ``mode`` and stay there (autonomy MANUAL). POINTING is refused without attitude
        knowledge (NoAttitudeKnowledge) or, with POINTING_ACTUATOR = WHEELS, without wheels
        (ModeUnavailableNoWheels): EXECUTION_ERROR, mode unchanged."""
        mode = ControlMode(mode)
        if mode == ControlMode.POINTING and not self._pointing_available(report=True, fresh=True):
            return CmdResponse.EXECUTION_ERROR
        self._set_autonomy(ControlAutonomy.MANUAL)
        self._change_mode(mode, ModeChangeReason.COMMAND)
        return CmdResponse.OK

    @sync_command()
    def SET_AUTO(self):
        """Hand the mode to the seed's triggers (AUTO). From IDLE the next cycle starts in DETUMBLE
        (the seed's "mission start")."""
        self._set_autonomy(ControlAutonomy.AUTO)
        return CmdResponse.OK

    @sync_command()
    def SET_TARGET_QUATERNION(self, q0: F64, q1: F64, q2: F64, q3: F64):
        """Set the POINTING target ``q_TN`` (scalar first). Refused unless | |q| − 1 | ≤ 1e-3
        (TargetNotUnitQuaternion, VALIDATION_ERROR); accepted targets are re-normalised."""
        q = (q0, q1, q2, q3)
        if not is_unit_quaternion(q):
            norm = math.sqrt(sum(c * c for c in q)) if _finite(*q) else float("nan")
            self.TargetNotUnitQuaternion(q0, q1, q2, q3, norm)
            return CmdResponse.VALIDATION_ERROR
        self.TargetNotUnitQuaternion.clear_throttle()
        self._set_target(quat_shortest(quat_normalize(q)))
        return CmdResponse.OK

    @sync_command()
    def SET_TARGET_DIRECTION(self, x: F64, y: F64, z: F64):
        """Point the body +Z axis along the inertial direction ``(x, y, z)`` (any length), by the
        smallest rotation from the present attitude. Refused for a zero or non-finite vector
        (TargetDirectionInvalid, VALIDATION_ERROR) and without attitude knowledge
        (NoAttitudeKnowledge, EXECUTION_ERROR)."""
        if not _finite(x, y, z) or _norm((x, y, z)) == 0.0:
            self.TargetDirectionInvalid(x, y, z)
            return CmdResponse.VALIDATION_ERROR
        q = self.filter.q
        if not self.attitude_valid or q is None:
            self.NoAttitudeKnowledge()
            return CmdResponse.EXECUTION_ERROR
        self._set_target(target_pointing_axis(q, BORESIGHT_B, (x, y, z)))
        return CmdResponse.OK

    # --- parameters (defaults and their derivation: docs/components/attitude_controller.md) ----
    # The defaults, with their units, live in detumble.control.attitude_defaults (shared with the plant-only law).

    K_P = Param(F64, default=_defaults.K_P)  # N·m: PD spring on q_err.v, wheels (ω_n 0.5 rad/s for 2.2e-3 kg·m²)
    K_D = Param(F64, default=_defaults.K_D)  # N·m·s: PD damping, wheels (ζ ≈ 0.9)
    K_I = Param(F64, default=_defaults.K_I)
    INTEGRAL_WINDOW = Param(F64, default=_defaults.INTEGRAL_WINDOW)  # deg: the integral runs only below this error
    K_P_MAG = Param(F64, default=_defaults.K_P_MAG, low=0.0, high=1.0e-3)  # N·m: spring ⟂ B, magnetorquer-only pointing
    K_D_MAG = Param(F64, default=_defaults.K_D_MAG, low=0.0, high=1.0e-2)
    C_DAMP = Param(F64, default=_defaults.C_DAMP)  # N·m·s: damper coefficient (seed c_damp)
    I_D = Param(F64, default=_defaults.I_D)  # kg·m²: damper virtual inertia (seed I_d)
    K_BDOT = Param(F64, default=_defaults.K_BDOT)  # A·m²·s/G: M = −k Ḃ when no dipoleMomentGet provider is connected
    SPIN_LAW = Param(SpinLaw, default=SpinLaw[_defaults.SPIN_LAW])
    SPIN_RATE_TARGET = Param(F64, default=_defaults.SPIN_RATE_TARGET)
    SPIN_K_TRANSVERSE = Param(F64, default=_defaults.SPIN_K_TRANSVERSE)  # N·m·s
    SPIN_K_RATE = Param(F64, default=_defaults.SPIN_K_RATE)  # N·m·s
    DETUMBLE_ENTER_RATE = Param(F64, default=_defaults.DETUMBLE_ENTER_RATE)  # deg/s: |ω| above this → DETUMBLE
    DETUMBLE_EXIT_RATE = Param(F64, default=_defaults.DETUMBLE_EXIT_RATE)
    MODE_DWELL = Param(F64, default=_defaults.MODE_DWELL)  # s
    SPIN_AXIS_ENTER = Param(F64, default=_defaults.SPIN_AXIS_ENTER)  # deg: rate within this of +Z counts as stable
    SPIN_AXIS_RESET = Param(F64, default=_defaults.SPIN_AXIS_RESET)  # deg: beyond this the stability timer restarts
    SPIN_RATE_ENTER = Param(F64, default=_defaults.SPIN_RATE_ENTER)  # fraction of SPIN_RATE_TARGET
    SPIN_RATE_RESET = Param(F64, default=_defaults.SPIN_RATE_RESET)  # fraction
    SPIN_STABLE_DWELL = Param(F64, default=_defaults.SPIN_STABLE_DWELL)  # s of stable spin before POINTING
    ATTITUDE_TIMEOUT = Param(F64, default=_defaults.ATTITUDE_TIMEOUT)
    SLEW_RATE_LIMIT = Param(F64, default=_defaults.SLEW_RATE_LIMIT)  # deg/s: largest rate a slew commands (wheels)
    POINTING_ACTUATOR = Param(PointingActuator, default=PointingActuator[_defaults.POINTING_ACTUATOR])
    K_DUMP = Param(F64, default=_defaults.K_DUMP)  # 1/s: magnetic momentum dumping while pointing on wheels
    WHEEL_MAX_TORQUE = Param(F64, default=_defaults.WHEEL_MAX_TORQUE)  # N·m per wheel
    WHEEL_MAX_MOMENTUM = Param(F64, default=_defaults.WHEEL_MAX_MOMENTUM)  # N·m·s per wheel
    FILTER_KP = Param(F64, default=_defaults.FILTER_KP)  # 1/s
    FILTER_KI = Param(F64, default=_defaults.FILTER_KI)  # 1/s²
    X_COIL_MAX_DIPOLE = Param(F64, default=_defaults.X_COIL_MAX_DIPOLE)  # A·m² per X coil at full drive
    Y_COIL_MAX_DIPOLE = Param(F64, default=_defaults.Y_COIL_MAX_DIPOLE)  # A·m² per Y coil
    Z_COIL_MAX_DIPOLE = Param(F64, default=_defaults.Z_COIL_MAX_DIPOLE)  # A·m², Z−
    CYCLE_TICKS = Param(U32, default=_defaults.CYCLE_TICKS)  # run ticks per control cycle (coils off on the last)
    # attitude estimation and the derivative term's rate (docs/studies/attitude_knowledge.md)
    ESTIMATOR = Param(AttitudeEstimator, default=AttitudeEstimator[_defaults.ESTIMATOR])
    #: deg/s, 1σ per axis of one gyro reading: LSM6DSO 0.0038 °/s/√Hz over 52 Hz, with the 70 mdps LSB/√12
    GYRO_NOISE = Param(F64, default=_defaults.GYRO_NOISE,
                       low=1e-6, high=10.0, finite=True)
    GYRO_BIAS_WALK = Param(F64, default=_defaults.GYRO_BIAS_WALK, low=0.0, high=1.0, finite=True)
    GYRO_BIAS_SIGMA0 = Param(F64, default=_defaults.GYRO_BIAS_SIGMA0, low=1e-6, high=10.0, finite=True)
    TRACKER_NOISE_CROSS = Param(F64, default=_defaults.TRACKER_NOISE_CROSS, low=1e-3, high=3600.0, finite=True)
    TRACKER_NOISE_ABOUT = Param(F64, default=_defaults.TRACKER_NOISE_ABOUT, low=1e-3, high=3600.0, finite=True)
    RATE_SOURCE = Param(RateSource, default=RateSource[_defaults.RATE_SOURCE])
    RATE_OBSERVER_GAIN = Param(F64, default=_defaults.RATE_OBSERVER_GAIN, low=1e-4, high=100.0, finite=True)
    INERTIA_XX = Param(F64, default=_defaults.INERTIA_XX, low=1e-6, high=10.0, finite=True)
    INERTIA_YY = Param(F64, default=_defaults.INERTIA_YY, low=1e-6, high=10.0, finite=True)  # kg·m²
    INERTIA_ZZ = Param(F64, default=_defaults.INERTIA_ZZ, low=1e-6, high=10.0, finite=True)  # kg·m²
    INERTIA_XY = Param(F64, default=_defaults.INERTIA_XY, low=-10.0, high=10.0, finite=True)
    INERTIA_XZ = Param(F64, default=_defaults.INERTIA_XZ, low=-10.0, high=10.0, finite=True)  # kg·m²
    INERTIA_YZ = Param(F64, default=_defaults.INERTIA_YZ, low=-10.0, high=10.0, finite=True)  # kg·m²
    # magnetorquer-only pointing (detumble.control.magnetic_pointing; docs/studies/magnetic_pointing.md)
    MAG_POINTING_LAW = Param(MagPointingLaw, default=MagPointingLaw[_defaults.MAG_POINTING_LAW])
    MAG_STEER_RHO = Param(F64, default=_defaults.MAG_STEER_RHO, low=0.0, high=10.0)
    MAG_STEER_ZETA = Param(F64, default=_defaults.MAG_STEER_ZETA, low=0.0, high=5.0)  # their damping ratio
    MAG_FIELD_RATE_BANDWIDTH = Param(F64, default=_defaults.MAG_FIELD_RATE_BANDWIDTH, low=1.0e-3, high=1.0)
    MAG_FIELD_RATE_MIN = Param(F64, default=_defaults.MAG_FIELD_RATE_MIN, low=1.0e-5, high=1.0e-1)
    MAG_SETTLE_TIME = Param(F64, default=_defaults.MAG_SETTLE_TIME, low=0.0, high=3600.0)
    # residual-dipole feed-forward (ResidualDipoleEstimator; docs/studies/magnetic_pointing.md)
    MAG_RESIDUAL_MODE = Param(MagResidualMode, default=MagResidualMode[_defaults.MAG_RESIDUAL_MODE])
    MAG_RESIDUAL_DIPOLE_X = Param(F64, default=_defaults.MAG_RESIDUAL_DIPOLE_X, low=-0.05, high=0.05)  # A·m², B
    MAG_RESIDUAL_DIPOLE_Y = Param(F64, default=_defaults.MAG_RESIDUAL_DIPOLE_Y, low=-0.05, high=0.05)  # A·m², B
    MAG_RESIDUAL_DIPOLE_Z = Param(F64, default=_defaults.MAG_RESIDUAL_DIPOLE_Z, low=-0.05, high=0.05)  # A·m², B
    MAG_RESIDUAL_WINDOW = Param(F64, default=_defaults.MAG_RESIDUAL_WINDOW, low=5.0, high=600.0)  # s

    # --- ports ---------------------------------------------------------------------------------

    angularVelocityGet = OutputPort(AngularVelocityGet)
    magneticFieldGet = OutputPort(MagneticFieldGet)
    attitudeGet = OutputPort(AttitudeGet)
    #: Optional: when connected (to a BDotDetumble), DETUMBLE takes its dipole instead of K_BDOT's.
    dipoleMomentGet = OutputPort(DipoleMomentGet)
    xPlusStart = OutputPort(StartMagnetorquer)
    xPlusStop = OutputPort(StopMagnetorquer)
    xMinusStart = OutputPort(StartMagnetorquer)
    xMinusStop = OutputPort(StopMagnetorquer)
    yPlusStart = OutputPort(StartMagnetorquer)
    yPlusStop = OutputPort(StopMagnetorquer)
    yMinusStart = OutputPort(StartMagnetorquer)
    yMinusStop = OutputPort(StopMagnetorquer)
    zMinusStart = OutputPort(StartMagnetorquer)
    zMinusStop = OutputPort(StopMagnetorquer)
    wheelTorqueSet = OutputPort(WheelTorqueSet, size=MAX_WHEELS)
    wheelStateGet = OutputPort(WheelStateGet, size=MAX_WHEELS)
    wheelEnableSet = OutputPort(WheelEnableSet, size=MAX_WHEELS)

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
    AttitudeKnowledgeLost = Event(Severity.WARNING_HI, "Attitude knowledge lost while pointing: back to SPIN_STABLE",
                                  throttle=5)
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

    # --- construction --------------------------------------------------------------------------

    def __init__(self, name: str, *, base_id: int = 0,
                 wheel_axes=((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))):
        super().__init__(name, base_id=base_id)
        if not 3 <= len(wheel_axes) <= MAX_WHEELS:
            raise ValueError(f"wheel_axes: give 3 to {MAX_WHEELS} unit axes, got {len(wheel_axes)}")
        self.wheel_axes = tuple((float(a[0]), float(a[1]), float(a[2])) for a in wheel_axes)
        self.mode = ControlMode.IDLE
        self.autonomy = ControlAutonomy.MANUAL
        self.filter: AttitudeFilter | Mekf = self._make_filter(AttitudeEstimator.MEKF)
        self.estimator = AttitudeEstimator.MEKF
        self.rate_observer = RateObserver(((2.20e-3, 2.0e-5, -1.5e-5), (2.0e-5, 2.15e-3, 1.0e-5),
                                           (-1.5e-5, 1.0e-5, 2.05e-3)), 0.1)
        self.pd_rate: tuple[float, float, float] | None = None  # rad/s, B: the rate the wheel PD's D term uses
        self.field_rate = FieldDirectionRate()  # db̂_N/dt for magnetorquer-only pointing
        self.bdot_hat_B: tuple | None = None  # its latest estimate in B, 1/s
        self.attitude_known_s = 0.0  # s since the attitude became known (gyro bias settling, MAG_SETTLE_TIME)
        self.residual_estimator = ResidualDipoleEstimator(self.rate_observer.inertia)
        self.residual_ff: tuple = _ZERO  # A·m², B: the residual-dipole feed-forward of the last POINTING cycle
        self.integrator = ErrorIntegrator(math.radians(1.0), _defaults.INTEGRAL_MAX_TORQUE)
        self.target: tuple[float, float, float, float] | None = None
        self.seed_damper = SeedKaneDamper(1.0e-4, 2.0e-4)
        self.virtual_damper = VirtualDamper(1.0e-4, 2.0e-4)
        self.ticks = 0
        self.cycles = 0
        self.coils_driven = False
        self.omega: tuple[float, float, float] | None = None  # ω̂ rad/s, B
        self.b_tesla: tuple | None = None
        self.dipole: tuple = _ZERO  # A·m² achieved by the levels of the present cycle
        self.torque_request: tuple = _ZERO
        self.wheel_torques: tuple = ()
        self.wheel_momenta: tuple | None = None
        self.pointing_error_deg = float("nan")
        self._last_cycle_us: int | None = None
        self._dwell_s = 0.0  # DETUMBLE-exit qualification timer
        self._stable_s = 0.0  # SPIN_STABLE qualification timer
        self._b_prev: tuple | None = None  # (b gauss, t µs) for the internal B-dot
        self._bdot_primed = False  # the dipoleMomentGet provider has been called in this DETUMBLE
        self._b_gauss: tuple = _ZERO
        self._gyro_sum: tuple = _ZERO  # rad/s, summed over the ticks since the last cycle
        self._gyro_count = 0
        self._last_fix_us: int | None = None  # time stamp of the last star-tracker solution used
        self._wheels_enabled = False
        self._b_stamp_us = 0
        self._start_ports = [self.output_port(n) for n in
                             ("xPlusStart", "xMinusStart", "yPlusStart", "yMinusStart", "zMinusStart")]
        self._stop_ports = [self.output_port(n) for n in
                            ("xPlusStop", "xMinusStop", "yPlusStop", "yMinusStop", "zMinusStop")]
        # The output port arrays read every tick or cycle (``targets[i]`` says whether index i is
        # connected, ``calls[i]`` calls it), looked up once instead of by name on every call.
        self._gyro_port = self.output_port("angularVelocityGet")
        self._attitude_port = self.output_port("attitudeGet")
        self._field_port = self.output_port("magneticFieldGet")
        self._dipole_port = self.output_port("dipoleMomentGet")
        self._torque_ports = self.output_port("wheelTorqueSet")
        self._state_ports = self.output_port("wheelStateGet")
        self._enable_ports = self.output_port("wheelEnableSet")
        # Allocators: Σ h_i g_i needs only the axes (limits 1, 1); the limited one is rebuilt when
        # the axes or WHEEL_MAX_TORQUE / WHEEL_MAX_MOMENTUM differ from the ones it was built for.
        self._momentum_alloc: tuple = (None, None)  # (axes, WheelAllocator)
        self._limit_alloc: tuple = (None, None)  # ((axes, u_max, h_max), WheelAllocator)

    # --- state helpers -------------------------------------------------------------------------

    @property
    def attitude_valid(self) -> bool:
        """True while the filter holds an attitude and its last star-tracker fix is recent."""
        return self.filter.q is not None and self.filter.since_measurement_s <= self.ATTITUDE_TIMEOUT.value

    def wheel_count(self) -> int:
        """Wheels connected (torque and momentum ports both), in index order."""
        n = 0
        torque, state = self._torque_ports.targets, self._state_ports.targets
        for i in range(len(self.wheel_axes)):
            if torque[i] is not None and state[i] is not None:
                n += 1
        return n

    def _wheels_available(self, fresh: bool) -> bool:
        """Every wheel connected and answering: by the cycle's own reading (``wheel_momenta``, taken in
        ``_sense``), or, for a command handler between cycles (``fresh``), by reading them now."""
        momenta = self._read_wheel_momenta() if fresh else self.wheel_momenta
        return self.wheel_count() == len(self.wheel_axes) and momenta is not None

    def _pointing_uses_wheels(self) -> bool:
        """Whether this cycle points on the wheels (its own wheel reading decides)."""
        choice = self.POINTING_ACTUATOR.value
        if choice == PointingActuator.MAGNETORQUERS:
            return False
        return self._wheels_available(fresh=False)

    def _pointing_available(self, *, report: bool, fresh: bool = False) -> bool:
        if self.POINTING_ACTUATOR.value == PointingActuator.WHEELS and not self._wheels_available(fresh):
            if report:
                self.ModeUnavailableNoWheels(ControlMode.POINTING)
            return False
        if not self.attitude_valid:
            if report:
                self.NoAttitudeKnowledge()
            return False
        return True

    def _set_autonomy(self, autonomy: ControlAutonomy) -> None:
        if autonomy != self.autonomy:
            self.autonomy = autonomy
            self.AutonomyChanged(autonomy)

    def _set_target(self, q) -> None:
        self.integrator.reset()
        self.target = (float(q[0]), float(q[1]), float(q[2]), float(q[3]))
        self.TargetSet(*self.target)
        self.TargetQuaternion.write(Quaternion(*self.target))

    def _change_mode(self, mode: ControlMode, reason: ModeChangeReason) -> None:
        if mode == self.mode:
            return
        old = self.mode
        self.mode = mode
        self._dwell_s = 0.0
        self._stable_s = 0.0
        self._b_prev = None
        self._bdot_primed = False
        self.seed_damper.reset()
        self.virtual_damper.reset()
        self.integrator.reset()
        if mode == ControlMode.POINTING and self.target is None and self.filter.q is not None:
            self._set_target(self.filter.q)  # nothing commanded yet: hold the present attitude
        if mode in (ControlMode.IDLE, ControlMode.DETUMBLE, ControlMode.SPIN_STABLE):
            self._command_wheels((0.0,) * len(self.wheel_axes))
        if mode == ControlMode.IDLE:
            self._stop_coils()
        self.ControlModeChanged(old, mode, reason)
        self.Mode.write(mode)

    # --- run -----------------------------------------------------------------------------------

    @sync_input(Sched)
    def run(self, context):
        """50 Hz tick: a control cycle on tick 0 of every CYCLE_TICKS, coils off on the last tick.

        No exception escapes: a fault is reported (``report_fault("run", exc)``: the HandlerFault
        event, the HandlerFaults channel, the log) and the actuators are made safe (coils off,
        wheels at zero torque); a fault while making them safe is reported too ("run: safing").
        """
        try:
            cycle = int(self.CYCLE_TICKS.value) or 1  # U32: max(1, value)
            phase = self.ticks % cycle
            self.ticks += 1
            if phase == 0:
                self._cycle()
            else:  # between cycles: add this tick's gyro reading to the cycle's mean (failed reads skipped)
                g = self._read_gyro()
                if g is not None:
                    acc = self._gyro_sum
                    self._gyro_sum = (acc[0] + g[0], acc[1] + g[1], acc[2] + g[2])
                    self._gyro_count += 1
            if phase == cycle - 1 and self.coils_driven and cycle > 1:
                self._stop_coils()
        except Exception as exc:  # noqa: BLE001 - the rate group must keep running; fail safe instead
            self.report_fault("run", exc)
            try:
                self._stop_coils()
                self._command_wheels((0.0,) * len(self.wheel_axes))
            except Exception as safing:  # noqa: BLE001 - reported, never raised into the rate group
                self.report_fault("run: safing", safing)

    def _cycle(self) -> None:
        now_us = self.get_time().total_us
        nominal = max(1, int(self.CYCLE_TICKS.value)) * _defaults.RATE_GROUP_PERIOD_S
        if self._last_cycle_us is None or now_us <= self._last_cycle_us:
            dt = nominal
        else:
            dt = (now_us - self._last_cycle_us) / 1e6
        self._last_cycle_us = now_us
        self.cycles += 1
        self._sense(dt, now_us)
        if self.autonomy == ControlAutonomy.AUTO:
            self._auto_mode(dt)
        elif self.mode == ControlMode.POINTING and not self.attitude_valid:
            self.AttitudeKnowledgeLost()
            self._change_mode(ControlMode.SPIN_STABLE, ModeChangeReason.ATTITUDE_LOST)
        self._actuate(dt)
        self._telemeter()

    # --- sensing -------------------------------------------------------------------------------

    def _make_filter(self, which):
        if which == AttitudeEstimator.MEKF:
            return Mekf(math.radians(self.GYRO_NOISE.value), math.radians(self.GYRO_BIAS_WALK.value),
                        self.TRACKER_NOISE_CROSS.value * _ARCSEC, self.TRACKER_NOISE_ABOUT.value * _ARCSEC,
                        BORESIGHT_B, math.radians(self.GYRO_BIAS_SIGMA0.value))
        return AttitudeFilter(self.FILTER_KP.value, self.FILTER_KI.value)

    def _configure_filter(self) -> None:
        """Follow ESTIMATOR (a switch keeps the attitude, bias and fix age) and the noise/gain parameters."""
        which = self.ESTIMATOR.value
        if which != self.estimator:
            old, new = self.filter, self._make_filter(which)
            new.q, new.bias, new.since_measurement_s = old.q, old.bias, old.since_measurement_s
            if isinstance(new, Mekf) and new.q is not None:  # the new covariance: the tracker's noise, bias σ0
                new._initialise_attitude(new.q, new.tracker_noise())
            self.filter, self.estimator = new, which
            self.EstimatorSelected(which)
        f = self.filter
        if isinstance(f, Mekf):
            f.gyro_noise = math.radians(self.GYRO_NOISE.value)
            f.bias_walk = math.radians(self.GYRO_BIAS_WALK.value)
            f.tracker_cross = self.TRACKER_NOISE_CROSS.value * _ARCSEC
            f.tracker_about = self.TRACKER_NOISE_ABOUT.value * _ARCSEC
        else:
            f.k_p = self.FILTER_KP.value
            f.k_i = self.FILTER_KI.value

    def _sense(self, dt: float, now_us: int) -> None:
        self._configure_filter()
        gyro = self._read_gyro()
        n = 1
        if gyro is not None:
            if self.GyroRetrievalFailed.count:  # clear_throttle where there is something to clear
                self.GyroRetrievalFailed.clear_throttle()
            n = self._gyro_count + 1  # the mean over the cycle's ticks: the noise the D term sees drops by √n
            acc = self._gyro_sum
            gyro = ((acc[0] + gyro[0]) / n, (acc[1] + gyro[1]) / n, (acc[2] + gyro[2]) / n)
        else:
            self.GyroRetrievalFailed()
        self._gyro_sum, self._gyro_count = _ZERO, 0
        q_meas = None
        age_s = 0.0
        ok, q = _call_ref(self._attitude_port)
        if ok and q is not None and q.valid and is_unit_quaternion((q.q0, q.q1, q.q2, q.q3), tol=1e-2):
            stamp_us = q.timestamp.total_us
            if stamp_us != self._last_fix_us and stamp_us <= now_us:  # a new solution (the tracker holds its last)
                self._last_fix_us = stamp_us
                q_meas = quat_normalize((q.q0, q.q1, q.q2, q.q3))
                age_s = (now_us - stamp_us) / 1e6
        if gyro is not None:
            f = self.filter
            if isinstance(f, Mekf):
                before = f.reinitialisations
                f.update(gyro, dt, q_meas, age_s, samples=n)
                if f.reinitialisations != before:
                    self.AttitudeReinitialised()
            else:
                f.update(gyro, dt, q_meas, age_s)
            self.omega = f.omega
        else:
            self.omega = None
        ok, field = _call_ref(self._field_port)
        if ok and field is not None and _finite3(field.x, field.y, field.z):
            if self.MagneticFieldRetrievalFailed.count:
                self.MagneticFieldRetrievalFailed.clear_throttle()
            b = self._b_gauss = (float(field.x), float(field.y), float(field.z))
            self._b_stamp_us = field.timestamp.total_us
            self.b_tesla = (b[0] * _TESLA_PER_GAUSS, b[1] * _TESLA_PER_GAUSS, b[2] * _TESLA_PER_GAUSS)
        else:
            self.MagneticFieldRetrievalFailed()
            self.b_tesla = None
        self._track_field_line(dt)
        self.wheel_momenta = self._read_wheel_momenta() if self.wheel_count() else None
        # the last cycle's body torque (self.dipole: what it drove, zero when off), for both users below
        torque = (applied_torque(self.wheel_torques, self.wheel_axes, self.dipole, self.b_tesla, self._duty())
                  if self.omega is not None else None)
        self._update_rate_observer(dt, torque)
        self._track_residual_dipole(dt, torque)

    def _update_rate_observer(self, dt: float, torque) -> None:
        """The derivative term's rate: the bias-corrected gyro, or the model-aided observer (RATE_SOURCE)."""
        obs = self.rate_observer
        if self.omega is None:
            obs.reset()
            self.pd_rate = None
            return
        xy, xz, yz = self.INERTIA_XY.value, self.INERTIA_XZ.value, self.INERTIA_YZ.value
        try:  # free when the parameters are the model's already (RateObserver.set_model compares first)
            obs.set_model(((self.INERTIA_XX.value, xy, xz), (xy, self.INERTIA_YY.value, yz),
                           (xz, yz, self.INERTIA_ZZ.value)), self.RATE_OBSERVER_GAIN.value)
            if self.InertiaModelRefused.count:
                self.InertiaModelRefused.clear_throttle()
        except ValueError:  # not positive definite: keep the last good model, say so once per change
            self.InertiaModelRefused()
        h = _ZERO
        if self.wheel_momenta is not None:
            h = self._body_momentum(self.wheel_momenta)
        w = obs.update(self.omega, torque, h, dt)
        self.pd_rate = w if self.RATE_SOURCE.value == RateSource.OBSERVER else self.omega

    def _track_field_line(self, dt: float) -> None:
        """Feed the field-direction-rate estimator (every cycle with a field and an attitude, so it is
        settled when magnetorquer pointing starts); a gap in either restarts it."""
        fr = self.field_rate
        fr.bandwidth_rad_s = self.MAG_FIELD_RATE_BANDWIDTH.value
        q = self.filter.q
        if q is None or not self.attitude_valid:
            self.attitude_known_s = 0.0
        else:
            self.attitude_known_s += dt
        if self.b_tesla is None or q is None or not self.attitude_valid:
            fr.reset()
            self.bdot_hat_B = None
            return
        self.bdot_hat_B = fr.update(q, self.b_tesla, dt)

    def _track_residual_dipole(self, dt: float, torque) -> None:
        """Feed the residual-dipole estimator while the coils point (magnetorquer POINTING past MAG_SETTLE_TIME,
        small dipoles, a settled gyro bias); elsewhere its open window is dropped and its sums kept."""
        est = self.residual_estimator
        if (self.MAG_RESIDUAL_MODE.value != MagResidualMode.ESTIMATE or self.mode != ControlMode.POINTING
                or self._pointing_uses_wheels() or self.omega is None or self.b_tesla is None
                or self.attitude_known_s < self.MAG_SETTLE_TIME.value):
            est.gap()
            return
        est.window_s = self.MAG_RESIDUAL_WINDOW.value
        est.inertia = self.rate_observer.inertia
        ready = est.estimate is not None
        m = est.update(self.omega, torque, _ZERO, self.b_tesla, dt)
        if m is not None and not ready:
            self.ResidualDipoleEstimated(m[0], m[1], m[2])

    def _residual_feed_forward(self):
        """The residual dipole to cancel, A·m² (B), by MAG_RESIDUAL_MODE; an estimate past a coil limit is refused."""
        mode = self.MAG_RESIDUAL_MODE.value
        if mode == MagResidualMode.OFF:
            return _ZERO
        est = self.residual_estimator.estimate
        if mode == MagResidualMode.ESTIMATE and est is not None:
            lim = self._coil_limits()
            if _finite(*est) and all(abs(est[i]) <= lim[i] for i in range(3)):
                self.ResidualDipoleEstimateRefused.clear_throttle()
                return est
            self.ResidualDipoleEstimateRefused(est[0], est[1], est[2])
        return (self.MAG_RESIDUAL_DIPOLE_X.value, self.MAG_RESIDUAL_DIPOLE_Y.value, self.MAG_RESIDUAL_DIPOLE_Z.value)

    def _read_gyro(self):
        """The gyro reading ``(x, y, z)`` rad/s (B), or None when the port fails, is not connected or
        returns a non-finite value."""
        port = self._gyro_port
        if port.targets[0] is None:
            return None
        w, condition = port.calls[0]()
        if condition != _SUCCESS or w is None:
            return None
        x, y, z = w.x, w.y, w.z
        try:
            if not (_isfinite(x) and _isfinite(y) and _isfinite(z)):
                return None
        except TypeError:
            return None
        return (float(x), float(y), float(z))

    # --- AUTO ----------------------------------------------------------------------------------

    def _spin_errors(self) -> tuple[float, float]:
        """``(axis error deg, rate error fraction)`` of ω̂ against ``SPIN_RATE_TARGET`` about +Z."""
        w = self.omega
        assert w is not None  # AUTO looks at the spin only with a rate estimate
        return spin_errors(w, self.SPIN_RATE_TARGET.value * _DEG)

    def _auto_mode(self, dt: float) -> None:
        if self.mode == ControlMode.IDLE:
            self._change_mode(ControlMode.DETUMBLE, ModeChangeReason.AUTO_START)
            return
        if self.omega is None:
            return  # no rate: keep the mode (B-dot needs no gyro)
        rate_deg = math.degrees(_norm(self.omega))
        if self.mode != ControlMode.DETUMBLE and rate_deg > self.DETUMBLE_ENTER_RATE.value:
            self._change_mode(ControlMode.DETUMBLE, ModeChangeReason.RATE_HIGH)
            return
        if self.mode == ControlMode.DETUMBLE:
            self._dwell_s = self._dwell_s + dt if rate_deg < self.DETUMBLE_EXIT_RATE.value else 0.0
            if self._dwell_s >= self.MODE_DWELL.value:
                self._change_mode(ControlMode.SPIN_STABLE, ModeChangeReason.RATE_LOW)
        elif self.mode == ControlMode.SPIN_STABLE:
            axis_deg, frac = self._spin_errors()
            if axis_deg <= self.SPIN_AXIS_ENTER.value and frac <= self.SPIN_RATE_ENTER.value:
                self._stable_s += dt
            elif axis_deg > self.SPIN_AXIS_RESET.value or frac > self.SPIN_RATE_RESET.value:
                self._stable_s = 0.0
            if self._stable_s >= self.SPIN_STABLE_DWELL.value:
                if self._pointing_available(report=True):
                    self._change_mode(ControlMode.POINTING, ModeChangeReason.SPIN_STABLE_REACHED)
        elif self.mode == ControlMode.POINTING and not self.attitude_valid:
            self.AttitudeKnowledgeLost()
            self._change_mode(ControlMode.SPIN_STABLE, ModeChangeReason.ATTITUDE_LOST)

    # --- actuation -----------------------------------------------------------------------------

    def _coil_limits(self) -> tuple[float, float, float]:
        """Largest dipole per axis, A·m²: two coils on X and Y, the single Z− coil on Z."""
        return (2.0 * self.X_COIL_MAX_DIPOLE.value, 2.0 * self.Y_COIL_MAX_DIPOLE.value,
                self.Z_COIL_MAX_DIPOLE.value)

    def _duty(self) -> float:
        cycle = max(1, int(self.CYCLE_TICKS.value))
        return (cycle - 1) / cycle if cycle > 1 else 1.0

    def _actuate(self, dt: float) -> None:
        mode = self.mode
        self.residual_ff = _ZERO
        tau = _ZERO
        dipole = None  # None: coils off this cycle
        wheel_u = None  # None: wheels at zero torque
        levels = None  # (dipole, _coil_levels(dipole)) when already worked out for the dipole driven below
        self.pointing_error_deg = float("nan")
        if mode == ControlMode.DETUMBLE:
            dipole = self._detumble_dipole()
            if dipole is not None:  # B-dot: each axis saturates on its own, as the flight coils do
                dipole = clip_to_limits(dipole, self._coil_limits())
        elif mode == ControlMode.SPIN_STABLE and self.omega is not None:
            tau = self._spin_torque(dt)
            if self.b_tesla is not None:
                dipole, _ = project_dipole_weighted(tau, self.b_tesla, self._coil_limits())
        elif mode == ControlMode.POINTING and self.omega is not None and self.attitude_valid:
            q = self.filter.q
            assert q is not None  # attitude_valid
            if self.target is None:
                self._set_target(q)
            target = self.target
            assert target is not None  # _set_target set it
            if self._pointing_uses_wheels():
                rate = self.pd_rate if self.pd_rate is not None else self.omega
                tau, qe = pd_torque(target, q, rate, self.K_P.value, self.K_D.value,
                                    self.SLEW_RATE_LIMIT.value * _DEG)
                self.integrator.window_rad = self.INTEGRAL_WINDOW.value * _DEG
                ti = self.integrator.update(qe, dt, self.K_I.value)
                tau = (tau[0] + ti[0], tau[1] + ti[1], tau[2] + ti[2])
                tau_mag = _ZERO
                if self.b_tesla is not None and self.wheel_momenta is not None:
                    h_b = self._body_momentum(self.wheel_momenta)
                    limits = self._coil_limits()
                    dipole, _ = project_dipole_weighted(dump_torque(h_b, self.K_DUMP.value), self.b_tesla, limits)
                    dipole = scale_to_limits(dipole, limits)
                    levels = (dipole, self._coil_levels(dipole))
                    mb = _cross(levels[1][1], self.b_tesla)
                    d = self._duty()
                    tau_mag = (mb[0] * d, mb[1] * d, mb[2] * d)
                # the wheels supply what the dump torque does not (it would otherwise disturb the pointing)
                wheel_u = self._allocate((tau[0] - tau_mag[0], tau[1] - tau_mag[1], tau[2] - tau_mag[2]))
            else:
                tau, qe = self._magnetic_pointing_torque(target, q)
                if self.attitude_known_s < self.MAG_SETTLE_TIME.value:
                    tau = _ZERO  # the gyro-bias estimate is still settling: the coils wait (no dipole)
                elif self.b_tesla is not None:
                    dipole, _ = project_dipole_weighted(tau, self.b_tesla, self._coil_limits())
                    # cancel the residual dipole, which acts all the time, with coils on for the duty share
                    ff = self.residual_ff = self._residual_feed_forward()
                    d = self._duty()
                    dipole = (dipole[0] - ff[0] / d, dipole[1] - ff[1] / d, dipole[2] - ff[2] / d)
            self.pointing_error_deg = math.degrees(quat_angle(qe))
        self.torque_request = tau
        if dipole is None:
            if self.coils_driven:
                self._stop_coils()
            self.dipole = _ZERO
        else:
            m = self._limit_dipole(dipole)
            # the levels of the dump dipole are reused when the limit left it as it was (the same object)
            self._drive_coils(m, levels[1] if levels is not None and levels[0] is m else None)
        if wheel_u is None:
            wheel_u = (0.0,) * len(self.wheel_axes)
        self._command_wheels(wheel_u)

    def _magnetic_pointing_torque(self, target, q):
        """``(τ_req, q_err)`` of the MAG_POINTING_LAW (before the projection ⟂ B)."""
        w = self.omega
        assert w is not None  # POINTING actuates only with a rate estimate
        kp, kd = self.K_P_MAG.value, self.K_D_MAG.value
        if self.MAG_POINTING_LAW.value == MagPointingLaw.SEED_PD or self.b_tesla is None:
            return pd_torque(target, q, w, kp, kd)
        bd = self.bdot_hat_B if self.bdot_hat_B is not None else _ZERO  # no estimate yet: the law's ρ = 0 case
        return field_steering_torque(target, q, w, self.b_tesla, bd, kp, kd, self.MAG_STEER_RHO.value,
                                     self.MAG_STEER_ZETA.value, self.MAG_FIELD_RATE_MIN.value)

    def _limit_dipole(self, m):
        return scale_to_limits(m, self._coil_limits())

    def _body_momentum(self, momenta):
        """``Σ h_i g_i`` over the wheels, N·m·s (B)."""
        axes, alloc = self._momentum_alloc
        if axes != self.wheel_axes:
            alloc = WheelAllocator(self.wheel_axes, 1.0, 1.0)
            self._momentum_alloc = (self.wheel_axes, alloc)
        return alloc.body_momentum(momenta)

    def _allocate(self, tau):
        key, alloc = self._limit_alloc
        wanted = (self.wheel_axes, self.WHEEL_MAX_TORQUE.value, self.WHEEL_MAX_MOMENTUM.value)
        if key != wanted:  # first use, or a limit parameter changed: the allocator's limits follow
            alloc = WheelAllocator(*wanted)
            self._limit_alloc = (wanted, alloc)
        u, limited = alloc.allocate(tau, self.wheel_momenta)
        if limited:
            self.WheelLimitReached()
        elif self.WheelLimitReached.count:
            self.WheelLimitReached.clear_throttle()
        return u

    def _detumble_dipole(self):
        if self._dipole_port.targets[0] is not None:
            ok, m = _call_ref(self._dipole_port)
            primed, self._bdot_primed = self._bdot_primed, True
            if not ok or m is None or not _finite(m.x, m.y, m.z):
                if primed:  # the provider's first call after entering DETUMBLE only primes it
                    self.DipoleMomentRetrievalFailed()
                return None
            if self.DipoleMomentRetrievalFailed.count:
                self.DipoleMomentRetrievalFailed.clear_throttle()
            return (float(m.x), float(m.y), float(m.z))
        if self.b_tesla is None:
            return None
        now = (self._b_gauss, self._b_stamp_us)
        prev, self._b_prev = self._b_prev, now
        if prev is None:
            return None
        return bdot_dipole(prev[0], now[0], (now[1] - prev[1]) / 1e6, self.K_BDOT.value)

    def _spin_torque(self, dt: float):
        law = self.SPIN_LAW.value
        w = self.omega
        assert w is not None  # spin control runs only with a rate estimate
        c, i_d = self.C_DAMP.value, self.I_D.value
        if law == SpinLaw.SEED_KANE_DAMPER:
            sd = self.seed_damper
            sd.c_damp, sd.i_d = c, i_d
            b = self.b_tesla
            # τ_mag: the magnetic torque the previous cycle's dipole produced (its on-time share)
            tau_mag = _cross(self.dipole, b) if b is not None else _ZERO
            d = self._duty()
            sd.update((tau_mag[0] * d, tau_mag[1] * d, tau_mag[2] * d), dt)
            self.damper_state = sd.w_d
            return sd.torque_request()
        if law == SpinLaw.VIRTUAL_DAMPER:
            vd = self.virtual_damper
            vd.c_damp, vd.i_d = c, i_d
            vd.update(w, dt)
            self.damper_state = _norm(vd.omega_d) if vd.omega_d is not None else 0.0
            return vd.torque_request(w)
        reg = SpinRateRegulator(self.SPIN_K_TRANSVERSE.value, self.SPIN_K_RATE.value,
                                self.SPIN_RATE_TARGET.value * _DEG)
        self.damper_state = w[2] - reg.rate
        return reg.torque_request(w)

    # --- telemetry -----------------------------------------------------------------------------

    damper_state = 0.0

    def _telemeter(self) -> None:
        self.Mode.write(self.mode)
        self.Autonomy.write(self.autonomy)
        w = self.omega
        if w is not None:
            n = _norm(w)
            self.AngularRate.write(math.degrees(n))
            # as _spin_errors: the angle between ω̂ and +Z (180 without a rate)
            self.SpinAxisError.write(math.degrees(math.atan2(math.hypot(w[0], w[1]), w[2])) if n > 0.0 else 180.0)
            self.SpinRate.write(math.degrees(w[2]))
        if self.mode == ControlMode.POINTING and math.isfinite(self.pointing_error_deg):
            self.PointingError.write(self.pointing_error_deg)
        self.DamperState.write(float(self.damper_state))
        self.RequestedTorque.write(Vector3(self.torque_request))
        self.CommandedDipole.write(Vector3(self.dipole))
        self.WheelTorqueCommand.write(WheelValues(_pad(self.wheel_torques)))
        if self.wheel_momenta is not None:
            self.WheelMomentum.write(WheelValues(_pad(self.wheel_momenta)))
        b = self.filter.bias
        self.GyroBiasEstimate.write(Vector3([math.degrees(b[0]), math.degrees(b[1]), math.degrees(b[2])]))
        self.AttitudeValid.write(1 if self.attitude_valid else 0)
        if isinstance(self.filter, Mekf) and self.filter.q is not None:
            self.AttitudeSigma3.write(math.degrees(self.filter.attitude_sigma3_rad))
        if self.bdot_hat_B is not None:
            self.FieldLineRate.write(math.degrees(_norm(self.bdot_hat_B)))
        self.ResidualDipole.write(Vector3(self.residual_ff))

    # --- ports out -----------------------------------------------------------------------------

    def _read_wheel_momenta(self):
        """Each wheel's axial momentum (N·m·s) from its driver, or None when one does not answer."""
        momenta = []
        ports = self._state_ports
        targets, calls = ports.targets, ports.calls
        for i in range(len(self.wheel_axes)):
            if targets[i] is None:
                return None
            state, condition = calls[i]()
            if condition != _SUCCESS or state is None:
                return None
            h = state.momentum
            try:
                if not _isfinite(h):
                    return None
            except TypeError:
                return None
            momenta.append(float(h))
        return tuple(momenta)

    def _command_wheels(self, u) -> None:
        """Send one motor torque (N·m) per wheel; a non-zero command enables the wheels first."""
        sent = []
        if not self._wheels_enabled:
            for t in u:
                if t != 0.0:  # the first non-zero command enables every wheel
                    enable = self._enable_ports
                    for i in range(len(u)):
                        if enable.targets[i] is not None and enable.calls[i](True) != _SUCCESS:
                            self.WheelCommandFailed(i)
                    self._wheels_enabled = True
                    break
        ports = self._torque_ports
        targets, calls = ports.targets, ports.calls
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
        self.wheel_torques = tuple(sent)

    def _coil_levels(self, m):
        """``(levels X+, X−, Y+, Y−, Z−, achieved dipole A·m²)`` for the dipole ``m`` (A·m², B): half of
        m_x on each X coil, half of m_y on each Y coil, m_z on Z−; X−, Y− and Z− face the other way."""
        return face_coil_levels(m, self.X_COIL_MAX_DIPOLE.value, self.Y_COIL_MAX_DIPOLE.value,
                                self.Z_COIL_MAX_DIPOLE.value)

    def _drive_coils(self, m, coil_levels=None) -> None:
        """Drive the five coils for the dipole ``m``; ``self.dipole`` becomes what the rounded levels give.
        ``coil_levels``: ``_coil_levels(m)`` when the caller has it already."""
        levels, self.dipole = coil_levels if coil_levels is not None else self._coil_levels(m)
        for port, level in zip(self._start_ports, levels, strict=True):
            if port.targets[0] is not None:
                port.calls[0](level)
        self.coils_driven = True

    def _stop_coils(self) -> None:
        for port in self._stop_ports:
            if port.targets[0] is not None:
                port.calls[0]()
        self.coils_driven = False


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _pad(values) -> list:
    out = [float(v) for v in values][:MAX_WHEELS]
    return out + [0.0] * (MAX_WHEELS - len(out))
