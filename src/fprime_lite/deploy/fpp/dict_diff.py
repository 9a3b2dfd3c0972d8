"""Semantic comparison of two F´ JSON dictionaries (fprime-lite's and ``fpp-to-dict``'s).

Two dictionaries are the same when they hold the same entries: commands, events, channels and
parameters keyed by name, type definitions and constants by qualified name, packet sets by name,
each entry equal field by field (numbers compared as numbers, so ``1`` and ``1.0`` agree), and the
same deployment name. List order and the versions in ``metadata`` (which say who built the file)
are not compared.
"""

from __future__ import annotations

import json
import pathlib
from typing import Any

__all__ = ["dictionary_differences", "load_dictionary"]

_KEYED = {
    "typeDefinitions": "qualifiedName",
    "constants": "qualifiedName",
    "commands": "name",
    "parameters": "name",
    "events": "name",
    "telemetryChannels": "name",
    "records": "name",
    "containers": "name",
    "telemetryPacketSets": "name",
}


def load_dictionary(path: str | pathlib.Path) -> dict:
    """Read a JSON dictionary file."""
    return json.loads(pathlib.Path(path).read_text())


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return float(a) == float(b)
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return bool(a == b)


def _field_differences(where: str, a: dict, b: dict, left: str, right: str) -> list[str]:
    out = []
    for key in sorted(a.keys() | b.keys()):
        if key not in b:
            out.append(f"{where}: field {key!r} only in {left}: {json.dumps(a[key])[:160]}")
        elif key not in a:
            out.append(f"{where}: field {key!r} only in {right}: {json.dumps(b[key])[:160]}")
        elif not _same(a[key], b[key]):
            out.append(f"{where}: {key} differs: {left} {json.dumps(a[key])[:160]} / "
                       f"{right} {json.dumps(b[key])[:160]}")
    return out


def dictionary_differences(a: dict, b: dict, *, left: str = "ours", right: str = "fpp-to-dict") -> list[str]:
    """Every difference between dictionaries ``a`` and ``b``, one line each (empty: the same)."""
    out: list[str] = []
    name_a = a.get("metadata", {}).get("deploymentName")
    name_b = b.get("metadata", {}).get("deploymentName")
    if name_a != name_b:
        out.append(f"metadata.deploymentName differs: {left} {name_a!r} / {right} {name_b!r}")
    for section in sorted(a.keys() | b.keys()):
        if section == "metadata":
            continue
        if section not in _KEYED:
            out.append(f"section {section!r} is not an F´ dictionary section")
            continue
        key = _KEYED[section]
        entries_a = {e.get(key): e for e in a.get(section, [])}
        entries_b = {e.get(key): e for e in b.get(section, [])}
        if section not in a or section not in b:
            out.append(f"section {section} only in {left if section in a else right}")
        for name in sorted(entries_a.keys() | entries_b.keys(), key=str):
            where = f"{section} {name}"
            if name not in entries_b:
                out.append(f"{where}: only in {left}")
            elif name not in entries_a:
                out.append(f"{where}: only in {right}")
            else:
                out.extend(_field_differences(where, entries_a[name], entries_b[name], left, right))
    return out
