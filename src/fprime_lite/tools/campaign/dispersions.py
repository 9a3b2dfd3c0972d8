"""Dispersions: random values of a campaign key, drawn per run from the run's own generator.

Each is written ``{dist: NAME, ...}``; the fields of each kind:

============================ =========================================================================
``normal``                   ``mean``, ``std`` (numbers, or lists of equal length for a vector);
                             optional ``clip: [low, high]``
``uniform``                  ``low``, ``high`` (numbers, or lists of equal length)
``choice``                   ``values``: a list; one of them, each equally likely
``random_vector``            ``magnitude``: a number or a scalar dispersion; the direction is uniform
                             on the sphere (e.g. an initial rate of 5–180 °/s about a random axis)
``random_rotation``          no fields: a uniformly distributed attitude quaternion (scalar first)
``angle_about_random_axis``  ``angle_deg``: a number or a scalar dispersion; optional ``nominal``
                             quaternion (scalar first, default identity). The result is
                             ``nominal ⊗ δq``: δq turns by the angle about a uniformly random axis
``inertia``                  ``nominal``: 3 principal moments or a 3×3 matrix (kg·m²);
                             ``moment_std``: relative 1-σ of each principal moment (0.05 = 5 %);
                             optional ``axis_angle_deg`` (number or scalar dispersion): the principal
                             axes turned by that angle about a random axis. Returns a 3×3 matrix
============================ =========================================================================

Values come back as plain Python floats and lists, so they go into a scenario ``--set`` and a
results row unchanged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from fprime_lite.model.errors import did_you_mean

__all__ = ["Dispersion", "parse_dispersion", "DISTRIBUTIONS"]

DISTRIBUTIONS = {
    "normal": ({"mean", "std"}, {"clip"}),
    "uniform": ({"low", "high"}, set()),
    "choice": ({"values"}, set()),
    "random_vector": ({"magnitude"}, set()),
    "random_rotation": (set(), set()),
    "angle_about_random_axis": ({"angle_deg"}, {"nominal"}),
    "inertia": ({"nominal", "moment_std"}, {"axis_angle_deg"}),
}
SCALAR_DISTRIBUTIONS = ("normal", "uniform", "choice")


@dataclass(frozen=True)
class Dispersion:
    """One dispersed key: ``sample(rng)`` draws its value; ``nominals`` are the values the pre-flight
    check builds a run with (the mean, the middle of a range, each choice…): they do not depend on
    any seed, so whether a campaign starts never depends on the master seed."""

    dist: str
    sample: Callable[[np.random.Generator], Any]
    nominals: tuple = ()


def _is_number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def _numbers_or_vector(value, field: str) -> np.ndarray:
    if _is_number(value):
        return np.array(float(value))
    if isinstance(value, list) and value and all(_is_number(v) for v in value):
        return np.array([float(v) for v in value])
    raise ValueError(f"'{field}' must be a number or a list of numbers")


def _plain(x):
    if isinstance(x, np.ndarray):
        return float(x) if x.ndim == 0 else [_plain(v) for v in x]
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    return float(x)


# Vector arithmetic in plain Python: numpy's ``linalg.norm`` and ``@`` call BLAS, whose kernels (and
# so the last bit of a result) depend on the CPU; these give the same floats on every machine.

def _norm(v) -> float:
    """Euclidean norm, CPU-independent (``math.hypot`` is CPython's own correctly-rounded-ish loop)."""
    return math.hypot(*(float(x) for x in v))


def _unit_vector(rng: np.random.Generator) -> list[float]:
    while True:
        v = [float(x) for x in rng.standard_normal(3)]
        n = _norm(v)
        if n > 1e-9:
            return [x / n for x in v]


def _quat_mul(a, b) -> list[float]:
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return [a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3, a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
            a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1, a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0]


def _matmul(a, b) -> list[list[float]]:
    """3×3 product, each element summed left to right."""
    return [[a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] for j in range(3)] for i in range(3)]


def _transpose(a) -> list[list[float]]:
    return [[a[j][i] for j in range(3)] for i in range(3)]


def _rotation(axis, angle: float) -> list[list[float]]:
    """Rotation matrix turning by ``angle`` rad about the unit ``axis`` (Rodrigues)."""
    x, y, z = axis
    k = [[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]]
    kk = _matmul(k, k)
    s, c1 = math.sin(angle), 1 - math.cos(angle)
    return [[(1.0 if i == j else 0.0) + s * k[i][j] + c1 * kk[i][j] for j in range(3)] for i in range(3)]


def _symmetric_eigen(m) -> tuple[list[float], list[list[float]]]:
    """Eigenvalues (ascending) and eigenvectors (columns) of a symmetric 3×3 matrix, by cyclic Jacobi
    rotations in plain Python (deterministic on every CPU, unlike LAPACK's ``eigh``)."""
    a = [[float(m[i][j]) for j in range(3)] for i in range(3)]
    v = [[1.0 if i == j else 0.0 for j in range(3)] for i in range(3)]
    for _ in range(50):
        off = abs(a[0][1]) + abs(a[0][2]) + abs(a[1][2])
        if off <= 1e-300 or off <= 1e-17 * (abs(a[0][0]) + abs(a[1][1]) + abs(a[2][2])):
            break
        for p, q in ((0, 1), (0, 2), (1, 2)):
            if a[p][q] == 0.0:
                continue
            theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q])
            t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1.0))
            c = 1.0 / math.sqrt(t * t + 1.0)
            s = t * c
            for k in range(3):  # a ← Jᵀ a J, v ← v J
                akp, akq = a[k][p], a[k][q]
                a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
            for k in range(3):
                apk, aqk = a[p][k], a[q][k]
                a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
            for k in range(3):
                vkp, vkq = v[k][p], v[k][q]
                v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    order = sorted(range(3), key=lambda i: a[i][i])
    return [a[i][i] for i in order], [[v[r][i] for i in order] for r in range(3)]


def _canonical_quat(q) -> list:
    n = _norm(q)
    q = [float(x) / n for x in q]
    return [-x for x in q] if q[0] < 0 else q


def _scalar(value, field: str, where: str) -> tuple[Callable[[np.random.Generator], float], float]:
    """A fixed number or a nested scalar dispersion: (sampler, nominal value)."""
    if _is_number(value):
        v = float(value)
        return (lambda rng: v), v
    if isinstance(value, dict):
        inner = parse_dispersion(value, f"{where}.{field}")
        if inner.dist not in SCALAR_DISTRIBUTIONS:
            raise ValueError(f"'{field}' needs a scalar dispersion ({', '.join(SCALAR_DISTRIBUTIONS)}), "
                             f"not {inner.dist}")
        if not all(_is_number(n) for n in inner.nominals):
            raise ValueError(f"'{field}' must draw numbers")
        return (lambda rng: float(inner.sample(rng))), float(inner.nominals[0])
    raise ValueError(f"'{field}' must be a number or a scalar dispersion such as {{dist: uniform, low: 5, high: 180}}")


def _diagonal_or_matrix(value) -> np.ndarray:
    if isinstance(value, list) and len(value) == 3 and all(_is_number(v) for v in value):
        return np.diag([float(v) for v in value])
    if isinstance(value, list) and len(value) == 3 and all(
            isinstance(r, list) and len(r) == 3 and all(_is_number(v) for v in r) for r in value):
        m = np.array(value, dtype=float)
        if not np.allclose(m, m.T, rtol=1e-9, atol=0):
            raise ValueError("'nominal' inertia must be symmetric")
        return m
    raise ValueError("'nominal' inertia is 3 principal moments [Jxx, Jyy, Jzz] or a 3x3 matrix (kg m^2)")


def parse_dispersion(spec, where: str) -> Dispersion:
    """Build a :class:`Dispersion` from its mapping; ``ValueError`` names the field at fault.

    Unknown fields are refused (a misspelt field would otherwise be silently ignored).
    """
    if not isinstance(spec, dict) or "dist" not in spec:
        raise ValueError(f"a dispersion is a mapping with 'dist' (one of {', '.join(DISTRIBUTIONS)})")
    dist = spec["dist"]
    if dist not in DISTRIBUTIONS:
        hint = " — " + did_you_mean(dist, DISTRIBUTIONS, f"use one of {', '.join(DISTRIBUTIONS)}")
        raise ValueError(f"unknown dist '{dist}'{hint}")
    required, optional = DISTRIBUTIONS[dist]
    fields = set(spec) - {"dist"}
    unknown = fields - required - optional
    if unknown:
        raise ValueError(f"unknown field{'s' if len(unknown) > 1 else ''} {', '.join(sorted(map(str, unknown)))} "
                         f"for dist {dist} (fields: {', '.join(sorted(required | optional)) or 'none'})")
    missing = required - fields
    if missing:
        raise ValueError(f"dist {dist} needs {', '.join(sorted(missing))}")

    if dist == "normal":
        mean, std = _numbers_or_vector(spec["mean"], "mean"), _numbers_or_vector(spec["std"], "std")
        if np.any(std < 0):
            raise ValueError("'std' must be >= 0")
        if std.ndim and mean.ndim and std.shape != mean.shape:
            raise ValueError("'mean' and 'std' lists must have the same length")
        clip = spec.get("clip")
        if clip is not None and not (isinstance(clip, list) and len(clip) == 2 and all(map(_is_number, clip))
                                     and clip[0] <= clip[1]):
            raise ValueError("'clip' must be [low, high] with low <= high")
        shape = np.broadcast(mean, std).shape

        def sample(rng):
            x = mean + std * rng.standard_normal(shape)
            return _plain(np.clip(x, clip[0], clip[1]) if clip is not None else x)
        middle = np.broadcast_to(mean, shape)
        return Dispersion(dist, sample, (_plain(np.clip(middle, clip[0], clip[1]) if clip is not None else middle),))
    if dist == "uniform":
        low, high = _numbers_or_vector(spec["low"], "low"), _numbers_or_vector(spec["high"], "high")
        if low.ndim and high.ndim and low.shape != high.shape:
            raise ValueError("'low' and 'high' lists must have the same length")
        if np.any(high < low):
            raise ValueError("'high' must be >= 'low'")
        shape = np.broadcast(low, high).shape
        return Dispersion(dist, lambda rng: _plain(low + (high - low) * rng.random(shape)),
                          (_plain(np.broadcast_to(low + (high - low) * 0.5, shape)),))
    if dist == "choice":
        values = spec["values"]
        if not isinstance(values, list) or not values:
            raise ValueError("'values' must be a non-empty list")
        return Dispersion(dist, lambda rng: values[int(rng.integers(len(values)))], tuple(values))
    if dist == "random_vector":
        magnitude, m0 = _scalar(spec["magnitude"], "magnitude", where)

        def sample(rng):
            m = magnitude(rng)
            return [m * x for x in _unit_vector(rng)]
        return Dispersion(dist, sample, ([m0, 0.0, 0.0],))
    if dist == "random_rotation":
        def sample(rng):
            while True:
                q = [float(x) for x in rng.standard_normal(4)]
                if _norm(q) > 1e-9:
                    return _canonical_quat(q)
        return Dispersion(dist, sample, ([1.0, 0.0, 0.0, 0.0],))
    if dist == "angle_about_random_axis":
        angle, angle0 = _scalar(spec["angle_deg"], "angle_deg", where)
        nominal = np.array(_numbers_or_vector(spec.get("nominal", [1.0, 0.0, 0.0, 0.0]), "nominal"))
        if nominal.shape != (4,) or abs(_norm(nominal) - 1.0) > 1e-6:
            raise ValueError("'nominal' must be a unit quaternion [q0, q1, q2, q3] (scalar first)")

        def sample(rng):
            a = math.radians(angle(rng))
            e = _unit_vector(rng)
            dq = [math.cos(a / 2)] + [math.sin(a / 2) * x for x in e]
            return _canonical_quat(_quat_mul([float(x) for x in nominal], dq))
        a0 = math.radians(angle0)
        return Dispersion(dist, sample, (_canonical_quat(_quat_mul([float(x) for x in nominal],
                                                                   [math.cos(a0 / 2), math.sin(a0 / 2), 0.0, 0.0])),))
    # inertia
    nominal = _diagonal_or_matrix(spec["nominal"])
    std = spec["moment_std"]
    if not (_is_number(std) and std >= 0):
        raise ValueError("'moment_std' must be a number >= 0 (relative: 0.05 is 5 %)")
    axis_angle, _ = _scalar(spec.get("axis_angle_deg", 0.0), "axis_angle_deg", where)
    moments, axes = _symmetric_eigen(nominal.tolist())

    def sample_inertia(rng):
        scaled = [m * (1.0 + std * float(g)) for m, g in zip(moments, rng.standard_normal(3), strict=True)]
        turn = _rotation(_unit_vector(rng), math.radians(axis_angle(rng)))
        v = _matmul(turn, axes)
        j = _matmul([[v[i][k] * scaled[k] for k in range(3)] for i in range(3)], _transpose(v))
        return [[0.5 * (j[i][k] + j[k][i]) for k in range(3)] for i in range(3)]
    return Dispersion(dist, sample_inertia, (_plain(nominal),))
