"""The hold scheduled on the on-board field model (control.magnetic_lqr): the propagated orbit, the Riccati gains, the
dipole's frames (MAGPT-110…113)."""

from __future__ import annotations

import math

import pytest

from detumble.control.geomagnetic import dipole_field_N
from detumble.control.magnetic_lqr import (EARTH_ROTATION_RATE_RAD_S, circular_position_N, hold_gain_table, hold_gains,
                                           lqr_dipole_B)
from detumble.control.quaternion import quat_from_axis_angle, rotate_b_to_n, rotate_n_to_b

R0 = (6.791e6, 0.0, 0.0)
V0 = (0.0, 7661.0 * math.cos(0.9), 7661.0 * math.sin(0.9))
INERTIA = ((2.75e-3, 2.5e-5, -1.9e-5), (2.5e-5, 2.69e-3, 1.25e-5), (-1.9e-5, 1.25e-5, 2.56e-3))
M_MAX = (0.116, 0.116, 0.0087)


def test_circular_position_is_the_closed_form_circle():
    """MAGPT-110: the propagated position keeps |r|, is ``|r| ĥ × r̂`` a quarter of the period ``2π |r|² / |r × v|``
    later, ``−r`` at half and ``r`` again after one period (1e-6 m on 6.8e6 m)."""
    rate = 6.791e6 * 7661.0 / 6.791e6 ** 2
    period = 2.0 * math.pi / rate
    quarter = circular_position_N(R0, V0, period / 4.0)
    assert quarter == pytest.approx((0.0, 6.791e6 * math.cos(0.9), 6.791e6 * math.sin(0.9)), abs=1e-6)
    assert circular_position_N(R0, V0, period / 2.0) == pytest.approx((-6.791e6, 0.0, 0.0), abs=1e-6)
    assert circular_position_N(R0, V0, period) == pytest.approx(R0, abs=1e-6)
    later = circular_position_N(R0, V0, 1234.5)
    assert math.hypot(*later) == pytest.approx(6.791e6, rel=1e-12)
    with pytest.raises(ValueError):
        circular_position_N(R0, R0, 10.0)


def test_hold_gains_match_the_periodic_riccati_of_the_analysis():
    """MAGPT-111: over a sequence of fields flown twice, the gains of the first pass are those of
    ``analysis.magnetic_periodic_lqr.periodic_riccati_gains`` (numpy) stopped after its second pass (1e-9 relative):
    the same Riccati recursion, α-shift and weights, written twice."""
    np = pytest.importorskip("numpy")
    from detumble.analysis.magnetic_periodic_lqr import periodic_riccati_gains, sampled_double_integrator

    h, n = 2.0, 40
    fields = [(3e-5 * math.cos(0.02 * k), 2e-5 * math.sin(0.02 * k), 1e-5 + 2e-7 * k) for k in range(n)]
    q = np.diag([1.0 / math.radians(30.0) ** 2] * 3 + [1.0 / 0.03 ** 2] * 3)
    r = np.diag([1.0 / m ** 2 for m in M_MAX])
    seq = [sampled_double_integrator(b, np.array(INERTIA), h) for b in fields]
    ref, _, _ = periodic_riccati_gains([s[0] for s in seq], [s[1] for s in seq], q, r, h, alpha=2e-3, tol=1e300)
    got = hold_gains(fields * 2, INERTIA, h, M_MAX, math.radians(30.0), 0.03, 1.0, 2e-3)
    assert len(got) == 2 * n
    for k in range(n):
        scale = float(np.max(np.abs(ref[k])))
        assert float(np.max(np.abs(np.array(got[k]).reshape(3, 6) - ref[k]))) <= 1e-9 * scale


def test_gain_table_predicts_the_model_field_along_the_orbit():
    """MAGPT-112: the table's gains are those of :func:`hold_gains` over the on-board dipole at the circular
    propagation of the ephemeris, turned into the target frame (the same floats), and it answers only within its
    ``use_s`` (None before and after: time to compute a new table)."""
    q_tn = quat_from_axis_angle((0.0, 1.0, 0.0), math.radians(45.0))
    table = hold_gain_table(q_tn, 100.0, R0, V0, 0.3, INERTIA, M_MAX, 7.0, 70.0, 70.0, math.radians(30.0), 0.03,
                            1.0, 2e-3)
    fields = [rotate_n_to_b(q_tn, dipole_field_N(circular_position_N(R0, V0, 7.0 * k),
                                                 0.3 + EARTH_ROTATION_RATE_RAD_S * 7.0 * k)) for k in range(20)]
    expected = hold_gains(fields, INERTIA, 7.0, M_MAX, math.radians(30.0), 0.03, 1.0, 2e-3)
    assert table.gain(100.0) == expected[0]
    assert table.gain(100.0 + 7.0 * 9 + 3.5) == expected[9]
    assert table.gain(99.9) is None and table.gain(170.0) is None


def test_lqr_dipole_acts_in_the_target_frame():
    """MAGPT-113: ``m_B = R_BT (−K (θ, R_TB ω))``: for an error of 40° about an axis, the dipole in B is the gain's
    target-frame dipole turned into B, and a gain that only damps z (T) gives a dipole along T's z turned into B."""
    q_err = quat_from_axis_angle((0.0, 0.6, 0.8), math.radians(40.0))
    gain = [[0.0] * 6 for _ in range(3)]
    gain[2][5] = 2.0  # m_z(T) = −2 ω_z(T)
    w_b = (0.01, -0.02, 0.03)
    w_t = rotate_b_to_n(q_err, w_b)
    m = lqr_dipole_B([x for row in gain for x in row], q_err, w_b)  # the gain's 18 floats row by row
    assert m == pytest.approx(rotate_n_to_b(q_err, (0.0, 0.0, -2.0 * w_t[2])), abs=1e-15)
    # and a θ gain: θ = 2 q_err.v is the same vector in B and T
    gain = [[3.0 if i == k else 0.0 for k in range(6)] for i in range(3)]
    th = (2.0 * q_err[1], 2.0 * q_err[2], 2.0 * q_err[3])
    assert lqr_dipole_B([x for row in gain for x in row], q_err, (0.0, 0.0, 0.0)) == pytest.approx(
        rotate_n_to_b(q_err, (-3.0 * th[0], -3.0 * th[1], -3.0 * th[2])), abs=1e-15)


def test_onboard_field_is_the_dipole_at_degree_one_and_igrf_above():
    """MAGPT-114: the on-board model (``geomagnetic.OnboardField``) at degree 1 is :func:`dipole_field_N` (the closed
    form, 1e-12 relative: IGRF's degree 1 is that dipole); at 13 it is the plant's IGRF-14 of epoch 2025.0 at the same
    Earth angle (1e-12 relative); at 8 it differs from it (truncation) by less than 1 % of the field and more than 0."""
    from detumble.control.geomagnetic import OnboardField
    from detumble.sim.igrf import IgrfField

    r = (4.1e6, -3.2e6, 4.3e6)
    angle = 1.1
    dip = dipole_field_N(r, angle)
    assert OnboardField(1)(r, angle) == pytest.approx(dip, rel=1e-12)
    plant = IgrfField(2025.0, 13, theta0_rad=angle).b_N(0.0, r)
    assert OnboardField(13)(r, angle) == pytest.approx(plant, rel=1e-12)
    b8 = OnboardField(8)(r, angle)
    diff = math.dist(b8, plant)
    assert 0.0 < diff < 0.01 * math.hypot(*plant)
    assert math.dist(dip, plant) > 0.05 * math.hypot(*plant)  # the dipole is far from IGRF-14 here
    with pytest.raises(ValueError):
        OnboardField(14)


def test_builder_in_pieces_gives_the_table_to_the_float():
    """MAGPT-115: :class:`HoldGainTableBuilder` advanced a few units at a time (7, then 3: the budget's smallest) does
    at most its budget each call and finishes with the gains :func:`hold_gain_table` gives in one call, to the float
    (the dipole and IGRF-14 of degree 6 on board), after ``⌈units / budget⌉`` calls."""
    from detumble.control.geomagnetic import OnboardField
    from detumble.control.magnetic_lqr import RICCATI_STEP_UNITS, SAMPLE_UNITS, HoldGainTableBuilder

    q_tn = quat_from_axis_angle((0.3, 0.5, 0.8), 0.9)
    for field, budget in ((dipole_field_N, 7), (OnboardField(6), RICCATI_STEP_UNITS)):
        args = (q_tn, 50.0, R0, V0, 0.3, INERTIA, M_MAX, 1.4, 56.0, 42.0, math.radians(30.0), 0.03, 1.0, 2e-3, field)
        whole = hold_gain_table(*args)
        builder = HoldGainTableBuilder(*args)
        n = math.ceil(98.0 / 1.4)
        assert builder.units_total == n * (SAMPLE_UNITS + RICCATI_STEP_UNITS)
        calls, table = 0, None
        while table is None:
            before = builder.units_done
            table = builder.advance(budget)
            calls += 1
            assert 0 < builder.units_done - before <= budget
        assert builder.units_done == builder.units_total
        assert list(table.gains) == list(whole.gains) and len(table.gains) == 18 * n
        assert (table.q_tn, table.t0_s, table.step_s, table.use_s) == (q_tn, 50.0, 1.4, 56.0)
        assert table.gain(50.0 + 1.4 * 7 + 0.2) == whole.gain(50.0 + 1.4 * 7 + 0.2)
        # samples fill whole budgets; a step needs RICCATI_STEP_UNITS left
        assert calls == math.ceil(n / budget) + math.ceil(n / (budget // RICCATI_STEP_UNITS))
    with pytest.raises(ValueError):
        HoldGainTableBuilder(*args).advance(RICCATI_STEP_UNITS - 1)


def test_builder_raises_from_the_advance_that_meets_the_failure():
    """MAGPT-116: an ephemeris without an orbit plane (v along r) raises ValueError from the first :meth:`advance`
    (the first sample), not from the builder's construction."""
    from detumble.control.magnetic_lqr import HoldGainTableBuilder

    builder = HoldGainTableBuilder((1.0, 0.0, 0.0, 0.0), 0.0, R0, (7661.0, 0.0, 0.0), 0.3, INERTIA, M_MAX, 1.4, 56.0,
                                   42.0, math.radians(30.0), 0.03, 1.0, 2e-3)
    with pytest.raises(ValueError, match="no orbit plane"):
        builder.advance(30)
