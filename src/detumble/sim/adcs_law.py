"""The three-mode attitude controller flown plant-only (``fprime-lite sim --law adcs``; no framework).

:class:`AdcsLaw` flies :class:`detumble.control.three_mode.ThreeModeLaw`, the law adcs_ref's AttitudeController
flies, on a :class:`~detumble.sim.plant.Plant` through :class:`PlantIo` (read as the simulated drivers read it:
held samples with their own time stamps, integer µs; the wheels start enabled). It stands in for what the
deployment has around the controller: the BDotDetumble dipole provider adcs_ref connects (``m = −Gain·Ḃ/|B|``,
B gauss) and the commands of the start-up sequence and later ones — SET_AUTO at ``auto_start_s``, or one
FORCE_MODE at ``force_at_s`` (then no AUTO), and SET_TARGET_QUATERNION at ``target_changes``' times. A command
stamped t acts from the first cycle after t, on the state the cycle before left, as in the deployment, where its
handler runs after the rate group's cycle of that instant; its transition is stamped t. Events and telemetry go
nowhere; the modes and reasons are named as the flight enums name them (``MODES``).
"""

from __future__ import annotations

import functools
import math
from typing import Mapping, Sequence, cast

from detumble.analysis.pooled_stats import POINTING_THRESHOLDS_DEG, error_statistics
from detumble.control import attitude_defaults
from detumble.control.albedo import AlbedoCorrector
from detumble.control.magnetic import normalised_bdot_dipole
from detumble.control.quaternion import quat_angle, quat_error
from detumble.control.sun_vector import SUN_LIT_FRACTION, SUN_MAGNITUDE_TOLERANCE, estimate_sun_vector
from detumble.control.targets import Ephemeris, target_command, target_entry_error, true_reference_q
from detumble.sim.sun_sensors import FULL_SUN_LUX
from detumble.control.three_mode import MODES, REASONS, XYZ, ControllerIo, Quiet, ThreeModeLaw, checked_parameters

__all__ = ["AdcsLaw", "PlantIo", "MODES", "COIL_FACES", "pointing_statistics"]

#: Coil faces in the order the controller drives them: X+, X−, Y+, Y−, Z− (plant face numbers).
COIL_FACES = (0, 1, 2, 3, 5)


class PlantIo:
    """The law's ``ControllerIo`` on a plant: three or four wheels (else none), face coils or torque rods; with
    ``sun_sensors`` (a ``sim.sun_sensors.SunSensorModel``) the six face light sensors, read and turned into a Sun
    vector every ``sun_period_s`` as the ADCS component does (``detumble.proves.adcs``; a face lit above
    ``lit_fraction`` of the full Sun, the component's SUN_LIT_FRACTION); with ``albedo_model`` > 0
    the Earth's albedo (that Bond albedo) taken out of it (``control.albedo``: TRIAD on the Sun vector and the
    magnetometer against the ephemeris and the plant's field model as the on-board one); ``system_safe`` stands
    for the mode manager (None: not connected; True: safe mode)."""

    def __init__(self, plant, sun_sensors=None, sun_period_s: float = 1.0, albedo_model: float = 0.0,
                 lit_fraction: float = SUN_LIT_FRACTION) -> None:
        self.plant = plant
        self.lit_fraction = float(lit_fraction)
        self.albedo = (AlbedoCorrector(albedo_model, sun_sensors.earth_radius_m)
                       if albedo_model > 0.0 and sun_sensors is not None and plant.field is not None else None)
        self.sun_sensors = sun_sensors
        self._sun_period_us = max(1, int(round(sun_period_s * 1e6)))
        self._sun_slot: int | None = None
        self._sun: tuple | None = None
        self.system_safe: bool | None = None
        coils = getattr(plant.actuators, "coils", None)
        self.face_coils = coils is not None and all(f in coils for f in COIL_FACES)
        self.has_tracker = plant.star_tracker is not None
        self.wheels = plant.wheel_count if 3 <= plant.wheel_count <= 4 else 0

    def now_us(self) -> int:
        return self.plant.t_ns // 1000

    def gyro(self) -> tuple[float, float, float]:
        w = self.plant.gyro_reading()
        return (w[0], w[1], w[2])

    def field(self) -> tuple[tuple[float, float, float], int]:
        p = self.plant
        if p.magnetometer.spec.ideal:
            g = p.magnetometer_reading()
            return (g[0], g[1], g[2]), p.t_ns // 1000
        s = p.magnetometer.sample_gauss
        return (s[0], s[1], s[2]), p.magnetometer.sample_time_ns // 1000

    def attitude(self):
        if not self.has_tracker:
            return None
        q0, q1, q2, q3, valid, t = self.plant.star_tracker_reading()
        return ((q0, q1, q2, q3), int(round(t * 1e9)) // 1000) if valid else None

    def wheel_count(self) -> int:
        return self.wheels

    def wheel_momenta(self) -> tuple[float, ...]:
        return tuple(self.plant.wheel_reading(i)[1] for i in range(self.wheels))

    def drive_coils(self, levels: Sequence[int], dipole_B) -> None:
        if self.face_coils:
            for face, level in zip(COIL_FACES, levels, strict=True):
                self.plant.set_coil_level(face, level)
        else:
            self.plant.apply_dipole_B(dipole_B)

    def stop_coils(self) -> None:
        self.drive_coils((0, 0, 0, 0, 0), (0.0, 0.0, 0.0))

    def set_wheel_torques(self, torques: Sequence[float]) -> tuple[float, ...]:
        for i in range(min(self.wheels, len(torques))):
            self.plant.set_wheel_torque(i, torques[i])
        return tuple(float(u) for u in torques)

    def ephemeris(self) -> Ephemeris:
        return self.plant.ephemeris()

    def has_sun_sensor(self) -> bool:
        return self.sun_sensors is not None

    def sun_vector(self):
        """The Sun vector of the light sensors' latest reading (taken on the ``sun_period_s`` grid)."""
        model = self.sun_sensors
        if model is None:
            return None
        p = self.plant
        t_us = p.t_ns // 1000
        slot = t_us // self._sun_period_us
        if slot != self._sun_slot:
            self._sun_slot = slot
            t = p.t_ns * 1e-9
            readings = model.read(t, p.q_BN, p.r_N)
            if self.albedo is not None:
                r_N, sun_N = p.r_N, model.sun(t)[0]
                est = self.albedo.estimate(readings, FULL_SUN_LUX, t, r_N=r_N, sun_N=sun_N, field_B=self.field()[0],
                                           field_N=p.field.b_N(t, r_N), omega_B=self.gyro())
            else:
                est = estimate_sun_vector(readings, FULL_SUN_LUX, lit_fraction=self.lit_fraction,
                                          magnitude_tolerance=SUN_MAGNITUDE_TOLERANCE)
            self._sun = (est.direction, est.valid, t_us)
        return self._sun

    def system_safe_mode(self) -> bool | None:
        return self.system_safe


class AdcsLaw(Quiet):
    """The three-mode controller in AUTO (or a forced mode), one :meth:`tick` per rate-group tick.

    Args: ``wheel_axes`` (unit, B; three to four), ``wheels`` (False: fly without them), ``params`` (flight names
    over ``attitude_defaults.DEFAULTS``), ``target_q_bn`` (the SET_TARGET_QUATERNION target; None: hold the
    attitude POINTING starts from), ``bdot_provider`` (False: the law's own ``−K_BDOT Ḃ``) with
    ``provider_gain`` (A·m²·s), ``auto_start_s`` (s; IDLE before), ``force_mode`` (DETUMBLE, SPIN_STABLE,
    POINTING or None) at ``force_at_s`` (s), ``target_changes`` (``(t_s, q_TN)`` in time order).
    """

    name = "adcs"
    ticked = True  # the runner calls tick() every rate-group tick
    full_state = False
    wheel_law = False
    tick_s = attitude_defaults.RATE_GROUP_PERIOD_S

    def __init__(self, wheel_axes: Sequence[Sequence[float]] = XYZ, wheels: bool = True,
                 params: Mapping[str, object] | None = None, target_q_bn=None, *, bdot_provider: bool = True,
                 provider_gain: float = attitude_defaults.BDOT_PROVIDER_GAIN, auto_start_s: float = 0.0,
                 force_mode: str | None = None, force_at_s: float = 0.0,
                 target_changes: Sequence[tuple[float, Sequence[float]]] = ()) -> None:
        self.params = checked_parameters(params)
        self.axes, self.wheels = wheel_axes, bool(wheels)
        self.bdot_provider, self.provider_gain = bool(bdot_provider), float(provider_gain)
        self.auto_start_us = int(round(float(auto_start_s) * 1e6))
        if force_mode not in (None, "DETUMBLE", "SPIN_STABLE", "POINTING", "SUN_SAFE"):
            raise ValueError(f"force_mode {force_mode!r}: use DETUMBLE, SPIN_STABLE, POINTING, SUN_SAFE or None (AUTO)")
        self.force_mode, self.force_at_us = force_mode, int(round(float(force_at_s) * 1e6))
        self.initial_target = None if target_q_bn is None else tuple(float(c) for c in target_q_bn)
        self.target_changes = tuple((int(round(float(t) * 1e6)), _target_entry(q)) for t, q in target_changes)
        for t_us, q in self.target_changes:  # (t µs, q_TN or a moving target's command)
            why = target_entry_error(q)
            if why is not None:
                raise ValueError(f"target change at {t_us / 1e6} s: {why}")
        if list(self.target_changes) != sorted(self.target_changes, key=lambda c: c[0]):
            raise ValueError("target changes must be in time order")
        self.reset()

    def reset(self) -> None:
        """Back to the state before the first tick: IDLE, nothing known, the target given at construction."""
        self.law = ThreeModeLaw(cast(ControllerIo, None), self, self, self.axes, self.params)  # io: the first tick's
        self.transitions: list[tuple[float, str, str]] = []  # (t s, mode, reason)
        self._next_change, self._force_pending, self._auto_pending = 0, True, True
        self._command_us: int | None = None
        self._provider_prev: tuple | None = None  # (b gauss, µs): BDotDetumble's memory outlives mode changes
        if self.initial_target is not None and self.law.set_target_quaternion(self.initial_target) != "OK":
            raise ValueError(f"target_q_bn {self.initial_target!r} is not a unit quaternion (within 1e-3)")

    mode = property(lambda self: MODES[self.law.mode], doc="The mode's name.")
    target = property(lambda self: self.law.target, doc="The POINTING target q_TN (None: none yet).")
    cycles = property(lambda self: self.law.cycles)
    ticks = property(lambda self: self.law.ticks)
    integrator = property(lambda self: self.law.integrator)
    cycle_ticks = property(lambda self: self.law.cycle_ticks)

    def tick(self, io: PlantIo) -> None:
        """One rate-group tick; before a cycle, the commands whose time has passed."""
        law = self.law
        if io is not law.io:
            law.io = io
            if not self.wheels:
                io.wheels = 0
        if law.ticks % law.cycle_ticks == 0:
            self._commands(io.now_us())
        law.tick()

    def _commands(self, now: int) -> None:
        law, changes = self.law, self.target_changes
        while self._next_change < len(changes) and changes[self._next_change][0] < now:
            target_command(law, changes[self._next_change][1])
            self._next_change += 1
        if self.force_mode is not None and self._force_pending and self.force_at_us < now:
            self._force_pending, self._command_us = False, self.force_at_us  # one command: not retried
            law.force_mode(MODES.index(self.force_mode))
            self._command_us = None
        elif self.force_mode is None and self._auto_pending and now >= self.auto_start_us:
            self._auto_pending = False
            law.set_auto()

    def mode_changed(self, old: int, new: int, reason: int) -> None:
        t_us = self._command_us if self._command_us is not None else self.law.last_cycle_us
        assert t_us is not None  # a mode changes in a cycle or by a command
        self.transitions.append((t_us / 1e6, MODES[new], REASONS[reason]))

    def has_dipole_provider(self) -> bool:
        return self.bdot_provider

    def provider_dipole(self):
        """BDotDetumble's ``−Gain·Ḃ/|B|`` (A·m², B) on the cycle's magnetometer sample; None as it fails."""
        b, stamp, prev = self.law.b_gauss, self.law.b_stamp_us, self._provider_prev
        if prev is not None:
            size = math.sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2])
            if size < attitude_defaults.BDOT_MIN_FIELD_GAUSS or stamp == prev[1]:
                return None
        self._provider_prev = (b, stamp)
        if prev is None or stamp < prev[1]:  # the first reading only primes; a clock gone back starts again
            return None
        m = normalised_bdot_dipole(prev[0], b, (stamp - prev[1]) / 1e6, self.provider_gain, size)
        return m if all(math.isfinite(x) for x in m) else None

    def true_pointing_error_deg(self, q_BN, ephemeris=None) -> float:
        """The angle between the attitude ``q_BN`` (the truth) and the target, deg (nan without one): a moving
        target's reference by ``ephemeris()`` (the plant's truth, called only for one), else the law's."""
        law = self.law
        t = true_reference_q(law.target_spec, ephemeris, law.target) if ephemeris is not None else law.target
        return math.nan if t is None else math.degrees(quat_angle(quat_error(t, q_BN)))


def _target_entry(q) -> tuple:
    """A target change as given: four numbers (floats), or a moving target's command (kept as given)."""
    if q and isinstance(q[0], str):
        return tuple(q)
    return tuple(float(c) for c in q)


#: ``{"median", "p95", "max", "samples"}`` (deg) of errors after their first tenth (the window before issue 27), with
#: the pooling fields when given ``sample_interval_s`` (the summaries now use analysis.pointing_windows).
pointing_statistics = functools.partial(error_statistics, thresholds_deg=POINTING_THRESHOLDS_DEG)
