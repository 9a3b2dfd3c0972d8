"""Reference magnetic detumble laws for plant-only runs (plain floats, SI unless stated).

Each law is an object with ``update(b_B, t) -> m_B``: given a field measurement ``b_B`` (tesla,
body frame) taken at time ``t`` (s), it returns the dipole (A m^2, body frame) to apply until the
next update. The first update only primes the finite difference and returns zero.

* ``none`` - zero dipole.
* ``kopt`` - the law of the Basilisk cross-check, case A (Markley & Crassidis eq. 7.55; Avanzini &
  Giulietti 2012): ``m = -(k/|B|^2) (B_now - B_prev)/dt`` with ``k = 2 n (1 + sin i) J_min``, the
  whole vector scaled down so that every ``|m_i| <= m_max_i`` (or, with ``control.saturation:
  clip``, each axis clipped on its own; set by :func:`detumble.sim.runner.make_law`).
* ``bdot`` - ``m = -gain * dB/dt`` with the gain in the flight units, A m^2 s / G (dB/dt in
  gauss/s; the flight DetumbleManager's GAIN default is 3.0), scaled like ``kopt``.
* ``bangbang`` - ``m_i = -m_max_i sign(dB_i/dt)``: saturated bang-bang B-dot.

The other laws of :data:`detumble.sim.scenario.LAWS` live beside this module and are made by
:func:`detumble.sim.runner.make_law`: seed 004's in :mod:`detumble.sim.coursework_laws`, and
``adcs``, the three-mode attitude controller of adcs_ref, in :mod:`detumble.sim.adcs_law`.
"""

from __future__ import annotations

import math

from detumble.control.magnetic import clip_to_limits, scale_to_limits  # noqa: F401 - re-exported
from detumble.control.units import GAUSS_PER_TESLA
from detumble.sim.vec import Vec3

_ZERO = (0.0, 0.0, 0.0)


def kopt_gain(mean_motion_rad_s: float, inclination_rad: float, j_min_kg_m2: float) -> float:
    """``k = 2 n (1 + sin i) J_min`` in kg m^2/s (N m s)."""
    return 2.0 * mean_motion_rad_s * (1.0 + math.sin(inclination_rad)) * j_min_kg_m2


class _Differencing:
    #: how a law meets its per-axis limits: ``scale_to_limits`` (default) or ``clip_to_limits``
    limit = staticmethod(scale_to_limits)

    def __init__(self) -> None:
        self._prev: Vec3 | None = None
        self._t_prev = 0.0

    def reset(self) -> None:
        self._prev = None

    def _bdot(self, b: Vec3, t: float) -> Vec3 | None:
        prev, tp = self._prev, self._t_prev
        self._prev, self._t_prev = b, t
        if prev is None or t <= tp:
            return None
        inv = 1.0 / (t - tp)
        return ((b[0] - prev[0]) * inv, (b[1] - prev[1]) * inv, (b[2] - prev[2]) * inv)


class NoLaw:
    name = "none"

    def reset(self) -> None:
        pass

    def update(self, b_B: Vec3, t: float) -> Vec3:
        return _ZERO


class KoptLaw(_Differencing):
    """Gain ``k`` in kg m^2/s; ``m_max`` per axis in A m^2."""

    name = "kopt"

    def __init__(self, k: float, m_max: Vec3) -> None:
        super().__init__()
        self.k = k
        self.m_max = m_max

    def update(self, b_B: Vec3, t: float) -> Vec3:
        bdot = self._bdot(b_B, t)
        b2 = b_B[0] * b_B[0] + b_B[1] * b_B[1] + b_B[2] * b_B[2]
        if bdot is None or b2 == 0.0:
            return _ZERO
        c = -self.k / b2
        return self.limit((c * bdot[0], c * bdot[1], c * bdot[2]), self.m_max)


class BdotLaw(_Differencing):
    """Gain in A m^2 s / G (flight units); ``m_max`` per axis in A m^2."""

    name = "bdot"

    def __init__(self, gain_am2_s_per_gauss: float, m_max: Vec3) -> None:
        super().__init__()
        self.gain = gain_am2_s_per_gauss
        self.m_max = m_max

    def update(self, b_B: Vec3, t: float) -> Vec3:
        bdot = self._bdot(b_B, t)
        if bdot is None:
            return _ZERO
        c = -self.gain * GAUSS_PER_TESLA  # T/s -> G/s
        return self.limit((c * bdot[0], c * bdot[1], c * bdot[2]), self.m_max)


class BangBangLaw(_Differencing):
    name = "bangbang"

    def __init__(self, m_max: Vec3) -> None:
        super().__init__()
        self.m_max = m_max

    def update(self, b_B: Vec3, t: float) -> Vec3:
        bdot = self._bdot(b_B, t)
        if bdot is None:
            return _ZERO
        m = self.m_max
        return (-math.copysign(m[0], bdot[0]) if bdot[0] != 0.0 else 0.0,
                -math.copysign(m[1], bdot[1]) if bdot[1] != 0.0 else 0.0,
                -math.copysign(m[2], bdot[2]) if bdot[2] != 0.0 else 0.0)
