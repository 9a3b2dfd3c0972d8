"""The controller's use of the on-board field model: MAG_BIAS_TIME's magnetometer-bias estimate and MAG_LQR_ANGLE's
hold scheduled on the model (ADCS-190…196). A hand-made io: the star tracker's fix, a still gyro, the reading the
on-board dipole gives at the ephemeris' position turned into B, plus a bias."""

from __future__ import annotations

import math

import pytest

from detumble.control import three_mode
from detumble.control.geomagnetic import dipole_field_N
from detumble.control.magnetic_lqr import hold_gain_table, lqr_dipole_B
from detumble.control.magnetic_pointing import field_steering_torque
from detumble.control.quaternion import quat_angle, quat_error, quat_from_axis_angle, quat_mul, rotate_n_to_b
from detumble.control.targets import Ephemeris
from detumble.control.three_mode import POINTING, Quiet, ThreeModeLaw
from detumble.control.units import TESLA_PER_GAUSS

R_N = (6.791e6, 0.0, 0.0)
V_N = (0.0, 7661.0 * math.cos(0.9), 7661.0 * math.sin(0.9))
EARTH = 0.3
TARGET = quat_from_axis_angle((0.0, 1.0, 0.0), math.radians(45.0))


class _Io:
    """A spacecraft at rest at the attitude ``q`` in the on-board model's field, read with ``bias_g`` (gauss)."""

    def __init__(self, q, bias_g) -> None:
        self.q, self.bias_g, self.t_us, self.eph_ok, self.bad_velocity = q, bias_g, 0, True, False

    def model_b(self):
        return rotate_n_to_b(self.q, dipole_field_N(R_N, EARTH))

    def now_us(self):
        return self.t_us

    def gyro(self):
        return (0.0, 0.0, 0.0)

    def attitude(self):
        return self.q, self.t_us

    def field(self):
        b = self.model_b()
        return tuple(b[i] / TESLA_PER_GAUSS + self.bias_g[i] for i in range(3)), self.t_us

    def wheel_count(self):
        return 0

    def wheel_momenta(self):
        return None

    def drive_coils(self, levels, dipole_b):
        pass

    def stop_coils(self):
        pass

    def set_wheel_torques(self, torques):
        return tuple(0.0 for _ in torques)

    def ephemeris(self):
        v = (7661.0, 0.0, 0.0) if self.bad_velocity else V_N  # along R_N: no orbit plane
        return Ephemeris(R_N, v, EARTH, (1.0, 0.0, 0.0)) if self.eph_ok else None

    def has_sun_sensor(self):
        return False

    def sun_vector(self):
        return None

    def system_safe_mode(self):
        return None


class _NoProvider:
    def has_dipole_provider(self):
        return False

    def provider_dipole(self):
        return None


# This world's field is the on-board tilted dipole: the tests fly degree 1 on board, and the estimate and the
# scheduled hold only where a test turns them on (the defaults since 2026-12-05 are 1 s, 50°, degree 6).
_THIS_WORLD = {"MAG_FIELD_MODEL_DEGREE": 1.0, "MAG_BIAS_TIME": 0.0, "MAG_LQR_ANGLE": 0.0}


def _law(q, bias_g, io_class=None, **params):
    io = (io_class or _Io)(q, bias_g)
    law = ThreeModeLaw(io, Quiet(), _NoProvider(), params={"ESTIMATOR": "COMPLEMENTARY", **_THIS_WORLD, **params})
    return io, law


def _cycles(io, law, n):
    """``n`` control cycles (CYCLE_TICKS ticks of 20 ms each)."""
    for _ in range(n * law.cycle_ticks):
        io.t_us += 20000
        law.tick()


def test_bias_estimate_converges_at_its_time_constant():
    """ADCS-190: MAG_BIAS_TIME 0: the controller's field is the reading. 20 s: from the first cycle it is
    the model's (the estimate starts at the reading less the model), and after a step Δ of the bias it moves by
    ``(1 − (1 − dt/τ)ⁿ) Δ`` in n cycles (the discrete low-pass, 1e-9 relative); without an ephemeris the estimate is
    held and still subtracted."""
    q = quat_from_axis_angle((0.3, 0.4, 0.866), 0.7)
    bias = (0.012, -0.008, 0.005)
    io, law = _law(q, bias)
    _cycles(io, law, 3)
    assert law.b_tesla == pytest.approx(tuple((io.model_b()[i] + bias[i] * TESLA_PER_GAUSS) for i in range(3)),
                                        rel=1e-12)
    io, law = _law(q, bias, MAG_BIAS_TIME=20.0)
    _cycles(io, law, 3)
    model = io.model_b()
    assert law.b_tesla == pytest.approx(model, abs=1e-6 * math.hypot(*model))
    est0 = law.mag_bias_T
    step = (0.004, 0.002, -0.006)
    io.bias_g = tuple(bias[i] + step[i] for i in range(3))
    dt = law.cycle_ticks * 0.02
    n = 100
    _cycles(io, law, n)
    share = 1.0 - (1.0 - dt / 20.0) ** n
    for i in range(3):
        assert law.mag_bias_T[i] - est0[i] == pytest.approx(share * step[i] * TESLA_PER_GAUSS, rel=1e-6)
    held = law.mag_bias_T
    io.eph_ok = False
    _cycles(io, law, 10)
    assert law.mag_bias_T == held
    reading = io.field()[0]
    assert law.b_tesla == pytest.approx(tuple(reading[i] * TESLA_PER_GAUSS - held[i] for i in range(3)), rel=1e-12)


class _IoWithWheels(_Io):
    """The same spacecraft with three wheels at rest, answering unless ``wheels_answer`` is False."""

    wheels_answer = True

    def wheel_count(self):
        return 3

    def wheel_momenta(self):
        return (0.0, 0.0, 0.0) if self.wheels_answer else None


def test_bias_estimate_serves_the_coils_alone():
    """ADCS-197: the defaults are issue 27's hold (MAG_BIAS_TIME 1 s, MAG_LQR_ANGLE 50°, MAG_FIELD_MODEL_DEGREE 6),
    and the bias estimate serves the coils alone: with POINTING_ACTUATOR ANY and every wheel answering the
    controller's field is the reading as it is (no estimate made), with MAGNETORQUERS it is corrected (here to the
    model's own field, the bias gone), and under ANY it is corrected from the first cycle a wheel stops answering."""
    law = ThreeModeLaw(_Io((1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0)), Quiet(), _NoProvider())
    assert (law.MAG_BIAS_TIME, law.MAG_LQR_ANGLE, law.MAG_FIELD_MODEL_DEGREE) == (1.0, 50.0, 6.0)
    q = quat_from_axis_angle((0.3, 0.4, 0.866), 0.7)
    bias = (0.012, -0.008, 0.005)

    def reading_T(io):
        return tuple(io.field()[0][i] * TESLA_PER_GAUSS for i in range(3))

    io, law = _law(q, bias, _IoWithWheels, MAG_BIAS_TIME=1.0)
    _cycles(io, law, 5)
    assert law.b_tesla == reading_T(io)
    assert law.mag_bias_T is None
    io.wheels_answer = False
    _cycles(io, law, 1)
    model = io.model_b()
    assert law.b_tesla == pytest.approx(model, abs=1e-9 * math.hypot(*model))
    io, law = _law(q, bias, _IoWithWheels, MAG_BIAS_TIME=1.0, POINTING_ACTUATOR="MAGNETORQUERS")
    _cycles(io, law, 5)
    assert law.b_tesla == pytest.approx(model, abs=1e-9 * math.hypot(*model))


def _pointing(error_deg, **params):
    q = quat_mul(TARGET, quat_from_axis_angle((0.6, 0.0, 0.8), math.radians(error_deg)))
    io, law = _law(q, (0.0, 0.0, 0.0), POINTING_ACTUATOR="MAGNETORQUERS", MAG_SETTLE_TIME=0.0, **params)
    _cycles(io, law, 2)
    assert law.set_target_quaternion(TARGET) == "OK"
    assert law.force_mode(POINTING) == "OK"
    _cycles(io, law, 2)
    return io, law


def test_model_lqr_hold_below_its_angle():
    """ADCS-191: MAG_LQR_ANGLE 40° on an inertial target at 20° of error: once its table is built (over cycles), the
    torque request is ``m × b`` for the LQR dipole of a table computed from the ephemeris at the table's time (the
    on-board model along the orbit), which is not the field-steering law's; at 50° (above the angle) and with
    MAG_LQR_ANGLE 0 it is field steering."""
    io, law = _pointing(20.0, MAG_LQR_ANGLE=40.0)
    _cycles(io, law, 1100)  # an orbit's table: 31,888 work units at MAG_LQR_BUDGET_UNITS a cycle
    table = law._lqr_table
    assert table is not None and table.q_tn == TARGET
    duty = law.duty
    inertia = tuple(tuple(x / duty for x in row) for row in law.rate_observer.inertia)
    fresh = hold_gain_table(TARGET, table.t0_s, R_N, V_N, EARTH, inertia, law.coil_limits(), three_mode.MAG_LQR_STEP_S,
                            three_mode.MAG_LQR_USE_S, three_mode.MAG_LQR_EXTRA_S, three_mode.MAG_LQR_THETA_SCALE,
                            three_mode.MAG_LQR_RATE_SCALE, three_mode.MAG_LQR_R_WEIGHT, three_mode.MAG_LQR_ALPHA)
    q, w = law.filter.q, law.omega
    qe = quat_error(TARGET, q)
    assert math.degrees(quat_angle(qe)) == pytest.approx(20.0, abs=0.1)
    m = lqr_dipole_B(fresh.gain(io.t_us / 1e6 - law.cycle_ticks * 0.02), qe, w)
    b = law.b_tesla
    expected = (m[1] * b[2] - m[2] * b[1], m[2] * b[0] - m[0] * b[2], m[0] * b[1] - m[1] * b[0])
    got = law.torque_request
    assert got == pytest.approx(expected, rel=1e-9, abs=1e-18)
    steer, _ = field_steering_torque(TARGET, q, w, b, law.bdot_hat_B or (0.0, 0.0, 0.0), law.K_P_MAG, law.K_D_MAG,
                                     law.MAG_STEER_RHO, law.MAG_STEER_ZETA, law.MAG_FIELD_RATE_MIN)
    assert max(abs(a - s) for a, s in zip(got, steer, strict=True)) > 1e-3 * max(abs(s) for s in steer)
    for error, angle in ((50.0, 40.0), (20.0, 0.0)):
        io, law = _pointing(error, MAG_LQR_ANGLE=angle)
        assert law._lqr_table is None
        steer, _ = field_steering_torque(TARGET, law.filter.q, law.omega, law.b_tesla,
                                         law.bdot_hat_B or (0.0, 0.0, 0.0), law.K_P_MAG, law.K_D_MAG,
                                         law.MAG_STEER_RHO, law.MAG_STEER_ZETA, law.MAG_FIELD_RATE_MIN)
        assert law.torque_request == pytest.approx(steer, rel=1e-12, abs=1e-20)


def test_model_lqr_needs_an_ephemeris_for_its_table():
    """ADCS-192: without an ephemeris no table can be computed, and the hold is field steering."""
    q = quat_mul(TARGET, quat_from_axis_angle((0.6, 0.0, 0.8), math.radians(20.0)))
    io, law = _law(q, (0.0, 0.0, 0.0), POINTING_ACTUATOR="MAGNETORQUERS", MAG_SETTLE_TIME=0.0, MAG_LQR_ANGLE=40.0)
    io.eph_ok = False
    _cycles(io, law, 2)
    assert law.set_target_quaternion(TARGET) == "OK"
    assert law.force_mode(POINTING) == "OK"
    _cycles(io, law, 2)
    assert law._lqr_table is None
    steer, _ = field_steering_torque(TARGET, law.filter.q, law.omega, law.b_tesla, law.bdot_hat_B or (0.0, 0.0, 0.0),
                                     law.K_P_MAG, law.K_D_MAG, law.MAG_STEER_RHO, law.MAG_STEER_ZETA,
                                     law.MAG_FIELD_RATE_MIN)
    assert law.torque_request == pytest.approx(steer, rel=1e-12, abs=1e-20)


def test_bias_estimate_uses_the_model_of_its_degree():
    """ADCS-193: with MAG_FIELD_MODEL_DEGREE 8 the bias estimate is taken against IGRF-14 of degree 8
    (``geomagnetic.OnboardField(8)``), not the dipole: the controller's field is that model turned into B."""
    from detumble.control.geomagnetic import OnboardField

    q = quat_from_axis_angle((0.3, 0.4, 0.866), 0.7)
    io, law = _law(q, (0.012, -0.008, 0.005), MAG_BIAS_TIME=20.0, MAG_FIELD_MODEL_DEGREE=8.0)
    _cycles(io, law, 3)
    model = rotate_n_to_b(q, OnboardField(8)(R_N, EARTH))
    assert law.b_tesla == pytest.approx(model, abs=1e-6 * math.hypot(*model))
    assert math.dist(law.b_tesla, io.model_b()) > 1e-3 * math.hypot(*model)


class _Events(Quiet):
    """A :class:`Notify` that keeps the events (name, args) and the cleared names."""

    def __init__(self) -> None:
        self.events: list[tuple] = []
        self.cleared: list[str] = []

    def event(self, name, *args):
        self.events.append((name, *args))

    def clear_event(self, name):
        self.cleared.append(name)


def _pointing_logged(error_deg, target=TARGET, **params):
    """As :func:`_pointing` with an :class:`_Events` notify; returns ``(io, law, notify)``."""
    q = quat_mul(target, quat_from_axis_angle((0.6, 0.0, 0.8), math.radians(error_deg)))
    io = _Io(q, (0.0, 0.0, 0.0))
    notify = _Events()
    law = ThreeModeLaw(io, notify, _NoProvider(), params={"ESTIMATOR": "COMPLEMENTARY", **_THIS_WORLD,
                                                          "POINTING_ACTUATOR": "MAGNETORQUERS",
                                                          "MAG_SETTLE_TIME": 0.0, **params})
    _cycles(io, law, 2)
    assert law.set_target_quaternion(target) == "OK"
    assert law.force_mode(POINTING) == "OK"
    return io, law, notify


def _steering(law):
    tau, _ = field_steering_torque(law.target, law.filter.q, law.omega, law.b_tesla, law.bdot_hat_B or (0.0, 0.0, 0.0),
                                   law.K_P_MAG, law.K_D_MAG, law.MAG_STEER_RHO, law.MAG_STEER_ZETA,
                                   law.MAG_FIELD_RATE_MIN)
    return tau


def _is_steering(law) -> bool:
    steer = _steering(law)
    return law.torque_request == pytest.approx(steer, rel=1e-12, abs=1e-20)


def test_gain_table_is_built_over_cycles_within_the_budget():
    """ADCS-194: an orbit's gain table (7,972 samples and Riccati steps) is built over control cycles, never more than
    MAG_LQR_BUDGET_UNITS work units in one, from the first POINTING cycle even above MAG_LQR_ANGLE (50°); at 20° the
    law is field steering until the table is ready, in the cycle its last unit is done, and the LQR hold from then."""
    budget = three_mode.MAG_LQR_BUDGET_UNITS
    io, law, _ = _pointing_logged(50.0, MAG_LQR_ANGLE=40.0)
    _cycles(io, law, 20)
    assert law.lqr_work_units == 20 * budget and law._lqr_table is None
    io, law, _ = _pointing_logged(20.0, MAG_LQR_ANGLE=40.0)
    total = 0
    cycles = 0
    while law._lqr_table is None:
        before = law.lqr_work_units
        _cycles(io, law, 1)
        cycles += 1
        done = law.lqr_work_units - before
        assert 0 < done <= budget
        total += done
        if law._lqr_table is None:
            assert _is_steering(law), cycles
        assert cycles < 2000
    n = math.ceil((three_mode.MAG_LQR_USE_S + three_mode.MAG_LQR_EXTRA_S) / three_mode.MAG_LQR_STEP_S)
    assert total == n * 4  # a sample 1 unit, a step 3
    assert cycles == math.ceil(total / budget)
    assert not _is_steering(law)  # the table's first cycle already holds on it
    _cycles(io, law, 5)
    assert law.lqr_work_units == total and not _is_steering(law)  # nothing more to build


def test_gain_table_renewed_without_a_gap_and_rebuilt_on_a_target_change(monkeypatch):
    """ADCS-195: with a 70 s table (70 s more of horizon), the next table is started before the one in use runs out
    (its time left below the last build's time plus MAG_LQR_RENEW_MARGIN_S) and taken when ready: over 200 s the hold
    has a gain at every cycle once the first table is ready, within the budget every cycle. A target change abandons
    the build under way: the new target's table takes a whole build from the change, and the old target's table is
    not used meanwhile (field steering)."""
    monkeypatch.setattr(three_mode, "MAG_LQR_USE_S", 70.0)
    monkeypatch.setattr(three_mode, "MAG_LQR_EXTRA_S", 70.0)
    monkeypatch.setattr(three_mode, "MAG_LQR_RENEW_MARGIN_S", 5.0)
    budget = three_mode.MAG_LQR_BUDGET_UNITS
    build_cycles = math.ceil(100 * 4 / budget)  # 100 samples and steps
    io, law, _ = _pointing_logged(20.0, MAG_LQR_ANGLE=40.0)
    _cycles(io, law, build_cycles)
    first = law._lqr_table
    assert first is not None and not _is_steering(law)
    starts = {first.t0_s}
    for _ in range(2000):  # 200 s
        before = law.lqr_work_units
        _cycles(io, law, 1)
        assert law.lqr_work_units - before <= budget
        table = law._lqr_table
        starts.add(table.t0_s)
        assert table.gain(law.last_cycle_us / 1e6) is not None
        assert not _is_steering(law)
    assert len(starts) >= 3  # renewed at least twice in 200 s of 70 s tables
    # a target change in the middle of a build
    _cycles(io, law, 1)
    while law._lqr_builder is None:
        _cycles(io, law, 1)
    _cycles(io, law, 3)
    old_table = law._lqr_table
    new_target = quat_mul(TARGET, quat_from_axis_angle((0.0, 0.0, 1.0), math.radians(10.0)))
    assert law.set_target_quaternion(new_target) == "OK"
    cycles = 0
    while law._lqr_table is old_table:
        _cycles(io, law, 1)
        cycles += 1
        if law._lqr_table is old_table:
            assert _is_steering(law)
        assert cycles < 100
    assert law._lqr_table.q_tn == new_target
    assert cycles == build_cycles
    assert not _is_steering(law)


def test_failed_gain_table_gives_an_event_and_waits_before_trying_again():
    """ADCS-196: an ephemeris without an orbit plane (v along r) fails the build: one MagLqrTableFailed(reason,
    MAG_LQR_RETRY_S), field steering, and no new attempt for MAG_LQR_RETRY_S (no work, no event) — then one; once the
    ephemeris is good again the next attempt builds the table and clears the event's throttle."""
    io, law, notify = _pointing_logged(20.0, MAG_LQR_ANGLE=40.0)
    io.bad_velocity = True
    _cycles(io, law, 1)
    failed = [e for e in notify.events if e[0] == "MagLqrTableFailed"]
    assert failed == [("MagLqrTableFailed", "no orbit plane: r × v is zero", three_mode.MAG_LQR_RETRY_S)]
    retry_cycles = round(three_mode.MAG_LQR_RETRY_S / 0.1)
    work = law.lqr_work_units
    for _ in range(retry_cycles - 1):
        _cycles(io, law, 1)
        assert _is_steering(law)
    assert law.lqr_work_units == work
    assert len([e for e in notify.events if e[0] == "MagLqrTableFailed"]) == 1
    _cycles(io, law, 2)
    assert len([e for e in notify.events if e[0] == "MagLqrTableFailed"]) == 2
    io.bad_velocity = False
    _cycles(io, law, retry_cycles + 1100)
    assert law._lqr_table is not None and not _is_steering(law)
    assert "MagLqrTableFailed" in notify.cleared
    assert len([e for e in notify.events if e[0] == "MagLqrTableFailed"]) == 2
