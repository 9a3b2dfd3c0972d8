"""DetumbleManager: the PROVES detumble controller as a passive fprime_lite component.

Behaviour, requirements and deviations: ``docs/components/detumble_manager.md``.
The control laws live in framework-free helpers (:mod:`detumble.control.bdot`,
:mod:`detumble.control.strategy_selector`, :mod:`detumble.control.magnetorquer`); this module adapts them to ports,
parameters, events and telemetry.

Units: angular rate in deg/s (requested from the provider as ``AngularUnit.DEG_PER_SEC``), magnetic
field in gauss (body frame), dipole moment in A·m² (body frame), durations as
``Fw.TimeIntervalValue``, coil drive levels −127…127. The reference deployment runs ``run`` at 50 Hz.

One state's actions run per ``run`` call; a transition takes effect on the next call::

    COOLDOWN ──(≥ COOLDOWN_DURATION)──▶ SENSING_ANGULAR_VELOCITY
    SENSING_ANGULAR_VELOCITY ──BDOT──▶ SENSING_MAGNETIC_FIELD ──(5 samples)──▶ ACTUATING_BDOT
    SENSING_ANGULAR_VELOCITY ──HYSTERESIS──▶ ACTUATING_HYSTERESIS ──▶ COOLDOWN
    ACTUATING_BDOT ──(≥ TORQUE_DURATION, or sampling-period failure)──▶ COOLDOWN
    any state ──(mode DISABLED)──▶ COOLDOWN, coils stopped once, timers and window cleared

Actuator health (an addition to the PROVES design): a coil that was switched on and whose stop
answers FAILURE may still be on; it is reported (CoilStopFailed, WARNING_HI) and isolated — no start
or stop reaches it — until the ground sends ENABLE_COIL. Every torque period ends with a stop, so this
takes at most one period.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from fprime_lite import (F64, U32, Channel, CmdResponse, Event, OutputPort, Param, PassiveComponent,
                         Sched, Severity, sync_command, sync_input)
from fprime_lite.model.params import ParamEcho
from fprime_lite.model.time import Time
from fprime_lite.model.types import U8

from detumble.components import types as T
from detumble.control.bdot import BDot
from detumble.control.coil_layout import COIL_FACES
from detumble.control.coil_layout import FLIGHT_XY_COIL as _XY
from detumble.control.coil_layout import FLIGHT_Z_COIL as _Z
from detumble.control.magnetorquer import CoilShape as CoilOutline
from detumble.control.magnetorquer import DirectionSign, Magnetorquer
from detumble.control.strategy_selector import Strategy, StrategySelector
from detumble.components.types import (AngularUnit, AngularVelocityMagnitudeGet, CoilShape, DetumbleMode, DetumbleState,
                    DipoleMomentGet, GetSystemMode, HysteresisAxis, MagneticFieldGet, MagnetorquerFace,
                    SamplingPeriodGet,
                    SetDetumbleMode, StartMagnetorquer, StopMagnetorquer, Success, SystemMode,
                    SystemModeChanged, TimeIntervalValue)

__all__ = ["DetumbleManager"]

_FULL_SCALE = 127

#: Hysteresis drive levels (X+, X−, Y+, Y−, Z−) per axis.
_HYSTERESIS_LEVELS = {
    HysteresisAxis.X_AXIS: (_FULL_SCALE, -_FULL_SCALE, 0, 0, 0),
    HysteresisAxis.Y_AXIS: (0, 0, _FULL_SCALE, -_FULL_SCALE, 0),
    HysteresisAxis.Z_AXIS: (0, 0, 0, 0, -_FULL_SCALE),
}


@dataclass(frozen=True)
class _CoilParams:
    """Which parameters configure one coil, and its ports and turns channel."""

    name: str
    turns: str
    voltage: str
    resistance: str
    shape: str
    width: str | None
    length: str | None
    diameter: str | None
    sign: DirectionSign
    turns_channel: str
    start_port: str
    stop_port: str

    @property
    def params(self) -> tuple[str, ...]:
        return tuple(p for p in (self.turns, self.voltage, self.resistance, self.shape, self.width,
                                 self.length, self.diameter) if p is not None)


def _rect(name: str, prefix: str, axis: str, sign: DirectionSign, port: str) -> _CoilParams:
    camel = "".join(p.capitalize() for p in prefix.split("_"))
    return _CoilParams(name, f"{axis}_TURNS", f"{prefix}_VOLTAGE", f"{prefix}_RESISTANCE",
                       f"{prefix}_SHAPE", f"{prefix}_WIDTH", f"{prefix}_LENGTH", None, sign,
                       f"{camel}TurnsParam", f"{port}Start", f"{port}Stop")


#: The five coils in drive order (X+, X−, Y+, Y−, Z−). There is no Z+ coil.
_COILS = (
    _rect("x_plus", "X_PLUS", "X", DirectionSign.POSITIVE, "xPlus"),
    _rect("x_minus", "X_MINUS", "X", DirectionSign.NEGATIVE, "xMinus"),
    _rect("y_plus", "Y_PLUS", "Y", DirectionSign.POSITIVE, "yPlus"),
    _rect("y_minus", "Y_MINUS", "Y", DirectionSign.NEGATIVE, "yMinus"),
    _CoilParams("z_minus", "Z_TURNS", "Z_MINUS_VOLTAGE", "Z_MINUS_RESISTANCE", "Z_MINUS_SHAPE",
                None, None, "Z_MINUS_DIAMETER", DirectionSign.NEGATIVE, "ZMinusTurnsParam",
                "zMinusStart", "zMinusStop"),
)


#: The face of each coil of _COILS, and back.
_COIL_FACES = tuple(MagnetorquerFace(int(face)) for face in COIL_FACES)
_FACE_INDEX = {face: index for index, face in enumerate(_COIL_FACES)}


def _duration(min_us: int, max_us: int):
    """A parameter check: a ``TimeIntervalValue`` between ``min_us`` and ``max_us`` µs inclusive."""
    def check(value: TimeIntervalValue) -> str | None:
        if not min_us <= value.total_us <= max_us:
            return f"{value.total_us} us is outside [{min_us}, {max_us}] us"
        return None
    return check


#: The selector's strategy as the ground-visible enum (a dict lookup: enum calls cost ~0.7 µs a tick).
_DETUMBLE_STRATEGY = {Strategy(v.value): v for v in T.DetumbleStrategy}


# The modes and states the 50 Hz run compares against, read once: an enum class attribute costs a
# metaclass lookup (~0.1-0.5 µs), and run makes up to five of them a tick.
_DISABLED = DetumbleMode.DISABLED
_COOLDOWN = DetumbleState.COOLDOWN
_SENSING_ANGULAR_VELOCITY = DetumbleState.SENSING_ANGULAR_VELOCITY
_SENSING_MAGNETIC_FIELD = DetumbleState.SENSING_MAGNETIC_FIELD
_ACTUATING_BDOT = DetumbleState.ACTUATING_BDOT
_ACTUATING_HYSTERESIS = DetumbleState.ACTUATING_HYSTERESIS
_SUCCESS = Success.SUCCESS
_FAILURE = Success.FAILURE


def _finite(*values: float) -> bool:
    try:
        for v in values:  # all(...) without its generator: a check on every sensing tick
            if not math.isfinite(v):
                return False
        return True
    except TypeError:
        return False


class DetumbleManager(PassiveComponent):
    """Chooses and runs a detumble strategy (B-dot or hysteresis) and drives five magnetorquers.

    Start-up: the deployment calls ``load_parameters()``; :meth:`parameters_loaded` then calls
    :meth:`configure`, which caches the coil settings and publishes every parameter channel.
    The component starts in mode DISABLED, state COOLDOWN.
    """

    # --- command (declared first: opcode 0, as in the FPP) -------------------------------------

    @sync_command()
    def SET_MODE(self, mode: DetumbleMode):
        """Set the operating mode. AUTO is refused in SAFE_MODE: EnableFailedSafeMode and
        EXECUTION_ERROR (DEVIATION: the flight code answers OK)."""
        if self._request_mode(DetumbleMode(mode)):
            return CmdResponse.OK
        return CmdResponse.EXECUTION_ERROR

    # --- parameters (FPP order; ids fixed by the flight FPP) -----------------------------------
    # Each one's …ParamSet event and …Param channel are generated by the framework (ParamEcho) with
    # the flight ids; the bounds refuse values that would disable or break control (issue #16).

    BDOT_MAX_THRESHOLD = Param(F64, units="deg/s", default=720.0, id=40, low=0.0, high=3600.0,
                               echo=ParamEcho(event_id=6, channel_id=4, unit="deg/s"))
    DEADBAND_UPPER_THRESHOLD = Param(F64, units="deg/s", default=8.0, id=41, low=0.0, high=360.0,
                                     echo=ParamEcho(event_id=8, channel_id=5, unit="deg/s"))
    DEADBAND_LOWER_THRESHOLD = Param(F64, units="deg/s", default=5.0, id=1, low=0.0, high=360.0,
                                     echo=ParamEcho(event_id=9, channel_id=6, unit="deg/s"))
    COOLDOWN_DURATION = Param(TimeIntervalValue, units="s, µs", default=TimeIntervalValue(seconds=0, useconds=20000),
                              id=3, validate=_duration(0, 600_000_000), echo=ParamEcho(event_id=7, channel_id=9))
    TORQUE_DURATION = Param(TimeIntervalValue, units="s, µs", default=TimeIntervalValue(seconds=0, useconds=320000),
                            id=38, validate=_duration(1, 60_000_000), echo=ParamEcho(event_id=12, channel_id=10))
    GAIN = Param(F64, units="A·m²·s/G", default=3.0, id=39, low=0.0, high=1000.0,
                 echo=ParamEcho(event_id=10, channel_id=7))
    HYSTERESIS_AXIS = Param(HysteresisAxis, default=HysteresisAxis.X_AXIS, id=42,
                            echo=ParamEcho(event_id=11, channel_id=8))
    X_TURNS = Param(F64, units="turns", default=_XY.turns, id=11, low=1.0, high=10000.0,
                    echo=ParamEcho(event_id=23, channel_id=25))  # turns, both X coils
    Y_TURNS = Param(F64, units="turns", default=_XY.turns, id=21, low=1.0, high=10000.0,
                    echo=ParamEcho(event_id=34, channel_id=38))  # turns, both Y coils
    Z_TURNS = Param(F64, units="turns", default=_Z.turns, id=31, low=1.0, high=10000.0,
                    echo=ParamEcho(event_id=39, channel_id=44))  # turns, Z− coil
    X_PLUS_VOLTAGE = Param(F64, units="V", default=_XY.voltage_v, id=9, low=0.1, high=50.0,
                           echo=ParamEcho(event_id=21, channel_id=13, unit="V"))
    X_PLUS_RESISTANCE = Param(F64, units="Ω", default=_XY.resistance_ohm, id=10, low=0.1, high=10000.0,
                              echo=ParamEcho(event_id=19, channel_id=14, unit="Ω"))
    X_PLUS_LENGTH = Param(F64, units="m", default=_XY.length_m, id=12, low=0.001, high=1.0,
                          echo=ParamEcho(event_id=18, channel_id=16, unit="m"))
    X_PLUS_WIDTH = Param(F64, units="m", default=_XY.width_m, id=13, low=0.001, high=1.0,
                         echo=ParamEcho(event_id=22, channel_id=17, unit="m"))
    X_PLUS_SHAPE = Param(CoilShape, default=CoilShape(_XY.shape), id=33, echo=ParamEcho(event_id=20, channel_id=18))
    X_MINUS_VOLTAGE = Param(F64, units="V", default=_XY.voltage_v, id=14, low=0.1, high=50.0,
                            echo=ParamEcho(event_id=16, channel_id=19, unit="V"))
    X_MINUS_RESISTANCE = Param(F64, units="Ω", default=_XY.resistance_ohm, id=15, low=0.1, high=10000.0,
                               echo=ParamEcho(event_id=14, channel_id=20, unit="Ω"))
    X_MINUS_LENGTH = Param(F64, units="m", default=_XY.length_m, id=17, low=0.001, high=1.0,
                           echo=ParamEcho(event_id=13, channel_id=22, unit="m"))
    X_MINUS_WIDTH = Param(F64, units="m", default=_XY.width_m, id=18, low=0.001, high=1.0,
                          echo=ParamEcho(event_id=17, channel_id=23, unit="m"))
    X_MINUS_SHAPE = Param(CoilShape, default=CoilShape(_XY.shape), id=34, echo=ParamEcho(event_id=15, channel_id=24))
    Y_PLUS_VOLTAGE = Param(F64, units="V", default=_XY.voltage_v, id=19, low=0.1, high=50.0,
                           echo=ParamEcho(event_id=32, channel_id=26, unit="V"))
    Y_PLUS_RESISTANCE = Param(F64, units="Ω", default=_XY.resistance_ohm, id=20, low=0.1, high=10000.0,
                              echo=ParamEcho(event_id=30, channel_id=27, unit="Ω"))
    Y_PLUS_LENGTH = Param(F64, units="m", default=_XY.length_m, id=22, low=0.001, high=1.0,
                          echo=ParamEcho(event_id=29, channel_id=29, unit="m"))
    Y_PLUS_WIDTH = Param(F64, units="m", default=_XY.width_m, id=23, low=0.001, high=1.0,
                         echo=ParamEcho(event_id=33, channel_id=30, unit="m"))
    Y_PLUS_SHAPE = Param(CoilShape, default=CoilShape(_XY.shape), id=35, echo=ParamEcho(event_id=31, channel_id=31))
    Y_MINUS_VOLTAGE = Param(F64, units="V", default=_XY.voltage_v, id=24, low=0.1, high=50.0,
                            echo=ParamEcho(event_id=27, channel_id=32, unit="V"))
    Y_MINUS_RESISTANCE = Param(F64, units="Ω", default=_XY.resistance_ohm, id=25, low=0.1, high=10000.0,
                               echo=ParamEcho(event_id=25, channel_id=33, unit="Ω"))
    Y_MINUS_LENGTH = Param(F64, units="m", default=_XY.length_m, id=27, low=0.001, high=1.0,
                           echo=ParamEcho(event_id=24, channel_id=35, unit="m"))
    Y_MINUS_WIDTH = Param(F64, units="m", default=_XY.width_m, id=28, low=0.001, high=1.0,
                          echo=ParamEcho(event_id=28, channel_id=36, unit="m"))
    Y_MINUS_SHAPE = Param(CoilShape, default=CoilShape(_XY.shape), id=36, echo=ParamEcho(event_id=26, channel_id=37))
    Z_MINUS_VOLTAGE = Param(F64, units="V", default=_Z.voltage_v, id=29, low=0.1, high=50.0,
                            echo=ParamEcho(event_id=38, channel_id=39, unit="V"))
    Z_MINUS_RESISTANCE = Param(F64, units="Ω", default=_Z.resistance_ohm, id=30, low=0.1, high=10000.0,
                               echo=ParamEcho(event_id=36, channel_id=40, unit="Ω"))
    Z_MINUS_DIAMETER = Param(F64, units="m", default=_Z.diameter_m, id=32, low=0.001, high=1.0,
                             echo=ParamEcho(event_id=35, channel_id=42, unit="m"))
    Z_MINUS_SHAPE = Param(CoilShape, default=CoilShape(_Z.shape), id=37, echo=ParamEcho(event_id=37, channel_id=43))


    # --- output ports (FPP order) --------------------------------------------------------------

    angularVelocityMagnitudeGet = OutputPort(AngularVelocityMagnitudeGet)
    magneticFieldGet = OutputPort(MagneticFieldGet)
    magneticFieldSamplingPeriodGet = OutputPort(SamplingPeriodGet)
    getSystemMode = OutputPort(GetSystemMode)
    xPlusStart = OutputPort(StartMagnetorquer)
    xPlusStop = OutputPort(StopMagnetorquer)
    xMinusStart = OutputPort(StartMagnetorquer)
    xMinusStop = OutputPort(StopMagnetorquer)
    yPlusStart = OutputPort(StartMagnetorquer)
    yPlusStop = OutputPort(StopMagnetorquer)
    yMinusStart = OutputPort(StartMagnetorquer)
    yMinusStop = OutputPort(StopMagnetorquer)
    zMinusStart = OutputPort(StartMagnetorquer)
    zMinusStop = OutputPort(StopMagnetorquer)
    #: Optional: when connected (to a BDotDetumble), its dipole replaces the internal BDot's.
    dipoleMomentGet = OutputPort(DipoleMomentGet)

    # --- events (FPP order) --------------------------------------------------------------------

    EnableFailedSafeMode = Event(Severity.WARNING_LO,
                                 "Failed to enable detumbling because system is in SAFE_MODE.", throttle=5)
    DetumbleStarted = Event(Severity.ACTIVITY_LO, "Detumble started. Angular velocity magnitude: {} deg/s",
                            angular_velocity_magnitude_deg_sec=F64, throttle=1)
    DetumbleCompleted = Event(Severity.ACTIVITY_LO, "Detumble complete. Angular velocity magnitude: {} deg/s",
                              angular_velocity_magnitude_deg_sec=F64, throttle=1)
    MagneticFieldRetrievalFailed = Event(Severity.WARNING_LO, "Failed to retrieve magnetic field.", throttle=5)
    MagneticFieldSamplingPeriodRetrievalFailed = Event(
        Severity.WARNING_LO, "Failed to retrieve magnetic field sampling frequency.", throttle=5)
    AngularVelocityRetrievalFailed = Event(Severity.WARNING_LO, "Failed to retrieve angular velocity.",
                                           throttle=5)

    #: Addition (not in the flight FPP; declared last so every flight event keeps its id): the
    #: connected dipoleMomentGet provider answered FAILURE or a non-finite dipole.
    DipoleMomentRetrievalFailed = Event(Severity.WARNING_LO, "Failed to retrieve dipole moment.", throttle=5,
                                        id=40)

    # --- telemetry (FPP order; the parameter echoes in between are generated) -------------------

    Mode = Channel(DetumbleMode)
    State = Channel(DetumbleState)
    DetumbleStrategy = Channel(T.DetumbleStrategy)
    AngularVelocityMagnitude = Channel(F64, format="{.3f}", units="deg/s")
    TorqueDuration = Channel(TimeIntervalValue, id=11)  # measured length of the last B-dot actuation
    TimeBetweenMagneticFieldReadings = Channel(TimeIntervalValue)  # first to last sample of a window
    XPlusTurnsParam = Channel(F64, id=15, units="turns")
    XMinusTurnsParam = Channel(F64, id=21, units="turns")
    YPlusTurnsParam = Channel(F64, id=28, units="turns")
    YMinusTurnsParam = Channel(F64, id=34, units="turns")
    ZMinusTurnsParam = Channel(F64, id=41, units="turns")

    # --- actuator health (addition; declared last so every flight id stays as it is) -----------

    @sync_command()
    def ENABLE_COIL(self, face: MagnetorquerFace):
        """Return an isolated coil to service: it is driven again from the next cycle (a coil that
        still does not stop is isolated again at its next stop)."""
        index = _FACE_INDEX[MagnetorquerFace(face)]
        was_isolated = self._isolated[index]
        self._isolated[index] = False
        self._stop_failures[index] = 0
        self.CoilEnabled(face)
        if was_isolated:
            self.CoilStopFailed.clear_throttle()
        self._write_isolated()
        return CmdResponse.OK

    @sync_command()
    def ISOLATE_COIL(self, face: MagnetorquerFace):
        """Take a coil out of service: it is stopped once more, then never driven until ENABLE_COIL."""
        index = _FACE_INDEX[MagnetorquerFace(face)]
        port = self._stop_ports[index]
        if port.targets[0] is not None:
            port.calls[0]()
        self._isolated[index] = True
        self.CoilIsolatedByCommand(face)
        self._write_isolated()
        return CmdResponse.OK

    #: A coil's stop answered FAILURE: it may still carry current. The coil is isolated (no start
    #: and no stop is sent to it) until ENABLE_COIL.
    CoilStopFailed = Event(Severity.WARNING_HI,
                           "Magnetorquer {} did not stop (stop answered FAILURE): coil isolated until ENABLE_COIL",
                           face=MagnetorquerFace, throttle=10)
    CoilEnabled = Event(Severity.ACTIVITY_HI, "Magnetorquer {} enabled by command", face=MagnetorquerFace)
    CoilIsolatedByCommand = Event(Severity.ACTIVITY_HI, "Magnetorquer {} isolated by command",
                                  face=MagnetorquerFace)
    #: Isolated coils as a bit mask: bit = face number (X+ 0, X− 1, Y+ 2, Y− 3, Z− 5); 0 = all in service.
    IsolatedCoils = Channel(U8, update="on change")
    #: Stops that answered FAILURE, since start (all coils).
    CoilStopFailures = Channel(U32, update="on change")

    # --- construction --------------------------------------------------------------------------

    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self.bdot = BDot()
        self.strategy_selector = StrategySelector()
        self.magnetorquers: dict[str, Magnetorquer] = {c.name: Magnetorquer() for c in _COILS}
        self.mode = DetumbleMode.DISABLED
        self.state = DetumbleState.COOLDOWN
        self.strategy = T.DetumbleStrategy.IDLE
        self.cooldown_start_time: Time | None = None
        self.torque_start_time: Time | None = None
        self._bdot_levels: tuple[int, ...] | None = None  # drive levels of the current torque period
        self._start_ports = [self.output_port(c.start_port) for c in _COILS]  # X+, X−, Y+, Y−, Z−
        self._stop_ports = [self.output_port(c.stop_port) for c in _COILS]
        self.coils_driven = False
        self._safed = False  # the coils were stopped and the cycle reset since the mode became DISABLED
        self._isolated = [False] * len(_COILS)  # per coil (X+, X−, Y+, Y−, Z−): never driven while True
        self._stop_failures = [0] * len(_COILS)
        self._may_be_on = [False] * len(_COILS)  # a start switched it on; no good stop since
        self._last_system_mode: SystemMode | None = None
        self._external_dipole: tuple[float, float, float] | None = None
        self._param_by_local_id = {p.local_id: name for name, p in self.params.items()}
        # Cache the default coil settings so a deployment that never loads parameters still has
        # consistent coils; configure() (after load_parameters) replaces them and publishes them.
        for coil in _COILS:
            self._configure_coil(coil)

    # --- start-up and parameters ---------------------------------------------------------------

    def parameters_loaded(self) -> None:
        """Parameters are loaded: cache coil settings and publish them (DEVIATION: the flight
        code configured before loading)."""
        self.configure()

    def configure(self) -> None:
        """Cache every coil's settings from the parameters and write the per-coil turns channels
        (the framework has written every parameter's echo channel just before)."""
        for coil in _COILS:
            self._configure_coil(coil)
        for coil in _COILS:
            getattr(self, coil.turns_channel).write(self.params[coil.turns].value)
        self._write_isolated()
        self.CoilStopFailures.write(sum(self._stop_failures) & 0xFFFFFFFF)

    def parameter_updated(self, local_id: int) -> None:
        """A PRM_SET was accepted (the framework has echoed it: event + channel): re-configure the
        coils it belongs to (DEVIATION: the flight code emits neighbours' events too and never
        re-configures)."""
        name = self._param_by_local_id.get(local_id)
        if name is None:
            return
        value = self.params[name].value
        for coil in _COILS:
            if name in coil.params:
                self._configure_coil(coil)
                if name == coil.turns:
                    getattr(self, coil.turns_channel).write(value)

    def _configure_coil(self, coil: _CoilParams) -> None:
        self._bdot_levels = None  # the drive levels of a torque period depend on the coil settings
        p = self.params
        m = self.magnetorquers[coil.name]
        m.turns = float(p[coil.turns].value)
        m.voltage = float(p[coil.voltage].value)
        m.resistance = float(p[coil.resistance].value)
        m.shape = CoilOutline(int(p[coil.shape].value))
        m.direction_sign = coil.sign
        m.width = float(p[coil.width].value) if coil.width else 0.0
        m.length = float(p[coil.length].value) if coil.length else 0.0
        m.diameter = float(p[coil.diameter].value) if coil.diameter else 0.0

    # --- mode control --------------------------------------------------------------------------

    @sync_input(SetDetumbleMode)
    def setMode(self, mode):
        """SET_MODE without a command response."""
        self._request_mode(DetumbleMode(mode))

    @sync_input(SystemModeChanged)
    def systemModeChanged(self, mode):
        """SAFE_MODE forces DISABLED (coils stop on the next run); NORMAL does not re-enable."""
        self._last_system_mode = SystemMode(mode)
        if self._last_system_mode == SystemMode.SAFE_MODE:
            self.mode = DetumbleMode.DISABLED

    def _request_mode(self, mode: DetumbleMode) -> bool:
        """Apply a mode request; return False when AUTO was refused because of SAFE_MODE."""
        if mode != DetumbleMode.DISABLED and self._system_in_safe_mode():
            self.EnableFailedSafeMode()
            self.mode = DetumbleMode.DISABLED
            return False
        self.EnableFailedSafeMode.clear_throttle()
        self.mode = mode
        return True

    def _system_in_safe_mode(self) -> bool:
        """SAFE when the getSystemMode provider (if connected) says so, or when the latest
        systemModeChanged notification was SAFE_MODE."""
        if self._last_system_mode == SystemMode.SAFE_MODE:
            return True
        if self.is_connected("getSystemMode", 0):
            return self.getSystemMode[0]() == SystemMode.SAFE_MODE
        return False

    # --- run -----------------------------------------------------------------------------------

    @sync_input(Sched)
    def run(self, context):
        """Rate-group tick: telemeter Mode and State, then one state's actions.

        No exception escapes: a fault (a provider raising, a malformed reply) stops the coils, is
        reported (``report_fault``: the HandlerFault event, the HandlerFaults channel, the log)
        and restarts the cycle from COOLDOWN, so the next call tries again. A fault while stopping
        the coils is reported too ("run: safing").
        """
        try:
            self._run()
        except Exception as exc:  # noqa: BLE001 - the rate group must keep running; fail safe instead
            self.report_fault("run", exc)
            try:
                self._stop_coils()
            except Exception as safing:  # noqa: BLE001 - reported, never raised into the rate group
                self.report_fault("run: safing", safing)
            self._reset_cycle()

    def _run(self) -> None:
        mode = self.mode
        state = self.state
        self.Mode.write(mode)
        self.State.write(state)
        if mode == _DISABLED:
            if not self._safed:  # once per DISABLED spell, in any state; a ground START stays on (as flown)
                self._stop_coils()
                self._reset_cycle()
                self._safed = True
            return
        self._safed = False
        # the states in the order a B-dot cycle spends its ticks in them (most, then fewer)
        if state == _ACTUATING_BDOT:
            self._actuate_bdot()
        elif state == _SENSING_MAGNETIC_FIELD:
            self._sense_magnetic_field()
        elif state == _COOLDOWN:
            self._cooldown()
        elif state == _SENSING_ANGULAR_VELOCITY:
            self._sense_angular_velocity()
        elif state == _ACTUATING_HYSTERESIS:
            self._actuate_hysteresis()

    def _reset_cycle(self) -> None:
        """Back to COOLDOWN with timers and the B window cleared (Safe Disable)."""
        self.state = DetumbleState.COOLDOWN
        self.cooldown_start_time = None
        self.torque_start_time = None
        self._external_dipole = None
        self._bdot_levels = None
        self.bdot.empty_sample_set()

    @staticmethod
    def _elapsed_us(start: Time, now: Time) -> int:
        return now.total_us - start.total_us

    def _cooldown(self) -> None:
        now = self.get_time()
        if self.cooldown_start_time is None or now.total_us < self.cooldown_start_time.total_us:
            self.cooldown_start_time = now  # first call (or the clock went backwards: start again)
        elapsed = self._elapsed_us(self.cooldown_start_time, now)
        if elapsed >= self.COOLDOWN_DURATION.value.total_us:  # "at least" (flight: strictly greater)
            self.cooldown_start_time = None
            self.state = DetumbleState.SENSING_ANGULAR_VELOCITY

    def _sense_angular_velocity(self) -> None:
        self.strategy_selector.configure(self.BDOT_MAX_THRESHOLD.value, self.DEADBAND_UPPER_THRESHOLD.value,
                                         self.DEADBAND_LOWER_THRESHOLD.value)
        ok, w = self._read("angularVelocityMagnitudeGet", AngularUnit.DEG_PER_SEC)
        if not ok:
            self.AngularVelocityRetrievalFailed()
            return
        if not _finite(w):
            # A NaN or infinite rate is a failed read; never act on it, and stop a running drive.
            self.AngularVelocityRetrievalFailed()
            if self.coils_driven:
                self._stop_coils()
            return
        w = float(w)
        self.AngularVelocityRetrievalFailed.clear_throttle()
        self.AngularVelocityMagnitude.write(w)
        strategy = _DETUMBLE_STRATEGY[self.strategy_selector.from_angular_velocity_magnitude(w)]
        if strategy != T.DetumbleStrategy.HYSTERESIS and self.coils_driven:
            self._stop_coils()  # leaving HYSTERESIS (the only drive that outlives its state)
        self.strategy = strategy
        self.DetumbleStrategy.write(strategy)
        if strategy == T.DetumbleStrategy.IDLE:
            self.DetumbleCompleted(w)
            self.DetumbleStarted.clear_throttle()
            return
        if strategy == T.DetumbleStrategy.BDOT:
            self.bdot.empty_sample_set()
            self.state = DetumbleState.SENSING_MAGNETIC_FIELD
        else:
            self.state = DetumbleState.ACTUATING_HYSTERESIS
        self.DetumbleStarted(w)
        self.DetumbleCompleted.clear_throttle()

    def _sense_magnetic_field(self) -> None:
        ok, field = self._read("magneticFieldGet")
        if not ok or not _finite(field.x, field.y, field.z):
            self.MagneticFieldRetrievalFailed()
            return
        self.MagneticFieldRetrievalFailed.clear_throttle()
        self.bdot.add_sample((field.x, field.y, field.z), field.timestamp.total_us)
        if self.bdot.sampling_complete():
            spread_us = max(0, self.bdot.get_time_between_samples())
            self.TimeBetweenMagneticFieldReadings.write(TimeIntervalValue.from_us(spread_us))
            self.state = DetumbleState.ACTUATING_BDOT

    def _actuate_bdot(self) -> None:
        now = self.get_time()
        if self.torque_start_time is None and not self._enter_actuating_bdot():
            return
        levels = self._bdot_levels
        if levels is None:
            # The dipole depends only on the sample window, the gain configured at entry and the coil
            # settings, none of which change during the torque period (a coil parameter set by
            # command clears this cache), so it is computed once per period.
            if self._external_dipole is not None:
                mx, my, mz = self._external_dipole
            else:
                mx, my, mz = self.bdot.get_magnetic_moment()
            mt = self.magnetorquers
            levels = self._bdot_levels = (mt["x_plus"].dipole_moment_to_current(mx),
                                          mt["x_minus"].dipole_moment_to_current(mx),
                                          mt["y_plus"].dipole_moment_to_current(my),
                                          mt["y_minus"].dipole_moment_to_current(my),
                                          mt["z_minus"].dipole_moment_to_current(mz))
        self._start_coils(levels)
        start = self.torque_start_time
        assert start is not None  # set by _enter_actuating_bdot above
        now_us, start_us = now.total_us, start.total_us
        if now_us < start_us:
            self.torque_start_time = start = now  # the clock went backwards: measure from here
            start_us = now_us
        elapsed = now_us - start_us  # _elapsed_us(start, now), written out: every tick of a torque period
        if elapsed >= self.TORQUE_DURATION.value.total_us:
            self._bdot_levels = None
            self.bdot.empty_sample_set()
            self._stop_coils()
            self.TorqueDuration.write(TimeIntervalValue.from_us(elapsed))
            self.torque_start_time = None
            self._external_dipole = None
            self.state = DetumbleState.COOLDOWN

    def _enter_actuating_bdot(self) -> bool:
        """Entry actions of ACTUATING_BDOT; False when the cycle was abandoned (no actuation)."""
        gain = self.GAIN.value
        ok, period = self._read("magneticFieldSamplingPeriodGet")
        if not ok:
            self.MagneticFieldSamplingPeriodRetrievalFailed()
            self._abandon_bdot_cycle()  # DEVIATION: the flight code still fires one stale pulse
            return False
        self.MagneticFieldSamplingPeriodRetrievalFailed.clear_throttle()
        self.bdot.configure(gain, period.total_us)
        self._external_dipole = None
        self._bdot_levels = None
        if self.is_connected("dipoleMomentGet", 0):
            ok, dipole = self._read("dipoleMomentGet")
            if not ok or not _finite(dipole.x, dipole.y, dipole.z):
                self.DipoleMomentRetrievalFailed()
                self._abandon_bdot_cycle()
                return False
            self.DipoleMomentRetrievalFailed.clear_throttle()
            self._external_dipole = (float(dipole.x), float(dipole.y), float(dipole.z))
        self.torque_start_time = self.get_time()
        return True

    def _abandon_bdot_cycle(self) -> None:
        self._stop_coils()
        self._reset_cycle()

    def _actuate_hysteresis(self) -> None:
        axis = HysteresisAxis(self.HYSTERESIS_AXIS.value)
        self._start_coils(_HYSTERESIS_LEVELS[axis])
        self.cooldown_start_time = None
        self.state = DetumbleState.COOLDOWN

    # --- ports out -----------------------------------------------------------------------------

    def _read(self, port: str, *args):
        """Call a ``ref condition`` port; return ``(ok, value)``. Unconnected counts as a failure."""
        if not self.is_connected(port):
            return False, None
        value, condition = getattr(self, port)[0](*args)
        return condition == _SUCCESS, value

    def _start_coils(self, levels) -> None:
        """Drive X+, X−, Y+, Y−, Z− at ``levels`` (each −127…127); unconnected coils are skipped."""
        isolated, may_be_on, ports = self._isolated, self._may_be_on, self._start_ports
        if len(levels) != len(ports):
            raise ValueError(f"{len(levels)} drive levels for {len(ports)} coils")
        # indexed rather than enumerate(zip(...)): this runs every 50 Hz tick of a torque period
        for index in range(len(ports)):
            port = ports[index]
            if port.targets[0] is not None and not isolated[index]:  # unconnected coils are skipped
                level = levels[index]
                if port.calls[0](level) == _SUCCESS:
                    may_be_on[index] = level != 0
        self.coils_driven = True

    def _stop_coils(self) -> None:
        """Stop the five coils (unconnected and isolated coils are skipped).

        A coil that a start switched on (SUCCESS, non-zero level) and whose stop then answers FAILURE
        may still be on: it is isolated at once (CoilStopFailed, WARNING_HI) and not driven again
        until ENABLE_COIL. Every torque period ends with a stop, so a coil that stays on past its
        commanded duration is caught within one period. A failing stop of a coil that was not on
        since its last good stop (an unpowered or not yet initialised device) isolates nothing.
        """
        isolated, may_be_on = self._isolated, self._may_be_on
        for index, port in enumerate(self._stop_ports):
            if port.targets[0] is not None and not isolated[index]:
                if port.calls[0]() == _FAILURE:
                    if may_be_on[index]:
                        self._isolate_failed_coil(index)
                else:
                    may_be_on[index] = False
        self.coils_driven = False

    def _isolate_failed_coil(self, index: int) -> None:
        self._isolated[index] = True
        self._stop_failures[index] += 1
        self.CoilStopFailed(_COIL_FACES[index])
        self.CoilStopFailures.write(sum(self._stop_failures) & 0xFFFFFFFF)
        self._write_isolated()

    def _write_isolated(self) -> None:
        self.IsolatedCoils.write(sum(1 << int(face)
                                     for face, off in zip(_COIL_FACES, self._isolated, strict=True) if off))

    @property
    def isolated_faces(self) -> tuple[MagnetorquerFace, ...]:
        """The coils out of service now."""
        return tuple(face for face, off in zip(_COIL_FACES, self._isolated, strict=True) if off)
