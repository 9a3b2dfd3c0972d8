"""The import rule: a lower layer never imports a higher one (docs/architecture.md).

Every ``import`` and ``from … import`` in ``src/`` is read with :mod:`ast` (including imports
inside functions and under ``TYPE_CHECKING``), resolved to the layer of the module it names, and
checked against the layer of the module that contains it.
"""
from __future__ import annotations

import ast
import pathlib

import pytest

SRC = pathlib.Path(__file__).resolve().parents[2] / "src"

#: Framework layers, lowest first. A module may import its own layer and any lower one.
FRAMEWORK_LAYERS = ["osal", "model", "wire", "svc", "deploy", "ground", "tools"]
#: Packages beside the ladder and the highest framework layer each may use.
FRAMEWORK_SIDE = {"testing": "model"}
#: What each application layer may import: application layers, and the highest framework layer.
APPLICATION = {
    "control": ({"control"}, None),
    "analysis": ({"analysis"}, None),
    "sim": ({"sim", "control", "analysis"}, None),
    "components": ({"components", "control"}, "ground"),
    "drivers": ({"drivers", "components", "control", "sim", "analysis"}, "ground"),
    "proves": ({"proves", "drivers", "components", "control", "sim", "analysis"}, "ground"),
    "reports": ({"reports", "proves", "drivers", "components", "control", "sim", "analysis"}, "tools"),
    "tools": ({"tools", "reports", "proves", "drivers", "components", "control", "sim", "analysis"}, "tools"),
}


def _layer(module: str) -> tuple[str, str] | None:
    """(package, layer) of a dotted module name inside the project, else None."""
    parts = module.split(".")
    if parts[0] not in {"fprime_lite", "detumble"}:
        return None
    return parts[0], (parts[1] if len(parts) > 1 else "")


def _imports(path: pathlib.Path) -> list[tuple[int, str]]:
    tree = ast.parse(path.read_text(), filename=str(path))
    module = ".".join(path.relative_to(SRC).with_suffix("").parts)
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    if path.name == "__init__.py":
        package = module.rsplit(".", 1)[0] if module.endswith("__init__") else module
        package = package.removesuffix(".__init__")
    found = []
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
            # `from fprime_lite import tools` names a layer too
            for alias in node.names:
                if _layer(target) and _layer(target)[1] == "":
                    found.append((node.lineno, f"{target}.{alias.name}"))
    return found


def _allowed(src: tuple[str, str], dst: tuple[str, str]) -> bool:
    (src_pkg, src_layer), (dst_pkg, dst_layer) = src, dst
    if dst_layer == "" or dst_layer not in FRAMEWORK_LAYERS + list(FRAMEWORK_SIDE) + list(APPLICATION):
        # the package root (re-exports) or a top-level module: the root re-exports the model only
        return src_pkg == dst_pkg or dst_pkg == "fprime_lite"
    if src_pkg == "fprime_lite":
        if dst_pkg != "fprime_lite":
            return False
        if src_layer == "" :
            return dst_layer in {"model", "osal"}
        ceiling = FRAMEWORK_SIDE.get(src_layer, src_layer)
        if dst_layer in FRAMEWORK_SIDE:
            return src_layer in {dst_layer, "tools"}
        return FRAMEWORK_LAYERS.index(dst_layer) <= FRAMEWORK_LAYERS.index(ceiling)
    allowed_app, framework_ceiling = APPLICATION.get(src_layer, (set(), None))
    if dst_pkg == "detumble":
        return dst_layer in allowed_app
    if framework_ceiling is None:
        return False
    if dst_layer in FRAMEWORK_SIDE:
        return False
    return FRAMEWORK_LAYERS.index(dst_layer) <= FRAMEWORK_LAYERS.index(framework_ceiling)


def _violations() -> list[str]:
    problems = []
    for path in sorted(SRC.rglob("*.py")):
        module = ".".join(path.relative_to(SRC).with_suffix("").parts).removesuffix(".__init__")
        here = _layer(module)
        for line, target in _imports(path):
            there = _layer(target)
            if here and there and not _allowed(here, there):
                problems.append(f"{path.relative_to(SRC)}:{line}: {module} imports {target}")
    return problems


def test_no_module_imports_a_higher_layer():
    """ARCH-001: lower layers never import higher ones; the framework never imports detumble;
    control laws and physics import no framework."""
    assert _violations() == []


@pytest.mark.parametrize("source, target, allowed", [
    (("fprime_lite", "svc"), ("fprime_lite", "deploy"), False),
    (("fprime_lite", "model"), ("fprime_lite", "wire"), False),
    (("fprime_lite", "tools"), ("detumble", "sim"), False),
    (("detumble", "sim"), ("fprime_lite", "model"), False),
    (("detumble", "control"), ("detumble", "components"), False),
    (("detumble", "components"), ("fprime_lite", "model"), True),
    (("fprime_lite", "deploy"), ("fprime_lite", "svc"), True),
])
def test_the_rule_itself_tells_allowed_from_forbidden(source, target, allowed):
    """ARCH-002: the checker refuses the imports the rule forbids (it is not vacuous)."""
    assert _allowed(source, target) is allowed
