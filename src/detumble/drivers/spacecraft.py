"""The simulated spacecraft behind the simulated drivers: a plant stepped in lock-step with the clock.

:class:`SimulatedSpacecraft` owns one :class:`~detumble.sim.plant.Plant` built from a scenario and
keeps the physics at the deployment's time. There is **one time base**: the deployment's
:class:`~fprime_lite.model.time.SimulatedClock` (integer microseconds; ``clock.now()`` is
``epoch_us + current_us`` in ``TB_WORKSTATION_TIME``). The plant's own clock (integer nanoseconds
from the scenario epoch, t = 0) is tied to it by one offset fixed when the spacecraft is made::

    plant t_ns = (clock.current_us - origin_us) * 1000          origin_us = clock.current_us at creation

so plant t = 0 is the moment the spacecraft was created (normally scheduler time 0). Every time
stamp the drivers hand out (the magnetometer's sample time) is converted back to an F´
:class:`~fprime_lite.model.time.Time` in the clock's base and context. Use :func:`scenario_epoch_us` as
the clock's ``epoch_us`` to make F´ times read as Unix time at the scenario's UTC epoch.

Stepping
--------
:meth:`attach` registers :meth:`on_time` as a scheduler time listener: whenever the scheduler
moves time forward, *before* any event at the new time runs, the plant is integrated up to it in
fixed dynamics steps on the grid ``k * dynamics_step_s`` from t = 0; when the new time (or a truth
trace instant) falls between grid points the last step is partial and the next one returns to the
grid. Consequences, all tested:

* after ``scheduler.run(until_us=T)`` the physics time equals the scheduler time exactly;
* a handler running at time t sees the plant at t; a coil level set at t is held over the steps
  *after* t only (it cannot act on the past);
* physics never integrates backwards (asking for an earlier time raises ``ValueError``).

The drivers also call :meth:`sync` before each access, so a spacecraft whose clock is moved by hand
(unit tests with the port harness) behaves identically; with the listener attached it is a no-op.

Truth trace
-----------
:meth:`set_trace` calls ``callback(TruthSample)`` at every multiple of ``interval_us`` of plant
time (exact instants: the stepper stops there), for plots and acceptance checks.
:class:`TruthRecorder` is a ready-made callback that keeps the rows and writes a CSV.

Frames and units: ``omega_BN_B`` rad/s (body rate relative to inertial, in B); ``b_B`` tesla (true
geomagnetic field in B, *without* the coils' own field); ``m_coils_B`` A·m² (total coil dipole in
B); quaternion ``q_BN`` scalar first (see ``docs/scenarios.md``). Sensor outputs follow the flight
code: magnetometer in gauss, gyro in rad/s.
"""

from __future__ import annotations

import datetime as _dt
import math
from collections import deque
from typing import TYPE_CHECKING, Callable, NamedTuple, Sequence

from fprime_lite.deploy.resources import ResetLine, RoleOptionError, SimulationEnded, topology_resource
from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.model.time import SimulatedClock, Time

from detumble.sim import plant_kernel
from detumble.sim.accelerometer import Accelerometer
from detumble.sim.coils import CoilSet, MAX_LEVEL
from detumble.sim.epoch import julian_date
from detumble.sim.orbit import R_EARTH_EQ
from detumble.sim.power import FACE_SWITCHES, ElectricalSystem, coil_supply_power_w
from detumble.sim.thermal import ThermalModel
from detumble.sim.sun_sensors import SunSensorModel
from detumble.control.units import GAUSS_PER_TESLA

if TYPE_CHECKING:  # the plant and the scenario schema are imported when a spacecraft is made: a
    # module that only names SimulatedSpacecraft (each PROVES driver) stays light to import (issue 30)
    from detumble.sim.scenario import Scenario

__all__ = ["SimulatedSpacecraft", "TruthSample", "TruthRecorder", "scenario_epoch_us", "require_spacecraft",
           "make_spacecraft"]

_UNIX_EPOCH = _dt.datetime(1970, 1, 1, tzinfo=_dt.timezone.utc)

#: Errors a sensor model raises on a state that is no longer finite (``math.floor(nan)`` …).
_NUMERIC_ERRORS = (ValueError, OverflowError, ZeroDivisionError)
#: A body rate beyond this (rad/s, about 5.7e7 deg/s) counts as a diverged integration, as a NaN does.
_DIVERGED_RATE_RAD_S = 1e6
#: More rotation than this per dynamics step (rad) is past what the fixed-step integration resolves.
_MAX_TURN_PER_STEP_RAD = 0.5

#: The electrical system is integrated over this much plant time at once (100 ms, five 50 Hz
#: dynamics steps); the coils' energy in between is summed exactly, step by step.
POWER_STEP_NS = 100_000_000


def load_scenario(name: str, **kwargs) -> Scenario:
    """:func:`detumble.sim.scenario.load_scenario`, its module imported on the first call (a module
    name, so that a test can replace it here)."""
    from detumble.sim.scenario import load_scenario as load

    return load(name, **kwargs)


def scenario_epoch_us(scenario: Scenario) -> int:
    """The scenario's UTC epoch as microseconds since 1970-01-01 (a clock ``epoch_us``)."""
    delta = scenario.epoch - _UNIX_EPOCH
    return (delta.days * 86400 + delta.seconds) * 1_000_000 + delta.microseconds


def require_spacecraft(owner: str, spacecraft) -> "SimulatedSpacecraft":
    """``spacecraft`` if it is a :class:`SimulatedSpacecraft`, else a TypeError naming ``owner``."""
    if not isinstance(spacecraft, SimulatedSpacecraft):
        raise TypeError(f"{owner}: spacecraft must be a SimulatedSpacecraft, got {spacecraft!r}")
    return spacecraft


class _TruthFields(NamedTuple):
    time_us: int                       #: deployment time, µs since the clock's epoch (``Time.total_us``)
    t_s: float                         #: plant time since the scenario epoch, s
    q_BN: tuple                        #: attitude quaternion, scalar first
    omega_BN_B: tuple                  #: body rate, rad/s, in B
    rate_deg_s: float                  #: |omega_BN_B|, deg/s
    b_B: tuple                         #: true geomagnetic field in B, T (no coil field)
    m_coils_B: tuple                   #: total coil dipole in B, A·m² (achieved)
    coil_levels: dict                  #: face -> drive level (-127..127)
    q_BO: tuple = (1.0, 0.0, 0.0, 0.0)  #: attitude relative to the orbit frame, scalar first
    omega_BO_B: tuple = (0.0, 0.0, 0.0)  #: body rate relative to the orbit frame, rad/s, in B
    m_commanded_B: tuple = (0.0, 0.0, 0.0)  #: commanded dipole, A·m²
    pointing_error_rad: float | None = None  #: angle to the controller's target, if one is set
    wheel_momenta: tuple = ()          #: per wheel, N·m·s
    wheel_speeds_rad_s: tuple = ()     #: per wheel, relative to the body, rad/s
    wheel_torques_nm: tuple = ()       #: per wheel, motor torque over the last step, N·m


class TruthSample(_TruthFields):
    """One row of the truth trace (the fields are :class:`_TruthFields`'; a NamedTuple body holds
    fields only, so the CSV header and row live on this subclass)."""

    __slots__ = ()

    CSV_HEADER = ("time_us", "t_s", "q0", "q1", "q2", "q3", "wx_rad_s", "wy_rad_s", "wz_rad_s",
                  "rate_deg_s", "bx_T", "by_T", "bz_T", "mx_Am2", "my_Am2", "mz_Am2",
                  "qo0", "qo1", "qo2", "qo3", "wox_rad_s", "woy_rad_s", "woz_rad_s",
                  "mcmd_x_Am2", "mcmd_y_Am2", "mcmd_z_Am2")

    def csv_row(self) -> tuple:
        return (self.time_us, self.t_s, *self.q_BN, *self.omega_BN_B, self.rate_deg_s, *self.b_B,
                *self.m_coils_B, *self.q_BO, *self.omega_BO_B, *self.m_commanded_B)


class TruthRecorder:
    """A truth-trace callback that keeps every :class:`TruthSample` (``rows``) and writes CSV."""

    def __init__(self) -> None:
        self.rows: list[TruthSample] = []

    def __call__(self, sample: TruthSample) -> None:
        self.rows.append(sample)

    def write_csv(self, path: str) -> None:
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(",".join(TruthSample.CSV_HEADER) + "\n")
            for row in self.rows:
                fh.write(",".join(repr(v) for v in row.csv_row()) + "\n")


class SimulatedSpacecraft(ResetLine):
    """One simulated spacecraft, stepped on the deployment's clock.

    Args:
        scenario: a :class:`~detumble.sim.scenario.Scenario`, or a packaged scenario name / file path.
        clock: the deployment's clock (default: a new :class:`SimulatedClock`). Use
            ``scheduler.clock`` and then :meth:`attach` the scheduler.
        seed: overrides the scenario's sensor-noise seed.
        origin_us: the clock reading (``clock.current_us``) that is plant t = 0; default: now.
    """

    # Avionics state, set in _init_avionics (declared here: methods above it assign it too).
    _coil_w: float | None  # the coils' supply power, W; None: recompute
    _accel_slot: int | None
    _accel_period_ns: int
    _flash_dir: str | None

    def __init__(self, scenario: Scenario | str, *, clock: SimulatedClock | None = None,
                 seed: int | None = None, origin_us: int | None = None) -> None:
        from detumble.sim.plant import Plant

        if isinstance(scenario, str):
            scenario = load_scenario(scenario)
        self.scenario = scenario
        self.plant = Plant(scenario, seed)
        self.clock = clock if clock is not None else SimulatedClock()
        self.origin_us = self.clock.current_us if origin_us is None else int(origin_us)
        if self.origin_us > self.clock.current_us:
            raise ValueError(f"origin_us {self.origin_us} is after the clock's time "
                             f"{self.clock.current_us} us; the plant cannot start in the future")
        step_ns = int(round(scenario.dynamics_step_s * 1e9))
        if step_ns <= 0:
            raise ValueError(f"dynamics_step_s must be positive, got {scenario.dynamics_step_s}")
        self._step_ns = step_ns
        self._trace: Callable[[TruthSample], None] | None = None
        self._trace_interval_ns = 0
        self._trace_next_ns: int | None = None
        self.steps_taken = 0
        self._attached: list[object] = []  # the schedulers this spacecraft is attached to
        self._times: dict[int, Time] = {}  # time_of's latest results, by plant time (ns)
        self._times_generation = -1  # the clock generation and origin they were made with
        self._times_origin_us = self.origin_us
        self._init_avionics(seed)
        self.sync()

    @classmethod
    def for_scheduler(cls, scenario: Scenario | str, scheduler, *, seed: int | None = None) -> "SimulatedSpacecraft":
        """Make a spacecraft on ``scheduler.clock`` (plant t = 0 at the scheduler's now) and attach it."""
        craft = cls(scenario, clock=scheduler.clock, seed=seed)
        craft.attach(scheduler)
        return craft

    # --- time -----------------------------------------------------------------------------------

    def attach(self, scheduler) -> None:
        """Step the physics whenever ``scheduler`` advances time (it must run this spacecraft's clock)."""
        if scheduler.clock is not self.clock:
            raise ValueError("the scheduler runs another clock than this spacecraft; make the spacecraft "
                             "with clock=scheduler.clock (or use SimulatedSpacecraft.for_scheduler)")
        if scheduler in self._attached:
            return
        self._attached.append(scheduler)
        scheduler.add_time_listener(self.advance_to_us)  # on_time without the extra call

    def on_time(self, time_us: int) -> None:
        """Scheduler time listener: integrate up to clock time ``time_us`` (``clock.current_us``)."""
        self.advance_to_us(time_us)

    def sync(self) -> None:
        """Bring the physics to the clock's present time (no-op when already there)."""
        # The plant's time read from its slot (what Plant.t_ns returns): the drivers sync before
        # every access, about ten times a tick.
        if (self.clock.current_us - self.origin_us) * 1000 != self.plant._t_ns:
            self.advance_to_us(self.clock.current_us)

    def advance_to_us(self, time_us: int) -> None:
        """Integrate to clock time ``time_us`` in fixed dynamics steps (the last one partial).

        Raises ValueError for a time earlier than the plant's: physics never runs backwards.
        """
        plant = self.plant
        target = (int(time_us) - self.origin_us) * 1000
        now = plant._t_ns  # Plant.t_ns's slot: this runs on every scheduler event
        if target <= now:
            if target < now:
                raise ValueError(f"cannot integrate backwards: the plant is at {self.plant_time_us} us "
                                 f"of clock time, asked for {time_us} us")
            return
        step = self._step_ns
        trace_next = self._trace_next_ns
        while now < target:
            nxt = (now // step + 1) * step
            if nxt > target:
                nxt = target
            if trace_next is not None and trace_next < nxt:
                nxt = trace_next
            if self.power is not None:
                self._step_power(now, nxt)
            plant.step_ns(nxt - now)  # nxt > now: the plant's own ns step, no float round trip
            self.steps_taken += 1
            now = plant._t_ns
            if now != nxt:  # pragma: no cover - guards the ns rounding in Plant.step
                raise AssertionError(f"plant stepped to {now} ns instead of {nxt} ns")
            if now == trace_next and self._trace is not None:
                self.end_if_diverged()
                self._trace(self.truth())
                trace_next += self._trace_interval_ns
        self._trace_next_ns = trace_next

    def end_if_diverged(self) -> None:
        """Raise :class:`~fprime_lite.deploy.resources.SimulationEnded` when the plant's state is no
        longer finite (the integration diverged: a rate far beyond what the dynamics step resolves).

        Checked where it costs nothing per tick: at each truth-trace sample, and when a sensor read
        fails on the numbers it was given. The run then stops with one line saying why, instead of
        every flight component reading NaN and containing the same fault thousands of times."""
        plant = self.plant
        state = plant._state  # a NaN anywhere reaches the rate within a step; NaN < x is False
        lim = _DIVERGED_RATE_RAD_S
        if -lim < state[4] < lim and -lim < state[5] < lim and -lim < state[6] < lim:
            return
        sc = self.scenario
        w0 = sc.omega_BN_B0
        start_deg_s = math.degrees(math.sqrt(w0[0] ** 2 + w0[1] ** 2 + w0[2] ** 2))
        turn = math.radians(start_deg_s) * sc.dynamics_step_s
        why = (f"a start at {start_deg_s:,.6g} deg/s turns the body {turn:,.3g} rad per {sc.dynamics_step_s:g} s "
               f"dynamics step, more than the integrator resolves — lower the rate or the scenario's "
               f"dynamics_step_s" if turn > _MAX_TURN_PER_STEP_RAD else
               "check the scenario's inertia, actuator limits and dynamics_step_s")
        raise SimulationEnded("plant diverged", f"the simulated spacecraft diverged at t = {plant.t_ns * 1e-9:.3f} s "
                                                f"of plant time (its body rate is no longer finite): {why}")

    @property
    def plant_time_us(self) -> int:
        """The plant's time as a clock reading (``current_us``; truncated to whole µs)."""
        return self.origin_us + self.plant.t_ns // 1000

    def time_of(self, t_ns: int) -> Time:
        """The F´ time (clock base and context) of plant time ``t_ns`` (ns since plant t = 0)."""
        c = self.clock
        # Sensors and wheels are read several times per sample instant: the few latest times are
        # kept (a Time is immutable), keyed by plant time while what else they are made of holds
        # (the origin, and a SimulatedClock's epoch, base and context by its generation, which
        # changes with any of them); a change of either empties the table.
        times = self._times
        if c.generation != self._times_generation or self.origin_us != self._times_origin_us:
            times.clear()
            self._times_generation = c.generation
            self._times_origin_us = self.origin_us
        t = times.get(t_ns)
        if t is None:
            if len(times) >= 8:
                times.clear()
            t = times[t_ns] = Time.from_us(c.epoch_us + self.origin_us + t_ns // 1000, c.time_base, c.context)
        return t

    def now(self) -> Time:
        """The clock's present time as an F´ time."""
        return self.clock.now()

    # --- sensors --------------------------------------------------------------------------------

    def magnetometer_sample(self) -> tuple[float, float, float, Time]:
        """``(bx, by, bz, t_sample)``: the held LIS2MDL sample in gauss (body axes) and when it was taken.

        Sample-and-hold at the sensor's ODR: ``t_sample`` is the latest ODR instant ≤ now. The
        sample includes the coils' coupling ``K · m_coils`` when the coils were on at that instant.
        An ``ideal`` magnetometer returns the true field now, stamped now.
        """
        plant = self.plant
        clock = self.clock  # sync(), written out: these are the reads and commands of every tick
        if (clock.current_us - self.origin_us) * 1000 != plant._t_ns:
            self.advance_to_us(clock.current_us)
        mag = plant.magnetometer
        if mag.spec.ideal:
            b = plant.b_B
            g = GAUSS_PER_TESLA
            return (b[0] * g, b[1] * g, b[2] * g, self.time_of(plant.t_ns))
        try:
            s = mag.sample_gauss
        except _NUMERIC_ERRORS:
            self.end_if_diverged()
            raise
        return (s[0], s[1], s[2], self.time_of(mag.sample_time_ns))

    def gyro_sample(self, stamped: bool = True) -> tuple:
        """``(wx, wy, wz, t_sample)``: the held LSM6DSO sample in rad/s (body axes) and its time;
        ``(wx, wy, wz)`` without the time when ``stamped`` is False (the IMU manager's reads, whose
        ``AngularVelocity`` carries no time stamp)."""
        plant = self.plant
        clock = self.clock  # sync(), written out: these are the reads and commands of every tick
        if (clock.current_us - self.origin_us) * 1000 != plant._t_ns:
            self.advance_to_us(clock.current_us)
        gyro = plant.gyro
        if gyro.spec.ideal:
            w = plant.omega_BN_B
            return (w[0], w[1], w[2], self.time_of(plant.t_ns)) if stamped else (w[0], w[1], w[2])
        try:
            s = gyro.sample_rad_s
        except _NUMERIC_ERRORS:
            self.end_if_diverged()
            raise
        return (s[0], s[1], s[2], self.time_of(gyro.sample_time_ns)) if stamped else s

    def acceleration(self) -> tuple[float, float, float]:
        """The LSM6DSO reading, m/s², body axes: free fall plus the centripetal term at the IMU's lever
        arm, with the sensor's bias, noise and quantisation (:mod:`detumble.sim.accelerometer`).
        The output register is refreshed at the accelerometer's ODR (:meth:`set_accelerometer_odr_hz`,
        initially the gyro's): reads within one output period return the same sample."""
        self.sync()
        slot = self.plant.t_ns // self._accel_period_ns
        if slot != self._accel_slot:
            try:
                self._accel_sample = self.accelerometer.measure(self.plant.omega_BN_B)
            except _NUMERIC_ERRORS:
                self.end_if_diverged()
                raise
            self._accel_slot = slot
        return self._accel_sample

    @property
    def magnetometer_period_us(self) -> float:
        """The magnetometer's output period, µs."""
        return self.plant.magnetometer.period_ns / 1000.0

    def set_magnetometer_odr_hz(self, odr_hz: float) -> None:
        """Reconfigure the magnetometer's output data rate (the flight ImuManager's configure()).

        Samples stay on the grid ``k / odr`` from plant t = 0; the held sample is kept until the
        next instant of the new grid.
        """
        if not (isinstance(odr_hz, (int, float)) and math.isfinite(odr_hz) and odr_hz > 0):
            raise ValueError(f"odr_hz must be a positive number, got {odr_hz!r}")
        self.plant.magnetometer.period_ns = int(round(1e9 / odr_hz))

    def set_gyro_odr_hz(self, odr_hz: float) -> None:
        """Reconfigure the gyro's output data rate."""
        if not (isinstance(odr_hz, (int, float)) and math.isfinite(odr_hz) and odr_hz > 0):
            raise ValueError(f"odr_hz must be a positive number, got {odr_hz!r}")
        self.plant.gyro.period_ns = int(round(1e9 / odr_hz))

    # --- actuators ------------------------------------------------------------------------------

    @property
    def coil_faces(self) -> tuple[int, ...]:
        """Faces that carry a coil (empty for ideal torque rods)."""
        act = self.plant.actuators
        return tuple(sorted(act.coils)) if isinstance(act, CoilSet) else ()

    def set_coil_level(self, face: int, level: int) -> None:
        """Drive the coil on ``face`` at ``level`` (-127..127) from now on (plant sign conventions:
        a positive level gives a dipole along the face's outward normal, so X- +level is -X)."""
        plant = self.plant
        clock = self.clock  # sync(), written out: these are the reads and commands of every tick
        if (clock.current_us - self.origin_us) * 1000 != plant._t_ns:
            self.advance_to_us(clock.current_us)
        if level and self.power is not None and not self.power.face_powered(face):
            raise RuntimeError(f"face {face} is unpowered (its load switch is off); its coil cannot be driven")
        plant.set_coil_level(face, level)
        self._coil_w = None

    def coil_level(self, face: int) -> int:
        return self.plant.coil_levels().get(face, 0)

    # --- reaction wheels ----------------------------------------------------------------------
    # Wheel i of the plant (scenario spacecraft.reaction_wheels); commands act from now on.

    @property
    def wheel_count(self) -> int:
        return self.plant.wheel_count

    def wheel_limits(self, i: int) -> tuple[float, float]:
        """``(max_torque_nm, max_momentum_nms)`` of wheel ``i``."""
        w = self.plant._wheels()
        w._index(i)
        return (w.u_max[i], w.h_max[i])

    def set_wheel_torque(self, i: int, torque_nm: float) -> None:
        """Motor torque on wheel ``i`` (N·m along its axis) from now on (clipped by the plant)."""
        plant = self.plant
        clock = self.clock  # sync(), written out: these are the reads and commands of every tick
        if (clock.current_us - self.origin_us) * 1000 != plant._t_ns:
            self.advance_to_us(clock.current_us)
        plant.set_wheel_torque(i, torque_nm)

    def set_wheel_speed(self, i: int, speed_rad_s: float) -> None:
        """Speed set-point of wheel ``i`` relative to the body, rad/s, from now on."""
        self.sync()
        self.plant.set_wheel_speed(i, speed_rad_s)

    def set_wheel_enabled(self, i: int, enabled: bool) -> None:
        self.sync()
        self.plant.set_wheel_enabled(i, enabled)

    def wheel_sample(self, i: int) -> tuple[float, float, float, Time]:
        """``(speed_rad_s, momentum_nms, torque_nm, t)`` as wheel ``i`` reports them now (the
        momentum with the configured reading noise)."""
        plant = self.plant
        clock = self.clock  # sync(), written out: these are the reads and commands of every tick
        if (clock.current_us - self.origin_us) * 1000 != plant._t_ns:
            self.advance_to_us(clock.current_us)
        try:
            speed, h, u, _ = plant.wheel_reading(i)
        except _NUMERIC_ERRORS:
            self.end_if_diverged()
            raise
        return (speed, h, u, self.time_of(plant._t_ns))

    def wheel_limit_flags(self, i: int) -> tuple[bool, bool]:
        """``(torque_clipped, momentum_limited)`` of wheel ``i`` over the last step."""
        self.sync()
        w = self.plant._wheels()
        w._index(i)
        return (w.torque_clipped[i], w.momentum_limited[i])

    # --- star tracker ---------------------------------------------------------------------------

    @property
    def has_star_tracker(self) -> bool:
        return self.plant.star_tracker is not None

    def star_tracker_sample(self) -> tuple[tuple[float, float, float, float], bool, Time]:
        """``(q_BN, valid, t_sample)``: the held star-tracker solution (scalar first), whether it is
        valid and when it was taken."""
        plant = self.plant
        clock = self.clock  # sync(), written out: these are the reads and commands of every tick
        if (clock.current_us - self.origin_us) * 1000 != plant._t_ns:
            self.advance_to_us(clock.current_us)
        try:
            q0, q1, q2, q3, valid, t = plant.star_tracker_reading()
        except _NUMERIC_ERRORS:
            self.end_if_diverged()
            raise
        return ((q0, q1, q2, q3), valid, self.time_of(int(round(t * 1e9))))

    def set_pointing_target(self, q_target, frame: str = "inertial") -> None:
        """Tell the truth log what the controller is pointing at (``Plant.set_pointing_target``)."""
        self.plant.set_pointing_target(q_target, frame)

    # --- ideal torque rods and the orbit frame --------------------------------------------------

    @property
    def has_torque_rods(self) -> bool:
        """True when the actuators are ideal rods commanded by dipole (scenario actuators: rods)."""
        return not isinstance(self.plant.actuators, CoilSet)

    def apply_dipole(self, m_B) -> tuple[float, float, float]:
        """Command the ideal rods to ``m_B`` (A·m², B) from now on; returns the dipole they give
        (each axis limited to the rods' maximum)."""
        if not self.has_torque_rods:
            raise ValueError("this spacecraft has coils, not ideal torque rods; drive its coils by level")
        self.sync()
        self.plant.apply_dipole_B((float(m_B[0]), float(m_B[1]), float(m_B[2])))
        return self.plant.m_coils_B

    def orbit_frame_sample(self) -> tuple[tuple[float, float, float, float], float, Time]:
        """``(q_ON, n, t)``: the orbit frame O relative to N (scalar first), the orbit rate (rad/s)
        and the time — what an on-board orbit propagator knows."""
        self.sync()
        plant = self.plant
        return plant.q_ON, plant.orbit.mean_motion, self.clock.now()

    def ephemeris_sample(self):
        """The plant's :meth:`~detumble.sim.plant.Plant.ephemeris` now (``control.targets.Ephemeris``): what an
        on-board ephemeris or GPS knows (truth here)."""
        self.sync()
        return self.plant.ephemeris()

    # --- truth ----------------------------------------------------------------------------------

    def truth(self) -> TruthSample:
        """The present true state (no sync: the state at the plant's own time)."""
        p = self.plant
        t_ns = p.t_ns
        w = p.omega_BN_B
        q_bo, w_bo = p.orbit_relative()  # the orbit's position and O's axes once for both
        return TruthSample(
            time_us=self.clock.epoch_us + self.origin_us + t_ns // 1000,
            t_s=t_ns * 1e-9,
            q_BN=tuple(p.q_BN),
            omega_BN_B=tuple(w),
            rate_deg_s=math.degrees(math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])),
            b_B=tuple(p.b_B),
            m_coils_B=tuple(p.m_coils_B),
            coil_levels=p.coil_levels(),
            q_BO=q_bo,
            omega_BO_B=w_bo,
            m_commanded_B=tuple(p.m_commanded_B),
            pointing_error_rad=p.pointing_error_rad(),
            wheel_momenta=tuple(p.wheel_momenta),
            wheel_speeds_rad_s=tuple(p.wheel_speeds_rad_s),
            wheel_torques_nm=tuple(p.wheel_torques_nm),
        )

    def set_trace(self, callback: Callable[[TruthSample], None] | None, interval_us: int = 1_000_000) -> None:
        """Call ``callback(TruthSample)`` now and then every ``interval_us`` of plant time (on the grid
        ``k * interval_us`` from plant t = 0). ``None`` stops the trace."""
        if callback is None:
            self._trace = None
            self._trace_next_ns = None
            return
        if not isinstance(interval_us, int) or interval_us <= 0:
            raise ValueError(f"interval_us must be a positive integer, got {interval_us!r}")
        self.sync()
        self._trace = callback
        self._trace_interval_ns = interval_us * 1000
        now = self.plant.t_ns
        callback(self.truth())
        self._trace_next_ns = (now // self._trace_interval_ns + 1) * self._trace_interval_ns

    def read_setting(self, key: str):
        """Scenario value ``key`` as this spacecraft's plant holds it (campaign read-back; call it
        before the run: initial-state keys read the present state)."""
        from detumble.sim.readback import read_setting

        return read_setting(self.plant, key)

    # --- avionics: electrical power, load switches, flash, reset line ---------------------------------

    def _init_avionics(self, seed: int | None) -> None:
        sc = self.scenario
        self.power = (ElectricalSystem(sc.power, julian_date(sc.epoch), R_EARTH_EQ)
                      if sc.power.enabled else None)
        #: face and interior temperatures (with the power model: the loads heat the interior)
        self.thermal = ThermalModel() if self.power is not None else None
        #: the compiled kernel's power_step when the plant flies the compiled kernel (the same floats as
        #: power.step then thermal.step: plant_kernel.step_power_thermal), else None
        self._power_kernel = None
        self._power_constants: tuple = ()
        if self.power is not None and self.thermal is not None and self.plant.implementation == "compiled":
            self._power_kernel = plant_kernel.load().module
            self._power_constants = plant_kernel.power_constants(self.power, self.thermal)
        self.accelerometer = Accelerometer(sc.accelerometer, (sc.seed if seed is None else seed) * 7919 + 3)
        #: the six face light sensors (cosine response, eclipse, the stated noise: ``sim.sun_sensors``)
        self.sun_sensors = SunSensorModel(julian_date(sc.epoch), R_EARTH_EQ, sc.sun_sensors,
                                          seed=sc.seed if seed is None else seed)
        act = self.plant.actuators
        self._coils_lagged = isinstance(act, CoilSet) and act._lagged  # currents change between commands
        self._coil_w = None
        self._power_pending_ns = 0
        self._power_t0_ns = 0
        self._power_coil_j = 0.0
        self._accel_slot = None
        self._accel_period_ns = max(1, self.plant.gyro.period_ns)
        self._accel_sample = (0.0, 0.0, 0.0)
        self._flash_dir = None
        #: what the simulated LoRa ground peer heard from the radio, oldest first (64 KiB kept)
        self.radio_peer: deque[int] = deque(maxlen=65536)
        self.resets = 0                                      #: flight-software resets so far
        self.reset_handler: Callable[[str], None] | None = None

    def _step_power(self, t0_ns: int, t1_ns: int) -> None:
        """Sum the coils' energy over this dynamics step; integrate the electrical system once
        :data:`POWER_STEP_NS` of plant time has gathered (solar input and battery held over it)."""
        coil_w = self._coil_w
        if coil_w is None or self._coils_lagged:
            coil_w = 0.0
            act = self.plant.actuators
            if isinstance(act, CoilSet):
                for coil in act.coils.values():
                    if coil.level:
                        coil_w += coil_supply_power_w(coil.level, MAX_LEVEL, coil.spec.voltage_v, coil.current_a)
            self._coil_w = coil_w
        pending = self._power_pending_ns
        if pending == 0:
            self._power_t0_ns = t0_ns
        d_ns = t1_ns - t0_ns
        pending += d_ns
        if coil_w:  # adding 0.0 W x dt leaves the sum as it is
            self._power_coil_j += coil_w * d_ns * 1e-9
        if pending >= POWER_STEP_NS:
            dt = pending * 1e-9
            plant = self.plant
            assert self.power is not None  # only called with a power model
            if self._power_kernel is not None:
                plant_kernel.step_power_thermal(self._power_kernel, self._power_constants, self.power, self.thermal,
                                                dt, self._power_t0_ns * 1e-9, plant.q_BN, plant.r_N,
                                                self._power_coil_j / dt)
            else:
                self.power.step(dt, self._power_t0_ns * 1e-9, plant.q_BN, plant.r_N, self._power_coil_j / dt)
                assert self.thermal is not None  # made with the power model
                self.thermal.step(dt, self.power.face_flux_w_m2, self.power.load_w)
            pending = 0
            self._power_coil_j = 0.0
        self._power_pending_ns = pending

    def energy_j(self) -> tuple[float, float]:
        """``(coil_j, load_j)``: the energy the coils and the whole load drew from plant t = 0 to now, J,
        exact to the last dynamics step (the part not yet handed to the electrical system included);
        ``(0.0, 0.0)`` without a power model. Their differences over an interval give its mean powers."""
        eps = self.power
        if eps is None:
            return (0.0, 0.0)
        pending_coil = self._power_coil_j
        pending_s = self._power_pending_ns * 1e-9
        return (eps.coil_j + pending_coil, eps.load_j + pending_coil + eps.switched_load_w() * pending_s)

    def set_accelerometer_odr_hz(self, odr_hz: float) -> None:
        """Reconfigure the accelerometer's output data rate."""
        if not (isinstance(odr_hz, (int, float)) and math.isfinite(odr_hz) and odr_hz > 0):
            raise ValueError(f"odr_hz must be a positive number, got {odr_hz!r}")
        self._accel_period_ns = max(1, int(round(1e9 / odr_hz)))

    def face_powered(self, face: int) -> bool:
        """True when the face's load switch is closed (always True without a power model)."""
        return self.power is None or self.power.face_powered(face)

    def load_switch(self, name: str) -> bool:
        """The state of load switch ``name`` (``face0`` … ``face5``, ``payloadPower``, ``payloadBattery``)."""
        return True if self.power is None else self.power.switches[name]

    def set_load_switch(self, name: str, on: bool) -> None:
        """Open or close a load switch from now on; opening a face's switch de-energises its coil."""
        self.sync()
        if self.power is None:
            return
        self.power.set_switch(name, on)
        if not on and name in FACE_SWITCHES:
            face = FACE_SWITCHES.index(name)
            if face in self.coil_faces:
                self.plant.set_coil_level(face, 0)
                self._coil_w = None

    def temperature_c(self, where: str) -> float:
        """The temperature (°C) at ``where``: ``face0`` … ``face5`` (a face panel) or ``interior``
        (battery cells, flight computer); 20 °C without a power model (no thermal model either)."""
        self.sync()
        th = self.thermal
        if th is None:
            return 20.0
        if where == "interior":
            return th.interior_c
        if where in FACE_SWITCHES:
            return th.face_c(FACE_SWITCHES.index(where))
        raise ValueError(f"no temperature at {where!r}; places are {list(FACE_SWITCHES)} and 'interior'")

    def face_sunlight_w_m2(self, face: int) -> float:
        """Sunlight falling on face ``face`` (0 X+ … 5 Z−), W/m², over the last power step (0 in
        eclipse or without a power model)."""
        self.sync()
        return 0.0 if self.power is None else self.power.face_flux_w_m2[face]

    def light_sensor_lux(self, face: int) -> float:
        """What the light sensor on face ``face`` (0 X+ … 5 Z−) reads now, lux: the cosine response to the Sun,
        0 in eclipse, with the sensor's gain error and noise (``sim.sun_sensors``; independent of the power model)."""
        self.sync()
        p = self.plant
        return self.sun_sensors.read(p.t_ns * 1e-9, p.q_BN, p.r_N)[face]

    @property
    def burnwire_on(self) -> bool:
        """True while the antenna burnwire's GPIOs are high (always False without a power model)."""
        return self.power is not None and self.power.burnwire_on

    def set_burnwire(self, on: bool) -> None:
        """Drive the antenna burnwire's GPIOs from now on (its heater is a load on the battery)."""
        self.sync()
        if self.power is not None:
            self.power.burnwire_on = bool(on)

    @property
    def flash_dir(self) -> str:
        """The simulated flight computer's non-volatile storage (a directory kept for this spacecraft's
        life: files written there survive a flight-software reset)."""
        if self._flash_dir is None:
            import tempfile
            self._flash = tempfile.TemporaryDirectory(prefix="sitl-flash-")
            self._flash_dir = flash_dir = self._flash.name
            return flash_dir
        return self._flash_dir

    def use_flash_dir(self, path: str) -> None:
        """Keep the simulated flash in ``path`` (created if needed) instead of a temporary directory."""
        import os
        os.makedirs(path, exist_ok=True)
        self._flash_dir = os.fspath(path)

    def request_reset(self, kind: str = "cold") -> None:
        """Pull the flight computer's reset line (``kind`` "cold" or "warm"); the deployment that
        attached itself through :attr:`reset_handler` restarts its software. The plant keeps flying."""
        if self.reset_handler is None:
            raise RuntimeError("no flight software is attached to this spacecraft's reset line")
        self.reset_handler(kind)

    def attach_flight_software(self, deployment) -> None:
        """Wire the reset line to ``deployment`` (called by the deployment at start-up)."""
        self.reset_handler = deployment.request_reset

    def flight_software_reset(self) -> None:
        """The deployment restarts its software: reset what the flight computer's reset resets."""
        self.hardware_reset()
        self.resets += 1

    def scheduler(self):
        """The scheduler this spacecraft is attached to (None when stepped by hand)."""
        return self._attached[0] if self._attached else None

    def hardware_reset(self) -> None:
        """What a reset of the flight computer does to the hardware: the load-switch GPIOs return to
        their power-on state (open), the burnwire GPIOs go low and every coil driver stops."""
        if self.power is not None:
            for name in self.power.switches:
                self.set_load_switch(name, False)
            self.power.burnwire_on = False
        for face in self.coil_faces:
            self.plant.set_coil_level(face, 0)
        self._coil_w = None

    def __repr__(self) -> str:
        return (f"<SimulatedSpacecraft {self.scenario.name!r} t={self.plant.t:.6f} s "
                f"|w|={self.plant.rate_deg_s:.3f} deg/s>")


def _spacecraft_fingerprint(args: dict) -> dict:
    """The scenario a spacecraft made with topology ``args`` resolves to
    (:func:`detumble.sim.scenario.scenario_fingerprint`); a Scenario object given directly has none."""
    from detumble.sim.scenario import scenario_fingerprint

    scenario = args.get("scenario", "default")
    return scenario_fingerprint(scenario) if isinstance(scenario, str) else {}


@topology_resource(role="simulation", fingerprint=_spacecraft_fingerprint)
def make_spacecraft(scenario: Scenario | str = "default", scheduler: Scheduler | None = None, *,
                    seed: int | None = None, settings: Sequence[str] = ()) -> SimulatedSpacecraft:
    """The simulated spacecraft of ``scenario`` stepping on ``scheduler``'s clock from now.

    ``settings`` override single scenario values (``"sensors.magnetometer.noise_std_gauss=0"``)
    when ``scenario`` is a name or file.
    """
    if scheduler is None:
        raise ValueError("make_spacecraft needs the deployment's scheduler (args: {scheduler: $scheduler})")
    from detumble.sim.scenario import SettingError

    if isinstance(scenario, str):
        try:
            scenario = load_scenario(scenario, settings=settings)
        except SettingError as exc:  # the command line's --set, not the topology's args
            raise RoleOptionError(str(exc)) from None
    elif settings:
        raise ValueError("settings apply to a scenario given by name or file, not to a loaded Scenario")
    clock = scheduler.clock
    if clock.current_us == 0 and clock.epoch_us == 0:
        clock.epoch_us = scenario_epoch_us(scenario)
    return SimulatedSpacecraft.for_scheduler(scenario, scheduler, seed=seed)
