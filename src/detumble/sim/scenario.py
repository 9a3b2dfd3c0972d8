"""Scenario files: YAML description of one plant-only or closed-loop simulation run.

``load_scenario(name_or_path)`` resolves a packaged scenario name (``case_a``, ``default``, ...
in ``detumble/sim/scenarios/``) or a file path, parses it with PyYAML's safe loader (libyaml's
when installed) and validates every key. Unknown keys and bad values raise :class:`ScenarioError` whose message reads
``FILE:LINE: dotted.key: what is wrong - what to do``. The full schema (every key, unit and
default) is documented in ``docs/scenarios.md``.
"""

from __future__ import annotations

import copy
import datetime as _dt
import math
import os
import random
from dataclasses import dataclass
from dataclasses import field as _dc_field
from dataclasses import make_dataclass
from importlib import resources
from typing import Any, Literal, NoReturn, Sequence, overload

import yaml

from detumble.errors import DetumbleError
from detumble.control.attitude_defaults import BDOT_PROVIDER_GAIN
from detumble.control.attitude_defaults import DEFAULTS as ADCS_DEFAULTS
from detumble.control.attitude_defaults import ENUM_CHOICES as ADCS_ENUMS
from detumble.control.targets import target_entry_error
from detumble.control.quaternion import is_unit_quaternion
from detumble.sim.coils import FACE_NAMES, CoilSpec, default_coil_layout
from detumble.sim.epoch import gmst_rad, julian_date, parse_epoch
from detumble.sim.field import (EARTH_ROTATION_RATE, IGRF2025_G10_NT, IGRF2025_G11_NT, IGRF2025_H11_NT,
                    IGRF_REFERENCE_RADIUS_M)
from detumble.sim.orbit import J2_EARTH, MU_EARTH, R_EARTH_EQ
from detumble.sim.sun_sensors import SunSensorSpec
from detumble.sim.sensors import GyroSpec, MagnetometerSpec
from detumble.sim.accelerometer import AccelerometerSpec
from detumble.sim.power import PowerConfig
from detumble.sim.scenario_power import ACCELEROMETER_SCHEMA, POWER_SCHEMA, parse_accelerometer, parse_power
from detumble.sim.star_tracker import StarTrackerSpec
from detumble.sim.wheels import CATALOGUE as WHEEL_CATALOGUE
from detumble.sim.wheels import WheelSpec, equations_inertia
from detumble.sim.vec import Mat3, Quat, Vec3, mrp_to_quat, quat_normalize, unit

LAWS = ("none", "kopt", "bdot", "bangbang", "cross_product", "beta_pd", "wheels_pd", "adcs")
SATURATION = ("clip", "scale")
FIELD_MODELS = ("dipole", "igrf14", "wmm2025", "none", "orbit_constant")


class ScenarioError(DetumbleError, ValueError):
    """A scenario file or dictionary is invalid; the message names file, line and key.

    ``key_path`` and ``detail``: the dotted key and what is wrong with it, when one key is at fault."""

    key_path: str | None = None
    detail: str | None = None


class SettingError(ScenarioError):
    """A ``--set KEY.PATH=VALUE`` override is wrong; the message starts with ``--set 'KEY.PATH=VALUE':``."""


@dataclass(frozen=True)
class OrbitConfig:
    type: str = "circular"
    altitude_km: float = 420.0
    inclination_deg: float = 51.6
    raan_deg: float = 0.0
    arg_latitude_deg: float = 0.0
    j2: bool = False
    mu_m3_s2: float = MU_EARTH
    earth_radius_m: float = R_EARTH_EQ
    j2_coefficient: float = J2_EARTH
    tle: tuple[str, str] | None = None
    table_step_s: float = 10.0


@dataclass(frozen=True)
class FieldConfig:
    model: str = "dipole"
    g10_nt: float = IGRF2025_G10_NT
    g11_nt: float = IGRF2025_G11_NT
    h11_nt: float = IGRF2025_H11_NT
    reference_radius_m: float = IGRF_REFERENCE_RADIUS_M
    earth_rotation_rate_rad_s: float = EARTH_ROTATION_RATE
    earth_rotation_angle_deg: float | None = None
    table_step_s: float = 1.0
    b_orbit_t: Vec3 = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class SurfacesConfig:
    """Drag and solar-radiation-pressure torques (``spacecraft.surfaces``; :class:`~.torques.BoxSurfaces`).

    Both off by default (the shipped deployments' outputs do not change). ``size_m`` the box's edges (m, B:
    a 1U is 0.1 x 0.1 x 0.1135); ``cp_offset_m`` its geometric centre minus the centre of mass (m, B);
    ``drag_coefficient`` C_D (2.2, a flat plate in free-molecular flow); ``specular_reflectivity`` ε (0: all
    absorbed)."""

    drag: bool = False
    solar_pressure: bool = False
    size_m: Vec3 = (0.1, 0.1, 0.1135)
    cp_offset_m: Vec3 = (0.0, 0.0, 0.0)
    drag_coefficient: float = 2.2
    specular_reflectivity: float = 0.0


@dataclass(frozen=True)
class SpacecraftConfig:
    mass_kg: float = 1.3
    inertia_kg_m2: Mat3 = ((2.2e-3, 0.0, 0.0), (0.0, 2.2e-3, 0.0), (0.0, 0.0, 2.2e-3))
    residual_dipole_am2: Vec3 = (0.0, 0.0, 0.0)
    wheel_momentum_nms: Vec3 = (0.0, 0.0, 0.0)
    gravity_gradient: bool = True
    actuator_type: str = "coils"
    coils: dict[int, CoilSpec] = _dc_field(default_factory=default_coil_layout)
    rods_max_dipole_am2: Vec3 = (0.2, 0.2, 0.2)
    #: how the actuators meet a requested body dipole beyond their per-axis limits
    actuator_saturation: str = "clip"
    #: reaction wheels (empty: none; the plant then runs the wheel-free integrator)
    reaction_wheels: tuple[WheelSpec, ...] = ()
    #: drag and solar-pressure surfaces (both torques off by default)
    surfaces: SurfacesConfig = SurfacesConfig()


@dataclass(frozen=True)
class BetaPdConfig:
    """Seed 004's ``magnetorquer2`` gains (its best pair: K_s = 990, K_d = 0.06)."""

    k_s: float = 990.0
    k_d: float = 0.06
    switched: bool = True       # True: eq. 23 or 24 by |B_z| vs |B_x|, as its equations (and figures);
    #                             False: both, as its listing


@dataclass(frozen=True)
class WheelsPdConfig:
    """Seed 004's ``wheels`` gains (K_p = wp = 5, K_d = wd = 9) and target (q_BO, scalar first)."""

    k_p: float = 5.0
    k_d: float = 9.0
    target_q_bo: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)
    limits: str = "report"      # report: its ±1 mN m / ±0.1 N m s checks; wheel: the wheels' own limits only
    error: str = "shortest_path"  # corrected; "report": eq. 25 as written (settles at q4 = -1, the long way)
    dump_gain: float = 0.0      # 1/s: magnetic momentum dumping M = k (h x B)/|B|^2 (0: none, as the report)


#: ``control.adcs``: the plant-only three-mode controller (:mod:`detumble.sim.adcs_law`): its target
#: ``target_q_bn`` (q_TN, scalar first; None holds the attitude POINTING starts from), whether DETUMBLE
#: takes the BDotDetumble provider's dipole (``bdot_provider``) and that provider's gain, when AUTO
#: starts (``auto_start_s``: before it the controller idles, as until the start-up sequence's SET_AUTO), or
#: instead a mode held from ``force_at_s`` on as FORCE_MODE holds it (``force_mode``: DETUMBLE, SPIN_STABLE or
#: POINTING; None: AUTO), the later targets SET_TARGET_QUATERNION would set (``target_changes``: a list of
#: ``[t_s, q0, q1, q2, q3]``, in time order), and every flight parameter of the AttitudeController by its own
#: name (default: the component's default).
AdcsConfig = make_dataclass(
    "AdcsConfig",
    [("target_q_bn", "tuple[float, float, float, float] | None", None), ("bdot_provider", bool, True),
     ("bdot_provider_gain", float, BDOT_PROVIDER_GAIN), ("auto_start_s", float, 0.0),
     ("force_mode", "str | None", None), ("force_at_s", float, 0.0),
     ("target_changes", "tuple[tuple[float, tuple[float, float, float, float]], ...]", ())]
    + [(name, type(value), value) for name, value in ADCS_DEFAULTS.items()],
    frozen=True)


@dataclass(frozen=True)
class ControlConfig:
    law: str = "none"
    gain: float | None = None
    period_s: float = 0.05
    sense_settle_s: float = 0.0
    saturation: str = "scale"
    beta_pd: BetaPdConfig = BetaPdConfig()
    wheels_pd: WheelsPdConfig = WheelsPdConfig()
    adcs: Any = AdcsConfig()


@dataclass(frozen=True)
class Scenario:
    name: str = "unnamed"
    description: str = ""
    source: str = "<dict>"
    epoch: _dt.datetime = parse_epoch("2025-06-01T00:00:00Z")
    duration_s: float = 5400.0
    dynamics_step_s: float = 0.05
    record_interval_s: float = 1.0
    seed: int = 0
    spacecraft: SpacecraftConfig = _dc_field(default_factory=SpacecraftConfig)
    orbit: OrbitConfig = _dc_field(default_factory=OrbitConfig)
    field: FieldConfig = _dc_field(default_factory=FieldConfig)
    magnetometer: MagnetometerSpec = _dc_field(default_factory=MagnetometerSpec)
    gyro: GyroSpec = _dc_field(default_factory=GyroSpec)
    star_tracker: StarTrackerSpec | None = None
    #: the six face light sensors (``sim.sun_sensors``): noise figures, Earth albedo, penumbra
    sun_sensors: SunSensorSpec = _dc_field(default_factory=SunSensorSpec)
    #: RK4 sub-steps per dynamics step (environment held over the whole step)
    integrator_substeps: int = 1
    #: the frame ``q_BN0`` is given relative to: "inertial" (it is q_BN) or "orbit" (it is q_BO)
    attitude_frame: str = "inertial"
    q_BN0: Quat = (1.0, 0.0, 0.0, 0.0)
    omega_BN_B0: Vec3 = (0.0, 0.0, 0.0)
    control: ControlConfig = _dc_field(default_factory=ControlConfig)
    accelerometer: AccelerometerSpec = _dc_field(default_factory=AccelerometerSpec)
    power: PowerConfig = _dc_field(default_factory=PowerConfig)

    @property
    def earth_angle0_rad(self) -> float:
        """Earth rotation angle at t = 0: the configured one, else GMST of the epoch."""
        if self.field.earth_rotation_angle_deg is not None:
            return math.radians(self.field.earth_rotation_angle_deg)
        return gmst_rad(julian_date(self.epoch))


# --- loading -----------------------------------------------------------------------------------


def packaged_scenarios() -> list[str]:
    """Names of the scenarios shipped in ``detumble/sim/scenarios``."""
    root = resources.files("detumble.sim").joinpath("scenarios")
    return sorted(p.name[:-5] for p in root.iterdir() if p.name.endswith(".yaml"))


def resolve_scenario(name_or_path: str) -> tuple[str, str]:
    """Return ``(source_label, text)`` for a packaged name or a file path."""
    if os.path.exists(name_or_path):
        with open(name_or_path, encoding="utf-8") as fh:
            return name_or_path, fh.read()
    base = name_or_path[:-5] if name_or_path.endswith(".yaml") else name_or_path
    if os.sep not in base and "/" not in base:
        res = resources.files("detumble.sim").joinpath("scenarios", base + ".yaml")
        if res.is_file():
            return f"{base}.yaml", res.read_text(encoding="utf-8")
    raise ScenarioError(
        f"{name_or_path}: no such scenario file, and not a packaged scenario "
        f"(packaged: {', '.join(packaged_scenarios())})"
    )


def load_scenario(name_or_path: str, seed: int | None = None, settings: Sequence[str] = ()) -> Scenario:
    """Load and validate a scenario by packaged name or path. ``seed`` overrides the file's;
    ``settings`` (``"sensors.magnetometer.noise_std_gauss=0"``, …) override single values."""
    source, text = resolve_scenario(name_or_path)
    return parse_scenario(text, source=source, seed=seed, settings=settings)


#: Fields of a :class:`Scenario` that describe it without changing a run (prose, where it was read from).
_UNFLOWN_FIELDS = ("description", "source")


def scenario_fingerprint(name_or_path: str) -> dict:
    """What a run of ``name_or_path`` (a packaged name or a file) resolves to, for a campaign manifest.

    ``sha256``: a digest of the loaded scenario's values, defaults filled in (its description and
    source path left out), so a changed packaged file or a changed schema default both show;
    ``sections``: one digest per top-level section, naming what changed; ``field_model``: the
    geomagnetic field model the plant flies (``dipole``, ``igrf14`` …); ``source``: the file label.
    """
    import dataclasses
    import hashlib
    import json

    scenario = load_scenario(name_or_path)
    values = {k: v for k, v in dataclasses.asdict(scenario).items() if k not in _UNFLOWN_FIELDS}

    def digest(value: Any) -> str:
        return hashlib.sha256(json.dumps(value, sort_keys=True, default=str).encode()).hexdigest()

    return {"source": os.path.basename(scenario.source), "field_model": scenario.field.model,
            "sha256": digest(values), "sections": {k: digest(v)[:16] for k, v in values.items()}}


def parse_scenario(text: str, source: str = "<string>", seed: int | None = None,
                   settings: Sequence[str] = ()) -> Scenario:
    """Validate scenario YAML text. Safe loader only (libyaml's when PyYAML has it)."""
    try:
        data, lines = _read_yaml(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{source}:{mark.line + 1}" if mark is not None else source
        raise ScenarioError(f"{where}: not valid YAML: {getattr(exc, 'problem', exc)}") from None
    if data is None:
        data = {}
    for setting in settings:
        apply_setting(data, setting, source)
    try:
        return scenario_from_dict(data, source=source, lines=lines, seed=seed)
    except ScenarioError as exc:
        for setting in settings:  # a value a --set gave is named by the --set, not the file's line
            key = setting.partition("=")[0].strip()
            if exc.key_path is not None and (exc.key_path == key or exc.key_path.startswith((key + ".", key + "["))):
                raise SettingError(f"--set {setting!r}: {exc.key_path}: {exc.detail}") from None
        raise


def apply_setting(data: dict, setting: str, source: str = "<scenario>") -> None:
    """Set one value of scenario ``data`` in place from ``"dotted.key.path=YAML value"``.

    A key missing from the scenario is added when the schema knows it (:data:`SCHEMA`; sections on
    the way are created), so ``initial.rate.omega_deg_s=[1, 2, 3]`` works on a file that gives a
    magnitude and an axis - the alternative keys it replaces are removed (``_EXCLUSIVE``). A key the
    schema does not know is an error naming the keys that are there, never a silently added one.
    A list element is addressed by its index.
    The value is read as YAML, so ``0``, ``2.5e-3``, ``[1, 0, 0]`` and ``true`` have their types.
    """
    path_text, sep, value_text = setting.partition("=")
    if not sep or not path_text.strip():
        raise SettingError(f"--set {setting!r}: expected KEY.PATH=VALUE, e.g. "
                            f"sensors.magnetometer.noise_std_gauss=0")
    try:
        value = _numbers(yaml.safe_load(value_text), setting)
    except yaml.YAMLError as exc:
        raise SettingError(f"--set {setting!r}: the value is not valid YAML: "
                            f"{getattr(exc, 'problem', exc)}") from None
    keys = path_text.strip().split(".")
    node = data
    walked: list[str] = []
    schema: dict | None = SCHEMA
    for i, key in enumerate(keys):
        last = i == len(keys) - 1
        known = schema if isinstance(schema, dict) else {}
        if isinstance(node, dict):
            if key not in node:
                if key not in known:
                    where = ".".join(walked) or "the top level"
                    addable = sorted(k for k in known if k not in node)
                    raise SettingError(f"--set {setting!r}: {source} has no key {key!r} at {where} "
                                        f"(keys there: {', '.join(map(str, node)) or 'none'})"
                                        + (f"; keys that can be added there: {', '.join(addable)}" if addable else ""))
                if not last:
                    node[key] = {}
            if last:
                for other in _EXCLUSIVE.get((tuple(walked), key), ()):
                    node.pop(other, None)
                node[key] = value
            else:
                if node[key] is None and isinstance(known.get(key), dict):
                    node[key] = {}
                node = node[key]
            schema = known.get(key)
        elif isinstance(node, list):
            if not (key.isdigit() and int(key) < len(node)):
                raise SettingError(f"--set {setting!r}: {'.'.join(walked)} is a list of {len(node)}; "
                                    f"address an element by its index 0..{len(node) - 1}")
            if last:
                node[int(key)] = value
            else:
                node = node[int(key)]
        else:
            raise SettingError(f"--set {setting!r}: {'.'.join(walked)} is a value, not a section")
        walked.append(key)


def _numbers(value: Any, setting: str) -> Any:
    """``value`` with the words a command line means as numbers made numbers: YAML 1.1 reads ``1e6``
    (no dot, no sign) as text; ``nan`` and ``inf`` are refused, as every scenario number must be finite."""
    if isinstance(value, list):
        return [_numbers(v, setting) for v in value]
    if isinstance(value, str):
        try:
            x = float(value)
        except ValueError:
            return value
        if not math.isfinite(x):
            raise SettingError(f"--set {setting!r}: {value} is not a finite number; scenario values must be "
                               f"finite — give a number such as 1e6 or 2.5e-3")
        return x
    return value


_LEAF = None
_VEC = None
_COIL = {k: _LEAF for k in ("turns", "voltage_v", "resistance_ohm", "shape", "length_m", "width_m", "diameter_m",
                            "inductance_h")}
#: Every key a scenario may have (sections are dicts, leaves None): ``--set`` may add any of them.
SCHEMA: dict = {
    "name": _LEAF, "description": _LEAF, "epoch": _LEAF, "duration_s": _LEAF, "dynamics_step_s": _LEAF,
    "integrator_substeps": _LEAF, "record_interval_s": _LEAF, "seed": _LEAF,
    "spacecraft": {
        "mass_kg": _LEAF, "inertia_kg_m2": _LEAF, "residual_dipole_am2": _VEC, "wheel_momentum_nms": _VEC,
        "gravity_gradient": _LEAF,
        "surfaces": {k: _LEAF for k in ("drag", "solar_pressure", "size_m", "cp_offset_m", "drag_coefficient",
                                        "specular_reflectivity")},
        "actuators": {"type": _LEAF, "max_dipole_am2": _VEC, "saturation": _LEAF,
                      "x_plus": _COIL, "x_minus": _COIL, "y_plus": _COIL, "y_minus": _COIL, "z_minus": _COIL},
        "reaction_wheels": {"model": _LEAF, "axes": _LEAF, "inertia_kg_m2": _LEAF, "max_torque_nm": _LEAF,
                            "max_momentum_nms": _LEAF, "viscous_friction_nms": _LEAF, "coulomb_friction_nm": _LEAF,
                            "coulomb_smoothing_rad_s": _LEAF, "momentum_noise_std_nms": _LEAF,
                            "initial_momentum_nms": _LEAF, "speed_loop_time_constant_s": _LEAF},
    },
    "orbit": {k: _LEAF for k in ("type", "altitude_km", "radius_km", "inclination_deg", "raan_deg",
                                 "arg_latitude_deg", "j2", "j2_coefficient", "mu_m3_s2", "earth_radius_m", "tle",
                                 "table_step_s")},
    "field": {k: _LEAF for k in ("model", "g10_nt", "g11_nt", "h11_nt", "reference_radius_m",
                                 "earth_rotation_rate_rad_s", "earth_rotation_angle_deg", "table_step_s",
                                 "b_orbit_t")},
    "sensors": {
        "magnetometer": {k: _LEAF for k in ("ideal", "odr_hz", "noise_std_gauss", "bias_gauss", "resolution_gauss",
                                            "full_scale_gauss", "coupling_t_per_am2")},
        "gyro": {k: _LEAF for k in ("ideal", "odr_hz", "noise_density_dps_rthz", "bias_dps", "full_scale_dps",
                                    "resolution_dps")},
        "star_tracker": {k: _LEAF for k in ("ideal", "rate_hz", "noise_cross_boresight_arcsec",
                                            "noise_about_boresight_arcsec", "boresight_B", "bias_arcsec",
                                            "dropout_probability", "max_rate_deg_s", "sun_exclusion_deg",
                                            "outage_s")},
        "accelerometer": ACCELEROMETER_SCHEMA,
        "sun_sensors": {k: _LEAF for k in ("gain_sigma", "noise_sigma", "albedo", "penumbra")},
    },
    "initial": {
        "attitude": {"quaternion": _LEAF, "mrp": _LEAF, "frame": _LEAF},
        "rate": {k: _LEAF for k in ("omega_deg_s", "omega_rad_s", "magnitude_deg_s", "axis", "random_axis", "seed")},
    },
    "control": {
        **{k: _LEAF for k in ("law", "gain", "period_s", "sense_settle_s", "saturation")},
        "beta_pd": {k: _LEAF for k in ("k_s", "k_d", "switched")},
        "wheels_pd": {k: _LEAF for k in ("k_p", "k_d", "target_q_bo", "limits", "error", "dump_gain")},
        "adcs": {k: _LEAF for k in ("target_q_bn", "bdot_provider", "bdot_provider_gain", "auto_start_s",
                                       "force_mode", "force_at_s", "target_changes",
                                       *ADCS_DEFAULTS)},
    },
    "power": POWER_SCHEMA,
}

_RATE_FORMS = ("omega_deg_s", "omega_rad_s", "magnitude_deg_s", "axis", "random_axis", "seed")
#: Setting one of a set of alternative keys with ``--set`` removes the others of its section.
_EXCLUSIVE: dict[tuple, tuple[str, ...]] = {
    (("initial", "rate"), "omega_deg_s"): tuple(k for k in _RATE_FORMS if k != "omega_deg_s"),
    (("initial", "rate"), "omega_rad_s"): tuple(k for k in _RATE_FORMS if k != "omega_rad_s"),
    (("initial", "rate"), "magnitude_deg_s"): ("omega_deg_s", "omega_rad_s"),
    (("initial", "rate"), "axis"): ("omega_deg_s", "omega_rad_s", "random_axis"),
    (("initial", "rate"), "random_axis"): ("omega_deg_s", "omega_rad_s", "axis"),
    (("initial", "attitude"), "quaternion"): ("mrp",),
    (("initial", "attitude"), "mrp"): ("quaternion",),
    (("orbit",), "altitude_km"): ("radius_km",),
    (("orbit",), "radius_km"): ("altitude_km",),
}


#: libyaml's safe loader when PyYAML has it (about ten times faster), else PyYAML's own.
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
#: Scenario texts read before: (data, line map) by text, so that loading the same scenario again
#: (every topology load builds the spacecraft) does not parse it again.
_read_before: dict[str, tuple[Any, dict[tuple, int]]] = {}
_READ_BEFORE_MAX = 16


def _read_yaml(text: str) -> tuple[Any, dict[tuple, int]]:
    """The data of scenario YAML ``text`` (safe loader) and the line of each key path; the data is
    a fresh copy each call, since settings are applied to it in place."""
    if text not in _read_before:
        loader = _LOADER(text)
        try:
            root = loader.get_single_node()
            data = loader.construct_document(root) if root is not None else None
        finally:
            loader.dispose()
        if len(_read_before) >= _READ_BEFORE_MAX:
            _read_before.pop(next(iter(_read_before)))
        _read_before[text] = (data, _line_map(root))
    data, lines = _read_before[text]
    return copy.deepcopy(data), dict(lines)


def _line_map(root) -> dict[tuple, int]:
    """Map key paths to 1-based line numbers using the YAML node tree ``root``."""
    out: dict[tuple, int] = {}

    def walk(node, path):
        if isinstance(node, yaml.MappingNode):
            for k, v in node.value:
                p = path + (str(k.value),)
                out[p] = k.start_mark.line + 1
                walk(v, p)
        elif isinstance(node, yaml.SequenceNode):
            for i, v in enumerate(node.value):
                p = path + (i,)
                out[p] = v.start_mark.line + 1
                walk(v, p)

    if root is not None:
        walk(root, ())
    return out


class _Section:
    """A mapping being validated: typed getters, then :meth:`finish` rejects unknown keys."""

    def __init__(self, data: Any, path: tuple, ctx: "_Ctx") -> None:
        self.path = path
        self.ctx = ctx
        if data is None:
            data = {}
        if not isinstance(data, dict):
            ctx.fail(path, f"expected a mapping of keys, got {type(data).__name__}")
        self.data = data
        self.used: set[str] = set()
        self.declared: set[str] = set()

    def allow(self, *keys: str) -> None:
        """Declare keys that are valid here even when absent (for the 'allowed here' hint)."""
        self.declared.update(keys)

    def has(self, key: str) -> bool:
        return key in self.data

    def raw(self, key: str, default: Any = None) -> Any:
        self.used.add(key)
        return self.data.get(key, default)

    def fail(self, key: str, msg: str) -> NoReturn:
        self.ctx.fail(self.path + (key,), msg)

    @overload
    def number(self, key: str, default: float | None, *, positive: bool = ..., nonneg: bool = ...,
               allow_none: Literal[False] = ...) -> float: ...

    @overload
    def number(self, key: str, default: float | None, *, positive: bool = ..., nonneg: bool = ...,
               allow_none: bool) -> float | None: ...

    def number(self, key: str, default: float | None, *, positive: bool = False,
               nonneg: bool = False, allow_none: bool = False) -> float | None:
        v = self.raw(key, default)
        if v is None:
            if allow_none:
                return None
            self.fail(key, "a number is required")
        return self.ctx.number(self.path + (key,), v, positive=positive, nonneg=nonneg)

    def integer(self, key: str, default: int) -> int:
        v = self.raw(key, default)
        if isinstance(v, bool) or not isinstance(v, int):
            self.fail(key, f"expected an integer, got {v!r}")
        return v

    def boolean(self, key: str, default: bool) -> bool:
        v = self.raw(key, default)
        if not isinstance(v, bool):
            self.fail(key, f"expected true or false, got {v!r}")
        return v

    def string(self, key: str, default: str | None, choices: tuple[str, ...] | None = None) -> str:
        v = self.raw(key, default)
        if not isinstance(v, str):
            self.fail(key, f"expected a string, got {v!r}")
        if choices is not None and v not in choices:
            self.fail(key, f"unknown value {v!r}; expected one of: {', '.join(choices)}")
        return v

    def vec3(self, key: str, default: Vec3 | None, *, nonneg: bool = False) -> Vec3:
        v = self.raw(key, default)
        p = self.path + (key,)
        if not isinstance(v, (list, tuple)) or len(v) != 3:
            self.ctx.fail(p, f"expected a list of 3 numbers, got {v!r}")
        number = self.ctx.number
        return (number(p + (0,), v[0], nonneg=nonneg), number(p + (1,), v[1], nonneg=nonneg),
                number(p + (2,), v[2], nonneg=nonneg))

    def section(self, key: str) -> "_Section":
        return _Section(self.raw(key, {}), self.path + (key,), self.ctx)

    def finish(self) -> None:
        for key in self.data:
            if key not in self.used:
                allowed = ", ".join(sorted(self.used | self.declared)) or "(none)"
                self.ctx.fail(self.path + (str(key),), f"unknown key {key!r}; allowed here: {allowed}")


class _Ctx:
    def __init__(self, source: str, lines: dict[tuple, int]) -> None:
        self.source = source
        self.lines = lines

    def fail(self, path: tuple, msg: str) -> NoReturn:
        line = None
        p = path
        while p and line is None:
            line = self.lines.get(p)
            p = p[:-1]
        dotted = ".".join(f"[{x}]" if isinstance(x, int) else x for x in path).replace(".[", "[")
        where = f"{self.source}:{line}" if line is not None else self.source
        exc = ScenarioError(f"{where}: {dotted or '(top level)'}: {msg}")
        exc.key_path, exc.detail = dotted, msg
        raise exc

    def number(self, path: tuple, v: Any, *, positive: bool = False, nonneg: bool = False) -> float:
        if isinstance(v, str):
            try:
                float(v)
            except ValueError:
                pass
            else:
                self.fail(path, f"expected a number, got the string {v!r}; YAML reads exponents only with a "
                                f"sign and a dot, e.g. 3.986e+14")
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            self.fail(path, f"expected a number, got {v!r}")
        x = float(v)
        if not math.isfinite(x):
            self.fail(path, f"must be a finite number, got {x}")
        if positive and not x > 0.0:
            self.fail(path, f"must be positive, got {x}")
        if nonneg and x < 0.0:
            self.fail(path, f"must not be negative, got {x}")
        return x


_COIL_KEYS = ("turns", "voltage_v", "resistance_ohm", "shape", "length_m", "width_m", "diameter_m", "inductance_h")


def scenario_from_dict(data: Any, source: str = "<dict>", lines: dict[tuple, int] | None = None,
                       seed: int | None = None) -> Scenario:
    """Build a validated :class:`Scenario` from plain data (as ``yaml.safe_load`` returns)."""
    ctx = _Ctx(source, lines or {})
    top = _Section(data, (), ctx)
    name = top.string("name", "unnamed")
    description = top.string("description", "")
    epoch_raw = top.raw("epoch", "2025-06-01T00:00:00Z")
    try:
        epoch = parse_epoch(epoch_raw)
    except ValueError as exc:
        top.fail("epoch", str(exc))
    duration = top.number("duration_s", 5400.0, positive=True)
    dt = top.number("dynamics_step_s", 0.05, positive=True)
    if dt > 1.0:
        top.fail("dynamics_step_s", f"{dt} s is too coarse for RK4 on a tumbling body; use <= 1 s")
    record = top.number("record_interval_s", 1.0, positive=True)
    file_seed = top.integer("seed", 0)
    substeps = top.integer("integrator_substeps", 1)
    if not 1 <= substeps <= 1000:
        top.fail("integrator_substeps", f"{substeps}: give a whole number of RK4 sub-steps per dynamics step, 1...1000")

    sc = _spacecraft(top.section("spacecraft"))
    orbit = _orbit(top.section("orbit"))
    fld = _field(top.section("field"))
    sens = top.section("sensors")
    mag = _magnetometer(sens.section("magnetometer"))
    gyro = _gyro(sens.section("gyro"))
    accelerometer = parse_accelerometer(sens.section("accelerometer"))
    star = _star_tracker(sens.section("star_tracker")) if sens.has("star_tracker") else None
    sun_sensors = _sun_sensors(sens.section("sun_sensors"))
    sens.allow("star_tracker")
    sens.finish()
    use_seed = file_seed if seed is None else seed
    q0, frame, w0 = _initial(top.section("initial"), use_seed)
    control = _control(top.section("control"), dt)
    power = parse_power(top.section("power"))
    top.allow("integrator_substeps")
    top.finish()
    return Scenario(name=name, description=description, source=source, epoch=epoch, duration_s=duration,
                    dynamics_step_s=dt, record_interval_s=record, seed=use_seed, spacecraft=sc, orbit=orbit,
                    field=fld, magnetometer=mag, gyro=gyro, star_tracker=star, sun_sensors=sun_sensors,
                    integrator_substeps=substeps,
                    attitude_frame=frame, q_BN0=q0, omega_BN_B0=w0, control=control,
                    accelerometer=accelerometer, power=power)


def symmetric_eigenvalues(j: Mat3) -> list[float]:
    """The eigenvalues of the symmetric 3x3 matrix ``j``, ascending, by cyclic Jacobi rotations (each
    zeroes one off-diagonal element; convergence is quadratic, a few sweeps), so that loading a
    scenario needs no numpy (its import was ~0.1 s of a run). Agrees with ``numpy.linalg.eigvalsh``
    within 1e-12 of the largest eigenvalue's magnitude, repeated eigenvalues included
    (tests/detumble/sim/test_scenario_inertia_eigen.py)."""
    a = [list(row) for row in j]
    for _ in range(50):
        off = abs(a[0][1]) + abs(a[0][2]) + abs(a[1][2])
        if off == 0.0 or off <= 1e-18 * (abs(a[0][0]) + abs(a[1][1]) + abs(a[2][2])):
            break
        for p, q in ((0, 1), (0, 2), (1, 2)):
            apq = a[p][q]
            if apq == 0.0:
                continue
            theta = (a[q][q] - a[p][p]) / (2.0 * apq)
            t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1.0))
            c = 1.0 / math.sqrt(t * t + 1.0)
            s = t * c
            for k in range(3):  # columns p and q of A G
                akp, akq = a[k][p], a[k][q]
                a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
            for k in range(3):  # rows p and q of G^T (A G)
                apk, aqk = a[p][k], a[q][k]
                a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
            a[p][q] = a[q][p] = 0.0
    return sorted((a[0][0], a[1][1], a[2][2]))


def _inertia(s: _Section) -> Mat3:
    key = "inertia_kg_m2"
    v = s.raw(key, [2.2e-3, 2.2e-3, 2.2e-3])
    p = s.path + (key,)
    if isinstance(v, (list, tuple)) and len(v) == 3 and all(not isinstance(x, (list, tuple)) for x in v):
        d = [s.ctx.number(p + (i,), x) for i, x in enumerate(v)]
        j = ((d[0], 0.0, 0.0), (0.0, d[1], 0.0), (0.0, 0.0, d[2]))
    elif isinstance(v, (list, tuple)) and len(v) == 3 and all(isinstance(r, (list, tuple)) and len(r) == 3 for r in v):
        r = [[s.ctx.number(p + (i, k), x) for k, x in enumerate(row)] for i, row in enumerate(v)]
        j = ((r[0][0], r[0][1], r[0][2]), (r[1][0], r[1][1], r[1][2]), (r[2][0], r[2][1], r[2][2]))
    else:
        s.ctx.fail(p, "expected 3 principal moments [Jxx, Jyy, Jzz] or a 3x3 matrix, kg m^2")
    for i in range(3):
        if not j[i][i] > 0.0:
            s.ctx.fail(p, f"diagonal element J[{i}][{i}] = {j[i][i]} must be positive")
        for k in range(3):
            if abs(j[i][k] - j[k][i]) > 1e-9 * max(abs(j[i][i]), abs(j[k][k])):
                s.ctx.fail(p, f"must be symmetric: J[{i}][{k}] = {j[i][k]} but J[{k}][{i}] = {j[k][i]}")
    eig = symmetric_eigenvalues(j)
    if not eig[0] > 0.0:
        s.ctx.fail(p, f"must be positive definite; eigenvalues are {', '.join(f'{e:.4g}' for e in eig)} kg m^2")
    if eig[0] + eig[1] < eig[2] * (1.0 - 1e-9):
        s.ctx.fail(p, f"principal moments {', '.join(f'{e:.4g}' for e in eig)} violate the triangle "
                      "inequality (J1 + J2 >= J3): no rigid body has them")
    return j


def _spacecraft(s: _Section) -> SpacecraftConfig:
    mass = s.number("mass_kg", 1.3, positive=True)
    inertia = _inertia(s)
    res = s.vec3("residual_dipole_am2", (0.0, 0.0, 0.0))
    wheel = s.vec3("wheel_momentum_nms", (0.0, 0.0, 0.0))
    gg = s.boolean("gravity_gradient", True)
    act = s.section("actuators")
    kind = act.string("type", "coils", ("coils", "rods"))
    saturation = act.string("saturation", "clip", SATURATION)
    coils = default_coil_layout()
    rods = (0.2, 0.2, 0.2)
    if kind == "rods":
        rods = act.vec3("max_dipole_am2", rods, nonneg=True)
    else:
        act.allow(*FACE_NAMES.values())
        for face, fname in FACE_NAMES.items():
            if not act.has(fname):
                continue
            c = act.section(fname)
            c.allow(*_COIL_KEYS)
            base = coils[face]
            kw: dict[str, Any] = {}
            for key in _COIL_KEYS:
                if not c.has(key):
                    continue
                if key == "shape":
                    kw[key] = c.string(key, None, ("rectangular", "circular"))
                else:
                    kw[key] = c.number(key, None, nonneg=True)
            c.finish()
            merged = CoilSpec(**{**base.__dict__, **kw})
            if merged.shape == "circular" and not merged.diameter_m > 0:
                c.fail("diameter_m", "a circular coil needs a positive diameter_m")
            coils[face] = merged
    act.finish()
    wheels: tuple[WheelSpec, ...] = ()
    if s.raw("reaction_wheels") is not None:
        wheels = _reaction_wheels(s.section("reaction_wheels"), inertia)
    s.allow("reaction_wheels")
    surfaces = SurfacesConfig()
    if s.raw("surfaces") is not None:
        surfaces = _surfaces(s.section("surfaces"))
    s.allow("surfaces")
    s.finish()
    return SpacecraftConfig(mass_kg=mass, inertia_kg_m2=inertia, residual_dipole_am2=res, wheel_momentum_nms=wheel,
                            gravity_gradient=gg, actuator_type=kind, coils=coils, rods_max_dipole_am2=rods,
                            actuator_saturation=saturation, reaction_wheels=wheels, surfaces=surfaces)


def _surfaces(s: _Section) -> SurfacesConfig:
    d = SurfacesConfig()
    size = s.vec3("size_m", d.size_m, nonneg=True)
    if min(size) <= 0.0:
        s.fail("size_m", f"every edge must be positive (m), got {list(size)}")
    eps = s.number("specular_reflectivity", d.specular_reflectivity, nonneg=True)
    if eps > 1.0:
        s.fail("specular_reflectivity", f"must be between 0 and 1, got {eps}")
    out = SurfacesConfig(drag=s.boolean("drag", d.drag), solar_pressure=s.boolean("solar_pressure", d.solar_pressure),
                         size_m=size, cp_offset_m=s.vec3("cp_offset_m", d.cp_offset_m),
                         drag_coefficient=s.number("drag_coefficient", d.drag_coefficient, nonneg=True),
                         specular_reflectivity=eps)
    s.finish()
    return out


_WHEEL_NUMBERS = (  # key, default, check
    ("inertia_kg_m2", None, "positive"), ("max_torque_nm", None, "positive"), ("max_momentum_nms", None, "positive"),
    ("viscous_friction_nms", 0.0, "nonneg"), ("coulomb_friction_nm", 0.0, "nonneg"),
    ("coulomb_smoothing_rad_s", 0.1, "positive"), ("momentum_noise_std_nms", 0.0, "nonneg"),
    ("initial_momentum_nms", 0.0, "any"), ("speed_loop_time_constant_s", 0.1, "positive"),
)


def _reaction_wheels(s: _Section, inertia: Mat3) -> tuple[WheelSpec, ...]:
    """``spacecraft.reaction_wheels``: a catalogue ``model`` and/or explicit values; every number
    is one value for all wheels or a list with one per wheel."""
    if not s.data:
        s.finish()
        return ()
    model = s.string("model", "custom", ("custom", *WHEEL_CATALOGUE))
    entry = WHEEL_CATALOGUE.get(model)
    axes_raw = s.raw("axes", [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    p = s.path + ("axes",)
    if not isinstance(axes_raw, (list, tuple)) or not axes_raw or \
            not all(isinstance(a, (list, tuple)) and len(a) == 3 for a in axes_raw):
        s.ctx.fail(p, "expected a list of spin axes, each 3 numbers in the body frame, e.g. [[1, 0, 0], [0, 1, 0]]")
    axes: list[Vec3] = []
    for i, a in enumerate(axes_raw):
        v = (s.ctx.number(p + (i, 0), a[0]), s.ctx.number(p + (i, 1), a[1]), s.ctx.number(p + (i, 2), a[2]))
        n = math.sqrt(sum(x * x for x in v))
        if n == 0.0:
            s.ctx.fail(p + (i,), "a spin axis must not be the zero vector")
        axes.append((v[0] / n, v[1] / n, v[2] / n))
    count = len(axes)
    values: dict[str, list[float]] = {}
    for key, default, check in _WHEEL_NUMBERS:
        if entry is not None and default is None:
            default = getattr(entry, key)
        v = s.raw(key, default)
        kp = s.path + (key,)
        if v is None:
            s.ctx.fail(kp, f"required without a catalogue model; give it, or model: one of "
                           f"{', '.join(WHEEL_CATALOGUE)}")
        if isinstance(v, (list, tuple)):
            if len(v) != count:
                s.ctx.fail(kp, f"a list needs one value per wheel ({count} wheels), got {len(v)}")
            xs = [s.ctx.number(kp + (i,), x, positive=check == "positive", nonneg=check == "nonneg")
                  for i, x in enumerate(v)]
        else:
            xs = [s.ctx.number(kp, v, positive=check == "positive", nonneg=check == "nonneg")] * count
        values[key] = xs
    s.finish()
    specs = tuple(WheelSpec(axis_B=axes[i], **{k: values[k][i] for k in values}) for i in range(count))
    for i, w in enumerate(specs):
        if abs(w.initial_momentum_nms) > w.max_momentum_nms:
            s.fail("initial_momentum_nms", f"wheel {i}: {w.initial_momentum_nms} N m s is beyond its "
                                           f"max_momentum_nms {w.max_momentum_nms}")
    import numpy as np  # load time only

    eig = np.linalg.eigvalsh(np.array(equations_inertia(inertia, specs))).tolist()
    if not min(eig) > 0.0:
        s.fail("inertia_kg_m2", "the wheels' axial inertia exceeds the spacecraft's; spacecraft.inertia_kg_m2 "
                                "is the whole spacecraft including its wheels")
    return specs


def _orbit(s: _Section) -> OrbitConfig:
    kind = s.string("type", "circular", ("circular", "tle"))
    mu = s.number("mu_m3_s2", MU_EARTH, positive=True)
    re = s.number("earth_radius_m", R_EARTH_EQ, positive=True)
    if kind == "tle":
        tle = s.raw("tle")
        if not (isinstance(tle, (list, tuple)) and len(tle) == 2 and all(isinstance(x, str) for x in tle)):
            s.fail("tle", "expected a list of the two TLE lines as strings")
        step = s.number("table_step_s", 10.0, positive=True)
        s.finish()
        return OrbitConfig(type="tle", tle=(tle[0], tle[1]), table_step_s=step, mu_m3_s2=mu, earth_radius_m=re)
    if s.has("radius_km"):
        if s.has("altitude_km"):
            s.fail("radius_km", "give either altitude_km or radius_km, not both")
        radius = s.number("radius_km", None, positive=True)
        alt = radius - re / 1e3
        if not alt > 0.0:
            s.fail("radius_km", f"{radius} km is inside the Earth (earth_radius_m {re:.0f} m); give the distance "
                                f"from the Earth's centre in km (e.g. 7000)")
    else:
        alt = s.number("altitude_km", 420.0)
    s.allow("altitude_km", "radius_km")
    if not alt > 0.0:
        s.fail("altitude_km", f"{alt} km is inside the Earth; give the height above the surface in km (e.g. 420)")
    inc = s.number("inclination_deg", 51.6)
    if not 0.0 <= inc <= 180.0:
        s.fail("inclination_deg", f"{inc} deg is outside 0...180")
    raan = s.number("raan_deg", 0.0)
    u0 = s.number("arg_latitude_deg", 0.0)
    j2 = s.boolean("j2", False)
    j2c = s.number("j2_coefficient", J2_EARTH, nonneg=True)
    s.finish()
    return OrbitConfig(type="circular", altitude_km=alt, inclination_deg=inc, raan_deg=raan, arg_latitude_deg=u0,
                       j2=j2, mu_m3_s2=mu, earth_radius_m=re, j2_coefficient=j2c)


def _field(s: _Section) -> FieldConfig:
    model = s.string("model", "dipole", FIELD_MODELS)
    b_orbit = s.vec3("b_orbit_t", (0.0, 0.0, 0.0))
    if model == "orbit_constant" and b_orbit == (0.0, 0.0, 0.0) and not s.has("b_orbit_t"):
        s.fail("b_orbit_t", "model orbit_constant needs the field in the orbit frame, tesla "
                            "(e.g. [3.0e-5, 3.0e-5, 3.0e-5])")
    g10 = s.number("g10_nt", IGRF2025_G10_NT)
    g11 = s.number("g11_nt", IGRF2025_G11_NT)
    h11 = s.number("h11_nt", IGRF2025_H11_NT)
    rr = s.number("reference_radius_m", IGRF_REFERENCE_RADIUS_M, positive=True)
    rate = s.number("earth_rotation_rate_rad_s", EARTH_ROTATION_RATE)
    angle = s.number("earth_rotation_angle_deg", None, allow_none=True)
    step = s.number("table_step_s", 1.0, positive=True)
    if model == "wmm2025" and step > 1.0:
        s.fail("table_step_s", f"{step} s: evaluate the WMM at <= 1 Hz (table_step_s <= 1)")
    if model == "igrf14" and step > 10.0:  # a 10 s table is within 3.4 nT of direct evaluation (SIM-IGRF-006)
        s.fail("table_step_s", f"{step} s: evaluate IGRF-14 at least every 10 s (table_step_s <= 10)")
    s.finish()
    return FieldConfig(model=model, g10_nt=g10, g11_nt=g11, h11_nt=h11, reference_radius_m=rr,
                       earth_rotation_rate_rad_s=rate, earth_rotation_angle_deg=angle, table_step_s=step,
                       b_orbit_t=b_orbit)


def _magnetometer(s: _Section) -> MagnetometerSpec:
    d = MagnetometerSpec()
    spec = MagnetometerSpec(
        ideal=s.boolean("ideal", d.ideal),
        odr_hz=s.number("odr_hz", d.odr_hz, positive=True),
        noise_std_gauss=s.number("noise_std_gauss", d.noise_std_gauss, nonneg=True),
        bias_gauss=s.vec3("bias_gauss", d.bias_gauss),
        resolution_gauss=s.number("resolution_gauss", d.resolution_gauss, nonneg=True),
        full_scale_gauss=s.number("full_scale_gauss", d.full_scale_gauss, positive=True),
        coupling_t_per_am2=s.vec3("coupling_t_per_am2", d.coupling_t_per_am2),
    )
    s.finish()
    return spec


def _gyro(s: _Section) -> GyroSpec:
    d = GyroSpec()
    spec = GyroSpec(
        ideal=s.boolean("ideal", d.ideal),
        odr_hz=s.number("odr_hz", d.odr_hz, positive=True),
        noise_density_dps_rthz=s.number("noise_density_dps_rthz", d.noise_density_dps_rthz, nonneg=True),
        bias_dps=s.vec3("bias_dps", d.bias_dps),
        full_scale_dps=s.number("full_scale_dps", d.full_scale_dps, positive=True),
        resolution_dps=s.number("resolution_dps", None, nonneg=True, allow_none=True),
    )
    s.finish()
    return spec


def _star_tracker(s: _Section) -> StarTrackerSpec:
    d = StarTrackerSpec()
    bore = s.vec3("boresight_B", d.boresight_B)
    if bore == (0.0, 0.0, 0.0):
        s.fail("boresight_B", "the boresight must not be the zero vector")
    spec = StarTrackerSpec(
        ideal=s.boolean("ideal", d.ideal),
        rate_hz=s.number("rate_hz", d.rate_hz, positive=True),
        noise_cross_boresight_arcsec=s.number("noise_cross_boresight_arcsec", d.noise_cross_boresight_arcsec,
                                              nonneg=True),
        noise_about_boresight_arcsec=s.number("noise_about_boresight_arcsec", d.noise_about_boresight_arcsec,
                                              nonneg=True),
        boresight_B=unit(bore),
        bias_arcsec=s.vec3("bias_arcsec", d.bias_arcsec),
        dropout_probability=s.number("dropout_probability", d.dropout_probability, nonneg=True),
        max_rate_deg_s=s.number("max_rate_deg_s", d.max_rate_deg_s, nonneg=True),
        sun_exclusion_deg=s.number("sun_exclusion_deg", d.sun_exclusion_deg, nonneg=True),
        outage_s=_outage(s),
    )
    if spec.sun_exclusion_deg >= 180.0:
        s.fail("sun_exclusion_deg",
               f"{spec.sun_exclusion_deg} deg would blind the tracker everywhere: give 0 (off) ... < 180")
    if spec.dropout_probability > 1.0:
        s.fail("dropout_probability", f"{spec.dropout_probability} is a probability: give 0...1")
    s.finish()
    return spec


def _sun_sensors(s: _Section) -> SunSensorSpec:
    """``sensors.sun_sensors``: the light sensors' noise figures, the Earth's albedo and the penumbra (absent: the
    ``SunSensorSpec`` defaults, as the deployments fly)."""
    d = SunSensorSpec()
    gain = s.number("gain_sigma", d.gain_sigma, nonneg=True)
    noise = s.number("noise_sigma", d.noise_sigma, nonneg=True)
    albedo = s.number("albedo", d.albedo, nonneg=True)
    penumbra = s.boolean("penumbra", d.penumbra)
    s.finish()
    try:
        return SunSensorSpec(gain_sigma=gain, noise_sigma=noise, albedo=albedo, penumbra=penumbra)
    except ValueError as exc:
        key = next((k for k in ("gain_sigma", "noise_sigma") if f"SunSensorSpec.{k} " in str(exc)), "albedo")
        s.fail(key, str(exc).replace("SunSensorSpec.", ""))


def _outage(s: _Section) -> tuple[float, float] | None:
    """``sensors.star_tracker.outage_s``: ``[start, end]`` s of plant time with no solution (absent: none)."""
    v = s.raw("outage_s", None)
    if v is None:
        return None
    p = s.path + ("outage_s",)
    if not isinstance(v, (list, tuple)) or len(v) != 2:
        s.ctx.fail(p, f"expected [start, end] in seconds, got {v!r}")
    start, end = s.ctx.number(p + (0,), v[0], nonneg=True), s.ctx.number(p + (1,), v[1], nonneg=True)
    if not end > start:
        s.ctx.fail(p, f"the outage must end after it starts: got [{start}, {end}] s")
    return (start, end)


def _initial(s: _Section, seed: int) -> tuple[Quat, str, Vec3]:
    att = s.section("attitude")
    frame = att.string("frame", "inertial", ("inertial", "orbit"))
    if att.has("quaternion") and att.has("mrp"):
        att.fail("mrp", "give either quaternion or mrp, not both")
    if att.has("mrp"):
        sigma = att.vec3("mrp", None)
        q = mrp_to_quat(sigma)
    else:
        v = att.raw("quaternion", [1.0, 0.0, 0.0, 0.0])
        p = att.path + ("quaternion",)
        if not isinstance(v, (list, tuple)) or len(v) != 4:
            s.ctx.fail(p, "expected 4 numbers [q0, q1, q2, q3] (scalar first)")
        qs = tuple(s.ctx.number(p + (i,), x) for i, x in enumerate(v))
        n = math.sqrt(sum(x * x for x in qs))
        if abs(n - 1.0) > 1e-6:
            s.ctx.fail(p, f"must be a unit quaternion (scalar first); its norm is {n:.9g}")
        q = quat_normalize((qs[0], qs[1], qs[2], qs[3]))
    att.finish()

    rate = s.section("rate")
    given = [k for k in ("omega_deg_s", "omega_rad_s", "magnitude_deg_s") if rate.has(k)]
    if len(given) > 1:
        rate.fail(given[1], f"give one of omega_deg_s, omega_rad_s or magnitude_deg_s (+ axis), not "
                            f"{' and '.join(given)}")
    rate.allow("omega_deg_s", "omega_rad_s", "magnitude_deg_s", "axis", "random_axis", "seed")
    if rate.has("omega_deg_s") or rate.has("omega_rad_s"):
        if rate.has("omega_rad_s"):
            omega = rate.vec3("omega_rad_s", None)
        else:
            w = rate.vec3("omega_deg_s", None)
            omega = (math.radians(w[0]), math.radians(w[1]), math.radians(w[2]))
    else:
        mag = rate.number("magnitude_deg_s", 0.0, nonneg=True)
        random_axis = rate.boolean("random_axis", False)
        if random_axis:
            if rate.has("axis"):
                rate.fail("axis", "give either axis or random_axis: true, not both")
            rseed = rate.integer("seed", seed)
            rng = random.Random(rseed)
            while True:
                a = (rng.gauss(0.0, 1.0), rng.gauss(0.0, 1.0), rng.gauss(0.0, 1.0))
                if sum(x * x for x in a) > 1e-12:
                    break
        else:
            a = rate.vec3("axis", (1.0, 0.0, 0.0))
            if a == (0.0, 0.0, 0.0):
                rate.fail("axis", "the rotation axis must not be the zero vector")
        e = unit(a)
        r = math.radians(mag)
        omega = (r * e[0], r * e[1], r * e[2])
    rate.finish()
    s.finish()
    return q, frame, omega


def _control(s: _Section, dt: float) -> ControlConfig:
    law = s.string("law", "none", LAWS)
    gain = s.number("gain", None, positive=True, allow_none=True)
    period = s.number("period_s", dt, positive=True)
    settle = s.number("sense_settle_s", 0.0, nonneg=True)
    for key, val in (("period_s", period), ("sense_settle_s", settle)):
        n = val / dt
        if abs(n - round(n)) > 1e-6:
            s.fail(key, f"{val} s must be a whole number of dynamics steps ({dt} s)")
    if settle >= period:
        s.fail("sense_settle_s", f"{settle} s must be shorter than period_s ({period} s)")
    saturation = s.string("saturation", "scale", SATURATION)
    beta = s.section("beta_pd")
    beta_pd = BetaPdConfig(k_s=beta.number("k_s", BetaPdConfig.k_s), k_d=beta.number("k_d", BetaPdConfig.k_d),
                           switched=beta.boolean("switched", BetaPdConfig.switched))
    beta.finish()
    wheels = s.section("wheels_pd")
    target = wheels.raw("target_q_bo", list(WheelsPdConfig.target_q_bo))
    if not isinstance(target, (list, tuple)) or len(target) != 4:
        wheels.fail("target_q_bo", f"expected 4 numbers (scalar first), got {target!r}")
    tq = [s.ctx.number(wheels.path + ("target_q_bo", i), x) for i, x in enumerate(target)]
    q = (tq[0], tq[1], tq[2], tq[3])
    if not math.sqrt(sum(c * c for c in q)) > 0.0:
        wheels.fail("target_q_bo", "the target quaternion must not be zero")
    wheels_pd = WheelsPdConfig(k_p=wheels.number("k_p", WheelsPdConfig.k_p),
                               k_d=wheels.number("k_d", WheelsPdConfig.k_d),
                               target_q_bo=q,
                               limits=wheels.string("limits", WheelsPdConfig.limits, ("report", "wheel")),
                               error=wheels.string("error", WheelsPdConfig.error, ("report", "shortest_path")),
                               dump_gain=wheels.number("dump_gain", WheelsPdConfig.dump_gain, nonneg=True))
    wheels.finish()
    adcs = _adcs(s.section("adcs"))
    s.finish()
    return ControlConfig(law=law, gain=gain, period_s=period, sense_settle_s=settle, saturation=saturation,
                         beta_pd=beta_pd, wheels_pd=wheels_pd, adcs=adcs)


def _target_changes(a: _Section) -> tuple:
    """``control.adcs.target_changes``: ``[[t_s, q0, q1, q2, q3], ...]`` (SET_TARGET_QUATERNION) or a moving
    target's command ``[t_s, NADIR, p, s]``, ``[t_s, SUN, p, s]``, ``[t_s, GROUND_STATION, lat, lon, alt, p, s]``
    (axes by BodyAxis name); times ≥ 0 in order, each target as its command would accept it."""
    raw = a.raw("target_changes", None)
    if raw is None:
        return ()
    if not isinstance(raw, (list, tuple)):
        a.fail("target_changes", f"expected a list of [t_s, q0, q1, q2, q3] or [t_s, NADIR, p, s], got {raw!r}")
    changes: list[tuple[float, tuple]] = []
    for i, entry in enumerate(raw):
        moving = isinstance(entry, (list, tuple)) and len(entry) >= 2 and isinstance(entry[1], str)
        if not isinstance(entry, (list, tuple)) or not moving and len(entry) != 5:
            a.fail("target_changes", f"entry {i}: expected [t_s, q0, q1, q2, q3] or [t_s, NADIR, p, s], got {entry!r}")
        t = a.ctx.number(a.path + ("target_changes", i, 0), entry[0])
        q = tuple(entry[1:]) if moving else tuple(a.ctx.number(a.path + ("target_changes", i, j), x)
                                                  for j, x in enumerate(entry) if j)
        if t < 0.0:
            a.fail("target_changes", f"entry {i}: the time {t!r} s is negative")
        if changes and t < changes[-1][0]:
            a.fail("target_changes", f"entry {i}: {t!r} s comes before the previous entry's {changes[-1][0]!r} s; "
                   "list the changes in time order")
        why = target_entry_error(q)
        if why is not None:
            a.fail("target_changes", f"entry {i}: {why}")
        changes.append((t, q))
    return tuple(changes)


def _adcs(a: _Section):
    """``control.adcs`` (see :data:`AdcsConfig`)."""
    values: dict[str, Any] = {}
    target = a.raw("target_q_bn", None)
    if target is not None:
        if not isinstance(target, (list, tuple)) or len(target) != 4:
            a.fail("target_q_bn", f"expected 4 numbers (q_TN, scalar first) or null, got {target!r}")
        q = tuple(a.ctx.number(a.path + ("target_q_bn", i), x) for i, x in enumerate(target))
        if not is_unit_quaternion(q):
            a.fail("target_q_bn", "must be a unit quaternion (within 1e-3), as SET_TARGET_QUATERNION requires")
        values["target_q_bn"] = q
    values["bdot_provider"] = a.boolean("bdot_provider", True)
    values["bdot_provider_gain"] = a.number("bdot_provider_gain", BDOT_PROVIDER_GAIN, nonneg=True)
    values["auto_start_s"] = a.number("auto_start_s", 0.0, nonneg=True)
    if a.raw("force_mode", None) is not None:
        values["force_mode"] = a.string("force_mode", "POINTING", ("DETUMBLE", "SPIN_STABLE", "POINTING"))
    values["force_at_s"] = a.number("force_at_s", 0.0, nonneg=True)
    values["target_changes"] = _target_changes(a)
    for name, default in ADCS_DEFAULTS.items():
        if name in ADCS_ENUMS:
            values[name] = a.string(name, str(default), ADCS_ENUMS[name])
        elif isinstance(default, int):
            v = a.number(name, default, positive=True)
            if v != int(v):
                a.fail(name, f"expected a whole number, got {v!r}")
            values[name] = int(v)
        else:
            values[name] = a.number(name, float(default))
    a.finish()
    return AdcsConfig(**values)
