"""FPP state machines that run: a component's ``state machine instance`` flown as F´ flies it.

An FPP state machine (``state machine M { signal … action … guard … initial … state … choice … }``)
is compiled from F´'s own analysis (fpp-python's flattened transition maps: a transition's action
list already holds the exit actions of the states it leaves and the entry actions of the states it
passes through on the way down, as F´'s C++ generator flattens it) into plain tables, and each
instance runs them. What a component gets, with F´'s generated names (``inst`` an instance of
state machine ``Components.M``):

- ``inst_sendSignal_s(value)`` (``value`` only for a typed signal): puts the signal on the
  component's queue with the instance's priority and queue-full behaviour; the state machine
  handles it when the queue is dispatched, as F´'s ``sendSignal`` does.
- ``inst_getState()``: the current leaf state, a member of the ``State`` enum F´ generates
  (``__FPRIME_UNINITIALIZED``, then ``OUTER_INNER`` names of the leaf states).
- The Python class supplies ``Components_M_action_a(self, smId, signal[, value])`` for each action
  and ``Components_M_guard_g(self, smId, signal[, value]) -> bool`` for each guard (the value
  argument only when the action or guard is typed), as a ``.cpp`` supplies them.
- The initial transition runs when the component is constructed (F´ runs it in ``init``); its
  actions receive the signal ``__FPRIME_AC_INITIAL_TRANSITION``.

Semantics (FPP's): a signal is looked up for the current leaf state (a transition of an enclosing
state applies when the leaf has none); with a guard that answers false, or no transition, nothing
happens. An external transition runs its flattened actions and enters its target: a state's entry
actions, then its initial transition when it has substates; a choice evaluates its guard and takes
its ``if`` or ``else`` transition. An internal transition (``on s do { … }``) runs its actions only.
"""

from __future__ import annotations

import enum
import inspect
from typing import Any, Callable

from fprime_lite.model.errors import DeclarationError

__all__ = ["StateMachineDef", "StateMachineRunner", "compile_state_machine", "state_machine_members",
           "INITIAL_SIGNAL"]

INITIAL_SIGNAL = "__FPRIME_AC_INITIAL_TRANSITION"

#: a target: ("state", key) or ("choice", key); keys are FPP definition node ids
Target = tuple[str, int]
#: (action names, target or None for an internal transition)
Step = tuple[tuple[str, ...], "Target | None"]


class StateMachineDef:
    """One FPP state machine, compiled: its signals, actions and guards (name -> typed?), its
    states and choices, and the flattened transitions."""

    def __init__(self, name: str, where: str):
        #: the qualified name (``Components.Lamp``); F´'s function prefix is it with ``_`` for ``.``
        self.name = name
        self.prefix = name.replace(".", "_")
        self.where = where
        self.signals: dict[str, bool] = {}
        self.actions: dict[str, tuple[bool, str]] = {}   # name -> (typed, FPP file:line)
        self.guards: dict[str, tuple[bool, str]] = {}
        self.state_enum: Any = None   # F´'s State enum (an IntEnum), set by compile_state_machine
        self.signal_enum: Any = None  # F´'s Signal enum: the initial transition's, then the signals
        self.initial: Step = ((), None)
        #: state key -> (State enum member or None for a state with substates, entry actions, initial step or None)
        self.states: dict[int, tuple[Any, tuple[str, ...], Step | None]] = {}
        #: choice key -> (guard name, if step, else step)
        self.choices: dict[int, tuple[str, Step, Step]] = {}
        #: signal name -> leaf state key -> (guard name or None, step)
        self.transitions: dict[str, dict[int, tuple[str | None, Step]]] = {}

    def action_method(self, action: str) -> str:
        return f"{self.prefix}_action_{action}"

    def guard_method(self, guard: str) -> str:
        return f"{self.prefix}_guard_{guard}"


def compile_state_machine(sm: Any, analysis: Any, where: Callable[[Any], str]) -> StateMachineDef:
    """A :class:`StateMachineDef` of fpp-python's internal state machine ``sm``; raise
    :class:`DeclarationError` for an external one (its behaviour is C++ F´ does not generate)."""
    name = analysis.get_qualified_name(sm.symbol)
    if "External" in str(sm.kind):
        raise DeclarationError(f"{where(sm.node)}: state machine {name} is external (no states in FPP): "
                               f"fprime-lite runs state machines defined in FPP — give it its states, signals, "
                               f"actions and guards")
    sma = sm.sma
    out = StateMachineDef(name, where(sm.node))
    for signal in sm.signals:
        out.signals[signal.unqualified_name] = signal.definition.type_name is not None
    for action in sm.actions:
        out.actions[action.unqualified_name] = (action.definition.type_name is not None, where(action.definition))
    for guard in sm.guards:
        out.guards[guard.unqualified_name] = (guard.definition.type_name is not None, where(guard.definition))
    out.signal_enum = enum.IntEnum("Signal", [INITIAL_SIGNAL, *out.signals], start=0)  # type: ignore[misc]
    state_enum_node = next(m for m in sm.node.members if type(m).__name__ == "DefEnum" and m.name == "State")
    out.state_enum = enum.IntEnum("State", {c.name: int(c.resolved_value.value[1])  # type: ignore[misc]
                                            for c in state_enum_node.constants})

    def target(symbol: Any) -> Target:
        kind = "choice" if type(symbol).__name__ == "Choice" else "state"
        return (kind, symbol.definition.node_id)

    def actions_of(do: Any) -> tuple[str, ...]:
        return tuple(sma.get_action_symbol(a).unqualified_name for a in do.actions) if do is not None else ()

    def step_of(expr: Any) -> Step:  # an initial transition's: its target is a member of the state
        return (actions_of(expr.actions), target(sma.use_def_map[expr.target.node_id]))

    def flattened(transition: Any) -> Step:
        acts = tuple(a.unqualified_name for a in transition.actions)
        soc = transition.target_opt
        return (acts, target(soc.symbol) if soc is not None else None)

    def walk(members: Any, path: str) -> None:
        for member in members:
            kind = type(member).__name__
            if kind == "DefState":
                entry: tuple[str, ...] = ()
                initial = None
                for inner in member.members:
                    inner_kind = type(inner).__name__
                    if inner_kind == "SpecStateEntry":
                        entry += actions_of(inner.actions)
                    elif inner_kind == "SpecInitialTransition":
                        initial = step_of(inner.transition)
                leaf = None
                if initial is None:
                    leaf = out.state_enum[path + member.name]  # F´'s State enum: OUTER_INNER
                out.states[member.node_id] = (leaf, entry, initial)
                walk(member.members, f"{path}{member.name}_")
            elif kind == "DefChoice":
                guard = sma.get_guard_symbol(member.guard).unqualified_name
                out.choices[member.node_id] = (
                    guard, flattened(sma.flattened_choice_transition_map[member.if_transition.node_id]),
                    flattened(sma.flattened_choice_transition_map[member.else_transition.node_id]))
            elif kind == "SpecInitialTransition" and not path:  # the machine's own
                out.initial = step_of(member.transition)

    walk(sm.node.members, "")
    for signal, by_state in sma.flattened_state_transition_map.items():
        table = out.transitions.setdefault(signal.unqualified_name, {})
        for state, guarded in by_state.items():
            guard = guarded.guard_opt.unqualified_name if guarded.guard_opt is not None else None
            table[state.definition.node_id] = (guard, flattened(guarded.transition))
    return out


class StateMachineRunner:
    """One state machine instance of one component: its current state and its signal handling.
    Actions and guards are the component's methods, looked up once."""

    __slots__ = ("definition", "sm_id", "state_key", "_actions", "_typed_actions", "_guards", "_typed_guards")

    def __init__(self, definition: StateMachineDef, component: Any, sm_id: Any):
        self.definition = definition
        self.sm_id = sm_id
        self.state_key: int | None = None
        self._actions = {a: getattr(component, definition.action_method(a)) for a in definition.actions}
        self._typed_actions = {a for a, (typed, _) in definition.actions.items() if typed}
        self._guards = {g: getattr(component, definition.guard_method(g)) for g in definition.guards}
        self._typed_guards = {g for g, (typed, _) in definition.guards.items() if typed}

    def state(self) -> Any:
        """The current leaf state (``State.__FPRIME_UNINITIALIZED`` before the initial transition)."""
        if self.state_key is None:
            return self.definition.state_enum(0)
        return self.definition.states[self.state_key][0]

    def initialize(self) -> None:
        """Run the initial transition (F´: the component's ``init``)."""
        signal = self.definition.signal_enum[INITIAL_SIGNAL]
        self._step(self.definition.initial, signal, None)

    def signal(self, name: str, value: Any = None) -> None:
        """Handle signal ``name`` now (what the queued message does when dispatched)."""
        definition = self.definition
        signal = definition.signal_enum[name]
        entry = definition.transitions.get(name, {}).get(self.state_key)  # type: ignore[arg-type]
        if entry is None:
            return
        guard, step = entry
        if guard is not None and not self._guard(guard, signal, value):
            return
        self._step(step, signal, value)

    def _guard(self, name: str, signal: Any, value: Any) -> bool:
        fn = self._guards[name]
        answer = fn(self.sm_id, signal, value) if name in self._typed_guards else fn(self.sm_id, signal)
        if not isinstance(answer, bool):
            raise TypeError(f"guard {self.definition.guard_method(name)} returned {answer!r}; return a bool")
        return answer

    def _run(self, actions: tuple[str, ...], signal: Any, value: Any) -> None:
        for name in actions:
            fn = self._actions[name]
            if name in self._typed_actions:
                fn(self.sm_id, signal, value)
            else:
                fn(self.sm_id, signal)

    def _step(self, step: Step, signal: Any, value: Any) -> None:
        actions, target = step
        self._run(actions, signal, value)
        while target is not None:
            kind, key = target
            if kind == "choice":
                guard, if_step, else_step = self.definition.choices[key]
                actions, target = if_step if self._guard(guard, signal, value) else else_step
                self._run(actions, signal, value)
                continue
            leaf, entry, initial = self.definition.states[key]
            self._run(entry, signal, value)
            if initial is None:
                self.state_key = key
                return
            actions, target = initial
            self._run(actions, signal, value)


def state_machine_members(cls: type, instances: list[tuple[str, StateMachineDef, int, str, str]],
                          where: Callable[[str], str]) -> dict[str, Any]:
    """The class-body members a component gets for its state machine instances
    ``(instance name, definition, priority, queue full, FPP file:line)``: ``SmId``, each instance's
    ``NAME_sendSignal_SIGNAL`` and ``NAME_getState``, and an ``__init__`` that makes the runners and
    runs the initial transitions. Raise :class:`DeclarationError` for a missing or ill-fitting
    action or guard method, or a ``hook`` queue-full without ``stateMachineOverflowHook``."""
    problems = []
    for definition in {d.name: d for _, d, _, _, _ in instances}.values():
        for kind, table, method in (("action", definition.actions, definition.action_method),
                                    ("guard", definition.guards, definition.guard_method)):
            for name, (typed, loc) in table.items():
                fn = getattr(cls, method(name), None)
                wanted = 3 if typed else 2
                args = "smId, signal, value" if typed else "smId, signal"
                if not inspect.isfunction(fn):
                    problems.append(f"{loc}: {kind} {name} of state machine {definition.name} has no method: give "
                                    f"{cls.__qualname__} a method {method(name)}(self, {args})")
                    continue
                params = list(inspect.signature(fn).parameters.values())[1:]
                if len(params) != wanted or any(p.kind not in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)
                                                for p in params):
                    problems.append(f"{loc}: {kind} {name} of state machine {definition.name}: "
                                    f"{cls.__qualname__}.{method(name)} takes ({', '.join(p.name for p in params)}); "
                                    f"it must take ({args})")
    if any(full == "hook" for _, _, _, full, _ in instances) and not inspect.isfunction(
            getattr(cls, "stateMachineOverflowHook", None)):
        loc = next(at for _, _, _, full, at in instances if full == "hook")
        problems.append(f"{loc}: a state machine instance's queue full is hook: give {cls.__qualname__} a method "
                        f"stateMachineOverflowHook(self, smId, signal, value)")
    if problems:
        raise DeclarationError("\n".join(problems))
    sm_id = enum.IntEnum("SmId", [name for name, *_ in instances], start=0)  # type: ignore[misc]
    body: dict[str, Any] = {"SmId": sm_id}
    user_init: Any = getattr(cls, "__init__")  # noqa: B009 - mypy refuses cls.__init__ on a type

    def init(self: Any, *args: Any, **kwargs: Any) -> None:
        user_init(self, *args, **kwargs)
        self._state_machines = {name: StateMachineRunner(d, self, sm_id[name]) for name, d, *_ in instances}
        for runner in self._state_machines.values():
            runner.initialize()

    body["__init__"] = init
    for name, definition, priority, queue_full, _ in instances:
        body[f"{name}_getState"] = _get_state(name)
        for signal, typed in definition.signals.items():
            body[f"{name}_sendSignal_{signal}"] = _send_signal(name, signal, typed, priority, queue_full, sm_id[name])
    return body


def _get_state(instance: str) -> Callable[[Any], Any]:
    def get_state(self: Any) -> Any:
        return self._state_machines[instance].state()
    get_state.__name__ = f"{instance}_getState"
    return get_state


def _send_signal(instance: str, signal: str, typed: bool, priority: int, queue_full: str,
                 sm_id: Any) -> Callable[..., None]:
    port = f"{instance}.{signal}"

    def put(self: Any, value: Any) -> None:
        runner = self._state_machines[instance]

        def handle(value: Any) -> None:  # named so that a faulting action is reported by signal
            runner.signal(signal, value)

        handle.__name__ = port

        def overflow(*_: Any) -> None:
            self.stateMachineOverflowHook(sm_id, runner.definition.signal_enum[signal], value)

        self._queue.put(priority, handle, (value,), queue_full=queue_full,
                        port=f"{self.name}.{port}", overflow=overflow, run_inline=self.dispatch,
                        threaded=self._thread is not None)

    if typed:
        def send(self: Any, value: Any) -> None:
            put(self, value)
    else:
        def send(self: Any) -> None:  # type: ignore[misc]
            put(self, None)
    send.__name__ = f"{instance}_sendSignal_{signal}"
    return send
