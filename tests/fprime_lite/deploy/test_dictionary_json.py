"""``dumps_indented``: the text of ``json.dumps(obj, indent=2)``, written without the json module's
pure-Python encoder (issue 32: writing dictionary.json was three quarters of a run's fixed output cost).

DICTJSON-001 random plain documents, DICTJSON-002 the reference deployments' dictionaries,
DICTJSON-003 documents that are not plain JSON (left to json.dumps), DICTJSON-004 the fast path is
the one a plain document takes.
"""

from __future__ import annotations

import enum
import json
import random
from pathlib import Path

import pytest

from fprime_lite.deploy import dictionary
from fprime_lite.deploy.dictionary import build_dictionary, dumps_indented
from fprime_lite.deploy.topology_loader import load_topology

ROOT = Path(__file__).resolve().parents[3]

_WORDS = ["", "a", "ünïcode", "quote\"d", "back\\slash", "tab\tnew\nline", "\x00\x1f", "𝄞 clef", "{[,]}: ",
          "NaN", "null", "  spaced  "]
_FLOATS = [0.0, -0.0, 1.0, -2.5, 0.1, 1e300, -1e-300, 5e-324, 1.7976931348623157e308, 123456789.125, 1e16, 1e-7]


def _scalar(rng: random.Random):
    kind = rng.randrange(7)
    if kind == 0:
        return rng.choice(_WORDS) + str(rng.randrange(100))
    if kind == 1:
        return rng.choice([0, 1, -1, 2**31, -(2**63), 2**64 + 7, rng.randrange(-10**6, 10**6)])
    if kind == 2:
        return rng.choice(_FLOATS) if rng.random() < 0.5 else rng.uniform(-1e6, 1e6)
    if kind == 3:
        return rng.random() < 0.5
    if kind == 4:
        return None
    if kind == 5:
        return {}
    return rng.choice([[], ()])


def _document(rng: random.Random, depth: int):
    if depth == 0 or rng.random() < 0.3:
        return _scalar(rng)
    n = rng.randrange(5)
    kind = rng.randrange(3)
    if kind == 0:
        return {rng.choice(_WORDS) + str(k): _document(rng, depth - 1) for k in range(n)}
    items = [_document(rng, depth - 1) for _ in range(n)]
    return items if kind == 1 else tuple(items)


@pytest.mark.parametrize("seed", range(8))
def test_random_plain_documents_are_json_dumps_text(seed):
    """DICTJSON-001."""
    rng = random.Random(seed)
    for _ in range(300):
        doc = _document(rng, 5)
        assert dumps_indented(doc) == json.dumps(doc, indent=2)


@pytest.mark.parametrize("topology", ["deployments/proves_ref/topology.yaml", "deployments/adcs_ref/topology.yaml"])
def test_reference_dictionaries_are_json_dumps_text(topology):
    """DICTJSON-002."""
    doc = build_dictionary(load_topology(ROOT / topology).topology)
    assert dumps_indented(doc) == json.dumps(doc, indent=2)


class _Level(enum.IntEnum):
    LOW = 1


class _Text(str):
    pass


@pytest.mark.parametrize("doc", [
    {"x": float("nan")}, [float("inf"), -float("inf")], {"level": _Level.LOW}, [True, 1, _Level.LOW],
    {1: "int key"}, {2.5: "float key", True: "bool key", None: "null key"}, {"a": _Text("sub")},
    {_Text("key"): 1}, [1.0, type("F", (float,), {})(2.0)],
])
def test_documents_that_are_not_plain_json_are_json_dumps_text(doc):
    """DICTJSON-003: what json.dumps writes for them (NaN, subclasses, other keys)."""
    assert dumps_indented(doc) == json.dumps(doc, indent=2)


def test_a_document_json_dumps_refuses_raises_as_json_dumps_does():
    """DICTJSON-003: a cycle, an object json cannot write."""
    cycle: list = [1]
    cycle.append(cycle)
    with pytest.raises(ValueError, match="Circular reference"):
        dumps_indented({"a": cycle})
    with pytest.raises(TypeError, match="not JSON serializable"):
        dumps_indented({"a": [object()]})


def test_a_plain_document_does_not_use_json_dumps(monkeypatch):
    """DICTJSON-004: the fast path is taken (json.dumps is only the fallback)."""
    def refuse(*_args, **_kwargs):
        raise AssertionError("json.dumps called for a plain document")

    doc = {"a": [1, 2.5, "x", None, True, {"b": []}], "c": {}}
    want = json.dumps(doc, indent=2)
    monkeypatch.setattr(dictionary.json, "dumps", refuse)
    assert dumps_indented(doc) == want
