"""The events every PROVES Zephyr sensor manager declares first, in the flight order (a mixin).

``Drv.Tmp112Manager`` and ``Drv.Veml6031Manager`` both begin their event lists with these eight
(ids 0…7 from the component's base id); a component that mixes this class in before its own
events gets the flight ids. Only DeviceNotReady can happen in the simulation (the I²C mux and the
Zephyr sensor driver are not simulated); the others are kept for the dictionary.
"""

from __future__ import annotations

from fprime_lite import I32, Event, Severity

__all__ = ["ZephyrSensorEvents"]


class ZephyrSensorEvents:
    """DeviceNotReady, DeviceInitFailed, DeviceNil, DeviceStateNil, TcaUnhealthy, MuxUnhealthy,
    SensorSampleFetchFailed, SensorChannelGetFailed (WARNING_LO, throttled 5)."""

    DeviceNotReady = Event(Severity.WARNING_LO, "Device not ready", throttle=5)
    DeviceInitFailed = Event(Severity.WARNING_LO, "Initialization failed with return code: {}", ret=I32, throttle=5)
    DeviceNil = Event(Severity.WARNING_LO, "Device is nil", throttle=5)
    DeviceStateNil = Event(Severity.WARNING_LO, "Device state is nil", throttle=5)
    TcaUnhealthy = Event(Severity.WARNING_LO, "TCA device is unhealthy", throttle=5)
    MuxUnhealthy = Event(Severity.WARNING_LO, "MUX device is unhealthy", throttle=5)
    SensorSampleFetchFailed = Event(Severity.WARNING_LO, "Sensor fetch failed with return code: {}", ret=I32,
                                    throttle=5)
    SensorChannelGetFailed = Event(Severity.WARNING_LO, "Sensor channel get failed with return code: {}", ret=I32,
                                   throttle=5)
