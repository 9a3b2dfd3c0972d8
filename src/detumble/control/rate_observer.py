"""A model-aided body-rate observer for the PD law's derivative term (plain floats, no framework import).

Why: the gyro's white noise, through ``K_d ω``, is what limits the pointing error on the wheels
(docs/studies/attitude_knowledge.md). A plain low-pass chosen above the closed-loop bandwidth removes
noise the plant's inertia would have filtered anyway and adds lag; the noise that moves the body lies
near the loop's natural frequency. This observer integrates Euler's equation with the torque the
controller itself commands (known to the flight software) and only pulls toward the bias-corrected gyro
with gain ``L``, so near and above ``L`` the rate comes from the model (no lag on commanded motion, no
gyro noise) and below ``L`` from the gyro (which corrects the model's errors: unknown disturbance torques,
inertia error)::

    a      = I⁻¹ (τ − ω̂ × (I ω̂ + h_w))                 (rad/s², B; τ the body torque over the last cycle)
    r      = ω_meas − (ω̂ + a Δt/2)                     (the gyro mean describes the interval's middle)
    ω̂     ← ω̂ + a Δt + (1 − e^(−L Δt)) r

Units: rad/s, N·m, N·m·s, kg·m², s. ``I`` is the full body inertia (B axes): a 1 % product of inertia
left out misplaces 1 % of every slew's velocity change onto another axis, which the pull then takes
``1/L`` seconds to remove (measured: a 0.1° tail after a 90° slew).
"""

from __future__ import annotations

import math

from detumble.control.mat3 import det3, inv3
from detumble.control.quaternion import Vec3

__all__ = ["RateObserver", "applied_torque", "DIPOLE_LEARN_MAX_RATE", "DIPOLE_LEARN_MAX_TORQUE", "DIPOLE_MAX"]

#: rad/s: the residual dipole is learned only while the body turns slower than this (0.5 deg/s): the gyroscopic
#: term's model error ``ω × (δI ω)`` is then below ~2e-8 N·m at a 10 % inertia error
DIPOLE_LEARN_MAX_RATE = math.radians(0.5)
#: N·m: ... and while the cycle's applied torque is below this: the model's inertia error ``δ`` misreads a torque
#: ``τ`` as ``δ τ`` of disturbance (a slew's 1e-3 N·m would swamp a 1e-7 N·m dipole torque; a hold's ~1e-6 does not)
DIPOLE_LEARN_MAX_TORQUE = 1.0e-5
#: A·m²: the largest residual dipole the estimate may hold per axis (the MAG_RESIDUAL_DIPOLE_* parameters' range)
DIPOLE_MAX = 0.05


def _mul(m, v):
    return (m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
            m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2])


class RateObserver:
    """Args: ``inertia_kg_m2`` three principal moments or a symmetric 3×3 matrix (B axes), ``gain_per_s`` the
    pull ``L`` toward the gyro."""

    def __init__(self, inertia_kg_m2, gain_per_s: float) -> None:
        self._key: object = None  # the model last set: a repeated set_model is free
        self._key_inertia: object = None  # that model's inertia and gain (the two parts of ``_key``)
        self._key_gain: object = None
        self.set_model(inertia_kg_m2, gain_per_s)
        self.omega: Vec3 | None = None
        #: A·m², B: the residual-dipole estimate whose torque ``m̂ × B`` the model adds (:meth:`learn_dipole`)
        self.dipole: Vec3 = (0.0, 0.0, 0.0)
        self._last: tuple[Vec3, Vec3] | None = None  # (gyro mean, applied torque) of the last interval learned on
        self._fit: list | None = None  # the calm stretch's weighted sums (learn_dipole)

    def set_model(self, inertia_kg_m2, gain_per_s: float) -> None:
        """Take a new inertia (kg·m², B) and pull gain (1/s); ValueError when either is unusable (the
        previous model stays). Setting the model it has already costs one comparison."""
        if type(inertia_kg_m2) is tuple and gain_per_s == self._key_gain and inertia_kg_m2 == self._key_inertia:
            return  # the same numbers as last time, given as tuples (anything else takes the long way)
        key = (tuple(tuple(r) if isinstance(r, (tuple, list)) else r for r in inertia_kg_m2), gain_per_s)
        if key == self._key:
            return
        rows = list(inertia_kg_m2)
        if all(not isinstance(r, (tuple, list)) for r in rows) and len(rows) == 3:
            rows = [[rows[0], 0.0, 0.0], [0.0, rows[1], 0.0], [0.0, 0.0, rows[2]]]
        m = tuple(tuple(float(x) for x in r) for r in rows)
        ok = len(m) == 3 and all(len(r) == 3 for r in m) and all(math.isfinite(x) for r in m for x in r)
        ok = ok and all(abs(m[i][j] - m[j][i]) <= 1e-12 * (abs(m[i][j]) + 1e-30) for i in range(3) for j in range(3))
        # positive definite: leading minors
        ok = ok and m[0][0] > 0.0 and m[0][0] * m[1][1] - m[0][1] ** 2 > 0.0
        ok = ok and det3(m) > 0.0
        if not ok:
            raise ValueError(f"inertia_kg_m2 must be three positive moments or a symmetric positive definite 3x3 "
                             f"matrix, got {inertia_kg_m2}")
        if not (math.isfinite(gain_per_s) and gain_per_s > 0.0):
            raise ValueError(f"gain_per_s must be positive, got {gain_per_s}")
        self.inertia = m
        self.inertia_inv = inv3(m)
        self.gain = float(gain_per_s)
        self._key = key
        self._key_inertia, self._key_gain = key

    def reset(self, omega: Vec3 | None = None) -> None:
        """Start again from ``omega`` (rad/s, B; None: from the next gyro mean). The dipole estimate is kept (a
        body-fixed constant); the next :meth:`learn_dipole` starts a new difference."""
        self.omega = None if omega is None else (float(omega[0]), float(omega[1]), float(omega[2]))
        self.skip_dipole()

    def learn_dipole(self, omega_meas: Vec3, torque_B: Vec3, wheel_momentum_B: Vec3, b_tesla: Vec3, dt: float,
                     time_s: float) -> Vec3:
        """One step of the residual-dipole estimate ``m̂`` (A·m², B); call it before :meth:`update` with the same
        interval, only while calm (the caller's gate: :data:`DIPOLE_LEARN_MAX_RATE`, :data:`DIPOLE_LEARN_MAX_TORQUE`,
        no slew; :meth:`skip_dipole` otherwise).

        ``omega_meas`` is the gyro's reading (rad/s, B); a constant bias in it adds a constant to ``I ω_meas`` and
        nothing to the slope fitted, so the caller gives the reading as measured, not the estimator's bias-corrected
        rate, whose correction moves while it converges.

        The momentum the model does not explain, ``p(t) = I ω_meas − ∫ (τ − ω̂ × (I ω̂ + h_w)) dt`` (N·m·s; the
        torque between the middles of two gyro means taken as the mean of the two intervals'), grows at the
        unmodelled torque ``d``. Its slope over the calm stretch so far is fitted by least squares with weights
        fading as ``e^(−age/T)`` (``T`` = ``time_s``): the gyro's noise σ (rad/s per mean, white) then leaves
        ``σ_d = I σ √Δt / (2 T^1.5)`` per axis once the stretch is long (the weighted fit's variance with the
        exponential's moments; 1e-9 N·m at T = 20 s, Δt = 0.1 s and the adcs gyro's 2.65e-4 rad/s: ADCS-172), where
        a low-pass on the differenced gyro would leave ``I σ / T`` (3e-8 N·m). Once the stretch is ``T`` long,
        ``m̂`` takes the field-perpendicular
        part that explains ``d``, ``(B × d)/|B|²``, and keeps its own part along B (which gives no torque and is
        learned only when the field turns in B). A new stretch (after :meth:`skip_dipole`) starts from the
        dipole learned before, whose torque ``m̂ × B`` turns with the body through a slew."""
        last = self._last
        self._last = (omega_meas, torque_B)
        w = self.omega
        if last is None or w is None or not (dt > 0.0 and time_s > 0.0):
            self._fit = None
            return self.dipole
        w_prev, tau_prev = last
        iw = _mul(self.inertia, w)
        h = wheel_momentum_B
        hx, hy, hz = iw[0] + h[0], iw[1] + h[1], iw[2] + h[2]
        g = (w[1] * hz - w[2] * hy, w[2] * hx - w[0] * hz, w[0] * hy - w[1] * hx)
        dh = _mul(self.inertia, (omega_meas[0] - w_prev[0], omega_meas[1] - w_prev[1], omega_meas[2] - w_prev[2]))
        dp = tuple(dh[i] - dt * (0.5 * (tau_prev[i] + torque_B[i]) - g[i]) for i in range(3))
        fit = self._fit
        if fit is None:  # a new stretch: its first sample, at t = 0 and p = 0 (both measured from now)
            self._fit = fit = [0.0, 1.0, 0.0, 0.0, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
            return self.dipole
        age, sw, st, stt, sp, stp = fit
        # move the origin to now (t → t − Δt, p → p − Δp), fade, and add the new sample at (0, 0)
        stt = stt - 2.0 * dt * st + dt * dt * sw
        st = st - dt * sw
        stp = [stp[i] - dt * sp[i] - dp[i] * st for i in range(3)]  # st: already moved
        sp = [sp[i] - dp[i] * sw for i in range(3)]
        fade = math.exp(-dt / time_s)
        sw, st, stt = fade * sw + 1.0, fade * st, fade * stt
        sp = [fade * x for x in sp]
        stp = [fade * x for x in stp]
        age += dt
        self._fit = [age, sw, st, stt, sp, stp]
        den = sw * stt - st * st
        b2 = b_tesla[0] * b_tesla[0] + b_tesla[1] * b_tesla[1] + b_tesla[2] * b_tesla[2]
        if age < time_s or not (den > 0.0 and b2 > 0.0):
            return self.dipole
        d = [(sw * stp[i] - st * sp[i]) / den for i in range(3)]
        m = self.dipole
        k = (m[0] * b_tesla[0] + m[1] * b_tesla[1] + m[2] * b_tesla[2]) / b2
        bxd = (b_tesla[1] * d[2] - b_tesla[2] * d[1], b_tesla[2] * d[0] - b_tesla[0] * d[2],
               b_tesla[0] * d[1] - b_tesla[1] * d[0])
        self.dipole = tuple(max(-DIPOLE_MAX, min(DIPOLE_MAX, k * b_tesla[i] + bxd[i] / b2)) for i in range(3))
        return self.dipole

    def skip_dipole(self) -> None:
        """Not calm this interval: the next :meth:`learn_dipole` starts a new stretch (nothing learned across)."""
        self._last = None
        self._fit = None

    def update(self, omega_meas: Vec3, torque_B: Vec3, wheel_momentum_B: Vec3, dt: float,
               gain_per_s: float | None = None, b_tesla: Vec3 | None = None) -> Vec3:
        """Advance by ``dt`` under ``torque_B`` (the body torque applied over the interval) and correct with
        ``omega_meas`` (bias-corrected gyro mean over it); returns the estimate now. ``gain_per_s``: the pull for
        this step instead of the model's (a slew's larger one; ``inf``: the gyro mean carried to now). ``b_tesla``
        (T, B; None: none): the field, whose torque on the dipole estimate ``m̂ × B`` the model adds."""
        if b_tesla is not None:
            m = self.dipole
            if m[0] or m[1] or m[2]:
                torque_B = (torque_B[0] + m[1] * b_tesla[2] - m[2] * b_tesla[1],
                            torque_B[1] + m[2] * b_tesla[0] - m[0] * b_tesla[2],
                            torque_B[2] + m[0] * b_tesla[1] - m[1] * b_tesla[0])
        w = self.omega
        if w is None:
            self.omega = w = (float(omega_meas[0]), float(omega_meas[1]), float(omega_meas[2]))
            return w
        iw = _mul(self.inertia, w)
        h = wheel_momentum_B
        hx, hy, hz = iw[0] + h[0], iw[1] + h[1], iw[2] + h[2]
        gx = w[1] * hz - w[2] * hy
        gy = w[2] * hx - w[0] * hz
        gz = w[0] * hy - w[1] * hx
        a = _mul(self.inertia_inv, (torque_B[0] - gx, torque_B[1] - gy, torque_B[2] - gz))
        k = 1.0 - math.exp(-(self.gain if gain_per_s is None else gain_per_s) * dt)
        half = 0.5 * dt
        w0, w1, w2 = w
        a0, a1, a2 = a
        self.omega = out = (w0 + a0 * dt + k * (omega_meas[0] - (w0 + a0 * half)),
                            w1 + a1 * dt + k * (omega_meas[1] - (w1 + a1 * half)),
                            w2 + a2 * dt + k * (omega_meas[2] - (w2 + a2 * half)))
        return out


def applied_torque(wheel_torques, wheel_axes, dipole, b_tesla, duty: float) -> Vec3:
    """The body torque a control cycle applied, N·m (B): the wheels' reaction ``−Σ u_i g_i`` (``u_i`` N·m on
    spin axis ``g_i``) plus the coils' ``m × B`` (``dipole`` A·m², ``b_tesla`` T, None: no field known) over
    their ``duty`` (the fraction of the cycle they are on). The observer's and the residual estimator's input."""
    tx = ty = tz = 0.0
    for u, g in zip(wheel_torques, wheel_axes, strict=False):  # () before the first command
        tx, ty, tz = tx - u * g[0], ty - u * g[1], tz - u * g[2]
    if b_tesla is not None:
        m, b = dipole, b_tesla
        mb = (m[1] * b[2] - m[2] * b[1], m[2] * b[0] - m[0] * b[2], m[0] * b[1] - m[1] * b[0])
        tx, ty, tz = tx + mb[0] * duty, ty + mb[1] * duty, tz + mb[2] * duty
    return (tx, ty, tz)
