"""Seed 003's three-mode attitude controller, written once (plain floats; no framework import).

:class:`ThreeModeLaw` is the whole controller: DETUMBLE (B-dot) → SPIN_STABLE (spin about body +Z) →
POINTING (quaternion PD on the wheels, or on the magnetorquers), its AUTO triggers, its commands and
its estimators. Two adapters fly it: the F´ component
:class:`detumble.components.attitude_controller.AttitudeController` (ports, commands, events,
telemetry, parameters) and the plant-only law of ``fprime-lite sim --law adcs``
(:mod:`detumble.sim.adcs_law`). Behaviour and every parameter's reason:
``docs/components/attitude_controller.md``.

It reads and drives the spacecraft through a :class:`ControllerIo`, asks DETUMBLE's dipole of a
:class:`DipoleProvider` when one is connected, and tells what happens through a :class:`Notify` (F´
events by name, the mode and target changes, the end of each cycle for telemetry; :class:`Quiet`
tells nobody).

Timing: :meth:`ThreeModeLaw.tick` once per rate-group tick (``RATE_GROUP_PERIOD_S``, 20 ms). Every
``CYCLE_TICKS`` ticks (default 5, so 10 Hz) one control cycle runs on tick 0: read the gyro (the mean
of the cycle's readings), the star tracker and the magnetometer, update the estimators, choose the
mode, compute and actuate. The coils are switched off on the last tick of each cycle, so the next
cycle's magnetometer reading is free of their field; they drive ``(CYCLE_TICKS − 1)/CYCLE_TICKS`` of
the time. Wheels are commanded once per cycle and hold their torque.

Parameters are attributes named as the flight parameters (the ground's names, upper case), in their
units (``control.attitude_defaults.UNITS``: deg/s, deg, N·m, …); :meth:`ThreeModeLaw.set_parameters`
changes them and a change acts from the next cycle. Enumerated parameters, modes, reasons and the
autonomy are plain ints in the order of the flight enums (``attitude_defaults.ENUM_CHOICES``,
:data:`MODES`, :data:`REASONS`).

Frames and units: body B, inertial N; quaternions ``q_BN`` scalar first; rates rad/s inside; field
gauss at the I/O, tesla inside; torque N·m; momentum N·m·s; dipole A·m²; time stamps integer µs.
"""

from __future__ import annotations

import math
from typing import Mapping, Protocol, Sequence

from detumble.control import attitude_defaults as defaults
from detumble.control.attitude_filter import AttitudeFilter
from detumble.control.geomagnetic import OnboardField
from detumble.control.magnetic import bdot_dipole, clip_to_limits, dump_torque, project_dipole_weighted, scale_to_limits
from detumble.control.magnetic_lqr import HoldGainTable, HoldGainTableBuilder, lqr_dipole_B
from detumble.control.magnetic_pointing import FieldDirectionRate, ResidualDipoleEstimator, field_steering_torque
from detumble.control.magnetorquer import face_coil_levels
from detumble.control.mat3 import cross as _cross
from detumble.control.mekf import Mekf
from detumble.control.pointing import ErrorIntegrator, gravity_gradient_torque, gyroscopic_torque, pd_torque
from detumble.control.quaternion import (Quat, Vec3, is_unit_quaternion, quat_angle, quat_error, quat_normalize,
                                         quat_shortest, rotate_n_to_b, target_pointing_axis)
from detumble.control.rate_observer import (DIPOLE_LEARN_MAX_RATE, DIPOLE_LEARN_MAX_TORQUE, RateObserver,
                                            applied_torque)
from detumble.control.spin import SeedKaneDamper, SpinRateRegulator, VirtualDamper, spin_errors
from detumble.control.sun_safe import SunHold, SunRateBias, spin_down_tip, sun_spin_torque
from detumble.control.sun_vector import propagate_body_vector
from detumble.control.targets import (BODY_AXES, GROUND_STATION, MU_EARTH_M3_S2, STATION_FALLBACK, Ephemeris,
                                      InertialTarget, NadirTarget, Reference, StationTarget, SunTarget, Target,
                                      axes_error, station_error)
from detumble.control.units import TESLA_PER_GAUSS
from detumble.control.wheel_allocation import WheelAllocator

__all__ = ["ThreeModeLaw", "checked_parameters", "ControllerIo", "DipoleProvider", "Notify", "Quiet", "MODES",
           "REASONS", "IDLE", "DETUMBLE", "SPIN_STABLE", "POINTING", "SUN_SAFE", "MANUAL", "AUTO", "XYZ"]

#: The modes (ControlMode), by value.
MODES = ("IDLE", "DETUMBLE", "SPIN_STABLE", "POINTING", "SUN_SAFE")
IDLE, DETUMBLE, SPIN_STABLE, POINTING, SUN_SAFE = range(5)
#: Why a mode changed (ModeChangeReason), by value.
REASONS = ("COMMAND", "AUTO_START", "RATE_HIGH", "RATE_LOW", "SPIN_STABLE_REACHED", "ATTITUDE_LOST",
           "SYSTEM_SAFE_MODE", "KNOWLEDGE_RESTORED")
(_COMMAND, _AUTO_START, _RATE_HIGH, _RATE_LOW, _SPIN_STABLE_REACHED, _ATTITUDE_LOST, _SYSTEM_SAFE_MODE,
 _KNOWLEDGE_RESTORED) = range(8)
#: ControlAutonomy: MANUAL (the mode stays where it was put) or AUTO (the triggers choose it).
MANUAL, AUTO = 0, 1
#: Three orthogonal wheels on x, y, z (the default wheel axes).
XYZ: tuple[Vec3, Vec3, Vec3] = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def _member(param: str, name: str) -> int:
    return defaults.ENUM_CHOICES[param].index(name)


_SEED_KANE_DAMPER, _VIRTUAL_DAMPER = _member("SPIN_LAW", "SEED_KANE_DAMPER"), _member("SPIN_LAW", "VIRTUAL_DAMPER")
_WHEELS, _MAGNETORQUERS = _member("POINTING_ACTUATOR", "WHEELS"), _member("POINTING_ACTUATOR", "MAGNETORQUERS")
_MEKF = _member("ESTIMATOR", "MEKF")
_OBSERVER = _member("RATE_SOURCE", "OBSERVER")
_SEED_PD = _member("MAG_POINTING_LAW", "SEED_PD")
_OFF, _ESTIMATE = _member("MAG_RESIDUAL_MODE", "OFF"), _member("MAG_RESIDUAL_MODE", "ESTIMATE")
_FF_REFERENCE = _member("WHEEL_FEED_FORWARD", "REFERENCE")
_FF_GYROSCOPIC = _member("WHEEL_FEED_FORWARD", "REFERENCE_GYROSCOPIC")
_FF_GRAVITY = _member("WHEEL_FEED_FORWARD", "REFERENCE_GYROSCOPIC_GRAVITY")

_DEG = math.pi / 180.0
_ARCSEC = _DEG / 3600.0
# the model-scheduled hold (MAG_LQR_ANGLE > 0; control.magnetic_lqr): weights chosen on the linearised hold in the
# campaign's field (docs/studies/magnetorquer_hold_after_acquisition.md, "The hold scheduled on the field model"): the
# periodic-LQR bound's fastest law (rate scale 0.01 rad/s, α 8e-3 /s) swings a 30° error at rest past 100° once
# scaled to the coils (campaigns/adcs/magnetorquer_hold_lqr_weights.py); rate scale 0.03 rad/s, r 1, α 2e-3 /s peaks
# at 63-80° and falls to 15° in 200-304 s (median over the axes);
# its 1.4 s step, a table for an orbit computed over two
MAG_LQR_STEP_S = 1.4
MAG_LQR_USE_S = 5580.0
MAG_LQR_EXTRA_S = 5580.0
MAG_LQR_THETA_SCALE = math.radians(30.0)
MAG_LQR_RATE_SCALE = 0.03
MAG_LQR_R_WEIGHT = 1.0
MAG_LQR_ALPHA = 2.0e-3
# the table is built over control cycles (control.magnetic_lqr.HoldGainTableBuilder), at most this many work units a
# cycle (a field sample 1, a Riccati step 3): ≤ 10 Riccati steps, ~1.2 ms of CPU on the development machine (a field
# sample ≤ 44 µs at IGRF degree 13), against the 20 ms rate-group tick; an orbit's table (7,972 samples and steps,
# 31,888 units) takes 1,063 cycles, 106 s at 10 Hz (docs/components/attitude_controller.md, MAG_LQR_ANGLE)
MAG_LQR_BUDGET_UNITS = 30
# the next table is started when the one in use has less than the last build's time plus this margin left (s)
MAG_LQR_RENEW_MARGIN_S = 60.0
# after a failed build (MagLqrTableFailed), the next attempt waits this long (s); field steering meanwhile
MAG_LQR_RETRY_S = 60.0
_ZERO = (0.0, 0.0, 0.0)
_isfinite = math.isfinite


class ControllerIo(Protocol):
    """The spacecraft as the law reads and drives it (a failed read returns None)."""

    def now_us(self) -> int:
        """The time now, µs."""

    def gyro(self) -> Vec3 | None:
        """One gyro reading, rad/s (B), finite."""

    def attitude(self) -> tuple[Quat, int] | None:
        """The star tracker's held solution ``(q_BN, image time µs)`` when it says it is valid."""

    def field(self) -> tuple[Vec3, int] | None:
        """The magnetometer's held sample ``(b gauss in B, sample time µs)``, finite."""

    def wheel_count(self) -> int:
        """How many wheels are connected (index order)."""

    def wheel_momenta(self) -> tuple[float, ...] | None:
        """Each wheel's axial momentum, N·m·s; None when one does not answer."""

    def drive_coils(self, levels: Sequence[int], dipole_B: Vec3) -> None:
        """Drive the five coils X+, X−, Y+, Y−, Z− at ``levels`` (−127…127), which give ``dipole_B`` (A·m²)."""

    def stop_coils(self) -> None:
        """Every coil off."""

    def set_wheel_torques(self, torques: Sequence[float]) -> tuple[float, ...]:
        """Command one motor torque per wheel (N·m); returns what each wheel was sent (0 where none)."""

    def ephemeris(self) -> Ephemeris | None:
        """Where the spacecraft is now (orbit, Earth angle, Sun: ``control.targets.Ephemeris``); None without."""

    def has_sun_sensor(self) -> bool:
        """Whether a Sun vector source (the ADCS light sensors) is connected: SUN_SAFE needs one."""

    def sun_vector(self) -> tuple[Vec3, bool, int] | None:
        """The light sensors' latest Sun vector ``(unit vector in B, valid, time µs)``; None when the read fails."""

    def system_safe_mode(self) -> bool | None:
        """True while the spacecraft's mode manager is in safe mode; None when it is not connected."""


class DipoleProvider(Protocol):
    """DETUMBLE's external dipole source (the BDotDetumble component, or its plant-only stand-in)."""

    def has_dipole_provider(self) -> bool:
        """Whether one is connected (otherwise DETUMBLE flies the internal ``−K_BDOT Ḃ``)."""

    def provider_dipole(self) -> Vec3 | None:
        """Its dipole now, A·m² (B), finite; None when it has none (its first call only primes it)."""


class Notify(Protocol):
    """Where the law's events and telemetry go."""

    def event(self, name: str, *args: object) -> None:
        """The F´ event ``name`` (enumerated arguments as ints)."""

    def clear_event(self, name: str) -> None:
        """A good reading or result: the event ``name`` may be emitted again (clear its throttle)."""

    def mode_changed(self, old: int, new: int, reason: int) -> None:
        """The mode changed from ``old`` to ``new`` (:data:`MODES`) for ``reason`` (:data:`REASONS`)."""

    def target_set(self, q: Quat) -> None:
        """A new POINTING target ``q_TN`` (commanded, or the attitude captured on entering POINTING)."""

    def cycle_done(self) -> None:
        """A control cycle ended (its state is the cycle's telemetry)."""


class Quiet:
    """A :class:`Notify` that tells nobody."""

    def event(self, name: str, *args: object) -> None:
        pass

    def clear_event(self, name: str) -> None:
        pass

    def mode_changed(self, old: int, new: int, reason: int) -> None:
        pass

    def target_set(self, q: Quat) -> None:
        pass

    def cycle_done(self) -> None:
        pass


def checked_parameters(overrides: Mapping[str, object] | None) -> dict:
    """``attitude_defaults.DEFAULTS`` with ``overrides`` (flight names; enums by member name); ValueError naming a
    bad one."""
    out = dict(defaults.DEFAULTS)
    for key, value in (overrides or {}).items():
        if key not in out:
            raise ValueError(f"unknown attitude-controller parameter {key!r}; known: {', '.join(sorted(out))}")
        choices = defaults.ENUM_CHOICES.get(key)
        if choices is not None:
            if value not in choices:
                raise ValueError(f"{key} must be one of {', '.join(choices)}, got {value!r}")
        elif isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise ValueError(f"{key} must be a finite number, got {value!r}")
        out[key] = value
    return out


def _finite(*values) -> bool:
    try:
        for v in values:
            if not _isfinite(v):
                return False
    except TypeError:
        return False
    return True


def _norm(v) -> float:
    return math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])



class ThreeModeLaw:
    """DETUMBLE → SPIN_STABLE → POINTING with every trigger a parameter; one :meth:`tick` per rate-group tick.

    Args:
        io: the sensors and actuators (:class:`ControllerIo`).
        notify: where events and telemetry go (:class:`Notify`).
        provider: DETUMBLE's external dipole (:class:`DipoleProvider`).
        wheel_axes: unit spin axes of the wheels in B, one per wheel index (default x, y, z).
        params: flight parameter name → value (enums as member names or values) over
            ``attitude_defaults.DEFAULTS``; the estimators start from them.

    The commands (:meth:`force_mode`, :meth:`set_auto`, :meth:`set_target_quaternion`,
    :meth:`set_target_direction`) answer ``"OK"``, ``"VALIDATION_ERROR"`` or ``"EXECUTION_ERROR"``.
    """

    # parameters (set_parameters), units in attitude_defaults.UNITS
    K_P: float
    K_D: float
    K_I: float
    INTEGRAL_WINDOW: float
    INTEGRAL_RATE_GATE: float
    K_P_MAG: float
    K_D_MAG: float
    C_DAMP: float
    I_D: float
    K_BDOT: float
    SPIN_LAW: int
    SPIN_RATE_TARGET: float
    SPIN_K_TRANSVERSE: float
    SPIN_K_RATE: float
    DETUMBLE_ENTER_RATE: float
    DETUMBLE_EXIT_RATE: float
    MODE_DWELL: float
    SPIN_AXIS_ENTER: float
    SPIN_AXIS_RESET: float
    SPIN_RATE_ENTER: float
    SPIN_RATE_RESET: float
    SPIN_STABLE_DWELL: float
    ATTITUDE_TIMEOUT: float
    SLEW_RATE_LIMIT: float
    POINTING_ACTUATOR: int
    K_DUMP: float
    WHEEL_MAX_TORQUE: float
    WHEEL_MAX_MOMENTUM: float
    FILTER_KP: float
    FILTER_KI: float
    X_COIL_MAX_DIPOLE: float
    Y_COIL_MAX_DIPOLE: float
    Z_COIL_MAX_DIPOLE: float
    CYCLE_TICKS: int
    ESTIMATOR: int
    GYRO_NOISE: float
    GYRO_BIAS_WALK: float
    GYRO_BIAS_SIGMA0: float
    TRACKER_NOISE_CROSS: float
    TRACKER_NOISE_ABOUT: float
    RATE_SOURCE: int
    RATE_OBSERVER_GAIN: float
    RATE_OBSERVER_DIPOLE_TIME: float
    INERTIA_XX: float
    INERTIA_YY: float
    INERTIA_ZZ: float
    INERTIA_XY: float
    INERTIA_XZ: float
    INERTIA_YZ: float
    MAG_POINTING_LAW: int
    MAG_STEER_RHO: float
    MAG_STEER_ZETA: float
    MAG_STEER_RHO_LARGE: float
    MAG_STEER_RHO_FROM: float
    MAG_STEER_RHO_AT: float
    MAG_FIELD_RATE_BANDWIDTH: float
    MAG_FIELD_RATE_MIN: float
    MAG_SETTLE_TIME: float
    MAG_RESIDUAL_MODE: int
    MAG_RESIDUAL_DIPOLE_X: float
    MAG_RESIDUAL_DIPOLE_Y: float
    MAG_RESIDUAL_DIPOLE_Z: float
    MAG_RESIDUAL_WINDOW: float
    GS_MIN_ELEVATION: float
    WHEEL_FEED_FORWARD: int
    RATE_BLEND_ANGLE: float
    RATE_BLEND_GAIN: float
    SUN_SAFE_AXIS: int
    SUN_SAFE_K_P: float
    SUN_SAFE_K_D: float
    SUN_SAFE_K_P_MAG: float
    SUN_SAFE_K_D_MAG: float
    SUN_VECTOR_TIMEOUT: float
    SUN_SAFE_EXIT_DWELL: float
    SUN_SPIN_RATE: float
    SUN_BIAS_TIME: float
    SUN_HOLD_ANGLE: float
    SUN_HOLD_DWELL: float
    SUN_HOLD_SPIN_RATE: float
    SUN_HOLD_RAMP: float
    SUN_HOLD_FIELD_ANGLE: float
    SUN_HOLD_TIP_ANGLE: float
    MAG_BIAS_TIME: float
    MAG_LQR_ANGLE: float
    MAG_FIELD_MODEL_DEGREE: float

    def __init__(self, io: ControllerIo, notify: Notify, provider: DipoleProvider,
                 wheel_axes: Sequence[Sequence[float]] = XYZ, params: Mapping[str, object] | None = None) -> None:
        self.io, self.notify, self.provider = io, notify, provider
        self.wheel_axes = tuple((float(a[0]), float(a[1]), float(a[2])) for a in wheel_axes)
        self.set_parameters({**defaults.DEFAULTS, **(params or {})})
        self.mode = IDLE
        self.autonomy = MANUAL
        self.estimator = self.ESTIMATOR
        self.filter: AttitudeFilter | Mekf = self._make_filter(self.ESTIMATOR)
        xy, xz, yz = self.INERTIA_XY, self.INERTIA_XZ, self.INERTIA_YZ
        self.rate_observer = RateObserver(((self.INERTIA_XX, xy, xz), (xy, self.INERTIA_YY, yz),
                                           (xz, yz, self.INERTIA_ZZ)), self.RATE_OBSERVER_GAIN)
        self.pd_rate: Vec3 | None = None  # rad/s, B: the rate the wheel PD's D term uses
        self.field_rate = FieldDirectionRate(self.MAG_FIELD_RATE_BANDWIDTH)  # db̂_N/dt, magnetorquer pointing
        self.bdot_hat_B: Vec3 | None = None  # its latest estimate in B, 1/s
        self.attitude_known_s = 0.0  # s since the attitude became known (gyro bias settling, MAG_SETTLE_TIME)
        self.residual_estimator = ResidualDipoleEstimator(self.rate_observer.inertia, self.MAG_RESIDUAL_WINDOW)
        self.residual_ff: Vec3 = _ZERO  # A·m², B: the residual-dipole feed-forward of the last POINTING cycle
        self.integrator = ErrorIntegrator(self.INTEGRAL_WINDOW * _DEG, defaults.INTEGRAL_MAX_TORQUE)
        self.target: Quat | None = None  # the attitude to hold now, q_RN (the reference's; None: no target yet)
        self.target_spec: Target | None = None  # what was commanded (control.targets)
        self.reference: Reference | None = None  # the target's reference now: attitude, rate, acceleration, label
        self.seed_damper = SeedKaneDamper(self.C_DAMP, self.I_D)
        self.virtual_damper = VirtualDamper(self.C_DAMP, self.I_D)
        self.ticks = 0
        self.cycles = 0
        self.coils_driven = False
        self.omega: Vec3 | None = None  # ω̂ rad/s, B
        self.gyro_mean: Vec3 = _ZERO  # rad/s, B: the cycle's gyro mean as read, bias and all (the dipole fit's rate)
        self.b_tesla: Vec3 | None = None
        self.b_gauss: Vec3 = _ZERO  # the cycle's magnetometer sample, gauss (B), and its time µs
        self.b_stamp_us = 0
        self._onboard_field: OnboardField | None = None  # MAG_FIELD_MODEL_DEGREE's model (made when first used)
        self._lqr_table: HoldGainTable | None = None  # MAG_LQR_ANGLE > 0: the model-scheduled hold's gains
        self._lqr_builder: HoldGainTableBuilder | None = None  # the table being built (over cycles), if any
        self._lqr_build_s = 0.0  # s: when that build started (its ephemeris' time)
        self._lqr_lead_s = MAG_LQR_RENEW_MARGIN_S  # s: renew a table with less than this left (last build + margin)
        self._lqr_retry_s = -math.inf  # s: no build before this (MAG_LQR_RETRY_S after a failure)
        # µs: the first control cycle's time, the LQR table's clock's zero (its seconds are integer µs differences
        # from it, so the flight's absolute time, ~1.7e15 µs, does not round them: the deployment flies the plant-only
        # law's floats)
        self.first_cycle_us: int | None = None
        self.lqr_work_units = 0  # the gain-table work done so far (HoldGainTableBuilder units), for tests and studies
        self.mag_bias_T: Vec3 | None = None  # T, B: the on-board magnetometer-bias estimate (MAG_BIAS_TIME > 0)
        self.dipole: Vec3 = _ZERO  # A·m² achieved by the levels of the present cycle
        self.torque_request: Vec3 = _ZERO
        self.wheel_torques: tuple[float, ...] = ()
        self.wheel_momenta: tuple[float, ...] | None = None
        self._cycle_wheel_count = 0  # wheels connected at the cycle's reading (io.wheel_count(), read once a cycle)
        self.pointing_error_deg = math.nan
        self.damper_state = 0.0  # seed w_d, |ω_d| of the 3-axis damper, or the spin-rate error (rad/s)
        self.last_cycle_us: int | None = None
        self._dwell_s = 0.0  # DETUMBLE-exit qualification timer
        self._stable_s = 0.0  # SPIN_STABLE qualification timer
        self._b_prev: tuple | None = None  # (b gauss, t µs) for the internal B-dot
        self._bdot_primed = False  # the dipole provider has been called in this DETUMBLE
        self._gyro_sum: Vec3 = _ZERO  # rad/s, summed over the ticks since the last cycle
        self._gyro_count = 0
        self._last_fix_us: int | None = None  # time stamp of the last star-tracker solution used
        # SUN_SAFE: the Sun vector (unit, B) carried on the gyro between light-sensor readings, its age (s) and the
        # time stamp of the reading last taken; why SUN_SAFE was entered; how long the attitude has been known in it
        self.sun_B: Vec3 | None = None
        self.sun_age_s = math.inf
        self._sun_stamp_us: int | None = None
        self.sun_error_deg = math.nan  # angle between SUN_SAFE_AXIS and the Sun vector, deg (SUN_SAFE only)
        self.system_safe = False  # the mode manager's safe mode, as last read
        self._sun_safe_reason: int | None = None
        self._known_in_sun_safe_s = 0.0
        self.sun_bias = SunRateBias()  # SUN_SAFE: the gyro bias across the Sun line, from the Sun vector (rad/s, B)
        self.sun_hold = SunHold()  # SUN_SAFE on the coils: has the Sun been held long enough to lower the spin?
        self.sun_error_deg_last = math.nan  # deg: the coils' Sun-safe angle of the previous cycle (SunHold's input)
        self._sun_left_us: int | None = None  # µs: when SUN_SAFE was last left (the spin-down's memory)
        # Σ h_i g_i needs only the axes (limits 1, 1); the limited allocator is rebuilt when the axes or
        # WHEEL_MAX_TORQUE / WHEEL_MAX_MOMENTUM differ from the ones it was built for.
        self._momentum_alloc: tuple = (None, None)  # (axes, WheelAllocator)
        self._limit_alloc: tuple = (None, None)  # ((axes, u_max, h_max), WheelAllocator)

    def set_parameters(self, values: Mapping[str, object]) -> None:
        """Take parameter values by flight name (enums by member name or value); they act from the next cycle."""
        for name, value in values.items():
            if name not in defaults.DEFAULTS:
                raise ValueError(f"unknown attitude-controller parameter {name!r}")
            choices = defaults.ENUM_CHOICES.get(name)
            if choices is not None:
                if isinstance(value, str):
                    value = choices.index(value)
                elif isinstance(value, int):  # an F´ enum member (an IntEnum) or its value
                    value = int(value)
                else:
                    raise ValueError(f"{name} takes one of {', '.join(choices)}, got {value!r}")
            setattr(self, name, value)
        self.cycle_ticks = max(1, int(self.CYCLE_TICKS))  # ticks per control cycle

    # --- commands -------------------------------------------------------------------------------

    def force_mode(self, mode: int) -> str:
        """FORCE_MODE: switch to ``mode`` and stay there (MANUAL). POINTING is refused without attitude
        knowledge or, with POINTING_ACTUATOR = WHEELS, without wheels (the wheels are read afresh); SUN_SAFE without
        a Sun vector source (SunSensorsUnavailable)."""
        if mode == POINTING and not self._pointing_available(report=True, fresh=True):
            return "EXECUTION_ERROR"
        if mode == SUN_SAFE and not self.io.has_sun_sensor():
            self.notify.event("SunSensorsUnavailable")
            return "EXECUTION_ERROR"
        self._set_autonomy(MANUAL)
        self._change_mode(mode, _COMMAND)
        return "OK"

    def set_auto(self) -> str:
        """SET_AUTO: the triggers choose the mode; from IDLE the next cycle starts DETUMBLE."""
        self._set_autonomy(AUTO)
        return "OK"

    def set_target_quaternion(self, q: Sequence[float]) -> str:
        """SET_TARGET_QUATERNION: the POINTING target ``q_TN`` (scalar first), unit within 1e-3, re-normalised."""
        q0, q1, q2, q3 = q
        if not is_unit_quaternion(q):
            norm = math.sqrt(sum(c * c for c in q)) if _finite(*q) else float("nan")
            self.notify.event("TargetNotUnitQuaternion", q0, q1, q2, q3, norm)
            return "VALIDATION_ERROR"
        self.notify.clear_event("TargetNotUnitQuaternion")
        self.set_target(quat_shortest(quat_normalize((q0, q1, q2, q3))))
        return "OK"

    def set_target_direction(self, x: float, y: float, z: float) -> str:
        """SET_TARGET_DIRECTION: point the boresight (+Z) along the inertial ``(x, y, z)`` by the smallest turn."""
        if not _finite(x, y, z) or _norm((x, y, z)) == 0.0:
            self.notify.event("TargetDirectionInvalid", x, y, z)
            return "VALIDATION_ERROR"
        q = self.filter.q
        if not self.attitude_valid or q is None:
            self.notify.event("NoAttitudeKnowledge")
            return "EXECUTION_ERROR"
        self.set_target(target_pointing_axis(q, defaults.BORESIGHT_B, (x, y, z)))
        return "OK"

    def set_target_nadir(self, primary: int, secondary: int) -> str:
        """SET_TARGET_NADIR: body ``primary`` (BodyAxis) to nadir, ``secondary`` along the velocity (LVLH)."""
        if not self._axes_ok(primary, secondary):
            return "VALIDATION_ERROR"
        return self._set_moving_target(NadirTarget(int(primary), int(secondary)))

    def set_target_ground_station(self, latitude_deg: float, longitude_deg: float, altitude_m: float,
                                  primary: int, secondary: int) -> str:
        """SET_TARGET_GROUND_STATION: body ``primary`` at the station (WGS-84 geodetic, deg, deg, m) while it sees
        the spacecraft at GS_MIN_ELEVATION or more, ``secondary`` along the velocity; nadir otherwise."""
        why = station_error(latitude_deg, longitude_deg, altitude_m)
        if why is not None:
            self.notify.event("TargetStationInvalid", latitude_deg, longitude_deg, altitude_m)
            return "VALIDATION_ERROR"
        self.notify.clear_event("TargetStationInvalid")
        if not self._axes_ok(primary, secondary):
            return "VALIDATION_ERROR"
        return self._set_moving_target(StationTarget(float(latitude_deg), float(longitude_deg), float(altitude_m),
                                                     int(primary), int(secondary), float(self.GS_MIN_ELEVATION)))

    def set_target_sun(self, primary: int, secondary: int) -> str:
        """SET_TARGET_SUN: body ``primary`` at the Sun, ``secondary`` toward the orbit normal."""
        if not self._axes_ok(primary, secondary):
            return "VALIDATION_ERROR"
        return self._set_moving_target(SunTarget(int(primary), int(secondary)))

    def _axes_ok(self, primary: int, secondary: int) -> bool:
        if axes_error(primary, secondary) is not None:
            self.notify.event("TargetAxesInvalid", primary, secondary)
            return False
        self.notify.clear_event("TargetAxesInvalid")
        return True

    def _set_moving_target(self, spec: Target) -> str:
        """Take a target that needs the ephemeris: refused (EXECUTION_ERROR) without one or where its reference is
        undefined now (e.g. the Sun along the orbit normal)."""
        eph = self.io.ephemeris()
        if eph is None:
            self.notify.event("NoEphemeris")
            return "EXECUTION_ERROR"
        try:
            ref = spec.reference(eph)
        except ValueError:
            self.notify.event("TargetReferenceUndefined", spec.kind)
            return "EXECUTION_ERROR"
        self.notify.clear_event("NoEphemeris")
        self.target_spec = spec
        self._take_reference(ref)
        if isinstance(spec, NadirTarget):
            self.notify.event("TargetNadirSet", spec.primary, spec.secondary)
        elif isinstance(spec, StationTarget):
            self.notify.event("TargetStationSet", spec.latitude_deg, spec.longitude_deg, spec.altitude_m,
                              spec.primary, spec.secondary)
        elif isinstance(spec, SunTarget):
            self.notify.event("TargetSunSet", spec.primary, spec.secondary)
        self.notify.target_set(ref.q_RN)
        return "OK"

    def set_target(self, q: Sequence[float]) -> None:
        """Take ``q_TN`` as the (inertial) target as it is (the error integral starts again)."""
        q = (float(q[0]), float(q[1]), float(q[2]), float(q[3]))
        self.target_spec = InertialTarget(q)
        self._take_reference(self.target_spec.reference())
        self.notify.target_set(q)

    def _take_reference(self, ref: Reference) -> None:
        """A new target's reference (the error integral starts again)."""
        self.integrator.reset()
        self.reference = ref
        self.target = ref.q_RN

    def _update_reference(self) -> None:
        """Follow a moving target: its reference from the ephemeris now (a failed read or an undefined reference
        holds the last attitude, without feed-forward)."""
        spec = self.target_spec
        if spec is None or not spec.needs_ephemeris:
            return
        eph = self.io.ephemeris()
        old = self.reference
        assert old is not None  # a moving target was taken with a reference
        ref = None
        if eph is None:
            self.notify.event("EphemerisRetrievalFailed")
        else:
            self.notify.clear_event("EphemerisRetrievalFailed")
            try:
                ref = spec.reference(eph)
            except ValueError:
                self.notify.event("TargetReferenceUndefined", spec.kind)
        if ref is None:
            ref = Reference(old.q_RN, _ZERO, _ZERO, old.label)
        if ref.label != old.label:
            if ref.label == GROUND_STATION:
                self.notify.event("GroundStationInView")
            elif ref.label == STATION_FALLBACK and old.label == GROUND_STATION:
                self.notify.event("GroundStationOutOfView")
            self.integrator.reset()
        self.reference = ref
        self.target = ref.q_RN

    def safe(self) -> None:
        """Coils off and wheels at zero torque (after a fault); the wheels are zeroed even when stopping the
        coils raises (the exception then goes on to the caller, which reports it)."""
        try:
            self._stop_coils()
        finally:
            self._command_wheels((0.0,) * len(self.wheel_axes))

    # --- state ----------------------------------------------------------------------------------

    @property
    def attitude_valid(self) -> bool:
        """True while the filter holds an attitude and its last star-tracker fix is recent."""
        return self.filter.q is not None and self.filter.since_measurement_s <= self.ATTITUDE_TIMEOUT

    @property
    def duty(self) -> float:
        """The share of a cycle the coils drive."""
        cycle = self.cycle_ticks
        return (cycle - 1) / cycle if cycle > 1 else 1.0

    def coil_limits(self) -> Vec3:
        """Largest dipole per axis, A·m²: two coils on X and Y, the single Z− coil on Z."""
        return (2.0 * self.X_COIL_MAX_DIPOLE, 2.0 * self.Y_COIL_MAX_DIPOLE, self.Z_COIL_MAX_DIPOLE)

    def _wheels_available(self, fresh: bool) -> bool:
        """Every wheel connected and answering: by the cycle's own reading, or, for a command between
        cycles (``fresh``), by reading them now."""
        if fresh:
            io = self.io
            momenta = io.wheel_momenta()
            return io.wheel_count() == len(self.wheel_axes) and momenta is not None
        return self._cycle_wheel_count == len(self.wheel_axes) and self.wheel_momenta is not None

    @property
    def pointing_on_wheels(self) -> bool:
        """Whether POINTING flies (or would fly) on the wheels now (the cycle's own wheel reading)."""
        return self._pointing_uses_wheels()

    def _pointing_uses_wheels(self) -> bool:
        if self.POINTING_ACTUATOR == _MAGNETORQUERS:
            return False
        return self._wheels_available(fresh=False)

    def _pointing_available(self, *, report: bool, fresh: bool = False) -> bool:
        if self.POINTING_ACTUATOR == _WHEELS and not self._wheels_available(fresh):
            if report:
                self.notify.event("ModeUnavailableNoWheels", POINTING)
            return False
        if not self.attitude_valid:
            if report:
                self.notify.event("NoAttitudeKnowledge")
            return False
        return True

    def _set_autonomy(self, autonomy: int) -> None:
        if autonomy != self.autonomy:
            self.autonomy = autonomy
            self.notify.event("AutonomyChanged", autonomy)

    def _change_mode(self, mode: int, reason: int) -> None:
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
        if mode == POINTING and self.target is None and self.filter.q is not None:
            self.set_target(self.filter.q)  # nothing commanded yet: hold the present attitude
        if mode in (IDLE, DETUMBLE, SPIN_STABLE):
            self._command_wheels((0.0,) * len(self.wheel_axes))
        if mode == IDLE:
            self._stop_coils()
        self._known_in_sun_safe_s = 0.0
        self._sun_safe_reason = reason if mode == SUN_SAFE else None
        self.sun_bias.reset()
        self._sun_hold_on_change(old, mode)
        self.notify.mode_changed(old, mode, reason)
        if mode == SUN_SAFE:
            self.notify.event("SunSafeEntered", reason)
        elif old == SUN_SAFE:
            self.notify.event("SunSafeExited", mode, reason)

    # --- the tick -------------------------------------------------------------------------------

    def tick(self) -> None:
        """One rate-group tick: a control cycle on tick 0 of every CYCLE_TICKS, else the gyro reading
        joins the cycle's mean (a failed read is skipped); the coils go off on the cycle's last tick."""
        cycle = self.cycle_ticks
        phase = self.ticks % cycle
        self.ticks += 1
        if phase == 0:
            self._cycle()
        else:
            g = self.io.gyro()
            if g is not None:
                acc = self._gyro_sum
                self._gyro_sum = (acc[0] + g[0], acc[1] + g[1], acc[2] + g[2])
                self._gyro_count += 1
        if phase == cycle - 1 and self.coils_driven and cycle > 1:
            self._stop_coils()

    def _cycle(self) -> None:
        now_us = self.io.now_us()
        nominal = self.cycle_ticks * defaults.RATE_GROUP_PERIOD_S
        if self.last_cycle_us is None or now_us <= self.last_cycle_us:
            dt = nominal
        else:
            dt = (now_us - self.last_cycle_us) / 1e6
        self.last_cycle_us = now_us
        if self.first_cycle_us is None:
            self.first_cycle_us = now_us
        self.cycles += 1
        self._sense(dt, now_us)
        self._update_reference()
        if self.autonomy == AUTO:
            self._auto_mode(dt)
        elif self.mode == POINTING and not self.attitude_valid:
            self._attitude_lost()
        self._sun_safe_transitions(dt)
        self._actuate(dt)
        self.notify.cycle_done()

    # --- sensing --------------------------------------------------------------------------------

    def _make_filter(self, which: int) -> AttitudeFilter | Mekf:
        if which == _MEKF:
            return Mekf(math.radians(self.GYRO_NOISE), math.radians(self.GYRO_BIAS_WALK),
                        self.TRACKER_NOISE_CROSS * _ARCSEC, self.TRACKER_NOISE_ABOUT * _ARCSEC,
                        defaults.BORESIGHT_B, math.radians(self.GYRO_BIAS_SIGMA0))
        return AttitudeFilter(self.FILTER_KP, self.FILTER_KI)

    def _configure_filter(self) -> None:
        """Follow ESTIMATOR (a switch keeps the attitude, bias and fix age) and the noise/gain parameters."""
        which = self.ESTIMATOR
        if which != self.estimator:
            old, new = self.filter, self._make_filter(which)
            new.q, new.bias, new.since_measurement_s = old.q, old.bias, old.since_measurement_s
            if isinstance(new, Mekf) and new.q is not None:  # the new covariance: the tracker's noise, bias σ0
                new._initialise_attitude(new.q, new.tracker_noise())
            self.filter, self.estimator = new, which
            self.notify.event("EstimatorSelected", which)
        f = self.filter
        if isinstance(f, Mekf):
            f.gyro_noise = math.radians(self.GYRO_NOISE)
            f.bias_walk = math.radians(self.GYRO_BIAS_WALK)
            f.tracker_cross = self.TRACKER_NOISE_CROSS * _ARCSEC
            f.tracker_about = self.TRACKER_NOISE_ABOUT * _ARCSEC
        else:
            f.k_p = self.FILTER_KP
            f.k_i = self.FILTER_KI

    def _sense(self, dt: float, now_us: int) -> None:
        io, notify = self.io, self.notify
        self._configure_filter()
        gyro = io.gyro()
        n = 1
        if gyro is not None:
            notify.clear_event("GyroRetrievalFailed")
            n = self._gyro_count + 1  # the mean over the cycle's ticks: the noise the D term sees drops by √n
            acc = self._gyro_sum
            gyro = ((acc[0] + gyro[0]) / n, (acc[1] + gyro[1]) / n, (acc[2] + gyro[2]) / n)
        else:
            notify.event("GyroRetrievalFailed")
        self._gyro_sum, self._gyro_count = _ZERO, 0
        q_meas = None
        age_s = 0.0
        fix = io.attitude()
        if fix is not None and is_unit_quaternion(fix[0], tol=1e-2):
            stamp_us = fix[1]
            if stamp_us != self._last_fix_us and stamp_us <= now_us:  # a new solution (the tracker holds its last)
                self._last_fix_us = stamp_us
                q_meas = quat_normalize(fix[0])
                age_s = (now_us - stamp_us) / 1e6
        if gyro is not None:
            f = self.filter
            if isinstance(f, Mekf):
                before = f.reinitialisations
                f.update(gyro, dt, q_meas, age_s, samples=n)
                if f.reinitialisations != before:
                    notify.event("AttitudeReinitialised")
            else:
                f.update(gyro, dt, q_meas, age_s)
            self.omega = f.omega
            self.gyro_mean = gyro
        else:
            self.omega = None
        field = io.field()
        if field is not None:
            notify.clear_event("MagneticFieldRetrievalFailed")
            b, self.b_stamp_us = field
            self.b_gauss = b
            self.b_tesla = (b[0] * TESLA_PER_GAUSS, b[1] * TESLA_PER_GAUSS, b[2] * TESLA_PER_GAUSS)
        else:
            notify.event("MagneticFieldRetrievalFailed")
            self.b_tesla = None
        self._track_sun(dt, now_us)
        count = self._cycle_wheel_count = io.wheel_count()
        self.wheel_momenta = io.wheel_momenta() if count else None
        if self.b_tesla is not None and self.MAG_BIAS_TIME > 0.0 and not self._pointing_uses_wheels():
            self.b_tesla = self._correct_mag_bias(self.b_tesla, dt)
        self._track_field_line(dt)
        # the last cycle's body torque (self.dipole: what it drove, zero when off), for both users below
        torque = (applied_torque(self.wheel_torques, self.wheel_axes, self.dipole, self.b_tesla, self.duty)
                  if self.omega is not None else None)
        self._update_rate_observer(dt, torque)
        self._track_residual_dipole(dt, torque)

    def _field_model(self) -> OnboardField:
        """The on-board field model of MAG_FIELD_MODEL_DEGREE (made again when the parameter changes)."""
        degree = int(self.MAG_FIELD_MODEL_DEGREE)
        model = self._onboard_field
        if model is None or model.degree != degree:
            model = self._onboard_field = OnboardField(degree)
        return model

    def _correct_mag_bias(self, b_meas: Vec3, dt: float) -> Vec3:
        """The magnetometer reading ``b_meas`` (T, B) less the on-board bias estimate (MAG_BIAS_TIME > 0, called only
        while the coils are the pointing actuator: with the wheels pointing the reading is used as it is).

        The estimate low-passes, at the time constant MAG_BIAS_TIME (s), the reading minus the on-board field model
        (``control.geomagnetic.OnboardField`` of MAG_FIELD_MODEL_DEGREE at the ephemeris' position and Earth angle)
        turned into B by the attitude estimate: ``b̂ += min(dt/τ, 1) (b − A(q̂) B_model − b̂)``, started at the
        first difference. It is updated only with a valid attitude and an ephemeris, and held (still subtracted)
        without them; before the first update the reading is returned as it is. With τ of the order of the cycle
        the corrected field is the model's own (the reading's noise and bias gone, its model error in); with τ ≫ an
        orbit it is the reading less the orbit-mean of the model's error and the bias."""
        q = self.filter.q
        eph = self.io.ephemeris() if q is not None and self.attitude_valid else None
        if eph is not None and q is not None:
            try:
                b_model_B = rotate_n_to_b(q, self._field_model()(eph.r_N, eph.earth_angle_rad))
            except ValueError:
                b_model_B = None
            if b_model_B is not None:
                e = (b_meas[0] - b_model_B[0], b_meas[1] - b_model_B[1], b_meas[2] - b_model_B[2])
                est = self.mag_bias_T
                if est is None:
                    est = e
                else:
                    k = min(dt / self.MAG_BIAS_TIME, 1.0) if dt > 0.0 else 0.0
                    est = (est[0] + k * (e[0] - est[0]), est[1] + k * (e[1] - est[1]), est[2] + k * (e[2] - est[2]))
                self.mag_bias_T = est
        est = self.mag_bias_T
        if est is None:
            return b_meas
        return (b_meas[0] - est[0], b_meas[1] - est[1], b_meas[2] - est[2])

    def _update_rate_observer(self, dt: float, torque) -> None:
        """The derivative term's rate: the bias-corrected gyro, or the model-aided observer (RATE_SOURCE)."""
        obs = self.rate_observer
        if self.omega is None:
            obs.reset()
            self.pd_rate = None
            return
        xy, xz, yz = self.INERTIA_XY, self.INERTIA_XZ, self.INERTIA_YZ
        try:  # free when the parameters are the model's already (RateObserver.set_model compares first)
            obs.set_model(((self.INERTIA_XX, xy, xz), (xy, self.INERTIA_YY, yz), (xz, yz, self.INERTIA_ZZ)),
                          self.RATE_OBSERVER_GAIN)
            self.notify.clear_event("InertiaModelRefused")
        except ValueError:  # not positive definite: keep the last good model, say so once per change
            self.notify.event("InertiaModelRefused")
        h = _ZERO
        if self.wheel_momenta is not None:
            h = self._body_momentum(self.wheel_momenta)
        # a slew (the last cycle's error above RATE_BLEND_ANGLE): pull toward the gyro at RATE_BLEND_GAIN, so the
        # model's inertia error cannot build up a rate error over the slew's large torques
        # (docs/studies/robust_rates.md); at the default gain the step is the same floats as before
        blend = self.mode == POINTING and self.pointing_error_deg > self.RATE_BLEND_ANGLE
        b = None
        if self.RATE_OBSERVER_DIPOLE_TIME > 0.0 and self.b_tesla is not None:
            # the residual dipole, a body-fixed constant, learned while calm and kept across target changes and
            # mode changes (docs/studies/robust_rates.md, "The residual dipole in the observer")
            b = self.b_tesla
            w = self.omega
            calm = (not blend and _norm(w) < DIPOLE_LEARN_MAX_RATE and _norm(torque) < DIPOLE_LEARN_MAX_TORQUE)
            if calm:
                # the fit reads the gyro as measured: its bias is a constant with no slope, where the estimator's
                # bias correction moves while it converges and would read as a torque (the complementary filter's
                # did: docs/studies/robust_rates.md, limit (3))
                obs.learn_dipole(self.gyro_mean, torque, h, b, dt, self.RATE_OBSERVER_DIPOLE_TIME)
            else:
                obs.skip_dipole()
        w = obs.update(self.omega, torque, h, dt, self.RATE_BLEND_GAIN if blend else None, b)
        self.pd_rate = w if self.RATE_SOURCE == _OBSERVER else self.omega

    def _track_field_line(self, dt: float) -> None:
        """Feed the field-direction-rate estimator (every cycle with a field and an attitude, so it is
        settled when magnetorquer pointing starts); a gap in either restarts it."""
        fr = self.field_rate
        fr.bandwidth_rad_s = self.MAG_FIELD_RATE_BANDWIDTH
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
        if (self.MAG_RESIDUAL_MODE != _ESTIMATE or self.mode != POINTING or self._pointing_uses_wheels()
                or self.omega is None or self.b_tesla is None or self.attitude_known_s < self.MAG_SETTLE_TIME):
            est.gap()
            return
        est.window_s = self.MAG_RESIDUAL_WINDOW
        est.inertia = self.rate_observer.inertia
        ready = est.estimate is not None
        m = est.update(self.omega, torque, _ZERO, self.b_tesla, dt)
        if m is not None and not ready:
            self.notify.event("ResidualDipoleEstimated", m[0], m[1], m[2])

    def _residual_feed_forward(self) -> Vec3:
        """The residual dipole to cancel, A·m² (B), by MAG_RESIDUAL_MODE; an estimate past a coil limit is refused."""
        mode = self.MAG_RESIDUAL_MODE
        if mode == _OFF:
            return _ZERO
        est = self.residual_estimator.estimate
        if mode == _ESTIMATE and est is not None:
            lim = self.coil_limits()
            if _finite(*est) and all(abs(est[i]) <= lim[i] for i in range(3)):
                self.notify.clear_event("ResidualDipoleEstimateRefused")
                return est
            self.notify.event("ResidualDipoleEstimateRefused", est[0], est[1], est[2])
        return (self.MAG_RESIDUAL_DIPOLE_X, self.MAG_RESIDUAL_DIPOLE_Y, self.MAG_RESIDUAL_DIPOLE_Z)

    # --- AUTO -----------------------------------------------------------------------------------

    def spin_errors(self) -> tuple[float, float]:
        """``(axis error deg, rate error fraction)`` of ω̂ against ``SPIN_RATE_TARGET`` about +Z."""
        w = self.omega
        assert w is not None  # AUTO looks at the spin only with a rate estimate
        return spin_errors(w, self.SPIN_RATE_TARGET * _DEG)

    def _auto_mode(self, dt: float) -> None:
        if self.mode == IDLE:
            self._change_mode(DETUMBLE, _AUTO_START)
            return
        if self.omega is None:
            return  # no rate: keep the mode (B-dot needs no gyro)
        rate_deg = math.degrees(_norm(self.omega))
        if self.mode != DETUMBLE and rate_deg > self.DETUMBLE_ENTER_RATE:
            self._change_mode(DETUMBLE, _RATE_HIGH)
            return
        if self.mode == DETUMBLE:
            self._dwell_s = self._dwell_s + dt if rate_deg < self.DETUMBLE_EXIT_RATE else 0.0
            if self._dwell_s >= self.MODE_DWELL:
                self._change_mode(SPIN_STABLE, _RATE_LOW)
        elif self.mode == SPIN_STABLE:
            axis_deg, frac = self.spin_errors()
            if axis_deg <= self.SPIN_AXIS_ENTER and frac <= self.SPIN_RATE_ENTER:
                self._stable_s += dt
            elif axis_deg > self.SPIN_AXIS_RESET or frac > self.SPIN_RATE_RESET:
                self._stable_s = 0.0
            if self._stable_s >= self.SPIN_STABLE_DWELL:
                if self._pointing_available(report=True):
                    self._change_mode(POINTING, _SPIN_STABLE_REACHED)
        elif self.mode == POINTING and not self.attitude_valid:
            self._attitude_lost()

    # --- SUN_SAFE -------------------------------------------------------------------------------

    def _attitude_lost(self) -> None:
        """POINTING without attitude knowledge: SUN_SAFE where a Sun vector source is connected, SPIN_STABLE
        otherwise (both in AUTO and MANUAL)."""
        self.notify.event("AttitudeKnowledgeLost")
        self._change_mode(SUN_SAFE if self.io.has_sun_sensor() else SPIN_STABLE, _ATTITUDE_LOST)

    def _sun_safe_transitions(self, dt: float) -> None:
        """The mode manager's safe mode puts SPIN_STABLE and POINTING into SUN_SAFE (in either autonomy) and holds
        it there; SUN_SAFE entered on a loss of attitude or on the safe mode hands back to POINTING once the attitude
        has been known for SUN_SAFE_EXIT_DWELL outside safe mode (KNOWLEDGE_RESTORED). One commanded stays."""
        io = self.io
        safe = io.system_safe_mode() is True
        self.system_safe = safe
        mode = self.mode
        if safe and mode in (SPIN_STABLE, POINTING) and io.has_sun_sensor():
            self._change_mode(SUN_SAFE, _SYSTEM_SAFE_MODE)
            return
        if mode != SUN_SAFE:
            return
        if self._sun_safe_reason == _SYSTEM_SAFE_MODE and not safe:
            self._sun_safe_reason = _ATTITUDE_LOST  # out of safe mode: wait for the attitude as after a loss
        if self._sun_safe_reason != _ATTITUDE_LOST or not self.attitude_valid:
            self._known_in_sun_safe_s = 0.0
            return
        self._known_in_sun_safe_s += dt
        if self._known_in_sun_safe_s >= self.SUN_SAFE_EXIT_DWELL and self._pointing_available(report=False):
            self._change_mode(POINTING, _KNOWLEDGE_RESTORED)

    def _sun_hold_on_change(self, old: int, mode: int) -> None:
        """The coils' spin-down (SunHold) across mode changes: kept when SUN_SAFE is entered again within
        SUN_HOLD_DWELL of leaving it with the spin lowered (the Sun was held moments ago; POINTING on the coils
        starting from the spin can lose the tracker again, and the acquisition spin would smear it for good in an
        eclipse); otherwise started afresh on entering SUN_SAFE."""
        now = self.last_cycle_us
        if old == SUN_SAFE:
            self._sun_left_us = now
        if mode != SUN_SAFE:
            return
        left = self._sun_left_us
        recent = left is not None and now is not None and (now - left) / 1e6 <= self.SUN_HOLD_DWELL
        if not (recent and self.sun_hold.lowered):
            self.sun_hold.reset()
        self.sun_error_deg_last = math.nan

    def _sun_rate(self) -> Vec3 | None:
        """The rate SUN_SAFE uses (rad/s, B): ω̂ less the Sun-vector bias estimate (zero outside SUN_SAFE)."""
        w = self.omega
        if w is None:
            return None
        b = self.sun_bias.bias
        return (w[0] - b[0], w[1] - b[1], w[2] - b[2])

    def _track_sun(self, dt: float, now_us: int) -> None:
        """The Sun vector in B: a new valid light-sensor reading is taken (carried from its time to now on the
        gyro); between readings the last one is carried on the gyro (``v̇ = −ω × v``). Older than
        SUN_VECTOR_TIMEOUT (eclipse, failed sensors) it is dropped. In SUN_SAFE a new reading against the last one
        carried to now also feeds the gyro-bias observer (``control.sun_safe.SunRateBias``)."""
        io = self.io
        if not io.has_sun_sensor():
            self.sun_B, self.sun_age_s = None, math.inf
            return
        w = self._sun_rate()
        reading = io.sun_vector()
        if reading is not None:
            self.notify.clear_event("SunVectorRetrievalFailed")
            s, valid, stamp = reading
            if valid and stamp != self._sun_stamp_us and stamp <= now_us and _finite(*s) and _norm(s) > 0.5:
                prev_stamp, self._sun_stamp_us = self._sun_stamp_us, stamp
                age = (now_us - stamp) / 1e6
                n = _norm(s)
                s = (s[0] / n, s[1] / n, s[2] / n)
                s = propagate_body_vector(s, w, age) if w is not None else s
                if self.mode == SUN_SAFE and self.sun_B is not None and w is not None and prev_stamp is not None:
                    self.sun_bias.time_s = self.SUN_BIAS_TIME
                    self.sun_bias.update(s, propagate_body_vector(self.sun_B, w, dt), (stamp - prev_stamp) / 1e6)
                self.sun_B = s
                self.sun_age_s = age
                return
        else:
            self.notify.event("SunVectorRetrievalFailed")
        self.sun_age_s += dt
        if self.sun_B is not None and self.sun_age_s > self.SUN_VECTOR_TIMEOUT:
            self.sun_B = None
        elif self.sun_B is not None and w is not None:
            self.sun_B = propagate_body_vector(self.sun_B, w, dt)

    def _sun_safe_torque(self, kp: float, kd: float) -> Vec3:
        """SUN_SAFE's torque request (N·m, B): turn SUN_SAFE_AXIS to the Sun at a rate ``K_P/K_D θ`` capped at
        SLEW_RATE_LIMIT about ``â × ŝ`` and damp every other rate, ``τ = K_D (ω_c − ω)``; without a Sun vector
        (eclipse) only the damping ``−K_D ω``. Gains: the wheels' SUN_SAFE_K_P/K_D or the coils' *_MAG."""
        w = self._sun_rate()
        assert w is not None  # SUN_SAFE actuates only with a rate estimate
        s = self.sun_B
        if s is None:
            self.sun_error_deg = math.nan
            return (-kd * w[0], -kd * w[1], -kd * w[2])
        a = BODY_AXES[self.SUN_SAFE_AXIS][1]
        e = _cross(a, s)
        sin_t = _norm(e)
        theta = math.atan2(sin_t, a[0] * s[0] + a[1] * s[1] + a[2] * s[2])
        self.sun_error_deg = math.degrees(theta)
        if sin_t < 1e-9:  # on the axis, or exactly opposite: turn about any axis ⟂ â
            e, sin_t = ((a[1], a[2], a[0]), 1.0) if theta > 1.0 else (_ZERO, 1.0)
        rate = min(kp / kd * theta if kd > 0.0 else 0.0, self.SLEW_RATE_LIMIT * _DEG)
        k = rate / sin_t
        return (kd * (k * e[0] - w[0]), kd * (k * e[1] - w[1]), kd * (k * e[2] - w[2]))

    def _sun_spin_torque(self, dt: float) -> Vec3:
        """SUN_SAFE on the magnetorquers (``control.sun_safe.sun_spin_torque``): spin SUN_SAFE_AXIS at
        SUN_SPIN_RATE and tip it to the Sun at ``SUN_SAFE_K_P_MAG/SUN_SAFE_K_D_MAG θ`` (capped at
        SLEW_RATE_LIMIT); the transverse rate damped at SUN_SAFE_K_D_MAG, the spin held at SPIN_K_RATE. Once the Sun
        has been within SUN_HOLD_ANGLE for SUN_HOLD_DWELL (``control.sun_safe.SunHold``) the spin is
        SUN_HOLD_SPIN_RATE instead (SunSpinLowered), below the star tracker's rate limit, so its fixes can return;
        the ramp there advances only while the field is at least SUN_HOLD_FIELD_ANGLE from the axis."""
        w = self._sun_rate()
        assert w is not None  # SUN_SAFE actuates only with a rate estimate
        kd = self.SUN_SAFE_K_D_MAG
        axis = BODY_AXES[self.SUN_SAFE_AXIS][1]
        b = self.b_tesla
        b_n = _norm(b) if b is not None else 0.0
        cos_b = (b[0] * axis[0] + b[1] * axis[1] + b[2] * axis[2]) / b_n if b is not None and b_n > 0.0 else None
        hold, lowered = self.sun_hold, self.sun_hold.lowered
        tip = None
        if self.SUN_HOLD_TIP_ANGLE > 0.0 and b is not None and self.sun_B is not None:
            tip = spin_down_tip(axis, b, self.sun_B)
        spin = hold.spin(self.sun_error_deg_last, dt, self.SUN_SPIN_RATE, self.SUN_HOLD_SPIN_RATE, self.SUN_HOLD_ANGLE,
                         self.SUN_HOLD_DWELL, self.SUN_HOLD_RAMP, cos_b, self.SUN_HOLD_FIELD_ANGLE, tip,
                         self.SUN_HOLD_TIP_ANGLE)
        if hold.lowered and not lowered:
            self.notify.event("SunSpinLowered", self.SUN_HOLD_SPIN_RATE)
        tau, theta = sun_spin_torque(w, self.sun_B, axis, self.rate_observer.inertia,
                                     spin * _DEG, kd, self.SPIN_K_RATE,
                                     self.SUN_SAFE_K_P_MAG / kd if kd > 0.0 else 0.0, self.SLEW_RATE_LIMIT * _DEG)
        self.sun_error_deg = self.sun_error_deg_last = theta
        return tau

    # --- actuation ------------------------------------------------------------------------------

    def _actuate(self, dt: float) -> None:
        mode = self.mode
        self.residual_ff = _ZERO
        tau = _ZERO
        dipole = None  # None: coils off this cycle
        wheel_u = None  # None: wheels at zero torque
        levels = None  # (dipole, _coil_levels(dipole)) when already worked out for the dipole driven below
        self.pointing_error_deg = float("nan")
        self.sun_error_deg = float("nan")
        if mode == DETUMBLE:
            dipole = self._detumble_dipole()
            if dipole is not None:  # B-dot: each axis saturates on its own, as the flight coils do
                dipole = clip_to_limits(dipole, self.coil_limits())
        elif mode == SPIN_STABLE and self.omega is not None:
            tau = self._spin_torque(dt)
            if self.b_tesla is not None:
                dipole, _ = project_dipole_weighted(tau, self.b_tesla, self.coil_limits())
        elif mode == SUN_SAFE and self.omega is not None:
            if self._pointing_uses_wheels():
                tau = self._sun_safe_torque(self.SUN_SAFE_K_P, self.SUN_SAFE_K_D)
                wheel_u = self._allocate(tau)
            else:
                tau = self._sun_spin_torque(dt)
                if self.b_tesla is not None:
                    dipole, _ = project_dipole_weighted(tau, self.b_tesla, self.coil_limits())
        elif mode == POINTING and self.omega is not None and self.attitude_valid:
            q = self.filter.q
            assert q is not None  # attitude_valid
            if self.target is None:
                self.set_target(q)
            target = self.target
            assert target is not None  # set_target set it
            if self._pointing_uses_wheels():
                rate = base = self.pd_rate if self.pd_rate is not None else self.omega
                ref = self.reference
                ff = None
                if ref is not None and (ref.omega_R != _ZERO or ref.alpha_R != _ZERO):
                    # a moving reference: the PD acts on the rate relative to it, and the torque its motion needs
                    # is fed forward (an inertial target skips this, so its floats are those of the plain PD)
                    rate, ff = self._reference_feed_forward(ref, quat_error(target, q), rate)
                elif self.WHEEL_FEED_FORWARD == _FF_GRAVITY:
                    ff = self._body_feed_forward(q, rate)
                tau, qe = pd_torque(target, q, rate, self.K_P, self.K_D, self.SLEW_RATE_LIMIT * _DEG)
                if ff is not None:
                    tau = (tau[0] + ff[0], tau[1] + ff[1], tau[2] + ff[2])
                self.integrator.window_rad = self.INTEGRAL_WINDOW * _DEG
                # the rate gate reads the gyro (the bias-corrected cycle mean) relative to the reference, not the
                # D term's observer rate: that one carries an unmodelled torque's d/(I L) and would shut the gate
                # on the very offset the integral is there to remove (docs/studies/robust_rates.md, "The rate gate")
                self.integrator.rate_gate_rad_s = self.INTEGRAL_RATE_GATE * _DEG
                w = self.omega
                gate_rate = (w[0] - base[0] + rate[0], w[1] - base[1] + rate[1], w[2] - base[2] + rate[2])
                ti = self.integrator.update(qe, dt, self.K_I, gate_rate)
                tau = (tau[0] + ti[0], tau[1] + ti[1], tau[2] + ti[2])
                tau_mag = _ZERO
                if self.b_tesla is not None and self.wheel_momenta is not None:
                    h_b = self._body_momentum(self.wheel_momenta)
                    limits = self.coil_limits()
                    dipole, _ = project_dipole_weighted(dump_torque(h_b, self.K_DUMP), self.b_tesla, limits)
                    dipole = scale_to_limits(dipole, limits)
                    levels = (dipole, self._coil_levels(dipole))
                    mb = _cross(levels[1][1], self.b_tesla)
                    d = self.duty
                    tau_mag = (mb[0] * d, mb[1] * d, mb[2] * d)
                # the wheels supply what the dump torque does not (it would otherwise disturb the pointing)
                wheel_u = self._allocate((tau[0] - tau_mag[0], tau[1] - tau_mag[1], tau[2] - tau_mag[2]))
            else:
                tau, qe = self._magnetic_pointing_torque(target, q)
                if self.attitude_known_s < self.MAG_SETTLE_TIME:
                    tau = _ZERO  # the gyro-bias estimate is still settling: the coils wait (no dipole)
                elif self.b_tesla is not None:
                    dipole, _ = project_dipole_weighted(tau, self.b_tesla, self.coil_limits())
                    # cancel the residual dipole, which acts all the time, with coils on for the duty share
                    ff = self.residual_ff = self._residual_feed_forward()
                    d = self.duty
                    dipole = (dipole[0] - ff[0] / d, dipole[1] - ff[1] / d, dipole[2] - ff[2] / d)
            self.pointing_error_deg = math.degrees(quat_angle(qe))
        self.torque_request = tau
        if dipole is None:
            if self.coils_driven:
                self._stop_coils()
            self.dipole = _ZERO
        else:
            m = scale_to_limits(dipole, self.coil_limits())
            # the levels of the dump dipole are reused when the limit left it as it was (the same object)
            self._drive_coils(m, levels[1] if levels is not None and levels[0] is m else None)
        if wheel_u is None:
            wheel_u = (0.0,) * len(self.wheel_axes)
        self._command_wheels(wheel_u)

    def _reference_feed_forward(self, ref: Reference, q_err: Quat, rate: Vec3) -> tuple[Vec3, Vec3]:
        """``(ω − ω_r, τ_ff)`` in B for the reference ``ref`` seen from the attitude ``q_err`` (= q_BR): the
        reference rate ``ω_r = [BR] ω_R`` and acceleration ``α_r = [BR] α_R``; ``τ_ff = I (α_r − ω × ω_r)`` (the
        torque that keeps a body on the reference turning with it), plus :meth:`_body_feed_forward` with
        WHEEL_FEED_FORWARD = REFERENCE_GYROSCOPIC or REFERENCE_GYROSCOPIC_GRAVITY. ``I``: the INERTIA_* model;
        ``ω``: the D term's rate."""
        w_r = rotate_n_to_b(q_err, ref.omega_R)
        a_r = rotate_n_to_b(q_err, ref.alpha_R)
        inertia = self.rate_observer.inertia
        wxr = _cross(rate, w_r)
        d = (a_r[0] - wxr[0], a_r[1] - wxr[1], a_r[2] - wxr[2])
        ff = (inertia[0][0] * d[0] + inertia[0][1] * d[1] + inertia[0][2] * d[2],
              inertia[1][0] * d[0] + inertia[1][1] * d[1] + inertia[1][2] * d[2],
              inertia[2][0] * d[0] + inertia[2][1] * d[1] + inertia[2][2] * d[2])
        if self.WHEEL_FEED_FORWARD != _FF_REFERENCE:  # the gyroscopic term (and gravity gradient)
            g = self._body_feed_forward(self.filter.q, rate)
            ff = (ff[0] + g[0], ff[1] + g[1], ff[2] + g[2])
        return (rate[0] - w_r[0], rate[1] - w_r[1], rate[2] - w_r[2]), ff

    def _body_feed_forward(self, q: Quat | None, rate: Vec3) -> Vec3:
        """The wheels' share of Euler's equation beyond the PD (N·m, B): the gyroscopic ``ω × (I ω + h_w)`` and,
        with REFERENCE_GYROSCOPIC_GRAVITY and an ephemeris, minus the gravity-gradient torque ``3 μ/r³ r̂ × (I r̂)``
        the model expects at the estimated attitude ``q`` (I: INERTIA_*; the controller's μ)."""
        inertia = self.rate_observer.inertia
        h = self._body_momentum(self.wheel_momenta) if self.wheel_momenta is not None else _ZERO
        ff = gyroscopic_torque(inertia, rate, h)
        if self.WHEEL_FEED_FORWARD == _FF_GRAVITY and q is not None:
            eph = self.io.ephemeris()
            if eph is not None:
                gg = gravity_gradient_torque(inertia, rotate_n_to_b(q, eph.r_N), MU_EARTH_M3_S2)
                ff = (ff[0] - gg[0], ff[1] - gg[1], ff[2] - gg[2])
        return ff

    def _magnetic_pointing_torque(self, target: Quat, q: Quat):
        """``(τ_req, q_err)`` of the MAG_POINTING_LAW (before the projection ⟂ B)."""
        w = self.omega
        assert w is not None  # POINTING actuates only with a rate estimate
        kp, kd = self.K_P_MAG, self.K_D_MAG
        if self.MAG_POINTING_LAW == _SEED_PD or self.b_tesla is None:
            return pd_torque(target, q, w, kp, kd)
        if self.MAG_LQR_ANGLE > 0.0:
            lqr = self._model_lqr_torque(target, q, w)
            if lqr is not None:
                return lqr
        bd = self.bdot_hat_B if self.bdot_hat_B is not None else _ZERO  # no estimate yet: the law's ρ = 0 case
        return field_steering_torque(target, q, w, self.b_tesla, bd, kp, kd, self.MAG_STEER_RHO,
                                     self.MAG_STEER_ZETA, self.MAG_FIELD_RATE_MIN, self.MAG_STEER_RHO_LARGE,
                                     self.MAG_STEER_RHO_FROM, self.MAG_STEER_RHO_AT)

    def _model_lqr_torque(self, target: Quat, q: Quat, w: Vec3):
        """``(τ_req, q_err)`` of the hold scheduled on the on-board field model (``control.magnetic_lqr``), or None
        where it does not apply: a moving target, an error of MAG_LQR_ANGLE or more, or no table for the target (yet).
        ``τ_req = m × b`` for the LQR's dipole ``m`` and the field ``b`` the projection uses, so the projection gives
        ``m`` back (its part ⟂ b). The table is built over cycles (:meth:`_build_lqr_table`) whatever the error, so it
        is usually ready when the error comes below the angle."""
        spec = self.target_spec
        if spec is not None and spec.needs_ephemeris:
            self._lqr_builder = None
            return None
        t = (self.io.now_us() - (self.first_cycle_us or 0)) / 1e6  # s on the table's clock
        self._build_lqr_table(target, t)
        qe = quat_error(target, q)
        if math.degrees(quat_angle(qe)) >= self.MAG_LQR_ANGLE:
            return None
        table = self._lqr_table
        gain = table.gain(t) if table is not None and table.q_tn == target else None
        if gain is None:
            return None
        b = self.b_tesla
        assert b is not None  # the caller steers on the field reading
        m = lqr_dipole_B(gain, qe, w)
        return _cross(m, b), qe

    def _build_lqr_table(self, target: Quat, t: float) -> None:
        """One cycle's share (MAG_LQR_BUDGET_UNITS) of the gain table for ``target``: a build starts (from the
        ephemeris now) when there is no table for the target or the one in use has less than the last build's time
        plus MAG_LQR_RENEW_MARGIN_S left, and none is under way; a target change abandons the build under way. The
        finished table replaces the one in use. A failed build: ``MagLqrTableFailed`` and no new build for
        MAG_LQR_RETRY_S (s)."""
        builder = self._lqr_builder
        if builder is not None and builder.q_tn != target:
            builder = self._lqr_builder = None  # a new target: the build under way is for the old one
        if builder is None:
            table = self._lqr_table
            if ((table is not None and table.q_tn == target and table.t0_s + table.use_s - t > self._lqr_lead_s)
                    or t < self._lqr_retry_s):
                return
            eph = self.io.ephemeris()
            if eph is None:
                return
            duty = self.duty
            inertia = tuple(tuple(x / duty for x in row) for row in self.rate_observer.inertia)
            builder = self._lqr_builder = HoldGainTableBuilder(
                target, t, eph.r_N, eph.v_N, eph.earth_angle_rad, inertia, self.coil_limits(), MAG_LQR_STEP_S,
                MAG_LQR_USE_S, MAG_LQR_EXTRA_S, MAG_LQR_THETA_SCALE, MAG_LQR_RATE_SCALE, MAG_LQR_R_WEIGHT,
                MAG_LQR_ALPHA, self._field_model())
            self._lqr_build_s = t
        done = builder.units_done
        try:
            table = builder.advance(MAG_LQR_BUDGET_UNITS)
        except (ArithmeticError, ValueError) as exc:
            self.lqr_work_units += builder.units_done - done
            self._lqr_builder = None
            self._lqr_retry_s = t + MAG_LQR_RETRY_S
            reason = str(exc).encode()[:80].decode(errors="ignore")  # the event's String(80), in bytes
            self.notify.event("MagLqrTableFailed", reason, MAG_LQR_RETRY_S)
            return
        self.lqr_work_units += builder.units_done - done
        if table is not None:
            self._lqr_table = table
            self._lqr_builder = None
            self._lqr_lead_s = t - self._lqr_build_s + MAG_LQR_RENEW_MARGIN_S
            self.notify.clear_event("MagLqrTableFailed")

    def _body_momentum(self, momenta) -> Vec3:
        """``Σ h_i g_i`` over the wheels, N·m·s (B)."""
        axes, alloc = self._momentum_alloc
        if axes != self.wheel_axes:
            alloc = WheelAllocator(self.wheel_axes, 1.0, 1.0)
            self._momentum_alloc = (self.wheel_axes, alloc)
        return alloc.body_momentum(momenta)

    def _allocate(self, tau: Vec3):
        key, alloc = self._limit_alloc
        wanted = (self.wheel_axes, self.WHEEL_MAX_TORQUE, self.WHEEL_MAX_MOMENTUM)
        if key != wanted:  # first use, or a limit parameter changed: the allocator's limits follow
            alloc = WheelAllocator(*wanted)
            self._limit_alloc = (wanted, alloc)
        # more than three wheels: their null-space momentum is managed at K_DUMP (no body torque)
        u, limited = alloc.allocate(tau, self.wheel_momenta, self.K_DUMP)
        if limited:
            self.notify.event("WheelLimitReached")
        else:
            self.notify.clear_event("WheelLimitReached")
        return u

    def _detumble_dipole(self) -> Vec3 | None:
        provider = self.provider
        if provider.has_dipole_provider():
            m = provider.provider_dipole()
            primed, self._bdot_primed = self._bdot_primed, True
            if m is None:
                if primed:  # the provider's first call after entering DETUMBLE only primes it
                    self.notify.event("DipoleMomentRetrievalFailed")
                return None
            self.notify.clear_event("DipoleMomentRetrievalFailed")
            return m
        if self.b_tesla is None:
            return None
        now = (self.b_gauss, self.b_stamp_us)
        prev, self._b_prev = self._b_prev, now
        if prev is None:
            return None
        return bdot_dipole(prev[0], now[0], (now[1] - prev[1]) / 1e6, self.K_BDOT)

    def _spin_torque(self, dt: float) -> Vec3:
        law = self.SPIN_LAW
        w = self.omega
        assert w is not None  # spin control runs only with a rate estimate
        c, i_d = self.C_DAMP, self.I_D
        if law == _SEED_KANE_DAMPER:
            sd = self.seed_damper
            sd.c_damp, sd.i_d = c, i_d
            b = self.b_tesla
            # τ_mag: the magnetic torque the previous cycle's dipole produced (its on-time share)
            tau_mag = _cross(self.dipole, b) if b is not None else _ZERO
            d = self.duty
            sd.update((tau_mag[0] * d, tau_mag[1] * d, tau_mag[2] * d), dt)
            self.damper_state = sd.w_d
            return sd.torque_request()
        if law == _VIRTUAL_DAMPER:
            vd = self.virtual_damper
            vd.c_damp, vd.i_d = c, i_d
            vd.update(w, dt)
            self.damper_state = _norm(vd.omega_d) if vd.omega_d is not None else 0.0
            return vd.torque_request(w)
        reg = SpinRateRegulator(self.SPIN_K_TRANSVERSE, self.SPIN_K_RATE, self.SPIN_RATE_TARGET * _DEG)
        self.damper_state = w[2] - reg.rate
        return reg.torque_request(w)

    # --- actuators ------------------------------------------------------------------------------

    def _command_wheels(self, u) -> None:
        self.wheel_torques = self.io.set_wheel_torques(u)

    def _coil_levels(self, m: Vec3):
        """``(levels X+, X−, Y+, Y−, Z−, achieved dipole A·m²)`` for the dipole ``m`` (A·m², B): half of
        m_x on each X coil, half of m_y on each Y coil, m_z on Z−; X−, Y− and Z− face the other way."""
        return face_coil_levels(m, self.X_COIL_MAX_DIPOLE, self.Y_COIL_MAX_DIPOLE, self.Z_COIL_MAX_DIPOLE)

    def _drive_coils(self, m: Vec3, coil_levels=None) -> None:
        """Drive the five coils for the dipole ``m``; ``self.dipole`` becomes what the rounded levels give.
        ``coil_levels``: ``_coil_levels(m)`` when the caller has it already."""
        levels, self.dipole = coil_levels if coil_levels is not None else self._coil_levels(m)
        self.io.drive_coils(levels, self.dipole)
        self.coils_driven = True

    def _stop_coils(self) -> None:
        self.io.stop_coils()
        self.coils_driven = False
