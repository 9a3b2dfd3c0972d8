"""The parameter files the reference deployments ship hold every parameter their topologies declare.

A parameter added to a component without regenerating its deployment's file makes PrmDb answer
``PrmIdNotFound`` (a WARNING_LO on every run) and the component fly its default unannounced; the
file is made by ``fprime-lite params deployments/D/topology.yaml -o deployments/D/FILE``.
"""

import pathlib

import pytest

from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.svc.prm_db import decode_param_file

ROOT = pathlib.Path(__file__).parents[1]
DEPLOYMENTS = ("proves_ref", "adcs_ref", "coursework")


def declared_parameter_ids(topology) -> dict[int, str]:
    """Every parameter with a default in ``topology``: id → full name."""
    ids = {}
    for instance in topology.instances.values():
        comp = instance.component
        for param in comp.spec.params:
            if param.has_default:
                ids[comp.base_id + param.local_id] = f"{instance.qualified_name}.{param.name}"
    return ids


@pytest.mark.parametrize("deployment", DEPLOYMENTS)
def test_the_shipped_parameter_file_holds_every_declared_parameter(deployment):
    """PRMFILE-001: each reference deployment's parameter file has a record for exactly the
    parameters its topology declares (none missing, none stale)."""
    loaded = load_topology(str(ROOT / "deployments" / deployment / "topology.yaml"))
    assert loaded.parameter_file is not None, f"{deployment} names no parameter_file"
    held = {prm_id for prm_id, _ in decode_param_file(pathlib.Path(loaded.parameter_file).read_bytes()).records}
    declared = declared_parameter_ids(loaded.topology)
    missing = sorted(name for prm_id, name in declared.items() if prm_id not in held)
    stale = sorted(f"0x{prm_id:X}" for prm_id in held if prm_id not in declared)
    fix = f"fprime-lite params deployments/{deployment}/topology.yaml -o {loaded.parameter_file}"
    assert not missing, f"{loaded.parameter_file} lacks {missing}: regenerate it ({fix})"
    assert not stale, f"{loaded.parameter_file} holds ids no component declares {stale}: regenerate it ({fix})"
