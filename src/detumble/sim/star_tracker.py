"""Star tracker: the attitude ``q_BN`` with a boresight-shaped error, sample-and-hold at its rate.

A star tracker measures the directions of stars in its field of view; the attitude about its
boresight is worse determined than across it (the stars' angular spread is small compared with
their distance from the boresight axis), typically by a factor 5-10. The model draws, per
sample, a small rotation error in the body frame::

    delta_theta_B = s_c n1 e1 + s_c n2 e2 + s_b n3 e_bore        (n_k ~ N(0, 1))

with ``e_bore`` the boresight (unit vector in B), ``e1, e2`` two unit vectors across it,
``s_c`` and ``s_b`` the 1-sigma cross-boresight and about-boresight errors (arcsec in the
scenario), and reports ``q_meas = q_BN (x) (1, delta_theta_B / 2)`` normalised, i.e. the
measured body frame B' is B turned by ``delta_theta_B``. An optional constant misalignment
``bias_arcsec`` (a rotation vector in B) is added to every sample.

Samples are taken at ``k / rate_hz`` on the plant's integer-nanosecond grid and held. A sample
is *invalid* (no solution: the held attitude is kept, ``valid`` false) with probability
``dropout_probability``, and always when the body rate exceeds ``max_rate_deg_s`` (star smear;
0 disables that limit), and always when the Sun is within ``sun_exclusion_deg`` of the boresight
and not eclipsed (stray light blinds the tracker; typical baffles give 25-45 deg; 0, the default,
disables it), and always at an instant inside ``outage_s`` (``(start, end)`` s of plant time, end excluded: a
tracker lost and recovered, e.g. for the Sun-safe entry on star-tracker loss; None, the default, none).
``ideal: true`` returns the true attitude at the read time, always valid (no outage).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from detumble.sim.vec import Quat, Vec3, cross, rotate_n_to_b, unit

ARCSEC = math.pi / (180.0 * 3600.0)  #: radians per arcsecond


@dataclass(frozen=True)
class StarTrackerSpec:
    ideal: bool = False
    rate_hz: float = 5.0
    noise_cross_boresight_arcsec: float = 10.0
    noise_about_boresight_arcsec: float = 70.0
    boresight_B: Vec3 = (0.0, 0.0, 1.0)
    bias_arcsec: Vec3 = (0.0, 0.0, 0.0)
    dropout_probability: float = 0.0
    max_rate_deg_s: float = 2.0
    sun_exclusion_deg: float = 0.0
    outage_s: tuple[float, float] | None = None


def cross_axes(boresight: Vec3) -> tuple[Vec3, Vec3]:
    """Two unit vectors completing a right-handed triad ``(e1, e2, boresight)``."""
    b = unit(boresight)
    helper = (1.0, 0.0, 0.0) if abs(b[0]) < 0.9 else (0.0, 1.0, 0.0)
    e1 = unit(cross(helper, b))
    e2 = cross(b, e1)
    return e1, e2


class StarTracker:
    """Sample-and-hold star tracker model. ``sample_q`` / ``sample_valid`` / ``sample_time_ns``."""

    def __init__(self, spec: StarTrackerSpec, seed: int | None = None) -> None:
        if not spec.rate_hz > 0:
            raise ValueError(f"star tracker rate_hz must be positive, got {spec.rate_hz}")
        self.spec = spec
        self.period_ns = int(round(1e9 / spec.rate_hz))
        self.rng = random.Random(seed)
        self.bore = unit(spec.boresight_B)
        self.e1, self.e2 = cross_axes(self.bore)
        self._sc = spec.noise_cross_boresight_arcsec * ARCSEC
        self._sb = spec.noise_about_boresight_arcsec * ARCSEC
        self._bias = tuple(b * ARCSEC for b in spec.bias_arcsec)
        self._max_rate2 = math.radians(spec.max_rate_deg_s) ** 2 if spec.max_rate_deg_s > 0 else math.inf
        self._sun_cos = math.cos(math.radians(spec.sun_exclusion_deg)) if spec.sun_exclusion_deg > 0 else None
        self._outage_ns = (None if spec.outage_s is None
                           else (int(round(spec.outage_s[0] * 1e9)), int(round(spec.outage_s[1] * 1e9))))
        self.sample_q: Quat = (1.0, 0.0, 0.0, 0.0)
        self.sample_valid = False
        self.sample_time_ns = -1
        self.samples = 0
        self.dropouts = 0
        self.blinded = 0  # samples lost to the Sun in the exclusion cone (counted in dropouts too)

    def latest_instant(self, t0_ns: int, t1_ns: int) -> int | None:
        k = t1_ns // self.period_ns
        tk = k * self.period_ns
        return tk if tk > t0_ns else None

    def error_vector(self) -> Vec3:
        """One draw of the error rotation vector in B, rad (bias included)."""
        g = self.rng.gauss
        n1, n2, n3 = g(0.0, 1.0), g(0.0, 1.0), g(0.0, 1.0)
        sc, sb = self._sc, self._sb
        e1, e2, eb, bias = self.e1, self.e2, self.bore, self._bias
        return (sc * n1 * e1[0] + sc * n2 * e2[0] + sb * n3 * eb[0] + bias[0],
                sc * n1 * e1[1] + sc * n2 * e2[1] + sb * n3 * eb[1] + bias[1],
                sc * n1 * e1[2] + sc * n2 * e2[2] + sb * n3 * eb[2] + bias[2])

    @property
    def needs_sun(self) -> bool:
        """Whether :meth:`measure` uses the Sun's direction (a Sun exclusion angle is set)."""
        return self._sun_cos is not None

    def sun_blinds(self, q_BN: Quat, sun_N: Vec3 | None) -> bool:
        """True when the unit Sun direction ``sun_N`` (N; None: eclipsed) is within the exclusion angle of the
        boresight at the attitude ``q_BN``."""
        if self._sun_cos is None or sun_N is None:
            return False
        s_B = rotate_n_to_b(q_BN, sun_N)
        b = self.bore
        return s_B[0] * b[0] + s_B[1] * b[1] + s_B[2] * b[2] > self._sun_cos

    def measure(self, q_BN: Quat, omega_B: Vec3, sun_N: Vec3 | None = None,
                t_ns: int | None = None) -> tuple[Quat, bool]:
        """One sample: ``(q_meas, valid)``; an invalid sample keeps the held attitude. ``sun_N``: the unit Sun
        direction (N) when it is not eclipsed, for the exclusion angle; ``t_ns``: the sample's plant time, for the
        outage window."""
        self.samples += 1
        s = self.spec
        out = self._outage_ns
        if out is not None and t_ns is not None and out[0] <= t_ns < out[1]:
            self.dropouts += 1
            return self.sample_q, False
        if self.sun_blinds(q_BN, sun_N):
            self.blinded += 1
            self.dropouts += 1
            return self.sample_q, False
        w2 = omega_B[0] ** 2 + omega_B[1] ** 2 + omega_B[2] ** 2
        if w2 > self._max_rate2 or (s.dropout_probability > 0.0 and self.rng.random() < s.dropout_probability):
            self.dropouts += 1
            return self.sample_q, False
        d = self.error_vector()
        p0, p1, p2, p3 = q_BN
        e1, e2, e3 = 0.5 * d[0], 0.5 * d[1], 0.5 * d[2]
        # q_BN (x) (1, e)
        q = (p0 - p1 * e1 - p2 * e2 - p3 * e3,
             p1 + p0 * e1 + p2 * e3 - p3 * e2,
             p2 + p0 * e2 - p1 * e3 + p3 * e1,
             p3 + p0 * e3 + p1 * e2 - p2 * e1)
        n = 1.0 / math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
        return (q[0] * n, q[1] * n, q[2] * n, q[3] * n), True

    def latch(self, t0_ns: int, t1_ns: int, s0, s1, sun_N: Vec3 | None = None) -> None:
        """Take the sample due in (t0, t1] from the plant states at the step's ends (``sun_N``: as :meth:`measure`)."""
        tk = self.latest_instant(t0_ns, t1_ns)
        if tk is None:
            return
        f = (tk - t0_ns) / (t1_ns - t0_ns) if t1_ns > t0_ns else 1.0
        if s0[0] * s1[0] + s0[1] * s1[1] + s0[2] * s1[2] + s0[3] * s1[3] < 0.0:
            s1 = (-s1[0], -s1[1], -s1[2], -s1[3]) + tuple(s1[4:7])
        q = tuple(s0[i] + f * (s1[i] - s0[i]) for i in range(4))
        n = 1.0 / math.sqrt(sum(x * x for x in q))
        w = tuple(s0[4 + i] + f * (s1[4 + i] - s0[4 + i]) for i in range(3))
        q_meas, valid = self.measure((q[0] * n, q[1] * n, q[2] * n, q[3] * n), w, sun_N, tk)
        self.sample_q, self.sample_valid, self.sample_time_ns = q_meas, valid, tk
