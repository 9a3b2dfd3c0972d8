"""Simulated star tracker: the attitude ``q_BN`` of the simulated spacecraft, as an F´ component.

Backed by :mod:`detumble.sim.star_tracker` (noise 1σ across and about the boresight, update
rate, dropouts, a rate limit above which no solution is found, an ``ideal`` option).

Ports (sync):

======================  =========================================================================
``attitudeGet()``       Drv.AttitudeGet: ``Result(AttitudeQuaternion, Success)``; ``q_BN`` scalar
                        first, ``timestamp`` = when the image was taken. No valid solution (a
                        dropout, or the body turning faster than ``max_rate_deg_s``): FAILURE, the
                        value carries the last valid attitude with ``valid`` false (NoSolution)
``run(context)``        Svc.Sched: read and write the ``Attitude`` channel
======================  =========================================================================

Fault injection (simulation only): :meth:`StarTracker.set_fault` or ``SIM_SET_FAULT``:
``FAIL`` — reads fail (AttitudeReadFailed, throttled); ``NAN`` — reads *succeed* with NaN
components (a corrupted solution the consumer must catch); ``FROZEN`` — the tracker keeps
returning the solution it had when the fault was set, with its old time stamp, as valid (a hung
tracker: only the time stamp tells). An exception raised inside the plant is a failed read too,
reported (``report_fault``: the HandlerFault event, the HandlerFaults channel, the log).
"""

from __future__ import annotations

from fprime_lite import (F64, U32, U8, Channel, CmdResponse, Event, FwEnum, PassiveComponent, Sched, Severity,
                         sync_command, sync_input)

from detumble.components.types import AttitudeGet, AttitudeQuaternion, Result, Success
from detumble.components.types import new_result as _new_result  # Result(...) without its Python frame
from detumble.drivers.spacecraft import SimulatedSpacecraft

__all__ = ["StarTracker", "SimStarTrackerFault"]

_NAN = float("nan")


class SimStarTrackerFault(FwEnum, namespace="Sim", rep=U8):
    """Injected star-tracker fault (see the module docstring)."""

    NONE = 0
    FAIL = 1
    NAN = 2
    FROZEN = 3


# looked up once: an enum class attribute costs a metaclass lookup, and every control cycle reads
_FAIL, _NAN_FAULT, _FROZEN = SimStarTrackerFault.FAIL, SimStarTrackerFault.NAN, SimStarTrackerFault.FROZEN
_SUCCESS, _FAILURE = Success.SUCCESS, Success.FAILURE


class StarTracker(PassiveComponent):
    """Simulated star tracker on ``spacecraft`` (its scenario must have ``sensors.star_tracker``)."""

    @sync_input(AttitudeGet)
    def attitudeGet(self) -> Result:
        """The latest attitude solution (see the module docstring)."""
        fault = self.fault
        if fault == _FAIL:
            self.AttitudeReadFailed()
            return Result(None, _FAILURE)
        if fault == _FROZEN and self._frozen is not None:
            return Result(self._frozen, _SUCCESS)
        try:
            q, valid, stamp = self.spacecraft.star_tracker_sample()
        except Exception as exc:  # noqa: BLE001 - a plant fault is a failed read, never an exception
            self.report_fault("attitude read", exc)
            self.AttitudeReadFailed()
            return Result(None, _FAILURE)
        if self.AttitudeReadFailed.count:  # clear_throttle, where there is something to clear
            self.AttitudeReadFailed.clear_throttle()
        if fault == _NAN_FAULT:
            return Result(AttitudeQuaternion(_NAN, _NAN, _NAN, _NAN, True, stamp), _SUCCESS)
        value = AttitudeQuaternion(q[0], q[1], q[2], q[3], valid, stamp)
        if not valid:
            no_solution = self.NoSolution
            if no_solution.count < _NO_SOLUTION_THROTTLE:  # throttled, the call would do nothing
                no_solution()
            return Result(value, _FAILURE)
        if self.NoSolution.count:  # clear_throttle, where there is something to clear
            self.NoSolution.clear_throttle()
        self._solutions += 1
        return _new_result(Result, (value, _SUCCESS))

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """Read the tracker and write the Attitude channel (also when the solution is invalid)."""
        value, condition = self.attitudeGet()
        if value is not None:
            self.Attitude.write(value)
        self.Solutions.write(self._solutions)

    @sync_command()
    def GET_ATTITUDE(self):
        """Read the tracker and log AttitudeData (EXECUTION_ERROR without a valid solution)."""
        value, condition = self.attitudeGet()
        if condition != Success.SUCCESS:
            return CmdResponse.EXECUTION_ERROR
        self.AttitudeData(value.q0, value.q1, value.q2, value.q3)
        return CmdResponse.OK

    @sync_command()
    def SIM_SET_FAULT(self, fault: SimStarTrackerFault):
        """SIMULATION ONLY: inject a star-tracker fault (NONE clears it)."""
        self.set_fault(fault)

    AttitudeData = Event(Severity.ACTIVITY_LO, "Attitude q_BN: {.9f}, {.9f}, {.9f}, {.9f}",
                         q0=F64, q1=F64, q2=F64, q3=F64)
    AttitudeReadFailed = Event(Severity.WARNING_LO, "Star tracker read failed", throttle=5)
    NoSolution = Event(Severity.WARNING_LO, "Star tracker has no attitude solution", throttle=5)
    SimFaultSet = Event(Severity.ACTIVITY_HI, "SIM: star tracker fault set to {}", fault=SimStarTrackerFault)

    #: The latest solution (q_BN scalar first, valid flag, image time).
    Attitude = Channel(AttitudeQuaternion)
    #: Valid solutions handed out since start.
    Solutions = Channel(U32, update="on change")

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        if not isinstance(spacecraft, SimulatedSpacecraft):
            raise TypeError(f"{name}: spacecraft must be a SimulatedSpacecraft, got {spacecraft!r}")
        if not spacecraft.has_star_tracker:
            raise ValueError(f"{name}: the spacecraft's scenario has no star tracker; add sensors.star_tracker "
                             f"(e.g. --set sensors.star_tracker.ideal=true)")
        self.spacecraft = spacecraft
        self.fault = SimStarTrackerFault.NONE
        self._frozen: AttitudeQuaternion | None = None
        self._solutions = 0

    def set_fault(self, fault: SimStarTrackerFault) -> None:
        """Inject ``fault``; FROZEN keeps the solution held now."""
        self.fault = SimStarTrackerFault(fault)
        self._frozen = None
        if self.fault == SimStarTrackerFault.FROZEN:
            q, valid, stamp = self.spacecraft.star_tracker_sample()
            self._frozen = AttitudeQuaternion(*q, True, stamp)
        self.SimFaultSet(self.fault)


#: NoSolution's throttle: while the tracker finds no solution (up to 20 reads a second in adcs_ref), a
#: read past the throttle skips the event's call, which would return at its throttle test
_NO_SOLUTION_THROTTLE: int = StarTracker.NoSolution.throttle  # type: ignore[assignment]
