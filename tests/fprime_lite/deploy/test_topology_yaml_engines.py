"""The topology parser with libyaml and with PyYAML's pure-Python parser, and its cache of parsed
files (``fprime_lite.deploy.topology_yaml.parse``): the bounds and the loader's own messages are the
same whichever parser PyYAML has, and a cached file is never a different answer from a fresh parse.
"""

import pathlib

import pytest

from fprime_lite.deploy.topology import TopologyError
from fprime_lite.deploy.topology_loader import read_topology
from fprime_lite.deploy.topology_yaml import parse
from fprime_lite.deploy.topology_yaml.parse import MAX_VALUES, YList, YMap, parse_yaml

REF_DIR = pathlib.Path(__file__).parents[3] / "deployments" / "proves_ref"

needs_libyaml = pytest.mark.skipif(parse._FAST_LOADER is None, reason="PyYAML without libyaml")

_BOMB = "a: &a [" + ",".join(["x"] * 10) + "]\n" + "".join(
    f"{b}: &{b} [" + ",".join([f"*{a}"] * 10) + "]\n" for a, b in zip("abcdefgh", "bcdefghi", strict=True))

#: Documents refused by the loader's own checks (bounds, tags, keys, characters), not by YAML syntax.
REFUSED = {
    "deep list": "time: " + "[" * 500 + "]" * 500 + "\n",
    "deep mapping": "a:\n" + "".join("  " * i + f"k{i}:\n" for i in range(1, 80)) + "  " * 80 + "v: 1\n",
    "deep once aliases are followed": "a: &a " + "[" * 40 + "1" + "]" * 40 + "\nb: " + "[" * 30 + "*a"
                                      + "]" * 30 + "\n",
    "self-referencing alias": "time: &loop {time_base: *loop}\n",
    "alias bomb": _BOMB,
    "too many values": "time: [" + ",".join(["0"] * (MAX_VALUES + 10)) + "]\n",
    "python tag": "a: 1\nb: !!python/name:os.system\n",
    "set tag": "a: !!set {x: null}\n",
    "tag on a mapping": "a: !!omap [x: 1]\n",
    "list as key": "a: 1\n? [x, y]\n: 2\n",
    "duplicate key": "a: 1\nb: 2\na: 3\n",
    "wide integer": "a: 0x" + "f" * 100 + "\n",
    "bad timestamp": "a: 2001-13-45\n",
    "NUL": "a: 1\nb: x\0y\n",
    "control character": "a: 1\nb: x\x07y\n",
    "not UTF-8": b"a: 1\nb: \xff\n",
}


def _problems(path: pathlib.Path, engine: str, monkeypatch) -> list[str]:
    with monkeypatch.context() as m:
        if engine == "python":
            m.setattr(parse, "_FAST_LOADER", None)
        with pytest.raises(TopologyError) as err:
            parse_yaml(path)
    return err.value.problems


@needs_libyaml
@pytest.mark.parametrize("name", sorted(REFUSED))
def test_bounds_and_messages_are_the_same_with_either_parser(tmp_path, monkeypatch, name):
    """TOPO-YAML-001: every document refused by the loader's own checks (nesting, alias expansion,
    self-reference, value count, tags, keys, characters) gives exactly the same problems, lines
    included, with libyaml and with PyYAML's pure-Python parser."""
    path = tmp_path / "t.yaml"
    data = REFUSED[name]
    path.write_bytes(data if isinstance(data, bytes) else data.encode())
    fast, python = _problems(path, "libyaml", monkeypatch), _problems(path, "python", monkeypatch)
    assert fast == python
    assert fast and all(p.startswith(f"{path}:") and " — " in p for p in fast)


def test_a_cached_file_is_a_fresh_copy(tmp_path):
    """TOPO-YAML-002: parsing an unchanged file again answers an equal value that shares no map or
    list with the first, so a caller changing what it got cannot change the next answer."""
    path = tmp_path / "t.yaml"
    path.write_text("a: {b: [1, {c: 2}]}\nd: x\n")
    first = parse_yaml(path)
    first["a"]["b"][1]["c"] = 99
    first["a"]["b"].append(3)
    first["a"].key_lines["b"] = 42
    first["d"] = "changed"
    second = parse_yaml(path)
    assert second == {"a": {"b": [1, {"c": 2}]}, "d": "x"}
    assert second["a"].key_lines["b"] == 1 and second.key_lines["d"] == 2
    assert isinstance(second["a"]["b"], YList) and isinstance(second["a"]["b"][1], YMap)


def test_a_changed_file_is_parsed_again(tmp_path):
    """TOPO-YAML-003: the cache is keyed by the file's text: a file rewritten with other content of
    the same size, or the same text at another path, is not answered from the cache."""
    one, two = tmp_path / "one.yaml", tmp_path / "two.yaml"
    one.write_text("a: 1\n")
    assert parse_yaml(one) == {"a": 1}
    one.write_text("a: 2\n")
    assert parse_yaml(one) == {"a": 2}
    two.write_text("a: 2\n")
    assert parse_yaml(two).key_lines["a"].file == two
    assert parse_yaml(one).key_lines["a"].file == one


@needs_libyaml
def test_the_cache_keeps_the_parsers_apart(tmp_path, monkeypatch):
    """TOPO-YAML-004: a file parsed with libyaml is parsed again, not answered from the cache, when
    the pure-Python parser is in use (so each parser's tests test that parser)."""
    path = tmp_path / "t.yaml"
    path.write_text("a: 1\n")
    parse_yaml(path)
    made = []
    original = parse._BoundedLoader.__init__

    def spy(self, stream):
        made.append(stream)
        original(self, stream)

    monkeypatch.setattr(parse._BoundedLoader, "__init__", spy)
    monkeypatch.setattr(parse, "_FAST_LOADER", None)
    assert parse_yaml(path) == {"a": 1}
    assert made == ["a: 1\n"]


def test_checking_twice_gives_the_same_configuration():
    """TOPO-YAML-005: the reference topology's variant (which extends it and so merges its base,
    making the base's paths absolute) checks to the same configuration the second time, when its
    base and includes come from the cache."""
    path = REF_DIR / "topology_bdot_detumble.yaml"
    parse._parsed.clear()
    first = read_topology(path)
    second = read_topology(path)
    assert first == second
    assert first.parameter_file == (REF_DIR / "flight_params.dat").resolve()
