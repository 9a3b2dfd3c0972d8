"""The files a topology names: path rules, ``package:path`` resolution, and ``extends`` chains.

A path in a topology (``extends``, ``include``, ``parameter_file``, ``startup.sequence``) is
relative to the file that names it, absolute, or ``package:relative/path`` inside an installed
package. :func:`path_problem` refuses what no file system accepts (NUL, over-long names) before
anything touches the disk, so such a path is a message, not an ``OSError``.
"""

from __future__ import annotations

import importlib.util
import pathlib
import re
import sys

from fprime_lite.deploy.topology import TopologyError
from fprime_lite.deploy.topology_yaml.parse import UnreadableFile, YMap, parse_yaml
from fprime_lite.deploy.topology_yaml.problems import Problems

__all__ = ["path_problem", "resolve_path", "is_file", "read_document", "TOP_KEYS"]

TOP_KEYS = {"deployment", "extends", "resources", "modules", "patterns", "connections", "rate_groups",
            "parameter_file", "startup", "time", "run", "telemetry_packets"}

#: Longest path and path component accepted (Linux's PATH_MAX and NAME_MAX).
MAX_PATH = 4096
MAX_NAME = 255

_PACKAGE = re.compile(r"^[A-Za-z_]\w*(\.[A-Za-z_]\w*)*$")


def path_problem(value: object) -> str | None:
    """Why ``value`` cannot be a file path (with what to do), or None if it can."""
    if not isinstance(value, str) or not value.strip():
        return "must be a file path — give the path as text"
    if "\0" in value:
        return "contains a NUL character — remove it"
    if len(value) > MAX_PATH:
        return f"is {len(value)} characters long, more than {MAX_PATH} — give a shorter path"
    longest = max((len(part) for part in re.split(r"[/\\:]", value)), default=0)
    if longest > MAX_NAME:
        return f"has a name of {longest} characters, more than {MAX_NAME} — give a shorter path"
    return None


def _is_package_path(value: str) -> bool:
    package, sep, _ = value.partition(":")
    return bool(sep) and len(package) > 1 and bool(_PACKAGE.match(package))


def _package_folder(package: str) -> pathlib.Path | None:
    """The folder of an installed, non-standard-library package, found without running it."""
    if package.split(".")[0] in sys.stdlib_module_names:
        return None
    try:
        spec = importlib.util.find_spec(package)
    except (ImportError, ValueError, AttributeError):
        return None
    except Exception:  # noqa: BLE001 - finding a sub-package runs its parent's __init__; a broken one is "not found"
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    return pathlib.Path(list(spec.submodule_search_locations)[0])


def resolve_path(value: str, base_dir: pathlib.Path) -> pathlib.Path:
    """A path relative to ``base_dir``, or ``package:relative/path`` inside an installed package.

    ``value`` must have passed :func:`path_problem`.
    """
    if _is_package_path(value) and not pathlib.Path(value).is_absolute():
        package, _, rest = value.partition(":")
        folder = _package_folder(package)
        if folder is not None:
            return folder / rest
        return base_dir / value
    path = pathlib.Path(value)
    return path if path.is_absolute() else base_dir / path


def is_file(path: pathlib.Path) -> bool:
    """``path.is_file()`` that answers False instead of raising for a path the OS refuses."""
    try:
        return path.is_file()
    except (OSError, ValueError):
        return False


def _real(path: pathlib.Path) -> pathlib.Path:
    try:
        return path.resolve()
    except (OSError, ValueError, RuntimeError):
        return path.absolute()


def _absolute(value: object, folder: pathlib.Path) -> object:
    if not isinstance(value, str) or path_problem(value) or _is_package_path(value) \
            or pathlib.Path(value).is_absolute():
        return value
    return str(_real(folder) / value)


def _absolutize_paths(doc: YMap, folder: pathlib.Path) -> None:
    """Make the file paths of ``doc`` absolute, so a document merged into another keeps them."""
    if "parameter_file" in doc:
        doc["parameter_file"] = _absolute(doc["parameter_file"], folder)
    startup = doc.get("startup")
    if isinstance(startup, YMap) and "sequence" in startup:
        startup["sequence"] = _absolute(startup["sequence"], folder)
    modules = doc.get("modules")
    if isinstance(modules, YMap):
        for module in modules.values():
            if isinstance(module, YMap) and "include" in module:
                module["include"] = _absolute(module["include"], folder)


def _copy_map(m: YMap) -> YMap:
    return YMap(m, line=m.line, key_lines=m.key_lines)


def _merge_maps(base: YMap, over: YMap, deep: tuple = ()) -> YMap:
    """``base`` with ``over``'s entries added or replacing; keys in ``deep`` merge one level down."""
    out = _copy_map(base)
    for key, value in over.items():
        if key in deep and isinstance(out.get(key), YMap) and isinstance(value, YMap):
            value = _merge_maps(out[key], value)
        out[key] = value
        out.key_lines[key] = over.key_lines.get(key)
    return out


def _merge(base: YMap, over: YMap) -> YMap:
    """A topology that ``extends`` another: maps merge by name (modules, instances, resources,
    patterns, connection groups); anything else in the extending file replaces the base's."""
    out = _copy_map(base)
    out.pop("extends", None)
    for key, value in over.items():
        if key == "extends":
            continue
        if key == "modules" and isinstance(out.get(key), YMap) and isinstance(value, YMap):
            modules = _copy_map(out[key])
            for name, module in value.items():
                if isinstance(modules.get(name), YMap) and isinstance(module, YMap):
                    module = _merge_maps(modules[name], module, deep=("instances",))
                modules[name] = module
                modules.key_lines[name] = value.key_lines.get(name)
            value = modules
        elif key in ("resources", "patterns", "connections") and isinstance(out.get(key), YMap) \
                and isinstance(value, YMap):
            value = _merge_maps(out[key], value)
        out[key] = value
        out.key_lines[key] = over.key_lines.get(key)
    return out


def parse_into(path: pathlib.Path, problems: Problems, named_at: tuple[pathlib.Path, int | None] | None = None,
               ) -> object:
    """Parse ``path``; its problems go to ``problems`` (and None is returned). A file that cannot
    be read at all is reported at ``named_at`` (file, line), the key that names it, if given."""
    try:
        return parse_yaml(path)
    except UnreadableFile as exc:
        if named_at is None:
            problems.extend(exc.problems)
        else:
            problems.add(named_at[0], named_at[1], f"'{path}': {exc.problem}")
        return None
    except TopologyError as exc:
        problems.extend(exc.problems)
        return None


def read_document(path: pathlib.Path, problems: Problems, chain: tuple = (),
                  named_at: tuple[pathlib.Path, int | None] | None = None) -> YMap | None:
    """Parse ``path``; if it ``extends`` a base topology, merge it onto that base. ``named_at``:
    the 'extends' key that names ``path``, if any."""
    parsed = parse_into(path, problems, named_at)
    if parsed is None and len(problems):
        return None
    doc = problems.expect_map(path, parsed, 1, "the topology file")
    if doc is None:
        return None
    problems.check_keys(path, doc, TOP_KEYS, "the topology file")
    if chain:  # a base document: its relative paths are relative to its own folder
        _absolutize_paths(doc, path.parent)
    if "extends" not in doc:
        return doc
    line = doc.key_lines["extends"]
    target = doc["extends"]
    why = path_problem(target)
    if why is not None:
        problems.add(path, line, f"'extends' {why}")
        return doc
    base_path = resolve_path(target, path.parent)
    here = _real(path)
    if _real(base_path) in chain or _real(base_path) == here:
        problems.add(path, line, f"'extends: {target}' makes a cycle of topology files — remove it")
        return doc
    if not is_file(base_path):
        problems.add(path, line, f"base topology '{target}' not found (looked for {base_path}) — give a path "
                                 f"relative to this file, or package:path")
        return doc
    base = read_document(base_path, problems, chain + (here,), (path, line))
    return doc if base is None else _merge(base, doc)

