"""The compiled plant kernel: which plant implementation runs, and building the compiled one.

The pure-Python plant (:mod:`.attitude`, :mod:`.wheels`, :mod:`.orbit`, :mod:`.field`) is the
reference. :class:`~.plant.Plant` hands its RK4 step - the rigid body's, or the coupled body +
reaction-wheel step of :func:`.wheels.step_with_wheels` (frictionless or with bearing friction) -
and, on a circular orbit with the centred dipole or the orbit-constant field, its environment
update to ``plant_kernel.c``, a small CPython extension that repeats the reference's arithmetic
operation for operation and gives the same floats, bit for bit
(docs/decisions/0007-compiled-plant-kernel.md). The wheels' commands and limits
(:meth:`.wheels.WheelAssembly.motor_torques`) stay in Python.

Which one runs is chosen per plant (``Plant(..., implementation=...)``) or by the environment
variable ``FPRIME_LITE_PLANT``:

* ``auto`` (default): the compiled kernel when it can be had, else the pure-Python plant, with a
  note on the ``detumble.sim.plant_kernel`` logger (level INFO) saying why;
* ``python``: always the pure-Python reference;
* ``compiled``: the compiled kernel or an error (:class:`KernelUnavailableError`) saying why not.

The kernel is compiled at its first use on a machine with the C compiler Python was built with
(``sysconfig``'s ``LDSHARED``, or ``$CC``) and Python's headers, into a cache folder
(``$FPRIME_LITE_CACHE``, else ``$XDG_CACHE_HOME/fprime-lite``, else ``~/.cache/fprime-lite``),
once per source, Python version and platform (about 0.3 s). Before a process uses it, the loaded
kernel must reproduce the reference's floats exactly on a check trajectory; otherwise the pure-Python
plant is used. A passed check leaves a stamp beside the kernel file, named by everything the check's
outcome depends on (the kernel file, the reference's sources, this interpreter, the libm it maps and the
CPU): later processes in that same configuration skip the check (25-90 ms a process). Nothing here
is needed for correctness: without a compiler everything runs, slower.
"""

from __future__ import annotations

import hashlib
import importlib.machinery
import importlib.util
import logging
import math
import os
import shlex
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import time
from dataclasses import dataclass
from importlib import resources
from types import ModuleType

from detumble.errors import DetumbleError

ENV_VAR = "FPRIME_LITE_PLANT"
CACHE_ENV_VAR = "FPRIME_LITE_CACHE"
IMPLEMENTATIONS = ("auto", "python", "compiled")
#: IEEE arithmetic as the interpreter does it: no fused multiply-adds, no sin+cos merged into sincos
#: (and ``pow(x, 2.0)`` kept a libm call, as ``x ** 2`` is, rather than folded into ``x * x``)
COMPILE_FLAGS = ("-O2", "-fPIC", "-ffp-contract=off", "-fno-fast-math", "-fno-builtin-sin", "-fno-builtin-cos",
                 "-fno-builtin-pow")
_SOURCE = "plant_kernel.c"
_MODULE = "detumble.sim._plant_kernel"
_BUILD_TIMEOUT_S = 120.0

log = logging.getLogger(__name__)


class KernelUnavailableError(DetumbleError, RuntimeError):
    """``FPRIME_LITE_PLANT=compiled`` (or ``implementation="compiled"``) and the kernel cannot be had."""


class _NoToolchainError(DetumbleError, OSError):
    """No C compiler or no Python headers on this machine."""


@dataclass(frozen=True)
class KernelStatus:
    """What :func:`load` found: the module (or None) and, without it, why."""

    module: ModuleType | None
    reason: str  # "" when the module loaded and passed its check
    path: str | None = None
    build_seconds: float | None = None  # set when this process compiled it
    #: "ok", "no toolchain" (no compiler or headers), "build failed", "import failed" or "refused"
    #: (built and loaded, but its floats differ from the reference's)
    outcome: str = "ok"
    #: with a module: "now" (the load-time check ran in this process) or "stamp" (a stamp said it passed
    #: in this configuration: :func:`check_key`)
    checked: str | None = None


_status: KernelStatus | None = None


def requested(implementation: str | None = None) -> str:
    """The implementation asked for: ``implementation``, else ``$FPRIME_LITE_PLANT``, else ``auto``."""
    source = "implementation"
    if implementation is None:
        implementation = os.environ.get(ENV_VAR, "").strip().lower() or "auto"
        source = ENV_VAR
    if implementation not in IMPLEMENTATIONS:
        raise ValueError(f"{source} must be one of {', '.join(IMPLEMENTATIONS)}, got {implementation!r} "
                         f"(python: the pure-Python reference plant; compiled: the C kernel; auto: the "
                         f"kernel when it can be built)")
    return implementation


def cache_dir() -> str:
    """Where compiled kernels are kept."""
    path = os.environ.get(CACHE_ENV_VAR)
    if path:
        return path
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "fprime-lite")


def _source_bytes() -> bytes:
    return resources.files("detumble.sim").joinpath(_SOURCE).read_bytes()


def _ext_suffix() -> str:
    return sysconfig.get_config_var("EXT_SUFFIX") or importlib.machinery.EXTENSION_SUFFIXES[0]


def source_key(source: bytes | None = None) -> str:
    """Names one build: the C source, the flags, this Python and this platform."""
    h = hashlib.sha256(_source_bytes() if source is None else source)
    h.update(" ".join(COMPILE_FLAGS).encode())
    h.update(sys.version.encode())
    h.update(_ext_suffix().encode())
    h.update(sysconfig.get_platform().encode())
    return h.hexdigest()[:16]


def _compile_command(src: str, out: str, key: str) -> list[str]:
    """The compile-and-link command, from how this Python builds extensions (``$CC`` replaces the compiler)."""
    ldshared = sysconfig.get_config_var("LDSHARED")
    include = sysconfig.get_paths().get("include")
    if not ldshared:
        raise _NoToolchainError("this Python does not say how it links extensions (sysconfig LDSHARED)")
    if not include or not os.path.exists(os.path.join(include, "Python.h")):
        raise _NoToolchainError(f"Python's C headers are not installed (no Python.h in {include}; on Debian: "
                      f"apt-get install python3-dev)")
    cmd = shlex.split(ldshared)
    cc = os.environ.get("CC")
    if cc:
        cmd = shlex.split(cc) + cmd[1:]
    if shutil.which(cmd[0]) is None:
        raise _NoToolchainError(f"no C compiler: {cmd[0]!r} is not on PATH")
    return [*cmd, *COMPILE_FLAGS, f'-DFL_SOURCE_KEY="{key}"', "-I", include, src, "-o", out, "-lm"]


def _build(path: str, key: str) -> float:
    """Compile the kernel to ``path`` (atomically: concurrent processes each write their own file)."""
    folder = os.path.dirname(path)
    os.makedirs(folder, exist_ok=True)
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix=".build-", dir=folder) as tmp:
        src = os.path.join(tmp, _SOURCE)
        with open(src, "wb") as fh:
            fh.write(_source_bytes())
        out = os.path.join(tmp, "kernel" + _ext_suffix())
        cmd = _compile_command(src, out, key)
        try:
            done = subprocess.run(cmd, capture_output=True, text=True, timeout=_BUILD_TIMEOUT_S, check=False)
        except subprocess.TimeoutExpired:
            raise OSError(f"the C compiler did not finish in {_BUILD_TIMEOUT_S:.0f} s") from None
        if done.returncode != 0 or not os.path.exists(out):
            lines = (done.stderr or done.stdout or "").strip().splitlines()
            raise OSError(f"{cmd[0]} failed (exit {done.returncode}): {lines[-1] if lines else 'no output'}")
        os.replace(out, path)
    return time.perf_counter() - t0


def _import(path: str) -> ModuleType:
    loader = importlib.machinery.ExtensionFileLoader(_MODULE, path)
    spec = importlib.util.spec_from_file_location(_MODULE, path, loader=loader)
    assert spec is not None  # a path with a loader always gives a spec
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def _reference_environment(orbit, field_model, t: float):
    """``(r_N, r_hat_N, b_N)`` at ``t`` as :meth:`.plant.Plant._update_environment` computes them."""
    r = orbit.position_N(t)
    rn = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
    return r, (r[0] / rn, r[1] / rn, r[2] / rn), field_model.b_N(t, r)


def mismatch(module: ModuleType) -> str | None:
    """Where the kernel's floats differ from the reference's on a check case, or None when they agree.

    A full inertia tensor with products of inertia, a wheel momentum, gravity gradient, a J2 orbit
    and a turned Earth: every term of both functions contributes. Then the wheel step
    (:func:`_wheel_mismatch`), the orbit-constant field, a tabulated field, the electrical and thermal
    step and the sensors' samples (:func:`_sensor_mismatch`).
    """
    from detumble.sim.attitude import RigidBody
    from detumble.sim.field import DipoleField, OrbitConstantField
    from detumble.sim.orbit import CircularOrbit

    body = RigidBody(((2.0e-3, 1.0e-4, -5.0e-5), (1.0e-4, 3.0e-3, 8.0e-5), (-5.0e-5, 8.0e-5, 4.0e-3)),
                     (1.0e-5, -2.0e-5, 3.0e-5))
    orbit = CircularOrbit(420e3, math.radians(51.6), 0.5, 0.1, j2=1.0826267e-3)
    field = DipoleField(theta0_rad=0.3)
    kernel = module.Kernel(body._j, body._jinv, body.wheel_momentum_B, environment_parameters(orbit, field))
    s: tuple = (0.8, 0.2, -0.4, 0.4, 0.3, -0.2, 0.5)
    for k in range(60):
        t = 0.05 * k + 123.4
        want_env = _reference_environment(orbit, field, t)
        got_env = kernel.environment(t)
        if got_env != want_env:
            return f"environment at t = {t} s: {got_env} != {want_env}"
        args: tuple = (0.05, (0.02, -0.05, 0.01), want_env[2], 3.8e-6, want_env[1])
        if k % 2:  # an external torque (drag, solar pressure) on every other step
            args = (*args, (3e-7 * k, -2e-7, 1e-7))
        want = body.step_env(s, *args)
        got = kernel.step_env(s, *args)
        if got != want:
            return f"step {k}: {got} != {want}"
        got_fused = kernel.step(s, *args[:5], t + 0.05, *args[5:])
        want_fused = (want, *_reference_environment(orbit, field, t + 0.05))
        if got_fused != want_fused:
            return f"fused step {k}: {got_fused} != {want_fused}"
        s = want
    orbit_constant = OrbitConstantField((2.0e-5, -1.0e-5, 3.0e-5), orbit)
    kernel = module.Kernel(body._j, body._jinv, body.wheel_momentum_B, environment_parameters(orbit, orbit_constant))
    # frames.orbit_axes_N squares with ** (libm pow), which is not x * x for about 1 x in 1300 here: the
    # last 8 times are where, on this orbit, x * x instead of ** would change the field (a compiler
    # that folds pow(x, 2.0) into x * x is refused); elsewhere the sqrt and the division absorb it
    for t in (*(37.1 * k + 0.3 for k in range(20)), 69.75, 597.5, 1788.0, 1933.75, 3045.25, 4248.5, 4414.75, 6287.0):
        want_env = _reference_environment(orbit, orbit_constant, t)
        got_env = kernel.environment(t)
        if got_env != want_env:
            return f"orbit-constant environment at t = {t} s: {got_env} != {want_env}"
    problem = _table_mismatch(module, body, orbit, field)
    problem = problem if problem is not None else _wheel_mismatch(module, body, orbit, field)
    problem = problem if problem is not None else _power_mismatch(module)
    return problem if problem is not None else _sensor_mismatch(module)


def _sensor_mismatch(module: ModuleType) -> str | None:
    """The held samples' resolve (``magnetometer_sample``, ``gyro_sample``) against the sensors' Python: pairs of
    sensors from one seed, one resolving in the kernel, fed the same steps (several samples skipped unread, one
    each step, one at a step's end), noisy and quiet, quantised and not, saturating and tilted fast; every sample
    read and the generators' whole states after it (the cached half of a gauss pair included) must agree."""
    from detumble.sim.sensors import Gyro, GyroSpec, Magnetometer, MagnetometerSpec

    specs = (MagnetometerSpec(bias_gauss=(0.012, -0.008, 0.005)),
             MagnetometerSpec(noise_std_gauss=0.0, resolution_gauss=0.0, coupling_t_per_am2=(0.0, 2e-3, -1e-3),
                              bias_gauss=(0.0137, -0.0291, 0.00731)),
             MagnetometerSpec(noise_std_gauss=0.4, full_scale_gauss=0.3, odr_hz=155.0))
    gyros = (GyroSpec(bias_dps=(0.2, -0.1, 0.05)),
             GyroSpec(noise_density_dps_rthz=0.0, resolution_dps=0.0, bias_dps=(0.137, -0.291, 0.0731)),
             GyroSpec(noise_density_dps_rthz=0.9, full_scale_dps=125.0, odr_hz=833.0))
    for case in range(3):
        ref, got = Magnetometer(specs[case], seed=17 + case), Magnetometer(specs[case], seed=17 + case)
        ref_w, got_w = Gyro(gyros[case], seed=23 + case), Gyro(gyros[case], seed=23 + case)
        got.compiled, got_w.compiled = module.magnetometer_sample, module.gyro_sample
        if case == 1:  # start with the second half of a gauss pair cached
            for rng in (ref.rng, got.rng, ref_w.rng, got_w.rng):
                rng.gauss()
        t0 = 0
        for k in range(90):
            dt = (20_000_000, 7_000_000, 3_300_000)[k % 3]
            t1 = t0 + dt
            c, sn = math.cos(0.3 * k), math.sin(0.3 * k)
            q0, q1 = (c, sn * 0.6, -sn * 0.8, 0.0), (0.8, 0.0, 0.6, 0.0)
            w0, w1 = (*q0, 0.3 * c, -2.0 * sn, 1.1), (*q1, 0.31 * c, -1.9 * sn, 1.2 + (case == 2) * 3.0)
            b0, b1 = (2e-5 * c, -1e-5, 3e-5 * sn), (2.1e-5 * c, -1.1e-5, 2.9e-5)
            m = (0.05 * c, -0.02, 0.01 * k)
            for sensor, args in ((ref, (q0, q1, b0, b1, m)), (got, (q0, q1, b0, b1, m)),
                                 (ref_w, (w0, w1)), (got_w, (w0, w1))):
                tk = t1 // sensor.period_ns * sensor.period_ns
                if tk > t0:
                    sensor.defer(t0, t1, tk, *args)
            if k % 4 != 1:  # the others stay unread until a later step (getstate holds gauss's cached half)
                if (ref.sample_gauss, ref.rng.getstate()) != (got.sample_gauss, got.rng.getstate()):
                    return f"magnetometer sample {k} (case {case}): {got.sample_gauss} != {ref.sample_gauss}"
                if (ref_w.sample_rad_s, ref_w.rng.getstate()) != (got_w.sample_rad_s, got_w.rng.getstate()):
                    return f"gyro sample {k} (case {case}): {got_w.sample_rad_s} != {ref_w.sample_rad_s}"
            t0 = t1
    return None


def _table_mismatch(module: ModuleType, body, orbit, model) -> str | None:
    """A field tabulated along the orbit (:class:`~.field.FieldAlongOrbit` with a table step, as IGRF-14 and the
    WMM fly): the environment at times inside a node interval, on nodes, stepping forward node by node, jumping
    ahead and going back (the kernel re-asks Python for the nodes it does not hold), against the Python table's."""
    from detumble.sim.field import FieldAlongOrbit

    step = 0.7
    table, reference = FieldAlongOrbit(model, orbit, step), FieldAlongOrbit(model, orbit, step)
    kernel = module.Kernel(body._j, body._jinv, body.wheel_momentum_B, environment_parameters(orbit, table))
    times = [0.05 * k + 10.0 for k in range(60)] + [2.1, 2.8, 3.5, 1000.3, 1000.0, 1.4, 0.0]
    for t in times:
        r, r_hat, _ = _reference_environment(orbit, model, t)
        want_env = (r, r_hat, reference.b_N(t, r))
        got_env = kernel.environment(t)
        if got_env != want_env:
            return f"tabulated-field environment at t = {t} s: {got_env} != {want_env}"
    return None


def _wheel_mismatch(module: ModuleType, body, orbit, field) -> str | None:
    """The wheel step against :func:`.wheels.step_with_wheels`: four wheels in a pyramid (not along the
    body axes) and a fifth on body x, without friction and with viscous and Coulomb friction (speeds
    inside and beyond the Coulomb smoothing band), speed-mode and torque-mode commands, a momentum
    limit reached, a wheel disabled part-way and the fifth coasting from zero momentum on Coulomb
    friction alone (so that its momentum is the friction's floats, not absorbed in a larger torque); then, with
    each of the four kernels, the motor torques and their flags (:func:`_motor_torque_mismatch`)."""
    from detumble.sim.wheels import WheelAssembly, WheelSpec, step_with_wheels

    c, s3 = math.sqrt(2.0 / 3.0), math.sqrt(1.0 / 3.0)
    axes = ((c, 0.0, s3), (0.0, c, s3), (-c, 0.0, s3), (0.0, -c, s3), (1.0, 0.0, 0.0))
    # fast (0.6 rad/s: gyroscopic torques dominate) and slow (2 mrad/s: the magnetic and gravity-gradient
    # torques show in the rate's last bits)
    made = []
    for friction, w0 in ((False, 0.3), (True, 0.3), (False, 1e-3), (True, 1e-3)):
        specs = tuple(WheelSpec(axis, 1.4e-5 + 1e-6 * i, 4e-3, 1.2e-2 + 1e-3 * i,
                                viscous_friction_nms=(2e-7 * (i + 1)) if friction and i < 4 else 0.0,
                                coulomb_friction_nm=(5e-5 if friction and i != 1 else 0.0),
                                coulomb_smoothing_rad_s=(400.0 if i >= 2 else 0.1),
                                initial_momentum_nms=(-1e-3, 1.1e-2, 2e-4, 0.0, 0.0)[i] if w0 > 0.1 else 0.0)
                      for i, axis in enumerate(axes))
        wheels = WheelAssembly(specs)
        if wheels.friction != friction:
            return "the check case's friction switch is not the one it means to check"
        kernel = module.Kernel(body._j, body._jinv, body.wheel_momentum_B, environment_parameters(orbit, field),
                               wheel_parameters(wheels))
        if (kernel.wheel_count, bool(kernel.wheel_friction)) != (len(specs), friction):
            return f"wheel constants read back as {kernel.wheel_count} wheels, friction {kernel.wheel_friction}"
        # slow: wheel torques and momenta that do not swamp the environment's torques
        k_u = 1.0 if w0 > 0.1 else 1e-4
        m_B = (0.02, -0.05, 0.01) if w0 > 0.1 else (0.2, -0.5, 0.1)
        wheels.set_torque(0, 3e-3 * k_u)
        wheels.set_torque(1, 9e-3 * k_u)  # fast: clipped to 4 mN m, then cut at the momentum limit
        wheels.set_speed(2, -150.0 if w0 > 0.1 else 14.0)
        wheels.set_torque(3, -1e-3 * k_u)
        wheels.set_enabled(4, False)
        st: tuple = (0.8, 0.2, -0.4, 0.4, w0, -0.6 * w0, 1.5 * w0)
        h = wheels.h
        for k in range(100):
            if k == 20:
                wheels.set_enabled(3, False)
            t = 0.05 * k + 77.0
            _, r_hat, b_N = _reference_environment(orbit, field, t)
            u = wheels.motor_torques(0.05, st[4:7])
            args = (u, 0.05, m_B, b_N, 3.8e-6, r_hat)
            ext = ((2e-7, -1e-6 * k_u, 4e-7),) if k % 3 == 1 else ()  # an external torque on every third step
            want = step_with_wheels(body, st, h, u, wheels, *args[1:], *ext)
            got = kernel.step_wheels(st, h, *args, *ext)
            if got != want:
                return f"wheel step {k} (friction {friction}, rate {w0}): {got} != {want}"
            got_env = kernel.step_wheels_env(st, h, *args, t + 0.05, *ext)
            want_env = (*want, *kernel.environment(t + 0.05))
            if got_env != want_env:
                return (f"wheel step {k} with its environment (friction {friction}, rate {w0}): "
                        f"{got_env} != {want_env}")
            st, h = want
            wheels.h = h
        made.append((kernel, specs, friction))
    for kernel, specs, friction in made:  # the commands and limits, once every step above agreed
        problem = _motor_torque_mismatch(kernel, specs, friction)
        if problem is not None:
            return problem
    return None


def _motor_torque_mismatch(kernel, specs, friction: bool) -> str | None:
    """``Kernel.motor_torques`` against ``WheelAssembly.motor_torques`` on 400 random states: momenta inside and
    beyond the limits either way, torque and speed commands past the torque limit, wheels disabled, steps of 1 ms to
    0.2 s and speed loops whose time constant is above and below two steps; the torques and both flags."""
    import dataclasses
    import random

    from detumble.sim.wheels import WheelAssembly

    rng = random.Random(29 + friction)
    specs = tuple(dataclasses.replace(s, speed_loop_time_constant_s=(0.004, 0.1, 0.3, 0.05, 0.02)[i])
                  for i, s in enumerate(specs))
    ref, got = WheelAssembly(specs), WheelAssembly(specs)
    got.compiled = kernel.motor_torques
    for k in range(400):
        dt = rng.choice((0.001, 0.01, 0.05, 0.2))
        ref.h = got.h = tuple(rng.uniform(-1.5, 1.5) * s.max_momentum_nms for s in specs)
        omega = (rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0))
        for i, s in enumerate(specs):
            on, speed_loop = rng.random() < 0.85, rng.random() < 0.4
            command = rng.uniform(-400.0, 400.0) if speed_loop else rng.uniform(-2.0, 2.0) * s.max_torque_nm
            for assembly in (ref, got):
                assembly.set_enabled(i, on)
                (assembly.set_speed if speed_loop else assembly.set_torque)(i, command)
        want = ref.motor_torques(dt, omega)
        have = got.motor_torques(dt, omega)
        if (have, got.torque_applied, got.torque_clipped, got.momentum_limited) != \
                (want, ref.torque_applied, ref.torque_clipped, ref.momentum_limited):
            return (f"wheel motor torques, random state {k} (friction {friction}): {have} != {want} or the flags "
                    f"{got.torque_clipped, got.momentum_limited} != {ref.torque_clipped, ref.momentum_limited}")
    return None


def _power_mismatch(module: ModuleType) -> str | None:
    """The electrical and thermal step (:func:`step_power_thermal`) against ``ElectricalSystem.step`` then
    ``ThermalModel.step``: sunlit and eclipsed, charging to full (the shunt), the burnwire and the payload on
    (a pack emptied to brown-out), sub-stepped thermal steps; then steps in the shadow of faces without conduction
    and with a heat capacity so small that the last bit of each ``T ** 4`` shows in the result (in flight it is
    mostly absorbed in ``T``)."""
    from detumble.sim.power import BatteryConfig, ElectricalSystem, PowerConfig
    from detumble.sim.thermal import ThermalConfig, ThermalModel

    cfg = PowerConfig(battery=BatteryConfig(capacity_wh=0.01, initial_soc=0.98))
    ref, got = ElectricalSystem(cfg, 2460676.5, 6.378e6), ElectricalSystem(cfg, 2460676.5, 6.378e6)
    ref_th, got_th = ThermalModel(), ThermalModel()
    constants = power_constants(got, got_th)
    s_N = ref.sun(0.0)[0]
    r_lit, r_dark = tuple(6.9e6 * x for x in s_N), tuple(-6.9e6 * x + 1e5 for x in s_N)  # sunlit, in the shadow
    # face temperatures (K) whose ** 4 is neither x * x * x * x nor (x * x) * (x * x)
    temps = (251.78, 280.99, 260.66, 256.37, 396.56, 382.6, 373.06, 202.81, 298.72, 374.09, 238.21, 393.51)
    for k in range(84):
        if k == 30:
            for e in (ref, got):
                e.set_switch("payloadPower", True)
                e.burnwire_on = True
        if k >= 80:  # fresh thermal models with tiny capacities, faces at the temperatures above
            tiny = ThermalConfig(face_capacity_j_k=1e-9, interior_capacity_j_k=1e-9, face_interior_w_k=0.0)
            ref_th, got_th = ThermalModel(tiny), ThermalModel(tiny)
            ref_th.face_k[:] = got_th.face_k[:] = temps[(k % 2) * 6:(k % 2) * 6 + 6]
            constants = power_constants(got, got_th)
        q = (0.6, 0.0, 0.8, 0.0) if k % 5 == 0 else (0.9, 0.1 * (k % 3), -0.3, 0.3)
        dt = 0.1 if k % 7 else (2.5 if k % 14 else 1.005)
        args = (dt, 61.0 * k, q, r_dark if 40 <= k < 50 or k >= 80 else r_lit, 0.25 * (k % 4))
        ref.step(*args)
        ref_th.step(args[0], ref.face_flux_w_m2, ref.load_w)
        step_power_thermal(module, constants, got, got_th, *args)
        want = (vars(ref), vars(ref.battery), vars(ref_th))
        have = (vars(got), vars(got.battery), vars(got_th))
        for w, h in zip(want, have, strict=True):
            for name, value in w.items():
                if name not in ("cfg", "battery") and repr(h[name]) != repr(value):
                    return f"power step {k}: {name} {h[name]!r} != {value!r}"
    return None


def load() -> KernelStatus:
    """The compiled kernel for this process: built at first use, imported and checked once."""
    global _status
    if _status is None:
        _status = _load()
        if _status.module is None:
            log.info("compiled plant kernel unavailable (%s): using the pure-Python plant", _status.reason)
    return _status


def _load() -> KernelStatus:
    try:
        key = source_key()
        path = os.path.join(cache_dir(), f"plant_kernel-{key}{_ext_suffix()}")
        built = None
        if not os.path.exists(path):
            built = _build(path, key)
    except _NoToolchainError as exc:
        return KernelStatus(None, str(exc), outcome="no toolchain")
    except OSError as exc:
        return KernelStatus(None, str(exc) or type(exc).__name__, outcome="build failed")
    try:
        module = _import(path)
    except (OSError, ImportError) as exc:
        return KernelStatus(None, f"cannot import {path}: {exc} (remove it to rebuild)", path,
                            outcome="import failed")
    if getattr(module, "SOURCE_KEY", None) != key:
        return KernelStatus(None, f"{path} was not built from this source (remove it to rebuild)", path,
                            outcome="import failed")
    # the stamp vouches for this file's module only (a test may hand over another module for the path)
    stamp = check_stamp_path(path) if getattr(module, "__file__", None) == path else None
    if stamp is not None and os.path.exists(stamp):
        return KernelStatus(module, "", path, built, checked="stamp")
    problem = mismatch(module)
    if problem is not None:
        return KernelStatus(None, f"the compiled kernel does not reproduce the Python reference here ({problem})",
                            path, outcome="refused")
    if stamp is not None:
        _leave_stamp(stamp)
    return KernelStatus(module, "", path, built, checked="now")


def check_stamp_path(kernel_path: str) -> str | None:
    """The stamp a passed load-time check leaves beside ``kernel_path``: ``<kernel file>.checked-<check key>``
    (:func:`check_key`), or None where the key cannot be formed (the check then runs in every process)."""
    key = check_key(kernel_path)
    return None if key is None else f"{kernel_path}.checked-{key}"


def check_key(kernel_path: str) -> str | None:
    """Names everything the load-time check's outcome depends on: the kernel file's bytes, the reference's
    sources (every module of ``detumble.sim`` and ``detumble.control``, and ``detumble.errors``), this
    interpreter (its version and ``random``/``math`` with it), the libm mapped into this process (path, size,
    modification time, inode) and the CPU (model and flags: libm picks its code by them). None when the
    kernel file or a source cannot be read or the libm cannot be named (not Linux, a static libm)."""
    libm = _libm_identity()
    if libm is None:
        return None
    here = os.path.dirname(os.path.abspath(__file__))
    package = os.path.dirname(here)
    h = hashlib.sha256()
    try:
        with open(kernel_path, "rb") as fh:
            h.update(fh.read())
        sources = [os.path.join(package, "errors.py")]
        for folder in (here, os.path.join(package, "control")):
            sources += sorted(os.path.join(folder, name) for name in os.listdir(folder) if name.endswith(".py"))
        for source in sources:
            with open(source, "rb") as fh:
                h.update(os.path.relpath(source, package).encode() + b"\0" + fh.read())
    except OSError:
        return None
    h.update(sys.version.encode() + b"\0" + libm.encode() + b"\0" + _cpu_identity().encode())
    return h.hexdigest()[:16]


def _libm_identity() -> str | None:
    """``path:size:mtime_ns:inode`` of the libm this process has mapped (``/proc/self/maps``), or None."""
    try:
        with open("/proc/self/maps", encoding="ascii", errors="replace") as fh:
            paths = {line.split(None, 5)[-1].strip() for line in fh if "/libm" in line}
        libm = sorted(p for p in paths if os.path.basename(p).startswith(("libm.so", "libm-")))
        if len(libm) != 1:
            return None
        st = os.stat(libm[0])
    except OSError:
        return None
    return f"{libm[0]}:{st.st_size}:{st.st_mtime_ns}:{st.st_ino}"


def _cpu_identity() -> str:
    """The first CPU's model name and flags (``/proc/cpuinfo``); the platform's machine name elsewhere."""
    wanted = ("vendor_id", "model name", "flags", "Features", "CPU implementer", "CPU part")
    found: list[str] = []
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as fh:
            for line in fh:
                if not line.strip():
                    break  # the end of the first processor's block
                if line.split(":", 1)[0].strip() in wanted:
                    found.append(line.strip())
    except OSError:
        pass
    return "\n".join(found) or sysconfig.get_platform()


def _leave_stamp(stamp: str) -> None:
    """Create the (empty) stamp file; a cache that cannot take it only means the check runs again."""
    try:
        with open(stamp, "x"):
            pass
    except OSError:
        pass


def sensor_samples() -> tuple:
    """``(magnetometer_sample, gyro_sample)``: the loaded kernel's resolve of a held sensor sample
    (:attr:`.sensors.Magnetometer.compiled`, :attr:`.sensors.Gyro.compiled`); ``(None, None)`` without a kernel."""
    module = load().module
    return (None, None) if module is None else (module.magnetometer_sample, module.gyro_sample)


def environment_parameters(orbit, field_model) -> tuple:
    """The kernel's environment constants for a :class:`~.orbit.CircularOrbit` and a
    :class:`~.field.DipoleField` (12 floats), an :class:`~.field.OrbitConstantField` on that
    orbit (10 floats) or a :class:`~.field.FieldAlongOrbit` with a table step (the step and its node
    function: 8 floats and a callable; the kernel interpolates, Python computes each node once), in
    the order ``plant_kernel.c`` reads them."""
    from detumble.sim.field import FieldAlongOrbit, OrbitConstantField

    o, f = orbit, field_model
    orbit_part = (o.radius_m, o.arg_latitude0_rad, o.arg_latitude_rate, o.raan0_rad, o.raan_rate, o._ci, o._si)
    if type(f) is FieldAlongOrbit:
        if f.table_step_s is None or f.orbit is not orbit:
            raise ValueError("a tabulated field needs a table step and the plant's own orbit")
        return (*orbit_part, float(f.table_step_s), f._node)
    if type(f) is OrbitConstantField:
        if f.orbit is not orbit:
            raise ValueError("the orbit-constant field must be defined on the plant's own orbit")
        return (*orbit_part, *f.b_O)
    return (*orbit_part, f.theta0_rad, f.earth_rotation_rate, f._dx, f._dy, f._dz)


def wheel_parameters(wheels) -> tuple[tuple[float, ...], ...]:
    """The kernel's wheel constants for a :class:`~.wheels.WheelAssembly`: per wheel
    ``(gx, gy, gz, J_s, c_v, c_c, Omega_s)`` (axis in B, kg m^2, N m s/rad, N m, rad/s)."""
    return tuple((*s.axis_B, s.inertia_kg_m2, s.viscous_friction_nms, s.coulomb_friction_nm,
                  s.coulomb_smoothing_rad_s) for s in wheels.specs)


#: the most wheels the kernel takes (plant_kernel.c FL_MAX_WHEELS); a plant with more keeps the Python step
MAX_WHEELS = 16


def kernel_for(body, orbit, field, implementation: str | None = None, wheels=None):
    """A compiled kernel for one plant's body (with its reaction wheels when ``wheels``, its
    :class:`~.wheels.WheelAssembly`, is given; and its environment when the orbit is circular and the
    field the centred dipole or the orbit-constant field, evaluated at every step, or any model on a
    table, interpolated in the kernel between nodes Python computes), or None for the pure-Python plant.

    ``field`` is the plant's :class:`~.field.FieldAlongOrbit` (or None). Raises
    :class:`KernelUnavailableError` when ``compiled`` was asked for and the kernel cannot be had.
    """
    from detumble.sim.field import DipoleField, FieldAlongOrbit, OrbitConstantField
    from detumble.sim.orbit import CircularOrbit

    mode = requested(implementation)
    if mode == "python":
        return None
    status = load()
    if status.module is None:
        if mode == "compiled":
            raise KernelUnavailableError(f"{ENV_VAR}=compiled but the compiled plant kernel is unavailable: "
                                    f"{status.reason}")
        return None
    if wheels is not None and wheels.n > MAX_WHEELS:
        if mode == "compiled":
            raise KernelUnavailableError(f"{ENV_VAR}=compiled but the compiled plant kernel takes at most "
                                         f"{MAX_WHEELS} reaction wheels (this spacecraft has {wheels.n})")
        log.info("%d reaction wheels: more than the compiled kernel takes, using the pure-Python plant", wheels.n)
        return None
    env = None
    if (type(orbit) is CircularOrbit and type(field) is FieldAlongOrbit and field.table_step_s is None
            and (type(field.model) is DipoleField
                 or (type(field.model) is OrbitConstantField and field.model.orbit is orbit))):
        env = environment_parameters(orbit, field.model)
    elif type(orbit) is CircularOrbit and type(field) is FieldAlongOrbit and field.orbit is orbit \
            and field.table_step_s is not None:
        env = environment_parameters(orbit, field)  # IGRF-14 or the WMM on their table: nodes from Python
    wheel_part = None if wheels is None else wheel_parameters(wheels)
    return status.module.Kernel(body._j, body._jinv, body.wheel_momentum_B, env, wheel_part)


def power_constants(eps, thermal) -> tuple[float, ...]:
    """The kernel's constants for :func:`step_power_thermal`: an :class:`~.power.ElectricalSystem` ``eps``
    and its :class:`~.thermal.ThermalModel`, in the order ``plant_kernel.c`` (``PC_*``) reads them: shadow
    radius m, solar constant W/m^2, the six panel areas m^2, cell efficiency, pack resistance ohm, cells in
    series, capacity J; absorptivity, face area m^2, emissivity, Stefan-Boltzmann W m^-2 K^-4, face and
    interior heat capacities J/K, face-interior conductance W/K, longest sub-step s."""
    from detumble.sim.sun import SOLAR_CONSTANT_W_M2
    from detumble.sim.thermal import STEFAN_BOLTZMANN

    bat, tc = eps.cfg.battery, thermal.cfg
    return (float(eps.earth_radius_m), SOLAR_CONSTANT_W_M2, *eps._areas, float(eps.cfg.solar.efficiency),
            float(bat.internal_resistance_ohm), float(bat.cells_in_series), float(eps.battery.capacity_j),
            float(tc.absorptivity), float(tc.face_area_m2), float(tc.emissivity), STEFAN_BOLTZMANN,
            float(tc.face_capacity_j_k), float(tc.interior_capacity_j_k), float(tc.face_interior_w_k),
            float(tc.max_substep_s))


def step_power_thermal(module: ModuleType, constants: tuple, eps, thermal, dt: float, t_s: float, q_BN, r_N,
                       coil_w: float) -> None:
    """``eps.step(dt, t_s, q_BN, r_N, coil_w)`` then ``thermal.step(dt, eps.face_flux_w_m2, eps.load_w)``
    computed by the compiled ``module`` (the kernel :func:`load` gives), with the same floats, written back to
    the same attributes. ``constants`` is :func:`power_constants` of the two models. The Sun's direction
    (cached per minute) and the switched loads stay the Python models' own."""
    if dt <= 0.0:
        return
    s_N, d_au = eps.sun(t_s)
    bat = eps.battery
    acc = (bat.energy_j, eps.solar_j, eps.shunted_j, eps.load_j, eps.coil_j, eps.loss_j, eps.unserved_j)
    (eps.eclipse, eps.face_flux_w_m2, eps.solar_w, eps.load_w, bat.current_a, v, acc,
     thermal.interior_k) = module.power_step(constants, dt, q_BN, r_N, s_N, d_au, coil_w, eps.switched_load_w(),
                                             acc, thermal.face_k, thermal.interior_k)
    (bat.energy_j, eps.solar_j, eps.shunted_j, eps.load_j, eps.coil_j, eps.loss_j, eps.unserved_j) = acc
    eps.bus_v = bat.terminal_v = v
    eps.coil_w = coil_w


def describe(implementation: str | None = None) -> str:
    """One line for reports: which plant implementation a new plant gets, and why."""
    mode = requested(implementation)
    if mode == "python":
        return f"python ({ENV_VAR}=python)" if implementation is None else "python (asked for)"
    status = load()
    if status.module is not None:
        return "compiled"
    return f"python (compiled kernel unavailable: {status.reason})"


def _reset_for_tests() -> None:
    """Forget this process's kernel (tests that change the cache folder or the compiler)."""
    global _status
    _status = None
