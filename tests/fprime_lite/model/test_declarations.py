"""Component declarations are checked when the class is created."""

import pytest

from fprime_lite import (F64, I32, U8, U32, Channel, DeclarationError, Event, FwEnum, OutputPort,
                         Param, PassiveComponent, PortType, QueuedComponent, Sched, Severity,
                         String, async_command, async_input, sync_command, sync_input)

Ping = PortType("Test.Ping", key=U32)


def test_auto_ids_follow_declaration_order_and_continue_after_explicit_ones():
    class Comp(PassiveComponent):
        A = Event(Severity.DIAGNOSTIC, "a")
        B = Event(Severity.DIAGNOSTIC, "b", id=10)
        C = Event(Severity.DIAGNOSTIC, "c")
        X = Channel(U32)
        Y = Channel(U32, id=5)
        P = Param(F64, default=1.0)
        Q = Param(F64, default=1.0, id=7)

        @sync_command()
        def CMD_A(self):
            pass

        @sync_command(opcode=0x20)
        def CMD_B(self):
            pass

    spec = Comp.__fprime_spec__
    assert [(e.name, e.local_id) for e in spec.own_events] == [("A", 0), ("B", 10), ("C", 11)]
    assert [(c.name, c.local_id) for c in spec.own_channels] == [("X", 0), ("Y", 5)]
    assert [(p.name, p.local_id) for p in spec.params] == [("P", 0), ("Q", 7)]
    assert [(c.name, c.opcode) for c in spec.commands] == [
        ("P_PRM_SET", 0), ("P_PRM_SAVE", 1), ("Q_PRM_SET", 2), ("Q_PRM_SAVE", 3),
        ("CMD_A", 4), ("CMD_B", 0x20)]
    comp = Comp("comp", base_id=0x1000)
    assert comp.opcode("CMD_B") == 0x1020
    assert comp.event_id("C") == 0x100B
    assert comp.channel_id("Y") == 0x1005
    assert comp.param_id("Q") == 0x1007


def test_duplicate_event_id_names_class_and_both_members():
    with pytest.raises(DeclarationError,
                       match=r"Dup: event id 3 \(0x3\) of Second is already used by First"):
        class Dup(PassiveComponent):
            First = Event(Severity.DIAGNOSTIC, "x", id=3)
            Second = Event(Severity.DIAGNOSTIC, "y", id=3)


def test_duplicate_opcode_between_command_and_generated_param_command():
    with pytest.raises(DeclarationError, match=r"Dup: opcode 1 \(0x1\) of command CMD is already used by "
                                               r"command GAIN_PRM_SAVE"):
        class Dup(PassiveComponent):
            GAIN = Param(F64, default=1.0)

            @sync_command(opcode=1)
            def CMD(self):
                pass


def test_duplicate_channel_and_param_ids():
    with pytest.raises(DeclarationError, match=r"channel id 0 \(0x0\) of B is already used by A"):
        class C1(PassiveComponent):
            A = Channel(U32, id=0)
            B = Channel(U32, id=0)
    with pytest.raises(DeclarationError, match=r"parameter id 2 \(0x2\) of B is already used by A"):
        class C2(PassiveComponent):
            A = Param(U32, id=2)
            B = Param(U32, id=2)


def test_member_declared_twice():
    with pytest.raises(DeclarationError, match=r"Twice\.State is declared twice"):
        class Twice(PassiveComponent):
            State = Channel(U32)
            State = Channel(U8)  # the error under test


def test_handler_signature_must_fit_port_type():
    with pytest.raises(DeclarationError,
                       match=r"Bad\.run: handler takes 2 argument\(s\) \(port_num, context\) but port type "
                             r"Svc\.Sched needs 1 \(context\)"):
        class Bad(PassiveComponent):
            @sync_input(Sched)
            def run(self, port_num, context):
                pass


def test_port_array_handler_needs_port_num():
    with pytest.raises(DeclarationError, match=r"needs 2 \(port_num, context\); handlers of port arrays "
                                               r"take port_num first"):
        class Bad(PassiveComponent):
            @sync_input(Sched, size=2)
            def run(self, context):
                pass


def test_format_placeholders_must_match_arguments():
    with pytest.raises(DeclarationError, match=r"Fmt\.E: format 'w={} and {}' has more placeholders than "
                                               r"the 1 argument\(s\)"):
        class Fmt(PassiveComponent):
            E = Event(Severity.ACTIVITY_HI, "w={} and {}", w=F64)
    with pytest.raises(DeclarationError, match=r"format 'no placeholder' has 0 placeholder\(s\) but the event "
                                               r"has 1 argument\(s\)"):
        class Fmt2(PassiveComponent):
            E = Event(Severity.ACTIVITY_HI, "no placeholder", w=F64)


def test_format_placeholder_must_suit_argument_type():
    with pytest.raises(DeclarationError, match=r"placeholder \{\.2f\} needs a float argument, argument 1 is I32"):
        class Fmt(PassiveComponent):
            E = Event(Severity.ACTIVITY_HI, "{.2f}", n=I32)
    with pytest.raises(DeclarationError, match=r"placeholder \{x\} needs an integer argument"):
        class Fmt2(PassiveComponent):
            E = Event(Severity.ACTIVITY_HI, "{x}", v=F64)
    with pytest.raises(DeclarationError, match=r"unknown placeholder \{q\}"):
        class Fmt3(PassiveComponent):
            E = Event(Severity.ACTIVITY_HI, "{q}", v=F64)
    with pytest.raises(DeclarationError, match=r"unmatched '\{'"):
        class Fmt4(PassiveComponent):
            E = Event(Severity.ACTIVITY_HI, "oops { here")


def test_channel_format_is_checked_too():
    with pytest.raises(DeclarationError, match=r"Tlm\.T: placeholder \{d\} needs an integer argument"):
        class Tlm(PassiveComponent):
            T = Channel(F64, format="{d}")


def test_passive_component_cannot_have_async_members():
    with pytest.raises(DeclarationError, match=r"P\.ping: a passive component cannot have async input ports"):
        class P(PassiveComponent):
            @async_input(Ping)
            def ping(self, key):
                pass
    with pytest.raises(DeclarationError, match=r"P2\.GO: a passive component cannot have async commands"):
        class P2(PassiveComponent):
            @async_command()
            def GO(self):
                pass


def test_hook_overflow_needs_a_hook_method():
    with pytest.raises(DeclarationError, match=r"Q\.ping: queue_full='hook' needs a method ping_overflow_hook"):
        class Q(QueuedComponent):
            @async_input(Ping, queue_full="hook")
            def ping(self, key):
                pass


def test_async_port_cannot_return_a_value():
    Get = PortType("Test.Get", returns=U32)
    with pytest.raises(DeclarationError, match=r"async input ports cannot return a value"):
        class Q(QueuedComponent):
            @async_input(Get)
            def get(self):
                pass


def test_command_arguments_need_fprime_types():
    with pytest.raises(DeclarationError, match=r"C\.SET: argument 'x' needs an F´ type annotation"):
        class C(PassiveComponent):
            @sync_command()
            def SET(self, x):
                pass
    with pytest.raises(DeclarationError, match=r"C2\.SET: argument 'x': .* is not an F´ type"):
        class C2(PassiveComponent):
            @sync_command()
            def SET(self, x: int):
                pass


def test_param_default_must_fit_its_type():
    with pytest.raises(DeclarationError, match=r"C\.P: default 300 does not fit: U8 value 300 is out of range"):
        class C(PassiveComponent):
            P = Param(U8, default=300)


def test_reserved_names_and_command_name_clash():
    with pytest.raises(DeclarationError, match=r"the name 'cmdIn' is reserved"):
        class C(PassiveComponent):
            cmdIn = OutputPort(Ping)
    with pytest.raises(DeclarationError, match=r"command GAIN_PRM_SET clashes with the command generated for "
                                               r"parameter GAIN"):
        class C2(PassiveComponent):
            GAIN = Param(F64, default=0.0)

            @sync_command()
            def GAIN_PRM_SET(self, v: F64):
                pass


def test_bad_declaration_arguments():
    with pytest.raises(DeclarationError, match="event throttle must be a positive integer"):
        Event(Severity.DIAGNOSTIC, "x", throttle=0)
    with pytest.raises(DeclarationError, match="event severity must be a Severity"):
        Event(3, "x")
    with pytest.raises(DeclarationError, match="channel update must be 'always' or 'on change'"):
        Channel(U32, update="sometimes")
    with pytest.raises(DeclarationError, match="OutputPort needs a PortType"):
        OutputPort(U32)
    with pytest.raises(DeclarationError, match="queue_full must be one of assert, block, drop, hook"):
        async_input(Ping, queue_full="explode")
    with pytest.raises(DeclarationError, match="command opcode must be a non-negative integer"):
        sync_command(opcode=-1)


def test_special_ports_follow_members():
    class Bare(PassiveComponent):
        @sync_input(Sched)
        def run(self, context):
            pass

    class Full(PassiveComponent):
        E = Event(Severity.DIAGNOSTIC, "e")
        T = Channel(U32)
        P = Param(String(10), default="abc")

    # Every component has the framework's HandlerFault event and HandlerFaults channel (decision
    # 0005), so even a bare one has event and telemetry ports.
    assert set(Bare.__fprime_spec__.special) == {"time get", "event", "text event", "telemetry"}
    assert set(Full.__fprime_spec__.special) == {
        "time get", "command recv", "command reg", "command resp", "event", "text event", "telemetry",
        "param get", "param set"}
    f = Full("f")
    assert f.P.value == "abc"


def test_subclass_overriding_a_handler_keeps_the_port():
    class Base(PassiveComponent):
        __fprime_abstract__ = True

        @sync_input(Sched)
        def run(self, context):
            self.seen = ("base", context)

    class Derived(Base):
        def run(self, context):
            self.seen = ("derived", context)

    d = Derived("d")
    d.input_port("run").entries[0](4)
    assert d.seen == ("derived", 4)


def test_enum_rep_must_hold_every_value():
    class Big(FwEnum, rep=U8):
        A = 0
        B = 256

    with pytest.raises(DeclarationError, match=r"enum Big\.B = 256 does not fit its representation type U8"):
        class C(PassiveComponent):
            T = Channel(Big)


def test_declarations_leave_the_class_attributes_so_instance_lookups_stay_fast():
    """Instances own ``xOut``, ``Evt``, ``Chan``, ``Prm``; the class keeps them only in its body record
    (a same-named class attribute would stop CPython from specialising ``self.xOut``)."""

    class Mixin:  # a plain mixin declaring members, as the rate groups' shared logic does
        Shared = Channel(U32)

    class Base(Mixin, PassiveComponent):
        xOut = OutputPort(Ping)
        Evt = Event(Severity.DIAGNOSTIC, "e")
        Prm = Param(U32, default=3)

    class Derived(Base):
        Extra = Channel(F64)

    for name in ("xOut", "Evt", "Prm"):
        assert name not in vars(Base)
    assert "Shared" not in vars(Mixin) and "Extra" not in vars(Derived)
    # Class-level reads still give the declarations; the derived spec still has the inherited ones.
    assert isinstance(Base.xOut, OutputPort) and isinstance(Derived.Evt, Event)
    assert isinstance(Derived.Shared, Channel) and isinstance(Derived.Extra, Channel)
    spec = Derived.__fprime_spec__
    assert [c.name for c in spec.own_channels] == ["Shared", "Extra"]
    assert [p.name for p in spec.params] == ["Prm"] and "xOut" in spec.outputs
    # A second component built on the same mixin after the first one moved its declarations out.
    class Other(Mixin, PassiveComponent):
        pass

    assert [c.name for c in Other.__fprime_spec__.own_channels] == ["Shared"]
    d = Derived("d")
    assert type(d.xOut) is list and d.Prm.value == 3 and d.Shared.decl.name == "Shared"
    with pytest.raises(AttributeError, match="'Derived' has no attribute 'nothing'"):
        Derived.nothing  # noqa: B018


def test_channels_and_params_may_share_an_event_s_fprime_name_through_name():
    """F´ lets an event, a channel and a parameter share a name; attributes cannot, so ``name=``."""

    class Comp(PassiveComponent):
        Level = Event(Severity.ACTIVITY_LO, "level {}", value=U32)
        Level_channel = Channel(U32, name="Level")
        Level_param = Param(U32, default=1, name="Level")

    spec = Comp.__fprime_spec__
    assert [c.name for c in spec.own_channels] == ["Level"] and [p.name for p in spec.params] == ["Level"]
    assert [c.name for c in spec.commands] == ["LEVEL_PRM_SET", "LEVEL_PRM_SAVE"]
    comp = Comp("comp")
    assert comp.channels["Level"] is comp.Level_channel and comp.params["Level"] is comp.Level_param
    assert comp.events["Level"] is comp.Level


def test_two_channels_with_one_fprime_name_are_refused():
    with pytest.raises(DeclarationError, match="channels A and B both have the F´ name 'A'"):
        class Comp(PassiveComponent):
            A = Channel(U32)
            B = Channel(U32, name="A")
    with pytest.raises(DeclarationError, match="channel name must be an identifier, got 'a b'"):
        Channel(U32, name="a b")
