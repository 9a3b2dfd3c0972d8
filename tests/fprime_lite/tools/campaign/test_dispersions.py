"""Dispersions: each distribution checked against its defining property on many draws."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fprime_lite.tools.campaign.dispersions import parse_dispersion

N = 4000


def _draws(spec, n=N, seed=1):
    d = parse_dispersion(spec, "k")
    rng = np.random.default_rng(seed)
    return [d.sample(rng) for _ in range(n)]


def test_normal_and_uniform_moments():
    """CAMP-020: normal mean/std and uniform bounds/mean within 4 standard errors (N = 4000)."""
    x = np.array(_draws({"dist": "normal", "mean": 2.0, "std": 0.5}))
    assert abs(x.mean() - 2.0) < 4 * 0.5 / math.sqrt(N)
    assert abs(x.std() - 0.5) < 4 * 0.5 / math.sqrt(2 * N)
    v = np.array(_draws({"dist": "normal", "mean": [0, 10, 0], "std": [1, 0, 2], "clip": [-3, 11]}))
    assert v.shape == (N, 3) and np.all(v[:, 1] == 10) and v.min() >= -3
    u = np.array(_draws({"dist": "uniform", "low": 5, "high": 180}))
    assert u.min() >= 5 and u.max() <= 180 and abs(u.mean() - 92.5) < 4 * 175 / math.sqrt(12 * N)


def test_random_vector_has_its_magnitude_and_an_isotropic_direction():
    """CAMP-021: |v| is the magnitude drawn; the mean direction is 0 within 4/sqrt(3N) per axis."""
    v = np.array(_draws({"dist": "random_vector", "magnitude": {"dist": "uniform", "low": 5, "high": 180}}))
    n = np.linalg.norm(v, axis=1)
    assert n.min() >= 5 and n.max() <= 180
    e = v / n[:, None]
    assert np.all(np.abs(e.mean(axis=0)) < 4 / math.sqrt(3 * N))


def test_rotations_are_unit_quaternions_and_the_angle_is_kept():
    """CAMP-022: random rotations are unit, scalar-first with q0 >= 0, uniform (E[q0] = 4/(3π): q0 has
    density (2/π)·sqrt(1 − q0²) on S³); angle_about_random_axis turns the nominal by exactly the angle drawn."""
    q = np.array(_draws({"dist": "random_rotation"}))
    assert np.allclose(np.linalg.norm(q, axis=1), 1, atol=1e-12) and q[:, 0].min() >= 0
    sd = math.sqrt(0.25 - (4 / (3 * math.pi)) ** 2)
    assert abs(q[:, 0].mean() - 4 / (3 * math.pi)) < 4 * sd / math.sqrt(N)
    nominal = [math.cos(0.3), 0.0, math.sin(0.3), 0.0]
    p = np.array(_draws({"dist": "angle_about_random_axis", "angle_deg": 10, "nominal": nominal}, n=200))
    angle = 2 * np.degrees(np.arccos(np.clip(np.abs(p @ np.array(nominal)), -1, 1)))
    assert np.allclose(angle, 10, atol=1e-6)


def test_inertia_keeps_symmetry_and_scales_its_moments():
    """CAMP-023: a dispersed inertia is symmetric; with no axis turn its moments are the nominal
    ones times (1 + 5 % σ); with a 3° turn its eigenvalues are unchanged by the rotation."""
    nominal = [2.2e-3, 2.15e-3, 2.05e-3]
    m = np.array(_draws({"dist": "inertia", "nominal": nominal, "moment_std": 0.05}, n=2000))
    assert np.allclose(m, np.transpose(m, (0, 2, 1)), atol=0)
    ratio = np.diagonal(m, axis1=1, axis2=2) / np.array(nominal)
    assert abs(ratio.mean() - 1) < 4 * 0.05 / math.sqrt(6000) and abs(ratio.std() - 0.05) < 0.005
    r = np.array(_draws({"dist": "inertia", "nominal": nominal, "moment_std": 0.0, "axis_angle_deg": 3}, n=50))
    assert np.allclose(np.linalg.eigvalsh(r), sorted(nominal), rtol=1e-12)
    assert np.abs(r[:, 0, 1]).max() > 1e-7  # the axes did turn


def test_bad_dispersions_say_what_is_wrong():
    """CAMP-024: unknown fields, missing fields and non-scalar nested dispersions are refused."""
    with pytest.raises(ValueError, match="unknown field stdev for dist normal"):
        parse_dispersion({"dist": "normal", "mean": 0, "stdev": 1}, "k")
    with pytest.raises(ValueError, match="needs high"):
        parse_dispersion({"dist": "uniform", "low": 0}, "k")
    with pytest.raises(ValueError, match="needs a scalar dispersion"):
        parse_dispersion({"dist": "random_vector", "magnitude": {"dist": "random_rotation"}}, "k")
