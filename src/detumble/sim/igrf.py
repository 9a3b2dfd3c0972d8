"""IGRF-14 to degree and order 13 (the plant's field ``field.model: igrf14``): the model lives in
:mod:`detumble.control.igrf` since 2026-12-05, so that the flight software can carry it (truncated) as its on-board
field model (MAG_FIELD_MODEL_DEGREE); re-exported here for the plant."""

from __future__ import annotations

from detumble.control.igrf import IGRF14_2025, IgrfField

__all__ = ["IGRF14_2025", "IgrfField"]
