"""Exact time integrals of the switched actuator signals, so a log sampled once a second shows what
the coils did between its samples and not only at the sample instants.

The flight software switches the coils within each control cycle (the DetumbleManager drives them in
ACTUATING_BDOT only; the AttitudeController for 80 % of each 20 ms cycle), so a coil level or dipole
read at 1 s instants is aliased: it can read "always on" or "always off" while the true duty is
between. The levels change only when commanded, so their integrals are kept exactly by crediting the
held levels at each change (:meth:`DriveIntegrals.credit`, called by the plant before it changes a
level or a rod dipole) — nothing runs per dynamics step.

:meth:`DriveIntegrals.totals` reads the integrals now; :meth:`DriveIntegrals.interval_means` turns two readings into
the means over the interval between them:

* per coil face, the mean drive level (−127…127) and the share of the interval it was driven
  (level ≠ 0);
* the mean achieved dipole and the mean commanded dipole, A·m² in B. For coils they follow from the
  mean levels (the dipole is linear in the current); a coil with an L/R lag τ carries the current's
  own lag exactly: di/dt = (i_target − i)/τ gives ∫i dt = ∫i_target dt − τ (i(t1) − i(t0)). Ideal
  rods integrate their (piecewise constant) dipole directly.
"""
from __future__ import annotations

from typing import NamedTuple

from detumble.sim.coils import MAX_LEVEL, CoilSet

__all__ = ["DriveIntegrals", "DriveTotals", "IntervalMeans"]

Vec3 = tuple[float, float, float]


class DriveTotals(NamedTuple):
    """The integrals from their start (:class:`DriveIntegrals`' ``t_ns`` at creation) to ``t_ns``."""

    t_ns: int
    level_ns: dict[int, int]          #: face -> ∫ level dt (level · ns, exact)
    on_ns: dict[int, int]             #: face -> ∫ [level ≠ 0] dt (ns, exact)
    current_a: dict[int, float]       #: face -> the coil current at t_ns (A)
    m_ns: Vec3                        #: rods: ∫ achieved dipole dt (A·m²·ns)
    mcmd_ns: Vec3                     #: rods: ∫ commanded dipole dt (A·m²·ns)


class IntervalMeans(NamedTuple):
    """Means over one interval (all zero for an empty interval)."""

    level: dict[int, float]           #: face -> mean drive level, −127…127
    on: dict[int, float]              #: face -> share of the interval driven, 0…1
    m_B: Vec3                         #: mean achieved dipole, A·m², B
    mcmd_B: Vec3                      #: mean commanded dipole, A·m², B


class DriveIntegrals:
    """Running integrals of one plant's actuators (a :class:`CoilSet` or ideal rods), from ``t_ns`` on."""

    def __init__(self, actuators, t_ns: int = 0) -> None:
        self.actuators = actuators
        self.coils = actuators.coils if isinstance(actuators, CoilSet) else None
        #: plant time (ns) the integrals run to; they start at ``t_ns``
        self.t_ns = t_ns
        self._level_ns = dict.fromkeys(self.coils or (), 0)
        self._on_ns = dict.fromkeys(self.coils or (), 0)
        self._m_ns = [0.0, 0.0, 0.0]
        self._mcmd_ns = [0.0, 0.0, 0.0]
        self._mcmd: Vec3 = (0.0, 0.0, 0.0)

    def credit(self, t_ns: int) -> None:
        """Add the present levels (or rod dipole) held since the last credit up to ``t_ns``: call it
        before a level or dipole changes."""
        dt = t_ns - self.t_ns
        if dt <= 0:
            return
        self.t_ns = t_ns
        coils = self.coils
        if coils is not None:
            for face, c in coils.items():
                level = c.level
                if level:
                    self._level_ns[face] += level * dt
                    self._on_ns[face] += dt
            return
        m = self.actuators.dipole_B  # written out: the coursework commands its rods every 10 ms
        cmd = self._mcmd
        mn = self._m_ns
        cn = self._mcmd_ns
        mn[0] += m[0] * dt
        mn[1] += m[1] * dt
        mn[2] += m[2] * dt
        cn[0] += cmd[0] * dt
        cn[1] += cmd[1] * dt
        cn[2] += cmd[2] * dt

    def set_commanded(self, m_B: Vec3) -> None:
        """The rods' commanded dipole from now on, floats (call :meth:`credit` first)."""
        self._mcmd = m_B

    def totals(self, t_ns: int) -> DriveTotals:
        """The integrals from their start up to ``t_ns`` (the plant's present time)."""
        self.credit(t_ns)
        coils = self.coils or {}
        return DriveTotals(t_ns, dict(self._level_ns), dict(self._on_ns),
                           {face: c.current_a for face, c in coils.items()},
                           (self._m_ns[0], self._m_ns[1], self._m_ns[2]),
                           (self._mcmd_ns[0], self._mcmd_ns[1], self._mcmd_ns[2]))

    def interval_means(self, before: DriveTotals, after: DriveTotals) -> IntervalMeans:
        """The means over ``(before.t_ns, after.t_ns]``."""
        dt = after.t_ns - before.t_ns
        if dt <= 0:
            return IntervalMeans({f: 0.0 for f in after.level_ns}, {f: 0.0 for f in after.on_ns},
                                 (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
        level = {f: (after.level_ns[f] - before.level_ns[f]) / dt for f in after.level_ns}
        on = {f: (after.on_ns[f] - before.on_ns[f]) / dt for f in after.on_ns}
        if self.coils is None:
            m1, m0, c1, c0 = after.m_ns, before.m_ns, after.mcmd_ns, before.mcmd_ns
            return IntervalMeans(level, on, ((m1[0] - m0[0]) / dt, (m1[1] - m0[1]) / dt, (m1[2] - m0[2]) / dt),
                                 ((c1[0] - c0[0]) / dt, (c1[1] - c0[1]) / dt, (c1[2] - c0[2]) / dt))
        m = [0.0, 0.0, 0.0]
        cmd = [0.0, 0.0, 0.0]
        dt_s = dt * 1e-9
        for face, c in self.coils.items():
            spec = c.spec
            ohm = spec.resistance_ohm
            target = 0.0 if ohm == 0.0 else level[face] / MAX_LEVEL * spec.voltage_v / ohm
            current = target - c._tau * (after.current_a[face] - before.current_a[face]) / dt_s
            n = c._normal
            for k in range(3):
                m[k] += c._gain * current * n[k]
                cmd[k] += c._gain * target * n[k]
        return IntervalMeans(level, on, (m[0], m[1], m[2]), (cmd[0], cmd[1], cmd[2]))
