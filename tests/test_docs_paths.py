"""Every file, folder and Python name that README.md and docs/ point at exists (no stale paths after a move).

The pages name the tree in three ways, each checked here:

- repository paths (``src/…``, ``tests/…``, ``docs/…``, ``deployments/…``, ``campaigns/…``, ``benchmarks/…``,
  ``examples/…``, ``tools/…``): the file or folder exists;
- package paths (``detumble/sim/plant.py``, ``fprime_lite/svc/``): they exist under ``src/`` or ``tests/``;
- dotted names (``detumble.control.mekf.Mekf``, ``fprime_lite.tools.run``): the longest prefix that is a module
  imports and the rest are attributes of it, except the entry-point group names the framework defines.

A page may name what no longer exists where it says so: a line holding ``(formerly`` or ``(removed`` is a
record of history and is not checked.
"""
from __future__ import annotations

import importlib
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
_TOP = "src|tests|docs|deployments|campaigns|benchmarks|examples|tools"
_REPO_PATH = re.compile(rf"(?<![\w/.-])((?:{_TOP})/[\w./-]*\w/?)")
_PACKAGE_PATH = re.compile(r"(?<![\w/.-])((?:detumble|fprime_lite)/[\w./-]*\w/?)")
_DOTTED = re.compile(r"(?<![\w./-])((?:detumble|fprime_lite)(?:\.[A-Za-z_]\w*)+)")
#: Entry-point groups (pyproject ``[project.entry-points."…"]``) and logger names that are not modules.
NOT_MODULES = {"fprime_lite.verbs", "fprime_lite.bench", "fprime_lite.plots", "fprime_lite.campaign_runs",
               "fprime_lite.campaign_metrics"}
_HISTORY = ("(formerly", "(removed")
_FILE_SUFFIXES = (".md", ".py", ".yaml", ".json", ".csv", ".seq", ".c", ".png", ".txt")
#: Folders a page's path may be relative to: the checkout, and the two packages (``tools/campaign/spec.py``).
_PATH_ROOTS = (ROOT, ROOT / "src", ROOT / "tests", ROOT / "src" / "fprime_lite", ROOT / "src" / "detumble")


def _placeholder(line: str, m: re.Match) -> bool:
    """``deployments/NAME/topology.yaml``, ``tests/.../typecheck/``, ``docs/img/reference_run_*.png``: a pattern,
    not a path."""
    path, after = m.group(1), line[m.end():m.end() + 1]
    return ("..." in path or after in ("*", "<", "{")
            or any(part.isupper() and len(part) <= 6 for part in path.split("/")))


def _lines(page: pathlib.Path):
    for n, line in enumerate(page.read_text(encoding="utf-8").splitlines(), start=1):
        if not any(mark in line for mark in _HISTORY):
            yield n, line


def _dotted_name_exists(name: str) -> bool:
    parts = name.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for attr in parts[i:]:
            if not hasattr(obj, attr):
                return False
            obj = getattr(obj, attr)
        return True
    return False


def missing_names(page: pathlib.Path) -> list[str]:
    """``line: name`` for every path or dotted name of ``page`` that does not exist."""
    found = []
    for n, line in _lines(page):
        for m in (*_REPO_PATH.finditer(line), *_PACKAGE_PATH.finditer(line)):
            if not _placeholder(line, m) and not any((top / m.group(1)).exists() for top in _PATH_ROOTS):
                found.append(f"{n}: {m.group(1)}")
        for m in _DOTTED.finditer(line):
            name = m.group(1)
            if name not in NOT_MODULES and not name.endswith(_FILE_SUFFIXES) and not _dotted_name_exists(name):
                found.append(f"{n}: {name}")
    return found


@pytest.mark.parametrize("page", PAGES, ids=[str(p.relative_to(ROOT)) for p in PAGES])
def test_every_path_and_name_a_page_gives_exists(page):
    """DOC-001: a page that names a file, folder, module or class names one that is there."""
    missing = missing_names(page)
    assert missing == [], f"{page.relative_to(ROOT)} names what does not exist (line: name):\n" + "\n".join(missing)


def test_the_checker_finds_a_stale_path_a_stale_module_and_a_stale_class(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("See `src/detumble/sitl/no_such.py`, `detumble/nowhere.py`, `detumble.control.no_such`,\n"
                    "`detumble.control.mekf.NoSuchClass`; `detumble.control.mekf.Mekf` and `src/fprime_lite/` exist.\n"
                    "The file was `src/detumble/types.py` (formerly; now components/types.py).\n"
                    "Patterns: `deployments/NAME/topology.yaml`, `docs/img/run_*.png`, `tests/.../x/`, detumble.md.\n")
    assert missing_names(page) == ["1: src/detumble/sitl/no_such.py", "1: detumble/nowhere.py",
                                   "1: detumble.control.no_such", "2: detumble.control.mekf.NoSuchClass"]
