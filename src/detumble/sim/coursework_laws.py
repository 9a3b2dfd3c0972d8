"""Seed 004's controllers flown plant-only (``fprime-lite sim --law cross_product|beta_pd|wheels_pd``).

Adapters between the plant's readings and :mod:`detumble.control.coursework`, which holds the laws
in the report's convention. A *full-state* law gets, once per control period, the field (T, B),
the gyro rate (rad/s, B), the attitude relative to the orbit frame (``q_BO``, scalar first; from the
star tracker when the scenario has one, else the truth) and the wheel momenta (N m s), and returns
a dipole (A m², B) and, for the wheel law, one motor torque per wheel (N m).
"""
from __future__ import annotations

from detumble.control import coursework as cw
from detumble.sim.vec import Vec3

__all__ = ["CrossProductLaw", "BetaPdLaw", "WheelsPdLaw", "REPORT_CROSS_PRODUCT_GAIN"]

#: The report's best ``magnetorquer1`` gain (its Figure 1).
REPORT_CROSS_PRODUCT_GAIN = 146.0


class _FullState:
    full_state = True
    wheel_law = False

    def __init__(self, m_max: Vec3):
        self.m_max = m_max

    def reset(self) -> None:
        pass

    def _clip(self, m) -> Vec3:
        lx, ly, lz = self.m_max
        return (max(-lx, min(lx, m[0])), max(-ly, min(ly, m[1])), max(-lz, min(lz, m[2])))


class CrossProductLaw(_FullState):
    """``magnetorquer1``: ``M = k (ω × B)``, each axis clipped (eq. 19). ``k`` in A m² /(rad/s · T)."""

    name = "cross_product"

    def __init__(self, k: float, m_max: Vec3):
        super().__init__(m_max)
        self.k = float(k)

    def command(self, t, b_B, w_B, q_BO, h):
        return self._clip(cw.cross_product_dipole(self.k, w_B, b_B)), None


class BetaPdLaw(_FullState):
    """``magnetorquer2``: eqs. 20–24 with β̇ between successive control periods."""

    name = "beta_pd"

    def __init__(self, k_s: float, k_d: float, n: float, m_max: Vec3, switched: bool = True):
        super().__init__(m_max)
        self.law = cw.BetaPd(k_s, k_d, n=n, switched=switched)
        self.gain = (k_s, k_d)

    def reset(self) -> None:
        self.law.previous = None

    def command(self, t, b_B, w_B, q_BO, h):
        return self._clip(self.law.dipole(t, w_B, b_B)), None


class WheelsPdLaw(_FullState):
    """``wheels``: eqs. 25–26 (:class:`detumble.control.coursework.WheelsPd`), the torques limited
    as the report does (``limits="report"``) or only by the wheels themselves (``limits="wheel"``,
    the plant's exact saturation); ``error="shortest_path"`` (default) for the corrected law,
    ``error="report"`` for eq. 25 as the report writes it (the long way round); ``dump_gain``
    > 0 adds magnetic momentum dumping with the rods (not in the report)."""

    name = "wheels_pd"
    wheel_law = True

    def __init__(self, k_p: float, k_d: float, inertia, n: float, target_q_BO, m_max: Vec3,
                 limits: str = "report", error: str = "shortest_path", dump_gain: float = 0.0):
        super().__init__(m_max)
        self.dump_gain = float(dump_gain)
        self.law = cw.WheelsPd(k_p, k_d, inertia, cw.from_plant_quaternion(target_q_BO), n,
                               shortest_path=error == "shortest_path")
        self.gain = (self.law.k_p, self.law.k_d)
        self.limits = limits

    def reset(self) -> None:
        self.law.previous = None

    def command(self, t, b_B, w_B, q_BO, h):
        torque = self.law.torque(cw.from_plant_quaternion(q_BO), w_B, h)
        if self.limits == "report":
            torque = cw.limit_wheel_torque(torque, h)
        dipole = self._clip(cw.dumping_dipole(self.dump_gain, h, b_B)) if self.dump_gain > 0.0 else (0.0, 0.0, 0.0)
        return dipole, torque
