"""Model-aided rate observer (rad/s, N·m, kg·m², s)."""

import math
import random

import pytest

from detumble.control.rate_observer import RateObserver

MOMENTS = (2.2e-3, 2.15e-3, 2.05e-3)


def test_exact_model_tracks_a_constant_torque_spin_up_without_error():
    """RATE-001: about a principal axis under a constant torque the true rate is ω0 + τ t / I (closed form); fed
    the interval means of that rate (the rate at each interval's middle), the observer's estimate at every cycle
    equals the truth within 1e-12 rad/s whatever its gain."""
    tau, dt = (0.0, 0.0, 1e-3), 0.1
    for gain in (0.01, 0.2, 5.0):
        obs = RateObserver(MOMENTS, gain)
        obs.reset((0.0, 0.0, 0.01))
        for k in range(1, 301):
            w_mid = 0.01 + tau[2] / MOMENTS[2] * (k - 0.5) * dt
            est = obs.update((0.0, 0.0, w_mid), tau, (0.0, 0.0, 0.0), dt)
            assert est[2] == pytest.approx(0.01 + tau[2] / MOMENTS[2] * k * dt, abs=1e-12)
            assert est[0] == 0.0 and est[1] == 0.0


def test_white_gyro_noise_is_reduced_as_a_first_order_filter_predicts():
    """RATE-002: at rest with white gyro noise σ per cycle mean the estimate's std is σ √(k/(2−k)),
    k = 1 − e^(−L Δt) (the closed form of a first-order discrete filter), within 5 % over 200 000 cycles."""
    rng = random.Random(11)
    gain, dt, sigma = 0.2, 0.1, 1e-4
    obs = RateObserver(MOMENTS, gain)
    obs.reset((0.0, 0.0, 0.0))
    acc, n = 0.0, 200_000
    for _ in range(n):
        est = obs.update((rng.gauss(0, sigma), 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), dt)
        acc += est[0] ** 2
    k = 1 - math.exp(-gain * dt)
    assert math.sqrt(acc / n) == pytest.approx(sigma * math.sqrt(k / (2 - k)), rel=0.05)


def test_gyroscopic_coupling_with_wheel_momentum():
    """RATE-003: with no torque and wheel momentum h along z, a body rate ωx drives ω̇y = −(ω × (Iω + h))_y / I_y
    = ωx (I_z ω_z + h_z)/I_y … checked against the formula for one step at zero gain-limited pull."""
    obs = RateObserver(MOMENTS, 1e-4)
    w0 = (0.01, 0.0, 0.0)
    obs.reset(w0)
    h = (0.0, 0.0, 2e-3)
    dt = 0.1
    est = obs.update(w0, (0.0, 0.0, 0.0), h, dt)
    hx, hz = MOMENTS[0] * w0[0] + h[0], MOMENTS[2] * w0[2] + h[2]
    gy = w0[2] * hx - w0[0] * hz
    k = 1 - math.exp(-1e-4 * dt)
    assert est[1] == pytest.approx(-gy / MOMENTS[1] * dt * (1 - k / 2), rel=1e-9)


@pytest.mark.parametrize("inertia, gain, match", [((0.0, 1.0, 1.0), 1.0, "inertia"), (MOMENTS, -1.0, "gain")])
def test_bad_model_is_refused(inertia, gain, match):
    """RATE-004: a non-positive moment or gain is a clear error naming it."""
    with pytest.raises(ValueError, match=match):
        RateObserver(inertia, gain)


def test_a_new_model_is_taken_however_it_is_given():
    """RATE-004: ``set_model`` skips the work only for the model it already has: new moments (tuples), a new gain,
    and a list that was changed in place since the last call are all taken; the same numbers again change nothing."""
    obs = RateObserver(MOMENTS, 0.1)
    obs.set_model((2.0e-3, 2.0e-3, 2.0e-3), 0.1)
    assert obs.inertia[0][0] == 2.0e-3 and obs.inertia_inv[0][0] == pytest.approx(500.0)
    obs.set_model((2.0e-3, 2.0e-3, 2.0e-3), 0.3)
    assert obs.gain == 0.3
    rows = [[3.0e-3, 0.0, 0.0], [0.0, 3.0e-3, 0.0], [0.0, 0.0, 3.0e-3]]
    obs.set_model(rows, 0.3)
    assert obs.inertia[2][2] == 3.0e-3
    rows[2][2] = 4.0e-3  # the caller's own list, changed in place
    obs.set_model(rows, 0.3)
    assert obs.inertia[2][2] == 4.0e-3 and obs.inertia_inv[2][2] == pytest.approx(250.0)
    before = obs.inertia_inv
    obs.set_model(((3.0e-3, 0.0, 0.0), (0.0, 3.0e-3, 0.0), (0.0, 0.0, 4.0e-3)), 0.3)
    assert obs.inertia_inv is before  # the model it has: nothing recomputed


def test_applied_torque_is_the_wheels_reaction_plus_the_coils_over_their_duty():
    """RATE-005: the observer's torque input: −Σ u_i g_i of the wheels plus (m × B)·duty of the coils; without a
    known field only the wheels' part; no wheel command yet (an empty tuple) counts as none."""
    from detumble.control.rate_observer import applied_torque

    axes = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    m, b = (0.1, 0.0, 0.0), (0.0, 2e-5, 0.0)  # m × B = (0, 0, 2e-6) N·m
    assert applied_torque((1e-4, -2e-4, 0.0), axes, m, b, 0.8) == pytest.approx((-1e-4, 2e-4, 1.6e-6), abs=1e-18)
    assert applied_torque((1e-4, -2e-4, 0.0), axes, m, None, 0.8) == (-1e-4, 2e-4, 0.0)
    assert applied_torque((), axes, m, b, 1.0) == pytest.approx((0.0, 0.0, 2e-6), abs=1e-18)


def test_an_inertia_error_leaves_a_rate_lag_of_delta_a_over_the_pull():
    """RATE-006 (issue 27): with the true inertia 10 % above the model a constant torque makes the model predict
    10 % too much acceleration; the estimate then runs ahead of the truth by the discrete loop's fixed point
    ``e = (a_m − a) Δt (1 − k/2) / k`` (k = 1 − e^(−L Δt); ≈ (a_m − a)/L), to 1e-3 after 10/L s. The slew's pull
    (``gain_per_s`` = RATE_BLEND_GAIN, 2/s) makes it 20× smaller than the hold's 0.1/s."""
    tau, dt = 1e-3, 0.1
    a_true, a_model = tau / (1.1 * MOMENTS[2]), tau / MOMENTS[2]
    errors = {}
    for gain in (0.1, 2.0):
        obs = RateObserver(MOMENTS, 0.1)
        obs.reset((0.0, 0.0, 0.0))
        steps = int(round(10.0 / gain / dt))
        for k in range(1, steps + 1):
            est = obs.update((0.0, 0.0, a_true * (k - 0.5) * dt), (0.0, 0.0, tau), (0.0, 0.0, 0.0), dt,
                             None if gain == 0.1 else gain)
        errors[gain] = est[2] - a_true * steps * dt
        pull = 1.0 - math.exp(-gain * dt)
        assert errors[gain] == pytest.approx((a_model - a_true) * dt * (1 - pull / 2) / pull, rel=1e-3)
    assert errors[0.1] / errors[2.0] == pytest.approx(20.0, rel=0.02)


# --- the residual dipole learned by the observer (RATE_OBSERVER_DIPOLE_TIME; docs/studies/robust_rates.md) -------

_M_TRUE = (1.0e-3, -5.0e-4, 8.0e-4)  # A·m², B: the adcs scenario's residual dipole
#: kg·m²: equal moments, so that the body's own gyroscopic torque ω × I ω is zero and the rate's closed form exact
SPHERE = (2.2e-3, 2.2e-3, 2.2e-3)


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _hold(obs, b, steps, learn_time_s, dt=0.1, w0=(0.0, 0.0, 0.0), rng=None, sigma=0.0):
    """``steps`` cycles of a body of equal moments (SPHERE: no gyroscopic torque) under the dipole's torque
    ``_M_TRUE × b`` alone (no command), its rate growing as ``ω0 + d t / I``;
    the observer fed the interval means (+ white noise σ), learning with ``learn_time_s`` (0: not learning).
    Returns the true rate now."""
    d = _cross(_M_TRUE, b)
    w = list(w0)
    for _ in range(steps):
        mid = [w[i] + d[i] / SPHERE[i] * dt / 2 for i in range(3)]
        meas = tuple(mid[i] + (rng.gauss(0.0, sigma) if rng else 0.0) for i in range(3))
        if learn_time_s:
            obs.learn_dipole(meas, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), b, dt, learn_time_s)
        obs.update(meas, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), dt, None, b)
        w = [w[i] + d[i] / SPHERE[i] * dt for i in range(3)]
    return w


def test_the_learned_dipole_removes_the_observers_rate_error():
    """ADCS-170: under a constant unmodelled torque ``d = m × B`` the observer alone keeps the rate error
    ``d/(I L)`` per axis (RATE-006's lag, here the issue's mechanism 2); learning the dipole (a fading least-squares
    slope of the unexplained momentum) gives, noise-free, the part of ``m`` ⟂ B to 1e-6 once one time constant has
    passed, keeps the part along B it cannot see (0), and with ``m̂ × B`` in its model the rate error falls below
    1 % of that lag within 100 s."""
    b = (2.0e-5, -3.0e-5, 1.5e-5)
    gain = 0.1
    d = _cross(_M_TRUE, b)
    lag = [d[i] / (SPHERE[i] * gain) for i in range(3)]
    plain = RateObserver(SPHERE, gain)
    plain.reset((0.0, 0.0, 0.0))
    w = _hold(plain, b, 3000, 0.0)
    for i in range(3):
        assert w[i] - plain.omega[i] == pytest.approx(lag[i], rel=0.02)
    learner = RateObserver(SPHERE, gain)
    learner.reset((0.0, 0.0, 0.0))
    w = _hold(learner, b, 1000, 20.0)
    b2 = sum(x * x for x in b)
    along = sum(_M_TRUE[i] * b[i] for i in range(3)) / b2
    m_perp = [_M_TRUE[i] - along * b[i] for i in range(3)]
    for i in range(3):
        assert learner.dipole[i] == pytest.approx(m_perp[i], abs=1e-6 * max(map(abs, _M_TRUE)))
        assert abs(w[i] - learner.omega[i]) < 0.01 * max(map(abs, lag))
    assert sum(learner.dipole[i] * b[i] for i in range(3)) == pytest.approx(0.0, abs=1e-12)


def test_the_dipole_is_kept_through_a_slew_and_completed_when_the_field_turns():
    """ADCS-171: a body-fixed dipole learned in one field direction (B along z: only m_x, m_y learned) is kept while
    not calm (``skip_dipole``: a slew) and after it until the new calm stretch is one time constant long; in a field
    along x the stretch then learns m_z and keeps m_y (⟂ both fields: learned twice, unchanged) and m_x (along the
    new field): all three of m to 1e-6."""
    obs = RateObserver(SPHERE, 0.1)
    obs.reset((0.0, 0.0, 0.0))
    w = _hold(obs, (0.0, 0.0, 3.0e-5), 500, 20.0)
    first = obs.dipole
    assert first[0] == pytest.approx(_M_TRUE[0], abs=1e-9) and first[1] == pytest.approx(_M_TRUE[1], abs=1e-9)
    assert first[2] == 0.0
    obs.skip_dipole()  # the slew: nothing learned across it
    w = _hold(obs, (3.0e-5, 0.0, 0.0), 150, 20.0, w0=w)  # 15 s: the new stretch is younger than 20 s
    assert obs.dipole == first
    _hold(obs, (3.0e-5, 0.0, 0.0), 400, 20.0, w0=w)
    for i in range(3):
        assert obs.dipole[i] == pytest.approx(_M_TRUE[i], abs=1e-9)


def test_the_learned_dipoles_noise_is_the_fading_fits_closed_form():
    """ADCS-172: at rest with no torque and white gyro noise σ per cycle mean, the fitted slope of the unexplained
    momentum ``p = I ω_meas`` (white noise ``I σ``) with weights ``e^(−age/T)`` has, long after the start, the
    standard deviation ``I σ √Δt / (2 T^1.5)`` per axis (weighted least squares: ``s² Σw²(t−t̄)² / (Σw(t−t̄)²)²``
    with the exponential's moments): the dipole's torque ``m̂ × B`` (B along z: the x and y axes) sampled every
    10 T over 4000 T matches it within 12 %."""
    rng = random.Random(5)
    sigma, dt, time_s = 2.65e-4, 0.1, 5.0
    b = (0.0, 0.0, 3.0e-5)
    obs = RateObserver(MOMENTS, 0.1)
    obs.reset((0.0, 0.0, 0.0))
    samples_x, samples_y = [], []
    for k in range(int(4000 * time_s / dt)):
        meas = (rng.gauss(0.0, sigma), rng.gauss(0.0, sigma), rng.gauss(0.0, sigma))
        obs.learn_dipole(meas, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), b, dt, time_s)
        obs.omega = (0.0, 0.0, 0.0)  # no gyroscopic term: the fit alone
        if k % int(10 * time_s / dt) == 0 and k * dt > 10 * time_s:
            torque = _cross(obs.dipole, b)
            samples_x.append(torque[0])
            samples_y.append(torque[1])
    for axis, samples in ((0, samples_x), (1, samples_y)):
        std = math.sqrt(sum(x * x for x in samples) / len(samples))
        assert std == pytest.approx(MOMENTS[axis] * sigma * math.sqrt(dt) / (2 * time_s ** 1.5), rel=0.12)
