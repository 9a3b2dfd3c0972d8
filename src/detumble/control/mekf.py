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
        """``P ← sym(Φ P Φᵀ + Q)`` for ``Φ = [[F, −Δt I], [0, I]]``, ``F = exp(−[w×] Δt)``, in one pass.

        Written out element by element, the same floating-point operations in the same order as
        ``_symmetric(_phi_p_phi_t(F, −Δt, P) + Q)`` (the reference forms below; MEKF-003 and
        MEKF-007 check it bit for bit): each ``sum`` the same products in the same order, each Q
        term added to its element, each symmetrised pair ``0.5 (c_ij + c_ji)`` computed once for
        both (IEEE addition commutes), with no intermediate 6×6 lists.
        """
        (f00, f01, f02), (f10, f11, f12), (f20, f21, f22) = _rotation_transpose(w, dt)
        m = -dt
        su2 = self.bias_walk ** 2
        qa = var_rate * dt * dt + su2 * dt ** 3 / 3.0
        qab = -su2 * dt * dt / 2.0
        qb = su2 * dt
        p = self.P
        p00, p01, p02, p03, p04, p05 = p[0]
        p10, p11, p12, p13, p14, p15 = p[1]
        p20, p21, p22, p23, p24, p25 = p[2]
        p30, p31, p32, p33, p34, p35 = p[3]
        p40, p41, p42, p43, p44, p45 = p[4]
        p50, p51, p52, p53, p54, p55 = p[5]
        # Φ P, rows 0-2 (rows 3-5 are P's own)
        a00 = sum((f00 * p00, f01 * p10, f02 * p20, m * p30))
        a01 = sum((f00 * p01, f01 * p11, f02 * p21, m * p31))
        a02 = sum((f00 * p02, f01 * p12, f02 * p22, m * p32))
        a03 = sum((f00 * p03, f01 * p13, f02 * p23, m * p33))
        a04 = sum((f00 * p04, f01 * p14, f02 * p24, m * p34))
        a05 = sum((f00 * p05, f01 * p15, f02 * p25, m * p35))
        a10 = sum((f10 * p00, f11 * p10, f12 * p20, m * p40))
        a11 = sum((f10 * p01, f11 * p11, f12 * p21, m * p41))
        a12 = sum((f10 * p02, f11 * p12, f12 * p22, m * p42))
        a13 = sum((f10 * p03, f11 * p13, f12 * p23, m * p43))
        a14 = sum((f10 * p04, f11 * p14, f12 * p24, m * p44))
        a15 = sum((f10 * p05, f11 * p15, f12 * p25, m * p45))
        a20 = sum((f20 * p00, f21 * p10, f22 * p20, m * p50))
        a21 = sum((f20 * p01, f21 * p11, f22 * p21, m * p51))
        a22 = sum((f20 * p02, f21 * p12, f22 * p22, m * p52))
        a23 = sum((f20 * p03, f21 * p13, f22 * p23, m * p53))
        a24 = sum((f20 * p04, f21 * p14, f22 * p24, m * p54))
        a25 = sum((f20 * p05, f21 * p15, f22 * p25, m * p55))
        # (Φ P) Φᵀ plus Q (each Q term added to its element, as before)
        c00 = sum((a00 * f00, a01 * f01, a02 * f02, a03 * m)) + qa
        c01 = sum((a00 * f10, a01 * f11, a02 * f12, a04 * m))
        c02 = sum((a00 * f20, a01 * f21, a02 * f22, a05 * m))
        c03 = 0.0 + a03 + qab
        c04 = 0.0 + a04
        c05 = 0.0 + a05
        c10 = sum((a10 * f00, a11 * f01, a12 * f02, a13 * m))
        c11 = sum((a10 * f10, a11 * f11, a12 * f12, a14 * m)) + qa
        c12 = sum((a10 * f20, a11 * f21, a12 * f22, a15 * m))
        c13 = 0.0 + a13
        c14 = 0.0 + a14 + qab
        c15 = 0.0 + a15
        c20 = sum((a20 * f00, a21 * f01, a22 * f02, a23 * m))
        c21 = sum((a20 * f10, a21 * f11, a22 * f12, a24 * m))
        c22 = sum((a20 * f20, a21 * f21, a22 * f22, a25 * m)) + qa
        c23 = 0.0 + a23
        c24 = 0.0 + a24
        c25 = 0.0 + a25 + qab
        c30 = sum((p30 * f00, p31 * f01, p32 * f02, p33 * m)) + qab
        c31 = sum((p30 * f10, p31 * f11, p32 * f12, p34 * m))
        c32 = sum((p30 * f20, p31 * f21, p32 * f22, p35 * m))
        c33 = 0.0 + p33 + qb
        c34 = 0.0 + p34
        c35 = 0.0 + p35
        c40 = sum((p40 * f00, p41 * f01, p42 * f02, p43 * m))
        c41 = sum((p40 * f10, p41 * f11, p42 * f12, p44 * m)) + qab
        c42 = sum((p40 * f20, p41 * f21, p42 * f22, p45 * m))
        c43 = 0.0 + p43
        c44 = 0.0 + p44 + qb
        c45 = 0.0 + p45
        c50 = sum((p50 * f00, p51 * f01, p52 * f02, p53 * m))
        c51 = sum((p50 * f10, p51 * f11, p52 * f12, p54 * m))
        c52 = sum((p50 * f20, p51 * f21, p52 * f22, p55 * m)) + qab
        c53 = 0.0 + p53
        c54 = 0.0 + p54
        c55 = 0.0 + p55 + qb
        # symmetrised: element (i, j) and (j, i) are both 0.5 (c_ij + c_ji)
        s00 = 0.5 * (c00 + c00)
        s01 = 0.5 * (c01 + c10)
        s02 = 0.5 * (c02 + c20)
        s03 = 0.5 * (c03 + c30)
        s04 = 0.5 * (c04 + c40)
        s05 = 0.5 * (c05 + c50)
        s11 = 0.5 * (c11 + c11)
        s12 = 0.5 * (c12 + c21)
        s13 = 0.5 * (c13 + c31)
        s14 = 0.5 * (c14 + c41)
        s15 = 0.5 * (c15 + c51)
        s22 = 0.5 * (c22 + c22)
        s23 = 0.5 * (c23 + c32)
        s24 = 0.5 * (c24 + c42)
        s25 = 0.5 * (c25 + c52)
        s33 = 0.5 * (c33 + c33)
        s34 = 0.5 * (c34 + c43)
        s35 = 0.5 * (c35 + c53)
        s44 = 0.5 * (c44 + c44)
        s45 = 0.5 * (c45 + c54)
        s55 = 0.5 * (c55 + c55)
        self.P = [[s00, s01, s02, s03, s04, s05],
                  [s01, s11, s12, s13, s14, s15],
                  [s02, s12, s22, s23, s24, s25],
                  [s03, s13, s23, s33, s34, s35],
                  [s04, s14, s24, s34, s44, s45],
                  [s05, s15, s25, s35, s45, s55]]

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

        The Kalman step is written out element by element: the same floating-point operations in
        the same order as the matrix form (``_matmul`` of ``P Hᵀ + M`` and ``S⁻¹``, of ``K`` and
        ``S``, ``K S Kᵀ`` summed over the rows of ``K``, then ``_symmetric(P − K S Kᵀ)``; MEKF-007
        checks it bit for bit), with each symmetrised pair computed once for both (IEEE addition
        commutes).
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
        p00, p01, p02, p03, p04, p05 = p[0]
        p10, p11, p12, p13, p14, p15 = p[1]
        p20, p21, p22, p23, p24, p25 = p[2]
        p30, p31, p32, p33, p34, p35 = p[3]
        p40, p41, p42, p43, p44, p45 = p[4]
        p50, p51, p52, p53, p54, p55 = p[5]
        # S = H P Hᵀ + R + H M + Mᵀ Hᵀ: the attitude block plus R, −2 corr on the diagonal
        c2 = 2.0 * corr
        s00 = p00 + (sc2 + d * e0 * e0 + var_carry) - c2
        s01 = p01 + (0.0 + d * e0 * e1)
        s02 = p02 + (0.0 + d * e0 * e2)
        s10 = p10 + (0.0 + d * e1 * e0)
        s11 = p11 + (sc2 + d * e1 * e1 + var_carry) - c2
        s12 = p12 + (0.0 + d * e1 * e2)
        s20 = p20 + (0.0 + d * e2 * e0)
        s21 = p21 + (0.0 + d * e2 * e1)
        s22 = p22 + (sc2 + d * e2 * e2 + var_carry) - c2
        s = [[s00, s01, s02], [s10, s11, s12], [s20, s21, s22]]
        (n00, n01, n02), (n10, n11, n12), (n20, n21, n22) = _inv_spd3(s)
        # K = (P Hᵀ + M) S⁻¹; P Hᵀ + M: P's first three columns, −corr on the attitude block's diagonal
        h0 = p00 - corr
        k00 = sum((h0 * n00, p01 * n10, p02 * n20))
        k01 = sum((h0 * n01, p01 * n11, p02 * n21))
        k02 = sum((h0 * n02, p01 * n12, p02 * n22))
        h1 = p11 - corr
        k10 = sum((p10 * n00, h1 * n10, p12 * n20))
        k11 = sum((p10 * n01, h1 * n11, p12 * n21))
        k12 = sum((p10 * n02, h1 * n12, p12 * n22))
        h2 = p22 - corr
        k20 = sum((p20 * n00, p21 * n10, h2 * n20))
        k21 = sum((p20 * n01, p21 * n11, h2 * n21))
        k22 = sum((p20 * n02, p21 * n12, h2 * n22))
        k30 = sum((p30 * n00, p31 * n10, p32 * n20))
        k31 = sum((p30 * n01, p31 * n11, p32 * n21))
        k32 = sum((p30 * n02, p31 * n12, p32 * n22))
        k40 = sum((p40 * n00, p41 * n10, p42 * n20))
        k41 = sum((p40 * n01, p41 * n11, p42 * n21))
        k42 = sum((p40 * n02, p41 * n12, p42 * n22))
        k50 = sum((p50 * n00, p51 * n10, p52 * n20))
        k51 = sum((p50 * n01, p51 * n11, p52 * n21))
        k52 = sum((p50 * n02, p51 * n12, p52 * n22))
        # K S, then P − K S Kᵀ symmetrised: (i, j) and (j, i) both 0.5 ((P − K S Kᵀ)_ij + (P − K S Kᵀ)_ji)
        m00 = sum((k00 * s00, k01 * s10, k02 * s20))
        m01 = sum((k00 * s01, k01 * s11, k02 * s21))
        m02 = sum((k00 * s02, k01 * s12, k02 * s22))
        m10 = sum((k10 * s00, k11 * s10, k12 * s20))
        m11 = sum((k10 * s01, k11 * s11, k12 * s21))
        m12 = sum((k10 * s02, k11 * s12, k12 * s22))
        m20 = sum((k20 * s00, k21 * s10, k22 * s20))
        m21 = sum((k20 * s01, k21 * s11, k22 * s21))
        m22 = sum((k20 * s02, k21 * s12, k22 * s22))
        m30 = sum((k30 * s00, k31 * s10, k32 * s20))
        m31 = sum((k30 * s01, k31 * s11, k32 * s21))
        m32 = sum((k30 * s02, k31 * s12, k32 * s22))
        m40 = sum((k40 * s00, k41 * s10, k42 * s20))
        m41 = sum((k40 * s01, k41 * s11, k42 * s21))
        m42 = sum((k40 * s02, k41 * s12, k42 * s22))
        m50 = sum((k50 * s00, k51 * s10, k52 * s20))
        m51 = sum((k50 * s01, k51 * s11, k52 * s21))
        m52 = sum((k50 * s02, k51 * s12, k52 * s22))
        r0, r1, r2 = res
        d = p00 - sum((m00 * k00, m01 * k01, m02 * k02))
        t00 = 0.5 * (d + d)
        t01 = 0.5 * ((p01 - sum((m00 * k10, m01 * k11, m02 * k12)))
                     + (p10 - sum((m10 * k00, m11 * k01, m12 * k02))))
        t02 = 0.5 * ((p02 - sum((m00 * k20, m01 * k21, m02 * k22)))
                     + (p20 - sum((m20 * k00, m21 * k01, m22 * k02))))
        t03 = 0.5 * ((p03 - sum((m00 * k30, m01 * k31, m02 * k32)))
                     + (p30 - sum((m30 * k00, m31 * k01, m32 * k02))))
        t04 = 0.5 * ((p04 - sum((m00 * k40, m01 * k41, m02 * k42)))
                     + (p40 - sum((m40 * k00, m41 * k01, m42 * k02))))
        t05 = 0.5 * ((p05 - sum((m00 * k50, m01 * k51, m02 * k52)))
                     + (p50 - sum((m50 * k00, m51 * k01, m52 * k02))))
        d = p11 - sum((m10 * k10, m11 * k11, m12 * k12))
        t11 = 0.5 * (d + d)
        t12 = 0.5 * ((p12 - sum((m10 * k20, m11 * k21, m12 * k22)))
                     + (p21 - sum((m20 * k10, m21 * k11, m22 * k12))))
        t13 = 0.5 * ((p13 - sum((m10 * k30, m11 * k31, m12 * k32)))
                     + (p31 - sum((m30 * k10, m31 * k11, m32 * k12))))
        t14 = 0.5 * ((p14 - sum((m10 * k40, m11 * k41, m12 * k42)))
                     + (p41 - sum((m40 * k10, m41 * k11, m42 * k12))))
        t15 = 0.5 * ((p15 - sum((m10 * k50, m11 * k51, m12 * k52)))
                     + (p51 - sum((m50 * k10, m51 * k11, m52 * k12))))
        d = p22 - sum((m20 * k20, m21 * k21, m22 * k22))
        t22 = 0.5 * (d + d)
        t23 = 0.5 * ((p23 - sum((m20 * k30, m21 * k31, m22 * k32)))
                     + (p32 - sum((m30 * k20, m31 * k21, m32 * k22))))
        t24 = 0.5 * ((p24 - sum((m20 * k40, m21 * k41, m22 * k42)))
                     + (p42 - sum((m40 * k20, m41 * k21, m42 * k22))))
        t25 = 0.5 * ((p25 - sum((m20 * k50, m21 * k51, m22 * k52)))
                     + (p52 - sum((m50 * k20, m51 * k21, m52 * k22))))
        d = p33 - sum((m30 * k30, m31 * k31, m32 * k32))
        t33 = 0.5 * (d + d)
        t34 = 0.5 * ((p34 - sum((m30 * k40, m31 * k41, m32 * k42)))
                     + (p43 - sum((m40 * k30, m41 * k31, m42 * k32))))
        t35 = 0.5 * ((p35 - sum((m30 * k50, m31 * k51, m32 * k52)))
                     + (p53 - sum((m50 * k30, m51 * k31, m52 * k32))))
        d = p44 - sum((m40 * k40, m41 * k41, m42 * k42))
        t44 = 0.5 * (d + d)
        t45 = 0.5 * ((p45 - sum((m40 * k50, m41 * k51, m42 * k52)))
                     + (p54 - sum((m50 * k40, m51 * k41, m52 * k42))))
        d = p55 - sum((m50 * k50, m51 * k51, m52 * k52))
        t55 = 0.5 * (d + d)
        self.P = [[t00, t01, t02, t03, t04, t05],
                  [t01, t11, t12, t13, t14, t15],
                  [t02, t12, t22, t23, t24, t25],
                  [t03, t13, t23, t33, t34, t35],
                  [t04, t14, t24, t34, t44, t45],
                  [t05, t15, t25, t35, t45, t55]]
        self.last_residual = res
        self.last_innovation_cov = s
        # reset: fold the error into the reference attitude and the bias (dx = K r)
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
