"""The framework's own port types: the special ports every component may have, and Sched.

Special ports carry commands, events, telemetry, parameters and time between a component and the
standard services. Argument payloads travel as F´ serialized bytes, as they do in F´.
"""

from __future__ import annotations

from fprime_lite.model.commands import CmdResponse
from fprime_lite.model.events import Severity
from fprime_lite.model.ports import PortType
from fprime_lite.model.time import Time
from fprime_lite.model.types import U32

__all__ = ["Cmd", "CmdReg", "CmdResponsePort", "Log", "LogText", "Tlm", "PrmGet", "PrmSet",
           "TimeGet", "Sched", "Com", "BufferSend", "Cycle", "Ping", "FatalEvent", "CmdSeqIn", "CmdSeqCancel",
           "SPECIAL_PORTS"]

Cmd = PortType("Fw.Cmd", opcode=U32, cmd_seq=U32, args=bytes)
CmdReg = PortType("Fw.CmdReg", opcode=U32)
CmdResponsePort = PortType("Fw.CmdResponse", opcode=U32, cmd_seq=U32, response=CmdResponse)
Log = PortType("Fw.Log", id=U32, time=Time, severity=Severity, args=bytes)
LogText = PortType("Fw.LogText", id=U32, time=Time, severity=Severity, text=str)
Tlm = PortType("Fw.Tlm", id=U32, time=Time, value=bytes)
#: Returns ``(validity, value bytes)``; the bytes are None unless validity is VALID.
PrmGet = PortType("Fw.PrmGet", returns=tuple, id=U32)
PrmSet = PortType("Fw.PrmSet", id=U32, value=bytes)
TimeGet = PortType("Fw.Time", returns=Time)
Sched = PortType("Svc.Sched", context=U32)
#: A packet of F´ bytes (``U16 descriptor | payload``), as the ground link and services pass them.
Com = PortType("Fw.Com", data=bytes, context=U32)
#: A buffer of bytes handed on (F´'s ``Fw.BufferSend`` with the ``Fw::Buffer`` as ``bytes``): file
#: packets between the ground link and the file uplink/downlink components.
BufferSend = PortType("Fw.BufferSend", fwBuffer=bytes)
#: One tick of a rate-group driver; ``cycle_start`` is when the cycle began.
Cycle = PortType("Svc.Cycle", cycle_start=Time)
Ping = PortType("Svc.Ping", key=U32)
FatalEvent = PortType("Svc.FatalEvent", id=U32)
#: Ask a sequencer to run the sequence file ``file_name``.
CmdSeqIn = PortType("Svc.CmdSeqIn", file_name=str)
#: Ask a sequencer to cancel the running sequence.
CmdSeqCancel = PortType("Svc.CmdSeqCancel")

#: Special port kind (FPP spelling) -> (conventional F´ port name, port type, direction).
SPECIAL_PORTS = {
    "command recv": ("cmdIn", Cmd, "input"),
    "command reg": ("cmdRegOut", CmdReg, "output"),
    "command resp": ("cmdResponseOut", CmdResponsePort, "output"),
    "event": ("logOut", Log, "output"),
    "text event": ("logTextOut", LogText, "output"),
    "telemetry": ("tlmOut", Tlm, "output"),
    "param get": ("prmGetOut", PrmGet, "output"),
    "param set": ("prmSetOut", PrmSet, "output"),
    "time get": ("timeCaller", TimeGet, "output"),
}

