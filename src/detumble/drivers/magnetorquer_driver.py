"""Simulated magnetorquer driver: one DRV2605-driven face coil of the simulated spacecraft.

The flight ``Drv.Drv2605Manager`` ports and commands on top of the plant's coil model
(:mod:`detumble.sim.coils`). The reference deployment makes five instances, one per face that
carries a coil (there is no Z+ coil):

=========================  =====  =========================================
instance                   face   dipole for a positive level
=========================  =====  =========================================
``drv2605Face0Manager``    X+ 0   +X
``drv2605Face1Manager``    X− 1   −X (mirrored mounting: the coil's normal)
``drv2605Face2Manager``    Y+ 2   +Y
``drv2605Face3Manager``    Y− 3   −Y
``drv2605Face5Manager``    Z− 5   −Z
=========================  =====  =========================================

The driver only forwards the signed drive level −127…127; the plant turns it into coil voltage
``level/127 · V``, current ``V/R`` (optionally lagged by L/R) and dipole ``N·I·A`` along the
face's outward normal — so the mirroring of the minus faces is the plant's, not the driver's. The
new level acts on the dynamics from the present simulated time on.

Face power: the coil driver sits on the face board behind the face's load switch
(``face<N>LoadSwitch``). The switch tells the driver through ``loadSwitchStateChanged``: OFF
de-initialises the device (and the opened switch has already de-energised the coil); ON starts a
1 s settling time, after which the next ``start``/``stop`` initialises the device
(DeviceInitialized, flight id 8). While unpowered or settling, ``start``/``stop`` return FAILURE
and log the throttled DeviceNotReady (the flight code fails silently there; the simulation says
why, so an operator sees a coil that cannot act). At construction the driver takes the switch's
present state as settled (the spacecraft was already flying).

Fault injection (simulation only): :meth:`MagnetorquerDriver.set_fault` or ``SIM_SET_FAULT``:
``NOT_READY`` — the device does not answer: ``start``/``stop`` return FAILURE with the throttled
``DeviceNotReady`` event and the coil is switched off (the safe state); ``STUCK`` — the coil keeps
whatever level it had and ``start``/``stop`` return FAILURE (``DeviceNotReady``), the nasty case;
``STOP_FAILS`` — starts work, but a stop leaves the coil at its level and returns FAILURE
(``DeviceNotReady``); ``LATCHED`` — the device acknowledges every write but its output stays at the
level it had: the driver reads the coil level back after each write, so it answers FAILURE with the
WARNING_HI ``DriveReadbackMismatch`` event instead of a false SUCCESS.

The manager (:class:`~detumble.components.detumble_manager.DetumbleManager`) isolates a coil whose
stop answers FAILURE, so each of these faults is caught at the end of the torque period it occurs in.
"""

from __future__ import annotations

import logging

from fprime_lite import (I8, I32, Channel, CmdResponse, Event, FwEnum, PassiveComponent, Severity,
                         sync_command, sync_input)
from fprime_lite.model.fw_types import On
from fprime_lite.model.types import U8

from detumble.control.coil_layout import COIL_FACES, Face
from detumble.sim.coils import FACE_NAMES, MAX_LEVEL, CoilSet
from detumble.components.types import StartMagnetorquer, StopMagnetorquer, Success
from detumble.drivers.ports import LoadSwitchStateChanged
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

#: Time after a face's switch closes before its DRV2605 can be initialised (flight: 1 s).
LOAD_SWITCH_SETTLE_US = 1_000_000

__all__ = ["MagnetorquerDriver", "SimDriverFault", "DRIVER_FACES", "driver_instance_name",
           "make_magnetorquer_drivers"]

log = logging.getLogger("detumble.drivers")

#: Faces with a coil in the reference 1U (X+ 0, X− 1, Y+ 2, Y− 3, Z− 5), as plain ints.
DRIVER_FACES = tuple(int(face) for face in COIL_FACES)


def driver_instance_name(face: int) -> str:
    """The reference deployment's instance name of the driver on ``face``: ``drv2605Face<N>Manager``."""
    return f"drv2605Face{face}Manager"


class SimDriverFault(FwEnum, namespace="Sim", rep=U8):
    """Injected driver fault (see the module docstring)."""

    NONE = 0
    NOT_READY = 1
    STUCK = 2
    STOP_FAILS = 3
    LATCHED = 4


_FAULT_NONE = SimDriverFault.NONE  # read once: an enum class attribute costs a metaclass lookup
_SUCCESS = Success.SUCCESS

class MagnetorquerDriver(PassiveComponent):
    """Simulated DRV2605 manager for the coil on ``face`` of ``spacecraft``.

    Args:
        name: instance name (``drv2605Face0Manager`` … ``drv2605Face5Manager``).
        spacecraft: the simulated spacecraft.
        face: 0 (X+), 1 (X−), 2 (Y+), 3 (Y−) or 5 (Z−); the spacecraft must have a coil there.
    """

    # --- ports ---------------------------------------------------------------------------------

    @sync_input(StartMagnetorquer)
    def start(self, val: int) -> Success:
        """Drive the coil at level ``val`` (−127…127, sign = current direction). Out-of-range or
        non-integer levels are refused (FAILURE, InvalidDriveLevel) and switch the coil off.

        The one definition of a drive at a valid level (``STOP``, ``stop`` and the ``START`` command
        come here too): initialise the device when its face is powered and settled, refuse under an
        injected fault, set the coil, read the level back, and let DeviceNotReady and
        DriveReadbackMismatch be reported again after a good drive."""
        if type(val) is not int or not -MAX_LEVEL <= val <= MAX_LEVEL:  # _valid_level(val), its fast case
            return self._start(val)
        # The manager re-commands the same level every tick. A healthy, initialised device whose coil
        # already carries it and whose on-change DriveLevel last sent it: the drive below would only
        # clear the throttles, so it clears them here (stop is start(0)). Kept written out (issue 26):
        # 0.72-2.5 µs less a re-command than the drive, 3.2 re-commands a proves_ref tick (≈ 32 µs of
        # CPU): 7-25 % of the tick; `python benchmarks/bench_inlined.py magnetorquer_recommand`
        # (3 sittings on the shared 2-core machine, 2026-12-03, each the best of 40).
        fault = self.fault
        if (fault is _FAULT_NONE and self._initialized and val == self._coil.level
                and val == self.DriveLevel.last):
            if self.DeviceNotReady.count:
                self.DeviceNotReady.clear_throttle()
            if self.DriveReadbackMismatch.count:
                self.DriveReadbackMismatch.clear_throttle()
            return _SUCCESS
        if not self._initialized and not self._powered():
            self.DeviceNotReady()
            return Success.FAILURE
        if fault is not _FAULT_NONE:
            if fault in (SimDriverFault.NOT_READY, SimDriverFault.STUCK) or (
                    fault == SimDriverFault.STOP_FAILS and val == 0):
                self.DeviceNotReady()
                if fault == SimDriverFault.NOT_READY:
                    self._set_coil(0)
                return Success.FAILURE
        if (fault is _FAULT_NONE or fault != SimDriverFault.LATCHED) and not self._set_coil(val):
            self.DeviceNotReady()
            return Success.FAILURE
        actual = self._coil.level  # read back what the coil carries now
        if actual != val:
            self.DriveReadbackMismatch(int(actual), int(val))
            return Success.FAILURE
        # a successful drive lets DeviceNotReady and DriveReadbackMismatch be reported again
        if self.DeviceNotReady.count:  # clear_throttle, where there is something to clear
            self.DeviceNotReady.clear_throttle()
        if self.DriveReadbackMismatch.count:
            self.DriveReadbackMismatch.clear_throttle()
        return _SUCCESS

    @sync_input(StopMagnetorquer)
    def stop(self) -> Success:
        """Switch the coil off: level 0, as ``start(0)`` (its short cut included: idle coils are stopped too)."""
        return self.start(0)

    @sync_input(LoadSwitchStateChanged)
    def loadSwitchStateChanged(self, state: On) -> Success:
        """The face's power changed: OFF de-initialises the device, ON starts the settling time."""
        self._switch_on = state == On.ON
        if not self._switch_on:
            self._initialized = False
        else:
            self._ready_at_us = self.spacecraft.clock.current_us + LOAD_SWITCH_SETTLE_US
        return Success.SUCCESS

    # --- commands ------------------------------------------------------------------------------

    @sync_command()
    def START(self, val: I8):
        """Drive the coil at ``val`` (−127…127)."""
        if not _valid_level(val):
            self._start(val)
            return CmdResponse.VALIDATION_ERROR
        return CmdResponse.OK if self._start(val) == Success.SUCCESS else CmdResponse.EXECUTION_ERROR

    @sync_command()
    def STOP(self):
        """Switch the coil off."""
        return CmdResponse.OK if self.start(0) == Success.SUCCESS else CmdResponse.EXECUTION_ERROR

    @sync_command()
    def SIM_SET_FAULT(self, fault: SimDriverFault):
        """SIMULATION ONLY: inject a driver fault (NONE clears it)."""
        self.set_fault(fault)

    # --- events and channels -------------------------------------------------------------------

    DeviceNotReady = Event(Severity.WARNING_LO, "Device not ready", throttle=5)
    DeviceInitialized = Event(Severity.ACTIVITY_LO, "DRV2605 device initialized.", id=8)
    InvalidDriveLevel = Event(Severity.WARNING_LO, "Invalid drive level {d}; levels are -127..127", val=I32,
                              throttle=5, id=0x80)
    SimFaultSet = Event(Severity.ACTIVITY_HI, "SIM: driver fault set to {}", fault=SimDriverFault)
    #: Declared last so the ids above stay. The coil read back another level than the one written.
    DriveReadbackMismatch = Event(Severity.WARNING_HI, "Coil drive read back {} after writing {}",
                                  actual=I32, commanded=I32, throttle=5)

    #: The level the coil is driven at now (−127…127; 0 = off).
    DriveLevel = Channel(I8, update="on change")

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, face: int, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        if face not in spacecraft.coil_faces:
            raise ValueError(f"{name}: spacecraft has no coil on face {face!r}; its coil faces are "
                             f"{list(spacecraft.coil_faces) or 'none (ideal torque rods)'}")
        self.spacecraft = spacecraft
        self.face = face
        self.face_name = FACE_NAMES[Face(face)]
        self.fault = SimDriverFault.NONE
        actuators = spacecraft.plant.actuators
        assert isinstance(actuators, CoilSet)  # the spacecraft has a coil on this face
        self._coil = actuators.coils[face]  # read-only: the level the coil carries
        self._switch_on = spacecraft.face_powered(face)
        self._initialized = self._switch_on
        self._ready_at_us = spacecraft.clock.current_us

    # --- fault injection -----------------------------------------------------------------------

    def set_fault(self, fault: SimDriverFault) -> None:
        """Inject ``fault``; NOT_READY switches the coil off at once, STUCK freezes its level."""
        self.fault = SimDriverFault(fault)
        if self.fault == SimDriverFault.NOT_READY:
            self._set_coil(0)
        self.SimFaultSet(self.fault)

    @property
    def level(self) -> int:
        """The level the plant's coil is driven at now."""
        return self.spacecraft.coil_level(self.face)

    # --- behaviour -----------------------------------------------------------------------------

    def _start(self, val) -> Success:
        if not _valid_level(val):
            self.InvalidDriveLevel(_as_i32(val))
            if self.fault in (SimDriverFault.NONE, SimDriverFault.NOT_READY):
                self._set_coil(0)  # a faulty output stays where it is
            return Success.FAILURE
        return self.start(int(val))  # an int subclass (not bool) as the plain int it stands for

    def _powered(self) -> bool:
        """Initialise the device when its face is powered and settled (the flight initializeDevice)."""
        if self._initialized:
            return True
        if not self._switch_on or self.spacecraft.clock.current_us < self._ready_at_us \
                or not self.spacecraft.face_powered(self.face):
            return False
        self._initialized = True
        self.DeviceInitialized()
        return True

    def _set_coil(self, level: int) -> bool:
        level = int(level)
        try:
            self.spacecraft.set_coil_level(self.face, level)
        except Exception as exc:  # noqa: BLE001 - a plant fault is a failed drive, never an exception
            self.report_fault(f"coil {self.face_name} drive", exc)
            if level:  # the level the coil carries is not known: switch it off (a failure is reported too)
                self._set_coil(0)
            return False
        self.DriveLevel.write(level)
        return True


def _valid_level(val) -> bool:
    return isinstance(val, int) and not isinstance(val, bool) and -MAX_LEVEL <= val <= MAX_LEVEL


def _as_i32(val) -> int:
    if isinstance(val, int) and not isinstance(val, bool) and -2**31 <= val < 2**31:
        return int(val)
    return -2**31  # not an integer, or beyond I32: reported as I32 min


def make_magnetorquer_drivers(spacecraft: SimulatedSpacecraft, base_ids: dict[int, int] | None = None
                              ) -> dict[str, MagnetorquerDriver]:
    """The reference deployment's five drivers, by instance name (``drv2605Face0Manager`` …).

    ``base_ids`` maps face -> base id (default: 0 for all; give distinct ids in a real topology).
    """
    base_ids = base_ids or {}
    return {driver_instance_name(face): MagnetorquerDriver(driver_instance_name(face), spacecraft, face,
                                                           base_id=base_ids.get(face, 0))
            for face in DRIVER_FACES}
