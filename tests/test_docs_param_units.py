"""UNITS-006: the parameter tables of docs/components/*.md show the units the code declares.

Each page's table with a "name" and a "units" column is read; every row that names a parameter of
the component (or, in the DetumbleManager's compact coil rows, ``X_PLUS_VOLTAGE / RESISTANCE / …``
with units ``V / Ω / …``) must begin its units cell with the declaration's ``units=`` (``—`` when it
declares none), and every parameter of the component must be in the table. The component classes
are found through the reference topologies (by their ``type:``), so a module that moves needs no
change here.
"""

from __future__ import annotations

import importlib
import pathlib

import pytest
import yaml

ROOT = pathlib.Path(__file__).resolve().parents[1]

PAGES = [  # page, topology, instance
    ("detumble_manager.md", "deployments/proves_ref/topology.yaml", "detumbleManager"),
    ("mode_manager.md", "deployments/proves_ref/topology.yaml", "modeManager"),
    ("startup_manager.md", "deployments/proves_ref/topology.yaml", "startupManager"),
    ("simulated_drivers.md", "deployments/proves_ref/topology.yaml", "imuManager"),
    ("bdot_detumble.md", "deployments/proves_ref/topology_bdot_detumble.yaml", "bdotDetumble"),
    ("coursework_controller.md", "deployments/coursework/topology.yaml", "controller"),
    ("attitude_controller.md", "deployments/adcs_ref/topology.yaml", "attitudeController"),
]


def _component_class(topology: str, instance: str) -> type:
    doc = yaml.safe_load((ROOT / topology).read_text())
    for module in doc.get("modules", {}).values():
        spec = (module.get("instances") or {}).get(instance)
        if spec is not None:
            path, _, name = spec["type"].rpartition(".")
            return getattr(importlib.import_module(path), name)
    raise LookupError(f"{topology} has no instance {instance}")


def _table_rows(text: str) -> list[tuple[str, str]]:
    """(name cell, units cell) of every row of every table whose header has both columns."""
    rows, columns = [], None
    for line in text.splitlines():
        if not line.startswith("|"):
            columns = None
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if columns is None:
            header = [c.lower() for c in cells]
            columns = (header.index("name"), header.index("units")) if {"name", "units"} <= set(header) else ()
        elif columns and not set(line) <= set("|-: "):
            rows.append((cells[columns[0]].replace("`", ""), cells[columns[1]]))
    return rows


def _expand(name_cell: str, units_cell: str) -> list[tuple[str, str]]:
    """``X_PLUS_VOLTAGE / RESISTANCE``, ``V / Ω`` → [(X_PLUS_VOLTAGE, V), (X_PLUS_RESISTANCE, Ω)]."""
    if " / " not in name_cell:
        return [(name_cell, units_cell)]
    first, *rest = name_cell.split(" / ")
    prefix = first.rsplit("_", 1)[0] + "_"
    return list(zip([first, *(prefix + r for r in rest)], units_cell.split(" / "), strict=True))


@pytest.mark.parametrize("page, topology, instance", PAGES, ids=[p[0] for p in PAGES])
def test_component_page_shows_the_declared_units(page, topology, instance):
    params = {p.name: p for p in _component_class(topology, instance).__fprime_spec__.params}
    seen = set()
    for name_cell, units_cell in _table_rows((ROOT / "docs" / "components" / page).read_text()):
        for name, units in _expand(name_cell, units_cell):
            if name in params:
                want = params[name].units or "—"
                assert units.startswith(want), f"{page}: {name} shows units {units!r}, the code declares {want!r}"
                seen.add(name)
    assert seen == set(params), f"{page}: parameters missing from its table: {sorted(set(params) - seen)}"
