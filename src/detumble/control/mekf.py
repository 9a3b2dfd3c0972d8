"""A multiplicative extended Kalman filter (MEKF) for attitude and gyro bias (plain floats, no
framework import, no numpy).

State: the reference attitude ``q̂ = q_BN`` (scalar first) and gyro bias ``b̂`` (rad/s, B); the
filter's 6 error states are ``x = (δθ, δb)``, with the truth ``q = q̂ ⊗ (1, δθ/2)`` (δθ a small
rotation vector in B, rad) and ``b = b̂ + δb``. ``P`` is their 6×6 covariance (rad², rad²/s,
rad²/s²). The gyro is an input, not a measurement (Lefferts, Markley & Shuster 1982; Markley &
Crassidis 2014, ch. 7):

    ω̂ = ω_gyro − b̂;  q̂ ← q̂ ⊗ exp(½ ω̂ Δt)
    Φ = [[R(−ω̂Δt), −Δt I], [0, I]],   P ← Φ P Φᵀ + Q
    Q = [[σ_a² + σ_u² Δt³/3, −σ_u² Δt²/2], [−σ_u² Δt²/2, σ_u² Δt]] ⊗ I₃

``σ_a²`` is the variance of the angle increment over ``Δt``: the controller propagates with the
mean of ``n`` gyro readings, each with white noise ``σ_g`` (rad/s, 1σ per axis; the sensor's noise
density over its bandwidth plus its quantisation), so ``σ_a² = σ_g² Δt² / n``. ``σ_u`` is the bias
random walk (rad/s/√s).

Star-tracker update: a solution ``q_m`` taken ``age`` s ago (the tracker holds its last image) is
carried to now on ``ω̂``; the residual ``r = 2 vec(q̂⁻¹ ⊗ q_m)`` (shortest path) has ``H = [I 0]``
and noise ``R = σ_c² I + (σ_b² − σ_c²) e eᵀ`` (``e`` the boresight in B, ``σ_c``/``σ_b`` 1σ across
and about it, rad) plus ``σ_g² age² / n`` for the carrying. When the image lies inside the last
propagation step (``age ≤ Δt``) the carrying and the propagation used the same gyro mean, so the
residual's noise is correlated with the state error by ``M = −σ_g² Δt·age / n`` per axis; the gain
accounts for it (``K = (P Hᵀ + M) S⁻¹``, ``S = H P Hᵀ + R + H M + Mᵀ Hᵀ``). Then
``P ← P − K S Kᵀ`` (symmetrised) and the error is folded into ``q̂``, ``b̂`` (the reset).

A residual larger than ``reinit_angle_rad``, or an attitude 3σ larger than it (after a long time
on the gyro alone: the tracker has no solution above 2 °/s), re-initialises the attitude on the
measurement (``P_θθ = R``, no attitude–bias correlation); the bias and its covariance are kept.
"""

from __future__ import annotations

import math

from detumble.control.mat3 import det3, inv3
from detumble.control.quaternion import Quat, Vec3, quat_conj, quat_mul, quat_normalize, quat_shortest

__all__ = ["Mekf"]

Mat = list[list[float]]


def _zeros(n: int, m: int) -> Mat:
    return [[0.0] * m for _ in range(n)]


def _matmul(a: Mat, b: Mat) -> Mat:
    """``a b``. Each element is ``sum`` of its products in index order, as a generator over
    ``zip(row, col)`` would give (the same floats on every Python: 3.12's compensated ``sum`` too);
    the products are spelled out for the filter's inner dimensions 3 and 6 (a generator costs
    about four times as much)."""
    bt = list(zip(*b, strict=True))
    n = len(b)
    if n == 6:
        return [[sum((r0 * c[0], r1 * c[1], r2 * c[2], r3 * c[3], r4 * c[4], r5 * c[5])) for c in bt]
                for r0, r1, r2, r3, r4, r5 in a]
    if n == 3:
        return [[sum((r0 * c[0], r1 * c[1], r2 * c[2])) for c in bt] for r0, r1, r2 in a]
    return [[sum(x * y for x, y in zip(row, col, strict=True)) for col in bt] for row in a]


def _transpose(a: Mat) -> Mat:
    return [list(r) for r in zip(*a, strict=True)]


def _inv_spd3(m: Mat):
    """``m⁻¹`` (rows as tuples) of the innovation covariance; ValueError unless ``det m > 0``."""
    if not det3(m) > 0.0:  # S is a covariance: positive definite or something is badly wrong
        raise ValueError(f"innovation covariance is not positive definite (det {det3(m):g})")
    return inv3(m)


def _rotation_transpose(w: Vec3, dt: float) -> Mat:
    """``exp(−[w×] dt)`` by Rodrigues: how a body-frame error vector is carried over the step."""
    n = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    phi = n * dt
    if phi < 1e-12:
        return [[1.0, w[2] * dt, -w[1] * dt], [-w[2] * dt, 1.0, w[0] * dt], [w[1] * dt, -w[0] * dt, 1.0]]
    u = (w[0] / n, w[1] / n, w[2] / n)
    s, c = math.sin(phi), math.cos(phi)
    k = 1.0 - c
    # R(φ about u) = c I + s [u×] + k u uᵀ; its transpose flips the sign of the [u×] part
    return [[c + k * u[0] * u[0], k * u[0] * u[1] + s * u[2], k * u[0] * u[2] - s * u[1]],
            [k * u[1] * u[0] - s * u[2], c + k * u[1] * u[1], k * u[1] * u[2] + s * u[0]],
            [k * u[2] * u[0] + s * u[1], k * u[2] * u[1] - s * u[0], c + k * u[2] * u[2]]]


def _propagate(q: Quat, w: Vec3, dt: float) -> Quat:
    """``q ⊗ exp(½ w dt)``."""
    n = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    if n == 0.0 or dt == 0.0:
        return q
    half = 0.5 * n * dt
    s = math.sin(half) / n
    return quat_normalize(quat_mul(q, (math.cos(half), w[0] * s, w[1] * s, w[2] * s)))


class Mekf:
    """Attitude + gyro-bias MEKF; same interface as :class:`~detumble.control.attitude_filter.AttitudeFilter`.

    Args:
        gyro_noise_rad_s: ``σ_g``, white noise of one gyro reading, rad/s (1σ per axis).
        bias_walk_rad_s_rt_s: ``σ_u``, gyro-bias random walk, rad/s/√s.
        tracker_cross_rad, tracker_about_rad: star-tracker 1σ across / about the boresight, rad.
        boresight_B: the tracker's boresight, unit vector in B.
        initial_bias_sigma_rad_s: 1σ of the bias before any measurement, rad/s per axis.
        reinit_angle_rad: residual (or attitude 3σ) above which the attitude is re-initialised.
    """

    def __init__(self, gyro_noise_rad_s: float, bias_walk_rad_s_rt_s: float, tracker_cross_rad: float,
                 tracker_about_rad: float, boresight_B: Vec3 = (0.0, 0.0, 1.0),
                 initial_bias_sigma_rad_s: float = math.radians(1.0), reinit_angle_rad: float = math.radians(5.0)):
        self.gyro_noise = float(gyro_noise_rad_s)
        self.bias_walk = float(bias_walk_rad_s_rt_s)
        self.tracker_cross = float(tracker_cross_rad)
        self.tracker_about = float(tracker_about_rad)
        n = math.sqrt(sum(c * c for c in boresight_B))
        if not n > 0.0:
            raise ValueError(f"boresight_B must be a non-zero vector, got {boresight_B}")
        self.boresight = (boresight_B[0] / n, boresight_B[1] / n, boresight_B[2] / n)
        self.initial_bias_sigma = float(initial_bias_sigma_rad_s)
        self.reinit_angle = float(reinit_angle_rad)
        self.reset()

    def reset(self) -> None:
        """Forget everything: no attitude, zero bias with its initial uncertainty."""
        self.q: Quat | None = None
        self.bias: Vec3 = (0.0, 0.0, 0.0)
        self.omega: Vec3 = (0.0, 0.0, 0.0)
        self.since_measurement_s = math.inf
        self.P: Mat = _zeros(6, 6)
        s2 = self.initial_bias_sigma ** 2
        for i in range(3, 6):
            self.P[i][i] = s2
        self.last_residual: Vec3 | None = None  # rad, B: the last star-tracker residual r
        self.last_innovation_cov: Mat | None = None  # its covariance S, rad²
        self.reinitialisations = 0

    # --- figures -------------------------------------------------------------------------------

    @property
    def attitude_sigma3_rad(self) -> float:
        """3·√(trace P_θθ): the attitude error's 3σ (rad), or inf without an attitude."""
        if self.q is None:
            return math.inf
        p = self.P
        return 3.0 * math.sqrt(max(0.0, p[0][0] + p[1][1] + p[2][2]))

    @property
    def bias_sigma_rad_s(self) -> Vec3:
        p = self.P
        return (math.sqrt(p[3][3]), math.sqrt(p[4][4]), math.sqrt(p[5][5]))

    def tracker_noise(self) -> Mat:
        """``R``, rad²: the star tracker's noise in B."""
        sc2, sb2 = self.tracker_cross ** 2, self.tracker_about ** 2
        e = self.boresight
        d = sb2 - sc2
        return [[(sc2 if i == j else 0.0) + d * e[i] * e[j] for j in range(3)] for i in range(3)]

    # --- the filter ----------------------------------------------------------------------------

    def update(self, omega_gyro_B: Vec3, dt: float, q_measured: Quat | None = None, age_s: float = 0.0,
               samples: int = 1) -> None:
        """Advance by ``dt`` s on the mean of ``samples`` gyro readings ``omega_gyro_B`` (rad/s, B, held
        over the interval that ends now), then correct with ``q_measured`` (``q_BN`` taken ``age_s`` s
        ago), when given."""
        n = max(1, int(samples))
        b = self.bias
        w = (omega_gyro_B[0] - b[0], omega_gyro_B[1] - b[1], omega_gyro_B[2] - b[2])
        var_rate = self.gyro_noise ** 2 / n  # of the mean rate, per axis, (rad/s)²
        self.since_measurement_s += dt
        if self.q is not None:
            self.q = _propagate(self.q, w, dt)
            self._propagate_covariance(w, dt, var_rate)
        if q_measured is not None:
            q_m = _propagate(quat_normalize(q_measured), w, age_s) if age_s > 0.0 else quat_normalize(q_measured)
            corr = var_rate * dt * age_s if 0.0 < age_s <= dt else 0.0
            self._measure(q_m, var_rate * age_s * age_s, corr)
            self.since_measurement_s = 0.0
            b = self.bias
        self.omega = (omega_gyro_B[0] - b[0], omega_gyro_B[1] - b[1], omega_gyro_B[2] - b[2])

    def _propagate_covariance(self, w: Vec3, dt: float, var_rate: float) -> None:
        """``P ← sym(Φ P Φᵀ + Q)`` for ``Φ = [[F, −Δt I], [0, I]]``, ``F = exp(−[w×] Δt)``.

        :func:`_phi_p_phi_t` row by row with its sums spelled out, Q added to its twelve elements,
        then :func:`_symmetric6`: the same floating-point operations in the same order as
        ``_symmetric(Φ P Φᵀ + Q)`` (MEKF-003, MEKF-007).
        """
        f = _rotation_transpose(w, dt)
        m = -dt
        p0, p1, p2, p3, p4, p5 = self.P
        x00, x01, x02, x03, x04, x05 = p0
        x10, x11, x12, x13, x14, x15 = p1
        x20, x21, x22, x23, x24, x25 = p2
        # Φ P: rows 0-2 are F P_top − Δt P_bottom (only Φ's non-zero products, as _phi_p_phi_t), rows 3-5 P's own
        a0, a1, a2 = [(sum((g0 * x00, g1 * x10, g2 * x20, m * y0)), sum((g0 * x01, g1 * x11, g2 * x21, m * y1)),
                       sum((g0 * x02, g1 * x12, g2 * x22, m * y2)), sum((g0 * x03, g1 * x13, g2 * x23, m * y3)),
                       sum((g0 * x04, g1 * x14, g2 * x24, m * y4)), sum((g0 * x05, g1 * x15, g2 * x25, m * y5)))
                      for (g0, g1, g2), (y0, y1, y2, y3, y4, y5) in zip(f, (p3, p4, p5), strict=True)]
        # (Φ P) Φᵀ row by row, as _phi_p_phi_t
        (f00, f01, f02), (f10, f11, f12), (f20, f21, f22) = f
        p = [[sum((r0 * f00, r1 * f01, r2 * f02, r3 * m)), sum((r0 * f10, r1 * f11, r2 * f12, r4 * m)),
              sum((r0 * f20, r1 * f21, r2 * f22, r5 * m)), 0.0 + r3, 0.0 + r4, 0.0 + r5]
             for r0, r1, r2, r3, r4, r5 in (a0, a1, a2, p3, p4, p5)]
        su2 = self.bias_walk ** 2
        qa = var_rate * dt * dt + su2 * dt ** 3 / 3.0
        qab = -su2 * dt * dt / 2.0
        qb = su2 * dt
        for i in range(3):
            p[i][i] += qa
            p[i][i + 3] += qab
            p[i + 3][i] += qab
            p[i + 3][i + 3] += qb
        self.P = _symmetric6(p)

    def _initialise_attitude(self, q_m: Quat, r: Mat) -> None:
        self.q = quat_shortest(q_m)
        p = self.P
        for i in range(3):
            for j in range(6):
                p[i][j] = 0.0
                p[j][i] = 0.0
            for j in range(3):
                p[i][j] = r[i][j]
        self.last_residual = None
        self.last_innovation_cov = None

    def _measure(self, q_m: Quat, var_carry: float, corr: float) -> None:
        """Star-tracker update with ``R`` plus ``var_carry`` per axis and the correlation ``corr``.

        The Kalman step row by row with its 3-element sums spelled out: the same floating-point
        operations in the same order as the matrix form (``_matmul`` of ``P Hᵀ + M`` and ``S⁻¹``, of
        ``K`` and ``S``, ``K S Kᵀ`` summed over the rows of ``K``, then ``_symmetric(P − K S Kᵀ)``;
        MEKF-007 checks it bit for bit).
        """
        if self.q is None:
            self._initialise_attitude(q_m, self._measurement_noise(var_carry))
            return
        qe = quat_shortest(quat_mul(quat_conj(self.q), q_m))
        res = (2.0 * qe[1], 2.0 * qe[2], 2.0 * qe[3])
        if (math.sqrt(res[0] ** 2 + res[1] ** 2 + res[2] ** 2) > self.reinit_angle
                or self.attitude_sigma3_rad > self.reinit_angle):
            self.reinitialisations += 1
            self._initialise_attitude(q_m, self._measurement_noise(var_carry))
            return
        # R + var_carry I, as tracker_noise() builds R: (σ_c² on the diagonal, else 0) + (σ_b² − σ_c²) e_i e_j
        sc2, sb2 = self.tracker_cross ** 2, self.tracker_about ** 2
        e0, e1, e2 = self.boresight
        d = sb2 - sc2
        p = self.P
        p0, p1, p2 = p[0], p[1], p[2]
        # S = H P Hᵀ + R + H M + Mᵀ Hᵀ: the attitude block plus R, −2 corr on the diagonal
        c2 = 2.0 * corr
        s00 = p0[0] + (sc2 + d * e0 * e0 + var_carry) - c2
        s01 = p0[1] + (0.0 + d * e0 * e1)
        s02 = p0[2] + (0.0 + d * e0 * e2)
        s10 = p1[0] + (0.0 + d * e1 * e0)
        s11 = p1[1] + (sc2 + d * e1 * e1 + var_carry) - c2
        s12 = p1[2] + (0.0 + d * e1 * e2)
        s20 = p2[0] + (0.0 + d * e2 * e0)
        s21 = p2[1] + (0.0 + d * e2 * e1)
        s22 = p2[2] + (sc2 + d * e2 * e2 + var_carry) - c2
        s = [[s00, s01, s02], [s10, s11, s12], [s20, s21, s22]]
        (n00, n01, n02), (n10, n11, n12), (n20, n21, n22) = _inv_spd3(s)
        # K = (P Hᵀ + M) S⁻¹; P Hᵀ + M: P's first three columns, −corr on the attitude block's diagonal
        pht = ((p0[0] - corr, p0[1], p0[2]), (p1[0], p1[1] - corr, p1[2]), (p2[0], p2[1], p2[2] - corr),
               p[3], p[4], p[5])  # of rows 3-5 only the first three columns are read
        k = [(sum((x0 * n00, x1 * n10, x2 * n20)), sum((x0 * n01, x1 * n11, x2 * n21)),
              sum((x0 * n02, x1 * n12, x2 * n22))) for x0, x1, x2, *_ in pht]
        (k00, k01, k02), (k10, k11, k12), (k20, k21, k22), (k30, k31, k32), (k40, k41, k42), (k50, k51, k52) = k
        # K S, then P − K S Kᵀ (row i of K S against each row of K), symmetrised
        ks = [(sum((a0 * s00, a1 * s10, a2 * s20)), sum((a0 * s01, a1 * s11, a2 * s21)),
               sum((a0 * s02, a1 * s12, a2 * s22))) for a0, a1, a2 in k]
        self.P = _symmetric6([
            (x0 - sum((a0 * k00, a1 * k01, a2 * k02)), x1 - sum((a0 * k10, a1 * k11, a2 * k12)),
             x2 - sum((a0 * k20, a1 * k21, a2 * k22)), x3 - sum((a0 * k30, a1 * k31, a2 * k32)),
             x4 - sum((a0 * k40, a1 * k41, a2 * k42)), x5 - sum((a0 * k50, a1 * k51, a2 * k52)))
            for (x0, x1, x2, x3, x4, x5), (a0, a1, a2) in zip(p, ks, strict=True)])
        self.last_residual = res
        self.last_innovation_cov = s
        # reset: fold the error into the reference attitude and the bias (dx = K r)
        r0, r1, r2 = res
        q = self.q
        self.q = quat_normalize(quat_mul(q, (1.0, 0.5 * (k00 * r0 + k01 * r1 + k02 * r2),
                                             0.5 * (k10 * r0 + k11 * r1 + k12 * r2),
                                             0.5 * (k20 * r0 + k21 * r1 + k22 * r2))))
        b = self.bias
        self.bias = (b[0] + (k30 * r0 + k31 * r1 + k32 * r2), b[1] + (k40 * r0 + k41 * r1 + k42 * r2),
                     b[2] + (k50 * r0 + k51 * r1 + k52 * r2))

    def _measurement_noise(self, var_carry: float) -> Mat:
        """``R + var_carry I``, rad² (B)."""
        r = self.tracker_noise()
        for i in range(3):
            r[i][i] += var_carry
        return r


def _phi_p_phi_t(f: Mat, m: float, p: Mat) -> Mat:
    """``Φ P Φᵀ`` for ``Φ = [[F, m I], [0, I]]`` (F 3×3, ``m = −Δt``), P 6×6.

    The same floats as ``_matmul(_matmul(Φ, P), Φᵀ)`` whenever P is finite: every element there is
    ``sum`` of six products in index order, and the products with Φ's zeros are ±0.0, which leave
    a partial ``sum`` unchanged (it starts at +0 and never becomes −0, and 3.12's compensation
    term does not move either). So only the others are summed, in the same order; an element
    that is one product with a 1 of Φ is ``0.0 + x`` (as ``sum`` turns −0.0 into +0.0).
    """
    p0, p1, p2 = p[0], p[1], p[2]
    a = []  # Φ P
    for (f0, f1, f2), pk in zip(f, (p[3], p[4], p[5]), strict=True):
        a.append([sum((f0 * x0, f1 * x1, f2 * x2, m * xk)) for x0, x1, x2, xk in zip(p0, p1, p2, pk, strict=True)])
    a += (p[3], p[4], p[5])  # Φ's identity rows (the sums and 0.0 + below turn their −0.0 into +0.0, as there)
    (g00, g01, g02), (g10, g11, g12), (g20, g21, g22) = f
    return [[sum((r0 * g00, r1 * g01, r2 * g02, r3 * m)), sum((r0 * g10, r1 * g11, r2 * g12, r4 * m)),
             sum((r0 * g20, r1 * g21, r2 * g22, r5 * m)), 0.0 + r3, 0.0 + r4, 0.0 + r5]
            for r0, r1, r2, r3, r4, r5 in a]


def _symmetric(p: Mat) -> Mat:
    cols = zip(*p, strict=True)
    return [[0.5 * (x + y) for x, y in zip(row, col, strict=True)] for row, col in zip(p, cols, strict=True)]


def _symmetric6(c) -> Mat:
    """:func:`_symmetric` of a 6×6 ``c`` (rows any sequences): each pair ``0.5 (c_ij + c_ji)``
    computed once for both places (IEEE addition commutes, so the floats are ``_symmetric``'s)."""
    (c00, c01, c02, c03, c04, c05), (c10, c11, c12, c13, c14, c15), (c20, c21, c22, c23, c24, c25), \
        (c30, c31, c32, c33, c34, c35), (c40, c41, c42, c43, c44, c45), (c50, c51, c52, c53, c54, c55) = c
    s01, s02, s03, s04, s05 = 0.5 * (c01 + c10), 0.5 * (c02 + c20), 0.5 * (c03 + c30), 0.5 * (c04 + c40), \
        0.5 * (c05 + c50)
    s12, s13, s14, s15 = 0.5 * (c12 + c21), 0.5 * (c13 + c31), 0.5 * (c14 + c41), 0.5 * (c15 + c51)
    s23, s24, s25 = 0.5 * (c23 + c32), 0.5 * (c24 + c42), 0.5 * (c25 + c52)
    s34, s35, s45 = 0.5 * (c34 + c43), 0.5 * (c35 + c53), 0.5 * (c45 + c54)
    return [[0.5 * (c00 + c00), s01, s02, s03, s04, s05],
            [s01, 0.5 * (c11 + c11), s12, s13, s14, s15],
            [s02, s12, 0.5 * (c22 + c22), s23, s24, s25],
            [s03, s13, s23, 0.5 * (c33 + c33), s34, s35],
            [s04, s14, s24, s34, 0.5 * (c44 + c44), s45],
            [s05, s15, s25, s35, s45, 0.5 * (c55 + c55)]]
