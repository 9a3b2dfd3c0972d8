"""The three-mode attitude controller flown plant-only (``fprime-lite sim --law adcs``; no framework).

:class:`AdcsLaw` is the flight :class:`~detumble.components.attitude_controller.AttitudeController`
in AUTO, rebuilt from the same plain functions of :mod:`detumble.control` and started from the same
defaults (:mod:`detumble.control.attitude_defaults`): DETUMBLE (B-dot, by default the BDotDetumble
provider's ``m = −Gain·Ḃ/|B|``) → SPIN_STABLE (spin law, dipole projected ⟂ B) → POINTING (MEKF
attitude, rate observer, quaternion PD + integral on the wheels with magnetic momentum dumping, or
FIELD_STEERING on the magnetorquers when the spacecraft has no wheels).

Timing is the deployment's: :meth:`AdcsLaw.tick` is called once per rate-group tick
(``RATE_GROUP_PERIOD_S``, 20 ms); every ``CYCLE_TICKS`` ticks (default 5, so 10 Hz) one control
cycle runs on tick 0, the gyro is averaged over the cycle's ticks, and the coils are switched off on
the last tick so the next cycle's magnetometer sample is free of their field. A command stamped at
time t acts from the first cycle after t, on the state the cycle before left, as in the deployment,
where its handler runs after the rate group's cycle of that instant; the transition it causes is
stamped t, as the component's event is.

What it leaves out, because nothing plant-only can produce it: commands (it starts in AUTO with the
target it is given, as the start-up sequence sets it, or takes one FORCE_MODE at a set time:
``force_mode``, and SET_TARGET_QUATERNION at set times: ``target_changes``), telemetry and events,
and the fault paths of failed or non-finite reads (the plant's sensors always answer). The wheels start enabled, as the
plant's do.

Frames and units: body B, inertial N; quaternions ``q_BN`` scalar first; rates rad/s inside (deg/s in
the parameters); field gauss from the sensor, tesla inside; time stamps integer µs of plant time.
"""

from __future__ import annotations

import math
from typing import Mapping, Sequence

from detumble.analysis.pooled_stats import POINTING_THRESHOLDS_DEG, error_statistics
from detumble.control import attitude_defaults
from detumble.control.attitude_filter import AttitudeFilter
from detumble.control.magnetic import (bdot_dipole, clip_to_limits, dump_torque, project_dipole_weighted,
                                       scale_to_limits)
from detumble.control.magnetic_pointing import FieldDirectionRate, ResidualDipoleEstimator, field_steering_torque
from detumble.control.magnetorquer import face_coil_levels
from detumble.control.mekf import Mekf
from detumble.control.pointing import ErrorIntegrator, pd_torque
from detumble.control.quaternion import is_unit_quaternion, quat_angle, quat_error, quat_normalize, quat_shortest
from detumble.control.rate_observer import RateObserver, applied_torque
from detumble.control.spin import SeedKaneDamper, SpinRateRegulator, VirtualDamper, spin_errors
from detumble.control.wheel_allocation import WheelAllocator
from detumble.sim.vec import cross as _cross

__all__ = ["AdcsLaw", "PlantIo", "MODES", "COIL_FACES", "pointing_statistics"]

#: The controller's modes, as the flight ControlMode names them.
MODES = ("IDLE", "DETUMBLE", "SPIN_STABLE", "POINTING")
Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]
_DEG = math.pi / 180.0
_ARCSEC = _DEG / 3600.0
_ZERO = (0.0, 0.0, 0.0)
_XYZ = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
#: Coil faces in the order the controller drives them: X+, X−, Y+, Y−, Z− (plant face numbers).
COIL_FACES = (0, 1, 2, 3, 5)


def _settings(overrides: Mapping[str, object] | None) -> dict:
    """The defaults with ``overrides`` (flight parameter names) applied; a clear error for a bad one."""
    out = dict(attitude_defaults.DEFAULTS)
    for key, value in (overrides or {}).items():
        if key not in out:
            raise ValueError(f"unknown attitude-controller parameter {key!r}; known: {', '.join(sorted(out))}")
        choices = attitude_defaults.ENUM_CHOICES.get(key)
        if choices is not None:
            if value not in choices:
                raise ValueError(f"{key} must be one of {', '.join(choices)}, got {value!r}")
        elif isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise ValueError(f"{key} must be a finite number, got {value!r}")
        out[key] = value
    return out


def _as_target(q) -> Quat:
    """A commanded ``q_TN`` as SET_TARGET_QUATERNION stores it: re-normalised, scalar part ≥ 0."""
    c = tuple(float(x) for x in q)
    return quat_shortest(quat_normalize((c[0], c[1], c[2], c[3])))


class PlantIo:
    """The law's sensors and actuators on a :class:`~detumble.sim.plant.Plant`, read as the deployment's
    simulated drivers read them (held samples with their own time stamps, integer µs)."""

    def __init__(self, plant) -> None:
        self.plant = plant
        act = plant.actuators
        coils = getattr(act, "coils", None)
        self.face_coils = coils is not None and all(f in coils for f in COIL_FACES)
        self.has_tracker = plant.star_tracker is not None
        self.wheels = plant.wheel_count

    def now_us(self) -> int:
        return self.plant.t_ns // 1000

    def gyro(self) -> tuple[float, float, float]:
        """The held gyro sample, rad/s, B."""
        w = self.plant.gyro_reading()
        return (w[0], w[1], w[2])

    def field(self) -> tuple[tuple[float, float, float], int]:
        """``(b gauss in B, sample time µs)``: the held magnetometer sample."""
        p = self.plant
        mag = p.magnetometer
        if mag.spec.ideal:
            g = p.magnetometer_reading()
            return (g[0], g[1], g[2]), p.t_ns // 1000
        s = mag.sample_gauss
        return (s[0], s[1], s[2]), mag.sample_time_ns // 1000

    def attitude(self):
        """``(q_BN, stamp µs)`` of the held star-tracker solution when it is valid, else None."""
        if not self.has_tracker:
            return None
        q0, q1, q2, q3, valid, t = self.plant.star_tracker_reading()
        if not valid:
            return None
        return (q0, q1, q2, q3), int(round(t * 1e9)) // 1000

    def wheel_momenta(self) -> tuple[float, ...]:
        p = self.plant
        return tuple(p.wheel_reading(i)[1] for i in range(self.wheels))

    def drive_coils(self, levels: Sequence[int], dipole_B) -> None:
        """Set the five face coils to ``levels`` (X+, X−, Y+, Y−, Z−); torque rods get ``dipole_B``."""
        p = self.plant
        if self.face_coils:
            for face, level in zip(COIL_FACES, levels, strict=True):
                p.set_coil_level(face, level)
        else:
            p.apply_dipole_B(dipole_B)

    def stop_coils(self) -> None:
        self.drive_coils((0, 0, 0, 0, 0), _ZERO)

    def set_wheel_torques(self, torques: Sequence[float]) -> None:
        p = self.plant
        for i in range(min(self.wheels, len(torques))):
            p.set_wheel_torque(i, torques[i])


class AdcsLaw:
    """The three-mode controller in AUTO (or in a forced mode), one :meth:`tick` per rate-group tick.

    Args:
        wheel_axes: unit spin axes of the wheels in B (three to four; default x, y, z).
        wheels: whether those wheels answer (False: pointing on the magnetorquers alone).
        params: flight parameter name → value, over :data:`~detumble.control.attitude_defaults.DEFAULTS`.
        target_q_bn: the POINTING target ``q_TN`` (any length, re-normalised as SET_TARGET_QUATERNION
            does); None holds the attitude POINTING starts from.
        bdot_provider: DETUMBLE takes the BDotDetumble provider's dipole (``m = −Gain·Ḃ/|B|``, as
            adcs_ref connects it); False: the controller's own ``M = −K_BDOT Ḃ``.
        provider_gain: that provider's Gain, A·m²·s.
        auto_start_s: plant time (s) from which the controller is in AUTO; before it, it stays in
            IDLE (estimating, coils off, wheels at zero torque) as the component does until the start-up
            sequence's SET_AUTO arrives (in adcs_ref that is the second cycle, t = 0.1 s).
        force_mode: instead of AUTO, the mode a FORCE_MODE command sent at plant time ``force_at_s``
            (s) and holds; POINTING is refused, as the component refuses it, without attitude
            knowledge (the controller then stays in IDLE).
        target_changes: ``(t_s, q_TN)`` pairs: at plant time ``t_s`` (s) the target becomes ``q_TN``
            (re-normalised, and the error integral cleared, as SET_TARGET_QUATERNION does); in time
            order. Each acts from the first control cycle after its time (see the module docstring).
    """

    name = "adcs"
    ticked = True  # the runner calls tick() every rate-group tick
    full_state = False
    wheel_law = False

    def __init__(self, wheel_axes: Sequence[Sequence[float]] = _XYZ, wheels: bool = True,
                 params: Mapping[str, object] | None = None, target_q_bn=None, *, bdot_provider: bool = True,
                 provider_gain: float = attitude_defaults.BDOT_PROVIDER_GAIN, auto_start_s: float = 0.0,
                 force_mode: str | None = None, force_at_s: float = 0.0,
                 target_changes: Sequence[tuple[float, Sequence[float]]] = ()) -> None:
        p = _settings(params)
        self.params = p
        self.axes = tuple((float(a[0]), float(a[1]), float(a[2])) for a in wheel_axes)
        self.wheels = bool(wheels)
        self.cycle_ticks = max(1, int(p["CYCLE_TICKS"]))
        self.duty = (self.cycle_ticks - 1) / self.cycle_ticks if self.cycle_ticks > 1 else 1.0
        self.tick_s = attitude_defaults.RATE_GROUP_PERIOD_S
        self.coil_max = (p["X_COIL_MAX_DIPOLE"], p["Y_COIL_MAX_DIPOLE"], p["Z_COIL_MAX_DIPOLE"])
        cx, cy, cz = self.coil_max
        self.limits = (2.0 * cx, 2.0 * cy, cz)
        self.bdot_provider = bool(bdot_provider)
        self.provider_gain = float(provider_gain)
        self.auto_start_us = int(round(float(auto_start_s) * 1e6))
        if force_mode not in (None, "DETUMBLE", "SPIN_STABLE", "POINTING"):
            raise ValueError(f"force_mode {force_mode!r}: use DETUMBLE, SPIN_STABLE, POINTING or None (AUTO)")
        self.force_mode = force_mode
        self.force_at_us = int(round(float(force_at_s) * 1e6))
        self.allocator = WheelAllocator(self.axes, p["WHEEL_MAX_TORQUE"], p["WHEEL_MAX_MOMENTUM"])
        self._unit_allocator = WheelAllocator(self.axes, 1.0, 1.0)  # for Σ h_i g_i only
        if p["ESTIMATOR"] == "MEKF":
            self.filter: Mekf | AttitudeFilter = Mekf(
                math.radians(p["GYRO_NOISE"]), math.radians(p["GYRO_BIAS_WALK"]), p["TRACKER_NOISE_CROSS"] * _ARCSEC,
                p["TRACKER_NOISE_ABOUT"] * _ARCSEC, attitude_defaults.BORESIGHT_B, math.radians(p["GYRO_BIAS_SIGMA0"]))
        else:
            self.filter = AttitudeFilter(p["FILTER_KP"], p["FILTER_KI"])
        xy, xz, yz = p["INERTIA_XY"], p["INERTIA_XZ"], p["INERTIA_YZ"]
        self.observer = RateObserver(((p["INERTIA_XX"], xy, xz), (xy, p["INERTIA_YY"], yz),
                                      (xz, yz, p["INERTIA_ZZ"])), p["RATE_OBSERVER_GAIN"])
        self.field_rate = FieldDirectionRate(p["MAG_FIELD_RATE_BANDWIDTH"])
        self.residual = ResidualDipoleEstimator(self.observer.inertia, p["MAG_RESIDUAL_WINDOW"])
        self.integrator = ErrorIntegrator(p["INTEGRAL_WINDOW"] * _DEG, attitude_defaults.INTEGRAL_MAX_TORQUE)
        self.kane = SeedKaneDamper(p["C_DAMP"], p["I_D"])
        self.damper = VirtualDamper(p["C_DAMP"], p["I_D"])
        self.regulator = SpinRateRegulator(p["SPIN_K_TRANSVERSE"], p["SPIN_K_RATE"], p["SPIN_RATE_TARGET"] * _DEG)
        self.initial_target: Quat | None = None if target_q_bn is None else _as_target(target_q_bn)
        changes = []
        for t_s, q_tn in target_changes:
            q = tuple(float(c) for c in q_tn)
            if len(q) != 4 or not is_unit_quaternion(q):
                raise ValueError(f"target change at {t_s} s: {q!r} is not a unit quaternion (within 1e-3), as "
                                 "SET_TARGET_QUATERNION requires")
            changes.append((int(round(float(t_s) * 1e6)), _as_target(q)))
        if any(b[0] < a[0] for a, b in zip(changes, changes[1:], strict=False)):
            raise ValueError("target changes must be in time order")
        self.target_changes: tuple[tuple[int, Quat], ...] = tuple(changes)  # (t µs, q_TN)
        self.reset()

    def reset(self) -> None:
        """Back to the state before the first tick: IDLE, nothing known, the target given at construction."""
        self.mode = "IDLE"
        self.target = self.initial_target
        self._next_change = 0  # index of the first target change not yet applied
        self.transitions: list[tuple[float, str, str]] = []  # (t s, new mode, reason)
        self.filter.reset()
        self.observer.reset()
        self.field_rate.reset()
        self.residual.reset()
        self.residual_ff: Vec3 = _ZERO  # A·m², B: the residual-dipole feed-forward of the last cycle
        self.integrator.reset()
        self.kane.reset()
        self.damper.reset()
        self.ticks = 0
        self.cycles = 0
        # Each cycle sets the estimates before anything reads them (the plant's sensors always answer).
        self.omega: Vec3 = _ZERO  # ω̂ rad/s, B (bias-corrected)
        self.pd_rate: Vec3 | None = None  # the rate the wheel PD's D term uses, rad/s
        self.b_tesla: Vec3 = _ZERO
        self.b_gauss: Vec3 = _ZERO
        self.b_stamp_us = 0
        self.bdot_hat_B: Vec3 | None = None
        self.momenta: tuple[float, ...] = ()
        self.dipole = _ZERO  # A·m² the present levels give
        self.wheel_torques: tuple = ()
        self.coils_on = False
        self.pointing_error_deg = math.nan  # estimated, in POINTING
        self.attitude_known_s = 0.0
        self._gyro_acc, self._gyro_n = _ZERO, 0
        self._force_pending = True
        self._last_us: int | None = None
        self._last_fix_us: int | None = None
        self._timer_low = 0.0  # DETUMBLE-exit qualification, s
        self._timer_stable = 0.0  # SPIN_STABLE qualification, s
        self._bdot_prev: tuple[Vec3, int] | None = None  # (b gauss, stamp µs) for the internal B-dot
        #: the provider's last reading (it outlives mode changes, as BDotDetumble's does)
        self._provider_prev: tuple[Vec3, int] | None = None

    # --- the tick -------------------------------------------------------------------------------

    def tick(self, io: PlantIo) -> None:
        """One rate-group tick: a control cycle on tick 0 of each cycle, else add the gyro sample to the
        cycle's mean; the coils go off on the cycle's last tick."""
        n = self.cycle_ticks
        phase = self.ticks % n
        self.ticks += 1
        if phase == 0:
            self._control_cycle(io)
        else:
            g, acc = io.gyro(), self._gyro_acc
            self._gyro_acc = (acc[0] + g[0], acc[1] + g[1], acc[2] + g[2])
            self._gyro_n += 1
        if n > 1 and phase == n - 1 and self.coils_on:
            io.stop_coils()
            self.coils_on = False

    @property
    def attitude_valid(self) -> bool:
        f = self.filter
        return f.q is not None and f.since_measurement_s <= self.params["ATTITUDE_TIMEOUT"]

    def _control_cycle(self, io: PlantIo) -> None:
        now = io.now_us()
        self._handle_commands(now)
        last, self._last_us = self._last_us, now
        dt = self.cycle_ticks * self.tick_s if last is None or now <= last else (now - last) / 1e6
        self.cycles += 1
        self._estimate(io, dt, now)
        if self.force_mode is None and now >= self.auto_start_us:  # FORCE_MODE holds the mode: no trigger moves it
            self._choose_mode(dt, now)
        self._command(io, dt)

    def _handle_commands(self, now: int) -> None:
        """The commands stamped before this cycle, as their handlers run in the deployment: after the cycle
        before (a command sent at a cycle's own time lands after that cycle), on the state it left."""
        changes, i = self.target_changes, self._next_change
        while i < len(changes) and changes[i][0] < now:
            self.target = changes[i][1]
            self.integrator.reset()
            i += 1
        self._next_change = i
        if self.force_mode is not None and self._force_pending and self.force_at_us < now:
            self._force_pending = False  # one command: refused POINTING is not retried, as in flight
            if self.force_mode != "POINTING" or self._can_point():
                self._enter(self.force_mode, "COMMAND", self.force_at_us)

    # --- estimation -----------------------------------------------------------------------------

    def _estimate(self, io: PlantIo, dt: float, now: int) -> None:
        g = io.gyro()
        k = self._gyro_n + 1
        acc = self._gyro_acc
        mean = ((acc[0] + g[0]) / k, (acc[1] + g[1]) / k, (acc[2] + g[2]) / k)
        self._gyro_acc, self._gyro_n = _ZERO, 0
        fix = io.attitude()
        q_meas, age = None, 0.0
        if fix is not None and is_unit_quaternion(fix[0], tol=1e-2):
            stamp = fix[1]
            if stamp != self._last_fix_us and stamp <= now:  # a new solution (the tracker holds its last)
                self._last_fix_us = stamp
                q_meas, age = quat_normalize(fix[0]), (now - stamp) / 1e6
        f = self.filter
        if isinstance(f, Mekf):
            f.update(mean, dt, q_meas, age, samples=k)
        else:
            f.update(mean, dt, q_meas, age)
        self.omega = f.omega
        b, self.b_stamp_us = io.field()
        self.b_gauss = b
        self.b_tesla = (b[0] * 1e-4, b[1] * 1e-4, b[2] * 1e-4)
        self._follow_field_line(dt)
        self.momenta = io.wheel_momenta() if self.wheels else ()
        torque = applied_torque(self.wheel_torques, self.axes, self.dipole, self.b_tesla, self.duty)  # last cycle's
        self._observe_rate(dt, torque)
        self._track_residual_dipole(dt, torque)

    def _follow_field_line(self, dt: float) -> None:
        known = self.attitude_valid
        self.attitude_known_s = self.attitude_known_s + dt if known else 0.0
        if not known:
            self.field_rate.reset()
            self.bdot_hat_B = None
            return
        q = self.filter.q
        assert q is not None  # attitude_valid
        self.bdot_hat_B = self.field_rate.update(q, self.b_tesla, dt)

    def _observe_rate(self, dt: float, torque: Vec3) -> None:
        h = self._unit_allocator.body_momentum(self.momenta) if self.wheels else _ZERO
        w = self.observer.update(self.omega, torque, h, dt)
        self.pd_rate = w if self.params["RATE_SOURCE"] == "OBSERVER" else self.omega

    def _track_residual_dipole(self, dt: float, torque: Vec3) -> None:
        """Feed the residual-dipole estimator while the coils point past MAG_SETTLE_TIME (the
        component's rule); elsewhere its open window is dropped and its sums kept."""
        p = self.params
        if (p["MAG_RESIDUAL_MODE"] != "ESTIMATE" or self.mode != "POINTING" or self._points_on_wheels()
                or self.attitude_known_s < p["MAG_SETTLE_TIME"]):
            self.residual.gap()
            return
        self.residual.update(self.omega, torque, _ZERO, self.b_tesla, dt)

    def _residual_feed_forward(self) -> Vec3:
        """The residual dipole to cancel, A·m² (B), by MAG_RESIDUAL_MODE; an estimate past a coil
        limit gives way to the MAG_RESIDUAL_DIPOLE_* parameters."""
        p = self.params
        mode = p["MAG_RESIDUAL_MODE"]
        if mode == "OFF":
            return _ZERO
        est = self.residual.estimate
        if (mode == "ESTIMATE" and est is not None and all(math.isfinite(x) for x in est)
                and all(abs(est[i]) <= self.limits[i] for i in range(3))):
            return est
        return (p["MAG_RESIDUAL_DIPOLE_X"], p["MAG_RESIDUAL_DIPOLE_Y"], p["MAG_RESIDUAL_DIPOLE_Z"])

    def _points_on_wheels(self) -> bool:
        return self.wheels and self.params["POINTING_ACTUATOR"] != "MAGNETORQUERS"

    # --- modes ----------------------------------------------------------------------------------

    def _enter(self, mode: str, reason: str, now_us: int) -> None:
        if mode == self.mode:
            return
        self.mode = mode
        self._timer_low = self._timer_stable = 0.0
        self._bdot_prev = None
        self.kane.reset()
        self.damper.reset()
        self.integrator.reset()
        q = self.filter.q
        if mode == "POINTING" and self.target is None and q is not None:
            self.target = (float(q[0]), float(q[1]), float(q[2]), float(q[3]))
        self.transitions.append((now_us / 1e6, mode, reason))

    def spin_errors(self) -> tuple[float, float]:
        """``(angle of ω̂ from +Z deg, |ω̂_z − target| / target)``."""
        return spin_errors(self.omega, self.params["SPIN_RATE_TARGET"] * _DEG)

    def _can_point(self) -> bool:
        if self.params["POINTING_ACTUATOR"] == "WHEELS" and not self.wheels:
            return False
        return self.attitude_valid

    def _choose_mode(self, dt: float, now: int) -> None:
        p, mode = self.params, self.mode
        if mode == "IDLE":
            self._enter("DETUMBLE", "AUTO_START", now)
            return
        w = self.omega
        rate = math.degrees(math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]))
        if rate > p["DETUMBLE_ENTER_RATE"] and mode != "DETUMBLE":
            self._enter("DETUMBLE", "RATE_HIGH", now)
        elif mode == "DETUMBLE":
            self._timer_low = 0.0 if rate >= p["DETUMBLE_EXIT_RATE"] else self._timer_low + dt
            if self._timer_low >= p["MODE_DWELL"]:
                self._enter("SPIN_STABLE", "RATE_LOW", now)
        elif mode == "SPIN_STABLE":
            off_axis, off_rate = self.spin_errors()
            if off_axis <= p["SPIN_AXIS_ENTER"] and off_rate <= p["SPIN_RATE_ENTER"]:
                self._timer_stable += dt
            elif off_axis > p["SPIN_AXIS_RESET"] or off_rate > p["SPIN_RATE_RESET"]:
                self._timer_stable = 0.0
            if self._timer_stable >= p["SPIN_STABLE_DWELL"] and self._can_point():
                self._enter("POINTING", "SPIN_STABLE_REACHED", now)
        elif not self.attitude_valid:  # POINTING without attitude knowledge
            self._enter("SPIN_STABLE", "ATTITUDE_LOST", now)

    # --- actuation ------------------------------------------------------------------------------

    def _levels(self, m):
        """``(levels X+, X−, Y+, Y−, Z−, the dipole they give A·m²)``: half of m_x and m_y on each coil of
        the pair, m_z on Z−; X−, Y− and Z− face the other way."""
        return face_coil_levels(m, *self.coil_max)

    def _bdot(self):
        """DETUMBLE's dipole, A·m² (None: no dipole this cycle, the coils stay off)."""
        b, stamp = self.b_gauss, self.b_stamp_us
        if not self.bdot_provider:
            prev, self._bdot_prev = self._bdot_prev, (b, stamp)
            return None if prev is None else bdot_dipole(prev[0], b, (stamp - prev[1]) / 1e6, self.params["K_BDOT"])
        prev = self._provider_prev
        if prev is None:  # the first reading only primes the difference
            self._provider_prev = (b, stamp)
            return None
        size = math.sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2])
        if size < attitude_defaults.BDOT_MIN_FIELD_GAUSS or stamp == prev[1]:
            return None
        if stamp < prev[1]:  # the clock went back: start again from this reading
            self._provider_prev = (b, stamp)
            return None
        step = (stamp - prev[1]) / 1e6
        self._provider_prev = (b, stamp)
        c = -self.provider_gain / size
        m = (c * (b[0] - prev[0][0]) / step, c * (b[1] - prev[0][1]) / step, c * (b[2] - prev[0][2]) / step)
        return m if all(math.isfinite(x) for x in m) else None

    def _spin_torque(self, dt: float):
        law, w = self.params["SPIN_LAW"], self.omega
        if law == "RATE_REGULATOR":
            return self.regulator.torque_request(w)
        if law == "VIRTUAL_DAMPER":
            self.damper.update(w, dt)
            return self.damper.torque_request(w)
        mb, d = _cross(self.dipole, self.b_tesla), self.duty  # the last cycle's magnetic torque
        self.kane.update((mb[0] * d, mb[1] * d, mb[2] * d), dt)
        return self.kane.torque_request()

    def _point_on_wheels(self, target: Quat, q: Quat, dt: float):
        """``(dipole for dumping, wheel torques, q_err)``."""
        p = self.params
        rate = self.pd_rate if self.pd_rate is not None else self.omega
        tau, qe = pd_torque(target, q, rate, p["K_P"], p["K_D"], p["SLEW_RATE_LIMIT"] * _DEG)
        self.integrator.window_rad = p["INTEGRAL_WINDOW"] * _DEG
        ti = self.integrator.update(qe, dt, p["K_I"])
        tau = (tau[0] + ti[0], tau[1] + ti[1], tau[2] + ti[2])
        h_b = self._unit_allocator.body_momentum(self.momenta)
        dipole, _ = project_dipole_weighted(dump_torque(h_b, p["K_DUMP"]), self.b_tesla, self.limits)
        dipole = scale_to_limits(dipole, self.limits)
        mb = _cross(self._levels(dipole)[1], self.b_tesla)
        d = self.duty  # the wheels give what the dumping torque does not
        u, _limited = self.allocator.allocate((tau[0] - mb[0] * d, tau[1] - mb[1] * d, tau[2] - mb[2] * d),
                                              self.momenta)
        return dipole, u, qe

    def _point_on_coils(self, target: Quat, q: Quat):
        """``(dipole or None, q_err)`` for pointing on the magnetorquers alone."""
        p, w, b = self.params, self.omega, self.b_tesla
        if p["MAG_POINTING_LAW"] == "SEED_PD":
            tau, qe = pd_torque(target, q, w, p["K_P_MAG"], p["K_D_MAG"])
        else:
            bd = self.bdot_hat_B if self.bdot_hat_B is not None else _ZERO
            tau, qe = field_steering_torque(target, q, w, b, bd, p["K_P_MAG"], p["K_D_MAG"], p["MAG_STEER_RHO"],
                                            p["MAG_STEER_ZETA"], p["MAG_FIELD_RATE_MIN"])
        if self.attitude_known_s < p["MAG_SETTLE_TIME"]:
            return None, qe  # the gyro-bias estimate is still settling: the coils wait
        dipole = project_dipole_weighted(tau, b, self.limits)[0]
        ff = self.residual_ff = self._residual_feed_forward()  # it acts all the time; the coils only for the duty
        d = self.duty
        return (dipole[0] - ff[0] / d, dipole[1] - ff[1] / d, dipole[2] - ff[2] / d), qe

    def _command(self, io: PlantIo, dt: float) -> None:
        mode = self.mode
        dipole = None
        torques = None
        self.residual_ff = _ZERO
        self.pointing_error_deg = math.nan
        if mode == "DETUMBLE":
            dipole = self._bdot()
            if dipole is not None:
                dipole = clip_to_limits(dipole, self.limits)  # each axis saturates alone, as the coils do
        elif mode == "SPIN_STABLE":
            dipole = project_dipole_weighted(self._spin_torque(dt), self.b_tesla, self.limits)[0]
        elif mode == "POINTING" and self.attitude_valid:
            q = self.filter.q
            assert q is not None  # attitude_valid
            if self.target is None:
                self.target = (float(q[0]), float(q[1]), float(q[2]), float(q[3]))
                self.integrator.reset()
            target = self.target
            if self._points_on_wheels():
                dipole, torques, qe = self._point_on_wheels(target, q, dt)
            else:
                dipole, qe = self._point_on_coils(target, q)
            self.pointing_error_deg = math.degrees(quat_angle(qe))
        if dipole is None:
            if self.coils_on:
                io.stop_coils()
                self.coils_on = False
            self.dipole = _ZERO
        else:
            levels, self.dipole = self._levels(scale_to_limits(dipole, self.limits))
            io.drive_coils(levels, self.dipole)
            self.coils_on = True
        if torques is None:
            torques = (0.0,) * len(self.axes)
        self.wheel_torques = tuple(float(u) for u in torques) if self.wheels else (0.0,) * len(self.axes)
        if self.wheels:
            io.set_wheel_torques(self.wheel_torques)

    def true_pointing_error_deg(self, q_BN) -> float:
        """The angle between the attitude ``q_BN`` (the truth) and the target, deg (nan without one)."""
        return math.nan if self.target is None else math.degrees(quat_angle(quat_error(self.target, q_BN)))


def pointing_statistics(values: Sequence[float], skip_fraction: float = 0.1, *,
                        sample_interval_s: float | None = None) -> dict | None:
    """``{"median", "p95", "max", "samples"}`` (deg) of ``values`` after their first ``skip_fraction``, as the
    deployment's attitude report gives them (:func:`detumble.analysis.pooled_stats.error_statistics`); with
    ``sample_interval_s`` (s a sample stands for) also its pooling fields at the pointing thresholds."""
    return error_statistics(list(values), skip_fraction, sample_interval_s=sample_interval_s,
                            thresholds_deg=POINTING_THRESHOLDS_DEG)
