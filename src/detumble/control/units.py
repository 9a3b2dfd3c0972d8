"""Unit conversions the application uses in more than one layer, defined once.

In ``control`` (the lowest application layer, no framework import) so that the plant, the flight
components and the drivers can all import them.
"""

from __future__ import annotations

__all__ = ["GAUSS_PER_TESLA", "TESLA_PER_GAUSS"]

#: 1 T = 1e4 G (the magnetometer reports gauss; the physics works in tesla).
GAUSS_PER_TESLA = 1e4
#: 1 G = 1e-4 T.
TESLA_PER_GAUSS = 1e-4
