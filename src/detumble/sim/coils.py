"""Magnetorquers: the DRV2605-driven face coils of the reference 1U, and ideal torque rods.

One coil per face, driven by a DRV2605 with a signed level -127...127::

    V = level / 127 * V_supply          (volts)
    I = V / R                           (amps; with L > 0 the current lags with tau = L / R)
    m = N * I * A * n_face              (A m^2, along the face's outward normal)

Faces and outward normals: X+ 0 (+x), X- 1 (-x), Y+ 2 (+y), Y- 3 (-y), Z- 5 (-z); there is no Z+
coil (face 4). Because the minus-face coils are mounted mirrored, a *positive* level on X- gives a
**-X** dipole - which is why the flight DetumbleManager sends X- = -level. Default geometry is the
DetumbleManager parameter defaults (detumble.md section 3): X/Y coils 96 turns, 0.053 x 0.045 m,
13 ohm, 3.3 V (m_max 0.0581 A m^2 each); Z- 153 turns, 57.55 mm diameter, 150.7 ohm (0.00872 A m^2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

from detumble.control.coil_layout import (FACE_AXIS, FACE_KEYS, FACE_NORMALS_B, FLIGHT_XY_COIL, FLIGHT_Z_COIL,
                                          CoilGeometry, CoilShape, DirectionSign, Face, flight_coil_layout)
from detumble.control.magnetorquer import MAX_DRIVE_LEVEL
from detumble.control.magnetorquer import Magnetorquer as FlightCoilMath

X_PLUS, X_MINUS, Y_PLUS, Y_MINUS, Z_MINUS = (Face.X_PLUS, Face.X_MINUS, Face.Y_PLUS, Face.Y_MINUS, Face.Z_MINUS)
#: Scenario keys by face (``x_plus`` …).
FACE_NAMES = FACE_KEYS
MAX_LEVEL = MAX_DRIVE_LEVEL


@dataclass(frozen=True)
class CoilSpec:
    """One coil: turns, supply volts, ohms, shape ('rectangular' or 'circular'), metres, henries.

    The defaults are the flight X/Y coil (:data:`~detumble.control.coil_layout.FLIGHT_XY_COIL`);
    area, full-scale current and drive levels come from the flight coil arithmetic
    (:class:`detumble.control.magnetorquer.Magnetorquer`), so plant and flight agree to the bit.
    """

    turns: float = FLIGHT_XY_COIL.turns
    voltage_v: float = FLIGHT_XY_COIL.voltage_v
    resistance_ohm: float = FLIGHT_XY_COIL.resistance_ohm
    shape: str = FLIGHT_XY_COIL.shape.name.lower()
    length_m: float = FLIGHT_XY_COIL.length_m
    width_m: float = FLIGHT_XY_COIL.width_m
    diameter_m: float = FLIGHT_XY_COIL.diameter_m
    inductance_h: float = 0.0

    @classmethod
    def from_geometry(cls, geometry: CoilGeometry, inductance_h: float = 0.0) -> "CoilSpec":
        return cls(turns=geometry.turns, voltage_v=geometry.voltage_v, resistance_ohm=geometry.resistance_ohm,
                   shape=geometry.shape.name.lower(), length_m=geometry.length_m, width_m=geometry.width_m,
                   diameter_m=geometry.diameter_m, inductance_h=inductance_h)

    @cached_property
    def flight_math(self) -> FlightCoilMath:
        """The flight coil arithmetic for this coil, direction sign +1 (the face applies its own)."""
        return FlightCoilMath(turns=self.turns, voltage=self.voltage_v, resistance=self.resistance_ohm,
                              direction_sign=DirectionSign.POSITIVE, shape=CoilShape[self.shape.upper()],
                              width=self.width_m, length=self.length_m, diameter=self.diameter_m)

    @property
    def area_m2(self) -> float:
        return self.flight_math.coil_area()

    @property
    def max_current_a(self) -> float:
        return self.flight_math.max_coil_current()

    @property
    def max_dipole_am2(self) -> float:
        """Dipole magnitude at full drive (|level| = 127), A m^2."""
        return self.flight_math.max_dipole_moment()

    @property
    def time_constant_s(self) -> float:
        return 0.0 if self.resistance_ohm == 0.0 else self.inductance_h / self.resistance_ohm


XY_COIL_DEFAULT = CoilSpec.from_geometry(FLIGHT_XY_COIL)
Z_COIL_DEFAULT = CoilSpec.from_geometry(FLIGHT_Z_COIL)


def default_coil_layout() -> dict[int, CoilSpec]:
    return {int(face): CoilSpec.from_geometry(geometry) for face, geometry in flight_coil_layout().items()}


def level_for_coil_dipole(spec: CoilSpec, m: float) -> int:
    """Unsigned-direction drive level giving dipole ``m`` (A m^2) along the coil's own axis.

    The flight Magnetorquer's arithmetic (detumble.md section 5), so results match it; saturates
    at +-127. The caller applies the face's mounting sign.
    """
    return spec.flight_math.dipole_moment_to_current(m)


class Magnetorquer:
    """One face coil with its drive state. ``level`` in -127...127; current in amps."""

    __slots__ = ("face", "spec", "level", "current_a", "_normal", "_gain", "_tau")

    def __init__(self, face: int, spec: CoilSpec) -> None:
        if face not in FACE_NORMALS_B:
            raise ValueError(f"no coil on face {face}; faces are X+ 0, X- 1, Y+ 2, Y- 3, Z- 5")
        self.face = face
        self.spec = spec
        self.level = 0
        self.current_a = 0.0
        self._normal = FACE_NORMALS_B[Face(face)]
        self._gain = spec.turns * spec.area_m2  # A m^2 per amp
        self._tau = spec.time_constant_s

    def target_current_a(self) -> float:
        if self.spec.resistance_ohm == 0.0:
            return 0.0
        return self.level / MAX_LEVEL * self.spec.voltage_v / self.spec.resistance_ohm

    def set_level(self, level: int) -> None:
        if type(level) is not int and (isinstance(level, bool) or not isinstance(level, int)):
            raise TypeError(f"drive level must be an int in -127..127, got {level!r}")
        if not -MAX_LEVEL <= level <= MAX_LEVEL:
            raise ValueError(f"drive level {level} outside -127..127")
        self.level = level
        if self._tau == 0.0:
            self.current_a = self.target_current_a()

    def advance(self, dt: float) -> float:
        """Advance the L/R lag by ``dt`` s; return the mean current (A) over the interval."""
        target = self.target_current_a()
        if self._tau == 0.0 or self.current_a == target:
            self.current_a = target
            return target
        i0 = self.current_a
        decay = math.exp(-dt / self._tau)
        self.current_a = target + (i0 - target) * decay
        return target + (i0 - target) * self._tau / dt * (1.0 - decay)

    def dipole_B(self, current_a: float | None = None) -> tuple[float, float, float]:
        """Dipole (A m^2, body frame) for the present (or a given) current."""
        m = self._gain * (self.current_a if current_a is None else current_a)
        n = self._normal
        return (m * n[0], m * n[1], m * n[2])


class CoilSet:
    """The spacecraft's face coils. ``dipole_B`` is the total instantaneous dipole (A m^2)."""

    kind = "coils"

    def __init__(self, layout: dict[int, CoilSpec]) -> None:
        self.coils = {face: Magnetorquer(face, spec) for face, spec in sorted(layout.items())}
        self._lagged = any(c._tau > 0.0 for c in self.coils.values())
        self._dipole_B = (0.0, 0.0, 0.0)
        #: without lag, a level changed since ``_dipole_B`` was summed: :attr:`dipole_B` sums it again
        #: when next read (the controller changes several levels per cycle; one sum serves them all)
        self._dipole_stale = False
        #: every coil's current is at its target and no level changed since: advance() has nothing to do
        self._settled = True

    def set_level(self, face: int, level: int) -> None:
        coil = self.coils.get(face)
        if coil is None:
            raise ValueError(f"no coil on face {face}; this spacecraft has faces {sorted(self.coils)}")
        if type(level) is int and level == coil.level:
            return  # drivers re-command the same level every tick; nothing changes
        coil.set_level(level)
        self._settled = False
        if not self._lagged:
            self._dipole_stale = True  # the currents follow the levels at once; summed when read

    @property
    def dipole_B(self) -> tuple[float, float, float]:
        """Total instantaneous dipole (A m^2, B): :meth:`_sum` at the present currents."""
        if self._dipole_stale:
            self._dipole_B = self._sum()
            self._dipole_stale = False
        return self._dipole_B

    def levels(self) -> dict[int, int]:
        return {face: c.level for face, c in self.coils.items()}

    def _sum(self, currents=None):
        """Σ of the coils' ``dipole_B`` (A m^2, B) at their present currents or at ``currents`` (by face),
        in face order; each coil's term is computed as :meth:`Magnetorquer.dipole_B` does (same floats)."""
        mx = my = mz = 0.0
        for face, c in self.coils.items():
            m = c._gain * (c.current_a if currents is None else currents[face])
            n = c._normal
            mx += m * n[0]
            my += m * n[1]
            mz += m * n[2]
        return (mx, my, mz)

    def advance(self, dt: float) -> tuple[float, float, float]:
        """Advance coil currents by ``dt``; return the mean total dipole over the interval."""
        if not self._lagged or self._settled:
            # Settled: each coil's mean current is its (unchanged) current, so the mean dipole is
            # the dipole_B the last advance computed from those very currents - the same floats.
            # Without lag the currents are the levels' own; the sum is redone after a level change.
            if self._dipole_stale:
                self._dipole_B = self._sum()
                self._dipole_stale = False
            return self._dipole_B
        mean = {face: c.advance(dt) for face, c in self.coils.items()}
        self._dipole_B = self._sum()
        self._settled = all(c.current_a == c.target_current_a() for c in self.coils.values())
        return self._sum(mean)

    def commanded_dipole_B(self) -> tuple[float, float, float]:
        """The dipole the present levels give once the currents have settled (A m^2, B)."""
        return self._sum({face: c.target_current_a() for face, c in self.coils.items()})

    def max_dipole_per_axis(self) -> tuple[float, float, float]:
        """Largest |m| achievable on each body axis with every coil on that axis at full drive."""
        out = [0.0, 0.0, 0.0]
        for face, c in self.coils.items():
            axis = FACE_AXIS[Face(face)]
            out[axis] += c.spec.max_dipole_am2
        return (out[0], out[1], out[2])

    def levels_for_dipole_B(self, m_B: tuple[float, float, float]) -> dict[int, int]:
        """Drive levels that produce ``m_B`` with the coils of each axis sharing it equally.

        (Unlike the flight DetumbleManager, which drives both coils of a pair with the full
        component and so doubles the X and Y dipole - see detumble.md section 5.)
        """
        by_axis: dict[int, list[int]] = {0: [], 1: [], 2: []}
        for face in self.coils:
            axis = FACE_AXIS[Face(face)]
            by_axis[axis].append(face)
        out = {}
        for axis, faces in by_axis.items():
            for face in faces:
                share = m_B[axis] / len(faces)
                sign = FACE_NORMALS_B[Face(face)][axis]
                out[face] = int(sign) * level_for_coil_dipole(self.coils[face].spec, share)
        return out

    def apply_dipole_B(self, m_B: tuple[float, float, float]) -> None:
        for face, level in self.levels_for_dipole_B(m_B).items():
            self.set_level(face, level)


class TorqueRods:
    """Ideal orthogonal torque rods along the body axes, each limited to ``max_dipole_am2``."""

    kind = "rods"

    def __init__(self, max_dipole_am2: tuple[float, float, float]) -> None:
        m = [float(x) for x in max_dipole_am2]
        self.max_dipole = (m[0], m[1], m[2])
        self.dipole_B = (0.0, 0.0, 0.0)

    def max_dipole_per_axis(self) -> tuple[float, float, float]:
        return self.max_dipole

    def apply_dipole_B(self, m_B: tuple[float, float, float]) -> None:
        lx, ly, lz = self.max_dipole
        mx, my, mz = m_B
        self.dipole_B = (
            lx if mx > lx else (-lx if mx < -lx else float(mx)),
            ly if my > ly else (-ly if my < -ly else float(my)),
            lz if mz > lz else (-lz if mz < -lz else float(mz)),
        )

    def advance(self, dt: float) -> tuple[float, float, float]:
        return self.dipole_B

    def commanded_dipole_B(self) -> tuple[float, float, float]:
        return self.dipole_B
