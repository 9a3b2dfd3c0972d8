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
    """``value`` written as a YAML flow value (for ``KEY=VALUE`` settings); floats exact.

    A float is written so that YAML 1.1 (PyYAML) reads it back as a float: its resolver wants a dot
    in the mantissa and a signed exponent, so ``1e-05`` (what JSON writes) would come back as the
    string ``'1e-05'``; it is written ``1.0e-05``.
    """
    import json

    def text(v) -> str:
        if isinstance(v, float):
            if not math.isfinite(v):
                raise ValueError(f"not a finite number: {v!r}")
            r = repr(v)
            mantissa, e, exponent = r.partition("e")
            if e and "." not in mantissa:
                mantissa += ".0"
            if e and exponent[:1] not in "+-":
                exponent = "+" + exponent
            return mantissa + e + exponent
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(text(x) for x in v) + "]"
        if isinstance(v, dict):
            return "{" + ", ".join(f"{json.dumps(str(k))}: {text(x)}" for k, x in v.items()) + "}"
        return json.dumps(v)

    return text(plain(value))


def same_value(a, b, rel: float = 1e-9) -> bool:
    """Whether a read-back value equals the requested one (floats to ``rel``)."""
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same_value(x, y, rel) for x, y in zip(a, b, strict=True))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_value(a[k], b[k], rel) for k in a)
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return math.isclose(a, b, rel_tol=rel, abs_tol=rel * 1e-3)
    return a == b
