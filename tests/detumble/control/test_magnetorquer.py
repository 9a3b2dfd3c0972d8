"""Magnetorquer: dipole (A·m²) → signed drive level (−127…127), detumble.md §5.

Hand-computed values use the DetumbleManager parameter defaults: X/Y coils 96 turns, 0.053 × 0.045 m,
3.3 V / 13 Ω; Z− coil 153 turns, 0.05755 m diameter, 3.3 V / 150.7 Ω.
"""

import math

import pytest

from detumble.control.magnetorquer import (CoilShape, DirectionSign, Magnetorquer,
                                   round_half_away_from_zero)

AM2 = 1.0  # A·m²


def x_plus_coil():
    return Magnetorquer(turns=96.0, voltage=3.3, resistance=13.0, shape=CoilShape.RECTANGULAR,
                        width=0.045, length=0.053, direction_sign=DirectionSign.POSITIVE)


def z_minus_coil():
    return Magnetorquer(turns=153.0, voltage=3.3, resistance=150.7, shape=CoilShape.CIRCULAR,
                        diameter=0.05755, direction_sign=DirectionSign.NEGATIVE)


def test_round_half_away_from_zero_is_not_bankers_rounding():
    """B-Dot Strategy (§5 rounding): halves go away from zero, unlike Python's round."""
    assert round_half_away_from_zero(2.5) == 3 and round(2.5) == 2
    assert round_half_away_from_zero(-2.5) == -3
    assert round_half_away_from_zero(62.5) == 63 and round(62.5) == 62
    assert round_half_away_from_zero(0.49999999999999994) == 0  # floor(x + 0.5) would give 1
    assert round_half_away_from_zero(21.85) == 22
    assert round_half_away_from_zero(-0.4) == 0
    assert round_half_away_from_zero(-0.0) == 0


def test_x_coil_default_parameters_hand_computed():
    """B-Dot Strategy: X coil at defaults: 0.01 A·m² → 22 and 0.03 A·m² → 66.

    By hand: I = m / (96 · 0.053 · 0.045) = m / 0.22896 A; imax = 3.3/13 = 0.253846 A;
    0.01 → 0.043676 A → 0.17206 · 127 = 21.85 → 22; 0.03 → 65.56 → 66.
    """
    coil = x_plus_coil()
    assert coil.coil_area() == pytest.approx(0.002385, rel=1e-12)
    assert coil.max_coil_current() == pytest.approx(0.2538461538, rel=1e-9)
    assert coil.dipole_moment_to_current(0.01 * AM2) == 22
    assert coil.dipole_moment_to_current(0.03 * AM2) == 66
    assert coil.dipole_moment_to_current(-0.01 * AM2) == -22


def test_z_minus_coil_hand_computed_and_negative_direction():
    """B-Dot Strategy: the Z− coil gives −58 for 0.004 A·m².

    By hand: area = π·0.028775² = 0.0026013 m²; I = 0.004/(153·0.0026013) = 0.010050 A;
    imax = 3.3/150.7 = 0.021898 A; 0.45894 · 127 = 58.29 → 58; NEGATIVE → −58.
    """
    coil = z_minus_coil()
    assert coil.coil_area() == pytest.approx(math.pi * 0.028775 ** 2, rel=1e-12)
    assert coil.dipole_moment_to_current(0.004 * AM2) == -58
    assert coil.dipole_moment_to_current(-0.004 * AM2) == 58


def test_max_dipoles_match_the_spec_hand_numbers():
    """B-Dot Strategy: m_max = 96·(0.053·0.045)·(3.3/13) = 0.0581 A·m²; Z−: 0.00872 A·m²."""
    assert x_plus_coil().max_dipole_moment() == pytest.approx(0.05812, abs=1e-5)
    assert z_minus_coil().max_dipole_moment() == pytest.approx(0.008715, abs=1e-6)


def test_saturation_clamps_to_full_scale_with_sign():
    """B-Dot Strategy: requests beyond m_max clamp to ±127 (times the direction sign)."""
    assert x_plus_coil().dipole_moment_to_current(1.0 * AM2) == 127
    assert x_plus_coil().dipole_moment_to_current(-1.0 * AM2) == -127
    assert z_minus_coil().dipole_moment_to_current(1.0 * AM2) == -127
    exact_max = x_plus_coil().max_dipole_moment()
    assert abs(x_plus_coil().dipole_moment_to_current(exact_max)) == 127


def test_operation_order_puts_the_half_case_on_63():
    """B-Dot Strategy: a 0.1 × 0.2 m coil has area 0.020000000000000004 m², so the "half" request
    0.01 A·m² (1 turn, 1 V, 1 Ω) scales to 63.49999999999999 and lands on 63, not 64."""
    coil = Magnetorquer(turns=1.0, voltage=1.0, resistance=1.0, width=0.1, length=0.2)
    assert coil.coil_area() == 0.020000000000000004
    assert coil.target_current(0.01) * 127 < 63.5
    assert coil.dipole_moment_to_current(0.01 * AM2) == 63


def test_exact_half_rounds_away_from_zero_through_the_coil():
    """B-Dot Strategy: an exact 62.5 level (1 m² coil, 1 turn, 1 A max) becomes 63, −62.5 → −63."""
    coil = Magnetorquer(turns=1.0, voltage=1.0, resistance=1.0, width=1.0, length=1.0)
    request = 62.5 / 127
    assert request * 127 == 62.5  # really a half case
    assert coil.dipole_moment_to_current(request) == 63
    assert coil.dipole_moment_to_current(-request) == -63


@pytest.mark.parametrize("kwargs", [
    dict(turns=0.0), dict(width=0.0), dict(resistance=0.0), dict(voltage=0.0),
    dict(resistance=float("nan")), dict(voltage=-3.3),
])
def test_degenerate_coils_give_no_drive(kwargs):
    """B-Dot Strategy: zero turns/area/resistance (and nonsense electrical values) give level 0."""
    base = dict(turns=96.0, voltage=3.3, resistance=13.0, width=0.045, length=0.053)
    base.update(kwargs)
    assert Magnetorquer(**base).dipole_moment_to_current(0.03) == 0


@pytest.mark.parametrize("request_am2", [float("nan"), float("inf"), float("-inf")])
def test_non_finite_requests_give_no_drive(request_am2):
    """B-Dot Strategy: NaN/inf dipoles never raise and never drive the coil."""
    assert x_plus_coil().dipole_moment_to_current(request_am2) == 0


def test_circular_shape_ignores_rectangle_dimensions():
    """B-Dot Strategy: a CIRCULAR coil's area comes from its diameter only."""
    coil = Magnetorquer(turns=1.0, voltage=1.0, resistance=1.0, shape=CoilShape.CIRCULAR,
                        diameter=2.0, width=5.0, length=5.0)
    assert coil.coil_area() == math.pi


def test_the_ground_enum_and_the_coil_arithmetic_share_one_coil_shape():
    """COIL-ONE-002: Components.CoilShape (the ground's) has exactly the coil arithmetic's names and
    values, and the manager's coil defaults are the flight coil layout's."""
    from detumble.components.detumble_manager import DetumbleManager
    from detumble.components.types import CoilShape as GroundShape
    from detumble.control.coil_layout import FLIGHT_XY_COIL, FLIGHT_Z_COIL, CoilShape

    assert {m.name: m.value for m in GroundShape} == {m.name: m.value for m in CoilShape}
    params = {p.name: p.default for p in DetumbleManager("m", base_id=0x1000).spec.params}
    assert params["X_TURNS"] == FLIGHT_XY_COIL.turns and params["Z_TURNS"] == FLIGHT_Z_COIL.turns
    assert params["Y_MINUS_WIDTH"] == FLIGHT_XY_COIL.width_m and params["Z_MINUS_DIAMETER"] == FLIGHT_Z_COIL.diameter_m
    assert params["Z_MINUS_SHAPE"] == GroundShape.CIRCULAR and params["X_PLUS_SHAPE"] == GroundShape.RECTANGULAR
