"""A simulated on-board orbit propagator: the orbit frame O (z to nadir, y along the negative orbit
normal) relative to inertial space (``orbitFrameGet``), and the ephemeris the attitude controller's moving
targets need (``ephemerisGet``: position and velocity in N, the Earth rotation angle, the Sun's direction), as a
flight computer with a GPS fix or an uplinked ephemeris would know them. Here they are the plant's own (truth)."""
from __future__ import annotations

from fprime_lite import PassiveComponent, sync_input

from detumble.components.attitude_types import Ephemeris, EphemerisGet
from detumble.components.types import OrbitFrame, OrbitFrameGet, Result, Success
from detumble.components.types import new_result as _new_result  # Result(...) without its Python frame
from detumble.drivers.spacecraft import SimulatedSpacecraft

__all__ = ["OrbitEphemeris"]

_SUCCESS = Success.SUCCESS


class OrbitEphemeris(PassiveComponent):
    """Answers ``orbitFrameGet`` with ``q_ON`` (scalar first), the orbit rate and the time, and ``ephemerisGet``."""

    @sync_input(OrbitFrameGet)
    def orbitFrameGet(self) -> Result:
        (q0, q1, q2, q3), n, stamp = self.spacecraft.orbit_frame_sample()
        return _new_result(Result, (OrbitFrame(q0, q1, q2, q3, n, stamp), _SUCCESS))

    @sync_input(EphemerisGet)
    def ephemerisGet(self) -> Result:
        (rx, ry, rz), (vx, vy, vz), angle, (sx, sy, sz) = self.spacecraft.ephemeris_sample()
        return _new_result(Result, (Ephemeris(rx, ry, rz, vx, vy, vz, angle, sx, sy, sz), _SUCCESS))

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        if not isinstance(spacecraft, SimulatedSpacecraft):
            raise TypeError(f"{name}: spacecraft must be a SimulatedSpacecraft, got {spacecraft!r}")
        self.spacecraft = spacecraft
