"""Simulated reaction-wheel driver: one wheel of the simulated spacecraft, as an F´ component.

One instance per wheel (``reactionWheel0`` … ``reactionWheel<N-1>``), as a flight wheel is one
device on its own bus address with its own faults: a controller that loses one wheel still has
the others, and each wheel's events and channels say which wheel they are about. The controller
(not the driver) distributes a body torque over the wheels' spin axes.

Ports (sync; every ``Result`` port returns ``(value, condition)``):

=====================  ==========================================================================
``torqueSet(torque)``  Drv.WheelTorqueSet: motor torque, N·m along the spin axis (the body feels
                       the opposite); beyond ±max_torque it is clipped (TorqueSaturated, SUCCESS)
``speedSet(speed)``    Drv.WheelSpeedSet: speed set-point relative to the body, rad/s (the wheel
                       electronics' own speed loop, then the same limits)
``enableSet(enable)``  Drv.WheelEnableSet: motor on (TORQUE mode, 0 N·m) or off (DISABLED: coasting)
``wheelStateGet()``    Drv.WheelStateGet: ``Result(WheelState, Success)``
``run(context)``       Svc.Sched: read the wheel, write the channels, report the momentum limit
=====================  ==========================================================================

The wheel starts enabled in TORQUE mode at 0 N·m (the plant's state). A torque or speed command
while DISABLED fails (WheelNotEnabled). A non-finite command fails (InvalidTorque/InvalidSpeed)
and sets the motor torque to 0, the safe state.

Fault injection (simulation only): :meth:`ReactionWheelDriver.set_fault` or ``SIM_SET_FAULT``:
``NOT_READY`` — the wheel does not answer: commands fail (DeviceNotReady, throttled), reads fail,
and the motor is switched off at once (it coasts; once the fault is cleared it needs ENABLE);
``STUCK`` — the wheel keeps the torque or speed it was last given and every command fails
(DeviceNotReady); ``READ_FAIL`` — reads fail (WheelReadFailed, throttled), commands still work;
``READ_NAN`` — reads succeed with NaN values.

An exception raised inside the plant is reported (``report_fault``: the HandlerFault event, the
HandlerFaults channel, the log). In a command it fails the command (DeviceNotReady) and sets the
motor torque to zero, the safe state; in a read it fails the read (WheelReadFailed) and leaves
the motor as it was.
"""

from __future__ import annotations

import math

from fprime_lite import (F64, U8, Channel, CmdResponse, Event, FwEnum, PassiveComponent, Sched, Severity,
                         sync_command, sync_input)

from detumble.components.types import (Result, Success, WheelEnableSet, WheelMode, WheelSpeedSet, WheelState,
                                       WheelStateGet, WheelTorqueSet)
from detumble.components.types import new_result as _new_result  # Result(...) without its Python frame
from detumble.drivers.spacecraft import SimulatedSpacecraft

__all__ = ["ReactionWheelDriver", "SimWheelFault", "wheel_instance_name", "make_reaction_wheel_drivers"]

_NAN = float("nan")


def wheel_instance_name(i: int) -> str:
    """Instance name of the driver of wheel ``i``: ``reactionWheel<i>``."""
    return f"reactionWheel{i}"


class SimWheelFault(FwEnum, namespace="Sim", rep=U8):
    """Injected wheel fault (see the module docstring)."""

    NONE = 0
    NOT_READY = 1
    STUCK = 2
    READ_FAIL = 3
    READ_NAN = 4


# looked up once: reads and torque commands run every control cycle
_NO_FAULT = SimWheelFault.NONE
_SUCCESS = Success.SUCCESS
_DISABLED = WheelMode.DISABLED
_TORQUE = WheelMode.TORQUE
_isfinite = math.isfinite


class ReactionWheelDriver(PassiveComponent):
    """Simulated driver of wheel ``wheel`` of ``spacecraft``.

    Args:
        name: instance name (``reactionWheel0`` …).
        spacecraft: the simulated spacecraft; it must have that wheel.
        wheel: the wheel's index in the scenario's ``spacecraft.reaction_wheels.axes``.
    """

    mode: WheelMode  # what the motor is doing (set in __init__; annotated here for the handlers above it)

    # --- ports ---------------------------------------------------------------------------------

    @sync_input(WheelTorqueSet)
    def torqueSet(self, torque: float) -> Success:
        """Motor torque in N·m along the spin axis; clipped to ±max_torque."""
        if self.fault != _NO_FAULT or self.mode == _DISABLED or type(torque) is not float or not _isfinite(torque):
            checked = self._checked_torque(torque)  # refusals and invalid torques are answered there
            if checked is None:
                return Success.FAILURE
            torque = checked
        # Every control cycle sends one to each wheel: the plant call and mode change written out.
        if abs(torque) > self.max_torque_nm:
            self.TorqueSaturated(torque, self.max_torque_nm)
        else:
            if self.TorqueSaturated.count:  # clear_throttle, where there is something to clear
                self.TorqueSaturated.clear_throttle()
        try:
            self.spacecraft.set_wheel_torque(self.wheel, torque)
        except Exception as exc:  # noqa: BLE001 - a plant fault is a failed command (_plant_call_failed reports it)
            self._plant_call_failed(self.spacecraft.set_wheel_torque, (self.wheel, torque), exc)
            return Success.FAILURE
        self.mode = _TORQUE  # _set_mode(_TORQUE), written out
        self.Mode.write(_TORQUE)
        self.Command.write(torque)
        if self.DeviceNotReady.count:  # clear_throttle, where there is something to clear
            self.DeviceNotReady.clear_throttle()
        return _SUCCESS

    @sync_input(WheelSpeedSet)
    def speedSet(self, speed: float) -> Success:
        """Speed set-point relative to the body, rad/s."""
        return self._command_speed(speed)

    @sync_input(WheelEnableSet)
    def enableSet(self, enable: bool) -> Success:
        """Motor on (TORQUE mode at 0 N·m) or off (coasting)."""
        return self._enable(bool(enable))

    @sync_input(WheelStateGet)
    def wheelStateGet(self) -> Result:
        """The wheel's speed, momentum, applied torque, mode and the reading's time."""
        fault = self.fault
        if fault != _NO_FAULT:
            return self._read_faulty(fault)
        try:  # the healthy wheel: no fault to apply to the reading
            speed, h, u, stamp = self.spacecraft.wheel_sample(self.wheel)
        except Exception as exc:  # noqa: BLE001 - a plant fault is a failed read (_read_raised reports it)
            return self._read_raised(exc)
        if self.WheelReadFailed.count:  # clear_throttle, where there is something to clear
            self.WheelReadFailed.clear_throttle()
        return _new_result(Result, (WheelState(speed, h, u, self.mode, stamp), _SUCCESS))

    @sync_input(Sched)
    def run(self, context: int) -> None:
        """Read the wheel, write the channels, and report a momentum-limited wheel."""
        value, condition = self.wheelStateGet()
        if condition != _SUCCESS:
            return
        self.Speed.write(value.speed)
        self.Momentum.write(value.momentum)
        self.Torque.write(value.torque)
        _, limited = self.spacecraft.wheel_limit_flags(self.wheel)
        if limited:
            self.MomentumSaturated(value.momentum, self.max_momentum_nms)
        else:
            if self.MomentumSaturated.count:  # clear_throttle, where there is something to clear
                self.MomentumSaturated.clear_throttle()

    # --- commands ------------------------------------------------------------------------------

    @sync_command()
    def SET_TORQUE(self, torque: F64):
        """Command the motor torque, N·m (clipped to ±max_torque)."""
        if not math.isfinite(torque):
            self.torqueSet(torque)
            return CmdResponse.VALIDATION_ERROR
        return CmdResponse.OK if self.torqueSet(torque) == Success.SUCCESS else CmdResponse.EXECUTION_ERROR

    @sync_command()
    def SET_SPEED(self, speed: F64):
        """Command the wheel speed relative to the body, rad/s."""
        if not math.isfinite(speed):
            self._command_speed(speed)
            return CmdResponse.VALIDATION_ERROR
        return CmdResponse.OK if self._command_speed(speed) == Success.SUCCESS else CmdResponse.EXECUTION_ERROR

    @sync_command()
    def ENABLE(self):
        """Switch the motor on (TORQUE mode, 0 N·m)."""
        return CmdResponse.OK if self._enable(True) == Success.SUCCESS else CmdResponse.EXECUTION_ERROR

    @sync_command()
    def DISABLE(self):
        """Switch the motor off: the wheel coasts (friction still acts)."""
        return CmdResponse.OK if self._enable(False) == Success.SUCCESS else CmdResponse.EXECUTION_ERROR

    @sync_command()
    def SIM_SET_FAULT(self, fault: SimWheelFault):
        """SIMULATION ONLY: inject a wheel fault (NONE clears it)."""
        self.set_fault(fault)

    # --- events and channels -------------------------------------------------------------------

    TorqueSaturated = Event(Severity.WARNING_LO, "Torque {.6g} N m beyond the limit {.6g} N m; clipped",
                            commanded=F64, limit=F64, throttle=5)
    MomentumSaturated = Event(Severity.WARNING_HI, "Momentum {.6g} N m s at the limit {.6g} N m s; torque cut",
                              momentum=F64, limit=F64, throttle=5)
    DeviceNotReady = Event(Severity.WARNING_LO, "Wheel not ready", throttle=5)
    WheelNotEnabled = Event(Severity.WARNING_LO, "Wheel disabled; command refused (send ENABLE first)", throttle=5)
    InvalidTorque = Event(Severity.WARNING_LO, "Invalid torque {.6g}; motor torque set to 0", torque=F64,
                          throttle=5)
    InvalidSpeed = Event(Severity.WARNING_LO, "Invalid speed {.6g}; motor torque set to 0", speed=F64, throttle=5)
    WheelReadFailed = Event(Severity.WARNING_LO, "Wheel read failed", throttle=5)
    WheelEnabled = Event(Severity.ACTIVITY_HI, "Wheel enabled")
    WheelDisabled = Event(Severity.ACTIVITY_HI, "Wheel disabled")
    SimFaultSet = Event(Severity.ACTIVITY_HI, "SIM: wheel fault set to {}", fault=SimWheelFault)

    #: DISABLED / TORQUE / SPEED.
    Mode = Channel(WheelMode, update="on change")
    #: Wheel speed relative to the body, rad/s.
    Speed = Channel(F64)
    #: Absolute axial momentum, N·m·s.
    Momentum = Channel(F64)
    #: Motor torque applied (after the limits), N·m.
    Torque = Channel(F64)
    #: Last torque (N·m) or speed (rad/s) command accepted.
    Command = Channel(F64, update="on change")

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, wheel: int, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        if not isinstance(spacecraft, SimulatedSpacecraft):
            raise TypeError(f"{name}: spacecraft must be a SimulatedSpacecraft, got {spacecraft!r}")
        n = spacecraft.wheel_count
        if isinstance(wheel, bool) or not isinstance(wheel, int) or not 0 <= wheel < n:
            has = f"wheels 0..{n - 1}" if n else "no reaction wheels (scenario spacecraft.reaction_wheels)"
            raise ValueError(f"{name}: spacecraft has no wheel {wheel!r}; it has {has}")
        self.spacecraft = spacecraft
        self.wheel = wheel
        self.max_torque_nm, self.max_momentum_nms = spacecraft.wheel_limits(wheel)
        self.fault = SimWheelFault.NONE
        self.mode = WheelMode.TORQUE

    # --- fault injection -----------------------------------------------------------------------

    def set_fault(self, fault: SimWheelFault) -> None:
        """Inject ``fault``; NOT_READY switches the motor off at once."""
        self.fault = SimWheelFault(fault)
        if self.fault == SimWheelFault.NOT_READY:  # the wheel lost power: it needs ENABLE again
            self._plant_call(self.spacecraft.set_wheel_enabled, self.wheel, False)
            self._set_mode(WheelMode.DISABLED)
        self.SimFaultSet(self.fault)

    # --- behaviour -----------------------------------------------------------------------------

    def _refused(self) -> bool:
        """True (and the event logged) when a command cannot reach the wheel."""
        if self.fault == _NO_FAULT:
            if self.mode == _DISABLED:
                self.WheelNotEnabled()
                return True
            return False
        if self.fault in (SimWheelFault.NOT_READY, SimWheelFault.STUCK):
            self.DeviceNotReady()
            return True
        if self.mode == WheelMode.DISABLED:
            self.WheelNotEnabled()
            return True
        return False

    def _checked_torque(self, torque) -> float | None:
        """``torque`` as a float when the wheel takes commands and it is a finite number; else None, the
        refusal or InvalidTorque logged (an invalid one also sets the motor torque to zero)."""
        if self._refused():
            return None
        if type(torque) is not float and (isinstance(torque, bool) or not isinstance(torque, (int, float))):
            self.InvalidTorque(_as_f64(torque))
            self._plant_call(self.spacecraft.set_wheel_torque, self.wheel, 0.0)
            return None
        torque = float(torque)
        if not math.isfinite(torque):
            self.InvalidTorque(torque)
            self._plant_call(self.spacecraft.set_wheel_torque, self.wheel, 0.0)
            return None
        return torque

    def _command_speed(self, speed) -> Success:
        if self._refused():
            return Success.FAILURE
        if isinstance(speed, bool) or not isinstance(speed, (int, float)) or not math.isfinite(speed):
            self.InvalidSpeed(_as_f64(speed))
            self._plant_call(self.spacecraft.set_wheel_torque, self.wheel, 0.0)
            self._set_mode(WheelMode.TORQUE)
            return Success.FAILURE
        if not self._plant_call(self.spacecraft.set_wheel_speed, self.wheel, float(speed)):
            return Success.FAILURE
        self._set_mode(WheelMode.SPEED)
        self.Command.write(float(speed))
        if self.DeviceNotReady.count:  # clear_throttle, where there is something to clear
            self.DeviceNotReady.clear_throttle()
        return Success.SUCCESS

    def _enable(self, enable: bool) -> Success:
        if self.fault in (SimWheelFault.NOT_READY, SimWheelFault.STUCK):
            self.DeviceNotReady()
            return Success.FAILURE
        if not self._plant_call(self.spacecraft.set_wheel_enabled, self.wheel, enable):
            return Success.FAILURE
        if enable:
            self._plant_call(self.spacecraft.set_wheel_torque, self.wheel, 0.0)
            if self.mode == WheelMode.DISABLED:
                self.WheelEnabled()
            self._set_mode(WheelMode.TORQUE)
        else:
            if self.mode != WheelMode.DISABLED:
                self.WheelDisabled()
            self._set_mode(WheelMode.DISABLED)
        return Success.SUCCESS

    def _set_mode(self, mode: WheelMode) -> None:
        self.mode = mode
        self.Mode.write(mode)

    def _read_faulty(self, fault: SimWheelFault) -> Result:
        """A read under an injected fault (``wheelStateGet`` reads a healthy wheel itself)."""
        if fault in (SimWheelFault.READ_FAIL, SimWheelFault.NOT_READY):
            self.WheelReadFailed()
            return Result(WheelState(_NAN, _NAN, _NAN, self.mode, self.spacecraft.now()), Success.FAILURE)
        try:
            speed, h, u, stamp = self.spacecraft.wheel_sample(self.wheel)
        except Exception as exc:  # noqa: BLE001 - a plant fault is a failed read (_read_raised reports it)
            return self._read_raised(exc)
        if fault == SimWheelFault.READ_NAN:
            speed = h = u = _NAN
        if self.WheelReadFailed.count:  # clear_throttle, where there is something to clear
            self.WheelReadFailed.clear_throttle()
        return Result(WheelState(speed, h, u, self.mode, stamp), Success.SUCCESS)

    def _read_raised(self, exc: Exception) -> Result:
        """The failed read after the plant raised ``exc``: reported, WheelReadFailed, FAILURE. The
        motor keeps its command (a read commands nothing; the reader decides what to do)."""
        self.report_fault(f"wheel {self.wheel} read", exc)
        self.WheelReadFailed()
        return Result(WheelState(_NAN, _NAN, _NAN, self.mode, self.spacecraft.now()), Success.FAILURE)

    def _plant_call(self, fn, *args) -> bool:
        try:
            fn(*args)
        except Exception as exc:  # noqa: BLE001 - a plant fault is a failed command (_plant_call_failed reports it)
            self._plant_call_failed(fn, args, exc)
            return False
        return True

    def _plant_call_failed(self, fn, args: tuple, exc: Exception) -> None:
        """A plant call ``fn(*args)`` raised ``exc``: reported, DeviceNotReady, and the motor torque
        set to zero (the safe state) unless that is the call that failed."""
        self.report_fault(f"wheel {self.wheel} {getattr(fn, '__name__', 'command')}", exc)
        self.DeviceNotReady()
        if not (fn == self.spacecraft.set_wheel_torque and args[1:] == (0.0,)):
            self._make_safe()

    def _make_safe(self) -> None:
        """Motor torque to zero after a failed command (the mode follows unless the motor is off)."""
        try:
            self.spacecraft.set_wheel_torque(self.wheel, 0.0)
        except Exception as exc:  # noqa: BLE001 - reported, never raised to the caller
            self.report_fault(f"wheel {self.wheel} safing", exc)
            return
        if self.mode != _DISABLED:
            self._set_mode(_TORQUE)


def _as_f64(value) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        return _NAN


def make_reaction_wheel_drivers(spacecraft: SimulatedSpacecraft, base_ids: dict[int, int] | None = None
                                ) -> dict[str, ReactionWheelDriver]:
    """One driver per wheel of ``spacecraft``, by instance name (``reactionWheel0`` …)."""
    base_ids = base_ids or {}
    return {wheel_instance_name(i): ReactionWheelDriver(wheel_instance_name(i), spacecraft, i,
                                                        base_id=base_ids.get(i, 0))
            for i in range(spacecraft.wheel_count)}
