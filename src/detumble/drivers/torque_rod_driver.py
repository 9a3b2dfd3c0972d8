"""A simulated driver for ideal orthogonal torque rods (the coursework's magnetorquers, seed 004).

``dipoleSet(dipole)`` commands the rods' dipole (A·m², body frame) from now on; the plant limits
each axis to the rods' maximum (scenario ``spacecraft.actuators.max_dipole_am2``), and the driver
reports what the rods give. A non-finite command turns the rods off (a throttled WARNING_LO), a
limited one raises a throttled WARNING_LO, and ``STOP`` turns them off from the ground.
"""
from __future__ import annotations

import math

from fprime_lite import CmdResponse, Channel, Event, PassiveComponent, Severity, sync_command, sync_input
from fprime_lite.model.types import F64

from detumble.components.types import DipoleMoment, DipoleMomentSet, Success
from detumble.drivers.spacecraft import SimulatedSpacecraft

__all__ = ["TorqueRodDriver"]


class TorqueRodDriver(PassiveComponent):
    """Three ideal rods along body x, y, z on ``spacecraft`` (its actuators must be ``rods``)."""

    @sync_input(DipoleMomentSet)
    def dipoleSet(self, dipole: DipoleMoment) -> Success:
        """Command ``dipole`` (A·m², B); FAILURE (rods off) for a non-finite request."""
        request = (dipole.x, dipole.y, dipole.z)
        if not all(math.isfinite(c) for c in request):
            self._apply((0.0, 0.0, 0.0))
            self.InvalidDipole(*request)
            return Success.FAILURE
        achieved = self._apply(request)
        if any(abs(a - r) > 1e-12 * max(1.0, abs(r)) for a, r in zip(achieved, request, strict=True)):
            self.DipoleLimited(*request)
        return Success.SUCCESS

    @sync_command()
    def STOP(self):
        """Turn the rods off (dipole 0) until the next command."""
        self._apply((0.0, 0.0, 0.0))
        self.RodsStopped()
        return CmdResponse.OK

    InvalidDipole = Event(Severity.WARNING_LO, "Invalid dipole request ({}, {}, {}) A m^2; rods off",
                          x=F64, y=F64, z=F64, throttle=5)
    DipoleLimited = Event(Severity.WARNING_LO, "Dipole request ({.4g}, {.4g}, {.4g}) A m^2 beyond the rods' "
                          "limits; limited", x=F64, y=F64, z=F64, throttle=5)
    RodsStopped = Event(Severity.ACTIVITY_HI, "Torque rods stopped")

    #: The dipole the rods give now, A·m² (body frame).
    Dipole = Channel(DipoleMoment)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        if not isinstance(spacecraft, SimulatedSpacecraft):
            raise TypeError(f"{name}: spacecraft must be a SimulatedSpacecraft, got {spacecraft!r}")
        if not spacecraft.has_torque_rods:
            raise ValueError(f"{name}: the spacecraft's actuators are coils; a TorqueRodDriver needs "
                             f"spacecraft.actuators.type: rods")
        self.spacecraft = spacecraft

    def _apply(self, m_B) -> tuple[float, float, float]:
        achieved = self.spacecraft.apply_dipole(m_B)
        self.Dipole.write(DipoleMoment(*achieved))
        return achieved
