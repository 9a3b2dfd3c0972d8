"""Veml6031Manager as flown: a VEML6031 ambient-light sensor on a face board.

The reading is the face's light sensor as ``SimulatedSpacecraft.light_sensor_lux`` gives it
(``detumble.sim.sun_sensors``): the Sun's illuminance (133 klx at 1 AU, ``LUX_PER_W_M2`` ≈ 98 lm/W times the
flux) times the cosine of its angle to the face normal, 0 on faces turned away and in eclipse, with a fixed
gain error (2 % 1σ) and white noise (0.5 % of full Sun 1σ). Earth albedo is not modelled, nor is the sensor's
saturation at its gain and integration time (the parameters are kept and checked, not applied). The sensor is
powered through its face's load switch: while it is open GetVisibleLight logs DeviceNotReady (throttled) and answers
EXECUTION_ERROR, ``visibleLightGet`` returns FAILURE.

Ground interface (flight ``Drv.Veml6031Manager``; base ids 0x1004D000 face0 … 0x10052000 face5):
parameters GAIN, INTEGRATION_TIME, EFFECTIVE_PHOTODIODE_SIZE (flight enums and defaults); command
GetVisibleLight (0); channel VisibleLight (lux); the flight events in order, VisibleLight(lux) last.
"""

from __future__ import annotations

from fprime_lite import (F32, I32, U8, Channel, CmdResponse, Event, FwEnum, Param, PassiveComponent, Severity,
                         String, sync_command, sync_input)
from fprime_lite.model.fw_types import On, Success

from detumble.components.types import Result
from detumble.drivers.ports import LightGet, LoadSwitchStateChanged
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft
from detumble.proves.zephyr_sensor_events import ZephyrSensorEvents
from detumble.sim.power import FACE_SWITCHES
from detumble.sim.sun_sensors import LUX_PER_W_M2

__all__ = ["Veml6031Manager", "GAIN", "IT", "DIV4", "LUX_PER_W_M2"]



class GAIN(FwEnum, namespace="Drv", rep=U8):
    VEML6031_GAIN_1 = 0
    VEML6031_GAIN_2 = 1
    VEML6031_GAIN_0_66 = 2
    VEML6031_GAIN_0_5 = 3


class IT(FwEnum, namespace="Drv", rep=U8):
    VEML6031_IT_3_125 = 0
    VEML6031_IT_6_25 = 1
    VEML6031_IT_12_5 = 2
    VEML6031_IT_25 = 3
    VEML6031_IT_50 = 4
    VEML6031_IT_100 = 5
    VEML6031_IT_200 = 6
    VEML6031_IT_400 = 7


class DIV4(FwEnum, namespace="Drv", rep=U8):
    VEML6031_SIZE_4_4 = 0
    VEML6031_SIZE_1_4 = 1


class Veml6031Manager(ZephyrSensorEvents, PassiveComponent):
    """The VEML6031 on face ``face`` (0 X+ … 5 Z−) of ``spacecraft``."""

    GAIN = Param(GAIN, default=GAIN.VEML6031_GAIN_0_5)
    INTEGRATION_TIME = Param(IT, default=IT.VEML6031_IT_25)
    EFFECTIVE_PHOTODIODE_SIZE = Param(DIV4, default=DIV4.VEML6031_SIZE_1_4)

    @sync_command()
    def GetVisibleLight(self):
        """Read the sensor and log VisibleLight."""
        value, condition = self.visibleLightGet()
        if condition != Success.SUCCESS:
            return CmdResponse.EXECUTION_ERROR
        self.VisibleLight(value)

    #: The channel ``VisibleLight`` (the attribute differs: the event has the same F´ name).
    VisibleLight_tlm = Channel(F32, name="VisibleLight", units="lux")

    @sync_input(LightGet)
    def visibleLightGet(self) -> Result:
        """Illuminance in the visible band, lux, or FAILURE when the device is not powered."""
        if not self.spacecraft.load_switch(self.switch):
            self.DeviceNotReady()
            return Result(0.0, Success.FAILURE)
        self.DeviceNotReady.clear_throttle()
        lux = self.spacecraft.light_sensor_lux(self.face)
        self.VisibleLight_tlm.write(lux)
        return Result(lux, Success.SUCCESS)

    @sync_input(LoadSwitchStateChanged)
    def loadSwitchStateChanged(self, state: On) -> Success:
        return Success.SUCCESS

    InvalidGainParam = Event(Severity.WARNING_LO, "Invalid gain parameter: {}", gain=U8, throttle=5)
    InvalidIntegrationTimeParam = Event(Severity.WARNING_LO, "Invalid integration time parameter: {}", it=U8,
                                        throttle=5)
    InvalidDiv4Param = Event(Severity.WARNING_LO, "Invalid effective photodiode size parameter: {}", div4=U8,
                             throttle=5)
    SensorAttrSetFailed = Event(Severity.WARNING_LO, "Sensor attribute {}={} set failed with return code: {}",
                                attr=String(40), val=U8, ret=I32, throttle=5)
    VisibleLight = Event(Severity.ACTIVITY_HI, "Visible light: {} lux", lux=F32)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, face: int, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        if face not in range(6):
            raise ValueError(f"{name}: face must be 0..5 (X+, X-, Y+, Y-, Z+, Z-), got {face!r}")
        self.spacecraft = spacecraft
        self.face = face
        self.switch = FACE_SWITCHES[face]
