"""A port harness for unit-testing one component, with the abilities of F´'s generated TesterBase.

The harness connects every output port of the component under test to itself and records what
comes out: plain output ports into per-port histories (with overridable handlers that provide
return values), and the special ports decoded into command-response, event, text-event and telemetry
histories with typed values. It acts as the component's PrmDb and time source. Nothing sleeps:
time is whatever the test sets.

    h = ComponentHarness(DetumbleManager("detumbleManager", base_id=0x1005A000))
    h.set_port_return("getSystemMode", SystemMode.NORMAL)
    h.send_command("SET_MODE", DetumbleMode.AUTO)
    h.assert_cmd_response(0, "SET_MODE", CmdResponse.OK)
    h.invoke("run", 0)
    h.assert_tlm("State", 0, DetumbleState.COOLDOWN)

F´ spellings work too, with F´'s arguments: ``invoke_to_run(portNum, context)``,
``sendCmd_SET_MODE(instance, cmdSeq, mode)``, ``paramSet_GAIN(4.0, ParamValid.VALID)``,
``paramSend_GAIN(instance, cmdSeq)``, ``paramSave_GAIN(instance, cmdSeq)``, ``setTestTime(t)``,
``clearHistory()``, and GTestBase's assertions ``assertCmdResponse_size(n)``,
``assertCmdResponse(index, opCode, cmdSeq, response)``, ``assertEvents_size(n)``,
``assertEvents_<E>_size(n)``, ``assertEvents_<E>(index, args…)``, ``assertTlm_size(n)``,
``assertTlm_<C>_size(n)``, ``assertTlm_<C>(index, value)``, ``assertFromPortHistory_size(n)``,
``assert_from_<port>_size(n)``.
"""

from __future__ import annotations

from typing import Any, Callable, NamedTuple

from fprime_lite.model.commands import CmdResponse
from fprime_lite.model.component import Component, QueuedComponent
from fprime_lite.model.errors import FwAssertionError
from fprime_lite.model.events import Severity
from fprime_lite.model.params import BoundParam, ParamValid
from fprime_lite.model.time import Time, TimeBase, TimeInterval
from fprime_lite.model.types import deserialize_values

__all__ = ["ComponentHarness", "PortCall", "CommandResponseRecord", "EventRecord", "TextEventRecord",
           "TelemetryRecord"]


class PortCall(NamedTuple):
    """One call out of a plain output port."""

    port: str
    index: int  # type: ignore[assignment]  # F´'s from-port history has a port index; shadows tuple.index
    args: tuple[Any, ...]


class CommandResponseRecord(NamedTuple):
    opcode: int
    cmd_seq: int
    response: CmdResponse


class EventRecord(NamedTuple):
    name: str
    id: int
    time: Time
    severity: Severity
    args: tuple


class TextEventRecord(NamedTuple):
    id: int
    time: Time
    severity: Severity
    text: str


class TelemetryRecord(NamedTuple):
    name: str
    id: int
    time: Time
    value: Any


def _listing(rows, empty="(empty)") -> str:
    rows = list(rows)
    if not rows:
        return "  " + empty
    return "\n".join(f"  [{i}] {row}" for i, row in enumerate(rows))


class ComponentHarness:
    """Drives one component through its ports and records everything it sends."""

    def __init__(self, component: Component, *, test_time: Time | None = None,
                 unconnected: tuple[str, ...] = ()):
        """``unconnected`` names optional output ports to leave unconnected (as a topology might)."""
        self.component = component
        self._left_unconnected = set(unconnected)
        for port in unconnected:
            component.output_port(port)  # raises with the list of ports if the name is wrong
        self.test_time = test_time if test_time is not None else Time(TimeBase.TB_NONE, 0, 0, 0)
        self.port_calls: list[PortCall] = []
        self.cmd_responses: list[CommandResponseRecord] = []
        self.events: list[EventRecord] = []
        self.text_events: list[TextEventRecord] = []
        self.telemetry: list[TelemetryRecord] = []
        self.registered_opcodes: list[int] = []
        self.saved_params: list[tuple[str, int, Any]] = []
        self._param_store: dict[int, tuple[ParamValid, bytes | None]] = {}
        self._handlers: dict[tuple[str, int | None], Callable] = {}
        self._events_by_id = {e.id: e for e in component.events.values()}
        self._channels_by_id = {c.id: c for c in component.channels.values()}
        self._params_by_id = {p.id: p for p in component.params.values()}
        self._connect()

    # --- wiring ----------------------------------------------------------------------------------

    def _connect(self) -> None:
        comp = self.component
        special = {name: kind for kind, name in comp.spec.special.items()}
        recorders: dict[str, Callable[..., Any]] = {
            "command reg": self._on_cmd_reg,
            "command resp": self._on_cmd_response,
            "event": self._on_event,
            "text event": self._on_text_event,
            "telemetry": self._on_tlm,
            "param get": self._on_prm_get,
            "param set": self._on_prm_set,
            "time get": self._on_time_get,
        }
        for name, port in comp.output_ports.items():
            if name in self._left_unconnected:
                continue
            kind = special.get(name)
            for i in range(len(port)):
                if kind is not None:
                    port.connect_callable(i, recorders[kind], "harness")
                else:
                    port.connect_callable(i, self._recorder(name, i), "harness")

    def _recorder(self, port: str, index: int) -> Callable:
        calls = self.port_calls
        handlers = self._handlers
        returns = self.component.output_port(port).port_type.returns

        def record(*args):
            calls.append(PortCall(port, index, args))
            handler = handlers.get((port, index)) or handlers.get((port, None))
            if handler is not None:
                return handler(*args)
            if returns is not None:
                raise FwAssertionError(
                    f"harness: output port {port}[{index}] returns a value and no stub was given; "
                    f"call set_port_return({port!r}, value) or set_port_handler({port!r}, fn)")
            return None

        return record

    def _on_cmd_reg(self, opcode):
        self.registered_opcodes.append(opcode)

    def _on_cmd_response(self, opcode, cmd_seq, response):
        self.cmd_responses.append(CommandResponseRecord(opcode, cmd_seq, CmdResponse(response)))

    def _on_event(self, event_id, time, severity, args):
        bound = self._events_by_id.get(event_id)
        if bound is None:
            raise FwAssertionError(f"harness: {self.component.name} logged unknown event id 0x{event_id:X}")
        values = deserialize_values(bound.decl.arg_types, args)
        self.events.append(EventRecord(bound.decl.name, event_id, time, Severity(severity), tuple(values)))

    def _on_text_event(self, event_id, time, severity, text):
        self.text_events.append(TextEventRecord(event_id, time, Severity(severity), text))

    def _on_tlm(self, channel_id, time, value):
        bound = self._channels_by_id.get(channel_id)
        if bound is None:
            raise FwAssertionError(f"harness: {self.component.name} wrote unknown channel id 0x{channel_id:X}")
        decoded = deserialize_values([bound.decl.type], value)[0]
        self.telemetry.append(TelemetryRecord(bound.decl.name, channel_id, time, decoded))

    def _on_prm_get(self, param_id):
        return self._param_store.get(param_id, (ParamValid.UNINIT, None))

    def _on_prm_set(self, param_id, value):
        bound = self._params_by_id[param_id]
        decoded = deserialize_values([bound.decl.type], value)[0]
        self.saved_params.append((bound.decl.name, param_id, decoded))

    def _on_time_get(self):
        return self.test_time

    # --- stubs -----------------------------------------------------------------------------------

    def set_port_handler(self, port: str, handler: Callable, index: int | None = None) -> None:
        """Let ``handler(*args)`` answer calls out of ``port`` (all indices unless ``index``)."""
        self.component.output_port(port)  # raises with the list of ports if the name is wrong
        self._handlers[(port, index)] = handler

    def set_port_return(self, port: str, value: Any, index: int | None = None) -> None:
        """Make calls out of ``port`` return ``value``."""
        self.set_port_handler(port, lambda *args: value, index)

    # --- driving the component -------------------------------------------------------------------

    def invoke(self, port: str, *args, port_num: int = 0):
        """Call input port ``port`` (index ``port_num``) as a connected component would."""
        entries = self.component.input_port(port).entries
        if not 0 <= port_num < len(entries):
            raise FwAssertionError(f"harness: input port {port} has {len(entries)} index(es); "
                                   f"port_num {port_num} is out of range")
        return entries[port_num](*args)

    def send_command(self, name: str, *args, cmd_seq: int = 0) -> None:
        """Serialize ``args`` for command ``name`` and send it to the component's command port."""
        decl = self.component.spec.command(name)
        data = b"".join(t.serialize(v) for t, v in zip(decl.arg_types, args, strict=True))
        self.send_raw_command(self.component.base_id + decl.opcode, data, cmd_seq=cmd_seq)

    def send_raw_command(self, opcode: int, args: bytes, *, cmd_seq: int = 0) -> None:
        """Send a command as raw F´ bytes (opcode is the global one)."""
        self.invoke("cmdIn", opcode, cmd_seq, bytes(args))

    def dispatch(self) -> bool:
        """Handle one queued message of a queued or active component."""
        return self._queued().dispatch()

    def dispatch_all(self) -> int:
        return self._queued().dispatch_all()

    def _queued(self) -> QueuedComponent:
        if not isinstance(self.component, QueuedComponent):
            raise FwAssertionError(f"harness: {self.component.name} is passive and has no queue to dispatch")
        return self.component

    # --- parameters ------------------------------------------------------------------------------

    def param_set(self, name: str, value: Any, validity: ParamValid = ParamValid.VALID) -> None:
        """Put ``value`` in the harness's parameter store (what the component loads from PrmDb)."""
        bound = self._param(name)
        data = bound.decl.type.serialize(value) if validity == ParamValid.VALID else None
        self._param_store[bound.id] = (ParamValid(validity), data)

    def _param(self, name: str) -> BoundParam[Any]:
        params = self.component.params
        if name not in params:
            self.component.spec.param(name)  # raises with the list of parameters
        return params[name]

    def load_parameters(self) -> None:
        """Have the component load every parameter from the harness's store."""
        self.component.load_parameters()

    def param_send(self, name: str, *, cmd_seq: int = 0) -> None:
        """Send the stored value of ``name`` to the component with its PRM_SET command."""
        bound = self._param(name)
        validity, data = self._param_store.get(bound.id, (ParamValid.UNINIT, None))
        if data is None:
            raise FwAssertionError(f"harness: no value stored for {name}; call param_set({name!r}, value) first")
        self.send_raw_command(self.component.opcode(f"{name.upper()}_PRM_SET"), data, cmd_seq=cmd_seq)

    def param_save(self, name: str, *, cmd_seq: int = 0) -> None:
        """Send the component's PRM_SAVE command for ``name``."""
        self.send_raw_command(self.component.opcode(f"{name.upper()}_PRM_SAVE"), b"", cmd_seq=cmd_seq)

    # --- time ------------------------------------------------------------------------------------

    def set_test_time(self, time: Time) -> None:
        self.test_time = time

    def advance_time(self, seconds: int = 0, useconds: int = 0) -> Time:
        """Move test time forward; return the new time."""
        self.test_time = self.test_time + TimeInterval(seconds, useconds)
        return self.test_time

    # --- histories -------------------------------------------------------------------------------

    def clear_history(self) -> None:
        """Forget everything recorded so far (stubs and stored parameters stay)."""
        for history in (self.port_calls, self.cmd_responses, self.events, self.text_events,
                        self.telemetry, self.registered_opcodes, self.saved_params):
            history.clear()

    def from_port(self, port: str) -> list[PortCall]:
        """Calls out of ``port``, in order."""
        self.component.output_port(port)
        return [c for c in self.port_calls if c.port == port]

    def events_named(self, name: str) -> list[tuple]:
        """Arguments of each emission of event ``name``."""
        self.component.spec.event(name)
        return [e.args for e in self.events if e.name == name]

    def tlm_named(self, name: str) -> list[TelemetryRecord]:
        self.component.spec.channel(name)
        return [t for t in self.telemetry if t.name == name]

    def tlm_values(self, name: str) -> list:
        return [t.value for t in self.tlm_named(name)]

    # --- assertions ------------------------------------------------------------------------------

    def assert_from_port_history_size(self, size: int) -> None:
        if len(self.port_calls) != size:
            raise AssertionError(f"expected {size} output port call(s), got {len(self.port_calls)}:\n"
                                 + _listing(self.port_calls))

    def assert_from_port_size(self, port: str, size: int) -> None:
        calls = self.from_port(port)
        if len(calls) != size:
            raise AssertionError(f"expected {size} call(s) out of {port}, got {len(calls)}; all port calls:\n"
                                 + _listing(self.port_calls))

    def assert_from_port(self, port: str, index: int, *args) -> None:
        calls = self.from_port(port)
        if index >= len(calls) or calls[index].args != tuple(args):
            got = calls[index].args if index < len(calls) else "nothing"
            raise AssertionError(f"{port} call {index}: expected args {tuple(args)}, got {got}; calls:\n"
                                 + _listing(calls))

    def assert_cmd_response_size(self, size: int) -> None:
        if len(self.cmd_responses) != size:
            raise AssertionError(f"expected {size} command response(s), got {len(self.cmd_responses)}:\n"
                                 + _listing(self._named_responses()))

    def assert_cmd_response(self, index: int, command: str | int, response: CmdResponse,
                            cmd_seq: int | None = None) -> None:
        """Response ``index`` is ``response`` to ``command`` (a name or a global opcode)."""
        opcode = self.component.opcode(command) if isinstance(command, str) else command
        rows = self.cmd_responses
        ok = index < len(rows) and rows[index].opcode == opcode and rows[index].response == response \
            and (cmd_seq is None or rows[index].cmd_seq == cmd_seq)
        if not ok:
            raise AssertionError(f"expected response {index} to be {CmdResponse(response).name} for {command} "
                                 f"(opcode 0x{opcode:X}); responses:\n" + _listing(self._named_responses()))

    def _named_responses(self):
        names = {self.component.base_id + c.opcode: c.name for c in self.component.spec.commands}
        return [f"{names.get(r.opcode, hex(r.opcode))} seq {r.cmd_seq}: {r.response.name}"
                for r in self.cmd_responses]

    def assert_events_size(self, size: int) -> None:
        if len(self.events) != size:
            raise AssertionError(f"expected {size} event(s), got {len(self.events)}:\n" + self._event_listing())

    def assert_event_count(self, name: str, size: int) -> None:
        got = self.events_named(name)
        if len(got) != size:
            raise AssertionError(f"expected {size} {name} event(s), got {len(got)}; all events:\n"
                                 + self._event_listing())

    def assert_event(self, name: str, index: int, *args) -> None:
        """Emission ``index`` of event ``name`` carried ``args`` (``pytest.approx`` works)."""
        got = self.events_named(name)
        if index >= len(got) or tuple(got[index]) != tuple(args):
            raise AssertionError(f"expected {name}[{index}] with args {tuple(args)}; all events:\n"
                                 + self._event_listing())

    def assert_no_event(self, name: str) -> None:
        self.assert_event_count(name, 0)

    def _event_listing(self) -> str:
        return _listing(f"{e.time} {e.severity.name} {e.name}{e.args}" for e in self.events)

    def assert_tlm_size(self, size: int) -> None:
        if len(self.telemetry) != size:
            raise AssertionError(f"expected {size} telemetry write(s), got {len(self.telemetry)}:\n"
                                 + self._tlm_listing())

    def assert_tlm_count(self, name: str, size: int) -> None:
        got = self.tlm_named(name)
        if len(got) != size:
            raise AssertionError(f"expected {size} {name} write(s), got {len(got)}; all telemetry:\n"
                                 + self._tlm_listing())

    def assert_tlm(self, name: str, index: int, value: Any) -> None:
        """Write ``index`` of channel ``name`` was ``value`` (``pytest.approx`` works)."""
        got = self.tlm_values(name)
        if index >= len(got) or not (got[index] == value):
            raise AssertionError(f"expected {name}[{index}] == {value!r}; all telemetry:\n" + self._tlm_listing())

    def _tlm_listing(self) -> str:
        return _listing(f"{t.time} {t.name} = {t.value!r}" for t in self.telemetry)

    # --- F´ spellings, with F´'s arguments (TesterBase / GTestBase) -----------------------------

    def setTestTime(self, time: Time) -> None:
        self.set_test_time(time)

    def clearHistory(self) -> None:
        self.clear_history()

    def assertCmdResponse_size(self, size: int) -> None:
        self.assert_cmd_response_size(size)

    def assertCmdResponse(self, index: int, opCode: int, cmdSeq: int,
                          response: CmdResponse) -> None:
        """F´'s ``ASSERT_CMD_RESPONSE(index, opCode, cmdSeq, response)``: ``opCode`` is the global
        opcode (``component.opcode("CMD")``; a command name works too)."""
        self.assert_cmd_response(index, opCode, response, cmd_seq=cmdSeq)

    def assertEvents_size(self, size: int) -> None:
        self.assert_events_size(size)

    def assertTlm_size(self, size: int) -> None:
        self.assert_tlm_size(size)

    def assertFromPortHistory_size(self, size: int) -> None:
        self.assert_from_port_history_size(size)

    def __getattr__(self, attr: str):
        """The per-member F´ names: ``invoke_to_<port>(portNum, args…)``, ``sendCmd_<CMD>(instance,
        cmdSeq, args…)``, ``paramSet_<P>(value, valid)``, ``paramSend_<P>(instance, cmdSeq)``,
        ``paramSave_<P>(instance, cmdSeq)``, ``assertEvents_<E>_size(size)``, ``assertEvents_<E>(index,
        args…)``, ``assertTlm_<C>_size(size)``, ``assertTlm_<C>(index, value)``,
        ``assert_from_<port>_size(size)``. ``instance`` is accepted and ignored, as in F´'s tester."""
        if attr.startswith("__"):
            raise AttributeError(attr)
        for prefix, make in self._FPRIME_PREFIXES:
            if attr.startswith(prefix):
                member = attr[len(prefix):]
                return make(self, member)
        raise AttributeError(f"{type(self).__name__} has no attribute {attr!r}")

    def _sized(self, member: str, names: set, count: Callable, record: Callable | None, kind: str):
        if member in names and record is not None:
            return lambda index, *args: record(member, index, *args)
        if member.endswith("_size") and member[:-5] in names:
            return lambda size: count(member[:-5], size)
        raise AttributeError(f"{self.component.name} has no {kind} {member!r} (known: {', '.join(sorted(names))})")

    _FPRIME_PREFIXES = (
        ("invoke_to_", lambda h, port: lambda portNum, *args: h.invoke(port, *args, port_num=portNum)),
        ("sendCmd_", lambda h, cmd: lambda instance, cmdSeq, *args: h.send_command(cmd, *args, cmd_seq=cmdSeq)),
        ("paramSet_", lambda h, p: lambda value, valid=ParamValid.VALID: h.param_set(p, value, valid)),
        ("paramSend_", lambda h, p: lambda instance=0, cmdSeq=0: h.param_send(p, cmd_seq=cmdSeq)),
        ("paramSave_", lambda h, p: lambda instance=0, cmdSeq=0: h.param_save(p, cmd_seq=cmdSeq)),
        ("assertEvents_", lambda h, e: h._sized(e, {d.name for d in h.component.spec.events}, h.assert_event_count,
                                                h.assert_event, "event")),
        ("assertTlm_", lambda h, c: h._sized(c, {d.name for d in h.component.spec.channels}, h.assert_tlm_count,
                                             h.assert_tlm, "channel")),
        ("assert_from_", lambda h, p: h._sized(p, set(h.component.output_ports), h.assert_from_port_size, None,
                                               "output port")),
    )

    def close(self) -> None:
        """Stop an active component's thread if the test started one."""
        stop = getattr(self.component, "exit", None)
        if stop is not None:
            stop()
