"""Every fault a component contains reaches the ground (decision 0005; issue 26).

The components are *discovered*: every component class instantiated by the reference deployments
(and every component class defined in ``detumble`` and ``fprime_lite.svc``), with the classes
they inherit from. The places that contain a fault are discovered too: each ``except`` clause
catching ``Exception``, ``BaseException`` (or a tuple holding one) or everything, in a method of
one of those classes or a function of their modules, that does not raise again.

Each such place needs an injection recipe below (one recipe per ``except`` of a method: a second
``except`` added to a method needs a second recipe). A recipe injects a fault (``InjectedError``,
by monkeypatching something the handler calls), runs the handler and says what it expects:
the ``HandlerFault`` events (their ``port`` texts; the exception text is the injected one), the
``HandlerFaults`` channel counting them, ``handler_faults``, and — where the component commands an
actuator (an input or output port of an actuator port type) — that the actuators went safe, or
why that recipe's handler commands none. ``EXEMPT`` lists the places that are not handler
faults, each with its reason; a recipe or exemption whose place has gone fails too.
"""
from __future__ import annotations

import ast
import dataclasses
import importlib
import inspect
import pathlib
import pkgutil
import sys
from collections.abc import Callable

import pytest

from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.model.component import Component, QueuedComponent
from fprime_lite.model.time import Time
from fprime_lite.testing import ComponentHarness

REPO = pathlib.Path(__file__).resolve().parents[1]
TOPOLOGIES = ["deployments/proves_ref/topology.yaml", "deployments/proves_ref/topology_bdot_detumble.yaml",
              "deployments/adcs_ref/topology.yaml", "deployments/coursework/topology.yaml"]
PACKAGES = ["detumble", "fprime_lite.svc"]
OPTIONAL_IMPORTS = {"Basilisk"}  # the bsk extra: modules that need it are not flight components
#: Port types that command an actuator (coils, torque rods, wheels), by their name without namespace.
ACTUATOR_PORT_TYPES = {"StartMagnetorquer", "StopMagnetorquer", "DipoleMomentSet", "WheelTorqueSet",
                       "WheelSpeedSet", "WheelEnableSet"}
INJECTED = "InjectedError: injected"

#: Places with a broad ``except`` that are not handler faults: (owner, function) -> why.
EXEMPT = {
    ("Component", "report_fault"): "the report itself: a fault while reporting is logged; report_fault never raises",
}


class InjectedError(Exception):
    """What every recipe raises."""


def _raise(*args, **kwargs):
    raise InjectedError("injected")


# --- discovery ----------------------------------------------------------------------------------

def _deployment_classes() -> dict[type, str]:
    """Each component class of the reference deployments, with the first topology that flies it."""
    classes: dict[type, str] = {}
    for path in TOPOLOGIES:
        for component in load_topology(REPO / path).topology.components():
            classes.setdefault(type(component), path)
    return classes


def _package_classes() -> set[type]:
    classes = set()
    for package in PACKAGES:
        root = importlib.import_module(package)
        for info in pkgutil.walk_packages(root.__path__, package + "."):
            try:
                module = importlib.import_module(info.name)
            except ModuleNotFoundError as exc:
                if (exc.name or "").split(".")[0] in OPTIONAL_IMPORTS:
                    continue
                raise
            for value in vars(module).values():
                if inspect.isclass(value) and issubclass(value, Component) and value.__module__ == module.__name__:
                    classes.add(value)
    return classes


DEPLOYED = _deployment_classes()
CLASSES = set(DEPLOYED) | _package_classes()
BY_NAME = {c.__name__: c for c in CLASSES}


def _is_broad(handler: ast.ExceptHandler) -> bool:
    if handler.type is None:
        return True
    names = handler.type.elts if isinstance(handler.type, ast.Tuple) else [handler.type]
    return any((isinstance(n, ast.Name) and n.id in ("Exception", "BaseException"))
               or (isinstance(n, ast.Attribute) and n.attr in ("Exception", "BaseException")) for n in names)


def _contains(handler: ast.ExceptHandler) -> bool:
    """A broad handler that does not raise again (a ``raise`` among its statements propagates)."""
    return _is_broad(handler) and not any(isinstance(s, ast.Raise) for s in handler.body)


def _sites(classes) -> dict[tuple[str, str], int]:
    """(owner class or ``<module>``, function) -> how many fault-containing ``except`` it has."""
    owners: dict[str, set[str]] = {}
    for cls in classes:
        for base in cls.__mro__:
            if base is not object:
                owners.setdefault(base.__module__, set()).add(base.__name__)
    sites: dict[tuple[str, str], int] = {}
    for module_name, class_names in owners.items():
        tree = ast.parse(inspect.getsource(sys.modules[module_name]))
        for node in tree.body:
            if isinstance(node, ast.ClassDef) and node.name in class_names:
                owner, functions = node.name, node.body
            elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                owner, functions = f"<module {module_name.rsplit('.', 1)[-1]}>", [node]
            else:
                continue
            for fn in functions:
                if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    n = sum(1 for h in ast.walk(fn) if isinstance(h, ast.ExceptHandler) and _contains(h))
                    if n:
                        sites[(owner, fn.name)] = n
    return sites


SITES = _sites(CLASSES)


def _commands_actuators(cls: type) -> bool:
    spec = cls.__fprime_spec__
    ports = list(spec.inputs.values()) + list(spec.outputs.values())
    return any(p.port_type.name.rsplit(".", 1)[-1] in ACTUATOR_PORT_TYPES for p in ports)


# --- recipes ------------------------------------------------------------------------------------

@dataclasses.dataclass
class Expect:
    """What a recipe saw: the harness, the ``port`` of each HandlerFault expected, in order, and
    whether the actuators are safe (None: ``no_actuator`` says why this handler commands none)."""

    h: ComponentHarness
    where: list[str]
    safe: bool | None = None
    no_actuator: str = ""
    #: Reported by the framework's own member-fault report instead (rate groups: member_faults).
    member_fault: bool = False


class Rig:
    """Builds the component under test as a reference deployment builds it, in a harness."""

    def __init__(self, monkeypatch, tmp_path):
        self.monkeypatch = monkeypatch
        self.tmp_path = tmp_path
        self._loaded: list = []

    def harness(self, class_name: str, **kwargs) -> tuple[ComponentHarness, Component]:
        cls = BY_NAME[class_name]
        if cls in DEPLOYED:  # the first instance of a fresh load of its deployment
            loaded = load_topology(REPO / DEPLOYED[cls])
            self._loaded.append(loaded)  # keeps its resources (the spacecraft) alive
            component = next(c for c in loaded.topology.components() if type(c) is cls)
        else:  # a class no reference deployment flies (the ground link): built with its defaults
            component = cls(**kwargs)
        h = ComponentHarness(component)
        for name, decl in type(component).__fprime_spec__.outputs.items():
            success = getattr(decl.port_type.returns, "SUCCESS", None)
            if success is not None:  # actuator commands and the like: they succeed unless a recipe says
                h.set_port_return(name, success)
        if component.params:
            h.load_parameters()
        h.clear_history()
        return h, component

    def patch(self, target, name: str, value=_raise) -> None:
        self.monkeypatch.setattr(target, name, value)


RECIPES: dict[tuple[str, str], list[Callable[[Rig], Expect]]] = {}


def recipe(owner: str, function: str):
    def register(fn):
        RECIPES.setdefault((owner, function), []).append(fn)
        return fn
    return register


def _stops(h) -> set[str]:
    return {c.port for c in h.port_calls if c.port.endswith("Stop")}


def _coils_stopped(h) -> bool:
    """Every coil's stop was called (the harness connects them all)."""
    wanted = {name for name in h.component.output_ports if name.endswith("Stop")}
    return bool(wanted) and _stops(h) == wanted


def _last_per_index(h, port: str) -> dict[int, tuple]:
    return {c.index: c.args for c in h.from_port(port)}


# attitude controller


def _wheels_zero(h, ac) -> bool:
    torques = _last_per_index(h, "wheelTorqueSet")
    return bool(ac.law.wheel_axes) and all(torques.get(i) == (0.0,) for i in range(len(ac.law.wheel_axes)))


@recipe("AttitudeController", "run")
def _attitude_controller_run(rig):
    h, ac = rig.harness("AttitudeController")
    rig.patch(ac.law, "_cycle")
    h.invoke("run", 0)
    return Expect(h, ["run"], safe=_coils_stopped(h) and _wheels_zero(h, ac))


@recipe("AttitudeController", "run")
def _attitude_controller_run_safing(rig):
    """Stopping the coils fails too: reported as the safing's fault, and the wheels are zeroed all the same."""
    h, ac = rig.harness("AttitudeController")
    rig.patch(ac.law, "_cycle")
    rig.patch(ac.law, "_stop_coils")
    h.invoke("run", 0)
    return Expect(h, ["run", "run: safing"], safe=_wheels_zero(h, ac))


@recipe("AttitudeController", "tlmRun")
def _attitude_controller_tlm_run(rig):
    h, ac = rig.harness("AttitudeController")
    rig.patch(ac, "_write_telemetry")
    h.invoke("tlmRun", 0)
    return Expect(h, ["tlmRun"], no_actuator="it writes the cycles' telemetry; the cycles command the actuators")


# the ADCS light sensors


@recipe("ADCS", "run")
def _adcs_run(rig):
    h, adcs = rig.harness("ADCS")
    rig.patch(adcs, "_sense")
    h.invoke("run", 0)
    return Expect(h, ["run"], no_actuator="it reads the light sensors and makes the Sun vector")


@recipe("ADCS", "_sense")
def _adcs_albedo_correction(rig):
    """The albedo correction raises: reported, and the uncorrected Sun vector published all the same."""
    from detumble.components.types import Result, Success
    from fprime_lite.svc.health import FwEnabled

    h, adcs = rig.harness("ADCS")
    for i in range(6):
        h.set_port_handler("visibleLightGet", (lambda i=i: Result(133_000.0 if i == 4 else 0.0, Success.SUCCESS)),
                           index=i)
    h.send_command("SUN_ALBEDO_CORRECTION_PRM_SET", FwEnabled.ENABLED)
    h.clear_history()
    rig.patch(adcs, "_without_albedo")
    h.invoke("run", 0)
    assert [list(v) for v in h.tlm_values("SunVector")] == [[0.0, 0.0, 1.0]]
    return Expect(h, ["albedo correction"], no_actuator="it reads the light sensors and makes the Sun vector")


# detumble manager


@recipe("DetumbleManager", "run")
def _detumble_manager_run(rig):
    h, dm = rig.harness("DetumbleManager")
    rig.patch(dm, "_run")
    h.invoke("run", 0)
    return Expect(h, ["run"], safe=_coils_stopped(h))


@recipe("DetumbleManager", "run")
def _detumble_manager_run_safing(rig):
    h, dm = rig.harness("DetumbleManager")
    rig.patch(dm, "_run")
    rig.patch(dm, "_stop_coils")
    h.invoke("run", 0)
    return Expect(h, ["run", "run: safing"], no_actuator="stopping the coils is what fails: reported as such")


# coursework controller


def _coursework(rig):
    h, cw = rig.harness("CourseworkController")
    law = type(cw.LAW.value)
    h.send_command("SET_LAW", law.CROSS_PRODUCT)
    h.clear_history()
    rig.patch(cw, "_cycle")
    return h, cw


@recipe("CourseworkController", "run")
def _coursework_run(rig):
    h, cw = _coursework(rig)
    h.invoke("run", 0)
    rods = [c.args[0] for c in h.from_port("dipoleSet")]
    torques = _last_per_index(h, "wheelTorqueSet")
    rods_zero = bool(rods) and (rods[-1].x, rods[-1].y, rods[-1].z) == (0.0, 0.0, 0.0)
    wheels_zero = all(torques.get(i) == (0.0,) for i in range(3))
    safe = rods_zero and wheels_zero and len(h.events_named("ControlFault")) == 1
    return Expect(h, ["run"], safe=safe)


@recipe("CourseworkController", "run")
def _coursework_run_safing(rig):
    h, cw = _coursework(rig)
    rig.patch(cw, "_safe")
    h.invoke("run", 0)
    assert not h.events_named("ControlFault")  # it would say "actuators safe"
    return Expect(h, ["run", "run: safing"], no_actuator="making the actuators safe is what fails: reported as such")


# simulated drivers


def _wheel(rig):
    h, drv = rig.harness("ReactionWheelDriver")
    assert h.invoke("torqueSet", 1e-4).name == "SUCCESS"
    h.clear_history()
    return h, drv


def _wheel_safe(drv) -> bool:
    """The plant's motor command of the driver's wheel is zero torque."""
    wheels = drv.spacecraft.plant.wheels
    return wheels.command[drv.wheel] == 0.0 and wheels.mode[drv.wheel] == _plant_torque_mode()


def _plant_torque_mode():
    from detumble.sim import wheels
    return wheels.TORQUE


def _raising(real):
    """Raises InjectedError in place of ``real`` (under its name: drivers name the call that failed)."""
    def call(*args):
        raise InjectedError("injected")
    call.__name__ = real.__name__
    return call


def _raise_unless_zero(real):
    """``real`` for a zero value (switching off), InjectedError for anything else."""
    def call(i, value):
        if value:
            raise InjectedError("injected")
        real(i, value)
    call.__name__ = real.__name__
    return call


@recipe("ReactionWheelDriver", "torqueSet")
def _wheel_torque(rig):
    h, drv = _wheel(rig)
    rig.patch(drv.spacecraft, "set_wheel_torque", _raise_unless_zero(drv.spacecraft.set_wheel_torque))
    assert h.invoke("torqueSet", 2e-4).name == "FAILURE"
    return Expect(h, [f"wheel {drv.wheel} set_wheel_torque"], safe=_wheel_safe(drv))


@recipe("ReactionWheelDriver", "_plant_call")
def _wheel_plant_call(rig):
    h, drv = _wheel(rig)
    rig.patch(drv.spacecraft, "set_wheel_enabled", _raising(drv.spacecraft.set_wheel_enabled))
    assert h.invoke("enableSet", False).name == "FAILURE"
    return Expect(h, [f"wheel {drv.wheel} set_wheel_enabled"], safe=_wheel_safe(drv))


@recipe("ReactionWheelDriver", "_make_safe")
def _wheel_safing(rig):
    h, drv = _wheel(rig)
    rig.patch(drv.spacecraft, "set_wheel_torque", _raising(drv.spacecraft.set_wheel_torque))
    assert h.invoke("torqueSet", 2e-4).name == "FAILURE"
    return Expect(h, [f"wheel {drv.wheel} set_wheel_torque", f"wheel {drv.wheel} safing"],
                  no_actuator="zeroing the torque is what fails: reported as such")


@recipe("ReactionWheelDriver", "wheelStateGet")
def _wheel_read(rig):
    h, drv = _wheel(rig)
    rig.patch(drv.spacecraft, "wheel_sample")
    assert h.invoke("wheelStateGet")[1].name == "FAILURE"
    assert h.events_named("WheelReadFailed")
    return Expect(h, [f"wheel {drv.wheel} read"], no_actuator="a read commands nothing; the reader decides")


@recipe("ReactionWheelDriver", "_read_faulty")
def _wheel_read_with_a_fault_set(rig):
    h, drv = _wheel(rig)
    drv.set_fault(type(drv.fault).READ_NAN)
    h.clear_history()
    rig.patch(drv.spacecraft, "wheel_sample")
    assert h.invoke("wheelStateGet")[1].name == "FAILURE"
    return Expect(h, [f"wheel {drv.wheel} read"], no_actuator="a read commands nothing; the reader decides")


@recipe("MagnetorquerDriver", "_set_coil")
def _coil_drive(rig):
    h, drv = rig.harness("MagnetorquerDriver")
    craft = drv.spacecraft
    assert h.invoke("start", 3).name == "SUCCESS" and craft.coil_level(drv.face) == 3
    h.clear_history()
    rig.patch(craft, "set_coil_level", _raise_unless_zero(craft.set_coil_level))
    assert h.invoke("start", 5).name == "FAILURE"
    return Expect(h, [f"coil {drv.face_name} drive"], safe=craft.coil_level(drv.face) == 0)


def _failed_read(rig, class_name: str, sample: str, port: str, where: str) -> Expect:
    """A sensor whose plant ``sample`` raises: ``port`` answers FAILURE, the fault is reported."""
    h, sensor = rig.harness(class_name)
    rig.patch(sensor.spacecraft, sample)
    assert h.invoke(port)[1].name == "FAILURE"
    return Expect(h, [where])


@recipe("StarTracker", "attitudeGet")
def _star_tracker(rig):
    return _failed_read(rig, "StarTracker", "star_tracker_sample", "attitudeGet", "attitude read")


@recipe("ImuManager", "angularVelocityGet")
def _imu_gyro(rig):
    return _failed_read(rig, "ImuManager", "gyro_sample", "angularVelocityGet", "GYROSCOPE read")


@recipe("ImuManager", "_read")
def _imu_magnetometer(rig):
    return _failed_read(rig, "ImuManager", "magnetometer_sample", "magneticFieldGet", "MAGNETOMETER read")


# framework services


@recipe("CmdDispatcher", "seqCmdBuff")
def _dispatcher(rig):
    from fprime_lite.wire.packets import encode_command
    h, disp = rig.harness("CmdDispatcher")
    h.invoke("compCmdReg", 0x1234, port_num=2)
    h.set_port_handler("compCmdSend", _raise)
    h.invoke("seqCmdBuff", encode_command(0x1234), 0, port_num=0)
    h.dispatch_all()
    assert h.events_named("OpCodeError")
    return Expect(h, ["compCmdSend[2] 0x1234"])


def _downlink(rig):
    h, fd = rig.harness("FileDownlink")
    fd.set_default_root(rig.tmp_path)
    (rig.tmp_path / "a.bin").write_bytes(bytes(300))
    return h, fd


@recipe("FileDownlink", "_send")
def _downlink_send(rig):
    h, fd = _downlink(rig)
    h.set_port_handler("bufferSendOut", _raise)
    h.send_command("SendFile", "a.bin", "a.bin")
    h.dispatch_all()
    h.invoke("Run", 0)
    h.dispatch_all()
    assert h.events_named("SendDataFail")
    return Expect(h, ["bufferSendOut (StartPacket)"])


@recipe("FileDownlink", "_finish_request")
def _downlink_listener(rig):
    h, fd = _downlink(rig)
    h.set_port_handler("FileComplete", _raise)
    h.invoke("sendFile", "missing.bin", "m.bin", 0, 0)
    h.invoke("Run", 0)
    h.dispatch_all()
    return Expect(h, ["FileComplete[0]"])


def _file_manager(rig):
    h, fm = rig.harness("FileManager")
    fm.set_default_root(rig.tmp_path)
    (rig.tmp_path / "d").mkdir()
    return h, fm


def _unresolvable(rig, command: str, *args, allow_shell: bool = False) -> Expect:
    """FileManager ``command`` whose path resolution raises (not an OSError: a fault)."""
    h, fm = _file_manager(rig)
    fm.allow_shell = allow_shell
    rig.patch(fm, "resolve")
    h.send_command(command, *args)
    h.dispatch_all()
    return Expect(h, [command])


@recipe("FileManager", "_fs")
def _file_manager_fs(rig):
    return _unresolvable(rig, "RemoveDirectory", "d")


@recipe("FileManager", "ListDirectory")
def _file_manager_list(rig):
    return _unresolvable(rig, "ListDirectory", "d")


@recipe("FileManager", "CalculateCrc")
def _file_manager_crc(rig):
    return _unresolvable(rig, "CalculateCrc", "d")


@recipe("FileManager", "_system")
def _file_manager_shell(rig):
    return _unresolvable(rig, "ShellCommand", "true", "log.txt", allow_shell=True)


@recipe("FileManager", "_listing_tick")
def _file_manager_list_tick(rig):
    h, fm = _file_manager(rig)
    (rig.tmp_path / "d" / "f").write_bytes(b"x")
    h.send_command("ListDirectory", "d")
    h.dispatch_all()
    rig.patch(fm, "_list_entry")
    h.invoke("schedIn", 0)
    h.dispatch_all()
    return Expect(h, ["ListDirectory tick"])


@recipe("FileUplink", "bufferSendIn")
def _uplink(rig):
    h, fu = rig.harness("FileUplink")
    rig.patch(fu, "_receive")
    h.invoke("bufferSendIn", b"\x00")
    h.dispatch_all()
    return Expect(h, ["bufferSendIn"])


@recipe("FileUplink", "bufferSendIn")
def _uplink_reset(rig):
    h, fu = rig.harness("FileUplink")
    rig.patch(fu, "_receive")
    rig.patch(fu, "_go_to_start_mode")
    h.invoke("bufferSendIn", b"\x00")
    h.dispatch_all()
    return Expect(h, ["bufferSendIn", "bufferSendIn: reset"])


@recipe("GroundLink", "_socket_task")
def _ground_link(rig):
    h, link = rig.harness("GroundLink")

    class Sock:
        def close(self):
            pass

    def serve(sock):
        link._stop.set()
        raise InjectedError("injected")

    rig.patch(sys.modules[type(link).__module__].socket, "create_connection", lambda *a, **k: Sock())
    rig.patch(link, "_serve", serve)
    try:
        link._socket_task()  # on this thread: it stops after the fault
        h.invoke("schedIn", 0)
    finally:
        link.close()
    assert h.events_named("LinkDisconnected")
    return Expect(h, ["socket task"])


class _BrokenStream:
    def write(self, text):
        raise InjectedError("injected")

    def flush(self):
        pass


@recipe("TextLogger", "TextLogger")
def _text_logger(rig):
    h, tl = rig.harness("TextLogger")
    tl.stream = _BrokenStream()
    h.invoke("TextLogger", 1, Time(), 2, "text")
    return Expect(h, ["TextLogger"])


class _Unpackable:
    def __bytes__(self):
        raise InjectedError("injected")


@recipe("TlmChan", "TlmRecv")
def _tlm_recv(rig):
    h, tc = rig.harness("TlmChan")
    h.invoke("TlmRecv", 0x77, Time(), _Unpackable())
    assert tc.rejected_writes == 1
    return Expect(h, ["TlmRecv"])


class _UnserializableStamp:
    """A stand-in for the module's TIME whose serialization fails."""

    size = 11
    serialize = staticmethod(_raise)


def _run_with_unserializable_time(rig, h, component) -> None:
    """One ``Run`` tick of ``component`` (a telemetry store) with its time stamps failing to serialize."""
    rig.patch(sys.modules[type(component).__module__], "TIME", _UnserializableStamp())
    h.invoke("Run", 0)
    h.dispatch_all()


@recipe("TlmChan", "Run")
def _tlm_run(rig):
    h, tc = rig.harness("TlmChan")
    h.invoke("TlmRecv", 0x77, Time(), b"\x00")
    _run_with_unserializable_time(rig, h, tc)
    return Expect(h, ["Run: channel 0x77"])


@recipe("TlmPacketizer", "Run")
def _tlm_packetizer_run(rig):
    """A packet whose time stamp cannot be serialized is reported and not sent."""
    from fprime_lite.svc.tlm_packetizer import PacketSpec
    h, tp = rig.harness("TlmPacketizer")
    tp.set_packet_list([PacketSpec("A", 5, 0, ((0x10, 1),))], omitted=[], start_level=0)
    h.invoke("TlmRecv", 0x10, Time(), b"\x01")
    h.dispatch_all()
    _run_with_unserializable_time(rig, h, tp)
    assert not h.from_port("PktSend") and tp.packets_sent == 0
    return Expect(h, ["Run"], no_actuator="it downlinks telemetry packets")


# the framework's own containment (model/component.py, rate groups)


@recipe("Component", "_run_command")
def _command_handler(rig):
    h, st = rig.harness("StarTracker")
    rig.patch(st, "set_fault")
    h.send_command("SIM_SET_FAULT", type(st.fault).FAIL)
    assert h.cmd_responses[-1].response.name == "EXECUTION_ERROR"
    return Expect(h, ["SIM_SET_FAULT"])


def _pinged_uplink(rig):
    h, fu = rig.harness("FileUplink")
    h.set_port_handler("pingOut", _raise)
    return h, fu


@recipe("QueuedComponent", "dispatch_all")
def _queued_message(rig):
    h, fu = _pinged_uplink(rig)
    h.invoke("pingIn", 7)
    fu.dispatch_all(contain_faults=True)
    return Expect(h, ["pingIn"])


@recipe("ActiveComponent", "_thread_loop")
def _component_thread(rig):
    h, fu = _pinged_uplink(rig)
    fu.start()
    try:
        h.invoke("pingIn", 7)
    finally:
        fu.exit()
    return Expect(h, ["pingIn"])


@recipe("QueuedComponent", "_make_enqueuer")
def _cycle_run_at_once(rig):
    h, rg = rig.harness("ActiveRateGroup")
    assert isinstance(rg, QueuedComponent)
    rg.drained_by_scheduler = True  # what a deployment's scheduler sets: an idle group runs at once
    rig.patch(rg, "_cycle")
    h.invoke("CycleIn", Time())
    return Expect(h, ["CycleIn"])


@recipe("RateGroupBase", "_cycle")
def _rate_group_member(rig):
    h, rg = rig.harness("ActiveRateGroup")
    h.set_port_handler("RateGroupMemberOut", _raise, 0)
    h.invoke("CycleIn", Time())
    h.dispatch_all()
    return Expect(h, [], member_fault=True)


# --- the tests ----------------------------------------------------------------------------------

def test_the_walk_finds_the_components_and_their_contained_faults():
    """The discovery itself: the deployments' classes are found, and known places are seen."""
    names = {c.__name__ for c in DEPLOYED}
    assert {"AttitudeController", "DetumbleManager", "CourseworkController", "BDotDetumble",
            "ReactionWheelDriver", "StarTracker", "MagnetorquerDriver", "CmdDispatcher", "TlmChan"} <= names
    assert SITES[("AttitudeController", "run")] == 2
    assert ("ReactionWheelDriver", "wheelStateGet") in SITES
    assert all(_commands_actuators(BY_NAME[n]) for n in ("AttitudeController", "DetumbleManager",
                                                         "CourseworkController", "MagnetorquerDriver",
                                                         "ReactionWheelDriver", "TorqueRodDriver"))
    assert not _commands_actuators(BY_NAME["StarTracker"])


def test_every_place_that_contains_a_fault_has_a_recipe_for_each_except():
    missing = [f"{owner}.{fn}: {n} broad except(s), {len(RECIPES.get((owner, fn), []))} recipe(s)"
               for (owner, fn), n in sorted(SITES.items())
               if (owner, fn) not in EXEMPT and len(RECIPES.get((owner, fn), [])) < n]
    assert not missing, "add an injection recipe to tests/test_contained_faults.py for:\n" + "\n".join(missing)
    stale = sorted(set(RECIPES) - set(SITES)) + sorted(set(EXEMPT) - set(SITES))
    assert not stale, f"recipes or exemptions for places that no longer contain a fault: {stale}"


@pytest.mark.parametrize("key, index", [(key, i) for key, fns in sorted(RECIPES.items()) for i in range(len(fns))],
                         ids=lambda v: ".".join(v) if isinstance(v, tuple) else str(v))
def test_an_injected_fault_reaches_the_ground(key, index, monkeypatch, tmp_path):
    rig = Rig(monkeypatch, tmp_path)
    expect = RECIPES[key][index](rig)
    h = expect.h
    component = h.component
    if expect.member_fault:  # the framework's rate-group report, counted in member_faults instead
        assert [e[1] for e in h.events_named("RateGroupMemberFault")] == [INJECTED]
        assert h.tlm_values("RgMemberFaults") == [1]
        assert component.handler_faults == 0 and not h.events_named("HandlerFault")
        return
    faults = h.events_named("HandlerFault")
    assert [port for port, _ in faults] == expect.where, f"HandlerFault events: {faults}"
    assert all(text == INJECTED for _, text in faults), f"HandlerFault events: {faults}"
    assert h.tlm_values("HandlerFaults") == list(range(1, len(expect.where) + 1))
    assert component.handler_faults == len(expect.where)
    if _commands_actuators(type(component)):
        assert expect.safe is not None or expect.no_actuator, \
            f"{type(component).__name__} commands actuators: the recipe must check that they went safe"
        if expect.safe is not None:
            assert expect.safe, f"{type(component).__name__}: the actuators did not go safe after the fault"


def test_in_flight_the_faults_reach_the_ground_recorders(tmp_path):
    """The same path end to end: the ADCS reference deployment flies 2 s with its star tracker's
    and its wheels' plant reads raising; the ground's events.log, channels.csv and summary.json see
    every fault."""
    from fprime_lite.tools.runner import run_deployment
    loaded = load_topology(REPO / "deployments/adcs_ref/topology.yaml")
    by_name = {c.name: c for c in loaded.topology.components()}
    tracker, wheel = by_name["starTracker"], by_name["reactionWheel0"]
    tracker.spacecraft.star_tracker_sample = _raise
    wheel.spacecraft.wheel_sample = _raise
    summary = run_deployment(loaded, tmp_path, duration_s=2.0, plots=False, quiet=True)
    assert summary["handler_faults"] == sum(c.handler_faults for c in by_name.values())  # every wheel: one plant
    assert tracker.handler_faults > 0 and wheel.handler_faults > 0
    assert any("handler fault" in p for p in summary["problems"])
    events = (tmp_path / "events.log").read_text()
    assert f"starTracker.HandlerFault WARNING_HI Handler attitude read raised {INJECTED}" in events
    assert f"reactionWheel0.HandlerFault WARNING_HI Handler wheel 0 read raised {INJECTED}" in events
    channels = (tmp_path / "channels.csv").read_text()
    assert ".starTracker.HandlerFaults," in channels and ".reactionWheel0.HandlerFaults," in channels
