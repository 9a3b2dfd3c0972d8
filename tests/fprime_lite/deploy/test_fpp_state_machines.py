"""FPP state machines that run (issue 30; docs/fpp.md "State machines"): a component's `state machine
instance`, its signals queued and dispatched, its actions and guards supplied by the Python class
under F´'s generated names, FPP's semantics (initial transitions, entry/exit, inherited transitions,
choices, internal transitions, guards, typed signals) and the refusals."""

from __future__ import annotations

import pathlib
import shutil

import pytest

pytest.importorskip("fpp", reason="FPP models need fprime-fpp-python (the test extra installs it)")

from fprime_lite.deploy.fpp.loader import FppError, component_class, load_fpp  # noqa: E402

DATA = pathlib.Path(__file__).resolve().parents[2] / "data" / "fpp_state_machine"
INIT = "__FPRIME_AC_INITIAL_TRANSITION"


@pytest.fixture
def lamp(tmp_path, monkeypatch):
    """A fresh copy of the lamp component (its class is made per copy)."""
    for name in ("lamp_switch.fpp", "lamp_switch.py"):
        shutil.copy(DATA / name, tmp_path / name)
    monkeypatch.syspath_prepend(str(tmp_path))
    return tmp_path


def _make(folder):
    return component_class(folder / "lamp_switch.fpp", "Components.LampSwitch")("lampSwitch", base_id=0x100,
                                                                                 queue_size=4)


def _drain(c):
    c.calls.clear()
    c.dispatch_all()
    return c.calls, c.lamp_getState().name


def test_the_initial_transition_runs_at_construction(lamp):
    """FPSM-001: the machine's initial transition's actions, then OFF's entry, with F´'s initial signal."""
    c = _make(lamp)
    assert c.calls == [("log", INIT), ("countEntry", INIT)]
    assert c.lamp_getState().name == "OFF"
    assert [s.name for s in type(c.lamp_getState())] == ["__FPRIME_UNINITIALIZED", "OFF", "ON_BRIGHT", "ON_DIM"]


def test_a_signal_waits_on_the_queue_then_exits_enters_and_follows_initial_transitions(lamp):
    """FPSM-002: sendSignal queues (nothing runs until dispatch); OFF -> ON runs OFF's exit, ON's
    entry, ON's initial transition into DIM and DIM's entry, in that order."""
    c = _make(lamp)
    c.calls.clear()
    c.lamp_sendSignal_toggle()
    assert c.calls == [] and c.lamp_getState().name == "OFF" and len(c.queue) == 1
    assert _drain(c) == ([("log", "toggle"), ("countEntry", "toggle"), ("countEntry", "toggle")], "ON_DIM")


def test_a_choice_takes_the_branch_its_typed_guard_gives_with_the_signals_value(lamp):
    """FPSM-003: `level` enters choice CHECK; the U8 value reaches the guard and the action."""
    c = _make(lamp)
    c.lamp_sendSignal_toggle()
    c.dispatch_all()
    c.calls.clear()
    c.lamp_sendSignal_level(200)
    assert _drain(c) == ([("setLevel", 200), ("countEntry", "level")], "ON_BRIGHT")
    c.lamp_sendSignal_level(50)
    assert _drain(c) == ([("setLevel", 50), ("countEntry", "level")], "ON_DIM")


def test_a_false_guard_leaves_the_state_and_runs_nothing(lamp):
    """FPSM-004: OFF's `on toggle if allowed`: with the guard false nothing happens."""
    c = _make(lamp)
    c.allow = False
    c.calls.clear()
    c.lamp_sendSignal_toggle()
    assert _drain(c) == ([], "OFF")


def test_an_enclosing_states_transition_applies_unless_the_leaf_has_its_own(lamp):
    """FPSM-005: `reset` in DIM is ON's (exit ON, its action, enter OFF); in BRIGHT it is BRIGHT's
    own self-transition (BRIGHT entered again, ON not left)."""
    c = _make(lamp)
    c.lamp_sendSignal_toggle()
    c.dispatch_all()
    c.calls.clear()
    c.lamp_sendSignal_reset()
    assert _drain(c) == ([("log", "reset"), ("log", "reset"), ("countEntry", "reset")], "OFF")
    c.lamp_sendSignal_toggle()
    c.lamp_sendSignal_level(255)
    c.dispatch_all()
    c.calls.clear()
    c.lamp_sendSignal_reset()
    assert _drain(c) == ([("countEntry", "reset")], "ON_BRIGHT")


def test_a_transition_into_a_nested_state_enters_its_parents_first(lamp):
    """FPSM-006: OFF `on reset enter ON.BRIGHT`: OFF's exit, ON's entry, BRIGHT's entry (ON's
    initial transition to DIM is not taken)."""
    c = _make(lamp)
    c.calls.clear()
    c.lamp_sendSignal_reset()
    assert _drain(c) == ([("log", "reset"), ("countEntry", "reset"), ("countEntry", "reset")], "ON_BRIGHT")


def test_an_internal_transition_runs_its_actions_without_exit_or_entry(lamp):
    """FPSM-007: BRIGHT's `on toggle do { log }` overrides ON's `on toggle enter OFF`."""
    c = _make(lamp)
    c.lamp_sendSignal_reset()
    c.dispatch_all()
    c.calls.clear()
    c.lamp_sendSignal_toggle()
    assert _drain(c) == ([("log", "toggle")], "ON_BRIGHT")


def test_a_full_queue_drops_signals_as_the_instance_says(lamp):
    """FPSM-008: the instance is `drop`: signals beyond the queue's 4 are dropped and counted."""
    c = _make(lamp)
    for _ in range(6):
        c.lamp_sendSignal_toggle()
    assert len(c.queue) == 4 and c.queue.dropped == 2


def test_a_hook_instance_calls_the_overflow_hook(lamp):
    """FPSM-009: `hook`: a signal that finds the queue full goes to stateMachineOverflowHook."""
    fpp_file = lamp / "lamp_switch.fpp"
    fpp_file.write_text(fpp_file.read_text().replace("priority 3 drop", "priority 3 hook"))
    module = lamp / "lamp_switch.py"
    module.write_text(module.read_text() + "\n    def stateMachineOverflowHook(self, smId, signal, value):\n"
                                           "        self.calls.append(('overflow', smId.name, signal.name, value))\n")
    c = _make(lamp)
    c.calls.clear()
    for _ in range(4):
        c.lamp_sendSignal_toggle()
    c.lamp_sendSignal_level(7)
    assert c.calls == [("overflow", "lamp", "level", 7)]


def test_the_rate_groups_tick_reaches_the_state_machine_in_a_topology(lamp):
    """FPSM-010: the FPP topology binds the component and its `run` handler's signal changes state."""
    model = load_fpp([lamp / "lamp_switch.fpp"])
    (instance,) = model.instances.values()
    c = instance.component.cls("lampSwitch", base_id=instance.component.base_id, queue_size=4)
    c.run(0)
    c.dispatch_all()
    assert c.lamp_getState().name == "ON_DIM"


@pytest.mark.parametrize("edit, expected", [
    (("    def Components_Lamp_action_setLevel(self, smId, signal, value):",
      "    def setLevelOther(self, smId, signal, value):"),
     "lamp_switch.fpp:10:5: action setLevel of state machine Components.Lamp has no method: give LampSwitch a "
     "method Components_Lamp_action_setLevel(self, smId, signal, value)"),
    (("    def Components_Lamp_guard_allowed(self, smId, signal):",
      "    def Components_Lamp_guard_allowed(self, smId):"),
     "lamp_switch.fpp:13:5: guard allowed of state machine Components.Lamp: LampSwitch.Components_Lamp_guard_allowed "
     "takes (smId); it must take (smId, signal)"),
])
def test_a_missing_or_ill_fitting_action_or_guard_is_refused_at_its_fpp_line(lamp, edit, expected):
    """FPSM-011: a missing action method or a guard of the wrong arity is refused before flying,
    with the action's or guard's FPP line."""
    module = lamp / "lamp_switch.py"
    module.write_text(module.read_text().replace(*edit))
    with pytest.raises(FppError) as caught:
        _make(lamp)
    assert any(expected in p for p in caught.value.problems), caught.value.problems


def test_an_external_state_machine_is_refused_with_the_reason(lamp):
    """FPSM-012: a state machine with no states in FPP (F´'s external kind, C++ behaviour) is refused."""
    fpp_file = lamp / "lamp_switch.fpp"
    text = fpp_file.read_text().replace("  state machine Lamp {", "  state machine Plain\n\n  state machine Lamp {")
    fpp_file.write_text(text.replace("state machine instance lamp: Lamp", "state machine instance lamp: Plain"))
    with pytest.raises(FppError) as caught:
        _make(lamp)
    assert any("state machine Components.Plain is external" in p for p in caught.value.problems), caught.value.problems


def test_a_deployment_flies_the_state_machine_on_its_rate_group(tmp_path, monkeypatch):
    """FPSM-013: the FPP topology run as `fprime-lite run` runs it: a 1 Hz rate group calls the lamp
    switch, whose `run` queues a toggle; the scheduler dispatches it. Ticks at 0, 1, 2 and 3 s give
    four toggles: OFF -> ON_DIM -> OFF -> ON_DIM -> OFF."""
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.fpp.run import write_topology_yaml
    from fprime_lite.deploy.topology_loader import load_topology

    folder = tmp_path / "lamp"
    folder.mkdir()
    for name in ("lamp_switch.fpp", "lamp_switch.py"):
        shutil.copy(DATA / name, folder / name)
    text = (folder / "lamp_switch.fpp").read_text()
    (folder / "lamp_switch.fpp").write_text(text[:text.index("module Demo {")])  # the components only
    monkeypatch.syspath_prepend(str(folder))
    files = [folder / "lamp_switch.fpp", DATA / "deployment" / "topology.fpp"]
    yaml_path = write_topology_yaml(files, tmp_path, run_file=DATA / "deployment" / "run.yaml")
    deployment = Deployment(load_topology(yaml_path))
    deployment.start()
    deployment.run_for(3.5)
    lamp = deployment.topology.instance("Demo.lampSwitch").component
    assert [c for c in lamp.calls if c[0] == "log"] == [("log", INIT)] + [("log", "toggle")] * 4
    assert lamp.lamp_getState().name == "OFF"


def test_a_faulting_action_is_reported_by_instance_and_signal_and_the_queue_goes_on(lamp):
    """FPSM-014: an action that raises, dispatched as a deployment's scheduler dispatches (faults
    contained), is a HandlerFault naming `lamp.toggle`; the signals behind it still run."""
    module = lamp / "lamp_switch.py"
    module.write_text(module.read_text().replace('        self.calls.append(("log", signal.name))',
                                                 '        self.calls.append(("log", signal.name))\n'
                                                 '        if getattr(self, "fail", False):\n'
                                                 '            raise ZeroDivisionError("log")'))
    c = _make(lamp)
    faults = []
    c.report_fault = lambda where, exc: faults.append((where, type(exc).__name__))
    c.fail = True
    c.lamp_sendSignal_toggle()
    c.lamp_sendSignal_level(200)
    assert c.dispatch_all(contain_faults=True) == 2
    assert faults == [("lamp.toggle", "ZeroDivisionError")]


def test_a_class_declaring_its_members_is_refused_a_state_machine_instance(lamp):
    """FPSM-015: the state machine is flown for a handlers-only class; a class that declares its
    own members (checked against the FPP, not made from it) is refused at the instance's line."""
    from fprime_lite.model import fw_ports
    from fprime_lite.model.component import QueuedComponent
    from fprime_lite.model.ports import async_input

    class Declared(QueuedComponent):
        @async_input(fw_ports.Sched)
        def run(self, context):
            pass

    with pytest.raises(FppError) as caught:
        component_class(lamp / "lamp_switch.fpp", "Components.LampSwitch",
                        implementations={"Components.LampSwitch": Declared})
    assert any("lamp_switch.fpp:42:5: Components.LampSwitch: state machine instance lamp: " in p
               and "Declared declares its members" in p for p in caught.value.problems), caught.value.problems
