"""LoRa as flown (``Zephyr.LoRa``, instance ``lora``): the radio, with a link model and a simulated peer.

The flight component wraps Zephyr's LoRa driver and carries the LoRa com stack's frames. Here the
radio keeps the flight ground interface and state machine and sends its own beacon over a modelled
air link (the reference deployment's commands and events go over ``comDriver``, not over this radio):

* TRANSMIT(ENABLED) lets the radio transmit; TRANSMIT(DISABLED) stops it at once (DISABLING while a
  packet is on the air, then DISABLED). ``enableTransmit`` / ``disableTransmit`` do the same.
* Each ``comStatusIn`` (from the ComDelay, every DIVIDER+1 ticks of 10 Hz) is a transmit opportunity
  (answered on ``comStatusOut``, which closes the loop through the ComDelay): with
  transmit ENABLED and the modem idle, the radio sends one packet — an F´ telemetry packet of its
  ``BytesSent`` channel, fprime-framed — which occupies the modem for its time on air
  (:func:`detumble.sim.lora_link.time_on_air_s` at the DATA_RATE, BANDWIDTH_TX and CODING_RATE
  parameters). The bytes go to the simulated ground peer (``spacecraft.radio_peer``, a bounded
  buffer: 64 KiB, the oldest bytes dropped) — what a LoRa passthrough board on the ground would print.
* CONTINUOUS_WAVE(seconds) keys an unmodulated carrier for ``seconds`` (the modem is busy, nothing
  else is sent); a second one while the first is on restarts the count (flight issue #207 fixed:
  both answer OK and no ConfigurationFailed).
* Packets sent and bytes on the air: channels BytesSent; BytesReceived, LastRssi and LastSnr stay at
  0 (nothing is uplinked over this radio in the simulation).

Ground interface (flight ids from ``Zephyr.LoRa``, base id 0x1001F000): parameters CODING_RATE,
DATA_RATE, BANDWIDTH_TX, BANDWIDTH_RX; commands CONTINUOUS_WAVE(seconds) (0), TRANSMIT(enabled) (1);
events ConfigurationFailed, SendFailed, AllocationFailed; channels BytesReceived, BytesSent,
LastRssi, LastSnr.
"""

from __future__ import annotations

from fprime_lite import (I8, I16, I32, U8, U16, U64, Channel, Event, FwEnum, OutputPort, Param, PassiveComponent,
                         Severity, fw_type, sync_command, sync_input)
from fprime_lite.model.fw_types import Success
from fprime_lite.wire.framing import FprimeFraming
from fprime_lite.wire.packets import encode_telemetry

from detumble.drivers.ports import Signal, SuccessCondition
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft
from detumble.sim.lora_link import time_on_air_s

__all__ = ["LoRa", "LoRaDataRate", "LoRaCodingRate", "LoRaBandwidth", "LoRaMode", "TransmitState"]


class LoRaDataRate(FwEnum, namespace="Zephyr", rep=U8):
    SF_7 = 7
    SF_8 = 8
    SF_9 = 9
    SF_10 = 10


class LoRaCodingRate(FwEnum, namespace="Zephyr", rep=U8):
    CR_4_5 = 1
    CR_4_6 = 2
    CR_4_7 = 3
    CR_4_8 = 4


class LoRaBandwidth(FwEnum, namespace="Zephyr", rep=U16):
    BW_125_KHZ = 125
    BW_250_KHZ = 250
    BW_500_KHZ = 500


class LoRaMode(FwEnum, namespace="Zephyr", rep=U8):
    Transmit = 0
    Receive = 1


class TransmitState(FwEnum, namespace="Zephyr", rep=U8):
    ENABLED = 0
    DISABLED = 1
    DISABLING = 2


class LoRa(PassiveComponent):
    """The LoRa radio of ``spacecraft`` and its ground peer."""

    # Instance state, set in __init__ (declared here: the handlers above it use it).
    transmit: TransmitState
    busy_until_us: int
    cw_until_us: int

    CODING_RATE = Param(LoRaCodingRate, default=LoRaCodingRate.CR_4_5)
    DATA_RATE = Param(LoRaDataRate, default=LoRaDataRate.SF_8)
    BANDWIDTH_TX = Param(LoRaBandwidth, default=LoRaBandwidth.BW_125_KHZ)
    BANDWIDTH_RX = Param(LoRaBandwidth, default=LoRaBandwidth.BW_125_KHZ)

    @sync_command()
    def CONTINUOUS_WAVE(self, seconds: U16):
        """Key an unmodulated carrier for ``seconds`` s."""
        self.busy_until_us = self._now_us() + int(seconds) * 1_000_000
        self.cw_until_us = self.busy_until_us

    @sync_command()
    def TRANSMIT(self, enabled: TransmitState):
        """Enable or disable transmission."""
        self._set_transmit(TransmitState(enabled))

    ConfigurationFailed = Event(Severity.WARNING_HI, "Failed to configure LoRa into mode: {}", mode=LoRaMode,
                                throttle=2)
    SendFailed = Event(Severity.WARNING_HI, "Failed to send LoRa message: {}", status=I32, throttle=2)
    AllocationFailed = Event(Severity.WARNING_HI, "Failed to allocate buffer of: {} bytes", allocation_size=U64,
                             throttle=2)

    BytesReceived = Channel(U64, update="on change")
    BytesSent = Channel(U64, update="on change")
    LastRssi = Channel(I16, update="on change")
    LastSnr = Channel(I8, update="on change")

    @sync_input(Signal)
    def enableTransmit(self) -> None:
        self._set_transmit(TransmitState.ENABLED)

    @sync_input(Signal)
    def disableTransmit(self) -> None:
        self._set_transmit(TransmitState.DISABLED)

    @sync_input(SuccessCondition)
    def comStatusIn(self, condition: Success) -> None:
        """A transmit opportunity (from the ComDelay); answered on ``comStatusOut`` either way."""
        now = self._now_us()
        if self.transmit == TransmitState.DISABLING and now >= self.busy_until_us:
            self.transmit = TransmitState.DISABLED
        if self.transmit == TransmitState.ENABLED and now >= self.busy_until_us:
            self._send(now)
        if self.is_connected("comStatusOut", 0):
            self.comStatusOut[0](Success.SUCCESS)

    comStatusOut = OutputPort(SuccessCondition)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft
        self.transmit = TransmitState.DISABLED
        self.busy_until_us = 0
        self.cw_until_us = 0
        self.bytes_sent = 0
        self.packets_sent = 0
        #: what the simulated ground peer heard (the spacecraft's: it outlives a software reset)
        self.peer = spacecraft.radio_peer

    def take_peer_bytes(self, limit: int = 65536) -> bytes:
        """Remove and return up to ``limit`` bytes the ground peer heard, oldest first."""
        n = min(limit, len(self.peer))
        return bytes(self.peer.popleft() for _ in range(n))

    def _now_us(self) -> int:
        return self.get_time().total_us

    def _set_transmit(self, state: TransmitState) -> None:
        if state == TransmitState.DISABLED and self._now_us() < self.busy_until_us \
                and self._now_us() >= self.cw_until_us:
            self.transmit = TransmitState.DISABLING
        else:
            self.transmit = TransmitState.ENABLED if state == TransmitState.ENABLED else TransmitState.DISABLED

    def _send(self, now_us: int) -> None:
        record = (self.channel_id("BytesSent"), self.get_time(), fw_type(U64).serialize(self.bytes_sent))
        frame = FprimeFraming.frame(encode_telemetry([record]))
        air_s = time_on_air_s(min(len(frame), 255), int(self.DATA_RATE.value), int(self.BANDWIDTH_TX.value) * 1e3,
                              int(self.CODING_RATE.value))
        self.busy_until_us = now_us + int(air_s * 1e6)
        self.peer.extend(frame)
        self.bytes_sent += len(frame)
        self.packets_sent += 1
        self.BytesSent.write(self.bytes_sent)
