"""Port types of the PROVES flight components simulated here (flight FPP names)."""

from __future__ import annotations

from fprime_lite import F64, PortType
from fprime_lite.model.fw_types import On, Success

from detumble.components.types import Result

__all__ = ["Signal", "VoltageGet", "CurrentGet", "PowerGet", "LoadSwitchStateChanged", "TemperatureGet",
           "PicoTemperatureGet", "LightGet", "SuccessCondition"]

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
#: ``Drv.temperatureGet(ref condition: Fw.Success) -> F64``: °C, returned as ``Result(value, condition)``.
TemperatureGet = PortType("Drv.temperatureGet", returns=Result)
#: ``Drv.picoTemperatureGet(ref condition: Fw.Success) -> F64``: °C, as ``Result``.
PicoTemperatureGet = PortType("Drv.picoTemperatureGet", returns=Result)
#: ``Drv.lightGet(ref condition: Fw.Success) -> F32``: lux, as ``Result``.
LightGet = PortType("Drv.lightGet", returns=Result)
#: ``Fw.SuccessCondition(condition: Fw.Success)``: a com status.
SuccessCondition = PortType("Fw.SuccessCondition", condition=Success)
