"""Three-axis pointing with magnetorquers only: a PD on the plane ⟂ B that steers the error the
field cannot reach (plain floats; no framework import).

Why the plain projected PD fails. A dipole gives ``τ = m × B``: nothing about the field line ``b̂``.
If the PD on the plane ⟂ ``b̂`` is stiff (``ω_n`` ≫ the rate ``r = |db̂/dt|`` at which the field
line turns, ≈ 2 n in low Earth orbit), it pins the error onto the line, ``θ ≈ α b̂``, and the line
turns: ``b̂·θ̈ = α̈ − α r²`` with no torque along ``b̂``, so ``α̈ = r² α`` — a bead on a rotating rod,
unstable at the rate ``r``. If it is soft enough for orbit averaging (``ω_n`` ≲ n), it is stable but
its stiffness (~1e-9 N·m/rad for a 1U) is below the disturbances. ``docs/studies/magnetic_pointing.md``
measures both.

The law here keeps the stiff PD ⟂ ``b̂`` and controls the two slow states along the field line,
``α = b̂·θ`` and ``β = b̂·ω − r ĝ·θ`` (``ĝ = ḃ/r``), through an offset of the stiff loop's set point
along ``ĝ``: with the set point ``θ* = s ĝ`` held, ``α̇ = β + 2 r s`` and ``β̇ = r² α`` (rigid body with
near-isotropic inertia, small errors). Choosing ``s = −(a α + c β)/(2 r)`` with ``a = 2 ζ ρ r`` and
``c = 1 + ρ²`` places the slow pair at ``λ² + 2 ζ ρ r λ + ρ² r² = 0``: a decay rate ``ζ ρ r``, set by
how fast the field line turns (``test_magnetic_pointing.py`` checks it against the Floquet multipliers
of the linearised periodic system). The D term damps the motion relative to the turning line,
``ω − α ḃ``.

Robustness. The steering feeds the along-field rate back with the gain ``K_p (1 + ρ²)/(2 r)`` (≈ 5e-3
N·m·s for the controller's defaults K_p 4e-6 N·m, ρ 2), 10–30 times ``K_d``. A field direction that is wrong
by ``δ`` (a magnetometer bias: the default LIS2MDL's 0.015 G is δ ≈ 3.5° where the field is weakest) leaks
``δ |ω⊥|`` into it, which acts as negative damping of ``ω⊥`` unless ``K_d > K_p (1 + ρ²) δ / (2 r)``: with
``K_p`` 1e-6 and ``K_d`` = 4e-5 N·m·s the deployment spun up after converging, with 1e-4 it held; the present
defaults (4e-6, 4e-4, ρ 2, ζ 1) keep a Floquet decay of 2.6e-3 /s with the scenario's bias but not at twice it
(converged maps, 16000 samples of the orbit: +9.2e-4 /s in the tilted dipole; study section 4).
ζ = 1 maximises the slow pair's decay for a given ρ: its slower root is ``ρ r (ζ − √(ζ² − 1))`` above 1.

The residual dipole (a constant ``m_res`` in B, ~1e-3 A·m² on a 1U) adds ``m_res × B`` ≈ 4e-8 N·m, which the
stiff loop meets with an offset ≈ ``|m_res × B| / K_p``; :class:`ResidualDipoleEstimator` estimates
``m_res`` from the angular-momentum balance so the coils can cancel it (feed-forward ``−m_res / duty``).

Frames and units: body B; ``q_target`` = ``q_TN`` (inertial target), ``q_BN`` scalar first; ``ω`` rad/s
(B relative to N, in B); ``b`` any field unit (only its direction is used); ``bdot_hat`` = the time
derivative of the unit field direction in inertial space, expressed in B, 1/s; gains ``k_p`` N·m,
``k_d`` N·m·s; torque N·m in B.
"""

from __future__ import annotations

import math

from detumble.control.mat3 import det3 as _det3
from detumble.control.quaternion import Quat, Vec3, quat_angle, quat_error, rotate_b_to_n, rotate_n_to_b

__all__ = ["field_steering_torque", "scheduled_rho", "slow_pole_rate", "FieldDirectionRate", "ResidualDipoleEstimator"]


def _dot(a: Vec3, b: Vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def scheduled_rho(rho: float, rho_large: float, angle_deg: float, from_deg: float, at_deg: float) -> float:
    """The along-field pole ratio at a pointing error of ``angle_deg`` (deg): ``rho`` up to ``from_deg``,
    ``rho_large`` from ``at_deg`` on, linear in the angle between (a step at ``from_deg`` when ``at_deg`` ≤
    ``from_deg``); ``rho_large`` ≤ 0 turns the schedule off (``rho`` at every angle).

    Why: the slow along-field pair falls at ``ζ ρ r`` in the closed form, so a larger ρ while the error is large
    was to shorten the fall from the acquisition's 30° without touching the hold (below ``from_deg`` the law is the
    unscheduled one, the hold's Floquet margin that of ``rho``). Tried for issue 27 and not adopted: with the
    magnetometer's bias ρ 4 is unstable and most draws never acquire
    (``docs/studies/magnetorquer_hold_after_acquisition.md``, "Candidates for a faster fall from 30°")."""
    if not rho_large > 0.0 or angle_deg <= from_deg:
        return rho
    if angle_deg >= at_deg:
        return rho_large
    return rho + (rho_large - rho) * (angle_deg - from_deg) / (at_deg - from_deg)


def field_steering_torque(q_target: Quat, q_BN: Quat, omega_B: Vec3, b_B: Vec3, bdot_hat_B: Vec3,
                          k_p: float, k_d: float, rho: float = 1.0, zeta: float = 0.7,
                          r_min: float = 5.0e-4, rho_large: float = 0.0, large_from_deg: float = 12.0,
                          large_at_deg: float = 20.0) -> tuple[Vec3, Quat]:
    """``(τ_req, q_err)``: the torque to request (project it ⟂ B for the coils) and the error ``q_BT``.

    ``θ = 2 q_err.v`` (short way round); ``r = max(|ḃ|, r_min)`` so a field line that hardly turns
    does not blow the offset up (``r_min`` 1/s). With ``rho = 0`` the law is the PD on ``θ`` with the
    D term relative to the turning line — the unstable "stiff PD" case above. ``rho_large`` > 0 schedules ρ on
    the error angle (:func:`scheduled_rho`, angles in deg); 0 (default): ``rho`` at every angle.
    """
    qe = quat_error(q_target, q_BN)
    if rho_large > 0.0:
        rho = scheduled_rho(rho, rho_large, math.degrees(quat_angle(qe)), large_from_deg, large_at_deg)
    th = (2.0 * qe[1], 2.0 * qe[2], 2.0 * qe[3])
    bn = math.sqrt(_dot(b_B, b_B))
    if not (bn > 0.0 and math.isfinite(bn)):
        return (0.0, 0.0, 0.0), qe
    bh = (b_B[0] / bn, b_B[1] / bn, b_B[2] / bn)
    # the part of ḃ along b̂ is noise (a unit vector's derivative is ⟂ to it)
    along = _dot(bdot_hat_B, bh)
    bd = (bdot_hat_B[0] - along * bh[0], bdot_hat_B[1] - along * bh[1], bdot_hat_B[2] - along * bh[2])
    rn = math.sqrt(_dot(bd, bd))
    alpha = _dot(bh, th)
    if rn > 0.0 and rho > 0.0:
        g = (bd[0] / rn, bd[1] / rn, bd[2] / rn)
        r = max(rn, r_min)
        beta = _dot(bh, omega_B) - r * _dot(g, th)
        s = -(2.0 * zeta * rho * r * alpha + (1.0 + rho * rho) * beta) / (2.0 * r)
    else:
        g, s = (0.0, 0.0, 0.0), 0.0
    tau = tuple(-k_p * (th[i] - s * g[i]) - k_d * (omega_B[i] - alpha * bd[i]) for i in range(3))
    return (tau[0], tau[1], tau[2]), qe


def slow_pole_rate(r: float, rho: float = 1.0, zeta: float = 0.7) -> float:
    """Decay rate (1/s) of the along-field pair, ``ζ ρ r``, for a field line turning at ``r`` rad/s."""
    return zeta * rho * r


class FieldDirectionRate:
    """Estimate of ``db̂_N/dt`` (1/s) from the measured field and attitude: an α-β tracking filter on
    the inertial unit direction ``b̂_N = R_NB b̂_B``, bandwidth ``bandwidth_rad_s``.

    :meth:`update` takes one reading and returns the estimate expressed in B (None until two
    readings have been seen). :meth:`reset` forgets everything (a gap in the readings, a new mode).
    """

    def __init__(self, bandwidth_rad_s: float = 0.05) -> None:
        self.bandwidth_rad_s = float(bandwidth_rad_s)
        self.x: Vec3 | None = None  # filtered b̂_N
        self.v: Vec3 = (0.0, 0.0, 0.0)  # db̂_N/dt, 1/s
        self.samples = 0

    def reset(self) -> None:
        self.x = None
        self.v = (0.0, 0.0, 0.0)
        self.samples = 0

    def update(self, q_BN: Quat, b_B: Vec3, dt: float) -> Vec3 | None:
        """Add the reading ``b_B`` (any unit) at attitude ``q_BN``, ``dt`` s after the previous one."""
        bn = math.sqrt(_dot(b_B, b_B))
        if not (bn > 0.0 and math.isfinite(bn)) or not dt > 0.0:
            return None
        z = rotate_b_to_n(q_BN, (b_B[0] / bn, b_B[1] / bn, b_B[2] / bn))
        if self.x is None:
            self.x, self.samples = z, 1
            return None
        # critically damped α-β gains for a continuous bandwidth w: g = 2 w dt, h = (w dt)²
        wdt = min(self.bandwidth_rad_s * dt, 0.5)
        g, h = 2.0 * wdt, wdt * wdt
        x, v = self.x, self.v
        xp = (x[0] + v[0] * dt, x[1] + v[1] * dt, x[2] + v[2] * dt)
        e = (z[0] - xp[0], z[1] - xp[1], z[2] - xp[2])
        self.x = (xp[0] + g * e[0], xp[1] + g * e[1], xp[2] + g * e[2])
        self.v = (v[0] + h / dt * e[0], v[1] + h / dt * e[1], v[2] + h / dt * e[2])
        self.samples += 1
        return rotate_n_to_b(q_BN, self.v)


class ResidualDipoleEstimator:
    """Least-squares estimate of the spacecraft's constant residual dipole ``m`` (A·m², B) from the
    angular-momentum balance, for feed-forward compensation.

    Over a window of ``window_s`` seconds the momentum the body gained that the modelled torques do not
    explain is the residual dipole's impulse: ``d = J (ω_end − ω_start) − ∫ (τ_model − ω × (J ω + h)) dt
    = m × S`` with ``S = ∫ b dt`` (``m`` constant in B). One window gives ``S × d = (|S|² I − S Sᵀ) m``,
    rank 2 (nothing along ``S``); the field turns in B over an orbit, so the sum over windows
    ``A m = y`` (``A = Σ w (|S|² I − S Sᵀ)``, ``y = Σ w S × d``, each window weighted by ``w = 1/|S|²`` and the
    sums fading with the memory ``memory_s``) has full rank. :attr:`estimate` is ``A⁻¹ y`` once
    ``windows_min`` windows are in and ``A`` is well conditioned (``det A / (tr A / 3)³`` ≥
    ``conditioning_min``), else None.

    Noise: the rate enters only through the window's end points, so gyro noise σ_ω (rad/s, per reading)
    gives ``|δm| ≈ √2 J σ_ω / (|b| window_s)`` per window, averaging down as 1/√N. Unmodelled torques that
    are constant in B, or a coil-scale error (∝ the command), bias it; the study measures it on the
    deployment.

    Units: ``omega_B`` rad/s, ``torque_B`` N·m (the coils' and wheels' torque over the interval that
    ends now), ``wheel_momentum_B`` N·m·s, ``b_B`` T, ``inertia`` kg·m² (3×3, B), ``dt`` s.
    """

    def __init__(self, inertia, window_s: float = 60.0, memory_s: float = 20000.0, windows_min: int = 10,
                 conditioning_min: float = 0.05) -> None:
        self.inertia = tuple(tuple(float(x) for x in row) for row in inertia)
        self.window_s = float(window_s)
        self.memory_s = float(memory_s)
        self.windows_min = int(windows_min)
        self.conditioning_min = float(conditioning_min)
        self.reset()

    def reset(self) -> None:
        """Forget everything (a gap in the data, or a new start)."""
        self.a = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
        self.y = [0.0, 0.0, 0.0]
        self.windows = 0
        self.estimate: Vec3 | None = None
        self._restart_window(None)

    def _restart_window(self, omega: Vec3 | None) -> None:
        self._w0 = omega
        self._imp = [0.0, 0.0, 0.0]  # ∫ (τ_model − ω × (Jω + h)) dt, N·m·s
        self._s = [0.0, 0.0, 0.0]  # ∫ b dt, T·s
        self._elapsed = 0.0

    def gap(self) -> None:
        """The data stopped for a while (no rate, no field): drop the open window, keep the sums."""
        self._restart_window(None)

    def update(self, omega_B: Vec3, torque_B: Vec3, wheel_momentum_B: Vec3, b_B: Vec3, dt: float) -> Vec3 | None:
        """Add one interval of ``dt`` s; returns :attr:`estimate` (A·m², B, or None)."""
        if not dt > 0.0:
            return self.estimate
        if self._w0 is None:
            self._restart_window(omega_B)
            return self.estimate
        j = self.inertia
        w = omega_B
        hx = j[0][0] * w[0] + j[0][1] * w[1] + j[0][2] * w[2] + wheel_momentum_B[0]
        hy = j[1][0] * w[0] + j[1][1] * w[1] + j[1][2] * w[2] + wheel_momentum_B[1]
        hz = j[2][0] * w[0] + j[2][1] * w[1] + j[2][2] * w[2] + wheel_momentum_B[2]
        imp, s = self._imp, self._s
        imp[0] += (torque_B[0] - (w[1] * hz - w[2] * hy)) * dt
        imp[1] += (torque_B[1] - (w[2] * hx - w[0] * hz)) * dt
        imp[2] += (torque_B[2] - (w[0] * hy - w[1] * hx)) * dt
        s[0] += b_B[0] * dt
        s[1] += b_B[1] * dt
        s[2] += b_B[2] * dt
        self._elapsed += dt
        if self._elapsed < self.window_s:
            return self.estimate
        w0 = self._w0
        dw = (w[0] - w0[0], w[1] - w0[1], w[2] - w0[2])
        d = tuple(j[i][0] * dw[0] + j[i][1] * dw[1] + j[i][2] * dw[2] - imp[i] for i in range(3))
        s2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2]
        if s2 > 0.0:
            fade = math.exp(-self._elapsed / self.memory_s) if self.memory_s > 0.0 else 1.0
            a, y = self.a, self.y
            sxd = (s[1] * d[2] - s[2] * d[1], s[2] * d[0] - s[0] * d[2], s[0] * d[1] - s[1] * d[0])
            for i in range(3):
                y[i] = fade * y[i] + sxd[i] / s2
                for k in range(3):
                    a[i][k] = fade * a[i][k] + ((1.0 if i == k else 0.0) - s[i] * s[k] / s2)
            self.windows += 1
            self.estimate = self._solve()
        self._restart_window(omega_B)
        return self.estimate

    def conditioning(self) -> float:
        """``det A / (tr A / 3)³``: 1 when every direction is equally observed, 0 when one is not at all."""
        a = self.a
        tr = a[0][0] + a[1][1] + a[2][2]
        return _det3(a) / (tr / 3.0) ** 3 if tr > 0.0 else 0.0

    def _solve(self) -> Vec3 | None:
        if self.windows < self.windows_min or self.conditioning() < self.conditioning_min:
            return None
        a, y = self.a, self.y
        det = _det3(a)
        # Cramer's rule (A is symmetric positive definite here)
        out = []
        for c in range(3):
            m = [[y[i] if k == c else a[i][k] for k in range(3)] for i in range(3)]
            out.append(_det3(m) / det)
        return (out[0], out[1], out[2])
