"""Stage 1 of loading a topology: YAML text to values that remember their file and line.

Parsing is bounded so that no file, however malformed or hostile, crashes or stalls the loader:

- the file must be UTF-8 text of at most :data:`MAX_FILE_BYTES` bytes without NUL or other
  control characters;
- nesting is at most :data:`MAX_DEPTH` levels (checked while composing, before any recursion
  gets deep), and a document expands to at most :data:`MAX_VALUES` values once aliases are
  followed (an "alias bomb" of a few hundred bytes is refused in milliseconds);
- an alias inside the node it names (a self-referencing document) is refused;
- only the YAML core schema is accepted: mappings, sequences and safe scalars (PyYAML's
  SafeLoader); any other tag (``!!python/name:``, ``!!set``, …) is an error, as are mapping
  keys that are mappings or lists, and duplicate keys.

Every refusal is a :class:`~fprime_lite.deploy.topology.TopologyError` whose problems read
``file:line: what is wrong — what to do``.
"""

from __future__ import annotations

import pathlib
from collections import OrderedDict
from typing import Any

import yaml

from fprime_lite.deploy.topology import TopologyError
from fprime_lite.model.errors import FprimeLiteError

__all__ = ["Loc", "YMap", "YList", "parse_yaml", "UnreadableFile", "kind", "MAX_FILE_BYTES", "MAX_DEPTH", "MAX_VALUES"]

#: Largest topology (or included) file read, in bytes; the reference deployment is ~6 kB.
MAX_FILE_BYTES = 256 << 10
#: Deepest nesting of mappings and lists; a topology needs 6.
MAX_DEPTH = 64
#: Most values (mappings, lists, scalars) a document may expand to once aliases are followed.
MAX_VALUES = 50_000
#: Widest integer accepted (a topology's ids, sizes and times fit 64 bits).
MAX_INT_BITS = 128
#: Problems of one file listed in full (the others are summarised in one line).
MAX_PROBLEMS = 50

_MAP_TAG = "tag:yaml.org,2002:map"
_SEQ_TAG = "tag:yaml.org,2002:seq"
_MERGE_TAG = "tag:yaml.org,2002:merge"
_CORE = "tag:yaml.org,2002:"
#: Scalar tags the loader constructs (what SafeLoader resolves plain scalars to).
_SCALAR_TAGS = {_CORE + t for t in ("str", "int", "float", "bool", "null", "timestamp", "binary")}
_STR_TAG = _CORE + "str"
#: Parsed files kept (by path, text and parser) so that unchanged includes and bases are not
#: parsed again; each hit is a fresh copy, since later stages may change what they are given.
_CACHE_SIZE = 64


def _short_tag(tag: str) -> str:
    return "!!" + tag[len(_CORE):] if tag.startswith(_CORE) else tag


class Loc(int):
    """A line number that also knows its file (so merged documents report the right file)."""

    file: pathlib.Path

    def __new__(cls, line: int, file: pathlib.Path) -> "Loc":
        loc = super().__new__(cls, line)
        loc.file = file
        return loc


class YMap(dict):
    """A mapping that remembers its line and the line of each key."""

    def __init__(self, *args: Any, line: int | None = None, key_lines: dict | None = None):
        super().__init__(*args)
        self.line = line
        self.key_lines: dict = dict(key_lines or {})


class YList(list):
    """A list that remembers its line and the line of each item."""

    def __init__(self, *args: Any, line: int | None = None, item_lines: list | None = None):
        super().__init__(*args)
        self.line = line
        self.item_lines: list = list(item_lines or [])


_TOO_MANY = (f"the document expands to more than {MAX_VALUES} values (each alias counted as a copy) — a "
             f"topology needs a few hundred; remove repeated aliases or split the file")


class _Refused(FprimeLiteError):
    """A document refused while converting; ``line`` is 1-based."""

    def __init__(self, line: int, message: str):
        super().__init__(message)
        self.line = line
        self.message = message


class _BoundedLoader(yaml.SafeLoader):
    """SafeLoader whose composer refuses nesting deeper than :data:`MAX_DEPTH` and documents of
    more than :data:`MAX_VALUES` nodes (used when PyYAML has no libyaml).

    PyYAML composes recursively, so a 500-deep document would otherwise end in RecursionError.
    """

    def __init__(self, stream: str):
        super().__init__(stream)
        self._depth = 0
        self._nodes = 0

    def compose_node(self, parent, index):
        # counted as _check_shape counts libyaml's events: every node a value, every mapping or
        # list a level, so that both parsers refuse the same documents at the same line
        event = self.peek_event()
        collection = isinstance(event, yaml.CollectionStartEvent)
        self._nodes += 1
        self._depth += collection
        try:
            if collection and self._depth > MAX_DEPTH:
                raise _Refused(event.start_mark.line + 1, f"nesting deeper than {MAX_DEPTH} levels — a topology "
                                                          f"needs a handful; flatten the document")
            if self._nodes > MAX_VALUES:
                raise _Refused(event.start_mark.line + 1, _TOO_MANY)
            return super().compose_node(parent, index)
        finally:
            self._depth -= collection


class _Converter:
    """Composed nodes to YMap/YList/scalars, with a budget and alias-cycle detection."""

    def __init__(self, loader: yaml.SafeLoader, path: pathlib.Path):
        self.loader = loader
        self.path = path
        self.budget = MAX_VALUES
        self.open: set[int] = set()   # ids of the collection nodes being converted (cycle check)
        self.problems: list[str] = []
        self._locs: dict[int, Loc] = {}

    def loc(self, node: yaml.Node) -> Loc:
        line = node.start_mark.line + 1
        loc = self._locs.get(line)
        if loc is None:
            loc = self._locs[line] = Loc(line, self.path)
        return loc

    def convert(self, node: yaml.Node, depth: int = 1) -> Any:
        self.budget -= 1
        if self.budget < 0:
            raise _Refused(node.start_mark.line + 1, _TOO_MANY)
        if depth > MAX_DEPTH:
            raise _Refused(node.start_mark.line + 1,
                           f"nesting deeper than {MAX_DEPTH} levels once aliases are followed — flatten the "
                           f"document")
        if isinstance(node, yaml.ScalarNode):
            return self.scalar(node)
        if id(node) in self.open:
            raise _Refused(node.start_mark.line + 1,
                           "an alias refers to a node that contains it (a document cannot contain itself) — "
                           "remove the alias")
        self.open.add(id(node))
        try:
            if isinstance(node, yaml.MappingNode):
                return self.mapping(node, depth)
            if isinstance(node, yaml.SequenceNode):
                return self.sequence(node, depth)
        finally:
            self.open.discard(id(node))
        raise _Refused(node.start_mark.line + 1, f"unexpected YAML node {type(node).__name__} — fix the syntax")

    def scalar(self, node: yaml.ScalarNode) -> Any:
        if node.tag == _STR_TAG:  # what SafeConstructor.construct_yaml_str returns, without its dispatch
            return node.value
        if node.tag not in _SCALAR_TAGS:
            self.refuse(node, f"tag '{_short_tag(node.tag)}' is not allowed — a topology holds plain values only "
                              f"(text, numbers, booleans, null); remove the tag")
            return None
        try:
            value = self.loader.construct_object(node, deep=True)
        except yaml.constructor.ConstructorError as exc:
            self.refuse(node, f"{exc.problem or exc} — write a plain value")
            return None
        except (ValueError, OverflowError, TypeError) as exc:
            self.refuse(node, f"value {_short(node.value)!r} cannot be read ({exc}) — write a plain "
                              f"number or quote it")
            return None
        if isinstance(value, int) and value.bit_length() > MAX_INT_BITS:
            # (a hex literal of any length converts; its decimal form would not even print)
            self.refuse(node, f"integer {_short(node.value)!r} has more than {MAX_INT_BITS} bits — a topology's "
                              f"numbers (ids, sizes, times) fit in 64 bits")
            return None
        return value

    def refuse(self, node: yaml.Node, message: str) -> None:
        if len(self.problems) < MAX_PROBLEMS:
            self.problems.append(f"{self.path}:{node.start_mark.line + 1}: {message}")
        elif len(self.problems) == MAX_PROBLEMS:
            self.problems.append(f"{self.path}:{node.start_mark.line + 1}: more problems of this kind not shown — fix "
                                 f"the ones above first")

    def check_tag(self, node: yaml.Node, expected: str, what: str) -> None:
        if node.tag != expected:
            self.refuse(node, f"tag '{_short_tag(node.tag)}' is not allowed on a {what} — a topology uses plain "
                              f"mappings and lists; remove the tag")

    def mapping(self, node: yaml.MappingNode, depth: int) -> YMap:
        self.check_tag(node, _MAP_TAG, "mapping")
        out = YMap(line=self.loc(node))
        merged: list[YMap] = []
        for key_node, value_node in node.value:
            if key_node.tag == _MERGE_TAG:
                merged.extend(self.merge_sources(value_node, depth))
                continue
            if not isinstance(key_node, yaml.ScalarNode):
                self.refuse(key_node, f"a mapping key must be a plain value, not "
                                      f"{'a mapping' if isinstance(key_node, yaml.MappingNode) else 'a list'} — "
                                      f"write a name before the ':'")
                self.convert(value_node, depth + 1)  # still checked for limits and bad values
                continue
            key = self.convert(key_node, depth + 1)
            value = self.convert(value_node, depth + 1)
            if key in out:
                self.refuse(key_node, f"duplicate key {key!r} (first at line {out.key_lines[key]}) — "
                                      f"keep one of them")
                continue
            out[key] = value
            out.key_lines[key] = self.loc(key_node)
        for source in merged:  # YAML merge keys: explicit keys win, earlier sources win
            for key, value in source.items():
                if key not in out:
                    out[key] = value
                    out.key_lines[key] = source.key_lines.get(key, out.line)
        return out

    def merge_sources(self, node: yaml.Node, depth: int) -> list[YMap]:
        value = self.convert(node, depth + 1)
        sources = value if isinstance(value, list) else [value]
        if not all(isinstance(s, YMap) for s in sources):
            self.refuse(node, "a '<<' merge key takes a mapping or a list of mappings — fix its value")
            return []
        return sources

    def sequence(self, node: yaml.SequenceNode, depth: int) -> YList:
        self.check_tag(node, _SEQ_TAG, "list")
        return YList((self.convert(n, depth + 1) for n in node.value), line=self.loc(node),
                     item_lines=[self.loc(n) for n in node.value])


def _short(text: str, limit: int = 40) -> str:
    return text if len(text) <= limit else text[:limit] + "…"


def _line_of(text: str, index: int) -> int:
    return text.count("\n", 0, max(0, index)) + 1


class UnreadableFile(TopologyError):
    """A file that cannot be read at all (``problem`` has no line: the caller may place it at the
    line that names the file)."""

    def __init__(self, path: pathlib.Path, problem: str):
        self.path = path
        self.problem = problem
        super().__init__([f"{path}: {problem}"])


def read_text(path: pathlib.Path) -> str:
    """The text of a topology file; TopologyError if it cannot be read or is not UTF-8 text."""
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_FILE_BYTES + 1)
    except (OSError, ValueError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise UnreadableFile(path, f"cannot read the file ({reason}) — give a readable topology file") from None
    if len(data) > MAX_FILE_BYTES:
        raise UnreadableFile(path, f"the file is larger than {MAX_FILE_BYTES} bytes — a topology is a few "
                                   f"kilobytes; is this the right file?")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise TopologyError([f"{path}:{line}: byte 0x{data[exc.start]:02X} is not UTF-8 text — save the file "
                             f"as UTF-8"]) from None
    nul = text.find("\0")
    if nul >= 0:
        raise TopologyError([f"{path}:{_line_of(text, nul)}: the file contains a NUL byte — a topology is text; "
                             f"remove it (is this a binary file?)"])
    return text


#: libyaml's SafeLoader when PyYAML was built with it (ten times faster), else None.
_FAST_LOADER = getattr(yaml, "CSafeLoader", None)


def _check_shape(text: str) -> None:
    """Refuse excessive nesting or size from libyaml's event stream (a loop, no recursion), so
    that composing afterwards, which recurses, stays shallow and short."""
    depth = nodes = 0
    for event in yaml.parse(text, Loader=_FAST_LOADER):
        if isinstance(event, yaml.CollectionStartEvent):
            depth += 1
            nodes += 1
            if depth > MAX_DEPTH:
                raise _Refused(event.start_mark.line + 1, f"nesting deeper than {MAX_DEPTH} levels — a topology "
                                                          f"needs a handful; flatten the document")
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= 1
        elif isinstance(event, (yaml.ScalarEvent, yaml.AliasEvent)):
            nodes += 1
        if nodes > MAX_VALUES:
            raise _Refused(event.start_mark.line + 1, _TOO_MANY)


def _reader_error_line(text: str, exc: yaml.reader.ReaderError) -> int:
    if _FAST_LOADER is not None:  # libyaml counts bytes of the UTF-8 text
        return text.encode("utf-8", "surrogatepass").count(b"\n", 0, max(0, exc.position)) + 1
    return _line_of(text, exc.position)


_parsed: "OrderedDict[tuple[str, str, bool], Any]" = OrderedDict()


def _copy(value: Any) -> Any:
    """A copy of a parsed tree (maps and lists new; scalars, which are immutable, shared)."""
    if isinstance(value, YMap):
        return YMap({k: _copy(v) for k, v in value.items()}, line=value.line, key_lines=value.key_lines)
    if isinstance(value, YList):
        return YList([_copy(v) for v in value], line=value.line, item_lines=value.item_lines)
    return value


def parse_yaml(path: pathlib.Path) -> Any:
    """Parse ``path`` safely into YMap/YList values that carry line numbers (None if empty).

    A file whose text was parsed before (same path, same text, same parser) is not parsed again:
    the result is copied from the last parse. Only files that parsed without problems are kept.
    """
    text = read_text(path)
    key = (str(path), text, _FAST_LOADER is not None)
    if key in _parsed:
        _parsed.move_to_end(key)
        return _copy(_parsed[key])
    value = _parse_text(path, text)
    _parsed[key] = value
    if len(_parsed) > _CACHE_SIZE:
        _parsed.popitem(last=False)
    return _copy(value)


def _parse_text(path: pathlib.Path, text: str) -> Any:
    loader = None
    try:
        if _FAST_LOADER is not None:
            _check_shape(text)
            loader = _FAST_LOADER(text)
        else:
            loader = _BoundedLoader(text)
        node = loader.get_single_node()
        if node is None:
            return None
        converter = _Converter(loader, path)
        value = converter.convert(node)
        if converter.problems:
            raise TopologyError(converter.problems)
        return value
    except _Refused as exc:
        raise TopologyError([f"{path}:{exc.line}: {exc.message}"]) from None
    except yaml.reader.ReaderError as exc:
        line = _reader_error_line(text, exc)
        char = chr(exc.character) if isinstance(exc.character, int) else exc.character
        raise TopologyError([f"{path}:{line}: character {char!r} is not allowed in YAML — remove it"]) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{mark.line + 1}" if mark is not None else "?"
        problem = getattr(exc, "problem", None) or str(exc)
        raise TopologyError([f"{path}:{where}: invalid YAML: {problem} — fix the syntax"]) from None
    finally:
        if loader is not None:
            loader.dispose()


def kind(value: Any) -> str:
    """How a value is described in messages (``a mapping``, ``int 3`` …)."""
    if value is None:
        return "nothing"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    return f"{type(value).__name__} {_short(repr(value))}"
