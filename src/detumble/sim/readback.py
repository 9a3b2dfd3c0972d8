"""Scenario values read back from a built plant, for campaigns: what the simulation actually holds.

A campaign that disperses ``initial.rate.omega_deg_s`` records the rate the plant starts with, not
the number it asked for, so a setting that was silently not applied shows up in the results (the
failure Basilisk users met with dispersions). :func:`read_setting` must be called before the plant
is stepped: initial-state keys are read from the present state.

Keys use the scenario file's paths (``docs/scenarios.md``); an element of a list is addressed by
its index (``sensors.magnetometer.bias_gauss.1``).
"""

from __future__ import annotations

import dataclasses
import math

from detumble.sim.coils import FACE_NAMES
from detumble.sim.plant import Plant

__all__ = ["read_setting"]

_FACES_BY_NAME = {name: face for face, name in FACE_NAMES.items()}
_SCENARIO_FIELDS = {"duration_s", "dynamics_step_s", "record_interval_s", "seed", "name", "description"}


def _attr(obj, name: str, key: str):
    if dataclasses.is_dataclass(obj) and name in {f.name for f in dataclasses.fields(obj)}:
        return getattr(obj, name)
    raise KeyError(f"{key}: no value {name!r} here")


def _index(value, rest: list[str], key: str):
    for part in rest:
        if dataclasses.is_dataclass(value) and not isinstance(value, type):
            value = _attr(value, part, key)  # a nested section (control.beta_pd.k_s)
            continue
        if (not part.isdigit() and isinstance(value, tuple) and value
                and all(dataclasses.is_dataclass(v) for v in value)):
            # a key set for every element at once (reaction_wheels.momentum_noise_std_nms)
            each = [_attr(v, part, key) for v in value]
            value = each[0] if all(e == each[0] for e in each) else each
            continue
        if not (part.isdigit() and isinstance(value, (list, tuple)) and int(part) < len(value)):
            raise KeyError(f"{key}: {part!r} is not an element index of {value!r}")
        value = value[int(part)]
    return value


def _initial(plant: Plant, parts: list[str], key: str):
    if parts[:2] == ["rate", "omega_deg_s"]:
        return _index([math.degrees(w) for w in plant.omega_BN_B], parts[2:], key)
    if parts[:2] == ["rate", "magnitude_deg_s"]:
        return plant.rate_deg_s
    if parts[:2] == ["rate", "axis"]:  # the unit axis the scenario made of it
        w = plant.omega_BN_B
        n = math.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2)
        if n == 0.0:
            raise KeyError(f"{key}: the initial rate is zero, so it has no axis")
        return _index([x / n for x in w], parts[2:], key)
    if parts[:2] == ["attitude", "quaternion"]:
        return _index(list(plant.q_BN), parts[2:], key)
    if parts[:2] == ["attitude", "mrp"]:
        q0, q1, q2, q3 = plant.q_BN
        if q0 < 0:
            q0, q1, q2, q3 = -q0, -q1, -q2, -q3
        return _index([q1 / (1 + q0), q2 / (1 + q0), q3 / (1 + q0)], parts[2:], key)
    raise KeyError(f"{key}: the initial state is read back as initial.rate.omega_deg_s, "
                   f"initial.rate.magnitude_deg_s, initial.rate.axis (unit), initial.attitude.quaternion or "
                   f"initial.attitude.mrp")


def _spacecraft(plant: Plant, parts: list[str], key: str):
    head, rest = parts[0], parts[1:]
    if head == "inertia_kg_m2":
        return _index([list(row) for row in plant.body.inertia], rest, key)
    if head == "residual_dipole_am2":
        return _index(list(plant.residual_dipole_B), rest, key)
    if head == "wheel_momentum_nms":
        return _index(list(plant.body.wheel_momentum_B), rest, key)
    if head == "actuators" and rest and rest[0] in _FACES_BY_NAME:
        coils = getattr(plant.actuators, "coils", {})
        face = _FACES_BY_NAME[rest[0]]
        if face not in coils or len(rest) < 2:
            raise KeyError(f"{key}: no coil {rest[0]} with that value")
        return _index(_attr(coils[face].spec, rest[1], key), rest[2:], key)
    value = _attr(plant.scenario.spacecraft, head, key)
    return _index(value, rest, key)


def read_setting(plant: Plant, key: str):
    """The value of scenario key ``key`` (``initial.rate.omega_deg_s``) in the built ``plant``."""
    parts = key.split(".")
    head, rest = parts[0], parts[1:]
    if head == "initial" and rest:
        return _initial(plant, rest, key)
    if head == "spacecraft" and rest:
        return _spacecraft(plant, rest, key)
    if head == "sensors" and len(rest) >= 2 and rest[0] in ("magnetometer", "gyro"):
        sensor = plant.magnetometer if rest[0] == "magnetometer" else plant.gyro
        return _index(_attr(sensor.spec, rest[1], key), rest[2:], key)
    if head in ("orbit", "field", "control") and rest:
        return _index(_attr(getattr(plant.scenario, head), rest[0], key), rest[1:], key)
    if head in _SCENARIO_FIELDS and not rest:
        return plant.seed if head == "seed" else getattr(plant.scenario, head)
    raise KeyError(f"{key}: not a scenario key that can be read back (initial.*, spacecraft.*, sensors.*, "
                   f"orbit.*, field.*, control.*, duration_s, dynamics_step_s, seed)")
