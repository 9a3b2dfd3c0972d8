"""The reference 1U's magnetorquer faces and coils: the one place these facts are written.

Faces are numbered as the flight software numbers its DRV2605 drivers (``drv2605Face<N>Manager``):
X+ 0, X− 1, Y+ 2, Y− 3, Z− 5; there is no Z+ coil (face 4). Each coil's axis is its face's
outward normal in the body frame B. The minus-face coils are mounted mirrored: a *positive* drive
level on X− gives a −X dipole, which is why the flight DetumbleManager sends X− = −level (its
:class:`DirectionSign`). The default geometry is the DetumbleManager's parameter defaults
(spec/detumble.md §3): X/Y coils 96 turns, 0.053 × 0.045 m, 13 Ω, 3.3 V; Z− 153 turns, 57.55 mm
diameter, 150.7 Ω, 3.3 V.

Plain Python, no framework import: the flight components, the plant and the simulated drivers all
read these names.
"""
from __future__ import annotations

import enum
from dataclasses import dataclass

__all__ = ["Face", "CoilShape", "DirectionSign", "COIL_FACES", "FACE_KEYS", "FACE_LABELS", "FACE_NORMALS_B",
           "FACE_AXIS", "MOUNTING_SIGN", "CoilGeometry", "FLIGHT_XY_COIL", "FLIGHT_Z_COIL", "flight_coil_layout"]


class Face(enum.IntEnum):
    """Cube faces by the flight driver numbering."""

    X_PLUS = 0
    X_MINUS = 1
    Y_PLUS = 2
    Y_MINUS = 3
    Z_PLUS = 4
    Z_MINUS = 5


class CoilShape(enum.IntEnum):
    """Coil outline; the numeric values are ``Components.CoilShape``'s."""

    RECTANGULAR = 0
    CIRCULAR = 1


class DirectionSign(enum.IntEnum):
    """+1 when a positive drive level produces a dipole along the coil's face normal's axis in the
    positive sense, −1 when it opposes it (the mirrored X−, Y− and Z− coils)."""

    POSITIVE = 1
    NEGATIVE = -1


#: Faces that carry a coil, in the flight drive order (X+, X−, Y+, Y−, Z−).
COIL_FACES: tuple[Face, ...] = (Face.X_PLUS, Face.X_MINUS, Face.Y_PLUS, Face.Y_MINUS, Face.Z_MINUS)
#: Scenario-file keys of the coil faces (``spacecraft.actuators.x_plus`` …).
FACE_KEYS = {face: face.name.lower() for face in COIL_FACES}
#: Short labels for plots and logs.
FACE_LABELS = {Face.X_PLUS: "X+", Face.X_MINUS: "X−", Face.Y_PLUS: "Y+", Face.Y_MINUS: "Y−", Face.Z_MINUS: "Z−"}
#: Outward face normals in the body frame (unit vectors).
FACE_NORMALS_B: dict[Face, tuple[float, float, float]] = {
    Face.X_PLUS: (1.0, 0.0, 0.0),
    Face.X_MINUS: (-1.0, 0.0, 0.0),
    Face.Y_PLUS: (0.0, 1.0, 0.0),
    Face.Y_MINUS: (0.0, -1.0, 0.0),
    Face.Z_MINUS: (0.0, 0.0, -1.0),
}
#: Body axis (0 x, 1 y, 2 z) each coil acts along.
FACE_AXIS = {face: next(i for i, c in enumerate(normal) if c != 0.0) for face, normal in FACE_NORMALS_B.items()}
#: The flight manager's direction sign for each coil: the sign of its face normal.
MOUNTING_SIGN = {face: DirectionSign(int(FACE_NORMALS_B[face][FACE_AXIS[face]])) for face in COIL_FACES}


@dataclass(frozen=True)
class CoilGeometry:
    """One coil as the flight parameters describe it: turns, volts, ohms, outline and metres."""

    turns: float
    voltage_v: float
    resistance_ohm: float
    shape: CoilShape
    length_m: float = 0.0
    width_m: float = 0.0
    diameter_m: float = 0.0


#: The X and Y coils' flight defaults.
FLIGHT_XY_COIL = CoilGeometry(turns=96.0, voltage_v=3.3, resistance_ohm=13.0, shape=CoilShape.RECTANGULAR,
                              length_m=0.053, width_m=0.045)
#: The Z− coil's flight defaults.
FLIGHT_Z_COIL = CoilGeometry(turns=153.0, voltage_v=3.3, resistance_ohm=150.7, shape=CoilShape.CIRCULAR,
                             diameter_m=0.05755)


def flight_coil_layout() -> dict[Face, CoilGeometry]:
    """The reference 1U's coils by face, at the flight defaults."""
    return {face: (FLIGHT_Z_COIL if face is Face.Z_MINUS else FLIGHT_XY_COIL) for face in COIL_FACES}
