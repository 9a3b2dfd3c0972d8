"""MEKF (attitude + gyro bias): consistency, convergence, covariance health, and a comparison with the
complementary filter, flown on the plant's own sensor models (LSM6DSO gyro, star tracker) read the way the
AttitudeController reads them (gyro every 20 ms, a 10 Hz cycle on the mean of five readings, the tracker's
held 5 Hz solution with its age)."""

import math

import pytest

from detumble.control.attitude_filter import AttitudeFilter
from detumble.control.mekf import Mekf
from detumble.control.quaternion import quat_conj, quat_mul, quat_shortest
from detumble.sim.attitude import RigidBody
from detumble.sim.sensors import Gyro, GyroSpec
from detumble.sim.star_tracker import ARCSEC, StarTracker, StarTrackerSpec

GYRO = GyroSpec(bias_dps=(0.3, -0.2, 0.1), full_scale_dps=2000.0)  # the adcs scenario's LSM6DSO
TRACKER = StarTrackerSpec()  # 10″ across, 70″ about +Z, 5 Hz
#: one reading's noise: the density over the output bandwidth plus the 70 mdps quantisation, as the controller's
#: default GYRO_NOISE (docs/components/attitude_controller.md)
SIGMA_G = math.radians(math.hypot(GYRO.noise_std_dps, GYRO.lsb_dps / math.sqrt(12.0)))
BIAS = tuple(math.radians(b) for b in GYRO.bias_dps)
CYCLE_S, TICK_S = 0.1, 0.02


def make_mekf(**kw):
    args = dict(gyro_noise_rad_s=SIGMA_G, bias_walk_rad_s_rt_s=math.radians(1e-4),
                tracker_cross_rad=10 * ARCSEC, tracker_about_rad=70 * ARCSEC)
    args.update(kw)
    return Mekf(**args)


def small_error(q_true, q_est):
    """δθ with q_true = q_est ⊗ (1, δθ/2), rad, B."""
    e = quat_shortest(quat_mul(quat_conj(q_est), q_true))
    return (2 * e[1], 2 * e[2], 2 * e[3])


def fly(filters, duration_s, *, seed=3, rate_deg_s=(0.2, -0.1, 0.3), gyro_spec=GYRO, on_cycle=None):
    """Truth on RK4 (torque-free, 20 ms steps); the sensors latched from the truth; each filter updated every
    100 ms. ``on_cycle(t, state, filters)`` sees every cycle."""
    body = RigidBody(((2.2e-3, 2e-5, -1.5e-5), (2e-5, 2.15e-3, 1e-5), (-1.5e-5, 1e-5, 2.05e-3)))
    gyro, tracker = Gyro(gyro_spec, seed=seed), StarTracker(TRACKER, seed=seed + 100)
    state = (1.0, 0.0, 0.0, 0.0) + tuple(math.radians(w) for w in rate_deg_s)
    t_ns, acc, count, last_stamp = 0, [0.0, 0.0, 0.0], 0, None
    ticks = round(duration_s / TICK_S)
    for k in range(1, ticks + 1):
        new = body.step(state, TICK_S)
        t1 = t_ns + round(TICK_S * 1e9)
        gyro.latch(t_ns, t1, state[4:7], new[4:7])
        tracker.latch(t_ns, t1, state, new)
        state, t_ns = new, t1
        g = gyro.sample_rad_s
        acc = [a + x for a, x in zip(acc, g, strict=True)]
        count += 1
        if k % 5:
            continue
        mean = tuple(a / count for a in acc)
        q_m, age = None, 0.0
        if tracker.sample_valid and tracker.sample_time_ns != last_stamp:
            last_stamp = tracker.sample_time_ns
            q_m, age = tracker.sample_q, (t_ns - tracker.sample_time_ns) / 1e9
        for f in filters:
            if isinstance(f, Mekf):
                f.update(mean, CYCLE_S, q_m, age, samples=count)
            else:
                f.update(mean, CYCLE_S, q_m, age)
        acc, count = [0.0, 0.0, 0.0], 0
        if on_cycle is not None:
            on_cycle(t_ns / 1e9, state, filters)
    return state


def quad6(p, x):
    """xᵀ P⁻¹ x for the 6×6 P (numpy, test side)."""
    import numpy as np

    return float(np.asarray(x) @ np.linalg.solve(np.asarray(p), np.asarray(x)))


def _consistency(gyro_spec, sigma_g, seed=3):
    """(attitude NEES samples every 2 s, bias-only NEES samples, 6-dof NEES samples, NIS of every update) after
    100 s of 700 s (campaigns/adcs/mekf_evidence.py records them for attitude_knowledge.md)."""
    f = make_mekf(gyro_noise_rad_s=sigma_g)
    att, bias, full, nis = [], [], [], []

    def on_cycle(t, state, filters):
        if t < 100.0:
            return
        m = filters[0]
        if m.last_residual is not None and m.since_measurement_s == 0.0:
            nis.append(_quad3(m.last_innovation_cov, m.last_residual))
        if abs(t / 2.0 - round(t / 2.0)) < 1e-6:
            x = small_error(state[:4], m.q) + tuple(bt - be for bt, be in zip(BIAS, m.bias, strict=True))
            att.append(_quad3([row[:3] for row in m.P[:3]], x[:3]))
            bias.append(_quad3([row[3:] for row in m.P[3:]], x[3:]))
            full.append(quad6(m.P, x))

    fly([f], 700.0, seed=seed, gyro_spec=gyro_spec, on_cycle=on_cycle)
    return att, bias, full, nis


def _band(dof, n):
    """Two-sided 95 % band of the mean of n χ²(dof) samples (normal approximation)."""
    half = 1.96 * math.sqrt(2 * dof * n) / n
    return dof - half, dof + half


def test_attitude_nees_and_nis_are_within_their_chi_square_bounds():
    """MEKF-001: with the plant's sensor models as flown (noise, constant bias, 70 mdps quantisation), over 600 s
    after a 100 s settling: the attitude NEES (3 dof, truth from RK4), sampled every 2 s (300 samples), averages
    inside its two-sided 95 % χ² band, and so does the NIS of the ~3000 tracker updates (3 dof)."""
    att, _, _, nis = _consistency(GYRO, SIGMA_G)
    lo, hi = _band(3, len(att))
    assert lo <= sum(att) / len(att) <= hi, (sum(att) / len(att), lo, hi)
    lo, hi = _band(3, len(nis))
    assert lo <= sum(nis) / len(nis) <= hi, (sum(nis) / len(nis), lo, hi)


def test_full_nees_is_not_overconfident_on_the_bias():
    """MEKF-001: with the quantisation off (so the sensor's bias is exactly the constant the filter estimates;
    quantised readings add a rate-dependent mean error that the filter rightly folds into its bias), the 6-dof
    NEES averages at most the upper end of its 95 % band: consistent on the attitude, conservative on the
    bias (its random walk σ_u > 0 while the plant's bias is constant)."""
    spec = GyroSpec(bias_dps=GYRO.bias_dps, full_scale_dps=2000.0, resolution_dps=0.0)
    _, _, full, _ = _consistency(spec, math.radians(spec.noise_std_dps))
    lo, hi = _band(6, len(full))
    assert sum(full) / len(full) <= hi, (sum(full) / len(full), hi)


def _quad3(s, r):
    import numpy as np

    return float(np.asarray(r) @ np.linalg.solve(np.asarray(s), np.asarray(r)))


def test_bias_converges_from_a_wrong_start():
    """MEKF-002: started with b̂ = 0 against the sensor's (0.3, −0.2, 0.1) °/s, the bias error is within 3σ of
    the filter's own covariance and below 0.003 °/s per axis after 120 s, and its σ has fallen from 1 °/s to
    below 0.003 °/s."""
    f = make_mekf()
    fly([f], 120.0)
    sig = f.bias_sigma_rad_s
    for true, est, s in zip(BIAS, f.bias, sig, strict=True):
        assert abs(true - est) <= 3 * s
        assert math.degrees(abs(true - est)) < 0.003
        assert math.degrees(s) < 0.003


def test_covariance_stays_symmetric_positive_definite():
    """MEKF-003: at every cycle of a 200 s run that has an attitude, P is symmetric (|P − Pᵀ| = 0 after each step)
    and positive definite (Cholesky succeeds, smallest eigenvalue > 0)."""
    import numpy as np

    worst = []

    def on_cycle(t, state, filters):
        if filters[0].q is None:  # no attitude before the first tracker solution (its block is undefined)
            return
        p = np.asarray(filters[0].P)
        assert np.array_equal(p, p.T)
        np.linalg.cholesky(p)
        worst.append(np.linalg.eigvalsh(p).min())

    fly([make_mekf()], 200.0, on_cycle=on_cycle)
    assert min(worst) > 0.0


def rms_errors():
    """400 s from a wrong (zero) bias, same sensors and seed for both filters: over the last 300 s, per filter
    (``"mekf"``, ``"cf"``: the complementary filter at its defaults k_p 0.5 /s, k_i 0.02 /s²) the RMS attitude
    error per axis (″, body frame) and the RMS bias error (°/s). campaigns/adcs/mekf_evidence.py records them."""
    m, c = make_mekf(), AttitudeFilter(0.5, 0.02)
    sq = {"mekf": [0.0] * 3, "cf": [0.0] * 3}
    bias_sq = {"mekf": 0.0, "cf": 0.0}
    count = [0]

    def on_cycle(t, state, filters):
        if t < 100.0:
            return
        count[0] += 1
        for name, flt in (("mekf", filters[0]), ("cf", filters[1])):
            e = small_error(state[:4], flt.q)
            for i in range(3):
                sq[name][i] += e[i] ** 2
            bias_sq[name] += sum((bt - be) ** 2 for bt, be in zip(BIAS, flt.bias, strict=True))

    fly([m, c], 400.0, on_cycle=on_cycle)
    rms = {k: [math.sqrt(v / count[0]) / ARCSEC for v in vals] for k, vals in sq.items()}
    brms = {k: math.degrees(math.sqrt(v / count[0])) for k, v in bias_sq.items()}
    return rms, brms


def test_mekf_beats_the_complementary_filter():
    """MEKF-004: same sensors, same seed, 400 s from a wrong (zero) bias: over the last 300 s the MEKF's RMS
    attitude error is smaller than the complementary filter's (defaults k_p 0.5 /s, k_i 0.02 /s²) about every
    axis, and its RMS bias error smaller too. Prints both for the study."""
    rms, brms = rms_errors()
    print(f"RMS attitude error arcsec (x, y, z): MEKF {rms['mekf']}, complementary {rms['cf']}; "
          f"RMS bias error deg/s: MEKF {brms['mekf']:.2e}, complementary {brms['cf']:.2e}")
    for a, b in zip(rms["mekf"], rms["cf"], strict=True):
        assert a < b
    assert brms["mekf"] < brms["cf"]


def test_a_large_residual_reinitialises_the_attitude():
    """MEKF-005: after 60 s on the gyro alone at a 0.5 °/s bias error, the attitude 3σ exceeds 5°, so the next
    tracker solution re-initialises the attitude on it (within 1″ of the measurement), keeping the bias."""
    f = make_mekf(initial_bias_sigma_rad_s=math.radians(0.5))
    f.update((0.0, 0.0, 0.0), 0.1, (1.0, 0.0, 0.0, 0.0))
    for _ in range(600):
        f.update((math.radians(0.5), 0.0, 0.0), 0.1)
    assert f.attitude_sigma3_rad > math.radians(5.0)
    q_m = (math.cos(0.1), 0.0, math.sin(0.1), 0.0)
    bias = f.bias
    f.update((0.0, 0.0, 0.0), 0.1, q_m)
    assert f.reinitialisations == 1
    assert math.sqrt(sum(x * x for x in small_error(q_m, f.q))) < ARCSEC
    assert f.bias == bias


def test_bad_boresight_is_refused():
    """MEKF-006: a zero boresight is a clear error."""
    with pytest.raises(ValueError, match="boresight_B"):
        make_mekf(boresight_B=(0.0, 0.0, 0.0))


def test_structured_covariance_step_gives_the_floats_of_the_full_products():
    """MEKF-003: Φ P Φᵀ summed over Φ's non-zero entries only is, bit for bit, the product of the full 6×6
    matrices (each element ``sum`` of six products in index order) — for random P with exact zeros, negative
    zeros and mixed signs, and Φ from random rates and steps (the filter's outputs do not move by a last bit)."""
    import random

    from detumble.control.mekf import _matmul, _phi_p_phi_t, _rotation_transpose, _transpose

    rng = random.Random(3)
    specials = (0.0, -0.0, 1e-300, -1e-300)
    for _ in range(300):
        p = [[rng.choice(specials) if rng.random() < 0.2 else rng.uniform(-1.0, 1.0) * 10 ** rng.randint(-12, 0)
              for _ in range(6)] for _ in range(6)]
        w = tuple(rng.choice((0.0, rng.gauss(0.0, 0.3))) for _ in range(3))
        dt = rng.choice((0.0, 0.02, 0.1, rng.uniform(0.0, 1.0)))
        f = _rotation_transpose(w, dt)
        phi = [list(f[i]) + [-dt if j == i else 0.0 for j in range(3)] for i in range(3)]
        phi += [[0.0] * 3 + [1.0 if j == i else 0.0 for j in range(3)] for i in range(3)]
        full = _matmul(_matmul(phi, p), _transpose(phi))
        fast = _phi_p_phi_t(f, -dt, p)
        assert [[x.hex() for x in row] for row in fast] == [[x.hex() for x in row] for row in full]


def _reference_propagate_covariance(f, w, dt, var_rate):
    """The covariance step from the full 6×6 products: ``sym(Φ P Φᵀ + Q)``, Q built as a matrix."""
    from detumble.control.mekf import _matmul, _rotation_transpose, _symmetric, _transpose

    rot = _rotation_transpose(w, dt)
    phi = [list(rot[i]) + [-dt if j == i else 0.0 for j in range(3)] for i in range(3)]
    phi += [[0.0] * 3 + [1.0 if j == i else 0.0 for j in range(3)] for i in range(3)]
    su2 = f.bias_walk ** 2
    qa, qab, qb = var_rate * dt * dt + su2 * dt ** 3 / 3.0, -su2 * dt * dt / 2.0, su2 * dt
    q = [[(qa if i < 3 else qb) if i == j else qab if abs(i - j) == 3 else None for j in range(6)] for i in range(6)]
    full = _matmul(_matmul(phi, f.P), _transpose(phi))
    return _symmetric([[x if qx is None else x + qx for x, qx in zip(row, qrow, strict=True)]
                       for row, qrow in zip(full, q, strict=True)])


def _reference_measure(f, q_m, var_carry, corr):
    """The star-tracker update in its matrix form (main before the written-out step); ``(P, q, bias, r, S)``."""
    from detumble.control.mekf import _inv_spd3, _matmul, _symmetric
    from detumble.control.quaternion import quat_normalize

    r = f.tracker_noise()
    for i in range(3):
        r[i][i] += var_carry
    qe = quat_shortest(quat_mul(quat_conj(f.q), q_m))
    res = (2.0 * qe[1], 2.0 * qe[2], 2.0 * qe[3])
    p = f.P
    s = [[p[i][j] + r[i][j] for j in range(3)] for i in range(3)]
    for i in range(3):
        s[i][i] -= 2.0 * corr
    pht = [row[:3] for row in p]
    for i in range(3):
        pht[i][i] -= corr
    k = _matmul(pht, _inv_spd3(s))
    r0, r1, r2 = res
    dx = [k0 * r0 + k1 * r1 + k2 * r2 for k0, k1, k2 in k]
    ksk = [[sum((a0 * c0, a1 * c1, a2 * c2)) for c0, c1, c2 in k] for a0, a1, a2 in _matmul(k, s)]
    p_new = _symmetric([[x - y for x, y in zip(prow, krow, strict=True)] for prow, krow in zip(p, ksk, strict=True)])
    q = quat_normalize(quat_mul(f.q, (1.0, 0.5 * dx[0], 0.5 * dx[1], 0.5 * dx[2])))
    b = f.bias
    return p_new, q, (b[0] + dx[3], b[1] + dx[4], b[2] + dx[5]), res, s


def _hex(m):
    return [[x.hex() for x in row] for row in m]


def test_covariance_steps_give_the_floats_of_the_matrix_forms():
    """MEKF-007: the propagation step (structured products, _symmetric6) and the star-tracker step (rows with
    their sums spelled out) give bit for bit the floats of their matrix forms (``sym(Φ P Φᵀ + Q)`` from the full
    6×6 products; ``K = (P Hᵀ + M) S⁻¹``, ``sym(P − K S Kᵀ)``, the reset) — for random, not necessarily
    symmetric P with exact and negative zeros, random rates, steps, noises, boresights, carrying variances and
    correlations; a non-positive-definite S is refused by both."""
    import copy
    import random

    rng = random.Random(7)
    specials = (0.0, -0.0, 1e-300, -1e-300)
    refused = 0
    for trial in range(400):
        axis = [rng.gauss(0.0, 1.0) for _ in range(3)]
        f = make_mekf(gyro_noise_rad_s=rng.uniform(1e-5, 1e-2), bias_walk_rad_s_rt_s=rng.choice((0.0, 1e-6, 1e-4)),
                      tracker_cross_rad=rng.uniform(1.0, 50.0) * ARCSEC,
                      tracker_about_rad=rng.uniform(1.0, 200.0) * ARCSEC,
                      boresight_B=tuple(axis), reinit_angle_rad=math.pi)
        scale = 10.0 ** rng.randint(-12, -7)  # about R (1–200″)²: K S Kᵀ then cancels much of P
        f.P = [[rng.choice(specials) if rng.random() < 0.2 else rng.uniform(-1.0, 1.0) * scale for _ in range(6)]
               for _ in range(6)]
        for i in range(6):
            if rng.random() < 0.8:
                f.P[i][i] = abs(f.P[i][i]) + rng.uniform(0.0, 4.0) * scale
        f.q = quat_shortest(tuple(c / math.sqrt(sum(x * x for x in axis + [1.0])) for c in [1.0] + axis))
        f.bias = tuple(rng.gauss(0.0, 1e-3) for _ in range(3)) if trial % 2 else (0.0, 0.0, 0.0)  # 0: b + δb is δb
        w = tuple(rng.choice((0.0, rng.gauss(0.0, 0.3))) for _ in range(3))
        dt = rng.choice((0.0, 0.02, 0.1, rng.uniform(0.0, 1.0)))
        var_rate = rng.uniform(0.0, 1e-6)

        expected = _reference_propagate_covariance(f, w, dt, var_rate)
        f._propagate_covariance(w, dt, var_rate)
        assert _hex(f.P) == _hex(expected), trial

        half = rng.gauss(0.0, 1e-3)
        q_m = quat_mul(f.q, (math.cos(half), math.sin(half) * 0.6, -math.sin(half) * 0.8, 0.0))
        var_carry, corr = rng.choice((0.0, rng.uniform(0.0, 1e-9))), rng.choice((0.0, rng.uniform(0.0, 1e-10)))
        before = copy.deepcopy(f)
        try:
            p_ref, q_ref, b_ref, res_ref, s_ref = _reference_measure(before, q_m, var_carry, corr)
        except ValueError:
            refused += 1
            with pytest.raises(ValueError, match="not positive definite"):
                f._measure(q_m, var_carry, corr)
            continue
        f._measure(q_m, var_carry, corr)
        assert _hex(f.P) == _hex(p_ref), trial
        assert [x.hex() for x in f.q] == [x.hex() for x in q_ref], trial
        assert [x.hex() for x in f.bias] == [x.hex() for x in b_ref], trial
        assert f.last_residual == res_ref and _hex(f.last_innovation_cov) == _hex(s_ref), trial
    assert 0 < refused < 200  # both branches exercised


def test_symmetric6_is_symmetric():
    """MEKF-007: _symmetric6 (each pair summed once) gives _symmetric's floats, for random 6×6 matrices with exact
    and negative zeros, tiny and huge entries, as lists of lists or tuples."""
    import random

    from detumble.control.mekf import _symmetric, _symmetric6

    rng = random.Random(8)
    specials = (0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300)
    for _ in range(2000):
        c = [[rng.choice(specials) if rng.random() < 0.2 else rng.uniform(-1.0, 1.0) * 10 ** rng.randint(-20, 5)
              for _ in range(6)] for _ in range(6)]
        rows = c if rng.random() < 0.5 else [tuple(r) for r in c]
        assert _hex(_symmetric6(rows)) == _hex(_symmetric(c))
