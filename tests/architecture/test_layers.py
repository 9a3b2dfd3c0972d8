"""The import rule: a lower layer never imports a higher one (docs/architecture.md, "Layers").

Every ``import`` and ``from … import`` in ``src/`` is read with :mod:`ast` — at module level, inside
functions and under ``TYPE_CHECKING``, absolute and relative, and ``importlib.import_module("…")`` /
``__import__("…")`` with a literal name — resolved to the layer of the module it names, and checked
against the layer of the module that contains it. Every folder of ``src/`` that holds Python must be
a layer this file classifies: a new folder fails until it is given a place in the rule.

The checker takes the source root as an argument, so the tests at the end feed it small synthetic
trees, one per kind of violation, and see it report each: it cannot pass by seeing nothing.
"""
from __future__ import annotations

import ast
import pathlib

import pytest

SRC = pathlib.Path(__file__).resolve().parents[2] / "src"

#: Framework layers, lowest first. A module may import its own layer and any lower one.
FRAMEWORK_LAYERS = ["osal", "model", "wire", "svc", "deploy", "ground", "tools"]
#: Framework packages beside the ladder: the highest framework layer each may use, and who may import it.
FRAMEWORK_SIDE = {"testing": ("model", {"tools"})}
#: What the framework's root (``fprime_lite/__init__.py``, the re-exports) may import, and the layer
#: an import of the root counts as (``from fprime_lite import F64`` is an import of the model).
FRAMEWORK_ROOT_IMPORTS = {"osal", "model"}
FRAMEWORK_ROOT_LAYER = "model"

#: Application layers, lowest first, and what each may import besides itself: the application layers
#: below it, and the highest framework layer (None: no framework at all). ``components`` (the flight
#: software) skips the plant: it may use the control laws but never ``sim`` or ``analysis``.
APPLICATION = {
    "control": (set(), None),
    "analysis": (set(), None),
    "sim": ({"control", "analysis"}, None),
    "components": ({"control"}, "ground"),
    "drivers": ({"components", "sim", "control", "analysis"}, "ground"),
    "proves": ({"drivers", "components", "sim", "control", "analysis"}, "ground"),
    "reports": ({"proves", "drivers", "components", "sim", "control", "analysis"}, "tools"),
    "tools": ({"reports", "proves", "drivers", "components", "sim", "control", "analysis"}, "tools"),
}
#: What the application's root (``detumble/__init__.py``) may import: nothing of the project.
APPLICATION_ROOT_IMPORTS: set[str] = set()

PACKAGES = {"fprime_lite": set(FRAMEWORK_LAYERS) | set(FRAMEWORK_SIDE), "detumble": set(APPLICATION)}


def _layer(module: str) -> tuple[str, str] | None:
    """(package, layer) of a dotted module name inside the project ('' for the package root), else None."""
    parts = module.split(".")
    if parts[0] not in PACKAGES:
        return None
    return parts[0], (parts[1] if len(parts) > 1 else "")


def _module_name(src: pathlib.Path, path: pathlib.Path) -> str:
    return ".".join(path.relative_to(src).with_suffix("").parts).removesuffix(".__init__")


def _imports(src: pathlib.Path, path: pathlib.Path) -> list[tuple[int, str]]:
    """(line, dotted module) of every import in ``path``; ``from fprime_lite import a`` (a package root)
    names ``fprime_lite`` and ``fprime_lite.a``, which is a layer when ``a`` is one."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    module = _module_name(src, path)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found: list[tuple[int, str]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            found.append((node.lineno, target))
            if _layer(target) is not None and "." not in target:  # `from fprime_lite import tools` names a layer
                found += [(node.lineno, f"{target}.{alias.name}") for alias in node.names if alias.name != "*"]
        elif isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Constant) \
                and isinstance(node.args[0].value, str):
            func = node.func
            name = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
            if name in {"import_module", "__import__"}:
                found.append((node.lineno, node.args[0].value))
    return found


def _allowed(src: tuple[str, str], dst: tuple[str, str]) -> bool:
    """May a module of layer ``src`` import one of layer ``dst`` (each ``(package, layer)``)?"""
    (src_pkg, src_layer), (dst_pkg, dst_layer) = src, dst
    if src_pkg == "fprime_lite":
        if dst_pkg != "fprime_lite":
            return False  # the framework never imports the application
        if src_layer == dst_layer:
            return True
        if dst_layer == "":
            dst_layer = FRAMEWORK_ROOT_LAYER
        if src_layer == "":
            return dst_layer in FRAMEWORK_ROOT_IMPORTS
        if dst_layer in FRAMEWORK_SIDE:
            return src_layer in FRAMEWORK_SIDE[dst_layer][1]
        ceiling = FRAMEWORK_SIDE[src_layer][0] if src_layer in FRAMEWORK_SIDE else src_layer
        return FRAMEWORK_LAYERS.index(dst_layer) <= FRAMEWORK_LAYERS.index(ceiling)
    if src_layer == "":
        return dst_pkg == "detumble" and dst_layer in APPLICATION_ROOT_IMPORTS
    below, framework_ceiling = APPLICATION[src_layer]
    if dst_pkg == "detumble":  # the root imports nothing (APPLICATION_ROOT_IMPORTS): importing it is harmless
        return dst_layer in {"", src_layer} or dst_layer in below
    if framework_ceiling is None or dst_layer in FRAMEWORK_SIDE:
        return False
    if dst_layer == "":
        dst_layer = FRAMEWORK_ROOT_LAYER
    return FRAMEWORK_LAYERS.index(dst_layer) <= FRAMEWORK_LAYERS.index(framework_ceiling)


def unclassified(src: pathlib.Path) -> list[str]:
    """Folders (and top-level modules) of ``src`` holding Python that the rule does not classify."""
    problems = []
    folders = sorted({p.parent for p in src.rglob("*.py") if "__pycache__" not in p.parts})
    for folder in folders:
        parts = folder.relative_to(src).parts
        if not parts:
            problems += [f"{p.name}: a top-level module the layer rule does not classify"
                         for p in sorted(folder.glob("*.py"))]
        elif parts[0] not in PACKAGES:
            problems.append(f"{folder.relative_to(src)}/: a package the layer rule does not classify")
        elif len(parts) > 1 and parts[1] not in PACKAGES[parts[0]]:
            problems.append(f"{folder.relative_to(src)}/: a folder the layer rule does not classify — "
                            f"give it a place in tests/architecture/test_layers.py and docs/architecture.md")
    return problems


def violations(src: pathlib.Path) -> list[str]:
    """Every import in ``src`` that the rule forbids, and every folder it does not classify."""
    problems = unclassified(src)
    for path in sorted(src.rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        module = _module_name(src, path)
        here = _layer(module)
        if here is None or (here[1] and here[1] not in PACKAGES[here[0]]):
            continue  # reported above
        for line, target in _imports(src, path):
            there = _layer(target)
            if there is None or (there[1] and there[1] not in PACKAGES[there[0]]):
                continue  # outside the project, or a top-level module of a package (reported if it exists)
            if not _allowed(here, there):
                problems.append(f"{path.relative_to(src)}:{line}: {module} imports {target}")
    return problems


def test_no_module_imports_a_higher_layer():
    """ARCH-001: lower layers never import higher ones; the framework never imports detumble;
    control laws, analysis and physics import no framework; every folder of src/ is classified."""
    assert violations(SRC) == []


def test_every_classified_layer_exists():
    """ARCH-003: the rule names no folder that is gone (a renamed folder is renamed here too)."""
    for package, layers in PACKAGES.items():
        missing = sorted(layer for layer in layers if not (SRC / package / layer / "__init__.py").is_file())
        assert missing == [], f"{package}: classified but not in src/: {missing}"


@pytest.mark.parametrize("source, target, allowed", [
    (("fprime_lite", "svc"), ("fprime_lite", "deploy"), False),
    (("fprime_lite", "model"), ("fprime_lite", "wire"), False),
    (("fprime_lite", "tools"), ("detumble", "sim"), False),
    (("fprime_lite", "model"), ("fprime_lite", "testing"), False),
    (("fprime_lite", "tools"), ("fprime_lite", "testing"), True),
    (("detumble", "sim"), ("fprime_lite", "model"), False),
    (("detumble", "sim"), ("fprime_lite", ""), False),
    (("detumble", "control"), ("fprime_lite", ""), False),
    (("detumble", "analysis"), ("fprime_lite", "osal"), False),
    (("detumble", "control"), ("detumble", "components"), False),
    (("detumble", "control"), ("detumble", "analysis"), False),
    (("detumble", "components"), ("detumble", "sim"), False),
    (("detumble", "components"), ("fprime_lite", "tools"), False),
    (("detumble", "components"), ("fprime_lite", "model"), True),
    (("detumble", "components"), ("fprime_lite", ""), True),
    (("detumble", "drivers"), ("detumble", "proves"), False),
    (("detumble", "proves"), ("detumble", "drivers"), True),
    (("detumble", "proves"), ("detumble", "reports"), False),
    (("detumble", "reports"), ("detumble", "tools"), False),
    (("detumble", "reports"), ("fprime_lite", "tools"), True),
    (("detumble", "tools"), ("detumble", "reports"), True),
    (("detumble", ""), ("detumble", "sim"), False),
    (("fprime_lite", "deploy"), ("fprime_lite", "svc"), True),
])
def test_the_rule_itself_tells_allowed_from_forbidden(source, target, allowed):
    """ARCH-002: the checker refuses the imports the rule forbids (it is not vacuous)."""
    assert _allowed(source, target) is allowed


# --- the checker on synthetic trees: one tree per kind of violation ----------------------------------

def _tree(root: pathlib.Path, files: dict[str, str]) -> pathlib.Path:
    """A source tree under ``root``: the given files, and an ``__init__.py`` in every folder."""
    for name, text in files.items():
        path = root / name
        for folder in [path.parent, *path.parent.parents]:
            if folder == root or root not in folder.parents:
                break
            folder.mkdir(parents=True, exist_ok=True)
            (folder / "__init__.py").touch()
        path.write_text(text, encoding="utf-8")
    return root


@pytest.mark.parametrize("layer", ["control", "sim", "analysis"])
@pytest.mark.parametrize("statement", [
    "from fprime_lite import F64\n",
    "import fprime_lite\n",
    "import fprime_lite.model.types\n",
    "from fprime_lite.osal import atomic\n",
    "def f():\n    from fprime_lite.model.types import F64\n    return F64\n",
    "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from fprime_lite import Time\n",
    "import importlib\nM = importlib.import_module('fprime_lite.model')\n",
])
def test_any_framework_import_from_the_framework_free_layers_is_reported(tmp_path, layer, statement):
    """ARCH-004: control, sim and analysis import no fprime_lite at all — the root's re-exports
    (``from fprime_lite import F64``) and imports inside functions included."""
    src = _tree(tmp_path, {f"detumble/{layer}/law.py": statement})
    problems = violations(src)
    assert len(problems) == 1 and problems[0].startswith(f"detumble/{layer}/law.py:")
    assert f"detumble.{layer}.law imports fprime_lite" in problems[0]


def test_an_unclassified_folder_is_reported(tmp_path):
    """ARCH-005: a folder the rule does not list fails, even when it imports nothing: an application
    folder, a framework folder, a new top-level package and a top-level module."""
    src = _tree(tmp_path, {"detumble/sitl/driver.py": "X = 1\n", "detumble/control/bdot.py": "X = 1\n",
                           "fprime_lite/extras/x.py": "X = 1\n", "newpkg/a.py": "X = 1\n", "loose.py": "X = 1\n"})
    problems = violations(src)
    assert [p.split(":")[0] for p in problems] == ["loose.py", "detumble/sitl/", "fprime_lite/extras/", "newpkg/"]
    assert "does not classify" in problems[1]


@pytest.mark.parametrize("where, statement, culprit", [
    ("detumble/drivers/wheel.py", "from detumble.reports import plots\n", "detumble.reports"),
    ("detumble/drivers/wheel.py", "from detumble.proves.mode_manager import ModeManager\n", "detumble.proves"),
    ("detumble/sim/plant.py", "from ..components import types\n", "detumble.components"),
    ("detumble/components/ctrl.py", "def f():\n    import detumble.sim.plant\n", "detumble.sim"),
    ("detumble/control/law.py", "from detumble.analysis import settling\n", "detumble.analysis"),
    ("detumble/reports/plots.py", "from detumble import tools\n", "detumble.tools"),
    ("detumble/components/ctrl.py", "from fprime_lite.tools import plugins\n", "fprime_lite.tools"),
    ("fprime_lite/model/types.py", "from fprime_lite.svc import tlm_chan\n", "fprime_lite.svc"),
    ("fprime_lite/tools/cli.py", "from detumble.tools.cli import SIM_VERB\n", "detumble.tools"),
    ("fprime_lite/model/types.py", "from fprime_lite.testing import harness\n", "fprime_lite.testing"),
])
def test_an_upward_import_is_reported(tmp_path, where, statement, culprit):
    """ARCH-006: an import of a higher layer (absolute, relative, inside a function, through a package
    root's ``from P import layer``) is reported with its file, line and target."""
    src = _tree(tmp_path, {where: statement, "detumble/reports/__init__.py": "", "detumble/tools/__init__.py": ""})
    problems = violations(src)
    assert problems and all(p.startswith(f"{where}:") for p in problems)
    assert any(culprit in p.split(" imports ")[1] for p in problems)


def test_the_allowed_imports_of_a_synthetic_tree_pass(tmp_path):
    """ARCH-007: the same checker passes a tree that keeps the rule (so the failures above are the rule's)."""
    src = _tree(tmp_path, {
        "detumble/control/law.py": "import math\n",
        "detumble/sim/plant.py": "from detumble.control.law import math\nfrom . import law2\n",
        "detumble/sim/law2.py": "",
        "detumble/components/ctrl.py": "from fprime_lite import F64\nfrom detumble.control import law\n",
        "detumble/drivers/wheel.py": "from detumble.sim.plant import math\nfrom fprime_lite.deploy import scheduler\n",
        "detumble/proves/mode.py": "from detumble.drivers import wheel\n",
        "detumble/reports/plots.py": ("from fprime_lite.tools.plugins import RunPlotter\n"
                                      "from detumble.proves import mode\n"),
        "detumble/tools/cli.py": "from detumble.reports import plots\n",
        "fprime_lite/svc/x.py": "from fprime_lite.model import types\nfrom fprime_lite import F64\n",
    })
    assert violations(src) == []
