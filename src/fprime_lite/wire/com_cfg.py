"""F´'s ComCfg constants: the values both ends of the ground link must agree on.

The dictionary publishes them (``constants``) and the framings use them; they live here, in the
wire layer, so that neither has to import the other.
"""
from __future__ import annotations

from fprime_lite.model.types import U32

__all__ = ["CONSTANTS", "SPACECRAFT_ID", "TM_FRAME_SIZE"]

#: (qualified name, F´ type, value) of every ComCfg constant, as the dictionary lists them.
CONSTANTS = [
    ("ComCfg.SpacecraftId", U32, 0x44),
    ("ComCfg.TmFrameFixedSize", U32, 1024),
]

#: Spacecraft id of the CCSDS frames (``ComCfg.SpacecraftId``).
SPACECRAFT_ID: int = CONSTANTS[0][2]
#: Size in bytes of a downlink TM frame (``ComCfg.TmFrameFixedSize``).
TM_FRAME_SIZE: int = CONSTANTS[1][2]
