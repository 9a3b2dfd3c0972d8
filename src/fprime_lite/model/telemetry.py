"""Telemetry channels: declarations, update policy, time-stamped writes through the tlm port.

Declared as attributes of a component class::

    AngularVelocityMagnitude = Channel(F64, format="{.3f}")
    State = Channel(DetumbleState, update="on change")

and written on an instance as ``self.State.write(value)``. An ``on change`` channel sends its first
write and then only values that differ from the last one written.

Serialised when downlinked: a write whose ``tlmOut`` connects straight to a channel store that
declares :attr:`deferred_tlm_input` (TlmChan's ``TlmRecv``) hands the store the time stamp, the
value and the type's packer instead of the packed bytes; the store packs the latest value when it
downlinks it or when it is read; this is worked out when the write first finds ``tlmOut[0]``
connected to a new target.
Only values that cannot change after the write travel this way: numbers, booleans, enums and
strings as they are; structs whose members are all of those kinds or times, and arrays of numbers,
as a tuple of their member values taken at the write (struct and array values are mutable Python
objects). Other arrays, structs with struct or array members, and
every write to any other receiver (a test harness, a tap, a custom component) are packed at write,
so what such a receiver sees is F´'s ``Fw.Tlm`` call with the value's bytes.

Generated writers (F´ autocodes each component's ``tlmWrite_<channel>``): once a write has found
``tlmOut[0]`` connected to such a store, ``channel.write`` is a function generated for the channel's
kind (its value check, on change or always, snapshot or not) and closed over its bindings, which
assigns the stored entry to the store's table itself instead of calling ``store_tlm_value``. It
checks on every write that the ``tlmOut`` and time-port slots still hold what it was made for and
that the clock has made this instant's Time, and otherwise hands the write to the general path
(``BoundChannel._write_general``), which sees the change and makes a new writer. A snapshot channel
whose members all have one always-valid Python type gets a writer with its member tests written in
(``_snapshot_writer_factory``): the members it tests are the tuple it stores.
"""

from __future__ import annotations

import builtins
import functools
import operator

from typing import TYPE_CHECKING, Any, Generic, Protocol, TypeVar, overload

from fprime_lite.model.errors import DeclarationError, check_member_name, check_units
from fprime_lite.model.events import translate_format
from fprime_lite.model.time import NO_CLOCK_READING, US_PER_S, Time, TimeBase, TimeType
from fprime_lite.model.types import (_F64, ArrayType, BoolType, EnumType, FloatType, FwType, IntType, StringType,
                                     StructType, fw_type)

#: The first µs whose whole seconds no longer fit Fw.Time's U32 seconds.
_TIME_US_END = (0xFFFFFFFF + 1) * US_PER_S

__all__ = ["Channel", "BoundChannel", "BoundSnapshotChannel", "bind_channel"]

V = TypeVar("V")

_UPDATES = ("always", "on change")
_LIMIT_LEVELS = ("yellow", "orange", "red")


class Channel(Generic[V]):
    """Declares a telemetry channel of F´ type ``type_``.

    ``low`` and ``high`` are optional limits, e.g. ``high={"yellow": 10.0, "red": 20.0}``.
    ``name`` gives the channel an F´ name other than its attribute's (F´ lets a channel share its
    name with an event or a parameter; Python attributes cannot). ``units`` (e.g. ``"deg/s"``) is
    documentation for the ground: it heads the channel's column in a run's ``channels_wide.csv``
    (F´'s dictionary has no units field, so it is not in the dictionary). ``wall_clock=True`` marks a
    channel whose value is measured on the wall clock (F´'s ``RgMaxTime``): the one kind of value
    that differs between two runs of the same deployment, scenario and seed.
    """

    type: FwType[V]

    @overload
    def __init__(self, type_: FwType[V], *, id: int | None = ..., update: str = ...,
                 format: str | None = ..., low: dict[str, Any] | None = ..., high: dict[str, Any] | None = ...,
                 name: str | None = ..., wall_clock: bool = ..., units: str | None = ...) -> None: ...

    @overload
    def __init__(self, type_: builtins.type[V], *, id: int | None = ..., update: str = ...,
                 format: str | None = ..., low: dict[str, Any] | None = ..., high: dict[str, Any] | None = ...,
                 name: str | None = ..., wall_clock: bool = ..., units: str | None = ...) -> None: ...

    def __init__(self, type_: Any, *, id: int | None = None, update: str = "always",
                 format: str | None = None, low: dict[str, Any] | None = None, high: dict[str, Any] | None = None,
                 name: str | None = None, wall_clock: bool = False, units: str | None = None) -> None:
        if update not in _UPDATES:
            raise DeclarationError(f"channel update must be 'always' or 'on change', got {update!r}")
        if id is not None and (not isinstance(id, int) or id < 0):
            raise DeclarationError(f"channel id must be a non-negative integer, got {id!r}")
        for side in (low, high):
            for level in side or {}:
                if level not in _LIMIT_LEVELS:
                    raise DeclarationError(f"channel limit level must be one of {_LIMIT_LEVELS}, got {level!r}")
        self._raw_type = type_
        self.requested_id = id
        self.local_id = -1  # assigned when the component class is built
        self.update = update
        self.format = format
        self.low = dict(low or {})
        self.high = dict(high or {})
        self.wall_clock = bool(wall_clock)
        self.fprime_name = check_member_name(name, "channel")
        self.units = check_units(units, "channel")
        self.name = ""
        self.attr = ""
        self.framework = False  # True for the members the framework gives every component

    if TYPE_CHECKING:  # what a checker sees: on an instance the attribute is the BoundChannel
        @overload
        def __get__(self, instance: None, owner: Any) -> Channel[V]: ...
        @overload
        def __get__(self, instance: object, owner: Any) -> BoundChannel[V]: ...
        def __get__(self, instance: object, owner: Any) -> Channel[V] | BoundChannel[V]: ...

    def __set_name__(self, owner: builtins.type, name: str) -> None:
        self.name = name

    def finish(self, owner: str) -> None:
        where = f"{owner}.{self.name}"
        try:
            self.type = fw_type(self._raw_type)
        except DeclarationError as exc:
            raise DeclarationError(f"{where}: {exc}") from None
        if self.format is not None:
            translate_format(self.format, [self.type], where)

    def __repr__(self) -> str:
        t = getattr(self, "type", None)
        return f"Channel {self.name} ({t.name if t is not None else self._raw_type})"


V_contra = TypeVar("V_contra", contravariant=True)


class _Write(Protocol[V_contra]):
    """What ``channel.write`` is: ``write(value, time=None)``."""

    def __call__(self, value: V_contra, time: Time | None = None) -> None: ...


class BoundChannel(Generic[V]):
    """A channel of one component instance."""

    __slots__ = ("component", "decl", "id", "last", "written", "_on_change", "_serialize", "_check", "_port",
                 "_valid_type", "_tlm_targets", "_tlm_calls", "_time_calls", "_deferrable",
                 "_bound_call", "_store", "_members_of", "_min", "_max", "_clock", "_clock_now", "_table_owner",
                 "_quick", "write")

    #: Record ``value`` and send it (time-stamped now, unless ``time`` is given): an instance slot
    #: holding the writer generated for this channel, or :meth:`_write_general`.
    write: _Write[V]

    def __init__(self, component: Any, decl: Channel[V], channel_id: int) -> None:
        self.component = component
        self.decl = decl
        self.id = channel_id
        self.last: V | None = None
        self.written = False
        self._on_change = decl.update == "on change"
        t = decl.type
        # The struct's own pack for plain numbers and enums: the same bytes as ``t.pack``, one call less.
        self._serialize = (t._struct.pack if isinstance(t, (IntType, FloatType))
                           else t.rep._struct.pack if isinstance(t, EnumType) and isinstance(t.rep, IntType)
                           else t.pack)
        self._check = t.check
        self._port = component.output_port("tlmOut")
        # The port slots themselves (exact lists, changed in place on (dis)connection): a write
        # reads them without going through the component's attributes.
        self._tlm_targets = self._port.targets
        self._tlm_calls = self._port.calls
        self._time_calls = component.output_port("timeCaller").calls
        self._clock_now: Any = None  # the time call whose clock _clock is (see _time_now)
        self._clock: Any = NO_CLOCK_READING
        # A value of this exact Python type is valid for the channel without checking (enum
        # members of the channel's enum, and floats for F64), or, for an integer type, an int
        # within [_min, _max] (IntType.check's own first test).
        self._valid_type = (t.cls if isinstance(t, EnumType) else float if t is _F64
                            else int if isinstance(t, IntType) else None)
        self._min, self._max = (t.min, t.max) if isinstance(t, IntType) else (0, -1)
        # Checked values of these types are immutable, so packing them later gives the same bytes.
        self._deferrable = isinstance(t, (IntType, FloatType, BoolType, EnumType, StringType))
        self._bound_call: object = None  # the tlmOut call that _store was worked out for
        self._store = None  # the target's deferred store, or None: send packed bytes
        #: For a mutable value made of immutable parts: what is stored and packed (a tuple of them).
        self._members_of: Any = None
        #: For a snapshot channel whose check is :func:`_quick_check`'s: ``(cls, exact, times_at,
        #: full_check)``, which its generated writer tests in place of calling the check.
        self._quick: tuple | None = None
        self._table_owner: Any = None  # the store whose table the generated writer assigns to
        #: What ``channel.write(value, time=None)`` calls: this general path until a write has found
        #: a store with a table, then the writer generated for this channel (see _specialise).
        self.write = self._write_general

    def _write_general(self, value: V, time: Time | None = None) -> None:
        """Record ``value`` and send it (time-stamped now, unless ``time`` is given): every case,
        and what the generated writer hands over to whenever its bindings no longer hold."""
        valid_type = self._valid_type
        if (type(value) is not valid_type
                or (valid_type is int and not self._min <= value <= self._max)):  # type: ignore[operator]
            value = self._check(value)  # converts, or raises the type's error
        if self._on_change and self.written and value == self.last:
            return
        self.last = value
        self.written = True
        call = self._tlm_calls[0]
        if call is not self._bound_call:  # first write, or tlmOut was (re)connected since
            if self._tlm_targets[0] is None:
                return
            self._bind(call)
        # The component's get_time, written out (see _time_now). Kept (issue 26): 88-109 ns less a
        # write than calling it, 12.5 writes an adcs_ref tick (≈ 77 µs of CPU), 12.3 coursework
        # (≈ 71 µs), 4.7 proves_ref (≈ 32 µs): 1.4-1.7 % of each; `python benchmarks/bench_inlined.py
        # channel_write_time` (3 sittings on the shared 2-core machine, 2026-12-03, each the best of 40).
        if time is None:
            time_call = self._time_calls[0]
            clock = self._clock
            time = (clock._now if time_call is self._clock_now and clock._now_at == clock.current_us
                    else self._time_now(time_call))
        members_of = self._members_of
        stored = value if members_of is None else members_of(value)
        store = self._store
        if store is not None:
            store(self.id, time, stored, self._serialize)
        else:
            call(self.id, time, self._serialize(stored))

    def _time_now(self, time_call: Any) -> Time:
        """The time port's answer now through the component's :meth:`Component._port_time`; also
        keeps the clock it worked out for ``time_call``, which later writes read without the call
        while the port's slot holds that same callable."""
        component = self.component
        time = component._port_time(time_call)
        if (self._clock_now, self._clock) != (component._clock_now, component._clock):
            self._clock_now, self._clock = component._clock_now, component._clock
            self._specialise()
        return time

    def _bind(self, call: object) -> None:
        """Work out how writes reach what ``tlmOut[0]`` now connects to (``call`` is its slot)."""
        self._bound_call = call
        self._store = None
        target = self._tlm_targets[0]
        if self._deferrable and type(target) is tuple:
            port, index = target
            component = port.component
            # Only the store's own input: a slot whose callable was replaced (a tap) gets bytes.
            if getattr(component, "deferred_tlm_input", None) == port.name and call is port.entries[index]:
                self._store = component.store_tlm_value
        self._specialise()

    def _specialise(self) -> None:
        """Point ``write`` at a writer generated for this channel's bindings as they are now, or back
        at :meth:`_write_general` when there is nothing to specialise on.

        The writer (:func:`_writer_factory`) is the general path with every choice made: the value
        check for this type, the on-change test only for an on-change channel, the member snapshot
        only for a snapshot channel, and the store's table assignment written in place of the
        ``store_tlm_value`` call (only for a store that names a ``deferred_tlm_table``: an attribute
        whose dict ``store_tlm_value`` does nothing but assign ``(time, value, pack)`` to; TlmChan
        names none when a subclass overrides ``store_tlm_value``). It holds the ``tlmOut`` slot and
        the time-port slot it was made for, and hands the write to the general path when either slot
        now holds another callable or the clock has not made this instant's Time, so that every
        (dis)connection and every other clock is seen, and the general path makes a new writer.
        """
        owner = getattr(self._store, "__self__", None)
        table = getattr(owner, "deferred_tlm_table", None)
        if (not isinstance(table, str) or not table.isidentifier()
                or getattr(self._store, "__func__", None) is not getattr(type(owner), "store_tlm_value", None)):
            self.write = self._write_general
            self._table_owner = None
            return
        self._table_owner = owner
        valid = self._valid_type
        check_kind = "int" if valid is int else "none" if valid is None else "type"
        quick = self._quick
        if quick is not None and len(quick[1]) <= _QUICK_MEMBERS_MAX:
            make = _snapshot_writer_factory(len(quick[1]), quick[2], self._on_change, table)
        else:
            make = _writer_factory(check_kind, self._on_change, self._members_of is not None, table)
        self.write = make(self, self._write_general, owner, self.id, self._serialize, self._check, valid,
                          self._min, self._max, self._members_of, self._tlm_calls, self._bound_call,
                          self._time_calls, self._clock_now, self._clock, quick)


_WRITER_TEMPLATE = """
def make(channel, general, owner, cid, pack, check, valid, lo, hi, members_of, tlm_calls, bound_call,
         time_calls, clock_now, clock, quick=None):
{unpack}    def write(value, time=None):
        if tlm_calls[0] is not bound_call:
            return general(value, time)
        if time is None:
            if time_calls[0] is not clock_now or clock._now_at != clock.current_us:
                return general(value, time)
            time = clock._now
{check}{on_change}        channel.last = value
        channel.written = True
        owner.{table}[cid] = (time, {stored}, pack)
    return write
"""

_ON_CHANGE = "        if channel.written and value == channel.last:\n            return\n"

_CHECKS = {
    "type": "        if type(value) is not valid:\n            value = check(value)\n",
    "int": "        if type(value) is not int or not lo <= value <= hi:\n            value = check(value)\n",
    "none": "        value = check(value)\n",
}


@functools.lru_cache(maxsize=None)
def _writer_factory(check_kind: str, on_change: bool, snapshot: bool, table: str) -> Any:
    """The factory of channel writers of one kind (F´ autocodes a component's ``tlmWrite_<channel>``;
    this is its Python counterpart, generated once per kind and closed over each channel's bindings):
    ``check_kind`` is ``"type"`` (one exact Python type is valid as it is), ``"int"`` (an int within
    the type's range is) or ``"none"`` (the type's check always runs), as in
    :meth:`BoundChannel._write_general`; ``table`` is the store's ``deferred_tlm_table``."""
    source = _WRITER_TEMPLATE.format(
        unpack="", check=_CHECKS[check_kind],
        on_change=_ON_CHANGE if on_change else "",
        stored="members_of(value)" if snapshot else "value", table=table)
    namespace: dict[str, Any] = {}
    exec(compile(source, f"<channel writer {check_kind}{' on-change' if on_change else ''}"
                         f"{' snapshot' if snapshot else ''}>", "exec"), namespace)
    return namespace["make"]


#: A snapshot writer's check (:func:`_snapshot_writer_factory`): the members tested are those stored.
_SNAPSHOT_CHECK = """        if type(value) is cls:
            members = members_of(value)
            if not ({members_ok}):
                value = full_check(value)
                members = members_of(value)
        else:
            value = full_check(value)
            members = members_of(value)
"""

#: The most members a snapshot writer tests written out (one ``type(...) is`` test each).
_QUICK_MEMBERS_MAX = 16


@functools.lru_cache(maxsize=None)
def _snapshot_writer_factory(size: int, times_at: tuple[int, ...], on_change: bool, table: str) -> Any:
    """The factory of generated writers for a snapshot channel with a quick check (:func:`_quick_check`),
    for ``size`` members with time members at ``times_at``: the ``none snapshot`` writer of
    :func:`_writer_factory` with the check's tests written into it, so that the members taken for the
    test are those stored (one Python call and one member snapshot less a write). The value stored,
    the one kept as ``last`` and every error are those of the check: a ``cls`` whose members have
    exactly the types ``exact`` and whose time members fit (:func:`_times_fit`) as it is, anything
    else through ``full_check``."""
    tests = [f"type(members[{i}]) is e{i}" for i in range(size)]
    if times_at:
        tests.append("_times_fit(members, times_at)")
    source = _WRITER_TEMPLATE.format(
        unpack=("    cls, exact, times_at, full_check = quick\n"
                f"    {', '.join(f'e{i}' for i in range(size))}{',' if size == 1 else ''} = exact\n"),
        check=_SNAPSHOT_CHECK.format(members_ok=" and ".join(tests)),
        on_change=_ON_CHANGE if on_change else "",
        stored="members", table=table)
    namespace: dict[str, Any] = {"_times_fit": _times_fit}
    exec(compile(source, f"<channel writer snapshot {size}{' on-change' if on_change else ''}>", "exec"),
         namespace)
    return namespace["make"]


#: Member types whose checked values are immutable: a struct made only of these can be snapshotted.
_SNAPSHOT_MEMBER_TYPES = (IntType, FloatType, BoolType, EnumType, StringType, TimeType)


def bind_channel(component: Any, decl: Channel[V], channel_id: int) -> BoundChannel[V]:
    """The bound channel of ``decl`` on ``component``: a :class:`BoundSnapshotChannel` for a struct
    of two or more members of immutable kinds or an array of numbers, a :class:`BoundChannel`
    otherwise."""
    t = decl.type
    if (isinstance(t, StructType) and len(t.members) >= 2
            and all(isinstance(mt, _SNAPSHOT_MEMBER_TYPES) for _, mt in t.members)):
        return BoundSnapshotChannel(component, decl, channel_id)
    if isinstance(t, ArrayType) and t._fixed is not None:
        return BoundSnapshotChannel(component, decl, channel_id)
    return BoundChannel(component, decl, channel_id)


class BoundSnapshotChannel(BoundChannel[V]):
    """A channel of a struct whose members are numbers, booleans, enums, strings or times, or of an
    array of numbers: values that are mutable Python objects made of immutable parts.

    A write checks the value (without calling the member checks when every member already has the
    exact Python type that is always valid for it: ``float`` for F64, the enum's class; or, for a
    time member, is a :class:`Time` whose base, context and seconds are plain ints within U16, U8
    and U32, which is what the time's check accepts), and stores or packs the tuple of its member
    values taken at the write; the bytes are those of the type's own ``pack``.
    """

    __slots__ = ()

    def __init__(self, component: Any, decl: Channel[V], channel_id: int) -> None:
        super().__init__(component, decl, channel_id)
        t = decl.type
        self._deferrable = True
        if isinstance(t, StructType):
            self._members_of = operator.attrgetter(*[name for name, _ in t.members])
            member_types = [mt for _, mt in t.members]
        else:
            assert isinstance(t, ArrayType)
            self._members_of = tuple
            member_types = [t.elem] * t.size
        exact = [float if mt is _F64 else mt.cls if isinstance(mt, EnumType) else Time if isinstance(mt, TimeType)
                 else None for mt in member_types]
        # Every write goes through the quick check (_valid_type stays None), which falls back on
        # the type's own; a member type with no always-valid Python type leaves only the latter.
        if None in exact:
            self._check = t.check
        else:
            times_at = tuple(i for i, mt in enumerate(member_types) if isinstance(mt, TimeType))
            exact_types = tuple(e for e in exact if e is not None)
            self._check = _quick_check(t.cls, self._members_of, exact_types, times_at, t.check)
            self._quick = (t.cls, exact_types, times_at, t.check)
        fixed = t._fixed
        if fixed is not None:
            self._serialize = lambda members: fixed.pack(*members)
        else:
            packs = [mt.pack for mt in member_types]
            self._serialize = lambda members: b"".join([p(v) for p, v in zip(packs, members, strict=True)])


def _times_fit(members: tuple, times_at: tuple[int, ...]) -> bool:
    """Whether the time members at ``times_at`` pass TimeType.check's tests as they are: a base,
    context and µs that are plain ints (or a TimeBase) within U16, U8 and U32 seconds."""
    for i in times_at:
        t = members[i]
        base, context, us = t.time_base, t.context, t.total_us
        if not ((type(base) is int or type(base) is TimeBase) and 0 <= base <= 0xFFFF
                and type(context) is int and 0 <= context <= 0xFF
                and type(us) is int and 0 <= us < _TIME_US_END):
            return False
    return True


def _quick_check(cls: type, members_of: Any, exact: tuple[type, ...], times_at: tuple[int, ...],
                 full_check: Any) -> Any:
    """A snapshot channel's check: ``value`` itself when it is a ``cls`` whose members (as
    ``members_of`` gives them) have exactly the types ``exact``, position by position, and whose
    time members fit (:func:`_times_fit`); else what ``full_check(value)`` returns or raises.

    The general path's (:meth:`BoundChannel._write_general`): a channel written into TlmChan's table
    runs the same tests written into its generated writer (:func:`_snapshot_writer_factory`). The
    three- and four-member copy kept here by issue 26 (2.7 checks an adcs_ref tick then) was folded
    back when the tests moved into the writer (issue 32, branch fpart): no tick runs it any more.
    """
    def check(value: Any) -> Any:
        if type(value) is not cls:
            return full_check(value)
        m = members_of(value)
        for member, e in zip(m, exact, strict=True):
            if type(member) is not e:
                return full_check(value)
        return value if _times_fit(m, times_at) else full_check(value)
    return check
