"""The simulated spacecraft ("plant"): state, time, environment, actuators and sensors.

:class:`Plant` owns the rigid-body state (``q_BN`` scalar first, ``omega_BN_B`` rad/s), an
integer-nanosecond clock starting at 0 at the scenario epoch, the orbit and field models, the
coils (or ideal rods) and the magnetometer and gyro. The simulated F' drivers call its getters;
everything they exchange is plain floats and tuples (no numpy on the per-tick path).

Within one :meth:`Plant.step` the coil dipole (its mean over the step if the coils have an L/R
lag), the inertial field ``b_N`` and the orbit direction are held; the attitude-dependent torques
are re-evaluated at each RK4 stage. The field and orbit are evaluated once per step, at its end.

That RK4 step (with the reaction wheels' momenta, when the spacecraft has wheels) and (circular
orbit with the centred dipole or the orbit-constant field) that environment update run in the
compiled kernel when it can be had (:mod:`.plant_kernel`, ``FPRIME_LITE_PLANT``): the same floats
as this module's Python path, which is the reference.
"""

from __future__ import annotations

import math

from detumble.sim import frames, plant_kernel
from detumble.sim.attitude import RigidBody, State
from detumble.sim.coils import CoilSet, TorqueRods
from detumble.sim.drive_integrals import DriveIntegrals
from detumble.sim.field import DipoleField, FieldAlongOrbit, OrbitConstantField, WmmField
from detumble.sim.laws import scale_to_limits
from detumble.sim.orbit import CircularOrbit, TleOrbit
from detumble.sim.epoch import decimal_year, julian_date
from detumble.sim.igrf import IgrfField
from detumble.sim.scenario import Scenario
from detumble.sim.sun import in_umbra, sun_direction_N
from detumble.sim.torques import SOLAR_PRESSURE_N_M2, BoxSurfaces, atmosphere_density
from detumble.control.targets import Ephemeris
from detumble.control.units import GAUSS_PER_TESLA
from detumble.sim.sensors import Gyro, Magnetometer
from detumble.sim.star_tracker import StarTracker
from detumble.sim.vec import Quat, Vec3, cross, mat_vec, quat_normalize, rotate_b_to_n, rotate_n_to_b, scale
from detumble.sim.wheels import WheelAssembly, equations_inertia, step_with_wheels

_ZERO = (0.0, 0.0, 0.0)


def _derive_seed(seed: int, stream: int) -> int:
    return (int(seed) * 0x9E3779B1 + stream * 0x85EBCA6B) & 0xFFFFFFFFFFFF


def build_orbit(sc: Scenario):
    o = sc.orbit
    if o.type == "tle":
        assert o.tle is not None  # the scenario loader requires the TLE lines for type tle
        return TleOrbit(o.tle[0], o.tle[1], julian_date(sc.epoch), o.table_step_s, o.mu_m3_s2)
    return CircularOrbit(
        o.altitude_km * 1e3, math.radians(o.inclination_deg), math.radians(o.raan_deg),
        math.radians(o.arg_latitude_deg), o.mu_m3_s2, o.earth_radius_m, o.j2_coefficient if o.j2 else 0.0,
    )


def build_field(sc: Scenario, orbit) -> FieldAlongOrbit | None:
    f = sc.field
    if f.model == "none":
        return None
    if f.model == "orbit_constant":
        return FieldAlongOrbit(OrbitConstantField(f.b_orbit_t, orbit), orbit, None)
    if f.model == "wmm2025":
        return FieldAlongOrbit(WmmField(sc.epoch, f.earth_rotation_rate_rad_s, sc.earth_angle0_rad), orbit,
                               f.table_step_s)
    if f.model == "igrf14":
        igrf = IgrfField(decimal_year(sc.epoch), 13, f.earth_rotation_rate_rad_s, sc.earth_angle0_rad)
        return FieldAlongOrbit(igrf, orbit, f.table_step_s)
    model = DipoleField(f.g10_nt, f.g11_nt, f.h11_nt, f.reference_radius_m, f.earth_rotation_rate_rad_s,
                        sc.earth_angle0_rad)
    return FieldAlongOrbit(model, orbit, None)


class Plant:
    """One simulated spacecraft built from a :class:`~detumble.sim.scenario.Scenario`.

    ``seed`` (default: the scenario's) seeds the sensor noise streams. ``implementation`` is
    ``auto``, ``python`` or ``compiled`` (default: ``$FPRIME_LITE_PLANT``, else ``auto``): whether the
    RK4 step and the environment run in the compiled kernel (:mod:`.plant_kernel`; the same floats)
    or in the pure-Python reference. :attr:`implementation` says which one this plant got.
    """

    def __init__(self, scenario: Scenario, seed: int | None = None, implementation: str | None = None) -> None:
        sc = scenario
        self.scenario = sc
        self.seed = sc.seed if seed is None else seed
        self.dynamics_step_s = sc.dynamics_step_s
        self.substeps = sc.integrator_substeps
        rw = sc.spacecraft.reaction_wheels
        #: the wheels (None without: the plant then never touches the wheel code)
        self.wheels: WheelAssembly | None = WheelAssembly(rw, _derive_seed(self.seed, 3)) if rw else None
        inertia = equations_inertia(sc.spacecraft.inertia_kg_m2, rw) if rw else sc.spacecraft.inertia_kg_m2
        self.body = RigidBody(inertia, sc.spacecraft.wheel_momentum_nms)
        self.orbit = build_orbit(sc)
        self.field = build_field(sc, self.orbit)
        kernel = plant_kernel.kernel_for(self.body, self.orbit, self.field, implementation, self.wheels)
        #: ``"compiled"`` when the RK4 step (with or without wheels; and the environment, where it is
        #: the circular orbit with the centred dipole or the orbit-constant field) runs in the compiled
        #: kernel, ``"python"`` for the reference
        self.implementation = "python" if kernel is None else "compiled"
        self._step_env = self.body.step_env if kernel is None else kernel.step_env
        self._step_wheels = None if kernel is None or self.wheels is None else kernel.step_wheels
        with_env = kernel is not None and kernel.has_environment
        self._kernel_environment = kernel.environment if with_env else None
        # the fused RK4 step + environment: step (no wheels) or step_wheels_env (wheels), the other None
        self._kernel_step = kernel.step if with_env and self.wheels is None else None
        self._kernel_step_wheels = kernel.step_wheels_env if with_env and self.wheels is not None else None
        if kernel is not None and self.wheels is not None:  # the wheels' commands and limits compiled too
            self.wheels.compiled = kernel.motor_torques
        if sc.spacecraft.actuator_type == "rods":
            self.actuators: CoilSet | TorqueRods = TorqueRods(sc.spacecraft.rods_max_dipole_am2)
        else:
            self.actuators = CoilSet(sc.spacecraft.coils)
        #: exact time integrals of the levels and dipoles (interval means for the logs), kept at each change
        #: once something asked for them (:attr:`drive_integrals`); None until then, so runs that log no
        #: means (campaigns, benchmarks, plant-only runs) pay one attribute test per level change
        self._drive: DriveIntegrals | None = None
        self._scale_dipole = sc.spacecraft.actuator_saturation == "scale"
        self._m_commanded_B: Vec3 = _ZERO
        #: set_coil_level ran since ``_m_commanded_B`` was computed (or apply_dipole_B set it): the
        #: property m_commanded_B computes it from the present levels when next read
        self._commanded_stale = False
        st = sc.star_tracker
        self.star_tracker: StarTracker | None = StarTracker(st, _derive_seed(self.seed, 4)) if st is not None else None
        self._target: tuple[Quat, str] | None = None
        self._ephemeris_epoch: tuple[float, float] | None = None  # (Earth angle rad, Julian date) at t = 0
        self.residual_dipole_B: Vec3 = sc.spacecraft.residual_dipole_am2
        self._gravity_gradient = sc.spacecraft.gravity_gradient
        surf = sc.spacecraft.surfaces
        #: drag and solar-pressure surfaces (None when both torques are off: the steps then pass no torque)
        self._surfaces: BoxSurfaces | None = None
        self._drag, self._solar_pressure = surf.drag, surf.solar_pressure
        if surf.drag or surf.solar_pressure:
            self._surfaces = BoxSurfaces(surf.size_m, surf.cp_offset_m, surf.drag_coefficient,
                                         surf.specular_reflectivity)
        #: the drag and solar-pressure torque of the last step (N m, B)
        self.surface_torque_B: Vec3 = _ZERO
        self.magnetometer = Magnetometer(sc.magnetometer, _derive_seed(self.seed, 1))
        self.gyro = Gyro(sc.gyro, _derive_seed(self.seed, 2))
        if kernel is not None:  # the held samples' resolve compiled too (the same floats and noise draws)
            self.magnetometer.compiled, self.gyro.compiled = plant_kernel.sensor_samples()
        self._mag_samples = not self.magnetometer.spec.ideal  # an ideal sensor never latches
        self._gyro_samples = not self.gyro.spec.ideal
        q0 = sc.q_BN0
        if sc.attitude_frame == "orbit":
            q0 = quat_normalize(frames.q_BN_from_orbit(q0, frames.q_ON(self.orbit, 0.0)))
        w0 = sc.omega_BN_B0
        self._state: State = (q0[0], q0[1], q0[2], q0[3], w0[0], w0[1], w0[2])
        self._t_ns = 0
        self._update_environment()
        # the sensors' first sample is at t = 0
        if not sc.magnetometer.ideal:
            self.magnetometer.sample_gauss = self.magnetometer.measure(self.b_B, self.actuators.dipole_B)
            self.magnetometer.sample_time_ns = 0
        if not sc.gyro.ideal:
            self.gyro.sample_rad_s = self.gyro.measure(self.omega_BN_B)
            self.gyro.sample_time_ns = 0
        if self.star_tracker is not None and st is not None and not st.ideal:
            q, valid = self.star_tracker.measure(self.q_BN, self.omega_BN_B, self._tracker_sun_N(), 0)
            self.star_tracker.sample_q, self.star_tracker.sample_valid = q, valid
            self.star_tracker.sample_time_ns = 0

    # --- time ---------------------------------------------------------------------------------

    @property
    def t(self) -> float:
        """Simulated time since the scenario epoch, seconds."""
        return self._t_ns / 1e9

    @property
    def t_ns(self) -> int:
        return self._t_ns

    def _update_environment(self) -> None:
        t = self._t_ns / 1e9
        if self._kernel_environment is not None:
            self._r_N, self._r_hat_N, self._b_N = self._kernel_environment(t)
            self._gg = self.orbit.gg_coeff if self._gravity_gradient else 0.0  # constant on a circular orbit
            return
        r = self.orbit.position_N(t)
        self._r_N = r
        rn = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
        self._r_hat_N = (r[0] / rn, r[1] / rn, r[2] / rn)
        self._gg = self.orbit.gravity_gradient_coeff(r) if self._gravity_gradient else 0.0
        self._b_N = self.field.b_N(t, r) if self.field is not None else _ZERO

    def step(self, dt: float | None = None) -> None:
        """Advance the plant by ``dt`` seconds (default: the scenario's dynamics step)."""
        if dt is None:
            dt = self.dynamics_step_s
        dt_ns = int(round(dt * 1e9))
        if dt_ns <= 0:
            if dt_ns == 0:
                return
            raise ValueError(f"cannot step backwards (dt = {dt} s)")
        self.step_ns(dt_ns)

    def step_ns(self, dt_ns: int) -> None:
        """Advance the plant by ``dt_ns`` > 0 nanoseconds (what :meth:`step` does after rounding)."""
        dt = dt_ns * 1e-9
        t0 = self._t_ns
        t1 = t0 + dt_ns
        s0 = self._state
        b0_N = self._b_N
        m_coils = self.actuators.advance(dt)
        res = self.residual_dipole_B
        m_tot = (m_coils[0] + res[0], m_coils[1] + res[1], m_coils[2] + res[2])
        kernel_step = self._kernel_step
        kernel_step_wheels = self._kernel_step_wheels
        wheels = self.wheels
        # drag and solar pressure: evaluated at the step's start and held over it (an extra torque argument)
        ext: tuple = () if self._surfaces is None else (self._surface_torque(t0 / 1e9, s0),)
        if kernel_step is not None and self.substeps == 1:
            # the compiled kernel: step_env, then the environment at t1 (_update_environment's floats;
            # the gravity-gradient coefficient is constant on a circular orbit)
            s1, self._r_N, self._r_hat_N, self._b_N = kernel_step(s0, dt, m_tot, b0_N, self._gg, self._r_hat_N,
                                                                  t1 / 1e9, *ext)
            self._state = s1
            self._t_ns = t1
        elif kernel_step_wheels is not None and wheels is not None and self.substeps == 1:
            # the same with the wheels: their limited torques (Python), the coupled RK4 step, the environment
            u = wheels.motor_torques(dt, s0[4:7])
            s1, wheels.h, self._r_N, self._r_hat_N, self._b_N = kernel_step_wheels(
                s0, wheels.h, u, dt, m_tot, b0_N, self._gg, self._r_hat_N, t1 / 1e9, *ext)
            self._state = s1
            self._t_ns = t1
        else:
            n_sub = self.substeps
            if wheels is None:
                step_env = self._step_env  # RigidBody.step_env, or the kernel's (the same floats)
                if n_sub == 1:
                    s1 = step_env(s0, dt, m_tot, b0_N, self._gg, self._r_hat_N, *ext)
                else:
                    s1, h = s0, dt / n_sub
                    for _ in range(n_sub):
                        s1 = step_env(s1, h, m_tot, b0_N, self._gg, self._r_hat_N, *ext)
            else:
                u = wheels.motor_torques(dt, s0[4:7])
                s1, hw, h = s0, wheels.h, dt / n_sub
                step_wheels = self._step_wheels  # the kernel's step_with_wheels (the same floats), or None
                for _ in range(n_sub):
                    if step_wheels is None:
                        s1, hw = step_with_wheels(self.body, s1, hw, u, wheels, h, m_tot, b0_N, self._gg,
                                                  self._r_hat_N, *ext)
                    else:
                        s1, hw = step_wheels(s1, hw, u, h, m_tot, b0_N, self._gg, self._r_hat_N, *ext)
                wheels.h = hw
            self._state = s1
            self._t_ns = t1
            self._update_environment()
        # The sensors' samples due in (t0, t1] are only recorded here; each is computed when read.
        if self._mag_samples:
            mag = self.magnetometer
            period = mag.period_ns
            tk = t1 // period * period
            if tk > t0:
                mag.defer(t0, t1, tk, s0, s1, b0_N, self._b_N, m_coils)
        if self._gyro_samples:
            gyro = self.gyro
            period = gyro.period_ns
            tk = t1 // period * period
            if tk > t0:
                gyro.defer(t0, t1, tk, s0, s1)
        st = self.star_tracker
        if st is not None and not st.spec.ideal and st.latest_instant(t0, t1) is not None:
            st.latch(t0, t1, s0, s1, self._tracker_sun_N() if st.needs_sun else None)

    def _tracker_sun_N(self) -> Vec3 | None:
        """The unit Sun direction (N) now, for the star tracker's exclusion angle; None in the Earth's shadow
        (:func:`.sun.in_umbra`) or when the tracker has no exclusion angle."""
        st = self.star_tracker
        if st is None or not st.needs_sun:
            return None
        sc = self.scenario
        if self._ephemeris_epoch is None:
            self._ephemeris_epoch = (sc.earth_angle0_rad, julian_date(sc.epoch))
        s_hat, _ = sun_direction_N(self._ephemeris_epoch[1] + self.t / 86400.0)
        return None if in_umbra(self._r_N, s_hat, sc.orbit.earth_radius_m) else s_hat

    def _surface_torque(self, t: float, state: State) -> Vec3:
        """Drag + solar-pressure torque (N m, B) at ``t`` s for ``state``: the air co-rotating with the Earth
        (``v_rel = v − ω_E ẑ × r``) at the density of :func:`.torques.atmosphere_density` over the orbit's
        reference sphere; the Sun from :func:`.sun.sun_direction_N`, its pressure scaled by 1/d² and zero in the
        Earth's cylindrical shadow (:func:`.sun.in_umbra`)."""
        surf = self._surfaces
        assert surf is not None  # called only with surfaces
        sc = self.scenario
        q = (state[0], state[1], state[2], state[3])
        r = self._r_N
        tx = ty = tz = 0.0
        if self._drag:
            v = self.orbit.velocity_N(t)
            we = sc.field.earth_rotation_rate_rad_s
            v_rel = (v[0] + we * r[1], v[1] - we * r[0], v[2])
            rn = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
            rho = atmosphere_density(rn - sc.orbit.earth_radius_m)
            tx, ty, tz = surf.drag_torque(rotate_n_to_b(q, v_rel), rho)
        if self._solar_pressure:
            if self._ephemeris_epoch is None:
                self._ephemeris_epoch = (sc.earth_angle0_rad, julian_date(sc.epoch))
            s_hat, d_au = sun_direction_N(self._ephemeris_epoch[1] + t / 86400.0)
            if not in_umbra(r, s_hat, sc.orbit.earth_radius_m):
                a, b, c = surf.solar_torque(rotate_n_to_b(q, s_hat), SOLAR_PRESSURE_N_M2 / (d_au * d_au))
                tx, ty, tz = tx + a, ty + b, tz + c
        self.surface_torque_B = (tx, ty, tz)
        return self.surface_torque_B

    def advance_to(self, t: float) -> None:
        """Step (in dynamics steps, the last one partial) until the clock reads ``t`` seconds."""
        target = int(round(t * 1e9))
        if target < self._t_ns:
            raise ValueError(f"cannot go back in time: plant is at {self.t:.9f} s, asked for {t:.9f} s")
        step_ns = int(round(self.dynamics_step_s * 1e9))
        while self._t_ns < target:
            self.step(min(step_ns, target - self._t_ns) * 1e-9)

    def _sync(self, t: float | None) -> None:
        if t is not None and int(round(t * 1e9)) != self._t_ns:
            self.advance_to(t)

    # --- truth ----------------------------------------------------------------------------------

    @property
    def state(self) -> State:
        return self._state

    @property
    def q_BN(self) -> tuple[float, float, float, float]:
        return self._state[0:4]

    @property
    def omega_BN_B(self) -> Vec3:
        """True body rate relative to inertial, in B, rad/s."""
        return self._state[4:7]

    @property
    def rate_deg_s(self) -> float:
        s = self._state
        return math.degrees(math.sqrt(s[4] * s[4] + s[5] * s[5] + s[6] * s[6]))

    @property
    def r_N(self) -> Vec3:
        return self._r_N

    @property
    def b_N(self) -> Vec3:
        """True geomagnetic field in N, tesla."""
        return self._b_N

    @property
    def b_B(self) -> Vec3:
        """True geomagnetic field in B, tesla (without the coils' own field)."""
        return rotate_n_to_b(self._state[:4], self._b_N)

    def angular_momentum_B(self) -> Vec3:
        return self.body.angular_momentum_B(self._state)

    def gravity_gradient_torque_B(self) -> Vec3:
        """Gravity-gradient torque now, N m in B (zero when the scenario turns it off)."""
        if not self._gg:
            return _ZERO
        r = rotate_n_to_b(self.q_BN, self._r_hat_N)
        return scale(self._gg, cross(r, mat_vec(self.body.inertia, r)))

    def wheel_torque_on_body_B(self) -> Vec3:
        """The wheel motors' torque on the body over the last step, ``-sum u_i g_i`` (N m, B)."""
        w = self.wheels
        if w is None:
            return _ZERO
        x = y = z = 0.0
        for u, g in zip(w.torque_applied, w.axes, strict=True):
            x -= u * g[0]
            y -= u * g[1]
            z -= u * g[2]
        return (x, y, z)

    # --- sensors -------------------------------------------------------------------------------

    def magnetometer_reading(self, t: float | None = None) -> tuple[float, float, float, float]:
        """``(bx, by, bz, t_read)``: held magnetometer sample in gauss (body axes), read time in s.

        With ``t`` the plant is first advanced to ``t``.
        """
        self._sync(t)
        if self.magnetometer.spec.ideal:
            b = self.b_B
            return (b[0] * GAUSS_PER_TESLA, b[1] * GAUSS_PER_TESLA, b[2] * GAUSS_PER_TESLA, self.t)
        g = self.magnetometer.sample_gauss
        return (g[0], g[1], g[2], self.t)

    @property
    def magnetometer_period_s(self) -> float:
        return self.magnetometer.period_ns * 1e-9

    def gyro_reading(self, t: float | None = None) -> tuple[float, float, float, float]:
        """``(wx, wy, wz, t_read)``: held gyro sample in rad/s (body axes), read time in s."""
        self._sync(t)
        if self.gyro.spec.ideal:
            w = self.omega_BN_B
            return (w[0], w[1], w[2], self.t)
        w = self.gyro.sample_rad_s
        return (w[0], w[1], w[2], self.t)

    # --- actuators -----------------------------------------------------------------------------

    def set_coil_level(self, face: int, level: int, t: float | None = None) -> None:
        """Drive the coil on ``face`` (X+ 0, X- 1, Y+ 2, Y- 3, Z- 5) at ``level`` -127...127."""
        if t is not None:
            self._sync(t)
        act = self.actuators
        if type(act) is not CoilSet and not isinstance(act, CoilSet):
            raise TypeError("this spacecraft has ideal torque rods, not face coils; use apply_dipole_B")
        coil = act.coils.get(face)
        if coil is None or type(level) is not int or level != coil.level:
            drive = self._drive
            if drive is not None and drive.t_ns != self._t_ns:  # the coils switch together: credit once
                drive.credit(self._t_ns)
            act.set_level(face, level)  # drivers re-command unchanged levels: nothing to set then
        self._commanded_stale = True  # m_commanded_B follows the levels from now on

    @property
    def m_commanded_B(self) -> Vec3:
        """The commanded dipole, A m^2 in B: what apply_dipole_B was given last, or, after a
        set_coil_level, the dipole the present levels give once the currents have settled
        (:meth:`CoilSet.commanded_dipole_B`, computed when read)."""
        if self._commanded_stale:
            self._m_commanded_B = self.actuators.commanded_dipole_B()
            self._commanded_stale = False
        return self._m_commanded_B

    @property
    def drive_integrals(self) -> DriveIntegrals:
        """The exact time integrals of the actuators' levels and dipoles from the first time this is
        read (:mod:`detumble.sim.drive_integrals`); kept from then on, at each change."""
        if self._drive is None:
            self._drive = DriveIntegrals(self.actuators, self._t_ns)
            self._drive.set_commanded(self.m_commanded_B)
        return self._drive

    def coil_levels(self) -> dict[int, int]:
        if not isinstance(self.actuators, CoilSet):
            return {}
        return self.actuators.levels()

    def apply_dipole_B(self, m_B: Vec3) -> None:
        """Command a body dipole (A m^2): limited per axis (``actuators.saturation``: each axis
        clipped, or the whole vector scaled), split over each axis's coils for coils."""
        self._m_commanded_B = (float(m_B[0]), float(m_B[1]), float(m_B[2]))
        self._commanded_stale = False
        drive = self._drive
        if drive is not None:
            drive.credit(self._t_ns)
            drive.set_commanded(self._m_commanded_B)
        if self._scale_dipole:
            m_B = scale_to_limits(m_B, self.actuators.max_dipole_per_axis())
        self.actuators.apply_dipole_B(m_B)

    @property
    def m_coils_B(self) -> Vec3:
        """Present total actuator dipole in B, A m^2."""
        return self.actuators.dipole_B

    def max_dipole_per_axis(self) -> Vec3:
        return self.actuators.max_dipole_per_axis()

    # --- reaction wheels -------------------------------------------------------------------------
    # Wheel ``i`` spins about ``wheel_axes_B[i]``. Motor torque ``u`` (N m) acts on the wheel along
    # its axis, the body feels ``-u``. Commands are held until changed and act from the present
    # plant time on; the limits are applied at every step (see detumble.sim.wheels).

    @property
    def wheel_count(self) -> int:
        return 0 if self.wheels is None else self.wheels.n

    @property
    def wheel_axes_B(self) -> tuple[Vec3, ...]:
        return () if self.wheels is None else self.wheels.axes

    def _wheels(self) -> WheelAssembly:
        if self.wheels is None:
            raise ValueError("this spacecraft has no reaction wheels (scenario spacecraft.reaction_wheels)")
        return self.wheels

    def set_wheel_torque(self, i: int, torque_nm: float, t: float | None = None) -> None:
        """Command motor torque ``torque_nm`` (N m) on wheel ``i`` (torque mode)."""
        if t is not None:
            self._sync(t)
        w = self.wheels
        if w is None:
            w = self._wheels()  # raises: no wheels
        w.set_torque(i, torque_nm)

    def set_wheel_torques(self, torques_nm, t: float | None = None) -> None:
        """Command every wheel's motor torque at once (a sequence of N values, N m)."""
        self._sync(t)
        w = self._wheels()
        if len(torques_nm) != w.n:
            raise ValueError(f"expected {w.n} wheel torques, got {len(torques_nm)}")
        for i, u in enumerate(torques_nm):
            w.set_torque(i, u)

    def set_wheel_speed(self, i: int, speed_rad_s: float, t: float | None = None) -> None:
        """Command wheel ``i``'s speed relative to the body (rad/s; the wheel's own speed loop)."""
        self._sync(t)
        self._wheels().set_speed(i, speed_rad_s)

    def set_wheel_enabled(self, i: int, enabled: bool, t: float | None = None) -> None:
        """Enable or disable wheel ``i``'s motor (disabled: no motor torque, the wheel coasts)."""
        self._sync(t)
        self._wheels().set_enabled(i, enabled)

    @property
    def wheel_momenta(self) -> tuple[float, ...]:
        """True absolute axial momenta ``h_i = J_s (Omega_i + g_i . omega)``, N m s."""
        return () if self.wheels is None else self.wheels.h

    @property
    def wheel_speeds_rad_s(self) -> tuple[float, ...]:
        """True wheel speeds relative to the body, rad/s."""
        if self.wheels is None:
            return ()
        w = self.omega_BN_B
        return tuple(self.wheels.speed_rad_s(i, w) for i in range(self.wheels.n))

    @property
    def wheel_torques_nm(self) -> tuple[float, ...]:
        """Motor torques applied over the last step (after the limits), N m."""
        return () if self.wheels is None else tuple(self.wheels.torque_applied)

    @property
    def wheel_momentum_B(self) -> Vec3:
        """``sum h_i g_i`` (N m s, in B; the constant ``wheel_momentum_nms`` not included)."""
        return _ZERO if self.wheels is None else self.wheels.momentum_B()

    def wheel_reading(self, i: int, t: float | None = None) -> tuple[float, float, float, float]:
        """``(speed_rad_s, momentum_nms, torque_nm, t_read)`` as the wheel reports them: momentum
        with the configured noise, speed consistent with it, the motor torque of the last step."""
        if t is not None:
            self._sync(t)
        w = self.wheels
        if w is None:
            w = self._wheels()  # raises: no wheels
        if type(i) is not int or not 0 <= i < w.n:
            w._index(i)  # raises for anything but a wheel's index
        h = w.measured_momentum(i)
        s = self._state  # omega_BN_B at 4..6
        g = w.axes[i]
        speed = h / w.js[i] - (g[0] * s[4] + g[1] * s[5] + g[2] * s[6])
        return (speed, h, w.torque_applied[i], self._t_ns / 1e9)

    def total_angular_momentum_N(self) -> Vec3:
        """Body + wheels angular momentum in N, N m s (constant without external torque)."""
        hb = self.body.angular_momentum_B(self._state)
        hw = self.wheel_momentum_B
        return rotate_b_to_n(self.q_BN, (hb[0] + hw[0], hb[1] + hw[1], hb[2] + hw[2]))

    # --- attitude knowledge ------------------------------------------------------------------------

    def star_tracker_reading(self, t: float | None = None) -> tuple[float, float, float, float, bool, float]:
        """``(q0, q1, q2, q3, valid, t_sample)``: the held star-tracker attitude q_BN (scalar first),
        whether it is a valid solution, and when it was taken (s). Ideal: the truth, now."""
        self._sync(t)
        st = self.star_tracker
        if st is None:
            raise ValueError("this spacecraft has no star tracker (scenario sensors.star_tracker)")
        if st.spec.ideal:
            q = self.q_BN
            return (q[0], q[1], q[2], q[3], True, self.t)
        q = st.sample_q
        return (q[0], q[1], q[2], q[3], st.sample_valid, st.sample_time_ns * 1e-9)

    # --- orbit frame and pointing (truth) ----------------------------------------------------------

    @property
    def q_ON(self) -> Quat:
        """The orbit frame O relative to N now (detumble.sim.frames)."""
        return frames.q_ON(self.orbit, self.t)

    @property
    def q_BO(self) -> Quat:
        """True attitude relative to the orbit frame O (scalar first, q0 >= 0)."""
        return frames.q_BO(self.q_BN, self.q_ON)

    @property
    def omega_BO_B(self) -> Vec3:
        """True body rate relative to O, in B, rad/s (seed 004 eq. 14)."""
        t = self.t
        r, v = self.orbit.position_velocity_N(t)  # the same floats as position_N, velocity_N
        n = frames.orbit_rate(r, v)
        y_N = frames.orbit_axes_N(r, v)[1]
        wo = rotate_n_to_b(self.q_BN, (-n * y_N[0], -n * y_N[1], -n * y_N[2]))
        w = self.omega_BN_B
        return (w[0] - wo[0], w[1] - wo[1], w[2] - wo[2])

    def orbit_relative(self) -> tuple[Quat, Vec3]:
        """``(q_BO, omega_BO_B)`` together, the orbit's position, velocity and O's axes computed once:
        the same floats as the two properties (the same functions of the same state and time)."""
        t = self._t_ns / 1e9
        r, v = self.orbit.position_velocity_N(t)
        axes = frames.orbit_axes_N(r, v)
        q_bn = self._state[0:4]
        q_bo = frames.q_BO(q_bn, frames.dcm_to_quat(axes))
        n = frames.orbit_rate(r, v)
        y_N = axes[1]
        wo = rotate_n_to_b(q_bn, (-n * y_N[0], -n * y_N[1], -n * y_N[2]))
        s = self._state
        return q_bo, (s[4] - wo[0], s[5] - wo[1], s[6] - wo[2])

    def ephemeris(self) -> Ephemeris:
        """Where the spacecraft is now (truth): position and velocity in N, the Earth rotation angle (the field
        model's), the Sun's direction (``sim.sun``, from the scenario epoch) — what an on-board ephemeris knows."""
        t = self.t
        sc = self.scenario
        if self._ephemeris_epoch is None:
            self._ephemeris_epoch = (sc.earth_angle0_rad, julian_date(sc.epoch))
        theta0, jd0 = self._ephemeris_epoch
        r, v = self.orbit.position_velocity_N(t)
        sun, _ = sun_direction_N(jd0 + t / 86400.0)
        return Ephemeris(r, v, theta0 + sc.field.earth_rotation_rate_rad_s * t, sun)

    def set_pointing_target(self, q_target: Quat | None, frame: str = "inertial") -> None:
        """Hook for a controller: the attitude it is steering to (``q_TN``, or ``q_TO`` with
        ``frame="orbit"``), logged as the pointing error. ``None`` clears it. Truth only."""
        if q_target is None:
            self._target = None
            return
        if frame not in ("inertial", "orbit"):
            raise ValueError(f"target frame must be 'inertial' or 'orbit', got {frame!r}")
        q = [float(x) for x in q_target]
        if len(q) != 4:
            raise ValueError(f"target quaternion must have 4 components (scalar first), got {len(q)}")
        self._target = (quat_normalize((q[0], q[1], q[2], q[3])), frame)

    @property
    def pointing_target(self) -> tuple[Quat, str] | None:
        return self._target

    def pointing_error_rad(self) -> float | None:
        """Angle between the attitude and the current target (rad), or None without a target."""
        if self._target is None:
            return None
        q_t, frame = self._target
        if frame == "orbit":
            q_t = frames.q_BN_from_orbit(q_t, self.q_ON)
        return frames.attitude_error_rad(self.q_BN, q_t)
