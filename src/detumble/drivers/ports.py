"""Port types of the PROVES flight components simulated here (flight FPP names)."""

from __future__ import annotations

from fprime_lite import F64, PortType
from fprime_lite.model.fw_types import On, Success

__all__ = ["Signal", "VoltageGet", "CurrentGet", "PowerGet", "LoadSwitchStateChanged"]

#: ``Fw.Signal``: a call without arguments.
Signal = PortType("Fw.Signal")
#: ``Drv.VoltageGet -> F64``: volts.
VoltageGet = PortType("Drv.VoltageGet", returns=F64)
#: ``Drv.CurrentGet -> F64``: amps.
CurrentGet = PortType("Drv.CurrentGet", returns=F64)
#: ``Drv.PowerGet -> F64``: watts.
PowerGet = PortType("Drv.PowerGet", returns=F64)
#: ``Components.loadSwitchStateChanged(state: Fw.On) -> Fw.Success``.
LoadSwitchStateChanged = PortType("Components.loadSwitchStateChanged", returns=Success, state=On)
