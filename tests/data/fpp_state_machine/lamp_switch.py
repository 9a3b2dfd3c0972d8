"""The Python half of Components.LampSwitch (lamp_switch.fpp): the state machine's actions and
guards as F´ names them (Components_Lamp_action_*, Components_Lamp_guard_*), which record what
ran so that tests/fprime_lite/deploy/test_fpp_state_machines.py can check the order."""

from fprime_lite.model.component import QueuedComponent


class LampSwitch(QueuedComponent):
    def __init__(self, name, **kwargs):
        super().__init__(name, **kwargs)
        self.calls = []
        self.allow = True

    def run(self, context):
        self.lamp_sendSignal_toggle()

    def Components_Lamp_action_countEntry(self, smId, signal):
        self.calls.append(("countEntry", signal.name))

    def Components_Lamp_action_setLevel(self, smId, signal, value):
        self.calls.append(("setLevel", value))

    def Components_Lamp_action_log(self, smId, signal):
        self.calls.append(("log", signal.name))

    def Components_Lamp_guard_bright(self, smId, signal, value):
        return value > 100

    def Components_Lamp_guard_allowed(self, smId, signal):
        return self.allow
