"""Sun-safe on the light sensors' Sun vector (plain floats; no framework import).

Units: rates rad/s, torques N·m, inertias kg·m², gains as stated, every vector in the body frame B.

:func:`sun_spin_torque` is the magnetorquer Sun-safe law: hold a spin of ``ω_s`` about the Sun-safe axis â and
tip that spin to the Sun. The request is
``τ = −k_t ω⊥ + k_s (ω_s − ω·â) â + h_s Ω ŝ⊥/|ŝ⊥| + ω × (I ω)``: the transverse rate ``ω⊥`` (across â) damped,
the spin regulated, a torque along the Sun's component across â (``ŝ⊥``) that tips the momentum
``h_s = I_aa ω_s`` toward the Sun at ``Ω = min(k θ, Ω_max)`` (θ the angle between â and ŝ), and the gyroscopic
term. Only the part of τ across B is produced (the caller projects it).

Why a spin (the classic spinning Sun-safe): a magnetic torque is always ⟂ B, so the angular momentum along B̂
cannot be changed until B̂ turns (twice an orbit, inertially). A body at rest keeps any such momentum error ``δh``
as a rotation and its axis drifts without bound (``δh t / I``); a body spinning at ``ω_s`` about â rotates about
``ω_s â + δh / I`` instead, so â only cones, by ``atan(|δh⊥| / h_s)``, and every body-fixed requirement (the damping
of ``ω⊥``) turns inertially at ``ω_s`` and is achievable on average whatever B does. The same bound applies to a rate
error: a gyro bias ``b⊥`` the controller does not know makes â cone by ``atan(|b⊥| / ω_s)`` (6.8° for the LSM6DSO's
0.36 °/s at 3 °/s), which is why :class:`SunRateBias` estimates the bias across ŝ from the Sun vector itself.

The limit that stays: â moves toward ŝ only by a rotation about ``ê = â × ŝ``, which is inertially fixed while â is
held; when B̂ lies near ê that rate cannot be made (it is momentum along B), and the approach waits for B̂ to turn.
That is why acquisition takes 4–30 min rather than the ~2 time constants of the loop
(``docs/studies/sun_safe.md``).

:class:`SunHold` decides when the acquisition spin may be lowered: a spin fast enough to acquire (3 °/s) is above
the star tracker's rate limit (2 °/s), so knowledge could never come back in SUN_SAFE; once the Sun has been held
the spin is lowered to a hold spin below that limit, which keeps the axis by the same coning argument with half the
stiffness (``atan(|δh⊥| / h_s)`` doubles at half ``h_s``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

Vec3 = tuple[float, float, float]
Mat3 = Sequence[Sequence[float]]

__all__ = ["SunHold", "SunRateBias", "spin_down_tip", "sun_spin_torque", "SPIN_DOWN_FIELD_ANGLE_DEG",
           "SUN_BIAS_TIME_S"]

# The spin rate is the ground parameter SUN_SPIN_RATE (control.attitude_defaults: 3 °/s; with the LSM6DSO's bias
# ⟂ +Z, 0.36 °/s, left unestimated the axis would cone by atan(0.36 / 3) = 6.8°; estimated from the Sun vector, to
# ~0.05 °/s, by 1°). Above the star tracker's rate limit (2 °/s in the adcs scenario) the tracker gives no fix
# while the coils spin, so knowledge cannot come back in SUN_SAFE: docs/studies/sun_safe.md.
#: s: default time constant of the Sun-vector gyro-bias observer (noise ~0.6 °/s per 1 s reading → ~0.04 °/s
#: 1σ); the AttitudeController sets it from SUN_BIAS_TIME.
SUN_BIAS_TIME_S = 100.0


def _cross(a: Vec3, b: Vec3) -> Vec3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _mul(m: Mat3, v: Vec3) -> Vec3:
    return (m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2])


def sun_spin_torque(omega: Vec3, sun: Vec3 | None, axis: Vec3, inertia: Mat3, spin_rate: float, k_transverse: float,
                    k_spin: float, k_precess: float, max_precess: float) -> tuple[Vec3, float]:
    """``(τ_req N·m, θ deg)`` of the spinning Sun-safe law (module docstring).

    Args:
        omega: the body rate ω (rad/s, B), bias-corrected.
        sun: the unit Sun vector ŝ (B), or None (eclipse): then only the spin about â is held and the
            transverse rate damped (θ is NaN).
        axis: the unit Sun-safe axis â (B).
        inertia: the controller's inertia model (kg·m², B).
        spin_rate: ω_s, rad/s.
        k_transverse, k_spin: rate-loop gains across and along â, N·m·s.
        k_precess: Ω per radian of θ, 1/s; max_precess: Ω's cap, rad/s.
    """
    a = axis
    h_s = spin_rate * (a[0] * _mul(inertia, a)[0] + a[1] * _mul(inertia, a)[1] + a[2] * _mul(inertia, a)[2])
    w_a = omega[0] * a[0] + omega[1] * a[1] + omega[2] * a[2]
    kt, spin = k_transverse, k_spin * (spin_rate - w_a)
    gyro = _cross(omega, _mul(inertia, omega))
    tau = [-kt * (omega[i] - w_a * a[i]) + spin * a[i] + gyro[i] for i in range(3)]
    theta = math.nan
    if sun is not None:
        s_a = sun[0] * a[0] + sun[1] * a[1] + sun[2] * a[2]
        p = (sun[0] - s_a * a[0], sun[1] - s_a * a[1], sun[2] - s_a * a[2])  # ŝ⊥: where the momentum must go
        sin_t = math.sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])
        theta = math.atan2(sin_t, s_a)
        if sin_t < 1e-9:  # on the axis (nothing to do) or exactly opposite (tip toward any axis ⟂ â)
            p, sin_t = ((a[1], a[2], a[0]), 1.0) if theta > 1.0 else ((0.0, 0.0, 0.0), 1.0)
        k = h_s * min(k_precess * theta, max_precess) / sin_t
        tau = [tau[i] + k * p[i] for i in range(3)]
    return (tau[0], tau[1], tau[2]), math.degrees(theta)


class SunRateBias:
    """The gyro bias across the Sun line from the light sensors: a new Sun reading ``ŝ_m`` against the previous
    one carried on the (bias-corrected) gyro for ``Δt``, ``ŝ_p``, differs by ``r = ŝ_m − ŝ_p ≈ (b − b̂) × ŝ Δt``
    (to first order; ``v̇ = −ω × v``), so ``ŝ × r / Δt`` measures ``(b − b̂)⊥ŝ``; it is low-passed with the time
    constant ``time_s``: ``b̂ += min(Δt / time_s, 1) ŝ × r / Δt`` (rad/s, B). The component along ŝ is not
    observable and is left as it is. Readings more than ``max_gap_s`` apart, or turned by more than
    ``max_turn_rad`` between them, are not used (the first-order model no longer holds)."""

    def __init__(self, time_s: float = SUN_BIAS_TIME_S, max_gap_s: float = 3.0, max_turn_rad: float = 0.1) -> None:
        if not time_s > 0.0:
            raise ValueError(f"the bias observer's time constant must be positive (s), got {time_s}")
        self.time_s = float(time_s)
        self.max_gap_s = float(max_gap_s)
        self.max_turn_rad = float(max_turn_rad)
        self.bias: Vec3 = (0.0, 0.0, 0.0)
        self.updates = 0

    def reset(self) -> None:
        self.bias = (0.0, 0.0, 0.0)
        self.updates = 0

    def update(self, measured: Vec3, predicted: Vec3, gap_s: float) -> None:
        """Fold in one reading ``measured`` (unit, B) against the previous one carried ``gap_s`` s on the gyro,
        ``predicted`` (unit, B)."""
        if not 0.0 < gap_s <= self.max_gap_s:
            return
        r = (measured[0] - predicted[0], measured[1] - predicted[1], measured[2] - predicted[2])
        if not math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) <= self.max_turn_rad:
            return
        g = min(gap_s / self.time_s, 1.0) / gap_s
        c = _cross(measured, r)
        b = self.bias
        self.bias = (b[0] + g * c[0], b[1] + g * c[1], b[2] + g * c[2])
        self.updates += 1


#: The default of SUN_HOLD_FIELD_ANGLE (deg): the spin command moves only while the field is at least this far from
#: the spin axis; a spin change ``ΔH â`` made ⟂ B comes with ``ΔH cot(∠(â, B))`` across â, which tips the axis
#: (:class:`SunHold`).
SPIN_DOWN_FIELD_ANGLE_DEG = 80.0


def spin_down_tip(axis: Vec3, field: Vec3, sun: Vec3) -> tuple[float, float] | None:
    """Where lowering the spin on the coils tips the axis, against the Sun: ``(sin σ, tan β)`` with β = ∠(â, B) and
    σ the Sun's angle ahead of â along the tip (positive: lowering the spin turns â toward the Sun). None when the
    field is along or across â exactly (no tip, or no direction).

    The spin torque ``τ_a â`` (τ_a < 0 lowers it) projected ⟂ B is ``τ_a (â − cos β B̂)``; its part across â,
    ``−τ_a cos β B̂⊥â`` (``B̂⊥â = B̂ − cos β â``), is ``|τ_a| cos β B̂⊥â`` when lowering: the angular momentum, and the
    spin axis with it, moves along ``cos β B̂⊥â``, by ``cot β`` per unit of spin change. All vectors in B; ``axis``
    and ``sun`` unit, ``field`` any length."""
    n = math.sqrt(field[0] * field[0] + field[1] * field[1] + field[2] * field[2])
    if not n > 0.0:
        return None
    b = (field[0] / n, field[1] / n, field[2] / n)
    c = b[0] * axis[0] + b[1] * axis[1] + b[2] * axis[2]
    t = tuple(c * (b[i] - c * axis[i]) for i in range(3))  # cos β B̂⊥â: |t| = |cos β| sin β
    t_n = math.sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2])
    if not t_n > 1e-12:
        return None
    sin_b = math.sqrt(max(0.0, 1.0 - c * c))
    return (sun[0] * t[0] + sun[1] * t[1] + sun[2] * t[2]) / t_n, sin_b / abs(c)


class SunHold:
    """When and how SUN_SAFE on the coils lowers its spin. Once the angle θ between the Sun-safe axis and the Sun
    vector (deg, from the light sensors, as the law sees it) has stayed at or below ``angle_deg`` for ``dwell_s`` s
    without a break, the spin command leaves the acquisition spin and ramps at ``ramp_deg_s2`` to the hold spin; it
    stays there until :meth:`reset` (the mode left or entered again). A missing Sun vector (eclipse: θ is NaN) breaks
    the hold like an angle above it. ``angle_deg`` ≤ 0 never lowers.

    Why a ramp, and only while the field is across the axis: the coils make only torque ⟂ B, so the momentum
    change ``ΔH â`` of a spin change comes with at least ``ΔH cot(∠(â, B))`` across â, which tips the spin axis
    by about that over the spin left, ``h_s``. A step from 3 to 1.5 °/s swung +Z 54° off the Sun, a plain ramp
    (0.005 °/s²) 39°, gated at 70° 18° (docs/studies/sun_safe.md); the ramp therefore advances only while
    ∠(â, B) ≥ ``field_angle_deg`` (SUN_HOLD_FIELD_ANGLE, default :data:`SPIN_DOWN_FIELD_ANGLE_DEG`: ``cot`` ≤ 0.18)
    and waits otherwise for the field to turn. The price: the spin comes down only in those windows. With the Sun-safe
    axis on the Sun (inertially fixed) they are set by the orbit, the field and the epoch alone
    (``detumble.sim.spin_down_geometry``): in the adcs scenario, two a sunlit part at 80°, 216–387 s and
    2157–2390 s, so a spin-down that begins after 387 s reaches the tracker's 2 °/s at ~2357 s whenever it began.
    The pointing term cannot take the tip out meanwhile: it tips â only about ``â × B̂``, ⟂ the tip ``B̂⊥â``."""

    def __init__(self) -> None:
        self.held_s = 0.0
        self.lowered = False
        self.command_deg_s: float | None = None  # the spin command once lowering began (deg/s); None: not lowered

    def reset(self) -> None:
        self.held_s = 0.0
        self.lowered = False
        self.command_deg_s = None

    def spin(self, theta_deg: float, dt: float, acquire_deg_s: float, hold_deg_s: float, angle_deg: float,
             dwell_s: float, ramp_deg_s2: float, field_axis_cos: float | None,
             field_angle_deg: float = SPIN_DOWN_FIELD_ANGLE_DEG, tip: tuple[float, float] | None = None,
             tip_angle_deg: float = 0.0) -> float:
        """Fold in one control cycle of ``dt`` s at ``theta_deg`` and give the spin to command now (deg/s):
        ``acquire_deg_s`` until the Sun has been held, then ramping at ``ramp_deg_s2`` to ``hold_deg_s`` while
        ``|field_axis_cos|`` (the cosine between the field and the Sun-safe axis; None: no field reading) is small
        enough: at most ``cos(field_angle_deg)`` (deg; the field at least that far from the axis). :attr:`lowered`
        turns True on the cycle the ramp begins.

        With ``tip_angle_deg`` > 0 (SUN_HOLD_TIP_ANGLE) the ramp also moves outside the field gate while the tip it
        makes turns the axis toward the Sun: ``tip`` = :func:`spin_down_tip`'s ``(sin σ, tan β)``, and the command
        moves when the Sun is at least ``tip_angle_deg`` ahead along the tip (``sin σ ≥ sin tip_angle_deg`` when
        lowering, ``−sin σ`` when raising), at ``ramp × min(1, tan β)`` so the tip rate stays at most the ramp's
        (``cot β`` per unit). Past the Sun the sign flips and the command waits: the tip is spent on the pointing
        error instead of added to it."""
        if self.command_deg_s is None:
            if angle_deg > 0.0 and theta_deg <= angle_deg:  # NaN (no Sun vector) is not held
                self.held_s += dt
            else:
                self.held_s = 0.0
            if angle_deg <= 0.0 or self.held_s < dwell_s:
                return acquire_deg_s
            self.lowered = True
            self.command_deg_s = acquire_deg_s
        c = self.command_deg_s
        step = 0.0
        if field_axis_cos is not None and abs(field_axis_cos) <= math.cos(math.radians(field_angle_deg)):
            step = ramp_deg_s2 * dt
        elif tip_angle_deg > 0.0 and tip is not None and c != hold_deg_s:
            ahead = tip[0] if c > hold_deg_s else -tip[0]
            if ahead >= math.sin(math.radians(tip_angle_deg)):
                step = ramp_deg_s2 * dt * min(1.0, tip[1])
        if step > 0.0:
            c = max(c - step, hold_deg_s) if c > hold_deg_s else min(c + step, hold_deg_s)
            self.command_deg_s = c
        return c
