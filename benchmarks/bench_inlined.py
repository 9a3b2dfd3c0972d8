"""What each hand-written-out copy that the code keeps saves, against the function calls it replaces.

    python benchmarks/bench_inlined.py [CASE ...] [--repeat N]

Issue 26: a copy of a function written out on a hot path stays only with a measured speed-up
recorded beside it. Each case times the code as it is ("written out") and the same work done by
calling the functions it copies ("folded": the call chain the copy replaced, built here from the
module's own functions or, where the copy is inside a longer method, from that method's source
with the copied lines replaced by the call), with ``timeit``, the two variants in turn
``--repeat`` times so that both see the same load, keeping the best of each (the machine is
shared; the best is the least disturbed), in ns a call. The comment beside each kept copy quotes
this script's figures and how often the deployments run the code (cProfile call counts). Both
variants give the same floats (the tests that keep the old versions check that); only time is
compared here, and nothing asserts it. docs/performance.md ("Written-out copies") has the table.
"""

from __future__ import annotations

import argparse
import importlib.util
import inspect
import pathlib
import textwrap
import timeit

ROOT = pathlib.Path(__file__).resolve().parents[1]


#: divides every case's loop count (the test suite runs each case once, quickly, to keep them working)
SCALE = 1


def _best(written, folded, number: int, repeat: int, per: int = 1) -> tuple[float, float]:
    """The best time of ``written()`` and of ``folded()`` (ns a call, over ``per`` units of work a
    call), measured in turn, ``repeat`` times each, so that both see the same load."""
    number = max(1, number // SCALE)
    best_w = best_f = float("inf")
    for _ in range(repeat):
        best_w = min(best_w, timeit.timeit(written, number=number))
        best_f = min(best_f, timeit.timeit(folded, number=number))
    return best_w / number / per * 1e9, best_f / number / per * 1e9


def _code(text: str) -> str:
    """``text`` without its comments and blank lines, so that the lines a case replaces are found
    whatever the comments beside them say."""
    lines = ("" if line.lstrip().startswith("#") else line.split("  # ")[0].rstrip() for line in text.splitlines())
    return "".join(line + "\n" for line in lines if line)


def _refold(func, old: str, new: str, namespace: dict):
    """``func`` recompiled from its source with the code lines ``old`` replaced by ``new`` (comments
    ignored; a method stays a plain function taking ``self``); the globals are the module's, so the
    names resolve as in the original."""
    source, old, new = _code(inspect.getsource(func)), _code(old), _code(new)
    if source.count(old) != 1:
        raise SystemExit(f"{func.__qualname__}: the written-out lines to replace are not in its source (changed?)")
    glb = dict(func.__globals__)
    glb.update(namespace)
    lines = textwrap.dedent(source.replace(old, new)).splitlines()
    while lines[0].startswith("@"):  # the port or command decorator: the plain function is wanted
        lines.pop(0)
    exec(compile("\n".join(lines) + "\n", f"<folded {func.__qualname__}>", "exec"), glb)
    return glb[func.__name__]


# --- cases ------------------------------------------------------------------------------------------

def case_wheels_pd_torque(repeat):
    """coursework: WheelsPd.torque (eqs. 25, 14, 26 in one body) vs error_quaternion,
    rate_relative_to_orbit and wheel_torque called in turn (CW-101's _old_torque)."""
    from detumble.control import coursework as cw

    inertia = ((1.67e-3, 1e-5, 0.0), (1e-5, 1.67e-3, 0.0), (0.0, 0.0, 1.5e-3))
    target = (0.1, 0.2, 0.3, 0.927)
    law = cw.WheelsPd(5.0, 9.0, inertia, target, n=1.1e-3, shortest_path=True)
    q, w, h = (0.3, -0.1, 0.2, 0.92), (0.01, -0.02, 0.005), (1e-3, -2e-3, 5e-4)

    def folded():
        q_e = cw.error_quaternion(target, q)
        if q_e[3] >= 0.0:
            q_e = (-q_e[0], -q_e[1], -q_e[2], q_e[3])
        return cw.wheel_torque(5.0, 9.0, inertia, q_e, cw.rate_relative_to_orbit(q, w, 1.1e-3), w, h)

    return _best(lambda: law.torque(q, w, h), folded, 2000, repeat)


def case_limit_wheel_torque(repeat):
    """coursework: limit_wheel_torque written out for three wheels vs its loop."""
    from detumble.control.coursework import _limit_wheel_torque_loop, limit_wheel_torque

    u, h = (0.001, -0.002, 0.0005), (0.01, 0.02, -0.01)
    return _best(lambda: limit_wheel_torque(u, h, 0.004, 0.05), lambda: _limit_wheel_torque_loop(u, h, 0.004, 0.05),
                 5000, repeat)


def case_rk4_step_env(repeat):
    """sim (pure-Python plant): RigidBody.step_env's four RK4 stages written out vs the stage
    derivative as a nested function called four times (tests/detumble/sim/test_attitude.py keeps it)."""
    from detumble.sim.attitude import RigidBody

    spec = importlib.util.spec_from_file_location("_test_attitude", ROOT / "tests/detumble/sim/test_attitude.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    body = RigidBody(((2e-3, 1e-5, 0.0), (1e-5, 2.1e-3, 0.0), (0.0, 0.0, 1.9e-3)), (1e-4, 0.0, -2e-4))
    state = (0.9, 0.1, -0.3, 0.2874, 0.3, -0.2, 0.1)
    args = (0.02, (0.1, -0.05, 0.02), (2e-5, -1e-5, 3e-5), 3.4e-6, (0.6, -0.48, 0.64), (0.0, 0.0, 0.0))
    return _best(lambda: body.step_env(state, *args), lambda: module._stagewise_step_env(body, state, *args),
                 500, repeat)


def _proves_ref(name="proves_ref"):
    from fprime_lite.deploy.deployment import Deployment
    from fprime_lite.deploy.topology_loader import load_topology

    loaded = load_topology(ROOT / f"deployments/{name}/topology.yaml")
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(5.0)
    return loaded


def case_magnetorquer_recommand(repeat):
    """proves_ref: MagnetorquerDriver.start re-commanding the level its coil carries (the detumble
    manager does it for each coil every cycle): the short cut vs the full drive it stands for (``start``
    recompiled with the short cut's test never passing, so that every call takes the drive)."""
    from detumble.drivers.magnetorquer_driver import MagnetorquerDriver

    loaded = _proves_ref()
    driver = next(i.component for i in loaded.topology.instances.values()
                  if isinstance(i.component, MagnetorquerDriver))
    level = driver._coil.level
    driver.start(level)
    assert level == driver.DriveLevel.last
    full_drive = _refold(MagnetorquerDriver.start, """
        if (fault is _FAULT_NONE and self._initialized and val == self._coil.level
                and val == self.DriveLevel.last):
""", """
        if False:
""", {})  # the short cut's test never passes: every call takes the drive
    return _best(lambda: driver.start(level), lambda: full_drive(driver, level), 5000, repeat)


def _channel_case(old: str, new: str, repeat: int, pick):
    from fprime_lite.model.telemetry import BoundChannel

    loaded = _proves_ref()
    channels = [ch for i in loaded.topology.instances.values() for ch in i.component._channels.values()]
    channel, value = pick(channels)
    folded = _refold(BoundChannel._write_general, old, new, {})
    channel.write(value)
    assert channel._store is not None, "the channel is not connected to TlmChan (deferred store)"
    return _best(lambda: channel._write_general(value), lambda: folded(channel, value), 5000, repeat)


def _f64_channel(channels):
    from fprime_lite.model.types import F64

    channel = next(ch for ch in channels if ch.decl.type is F64 and not ch._on_change)
    return channel, 1.25


def case_channel_write_time(repeat):
    """every deployment: a channel write's time stamp, the component's get_time written out vs
    ``self.component.get_time()`` (an F64 channel of proves_ref, TlmChan's table)."""
    return _channel_case("""        if time is None:
            time_call = self._time_calls[0]
            clock = self._clock
            time = (clock._now if time_call is self._clock_now and clock._now_at == clock.current_us
                    else self._time_now(time_call))
""", """        if time is None:
            time = self.component.get_time()
""", repeat, _f64_channel)


def _instance(loaded, cls):
    return next(i.component for i in loaded.topology.instances.values() if isinstance(i.component, cls))


def case_wheel_torque_command(repeat):
    """coursework, adcs_ref: ReactionWheelDriver.torqueSet of a healthy wheel with the plant call and
    the mode change written out vs ``_plant_call`` and ``_set_mode``."""
    from detumble.drivers.reaction_wheel_driver import ReactionWheelDriver

    driver = _instance(_proves_ref("coursework"), ReactionWheelDriver)
    folded = _refold(ReactionWheelDriver.torqueSet, """        try:
            self.spacecraft.set_wheel_torque(self.wheel, torque)
        except Exception as exc:
            self._plant_call_failed(self.spacecraft.set_wheel_torque, (self.wheel, torque), exc)
            return Success.FAILURE
        self.mode = _TORQUE
        self.Mode.write(_TORQUE)
""", """        if not self._plant_call(self.spacecraft.set_wheel_torque, self.wheel, torque):
            return Success.FAILURE
        self._set_mode(_TORQUE)
""", {})
    driver.torqueSet(1e-5)
    return _best(lambda: driver.torqueSet(1e-5), lambda: folded(driver, 1e-5), 5000, repeat)


def case_gyro_read(repeat):
    """adcs_ref, coursework: ImuManager.angularVelocityGet of a healthy gyro with ``_read`` and
    ``_orient`` written out vs called."""
    from detumble.proves.imu_manager import ImuManager

    imu = _instance(_proves_ref("adcs_ref"), ImuManager)
    folded = _refold(ImuManager.angularVelocityGet, """        if self._faults[_GYROSCOPE] == _NO_FAULT:
            try:
                v = self.spacecraft.gyro_sample(False)
            except Exception as exc:
                self.report_fault(f"{_GYROSCOPE.name} read", exc)
                self.Lsm6dsoDeviceNotReady()
                return Result(AngularVelocity(0.0, 0.0, 0.0), Success.FAILURE)
            failed = self.Lsm6dsoDeviceNotReady
            if failed.count:
                failed.clear_throttle()
        else:
            v, _, ok = self._read(_GYROSCOPE, self.spacecraft.gyro_sample, self.Lsm6dsoDeviceNotReady)
            if not ok:
                return Result(AngularVelocity(0.0, 0.0, 0.0), Success.FAILURE)
        o = self.AXIS_ORIENTATION.value
        self.AxisOrientation.write(o)
        if o == _STANDARD:
            value = AngularVelocity(v[0], v[1], v[2])
        else:
            value = AngularVelocity(*_rotated(o, v[0], v[1], v[2]))
""", """        v, _, ok = self._read(_GYROSCOPE, lambda: self.spacecraft.gyro_sample(False),
                              self.Lsm6dsoDeviceNotReady)
        if not ok:
            return Result(AngularVelocity(0.0, 0.0, 0.0), Success.FAILURE)
        value = AngularVelocity(*self._orient(v[0], v[1], v[2]))
""", {})
    imu.angularVelocityGet()
    return _best(lambda: imu.angularVelocityGet(), lambda: folded(imu), 5000, repeat)


CASES = {name[len("case_"):]: fn for name, fn in globals().items() if name.startswith("case_")}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cases", nargs="*", help=f"cases (default all): {', '.join(CASES)}")
    parser.add_argument("--repeat", type=int, default=40,
                        help="timings of each variant, in turn with the other's; the best is kept (default 40)")
    parser.add_argument("--scale", type=int, default=1, help="divide every loop count by this (a quick check)")
    args = parser.parse_args(argv)
    global SCALE
    SCALE = args.scale
    for name in args.cases or CASES:
        written, folded = CASES[name](args.repeat)
        print(f"{name:26s} written out {written:9.1f} ns   folded {folded:9.1f} ns   saves {folded - written:8.1f} ns"
              f" ({(folded - written) / folded:5.1%})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
