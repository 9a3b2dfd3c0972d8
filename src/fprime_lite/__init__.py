"""fprime_lite: F´ (F Prime) components, ports and services in pure Python.

This module only re-exports the public names; each lives in its own module.
"""

from fprime_lite.model.commands import CmdResponse, CommandToken, async_command, guarded_command, sync_command
from fprime_lite.model.component import ActiveComponent, Component, PassiveComponent, QueuedComponent
from fprime_lite.model.errors import (DeclarationError, FprimeLiteError, FwAssertionError, PortConnectionError,
                     QueueFullError, SerializationError, UnconnectedPortError)
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.fw_ports import Sched
from fprime_lite.model.params import Param, ParamValid
from fprime_lite.model.ports import OutputPort, PortType, async_input, guarded_input, sync_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.time import SimulatedClock, Time, TimeBase, TimeInterval, WallClock
from fprime_lite.model.types import (BOOL, F32, F64, I8, I16, I32, I64, U8, U16, U32, U64, Alias, Array, FwEnum,
                    String, Struct, fw_type)

__version__ = "0.1.0"

__all__ = [
    "CmdResponse", "CommandToken", "async_command", "guarded_command", "sync_command",
    "ActiveComponent", "Component", "PassiveComponent", "QueuedComponent",
    "DeclarationError", "FprimeLiteError", "FwAssertionError", "PortConnectionError",
    "QueueFullError", "SerializationError", "UnconnectedPortError",
    "Event", "Severity", "Sched", "Param", "ParamValid",
    "OutputPort", "PortType", "async_input", "guarded_input", "sync_input", "Channel",
    "SimulatedClock", "Time", "TimeBase", "TimeInterval", "WallClock",
    "BOOL", "F32", "F64", "I8", "I16", "I32", "I64", "U8", "U16", "U32", "U64",
    "Alias", "Array", "FwEnum", "String", "Struct", "fw_type",
]
