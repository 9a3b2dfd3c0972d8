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

X_PLUS, X_MINUS, Y_PLUS, Y_MINUS, Z_MINUS = 0, 1, 2, 3, 5
FACE_NAMES = {X_PLUS: "x_plus", X_MINUS: "x_minus", Y_PLUS: "y_plus", Y_MINUS: "y_minus", Z_MINUS: "z_minus"}
FACE_NORMALS_B = {
    X_PLUS: (1.0, 0.0, 0.0),
    X_MINUS: (-1.0, 0.0, 0.0),
    Y_PLUS: (0.0, 1.0, 0.0),
    Y_MINUS: (0.0, -1.0, 0.0),
    Z_MINUS: (0.0, 0.0, -1.0),
}
MAX_LEVEL = 127


@dataclass(frozen=True)
class CoilSpec:
    """One coil: turns, supply volts, ohms, shape ('rectangular' or 'circular'), metres, henries."""

    turns: float = 96.0
    voltage_v: float = 3.3
    resistance_ohm: float = 13.0
    shape: str = "rectangular"
    length_m: float = 0.053
    width_m: float = 0.045
    diameter_m: float = 0.0
    inductance_h: float = 0.0

    @property
    def area_m2(self) -> float:
        if self.shape == "circular":
            return math.pi * (self.diameter_m / 2.0) ** 2
        return self.width_m * self.length_m

    @property
    def max_current_a(self) -> float:
        return 0.0 if self.resistance_ohm == 0.0 else self.voltage_v / self.resistance_ohm

    @property
    def max_dipole_am2(self) -> float:
        """Dipole magnitude at full drive (|level| = 127), A m^2."""
        return self.turns * self.area_m2 * self.max_current_a

    @property
    def time_constant_s(self) -> float:
        return 0.0 if self.resistance_ohm == 0.0 else self.inductance_h / self.resistance_ohm


XY_COIL_DEFAULT = CoilSpec()
Z_COIL_DEFAULT = CoilSpec(turns=153.0, resistance_ohm=150.7, shape="circular", length_m=0.0, width_m=0.0, diameter_m=0.05755)


def default_coil_layout() -> dict[int, CoilSpec]:
    return {X_PLUS: XY_COIL_DEFAULT, X_MINUS: XY_COIL_DEFAULT, Y_PLUS: XY_COIL_DEFAULT,
            Y_MINUS: XY_COIL_DEFAULT, Z_MINUS: Z_COIL_DEFAULT}


def round_half_away_from_zero(x: float) -> int:
    return int(math.floor(abs(x) + 0.5)) * (1 if x >= 0 else -1)


def level_for_coil_dipole(spec: CoilSpec, m: float) -> int:
    """Unsigned-direction drive level giving dipole ``m`` (A m^2) along the coil's own axis.

    Same operation order as the flight Magnetorquer (detumble.md section 5) so results match it;
    saturates at +-127. The caller applies the face's mounting sign.
    """
    area = spec.area_m2
    target = 0.0 if spec.turns == 0 or area == 0 else m / (spec.turns * area)
    imax = 0.0 if spec.resistance_ohm == 0 else spec.voltage_v / spec.resistance_ohm
    clamped = math.copysign(imax, target) if abs(target) > imax else target
    return 0 if imax == 0 else round_half_away_from_zero(clamped / imax * 127)


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
        self._normal = FACE_NORMALS_B[face]
        self._gain = spec.turns * spec.area_m2  # A m^2 per amp
        self._tau = spec.time_constant_s

    def target_current_a(self) -> float:
        if self.spec.resistance_ohm == 0.0:
            return 0.0
        return self.level / MAX_LEVEL * self.spec.voltage_v / self.spec.resistance_ohm

    def set_level(self, level: int) -> None:
        if isinstance(level, bool) or not isinstance(level, int):
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
        self.dipole_B = (0.0, 0.0, 0.0)

    def set_level(self, face: int, level: int) -> None:
        coil = self.coils.get(face)
        if coil is None:
            raise ValueError(f"no coil on face {face}; this spacecraft has faces {sorted(self.coils)}")
        if type(level) is int and level == coil.level:
            return  # drivers re-command the same level every tick; nothing changes
        coil.set_level(level)
        if not self._lagged:
            self.dipole_B = self._sum()

    def levels(self) -> dict[int, int]:
        return {face: c.level for face, c in self.coils.items()}

    def _sum(self, currents=None):
        mx = my = mz = 0.0
        for face, c in self.coils.items():
            d = c.dipole_B(None if currents is None else currents[face])
            mx += d[0]
            my += d[1]
            mz += d[2]
        return (mx, my, mz)

    def advance(self, dt: float) -> tuple[float, float, float]:
        """Advance coil currents by ``dt``; return the mean total dipole over the interval."""
        if not self._lagged:
            return self.dipole_B
        mean = {face: c.advance(dt) for face, c in self.coils.items()}
        self.dipole_B = self._sum()
        return self._sum(mean)

    def commanded_dipole_B(self) -> tuple[float, float, float]:
        """The dipole the present levels give once the currents have settled (A m^2, B)."""
        return self._sum({face: c.target_current_a() for face, c in self.coils.items()})

    def max_dipole_per_axis(self) -> tuple[float, float, float]:
        """Largest |m| achievable on each body axis with every coil on that axis at full drive."""
        out = [0.0, 0.0, 0.0]
        for face, c in self.coils.items():
            axis = [i for i in range(3) if FACE_NORMALS_B[face][i] != 0.0][0]
            out[axis] += c.spec.max_dipole_am2
        return (out[0], out[1], out[2])

    def levels_for_dipole_B(self, m_B: tuple[float, float, float]) -> dict[int, int]:
        """Drive levels that produce ``m_B`` with the coils of each axis sharing it equally.

        (Unlike the flight DetumbleManager, which drives both coils of a pair with the full
        component and so doubles the X and Y dipole - see detumble.md section 5.)
        """
        by_axis: dict[int, list[int]] = {0: [], 1: [], 2: []}
        for face in self.coils:
            axis = [i for i in range(3) if FACE_NORMALS_B[face][i] != 0.0][0]
            by_axis[axis].append(face)
        out = {}
        for axis, faces in by_axis.items():
            for face in faces:
                share = m_B[axis] / len(faces)
                sign = FACE_NORMALS_B[face][axis]
                out[face] = int(sign) * level_for_coil_dipole(self.coils[face].spec, share)
        return out

    def apply_dipole_B(self, m_B: tuple[float, float, float]) -> None:
        for face, level in self.levels_for_dipole_B(m_B).items():
            self.set_level(face, level)


class TorqueRods:
    """Ideal orthogonal torque rods along the body axes, each limited to ``max_dipole_am2``."""

    kind = "rods"

    def __init__(self, max_dipole_am2: tuple[float, float, float]) -> None:
        self.max_dipole = tuple(float(x) for x in max_dipole_am2)
        self.dipole_B = (0.0, 0.0, 0.0)

    def max_dipole_per_axis(self) -> tuple[float, float, float]:
        return self.max_dipole  # type: ignore[return-value]

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
