"""LoadSwitch as flown: one of the flight controller's eight power switches, on the simulated EPS.

The PROVES ``Components.LoadSwitch`` drives a GPIO that enables a load's power rail and reads the
rail's state back from the same GPIO. Here the GPIO *is* the simulated electrical system's switch
(``spacecraft.set_load_switch(switch, on)``): closing ``face0`` powers the X+ face board and its
coil driver, opening it de-energises that coil at once and removes the board's load.

Ground interface (flight): commands TURN_ON, TURN_OFF, GET_IS_ON; channel IsOn (``Fw.On``); events
StatusChanged (id 1, "Load switch state changed to {}") and IsOn ("Current load switch state: {}").
Ports: ``turnOn`` / ``turnOff`` (``Fw.Signal``, from the ModeManager) and
``loadSwitchStateChanged[0..2]`` (``Fw.On -> Fw.Success``) telling the face's devices — the coil
driver — that their power changed. A request for the state the switch is already in does nothing
(no event, no notification), as in flight.

Instances (flight ``instances.fpp``): ``face0LoadSwitch`` … ``face5LoadSwitch`` (switch ``face0`` …
``face5``), ``payloadPowerLoadSwitch`` (``payloadPower``), ``payloadBatteryLoadSwitch``
(``payloadBattery``).
"""

from __future__ import annotations

from fprime_lite import Channel, Event, OutputPort, PassiveComponent, Severity, sync_command, sync_input
from fprime_lite.model.fw_types import On

from detumble.sim.power import SWITCH_NAMES
from detumble.drivers.ports import LoadSwitchStateChanged, Signal
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["LoadSwitch", "STATE_CHANGED_PORTS"]

#: Number of ``loadSwitchStateChanged`` outputs (flight: temperature sensor, light sensor, coil driver).
STATE_CHANGED_PORTS = 3


class LoadSwitch(PassiveComponent):
    """Switch ``switch`` (``face0`` … ``face5``, ``payloadPower``, ``payloadBattery``) of ``spacecraft``."""

    @sync_command()
    def TURN_ON(self):
        """Close the switch."""
        self.set_state(On.ON)

    @sync_command()
    def TURN_OFF(self):
        """Open the switch."""
        self.set_state(On.OFF)

    @sync_command()
    def GET_IS_ON(self):
        """Report the state (IsOn event)."""
        self.IsOn(self.state)

    #: The channel ``IsOn`` (the attribute differs: the event has the same F´ name).
    IsOn_tlm = Channel(On, name="IsOn")

    StatusChanged = Event(Severity.ACTIVITY_HI, "Load switch state changed to {}", state=On, id=1)
    IsOn = Event(Severity.ACTIVITY_LO, "Current load switch state: {}", state=On)

    loadSwitchStateChanged = OutputPort(LoadSwitchStateChanged, size=STATE_CHANGED_PORTS)

    @sync_input(Signal)
    def turnOn(self) -> None:
        self.set_state(On.ON)

    @sync_input(Signal)
    def turnOff(self) -> None:
        self.set_state(On.OFF)

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, switch: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        if switch not in SWITCH_NAMES:
            raise ValueError(f"{name}: unknown switch {switch!r}; switches are {list(SWITCH_NAMES)}")
        self.spacecraft = spacecraft
        self.switch = switch

    @property
    def state(self) -> On:
        """The switch as the GPIO reads it back."""
        return On.ON if self.spacecraft.load_switch(self.switch) else On.OFF

    def set_state(self, state: On) -> None:
        if self.state == state:
            return
        self.spacecraft.set_load_switch(self.switch, state == On.ON)
        for i in range(STATE_CHANGED_PORTS):
            if self.is_connected("loadSwitchStateChanged", i):
                self.loadSwitchStateChanged[i](state)
        self.StatusChanged(state)
        self.IsOn_tlm.write(state)
