"""Sensor models: noise statistics, sample-and-hold, quantisation, saturation, coil coupling."""

import math

import pytest

from detumble.sim.coils import X_MINUS, X_PLUS, Z_MINUS
from detumble.sim.plant import Plant
from detumble.sim.scenario import scenario_from_dict
from detumble.sim.sensors import Gyro, GyroSpec, Magnetometer, MagnetometerSpec

GAUSS = 1e-4  # tesla per gauss
N_SAMPLES = 20_000


def _stats(xs):
    m = sum(xs) / len(xs)
    return m, math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1))


def test_magnetometer_noise_statistics_seeded():
    """Mean = truth + bias within 4 sigma/sqrt(N); std = sqrt(sigma^2 + LSB^2/12) within 3 %."""
    spec = MagnetometerSpec(noise_std_gauss=0.003, bias_gauss=(0.012, -0.008, 0.005), resolution_gauss=0.0015)
    mag = Magnetometer(spec, seed=42)
    b_true = (0.21 * GAUSS, -0.13 * GAUSS, 0.35 * GAUSS)
    data = [mag.measure(b_true, (0.0, 0.0, 0.0)) for _ in range(N_SAMPLES)]
    expect_std = math.sqrt(0.003**2 + 0.0015**2 / 12)  # gauss
    for i, truth in enumerate((0.21, -0.13, 0.35)):
        mean, std = _stats([d[i] for d in data])
        assert abs(mean - (truth + spec.bias_gauss[i])) < 4 * expect_std / math.sqrt(N_SAMPLES)
        assert abs(std - expect_std) < 0.03 * expect_std
        # every value on the 1.5 mG grid
        assert all(abs(d[i] / 0.0015 - round(d[i] / 0.0015)) < 1e-6 for d in data[:100])


def test_gyro_noise_statistics_seeded():
    """Per-sample std = noise density * sqrt(ODR/2) = 0.0038 * sqrt(52) = 0.0274 deg/s, within 3 %."""
    spec = GyroSpec(noise_density_dps_rthz=0.0038, odr_hz=104.0, bias_dps=(0.3, -0.2, 0.1), resolution_dps=0.0)
    assert spec.noise_std_dps == pytest.approx(0.0038 * math.sqrt(52.0), rel=1e-12)
    gyro = Gyro(spec, seed=7)
    w = (0.1, -0.2, 0.3)  # rad/s
    data = [gyro.measure(w) for _ in range(N_SAMPLES)]
    sd = math.radians(spec.noise_std_dps)
    for i in range(3):
        mean, std = _stats([d[i] for d in data])
        assert abs(mean - (w[i] + math.radians(spec.bias_dps[i]))) < 4 * sd / math.sqrt(N_SAMPLES)
        assert abs(std - sd) < 0.03 * sd


def test_gyro_quantisation_and_saturation():
    spec = GyroSpec(noise_density_dps_rthz=0.0, full_scale_dps=125.0)
    assert spec.lsb_dps == 0.004375
    gyro = Gyro(spec, seed=0)
    out = gyro.measure((math.radians(200.0), math.radians(-500.0), math.radians(10.0001)))
    assert out[0] == pytest.approx(math.radians(125.0)) and out[1] == pytest.approx(math.radians(-125.0))
    assert math.degrees(out[2]) == pytest.approx(round(10.0001 / 0.004375) * 0.004375, abs=1e-12)


def test_magnetometer_saturates_at_full_scale():
    mag = Magnetometer(MagnetometerSpec(noise_std_gauss=0.0, full_scale_gauss=50.0), seed=0)
    assert mag.measure((0.0, 0.0, 0.0), (40.0, -40.0, 0.0)) == (50.0, -50.0, 0.0)


def _plant(**mag):
    spec = {"noise_std_gauss": 0.0, "bias_gauss": [0, 0, 0], **mag}
    return Plant(scenario_from_dict({
        "dynamics_step_s": 0.002,
        "sensors": {"magnetometer": spec, "gyro": {"noise_density_dps_rthz": 0.0, "resolution_dps": 0.0}},
        "initial": {"rate": {"omega_deg_s": [20.0, -10.0, 5.0]}},
    }))


def test_sample_and_hold_at_odr_and_read_time():
    """100 Hz magnetometer: reads between ODR instants return the held sample; the read time is reported."""
    p = _plant()
    p.advance_to(0.012)
    a = p.magnetometer_reading()
    p.advance_to(0.018)
    b = p.magnetometer_reading()
    assert a[:3] == b[:3]  # same 10 ms sample (taken at 0.010 s)
    assert (a[3], b[3]) == (pytest.approx(0.012), pytest.approx(0.018))
    assert p.magnetometer.sample_time_ns == 10_000_000
    c = p.magnetometer_reading(t=0.0205)
    assert c[:3] != b[:3] and p.magnetometer.sample_time_ns == 20_000_000
    # the held sample is the true field at the ODR instant, to quantisation (0.75 mG) and interpolation
    p2 = _plant()
    p2.advance_to(0.020)
    assert all(abs(x - y / GAUSS) < 0.0008 for x, y in zip(c[:3], p2.b_B, strict=True))
    # gyro at 104 Hz: instants every 9.615385 ms
    g1 = p.gyro_reading()
    assert p.gyro.sample_time_ns == 2 * 9_615_385
    assert g1[:3] == pytest.approx(p.omega_BN_B, abs=1e-4)


def test_coil_coupling_visible_while_coils_are_on():
    """With coils on, the next sample shifts by K m_coils (1.6e-3 T per A m^2): a 'violation' is visible."""
    p = _plant()
    p.advance_to(0.010)
    off = p.magnetometer_reading()
    p.set_coil_level(X_PLUS, 127)
    p.set_coil_level(X_MINUS, -127)
    p.set_coil_level(Z_MINUS, 127)
    m = p.m_coils_B
    assert m[0] == pytest.approx(2 * 0.0581206, rel=1e-4) and m[2] == pytest.approx(-0.0087151, rel=1e-4)
    # still the held coils-off sample until the next ODR instant
    p.advance_to(0.015)
    assert p.magnetometer_reading()[:3] == off[:3]
    p.advance_to(0.020)
    on = p.magnetometer_reading()
    # reference: the same plant without coils at t = 0.020 (the torque of 10 ms moves the true field < 1 mG)
    ref = _plant()
    ref.advance_to(0.020)
    clean = ref.magnetometer_reading()
    k_gauss = 1.6e-3 / GAUSS  # gauss per A m^2
    for i in range(3):
        assert on[i] - clean[i] == pytest.approx(k_gauss * m[i], abs=2 * 0.0015)  # 2 LSB
    assert on[0] - clean[0] > 1.8  # 186 uT = 1.86 G: several times the Earth's field
    # coupling gain configurable (0 turns it off)
    p0 = _plant(coupling_t_per_am2=[0.0, 0.0, 0.0])
    p0.set_coil_level(X_PLUS, 127)
    p0.advance_to(0.020)
    assert abs(p0.magnetometer_reading()[0] - clean[0]) < 0.01


def test_skip_gauss_leaves_the_stream_where_n_gauss_draws_would():
    """SIM-SENS-LAZY-001: after skip_gauss(n) the next draws equal those after n real gauss() calls,
    for every n up to 40 (whole pairs skipped by one getrandbits call) and either half of a pair pending
    (bit-identical floats)."""
    import random

    from detumble.sim.sensors import skip_gauss

    for before in range(3):
        for n in range(41):
            real, skipped = random.Random(11), random.Random(11)
            for rng in (real, skipped):
                for _ in range(before):
                    rng.gauss()
            for _ in range(n):
                real.gauss()
            skip_gauss(skipped, n)
            assert [real.gauss() for _ in range(5)] == [skipped.gauss() for _ in range(5)], (before, n)


def _noisy_plant():
    return Plant(scenario_from_dict({
        "dynamics_step_s": 0.02,
        "sensors": {"magnetometer": {"noise_std_gauss": 0.003}, "gyro": {"noise_density_dps_rthz": 0.0038}},
        "initial": {"rate": {"omega_deg_s": [20.0, -10.0, 5.0]}},
    }))


def test_lazy_samples_equal_eager_ones_whatever_is_read_when():
    """SIM-SENS-LAZY-002: samples are computed only when read, yet every sample read is bit for bit
    the one a plant reading both sensors after every step gets (unread samples still consume their
    noise draws), including after a direct measure() call in between."""
    eager, lazy = _noisy_plant(), _noisy_plant()
    for k in range(1, 400):
        eager.step()
        lazy.step()
        e_mag, e_gyro = eager.magnetometer.sample_gauss, eager.gyro.sample_rad_s
        if k % 7 == 0:
            assert lazy.magnetometer.sample_gauss == e_mag, k
        if k % 11 == 0:
            assert lazy.gyro.sample_rad_s == e_gyro, k
        if k == 200:  # an extra measurement draws after the deferred sample, as it would eagerly
            assert lazy.magnetometer.measure((1e-5, 0.0, 0.0), (0.0, 0.0, 0.0)) == \
                eager.magnetometer.measure((1e-5, 0.0, 0.0), (0.0, 0.0, 0.0))
    assert lazy.magnetometer.sample_time_ns == eager.magnetometer.sample_time_ns
    assert lazy.state == eager.state


def _hexes(v):
    return [x.hex() for x in v]


def test_quantise3_is_three_quantise_calls():
    """SIM-SENS-LAZY-003: the three-axis quantiser gives bit for bit what _quantise gives per axis (rounding,
    saturation either side, LSB 0 = off, exact and negative zeros)."""
    import random

    from detumble.sim.sensors import _quantise, _quantise3

    rng = random.Random(4)
    for _ in range(5000):
        lsb = rng.choice((0.0, 0.0015, math.radians(0.07), rng.uniform(1e-6, 1.0)))
        limit = rng.choice((50.0, math.radians(125.0), rng.uniform(0.1, 10.0)))
        xyz = [rng.choice((0.0, -0.0, limit, -limit, rng.uniform(-2.0, 2.0) * limit)) for _ in range(3)]
        assert _hexes(_quantise3(*xyz, lsb, limit)) == _hexes([_quantise(v, lsb, limit) for v in xyz])


def test_held_samples_are_the_step_by_step_formula():
    """SIM-SENS-LAZY-004: a deferred sample read through ``sample_rad_s`` / ``sample_gauss`` (the resolve
    written out) is bit for bit the formula step by step: the unread samples' draws skipped, the true value
    interpolated to the ODR instant, bias (coil coupling), three gauss() draws, _quantise per axis."""
    import random

    from detumble.sim.sensors import _quantise, skip_gauss
    from detumble.sim.vec import rotate_n_to_b

    rng = random.Random(9)
    for trial in range(300):
        gspec = GyroSpec(noise_density_dps_rthz=rng.choice((0.0, 0.0038, 0.05)),
                         bias_dps=tuple(rng.uniform(-0.5, 0.5) for _ in range(3)),
                         full_scale_dps=rng.choice((125.0, 2000.0)), resolution_dps=rng.choice((None, 0.0)))
        mspec = MagnetometerSpec(noise_std_gauss=rng.choice((0.0, 0.003)), resolution_gauss=rng.choice((0.0, 0.0015)),
                                 bias_gauss=tuple(rng.uniform(-0.01, 0.01) for _ in range(3)),
                                 full_scale_gauss=rng.choice((0.4, 50.0)))
        gyro, mag = Gyro(gspec, seed=trial), Magnetometer(mspec, seed=trial + 1)
        for _ in range(rng.randint(0, 2)):  # a pending half of a gauss pair, or not
            gyro.rng.gauss()
            mag.rng.gauss()
        t = 0
        for _ in range(rng.randint(1, 4)):  # some samples superseded unread
            t1 = t + 20_000_000
            s0 = [rng.uniform(-1.0, 1.0) for _ in range(4)] + [rng.uniform(-3.0, 3.0) for _ in range(3)]
            s1 = [rng.uniform(-1.0, 1.0) for _ in range(4)] + [rng.uniform(-3.0, 3.0) for _ in range(3)]
            b0_N, b1_N = (tuple(rng.uniform(-5e-5, 5e-5) for _ in range(3)) for _ in range(2))
            m = tuple(rng.uniform(-0.2, 0.2) for _ in range(3))
            tk = t + rng.choice((1, 9_615_385, 20_000_000))
            gyro.defer(t, t1, tk, s0, s1)
            mag.defer(t, t1, tk, s0, s1, b0_N, b1_N, m)
            t = t1
        g_rng, m_rng = random.Random(), random.Random()
        g_rng.setstate(gyro.rng.getstate())
        m_rng.setstate(mag.rng.getstate())
        skip_gauss(g_rng, gyro._draws * gyro._skipped)
        skip_gauss(m_rng, mag._draws * mag._skipped)
        s = (tk - (t - 20_000_000)) / 20_000_000
        w = [s0[4 + i] + s * (s1[4 + i] - s0[4 + i]) + gyro._bias[i] for i in range(3)]
        if gyro._sd > 0.0:
            w = [v + g_rng.gauss(0.0, gyro._sd) for v in w]
        expected = [_quantise(v, gyro._lsb, gyro._fs) for v in w]
        assert _hexes(gyro.sample_rad_s) == _hexes(expected), trial
        b0 = rotate_n_to_b(tuple(s0[:4]), b0_N)
        b1 = rotate_n_to_b(tuple(s1[:4]), b1_N)
        b = [b0[i] + s * (b1[i] - b0[i]) for i in range(3)]
        x = [1e4 * b[i] + mag._k[i] * m[i] + mspec.bias_gauss[i] for i in range(3)]
        if mspec.noise_std_gauss > 0.0:
            x = [v + m_rng.gauss(0.0, mspec.noise_std_gauss) for v in x]
        expected = [_quantise(v, mspec.resolution_gauss, mspec.full_scale_gauss) for v in x]
        assert _hexes(mag.sample_gauss) == _hexes(expected), trial
        assert gyro.rng.getstate() == g_rng.getstate() and mag.rng.getstate() == m_rng.getstate()
