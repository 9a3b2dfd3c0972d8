"""One magnetorquer coil: converts a dipole-moment component into a signed drive level.

Plain Python (no framework import); runs on the 50 Hz path. Units: dipole in A·m², lengths in
metres, voltage in volts, resistance in ohms, current in amperes. The drive level is a signed
integer in −127…127 where ±127 is the coil's maximum current ``voltage / resistance`` and the sign
is the current direction seen by the driver (detumble.md §5).

The operation order below is the flight code's and is kept on purpose: reference values depend on
it (a 0.1 × 0.2 m coil has area 0.020000000000000004 m², so a mathematically "half" level lands on
63, not 64). Rounding is half away from zero, as C++ ``std::round`` (never Python's ``round``,
which rounds half to even).
"""

from __future__ import annotations

import math

from detumble.control.coil_layout import CoilShape, DirectionSign

__all__ = ["CoilShape", "DirectionSign", "Magnetorquer", "round_half_away_from_zero", "MAX_DRIVE_LEVEL", "drive_level",
           "face_coil_levels"]

#: Full-scale drive level (the I8 range used by the coil drivers is −127…127).
MAX_DRIVE_LEVEL = 127



def round_half_away_from_zero(x: float) -> int:
    """Round to the nearest integer, halves away from zero (C++ ``std::round``).

    Exact for every finite double (``x - floor(x)`` is computed without rounding error), so
    0.49999999999999994 rounds to 0, 2.5 to 3 and −2.5 to −3. ``x`` must be finite.
    """
    magnitude = abs(x)
    whole = math.floor(magnitude)
    if magnitude - whole >= 0.5:
        whole += 1
    return -whole if x < 0 else whole



def drive_level(m: float, m_max: float) -> int:
    """Drive level −127…127 for dipole ``m`` (A·m²) on a coil whose full drive gives ``m_max`` A·m²
    (0 for a non-finite ``m`` or a coil that gives nothing)."""
    if not m_max > 0.0 or not math.isfinite(m):
        return 0
    level = round_half_away_from_zero(m / m_max * MAX_DRIVE_LEVEL)
    return max(-MAX_DRIVE_LEVEL, min(MAX_DRIVE_LEVEL, level))


def face_coil_levels(m, cx: float, cy: float, cz: float):
    """``((levels X+, X−, Y+, Y−, Z−), achieved dipole A·m²)`` for the dipole ``m`` (A·m², B) on the five face
    coils (``cx``, ``cy``, ``cz``: one X, Y or Z coil's full-drive dipole, A·m²): half of m_x on each X coil,
    half of m_y on each Y coil, m_z on Z−; X−, Y− and Z− face the other way."""
    lx, ly, lz = drive_level(0.5 * m[0], cx), drive_level(0.5 * m[1], cy), drive_level(m[2], cz)
    f = 1.0 / MAX_DRIVE_LEVEL
    return (lx, -lx, ly, -ly, -lz), (2.0 * lx * f * cx, 2.0 * ly * f * cy, lz * f * cz)


class Magnetorquer:
    """Geometry and electrical limits of one coil.

    Attributes:
        turns: number of turns.
        voltage: drive voltage, V.
        resistance: coil resistance, Ω.
        direction_sign: :class:`DirectionSign` applied to the level.
        shape: :class:`CoilShape`; RECTANGULAR uses ``width · length``, CIRCULAR uses ``diameter``.
        width, length, diameter: metres.
    """

    def __init__(self, *, turns: float = 0.0, voltage: float = 0.0, resistance: float = 0.0,
                 direction_sign: DirectionSign = DirectionSign.POSITIVE,
                 shape: CoilShape = CoilShape.RECTANGULAR, width: float = 0.0, length: float = 0.0,
                 diameter: float = 0.0):
        self.turns = float(turns)
        self.voltage = float(voltage)
        self.resistance = float(resistance)
        self.direction_sign = DirectionSign(direction_sign)
        self.shape = CoilShape(int(shape))
        self.width = float(width)
        self.length = float(length)
        self.diameter = float(diameter)

    def coil_area(self) -> float:
        """Enclosed area, m²."""
        if self.shape == CoilShape.CIRCULAR:
            return math.pi * (self.diameter / 2.0) ** 2
        return self.width * self.length

    def max_coil_current(self) -> float:
        """Largest current the driver can push, ``voltage / resistance`` A (0 when resistance is 0)."""
        if self.resistance == 0.0:
            return 0.0
        return self.voltage / self.resistance

    def target_current(self, dipole_moment_component: float) -> float:
        """Current that would produce ``dipole_moment_component`` A·m² along the coil axis, A."""
        area = self.coil_area()
        if self.turns == 0.0 or area == 0.0:
            return 0.0
        return dipole_moment_component / (self.turns * area)

    def max_dipole_moment(self) -> float:
        """Dipole at full-scale current, A·m² (``turns · area · imax``)."""
        return self.turns * self.coil_area() * self.max_coil_current()

    def dipole_moment_to_current(self, dipole_moment_component: float) -> int:
        """Signed drive level (−127…127) for a dipole component in A·m² along this coil's axis.

        The requested current is clamped to ±imax, scaled to ±127 and rounded half away from zero,
        then multiplied by :attr:`direction_sign`. A non-finite request, or a coil whose maximum
        current is not a positive finite number (zero, negative or NaN resistance/voltage), gives 0:
        no drive rather than an exception.
        """
        if not math.isfinite(dipole_moment_component):
            return 0
        target = self.target_current(dipole_moment_component)
        imax = self.max_coil_current()
        if not (imax > 0.0 and math.isfinite(imax)) or math.isnan(target):
            return 0
        if abs(target) > imax:
            clamped = imax if target > 0 else -imax
        else:
            clamped = target
        scaled = clamped / imax * MAX_DRIVE_LEVEL
        if not math.isfinite(scaled):
            return 0
        level = round_half_away_from_zero(scaled)
        return int(self.direction_sign) * level

    def __repr__(self) -> str:
        size = (f"diameter={self.diameter}" if self.shape == CoilShape.CIRCULAR
                else f"{self.width}x{self.length}")
        return (f"Magnetorquer({self.shape.name} {size} m, {self.turns} turns, {self.voltage} V, "
                f"{self.resistance} ohm, {self.direction_sign.name})")
