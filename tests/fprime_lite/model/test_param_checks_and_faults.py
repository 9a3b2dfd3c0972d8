"""Parameter validation and echoes, and the framework's fault reporting (issues #11, #16)."""

from __future__ import annotations

import math

import pytest

from fprime_lite import (F64, U32, Channel, CmdResponse, DeclarationError, Event, ParamValid, PassiveComponent,
                         QueuedComponent, Sched, Severity, Param, async_input, sync_command, sync_input)
from fprime_lite.deploy.scheduler import Scheduler
from fprime_lite.model.params import ParamEcho


class Coil(PassiveComponent):
    Started = Event(Severity.ACTIVITY_LO, "started")
    TURNS = Param(F64, default=96.0, low=1.0, high=1000.0, echo=ParamEcho(unit="turns"))
    RATE = Param(F64, default=1.0, finite=True)
    LIMIT = Param(U32, default=5, validate=lambda v: None if v % 5 == 0 else f"{v} is not a multiple of 5")

    @sync_command()
    def BOOM(self):
        raise ZeroDivisionError("by design")


def test_echo_members_are_generated_after_the_declared_ones():
    """PRM-011-1: ParamEcho gives TurnsParamSet (ACTIVITY_HI, '<NAME> parameter set to {} <unit>.')
    and TurnsParam, numbered after the declared members; the framework's own follow them."""
    spec = Coil.__fprime_spec__
    assert [(e.name, e.local_id) for e in spec.events] == [
        ("Started", 0), ("TurnsParamSet", 1), ("HandlerFault", 2), ("ParamSetRefused", 3), ("ParamDefaulted", 4)]
    echo = spec.event("TurnsParamSet")
    assert (echo.severity, echo.format, [t.name for t in echo.arg_types]) == (
        Severity.ACTIVITY_HI, "TURNS parameter set to {} turns.", ["F64"])
    assert [(c.name, c.local_id, c.type.name) for c in spec.channels] == [("TurnsParam", 0, "F64"),
                                                                          ("HandlerFaults", 1, "U32")]
    assert [e.name for e in spec.own_events] == ["Started", "TurnsParamSet"]


def test_explicit_echo_ids_and_names():
    """PRM-011-2: explicit echo ids and names are taken as given; a clash is a declaration error."""
    class Named(PassiveComponent):
        A = Event(Severity.ACTIVITY_LO, "a", id=0)
        P = Param(F64, default=0.0, echo=ParamEcho(event_id=7, channel_id=3, event="PSet", channel="PNow",
                                                    format="P is {}"))

    spec = Named.__fprime_spec__
    assert (spec.event("PSet").local_id, spec.event("PSet").format, spec.channel("PNow").local_id) == (7, "P is {}", 3)
    assert spec.event("HandlerFault").local_id == 8  # after the largest id, not after the last one

    with pytest.raises(DeclarationError, match="event id 0"):
        class Clash(PassiveComponent):
            A = Event(Severity.ACTIVITY_LO, "a", id=0)
            P = Param(F64, default=0.0, echo=ParamEcho(event_id=0))


def test_framework_member_names_are_reserved():
    """FLT-011-1: a component cannot declare HandlerFault or HandlerFaults itself."""
    with pytest.raises(DeclarationError, match="reserved"):
        class Mine(PassiveComponent):
            HandlerFault = Event(Severity.WARNING_HI, "mine")


@pytest.mark.parametrize("kwargs, message", [
    ({"low": 2.0, "high": 1.0}, "above high"),
    ({"default": 0.5, "low": 1.0}, "below the minimum"),
    ({"default": math.nan, "finite": True}, "not a finite number"),
    ({"low": "x"}, "not a F64"),
])
def test_bad_validation_declarations_are_declaration_errors(kwargs, message):
    """PRM-016-7: inconsistent bounds, or a default they refuse, fail when the class is built."""
    kwargs = {"default": 1.0, **kwargs}
    with pytest.raises(DeclarationError, match=message):
        class Bad(PassiveComponent):
            P = Param(F64, **kwargs)


def test_bounds_apply_to_numbers_only():
    """PRM-016-8: low/high on an enum or struct parameter is refused with what to use instead."""
    with pytest.raises(DeclarationError, match="use validate="):
        class Bad(PassiveComponent):
            P = Param(ParamValid, default=ParamValid.VALID, low=1)


@pytest.mark.parametrize("name, value, accepted", [
    ("TURNS", 1.0, True), ("TURNS", 1000.0, True), ("TURNS", 0.999, False), ("TURNS", 1000.5, False),
    ("TURNS", math.nan, False), ("RATE", -1e300, True), ("RATE", math.inf, False), ("RATE", math.nan, False),
    ("LIMIT", 10, True), ("LIMIT", 7, False),
])
def test_prm_set_validation(fprime_harness, name, value, accepted):
    """PRM-016-9: bounds are inclusive; finite= refuses NaN and ±inf; validate= gives the reason.
    A refused value answers VALIDATION_ERROR, changes nothing, emits ParamSetRefused and no echo."""
    h = fprime_harness(Coil("coil"))
    h.load_parameters()
    h.clear_history()
    before = h.component.params[name].value
    h.send_raw_command(h.component.opcode(f"{name}_PRM_SET"), h.component.spec.param(name).type.serialize(value))
    if accepted:
        h.assert_cmd_response(0, f"{name}_PRM_SET", CmdResponse.OK)
        assert h.component.params[name].value == value
        h.assert_no_event("ParamSetRefused")
    else:
        h.assert_cmd_response(0, f"{name}_PRM_SET", CmdResponse.VALIDATION_ERROR)
        assert h.component.params[name].value == before
        assert [e.name for e in h.events] == ["ParamSetRefused"] and h.events[0].args[0] == name
        assert h.telemetry == []


def test_echo_on_set_and_on_load(fprime_harness):
    """PRM-011-3: loading writes the echo channel with the loaded value; an accepted PRM_SET emits
    the event and writes the channel, then parameter_updated runs."""
    h = fprime_harness(Coil("coil"))
    h.param_set("TURNS", 120.0)
    h.load_parameters()
    assert h.tlm_values("TurnsParam") == [120.0] and h.events == []
    h.param_set("TURNS", 150.0)
    h.param_send("TURNS")
    assert h.events_named("TurnsParamSet") == [(150.0,)] and h.tlm_values("TurnsParam") == [120.0, 150.0]
    assert h.text_events[-1].text == "(coil) TurnsParamSet: TURNS parameter set to 150.0 turns."


def test_refused_file_values_fall_back_to_the_default(fprime_harness):
    """PRM-016-10: a stored value that fails validation, or does not deserialize, loads the
    default (validity DEFAULT) with a WARNING_HI ParamDefaulted naming the parameter and why."""
    h = fprime_harness(Coil("coil"))
    h.param_set("TURNS", 5000.0)
    h.param_set("LIMIT", 7)
    h._param_store[h.component.params["RATE"].id] = (ParamValid.VALID, b"\x00\x01")  # 2 bytes for an F64
    h.load_parameters()
    c = h.component
    assert (c.TURNS.value, c.TURNS.validity, c.LIMIT.value, c.RATE.value) == (96.0, ParamValid.DEFAULT, 5, 1.0)
    got = {e.args[0]: e.args[1] for e in h.events if e.name == "ParamDefaulted"}
    assert got.keys() == {"TURNS", "LIMIT", "RATE"}
    assert got["TURNS"] == "5000.0 is above the maximum 1000.0" and got["LIMIT"] == "7 is not a multiple of 5"
    assert "needs 8 byte(s)" in got["RATE"]
    assert all(e.severity == Severity.WARNING_HI for e in h.events)


def test_a_command_fault_is_reported(fprime_harness):
    """FLT-016-3: a command handler that raises answers EXECUTION_ERROR, emits HandlerFault naming
    the command and the exception, and HandlerFaults counts it."""
    h = fprime_harness(Coil("coil"))
    h.send_command("BOOM")
    h.assert_cmd_response(0, "BOOM", CmdResponse.EXECUTION_ERROR)
    assert h.events_named("HandlerFault") == [("BOOM", "ZeroDivisionError: by design")]
    assert h.tlm_values("HandlerFaults") == [1]
    assert h.text_events[-1].text == "(coil) HandlerFault: Handler BOOM raised ZeroDivisionError: by design"


class Worker(QueuedComponent):
    @async_input(Sched)
    def work(self, context):
        if context == 13:
            raise KeyError("unlucky")
        self.done = context


def test_a_queued_fault_in_a_deployment_is_reported_and_the_queue_goes_on(fprime_harness):
    """FLT-016-4: drained by a scheduler (a deployment), a queued handler that raises is reported
    with its port; the message behind it runs. Without a scheduler (a unit test) it propagates."""
    s = Scheduler()
    w = Worker("worker")
    h = fprime_harness(w)
    s.drain_after_each_event(w)
    s.call_at(5, lambda: [w.input_port("work").entries[0](c) for c in (13, 14)])
    s.run()
    assert w.done == 14 and w.handler_faults == 1
    assert h.events_named("HandlerFault") == [("work", "KeyError: 'unlucky'")]
    w2 = Worker("alone")
    fprime_harness(w2)
    w2.input_port("work").entries[0](13)
    with pytest.raises(KeyError):
        w2.dispatch_all()


def test_fault_report_never_raises_when_the_event_port_does(fprime_harness, caplog):
    """FLT-016-5: if sending the fault event itself fails, the fault is still counted and logged."""
    h = fprime_harness(Coil("coil"))
    h.component.output_port("logOut").connect_callable(0, lambda *a: 1 / 0, "broken")
    h.component.report_fault("somewhere", RuntimeError("x"))
    assert h.component.handler_faults == 1 and "reporting a fault failed" in caplog.text


def test_run_handler_type_checks_are_not_needed_at_run_time():
    """TYP-011-1: the descriptors exist only for a type checker: on the class the declarations are
    gone (no shadowing of the instance attributes), on the instance they are the bound objects."""
    c = Coil("c")
    assert "TURNS" not in vars(Coil) and "Started" not in vars(Coil)
    assert type(c).__dict__.get("__get__") is None and not hasattr(Param, "__get__") and not hasattr(Event, "__get__")
    assert c.TURNS.value == 96.0 and c.Started() is True


def test_sync_input_decorator_keeps_the_function():
    """TYP-011-2: the input/command decorators return the function itself (typed as such)."""
    def run(self, context):
        return context
    assert sync_input(Sched)(run) is run


def test_an_automatic_id_steps_over_explicit_echo_ids():
    """PRM-011-4: a member declared after the last one takes the id after the echoes that the
    flight listing puts there (explicit echo ids 2 and 3 after declared 1: the next is 4)."""
    class Listing(PassiveComponent):
        P = Param(F64, default=0.0, echo=ParamEcho(event_id=0, channel_id=2))
        Q = Param(F64, default=0.0, echo=ParamEcho(event_id=1, channel_id=3))
        A = Channel(F64)
        B = Channel(F64, id=1)
        C = Channel(F64)

    spec = Listing.__fprime_spec__
    assert [(c.name, c.local_id) for c in spec.own_channels] == [("A", 0), ("B", 1), ("C", 4), ("PParam", 2),
                                                                 ("QParam", 3)]
    with pytest.raises(DeclarationError, match="channel id 2"):
        class Clash(PassiveComponent):
            P = Param(F64, default=0.0, echo=ParamEcho(channel_id=2))
            A = Channel(F64, id=2)
