"""A simulated on-board orbit propagator: the orbit frame O (z to nadir, y along the negative orbit
normal) relative to inertial space, as a flight computer with a GPS fix or an uplinked ephemeris
would know it. Here it is the plant's own orbit (truth)."""
from __future__ import annotations

from fprime_lite import PassiveComponent, sync_input

from detumble.components.types import OrbitFrame, OrbitFrameGet, Result, Success
from detumble.components.types import new_result as _new_result  # Result(...) without its Python frame
from detumble.drivers.spacecraft import SimulatedSpacecraft

__all__ = ["OrbitEphemeris"]

_SUCCESS = Success.SUCCESS


class OrbitEphemeris(PassiveComponent):
    """Answers ``orbitFrameGet`` with ``q_ON`` (scalar first), the orbit rate and the time."""

    @sync_input(OrbitFrameGet)
    def orbitFrameGet(self) -> Result:
        (q0, q1, q2, q3), n, stamp = self.spacecraft.orbit_frame_sample()
        return _new_result(Result, (OrbitFrame(q0, q1, q2, q3, n, stamp), _SUCCESS))

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        if not isinstance(spacecraft, SimulatedSpacecraft):
            raise TypeError(f"{name}: spacecraft must be a SimulatedSpacecraft, got {spacecraft!r}")
        self.spacecraft = spacecraft
