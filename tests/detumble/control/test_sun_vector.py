"""SUNV-001…005: the Sun vector from six face light sensors (detumble.control.sun_vector)."""

from __future__ import annotations

import math
import random

import pytest

from detumble.control.sun_vector import CUBE_NORMALS_B, estimate_sun_vector, propagate_body_vector


def _readings(s, e=1.0):
    return [e * max(0.0, n[0] * s[0] + n[1] * s[1] + n[2] * s[2]) for n in CUBE_NORMALS_B]


def _angle_deg(a, b) -> float:
    d = max(-1.0, min(1.0, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]))
    return math.degrees(math.acos(d))


def test_closed_form_cases_are_exact():
    """SUNV-001: noise-free cosine readings give the Sun exactly: three faces lit ((1,1,1)/√3 in every octant),
    two faces, one face (the Sun along a normal: the unseen axes are 0); |s| = 1; the full-Sun scale cancels."""
    k = 1.0 / math.sqrt(3.0)
    for sx in (1, -1):
        for sy in (1, -1):
            for sz in (1, -1):
                s = (sx * k, sy * k, sz * k)
                est = estimate_sun_vector(_readings(s, 120_000.0), 120_000.0)
                assert est.valid and est.lit == 3 and est.magnitude == pytest.approx(1.0)
                assert est.direction == pytest.approx(s, abs=1e-12)
    two = (math.cos(0.4), 0.0, -math.sin(0.4))
    est = estimate_sun_vector(_readings(two), 1.0)
    assert est.lit == 2 and est.direction == pytest.approx(two, abs=1e-12)
    for n in CUBE_NORMALS_B:
        est = estimate_sun_vector(_readings(n), 1.0)
        assert est.lit == 1 and est.valid and est.direction == pytest.approx(n, abs=1e-12)


def test_nothing_lit_or_the_wrong_brightness_is_not_valid():
    """SUNV-002: eclipse (all dark) gives no direction and valid False; a reading far from a cosine detector's unit
    magnitude (half the Sun: albedo-like, or a wrong full scale) keeps a direction but is not valid."""
    dark = estimate_sun_vector([0.0] * 6, 1.0)
    assert not dark.valid and dark.lit == 0 and dark.direction == (0.0, 0.0, 0.0)
    s = (0.6, 0.0, 0.8)
    dim = estimate_sun_vector(_readings(s, 0.5), 1.0)
    assert not dim.valid and dim.direction == pytest.approx(s) and dim.magnitude == pytest.approx(0.5)
    assert not estimate_sun_vector([float("nan")] * 6, 1.0).valid


def test_noise_error_matches_the_closed_form():
    """SUNV-003: with white noise σ (fraction of full Sun) on each reading the angular error's RMS over random Sun
    directions is ≈ √2 σ rad (σ per axis ⟂ ŝ, lit faces; sub-threshold components read 0 add a little):
    σ = 0.5 % → RMS within 0.3…0.8°, and every error below 5°."""
    rng = random.Random(5)
    sigma = 0.005
    errors = []
    for _ in range(2000):
        v = [rng.gauss(0.0, 1.0) for _ in range(3)]
        n = math.sqrt(sum(c * c for c in v))
        s = tuple(c / n for c in v)
        r = [max(0.0, x + rng.gauss(0.0, sigma)) for x in _readings(s)]
        est = estimate_sun_vector(r, 1.0)
        assert est.valid
        errors.append(_angle_deg(est.direction, s))
    rms = math.sqrt(sum(e * e for e in errors) / len(errors))
    assert math.degrees(math.sqrt(2.0) * sigma) * 0.7 <= rms <= 0.8
    assert max(errors) < 5.0


def test_bad_inputs_are_refused():
    """SUNV-004: a full scale that is not positive and finite, or readings that do not match the normals, are
    refused naming what is wrong."""
    with pytest.raises(ValueError, match="full_scale"):
        estimate_sun_vector([0.0] * 6, 0.0)
    with pytest.raises(ValueError, match="5 readings for 6"):
        estimate_sun_vector([0.0] * 5, 1.0)


def test_propagation_is_the_exact_rotation():
    """SUNV-005: an inertially fixed vector seen from a body turning at ω for dt turns by −|ω| dt about ω in B
    (quarter turn about z: x → −y); the length stays 1; zero rate leaves it alone."""
    v = propagate_body_vector((1.0, 0.0, 0.0), (0.0, 0.0, 0.5), math.pi)
    assert v == pytest.approx((0.0, -1.0, 0.0), abs=1e-12)
    w = propagate_body_vector((0.6, 0.0, 0.8), (0.01, -0.02, 0.03), 7.0)
    assert math.sqrt(sum(c * c for c in w)) == pytest.approx(1.0, abs=1e-12)
    # about an axis along the vector nothing moves
    assert propagate_body_vector((0.6, 0.0, 0.8), (0.06, 0.0, 0.08), 3.0) == pytest.approx((0.6, 0.0, 0.8))
    assert propagate_body_vector((0.0, 1.0, 0.0), (0.0, 0.0, 0.0), 1.0) == (0.0, 1.0, 0.0)


def test_cube_difference_equals_least_squares_with_one_face_a_pair_and_keeps_both_lit():
    """SUNVEC-010: on the cube, with at most one face of each opposite pair lit, the difference form gives the same
    floats as the general least squares (the normals passed as an equal tuple that is not CUBE_NORMALS_B); with both
    faces of a pair lit (the Sun on +Z, albedo 0.2 on −Z) it keeps the difference, 0.8, where least squares gives
    half of it (0.4: |s| then reads as no Sun)."""
    rng = random.Random(7)
    general = tuple(tuple(n) for n in CUBE_NORMALS_B)
    assert general is not CUBE_NORMALS_B
    for _ in range(200):
        r = [0.0] * 6
        for axis in range(3):
            r[2 * axis + rng.randrange(2)] = rng.uniform(0.0, 1.0)
        assert estimate_sun_vector(r, 1.0) == estimate_sun_vector(r, 1.0, normals=general)
    both = [0.0, 0.0, 0.0, 0.0, 1.0, 0.2]
    est = estimate_sun_vector(both, 1.0)
    assert est.magnitude == pytest.approx(0.8) and est.valid and est.direction == pytest.approx((0.0, 0.0, 1.0))
    assert estimate_sun_vector(both, 1.0, normals=general).magnitude == pytest.approx(0.4)
