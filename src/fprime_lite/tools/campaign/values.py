"""Values as a results row holds them: plain numbers, strings, lists and mappings."""

from __future__ import annotations

import dataclasses
import enum
import math

__all__ = ["plain", "yaml_text", "same_value"]


def plain(value):
    """``value`` as JSON-able Python: enums by name, F´ structs as mappings, tuples and arrays as lists."""
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, bool) or value is None or isinstance(value, (int, str)):
        return value
    if isinstance(value, float):
        return value
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if hasattr(value, "tolist"):
        return plain(value.tolist())
    if isinstance(value, (list, tuple)) or hasattr(value, "__iter__"):
        return [plain(v) for v in value]
    return str(value)


def yaml_text(value) -> str:
    """``value`` written as a YAML flow value (for ``KEY=VALUE`` settings); floats exact."""
    import json

    return json.dumps(plain(value), allow_nan=False)


def same_value(a, b, rel: float = 1e-9) -> bool:
    """Whether a read-back value equals the requested one (floats to ``rel``)."""
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same_value(x, y, rel) for x, y in zip(a, b, strict=True))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_value(a[k], b[k], rel) for k in a)
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return math.isclose(a, b, rel_tol=rel, abs_tol=rel * 1e-3)
    return a == b
