"""The Earth's albedo on the face light sensors, predicted on board and taken out of the Sun vector (plain floats;
no framework import).

Why: the Earth's reflected light reaches every face that sees the Earth and pulls the light-sensor Sun vector
toward nadir (with a Bond albedo of 0.30 the median error is ~7°, docs/studies/sun_safe.md). The light sensors alone
cannot tell that light from the Sun's (on a cube the difference of opposite faces is ``ŝ + A ê``, ê the nadir in B,
and the readings leave ê free on a cone about it: the Sun-pointing case, where the side faces see mostly the Earth,
is exactly the unresolved one). What makes it removable is an estimate of ê in B, which needs the attitude about
the Sun line: here from the magnetometer.

The model (the same stated model the simulated sensors use, ``sim.sun_sensors``): the Earth as a point source at
its centre, of illuminance ``A = a (R_E / r)² max(0, r̂·ŝ)`` of the full Sun (:func:`albedo_share`; ``a`` the Bond
albedo, a ground parameter), read by each face with the cosine response toward nadir: ``A max(0, n̂·ê)``.

The estimate (:func:`sun_vector_without_albedo`), iterated ``iterations`` times from the uncorrected Sun vector:

1. TRIAD (:func:`triad_dcm`): the attitude ``C_BN`` from the Sun vector and the measured field (body) against the
   Sun from the ephemeris and the field model at the ephemeris' position (inertial); the Sun first, the field
   fixing the rotation about it.
2. ``ê = C_BN (−r̂)``; each face's expected albedo ``A max(0, n̂·ê)`` subtracted from its reading before the lit
   test, then the Sun vector re-estimated (``control.sun_vector.estimate_sun_vector``).

Error budget (closed form): an error δ in ê leaves at most ``A δ`` in the Sun components, i.e. ≤ 0.26 δ at 500 km
with the Sun overhead, so each pass shrinks the Sun vector's error by that factor: 7° → 1.8° → 0.5° → 0.1°, until
the field's direction error (the magnetometer's bias and noise, the field model) and the albedo model's own error
(a in the real Earth is 0.06 over the ocean to 0.8 over cloud and ice) dominate. The correction is skipped (the
uncorrected estimate returned) when the Sun and the field are within :data:`MIN_TRIAD_ANGLE_DEG` of parallel
(TRIAD undefined) or when the albedo share is 0 (the sub-satellite point dark).

Units: positions m, the field in any one unit (only its direction is used), the Sun vector unit, B body, N inertial.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from detumble.control.sun_vector import (CUBE_NORMALS_B, SUN_LIT_FRACTION, SUN_MAGNITUDE_TOLERANCE, SunVectorEstimate,
                                         estimate_sun_vector, propagate_body_vector)

__all__ = ["AlbedoCorrector", "albedo_share", "triad_dcm", "sun_vector_without_albedo", "MIN_TRIAD_ANGLE_DEG",
           "EARTH_MEAN_ALBEDO", "MAX_CARRY_S"]

Vec3 = tuple[float, float, float]

#: The Earth's mean Bond albedo (the sensors model's 0.30).
EARTH_MEAN_ALBEDO = 0.30
#: deg: below this angle between the Sun and the field TRIAD has no second direction (the magnetometer's ~2°
#: direction error becomes ≥ 11° about the Sun line); the attitude is then carried on the gyro (AlbedoCorrector).
MIN_TRIAD_ANGLE_DEG = 10.0
#: s: the longest the last TRIAD attitude is carried on the gyro (the field within 10° of the Sun line lasts
#: ~5 min twice an orbit on the adcs orbit; an unestimated gyro bias of 0.1 °/s about the Sun line turns it 30° in
#: 300 s, which moves the Sun vector by at most A sin(30°) ≈ 0.12 rad of the albedo share A).
MAX_CARRY_S = 600.0


def _unit(v: Sequence[float]) -> Vec3:
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return (v[0] / n, v[1] / n, v[2] / n)


def _cross(a: Sequence[float], b: Sequence[float]) -> Vec3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def albedo_share(r_N: Sequence[float], sun_N: Sequence[float], albedo: float, earth_radius_m: float) -> float:
    """``a (R_E/r)² max(0, r̂·ŝ)``: the Earth's albedo illuminance toward nadir as a fraction of the full Sun, for
    the position ``r_N`` (m) and the unit Sun direction ``sun_N``."""
    rn = math.sqrt(r_N[0] * r_N[0] + r_N[1] * r_N[1] + r_N[2] * r_N[2])
    elevation = (r_N[0] * sun_N[0] + r_N[1] * sun_N[1] + r_N[2] * sun_N[2]) / rn
    if elevation <= 0.0 or albedo <= 0.0:
        return 0.0
    ratio = earth_radius_m / rn
    return albedo * ratio * ratio * elevation


def triad_dcm(v1_B: Sequence[float], v2_B: Sequence[float], v1_N: Sequence[float],
              v2_N: Sequence[float]) -> tuple[Vec3, Vec3, Vec3] | None:
    """TRIAD: the rotation ``C_BN`` (rows; ``x_B = C_BN x_N``) that maps ``v1_N`` exactly onto ``v1_B`` and puts
    ``v2`` in the same plane. None when either pair is within :data:`MIN_TRIAD_ANGLE_DEG` of parallel."""
    limit = math.sin(math.radians(MIN_TRIAD_ANGLE_DEG))
    frames = []
    for a, b in ((v1_B, v2_B), (v1_N, v2_N)):
        t1 = _unit(a)
        c = _cross(t1, _unit(b))
        if math.sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) < limit:
            return None
        t2 = _unit(c)
        frames.append((t1, t2, _cross(t1, t2)))
    (b1, b2, b3), (n1, n2, n3) = frames
    return tuple(  # type: ignore[return-value]
        tuple(b1[i] * n1[j] + b2[i] * n2[j] + b3[i] * n3[j] for j in range(3)) for i in range(3))


def _without(readings: Sequence[float], full_scale: float, share: float, c_bn, down_N: Vec3, lit_fraction: float,
             magnitude_tolerance: float) -> SunVectorEstimate:
    e = tuple(c_bn[i][0] * down_N[0] + c_bn[i][1] * down_N[1] + c_bn[i][2] * down_N[2] for i in range(3))
    k = share * full_scale
    corrected = [r - k * max(0.0, n[0] * e[0] + n[1] * e[1] + n[2] * e[2])
                 for r, n in zip(readings, CUBE_NORMALS_B, strict=True)]
    return estimate_sun_vector(corrected, full_scale, lit_fraction=lit_fraction,
                               magnitude_tolerance=magnitude_tolerance)


def sun_vector_without_albedo(readings: Sequence[float], full_scale: float, *, share: float, r_N: Sequence[float],
                              sun_N: Sequence[float], field_B: Sequence[float], field_N: Sequence[float],
                              iterations: int = 3, lit_fraction: float = SUN_LIT_FRACTION,
                              magnitude_tolerance: float = SUN_MAGNITUDE_TOLERANCE):
    """``(estimate, C_BN or None)``: the cube's Sun vector (``CUBE_NORMALS_B`` face order) with the Earth's albedo
    ``share`` (fraction of the full Sun toward nadir, :func:`albedo_share`) taken out, ê from TRIAD on the Sun
    vector and the field (module docstring), and the last TRIAD attitude. Without a usable first estimate, with
    ``share`` ≤ 0, or with the Sun and the field near parallel, the uncorrected estimate (and None)."""
    est = estimate_sun_vector(readings, full_scale, lit_fraction=lit_fraction, magnitude_tolerance=magnitude_tolerance)
    if share <= 0.0 or est.lit == 0:
        return est, None
    rn = math.sqrt(r_N[0] * r_N[0] + r_N[1] * r_N[1] + r_N[2] * r_N[2])
    down_N = (-r_N[0] / rn, -r_N[1] / rn, -r_N[2] / rn)
    best, c_bn = est, None
    for _ in range(iterations):
        c = triad_dcm(best.direction, field_B, sun_N, field_N)
        if c is None:
            return best, c_bn
        nxt = _without(readings, full_scale, share, c, down_N, lit_fraction, magnitude_tolerance)
        if nxt.lit == 0:
            return best, c_bn
        best, c_bn = nxt, c
    return best, c_bn


class AlbedoCorrector:
    """:func:`sun_vector_without_albedo` each reading, with the last TRIAD attitude carried on the gyro (at most
    :data:`MAX_CARRY_S`) for the readings where the Sun and the field are too near parallel for TRIAD.

    Args: ``albedo`` the Bond albedo of the model (0: no correction), ``earth_radius_m``."""

    def __init__(self, albedo: float, earth_radius_m: float) -> None:
        if not (math.isfinite(albedo) and 0.0 <= albedo < 1.0):
            raise ValueError(f"the albedo model must be a Bond albedo in [0, 1) (the Earth's mean: 0.30), got {albedo}")
        self.albedo = float(albedo)
        self.earth_radius_m = float(earth_radius_m)
        self._c_bn = None
        self._t_s = 0.0
        self._carried_s = 0.0
        self.carried = 0  #: readings corrected on the carried attitude
        self.applied = False  #: whether the last estimate had the albedo taken out (TRIAD or the carried attitude)

    def reset(self) -> None:
        """Forget the attitude carried on the gyro (the gyro missing: it cannot be carried)."""
        self._c_bn = None
        self._carried_s = 0.0

    def estimate(self, readings: Sequence[float], full_scale: float, t_s: float, *, r_N: Sequence[float],
                 sun_N: Sequence[float], field_B: Sequence[float], field_N: Sequence[float],
                 omega_B: Sequence[float], lit_fraction: float = SUN_LIT_FRACTION,
                 magnitude_tolerance: float = SUN_MAGNITUDE_TOLERANCE) -> SunVectorEstimate:
        """The Sun vector of ``readings`` at time ``t_s`` (s), ``omega_B`` the body rate (rad/s, B) that carries
        the attitude from the previous reading; ``lit_fraction`` and ``magnitude_tolerance`` as
        ``control.sun_vector.estimate_sun_vector`` takes them."""
        share = albedo_share(r_N, sun_N, self.albedo, self.earth_radius_m)
        self.applied = False
        if self._c_bn is not None:  # carry C_BN's columns (N's axes seen in B) on the gyro to now
            dt = t_s - self._t_s
            cols = [propagate_body_vector((self._c_bn[0][j], self._c_bn[1][j], self._c_bn[2][j]),
                                          (omega_B[0], omega_B[1], omega_B[2]), dt) for j in range(3)]
            self._c_bn = tuple(tuple(cols[j][i] for j in range(3)) for i in range(3))
            self._carried_s += dt
        self._t_s = t_s
        est, c = sun_vector_without_albedo(readings, full_scale, share=share, r_N=r_N, sun_N=sun_N, field_B=field_B,
                                           field_N=field_N, lit_fraction=lit_fraction,
                                           magnitude_tolerance=magnitude_tolerance)
        if c is not None:
            self._c_bn, self._carried_s = c, 0.0
            self.applied = True
            return est
        if share <= 0.0 or est.lit == 0 or self._c_bn is None or self._carried_s > MAX_CARRY_S:
            return est
        rn = math.sqrt(r_N[0] * r_N[0] + r_N[1] * r_N[1] + r_N[2] * r_N[2])
        down_N = (-r_N[0] / rn, -r_N[1] / rn, -r_N[2] / rn)
        best = est
        for _ in range(3):  # the carried attitude turned (least rotation) to put the Sun where the light sensors see it
            c_bn = _align(self._c_bn, sun_N, best.direction)
            nxt = _without(readings, full_scale, share, c_bn, down_N, lit_fraction, magnitude_tolerance)
            if nxt.lit == 0:
                return est
            best = nxt
        self._c_bn = c_bn
        self.carried += 1
        self.applied = True
        return best


def _align(c_bn, v_N: Sequence[float], v_B: Sequence[float]):
    """``c_bn`` turned by the least rotation that maps ``c_bn v_N`` onto the unit ``v_B``."""
    p = tuple(c_bn[i][0] * v_N[0] + c_bn[i][1] * v_N[1] + c_bn[i][2] * v_N[2] for i in range(3))
    axis = _cross(p, v_B)
    s = math.sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2])
    if s < 1e-12:
        return c_bn
    angle = math.atan2(s, p[0] * v_B[0] + p[1] * v_B[1] + p[2] * v_B[2])
    # a rotation of the frame by +angle about axis = carrying the columns by the rate axis·angle over −1 s
    w = (-axis[0] / s * angle, -axis[1] / s * angle, -axis[2] / s * angle)
    cols = [propagate_body_vector((c_bn[0][j], c_bn[1][j], c_bn[2][j]), w, 1.0) for j in range(3)]
    return tuple(tuple(cols[j][i] for j in range(3)) for i in range(3))
