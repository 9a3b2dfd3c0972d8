"""The Sun's direction in the body frame from coarse light sensors (plain floats; no framework import).

Each sensor ``i`` on a face with outward unit normal ``n̂_i`` reads ``r_i = E max(0, n̂_i·ŝ) + noise`` (a cosine
detector; ``E`` the full-Sun reading). :func:`estimate_sun_vector` takes the faces whose reading is above
``lit_fraction × E`` as lit, where the model is linear, and solves the least-squares problem over them:

    minimise Σ_lit (r_i / E − n̂_iᵀ s)²  ⇒  (Σ n̂_i n̂_iᵀ) s = Σ n̂_i r_i / E.

Where the lit normals do not span three dimensions (the Sun along a face normal: one face lit) the unseen
directions are set to 0 (the minimum-norm solution: the unlit faces say the Sun's component there is below the
threshold). On the cube faces (``CUBE_NORMALS_B``) ``s`` is the difference of opposite faces' readings: the least
squares solution when one face of a pair is lit, and kept when both are (light from two sides, e.g. Earth albedo
on the face opposite the Sun; least squares would halve the difference and the magnitude test reject it).
The direction is ``ŝ = s/|s|``; it is **valid** when at least one face is lit and ``|s|`` lies within
``magnitude_tolerance`` of 1
(a reading scaled by ``E`` that is not near unit length is no Sun seen by cosine detectors: eclipse, Earth
albedo, a failed sensor). ``E`` is the full-Sun reading at the present Earth–Sun distance (±3.4 % over a year;
the direction does not depend on it).

Errors (closed form, cube faces): white noise σ (fraction of E) on each lit face tilts ŝ by about σ rad per
axis ⟂ ŝ; a component of ŝ below the threshold t is read as 0, an error of at most ``asin(t)`` per axis.
"""

from __future__ import annotations

import math
from typing import NamedTuple, Sequence

from detumble.control.mat3 import inv3

__all__ = ["SunVectorEstimate", "estimate_sun_vector", "CUBE_NORMALS_B", "propagate_body_vector", "SUN_LIT_FRACTION",
           "SUN_MAGNITUDE_TOLERANCE"]

Vec3 = tuple[float, float, float]

#: Outward normals of the six faces of a cube in B: X+, X−, Y+, Y−, Z+, Z− (the PROVES face order).
CUBE_NORMALS_B: tuple[Vec3, ...] = ((1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, -1.0, 0.0),
                                    (0.0, 0.0, 1.0), (0.0, 0.0, -1.0))

#: A face is lit above this fraction of the full-Sun reading: 4σ of the sensors' 0.5 % noise, so a dark face is
#: taken as lit in 3e-5 of its readings; a Sun component below it (1.15°) is read as 0. At 5 % (10σ) that dead
#: zone was 2.9° and sat exactly where Sun pointing holds the Sun (the faces beside the pointed one see grazing
#: light): median error 2.8° there (docs/studies/sun_safe.md).
SUN_LIT_FRACTION = 0.02
#: |s| may differ from 1 by this much and the estimate is still valid: the Earth–Sun distance (±3.4 %) and the
#: sensors' gain spread (2 % 1σ) stay inside; a dark sky or a half-lit one does not.
SUN_MAGNITUDE_TOLERANCE = 0.25

_RANK_TOL = 1e-6  # an eigen-direction of Σ n nᵀ weaker than this is not seen by any lit face


class SunVectorEstimate(NamedTuple):
    """``direction`` (unit, B; (0, 0, 0) when nothing is lit), ``valid``, ``lit`` (faces above the
    threshold) and ``magnitude`` (|s|: 1 for the full Sun on cosine detectors)."""

    direction: Vec3
    valid: bool
    lit: int
    magnitude: float


def estimate_sun_vector(readings: Sequence[float], full_scale: float, *, lit_fraction: float = SUN_LIT_FRACTION,
                        magnitude_tolerance: float = SUN_MAGNITUDE_TOLERANCE,
                        normals: Sequence[Vec3] = CUBE_NORMALS_B) -> SunVectorEstimate:
    """Least-squares Sun direction from ``readings`` (one per normal, the sensor's unit, e.g. lux) with
    ``full_scale`` the full-Sun reading in that unit. Readings that are not finite count as unlit.

    Raises ValueError for a ``full_scale`` that is not a positive finite number or readings and normals of
    different lengths."""
    if not (isinstance(full_scale, (int, float)) and math.isfinite(full_scale) and full_scale > 0.0):
        raise ValueError(f"full_scale must be a positive finite number, got {full_scale!r}")
    if len(readings) != len(normals):
        raise ValueError(f"{len(readings)} readings for {len(normals)} sensor normals")
    threshold = lit_fraction * full_scale
    a = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
    b = [0.0, 0.0, 0.0]
    lit = 0
    for r, n in zip(readings, normals, strict=True):
        if not math.isfinite(r) or r <= threshold:
            continue
        lit += 1
        y = r / full_scale
        for i in range(3):
            b[i] += n[i] * y
            for j in range(3):
                a[i][j] += n[i] * n[j]
    if lit == 0:
        return SunVectorEstimate((0.0, 0.0, 0.0), False, 0, 0.0)
    if normals is CUBE_NORMALS_B:
        # the cube: each axis is the difference of its opposite faces' readings. With one face of a pair lit this is
        # the least-squares solution below, float for float; with both lit (light from two sides: Earth albedo on the
        # face opposite the Sun) the least squares would halve the difference, this keeps it
        return _direction(b[0], b[1], b[2], lit, magnitude_tolerance)
    # directions no lit face sees get a unit diagonal and a zero right-hand side: their component is 0
    # (exact for normals along the axes; the cube's case, and the minimum-norm solution there)
    for i in range(3):
        if a[i][i] < _RANK_TOL:
            a[i][i] = 1.0
            b[i] = 0.0
    try:
        inv = inv3(a, 1e-12)
    except ValueError:
        return SunVectorEstimate((0.0, 0.0, 0.0), False, lit, 0.0)
    return _direction(inv[0][0] * b[0] + inv[0][1] * b[1] + inv[0][2] * b[2],
                      inv[1][0] * b[0] + inv[1][1] * b[1] + inv[1][2] * b[2],
                      inv[2][0] * b[0] + inv[2][1] * b[1] + inv[2][2] * b[2], lit, magnitude_tolerance)


def _direction(x: float, y: float, z: float, lit: int, tolerance: float) -> SunVectorEstimate:
    m = math.sqrt(x * x + y * y + z * z)
    if m == 0.0:
        return SunVectorEstimate((0.0, 0.0, 0.0), False, lit, 0.0)
    return SunVectorEstimate((x / m, y / m, z / m), abs(m - 1.0) <= tolerance, lit, m)


def propagate_body_vector(v: Vec3, omega: Vec3, dt: float) -> Vec3:
    """An inertially fixed unit vector seen in B, carried ``dt`` s on the body rate ``omega`` (rad/s, B):
    ``v̇ = −ω × v`` (exact rotation by the angle |ω| dt about ω, so it stays unit)."""
    wx, wy, wz = omega
    w = math.sqrt(wx * wx + wy * wy + wz * wz)
    if w * dt == 0.0:
        return v
    ax, ay, az = wx / w, wy / w, wz / w
    angle = -w * dt  # the body turns by +angle: the fixed vector turns by −angle in B (Rodrigues)
    c, s = math.cos(angle), math.sin(angle)
    x, y, z = v
    d = ax * x + ay * y + az * z
    cx, cy, cz = ay * z - az * y, az * x - ax * z, ax * y - ay * x
    return (x * c + cx * s + ax * d * (1.0 - c), y * c + cy * s + ay * d * (1.0 - c),
            z * c + cz * s + az * d * (1.0 - c))
